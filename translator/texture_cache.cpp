// SPDX-License-Identifier: MIT
// Decoded-texture cache (see texture_cache.h).
#include "translator/texture_cache.h"

#include <algorithm>
#include <cstring>

#include "hle/texture_decoder.h"

namespace ge::gl {

namespace {
// What GL textures may hold: the entries and the atlas bytes, least recently used going first.
constexpr texcache::Budget kBudget{size_t(256) << 20, 512};
}  // namespace

TextureCache::TextureCache(const GlContext& ctx) : ctx_(ctx), cache_(kBudget) {}

TextureCache::~TextureCache() { clear(); }

void TextureCache::drop(TextureEntry& e) {
    if (e.tex) ctx_.f().DeleteTextures(1, &e.tex);
    e.tex = 0;
}

void TextureCache::clear() {
    cache_.clear([this](Cache::Entry& e) { drop(e.payload); });
}

void TextureCache::sourceRange(const GeState& st, int levelCount, u32& begin, u32& end) {
    begin = ~0u;
    end = 0;
    for (int l = 0; l < levelCount; ++l) {
        const u32 a = Memory::normalize(st.textureAddr(l));
        const u32 n = textureLevelBytes(st, l);
        begin = std::min(begin, a);
        end = std::max(end, a + n);
    }
    if (begin > end) begin = end = 0;
}

const TextureEntry* TextureCache::get(const Memory& mem, const GeState& st, int levelCount, u64 generation,
                                      u64 clutHash) {
    levelCount = std::clamp(levelCount, 1, texcache::kMaxLevels);
    if (generation != generation_) {
        cache_.invalidate(0, 0);
        generation_ = generation;
    }
    const texcache::TextureKey key = texcache::textureKey(st, 0, levelCount, clutHash);
    auto onDrop = [this](Cache::Entry& e) { drop(e.payload); };
    auto [entry, use] = cache_.find(key, st, mem, 0, levelCount, onDrop);
    if (use == Cache::Use::Reuse) {
        ++stats_.hits;
        return &entry.payload;
    }
    upload(mem, st, entry.payload, levelCount);
    size_t bytes = 0;
    for (int l = 0; l < levelCount; ++l) bytes += size_t(entry.payload.placement[l][1]) * entry.payload.placement[l][2] * 4;
    cache_.setBytes(entry, bytes, onDrop);
    return &entry.payload;
}

void TextureCache::upload(const Memory& mem, const GeState& st, TextureEntry& e, int levelCount) {
    const GlFuncs& gl = ctx_.f();
    int width = 1, height = 0;
    e.levels = levelCount;
    for (int l = 0; l < levelCount; ++l) {
        const TextureLevelInfo info = textureLevelInfo(st, l);
        const int w = int(std::max<u32>(info.width, 1)), h = int(std::max<u32>(info.height, 1));
        e.placement[l][0] = height;
        e.placement[l][1] = w;
        e.placement[l][2] = h;
        e.placement[l][3] = 0;
        width = std::max(width, w);
        height += h;
    }
    atlas_.resize(size_t(width) * size_t(height));
    for (int l = 0; l < levelCount; ++l) {
        scratch_.clear();
        decodeTextureLevel(mem, st, l, scratch_);  // unreadable bytes decode as zero
        const size_t w = size_t(e.placement[l][1]), h = size_t(e.placement[l][2]);
        // Row by row into the atlas; what the decoder did not produce, and the columns right of a
        // narrower level, read as zero.
        for (size_t y = 0; y < h; ++y) {
            u32* row = &atlas_[(size_t(e.placement[l][0]) + y) * size_t(width)];
            const size_t have = scratch_.size() > y * w ? std::min(w, scratch_.size() - y * w) : 0;
            if (have) std::memcpy(row, &scratch_[y * w], have * sizeof(u32));
            std::fill(row + have, row + width, 0u);
        }
    }
    if (!e.tex) {
        gl.GenTextures(1, &e.tex);
        gl.BindTexture(GL_TEXTURE_2D, e.tex);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    } else {
        gl.BindTexture(GL_TEXTURE_2D, e.tex);
    }
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    // RGBA8888 with R in the low byte is the byte order R, G, B, A in memory.
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, width, height, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, atlas_.data());
    ++stats_.uploads;
}

}  // namespace ge::gl
