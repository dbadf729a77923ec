// SPDX-License-Identifier: MIT
// Block transfer (CMD_XSTART): docs/ge-rules.md §3.11.
//
// Row r copies width·bpp bytes from src + ((sy + r)·srcW + sx)·bpp to dst + ((dy + r)·dstW + dx)·bpp.
//
// VRAM: an address in 0x04000000–0x047FFFFF wraps inside that window (observed: pat
// gpu/transfer/mirrors), and, as for drawing (memory.h), all four mirrors address the same
// linear 2 MiB, so every VRAM byte is vram[offset & 0x1FFFFF]. (On hardware a transfer through
// mirrors 1/3 sees the same byte permutation as the CPU; our VRAM image is linear — depth included —
// so applying the permutation here would scramble what the renderers wrote.)
//
// Overlap: the GE copies each row front to back in 64-byte bursts (read a burst, write it). That
// reproduces pat gpu/transfer/overlap.expected: with dst = src + 0x40 or + 0x50 the copy smears
// (every burst after the first re-reads bytes it has just written) while dst = src + 0x10…0x30 is
// a clean copy. A whole-row temporary would not match the 0x40/0x50 cases.
//
// Rows whose bytes are not valid guest memory (outside RAM/VRAM/scratchpad, or running off the
// end of RAM) are skipped and counted.
#include <algorithm>

#include "hle/renderer.h"

namespace ge {

namespace {

constexpr u32 kBurst = 64;

struct Side {
    bool vram = false;
    u32 vramOff = 0;  // base offset inside VRAM (vram sides)
    u32 base = 0;     // guest address (other sides)
    u32 stride = 0, x = 0, y = 0;
};

Side makeSide(u32 addr, u32 stride, u32 x, u32 y) {
    Side s;
    s.vram = Memory::isVram(addr);
    s.vramOff = Memory::normalize(addr) - Memory::kVramBase;
    s.base = addr;
    s.stride = stride;
    s.x = x;
    s.y = y;
    return s;
}

// Byte offset of row r relative to the side's base.
inline u64 rowOffset(const Side& s, u32 r, u32 bpp) { return (u64(s.y + r) * s.stride + s.x) * bpp; }

}  // namespace

u32 performTransfer(Memory& mem, const TransferPacket& t) {
    if (t.width == 0 || t.height == 0 || (t.bpp != 2 && t.bpp != 4)) return 0;
    const Side src = makeSide(t.src, t.srcStride, t.srcX, t.srcY);
    const Side dst = makeSide(t.dst, t.dstStride, t.dstX, t.dstY);
    const u32 bytes = t.width * t.bpp;
    u8* vram = mem.vram();
    u32 skipped = 0;
    u8 burst[kBurst];

    for (u32 r = 0; r < t.height; ++r) {
        const u64 so = rowOffset(src, r, t.bpp), doff = rowOffset(dst, r, t.bpp);
        const u8* sp = nullptr;
        u8* dp = nullptr;
        u32 sv = 0, dv = 0;  // VRAM offsets (mod 2 MiB) for VRAM sides
        if (src.vram) {
            sv = u32((src.vramOff + so) & (Memory::kVramSize - 1));
            if (sv + bytes <= Memory::kVramSize) sp = vram + sv;  // no wrap inside this row
        } else {
            const u64 a = u64(src.base) + so;
            if (a <= 0xFFFFFFFFull) sp = mem.ptr(u32(a), bytes);
            if (!sp) {
                ++skipped;
                continue;
            }
        }
        if (dst.vram) {
            dv = u32((dst.vramOff + doff) & (Memory::kVramSize - 1));
            if (dv + bytes <= Memory::kVramSize) dp = vram + dv;
        } else {
            const u64 a = u64(dst.base) + doff;
            if (a <= 0xFFFFFFFFull) dp = mem.ptr(u32(a), bytes);
            if (!dp) {
                ++skipped;
                continue;
            }
        }
        for (u32 k = 0; k < bytes; k += kBurst) {
            const u32 n = std::min(kBurst, bytes - k);
            if (sp) {
                std::memcpy(burst, sp + k, n);
            } else {  // VRAM row wrapping at the end of the 2 MiB
                for (u32 i = 0; i < n; ++i) burst[i] = vram[(sv + k + i) & (Memory::kVramSize - 1)];
            }
            if (dp) {
                std::memcpy(dp + k, burst, n);
            } else {
                for (u32 i = 0; i < n; ++i) vram[(dv + k + i) & (Memory::kVramSize - 1)] = burst[i];
            }
        }
    }
    return skipped;
}

}  // namespace ge
