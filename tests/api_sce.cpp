// SPDX-License-Identifier: MIT
// sceGe semantics through the C ABI, driven as an emulator would drive them: lists written into
// host-owned RAM, sceGe calls forwarded, interrupts received through callbacks. Expected values
// follow docs/ge-rules.md §4.4, §4.5, §4.7 (uOFW behaviour) and are worked out by hand per test.
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "ge2gl/ge2gl.h"
#include "tests/api_host.h"

using namespace apitest;

namespace {

// Opcodes used as observable "markers" (plain state registers, no side effects).
constexpr uint32_t TEC = 0xCA, MDC = 0x56, MSC = 0x57;
constexpr uint32_t BASE = 0x10, OFFSET = 0x13, JUMP = 0x08, CALL = 0x0A, RET = 0x0B, END = 0x0C;
constexpr uint32_t L0 = 0x08100000;  // where the tests put their lists

uint32_t word(uint32_t op, uint32_t arg) { return (op << 24) | (arg & 0xFFFFFF); }

}  // namespace

TEST(ApiBasics, VersionAndCreation) {
    EXPECT_EQ(ge2gl_api_version(), GE2GL_API_VERSION);
    EXPECT_EQ(GE2GL_API_VERSION >> 16, 1u);

    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    ge2gl_context* h = reinterpret_cast<ge2gl_context*>(0x1);
    cfg.struct_size = 8;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_VERSION);
    EXPECT_EQ(h, nullptr);
    ge2gl_config_init(&cfg);
    cfg.api_version = (2u << 16);
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_VERSION);
    ge2gl_config_init(&cfg);
    cfg.backend = 42;
    EXPECT_EQ(ge2gl_create(&cfg, &h), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_create(nullptr, &h), GE2GL_ERR_INVALID_ARGUMENT);

    // ge2gl-owned memory: data goes in and out through the copy functions.
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_NULL;
    ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);
    const uint32_t words[3] = {word(TEC, 0x123), word(0x0F, 0), word(END, 0)};
    ASSERT_EQ(ge2gl_mem_write(h, 0x09000000, words, sizeof words), GE2GL_OK);
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(h, 0x09000000, 0, -1, nullptr, &id), GE2GL_OK);
    int32_t state = -1;
    ASSERT_EQ(ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &state), GE2GL_OK);
    EXPECT_EQ(state, GE2GL_LIST_COMPLETED);
    uint32_t v = 0;
    ASSERT_EQ(ge2gl_get_cmd(h, TEC, &v), GE2GL_OK);
    EXPECT_EQ(v, word(TEC, 0x123));
    uint8_t* p = nullptr;
    ASSERT_EQ(ge2gl_mem_pointer(h, 0x09000000, 12, &p), GE2GL_OK);
    EXPECT_EQ(std::memcmp(p, words, 12), 0);
    EXPECT_EQ(ge2gl_mem_pointer(h, 0x0BFFFFFC, 8, &p), GE2GL_ERR_MEMORY);  // crosses the end of RAM
    EXPECT_STRNE(ge2gl_last_message(h), "");
    ge2gl_destroy(h);

    // A NULL handle is refused everywhere, never dereferenced.
    EXPECT_EQ(ge2gl_continue(nullptr), GE2GL_ERR_INVALID_HANDLE);
    EXPECT_EQ(ge2gl_run(nullptr, 1, nullptr), GE2GL_ERR_INVALID_HANDLE);
    ge2gl_destroy(nullptr);
}

// ge2gl_get_registers is ge2gl_get_cmd for every opcode at once (a host mirroring the register
// file refreshes it with one call): the same words, including the matrix ports and number
// registers that read back specially, and out[0xFF] = 0.
TEST(ApiBasics, GetRegistersEqualsGetCmdForEveryOpcode) {
    Host host;
    ASSERT_EQ(host.status, GE2GL_OK);
    ListWriter L(host, L0);
    L.put(TEC, 0x123456);
    L.put(0x3A, 2);         // WORLDN = 2
    L.put(0x3B, 0x3F8000);  // WORLDD: 1.0 into world[2], index now 3
    L.put(MDC, 0xABCDEF);
    L.finish(0);
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, nullptr), GE2GL_OK);
    uint32_t all[256];
    std::memset(all, 0xEE, sizeof all);
    ASSERT_EQ(ge2gl_get_registers(host.h, all), GE2GL_OK);
    for (uint32_t op = 0; op < 0xFF; ++op) {
        uint32_t w = 0;
        ASSERT_EQ(ge2gl_get_cmd(host.h, op, &w), GE2GL_OK);
        EXPECT_EQ(all[op], w) << "opcode 0x" << std::hex << op;
    }
    EXPECT_EQ(all[0xFF], 0u);
    EXPECT_EQ(all[TEC], word(TEC, 0x123456));
    EXPECT_EQ(all[0x3A], word(0x3A, 3));  // the upload index, as sceGeGetCmd reads it
    EXPECT_EQ(all[0x3B], word(0x3B, 0));  // a matrix data port reads back as its bare opcode
    EXPECT_EQ(ge2gl_get_registers(host.h, nullptr), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_get_registers(nullptr, all), GE2GL_ERR_INVALID_HANDLE);
}

// The GE stops exactly at the stall address and continues word by word as it moves (manual §20.5).
TEST(ApiStall, PausesAndResumesAtTheExactAddress) {
    Host host;
    ASSERT_EQ(host.status, GE2GL_OK);
    ListWriter L(host, L0);
    for (uint32_t k = 1; k <= 6; ++k) L.put(TEC, k);  // L0 + 0x00 … 0x14
    L.finish(0x42);                                    // L0 + 0x18, 0x1C
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, L0 + 8, -1, nullptr, &id), GE2GL_OK);
    // The list starts at once (queue was empty): DRAWING, not QUEUED.
    EXPECT_EQ(host.peek(id), GE2GL_LIST_DRAWING);

    ge2gl_run_info info = host.run();
    EXPECT_EQ(info.ge_state, GE2GL_GE_STALLED);
    EXPECT_EQ(info.pc, L0 + 8);
    EXPECT_EQ(info.stall, L0 + 8);
    EXPECT_EQ(info.commands, 2u);
    EXPECT_EQ(info.list_id, id);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 2));
    EXPECT_EQ(host.peek(id), GE2GL_LIST_STALLING);
    ASSERT_FALSE(host.only("P").empty());
    EXPECT_EQ(host.only("P").back().pc, L0 + 8);  // "read up to" report

    // Running again without moving the stall does nothing.
    info = host.run();
    EXPECT_EQ(info.commands, 0u);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 2));

    // One word further; through the uncached mirror (0x4xxxxxxx), as games pass it.
    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, 0x40000000 | (L0 + 12)), GE2GL_OK);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_DRAWING);
    info = host.run();
    EXPECT_EQ(info.ge_state, GE2GL_GE_STALLED);
    EXPECT_EQ(info.pc, L0 + 12);
    EXPECT_EQ(info.commands, 1u);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 3));

    // Budget: one command at a time, the stall still respected.
    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, L0 + 0x18), GE2GL_OK);
    info = host.run(1);
    EXPECT_EQ(info.ge_state, GE2GL_GE_READY);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 4));
    info = host.run();
    EXPECT_EQ(info.pc, L0 + 0x18);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 6));
    EXPECT_TRUE(host.only("F").empty());

    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, L0 + 0x20), GE2GL_OK);
    info = host.run();
    EXPECT_EQ(info.ge_state, GE2GL_GE_IDLE);
    ASSERT_EQ(host.only("F").size(), 1u);
    EXPECT_EQ(host.only("F")[0].arg, 0x42u);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_COMPLETED);
    EXPECT_EQ(ge2gl_list_update_stall(host.h, id, L0), GE2GL_SCE_ERROR_ALREADY);
}

