// SPDX-License-Identifier: MIT
// GL translator: texture sampling (nearest/bilinear with 4-bit weights, wrap/clamp), CLUT,
// render-to-texture and CLUT loads from a frame buffer, transfers and CPU writes over targets.
#include <algorithm>
#include <vector>

#include "hle/pixel_format.h"
#include "tests/gl_fixture.h"

namespace ge::gltest {
namespace {

using GlTexture = GlScene;

u32 rgba(u32 r, u32 g, u32 b, u32 a) { return r | g << 8 | b << 16 | a << 24; }

TEST_P(GlTexture, NearestRepeatAndClamp) {
    // 4×4 texture, texel (u, v) = red u·40, green v·40.
    std::vector<u32> tex(16);
    for (int v = 0; v < 4; ++v)
        for (int u = 0; u < 4; ++u) tex[size_t(v * 4 + u)] = rgba(u32(u * 40), u32(v * 40), 7, 255);
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    const u32 addr = b->place(tex.data(), 64);
    b->texMode(GE_TFMT_8888, 0, false);
    b->setTexture(0, addr, 4, 4, 4);
    b->texFunc(3, true);
    b->texFilter(0, 0);
    b->enable(GE_CMD_TME, true);
    b->texWrap(false, false);
    rect(0, 0, 8, 8, 0xFFFFFFFF, 0, 0, 8, 8);      // repeat: texel x & 3
    b->texWrap(true, true);
    rect(8, 0, 16, 8, 0xFFFFFFFF, 0, 0, 8, 8);     // clamp: min(x, 3)
    run();
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            EXPECT_EQ(px32(x, y) & 0xFFFFFF, tex[size_t((y & 3) * 4 + (x & 3))] & 0xFFFFFF) << x << "," << y;
            EXPECT_EQ(px32(8 + x, y) & 0xFFFFFF, tex[size_t(std::min(y, 3) * 4 + std::min(x, 3))] & 0xFFFFFF)
                << x << "," << y;
        }
}

TEST_P(GlTexture, BilinearUsesFourBitWeights) {
    // 2×1 texture (black, white), stretched over 16 pixels with clamp: pixel x samples at
    // u = (x + 0.5)·2/16 texels; u0 = floor(u − 0.5) and the 4-bit fraction weights the two texels
    // (docs/ge-rules.md §8.10): value = (0·(16 − f) + 255·f) >> 4... per channel ((c0·(16−f)(16−fv) + …) >> 8).
    const u32 tex[4] = {rgba(0, 0, 0, 255), rgba(255, 255, 255, 255), 0, 0};
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    const u32 addr = b->place(tex, sizeof tex);
    b->texMode(GE_TFMT_8888, 0, false);
    b->setTexture(0, addr, 2, 1, 4);
    b->texFunc(3, true);
    b->texFilter(1, 1);
    b->texWrap(true, true);
    b->enable(GE_CMD_TME, true);
    rect(0, 0, 16, 1, 0xFFFFFFFF, 0, 0, 2, 1);
    run();
    for (int x = 0; x < 16; ++x) {
        // u·256 = (x + 0.5)·2/16·256 = 32x + 16; minus 128 → position in 1/256 texel.
        const int p = 32 * x + 16 - 128;
        const int u0 = p >> 8, f = (p >> 4) & 15;
        auto texel = [&](int u) { return std::clamp(u, 0, 1) ? 255 : 0; };
        // v: 0.5·1·256 − 128 = 0 → fv = 0, both rows the same texel row (clamped).
        const int expect = (texel(u0) * (16 - f) * 16 + texel(u0 + 1) * f * 16) >> 8;
        EXPECT_EQ(px32(x, 0) & 0xFF, u32(expect)) << "x " << x;
    }
}

TEST_P(GlTexture, Clut8With5551Palette) {
    // Palette in RAM (5551), indices in RAM, shift 0 mask 0xFF start 0 (ge-rules.md §6.4).
    std::vector<u16> pal(256);
    for (int i = 0; i < 256; ++i) pal[size_t(i)] = u16((i & 31) | ((31 - (i & 31)) << 10) | 0x8000);
    std::vector<u8> idx(16 * 4);
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = u8(i * 3);
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    const u32 palAddr = b->place(pal.data(), 512);
    const u32 texAddr = b->place(idx.data(), u32(idx.size()));
    b->clutMode(GE_FORMAT_5551, 0, 0xFF, 0);
    b->clutLoad(palAddr, 16);  // 16 blocks of 32 bytes = 256 entries
    b->texMode(GE_TFMT_CLUT8, 0, false);
    b->setTexture(0, texAddr, 16, 4, 16);
    b->texFunc(3, true);
    b->texFilter(0, 0);
    b->enable(GE_CMD_TME, true);
    rect(0, 0, 16, 4, 0xFFFFFFFF, 0, 0, 16, 4);
    run();
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 16; ++x)
            EXPECT_EQ(px32(x, y) & 0xFFFFFF, decode5551(pal[idx[size_t(y * 16 + x)]]) & 0xFFFFFF) << x << "," << y;
}

