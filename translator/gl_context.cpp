// SPDX-License-Identifier: MIT
// Context creation and capability detection (see gl_context.h).
//
// libOSMesa and libEGL are not linked: they (and libLLVM behind llvmpipe, ~60 MiB mapped and
// ~0.1 s of loading) are dlopen()ed the first time a context of that kind is created, so
// processes that never draw with GL (soft/null backends, info, disasm) map none of them. The
// headers give the function types; every OSMesa*/egl* entry point used goes through the tables
// below.
#include "translator/gl_context.h"
#include "translator/null_gl.h"

#include <dlfcn.h>
#include <link.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <atomic>
#include <cstring>
#include <string>

#include "translator/gl_renderer.h"

namespace ge::gl {

namespace {

// Opens the first library of `names` that loads (the Debian sonames first, then the unversioned
// development names) and says which in `opened`. RTLD_LOCAL: the gl* symbols both libraries
// export stay out of the global namespace. With `noload`, only a library already in the process.
void* openFirst(std::initializer_list<const char*> names, bool noload, const char*& opened, std::string& tried) {
    for (const char* n : names) {
        if (void* h = dlopen(n, RTLD_NOW | RTLD_LOCAL | (noload ? RTLD_NOLOAD : 0))) {
            opened = n;
            return h;
        }
        const char* e = dlerror();
        if (!tried.empty()) tried += "; ";
        tried += e ? e : n;
    }
    return nullptr;
}

template <typename F>
bool resolve(void* lib, const char* name, F& fn, std::string& missing) {
    fn = reinterpret_cast<F>(dlsym(lib, name));
    if (!fn && missing.empty()) missing = name;
    return fn != nullptr;
}

#define GE2GL_OSMESA_NAMES {"libOSMesa.so.8", "libOSMesa.so"}
#define GE2GL_EGL_NAMES {"libEGL.so.1", "libEGL.so"}

struct OsmesaApi {
    decltype(&::OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
    decltype(&::OSMesaDestroyContext) DestroyContext = nullptr;
    decltype(&::OSMesaMakeCurrent) MakeCurrent = nullptr;
    decltype(&::OSMesaGetCurrentContext) GetCurrentContext = nullptr;
    decltype(&::OSMesaGetProcAddress) GetProcAddress = nullptr;
    decltype(&::OSMesaGetColorBuffer) GetColorBuffer = nullptr;
    std::string error;  // empty when the library loaded and every entry point resolved

    bool resolveAll(void* lib, std::string& missing) {
        bool ok = true;
        ok &= resolve(lib, "OSMesaCreateContextAttribs", CreateContextAttribs, missing);
        ok &= resolve(lib, "OSMesaDestroyContext", DestroyContext, missing);
        ok &= resolve(lib, "OSMesaMakeCurrent", MakeCurrent, missing);
        ok &= resolve(lib, "OSMesaGetCurrentContext", GetCurrentContext, missing);
        ok &= resolve(lib, "OSMesaGetProcAddress", GetProcAddress, missing);
        ok &= resolve(lib, "OSMesaGetColorBuffer", GetColorBuffer, missing);
        return ok;
    }
};

struct EglApi {
    decltype(&::eglGetProcAddress) GetProcAddress = nullptr;
    decltype(&::eglInitialize) Initialize = nullptr;
    decltype(&::eglTerminate) Terminate = nullptr;
    decltype(&::eglBindAPI) BindAPI = nullptr;
    decltype(&::eglChooseConfig) ChooseConfig = nullptr;
    decltype(&::eglCreateContext) CreateContext = nullptr;
    decltype(&::eglDestroyContext) DestroyContext = nullptr;
    decltype(&::eglMakeCurrent) MakeCurrent = nullptr;
    decltype(&::eglGetCurrentContext) GetCurrentContext = nullptr;
    decltype(&::eglGetCurrentDisplay) GetCurrentDisplay = nullptr;
    decltype(&::eglGetCurrentSurface) GetCurrentSurface = nullptr;
    std::string error;