// Lists run in enqueue order; a head-enqueued list runs before the paused current one.
TEST(ApiQueue, TailAndHeadOrder) {
    Host host;
    uint32_t addr[4];
    for (uint32_t k = 0; k < 4; ++k) {
        ListWriter L(host, L0 + k * 0x100);
        addr[k] = L.start();
        L.put(TEC, k + 1);
        L.finish(0x10 + k);
    }
    int32_t a, b, c;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, addr[0], 0, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, addr[1], 0, -1, nullptr, &b), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, addr[2], 0, -1, nullptr, &c), GE2GL_OK);
    EXPECT_NE(a, b);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_DRAWING);
    EXPECT_EQ(host.peek(b), GE2GL_LIST_QUEUED);
    EXPECT_EQ(host.peek(c), GE2GL_LIST_QUEUED);
    host.run();
    auto f = host.only("F");
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f[0].list, a);
    EXPECT_EQ(f[1].list, b);
    EXPECT_EQ(f[2].list, c);
    EXPECT_EQ(f[0].arg, 0x10u);
    EXPECT_EQ(f[2].arg, 0x12u);
    host.events.clear();

    // Head enqueue needs the current list paused.
    int32_t idA, idB, idH;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, addr[0], addr[0], -1, nullptr, &idA), GE2GL_OK);  // stalled at its start
    ASSERT_EQ(ge2gl_list_enqueue(host.h, addr[1], 0, -1, nullptr, &idB), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue_head(host.h, addr[3], 0, -1, nullptr, &idH), GE2GL_SCE_ERROR_INVALID_VALUE);
    int32_t broken = 0;
    ASSERT_EQ(ge2gl_break(host.h, 0, &broken), GE2GL_OK);
    EXPECT_EQ(broken, idA);
    ASSERT_EQ(ge2gl_list_enqueue_head(host.h, addr[3], 0, -1, nullptr, &idH), GE2GL_OK);
    EXPECT_EQ(host.peek(idH), GE2GL_LIST_PAUSED);  // waits for sceGeContinue
    EXPECT_EQ(host.peek(idA), GE2GL_LIST_PAUSED);  // demoted to queued, but it had started
    EXPECT_EQ(host.peek(idB), GE2GL_LIST_QUEUED);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_PAUSED);
    EXPECT_TRUE(host.only("F").empty());
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    ge2gl_run_info info = host.run();
    // H finished, A resumed and sits at its stall again.
    EXPECT_EQ(info.ge_state, GE2GL_GE_STALLED);
    EXPECT_EQ(info.list_id, idA);
    ASSERT_EQ(ge2gl_list_update_stall(host.h, idA, 0), GE2GL_OK);
    host.run();
    f = host.only("F");
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f[0].list, idH);
    EXPECT_EQ(f[1].list, idA);
    EXPECT_EQ(f[2].list, idB);
    EXPECT_EQ(f[0].arg, 0x13u);
    EXPECT_EQ(f[1].arg, 0x10u);

    // Head enqueue into an empty queue: paused until continued.
    host.events.clear();
    ASSERT_EQ(ge2gl_list_enqueue_head(host.h, addr[2], 0, -1, nullptr, &idH), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_PAUSED);
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.only("F").size(), 1u);
}

// sceGeListSync / sceGeDrawSync in both modes at every list state (ge-rules.md §4.7).
TEST(ApiSync, WaitAndPeekAtEveryState) {
    Host host;
    ListWriter A(host, L0);
    A.put(TEC, 1);
    A.put(TEC, 2);
    A.finish(1);
    ListWriter B(host, L0 + 0x100);
    B.put(MDC, 7);
    B.finish(2);
    int32_t a, b, s = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, A.start(), A.start() + 4, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, B.start(), 0, -1, nullptr, &b), GE2GL_OK);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_DRAWING);
    EXPECT_EQ(host.peek(b), GE2GL_LIST_QUEUED);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_DRAWING);

    // Wait on the queued list: the GE runs A up to its stall and cannot go on.
    EXPECT_EQ(ge2gl_list_sync(host.h, b, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_NE(std::string(ge2gl_last_message(host.h)).find("stalled"), std::string::npos);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
    EXPECT_EQ(host.peek(a), GE2GL_LIST_STALLING);
    EXPECT_EQ(host.peek(b), GE2GL_LIST_QUEUED);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_STALLING);
    EXPECT_EQ(ge2gl_list_sync(host.h, a, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);

    // Paused.
    int32_t broken = 0;
    ASSERT_EQ(ge2gl_break(host.h, 0, &broken), GE2GL_OK);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_PAUSED);
    EXPECT_EQ(ge2gl_list_sync(host.h, a, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_DRAWING);  // the firmware answers DRAWING/STALLING only
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_STALLING);

    // Wait for A only: B must not run yet (it becomes the current list, DRAWING).
    ASSERT_EQ(ge2gl_list_update_stall(host.h, a, 0), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_sync(host.h, a, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_COMPLETED);
    EXPECT_EQ(host.peek(b), GE2GL_LIST_DRAWING);
    EXPECT_EQ(host.cmd(MDC), word(MDC, 0));
    ASSERT_EQ(host.only("F").size(), 1u);

    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);
    EXPECT_EQ(host.cmd(MDC), word(MDC, 7));
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);
    // A completed draw sync frees the completed lists (uOFW sceGeDrawSync): peek no longer knows
    // them, a wait returns at once.
    EXPECT_EQ(host.peek(a), GE2GL_SCE_ERROR_INVALID_ID);
    ASSERT_EQ(ge2gl_list_sync(host.h, a, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);

    EXPECT_EQ(ge2gl_list_sync(host.h, a, 2, &s), GE2GL_SCE_ERROR_INVALID_MODE);
    EXPECT_EQ(ge2gl_draw_sync(host.h, -1, &s), GE2GL_SCE_ERROR_INVALID_MODE);
    EXPECT_EQ(ge2gl_list_sync(host.h, 12345, GE2GL_SYNC_PEEK, &s), GE2GL_SCE_ERROR_INVALID_ID);
}

