// SPDX-License-Identifier: MIT
// Decoded-texture cache for the GL path.
//
// Each entry holds the levels a draw samples, decoded by the shared decoder
// (hle/texture_decoder.h, CLUT applied, RGBA8888) and stacked vertically in one RGBA8UI "atlas"
// texture; the fragment shader samples it with texelFetch and does wrap/clamp and filtering
// itself (exact 4-bit weights, docs/ge-rules.md §8.10).
//
// Invalidation contract (style-anchors §7.11): an entry is keyed by the texture registers and the
// palette contents, and validated by a full hash of its source bytes (hashTextureLevel, which
// includes the palette bytes used). Validation runs only when the renderer's memory generation
// changed since the entry was last checked — the generation advances on TFLUSH, CLOAD, block
// transfers, memoryWritten and every write-back of a render target to VRAM. No sampling, no
// heuristics: a changed byte always re-decodes.
#pragma once
#include <string>
#include <unordered_map>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "translator/gl_context.h"

namespace ge::gl {

struct TextureEntry {
    GLuint tex = 0;
    int levels = 1;
    int placement[8][4] = {};  // atlas y offset, stored width, height (≤ 512), 0 (u_texLevels takes the y)
    u64 hashes[8] = {};
    u32 rangeBegin = 0, rangeEnd = 0;  // normalised source bytes of all levels (for sync)
    u64 checkedGen = ~u64(0);
    u64 lastUse = 0;
};

struct TextureCacheStats {
    u64 uploads = 0, hits = 0;
};

class TextureCache {
public:
    explicit TextureCache(const GlContext& ctx) : ctx_(ctx) {}
    ~TextureCache();
    // The source byte range of the texture the state selects (levels 0..levelCount−1).
    static void sourceRange(const GeState& st, int levelCount, u32& begin, u32& end);
    // Returns the entry for the current texture state, decoding/uploading when needed.
    // `generation` is the renderer's memory generation; `clutHash` the palette contents hash.
    const TextureEntry* get(const Memory& mem, const GeState& st, int levelCount, u64 generation, u64 clutHash);
    const TextureCacheStats& stats() const { return stats_; }
    void clear();

private:
    struct Key {
        u32 addr[8], bufw[8], size[8];
        u32 format, swizzle, clut, multiClut, levels;
        u64 clutHash;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const;
    };
    struct KeyEq {
        bool operator()(const Key& a, const Key& b) const { return std::memcmp(&a, &b, sizeof a) == 0; }
    };
    void upload(const Memory& mem, const GeState& st, TextureEntry& e, int levelCount);

    const GlContext& ctx_;
    std::unordered_map<Key, TextureEntry, KeyHash, KeyEq> entries_;
    std::vector<u32> scratch_;
    std::vector<u32> atlas_;
    TextureCacheStats stats_;
    u64 useCounter_ = 0;
};

}  // namespace ge::gl
