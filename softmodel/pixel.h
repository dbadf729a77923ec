// SPDX-License-Identifier: MIT
// The contract between the rasteriser the software model draws with (raster side:
// geometry/raster*, transform*, clip*) and its per-pixel stages (pixel side: softmodel/pixel*,
// sampler*).
//
// The rasteriser turns primitives into Fragments (geometry/fragment.h), in primitive order,
// already limited to the scissor/region rectangle; the pixel side runs manual §13–§17 on each
// (texture sampling and function, colour addition, fog, tests, stencil, depth, blending,
// dithering, clamp, logic op, masks) and writes the frame and depth buffers in emulated VRAM in
// their real formats. Everything here is integer/fixed point except texture coordinates; results are bit-exact and
// independent of thread count (threads own disjoint rows).
#pragma once
#include <memory>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "geometry/fragment.h"
#include "hle/ge_state.h"
#include "hle/memory.h"

namespace ge::soft {

class TextureCache;  // decoded texture levels reused across draws (pixel side owns it)

// Per-draw pixel state derived once from GeState (and memory pointers), read-only while shading.
struct PixelState {
    // Frame and depth buffers (VRAM pointers computed with bounds checks; null = not writable).
    u8* fb = nullptr;
    u32 fbStride = 0;  // pixels
    GeBufferFormat fbFormat = GE_FORMAT_8888;
    u8* zb = nullptr;
    u32 zbStride = 0;
    // Rows/columns the buffers can hold without leaving VRAM (fragments outside are dropped).
    int fbMaxY = 0, zbMaxY = 0;
    // The rest is private to the pixel side (decoded textures, tests, blend, masks, the
    // specialised shading function chosen for this state…).
    struct Impl;
    std::shared_ptr<const Impl> impl;
};

// Builds the pixel state for the draw about to happen. `through` and `clearMode` come from the
// packet/state; `textureEnabled` may be overridden (immediate vertices carry their own flags).
// `vertexAlphaFull`: every primary colour of the draw that reaches a fragment has alpha 255 (the
// reference's skipped alpha test depends on it, geometry/reference_rules.h
// referenceSkipsAlphaTest). `acc`: whether the reference's alpha-test rules apply
// (AccuracyProfile::clutSkipsAlphaTest, implicitAlphaNonZeroTest).
PixelState buildPixelState(const GeState& st, Memory& mem, TextureCache& cache, const geo::AccuracyProfile& acc,
                           bool textureEnabled, bool vertexAlphaFull = false);

// Runs the whole per-pixel pipeline for n fragments, in order.
void shadeFragments(const PixelState& ps, const geo::Fragment* frags, size_t n);

// Decoded-texture cache shared by draws of one renderer (invalidate on memory writes, TFLUSH,
// CLUT loads).
void destroyTextureCache(TextureCache* cache);
struct TextureCacheDeleter {
    void operator()(TextureCache* c) const { destroyTextureCache(c); }
};
using TextureCachePtr = std::unique_ptr<TextureCache, TextureCacheDeleter>;
TextureCachePtr createTextureCache();
void invalidateTextureCache(TextureCache& cache, u32 addr, u32 size);  // size 0: everything
void clutChanged(TextureCache& cache);

}  // namespace ge::soft
