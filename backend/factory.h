// SPDX-License-Identifier: MIT
// The one place backends are made (plugin API ge2gl_create, the tools' --backend): a Renderer
// plus the optional interfaces of backend/capabilities.h it offers. Callers ask the Backend for
// an interface and never learn the backend's class; whether the GL translator is built in is
// known here only (backendBuilt).
#pragma once
#include <memory>
#include <string>

#include "backend/capabilities.h"
#include "geometry/accuracy_profile.h"
#include "hle/memory.h"
#include "hle/renderer.h"

namespace ge::backend {

enum class BackendKind {
    Null,  // draws nothing (hle/renderer.h NullRenderer; block transfers still happen)
    Soft,  // the software model (softmodel/)
    Gl,    // the OpenGL translator (translator/)
};

// Where the GL translator draws (translator/gl_renderer.h ContextKind).
enum class GlContext { OSMesa, EGL, Current /*the host made its context current*/, Null /*GL calls do nothing*/ };
// translator/gl_renderer.h GlMode: exact (1×, the accuracy mode) or hw (native rasterisation, scale 1–8).
enum class GlMode { Exact, Hw };
// GL hw mode: where PRIM vertices are transformed (translator/gl_renderer.h GlOptions::vertices).
enum class GlVertices { Auto, Gpu, Cpu };

struct BackendOptions {
    BackendKind kind = BackendKind::Soft;
    int threads = 0;  // Soft: band threads (0 = all cores); the output is identical for any count
    // Both: the rules where the PSP and PPSSPP's software renderer differ
    // (geometry/accuracy_profile.h): psp, what the GE does, or ppsspp, that renderer's pixels.
    geo::AccuracyProfile accuracy = geo::AccuracyProfile::psp();
    // Gl only:
    GlContext glContext = GlContext::OSMesa;
    GlMode glMode = GlMode::Exact;
    int scale = 1;  // render scale 1–8, above 1 only in GlMode::Hw
    GlVertices glVertices = GlVertices::Auto;
    bool glBaseline = false;  // force the GL 3.3 core paths, no optional extensions
    // GlContext::Current: the host's GL loader (SDL_GL_GetProcAddress, ...); null: EGL's or OSMesa's.
    void* (*glLoader)(const char*) = nullptr;
    std::string shaderDumpDir;    // write every generated shader here (empty = off)
    std::string programCacheDir;  // on-disk program binaries (empty = off)
};

// A made backend: the Renderer and, for each optional interface, the view of it that the
// backend offers (null where it does not). Views live as long as `renderer`.
struct Backend {
    std::unique_ptr<Renderer> renderer;
    FramePresenter* presenter = nullptr;
    ScaledRendering* scaled = nullptr;
    HostContextUser* host = nullptr;
    StatsSource* stats = nullptr;

    explicit operator bool() const { return renderer != nullptr; }
};

// Whether this build holds the backend (the GL translator is optional: GE2GL_BUILD_GL).
bool backendBuilt(BackendKind kind);

// Makes the backend drawing into `mem`; an empty Backend and `err` when it cannot (a kind not
// built, no GL context, options out of range). A GL backend is returned entered
// (HostContextUser): its context current on this thread, or the host's state saved.
Backend createBackend(Memory& mem, const BackendOptions& opt, std::string& err);

// What createBackend would load before making a backend of `opt` — the GL context's library
// (translator/gl_context.h preloadContextLibrary) — loaded now, on the calling thread: a caller
// may run it on another thread while it reads its input. Thread-safe; nothing for soft and null.
void preloadBackend(const BackendOptions& opt);

}  // namespace ge::backend
