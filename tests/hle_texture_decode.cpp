// SPDX-License-Identifier: MIT
// Texture decoding (manual §13; docs/ge-rules.md §6). Expected texels are computed by hand from the
// reference's layouts; DXT values follow ge-rules.md §6.5 (no endpoint replication, PSP block order).
#include <gtest/gtest.h>

#include "hle/pixel_format.h"
#include "hle/texture_decoder.h"

using namespace ge;

namespace {

constexpr u32 kTex = 0x08100000;

void set(GeState& st, u8 op, u32 arg) { st.regs[op] = (u32(op) << 24) | (arg & 0xFFFFFF); }

void setTexture(GeState& st, GeTexFormat fmt, u32 addr, u32 bufw, u32 wlog, u32 hlog, int level = 0) {
    set(st, u8(GE_CMD_TBP0 + level), addr & 0xFFFFFF);
    set(st, u8(GE_CMD_TBW0 + level), ((addr >> 24) & 0xF) << 16 | bufw);
    set(st, u8(GE_CMD_TSIZE0 + level), hlog << 8 | wlog);
    set(st, GE_CMD_TPF, fmt);
}

void setClut(GeState& st, u32 cpf, u32 sft, u32 msk, u32 csa) {
    set(st, GE_CMD_CLUT, cpf | sft << 2 | msk << 8 | csa << 16);
}

u32 rgba(u32 r, u32 g, u32 b, u32 a) { return r | g << 8 | b << 16 | a << 24; }

TEST(TextureDecode, Linear5650UsesBufferWidthAsPitch) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_5650, kTex, 16, 3, 1);  // 8x2, pitch 16 texels = 32 bytes
    mem.write16(kTex + 0, 0x001F);
    mem.write16(kTex + 14, 0xF800);  // texel (7, 0)
    mem.write16(kTex + 16, 0x1234);  // texel (8, 0): beyond the width, not decoded
    mem.write16(kTex + 32, 0x07E0);  // texel (0, 1)
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    ASSERT_EQ(out.size(), 16u);
    EXPECT_EQ(out[0], 0xFF0000FFu);
    EXPECT_EQ(out[7], 0xFFFF0000u);
    EXPECT_EQ(out[8], 0xFF00FF00u);
    EXPECT_EQ(out[1], 0xFF000000u);  // zero texel: black, alpha 255
}

TEST(TextureDecode, Linear5551And4444And8888) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_5551, kTex, 8, 1, 0);  // 2x1
    mem.write16(kTex, 0x8000 | 0x001F);
    mem.write16(kTex + 2, 0x7C00);
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], rgba(255, 0, 0, 255));
    EXPECT_EQ(out[1], rgba(0, 0, 255, 0));

    setTexture(st, GE_TFMT_4444, kTex, 8, 0, 0);
    mem.write16(kTex, 0x1234);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], 0x11223344u);

    setTexture(st, GE_TFMT_8888, kTex, 4, 1, 1);  // 2x2, pitch 4 texels
    mem.write32(kTex + 4, 0xAABBCCDD);
    mem.write32(kTex + 16, 0x01020304);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[1], 0xAABBCCDDu);
    EXPECT_EQ(out[2], 0x01020304u);
}

TEST(TextureDecode, BufferWidthZeroUsesTheMinimum) {
    GeState st;
    // 16 bytes' worth of texels (ge-rules.md §6.2).
    const std::pair<GeTexFormat, u32> expect[] = {{GE_TFMT_5650, 8}, {GE_TFMT_8888, 4}, {GE_TFMT_CLUT4, 32},
                                                  {GE_TFMT_CLUT8, 16}, {GE_TFMT_CLUT16, 8}, {GE_TFMT_CLUT32, 4},
                                                  {GE_TFMT_DXT1, 8}, {GE_TFMT_DXT3, 4}, {GE_TFMT_DXT5, 4}};
    for (auto [fmt, minw] : expect) {
        setTexture(st, fmt, kTex, 0, 2, 2);
        EXPECT_EQ(textureLevelInfo(st, 0).bufw, minw) << int(fmt);
    }
    // And the decoder uses it as the pitch: 4x2 5650 texture, row 1 starts 8 texels in.
    Memory mem;
    setTexture(st, GE_TFMT_5650, kTex, 0, 2, 1);
    mem.write16(kTex + 16, 0xF800);
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[4], 0xFFFF0000u);
}

