// SPDX-License-Identifier: MIT
// One scene per switch of geometry/accuracy_profile.h, rendered with both profiles on the
// software model, GL exact and GL hw (1x) — GL hw where the switch applies to it: the pixels each profile must give. Every scene fails
// when its switch is ignored by a backend (the two profiles' expected pixels differ).
#include <cstring>
#include <functional>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>

#include "backend/factory.h"
#include "tests/gl_fixture.h"
#include "tests/reference_quirk_scenes.h"
#include "tests/screen_frame.h"
#include "tests/sprite_position_scene.h"

namespace ge::gltest {
namespace {

using Scene = std::function<void(ListBuilder&)>;
using Check = std::function<void(const std::vector<u8>& vram)>;

enum class Where { Soft, GlExact, GlHw };

// `scene`'s VRAM on one backend with `acc`; false when the backend cannot start (no GL context).
bool render(Where w, const geo::AccuracyProfile& acc, const Scene& scene, std::vector<u8>& vram, std::string& err) {
    Memory mem;
    backend::BackendOptions bo;
    bo.accuracy = acc;
    bo.threads = 1;
    bo.kind = w == Where::Soft ? backend::BackendKind::Soft : backend::BackendKind::Gl;
    bo.glMode = w == Where::GlHw ? backend::GlMode::Hw : backend::GlMode::Exact;
    backend::Backend b = backend::createBackend(mem, bo, err);
    if (!b) return false;
    vram = runListVram(mem, *b.renderer, scene);
    return true;
}

// Runs `psp` on each backend's render with the psp profile and `ppsspp` with the ppsspp one.
void checkBothProfiles(const Scene& scene, const Check& psp, const Check& ppsspp,
                       std::initializer_list<Where> backends = {Where::Soft, Where::GlExact, Where::GlHw}) {
    for (Where w : backends) {
        SCOPED_TRACE(w == Where::Soft ? "soft" : w == Where::GlExact ? "GL exact" : "GL hw");
        for (bool isPsp : {true, false}) {
            SCOPED_TRACE(isPsp ? "psp" : "ppsspp");
            std::vector<u8> vram;
            std::string err;
            if (!render(w, isPsp ? geo::AccuracyProfile::psp() : geo::AccuracyProfile::ppsspp(), scene, vram, err)) {
                ASSERT_NE(w, Where::Soft) << err;
                GTEST_SKIP() << "no GL context: " << err;
            }
            (isPsp ? psp : ppsspp)(vram);
        }
    }
}

u32 rgbAt(const std::vector<u8>& vram, int x, int y, int stride) {
    return readLE32(&vram[(size_t(y) * size_t(stride) + size_t(x)) * 4]) & 0xFFFFFFu;
}

TEST(AccuracyProfiles, NamesRoundTrip) {
    geo::AccuracyProfile a;
    ASSERT_TRUE(geo::AccuracyProfile::fromName("psp", a));
    EXPECT_EQ(a, geo::AccuracyProfile::psp());
    EXPECT_STREQ(a.name(), "psp");
    ASSERT_TRUE(geo::AccuracyProfile::fromName("ppsspp", a));
    EXPECT_EQ(a, geo::AccuracyProfile::ppsspp());
    EXPECT_STREQ(a.name(), "ppsspp");
    EXPECT_FALSE(geo::AccuracyProfile::fromName("hardware", a));
    a.zeroAreaTriangles = false;
    EXPECT_STREQ(a.name(), "custom");
    // Every switch differs between the two profiles (a switch exists only where they disagree),
    // and each can be flipped by name from either base.
    const geo::AccuracyProfile p = geo::AccuracyProfile::psp(), q = geo::AccuracyProfile::ppsspp();
    for (const geo::AccuracySwitch& sw : geo::kAccuracySwitches) {
        SCOPED_TRACE(sw.name);
        EXPECT_NE(p.*sw.member, q.*sw.member);
        const std::string toPpsspp = std::string("psp") + (q.*sw.member ? "+" : "-") + sw.name;
        ASSERT_TRUE(geo::AccuracyProfile::fromName(toPpsspp.c_str(), a));
        EXPECT_EQ(a.*sw.member, q.*sw.member);
        EXPECT_STREQ(a.name(), "custom");
        geo::AccuracyProfile back = a;
        back.*sw.member = p.*sw.member;
        EXPECT_EQ(back, p) << "only the named switch moved";
    }
    ASSERT_TRUE(geo::AccuracyProfile::fromName("ppsspp+pspColourGradients-zeroAreaTriangles", a));
    EXPECT_TRUE(a.pspColourGradients);
    EXPECT_FALSE(a.zeroAreaTriangles);
    EXPECT_TRUE(a.clutSkipsAlphaTest);
    EXPECT_FALSE(geo::AccuracyProfile::fromName("psp+noSuchRule", a));
    EXPECT_FALSE(geo::AccuracyProfile::fromName("pspx", a));
    EXPECT_FALSE(geo::AccuracyProfile::fromName("psp+", a));
}

// pspBilinearTruncation: a 1x1 through-mode sprite over a 2-texel texture (red, green), bilinear,
// clamped, from u = 143.7/256 texel, v = 1/2. Pixel 0 samples half a pixel (= half a texel) in:
// the position with 8 fraction bits is 271.7, truncated 271 on a PSP (half a texel back: 143,
// fraction 8/16: red and green 127), rounded 272 by PPSSPP (144, fraction 9/16: red 111, green
// 143).
void bilinearPositionScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0xFF000000, 0);
    const u32 texels[8] = {0xFF0000FFu, 0xFF00FF00u, 0, 0, 0xFF0000FFu, 0xFF00FF00u, 0, 0};
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, b.place(texels, sizeof texels), 2, 2, 4);
    b.texFunc(3, true);  // REPLACE
    b.texFilter(1, 1);
    b.texWrap(true, true);
    b.enable(GE_CMD_TME, true);
    constexpr u32 vtype = vt::TC_F | vt::COL_8888 | vt::POS_F | vt::THROUGH;
    BuildVertex v[2];
    v[0].u = 143.7f / 256.0f, v[0].v = 0.5f;
    v[1].x = 1, v[1].y = 1, v[1].u = v[0].u + 1, v[1].v = 1.5f;
    v[0].color = v[1].color = 0xFFFFFFFFu;
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, packVertices(vtype, v, 2).data());
}

