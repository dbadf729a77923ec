// SPDX-License-Identifier: MIT
#include "softmodel/texture_cache.h"

#include <algorithm>

#include "hle/texture_decoder.h"
#include "softmodel/pixel.h"

namespace ge::soft {

namespace {
// The software model keys on the CLUT register and hears palette reloads (clutChanged), so it
// has no palette hash in its keys; its budget is bytes of decoded texels.
constexpr u64 kNoClutHash = 0;
auto keep = [](auto&) {};  // dropping an entry frees its texels when the last draw lets go
}  // namespace

TextureCache::TextureCache(size_t maxBytes) : cache_(texcache::Budget{maxBytes, size_t(1) << 20}) {}

std::shared_ptr<const DecodedLevel> TextureCache::level(const GeState& st, const Memory& mem, int lvl) {
    const texcache::TextureKey key = texcache::textureKey(st, lvl, 1, kNoClutHash);
    std::lock_guard<std::mutex> lock(mutex_);
    auto [entry, use] = cache_.find(key, st, mem, lvl, 1, keep);
    if (use == Cache::Use::Reuse) return entry.payload;

    const TextureLevelInfo info = textureLevelInfo(st, lvl);
    auto decoded = std::make_shared<DecodedLevel>();
    decoded->width = std::max<u32>(info.width, 1);
    decoded->height = std::max<u32>(info.height, 1);
    // Unreadable memory decodes as zeros (the decoder reports it; a wild texture address must not
    // stop the draw). Any size mismatch is padded/truncated so the sampler's bounds hold.
    decodeTextureLevel(mem, st, lvl, decoded->texels);
    decoded->texels.resize(size_t(decoded->width) * decoded->height, 0);
    entry.payload = decoded;
    cache_.setBytes(entry, decoded->texels.size() * sizeof(u32) + sizeof(DecodedLevel), keep);
    return decoded;
}

void TextureCache::invalidate(u32 addr, u32 size) {
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.invalidate(addr, size);
}

void TextureCache::clutChanged() {
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.clutChanged();
}

void TextureCache::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.clear(keep);
}

TextureCacheStats TextureCache::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    const texcache::ValidityStats& v = cache_.stats();
    TextureCacheStats s;
    s.lookups = v.lookups;
    s.decodes = v.builds;
    s.rehashes = v.rehashes;
    s.entries = cache_.entries();
    s.bytes = cache_.bytes();
    return s;
}

// ---- The pixel.h entry points ----
TextureCachePtr createTextureCache() { return TextureCachePtr(new TextureCache()); }
void destroyTextureCache(TextureCache* cache) { delete cache; }
void invalidateTextureCache(TextureCache& cache, u32 addr, u32 size) { cache.invalidate(addr, size); }
void clutChanged(TextureCache& cache) { cache.clutChanged(); }

}  // namespace ge::soft
