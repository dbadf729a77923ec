// SPDX-License-Identifier: MIT
// Patch tessellation (manual §5; docs/ge-rules.md §3.2). Expected values from the Bernstein and
// B-spline definitions of the manual, computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/spline.h"

using namespace ge;
using namespace ge::geo;

namespace {

constexpr u32 kV = 0x08200000;

void set(GeState& st, u8 op, u32 arg) { st.regs[op] = (u32(op) << 24) | (arg & 0xFFFFFF); }
void writeF(Memory& mem, u32 addr, float f) {
    u32 bits;
    std::memcpy(&bits, &f, 4);
    mem.write32(addr, bits);
}

constexpr u32 kFloatPos = 3u << 7;             // VT float, 12 bytes
constexpr u32 kColPos = (7u << 2) | (3u << 7); // 8888 colour + float XYZ, 16 bytes

// Control points on a grid: P(u, v) = (u, v, z(u, v)).
void writeGrid(Memory& mem, u32 nu, u32 nv, float (*z)(u32, u32)) {
    for (u32 v = 0; v < nv; ++v)
        for (u32 u = 0; u < nu; ++u) {
            const u32 a = kV + 12 * (v * nu + u);
            writeF(mem, a, float(u));
            writeF(mem, a + 4, float(v));
            writeF(mem, a + 8, z(u, v));
        }
}
float flat(u32, u32) { return 0.0f; }
float bumpy(u32 u, u32 v) { return float((u * 7 + v * 3) % 5); }

PatchPacket patch(bool spline, u32 nu, u32 nv, u32 div, u32 vtype = kFloatPos) {
    PatchPacket p;
    p.spline = spline;
    p.ucount = nu;
    p.vcount = nv;
    p.divU = p.divV = div;
    p.vtype = vtype;
    p.vertexAddr = kV;
    return p;
}

TEST(Spline, BezierWeights) {
    float w[4];
    bezierWeights(0.0f, w);
    EXPECT_EQ(w[0], 1.0f);
    EXPECT_EQ(w[1], 0.0f);
    EXPECT_EQ(w[2], 0.0f);
    EXPECT_EQ(w[3], 0.0f);
    bezierWeights(0.5f, w);  // 1/8, 3/8, 3/8, 1/8
    EXPECT_EQ(w[0], 0.125f);
    EXPECT_EQ(w[1], 0.375f);
    EXPECT_EQ(w[2], 0.375f);
    EXPECT_EQ(w[3], 0.125f);
    bezierWeights(1.0f, w);
    EXPECT_EQ(w[0], 0.0f);
    EXPECT_EQ(w[3], 1.0f);
}

TEST(Spline, KnotVectorsOfTheFourTypes) {
    // Manual §5.2.1 with 5 control points (m = 4).
    std::vector<float> k;
    splineKnots(5, 0, k);  // CLOSE/CLOSE {-3,-2,-1,0,…,m-2,m-1,m,m+1}
    EXPECT_EQ(k, (std::vector<float>{-3, -2, -1, 0, 1, 2, 3, 4, 5}));
    splineKnots(5, 1, k);  // OPEN/CLOSE
    EXPECT_EQ(k, (std::vector<float>{0, 0, 0, 0, 1, 2, 3, 4, 5}));
    splineKnots(5, 2, k);  // CLOSE/OPEN: end knots all m-2
    EXPECT_EQ(k, (std::vector<float>{-3, -2, -1, 0, 1, 2, 2, 2, 2}));
    splineKnots(5, 3, k);  // OPEN/OPEN
    EXPECT_EQ(k, (std::vector<float>{0, 0, 0, 0, 1, 2, 2, 2, 2}));
    splineKnots(4, 3, k);  // one open patch is a Bezier patch
    EXPECT_EQ(k, (std::vector<float>{0, 0, 0, 0, 1, 1, 1, 1}));
}

TEST(Spline, Bezier4x4Div2) {
    Memory mem;
    GeState st;
    writeGrid(mem, 4, 4, bumpy);
    TessOutput out;
    std::string err;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 2), geo::AccuracyProfile::ppsspp(), out, &err)) << err;
    EXPECT_EQ(out.prim, GE_PRIM_TRIANGLES);
    ASSERT_EQ(out.verts.size(), 9u);
    ASSERT_EQ(out.indices.size(), 24u);  // 8 triangles
    // Corners are the corner control points, exactly.
    auto expectPos = [&](u32 vi, float x, float y, float z) {
        EXPECT_EQ(out.verts[vi].pos[0], x) << vi;
        EXPECT_EQ(out.verts[vi].pos[1], y) << vi;
        EXPECT_EQ(out.verts[vi].pos[2], z) << vi;
    };
    expectPos(0, 0, 0, bumpy(0, 0));
    expectPos(2, 3, 0, bumpy(3, 0));
    expectPos(6, 0, 3, bumpy(0, 3));
    expectPos(8, 3, 3, bumpy(3, 3));
    // Centre: weights 1/8, 3/8, 3/8, 1/8 in both directions → x = y = 1.5.
    EXPECT_FLOAT_EQ(out.verts[4].pos[0], 1.5f);
    EXPECT_FLOAT_EQ(out.verts[4].pos[1], 1.5f);
    float zc = 0;
    const float b[4] = {0.125f, 0.375f, 0.375f, 0.125f};
    for (u32 v = 0; v < 4; ++v)
        for (u32 u = 0; u < 4; ++u) zc += b[u] * b[v] * bumpy(u, v);
    EXPECT_NEAR(out.verts[4].pos[2], zc, 1e-5f);
    // First quad: (q0, q2, q1), (q1, q2, q3) with q0 = 0, q1 = 1, q2 = 3, q3 = 4.
    EXPECT_EQ(std::vector<u32>(out.indices.begin(), out.indices.begin() + 6), (std::vector<u32>{0, 3, 1, 1, 3, 4}));
    for (u32 i : out.indices) EXPECT_LT(i, 9u);
    // Generated texture coordinates: S = patch_u + i/divU.
    EXPECT_EQ(out.verts[4].uv[0], 0.5f);
    EXPECT_EQ(out.verts[4].uv[1], 0.5f);
    EXPECT_EQ(out.verts[8].uv[0], 1.0f);
    EXPECT_EQ(out.verts[5].uv[0], 1.0f);
    EXPECT_EQ(out.verts[5].uv[1], 0.5f);
}

