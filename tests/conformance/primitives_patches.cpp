// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/primitives/bezier and primitives/spline, re-created (gu_sim.h,
// conformance.h, screenshot.h). Through-mode patches of 16-bit-position control points on a black
// frame: 4x4 grids of 30x30 pixels (control points 10 pixels apart, rows at the y given), in flat
// colours, with UVs (a 2x2 CLUT8 texture {0, 0 / 0, 1}: red, red / red, green; DECAL), with
// rows of different colours, as triangle strips (PPM 0), lines (1), points (2) and the values 3 and
// 4, divided 16x16, 4x4, 1x1, 1x2, 2x2 and 0x0, flat and Gouraud, 4x2, 4x5 and 4x8 control points,
// 8-, 16- and 32-bit indices, and draws that continue with the vertex and index pointers the
// previous one left (VADR/IADR not sent). spline also draws six patches with each u and v edge type
// (open/closed ends 0..3). The arrays are the programs' static ones (checked against their source:
// each a grid of 4 columns 10 pixels apart or a 30x30 quad of 4 points reached through the indices
// {0 0 1 1 / 0 0 1 1 / 2 2 3 3 / 2 2 3 3}). The screenshot is the check; the PSP's picture is a table
// of spans generated from it and checked to reproduce all its pixels (primitives_bezier.inc,
// primitives_spline.inc: the Gouraud patches' colour steps make many short spans).
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr u32 kClut = 0x08380000, kImage = 0x08380040, kData = 0x08380100;
constexpr u32 kRed = 0xFF0000FF;

// Vertex_C8888_P16 (12 bytes): a grid of 4 columns from x0, 10 apart, one row per y, colour per row.
std::vector<u8> grid(int x0, const std::vector<int>& ys, const std::vector<u32>& rowColors) {
    std::vector<u8> out(ys.size() * 4 * 12, 0);
    for (size_t j = 0; j < ys.size(); ++j)
        for (int i = 0; i < 4; ++i) {
            u8* p = &out[(j * 4 + size_t(i)) * 12];
            writeLE32(p, rowColors[j]);
            writeLE16(p + 4, u16(x0 + 10 * i)), writeLE16(p + 6, u16(ys[j]));
        }
    return out;
}
std::vector<u8> grid(int x0, const std::vector<int>& ys, u32 first, u32 rest) {
    std::vector<u32> c(ys.size(), rest);
    c[0] = first;
    return grid(x0, ys, c);
}
// vertices2_uvs: Vertex_UV16_P16 (10 bytes), u per column and v per row {0, 1, 2, 2}.
std::vector<u8> uvGrid(int x0) {
    static constexpr u16 kUv[4] = {0, 1, 2, 2};
    std::vector<u8> out(16 * 10, 0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            u8* p = &out[size_t(j * 4 + i) * 10];
            writeLE16(p, kUv[i]), writeLE16(p + 2, kUv[j]);
            writeLE16(p + 4, u16(x0 + 10 * i)), writeLE16(p + 6, u16(10 + 10 * j));
        }
    return out;
}
// A 30x30 quad TL, TR, BL, BR from (x0, y0), top and bottom colours.
std::vector<u8> quad(int x0, int y0, u32 top, u32 bottom) {
    std::vector<u8> out(4 * 12, 0);
    const int pts[4][2] = {{x0, y0}, {x0 + 30, y0}, {x0, y0 + 30}, {x0 + 30, y0 + 30}};
    for (int k = 0; k < 4; ++k) {
        writeLE32(&out[size_t(k) * 12], k < 2 ? top : bottom);
        writeLE16(&out[size_t(k) * 12 + 4], u16(pts[k][0])), writeLE16(&out[size_t(k) * 12 + 6], u16(pts[k][1]));
    }
    return out;
}
std::vector<u8> quadIndices(u32 size, u32 base = 0) {
    static constexpr u32 kIdx[16] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};
    std::vector<u8> out(16 * size, 0);
    for (int k = 0; k < 16; ++k) {
        const u32 v = kIdx[k] + base;
        if (size == 1)
            out[size_t(k)] = u8(v);
        else if (size == 2)
            writeLE16(&out[size_t(k) * 2], u16(v));
        else
            writeLE32(&out[size_t(k) * 4], v);
    }
    return out;
}

