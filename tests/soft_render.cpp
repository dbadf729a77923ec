// SPDX-License-Identifier: MIT
// End-to-end tests of the software renderer: display lists built with ListBuilder, executed by
// GeEngine, drawn by SoftRenderer into emulated VRAM. Checks coverage, culling sense (docs/ge-rules.md §3.6),
// PRIM type 7 continuation (ge-rules.md §3.2), near clipping (ge-rules.md §8.5), immediate vertices (ge-rules.md §3.12), render to
// texture ordering and thread-count independence of the output.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "hle/ge_engine.h"
#include "softmodel/soft_renderer.h"
#include "tests/near_clip_scene.h"
#include "tests/reference_quirk_scenes.h"
#include "tests/sprite_position_scene.h"

using namespace ge;
using namespace ge::soft;

namespace {

constexpr u32 kFb = 0x04000000, kZb = 0x04088000, kFb2 = 0x04110000;
constexpr u32 kStride = 512;

struct Scene {
    Memory mem{16u << 20};  // the builder's arena starts at 0x08800000
    ListBuilder b{&mem};

    Scene() {
        b.drawBuffer(GE_FORMAT_8888, 0, kStride);
        b.depthBuffer(kZb - Memory::kVramBase, kStride);
        b.scissor(0, 0, 480, 272);
        b.region(0, 0, 480, 272);
        b.offset(2048 - 240, 2048 - 136);
        b.viewport(2048, 2048, 480, 272);
        b.depthRange(65535, 0);
        b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    }
    // Runs the list on a fresh renderer with `threads` and returns the whole of VRAM.
    std::vector<u8> run(int threads, const geo::AccuracyProfile& acc = geo::AccuracyProfile::psp(),
                        SoftStats* stats = nullptr) {
        ListBuilder copy = b;
        copy.finish();
        const u32 list = copy.placeList();
        SoftOptions o;
        o.threads = threads;
        o.accuracy = acc;
        auto r = createSoftRenderer(mem, o);
        mem.fill(Memory::kVramBase, 0, Memory::kVramSize);
        GeEngine eng(mem, r.get());
        eng.startList(list, 0);
        EXPECT_EQ(eng.run(), RunStatus::Completed);
        r->flushToMemory();
        if (stats) *stats = static_cast<SoftRenderer*>(r.get())->stats();
        const u8* v = mem.ptr(Memory::kVramBase, Memory::kVramSize);
        return std::vector<u8>(v, v + Memory::kVramSize);
    }
    static u32 pixel(const std::vector<u8>& vram, u32 fb, int x, int y) {
        // RGB only: without a stencil test drawing keeps the alpha (stencil) bits (ge-rules.md §8.7).
        return readLE32(&vram[(fb - Memory::kVramBase) + (u32(y) * kStride + u32(x)) * 4]) & 0xFFFFFF;
    }
    // Through-mode vertices: 8888 colour, 16-bit position.
    static constexpr u32 kThrough = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    void throughPrim(u32 prim, const std::vector<BuildVertex>& v) {
        auto bytes = packVertices(kThrough, v.data(), u32(v.size()));
        b.drawArrayData(prim, kThrough, u32(v.size()), nullptr, bytes.data());
    }
};

BuildVertex tv(float x, float y, u32 color, float z = 0) {
    BuildVertex v;
    v.x = x, v.y = y, v.z = z;
    v.color = color;
    return v;
}

}  // namespace

TEST(SoftRender, ThroughRectangleCoversHalfOpenBox) {
    Scene s;
    s.throughPrim(GE_PRIM_RECTANGLES, {tv(10, 10, 0xFF0000FF), tv(20, 15, 0xFF0000FF)});
    auto vram = s.run(1);
    EXPECT_EQ(Scene::pixel(vram, kFb, 10, 10), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(vram, kFb, 19, 14), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(vram, kFb, 20, 14), 0x000000u);  // x2 excluded
    EXPECT_EQ(Scene::pixel(vram, kFb, 19, 15), 0x000000u);  // y2 excluded
    EXPECT_EQ(Scene::pixel(vram, kFb, 9, 10), 0x000000u);
    int n = 0;
    for (int y = 0; y < 272; ++y)
        for (int x = 0; x < 480; ++x) n += Scene::pixel(vram, kFb, x, y) == 0x0000FFu;
    EXPECT_EQ(n, 10 * 5);
}

