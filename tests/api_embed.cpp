// SPDX-License-Identifier: MIT
// Embedding in an emulator: each test is a condition an emulator meets that made the
// 1.1 library return GE2GL_OK with a wrong picture or a hang — memory coherence, unreported CPU
// writes, second threads, the host's own GL context and state, presenting, callbacks that block,
// creation errors. Hosts here use only the C ABI, and for GL a context they make themselves
// (tests/api_gl_host.h).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "authoring/list_builder.h"
#include "ge2gl/ge2gl.h"
#include "hle/memory.h"
#include "tests/api_embed_host.h"
#include "tests/api_gl_host.h"

using namespace apitest;

namespace {

constexpr uint32_t kRam = 0x08000000, kRamSize = GameHost::kRamSize, kVram = 0x04000000;
constexpr uint32_t RED = 0xFF0000FF, GREEN = 0xFF00FF00, BLUE = 0xFFFF0000;  // ABGR
constexpr uint32_t kVt = ge::vt::COL_8888 | ge::vt::POS_16 | ge::vt::THROUGH;

enum class Backend { Soft, Gl, GlEgl };
const char* backendName(Backend b) { return b == Backend::Soft ? "soft" : b == Backend::Gl ? "gl-osmesa" : "gl-egl"; }

// The game-like host (tests/api_embed_host.h), also made from a test parameter.
struct EmbedHost : GameHost {
    using GameHost::GameHost;
    EmbedHost(Backend b) : GameHost(b == Backend::Soft ? GE2GL_BACKEND_SOFT : GE2GL_BACKEND_GL_HEADLESS,
                                    [b](ge2gl_config& c) { c.gl_use_egl = b == Backend::GlEgl; }) {}
    static void rect(ge::ListBuilder& b, int x0, int y0, int x1, int y1, uint32_t abgr) {
        ge::BuildVertex v[2];
        v[0].x = float(x0), v[0].y = float(y0), v[0].color = abgr;
        v[1].x = float(x1), v[1].y = float(y1), v[1].color = abgr;
        b.drawArrayData(ge::GE_PRIM_RECTANGLES, kVt, 2, nullptr, ge::packVertices(kVt, v, 2).data());
    }
};

bool glAvailable(Backend b) {
    if (b == Backend::Soft) return true;
    EmbedHost probe(b);
    return probe.status == GE2GL_OK;
}

class Coherence : public ::testing::TestWithParam<Backend> {
protected:
    void SetUp() override {
        if (!glAvailable(GetParam())) GTEST_SKIP() << "GL backend unavailable: " << ge2gl_last_message(nullptr);
    }
};

// Colour only (alpha holds stencil in CLEAR mode).
uint32_t rgb(uint32_t abgr) { return abgr & 0xFFFFFF; }

}  // namespace

// "After a draw sync with the GL backend, host VRAM still holds the previous frame."
TEST_P(Coherence, HostVramHoldsWhatWasDrawnWhenTheSyncReturns) {
    EmbedHost host(GetParam());
    ASSERT_EQ(host.status, GE2GL_OK) << ge2gl_last_message(nullptr);
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, RED); })), GE2GL_OK);
    // No ge2gl_mem_read / ge2gl_read_frame: the host looks at its own VRAM.
    EXPECT_EQ(rgb(host.hostPixel(10, 10)), rgb(RED));
    EXPECT_EQ(rgb(host.hostPixel(479, 271)), rgb(RED));
}

// "A CPU write to the frame buffer without ge2gl_mem_written is overwritten by GL": the CPU's
// pixels inside the next list's drawn bounding box but outside its primitives must survive.
TEST_P(Coherence, UnreportedCpuFrameBufferWritesSurviveTheNextList) {
    EmbedHost host(GetParam());
    ASSERT_EQ(host.status, GE2GL_OK);
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, BLUE); })), GE2GL_OK);
    for (int y = 100; y < 110; ++y)
        for (int x = 200; x < 220; ++x) host.pokePixel(x, y, GREEN);  // the CPU draws (not reported)
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) {
        EmbedHost::rect(b, 0, 0, 10, 10, RED);
        EmbedHost::rect(b, 400, 200, 410, 210, RED);
    })),
              GE2GL_OK);
    EXPECT_EQ(rgb(host.hostPixel(205, 105)), rgb(GREEN));
    EXPECT_EQ(rgb(host.hostPixel(5, 5)), rgb(RED));
    EXPECT_EQ(rgb(host.hostPixel(405, 205)), rgb(RED));
    EXPECT_EQ(rgb(host.hostPixel(300, 50)), rgb(BLUE));
}

