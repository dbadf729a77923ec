// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp), licensed like the glue it tests.
//
// The glue's clock logic (src/Ge2glTimeline.h) against a real libge2gl instance, driven the way
// GPU_Ge2gl drives it inside PPSSPP but with the emulated CPU's clock simulated: the GE runs ahead
// of the CPU up to a look-ahead (ge2gl_run_until), holds at each interrupt until the "guest
// handler" returns (hold_interrupts), and what the game may observe - interrupt ticks, the state a
// peek sync reports - follows the mapped ticks. Needs no PPSSPP.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "ge2gl/ge2gl.h"
#include "integrations/ppsspp/src/Ge2glTimeline.h"

using ge2gl_ppsspp::Timeline;
using ge2gl_ppsspp::visibleListState;

TEST(PpssppGlueTimeline, MapsGeTicksOntoTheCpuClockFromItsAnchor) {
    Timeline t;
    t.restore(0, 1000, Timeline::kGeHz);
    EXPECT_EQ(t.cpuTickOf(222), 1222);
    EXPECT_EQ(t.geTickAt(1222), 222u);
    EXPECT_EQ(t.geTickAt(500), 0u);  // before the anchor: the anchor's GE tick
    // A game that runs the CPU at 333 MHz: a GE tick lasts 1.5 CPU ticks from here on.
    t.setCpuHz(222, 333000000);
    EXPECT_EQ(t.cpuTickOf(222), 1222);
    EXPECT_EQ(t.cpuTickOf(222 + 222), 1222 + 333);
    EXPECT_EQ(t.geTickAt(1222 + 333), 444u);
}

TEST(PpssppGlueTimeline, WorkGivenToAStoppedGeStartsAtTheCpusTimeNeverEarlier) {
    Timeline t;
    t.restore(0, 0, Timeline::kGeHz);
    // The GE worked 500 ticks (it reached CPU tick 500) and then stood idle.
    t.resume(500, 5000);  // new work at CPU tick 5000: GE tick 500 is now CPU tick 5000
    EXPECT_EQ(t.cpuTickOf(500), 5000);
    EXPECT_EQ(t.cpuTickOf(600), 5100);
    t.resume(600, 4000);  // the CPU is behind the GE: nothing moves
    EXPECT_EQ(t.cpuTickOf(600), 5100);
}

TEST(PpssppGlueTimeline, APeekShowsDrawingUntilTheCpuReachesTheStateTheGeRanAheadTo) {
    constexpr int32_t completed = GE2GL_LIST_COMPLETED, drawing = GE2GL_LIST_DRAWING;
    EXPECT_EQ(visibleListState(completed, 2000, 1999), drawing);
    EXPECT_EQ(visibleListState(completed, 2000, 2000), completed);
    EXPECT_EQ(visibleListState(GE2GL_LIST_STALLING, 2000, 100), drawing);
    EXPECT_EQ(visibleListState(GE2GL_LIST_PAUSED, 2000, 100), drawing);
    EXPECT_EQ(visibleListState(GE2GL_LIST_QUEUED, 2000, 100), GE2GL_LIST_QUEUED);
    EXPECT_EQ(visibleListState(GE2GL_LIST_STALLING, 50, 100), GE2GL_LIST_STALLING);
}