TEST(SoftRender, TransformedTriangleLandsWhereTheViewportPutsIt) {
    Scene s;
    // Identity matrices: clip = model. Viewport 480×272 centred at 2048 with the usual offset:
    // drawing x = 240 + 240·X, y = 136 − 136·Y.
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    s.b.setMatrix(GeMatrix::World, id);
    s.b.setMatrix(GeMatrix::View, id);
    s.b.setMatrix(GeMatrix::Proj, id);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
    BuildVertex v[3];
    v[0].x = -0.5f, v[0].y = 0.5f;   // (120, 68)
    v[1].x = 0.5f, v[1].y = 0.5f;    // (360, 68)
    v[2].x = -0.5f, v[2].y = -0.5f;  // (120, 204)
    for (auto& e : v) e.color = 0xFF00FF00, e.z = 0.25f;
    auto bytes = packVertices(vtype, v, 3);
    s.b.enable(GE_CMD_CLE, true);
    s.b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, bytes.data());
    auto vram = s.run(1);
    EXPECT_EQ(Scene::pixel(vram, kFb, 121, 69), 0x00FF00u);
    EXPECT_EQ(Scene::pixel(vram, kFb, 120, 68), 0x00FF00u);  // top-left corner centre is inside
    EXPECT_EQ(Scene::pixel(vram, kFb, 119, 100), 0x000000u);
    EXPECT_EQ(Scene::pixel(vram, kFb, 300, 190), 0x000000u);  // beyond the hypotenuse
    EXPECT_EQ(Scene::pixel(vram, kFb, 355, 68), 0x00FF00u);
    EXPECT_EQ(Scene::pixel(vram, kFb, 359, 68), 0x000000u);  // centre just right of the hypotenuse
    // Depth written: Z = SZ·0.25 + TZ with sceGuDepthRange(65535, 0): −32767.5·0.25 + 32767.5.
    const u16 z = readLE16(&vram[(kZb - Memory::kVramBase) + (100u * kStride + 150u) * 2]);
    EXPECT_EQ(z, 0);  // depth writes are off (ZTE = 0)
}

// A patch wholly beyond a side of the clip rectangle is not tessellated: its surface lies in its
// control points' hull (geometry/draw_front_end.cpp patchOffClip), so it would draw nothing. One
// reaching into the rectangle is drawn, and control points with W <= 0 are not judged.
TEST(SoftRender, PatchesWhollyBeyondTheClipRectangleAreCulledAndOnlyThose) {
    struct Case {
        const char* what;
        float x0, x1;   // the control points' X span (model = clip X; drawing x = 240 + 240·X)
        float w;        // the projection's W row: clip W = w (identity otherwise)
        bool through;   // through mode: the control points in drawing coordinates (x0..x1, y 100..140)
        u64 culled;
        int lit;        // pixels drawn in row 136 (through mode: row 120)
    };
    const Case cases[] = {
        {"right of the screen", 1.05f, 1.5f, 1.0f, false, 1, 0},                 // x 492 … 600
        {"reaching in from the right", 0.9f, 1.5f, 1.0f, false, 0, 480 - 456},  // x 456 … 600
        // Projected to x 492 … 600 too, but by a negative W: the hull test does not hold there.
        {"beyond the right edge, W < 0", 1.05f, 1.5f, -1.0f, false, 0, 0},
        {"through mode, right of the screen", 483.0f, 520.0f, 1.0f, true, 1, 0},
        {"through mode, two pixels in", 478.0f, 520.0f, 1.0f, true, 0, 2},
    };
    for (const Case& c : cases) {
        Scene s;
        const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, c.w};
        s.b.setMatrix(GeMatrix::World, id);
        s.b.setMatrix(GeMatrix::View, id);
        s.b.setMatrix(GeMatrix::Proj, proj);
        s.b.enable(GE_CMD_CLE, true);
        s.b.patchDivide(4, 4);
        const u32 vtype = vt::COL_8888 | vt::POS_F | (c.through ? vt::THROUGH : 0);
        BuildVertex v[16];
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                BuildVertex& e = v[j * 4 + i];
                e.x = c.x0 + (c.x1 - c.x0) * float(i) / 3.0f;
                e.y = c.through ? 100.0f + 40.0f * float(j) / 3.0f : (0.5f - float(j) / 3.0f) * c.w;
                e.z = c.through ? 1000.0f : 0.25f * c.w;
                if (!c.through) e.x *= c.w;  // clip X = x·w: the same projected place whatever W's sign
                e.color = 0xFF00FF00;
            }
        const auto bytes = packVertices(vtype, v, 16);
        s.b.drawBezier(vtype, 4, 4, 0, s.b.place(bytes.data(), u32(bytes.size()), 4));
        SoftStats st;
        const auto vram = s.run(1, geo::AccuracyProfile::psp(), &st);
        const int row = c.through ? 120 : 136;
        int lit = 0;
        for (int x = 0; x < 480; ++x) lit += Scene::pixel(vram, kFb, x, row) == 0x00FF00u;
        EXPECT_EQ(st.culledPatches, c.culled) << c.what;
        EXPECT_EQ(lit, c.lit) << c.what;
    }
}

