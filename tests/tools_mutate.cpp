// SPDX-License-Identifier: MIT
// The mutation fuzzer's mutants (tools/lib/mutate.h, scripts/fuzz_mutate.sh): a seed gives the
// same mutant every time, different seeds give different ones, every kind of mutation is reached,
// and each mutant either loads or is refused with a message.
#include <gtest/gtest.h>

#include <set>

#include "hle/dump/ppdmp.h"
#include "tools/lib/mutate.h"

using namespace ge;

namespace {

dump::Dump scene() {
    dump::Dump d;
    std::string err, path = GE2GL_SOURCE_DIR;
    // Appended, not std::string(...) + "...": GCC 12 at -O1 warns falsely (-Warray-bounds) on that.
    path += "/dumps/lit_textured_skinned.ppdmp";
    EXPECT_TRUE(dump::loadDump(path, d, err)) << err;
    return d;
}

TEST(Mutate, ASeedReproducesItsMutant) {
    const dump::Dump d = scene();
    for (u64 seed : {1ull, 2ull, 77ull, 123456789ull}) {
        const tools::Mutant a = tools::mutateDump(d, seed), b = tools::mutateDump(d, seed);
        EXPECT_EQ(a.steps, b.steps);
        EXPECT_EQ(tools::mutantFile(a), tools::mutantFile(b));
        EXPECT_FALSE(a.steps.empty());
        EXPECT_LE(a.steps.size(), 4u);
    }
}

TEST(Mutate, SeedsDifferAndReachEveryKind) {
    const dump::Dump d = scene();
    std::set<std::vector<u8>> files;
    std::set<std::string> kinds;
    int truncated = 0;
    for (u64 seed = 1; seed <= 200; ++seed) {
        const tools::Mutant m = tools::mutateDump(d, seed);
        files.insert(tools::mutantFile(m));
        truncated += m.truncate != 0;
        for (const std::string& s : m.steps) kinds.insert(s.substr(0, s.find_first_of(" ")));
        // Loads, or is refused with a message (the cut files, records past the limits).
        const std::vector<u8> f = tools::mutantFile(m);
        dump::Dump back;
        std::string err;
        if (!dump::loadDumpFromMemory(f.data(), f.size(), back, err)) {
            EXPECT_FALSE(err.empty());
        }
    }
    EXPECT_GE(files.size(), 195u);
    EXPECT_GT(truncated, 0);
    // "GE words ...", "record N ...", "payload of ...", "records ..." (list changes).
    for (const char* k : {"GE", "record", "payload", "records"}) EXPECT_TRUE(kinds.count(k)) << k;
}

TEST(Mutate, TheGeneratorIsFixed) {
    // splitmix64's first outputs for seed 0 (its published test vector): the same mutants on any
    // machine and standard library.
    tools::MutationRng r(0);
    EXPECT_EQ(r.next(), 0xE220A8397B1DCDAFull);
    EXPECT_EQ(r.next(), 0x6E789E6AA1B965F4ull);
}

}  // namespace