TEST(TextureDecode, SizesAbove512Saturate) {
    GeState st;
    setTexture(st, GE_TFMT_8888, kTex, 512, 10, 11);
    const TextureLevelInfo li = textureLevelInfo(st, 0);
    EXPECT_EQ(li.width, 512u);
    EXPECT_EQ(li.height, 512u);
    EXPECT_EQ(li.addr, kTex);
}

TEST(TextureDecode, LevelBytes) {
    GeState st;
    setTexture(st, GE_TFMT_5650, kTex, 16, 3, 2);  // 8x4, pitch 32 bytes: 3 rows + 16 bytes
    EXPECT_EQ(textureLevelBytes(st, 0), 3u * 32 + 16);
    setTexture(st, GE_TFMT_CLUT4, kTex, 32, 0, 0);  // 1x1 4-bit: one byte
    EXPECT_EQ(textureLevelBytes(st, 0), 1u);
    setTexture(st, GE_TFMT_DXT1, kTex, 8, 3, 3);  // 2x2 blocks of 8 bytes
    EXPECT_EQ(textureLevelBytes(st, 0), 32u);
    setTexture(st, GE_TFMT_DXT5, kTex, 8, 3, 3);  // 2x2 blocks of 16 bytes
    EXPECT_EQ(textureLevelBytes(st, 0), 64u);
    setTexture(st, GE_TFMT_8888, kTex, 16, 4, 4);
    set(st, GE_CMD_TMODE, 1);  // swizzled 16x16x4: whole 128-byte blocks
    EXPECT_EQ(textureLevelBytes(st, 0), 1024u);
    setTexture(st, GE_TFMT_8888, kTex, 16, 4, 2);  // 4 rows still occupy 8-row blocks
    EXPECT_EQ(textureLevelBytes(st, 0), 512u);
}

// ---- CLUT (ge-rules.md §6.4) ----

TEST(TextureDecode, ClutLookupShiftMaskStart) {
    GeState st;
    for (u32 i = 0; i < 256; ++i) writeLE32(st.clut + 4 * i, 0xFF000000u | i);  // 8888 entry i = i
    setTexture(st, GE_TFMT_CLUT8, kTex, 16, 0, 0);
    setClut(st, 3, 4, 0x0F, 2);
    // (0xAB >> 4) & 0xF = 0xA, | 2<<4 → 0x2A.
    EXPECT_EQ(clutLookup(st, 0xAB, 0), 0xFF00002Au);
    // CSA is OR-ed, not added: CSA 1, t = 16, mask 0xFF → 16 | 16 = 16 (pat gpu/clut/offset).
    setClut(st, 3, 0, 0xFF, 1);
    EXPECT_EQ(clutLookup(st, 16, 0), 0xFF000010u);
    EXPECT_EQ(clutLookup(st, 1, 0), 0xFF000011u);
    // 32-bit palettes wrap at 256 entries: CSA 31 | 0xFF = 0x1FF → & 0xFF.
    setClut(st, 3, 0, 0xFF, 31);
    EXPECT_EQ(clutLookup(st, 0xFF, 0), 0xFF0000FFu);
}

TEST(TextureDecode, Clut16BitPaletteUses512Entries) {
    GeState st;
    for (u32 i = 0; i < 512; ++i) writeLE16(st.clut + 2 * i, u16(i));
    setTexture(st, GE_TFMT_CLUT8, kTex, 16, 0, 0);
    setClut(st, GE_FORMAT_4444, 0, 0xFF, 31);  // 0xFF | 0x1F0 = 0x1FF
    EXPECT_EQ(clutLookup(st, 0xFF, 0), decode4444(0x1FF));
    setClut(st, GE_FORMAT_565, 0, 0xFF, 16);  // 0x100 + 5
    EXPECT_EQ(clutLookup(st, 5, 0), decode5650(0x105));
    setClut(st, GE_FORMAT_5551, 0, 0xFF, 0);
    EXPECT_EQ(clutLookup(st, 0x80, 0), decode5551(0x80));
}