TEST(ApiBreak, BreakThenContinueResumesAtTheNextCommand) {
    Host host;
    int32_t id = 0, out = 0;
    EXPECT_EQ(ge2gl_break(host.h, 0, &out), GE2GL_SCE_ERROR_ALREADY);  // nothing queued
    EXPECT_EQ(ge2gl_continue(host.h), GE2GL_OK);                       // nothing to continue: fine
    ListWriter L(host, L0);
    for (uint32_t k = 1; k <= 8; ++k) L.put(TEC, k);
    L.finish();
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(host.run(3).pc, L0 + 12);
    EXPECT_EQ(ge2gl_continue(host.h), GE2GL_SCE_ERROR_ALREADY);  // running, not paused
    ASSERT_EQ(ge2gl_break(host.h, 0, &out), GE2GL_OK);
    EXPECT_EQ(out, id);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_PAUSED);
    EXPECT_EQ(ge2gl_break(host.h, 0, &out), GE2GL_SCE_ERROR_ALREADY);
    EXPECT_EQ(ge2gl_break(host.h, 2, &out), GE2GL_SCE_ERROR_INVALID_MODE);
    ge2gl_run_info info = host.run();
    EXPECT_EQ(info.ge_state, GE2GL_GE_PAUSED);
    EXPECT_EQ(info.commands, 0u);
    EXPECT_EQ(info.pc, L0 + 12);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 3));
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    host.run(1);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 4));  // exactly the next command
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 8));
    EXPECT_EQ(host.only("F").size(), 1u);
}

TEST(ApiBreak, BreakFromASignalCallbackStopsAfterTheEnd) {
    Host host;
    ListWriter L(host, L0);
    L.put(TEC, 1);
    const uint32_t sig = L.signal(0x02, 0x55);  // HANDLER_CONTINUE
    L.put(TEC, 2);
    L.put(TEC, 3);
    L.finish();
    int32_t id = 0, broken = 0;
    ge2gl_status inCallback = 1;
    host.onSignal = [&](const ge2gl_interrupt&) { inCallback = ge2gl_break(host.h, 0, &broken); };
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info = host.run();
    EXPECT_EQ(inCallback, GE2GL_OK);
    EXPECT_EQ(broken, id);
    EXPECT_EQ(info.ge_state, GE2GL_GE_PAUSED);
    EXPECT_EQ(info.pc, sig + 8);  // right after the END
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
    host.onSignal = nullptr;
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 3));
}

TEST(ApiBreak, ResetClearsTheQueue) {
    Host host;
    ListWriter L(host, L0);
    L.put(TEC, 1);
    L.finish();
    ListWriter M(host, L0 + 0x100);
    M.put(TEC, 2);
    M.finish();
    int32_t a, b, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, M.start(), 0, -1, nullptr, &b), GE2GL_OK);
    ASSERT_EQ(ge2gl_break(host.h, 1, nullptr), GE2GL_OK);
    EXPECT_EQ(host.peek(a), GE2GL_SCE_ERROR_INVALID_ID);
    EXPECT_EQ(host.peek(b), GE2GL_SCE_ERROR_INVALID_ID);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_PEEK, &s), GE2GL_OK);
    EXPECT_EQ(s, GE2GL_LIST_COMPLETED);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 0));
    // The same addresses can be queued again.
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
}

// ---- SIGNAL behaviours (ge-rules.md §4.4) ----

TEST(ApiSignal, HandlerSuspendAndContinueCallBackAndGoOn) {
    Host host;
    int32_t cbid = -1, id = 0;
    ASSERT_EQ(ge2gl_set_callback(host.h, 0x08801000, 0x1111, 0x08802000, 0x2222, &cbid), GE2GL_OK);
    EXPECT_EQ(cbid, 0);
    ListWriter L(host, L0);
    const uint32_t s1 = L.signal(0x01, 0xABCD, 0x0077);  // HANDLER_SUSPEND
    L.put(TEC, 1);
    const uint32_t s2 = L.signal(0x02, 0x1234, 0x0056);  // HANDLER_CONTINUE
    L.put(TEC, 2);
    const uint32_t fin = L.finish(0xBEEF);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, cbid, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(host.cmd(TEC), word(TEC, 2));
    // Order and arguments: signal, its END, signal, its END, the FINISH's END, then finish.
    auto ev = host.only("SEF");
    ASSERT_EQ(ev.size(), 6u);
    EXPECT_EQ(ev[0].kind, 'S');
    EXPECT_EQ(ev[0].behaviour, 1u);
    EXPECT_EQ(ev[0].arg, 0xABCDu);
    EXPECT_EQ(ev[0].endArg, 0x77u);
    EXPECT_EQ(ev[0].pc, s1 + 8);
    EXPECT_EQ(ev[0].list, id);
    EXPECT_EQ(ev[0].cbid, cbid);
    EXPECT_EQ(ev[0].registered, 1);
    EXPECT_EQ(ev[0].func, 0x08801000u);
    EXPECT_EQ(ev[0].funcArg, 0x1111u);
    EXPECT_EQ(ev[1].kind, 'E');
    EXPECT_EQ(ev[1].pc, s1 + 8);
    EXPECT_EQ(ev[2].kind, 'S');
    EXPECT_EQ(ev[2].behaviour, 2u);
    EXPECT_EQ(ev[2].arg, 0x1234u);
    EXPECT_EQ(ev[2].pc, s2 + 8);
    EXPECT_EQ(ev[3].kind, 'E');
    EXPECT_EQ(ev[4].kind, 'E');
    EXPECT_EQ(ev[4].pc, fin + 8);
    EXPECT_EQ(ev[5].kind, 'F');
    EXPECT_EQ(ev[5].arg, 0xBEEFu);
    EXPECT_EQ(ev[5].pc, fin + 8);
    EXPECT_EQ(ev[5].func, 0x08802000u);
    EXPECT_EQ(ev[5].funcArg, 0x2222u);
    EXPECT_EQ(ev[5].behaviour, 0u);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_COMPLETED);

    // Unregistered callback ID: interrupts still reported, marked as not registered.
    ASSERT_EQ(ge2gl_unset_callback(host.h, cbid), GE2GL_OK);
    host.events.clear();
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, cbid, nullptr, &id), GE2GL_OK);
    host.run();
    ASSERT_EQ(host.only("F").size(), 1u);
    EXPECT_EQ(host.only("F")[0].registered, 0);
    EXPECT_EQ(host.only("F")[0].func, 0u);
}

TEST(ApiSignal, OldSdkPassesNoListAddressAndSuspendsDuringTheCallback) {
    Host host(GE2GL_BACKEND_NULL, 0x02000010);
    ListWriter L(host, L0);
    L.signal(0x01, 0x99);
    L.finish(5);
    int32_t id = 0, during = -1;
    host.onSignal = [&](const ge2gl_interrupt& i) { during = host.peek(i.list_id); };
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(during, GE2GL_LIST_PAUSED);  // SDK <= 2.00.10: PAUSED while the handler runs
    auto ev = host.only("SF");
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].pc, 0u);
    EXPECT_EQ(ev[1].pc, 0u);
    EXPECT_EQ(ev[1].arg, 5u);
    // The duplicate-address check starts with SDK 2.0 (uOFW: version > 0x01FFFFFF).
    ListWriter M(host, L0 + 0x100);
    M.finish();
    int32_t x, y;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, M.start(), M.start(), -1, nullptr, &x), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, M.start(), M.start(), -1, nullptr, &y), GE2GL_SCE_ERROR_BUSY);
    Host sdk1(GE2GL_BACKEND_NULL, 0x01050001);
    ListWriter N(sdk1, L0);
    N.finish();
    ASSERT_EQ(ge2gl_list_enqueue(sdk1.h, L0, L0, -1, nullptr, &x), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue(sdk1.h, L0, L0, -1, nullptr, &y), GE2GL_OK);
    EXPECT_NE(x, y);
}

