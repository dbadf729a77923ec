// SPDX-License-Identifier: MIT
// Texture sampling of the software model: nearest vs bilinear, repeat vs clamp, sizes above 512,
// level-of-detail and mip level choice, and the decoded-texture cache's invalidation rules.
// Expected values are computed by hand from docs/ge-rules.md §6.6 and §8.10.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "authoring/list_builder.h"
#include "geometry/texture_size.h"
#include "hle/ge_engine.h"
#include "soft_pixel_fixture.h"
#include "softmodel/sampler.h"
#include "softmodel/soft_renderer.h"
#include "softmodel/texture_cache.h"
#include "tests/wide_texture_scene.h"

using namespace ge;
using namespace ge::soft;
using ge::soft::testing::PixelRig;
using ge::soft::testing::rgba;

namespace {

// 2×2: (0,0) (16,32,48,64), (1,0) (240,0,80,255), (0,1) (0,160,200,128), (1,1) (96,96,96,0).
const std::vector<u32> k2x2 = {rgba(16, 32, 48, 64), rgba(240, 0, 80, 255), rgba(0, 160, 200, 128), rgba(96, 96, 96, 0)};

TexLevel levelOf(const std::vector<u32>& texels, u32 wlog, u32 hlog) {
    TexLevel lv;
    lv.texels = texels.data();
    lv.setSize(wlog, hlog, 1 << std::min<u32>(wlog, 9), 1 << std::min<u32>(hlog, 9));
    return lv;
}

// Draws one REPLACE/RGBA fragment at (s, t) and returns the written 8888 pixel.
u32 drawSample(PixelRig& rig, float s, float t, float lod = 0, float w = 1) {
    rig.set(GE_CMD_TME, 1);
    rig.set(GE_CMD_TFUNC, 3 | 1 << 8);
    // No stencil test: the alpha byte keeps its stored value, the RGB bits show the texel.
    geo::Fragment f = PixelRig::frag(0, 0, 255, 255, 255, 255);
    f.s = s;
    f.t = t;
    f.lod = lod;
    f.w = w;
    rig.draw(f, true);
    return rig.pixel(0, 0) & 0xFFFFFF;
}

}  // namespace

TEST(SoftSampler, NearestPicksTruncatedTexel) {
    const TexLevel lv = levelOf(k2x2, 1, 1);
    // u = trunc(s·2·256) >> 8.
    EXPECT_EQ(sampleNearest(lv, 0.5f, 0.5f, false, false), k2x2[3]);
    EXPECT_EQ(sampleNearest(lv, 0.25f, 0.75f, false, false), k2x2[2]);
    EXPECT_EQ(sampleNearest(lv, 0.499f, 0.0f, false, false), k2x2[0]);
}

TEST(SoftSampler, BilinearWeightsWithHalfTexelShift) {
    const TexLevel lv = levelOf(k2x2, 1, 1);
    // (0.5, 0.5): u0 = v0 = 0, fu = fv = 8: the four texels at 64/256 each.
    EXPECT_EQ(sampleBilinear(lv, 0.5f, 0.5f, false, false), rgba(88, 72, 106, 111));
    // (0.3, 0.6): 153 − 128 = 25 → u0 0, fu 1; 307 − 128 = 179 → v0 0, fv 11; weights 75, 5, 165, 11.
    EXPECT_EQ(sampleBilinear(lv, 0.3f, 0.6f, false, false), rgba(13, 116, 148, 106));
    // (0.9, 0.1): u0 1 (u1 wraps to 0), fu 4; 51 − 128 = −77 → v0 −1 (wraps to 1), fv 11.
    EXPECT_EQ(sampleBilinear(lv, 0.9f, 0.1f, false, false), rgba(149, 40, 87, 152));
}

