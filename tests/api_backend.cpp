// SPDX-License-Identifier: MIT
// The plugin API with real drawing (software backend), with the worker thread, and the public
// headers' build hygiene.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "authoring/list_builder.h"
#include "ge2gl/ge2gl.hpp"
#include "hle/ge_engine.h"
#include "softmodel/soft_renderer.h"
#include "tests/api_host.h"
#include "tests/reference_quirk_scenes.h"

using namespace apitest;

namespace {

constexpr uint32_t TEC = 0xCA;
constexpr uint32_t L0 = 0x08100000;

// A small scene: clear to a colour, then a gouraud-less flat rectangle, built like a game would
// (sceGu-style words) into the host's RAM. Returns the list address.
uint32_t buildScene(std::vector<uint8_t>& ram, std::vector<uint8_t>& vram) {
    ge::Memory mem(ram.data(), uint32_t(ram.size()), vram.data());
    ge::ListBuilder b(&mem, 0x08200000);
    b.drawBuffer(ge::GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.clear(ge::CLEAR_COLOR | ge::CLEAR_STENCIL, 0xFF202080, 0);  // ABGR
    b.fillRect(100, 50, 200, 150, 0xFF00FF00);
    b.finish(0x77);
    return b.placeList();
}

}  // namespace

TEST(ApiSoft, DrawsIntoHostVramAndReadsTheFrameBack) {
    Host host(GE2GL_BACKEND_SOFT);
    ASSERT_EQ(host.status, GE2GL_OK);
    const uint32_t list = buildScene(host.ram, host.vram);
    ASSERT_NE(list, 0u);
    int32_t id, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, list, 0, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    ASSERT_EQ(host.only("F").size(), 1u);
    std::vector<uint8_t> rgba(480 * 272 * 4);
    ASSERT_EQ(ge2gl_read_frame(host.h, 0x04000000, 512, GE2GL_FORMAT_8888, 480, 272, rgba.data(), rgba.size()), GE2GL_OK);
    auto px = [&](int x, int y) { return &rgba[(size_t(y) * 480 + x) * 4]; };
    // Clear colour ABGR 0xFF202080: R 0x80, G 0x20, B 0x20; alpha = stencil 0 (docs/ge-rules.md §8.4).
    EXPECT_EQ(px(0, 0)[0], 0x80);
    EXPECT_EQ(px(0, 0)[1], 0x20);
    EXPECT_EQ(px(0, 0)[2], 0x20);
    EXPECT_EQ(px(0, 0)[3], 0x00);
    // Rectangle [100,200) x [50,150): green.
    EXPECT_EQ(px(100, 50)[1], 0xFF);
    EXPECT_EQ(px(100, 50)[0], 0x00);
    EXPECT_EQ(px(199, 149)[1], 0xFF);
    EXPECT_EQ(px(200, 149)[0], 0x80);  // right edge exclusive
    EXPECT_EQ(px(150, 150)[0], 0x80);  // bottom edge exclusive
    // The host's own VRAM holds the pixels (the API drew in place).
    EXPECT_EQ(host.vram[(50 * 512 + 100) * 4 + 1], 0xFF);

    // The same list through a GeEngine + software renderer directly gives the same VRAM bytes.
    std::vector<uint8_t> ram2(kRamSize), vram2(0x200000);
    const uint32_t list2 = buildScene(ram2, vram2);
    ASSERT_EQ(list2, list);
    ge::Memory mem2(ram2.data(), kRamSize, vram2.data());
    auto r = ge::soft::createSoftRenderer(mem2, {});
    ge::GeEngine eng(mem2, r.get());
    eng.startList(list2, 0);
    EXPECT_EQ(eng.run(), ge::RunStatus::Completed);
    r->flushToMemory();
    EXPECT_TRUE(vram2 == host.vram);
}

TEST(ApiWorker, StreamsAListMovingTheStallFromTheHostThread) {
    Host host(GE2GL_BACKEND_NULL, 0, true);
    ASSERT_EQ(host.status, GE2GL_OK);
    EXPECT_EQ(ge2gl_run(host.h, 10, nullptr), GE2GL_ERR_BAD_STATE);
    std::thread::id finishThread;
    host.onFinish = [&](const ge2gl_interrupt&) { finishThread = std::this_thread::get_id(); };
    int32_t id, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &id), GE2GL_OK);
    ListWriter L(host, L0);
    for (uint32_t chunk = 0; chunk < 20; ++chunk) {
        for (uint32_t k = 0; k < 50; ++k) L.put(TEC, chunk * 50 + k + 1);
        ASSERT_EQ(ge2gl_list_update_stall(host.h, id, L.here()), GE2GL_OK);
    }
    // Everything written so far is executed; then the GE sits at the stall.
    EXPECT_EQ(ge2gl_list_sync(host.h, id, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_EQ(host.cmd(TEC), (TEC << 24) | 1000u);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_STALLING);
    L.finish(3);
    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, L.here()), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);
    ASSERT_EQ(host.only("F").size(), 1u);
    EXPECT_EQ(host.only("F")[0].arg, 3u);
    EXPECT_NE(finishThread, std::this_thread::get_id());  // delivered on the worker
    EXPECT_EQ(host.peek(id), GE2GL_SCE_ERROR_INVALID_ID);  // freed by the draw sync
}