TEST(Spline, BezierTwoPatchesAndGeneratedUV) {
    Memory mem;
    GeState st;
    writeGrid(mem, 7, 4, flat);  // 2 patches in U
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 7, 4, 1), geo::AccuracyProfile::ppsspp(), out));
    ASSERT_EQ(out.verts.size(), 8u);  // 2 patches × 2×2 vertices
    EXPECT_EQ(out.indices.size(), 12u);
    // Patch 1 starts at control point column 3; its S runs 1..2.
    EXPECT_EQ(out.verts[4].pos[0], 3.0f);
    EXPECT_EQ(out.verts[4].uv[0], 1.0f);
    EXPECT_EQ(out.verts[5].pos[0], 6.0f);
    EXPECT_EQ(out.verts[5].uv[0], 2.0f);
    EXPECT_EQ(out.indices[6], 4u);
}

TEST(Spline, GeneratedNormalsFollowPface) {
    Memory mem;
    GeState st;
    writeGrid(mem, 4, 4, flat);
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 2), geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.verts[4].nrm[2], 0.0f);  // lighting off: no normals generated
    set(st, GE_CMD_LTE, 1);
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 2), geo::AccuracyProfile::ppsspp(), out));
    // dP/du = +x, dP/dv = +y → cross = +z.
    for (const DecodedVertex& v : out.verts) {
        EXPECT_NEAR(v.nrm[0], 0.0f, 1e-6f);
        EXPECT_NEAR(v.nrm[1], 0.0f, 1e-6f);
        EXPECT_NEAR(v.nrm[2], 1.0f, 1e-6f);
    }
    PatchPacket p = patch(false, 4, 4, 2);
    p.reverseFace = true;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    EXPECT_NEAR(out.verts[4].nrm[2], -1.0f, 1e-6f);
}

