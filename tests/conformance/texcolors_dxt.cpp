// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/texcolors/dxt1, dxt3 and dxt5, re-created (gu_sim.h,
// conformance.h). An 8x8 texture of four identical DXT blocks (the same two 565 colours and index
// rows in each), nearest filtering, REPLACE/RGBA, clamped, drawn by a 2x2 through-mode sprite at
// (0, 0) into an 8888 buffer, twice per box: once with blending off (pixel 0's RGB: the texel's
// colour), once over a white pixel with blending ADD, FIX 0 x source + SRC_ALPHA x destination
// (pixel 0's RGB: the texel's alpha in all three channels). The test prints "colour / alpha"; each
// of the two is a checkpoint here. The values show how the PSP decodes DXT: 565 endpoints with red
// in bits 15..11 widened by a shift alone (0xFFFF is f8fcf8), the 1/3 and 2/3 mixes when the first
// endpoint is greater, the half mix and a transparent (DXT1) or opaque (DXT3/5) black otherwise,
// DXT3's 4-bit alpha as a << 4, DXT5's alpha endpoints and their 8- or 6-step interpolation.
#include "tests/conformance/conformance.h"

#include <cstdio>
#include <iterator>
#include <string>

namespace ge::conformance {
namespace {

// The test program's fillTexture(img, c1, c2, line, ...): four blocks, each with colour endpoints
// c1, c2 and all four index rows `line`; "Top left pixel only" has index row 0 = 0x02 and rows
// 1..3 = 0 (index 2 at texel (0, 0), 0 elsewhere); in DXT3 its alpha rows likewise (0xF, 0, 0, 0).
struct ColorBlock {
    u16 c1, c2;
    u8 line;
    bool topLeftOnly = false;
};

// The DXT colour half (8 bytes), in the PSP's order: the four index rows, then the endpoints.
void putColorBlock(u8* p, const ColorBlock& c) {
    for (int y = 0; y < 4; ++y) p[y] = c.topLeftOnly ? (y == 0 ? 0x02 : 0x00) : c.line;
    writeLE16(p + 4, c.c1);
    writeLE16(p + 6, c.c2);
}

constexpr u32 kImages = 0x08400000;  // memalign(16, ...) blocks, one per image, 512 bytes apart
constexpr u32 kImageStride = 0x200;

// drawTexFlush(img, verts, exposeAlpha): the texture state, blending, the through-mode sprite.
void drawTexFlush(GuSim& gu, u32 format, u32 addr, bool exposeAlpha) {
    static const std::vector<u8> verts = spriteUv16(2, 2, 2, 2);  // verticesThrough
    ListBuilder& l = gu.start();
    l.enable(GE_CMD_TME, true);
    l.texSync();
    l.texFlush();
    l.texMode(format, 0, false);
    l.texWrap(true, true);                 // GU_CLAMP, GU_CLAMP
    l.texFunc(3 /*REPLACE*/, true /*RGBA*/);
    l.texSlope(2.0f);
    l.setTexture(0, addr, 8, 8, 8);
    if (exposeAlpha) {
        l.enable(GE_CMD_ABE, true);
        l.blendFunc(0 /*ADD*/, 10 /*FIX*/, 2 /*SRC_ALPHA*/, 0, 0xFFFFFF);
    } else {
        l.enable(GE_CMD_ABE, false);
    }
    l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, verts.data());
    gu.finishSync();
}

// getBuffer(): pixel 0's RGB; resetBuffer(c): the first row (512 pixels) filled with byte c.
u32 getBuffer(GuSim& gu) { return gu.readVram32(0) & 0x00FFFFFF; }
void resetBuffer(GuSim& gu, u8 c) { gu.fillVram32(0, 0x01010101u * c, 512); }

// init(): sceGuInit, the frame (scissor 8x8, enabled), depth range 65535-65500, dither off, Gouraud
// shading, identity matrices, the buffer's first row zeroed; then main()'s sceGuTexFilter(GU_NEAREST,
// GU_NEAREST) list.
void init(GuSim& gu) {
    gu.init();
    ListBuilder& b = gu.start();
    sdkFrameSetup(b, {480, 272, 8, 8});
    b.depthRange(65535, 65500);
    b.enable(GE_CMD_DTE, false);
    b.shadeModel(true);
    setIdentityMatrices(b);
    gu.finishSync();
    resetBuffer(gu, 0);
    gu.start().texFilter(0, 0);
    gu.finishSync();
}

// testDrawingBox(title, img): the colour draw, the white reset, the alpha draw, the black reset.
void testDrawingBox(GuSim& gu, TestRun& run, u32 format, u32 addr, const std::string& title, u32 hwColor,
                    u32 hwAlpha) {
    drawTexFlush(gu, format, addr, false);
    const u32 color = getBuffer(gu);
    resetBuffer(gu, 0xFF);
    drawTexFlush(gu, format, addr, true);
    const u32 alpha = getBuffer(gu);
    resetBuffer(gu, 0x00);
    run.checkpoints.push_back({title + " colour", hwColor, color, 0x00FFFFFF});
    run.checkpoints.push_back({title + " alpha", hwAlpha, alpha, 0x00FFFFFF});
}

// ---- texcolors/dxt1 -------------------------------------------------------------------------

struct Dxt1Box {
    const char* title;
    ColorBlock block;
    u32 color, alpha;  // what a PSP printed: "%06x / %06x"
};
const Dxt1Box kDxt1[] = {
    {"White 0", {0xFFFF, 0xFFFF, 0x00}, 0xf8fcf8, 0xffffff},
    {"White 1", {0xFFFF, 0xFFFF, 0x55}, 0xf8fcf8, 0xffffff},
    {"White 2", {0xFFFF, 0xFFFF, 0xAA}, 0xf8fcf8, 0xffffff},
    {"White 3", {0xFFFF, 0xFFFF, 0xFF}, 0x000000, 0x000000},
    {"First greater 0", {0xFFE3, 0x8410, 0x00}, 0x18fcf8, 0xffffff},
    {"First greater 1", {0xFFE3, 0x8410, 0x55}, 0x808080, 0xffffff},
    {"First greater 2", {0xFFE3, 0x8410, 0xAA}, 0x3ad2d0, 0xffffff},
    {"First greater 3", {0xFFE3, 0x8410, 0xFF}, 0x5da9a8, 0xffffff},
    {"First lesser 0", {0x8410, 0xF85F, 0x00}, 0x808080, 0xffffff},
    {"First lesser 1", {0x8410, 0xF85F, 0x55}, 0xf808f8, 0xffffff},
    {"First lesser 2", {0x8410, 0xF85F, 0xAA}, 0xbc44bc, 0xffffff},
    {"First lesser 3", {0x8410, 0xF85F, 0xFF}, 0x000000, 0x000000},
    {"Color mix 2", {0x7890, 0x1234, 0xAA}, 0x8a2155, 0xffffff},
    {"Color mix 3", {0x7890, 0x1234, 0xFF}, 0x953232, 0xffffff},
    {"Top left pixel only", {0x7777, 0x1356, 0x00, true}, 0xb5c050, 0xffffff},
};

TestRun runDxt1(GuSim& gu) {
    TestRun run{"texcolors/dxt1", gu.backend(), {}};
    init(gu);
    for (u32 i = 0; i < std::size(kDxt1); ++i) {  // setupTexture()
        u8 img[4 * 8];
        for (int k = 0; k < 4; ++k) putColorBlock(img + 8 * k, kDxt1[i].block);
        gu.cpuWrite(kImages + i * kImageStride, img, sizeof(img));
    }
    for (u32 i = 0; i < std::size(kDxt1); ++i)
        testDrawingBox(gu, run, GE_TFMT_DXT1, kImages + i * kImageStride, kDxt1[i].title, kDxt1[i].color,
                       kDxt1[i].alpha);
    return run;
}

// ---- texcolors/dxt3 -------------------------------------------------------------------------

struct Dxt3Box {
    const char* title;
    ColorBlock block;
    u16 alphaLine;     // all four 16-bit alpha rows (4 bits per texel); top-left only: row 0
    u32 color, alpha;  // what a PSP printed
};
const Dxt3Box kDxt3[] = {
    {"White 0", {0xFFFF, 0xFFFF, 0x00}, 0x5555, 0xf8fcf8, 0x505050},
    {"White 1", {0xFFFF, 0xFFFF, 0x55}, 0x5555, 0xf8fcf8, 0x505050},
    {"White 2", {0xFFFF, 0xFFFF, 0xAA}, 0x5555, 0xf8fcf8, 0x505050},
    {"White 3", {0xFFFF, 0xFFFF, 0xFF}, 0x5555, 0x000000, 0x505050},
    {"First greater 0", {0xFFE3, 0x8410, 0x00}, 0x5555, 0x18fcf8, 0x505050},
    {"First greater 1", {0xFFE3, 0x8410, 0x55}, 0x5555, 0x808080, 0x505050},
    {"First greater 2", {0xFFE3, 0x8410, 0xAA}, 0x5555, 0x3ad2d0, 0x505050},
    {"First greater 3", {0xFFE3, 0x8410, 0xFF}, 0x5555, 0x5da9a8, 0x505050},
    {"First lesser 0", {0x8410, 0xF85F, 0x00}, 0x5555, 0x808080, 0x505050},
    {"First lesser 1", {0x8410, 0xF85F, 0x55}, 0x5555, 0xf808f8, 0x505050},
    {"First lesser 2", {0x8410, 0xF85F, 0xAA}, 0x5555, 0xbc44bc, 0x505050},
    {"First lesser 3", {0x8410, 0xF85F, 0xFF}, 0x5555, 0x000000, 0x505050},
    {"Color mix 2", {0x7890, 0x1234, 0xAA}, 0x5555, 0x8a2155, 0x505050},
    {"Color mix 3", {0x7890, 0x1234, 0xFF}, 0x5555, 0x953232, 0x505050},
    {"Alpha 0", {0x7890, 0x1234, 0xAA}, 0x0000, 0x8a2155, 0x000000},
    {"Alpha F", {0x7890, 0x1234, 0xFF}, 0xFFFF, 0x953232, 0xf0f0f0},
    {"Top left pixel only", {0x7777, 0x1356, 0x00, true}, 0x000F, 0xb5c050, 0xf0f0f0},
};

TestRun runDxt3(GuSim& gu) {
    TestRun run{"texcolors/dxt3", gu.backend(), {}};
    init(gu);
    for (u32 i = 0; i < std::size(kDxt3); ++i) {  // setupTexture()
        const Dxt3Box& box = kDxt3[i];
        u8 img[4 * 16];
        for (int k = 0; k < 4; ++k) {
            u8* p = img + 16 * k;
            putColorBlock(p, box.block);
            for (int y = 0; y < 4; ++y)
                writeLE16(p + 8 + 2 * y, box.block.topLeftOnly && y != 0 ? u16(0) : box.alphaLine);
        }
        gu.cpuWrite(kImages + i * kImageStride, img, sizeof(img));
    }
    for (u32 i = 0; i < std::size(kDxt3); ++i)
        testDrawingBox(gu, run, GE_TFMT_DXT3, kImages + i * kImageStride, kDxt3[i].title, kDxt3[i].color,
                       kDxt3[i].alpha);
    return run;
}

// ---- texcolors/dxt5 -------------------------------------------------------------------------
// Each image holds eight textures of four blocks (512 bytes); the i-th (getTexturePtr(img, i))
// has alpha index i at every texel of the first 32 bits of index data (fillTexture's alpha32:
// (i | i << 3 | i << 6 | i << 9) repeated at bits 0, 12 and 24, its low 16 bits in the last two
// index bytes as well). "Top left pixel only" has index bits 0..31 = i, 32..47 = 0. The block's
// second half, as the test's struct lays it out: u32 index bits 0..31, u16 index bits 32..47,
// u8 alpha1, u8 alpha2.

struct Dxt5Box {
    const char* title;
    ColorBlock block;
    u8 a1, a2;
    u32 color;     // what a PSP printed for colour, the same for all eight indices
    u8 alpha[8];   // the alpha it printed for index 0..7 (a grey: the byte three times)
};
const Dxt5Box kDxt5[] = {
    {"White 0", {0xFFFF, 0xFFFF, 0x00}, 0x55, 0xFF, 0xf8fcf8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"White 1", {0xFFFF, 0xFFFF, 0x55}, 0x55, 0xFF, 0xf8fcf8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"White 2", {0xFFFF, 0xFFFF, 0xAA}, 0x55, 0xFF, 0xf8fcf8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"White 3", {0xFFFF, 0xFFFF, 0xFF}, 0x55, 0xFF, 0x000000, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First greater 0", {0xFFE3, 0x8410, 0x00}, 0x55, 0xFF, 0x18fcf8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First greater 1", {0xFFE3, 0x8410, 0x55}, 0x55, 0xFF, 0x808080, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First greater 2", {0xFFE3, 0x8410, 0xAA}, 0x55, 0xFF, 0x3ad2d0, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First greater 3", {0xFFE3, 0x8410, 0xFF}, 0x55, 0xFF, 0x5da9a8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First lesser 0", {0x8410, 0xF85F, 0x00}, 0x55, 0xFF, 0x808080, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First lesser 1", {0x8410, 0xF85F, 0x55}, 0x55, 0xFF, 0xf808f8, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First lesser 2", {0x8410, 0xF85F, 0xAA}, 0x55, 0xFF, 0xbc44bc, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"First lesser 3", {0x8410, 0xF85F, 0xFF}, 0x55, 0xFF, 0x000000, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"Color mix 2", {0x7890, 0x1234, 0xAA}, 0x55, 0xFF, 0x8a2155, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"Color mix 3", {0x7890, 0x1234, 0xFF}, 0x55, 0xFF, 0x953232, {0x55, 0xff, 0x77, 0x99, 0xbb, 0xdd, 0x00, 0xff}},
    {"Alpha greater", {0x7890, 0x1234, 0xAA}, 0xFF, 0x00, 0x8a2155, {0xff, 0x00, 0xda, 0xb6, 0x91, 0x6d, 0x48, 0x24}},
    {"Alpha equal", {0x7890, 0x1234, 0xAA}, 0x00, 0xFF, 0x8a2155, {0x00, 0xff, 0x33, 0x66, 0x99, 0xcc, 0x00, 0xff}},
    {"Top left pixel only", {0x7777, 0x1356, 0x00, true}, 0xE1, 0x59, 0xb5c050,
     {0xe1, 0x59, 0xcd, 0xba, 0xa6, 0x93, 0x7f, 0x6c}},
};
constexpr int kAlphaGreater = 14;  // the image main()'s last loop refills

// main()'s last loop: for a2 = 0 .. 255, fillTexture(IMG_ALPHA_GT, 0x7890, 0x1234, 0xAA, 0xFF, a2)
// and testDrawingBox("Alpha %02x"). All 2,048 colour read-backs were 8a2155.
constexpr u32 kAlphaLoopColor = 0x8a2155;
constexpr u8 kAlphaLoopHardware[256][8] = {
#include "tests/conformance/texcolors_dxt5_alpha.inc"
};

void fillDxt5(GuSim& gu, u32 addr, const ColorBlock& c, u8 a1, u8 a2) {
    u8 img[8 * 4 * 16];
    for (u32 i = 0; i < 8; ++i) {
        const u32 alpha12 = i | i << 3 | i << 6 | i << 9;
        const u32 alpha32 = alpha12 | alpha12 << 12 | alpha12 << 24;
        for (int k = 0; k < 4; ++k) {
            u8* p = img + (i * 4 + u32(k)) * 16;
            putColorBlock(p, c);
            writeLE32(p + 8, c.topLeftOnly ? i : alpha32);
            writeLE16(p + 12, c.topLeftOnly ? u16(0) : u16(alpha32));
            p[14] = a1;
            p[15] = a2;
        }
    }
    gu.cpuWrite(addr, img, sizeof(img));
}

TestRun runDxt5(GuSim& gu) {
    TestRun run{"texcolors/dxt5", gu.backend(), {}};
    init(gu);
    for (u32 i = 0; i < std::size(kDxt5); ++i)  // setupTexture()
        fillDxt5(gu, kImages + i * kImageStride, kDxt5[i].block, kDxt5[i].a1, kDxt5[i].a2);
    auto box = [&](u32 addr, const std::string& title, u32 color, const u8 alpha[8]) {
        for (u32 i = 0; i < 8; ++i)
            testDrawingBox(gu, run, GE_TFMT_DXT5, addr + i * 4 * 16, title + " (alpha=" + std::to_string(i) + ")",
                           color, 0x010101u * alpha[i]);
    };
    for (u32 i = 0; i < std::size(kDxt5); ++i)
        box(kImages + i * kImageStride, kDxt5[i].title, kDxt5[i].color, kDxt5[i].alpha);
    const u32 gt = kImages + kAlphaGreater * kImageStride;
    for (u32 a2 = 0; a2 < 0x100; ++a2) {
        fillDxt5(gu, gt, kDxt5[kAlphaGreater].block, 0xFF, u8(a2));
        char title[16];
        std::snprintf(title, sizeof(title), "Alpha %02x", a2);
        box(gt, title, kAlphaLoopColor, kAlphaLoopHardware[a2]);
    }
    return run;
}

CONFORMANCE_TEST(TexColorsDxt1, runDxt1)
CONFORMANCE_TEST(TexColorsDxt3, runDxt3)
CONFORMANCE_TEST(TexColorsDxt5, runDxt5)

}  // namespace
}  // namespace ge::conformance
