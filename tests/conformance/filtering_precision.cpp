// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/filtering/precisionlinear2d, precisionlinear3d, precisionnearest2d and
// precisionnearest3d, re-created (gu_sim.h, conformance.h). A 2x2 8888 texture (white,
// black / red, green; buffer width 4, clamped) is magnified onto a sprite from (0, 0) to (w, h)
// pixels — 256x256 in each of the four corner orders, 2x2, with UVs shifted by a texel or half a
// texel — and the sprite is moved by 1/16-pixel steps in X and in Y; in through mode (2d: the
// vertices carry the sub-pixel offset) or in transform mode set up to match it (3d: texture scale
// 0.5, screen offset (2048, 2048), viewport 2 x -2, Z scale 1, the sub-pixel step in OFFSETX/Y).
// The whole buffer is filled with 0x44444444 before each draw; after it, pixel (0, 0) is read, and
// the first pixel down column 0 and along row 0 that differs from it (position and colour). The
// issue lists these four as tests PPSSPP fails: the texel centre and the weights' precision.
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// On a PSP: COLOR (pixel 0, 0), then "left" (the first row y > 0 of column 0 whose pixel differs,
// -1 when none, and that pixel) and "top" (the same along row 0), for each draw in order.
struct ReadBack {
    u32 color;
    int left;
    u32 leftColor;
    int top;
    u32 topColor;
};
constexpr ReadBack kLinear2d[74] = {
    {0x44444444, -1, 0x00000000, -1, 0x00000000}, {0x44ffffff, 72, 0x44efefff, 72, 0x44efefef}, {0x4400ff00, 64, 0x4400ef00, 64, 0x4400ef0f},
    {0x440000ff, 72, 0x44000fef, 64, 0x440f0fff}, {0x44000000, 64, 0x440f0f0f, 72, 0x44000f00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x443f7f7f, 8, 0x44377f7f, 8, 0x44377f6f}, {0x44ffffff, 8, 0x44efefff, 8, 0x44efefef}, {0x44ffffff, 136, 0x44efefff, 136, 0x44efefef},
    {0x443f7f7f, 1, 0x44007f7f, 1, 0x44007f00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44efefef, 1, 0x44000fef, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44dfdfdf, 1, 0x44001fdf, 1, 0x44000000},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44cfcfcf, 1, 0x44002fcf, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44bfbfbf, 1, 0x44003fbf, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44afafaf, 1, 0x44004faf, 1, 0x44000000},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x449f9f9f, 1, 0x44005f9f, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x448f8f8f, 1, 0x44006f8f, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x447f7f7f, 1, 0x44007f7f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x446f6f6f, 1, 0x44008f6f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x445f5f5f, 1, 0x44009f5f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x444f4f4f, 1, 0x4400af4f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x443f3f3f, 1, 0x4400bf3f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x442f2f2f, 1, 0x4400cf2f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x441f1f1f, 1, 0x4400df1f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x440f0f0f, 1, 0x4400ef0f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44efefff, 1, 0x440000ff, 1, 0x44000f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44dfdfff, 1, 0x440000ff, 1, 0x44001f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44cfcfff, 1, 0x440000ff, 1, 0x44002f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44bfbfff, 1, 0x440000ff, 1, 0x44003f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44afafff, 1, 0x440000ff, 1, 0x44004f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x449f9fff, 1, 0x440000ff, 1, 0x44005f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x448f8fff, 1, 0x440000ff, 1, 0x44006f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x447f7fff, 1, 0x44444444, 1, 0x44007f00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x446f6fff, 1, 0x44444444, 1, 0x44008f00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x445f5fff, 1, 0x44444444, 1, 0x44009f00},
    {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x444f4fff, 1, 0x44444444, 1, 0x4400af00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x443f3fff, 1, 0x44444444, 1, 0x4400bf00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x442f2fff, 1, 0x44444444, 1, 0x4400cf00},
    {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x441f1fff, 1, 0x44444444, 1, 0x4400df00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x440f0fff, 1, 0x44444444, 1, 0x4400ef00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
};
constexpr ReadBack kLinear3d[74] = {
    {0x44444444, -1, 0x44444444, -1, 0x44444444}, {0x44ffffff, 72, 0x44efefff, 72, 0x44efefef}, {0x4400ff00, 64, 0x4400ef00, 64, 0x4400ef0f},
    {0x440000ff, 72, 0x44000fef, 64, 0x440f0fff}, {0x44000000, 64, 0x440f0f0f, 72, 0x44000f00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x443f7f7f, 8, 0x44377f7f, 8, 0x44377f6f}, {0x44ffffff, 8, 0x44efefff, 8, 0x44efefef}, {0x44ffffff, 136, 0x44efefff, 136, 0x44efefef},
    {0x443f7f7f, 1, 0x44007f7f, 1, 0x44007f00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44efefef, 1, 0x44000fef, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44dfdfdf, 1, 0x44001fdf, 1, 0x44000000},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44cfcfcf, 1, 0x44002fcf, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44bfbfbf, 1, 0x44003fbf, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44afafaf, 1, 0x44004faf, 1, 0x44000000},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x449f9f9f, 1, 0x44005f9f, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x448f8f8f, 1, 0x44006f8f, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x447f7f7f, 1, 0x44007f7f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x446f6f6f, 1, 0x44008f6f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x445f5f5f, 1, 0x44009f5f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x444f4f4f, 1, 0x4400af4f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x443f3f3f, 1, 0x4400bf3f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x442f2f2f, 1, 0x4400cf2f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x441f1f1f, 1, 0x4400df1f, 1, 0x44444444},
    {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef}, {0x440f0f0f, 1, 0x4400ef0f, 1, 0x44444444}, {0x44ffffff, 144, 0x44efefff, 143, 0x44efefef},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44efefff, 1, 0x440000ff, 1, 0x44000f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44dfdfff, 1, 0x440000ff, 1, 0x44001f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x44cfcfff, 1, 0x440000ff, 1, 0x44002f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44bfbfff, 1, 0x440000ff, 1, 0x44003f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x44afafff, 1, 0x440000ff, 1, 0x44004f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef},
    {0x449f9fff, 1, 0x440000ff, 1, 0x44005f00}, {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x448f8fff, 1, 0x440000ff, 1, 0x44006f00},
    {0x44ffffff, 144, 0x44efefff, 144, 0x44efefef}, {0x447f7fff, 1, 0x44444444, 1, 0x44007f00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x446f6fff, 1, 0x44444444, 1, 0x44008f00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x445f5fff, 1, 0x44444444, 1, 0x44009f00},
    {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x444f4fff, 1, 0x44444444, 1, 0x4400af00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x443f3fff, 1, 0x44444444, 1, 0x4400bf00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x442f2fff, 1, 0x44444444, 1, 0x4400cf00},
    {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef}, {0x441f1fff, 1, 0x44444444, 1, 0x4400df00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
    {0x440f0fff, 1, 0x44444444, 1, 0x4400ef00}, {0x44ffffff, 143, 0x44efefff, 144, 0x44efefef},
};
constexpr ReadBack kNearest2d[74] = {
    {0x44444444, -1, 0x00000000, -1, 0x00000000}, {0x44ffffff, 128, 0x440000ff, 128, 0x44000000}, {0x4400ff00, 128, 0x44000000, 128, 0x440000ff},
    {0x440000ff, 128, 0x4400ff00, 128, 0x44ffffff}, {0x44000000, 128, 0x44ffffff, 128, 0x4400ff00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x4400ff00, 256, 0x44444444, 256, 0x44444444}, {0x44ffffff, 64, 0x440000ff, 64, 0x44000000}, {0x44ffffff, 192, 0x440000ff, 192, 0x44000000},
    {0x4400ff00, 2, 0x44444444, 2, 0x44444444}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00},
    {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00},
    {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
};
constexpr ReadBack kNearest3d[74] = {
    {0x44444444, -1, 0x44444444, -1, 0x44444444}, {0x44ffffff, 128, 0x440000ff, 128, 0x44000000}, {0x4400ff00, 128, 0x44000000, 128, 0x440000ff},
    {0x440000ff, 128, 0x4400ff00, 128, 0x44ffffff}, {0x44000000, 128, 0x44ffffff, 128, 0x4400ff00}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x4400ff00, 256, 0x44444444, 256, 0x44444444}, {0x44ffffff, 64, 0x440000ff, 64, 0x44000000}, {0x44ffffff, 192, 0x440000ff, 192, 0x44000000},
    {0x4400ff00, 2, 0x44444444, 2, 0x44444444}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444},
    {0x44ffffff, 256, 0x440000ff, 255, 0x44000000}, {0x44000000, 1, 0x4400ff00, 1, 0x44444444}, {0x44ffffff, 256, 0x440000ff, 255, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000},
    {0x44ffffff, 1, 0x440000ff, 1, 0x44000000}, {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x44ffffff, 1, 0x440000ff, 1, 0x44000000},
    {0x44ffffff, 256, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00},
    {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00},
    {0x44ffffff, 255, 0x440000ff, 256, 0x44000000}, {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
    {0x440000ff, 1, 0x44444444, 1, 0x4400ff00}, {0x44ffffff, 255, 0x440000ff, 256, 0x44000000},
};

