// SPDX-License-Identifier: MIT
// Vertex processing and clipping tests: matrix element order (docs/ge-rules.md §3.4), viewport and
// the 1/16-pixel rounding (ge-rules.md §8.1), texture-coordinate generation (manual §13.1–13.2, ge-rules.md §8.10), fog (ge-rules.md §3.9,
// §8.9) and the clipping/discard rules (ge-rules.md §8.5). Expected values are computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/clip.h"
#include "geometry/transform.h"

using namespace ge;
using namespace ge::geo;

namespace {

struct Rig {
    GeState st;
    Rig() {
        // Identity world/view, identity projection: clip = (x, y, z, 1).
        st.world[0] = st.world[4] = st.world[8] = 1;
        st.view[0] = st.view[4] = st.view[8] = 1;
        st.proj[0] = st.proj[5] = st.proj[10] = st.proj[15] = 1;
        setf(GE_CMD_SX, 1), setf(GE_CMD_SY, 1), setf(GE_CMD_SZ, 16384);
        setf(GE_CMD_TX, 0), setf(GE_CMD_TY, 0), setf(GE_CMD_TZ, 32768);
        setf(GE_CMD_SU, 1), setf(GE_CMD_SV, 1), setf(GE_CMD_TU, 0), setf(GE_CMD_TV, 0);
        set(GE_CMD_TSIZE0, 6 | 5 << 8);  // 64 × 32
    }
    void set(u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }
    void setf(u8 cmd, float f) { set(cmd, toFloat24(f)); }
    ClipVertex run(const DecodedVertex& dv, u32 vtype = 0x180 /* float position */, bool hasNormal = false) {
        TransformState ts = makeTransformState(st, vtype, false, hasNormal);
        ClipVertex cv;
        transformVertex(ts, dv, cv);
        return cv;
    }
};

DecodedVertex at(float x, float y, float z) {
    DecodedVertex d;
    d.pos[0] = x, d.pos[1] = y, d.pos[2] = z;
    d.color[0] = d.color[1] = d.color[2] = d.color[3] = 255;
    return d;
}

}  // namespace

TEST(GeoTransform, MatrixElementOrder) {
    // Element k of a 3×4 matrix is row k%3, column k/3; of the 4×4 row k%4, column k/4 (ge-rules.md §3.4).
    float m12[12], m16[16];
    for (int k = 0; k < 12; ++k) m12[k] = float(k + 1);
    for (int k = 0; k < 16; ++k) m16[k] = float(k + 1);
    const float p[3] = {1, 2, 3};
    float o3[3], o4[4];
    mulPoint3x4(m12, p, o3);
    EXPECT_EQ(o3[0], 1 + 4 * 2 + 7 * 3 + 10);  // m0·x + m3·y + m6·z + m9 = 40
    EXPECT_EQ(o3[1], 2 + 5 * 2 + 8 * 3 + 11);  // 47
    EXPECT_EQ(o3[2], 3 + 6 * 2 + 9 * 3 + 12);  // 54
    mulDir3x4(m12, p, o3);
    EXPECT_EQ(o3[0], 30);
    mulPoint4x4(m16, p, o4);
    EXPECT_EQ(o4[0], 1 + 5 * 2 + 9 * 3 + 13);   // 51
    EXPECT_EQ(o4[1], 2 + 6 * 2 + 10 * 3 + 14);  // 58
    EXPECT_EQ(o4[2], 3 + 7 * 2 + 11 * 3 + 15);  // 65
    EXPECT_EQ(o4[3], 4 + 8 * 2 + 12 * 3 + 16);  // 72
}

