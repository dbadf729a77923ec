// SPDX-License-Identifier: MIT
// Differential tests: the same display list through the GL translator and
// the software model (the bit-accurate reference), comparing VRAM byte for byte.
//
// Through-mode scenes must match exactly. Transform-mode scenes share the software model's vertex
// code (geometry/transform.h), so positions and per-vertex values are identical; only GL's
// float interpolation of Gouraud colours and texture coordinates across a triangle can differ from
// the software model's edge-function interpolation, by at most one step on a few pixels.
#include <cstdlib>
#include <cstring>
#include <functional>

#include "softmodel/soft_renderer.h"
#include "tests/gl_fixture.h"
#include "tests/near_clip_scene.h"
#include "tests/reference_quirk_scenes.h"
#include "tests/sprite_position_scene.h"
#include "tests/wide_texture_scene.h"

namespace ge::gltest {
namespace {

struct Frame {
    std::vector<u8> vram;
};

// Runs `build` on a fresh Memory with the given backend; returns the whole of VRAM.
bool renderWith(bool gl, const std::function<void(ListBuilder&)>& build, Frame& out, std::string& err,
                const geo::AccuracyProfile& acc = geo::AccuracyProfile::psp()) {
    Memory mem;
    std::unique_ptr<Renderer> r;
    if (gl) {
        gl::GlOptions go;
        go.accuracy = acc;
        r = gl::createGlRenderer(mem, go, err);
        if (!r) return false;
    } else {
        soft::SoftOptions so;
        so.threads = 1;
        so.accuracy = acc;
        r = soft::createSoftRenderer(mem, so);
    }
    out.vram = runListVram(mem, *r, build);
    return true;
}

// Renders `scene` on the software model and on GL in exact and hardware mode, and runs `check`
// on each one's VRAM (traced with the backend's name).
void checkEveryBackend(const std::function<void(ListBuilder&)>& scene,
                       const std::function<void(const std::vector<u8>&)>& check) {
    Frame s;
    std::string err;
    ASSERT_TRUE(renderWith(false, scene, s, err));
    {
        SCOPED_TRACE("soft");
        check(s.vram);
    }
    for (gl::GlMode mode : {gl::GlMode::Exact, gl::GlMode::Hw}) {
        SCOPED_TRACE(mode == gl::GlMode::Hw ? "GL hw" : "GL exact");
        Memory mem;
        gl::GlOptions opt;
        opt.mode = mode;
        std::unique_ptr<Renderer> r = gl::createGlRenderer(mem, opt, err);
        if (!r) GTEST_SKIP() << "no GL context: " << err;
        check(runListVram(mem, *r, scene));
    }
}

void frameSetup(ListBuilder& b, u32 fmt = GE_FORMAT_8888) {
    b.drawBuffer(fmt, 0, 64);
    b.depthBuffer(0x100000, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.offset(2048 - 32, 2048 - 32);
    b.viewport(2048, 2048, 64, 64);
    b.depthRange(65535, 0);
}

// Max per-byte difference and count of differing bytes over the whole VRAM.
void compare(const Frame& a, const Frame& b, int& maxDiff, size_t& differing) {
    maxDiff = 0;
    differing = 0;
    for (size_t i = 0; i < a.vram.size(); ++i) {
        const int d = std::abs(int(a.vram[i]) - int(b.vram[i]));
        if (d) ++differing, maxDiff = std::max(maxDiff, d);
    }
}

void expectSame(const std::function<void(ListBuilder&)>& build, int allowedMax, size_t allowedBytes,
                const geo::AccuracyProfile& acc = geo::AccuracyProfile::psp()) {
    Frame g, s;
    std::string err;
    if (!renderWith(true, build, g, err, acc)) GTEST_SKIP() << "no GL context: " << err;
    renderWith(false, build, s, err, acc);
    int maxDiff;
    size_t differing;
    compare(g, s, maxDiff, differing);
    EXPECT_LE(maxDiff, allowedMax);
    EXPECT_LE(differing, allowedBytes);
    for (size_t i = 0; i < g.vram.size() && (maxDiff > allowedMax || differing > allowedBytes); i += 4)
        if (std::memcmp(&g.vram[i], &s.vram[i], 4) != 0) {
            ADD_FAILURE() << "first difference at byte 0x" << std::hex << i << ": gl " << readLE32(&g.vram[i])
                          << " soft " << readLE32(&s.vram[i]);
            break;
        }
}

void sprites(ListBuilder& b, bool bilinear) {
    frameSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0x00302010, 0x8000, 0x20);
    std::vector<u32> tex(16 * 16);
    for (int i = 0; i < 256; ++i) tex[size_t(i)] = u32(i * 0x010305) | (u32(i) << 24);
    const u32 addr = b.place(tex.data(), 1024);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, addr, 16, 16, 16);
    b.texFunc(0, true);
    b.texFilter(bilinear ? 1 : 0, bilinear ? 1 : 0);
    b.enable(GE_CMD_TME, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);
    b.enable(GE_CMD_DTE, true);
    const int m[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
    b.setDither(m);
    const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[6];
    // Scale 1, scale 2, and a mirrored one; with bilinear filtering the odd sizes matter too.
    const float pos[3][4] = {{2, 3, 18, 19}, {20, 10, 52, 42}, {61, 50, 45, 34}};
    for (int i = 0; i < 3; ++i) {
        v[2 * i].x = pos[i][0], v[2 * i].y = pos[i][1], v[2 * i].u = 0, v[2 * i].v = 0;
        v[2 * i + 1].x = pos[i][2], v[2 * i + 1].y = pos[i][3], v[2 * i + 1].u = 16, v[2 * i + 1].v = 16;
        v[2 * i].color = v[2 * i + 1].color = 0xC0FFE0A0u - u32(i) * 0x101010u;
    }
    const std::vector<u8> data = packVertices(vtype, v, 6);
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 6, nullptr, data.data());
}

TEST(GlVsSoft, ThroughModeSpritesAreIdentical) {
    expectSame([](ListBuilder& b) { sprites(b, false); }, 0, 0);
}

TEST(GlVsSoft, BilinearSpritesWithinOneWeightStep) {
    // Texture coordinates across a rectangle are interpolated by GL in float and by the software
    // model in double: a sample exactly on a 1/16-texel boundary may take the neighbouring 4-bit
    // weight, changing a channel by at most (Δtexel)/16 ≈ 16 here, on a few pixels.
    expectSame([](ListBuilder& b) {
        sprites(b, true);
        // Stretch one more sprite by a non-integer factor.
        const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        BuildVertex v[2];
        v[0].x = 5, v[0].y = 40, v[1].x = 46, v[1].y = 63, v[1].u = 16, v[1].v = 16;
        const std::vector<u8> data = packVertices(vtype, v, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
    }, 0x20, 64 * 64 * 4 / 20);
}

// Zero-area triangles draw the samples exactly on their line (the reference renderer's rule,
// geometry/raster.cpp rasterZeroAreaTriangle); GL takes them from the software rasteriser.
TEST(GlVsSoft, ZeroAreaTrianglesAreIdentical) {
    auto build = [](ListBuilder& b) {
        frameSetup(b);
        b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0x00000000, 0, 0);
        const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        // Collinear triangles along the diagonal: (P, Q, Q) in white, (Q, P, P) and a strip with
        // a repeated vertex in blue.
        BuildVertex v[6];
        const float xy[6][2] = {{4, 4}, {20, 20}, {20, 20}, {40, 40}, {24, 24}, {24, 24}};
        for (int i = 0; i < 6; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].color = i < 3 ? 0xFFFFFFFFu : 0xFFFF0000u;
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, packVertices(vtype, v, 6).data());
        const float strip[5][2] = {{44, 2}, {44, 12}, {54, 2}, {54, 12}, {54, 12}};
        for (int i = 0; i < 5; ++i) v[i].x = strip[i][0], v[i].y = strip[i][1], v[i].color = 0xFF00C000u;
        b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 5, nullptr, packVertices(vtype, v, 5).data());
    };
    // Profile ppsspp (AccuracyProfile::zeroAreaTriangles; the psp profile draws nothing of them:
    // tests/gl_accuracy_profiles.cpp).
    const geo::AccuracyProfile acc = geo::AccuracyProfile::ppsspp();
    expectSame(build, 0, 0, acc);
    // The software model did draw pixels of the diagonal (the reference's rule, docs/ge-rules.md §8.11).
    Frame s;
    std::string err;
    ASSERT_TRUE(renderWith(false, build, s, err, acc)) << err;
    size_t drawn = 0;
    for (int i = 0; i < 48; ++i) drawn += readLE32(&s.vram[(size_t(i) * 64 + size_t(i)) * 4]) != 0 ? 1 : 0;
    EXPECT_GT(drawn, 0u);
}

