// SPDX-License-Identifier: MIT
// Texture decoding (manual §13; docs/ge-rules.md §6).
//
// One decode per texture level: the source bytes are fetched once (bounds-checked, unreadable
// bytes read as zero), swizzled storage is unswizzled block-wise into a linear copy, and a
// per-format loop converts rows to RGBA8888 (R in bits 7..0). CLUT formats go through a palette
// table resolved once per decode, so the per-texel work is a shift, a mask and a load.
#include "hle/texture_decoder.h"

#include <xxhash.h>

#include <algorithm>

#include "hle/pixel_format.h"

namespace ge {

namespace {

constexpr u32 kFormatBits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8, 0, 0, 0, 0, 0};

inline bool isDxt(GeTexFormat f) { return f == GE_TFMT_DXT1 || f == GE_TFMT_DXT3 || f == GE_TFMT_DXT5; }
inline bool isClut(GeTexFormat f) { return f >= GE_TFMT_CLUT4 && f <= GE_TFMT_CLUT32; }
inline bool validLevel(int level) { return level >= 0 && level < 8; }

// Bytes holding the first `w` texels of a row.
inline u32 rowBytes(u32 w, u32 bits) { return (w * bits + 7) / 8; }

// Palette entry `i` (already limited to the palette size) in the CPF format (ge-rules.md §6.4).
inline u32 paletteEntry(const GeState& st, u32 i) {
    const u32 cpf = st.CLUT_format();
    if (cpf == GE_FORMAT_8888) return readLE32(st.clut + 4 * (i & 0xFF));
    return decodePixel16(readLE16(st.clut + 2 * (i & 0x1FF)), GeBufferFormat(cpf));
}

// CSA in effect for a level: multi-CLUT moves CLUT4 level n to CSA + n (ge-rules.md §6.4, PPSSPP). For CLUT8
// the manual puts level 1 at +256 entries while PPSSPP applies no offset [conflict, ge-rules.md §6.4]; we
// follow PPSSPP, which is what the reference renders were produced with.
inline u32 effectiveCsa(const GeState& st, int level) {
    u32 csa = st.CLUT_start();
    if (st.TMODE_multiclut() && st.textureFormat() == GE_TFMT_CLUT4 && level > 0) csa += u32(level);
    return csa;
}

// Palette resolved for every masked index value m = (t >> SFT) & MSK (0–255).
void buildMaskedPalette(const GeState& st, int level, u32 pal[256]) {
    const u32 csaBits = effectiveCsa(st, level) << 4;
    const u32 limit = st.CLUT_format() == GE_FORMAT_8888 ? 0xFF : 0x1FF;
    for (u32 m = 0; m < 256; ++m) pal[m] = paletteEntry(st, (m | csaBits) & limit);
}

template <u32 (*Decode)(u16)>
void decodeRows16(const u8* src, u32 pitch, u32 w, u32 h, u32* out) {
    for (u32 y = 0; y < h; ++y) {
        const u8* row = src + size_t(y) * pitch;
        u32* o = out + size_t(y) * w;
        for (size_t x = 0; x < w; ++x) o[x] = Decode(readLE16(row + 2 * x));
    }
}

// Linear (unswizzled) storage of the non-DXT formats; src holds h rows of `pitch` bytes (the last
// row at least rowBytes(w)).
void decodeLinear(const GeState& st, int level, GeTexFormat fmt, const u8* src, u32 pitch, u32 w, u32 h,
                  u32* out) {
    switch (fmt) {
    case GE_TFMT_5650: decodeRows16<decode5650>(src, pitch, w, h, out); return;
    case GE_TFMT_5551: decodeRows16<decode5551>(src, pitch, w, h, out); return;
    case GE_TFMT_4444: decodeRows16<decode4444>(src, pitch, w, h, out); return;
    case GE_TFMT_8888:
        for (u32 y = 0; y < h; ++y) {
            const u8* row = src + size_t(y) * pitch;
            u32* o = out + size_t(y) * w;
            for (size_t x = 0; x < w; ++x) o[x] = readLE32(row + 4 * x);
        }
        return;
    default: break;
    }
    u32 masked[256];
    buildMaskedPalette(st, level, masked);
    const u32 sft = st.CLUT_shift(), msk = st.CLUT_mask();
    if (fmt == GE_TFMT_CLUT4 || fmt == GE_TFMT_CLUT8) {
        // Small raw index: resolve shift and mask per raw value once.
        u32 direct[256];
        const u32 n = fmt == GE_TFMT_CLUT4 ? 16 : 256;
        for (u32 t = 0; t < n; ++t) direct[t] = masked[(t >> sft) & msk];
        for (u32 y = 0; y < h; ++y) {
            const u8* row = src + size_t(y) * pitch;
            u32* o = out + size_t(y) * w;
            if (fmt == GE_TFMT_CLUT8) {
                for (u32 x = 0; x < w; ++x) o[x] = direct[row[x]];
            } else {
                // Texel 2k in bits 3..0 of byte k, texel 2k+1 in bits 7..4 (ge-rules.md §6.1).
                for (u32 x = 0; x < w; ++x) o[x] = direct[(row[x >> 1] >> ((x & 1) * 4)) & 0xF];
            }
        }
        return;
    }
    for (u32 y = 0; y < h; ++y) {
        const u8* row = src + size_t(y) * pitch;
        u32* o = out + size_t(y) * w;
        if (fmt == GE_TFMT_CLUT16) {
            for (u32 x = 0; x < w; ++x) o[x] = masked[(u32(readLE16(row + 2 * x)) >> sft) & msk];
        } else {
            for (u32 x = 0; x < w; ++x) o[x] = masked[(readLE32(row + 4 * x) >> sft) & msk];
        }
    }
}

// DXT colour block (bytes 0–7, PSP order: indices first, ge-rules.md §6.5).
struct DxtColors {
    u32 c[4];
};
DxtColors dxtColors(const u8* block, bool dxt1) {
    const u16 c0 = readLE16(block + 4), c1 = readLE16(block + 6);
    // Standard 565 (red in bits 15..11), expanded without bit replication (observed: pat dxt1).
    const u32 r0 = (c0 >> 11) << 3, g0 = ((c0 >> 5) & 0x3F) << 2, b0 = (c0 & 0x1F) << 3;
    const u32 r1 = (c1 >> 11) << 3, g1 = ((c1 >> 5) & 0x3F) << 2, b1 = (c1 & 0x1F) << 3;
    auto pack = [](u32 r, u32 g, u32 b, u32 a) { return r | (g << 8) | (b << 16) | (a << 24); };
    DxtColors d;
    d.c[0] = pack(r0, g0, b0, 255);
    d.c[1] = pack(r1, g1, b1, 255);
    if (c0 > c1) {
        d.c[2] = pack((2 * r0 + r1) / 3, (2 * g0 + g1) / 3, (2 * b0 + b1) / 3, 255);
        d.c[3] = pack((r0 + 2 * r1) / 3, (g0 + 2 * g1) / 3, (b0 + 2 * b1) / 3, 255);
    } else {
        d.c[2] = pack((r0 + r1) / 2, (g0 + g1) / 2, (b0 + b1) / 2, 255);
        // Black; transparent only in DXT1 (DXT3/5 take alpha from their alpha block).
        d.c[3] = dxt1 ? 0u : pack(0, 0, 0, 255);
    }
    return d;
}

void dxtColorTexels(const u8* block, bool dxt1, u32 out[16]) {
    const DxtColors d = dxtColors(block, dxt1);
    for (int r = 0; r < 4; ++r) {
        const u8 bits = block[r];
        for (int x = 0; x < 4; ++x) out[r * 4 + x] = d.c[(bits >> (2 * x)) & 3];
    }
}

}  // namespace