TEST(GeoTransform, ViewportRoundingAndOffset) {
    Rig r;
    // Xs·16 = 1600.625 → trunc(1600.625 + 0.375) = 1601 (rounds up from 0.625 of a subpixel);
    // Ys·16 = 1600.48 → trunc(1600.855) = 1600.
    ClipVertex v = r.run(at(100.0390625f, 100.03f, 0.5f));
    EXPECT_EQ(v.sv.x, 1601);
    EXPECT_EQ(v.sv.y, 1600);
    EXPECT_EQ(v.sv.z, 40960);  // 16384·0.5 + 32768
    EXPECT_FALSE(v.outside);
    // OFFSETX/OFFSETY (12.4) are subtracted after rounding: drawing X = x16 − OFFX.
    r.set(GE_CMD_OFFSETX, 10 * 16 + 3);
    r.set(GE_CMD_OFFSETY, 0x20);
    v = r.run(at(100.0390625f, 100.03f, 0.5f));
    EXPECT_EQ(v.sv.x, 1601 - 163);
    EXPECT_EQ(v.sv.y, 1600 - 32);
    // The perspective divide: w = 2 halves x/w (world → view → projection chain).
    r.st.proj[15] = 2;
    v = r.run(at(200.078125f, 0, 1.0f));
    EXPECT_EQ(v.clip[3], 2.0f);
    EXPECT_EQ(v.sv.x, 1601 - 163);
    EXPECT_EQ(v.sv.w, 2.0f);
    EXPECT_EQ(v.sv.z, 40960);
}

TEST(GeoTransform, OffscreenVertexTruncatesTowardZeroAfterOffset) {
    Rig r;
    // The offset comes off before the truncating conversion (reference: int(x·16 + 0.375 − OFF)).
    // OFFX16 = OFFY16 = 1608: Xs·16 + 0.375 = 1601 → 1601 − 1608 = −7 exactly;
    // Ys·16 = 1600.48 → 1600.855 − 1608 = −7.145 → trunc −7 (flooring first would give −8).
    r.set(GE_CMD_OFFSETX, 1608);
    r.set(GE_CMD_OFFSETY, 1608);
    ClipVertex v = r.run(at(100.0390625f, 100.03f, 0.5f));
    EXPECT_EQ(v.sv.x, -7);
    EXPECT_EQ(v.sv.y, -7);
    // Xs·16 = 1600.5 → 1600.875 − 1608 = −7.125 → −7 (not −8).
    v = r.run(at(100.03125f, 100.03f, 0.5f));
    EXPECT_EQ(v.sv.x, -7);
    // On-screen vertices are unaffected: 1600.875 − 1592 = 8.875 → 8.
    r.set(GE_CMD_OFFSETX, 1592);
    v = r.run(at(100.03125f, 100.03f, 0.5f));
    EXPECT_EQ(v.sv.x, 8);
}

TEST(GeoTransform, WorldViewProjectionChain) {
    Rig r;
    // World: translate (1, 2, 3); view: scale 2; projection: w = −z (a perspective divide).
    r.st.world[9] = 1, r.st.world[10] = 2, r.st.world[11] = 3;
    r.st.view[0] = r.st.view[4] = r.st.view[8] = 2;
    for (float& e : r.st.proj) e = 0;
    r.st.proj[0] = r.st.proj[5] = r.st.proj[10] = 1;
    r.st.proj[11] = -1;  // row 3, column 2
    r.setf(GE_CMD_SX, 100), r.setf(GE_CMD_TX, 2048), r.setf(GE_CMD_SY, -100), r.setf(GE_CMD_TY, 2048);
    // model (1, 1, −7) → world (2, 3, −4) → view (4, 6, −8) → clip (4, 6, −8, 8)
    ClipVertex v = r.run(at(1, 1, -7));
    EXPECT_EQ(v.clip[0], 4); EXPECT_EQ(v.clip[1], 6); EXPECT_EQ(v.clip[2], -8); EXPECT_EQ(v.clip[3], 8);
    EXPECT_EQ(v.sv.x, (2048 + 50) * 16);  // 100·4/8 + 2048
    EXPECT_EQ(v.sv.y, (2048 - 75) * 16);  // −100·6/8 + 2048
    EXPECT_EQ(v.sv.z, 16384);             // 16384·(−1) + 32768
}

