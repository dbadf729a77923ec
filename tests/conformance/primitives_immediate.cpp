// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/primitives/immediate, re-created (gu_sim.h, conformance.h,
// screenshot.h). Primitives sent as immediate vertices: per vertex X2, Y2 (0xFF0000 | (2048 + x) << 4),
// Z2, [S2, T2, Q2,] RGB2, F2 (fog 0x7F, or 0xFF for the textured ones), I2 (secondary colour
// 0x7F7F7F), then AP2 (flags | prim << 8 | alpha), where a first vertex's flags bits choose shading
// (0x40000), culling (0x80000, 0x100000 the cull direction), texturing (0x200000), fog (0x400000) and
// dithering (0x800000). Viewport 1x1 at 0, OFFSETX/Y 2048 << 4, VTYPE transform mode (its vertex
// formats unused), blending SRC_ALPHA / ONE_MINUS_SRC_ALPHA, depth test ALWAYS. The screenshot is
// the check.
//
// What the PSP shows, left to right on rows 10..50: POINTS, LINES, LINE_STRIP, TRIANGLES,
// TRIANGLE_STRIP each as one vertex then GU_CONTINUE (as primitives/continue draws them); a Gouraud
// fan (0x40000) from (0, 255, 255) to (0, 127, 255), one green value per row; a sprite with fog and
// dithering (0xD40000): magenta half-fogged to grey 0x77, dithered by the SDK's 4x4 matrix; a fan
// with the 4x4 greyscale texture (0x200000), clamped, in 10-pixel texels; the same in clear mode:
// white. Rows 60..100: a clockwise fan culled by 0x80000 and a counter-clockwise one culled by
// 0x180000 (nothing drawn), a flat fan with separate specular in transform mode (the last colour
// (0, 127, 255) + (127, 127, 127)) and in through mode (no secondary colour added).
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr u32 kContinue = 7;
constexpr u32 kShade = 0x40000, kCull = 0x80000, kCullMode = 0x100000, kTexture = 0x200000;
constexpr u32 kImage = 0x08400000;

struct ImmVertex {
    u32 color;  // ABGR; alpha goes into AP2
    int x, y;
    u16 z = 0;
    int u = -1, v = -1;  // Vertex_UV16_P16's u, v (texels of 4); -1: a Vertex_C8888_P16
};

void sendImmediate(ListBuilder& b, u32 prim, u32 flags, const std::vector<ImmVertex>& vs) {
    for (const ImmVertex& v : vs) {
        b.cmd(GE_CMD_X2, 0xFF0000 | u32((2048 + v.x) << 4));
        b.cmd(GE_CMD_Y2, 0xFF0000 | u32((2048 + v.y) << 4));
        b.cmd(GE_CMD_Z2, 0xFF0000 | v.z);
        const bool uv = v.u >= 0;
        if (uv) {
            b.cmdf(GE_CMD_S2, float(v.u) / 4.0f);
            b.cmdf(GE_CMD_T2, float(v.v) / 4.0f);
            b.cmdf(GE_CMD_Q2, 1.0f);
        }
        b.cmd(GE_CMD_RGB2, uv ? 0xFFFFFF : v.color & 0xFFFFFF);
        b.cmd(GE_CMD_F2, uv ? 0xFFFFFF : 0xFFFF7F);
        b.cmd(GE_CMD_I2, 0x7F7F7F);
        b.cmd(GE_CMD_AP2, flags | (prim << 8) | (uv ? 0xFF : v.color >> 24));
    }
}

// One vertex with `prim` and `flags`, then GU_CONTINUE with the rest.
void sendContinued(ListBuilder& b, u32 prim, u32 flags, const std::vector<ImmVertex>& vs) {
    sendImmediate(b, prim, flags, {vs[0]});
    sendImmediate(b, kContinue, 0, std::vector<ImmVertex>(vs.begin() + 1, vs.end()));
}

