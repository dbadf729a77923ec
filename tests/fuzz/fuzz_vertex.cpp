// SPDX-License-Identifier: MIT
// Harness (f): vertex decoding (every VTYPE: formats, morphing, skinning, indices), the shared
// geometry (geometry/): transform, lighting and texture-coordinate generation, near clipping and
// the discard rules, primitive assembly and the rasteriser's row bounds; BBOX; and, where the GL translator
// is built, its CPU vertex pipeline over the same draw (no GL context needed).
//
// Input: u32 VTYPE, u16 count (cut to 512), u8 primitive, u8 flags (bits 0-1 data placement as in
// the texture harness, bit 2 a BBOX over the vertices), u32 index-buffer offset into the data,
// u32 two interpolation parameters for lerpVertex (as floats); up to 64 state words (matrices,
// viewport, lights, …); then the vertex and index bytes.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/assembly.h"
#include "geometry/clip.h"
#include "geometry/raster.h"
#include "geometry/transform.h"
#include "hle/ge_engine.h"
#include "hle/vertex_decoder.h"
#include "tests/fuzz/fuzz_common.h"
#ifdef GE2GL_HAVE_GL
#include "translator/vertex_pipeline.h"
#endif

using namespace ge;
using namespace ge::geo;

namespace {

u32 cmd(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

// assemblePrimitives' sink: clips and bounds every primitive as the software model does.
struct ClipSink {
    const TransformState& ts;
    const RasterParams& rp;
    std::vector<ClipVertex>& v;
    float t;
    u64 sum = 0;

    void bound(PrimKind kind, const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
        const ScreenVertex* sv[3] = {&a, &b, &c};
        int y1 = 0, y2 = 0;
        if (primitiveRows(rp, kind, sv, y1, y2)) sum += u64(y2 - y1);
    }
    void point(u32 i) {
        const ClipVertex* p[1] = {&v[i]};
        if (!ts.through && discardPrimitive(ts, p, 1)) return;
        bound(PrimKind::Point, v[i].sv, v[i].sv, v[i].sv);
    }
    void line(u32 i, u32 j) {
        const ClipVertex* p[2] = {&v[i], &v[j]};
        if (!ts.through && discardPrimitive(ts, p, 2)) return;
        ClipVertex a = v[i], b = v[j];
        if (!ts.through && (beyondNear(a) || beyondNear(b)) && !clipLineNear(ts, a, b)) return;
        ClipVertex m;
        lerpVertex(ts, a, b, t, m);
        sum += u64(depthSide(m) + 1);
        bound(PrimKind::Line, a.sv, b.sv, b.sv);
    }
    void rectangle(u32 i, u32 j) {
        const ClipVertex* p[2] = {&v[i], &v[j]};
        if (!ts.through && discardPrimitive(ts, p, 2)) return;
        for (int fx = 0; fx < 2; ++fx)
            for (int fy = 0; fy < 2; ++fy) sum += u64(rectangleCorner(v[i].sv, v[j].sv, fx, fy).x);
        bound(PrimKind::Rect, v[i].sv, v[j].sv, v[j].sv);
    }
    void triangle(u32 a, u32 b, u32 c, const u32* ring) {
        const ClipVertex* p[3] = {&v[a], &v[b], &v[c]};
        if (!ts.through && discardPrimitive(ts, p, 3)) return;
        if (!ts.through && (beyondNear(v[a]) || beyondNear(v[b]) || beyondNear(v[c]))) {
            ClipVertex poly[4];
            const int n = ring ? clipTriangleNear(ts, v[ring[0]], v[ring[1]], v[ring[2]], poly)
                               : clipTriangleNear(ts, v[a], v[b], v[c], poly);
            if (ring) sum += ringReversed(ring, a, b);
            for (int k = 1; k + 1 < n; ++k) bound(PrimKind::Triangle, poly[0].sv, poly[k].sv, poly[k + 1].sv);
            return;
        }
        bound(PrimKind::Triangle, v[a].sv, v[b].sv, v[c].sv);
    }
    bool quadAsRect(bool fan, const u32 q[4], u32& tl, u32& br) {
        RectDetect rd;
        rd.allowed = true;
        rd.through = ts.through;
        const ClipVertex* d[4] = {&v[q[0]], &v[q[1]], &v[q[2]], &v[q[3]]};
        int itl = 0, ibr = 0;
        if (!(fan ? fanQuadAsRect(rd, d, itl, ibr) : stripQuadAsRect(rd, d, itl, ibr))) return false;
        tl = q[itl], br = q[ibr];
        return true;
    }
};

float floatOf(u32 bits) {
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    fuzz::Bytes in(data, size);
    const u32 vtype = in.u32v() & 0xFFFFFF;
    const u32 count = std::min<u32>(in.u16v(), 512);
    const GePrimType prim = GePrimType(in.u8v() & 7);
    const u8 flags = in.u8v();
    const u32 indexOffset = in.u32v();
    const float t = floatOf(in.u32v());

    static Memory mem;
    static NullRenderer null;
    GeEngine eng(mem, &null);
    fuzz::applyStateWords(eng, in, 64);

    const u8* blob = nullptr;
    const u32 n = u32(in.take(fuzz::kMaxInput, blob));
    u32 base = 0;
    switch (flags & 3) {
    case 0: base = 0x08800000; break;
    case 1: base = Memory::kRamBase + mem.ramSize() - n; break;
    case 2: base = Memory::kVramBase; break;
    case 3: base = Memory::kVramBase + Memory::kVramSize - std::min<u32>(n, Memory::kVramSize); break;
    }
    const u32 stored = (flags & 3) >= 2 ? std::min<u32>(n, Memory::kVramSize) : n;
    if (stored) mem.write(base, blob, stored);
    const u32 iaddr = base + (indexOffset % (n + 64));

    eng.execute(cmd(GE_CMD_VTYPE, vtype));
    const GeState& st = eng.state();
    u64 sum = 0;
    if (prim != GE_PRIM_KEEP_PREVIOUS) {
        VertexReader reader(mem, st, vtype);
        sum += reader.stride() + reader.morphCount() + reader.weightCount() + reader.indexSize();
        std::vector<DecodedVertex> dv;
        std::string err;
        decodeDrawVertices(mem, st, vtype, base, iaddr, count, dv, &err);
        const TransformState ts = makeTransformState(st, vtype, reader.hasColor(), reader.hasNormal());
        std::vector<ClipVertex> cv(dv.size());
        std::vector<u32> seq(dv.size());
        for (size_t i = 0; i < dv.size(); ++i) {
            transformVertex(ts, dv[i], cv[i]);
            seq[i] = u32(i);
        }
        RasterParams rp;
        rp.clipX1 = int(st.SCISSOR1_x()), rp.clipY1 = int(st.SCISSOR1_y());
        rp.clipX2 = int(std::min(st.SCISSOR2_x(), st.REGION2_x()));
        rp.clipY2 = int(std::min(st.SCISSOR2_y(), st.REGION2_y()));
        ClipSink sink{ts, rp, cv, t};
        bool stripOdd = (flags >> 3) & 1;
        std::vector<u32> keep;
        assemblePrimitives(prim, seq, (flags >> 4) & 1, stripOdd, sink, keep);
        sum += sink.sum + keep.size();
#ifdef GE2GL_HAVE_GL
        // The GL translator's vertex pipeline, twice: the second as a PRIM type 7 continuation.
        gl::VertexPipeline pipeline{geo::AccuracyProfile::ppsspp()};
        pipeline.setRecords((flags >> 5) & 1);
        PrimPacket p;
        p.state = &st;
        p.prim = prim;
        p.count = count;
        p.vtype = vtype;
        p.vertexAddr = base;
        p.indexAddr = iaddr;
        if (count) {
            gl::Geometry geo;
            pipeline.processPrim(mem, st, p, geo, &err);
            p.continuation = true;
            pipeline.processPrim(mem, st, p, geo, &err);
            sum += geo.tris.size() + geo.records.size();
        }
#endif
    }
    if ((flags >> 2) & 1) {
        // BBOX over the same vertices (the engine reads them from the vertex address).
        eng.execute(cmd(GE_CMD_BASE, (base >> 8) & 0xFF0000));
        eng.execute(cmd(GE_CMD_VADR, base & 0xFFFFFF));
        eng.execute(cmd(GE_CMD_BBOX, count));
        sum += eng.list().bflg;
    }
    if (stored) mem.fill(base, 0, stored);
    volatile u64 sink = sum;
    (void)sink;
    return 0;
}