TEST(Spline, ColoursAndUVsInterpolate) {
    Memory mem;
    GeState st;
    // 8888 colour + float UV + float XYZ: 24 bytes. UV = (u, v)·0.5; colour constant.
    const u32 vtype = 3u | (7u << 2) | (3u << 7);
    for (u32 v = 0; v < 4; ++v)
        for (u32 u = 0; u < 4; ++u) {
            const u32 a = kV + 24 * (v * 4 + u);
            writeF(mem, a, 0.5f * float(u));
            writeF(mem, a + 4, 0.5f * float(v));
            mem.write32(a + 8, 0x40302010);
            writeF(mem, a + 12, float(u));
            writeF(mem, a + 16, float(v));
            writeF(mem, a + 20, 0.0f);
        }
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 2, vtype), geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.verts[8].uv[0], 1.5f);  // corner control point's UV
    EXPECT_FLOAT_EQ(out.verts[4].uv[0], 0.75f);
    for (const DecodedVertex& v : out.verts) {
        EXPECT_EQ(v.color[0], 0x10);
        EXPECT_EQ(v.color[3], 0x40);
    }
}

TEST(Spline, OpenSingleSplinePatchHasTheReferenceWeights) {
    // One patch open at both ends would be the Bezier patch (knots 0,0,0,0,1,1,1,1), but the
    // reference computes 1/(U[5]−U[2]) as 1/2 instead of 1 there (GachiTora's text splines):
    // at t = 1/2 the weights are (1/8, 1/2, 1/4, 1/8), not (1/8, 3/8, 3/8, 1/8); at t = 1/4
    // (27/64, 30/64, 6/64, 1/64). Control x = 0, 1, 2, 3 along u.
    Memory mem;
    GeState st;
    writeGrid(mem, 4, 4, flat);
    PatchPacket p = patch(true, 4, 4, 4);
    p.uknot = p.vknot = 3;
    TessOutput spl;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), spl));
    ASSERT_EQ(spl.verts.size(), 25u);
    EXPECT_EQ(spl.verts[0].pos[0], 0.0f);
    EXPECT_EQ(spl.verts[1].pos[0], 0.703125f);   // 30/64 + 2·6/64 + 3/64; Bezier: 0.75
    EXPECT_EQ(spl.verts[2].pos[0], 1.375f);      // 1/2 + 2/4 + 3/8; Bezier: 1.5
    EXPECT_EQ(spl.verts[4].pos[0], 3.0f);        // the ends stay exact
    EXPECT_EQ(spl.verts[2 * 5].pos[1], 1.375f);  // the same along v
    EXPECT_EQ(spl.verts[24].pos[1], 3.0f);
    // Same triangles as the Bezier patch.
    TessOutput bez;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 4), geo::AccuracyProfile::ppsspp(), bez));
    EXPECT_EQ(spl.indices, bez.indices);
}

TEST(Spline, TwoOpenSplinePatchesFollowTheKnotVector) {
    // 5 control points open at both ends: knots 0,0,0,0,1,2,2,2,2. At t = 1/2:
    // N = ((1−t)³, …) = (1/8, 19/32, 1/4, 1/32); at the inner knot t = 1: (1/4, 1/2, 1/4) on
    // control points 1…3. x = control index.
    Memory mem;
    GeState st;
    writeGrid(mem, 5, 4, flat);
    PatchPacket p = patch(true, 5, 4, 2);
    p.uknot = p.vknot = 3;
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    ASSERT_EQ(out.verts.size(), 5u * 3u);
    EXPECT_EQ(out.verts[1].pos[0], 1.1875f);  // 19/32 + 2/4 + 3/32
    EXPECT_EQ(out.verts[2].pos[0], 2.0f);     // 1/4 + 2/2 + 3/4
    EXPECT_EQ(out.verts[4].pos[0], 4.0f);
}

TEST(Spline, ClosedUniformSplineStartsAtTheBlendOfThreePoints) {
    Memory mem;
    GeState st;
    writeGrid(mem, 5, 4, flat);
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(true, 5, 4, 2), geo::AccuracyProfile::ppsspp(), out));
    // (5−3)·2 + 1 = 5 by (4−3)·2 + 1 = 3 vertices.
    ASSERT_EQ(out.verts.size(), 15u);
    EXPECT_EQ(out.indices.size(), 4u * 2 * 6);
    // Uniform cubic B-spline at a knot: (P0 + 4·P1 + P2)/6 → (0 + 4 + 2)/6 = 1 in x and y.
    EXPECT_NEAR(out.verts[0].pos[0], 1.0f, 1e-6f);
    EXPECT_NEAR(out.verts[0].pos[1], 1.0f, 1e-6f);
    // Last column: (P2 + 4·P3 + P4)/6 = 3.
    EXPECT_NEAR(out.verts[4].pos[0], 3.0f, 1e-6f);
    // Generated S runs over the parameter range 0..count−3.
    EXPECT_EQ(out.verts[4].uv[0], 2.0f);
    EXPECT_EQ(out.verts[14].uv[1], 1.0f);
}

