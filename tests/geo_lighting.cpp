// SPDX-License-Identifier: MIT
// Lighting tests (manual equations 9-1 … 9-10; docs/ge-rules.md §8.3, §8.9, §8.12). Each expected
// colour is worked out by hand with the fixed-point forms of ge-rules.md §8.3:
//   global ambient ((2·MAC + 1)·(2·AC + 1)) >> 10;  per light ((2·Lc + 1)·(2·Mc + 1)·s) >> 19,
//   s = min(512, ceil(512·k + 1)).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/lighting.h"

using namespace ge;
using namespace ge::geo;

namespace {

struct Rig {
    GeState st;
    void set(u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }
    void setf(u8 cmd, float f) { set(cmd, toFloat24(f)); }
    static u32 rgb(u32 r, u32 g, u32 b) { return r | g << 8 | b << 16; }
    // Light n: type (0 dir, 1 point, 2 spot), components (0 A+D, 1 A+D+S, 2 powered D), position.
    void light(int n, u32 type, u32 comp, float x, float y, float z) {
        set(u8(GE_CMD_LE0 + n), 1);
        set(u8(GE_CMD_LTYPE0 + n), comp | type << 8);
        setf(u8(GE_CMD_LX0 + 3 * n), x), setf(u8(GE_CMD_LY0 + 3 * n), y), setf(u8(GE_CMD_LZ0 + 3 * n), z);
        setf(u8(GE_CMD_LKA0 + 3 * n), 1), setf(u8(GE_CMD_LKB0 + 3 * n), 0), setf(u8(GE_CMD_LKC0 + 3 * n), 0);
    }
    struct Out {
        u8 c[4], s[3];
    };
    Out run(const float pos[3], const float nrm[3], u8 r = 0, u8 g = 0, u8 b = 0, u8 a = 255, bool hasColor = false) {
        LightingState ls = makeLightingState(st, hasColor);
        const u8 vc[4] = {r, g, b, a};
        Out o{};
        lightVertex(ls, pos, nrm, vc, o.c, o.s);
        return o;
    }
};

const float kOrigin[3] = {0, 0, 0};
const float kUp[3] = {0, 0, 1};

// ((2L + 1)(2M + 1)·s) >> 19 with s = min(512, ceil(512k + 1)) — the hand formula of ge-rules.md §8.3.
int term(int L, int M, double k) {
    int s = int(std::ceil(512.0 * k + 1.0));
    if (s > 512) s = 512;
    return ((2 * L + 1) * (2 * M + 1) * s) >> 19;
}

}  // namespace

TEST(GeoLighting, EmissiveAndGlobalAmbient) {
    Rig r;
    r.set(GE_CMD_MEC, Rig::rgb(10, 0, 0));
    r.set(GE_CMD_MAC, Rig::rgb(200, 100, 50));
    r.set(GE_CMD_MAA, 255);
    r.set(GE_CMD_AC, Rig::rgb(128, 255, 0));
    r.set(GE_CMD_AA, 128);
    auto o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.c[0], 10 + 100);  // 10 + (401·257 >> 10) = 10 + 100
    EXPECT_EQ(o.c[1], 100);       // 201·511 >> 10 = 100
    EXPECT_EQ(o.c[2], 0);         // 101·1 >> 10
    EXPECT_EQ(o.c[3], 128);       // (511·257) >> 10 = 128
    EXPECT_EQ(o.s[0], 0);
    // With MATERIAL bit 0 and a vertex colour, the vertex colour replaces MAC (and MAA).
    r.set(GE_CMD_MATERIAL, 1);
    o = r.run(kOrigin, kUp, 255, 0, 0, 64, true);
    EXPECT_EQ(o.c[0], 10 + ((511 * 257) >> 10));  // 138
    EXPECT_EQ(o.c[1], 0);
    EXPECT_EQ(o.c[3], (129 * 257) >> 10);         // 32
    // Without a vertex colour the flag has no effect.
    o = r.run(kOrigin, kUp, 255, 0, 0, 64, false);
    EXPECT_EQ(o.c[0], 110);
}

