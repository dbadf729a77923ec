// SPDX-License-Identifier: MIT
// The draw front end both backends run (see draw_front_end.h).
#include "geometry/draw_front_end.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/clip.h"
#include "geometry/spline.h"
#include "geometry/texture_size.h"

namespace ge::geo {

namespace {

// Whether no point of a patch's surface can reach the clip rectangle, judged from its control
// points. The Bernstein (manual §5.1) and cubic B-spline (manual §5.2; splineBasis, the
// reference's quirk included) weights are non-negative and sum to one, so every tessellated
// position is a convex combination of the control positions, in model space and, the transform
// being affine, in clip space. A linear inequality in clip coordinates that holds at every
// control point holds over their hull: W > 0, and the projected x (or y) beyond one side of the
// rectangle, multiplied out by W (sx·x + (tx − offset − edge)·W > 0). Near clipping only cuts the
// triangles within it. The test asks 2 pixels beyond the side, and a margin of 1e-4 of the
// products' magnitudes for the float rounding of tessellation and transform (a few 1e-7 of them).
// A patch it culls would have drawn nothing: this only saves its tessellation, transform and
// assembly (Pursuit Force: 497 of a frame's 1,035 patches). Matrices with exponent-255 elements
// (the GE's own term rule) are not judged.
bool patchOffClip(const TransformState& ts, const RasterParams& rp, const std::vector<DecodedVertex>& cps) {
    constexpr double kPixels = 2.0, kRel = 1e-4;
    // The four sides: beyond when a·(x or y) + b·W > 0 (W = 1 in through mode).
    const double ox = ts.through ? 0.0 : ts.tx - ts.offX16 / 16.0, oy = ts.through ? 0.0 : ts.ty - ts.offY16 / 16.0;
    const double sx = ts.through ? 1.0 : ts.sx, sy = ts.through ? 1.0 : ts.sy;
    const double a[4] = {sx, -sx, sy, -sy};
    const double b[4] = {ox - (rp.clipX2 + 1 + kPixels), -(ox - (rp.clipX1 - kPixels)), oy - (rp.clipY2 + 1 + kPixels),
                         -(oy - (rp.clipY1 - kPixels))};
    double lo[4], mag[4] = {}, wLo = std::numeric_limits<double>::infinity(), wMag = 0.0;
    std::fill(lo, lo + 4, std::numeric_limits<double>::infinity());
    const MatrixColumns& C = ts.clipCols;
    const MatrixColumns& W = ts.worldCols;
    if (!ts.through && (C.special || (ts.worldToClip && W.special) || (!ts.combinedClip && !ts.worldToClip)))
        return false;
    for (const DecodedVertex& cp : cps) {
        double c[4], m[4];  // clip x, y, -, W and bounds on the magnitudes of their terms
        if (ts.through) {
            c[0] = cp.pos[0], c[1] = cp.pos[1], c[3] = 1.0;
            m[0] = std::fabs(c[0]), m[1] = std::fabs(c[1]), m[3] = 1.0;
        } else {
            double q[3], qm[3];
            for (int k = 0; k < 3; ++k) q[k] = cp.pos[k], qm[k] = std::fabs(q[k]);
            if (ts.worldToClip) {
                double wq[3], wm[3];
                for (int r = 0; r < 3; ++r) {
                    wq[r] = W.col[3][r], wm[r] = std::fabs(W.col[3][r]);
                    for (int k = 0; k < 3; ++k) wq[r] += W.col[k][r] * q[k], wm[r] += std::fabs(W.col[k][r]) * qm[k];
                }
                std::copy(wq, wq + 3, q), std::copy(wm, wm + 3, qm);
            }
            for (int r : {0, 1, 3}) {
                c[r] = C.col[3][r], m[r] = std::fabs(C.col[3][r]);
                for (int k = 0; k < 3; ++k) c[r] += C.col[k][r] * q[k], m[r] += std::fabs(C.col[k][r]) * qm[k];
            }
        }
        for (int s = 0; s < 4; ++s) {
            const int r = s < 2 ? 0 : 1;
            const double g = a[s] * c[r] + b[s] * c[3];
            if (!(g >= lo[s])) lo[s] = g;  // a NaN stays (no comparison holds for it)
            mag[s] = std::max(mag[s], std::fabs(a[s]) * m[r] + std::fabs(b[s]) * m[3]);
        }
        if (!(c[3] >= wLo)) wLo = c[3];
        wMag = std::max(wMag, m[3]);
    }
    if (!(wLo > kRel * wMag)) return false;
    for (int s = 0; s < 4; ++s)
        if (lo[s] > kRel * mag[s]) return true;
    return false;
}

}  // namespace

RasterParams rasterParamsFor(const GeState& st, bool through, bool rectangles, const AccuracyProfile& acc) {
    RasterParams rp;
    // Scissor ∩ REGION2 (docs/ge-rules.md §8.6; REGION1 is kept 0 by games).
    rp.clipX1 = int(st.SCISSOR1_x());
    rp.clipY1 = int(st.SCISSOR1_y());
    rp.clipX2 = int(std::min(st.SCISSOR2_x(), st.REGION2_x()));
    rp.clipY2 = int(std::min(st.SCISSOR2_y(), st.REGION2_y()));
    // Clear mode draws flat: colour from the provoking vertex (PPSSPP's software renderer).
    rp.gouraud = st.SHADE_gouraud() && !st.isClearMode();
    rp.textured = st.TME_on() && !st.isClearMode();
    const u32 levelMode = st.TLEVEL_mode();
    rp.needLod = rp.textured && levelMode == 0;
    rp.needW = rp.textured && levelMode == 2;
    rp.fog = !through && st.FGE_on();
    rp.through = through;
    rp.sprite = rectangles && acc.spriteFarEdgeExcluded;
    rp.zeroAreaTriangles = acc.zeroAreaTriangles;
    rp.sampleCentre = acc.pspTriangleSampleCentre;
    rp.colourGradients = acc.pspColourGradients;
    rp.lineCentres = acc.pspLineCentres;
    rp.texW0 = float(texCoordWidth(st, 0));  // unclamped 2^n (texture_size.h)
    rp.texH0 = float(texCoordHeight(st, 0));
    return rp;
}

GeState immediateState(const GeState& st, u32 f) {
    GeState s = st;
    auto setFlag = [&](GeCmd op, bool on) { s.regs[op] = (u32(op) << 24) | (on ? 1u : 0u); };
    setFlag(GE_CMD_AAE, (f >> 11) & 1);
    setFlag(GE_CMD_SHADE, (f >> 18) & 1);
    setFlag(GE_CMD_BCE, (f >> 19) & 1);
    setFlag(GE_CMD_CULL, (f >> 20) & 1);
    setFlag(GE_CMD_TME, (f >> 21) & 1);
    setFlag(GE_CMD_FGE, (f >> 22) & 1);
    setFlag(GE_CMD_DTE, (f >> 23) & 1);
    return s;
}

void DrawFrontEnd::begin(const GeState& st, const RasterParams& rp, PrimitiveSink& sink) {
    sink_ = &sink;
    rp_ = rp;
    // Back-face culling (docs/ge-rules.md §3.6), never in clear mode.
    cull_ = st.BCE_on() && !st.isClearMode();
    cullClockwise_ = !st.CULL_ccw();
    alphaFull_ = true;
    joinable_ = false;
}

bool DrawFrontEnd::prim(const Memory& mem, const GeState& st, const PrimPacket& p, PrimitiveSink& sink,
                        std::string* err) {
    if (!p.continuation) {
        pending_.clear();
        stripOdd_ = false;
    }
    if (!decode(mem, st, p)) {
        ++stats_.badDraws;
        pending_.clear();
        if (err) *err = "unreadable index data";
        return false;
    }
    begin(st, rasterParamsFor(st, ts_.through, p.prim == GE_PRIM_RECTANGLES, acc_), sink);
    rectDetect_ = RectDetect::fromState(st, ts_.through, st.TME_on(), pending_.empty());
    assemble(p.prim, true);
    rectDetect_.allowed = false;
    return true;
}

// Decodes the vertices a draw uses (each distinct one once) into cverts_ after the open ones of a
// continued PRIM, and the draw order (those first) into seq_. False on unreadable index data.
bool DrawFrontEnd::decode(const Memory& mem, const GeState& st, const PrimPacket& p) {
    VertexReader reader(mem, st, p.vtype);
    setTransform(st, p.vtype, reader.hasColor(), /*hasNormal: the format's or the latched one*/ true);
    ts_.sprite = p.prim == GE_PRIM_RECTANGLES && acc_.pspSpritePosition;
    cverts_.assign(pending_.begin(), pending_.end());
    seq_.clear();
    for (u32 i = 0; i < pending_.size(); ++i) seq_.push_back(i);
    if (!reader.readIndices(p.indexAddr, p.count, indices_)) return false;
    if (indices_.empty()) return true;
    const bool skin = reader.hasWeights() && !reader.through();
    bool anyBad = false;
    u32 lo = ~0u, hi = 0;
    for (u32 i : indices_) lo = std::min(lo, i), hi = std::max(hi, i);
    // The dense range's bytes checked and looked up once (VertexReader::span); a range that is
    // not all valid memory is read vertex by vertex, which finds the unreadable ones.
    const u8* range = nullptr;
    auto process = [&](u32 index, ClipVertex& out) {
        DecodedVertex dv;
        bool ok = true;
        if (range) reader.decodeAt(range + size_t(index - lo) * reader.stride(), dv);
        else ok = reader.read(p.vertexAddr, index, dv);
        anyBad |= !ok;
        if (ok && skin) applySkinning(st, p.vtype, dv);
        transformVertex(ts_, dv, out);
        out.valid = ok && reader.hasPosition();  // no position: dropped (docs/ge-rules.md §8.11)
    };
    const size_t first = cverts_.size();
    if (u64(hi) - lo < u64(p.count) * 2 + 64) {
        // Dense index range: each vertex of the range that is used, transformed once.
        range = reader.span(p.vertexAddr, lo, hi - lo + 1);
        used_.assign(size_t(hi - lo) + 1, 0);
        for (u32 i : indices_) used_[i - lo] = 1;
        cverts_.resize(first + used_.size());
        for (size_t k = 0; k < used_.size(); ++k)
            if (used_[k]) process(lo + u32(k), cverts_[first + k]), ++stats_.vertices;
        for (u32 i : indices_) seq_.push_back(u32(first + (i - lo)));
    } else {
        cverts_.resize(first + indices_.size());
        for (size_t k = 0; k < indices_.size(); ++k) {
            process(indices_[k], cverts_[first + k]);
            seq_.push_back(u32(first + k));
        }
        stats_.vertices += indices_.size();
    }
    if (anyBad) ++stats_.badDraws;  // drawn without the unreadable vertices
    return true;
}

bool DrawFrontEnd::patch(const Memory& mem, const GeState& st, const PatchPacket& p, PrimitiveSink& sink,
                         std::string* err) {
    pending_.clear();
    stripOdd_ = false;
    TessOutput& tess = tess_;
    if (!tessellatePatch(mem, st, p, acc_, tess, err, offClipTest(mem, st, p))) {
        ++stats_.badDraws;
        return false;
    }
    if (tess.verts.empty()) return true;
    cverts_.resize(tess.verts.size());
    for (size_t i = 0; i < tess.verts.size(); ++i) {
        transformVertex(ts_, tess.verts[i], cverts_[i]);
        cverts_[i].valid = true;
    }
    stats_.vertices += tess.verts.size();
    // The tessellator's indices, each checked against its vertices (written in place, not pushed:
    // a patch has thousands).
    seq_.resize(tess.indices.size());
    size_t kept = 0;
    for (u32 i : tess.indices) {
        seq_[kept] = i;
        kept += i < tess.verts.size();
    }
    seq_.resize(kept);
    // Patch culling (CMD_PCE, manual §11.2) removes patches outside the drawing region; the clip
    // rectangle already includes REGION2, so those pixels are never drawn either way.
    begin(st, rasterParamsFor(st, ts_.through, false, acc_), sink);
    rectDetect_.allowed = false;
    assemble(tess.prim, false);
    stripOdd_ = false;
    trimVertices();
    // A patch's tessellation can be far larger than any PRIM: its arrays are not kept past it.
    constexpr size_t kKeepTessVertices = size_t(1) << 17;
    if (tess.verts.capacity() > kKeepTessVertices) tess = TessOutput{};
    return true;
}

PatchSkip DrawFrontEnd::offClipTest(const Memory& mem, const GeState& st, const PatchPacket& p) {
    const VertexReader probe(mem, st, p.vtype);
    // The tessellator generates normals when lighting needs them (docs/ge-rules.md §3.2).
    setTransform(st, p.vtype, probe.hasColor(), probe.hasNormal() || st.LTE_on());
    return [this, rp = rasterParamsFor(st, ts_.through, false, acc_)](const std::vector<DecodedVertex>& cps) {
        const bool off = patchOffClip(ts_, rp, cps);
        stats_.culledPatches += off;
        return off;
    };
}

void DrawFrontEnd::immediate(const GeState& st, const ImmPacket& p, PrimitiveSink& sink) {
    // Immediate vertices are already in drawing coordinates: no transform, lighting or clipping.
    ts_ = TransformState{};
    ts_.through = true;
    tsState_ = nullptr;  // ts_ no longer holds setTransform's result
    immediateVertices(st, p.vertices, cverts_, seq_);
    RasterParams rp = rasterParamsFor(st, true, false, acc_);
    rp.fog = st.FGE_on() && !st.isThrough();
    begin(st, rp, sink);
    rectDetect_.allowed = false;
    // The primitive stands alone: it neither continues nor leaves open a PRIM's strip.
    const bool odd = stripOdd_;
    stripOdd_ = false;
    assemble(p.prim, false);
    stripOdd_ = odd;
}

void DrawFrontEnd::keepOpenVertices(const Memory& mem, const GeState& st, const PrimPacket& p) {
    pending_.clear();
    stripOdd_ = false;
    VertexReader reader(mem, st, p.vtype);
    if (!reader.readIndices(p.indexAddr, p.count, indices_)) return;
    const size_t n = indices_.size();
    // assemblePrimitives' `keep` for a fresh PRIM without rectangle detection (GPU draws never
    // have it): list leftovers, the strip's last two (parity flipped per triangle), the fan's
    // centre and last vertex.
    size_t open[2];
    size_t count = 0;
    switch (p.prim) {
        case GE_PRIM_TRIANGLES:
            for (size_t i = n - n % 3; i < n; ++i) open[count++] = i;
            break;
        case GE_PRIM_TRIANGLE_STRIP:
            for (size_t i = n > 2 ? n - 2 : 0; i < n; ++i) open[count++] = i;
            stripOdd_ = n > 2 && ((n - 2) & 1);
            break;
        case GE_PRIM_TRIANGLE_FAN:
            if (n >= 1) open[count++] = 0;
            if (n >= 2) open[count++] = n - 1;
            break;
        default: return;
    }
    setTransform(st, p.vtype, reader.hasColor(), /*hasNormal: the format's or the latched one*/ true);
    const bool skin = reader.hasWeights() && !reader.through();
    for (size_t k = 0; k < count; ++k) {
        DecodedVertex dv;
        ClipVertex cv;
        const bool ok = reader.read(p.vertexAddr, indices_[open[k]], dv);
        if (ok && skin) applySkinning(st, p.vtype, dv);
        transformVertex(ts_, dv, cv);
        cv.valid = ok && reader.hasPosition();
        pending_.push_back(cv);
    }
}

void DrawFrontEnd::setTransform(const GeState& st, u32 vtype, bool hasColor, bool hasNormal) {
    // What makeTransformState reads: VTYPE and the morph weights (VERTEX), the matrices, viewport,
    // offsets, CLE, UV scale, TMAP, TSHADE and fog parameters (TRANSFORM), lights, material and
    // NREV (LIGHTING), the level-0 texture size (TEXTURE), FGE (FRAGMENT).
    constexpr u32 kReads = DIRTY_VERTEX | DIRTY_TRANSFORM | DIRTY_LIGHTING | DIRTY_TEXTURE | DIRTY_FRAGMENT;
    const u32 key = (vtype & 0xFFFFFF) | u32(hasColor) << 24 | u32(hasNormal) << 25;
    if ((dirty_ & kReads) || key != tsKey_ || &st != tsState_) {
        ts_ = makeTransformState(st, vtype, hasColor, hasNormal, &fold_, acc_);
        tsKey_ = key;
        tsState_ = &st;
        dirty_ = 0;
    }
    ts_.sprite = false;  // the caller sets it for rectangles
}

// Assembles seq_ as `prim` (assembly.h); what does not complete a primitive, and the strip/fan
// state, is kept in pending_ for PRIM type 7 (docs/ge-rules.md §3.2, §8.11).
void DrawFrontEnd::assemble(GePrimType prim, bool keepPending) {
    assemblePrimitives(prim, seq_, rectDetect_.allowed && !cull_, stripOdd_, *this, keep_);
    if (keepPending) {
        pending_.clear();
        for (u32 k : keep_) pending_.push_back(cverts_[k]);
    }
}

void DrawFrontEnd::trimVertices() {
    // A PRIM has at most 65,535 vertices; a patch's tessellation can have far more.
    constexpr size_t kKeep = size_t(1) << 17;
    if (cverts_.capacity() > kKeep) std::vector<ClipVertex>().swap(cverts_);
    if (seq_.capacity() > kKeep) std::vector<u32>().swap(seq_);
}

// CULL = 0 culls triangles clockwise on screen (y down), 1 counter-clockwise ones (docs/ge-rules.md
// §3.6). Zero-area triangles are never culled: the rasteriser draws the samples they pass through
// as the reference does (raster.cpp rasterZeroAreaTriangle).
bool DrawFrontEnd::culled(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) const {
    const s64 area = s64(b.x - a.x) * (c.y - a.y) - s64(b.y - a.y) * (c.x - a.x);
    if (!cull_ || area == 0) return false;
    return cullClockwise_ ? area > 0 : area < 0;
}

void DrawFrontEnd::emit(PrimKind kind, const ScreenVertex* a, const ScreenVertex* b, const ScreenVertex* c,
                        const ScreenVertex* prov, const s32 ids[4], int joinPrev) {
    Primitive p;
    p.kind = kind;
    p.v[0] = a, p.v[1] = b, p.v[2] = c;
    p.prov = prov;
    p.id[0] = ids[0], p.id[1] = ids[1], p.id[2] = ids[2], p.provId = ids[3];
    // A piece joins the previous one only when that one was drawn.
    p.joinPrev = joinPrev && joinable_ ? 1 : 0;
    joinable_ = false;
    if (!primitiveRows(rp_, kind, p.v, p.y1, p.y2)) {  // no pixel row of the clip rectangle
        p.inside = false;
        joinable_ = true;
        sink_->primitive(p);
        return;
    }
    const u64 bound = primitivePixelBound(rp_, kind, p.v, p.y1, p.y2);
    if (bound > pixelBudgetLeft_) {  // the GE-time limit reached into this draw: dropped,
        pixelBudgetLeft_ = 0;        // but charged, so the engine sees the limit passed
        pixelWork_ += bound;
        ++stats_.budgetDropped;
        return;
    }
    pixelBudgetLeft_ -= bound;
    pixelWork_ += bound;
    if (alphaFull_) {
        const bool perVertex = rp_.gouraud && kind != PrimKind::Rect;
        if (prov->color[3] != 255) alphaFull_ = false;
        if (perVertex && (a->color[3] != 255 || b->color[3] != 255 || c->color[3] != 255)) alphaFull_ = false;
    }
    ++stats_.primitives;
    joinable_ = true;
    sink_->primitive(p);
}

// A triangle in primitive order; the third vertex is the provoking one (docs/ge-rules.md §8.1).
// `ring`, when given, is the order the vertices are handed to the rasteriser in (the reference's
// float attribute sums depend on it, assembly.h); (ia, ib, ic) is the winding order used for
// culling and clipping.
void DrawFrontEnd::triangle(u32 ia, u32 ib, u32 ic, const u32* ring) {
    const ClipVertex& a = cverts_[ia];
    const ClipVertex& b = cverts_[ib];
    const ClipVertex& c = cverts_[ic];
    const ClipVertex* v[3] = {&a, &b, &c};
    if (!a.valid || !b.valid || !c.valid || discardPrimitive(ts_, v, 3)) {
        ++stats_.discarded;
        return;
    }
    if (!ts_.through) {
        if (a.clip[3] < 0.0f && b.clip[3] < 0.0f && c.clip[3] < 0.0f) {  // docs/ge-rules.md §8.5
            ++stats_.discarded;
            return;
        }
        // Near clipping whatever CLE says: CLE selects only the depth clamp and the discard rule
        // (docs/ge-rules.md §8.5; PPSSPP Clipper::ProcessTriangle).
        if (beyondNear(a) || beyondNear(b) || beyondNear(c)) {
            clippedTriangle(ia, ib, ic, ring);
            return;
        }
    }
    if (culled(a.sv, b.sv, c.sv)) {
        ++stats_.culled;
        return;
    }
    const s32 provId = s32(ic);
    if (ring) {
        const s32 ids[4] = {s32(ring[0]), s32(ring[1]), s32(ring[2]), provId};
        emit(PrimKind::Triangle, &cverts_[ring[0]].sv, &cverts_[ring[1]].sv, &cverts_[ring[2]].sv, &c.sv, ids, 0);
    } else {
        const s32 ids[4] = {s32(ia), s32(ib), provId, provId};
        emit(PrimKind::Triangle, &a.sv, &b.sv, &c.sv, &c.sv, ids, 0);
    }
}

// A triangle reaching beyond the near plane, clipped in the reference's vertex order (the
// strip/fan ring, clip.h) into a convex polygon drawn as a fan.
void DrawFrontEnd::clippedTriangle(u32 ia, u32 ib, u32 ic, const u32* ring) {
    const bool reversed = ring && ringReversed(ring, ia, ib);
    ClipVertex poly[4];
    const int n = ring ? clipTriangleNear(ts_, cverts_[ring[0]], cverts_[ring[1]], cverts_[ring[2]], poly)
                       : clipTriangleNear(ts_, cverts_[ia], cverts_[ib], cverts_[ic], poly);
    ++stats_.clipped;
    // Flat shading keeps the original provoking vertex's colour.
    const s32 ids[4] = {-1, -1, -1, s32(ic)};
    int join = 0;
    for (int k = 1; k + 1 < n; ++k) {
        const int k1 = reversed ? k + 1 : k, k2 = reversed ? k : k + 1;  // the primitive's winding
        if (culled(poly[0].sv, poly[k1].sv, poly[k2].sv)) {
            ++stats_.culled;
            continue;
        }
        emit(PrimKind::Triangle, &poly[0].sv, &poly[k].sv, &poly[k + 1].sv, &cverts_[ic].sv, ids, join);
        join = 1;
    }
}

void DrawFrontEnd::line(u32 ia, u32 ib) {
    const ClipVertex* v[2] = {&cverts_[ia], &cverts_[ib]};
    if (!v[0]->valid || !v[1]->valid || discardPrimitive(ts_, v, 2)) {
        ++stats_.discarded;
        return;
    }
    if (!ts_.through && (beyondNear(*v[0]) || beyondNear(*v[1]))) {  // whatever CLE says (docs/ge-rules.md §8.5)
        ClipVertex a = *v[0], b = *v[1];
        ++stats_.clipped;
        if (!clipLineNear(ts_, a, b)) return;
        const s32 ids[4] = {-1, -1, -1, -1};
        emit(PrimKind::Line, &a.sv, &b.sv, &b.sv, &b.sv, ids, 0);
        return;
    }
    const s32 ids[4] = {s32(ia), s32(ib), s32(ib), s32(ib)};
    emit(PrimKind::Line, &v[0]->sv, &v[1]->sv, &v[1]->sv, &v[1]->sv, ids, 0);
}

void DrawFrontEnd::point(u32 ia) {
    const ClipVertex* v[1] = {&cverts_[ia]};
    if (!v[0]->valid || discardPrimitive(ts_, v, 1)) {
        ++stats_.discarded;
        return;
    }
    const s32 ids[4] = {s32(ia), s32(ia), s32(ia), s32(ia)};
    emit(PrimKind::Point, &v[0]->sv, &v[0]->sv, &v[0]->sv, &v[0]->sv, ids, 0);
}

void DrawFrontEnd::rectangle(u32 ia, u32 ib) {
    const ClipVertex* v[2] = {&cverts_[ia], &cverts_[ib]};
    if (!v[0]->valid || !v[1]->valid || discardPrimitive(ts_, v, 2)) {
        ++stats_.discarded;
        return;
    }
    if (ts_.rectAsTriangles) {
        rectangleAsTriangles(v[0]->sv, v[1]->sv);
        return;
    }
    const s32 ids[4] = {s32(ia), s32(ib), s32(ib), s32(ib)};
    emit(PrimKind::Rect, &v[0]->sv, &v[1]->sv, &v[1]->sv, &v[1]->sv, ids, 0);
}

// Rectangles with texture projection are drawn as two triangles (docs/ge-rules.md §8.2), corners
// textured by the orientation table, colour/Z/fog of the second vertex.
void DrawFrontEnd::rectangleAsTriangles(const ScreenVertex& v0, const ScreenVertex& v1) {
    if (v0.x == v1.x || v0.y == v1.y) return;
    const ScreenVertex tl = rectangleCorner(v0, v1, 0, 0), tr = rectangleCorner(v0, v1, 1, 0);
    const ScreenVertex bl = rectangleCorner(v0, v1, 0, 1), br = rectangleCorner(v0, v1, 1, 1);
    const s32 ids[4] = {-1, -1, -1, -1};
    emit(PrimKind::Triangle, &tl, &tr, &bl, &bl, ids, 0);
    emit(PrimKind::Triangle, &tr, &br, &bl, &bl, ids, 1);
}

// Strip/fan quads drawn as rectangles (assembly.h): `tl`/`br` get the top-left and bottom-right
// vertices (the rectangle's v0 and v1).
bool DrawFrontEnd::quadAsRect(bool fan, const u32 q[4], u32& tl, u32& br) const {
    const ClipVertex* d[4] = {&cverts_[q[0]], &cverts_[q[1]], &cverts_[q[2]], &cverts_[q[3]]};
    int itl = 0, ibr = 0;
    if (!(fan ? fanQuadAsRect(rectDetect_, d, itl, ibr) : stripQuadAsRect(rectDetect_, d, itl, ibr))) return false;
    tl = q[itl], br = q[ibr];
    return true;
}

}  // namespace ge::geo
