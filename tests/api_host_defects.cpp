// SPDX-License-Identifier: MIT
// What a threaded emulator host tripped on, each returning GE2GL_OK or blocking silently before:
// a GL_CURRENT instance called with another context (or none) current, a partial write-back over
// CPU writes the host did not report, one huge draw holding a call for seconds, data dropped
// without a word, a frame address inside a pixel. Hosts use only the C ABI (docs/plugin-api.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <memory>
#include <string>
#include <vector>

#include "authoring/list_builder.h"
#include "ge2gl/ge2gl.h"
#include "hle/memory.h"
#include "tests/api_embed_host.h"
#include "tests/api_gl_host.h"

using namespace apitest;

namespace {

constexpr uint32_t kRamSize = GameHost::kRamSize, kVram = 0x04000000;
constexpr uint32_t RED = 0xFF0000FF, BLUE = 0xFFFF0000;  // ABGR
constexpr uint32_t kVt = ge::vt::COL_8888 | ge::vt::POS_16 | ge::vt::THROUGH;

using Drop = GameHost::Drop;

// The game-like host (tests/api_embed_host.h) with 1 MiB per list (room for big vertex arrays)
// and no vram_dirty callback: lazy write-back ranges stay with ge2gl until a sync asks for them.
struct DefectHost : GameHost {
    template <class Tweak>
    DefectHost(int backend, Tweak tweak)
        : GameHost(backend, [&](ge2gl_config& c) {
              c.vram_dirty = nullptr;
              tweak(c);
          }) {
        arena = 0x08100000;
        arenaStep = 0x100000;
    }
    explicit DefectHost(int backend) : DefectHost(backend, [](ge2gl_config&) {}) {}
};

uint32_t rgb(uint32_t abgr) { return abgr & 0xFFFFFF; }

std::unique_ptr<GlHost> makeGlHost(GlHost::Kind k) {
    auto g = std::make_unique<GlHost>(k);
    if (!g->ok()) return nullptr;
    return g;
}

bool headlessGl() {
    DefectHost probe(GE2GL_BACKEND_GL_HEADLESS);
    return probe.status == GE2GL_OK;
}

// Full-screen triangles in through mode, `count` vertices, blended.
std::vector<uint8_t> fullScreenTriangles(uint32_t count) {
    std::vector<ge::BuildVertex> v(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t k = i % 3;
        v[i].x = k == 1 ? 960.0f : 0.0f;
        v[i].y = k == 2 ? 544.0f : 0.0f;
        v[i].color = 0x80FFFFFF;
    }
    return ge::packVertices(kVt, v.data(), count);
}

}  // namespace

// "GL_CURRENT with another (unshared) context current: draw_sync returns OK, leaves
// GL_INVALID_OPERATION in that context and the draw is never made; with no context current the
// draw is lost; after the host destroyed its context, calls still return OK."
TEST(ApiGlContext, AnotherContextOrNoneCurrentIsAnErrorAndNothingIsDrawnThere) {
    int hosts = 0;
    for (GlHost::Kind kind : {GlHost::Kind::EGL, GlHost::Kind::OSMesa}) {
        SCOPED_TRACE(kind == GlHost::Kind::EGL ? "EGL host" : "OSMesa host");
        auto a = makeGlHost(kind);
        if (!a) continue;
        ++hosts;
        DefectHost gl(GE2GL_BACKEND_GL_CURRENT, [&](ge2gl_config& c) { c.gl_get_proc_address = a->loader(); });
        ASSERT_EQ(gl.status, GE2GL_OK) << ge2gl_last_message(nullptr);
        auto b = makeGlHost(kind);  // made current on this thread
        ASSERT_TRUE(b);
        ASSERT_TRUE(b->isCurrent());
        ASSERT_EQ(gl.enqueue(gl.list([](ge::ListBuilder& l) { DefectHost::clearTo(l, RED); })), GE2GL_OK);
        EXPECT_EQ(gl.drawSync(), GE2GL_ERR_GL_CONTEXT);
        EXPECT_NE(std::string(ge2gl_last_message(gl.h)).find("not the one"), std::string::npos) << ge2gl_last_message(gl.h);
        EXPECT_EQ(b->GetError(), GLenum(GL_NO_ERROR)) << "ge2gl left an error in the other context";
        EXPECT_EQ(gl.hostPixel(10, 10), 0u);
        // None current.
        b->release();
        EXPECT_EQ(gl.drawSync(), GE2GL_ERR_GL_CONTEXT);
        EXPECT_NE(std::string(ge2gl_last_message(gl.h)).find("no GL context"), std::string::npos) << ge2gl_last_message(gl.h);
        // Its own context back: the list draws.
        ASSERT_TRUE(a->makeCurrent());
        EXPECT_EQ(gl.drawSync(), GE2GL_OK) << ge2gl_last_message(gl.h);
        EXPECT_EQ(rgb(gl.hostPixel(10, 10)), rgb(RED));
        // The host destroys its context, a new one is current: an error, and destroy harms nothing.
        ASSERT_EQ(gl.enqueue(gl.list([](ge::ListBuilder& l) { DefectHost::clearTo(l, BLUE); })), GE2GL_OK);
        a.reset();
        ASSERT_TRUE(b->makeCurrent());
        EXPECT_EQ(gl.drawSync(), GE2GL_ERR_GL_CONTEXT);
        EXPECT_EQ(b->GetError(), GLenum(GL_NO_ERROR));
        b->release();
        EXPECT_EQ(gl.drawSync(), GE2GL_ERR_GL_CONTEXT);
    }
    if (!hosts) GTEST_SKIP() << "no host GL context could be made";
}

