// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/primitives/indices and primitives/continue, re-created (gu_sim.h,
// conformance.h, screenshot.h). The vertex and index arrays are the test program's static arrays,
// placed in memory once; the draws point into them as its sceGuDrawArray calls do (an
// address of NULL sends no BASE/IADR/VADR word, so the GE carries on from where the previous draw
// left its pointers), and PRIM 7 is GU_CONTINUE. The screenshot is the check.
//
// indices: the outline of a 40x40 box (LINES through the indices 0 1 2 3 1 2 0 3) from 8-, 16- and
// 32-bit indices; one index then GU_CONTINUE with seven more; 8-bit index 255 reaching vertex 256
// (indices are unsigned); the vertex pointer not advanced by indexed draws while the index pointer
// is; a line continued across index and vertex formats. Each line covers the pixels from its
// lower to its higher x (or y) and leaves out the higher one, whichever way it runs (the right-to-left
// bottom edge 50 -> 10 draws 10..49), so a box's bottom-right corner stays black.
//
// continue: POINTS, LINES, LINE_STRIP, TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN and SPRITES each
// drawn as one vertex, then GU_CONTINUE with the rest, through mode (rows 10..50) and transform
// mode (rows 60..100); then a fan continued with the vertex pointer left where the first draw ended.
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr u32 kContinue = 7;  // GU_CONTINUE: PRIM 7

struct Pt {
    u32 color;
    int x, y;
};

// Vertex_C8888_P16 (colour, s16 x, y, z, pad: 12 bytes), positions through norm16x/y in transform mode.
std::vector<u8> p16(const std::vector<Pt>& v, bool through = true) {
    std::vector<u8> out(v.size() * 12, 0);
    for (size_t i = 0; i < v.size(); ++i) {
        writeLE32(&out[i * 12], v[i].color);
        writeLE16(&out[i * 12 + 4], u16(through ? v[i].x : v[i].x * 65536 / 480 - 32768));
        writeLE16(&out[i * 12 + 6], u16(through ? v[i].y : 32768 - v[i].y * 65536 / 272));
    }
    return out;
}
// Vertex_C8888_P32 (colour, float x, y, z: 16 bytes), through mode.
std::vector<u8> p32(const std::vector<Pt>& v) {
    std::vector<u8> out(v.size() * 16, 0);
    for (size_t i = 0; i < v.size(); ++i) {
        writeLE32(&out[i * 16], v[i].color);
        writeLE32(&out[i * 16 + 4], floatBits(float(v[i].x)));
        writeLE32(&out[i * 16 + 8], floatBits(float(v[i].y)));
    }
    return out;
}
// A 40x40 box's corners from (x, y) clockwise in screen order: TL, TR, BR, BL.
std::vector<Pt> box(u32 c, int x, int y) { return {{c, x, y}, {c, x + 40, y}, {c, x + 40, y + 40}, {c, x, y + 40}}; }

ListBuilder& startPrimitives(GuSim& gu) {
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);  // startFrame()
    b.enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE)
    return b;
}

// sceGuDrawArray(prim, vtype, count, indices, vertices); 0 for NULL.
void draw(ListBuilder& b, u32 prim, u32 vtype, u32 count, u32 indices, u32 vertices) {
    b.drawArray(prim, vtype, count, indices, vertices);
}

// The PSP's screenshot of indices (black elsewhere): each box's top edge, 41 pixels (x .. x + 40)
// on row 10, its left and right edges on rows 11..49, its bottom edge x .. x + 39 on row 50; the
// unsigned-index line at x 210, rows 10..49; the mixed-format line white (310..349, row 10) and
// grey (310..349, row 50).
const std::vector<ScreenSpan> kIndicesScreen = {
    {10, 11, 10, 51, 0, 0, 0xFF0000},   {10, 11, 60, 101, 0, 0, 0x00FF00},  {10, 11, 110, 151, 0, 0, 0x0000FF},
    {10, 11, 160, 201, 0, 0, 0xFFFF00}, {10, 50, 210, 211, 0, 0, 0xFF00FF}, {10, 11, 260, 301, 0, 0, 0x00FFFF},
    {10, 11, 310, 350, 0, 0, 0xFFFFFF}, {11, 50, 10, 11, 0, 0, 0xFF0000},   {11, 50, 50, 51, 0, 0, 0xFF0000},
    {11, 50, 60, 61, 0, 0, 0x00FF00},   {11, 50, 100, 101, 0, 0, 0x00FF00}, {11, 50, 110, 111, 0, 0, 0x0000FF},
    {11, 50, 150, 151, 0, 0, 0x0000FF}, {11, 50, 160, 161, 0, 0, 0xFFFF00}, {11, 50, 200, 201, 0, 0, 0xFFFF00},
    {11, 50, 260, 261, 0, 0, 0x00FFFF}, {11, 50, 300, 301, 0, 0, 0x00FFFF}, {50, 51, 10, 50, 0, 0, 0xFF0000},
    {50, 51, 60, 100, 0, 0, 0x00FF00},  {50, 51, 110, 150, 0, 0, 0x0000FF}, {50, 51, 160, 200, 0, 0, 0xFFFF00},
    {50, 51, 260, 300, 0, 0, 0x00FFFF}, {50, 51, 310, 350, 0, 0, 0x777777},
};

