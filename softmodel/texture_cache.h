// SPDX-License-Identifier: MIT
// Decoded-texture cache of the software model (the TextureCache of softmodel/pixel.h).
//
// Each texture level is decoded to RGBA8888 once (hle/texture_decoder.h) and reused by later
// draws. When a decoded level is still valid — key, content hashes, invalidation by memory writes
// and palette reloads, eviction budget — is texcache/texture_validity.h's job, shared with the GL
// translator; this cache keeps the decoded texels, one entry per level.
// Decoded data is handed out as shared_ptr<const>, so a draw keeps its textures alive and
// read-only for its shading threads even if the cache drops or replaces the entry meanwhile.
// All member functions are thread-safe (one mutex; they run per draw, never per pixel).
#pragma once
#include <memory>
#include <mutex>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"
#include "texcache/texture_validity.h"

namespace ge::soft {

struct DecodedLevel {
    std::vector<u32> texels;  // width × height, RGBA8888 with R in bits 7..0
    u32 width = 0, height = 0;
};

struct TextureCacheStats {
    u64 lookups = 0;   // level requests
    u64 decodes = 0;   // levels decoded (misses and changed content)
    u64 rehashes = 0;  // suspect entries re-hashed
    u64 entries = 0;   // entries held now
    u64 bytes = 0;     // decoded bytes held now
};

class TextureCache {
public:
    // Budget for decoded data; least recently used entries go first beyond it.
    explicit TextureCache(size_t maxBytes = size_t(192) << 20);

    // The decoded texels of `level` of the texture described by `st`, decoding if needed.
    std::shared_ptr<const DecodedLevel> level(const GeState& st, const Memory& mem, int level);

    void invalidate(u32 addr, u32 size);  // size 0: everything
    void clutChanged();
    void clear();
    TextureCacheStats stats() const;

private:
    using Cache = texcache::ValidatedCache<std::shared_ptr<const DecodedLevel>>;
    mutable std::mutex mutex_;
    Cache cache_;
};

}  // namespace ge::soft