TEST(SoftRender, CullingSense) {
    // Clockwise on screen (y down): (10,10) → (40,10) → (10,40).
    auto draw = [](bool cullOn, bool ccwBit, bool clockwise) {
        Scene s;
        s.b.enable(GE_CMD_BCE, cullOn);
        s.b.cullMode(ccwBit);
        if (clockwise) s.throughPrim(GE_PRIM_TRIANGLES, {tv(10, 10, 0xFFFFFFFF), tv(40, 10, 0xFFFFFFFF), tv(10, 40, 0xFFFFFFFF)});
        else s.throughPrim(GE_PRIM_TRIANGLES, {tv(10, 10, 0xFFFFFFFF), tv(10, 40, 0xFFFFFFFF), tv(40, 10, 0xFFFFFFFF)});
        auto vram = s.run(1);
        return Scene::pixel(vram, kFb, 15, 15) == 0xFFFFFFu;
    };
    // CULL = 0 culls clockwise triangles, CULL = 1 counter-clockwise ones (ge-rules.md §3.6).
    EXPECT_FALSE(draw(true, false, true));
    EXPECT_TRUE(draw(true, false, false));
    EXPECT_TRUE(draw(true, true, true));
    EXPECT_FALSE(draw(true, true, false));
    EXPECT_TRUE(draw(false, false, true));
    EXPECT_TRUE(draw(false, true, false));
    // Clear mode never culls.
    Scene c;
    c.b.enable(GE_CMD_BCE, true);
    c.b.cullMode(false);
    c.b.cmd(GE_CMD_CMODE, 1 | 1 << 8);
    c.throughPrim(GE_PRIM_TRIANGLES, {tv(10, 10, 0xFF123456), tv(40, 10, 0xFF123456), tv(10, 40, 0xFF123456)});
    c.b.cmd(GE_CMD_CMODE, 0);
    EXPECT_EQ(Scene::pixel(c.run(1), kFb, 15, 15), 0x123456u);
}

TEST(SoftRender, StripContinuesAcrossPrimType7) {
    std::vector<BuildVertex> strip;
    for (int i = 0; i < 8; ++i)
        strip.push_back(tv(float(20 + 30 * (i / 2)), float(i % 2 ? 80 : 20), 0xFF000000 | u32(i * 30) << 8 | 0xFF, 0));
    Scene whole;
    whole.throughPrim(GE_PRIM_TRIANGLE_STRIP, strip);
    Scene split;
    auto bytes = packVertices(Scene::kThrough, strip.data(), 8);
    const u32 addr = split.b.place(bytes.data(), u32(bytes.size()));
    split.b.setVertexType(Scene::kThrough);
    split.b.drawArray(GE_PRIM_TRIANGLE_STRIP, Scene::kThrough, 3, 0, addr);
    split.b.drawArray(GE_PRIM_KEEP_PREVIOUS, Scene::kThrough, 1, 0, 0);  // pointer continues
    split.b.drawArray(GE_PRIM_KEEP_PREVIOUS, Scene::kThrough, 4, 0, 0);
    auto a = whole.run(1), c = split.run(1);
    EXPECT_TRUE(a == c);
    EXPECT_NE(Scene::pixel(a, kFb, 100, 50), 0x000000u);
    // Culling follows the strip's alternating winding across the split too: with culling on,
    // exactly every second triangle survives, the same ones either way.
    whole.b.enable(GE_CMD_BCE, true);
    whole.throughPrim(GE_PRIM_TRIANGLE_STRIP, strip);
    split.b.enable(GE_CMD_BCE, true);
    split.b.drawArray(GE_PRIM_TRIANGLE_STRIP, Scene::kThrough, 3, 0, addr);
    split.b.drawArray(GE_PRIM_KEEP_PREVIOUS, Scene::kThrough, 5, 0, 0);
    EXPECT_TRUE(whole.run(1) == split.run(1));
}