TEST(GeoLighting, DirectionalDiffuse) {
    Rig r;
    r.light(0, 0, 0, 0, 0, 5);  // direction normalised to (0, 0, 1)
    r.set(GE_CMD_LDC0, Rig::rgb(255, 255, 0));
    r.set(GE_CMD_MDC, Rig::rgb(100, 100, 100));
    // N·L = 1 → s = 512: (511·201·512) >> 19 = 100.
    auto o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.c[0], 100);
    EXPECT_EQ(o.c[1], 100);
    EXPECT_EQ(o.c[2], 0);  // (1·201·512) >> 19
    // N·L = 0.6 → s = ceil(307.2 + 1) = 309: (511·201·309) >> 19 = 60.
    const float n[3] = {0, 0.8f, 0.6f};
    o = r.run(kOrigin, n);
    EXPECT_EQ(o.c[0], 60);
    EXPECT_EQ(o.c[0], term(255, 100, 0.6f));
    // Facing away: no diffuse.
    const float away[3] = {0, 0, -1};
    o = r.run(kOrigin, away);
    EXPECT_EQ(o.c[0], 0);
    // Light disabled: nothing.
    r.set(GE_CMD_LE0, 0);
    EXPECT_EQ(r.run(kOrigin, kUp).c[0], 0);
}

TEST(GeoLighting, LightAmbientAndMaterialDiffuseFromVertex) {
    Rig r;
    r.light(0, 0, 0, 0, 0, 1);
    r.set(GE_CMD_LAC0, Rig::rgb(255, 0, 0));
    r.set(GE_CMD_MAC, Rig::rgb(100, 0, 0));
    r.set(GE_CMD_LDC0, Rig::rgb(0, 255, 0));
    r.set(GE_CMD_MDC, Rig::rgb(0, 50, 0));
    auto o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.c[0], (511 * 201 * 512) >> 19);  // light ambient LAC·MAC, k = 1: 100
    EXPECT_EQ(o.c[1], (511 * 101 * 512) >> 19);  // 50
    r.set(GE_CMD_MATERIAL, 2);                   // diffuse from the vertex colour
    o = r.run(kOrigin, kUp, 0, 200, 0, 255, true);
    EXPECT_EQ(o.c[1], (511 * 401 * 512) >> 19);  // 200
}

TEST(GeoLighting, PointLightAttenuation) {
    Rig r;
    r.light(0, 1, 0, 0, 0, 2);  // point light 2 above the vertex
    r.setf(GE_CMD_LKA0, 1), r.setf(GE_CMD_LKB0, 0.5f), r.setf(GE_CMD_LKC0, 0);
    r.set(GE_CMD_LDC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MDC, Rig::rgb(100, 100, 100));
    // d = 2: att = 1/(1 + 0.5·2) = 0.5; N·L = 1 → k = 0.5 → s = 257: (511·201·257) >> 19 = 50.
    auto o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.c[0], 50);
    // att > 1 is clamped to 1: A = 0.1, B = 0 → 10 → 1.
    r.setf(GE_CMD_LKA0, 0.1f), r.setf(GE_CMD_LKB0, 0);
    EXPECT_EQ(r.run(kOrigin, kUp).c[0], 100);
    // Quadratic term: C = 0.25 → 1/(0.1 + 0.25·4) ≈ 0.909 → s = ceil(465.45 + 1) = 467.
    r.setf(GE_CMD_LKC0, 0.25f);
    EXPECT_EQ(r.run(kOrigin, kUp).c[0], (511 * 201 * 467) >> 19);
    // A directional light ignores attenuation.
    r.set(GE_CMD_LTYPE0, 0);
    EXPECT_EQ(r.run(kOrigin, kUp).c[0], 100);
}