// Sampler::sampleFragments forms four pixels' texel coordinates at once (SSE2) where one level and
// one filter serve the draw; every result must be the per-pixel routine's, for every filter,
// wrap/clamp and rounding mode, at ties, far out of range, at the edge of the 32-bit range (where
// the four-pixel path hands the group to the scalar one) and for NaN and infinities.
TEST(SoftSampler, FourPixelPathMatchesThePerPixelOne) {
    std::vector<u32> texels(512 * 64);
    u32 x = 12345;
    for (u32& t : texels) t = x = x * 1664525u + 1013904223u;
    std::vector<geo::Fragment> frags;
    auto add = [&](float s, float t) {
        geo::Fragment f;
        f.s = s, f.t = t;
        frags.push_back(f);
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> wide(-4.0f, 4.0f);
    for (int i = 0; i < 2000; ++i) add(wide(rng), wide(rng));
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (float e : {nan, inf, -inf, 1e10f, -1e10f, 0.0f, -0.0f}) add(e, 0.25f), add(0.25f, e);
    for (u32 wlog : {6u, 10u}) {  // 64 wide, and 1024 (addressing saturates at 511)
        const float scale = float(1u << wlog) * 256.0f;
        std::uniform_int_distribution<int> m(-100000, 100000);
        for (int i = 0; i < 500; ++i) add((float(m(rng)) + 0.5f) / scale, (float(m(rng)) + 0.5f) / 8192.0f);  // ties
        for (int d = 0; d < 260; d += 7)  // around INT32_MIN once scaled
            add((-2147483648.0f + float(d * 128)) / scale, 0.5f), add(0.5f, (-2147483648.0f + float(d * 128)) / 8192.0f);
    }
    frags.push_back(frags[5]);  // a count that is not a multiple of four
    for (u32 wlog : {6u, 10u})
        for (int k = 0; k < 16; ++k) {
            Sampler sm;
            sm.levels[0] = levelOf(texels, wlog, 5);
            sm.levels[0].linearTruncates = (k & 8) != 0;
            sm.levelCount = 1;
            sm.fixedChoice = true;
            sm.fixed.linear = (k & 4) != 0;
            sm.clampU = (k & 2) != 0;
            sm.clampV = (k & 1) != 0;
            sm.finalize();
#if defined(__SSE2__)
            ASSERT_NE(sm.fn4, nullptr);
#endif
            std::vector<u32> got(frags.size());
            sm.sampleFragments(frags.data(), frags.size(), got.data());
            for (size_t i = 0; i < frags.size(); ++i)
                ASSERT_EQ(got[i], sm.sample(frags[i].s, frags[i].t, 0, 1))
                    << "wlog " << wlog << " variant " << k << " s " << frags[i].s << " t " << frags[i].t;
        }
}

TEST(SoftSampler, RepeatVersusClamp) {
    const std::vector<u32> row = {rgba(10, 0, 0, 255), rgba(20, 0, 0, 255), rgba(30, 0, 0, 255), rgba(40, 0, 0, 255)};
    const TexLevel lv = levelOf(row, 2, 0);
    auto red = [](u32 c) { return c & 255; };
    // Nearest: s = 1.25 → u 5: repeat 1, clamp 3. s = −0.25 → u −1: repeat 3, clamp 0.
    EXPECT_EQ(red(sampleNearest(lv, 1.25f, 0.5f, false, false)), 20u);
    EXPECT_EQ(red(sampleNearest(lv, 1.25f, 0.5f, true, false)), 40u);
    EXPECT_EQ(red(sampleNearest(lv, -0.25f, 0.5f, false, false)), 40u);
    EXPECT_EQ(red(sampleNearest(lv, -0.25f, 0.5f, true, false)), 10u);
    // Truncation toward zero: s·w·256 = −0.512 → 0 → texel 0 (a floor would give texel 3).
    EXPECT_EQ(red(sampleNearest(lv, -0.0005f, 0.5f, false, false)), 10u);
    // Bilinear at the edges: s = 0 → u0 −1, fu 8: repeat mixes texels 3 and 0, clamp uses 0 twice.
    EXPECT_EQ(red(sampleBilinear(lv, 0.0f, 0.5f, false, false)), 25u);
    EXPECT_EQ(red(sampleBilinear(lv, 0.0f, 0.5f, true, false)), 10u);
    EXPECT_EQ(red(sampleBilinear(lv, 1.0f, 0.5f, false, false)), 25u);
    EXPECT_EQ(red(sampleBilinear(lv, 1.0f, 0.5f, true, false)), 40u);
    // Far out of range (and NaN) stays inside the texture.
    EXPECT_EQ(red(sampleNearest(lv, 1e30f, NAN, false, false)), 10u);
    EXPECT_EQ(red(sampleBilinear(lv, -1e30f, 1e30f, true, true)), 10u);
}

TEST(SoftSampler, BilinearRoundsThePositionNearestSampleTruncates) {
    // The reference renderer's x86 sampler converts s·w·256 to an integer with CVTPS2DQ (round to
    // nearest, ties to even) for bilinear quads but CVTTPS2DQ (truncation) for nearest sampling.
    // 16×1 texture, red 160 at texel 4, 0 elsewhere; t = 0.5 → v0 0, fv 0.
    std::vector<u32> row(16, rgba(0, 0, 0, 255));
    row[4] = rgba(160, 0, 0, 255);
    const TexLevel lv = levelOf(row, 4, 0);
    auto red = [](u32 c) { return c & 255; };
    // s·4096 = 1023.6 → 1024 − 128 = 896: u0 3, fu 8 → 160·8·16 >> 8 = 80 (truncation: fu 7, 70).
    EXPECT_EQ(red(sampleBilinear(lv, 1023.6f / 4096.0f, 0.5f, false, false)), 80u);
    // 1039.5 is a tie: nearest-even 1040 → 912: fu 9 → 90 (truncation: fu 8, 80).
    EXPECT_EQ(red(sampleBilinear(lv, 1039.5f / 4096.0f, 0.5f, false, false)), 90u);
    // 1038.5 ties down to 1038 → 910: fu 8 → 80.
    EXPECT_EQ(red(sampleBilinear(lv, 1038.5f / 4096.0f, 0.5f, false, false)), 80u);
    // Nearest still truncates: s·4096 = 1279.9 → 1279 >> 8 = texel 4 (1280 would be texel 5).
    EXPECT_EQ(red(sampleNearest(lv, 1279.9f / 4096.0f, 0.5f, false, false)), 160u);
}

TEST(SoftSampler, SizesAbove512SaturateAddressing) {
    // TSIZE 2^10: coordinates scale by 1024, addressing uses & 1023 & 511 (repeat) or ≤ 511.
    std::vector<u32> texels(512);
    for (u32 i = 0; i < 512; ++i) texels[i] = i;
    const TexLevel lv = levelOf(texels, 10, 0);
    EXPECT_EQ(sampleNearest(lv, 0.75f, 0.0f, false, false), texels[256]);  // u 768 → 256
    EXPECT_EQ(sampleNearest(lv, 0.75f, 0.0f, true, false), texels[511]);
    EXPECT_EQ(sampleNearest(lv, 0.25f, 0.0f, true, false), texels[256]);
}

// The size rule (geometry/texture_size.h): coordinates scale by the full 2^n, the texel index
// stops at min(2^n, 512) − 1 or wraps with (2^n − 1) & 511. With the PSP's values for rows of
// 1024 and 32768 texels drawn over 256 pixels (tests/conformance/textures_size.cpp): pixel 0
// (s = 0.5/256) reads texel 2 and 64, pixel 127 texel 510.
TEST(SoftSampler, SizesAbove512ScaleByTheFullSize) {
    EXPECT_EQ(geo::texCoordSize(9), 512u);
    EXPECT_EQ(geo::texCoordSize(10), 1024u);
    EXPECT_EQ(geo::texCoordSize(15), 32768u);
    EXPECT_EQ(geo::texelClampMax(3), 7);
    EXPECT_EQ(geo::texelClampMax(10), 511);
    EXPECT_EQ(geo::texelWrapMask(3), 7);
    EXPECT_EQ(geo::texelWrapMask(15), 511);
    std::vector<u32> texels(512);
    std::iota(texels.begin(), texels.end(), 0u);
    const TexLevel w1024 = levelOf(texels, 10, 0), w32768 = levelOf(texels, 15, 0);
    EXPECT_EQ(sampleNearest(w1024, 0.5f / 256, 0.0f, true, true), 2u);
    EXPECT_EQ(sampleNearest(w1024, 127.5f / 256, 0.0f, true, true), 510u);
    EXPECT_EQ(sampleNearest(w1024, 255.5f / 256, 0.0f, true, true), 511u);
    EXPECT_EQ(sampleNearest(w32768, 0.5f / 256, 0.0f, true, true), 64u);
}

// End to end, through mode divides its texel coordinates by the same unclamped 2^n the sampler
// multiplies by (geometry/transform.cpp), so both modes read the PSP's texels
// (tests/wide_texture_scene.h: 1024 wide and high, clamp and repeat).
TEST(SoftSampler, SizesAbove512ReadTheSameTexelsInBothModes) {
    Memory mem;
    SoftOptions o;
    o.threads = 1;
    auto r = createSoftRenderer(mem, o);
    GeEngine eng(mem, r.get());
    ListBuilder b(&mem);
    testscene::wideTextureScene(b);
    b.finish();
    eng.startList(b.placeList(), 0);
    eng.run();
    r->flushToMemory();
    const std::vector<std::string> bad = testscene::wideTextureMismatches(mem.vram());
    EXPECT_TRUE(bad.empty()) << bad.size() << " pixels, first " << bad.front();
}

TEST(SoftSampler, EndToEndNearestAndBilinear) {
    PixelRig rig;
    rig.texture8888(0, PixelRig::kTex, 1, 1, k2x2);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), k2x2[3] & 0xFFFFFF);
    rig.set(GE_CMD_TFILTER, 1 | 1 << 8);  // LINEAR both ways
    EXPECT_EQ(drawSample(rig, 0.3f, 0.6f), rgba(13, 116, 148, 0));
    rig.set(GE_CMD_TWRAP, 1 | 1 << 8);  // clamp both
    // (0.9, 0.1) clamped: u0 1, u1 1; v0 0, v1 0 → texel (1, 0).
    EXPECT_EQ(drawSample(rig, 0.9f, 0.1f), k2x2[1] & 0xFFFFFF);
}