// "A CPU write to VRAM row 10 that was not reported, then ge2gl_sync_range on row 175 only: row 10
// gets the GPU's old pixels."
TEST(ApiCoherence, SyncRangeWritesBackOnlyItsRangeAndKeepsUnreportedCpuWrites) {
    if (!headlessGl()) GTEST_SKIP() << "GL backend unavailable";
    for (int mode : {GE2GL_GL_MODE_EXACT, GE2GL_GL_MODE_HW}) {
        SCOPED_TRACE(mode == GE2GL_GL_MODE_HW ? "hw 2x" : "exact");
        DefectHost host(GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) {
            c.lazy_writeback = 1;
            c.gl_mode = mode;
            c.render_scale = mode == GE2GL_GL_MODE_HW ? 2 : 1;
        });
        ASSERT_EQ(host.status, GE2GL_OK);
        ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { DefectHost::clearTo(b, RED); })), GE2GL_OK);
        host.pokePixel(20, 10, BLUE);  // not reported
        host.pokePixel(20, 176, BLUE);
        // Row 175 from x = 8 to the end of the row, and one pixel of row 176 cut in half.
        ASSERT_EQ(ge2gl_sync_range(host.h, kVram + (175 * 512 + 8) * 4, (512 - 8) * 4 + 2), GE2GL_OK);
        EXPECT_EQ(rgb(host.hostPixel(100, 175)), rgb(RED));
        EXPECT_EQ(rgb(host.hostPixel(8, 175)), rgb(RED));
        EXPECT_EQ(host.hostPixel(7, 175), 0u) << "before the range";
        EXPECT_EQ(host.hostPixel(0, 176), 0u) << "a pixel half inside the range";
        EXPECT_EQ(host.hostPixel(20, 10), BLUE);
        EXPECT_EQ(host.hostPixel(20, 176), BLUE);
        EXPECT_EQ(host.hostPixel(30, 10), 0u);
        // What was not written back still is, when asked: the rest of the frame.
        ASSERT_EQ(ge2gl_sync_range(host.h, kVram, 512 * 100 * 4), GE2GL_OK);
        EXPECT_EQ(rgb(host.hostPixel(30, 10)), rgb(RED));
        EXPECT_EQ(host.hostPixel(30, 150), 0u);
    }
}