TestRun runIndices(GuSim& gu) {
    TestRun run{"primitives/indices", gu.backend(), {}};
    ListBuilder& b = startPrimitives(gu);
    StaticData mem(gu, 0x08400000);
    const u32 v1 = mem.put(p16(box(0xFF0000FF, 10, 10))), v2 = mem.put(p16(box(0xFF00FF00, 60, 10)));
    const u32 v3 = mem.put(p16(box(0xFFFF0000, 110, 10))), v4 = mem.put(p16(box(0xFF00FFFF, 160, 10)));
    const std::vector<Pt> b5 = box(0xFFFF00FF, 210, 10);
    const u32 v6 = mem.put(p16(box(0xFFFFFF00, 260, 10)));
    const u32 v7 = mem.put(p16({{0xFFFFFFFF, 310, 10}, {0xFF0000FF, 320, 20}, {0xFF0000FF, 320, 20}, {0xFF0000FF, 320, 20}}));
    const u32 v8 = mem.put(p32({{0xFF0000FF, 320, 20}, {0xFFFFFFFF, 350, 10}, {0xFF777777, 350, 50}, {0xFF777777, 310, 50}}));
    // vertices_big[257]: [0] = vertices5[1], [1] = vertices5[0], [256] = vertices5[3], the rest 0.
    std::vector<u8> big(257 * 12, 0);
    const std::vector<u8> b5bytes = p16(b5);
    std::copy_n(&b5bytes[12], 12, &big[0]);
    std::copy_n(&b5bytes[0], 12, &big[12]);
    std::copy_n(&b5bytes[36], 12, &big[256 * 12]);
    const u32 vBig = mem.put(big);
    static constexpr u32 kOrder[8] = {0, 1, 2, 3, 1, 2, 0, 3};
    std::vector<u8> i8(8), i16(16), i32(32), iBig(8, 0);
    for (int k = 0; k < 8; ++k) {
        i8[size_t(k)] = u8(kOrder[k]);
        writeLE16(&i16[size_t(k) * 2], u16(kOrder[k]));
        writeLE32(&i32[size_t(k) * 4], kOrder[k]);
    }
    iBig[1] = 255;
    const u32 idx8 = mem.put(i8), idx16 = mem.put(i16), idx32 = mem.put(i32), idxBig = mem.put(iBig);

    const u32 base = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 8, idx8, v1);
    draw(b, GE_PRIM_LINES, base | vt::IDX_16, 8, idx16, v2);
    draw(b, GE_PRIM_LINES, base | vt::IDX_32, 8, idx32, v3);  // GU_INDEX_BITS: the 32-bit field value
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 1, idx8, v4);
    draw(b, kContinue, base | vt::IDX_8, 7, idx8 + 1, 0);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 2, idxBig, vBig + 12);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 2, idx8, v6);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 2, idx8 + 2, 0);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 2, 0, 0);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 2, 0, 0);
    draw(b, GE_PRIM_LINES, base | vt::IDX_8, 1, idx8, v7);
    const u32 floatBase = vt::COL_8888 | vt::POS_F | vt::THROUGH;
    draw(b, kContinue, floatBase | vt::IDX_16, 2, idx16 + 2, v8);
    draw(b, kContinue, floatBase | vt::IDX_32, 1, idx32 + 12, v8);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, kIndicesScreen);
    return run;
}

CONFORMANCE_TEST(PrimitivesIndices, runIndices)