TEST(AccuracyProfiles, BilinearPositionTruncation) {
    checkBothProfiles(
        bilinearPositionScene, [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 0, 0, 64), 0x007F7Fu); },
        [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 0, 0, 64), 0x008F6Fu); });
}

// pspTriangleSampleCentre: a through-mode triangle (20, 0), (20, 20), (0, 20) whose left edge is
// the up-right diagonal x + y = 20 (pspautotests primitives/continue's second triangle). Pixel
// (10, 9) has its centre exactly on it: the PSP samples the centre and draws it (a left edge is
// inside, top-left rule); PPSSPP samples 1/16 pixel up-left of it, outside. (10, 10) is inside
// for both, (10, 8) for neither.
void sampleCentreScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0x00000000, 0);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[3];
    const float xy[3][2] = {{20, 0}, {20, 20}, {0, 20}};
    for (int i = 0; i < 3; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].color = 0xFF00C000u;
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, packVertices(vtype, v, 3).data());
}

TEST(AccuracyProfiles, TriangleSampleCentre) {
    checkBothProfiles(
        sampleCentreScene,
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 10, 9, 64), 0x00C000u);
            EXPECT_EQ(rgbAt(vram, 10, 10, 64), 0x00C000u);
            EXPECT_EQ(rgbAt(vram, 10, 8, 64), 0u);
        },
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 10, 9, 64), 0u);
            EXPECT_EQ(rgbAt(vram, 10, 10, 64), 0x00C000u);
            EXPECT_EQ(rgbAt(vram, 10, 8, 64), 0u);
        });
}