constexpr u32 kTexture = 0x08400000;
constexpr u32 kTexels[16] = {0xFFFFFFFF, 0xFF000000, 0xFFFFFFFF, 0xFFFFFFFF, 0xFF0000FF, 0xFF00FF00, 0xFFFFFFFF, 0xFFFFFFFF,
                             0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF};

class PrecisionTest {
public:
    PrecisionTest(GuSim& gu, const char* test, bool linear, bool transform, const ReadBack* hw)
        : gu_(gu), linear_(linear), transform_(transform), hw_(hw), run_{test, gu.backend(), {}} {}

    TestRun run() {
        gu_.init();
        filteringInitDisplay(gu_.start());
        gu_.finishSync();
        clear();
        read("Initial");
        gu_.cpuWrite(kTexture, kTexels, sizeof kTexels);
        ListBuilder& b = gu_.start();
        b.texFilter(linear_ ? 1 : 0, linear_ ? 1 : 0);
        b.setTexture(0, kTexture, 2, 2, 4);
        b.texWrap(true, true);
        if (transform_) {  // "simply scale the UVs and pos to match through"
            b.texScale(0.5f, 0.5f);
            b.offset(2048, 2048);
            b.viewport(2048, 2048, 2, -2);
            b.cmdf(GE_CMD_SZ, 1.0f);
            b.cmdf(GE_CMD_TZ, 0.0f);
        }
        b.texFlush();
        b.texSync();
        gu_.finishSync();

        magnify("TL -> BR", 256, 256, 0, 0);
        magnify("BR -> TL", -256, -256, 0, 0);
        magnify("TR -> BL", -256, 256, 0, 0);
        magnify("BL -> TR", 256, -256, 0, 0);
        magnify("TL -> BR (small)", 2, 2, 0, 0);
        magnify("One texel", 256, 256, 1, 1);
        magnify("Half texel", 256, 256, 0.5f, 0.5f);
        magnify("Negative half texel", 256, 256, -0.5f, -0.5f);
        magnify("Half texel (small)", 2, 2, 0.5f, 0.5f);
        for (int axis = 0; axis < 2; ++axis)
            for (int i = 0; i < 16; ++i) {
                const char* name = axis == 0 ? "X" : "Y";
                if (transform_) {
                    ListBuilder& l = gu_.start();
                    l.cmd(GE_CMD_OFFSETX, 2048 * 16 + (axis == 0 ? i : 0));
                    l.cmd(GE_CMD_OFFSETY, 2048 * 16 + (axis == 1 ? i : 0));
                    gu_.finishSync();
                }
                const float sub = transform_ ? 0.0f : -float(i) / 16.0f;
                magnify(std::string("Pos ") + name + " offset " + std::to_string(i), 2, 2, 0, 0, axis == 0 ? sub : 0,
                        axis == 1 ? sub : 0);
                magnify(std::string("Pos ") + name + " offset (256x) " + std::to_string(i), 512, 512, 0, 0,
                        axis == 0 ? sub : 0, axis == 1 ? sub : 0);
            }
        return run_;
    }

private:
    void clear() { gu_.fillVram32(0, 0x44444444, 512 * 272); }