void litMesh(ListBuilder& b) {
    frameSetup(b, GE_FORMAT_565);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0x00000000, 0, 0);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    // A simple perspective projection looking down −Z.
    const float proj[16] = {1.5f, 0, 0, 0, 0, 1.5f, 0, 0, 0, 0, -1.01f, -1, 0, 0, -0.2f, 0};
    b.setMatrix(GeMatrix::World, id);
    b.setMatrix(GeMatrix::View, id);
    b.setMatrix(GeMatrix::Proj, proj);
    b.enable(GE_CMD_LTE, true);
    b.enable(GE_CMD_LE0, true);
    const float lpos[3] = {0.3f, 0.5f, 1.0f};
    b.light(0, 0, 1, lpos);
    b.lightColor(0, LIGHT_AMBIENT | LIGHT_DIFFUSE | LIGHT_SPECULAR, 0xFFFFFF);
    b.ambient(0xFF202020);
    b.materialAmbient(0xFF404040);
    b.materialDiffuse(0x80C0FF);
    b.materialSpecular(0xFFFFFF);
    b.specularPower(8.0f);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);
    b.enable(GE_CMD_DTE, true);
    b.enable(GE_CMD_BCE, false);
    // A 4×4 grid strip mesh bent in Z, with normals.
    const u32 vtype = vt::NRM_F | vt::POS_F;
    std::vector<BuildVertex> v;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col <= 4; ++col)
            for (int k = 0; k < 2; ++k) {
                BuildVertex bv;
                bv.x = -0.8f + 0.4f * float(col);
                bv.y = -0.8f + 0.4f * float(row + k);
                bv.z = -2.0f - 0.3f * bv.x * bv.x;
                bv.nx = 0.6f * bv.x, bv.ny = 0.1f, bv.nz = 1.0f;
                v.push_back(bv);
            }
    const std::vector<u8> data = packVertices(vtype, v.data(), u32(v.size()));
    for (int row = 0; row < 4; ++row) {
        const u32 addr = b.place(data.data() + size_t(row) * 10 * VertexLayout::fromVtype(vtype).size,
                                 10 * VertexLayout::fromVtype(vtype).size);
        b.drawArray(GE_PRIM_TRIANGLE_STRIP, vtype, 10, 0, addr);
    }
}