TEST(GeoLighting, SpotLight) {
    Rig r;
    // A spot at (0, 0, 2) lighting the plane below it. LD points from the lit surface toward the
    // light (cos = LD·L, L = light − vertex: what a PSP does, pspautotests gpu/commands/light;
    // the manual's equation 9-4 has the opposite sign). LD need not be normalised.
    r.light(0, 2, 0, 0, 0, 2);
    r.setf(GE_CMD_LDX0, 0), r.setf(GE_CMD_LDY0, 0), r.setf(GE_CMD_LDZ0, 3);
    r.setf(GE_CMD_LKS0, 2), r.setf(GE_CMD_LKO0, 0.5f);
    r.set(GE_CMD_LDC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MDC, Rig::rgb(100, 100, 100));
    // Vertex (1, 0, 0): L = (−1, 0, 2)/√5, cos = 2/√5 ≈ 0.894 ≥ 0.5 → spot = 0.8;
    // L = (−1, 0, 2)/√5, N·L = 0.894; k = 0.8·0.894 = 0.7155 → s = ceil(366.3 + 1) = 368.
    const float p[3] = {1, 0, 0};
    auto o = r.run(p, kUp);
    EXPECT_EQ(o.c[0], (511 * 201 * 368) >> 19);  // 72
    EXPECT_EQ(o.c[0], term(255, 100, 0.8 * 2 / std::sqrt(5.0)));
    // Outside the cone (cutoff 0.95 > 0.894): nothing.
    r.setf(GE_CMD_LKO0, 0.95f);
    EXPECT_EQ(r.run(p, kUp).c[0], 0);
    // Exponent ≤ 0 gives a spot factor of 1 (ge-rules.md §8.9): k = 0.894 → s = ceil(458.0 + 1) = 459.
    r.setf(GE_CMD_LKO0, 0.5f), r.setf(GE_CMD_LKS0, 0);
    EXPECT_EQ(r.run(p, kUp).c[0], (511 * 201 * 459) >> 19);
    // LTYPE type 3 behaves as a spot.
    r.set(GE_CMD_LTYPE0, 0 | 3 << 8);
    EXPECT_EQ(r.run(p, kUp).c[0], (511 * 201 * 459) >> 19);
    // LD pointing away from the light (the manual's reading of "pointing down"): cos = −0.894,
    // outside any cutoff ≥ 0: nothing, ambient included.
    r.set(GE_CMD_LTYPE0, 0 | 2 << 8);
    r.setf(GE_CMD_LDZ0, -3);
    r.set(GE_CMD_LAC0, Rig::rgb(255, 255, 255));
    EXPECT_EQ(r.run(p, kUp).c[0], 0);
}

// Spot directions that cannot be normalised, as a PSP lights them (pspautotests
// gpu/commands/light, tests/conformance/commands_light.cpp): zero → no light, ambient included;
// NaN or infinite components → full spot factor when positive, none when negative.
TEST(GeoLighting, SpotDirectionThatCannotBeNormalised) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Case {
        float d;
        int want;  // 0: no light; 1: as a spot factor of 1
    } cases[] = {{0.0f, 0}, {nan, 1}, {-nan, 0}, {inf, 1}, {-inf, 0}};
    for (const Case& c : cases) {
        Rig r;
        r.light(0, 2, 0, 0, 0, 2);
        r.setf(GE_CMD_LDX0, c.d), r.setf(GE_CMD_LDY0, c.d), r.setf(GE_CMD_LDZ0, c.d);
        r.setf(GE_CMD_LKS0, 1), r.setf(GE_CMD_LKO0, 0);
        r.set(GE_CMD_LAC0, Rig::rgb(255, 255, 255));
        r.set(GE_CMD_MAC, Rig::rgb(100, 100, 100));
        const float p[3] = {0, 0, 0};
        SCOPED_TRACE(c.d);
        EXPECT_EQ(r.run(p, kUp).c[0], c.want ? term(255, 100, 1.0) : 0);
    }
}

