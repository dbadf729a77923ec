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

#include "hle/memory.h"
#include "hle/renderer.h"

namespace ge::gl {

enum class ContextKind { OSMesa, EGL, Current /*host made a context current*/ };

struct GlOptions {
    ContextKind context = ContextKind::OSMesa;
    bool baseline = false;        // force GL 3.3 core paths, no optional extensions
    std::string shaderDumpDir;    // write every generated shader here (empty = off)
    std::string programCacheDir;  // on-disk program binaries, empty = off
    // Testing aid: ignore framebuffer fetch so destination reads use the texture-barrier path
    // (the path a driver without EXT_shader_framebuffer_fetch takes). Additive to the spec.
    bool disableFramebufferFetch = false;
    // Interpolate triangle attributes in GL float even where exact interpolation (per-pixel
    // evaluation of the software rasteriser's setup; GL 4.0 + ARB_gpu_shader_int64) is available:
    // the path of hosts without it. Additive to the spec, for tests and comparisons.
    bool floatInterpolation = false;
};

struct GlStats {
    u64 draws = 0, glDrawCalls = 0, stateChanges = 0, shaderCompiles = 0, shaderCacheHits = 0, diskCacheHits = 0,
        textureUploads = 0, textureCacheHits = 0, readbacks = 0;
};

// Creates the context (unless Current) and the renderer; nullptr + err when GL is unavailable.
std::unique_ptr<ge::Renderer> createGlRenderer(ge::Memory& mem, const GlOptions& opt, std::string& err);
GlStats glStats(const ge::Renderer& r);     // r must come from createGlRenderer
std::string glStatsText(const GlStats& s);  // one line per counter
// GL texture name (RGBA8, row 0 = top line) holding the frame at vramAddr for presenting (plugin
// API). Valid until the next call; 0 on error.
unsigned glFrameTexture(ge::Renderer& r, u32 vramAddr, u32 stride, GeBufferFormat fmt);

}  // namespace ge::gl