// pspColourGradients: pspautotests primitives/immediate's Gouraud fan in through mode: a 40x40
// quad from (260, 10) as a fan, green 255 on the top vertices and 127 on the bottom ones (blue
// 255). The PSP's capture reads one green per row (kFanGreen, rows 10..49): 253, 250, 246, 243 …
// where the exact values at the centres are 253.4, 250.2, 247.0, 243.8. PPSSPP samples 7/16 down
// the pixel and rounds the float sum to nearest: 254 on row 10 (253.6), 247 on row 12 (247.2).
// GL hw interpolates on the GPU and is not held to either rule.
// The 480x272 screen of an 8888, 512-stride frame cleared to black, Gouraud shading on.
void gouraudScreen(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.clear(CLEAR_COLOR, 0x00000000, 0);
    b.shadeModel(true);
}

constexpr u8 kFanGreen[40] = {0xfd, 0xfa, 0xf6, 0xf3, 0xf0, 0xed, 0xea, 0xe6, 0xe3, 0xe0, 0xdd, 0xda, 0xd6, 0xd3,
                              0xd0, 0xcd, 0xca, 0xc6, 0xc3, 0xc0, 0xbd, 0xba, 0xb6, 0xb3, 0xb0, 0xad, 0xaa, 0xa6,
                              0xa3, 0xa0, 0x9d, 0x9a, 0x96, 0x93, 0x90, 0x8d, 0x8a, 0x86, 0x83, 0x80};
void gouraudFanScene(ListBuilder& b) {
    gouraudScreen(b);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[4];
    const float xy[4][2] = {{260, 10}, {300, 10}, {300, 50}, {260, 50}};
    for (int i = 0; i < 4; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].color = i < 2 ? 0xFFFFFF00u : 0xFFFF7F00u;
    b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, packVertices(vtype, v, 4).data());
}

TEST(AccuracyProfiles, ColourGradients) {
    checkBothProfiles(
        gouraudFanScene,
        [](const std::vector<u8>& vram) {
            for (int y = 10; y < 50; ++y)
                for (int x : {260, 262, 281, 299})
                    ASSERT_EQ(rgbAt(vram, x, y, 512), 0xFF0000u | u32(kFanGreen[y - 10]) << 8) << x << "," << y;
        },
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 270, 10, 512), 0xFFFE00u);
            EXPECT_EQ(rgbAt(vram, 270, 12, 512), 0xFFF700u);
        },
        {Where::Soft, Where::GlExact});
}

// pspPatchColourRoundUp: a through-mode 4x4 Bezier patch (control rows 10 pixels apart, red 100
// on the first row, 0 on the others), divided 4x4 and flat-shaded, so every pixel shows one
// generated vertex's colour. The row at v = 1/4 evaluates to 100·(3/4)^3 = 42.19: 43 rounded up
// on a PSP, 42 to nearest in PPSSPP; the other rows are 100, 12.5 (13 either way), 1.56 (2), 0.
void flatPatchScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0x00000000, 0);
    b.shadeModel(false);
    b.patchDivide(4, 4);
    b.patchPrim(0);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[16];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            BuildVertex& c = v[j * 4 + i];
            c.x = float(10 + 10 * i), c.y = float(10 + 10 * j);
            c.color = 0xFF000000u | (j == 0 ? 100u : 0u);
        }
    const std::vector<u8> data = packVertices(vtype, v, 16);
    b.drawBezier(vtype, 4, 4, 0, b.place(data.data(), u32(data.size()), 4));
}

TEST(AccuracyProfiles, PatchColourRoundUp) {
    auto reds = [](const std::vector<u8>& vram) {
        std::set<u32> r;
        for (int y = 10; y < 40; ++y)
            for (int x = 10; x < 40; ++x) r.insert(rgbAt(vram, x, y, 64) & 0xFFu);
        return r;
    };
    checkBothProfiles(
        flatPatchScene,
        [&](const std::vector<u8>& vram) {
            const std::set<u32> r = reds(vram);
            EXPECT_TRUE(r.count(43)) << "v = 1/4 rounded up";
            EXPECT_FALSE(r.count(42));
        },
        [&](const std::vector<u8>& vram) {
            const std::set<u32> r = reds(vram);
            EXPECT_TRUE(r.count(42)) << "v = 1/4 rounded to nearest";
            EXPECT_FALSE(r.count(43));
        });
}