TEST(TextureDecode, Clut4TexelsAndNibbleOrder) {
    Memory mem;
    GeState st;
    for (u32 i = 0; i < 512; ++i) writeLE16(st.clut + 2 * i, u16(0x1000 + i));
    setTexture(st, GE_TFMT_CLUT4, kTex, 32, 2, 1);  // 4x2
    setClut(st, GE_FORMAT_4444, 0, 0xFF, 0);
    mem.write8(kTex + 0, 0x10);  // texel 0 = 0, texel 1 = 1 (low nibble first)
    mem.write8(kTex + 1, 0x32);
    mem.write8(kTex + 16, 0xFE);  // row 1 (pitch 32 texels = 16 bytes): texel 0 = 0xE, 1 = 0xF
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], decode4444(0x1000));
    EXPECT_EQ(out[1], decode4444(0x1001));
    EXPECT_EQ(out[2], decode4444(0x1002));
    EXPECT_EQ(out[3], decode4444(0x1003));
    EXPECT_EQ(out[4], decode4444(0x100E));
    EXPECT_EQ(out[5], decode4444(0x100F));
    // Start 3: entries 0x30…0x3F.
    setClut(st, GE_FORMAT_4444, 0, 0xFF, 3);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[1], decode4444(0x1031));
}

TEST(TextureDecode, Clut8And16And32Decode) {
    Memory mem;
    GeState st;
    for (u32 i = 0; i < 256; ++i) writeLE32(st.clut + 4 * i, 0x80000000u | i << 8);
    setClut(st, 3, 0, 0xFF, 0);
    setTexture(st, GE_TFMT_CLUT8, kTex, 16, 1, 0);
    mem.write8(kTex, 0x7F);
    mem.write8(kTex + 1, 0xFF);
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], 0x80007F00u);
    EXPECT_EQ(out[1], 0x8000FF00u);

    // CLUT16: whole 16-bit value, shift 8 → the high byte selects the entry.
    setTexture(st, GE_TFMT_CLUT16, kTex, 8, 0, 0);
    setClut(st, 3, 8, 0xFF, 0);
    mem.write16(kTex, 0x1234);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], 0x80001200u);

    // CLUT32: shift 24, mask 0x0F → 0x89 >> 0 & 0xF = 9.
    setTexture(st, GE_TFMT_CLUT32, kTex, 4, 0, 0);
    setClut(st, 3, 24, 0x0F, 0);
    mem.write32(kTex, 0x89ABCDEF);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], 0x80000900u);
}

TEST(TextureDecode, MultiClutOffsetsClut4Levels) {
    GeState st;
    for (u32 i = 0; i < 512; ++i) writeLE16(st.clut + 2 * i, u16(i));
    setTexture(st, GE_TFMT_CLUT4, kTex, 32, 0, 0);
    setClut(st, GE_FORMAT_4444, 0, 0xFF, 2);
    set(st, GE_CMD_TMODE, 1 << 8);  // multi-CLUT: level n uses CSA + n
    EXPECT_EQ(clutLookup(st, 3, 0), decode4444(0x23));
    EXPECT_EQ(clutLookup(st, 3, 1), decode4444(0x33));
    EXPECT_EQ(clutLookup(st, 3, 5), decode4444(0x73));
    set(st, GE_CMD_TMODE, 0);  // shared CLUT
    EXPECT_EQ(clutLookup(st, 3, 5), decode4444(0x23));
    // CLUT8: no per-level offset (PPSSPP's choice; manual says +256 entries — ge-rules.md §6.4).
    set(st, GE_CMD_TMODE, 1 << 8);
    set(st, GE_CMD_TPF, GE_TFMT_CLUT8);
    EXPECT_EQ(clutLookup(st, 3, 1), decode4444(0x23));
}

// ---- DXT (ge-rules.md §6.5) ----

void dxtColorBlock(u8* b, u8 idxRow0, u16 c0, u16 c1) {
    b[0] = idxRow0;
    b[1] = b[2] = b[3] = 0;
    writeLE16(b + 4, c0);
    writeLE16(b + 6, c1);
}

TEST(TextureDecode, Dxt1FourColourMode) {
    u8 b[8];
    dxtColorBlock(b, 0xE4, 0xFFFF, 0x0000);  // row 0: indices 0, 1, 2, 3
    u32 out[16];
    decodeDxt1Block(b, out);
    EXPECT_EQ(out[0], 0xFFF8FCF8u);  // white without replication: F8 FC F8
    EXPECT_EQ(out[1], 0xFF000000u);
    EXPECT_EQ(out[2], rgba(496 / 3, 504 / 3, 496 / 3, 255));  // (2·C0 + C1)/3 = A5 A8 A5
    EXPECT_EQ(out[3], rgba(248 / 3, 252 / 3, 248 / 3, 255));  // (C0 + 2·C1)/3 = 52 54 52
    EXPECT_EQ(out[4], 0xFFF8FCF8u);  // rows 1–3 use index 0
    // Channel order of the endpoints: red in bits 15..11.
    dxtColorBlock(b, 0x00, 0xF800, 0x001F);
    decodeDxt1Block(b, out);
    EXPECT_EQ(out[0], rgba(0xF8, 0, 0, 255));
    dxtColorBlock(b, 0x01, 0x07E0, 0x001F);
    decodeDxt1Block(b, out);
    EXPECT_EQ(out[0], rgba(0, 0, 0xF8, 255));  // index 1 = COLOR1 = blue
}

