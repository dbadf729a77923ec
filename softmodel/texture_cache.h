// SPDX-License-Identifier: MIT
// Decoded-texture cache of the software model (the TextureCache of softmodel/pixel.h).
//
// Each texture level is decoded to RGBA8888 once (hle/texture_decoder.h) and reused by later
// draws. Key: level address, format, size, buffer width, swizzle, CLUT register (+ level for
// multi-CLUT) — everything decodeTextureLevel reads besides memory and the palette. Validity is
// driven by events, with a full content hash as the fallback (style-anchors §7.11, §8.6):
//   * invalidate(addr, size): guest memory was written (transfers, CPU/dump writes, drawing into
//     VRAM); overlapping entries become "suspect";
//   * clutChanged(): palette RAM reloaded; entries of CLUT formats become suspect;
//   * a suspect entry is re-hashed (hashTextureLevel: source bytes + palette bytes used) when next
//     used, and reused if the content is unchanged, else decoded again.
// Decoded data is handed out as shared_ptr<const>, so a draw keeps its textures alive and
// read-only for its shading threads even if the cache drops or replaces the entry meanwhile.
// All member functions are thread-safe (one mutex; they run per draw, never per pixel).
#pragma once
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

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
    struct Key {
        u32 addr = 0, bufw = 0, width = 0, height = 0;
        u32 clut = 0;     // CLUT register argument for CLUT formats, else 0
        u8 format = 0, swizzle = 0, level = 0xFF;  // level only where the decode depends on it
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const;
    };
    struct Entry {
        std::shared_ptr<const DecodedLevel> data;
        u64 hash = 0;
        u32 begin = 0, end = 0;  // canonical source byte range [begin, end)
        bool usesClut = false;
        bool suspect = false;
        u64 lastUse = 0;
        size_t bytes = 0;
    };

    void evictLocked();

    mutable std::mutex mutex_;
    std::unordered_map<Key, Entry, KeyHash> entries_;
    size_t maxBytes_;
    size_t bytes_ = 0;
    u64 clock_ = 0;
    TextureCacheStats stats_;
};

}  // namespace ge::soft
