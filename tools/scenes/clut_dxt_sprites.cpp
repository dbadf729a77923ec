// SPDX-License-Identifier: MIT
// make_scenes Scene 2: clut_dxt_sprites (docs/scenes.md).
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

namespace ge::scenes {

namespace {

// The sprite grid: 8 columns, 3 rows of cells.
struct Grid {
    int cell = 52, pitchX = 60, pitchY = 88, x0 = 4, y0 = 10;
    int cx(int c) const { return x0 + c * pitchX; }
    int cy(int r) const { return y0 + r * pitchY; }
};

// Guest addresses of the palettes and index textures row 0 draws with.
struct ClutTextures {
    u32 palA = 0, palB = 0, pal32Addr = 0, pal5551Addr = 0;
    u32 t4Addr = 0, t4SwAddr = 0, t8Addr = 0, t8SwAddr = 0, t16Addr = 0, t32Addr = 0;
};

// Palettes and index textures.
ClutTextures placeClutTextures(ListBuilder& b) {
    ClutTextures t;
    std::vector<u16> pal16a(16), pal16b(32);
    for (u32 i = 0; i < 16; ++i) pal16a[i] = to5650(hue(i, 16));
    for (u32 i = 0; i < 32; ++i) pal16b[i] = to4444(i < 16 ? rgba(255, 0, 255) : hue(i * 3, 48, 128 + (i - 16) * 8));
    std::vector<u32> pal32(256);
    // Low nibble picks the hue, high nibble shifts it a little: masks/shifts of the index give
    // visibly different pictures.
    for (u32 i = 0; i < 256; ++i) pal32[i] = hue((i & 15) * 16 + (i >> 4), 256, 255 - (i >> 4) * 4);
    std::vector<u16> pal5551(256);
    for (u32 i = 0; i < 256; ++i) pal5551[i] = to5551(hue(255 - i, 256, (i & 8) ? 255 : 0));
    t.palA = b.place(bytes16(pal16a).data(), 32, 16);
    t.palB = b.place(bytes16(pal16b).data(), 64, 16);
    t.pal32Addr = b.place(bytes32(pal32).data(), 1024, 16);
    t.pal5551Addr = b.place(bytes16(pal5551).data(), 512, 16);

    // ---- index textures ----
    // CLUT4 32×32: 16 concentric bands.
    std::vector<u8> t4(32 * 32 / 2);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) {
            u32 d = u32(std::abs(int(x) - 16) + std::abs(int(y) - 16)) / 2;
            u32 v = d & 15;
            t4[(y * 32 + x) / 2] |= u8(v << ((x & 1) * 4));
        }
    // CLUT8 64×64: angle/radius pattern.
    std::vector<u8> t8(64 * 64);
    for (u32 y = 0; y < 64; ++y)
        for (u32 x = 0; x < 64; ++x) {
            float dx = float(x) - 31.5f, dy = float(y) - 31.5f;
            float ang = std::atan2(dy, dx) / (2 * kPi) + 0.5f;
            u32 r = u32(std::sqrt(dx * dx + dy * dy) / 2.f);
            t8[y * 64 + x] = u8((u32(ang * 240.f) & 0xF0) | (r & 0x0F));
        }
    // CLUT16 32×32: index in bits 11..4 (shift 4), junk in the other bits.
    std::vector<u16> t16(32 * 32);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) t16[y * 32 + x] = u16((((x * 8) ^ (y * 4)) & 0xFF) << 4 | 0xF00F);
    // CLUT32 32×32: index in bits 23..16 (shift 16).
    std::vector<u32> t32(32 * 32);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) t32[y * 32 + x] = ((x * 8 + y) & 0xFF) << 16 | 0xAB00CD12u;

    t.t4Addr = b.place(t4.data(), u32(t4.size()), 16);
    const auto t4sw = swizzle(t4, 16, 32);
    t.t4SwAddr = b.place(t4sw.data(), u32(t4sw.size()), 16);
    t.t8Addr = b.place(t8.data(), u32(t8.size()), 16);
    const auto t8sw = swizzle(t8, 64, 64);
    t.t8SwAddr = b.place(t8sw.data(), u32(t8sw.size()), 16);
    const auto t16b = bytes16(t16);
    t.t16Addr = b.place(t16b.data(), u32(t16b.size()), 16);
    const auto t32b = bytes32(t32);
    t.t32Addr = b.place(t32b.data(), u32(t32b.size()), 16);
    return t;
}