    // displayBuffer(): the read-backs, then the buffer reset.
    void read(const std::string& name) {
        const ReadBack& want = hw_[n_++];
        const u32 tl = gu_.readVram32(0);
        ReadBack got{tl, -1, 0, -1, 0};
        for (int y = 1; y < 272 && got.left < 0; ++y) {
            const u32 c = gu_.readVram32(u32(y) * 512 * 4);
            if (c != tl) got.left = y, got.leftColor = c;
        }
        for (int x = 1; x < 480 && got.top < 0; ++x) {
            const u32 c = gu_.readVram32(u32(x) * 4);
            if (c != tl) got.top = x, got.topColor = c;
        }
        run_.checkpoints.push_back({name + ": COLOR", want.color, got.color});
        run_.checkpoints.push_back({name + ": left", u32(want.left), u32(got.left)});
        // The colour found is only a read-back where a pixel was found (the 2d tests print an
        // uninitialised variable otherwise).
        if (want.left >= 0) run_.checkpoints.push_back({name + ": left colour", want.leftColor, got.leftColor});
        run_.checkpoints.push_back({name + ": top", u32(want.top), u32(got.top)});
        if (want.top >= 0) run_.checkpoints.push_back({name + ": top colour", want.topColor, got.topColor});
        clear();
    }

