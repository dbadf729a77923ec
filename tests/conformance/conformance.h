// SPDX-License-Identifier: MIT
// Shared pieces of the conformance tests (the environment is gu_sim.h): the SDK call
// sequences the pspautotests GPU tests open with, one-pixel draws, and the test macro that runs a
// test program on both backends and holds each to its floor (floors.cpp).
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <iostream>
#include <string>
#include <vector>

#include "tests/conformance/gu_sim.h"

namespace ge::conformance {

// The opening most pspautotests GPU tests share (commands/blend's init(), texfunc/shared.cpp's
// initDisplay()): sceGuDrawBuffer(format, 0, 512) before sceGuDispBuffer (so ZBP is still 0,
// ZBW 512), sceGuDispBuffer(480, 272, ...) (REGION1 0, REGION2 (479, 271): see sdkDispBuffer),
// sceGuDepthBuffer(0x88000, 512), sceGuOffset(2048 - w/2, 2048 - h/2), sceGuViewport(2048,
// 2048, w, h), sceGuDepthRange(65535, 0), sceGuDepthMask(0), sceGuScissor(0, 0, sw, sh) then
// sceGuEnable(GU_SCISSOR_TEST) (SCISSOR1/2), sceGuFrontFace(GU_CW) (CULL 0).
struct FrameSetup {
    u32 viewW = 480, viewH = 272;        // sceGuViewport's width and height (offset centres it)
    u32 scissorW = 480, scissorH = 272;  // sceGuScissor(0, 0, w, h)
    u32 format = GE_FORMAT_8888;         // sceGuDrawBuffer's pixel format
};
void sdkFrameSetup(ListBuilder& b, const FrameSetup& f);
// sceGuDispBuffer(w, h, ...) as the SDK the tests were built with has it: its drawRegion(0, 0, w, h)
// sends REGION1 = 0 and REGION2 = (w - 1, h - 1) (pspsdk's first src/gu/sceGuDispBuffer.c;
// today's pspsdk no longer does, and after sceGuInit the region would be the single pixel 0, 0).
void sdkDispBuffer(ListBuilder& b, u32 w = 480, u32 h = 272);
// sceGuSetMatrix(GU_MODEL / GU_VIEW / GU_PROJECTION, identity).
void setIdentityMatrices(ListBuilder& b);
// sceGuDrawArray(GU_SPRITES, GU_COLOR_8888 | GU_VERTEX_32BITF | GU_TRANSFORM_2D, 2, NULL, v) with
// v = {c, -1, -1, 0}, {c, 1, 1, 0}: a through-mode sprite covering pixel (0, 0) only.
void drawOnePixel(ListBuilder& b, u32 abgr);

// initDisplay() of commands/shared.cpp (cull, fog, light, dither): sdkFrameSetup with the given
// frame, Gouraud shading, texturing off, identity matrices.
void commandsInitDisplay(ListBuilder& b, const FrameSetup& f = {});
// The init() of the clut tests: an 8888 draw buffer at 0 (depth buffer 0, width 512, as
// sceGuDrawBuffer leaves it before sceGuDispBuffer), the display region, the full scissor.
void clutInit(ListBuilder& b);
// A through-mode sprite vertex pair {u16 u, v, x, y, z} from (0, 0, 0, 0, 0) to (u, v, x, y, 0).
std::vector<u8> spriteUv16(u16 u, u16 v, u16 x, u16 y);
// Vertices {float u, v; u32 colour; float x, y, z} (GU_TEXTURE_32BITF | GU_COLOR_8888 |
// GU_VERTEX_32BITF), 24 bytes each; `v` holds u, v, x, y, z per vertex.
std::vector<u8> uvColorPosF(const std::vector<std::array<float, 5>>& v, u32 color);

// One vertex of commands/shared.cpp's Vertices(GU_COLOR_8888 | GU_VERTEX_16BIT | transform), CP():
// colour, then x, y, z as s16 — pixels in through mode, norm16x/norm16y of the pixel (x * 65536 /
// 480 - 32768, 32768 - y * 65536 / 272, wrapped to s16) in transform mode — 12 bytes with the
// padding EndVert() aligns to.
struct ColorPos {
    u32 color;
    int x, y;
    u16 z = 0;
};
std::vector<u8> colorPos16(const std::vector<ColorPos>& v, bool through);
inline u32 colorPos16Type(bool through) { return vt::COL_8888 | vt::POS_16 | (through ? vt::THROUGH : 0u); }

// initDisplay() of the filtering tests (filtering/shared.cpp): 8888 buffer, screen offset
// (2048 - 240, 2048 - 136) sent as raw OFFSETX/Y words, full viewport, depth range 65535-0, the
// scissor the whole display (sceGuScissor(0, 0, 8, 8) sends nothing while the scissor test is off;
// sceGuDisable(GU_SCISSOR_TEST) then sets (0, 0)-(479, 271)), texturing on, blending off, identity
// matrices, an 8888 texture mode and REPLACE/RGBA.
void filteringInitDisplay(ListBuilder& b);

// A float's bits, as a vertex array holds it.
u32 floatBits(float f);

// The checkpoints a backend must pass at least (floors.cpp; they only rise).
int floorOf(const std::string& test, const std::string& backend);

class Conformance : public ::testing::TestWithParam<std::string> {};

inline std::string backendName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

// Runs `fn(GuSim&) -> TestRun` on the parameter's backend, prints the summary line and the failing
// checkpoints, and fails when fewer than the floor pass.
#define CONFORMANCE_TEST(Name, fn)                                                                   \
    TEST_P(Conformance, Name) {                                                                      \
        GuSim gu;                                                                                    \
        std::string err;                                                                             \
        if (!gu.create(GetParam(), err)) GTEST_SKIP() << "backend " << GetParam() << ": " << err;   \
        const TestRun run = fn(gu);                                                                  \
        std::cout << run.report();                                                                   \
        RecordProperty("checkpoints_passed", run.passed());                                          \
        RecordProperty("checkpoints_total", run.total());                                            \
        EXPECT_GE(run.passed(), floorOf(run.test, run.backend)) << run.report();                     \
    }

}  // namespace ge::conformance
