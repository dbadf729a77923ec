// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/textures/size, re-created (gu_sim.h, conformance.h). Textures of
// 1 to 32768 texels wide (one row) and 1 to 32768 texels high (one column) in 8888, 4444, CLUT8 and
// CLUT4 are drawn by a sprite over pixels (0, 0)-(256, 256), in transform mode (a 256x256 viewport,
// texture coordinates 0..1) and in through mode (texture coordinates 0..w, 0..h), NEAREST, clamped,
// REPLACE/RGBA, level mode CONST. TSIZE gets the raw exponent (up to 15, past the 512 texels the GE
// is documented for), and the buffer width the texture width (at least 16 bytes). The texture
// buffer is one 512 KiB array that each test only partly rewrites (8888: 0xFFF00000 | i, 4444:
// 0xF000 | i & 0xFFF, CLUT8: i % w, CLUT4: i & 0xF per nibble; the palette is 0xFF000000 | i), so
// texels past the size read what earlier tests left there, as they did on the PSP; the frame buffer
// is cleared once. Four pixels are read back after each draw: (0, 0) and, along the long side,
// 127, 255 and (255, 255).
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// On a PSP, per draw (widths, then heights; per format 16 transform then 16 through): TL and, for a
// row (h=1), TC, TR, BR; for a column, CL, BL, BR (0xAARRGGBB, alpha 0 as the frame buffer was).
constexpr u32 kHardware[256][4] = {
    {0xf00000, 0xf00000, 0xf00000, 0xf00000},  // w=1 8888 transform
    {0xf00000, 0xf00000, 0xf00001, 0xf00001},  // w=2 8888 transform
    {0xf00000, 0xf00001, 0xf00003, 0xf00003},  // w=4 8888 transform
    {0xf00000, 0xf00003, 0xf00007, 0xf00007},  // w=8 8888 transform
    {0xf00000, 0xf00007, 0xf0000f, 0xf0000f},  // w=16 8888 transform
    {0xf00000, 0xf0000f, 0xf0001f, 0xf0001f},  // w=32 8888 transform
    {0xf00000, 0xf0001f, 0xf0003f, 0xf0003f},  // w=64 8888 transform
    {0xf00000, 0xf0003f, 0xf0007f, 0xf0007f},  // w=128 8888 transform
    {0xf00000, 0xf0007f, 0xf000ff, 0xf000ff},  // w=256 8888 transform
    {0xf00001, 0xf000ff, 0xf001ff, 0xf001ff},  // w=512 8888 transform
    {0xf00002, 0xf001fe, 0xf001ff, 0xf001ff},  // w=1024 8888 transform
    {0xf00004, 0xf001ff, 0xf001ff, 0xf001ff},  // w=2048 8888 transform
    {0xf00008, 0xf001ff, 0xf001ff, 0xf001ff},  // w=4096 8888 transform
    {0xf00010, 0xf001ff, 0xf001ff, 0xf001ff},  // w=8192 8888 transform
    {0xf00020, 0xf001ff, 0xf001ff, 0xf001ff},  // w=16384 8888 transform
    {0xf00040, 0xf001ff, 0xf001ff, 0xf001ff},  // w=32768 8888 transform
    {0xf00000, 0xf00000, 0xf00000, 0xf00000},  // w=1 8888 through
    {0xf00000, 0xf00000, 0xf00001, 0xf00001},  // w=2 8888 through
    {0xf00000, 0xf00001, 0xf00003, 0xf00003},  // w=4 8888 through
    {0xf00000, 0xf00003, 0xf00007, 0xf00007},  // w=8 8888 through
    {0xf00000, 0xf00007, 0xf0000f, 0xf0000f},  // w=16 8888 through
    {0xf00000, 0xf0000f, 0xf0001f, 0xf0001f},  // w=32 8888 through
    {0xf00000, 0xf0001f, 0xf0003f, 0xf0003f},  // w=64 8888 through
    {0xf00000, 0xf0003f, 0xf0007f, 0xf0007f},  // w=128 8888 through
    {0xf00000, 0xf0007f, 0xf000ff, 0xf000ff},  // w=256 8888 through
    {0xf00001, 0xf000ff, 0xf001ff, 0xf001ff},  // w=512 8888 through
    {0xf00002, 0xf001fe, 0xf001ff, 0xf001ff},  // w=1024 8888 through
    {0xf00004, 0xf001ff, 0xf001ff, 0xf001ff},  // w=2048 8888 through
    {0xf00008, 0xf001ff, 0xf001ff, 0xf001ff},  // w=4096 8888 through
    {0xf00010, 0xf001ff, 0xf001ff, 0xf001ff},  // w=8192 8888 through
    {0xf00020, 0xf001ff, 0xf001ff, 0xf001ff},  // w=16384 8888 through
    {0xf00040, 0xf001ff, 0xf001ff, 0xf001ff},  // w=32768 8888 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 4444 transform
    {0x000000, 0x000000, 0x000011, 0x000011},  // w=2 4444 transform
    {0x000000, 0x000011, 0x000033, 0x000033},  // w=4 4444 transform
    {0x000000, 0x000033, 0x000077, 0x000077},  // w=8 4444 transform
    {0x000000, 0x000077, 0x0000ff, 0x0000ff},  // w=16 4444 transform
    {0x000000, 0x0000ff, 0x0011ff, 0x0011ff},  // w=32 4444 transform
    {0x000000, 0x0011ff, 0x0033ff, 0x0033ff},  // w=64 4444 transform
    {0x000000, 0x0033ff, 0x0077ff, 0x0077ff},  // w=128 4444 transform
    {0x000000, 0x0077ff, 0x00ffff, 0x00ffff},  // w=256 4444 transform
    {0x000011, 0x00ffff, 0x11ffff, 0x11ffff},  // w=512 4444 transform
    {0x000022, 0x11ffee, 0x11ffff, 0x11ffff},  // w=1024 4444 transform
    {0x000044, 0x11ffff, 0x11ffff, 0x11ffff},  // w=2048 4444 transform
    {0x000088, 0x11ffff, 0x11ffff, 0x11ffff},  // w=4096 4444 transform
    {0x001100, 0x11ffff, 0x11ffff, 0x11ffff},  // w=8192 4444 transform
    {0x002200, 0x11ffff, 0x11ffff, 0x11ffff},  // w=16384 4444 transform
    {0x004400, 0x11ffff, 0x11ffff, 0x11ffff},  // w=32768 4444 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 4444 through
    {0x000000, 0x000000, 0x000011, 0x000011},  // w=2 4444 through
    {0x000000, 0x000011, 0x000033, 0x000033},  // w=4 4444 through
    {0x000000, 0x000033, 0x000077, 0x000077},  // w=8 4444 through
    {0x000000, 0x000077, 0x0000ff, 0x0000ff},  // w=16 4444 through
    {0x000000, 0x0000ff, 0x0011ff, 0x0011ff},  // w=32 4444 through
    {0x000000, 0x0011ff, 0x0033ff, 0x0033ff},  // w=64 4444 through
    {0x000000, 0x0033ff, 0x0077ff, 0x0077ff},  // w=128 4444 through
    {0x000000, 0x0077ff, 0x00ffff, 0x00ffff},  // w=256 4444 through
    {0x000011, 0x00ffff, 0x11ffff, 0x11ffff},  // w=512 4444 through
    {0x000022, 0x11ffee, 0x11ffff, 0x11ffff},  // w=1024 4444 through
    {0x000044, 0x11ffff, 0x11ffff, 0x11ffff},  // w=2048 4444 through
    {0x000088, 0x11ffff, 0x11ffff, 0x11ffff},  // w=4096 4444 through
    {0x001100, 0x11ffff, 0x11ffff, 0x11ffff},  // w=8192 4444 through
    {0x002200, 0x11ffff, 0x11ffff, 0x11ffff},  // w=16384 4444 through
    {0x004400, 0x11ffff, 0x11ffff, 0x11ffff},  // w=32768 4444 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 CLUT8 transform
    {0x000000, 0x000000, 0x000001, 0x000001},  // w=2 CLUT8 transform
    {0x000000, 0x000001, 0x000003, 0x000003},  // w=4 CLUT8 transform
    {0x000000, 0x000003, 0x000007, 0x000007},  // w=8 CLUT8 transform
    {0x000000, 0x000007, 0x00000f, 0x00000f},  // w=16 CLUT8 transform
    {0x000000, 0x00000f, 0x00001f, 0x00001f},  // w=32 CLUT8 transform
    {0x000000, 0x00001f, 0x00003f, 0x00003f},  // w=64 CLUT8 transform
    {0x000000, 0x00003f, 0x00007f, 0x00007f},  // w=128 CLUT8 transform
    {0x000000, 0x00007f, 0x0000ff, 0x0000ff},  // w=256 CLUT8 transform
    {0x000001, 0x0000ff, 0x0000ff, 0x0000ff},  // w=512 CLUT8 transform
    {0x000002, 0x0000fe, 0x0000ff, 0x0000ff},  // w=1024 CLUT8 transform
    {0x000004, 0x0000ff, 0x0000ff, 0x0000ff},  // w=2048 CLUT8 transform
    {0x000008, 0x0000ff, 0x0000ff, 0x0000ff},  // w=4096 CLUT8 transform
    {0x000010, 0x0000ff, 0x0000ff, 0x0000ff},  // w=8192 CLUT8 transform
    {0x000020, 0x0000ff, 0x0000ff, 0x0000ff},  // w=16384 CLUT8 transform
    {0x000040, 0x0000ff, 0x0000ff, 0x0000ff},  // w=32768 CLUT8 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 CLUT8 through
    {0x000000, 0x000000, 0x000001, 0x000001},  // w=2 CLUT8 through
    {0x000000, 0x000001, 0x000003, 0x000003},  // w=4 CLUT8 through
    {0x000000, 0x000003, 0x000007, 0x000007},  // w=8 CLUT8 through
    {0x000000, 0x000007, 0x00000f, 0x00000f},  // w=16 CLUT8 through
    {0x000000, 0x00000f, 0x00001f, 0x00001f},  // w=32 CLUT8 through
    {0x000000, 0x00001f, 0x00003f, 0x00003f},  // w=64 CLUT8 through
    {0x000000, 0x00003f, 0x00007f, 0x00007f},  // w=128 CLUT8 through
    {0x000000, 0x00007f, 0x0000ff, 0x0000ff},  // w=256 CLUT8 through
    {0x000001, 0x0000ff, 0x0000ff, 0x0000ff},  // w=512 CLUT8 through
    {0x000002, 0x0000fe, 0x0000ff, 0x0000ff},  // w=1024 CLUT8 through
    {0x000004, 0x0000ff, 0x0000ff, 0x0000ff},  // w=2048 CLUT8 through
    {0x000008, 0x0000ff, 0x0000ff, 0x0000ff},  // w=4096 CLUT8 through
    {0x000010, 0x0000ff, 0x0000ff, 0x0000ff},  // w=8192 CLUT8 through
    {0x000020, 0x0000ff, 0x0000ff, 0x0000ff},  // w=16384 CLUT8 through
    {0x000040, 0x0000ff, 0x0000ff, 0x0000ff},  // w=32768 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 CLUT4 transform
    {0x000000, 0x000000, 0x000001, 0x000001},  // w=2 CLUT4 transform
    {0x000000, 0x000001, 0x000003, 0x000003},  // w=4 CLUT4 transform
    {0x000000, 0x000003, 0x000007, 0x000007},  // w=8 CLUT4 transform
    {0x000000, 0x000007, 0x00000f, 0x00000f},  // w=16 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=32 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=64 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=128 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=256 CLUT4 transform
    {0x000001, 0x00000f, 0x00000f, 0x00000f},  // w=512 CLUT4 transform
    {0x000002, 0x00000e, 0x00000f, 0x00000f},  // w=1024 CLUT4 transform
    {0x000004, 0x00000f, 0x00000f, 0x00000f},  // w=2048 CLUT4 transform
    {0x000008, 0x00000f, 0x00000f, 0x00000f},  // w=4096 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=8192 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=16384 CLUT4 transform
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=32768 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // w=1 CLUT4 through
    {0x000000, 0x000000, 0x000001, 0x000001},  // w=2 CLUT4 through
    {0x000000, 0x000001, 0x000003, 0x000003},  // w=4 CLUT4 through
    {0x000000, 0x000003, 0x000007, 0x000007},  // w=8 CLUT4 through
    {0x000000, 0x000007, 0x00000f, 0x00000f},  // w=16 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=32 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=64 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=128 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=256 CLUT4 through
    {0x000001, 0x00000f, 0x00000f, 0x00000f},  // w=512 CLUT4 through
    {0x000002, 0x00000e, 0x00000f, 0x00000f},  // w=1024 CLUT4 through
    {0x000004, 0x00000f, 0x00000f, 0x00000f},  // w=2048 CLUT4 through
    {0x000008, 0x00000f, 0x00000f, 0x00000f},  // w=4096 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=8192 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=16384 CLUT4 through
    {0x000000, 0x00000f, 0x00000f, 0x00000f},  // w=32768 CLUT4 through
    {0xf00000, 0xf00000, 0xf00000, 0xf00000},  // h=1 8888 transform
    {0xf00000, 0xf00000, 0x543210, 0x543210},  // h=2 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=4 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=8 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=16 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=32 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=64 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=128 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=256 8888 transform
    {0xf00000, 0x543210, 0x543210, 0x543210},  // h=512 8888 transform
    {0xf00004, 0x543210, 0x543210, 0x543210},  // h=1024 8888 transform
    {0xf0000c, 0xf007fc, 0xf007fc, 0xf007fc},  // h=2048 8888 transform
    {0xf0001c, 0xf007fc, 0xf007fc, 0xf007fc},  // h=4096 8888 transform
    {0xf00038, 0xf007fc, 0xf007fc, 0xf007fc},  // h=8192 8888 transform
    {0xf00070, 0xf007fc, 0xf007fc, 0xf007fc},  // h=16384 8888 transform
    {0xf000e0, 0xf007fc, 0xf007fc, 0xf007fc},  // h=32768 8888 transform
    {0xf00000, 0xf00000, 0xf00000, 0xf00000},  // h=1 8888 through
    {0xf00000, 0xf00000, 0xf00004, 0xf00004},  // h=2 8888 through
    {0xf00000, 0xf00004, 0xf0000c, 0xf0000c},  // h=4 8888 through
    {0xf00000, 0xf0000c, 0xf0001c, 0xf0001c},  // h=8 8888 through
    {0xf00000, 0xf0001c, 0xf0003c, 0xf0003c},  // h=16 8888 through
    {0xf00000, 0xf0003c, 0xf0007c, 0xf0007c},  // h=32 8888 through
    {0xf00000, 0xf0007c, 0xf000fc, 0xf000fc},  // h=64 8888 through
    {0xf00000, 0xf000fc, 0xf001fc, 0xf001fc},  // h=128 8888 through
    {0xf00000, 0xf001fc, 0xf003fc, 0xf003fc},  // h=256 8888 through
    {0xf00004, 0xf003fc, 0xf007fc, 0xf007fc},  // h=512 8888 through
    {0xf00008, 0xf007f8, 0xf007fc, 0xf007fc},  // h=1024 8888 through
    {0xf00010, 0xf007fc, 0xf007fc, 0xf007fc},  // h=2048 8888 through
    {0xf00020, 0xf007fc, 0xf007fc, 0xf007fc},  // h=4096 8888 through
    {0xf00040, 0xf007fc, 0xf007fc, 0xf007fc},  // h=8192 8888 through
    {0xf00080, 0xf007fc, 0xf007fc, 0xf007fc},  // h=16384 8888 through
    {0xf00100, 0xf007fc, 0xf007fc, 0xf007fc},  // h=32768 8888 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 4444 transform
    {0x000000, 0x000000, 0x000044, 0x000044},  // h=2 4444 transform
    {0x000000, 0x000044, 0x0000cc, 0x0000cc},  // h=4 4444 transform
    {0x000000, 0x0000cc, 0x0011cc, 0x0011cc},  // h=8 4444 transform
    {0x000000, 0x0011cc, 0x0033cc, 0x0033cc},  // h=16 4444 transform
    {0x000000, 0x0033cc, 0x0077cc, 0x0077cc},  // h=32 4444 transform
    {0x000000, 0x0077cc, 0x00ffcc, 0x00ffcc},  // h=64 4444 transform
    {0x000000, 0x00ffcc, 0x11ffcc, 0x11ffcc},  // h=128 4444 transform
    {0x000000, 0x11ffcc, 0x33ffcc, 0x33ffcc},  // h=256 4444 transform
    {0x000000, 0x33ff88, 0x77ff88, 0x77ff88},  // h=512 4444 transform
    {0x000088, 0x77ff44, 0x77ffcc, 0x77ffcc},  // h=1024 4444 transform
    {0x001188, 0x77ffcc, 0x77ffcc, 0x77ffcc},  // h=2048 4444 transform
    {0x003388, 0xffff88, 0xffff88, 0xffff88},  // h=4096 4444 transform
    {0x007700, 0xffff88, 0xffff88, 0xffff88},  // h=8192 4444 transform
    {0x00ee00, 0xffff88, 0xffff88, 0xffff88},  // h=16384 4444 transform
    {0x11cc00, 0xffff88, 0xffff88, 0xffff88},  // h=32768 4444 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 4444 through
    {0x000000, 0x000000, 0x000088, 0x000088},  // h=2 4444 through
    {0x000000, 0x000088, 0x001188, 0x001188},  // h=4 4444 through
    {0x000000, 0x001188, 0x003388, 0x003388},  // h=8 4444 through
    {0x000000, 0x003388, 0x007788, 0x007788},  // h=16 4444 through
    {0x000000, 0x007788, 0x00ff88, 0x00ff88},  // h=32 4444 through
    {0x000000, 0x00ff88, 0x11ff88, 0x11ff88},  // h=64 4444 through
    {0x000000, 0x11ff88, 0x33ff88, 0x33ff88},  // h=128 4444 through
    {0x000000, 0x33ff88, 0x77ff88, 0x77ff88},  // h=256 4444 through
    {0x000088, 0x77ff88, 0xffff88, 0xffff88},  // h=512 4444 through
    {0x001100, 0xffff00, 0xffff88, 0xffff88},  // h=1024 4444 through
    {0x002200, 0xffff88, 0xffff88, 0xffff88},  // h=2048 4444 through
    {0x004400, 0xffff88, 0xffff88, 0xffff88},  // h=4096 4444 through
    {0x008800, 0xffff88, 0xffff88, 0xffff88},  // h=8192 4444 through
    {0x110000, 0xffff88, 0xffff88, 0xffff88},  // h=16384 4444 through
    {0x220000, 0xffff88, 0xffff88, 0xffff88},  // h=32768 4444 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 CLUT8 transform
    {0x000000, 0x000000, 0x000008, 0x000008},  // h=2 CLUT8 transform
    {0x000000, 0x000008, 0x000018, 0x000018},  // h=4 CLUT8 transform
    {0x000000, 0x000018, 0x000038, 0x000038},  // h=8 CLUT8 transform
    {0x000000, 0x000038, 0x000078, 0x000078},  // h=16 CLUT8 transform
    {0x000000, 0x000078, 0x0000f8, 0x0000f8},  // h=32 CLUT8 transform
    {0x000000, 0x0000f8, 0x0000f8, 0x0000f8},  // h=64 CLUT8 transform
    {0x000000, 0x0000f8, 0x0000f8, 0x0000f8},  // h=128 CLUT8 transform
    {0x000000, 0x0000f8, 0x0000f8, 0x0000f8},  // h=256 CLUT8 transform
    {0x000000, 0x0000f0, 0x0000f0, 0x0000f0},  // h=512 CLUT8 transform
    {0x000000, 0x0000e8, 0x0000f8, 0x0000f8},  // h=1024 CLUT8 transform
    {0x000000, 0x0000f8, 0x0000f8, 0x0000f8},  // h=2048 CLUT8 transform
    {0x000000, 0x0000f8, 0x0000f8, 0x0000f8},  // h=4096 CLUT8 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8192 CLUT8 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16384 CLUT8 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32768 CLUT8 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=64 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=128 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=256 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=512 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1024 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2048 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4096 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8192 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16384 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32768 CLUT8 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=64 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=128 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=256 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=512 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1024 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2048 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4096 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8192 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16384 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32768 CLUT4 transform
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=64 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=128 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=256 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=512 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=1024 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=2048 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=4096 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=8192 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=16384 CLUT4 through
    {0x000000, 0x000000, 0x000000, 0x000000},  // h=32768 CLUT4 through
};