TEST(TextureDecode, Dxt1ThreeColourModeHasTransparentBlack) {
    u8 b[8];
    dxtColorBlock(b, 0xE4, 0x0000, 0xFFFF);  // C0 <= C1
    u32 out[16];
    decodeDxt1Block(b, out);
    EXPECT_EQ(out[0], 0xFF000000u);
    EXPECT_EQ(out[1], 0xFFF8FCF8u);
    EXPECT_EQ(out[2], rgba(0x7C, 0x7E, 0x7C, 255));  // (C0 + C1)/2
    EXPECT_EQ(out[3], 0x00000000u);                  // C3 transparent black
    dxtColorBlock(b, 0xFF, 0x1234, 0x1234);          // equal endpoints are the 3-colour mode too
    decodeDxt1Block(b, out);
    EXPECT_EQ(out[3], 0x00000000u);
}

TEST(TextureDecode, Dxt3AlphaIsShiftedNotReplicated) {
    u8 b[16] = {};
    dxtColorBlock(b, 0xE4, 0x0000, 0xFFFF);
    writeLE16(b + 8, 0xF50A);  // row 0 alpha: A, 0, 5, F
    writeLE16(b + 14, 0x000F); // row 3, column 0: F
    u32 out[16];
    decodeDxt3Block(b, out);
    EXPECT_EQ(out[0], 0xA0000000u);
    EXPECT_EQ(out[1], 0x00F8FCF8u);
    EXPECT_EQ(out[2], rgba(0x7C, 0x7E, 0x7C, 0x50));
    EXPECT_EQ(out[3], 0xF0000000u);  // C3 black, alpha from the alpha block
    EXPECT_EQ(out[12], 0xF0000000u);
}

TEST(TextureDecode, Dxt5BothAlphaModes) {
    u8 b[16] = {};
    dxtColorBlock(b, 0, 0xFFFF, 0x0000);
    // Texels 0..7 use alpha indices 0..7: octal 76543210 in bits 0..23.
    b[8] = 0x88;
    b[9] = 0xC6;
    b[10] = 0xFA;
    b[14] = 255;  // A0
    b[15] = 0;    // A1
    u32 out[16];
    decodeDxt5Block(b, out);
    // ((A0·(7−n)·256)/7 + (A1·n·256)/7 + 31) >> 8 for n = 1..6, by hand.
    const u32 expect7[8] = {255, 0, 218, 182, 145, 109, 72, 36};
    for (int i = 0; i < 8; ++i) EXPECT_EQ(out[i] >> 24, expect7[i]) << i;
    EXPECT_EQ(out[8] >> 24, 255u);  // index 0
    EXPECT_EQ(out[0] & 0xFFFFFF, 0xF8FCF8u);

    b[14] = 0;
    b[15] = 255;  // A0 <= A1: 5-step mode, 6 → 0, 7 → 255
    decodeDxt5Block(b, out);
    const u32 expect5[8] = {0, 255, 51, 102, 153, 204, 0, 255};
    for (int i = 0; i < 8; ++i) EXPECT_EQ(out[i] >> 24, expect5[i]) << i;
}

TEST(TextureDecode, DxtLevelBlocksInRowsOfBufwOver4) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_DXT1, kTex, 8, 3, 3);  // 8x8: 2x2 blocks, 2 blocks per row
    u8 b[8];
    dxtColorBlock(b, 0, 0xF800, 0);  // solid red-ish block
    mem.write(kTex + 8 * 3, b, 8);   // block (1, 1)
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[5 * 8 + 5], rgba(0xF8, 0, 0, 255));
    EXPECT_EQ(out[7 * 8 + 7], rgba(0xF8, 0, 0, 255));
    EXPECT_EQ(out[3 * 8 + 3], 0xFF000000u);  // zero block: C0 = C1 = 0 → index 0 black opaque
    // A 2x2 DXT texture still reads a whole block.
    mem.write(kTex + 0x100, b, 8);
    setTexture(st, GE_TFMT_DXT1, kTex + 0x100, 8, 1, 1);
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    ASSERT_EQ(out.size(), 4u);
    EXPECT_EQ(out[3], rgba(0xF8, 0, 0, 255));
}