void maskedPalette(const GeState& st, int level, u32 pal[256]) { buildMaskedPalette(st, level, pal); }

void decodeDxt1Block(const u8* block, u32 out[16]) { dxtColorTexels(block, true, out); }

void decodeDxt3Block(const u8* block, u32 out[16]) {
    dxtColorTexels(block, false, out);
    for (int r = 0; r < 4; ++r) {
        const u16 row = readLE16(block + 8 + 2 * r);
        for (int x = 0; x < 4; ++x) {
            // 4-bit alpha becomes a << 4, no replication (observed: pat texcolors/dxt3).
            const u32 a = ((row >> (4 * x)) & 0xF) << 4;
            out[r * 4 + x] = (out[r * 4 + x] & 0x00FFFFFF) | (a << 24);
        }
    }
}

void decodeDxt5Block(const u8* block, u32 out[16]) {
    dxtColorTexels(block, false, out);
    const u32 a0 = block[14], a1 = block[15];
    u32 alpha[8];
    alpha[0] = a0;
    alpha[1] = a1;
    // Interpolation exactly as ge-rules.md §6.5 (each division truncating, + 31 >> 8).
    if (a0 > a1) {
        for (u32 n = 1; n <= 6; ++n) alpha[n + 1] = ((a0 * (7 - n) * 256) / 7 + (a1 * n * 256) / 7 + 31) >> 8;
    } else {
        for (u32 n = 1; n <= 4; ++n) alpha[n + 1] = ((a0 * (5 - n) * 256) / 5 + (a1 * n * 256) / 5 + 31) >> 8;
        alpha[6] = 0;
        alpha[7] = 255;
    }
    u64 bits = 0;
    for (int i = 0; i < 6; ++i) bits |= u64(block[8 + i]) << (8 * i);
    for (int i = 0; i < 16; ++i) {
        const u32 a = alpha[(bits >> (3 * i)) & 7];
        out[i] = (out[i] & 0x00FFFFFF) | (a << 24);
    }
}

