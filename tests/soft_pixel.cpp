// SPDX-License-Identifier: MIT
// Pixel side of the software model, front of the pipeline: texture functions (with doubling and
// secondary colour), fog, the depth-range/alpha/colour/stencil/depth tests, every stencil op per
// format, and the stage order of docs/ge-rules.md §8.4. Expected values are computed by hand from
// ge-rules.md §8.3 and §8.7.
#include <gtest/gtest.h>

#include <thread>

#include "soft_pixel_fixture.h"

using namespace ge;
using namespace ge::soft;
using ge::soft::testing::PixelRig;
using ge::soft::testing::rgba;

namespace {

constexpr u32 kSentinel = 0x5A5A5A5A;

// A 1×1 8888 texture holding T = (200, 100, 50, 128) and TEC = (10, 20, 255).
void setupTexel(PixelRig& rig, u32 func, bool tcc, bool dbl) {
    rig.texture8888(0, PixelRig::kTex, 0, 0, {rgba(200, 100, 50, 128)});
    rig.set(GE_CMD_TME, 1);
    rig.set(GE_CMD_TFUNC, func | (tcc ? 1u << 8 : 0) | (dbl ? 1u << 16 : 0));
    rig.set(GE_CMD_TEC, 10 | 20 << 8 | 255 << 16);
}

geo::Fragment texFrag(u8 r, u8 g, u8 b, u8 a) {
    geo::Fragment f = PixelRig::frag(4, 4, r, g, b, a);
    f.s = 0.5f;
    f.t = 0.5f;
    return f;
}

// Draws one textured fragment with the alpha test set to `func` against `alphaRef`.
u32 drawWithAlphaTest(PixelRig& rig, const geo::Fragment& f, u32 func, u32 alphaRef) {
    rig.set(GE_CMD_ATE, 1);
    rig.set(GE_CMD_ATEST, func | alphaRef << 8 | 0xFF << 16);
    rig.setPixel(f.x, f.y, kSentinel);
    rig.draw(f, true);
    return rig.pixel(f.x, f.y);
}

}  // namespace

// P = (100, 150, 250, 60) [second block: (10, 20, 30, 60)], T = (200, 100, 50, 128),
// TEC = (10, 20, 255). Cv from ge-rules.md §8.3: MODULATE (P+1)·T >> 8, DECAL/BLEND as listed, doubling
// inside the function; RGB clamped after. The alpha is observed through the alpha test.
struct TexFuncCase {
    u32 func;
    bool tcc, dbl;
    u8 p[4];
    u32 r, g, b, a;
};
static const TexFuncCase kTexFuncCases[] = {
    {0, false, false, {100, 150, 250, 60}, 78, 58, 49, 60},
    {0, false, true, {100, 150, 250, 60}, 157, 117, 98, 60},
    {0, true, false, {100, 150, 250, 60}, 78, 58, 49, 30},
    {0, true, true, {100, 150, 250, 60}, 157, 117, 98, 30},
    {1, false, false, {100, 150, 250, 60}, 200, 100, 50, 60},
    {1, false, true, {100, 150, 250, 60}, 255, 200, 100, 60},
    {1, true, false, {100, 150, 250, 60}, 150, 125, 150, 60},
    {1, true, true, {100, 150, 250, 60}, 255, 250, 255, 60},
    {2, false, false, {100, 150, 250, 60}, 30, 99, 250, 60},
    {2, false, true, {100, 150, 250, 60}, 60, 199, 255, 60},
    {2, true, false, {100, 150, 250, 60}, 30, 99, 250, 30},
    {2, true, true, {100, 150, 250, 60}, 60, 199, 255, 30},
    {3, false, false, {100, 150, 250, 60}, 200, 100, 50, 60},
    {3, false, true, {100, 150, 250, 60}, 255, 200, 100, 60},
    {3, true, false, {100, 150, 250, 60}, 200, 100, 50, 128},
    {3, true, true, {100, 150, 250, 60}, 255, 200, 100, 128},
    {4, false, false, {10, 20, 30, 60}, 210, 120, 80, 60},
    {4, false, true, {10, 20, 30, 60}, 255, 240, 160, 60},
    {4, true, false, {10, 20, 30, 60}, 210, 120, 80, 30},
    {4, true, true, {10, 20, 30, 60}, 255, 240, 160, 30},
    // Codes 5–7 behave as ADD.
    {5, true, false, {10, 20, 30, 60}, 210, 120, 80, 30},
    {7, false, true, {10, 20, 30, 60}, 255, 240, 160, 60},
};