// "A CPU texture write without ge2gl_mem_written stays stale unless the list flushes textures."
TEST_P(Coherence, UnreportedCpuTextureWritesAreSeenByTheNextList) {
    EmbedHost host(GetParam());
    ASSERT_EQ(host.status, GE2GL_OK);
    constexpr uint32_t tex = 0x08600000;
    auto fillTexture = [&](uint32_t abgr) {
        for (uint32_t i = 0; i < 16 * 16; ++i) std::memcpy(&host.ram[tex - kRam + 4 * i], &abgr, 4);
    };
    fillTexture(RED);
    constexpr uint32_t vt = ge::vt::TC_16 | ge::vt::POS_16 | ge::vt::THROUGH;
    auto sprite = [&](ge::ListBuilder& b) {
        ge::BuildVertex v[2];
        v[0].x = 0, v[0].y = 0, v[0].u = 0, v[0].v = 0;
        v[1].x = 64, v[1].y = 64, v[1].u = 16, v[1].v = 16;
        b.drawArrayData(ge::GE_PRIM_RECTANGLES, vt, 2, nullptr, ge::packVertices(vt, v, 2).data());
    };
    ASSERT_EQ(host.draw(host.list([&](ge::ListBuilder& b) {
        b.enable(ge::GE_CMD_TME, true);
        b.texMode(ge::GE_TFMT_8888, 0, false);
        b.setTexture(0, tex, 16, 16, 16);
        b.texFunc(3, true);  // replace
        b.texFilter(0, 0);
        sprite(b);
    })),
              GE2GL_OK);
    EXPECT_EQ(rgb(host.hostPixel(32, 32)), rgb(RED));
    fillTexture(GREEN);  // the CPU rewrites the texture (not reported)
    // The same texture state, no TFLUSH in this list.
    ASSERT_EQ(host.draw(host.list([&](ge::ListBuilder& b) { sprite(b); })), GE2GL_OK);
    EXPECT_EQ(rgb(host.hostPixel(32, 32)), rgb(GREEN));
}

// Lazy write-back: VRAM is left alone until the host asks, and the host hears where drawing went.
TEST_P(Coherence, LazyWriteBackAnnouncesRangesAndSyncsInPlace) {
    if (GetParam() == Backend::Soft) GTEST_SKIP() << "the software backend draws into VRAM itself";
    EmbedHost host(GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) {
        c.lazy_writeback = 1;
        c.gl_use_egl = GetParam() == Backend::GlEgl;
    });
    ASSERT_EQ(host.status, GE2GL_OK);
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, RED); })), GE2GL_OK);
    EXPECT_EQ(host.hostPixel(10, 10), 0u);  // not written back yet
    ASSERT_FALSE(host.dirty.empty());
    EXPECT_EQ(host.dirty[0].first, kVram);
    EXPECT_GE(host.dirty[0].second, 272u * 512 * 4 - 32 * 4);
    ASSERT_EQ(ge2gl_sync_range(host.h, kVram, 512 * 272 * 4), GE2GL_OK);
    EXPECT_EQ(rgb(host.hostPixel(10, 10)), rgb(RED));
}