// CLE = 0 drops a triangle with a vertex outside |z/w| < 1; CLE = 1 keeps it and clips it.
TEST(SoftRender, NearVertexDroppedWithoutCleClippedWithIt) {
    auto draw = [](bool cle) {
        Scene s;
        const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        s.b.setMatrix(GeMatrix::World, id);
        s.b.setMatrix(GeMatrix::View, id);
        s.b.setMatrix(GeMatrix::Proj, id);
        s.b.enable(GE_CMD_CLE, cle);
        constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
        BuildVertex v[3];
        v[0].x = -0.5f, v[0].y = 0.5f, v[0].z = -3.0f;  // beyond the near plane (z < −w)
        v[1].x = 0.5f, v[1].y = 0.5f, v[1].z = 0.5f;
        v[2].x = -0.5f, v[2].y = -0.5f, v[2].z = 0.5f;
        for (auto& e : v) e.color = 0xFFFFFFFF;
        auto bytes = packVertices(vtype, v, 3);
        s.b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, bytes.data());
        auto vram = s.run(1);
        int n = 0;
        for (int y = 0; y < 272; ++y)
            for (int x = 0; x < 480; ++x) n += Scene::pixel(vram, kFb, x, y) == 0xFFFFFFu;
        return n;
    };
    EXPECT_EQ(draw(false), 0);  // CLE = 0: a vertex beyond the near plane drops the triangle
    const int clipped = draw(true);
    EXPECT_GT(clipped, 1000);
    EXPECT_LT(clipped, 240 * 136 / 2);  // less than the unclipped triangle
}

// Records a scene (tests/near_clip_scene.h, reference_quirk_scenes.h) as a frame dump with
// DumpRecorder, replays the dump with the software model on one thread, and reads the 512-stride
// 8888 frame at VRAM offset 0: the rules are checked on the path real dumps take.
struct NearClipRender {
    Memory mem{16u << 20};
    explicit NearClipRender(const std::function<void(ListBuilder&)>& build,
                            const geo::AccuracyProfile& acc = geo::AccuracyProfile::psp()) {
        Memory src{16u << 20};
        dump::DumpWriter w;
        DumpRecorder rec(src, w);
        GeState init;
        init.reset();
        for (int op = 0; op < 256; ++op) init.regs[op] = u32(op) << 24;
        rec.begin(init, Memory::kVramBase, 512, GE_FORMAT_8888);
        ListBuilder b(&src);
        b.attach(&rec);
        build(b);
        rec.end(Memory::kVramBase, 512, GE_FORMAT_8888);
        EXPECT_TRUE(rec.warnings().empty());
        SoftOptions o;
        o.threads = 1;
        o.accuracy = acc;
        auto r = createSoftRenderer(mem, o);
        GeEngine eng(mem, r.get());
        dump::ReplayResult res;
        std::string err;
        EXPECT_TRUE(dump::replayDump(w.dump(), eng, {}, res, err)) << err;
        EXPECT_EQ(res.listErrors, 0u) << res.warning;
    }
    u32 rgb(int x, int y) const { return mem.read32(Memory::kVramBase + (u32(y) * 512 + u32(x)) * 4) & 0xFFFFFF; }
};

// A vertex behind the camera that passes CLE = 0's discard rule is near-clipped with either CLE
// value (tests/near_clip_scene.h).
TEST(SoftRender, NearClippingWhateverCleSays) {
    for (bool cle : {false, true}) {
        SCOPED_TRACE(cle ? "CLE = 1" : "CLE = 0");
        NearClipRender r([cle](ListBuilder& b) { testscene::nearClipScene(b, cle); });
        for (const auto& p : testscene::kNearClipProbes)
            EXPECT_EQ(r.rgb(p.x, p.y), p.covered ? 0xFFFFFFu : 0u) << p.x << "," << p.y;
    }
}

// Transform-mode sprites reach the screen by the PSP's rule (tests/sprite_position_scene.h), on the
// path a recorded dump takes.
TEST(SoftRender, TransformModeSpritesRoundAsThePspDoes) {
    NearClipRender r(testscene::spritePositionScene);
    testscene::checkSpritePositionScene([&](int x, int y) { return r.rgb(x, y); });
}

// Fan triangles are clipped in the reference's slot order (centre, odd, even vertex): the second
// triangle of the fan loses its wedge, the same triangle drawn from a triangle list keeps it.
TEST(SoftRender, NearClippedFanFollowsTheReferenceVertexOrder) {
    using namespace testscene;
    NearClipRender fan([](ListBuilder& b) { nearClipFanScene(b, false); });
    NearClipRender list([](ListBuilder& b) { nearClipFanScene(b, true); });
    EXPECT_EQ(fan.rgb(kFanProbeFirst.x, kFanProbeFirst.y), 0xFFFFFFu);
    EXPECT_EQ(list.rgb(kFanProbeFirst.x, kFanProbeFirst.y), 0xFFFFFFu);
    EXPECT_EQ(fan.rgb(kFanWedgeX, kFanWedgeY), 0u);
    EXPECT_EQ(list.rgb(kFanWedgeX, kFanWedgeY), 0xFFFFFFu);
}

