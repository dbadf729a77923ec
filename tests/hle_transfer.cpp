// SPDX-License-Identifier: MIT
// Block transfers (docs/ge-rules.md §3.11). The overlap expectations are pspautotests'
// gpu/transfer/overlap.expected, recorded on a PSP.
#include <gtest/gtest.h>

#include <cstring>

#include "hle/renderer.h"

using namespace ge;

namespace {

TransferPacket packet(u32 src, u32 srcStride, u32 dst, u32 dstStride, u32 w, u32 h, u32 bpp) {
    TransferPacket t;
    t.src = src;
    t.srcStride = srcStride;
    t.dst = dst;
    t.dstStride = dstStride;
    t.width = w;
    t.height = h;
    t.bpp = bpp;
    return t;
}

TEST(Transfer, CopiesRowsWithPositionsAndStrides) {
    Memory mem;
    const u32 src = 0x08100000, dst = 0x04000000;
    for (u32 i = 0; i < 64 * 4; ++i) mem.write32(src + 4 * i, 0xA0000000u + i);  // 64-pixel rows
    TransferPacket t = packet(src, 64, dst, 32, 3, 2, 4);
    t.srcX = 5;
    t.srcY = 1;
    t.dstX = 2;
    t.dstY = 3;
    EXPECT_EQ(performTransfer(mem, t), 0u);
    // Row r: src pixel (5 + x, 1 + r) → dst pixel (2 + x, 3 + r).
    for (u32 r = 0; r < 2; ++r)
        for (u32 x = 0; x < 3; ++x)
            EXPECT_EQ(mem.read32(dst + 4 * ((3 + r) * 32 + 2 + x)), 0xA0000000u + (1 + r) * 64 + 5 + x);
    EXPECT_EQ(mem.read32(dst + 4 * (3 * 32 + 1)), 0u);  // left of the rectangle
    EXPECT_EQ(mem.read32(dst + 4 * (3 * 32 + 5)), 0u);  // right of it
    EXPECT_EQ(mem.read32(dst + 4 * (5 * 32 + 2)), 0u);  // below it

    // 16-bit pixels.
    mem.write16(src + 2 * (64 + 1), 0xBEEF);
    TransferPacket h = packet(src, 64, dst + 0x1000, 8, 1, 1, 2);
    h.srcX = 1;
    h.srcY = 1;
    EXPECT_EQ(performTransfer(mem, h), 0u);
    EXPECT_EQ(mem.read16(dst + 0x1000), 0xBEEF);
}

// pat gpu/transfer/overlap: VRAM bytes i & 0xFF, then 0x4000 bytes of 0xFF at the destination,
// then a 16-row transfer of 1024-byte rows from 0x04000000 to 0x04000000 + off.
struct OverlapResult {
    int cmpSign;
    u8 m1a, m1b, m2a, m2b;
};
OverlapResult runOverlap(u32 off, u32 bpp, u32 probe) {
    Memory mem;
    u8* v = mem.vram();
    for (u32 i = 0; i < 0x4000; ++i) v[i] = u8(i);
    std::memset(v + off, 0xFF, 0x4000);
    const u32 w = bpp == 4 ? 256 : 512;
    performTransfer(mem, packet(0x04000000, w, 0x04000000 + off, w, w, 16, bpp));
    const int c = std::memcmp(v, v + off, 1024);
    return {c < 0 ? -1 : c > 0 ? 1 : 0, v[probe], v[probe + 1], v[off + probe], v[off + probe + 1]};
}

TEST(Transfer, OverlapMatchesHardware) {
    for (u32 bpp : {2u, 4u}) {
        // Overlap 0x50 and 0x40: the copy smears, both regions compare equal.
        OverlapResult r = runOverlap(0x50, bpp, 0x4F);
        EXPECT_EQ(r.cmpSign, 0) << bpp;
        EXPECT_EQ(r.m1a, 79);
        EXPECT_EQ(r.m1b, 0);
        EXPECT_EQ(r.m2a, 79);
        EXPECT_EQ(r.m2b, 0);
        r = runOverlap(0x40, bpp, 0x3F);
        EXPECT_EQ(r.cmpSign, 0) << bpp;
        EXPECT_EQ(r.m2a, 63);
        EXPECT_EQ(r.m2b, 0);
        // Overlap 0x30, 0x20, 0x10: a clean copy of the original bytes (0xFF from the fill).
        for (u32 off : {0x30u, 0x20u, 0x10u}) {
            r = runOverlap(off, bpp, off - 1);
            EXPECT_EQ(r.cmpSign, -1) << off << " " << bpp;
            EXPECT_EQ(r.m1a, off - 1);
            EXPECT_EQ(r.m1b, 0);
            EXPECT_EQ(r.m2a, off - 1);
            EXPECT_EQ(r.m2b, 255) << off << " " << bpp;
        }
    }
}

TEST(Transfer, VramWrapsInsideTheMirrorWindow) {
    Memory mem;
    const u32 src = 0x08100000;
    for (u32 i = 0; i < 32; ++i) mem.write8(src + i, u8(0x40 + i));
    // 16 pixels × 2 bytes starting 16 bytes before the end of the last mirror: wraps to 0x04000000.
    EXPECT_EQ(performTransfer(mem, packet(src, 16, 0x047FFFF0, 16, 16, 1, 2)), 0u);
    EXPECT_EQ(mem.vram()[0x1FFFF0], 0x40);
    EXPECT_EQ(mem.vram()[0x1FFFFF], 0x4F);
    EXPECT_EQ(mem.vram()[0], 0x50);
    EXPECT_EQ(mem.vram()[15], 0x5F);
    // Row 1 of a transfer whose rows pass 0x04800000 wraps as well (stride 512 × 2 bytes).
    mem.write16(src + 1024, 0x1234);
    EXPECT_EQ(performTransfer(mem, packet(src, 512, 0x047FFF00, 512, 1, 2, 2)), 0u);
    EXPECT_EQ(mem.read16(0x04000300), 0x1234);
    // Reading from VRAM through a mirror sees the same linear bytes.
    mem.vram()[0x100] = 0x77;
    EXPECT_EQ(performTransfer(mem, packet(0x04600100, 8, src, 8, 1, 1, 2)), 0u);
    EXPECT_EQ(mem.read8(src), 0x77);
}

TEST(Transfer, RowsOutOfRangeAreSkippedAndCounted) {
    Memory mem;
    const u32 end = Memory::kRamBase + mem.ramSize();
    // 1024-byte rows; only row 0 of the source lies inside RAM.
    mem.write32(end - 1024, 0xCAFEBABE);
    EXPECT_EQ(performTransfer(mem, packet(end - 1024, 256, 0x04000000, 256, 256, 3, 4)), 2u);
    EXPECT_EQ(mem.read32(0x04000000), 0xCAFEBABEu);
    // Unmapped source: every row skipped, the destination untouched.
    mem.write32(0x04001000, 0x11111111);
    EXPECT_EQ(performTransfer(mem, packet(0x00000000, 8, 0x04001000, 8, 8, 4, 4)), 4u);
    EXPECT_EQ(mem.read32(0x04001000), 0x11111111u);
    // Unmapped destination.
    EXPECT_EQ(performTransfer(mem, packet(0x04000000, 8, 0x02000000, 8, 8, 4, 4)), 4u);
    // Degenerate packets copy nothing.
    EXPECT_EQ(performTransfer(mem, packet(0x04000000, 8, 0x04001000, 8, 0, 4, 4)), 0u);
    EXPECT_EQ(mem.read32(0x04001000), 0x11111111u);
}

}  // namespace