TEST(GeoTransform, MatrixModeFollowsLightTypes) {
    // PPSSPP SWR (ComputeTransformState): one folded world·view·proj matrix unless an enabled
    // light needs the world position (point/spot); then model → world, and view·proj folded.
    Rig r;
    r.st.world[9] = 1, r.st.world[10] = 2, r.st.world[11] = 3;
    r.st.view[0] = r.st.view[4] = r.st.view[8] = 2;
    for (float& e : r.st.proj) e = 0;
    r.st.proj[0] = r.st.proj[5] = r.st.proj[10] = 1;
    r.st.proj[11] = -1;
    auto mode = [&](TransformState ts) { return ts.combinedClip ? 1 : ts.worldToClip ? 2 : 0; };
    EXPECT_EQ(mode(makeTransformState(r.st, 0x180, false, true)), 1);
    r.set(GE_CMD_FGE, 1);  // fog alone keeps the folded matrix
    EXPECT_EQ(mode(makeTransformState(r.st, 0x180, false, true)), 1);
    r.set(GE_CMD_FGE, 0);
    r.set(GE_CMD_LTE, 1);
    r.set(GE_CMD_LTYPE0, 1 << 8);  // point light, but disabled
    EXPECT_EQ(mode(makeTransformState(r.st, 0x180, false, true)), 1);
    r.set(GE_CMD_LE0, 1);
    const TransformState ts = makeTransformState(r.st, 0x180, false, true);
    EXPECT_EQ(mode(ts), 2);
    // view·proj = diag(2, 2, 2, 1)·P: elements 0, 5, 10 = 2, element 11 = −2, element 15 = 0.
    EXPECT_EQ(ts.viewProj[0], 2); EXPECT_EQ(ts.viewProj[5], 2); EXPECT_EQ(ts.viewProj[10], 2);
    EXPECT_EQ(ts.viewProj[11], -2); EXPECT_EQ(ts.viewProj[15], 0); EXPECT_EQ(ts.viewProj[14], 0);
    // model (1, 1, −7) → world (2, 3, −4) → clip (4, 6, −8, 8), as in the chained form.
    ClipVertex v = r.run(at(1, 1, -7), 0x180, true);
    EXPECT_EQ(v.clip[0], 4); EXPECT_EQ(v.clip[1], 6); EXPECT_EQ(v.clip[2], -8); EXPECT_EQ(v.clip[3], 8);
    r.set(GE_CMD_LTYPE0, 0);  // directional: the world position is not needed
    EXPECT_EQ(mode(makeTransformState(r.st, 0x180, false, true)), 1);
}

TEST(GeoTransform, ThroughModeTexelsAndPositions) {
    Rig r;
    r.set(GE_CMD_OFFSETX, 1000);  // ignored in through mode
    DecodedVertex d = at(10.5f, 20.25f, 1234);
    d.uv[0] = 32, d.uv[1] = 16;
    d.color[0] = 7;
    ClipVertex v = r.run(d, 0x800000 | 0x100 | 0x2 /* through, s16 pos, u16 uv */);
    EXPECT_EQ(v.sv.x, 168);
    EXPECT_EQ(v.sv.y, 324);
    EXPECT_EQ(v.sv.z, 1234);
    EXPECT_FLOAT_EQ(v.sv.s, 0.5f);  // 32 / 64
    EXPECT_FLOAT_EQ(v.sv.t, 0.5f);  // 16 / 32
    EXPECT_EQ(v.sv.w, 1.0f);
    EXPECT_EQ(v.sv.fog, 1.0f);
    EXPECT_EQ(v.sv.color[0], 7);
    EXPECT_FALSE(v.outside);
}

TEST(GeoTransform, UvScaleOffset) {
    Rig r;
    r.setf(GE_CMD_SU, 2), r.setf(GE_CMD_SV, 0.5f), r.setf(GE_CMD_TU, 0.25f), r.setf(GE_CMD_TV, -1);
    DecodedVertex d = at(1, 1, 0.5f);
    d.uv[0] = 0.5f, d.uv[1] = 2;
    ClipVertex v = r.run(d);
    EXPECT_FLOAT_EQ(v.sv.s, 1.25f);  // 2·0.5 + 0.25
    EXPECT_FLOAT_EQ(v.sv.t, 0.0f);   // 0.5·2 − 1
    EXPECT_EQ(v.sv.q, 1.0f);
}

