// SPDX-License-Identifier: MIT
#include "hle/memory.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <new>
#include <vector>

namespace ge {

namespace {

size_t pageSize() {
    static const size_t size = size_t(::sysconf(_SC_PAGESIZE));
    return size;
}

size_t pageRound(size_t n) { return (n + pageSize() - 1) / pageSize() * pageSize(); }

// Zeroed pages on first touch; nothing is written or reserved up front. An inaccessible page on
// either side makes a host access that runs off the region fault at once (the heap redzones the
// old new[] buffers had under ASan; exact at the end for page-multiple sizes, as RAM and VRAM are).
//
// `huge`: the region starts on a 2 MiB boundary and is marked MADV_HUGEPAGE, so that a host whose
// transparent huge pages are "madvise" or "always" backs each 2 MiB with one page and one fault.
// VRAM asks for it: it is 2 MiB and a frame touches much of it (frame and depth buffers, textures
// and CLUTs), which took a few hundred 4 KiB faults per render (hot pixel, software model: 1,411
// minor faults in all, 1,071 so). Whole `ge2gl render` over the 20 frametests, five alternating
// runs, median of the per-dump ratios: software model 0.95, GL hw 0.96, GL exact 0.98. RAM does
// not: it is 32 MiB or more, touched in scattered places, and on huge pages it zeroed more than it
// saved (software model: median 0.97, but peak RSS +5 MiB).
u8* mapZeroed(size_t size, bool huge = false) {
    const size_t page = pageSize(), bytes = pageRound(size);
    constexpr size_t kHugePage = size_t(2) << 20;
    const size_t slack = huge ? kHugePage : 0;  // room to move the region to a 2 MiB boundary
    const size_t total = bytes + 2 * page + slack;
    void* p = mmap(nullptr, total, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    u8* const base = static_cast<u8*>(p);
    u8* region = base + page;
    if (huge) {
        // Keep [guard page, region, guard page] and give the slack before and after back, so that
        // unmapZeroed finds the same layout either way.
        const uintptr_t aligned = (reinterpret_cast<uintptr_t>(region) + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
        region = reinterpret_cast<u8*>(aligned);
        u8* const keepBegin = region - page;
        u8* const keepEnd = region + bytes + page;
        if (keepBegin > base) munmap(base, size_t(keepBegin - base));
        if (base + total > keepEnd) munmap(keepEnd, size_t(base + total - keepEnd));
    }
    if (mprotect(region, bytes, PROT_READ | PROT_WRITE) != 0) {
        munmap(region - page, bytes + 2 * page);
        throw std::bad_alloc();
    }
    // Advice only: where the kernel has no transparent huge pages this fails and changes nothing.
    if (huge) (void)madvise(region, bytes, MADV_HUGEPAGE);
    return region;
}

void unmapZeroed(u8* region, size_t size) { munmap(region - pageSize(), pageRound(size) + 2 * pageSize()); }

// Makes a mapping made by mapZeroed read zero again, giving its touched pages back.
void rezero(u8* p, size_t size) {
    if (madvise(p, pageRound(size), MADV_DONTNEED) != 0) std::memset(p, 0, size);
}

// Zeroes the resident pages of a mapping made by mapZeroed and leaves them resident; pages never
// touched stay unmapped (mincore tells which are which).
void zeroResident(u8* p, size_t size) {
    const size_t page = pageSize(), pages = pageRound(size) / page;
    std::vector<unsigned char> resident(pages);
    if (mincore(p, pages * page, resident.data()) != 0) {
        std::memset(p, 0, size);
        return;
    }
    for (size_t i = 0; i < pages;) {
        if (!(resident[i] & 1)) {
            ++i;
            continue;
        }
        size_t j = i;
        while (j < pages && (resident[j] & 1)) ++j;
        std::memset(p + i * page, 0, std::min(j * page, size) - i * page);
        i = j;
    }
}

}  // namespace

Memory::Memory(u32 ramSize) : ramSize_(ramSize) {
    vram_ = mapZeroed(kVramSize, true);
    ownsVram_ = true;
    if (ramSize_) {
        try {
            ram_ = mapZeroed(ramSize_);
        } catch (...) {
            unmapZeroed(vram_, kVramSize);
            throw;
        }
        ownsRam_ = true;
    }
}

Memory::Memory(u8* hostRam, u32 ramSize, u8* hostVram) : ram_(hostRam), vram_(hostVram), ramSize_(ramSize) {
    if (!vram_) {
        vram_ = mapZeroed(kVramSize, true);
        ownsVram_ = true;
    }
    if (!ram_) ramSize_ = 0;
}

Memory::~Memory() {
    if (ownsRam_) unmapZeroed(ram_, ramSize_);
    if (ownsVram_) unmapZeroed(vram_, kVramSize);
}

void Memory::clear() {
    if (ram_ && ramSize_) {
        if (ownsRam_) keepPages_ ? zeroResident(ram_, ramSize_) : rezero(ram_, ramSize_);
        else std::memset(ram_, 0, ramSize_);
    }
    if (ownsVram_) keepPages_ ? zeroResident(vram_, kVramSize) : rezero(vram_, kVramSize);
    else std::memset(vram_, 0, kVramSize);
    std::memset(scratch_, 0, sizeof scratch_);
    edramTrans_ = 0x400;
    badAccesses_ = 0;
    lastBad_ = 0;
}

const u8* Memory::ptr(u32 addr, u32 size) const {
    u32 a = normalize(addr);
    u64 end = u64(a) + size;
    if (a >= kVramBase && a < kVramMirrorsEnd) {
        u32 off = (a - kVramBase) & (kVramSize - 1);
        // The range must stay inside one 2 MiB mirror.
        if (u64(off) + size > kVramSize) return nullptr;
        return vram_ + off;
    }
    if (a >= kRamBase && ram_) {
        if (end > u64(kRamBase) + ramSize_) return nullptr;
        return ram_ + (a - kRamBase);
    }
    if (a >= kScratchBase && end <= u64(kScratchBase) + kScratchSize) return scratch_ + (a - kScratchBase);
    return nullptr;
}

u8* Memory::ptr(u32 addr, u32 size) { return const_cast<u8*>(static_cast<const Memory*>(this)->ptr(addr, size)); }

u32 Memory::validSize(u32 addr, u32 maxSize) const {
    u32 a = normalize(addr);
    u64 avail = 0;
    if (a >= kVramBase && a < kVramMirrorsEnd)
        avail = kVramSize - ((a - kVramBase) & (kVramSize - 1));
    else if (a >= kRamBase && ram_ && a - kRamBase < ramSize_)
        avail = u64(kRamBase) + ramSize_ - a;
    else if (a >= kScratchBase && a < kScratchBase + kScratchSize)
        avail = kScratchBase + kScratchSize - a;
    return u32(std::min<u64>(avail, maxSize));
}

u8 Memory::read8(u32 addr) const {
    const u8* p = ptr(addr, 1);
    if (!p) return noteBadAccess(addr), 0;
    return *p;
}
u16 Memory::read16(u32 addr) const {
    const u8* p = ptr(addr, 2);
    if (!p) return noteBadAccess(addr), 0;
    return readLE16(p);
}
u32 Memory::read32(u32 addr) const {
    const u8* p = ptr(addr, 4);
    if (!p) return noteBadAccess(addr), 0;
    return readLE32(p);
}
void Memory::write8(u32 addr, u8 v) {
    if (u8* p = ptr(addr, 1)) *p = v;
    else noteBadAccess(addr);
}
void Memory::write16(u32 addr, u16 v) {
    if (u8* p = ptr(addr, 2)) writeLE16(p, v);
    else noteBadAccess(addr);
}
void Memory::write32(u32 addr, u32 v) {
    if (u8* p = ptr(addr, 4)) writeLE32(p, v);
    else noteBadAccess(addr);
}
bool Memory::read(u32 addr, void* dst, u32 size) const {
    if (size == 0) return true;
    const u8* p = ptr(addr, size);
    if (!p) return noteBadAccess(addr), false;
    std::memmove(dst, p, size);
    return true;
}
bool Memory::write(u32 addr, const void* src, u32 size) {
    if (size == 0) return true;
    u8* p = ptr(addr, size);
    if (!p) return noteBadAccess(addr), false;
    std::memmove(p, src, size);
    return true;
}
bool Memory::fill(u32 addr, u8 value, u32 size) {
    if (size == 0) return true;
    u8* p = ptr(addr, size);
    if (!p) return noteBadAccess(addr), false;
    std::memset(p, value, size);
    return true;
}

bool Memory::setEdramTranslation(u32 value) {
    if (value != 0 && value != 0x200 && value != 0x400 && value != 0x800 && value != 0x1000) return false;
    edramTrans_ = value;
    return true;
}

// Mirror permutations measured on hardware (docs/ge-rules.md §7.3, pat gpu/ge/edramswizzle).
namespace {

u32 linearToMirrorFor(u32 T, u32 i, int mirror) {
    switch (mirror & 3) {
    case 0:
    case 2: return i;
    case 1: return T == 0 ? (i ^ 0x600) : (i ^ (8 * T | 0x40));
    default: {
        if (T == 0) {
            u32 b = (i >> 9) & 3;
            return (b == 0 || b == 3) ? (i ^ 0x600) : i;
        }
        int k = 0;
        while ((1u << k) < T) ++k;
        u32 j = i ^ (8 * T);
        // Rebuild bits k-1..5: bit 5 = NOT bit 6 of i; bits k-2..6 = bits k-1..7 of i; bit k-1 = bit 5 of i.
        u32 fieldMask = ((1u << k) - 1) & ~0x1Fu;
        j &= ~fieldMask;
        j |= ((~i >> 6) & 1) << 5;
        for (int b = 6; b <= k - 2; ++b) j |= ((i >> (b + 1)) & 1) << b;
        j |= ((i >> 5) & 1) << (k - 1);
        return j;
    }
    }
}

}  // namespace

u32 Memory::linearToMirror(u32 i, int mirror) const { return linearToMirrorFor(edramTrans_, i, mirror); }

const u16* Memory::mirror3Inverse(u32 edramTrans) {
    // One table per valid translation value (0, 0x200, 0x400, 0x800, 0x1000), built once.
    static std::once_flag once[5];
    static std::unique_ptr<u16[]> tables[5];
    const int slot = edramTrans == 0 ? 0 : edramTrans == 0x200 ? 1 : edramTrans == 0x400 ? 2 : edramTrans == 0x800 ? 3 : 4;
    std::call_once(once[slot], [&] {
        auto t = std::make_unique<u16[]>(0x10000);
        for (u32 i = 0; i < 0x10000; ++i) t[linearToMirrorFor(edramTrans, i, 3) & 0xFFFF] = u16(i);
        tables[slot] = std::move(t);
    });
    return tables[slot].get();
}

u32 Memory::mirrorToLinear(u32 off, int mirror) const {
    switch (mirror & 3) {
    case 0:
    case 2: return off;
    case 1: return linearToMirror(off, 1);  // XOR: its own inverse
    default: return (off & ~0xFFFFu) | mirror3Inverse(edramTrans_)[off & 0xFFFF];
    }
}

u8 Memory::readMirrored(u32 addr) const {
    u32 a = normalize(addr);
    if (a < kVramBase || a >= kVramMirrorsEnd) return read8(addr);
    int mirror = int((a - kVramBase) >> 21);
    u32 lin = mirrorToLinear((a - kVramBase) & (kVramSize - 1), mirror) & (kVramSize - 1);
    return vram_[lin];
}

void Memory::writeMirrored(u32 addr, u8 v) {
    u32 a = normalize(addr);
    if (a < kVramBase || a >= kVramMirrorsEnd) return write8(addr, v);
    int mirror = int((a - kVramBase) >> 21);
    u32 lin = mirrorToLinear((a - kVramBase) & (kVramSize - 1), mirror) & (kVramSize - 1);
    vram_[lin] = v;
}

}  // namespace ge
