// SPDX-License-Identifier: MIT
// Robustness of the .ppdmp reader against damaged input: truncations, seeded bit flips and byte
// overwrites in the header and both compressed blocks, lying size fields, damaged zips and
// random garbage. Every load must either fail with a non-empty message or give a Dump whose
// payload() answers stay inside the push buffer — never crash, hang or read out of bounds
// (CI runs this under ASan/UBSan). Deterministic: fixed seeds, raw mt19937 output only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "hle/dump/ppdmp.h"

using namespace ge;
using namespace ge::dump;
namespace fs = std::filesystem;

namespace {

struct RawDump {
    std::string name;
    std::vector<u8> zip;  // the zip as stored
    std::vector<u8> raw;  // the .ppdmp bytes inside it
};

std::vector<u8> readFile(const fs::path& p) {
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    std::vector<u8> out(ec ? 0 : size_t(size));
    std::ifstream f(p, std::ios::binary);
    f.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size()));
    out.resize(size_t(f.gcount()));
    return out;
}

std::vector<RawDump> loadRawDumps() {
    std::vector<RawDump> out;
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    std::vector<fs::path> zips;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().extension() == ".zip") zips.push_back(e.path());
    std::sort(zips.begin(), zips.end());
    for (const fs::path& z : zips) {
        RawDump d;
        d.name = z.filename().string();
        d.zip = readFile(z);
        std::string err;
        if (!extractPpdmpFromZip(d.zip.data(), d.zip.size(), d.raw, err)) {
            ADD_FAILURE() << d.name << ": " << err;
            continue;
        }
        out.push_back(std::move(d));
    }
    return out;
}

// Extracted once per test binary run (inflating 20 zips is most of the cost).
const std::vector<RawDump>& rawDumps() {
    static const std::vector<RawDump> dumps = loadRawDumps();
    return dumps;
}

// Layout of a well-formed raw dump (docs/ppdmp.md §2): header size H and where each block starts.
struct Layout {
    size_t header = 0;     // H
    size_t cmdStart = 0;   // H + 12
    size_t cmdSize = 0;
    size_t pushField = 0;  // u32 pushCompressedSize
    size_t pushStart = 0;
    size_t pushSize = 0;
};

Layout layoutOf(const std::vector<u8>& raw) {
    Layout l;
    const u32 version = readLE32(&raw[8]);
    l.header = version >= 4 ? 24 : 12;
    l.cmdStart = l.header + 12;
    l.cmdSize = readLE32(&raw[l.header + 8]);
    l.pushField = l.cmdStart + l.cmdSize;
    l.pushStart = l.pushField + 4;
    l.pushSize = readLE32(&raw[l.pushField]);
    return l;
}

// A successful load must be internally consistent: payload() non-null exactly for in-range
// records, and every byte it hands out readable (ASan checks the touches).
void expectConsistent(const Dump& d) {
    EXPECT_GE(d.version, kMinVersion);
    EXPECT_LE(d.version, kMaxVersion);
    EXPECT_LE(d.gameId.size(), kGameIdBytes);
    unsigned sum = 0;
    for (const Record& r : d.records) {
        const u8* p = d.payload(r);
        const bool inRange = u64(r.ptr) + r.size <= d.pushbuf.size();
        ASSERT_EQ(p != nullptr, inRange);
        if (p && r.size) sum += p[0] + p[r.size - 1];
        EXPECT_NE(recordTypeName(r.type), nullptr);
    }
    (void)sum;
}

struct Outcome {
    int failed = 0;
    int loaded = 0;
};

void check(const std::vector<u8>& bytes, bool zip, Outcome& o) {
    Dump d;
    std::string err;
    const bool ok = zip ? loadZipFromMemory(bytes.data(), bytes.size(), d, err)
                        : loadDumpFromMemory(bytes.data(), bytes.size(), d, err);
    if (ok) {
        ++o.loaded;
        expectConsistent(d);
    } else {
        ++o.failed;
        EXPECT_FALSE(err.empty());
        EXPECT_EQ(err.find('\n'), std::string::npos) << "one-line error: " << err;
        EXPECT_TRUE(d.records.empty() && d.pushbuf.empty());
    }
}

}  // namespace