TEST(GeoTransform, ProjectionMappingSources) {
    Rig r;
    r.setf(GE_CMD_SU, 5);  // not applied in projection mapping
    // TGEN: S = 2·x, T = 3·y, Q = z + 1.
    r.st.tgen[0] = 2, r.st.tgen[4] = 3, r.st.tgen[8] = 1, r.st.tgen[11] = 1;
    DecodedVertex d = at(1, 2, 3);
    d.uv[0] = 0.5f, d.uv[1] = 0.25f;
    d.nrm[0] = 0, d.nrm[1] = 0, d.nrm[2] = 2;
    const u32 vt = 0x180 | 0x60 | 0x3;  // float pos, float normal, float uv
    r.set(GE_CMD_TMAP, 1 | 0 << 8);  // source: model position
    ClipVertex v = r.run(d, vt, true);
    EXPECT_EQ(v.sv.s, 2); EXPECT_EQ(v.sv.t, 6); EXPECT_EQ(v.sv.q, 4);
    r.set(GE_CMD_TMAP, 1 | 1 << 8);  // texture coordinates (U, V, 0)
    v = r.run(d, vt, true);
    EXPECT_EQ(v.sv.s, 1); EXPECT_EQ(v.sv.t, 0.75f); EXPECT_EQ(v.sv.q, 1);
    r.set(GE_CMD_TMAP, 1 | 2 << 8);  // normalised normal (0, 0, 1)
    v = r.run(d, vt, true);
    EXPECT_EQ(v.sv.s, 0); EXPECT_EQ(v.sv.q, 2);
    r.set(GE_CMD_TMAP, 1 | 3 << 8);  // raw normal (0, 0, 2)
    v = r.run(d, vt, true);
    EXPECT_EQ(v.sv.q, 3);
    // NREV negates the normal before it is used.
    r.set(GE_CMD_NREV, 1);
    v = r.run(d, vt, true);
    EXPECT_EQ(v.sv.q, -1);
}

TEST(GeoTransform, ShadeMappingEvenWithoutLighting) {
    Rig r;
    r.set(GE_CMD_TMAP, 2);
    r.set(GE_CMD_TSHADE, 1 | 2 << 8);  // S from light 1, T from light 2
    r.setf(GE_CMD_LX0 + 3, 0), r.setf(GE_CMD_LY0 + 3, 0), r.setf(GE_CMD_LZ0 + 3, 5);      // light 1 → (0, 0, 1)
    r.setf(GE_CMD_LX0 + 6, 3), r.setf(GE_CMD_LY0 + 6, 0), r.setf(GE_CMD_LZ0 + 6, 4);      // light 2 → (0.6, 0, 0.8)
    DecodedVertex d = at(0, 0, 0.5f);
    d.nrm[2] = 1;
    ClipVertex v = r.run(d, 0x180 | 0x60, true);
    EXPECT_FLOAT_EQ(v.sv.s, 1.0f);  // (1 + 1) / 2
    EXPECT_FLOAT_EQ(v.sv.t, 0.9f);  // (0.8 + 1) / 2
}

TEST(GeoTransform, FogFactorAndSpecials) {
    Rig r;
    r.set(GE_CMD_FGE, 1);
    r.setf(GE_CMD_FOG1, 10), r.setf(GE_CMD_FOG2, 0.0625f);
    // View Z = −4: f = (−4 + 10)·0.0625 = 0.375.
    EXPECT_FLOAT_EQ(r.run(at(0, 0, -4)).sv.fog, 0.375f);
    r.set(GE_CMD_FGE, 0);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 1.0f);
    r.set(GE_CMD_FGE, 1);
    const float inf = std::numeric_limits<float>::infinity();
    r.setf(GE_CMD_FOG1, inf), r.setf(GE_CMD_FOG2, 2);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 1.0f);  // +∞·positive: no fog for the whole draw
    r.setf(GE_CMD_FOG2, -2);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 0.0f);
    r.setf(GE_CMD_FOG2, 0);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 0.0f);  // ∞·0
    r.setf(GE_CMD_FOG1, -inf), r.setf(GE_CMD_FOG2, -3);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 1.0f);
    // FOG2 infinite → ±262144.
    r.setf(GE_CMD_FOG1, 4), r.setf(GE_CMD_FOG2, inf);
    EXPECT_EQ(r.run(at(0, 0, -4)).sv.fog, 0.0f);  // (−4 + 4)·262144
    EXPECT_EQ(r.run(at(0, 0, -3)).sv.fog, 262144.0f);
}