namespace {

constexpr uint32_t kRam = 0x08000000, kRamSize = 1u << 20, kList = 0x08010000;

struct Irq {
    bool finish;
    uint64_t tick;
    int32_t list;
};

class Ge {
public:
    Ge() : ram(kRamSize), vram(0x200000) {
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.ram = ram.data();
        cfg.ram_size = kRamSize;
        cfg.vram = vram.data();
        cfg.backend = GE2GL_BACKEND_SOFT;
        cfg.soft_threads = 1;
        cfg.hold_interrupts = 1;
        cfg.callbacks.user = this;
        cfg.callbacks.signal = [](void *u, const ge2gl_interrupt *i) { static_cast<Ge *>(u)->irqs.push_back({false, i->tick, i->list_id}); };
        cfg.callbacks.finish = [](void *u, const ge2gl_interrupt *i) { static_cast<Ge *>(u)->irqs.push_back({true, i->tick, i->list_id}); };
        status = ge2gl_create(&cfg, &h);
    }
    ~Ge() { ge2gl_destroy(h); }
    void put(uint32_t &at, uint32_t op, uint32_t arg = 0) {
        const uint32_t w = (op << 24) | (arg & 0xFFFFFF);
        std::memcpy(&ram[at - kRam], &w, 4);
        at += 4;
    }
    uint64_t tick() {
        uint64_t t = 0;
        ge2gl_get_tick(h, &t);
        return t;
    }
    int32_t run(uint64_t until) {
        ge2gl_run_info info{};
        EXPECT_EQ(ge2gl_run_until(h, until, &info), GE2GL_OK);
        return info.ge_state;
    }
    int32_t peek(int32_t id) {
        int32_t s = -1;
        EXPECT_EQ(ge2gl_list_sync(h, id, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
        return s;
    }
    std::vector<uint8_t> ram, vram;
    ge2gl_context *h = nullptr;
    ge2gl_status status = GE2GL_OK;
    std::vector<Irq> irqs;
};

}  // namespace

// The glue's run loop on a list with a handler signal in the middle: the GE runs ahead to the
// signal and holds there; the interrupt is due at the mapped tick; once the CPU got there and the
// handler returned, the GE goes on (from that tick, not from where it stopped) to the finish,
// which a peek shows as DRAWING until the CPU reaches the finish's tick.
TEST(PpssppGlueTimeline, InterruptsAndCompletionFollowTheGesOwnTicks) {
    Ge ge;
    ASSERT_EQ(ge.status, GE2GL_OK);
    uint32_t at = kList;
    for (int i = 0; i < 200; ++i) ge.put(at, 0xCA, uint32_t(i));  // TEC: a plain state write
    ge.put(at, 0x0E, (0x01u << 16) | 0x42);                         // SIGNAL HANDLER_SUSPEND
    ge.put(at, 0x0C, 0);
    for (int i = 0; i < 200; ++i) ge.put(at, 0xCA, uint32_t(i));
    ge.put(at, 0x0F, 0);  // FINISH
    ge.put(at, 0x0C, 0);

    Timeline t;
    int64_t now = 100000;  // the CPU's clock when the game enqueues
    t.restore(ge.tick(), now, Timeline::kGeHz);
    const int64_t lookahead = 1000000;
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(ge.h, kList, 0, -1, nullptr, &id), GE2GL_OK);
    t.resume(ge.tick(), now);
    ASSERT_EQ(ge.run(t.geTickAt(now + lookahead)), GE2GL_GE_INTERRUPT);
    ASSERT_EQ(ge.irqs.size(), 1u);
    EXPECT_FALSE(ge.irqs[0].finish);
    const int64_t signalAt = t.cpuTickOf(ge.irqs[0].tick);
    EXPECT_GT(signalAt, now);  // 200 commands of GE time after the enqueue
    EXPECT_EQ(ge.irqs[0].tick, ge.tick());  // held right after the signal's END
    EXPECT_EQ(visibleListState(ge.peek(id), signalAt, now), GE2GL_LIST_DRAWING);

    // The CPU reaches the interrupt's tick plus the handler's run; the handler returns.
    now = signalAt + 5000;
    ASSERT_EQ(ge2gl_interrupt_ack(ge.h), GE2GL_OK);
    t.resume(ge.tick(), now);  // the GE stood held: it goes on from the CPU's time
    EXPECT_EQ(t.cpuTickOf(ge.tick()), now);
    ASSERT_EQ(ge.run(t.geTickAt(now + lookahead)), GE2GL_GE_INTERRUPT);
    ASSERT_EQ(ge.irqs.size(), 2u);
    EXPECT_TRUE(ge.irqs[1].finish);
    const int64_t finishAt = t.cpuTickOf(ge.irqs[1].tick);
    EXPECT_GT(finishAt, now);
    EXPECT_EQ(ge.peek(id), GE2GL_LIST_COMPLETED);  // ge2gl's own view: done
    EXPECT_EQ(visibleListState(GE2GL_LIST_COMPLETED, finishAt, now), GE2GL_LIST_DRAWING);
    EXPECT_EQ(visibleListState(GE2GL_LIST_COMPLETED, finishAt, finishAt), GE2GL_LIST_COMPLETED);
    ASSERT_EQ(ge2gl_interrupt_ack(ge.h), GE2GL_OK);
    EXPECT_EQ(ge.run(t.geTickAt(finishAt + lookahead)), GE2GL_GE_IDLE);
}

// The look-ahead bounds how far one run goes: a long list stops at the first command that crosses
// the target tick (READY), and the next slice goes on from there.
TEST(PpssppGlueTimeline, ALongListRunsInSlicesBoundedByTheLookAhead) {
    Ge ge;
    ASSERT_EQ(ge.status, GE2GL_OK);
    uint32_t at = kList;
    for (int i = 0; i < 20000; ++i) ge.put(at, 0xCA, uint32_t(i));
    ge.put(at, 0x0F, 0);
    ge.put(at, 0x0C, 0);
    Timeline t;
    t.restore(ge.tick(), 0, Timeline::kGeHz);
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(ge.h, kList, 0, -1, nullptr, &id), GE2GL_OK);
    const int64_t lookahead = 2000;
    int slices = 0;
    int64_t now = 0;
    int32_t state = GE2GL_GE_READY;
    while (state == GE2GL_GE_READY && slices < 100000) {
        const uint64_t target = t.geTickAt(now + lookahead);
        state = ge.run(target);
        if (state == GE2GL_GE_READY) {
            EXPECT_GE(ge.tick(), target);
            EXPECT_LT(ge.tick(), target + 100);  // one command past the target at most
        }
        ++slices;
        now = t.cpuTickOf(ge.tick()) - lookahead / 2;  // the slice event's time
    }
    EXPECT_EQ(state, GE2GL_GE_INTERRUPT);  // the finish
    EXPECT_GT(slices, 5);
    ASSERT_EQ(ge.irqs.size(), 1u);
    EXPECT_TRUE(ge.irqs[0].finish);
}
