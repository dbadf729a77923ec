// SPDX-License-Identifier: MIT
// The GL entry points the translator uses, loaded through the context's GetProcAddress into a
// table owned by the context (no global function pointers: two renderers on two contexts — e.g.
// OSMesa and EGL, whose libraries both export gl* symbols — never share state).
#pragma once
#include <GL/glcorearb.h>

namespace ge::gl {

#define GE2GL_GL_FUNCS(X)                                                             \
    X(PFNGLGETSTRINGPROC, GetString)                                                  \
    X(PFNGLGETSTRINGIPROC, GetStringi)                                                \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                              \
    X(PFNGLGETERRORPROC, GetError)                                                    \
    X(PFNGLGETBOOLEANVPROC, GetBooleanv)                                              \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                                  \
    X(PFNGLISENABLEDPROC, IsEnabled)                                                  \
    X(PFNGLDEPTHRANGEPROC, DepthRange)                                                \
    X(PFNGLPOLYGONMODEPROC, PolygonMode)                                              \
    X(PFNGLPROVOKINGVERTEXPROC, ProvokingVertex)                                      \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                                              \
    X(PFNGLENABLEPROC, Enable)                                                        \
    X(PFNGLDISABLEPROC, Disable)                                                      \
    X(PFNGLFLUSHPROC, Flush)                                                          \
    X(PFNGLFINISHPROC, Finish)                                                        \
    X(PFNGLVIEWPORTPROC, Viewport)                                                    \
    X(PFNGLSCISSORPROC, Scissor)                                                      \
    X(PFNGLCOLORMASKPROC, ColorMask)                                                  \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                                  \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                  \
    X(PFNGLCULLFACEPROC, CullFace)                                                    \
    X(PFNGLFRONTFACEPROC, FrontFace)                                                  \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                              \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                                \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                                \
    X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                                \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                              \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                        \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                              \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                          \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                                \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                                          \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                          \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                      \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                      \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                            \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                        \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                                      \
    X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv)                                        \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                                          \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                                \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                          \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                                \
    X(PFNGLBUFFERDATAPROC, BufferData)                                                \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                          \
    X(PFNGLTEXBUFFERPROC, TexBuffer)                                                  \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                      \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                      \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                      \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                              \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                \
    X(PFNGLCREATESHADERPROC, CreateShader)                                            \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                            \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                            \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                          \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                              \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                    \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                          \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                          \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                            \
    X(PFNGLDETACHSHADERPROC, DetachShader)                                            \
    X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)                                \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                              \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                            \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                  \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                                  \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                                  \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                                                  \
    X(PFNGLUNIFORM2IVPROC, Uniform2iv)                                                \
    X(PFNGLUNIFORM3IVPROC, Uniform3iv)                                                \
    X(PFNGLUNIFORM4IVPROC, Uniform4iv)                                                \
    X(PFNGLUNIFORM1IVPROC, Uniform1iv)                                                \
    X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri)                                  \
    X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary)                                    \
    X(PFNGLPROGRAMBINARYPROC, ProgramBinary)

// Optional (extension / newer core) entry points: may be null.
#define GE2GL_GL_OPTIONAL_FUNCS(X)                                                    \
    X(PFNGLTEXTUREBARRIERPROC, TextureBarrier)                                        \
    X(PFNGLUNIFORM4UIVPROC, Uniform4uiv)                                              \
    X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, TransformFeedbackVaryings)                  \
    X(PFNGLBEGINTRANSFORMFEEDBACKPROC, BeginTransformFeedback)                        \
    X(PFNGLENDTRANSFORMFEEDBACKPROC, EndTransformFeedback)                            \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                        \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                                    \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                            \
    X(PFNGLISBUFFERPROC, IsBuffer)                                                    \
    X(PFNGLOBJECTLABELPROC, ObjectLabel)                                              \
    X(PFNGLGETOBJECTLABELPROC, GetObjectLabel)

struct GlFuncs {
#define GE2GL_DECLARE(type, name) type name = nullptr;
    GE2GL_GL_FUNCS(GE2GL_DECLARE)
    GE2GL_GL_OPTIONAL_FUNCS(GE2GL_DECLARE)
#undef GE2GL_DECLARE
    // Loads every entry point; returns the name of the first missing required one, or nullptr.
    template <typename GetProc>
    const char* load(GetProc getProc) {
#define GE2GL_LOAD(type, name)                                         \
    name = reinterpret_cast<type>(getProc("gl" #name));                 \
    if (!name) return "gl" #name;
        GE2GL_GL_FUNCS(GE2GL_LOAD)
#undef GE2GL_LOAD
#define GE2GL_LOAD_OPT(type, name) name = reinterpret_cast<type>(getProc("gl" #name));
        GE2GL_GL_OPTIONAL_FUNCS(GE2GL_LOAD_OPT)
#undef GE2GL_LOAD_OPT
        return nullptr;
    }
    // Every entry point becomes a call that does nothing and returns zero: for a host context that
    // is gone (GL_CURRENT), so that releasing our objects cannot touch whatever context is current.
    void disarm() {
#define GE2GL_DISARM(type, name) name = &Nop<type>::call;
        GE2GL_GL_FUNCS(GE2GL_DISARM)
        GE2GL_GL_OPTIONAL_FUNCS(GE2GL_DISARM)
#undef GE2GL_DISARM
    }

private:
    template <typename F>
    struct Nop;
    template <typename R, typename... A>
    struct Nop<R(APIENTRYP)(A...)> {
        static R APIENTRY call(A...) { return R(); }
    };
};

}  // namespace ge::gl
