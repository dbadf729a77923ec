// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/primitives/{triangles, trianglestrip, trianglefan, points, invalidprim,
// lines, linestrip, rectangles}, re-created (gu_sim.h, conformance.h, screenshot.h). Each
// draws one 40x40 shape (or a pair of points / a short line) per vertex format and mode on a frame
// cleared to black: colour only (no position), 8-bit, 16-bit and float positions, in through mode
// (upper row: pixels) and transform mode (lower row, 50 pixels down for the shapes, 10 for points
// and lines: the pixel through norm8x/y, norm16x/y or norm32x/y of primitives/shared.h, identity
// matrices, the 480x272 viewport); then the
// same shape with its vertices in the other winding or corner order, and a draw of one vertex
// ("incomplete"). The screenshot is the check. What the PSP shows: nothing of the colour-only
// arrays (no position); of the through-mode 8-bit ones only a green pixel at (0, 0) (points), so
// their positions do not land where given; a triangle leaves out its top row and the pixels on
// its right (diagonal) edge; reversed order and both diagonals of a sprite draw the same; an
// incomplete primitive draws nothing; a line leaves out its last pixel; PRIM 8
// (primitives/invalidprim) draws points.
#include <algorithm>

#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

// Position formats of the test's vertex structs (primitives/shared.h): none (Vertex_C8888,
// Vertex_UV16), Vertex_*_P8 (s8 x, y, z, pad), Vertex_*_P16 (s16 x, y, z[, pad]), Vertex_*_P32.
enum class Pos { None, S8, S16, F32 };

struct TestVertex {
    int x, y;         // the pixel, as the test program writes it (through) or normalises it (transform)
    u32 color = 0;    // vertex colour (Vertex_C8888_*), when the format has one
    u16 u = 0, v = 0; // texture coordinate (Vertex_UV16_*), when the format has one
};

u32 posBits(Pos p) { return p == Pos::S8 ? vt::POS_8 : p == Pos::S16 ? vt::POS_16 : p == Pos::F32 ? vt::POS_F : 0u; }

// The test's static vertex array for `vtype` (colour 8888 or UV16, then the position), laid out as
// its C struct is (and as the GE reads it: each field aligned to its size, the vertex to the
// largest), with norm8x/y, norm16x/y and norm32x/y of shared.h applied in transform mode.
std::vector<u8> packVertices(bool uv, Pos pos, bool through, const std::vector<TestVertex>& vs) {
    const u32 head = 4;  // u32 colour or u16 u, v
    const u32 posSize = pos == Pos::S8 ? 3 : pos == Pos::S16 ? 6 : pos == Pos::F32 ? 12 : 0;
    const u32 align = pos == Pos::F32 ? 4 : (pos == Pos::S16 || uv) ? 2 : 1;
    u32 size = head + posSize;
    if (!uv) size = (size + 3) & ~3u;  // the colour aligns the vertex to 4
    size = (size + align - 1) & ~(align - 1);
    std::vector<u8> out(vs.size() * size, 0);
    for (size_t i = 0; i < vs.size(); ++i) {
        u8* p = &out[i * size];
        const TestVertex& t = vs[i];
        if (uv) {
            writeLE16(p, t.u), writeLE16(p + 2, t.v);
        } else {
            writeLE32(p, t.color);
        }
        u8* q = p + head;
        switch (pos) {
        case Pos::None: break;
        case Pos::S8:
            q[0] = u8(through ? t.x : t.x * 255 / 480 - 128);  // norm8x
            q[1] = u8(through ? t.y : 128 - t.y * 255 / 272);  // norm8y
            break;
        case Pos::S16:
            writeLE16(q, u16(through ? t.x : t.x * 65536 / 480 - 32768));       // norm16x
            writeLE16(q + 2, u16(through ? t.y : 32768 - t.y * 65536 / 272));   // norm16y
            break;
        case Pos::F32: {
            const float x = through ? float(t.x) : 2.0f * float(t.x) / 480 - 1.0f;  // norm32x
            const float y = through ? float(t.y) : 1.0f - 2.0f * float(t.y) / 272;  // norm32y
            writeLE32(q, floatBits(x));
            writeLE32(q + 4, floatBits(y));
            writeLE32(q + 8, floatBits(0.0f));
            break;
        }
        }
    }
    return out;
}

