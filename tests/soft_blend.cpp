// SPDX-License-Identifier: MIT
// Pixel side of the software model, back end of the pipeline: blending (every equation and factor
// code), dithering + clamp + truncation per format, logic ops, PMSK masks, clear mode.
// Expected values are computed by hand from docs/ge-rules.md §3.10 and §8.3/§8.4/§8.7/§8.8.
#include <gtest/gtest.h>

#include "geometry/reference_rules.h"
#include "hle/pixel_format.h"
#include "soft_pixel_fixture.h"
#include "softmodel/blend.h"
#include "softmodel/framebuffer.h"

using namespace ge;
using namespace ge::soft;
using ge::soft::testing::PixelRig;
using ge::soft::testing::rgba;

namespace {

// The SDK's default dither matrix (ge-rules.md §3.10): rows (−4, 0, −3, 1), (2, −2, 3, −1), (−3, 1, −4, 0),
// (3, −1, 2, −2), one signed nibble per column.
void setSdkDither(PixelRig& rig) {
    rig.set(GE_CMD_DTTH1, 0x1D0C);
    rig.set(GE_CMD_DTTH2, 0xF3E2);
    rig.set(GE_CMD_DTTH3, 0x0C1D);
    rig.set(GE_CMD_DTTH4, 0xE2F3);
}

template <GeBufferFormat F>
void checkFbHelpers() {
    for (u32 v = 0; v < 0x10000; ++v) {
        const Rgba c = Fb<F>::decode(v);
        const u32 ref = decodePixel16(u16(v), F);
        ASSERT_EQ(u32(c.r), ref & 255) << std::hex << v;
        ASSERT_EQ(u32(c.g), (ref >> 8) & 255) << std::hex << v;
        ASSERT_EQ(u32(c.b), (ref >> 16) & 255) << std::hex << v;
        if (F != GE_FORMAT_565) {
            ASSERT_EQ(u32(c.a), ref >> 24) << std::hex << v;  // 5650: Ad = 0 (ge-rules.md §8.8)
        }
    }
    for (u32 i = 0; i < 0x10000; ++i) {
        // A spread of 8-bit RGBA values (every channel value occurs).
        const u32 r = i & 255, g = (i * 7) & 255, b = (i >> 8) & 255, a = (i * 13 + 5) & 255;
        ASSERT_EQ(Fb<F>::encode(int(r), int(g), int(b), int(a)), encodePixel16(rgba(r, g, b, a), F)) << i;
    }
}

}  // namespace

TEST(SoftFramebuffer, InlineHelpersMatchPixelFormat) {
    checkFbHelpers<GE_FORMAT_565>();
    checkFbHelpers<GE_FORMAT_5551>();
    checkFbHelpers<GE_FORMAT_4444>();
    EXPECT_EQ(Fb<GE_FORMAT_565>::decode(0xFFFF).a, 0);
    EXPECT_EQ(Fb<GE_FORMAT_4444>::stencil(0x3000), 0x33);
    EXPECT_EQ(Fb<GE_FORMAT_5551>::stencil(0x8000), 255);
    EXPECT_EQ(Fb<GE_FORMAT_8888>::stencil(0x7F000000), 0x7F);
}

