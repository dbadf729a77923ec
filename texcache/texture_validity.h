// SPDX-License-Identifier: MIT
// When a cached texture is still what guest memory holds: the part of a texture cache both
// backends share. A backend keeps its own storage (the software model decoded texels, the GL
// translator GL textures) as the Payload of a ValidatedCache; the cache decides, for every use,
// whether that payload can be reused, must be rebuilt, or does not exist yet.
//
// The rules (PPSSPP's TextureCacheCommon works the same way: events first, content hash as the
// judge):
//   * key: everything the decoder reads besides memory and the palette bytes — the levels'
//     addresses, buffer widths and sizes, format, swizzle, the CLUT register for palette formats
//     (TextureKey below). A backend may add the palette contents' hash to the key.
//   * content: each entry holds hashTextureLevel (hle/texture_decoder.h: source bytes and the
//     palette bytes used) of each of its levels. A hash decides; no sampling, no heuristics.
//   * events make entries "suspect": guest memory written over their source range
//     (invalidate(addr, size), addresses folded by Memory::drawingAddress), the palette reloaded
//     (clutChanged(), palette formats only), or everything at once (invalidate(0, 0)). A suspect
//     entry is re-hashed when next used and kept if its content is unchanged.
//   * eviction: over the byte budget or the entry count, the least recently used entries go
//     until 3/4 of each is left; the entry in use now never goes.
// Not thread-safe: a backend that looks up from several threads holds its own lock.
#pragma once
#include <algorithm>
#include <bitset>
#include <cstring>
#include <unordered_map>
#include <utility>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/texture_decoder.h"
#include "hle/types.h"

namespace ge::texcache {

constexpr int kMaxLevels = 8;

// The registers that select a texture: levels [first, first + count) of the state's texture.
struct TextureKey {
    u32 addr[kMaxLevels], bufw[kMaxLevels], size[kMaxLevels];
    u32 format, swizzle, clut, multiClut, levels;
    u32 levelTag;  // the first level when the decode depends on which level it is (multi-CLUT), else 0
    u64 clutHash;  // palette contents, where the backend keys on them (else 0)
    bool operator==(const TextureKey& o) const { return std::memcmp(this, &o, sizeof o) == 0; }
};
// clutHash: 0 for a backend that tracks palette reloads by clutChanged() instead.
TextureKey textureKey(const GeState& st, int first, int count, u64 clutHash);
struct TextureKeyHash {
    size_t operator()(const TextureKey& k) const;
};

// True for the palette formats (CLUT4 … CLUT32), whose texels depend on palette RAM.
bool usesClut(const GeState& st);

// Source bytes of levels [first, first + count): [begin, end) in drawing addresses.
void sourceRange(const GeState& st, int first, int count, u32& begin, u32& end);

struct ValidityStats {
    u64 lookups = 0;   // find() calls
    u64 builds = 0;    // payloads built: misses and changed content
    u64 rehashes = 0;  // suspect entries re-hashed
    u64 hits = 0;      // payloads reused
    u64 evicted = 0;   // entries dropped by the budget
};

struct Budget {
    size_t bytes = size_t(192) << 20;
    size_t entries = 4096;
};

template <class Payload>
class ValidatedCache {
public:
    struct Entry {
        Payload payload{};
        u64 hashes[kMaxLevels] = {};
        u32 begin = 0, end = 0;  // source range, drawing addresses
        bool clut = false;
        bool suspect = false;
        u64 lastUse = 0;
        size_t bytes = 0;  // the payload's size, set by the backend after it builds it
    };
    enum class Use { Reuse, Rebuild, Build };

    explicit ValidatedCache(Budget budget = {}) : budget_(budget) {}

    // The entry for `key` (levels [first, first + count) of the state's texture), and what the
    // caller has to do with its payload: Reuse it, Rebuild it (same entry, content changed) or
    // Build it (a new entry). The entry's hashes and range are already current. `onDrop` is
    // called for each entry the budget evicts (before the new entry is made); the returned
    // reference stays valid until the next find() or clear().
    template <class OnDrop>
    std::pair<Entry&, Use> find(const TextureKey& key, const GeState& st, const Memory& mem, int first, int count,
                                OnDrop&& onDrop) {
        ++stats_.lookups;
        ++clock_;
        auto it = entries_.find(key);
        if (it != entries_.end()) {
            Entry& e = it->second;
            e.lastUse = clock_;
            if (!e.suspect) {
                ++stats_.hits;
                return {e, Use::Reuse};
            }
            ++stats_.rehashes;
            e.suspect = false;
            bool same = true;
            u64 now[kMaxLevels] = {};
            for (int l = 0; l < count; ++l) {
                now[l] = hashTextureLevel(mem, st, first + l);
                same = same && now[l] == e.hashes[l];
            }
            if (same) {
                ++stats_.hits;
                return {e, Use::Reuse};
            }
            std::copy(now, now + count, e.hashes);
            ++stats_.builds;
            return {e, Use::Rebuild};
        }
        if (entries_.size() + 1 > budget_.entries || bytes_ > budget_.bytes) evict(onDrop);
        Entry& e = entries_[key];
        for (int l = 0; l < count; ++l) e.hashes[l] = hashTextureLevel(mem, st, first + l);
        sourceRange(st, first, count, e.begin, e.end);
        markPages(e.begin, e.end);
        e.clut = usesClut(st);
        spans_.push_back({e.begin, e.end, e.clut, &e});
        e.lastUse = clock_;
        ++stats_.builds;
        return {e, Use::Build};
    }