// sceGuDrawArray(prim, vtype, count, NULL, vertices) with the array placed in memory; `prim` goes
// into the PRIM word unmasked, (prim << 16) | count, as the SDK sends it.
void drawTest(ListBuilder& b, u32 prim, bool uv, Pos pos, bool through, const std::vector<TestVertex>& vs, u32 count) {
    const std::vector<u8> data = packVertices(uv, pos, through, vs);
    const u32 vtype = (uv ? vt::TC_16 : vt::COL_8888) | posBits(pos) | (through ? vt::THROUGH : 0u);
    const u32 addr = b.place(data.data(), u32(data.size()), 16);
    b.setVertexType(vtype);
    b.cmd(GE_CMD_BASE, (addr >> 8) & 0x0F0000);
    b.cmd(GE_CMD_VADR, addr & 0xFFFFFF);
    b.cmd(GE_CMD_PRIM, (prim << 16) | count);
}

// initDisplay() and startFrame() of primitives/shared.cpp: the commands/ set-up, then a list that
// clears the colour to black.
ListBuilder& startPrimitives(GuSim& gu) {
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);
    return b;
}

// ---- triangles, trianglestrip, trianglefan ----

// Vertex orders (pixel offsets from the shape's top-left corner; 40x40) of the three tests.
struct TriangleTest {
    const char* name;
    u32 prim;
    std::vector<std::pair<int, int>> order, reversed;
};

const TriangleTest kTriangles = {"primitives/triangles", GE_PRIM_TRIANGLES, {{0, 40}, {0, 0}, {40, 40}},
                                 {{0, 0}, {0, 40}, {40, 40}}};
const TriangleTest kStrip = {"primitives/trianglestrip", GE_PRIM_TRIANGLE_STRIP,
                             {{0, 40}, {0, 0}, {40, 40}, {40, 0}}, {{0, 0}, {0, 40}, {40, 0}, {40, 40}}};
const TriangleTest kFan = {"primitives/trianglefan", GE_PRIM_TRIANGLE_FAN,
                           {{0, 0}, {40, 0}, {40, 40}, {0, 40}}, {{0, 0}, {0, 40}, {40, 40}, {40, 0}}};

// The PSP's screenshots (black elsewhere). Triangles: the lower-left half of each box, from one
// pixel on its second row to 39 on its last; strip and fan: the whole box. The through-mode 8-bit
// shape (x 10..50) is missing; the transform-mode 8-bit one lands one pixel up and left.
const std::vector<ScreenSpan> kTrianglesScreen = {
    {11, 50, 60, 61, 0, 1, 0x0000FF},  {11, 50, 110, 111, 0, 1, 0xFFFF00}, {11, 50, 160, 161, 0, 1, 0xFF00FF},
    {60, 99, 9, 10, 0, 1, 0x00FF00},   {61, 100, 60, 61, 0, 1, 0x0000FF},  {61, 100, 110, 111, 0, 1, 0xFFFF00},
    {61, 100, 160, 161, 0, 1, 0xFF00FF},
};
const std::vector<ScreenSpan> kBoxesScreen = {
    {10, 50, 60, 100, 0, 0, 0x0000FF}, {10, 50, 110, 150, 0, 0, 0xFFFF00}, {10, 50, 160, 200, 0, 0, 0xFF00FF},
    {59, 99, 9, 49, 0, 0, 0x00FF00},   {60, 100, 60, 100, 0, 0, 0x0000FF}, {60, 100, 110, 150, 0, 0, 0xFFFF00},
    {60, 100, 160, 200, 0, 0, 0xFF00FF},
};