TEST(SoftTexFunc, EveryFunctionTccAndDoubling) {
    for (const TexFuncCase& c : kTexFuncCases) {
        SCOPED_TRACE(::testing::Message() << "func " << c.func << " tcc " << c.tcc << " double " << c.dbl);
        PixelRig rig;
        setupTexel(rig, c.func, c.tcc, c.dbl);
        const geo::Fragment f = texFrag(c.p[0], c.p[1], c.p[2], c.p[3]);
        // Alpha EQUAL to the expected Av draws (and shows RGB); NOTEQUAL must not draw.
        EXPECT_EQ(drawWithAlphaTest(rig, f, 2, c.a), rgba(c.r, c.g, c.b, 0x5A));
        EXPECT_EQ(drawWithAlphaTest(rig, f, 3, c.a), kSentinel);
    }
}

TEST(SoftTexFunc, SecondaryColourAddedAfterFunctionAndNotDoubled) {
    {
        PixelRig rig;
        setupTexel(rig, 0, false, false);
        geo::Fragment f = texFrag(100, 150, 250, 60);
        f.secondary[0] = 5;
        f.secondary[1] = 10;
        f.secondary[2] = 255;
        rig.draw(f, true);
        EXPECT_EQ(rig.pixel(4, 4), rgba(83, 68, 255, 0));
    }
    {
        PixelRig rig;
        setupTexel(rig, 0, false, true);
        geo::Fragment f = texFrag(100, 150, 250, 60);
        f.secondary[0] = 5;
        f.secondary[1] = 10;
        rig.draw(f, true);
        EXPECT_EQ(rig.pixel(4, 4), rgba(162, 127, 98, 0));
    }
}

TEST(SoftTexFunc, UntexturedIsPrimaryPlusSecondaryAndNeverDoubled) {
    PixelRig rig;
    rig.set(GE_CMD_TFUNC, 1u << 16);  // doubling has no effect without texturing (ge-rules.md §8.13)
    geo::Fragment f = PixelRig::frag(0, 0, 250, 10, 0, 9);
    f.secondary[0] = 10;
    f.secondary[1] = 5;
    rig.draw(f, false);
    EXPECT_EQ(rig.pixel(0, 0), rgba(255, 15, 0, 0));
    // TME set but the caller says untextured (e.g. vertices without UVs): no texture function.
    rig.set(GE_CMD_TME, 1);
    rig.texture8888(0, PixelRig::kTex, 0, 0, {rgba(1, 2, 3, 4)});
    rig.draw(PixelRig::frag(1, 0, 7, 8, 9, 10), false);
    EXPECT_EQ(rig.pixel(1, 0), rgba(7, 8, 9, 0));
}

TEST(SoftFog, FormulaAndEnables) {
    // (C·f + FC·(255 − f) + 255) >> 8 with FC = (0, 128, 255).
    PixelRig rig;
    rig.set(GE_CMD_FGE, 1);
    rig.set(GE_CMD_FC, 0 | 128 << 8 | 255 << 16);
    geo::Fragment f = PixelRig::frag(0, 0, 200, 50, 30, 0);
    f.fog = 100;
    geo::Fragment none = PixelRig::frag(1, 0, 200, 50, 30, 0);  // f = 255: unchanged
    geo::Fragment full = PixelRig::frag(2, 0, 200, 50, 30, 0);
    full.fog = 0;
    rig.draw({f, none, full});
    EXPECT_EQ(rig.pixel(0, 0), rgba(79, 98, 167, 0));
    EXPECT_EQ(rig.pixel(1, 0), rgba(200, 50, 30, 0));
    EXPECT_EQ(rig.pixel(2, 0), rgba(0, 128, 255, 0));
    // Through mode: no fog.
    rig.set(GE_CMD_VTYPE, 1u << 23);
    f.x = 3;
    rig.draw(f);
    EXPECT_EQ(rig.pixel(3, 0), rgba(200, 50, 30, 0));
    // FGE off: no fog.
    rig.set(GE_CMD_VTYPE, 0);
    rig.set(GE_CMD_FGE, 0);
    f.x = 4;
    rig.draw(f);
    EXPECT_EQ(rig.pixel(4, 0), rgba(200, 50, 30, 0));
}

