// SPDX-License-Identifier: MIT
// The GE-time estimate (hle/ge_time.h, docs/timing.md): lists with known command,
// vertex and transfer counts cost what the model says, part by part; the sceGe layer charges each
// list its own time and stamps interrupts with the time they occur; a run to a tick stops between
// commands at that tick.
#include <gtest/gtest.h>

#include "authoring/list_builder.h"
#include "hle/ge_time.h"
#include "hle/sce_ge.h"

using namespace ge;

namespace {

TEST(GeTiming, CommandsVerticesAndTransfersCostWhatTheModelSays) {
    Memory mem;
    ListBuilder b(&mem);
    for (int i = 0; i < 37; ++i) b.nop();
    // 30 through-mode vertices: transform only, 20 cycles each (PPSSPP EstimatePerVertexCost).
    std::vector<BuildVertex> v(30);
    const u32 through = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    b.drawArrayData(GE_PRIM_TRIANGLES, through, 30, nullptr, packVertices(through, v.data(), 30).data());
    // 12 vertices lit by two lights with environment-map texture generation: 20 + 10 + 2 x 7 + 20.
    b.enable(GE_CMD_LTE, true);
    b.enable(GE_CMD_LE0, true);
    b.enable(GE_CMD_LE0 + 2, true);
    b.cmd(GE_CMD_TMAP, 2);
    const u32 lit = vt::NRM_F | vt::POS_F;
    std::vector<BuildVertex> w(12);
    b.drawArrayData(GE_PRIM_TRIANGLES, lit, 12, nullptr, packVertices(lit, w.data(), 12).data());
    // A 16 x 8 block transfer of 32-bit pixels: 512 bytes at 1.6 cycles a byte.
    b.copyImage(3, 0, 0, 16, 8, 64, 0x08200000, 0, 0, 64, 0x08210000);
    b.finish();
    const u32 list = b.placeList();
    ASSERT_NE(list, 0u);
    const u64 words = b.words().size();

    NullRenderer null;
    GeEngine eng(mem, &null);
    eng.startList(list, 0);
    ASSERT_EQ(eng.run(), RunStatus::Completed);
    const GeStats& s = eng.stats();
    EXPECT_EQ(s.commands, words);
    EXPECT_EQ(s.cyclesCommands, getime::kListStart + 2 * words + getime::kEnd);
    EXPECT_EQ(s.cyclesVertices, 30u * 20 + 12u * (20 + 10 + 2 * 7 + 20));
    EXPECT_EQ(s.cyclesTransfers, 16u * 8 * 4 * 16 / 10);
    EXPECT_EQ(s.cyclesPixels, 0u);  // the null backend fills no pixels
    EXPECT_EQ(s.cycles, s.cyclesCommands + s.cyclesVertices + s.cyclesTransfers + s.cyclesPixels);
}

struct Stamps : SceGeListener {
    std::vector<u64> finishTicks, signalTicks;
    void onSignal(const SceInterrupt& in) override { signalTicks.push_back(in.tick); }
    void onFinish(const SceInterrupt& in) override { finishTicks.push_back(in.tick); }
};

TEST(GeTiming, ListsAreChargedTheirOwnTimeAndInterruptsCarryTheirTick) {
    Memory mem;
    // List A: 100 NOPs, SIGNAL (continue) + END, 100 NOPs, FINISH + END. List B: 50 NOPs, FINISH + END.
    ListBuilder a(&mem);
    for (int i = 0; i < 100; ++i) a.nop();
    a.signal(2, 7);
    for (int i = 0; i < 100; ++i) a.nop();
    a.finish();
    const u32 listA = a.placeList();
    ListBuilder bb(&mem, ListBuilder::kDefaultArena + 0x10000);
    for (int i = 0; i < 50; ++i) bb.nop();
    bb.finish();
    const u32 listB = bb.placeList();

    NullRenderer null;
    GeEngine eng(mem, &null);
    SceGe sce(eng);
    Stamps st;
    sce.setListener(&st);
    const s32 idA = sce.listEnqueue(listA, 0, -1, nullptr, false);
    const s32 idB = sce.listEnqueue(listB, 0, -1, nullptr, false);
    ASSERT_GE(idA, 0);
    ASSERT_GE(idB, 0);
    // A started at enqueue: its start is already its time.
    EXPECT_EQ(sce.listCycles(idA), s64(getime::kListStart));

    // Run to tick 260: 60 for the start, then 100 NOPs at 2 cycles; it stops between commands.
    sce.setTickStop(260);
    SceRunResult r = sce.run(1u << 20);
    EXPECT_EQ(r.state, SceRunState::Budget);
    EXPECT_EQ(r.commands, 100u);
    EXPECT_EQ(eng.stats().cycles, 260u);
    EXPECT_TRUE(st.signalTicks.empty());
    sce.setTickStop(~u64(0));
    r = sce.run(1u << 20);
    EXPECT_EQ(r.state, SceRunState::Idle);

    // A: start, 204 commands, END costs of its SIGNAL and FINISH pairs.
    const u64 costA = getime::kListStart + 2 * 204 + 2 * getime::kEnd;
    const u64 costB = getime::kListStart + 2 * 52 + getime::kEnd;
    EXPECT_EQ(sce.listCycles(idA), s64(costA));
    EXPECT_EQ(sce.listCycles(idB), s64(costB));
    EXPECT_EQ(eng.stats().cycles, costA + costB);
    // The signal came after 102 commands of A; each finish at its list's end.
    ASSERT_EQ(st.signalTicks.size(), 1u);
    EXPECT_GE(st.signalTicks[0], getime::kListStart + 2 * 102);
    EXPECT_LE(st.signalTicks[0], getime::kListStart + 2 * 102 + getime::kEnd);
    ASSERT_EQ(st.finishTicks.size(), 2u);
    EXPECT_GE(st.finishTicks[0], costA - getime::kEnd);
    EXPECT_LE(st.finishTicks[0], costA);
    EXPECT_GE(st.finishTicks[1], costA + costB - getime::kEnd);
    EXPECT_LE(st.finishTicks[1], costA + costB);
    EXPECT_EQ(sce.listCycles(0x7FFF), -1);
}

}  // namespace