TestRun runTriangleTest(GuSim& gu, const TriangleTest& t, const std::vector<ScreenSpan>& screen) {
    TestRun run{t.name, gu.backend(), {}};
    ListBuilder& b = startPrimitives(gu);
    b.enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE)
    auto shape = [&](int x, int y, u32 c, const std::vector<std::pair<int, int>>& order) {
        std::vector<TestVertex> vs;
        for (const auto& [dx, dy] : order) vs.push_back({x + dx, y + dy, c});
        return vs;
    };
    const u32 n = u32(t.order.size());
    for (int mode = 0; mode < 2; ++mode) {  // through (y 10), transform (y 60)
        const bool through = mode == 0;
        const int y = through ? 10 : 60;
        drawTest(b, t.prim, false, Pos::None, through, shape(0, 0, 0xFF0000FF, t.order), n);
        drawTest(b, t.prim, false, Pos::S8, through, shape(10, y, 0xFF00FF00, t.order), n);
        drawTest(b, t.prim, false, Pos::S16, through, shape(60, y, 0xFFFF0000, t.order), n);
        drawTest(b, t.prim, false, Pos::F32, through, shape(110, y, 0xFF00FFFF, t.order), n);
    }
    drawTest(b, t.prim, false, Pos::F32, true, shape(160, 10, 0xFFFF00FF, t.reversed), n);
    drawTest(b, t.prim, false, Pos::F32, false, shape(160, 60, 0xFFFF00FF, t.reversed), n);
    drawTest(b, t.prim, false, Pos::F32, true, {{210, 10, 0xFFFFFFFF}}, 1);
    drawTest(b, t.prim, false, Pos::F32, false, {{210, 60, 0xFFFFFFFF}}, 1);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, screen);
    return run;
}

TestRun runTriangles(GuSim& gu) { return runTriangleTest(gu, kTriangles, kTrianglesScreen); }
TestRun runTriangleStrip(GuSim& gu) { return runTriangleTest(gu, kStrip, kBoxesScreen); }
TestRun runTriangleFan(GuSim& gu) { return runTriangleTest(gu, kFan, kBoxesScreen); }

CONFORMANCE_TEST(PrimitivesTriangles, runTriangles)
CONFORMANCE_TEST(PrimitivesTriangleStrip, runTriangleStrip)
CONFORMANCE_TEST(PrimitivesTriangleFan, runTriangleFan)

// ---- points, invalidprim, lines, linestrip ----

// One short shape per format (`offsets` from its first vertex: a pair two pixels apart, or for
// linestrip two pixels right then two down), through mode from row 10, transform mode from row 20,
// x from 10 in steps of 4; lines and linestrip also draw the shape in reverse vertex order at x 22
// and a one-vertex draw at x 26.
TestRun runPairs(GuSim& gu, const char* name, u32 prim, const std::vector<std::pair<int, int>>& offsets,
                 bool reversedAndIncomplete, const std::vector<ScreenSpan>& screen) {
    TestRun run{name, gu.backend(), {}};
    ListBuilder& b = startPrimitives(gu);
    b.enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE)
    auto shape = [&](int x, int y, u32 c) {
        std::vector<TestVertex> vs;
        for (const auto& [dx, dy] : offsets) vs.push_back({x + dx, y + dy, c});
        return vs;
    };
    const u32 n = u32(offsets.size());
    for (int mode = 0; mode < 2; ++mode) {
        const bool through = mode == 0;
        const int y = through ? 10 : 20;
        drawTest(b, prim, false, Pos::None, through, shape(0, 0, 0xFF0000FF), n);
        drawTest(b, prim, false, Pos::S8, through, shape(10, y, 0xFF00FF00), n);
        drawTest(b, prim, false, Pos::S16, through, shape(14, y, 0xFFFF0000), n);
        drawTest(b, prim, false, Pos::F32, through, shape(18, y, 0xFF00FFFF), n);
    }
    if (reversedAndIncomplete) {
        for (int y : {10, 20}) {
            std::vector<TestVertex> rev = shape(22, y, 0xFFFF00FF);
            std::reverse(rev.begin(), rev.end());
            drawTest(b, prim, false, Pos::F32, y == 10, rev, n);
        }
        drawTest(b, prim, false, Pos::F32, true, {{26, 10, 0xFFFFFFFF}}, 1);
        drawTest(b, prim, false, Pos::F32, false, {{26, 20, 0xFFFFFFFF}}, 1);
    }
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, screen);
    return run;
}

const std::vector<std::pair<int, int>> kPair = {{0, 0}, {2, 0}}, kCorner = {{0, 0}, {2, 0}, {2, 2}};