// Pass/fail of the comparison codes for a value against 100 at 99, 100, 101.
static const bool kCompareTable[8][3] = {
    {false, false, false},  // NEVER
    {true, true, true},     // ALWAYS
    {false, true, false},   // EQUAL
    {true, false, true},    // NOTEQUAL
    {true, false, false},   // LESS
    {true, true, false},    // LEQUAL
    {false, false, true},   // GREATER
    {false, true, true},    // GEQUAL
};

TEST(SoftTests, AlphaTestEveryFunction) {
    for (u32 func = 0; func < 8; ++func)
        for (int k = 0; k < 3; ++k) {
            PixelRig rig;
            rig.set(GE_CMD_ATE, 1);
            rig.set(GE_CMD_ATEST, func | 100 << 8 | 0xFF << 16);
            rig.setPixel(0, 0, kSentinel);
            rig.draw(PixelRig::frag(0, 0, 1, 2, 3, u8(99 + k)));
            EXPECT_EQ(rig.pixel(0, 0) != kSentinel, kCompareTable[func][k]) << "func " << func << " alpha " << 99 + k;
        }
    // Both sides masked: 0x5F & 0xF0 == 0x50 & 0xF0; 0x4F & 0xF0 < 0x5A & 0xF0.
    PixelRig rig;
    rig.set(GE_CMD_ATE, 1);
    rig.set(GE_CMD_ATEST, 2 | 0x5A << 8 | 0xF0 << 16);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 0x5F));
    EXPECT_EQ(rig.pixel(0, 0), rgba(1, 2, 3, 0));
    rig.set(GE_CMD_ATEST, 4 | 0x5A << 8 | 0xF0 << 16);
    rig.draw(PixelRig::frag(1, 0, 1, 2, 3, 0x4F));
    EXPECT_EQ(rig.pixel(1, 0), rgba(1, 2, 3, 0));
}

TEST(SoftTests, ColourTestEveryFunction) {
    // CREF (0x10, 0x20, 0x30), CMSK 0xF0F0F0: (0x1F, 0x2A, 0x35) matches, (0x1F, 0x4A, 0x35) not.
    const bool expectMatch[4] = {false, true, true, false}, expectOther[4] = {false, true, false, true};
    for (u32 func = 0; func < 4; ++func) {
        PixelRig rig;
        rig.set(GE_CMD_CTE, 1);
        rig.set(GE_CMD_CTEST, func);
        rig.set(GE_CMD_CREF, 0x10 | 0x20 << 8 | 0x30 << 16);
        rig.set(GE_CMD_CMSK, 0xF0F0F0);
        rig.setPixel(0, 0, kSentinel);
        rig.setPixel(1, 0, kSentinel);
        rig.draw({PixelRig::frag(0, 0, 0x1F, 0x2A, 0x35, 0), PixelRig::frag(1, 0, 0x1F, 0x4A, 0x35, 0)});
        EXPECT_EQ(rig.pixel(0, 0) != kSentinel, expectMatch[func]) << func;
        EXPECT_EQ(rig.pixel(1, 0) != kSentinel, expectOther[func]) << func;
    }
}

