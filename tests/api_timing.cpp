// SPDX-License-Identifier: MIT
// GE time through the C ABI (docs/timing.md): ge2gl_run_until stops at the tick asked,
// interrupts carry the tick they occur at, ge2gl_list_ticks gives each list its own time, and the
// time survives a save state.
#include <gtest/gtest.h>

#include <vector>

#include "ge2gl/ge2gl.h"

namespace {

struct Ticks {
    std::vector<uint64_t> finish;
};

TEST(ApiTiming, RunUntilStopsAtTheTickAndInterruptsCarryIt) {
    Ticks t;
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.callbacks.user = &t;
    cfg.callbacks.finish = [](void* u, const ge2gl_interrupt* irq) { static_cast<Ticks*>(u)->finish.push_back(irq->tick); };
    ge2gl_context* h = nullptr;
    ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);
    // 300 NOPs, FINISH, END at 0x08100000.
    std::vector<uint32_t> words(300, 0);
    words.push_back(0x0F000000);
    words.push_back(0x0C000000);
    ASSERT_EQ(ge2gl_mem_write(h, 0x08100000, words.data(), uint32_t(words.size() * 4)), GE2GL_OK);
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(h, 0x08100000, 0, -1, nullptr, &id), GE2GL_OK);
    uint64_t tick = 0;
    ASSERT_EQ(ge2gl_get_tick(h, &tick), GE2GL_OK);
    EXPECT_EQ(tick, 60u);  // the list started at enqueue (PPSSPP: 60 cycles a list start)

    // The host's next event is at tick 461: the GE stops after the command that reaches it.
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run_until(h, 461, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_READY);
    EXPECT_EQ(info.commands, 201u);  // 60 + 201 x 2 = 462 >= 461
    ASSERT_EQ(ge2gl_get_tick(h, &tick), GE2GL_OK);
    EXPECT_EQ(tick, 462u);
    EXPECT_TRUE(t.finish.empty());

    // A save state keeps the time.
    const void* data = nullptr;
    size_t size = 0;
    ASSERT_EQ(ge2gl_state_save(h, GE2GL_STATE_WITH_MEMORY, &data, &size), GE2GL_OK);
    const std::vector<uint8_t> blob(static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
    ge2gl_context* g = nullptr;
    ASSERT_EQ(ge2gl_create(&cfg, &g), GE2GL_OK);
    ASSERT_EQ(ge2gl_state_load(g, blob.data(), blob.size()), GE2GL_OK);
    ASSERT_EQ(ge2gl_get_tick(g, &tick), GE2GL_OK);
    EXPECT_EQ(tick, 462u);

    for (ge2gl_context* x : {h, g}) {
        ASSERT_EQ(ge2gl_run_until(x, 1000000, &info), GE2GL_OK);
        EXPECT_EQ(info.ge_state, GE2GL_GE_IDLE);
        uint64_t listTicks = 0;
        ASSERT_EQ(ge2gl_list_ticks(x, id, &listTicks), GE2GL_OK);
        EXPECT_EQ(listTicks, 60u + 302 * 2 + 60);  // start, 302 commands, END
        ASSERT_EQ(ge2gl_get_tick(x, &tick), GE2GL_OK);
        EXPECT_EQ(tick, listTicks);
    }
    ASSERT_EQ(t.finish.size(), 2u);  // one per instance, at the same tick
    EXPECT_EQ(t.finish[0], t.finish[1]);
    EXPECT_GE(t.finish[0], 60u + 302 * 2);
    EXPECT_LE(t.finish[0], tick);
    uint64_t none = 0;
    EXPECT_EQ(ge2gl_list_ticks(h, 12345, &none), GE2GL_SCE_ERROR_INVALID_ID);
    ge2gl_destroy(g);
    ge2gl_destroy(h);
}

}  // namespace
