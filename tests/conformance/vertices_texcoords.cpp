// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/vertices/texcoords, re-created (gu_sim.h, conformance.h,
// screenshot.h). 30 textured fans of 32x32 pixels (two of 128x32), left to right from (10, 10), 10
// pixels apart, wrapping into rows 42 apart, each with texture coordinates (0, 0)-(u, v) in an 8-bit,
// 16-bit or float format, in through and transform mode, over a 4x4 8888 texture whose texel
// (row r, column c) is COLORS[r + c] (red, green, blue, yellow, magenta, cyan, white); nearest and
// repeat, then four with bilinear filtering and clamp, then large, negative, NaN and infinite
// coordinates, then two in clear mode. The vertices are written as vertices/shared.cpp's Vertices
// class writes them (8-bit coordinates as (s8)(int)u, 16-bit as (s16)(int)u). The screenshot is the
// check.
//
// The PSP's picture, written as what each box samples: `ku` texels across its width and `kv` down
// its 32 rows. Nearest: pixel (i, j) shows texel (floor((j + 0.5)·kv / 32), floor((i + 0.5)·ku / w))
// wrapped to 0..3. Bilinear: the texel position (i + 0.5)·ku / w − 0.5 (the same down) is cut to
// 1/16 texel (truncated), the four clamped texels are weighted by the sixteenths and the sum over
// 256 truncated: 0xef0f00 one sixteenth from red towards green. Every pixel of the capture is this
// (black outside the boxes). What it shows: 8-bit through-mode coordinates 4 sample texel 0 and 255
// sample two texels; transform-mode 8-bit 128 and 16-bit 32768 are 1.0 (the whole texture), 8-bit
// 127 is 127/128 of it, 255 and 65535 twice it; negative coordinates repeat backwards; NaN and both
// infinities sample texel 0 (so does the NaN v of (1, NaN)); nothing is drawn in clear mode (the
// vertices have no colour).
#include <cmath>
#include <limits>

#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr int kBoxW = 32, kBoxH = 32, kBoxSpace = 10;
constexpr u32 kImage = 0x08400000;
constexpr u32 kColors[7] = {0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFF00FFFF, 0xFFFF00FF, 0xFFFFFF00, 0xFFFFFFFF};

struct Cursor {
    int x = 10, y = 10;
};

// nextBox(u, v, vtype, w): TP(0, 0, x, y), (u, 0, x + w, y), (u, v, x + w, y + H), (0, v, x, y + H)
// as a GU_TRIANGLE_FAN; 16-bit positions (norm16x/y in transform mode).
void nextBox(ListBuilder& b, Cursor& at, float u, float v, u32 vtype, int w = kBoxW) {
    const u32 tc = vtype & 3;
    const bool through = (vtype & vt::THROUGH) != 0;
    const u32 tcSize = tc == 1 ? 1 : tc == 2 ? 2 : 4, posAt = 2 * tcSize;
    u32 size = posAt + 6;
    size = (size + tcSize - 1) / tcSize * tcSize;  // EndVert(): aligned to the texture coordinate
    const float uv[4][2] = {{0, 0}, {u, 0}, {u, v}, {0, v}};
    const int pos[4][2] = {{at.x, at.y}, {at.x + w, at.y}, {at.x + w, at.y + kBoxH}, {at.x, at.y + kBoxH}};
    std::vector<u8> data(4 * size, 0);
    for (int k = 0; k < 4; ++k) {
        u8* p = &data[size_t(k) * size];
        for (int c = 0; c < 2; ++c) {
            const float f = uv[k][c];
            if (tc == 1)
                p[c] = u8(s8(int(f)));
            else if (tc == 2)
                writeLE16(p + 2 * c, u16(s16(int(f))));
            else
                writeLE32(p + 4 * c, floatBits(f));
        }
        const int x = through ? pos[k][0] : pos[k][0] * 65536 / 480 - 32768;
        const int y = through ? pos[k][1] : 32768 - pos[k][1] * 65536 / 272;
        writeLE16(p + posAt, u16(x));
        writeLE16(p + posAt + 2, u16(y));
    }
    b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, data.data());
    at.x += w + kBoxSpace;
    if (at.x + w >= 480) {
        at.x = 10;
        at.y += kBoxH + kBoxSpace;
    }
}

// What the PSP shows per box, in drawing order: texels across and down, bilinear; `drawn` false
// for the clear-mode boxes.
struct BoxSample {
    float ku, kv;
    bool linear = false, drawn = true;
    int w = kBoxW;
};
const BoxSample kBoxes[30] = {
    {0, 0},   {2, 2},   {4, 4},   {0, 0}, {2, 2}, {4, 4},       {4, 4},      {0, 0},       {4, 4},      {4, 4},
    {4, 4},   {3.96875f, 3.96875f, false, true, 128},           {4, 4, false, true, 128},  {4, 4, true},
    {3.5f, 3.5f, true},                   {3, 3, true},         {1, 1, true}, {16, 16},    {16, 16},    {-16, -16},
    {8, 8},   {8, 8},   {2, 2},   {0, 0}, {0, 0}, {0, 0},       {4, 0},      {4, 0},       {0, 0, false, false},
    {0, 0, false, false},
};

