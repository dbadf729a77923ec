// SPDX-License-Identifier: MIT
// Decoded-texture cache for the GL path.
//
// Each entry holds the levels a draw samples, decoded by the shared decoder
// (hle/texture_decoder.h, CLUT applied, RGBA8888) and stacked vertically in one RGBA8UI "atlas"
// texture; the fragment shader samples it with texelFetch and does wrap/clamp and filtering
// itself (exact 4-bit weights, docs/ge-rules.md §8.10).
//
// When an entry is still valid (key, content hashes, eviction budget) is texcache/texture_validity.h's
// job, shared with the software model. This cache adds the palette contents' hash to the key and
// is told of memory changes by a generation: the renderer's memory generation advances on TFLUSH,
// CLOAD, block transfers, memoryWritten and every write-back of a render target to VRAM, and when
// it has moved since the last lookup every entry is re-hashed against its source bytes when next
// used. No sampling, no heuristics: a changed byte always re-decodes.
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "texcache/texture_validity.h"
#include "translator/gl_context.h"

namespace ge::gl {

struct TextureEntry {
    GLuint tex = 0;
    int levels = 1;
    int placement[8][4] = {};  // atlas y offset, stored width, height (≤ 512), 0 (u_texLevels takes the y)
};

struct TextureCacheStats {
    u64 uploads = 0, hits = 0;
};

class TextureCache {
public:
    explicit TextureCache(const GlContext& ctx);
    ~TextureCache();
    // The source byte range of the texture the state selects (levels 0..levelCount−1).
    static void sourceRange(const GeState& st, int levelCount, u32& begin, u32& end);
    // Returns the entry for the current texture state, decoding/uploading when needed.
    // `generation` is the renderer's memory generation; `clutHash` the palette contents hash.
    const TextureEntry* get(const Memory& mem, const GeState& st, int levelCount, u64 generation, u64 clutHash);
    // Guest memory [addr, addr + size) was written by the host: the entries whose bytes lie there
    // are re-hashed when next used (a change of `generation` re-hashes every entry).
    void invalidate(u32 addr, u32 size) { cache_.invalidate(addr, size); }
    const TextureCacheStats& stats() const { return stats_; }
    void clear();

private:
    using Cache = texcache::ValidatedCache<TextureEntry>;
    void upload(const Memory& mem, const GeState& st, TextureEntry& e, int levelCount);
    void drop(TextureEntry& e);
    const GlContext& ctx_;
    Cache cache_;
    u64 generation_ = ~u64(0);  // the renderer's memory generation at the last lookup
    std::vector<u32> scratch_;
    std::vector<u32> atlas_;
    TextureCacheStats stats_;
};

}  // namespace ge::gl