// "A ge2gl_mem_read from a second thread returns zeros and leaves the GL thread reading zeros."
TEST_P(Coherence, ReadsFromASecondThreadSeeTheFrameAndTheGlThreadGoesOn) {
    EmbedHost host(GetParam() == Backend::Soft ? GE2GL_BACKEND_SOFT : GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) {
        c.lazy_writeback = 1;  // the read must fetch from the GPU itself
        c.gl_use_egl = GetParam() == Backend::GlEgl;
    });
    ASSERT_EQ(host.status, GE2GL_OK);
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, RED); })), GE2GL_OK);
    uint32_t seen = 0;
    ge2gl_status st = GE2GL_ERR_BAD_STATE;
    std::thread([&] { st = ge2gl_mem_read(host.h, kVram + (10 * 512 + 10) * 4, &seen, 4); }).join();
    ASSERT_EQ(st, GE2GL_OK) << ge2gl_last_message(host.h);
    EXPECT_EQ(rgb(seen), rgb(RED));
    // The GL thread still draws and reads.
    ASSERT_EQ(host.draw(host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, GREEN); })), GE2GL_OK);
    std::vector<uint8_t> rgba(480 * 272 * 4);
    ASSERT_EQ(ge2gl_read_frame(host.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, rgba.data(), rgba.size()), GE2GL_OK);
    EXPECT_EQ(rgba[0], 0x00);
    EXPECT_EQ(rgba[1], 0xFF);
}

// ---- The host's own GL context ----

namespace {

// A host GL context of each kind, skipped where the platform lacks it.
std::unique_ptr<GlHost> makeGlHost(GlHost::Kind k) {
    auto g = std::make_unique<GlHost>(k);
    if (!g->ok()) return nullptr;
    return g;
}

}  // namespace

// "Once the host makes its own GL context current, ge2gl's headless draws are lost;
// ge2gl_destroy unbinds the host's context; destroying one of two instances leaves the other
// drawing nothing."
TEST(ApiGlContext, HeadlessInstancesLeaveTheHostContextCurrentAndKeepDrawing) {
    for (GlHost::Kind hostKind : {GlHost::Kind::EGL, GlHost::Kind::OSMesa}) {
        for (int egl = 0; egl < 2; ++egl) {
            SCOPED_TRACE(std::string("host ") + (hostKind == GlHost::Kind::EGL ? "EGL" : "OSMesa") + ", ge2gl " +
                         (egl ? "EGL" : "OSMesa"));
            auto gh = makeGlHost(hostKind);
            if (!gh) continue;
            auto a = std::make_unique<EmbedHost>(GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) { c.gl_use_egl = egl; });
            if (a->status != GE2GL_OK) continue;
            EXPECT_TRUE(gh->isCurrent());
            auto b = std::make_unique<EmbedHost>(GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) { c.gl_use_egl = egl; });
            ASSERT_EQ(b->status, GE2GL_OK);
            EXPECT_TRUE(gh->isCurrent());
            // The host draws with its own context between ge2gl's calls.
            gh->scramble();
            ASSERT_EQ(a->draw(a->list([](ge::ListBuilder& l) { EmbedHost::clearTo(l, RED); })), GE2GL_OK);
            EXPECT_TRUE(gh->isCurrent());
            EXPECT_EQ(gh->check(), "");
            ASSERT_EQ(b->draw(b->list([](ge::ListBuilder& l) { EmbedHost::clearTo(l, GREEN); })), GE2GL_OK);
            EXPECT_EQ(rgb(a->hostPixel(3, 3)), rgb(RED));
            EXPECT_EQ(rgb(b->hostPixel(3, 3)), rgb(GREEN));
            a.reset();  // destroy one
            EXPECT_TRUE(gh->isCurrent());
            EXPECT_EQ(gh->check(), "");
            ASSERT_EQ(b->draw(b->list([](ge::ListBuilder& l) {
                EmbedHost::rect(l, 0, 0, 20, 20, BLUE);
            })),
                      GE2GL_OK);
            EXPECT_EQ(rgb(b->hostPixel(3, 3)), rgb(BLUE));
            EXPECT_EQ(rgb(b->hostPixel(30, 30)), rgb(GREEN));
            b.reset();
            EXPECT_TRUE(gh->isCurrent());
            EXPECT_NE(gh->GetString(GL_RENDERER), nullptr);
        }
    }
}