u32 swizzledByteOffset(u32 xBytes, u32 y, u32 pitchBytes) {
    const u32 blocksPerRow = pitchBytes / 16;
    return ((y / 8) * blocksPerRow + xBytes / 16) * 128 + (y % 8) * 16 + xBytes % 16;
}

u32 textureFormatBits(GeTexFormat fmt) { return kFormatBits[fmt & 15]; }

TextureLevelInfo textureLevelInfo(const GeState& st, int level) {
    TextureLevelInfo info;
    if (!validLevel(level)) return info;
    info.addr = st.textureAddr(level);
    info.bufw = st.textureBufWidth(level);
    // Exponents above 9 saturate at 512 (ge-rules.md §6.2: addressing saturates at 511).
    info.width = st.textureWidth(level);
    info.height = st.textureHeight(level);
    return info;
}

u32 textureLevelBytes(const GeState& st, int level) {
    if (!validLevel(level)) return 0;
    const GeTexFormat fmt = st.textureFormat();
    const u32 bits = textureFormatBits(fmt);
    if (bits == 0) return 0;
    const TextureLevelInfo li = textureLevelInfo(st, level);
    if (isDxt(fmt)) {
        // Rows of bufw/4 blocks (ge-rules.md §6.2); the last block row needs only the blocks the width covers.
        const u32 blockBytes = fmt == GE_TFMT_DXT1 ? 8 : 16;
        const u32 blocksPerRow = li.bufw / 4, blockRows = (li.height + 3) / 4;
        return ((blockRows - 1) * blocksPerRow + (li.width + 3) / 4) * blockBytes;
    }
    const u32 pitch = rowBytes(li.bufw, bits);
    if (st.TMODE_swizzle()) {
        // 16-byte × 8-row blocks; the height is used in multiples of 8 rows (ge-rules.md §6.3).
        const u32 blockRows = (li.height + 7) / 8;
        const u32 cols = (rowBytes(li.width, bits) + 15) / 16;
        return ((blockRows - 1) * (pitch / 16) + cols) * 128;
    }
    return (li.height - 1) * pitch + rowBytes(li.width, bits);
}

