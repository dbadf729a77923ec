// SPDX-License-Identifier: MIT
// PSP 16/32-bit pixel layouts (docs/ge-rules.md §5.4, §6.1, §8.8).
//
// RGBA8888 is handled as a u32 with R in bits 7..0, G 15..8, B 23..16, A 31..24 — the same
// layout as an 8888 texel or frame-buffer pixel in guest memory, read little-endian.
#pragma once
#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge {

// 16-bit → RGBA8888 by bit replication (a 5-bit channel c becomes c<<3 | c>>2, 6-bit c<<2 | c>>4,
// 4-bit c·17; ge-rules.md §5.4). 5650: R bits 4..0, G 10..5, B 15..11, alpha 255. 5551: R 4..0, G 9..5,
// B 14..10, A bit 15 (0 or 255). 4444: R 3..0, G 7..4, B 11..8, A 15..12.
// Inline so that the per-format texture/frame-buffer loops can inline them.
inline u32 decode5650(u16 v) {
    const u32 r = v & 0x1F, g = (v >> 5) & 0x3F, b = v >> 11;
    return ((r << 3) | (r >> 2)) | ((g << 2) | (g >> 4)) << 8 | ((b << 3) | (b >> 2)) << 16 | 0xFF000000u;
}
inline u32 decode5551(u16 v) {
    const u32 r = v & 0x1F, g = (v >> 5) & 0x1F, b = (v >> 10) & 0x1F;
    return ((r << 3) | (r >> 2)) | ((g << 3) | (g >> 2)) << 8 | ((b << 3) | (b >> 2)) << 16 |
           ((v & 0x8000) ? 0xFF000000u : 0u);
}
inline u32 decode4444(u16 v) {
    return (v & 0xF) * 0x11u | ((v >> 4) & 0xF) * 0x1100u | ((v >> 8) & 0xF) * 0x110000u | u32(v >> 12) * 0x11000000u;
}
u32 decodePixel16(u16 v, GeBufferFormat fmt);  // dispatch; GE_FORMAT_8888 is not 16-bit: returns 0

// Frame-buffer write conversion: truncation (keep the high bits of each 8-bit channel).
u16 encode5650(u32 rgba);
u16 encode5551(u32 rgba);
u16 encode4444(u32 rgba);
u16 encodePixel16(u32 rgba, GeBufferFormat fmt);  // GE_FORMAT_8888: returns 0

// Convert a whole frame-buffer region (stride in pixels) to RGBA8888 (alpha as stored; 5650 → 255).
// src holds height rows of stridePixels pixels (the last row needs only width pixels); dst receives
// width*height pixels, row-major, tightly packed.
void convertToRGBA8888(const u8* src, GeBufferFormat fmt, u32 width, u32 height, u32 stridePixels, u32* dst);
// The other way for one row of `width` pixels: RGBA8888 (R in the low byte) stored as `fmt`
// (16-bit formats truncate: encode5650 …; 8888 as it is), little-endian.
void convertFromRGBA8888(const u32* src, GeBufferFormat fmt, u32 width, u8* dst);

// Bytes per pixel of a frame-buffer format (2 or 4).
inline u32 bytesPerPixel(GeBufferFormat fmt) { return fmt == GE_FORMAT_8888 ? 4 : 2; }

}  // namespace ge