// pspLineCentres: two through-mode lines. A Gouraud line from (170, 10) down to (170, 22 + 7/16),
// green 0 to 148 (a vertical line of pspautotests primitives/bezier's line patch): the PSP's
// row r reads ⌊148·(16r + 8 − 160) / 199⌋: 5, 29, 41 on rows 10, 12, 13; PPSSPP's walk of 12
// whole steps 148·(r − 10) / 12: 0, 24, 37. A white line from x 9.375 to 11.25 on row 30
// (pspautotests primitives/lines): the PSP draws the pixels whose centres lie on it, 9 and 10;
// PPSSPP ⌊30 / 16⌋ = 1 step, pixel 9.
void lineScene(ListBuilder& b) {
    gouraudScreen(b);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F | vt::THROUGH;
    BuildVertex v[4];
    v[0].x = v[1].x = 170.0f, v[0].y = 10.0f, v[1].y = 22.4375f;
    v[0].color = 0xFF0000FFu, v[1].color = 0xFF0094FFu;  // red 255; green 0 → 148
    v[2].x = 9.375f, v[3].x = 11.25f, v[2].y = v[3].y = 30.0f;
    v[2].color = v[3].color = 0xFFFFFFFFu;
    b.drawArrayData(GE_PRIM_LINES, vtype, 4, nullptr, packVertices(vtype, v, 4).data());
}

TEST(AccuracyProfiles, LineCentres) {
    auto green = [](const std::vector<u8>& vram, int y) { return (rgbAt(vram, 170, y, 512) >> 8) & 0xFFu; };
    checkBothProfiles(
        lineScene,
        [&](const std::vector<u8>& vram) {
            EXPECT_EQ(green(vram, 10), 5u);
            EXPECT_EQ(green(vram, 12), 29u);
            EXPECT_EQ(green(vram, 13), 41u);
            EXPECT_EQ(rgbAt(vram, 9, 30, 512), 0xFFFFFFu);
            EXPECT_EQ(rgbAt(vram, 10, 30, 512), 0xFFFFFFu);
            EXPECT_EQ(rgbAt(vram, 11, 30, 512), 0u);
        },
        [&](const std::vector<u8>& vram) {
            EXPECT_EQ(green(vram, 10), 0u);
            EXPECT_EQ(green(vram, 12), 24u);
            EXPECT_EQ(green(vram, 13), 37u);
            EXPECT_EQ(rgbAt(vram, 9, 30, 512), 0xFFFFFFu);
            EXPECT_EQ(rgbAt(vram, 10, 30, 512), 0u);
        },
        {Where::Soft, Where::GlExact});
}

// A transform-mode quad over clip (−0.5..0.5)² (pixels 120..359 × 68..203), normal (0, 0, 1), lit
// by light 0 of `type` at `pos` with only the colours given (black elsewhere: no global ambient,
// emissive or other light), white materials, MK = 1.
void litQuadScene(ListBuilder& b, u32 type, u32 comps, const float pos[3], u32 lightComponents, u32 rgb,
                  const float spotDir[3]) {
    testscene::screenFrame(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    testscene::identityTransform(b);
    b.enable(GE_CMD_LTE, true);
    b.enable(GE_CMD_LE0, true);
    b.ambient(0xFF000000);
    b.materialAmbient(0xFFFFFFFF);
    b.materialDiffuse(0xFFFFFF);
    b.materialSpecular(0xFFFFFF);
    b.materialEmissive(0);
    b.specularPower(1.0f);
    b.light(0, type, comps, pos);
    b.lightAtt(0, 1, 0, 0);
    b.lightColor(0, LIGHT_AMBIENT | LIGHT_DIFFUSE | LIGHT_SPECULAR, 0);
    b.lightColor(0, lightComponents, rgb);
    if (spotDir) b.lightSpot(0, spotDir, 1.0f, 0.0f);
    constexpr u32 vtype = vt::NRM_F | vt::POS_F;
    BuildVertex v[4];
    const float xy[4][2] = {{-0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, -0.5f}, {-0.5f, -0.5f}};
    for (int i = 0; i < 4; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1];
    b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, packVertices(vtype, v, 4).data());
}