TEST(SoftTests, StencilTestEveryFunction) {
    // Stored stencil 100 (8888 alpha byte); test is (ref & mask) OP (stored & mask) with the refs
    // 99, 100, 101 — so LESS passes for ref 99 (ref < stored, the emulators' order, ge-rules.md §8.7).
    for (u32 func = 0; func < 8; ++func)
        for (int k = 0; k < 3; ++k) {
            PixelRig rig;
            rig.set(GE_CMD_STE, 1);
            rig.set(GE_CMD_STEST, func | u32(99 + k) << 8 | 0xFF << 16);
            rig.set(GE_CMD_SOP, 0);  // KEEP everywhere
            rig.setPixel(0, 0, 0x64000000);
            rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4));
            const bool pass = kCompareTable[func][k];  // ref (99 + k) OP stored (100)
            EXPECT_EQ(rig.pixel(0, 0), pass ? 0x64030201u : 0x64000000u) << "func " << func << " ref " << 99 + k;
        }
}

TEST(SoftTests, DepthTestEveryFunctionAndWriteMask) {
    for (u32 func = 0; func < 8; ++func)
        for (int k = 0; k < 3; ++k) {
            PixelRig rig;
            rig.set(GE_CMD_ZTE, 1);
            rig.set(GE_CMD_ZTEST, func);
            rig.setDepth(0, 0, 100);
            rig.setPixel(0, 0, kSentinel);
            rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4, u16(99 + k)));
            const bool pass = kCompareTable[func][k];
            EXPECT_EQ(rig.pixel(0, 0) != kSentinel, pass) << "func " << func << " z " << 99 + k;
            EXPECT_EQ(rig.depth(0, 0), pass ? 99 + k : 100) << "func " << func << " z " << 99 + k;
        }
    // ZMSK: colour drawn, depth kept. ZTE off: no test and no depth write.
    PixelRig rig;
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, 1);
    rig.set(GE_CMD_ZMSK, 1);
    rig.setDepth(0, 0, 100);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4, 500));
    EXPECT_EQ(rig.pixel(0, 0), rgba(1, 2, 3, 0));
    EXPECT_EQ(rig.depth(0, 0), 100);
    rig.set(GE_CMD_ZMSK, 0);
    rig.set(GE_CMD_ZTE, 0);
    rig.set(GE_CMD_ZTEST, 0);  // NEVER, but the test is off
    rig.draw(PixelRig::frag(1, 0, 1, 2, 3, 4, 500));
    EXPECT_EQ(rig.pixel(1, 0), rgba(1, 2, 3, 0));
    EXPECT_EQ(rig.depth(1, 0), 0);
}

TEST(SoftTests, DepthRangeOutsideThroughModeOnly) {
    PixelRig rig;
    rig.set(GE_CMD_MINZ, 100);
    rig.set(GE_CMD_MAXZ, 200);
    rig.setPixel(0, 0, kSentinel);
    rig.setPixel(1, 0, kSentinel);
    rig.setPixel(2, 0, kSentinel);
    rig.draw({PixelRig::frag(0, 0, 1, 2, 3, 4, 99), PixelRig::frag(1, 0, 1, 2, 3, 4, 100),
              PixelRig::frag(2, 0, 1, 2, 3, 4, 201)});
    EXPECT_EQ(rig.pixel(0, 0), kSentinel);
    EXPECT_EQ(rig.pixel(1, 0), rgba(1, 2, 3, 0x5A));
    EXPECT_EQ(rig.pixel(2, 0), kSentinel);
    rig.set(GE_CMD_VTYPE, 1u << 23);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4, 99));
    EXPECT_EQ(rig.pixel(0, 0), rgba(1, 2, 3, 0x5A));
}

// ---- Stencil operations per format (ge-rules.md §8.7) ----

enum class Path { SFail, ZFail, ZPass };

