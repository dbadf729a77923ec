// The project's own dumps/ scenes replayed through the plugin C ABI the way an emulator drives the
// GE (guest memory writes, list enqueue, stall updates, run, draw sync, frame read-back) give the
// same pixels as `ge2gl render` (the tools' render path on GeEngine).
#include <gtest/gtest.h>

#include <filesystem>

#include "ge2gl/ge2gl.h"
#include "hle/dump/player.h"
#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

class ApiTarget : public dump::ReplayTarget {
public:
    explicit ApiTarget(int backend) {
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.backend = backend;
        ok = ge2gl_create(&cfg, &h) == GE2GL_OK;
    }
    ~ApiTarget() override { ge2gl_destroy(h); }
    u32 ramSize() const override { return 64u << 20; }
    u32 write(u32 addr, const void* data, u32 size) override {
        return ge2gl_mem_write(h, addr, data, size) == GE2GL_OK ? size : 0;
    }
    u32 fill(u32 addr, u8 value, u32 size) override {
        std::vector<u8> b(size, value);
        return write(addr, b.data(), size);
    }
    void loadContext(const u32 ctx[512]) override { EXPECT_EQ(ge2gl_restore_context(h, ctx), GE2GL_OK) << ge2gl_last_message(h); }
    void startList(u32 pc, u32 stall) override {
        EXPECT_EQ(ge2gl_list_enqueue(h, pc, stall, -1, nullptr, &id), GE2GL_OK) << ge2gl_last_message(h);
    }
    RunStatus runTo(u32 stall, u64 budget) override {
        ge2gl_list_update_stall(h, id, stall);
        ge2gl_run_info info{};
        if (ge2gl_run(h, budget, &info) != GE2GL_OK) return RunStatus::Error;
        switch (info.ge_state) {
        case GE2GL_GE_IDLE: return RunStatus::Completed;
        case GE2GL_GE_STALLED: return RunStatus::Stalled;
        case GE2GL_GE_READY: return RunStatus::Budget;
        case GE2GL_GE_PAUSED: return RunStatus::Paused;
        default: return RunStatus::Ended;
        }
    }
    std::string lastError() override { return ge2gl_last_message(h); }
    u32 readRegister(u8 op) override {
        uint32_t w = 0;
        ge2gl_get_cmd(h, op, &w);
        return w;
    }
    bool setEdramTranslation(u32 v) override { return ge2gl_edram_set_translation(h, v, nullptr) == GE2GL_OK; }
    void finishFrame() override {
        int32_t state = 0;
        EXPECT_EQ(ge2gl_draw_sync(h, 0, &state), GE2GL_OK) << ge2gl_last_message(h);
    }

    ge2gl_context* h = nullptr;
    int32_t id = -1;
    bool ok = false;
};

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

        ApiTarget api(apiBackend);
        ASSERT_TRUE(api.ok);
        dump::ReplayResult res;
        ASSERT_TRUE(dump::replayDump(d, api, {}, res, err)) << err;
        EXPECT_EQ(res.listErrors, 0u) << res.warning;
        ASSERT_TRUE(res.hasDisplay);
        std::vector<u8> rgba(480 * 272 * 4);
        ASSERT_EQ(ge2gl_read_frame(api.h, res.displayAddr, res.displayStride, int32_t(res.displayFormat), 480, 272, rgba.data(),
                                   rgba.size()),
                  GE2GL_OK)
            << ge2gl_last_message(api.h);
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