TEST(GlVsSoft, LitPerspectiveMeshMatchesWithinInterpolation) {
    // 16-bit output: a one-step difference in an 8-bit colour before truncation shows as at most
    // one step of the stored field, i.e. a byte difference of up to 0x08 in the packed pixel.
    expectSame(litMesh, 0x21, 64 * 64 * 2 / 50);
}

// A vertex behind the camera passing CLE = 0's discard rule: both backends near-clip it with
// either CLE value and draw the clipped quadrilateral (tests/near_clip_scene.h).
TEST(GlVsSoft, NearClippingWhateverCleSays) {
    for (bool cle : {false, true}) {
        SCOPED_TRACE(cle ? "CLE = 1" : "CLE = 0");
        auto build = [cle](ListBuilder& b) { testscene::nearClipScene(b, cle); };
        Frame g, s;
        std::string err;
        if (!renderWith(true, build, g, err)) GTEST_SKIP() << "no GL context: " << err;
        ASSERT_TRUE(renderWith(false, build, s, err));
        for (const auto& p : testscene::kNearClipProbes) {
            const size_t at = (size_t(p.y) * 512 + size_t(p.x)) * 4;
            EXPECT_EQ(readLE32(&g.vram[at]) & 0xFFFFFF, p.covered ? 0xFFFFFFu : 0u) << "GL " << p.x << "," << p.y;
            EXPECT_EQ(readLE32(&s.vram[at]) & 0xFFFFFF, p.covered ? 0xFFFFFFu : 0u) << "soft " << p.x << "," << p.y;
        }
    }
}