// Runs one stencil op through one of the three paths on a pixel whose stored value is `stored`
// (raw frame-buffer bits) and returns the stored value afterwards.
u32 runStencilOp(GeBufferFormat fmt, Path path, u32 op, u32 stored, u32 ref, u32 mask = 0xFF) {
    PixelRig rig(fmt);
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, (path == Path::SFail ? 0u : 1u) | ref << 8 | mask << 16);
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, path == Path::ZFail ? 0 : 1);
    const u32 sop = path == Path::SFail ? op : path == Path::ZFail ? op << 8 : op << 16;
    rig.set(GE_CMD_SOP, sop);
    rig.setPixel(0, 0, stored);
    rig.draw(PixelRig::frag(0, 0, 0, 0, 0, 0x33, 5));
    return rig.pixel(0, 0);
}

TEST(SoftStencil, OpsOn8888) {
    // Stored 0x7F, ref 0xAB with test mask 0x0F (REPLACE ignores the mask). Colour bits: the
    // failing paths leave RGB 0x123456; ZPASS writes the fragment's (0, 0, 0).
    const u32 ops[8] = {0x7F, 0x00, 0xAB, 0x80, 0x80, 0x7E, 0x7F, 0x7F};  // KEEP … DECR, 6, 7
    for (u32 op = 0; op < 8; ++op) {
        EXPECT_EQ(runStencilOp(GE_FORMAT_8888, Path::SFail, op, 0x7F123456, 0xAB, 0x0F), ops[op] << 24 | 0x123456) << op;
        EXPECT_EQ(runStencilOp(GE_FORMAT_8888, Path::ZFail, op, 0x7F123456, 0xAB, 0x0F), ops[op] << 24 | 0x123456) << op;
        EXPECT_EQ(runStencilOp(GE_FORMAT_8888, Path::ZPass, op, 0x7F123456, 0xAB, 0x0F), ops[op] << 24) << op;
    }
    // Saturation: INCR at 255, DECR at 0.
    EXPECT_EQ(runStencilOp(GE_FORMAT_8888, Path::ZPass, 4, 0xFF000000, 0), 0xFF000000u);
    EXPECT_EQ(runStencilOp(GE_FORMAT_8888, Path::ZPass, 5, 0x00000000, 0), 0x00000000u);
}

TEST(SoftStencil, OpsOn4444) {
    // Stored nibble 7 (reads 0x77): INVERT 0x88 → 8; INCR 0x87 → 8; DECR 0x67 → 6; REPLACE 0xAB → A.
    const u32 ops[6] = {0x7, 0x0, 0xA, 0x8, 0x8, 0x6};
    for (u32 op = 0; op < 6; ++op) {
        EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::SFail, op, 0x7123, 0xAB), ops[op] << 12 | 0x123) << op;
        EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::ZFail, op, 0x7123, 0xAB), ops[op] << 12 | 0x123) << op;
        EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::ZPass, op, 0x7123, 0xAB), ops[op] << 12) << op;
    }
    EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::ZPass, 4, 0xF000, 0), 0xF000u);  // saturates
    EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::ZPass, 5, 0x0000, 0), 0x0000u);
    EXPECT_EQ(runStencilOp(GE_FORMAT_4444, Path::ZPass, 4, 0xE000, 0), 0xF000u);
}

TEST(SoftStencil, OpsOn5551) {
    // One bit: reads 0 or 255; INCR → 1, DECR → 0, INVERT flips, REPLACE takes bit 7 of ref.
    struct Case {
        u32 op, stored, ref, expectBit;
    };
    const Case cases[] = {{0, 1, 0, 1}, {1, 1, 0, 0}, {2, 0, 0xAB, 1}, {2, 1, 0x2B, 0}, {3, 1, 0, 0},
                          {3, 0, 0, 1}, {4, 0, 0, 1},   {4, 1, 0, 1},    {5, 1, 0, 0},    {5, 0, 0, 0}};
    for (const Case& c : cases) {
        const u32 stored = c.stored << 15 | 0x1234;
        EXPECT_EQ(runStencilOp(GE_FORMAT_5551, Path::SFail, c.op, stored, c.ref), c.expectBit << 15 | 0x1234) << c.op;
        EXPECT_EQ(runStencilOp(GE_FORMAT_5551, Path::ZPass, c.op, stored, c.ref), c.expectBit << 15) << c.op;
    }
}