// Cs = (200, 30, 90), As varies; Cd = (100, 50, 200), Ad = 64; FIXA = (10, 20, 30),
// FIXB = (40, 50, 60). term = ((2C + 1)(2F + 1)) >> 10 (ge-rules.md §8.3), results clamped at the end.
struct BlendCase {
    u32 eq, a, b, as;
    u32 r, g, b2;
};
static const BlendCase kBlendCases[] = {
    // Every source factor code with B = FIXB, As = 100 (2·As = 200, 255 − 2·As = 55).
    {0, 0, 10, 100, 93, 15, 117}, {0, 1, 10, 100, 136, 33, 66}, {0, 2, 10, 100, 93, 20, 82},
    {0, 3, 10, 100, 136, 27, 101}, {0, 4, 10, 100, 65, 16, 69}, {0, 5, 10, 100, 164, 31, 114},
    {0, 6, 10, 100, 172, 32, 117}, {0, 7, 10, 100, 58, 15, 66}, {0, 8, 10, 100, 115, 24, 92},
    {0, 9, 10, 100, 114, 24, 92}, {0, 10, 10, 100, 23, 11, 57},
    // Every destination factor code with A = FIXA.
    {0, 10, 0, 100, 86, 8, 80}, {0, 10, 1, 100, 29, 46, 139}, {0, 10, 2, 100, 47, 21, 88},
    {0, 10, 3, 100, 69, 32, 131}, {0, 10, 4, 100, 33, 14, 60}, {0, 10, 5, 100, 83, 39, 159},
    {0, 10, 6, 100, 86, 41, 167}, {0, 10, 7, 100, 29, 12, 53}, {0, 10, 8, 100, 58, 27, 110},
    {0, 10, 9, 100, 58, 27, 109}, {0, 10, 10, 100, 23, 11, 57},
    // As = 200: 2·As = 400 exceeds 255, 255 − 2·As stops at 0.
    {0, 6, 10, 200, 255, 56, 188}, {0, 7, 10, 200, 15, 9, 47}, {0, 10, 6, 200, 165, 81, 255},
    {0, 10, 7, 200, 8, 2, 10}, {0, 6, 8, 200, 255, 72, 241},
    // Codes 11–15 behave as FIXA/FIXB.
    {0, 11, 15, 100, 23, 11, 57},
    // The other equations (A = As, B = 255 − As where they matter).
    {1, 2, 3, 100, 17, 0, 0}, {2, 2, 3, 100, 0, 19, 86}, {3, 2, 3, 100, 100, 30, 90},
    {4, 2, 3, 100, 200, 50, 200}, {5, 2, 3, 100, 100, 20, 110}, {1, 2, 3, 200, 136, 13, 27},
    {2, 2, 3, 200, 0, 0, 0},
    // SUBTRACT below zero becomes 0; REVERSE_SUBTRACT with fixed factors.
    {1, 10, 10, 100, 0, 0, 0}, {2, 10, 10, 100, 7, 7, 37}, {1, 3, 0, 100, 43, 12, 0},
};

TEST(SoftBlend, EveryEquationAndFactor) {
    for (const BlendCase& c : kBlendCases) {
        SCOPED_TRACE(::testing::Message() << "eq " << c.eq << " a " << c.a << " b " << c.b << " As " << c.as);
        PixelRig rig;
        rig.set(GE_CMD_ABE, 1);
        rig.set(GE_CMD_BLEND, c.a | c.b << 4 | c.eq << 8);
        rig.set(GE_CMD_FIXA, 10 | 20 << 8 | 30 << 16);
        rig.set(GE_CMD_FIXB, 40 | 50 << 8 | 60 << 16);
        rig.setPixel(3, 2, rgba(100, 50, 200, 64));
        rig.draw(PixelRig::frag(3, 2, 200, 30, 90, u8(c.as)));
        // Blending never produces alpha; without a stencil test the alpha byte is unchanged (ge-rules.md §8.7).
        EXPECT_EQ(rig.pixel(3, 2), rgba(c.r, c.g, c.b2, 64));
    }
}

TEST(SoftBlend, ResultIsNotClampedBeforeDither) {
    // Cs = 255 with A = FIXA 255: term 255; Cd = 100 with B = FIXB 5: term 2 → 257. Dither −4 at
    // (0, 0) gives 253; clamping first would give 251.
    PixelRig rig;
    setSdkDither(rig);
    rig.set(GE_CMD_DTE, 1);
    rig.set(GE_CMD_ABE, 1);
    rig.set(GE_CMD_BLEND, 10 | 10 << 4);
    rig.set(GE_CMD_FIXA, 0xFFFFFF);
    rig.set(GE_CMD_FIXB, 0x050505);
    rig.setPixel(0, 0, rgba(100, 100, 100, 0));
    rig.draw(PixelRig::frag(0, 0, 255, 255, 255, 0));
    EXPECT_EQ(rig.pixel(0, 0), rgba(253, 253, 253, 0));
}

TEST(SoftBlend, UndefinedEquationsDoNotBlend) {
    for (u32 eq : {6u, 7u}) {
        PixelRig rig;
        rig.set(GE_CMD_ABE, 1);
        rig.set(GE_CMD_BLEND, 10 | 10 << 4 | eq << 8);
        rig.setPixel(1, 1, rgba(1, 2, 3, 4));
        rig.draw(PixelRig::frag(1, 1, 200, 30, 90, 7));
        EXPECT_EQ(rig.pixel(1, 1), rgba(200, 30, 90, 4)) << eq;
    }
}