// "In host-context mode, a host that changes VAO, viewport, scissor or colour mask between lists
// gets wrong output; ge2gl leaves its FBO, program, VAO, viewport and scissor bound."
TEST(ApiGlContext, HostContextStateIsRestoredAndScramblingChangesNoPixel) {
    for (GlHost::Kind hostKind : {GlHost::Kind::OSMesa, GlHost::Kind::EGL}) {
        SCOPED_TRACE(hostKind == GlHost::Kind::EGL ? "EGL host" : "OSMesa host");
        auto gh = makeGlHost(hostKind);
        if (!gh) continue;
        gh->scramble();
        EmbedHost gl(GE2GL_BACKEND_GL_CURRENT, [&](ge2gl_config& c) { c.gl_get_proc_address = gh->loader(); });
        ASSERT_EQ(gl.status, GE2GL_OK) << ge2gl_last_message(nullptr);
        EXPECT_EQ(gh->check(), "") << "after ge2gl_create";
        EmbedHost soft(GE2GL_BACKEND_SOFT);
        auto scene = [](ge::ListBuilder& b) {
            EmbedHost::clearTo(b, BLUE);
            EmbedHost::rect(b, 10, 20, 200, 100, RED);
            b.enable(ge::GE_CMD_ABE, true);
            b.blendFunc(ge::BLEQ_ADD, 2, 3);  // src alpha, 1 - src alpha
            EmbedHost::rect(b, 100, 50, 300, 200, 0x8000FF00);
        };
        // Every call of the frame, with the host scrambling its state around each.
        const uint32_t l1 = gl.list(scene), l2 = soft.list(scene);
        ASSERT_EQ(l1, l2);
        int32_t id = -1, s = -1;
        gh->scramble();
        ASSERT_EQ(ge2gl_list_enqueue(gl.h, l1, l1 + 16, -1, nullptr, &id), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after enqueue";
        ge2gl_run_info info{};
        ASSERT_EQ(ge2gl_run(gl.h, 1000, &info), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after run";
        ASSERT_EQ(ge2gl_list_update_stall(gl.h, id, 0), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after stall update";
        ASSERT_EQ(ge2gl_draw_sync(gl.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after draw sync";
        std::vector<uint8_t> a(480 * 272 * 4), b(480 * 272 * 4);
        ASSERT_EQ(ge2gl_read_frame(gl.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, a.data(), a.size()), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after read_frame";
        uint32_t tex = 0;
        ASSERT_EQ(ge2gl_frame_texture(gl.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, &tex), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after frame_texture";
        uint32_t word = 0;
        ASSERT_EQ(ge2gl_mem_read(gl.h, kVram, &word, 4), GE2GL_OK);
        EXPECT_EQ(gh->check(), "") << "after mem_read";
        ASSERT_EQ(soft.draw(l2), GE2GL_OK);
        ASSERT_EQ(ge2gl_read_frame(soft.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, b.data(), b.size()), GE2GL_OK);
        size_t differ = 0;
        for (size_t i = 0; i < a.size(); i += 4) differ += std::memcmp(&a[i], &b[i], 3) != 0;
        EXPECT_EQ(differ, 0u) << "GL on a scrambled host context vs the software model";
        const uint8_t r = a[(size_t(60) * 480 + 150) * 4 + 0];  // the blended overlap is there
        EXPECT_TRUE(r > 0x60 && r < 0xA0) << int(r);
    }
}

// "ge2gl_frame_texture ignores the requested size, is a CPU conversion of VRAM, and rejects frame
// buffers in RAM."
TEST(ApiPresent, FrameTexturesAtTheRenderScaleAndTheAskedSizeFromVramAndRam) {
    auto gh = makeGlHost(GlHost::Kind::OSMesa);
    if (!gh) GTEST_SKIP() << "no OSMesa";
    EmbedHost gl(GE2GL_BACKEND_GL_CURRENT, [&](ge2gl_config& c) {
        c.gl_get_proc_address = gh->loader();
        c.gl_mode = GE2GL_GL_MODE_HW;
        c.render_scale = 2;
    });
    ASSERT_EQ(gl.status, GE2GL_OK) << ge2gl_last_message(nullptr);
    gh->scramble();
    ASSERT_EQ(gl.draw(gl.list([](ge::ListBuilder& b) {
        EmbedHost::clearTo(b, BLUE);
        EmbedHost::rect(b, 100, 50, 200, 150, RED);
    })),
              GE2GL_OK);
    uint32_t tex = 0;
    int w = 0, h = 0;
    ASSERT_EQ(ge2gl_frame_texture(gl.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, &tex), GE2GL_OK);
    gh->textureSize(tex, w, h);
    EXPECT_EQ(w, 960);
    EXPECT_EQ(h, 544);
    auto px = gh->readTexture(tex, 960, 544);
    auto at = [&](const std::vector<unsigned char>& p, int W, int x, int y) {
        const unsigned char* c = &p[(size_t(y) * size_t(W) + size_t(x)) * 4];
        return uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16;
    };
    // At 2x the rectangle's edges fall on even texels: exact, no blur.
    EXPECT_EQ(at(px, 960, 200, 100), 0x0000FFu);
    EXPECT_EQ(at(px, 960, 199, 100), 0xFF0000u);
    EXPECT_EQ(at(px, 960, 399, 299), 0x0000FFu);
    EXPECT_EQ(at(px, 960, 400, 299), 0xFF0000u);
    EXPECT_EQ(gh->check(), "");
    // The size the host asks for.
    ASSERT_EQ(ge2gl_frame_texture_sized(gl.h, kVram, 512, GE2GL_FORMAT_8888, 480, 272, 240, 136, &tex), GE2GL_OK);
    gh->textureSize(tex, w, h);
    EXPECT_EQ(w, 240);
    EXPECT_EQ(h, 136);
    auto small = gh->readTexture(tex, 240, 136);
    EXPECT_EQ(at(small, 240, 75, 50), 0x0000FFu);  // inside the rectangle
    EXPECT_EQ(at(small, 240, 10, 10), 0xFF0000u);
    // A frame buffer in RAM (a video the CPU decoded), 16x8 565 pixels.
    constexpr uint32_t fb = 0x08700000;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const uint16_t p = uint16_t(x < 8 ? 0x001F : 0x07E0);  // red | green (565: R in bits 4..0)
            std::memcpy(&gl.ram[fb - kRam + size_t(y * 16 + x) * 2], &p, 2);
        }
    ASSERT_EQ(ge2gl_frame_texture_sized(gl.h, fb, 16, GE2GL_FORMAT_565, 16, 8, 16, 8, &tex), GE2GL_OK)
        << ge2gl_last_message(gl.h);
    auto ramPx = gh->readTexture(tex, 16, 8);
    EXPECT_EQ(at(ramPx, 16, 0, 0), 0x0000FFu);
    EXPECT_EQ(at(ramPx, 16, 15, 7), 0x00FF00u);
    EXPECT_EQ(gh->check(), "");
    EXPECT_EQ(ge2gl_frame_texture_sized(gl.h, fb, 16, GE2GL_FORMAT_565, 16, 8, 0, 8, &tex), GE2GL_ERR_INVALID_ARGUMENT);
}

// ---- Threads ----

// GL_CURRENT from a thread where the host's context is not: a clear refusal, never zeros; and a
// plain read once the frame is in VRAM.
TEST(ApiThreads, GlCurrentFromAnotherThreadIsRefusedWhereItNeedsTheGpu) {
    auto gh = makeGlHost(GlHost::Kind::OSMesa);
    if (!gh) GTEST_SKIP() << "no OSMesa";
    for (int lazy = 1; lazy >= 0; --lazy) {
        EmbedHost gl(GE2GL_BACKEND_GL_CURRENT, [&](ge2gl_config& c) {
            c.gl_get_proc_address = gh->loader();
            c.lazy_writeback = lazy;
        });
        ASSERT_EQ(gl.status, GE2GL_OK);
        ASSERT_EQ(gl.draw(gl.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, RED); })), GE2GL_OK);
        uint32_t seen = 0;
        ge2gl_status read = GE2GL_OK, run = GE2GL_OK;
        std::string message;
        std::thread([&] {
            read = ge2gl_mem_read(gl.h, kVram + 40, &seen, 4);
            message = ge2gl_last_message(gl.h);
            int32_t id = -1;
            ge2gl_list_enqueue(gl.h, gl.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, GREEN); }), 0, -1, nullptr, &id);
            ge2gl_run_info info{};
            run = ge2gl_run(gl.h, 100, &info);
        }).join();
        if (lazy) {
            EXPECT_EQ(read, GE2GL_ERR_WRONG_THREAD);
            EXPECT_NE(message.find("creating thread"), std::string::npos) << message;
        } else {
            EXPECT_EQ(read, GE2GL_OK);
            EXPECT_EQ(rgb(seen), rgb(RED));
        }
        EXPECT_EQ(run, GE2GL_ERR_WRONG_THREAD);
        // The owning thread runs what the other queued.
        int32_t s = -1;
        ASSERT_EQ(ge2gl_draw_sync(gl.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
        ASSERT_EQ(ge2gl_sync_range(gl.h, kVram, 512 * 272 * 4), GE2GL_OK);
        EXPECT_EQ(rgb(gl.hostPixel(1, 1)), rgb(GREEN));
    }
}

namespace {

// A list that signals (behaviour 1, suspend) between two clears, then finishes.
uint32_t signallingList(EmbedHost& host, uint32_t first, uint32_t second) {
    return host.list([&](ge::ListBuilder& b) {
        EmbedHost::clearTo(b, first);
        b.signal(1, 0x42);
        EmbedHost::clearTo(b, second);
    });
}

}  // namespace

// "Callbacks run with the lock held, so a signal callback that waits on the CPU thread
// deadlocks" — inline (a GE thread calls ge2gl_run) and with the worker. The callback blocks until
// the CPU thread has peeked, moved a stall, read memory and enqueued; a lock held across the
// callback would hang those calls (the watchdog turns that into a failure).
TEST(ApiThreads, ACallbackMayWaitForTheCpuThreadWhileItCallsIn) {
    for (int worker = 0; worker < 2; ++worker) {
        for (Backend be : {Backend::Soft, Backend::Gl}) {
            if (!glAvailable(be)) continue;
            SCOPED_TRACE(std::string(worker ? "worker " : "inline ") + backendName(be));
            std::mutex m;
            std::condition_variable cv;
            bool inCallback = false, cpuDone = false;
            struct Ctx {
                std::mutex* m;
                std::condition_variable* cv;
                bool *in, *done;
            } ctx{&m, &cv, &inCallback, &cpuDone};
            EmbedHost host(be == Backend::Soft ? GE2GL_BACKEND_SOFT : GE2GL_BACKEND_GL_HEADLESS, [&](ge2gl_config& c) {
                c.worker_thread = worker;
                c.callbacks.user = &ctx;
                c.callbacks.signal = [](void* u, const ge2gl_interrupt*) {
                    Ctx& cx = *static_cast<Ctx*>(u);
                    std::unique_lock<std::mutex> lk(*cx.m);
                    *cx.in = true;
                    cx.cv->notify_all();
                    cx.cv->wait_for(lk, std::chrono::seconds(20), [&] { return *cx.done; });
                };
            });
            ASSERT_EQ(host.status, GE2GL_OK) << ge2gl_last_message(nullptr);
            const uint32_t l = signallingList(host, RED, GREEN);
            int32_t id = -1;
            ASSERT_EQ(ge2gl_list_enqueue(host.h, l, 0, -1, nullptr, &id), GE2GL_OK);
            std::thread ge;
            if (!worker) ge = std::thread([&] { ge2gl_run(host.h, 1u << 20, nullptr); });
            {
                std::unique_lock<std::mutex> lk(m);
                ASSERT_TRUE(cv.wait_for(lk, std::chrono::seconds(20), [&] { return inCallback; }));
            }
            // The GE thread is inside the callback: every one of these must return.
            auto calls = std::async(std::launch::async, [&] {
                int32_t s = -1;
                bool ok = ge2gl_list_sync(host.h, id, GE2GL_SYNC_PEEK, &s) == GE2GL_OK && s == GE2GL_LIST_DRAWING;
                ok &= ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s) == GE2GL_OK;
                uint32_t w = 0;
                ok &= ge2gl_mem_read(host.h, kVram, &w, 4) == GE2GL_OK;
                ok &= rgb(w) == rgb(RED);  // the first clear is done (and written back for the read)
                int32_t id2 = -1;
                ok &= ge2gl_list_enqueue(host.h, host.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, BLUE); }), 0,
                                         -1, nullptr, &id2) == GE2GL_OK;
                return ok;
            });
            const bool returned = calls.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
            {
                std::lock_guard<std::mutex> lk(m);
                cpuDone = true;
            }
            cv.notify_all();
            if (ge.joinable()) ge.join();
            ASSERT_TRUE(returned) << "API calls blocked while a callback ran: a lock is held across callbacks";
            EXPECT_TRUE(calls.get());
            int32_t s = -1;
            ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK) << ge2gl_last_message(host.h);
            EXPECT_EQ(rgb(host.hostPixel(7, 7)), rgb(BLUE));
        }
    }
}