TEST(SoftLod, Log2WithFourFractionBits) {
    EXPECT_EQ(texLog2x16(1.0f), 0);
    EXPECT_EQ(texLog2x16(2.0f), 16);
    EXPECT_EQ(texLog2x16(1.5f), 8);
    EXPECT_EQ(texLog2x16(3.0f), 24);
    EXPECT_EQ(texLog2x16(0.75f), -8);
    EXPECT_EQ(texLog2x16(1.99f), 15);
    EXPECT_EQ(texLog2x16(-2.0f), 16);  // sign ignored
    EXPECT_EQ(texLog2x16(0.0f), -2032);
}

TEST(SoftLod, DetailPerMode) {
    LodParams p;
    p.mode = 0;
    EXPECT_EQ(levelOfDetail16(p, 1.0f, 1), 16);
    // The rasteriser's GE-style log2 of 1.5 is 0.5 (exponent + mantissa), of 1.53125 0.53125.
    EXPECT_EQ(levelOfDetail16(p, 0.5f, 1), 8);
    EXPECT_EQ(levelOfDetail16(p, 0.53125f, 1), 8);
    EXPECT_EQ(levelOfDetail16(p, -0.5f, 1), -8);
    EXPECT_EQ(levelOfDetail16(p, NAN, 1), -4096);
    EXPECT_EQ(levelOfDetail16(p, -1.0f, 1), -16);
    p.bias16 = -16;
    EXPECT_EQ(levelOfDetail16(p, 1.0f, 1), 0);
    p.mode = 2;  // log2(TSLOPE·W) + 1
    p.bias16 = 0;
    p.slope = 0.25f;
    EXPECT_EQ(levelOfDetail16(p, 0, 8.0f), 32);
    EXPECT_EQ(levelOfDetail16(p, 0, 2.0f), 0);
    p.mode = 1;  // constant: OFFL alone
    p.bias16 = 0x18;
    EXPECT_EQ(levelOfDetail16(p, 5.0f, 8.0f), 0x18);
}