u32 texelRgb(int r, int c, bool clamp) {
    if (clamp) {
        r = std::clamp(r, 0, 3), c = std::clamp(c, 0, 3);
    } else {
        r &= 3, c &= 3;
    }
    const u32 abgr = kColors[r + c];
    return (abgr & 0xFF) << 16 | (abgr & 0xFF00) | (abgr >> 16 & 0xFF);
}

std::vector<u32> texcoordsRow(int y) {
    std::vector<u32> row(480, 0);
    int bx = 10, by = 10;
    for (const BoxSample& box : kBoxes) {
        const int w = box.w;
        if (box.drawn && y >= by && y < by + kBoxH) {
            const int j = y - by;
            for (int i = 0; i < w; ++i) {
                u32& out = row[size_t(bx + i)];
                if (!box.linear) {
                    out = texelRgb(int(std::floor((j + 0.5) * box.kv / kBoxH)), int(std::floor((i + 0.5) * box.ku / w)), false);
                    continue;
                }
                const int s = int(std::floor(((i + 0.5) * box.ku / w - 0.5) * 16));
                const int t = int(std::floor(((j + 0.5) * box.kv / kBoxH - 0.5) * 16));
                const int s0 = s >> 4, fs = s & 15, t0 = t >> 4, ft = t & 15;
                const u32 c00 = texelRgb(t0, s0, true), c01 = texelRgb(t0, s0 + 1, true);
                const u32 c10 = texelRgb(t0 + 1, s0, true), c11 = texelRgb(t0 + 1, s0 + 1, true);
                u32 rgb = 0;
                for (int shift : {16, 8, 0}) {
                    const u32 sum = (c00 >> shift & 0xFF) * u32((16 - fs) * (16 - ft)) + (c01 >> shift & 0xFF) * u32(fs * (16 - ft)) +
                                    (c10 >> shift & 0xFF) * u32((16 - fs) * ft) + (c11 >> shift & 0xFF) * u32(fs * ft);
                    rgb |= (sum >> 8) << shift;
                }
                out = rgb;
            }
        }
        bx += w + kBoxSpace;
        if (bx + w >= 480) {
            bx = 10;
            by += kBoxH + kBoxSpace;
        }
    }
    return row;
}

TestRun runTexcoords(GuSim& gu) {
    TestRun run{"vertices/texcoords", gu.backend(), {}};
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    u32 image[16];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) image[r * 4 + c] = kColors[r + c];
    gu.cpuWrite(kImage, image, sizeof image);

    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);  // startFrame()
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.texFilter(0, 0);
    b.texFunc(1 /*DECAL*/, false);
    b.texWrap(false, false);
    b.setTexture(0, kImage, 4, 4, 4);

    Cursor at;
    const u32 p16 = vt::POS_16, th = vt::THROUGH;
    nextBox(b, at, 0, 0, vt::TC_16 | p16 | th);
    nextBox(b, at, 2, 2, vt::TC_16 | p16 | th);
    nextBox(b, at, 4, 4, vt::TC_16 | p16 | th);
    nextBox(b, at, 4, 4, vt::TC_8 | p16 | th);
    nextBox(b, at, 255, 255, vt::TC_8 | p16 | th);
    nextBox(b, at, 4, 4, vt::TC_16 | p16 | th);
    nextBox(b, at, 4, 4, vt::TC_F | p16 | th);
    nextBox(b, at, 0, 0, vt::TC_16 | p16);
    nextBox(b, at, 32768, 32768, vt::TC_16 | p16);
    nextBox(b, at, 128, 128, vt::TC_8 | p16);
    nextBox(b, at, 1, 1, vt::TC_F | p16);
    nextBox(b, at, 127, 127, vt::TC_8 | p16, 128);
    nextBox(b, at, 128, 128, vt::TC_8 | p16, 128);
    b.texWrap(true, true);
    b.texFilter(1, 1);
    nextBox(b, at, 128, 128, vt::TC_8 | p16);
    nextBox(b, at, 112, 112, vt::TC_8 | p16);
    nextBox(b, at, 96, 96, vt::TC_8 | p16);
    nextBox(b, at, 32, 32, vt::TC_8 | p16);
    b.texWrap(false, false);
    b.texFilter(0, 0);
    nextBox(b, at, 16, 16, vt::TC_16 | p16 | th);
    nextBox(b, at, 4, 4, vt::TC_F | p16);
    nextBox(b, at, -4, -4, vt::TC_F | p16);
    nextBox(b, at, 255, 255, vt::TC_8 | p16);
    nextBox(b, at, 65535, 65535, vt::TC_16 | p16);
    nextBox(b, at, 0.5f, 0.5f, vt::TC_F | p16);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    nextBox(b, at, nan, nan, vt::TC_F | p16);
    nextBox(b, at, inf, inf, vt::TC_F | p16);
    nextBox(b, at, -inf, -inf, vt::TC_F | p16);
    nextBox(b, at, 1, nan, vt::TC_F | p16);
    nextBox(b, at, 1, 0, vt::TC_F | p16);
    b.cmd(GE_CMD_CMODE, 1 | ((CLEAR_COLOR | CLEAR_STENCIL) << 8));
    b.enable(GE_CMD_ABE, false);
    nextBox(b, at, 4, 4, vt::TC_F | p16 | th);
    nextBox(b, at, 1, 1, vt::TC_F | p16);
    b.cmd(GE_CMD_CMODE, 0);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, texcoordsRow);
    return run;
}

CONFORMANCE_TEST(VerticesTexcoords, runTexcoords)

}  // namespace
}  // namespace ge::conformance