constexpr u32 kTexBuf = 0x08400000;   // texbuf[32768 * 4], 16-byte aligned
constexpr u32 kTexBufBytes = 32768 * 4 * 4;
constexpr u32 kClut = kTexBuf + kTexBufBytes;  // clut[256]

constexpr u32 kFormats[4] = {GE_TFMT_8888, GE_TFMT_4444, GE_TFMT_CLUT8, GE_TFMT_CLUT4};
constexpr const char* kFormatNames[4] = {"8888", "4444", "CLUT8", "CLUT4"};

class SizeTest {
public:
    explicit SizeTest(GuSim& gu) : gu_(gu), run_{"textures/size", gu.backend(), {}}, texbuf_(kTexBufBytes, 0) {}

    TestRun run() {
        gu_.init();
        ListBuilder& b = gu_.start();  // init()
        b.drawBuffer(GE_FORMAT_8888, 0, 512);
        b.depthBuffer(0, 512);  // sceGuDrawBuffer before sceGuDispBuffer: depth buffer 0, width 512
        sdkDispBuffer(b);
        b.scissor(0, 0, 480, 272);  // sceGuEnable(GU_SCISSOR_TEST) first, so the scissor is sent
        b.offset(2048 - 256 / 2, 2048 - 256 / 2);
        b.viewport(2048, 2048, 256, 256);
        b.depthMask(true);
        b.cullMode(false);
        b.shadeModel(true);
        b.enable(GE_CMD_TME, true);
        b.texFunc(3 /*REPLACE*/, true);
        b.texFilter(0, 0);
        b.cmd(GE_CMD_TLEVEL, 1);  // sceGuTexLevelMode(GU_TEXTURE_CONST, 0.0f)
        b.texWrap(true, true);
        setIdentityMatrices(b);
        gu_.finishSync();
        gu_.fillVram32(0, 0, 512 * 272);

        for (bool heights : {false, true})
            for (int f = 0; f < 4; ++f)
                for (bool through : {false, true})
                    for (int i = 0; i < 16; ++i) draw(heights, f, through, heights ? 0 : i, heights ? i : 0);
        return run_;
    }

private:
    // prepareTexture(fmt, wf, hf, w, h): the first w * h texels rewritten (the rest of the buffer
    // left as it is), the palette loaded for the CLUT formats, then the texture state.
    void prepare(ListBuilder& l, int f, int wf, int hf) {
        const u32 w = 1u << wf, h = 1u << hf, n = w * h;
        u32 bufw = 0, bytes = 0;
        u8* t = texbuf_.data();
        switch (kFormats[f]) {
        case GE_TFMT_8888:
            bufw = w < 4 ? 4 : w;
            for (u32 i = 0; i < n; ++i) writeLE32(t + i * 4, 0xFFF00000u | i);
            bytes = n * 4;
            break;
        case GE_TFMT_4444:
            bufw = w < 8 ? 8 : w;
            for (u32 i = 0; i < n; ++i) writeLE16(t + i * 2, u16(0xF000 | (i & 0x0FFF)));
            bytes = n * 2;
            break;
        case GE_TFMT_CLUT8:
            bufw = w < 16 ? 16 : w;
            for (u32 i = 0; i < n; ++i) t[i] = u8((i % w) & 0xFF);
            bytes = n;
            break;
        default:  // CLUT4: byte i / 2 = (i & 0xF) | ((i + 1) << 4 & 0xF0) for even i
            bufw = w < 32 ? 32 : w;
            for (u32 i = 0; i < n; i += 2) t[i / 2] = u8((i & 0xF) | (((i + 1) << 4) & 0xF0));
            bytes = (n + 1) / 2;
            break;
        }
        gu_.cpuWrite(kTexBuf, t, bytes);
        if (kFormats[f] == GE_TFMT_CLUT8 || kFormats[f] == GE_TFMT_CLUT4) {
            u32 clut[256];
            for (u32 i = 0; i < 256; ++i) clut[i] = 0xFF000000u | i;
            gu_.cpuWrite(kClut, clut, sizeof clut);
            l.clutLoad(kClut, 32);
            l.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        }
        l.enable(GE_CMD_TME, true);
        l.texMode(kFormats[f], 0, false);
        // correctedGuTexImage(0, wf, hf, bufw, texbuf): the exponents and the width as given.
        l.cmd(GE_CMD_TBP0, kTexBuf & 0xFFFFFF);
        l.cmd(GE_CMD_TBW0, ((kTexBuf & 0xFF000000) >> 8) | bufw);
        l.cmd(GE_CMD_TSIZE0, (u32(hf) << 8) | u32(wf));
        l.texFlush();
        l.texSync();
    }