// Row 0: row 0: CLUT formats.
void drawClutRow(ListBuilder& b, const Grid& g, const ClutTextures& t) {
    // c0: CLUT4, 5650 palette, nearest.
    b.clutMode(GE_FORMAT_565, 0, 0x0F, 0);
    b.clutLoad(t.palA, 1);  // 16 entries × 2 bytes = one 32-byte block
    b.texMode(GE_TFMT_CLUT4, 0, false);
    b.setTexture(0, t.t4Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, g.cx(0), g.cy(0), g.cell, g.cell, 0, 0, 32, 32);
    // c1: CLUT4, 4444 palette, start 1 (entries 16–31 OR-ed in, ge-rules.md §6.4), bilinear, swizzled.
    b.clutMode(GE_FORMAT_4444, 0, 0x0F, 1);
    b.clutLoad(t.palB, 2);
    b.texMode(GE_TFMT_CLUT4, 0, true);
    b.setTexture(0, t.t4SwAddr, 32, 32, 32);
    b.texFilter(1, 1);
    texRect(b, g.cx(1), g.cy(0), g.cell, g.cell, 0, 0, 32, 32);
    // c2: CLUT8, 8888 palette, linear storage, nearest.
    b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
    b.clutLoad(t.pal32Addr, 32);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.setTexture(0, t.t8Addr, 64, 64, 64);
    b.texFilter(0, 0);
    texRect(b, g.cx(2), g.cy(0), g.cell, g.cell, 0, 0, 64, 64);
    // c3: CLUT8 swizzled, shift 4 mask 0x0F (angle bands only), bilinear.
    b.clutMode(GE_FORMAT_8888, 4, 0x0F, 0);
    b.texMode(GE_TFMT_CLUT8, 0, true);
    b.setTexture(0, t.t8SwAddr, 64, 64, 64);
    b.texFilter(1, 1);
    texRect(b, g.cx(3), g.cy(0), g.cell, g.cell, 0, 0, 64, 64);
    // c4: CLUT8 mask 0x0F with start 2 and shift 0 (radius bands from entries 32–47).
    b.clutMode(GE_FORMAT_8888, 0, 0x0F, 2);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.setTexture(0, t.t8Addr, 64, 64, 64);
    b.texFilter(0, 0);
    texRect(b, g.cx(4), g.cy(0), g.cell, g.cell, 0, 0, 64, 64);
    // c5: CLUT16, 5551 palette (alpha 0/255), shift 4, mask 0xFF.
    b.clutMode(GE_FORMAT_5551, 4, 0xFF, 0);
    b.clutLoad(t.pal5551Addr, 16);
    b.texMode(GE_TFMT_CLUT16, 0, false);
    b.setTexture(0, t.t16Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, g.cx(5), g.cy(0), g.cell, g.cell, 0, 0, 32, 32);
    // c6: CLUT32, 8888 palette reloaded, shift 16, mask 0xFF, bilinear.
    b.clutMode(GE_FORMAT_8888, 16, 0xFF, 0);
    b.clutLoad(t.pal32Addr, 32);
    b.texMode(GE_TFMT_CLUT32, 0, false);
    b.setTexture(0, t.t32Addr, 32, 32, 32);
    b.texFilter(1, 1);
    texRect(b, g.cx(6), g.cy(0), g.cell, g.cell, 0, 0, 32, 32);
    // c7: CLUT4 repeated 2×2 with the 5650 palette reloaded (palette RAM reuse after a bigger load).
    b.clutMode(GE_FORMAT_565, 0, 0x0F, 0);
    b.clutLoad(t.palA, 1);
    b.texMode(GE_TFMT_CLUT4, 0, false);
    b.setTexture(0, t.t4Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, g.cx(7), g.cy(0), g.cell, g.cell, 0, 0, 64, 64);
}