TEST(ApiSignal, HandlerPauseStopsAtTheFinishUntilContinued) {
    Host host;
    ListWriter L(host, L0);
    L.signal(0x03, 0x77);        // HANDLER_PAUSE (sceGuSignal(GU_SIGNAL_PAUSE): SIGNAL, END, FINISH, END)
    const uint32_t mid = L.put(TEC, 1);
    const uint32_t fin = L.finish(0x31);
    L.put(TEC, 2);
    const uint32_t fin2 = L.finish(0x32);
    int32_t id = 0;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, mid + 4, -1, nullptr, &id), GE2GL_OK);
    host.run();
    // Between the SIGNAL and its FINISH the firmware already reports PAUSED, and refuses both
    // break and continue.
    EXPECT_EQ(host.peek(id), GE2GL_LIST_PAUSED);
    EXPECT_EQ(ge2gl_continue(host.h), GE2GL_SCE_ERROR_BUSY);
    EXPECT_EQ(ge2gl_break(host.h, 0, nullptr), GE2GL_SCE_ERROR_BUSY);
    EXPECT_TRUE(host.only("S").empty());

    ASSERT_EQ(ge2gl_list_update_stall(host.h, id, 0), GE2GL_OK);
    ge2gl_run_info info = host.run();
    EXPECT_EQ(info.ge_state, GE2GL_GE_PAUSED);
    EXPECT_EQ(info.pc, fin + 8);
    auto s = host.only("S");
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].behaviour, 3u);
    EXPECT_EQ(s[0].arg, 0x77u);
    EXPECT_EQ(s[0].pc, fin + 8);
    EXPECT_TRUE(host.only("F").empty());  // paused, not finished
    EXPECT_EQ(host.peek(id), GE2GL_LIST_PAUSED);
    EXPECT_EQ(host.run().commands, 0u);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));

    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 2));
    auto f = host.only("F");
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].arg, 0x32u);
    EXPECT_EQ(f[0].pc, fin2 + 8);
}

TEST(ApiSignal, SyncResumesAtTheFinishWithoutCallbacks) {
    Host host;
    ListWriter L(host, L0);
    L.signal(0x08, 0);
    L.finish(1);
    L.put(TEC, 5);
    L.finish(2);
    int32_t id = 0;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 5));
    EXPECT_TRUE(host.only("S").empty());
    auto f = host.only("F");
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].arg, 2u);
}

namespace {

// Builds: main list with `SIGNAL form` to a target that marks MDC and finishes; the word after
// the SIGNAL pair marks TEC 0xBAD (must be skipped). Returns the final TEC/MDC.
void checkJump(uint32_t behaviour, bool relative, bool offsetForm) {
    Host host;
    const uint32_t target = 0x08180040;
    ListWriter T(host, target);
    T.put(MDC, 0x600D);
    T.finish();
    ListWriter L(host, L0);
    uint32_t offset = 0;
    if (offsetForm) {
        offset = 0x08170000;
        L.put(OFFSET, offset >> 8);
    }
    const uint32_t sigAddr = L.here();
    uint32_t value = target;
    if (relative) value = target - sigAddr;
    if (offsetForm) value = target - offset;
    L.signalAddr(behaviour, value);
    L.put(TEC, 0xBAD);
    L.finish();
    int32_t id = 0;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(MDC), word(MDC, 0x600D)) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(TEC), word(TEC, 0)) << "behaviour " << behaviour;
    EXPECT_EQ(host.only("F").size(), 1u);
    EXPECT_TRUE(host.only("X").empty());
}

void checkCall(uint32_t behaviour, bool relative, bool offsetForm) {
    Host host;
    const uint32_t target = 0x08180040;
    ListWriter T(host, target);
    T.put(MDC, 0x5B);
    T.put(BASE, 0x0A0000);  // the sub-list changes BASE; signal RET restores it
    T.signal(0x12, 0);      // RET
    ListWriter L(host, L0);
    uint32_t offset = 0;
    L.put(BASE, 0x080000);
    if (offsetForm) {
        // OCALL forms its target like CMD_CALL: (BASE-high | value) + OFFSET (PPSSPP).
        offset = 0x00170000;
        L.put(OFFSET, offset >> 8);
    }
    const uint32_t sigAddr = L.here();
    uint32_t value = target;
    if (relative) value = target - sigAddr;
    if (offsetForm) value = target - 0x08000000 - offset;
    L.signalAddr(behaviour, value);
    L.put(TEC, 0x2);
    L.finish();
    int32_t id = 0;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(MDC), word(MDC, 0x5B)) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(TEC), word(TEC, 2)) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(BASE), word(BASE, 0x080000)) << "behaviour " << behaviour;
    EXPECT_EQ(host.cmd(OFFSET) & 0xFFFFFF, offset >> 8);
    EXPECT_EQ(host.only("F").size(), 1u);
    EXPECT_TRUE(host.only("X").empty());
}

}  // namespace

TEST(ApiSignal, JumpVariants) {
    checkJump(0x10, false, false);  // JUMP: absolute
    checkJump(0x13, true, false);   // RJUMP: relative to the SIGNAL's address
    checkJump(0x15, false, true);   // OJUMP: relative to OFFSET
}

TEST(ApiSignal, CallReturnVariants) {
    checkCall(0x11, false, false);  // CALL
    checkCall(0x14, true, false);   // RCALL
    checkCall(0x16, false, true);   // OCALL
}

TEST(ApiSignal, ReturnWithEmptyStackDropsTheListAndTheQueueGoesOn) {
    Host host;
    ListWriter L(host, L0);
    L.signal(0x12, 0);
    L.put(TEC, 0xBAD);
    L.finish();
    ListWriter M(host, L0 + 0x100);
    M.put(MDC, 1);
    M.finish(9);
    int32_t a, b;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, M.start(), 0, -1, nullptr, &b), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
    auto x = host.only("X");
    ASSERT_EQ(x.size(), 1u);
    EXPECT_EQ(x[0].list, a);
    EXPECT_FALSE(x[0].message.empty());
    EXPECT_EQ(host.cmd(TEC), word(TEC, 0));
    auto f = host.only("F");
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].list, b);
    EXPECT_EQ(host.peek(a), GE2GL_LIST_COMPLETED);
}