// The reference's skipped alpha test (geometry/reference_rules.h; profile ppsspp) on both backends:
// entry-0 texels are written only when the palette ANDs to non-zero and the vertex alpha is 255.
TEST(GlVsSoft, ReferenceSkipsTheAlphaTestForClutTexturesItTakesAsOpaque) {
    for (u32 entry0 : {0x00000001u, 0x00000000u}) {
        for (u8 alpha : {u8(255), u8(254)}) {
            SCOPED_TRACE(testing::Message() << "entry0 " << entry0 << " vertex alpha " << int(alpha));
            auto build = [&](ListBuilder& b) { testscene::skippedAlphaTestScene(b, entry0, alpha); };
            Frame g, s;
            std::string err;
            const geo::AccuracyProfile acc = geo::AccuracyProfile::ppsspp();
            if (!renderWith(true, build, g, err, acc)) GTEST_SKIP() << "no GL context: " << err;
            ASSERT_TRUE(renderWith(false, build, s, err, acc));
            const u32 want = entry0 && alpha == 255 ? 0x000001u : 0u;
            EXPECT_EQ(readLE32(&g.vram[0]) & 0xFFFFFF, want);
            EXPECT_EQ(readLE32(&s.vram[0]) & 0xFFFFFF, want);
            EXPECT_EQ(readLE32(&g.vram[4]) & 0xFFFFFF, readLE32(&s.vram[4]) & 0xFFFFFF);
        }
    }
}

// Fan triangles near-clipped in the reference's slot order, on both backends (near_clip_scene.h).
TEST(GlVsSoft, NearClippedFanFollowsTheReferenceVertexOrder) {
    using namespace testscene;
    for (bool asTriangles : {false, true}) {
        SCOPED_TRACE(asTriangles ? "triangle list" : "fan");
        auto build = [asTriangles](ListBuilder& b) { nearClipFanScene(b, asTriangles); };
        Frame g, s;
        std::string err;
        if (!renderWith(true, build, g, err)) GTEST_SKIP() << "no GL context: " << err;
        ASSERT_TRUE(renderWith(false, build, s, err));
        auto rgb = [](const Frame& f, int x, int y) { return readLE32(&f.vram[(size_t(y) * 512 + size_t(x)) * 4]) & 0xFFFFFF; };
        const u32 wedge = asTriangles ? 0xFFFFFFu : 0u;
        EXPECT_EQ(rgb(g, kFanProbeFirst.x, kFanProbeFirst.y), 0xFFFFFFu);
        EXPECT_EQ(rgb(s, kFanProbeFirst.x, kFanProbeFirst.y), 0xFFFFFFu);
        EXPECT_EQ(rgb(g, kFanWedgeX, kFanWedgeY), wedge);
        EXPECT_EQ(rgb(s, kFanWedgeX, kFanWedgeY), wedge);
    }
}

// Textures past 512 texels (geometry/texture_size.h, tests/wide_texture_scene.h): the software
// model and GL in exact and hardware mode all scale coordinates by the full 2^n and stop the
// texel index at 511, through mode and transform mode alike (a PSP: texel 2 at pixel 0 of a
// 1024-wide row over 256 pixels). GL used to scale transform-mode coordinates by 512, the
// software model through-mode ones by 2^n/512 too much.
TEST(GlVsSoft, TexturesPast512ReadThePspTexels) {
    for (gl::GlMode mode : {gl::GlMode::Exact, gl::GlMode::Hw}) {
        SCOPED_TRACE(mode == gl::GlMode::Hw ? "GL hw" : "GL exact");
        Memory mem;
        gl::GlOptions opt;
        opt.mode = mode;
        std::string err;
        std::unique_ptr<Renderer> r = gl::createGlRenderer(mem, opt, err);
        if (!r) GTEST_SKIP() << "no GL context: " << err;
        const std::vector<u8> vram = runListVram(mem, *r, testscene::wideTextureScene);
        const std::vector<std::string> bad = testscene::wideTextureMismatches(vram.data());
        EXPECT_TRUE(bad.empty()) << bad.size() << " pixels, first " << bad.front();
    }
    Frame s;
    std::string err;
    ASSERT_TRUE(renderWith(false, testscene::wideTextureScene, s, err));
    const std::vector<std::string> bad = testscene::wideTextureMismatches(s.vram.data());
    EXPECT_TRUE(bad.empty()) << "soft: " << bad.size() << " pixels, first " << bad.front();
}