    bool resolveAll(void* lib, std::string& missing) {
        bool ok = true;
        ok &= resolve(lib, "eglGetProcAddress", GetProcAddress, missing);
        ok &= resolve(lib, "eglGetCurrentContext", GetCurrentContext, missing);
        ok &= resolve(lib, "eglGetCurrentDisplay", GetCurrentDisplay, missing);
        ok &= resolve(lib, "eglGetCurrentSurface", GetCurrentSurface, missing);
        ok &= resolve(lib, "eglInitialize", Initialize, missing);
        ok &= resolve(lib, "eglTerminate", Terminate, missing);
        ok &= resolve(lib, "eglBindAPI", BindAPI, missing);
        ok &= resolve(lib, "eglChooseConfig", ChooseConfig, missing);
        ok &= resolve(lib, "eglCreateContext", CreateContext, missing);
        ok &= resolve(lib, "eglDestroyContext", DestroyContext, missing);
        ok &= resolve(lib, "eglMakeCurrent", MakeCurrent, missing);
        return ok;
    }
};

template <typename Api>
Api loadApi(std::initializer_list<const char*> names, const char* what) {
    Api api;
    std::string tried, missing;
    const char* opened = nullptr;
    if (void* lib = openFirst(names, false, opened, tried)) {
        if (!api.resolveAll(lib, missing))
            api.error = std::string(what) + ": " + opened + " lacks " + missing;
    } else {
        api.error = std::string("cannot load ") + what + " (" + tried + ")";
    }
    return api;
}

// Loaded on first use, once per process (thread-safe static initialisation); never unloaded.
const OsmesaApi& osmesa() {
    static const OsmesaApi api = loadApi<OsmesaApi>(GE2GL_OSMESA_NAMES, "OSMesa");
    return api;
}

const EglApi& egl() {
    static const EglApi api = loadApi<EglApi>(GE2GL_EGL_NAMES, "EGL");
    return api;
}

// Whether an object whose file name is one of `names` is mapped in the process. Walks the loader's
// list in memory: dlopen(RTLD_NOLOAD) of a library that is not loaded still searches the library
// path and opens the file to compare its identity, which cost ~0.5 ms per call on every call of a
// host without EGL (found with PPSSPPHeadless: 40,000 opens and unmaps in one short test).
bool mapped(std::initializer_list<const char*> names) {
    struct Query {
        std::initializer_list<const char*> names;
        bool found = false;
    } q{names};
    dl_iterate_phdr(
        [](struct dl_phdr_info* info, size_t, void* data) -> int {
            auto* q = static_cast<Query*>(data);
            const char* path = info->dlpi_name ? info->dlpi_name : "";
            const char* slash = std::strrchr(path, '/');
            const char* base = slash ? slash + 1 : path;
            for (const char* n : q->names)
                if (std::strncmp(base, n, std::strlen(n)) == 0) q->found = true;  // also libEGL.so.1.1.0
            return q->found ? 1 : 0;
        },
        &q);
    return q.found;
}

// A library's table only when the library is already in the process (a host that made one of
// its contexts current); never loads it. `table` is osmesa() or egl(). Once found, the table's
// loader holds a reference, so the library stays and the answer is kept.
template <typename Api>
const Api* ifLoaded(std::initializer_list<const char*> names, const Api& (*table)()) {
    static std::atomic<const Api*> known{nullptr};
    if (const Api* k = known.load(std::memory_order_acquire)) return k;
    if (!mapped(names)) return nullptr;
    std::string tried;
    const char* opened = nullptr;
    void* lib = openFirst(names, true, opened, tried);
    if (!lib) return nullptr;
    const Api& api = table();
    dlclose(lib);  // the reference RTLD_NOLOAD took; the table's loader holds its own
    if (!api.error.empty()) return nullptr;
    known.store(&api, std::memory_order_release);
    return &api;
}

const OsmesaApi* osmesaIfLoaded() { return ifLoaded<OsmesaApi>(GE2GL_OSMESA_NAMES, &osmesa); }
const EglApi* eglIfLoaded() { return ifLoaded<EglApi>(GE2GL_EGL_NAMES, &egl); }

}  // namespace

void preloadContextLibrary(ContextKind kind) {
    if (kind == ContextKind::OSMesa) (void)osmesa();
    else if (kind == ContextKind::EGL) (void)egl();
}

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
        const OsmesaApi& os = osmesa();
        if (os.GetCurrentContext() == static_cast<OSMesaContext>(osmesa_)) os.MakeCurrent(nullptr, nullptr, 0, 0, 0);
        os.DestroyContext(static_cast<OSMesaContext>(osmesa_));
    }
    if (eglContext_) {
        EGLDisplay d = static_cast<EGLDisplay>(eglDisplay_);
        // Unbind only our own context: a host's context current on this thread stays current.
        if (egl().GetCurrentContext() == static_cast<EGLContext>(eglContext_))
            egl().MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        egl().DestroyContext(d, static_cast<EGLContext>(eglContext_));
        // No eglTerminate: the surfaceless display is one per process and shared by every EGL
        // renderer (eglGetPlatformDisplay returns the same handle); terminating it here would
        // pull the driver from under the others.
    }
}