// spotDirectionDivide: a spot light at (0, 0, 1) with LD = (+∞, +∞, +∞), red ambient. A PSP
// lights it fully (pspautotests commands/light "Spot INFINITY"): red 255; PPSSPP divides LD by
// its infinite length, the cosine is NaN and the light dark: black. GL hw carries the forced
// cosine in its uniforms and follows both.
void infiniteSpotScene(ListBuilder& b) {
    const float pos[3] = {0, 0, 1};
    const float inf = std::numeric_limits<float>::infinity();
    const float dir[3] = {inf, inf, inf};
    litQuadScene(b, 2, 0, pos, LIGHT_AMBIENT, 0x0000FF, dir);
}

TEST(AccuracyProfiles, SpotDirectionDivide) {
    checkBothProfiles(
        infiniteSpotScene, [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 240, 136, 512), 0x0000FFu); },
        [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 240, 136, 512), 0u); });
}

// sseVectorArithmetic: a directional light toward (0.5, 0.5, 0) with only a blue specular
// colour, over the quad's normal (0, 0, 1) (pspautotests commands/light "Diffuse 0.0 - Direc
// A + D + pow(S)"): N·L = 0, H = (0.5, 0.5, 0.707…), N·H = 0.70711, s = ceil(512·0.70711 + 1) =
// 364, blue (511·511·364) >> 19 = 181 (0xb5, what the PSP reads). PPSSPP normalises H with
// rsqrtss: N·H a hair under, s = 363, blue 180 (0xb4) — on an x86 host, whose rsqrtss is the
// one PPSSPP used; elsewhere the exact root stands in. GL hw lights on the GPU with exact roots
// (not held to the switch).
void specularHalfVectorScene(ListBuilder& b) {
    const float pos[3] = {0.5f, 0.5f, 0.0f};
    litQuadScene(b, 0, 1, pos, LIGHT_SPECULAR, 0xFF0000, nullptr);
}

TEST(AccuracyProfiles, SseVectorArithmetic) {
#if defined(__SSE__) || defined(_M_X64)
    constexpr u32 kPpssppBlue = 0xB4;
#else
    constexpr u32 kPpssppBlue = 0xB5;
#endif
    checkBothProfiles(
        specularHalfVectorScene,
        [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 240, 136, 512), 0xB50000u); },
        [](const std::vector<u8>& vram) { EXPECT_EQ(rgbAt(vram, 240, 136, 512), kPpssppBlue << 16); },
        {Where::Soft, Where::GlExact});
}

// implicitAlphaNonZeroTest: an alpha-0 source-alpha blend (A = As, B = 1 − As) without depth
// write, stencil or alpha test over a dithered 5650 buffer. The blend leaves the destination,
// and the SDK dither matrix adds 3 at (2, 1): the GE stores (25, 54, 24); PPSSPP drops the
// fragment and the pixel keeps (24, 53, 23) (the values of tests/soft_blend.cpp
// ZeroAlphaSourceAlphaBlendSkipsDither, Monster Hunter 3rd's HUD).
void zeroAlphaDitherScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_565, 0, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0xFF000000u | 189u << 16 | 215u << 8 | 198u, 0);  // exact in 5650: (24, 53, 23)
    const int sdk[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
    b.setDither(sdk);
    b.enable(GE_CMD_DTE, true);
    b.enable(GE_CMD_ABE, true);
    b.cmd(GE_CMD_BLEND, 2 | 3 << 4);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[2];
    v[0].color = v[1].color = 0x00FFFFFFu;
    v[1].x = 4, v[1].y = 4;
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, packVertices(vtype, v, 2).data());
}