u32 clutLookup(const GeState& st, u32 rawIndex, int level) {
    // i = ((t >> SFT) & MSK) | (CSA << 4): CSA is OR-ed, not added (ge-rules.md §6.4, observed: pat gpu/clut).
    const u32 i = ((rawIndex >> st.CLUT_shift()) & st.CLUT_mask()) | (effectiveCsa(st, level) << 4);
    return paletteEntry(st, i);  // limited to 0xFF (32-bit palette) or 0x1FF (16-bit) inside
}

namespace {

// The level's source bytes [addr, addr + bytes), read piece by piece: straight from guest memory
// where the piece lies in the readable prefix of the range, else a copy of the piece with the
// bytes past that prefix zero (texels off the end of memory read as 0). A texture running off the
// end of memory with a wide buffer width spans megabytes of which it reads a few rows: copying and
// zeroing only the pieces keeps that cheap (the whole range zero-filled took most of a fuzzed
// replay's time).
class Source {
public:
    Source(const Memory& mem, u32 addr, u32 bytes)
        : mem_(mem), addr_(addr), whole_(bytes && mem.ptr(addr, bytes) != nullptr), valid_(mem.validSize(addr, bytes)) {}
    // True when every byte of the range is readable.
    bool whole() const { return whole_; }
    u32 valid() const { return valid_; }
    // n bytes at offset off; valid until the next call.
    const u8* at(u32 off, u32 n) {
        if (u64(off) + n <= valid_) return mem_.ptr(addr_ + off, n);
        tmp_.assign(n, 0);
        if (off < valid_) mem_.read(addr_ + off, tmp_.data(), valid_ - off);
        return tmp_.data();
    }

private:
    const Memory& mem_;
    u32 addr_;
    bool whole_;
    u32 valid_;
    std::vector<u8> tmp_;
};

}  // namespace

bool decodeTextureLevel(const Memory& mem, const GeState& st, int level, std::vector<u32>& out) {
    const TextureLevelInfo li = textureLevelInfo(st, level);
    out.assign(size_t(li.width) * li.height, 0);
    if (!validLevel(level)) return false;
    const GeTexFormat fmt = st.textureFormat();
    const u32 bits = textureFormatBits(fmt);
    if (bits == 0) return false;  // TPF 11–15: no defined format, texels read as 0

    const u32 bytes = textureLevelBytes(st, level);
    Source src(mem, li.addr, bytes);
    const bool ok = bytes == 0 || src.whole();

    if (isDxt(fmt)) {
        // DXT is never swizzled (ge-rules.md §6.3). Block (bx, by) at (by * bufw/4 + bx) * blockBytes (ge-rules.md §6.2).
        const u32 blockBytes = fmt == GE_TFMT_DXT1 ? 8 : 16;
        const u32 blocksPerRow = li.bufw / 4, rowBlocks = (li.width + 3) / 4;
        u32 texels[16];
        for (u32 by = 0; by < (li.height + 3) / 4; ++by) {
            const u8* row = src.at(by * blocksPerRow * blockBytes, rowBlocks * blockBytes);
            for (u32 bx = 0; bx < rowBlocks; ++bx) {
                const u8* block = row + size_t(bx) * blockBytes;
                switch (fmt) {
                case GE_TFMT_DXT1: decodeDxt1Block(block, texels); break;
                case GE_TFMT_DXT3: decodeDxt3Block(block, texels); break;
                default: decodeDxt5Block(block, texels); break;
                }
                for (u32 r = 0; r < 4 && by * 4 + r < li.height; ++r)
                    for (u32 x = 0; x < 4 && bx * 4 + x < li.width; ++x)
                        out[size_t(by * 4 + r) * li.width + bx * 4 + x] = texels[r * 4 + x];
            }
        }
        return ok;
    }

    const u32 pitch = rowBytes(li.bufw, bits);
    if (st.TMODE_swizzle()) {
        // Unswizzle block-wise into a linear copy of `cols` 16-byte columns per row (ge-rules.md §6.3): block
        // row b (8 texel rows) is the cols * 128 bytes from b * pitch * 8.
        const u32 cols = (rowBytes(li.width, bits) + 15) / 16;
        const u32 linPitch = cols * 16;
        const u32 blocksPerRow = pitch / 16;
        std::vector<u8> lin(size_t(linPitch) * li.height);
        for (u32 b = 0; b * 8 < li.height; ++b) {
            const u8* blockRow = src.at(b * blocksPerRow * 128, cols * 128);
            for (u32 y = b * 8; y < std::min(li.height, b * 8 + 8); ++y) {
                u8* dst = lin.data() + size_t(y) * linPitch;
                for (u32 c = 0; c < cols; ++c) std::memcpy(dst + 16 * c, blockRow + size_t(c) * 128 + (y % 8) * 16, 16);
            }
        }
        decodeLinear(st, level, fmt, lin.data(), linPitch, li.width, li.height, out.data());
        return ok;
    }
    if (bytes == 0) return ok;
    const u32 rb = rowBytes(li.width, bits);
    for (u32 y = 0; y < li.height;) {
        const u32 off = y * pitch;
        if (u64(off) + rb <= src.valid()) {
            // Rows wholly readable, decoded in one go straight from memory.
            u32 y2 = y + 1;
            while (y2 < li.height && u64(y2) * pitch + rb <= src.valid()) ++y2;
            decodeLinear(st, level, fmt, src.at(off, (y2 - 1 - y) * pitch + rb), pitch, li.width, y2 - y, out.data() + size_t(y) * li.width);
            y = y2;
        } else if (off >= src.valid()) {
            // This row and every later one read only zeros: decoded once, copied.
            u32* row = out.data() + size_t(y) * li.width;
            decodeLinear(st, level, fmt, src.at(off, rb), pitch, li.width, 1, row);
            for (u32 r = y + 1; r < li.height; ++r) std::copy(row, row + li.width, out.data() + size_t(r) * li.width);
            break;
        } else {
            decodeLinear(st, level, fmt, src.at(off, rb), pitch, li.width, 1, out.data() + size_t(y) * li.width);
            ++y;
        }
    }
    return ok;
}