// "One PRIM of 65,535 full-screen vertices runs 21 s inside one draw_sync."
TEST(ApiBudget, AHugeDrawStopsAtTheRunBudgetWithAStatusAndTheListGoesOn) {
    for (int backend : {GE2GL_BACKEND_SOFT, GE2GL_BACKEND_GL_HEADLESS}) {
        SCOPED_TRACE(backend == GE2GL_BACKEND_SOFT ? "soft" : "gl");
        if (backend != GE2GL_BACKEND_SOFT && !headlessGl()) continue;
        DefectHost host(backend);
        ASSERT_EQ(host.status, GE2GL_OK);
        const std::vector<uint8_t> tris = fullScreenTriangles(65535);
        const uint32_t l = host.list([&](ge::ListBuilder& b) {
            b.enable(ge::GE_CMD_ABE, true);
            b.blendFunc(ge::BLEQ_ADD, 2, 3);
            b.drawArrayData(ge::GE_PRIM_TRIANGLES, kVt, 65535, nullptr, tris.data());
            DefectHost::clearTo(b, RED);  // after the cut draw: must still happen
        });
        ASSERT_EQ(host.enqueue(l), GE2GL_OK);
        EXPECT_EQ(host.drawSync(), GE2GL_ERR_TIME_BUDGET);
        const std::string why = ge2gl_last_message(host.h);
        EXPECT_NE(why.find("run_budget_us"), std::string::npos) << why;
        ge2gl_stats s = host.stats();
        EXPECT_EQ(s.draws_cut, 1u);
        EXPECT_NE(std::string(s.last_drop).find("budget"), std::string::npos) << s.last_drop;
        // Ten 60 Hz frames of GE time (the default budget) and a little for the list around it.
        const uint64_t budget = 222'000'000ull / 6;
        EXPECT_LE(s.ge_ticks, budget + budget / 100);
        ASSERT_EQ(host.drops.size(), 1u);
        // The list goes on after the cut draw.
        EXPECT_EQ(host.drawSync(), GE2GL_OK) << ge2gl_last_message(host.h);
        EXPECT_EQ(rgb(host.hostPixel(5, 5)), rgb(RED));
        // A budget the host sets: 1 ms.
        DefectHost small(backend, [](ge2gl_config& c) { c.run_budget_us = 1000; });
        ASSERT_EQ(small.enqueue(small.list([&](ge::ListBuilder& b) {
            b.drawArrayData(ge::GE_PRIM_TRIANGLES, kVt, 300, nullptr, tris.data());
        })),
                  GE2GL_OK);
        ge2gl_run_info info{};
        EXPECT_EQ(ge2gl_run(small.h, 1000, &info), GE2GL_ERR_TIME_BUDGET);
        EXPECT_EQ(info.ge_state, GE2GL_GE_READY);
        EXPECT_LE(small.stats().ge_ticks, 222'000u + 2'220u);
        // No limit: the same draw completes.
        DefectHost none(backend, [](ge2gl_config& c) { c.run_budget_us = UINT32_MAX; });
        ASSERT_EQ(none.draw(none.list([&](ge::ListBuilder& b) {
            b.drawArrayData(ge::GE_PRIM_TRIANGLES, kVt, 300, nullptr, tris.data());
        })),
                  GE2GL_OK);
        EXPECT_EQ(none.stats().draws_cut, 0u);
    }
}

// A run that is not cut stops between commands once the call has spent its budget (no draw is
// cut): ge2gl_run returns OK with the GE READY, and the next call goes on.
TEST(ApiBudget, ARunStopsBetweenDrawsOnceTheCallSpentItsBudget) {
    DefectHost host(GE2GL_BACKEND_SOFT, [](ge2gl_config& c) { c.run_budget_us = 2000; });
    ASSERT_EQ(host.status, GE2GL_OK);
    const std::vector<uint8_t> tris = fullScreenTriangles(30);
    ASSERT_EQ(host.enqueue(host.list([&](ge::ListBuilder& b) {
        for (int i = 0; i < 40; ++i) b.drawArrayData(ge::GE_PRIM_TRIANGLES, kVt, 30, nullptr, tris.data());
    })),
              GE2GL_OK);
    int calls = 0;
    ge2gl_run_info info{};
    do {
        ASSERT_EQ(ge2gl_run(host.h, 1u << 20, &info), GE2GL_OK) << ge2gl_last_message(host.h);
        ++calls;
    } while (info.ge_state == GE2GL_GE_READY && calls < 1000);
    EXPECT_EQ(info.ge_state, GE2GL_GE_IDLE);
    EXPECT_GT(calls, 2);
    EXPECT_EQ(host.stats().draws_cut, 0u);
}