bool GlContext::makeCurrent() {
    if (osmesa_)
        return osmesa().MakeCurrent(static_cast<OSMesaContext>(osmesa_), dummy_, GL_UNSIGNED_BYTE, 4, 4) == GL_TRUE;
    if (eglContext_)
        return egl().MakeCurrent(static_cast<EGLDisplay>(eglDisplay_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                              static_cast<EGLContext>(eglContext_)) == EGL_TRUE;
    return true;  // Current: the host keeps it current
}

bool GlContext::enter(std::string& err) {
    if (!headless()) return true;
    if (depth_++ > 0) return true;
    prevOsmesa_ = prevEglContext_ = nullptr;
    // What the thread has current, from whichever of the two libraries is in the process. A
    // host's OSMesa context is restored with its colour buffer; EGL with its display and surfaces.
    if (const OsmesaApi* os = osmesaIfLoaded()) {
        if (OSMesaContext c = os->GetCurrentContext(); c && c != static_cast<OSMesaContext>(osmesa_)) {
            GLint w = 0, h = 0, fmt = 0;
            void* buf = nullptr;
            if (os->GetColorBuffer(c, &w, &h, &fmt, &buf)) {
                prevOsmesa_ = c, prevOsmesaBuffer_ = buf, prevOsmesaW_ = w, prevOsmesaH_ = h;
            }
        }
    }
    if (const EglApi* e = eglIfLoaded()) {
        EGLContext c = e->GetCurrentContext();
        if (c != EGL_NO_CONTEXT && c != static_cast<EGLContext>(eglContext_)) {
            prevEglContext_ = c;
            prevEglDisplay_ = e->GetCurrentDisplay();
            prevEglDraw_ = e->GetCurrentSurface(EGL_DRAW);
            prevEglRead_ = e->GetCurrentSurface(EGL_READ);
        }
    }
    if (!makeCurrent()) {
        --depth_;
        err = osmesa_ ? "OSMesaMakeCurrent failed" : "eglMakeCurrent failed (is the context current on another thread?)";
        return false;
    }
    return true;
}

void GlContext::leave() {
    if (!headless() || depth_ == 0 || --depth_ > 0) return;
    if (osmesa_) {
        const OsmesaApi& os = osmesa();
        if (prevOsmesa_)
            os.MakeCurrent(static_cast<OSMesaContext>(prevOsmesa_), prevOsmesaBuffer_, GL_UNSIGNED_BYTE, prevOsmesaW_,
                           prevOsmesaH_);
        else
            os.MakeCurrent(nullptr, nullptr, 0, 0, 0);  // release ours: another thread may take it
        if (prevEglContext_) {
            // Mesa's EGL and OSMesa share one dispatch per thread: OSMesa took it over, so EGL's
            // context is bound again (unbinding first, as EGL may think it is still current).
            const EglApi& e = egl();
            EGLDisplay d = static_cast<EGLDisplay>(prevEglDisplay_);
            e.MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            e.MakeCurrent(d, static_cast<EGLSurface>(prevEglDraw_), static_cast<EGLSurface>(prevEglRead_),
                          static_cast<EGLContext>(prevEglContext_));
        }
    } else {
        const EglApi& e = egl();
        if (prevEglContext_)
            e.MakeCurrent(static_cast<EGLDisplay>(prevEglDisplay_), static_cast<EGLSurface>(prevEglDraw_),
                          static_cast<EGLSurface>(prevEglRead_), static_cast<EGLContext>(prevEglContext_));
        else
            e.MakeCurrent(static_cast<EGLDisplay>(eglDisplay_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (prevOsmesa_)
            osmesa().MakeCurrent(static_cast<OSMesaContext>(prevOsmesa_), prevOsmesaBuffer_, GL_UNSIGNED_BYTE,
                                 prevOsmesaW_, prevOsmesaH_);
    }
    prevOsmesa_ = prevEglContext_ = nullptr;
}

std::unique_ptr<GlContext> GlContext::create(ContextKind kind, std::string& err, void* (*loader)(const char*)) {
    std::unique_ptr<GlContext> ctx(new GlContext());
    ctx->kind_ = kind;
    if (kind == ContextKind::OSMesa) {
        const OsmesaApi& os = osmesa();
        if (!os.error.empty()) {
            err = os.error;
            return nullptr;
        }
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                               OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
        OSMesaContext c = os.CreateContextAttribs(attribs, nullptr);
        if (!c) {
            err = "OSMesaCreateContextAttribs failed (no GL 3.3 core profile)";
            return nullptr;
        }
        ctx->osmesa_ = c;
        if (!ctx->enter(err)) return nullptr;
        if (const char* missing =
                ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(osmesa().GetProcAddress(n)); })) {
            err = std::string("OSMesa lacks ") + missing;
            return nullptr;
        }
    } else if (kind == ContextKind::EGL) {
        const EglApi& e = egl();
        if (!e.error.empty()) {
            err = e.error;
            return nullptr;
        }
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(e.GetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) {
            err = "EGL: eglGetPlatformDisplayEXT unavailable";
            return nullptr;
        }
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d == EGL_NO_DISPLAY || !e.Initialize(d, nullptr, nullptr)) {
            err = "EGL: surfaceless platform unavailable";
            return nullptr;
        }
        ctx->eglDisplay_ = d;
        if (!e.BindAPI(EGL_OPENGL_API)) {
            err = "EGL: desktop OpenGL API unavailable";
            e.Terminate(d);
            ctx->eglDisplay_ = nullptr;
            return nullptr;
        }
        const EGLint cfgAttr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig cfg = nullptr;
        EGLint n = 0;
        if (!e.ChooseConfig(d, cfgAttr, &cfg, 1, &n) || n < 1) cfg = nullptr;  // no-config contexts are fine
        const EGLint ctxAttr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLContext c = e.CreateContext(d, cfg, EGL_NO_CONTEXT, ctxAttr);
        if (c == EGL_NO_CONTEXT) {
            err = "EGL: eglCreateContext (3.3 core) failed";
            e.Terminate(d);
            ctx->eglDisplay_ = nullptr;
            return nullptr;
        }
        ctx->eglContext_ = c;
        if (!ctx->enter(err)) {
            err = "EGL: eglMakeCurrent (surfaceless) failed";
            return nullptr;
        }
        if (const char* missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(egl().GetProcAddress(n)); })) {
            err = std::string("EGL lacks ") + missing;
            return nullptr;
        }
    } else if (kind == ContextKind::Null) {
        // No driver: the capabilities of a GL 4.5 driver like llvmpipe (texture barrier, exact
        // interpolation), so the translator takes the paths it takes there.
        loadNullGl(ctx->funcs_);
        GlCaps& c = ctx->caps_;
        c.major = 4, c.minor = 5;
        c.version = "4.5 (null GL)";
        c.renderer = "null GL";
        c.textureBarrier = true;
        c.exactInterp = true;
        return ctx;
    } else {
        // Host context: OSMesa's if the host has libOSMesa loaded and one of its contexts current,
        // else ask EGL (Mesa/glvnd resolve core entry points for any current context).
        const char* missing = nullptr;
        const OsmesaApi* os = osmesaIfLoaded();
        if (loader) {
            missing = ctx->funcs_.load(loader);
        } else if (os && os->GetCurrentContext()) {
            missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(osmesa().GetProcAddress(n)); });
        } else {
            if (!egl().error.empty()) {
                err = "no OSMesa context current and " + egl().error;
                return nullptr;
            }
            missing = ctx->funcs_.load([](const char* n) { return reinterpret_cast<void*>(egl().GetProcAddress(n)); });
        }
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
