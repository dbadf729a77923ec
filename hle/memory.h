// SPDX-License-Identifier: MIT
// The PSP address space as the GE sees it (docs/ge-rules.md §7, manual §22).
//
// Every access is bounds-checked. Host pointers are handed out only for ranges that lie wholly
// inside one region; a wild address yields nullptr / zero and is counted in badAccesses(), never
// undefined behaviour. Address bits 31..28 (uncached 0x4…, kernel 0x8…/0xC… views) are dropped
// as the GE does.
//
// VRAM: 2 MiB at 0x04000000 with three mirrors up to 0x047FFFFF. For drawing, all four mirrors
// address the same linear bytes (as PPSSPP does); readMirrored()/writeMirrored() give the exact
// byte permutation measured on hardware for mirrors 1 and 3 (ge-rules.md §7.3), for CPU-side
// reads and writes through the swizzled views.
//
// Owned RAM and VRAM are anonymous private mappings (MAP_NORESERVE): the kernel hands out zeroed
// pages on first touch, so a Memory costs nothing proportional to its 64 MiB address space, and a
// replay pays only for the pages it writes (ge2gl bench --backend null). clear() gives the pages
// back (madvise(MADV_DONTNEED)) so one Memory can serve many replays. An inaccessible page guards
// each side of both mappings.
#pragma once
#include <memory>
#include <vector>

#include "hle/types.h"

namespace ge {

class Memory {
public:
    static constexpr u32 kScratchBase = 0x00010000, kScratchSize = 0x4000;
    static constexpr u32 kVramBase = 0x04000000, kVramSize = 0x200000, kVramMirrorsEnd = 0x04800000;
    static constexpr u32 kRamBase = 0x08000000;
    static constexpr u32 kDefaultRamSize = 64u << 20;  // PSP-2000+; 32 MiB models use the low half

    explicit Memory(u32 ramSize = kDefaultRamSize);
    // Wrap host-owned buffers (plugin API): nothing is copied or freed by Memory.
    Memory(u8* hostRam, u32 ramSize, u8* hostVram);
    ~Memory();

    Memory(const Memory&) = delete;
    Memory& operator=(const Memory&) = delete;

    // Back to the state of a fresh Memory of the same size: RAM, VRAM and scratchpad read zero,
    // eDRAM translation 0x400, no bad accesses counted. Owned pages are returned to the kernel
    // (cost proportional to the pages touched, not to the address space); host-owned buffers
    // are zero-filled.
    void clear();
    // With `keep`, clear() zeroes the owned pages a replay touched in place instead of handing them
    // back: the next replay writes the same pages without a page fault each, as an emulator's
    // memory, allocated once, never faults again. `ge2gl bench --warm` (steady state) uses it; the
    // pages stay resident until the Memory is destroyed.
    void keepPagesOnClear(bool keep) { keepPages_ = keep; }

    static u32 normalize(u32 addr) { return addr & 0x0FFFFFFF; }
    static bool isVram(u32 addr) {
        u32 a = normalize(addr);
        return a >= kVramBase && a < kVramMirrorsEnd;
    }
    // The address drawing sees: bits 31..28 dropped and the four VRAM mirrors folded onto the
    // linear 2 MiB (all mirrors are the same bytes for drawing, above). Both backends key their
    // overlap tests (texture caches, render targets) on it.
    static u32 drawingAddress(u32 addr) {
        const u32 a = normalize(addr);
        return isVram(a) ? kVramBase | (a & (kVramSize - 1)) : a;
    }
    static bool isRam(u32 addr, u32 ramSize) {
        u32 a = normalize(addr);
        return a >= kRamBase && a - kRamBase < ramSize;
    }

    // Host pointer to [addr, addr+size) or nullptr when the range is not wholly valid.
    u8* ptr(u32 addr, u32 size);
    const u8* ptr(u32 addr, u32 size) const;
    bool valid(u32 addr, u32 size) const { return ptr(addr, size) != nullptr; }
    // Number of bytes readable contiguously from addr (0 if addr is invalid), at most maxSize.
    u32 validSize(u32 addr, u32 maxSize) const;

    u8 read8(u32 addr) const;
    u16 read16(u32 addr) const;
    u32 read32(u32 addr) const;
    void write8(u32 addr, u8 v);
    void write16(u32 addr, u16 v);
    void write32(u32 addr, u32 v);
    // Whole-range copies; false (and nothing copied) when the range is not wholly valid.
    bool read(u32 addr, void* dst, u32 size) const;
    bool write(u32 addr, const void* src, u32 size);
    bool fill(u32 addr, u8 value, u32 size);

    u8* ram() { return ram_; }
    u8* vram() { return vram_; }
    const u8* ram() const { return ram_; }
    const u8* vram() const { return vram_; }
    u32 ramSize() const { return ramSize_; }

    // eDRAM address translation (sceGeEdramSetAddrTranslation): 0, 0x200, 0x400, 0x800, 0x1000.
    u32 edramTranslation() const { return edramTrans_; }
    bool setEdramTranslation(u32 value);
    // Byte access through any VRAM view with the hardware's mirror permutation applied.
    u8 readMirrored(u32 addr) const;
    void writeMirrored(u32 addr, u8 v);
    // Linear VRAM offset of the byte seen at `offset` inside mirror m (0–3).
    u32 mirrorToLinear(u32 offset, int mirror) const;
    u32 linearToMirror(u32 linear, int mirror) const;

    u64 badAccesses() const { return badAccesses_; }
    u32 lastBadAddress() const { return lastBad_; }
    void noteBadAccess(u32 addr) const {
        ++badAccesses_;
        lastBad_ = addr;
    }

private:
    // Inverse of the mirror-3 permutation on the low 16 bits for one translation value: built on
    // first use and shared by every Memory of the process (only CPU-side mirrored access needs it).
    static const u16* mirror3Inverse(u32 edramTrans);

    bool ownsRam_ = false, ownsVram_ = false;  // anonymous mappings to munmap
    bool keepPages_ = false;                   // keepPagesOnClear
    u8* ram_ = nullptr;
    u8* vram_ = nullptr;
    u32 ramSize_ = 0;
    u8 scratch_[kScratchSize] = {};
    u32 edramTrans_ = 0x400;
    mutable u64 badAccesses_ = 0;
    mutable u32 lastBad_ = 0;
};

}  // namespace ge