// A host that writes its VRAM in place while a list is stalled (PPSSPP's dump player writes a
// frame image after a clear, then reports it) must see its bytes survive: draws the software
// model queued before the stall land in memory before ge2gl_run returns, not after the write.
TEST(ApiThreads, HostWritesAtAStallLandAfterTheDrawsBeforeIt) {
    EmbedHost host(GE2GL_BACKEND_SOFT);
    ASSERT_EQ(host.status, GE2GL_OK);
    uint32_t words = 0;
    const uint32_t l = host.list([&](ge::ListBuilder& b) {
        EmbedHost::clearTo(b, RED);
        words = uint32_t(b.words().size());  // the stall: right after the clear
        EmbedHost::rect(b, 0, 0, 4, 4, GREEN);
    });
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, l, l + 4 * words, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run(host.h, 1u << 20, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_STALLED);
    EXPECT_EQ(rgb(host.hostPixel(100, 100)), rgb(RED));  // the clear is in memory already
    host.pokePixel(100, 100, BLUE);                       // the host's own write, in place
    ASSERT_EQ(ge2gl_mem_written(host.h, kVram + (100 * 512 + 100) * 4, 4), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, 0), GE2GL_OK);
    int32_t s = -1;
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(rgb(host.hostPixel(100, 100)), rgb(BLUE));
    EXPECT_EQ(rgb(host.hostPixel(2, 2)), rgb(GREEN));
}