// Points: each vertex one pixel; the through-mode 8-bit pair at (0, 0), the transform-mode one a
// pixel up and left of (10, 20) and (12, 20). PRIM 8 draws the same.
const std::vector<ScreenSpan> kPointsScreen = {
    {0, 1, 0, 1, 0, 0, 0x00FF00},     {10, 11, 14, 15, 0, 0, 0x0000FF}, {10, 11, 16, 17, 0, 0, 0x0000FF},
    {10, 11, 18, 19, 0, 0, 0xFFFF00}, {10, 11, 20, 21, 0, 0, 0xFFFF00}, {19, 20, 9, 10, 0, 0, 0x00FF00},
    {19, 20, 11, 12, 0, 0, 0x00FF00}, {20, 21, 14, 15, 0, 0, 0x0000FF}, {20, 21, 16, 17, 0, 0, 0x0000FF},
    {20, 21, 18, 19, 0, 0, 0xFFFF00}, {20, 21, 20, 21, 0, 0, 0xFFFF00},
};
// Lines: two pixels from the first vertex, the last left out; the reversed pair the same two
// pixels; the through-mode 8-bit line is not seen.
const std::vector<ScreenSpan> kLinesScreen = {
    {10, 11, 14, 16, 0, 0, 0x0000FF}, {10, 11, 18, 20, 0, 0, 0xFFFF00}, {10, 11, 22, 24, 0, 0, 0xFF00FF},
    {19, 20, 9, 11, 0, 0, 0x00FF00},  {20, 21, 14, 16, 0, 0, 0x0000FF}, {20, 21, 18, 20, 0, 0, 0xFFFF00},
    {20, 21, 22, 24, 0, 0, 0xFF00FF},
};

// Line strip: the same two pixels per segment, the horizontal one then the vertical one (its
// first pixel is the horizontal one's end, left out there and drawn here); the reversed strip, from
// (24, 12) up and left, the same pixels. The transform-mode 8-bit strip again lands one pixel up
// and left; its vertical segment is one pixel (x 11, row 20).
const std::vector<ScreenSpan> kLineStripScreen = {
    {10, 11, 14, 17, 0, 0, 0x0000FF}, {10, 11, 18, 21, 0, 0, 0xFFFF00}, {10, 11, 22, 25, 0, 0, 0xFF00FF},
    {11, 12, 16, 17, 0, 0, 0x0000FF}, {11, 12, 20, 21, 0, 0, 0xFFFF00}, {11, 12, 24, 25, 0, 0, 0xFF00FF},
    {19, 20, 9, 12, 0, 0, 0x00FF00},  {20, 21, 11, 12, 0, 0, 0x00FF00}, {20, 21, 14, 17, 0, 0, 0x0000FF},
    {20, 21, 18, 21, 0, 0, 0xFFFF00}, {20, 21, 22, 25, 0, 0, 0xFF00FF}, {21, 22, 16, 17, 0, 0, 0x0000FF},
    {21, 22, 20, 21, 0, 0, 0xFFFF00}, {21, 22, 24, 25, 0, 0, 0xFF00FF},
};

TestRun runPoints(GuSim& gu) { return runPairs(gu, "primitives/points", GE_PRIM_POINTS, kPair, false, kPointsScreen); }
TestRun runInvalidPrim(GuSim& gu) { return runPairs(gu, "primitives/invalidprim", 8, kPair, false, kPointsScreen); }
TestRun runLines(GuSim& gu) { return runPairs(gu, "primitives/lines", GE_PRIM_LINES, kPair, true, kLinesScreen); }
TestRun runLineStrip(GuSim& gu) {
    return runPairs(gu, "primitives/linestrip", GE_PRIM_LINE_STRIP, kCorner, true, kLineStripScreen);
}

CONFORMANCE_TEST(PrimitivesPoints, runPoints)
CONFORMANCE_TEST(PrimitivesInvalidPrim, runInvalidPrim)
CONFORMANCE_TEST(PrimitivesLines, runLines)
CONFORMANCE_TEST(PrimitivesLineStrip, runLineStrip)

// ---- rectangles ----