u64 hashTextureLevel(const Memory& mem, const GeState& st, int level) {
    if (!validLevel(level)) return 0;
    const TextureLevelInfo li = textureLevelInfo(st, level);
    const u32 bytes = textureLevelBytes(st, level);
    // The readable prefix, then zeros for the rest of the range (as decodeTextureLevel reads it).
    const u32 valid = mem.validSize(li.addr, bytes);
    static constexpr u8 kZeros[4096] = {};
    XXH3_state_t* state = XXH3_createState();
    if (!state) return 0;
    XXH3_64bits_reset(state);
    if (valid) XXH3_64bits_update(state, mem.ptr(li.addr, valid), valid);
    for (u32 left = bytes - valid; left;) {
        const u32 n = std::min<u32>(left, sizeof kZeros);
        XXH3_64bits_update(state, kZeros, n);
        left -= n;
    }
    const GeTexFormat fmt = st.textureFormat();
    if (isClut(fmt)) {
        // Palette entries reachable from this format's raw index range with the current
        // shift/mask/start: v = t >> SFT only matters through its low 8 bits.
        static constexpr u32 maxRaw[4] = {0xF, 0xFF, 0xFFFF, 0xFFFFFFFF};
        const u32 vmax = std::min<u32>(255, maxRaw[fmt - GE_TFMT_CLUT4] >> st.CLUT_shift());
        const u32 csaBits = effectiveCsa(st, level) << 4;
        const bool pal32 = st.CLUT_format() == GE_FORMAT_8888;
        const u32 limit = pal32 ? 0xFF : 0x1FF, entryBytes = pal32 ? 4 : 2;
        u32 lo = ~0u, hi = 0;
        for (u32 v = 0; v <= vmax; ++v) {
            const u32 i = ((v & st.CLUT_mask()) | csaBits) & limit;
            lo = std::min(lo, i);
            hi = std::max(hi, i);
        }
        XXH3_64bits_update(state, st.clut + lo * entryBytes, (hi - lo + 1) * entryBytes);
    }
    const u64 h = XXH3_64bits_digest(state);
    XXH3_freeState(state);
    return h;
}

}  // namespace ge
