// SPDX-License-Identifier: MIT
// Texture decoding (manual §13; docs/ge-rules.md §6): every texel format, CLUT lookup, swizzled
// storage and the PSP's DXT variants, to RGBA8888 (R in bits 7..0).
#pragma once
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

namespace ge {

struct TextureLevelInfo {
    u32 addr = 0, bufw = 0, width = 0, height = 0;
};
TextureLevelInfo textureLevelInfo(const GeState& st, int level);

// Number of source bytes a level occupies (for hashing/invalidation); swizzle-aware.
u32 textureLevelBytes(const GeState& st, int level);

// Bits per texel of a texture format (4, 8, 16 or 32; DXT1 4, DXT3/5 8).
u32 textureFormatBits(GeTexFormat fmt);

// CLUT lookup of a raw texel index (ge-rules.md §6.4): ((t>>SFT)&MSK)|(CSA<<4), 16-bit palettes &0x1FF,
// 32-bit &0xFF, multi-CLUT per-level offset for CLUT4, palette from st.clut in CPF format.
u32 clutLookup(const GeState& st, u32 rawIndex, int level);
// The palette resolved for every masked index m = (t >> SFT) & MSK (0–255): pal[m] is what
// clutLookup gives for any raw index with that masked value (the GL path's palette texture).
void maskedPalette(const GeState& st, int level, u32 pal[256]);

// Decodes a whole level to RGBA8888 (R in bits 7..0), width*height texels, row-major, all 11
// formats, swizzled storage (TMODE bit 0), DXT1/3/5 as ge-rules.md §6.5, sizes > 512 saturated as ge-rules.md §6.2.
// Unreadable memory reads as zero bytes and returns false.
bool decodeTextureLevel(const Memory& mem, const GeState& st, int level, std::vector<u32>& out);

// Pieces exposed for tests and the GL path's CPU fallback. Blocks are 8 (DXT1) or 16 bytes.
void decodeDxt1Block(const u8* block, u32 out[16]);
void decodeDxt3Block(const u8* block, u32 out[16]);
void decodeDxt5Block(const u8* block, u32 out[16]);
u32 swizzledByteOffset(u32 xBytes, u32 y, u32 pitchBytes);  // ge-rules.md §6.3
// XXH3_64bits of the level's source bytes (+ the palette bytes used, for CLUT formats).
u64 hashTextureLevel(const Memory& mem, const GeState& st, int level);

}  // namespace ge
