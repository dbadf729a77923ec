// SPDX-License-Identifier: MIT
// PSP 16-bit pixel conversions (docs/ge-rules.md §5.4, §6.1, §8.8).
#include "hle/pixel_format.h"

namespace ge {

u32 decodePixel16(u16 v, GeBufferFormat fmt) {
    switch (fmt) {
    case GE_FORMAT_565: return decode5650(v);
    case GE_FORMAT_5551: return decode5551(v);
    case GE_FORMAT_4444: return decode4444(v);
    default: return 0;
    }
}

// Writes truncate: only the high bits of each 8-bit channel survive (ge-rules.md §8.8).
u16 encode5650(u32 c) {
    u32 r = (c >> 3) & 0x1F, g = (c >> 10) & 0x3F, b = (c >> 19) & 0x1F;
    return u16(r | (g << 5) | (b << 11));
}
u16 encode5551(u32 c) {
    u32 r = (c >> 3) & 0x1F, g = (c >> 11) & 0x1F, b = (c >> 19) & 0x1F, a = c >> 31;
    return u16(r | (g << 5) | (b << 10) | (a << 15));
}
u16 encode4444(u32 c) {
    u32 r = (c >> 4) & 0xF, g = (c >> 12) & 0xF, b = (c >> 20) & 0xF, a = c >> 28;
    return u16(r | (g << 4) | (b << 8) | (a << 12));
}

u16 encodePixel16(u32 c, GeBufferFormat fmt) {
    switch (fmt) {
    case GE_FORMAT_565: return encode5650(c);
    case GE_FORMAT_5551: return encode5551(c);
    case GE_FORMAT_4444: return encode4444(c);
    default: return 0;
    }
}

namespace {
// size_t indices: with a 32-bit index (whose arithmetic wraps) GCC does not vectorise the rows.
template <u32 (*Decode)(u16)>
void convertRows16(const u8* src, u32 width, u32 height, u32 stride, u32* dst) {
    for (u32 y = 0; y < height; ++y) {
        const u8* row = src + size_t(y) * stride * 2;
        u32* out = dst + size_t(y) * width;
        for (size_t x = 0; x < width; ++x) out[x] = Decode(readLE16(row + 2 * x));
    }
}
template <u16 (*Encode)(u32)>
void encodeRow16(const u32* src, u32 width, u8* dst) {
    for (size_t x = 0; x < width; ++x) writeLE16(dst + 2 * x, Encode(src[x]));
}
}  // namespace

void convertFromRGBA8888(const u32* src, GeBufferFormat fmt, u32 width, u8* dst) {
    switch (fmt) {
    case GE_FORMAT_565: encodeRow16<encode5650>(src, width, dst); break;
    case GE_FORMAT_5551: encodeRow16<encode5551>(src, width, dst); break;
    case GE_FORMAT_4444: encodeRow16<encode4444>(src, width, dst); break;
    case GE_FORMAT_8888:
        for (size_t x = 0; x < width; ++x) writeLE32(dst + 4 * x, src[x]);
        break;
    }
}

void convertToRGBA8888(const u8* src, GeBufferFormat fmt, u32 width, u32 height, u32 stridePixels, u32* dst) {
    switch (fmt) {
    case GE_FORMAT_565: convertRows16<decode5650>(src, width, height, stridePixels, dst); break;
    case GE_FORMAT_5551: convertRows16<decode5551>(src, width, height, stridePixels, dst); break;
    case GE_FORMAT_4444: convertRows16<decode4444>(src, width, height, stridePixels, dst); break;
    case GE_FORMAT_8888:
        for (u32 y = 0; y < height; ++y) {
            const u8* row = src + size_t(y) * stridePixels * 4;
            u32* out = dst + size_t(y) * width;
            for (size_t x = 0; x < width; ++x) out[x] = readLE32(row + 4 * x);
        }
        break;
    }
}

}  // namespace ge