TEST_P(GlTexture, RenderToTextureReadsDrawnPixels) {
    // Draw into buffer B (VRAM +0x80000), then texture from it while drawing buffer A.
    constexpr u32 kB = 0x80000;
    setupFrame();
    b->drawBuffer(GE_FORMAT_8888, kB, 64);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00102030, 0, 0x40);
    rect(0, 0, 32, 32, 0xFF0000FF);
    rect(32, 32, 64, 64, 0xFF00FF00);
    b->drawBuffer(GE_FORMAT_8888, kFbOffset, 64);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->texSync();
    b->texMode(GE_TFMT_8888, 0, false);
    b->setTexture(0, 0x04000000 + kB, 64, 64, 64);
    b->texFunc(3, true);
    b->texFilter(0, 0);
    b->enable(GE_CMD_TME, true);
    rect(0, 0, 64, 64, 0xFFFFFFFF, 0, 0, 64, 64);
    run();
    EXPECT_EQ(px32(5, 5) & 0xFFFFFF, 0x0000FFu);
    EXPECT_EQ(px32(40, 40) & 0xFFFFFF, 0x00FF00u);
    EXPECT_EQ(px32(40, 5) & 0xFFFFFF, 0x102030u);
    // The source buffer itself is in VRAM too.
    EXPECT_EQ(px32(5, 5, kB), 0x400000FFu);
}

TEST_P(GlTexture, Clut16TextureReadingA5650Framebuffer) {
    // A 16-bit frame buffer read back as a CLUT16 texture through a palette drawn by the GE into
    // another frame buffer (CLUT from a frame buffer + format reinterpretation).
    constexpr u32 kTex = 0x80000, kPal = 0x90000;
    setupFrame();
    // Palette: 16 entries of 8888 drawn into VRAM at kPal as a 16×1 8888 "frame buffer".
    b->drawBuffer(GE_FORMAT_8888, kPal, 64);
    for (int i = 0; i < 16; ++i) rect(float(i), 0, float(i + 1), 1, rgba(u32(i * 16), 0x55, u32(255 - i * 16), 0xFF));
    // Texture: a 5650 buffer whose 16-bit values are small indices: draw colour R=i·8 → value i.
    b->drawBuffer(GE_FORMAT_565, kTex, 64);
    for (int i = 0; i < 16; ++i) rect(float(i), 0, float(i + 1), 4, rgba(u32(i * 8), 0, 0, 0xFF));
    b->drawBuffer(GE_FORMAT_8888, kFbOffset, 64);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->texSync();
    b->clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
    b->clutLoad(0x04000000 + kPal, 2);  // 2 blocks = 16 entries of 32 bits
    b->texMode(GE_TFMT_CLUT16, 0, false);
    b->setTexture(0, 0x04000000 + kTex, 16, 4, 64);
    b->texFunc(3, true);
    b->texFilter(0, 0);
    b->enable(GE_CMD_TME, true);
    rect(0, 0, 16, 4, 0xFFFFFFFF, 0, 0, 16, 4);
    run();
    for (int i = 0; i < 16; ++i)
        EXPECT_EQ(px32(i, 2) & 0xFFFFFF, rgba(u32(i * 16), 0x55, u32(255 - i * 16), 0) & 0xFFFFFF) << i;
}

