// Context creation and capability detection (see gl_context.h).
#include "translator/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <cstring>
#include <string>

#include "translator/gl_renderer.h"

namespace ge::gl {

shadergen::HostCaps GlCaps::hostCaps(bool baseline, bool floatInterp) const {
    shadergen::HostCaps c;
    c.exactInterp = exactInterp && !floatInterp ? 1 : 0;
    if (baseline) return c;  // no fetch/barrier: destination reads go through copies
    c.fbFetch = fbFetch ? 1 : 0;
    c.depthFetch = depthFetch ? 1 : 0;
    c.textureBarrier = textureBarrier ? 1 : 0;
    c.programBinary = programBinary ? 1 : 0;
    return c;
}

std::string GlCaps::summary() const {
    std::string s = "GL " + version + " on " + renderer + ";";
    if (fbFetch) s += " fbfetch";
    if (depthFetch) s += " depthfetch";
    if (textureBarrier) s += " texture_barrier";
    if (clipControl) s += " clip_control";
    if (dualSourceBlend) s += " dual_source_blend";
    if (bufferStorage) s += " buffer_storage";
    if (programBinary) s += " program_binary";
    if (exactInterp) s += " exact_interp";
    return s;
}

GlContext::~GlContext() {
    if (osmesa_) {
        // Unbind first so OSMesa releases the framebuffer it made for the current binding.
        if (OSMesaGetCurrentContext() == static_cast<OSMesaContext>(osmesa_))
            OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(static_cast<OSMesaContext>(osmesa_));
    }
    if (eglContext_) {
        EGLDisplay d = static_cast<EGLDisplay>(eglDisplay_);
        eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(d, static_cast<EGLContext>(eglContext_));
        // No eglTerminate: the surfaceless display is one per process and shared by every EGL
        // renderer (eglGetPlatformDisplay returns the same handle); terminating it here would
        // pull the driver from under the others.
    }
}

bool GlContext::makeCurrent() {
    if (osmesa_)
        return OSMesaMakeCurrent(static_cast<OSMesaContext>(osmesa_), dummy_, GL_UNSIGNED_BYTE, 4, 4) == GL_TRUE;
    if (eglContext_)
        return eglMakeCurrent(static_cast<EGLDisplay>(eglDisplay_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                              static_cast<EGLContext>(eglContext_)) == EGL_TRUE;
    return true;  // Current: the host keeps it current
}

std::unique_ptr<GlContext> GlContext::create(ContextKind kind, std::string& err) {
    std::unique_ptr<GlContext> ctx(new GlContext());
    ctx->kind_ = kind;
    if (kind == ContextKind::OSMesa) {
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                               OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
        OSMesaContext c = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!c) {
            err = "OSMesaCreateContextAttribs failed (no GL 3.3 core profile)";
            return nullptr;
        }
        ctx->osmesa_ = c;
        if (!ctx->makeCurrent()) {
            err = "OSMesaMakeCurrent failed";
            return nullptr;
        }
        if (const char* missing =
                ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(OSMesaGetProcAddress(n)); })) {
            err = std::string("OSMesa lacks ") + missing;
            return nullptr;
        }
    } else if (kind == ContextKind::EGL) {
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) {
            err = "EGL: eglGetPlatformDisplayEXT unavailable";
            return nullptr;
        }
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) {
            err = "EGL: surfaceless platform unavailable";
            return nullptr;
        }
        ctx->eglDisplay_ = d;
        if (!eglBindAPI(EGL_OPENGL_API)) {
            err = "EGL: desktop OpenGL API unavailable";
            eglTerminate(d);
            ctx->eglDisplay_ = nullptr;
            return nullptr;
        }
        const EGLint cfgAttr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig cfg = nullptr;
        EGLint n = 0;
        if (!eglChooseConfig(d, cfgAttr, &cfg, 1, &n) || n < 1) cfg = nullptr;  // no-config contexts are fine
        const EGLint ctxAttr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLContext c = eglCreateContext(d, cfg, EGL_NO_CONTEXT, ctxAttr);
        if (c == EGL_NO_CONTEXT) {
            err = "EGL: eglCreateContext (3.3 core) failed";
            eglTerminate(d);
            ctx->eglDisplay_ = nullptr;
            return nullptr;
        }
        ctx->eglContext_ = c;
        if (!ctx->makeCurrent()) {
            err = "EGL: eglMakeCurrent (surfaceless) failed";
            return nullptr;
        }
        if (const char* missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); })) {
            err = std::string("EGL lacks ") + missing;
            return nullptr;
        }
    } else {
        // Host context: OSMesa's if one is current, else ask EGL (Mesa/glvnd resolve core entry
        // points for any current context).
        const char* missing = nullptr;
        if (OSMesaGetCurrentContext())
            missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(OSMesaGetProcAddress(n)); });
        else
            missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); });
        if (missing) {
            err = std::string("current context lacks ") + missing;
            return nullptr;
        }
    }
    if (!ctx->init(err)) return nullptr;
    return ctx;
}

bool GlContext::init(std::string& err) {
    const GlFuncs& gl = funcs_;
    const char* ver = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
    const char* ren = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    if (!ver) {
        err = "no current GL context";
        return false;
    }
    caps_.version = ver;
    caps_.renderer = ren ? ren : "?";
    gl.GetIntegerv(GL_MAJOR_VERSION, &caps_.major);
    gl.GetIntegerv(GL_MINOR_VERSION, &caps_.minor);
    if (caps_.major * 10 + caps_.minor < 33) {
        err = "GL 3.3 required, got " + caps_.version;
        return false;
    }
    GLint n = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    bool arbBarrier = false, int64 = false;
    for (GLint i = 0; i < n; ++i) {
        const char* e = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, GLuint(i)));
        if (!e) continue;
        if (!std::strcmp(e, "GL_EXT_shader_framebuffer_fetch")) caps_.fbFetch = true;
        if (!std::strcmp(e, "GL_ARM_shader_framebuffer_fetch_depth_stencil")) caps_.depthFetch = true;
        if (!std::strcmp(e, "GL_ARB_texture_barrier") || !std::strcmp(e, "GL_NV_texture_barrier")) arbBarrier = true;
        if (!std::strcmp(e, "GL_ARB_clip_control")) caps_.clipControl = true;
        if (!std::strcmp(e, "GL_ARB_blend_func_extended")) caps_.dualSourceBlend = true;
        if (!std::strcmp(e, "GL_ARB_buffer_storage")) caps_.bufferStorage = true;
        if (!std::strcmp(e, "GL_ARB_get_program_binary")) caps_.programBinary = true;
        if (!std::strcmp(e, "GL_ARB_gpu_shader_int64")) int64 = true;
    }
    caps_.textureBarrier = gl.TextureBarrier && (arbBarrier || caps_.major * 10 + caps_.minor >= 45);
    caps_.exactInterp = int64 && caps_.major >= 4;
    GLint formats = 0;
    gl.GetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    if (formats < 1) caps_.programBinary = false;
    while (gl.GetError() != GL_NO_ERROR) {
    }
    return true;
}

}  // namespace ge::gl
