// SPDX-License-Identifier: MIT
// Corrupted dumps replayed through the GL translator: never a crash or out-of-bounds access.
#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/lib/render.h"

using namespace ge;

TEST(GlFuzz, CorruptedDumpsRenderWithoutCrashing) {
    auto files = frametestDumps();
    if (files.empty()) GTEST_SKIP() << "frametests not found";
    {
        Memory probe(1u << 20);
        std::string err;
        tools::RenderOptions o;
        o.backend = "gl";
        if (!tools::createBackend(o, probe, err)) GTEST_SKIP() << "GL unavailable: " << err;
    }
    std::mt19937 rng(4242);
    for (size_t i = 0; i < files.size(); i += 2) {
        SCOPED_TRACE(files[i]);
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(files[i], d, err)) << err;
        mutateDump(d, rng, 60);
        tools::RenderOptions opt;
        opt.backend = "gl";
        tools::RenderOutput out;
        std::string e2;
        if (!tools::renderDump(d, opt, out, e2)) {
            EXPECT_FALSE(e2.empty());
        }
    }
}