TEST(GeoTransform, ScreenRangeAndDepthFlags) {
    Rig r;
    // X beyond 4096 breaks the range rule.
    EXPECT_TRUE(r.run(at(5000, 10, 0.5f)).outside);
    EXPECT_TRUE(r.run(at(-0.5f, 10, 0.5f)).outside);
    EXPECT_FALSE(r.run(at(4095.9f, 10, 0.5f)).outside);
    // CLE = 0: screen Z outside [0, 65536) breaks it too (16384·z + 32768).
    EXPECT_TRUE(r.run(at(10, 10, 2.1f)).outside);
    EXPECT_TRUE(r.run(at(10, 10, -2.1f)).outside);
    // CLE = 1: Z is clamped to [0, 65535] and that vertex is exempt from the X/Y check.
    r.set(GE_CMD_CLE, 1);
    ClipVertex v = r.run(at(10, 10, 2.1f));
    EXPECT_FALSE(v.outside);
    EXPECT_EQ(v.sv.z, 65535);
    v = r.run(at(5000, 10, -2.1f));
    EXPECT_FALSE(v.outside);
    EXPECT_EQ(v.sv.z, 0);
    EXPECT_TRUE(r.run(at(5000, 10, 0.5f)).outside);
}

// NaN and huge screen Z/W convert to integers without undefined behaviour (clang's
// float-cast-overflow check, enabled in the sanitizer build, caught int(NaN) here): NaN depth is 0,
// huge depth 65535, a NaN clip parameter gives the first vertex's colour.
TEST(GeoTransform, NanAndHugeDepthConvertSafely) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(depthToInt(nan), 0);
    EXPECT_EQ(depthToInt(-1e30f), 0);
    EXPECT_EQ(depthToInt(1e30f), 65535);
    EXPECT_EQ(depthToInt(std::numeric_limits<float>::infinity()), 65535);
    EXPECT_EQ(depthToInt(1234.9f), 1234);
    Rig r;
    ClipVertex v = r.run(at(10, 10, nan));  // CLE = 0: out of range (the GE's terms make NaN huge)
    EXPECT_TRUE(v.outside);
    v = r.run(at(10, 10, 1e30f));
    EXPECT_TRUE(v.outside);
    EXPECT_EQ(v.sv.z, 65535);
    const ClipVertex through = r.run(at(10, 10, nan), 0x800000 | 0x180);
    EXPECT_EQ(through.sv.z, 0);
    const TransformState ts = makeTransformState(r.st, 0x180, false, false);
    ClipVertex a = r.run(at(10, 10, 0.5f)), b = r.run(at(20, 10, 0.5f)), out;
    a.sv.color[0] = 10, b.sv.color[0] = 200;
    lerpVertex(ts, a, b, nan, out);
    EXPECT_EQ(out.sv.color[0], 10);
    lerpVertex(ts, a, b, 1e30f, out);
    EXPECT_EQ(out.sv.color[0], 200);
}