TEST(SoftStencil, NoStencilIn5650) {
    // Stencil reads 0 (EQUAL 0 passes), REPLACE has nowhere to go; colour is written.
    PixelRig rig(GE_FORMAT_565);
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 2 | 0 << 8 | 0xFF << 16);
    rig.set(GE_CMD_SOP, 2 << 16);
    rig.setPixel(0, 0, 0xFFFF);
    rig.draw(PixelRig::frag(0, 0, 0, 0, 0, 0xFF));
    EXPECT_EQ(rig.pixel(0, 0), 0u);
    rig.set(GE_CMD_STEST, 2 | 1 << 8 | 0xFF << 16);  // EQUAL 1 fails against 0
    rig.setPixel(1, 0, 0xFFFF);
    rig.draw(PixelRig::frag(1, 0, 0, 0, 0, 0xFF));
    EXPECT_EQ(rig.pixel(1, 0), 0xFFFFu);
}

TEST(SoftStencil, DepthTestOffMeansZPass) {
    PixelRig rig;
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 1 | 0xFF << 16);
    rig.set(GE_CMD_SOP, 1 << 8 | 4 << 16);  // ZFAIL ZERO, ZPASS INCR
    rig.setPixel(0, 0, 0x10000000);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4));
    EXPECT_EQ(rig.pixel(0, 0), 0x11030201u);
}

// ---- Stage order (ge-rules.md §8.4) ----

TEST(SoftOrder, AlphaTestBeforeStencilOps) {
    // Alpha test fails → no SFAIL/ZPASS op runs.
    PixelRig rig;
    rig.set(GE_CMD_ATE, 1);
    rig.set(GE_CMD_ATEST, 0);
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 0 | 0xFF << 16);
    rig.set(GE_CMD_SOP, 1 | 1 << 8 | 1 << 16);
    rig.setPixel(0, 0, 0x80000000);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4));
    EXPECT_EQ(rig.pixel(0, 0), 0x80000000u);
}

TEST(SoftOrder, StencilFailSkipsDepthWrite) {
    PixelRig rig;
    rig.set(GE_CMD_STE, 1);
    rig.set(GE_CMD_STEST, 0);  // NEVER
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, 1);
    rig.setDepth(0, 0, 100);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4, 50));
    EXPECT_EQ(rig.depth(0, 0), 100);
}

TEST(SoftOrder, DepthWrittenEvenWhenColourMasked) {
    PixelRig rig;
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, 1);
    rig.set(GE_CMD_PMSK1, 0xFFFFFF);
    rig.setPixel(0, 0, kSentinel);
    rig.draw(PixelRig::frag(0, 0, 1, 2, 3, 4, 77));
    EXPECT_EQ(rig.pixel(0, 0), kSentinel);
    EXPECT_EQ(rig.depth(0, 0), 77);
}

TEST(SoftOrder, ColourTestSeesFoggedColour) {
    // Fog with f = 0 turns the colour into FC = (9, 9, 9); the colour test compares against that.
    PixelRig rig;
    rig.set(GE_CMD_FGE, 1);
    rig.set(GE_CMD_FC, 0x090909);
    rig.set(GE_CMD_CTE, 1);
    rig.set(GE_CMD_CTEST, 2);
    rig.set(GE_CMD_CREF, 0x090909);
    rig.set(GE_CMD_CMSK, 0xFFFFFF);
    geo::Fragment f = PixelRig::frag(0, 0, 200, 200, 200, 0);
    f.fog = 0;
    rig.draw(f);
    EXPECT_EQ(rig.pixel(0, 0), rgba(9, 9, 9, 0));
}

TEST(SoftOrder, TextureFunctionFeedsAlphaTest) {
    // REPLACE with TCC: alpha comes from the texel (128), not the vertex (60).
    PixelRig rig;
    setupTexel(rig, 3, true, false);
    EXPECT_EQ(drawWithAlphaTest(rig, texFrag(100, 150, 250, 60), 2, 128), rgba(200, 100, 50, 0x5A));
}