std::vector<ImmVertex> box(int x, int y, u32 top, u32 bottom, u16 z = 0) {
    return {{top, x, y, z}, {top, x + 40, y, z}, {bottom, x + 40, y + 40, z}, {bottom, x, y + 40, z}};
}
std::vector<ImmVertex> texturedBox(int x, int y) {
    return {{0, x, y, 0, 0, 0}, {0, x + 40, y, 0, 4, 0}, {0, x + 40, y + 40, 0, 4, 4}, {0, x, y + 40, 0, 0, 4}};
}

// The PSP's screenshot (black elsewhere).
const std::vector<ScreenSpan> kScreen = {
    {10, 11, 10, 11, 0, 0, 0xFF0000},   {10, 11, 50, 51, 0, 0, 0xFF0000},   {10, 11, 60, 100, 0, 0, 0x00FF00},
    {10, 11, 110, 151, 0, 0, 0x0000FF}, {10, 50, 160, 200, 1, 0, 0xFFFF00}, {10, 30, 210, 250, 1, 0, 0xFF00FF},
    {10, 20, 370, 380, 0, 0, 0x111111}, {10, 20, 380, 390, 0, 0, 0x222222}, {10, 20, 390, 400, 0, 0, 0x333333},
    {10, 50, 410, 450, 0, 0, 0xFFFFFF}, {11, 50, 150, 151, 0, 0, 0x0000FF}, {20, 30, 360, 370, 0, 0, 0x444444},
    {20, 30, 370, 380, 0, 0, 0x555555}, {20, 30, 380, 390, 0, 0, 0x666666}, {20, 30, 390, 400, 0, 0, 0x777777},
    {30, 50, 229, 250, -1, 0, 0xFF00FF}, {30, 40, 360, 370, 0, 0, 0x888888}, {30, 40, 370, 380, 0, 0, 0x999999},
    {30, 40, 380, 390, 0, 0, 0xAAAAAA}, {30, 40, 390, 400, 0, 0, 0xBBBBBB}, {40, 50, 360, 370, 0, 0, 0xCCCCCC},
    {40, 50, 370, 380, 0, 0, 0xDDDDDD}, {40, 50, 380, 390, 0, 0, 0xEEEEEE}, {40, 50, 390, 400, 0, 0, 0xFFFFFF},
    {50, 51, 10, 11, 0, 0, 0xFF0000},   {50, 51, 50, 51, 0, 0, 0xFF0000},   {50, 51, 60, 100, 0, 0, 0x00FF00},
    {50, 51, 110, 150, 0, 0, 0x0000FF}, {60, 100, 110, 150, 0, 0, 0x7FFEFF}, {60, 100, 160, 200, 0, 0, 0x007FFF},
};
// The Gouraud fan's green on rows 10..49 (x 260..299; red 0, blue 255).
constexpr u8 kFanGreen[40] = {0xfd, 0xfa, 0xf6, 0xf3, 0xf0, 0xed, 0xea, 0xe6, 0xe3, 0xe0, 0xdd, 0xda, 0xd6, 0xd3,
                              0xd0, 0xcd, 0xca, 0xc6, 0xc3, 0xc0, 0xbd, 0xba, 0xb6, 0xb3, 0xb0, 0xad, 0xaa, 0xa6,
                              0xa3, 0xa0, 0x9d, 0x9a, 0x96, 0x93, 0x90, 0x8d, 0x8a, 0x86, 0x83, 0x80};
// The dithered sprite (x 310..349, rows 10..49): grey-magenta (r = b, g = r - 0x7F), one value of r
// per pixel repeating every 4 pixels and 4 rows from (310, 10).
constexpr u8 kSpriteRed[4][4] = {{0xb7, 0xbb, 0xb8, 0xbc}, {0xbd, 0xb9, 0xbe, 0xba}, {0xb8, 0xbc, 0xb7, 0xbb}, {0xbe, 0xba, 0xbd, 0xb9}};