// The GE's matrix terms (transform.cpp geTerm): a zero or denormal factor gives a zero term, and
// an exponent field of 255 (IEEE NaN/inf) is an ordinary exponent, ±1.m·2^128. Beam 'em up's text
// (rectangles whose second vertex has z = NaN under an orthographic matrix) depends on it.
TEST(GeoTransform, NanAndDenormalMatrixTerms) {
    const float nan = std::numeric_limits<float>::quiet_NaN();  // 0x7FC00000: +1.5·2^128 to the GE
    float m[16] = {};
    m[0] = 1, m[5] = 1, m[10] = -0.0078125f, m[15] = 1;  // z column only feeds row 2
    const float p[3] = {3, 4, nan};
    float out[4];
    mulPoint4x4(m, p, out);
    EXPECT_EQ(out[0], 3.0f);  // NaN·0 contributes nothing
    EXPECT_EQ(out[1], 4.0f);
    EXPECT_EQ(out[3], 1.0f);
    EXPECT_EQ(out[2], std::ldexp(-1.5f, 121));  // 1.5·2^128 · −2^−7, finite
    m[10] = 1;
    mulPoint4x4(m, p, out);
    EXPECT_TRUE(std::isinf(out[2]) && out[2] > 0);  // 1.5·2^128 overflows a float
    // A denormal factor is zero even against a huge one.
    const float m12[12] = {1e30f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const float d[3] = {1e-40f, 0, 0};
    float o3[3];
    mulDir3x4(m12, d, o3);
    EXPECT_EQ(o3[0], 0.0f);

    // The same through the point products, whose plain-float shortcut must not see a denormal
    // as a factor (IEEE: 1e-40·1e30 = 1e-10; the GE: 0) …
    float m4[16] = {};
    m4[0] = 1e-40f, m4[5] = 1, m4[10] = 1, m4[15] = 1;
    const float big[3] = {1e30f, 2, 3};
    mulPoint4x4(m4, big, out);
    EXPECT_EQ(out[0], 0.0f);
    const float m3[12] = {1e-40f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    mulPoint3x4(m3, big, o3);
    EXPECT_EQ(o3[0], 0.0f);
    EXPECT_EQ(o3[1], 2.0f);
    // … nor give a zero result the sign IEEE products would: zero elements against negative
    // coordinates are −0 in IEEE, +0 as GE terms; with a −0 translation the IEEE sum is −0, the
    // GE's +0 (a W or Z of −0 would flip a later division's infinity).
    float mz[16] = {};
    mz[12] = mz[13] = mz[14] = mz[15] = -0.0f;
    const float neg[3] = {-1, -2, -3};
    mulPoint4x4(mz, neg, out);
    for (int i = 0; i < 4; ++i) EXPECT_FALSE(std::signbit(out[i])) << i;
    float mz3[12] = {};
    mz3[9] = mz3[10] = mz3[11] = -0.0f;
    mulPoint3x4(mz3, neg, o3);
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(std::signbit(o3[i])) << i;

    // Through the whole vertex path with CLE = 1: X/Y stay valid, Z clamps (16384·inf + 32768).
    Rig r;
    r.set(GE_CMD_CLE, 1);
    const ClipVertex v = r.run(at(10, 20, nan));
    EXPECT_FALSE(v.outside);
    EXPECT_EQ(v.sv.x, 160);
    EXPECT_EQ(v.sv.y, 320);
    EXPECT_EQ(v.sv.z, 65535);
}

TEST(GeoClip, DiscardRules) {
    Rig r;
    auto tri = [&](const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) {
        TransformState ts = makeTransformState(r.st, 0x180, false, false);
        const ClipVertex* v[3] = {&a, &b, &c};
        return discardPrimitive(ts, v, 3);
    };
    auto cv = [&](float x, float y, float z, float w) {
        ClipVertex c;
        c.clip[0] = x, c.clip[1] = y, c.clip[2] = z, c.clip[3] = w;
        c.side = s8(depthSide(c));  // as projectToScreen sets it
        return c;
    };
    const ClipVertex in1 = cv(1, 1, 0, 1), in2 = cv(2, 1, 0.5f, 1), nearV = cv(1, 2, -1.5f, 1), farV = cv(1, 2, 1.5f, 1);
    const ClipVertex edge = cv(1, 2, 1.00002f, 1);  // inside the 1.00003 tolerance
    EXPECT_FALSE(tri(in1, in2, edge));
    // CLE = 0: one vertex beyond a plane drops the primitive.
    EXPECT_TRUE(tri(in1, in2, nearV));
    EXPECT_TRUE(tri(in1, farV, in2));
    // CLE = 1: only when all are beyond the same plane.
    r.set(GE_CMD_CLE, 1);
    EXPECT_FALSE(tri(in1, in2, nearV));
    EXPECT_FALSE(tri(nearV, farV, nearV));
    EXPECT_TRUE(tri(nearV, nearV, nearV));
    EXPECT_TRUE(tri(farV, farV, farV));
    // A vertex breaking the range rule drops it in any case.
    ClipVertex wild = in1;
    wild.outside = true;
    EXPECT_TRUE(tri(in1, in2, wild));
    // Through mode: never.
    TransformState ts = makeTransformState(r.st, 0x800000 | 0x100, false, false);
    const ClipVertex* v[3] = {&wild, &nearV, &farV};
    EXPECT_FALSE(discardPrimitive(ts, v, 3));
}

TEST(GeoClip, TriangleCrossingNearPlane) {
    Rig r;
    r.set(GE_CMD_CLE, 1);
    TransformState ts = makeTransformState(r.st, 0x180, false, false);
    ClipVertex a, b, c;
    auto setc = [&](ClipVertex& v, float x, float y, float z, float w, u8 red) {
        v.clip[0] = x, v.clip[1] = y, v.clip[2] = z, v.clip[3] = w;
        projectToScreen(ts, v, false);  // screen positions give the polygon's winding
        v.sv.color[0] = red;
        v.sv.s = x;
    };
    setc(a, 0, 0, -2, 1, 0);    // beyond the near plane (z < −w): distance z + w = −1
    setc(b, 1, 0, 0, 1, 255);   // distance 1
    setc(c, 0, 1, 0, 1, 100);
    EXPECT_TRUE(beyondNear(a));
    EXPECT_FALSE(beyondNear(b));
    ClipVertex out[4];
    ASSERT_EQ(clipTriangleNear(ts, a, b, c, out), 4);
    // a→b cut at t = 0.5: (0.5, 0, −1, 1); then b, c; c→a cut at t = 0.5: (0, 0.5, −1, 1).
    EXPECT_FLOAT_EQ(out[0].clip[0], 0.5f); EXPECT_FLOAT_EQ(out[0].clip[2], -1); EXPECT_FLOAT_EQ(out[0].clip[3], 1);
    EXPECT_EQ(out[1].clip[0], 1);
    EXPECT_EQ(out[2].clip[1], 1);
    EXPECT_FLOAT_EQ(out[3].clip[1], 0.5f); EXPECT_FLOAT_EQ(out[3].clip[2], -1);
    EXPECT_EQ(out[0].sv.color[0], 127);  // (0·128 + 255·128) / 256
    EXPECT_EQ(out[3].sv.color[0], 50);   // (100·128 + 0·128) / 256
    EXPECT_FLOAT_EQ(out[0].sv.s, 0.5f);
    // The new vertices are on the near plane: screen Z = 16384·(−1) + 32768.
    EXPECT_EQ(out[0].sv.z, 16384);
    EXPECT_EQ(out[0].sv.x, int(0.5f * 16 + 0.375f));
    // Two vertices beyond: a triangle remains.
    ClipVertex b2 = b;
    setc(b2, 1, 0, -3, 1, 255);
    EXPECT_EQ(clipTriangleNear(ts, a, b2, c, out), 3);
    // Lines.
    ClipVertex la = a, lb = b;
    ASSERT_TRUE(clipLineNear(ts, la, lb));
    EXPECT_FLOAT_EQ(la.clip[0], 0.5f);
    EXPECT_EQ(lb.clip[0], 1);
    ClipVertex lc = a, ld = b2;
    EXPECT_FALSE(clipLineNear(ts, lc, ld));
}

TEST(GeoClip, ClippedVertexOffScreenDropsItsFanTriangles) {
    // PPSSPP Clipper.cpp: a new (clipped) vertex whose screen X/Y is outside [0, 4096) drops the
    // fan triangles using it; Z is clamped by CLE but gives no exemption for new vertices.
    Rig r;
    r.set(GE_CMD_CLE, 1);
    r.setf(GE_CMD_SX, 10), r.setf(GE_CMD_TX, 2048), r.setf(GE_CMD_SY, 10), r.setf(GE_CMD_TY, 2048);
    TransformState ts = makeTransformState(r.st, 0x180, false, false);
    auto setc = [&](ClipVertex& v, float x, float y, float z, float w) {
        v.clip[0] = x, v.clip[1] = y, v.clip[2] = z, v.clip[3] = w;
        projectToScreen(ts, v, true);
    };
    ClipVertex a, b, c, out[4];
    setc(a, 0, 0, -2, 1);  // beyond the near plane, distance −1
    setc(b, 1, 0, 0, 1);   // inside, distance 1; screen x = 2058
    setc(c, 0, 1, 0, 1);   // inside; screen y = 2058
    // Polygon (ab, b, c, ca), ab = (0.5, 0, −1, 1) → x 2053, ca → y 2053: all on screen.
    ASSERT_EQ(clipTriangleNear(ts, a, b, c, out), 4);
    EXPECT_FALSE(out[0].outside);
    EXPECT_FALSE(out[3].outside);
    // Move a far left: ab = (−499.5, 0, −1, 1) → screen x 2048 − 4995 < 0: outside. Both fan
    // triangles (ab, b, c), (ab, c, ca) use it: nothing is drawn.
    setc(a, -1000, 0, -2, 1);
    EXPECT_EQ(clipTriangleNear(ts, a, b, c, out), 0);
    // Only ca outside: a = (−400, 0) at distance −4, b = (100, 0) at 1 → ab at t = 0.8 = (0, 0);
    // c = (0, 1) at distance 100 → ca at t = 4/104 ≈ (−384.6, 0.04) → x < 0. (ab, b, c) remains.
    setc(a, -400, 0, -5, 1);
    setc(b, 100, 0, 0, 1);
    setc(c, 0, 1, 99, 1);
    ASSERT_EQ(clipTriangleNear(ts, a, b, c, out), 3);
    EXPECT_FLOAT_EQ(out[0].clip[0], 0.0f);
    EXPECT_EQ(out[1].clip[0], 100);
    EXPECT_EQ(out[2].clip[1], 1);
}

TEST(GeoClip, IntersectionInterpolatedFromOutsideVertex) {
    // The new vertex is a_out + (a_in − a_out)·t with t = d_out / (d_out − d_in), whichever edge
    // direction the polygon walks (PPSSPP Clipper.cpp). Distances −1 and 2: t = 1/3. Colour weight
    // int(t·256) = 85: (0·171 + 255·85) / 256 = 84 from the outside vertex; walking from the inside
    // one would give int(2/3·256) = 170 → (255·86 + 0·170) / 256 = 85.
    Rig r;
    r.set(GE_CMD_CLE, 1);
    TransformState ts = makeTransformState(r.st, 0x180, false, false);
    ClipVertex a, b, c, out[4];
    auto setc = [&](ClipVertex& v, float x, float y, float z, float w, u8 red) {
        v.clip[0] = x, v.clip[1] = y, v.clip[2] = z, v.clip[3] = w;
        projectToScreen(ts, v, true);
        v.sv.color[0] = red;
    };
    setc(a, 0, 0, 1, 1, 255);   // inside, distance 2
    setc(b, 1, 0, -2, 1, 0);    // beyond, distance −1
    setc(c, 0, 1, 1, 1, 255);
    const int n = clipTriangleNear(ts, a, b, c, out);
    ASSERT_EQ(n, 4);
    // (a, a→b, b→c, c): the a→b point comes from b (outside) toward a.
    EXPECT_EQ(out[1].sv.color[0], 84);
}

TEST(GeoTransform, ProjectionRectangleKeepsRectangleWalkWhenQIsOne) {
    // A transform-mode rectangle with projection mapping is drawn as two triangles (ge-rules.md §8.2) unless
    // the texture matrix makes Q = 1 for every vertex (Q column 0 for X and Y, 0 for Z or UV
    // source, translation Q = 1): PPSSPP's software renderer keeps the rectangle walk then.
    Rig r;
    r.set(GE_CMD_TMAP, 1 | 0 << 8);  // projection mapping from the model position
    r.st.tgen[0] = 2, r.st.tgen[4] = 3, r.st.tgen[9] = 0.5f, r.st.tgen[11] = 1;
    EXPECT_FALSE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.st.tgen[11] = 0.5f;  // Q constant but not 1
    EXPECT_TRUE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.st.tgen[11] = 1, r.st.tgen[8] = 1;  // Q = z + 1 varies with the position's Z
    EXPECT_TRUE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.set(GE_CMD_TMAP, 1 | 1 << 8);  // ...but a UV source has Z = 0
    EXPECT_FALSE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.st.tgen[8] = 0, r.st.tgen[5] = 1;  // Q = V + 1
    EXPECT_TRUE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.st.tgen[5] = 0;
    r.set(GE_CMD_TMAP, 0);  // UV mapping: always the rectangle walk
    EXPECT_FALSE(makeTransformState(r.st, 0x180, false, false).rectAsTriangles);
    r.set(GE_CMD_TMAP, 1);
    r.st.tgen[11] = 0.5f;
    EXPECT_FALSE(makeTransformState(r.st, 0x180 | 1u << 23, false, false).rectAsTriangles);  // through
}
