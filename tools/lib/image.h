// SPDX-License-Identifier: MIT
// Host image I/O and the accuracy measure used by `ge2gl compare` (PNG through libpng; other
// file formats through OpenImageIO, loaded on first use).
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"

namespace ge::tools {

struct Image {
    int width = 0, height = 0;
    std::vector<u32> rgba;  // R in bits 7..0, A in 31..24
    u32 at(int x, int y) const { return rgba[size_t(y) * width + x]; }
};

// The visible frame (width x height from addr, `stride` pixels per row, PSP format 0–3) converted
// to RGBA8888 with alpha forced to 255. Memory outside VRAM/RAM reads as black.
Image readFrame(const Memory& mem, u32 addr, u32 stride, u32 format, int width = 480, int height = 272);

// Each n×n block of img averaged (per channel, rounded): how `compare` measures a frame rendered
// at render scale n against 480x272 references.
Image boxDownsample(const Image& img, int n);

bool writePng(const std::string& path, const Image& img, std::string& err);
bool readImage(const std::string& path, Image& img, std::string& err);

// PPSSPP's frametest measure: over the top-left w x h pixels, RGB only, the sum of squared 8-bit
// channel differences divided by w*h*3. Returns -1 when either image is smaller than w x h.
double mseRGB(const Image& a, const Image& b, int w = 480, int h = 272);
double psnrFromMse(double mse);  // 10*log10(255^2/MSE), +inf for 0
// A picture of the differences: differing pixels in magenta over a dimmed grey copy of `a`.
Image diffImage(const Image& a, const Image& b, int w = 480, int h = 272);
// A heat map of the differences: a pixel whose RGB matches is a dim grey copy of `a`; one that
// differs takes the colour of its largest channel difference d (1..255) on a logarithmic ramp,
// t = log2(1 + d) / 8: blue (d = 1) through cyan (d ~ 6), green (~ 20), yellow (~ 63) to red (255).
// heatColour(d) is that ramp (the HTML report draws its legend from it).
u32 heatColour(int d);
Image heatImage(const Image& a, const Image& b, int w = 480, int h = 272);

}  // namespace ge::tools
