// SPDX-License-Identifier: MIT
// ge2gl's OpenGL backend: draws what the PSP's GE draws, on GL 3.3 core, headless (OSMesa by
// default, EGL surfaceless as an option, or a context the host made current).
//
// How it stays exact (details in the file comments of gl_renderer.cpp, vertex_pipeline.h,
// framebuffer_manager.h, texture_cache.h and shadergen/shader_gen.cpp):
//  - vertices are transformed, lit, clipped and culled on the CPU and fed in drawing coordinates
//    on the GE's 1/16-pixel grid; GL only rasterises (its fill convention equals the GE's);
//  - the fragment shader runs the GE pixel pipeline in integers (texture function, filtering with
//    4-bit weights, fog, tests, stencil in the alpha bits, blending, dither, logic op, masks,
//    truncation to the frame-buffer format) reading the destination by framebuffer fetch, by
//    texture barrier, or from a copy (`baseline`);
//  - emulated VRAM stays the source of truth: render targets are caches of VRAM ranges, uploaded
//    before drawing and written back exactly on syncMemoryForRead / flushToMemory.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "backend/capabilities.h"
#include "geometry/accuracy_profile.h"
#include "hle/memory.h"
#include "hle/renderer.h"

namespace ge::gl {

// Null: a dispatch table whose calls do nothing (translator/null_gl.h): measures the
// translator's own CPU cost; renders nothing.
enum class ContextKind { OSMesa, EGL, Current /*host made a context current*/, Null };

// exact: the software model's rasteriser arithmetic in the fragment shader (per-triangle records,
//        GL 4.0 + int64; float interpolation without), 1× only — the accuracy and CI mode.
// hw:    GL rasterises natively with interpolated attributes at render scale 1–8 (targets N× the
//        PSP's pixels; VRAM write-back box-downsampled); the pixel pipeline keeps the exact integer
//        fragment code (dither indexed by the PSP pixel). Vertex work runs on the CPU (shared
//        geometry code) or, for triangle/strip/fan PRIMs, in a generated vertex shader with a
//        geometry shader (GlOptions::vertices below, gpu_vertex_path.h).
enum class GlMode { Exact, Hw };

struct GlOptions {
    ContextKind context = ContextKind::OSMesa;
    GlMode mode = GlMode::Exact;
    int scale = 1;                // render scale N (1–8); above 1 needs GlMode::Hw
    // Hw mode: where PRIM vertices are transformed and lit. Gpu: in the generated vertex shader
    // where it can (gpu_vertex_path.h). Cpu: all on the CPU (shared geometry/ code). Auto: Cpu on
    // a software rasteriser (llvmpipe, softpipe, SwiftShader: the "GPU" is the same CPU, and one
    // GL draw per GE draw costs it more than the CPU transform of a batched draw), else Gpu.
    enum class Vertices { Auto, Gpu, Cpu } vertices = Vertices::Auto;
    bool baseline = false;        // force GL 3.3 core paths, no optional extensions
    // Current: the host's GL loader (SDL_GL_GetProcAddress, eglGetProcAddress, ...); null: EGL's
    // or OSMesa's, whichever has a context current.
    void* (*loader)(const char*) = nullptr;
    std::string shaderDumpDir;    // write every generated shader here (empty = off)
    std::string programCacheDir;  // on-disk program binaries, empty = off
    // Testing aid: ignore framebuffer fetch so destination reads use the texture-barrier path
    // (the path a driver without EXT_shader_framebuffer_fetch takes). Additive to the spec.
    bool disableFramebufferFetch = false;
    // Interpolate triangle attributes in GL float even where exact interpolation (per-pixel
    // evaluation of the software rasteriser's setup; GL 4.0 + ARB_gpu_shader_int64) is available:
    // the path of hosts without it. Additive to the spec, for tests and comparisons.
    bool floatInterpolation = false;
    // The rules where the PSP and PPSSPP's software renderer differ (geometry/accuracy_profile.h):
    // the shared geometry's and the shader keys'.
    geo::AccuracyProfile accuracy = geo::AccuracyProfile::psp();
};

// The most GL triangles the translator holds on the CPU before it draws them (one batch, or the
// part of one huge draw built so far): about 25 MB of vertices, bounds and exact-mode records.
inline constexpr size_t kGlBatchTriangles = size_t(1) << 16;

struct GlStats {
    u64 draws = 0, glDrawCalls = 0, stateChanges = 0, shaderCompiles = 0, shaderCacheHits = 0, diskCacheHits = 0,
        textureUploads = 0, textureCacheHits = 0, readbacks = 0,
        // Hardware mode: textures sampled from a render target in place / through VRAM (a frame
        // buffer the GPU path cannot read: other formats, mipmaps, the draw's own target); block
        // transfers done between render targets on the GPU.
        rttGpu = 0, rttVram = 0, transfersGpu = 0,
        // Hardware mode: PRIM draws whose vertices the vertex shader processed / that stayed on
        // the CPU (reasons in gpuVertexStats, gpu_vertex_path.h).
        gpuVertexDraws = 0, cpuVertexDraws = 0,
        // Fragment-uniform sets per flush: uploaded / skipped because the program already held them.
        uniformUploads = 0, uniformUploadsSkipped = 0,
        // GL triangles built on the CPU (a line or point fragment's quad counts two), and the GE
        // time charged for them while a GE-time limit was set (VertexPipeline::kHostPixelsPerGlTriangle).
        cpuTriangles = 0, cpuTriangleCycles = 0,
        // The most GL triangles one batch held, and the bytes the CPU geometry arrays (batch and
        // current draw) hold reserved now.
        batchPeak = 0, cpuGeometryBytes = 0,
        // Patches the CPU path did not tessellate: wholly beyond a side of the clip rectangle.
        culledPatches = 0;
    u64 cpuVertexByReason[8] = {};  // gpu_vertex_path.h CpuReason order
};

// The GL translator as a backend: a Renderer offering every optional interface of
// backend/capabilities.h, plus what only GL tests and tools ask of it. The drawing class itself
// is translator-internal (gl_renderer_impl.h).
//
// HostContextUser (gl_host_state.h): plugin API calls that touch GL are bracketed by
// hostEnter/hostLeave: a headless context is made current on the calling thread and the thread's
// previous one restored after; a host's context has its state saved and restored; either way the
// renderer re-establishes its own state on entry. FramePresenter: the texture comes from
// present.h. ScaledRendering: read from the render target where one holds the frame.
class GlRenderer : public Renderer,
                   public backend::FramePresenter,
                   public backend::ScaledRendering,
                   public backend::HostContextUser,
                   public backend::StatsSource {
public:
    virtual GlStats stats() const = 0;
    // Guest memory was replaced wholesale (the host restored it, or reuses the renderer for
    // another dump): draws what is batched, then drops every render target, texture and palette
    // without writing anything back. The renderer then reads memory as a fresh one would;
    // compiled programs stay (creating them dominates a fresh renderer's cost). The fuzz harness
    // replay_gl runs each input this way.
    virtual void forgetGuestMemory() = 0;
};

// Loads the library a context of `kind` is made with (libOSMesa or libEGL, and libLLVM behind
// llvmpipe: tens of milliseconds of loading and relocation) without making a context, as the
// first createGlRenderer with that context would. A caller with other work first (reading a dump)
// may call it on another thread, so that the loading overlaps that work. Thread-safe; nothing for
// Current and Null, nor once loaded.
void preloadContextLibrary(ContextKind kind);

// Creates the context (unless Current) and the renderer, entered (HostContextUser); nullptr +
// err when GL is unavailable or the options are out of range.
std::unique_ptr<GlRenderer> createGlRenderer(ge::Memory& mem, const GlOptions& opt, std::string& err);
std::string glStatsText(const GlStats& s);  // one line per counter

}  // namespace ge::gl
