// SPDX-License-Identifier: MIT
// 16-bit pixel layouts (docs/ge-rules.md §5.4, §6.1, §8.8): expected values computed by hand from
// the bit layouts and the replication / truncation rules.
#include <gtest/gtest.h>

#include "hle/pixel_format.h"

using namespace ge;

namespace {

TEST(PixelFormat, Decode5650ChannelsAndReplication) {
    EXPECT_EQ(decode5650(0x0000), 0xFF000000u);  // alpha always 255
    EXPECT_EQ(decode5650(0xFFFF), 0xFFFFFFFFu);
    EXPECT_EQ(decode5650(0x001F), 0xFF0000FFu);  // red in bits 4..0
    EXPECT_EQ(decode5650(0x07E0), 0xFF00FF00u);  // green 10..5
    EXPECT_EQ(decode5650(0xF800), 0xFFFF0000u);  // blue 15..11
    // R = 16: 16<<3 | 16>>2 = 0x84; G = 32: 32<<2 | 32>>4 = 0x82.
    EXPECT_EQ(decode5650(0x0010), 0xFF000084u);
    EXPECT_EQ(decode5650(0x0400), 0xFF008200u);
}

TEST(PixelFormat, Decode5551) {
    EXPECT_EQ(decode5551(0x8000), 0xFF000000u);
    EXPECT_EQ(decode5551(0x7FFF), 0x00FFFFFFu);
    EXPECT_EQ(decode5551(0x0001), 0x00000008u);   // 1 → 1<<3 | 1>>2 = 8
    EXPECT_EQ(decode5551(0x03E0), 0x0000FF00u);   // green 9..5
    EXPECT_EQ(decode5551(0x7C00), 0x00FF0000u);   // blue 14..10
}

TEST(PixelFormat, Decode4444) {
    EXPECT_EQ(decode4444(0x1234), 0x11223344u);  // R 3..0 = 4 → 0x44, A 15..12 = 1 → 0x11
    EXPECT_EQ(decode4444(0xF000), 0xFF000000u);
    EXPECT_EQ(decode4444(0x0F0F), 0x00FF00FFu);
}

TEST(PixelFormat, DispatchMatchesFormat) {
    EXPECT_EQ(decodePixel16(0x1234, GE_FORMAT_565), decode5650(0x1234));
    EXPECT_EQ(decodePixel16(0x1234, GE_FORMAT_5551), decode5551(0x1234));
    EXPECT_EQ(decodePixel16(0x1234, GE_FORMAT_4444), decode4444(0x1234));
    EXPECT_EQ(encodePixel16(0xFF8387u, GE_FORMAT_565), encode5650(0xFF8387u));
    EXPECT_EQ(encodePixel16(0x80FF8387u, GE_FORMAT_5551), encode5551(0x80FF8387u));
    EXPECT_EQ(encodePixel16(0x80FF8387u, GE_FORMAT_4444), encode4444(0x80FF8387u));
}

TEST(PixelFormat, EncodeTruncates) {
    // R = 0x87 → 0x87>>3 = 16, G = 0x83 → 0x83>>2 = 32, B = 0xFF → 31 (no rounding up).
    EXPECT_EQ(encode5650(0x00FF8387u), u16(16 | 32 << 5 | 31 << 11));
    EXPECT_EQ(encode5650(0x00070307u), 0u);  // every channel below one step truncates to 0
    EXPECT_EQ(encode5551(0x80FFFFFFu), 0xFFFFu);
    EXPECT_EQ(encode5551(0x7FFFFFFFu), 0x7FFFu);  // alpha 0x7F → bit 15 clear
    EXPECT_EQ(encode4444(0x1F2F3F4Fu), 0x1234u);
}

TEST(PixelFormat, EncodeOfDecodeIsIdentity) {
    for (u32 v = 0; v < 0x10000; ++v) {
        ASSERT_EQ(encode5650(decode5650(u16(v))), v);
        ASSERT_EQ(encode5551(decode5551(u16(v))), v);
        ASSERT_EQ(encode4444(decode4444(u16(v))), v);
    }
}

TEST(PixelFormat, ConvertRegionHonoursStride) {
    // 2x2 region of a 5650 buffer with a stride of 4 pixels.
    u8 src[16] = {};
    writeLE16(src + 0, 0x001F);
    writeLE16(src + 2, 0x07E0);
    writeLE16(src + 8, 0xF800);
    writeLE16(src + 10, 0xFFFF);
    writeLE16(src + 4, 0x1234);  // outside the region
    u32 dst[4] = {};
    convertToRGBA8888(src, GE_FORMAT_565, 2, 2, 4, dst);
    EXPECT_EQ(dst[0], 0xFF0000FFu);
    EXPECT_EQ(dst[1], 0xFF00FF00u);
    EXPECT_EQ(dst[2], 0xFFFF0000u);
    EXPECT_EQ(dst[3], 0xFFFFFFFFu);

    u8 src32[24] = {};
    writeLE32(src32 + 0, 0x11223344);
    writeLE32(src32 + 12, 0x55667788);  // row 1 at stride 3 pixels
    u32 d32[2] = {};
    convertToRGBA8888(src32, GE_FORMAT_8888, 1, 2, 3, d32);
    EXPECT_EQ(d32[0], 0x11223344u);  // alpha kept as stored
    EXPECT_EQ(d32[1], 0x55667788u);

    u8 s4[2] = {0x34, 0x12};
    u32 d4 = 0;
    convertToRGBA8888(s4, GE_FORMAT_4444, 1, 1, 1, &d4);
    EXPECT_EQ(d4, 0x11223344u);
}

TEST(PixelFormat, BytesPerPixel) {
    EXPECT_EQ(bytesPerPixel(GE_FORMAT_565), 2u);
    EXPECT_EQ(bytesPerPixel(GE_FORMAT_8888), 4u);
}

}  // namespace
