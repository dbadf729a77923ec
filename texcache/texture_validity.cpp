// SPDX-License-Identifier: MIT
#include "texcache/texture_validity.h"

#include <xxhash.h>


namespace ge::texcache {

bool usesClut(const GeState& st) {
    const GeTexFormat fmt = st.textureFormat();
    return fmt >= GE_TFMT_CLUT4 && fmt <= GE_TFMT_CLUT32;
}

TextureKey textureKey(const GeState& st, int first, int count, u64 clutHash) {
    TextureKey k;
    // Zeroed as a whole (padding included): keys compare and hash as bytes.
    std::memset(static_cast<void*>(&k), 0, sizeof k);
    count = std::clamp(count, 1, kMaxLevels - first);
    for (int i = 0; i < count; ++i) {
        const int l = first + i;
        k.addr[i] = st.textureAddr(l);
        k.bufw[i] = st.textureBufWidth(l);
        k.size[i] = st.TSIZE_wlog(l) | (st.TSIZE_hlog(l) << 8);
    }
    k.format = st.TPF_format();
    k.swizzle = st.TMODE_swizzle();
    k.levels = u32(count);
    if (usesClut(st)) {
        k.clut = st.op(GE_CMD_CLUT);
        // Multi-CLUT (docs/ge-rules.md §6.4) makes the palette window depend on the level.
        k.multiClut = st.TMODE_multiclut();
        if (k.multiClut) k.levelTag = u32(first);
        k.clutHash = clutHash;
    }
    return k;
}

size_t TextureKeyHash::operator()(const TextureKey& k) const { return size_t(XXH3_64bits(&k, sizeof k)); }

void sourceRange(const GeState& st, int first, int count, u32& begin, u32& end) {
    u64 lo = ~u64(0), hi = 0;
    for (int l = first; l < first + count && l < kMaxLevels; ++l) {
        const u64 a = Memory::drawingAddress(st.textureAddr(l));
        lo = std::min(lo, a);
        hi = std::max(hi, a + textureLevelBytes(st, l));
    }
    if (lo > hi) lo = hi = 0;
    begin = u32(lo);
    end = u32(std::min<u64>(hi, 0xFFFFFFFFull));
}

}  // namespace ge::texcache
