// SPDX-License-Identifier: MIT
// Display-list control commands (manual §20, §11.1; docs/ge-rules.md §4), with expected values taken
// from the reference's worked examples.
#include <gtest/gtest.h>

#include "hle/ge_engine.h"

using namespace ge;

namespace {

u32 W(u8 op, u32 arg = 0) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

struct Recorder : Renderer {
    std::vector<PrimPacket> prims;
    std::vector<PatchPacket> patches;
    std::vector<TransferPacket> transfers;
    int finishes = 0, flushes = 0, clutLoads = 0;
    void drawPrim(const PrimPacket& p) override { prims.push_back(p); }
    void drawPatch(const PatchPacket& p) override { patches.push_back(p); }
    void drawImmediate(const ImmPacket&) override {}
    void blockTransfer(const TransferPacket& t, Memory&) override { transfers.push_back(t); }
    void finish() override { ++finishes; }
    void textureFlush() override { ++flushes; }
    void clutLoaded(const GeState&) override { ++clutLoads; }
};

struct Events : GeListener {
    std::vector<std::string> log;
    void onSignal(u32 b, u32 a, u32 e, u32) override { log.push_back("signal " + std::to_string(b) + " " + std::to_string(a) + " " + std::to_string(e)); }
    void onFinish(u32 a, u32) override { log.push_back("finish " + std::to_string(a)); }
    void onEnd(u32) override { log.push_back("end"); }
    void onError(GeError e, u32, const std::string&) override { log.push_back(std::string("error ") + geErrorName(e)); }
};

class EngineTest : public ::testing::Test {
protected:
    Memory mem{32u << 20};
    Recorder rec;
    Events ev;
    GeEngine eng{mem, &rec};
    static constexpr u32 kList = 0x08800000;
    void SetUp() override { eng.setListener(&ev); }
    void put(u32 addr, std::initializer_list<u32> words) {
        for (u32 w : words) {
            mem.write32(addr, w);
            addr += 4;
        }
    }
    RunStatus runAt(u32 pc, u32 stall = 0) {
        eng.startList(pc, stall);
        return eng.run(100000);
    }
};

TEST_F(EngineTest, FinishEndCompletesAndReportsArgument) {
    put(kList, {W(GE_CMD_NOP), W(GE_CMD_FINISH, 0x1234), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(rec.finishes, 1);
    ASSERT_EQ(ev.log.size(), 2u);
    EXPECT_EQ(ev.log[0], "end");
    EXPECT_EQ(ev.log[1], "finish 4660");
}

TEST_F(EngineTest, BareEndStopsTheGe) {
    put(kList, {W(GE_CMD_END), W(GE_CMD_AC, 0x112233)});
    EXPECT_EQ(runAt(kList), RunStatus::Ended);
    EXPECT_EQ(eng.state().AC_rgb(), 0u);  // the word after END was not executed
}

TEST_F(EngineTest, BaseAndVadrFormAddress) {
    // ge-rules.md §4.2: BASE 0x080000 then VADR 0x9ABCDE with OFFSET 0 → 0x089ABCDE.
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_VADR, 0x9ABCDE), W(GE_CMD_IADR, 0x000010), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().vertexAddr, 0x089ABCDEu);
    EXPECT_EQ(eng.state().indexAddr, 0x08000010u);
}

TEST_F(EngineTest, OriginThenJumpIsRelativeToTheOriginCommand) {
    // ge-rules.md §4.2: ORIGIN at 0x08801000, BASE 0, JUMP 0x000100 → PC = 0x08801100.
    put(0x08801000, {W(GE_CMD_ORIGIN), W(GE_CMD_BASE, 0), W(GE_CMD_JUMP, 0x000100)});
    put(0x08801100, {W(GE_CMD_AC, 0xABCDEF), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(0x08801000), RunStatus::Completed);
    EXPECT_EQ(eng.state().offsetAddr, 0x08801000u);
    EXPECT_EQ(eng.state().AC_rgb(), 0xABCDEFu);
}

TEST_F(EngineTest, OffsetCommandShiftsByEightBits) {
    put(kList, {W(GE_CMD_OFFSET, 0x000010), W(GE_CMD_BASE, 0x080000), W(GE_CMD_VADR, 0x800000), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().offsetAddr, 0x1000u);
    EXPECT_EQ(eng.state().vertexAddr, 0x08801000u);
}

TEST_F(EngineTest, JumpSkipsCommands) {
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_JUMP, 0x800010), W(GE_CMD_AC, 1), W(GE_CMD_AA, 2),
                W(GE_CMD_MAA, 3), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().AC_rgb(), 0u);
    EXPECT_EQ(eng.state().AA_alpha(), 0u);
    EXPECT_EQ(eng.state().MAA_alpha(), 3u);
}

TEST_F(EngineTest, CallNestsTwoLevelsAndRetRestoresOffset) {
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_CALL, 0x810000), W(GE_CMD_MAA, 7), W(GE_CMD_FINISH), W(GE_CMD_END)});
    // level 1 sets OFFSET, calls level 2, returns
    put(0x08810000, {W(GE_CMD_OFFSET, 0x000001), W(GE_CMD_CALL, 0x81FF00), W(GE_CMD_AA, 5), W(GE_CMD_RET)});
    // level 2 (0x0881FF00 + OFFSET 0x100 = 0x08820000)
    put(0x08820000, {W(GE_CMD_AC, 0x42), W(GE_CMD_RET)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 0x42u);
    EXPECT_EQ(eng.state().AA_alpha(), 5u);
    EXPECT_EQ(eng.state().MAA_alpha(), 7u);
    EXPECT_EQ(eng.state().offsetAddr, 0u);  // restored by the outer RET
    EXPECT_EQ(eng.list().callDepth, 0u);
}

