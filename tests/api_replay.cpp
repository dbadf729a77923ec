// SPDX-License-Identifier: MIT
// The project's own dumps/ scenes replayed through the plugin C ABI the way an emulator drives the
// GE (ge2gl_replay_dump: guest memory writes, list enqueue, stall updates, run, draw sync; then a
// frame read-back) give the same pixels as `ge2gl render` (the tools' render path on GeEngine).
#include <gtest/gtest.h>

#include <filesystem>

#include "ge2gl/ge2gl.h"
#include "hle/dump/player.h"
#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

void replayScenesThroughApi(int apiBackend, const std::string& cliBackend) {
    fs::path dir = fs::path(GE2GL_SOURCE_DIR) / "dumps";
    int scenes = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".ppdmp") continue;
        SCOPED_TRACE(e.path().string());
        ++scenes;
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(e.path().string(), d, err)) << err;

        tools::RenderOptions opt;
        opt.backend = cliBackend;
        tools::RenderOutput cli;
        ASSERT_TRUE(tools::renderDump(d, opt, cli, err)) << err;

        // ge2gl_replay_dump: the library's player target makes the calls an emulator makes
        // (memory writes, enqueue, stall updates, runs, draw sync) on the handle.
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.backend = apiBackend;
        ge2gl_context* h = nullptr;
        ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK) << ge2gl_last_message(nullptr);
        ge2gl_display disp{};
        ASSERT_EQ(ge2gl_replay_dump(h, e.path().c_str(), &disp), GE2GL_OK) << ge2gl_last_message(h);
        EXPECT_EQ(disp.addr, cli.displayAddr);
        std::vector<u8> rgba(480 * 272 * 4);
        ASSERT_EQ(ge2gl_read_frame(h, disp.addr, disp.stride, disp.format, 480, 272, rgba.data(), rgba.size()), GE2GL_OK)
            << ge2gl_last_message(h);
        ge2gl_destroy(h);
        size_t differing = 0;
        for (size_t i = 0; i < 480 * 272; ++i) {
            const u32 p = readLE32(&rgba[4 * i]) & 0xFFFFFF;
            differing += p != (cli.frame.rgba[i] & 0xFFFFFF);
        }
        EXPECT_EQ(differing, 0u);
        size_t lit = 0;
        for (u32 p : cli.frame.rgba) lit += (p & 0xFFFFFF) != 0;
        EXPECT_GT(lit, 1000u);  // the comparison is not between two blank frames
    }
    EXPECT_GE(scenes, 5);
}

TEST(ApiReplay, ScenesMatchTheCliRenderExactly) { replayScenesThroughApi(GE2GL_BACKEND_SOFT, "soft"); }

TEST(ApiReplay, ScenesMatchTheCliRenderExactlyWithGl) {
    {
        Memory probe(1u << 20);
        std::string err;
        tools::RenderOptions o;
        o.backend = "gl";
        if (!tools::createBackend(o, probe, err)) GTEST_SKIP() << "GL backend unavailable: " << err;
    }
    replayScenesThroughApi(GE2GL_BACKEND_GL_HEADLESS, "gl");
}

}  // namespace