TEST(ApiSignal, SignalCallStackDepthFollowsTheListArgs) {
    Host host;
    // sub calls itself through a second signal CALL: depth 2 with numStacks = 1 must fail.
    const uint32_t sub = 0x08180000;
    ListWriter S(host, sub);
    S.put(MDC, 1);
    S.signalAddr(0x11, 0x08180100);
    S.signal(0x12, 0);
    ListWriter S2(host, 0x08180100);
    S2.put(MSC, 1);
    S2.signal(0x12, 0);
    ListWriter L(host, L0);
    L.signalAddr(0x11, sub);
    L.put(TEC, 3);
    L.finish();
    ge2gl_list_args args{16, 0, 1, 0x08200000};
    int32_t id;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, &args, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(host.only("X").size(), 1u);
    EXPECT_EQ(host.cmd(MSC), word(MSC, 0));
    host.events.clear();
    args.num_stacks = 2;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, &args, &id), GE2GL_OK);
    host.run();
    EXPECT_TRUE(host.only("X").empty());
    EXPECT_EQ(host.cmd(MSC), word(MSC, 1));
    EXPECT_EQ(host.cmd(TEC), word(TEC, 3));
    args.num_stacks = 256;
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, &args, &id), GE2GL_SCE_ERROR_INVALID_SIZE);
}

// sceGeGetStack as pspautotests gpu/ge/get reads it on a PSP: 0 for any index outside a list; in
// a signal handler one SIGNAL CALL deep, depth 1 for index -1 and 0 (entry 0 written: the return
// address, OFFSET and BASE of the call), an invalid index error for 255.
TEST(ApiSignal, GetStackReportsTheSignalCallDepthInsideAHandler) {
    Host host;
    int32_t depth = -1;
    uint32_t frame[8];
    ASSERT_EQ(ge2gl_get_stack(host.h, 255, frame, &depth), GE2GL_OK);
    EXPECT_EQ(depth, 0);
    const uint32_t sub = 0x08180000;
    ListWriter S(host, sub);
    S.put(BASE, 0x0A0000);
    S.signal(0x01, 7);  // HANDLER_SUSPEND: the callback runs one call deep
    S.signal(0x12, 0);  // RET
    ListWriter L(host, L0);
    L.put(BASE, 0x080000);
    L.put(OFFSET, 0x000100);
    const uint32_t callAt = L.signalAddr(0x11, sub);
    L.finish();
    struct Seen { ge2gl_status minus1 = 1, zero = 1, big = 1, nullOut = 1; int32_t d1 = -1, d0 = -1, dn = -1; uint32_t f[8] = {}; } seen;
    host.onSignal = [&](const ge2gl_interrupt&) {
        seen.minus1 = ge2gl_get_stack(host.h, -1, nullptr, &seen.d1);
        std::memset(seen.f, 0xCC, sizeof seen.f);
        seen.zero = ge2gl_get_stack(host.h, 0, seen.f, &seen.d0);
        seen.big = ge2gl_get_stack(host.h, 255, nullptr, nullptr);
        seen.nullOut = ge2gl_get_stack(host.h, 0, nullptr, &seen.dn);
    };
    int32_t id;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(seen.minus1, GE2GL_OK);
    EXPECT_EQ(seen.d1, 1);
    EXPECT_EQ(seen.zero, GE2GL_OK);
    EXPECT_EQ(seen.d0, 1);
    EXPECT_EQ(seen.big, GE2GL_SCE_ERROR_INVALID_INDEX);
    EXPECT_EQ(seen.nullOut, GE2GL_OK);
    EXPECT_EQ(seen.dn, 1);
    EXPECT_EQ(seen.f[0], 0u);
    EXPECT_EQ(seen.f[1], callAt + 8);  // returns past the SIGNAL + END pair
    EXPECT_EQ(seen.f[2], 0x100u << 8);           // OFFSET holds its argument shifted by 8
    EXPECT_EQ(seen.f[7], word(BASE, 0x080000));  // the BASE register word, as PPSSPP keeps it
    EXPECT_EQ(seen.f[3], 0u);
    ASSERT_EQ(host.only("F").size(), 1u);
    EXPECT_EQ(ge2gl_get_stack(host.h, 0, nullptr, &depth), GE2GL_OK);
    EXPECT_EQ(depth, 0);
}

TEST(ApiSignal, CmdJumpCallRetStillWorkThroughTheQueue) {
    Host host;
    ListWriter Sub(host, 0x08190000);
    Sub.put(MSC, 0x44);
    Sub.put(RET, 0);
    ListWriter L(host, L0);
    L.put(BASE, 0x080000);
    L.put(CALL, 0x190000);
    L.put(JUMP, (L0 + 0x40) & 0xFFFFFF);
    L.put(TEC, 0xBAD);
    ListWriter T(host, L0 + 0x40);
    T.put(TEC, 0x600D);
    T.finish();
    int32_t id;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(host.cmd(MSC), word(MSC, 0x44));
    EXPECT_EQ(host.cmd(TEC), word(TEC, 0x600D));
}

// ---- Context, readback ----

namespace {

// A list that sets every context register to a pattern and loads all matrices.
void writeStateList(Host& host, uint32_t at, uint32_t seed) {
    ListWriter L(host, at);
    // The state opcodes of the 512-word context (docs/ppdmp.md §5), minus those with side
    // effects on list flow (BASE/OFFSET/ORIGIN) and the address registers.
    const std::pair<int, int> ranges[] = {{0x12, 0x12}, {0x15, 0x28}, {0x2C, 0x33}, {0x36, 0x38}, {0x42, 0x4D},
                                          {0x50, 0x51}, {0x53, 0x58}, {0x5B, 0xB5}, {0xB8, 0xC3}, {0xC5, 0xCA},
                                          {0xCD, 0xD0}, {0xD2, 0xE9}, {0xEB, 0xEC}, {0xEE, 0xEE},
                                          {0xF0, 0xF6}, {0xF8, 0xF9}};
    for (auto [a, b] : ranges)
        for (int op = a; op <= b; ++op) L.put(uint32_t(op), (seed * 0x9E3779B1u + uint32_t(op) * 0x01010101u) & 0xFFFFFF);
    const uint32_t mats[5][3] = {{0x2A, 0x2B, 96}, {0x3A, 0x3B, 12}, {0x3C, 0x3D, 12}, {0x3E, 0x3F, 16}, {0x40, 0x41, 12}};
    for (auto& m : mats) {
        L.put(m[0], 0);
        for (uint32_t k = 0; k < m[2]; ++k) L.put(m[1], (seed << 16) ^ (k * 0x1357) ^ (m[1] << 4));
        L.put(m[0], (seed + m[2]) & 0xF);  // leave a non-zero upload index
    }
    L.finish();
}

struct Snapshot {
    std::array<uint32_t, 255> cmds{};
    std::array<std::array<uint32_t, 16>, 12> mtx{};
    bool operator==(const Snapshot& o) const { return cmds == o.cmds && mtx == o.mtx; }
};

Snapshot snapshot(Host& host) {
    Snapshot s;
    for (uint32_t op = 0; op < 255; ++op) s.cmds[op] = host.cmd(op);
    for (int t = 0; t < 12; ++t) {
        int32_t n = 0;
        EXPECT_EQ(ge2gl_get_matrix(host.h, t, s.mtx[t].data(), &n), GE2GL_OK);
        EXPECT_EQ(n, t == 10 ? 16 : 12);
    }
    return s;
}

int32_t runList(Host& host, uint32_t at, const ge2gl_list_args* args = nullptr) {
    int32_t id = 0, s = 0;
    EXPECT_EQ(ge2gl_list_enqueue(host.h, at, 0, -1, args, &id), GE2GL_OK);
    EXPECT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    return id;
}

}  // namespace