    // testTextureFormat("Texture w=" or "h=", fmt, through, wf, hf).
    void draw(bool heights, int f, bool through, int wf, int hf) {
        const u32 w = 1u << wf, h = 1u << hf;
        ListBuilder& l = gu_.start();
        prepare(l, f, wf, hf);
        // Vertex {u16 u, v; s16 x, y, z}: (0, 0) at (0, 0) or (-32768, 32767); (w, h) or (32768, 32768)
        // at (256, 256) or (32767, -32768).
        u8 v[20] = {};
        auto put = [&](int k, u16 u, u16 vv, s16 x, s16 y) {
            writeLE16(&v[k * 10], u), writeLE16(&v[k * 10 + 2], vv);
            writeLE16(&v[k * 10 + 4], u16(x)), writeLE16(&v[k * 10 + 6], u16(y));
        };
        put(0, 0, 0, s16(through ? 0 : -32768), s16(through ? 0 : 32767));
        put(1, u16(through ? w : 32768), u16(through ? h : 32768), s16(through ? 256 : 32767),
            s16(through ? 256 : -32768));
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | (through ? vt::THROUGH : 0u), 2, nullptr, v);
        gu_.finishSync();

        char title[64];
        std::snprintf(title, sizeof title, "%s=%u %s %s", heights ? "h" : "w", heights ? h : w, kFormatNames[f],
                      through ? "through" : "transform");
        const bool row = hf == 0;  // the test prints TC/TR for a row (and for 1x1), CL/BL for a column
        const u32 at[4] = {0, row ? 127u : 127u * 512, row ? 255u : 255u * 512, 255u * 512 + 255};
        const char* names[4] = {"TL", row ? "TC" : "CL", row ? "TR" : "BL", "BR"};
        const size_t line = run_.checkpoints.size() / 4;
        for (int k = 0; k < 4; ++k)
            run_.checkpoints.push_back(
                {std::string(title) + " " + names[k], kHardware[line][k], gu_.readVram32(at[k] * 4)});
    }

    GuSim& gu_;
    TestRun run_;
    std::vector<u8> texbuf_;  // the host side of texbuf: what the test program last wrote there
};

TestRun runSize(GuSim& gu) { return SizeTest(gu).run(); }

CONFORMANCE_TEST(TexturesSize, runSize)

}  // namespace
}  // namespace ge::conformance
