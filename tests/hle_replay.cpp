// SPDX-License-Identifier: MIT
// Dump replay (docs/ppdmp.md §6) on the real frametests, and robustness of the replay against
// corrupted dumps (random words, record types, sizes and pointers): never a crash or a hang.
#include <gtest/gtest.h>

#include "tests/test_util.h"

#include <chrono>
#include <filesystem>
#include <random>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {


struct CountingRenderer : NullRenderer {
    u64 flushes = 0;
    void flushToMemory() override { ++flushes; }
};

TEST(Replay, AllFrametestsReplayCleanly) {
    auto files = frametestDumps();
    if (files.empty()) GTEST_SKIP() << "frametests not found at " << GE2GL_FRAMETESTS_DIR;
    EXPECT_EQ(files.size(), 20u);
    for (const auto& f : files) {
        SCOPED_TRACE(f);
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(f, d, err)) << err;
        dump::DumpSummary s = dump::summarize(d);
        Memory mem;
        CountingRenderer r;
        GeEngine eng(mem, &r);
        dump::ReplayResult res;
        ASSERT_TRUE(dump::replayDump(d, eng, {}, res, err)) << err;
        EXPECT_EQ(res.listErrors, 0u) << res.warning;
        EXPECT_TRUE(res.hasDisplay);
        EXPECT_EQ(res.draws, s.draws);
        EXPECT_EQ(eng.stats().prims + eng.stats().patches, r.prims + r.patches);
        // Every recorded draw with vertices reaches the backend (count-0 kicks draw nothing).
        EXPECT_LE(r.prims + r.patches, s.draws);
        EXPECT_GT(r.prims + r.patches, s.draws / 2);
        EXPECT_EQ(r.flushes, 1u);
        EXPECT_TRUE(Memory::isVram(res.displayAddr));
    }
}

TEST(Replay, ReplayEndStopsAfterTheNthDraw) {
    auto files = frametestDumps();
    if (files.empty()) GTEST_SKIP() << "frametests not found";
    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(files[0], d, err)) << err;
    Memory mem;
    NullRenderer r;
    GeEngine eng(mem, &r);
    dump::ReplayResult res;
    dump::ReplayOptions opt;
    opt.replayEnd = 5;
    ASSERT_TRUE(dump::replayDump(d, eng, opt, res, err)) << err;
    EXPECT_EQ(res.draws, 5u);
    EXPECT_LE(r.prims + r.patches, 5u);
}

TEST(Replay, MissingInitIsAnError) {
    dump::Dump d;
    d.records.push_back({dump::REGISTERS, 0, 0});
    Memory mem(1u << 20);
    GeEngine eng(mem);
    dump::ReplayResult res;
    std::string err;
    EXPECT_FALSE(dump::replayDump(d, eng, {}, res, err));
    EXPECT_FALSE(err.empty());
}

// A first record INIT of size 0 whose pointer lies outside an (empty) push buffer made
// the player memcpy from a null pointer; it is skipped with a warning.
TEST(Replay, ZeroSizeInitOutsideThePushBufferIsSkipped) {
    dump::Dump d;
    d.records.push_back({dump::INIT, 0, 0x1000});
    d.records.push_back({dump::REGISTERS, 0, 0x2000});
    Memory mem(1u << 20);
    GeEngine eng(mem);
    dump::ReplayResult res;
    std::string err;
    EXPECT_TRUE(dump::replayDump(d, eng, {}, res, err)) << err;
    EXPECT_NE(res.warning.find("outside the push buffer"), std::string::npos) << res.warning;
}

// One 4 MiB REGISTERS block behind 200,000 records (`info` once took minutes on it): summarize
// scans a shared block once and multiplies.
TEST(Replay, SummarizeCountsASharedBlockOnce) {
    dump::Dump d;
    d.pushbuf.assign(4u << 20, 0);
    for (size_t i = 0; i < d.pushbuf.size(); i += 4) d.pushbuf[i + 3] = u8(GE_CMD_PRIM);
    d.records.push_back({dump::INIT, 0, 0});
    for (int i = 0; i < 200000; ++i) d.records.push_back({dump::REGISTERS, 4u << 20, 0});
    const auto t0 = std::chrono::steady_clock::now();
    const dump::DumpSummary s = dump::summarize(d);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
    EXPECT_EQ(s.commands, 200000ull << 20);
    EXPECT_EQ(s.prims, 200000ull << 20);
}

TEST(Replay, UnknownRecordTypeIsAnError) {
    dump::Dump d;
    d.pushbuf.assign(2048, 0);
    d.records.push_back({dump::INIT, 2048, 0});
    d.records.push_back({0x0C, 0, 0});
    Memory mem;
    GeEngine eng(mem);
    dump::ReplayResult res;
    std::string err;
    EXPECT_FALSE(dump::replayDump(d, eng, {}, res, err));
    EXPECT_NE(err.find("unknown record type"), std::string::npos);
}

// PPSSPP's player maps the push buffer in 1 MiB slabs, so the bytes after a texture's recorded
// size are the dump's next bytes (NFS Carbon reads DXT rows past its recorded size); the player
// keeps them readable after texture payloads, up to the slab's end.
TEST(Replay, TexturePayloadsKeepTheFollowingPushBufferBytes) {
    dump::Dump d;
    d.pushbuf.assign(2048, 0);  // INIT context: all zero
    for (u32 i = 0; i < 64; ++i) d.pushbuf.push_back(u8(0x40 + i));
    d.records.push_back({dump::INIT, 2048, 0});
    d.records.push_back({dump::TEXTURE0, 16, 2048});  // 16 bytes recorded, 48 more follow
    const u32 regs = u32(d.pushbuf.size());
    for (u8 b : {0x00, 0x00, 0x00, 0x00}) d.pushbuf.push_back(b);  // one NOP word
    d.records.push_back({dump::REGISTERS, 4, regs});
    Memory mem;
    GeEngine eng(mem);
    dump::ReplayResult res;
    std::string err;
    ASSERT_TRUE(dump::replayDump(d, eng, {}, res, err)) << err;
    const u32 tex = eng.state().textureAddr(0);
    ASSERT_NE(mem.ptr(tex, 64), nullptr) << std::hex << tex;
    for (u32 i = 0; i < 64; ++i) EXPECT_EQ(mem.read8(tex + i), 0x40 + i) << i;
}

TEST(Replay, CorruptedDumpsNeverCrashOrHang) {
    auto files = frametestDumps();
    if (files.empty()) GTEST_SKIP() << "frametests not found";
    std::mt19937 rng(12345);
    for (const auto& f : files) {
        SCOPED_TRACE(f);
        dump::Dump orig;
        std::string err;
        ASSERT_TRUE(dump::loadDump(f, orig, err)) << err;
        for (int variant = 0; variant < 3; ++variant) {
            dump::Dump d = orig;
            mutateDump(d, rng, 40);
            Memory mem;
            NullRenderer r;
            GeEngine eng(mem, &r);
            dump::ReplayResult res;
            std::string e2;
            bool ok = dump::replayDump(d, eng, {}, res, e2);
            if (!ok) {
                EXPECT_FALSE(e2.empty());
            }
        }
        // Truncated record lists replay what is there.
        dump::Dump t = orig;
        t.records.resize(t.records.size() / 3);
        Memory mem;
        GeEngine eng(mem);
        dump::ReplayResult res;
        std::string e3;
        EXPECT_TRUE(dump::replayDump(t, eng, {}, res, e3)) << e3;
    }
}

}  // namespace
