// SPDX-License-Identifier: MIT
// Replays bounded in emulated GE time (hle/ge_time.h, ReplayOptions::maxGeMs): small
// hostile dumps that loop or make the player copy without end stop at the budget with a warning,
// and the estimate itself adds up as documented.
#include <gtest/gtest.h>

#include <cstring>

#include "authoring/list_builder.h"
#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "hle/ge_time.h"
#include "softmodel/soft_renderer.h"
#include "tests/hostile_dumps.h"

using namespace ge;

namespace {

using namespace hostile;

struct Replay {
    Memory mem;
    std::unique_ptr<Renderer> r;
    GeStats stats;
    dump::ReplayResult res;
    explicit Replay(const dump::Dump& d, double maxGeMs = dump::ReplayOptions::kDefaultMaxGeMs, bool soft = true) {
        soft::SoftOptions so;
        so.threads = 1;
        if (soft) r = soft::createSoftRenderer(mem, so);
        else r = std::make_unique<NullRenderer>();
        GeEngine eng(mem, r.get());
        dump::ReplayOptions opt;
        opt.maxGeMs = maxGeMs;
        std::string err;
        EXPECT_TRUE(dump::replayDump(d, eng, opt, res, err)) << err;
        stats = eng.stats();
    }
};

// A block that draws a full-screen through-mode rectangle and jumps back to its own start: each
// catch-up runs until its command budget, tens of thousands of full-screen rectangles, and the
// next catch-up starts over — minutes of drawing without a budget in GE time.
TEST(ReplayBudget, RectangleLoopStopsAtTheBudget) {
    constexpr double kMs = 10.0;
    Replay r(rectangleLoop(), kMs);
    EXPECT_TRUE(r.res.timeLimitHit);
    EXPECT_NE(r.res.warning.find("GE time budget"), std::string::npos) << r.res.warning;
    // 480·272 pixels at 1/3 cycle + 2 vertices at 20 + 3 commands at 2 a loop.
    const u64 perLoop = getime::pixelCost(480 * 272) + 2 * 20 + 3 * getime::kPerCommand;
    const u64 budget = getime::cyclesFromMs(kMs);
    EXPECT_NEAR(double(r.stats.prims), double(budget / perLoop), 3.0);
    EXPECT_GE(r.res.geCycles, budget);
    EXPECT_LT(r.res.geCycles, budget + 2 * perLoop);
    // The pixels drawn before the cut are there.
    EXPECT_EQ(r.mem.read32(0x04000000 + (100 * 512 + 100) * 4) & 0xFFFFFF, 0xFFFFFFu);
}

// A list that jumps to itself, in many records: each catch-up runs out of commands and the next
// record's catch-up starts the loop again; the budget counts across all of them. Null backend.
TEST(ReplayBudget, SelfJumpStopsAtTheBudget) {
    constexpr double kMs = 5.0;
    Replay r(selfJumps(), kMs, false);
    EXPECT_TRUE(r.res.timeLimitHit);
        // List starts (60 cycles each) take a little of the budget too.
    const double want = double(getime::cyclesFromMs(kMs) / getime::kPerCommand);
    EXPECT_NEAR(double(r.stats.commands), want, want * 0.01);
}

// One 2 MiB FRAMEBUF payload behind thousands of records: the player would copy 2 MiB into
// VRAM for each; its copies are charged (hle/ge_time.h hostCopyCost) and the replay stops.
TEST(ReplayBudget, SharedPayloadCopiesStopAtTheBudget) {
    Replay r(sharedFramebufPayload(), dump::ReplayOptions::kDefaultMaxGeMs, false);
    EXPECT_TRUE(r.res.timeLimitHit);
    const u64 perRecord = getime::hostCopyCost(2u << 20);
    EXPECT_LE(r.res.records, getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs) / perRecord + 3);
    EXPECT_EQ(r.mem.read8(0x04000000), 0x5A);
}

// One 4 MiB REGISTERS payload behind 200,000 records: the player scans the payload for the
// words it rewrites once (the scan is kept by payload offset and size), and each record's copy
// into the list buffer and the GE's run of its words are charged, so the replay stops after a
// few records instead of translating and running 2^38 words.
TEST(ReplayBudget, SharedRegistersPayloadIsScannedOnceAndCharged) {
    Replay r(sharedRegistersPayload(), dump::ReplayOptions::kDefaultMaxGeMs, false);
    EXPECT_TRUE(r.res.timeLimitHit) << r.res.warning;
    EXPECT_EQ(r.res.blockScans, 1u);
    EXPECT_EQ(r.res.scannedBytes, u64(kSharedBytes));
    const u64 budget = getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs);
    // Each record: 1 Mi NOPs run (the block is larger than the list buffer: it is written and
    // run in pieces) and 4 MiB copied.
    const u64 perRecord = (kSharedBytes / 4) * getime::kPerCommand + getime::hostCopyCost(kSharedBytes);
    EXPECT_LE(r.res.records, budget / perRecord + 4);
    EXPECT_LE(r.res.listBytes, (budget / perRecord + 2) * u64(kSharedBytes));
    // The GE ran the words: a block bigger than the list buffer is not dropped piece by piece.
    EXPECT_GE(r.stats.commands, (r.res.records - 4) * (kSharedBytes / 4));
}