// Row 1: row 1: DXT and direct-colour formats.
void drawDxtRow(ListBuilder& b, const Grid& g) {
    const auto dxt1 = makeDxt(GE_TFMT_DXT1, 32, 32, false);
    const auto dxt1a = makeDxt(GE_TFMT_DXT1, 32, 32, true);
    const auto dxt3 = makeDxt(GE_TFMT_DXT3, 32, 32, false);
    const auto dxt5 = makeDxt(GE_TFMT_DXT5, 32, 32, false);
    b.texFilter(0, 0);
    b.texMode(GE_TFMT_DXT1, 0, false);
    placeTexture(b, 0, dxt1, 32, 32, 32);
    texRect(b, g.cx(0), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    // DXT1 with punch-through alpha, plus an alpha test that drops the transparent texels.
    b.enable(GE_CMD_ATE, true);
    b.alphaFunc(6, 0x10, 0xFF);  // GREATER 0x10
    placeTexture(b, 0, dxt1a, 32, 32, 32);
    texRect(b, g.cx(1), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    b.enable(GE_CMD_ATE, false);
    b.texMode(GE_TFMT_DXT3, 0, false);
    placeTexture(b, 0, dxt3, 32, 32, 32);
    texRect(b, g.cx(2), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_DXT5, 0, false);
    b.texFilter(1, 1);
    placeTexture(b, 0, dxt5, 32, 32, 32);
    texRect(b, g.cx(3), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);

    const std::vector<u32> pic = rings(32, 32, 0), picA = rings(32, 32, 1), picB = rings(32, 32, 2);
    std::vector<u16> p5650(32 * 32), p5551(32 * 32), p4444(32 * 32);
    for (u32 i = 0; i < 32 * 32; ++i) {
        p5650[i] = to5650(pic[i]);
        p5551[i] = to5551(picB[i]);
        p4444[i] = to4444(picA[i]);
    }
    b.texFilter(0, 0);
    b.texMode(GE_TFMT_5650, 0, false);
    placeTexture(b, 0, bytes16(p5650), 32, 32, 32);
    texRect(b, g.cx(4), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_5551, 0, true);
    placeTexture(b, 0, swizzle(bytes16(p5551), 64, 32), 32, 32, 32);
    texRect(b, g.cx(5), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    b.texFilter(1, 1);
    b.texMode(GE_TFMT_4444, 0, false);
    // Buffer width 64 > texture width 32: rows are 128 bytes apart.
    std::vector<u16> p4444wide(64 * 32, 0);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) p4444wide[y * 64 + x] = p4444[y * 32 + x];
    placeTexture(b, 0, bytes16(p4444wide), 32, 32, 64);
    texRect(b, g.cx(6), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_8888, 0, true);
    placeTexture(b, 0, swizzle(bytes32(picA), 128, 32), 32, 32, 32);
    texRect(b, g.cx(7), g.cy(1), g.cell, g.cell, 0, 0, 32, 32);
}

// Row 2: row 2: filtering, wrapping and texture functions on a small 8888 texture.
void drawFilterRow(ListBuilder& b, const Grid& g) {
    const std::vector<u32> small = checker(8, 8, 2, rgba(255, 255, 255, 255), rgba(20, 60, 200, 160));
    b.texMode(GE_TFMT_8888, 0, false);
    const u32 smallAddr = placeTexture(b, 0, bytes32(small), 8, 8, 8);
    (void)smallAddr;
    b.texFilter(0, 0);
    texRect(b, g.cx(0), g.cy(2), g.cell, g.cell, 0, 0, 8, 8);          // nearest magnification
    b.texFilter(1, 1);
    texRect(b, g.cx(1), g.cy(2), g.cell, g.cell, 0, 0, 8, 8);          // bilinear magnification
    b.texWrap(true, true);
    texRect(b, g.cx(2), g.cy(2), g.cell, g.cell, 0, 0, 16, 16);        // clamp both: the last texel repeats
    b.texWrap(false, true);
    texRect(b, g.cx(3), g.cy(2), g.cell, g.cell, 0, 0, 24, 16);        // repeat U, clamp V
    b.texWrap(false, false);
    b.texFilter(0, 0);
    // Texture functions with a coloured vertex.
    const u32 vcol = rgba(255, 160, 60, 200);
    b.texFunc(0, true);  // MODULATE
    texRect(b, g.cx(4), g.cy(2), g.cell, g.cell, 0, 0, 16, 16, vcol);
    b.texFunc(1, true);  // DECAL
    texRect(b, g.cx(5), g.cy(2), g.cell, g.cell, 0, 0, 16, 16, vcol);
    b.texFunc(2, true);  // BLEND with the environment colour
    b.texEnvColor(rgba(40, 255, 80));
    texRect(b, g.cx(6), g.cy(2), g.cell, g.cell, 0, 0, 16, 16, vcol);
    b.texFunc(4, false, true);  // ADD, RGB only, colour doubling
    texRect(b, g.cx(7), g.cy(2), g.cell, g.cell, 0, 0, 16, 16, rgba(60, 30, 10, 255));
    b.texFunc(3, true);  // REPLACE: a narrow strip under the row
    texRect(b, 4, 262, 472, 8, 0, 0, 128, 2, vcol);

    b.enable(GE_CMD_ABE, false);
    b.enable(GE_CMD_TME, false);
}

}  // namespace

void sceneClutDxtSprites(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(0, 0, 0), 0);
    // A gouraud background so alpha shows.
    gradQuad(b, 0, 0, 480, 272, rgba(40, 40, 80), rgba(120, 40, 40), rgba(30, 90, 60), rgba(200, 200, 200));

    b.enable(GE_CMD_TME, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);  // ADD, As, 1 − As
    b.texFunc(0, true);    // MODULATE, RGBA
    b.texWrap(false, false);
    b.texLevelMode(1, 0.f);  // constant level 0

    const Grid g;
    const ClutTextures t = placeClutTextures(b);
    drawClutRow(b, g, t);
    drawDxtRow(b, g);
    drawFilterRow(b, g);
    b.finish();
}

}  // namespace ge::scenes