std::vector<u32> immediateRow(int y) {
    std::vector<u32> row = screenRow(0, kScreen, y);
    if (y >= 10 && y < 50) {
        for (int x = 260; x < 300; ++x) row[size_t(x)] = u32(kFanGreen[y - 10]) << 8 | 0xFF;
        for (int x = 310; x < 350; ++x) {
            const u32 r = kSpriteRed[(y - 10) & 3][(x - 310) & 3];
            row[size_t(x)] = r << 16 | (r - 0x7F) << 8 | r;
        }
    }
    return row;
}

TestRun runImmediate(GuSim& gu) {
    TestRun run{"primitives/immediate", gu.backend(), {}};
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    u32 image[16];
    for (u32 i = 0; i < 16; ++i) image[i] = 0xFF000000 | (0x111111 * i);
    gu.cpuWrite(kImage, image, sizeof image);

    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);  // startFrame()
    b.enable(GE_CMD_TME, false);
    b.enable(GE_CMD_ABE, true);
    b.enable(GE_CMD_ZTE, true);
    b.blendFunc(0 /*ADD*/, 2 /*SRC_ALPHA*/, 3 /*ONE_MINUS_SRC_ALPHA*/, 0, 0);
    b.depthFunc(1 /*ALWAYS*/);
    b.depthMask(false);
    b.depthRange(65535, 0);  // sceGuDepthOffset(0) re-sends the range it has
    b.depthRange(0, 65535);
    b.lightMode(false);
    b.fog(0.0f, 1.0f, 0x777777);
    b.viewport(0, 0, 1, 1);
    b.offset(0, 0);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b.setVertexType(vt::COL_5650 | vt::POS_F);
    b.cmd(GE_CMD_OFFSETX, 2048 << 4);
    b.cmd(GE_CMD_OFFSETY, 2048 << 4);

    sendContinued(b, GE_PRIM_POINTS, 0, box(10, 10, 0xFF0000FF, 0xFF0000FF, 0x1234));
    sendContinued(b, GE_PRIM_LINES, 0, box(60, 10, 0xFF00FF00, 0xFF00FF00));
    sendContinued(b, GE_PRIM_LINE_STRIP, 0, box(110, 10, 0xFFFF0000, 0xFFFF0000));
    sendContinued(b, GE_PRIM_TRIANGLES, 0, box(160, 10, 0xFF00FFFF, 0xFF00FFFF));
    sendContinued(b, GE_PRIM_TRIANGLE_STRIP, 0, box(210, 10, 0xFFFF00FF, 0xFFFF00FF));
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, kShade, box(260, 10, 0xFFFFFF00, 0xFFFF7F00));
    sendContinued(b, GE_PRIM_RECTANGLES, 0xD40000, {{0xFFFFFFFF, 310, 10}, {0xFFFF00FF, 350, 50}});

    b.enable(GE_CMD_TME, true);
    b.texFilter(0, 0);
    b.texFunc(0 /*REPLACE*/, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, kImage, 4, 4, 4);
    b.texWrap(true, true);
    b.texFlush();
    b.texSync();
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, kTexture, texturedBox(360, 10));
    b.cmd(GE_CMD_CMODE, 1 | ((CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH) << 8));
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, kTexture, texturedBox(410, 10));
    b.cmd(GE_CMD_CMODE, 0);

    // vertices10 (clockwise) and vertices11 (counter-clockwise).
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, kCull, box(10, 60, 0xFFFFFF00, 0xFFFF7F00));
    const u32 c = 0xFFFFFF00;
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, kCull | kCullMode, {{c, 60, 60}, {c, 60, 100}, {c, 100, 100}, {c, 100, 60}});
    b.lightMode(true);
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, 0, box(110, 60, 0xFFFFFF00, 0xFFFF7F00));
    b.lightMode(false);
    b.lightMode(true);
    b.setVertexType(vt::COL_5650 | vt::POS_F | vt::THROUGH);
    sendContinued(b, GE_PRIM_TRIANGLE_FAN, 0, box(160, 60, 0xFFFFFF00, 0xFFFF7F00));
    b.lightMode(false);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, immediateRow);
    return run;
}

CONFORMANCE_TEST(PrimitivesImmediate, runImmediate)

}  // namespace
}  // namespace ge::conformance
