// SPDX-License-Identifier: MIT
// Headless GL context creation (OSMesa core profile, EGL surfaceless) or adoption of the host's
// current context, plus capability detection. One GlContext per renderer; the GL function table
// lives here (no globals).
#pragma once
#include <memory>
#include <string>

#include "shadergen/shader_keys.h"
#include "translator/gl_funcs.h"

namespace ge::gl {

enum class ContextKind;

struct GlCaps {
    int major = 0, minor = 0;
    std::string version, renderer;
    bool fbFetch = false;         // GL_EXT_shader_framebuffer_fetch (coherent)
    bool depthFetch = false;      // GL_ARM_shader_framebuffer_fetch_depth_stencil
    bool textureBarrier = false;  // glTextureBarrier (GL 4.5 / ARB / NV)
    bool clipControl = false;     // GL_ARB_clip_control (detected; not needed: see shader_gen.cpp)
    bool dualSourceBlend = false; // GL_ARB_blend_func_extended (detected; blending is in-shader)
    bool bufferStorage = false;   // GL_ARB_buffer_storage (detected)
    bool programBinary = false;   // GL_ARB_get_program_binary with ≥ 1 format
    bool exactInterp = false;     // GL 4.0 (fp64, precise) + GL_ARB_gpu_shader_int64
    // What the shader generator may use, after the `baseline` switch. Exact interpolation is
    // kept under `baseline` (which is about destination reads); floatInterp turns it off.
    shadergen::HostCaps hostCaps(bool baseline, bool floatInterp = false) const;
    std::string summary() const;
};

class GlContext {
public:
    ~GlContext();
    // Creates (or adopts, for Current) a context, makes it current and loads the functions.
    // Headless contexts are created entered (enter() below, depth 1): a caller that lends the
    // thread back to a host calls leave().
    // `loader` (Current only): the host's GetProcAddress; null: EGL's or OSMesa's, whichever has
    // a context current.
    static std::unique_ptr<GlContext> create(ContextKind kind, std::string& err,
                                             void* (*loader)(const char*) = nullptr);
    bool makeCurrent();
    // Headless contexts: makes this context current on the calling thread and remembers what was
    // current there (an OSMesa or EGL context of the host, or of another ge2gl instance); the
    // matching leave() makes that current again, or releases this context so another thread may
    // take it. Nested calls count. Current and Null: nothing to do.
    bool enter(std::string& err);
    void leave();
    bool headless() const { return osmesa_ || eglContext_; }
    bool entered() const { return depth_ > 0; }
    const GlFuncs& f() const { return funcs_; }
    const GlCaps& caps() const { return caps_; }
    // Current contexts the host destroyed or replaced: GL calls through f() do nothing from now on.
    void disarm() { funcs_.disarm(); }

private:
    GlContext() = default;
    bool init(std::string& err);

    ContextKind kind_{};
    void* osmesa_ = nullptr;   // OSMesaContext
    void* eglDisplay_ = nullptr;
    void* eglContext_ = nullptr;
    // What enter() found current on the thread (restored by the outermost leave()).
    int depth_ = 0;
    void* prevOsmesa_ = nullptr;
    void* prevOsmesaBuffer_ = nullptr;
    int prevOsmesaW_ = 0, prevOsmesaH_ = 0;
    void* prevEglDisplay_ = nullptr;
    void* prevEglDraw_ = nullptr;
    void* prevEglRead_ = nullptr;
    void* prevEglContext_ = nullptr;
    unsigned char dummy_[4 * 4 * 4] = {};  // OSMesa needs a colour buffer; we render to FBOs
    GlFuncs funcs_;
    GlCaps caps_;
};

}  // namespace ge::gl
