// SPDX-License-Identifier: MIT
// Save states on real game frames: five shared frametests replayed through the C ABI
// with a save/load onto the other backend every 100 commands (tests/savestate_switch.h) finish
// with the uninterrupted software frame, pixel for pixel. Whole-frametest runs: label
// "accuracy", left out of the sanitizer pass (the project's scenes run there, api_savestate.cpp).
#include "tests/savestate_switch.h"

using namespace savestate_test;

namespace {

// Five of the shared frametests (the five with the fewest commands, so that the test stays short).
TEST(SaveStateSwitch, FrametestsEveryHundredCommandsOnAlternatingBackends) {
    if (!glAvailable()) GTEST_SKIP() << "GL backend unavailable";
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    if (!fs::is_directory(dir)) GTEST_SKIP() << "no ../shared/frametests";
    const char* names[] = {"15826 hot pixel ULUS10298.zip", "20204 Beam 'em up NPUZ00087_0001.zip",
                           "17397 Nova NPUZ00179_nova_culling.zip", "15816 Boku no Natsuyasumi 4 issue UCJS10095.zip",
                           "10928 Project Diva teardrops DUMP.zip"};
    for (const char* n : names) {
        ASSERT_TRUE(fs::exists(dir / n)) << n;
        checkDump(dir / n, GE2GL_BACKEND_SOFT);
    }
}

}  // namespace