TEST(ApiWorker, SameResultsAsInlineMode) {
    auto render = [](bool worker) {
        Host host(GE2GL_BACKEND_SOFT, 0, worker);
        const uint32_t list = buildScene(host.ram, host.vram);
        int32_t id, s;
        EXPECT_EQ(ge2gl_list_enqueue(host.h, list, 0, -1, nullptr, &id), GE2GL_OK);
        EXPECT_EQ(ge2gl_list_sync(host.h, id, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
        std::vector<uint8_t> rgba(480 * 272 * 4);
        EXPECT_EQ(ge2gl_read_frame(host.h, 0x04000000, 512, GE2GL_FORMAT_8888, 480, 272, rgba.data(), rgba.size()), GE2GL_OK);
        return rgba;
    };
    EXPECT_TRUE(render(false) == render(true));
}

TEST(ApiCpp, WrapperOwnsTheHandleAndForwardsCallbacks) {
    std::vector<uint8_t> ram(kRamSize), vram(0x200000);
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.ram = ram.data();
    cfg.ram_size = kRamSize;
    cfg.vram = vram.data();
    cfg.backend = GE2GL_BACKEND_NULL;
    std::vector<uint32_t> finishes;
    ge2gl::Callbacks cbs;
    cbs.finish = [&](const ge2gl_interrupt& i) { finishes.push_back(i.arg); };
    cbs.signal = [](const ge2gl_interrupt&) { throw 42; };  // must not escape into C
    auto made = ge2gl::Context::create(cfg, cbs);
    ASSERT_TRUE(made.ok()) << made.message;
    ge2gl::Context ctx = std::move(made.value);
    const uint32_t words[] = {0x0E020001, 0x0C000000, 0xCA000005, 0x0F000009, 0x0C000000};
    std::memcpy(&ram[L0 - kRamBase], words, sizeof words);
    auto id = ctx.enqueue(L0, 0);
    ASSERT_TRUE(id.ok());
    auto sync = ctx.drawSync(GE2GL_SYNC_WAIT);
    ASSERT_TRUE(sync.ok()) << sync.message;
    EXPECT_EQ(finishes, std::vector<uint32_t>{9});
    EXPECT_EQ(ctx.callbackFailures(), 1u);
    EXPECT_EQ(ctx.getCmd(0xCA).value, 0xCA000005u);
    auto bad = ctx.listSync(12345, GE2GL_SYNC_PEEK);
    EXPECT_EQ(bad.status.code, GE2GL_SCE_ERROR_INVALID_ID);
    EXPECT_FALSE(bad.message.empty());
    auto m = ctx.getMatrix(10);
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(m.value.size(), 16u);
    // API 1.3 wrappers: a save state round trip, the debugger's text and a step at an idle GE.
    auto st = ctx.saveState();
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_GT(st.value.size(), 32u);
    EXPECT_TRUE(ctx.loadState(st.value).ok());
    std::vector<uint8_t> corrupt = st.value;
    corrupt[40] ^= 1;
    EXPECT_EQ(ctx.loadState(corrupt).code, GE2GL_ERR_INVALID_ARGUMENT);
    auto text = ctx.debugText(GE2GL_DEBUG_STATE);
    ASSERT_TRUE(text.ok()) << text.message;
    EXPECT_NE(text.value.find("0xca TEC      000005  rgb=#000005"), std::string::npos) << text.value;
    auto stepped = ctx.debugStep(GE2GL_STEP_COMMAND);
    ASSERT_TRUE(stepped.ok());
    EXPECT_EQ(stepped.value.ge_state, GE2GL_GE_IDLE);
    auto pal = ctx.debugReadClut();
    ASSERT_TRUE(pal.ok()) << pal.message;
    EXPECT_EQ(pal.value.size(), 512u);  // CLUT format 565 after reset: 16-bit entries
    EXPECT_TRUE(ctx.debugSetRegister(0xC5000003).ok());  // CLUT 8888
    EXPECT_EQ(ctx.debugReadClut().value.size(), 256u);
    EXPECT_EQ(ctx.debugSetRegister(0x04000000).code, GE2GL_ERR_INVALID_ARGUMENT);
    auto color = ctx.debugReadBuffer(GE2GL_DEBUG_COLOR, 8, 8);
    ASSERT_TRUE(color.ok()) << color.message;
    EXPECT_EQ(color.value.size(), 8u * 8 * 4);
    ge2gl::Context moved = std::move(ctx);
    EXPECT_FALSE(static_cast<bool>(ctx));
    EXPECT_TRUE(static_cast<bool>(moved));
}

// The public C header must compile as C99 and as C++ without warnings (-Wall -Wextra -pedantic).
TEST(ApiHeaders, CompileCleanAsC99AndCxx) {
    const std::string inc = std::string(GE2GL_SOURCE_DIR) + "/include";
    if (std::system("cc --version > /dev/null 2>&1") != 0 || std::system("c++ --version > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "no cc/c++ on PATH";
    const std::string tmp = std::string(GE2GL_BINARY_DIR) + "/api_header_check";
    std::system(("mkdir -p '" + tmp + "'").c_str());
    {
        FILE* f = std::fopen((tmp + "/check.c").c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fputs("#include <ge2gl/ge2gl.h>\nint main(void) { ge2gl_config c; ge2gl_config_init(&c); return (int)c.backend; }\n", f);
        std::fclose(f);
        f = std::fopen((tmp + "/check.cpp").c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fputs("#include <ge2gl/ge2gl.h>\n#include <ge2gl/ge2gl.hpp>\nint main() { ge2gl::Context c; return c ? 1 : 0; }\n", f);
        std::fclose(f);
    }
    const std::string flags = " -Wall -Wextra -Werror -pedantic -fsyntax-only -I'" + inc + "' ";
    EXPECT_EQ(std::system(("cc -std=c99" + flags + "'" + tmp + "/check.c'").c_str()), 0);
    EXPECT_EQ(std::system(("c++ -std=c++17" + flags + "'" + tmp + "/check.cpp'").c_str()), 0);
    EXPECT_EQ(std::system(("c++ -std=c++17 -x c++" + flags + "'" + tmp + "/check.c'").c_str()), 0);
}

// examples/minimal_host runs as a host would and writes a PNG.
TEST(ApiExample, MinimalHostRendersAFrame) {
    const std::string exe = std::string(GE2GL_BINARY_DIR) + "/examples/minimal_host";
    if (FILE* f = std::fopen(exe.c_str(), "rb")) std::fclose(f);
    else GTEST_SKIP() << "examples not built (" << exe << ")";
    const std::string png = std::string(GE2GL_BINARY_DIR) + "/minimal_host_test.png";
    std::remove(png.c_str());
    ASSERT_EQ(std::system(("'" + exe + "' '" + png + "' > /dev/null").c_str()), 0);
    FILE* f = std::fopen(png.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    unsigned char sig[8] = {};
    ASSERT_EQ(std::fread(sig, 1, 8, f), 8u);
    std::fseek(f, 0, SEEK_END);
    long size = std::ftell(f);
    std::fclose(f);
    const unsigned char expect[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    EXPECT_EQ(std::memcmp(sig, expect, 8), 0);
    EXPECT_GT(size, 480 * 272 * 4);  // stored (uncompressed) deflate blocks
}

// API 1.1: the GL hardware mode and its render scale come through the config; a 1.0 host's smaller
// config is still accepted (defaults: exact mode, scale 1). Invalid combinations are refused.
TEST(ApiGl, HardwareModeAtScaleTwoFromTheConfig) {
    std::vector<uint8_t> ram(kRamSize), vram(0x200000);
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.ram = ram.data();
    cfg.ram_size = kRamSize;
    cfg.vram = vram.data();
    cfg.backend = GE2GL_BACKEND_GL_HEADLESS;
    cfg.gl_mode = GE2GL_GL_MODE_EXACT;
    cfg.render_scale = 2;
    ge2gl_context* h = nullptr;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_INVALID_ARGUMENT);  // scale needs the hw mode
    cfg.gl_mode = 7;
    cfg.render_scale = 1;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_INVALID_ARGUMENT);
    cfg.gl_mode = GE2GL_GL_MODE_HW;
    cfg.render_scale = 9;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_INVALID_ARGUMENT);
    cfg.render_scale = 2;
    if (ge2gl_create(&cfg, &h) != GE2GL_OK) GTEST_SKIP() << "GL backend unavailable";
    const uint32_t list = buildScene(ram, vram);
    int32_t id, s;
    ASSERT_EQ(ge2gl_list_enqueue(h, list, 0, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    std::vector<uint8_t> rgba(480 * 272 * 4);
    ASSERT_EQ(ge2gl_read_frame(h, 0x04000000, 512, GE2GL_FORMAT_8888, 480, 272, rgba.data(), rgba.size()), GE2GL_OK);
    auto px = [&](int x, int y) { return &rgba[(size_t(y) * 480 + x) * 4]; };
    EXPECT_EQ(px(0, 0)[0], 0x80);
    EXPECT_EQ(px(100, 50)[1], 0xFF);
    EXPECT_EQ(px(199, 149)[1], 0xFF);
    EXPECT_EQ(px(200, 149)[0], 0x80);
    ge2gl_destroy(h);

    // A host built against API 1.0 passes the config without gl_mode / render_scale.
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_NULL;
    cfg.api_version = (1u << 16) | 0u;
    cfg.struct_size = uint32_t(offsetof(ge2gl_config, gl_mode));
    cfg.gl_mode = 99;  // beyond the 1.0 struct: never read
    ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);
    ge2gl_destroy(h);
    cfg.struct_size = uint32_t(sizeof(ge2gl_config)) + 4;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_VERSION);
}

namespace {

// Pixel (0, 0) of tests/reference_quirk_scenes.h skippedAlphaTestScene (palette entry 0 =
// 0x00000001, vertex alpha 255) drawn through the API on the software backend with `cfg`
// adjusted by `edit`: 0x000001 under the ppsspp profile (PPSSPP skips the alpha test), 0 under
// psp (the GE rejects the alpha-0 texel). Returns the create status in *status.
uint32_t clutAlphaPixel(void (*edit)(ge2gl_config&), ge2gl_status* status) {
    std::vector<uint8_t> ram(kRamSize), vram(0x200000);
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.ram = ram.data();
    cfg.ram_size = kRamSize;
    cfg.vram = vram.data();
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.soft_threads = 1;
    edit(cfg);
    ge2gl_context* h = nullptr;
    *status = ge2gl_create(&cfg, &h);
    if (*status != GE2GL_OK) return ~0u;
    ge::Memory mem(ram.data(), uint32_t(ram.size()), vram.data());
    ge::ListBuilder b(&mem, 0x08200000);
    ge::testscene::skippedAlphaTestScene(b, 0x00000001u, 255);
    b.finish(0);
    const uint32_t list = b.placeList();
    int32_t id = 0, s = 0;
    EXPECT_EQ(ge2gl_list_enqueue(h, list, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    ge2gl_destroy(h);
    return (uint32_t(vram[0]) | uint32_t(vram[1]) << 8 | uint32_t(vram[2]) << 16);
}

}  // namespace

// API 1.6 config.accuracy selects the profile (geometry/accuracy_profile.h); a host built against
// 1.5 passes the smaller struct and gets the default, psp; other values are refused.
TEST(ApiSoft, ConfigAccuracySelectsTheProfile) {
    ge2gl_status st;
    EXPECT_EQ(clutAlphaPixel([](ge2gl_config&) {}, &st), 0u);
    EXPECT_EQ(st, GE2GL_OK);
    EXPECT_EQ(clutAlphaPixel([](ge2gl_config& c) { c.accuracy = GE2GL_ACCURACY_PPSSPP; }, &st), 0x000001u);
    EXPECT_EQ(st, GE2GL_OK);
    EXPECT_EQ(clutAlphaPixel([](ge2gl_config& c) { c.accuracy = GE2GL_ACCURACY_PSP; }, &st), 0u);
    EXPECT_EQ(st, GE2GL_OK);
    // A 1.5 host: the struct ends before accuracy, so the field (set here) is never read.
    EXPECT_EQ(clutAlphaPixel(
                  [](ge2gl_config& c) {
                      c.api_version = (1u << 16) | 5u;
                      c.struct_size = uint32_t(offsetof(ge2gl_config, accuracy));
                      c.accuracy = GE2GL_ACCURACY_PPSSPP;
                  },
                  &st),
              0u);
    EXPECT_EQ(st, GE2GL_OK);
    clutAlphaPixel([](ge2gl_config& c) { c.accuracy = 7; }, &st);
    EXPECT_EQ(st, GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(GE2GL_API_VERSION_MINOR, 6);
}