// "A Bezier of 253x253 control points at 64x64 divisions draws nothing; vertex or index reads
// past the end of RAM are ignored silently."
TEST(ApiDrops, DroppedPatchesAndVerticesAreReportedAndCounted) {
    for (int backend : {GE2GL_BACKEND_SOFT, GE2GL_BACKEND_GL_HEADLESS}) {
        SCOPED_TRACE(backend == GE2GL_BACKEND_SOFT ? "soft" : "gl");
        if (backend != GE2GL_BACKEND_SOFT && !headlessGl()) continue;
        // No run budget: the patch's vertex work is charged at the tessellator's cap.
        DefectHost host(backend, [](ge2gl_config& c) { c.run_budget_us = UINT32_MAX; });
        ASSERT_EQ(host.status, GE2GL_OK);
        const uint32_t ramEnd = 0x08000000 + kRamSize;
        const uint32_t l = host.list([&](ge::ListBuilder& b) {
            b.patchDivide(64, 64);
            b.drawBezier(ge::vt::POS_F, 253, 253, 0, 0x08400000);
            // 16 vertices of 12 bytes whose last 4 lie past the end of RAM.
            b.drawArray(ge::GE_PRIM_TRIANGLES, kVt, 16, 0, ramEnd - 12 * 12);
            // An index past RAM's end.
            const uint16_t idx[3] = {0, 1, 60000};
            b.drawArrayData(ge::GE_PRIM_TRIANGLES, kVt | ge::vt::IDX_16, 3, idx, nullptr);
        });
        ASSERT_EQ(host.draw(l), GE2GL_OK) << ge2gl_last_message(host.h);
        ASSERT_EQ(host.drops.size(), 3u);
        EXPECT_NE(host.drops[0].message.find("BEZIER of 253x253 control points at 64x64 divisions"), std::string::npos)
            << host.drops[0].message;
        EXPECT_NE(host.drops[0].message.find("not drawn"), std::string::npos);
        EXPECT_NE(host.drops[1].message.find("16 vertices"), std::string::npos) << host.drops[1].message;
        EXPECT_NE(host.drops[2].message.find("vertex 60000"), std::string::npos) << host.drops[2].message;
        for (const Drop& d : host.drops) EXPECT_GT(d.pc, l);
        const ge2gl_stats s = host.stats();
        EXPECT_EQ(s.draws_dropped, 3u);
        EXPECT_EQ(s.draws, 3u);
        EXPECT_EQ(std::string(s.last_drop), host.drops[2].message);
    }
}

// "ge2gl_read_frame accepts an unaligned 8888 address."
TEST(ApiErrors, FrameAddressesInsideAPixelAreRefused) {
    DefectHost host(GE2GL_BACKEND_SOFT);
    ASSERT_EQ(host.status, GE2GL_OK);
    std::vector<uint8_t> out(16 * 16 * 4);
    EXPECT_EQ(ge2gl_read_frame(host.h, kVram + 2, 16, GE2GL_FORMAT_8888, 16, 16, out.data(), out.size()),
              GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ge2gl_last_message(host.h)).find("not aligned"), std::string::npos);
    EXPECT_EQ(ge2gl_read_frame(host.h, kVram + 1, 16, GE2GL_FORMAT_565, 16, 16, out.data(), out.size()),
              GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_read_frame(host.h, kVram + 2, 16, GE2GL_FORMAT_565, 16, 16, out.data(), out.size()), GE2GL_OK);
    EXPECT_EQ(ge2gl_read_frame(host.h, kVram + 4, 16, GE2GL_FORMAT_8888, 16, 16, out.data(), out.size()), GE2GL_OK);
}

namespace {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(p * double(v.size())))];
}

#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
constexpr double kSlowdown = 10;  // sanitizer builds: the same check, a tenfold slower machine
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer)
constexpr double kSlowdown = 10;
#else
constexpr double kSlowdown = 1;
#endif
#else
constexpr double kSlowdown = 1;
#endif

}  // namespace