TEST(Spline, OpenEdgesInterpolateTheEndPoints) {
    Memory mem;
    GeState st;
    writeGrid(mem, 6, 5, bumpy);
    for (u32 type = 0; type < 4; ++type) {
        PatchPacket p = patch(true, 6, 5, 3);
        p.uknot = type;
        p.vknot = 3;
        TessOutput out;
        ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
        const u32 nu = 3 * 3 + 1;
        ASSERT_EQ(out.verts.size(), size_t(nu) * (2 * 3 + 1));
        // V is open at both ends, so row 0 lies on control row 0 (y = 0).
        EXPECT_NEAR(out.verts[0].pos[1], 0.0f, 1e-6f);
        // Open start: P0 (x = 0); closed: (P0 + 4·P1 + P2)/6 = 1.
        EXPECT_NEAR(out.verts[0].pos[0], (type & 1) ? 0.0f : 1.0f, 1e-6f) << type;
        // Open end: P5 (x = 5); closed: (P3 + 4·P4 + P5)/6 = 4.
        EXPECT_NEAR(out.verts[nu - 1].pos[0], (type & 2) ? 5.0f : 4.0f, 1e-5f) << type;
    }
}

TEST(Spline, BasisIsAPartitionOfUnity) {
    // Constant control points must give that constant everywhere, for every knot type.
    Memory mem;
    GeState st;
    for (u32 i = 0; i < 7 * 6; ++i) {
        writeF(mem, kV + 12 * i, 7.0f);
        writeF(mem, kV + 12 * i + 4, -3.0f);
        writeF(mem, kV + 12 * i + 8, 0.5f);
    }
    for (u32 uk = 0; uk < 4; ++uk)
        for (u32 vk = 0; vk < 4; ++vk) {
            PatchPacket p = patch(true, 7, 6, 5);
            p.uknot = uk;
            p.vknot = vk;
            TessOutput out;
            ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
            for (const DecodedVertex& v : out.verts) {
                ASSERT_NEAR(v.pos[0], 7.0f, 1e-5f);
                ASSERT_NEAR(v.pos[1], -3.0f, 1e-5f);
            }
        }
}

TEST(Spline, PatchPrimitivesAndMinimumCounts) {
    Memory mem;
    GeState st;
    writeGrid(mem, 4, 4, flat);
    PatchPacket p = patch(false, 4, 4, 2);
    p.patchPrim = 1;
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.prim, GE_PRIM_LINES);
    EXPECT_EQ(std::vector<u32>(out.indices.begin(), out.indices.begin() + 6), (std::vector<u32>{0, 3, 1, 4, 1, 3}));
    p.patchPrim = 2;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.prim, GE_PRIM_POINTS);
    EXPECT_EQ(out.indices.size(), 9u);
    p.patchPrim = 3;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.prim, GE_PRIM_POINTS);
    // Fewer than 4 control points in a direction: nothing, but no error.
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 3, 4, 2), geo::AccuracyProfile::ppsspp(), out));
    EXPECT_TRUE(out.verts.empty());
    EXPECT_TRUE(out.indices.empty());
    ASSERT_TRUE(tessellatePatch(mem, st, patch(true, 4, 3, 2), geo::AccuracyProfile::ppsspp(), out));
    EXPECT_TRUE(out.verts.empty());
    // Division 0 acts as 1.
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 0), geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.verts.size(), 4u);
}

TEST(Spline, BadInputFails) {
    Memory mem;
    GeState st;
    TessOutput out;
    std::string err;
    PatchPacket p = patch(false, 4, 4, 2);
    p.vertexAddr = 0x00000100;
    EXPECT_FALSE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out, &err));
    EXPECT_FALSE(err.empty());
    p = patch(false, 4, 4, 2, kFloatPos | (2u << 11));
    p.indexAddr = 0x00000100;
    err.clear();
    EXPECT_FALSE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out, &err));
    EXPECT_FALSE(err.empty());
    // Absurd division counts are refused instead of allocating gigabytes.
    writeGrid(mem, 4, 4, flat);
    p = patch(true, 200, 200, 255);
    EXPECT_FALSE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out, &err));
}