// A needle-thin triangle (corners of 1.8 and 4.9 degrees) with a blend that reads the destination.
// Its grown outline used to be a bevelled hexagon drawn as a fan whose slivers GL's subpixel
// snapping could flip: pixels on the long edge got three fragments and were blended three times
// through framebuffer fetch or the texture barrier (found by `ge2gl fuzz`, seed 2000953, the
// vertices below are that case's). Every pixel must be blended once, as in the software model.
TEST(GlVsSoft, NeedleTriangleIsBlendedOncePerPixel) {
    auto build = [](ListBuilder& b) {
        b.drawBuffer(GE_FORMAT_565, 0, 512);
        b.depthBuffer(0x110000, 512);
        b.scissor(0, 0, 480, 272);
        b.region(0, 0, 480, 272);
        b.clear(CLEAR_COLOR, 0xFF808080, 0);
        b.shadeModel(false);
        b.enable(GE_CMD_ABE, true);
        b.blendFunc(0, 0, 0);  // add(destination colour, source colour): reads the destination
        BuildVertex v[3];
        const float pos[3][3] = {{114.497f, 61.241f, 30813}, {380, 198, 51447}, {487, 238, 59082}};
        const u32 col[3] = {0xD323D4A4, 0xFFC49280, 0xDE6DE647};
        for (int i = 0; i < 3; ++i) v[i].x = pos[i][0], v[i].y = pos[i][1], v[i].z = pos[i][2], v[i].color = col[i];
        const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_F | vt::THROUGH;
        const std::vector<u8> data = packVertices(vtype, v, 3);
        b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 3, nullptr, data.data());
    };
    Frame g, s;
    std::string err;
    // The fuzzer's case ran with PPSSPP's sample point (the ppsspp profile): the pixels below are
    // chosen for it.
    const geo::AccuracyProfile ppsspp = geo::AccuracyProfile::ppsspp();
    if (!renderWith(true, build, g, err, ppsspp)) GTEST_SKIP() << "no GL context: " << err;
    ASSERT_TRUE(renderWith(false, build, s, err, ppsspp));
    auto px = [](const Frame& f, int x, int y) { return readLE16(&f.vram[(size_t(y) * 512 + size_t(x)) * 2]); };
    // (198,104) lies on the long edge, (199,104) inside, (197,104) outside (the clear colour).
    EXPECT_NE(px(s, 197, 104), px(s, 199, 104));
    EXPECT_EQ(px(s, 198, 104), px(s, 199, 104));
    EXPECT_EQ(px(g, 198, 104), px(s, 198, 104));
    size_t differing = 0;
    for (int y = 0; y < 272; ++y)
        for (int x = 0; x < 480; ++x) differing += px(g, x, y) != px(s, x, y);
    EXPECT_EQ(differing, 0u);
}

// Immediate vertices' secondary colour (I2) is added only with separate specular (LMODE 1) in
// transform mode (geometry/assembly.cpp immediateVertices; a PSP, pspautotests
// gpu/primitives/immediate: (0, 127, 255) + I2 0x7F7F7F shows 0x7FFEFF with LMODE 1 in transform
// mode and 0x007FFF in through mode). Four 8x8 immediate sprites of RGB (0x10, 0x20, 0x30) with
// I2 = 0x7F7F7F: transform mode with LMODE 0 and 1, through mode with LMODE 0 and 1. The software
// model and GL in exact and hardware mode.
void immediateSecondaryScene(ListBuilder& b) {
    frameSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    auto sprite = [&](int x, int y, bool through, bool lmode1) {
        b.setVertexType(through ? vt::THROUGH : 0u);
        b.lightMode(lmode1);
        // X2/Y2: drawing position · 16 plus OFFSETX/Y (transform mode) or 0x8000 (through mode).
        const u32 bx = through ? 0x8000 : (2048 - 32) << 4, by = through ? 0x8000 : (2048 - 32) << 4;
        for (int k = 0; k < 2; ++k) {
            b.cmd(GE_CMD_X2, bx + u32((x + 8 * k) << 4));
            b.cmd(GE_CMD_Y2, by + u32((y + 8 * k) << 4));
            b.cmd(GE_CMD_Z2, 0);
            b.cmd(GE_CMD_RGB2, 0x302010);
            b.cmd(GE_CMD_F2, 0xFF);
            b.cmd(GE_CMD_I2, 0x7F7F7F);
            b.cmd(GE_CMD_AP2, 0xFF | u32(k ? GE_PRIM_KEEP_PREVIOUS : GE_PRIM_RECTANGLES) << 8);
        }
        b.lightMode(false);  // any other command ends the immediate primitive
    };
    sprite(0, 0, false, false);
    sprite(10, 0, false, true);
    sprite(20, 0, true, false);
    sprite(30, 0, true, true);
}

