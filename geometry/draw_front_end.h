// SPDX-License-Identifier: MIT
// The draw front end both backends run: from a draw packet (hle/renderer.h) to the primitives a
// backend rasterises, in the order and with the numbers the software model uses.
//
//   decode (hle/vertex_decoder.h: each vertex a draw's indices reach, once, skinned)
//   → transform, lighting, texture coordinates, fog (transform.h)
//   → PRIM type 7 continuation (the still-open vertices of the previous PRIM come first)
//   → primitive assembly and strip/fan-as-rectangle detection (assembly.h)
//   → discard rules, near clipping and back-face culling (clip.h)
//   → rectangles drawn as triangles under texture projection (assembly.h rectangleCorner)
//   → the clip-rectangle row test, the pixel bound and the GE-time pixel budget (raster.h)
//   → PrimitiveSink::primitive, one call per primitive to draw.
//
// A backend implements PrimitiveSink: the software model queues the primitives for its band
// threads (softmodel/soft_renderer.cpp), the GL translator turns them into GL triangles
// (translator/vertex_pipeline.cpp). Nothing here knows either backend.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "geometry/assembly.h"
#include "geometry/raster.h"
#include "geometry/spline.h"
#include "geometry/transform.h"
#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/renderer.h"
#include "hle/vertex_decoder.h"

namespace ge::geo {

// One primitive to draw. Vertex pointers are valid during the sink call only.
struct Primitive {
    PrimKind kind = PrimKind::Point;
    // Triangle: a, b, c in the order the software model rasterises them (the strip/fan ring
    // order, clip.h); line: v0, v1, v1; point: v0 three times; rectangle: v0, v1, v1.
    const ScreenVertex* v[3] = {};
    const ScreenVertex* prov = nullptr;  // the provoking vertex: flat shading takes its colours
    // Per vertex (and for prov): its index among the draw's transformed vertices when it is one of
    // them unchanged, so a sink may store each once; -1 for a vertex made here (clipping,
    // rectangle corners).
    s32 id[3] = {-1, -1, -1};
    s32 provId = -1;
    // False when it covers no pixel row of the clip rectangle (raster.h primitiveRows): nothing of
    // it is drawn at the GE's resolution, and it is not charged. A backend drawing at a higher
    // resolution (GL render scaling) still draws it, so that features thinner than a pixel keep
    // the samples they cover there; the software model drops it.
    bool inside = true;
    int y1 = 0, y2 = -1;  // pixel rows it may touch inside the clip rectangle (when inside)
    // 1 when this triangle and the previous one are parts of one convex shape (a clipped polygon,
    // a rectangle drawn as two triangles): they never cover the same pixel.
    int joinPrev = 0;
};

class PrimitiveSink {
public:
    virtual void primitive(const Primitive& p) = 0;

protected:
    ~PrimitiveSink() = default;
};

// Counters over all draws (software model statistics, `ge2gl render --stats`).
struct FrontEndStats {
    u64 vertices = 0;       // vertices transformed
    u64 primitives = 0;     // primitives handed to the sink
    u64 culled = 0;         // back-face culled triangles
    u64 discarded = 0;      // dropped by the docs/ge-rules.md §8.5 rules (range, depth, w < 0) or bad vertices
    u64 clipped = 0;        // primitives cut at the near plane
    u64 badDraws = 0;       // draws whose vertex or index data was not valid memory
    u64 budgetDropped = 0;  // primitives dropped at the GE-time limit (setPixelBudget)
    u64 culledPatches = 0;  // patches not tessellated: wholly beyond a side of the clip rectangle
};

// The raster parameters of a draw: scissor ∩ REGION2 (docs/ge-rules.md §8.6), shading, texturing
// and fog as the state sets them, clear mode drawing flat and untextured (PPSSPP's software
// renderer, ClearMode handling in Rasterizer).
// `rectangles`: a RECTANGLES draw (its far edge as AccuracyProfile::spriteFarEdgeExcluded says);
// AccuracyProfile::zeroAreaTriangles as `acc` says.
RasterParams rasterParamsFor(const GeState& st, bool through, bool rectangles, const AccuracyProfile& acc);

// The state an immediate-mode primitive draws with: the AP2 flags of its first vertex override
// antialiasing, shading, culling, texturing, fog and dither (docs/ge-rules.md §3.12).
GeState immediateState(const GeState& st, u32 ap2Flags);

class DrawFrontEnd {
public:
    // `acc`: the rules where the PSP and PPSSPP's software renderer differ (accuracy_profile.h).
    explicit DrawFrontEnd(const AccuracyProfile& acc) : acc_(acc) {}
    const AccuracyProfile& accuracy() const { return acc_; }

