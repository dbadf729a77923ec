// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/vertices/colors, re-created (gu_sim.h, conformance.h,
// screenshot.h). 27 boxes of 40x40 pixels, nine a row from (10, 10), 50 pixels apart, each a
// 4-vertex fan of one colour in a 16-bit position format: the colour as 5650, 5551, 4444 or 8888;
// three rows: transform mode, through mode, through mode in clear mode (CMODE 0x301, colour and
// stencil written). Each row draws four opaque boxes, then, with blending SRC_ALPHA /
// ONE_MINUS_SRC_ALPHA on the black frame, five with alpha 0x80 or 0x7F. The screenshot is the check.
// What the PSP shows: a 5650 colour is opaque whatever its alpha; 5551 alpha 0x7F is 0 (the box
// blends to nothing) and 0x80 is 1; 4444 alpha 0x80 is 8/15 (0x88 of yellow); 8888 alpha 0x80 gives
// 0x80 of cyan; in clear mode nothing blends.
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr int kBoxW = 40, kBoxH = 40, kBoxSpace = 10;

// The vertex colour as the test program's Vertices::WriteCol stores it for each format.
u32 packColor(u32 fmt, u32 c) {
    switch (fmt) {
    case vt::COL_5650: return ((c >> 3) & 0x001F) | ((c >> 5) & 0x07E0) | ((c >> 8) & 0xF800);
    case vt::COL_5551: return ((c >> 3) & 0x001F) | ((c >> 6) & 0x03E0) | ((c >> 9) & 0x7C00) | ((c >> 16) & 0x8000);
    case vt::COL_4444: return ((c >> 4) & 0x000F) | ((c >> 8) & 0x00F0) | ((c >> 12) & 0x0F00) | ((c >> 16) & 0xF000);
    default: return c;
    }
}

struct BoxCursor {
    int x = 10, y = 10;
    void next() {
        x += kBoxW + kBoxSpace;
        if (x + kBoxW >= 480) {
            x = 10;
            y += kBoxH + kBoxSpace;
        }
    }
};

// nextBox(c, vtype): CP(c, x, y), (x + W, y), (x + W, y + H), (x, y + H) with 16-bit positions
// (norm16x/norm16y of the pixel in transform mode), drawn as GU_TRIANGLE_FAN.
void nextBox(ListBuilder& b, BoxCursor& at, u32 color, u32 colFmt, bool through) {
    const int x = at.x, y = at.y;
    const int pts[4][2] = {{x, y}, {x + kBoxW, y}, {x + kBoxW, y + kBoxH}, {x, y + kBoxH}};
    const bool wideColor = colFmt == vt::COL_8888;
    const u32 size = wideColor ? 12 : 8, posAt = wideColor ? 4 : 2;
    std::vector<u8> data(4 * size, 0);
    for (int i = 0; i < 4; ++i) {
        u8* p = &data[size_t(i) * size];
        if (wideColor)
            writeLE32(p, color);
        else
            writeLE16(p, u16(packColor(colFmt, color)));
        const int px = through ? pts[i][0] : pts[i][0] * 65536 / 480 - 32768;
        const int py = through ? pts[i][1] : 32768 - pts[i][1] * 65536 / 272;
        writeLE16(p + posAt, u16(px));
        writeLE16(p + posAt + 2, u16(py));
    }
    const u32 vtype = colFmt | vt::POS_16 | (through ? vt::THROUGH : 0u);
    b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, data.data());
    at.next();
}

// The PSP's screenshot: each box's colour (0xRRGGBB; 0 where nothing shows), rows of nine.
constexpr u32 kBoxes[27] = {
    0xFF0000, 0x00FF00, 0x0000FF, 0xFFFF00, 0xFF0000, 0x000000, 0x0000FF, 0x888800, 0x008080,  // transform
    0xFF0000, 0x00FF00, 0x0000FF, 0xFFFF00, 0xFF0000, 0x000000, 0x0000FF, 0x888800, 0x008080,  // through
    0xFF0000, 0x00FF00, 0x0000FF, 0xFFFF00, 0xFF0000, 0x00FF00, 0x0000FF, 0xFFFF00, 0x00FFFF,  // clear mode
};

TestRun runColors(GuSim& gu) {
    TestRun run{"vertices/colors", gu.backend(), {}};
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();

    ListBuilder& b = gu.start();  // startFrame(): sceGuClearColor(0), sceGuClear(GU_COLOR_BUFFER_BIT)
    b.clear(CLEAR_COLOR, 0, 0);
    b.enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE): GU_TEXTURE is 3, GU_STENCIL_TEST's number
    b.enable(GE_CMD_ABE, false);
    BoxCursor at;
    auto opaque = [&](bool through) {
        nextBox(b, at, 0xFF0000FF, vt::COL_5650, through);
        nextBox(b, at, 0xFF00FF00, vt::COL_5551, through);
        nextBox(b, at, 0xFFFF0000, vt::COL_4444, through);
        nextBox(b, at, 0xFF00FFFF, vt::COL_8888, through);
    };
    auto translucent = [&](bool through) {
        b.enable(GE_CMD_ABE, true);
        b.blendFunc(0 /*ADD*/, 2 /*SRC_ALPHA*/, 3 /*ONE_MINUS_SRC_ALPHA*/, 0, 0);
        nextBox(b, at, 0x800000FF, vt::COL_5650, through);
        nextBox(b, at, 0x7F00FF00, vt::COL_5551, through);
        nextBox(b, at, 0x80FF0000, vt::COL_5551, through);
        nextBox(b, at, 0x8000FFFF, vt::COL_4444, through);
        nextBox(b, at, 0x80FFFF00, vt::COL_8888, through);
    };
    opaque(false);
    translucent(false);
    b.enable(GE_CMD_ABE, false);
    opaque(true);
    translucent(true);
    b.cmd(GE_CMD_CMODE, 1 | ((CLEAR_COLOR | CLEAR_STENCIL) << 8));  // sceGuSendCommandi(211, ...)
    b.enable(GE_CMD_ABE, false);
    opaque(true);
    translucent(true);
    b.cmd(GE_CMD_CMODE, 0);
    gu.finishSync();

    std::vector<ScreenSpan> spans;
    for (int i = 0; i < 27; ++i) {
        const int x = 10 + (i % 9) * (kBoxW + kBoxSpace), y = 10 + (i / 9) * (kBoxH + kBoxSpace);
        spans.push_back({y, y + kBoxH, x, x + kBoxW, 0, 0, kBoxes[i]});
    }
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, spans);
    return run;
}

CONFORMANCE_TEST(VerticesColors, runColors)

}  // namespace
}  // namespace ge::conformance