TEST(AccuracyProfiles, ImplicitAlphaNonZeroTest) {
    auto px = [](const std::vector<u8>& vram) { return u32(readLE16(&vram[(1 * 64 + 2) * 2])); };
    const u32 before = 24u | 53u << 5 | 23u << 11, dithered = 25u | 54u << 5 | 24u << 11;
    checkBothProfiles(
        zeroAlphaDitherScene, [&](const std::vector<u8>& vram) { EXPECT_EQ(px(vram), dithered); },
        [&](const std::vector<u8>& vram) { EXPECT_EQ(px(vram), before); });
}

// clutSkipsAlphaTest: tests/reference_quirk_scenes.h skippedAlphaTestScene with palette entry 0
// = 0x00000001 (alpha 0, entries AND to non-zero) and vertex alpha 255: the GE's alpha test
// GREATER 0 rejects entry-0 texels (pixel (0, 0) keeps the black clear colour); PPSSPP skips
// the test and writes RGB 0x000001. Entry 1 (opaque red) is drawn by both.
TEST(AccuracyProfiles, ClutSkipsAlphaTest) {
    auto scene = [](ListBuilder& b) { testscene::skippedAlphaTestScene(b, 0x00000001u, 255); };
    checkBothProfiles(
        scene,
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 0, 0, 512), 0u);
            EXPECT_EQ(rgbAt(vram, 1, 0, 512), 0x0000FFu);
        },
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 0, 0, 512), 0x000001u);
            EXPECT_EQ(rgbAt(vram, 1, 0, 512), 0x0000FFu);
        });
}

// splineOpenKnotQuirk: one 4x4 spline patch open at both ends has the manual's knot vector
// 0,0,0,0,1,1,1,1 (§5.2.1): it is the Bezier patch of the same control points, so the GE draws
// both alike. PPSSPP's knot setup gives other weights, so its spline differs from its Bezier.
// Control points: columns at clip x −1, −1, −0.5, −0.5 (red 0, 0, 255, 255), rows at y 1, 1,
// 0.5, 0.5; Gouraud, 4x4 divisions.
void patchScene(ListBuilder& b, bool spline) {
    testscene::screenFrame(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    testscene::identityTransform(b);
    b.patchDivide(4, 4);
    b.patchPrim(0);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
    const float xs[4] = {-1.0f, -1.0f, -0.5f, -0.5f}, ys[4] = {1.0f, 1.0f, 0.5f, 0.5f};
    BuildVertex v[16];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            BuildVertex& c = v[j * 4 + i];
            c.x = xs[i], c.y = ys[j], c.z = 0;
            c.color = 0xFF00FF00u | (i >= 2 ? 0xFFu : 0u) | (j >= 2 ? 0xFF0000u : 0u);
        }
    const std::vector<u8> data = packVertices(vtype, v, 16);
    const u32 addr = b.place(data.data(), u32(data.size()), 4);
    if (spline) b.drawSpline(vtype, 4, 4, 3, 3, 0, addr);
    else b.drawBezier(vtype, 4, 4, 0, addr);
}

TEST(AccuracyProfiles, SplineOpenKnotQuirk) {
    for (Where w : {Where::Soft, Where::GlExact, Where::GlHw}) {
        SCOPED_TRACE(w == Where::Soft ? "soft" : w == Where::GlExact ? "GL exact" : "GL hw");
        for (bool isPsp : {true, false}) {
            SCOPED_TRACE(isPsp ? "psp" : "ppsspp");
            const geo::AccuracyProfile acc = isPsp ? geo::AccuracyProfile::psp() : geo::AccuracyProfile::ppsspp();
            std::vector<u8> spl, bez;
            std::string err;
            if (!render(w, acc, [](ListBuilder& b) { patchScene(b, true); }, spl, err) ||
                !render(w, acc, [](ListBuilder& b) { patchScene(b, false); }, bez, err)) {
                ASSERT_NE(w, Where::Soft) << err;
                GTEST_SKIP() << "no GL context: " << err;
            }
            // The patch was drawn (its corner pixel is green, not the clear colour).
            EXPECT_NE(rgbAt(bez, 1, 1, 512), 0u);
            if (isPsp) EXPECT_TRUE(spl == bez) << "the open-open spline is the Bezier patch";
            else EXPECT_FALSE(spl == bez) << "PPSSPP's knot quirk moves the spline's vertices";
        }
    }
}