// ---- Robustness ----

TEST(SoftRobustness, FragmentsOutsideBuffersAreDropped) {
    PixelRig rig;
    // Frame buffer 256 bytes before the end of VRAM: 64 pixels of 8888 remain.
    rig.set(GE_CMD_FBP, 0x1FFF00);
    rig.set(GE_CMD_ZBP, 0x1FFFC0);  // 32 depth pixels
    rig.set(GE_CMD_ZTE, 1);
    rig.set(GE_CMD_ZTEST, 1);
    PixelState ps = buildPixelState(rig.st, rig.mem, *rig.cache, geo::AccuracyProfile::ppsspp(), false);
    EXPECT_EQ(ps.fbMaxY, 1);
    std::vector<geo::Fragment> fs = {PixelRig::frag(0, 0, 1, 2, 3, 4), PixelRig::frag(63, 0, 1, 2, 3, 4),
                                PixelRig::frag(64, 0, 1, 2, 3, 4), PixelRig::frag(0, 1, 1, 2, 3, 4),
                                PixelRig::frag(-1, 0, 1, 2, 3, 4), PixelRig::frag(0, 100000, 1, 2, 3, 4)};
    shadeFragments(ps, fs.data(), fs.size());
    EXPECT_EQ(rig.mem.read32(0x041FFF00), rgba(1, 2, 3, 0));
    // (63, 0) has a colour pixel but its depth pixel would be past VRAM.
    EXPECT_EQ(rig.mem.read32(0x041FFF00 + 63 * 4), 0u);
    EXPECT_EQ(rig.mem.badAccesses(), 0u);
}

TEST(SoftThreads, DisjointRowsFromSeveralThreadsMatchOneThread) {
    // One PixelState shared read-only by four threads shading disjoint rows (as the renderer's
    // bands do) must give exactly the single-threaded frame buffer.
    auto setup = [](PixelRig& rig) {
        std::vector<u32> texels(16 * 16);
        for (u32 i = 0; i < texels.size(); ++i) texels[i] = i * 2654435761u;
        rig.texture8888(0, PixelRig::kTex, 4, 4, texels);
        rig.set(GE_CMD_TME, 1);
        rig.set(GE_CMD_TFUNC, 0 | 1 << 8);
        rig.set(GE_CMD_TFILTER, 1 | 1 << 8);
        rig.set(GE_CMD_ABE, 1);
        rig.set(GE_CMD_BLEND, 2 | 3 << 4);
        rig.set(GE_CMD_STE, 1);
        rig.set(GE_CMD_STEST, 1 | 0xFF << 16);
        rig.set(GE_CMD_SOP, 4 << 16);
        rig.set(GE_CMD_ZTE, 1);
        rig.set(GE_CMD_ZTEST, 7);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) rig.setPixel(x, y, u32(x * 77 + y * 131) * 2246822519u);
    };
    std::vector<geo::Fragment> rows[4];
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            geo::Fragment f = PixelRig::frag(x, y, u8(x * 4), u8(y * 4), u8(x ^ y), u8(x + y), u16(x * y));
            f.s = float(x) / 37.0f;
            f.t = float(y) / 23.0f;
            rows[y % 4].push_back(f);
        }
    PixelRig one, many;
    setup(one);
    setup(many);
    PixelState ps1 = buildPixelState(one.st, one.mem, *one.cache, geo::AccuracyProfile::ppsspp(), true);
    for (auto& r : rows) shadeFragments(ps1, r.data(), r.size());
    PixelState psN = buildPixelState(many.st, many.mem, *many.cache, geo::AccuracyProfile::ppsspp(), true);
    std::vector<std::thread> threads;
    for (auto& r : rows) threads.emplace_back([&psN, &r] { shadeFragments(psN, r.data(), r.size()); });
    for (auto& t : threads) t.join();
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(many.pixel(x, y), one.pixel(x, y)) << x << "," << y;
            ASSERT_EQ(many.depth(x, y), one.depth(x, y)) << x << "," << y;
        }
}
