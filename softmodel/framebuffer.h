// SPDX-License-Identifier: MIT
// Inline frame-buffer pixel access for the software model's hot loop (private to softmodel/).
//
// The layouts are those of hle/pixel_format.h (docs/ge-rules.md §6.1): 5650 R 4..0 G 10..5 B 15..11;
// 5551 R 4..0 G 9..5 B 14..10 A 15; 4444 R 3..0 G 7..4 B 11..8 A 15..12; 8888 bytes R G B A.
// Reads expand by bit replication, writes truncate (ge-rules.md §8.8). These are templates so the shading
// routine, specialised per frame-buffer format, inlines them; tests/soft_blend.cpp checks them
// against ge::decodePixel16/encodePixel16 for every 16-bit value so the two never drift apart.
#pragma once
#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge::soft {

struct Rgba {
    int r = 0, g = 0, b = 0, a = 0;
};

template <GeBufferFormat F>
struct Fb;

template <>
struct Fb<GE_FORMAT_565> {
    static constexpr u32 kBytes = 2;
    static constexpr u32 kRgbBits = 0xFFFF, kAlphaBits = 0;
    static u32 load(const u8* p) { return readLE16(p); }
    static void store(u8* p, u32 v) { writeLE16(p, u16(v)); }
    static Rgba decode(u32 v) {
        int r = v & 31, g = (v >> 5) & 63, b = (v >> 11) & 31;
        return {r << 3 | r >> 2, g << 2 | g >> 4, b << 3 | b >> 2, 0};  // Ad = 0 for 5650 (ge-rules.md §8.8)
    }
    static int stencil(u32) { return 0; }  // ge-rules.md §8.7: always 0
    static u32 encode(int r, int g, int b, int) { return u32(r >> 3) | u32(g >> 2) << 5 | u32(b >> 3) << 11; }
};

template <>
struct Fb<GE_FORMAT_5551> {
    static constexpr u32 kBytes = 2;
    static constexpr u32 kRgbBits = 0x7FFF, kAlphaBits = 0x8000;
    static u32 load(const u8* p) { return readLE16(p); }
    static void store(u8* p, u32 v) { writeLE16(p, u16(v)); }
    static Rgba decode(u32 v) {
        int r = v & 31, g = (v >> 5) & 31, b = (v >> 10) & 31;
        return {r << 3 | r >> 2, g << 3 | g >> 2, b << 3 | b >> 2, (v & 0x8000) ? 255 : 0};
    }
    static int stencil(u32 v) { return (v & 0x8000) ? 255 : 0; }
    static u32 encode(int r, int g, int b, int a) {
        return u32(r >> 3) | u32(g >> 3) << 5 | u32(b >> 3) << 10 | u32(a >> 7) << 15;
    }
};

template <>
struct Fb<GE_FORMAT_4444> {
    static constexpr u32 kBytes = 2;
    static constexpr u32 kRgbBits = 0x0FFF, kAlphaBits = 0xF000;
    static u32 load(const u8* p) { return readLE16(p); }
    static void store(u8* p, u32 v) { writeLE16(p, u16(v)); }
    static Rgba decode(u32 v) {
        return {int(v & 15) * 17, int((v >> 4) & 15) * 17, int((v >> 8) & 15) * 17, int((v >> 12) & 15) * 17};
    }
    static int stencil(u32 v) { return int((v >> 12) & 15) * 17; }
    static u32 encode(int r, int g, int b, int a) {
        return u32(r >> 4) | u32(g >> 4) << 4 | u32(b >> 4) << 8 | u32(a >> 4) << 12;
    }
};

template <>
struct Fb<GE_FORMAT_8888> {
    static constexpr u32 kBytes = 4;
    static constexpr u32 kRgbBits = 0x00FFFFFF, kAlphaBits = 0xFF000000;
    static u32 load(const u8* p) { return readLE32(p); }
    static void store(u8* p, u32 v) { writeLE32(p, v); }
    static Rgba decode(u32 v) { return {int(v & 255), int((v >> 8) & 255), int((v >> 16) & 255), int(v >> 24)}; }
    static int stencil(u32 v) { return int(v >> 24); }
    static u32 encode(int r, int g, int b, int a) { return u32(r) | u32(g) << 8 | u32(b) << 16 | u32(a) << 24; }
};

// Runtime dispatch for per-draw set-up (never per pixel).
inline u32 fbEncode(GeBufferFormat f, int r, int g, int b, int a) {
    switch (f) {
    case GE_FORMAT_565: return Fb<GE_FORMAT_565>::encode(r, g, b, a);
    case GE_FORMAT_5551: return Fb<GE_FORMAT_5551>::encode(r, g, b, a);
    case GE_FORMAT_4444: return Fb<GE_FORMAT_4444>::encode(r, g, b, a);
    default: return Fb<GE_FORMAT_8888>::encode(r, g, b, a);
    }
}
inline Rgba fbDecode(GeBufferFormat f, u32 v) {
    switch (f) {
    case GE_FORMAT_565: return Fb<GE_FORMAT_565>::decode(v);
    case GE_FORMAT_5551: return Fb<GE_FORMAT_5551>::decode(v);
    case GE_FORMAT_4444: return Fb<GE_FORMAT_4444>::decode(v);
    default: return Fb<GE_FORMAT_8888>::decode(v);
    }
}
inline u32 fbAlphaBits(GeBufferFormat f) {
    switch (f) {
    case GE_FORMAT_565: return Fb<GE_FORMAT_565>::kAlphaBits;
    case GE_FORMAT_5551: return Fb<GE_FORMAT_5551>::kAlphaBits;
    case GE_FORMAT_4444: return Fb<GE_FORMAT_4444>::kAlphaBits;
    default: return Fb<GE_FORMAT_8888>::kAlphaBits;
    }
}
inline u32 fbRgbBits(GeBufferFormat f) {
    switch (f) {
    case GE_FORMAT_565: return Fb<GE_FORMAT_565>::kRgbBits;
    case GE_FORMAT_5551: return Fb<GE_FORMAT_5551>::kRgbBits;
    case GE_FORMAT_4444: return Fb<GE_FORMAT_4444>::kRgbBits;
    default: return Fb<GE_FORMAT_8888>::kRgbBits;
    }
}

}  // namespace ge::soft