// A 192 KiB block behind 200,000 records fits the list buffer; each record wraps the list and
// the GE, already at the buffer's start where the stall address goes, runs none of the later
// ones (as in PPSSPP's player, docs/ppdmp.md §6.2). The player's copies alone must stop the replay.
TEST(ReplayBudget, RegistersCopiesAreChargedWhenTheGeRunsNothing) {
    Replay r(sharedRegistersBlock(), dump::ReplayOptions::kDefaultMaxGeMs, false);
    EXPECT_TRUE(r.res.timeLimitHit) << r.res.warning;
    EXPECT_EQ(r.res.blockScans, 1u);
    const u64 budget = getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs);
    const u64 block = 192u << 10;
    EXPECT_LE(getime::hostCopyCost(r.res.listBytes), budget + getime::hostCopyCost(block));
    EXPECT_LE(r.res.records, budget / getime::hostCopyCost(block) + 4);
    // Only the first record's block runs (the GE stood after the list's first NOP then).
    EXPECT_LT(r.stats.commands, block / 4 + 100);
}

// 65,536 different windows of one 4 MiB block: no record repeats another's payload, so each is
// scanned; the scans are charged like the copies and the replay stops after a few.
TEST(ReplayBudget, DistinctOverlappingRegistersPayloadsAreCharged) {
    Replay r(slidingRegistersPayloads(), dump::ReplayOptions::kDefaultMaxGeMs, false);
    EXPECT_TRUE(r.res.timeLimitHit) << r.res.warning;
    const u64 budget = getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs);
    EXPECT_LE(getime::hostCopyCost(r.res.scannedBytes), budget);
    EXPECT_LE(r.res.blockScans, budget / getime::hostCopyCost(2 * u64(kSharedBytes)) + 4);
}

// The translation of a block found through the kept scan is the translation of a fresh one:
// the same TBW/TBP/BASE rewrites, in order, with the player's state carried across records.
// Blocks of 256 bytes and more are scanned once per payload; smaller ones are walked as they
// are copied, each record (Replayer::kWalkBelowBytes), with the same words in the list.
TEST(ReplayBudget, RepeatedRegistersRecordsTranslateLikeFreshOnes) {
    // One dump repeats a block three times, the other holds three copies of it.
    auto make = [](bool shared, bool large) {
        dump::DumpWriter w = start();
        std::vector<u8> tex(64 * 64 * 4, 0x7F);
        w.texture(0, tex.data(), u32(tex.size()));
        std::vector<u32> block = frameState();
        for (u32 k : {64u, 128u, 64u}) block.push_back(word(GE_CMD_TBW0, k));
        block.push_back(word(GE_CMD_TBP0, 0x123456));
        block.push_back(word(GE_CMD_BASE, 0x080000));
        block.push_back(word(GE_CMD_TBW0 + 1, 32));
        if (large) block.resize(std::max<size_t>(block.size(), 80), word(GE_CMD_NOP, 0));
        else EXPECT_LT(block.size() * 4, 256u);
        w.registers(block);
        dump::Dump d = w.dump();
        for (int i = 0; i < 2; ++i) {
            dump::Record r = d.records.back();
            if (!shared) {
                const std::vector<u8> copy(d.pushbuf.begin() + r.ptr, d.pushbuf.begin() + r.ptr + r.size);
                r.ptr = u32(d.pushbuf.size());
                d.pushbuf.insert(d.pushbuf.end(), copy.begin(), copy.end());
            }
            d.records.push_back(r);
        }
        d.records.push_back(d.records[1]);
        return d;
    };
    for (bool large : {true, false}) {
        SCOPED_TRACE(large ? "kept scan" : "walked");
        Replay shared(make(true, large), dump::ReplayOptions::kDefaultMaxGeMs, false);
        Replay fresh(make(false, large), dump::ReplayOptions::kDefaultMaxGeMs, false);
        EXPECT_EQ(shared.res.blockScans, large ? 1u : 3u);
        EXPECT_EQ(fresh.res.blockScans, 3u);
        EXPECT_EQ(shared.res.listBytes, fresh.res.listBytes);
        // The list buffers hold the same words.
        const u32 n = u32(shared.res.listBytes + 16);
        std::vector<u8> a(n), b(n);
        shared.mem.read(kListBuf, a.data(), n);
        fresh.mem.read(kListBuf, b.data(), n);
        EXPECT_EQ(a, b);
        EXPECT_EQ(shared.stats.commands, fresh.stats.commands);
    }
}

