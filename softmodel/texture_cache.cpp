// SPDX-License-Identifier: MIT
#include "softmodel/texture_cache.h"

#include <algorithm>

#include "hle/texture_decoder.h"
#include "softmodel/pixel.h"

namespace ge::soft {

TextureCache::TextureCache(size_t maxBytes) : maxBytes_(maxBytes) {}

size_t TextureCache::KeyHash::operator()(const Key& k) const {
    u64 h = 0x9E3779B97F4A7C15ull;
    auto mix = [&h](u64 v) {
        h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        h *= 0xBF58476D1CE4E5B9ull;
    };
    mix(k.addr);
    mix(u64(k.bufw) << 32 | k.width << 16 | k.height);
    mix(u64(k.clut) << 24 | u64(k.format) << 16 | u64(k.swizzle) << 8 | k.level);
    return size_t(h ^ (h >> 31));
}

std::shared_ptr<const DecodedLevel> TextureCache::level(const GeState& st, const Memory& mem, int lvl) {
    const TextureLevelInfo info = textureLevelInfo(st, lvl);
    const GeTexFormat fmt = st.textureFormat();
    const bool isClut = fmt >= GE_TFMT_CLUT4 && fmt <= GE_TFMT_CLUT32;
    Key key;
    key.addr = info.addr;
    key.bufw = info.bufw;
    key.width = info.width;
    key.height = info.height;
    key.format = u8(st.TPF_format());
    key.swizzle = st.TMODE_swizzle() ? 1 : 0;
    if (isClut) {
        key.clut = st.op(GE_CMD_CLUT);
        // Multi-CLUT (docs/ge-rules.md §6.4) makes the palette window depend on the level.
        if (st.TMODE_multiclut()) key.level = u8(lvl);
    }

    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.lookups;
    ++clock_;
    auto it = entries_.find(key);
    if (it != entries_.end() && !it->second.suspect) {
        it->second.lastUse = clock_;
        return it->second.data;
    }
    const u64 hash = hashTextureLevel(mem, st, lvl);
    if (it != entries_.end()) {
        ++stats_.rehashes;
        if (it->second.hash == hash) {
            it->second.suspect = false;
            it->second.lastUse = clock_;
            return it->second.data;
        }
    }

    auto decoded = std::make_shared<DecodedLevel>();
    decoded->width = std::max<u32>(info.width, 1);
    decoded->height = std::max<u32>(info.height, 1);
    // Unreadable memory decodes as zeros (the decoder reports it; a wild texture address must not
    // stop the draw). Any size mismatch is padded/truncated so the sampler's bounds hold.
    decodeTextureLevel(mem, st, lvl, decoded->texels);
    decoded->texels.resize(size_t(decoded->width) * decoded->height, 0);
    ++stats_.decodes;

    Entry e;
    e.data = decoded;
    e.hash = hash;
    e.begin = Memory::drawingAddress(info.addr);
    const u64 end = u64(e.begin) + textureLevelBytes(st, lvl);
    e.end = u32(std::min<u64>(end, 0xFFFFFFFFull));
    e.usesClut = isClut;
    e.lastUse = clock_;
    e.bytes = decoded->texels.size() * sizeof(u32) + sizeof(DecodedLevel);
    if (it != entries_.end()) {
        bytes_ -= it->second.bytes;
        it->second = std::move(e);
        bytes_ += it->second.bytes;
    } else {
        bytes_ += e.bytes;
        entries_.emplace(key, std::move(e));
    }
    if (bytes_ > maxBytes_) evictLocked();
    return decoded;
}

void TextureCache::evictLocked() {
    // Drop least recently used entries down to 3/4 of the budget. Callers hold shared_ptrs to
    // what they use, so dropping never invalidates a draw in flight.
    std::vector<std::pair<u64, Key>> order;
    order.reserve(entries_.size());
    for (const auto& [k, e] : entries_) order.emplace_back(e.lastUse, k);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const size_t target = maxBytes_ / 4 * 3;
    for (const auto& [use, k] : order) {
        if (bytes_ <= target || use == clock_) break;
        auto it = entries_.find(k);
        bytes_ -= it->second.bytes;
        entries_.erase(it);
    }
}

void TextureCache::invalidate(u32 addr, u32 size) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (size == 0) {
        for (auto& [k, e] : entries_) e.suspect = true;
        return;
    }
    const u64 begin = Memory::drawingAddress(addr);
    const u64 end = begin + size;
    for (auto& [k, e] : entries_)
        if (e.begin < end && begin < e.end) e.suspect = true;
}

void TextureCache::clutChanged() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [k, e] : entries_)
        if (e.usesClut) e.suspect = true;
}

void TextureCache::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    bytes_ = 0;
}

TextureCacheStats TextureCache::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    TextureCacheStats s = stats_;
    s.entries = entries_.size();
    s.bytes = bytes_;
    return s;
}

// ---- The pixel.h entry points ----
TextureCachePtr createTextureCache() { return TextureCachePtr(new TextureCache()); }
void destroyTextureCache(TextureCache* cache) { delete cache; }
void invalidateTextureCache(TextureCache& cache, u32 addr, u32 size) { cache.invalidate(addr, size); }
void clutChanged(TextureCache& cache) { cache.clutChanged(); }

}  // namespace ge::soft