TEST(SoftBlend, ReadsDestinationByBitReplication) {
    // 5551 Cd: R 0x1F → 255, G 0x10 → 0x84, B 0 → 0, A bit → Ad = 255. Blend ADD, A = FIXA 0,
    // B = Ad (code 4): term(255, 255) = 255, term(0x84, 255) = 132, term(0, 255) = 0.
    PixelRig rig(GE_FORMAT_5551);
    rig.set(GE_CMD_ABE, 1);
    rig.set(GE_CMD_BLEND, 10 | 4 << 4);
    rig.set(GE_CMD_FIXA, 0);
    rig.setPixel(5, 5, 0x8000 | 0x10 << 5 | 0x1F);
    rig.draw(PixelRig::frag(5, 5, 0, 0, 0, 0));
    EXPECT_EQ(rig.pixel(5, 5), 0x8000u | (132u >> 3) << 5 | 0x1Fu);
}

TEST(SoftDither, MatrixAndTruncationPerFormat) {
    // Colour (127, 128, 120) + MATRIX[y & 3][x & 3], clamped, truncated; alpha bits unchanged.
    struct Expect {
        GeBufferFormat fmt;
        u32 oldAlpha;
        u32 values[16];
    };
    const Expect expects[] = {
        {GE_FORMAT_565, 0, {0x73ef, 0x7c0f, 0x73ef, 0x7c10, 0x7c10, 0x73ef, 0x7c10, 0x73ef, 0x73ef, 0x7c10, 0x73ef, 0x7c0f, 0x7c10, 0x73ef, 0x7c10, 0x73ef}},
        {GE_FORMAT_5551, 0x8000, {0xb9ef, 0xbe0f, 0xb9ef, 0xbe10, 0xbe10, 0xb9ef, 0xbe10, 0xb9ef, 0xb9ef, 0xbe10, 0xb9ef, 0xbe0f, 0xbe10, 0xb9ef, 0xbe10, 0xb9ef}},
        {GE_FORMAT_4444, 0xA000, {0xa777, 0xa787, 0xa777, 0xa788, 0xa788, 0xa777, 0xa788, 0xa777, 0xa777, 0xa788, 0xa777, 0xa787, 0xa788, 0xa777, 0xa788, 0xa777}},
        {GE_FORMAT_8888, 0x5A000000, {0x5a747c7b, 0x5a78807f, 0x5a757d7c, 0x5a798180, 0x5a7a8281, 0x5a767e7d, 0x5a7b8382, 0x5a777f7e, 0x5a757d7c, 0x5a798180, 0x5a747c7b, 0x5a78807f, 0x5a7b8382, 0x5a777f7e, 0x5a7a8281, 0x5a767e7d}},
    };
    for (const Expect& e : expects) {
        PixelRig rig(e.fmt);
        setSdkDither(rig);
        rig.set(GE_CMD_DTE, 1);
        std::vector<geo::Fragment> fs;
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                // Drawing at (x + 4, y + 8) uses the same matrix cell as (x, y).
                rig.setPixel(x + 4, y + 8, e.oldAlpha);
                fs.push_back(PixelRig::frag(x + 4, y + 8, 127, 128, 120, 0x33));
            }
        rig.draw(fs);
        for (int i = 0; i < 16; ++i)
            EXPECT_EQ(rig.pixel(4 + i % 4, 8 + i / 4), e.values[i]) << "format " << int(e.fmt) << " cell " << i;
    }
}

TEST(SoftDither, ClampsAfterDither) {
    struct Expect {
        GeBufferFormat fmt;
        u32 oldAlpha, high, low;
    };
    // (254, 253, 0) + 3 at (2, 1) and (2, 3, 255) − 4 at (0, 0).
    const Expect expects[] = {{GE_FORMAT_565, 0, 0x7ff, 0xf800},
                              {GE_FORMAT_5551, 0x8000, 0x83ff, 0xfc00},
                              {GE_FORMAT_4444, 0xA000, 0xa0ff, 0xaf00},
                              {GE_FORMAT_8888, 0x5A000000, 0x5a03ffff, 0x5afb0000}};
    for (const Expect& e : expects) {
        PixelRig rig(e.fmt);
        setSdkDither(rig);
        rig.set(GE_CMD_DTE, 1);
        rig.setPixel(2, 1, e.oldAlpha);
        rig.setPixel(0, 0, e.oldAlpha);
        rig.draw({PixelRig::frag(2, 1, 254, 253, 0, 0), PixelRig::frag(0, 0, 2, 3, 255, 0)});
        EXPECT_EQ(rig.pixel(2, 1), e.high) << int(e.fmt);
        EXPECT_EQ(rig.pixel(0, 0), e.low) << int(e.fmt);
    }
}