// Every hostile dump, each record type's shared-payload shape among them: the replay ends, and
// the work the player does on its own (copies, scans, list writes) and the commands the GE runs
// stay within the budget, give or take one record.
TEST(ReplayBudget, EveryHostileDumpStaysWithinTheBudget) {
    const u64 budget = getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs);
    // One record may overrun: a payload of up to 8 MiB copied and scanned, a MEMSET over VRAM and
    // its mirrors (8 MiB), a catch-up of a list buffer's worth of commands.
    const u64 slack = getime::hostCopyCost(3 * (8u << 20)) + getime::transferCost(8u << 20) +
                      (kListBufWords + 4096) * getime::kPerCommand;
    for (const auto& h : all()) {
        SCOPED_TRACE(h.name);
        Replay r(h.make(), dump::ReplayOptions::kDefaultMaxGeMs, false);
        const u64 copies = getime::hostCopyCost(r.res.playerBytes + r.res.scannedBytes + r.res.listBytes) +
                           getime::transferCost(r.res.cpuBytes);
        EXPECT_LE(copies, budget + slack);
        EXPECT_LE(r.stats.cycles, budget + slack);
        EXPECT_LE(r.stats.commands, (budget + slack) / getime::kPerCommand);
    }
}

TEST(ReplayBudget, RealFramesStayFarBelowTheDefault) {
    // The project's scenes (the 20 frametests' real frames take at most about 30 ms of GE time,
    // docs/timing.md).
    for (const char* name : {"lit_textured_skinned", "clut_dxt_sprites", "bezier_spline", "blend_stencil_logic",
                             "render_to_texture"}) {
        SCOPED_TRACE(name);
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(std::string(GE2GL_SOURCE_DIR) + "/dumps/" + name + ".ppdmp", d, err)) << err;
        Replay r(d);
        EXPECT_FALSE(r.res.timeLimitHit) << r.res.warning;
        EXPECT_GT(r.res.geCycles, 0u);
        EXPECT_LT(getime::msFromCycles(r.res.geCycles), dump::ReplayOptions::kDefaultMaxGeMs / 5);
    }
}

// One draw can hold more work than the budget: a 57,300-vertex fan of screen-sized triangles is
// cut inside the draw (the engine hands the backend the pixels left, later primitives are
// dropped), and a patch whose tessellation alone overruns the budget is not drawn at all.
TEST(ReplayBudget, HugeDrawsAreCutInsideTheDraw) {
    for (bool patch : {false, true}) {
        SCOPED_TRACE(patch ? "Bezier patch at the tessellation cap" : "57,300-vertex fan");
        Replay r(patch ? patchAtTheCap() : hugeFan());
        EXPECT_TRUE(r.res.timeLimitHit) << r.res.warning;
        const auto* soft = dynamic_cast<const soft::SoftRenderer*>(r.r.get());
        ASSERT_NE(soft, nullptr);
        if (patch) {
            EXPECT_EQ(soft->stats().patches, 0u);  // refused before tessellation
        } else {
            // Triangles of about 240 × 272 pixels: some 1,700 fit in the budget, the rest are dropped.
            const u64 fit = getime::cyclesFromMs(dump::ReplayOptions::kDefaultMaxGeMs) * 3 / (240 * 272);
            EXPECT_LT(soft->stats().primitives, fit * 2);
            EXPECT_GT(soft->stats().budgetDropped, 57298u - fit * 2);
        }
    }
}

TEST(GeTime, EstimateAddsUpAsDocumented) {
    Memory mem;
    NullRenderer nr;
    GeEngine eng(mem, &nr);
    ListBuilder b(&mem);
    b.setVertexType(vt::POS_16 | vt::THROUGH);
    const s16 v[6] = {0, 0, 0, 10, 10, 0};
    b.drawArrayData(GE_PRIM_RECTANGLES, vt::POS_16 | vt::THROUGH, 2, nullptr, v);
    b.copyImage(GE_FORMAT_8888, 0, 0, 8, 4, 64, 0x04000000, 0, 0, 64, 0x04100000);
    b.finish();
    eng.startList(b.placeList(), 0);
    ASSERT_EQ(eng.run(), RunStatus::Completed);
    const GeStats& s = eng.stats();
    const u64 want = getime::kListStart + s.commands * getime::kPerCommand + 2 * 20 /* vertices */ +
                     getime::transferCost(8 * 4 * 4) + getime::kEnd;
    EXPECT_EQ(s.cycles, want);
    // Lighting with two lights and a morphing vertex type cost more per vertex.
    GeState st;
    st.regs[GE_CMD_LTE] = word(GE_CMD_LTE, 1);
    st.regs[GE_CMD_LE0] = word(GE_CMD_LE0, 1);
    st.regs[GE_CMD_LE0 + 2] = word(GE_CMD_LE0 + 2, 1);
    st.regs[GE_CMD_VTYPE] = word(GE_CMD_VTYPE, vt::morphs(3));
    EXPECT_EQ(getime::perVertexCost(st), 20u + 10 + 2 * 7 + 5 * 3);
}

}  // namespace
