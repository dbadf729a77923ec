// SPDX-License-Identifier: MIT
// The software model's Renderer: ge2gl's bit-accurate CPU GE (manual §3–§11; docs/ge-rules.md §8).
//
// Per draw, on the caller's thread: vertices are decoded once (hle/vertex_decoder.h; patches via
// geometry/spline.h), transformed, lit and clipped (geometry/transform.h, lighting.h, clip.h, the
// code the GL translator runs too), assembled into points, lines, triangles and rectangles
// (geometry/assembly.h; strip/fan state survives PRIM type 7), culled, and queued with the draw's
// PixelState (pixel.h) into a batch. Batches are rasterised by worker threads, each owning a set
// of 16-row bands (geometry/raster.h Band) and walking every primitive of the batch in order, so
// every pixel is shaded by exactly one thread in primitive order: the output is identical for any
// thread count. While workers rasterise one batch the caller builds the next.
//
// Synchronisation: finish(), flushToMemory(), transfers, memoryWritten(), syncMemoryForRead()
// touching VRAM, and a texture read from a range that queued draws may still write (render to
// texture) all wait for the queued work first.
#pragma once
#include <memory>

#include "geometry/accuracy_profile.h"
#include "hle/renderer.h"

namespace ge::soft {

struct SoftOptions {
    int threads = 0;  // rasterising threads; 0 = hardware concurrency; 1 = no worker threads
    // The rules where the PSP and PPSSPP's software renderer differ (geometry/accuracy_profile.h).
    geo::AccuracyProfile accuracy = geo::AccuracyProfile::psp();
};

struct SoftStats {
    u64 draws = 0, patches = 0, immediates = 0;
    u64 vertices = 0;        // vertices transformed
    u64 primitives = 0;      // primitives queued for rasterisation
    u64 culled = 0;          // back-face culled triangles
    u64 discarded = 0;       // dropped by the ge-rules.md §8.5 rules (range, depth, w < 0) or bad vertices
    u64 clipped = 0;         // primitives cut at the near plane
    u64 batches = 0;
    u64 badDraws = 0;        // draws whose vertex or index data was not valid memory
    u64 budgetDropped = 0;   // primitives dropped at the GE-time limit (setPixelBudget)
    u64 culledPatches = 0;   // patches wholly beyond a side of the clip rectangle: not tessellated
};

class SoftRenderer : public Renderer {
public:
    SoftRenderer(Memory& mem, const SoftOptions& opt);
    ~SoftRenderer() override;
    SoftRenderer(const SoftRenderer&) = delete;
    SoftRenderer& operator=(const SoftRenderer&) = delete;

    void drawPrim(const PrimPacket& p) override;
    void drawPatch(const PatchPacket& p) override;
    void drawImmediate(const ImmPacket& p) override;
    void blockTransfer(const TransferPacket& t, Memory& mem) override;
    void clutLoaded(const GeState& st) override;
    void textureFlush() override;
    void textureSync() override;
    void finish() override;
    void syncMemoryForRead(u32 addr, u32 size) override;
    void memoryWritten(u32 addr, u32 size) override;
    void hostMayHaveWritten(bool frameBuffers) override;
    void flushToMemory() override;
    u64 pixelWork() const override;
    void setPixelBudget(u64 pixels) override;

    int threadCount() const;
    const SoftStats& stats() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// The software model as a Renderer (what tools and the API create).
std::unique_ptr<ge::Renderer> createSoftRenderer(ge::Memory& mem, const SoftOptions& opt = {});

}  // namespace ge::soft