// Draws a patch: bezier (uedge < 0) or spline with the edge types; sceGuDrawBezier/sceGuDrawSpline.
struct PatchDraw {
    ListBuilder& b;
    bool spline;
    void operator()(u32 vtype, u32 u, u32 v, u32 indices, u32 vertices, u32 uedge = 3, u32 vedge = 3) const {
        if (spline)
            b.drawSpline(vtype, u, v, uedge, vedge, indices, vertices);
        else
            b.drawBezier(vtype, u, v, indices, vertices);
    }
};

void drawPatches(GuSim& gu, bool spline) {
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    const u32 clut[8] = {0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFF00FFFF, 0, 0, 0, 0};
    gu.cpuWrite(kClut, clut, sizeof clut);
    u8 image[64] = {};
    image[17] = image[18] = image[33] = image[34] = 1;
    gu.cpuWrite(kImage, image, sizeof image);
    StaticData mem(gu, kData);
    const std::vector<int> rows = {10, 20, 30, 40}, pos = {10, 30, 35, 40};
    const u32 v1 = mem.put(grid(10, rows, kRed, kRed)), v2 = mem.put(uvGrid(50));
    const u32 v3 = mem.put(grid(90, rows, kRed, 0xFFFF0000));
    u32 v4to8[5];
    for (int i = 0; i < 5; ++i) v4to8[i] = mem.put(grid(130 + 40 * i, pos, kRed, 0xFF00FFFF));
    u32 v9to11[3];
    for (int i = 0; i < 3; ++i) v9to11[i] = mem.put(grid(330 + 40 * i, pos, kRed, 0xFFFF00FF));
    const u32 v12 = mem.put(grid(10, {50, 80}, kRed, 0xFFFFFF00));
    const u32 v13 = mem.put(grid(50, {50, 55, 60, 70, 80}, kRed, 0xFFFFFF00));
    const u32 v14 = mem.put(grid(90, {50, 54, 58, 62, 66, 70, 75, 80}, kRed, 0xFFFFFF00));
    const u32 v15 = mem.put(quad(130, 50, 0xFFFF0000, 0xFFFFFFFF)), i15 = mem.put(quadIndices(1));
    const u32 v16 = mem.put(quad(170, 50, 0xFFFF0000, 0xFF777777)), i16 = mem.put(quadIndices(2));
    const u32 v17 = mem.put(quad(210, 50, 0xFFFF0000, 0xFF007FFF)), i17 = mem.put(quadIndices(4));
    std::vector<u8> inc = grid(250, {50, 60, 70, 80}, kRed, 0xFF000077);
    const std::vector<u8> inc2 = grid(290, {50, 60, 70, 80}, kRed, 0xFF007700);
    inc.insert(inc.end(), inc2.begin(), inc2.end());
    const u32 v18 = mem.put(inc);
    std::vector<u8> q2021 = quad(330, 50, 0xFFFF0000, 0xFF770000), q21 = quad(370, 50, 0xFFFF0000, 0xFF777700);
    q2021.insert(q2021.end(), q21.begin(), q21.end());
    const u32 v20 = mem.put(q2021);
    std::vector<u8> i2021 = quadIndices(1), i21 = quadIndices(1, 4);
    i2021.insert(i2021.end(), i21.begin(), i21.end());
    const u32 i20 = mem.put(i2021);
    const u32 v22 = mem.put(grid(410, {50, 60, 75, 80}, 0xFFFF0000, 0xFF007777));
    static constexpr u32 kUvTypeBottom[6] = {0xFF9999FF, 0xFF993366, 0xFFFFFFCC, 0xFF660066, 0xFFFF8080, 0xFF0066CC};
    u32 vTypes[6] = {}, iTypes = 0;
    if (spline) {
        for (int k = 0; k < 6; ++k) vTypes[k] = mem.put(quad(10 + 40 * k, 90, 0xFFFFFFFF, kUvTypeBottom[k]));
        iTypes = mem.put(quadIndices(1));
    }

    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);  // startFrame()
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.texFilter(0, 0);
    b.texFunc(1 /*DECAL*/, false);
    b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
    b.setTexture(0, kImage, 2, 2, 16);
    b.clutLoad(kClut, 1);
    b.patchPrim(0);  // sceGuPatchPrim(GU_TRIANGLE_STRIP)
    b.patchDivide(16, 16);
    b.patchFace(true);  // sceGuPatchFrontFace(GU_CW): PFACE 1
    const PatchDraw draw{b, spline};
    const u32 cp = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    b.enable(GE_CMD_TME, false);
    draw(cp, 4, 4, 0, v1);
    b.enable(GE_CMD_TME, true);
    draw(vt::TC_16 | vt::POS_16 | vt::THROUGH, 4, 4, 0, v2);
    b.enable(GE_CMD_TME, false);
    draw(cp, 4, 4, 0, v3);
    draw(cp, 4, 4, 0, v4to8[0]);
    for (u32 k = 1; k <= 4; ++k) {
        b.patchPrim(k);  // sceGuSendCommandi(55, k)
        b.patchDivide(4, 4);
        draw(cp, 4, 4, 0, v4to8[k]);
    }
    b.patchPrim(0);
    b.shadeModel(false);
    b.patchDivide(1, 1);
    draw(cp, 4, 4, 0, v9to11[0]);
    b.patchDivide(1, 2);
    draw(cp, 4, 4, 0, v9to11[1]);
    b.patchDivide(2, 2);
    draw(cp, 4, 4, 0, v9to11[2]);
    b.patchDivide(4, 4);
    b.shadeModel(true);
    draw(cp, 4, 2, 0, v12);
    draw(cp, 4, 5, 0, v13);
    draw(cp, 4, 8, 0, v14);
    draw(cp | vt::IDX_8, 4, 4, i15, v15);
    draw(cp | vt::IDX_16, 4, 4, i16, v16);
    draw(cp | vt::IDX_32, 4, 4, i17, v17);  // GU_INDEX_BITS
    draw(cp, 4, 4, 0, v18);
    draw(cp, 4, 4, 0, 0);
    draw(cp | vt::IDX_8, 4, 4, i20, v20);
    draw(cp | vt::IDX_8, 4, 4, 0, 0);
    b.shadeModel(false);
    b.patchDivide(0, 0);
    draw(cp, 4, 4, 0, v22);
    if (spline) {
        b.shadeModel(true);
        b.patchDivide(0, 0);
        static constexpr u32 kEdges[6][2] = {{0, 3}, {1, 3}, {2, 3}, {3, 0}, {3, 1}, {3, 2}};
        for (int k = 0; k < 6; ++k) draw(cp | vt::IDX_8, 4, 4, iTypes, vTypes[k], kEdges[k][0], kEdges[k][1]);
    }
    gu.finishSync();
}

// The PSP's screenshots (black elsewhere), spans generated from the captures.
const std::vector<ScreenSpan> kBezierScreen = {
#include "tests/conformance/primitives_bezier.inc"
};
const std::vector<ScreenSpan> kSplineScreen = {
#include "tests/conformance/primitives_spline.inc"
};

TestRun runBezier(GuSim& gu) {
    TestRun run{"primitives/bezier", gu.backend(), {}};
    drawPatches(gu, false);
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, kBezierScreen);
    return run;
}
TestRun runSpline(GuSim& gu) {
    TestRun run{"primitives/spline", gu.backend(), {}};
    drawPatches(gu, true);
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, kSplineScreen);
    return run;
}

CONFORMANCE_TEST(PrimitivesBezier, runBezier)
CONFORMANCE_TEST(PrimitivesSpline, runSpline)

}  // namespace
}  // namespace ge::conformance
