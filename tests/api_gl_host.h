// SPDX-License-Identifier: MIT
// Test helper: a host's own GL context, made the way an emulator makes one (libOSMesa or libEGL
// opened by the host itself, GL entry points through the library's GetProcAddress), plus the GL
// state a host keeps: scramble() sets a distinctive value for everything ge2gl touches, check()
// says what differs from it. Used by tests/api_embed.cpp to hold ge2gl to its GL contract
// (docs/plugin-api.md "GL state").
#pragma once
#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

namespace apitest {

class GlHost {
public:
    enum class Kind { OSMesa, EGL };

    // Creates a 3.3 core context and makes it current on this thread; ok() says whether it worked.
    explicit GlHost(Kind kind) : kind_(kind) {
        if (kind == Kind::OSMesa) {
            lib_ = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
            if (!lib_) return;
            auto create = reinterpret_cast<decltype(&OSMesaCreateContextAttribs)>(dlsym(lib_, "OSMesaCreateContextAttribs"));
            osMakeCurrent_ = reinterpret_cast<decltype(&OSMesaMakeCurrent)>(dlsym(lib_, "OSMesaMakeCurrent"));
            osGetCurrent_ = reinterpret_cast<decltype(&OSMesaGetCurrentContext)>(dlsym(lib_, "OSMesaGetCurrentContext"));
            osDestroy_ = reinterpret_cast<decltype(&OSMesaDestroyContext)>(dlsym(lib_, "OSMesaDestroyContext"));
            osGetProc_ = reinterpret_cast<decltype(&OSMesaGetProcAddress)>(dlsym(lib_, "OSMesaGetProcAddress"));
            if (!create || !osMakeCurrent_ || !osGetCurrent_ || !osDestroy_ || !osGetProc_) return;
            const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                   OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
            os_ = create(attribs, nullptr);
            if (!os_ || !makeCurrent()) return;
        } else {
            lib_ = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
            if (!lib_) return;
            eglGetProc_ = reinterpret_cast<decltype(&eglGetProcAddress)>(dlsym(lib_, "eglGetProcAddress"));
            eglMake_ = reinterpret_cast<decltype(&eglMakeCurrent)>(dlsym(lib_, "eglMakeCurrent"));
            eglCur_ = reinterpret_cast<decltype(&eglGetCurrentContext)>(dlsym(lib_, "eglGetCurrentContext"));
            eglDestroy_ = reinterpret_cast<decltype(&eglDestroyContext)>(dlsym(lib_, "eglDestroyContext"));
            auto init = reinterpret_cast<decltype(&eglInitialize)>(dlsym(lib_, "eglInitialize"));
            auto bind = reinterpret_cast<decltype(&eglBindAPI)>(dlsym(lib_, "eglBindAPI"));
            auto createCtx = reinterpret_cast<decltype(&eglCreateContext)>(dlsym(lib_, "eglCreateContext"));
            if (!eglGetProc_ || !eglMake_ || !eglCur_ || !init || !bind || !createCtx) return;
            auto platform = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProc_("eglGetPlatformDisplayEXT"));
            if (!platform) return;
            dpy_ = platform(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (dpy_ == EGL_NO_DISPLAY || !init(dpy_, nullptr, nullptr) || !bind(EGL_OPENGL_API)) return;
            const EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
            egl_ = createCtx(dpy_, nullptr, EGL_NO_CONTEXT, attr);
            if (egl_ == EGL_NO_CONTEXT || !makeCurrent()) return;
        }
        ok_ = load();
    }
    ~GlHost() {
        if (os_) {
            if (osGetCurrent_() == os_) osMakeCurrent_(nullptr, nullptr, 0, 0, 0);
            osDestroy_(os_);
        }
        if (egl_ != EGL_NO_CONTEXT) {
            if (eglCur_() == egl_) eglMake_(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroy_(dpy_, egl_);
        }
        // The libraries stay loaded (drivers do not like being unloaded).
    }
    GlHost(const GlHost&) = delete;
    GlHost& operator=(const GlHost&) = delete;

    bool ok() const { return ok_; }
    bool makeCurrent() {
        if (os_) return osMakeCurrent_(os_, buffer_, GL_UNSIGNED_BYTE, 4, 4) == GL_TRUE;
        return eglMake_(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_) == EGL_TRUE;
    }
    // Leaves the thread with no context current.
    void release() {
        if (os_) osMakeCurrent_(nullptr, nullptr, 0, 0, 0);
        else eglMake_(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    // Is this host's context the one current on the calling thread?
    bool isCurrent() const { return os_ ? osGetCurrent_() == os_ : eglCur_() == egl_; }
    // The host's loader, as a host would hand it to ge2gl (config.gl_get_proc_address).
    void* (*loader() const)(const char*) { return kind_ == Kind::OSMesa ? &osmesaLoader : &eglLoader; }

    // ---- GL calls the tests make as the host ----
    PFNGLGETSTRINGPROC GetString = nullptr;
    PFNGLGETINTEGERVPROC GetIntegerv = nullptr;
    PFNGLGETBOOLEANVPROC GetBooleanv = nullptr;
    PFNGLISENABLEDPROC IsEnabled = nullptr;
    PFNGLENABLEPROC Enable = nullptr;
    PFNGLDISABLEPROC Disable = nullptr;
    PFNGLVIEWPORTPROC Viewport = nullptr;
    PFNGLSCISSORPROC Scissor = nullptr;
    PFNGLCOLORMASKPROC ColorMask = nullptr;
    PFNGLDEPTHMASKPROC DepthMask = nullptr;
    PFNGLDEPTHFUNCPROC DepthFunc = nullptr;
    PFNGLBLENDFUNCPROC BlendFunc = nullptr;
    PFNGLPIXELSTOREIPROC PixelStorei = nullptr;
    PFNGLACTIVETEXTUREPROC ActiveTexture = nullptr;
    PFNGLGENTEXTURESPROC GenTextures = nullptr;
    PFNGLBINDTEXTUREPROC BindTexture = nullptr;
    PFNGLTEXIMAGE2DPROC TexImage2D = nullptr;
    PFNGLGETTEXLEVELPARAMETERIVPROC GetTexLevelParameteriv = nullptr;
    PFNGLGENSAMPLERSPROC GenSamplers = nullptr;
    PFNGLBINDSAMPLERPROC BindSampler = nullptr;
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
    PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D = nullptr;
    PFNGLREADPIXELSPROC ReadPixels = nullptr;
    PFNGLGENVERTEXARRAYSPROC GenVertexArrays = nullptr;
    PFNGLBINDVERTEXARRAYPROC BindVertexArray = nullptr;
    PFNGLGENBUFFERSPROC GenBuffers = nullptr;
    PFNGLBINDBUFFERPROC BindBuffer = nullptr;
    PFNGLBUFFERDATAPROC BufferData = nullptr;
    PFNGLCREATEPROGRAMPROC CreateProgram = nullptr;
    PFNGLUSEPROGRAMPROC UseProgram = nullptr;
    PFNGLCREATESHADERPROC CreateShader = nullptr;
    PFNGLSHADERSOURCEPROC ShaderSource = nullptr;
    PFNGLCOMPILESHADERPROC CompileShader = nullptr;
    PFNGLATTACHSHADERPROC AttachShader = nullptr;
    PFNGLLINKPROGRAMPROC LinkProgram = nullptr;
    PFNGLPROVOKINGVERTEXPROC ProvokingVertex = nullptr;
    PFNGLGETERRORPROC GetError = nullptr;

    // Sets a distinctive value for every binding and setting of the GL contract (objects of its
    // own bound everywhere, odd rectangles, masks off, blending and culling on, odd pixel store).
    void scramble() {
        if (!objects_) makeObjects();
        BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_[0]);
        BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_[1]);
        UseProgram(prog_);
        BindVertexArray(vao_);
        BindBuffer(GL_ARRAY_BUFFER, buf_[0]);
        BindBuffer(GL_PIXEL_UNPACK_BUFFER, buf_[1]);
        BindBuffer(GL_PIXEL_PACK_BUFFER, buf_[2]);
        for (int u = 0; u < 8; ++u) {
            ActiveTexture(GLenum(GL_TEXTURE0 + u));
            BindTexture(GL_TEXTURE_2D, tex_[u]);
            BindSampler(GLuint(u), sampler_);
        }
        ActiveTexture(GL_TEXTURE3);
        Viewport(3, 5, 77, 33);
        Scissor(7, 9, 11, 13);
        ColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
        DepthMask(GL_FALSE);
        DepthFunc(GL_NEVER);
        BlendFunc(GL_SRC_COLOR, GL_DST_ALPHA);
        ProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
        for (GLenum e : {GL_SCISSOR_TEST, GL_BLEND, GL_DEPTH_TEST, GL_CULL_FACE, GL_STENCIL_TEST, GL_RASTERIZER_DISCARD})
            Enable(e);
        PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        PixelStorei(GL_UNPACK_ROW_LENGTH, 7);
        PixelStorei(GL_PACK_ALIGNMENT, 2);
        PixelStorei(GL_PACK_ROW_LENGTH, 5);
    }
    // What differs from scramble()'s state ("" when nothing).
    std::string check() {
        std::string bad;
        auto want = [&](const char* what, GLint got, GLint expect) {
            if (got != expect) bad += std::string(what) + "=" + std::to_string(got) + " (host set " + std::to_string(expect) + ") ";
        };
        auto geti = [&](GLenum e) {
            GLint v[4] = {};
            GetIntegerv(e, v);
            return v[0];
        };
        want("draw framebuffer", geti(GL_DRAW_FRAMEBUFFER_BINDING), GLint(fbo_[0]));
        want("read framebuffer", geti(GL_READ_FRAMEBUFFER_BINDING), GLint(fbo_[1]));
        want("program", geti(GL_CURRENT_PROGRAM), GLint(prog_));
        want("vertex array", geti(GL_VERTEX_ARRAY_BINDING), GLint(vao_));
        want("array buffer", geti(GL_ARRAY_BUFFER_BINDING), GLint(buf_[0]));
        want("pixel unpack buffer", geti(GL_PIXEL_UNPACK_BUFFER_BINDING), GLint(buf_[1]));
        want("pixel pack buffer", geti(GL_PIXEL_PACK_BUFFER_BINDING), GLint(buf_[2]));
        want("active texture", geti(GL_ACTIVE_TEXTURE), GL_TEXTURE3);
        for (int u = 0; u < 8; ++u) {
            ActiveTexture(GLenum(GL_TEXTURE0 + u));
            want(("texture unit " + std::to_string(u)).c_str(), geti(GL_TEXTURE_BINDING_2D), GLint(tex_[u]));
            want(("sampler unit " + std::to_string(u)).c_str(), geti(GL_SAMPLER_BINDING), GLint(sampler_));
        }
        ActiveTexture(GL_TEXTURE3);
        GLint vp[4] = {}, sc[4] = {};
        GetIntegerv(GL_VIEWPORT, vp);
        GetIntegerv(GL_SCISSOR_BOX, sc);
        want("viewport x", vp[0], 3), want("viewport w", vp[2], 77), want("scissor x", sc[0], 7), want("scissor h", sc[3], 13);
        GLboolean cm[4] = {}, dm = 1;
        GetBooleanv(GL_COLOR_WRITEMASK, cm);
        GetBooleanv(GL_DEPTH_WRITEMASK, &dm);
        want("colour mask r", cm[0], 0), want("colour mask g", cm[1], 1), want("depth mask", dm, 0);
        want("depth func", geti(GL_DEPTH_FUNC), GL_NEVER);
        want("blend src", geti(GL_BLEND_SRC_RGB), GL_SRC_COLOR);
        want("provoking vertex", geti(GL_PROVOKING_VERTEX), GL_FIRST_VERTEX_CONVENTION);
        for (GLenum e : {GL_SCISSOR_TEST, GL_BLEND, GL_DEPTH_TEST, GL_CULL_FACE, GL_STENCIL_TEST, GL_RASTERIZER_DISCARD})
            want(("enable 0x" + std::to_string(e)).c_str(), IsEnabled(e), GL_TRUE);
        want("unpack alignment", geti(GL_UNPACK_ALIGNMENT), 1);
        want("unpack row length", geti(GL_UNPACK_ROW_LENGTH), 7);
        want("pack alignment", geti(GL_PACK_ALIGNMENT), 2);
        want("pack row length", geti(GL_PACK_ROW_LENGTH), 5);
        want("GL error", GLint(GetError()), GL_NO_ERROR);
        return bad;
    }
    // Reads a texture of ge2gl's (RGBA8) through a framebuffer of the host's: w x h RGBA bytes,
    // row 0 = texture row 0. Leaves the host's scrambled state as it was.
    std::vector<unsigned char> readTexture(GLuint tex, int w, int h) {
        std::vector<unsigned char> out(size_t(w) * size_t(h) * 4);
        BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        PixelStorei(GL_PACK_ALIGNMENT, 4);
        PixelStorei(GL_PACK_ROW_LENGTH, 0);
        BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_[2]);
        FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
        ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
        FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        scramble();
        return out;
    }
    void textureSize(GLuint tex, int& w, int& h) {
        ActiveTexture(GL_TEXTURE7);
        BindTexture(GL_TEXTURE_2D, tex);
        GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
        GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &h);
        scramble();
    }

private:
    static void* osmesaLoader(const char* name) {
        static auto get = reinterpret_cast<decltype(&OSMesaGetProcAddress)>(
            dlsym(dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL), "OSMesaGetProcAddress"));
        return reinterpret_cast<void*>(get(name));
    }
    static void* eglLoader(const char* name) {
        static auto get = reinterpret_cast<decltype(&eglGetProcAddress)>(
            dlsym(dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL), "eglGetProcAddress"));
        return reinterpret_cast<void*>(get(name));
    }
    template <class T>
    bool get(T& fn, const char* name) {
        fn = reinterpret_cast<T>(loader()(name));
        return fn != nullptr;
    }
    bool load() {
        // Every entry point is looked up, present or not: each one is set or null afterwards.
        const bool found[] = {
            get(GetString, "glGetString"), get(GetIntegerv, "glGetIntegerv"), get(GetBooleanv, "glGetBooleanv"),
            get(IsEnabled, "glIsEnabled"), get(Enable, "glEnable"), get(Disable, "glDisable"),
            get(Viewport, "glViewport"), get(Scissor, "glScissor"), get(ColorMask, "glColorMask"),
            get(DepthMask, "glDepthMask"), get(DepthFunc, "glDepthFunc"), get(BlendFunc, "glBlendFunc"),
            get(PixelStorei, "glPixelStorei"), get(ActiveTexture, "glActiveTexture"),
            get(GenTextures, "glGenTextures"), get(BindTexture, "glBindTexture"), get(TexImage2D, "glTexImage2D"),
            get(GetTexLevelParameteriv, "glGetTexLevelParameteriv"), get(GenSamplers, "glGenSamplers"),
            get(BindSampler, "glBindSampler"), get(GenFramebuffers, "glGenFramebuffers"),
            get(BindFramebuffer, "glBindFramebuffer"), get(FramebufferTexture2D, "glFramebufferTexture2D"),
            get(ReadPixels, "glReadPixels"), get(GenVertexArrays, "glGenVertexArrays"),
            get(BindVertexArray, "glBindVertexArray"), get(GenBuffers, "glGenBuffers"),
            get(BindBuffer, "glBindBuffer"), get(BufferData, "glBufferData"), get(CreateProgram, "glCreateProgram"),
            get(UseProgram, "glUseProgram"), get(CreateShader, "glCreateShader"),
            get(ShaderSource, "glShaderSource"), get(CompileShader, "glCompileShader"),
            get(AttachShader, "glAttachShader"), get(LinkProgram, "glLinkProgram"),
            get(ProvokingVertex, "glProvokingVertex"), get(GetError, "glGetError")};
        return std::all_of(std::begin(found), std::end(found), [](bool f) { return f; });
    }
    void makeObjects() {
        objects_ = true;
        GenFramebuffers(3, fbo_);
        GenVertexArrays(1, &vao_);
        GenBuffers(3, buf_);
        for (GLuint b : buf_) {
            BindBuffer(GL_ARRAY_BUFFER, b);
            BufferData(GL_ARRAY_BUFFER, 64, nullptr, GL_STATIC_DRAW);
        }
        GenTextures(8, tex_);
        for (GLuint t : tex_) {
            BindTexture(GL_TEXTURE_2D, t);
            TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        }
        GenSamplers(1, &sampler_);
        // A program of the host's (its compile status does not matter for binding).
        const char* vs = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
        const char* fs = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
        prog_ = CreateProgram();
        for (auto [type, src] : {std::pair<GLenum, const char*>{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}}) {
            GLuint sh = CreateShader(type);
            ShaderSource(sh, 1, &src, nullptr);
            CompileShader(sh);
            AttachShader(prog_, sh);
        }
        LinkProgram(prog_);
        // Framebuffers need an attachment to be bindable as complete; the binding itself is all
        // the contract is about.
        BindFramebuffer(GL_FRAMEBUFFER, fbo_[0]);
        FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex_[0], 0);
        BindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    Kind kind_;
    void* lib_ = nullptr;
    bool ok_ = false, objects_ = false;
    OSMesaContext os_ = nullptr;
    unsigned char buffer_[4 * 4 * 4] = {};
    decltype(&OSMesaMakeCurrent) osMakeCurrent_ = nullptr;
    decltype(&OSMesaGetCurrentContext) osGetCurrent_ = nullptr;
    decltype(&OSMesaDestroyContext) osDestroy_ = nullptr;
    decltype(&OSMesaGetProcAddress) osGetProc_ = nullptr;
    EGLDisplay dpy_ = EGL_NO_DISPLAY;
    EGLContext egl_ = EGL_NO_CONTEXT;
    decltype(&eglGetProcAddress) eglGetProc_ = nullptr;
    decltype(&eglMakeCurrent) eglMake_ = nullptr;
    decltype(&eglGetCurrentContext) eglCur_ = nullptr;
    decltype(&eglDestroyContext) eglDestroy_ = nullptr;
    GLuint fbo_[3] = {}, vao_ = 0, buf_[3] = {}, tex_[8] = {}, sampler_ = 0, prog_ = 0;
};

}  // namespace apitest
