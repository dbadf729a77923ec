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

INSTANTIATE_TEST_SUITE_P(Paths, GlFuzzFindings, GE2GL_GL_PATHS);

}  // namespace
}  // namespace ge::gltest