    // The backend built or rebuilt `e`'s payload, now `bytes` long.
    template <class OnDrop>
    void setBytes(Entry& e, size_t bytes, OnDrop&& onDrop) {
        bytes_ = bytes_ - e.bytes + bytes;
        e.bytes = bytes;
        if (bytes_ > budget_.bytes) evict(onDrop);
    }

    // Guest memory [addr, addr + size) was written; size 0: any of it may have been.
    void invalidate(u32 addr, u32 size) {
        if (size == 0) {
            for (auto& kv : entries_) kv.second.suspect = true;
            return;
        }
        const u64 begin = Memory::drawingAddress(addr), end = begin + size;
        if (!pagesMarked(begin, end)) return;  // no entry's source there
        for (const Span& sp : spans_)
            if (sp.begin < end && begin < sp.end) sp.entry->suspect = true;
    }
    // Palette RAM was reloaded (CMD_CLOAD): the palette formats' texels may have changed.
    void clutChanged() {
        for (const Span& sp : spans_)
            if (sp.clut) sp.entry->suspect = true;
    }
    template <class OnDrop>
    void clear(OnDrop&& onDrop) {
        for (auto& kv : entries_) onDrop(kv.second);
        entries_.clear();
        spans_.clear();
        bytes_ = 0;
        pages_.reset();
    }

    const ValidityStats& stats() const { return stats_; }
    size_t entries() const { return entries_.size(); }
    size_t bytes() const { return bytes_; }

private:
    // Least recently used first, down to 3/4 of the byte budget and of the entry count; the entry
    // used by the current lookup (lastUse == clock_) stays.
    template <class OnDrop>
    void evict(OnDrop& onDrop) {
        std::vector<std::pair<u64, const TextureKey*>> order;
        order.reserve(entries_.size());
        for (const auto& kv : entries_) order.emplace_back(kv.second.lastUse, &kv.first);
        std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        const size_t bytesTarget = budget_.bytes / 4 * 3, countTarget = budget_.entries / 4 * 3;
        for (const auto& [use, key] : order) {
            if ((bytes_ <= bytesTarget && entries_.size() <= countTarget) || use == clock_) break;
            auto it = entries_.find(*key);
            onDrop(it->second);
            bytes_ -= it->second.bytes;
            entries_.erase(it);
            ++stats_.evicted;
        }
        // The spans of the entries left (entries never move: the map's nodes are stable).
        spans_.clear();
        for (auto& kv : entries_) spans_.push_back({kv.second.begin, kv.second.end, kv.second.clut, &kv.second});
    }

    // Which 64 KiB pages of drawing addresses hold some entry's source bytes, so that a write to
    // none of them (a replay's display-list blocks and vertex payloads, an emulator's writes to
    // its game's RAM) is answered without a walk over every entry. Set as entries are made, reset
    // only when all go: an evicted entry's pages stay marked, which costs a walk, never a miss.
    // Pages from 2^28 on share the last bit.
    static constexpr u32 kPageShift = 16, kPages = 1u << (28 - kPageShift);
    static size_t pageOf(u64 a) { return size_t(std::min<u64>(a >> kPageShift, kPages - 1)); }
    void markPages(u64 begin, u64 end) {
        if (end <= begin) return;
        for (size_t pg = pageOf(begin), last = pageOf(end - 1); pg <= last; ++pg) pages_.set(pg);
    }
    bool pagesMarked(u64 begin, u64 end) const {
        if (end <= begin) return false;
        for (size_t pg = pageOf(begin), last = pageOf(end - 1); pg <= last; ++pg)
            if (pages_.test(pg)) return true;
        return false;
    }

    // Every entry's source range with the entry, contiguous: a write walks these, not the map.
    struct Span {
        u32 begin, end;
        bool clut;
        Entry* entry;
    };

    Budget budget_;
    std::bitset<kPages> pages_;
    std::vector<Span> spans_;
    std::unordered_map<TextureKey, Entry, TextureKeyHash> entries_;
    size_t bytes_ = 0;
    u64 clock_ = 0;
    ValidityStats stats_;
};

}  // namespace ge::texcache