// The reference drops an alpha test GREATER 0 for a CLUT texture whose used entries AND to a
// non-zero value when every vertex alpha is 255 (geometry/reference_rules.h referenceSkipsAlphaTest;
// profile ppsspp, AccuracyProfile::clutSkipsAlphaTest).
TEST(SoftRender, ReferenceSkipsTheAlphaTestForClutTexturesItTakesAsOpaque) {
    struct Case {
        u32 entry0;
        u8 vertexAlpha;
        u32 zeroTexel;  // RGB where the texel is entry 0
    };
    for (const Case& c : {Case{0x00000001, 255, 0x000001}, Case{0x00000000, 255, 0}, Case{0x00000001, 254, 0}}) {
        SCOPED_TRACE(testing::Message() << "entry0 " << c.entry0 << " vertex alpha " << int(c.vertexAlpha));
        NearClipRender r([&](ListBuilder& b) { testscene::skippedAlphaTestScene(b, c.entry0, c.vertexAlpha); },
                         geo::AccuracyProfile::ppsspp());
        EXPECT_EQ(r.rgb(0, 0), c.zeroTexel);
        EXPECT_EQ(r.rgb(1, 0), 0x0000FFu);  // red
        EXPECT_EQ(r.rgb(3, 3), c.zeroTexel);
        EXPECT_EQ(r.rgb(4, 0), 0u);  // outside the rectangle
    }
}

TEST(SoftRender, ImmediateVertices) {
    Scene s;
    // Through mode for the immediate vertices: X2/Y2 = (x << 4) + 0x8000 (ge-rules.md §3.12).
    s.b.setVertexType(vt::THROUGH);
    auto vertex = [&](int x, int y, u32 rgb, u32 ap2) {
        s.b.cmd(GE_CMD_X2, u32(x * 16 + 0x8000));
        s.b.cmd(GE_CMD_Y2, u32(y * 16 + 0x8000));
        s.b.cmd(GE_CMD_Z2, 0);
        s.b.cmd(GE_CMD_RGB2, rgb);
        s.b.cmd(GE_CMD_AP2, ap2);
    };
    vertex(30, 30, 0x00FF00, 0xFF | GE_PRIM_RECTANGLES << 8);
    vertex(50, 40, 0x0000FF, 0xFF | GE_PRIM_KEEP_PREVIOUS << 8);
    s.b.nop();  // ends the immediate primitive
    auto vram = s.run(1);
    EXPECT_EQ(Scene::pixel(vram, kFb, 30, 30), 0x0000FFu);  // the second vertex's colour (red)
    EXPECT_EQ(Scene::pixel(vram, kFb, 49, 39), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(vram, kFb, 50, 39), 0x000000u);
}

TEST(SoftRender, RenderToTextureSeesEarlierDraws) {
    // Draw a red square into a second buffer, then texture from it (REPLACE) onto the screen.
    auto build = [](Scene& s) {
        s.b.drawBuffer(GE_FORMAT_8888, kFb2 - Memory::kVramBase, 64);
        s.throughPrim(GE_PRIM_RECTANGLES, {tv(0, 0, 0xFF0000FF), tv(64, 64, 0xFF0000FF)});
        s.b.drawBuffer(GE_FORMAT_8888, 0, kStride);
        s.b.enable(GE_CMD_TME, true);
        s.b.texMode(GE_TFMT_8888, 0, false);
        s.b.setTexture(0, kFb2, 64, 64, 64);
        s.b.texFunc(3, true);
        s.b.texFilter(0, 0);
        constexpr u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        BuildVertex a = tv(100, 100, 0xFFFFFFFF), c = tv(164, 164, 0xFFFFFFFF);
        a.u = 0, a.v = 0, c.u = 64, c.v = 64;
        BuildVertex v[2] = {a, c};
        auto bytes = packVertices(vtype, v, 2);
        s.b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, bytes.data());
    };
    Scene one, four;
    build(one);
    build(four);
    auto a = one.run(1), b = four.run(4);
    EXPECT_EQ(Scene::pixel(a, kFb, 130, 130), 0x0000FFu);
    EXPECT_TRUE(a == b);
}

// Renders a 64×64 texture, red left half and green right half, at kFb2 and binds it with
// REPLACE and bilinear filtering: sampling 1/16 pixel apart at the boundary tells a rectangle's
// centre sampling from a triangle's.
void redGreenTexture(Scene& s) {
    s.b.drawBuffer(GE_FORMAT_8888, kFb2 - Memory::kVramBase, 64);
    s.throughPrim(GE_PRIM_RECTANGLES, {tv(0, 0, 0xFF0000FF), tv(32, 64, 0xFF0000FF)});
    s.throughPrim(GE_PRIM_RECTANGLES, {tv(32, 0, 0xFF00FF00), tv(64, 64, 0xFF00FF00)});
    s.b.drawBuffer(GE_FORMAT_8888, 0, kStride);
    s.b.enable(GE_CMD_TME, true);
    s.b.texMode(GE_TFMT_8888, 0, false);
    s.b.setTexture(0, kFb2, 64, 64, 64);
    s.b.texFunc(3, true);
    s.b.texFilter(1, 1);
}