TEST(SoftLod, LevelChoice) {
    LodParams p;
    p.maxLevel = 3;
    p.minLinear = true;
    p.magLinear = false;
    auto check = [&](int d, int level, int frac, bool linear) {
        const LevelChoice c = chooseLevel(p, d);
        EXPECT_EQ(c.level, level) << d;
        EXPECT_EQ(c.frac, frac) << d;
        EXPECT_EQ(c.linear, linear) << d;
    };
    check(0, 0, 0, false);    // d ≤ 0: magnification filter, level 0
    check(-40, 0, 0, false);
    check(7, 0, 0, true);     // d > 0: minification even at level 0
    check(8, 1, 0, true);     // nearest mip: floor(d + 0.5)
    check(24, 2, 0, true);
    check(100, 3, 0, true);   // limited by MXL
    p.mipLinear = true;
    check(24, 1, 8, true);    // mipmap-linear: floor(d) and the 4-bit fraction
    check(8, 0, 8, true);
    check(100, 3, 0, true);
    p.maxLevel = 0;           // no mipmaps: level 0, but still the minification filter
    check(40, 0, 0, true);
}

TEST(SoftLod, EndToEndMipLevels) {
    // Level 0 (2×2) red, level 1 (1×1) green.
    PixelRig rig;
    rig.texture8888(0, PixelRig::kTex, 1, 1, {rgba(255, 0, 0, 255), rgba(255, 0, 0, 255), rgba(255, 0, 0, 255), rgba(255, 0, 0, 255)});
    rig.texture8888(1, PixelRig::kTex + 0x1000, 0, 0, {rgba(0, 255, 0, 255)});
    rig.set(GE_CMD_TMODE, 1 << 16);    // MXL 1
    rig.set(GE_CMD_TFILTER, 4);        // NEAREST_MIPMAP_NEAREST
    rig.set(GE_CMD_TLEVEL, 1 | 0x10 << 16);  // constant, OFFL +1.0
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(0, 255, 0, 0));
    rig.set(GE_CMD_TFILTER, 6);        // NEAREST_MIPMAP_LINEAR
    rig.set(GE_CMD_TLEVEL, 1 | 0x08 << 16);  // +0.5: level 0, fraction 8
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(127, 127, 0, 0));
    rig.set(GE_CMD_TFILTER, 1);        // LINEAR without mipmapping: MXL ignored
    rig.set(GE_CMD_TLEVEL, 1 | 0x10 << 16);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(255, 0, 0, 0));
    rig.set(GE_CMD_TFILTER, 4);
    rig.set(GE_CMD_TLEVEL, 0);         // auto: the fragment's lod
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f, 1.0f), rgba(0, 255, 0, 0));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f, 0.0f), rgba(255, 0, 0, 0));
    rig.set(GE_CMD_TLEVEL, 2);         // slope: log2(0.25·4) + 1 = 1
    rig.set(GE_CMD_TSLOPE, toFloat24(0.25f));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f, 0.0f, 4.0f), rgba(0, 255, 0, 0));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f, 0.0f, 1.0f), rgba(255, 0, 0, 0));
}