    // testTexMagnify(title, w, h, xoff, yoff[, subx, suby]): UVs (xoff, yoff)-(2 + xoff, 2 + yoff),
    // positions from (subx, suby) to (w + subx, h + suby), a negative size swapping the corners.
    void magnify(const std::string& name, float w, float h, float xoff, float yoff, float subx = 0, float suby = 0) {
        float p0[2] = {subx, suby}, p1[2] = {w + subx, h + suby};
        if (w < 0) p0[0] = -w + subx, p1[0] = subx;
        if (h < 0) p0[1] = -h + suby, p1[1] = suby;
        const std::vector<u8> data =
            uvColorPosF({{xoff, yoff, p0[0], p0[1], 0.0f}, {2.0f + xoff, 2.0f + yoff, p1[0], p1[1], 0.0f}}, 0xFFFFFFFF);
        ListBuilder& l = gu_.start();
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_F | vt::COL_8888 | vt::POS_F | (transform_ ? 0u : vt::THROUGH), 2,
                        nullptr, data.data());
        gu_.finishSync();
        read(name);
    }

    GuSim& gu_;
    bool linear_, transform_;
    const ReadBack* hw_;
    size_t n_ = 0;
    TestRun run_;
};

TestRun runLinear2d(GuSim& gu) { return PrecisionTest(gu, "filtering/precisionlinear2d", true, false, kLinear2d).run(); }
TestRun runLinear3d(GuSim& gu) { return PrecisionTest(gu, "filtering/precisionlinear3d", true, true, kLinear3d).run(); }
TestRun runNearest2d(GuSim& gu) { return PrecisionTest(gu, "filtering/precisionnearest2d", false, false, kNearest2d).run(); }
TestRun runNearest3d(GuSim& gu) { return PrecisionTest(gu, "filtering/precisionnearest3d", false, true, kNearest3d).run(); }

CONFORMANCE_TEST(FilteringPrecisionLinear2d, runLinear2d)
CONFORMANCE_TEST(FilteringPrecisionLinear3d, runLinear3d)
CONFORMANCE_TEST(FilteringPrecisionNearest2d, runNearest2d)
CONFORMANCE_TEST(FilteringPrecisionNearest3d, runNearest3d)

}  // namespace
}  // namespace ge::conformance