TEST(SoftDither, OffMeansPlainTruncation) {
    PixelRig rig(GE_FORMAT_565);
    setSdkDither(rig);  // matrix set but DTE off
    rig.draw(PixelRig::frag(0, 0, 0xFF, 0x7F, 0x08, 0));
    EXPECT_EQ(rig.pixel(0, 0), 0x1Fu | 0x1Fu << 5 | 1u << 11);
}

TEST(SoftLogicOp, All16On8888) {
    const u32 expected[16] = {0xa6000000, 0xa6120c05, 0xa648300a, 0xa65a3c0f, 0xa621c050, 0xa633cc55,
                              0xa669f05a, 0xa67bfc5f, 0xa68403a0, 0xa6960fa5, 0xa6cc33aa, 0xa6de3faf,
                              0xa6a5c3f0, 0xa6b7cff5, 0xa6edf3fa, 0xa6ffffff};
    for (u32 op = 0; op < 16; ++op) {
        PixelRig rig;
        rig.set(GE_CMD_LOE, 1);
        rig.set(GE_CMD_LOP, op);
        rig.setPixel(7, 7, 0xA633CC55);
        rig.draw(PixelRig::frag(7, 7, 0x0F, 0x3C, 0x5A, 0x11));
        EXPECT_EQ(rig.pixel(7, 7), expected[op]) << "op " << op;  // alpha/stencil untouched
    }
}

TEST(SoftLogicOp, All16On5650) {
    // Fragment (0xF0, 0x3C, 0x5A) truncates to 0x59FE; stored 0x9A65; op on the stored bits.
    const u32 expected[16] = {0x0, 0x1864, 0x419a, 0x59fe, 0x8201, 0x9a65, 0xc39b, 0xdbff,
                              0x2400, 0x3c64, 0x659a, 0x7dfe, 0xa601, 0xbe65, 0xe79b, 0xffff};
    for (u32 op = 0; op < 16; ++op) {
        PixelRig rig(GE_FORMAT_565);
        rig.set(GE_CMD_LOE, 1);
        rig.set(GE_CMD_LOP, op);
        rig.setPixel(7, 7, 0x9A65);
        rig.draw(PixelRig::frag(7, 7, 0xF0, 0x3C, 0x5A, 0x11));
        EXPECT_EQ(rig.pixel(7, 7), expected[op]) << "op " << op;
    }
}

TEST(SoftLogicOp, AppliesAfterBlendAndDither) {
    // Blend ADD FIXA 255 / FIXB 0: Cs unchanged (term(c, 255) = c); dither +1 at (3, 0); XOR with
    // Cd 0xFF: (0x10 + 1) ^ 0xFF = 0xEE.
    PixelRig rig;
    setSdkDither(rig);
    rig.set(GE_CMD_DTE, 1);
    rig.set(GE_CMD_ABE, 1);
    rig.set(GE_CMD_BLEND, 10 | 10 << 4);
    rig.set(GE_CMD_FIXA, 0xFFFFFF);
    rig.set(GE_CMD_FIXB, 0);
    rig.set(GE_CMD_LOE, 1);
    rig.set(GE_CMD_LOP, 6);
    rig.setPixel(3, 0, 0x00FFFFFF);
    rig.draw(PixelRig::frag(3, 0, 0x10, 0x10, 0x10, 0));
    EXPECT_EQ(rig.pixel(3, 0), 0x00EEEEEEu);
}

TEST(SoftMask, PlaneMask8888) {
    PixelRig rig;
    rig.set(GE_CMD_PMSK1, 0x0000FF | 0x0F << 8);  // keep R entirely, low nibble of G
    rig.setPixel(0, 0, 0x44332211);
    rig.draw(PixelRig::frag(0, 0, 0xAA, 0xBB, 0xCC, 0xDD));
    EXPECT_EQ(rig.pixel(0, 0), 0x44CCB211u);
}

TEST(SoftMask, PlaneMaskConvertedByTruncation5650) {
    // PMSK1 G byte 0x07 → 6-bit 0x01 (protects G bit 0 = raw bit 5); B byte 0xF8 → 0x1F; R 0x07 → 0.
    PixelRig rig(GE_FORMAT_565);
    rig.set(GE_CMD_PMSK1, 0x07 | 0x07 << 8 | 0xF8 << 16);
    rig.setPixel(0, 0, 0xFFFF);
    rig.draw(PixelRig::frag(0, 0, 0, 0, 0, 0));
    EXPECT_EQ(rig.pixel(0, 0), (1u << 5) | (0x1Fu << 11));
}