// ---- Swizzle (ge-rules.md §6.3) ----

TEST(TextureDecode, SwizzleOffsetExample) {
    // Manual Figure 13-7: 32-bit 16x16, P = 64; texel (5, 2) → xb = 20 → offset 164.
    EXPECT_EQ(swizzledByteOffset(20, 2, 64), 164u);
    EXPECT_EQ(swizzledByteOffset(0, 0, 64), 0u);
    EXPECT_EQ(swizzledByteOffset(16, 0, 64), 128u);
    EXPECT_EQ(swizzledByteOffset(0, 8, 64), 512u);
    EXPECT_EQ(swizzledByteOffset(63, 15, 64), 1023u);
}

// Stores a linear image swizzled with the reference's per-byte formula.
void storeSwizzled(Memory& mem, u32 addr, const std::vector<u8>& linear, u32 pitch, u32 rows) {
    for (u32 y = 0; y < rows; ++y)
        for (u32 xb = 0; xb < pitch; ++xb) {
            const u32 off = ((y / 8) * (pitch / 16) + xb / 16) * 128 + (y % 8) * 16 + xb % 16;
            mem.write8(addr + off, linear[y * pitch + xb]);
        }
}

TEST(TextureDecode, Swizzled8888MatchesLinear) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_8888, kTex, 16, 4, 4);
    set(st, GE_CMD_TMODE, 1);
    std::vector<u8> lin(64 * 16);
    for (u32 y = 0; y < 16; ++y)
        for (u32 x = 0; x < 16; ++x) writeLE32(&lin[y * 64 + x * 4], 0xFF000000u | y << 8 | x);
    storeSwizzled(mem, kTex, lin, 64, 16);
    EXPECT_EQ(mem.read32(kTex + 164), 0xFF000205u);  // texel (5, 2) where ge-rules.md §6.3 says
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    for (u32 y = 0; y < 16; ++y)
        for (u32 x = 0; x < 16; ++x) ASSERT_EQ(out[y * 16 + x], 0xFF000000u | y << 8 | x) << x << "," << y;
}

TEST(TextureDecode, SwizzledClut4AndPartialHeight) {
    Memory mem;
    GeState st;
    for (u32 i = 0; i < 16; ++i) writeLE32(st.clut + 4 * i, 0xFF000000u | i * 0x10);
    setClut(st, 3, 0, 0xFF, 0);
    // 64x4 CLUT4, pitch 32 bytes: the 4 rows sit in 8-row blocks, nibble order unchanged.
    setTexture(st, GE_TFMT_CLUT4, kTex, 64, 6, 2);
    set(st, GE_CMD_TMODE, 1);
    std::vector<u8> lin(32 * 8, 0);
    for (u32 y = 0; y < 4; ++y)
        for (u32 xb = 0; xb < 32; ++xb) lin[y * 32 + xb] = u8(((xb + y) & 0xF) | ((xb + y + 1) & 0xF) << 4);
    storeSwizzled(mem, kTex, lin, 32, 8);
    std::vector<u32> out;
    ASSERT_TRUE(decodeTextureLevel(mem, st, 0, out));
    ASSERT_EQ(out.size(), 256u);
    for (u32 y = 0; y < 4; ++y)
        for (u32 x = 0; x < 64; ++x) {
            const u32 t = (x / 2 + y + (x & 1)) & 0xF;
            ASSERT_EQ(out[y * 64 + x], 0xFF000000u | t * 0x10) << x << "," << y;
        }
}

// ---- Bad memory and hashing ----

TEST(TextureDecode, UnreadableMemoryReadsAsZero) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_8888, 0x00000000, 4, 2, 2);  // nothing mapped at 0
    std::vector<u32> out;
    EXPECT_FALSE(decodeTextureLevel(mem, st, 0, out));
    ASSERT_EQ(out.size(), 16u);
    for (u32 v : out) EXPECT_EQ(v, 0u);

    // Texture running off the end of RAM: the readable part still decodes.
    const u32 end = Memory::kRamBase + mem.ramSize();
    setTexture(st, GE_TFMT_8888, end - 32, 4, 2, 2);  // needs 64 bytes, 32 readable
    mem.write32(end - 32, 0x11223344);
    EXPECT_FALSE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_EQ(out[0], 0x11223344u);
    EXPECT_EQ(out[15], 0u);
    // Invalid format and level.
    set(st, GE_CMD_TPF, 12);
    EXPECT_FALSE(decodeTextureLevel(mem, st, 0, out));
    EXPECT_FALSE(decodeTextureLevel(mem, st, 9, out));
}