TEST(SoftRender, StripQuadDrawnAsRectangle) {
    // The reference renderer (PPSSPP's) draws a 4-vertex strip that forms an axis-aligned
    // rectangle with matching UVs and one colour as a RECTANGLES primitive, sampled at pixel
    // centres; its triangles sample 1/16 pixel earlier (the ppsspp profile, geometry/raster.h
    // triangleSampleOffset; the psp profile samples triangles at the centre too). Bilinear 1:1
    // mapping of a texture whose left half is red and right half green shows which path ran: at
    // the column where green starts a rectangle gives pure green, triangles blend 1/16 of red in.
    auto build = [](Scene& s, u32 cornerColor) {
        redGreenTexture(s);
        constexpr u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        auto corner = [&](float x, float y, u32 c) {
            BuildVertex v = tv(100 + x, 100 + y, c);
            v.u = x, v.v = y;
            return v;
        };
        // TL, BL, TR, BR: the strip order the detection accepts.
        BuildVertex v[4] = {corner(0, 0, 0xFFFFFFFF), corner(0, 64, 0xFFFFFFFF), corner(64, 0, 0xFFFFFFFF),
                            corner(64, 64, cornerColor)};
        auto bytes = packVertices(vtype, v, 4);
        s.b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 4, nullptr, bytes.data());
    };
    Scene rect, tris;
    build(rect, 0xFFFFFFFF);
    build(tris, 0xFEFFFFFF);  // a different vertex colour: no longer one rectangle
    const geo::AccuracyProfile ppsspp = geo::AccuracyProfile::ppsspp();
    auto a = rect.run(1, ppsspp), b = tris.run(1, ppsspp);
    EXPECT_EQ(Scene::pixel(a, kFb, 131, 130), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(a, kFb, 132, 130), 0x00FF00u);
    const u32 blended = Scene::pixel(b, kFb, 132, 130);
    EXPECT_NE(blended, 0x00FF00u);
    EXPECT_GT((blended >> 8) & 0xFF, 200u);  // mostly green
    EXPECT_GT(blended & 0xFF, 0u);           // with a little red
}

TEST(SoftRender, ProjectionStripWithQOneDrawnAsRectangle) {
    // Projection mapping (TMAP mode 1) whose texture matrix gives Q = 1 everywhere: the reference
    // renderer (PPSSPP's, Rasterizer.cpp ComputeRasterizerState) then treats the texture as not
    // projected, so a transform-mode strip quad stays a rectangle sampled at pixel centres (NFS
    // Carbon's HUD). With Q = 2 (S and T doubled to match) it becomes two triangles sampled 1/16
    // pixel earlier (the ppsspp profile's sample point). Bilinear 1:1 mapping of a red|green
    // texture tells the two apart.
    auto build = [](Scene& s, float q) {
        redGreenTexture(s);
        const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        s.b.setMatrix(GeMatrix::World, id);
        s.b.setMatrix(GeMatrix::View, id);
        s.b.setMatrix(GeMatrix::Proj, id);
        // Viewport scale 1: drawing x = X + 2048 − 1808, y = Y + 2048 − 1912.
        s.b.cmdf(GE_CMD_SX, 1), s.b.cmdf(GE_CMD_SY, 1);
        // TGEN from (U, V, 0): S = q·U, T = q·V, Q = q.
        const float tgen[12] = {q, 0, 0, 0, q, 0, 0, 0, 0, 0, 0, q};
        s.b.setMatrix3x4(GeMatrix::TexGen, tgen);
        s.b.texMapMode(1, 1);
        constexpr u32 vtype = vt::TC_F | vt::COL_8888 | vt::POS_F;
        auto corner = [&](float x, float y) {
            BuildVertex v;
            v.x = x - 140, v.y = y - 36, v.z = 0;
            v.u = x / 64, v.v = y / 64;
            v.color = 0xFFFFFFFF;
            return v;
        };
        BuildVertex v[4] = {corner(0, 0), corner(0, 64), corner(64, 0), corner(64, 64)};  // TL, BL, TR, BR
        auto bytes = packVertices(vtype, v, 4);
        s.b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 4, nullptr, bytes.data());
    };
    Scene rect, tris;
    build(rect, 1);
    build(tris, 2);
    const geo::AccuracyProfile ppsspp = geo::AccuracyProfile::ppsspp();
    auto a = rect.run(1, ppsspp), b = tris.run(1, ppsspp);
    EXPECT_EQ(Scene::pixel(a, kFb, 100, 100), 0x0000FFu);  // the quad starts at (100, 100)
    EXPECT_EQ(Scene::pixel(a, kFb, 131, 130), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(a, kFb, 132, 130), 0x00FF00u);
    const u32 blended = Scene::pixel(b, kFb, 132, 130);
    EXPECT_NE(blended, 0x00FF00u);
    EXPECT_GT((blended >> 8) & 0xFF, 200u);  // mostly green
    EXPECT_GT(blended & 0xFF, 0u);           // with a little red
}