TEST_P(GlTexture, BlockTransferSeesDrawnPixelsAndKeepsOthers) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00AAAAAA, 0, 0x11);
    rect(0, 0, 4, 4, 0xFF0000FF);
    // Copy the 4×4 red block to (20, 20) in the same buffer (8888 → XSTART 1).
    b->copyImage(GE_FORMAT_8888, 0, 0, 4, 4, 64, 0x04000000, 20, 20, 64, 0x04000000);
    rect(40, 40, 44, 44, 0xFF00FF00);  // drawing continues after the transfer
    run();
    EXPECT_EQ(px32(21, 21), 0x110000FFu);
    EXPECT_EQ(px32(25, 21), 0x11AAAAAAu);
    EXPECT_EQ(px32(41, 41), 0x1100FF00u);
    EXPECT_EQ(px32(1, 1), 0x110000FFu);
}

TEST_P(GlTexture, CpuWriteBetweenDrawsIsKept) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00000000, 0, 0);
    rect(0, 0, 64, 2, 0xFF0000FF);
    run();  // drawn pixels are in VRAM now, target still cached
    // The CPU overwrites one pixel; the host reports it; a later draw elsewhere must not undo it.
    mem->write32(0x04000000 + (1 * 64 + 10) * 4, 0x12345678);
    renderer->memoryWritten(0x04000000 + (1 * 64 + 10) * 4, 4);
    setupFrame();
    rect(0, 10, 4, 14, 0xFF00FF00);
    run();
    EXPECT_EQ(px32(10, 1), 0x12345678u);
    EXPECT_EQ(px32(11, 1), 0x000000FFu);
    EXPECT_EQ(px32(1, 11), 0x0000FF00u);
}

TEST_P(GlTexture, MipLevelsFromConstantLodAndBias) {
    // Level 0 (8×8) red, level 1 (4×4) green. TLEVEL constant mode: d = OFFL (ge-rules.md §6.6).
    std::vector<u32> l0(64, rgba(255, 0, 0, 255)), l1(16, rgba(0, 255, 0, 255));
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    const u32 a0 = b->place(l0.data(), 256), a1 = b->place(l1.data(), 64);
    b->texMode(GE_TFMT_8888, 1, false);
    b->setTexture(0, a0, 8, 8, 8);
    b->setTexture(1, a1, 4, 4, 4);
    b->texFunc(3, true);
    b->enable(GE_CMD_TME, true);
    b->texFilter(4, 0);           // nearest mipmap nearest
    b->texLevelMode(1, 1.0f);     // d = 1.0 → level floor(1 + 0.5) = 1
    rect(0, 0, 8, 8, 0xFFFFFFFF, 0, 0, 8, 8);
    b->texLevelMode(1, 0.0f);     // d = 0 → magnification, level 0
    rect(8, 0, 16, 8, 0xFFFFFFFF, 0, 0, 8, 8);
    b->texFilter(6, 0);           // nearest mipmap linear
    b->texLevelMode(1, 0.5f);     // d = 8/16: level 0, fraction 8
    rect(16, 0, 24, 8, 0xFFFFFFFF, 0, 0, 8, 8);
    run();
    EXPECT_EQ(px32(3, 3) & 0xFFFFFF, 0x00FF00u);
    EXPECT_EQ(px32(11, 3) & 0xFFFFFF, 0x0000FFu);
    // c = (c_next·8 + c·(16 − 8)) >> 4 = (255·8) >> 4 = 127 per side (ge-rules.md §8.10).
    EXPECT_EQ(px32(19, 3) & 0xFFFFFF, rgba(127, 127, 0, 0));
}

INSTANTIATE_TEST_SUITE_P(Paths, GlTexture, GE2GL_GL_PATHS);

}  // namespace
}  // namespace ge::gltest
