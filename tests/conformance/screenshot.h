// SPDX-License-Identifier: MIT
// Whole-frame checkpoints for the pspautotests GPU tests whose hardware result is a screenshot
// (`.expected.bmp`: the display buffer as a PSP showed it, taken by the test's
// emulatorEmitScreenshot(), 512x272 of which PPSSPP's headless runner compares 480x272 exactly on
// RGB, alpha ignored: headless/Compare.cpp ComparePixel, CompareScreenshot with --max-mse 0).
//
// The PSP's picture is written as facts, not as an image: a background colour and spans of one
// colour over consecutive rows, each edge moving by a whole number of pixels per row (0 for the
// sides of a rectangle, ±1 for a 45° triangle edge), generated from the capture and checked to
// reproduce every one of its 480x272 pixels.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "tests/conformance/gu_sim.h"

namespace ge::conformance {

// Rows y0..y1-1; on row y the pixels [x0 + dx0·(y − y0), x1 + dx1·(y − y0)) are `rgb` (0xRRGGBB,
// as the capture holds it).
struct ScreenSpan {
    int y0, y1, x0, x1, dx0, dx1;
    u32 rgb;
};

// The PSP's row y (480 pixels, 0xRRGGBB): `background`, then every span covering y painted over it.
std::vector<u32> screenRow(u32 background, const std::vector<ScreenSpan>& spans, int y);

// What the display shows of the frame buffer at VRAM offset `fb` (stride 512, pixel format
// `format` GE_FORMAT_*), 480x272 as 0xRRGGBB: 16-bit formats expanded as the display and the
// capture expand them (5 bits: c << 3 | c >> 2, 6 bits: c << 2 | c >> 4, 4 bits: c << 4 | c).
std::vector<u32> displayedFrame(GuSim& gu, u32 fb, u32 format);

// One checkpoint per row: the number of the row's 480 pixels that differ from the PSP's (0 on
// hardware). A failing row's name gives the first differing pixel, ge2gl's and the PSP's colour.
void compareScreen(GuSim& gu, TestRun& run, u32 fb, u32 format, u32 background, const std::vector<ScreenSpan>& spans);
// The same against a picture given row by row (`row(y)`: 480 pixels, 0xRRGGBB), for pictures that
// spans alone do not describe compactly (a dither pattern).
void compareScreen(GuSim& gu, TestRun& run, u32 fb, u32 format, const std::function<std::vector<u32>(int)>& row);

// A test program's static arrays, laid out one after another from `base`, 16-byte aligned, as
// its linker placed them; written with CPU copies.
class StaticData {
public:
    StaticData(GuSim& gu, u32 base) : gu_(gu), next_(base) {}
    u32 put(const std::vector<u8>& bytes) {
        const u32 at = next_;
        gu_.cpuWrite(at, bytes.data(), u32(bytes.size()));
        next_ = (at + u32(bytes.size()) + 15) & ~15u;
        return at;
    }

private:
    GuSim& gu_;
    u32 next_;
};

}  // namespace ge::conformance
