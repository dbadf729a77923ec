// SPDX-License-Identifier: MIT
// The backend factory (backend/factory.h): what each backend offers besides drawing, and the
// errors a GL request can meet. The plugin API and the tools rely on these answers: an interface
// offered is what turns on frame textures, scaled frames, the GL scope and --stats.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/factory.h"
#include "hle/memory.h"

namespace ge {
namespace {

TEST(BackendFactory, SoftAndNullOfferNothingButDrawing) {
    for (backend::BackendKind kind : {backend::BackendKind::Soft, backend::BackendKind::Null}) {
        Memory mem;
        backend::BackendOptions o;
        o.kind = kind;
        o.threads = 1;
        std::string err;
        backend::Backend b = backend::createBackend(mem, o, err);
        ASSERT_TRUE(b) << err;
        EXPECT_TRUE(err.empty()) << err;
        EXPECT_EQ(b.presenter, nullptr);
        EXPECT_EQ(b.scaled, nullptr);
        EXPECT_EQ(b.host, nullptr);
        EXPECT_EQ(b.stats, nullptr);
        EXPECT_TRUE(backend::backendBuilt(kind));
    }
}

TEST(BackendFactory, GlOffersEveryInterfaceAtItsScale) {
    EXPECT_TRUE(backend::backendBuilt(backend::BackendKind::Gl));  // this test program needs GL built
    for (int scale : {1, 2}) {
        Memory mem;
        backend::BackendOptions o;
        o.kind = backend::BackendKind::Gl;
        o.glMode = scale > 1 ? backend::GlMode::Hw : backend::GlMode::Exact;
        o.scale = scale;
        std::string err;
        backend::Backend b = backend::createBackend(mem, o, err);
        if (!b) GTEST_SKIP() << "no GL context: " << err;
        ASSERT_NE(b.presenter, nullptr);
        ASSERT_NE(b.scaled, nullptr);
        ASSERT_NE(b.host, nullptr);
        ASSERT_NE(b.stats, nullptr);
        EXPECT_EQ(b.scaled->renderScale(), scale);
        // Created entered; leaving and entering again works on the thread that created it.
        b.host->hostLeave();
        ASSERT_TRUE(b.host->hostEnter(err)) << err;
        std::vector<u32> rgba;
        EXPECT_EQ(b.scaled->readScaledFrame(0x04000000, 64, GE_FORMAT_8888, 16, 8, rgba), scale);
        EXPECT_EQ(rgba.size(), size_t(16 * scale) * size_t(8 * scale));
        EXPECT_NE(b.presenter->presentFrame(0x04000000, 64, GE_FORMAT_8888, 16, 8, 32, 16, err), 0u) << err;
        const std::string text = b.stats->statsText();
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 21) << text;
        EXPECT_NE(text.find("glDrawCalls"), std::string::npos) << text;
    }
}

TEST(BackendFactory, GlOptionsOutOfRangeAreErrors) {
    Memory mem;
    backend::BackendOptions o;
    o.kind = backend::BackendKind::Gl;
    o.glContext = backend::GlContext::Null;  // no driver needed to reach the checks
    o.scale = 2;                             // exact mode
    std::string err;
    EXPECT_FALSE(backend::createBackend(mem, o, err));
    EXPECT_NE(err.find("hardware mode"), std::string::npos) << err;
    o.glMode = backend::GlMode::Hw;
    o.scale = 9;
    err.clear();
    EXPECT_FALSE(backend::createBackend(mem, o, err));
    EXPECT_NE(err.find("out of range"), std::string::npos) << err;
    o.scale = 1;
    err.clear();
    backend::Backend b = backend::createBackend(mem, o, err);
    ASSERT_TRUE(b) << err;
    EXPECT_NE(b.host, nullptr);
}

}  // namespace
}  // namespace ge
