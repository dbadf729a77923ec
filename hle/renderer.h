// SPDX-License-Identifier: MIT
// The one abstract interface between the GE machine (hle/) and a backend (softmodel/, translator/).
//
// The engine hands a backend plain packets. A packet refers to the engine's live GeState: it is
// valid only for the duration of the call (a backend that defers work snapshots what it needs).
// `dirty` carries the GeDirty groups that changed since the previous packet of any kind, so a
// backend re-derives only what changed. Backends read and write guest memory only through the
// Memory they were constructed with; the emulated VRAM is the source of truth.
#pragma once
#include <utility>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"

namespace ge {

struct PrimPacket {
    const GeState* state = nullptr;
    u32 dirty = 0;
    GePrimType prim = GE_PRIM_POINTS;  // resolved: never GE_PRIM_KEEP_PREVIOUS
    bool continuation = false;         // PRIM type 7: continues the previous strip/fan/list
    u32 count = 0;                     // vertices (or indices) to draw, > 0
    u32 vtype = 0;                     // CMD_VTYPE argument
    u32 vertexAddr = 0;                // vertex pointer at the kick
    u32 indexAddr = 0;                 // index pointer at the kick (used when VTYPE_idx != 0)
};

struct PatchPacket {
    const GeState* state = nullptr;
    u32 dirty = 0;
    bool spline = false;  // false: Bezier
    u32 ucount = 0, vcount = 0;       // control points per direction
    u32 uknot = 0, vknot = 0;         // spline knot types (bit 0 start open, bit 1 end open)
    u32 divU = 1, divV = 1;           // CMD_DIVIDE, 0 treated as 1
    u32 patchPrim = 0;                // CMD_PPM: 0 triangles, 1 lines, 2/3 points
    bool reverseFace = false;         // CMD_PFACE
    u32 vtype = 0, vertexAddr = 0, indexAddr = 0;
};

// The tessellator's output cap (geometry/spline.cpp): a surface past it is not drawn.
constexpr u64 kMaxPatchOutputVertices = u64(1) << 21;
// The vertices the tessellator generates for a patch of at least 4×4 control points: Bezier
// patches every 3 control points, each (div+1)² vertices; a spline surface of (spans·div + 1)
// vertices a side, a span for every point after the third (manual §5.2). Divisions 0 count as 1.
inline u64 patchOutputVertices(const PatchPacket& p) {
    const u64 divU = p.divU ? p.divU : 1, divV = p.divV ? p.divV : 1;
    const u64 patchesU = p.spline ? p.ucount - 3 : (p.ucount - 1) / 3;
    const u64 patchesV = p.spline ? p.vcount - 3 : (p.vcount - 1) / 3;
    return p.spline ? (patchesU * divU + 1) * (patchesV * divV + 1) : patchesU * patchesV * (divU + 1) * (divV + 1);
}

// A block transfer (CMD_XSTART), fully resolved. Strides and positions in pixels.
struct TransferPacket {
    u32 src = 0, srcStride = 0, srcX = 0, srcY = 0;
    u32 dst = 0, dstStride = 0, dstX = 0, dstY = 0;
    u32 width = 0, height = 0;  // pixels, 1–1024
    u32 bpp = 2;                // 2 or 4 bytes per pixel
    // First byte and byte extent touched on each side.
    u32 srcBegin() const { return src + (srcY * srcStride + srcX) * bpp; }
    u32 dstBegin() const { return dst + (dstY * dstStride + dstX) * bpp; }
    u32 srcBytes() const { return ((height - 1) * srcStride + width) * bpp; }
    u32 dstBytes() const { return ((height - 1) * dstStride + width) * bpp; }
};
// Performs the copy on guest memory exactly as the GE does (rows, VRAM wrap, overlap).
// Returns the number of rows that could not be copied because they were out of range.
u32 performTransfer(Memory& mem, const TransferPacket& t);

// Immediate-mode vertices (CMD_X2 … CMD_AP2), already in drawing coordinates.
struct ImmVertex {
    float x = 0, y = 0;  // drawing coordinates (OFFSETX/Y or the through bias removed), 1/16 precision
    u16 z = 0;
    float s = 0, t = 0, q = 1;
    u8 color[4] = {};    // RGBA
    u8 secondary[3] = {};
    u8 fog = 255;
};
struct ImmPacket {
    const GeState* state = nullptr;
    u32 dirty = 0;
    GePrimType prim = GE_PRIM_POINTS;
    u32 flags = 0;  // AP2 bits 11..23 of the first vertex (antialias, gouraud, cull, cullccw, texture, fog, dither)
    std::vector<ImmVertex> vertices;
};

class Renderer {
public:
    virtual ~Renderer() = default;