// pspautotests gpu/ge/break "Pause signal", as a PSP answered: sceGeBreak(0) on a list that a
// HANDLER_PAUSE signal paused is busy (0x80000021), on one a break paused already (0x80000020);
// after sceGeContinue the list completes.
TEST(ApiSignal, BreakOnASignalPausedListIsBusy) {
    Host host(GE2GL_BACKEND_NULL, 0x06060010);
    ListWriter L(host, L0);
    L.put(0, 0);
    L.signal(0x03, 0);  // HANDLER_PAUSE: pauses at the next FINISH
    L.put(0, 0);
    L.finish();
    int32_t id = -1, brk = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(host.peek(id), GE2GL_LIST_PAUSED);
    EXPECT_EQ(ge2gl_break(host.h, 0, &brk), GE2GL_SCE_ERROR_BUSY);
    ASSERT_EQ(ge2gl_continue(host.h), GE2GL_OK);
    host.run();
    EXPECT_EQ(host.peek(id), GE2GL_LIST_COMPLETED);
    // Paused by a break instead: already.
    ListWriter S(host, 0x08120000);
    S.put(0, 0);
    S.finish();
    ASSERT_EQ(ge2gl_list_enqueue(host.h, 0x08120000, 0x08120000, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_break(host.h, 0, &brk), GE2GL_OK);
    EXPECT_EQ(ge2gl_break(host.h, 0, &brk), GE2GL_SCE_ERROR_ALREADY);
}

// pspautotests gpu/ge/queue switches the SDK version at run time: with 0 (no version, an old
// SDK) the same list may be queued twice, with 2.00 the second enqueue is busy.
TEST(ApiSdk, SetSdkVersionTakesEffectAtTheNextCall) {
    Host host(GE2GL_BACKEND_NULL, 0x06060010);
    ListWriter L(host, L0);
    L.finish();
    int32_t a = -1, b = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &a), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &b), GE2GL_SCE_ERROR_BUSY);
    ASSERT_EQ(ge2gl_set_sdk_version(host.h, 0), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &b), GE2GL_OK);
    EXPECT_NE(a, b);
    ASSERT_EQ(ge2gl_set_sdk_version(host.h, 0x02000000), GE2GL_OK);
    int32_t c = -1;
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &c), GE2GL_SCE_ERROR_BUSY);
    EXPECT_EQ(ge2gl_set_sdk_version(nullptr, 0), GE2GL_ERR_INVALID_HANDLE);
}

// pspautotests gpu/signals/suspend on a PSP (old SDK): the list reads PAUSED while its suspend
// handler runs and DRAWING again after. With hold_interrupts the host runs the handler after the
// callback, so the PAUSED state lasts until ge2gl_interrupt_ack.
TEST(ApiSignal, OldSdkSuspendReadsPausedUntilTheHeldHandlerReturns) {
    Host host(GE2GL_BACKEND_NULL, 0x02000010, false, true);
    ListWriter L(host, L0);
    L.signal(0x01, 5);
    L.put(TEC, 1);
    L.finish();
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run(host.h, 1000, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_PAUSED);
    ASSERT_EQ(ge2gl_interrupt_ack(host.h), GE2GL_OK);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_DRAWING);
    ASSERT_EQ(ge2gl_run(host.h, 1000, &info), GE2GL_OK);  // to the finish, held
    ASSERT_EQ(ge2gl_interrupt_ack(host.h), GE2GL_OK);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_COMPLETED);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
}