TEST(GlVsSoft, ImmediateSecondaryColourOnlyWithSeparateSpecularInTransformMode) {
    auto check = [](const std::vector<u8>& vram) {
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 64 + size_t(x)) * 4]) & 0xFFFFFFu; };
        for (int y : {0, 7}) {
            EXPECT_EQ(rgb(0, y), 0x302010u) << "transform mode, LMODE 0";
            EXPECT_EQ(rgb(17, y), 0xAF9F8Fu) << "transform mode, LMODE 1: + 0x7F7F7F";
            EXPECT_EQ(rgb(20, y), 0x302010u) << "through mode, LMODE 0";
            EXPECT_EQ(rgb(37, y), 0x302010u) << "through mode, LMODE 1";
        }
        EXPECT_EQ(rgb(8, 0), 0u);
    };
    checkEveryBackend(immediateSecondaryScene, check);
}

// Clear mode draws flat whatever shading is asked for (geometry/draw_front_end.cpp
// rasterParamsFor, after PPSSPP's software renderer), also when an immediate primitive's AP2 flags
// ask for Gouraud shading (bit 18): one draw front end gives every backend the same rule. A
// through-mode immediate triangle (0,0) red, (32,0) green, (0,32) blue, drawn in clear mode with
// colour writes: every covered pixel takes the provoking (last) vertex's colour.
void immediateClearModeScene(ListBuilder& b) {
    frameSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    b.setVertexType(vt::THROUGH);
    b.cmd(GE_CMD_CMODE, (CLEAR_COLOR << 8) | 1);
    const int pos[3][2] = {{0, 0}, {32, 0}, {0, 32}};
    const u32 rgb[3] = {0x0000FF, 0x00FF00, 0xFF0000};
    for (int k = 0; k < 3; ++k) {
        b.cmd(GE_CMD_X2, 0x8000 + u32(pos[k][0] << 4));
        b.cmd(GE_CMD_Y2, 0x8000 + u32(pos[k][1] << 4));
        b.cmd(GE_CMD_Z2, 0);
        b.cmd(GE_CMD_RGB2, rgb[k]);
        b.cmd(GE_CMD_AP2, 0xFF | u32(k ? GE_PRIM_KEEP_PREVIOUS : GE_PRIM_TRIANGLES) << 8 | 1u << 18);
    }
    b.cmd(GE_CMD_CMODE, 0);  // any other command ends the immediate primitive
}

// The draw front end makes a draw's transform state again only when a register group it reads
// changed (geo::DrawFrontEnd::setTransform, the packets' GeDirty groups): three draws of the same
// vertices, each after one group changed. A 16x16 rectangle of two triangles without a vertex
// colour (so MAC colours it) at the top left; OFFSETX moved by 32 pixels (TRANSFORM) draws it at
// the top right, still red; MAC green (LIGHTING) then turns the right one green. A draw that kept
// the old transform state would land left, or stay red. Then a fragment-side change alone (below).
void dirtyGroupsScene(ListBuilder& b) {
    frameSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    b.setMatrix(GeMatrix::World, id);
    b.setMatrix(GeMatrix::View, id);
    b.setMatrix(GeMatrix::Proj, id);
    b.enable(GE_CMD_BCE, false);
    // Viewport 64x64 around (2048, 2048) with the drawing area's origin at 2048 − 32: clip x −1
    // is pixel 0, x 1 pixel 64 (y is flipped: clip y 1 is row 0).
    const u32 vtype = vt::POS_F;
    const float xy[6][2] = {{-1, 1}, {-0.5f, 1}, {-1, 0.5f}, {-0.5f, 1}, {-0.5f, 0.5f}, {-1, 0.5f}};
    BuildVertex v[6];
    for (int i = 0; i < 6; ++i) v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].z = 0.5f;
    const auto bytes = packVertices(vtype, v, 6);
    b.materialAmbient(0xFF0000FF);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, bytes.data());
    b.offset(2048 - 32 - 32, 2048 - 32);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, bytes.data());
    b.materialAmbient(0xFF00FF00);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, bytes.data());
    // Two through-mode rectangles at (0, 44)–(16, 60), colour and place from the vertices alone:
    // red, then white after PMSK1 protects green (BLEND, the only group that changes between
    // them): magenta. A draw that kept the first one's keys (the GL key cache) would leave white.
    const u32 tv = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex r[2];
    r[0].x = 0, r[0].y = 44, r[1].x = 16, r[1].y = 60;
    for (u32 c : {0xFF0000FFu, 0xFFFFFFFFu}) {
        if (c == 0xFFFFFFFFu) b.pixelMask(0x00FF00, 0);
        r[0].color = r[1].color = c;
        const auto rect = packVertices(tv, r, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, tv, 2, nullptr, rect.data());
    }
}