// "With 600 full-screen blended sprites, mem_write / get_cmd / list_update_stall waited 1.0-1.3 s
// (soft) and 0.28-0.59 s (GL)": the GE thread held the handle's lock through every draw. Now
// it leaves it while the backend draws (api/render_gate.h); the calls a CPU thread makes while
// its GE thread draws answer within 2 ms at the 99th percentile (docs/plugin-api.md "Threads").
TEST(ApiThreads, CallsFromTheCpuThreadAnswerWhileTheGeThreadDraws) {
    for (int backend : {GE2GL_BACKEND_SOFT, GE2GL_BACKEND_GL_HEADLESS}) {
        const char* name = backend == GE2GL_BACKEND_SOFT ? "soft" : "gl exact";
        SCOPED_TRACE(name);
        if (backend != GE2GL_BACKEND_SOFT && !headlessGl()) continue;
        DefectHost host(backend, [](ge2gl_config& c) { c.run_budget_us = UINT32_MAX; });
        ASSERT_EQ(host.status, GE2GL_OK);
        std::vector<ge::BuildVertex> corners(2);
        corners[1].x = 480;
        corners[1].y = 272;
        corners[0].color = corners[1].color = 0x80FFFFFF;
        const std::vector<uint8_t> sprite = ge::packVertices(kVt, corners.data(), 2);
        const uint32_t l = host.list([&](ge::ListBuilder& b) {
            b.enable(ge::GE_CMD_ABE, true);
            b.blendFunc(ge::BLEQ_ADD, 2, 3);
            for (int i = 0; i < 600; ++i) b.drawArrayData(ge::GE_PRIM_RECTANGLES, kVt, 2, nullptr, sprite.data());
        });
        // The list is placed whole: enqueued without a stall (0), and the updates keep it so.
        // update_stall, mem_write (RAM the list does not use), get_cmd, peek draw_sync.
        const char* names[4] = {"update_stall", "mem_write", "get_cmd", "draw_sync peek"};
        std::vector<double> us[4];
        const uint8_t bytes[64] = {1, 2, 3};
        double drawSeconds = 0;
        for (int round = 0; round < 20 && std::min({us[0].size(), us[1].size(), us[2].size(), us[3].size()}) < 1000;
             ++round) {
            int32_t id = -1;
            ASSERT_EQ(ge2gl_list_enqueue(host.h, l, 0, -1, nullptr, &id), GE2GL_OK);
            std::atomic<bool> done{false};
            ge2gl_status synced = GE2GL_ERR_BAD_STATE;
            const auto t0 = std::chrono::steady_clock::now();
            std::thread ge([&] {
                int32_t s = -1;
                synced = ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s);
                done = true;
            });
            for (int k = 0; !done.load(); k = (k + 1) % 4) {
                const auto c0 = std::chrono::steady_clock::now();
                ge2gl_status s = GE2GL_OK;
                uint32_t word = 0;
                int32_t state = -1;
                switch (k) {
                case 0: s = ge2gl_list_update_stall(host.h, id, 0); break;
                case 1: s = ge2gl_mem_write(host.h, 0x08700000, bytes, sizeof bytes); break;
                case 2: s = ge2gl_get_cmd(host.h, ge::GE_CMD_VTYPE, &word); break;
                default: s = ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &state); break;
                }
                const double dt = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - c0).count();
                if (done.load()) break;  // the list ended during the call: not a call during a draw
                // The GL backend completes the list's commands and then draws its batch at FINISH,
                // and the waiting thread frees the list before it returns: update_stall then
                // rightly answers that the list has completed or is gone.
                if (k == 0 && (s == GE2GL_SCE_ERROR_ALREADY || s == GE2GL_SCE_ERROR_INVALID_ID)) s = GE2GL_OK;
                if (s != GE2GL_OK) {
                    ADD_FAILURE() << names[k] << ": " << ge2gl_last_message(host.h);
                    break;
                }
                us[k].push_back(dt);
                std::this_thread::sleep_for(std::chrono::microseconds(50));
            }
            ge.join();
            drawSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            ASSERT_EQ(synced, GE2GL_OK) << ge2gl_last_message(host.h);
        }
        for (int k = 0; k < 4; ++k) {
            const double p99 = percentile(us[k], 0.99);
            std::printf("[%s] %-14s calls %zu  p50 %.1f us  p99 %.1f us  max %.1f us  (GE thread drew %.2f s)\n", name,
                        names[k], us[k].size(), percentile(us[k], 0.5), p99, percentile(us[k], 1.0), drawSeconds);
            EXPECT_GE(us[k].size(), 1000u) << names[k];
            EXPECT_LT(p99, 2000.0 * kSlowdown) << names[k];
        }
    }
}