TEST(SoftRender, FanQuadDrawnAsRectangle) {
    // Same idea for a fresh 4-vertex fan TL, TR, BR, BL (the reference's DetectRectangleFromFan):
    // drawn as a rectangle it samples pixel centres, so the first green column is pure green
    // (triangles under the ppsspp profile sample 1/16 pixel earlier).
    auto build = [](Scene& s, u32 cornerColor) {
        redGreenTexture(s);
        constexpr u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        auto corner = [&](float x, float y, u32 c) {
            BuildVertex v = tv(100 + x, 100 + y, c);
            v.u = x, v.v = y;
            return v;
        };
        BuildVertex v[4] = {corner(0, 0, 0xFFFFFFFF), corner(64, 0, 0xFFFFFFFF), corner(64, 64, 0xFFFFFFFF),
                            corner(0, 64, cornerColor)};
        auto bytes = packVertices(vtype, v, 4);
        s.b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, bytes.data());
    };
    Scene rect, tris;
    build(rect, 0xFFFFFFFF);
    build(tris, 0xFEFFFFFF);  // a different vertex colour: drawn as two triangles
    const geo::AccuracyProfile ppsspp = geo::AccuracyProfile::ppsspp();
    auto a = rect.run(1, ppsspp), b = tris.run(1, ppsspp);
    EXPECT_EQ(Scene::pixel(a, kFb, 131, 130), 0x0000FFu);
    EXPECT_EQ(Scene::pixel(a, kFb, 132, 130), 0x00FF00u);
    EXPECT_NE(Scene::pixel(b, kFb, 132, 130), 0x00FF00u);
}

TEST(SoftRender, OutputIdenticalForAnyThreadCount) {
    // Many overlapping blended, Gouraud-shaded triangles, rectangles and lines, transformed and
    // through mode: the VRAM bytes must not depend on the number of rasterising threads.
    Scene s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> X(-20, 500), Y(-20, 290);
    std::uniform_int_distribution<u32> C(0, 0xFFFFFFFF);
    s.b.enable(GE_CMD_ABE, true);
    s.b.blendFunc(0, 2, 3);
    s.b.enable(GE_CMD_ZTE, true);
    s.b.depthFunc(7);
    s.b.shadeModel(true);
    std::vector<BuildVertex> tris, rects;
    for (int i = 0; i < 150; ++i) tris.push_back(tv(X(rng), Y(rng), C(rng), float(C(rng) & 0xFFFF)));
    for (int i = 0; i < 40; ++i) rects.push_back(tv(X(rng), Y(rng), C(rng), float(C(rng) & 0xFFFF)));
    s.throughPrim(GE_PRIM_TRIANGLES, tris);
    s.throughPrim(GE_PRIM_RECTANGLES, rects);
    s.throughPrim(GE_PRIM_LINE_STRIP, rects);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    s.b.setMatrix(GeMatrix::World, id);
    s.b.setMatrix(GeMatrix::View, id);
    s.b.setMatrix(GeMatrix::Proj, id);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
    std::uniform_real_distribution<float> P(-1.2f, 1.2f);
    std::vector<BuildVertex> fan;
    for (int i = 0; i < 60; ++i) {
        BuildVertex v;
        v.x = P(rng), v.y = P(rng), v.z = P(rng) * 0.8f;
        v.color = C(rng);
        fan.push_back(v);
    }
    auto bytes = packVertices(vtype, fan.data(), u32(fan.size()));
    s.b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, u32(fan.size()), nullptr, bytes.data());
    auto one = s.run(1);
    auto two = s.run(2);
    auto four = s.run(4);
    EXPECT_TRUE(one == two);
    EXPECT_TRUE(one == four);
    int drawn = 0;
    for (int y = 0; y < 272; ++y)
        for (int x = 0; x < 480; ++x) drawn += Scene::pixel(one, kFb, x, y) != 0x000000u;
    EXPECT_GT(drawn, 20000);
}

