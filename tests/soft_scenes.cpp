// SPDX-License-Identifier: MIT
// The project's own scenes (dumps/*.ppdmp) rendered by the software model must match the checked-in
// expected images (dumps/expected/NAME-soft.png) pixel for pixel: the model is bit-exact and
// deterministic. The images are the ppsspp accuracy profile's (geometry/accuracy_profile.h): the
// model as it was before the profiles, bit for bit, but lit_textured_skinned, whose lit colours
// moved by one step on 1,866 pixels with the profile's sseVectorArithmetic (PPSSPP's float
// lengths and approximate half-vector normalisation). After an intended change of the model,
// regenerate the images with
//   GE2GL_UPDATE_EXPECTED=1 ./build/tests/test_soft --gtest_filter='Scenes*'
// and review the differences before committing them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

TEST(Scenes, SoftwareModelMatchesExpectedImages) {
    const fs::path dir = fs::path(GE2GL_SOURCE_DIR) / "dumps";
    const bool update = std::getenv("GE2GL_UPDATE_EXPECTED") != nullptr;
    int n = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".ppdmp") continue;
        ++n;
        const std::string name = e.path().stem().string();
        SCOPED_TRACE(name);
        for (int threads : {1, 2}) {
            tools::RenderOptions opt;
            opt.backend = "soft";
            opt.threads = threads;
            opt.accuracy = "ppsspp";
            tools::RenderOutput out;
            std::string err;
            ASSERT_TRUE(tools::renderDumpFile(e.path().string(), opt, out, err)) << err;
            EXPECT_EQ(out.replay.listErrors, 0u) << out.replay.warning;
            const fs::path ref = dir / "expected" / (name + "-soft.png");
            if (update && threads == 1) {
                fs::create_directories(ref.parent_path());
                ASSERT_TRUE(tools::writePng(ref.string(), out.frame, err)) << err;
            }
            tools::Image img;
            ASSERT_TRUE(tools::readImage(ref.string(), img, err)) << err;
            ASSERT_EQ(img.width, 480);
            ASSERT_EQ(img.height, 272);
            size_t differing = 0;
            for (size_t i = 0; i < img.rgba.size(); ++i) differing += (img.rgba[i] & 0xFFFFFF) != (out.frame.rgba[i] & 0xFFFFFF);
            EXPECT_EQ(differing, 0u) << "threads=" << threads;
        }
    }
    EXPECT_GE(n, 5);
}

}  // namespace