// A texture running off the end of memory reads its readable prefix and zeros after it, decoded
// piece by piece (only the rows it reads are copied): the same texels and hash as the same bytes,
// with the zeros written out, placed where all of them are readable. Every layout: linear rows
// (direct, partial and zero rows), CLUT rows, swizzled block rows and DXT block rows, off the end
// of RAM and of a VRAM mirror, with a buffer width wider than the texture.
TEST(TextureDecode, OffTheEndOfMemoryEqualsTheZeroFilledBytes) {
    struct Case {
        GeTexFormat fmt;
        bool swizzle;
        u32 bufw, wlog, hlog;
    };
    const Case cases[] = {{GE_TFMT_8888, false, 64, 5, 5}, {GE_TFMT_5650, false, 40, 5, 4},
                          {GE_TFMT_CLUT8, false, 128, 6, 5}, {GE_TFMT_CLUT4, false, 256, 7, 5},
                          {GE_TFMT_8888, true, 64, 5, 5},    {GE_TFMT_CLUT4, true, 128, 6, 5},
                          {GE_TFMT_DXT1, false, 64, 5, 5},   {GE_TFMT_DXT5, false, 32, 4, 5}};
    Memory mem;
    const u32 ramEnd = Memory::kRamBase + mem.ramSize();
    const u32 vramEnd = Memory::kVramBase + Memory::kVramSize;
    for (const Case& c : cases) {
        for (const u32 end : {ramEnd, vramEnd}) {
            GeState st;
            for (u32 i = 0; i < 256; ++i) writeLE32(st.clut + 4 * i, 0xFF000000u | (i * 0x010203u));
            setClut(st, 3, 0, 0xFF, 0);
            set(st, GE_CMD_TMODE, c.swizzle ? 1 : 0);
            setTexture(st, c.fmt, kTex, c.bufw, c.wlog, c.hlog);
            const u32 bytes = textureLevelBytes(st, 0);
            // Readable: about a third of the range (whole rows, then a row cut in the middle), the
            // texture address 16-byte aligned as TBP is.
            const u32 readable = (bytes / 3 + 8) & ~15u;
            const u32 addr = end - readable;
            std::vector<u8> image(bytes, 0);
            u32 seed = 12345;
            for (u32 i = 0; i < readable; ++i) {
                seed = seed * 1103515245u + 12345u;
                image[i] = u8(seed >> 16);
            }
            for (u32 i = 0; i < readable; ++i) mem.write8(addr + i, image[i]);
            for (u32 i = 0; i < bytes; ++i) mem.write8(kTex + i, image[i]);
            std::vector<u32> inside, offEnd;
            ASSERT_TRUE(decodeTextureLevel(mem, st, 0, inside));
            const u64 hInside = hashTextureLevel(mem, st, 0);
            setTexture(st, c.fmt, addr, c.bufw, c.wlog, c.hlog);
            EXPECT_FALSE(decodeTextureLevel(mem, st, 0, offEnd));
            EXPECT_EQ(offEnd, inside) << "format " << c.fmt << (c.swizzle ? " swizzled" : "") << " at " << std::hex << end;
            EXPECT_EQ(hashTextureLevel(mem, st, 0), hInside) << "format " << c.fmt;
        }
    }
}

TEST(TextureDecode, HashCoversTexelsAndUsedPaletteEntries) {
    Memory mem;
    GeState st;
    setTexture(st, GE_TFMT_CLUT4, kTex, 32, 3, 3);
    setClut(st, 3, 0, 0xFF, 0);  // uses entries 0..15 only
    const u64 h0 = hashTextureLevel(mem, st, 0);
    EXPECT_EQ(h0, hashTextureLevel(mem, st, 0));
    mem.write8(kTex + 3, 0x55);
    const u64 h1 = hashTextureLevel(mem, st, 0);
    EXPECT_NE(h0, h1);
    st.clut[4 * 5] = 0x77;  // used entry
    const u64 h2 = hashTextureLevel(mem, st, 0);
    EXPECT_NE(h1, h2);
    st.clut[4 * 100] = 0x77;  // unused entry
    EXPECT_EQ(h2, hashTextureLevel(mem, st, 0));
    mem.write8(kTex + 32 * 8, 0x55);  // beyond the 8x8 texture
    EXPECT_EQ(h2, hashTextureLevel(mem, st, 0));
}

}  // namespace