// The PSP's screenshot of continue, through mode (rows 10..50; transform mode is the same 50 rows
// lower): points at the four corners of (10, 10)-(50, 50); lines (60..99, rows 10 and 50: the
// second and fourth vertices start the next line); the strip's outline without its last pixel
// (110..150 row 10, x 150 rows 11..49, 110..149 row 50); triangles: the upper-right half of
// (160, 10)-(200, 50); the strip's two triangles (TL, TR, BR) and (TR, BR, BL) cover its box but
// for the quarter (TL, centre, BL), including the pixels whose centre lies on the second one's
// up-right diagonal (229, 30) ... (210, 49); the fan and
// the sprite fill their boxes (260, 310); the continued fan with the advancing vertex pointer fills
// (360, 10)-(400, 50).
std::vector<ScreenSpan> continueScreen() {
    const std::vector<ScreenSpan> through = {
        {10, 11, 10, 11, 0, 0, 0xFF0000},   {10, 11, 50, 51, 0, 0, 0xFF0000},   {10, 11, 60, 100, 0, 0, 0x00FF00},
        {10, 11, 110, 151, 0, 0, 0x0000FF}, {10, 50, 160, 200, 1, 0, 0xFFFF00}, {10, 30, 210, 250, 1, 0, 0xFF00FF},
        {10, 50, 260, 300, 0, 0, 0x00FFFF}, {10, 50, 310, 350, 0, 0, 0xFFFFFF}, {10, 50, 360, 400, 0, 0, 0x777777},
        {11, 50, 150, 151, 0, 0, 0x0000FF}, {30, 50, 229, 250, -1, 0, 0xFF00FF}, {50, 51, 10, 11, 0, 0, 0xFF0000},
        {50, 51, 50, 51, 0, 0, 0xFF0000},   {50, 51, 60, 100, 0, 0, 0x00FF00},  {50, 51, 110, 150, 0, 0, 0x0000FF},
    };
    std::vector<ScreenSpan> all = through;
    for (ScreenSpan s : through) {
        s.y0 += 50, s.y1 += 50;
        all.push_back(s);
    }
    return all;
}

TestRun runContinue(GuSim& gu) {
    TestRun run{"primitives/continue", gu.backend(), {}};
    ListBuilder& b = startPrimitives(gu);
    StaticData mem(gu, 0x08400000);
    static constexpr u32 kColors[6] = {0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFF00FFFF, 0xFFFF00FF, 0xFFFFFF00};
    static constexpr u32 kPrims[6] = {GE_PRIM_POINTS,    GE_PRIM_LINES,          GE_PRIM_LINE_STRIP,
                                      GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN};
    u32 v[6][2];
    for (int i = 0; i < 6; ++i) {
        v[i][0] = mem.put(p16(box(kColors[i], 10 + 50 * i, 10)));
        v[i][1] = mem.put(p16(box(kColors[i], 10 + 50 * i, 60), false));
    }
    const u32 v7 = mem.put(p16({{0xFFFFFFFF, 310, 10}, {0xFFFFFFFF, 350, 50}}));
    const u32 v7x = mem.put(p16({{0xFFFFFFFF, 310, 60}, {0xFFFFFFFF, 350, 100}}, false));
    const u32 v8 = mem.put(p16(box(0xFF777777, 360, 10)));
    const u32 v8x = mem.put(p16(box(0xFF777777, 360, 60), false));

    const u32 through = vt::COL_8888 | vt::POS_16 | vt::THROUGH, transform = vt::COL_8888 | vt::POS_16;
    for (int i = 0; i < 6; ++i) {
        draw(b, kPrims[i], through, 1, 0, v[i][0]);
        draw(b, kContinue, through, 3, 0, v[i][0] + 12);
        draw(b, kPrims[i], transform, 1, 0, v[i][1]);
        draw(b, kContinue, transform, 3, 0, v[i][1] + 12);
    }
    draw(b, GE_PRIM_RECTANGLES, through, 1, 0, v7);
    draw(b, kContinue, through, 1, 0, v7 + 12);
    draw(b, GE_PRIM_RECTANGLES, transform, 1, 0, v7x);
    draw(b, kContinue, transform, 1, 0, v7x + 12);
    draw(b, GE_PRIM_TRIANGLE_FAN, through, 1, 0, v8);
    draw(b, kContinue, through, 3, 0, 0);
    draw(b, GE_PRIM_TRIANGLE_FAN, transform, 1, 0, v8x);
    draw(b, kContinue, transform, 3, 0, 0);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, continueScreen());
    return run;
}

CONFORMANCE_TEST(PrimitivesContinue, runContinue)

}  // namespace
}  // namespace ge::conformance