TEST(GeoLighting, SpecularSeparateAndSingle) {
    Rig r;
    r.light(0, 0, 1, 0, 0, 1);  // directional, ambient + diffuse + specular
    r.set(GE_CMD_LSC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MSC, Rig::rgb(255, 128, 0));
    r.setf(GE_CMD_MK, 4);
    r.set(GE_CMD_LDC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MDC, Rig::rgb(10, 10, 10));
    // H = normalize((0,0,1) + (0,0,1)) = (0,0,1), (H·N)^4 = 1 → s = 512.
    const int spR = (511 * 511 * 512) >> 19, spG = (511 * 257 * 512) >> 19;  // 254, 128
    const int dif = (511 * 21 * 512) >> 19;                                  // 10
    r.set(GE_CMD_LMODE, 1);
    auto o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.s[0], spR);
    EXPECT_EQ(o.s[1], spG);
    EXPECT_EQ(o.c[0], dif);
    EXPECT_EQ(o.c[1], dif);
    r.set(GE_CMD_LMODE, 0);  // single colour: specular added into the primary
    o = r.run(kOrigin, kUp);
    EXPECT_EQ(o.s[0], 0);
    EXPECT_EQ(o.c[0], 255);  // clamped
    EXPECT_EQ(o.c[1], dif + spG);
    // Normal at 60°: N·L = 0.5, H = (0, 0, 1), H·N = 0.5 → 0.5^4 = 0.0625 → s = ceil(32 + 1) = 33.
    const float n[3] = {0, std::sqrt(3.0f) / 2, 0.5f};
    r.set(GE_CMD_LMODE, 1);
    o = r.run(kOrigin, n);
    EXPECT_EQ(o.s[0], (511 * 511 * 33) >> 19);
    // Specular only when N·L ≥ 0.
    const float away[3] = {0, 0, -1};
    o = r.run(kOrigin, away);
    EXPECT_EQ(o.s[0], 0);
    // Components 0 (ambient + diffuse): no specular.
    r.set(GE_CMD_LTYPE0, 0);
    EXPECT_EQ(r.run(kOrigin, kUp).s[0], 0);
}

TEST(GeoLighting, PoweredDiffuse) {
    Rig r;
    r.light(0, 0, 2, 0, 0, 1);  // powered diffuse
    r.set(GE_CMD_LDC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MDC, Rig::rgb(100, 100, 100));
    r.set(GE_CMD_LSC0, Rig::rgb(255, 255, 255));
    r.set(GE_CMD_MSC, Rig::rgb(255, 255, 255));
    r.setf(GE_CMD_MK, 2);
    r.set(GE_CMD_LMODE, 1);
    // N·L = 0.6 → 0.36 → s = ceil(184.32 + 1) = 186: (511·201·186) >> 19 = 36; no specular.
    const float n[3] = {0, 0.8f, 0.6f};
    auto o = r.run(kOrigin, n);
    EXPECT_EQ(o.c[0], 36);
    EXPECT_EQ(o.s[0], 0);
}

TEST(GeoLighting, PowerSpecialsAndNormalize) {
    EXPECT_EQ(lightPow(0.5f, 0.0f), 1.0f);
    EXPECT_EQ(lightPow(0.5f, -2.0f), 1.0f);
    EXPECT_EQ(lightPow(-0.5f, 2.0f), -0.5f);  // a negative base is not raised
    EXPECT_FLOAT_EQ(lightPow(0.5f, 2.0f), 0.25f);
    float z[3] = {0, 0, 0};
    EXPECT_EQ(normalizeOr001(z), 0.0f);
    EXPECT_EQ(z[2], 1.0f);
    float v[3] = {3, 0, 4};
    EXPECT_FLOAT_EQ(normalizeOr001(v), 5.0f);
    EXPECT_FLOAT_EQ(v[0], 0.6f);
}

TEST(GeoLighting, AllFourLightsAdd) {
    Rig r;
    for (int n = 0; n < 4; ++n) {
        r.light(n, 0, 0, 0, 0, 1);
        r.set(u8(GE_CMD_LDC0 + 3 * n), Rig::rgb(255, 0, 0));
    }
    r.set(GE_CMD_MDC, Rig::rgb(40, 0, 0));
    // Each adds (511·81·512) >> 19 = 40.
    EXPECT_EQ(r.run(kOrigin, kUp).c[0], 4 * ((511 * 81 * 512) >> 19));
}