    virtual void drawPrim(const PrimPacket& p) = 0;
    virtual void drawPatch(const PatchPacket& p) = 0;
    virtual void drawImmediate(const ImmPacket& p) = 0;

    // CMD_XSTART. The default performs the copy in guest memory; a backend that caches VRAM
    // (render targets) must make the source current first and invalidate the destination.
    virtual void blockTransfer(const TransferPacket& t, Memory& mem) {
        syncMemoryForRead(t.srcBegin(), t.srcBytes());
        performTransfer(mem, t);
        memoryWritten(t.dstBegin(), t.dstBytes());
    }
    // The palette RAM in GeState::clut was reloaded by CMD_CLOAD.
    virtual void clutLoaded(const GeState&) {}
    virtual void textureFlush() {}  // CMD_TFLUSH
    virtual void textureSync() {}   // CMD_TSYNC
    // FINISH reached: all drawing so far must be complete.
    virtual void finish() {}
    // Guest memory [addr, addr+size) is about to be read by the engine or the host (size 0 =
    // unknown extent starting at addr): write back anything the backend holds for it.
    virtual void syncMemoryForRead(u32 /*addr*/, u32 /*size*/) {}
    // Guest memory was written outside the backend (transfers, CPU, dump replay): drop caches.
    virtual void memoryWritten(u32 /*addr*/, u32 /*size*/) {}
    // Make emulated VRAM hold every pixel drawn so far (before the host reads a frame).
    virtual void flushToMemory() {}
    // The host may have written guest memory without saying where (plugin API: a list was queued,
    // continued or its stall moved). Cached textures are checked against their source bytes when
    // next used (content hash, as PPSSPP's texture cache does); with `frameBuffers`, cached frame
    // and depth buffers against VRAM too.
    virtual void hostMayHaveWritten(bool /*frameBuffers*/) {}
    // Byte ranges drawn into since they were last written to guest memory and not reported by an
    // earlier call (backends that draw elsewhere than guest memory; plugin API lazy write-back).
    virtual void takeDirtyRanges(std::vector<std::pair<u32, u32>>& /*out*/) {}
    // True when the backend may hold pixels of [addr, addr+size) newer than guest memory (a read
    // of guest memory needs syncMemoryForRead first). Answered without touching GL.
    virtual bool holdsNewerThanMemory(u32 /*addr*/, u32 /*size*/) const { return false; }
    // Cumulative upper bound of the pixels the primitives handed to the backend can write (their
    // clipped bounding boxes), for the GE-time estimate (hle/ge_time.h). 0 for a backend that
    // does not rasterise.
    virtual u64 pixelWork() const { return 0; }
    // The draws that follow may add at most `pixels` to pixelWork(): primitives beyond it are
    // dropped, though still counted in pixelWork() so that the engine sees its limit passed (the
    // GE-time limit reaching into a single huge draw). ~0: no limit.
    virtual void setPixelBudget(u64 /*pixels*/) {}
};

// A backend that draws nothing, for exercising the decoder (it still performs transfers).
class NullRenderer : public Renderer {
public:
    void drawPrim(const PrimPacket& p) override { ++prims; vertices += p.count; }
    void drawPatch(const PatchPacket&) override { ++patches; }
    void drawImmediate(const ImmPacket&) override { ++immediates; }
    u64 prims = 0, patches = 0, immediates = 0, vertices = 0;
};

}  // namespace ge
