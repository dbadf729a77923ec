// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/blend and blend565, re-created (gu_sim.h): every
// blend equation and factor (blend565 also factors 11-15, which act as FIX), the doubled alpha
// factors' saturation, FIX colours, on an 8888 and a 565 frame buffer. Each checkpoint fills VRAM
// with `prev`, draws a one-pixel through-mode sprite of colour `c` with the blend and a stencil
// REPLACE of 0xAA (so the 8888 alpha byte reads AA; 565 has no stencil), and reads pixel 0. The
// expected values are those the tests read back on a PSP (their .expected files).
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

struct BlendCase {
    const char* name;
    u32 prev, color;
    u32 op, src, dst, fixA, fixB;
    u32 hardware;
};

// name, VRAM before, sprite colour (ABGR), equation, source factor, destination factor, FIXA,
// FIXB (sceGuBlendFunc's arguments), value read back on hardware.
constexpr BlendCase kCases[] = {
    {"One + Zero", 0x44444444, 0xEEDDCCBB, 0, 10, 10, 0xFFFFFFFF, 0x00000000, 0xaaddccbb},
    {"Zero + One", 0x44444444, 0xEEDDCCBB, 0, 10, 10, 0x00000000, 0xFFFFFFFF, 0xaa444444},
    {"Alpha + Inverse alpha", 0x44444444, 0xEEDDCCBB, 0, 2, 3, 0x80808080, 0x80808080, 0xaad2c2b2},
    {"Double source alpha + Zero 0x80808080", 0x40404040, 0x80808080, 0, 6, 10, 0x00000000, 0x00000000, 0xaa808080},
    {"Double source alpha + Zero 0x80909090", 0x40404040, 0x80909090, 0, 6, 10, 0x00000000, 0x00000000, 0xaa909090},
    {"Double source alpha + Zero 0x90808080", 0x40404040, 0x90808080, 0, 6, 10, 0x00000000, 0x00000000, 0xaa909090},
    {"Double source alpha + Zero 0xFF707070", 0x40404040, 0xFF707070, 0, 6, 10, 0x00000000, 0x00000000, 0xaae0e0e0},
    {"Double source alpha + Zero 0xFF909090", 0x40404040, 0xFF909090, 0, 6, 10, 0x00000000, 0x00000000, 0xaaffffff},
    {"Double source alpha + Zero 0x7FFFFFFF", 0x40404040, 0x7FFFFFFF, 0, 6, 10, 0x00000000, 0x00000000, 0xaafefefe},
    {"Double source alpha + Zero 0xFF7F7F7F", 0x40404040, 0xFF7F7F7F, 0, 6, 10, 0x00000000, 0x00000000, 0xaafefefe},
    {"Inverse double source alpha + Zero 0x80808080", 0x40404040, 0x80808080, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double source alpha + Zero 0x80909090", 0x40404040, 0x80909090, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double source alpha + Zero 0x90808080", 0x40404040, 0x90808080, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double source alpha + Zero 0x40808080", 0x40404040, 0x40808080, 0, 7, 10, 0x00000000, 0x00000000, 0xaa3f3f3f},
    {"Inverse double source alpha + Zero 0xFF1188FF", 0x40404040, 0xFF1188FF, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double source alpha + Zero 0x7FFFFFFF", 0x40404040, 0x7FFFFFFF, 0, 7, 10, 0x00000000, 0x00000000, 0xaa010101},
    {"Inverse double source alpha + Zero 0xFF7F7F7F", 0x40404040, 0xFF7F7F7F, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Double dest alpha + Zero 0x40 + 0x80808080", 0x40404040, 0x80808080, 0, 8, 10, 0x00000000, 0x00000000, 0xaa404040},
    {"Double dest alpha + Zero 0x90 + 0x80808080", 0x90404040, 0x80808080, 0, 8, 10, 0x00000000, 0x00000000, 0xaa909090},
    {"Double dest alpha + Zero 0x40 + 0x80909090", 0x40404040, 0x80909090, 0, 8, 10, 0x00000000, 0x00000000, 0xaa484848},
    {"Double dest alpha + Zero 0xFF + 0x70707070", 0xFF404040, 0x70707070, 0, 8, 10, 0x00000000, 0x00000000, 0xaae0e0e0},
    {"Double dest alpha + Zero 0xFF + 0x90909090", 0xFF404040, 0x90909090, 0, 8, 10, 0x00000000, 0x00000000, 0xaaffffff},
    {"Double dest alpha + Zero 0x7F + 0xFFFFFFFF", 0x7F404040, 0xFFFFFFFF, 0, 8, 10, 0x00000000, 0x00000000, 0xaafefefe},
    {"Double dest alpha + Zero 0xFF + 0x7F7F7F7F", 0xFF404040, 0x7F7F7F7F, 0, 8, 10, 0x00000000, 0x00000000, 0xaafefefe},
    {"Inverse double dest alpha + Zero 0x40 + 0x80808080", 0x40404040, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0xaa3f3f3f},
    {"Inverse double dest alpha + Zero 0x90 + 0x80909090", 0x90404040, 0x80909090, 0, 9, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double dest alpha + Zero 0x40 + 0x80808080", 0x40404040, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0xaa3f3f3f},
    {"Inverse double dest alpha + Zero 0xFF + 0x80808080", 0xFF404040, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double dest alpha + Zero 0xFF + 0xFF1188FF", 0xFF404040, 0xFF1188FF, 0, 9, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Inverse double dest alpha + Zero 0x7F + 0xFFFFFFFF", 0x7F404040, 0xFFFFFFFF, 0, 9, 10, 0x00000000, 0x00000000, 0xaa010101},
    {"Inverse double dest alpha + Zero 0xFF + 0x7F7F7F7F", 0xFF404040, 0x7F7F7F7F, 0, 9, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Dest color + Zero", 0x50404040, 0x90808080, 0, 0, 10, 0x00000000, 0x00000000, 0xaa202020},
    {"Inverse dest color + Zero", 0x50404040, 0x90808080, 0, 1, 10, 0x00000000, 0x00000000, 0xaa606060},
    {"Src alpha + Zero", 0x50404040, 0x90808080, 0, 2, 10, 0x00000000, 0x00000000, 0xaa484848},
    {"Inverse src alpha + Zero", 0x50404040, 0x90808080, 0, 3, 10, 0x00000000, 0x00000000, 0xaa373737},
    {"Dest alpha + Zero", 0x50404040, 0x90808080, 0, 4, 10, 0x00000000, 0x00000000, 0xaa282828},
    {"Inverse dest alpha + Zero", 0x50404040, 0x90808080, 0, 5, 10, 0x00000000, 0x00000000, 0xaa585858},
    {"Double src alpha + Zero", 0x50404040, 0x90808080, 0, 6, 10, 0x00000000, 0x00000000, 0xaa909090},
    {"Inverse double src alpha + Zero", 0x50404040, 0x90808080, 0, 7, 10, 0x00000000, 0x00000000, 0xaa000000},
    {"Double dest alpha + Zero", 0x50404040, 0x90808080, 0, 8, 10, 0x00000000, 0x00000000, 0xaa505050},
    {"Inverse double dest alpha + Zero", 0x50404040, 0x90808080, 0, 9, 10, 0x00000000, 0x00000000, 0xaa2f2f2f},
    {"Fix + Zero", 0x50404040, 0x90808080, 0, 10, 10, 0x90808080, 0x00000000, 0xaa404040},
    {"Zero + Src color", 0x50404040, 0x90808080, 0, 10, 0, 0x00000000, 0x00000000, 0xaa202020},
    {"Zero + Inverse dest color", 0x50404040, 0x90808080, 0, 10, 1, 0x00000000, 0x00000000, 0xaa202020},
    {"Zero + Src alpha", 0x50404040, 0x90808080, 0, 10, 2, 0x00000000, 0x00000000, 0xaa242424},
    {"Zero + Inverse src alpha", 0x50404040, 0x90808080, 0, 10, 3, 0x00000000, 0x00000000, 0xaa1c1c1c},
    {"Zero + Dest alpha", 0x50404040, 0x90808080, 0, 10, 4, 0x00000000, 0x00000000, 0xaa141414},
    {"Zero + Inverse dest alpha", 0x50404040, 0x90808080, 0, 10, 5, 0x00000000, 0x00000000, 0xaa2c2c2c},
    {"Zero + Double src alpha", 0x50404040, 0x90808080, 0, 10, 6, 0x00000000, 0x00000000, 0xaa484848},
    {"Zero + Inverse double src alpha", 0x50404040, 0x90808080, 0, 10, 7, 0x00000000, 0x00000000, 0xaa000000},
    {"Zero + Double dest alpha", 0x50404040, 0x90808080, 0, 10, 8, 0x00000000, 0x00000000, 0xaa282828},
    {"Zero + Inverse double dest alpha", 0x50404040, 0x90808080, 0, 10, 9, 0x00000000, 0x00000000, 0xaa181818},
    {"F0 + 0F", 0xFFFFFFFF, 0xFFFFFFFF, 0, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0xaaffffff},
    {"0F + F0", 0xFFFFFFFF, 0xFFFFFFFF, 0, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0xaaffffff},
    {"F0 - 0F", 0xFFFFFFFF, 0xFFFFFFFF, 1, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0xaae1e1e1},
    {"0F - F0", 0xFFFFFFFF, 0xFFFFFFFF, 1, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0xaa000000},
    {"Reverse F0 - 0F", 0xFFFFFFFF, 0xFFFFFFFF, 2, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0xaa000000},
    {"Reverse 0F - F0", 0xFFFFFFFF, 0xFFFFFFFF, 2, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0xaae1e1e1},
    {"Min 0F, F0", 0xF0F0F0F0, 0x0F0F0F0F, 3, 10, 10, 0x80808080, 0x80808080, 0xaa0f0f0f},
    {"Min F0, 0F", 0x0F0F0F0F, 0xF0F0F0F0, 3, 10, 10, 0x80808080, 0x80808080, 0xaa0f0f0f},
    {"Max 0F, F0", 0xF0F0F0F0, 0x0F0F0F0F, 4, 10, 10, 0x80808080, 0x80808080, 0xaaf0f0f0},
    {"Max F0, 0F", 0x0F0F0F0F, 0xF0F0F0F0, 4, 10, 10, 0x80808080, 0x80808080, 0xaaf0f0f0},
    {"Abs 0F - F0", 0xF0F0F0F0, 0x0F0F0F0F, 5, 10, 10, 0x80808080, 0x80808080, 0xaae1e1e1},
    {"Abs F0 - 0F", 0x0F0F0F0F, 0xF0F0F0F0, 5, 10, 10, 0x80808080, 0x80808080, 0xaae1e1e1},
};

// blend565.cpp: the same program on a 565 frame buffer, VRAM filled and read as 16-bit words.
constexpr BlendCase kCases565[] = {
    {"One + Zero", 0x4444, 0xEEDDCCBB, 0, 10, 10, 0xFFFFFFFF, 0x00000000, 0xde77},
    {"Zero + One", 0x4444, 0xEEDDCCBB, 0, 10, 10, 0x00000000, 0xFFFFFFFF, 0x4444},
    {"Alpha + Inverse alpha", 0x4444, 0xEEDDCCBB, 0, 2, 3, 0x80808080, 0x80808080, 0xd636},
    {"Double source alpha + Zero 0x80808080", 0x4444, 0x80808080, 0, 6, 10, 0x00000000, 0x00000000, 0x8410},
    {"Double source alpha + Zero 0x80909090", 0x4444, 0x80909090, 0, 6, 10, 0x00000000, 0x00000000, 0x9492},
    {"Double source alpha + Zero 0x90808080", 0x4444, 0x90808080, 0, 6, 10, 0x00000000, 0x00000000, 0x9492},
    {"Double source alpha + Zero 0xFF707070", 0x4444, 0xFF707070, 0, 6, 10, 0x00000000, 0x00000000, 0xe71c},
    {"Double source alpha + Zero 0xFF909090", 0x4444, 0xFF909090, 0, 6, 10, 0x00000000, 0x00000000, 0xffff},
    {"Double source alpha + Zero 0x7FFFFFFF", 0x4444, 0x7FFFFFFF, 0, 6, 10, 0x00000000, 0x00000000, 0xffff},
    {"Double source alpha + Zero 0xFF7F7F7F", 0x4444, 0xFF7F7F7F, 0, 6, 10, 0x00000000, 0x00000000, 0xffff},
    {"Inverse double source alpha + Zero 0x80808080", 0x4444, 0x80808080, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double source alpha + Zero 0x80909090", 0x4444, 0x80909090, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double source alpha + Zero 0x90808080", 0x4444, 0x90808080, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double source alpha + Zero 0x40808080", 0x4444, 0x40808080, 0, 7, 10, 0x00000000, 0x00000000, 0x39e7},
    {"Inverse double source alpha + Zero 0xFF1188FF", 0x4444, 0xFF1188FF, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double source alpha + Zero 0x7FFFFFFF", 0x4444, 0x7FFFFFFF, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double source alpha + Zero 0xFF7F7F7F", 0x4444, 0xFF7F7F7F, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x80808080", 0x4444, 0x80808080, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x80808080", 0x9444, 0x80808080, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x80909090", 0x4444, 0x80909090, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x70707070", 0xF444, 0x70707070, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x90909090", 0xF444, 0x90909090, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0xFFFFFFFF", 0x7444, 0xFFFFFFFF, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero 0x7F7F7F7F", 0xF444, 0x7F7F7F7F, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double dest alpha + Zero 0x80808080", 0x4444, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0x8410},
    {"Inverse double dest alpha + Zero 0x80909090", 0x9444, 0x80909090, 0, 9, 10, 0x00000000, 0x00000000, 0x9492},
    {"Inverse double dest alpha + Zero 0x80808080", 0x4444, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0x8410},
    {"Inverse double dest alpha + Zero 0x80808080", 0xF444, 0x80808080, 0, 9, 10, 0x00000000, 0x00000000, 0x8410},
    {"Inverse double dest alpha + Zero 0xFF1188FF", 0xF444, 0xFF1188FF, 0, 9, 10, 0x00000000, 0x00000000, 0x145f},
    {"Inverse double dest alpha + Zero 0xFFFFFFFF", 0x7444, 0xFFFFFFFF, 0, 9, 10, 0x00000000, 0x00000000, 0xffff},
    {"Inverse double dest alpha + Zero 0x7F7F7F7F", 0xF444, 0x7F7F7F7F, 0, 9, 10, 0x00000000, 0x00000000, 0x7bef},
    {"Dest color + Zero", 0x5444, 0x90808080, 0, 0, 10, 0x00000000, 0x00000000, 0x2a22},
    {"Inverse dest color + Zero", 0x5444, 0x90808080, 0, 1, 10, 0x00000000, 0x00000000, 0x51cd},
    {"Src alpha + Zero", 0x5444, 0x90808080, 0, 2, 10, 0x00000000, 0x00000000, 0x4a49},
    {"Inverse src alpha + Zero", 0x5444, 0x90808080, 0, 3, 10, 0x00000000, 0x00000000, 0x31a6},
    {"Dest alpha + Zero", 0x5444, 0x90808080, 0, 4, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse dest alpha + Zero", 0x5444, 0x90808080, 0, 5, 10, 0x00000000, 0x00000000, 0x8410},
    {"Double src alpha + Zero", 0x5444, 0x90808080, 0, 6, 10, 0x00000000, 0x00000000, 0x9492},
    {"Inverse double src alpha + Zero", 0x5444, 0x90808080, 0, 7, 10, 0x00000000, 0x00000000, 0x0000},
    {"Double dest alpha + Zero", 0x5444, 0x90808080, 0, 8, 10, 0x00000000, 0x00000000, 0x0000},
    {"Inverse double dest alpha + Zero", 0x5444, 0x90808080, 0, 9, 10, 0x00000000, 0x00000000, 0x8410},
    {"Fix + Zero", 0x5444, 0x90808080, 0, 10, 10, 0x90808080, 0x00000000, 0x4208},
    {"Zero + Src color", 0x5444, 0x90808080, 0, 10, 0, 0x00000000, 0x00000000, 0x2a22},
    {"Zero + Inverse dest color", 0x5440, 0x90808080, 0, 10, 1, 0x00000000, 0x00000000, 0x2a20},
    {"Zero + Src alpha", 0x5444, 0x90808080, 0, 10, 2, 0x00000000, 0x00000000, 0x2a62},
    {"Zero + Inverse src alpha", 0x5444, 0x90808080, 0, 10, 3, 0x00000000, 0x00000000, 0x21e1},
    {"Zero + Dest alpha", 0x5444, 0x90808080, 0, 10, 4, 0x00000000, 0x00000000, 0x0000},
    {"Zero + Inverse dest alpha", 0x5444, 0x90808080, 0, 10, 5, 0x00000000, 0x00000000, 0x5444},
    {"Zero + Double src alpha", 0x5444, 0x90808080, 0, 10, 6, 0x00000000, 0x00000000, 0x5ce4},
    {"Zero + Inverse double src alpha", 0x5444, 0x90808080, 0, 10, 7, 0x00000000, 0x00000000, 0x0000},
    {"Zero + Double dest alpha", 0x5444, 0x90808080, 0, 10, 8, 0x00000000, 0x00000000, 0x0000},
    {"Zero + Inverse double dest alpha", 0x5444, 0x90808080, 0, 10, 9, 0x00000000, 0x00000000, 0x5444},
    {"Fixed + Zero", 0x5444, 0x90808080, 0, 10, 10, 0x12345678, 0x00000000, 0x1947},
    {"Factor 11 + Zero", 0x5444, 0x90808080, 0, 11, 10, 0x12345678, 0x00000000, 0x1947},
    {"Factor 12 + Zero", 0x5444, 0x90808080, 0, 12, 10, 0x12345678, 0x00000000, 0x1947},
    {"Factor 13 + Zero", 0x5444, 0x90808080, 0, 13, 10, 0x12345678, 0x00000000, 0x1947},
    {"Factor 14 + Zero", 0x5444, 0x90808080, 0, 14, 10, 0x12345678, 0x00000000, 0x1947},
    {"Factor 15 + Zero", 0x5444, 0x90808080, 0, 15, 10, 0x12345678, 0x00000000, 0x1947},
    {"F0 + 0F", 0xFFFF, 0xFFFFFFFF, 0, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0xffff},
    {"0F + F0", 0xFFFF, 0xFFFFFFFF, 0, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0xffff},
    {"F0 - 0F", 0xFFFF, 0xFFFFFFFF, 1, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0xe71c},
    {"0F - F0", 0xFFFF, 0xFFFFFFFF, 1, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0x0000},
    {"Reverse F0 - 0F", 0xFFFF, 0xFFFFFFFF, 2, 10, 10, 0xF0F0F0F0, 0x0F0F0F0F, 0x0000},
    {"Reverse 0F - F0", 0xFFFF, 0xFFFFFFFF, 2, 10, 10, 0x0F0F0F0F, 0xF0F0F0F0, 0xe71c},
    {"Min CC, 33", 0xCCCC, 0x33333333, 3, 10, 10, 0x80808080, 0x80808080, 0x3186},
    {"Min 33, CC", 0x3333, 0xCCCCCCCC, 3, 10, 10, 0x80808080, 0x80808080, 0x3333},
    {"Max CC, 33", 0xCCCC, 0x33333333, 4, 10, 10, 0x80808080, 0x80808080, 0xcccc},
    {"Max 33, CC", 0x3333, 0xCCCCCCCC, 4, 10, 10, 0x80808080, 0x80808080, 0xce79},
    {"Abs CC - 33", 0xCCCC, 0x33333333, 5, 10, 10, 0x80808080, 0x80808080, 0x9b26},
    {"Abs 33 - CC", 0x3333, 0xCCCCCCCC, 5, 10, 10, 0x80808080, 0x80808080, 0x9b26},
};

template <size_t N>
TestRun runBlendOn(GuSim& gu, const char* test, u32 fmt, const BlendCase (&cases)[N]) {
    const bool wide = fmt == GE_FORMAT_8888;
    const u32 fill = wide ? 0x44444444u : 0x4444u;
    TestRun run{test, gu.backend(), {}};
    auto fillVram = [&](u32 v) {
        if (wide) gu.fillVram32(0, v, 512 * 272);
        else gu.fillVram32(0, v | v << 16, 512 * 272 / 2);
    };
    auto read = [&] { return wide ? gu.readVram32(0) : u32(gu.readVram16(0)); };
    gu.init();
    ListBuilder& b = gu.start();
    sdkFrameSetup(b, {240, 136, 480, 272, fmt});
    b.shadeModel(true);                 // sceGuShadeModel(GU_SMOOTH)
    b.enable(GE_CMD_TME, false);        // sceGuDisable(GU_TEXTURE_2D)
    setIdentityMatrices(b);
    gu.finishSync();
    fillVram(fill);
    run.checkpoints.push_back({"Initial", fill, read()});
    for (const BlendCase& c : cases) {
        fillVram(c.prev);
        ListBuilder& l = gu.start();
        l.enable(GE_CMD_ABE, true);
        l.blendFunc(c.op, c.src, c.dst, c.fixA, c.fixB);
        l.enable(GE_CMD_STE, true);
        l.stencilFunc(1 /*ALWAYS*/, 0xAA, 0xFF);
        l.stencilOp(2, 2, 2);  // REPLACE
        drawOnePixel(l, c.color);
        gu.finishSync();
        run.checkpoints.push_back({c.name, c.hardware, read()});
        fillVram(fill);
        // The test's sceGuDisable(GU_BLEND) after sceGuFinish lands behind the list's END and
        // never runs: blending stays on, as each case sets it again anyway.
    }
    return run;
}

TestRun runBlend(GuSim& gu) { return runBlendOn(gu, "commands/blend", GE_FORMAT_8888, kCases); }
TestRun runBlend565(GuSim& gu) { return runBlendOn(gu, "commands/blend565", GE_FORMAT_565, kCases565); }

CONFORMANCE_TEST(CommandsBlend, runBlend)
CONFORMANCE_TEST(CommandsBlend565, runBlend565)

}  // namespace
}  // namespace ge::conformance
