// SPDX-License-Identifier: MIT
// GL translator end-to-end: clears, flat rectangles and frame-buffer formats, exact VRAM bytes.
#include "tests/gl_fixture.h"

#include "hle/pixel_format.h"

namespace ge::gltest {
namespace {

using GlBasic = GlScene;

TEST_P(GlBasic, ClearWritesColorAlphaAndDepth) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0x00332211, 0x1234, 0x5A);
    run();
    for (int y : {0, 31, 63})
        for (int x : {0, 17, 63}) {
            EXPECT_EQ(px32(x, y), 0x5A332211u) << x << "," << y;
            EXPECT_EQ(depth(x, y), 0x1234) << x << "," << y;
        }
    // Outside the scissor nothing changes (VRAM starts zeroed).
    EXPECT_EQ(px32(0, 64), 0u);
}

TEST_P(GlBasic, ClearColorOnlyKeepsAlpha) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x000000FF, 0, 0x77);
    b->clear(CLEAR_COLOR, 0x00010203, 0, 0x11);
    run();
    EXPECT_EQ(px32(5, 5), 0x77010203u);
}

TEST_P(GlBasic, RectangleCoversHalfOpenRange) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    rect(10, 20, 30, 25, 0xFF00FF00);
    run();
    EXPECT_EQ(px32(10, 20), 0x0000FF00u);  // alpha keeps the stencil (no stencil test, docs/ge-rules.md §8.7)
    EXPECT_EQ(px32(29, 24), 0x0000FF00u);
    EXPECT_EQ(px32(30, 24), 0u);
    EXPECT_EQ(px32(29, 25), 0u);
    EXPECT_EQ(px32(9, 20), 0u);
    EXPECT_EQ(px32(10, 19), 0u);
}

TEST_P(GlBasic, Format5650TruncatesOnWrite) {
    setupFrame(GE_FORMAT_565);
    b->clear(CLEAR_COLOR, 0, 0, 0);
    rect(0, 0, 8, 8, 0xFF3F7FFF);  // R=FF G=7F B=3F
    run();
    // R 0xFF → 31, G 0x7F → 31, B 0x3F → 7 (ge-rules.md §8.8 truncation).
    EXPECT_EQ(px16(3, 3), u16(31 | (31 << 5) | (7 << 11)));
    EXPECT_EQ(px16(8, 3), 0);
}

TEST_P(GlBasic, Format4444And5551KeepHighBits) {
    setupFrame(GE_FORMAT_4444);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00000000, 0, 0xF0);
    rect(0, 0, 8, 8, 0xFF80C0E0);  // R=E0 G=C0 B=80
    run();
    EXPECT_EQ(px16(1, 1), u16(0xE | (0xC << 4) | (0x8 << 8) | (0xF << 12)));
    setupFrame(GE_FORMAT_5551);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00000000, 0, 0x80);
    rect(0, 0, 8, 8, 0xFF80C0E0);
    run();
    EXPECT_EQ(px16(1, 1), u16((0xE0 >> 3) | ((0xC0 >> 3) << 5) | ((0x80 >> 3) << 10) | 0x8000));
}

TEST_P(GlBasic, PreservesExistingVramOutsideDraw) {
    // VRAM written by the CPU before any draw must survive around a draw.
    for (int i = 0; i < kSize * kSize; ++i) mem->write32(0x04000000 + u32(i) * 4, 0xDEADBEEF);
    setupFrame();
    rect(4, 4, 6, 6, 0xFF123456);
    run();
    EXPECT_EQ(px32(4, 4), 0xDE123456u);
    EXPECT_EQ(px32(6, 4), 0xDEADBEEFu);
    EXPECT_EQ(px32(63, 63), 0xDEADBEEFu);
}

INSTANTIATE_TEST_SUITE_P(Paths, GlBasic, GE2GL_GL_PATHS);

}  // namespace
}  // namespace ge::gltest