// An interrupt held until the host acknowledges it: the GE does not go past a signal or a finish
// before the host has run the guest handler.
TEST(ApiThreads, HeldInterruptsWaitForTheAcknowledgement) {
    std::vector<char> events;
    EmbedHost host(GE2GL_BACKEND_SOFT, [&](ge2gl_config& c) {
        c.hold_interrupts = 1;
        c.callbacks.user = &events;
        c.callbacks.signal = [](void* u, const ge2gl_interrupt*) { static_cast<std::vector<char>*>(u)->push_back('S'); };
        c.callbacks.finish = [](void* u, const ge2gl_interrupt*) { static_cast<std::vector<char>*>(u)->push_back('F'); };
    });
    ASSERT_EQ(host.status, GE2GL_OK);
    const uint32_t l = signallingList(host, RED, GREEN);
    int32_t id = -1, s = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, l, 0, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run(host.h, 1u << 20, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);
    EXPECT_EQ(events, std::vector<char>({'S'}));
    uint32_t w = 0;
    ASSERT_EQ(ge2gl_mem_read(host.h, kVram, &w, 4), GE2GL_OK);
    EXPECT_EQ(rgb(w), rgb(RED));  // the first clear only
    ASSERT_EQ(ge2gl_run(host.h, 1u << 20, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);
    EXPECT_EQ(info.commands, 0u);
    EXPECT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_NE(std::string(ge2gl_last_message(host.h)).find("ge2gl_interrupt_ack"), std::string::npos);
    ASSERT_EQ(ge2gl_interrupt_ack(host.h), GE2GL_OK);
    EXPECT_EQ(ge2gl_interrupt_ack(host.h), GE2GL_ERR_BAD_STATE);
    ASSERT_EQ(ge2gl_run(host.h, 1u << 20, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);  // the finish, held too
    EXPECT_EQ(events, std::vector<char>({'S', 'F'}));
    EXPECT_EQ(rgb(host.hostPixel(0, 0)), rgb(GREEN));  // written back before the finish callback
    ASSERT_EQ(ge2gl_interrupt_ack(host.h), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
}

// ---- Creation ----

// "Creation failures give no reason; ram_size = 0 assumes 64 MiB and reads past a 32 MiB host
// buffer."
TEST(ApiErrors, CreationFailuresSayWhyAndRamSizeIsExact) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    ge2gl_context* h = nullptr;
    cfg.struct_size = 12;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_VERSION);
    EXPECT_NE(std::string(ge2gl_last_message(nullptr)).find("struct_size"), std::string::npos);
    std::vector<uint8_t> ram32(32u << 20);
    ge2gl_config_init(&cfg);
    cfg.ram = ram32.data();  // ram_size left 0
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ge2gl_last_message(nullptr)).find("ram_size"), std::string::npos);
    cfg.ram_size = 32u << 20;
    ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);
    EXPECT_STREQ(ge2gl_last_message(nullptr), "");
    uint32_t w = 0;
    EXPECT_EQ(ge2gl_mem_read(h, 0x0A000000, &w, 4), GE2GL_ERR_MEMORY);  // past the 32 MiB
    EXPECT_EQ(ge2gl_mem_read(h, 0x09FFFFFC, &w, 4), GE2GL_OK);
    int32_t id = -1;
    EXPECT_NE(ge2gl_list_enqueue(h, 0x0A000000, 0, -1, nullptr, &id), GE2GL_OK);
    ge2gl_destroy(h);
    // A GL host context that is not there: the reason, not just GE2GL_ERR_BACKEND.
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_GL_CURRENT;
    cfg.gl_get_proc_address = [](const char*) -> void* { return nullptr; };
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_BACKEND);
    EXPECT_NE(std::string(ge2gl_last_message(nullptr)).find("GL"), std::string::npos) << ge2gl_last_message(nullptr);
}

