// SPDX-License-Identifier: MIT
// Regressions for what the libFuzzer harnesses found in the GL translator (docs/fuzzing.md).
#include "tests/gl_fixture.h"

namespace ge::gltest {
namespace {

using GlFuzzFindings = GlScene;

// fuzz_replay_gl: a depth buffer on the colour buffer's bytes (ZBP = FBP) with depth testing on.
// Taking the depth target claimed the colour target's bytes and freed the colour target that the
// draw was about to bind (heap-use-after-free in FramebufferManager::bindDraw). Such a draw now
// goes without a depth target, as PPSSPP treats a depth buffer at the colour buffer's address
// (the game does not care about Z); with the depth test ALWAYS and no depth writes the software
// model draws the same pixels.
TEST_P(GlFuzzFindings, DepthBufferOnTheColourBufferDrawsColour) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->depthBuffer(kFbOffset, kStride);
    b->enable(GE_CMD_ZTE, true);
    b->depthFunc(1);  // ALWAYS
    b->depthMask(true);
    rect(8, 8, 24, 24, 0xFF0000FF);
    rect(16, 16, 40, 40, 0xFF00FF00);
    run();
    EXPECT_EQ(px32(10, 10), 0x000000FFu);
    EXPECT_EQ(px32(20, 20), 0x0000FF00u);
    EXPECT_EQ(px32(39, 39), 0x0000FF00u);
    EXPECT_EQ(px32(40, 40), 0u);
}

// fuzz_replay_gl reuses one renderer for every input through forgetGuestMemory: a target drawn
// into and not yet written back must be dropped, not written over the new memory, and the next
// draw must start from what VRAM holds now (a fresh renderer's view).
TEST_P(GlFuzzFindings, ForgetGuestMemoryActsAsAFreshRenderer) {
    setupFrame();
    rect(0, 0, 32, 32, 0xFF0000FF);
    b->finish();
    engine->startList(b->placeList(), 0);
    engine->run();  // drawn into the target, not written back
    b = std::make_unique<ListBuilder>(mem.get(), b->arenaNext());
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) mem->write32(0x04000000 + kFbOffset + u32(y * int(kStride) + x) * 4, 0xFF00FF00u);
    renderer->forgetGuestMemory();
    renderer->flushToMemory();
    EXPECT_EQ(px32(10, 10), 0xFF00FF00u);  // the red square was not written back
    setupFrame();
    rect(40, 40, 48, 48, 0xFFFF0000);
    run();
    EXPECT_EQ(px32(10, 10), 0xFF00FF00u);  // the new target was read from VRAM
    EXPECT_EQ(px32(44, 44), 0xFFFF0000u);  // alpha (stencil bits) kept: no stencil writes
    EXPECT_EQ(px32(50, 50), 0xFF00FF00u);
}

INSTANTIATE_TEST_SUITE_P(Paths, GlFuzzFindings, GE2GL_GL_PATHS);

}  // namespace
}  // namespace ge::gltest
