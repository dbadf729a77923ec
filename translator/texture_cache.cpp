// SPDX-License-Identifier: MIT
// Decoded-texture cache (see texture_cache.h).
#include "translator/texture_cache.h"

#include <algorithm>
#include <cstring>

#include "hle/texture_decoder.h"
#include "shadergen/shader_keys.h"

namespace ge::gl {

namespace {
constexpr size_t kMaxEntries = 512;
}

size_t TextureCache::KeyHash::operator()(const Key& k) const { return size_t(shadergen::hashBytes(&k, sizeof k)); }

TextureCache::~TextureCache() { clear(); }

void TextureCache::clear() {
    for (auto& kv : entries_)
        if (kv.second.tex) ctx_.f().DeleteTextures(1, &kv.second.tex);
    entries_.clear();
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
    levelCount = std::clamp(levelCount, 1, 8);
    Key key;
    std::memset(static_cast<void*>(&key), 0, sizeof key);
    for (int l = 0; l < levelCount; ++l) {
        key.addr[l] = st.textureAddr(l);
        key.bufw[l] = st.textureBufWidth(l);
        key.size[l] = st.TSIZE_wlog(l) | (st.TSIZE_hlog(l) << 8);
    }
    key.format = st.TPF_format();
    key.swizzle = st.TMODE_swizzle();
    key.levels = u32(levelCount);
    const bool clut = key.format >= GE_TFMT_CLUT4 && key.format <= GE_TFMT_CLUT32;
    if (clut) {
        key.clut = st.op(GE_CMD_CLUT);
        key.multiClut = st.TMODE_multiclut();
        key.clutHash = clutHash;
    }
    ++useCounter_;
    auto it = entries_.find(key);
    if (it == entries_.end()) {
        if (entries_.size() >= kMaxEntries) {
            // Drop the least recently used half (simple, bounded).
            std::vector<u64> uses;
            for (auto& kv : entries_) uses.push_back(kv.second.lastUse);
            std::nth_element(uses.begin(), uses.begin() + long(uses.size() / 2), uses.end());
            const u64 cut = uses[uses.size() / 2];
            for (auto e = entries_.begin(); e != entries_.end();) {
                if (e->second.lastUse <= cut) {
                    ctx_.f().DeleteTextures(1, &e->second.tex);
                    e = entries_.erase(e);
                } else {
                    ++e;
                }
            }
        }
        it = entries_.emplace(key, TextureEntry{}).first;
        TextureEntry& e = it->second;
        sourceRange(st, levelCount, e.rangeBegin, e.rangeEnd);
        upload(mem, st, e, levelCount);
        e.checkedGen = generation;
        e.lastUse = useCounter_;
        return &e;
    }
    TextureEntry& e = it->second;
    e.lastUse = useCounter_;
    if (e.checkedGen != generation) {
        bool same = true;
        for (int l = 0; l < levelCount && same; ++l) same = hashTextureLevel(mem, st, l) == e.hashes[l];
        e.checkedGen = generation;
        if (!same) {
            upload(mem, st, e, levelCount);
            return &e;
        }
    }
    ++stats_.hits;
    return &e;
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
        e.hashes[l] = hashTextureLevel(mem, st, l);
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