TEST(GlVsSoft, EachDrawSeesTheRegisterGroupsChangedBeforeIt) {
    checkEveryBackend(dirtyGroupsScene, [](const std::vector<u8>& vram) {
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 64 + size_t(x)) * 4]) & 0xFFFFFFu; };
        EXPECT_EQ(rgb(8, 8), 0x0000FFu);
        EXPECT_EQ(rgb(40, 8), 0x00FF00u);
        EXPECT_EQ(rgb(24, 8), 0u);
        EXPECT_EQ(rgb(8, 40), 0u);
        EXPECT_EQ(rgb(8, 52), 0xFF00FFu);
    });
}

TEST(GlVsSoft, ImmediatePrimitivesInClearModeDrawFlat) {
    checkEveryBackend(immediateClearModeScene, [](const std::vector<u8>& vram) {
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 64 + size_t(x)) * 4]) & 0xFFFFFFu; };
        for (const auto& [x, y] : {std::pair{1, 1}, {20, 2}, {2, 20}, {10, 10}})
            EXPECT_EQ(rgb(x, y), 0xFF0000u) << x << "," << y;
        EXPECT_EQ(rgb(40, 40), 0u);
    });
}

// Transform-mode sprites reach the screen by the PSP's rule on every backend
// (tests/sprite_position_scene.h; GL takes the CPU vertex path for rectangles in both modes).
TEST(GlVsSoft, TransformModeSpritesRoundAsThePspDoes) {
    checkEveryBackend(testscene::spritePositionScene, [](const std::vector<u8>& vram) {
        testscene::checkSpritePositionScene(
            [&](int x, int y) { return readLE32(&vram[(size_t(y) * 512 + size_t(x)) * 4]) & 0xFFFFFFu; });
    });
}

// A draw whose vertex format has no texture coordinates takes the vertex unit's last ones
// (GeState::latchUV): a PSP shows it in pspautotests gpu/texmtx/source (the previous draw's last
// UV becomes the source of a draw without UVs), and the reference renderer keeps them the same
// way (PPSSPP TransformUnit.cpp ReadVertex lastTC, updated only when it reads UVs: texture mapping
// on, not clear mode; the last vertex read is the last index in draw order, or the highest index
// when an indexed draw reuses vertices). Through-mode rectangles over a 2x2 texture, nearest,
// REPLACE: texel (0,0) red, (1,0) green, (0,1) blue, (1,1) white.
void latchedUvScene(ListBuilder& b) {
    frameSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    // Rows 4 texels apart: the smallest 8888 buffer width (16 bytes, manual §6.2).
    const u32 texels[8] = {0xFF0000FFu, 0xFF00FF00u, 0, 0, 0xFFFF0000u, 0xFFFFFFFFu, 0, 0};
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, b.place(texels, sizeof texels), 2, 2, 4);
    b.texFunc(3, true);  // REPLACE (manual §13.13)
    b.texFilter(0, 0);
    b.enable(GE_CMD_TME, true);
    const u32 withUv = vt::TC_F | vt::COL_8888 | vt::POS_16 | vt::THROUGH, noUv = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    auto rect = [&](u32 vtype, float x, float y, float u, float v) {
        BuildVertex q[2];
        q[0].x = x, q[0].y = y, q[1].x = x + 8, q[1].y = y + 8;
        q[0].u = q[1].u = u, q[0].v = q[1].v = v;
        q[0].color = q[1].color = 0xFF808080u;
        const std::vector<u8> data = packVertices(vtype, q, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
    };
    rect(withUv, 0, 0, 1.5f, 0.5f);   // green, latches (1.5, 0.5)
    rect(noUv, 10, 0, 0, 0);          // green: the latch
    b.enable(GE_CMD_TME, false);
    rect(withUv, 20, 0, 0.5f, 1.5f);  // grey vertex colour; texture mapping off: latch unchanged
    b.enable(GE_CMD_TME, true);
    rect(noUv, 30, 0, 0, 0);          // green still
    // Indexed: v0 (0.5, 1.5) blue, v1 unused, v2 (1.5, 1.5) white, drawn at (40..48, 20..28).
    BuildVertex v[3];
    v[0].x = 48, v[0].y = 28, v[0].u = 0.5f, v[0].v = 1.5f;
    v[1].x = 44, v[1].y = 24;
    v[2].x = 40, v[2].y = 20, v[2].u = 1.5f, v[2].v = 1.5f;
    const std::vector<u8> data = packVertices(withUv | vt::IDX_8, v, 3);
    const u8 drawOrder[2] = {2, 0};  // fewer indices than the range's 3 vertices: index 0 is read last
    b.drawArrayData(GE_PRIM_RECTANGLES, withUv | vt::IDX_8, 2, drawOrder, data.data());
    rect(noUv, 0, 10, 0, 0);   // blue
    const u8 reuse[4] = {0, 2, 2, 0};  // more indices than vertices in 0..2: the range is read, 2 last
    b.drawArrayData(GE_PRIM_RECTANGLES, withUv | vt::IDX_8, 4, reuse, data.data());
    rect(noUv, 10, 10, 0, 0);  // white
}