TEST(SoftRender, BadVertexAddressIsHarmless) {
    Scene s;
    s.b.setVertexType(Scene::kThrough);
    s.b.drawArray(GE_PRIM_TRIANGLES, Scene::kThrough, 30, 0, 0x0FFFFFF0);  // wild address
    SoftOptions o;
    o.threads = 2;
    auto r = createSoftRenderer(s.mem, o);
    s.b.finish();
    const u32 list = s.b.placeList();
    GeEngine eng(s.mem, r.get());
    eng.startList(list, 0);
    eng.run();
    r->flushToMemory();
    EXPECT_GE(static_cast<SoftRenderer*>(r.get())->stats().badDraws, 1u);
}

// Host writes while draws are queued (the dump player and the plugin API call syncMemoryForRead
// before and memoryWritten after writing): a write into the frame buffer of a queued draw must
// land after that draw; a RAM write (vertex data the draw already copied) must not change it.
TEST(SoftRender, HostWritesStayInOrderWithQueuedDraws) {
    Scene s;
    s.throughPrim(GE_PRIM_RECTANGLES, {tv(0, 0, 0xFFFFFFFF), tv(100, 50, 0xFFFFFFFF)});
    ListBuilder copy = s.b;
    copy.finish();
    const u32 list = copy.placeList();
    const u32 stall = list + u32(copy.words().size()) * 4 - 8;  // stop before FINISH + END
    const u8* arenaPtr = s.mem.ptr(0x08800000, 0x10000);
    ASSERT_NE(arenaPtr, nullptr);
    const std::vector<u8> arena(arenaPtr, arenaPtr + 0x10000);  // the list and its vertices
    for (int threads : {1, 2, 4}) {
        SCOPED_TRACE(threads);
        s.mem.write(0x08800000, arena.data(), u32(arena.size()));
        SoftOptions o;
        o.threads = threads;
        auto r = createSoftRenderer(s.mem, o);
        s.mem.fill(Memory::kVramBase, 0, Memory::kVramSize);
        GeEngine eng(s.mem, r.get());
        eng.startList(list, stall);
        ASSERT_EQ(eng.run(), RunStatus::Stalled);
        // Overwrite RAM from the list's arena onwards (vertex data included): no effect on the
        // queued rectangle.
        const u32 ram = 0x08800000;
        std::vector<u8> junk(0x10000, 0xEE);
        r->syncMemoryForRead(ram, u32(junk.size()));
        s.mem.write(ram, junk.data(), u32(junk.size()));
        r->memoryWritten(ram, u32(junk.size()));
        // Write a pixel inside the rectangle: it must survive the queued draw.
        const u32 px = kFb + (10 * kStride + 10) * 4;
        const u8 blue[4] = {0, 0, 0xFF, 0};
        r->syncMemoryForRead(px, 4);
        s.mem.write(px, blue, 4);
        r->memoryWritten(px, 4);
        r->flushToMemory();
        const u8* v = s.mem.ptr(Memory::kVramBase, Memory::kVramSize);
        const std::vector<u8> vram(v, v + Memory::kVramSize);
        EXPECT_EQ(Scene::pixel(vram, kFb, 10, 10), 0xFF0000u);
        EXPECT_EQ(Scene::pixel(vram, kFb, 11, 10), 0xFFFFFFu);
        EXPECT_EQ(Scene::pixel(vram, kFb, 99, 49), 0xFFFFFFu);
        EXPECT_EQ(Scene::pixel(vram, kFb, 100, 49), 0x000000u);
    }
}

// Two render targets whose bytes alias at different rows (a second buffer starting inside the
// first, with another stride) in one frame: band threads own rows, so such draws must not share
// a batch; the result is the same for any thread count.
TEST(SoftRender, AliasingRenderTargetsStayInOrder) {
    Scene s;
    for (int k = 0; k < 6; ++k) {
        s.b.drawBuffer(GE_FORMAT_8888, 0, kStride);
        s.throughPrim(GE_PRIM_RECTANGLES, {tv(0, 0, 0xFF000000u | u32(k * 40)), tv(480, 272, 0xFF000000u | u32(k * 40))});
        // Starts 37 rows (plus 5 pixels) into the first buffer, 256 pixels per row.
        s.b.drawBuffer(GE_FORMAT_8888, (37 * kStride + 5) * 4, 256);
        s.throughPrim(GE_PRIM_RECTANGLES, {tv(0, 0, 0xFF00FF00u | u32(k)), tv(256, 200, 0xFF00FF00u | u32(k))});
    }
    const std::vector<u8> one = s.run(1);
    for (int threads : {2, 4}) {
        for (int repeat = 0; repeat < 4; ++repeat) EXPECT_TRUE(s.run(threads) == one) << threads;
    }
}
