// SPDX-License-Identifier: MIT
// CPU vertex processing for the GL path: the draw front end both backends run
// (geometry/draw_front_end.h: decode, the reference transform, lighting, texture-coordinate
// generation, fog, clipping and discard rules, primitive assembly), with this class as its sink,
// turning each primitive into GL-ready vertices in drawing coordinates.
//
// Why on the CPU: the GE rounds screen positions to 1/16 pixel (docs/ge-rules.md §8.1), drops
// rather than clips primitives outside the 4096² screen (ge-rules.md §8.5), lights in fixed point
// (ge-rules.md §8.3) and decides rectangles' texture orientation from vertex order
// (ge-rules.md §8.2) — none of which GL's own vertex processing does. The hardware mode's
// generated vertex and geometry shaders (shadergen/hw_vertex.h) reproduce the first three for triangle,
// strip and fan PRIMs sent to the GPU; everything else, and the exact mode, runs this code.
// Sharing the front end with the software model keeps both backends' geometry identical. GL then
// only rasterises triangles, with positions already on the GE's grid; its fill convention equals
// the GE's top-left rule. Lines and points use the software model's rasteriser, geometry/raster.h (GL line
// rules differ from the GE's DDA): each of their fragments becomes a one-pixel quad carrying that
// fragment's exact attributes.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "geometry/draw_front_end.h"
#include "geometry/raster.h"
#include "geometry/transform.h"
#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/renderer.h"
#include "hle/vertex_decoder.h"
#include "translator/tri_setup.h"