// setSimpleTexture() of primitives/shared.cpp: a 2x2 CLUT8 texture {0, 1 / 1, 2} (buffer width
// 16) with the palette {blue, red, magenta} (ABGR 0xFFFF0000, 0xFF0000FF, 0xFFFF00FF), nearest,
// DECAL/RGB, CLUT 8888.
constexpr u32 kImage = 0x08400000, kClut = 0x08400040;

void setSimpleTexture(GuSim& gu, ListBuilder& b) {
    u8 image[32] = {};
    image[0] = 0, image[1] = 1, image[16] = 1, image[17] = 2;
    const u32 clut[8] = {0xFFFF0000, 0xFF0000FF, 0xFFFF00FF, 0, 0, 0, 0, 0};
    gu.cpuWrite(kImage, image, sizeof image);
    gu.cpuWrite(kClut, clut, sizeof clut);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.texFilter(0, 0);
    b.texFunc(1 /*DECAL*/, false);
    b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
    b.setTexture(0, kImage, 2, 2, 16);
    b.clutLoad(kClut, 1);
}

// Each sprite shows the texture's four texels as 20x20 quarters: blue, red / red, magenta; the two
// sprites given right-to-left show it mirrored left to right (red, blue / magenta, red) and the one
// given bottom-right to top-left mirrored both ways (magenta, red / red, blue). The transform-mode
// 8-bit sprite lands one pixel up and left; the through-mode 8-bit one and the incomplete ones are
// not seen.
std::vector<ScreenSpan> rectanglesScreen() {
    std::vector<ScreenSpan> s;
    auto quad = [&](int x, int y, u32 tl, u32 tr, u32 bl, u32 br) {
        s.push_back({y, y + 20, x, x + 20, 0, 0, tl});
        s.push_back({y, y + 20, x + 20, x + 40, 0, 0, tr});
        s.push_back({y + 20, y + 40, x, x + 20, 0, 0, bl});
        s.push_back({y + 20, y + 40, x + 20, x + 40, 0, 0, br});
    };
    constexpr u32 B = 0x0000FF, R = 0xFF0000, M = 0xFF00FF;
    for (int y : {10, 60}) {
        quad(60, y, B, R, R, M);
        quad(110, y, B, R, R, M);
        quad(160, y, R, B, M, R);
        quad(210, y, M, R, R, B);
    }
    quad(9, 59, B, R, R, M);
    return s;
}

TestRun runRectangles(GuSim& gu) {
    TestRun run{"primitives/rectangles", gu.backend(), {}};
    ListBuilder& b = startPrimitives(gu);
    setSimpleTexture(gu, b);
    const u16 far = 2, farX = 32768;  // the second vertex's u, v: 2 texels (through), 1.0 (transform)
    auto sprite = [](int x0, int y0, int x1, int y1, u16 f) {
        std::vector<TestVertex> vs = {{x0, y0}, {x1, y1}};
        vs[1].u = vs[1].v = f;
        return vs;
    };
    for (int mode = 0; mode < 2; ++mode) {
        const bool through = mode == 0;
        const u16 f = through ? far : farX;
        const int y = through ? 10 : 60;
        drawTest(b, GE_PRIM_RECTANGLES, true, Pos::None, through, sprite(0, 0, 0, 0, 2), 2);
        drawTest(b, GE_PRIM_RECTANGLES, true, Pos::S8, through, sprite(10, y, 50, y + 40, f), 2);
        drawTest(b, GE_PRIM_RECTANGLES, true, Pos::S16, through, sprite(60, y, 100, y + 40, f), 2);
        drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, through, sprite(110, y, 150, y + 40, f), 2);
    }
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, true, sprite(200, 10, 160, 50, far), 2);
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, true, sprite(250, 50, 210, 10, far), 2);
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, false, sprite(200, 60, 160, 100, farX), 2);
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, false, sprite(250, 100, 210, 60, farX), 2);
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, true, {{260, 50}}, 1);
    drawTest(b, GE_PRIM_RECTANGLES, true, Pos::F32, false, {{260, 100}}, 1);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, rectanglesScreen());
    return run;
}

CONFORMANCE_TEST(PrimitivesRectangles, runRectangles)

}  // namespace
}  // namespace ge::conformance