TEST(SoftMask, AlphaMaskProtectsStencilBits) {
    // Stencil test ALWAYS, ZPASS REPLACE with ref 0xFF; PMSK2 0x0F keeps the low stencil nibble.
    PixelRig rig;
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 1 | 0xFF << 8 | 0xFF << 16);
    rig.set(GE_CMD_SOP, 2 << 16);
    rig.set(GE_CMD_PMSK2, 0x0F);
    rig.setPixel(0, 0, 0x35000000);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4));
    EXPECT_EQ(rig.pixel(0, 0), 0xF5030201u);
}

TEST(SoftClear, ColourAlphaDepthFlags) {
    struct Case {
        u32 flags;  // CEN 1, AEN 2, ZEN 4
        u32 pixel;
        u16 depth;
    };
    const Case cases[] = {{0, 0x44332211, 1000}, {1, 0x44CCBBAA, 1000}, {2, 0xDD332211, 1000},
                          {4, 0x44332211, 7},    {7, 0xDDCCBBAA, 7}};
    for (const Case& c : cases) {
        PixelRig rig;
        rig.set(GE_CMD_CMODE, 1 | c.flags << 8);
        rig.set(GE_CMD_VTYPE, 1u << 23);  // through mode, as sceGuClear draws
        rig.setPixel(9, 9, 0x44332211);
        rig.setDepth(9, 9, 1000);
        rig.draw(PixelRig::frag(9, 9, 0xAA, 0xBB, 0xCC, 0xDD, 7));
        EXPECT_EQ(rig.pixel(9, 9), c.pixel) << c.flags;
        EXPECT_EQ(rig.depth(9, 9), c.depth) << c.flags;
    }
}

TEST(SoftClear, IgnoresTestsBlendLogicAndTexture) {
    PixelRig rig;
    rig.set(GE_CMD_CMODE, 1 | 7 << 8);
    rig.set(GE_CMD_VTYPE, 1u << 23);
    rig.set(GE_CMD_ATE, 1);
    rig.set(GE_CMD_ATEST, 0);  // NEVER
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, 0);
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 0);
    rig.set(GE_CMD_CTE, 1);
    rig.set(GE_CMD_CTEST, 0);
    rig.set(GE_CMD_ABE, 1);
    rig.set(GE_CMD_BLEND, 10 | 10 << 4);
    rig.set(GE_CMD_LOE, 1);
    rig.set(GE_CMD_LOP, 0);
    rig.set(GE_CMD_FGE, 1);
    rig.set(GE_CMD_ZMSK, 1);  // clear writes depth by ZEN alone
    rig.draw(PixelRig::frag(2, 2, 0xAA, 0xBB, 0xCC, 0xDD, 0x1234), /*texture=*/true);
    EXPECT_EQ(rig.pixel(2, 2), 0xDDCCBBAAu);
    EXPECT_EQ(rig.depth(2, 2), 0x1234);
}

TEST(SoftClear, DitherMasksAndDepthRangeStillApply) {
    PixelRig rig;
    setSdkDither(rig);
    rig.set(GE_CMD_DTE, 1);
    rig.set(GE_CMD_CMODE, 1 | 7 << 8);
    rig.set(GE_CMD_PMSK1, 0xFF0000);  // keep B
    rig.set(GE_CMD_PMSK2, 0xF0);
    rig.set(GE_CMD_MINZ, 100);
    rig.set(GE_CMD_MAXZ, 200);
    rig.setPixel(1, 1, 0x12345678);
    rig.setPixel(0, 0, 0x12345678);
    // Not through mode: z = 50 fails the depth range test even in clear mode (ge-rules.md §8.4).
    rig.draw({PixelRig::frag(1, 1, 0x40, 0x40, 0x40, 0xAB, 150), PixelRig::frag(0, 0, 0x40, 0x40, 0x40, 0xAB, 50)});
    // (1, 1): dither −2 → 0x3E; B kept 0x34; alpha (0x12 & 0xF0) | (0xAB & 0x0F) = 0x1B.
    EXPECT_EQ(rig.pixel(1, 1), 0x1B343E3Eu);
    EXPECT_EQ(rig.depth(1, 1), 150);
    EXPECT_EQ(rig.pixel(0, 0), 0x12345678u);
    EXPECT_EQ(rig.depth(0, 0), 0);
    // Through mode skips the depth range test.
    rig.set(GE_CMD_VTYPE, 1u << 23);
    rig.draw(PixelRig::frag(0, 0, 0x40, 0x40, 0x40, 0xAB, 50));
    EXPECT_EQ(rig.depth(0, 0), 50);
}