TEST(ApiContext, SaveRestoreRoundTripsRegistersAndMatrices) {
    Host host;
    writeStateList(host, L0, 1);
    writeStateList(host, 0x08140000, 2);
    runList(host, L0);
    const Snapshot s1 = snapshot(host);
    EXPECT_EQ(s1.cmds[0xCA], word(0xCA, (1 * 0x9E3779B1u + 0xCAu * 0x01010101u) & 0xFFFFFF));
    std::array<uint32_t, 512> ctx{};
    ASSERT_EQ(ge2gl_save_context(host.h, ctx.data()), GE2GL_OK);
    // In guest memory the context ends with its END word (384): a PSP leaves the rest of the
    // 512-word buffer alone (pspautotests gpu/ge/context checks word 386).
    for (uint32_t k = 380; k < 512; ++k) host.write32(0x08200000 + 4 * k, 0xCCCCCCCC);
    ASSERT_EQ(ge2gl_save_context_at(host.h, 0x08200000), GE2GL_OK);
    uint32_t tail[3];
    ASSERT_EQ(ge2gl_mem_read(host.h, 0x08200000 + 4 * 384, tail, sizeof tail), GE2GL_OK);
    EXPECT_EQ(tail[0], 0x0C000000u);
    EXPECT_EQ(tail[1], 0xCCCCCCCCu);
    EXPECT_EQ(tail[2], 0xCCCCCCCCu);

    runList(host, 0x08140000);
    const Snapshot s2 = snapshot(host);
    EXPECT_FALSE(s1 == s2);

    ASSERT_EQ(ge2gl_restore_context(host.h, ctx.data()), GE2GL_OK);
    Snapshot r = snapshot(host);
    for (uint32_t op = 0; op < 255; ++op) EXPECT_EQ(r.cmds[op], s1.cmds[op]) << "opcode 0x" << std::hex << op;
    EXPECT_TRUE(r.mtx == s1.mtx);

    runList(host, 0x08140000);
    ASSERT_EQ(ge2gl_restore_context_at(host.h, 0x08200000), GE2GL_OK);
    EXPECT_TRUE(snapshot(host) == s1);

    // A list with its own context buffer leaves the state as it found it (saved at start,
    // restored at FINISH, ge-rules.md §4.5), and the buffer holds that state.
    ge2gl_list_args args{16, 0x08300000, 0, 0};
    runList(host, 0x08140000, &args);
    EXPECT_TRUE(snapshot(host) == s1);
    std::array<uint32_t, 512> fromList{};
    ASSERT_EQ(ge2gl_mem_read(host.h, 0x08300000, fromList.data(), 2048), GE2GL_OK);
    EXPECT_EQ(fromList, ctx);

    // Corrupt contexts change nothing.
    std::array<uint32_t, 512> bad = ctx;
    bad[17 + 20] = 0xFF000000;
    EXPECT_EQ(ge2gl_restore_context(host.h, bad.data()), GE2GL_SCE_ERROR_INVALID_VALUE);
    EXPECT_TRUE(snapshot(host) == s1);
    EXPECT_EQ(ge2gl_restore_context_at(host.h, 0x08200002), GE2GL_SCE_ERROR_INVALID_POINTER);
    EXPECT_EQ(ge2gl_save_context_at(host.h, 0x083FFF00), GE2GL_SCE_ERROR_BAD_POINTER);  // runs past RAM
    EXPECT_EQ(ge2gl_restore_context_at(host.h, 0x00000000), GE2GL_SCE_ERROR_BAD_POINTER);

    // Busy while a list is drawing (stalled counts as drawing): the save answers -1 as the firmware
    // does (pspautotests gpu/ge/context), the restore busy.
    int32_t id;
    ListWriter L(host, 0x08150000);
    L.put(TEC, 1);
    L.finish();
    ASSERT_EQ(ge2gl_list_enqueue(host.h, 0x08150000, 0x08150000, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(ge2gl_save_context(host.h, ctx.data()), ge2gl_status(-1));
    EXPECT_EQ(ge2gl_save_context_at(host.h, 0x08200000), ge2gl_status(-1));
    EXPECT_STRNE(ge2gl_last_message(host.h), "");
    EXPECT_EQ(ge2gl_restore_context(host.h, ctx.data()), GE2GL_SCE_ERROR_BUSY);
}

TEST(ApiReadback, GetCmdAndGetMtxFollowTheHardwareRules) {
    Host host;
    ListWriter L(host, L0);
    L.put(TEC, 0xABCDEF);
    L.put(0x3A, 0);  // WORLDN 0
    const float world[5] = {1.0f, -2.5f, 0.125f, 3.0f, 1e-3f};
    uint32_t bits[5];
    for (int k = 0; k < 5; ++k) {
        std::memcpy(&bits[k], &world[k], 4);
        L.put(0x3B, bits[k] >> 8);
    }
    L.put(0x2A, 12);  // BONEN 12: bone 1
    L.put(0x2B, 0x3F8000);  // 1.0
    L.put(0x2B, 0x400000);  // 2.0
    L.put(0x2B, 0x404000);  // 3.0
    L.finish();
    runList(host, L0);
    EXPECT_EQ(host.cmd(TEC), 0xCAABCDEFu);
    // Data ports read back as the bare opcode; number registers as the current index (ge-rules.md §1).
    EXPECT_EQ(host.cmd(0x3B), 0x3B000000u);
    EXPECT_EQ(host.cmd(0x3A), 0x3A000005u);
    EXPECT_EQ(host.cmd(0x2B), 0x2B000000u);
    EXPECT_EQ(host.cmd(0x2A), 0x2A00000Fu);
    uint32_t m[16];
    int32_t n = 0;
    ASSERT_EQ(ge2gl_get_matrix(host.h, 8, m, &n), GE2GL_OK);
    EXPECT_EQ(n, 12);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(m[k], bits[k] >> 8);
    ASSERT_EQ(ge2gl_get_matrix(host.h, 1, m, &n), GE2GL_OK);
    EXPECT_EQ(m[0], 0x3F8000u);
    EXPECT_EQ(m[1], 0x400000u);
    EXPECT_EQ(m[2], 0x404000u);
    ASSERT_EQ(ge2gl_get_matrix(host.h, 10, m, &n), GE2GL_OK);
    EXPECT_EQ(n, 16);

    uint32_t v;
    EXPECT_EQ(ge2gl_get_cmd(host.h, 0xFF, &v), GE2GL_SCE_ERROR_INVALID_INDEX);
    EXPECT_EQ(ge2gl_get_cmd(host.h, 0x100, &v), GE2GL_SCE_ERROR_INVALID_INDEX);
    EXPECT_EQ(ge2gl_get_cmd(host.h, 0x10, nullptr), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_get_matrix(host.h, 12, m, &n), GE2GL_SCE_ERROR_INVALID_INDEX);
    EXPECT_EQ(ge2gl_get_matrix(host.h, -1, m, &n), GE2GL_SCE_ERROR_INVALID_INDEX);
}

TEST(ApiEdram, TranslationAndSize) {
    Host host;
    uint32_t v = 0;
    ASSERT_EQ(ge2gl_edram_get_size(host.h, &v), GE2GL_OK);
    EXPECT_EQ(v, 0x200000u);
    ASSERT_EQ(ge2gl_edram_get_addr(host.h, &v), GE2GL_OK);
    EXPECT_EQ(v, 0x04000000u);
    ASSERT_EQ(ge2gl_edram_set_translation(host.h, 0x800, &v), GE2GL_OK);
    EXPECT_EQ(v, 0x400u);  // boot default
    EXPECT_EQ(ge2gl_edram_set_translation(host.h, 0x300, &v), GE2GL_SCE_ERROR_INVALID_VALUE);
    ASSERT_EQ(ge2gl_edram_set_translation(host.h, 0, &v), GE2GL_OK);
    EXPECT_EQ(v, 0x800u);
    ASSERT_EQ(ge2gl_edram_set_translation(host.h, 0x1000, nullptr), GE2GL_OK);
    ASSERT_EQ(ge2gl_edram_set_translation(host.h, 0x400, &v), GE2GL_OK);
    EXPECT_EQ(v, 0x1000u);
}

// ---- Bad input ----

TEST(ApiErrors, BadAddressesAndIdsGiveCodesAndCorruptNothing) {
    Host host;
    ListWriter L(host, L0);
    L.put(TEC, 1);
    L.finish(1);
    const std::vector<uint8_t> ram0 = host.ram, vram0 = host.vram;
    int32_t id = 0x7777, s = 0;
    auto expectMsg = [&] { EXPECT_STRNE(ge2gl_last_message(host.h), ""); };

    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0 + 2, 0, -1, nullptr, &id), GE2GL_SCE_ERROR_INVALID_POINTER);
    expectMsg();
    EXPECT_EQ(id, 0x7777);  // out-value untouched on failure
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, L0 + 1, -1, nullptr, &id), GE2GL_SCE_ERROR_INVALID_POINTER);
    ge2gl_list_args args{16, 0x08300001, 0, 0};
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, &args, &id), GE2GL_SCE_ERROR_INVALID_POINTER);
    args = {16, 0x0BFFF000, 0, 0};  // beyond this host's 4 MiB of RAM
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, &args, &id), GE2GL_SCE_ERROR_BAD_POINTER);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, 0x00000000, 0, -1, nullptr, &id), GE2GL_SCE_ERROR_BAD_POINTER);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, 0x08400000, 0, -1, nullptr, &id), GE2GL_SCE_ERROR_BAD_POINTER);
    expectMsg();

    for (int32_t bad : {0, -1, 0x35000040, 0x12345678, int32_t(0x80000000)}) {
        EXPECT_EQ(ge2gl_list_dequeue(host.h, bad), GE2GL_SCE_ERROR_INVALID_ID);
        EXPECT_EQ(ge2gl_list_update_stall(host.h, bad, L0), GE2GL_SCE_ERROR_INVALID_ID);
        EXPECT_EQ(ge2gl_list_sync(host.h, bad, GE2GL_SYNC_PEEK, &s), GE2GL_SCE_ERROR_INVALID_ID);
    }
    EXPECT_EQ(ge2gl_list_sync(host.h, 0x12345678, GE2GL_SYNC_WAIT, &s), GE2GL_SCE_ERROR_INVALID_ID);

    // Same list twice (SDK >= 2.0), 64 lists at most, dequeue rules.
    int32_t first, second;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &first), GE2GL_OK);  // stalled at its start
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0, L0, -1, nullptr, &id), GE2GL_SCE_ERROR_BUSY);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, 0x40000000 | L0, 0, -1, nullptr, &id), GE2GL_SCE_ERROR_BUSY);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0 + 0x1000, L0 + 0x1000, -1, nullptr, &second), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_dequeue(host.h, first), GE2GL_SCE_ERROR_BUSY);  // already started
    ASSERT_EQ(ge2gl_list_dequeue(host.h, second), GE2GL_OK);
    EXPECT_EQ(host.peek(second), GE2GL_SCE_ERROR_INVALID_ID);
    EXPECT_EQ(ge2gl_list_update_stall(host.h, first, L0 + 3), GE2GL_SCE_ERROR_INVALID_POINTER);
    for (uint32_t k = 1; k < 64; ++k) ASSERT_EQ(ge2gl_list_enqueue(host.h, L0 + 0x1000 + 4 * k, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_enqueue(host.h, L0 + 0x2000, 0, -1, nullptr, &id), GE2GL_SCE_ERROR_OUT_OF_MEMORY);
    ASSERT_EQ(ge2gl_break(host.h, 1, nullptr), GE2GL_OK);

    // Callbacks: 16 slots.
    int32_t cb;
    for (int k = 0; k < 16; ++k) {
        ASSERT_EQ(ge2gl_set_callback(host.h, 1, 2, 3, 4, &cb), GE2GL_OK);
        EXPECT_EQ(cb, k);
    }
    EXPECT_EQ(ge2gl_set_callback(host.h, 1, 2, 3, 4, &cb), GE2GL_SCE_ERROR_OUT_OF_MEMORY);
    EXPECT_EQ(ge2gl_unset_callback(host.h, 16), GE2GL_SCE_ERROR_INVALID_ID);
    EXPECT_EQ(ge2gl_unset_callback(host.h, -1), GE2GL_SCE_ERROR_INVALID_ID);

    // Memory and frame arguments.
    uint8_t buf[64];
    EXPECT_EQ(ge2gl_mem_write(host.h, 0x083FFFF0, buf, 64), GE2GL_ERR_MEMORY);
    EXPECT_EQ(ge2gl_mem_read(host.h, 0x02000000, buf, 4), GE2GL_ERR_MEMORY);
    EXPECT_EQ(ge2gl_mem_write(host.h, L0, nullptr, 4), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_read_frame(host.h, 0x04000000, 512, 3, 0, 272, buf, sizeof buf), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_read_frame(host.h, 0x04000000, 512, 7, 4, 4, buf, sizeof buf), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_read_frame(host.h, 0x04000000, 512, 3, 480, 272, buf, sizeof buf), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_read_frame(host.h, 0x041FFFF0, 512, 3, 4, 2, buf, sizeof buf), GE2GL_ERR_MEMORY);
    EXPECT_EQ(ge2gl_read_frame(host.h, 0x00000000, 4, 3, 4, 4, buf, sizeof buf), GE2GL_ERR_MEMORY);
    uint32_t tex;
    EXPECT_EQ(ge2gl_frame_texture(host.h, 0x04000000, 512, 3, 480, 272, &tex), GE2GL_ERR_UNSUPPORTED);

    EXPECT_EQ(host.ram, ram0);
    EXPECT_EQ(host.vram, vram0);

    // After all that the GE still works.
    host.events.clear();
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
    EXPECT_EQ(host.only("F").size(), 1u);
}

