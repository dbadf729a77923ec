// SPDX-License-Identifier: MIT
// Guest memory for the dump player (see replay_memory.h for the rules and their source).
#include "hle/dump/replay_memory.h"

#include <algorithm>

#include "hle/dump/player.h"

namespace ge::dump {

u32 GuestHeap::alloc(u32 size, bool fromTop) {
    if (size == 0 || size > end_ - base_) return 0;
    const u32 need = (size + kGrain - 1) & ~(kGrain - 1);
    // Free gaps between the used blocks, bottom up: gap k ends where used_[k] starts.
    auto gapStart = [&](size_t k) { return k == 0 ? base_ : used_[k - 1].start + used_[k - 1].size; };
    auto gapEnd = [&](size_t k) { return k == used_.size() ? end_ : used_[k].start; };
    const size_t gaps = used_.size() + 1;
    for (size_t i = 0; i < gaps; ++i) {
        const size_t k = fromTop ? gaps - 1 - i : i;
        const u32 s = gapStart(k), e = gapEnd(k);
        if (e - s < need) continue;
        const u32 at = fromTop ? e - need : s;
        used_.insert(used_.begin() + std::ptrdiff_t(k), Block{at, need});
        return at;
    }
    return 0;
}

void GuestHeap::free(u32 addr) {
    auto it = std::find_if(used_.begin(), used_.end(), [&](const Block& b) { return b.start == addr; });
    if (it != used_.end()) used_.erase(it);
}

void PushbufMapper::copyIn(u32 guest, u32 bufpos, u32 size) {
    // The player's own memory copy, as Memory::MemcpyUnchecked in PPSSPP's BufMapping.
    target_.write(guest, pushbuf_.data() + bufpos, size);
    stats_.bytesCopied += size;
}

u32 PushbufMapper::map(u32 bufpos, u32 size, const std::function<void()>& flush) {
    // A zero-size payload is taken as one byte so that it maps to its own slab.
    const u32 last = bufpos + (size ? size - 1 : 0);
    if (bufpos / kSlabSize == last / kSlabSize) {
        Slab& recent = slabs_[lastSlab_];
        if (recent.guest && recent.bufpos == bufpos / kSlabSize * kSlabSize) {
            recent.lastUsed = generation_;
            return recent.guest + (bufpos - recent.bufpos);
        }
        return mapSlab(bufpos, flush);
    }
    return mapExtra(bufpos, size, flush);
}

u32 PushbufMapper::mapSlab(u32 bufpos, const std::function<void()>& flush) {
    const u32 slabPos = bufpos / kSlabSize * kSlabSize;
    u32 best = 0;
    for (u32 i = 0; i < kSlabCount; ++i) {
        Slab& s = slabs_[i];
        if (s.guest && s.bufpos == slabPos) {
            s.lastUsed = generation_;
            return s.guest + (bufpos - slabPos);
        }
        if (age(s) > age(slabs_[best])) best = i;
    }
    // The memory is about to change: let the GE finish what reads it.
    flush();
    Slab& s = slabs_[best];
    if (!s.guest) {
        s.guest = heap_.alloc(kSlabSize, false);
        if (!s.guest) {
            ++stats_.failures;
            return 0;
        }
    }
    s.bufpos = slabPos;
    // Bytes past the push buffer's end keep what the slab held before.
    const u32 avail = slabPos < pushbuf_.size() ? u32(pushbuf_.size()) - slabPos : 0;
    copyIn(s.guest, slabPos, std::min<u32>(kSlabSize, avail));
    ++generation_;
    s.lastUsed = generation_;
    lastSlab_ = best;
    ++stats_.slabMaps;
    return s.guest + (bufpos - slabPos);
}

bool PushbufMapper::allocExtra(Extra& e, u32 bufpos, u32 size) {
    if (e.guest) heap_.free(e.guest);
    e = Extra{};
    const u32 g = heap_.alloc(size, false);
    if (!g) return false;
    e = Extra{g, bufpos, size};
    copyIn(g, bufpos, size);
    return true;
}

u32 PushbufMapper::mapExtra(u32 bufpos, u32 size, const std::function<void()>& flush) {
    for (const Extra& e : extras_)
        if (e.guest && e.bufpos == bufpos && e.size >= size) return e.guest;
    flush();
    Extra& e = extras_[nextExtra_];
    nextExtra_ = (nextExtra_ + 1) % kExtraCount;
    if (!allocExtra(e, bufpos, size)) {
        // As PPSSPP: free every extra (the list has run, none is in use) and try once more.
        for (Extra& x : extras_) {
            if (x.guest) heap_.free(x.guest);
            x = Extra{};
        }
        if (!allocExtra(e, bufpos, size)) {
            ++stats_.failures;
            return 0;
        }
    }
    ++stats_.extraMaps;
    return e.guest;
}

}  // namespace ge::dump