TEST(SoftTextureCache, DecodesOnceAndFollowsInvalidation) {
    PixelRig rig;
    rig.texture8888(0, PixelRig::kTex, 0, 0, {rgba(1, 2, 3, 255)});
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(1, 2, 3, 0));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(1, 2, 3, 0));
    EXPECT_EQ(rig.cache->stats().decodes, 1u);

    // Memory changes without an event: the cache keeps the decoded copy (event-driven).
    rig.mem.write32(PixelRig::kTex, rgba(9, 8, 7, 255));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(1, 2, 3, 0));
    // A write elsewhere does not touch it; an overlapping one makes it re-hash and decode.
    invalidateTextureCache(*rig.cache, PixelRig::kTex + 0x100, 16);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(1, 2, 3, 0));
    EXPECT_EQ(rig.cache->stats().rehashes, 0u);
    invalidateTextureCache(*rig.cache, PixelRig::kTex + 2, 1);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(9, 8, 7, 0));
    EXPECT_EQ(rig.cache->stats().decodes, 2u);
    // Invalidated but unchanged: re-hashed, not decoded again. Uncached-view addresses count.
    invalidateTextureCache(*rig.cache, 0x48000000, 4);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(9, 8, 7, 0));
    EXPECT_EQ(rig.cache->stats().decodes, 2u);
    EXPECT_EQ(rig.cache->stats().rehashes, 2u);
    invalidateTextureCache(*rig.cache, 0, 0);  // everything
    rig.mem.write32(PixelRig::kTex, rgba(5, 5, 5, 255));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(5, 5, 5, 0));
}