namespace ge::gl {

// One vertex as the generated vertex shader reads it (shader_gen.h attribute table).
struct GlVertex {
    float x = 0, y = 0, z = 0;  // drawing coordinates (1/16 grid), screen Z 0..65535
    u8 color[4] = {};
    u8 color2[4] = {};            // secondary RGB, [3] unused
    float tex[4] = {0, 0, 1, 1};  // s·k, t·k, q·k, w (k = 1/w for perspective, else 1)
    float fog = 1;
};
static_assert(sizeof(GlVertex) == 40);

// Per-triangle pixel bounds (for dirty tracking and for ordering destination reads between
// overlapping primitives).
struct PrimBounds {
    int x0, y0, x1, y1;  // inclusive pixel rectangle (may be empty: x1 < x0)
    // 1 when this triangle and the previous one come from one convex shape (rectangle, pixel
    // quad, clipped polygon): they never cover the same pixel, so no ordering is needed.
    int joinPrev;
};
struct Geometry {
    std::vector<GlVertex> tris;  // 3 per triangle
    std::vector<PrimBounds> triBounds;
    std::vector<TriRecord> records;  // 1 per triangle with VertexPipeline::setRecords (exact interpolation)
    std::vector<GradientRecord> gradients;  // the records' gradient planes (gradientIndex)
    void clear() {
        tris.clear();
        triBounds.clear();
        records.clear();
        gradients.clear();
    }
    void append(const Geometry& g) {
        tris.insert(tris.end(), g.tris.begin(), g.tris.end());
        triBounds.insert(triBounds.end(), g.triBounds.begin(), g.triBounds.end());
        const size_t first = records.size();
        const u32 base = u32(gradients.size());
        records.insert(records.end(), g.records.begin(), g.records.end());
        gradients.insert(gradients.end(), g.gradients.begin(), g.gradients.end());
        if (base && !g.gradients.empty())
            for (size_t i = first; i < records.size(); ++i)
                if (hasGradients(records[i])) gradientIndex(records[i]) += base;
    }
    bool empty() const { return tris.empty(); }
    size_t triangles() const { return triBounds.size(); }
    size_t reservedBytes() const {
        return tris.capacity() * sizeof(GlVertex) + triBounds.capacity() * sizeof(PrimBounds) +
               records.capacity() * sizeof(TriRecord) + gradients.capacity() * sizeof(GradientRecord);
    }
    // After a flush: hands the arrays' memory back when it is far more than `triangles` GL
    // triangles need (a huge batch once must not keep its peak resident for the rest of the run).
    void trim(size_t triangles) {
        const size_t keep = std::max<size_t>(4 * triangles, kTrimFloor);
        if (triBounds.capacity() <= keep) return;
        std::vector<GlVertex>().swap(tris);
        std::vector<PrimBounds>().swap(triBounds);
        std::vector<TriRecord>().swap(records);
        std::vector<GradientRecord>().swap(gradients);
    }
    static constexpr size_t kTrimFloor = 16384;  // GL triangles kept without question (6 MB exact)
};

// The GL backend's sink of the shared draw front end (geometry/draw_front_end.h): each primitive
// becomes GL triangles in drawing coordinates.
class VertexPipeline : private geo::PrimitiveSink {
public:
    // `acc`: the shared geometry's rules where the PSP and PPSSPP differ (geo::DrawFrontEnd).
    explicit VertexPipeline(const geo::AccuracyProfile& acc) : frontEnd_(acc) {}
    // Decodes and processes a PRIM draw into `out` (appending). Returns false + err on bad
    // memory (nothing is drawn for that draw). `continuation`: PRIM type 7 (ge-rules.md §3.2).
    bool processPrim(const Memory& mem, const GeState& st, const PrimPacket& p, Geometry& out, std::string* err);
    // Tessellated patch (geometry/spline.h) through the same path.
    bool processPatch(const Memory& mem, const GeState& st, const PatchPacket& p, Geometry& out, std::string* err);
    // A fresh triangle/strip/fan PRIM drawn elsewhere (the GPU vertex path): keeps what a PRIM
    // type 7 continuation after it needs (geo::DrawFrontEnd::keepOpenVertices).
    void keepOpenVertices(const Memory& mem, const GeState& st, const PrimPacket& p) {
        frontEnd_.keepOpenVertices(mem, st, p);
    }
    // A patch drawn elsewhere (the GPU vertex path): ends any open PRIM.
    void endOpenPrim() { frontEnd_.endOpenPrim(); }
    geo::PatchSkip patchOffClipTest(const Memory& mem, const GeState& st, const PatchPacket& p) {
        return frontEnd_.offClipTest(mem, st, p);
    }
    // Every draw packet's dirty groups, first thing (geo::DrawFrontEnd::noteDirty).
    void noteDirty(u32 groups) { frontEnd_.noteDirty(groups); }
    // Immediate vertices, already in drawing coordinates; the AP2 flags of the packet override
    // the state (geo::immediateState, ge-rules.md §3.12).
    void processImmediate(const GeState& st, const ImmPacket& p, Geometry& out);
    // Exact interpolation: each GL triangle also carries the software rasteriser's setup
    // (Geometry::records, tri_setup.h).
    void setRecords(bool on) { records_ = on; }
    // After a process* call: whether every primary colour of its primitives that reaches a
    // fragment has alpha 255 (geo::DrawFrontEnd::drawAlphaFull).
    bool drawAlphaFull() const { return frontEnd_.drawAlphaFull(); }
    const geo::FrontEndStats& frontEndStats() const { return frontEnd_.stats(); }
    // Cumulative pixel bound of the primitives processed (Renderer::pixelWork, hle/ge_time.h),
    // plus, while the engine hands a pixel budget (a GE-time limit is set: dump replays), the
    // CPU side of the GL triangles built: kHostPixelsPerGlTriangle each.
    u64 pixelWork() const { return frontEnd_.pixelWork(); }
    void setPixelBudget(u64 pixels) { frontEnd_.setPixelBudget(pixels); }
    // GL triangles built on the CPU so far (one-pixel fragment quads count two), and the part of
    // pixelWork() charged for them.
    u64 glTriangles() const { return glTriangles_; }
    u64 hostPixels() const { return hostPixels_; }
    // What the GL backend builds on the CPU per triangle it hands to GL — transformed vertices,
    // bounds, in exact mode a 240-byte record of the rasteriser's setup — and what GL then does
    // with it cost the host far more per pixel than the software model's shading: a one-pixel
    // quad per line or point fragment in particular (measured on the 2-core build machine with
    // llvmpipe: about 1.5 µs per GL triangle against 0.1 µs per fragment shaded by the software
    // model). A GE-time budget that bounds the software model's work therefore does not bound
    // this: each GL triangle is charged 16 cycles (48 pixels at hle/ge_time.h's 1/3 cycle a
    // pixel), so the default budget (166.7 ms, 37 M cycles) buys at most 2.3 M of them, and the
    // frametests' frames pay a few milliseconds more (docs/timing.md).
    static constexpr u64 kHostPixelsPerGlTriangle = 48;
    // When a process* call's output reaches `triangles` GL triangles, `full(ctx)` is called; it
    // takes the geometry (draws or batches it) and empties the output, and the draw goes on. One
    // huge draw (a long line strip, a patch) then never holds all its CPU geometry at once.
    void setOutputLimit(size_t triangles, void (*full)(void*), void* ctx) {
        outLimit_ = triangles, outFull_ = full, outCtx_ = ctx;
    }

private:
    void primitive(const geo::Primitive& p) override;
    void emitTriangle(const geo::ScreenVertex& a, const geo::ScreenVertex& b, const geo::ScreenVertex& c,
                      const geo::ScreenVertex& prov, int joinPrev);
    void emitRect(const geo::ScreenVertex& v0, const geo::ScreenVertex& v1);
    void emitFragments(const geo::Fragment* f, size_t n);
    static void sinkFlush(void* ctx, const geo::Fragment* f, size_t n);
    // `n` more GL triangles are about to be added to the output: it is handed on first when they
    // would not fit (setOutputLimit), and they are charged (kHostPixelsPerGlTriangle).
    void emitting(u64 n) {
        if (outFull_ && out_->triangles() + n > outLimit_) outFull_(outCtx_);
        glTriangles_ += n;
        if (frontEnd_.budgeted()) {  // no GE-time limit (a host's own GE): not charged
            const u64 px = n * kHostPixelsPerGlTriangle;
            hostPixels_ += px;
            frontEnd_.charge(px);
        }
    }

    geo::DrawFrontEnd frontEnd_;
    bool records_ = false;
    Geometry* out_ = nullptr;  // during one process* call
    u64 glTriangles_ = 0, hostPixels_ = 0;
    size_t outLimit_ = ~size_t(0);
    void (*outFull_)(void*) = nullptr;
    void* outCtx_ = nullptr;
    std::vector<geo::Fragment> fragBuf_;
};

}  // namespace ge::gl
