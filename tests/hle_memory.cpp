// SPDX-License-Identifier: MIT
// Emulated memory as storage: reserved, not written (pages zero on first touch), and reusable
// through clear() (no cost proportional to the 64 MiB address space per replay).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <vector>

#include "hle/memory.h"

using namespace ge;

namespace {

// Resident set of this process in bytes (/proc/self/statm, second field), 0 when unreadable.
u64 residentBytes() {
    std::ifstream f("/proc/self/statm");
    u64 size = 0, resident = 0;
    if (!(f >> size >> resident)) return 0;
    return resident * u64(::sysconf(_SC_PAGESIZE));
}

// Addresses spread over every region: each 64 KiB step of RAM and VRAM (all four VRAM views),
// both ends of each region, the scratchpad.
std::vector<u32> sampleAddresses(const Memory& mem) {
    std::vector<u32> a;
    for (u32 off = 0; off < mem.ramSize(); off += 0x10000) a.push_back(Memory::kRamBase + off);
    a.push_back(Memory::kRamBase + mem.ramSize() - 4);
    for (u32 off = 0; off < Memory::kVramMirrorsEnd - Memory::kVramBase; off += 0x10000) a.push_back(Memory::kVramBase + off);
    a.push_back(Memory::kVramBase + Memory::kVramSize - 4);
    a.push_back(Memory::kVramMirrorsEnd - 4);
    a.push_back(Memory::kScratchBase);
    a.push_back(Memory::kScratchBase + Memory::kScratchSize - 4);
    return a;
}

constexpr u64 kMiB = 1u << 20;

TEST(MemoryStorage, FreshMemoryReadsZeroEverywhere) {
    Memory mem;
    ASSERT_EQ(mem.ramSize(), Memory::kDefaultRamSize);
    for (u32 a : sampleAddresses(mem)) ASSERT_EQ(mem.read32(a), 0u) << std::hex << a;
    // Whole regions too, not only the samples.
    const u8* ram = mem.ram();
    for (u32 i = 0; i < mem.ramSize(); i += 4093) ASSERT_EQ(ram[i], 0) << i;
    for (u32 i = 0; i < Memory::kVramSize; ++i) ASSERT_EQ(mem.vram()[i], 0) << i;
    EXPECT_EQ(mem.badAccesses(), 0u);
    EXPECT_EQ(mem.edramTranslation(), 0x400u);
}

TEST(MemoryStorage, ConstructionCommitsNoPages) {
    // 64 MiB RAM + 2 MiB VRAM: eagerly zero-filled storage would add all of it to the resident
    // set; reserved storage adds next to nothing until written.
    const u64 before = residentBytes();
    ASSERT_GT(before, 0u) << "/proc/self/statm unreadable";
    std::vector<std::unique_ptr<Memory>> mems;
    for (int i = 0; i < 4; ++i) mems.push_back(std::make_unique<Memory>());
    const u64 after = residentBytes();
    EXPECT_LT(after, before + 8 * kMiB) << "four Memory objects made " << (after - before) / kMiB << " MiB resident";
}

TEST(MemoryStorage, WritesWorkAcrossRamVramAndScratchpad) {
    Memory mem;
    const std::vector<u32> addrs = sampleAddresses(mem);
    for (size_t i = 0; i < addrs.size(); ++i) mem.write32(addrs[i], u32(0x9E3779B9u * (i + 1)));
    for (size_t i = 0; i < addrs.size(); ++i) {
        const u32 a = addrs[i];
        // VRAM views alias the same 2 MiB: the last write to an offset wins.
        u32 expect = u32(0x9E3779B9u * (i + 1));
        if (Memory::isVram(a))
            for (size_t j = i + 1; j < addrs.size(); ++j)
                if (Memory::isVram(addrs[j]) &&
                    ((addrs[j] - Memory::kVramBase) & (Memory::kVramSize - 1)) == ((a - Memory::kVramBase) & (Memory::kVramSize - 1)))
                    expect = u32(0x9E3779B9u * (j + 1));
        EXPECT_EQ(mem.read32(a), expect) << std::hex << a;
    }
    // Bulk copies and fills at both ends of RAM and VRAM.
    std::vector<u8> block(3 * 4096 + 17, 0xA5);
    ASSERT_TRUE(mem.write(Memory::kRamBase + mem.ramSize() - u32(block.size()), block.data(), u32(block.size())));
    ASSERT_TRUE(mem.fill(Memory::kVramBase, 0x3C, 5 * 4096));
    EXPECT_EQ(mem.read8(Memory::kRamBase + mem.ramSize() - 1), 0xA5);
    EXPECT_EQ(mem.read8(Memory::kVramBase + 5 * 4096 - 1), 0x3C);
    EXPECT_EQ(mem.read8(Memory::kVramBase + 5 * 4096), 0x00);
    // Past the end nothing is written and the access is counted.
    EXPECT_FALSE(mem.write(Memory::kRamBase + mem.ramSize() - 2, block.data(), 4));
    EXPECT_EQ(mem.badAccesses(), 1u);
}

TEST(MemoryStorage, ClearZeroesAgainAndResetsState) {
    Memory mem;
    const std::vector<u32> addrs = sampleAddresses(mem);
    for (u32 a : addrs) mem.write32(a, 0xDEADBEEF);
    const u32 filled = 8 * kMiB;
    ASSERT_TRUE(mem.fill(Memory::kRamBase + 16 * kMiB, 0x77, filled));
    ASSERT_TRUE(mem.setEdramTranslation(0x200));
    mem.read32(0x0C000000);  // wild: counted
    ASSERT_EQ(mem.badAccesses(), 1u);
    const u64 dirty = residentBytes();

    mem.clear();
    // The 8 MiB written went back to the kernel. (Measured before reading: on some kernels a read
    // of an untouched page commits a zeroed page instead of mapping the shared zero page.)
    EXPECT_LT(residentBytes() + 4 * kMiB, dirty) << "clear() kept the written pages resident";
    for (u32 a : addrs) ASSERT_EQ(mem.read32(a), 0u) << std::hex << a;
    for (u32 i = 0; i < filled; i += 4096) ASSERT_EQ(mem.read8(Memory::kRamBase + 16 * kMiB + i), 0) << i;
    for (u32 i = 0; i < Memory::kVramSize; ++i) ASSERT_EQ(mem.vram()[i], 0) << i;
    EXPECT_EQ(mem.edramTranslation(), 0x400u);
    EXPECT_EQ(mem.badAccesses(), 0u);
    EXPECT_EQ(mem.lastBadAddress(), 0u);

    // Usable as new afterwards, including the mirror permutation of the reset translation.
    mem.write32(Memory::kRamBase + 0x100, 0x12345678);
    EXPECT_EQ(mem.read32(Memory::kRamBase + 0x100), 0x12345678u);
    mem.write8(Memory::kVramBase, 0x5A);
    EXPECT_EQ(mem.readMirrored(Memory::kVramBase + 0x600000 + mem.linearToMirror(0, 3)), 0x5A);
}

// keepPagesOnClear (ge2gl bench --warm): clear() zeroes what a replay wrote in place, so the
// pages stay resident for the next replay, and reads give zero as after a plain clear().
TEST(MemoryStorage, ClearCanKeepTheTouchedPagesResident) {
    Memory mem;
    mem.keepPagesOnClear(true);
    const u32 filled = 8 * kMiB;
    ASSERT_TRUE(mem.fill(Memory::kRamBase + 16 * kMiB, 0x77, filled));
    for (u32 i = 0; i < Memory::kVramSize; i += 4096) mem.write8(Memory::kVramBase + i + 5, 0x55);
    const u64 dirty = residentBytes();
    mem.clear();
    EXPECT_GT(residentBytes() + 2 * kMiB, dirty) << "clear() gave the written pages back";
    for (u32 i = 0; i < filled; i += 512) ASSERT_EQ(mem.read8(Memory::kRamBase + 16 * kMiB + i), 0) << i;
    for (u32 i = 0; i < Memory::kVramSize; ++i) ASSERT_EQ(mem.vram()[i], 0) << i;
}

TEST(MemoryStorage, HostAccessRunningOffTheRegionFaults) {
    // Guard pages after RAM and VRAM (and before them): a backend bug that writes past what
    // ptr() granted crashes at once instead of corrupting a neighbour.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    Memory mem(1u << 20);
    EXPECT_DEATH(
        {
            volatile u8* end = mem.ram() + mem.ramSize();
            *end = 1;
        },
        "");
    EXPECT_DEATH(
        {
            volatile u8* end = mem.vram() + Memory::kVramSize;
            *end = 1;
        },
        "");
    EXPECT_DEATH(
        {
            volatile u8* before = mem.ram() - 1;
            *before = 1;
        },
        "");
}

TEST(MemoryStorage, ClearZeroesHostOwnedBuffers) {
    std::vector<u8> ram(1 * kMiB, 0x11), vram(Memory::kVramSize, 0x22);
    Memory mem(ram.data(), u32(ram.size()), vram.data());
    EXPECT_EQ(mem.read8(Memory::kRamBase + 5), 0x11);
    mem.clear();
    EXPECT_EQ(std::count(ram.begin(), ram.end(), 0), std::ptrdiff_t(ram.size()));
    EXPECT_EQ(std::count(vram.begin(), vram.end(), 0), std::ptrdiff_t(vram.size()));
    EXPECT_EQ(mem.ram(), ram.data());  // still the host's buffers
    EXPECT_EQ(mem.vram(), vram.data());
}

}  // namespace
