// SPDX-License-Identifier: MIT
// Harness (g): Bezier and spline tessellation (geometry/spline.h): control-point counts, knot types,
// divisions, PPM triangles/lines/points, PFACE, every VTYPE (indices, morphing, weights, colours,
// normals generated for lighting), then the software model's transform of the output.
//
// Input: u8 flags (bit 0 spline, bits 1-2 PPM, bit 3 PFACE, bits 4-5 data placement), u8 ucount,
// u8 vcount, u8 knot types, u8 divU, u8 divV (7 bits each, as the engine reads CMD_DIVIDE), u16
// index-buffer offset, u32 VTYPE; up to 32 state words; then the control-point and index bytes.
// Control nets over 256 points are cut to that, and patches between 2^10 output vertices and the tessellator's own limit (2^21, refused before any
// work) get their divisions cut to fit 2^10 (the evaluation per vertex is the same whatever the count).
#include <cstdint>
#include <string>

#include "geometry/spline.h"
#include "geometry/transform.h"
#include "hle/ge_engine.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    fuzz::Bytes in(data, size);
    const u8 flags = in.u8v();
    PatchPacket p;
    p.spline = flags & 1;
    p.patchPrim = (flags >> 1) & 3;
    p.reverseFace = (flags >> 3) & 1;
    p.ucount = in.u8v();
    p.vcount = in.u8v();
    const u8 knots = in.u8v();
    p.uknot = knots & 3;
    p.vknot = (knots >> 2) & 3;
    p.divU = std::max<u32>(1, in.u8v() & 0x7F);
    p.divV = std::max<u32>(1, in.u8v() & 0x7F);
    const u32 indexOffset = in.u16v();
    p.vtype = in.u32v() & 0xFFFFFF;

    static Memory mem;
    static NullRenderer null;
    GeEngine eng(mem, &null);
    fuzz::applyStateWords(eng, in, 32);
    const u8* blob = nullptr;
    const u32 n = u32(in.take(fuzz::kMaxInput, blob));
    u32 base = 0;
    switch ((flags >> 4) & 3) {
    case 0: base = 0x08800000; break;
    case 1: base = Memory::kRamBase + mem.ramSize() - n; break;
    case 2: base = Memory::kVramBase; break;
    case 3: base = Memory::kVramBase + Memory::kVramSize - std::min<u32>(n, Memory::kVramSize); break;
    }
    const u32 stored = ((flags >> 4) & 3) >= 2 ? std::min<u32>(n, Memory::kVramSize) : n;
    if (stored) mem.write(base, blob, stored);
    p.vertexAddr = base;
    p.indexAddr = base + indexOffset;
    eng.execute((u32(GE_CMD_VTYPE) << 24) | p.vtype);
    const GeState& st = eng.state();
    p.state = &st;

    // Control nets of at most 256 points (up to 255 x 255 reads the same way, only longer).
    while (p.ucount * p.vcount > 256) {
        if (p.ucount >= p.vcount) p.ucount = (p.ucount + 1) / 2;
        else p.vcount = (p.vcount + 1) / 2;
    }
    // Cut the divisions until the output fits the harness's bound; patches over the tessellator's
    // own limit (2^21 vertices, refused before any work) are left as they are.
    auto outputVerts = [&] {
        const u64 pu = p.ucount < 4 ? 0 : (p.spline ? p.ucount - 3 : (p.ucount - 1) / 3);
        const u64 pv = p.vcount < 4 ? 0 : (p.spline ? p.vcount - 3 : (p.vcount - 1) / 3);
        return p.spline ? (pu * p.divU + 1) * (pv * p.divV + 1) : pu * pv * (p.divU + 1) * (p.divV + 1);
    };
    while (outputVerts() > (u64(1) << 10) && outputVerts() <= (u64(1) << 21) && (p.divU > 1 || p.divV > 1)) {
        if (p.divU >= p.divV) p.divU = (p.divU + 1) / 2;
        else p.divV = (p.divV + 1) / 2;
    }
    geo::TessOutput out;
    std::string err;
    u64 sum = 0;
    if (geo::tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out, &err)) {
        for (u32 i : out.indices)
            if (i >= out.verts.size()) __builtin_trap();  // an index outside the output
        const geo::TransformState ts = geo::makeTransformState(st, p.vtype, true, true);
        const size_t step = std::max<size_t>(1, out.verts.size() / 4096);
        for (size_t i = 0; i < out.verts.size(); i += step) {
            geo::ClipVertex cv;
            geo::transformVertex(ts, out.verts[i], cv);
            sum += u64(cv.sv.x) + u64(cv.sv.z);
        }
    }
    float w[4];
    geo::bezierWeights(float(p.divU) / float(p.divV), w);
    std::vector<float> kv;
    geo::splineKnots(int(p.ucount), int(p.uknot), kv);
    sum += out.verts.size() + kv.size();
    if (stored) mem.fill(base, 0, stored);
    volatile u64 sink = sum;
    (void)sink;
    return 0;
}