TEST(Spline, IndexedControlPoints) {
    Memory mem;
    GeState st;
    writeGrid(mem, 4, 4, bumpy);
    // Index buffer listing the points in reverse order: corner 0 of the patch is point 15.
    const u32 kI = 0x08300000;
    for (u32 i = 0; i < 16; ++i) mem.write16(kI + 2 * i, u16(15 - i));
    PatchPacket p = patch(false, 4, 4, 1, kFloatPos | (2u << 11));
    p.indexAddr = kI;
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, p, geo::AccuracyProfile::ppsspp(), out));
    EXPECT_EQ(out.verts[0].pos[0], 3.0f);
    EXPECT_EQ(out.verts[0].pos[1], 3.0f);
    EXPECT_EQ(out.verts[3].pos[0], 0.0f);
    (void)kColPos;
}

}  // namespace

// The reference sums each attribute separably in single precision (PPSSPP SplineCommon.cpp,
// Tessellator::SampleU then SampleV): every row of control points (fixed v) folded along u
// (r0·w0 + r1·w1 + r2·w2 + r3·w3, in that order), then the row sums along v the same way.
// Expected values below are that sum written out with the Bernstein weights at t = 2/13 (u)
// and 3/13 (v) of a 13×13 division; the control points are Coded Arms' floor grate (x ∈ {240,
// 200}, z ∈ {440, 480}, each corner doubled), whose vertices the reference rounds exactly this
// way. Summing columns first (v, then u) gives different floats here, so the test tells the
// two orders apart.
TEST(Spline, SummationOrderFollowsTheReference) {
    Memory mem;
    GeState st;
    const float xs[4] = {240.0f, 240.0f, 200.0f, 200.0f};
    const float zs[4] = {440.0f, 440.0f, 480.0f, 480.0f};
    for (u32 v = 0; v < 4; ++v)
        for (u32 u = 0; u < 4; ++u) {
            const u32 a = kV + 12 * (v * 4 + u);
            writeF(mem, a, xs[u]);
            writeF(mem, a + 4, 0.0f);
            writeF(mem, a + 8, zs[v]);
        }
    TessOutput out;
    ASSERT_TRUE(tessellatePatch(mem, st, patch(false, 4, 4, 13), geo::AccuracyProfile::ppsspp(), out));
    ASSERT_EQ(out.verts.size(), 14u * 14u);
    const float inv = 1.0f / 13.0f;
    float wu[4], wv[4];
    bezierWeights(2.0f * inv, wu);
    bezierWeights(3.0f * inv, wv);
    // Rows first: x is the same in every row; z is constant along each row.
    float rowX = xs[0] * wu[0], rowZ[4];
    for (int a = 1; a < 4; ++a) rowX = rowX + xs[a] * wu[a];
    for (int b = 0; b < 4; ++b) {
        rowZ[b] = zs[b] * wu[0];
        for (int a = 1; a < 4; ++a) rowZ[b] = rowZ[b] + zs[b] * wu[a];
    }
    float x = rowX * wv[0], z = rowZ[0] * wv[0];
    for (int b = 1; b < 4; ++b) {
        x = x + rowX * wv[b];
        z = z + rowZ[b] * wv[b];
    }
    // Columns first, for the check that the two orders differ at this vertex.
    float colX[4], colZ = zs[0] * wv[0];
    for (int b = 1; b < 4; ++b) colZ = colZ + zs[b] * wv[b];
    for (int a = 0; a < 4; ++a) {
        colX[a] = xs[a] * wv[0];
        for (int b = 1; b < 4; ++b) colX[a] = colX[a] + xs[a] * wv[b];
    }
    float xc = colX[0] * wu[0], zc = colZ * wu[0];
    for (int a = 1; a < 4; ++a) {
        xc = xc + colX[a] * wu[a];
        zc = zc + colZ * wu[a];
    }
    ASSERT_NE(x, xc);
    ASSERT_NE(z, zc);
    const DecodedVertex& v = out.verts[3 * 14 + 2];
    EXPECT_EQ(v.pos[0], x);
    EXPECT_EQ(v.pos[2], z);
}