TEST(DumpFuzz, Truncations) {
    const auto& dumps = rawDumps();
    if (dumps.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    for (const RawDump& rd : dumps) {
        SCOPED_TRACE(rd.name);
        const Layout l = layoutOf(rd.raw);
        const size_t n = rd.raw.size();
        const size_t cuts[] = {0,           7,           8,          11,          12,
                               23,          l.header + 11, l.cmdStart, l.cmdStart + l.cmdSize / 2,
                               l.pushField, l.pushField + 3, l.pushStart, l.pushStart + l.pushSize / 2,
                               n - 1};
        for (size_t cut : cuts) {
            if (cut >= n) continue;
            SCOPED_TRACE("cut at " + std::to_string(cut));
            Dump d;
            std::string err;
            // Every block is needed in full (ppdmp.md §2), so every truncation is an error.
            EXPECT_FALSE(loadDumpFromMemory(rd.raw.data(), cut, d, err));
            EXPECT_FALSE(err.empty());
        }
    }
}

TEST(DumpFuzz, LyingSizeFields) {
    const auto& dumps = rawDumps();
    if (dumps.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    for (const RawDump& rd : dumps) {
        SCOPED_TRACE(rd.name);
        const Layout l = layoutOf(rd.raw);
        const size_t fields[] = {l.header, l.header + 4, l.header + 8, l.pushField};
        for (size_t field : fields) {
            const u32 real = readLE32(&rd.raw[field]);
            const u32 values[] = {0, 1, real - 1, real + 1, 0x3FFFFFFFu, 0x40000000u, 0x7FFFFFFFu, 0xFFFFFFFFu};
            for (u32 v : values) {
                SCOPED_TRACE("field " + std::to_string(field) + " = " + std::to_string(v));
                std::vector<u8> f = rd.raw;
                writeLE32(&f[field], v);
                Dump d;
                std::string err;
                EXPECT_FALSE(loadDumpFromMemory(f.data(), f.size(), d, err));
                EXPECT_FALSE(err.empty());
            }
        }
    }
}

TEST(DumpFuzz, SeededMutations) {
    const auto& dumps = rawDumps();
    if (dumps.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    Outcome total;
    for (size_t di = 0; di < dumps.size(); ++di) {
        const RawDump& rd = dumps[di];
        SCOPED_TRACE(rd.name);
        const Layout l = layoutOf(rd.raw);
        std::mt19937 rng(0xC0FFEEu + u32(di));
        for (int m = 0; m < 30; ++m) {
            std::vector<u8> f = rd.raw;
            // Pick a region: header, command block, push size field or push block.
            size_t lo = 0, len = l.cmdStart;
            switch (rng() % 4) {
                case 0: lo = 0, len = l.cmdStart; break;
                case 1: lo = l.cmdStart, len = l.cmdSize; break;
                case 2: lo = l.pushField, len = 4; break;
                default: lo = l.pushStart, len = l.pushSize; break;
            }
            if (len == 0) lo = 0, len = l.cmdStart;
            const size_t pos = lo + rng() % len;
            const u32 kind = rng() % 3;
            if (kind == 0) {
                f[pos] ^= u8(1u << (rng() % 8));
            } else if (kind == 1) {
                f[pos] = u8(rng());
            } else {
                const u32 extremes[] = {0u, 0xFFFFFFFFu, 0x80000000u, u32(rng())};
                const size_t at = std::min(pos, f.size() - 4);
                writeLE32(&f[at], extremes[rng() % 4]);
            }
            SCOPED_TRACE("mutation " + std::to_string(m) + " at " + std::to_string(pos));
            check(f, false, total);
        }
    }
    std::printf("  raw mutations: %d refused, %d loaded\n", total.failed, total.loaded);
    EXPECT_GT(total.failed, 0);
}

TEST(DumpFuzz, DamagedZips) {
    const auto& dumps = rawDumps();
    if (dumps.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    Outcome total;
    for (size_t di = 0; di < dumps.size(); ++di) {
        const RawDump& rd = dumps[di];
        SCOPED_TRACE(rd.name);
        const size_t n = rd.zip.size();
        for (size_t cut : {size_t(0), size_t(4), size_t(21), size_t(22), n / 2, n - 22, n - 1}) {
            if (cut >= n) continue;
            std::vector<u8> f(rd.zip.begin(), rd.zip.begin() + long(cut));
            Dump d;
            std::string err;
            EXPECT_FALSE(loadZipFromMemory(f.data(), f.size(), d, err)) << "cut " << cut;
            EXPECT_FALSE(err.empty());
        }
        std::mt19937 rng(0x5EEDu + u32(di));
        for (int m = 0; m < 6; ++m) {
            std::vector<u8> f = rd.zip;
            // Half in the central directory / end record (the last bytes), half anywhere.
            const size_t tail = std::min<size_t>(n, 256);
            const size_t pos = (m % 2) ? n - tail + rng() % tail : rng() % n;
            if (rng() % 2) f[pos] ^= u8(1u << (rng() % 8));
            else f[pos] = u8(rng());
            SCOPED_TRACE("zip mutation at " + std::to_string(pos));
            check(f, true, total);
        }
    }
    std::printf("  zip mutations: %d refused, %d loaded\n", total.failed, total.loaded);
}

TEST(DumpFuzz, RandomGarbage) {
    std::mt19937 rng(1234);
    Outcome total;
    const char magic[] = "PPSSPPGE";
    for (int i = 0; i < 400; ++i) {
        std::vector<u8> f(rng() % 300);
        for (u8& b : f) b = u8(rng());
        // Most buffers get a valid-looking start so the parser gets past the magic and version.
        if (f.size() >= 12 && i % 4 != 0) {
            std::memcpy(f.data(), magic, 8);
            writeLE32(&f[8], 2 + u32(i % 5));
        }
        if (f.size() >= 40 && i % 3 == 0) {
            const size_t h = readLE32(&f[8]) >= 4 ? 24 : 12;
            writeLE32(&f[h], rng() % 8);          // small commandCount
            writeLE32(&f[h + 4], rng() % 64);     // small pushbufSize
            writeLE32(&f[h + 8], rng() % 40);     // plausible compressed size
        }
        check(f, false, total);
        if (f.size() >= 4) {
            f[0] = 'P', f[1] = 'K', f[2] = 3, f[3] = 4;
        }
        check(f, true, total);
    }
    std::printf("  garbage: %d refused, %d loaded\n", total.failed, total.loaded);
    // Null with zero size is a clean error too.
    Dump d;
    std::string err;
    EXPECT_FALSE(loadDumpFromMemory(nullptr, 0, d, err));
    EXPECT_FALSE(err.empty());
    EXPECT_FALSE(loadZipFromMemory(nullptr, 0, d, err));
    EXPECT_FALSE(err.empty());
}
