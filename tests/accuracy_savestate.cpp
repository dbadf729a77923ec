// SPDX-License-Identifier: MIT
// Save states on real game frames: five shared frametests replayed through the C ABI
// with a save/load onto the other backend every 100 commands (tests/savestate_switch.h) finish
// with the uninterrupted software frame, pixel for pixel. Whole-frametest runs: label
// "accuracy", left out of the sanitizer pass (the project's scenes run there, api_savestate.cpp).
#include "tests/savestate_switch.h"

using namespace savestate_test;

namespace {

// Five of the shared frametests (the five with the fewest commands, so that the test stays short),
// one test each so that ctest runs them side by side.
class SaveStateSwitchFrametest : public ::testing::TestWithParam<const char*> {};

TEST_P(SaveStateSwitchFrametest, EveryHundredCommandsOnAlternatingBackends) {
    if (!glAvailable()) GTEST_SKIP() << "GL backend unavailable";
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    if (!fs::is_directory(dir)) GTEST_SKIP() << "no ../shared/frametests";
    ASSERT_TRUE(fs::exists(dir / GetParam())) << GetParam();
    checkDump(dir / GetParam(), GE2GL_BACKEND_SOFT);
}

INSTANTIATE_TEST_SUITE_P(Frametests, SaveStateSwitchFrametest,
                         ::testing::Values("15826 hot pixel ULUS10298.zip", "20204 Beam 'em up NPUZ00087_0001.zip",
                                           "17397 Nova NPUZ00179_nova_culling.zip",
                                           "15816 Boku no Natsuyasumi 4 issue UCJS10095.zip",
                                           "10928 Project Diva teardrops DUMP.zip"),
                         [](const auto& info) { return "dump" + std::to_string(info.index); });

}  // namespace