TEST_F(EngineTest, ThirdCallLevelIsAnError) {
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_CALL, 0x810000)});
    put(0x08810000, {W(GE_CMD_CALL, 0x820000)});
    put(0x08820000, {W(GE_CMD_CALL, 0x830000)});
    put(0x08830000, {W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Error);
    EXPECT_EQ(eng.lastError(), GeError::CallDepth);
    EXPECT_EQ(ev.log.back(), "error call depth exceeded");
}

TEST_F(EngineTest, RetWithEmptyStackIsIgnored) {
    put(kList, {W(GE_CMD_RET), W(GE_CMD_AC, 9), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 9u);
}

TEST_F(EngineTest, StallPausesExactlyAtTheAddressAndResumes) {
    put(kList, {W(GE_CMD_AC, 1), W(GE_CMD_AA, 2), W(GE_CMD_MAA, 3), W(GE_CMD_FINISH), W(GE_CMD_END)});
    eng.startList(kList, kList + 8);
    EXPECT_EQ(eng.run(), RunStatus::Stalled);
    EXPECT_EQ(eng.list().pc, kList + 8);
    EXPECT_EQ(eng.state().AA_alpha(), 2u);
    EXPECT_EQ(eng.state().MAA_alpha(), 0u);
    EXPECT_EQ(eng.run(), RunStatus::Stalled);  // nothing moves until the stall does
    eng.setStall(kList + 12);
    EXPECT_EQ(eng.run(), RunStatus::Stalled);
    EXPECT_EQ(eng.state().MAA_alpha(), 3u);
    eng.setStall(0);
    EXPECT_EQ(eng.run(), RunStatus::Completed);
}

TEST_F(EngineTest, BudgetStopsAndContinues) {
    put(kList, {W(GE_CMD_AC, 1), W(GE_CMD_AA, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
    eng.startList(kList, 0);
    EXPECT_EQ(eng.run(1), RunStatus::Budget);
    EXPECT_EQ(eng.list().pc, kList + 4);
    EXPECT_EQ(eng.run(), RunStatus::Completed);
}

TEST_F(EngineTest, PauseRequestAndResume) {
    put(kList, {W(GE_CMD_AC, 1), W(GE_CMD_AA, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
    eng.startList(kList, 0);
    eng.run(1);
    eng.requestPause();
    EXPECT_EQ(eng.run(), RunStatus::Paused);
    EXPECT_EQ(eng.run(), RunStatus::Paused);
    eng.resume();
    EXPECT_EQ(eng.run(), RunStatus::Completed);
}

TEST_F(EngineTest, BadPcIsAnErrorNotACrash) {
    EXPECT_EQ(runAt(0x01000000), RunStatus::Error);
    EXPECT_EQ(eng.lastError(), GeError::BadListAddress);
    put(kList, {W(GE_CMD_BASE, 0x0F0000), W(GE_CMD_JUMP, 0xFFFFFC)});
    EXPECT_EQ(runAt(kList), RunStatus::Error);
    EXPECT_EQ(eng.lastError(), GeError::BadJumpTarget);
}

TEST_F(EngineTest, UnknownOpcodesAreNoOps) {
    put(kList, {W(0x03, 0x123456), W(0xFF, 1), W(0xD1, 5), W(GE_CMD_AC, 4), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.stats().unknownCommands, 3u);
    EXPECT_EQ(eng.state().AC_rgb(), 4u);
}

// ---- SIGNAL + END behaviours (ge-rules.md §4.4) ----

TEST_F(EngineTest, SignalHandlerCallsListenerAndContinues) {
    put(kList, {W(GE_CMD_SIGNAL, 0x020077), W(GE_CMD_END, 0x99), W(GE_CMD_AC, 1), W(GE_CMD_FINISH, 3), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    ASSERT_GE(ev.log.size(), 1u);
    EXPECT_EQ(ev.log[0], "signal 2 119 153");
    EXPECT_EQ(eng.state().AC_rgb(), 1u);
    EXPECT_EQ(ev.log.back(), "finish 3");
}

TEST_F(EngineTest, SignalJumpIsAbsolute) {
    // 0x10: PC = (SIGNAL bits 15..0 << 16) | END bits 15..0
    put(kList, {W(GE_CMD_SIGNAL, 0x100880), W(GE_CMD_END, 0x2000), W(GE_CMD_AC, 1)});
    put(0x08802000, {W(GE_CMD_AA, 6), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 0u);
    EXPECT_EQ(eng.state().AA_alpha(), 6u);
}

TEST_F(EngineTest, SignalCallAndReturnRestoreBaseAndOffset) {
    put(kList, {W(GE_CMD_BASE, 0x050000), W(GE_CMD_SIGNAL, 0x110880), W(GE_CMD_END, 0x3000), W(GE_CMD_MAA, 8),
                W(GE_CMD_FINISH), W(GE_CMD_END)});
    put(0x08803000, {W(GE_CMD_BASE, 0x090000), W(GE_CMD_OFFSET, 0x000100), W(GE_CMD_AC, 2), W(GE_CMD_SIGNAL, 0x120000),
                     W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 2u);
    EXPECT_EQ(eng.state().MAA_alpha(), 8u);
    EXPECT_EQ(eng.state().BASE_high(), 0x05u);  // BASE restored by the signal RET
    EXPECT_EQ(eng.state().offsetAddr, 0u);
}

TEST_F(EngineTest, SignalRelativeJumpIsFromTheSignalAddress) {
    // 0x13 RJUMP: target = address of SIGNAL + data. SIGNAL at kList+4, data 0x100 → kList+0x104.
    put(kList, {W(GE_CMD_NOP), W(GE_CMD_SIGNAL, 0x130000), W(GE_CMD_END, 0x0100), W(GE_CMD_AC, 1)});
    put(kList + 0x104, {W(GE_CMD_AA, 4), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 0u);
    EXPECT_EQ(eng.state().AA_alpha(), 4u);
}

TEST_F(EngineTest, SignalOffsetJumpAddsOffset) {
    // 0x15 OJUMP: data + OFFSET (ORIGIN at kList → OFFSET = kList).
    put(kList, {W(GE_CMD_ORIGIN), W(GE_CMD_SIGNAL, 0x150000), W(GE_CMD_END, 0x0200)});
    put(kList + 0x200, {W(GE_CMD_AA, 9), W(GE_CMD_FINISH), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AA_alpha(), 9u);
}

TEST_F(EngineTest, SignalPauseTakesEffectAtFinish) {
    // sceGuSignal(GU_SIGNAL_PAUSE, id): SIGNAL 0x03, END, FINISH, END.
    put(kList, {W(GE_CMD_SIGNAL, 0x030042), W(GE_CMD_END, 0x7), W(GE_CMD_FINISH, 1), W(GE_CMD_END), W(GE_CMD_AC, 5),
                W(GE_CMD_FINISH, 2), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Paused);
    EXPECT_EQ(ev.log.back(), "signal 3 66 7");
    EXPECT_EQ(eng.state().AC_rgb(), 0u);
    eng.resume();
    EXPECT_EQ(eng.run(), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 5u);
    EXPECT_EQ(ev.log.back(), "finish 2");
}

TEST_F(EngineTest, SignalSyncResumesAtFinishWithoutCallback) {
    put(kList, {W(GE_CMD_SIGNAL, 0x080000), W(GE_CMD_END), W(GE_CMD_FINISH, 1), W(GE_CMD_END), W(GE_CMD_AC, 5),
                W(GE_CMD_FINISH, 2), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Completed);
    EXPECT_EQ(eng.state().AC_rgb(), 5u);
    for (auto& e : ev.log) EXPECT_NE(e, "finish 1");
}

TEST_F(EngineTest, SignalRetWithEmptyStackIsAnError) {
    put(kList, {W(GE_CMD_SIGNAL, 0x120000), W(GE_CMD_END)});
    EXPECT_EQ(runAt(kList), RunStatus::Error);
    EXPECT_EQ(eng.lastError(), GeError::SignalStack);
}

TEST_F(EngineTest, SignalRelativeTextureAddress) {
    // 0x21 RTBP1: TBP1/TBW1 from SIGNAL address + data, width from END bits 23..16.
    put(kList, {W(GE_CMD_SIGNAL, 0x210000), W(GE_CMD_END, 0x401000), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().textureAddr(1), kList + 0x1000);
    EXPECT_EQ(eng.state().TBW_width(1), 0x40u);
}

// ---- Draws and data ----

TEST_F(EngineTest, PrimAdvancesVertexPointerAndContinues) {
    // VTYPE: s16 position (6 bytes), 8888 colour (4, align 4) → size 12.
    const u32 vtype = (7 << 2) | (2 << 7);
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_VADR, 0x900000), W(GE_CMD_VTYPE, vtype), W(GE_CMD_PRIM, (3 << 16) | 6),
                W(GE_CMD_PRIM, (7 << 16) | 3), W(GE_CMD_PRIM, (4 << 16) | 0), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(rec.prims.size(), 2u);  // count 0 draws nothing
    EXPECT_EQ(rec.prims[0].prim, GE_PRIM_TRIANGLES);
    EXPECT_EQ(rec.prims[0].vertexAddr, 0x08900000u);
    EXPECT_FALSE(rec.prims[0].continuation);
    EXPECT_EQ(rec.prims[1].prim, GE_PRIM_TRIANGLES);
    EXPECT_TRUE(rec.prims[1].continuation);
    EXPECT_EQ(rec.prims[1].vertexAddr, 0x08900000u + 6 * 12);
    EXPECT_EQ(eng.state().vertexAddr, 0x08900000u + 9 * 12);
}

TEST_F(EngineTest, IndexedPrimAdvancesIndexPointerOnly) {
    const u32 vtype = (2 << 7) | (2 << 11);  // s16 position, u16 indices
    put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_VADR, 0x900000), W(GE_CMD_IADR, 0x910000), W(GE_CMD_VTYPE, vtype),
                W(GE_CMD_PRIM, (3 << 16) | 3), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().vertexAddr, 0x08900000u);
    EXPECT_EQ(eng.state().indexAddr, 0x08910006u);
}

TEST_F(EngineTest, PrimTypeEightActsAsPoints) {
    put(kList, {W(GE_CMD_VTYPE, 2 << 7), W(GE_CMD_PRIM, (8 << 16) | 1), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(rec.prims.size(), 1u);
    EXPECT_EQ(rec.prims[0].prim, GE_PRIM_POINTS);
}

TEST_F(EngineTest, PatchPacketCarriesKnotsAndDivisions) {
    put(kList, {W(GE_CMD_VTYPE, 3 << 7), W(GE_CMD_DIVIDE, (0 << 8) | 0x84), W(GE_CMD_PPM, 1), W(GE_CMD_PFACE, 1),
                W(GE_CMD_SPLINE, (2 << 18) | (1 << 16) | (5 << 8) | 4), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(rec.patches.size(), 1u);
    const PatchPacket& p = rec.patches[0];
    EXPECT_TRUE(p.spline);
    EXPECT_EQ(p.ucount, 4u);
    EXPECT_EQ(p.vcount, 5u);
    EXPECT_EQ(p.uknot, 1u);
    EXPECT_EQ(p.vknot, 2u);
    EXPECT_EQ(p.divU, 4u);  // 7 bits read
    EXPECT_EQ(p.divV, 1u);  // 0 → 1
    EXPECT_EQ(p.patchPrim, 1u);
    EXPECT_TRUE(p.reverseFace);
}

TEST_F(EngineTest, MatrixUploadCountsAndDropsOverflow) {
    std::vector<u32> words = {W(GE_CMD_WORLDN, 0)};
    for (int i = 0; i < 13; ++i) words.push_back(W(GE_CMD_WORLDD, toFloat24(float(i + 1))));
    words.push_back(W(GE_CMD_BONEN, 12));
    words.push_back(W(GE_CMD_BONED, toFloat24(-2.5f)));
    words.push_back(W(GE_CMD_FINISH));
    words.push_back(W(GE_CMD_END));
    for (size_t i = 0; i < words.size(); ++i) mem.write32(kList + u32(4 * i), words[i]);
    runAt(kList);
    for (int i = 0; i < 12; ++i) EXPECT_EQ(eng.state().world[i], float(i + 1));
    EXPECT_EQ(eng.state().worldNum, 13u);
    EXPECT_EQ(eng.state().view[0], 0.0f);  // overflow does not spill into the view matrix
    EXPECT_EQ(eng.state().bone[12], -2.5f);
    EXPECT_EQ(eng.state().boneNum, 13u);
}

// What sceGeGetMtx reads after pspautotests gpu/ge/get's uploads (values a PSP printed): 100
// bone words (96-99 run into the world words, rewritten after), 16 world and 16 view words (12-15
// run into the next matrix), 20 projection words (16-19 wrap onto 0-3), 16 texgen words (12-15
// dropped). Rendering keeps only each matrix's own words.
TEST_F(EngineTest, ReadBackMatrixWordsOverflowAsOnAPsp) {
    std::vector<u32> words = {W(GE_CMD_BONEN, 0)};
    for (u32 i = 0; i < 100; ++i) words.push_back(W(GE_CMD_BONED, i));
    const u8 ports[4][2] = {{GE_CMD_WORLDN, GE_CMD_WORLDD}, {GE_CMD_VIEWN, GE_CMD_VIEWD}, {GE_CMD_PROJN, GE_CMD_PROJD}, {GE_CMD_TGENN, GE_CMD_TGEND}};
    for (int m = 0; m < 4; ++m) {
        words.push_back(W(ports[m][0], 0));
        for (u32 i = 0; i < (m == 2 ? 20u : 16u); ++i) words.push_back(W(ports[m][1], i));
    }
    words.push_back(W(GE_CMD_FINISH));
    words.push_back(W(GE_CMD_END));
    for (size_t i = 0; i < words.size(); ++i) mem.write32(kList + u32(4 * i), words[i]);
    runAt(kList);
    const GeState& st = eng.state();
    for (u32 i = 0; i < 96; ++i) EXPECT_EQ(st.visibleMtx[i], i) << "bone " << i;
    for (u32 i = 0; i < 12; ++i) {
        EXPECT_EQ(st.visibleMtx[96 + i], i) << "world " << i;
        EXPECT_EQ(st.visibleMtx[108 + i], i) << "view " << i;
        EXPECT_EQ(st.visibleMtx[136 + i], i) << "tgen " << i;
    }
    for (u32 i = 0; i < 4; ++i) EXPECT_EQ(st.visibleMtx[120 + i], 16 + i) << "proj " << i;
    for (u32 i = 4; i < 16; ++i) EXPECT_EQ(st.visibleMtx[120 + i], i) << "proj " << i;
    EXPECT_EQ(st.proj[0], float24(0));  // drawn with the first 16 words only
    EXPECT_EQ(st.projNum, 20u);
}

TEST_F(EngineTest, ClutLoadCopiesBlocks) {
    for (u32 i = 0; i < 1024; ++i) mem.write8(0x08900000 + i, u8(i * 7));
    put(kList, {W(GE_CMD_CBW, 0x080000), W(GE_CMD_CBP, 0x900000), W(GE_CMD_CLOAD, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(rec.clutLoads, 1);
    EXPECT_EQ(eng.state().clutLoadedBytes, 64u);
    EXPECT_EQ(eng.state().clut[63], u8(63 * 7));
    EXPECT_EQ(eng.state().clut[64], 0u);
    put(kList, {W(GE_CMD_CLOAD, 0x40), W(GE_CMD_FINISH), W(GE_CMD_END)});  // 0x40 = 64 blocks
    runAt(kList);
    EXPECT_EQ(eng.state().clutLoadedBytes, 1024u);
    EXPECT_EQ(eng.state().clut[1023], u8(1023 * 7));
}

// Palette bytes from outside valid memory load as zero, not as what the palette held before
// (pspautotests gpu/clut/address "Outside VRAM"; the engine still counts it as a bad access).
TEST_F(EngineTest, ClutLoadPastValidMemoryLoadsZeros) {
    for (u32 i = 0; i < 64; ++i) mem.write8(0x08900000 + i, u8(0x80 + i));
    put(kList, {W(GE_CMD_CBW, 0x080000), W(GE_CMD_CBP, 0x900000), W(GE_CMD_CLOAD, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(eng.state().clut[0], 0x80u);
    // The last 16 bytes of VRAM's mirrors, then 48 bytes past them.
    for (u32 i = 0; i < 16; ++i) mem.write8(0x047FFFF0 + i, u8(0x11 * (i / 4 + 1)));
    put(kList, {W(GE_CMD_CBW, 0x040000), W(GE_CMD_CBP, 0x7FFFF0), W(GE_CMD_CLOAD, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.state().clut[0], 0x11u);
    EXPECT_EQ(eng.state().clut[15], 0x44u);
    for (u32 i = 16; i < 64; ++i) EXPECT_EQ(eng.state().clut[i], 0u) << i;
    // Entirely past the mirrors: all zero.
    put(kList, {W(GE_CMD_CBW, 0x040000), W(GE_CMD_CBP, 0x800010), W(GE_CMD_CLOAD, 1), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    for (u32 i = 0; i < 32; ++i) EXPECT_EQ(eng.state().clut[i], 0u) << i;
}

TEST_F(EngineTest, TransferPacketIsResolved) {
    put(kList, {W(GE_CMD_XBP1, 0x900000), W(GE_CMD_XBW1, 0x080000 | 512), W(GE_CMD_XBP2, 0x088000),
                W(GE_CMD_XBW2, 0x040000 | 512), W(GE_CMD_XPOS1, (3 << 10) | 2), W(GE_CMD_XPOS2, (5 << 10) | 4),
                W(GE_CMD_XSIZE, (15 << 10) | 31), W(GE_CMD_XSTART, 1), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(rec.transfers.size(), 1u);
    const TransferPacket& t = rec.transfers[0];
    EXPECT_EQ(t.src, 0x08900000u);
    EXPECT_EQ(t.dst, 0x04088000u);
    EXPECT_EQ(t.srcStride, 512u);
    EXPECT_EQ(t.srcX, 2u);
    EXPECT_EQ(t.srcY, 3u);
    EXPECT_EQ(t.dstX, 4u);
    EXPECT_EQ(t.dstY, 5u);
    EXPECT_EQ(t.width, 32u);
    EXPECT_EQ(t.height, 16u);
    EXPECT_EQ(t.bpp, 4u);
}

// pspautotests gpu/transfer/invalid on a PSP: a base address at 0x04800000 (one past the last
// mirror) copies from / to the start of VRAM; 0x047FFFF0 stays as it is (its rows wrap instead).
TEST_F(EngineTest, TransferBaseJustAboveTheMirrorsDropsBit23) {
    put(kList, {W(GE_CMD_XBP1, 0x800000), W(GE_CMD_XBW1, 0x040000 | 512), W(GE_CMD_XBP2, 0x100000),
                W(GE_CMD_XBW2, 0x040000 | 512), W(GE_CMD_XPOS1, 0), W(GE_CMD_XPOS2, 0),
                W(GE_CMD_XSIZE, (15 << 10) | 511), W(GE_CMD_XSTART, 0), W(GE_CMD_XBP1, 0x100000),
                W(GE_CMD_XBP2, 0x800000), W(GE_CMD_XSTART, 0), W(GE_CMD_XBP1, 0x7FFFF0), W(GE_CMD_XBW1, 0x040000 | 512),
                W(GE_CMD_XSTART, 0), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    ASSERT_EQ(rec.transfers.size(), 3u);
    EXPECT_EQ(rec.transfers[0].src, 0x04000000u);
    EXPECT_EQ(rec.transfers[0].dst, 0x04100000u);
    EXPECT_EQ(rec.transfers[1].src, 0x04100000u);
    EXPECT_EQ(rec.transfers[1].dst, 0x04000000u);
    EXPECT_EQ(rec.transfers[2].src, 0x047FFFF0u);
}

TEST_F(EngineTest, DirtyGroupsOnlyOnChange) {
    put(kList, {W(GE_CMD_ATEST, 0x123), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    eng.takeDirty();
    put(kList, {W(GE_CMD_ATEST, 0x123), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_EQ(eng.takeDirty() & DIRTY_FRAGMENT, 0u);
    put(kList, {W(GE_CMD_ATEST, 0x124), W(GE_CMD_FINISH), W(GE_CMD_END)});
    runAt(kList);
    EXPECT_NE(eng.takeDirty() & DIRTY_FRAGMENT, 0u);
}

// ---- BBOX / BJUMP (manual §11.1) ----

class BBoxTest : public EngineTest {
protected:
    void SetUp() override {
        EngineTest::SetUp();
        GeState& st = eng.state();
        for (float* m : {st.world, st.view}) {
            std::fill(m, m + 12, 0.0f);
            m[0] = m[4] = m[8] = 1;
        }
        std::fill(st.proj, st.proj + 16, 0.0f);
        st.proj[0] = st.proj[5] = st.proj[10] = st.proj[15] = 1;
        // Viewport 480x272 centred at 2048, offset (2048-240, 2048-136); scissor/region full screen.
        const std::pair<u8, u32> regs[] = {
            {GE_CMD_SX, toFloat24(240)}, {GE_CMD_SY, toFloat24(-136)}, {GE_CMD_TX, toFloat24(2048)},
            {GE_CMD_TY, toFloat24(2048)}, {GE_CMD_OFFSETX, (2048 - 240) << 4}, {GE_CMD_OFFSETY, (2048 - 136) << 4},
            {GE_CMD_SCISSOR1, 0}, {GE_CMD_SCISSOR2, (271 << 10) | 479}, {GE_CMD_REGION1, 0},
            {GE_CMD_REGION2, (271 << 10) | 479}, {GE_CMD_VTYPE, 3 << 7}};
        for (auto [op, v] : regs) st.regs[op] = W(op, v);
    }
    void vertices(std::initializer_list<float> xyz) {
        u32 a = 0x08900000;
        for (float f : xyz) {
            u32 b;
            std::memcpy(&b, &f, 4);
            mem.write32(a, b);
            a += 4;
        }
    }
    bool taken(u32 count) {
        put(kList, {W(GE_CMD_BASE, 0x080000), W(GE_CMD_VADR, 0x900000), W(GE_CMD_BBOX, count), W(GE_CMD_BJUMP, 0x800100),
                    W(GE_CMD_AC, 1), W(GE_CMD_FINISH), W(GE_CMD_END)});
        put(kList + 0x100, {W(GE_CMD_AC, 2), W(GE_CMD_FINISH), W(GE_CMD_END)});
        runAt(kList);
        return eng.state().AC_rgb() == 2;
    }
};

TEST_F(BBoxTest, InsideVolumeDoesNotJump) {
    vertices({-0.5f, -0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    EXPECT_FALSE(taken(2));
    EXPECT_TRUE(eng.list().bflg);
    EXPECT_EQ(eng.state().vertexAddr, 0x08900000u + 2 * 12);  // pointer advanced like a draw
}

TEST_F(BBoxTest, VolumeEntirelyLeftOfTheScreenJumps) {
    vertices({-3.0f, -0.5f, 0.5f, -2.5f, 0.5f, 0.5f});
    EXPECT_TRUE(taken(2));
}

TEST_F(BBoxTest, VolumeStraddlingTheEdgeDoesNotJump) {
    vertices({-3.0f, 0.0f, 0.5f, 0.5f, 0.0f, 0.5f});
    EXPECT_FALSE(taken(2));
}

TEST_F(BBoxTest, ZeroCountJumps) { EXPECT_TRUE(taken(0)); }

}  // namespace