    // A PRIM draw (`p.continuation`: PRIM type 7, docs/ge-rules.md §3.2). False + err when its
    // index data is unreadable: nothing is drawn and no vertices stay open. Unreadable vertices
    // drop the primitives they belong to (counted as a bad draw, the rest is drawn).
    bool prim(const Memory& mem, const GeState& st, const PrimPacket& p, PrimitiveSink& sink, std::string* err);
    // A Bezier/spline patch (spline.h tessellates it). Ends any open PRIM. A patch whose control
    // points all lie beyond one side of the clip rectangle is not tessellated (its surface lies
    // in their hull: draw_front_end.cpp patchOffClip); FrontEndStats::culledPatches counts them.
    bool patch(const Memory& mem, const GeState& st, const PatchPacket& p, PrimitiveSink& sink, std::string* err);
    // Immediate vertices (already in drawing coordinates); `st` as immediateState gives it.
    void immediate(const GeState& st, const ImmPacket& p, PrimitiveSink& sink);
    // A fresh triangle/strip/fan PRIM drawn elsewhere (the GL translator's GPU vertex path):
    // keeps what a PRIM type 7 continuation after it needs — its still-open vertices,
    // transformed, and the strip parity — as prim()'s walk would have left them.
    void keepOpenVertices(const Memory& mem, const GeState& st, const PrimPacket& p);
    // The test patch() passes the tessellator (a patch wholly beyond a side of the clip
    // rectangle is skipped, counted in culledPatches), for a caller tessellating a patch itself
    // (the GL translator's GPU vertex path). It reads the front end's transform state made here
    // for `st` and the patch's format: use it before the next call into the front end.
    PatchSkip offClipTest(const Memory& mem, const GeState& st, const PatchPacket& p);
    // A patch drawn elsewhere: ends any open PRIM, as patch() does.
    void endOpenPrim() {
        pending_.clear();
        stripOdd_ = false;
    }
    // The GeDirty groups of every packet (PrimPacket/PatchPacket/ImmPacket::dirty), which a
    // backend hands on at the top of each draw call, whether or not the front end then sees the
    // draw: the transform state is remade only when a group it reads changed (hle/ge_cmds.def).
    void noteDirty(u32 groups) { dirty_ |= groups; }

    // Of the draw being assembled (valid in sink calls and after the call until the next draw).
    const RasterParams& rasterParams() const { return rp_; }
    const TransformState& transform() const { return ts_; }
    // Whether every primary colour of the draw's primitives that reaches a fragment has alpha 255:
    // all vertices with Gouraud shading, else the provoking one and rectangles' second vertex (as
    // the reference's CalculateRasterStateFlags reads them).
    bool drawAlphaFull() const { return alphaFull_; }

    // Renderer::pixelWork (hle/ge_time.h): the pixel bounds of the primitives handed on, plus what
    // charge() adds. While a budget is set (a GE-time limit: dump replays) primitives beyond it
    // are dropped but charged, so the engine sees the limit passed.
    u64 pixelWork() const { return pixelWork_; }
    void setPixelBudget(u64 pixels) {
        pixelBudgetLeft_ = pixels;
        budgeted_ = pixels != ~u64(0);
    }
    bool budgeted() const { return budgeted_; }
    // Host work a backend does beyond the pixels (GL triangles built on the CPU), in pixels.
    void charge(u64 pixels) {
        pixelWork_ += pixels;
        pixelBudgetLeft_ -= std::min(pixels, pixelBudgetLeft_);
    }
    const FrontEndStats& stats() const { return stats_; }

private:
    template <class Sink>
    friend void assemblePrimitives(GePrimType, const std::vector<u32>&, bool, bool&, Sink&, std::vector<u32>&);
    // geo::assemblePrimitives' callbacks.
    void triangle(u32 ia, u32 ib, u32 ic, const u32* ring);
    void line(u32 ia, u32 ib);
    void point(u32 ia);
    void rectangle(u32 ia, u32 ib);
    bool quadAsRect(bool fan, const u32 q[4], u32& tl, u32& br) const;

    void begin(const GeState& st, const RasterParams& rp, PrimitiveSink& sink);
    bool decode(const Memory& mem, const GeState& st, const PrimPacket& p);
    void assemble(GePrimType prim, bool keepPending);
    void clippedTriangle(u32 ia, u32 ib, u32 ic, const u32* ring);
    void rectangleAsTriangles(const ScreenVertex& v0, const ScreenVertex& v1);
    bool culled(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) const;
    // Hands one primitive on after the row test and the budget; `ids` as Primitive::id.
    void emit(PrimKind kind, const ScreenVertex* a, const ScreenVertex* b, const ScreenVertex* c,
              const ScreenVertex* prov, const s32 ids[4], int joinPrev);
    void trimVertices();
    // ts_ = makeTransformState(st, vtype, hasColor, hasNormal) with sprite = false, made again only
    // when a group it reads is dirty, the format or the state object differs; else kept.
    void setTransform(const GeState& st, u32 vtype, bool hasColor, bool hasNormal);

    // Per-draw context.
    PrimitiveSink* sink_ = nullptr;
    AccuracyProfile acc_;
    TransformState ts_;
    MatrixFold fold_;  // the last draw's matrix products (makeTransformState)
    // What ts_ was made for by setTransform (tsState_ null: not made by it), and the groups
    // changed since.
    u32 tsKey_ = ~0u;
    const GeState* tsState_ = nullptr;
    u32 dirty_ = DIRTY_ALL;
    RasterParams rp_;
    bool cull_ = false, cullClockwise_ = false;
    bool alphaFull_ = true;
    bool joinable_ = false;  // the last primitive of the shape being emitted was handed on
    RectDetect rectDetect_;

    std::vector<ClipVertex> cverts_;
    TessOutput tess_;  // patch(): kept between patches, trimmed past kKeepTessVertices
    std::vector<u32> indices_, seq_, keep_;
    std::vector<u8> used_;
    // PRIM type 7: the transformed vertices still open and the strip parity.
    std::vector<ClipVertex> pending_;
    bool stripOdd_ = false;

    u64 pixelWork_ = 0;
    u64 pixelBudgetLeft_ = ~u64(0);
    bool budgeted_ = false;
    FrontEndStats stats_;
};

}  // namespace ge::geo