TEST(ApiErrors, WildJumpDropsOnlyThatList) {
    Host host;
    ListWriter L(host, L0);
    L.put(BASE, 0);
    L.put(JUMP, 0x000100);  // 0x00000100: not memory
    L.finish();
    ListWriter M(host, L0 + 0x100);
    M.put(TEC, 9);
    M.finish();
    int32_t a, b, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &a), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(host.h, M.start(), 0, -1, nullptr, &b), GE2GL_OK);
    ASSERT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_OK);
    auto x = host.only("X");
    ASSERT_EQ(x.size(), 1u);
    EXPECT_EQ(x[0].list, a);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 9));
    auto f = host.only("F");
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].list, b);
}

TEST(ApiErrors, EndWithoutFinishHangsTheListUntilReset) {
    Host host;
    ListWriter L(host, L0);
    L.put(TEC, 1);
    L.put(END, 0);
    L.put(TEC, 2);
    L.finish();
    int32_t id, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_HUNG);
    EXPECT_EQ(host.only("X").size(), 1u);
    EXPECT_EQ(host.peek(id), GE2GL_LIST_DRAWING);
    EXPECT_EQ(ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_EQ(host.cmd(TEC), word(TEC, 1));
    ASSERT_EQ(ge2gl_break(host.h, 1, nullptr), GE2GL_OK);
    EXPECT_EQ(host.run().ge_state, GE2GL_GE_IDLE);
}

TEST(ApiErrors, EndlessListHitsTheWaitBudget) {
    Host host;
    ListWriter L(host, L0);
    L.put(BASE, 0x080000);
    L.put(JUMP, L0 & 0xFFFFFF);  // jumps to itself forever
    int32_t id, s;
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    EXPECT_EQ(ge2gl_list_sync(host.h, id, GE2GL_SYNC_WAIT, &s), GE2GL_ERR_WOULD_BLOCK);
    EXPECT_EQ(ge2gl_break(host.h, 1, nullptr), GE2GL_OK);
}

TEST(ApiReentrancy, WaitsFromCallbacksAreRefused) {
    Host host;
    ListWriter L(host, L0);
    L.signal(0x02, 1);
    L.finish();
    ge2gl_status wait = 0, run = 0, stall = 1;
    int32_t id = 0;
    host.onSignal = [&](const ge2gl_interrupt& i) {
        int32_t s;
        wait = ge2gl_draw_sync(host.h, GE2GL_SYNC_WAIT, &s);
        run = ge2gl_run(host.h, 10, nullptr);
        stall = ge2gl_list_update_stall(host.h, i.list_id, 0);  // allowed
    };
    ASSERT_EQ(ge2gl_list_enqueue(host.h, L0, 0, -1, nullptr, &id), GE2GL_OK);
    host.run();
    EXPECT_EQ(wait, GE2GL_ERR_REENTRANT);
    EXPECT_EQ(run, GE2GL_ERR_REENTRANT);
    EXPECT_EQ(stall, GE2GL_OK);
    EXPECT_EQ(host.only("F").size(), 1u);
}
