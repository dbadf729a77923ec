// SPDX-License-Identifier: MIT
// The null GL dispatch table (null_gl.h).
#include "translator/null_gl.h"

#include <atomic>
#include <type_traits>

namespace ge::gl {

namespace {

// A no-op for any entry-point signature, returning a zero value.
template <typename F>
struct Nop;
template <typename R, typename... A>
struct Nop<R (*)(A...)> {
    static R APIENTRY call(A...) {
        if constexpr (!std::is_void_v<R>) return R{};
    }
};

// Object names: one process-wide counter (the entry points get no context to keep one in; the
// only thing that depends on it is that names differ).
GLuint nextName() {
    static std::atomic<GLuint> counter{1};
    return counter.fetch_add(1, std::memory_order_relaxed);
}

void APIENTRY genNames(GLsizei n, GLuint* out) {
    for (GLsizei i = 0; i < n; ++i) out[i] = nextName();
}
GLuint APIENTRY createObject() { return nextName(); }
GLuint APIENTRY createShader(GLenum) { return nextName(); }
void APIENTRY objectStatus(GLuint, GLenum pname, GLint* v) {
    *v = (pname == GL_COMPILE_STATUS || pname == GL_LINK_STATUS) ? GL_TRUE : 0;
}
GLint APIENTRY uniformLocation(GLuint, const GLchar*) { return 0; }  // uniform calls still happen
GLenum APIENTRY framebufferStatus(GLenum) { return GL_FRAMEBUFFER_COMPLETE; }
const GLubyte* APIENTRY getString(GLenum) { return reinterpret_cast<const GLubyte*>("null GL"); }
void APIENTRY getIntegerv(GLenum, GLint* v) { *v = 0; }
GLboolean APIENTRY isObject(GLuint name) { return name ? GL_TRUE : GL_FALSE; }

}  // namespace

void loadNullGl(GlFuncs& f) {
#define GE2GL_NULL(type, name) f.name = &Nop<type>::call;
    GE2GL_GL_FUNCS(GE2GL_NULL)
    GE2GL_GL_OPTIONAL_FUNCS(GE2GL_NULL)
#undef GE2GL_NULL
    f.GenTextures = f.GenFramebuffers = f.GenBuffers = f.GenVertexArrays = &genNames;
    f.CreateProgram = &createObject;
    f.CreateShader = &createShader;
    f.GetShaderiv = f.GetProgramiv = &objectStatus;
    f.GetUniformLocation = &uniformLocation;
    f.CheckFramebufferStatus = &framebufferStatus;
    f.GetString = &getString;
    f.GetIntegerv = &getIntegerv;
    // GL_CURRENT's context check (GlRenderer::currentIsOurs): the names ge2gl made exist; no
    // object labels are kept, so the check rests on IsBuffer alone.
    f.IsBuffer = &isObject;
    f.ObjectLabel = nullptr;
    f.GetObjectLabel = nullptr;
}

}  // namespace ge::gl