TEST(GlVsSoft, DrawsWithoutUvTakeTheLastUvTheVertexUnitRead) {
    auto check = [](const std::vector<u8>& vram) {
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 64 + size_t(x)) * 4]) & 0xFFFFFFu; };
        EXPECT_EQ(rgb(4, 4), 0x00FF00u) << "with UV (1.5, 0.5)";
        EXPECT_EQ(rgb(14, 4), 0x00FF00u) << "without UV: the latched (1.5, 0.5)";
        EXPECT_EQ(rgb(24, 4), 0x808080u) << "texture mapping off";
        EXPECT_EQ(rgb(34, 4), 0x00FF00u) << "a draw with texture mapping off latches nothing";
        EXPECT_EQ(rgb(4, 14), 0xFF0000u) << "indexed: the last index in draw order";
        EXPECT_EQ(rgb(14, 14), 0xFFFFFFu) << "indexed with reuse: the highest index";
    };
    checkEveryBackend(latchedUvScene, check);
}

// Fragment uniforms are uploaded only when the program does not already hold them (the GL
// renderer's per-program shadow): programs alternate here with the same and with other texture
// environment colours, so a shadow kept for the wrong program or not refreshed shows as a
// sprite in the wrong colour. Texture function BLEND mixes the vertex colour and the environment
// colour by the texel (manual §13.13).
TEST(GlVsSoft, UniformsFollowEachProgramAcrossSwitches) {
    expectSame([](ListBuilder& b) {
        frameSetup(b);
        b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
        const u32 texels[4] = {0xFF404040u, 0xFFC0C0C0u, 0xFF808080u, 0xFFFFFFFFu};
        b.texMode(GE_TFMT_8888, 0, false);
        b.setTexture(0, b.place(texels, sizeof texels), 4, 1, 4);
        b.texFunc(2, false);  // BLEND
        b.texFilter(0, 0);
        b.enable(GE_CMD_TME, true);
        const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        // Even sprites one program, odd ones another (the alpha test on); each colour is set
        // first for one program and then for the other, which a shadow shared by the programs
        // would take as already uploaded.
        const u32 env[8] = {0x0000FF, 0x00FF00, 0x00FF00, 0xFF0000, 0xFF0000, 0xFF0000, 0xFF00FF, 0xFF00FF};
        b.alphaFunc(7, 0x10);  // GEQUAL 0x10: every texel passes
        for (int i = 0; i < 8; ++i) {
            b.enable(GE_CMD_ATE, (i & 1) != 0);
            b.texEnvColor(env[i]);
            BuildVertex q[2];
            q[0].x = float(8 * i), q[0].y = 0, q[1].x = float(8 * i + 7), q[1].y = 16, q[1].u = 4, q[1].v = 1;
            q[0].color = q[1].color = 0xFF302010u;
            const std::vector<u8> data = packVertices(vtype, q, 2);
            b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
        }
    }, 0, 0);
}

}  // namespace
}  // namespace ge::gltest