TEST(SoftTextureCache, ClutChangeIsSeen) {
    PixelRig rig;
    // CLUT8 1×1 texture holding index 3; 8888 palette.
    rig.set(GE_CMD_TBP0, PixelRig::kTex & 0xFFFFFF);
    rig.set(GE_CMD_TBW0, 16 | (PixelRig::kTex >> 24) << 16);
    rig.set(GE_CMD_TSIZE0, 0);
    rig.set(GE_CMD_TPF, GE_TFMT_CLUT8);
    rig.set(GE_CMD_CLUT, 3 | 0xFF << 8);
    rig.mem.write8(PixelRig::kTex, 3);
    writeLE32(rig.st.clut + 12, rgba(11, 22, 33, 255));
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(11, 22, 33, 0));
    writeLE32(rig.st.clut + 12, rgba(44, 55, 66, 255));
    clutChanged(*rig.cache);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(44, 55, 66, 0));
    // A different CLUT setting (index mask) is a different cache key: index 3 & 1 = 1.
    writeLE32(rig.st.clut + 4, rgba(7, 7, 7, 255));
    rig.set(GE_CMD_CLUT, 3 | 0x01 << 8);
    EXPECT_EQ(drawSample(rig, 0.5f, 0.5f), rgba(7, 7, 7, 0));
}

TEST(SoftTextureCache, DrawingIntoTheTextureIsSeen) {
    // Render to texture: the texture lives in VRAM on frame-buffer row 100; drawing there must
    // make the next draw re-read it.
    PixelRig rig;
    const u32 texAddr = PixelRig::kFb + 100 * PixelRig::kStride * 4;
    rig.texture8888(0, texAddr, 0, 0, {rgba(1, 1, 1, 255)});
    rig.set(GE_CMD_TME, 1);
    rig.set(GE_CMD_TFUNC, 3 | 1 << 8);
    geo::Fragment f = PixelRig::frag(0, 0, 0, 0, 0, 0);
    f.s = f.t = 0.5f;
    rig.draw(f, true);
    EXPECT_EQ(rig.pixel(0, 0) & 0xFFFFFF, 0x010101u);
    rig.draw(PixelRig::frag(0, 100, 50, 60, 70, 0), false);  // untextured draw onto the texel
    rig.draw(f, true);
    EXPECT_EQ(rig.pixel(0, 0) & 0xFFFFFF, rgba(50, 60, 70, 0));
}