TEST(SoftClear, NoAlphaIn5650) {
    PixelRig rig(GE_FORMAT_565);
    rig.set(GE_CMD_CMODE, 1 | 2 << 8);  // AEN only: nothing to write in 5650
    rig.set(GE_CMD_VTYPE, 1u << 23);
    rig.setPixel(0, 0, 0x1234);
    rig.draw(PixelRig::frag(0, 0, 0xFF, 0xFF, 0xFF, 0xFF));
    EXPECT_EQ(rig.pixel(0, 0), 0x1234u);
}

// The reference renderer's implicit "alpha != 0" test (geometry/reference_rules.h referenceDropsZeroAlpha,
// PPSSPP Rasterizer.cpp OPTIMIZED_ALPHATEST_ON): with A = As, B = 1 − As, no depth write and no
// stencil test, an alpha-0 fragment leaves the pixel alone even though dithering would change it.
// Values from Monster Hunter 3rd's HUD: 5650 Cd = (24, 53, 23) → (198, 215, 189); at (2, 1) the SDK
// matrix adds 3, which would store (201, 218, 192) → (25, 54, 24).
TEST(SoftBlend, ZeroAlphaSourceAlphaBlendSkipsDither) {
    const u32 before = 24u | 53u << 5 | 23u << 11, dithered = 25u | 54u << 5 | 24u << 11;
    for (bool depthWrite : {false, true}) {
        PixelRig rig(GE_FORMAT_565);
        setSdkDither(rig);
        rig.set(GE_CMD_DTE, 1);
        rig.set(GE_CMD_ABE, 1);
        rig.set(GE_CMD_BLEND, 2 | 3 << 4);
        if (depthWrite) {
            rig.set(GE_CMD_ZTE, 1);
            rig.set(GE_CMD_ZTEST, 1);  // ALWAYS, writing depth: the reference draws the fragment
        }
        rig.setPixel(2, 1, before);
        rig.draw(PixelRig::frag(2, 1, 0, 1, 1, 0));
        EXPECT_EQ(rig.pixel(2, 1), depthWrite ? dithered : before) << depthWrite;
    }
}

TEST(SoftBlend, ZeroAlphaRuleConditions) {
    PixelRig rig(GE_FORMAT_8888);
    rig.set(GE_CMD_ABE, 1);
    rig.set(GE_CMD_BLEND, 2 | 3 << 4);
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_BLEND, 2 | 10 << 4);  // B = FIXB
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_BLEND, 2 | 3 << 4 | 1 << 8);  // any equation 0–5 counts
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ABE, 0);
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ABE, 1);

    // Alpha test: a real one keeps its own function; GEQUAL 0 counts as off.
    rig.set(GE_CMD_ATE, 1);
    rig.set(GE_CMD_ATEST, 6 | 0x10 << 8 | 0xFF << 16);
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ATEST, 7 | 0 << 8 | 0xFF << 16);
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ATE, 0);

    // Depth writes and stencil tests turn it off; ZMSK (no write) does not.
    rig.set(GE_CMD_ZTE, 1);
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ZMSK, 1);
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_ZTE, 0);
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 2);  // EQUAL
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_STEST, 1);  // ALWAYS with KEEP everywhere: no effective stencil test
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));
    rig.set(GE_CMD_STE, 0);

    // A CLUT texture whose palette has only full alphas cannot give alpha 0 (as the reference
    // reasons); one zero-alpha entry (and a zero AND of the entries) brings the rule back.
    rig.set(GE_CMD_TPF, GE_TFMT_CLUT8);
    rig.set(GE_CMD_CLUT, 3 | 0xFF << 8);
    for (u32 i = 0; i < 256; ++i) writeLE32(rig.st.clut + 4 * i, 0xFF000000u | i);
    EXPECT_FALSE(geo::referenceDropsZeroAlpha(rig.st, true));
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, false));  // untextured: palette irrelevant
    writeLE32(rig.st.clut + 4 * 5, 0x00000000u);
    EXPECT_TRUE(geo::referenceDropsZeroAlpha(rig.st, true));
}
