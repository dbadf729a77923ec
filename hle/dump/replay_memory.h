// SPDX-License-Identifier: MIT
// Where the dump player puts the dump's bytes in guest memory, as PPSSPP's player does
// (GPU/Debugger/Playback.cpp: `BufMapping`, and the kernel's `userMemory` BlockAllocator behind it).
//
// The layout is observable: a draw that reads past its recorded payload (a DXT texture whose rows
// run beyond bufw, a mip level read at a guessed address) sees whatever these rules put there, and
// the moments at which the player has to let the GE catch up before reusing memory are sync points
// of the replay (docs/ppdmp.md §6.2 "When the GE runs"). So the rules are modelled exactly:
//
//  - GuestHeap: first fit from the bottom (or last fit from the top) over user memory
//    [0x08800000, 0x0A000000), sizes rounded up to 256 bytes, as BlockAllocator(256).
//  - PushbufMapper::map: a payload inside one 1 MiB slab of the push buffer is read through a
//    mapping of that whole slab (10 slabs, least recently used replaced; the last one used is
//    checked first). A payload straddling two slabs gets an "extra" copy of exactly its bytes
//    (10 extras, reused when one starts at the same offset and is at least as large, otherwise
//    replaced round robin; when the heap is full all extras are freed and the allocation retried).
//    Remapping a slab or allocating an extra first calls `flush` — the player runs the list so
//    far there, so queued draws never read memory that is about to be overwritten.
#pragma once
#include <functional>
#include <vector>

#include "hle/types.h"

namespace ge::dump {

class ReplayTarget;

class GuestHeap {
public:
    static constexpr u32 kGrain = 256;
    GuestHeap(u32 base, u32 end) : base_(base), end_(end) {}
    // The address of a new block of at least `size` bytes, or 0 when none is free.
    u32 alloc(u32 size, bool fromTop);
    void free(u32 addr);

private:
    struct Block {
        u32 start, size;
    };
    u32 base_, end_;
    std::vector<Block> used_;  // sorted by start
};

struct MapperStats {
    u64 slabMaps = 0;   // slabs (re)filled from the push buffer
    u64 extraMaps = 0;  // extras allocated for straddling payloads
    u64 failures = 0;   // payloads that could not be mapped (heap full)
    u64 bytesCopied = 0;  // push-buffer bytes copied into guest memory
};

class PushbufMapper {
public:
    static constexpr u32 kSlabSize = 1u << 20, kSlabCount = 10, kExtraCount = 10;

    PushbufMapper(const std::vector<u8>& pushbuf, ReplayTarget& target, GuestHeap& heap)
        : pushbuf_(pushbuf), target_(target), heap_(heap) {}

    // Guest address of push-buffer bytes [bufpos, bufpos + size), mapped as described above;
    // 0 when no memory could be had. The caller checked that the range lies in the push buffer.
    u32 map(u32 bufpos, u32 size, const std::function<void()>& flush);

    const MapperStats& stats() const { return stats_; }

private:
    struct Slab {
        u32 guest = 0;  // 0: never allocated
        u32 bufpos = 0;
        u64 lastUsed = 0;
    };
    struct Extra {
        u32 guest = 0, bufpos = 0, size = 0;
    };
    u32 mapSlab(u32 bufpos, const std::function<void()>& flush);
    u32 mapExtra(u32 bufpos, u32 size, const std::function<void()>& flush);
    bool allocExtra(Extra& e, u32 bufpos, u32 size);
    u64 age(const Slab& s) const { return s.guest ? generation_ - s.lastUsed : ~u64(0); }
    void copyIn(u32 guest, u32 bufpos, u32 size);

    const std::vector<u8>& pushbuf_;
    ReplayTarget& target_;
    GuestHeap& heap_;
    Slab slabs_[kSlabCount];
    u32 lastSlab_ = 0;
    u64 generation_ = 0;
    Extra extras_[kExtraCount];
    u32 nextExtra_ = 0;
    MapperStats stats_;
};

}  // namespace ge::dump