// zeroAreaTriangles: collinear triangles along a diagonal and a strip with a repeated vertex
// (tests/gl_vs_soft.cpp ZeroAreaTrianglesAreIdentical's scene) over black. PPSSPP draws the
// samples exactly on their line; the GE draws nothing.
void zeroAreaScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0x00000000, 0);
    const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[6];
    const float xy[6][2] = {{4, 4}, {20, 20}, {20, 20}, {40, 40}, {24, 24}, {24, 24}};
    for (int i = 0; i < 6; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].color = i < 3 ? 0xFFFFFFFFu : 0xFFFF0000u;
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, packVertices(vtype, v, 6).data());
    const float strip[5][2] = {{44, 2}, {44, 12}, {54, 2}, {54, 12}, {54, 12}};
    for (int i = 0; i < 5; ++i) v[i].x = strip[i][0], v[i].y = strip[i][1], v[i].color = 0xFF00C000u;
    b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 5, nullptr, packVertices(vtype, v, 5).data());
}

TEST(AccuracyProfiles, ZeroAreaTriangles) {
    auto diagonal = [](const std::vector<u8>& vram) {
        size_t drawn = 0;
        for (int i = 0; i < 48; ++i) drawn += rgbAt(vram, i, i, 64) != 0 ? 1 : 0;
        return drawn;
    };
    checkBothProfiles(
        zeroAreaScene,
        [&](const std::vector<u8>& vram) {
            EXPECT_EQ(diagonal(vram), 0u);
            EXPECT_EQ(rgbAt(vram, 49, 7, 64), 0x00C000u);  // the strip's quad itself
        },
        [&](const std::vector<u8>& vram) {
            EXPECT_GT(diagonal(vram), 0u);
            EXPECT_EQ(rgbAt(vram, 49, 7, 64), 0x00C000u);
        });
}

// pspSpritePosition and spriteFarEdgeExcluded: tests/sprite_position_scene.h, whose six cases
// are values a PSP printed (checkSpritePositionScene). With the ppsspp profile each case shows
// PPSSPP's value instead, as the scene's comments give them: the far corner 1809.999998 reads
// texel 1 already at u0 = 131/512; the offset 3/16 reads 3/16 green; the top edge on row 0's
// top reads row 1; Z 4659 fails GEQUAL 0x1234 (not drawn); the through-mode pixel on the far
// edge is drawn (the odd pixel of its pair).
TEST(AccuracyProfiles, SpritePositionAndFarEdge) {
    checkBothProfiles(
        testscene::spritePositionScene,
        [](const std::vector<u8>& vram) {
            testscene::checkSpritePositionScene([&](int x, int y) { return rgbAt(vram, x, y, 512); });
        },
        [](const std::vector<u8>& vram) {
            EXPECT_EQ(rgbAt(vram, 0, 0, 512), 0x00FF00u);
            EXPECT_EQ(rgbAt(vram, 8, 0, 512), 0x00FF00u);
            EXPECT_EQ(rgbAt(vram, 16, 0, 512), 0x002FCFu);
            EXPECT_EQ(rgbAt(vram, 24, 0, 512), 0xFF0000u);
            EXPECT_EQ(rgbAt(vram, 32, 0, 512), 0u);
            EXPECT_EQ(rgbAt(vram, 40, 1, 512), 0x0000FFu);
            EXPECT_NE(rgbAt(vram, 41, 1, 512), 0u);
            EXPECT_EQ(rgbAt(vram, 4, 0, 512), 0u);
        });
}

}  // namespace
}  // namespace ge::gltest