INSTANTIATE_TEST_SUITE_P(Backends, Coherence, ::testing::Values(Backend::Soft, Backend::Gl, Backend::GlEgl),
                         [](const ::testing::TestParamInfo<Backend>& i) {
                             return i.param == Backend::Soft ? "Soft" : i.param == Backend::Gl ? "GlOsmesa" : "GlEgl";
                         });

// The C++ wrapper carries the 1.2 calls: the dirty-range callback, sync_range, the sized frame
// texture, interrupt acknowledgement, and creation messages.
#include "ge2gl/ge2gl.hpp"

TEST(ApiCpp, WrapperCarriesTheEmbeddingCalls) {
    if (!glAvailable(Backend::Gl)) GTEST_SKIP() << "no GL";
    EmbedHost scene(GE2GL_BACKEND_NULL);  // only for writing the list into its RAM
    const uint32_t l = scene.list([](ge::ListBuilder& b) { EmbedHost::clearTo(b, RED); });
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.ram = scene.ram.data(), cfg.ram_size = kRamSize, cfg.vram = scene.vram.data();
    cfg.backend = GE2GL_BACKEND_GL_HEADLESS;
    cfg.lazy_writeback = 1;
    std::vector<std::pair<uint32_t, uint32_t>> dirty;
    ge2gl::Callbacks cb;
    cb.vramDirty = [&](uint32_t a, uint32_t n) { dirty.emplace_back(a, n); };
    auto ctx = ge2gl::Context::create(cfg, cb);
    ASSERT_TRUE(ctx.ok()) << ctx.message;
    ge2gl::Context& c = ctx.value;
    ASSERT_TRUE(c.enqueue(l, 0).ok());
    ASSERT_TRUE(c.drawSync(GE2GL_SYNC_WAIT).ok());
    ASSERT_FALSE(dirty.empty());
    EXPECT_EQ(scene.hostPixel(1, 1), 0u);
    ASSERT_TRUE(c.syncRange(kVram, 512 * 272 * 4));
    EXPECT_EQ(rgb(scene.hostPixel(1, 1)), rgb(RED));
    EXPECT_EQ(c.interruptAck().code, GE2GL_ERR_BAD_STATE);
    auto tex = c.frameTexture(kVram, 512, GE2GL_FORMAT_8888, 480, 272, 100, 50);
    EXPECT_TRUE(tex.ok()) << tex.message;
    cfg.ram_size = 0;
    auto bad = ge2gl::Context::create(cfg);
    EXPECT_EQ(bad.status.code, GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(bad.message.find("ram_size"), std::string::npos) << bad.message;
}
