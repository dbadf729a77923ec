// SPDX-License-Identifier: MIT
// Corrupted dumps (wild vertex types, texture sizes, buffer addresses, counts, flow control)
// replayed through the software model: never a crash, hang or out-of-bounds access (this runs
// under ASan/UBSan in CI).
#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/lib/render.h"

using namespace ge;

TEST(SoftFuzz, CorruptedDumpsRenderWithoutCrashing) {
    auto files = frametestDumps();
    if (files.empty()) GTEST_SKIP() << "frametests not found";
    std::mt19937 rng(777);
    for (size_t i = 0; i < files.size(); i += 2) {
        const std::string& f = files[i];
        SCOPED_TRACE(f);
        dump::Dump orig;
        std::string err;
        ASSERT_TRUE(dump::loadDump(f, orig, err)) << err;
        for (int variant = 0; variant < 1; ++variant) {
            dump::Dump d = orig;
            mutateDump(d, rng, 60);
            tools::RenderOptions opt;
            opt.backend = "soft";
            tools::RenderOutput out;
            std::string e2;
            if (!tools::renderDump(d, opt, out, e2)) {
                EXPECT_FALSE(e2.empty());
            } else {
                EXPECT_EQ(out.frame.width, 480);
            }
        }
    }
}
