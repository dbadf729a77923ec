// SPDX-License-Identifier: MIT
// .ppdmp reader/writer tests (docs/ppdmp.md §1–§3, §5, §7): hand-built files with known bytes,
// error cases, the 20 frametest dumps (load, facts, read → serialise → read round trip) and the
// DumpWriter.
#include <gtest/gtest.h>

#include <zip.h>
#include <zstd.h>

#include <algorithm>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "hle/dump/dump_writer.h"
#include "hle/dump/ppdmp.h"

using namespace ge;
using namespace ge::dump;
namespace fs = std::filesystem;

namespace {

// ---- hand-built file helpers --------------------------------------------------------------

void put32(std::vector<u8>& v, u32 x) {
    u8 b[4];
    writeLE32(b, x);
    v.insert(v.end(), b, b + 4);
}

// Raw snappy (ppdmp.md §2.2) made only of literal elements: varint uncompressed length, then for each
// chunk of ≤ 60 bytes a tag byte (len − 1) << 2 (element type 00 = literal) and the bytes.
std::vector<u8> snappyLiteral(const std::vector<u8>& data) {
    std::vector<u8> out;
    size_t n = data.size();
    do {
        u8 b = u8(n & 0x7F);
        n >>= 7;
        out.push_back(n ? u8(b | 0x80) : b);
    } while (n);
    for (size_t i = 0; i < data.size(); i += 60) {
        const size_t len = std::min<size_t>(60, data.size() - i);
        out.push_back(u8((len - 1) << 2));
        out.insert(out.end(), data.begin() + long(i), data.begin() + long(i + len));
    }
    return out;
}

// One zstd frame (RFC 8878) holding a single raw block. With `withSize`, the frame header
// descriptor is 0xA0 (single segment, 4-byte content size); without it 0x00 and a window
// descriptor byte 0x00 (1 KiB window, so data must be ≤ 1024 bytes).
std::vector<u8> zstdRaw(const std::vector<u8>& data, bool withSize = true) {
    std::vector<u8> out = {0x28, 0xB5, 0x2F, 0xFD};
    if (withSize) {
        out.push_back(0xA0);
        put32(out, u32(data.size()));
    } else {
        out.push_back(0x00);
        out.push_back(0x00);
    }
    const u32 blockHeader = 1u /*last*/ | (0u << 1) /*raw*/ | (u32(data.size()) << 3);
    out.push_back(u8(blockHeader));
    out.push_back(u8(blockHeader >> 8));
    out.push_back(u8(blockHeader >> 16));
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

std::vector<u8> recordBytes(const std::vector<Record>& recs) {
    std::vector<u8> out;
    for (const Record& r : recs) {
        out.push_back(r.type);
        put32(out, r.size);
        put32(out, r.ptr);
    }
    return out;
}

// ppdmp.md §2 layout, with the caller's compressed blocks and header numbers (which may lie).
std::vector<u8> buildFile(u32 version, const std::string& id9, u32 commandCount, u32 pushbufSize,
                          const std::vector<u8>& cmdBlock, const std::vector<u8>& pushBlock) {
    std::vector<u8> f = {'P', 'P', 'S', 'S', 'P', 'P', 'G', 'E'};
    put32(f, version);
    if (version >= 4) {
        u8 id[12] = {};
        std::memcpy(id, id9.data(), std::min<size_t>(9, id9.size()));
        f.insert(f.end(), id, id + 12);
    }
    put32(f, commandCount);
    put32(f, pushbufSize);
    put32(f, u32(cmdBlock.size()));
    f.insert(f.end(), cmdBlock.begin(), cmdBlock.end());
    put32(f, u32(pushBlock.size()));
    f.insert(f.end(), pushBlock.begin(), pushBlock.end());
    return f;
}

std::vector<u8> buildValid(u32 version, const std::string& id9, const std::vector<Record>& recs,
                           const std::vector<u8>& push) {
    const std::vector<u8> cmd = recordBytes(recs);
    const bool zstd = version >= 5;
    return buildFile(version, id9, u32(recs.size()), u32(push.size()), zstd ? zstdRaw(cmd) : snappyLiteral(cmd),
                     zstd ? zstdRaw(push) : snappyLiteral(push));
}

const std::vector<Record> kRecs = {{INIT, 8, 0}, {u8(TEXTURE0 + 3), 5, 3}, {DISPLAY, 12, 8}};
std::vector<u8> pushBytes20() {
    std::vector<u8> p(20);
    for (size_t i = 0; i < p.size(); ++i) p[i] = u8(0xA0 + i);
    return p;
}

bool load(const std::vector<u8>& f, Dump& d, std::string& err) { return loadDumpFromMemory(f.data(), f.size(), d, err); }

fs::path tempPath(const std::string& name) {
    return fs::temp_directory_path() / ("ge2gl_dump_io_" + std::to_string(::getpid()) + "_" + name);
}

std::vector<fs::path> frametestZips() {
    std::vector<fs::path> out;
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().extension() == ".zip") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<u8> readFile(const fs::path& p) {
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    std::vector<u8> out(ec ? 0 : size_t(size));
    std::ifstream f(p, std::ios::binary);
    f.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size()));
    out.resize(size_t(f.gcount()));
    return out;
}

}  // namespace

// ---- names ------------------------------------------------------------------------------------

TEST(DumpRecordTypes, Names) {
    EXPECT_STREQ(recordTypeName(0), "INIT");
    EXPECT_STREQ(recordTypeName(1), "REGISTERS");
    EXPECT_STREQ(recordTypeName(5), "TRANSFERSRC");
    EXPECT_STREQ(recordTypeName(9), "DISPLAY");
    EXPECT_STREQ(recordTypeName(10), "CLUTADDR");
    EXPECT_STREQ(recordTypeName(11), "EDRAMTRANS");
    EXPECT_STREQ(recordTypeName(0x0C), "UNKNOWN_0C");
    EXPECT_STREQ(recordTypeName(0x0F), "UNKNOWN_0F");
    EXPECT_STREQ(recordTypeName(0x10), "TEXTURE0");
    EXPECT_STREQ(recordTypeName(0x13), "TEXTURE3");
    EXPECT_STREQ(recordTypeName(0x17), "TEXTURE7");
    EXPECT_STREQ(recordTypeName(0x18), "FRAMEBUF0");
    EXPECT_STREQ(recordTypeName(0x1F), "FRAMEBUF7");
    EXPECT_STREQ(recordTypeName(0x20), "UNKNOWN_20");
    EXPECT_STREQ(recordTypeName(0xAB), "UNKNOWN_AB");
    EXPECT_STREQ(recordTypeName(0xFF), "UNKNOWN_FF");
}

TEST(DumpRecordTypes, Known) {
    int known = 0;
    for (int t = 0; t < 256; ++t) known += isKnownRecordType(u8(t)) ? 1 : 0;
    EXPECT_EQ(known, 12 + 16);
    EXPECT_TRUE(isKnownRecordType(EDRAMTRANS));
    EXPECT_FALSE(isKnownRecordType(12));
    EXPECT_FALSE(isKnownRecordType(15));
    EXPECT_TRUE(isKnownRecordType(0x10));
    EXPECT_TRUE(isKnownRecordType(0x1F));
    EXPECT_FALSE(isKnownRecordType(0x20));
    EXPECT_EQ(textureLevelOf(0x15), 5);
    EXPECT_EQ(textureLevelOf(0x18), -1);
    EXPECT_EQ(framebufLevelOf(0x1A), 2);
    EXPECT_EQ(framebufLevelOf(0x17), -1);
}

// ---- payload ranges ---------------------------------------------------------------------------

TEST(DumpPayload, RangeChecks) {
    Dump d;
    d.pushbuf = pushBytes20();
    EXPECT_EQ(d.payload({INIT, 20, 0}), d.pushbuf.data());
    EXPECT_EQ(d.payload({INIT, 5, 15}), d.pushbuf.data() + 15);
    EXPECT_EQ(d.payload({INIT, 6, 15}), nullptr);
    EXPECT_NE(d.payload({INIT, 0, 20}), nullptr);  // empty payload at the very end is in range
    EXPECT_EQ(d.payload({INIT, 0, 21}), nullptr);
    EXPECT_EQ(d.payload({INIT, 0x20, 0xFFFFFFF0u}), nullptr);  // ptr + size wraps in 32 bits
    EXPECT_EQ(d.payload({INIT, 0xFFFFFFFFu, 1}), nullptr);
    // payloadWord: little-endian words of the payload, fallback outside it.
    EXPECT_EQ(d.payloadWord({DISPLAY, 12, 4}, 0), 0xA7A6A5A4u);
    EXPECT_EQ(d.payloadWord({DISPLAY, 12, 4}, 2), 0xAFAEADACu);
    EXPECT_EQ(d.payloadWord({DISPLAY, 12, 4}, 3, 77), 77u);
    EXPECT_EQ(d.payloadWord({DISPLAY, 12, 10}, 0, 77), 77u);  // payload itself out of range
    Dump empty;
    EXPECT_NE(empty.payload({REGISTERS, 0, 0}), nullptr);
    EXPECT_EQ(empty.payload({REGISTERS, 1, 0}), nullptr);
}

// ---- hand-built files -------------------------------------------------------------------------

TEST(DumpLoad, HandBuiltV2Snappy) {
    Dump d;
    std::string err;
    ASSERT_TRUE(load(buildValid(2, "", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.version, 2u);
    EXPECT_EQ(d.gameId, "");
    ASSERT_EQ(d.records.size(), 3u);
    EXPECT_EQ(d.records[1].type, 0x13);
    EXPECT_EQ(d.records[1].size, 5u);
    EXPECT_EQ(d.records[1].ptr, 3u);
    EXPECT_EQ(d.records[2], (Record{DISPLAY, 12, 8}));
    ASSERT_EQ(d.pushbuf.size(), 20u);
    EXPECT_EQ(d.pushbuf[19], 0xB3);
    ASSERT_NE(d.payload(d.records[1]), nullptr);
    EXPECT_EQ(d.payload(d.records[1])[0], 0xA3);  // misaligned payloads are fine (ppdmp.md §3.1)
}

TEST(DumpLoad, HandBuiltV3AndV4Snappy) {
    Dump d;
    std::string err;
    ASSERT_TRUE(load(buildValid(3, "", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.version, 3u);
    // v4: 9-byte ID that fills all 9 bytes without a NUL (ppdmp.md §2).
    ASSERT_TRUE(load(buildValid(4, "ULUS10598", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.version, 4u);
    EXPECT_EQ(d.gameId, "ULUS10598");
    EXPECT_EQ(d.records, kRecs);
    // NUL-padded shorter ID.
    ASSERT_TRUE(load(buildValid(4, "ABC", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.gameId, "ABC");
    // A 200-byte push buffer spans several literal elements and a 2-byte varint.
    std::vector<u8> big(200);
    for (size_t i = 0; i < big.size(); ++i) big[i] = u8(i * 7);
    ASSERT_TRUE(load(buildValid(4, "X", {{VERTICES, 200, 0}}, big), d, err)) << err;
    EXPECT_EQ(d.pushbuf, big);
}

TEST(DumpLoad, HandBuiltV5V6Zstd) {
    Dump d;
    std::string err;
    ASSERT_TRUE(load(buildValid(5, "UCJS10095", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.version, 5u);
    EXPECT_EQ(d.gameId, "UCJS10095");
    EXPECT_EQ(d.records, kRecs);
    EXPECT_EQ(d.pushbuf, pushBytes20());
    ASSERT_TRUE(load(buildValid(6, "NPUZ00087", kRecs, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.version, 6u);
    // Frames without a content size still load when they decompress to the expected size.
    const std::vector<u8> cmd = recordBytes(kRecs);
    ASSERT_TRUE(load(buildFile(6, "A", 3, 20, zstdRaw(cmd, false), zstdRaw(pushBytes20(), false)), d, err)) << err;
    EXPECT_EQ(d.records, kRecs);
    EXPECT_EQ(d.pushbuf, pushBytes20());
    // ... but not when the size differs from the header.
    EXPECT_FALSE(load(buildFile(6, "A", 3, 21, zstdRaw(cmd, false), zstdRaw(pushBytes20(), false)), d, err));
    EXPECT_NE(err.find("push buffer"), std::string::npos) << err;
    // Empty dump: zero records and an empty push buffer are well-formed.
    ASSERT_TRUE(load(buildValid(6, "", {}, {}), d, err)) << err;
    EXPECT_TRUE(d.records.empty());
    EXPECT_TRUE(d.pushbuf.empty());
}

TEST(DumpLoad, RecordOutsidePushBufferIsNotALoadError) {
    const std::vector<Record> recs = {{INIT, 8, 0}, {VERTICES, 8, 16}, {TEXTURE0, 0x10, 0xFFFFFFF8u}};
    Dump d;
    std::string err;
    ASSERT_TRUE(load(buildValid(6, "", recs, pushBytes20()), d, err)) << err;
    EXPECT_NE(d.payload(d.records[0]), nullptr);
    EXPECT_EQ(d.payload(d.records[1]), nullptr);
    EXPECT_EQ(d.payload(d.records[2]), nullptr);
    // Unknown record types are kept; refusing them is the player's job (ppdmp.md §3.2).
    ASSERT_TRUE(load(buildValid(3, "", {{0x0C, 0, 0}}, pushBytes20()), d, err)) << err;
    EXPECT_EQ(d.records[0].type, 0x0C);
}

TEST(DumpLoad, Errors) {
    Dump d;
    std::string err;
    const std::vector<u8> good = buildValid(6, "ULUS10598", kRecs, pushBytes20());

    std::vector<u8> f = good;
    f[0] = 'X';
    EXPECT_FALSE(load(f, d, err));
    EXPECT_NE(err.find("bad magic"), std::string::npos) << err;

    EXPECT_FALSE(load(buildValid(1, "", kRecs, pushBytes20()), d, err));
    EXPECT_EQ(err, "unsupported version 1");
    EXPECT_FALSE(load(buildValid(7, "", kRecs, pushBytes20()), d, err));
    EXPECT_EQ(err, "unsupported version 7");
    f = good;
    writeLE32(f.data() + 8, 0);
    EXPECT_FALSE(load(f, d, err));
    EXPECT_EQ(err, "unsupported version 0");

    EXPECT_FALSE(load({}, d, err));
    EXPECT_NE(err.find("truncated header"), std::string::npos) << err;
    EXPECT_FALSE(load(std::vector<u8>(good.begin(), good.begin() + 20), d, err));
    EXPECT_NE(err.find("truncated header"), std::string::npos) << err;
    EXPECT_FALSE(load(std::vector<u8>(good.begin(), good.begin() + 40), d, err));
    EXPECT_NE(err.find("truncated command block"), std::string::npos) << err;
    EXPECT_FALSE(load(std::vector<u8>(good.begin(), good.end() - 1), d, err));
    EXPECT_NE(err.find("truncated push buffer"), std::string::npos) << err;

    // commandCount * 9 would overflow 32 bits and exceeds the record cap (ppdmp.h).
    f = good;
    writeLE32(f.data() + 24, 0xFFFFFFFFu);
    EXPECT_FALSE(load(f, d, err));
    EXPECT_NE(err.find("command block too large"), std::string::npos) << err;
    f = good;
    writeLE32(f.data() + 28, 0x40000001u);
    EXPECT_FALSE(load(f, d, err));
    EXPECT_NE(err.find("push buffer too large"), std::string::npos) << err;
    // Within the cap but not what the frame holds: refused before allocating (content size).
    f = good;
    writeLE32(f.data() + 28, u32(kMaxPushbufBytes - 1));
    EXPECT_FALSE(load(f, d, err));
    EXPECT_NE(err.find("header says"), std::string::npos) << err;
    // One record more than the block holds.
    f = good;
    writeLE32(f.data() + 24, 4);
    EXPECT_FALSE(load(f, d, err));
    EXPECT_NE(err.find("command block"), std::string::npos) << err;
    // Snappy length mismatch and garbage (v2).
    const std::vector<u8> cmd = recordBytes(kRecs);
    EXPECT_FALSE(load(buildFile(2, "", 3, 21, snappyLiteral(cmd), snappyLiteral(pushBytes20())), d, err));
    EXPECT_NE(err.find("header says"), std::string::npos) << err;
    std::vector<u8> badSnappy = snappyLiteral(pushBytes20());
    badSnappy[1] = 0xFC;  // literal tag claiming 64 bytes follow
    EXPECT_FALSE(load(buildFile(2, "", 3, 20, snappyLiteral(cmd), badSnappy), d, err));
    EXPECT_NE(err.find("snappy"), std::string::npos) << err;
    // A copy reaching back before the block's start: the right length, every tag well formed, caught
    // by the decompression itself (there is no separate validation pass).
    const std::vector<u8> pastStart = {20, 0x0C, 1, 2, 3, 4, u8(0x02 | (15 << 2)), 100, 0};
    EXPECT_FALSE(load(buildFile(2, "", 3, 20, snappyLiteral(cmd), pastStart), d, err));
    EXPECT_NE(err.find("corrupt snappy data"), std::string::npos) << err;
    // zstd block of the wrong kind of data.
    EXPECT_FALSE(load(buildFile(6, "", 3, 20, snappyLiteral(cmd), zstdRaw(pushBytes20())), d, err));
    EXPECT_NE(err.find("zstd"), std::string::npos) << err;
    // A failed load leaves an empty dump behind.
    EXPECT_TRUE(d.records.empty());
    EXPECT_TRUE(d.pushbuf.empty());

    // Trailing bytes after the second block are ignored (PPSSPP does not look there).
    f = good;
    f.push_back(0x55);
    EXPECT_TRUE(load(f, d, err)) << err;
}

// A zstd frame without a content size made of RLE blocks (3 header bytes + 1 byte each, 128 KiB
// window): a few kilobytes that decompress to `blocks` × 128 KiB of zeros.
std::vector<u8> zstdRleBomb(u32 blocks) {
    std::vector<u8> out = {0x28, 0xB5, 0x2F, 0xFD, 0x00, 0x38};  // no content size, 128 KiB window
    for (u32 i = 0; i < blocks; ++i) {
        const u32 h = (i + 1 == blocks ? 1u : 0u) | (1u << 1) /*RLE*/ | ((128u << 10) << 3);
        out.push_back(u8(h));
        out.push_back(u8(h >> 8));
        out.push_back(u8(h >> 16));
        out.push_back(0);
    }
    return out;
}

// Hostile sizes cost neither memory nor time: a 4 KB frame that would decompress to
// 128 MiB under a header that says 64 bytes stops at the header's size; caps on the header's
// record count and push-buffer size (ppdmp.h) refuse before anything is allocated.
TEST(DumpLoad, DecompressionBombsStopAtTheHeadersSize) {
    Dump d;
    std::string err;
    const std::vector<u8> cmd = recordBytes(kRecs);
    const std::vector<u8> bomb = zstdRleBomb(1024);
    ASSERT_LT(bomb.size(), 5000u);
    // The work is bounded by what the decoder produced, which the messages state: the 128 MiB
    // frame is refused at the 65th byte, past the 64 the header allows.
    EXPECT_FALSE(load(buildFile(6, "", 3, 64, zstdRaw(cmd), bomb), d, err));
    EXPECT_NE(err.find("decompresses to more than the 64 bytes the header says"), std::string::npos) << err;
    // A frame shorter than the header says: refused after producing only what it holds (128
    // blocks of 128 KiB), not the header's size plus anything.
    EXPECT_FALSE(load(buildFile(6, "", 3, (16u << 20) + 1, zstdRaw(cmd), zstdRleBomb(128)), d, err));
    EXPECT_NE(err.find("decompresses to " + std::to_string(128u << 17) + " bytes, header says"), std::string::npos) << err;
    // Caps: one record over, one byte over.
    EXPECT_FALSE(load(buildFile(6, "", u32(kMaxRecords + 1), 20, zstdRaw(cmd), zstdRaw(pushBytes20())), d, err));
    EXPECT_NE(err.find("command block too large"), std::string::npos) << err;
    EXPECT_FALSE(load(buildFile(6, "", 3, u32(kMaxPushbufBytes + 1), zstdRaw(cmd), zstdRaw(pushBytes20())), d, err));
    EXPECT_NE(err.find("push buffer too large"), std::string::npos) << err;
}

// Resident set of this process in bytes (/proc/self/statm), 0 when unreadable.
u64 residentBytes() {
    std::ifstream f("/proc/self/statm");
    u64 size = 0, resident = 0;
    if (!(f >> size >> resident)) return 0;
    return resident * u64(::sysconf(_SC_PAGESIZE));
}

// A zip archive at `path` holding `bytes` stored (not compressed) as entry `name`, written with
// libzip; false when libzip fails.
bool writeStoredZip(const fs::path& path, const char* name, const std::vector<u8>& bytes) {
    int zerr = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &zerr);
    if (!z) return false;
    zip_source_t* src = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    const zip_int64_t idx = src ? zip_file_add(z, name, src, 0) : -1;
    if (idx < 0 || zip_set_file_compression(z, zip_uint64_t(idx), ZIP_CM_STORE, 0) != 0) {
        if (src && idx < 0) zip_source_free(src);
        zip_discard(z);
        return false;
    }
    return zip_close(z) == 0;
}

// A zip whose directory claims a 200 MiB entry that holds a few bytes: refused as truncated after
// reading what is there, without allocating the claimed size first.
TEST(DumpLoad, ZipEntryClaimingMoreThanItHoldsCostsNothing) {
    const fs::path zpath = tempPath("liar.zip");
    const std::vector<u8> body = buildValid(6, "LIAR00001", kRecs, pushBytes20());
    ASSERT_TRUE(writeStoredZip(zpath, "x.ppdmp", body));
    std::vector<u8> zb = readFile(zpath);
    // Uncompressed size: offset 22 of the local header, 24 of the central directory entry.
    const u32 claim = 200u << 20;
    int patched = 0;
    for (size_t i = 0; i + 46 <= zb.size(); ++i) {
        if (zb[i] == 'P' && zb[i + 1] == 'K' && zb[i + 2] == 3 && zb[i + 3] == 4) writeLE32(&zb[i + 22], claim), ++patched;
        if (zb[i] == 'P' && zb[i + 1] == 'K' && zb[i + 2] == 1 && zb[i + 3] == 2) writeLE32(&zb[i + 24], claim), ++patched;
    }
    ASSERT_EQ(patched, 2);
    const u64 before = residentBytes();
    std::vector<u8> out;
    std::string err;
    EXPECT_FALSE(extractPpdmpFromZip(zb.data(), zb.size(), out, err));
    EXPECT_FALSE(err.empty());
    const u64 after = residentBytes();
    if (before && after) {
        EXPECT_LT(after, before + (64u << 20)) << "resident set grew by " << (after - before);
    }
    fs::remove(zpath);
}

// Entries the loader cannot read are refused by name: encrypted ones (flag bit 0; no password is
// known) and compression methods other than stored and deflate (here 12, bzip2).
TEST(DumpLoad, EncryptedAndUnknownMethodZipEntriesAreRefused) {
    const fs::path zpath = tempPath("kinds.zip");
    const std::vector<u8> body = buildValid(6, "KINDS0001", kRecs, pushBytes20());
    ASSERT_TRUE(writeStoredZip(zpath, "k.ppdmp", body));
    const std::vector<u8> good = readFile(zpath);
    std::vector<u8> out;
    std::string err;
    ASSERT_TRUE(extractPpdmpFromZip(good.data(), good.size(), out, err)) << err;
    EXPECT_EQ(out, body);
    // Flags at offset 6 of the local header and 8 of the central directory entry; the method
    // two bytes after each.
    auto patch = [&](int flagOr, int method) {
        std::vector<u8> z = good;
        for (size_t i = 0; i + 46 <= z.size(); ++i) {
            if (z[i] != 'P' || z[i + 1] != 'K') continue;
            size_t at = 0;
            if (z[i + 2] == 3 && z[i + 3] == 4) at = i + 6;
            else if (z[i + 2] == 1 && z[i + 3] == 2) at = i + 8;
            else continue;
            z[at] = u8(z[at] | flagOr);
            if (method >= 0) z[at + 2] = u8(method), z[at + 3] = 0;
        }
        return z;
    };
    const std::vector<u8> encrypted = patch(1, -1);
    EXPECT_FALSE(extractPpdmpFromZip(encrypted.data(), encrypted.size(), out, err));
    EXPECT_NE(err.find("encrypted"), std::string::npos) << err;
    const std::vector<u8> bzip2 = patch(0, 12);
    EXPECT_FALSE(extractPpdmpFromZip(bzip2.data(), bzip2.size(), out, err));
    EXPECT_NE(err.find("compression method 12"), std::string::npos) << err;
    fs::remove(zpath);
}

TEST(DumpLoad, FilesAndZips) {
    Dump d;
    std::string err;
    EXPECT_FALSE(loadDump("/nonexistent/dir/none.ppdmp", d, err));
    EXPECT_NE(err.find("no such file"), std::string::npos) << err;
    EXPECT_FALSE(loadDump(fs::temp_directory_path().string(), d, err));
    EXPECT_FALSE(err.empty());

    const std::vector<u8> a = buildValid(6, "AAAAAAAAA", kRecs, pushBytes20());
    const std::vector<u8> c = buildValid(4, "CCCCCCCCC", kRecs, pushBytes20());
    const fs::path raw = tempPath("raw.ppdmp");
    {
        std::ofstream(raw, std::ios::binary).write(reinterpret_cast<const char*>(a.data()), long(a.size()));
    }
    ASSERT_TRUE(loadDump(raw.string(), d, err)) << err;
    EXPECT_EQ(d.gameId, "AAAAAAAAA");

    const fs::path junk = tempPath("junk.bin");
    {
        std::ofstream(junk, std::ios::binary) << "hello, not a dump";
    }
    EXPECT_FALSE(loadDump(junk.string(), d, err));
    EXPECT_NE(err.find("bad magic"), std::string::npos) << err;

    // ppdmp.md §1: the last entry ending in .ppdmp (case-insensitive) wins; __macosx/ is skipped.
    const fs::path zpath = tempPath("pack.zip");
    {
        int zerr = 0;
        zip_t* z = zip_open(zpath.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &zerr);
        ASSERT_NE(z, nullptr);
        auto addEntry = [&](const char* name, const std::vector<u8>& bytes) {
            zip_source_t* s = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
            ASSERT_NE(s, nullptr);
            ASSERT_GE(zip_file_add(z, name, s, ZIP_FL_OVERWRITE), 0);
        };
        const std::vector<u8> png = {0x89, 'P', 'N', 'G'};
        addEntry("a.ppdmp", a);
        addEntry("C.PPDMP", c);
        addEntry("shot.png", png);
        addEntry("__MACOSX/._a.ppdmp", png);
        ASSERT_EQ(zip_close(z), 0);  // the buffers above must outlive this call
    }
    ASSERT_TRUE(loadDump(zpath.string(), d, err)) << err;
    EXPECT_EQ(d.version, 4u);
    EXPECT_EQ(d.gameId, "CCCCCCCCC");
    const std::vector<u8> zbytes = readFile(zpath);
    std::vector<u8> extracted;
    std::string entry;
    ASSERT_TRUE(extractPpdmpFromZip(zbytes.data(), zbytes.size(), extracted, err, &entry)) << err;
    EXPECT_EQ(entry, "C.PPDMP");
    EXPECT_EQ(extracted, c);
    ASSERT_TRUE(loadZipFromMemory(zbytes.data(), zbytes.size(), d, err)) << err;
    EXPECT_EQ(d.gameId, "CCCCCCCCC");
    // Raw bytes are not a zip, zip bytes are not a raw dump.
    EXPECT_FALSE(loadZipFromMemory(a.data(), a.size(), d, err));
    EXPECT_FALSE(err.empty());
    EXPECT_FALSE(loadDumpFromMemory(zbytes.data(), zbytes.size(), d, err));
    EXPECT_NE(err.find("bad magic"), std::string::npos) << err;

    const fs::path empty = tempPath("nodump.zip");
    {
        int zerr = 0;
        zip_t* z = zip_open(empty.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &zerr);
        ASSERT_NE(z, nullptr);
        const std::vector<u8> png = {1, 2, 3};
        zip_source_t* s = zip_source_buffer(z, png.data(), png.size(), 0);
        ASSERT_GE(zip_file_add(z, "x.png", s, 0), 0);
        ASSERT_EQ(zip_close(z), 0);
    }
    EXPECT_FALSE(loadDump(empty.string(), d, err));
    EXPECT_NE(err.find("no .ppdmp"), std::string::npos) << err;

    std::error_code ec;
    for (const fs::path& p : {raw, junk, zpath, empty}) fs::remove(p, ec);
}

// ---- serialisation ----------------------------------------------------------------------------

TEST(DumpSave, HeaderBytesFollowSection7) {
    Dump d;
    d.version = 3;  // whatever was loaded, the writer writes version 6
    d.gameId = "ULUS10598EXTRA";  // truncated to 9 bytes
    d.records = kRecs;
    d.pushbuf = pushBytes20();
    const std::vector<u8> f = serializeDump(d);
    ASSERT_GE(f.size(), 36u);
    EXPECT_EQ(std::string(f.begin(), f.begin() + 8), "PPSSPPGE");
    EXPECT_EQ(readLE32(&f[8]), 6u);
    EXPECT_EQ(std::string(f.begin() + 12, f.begin() + 21), "ULUS10598");
    EXPECT_EQ(f[21] | f[22] | f[23], 0);
    EXPECT_EQ(readLE32(&f[24]), 3u);   // commandCount
    EXPECT_EQ(readLE32(&f[28]), 20u);  // pushbufSize
    const u32 cmdZ = readLE32(&f[32]);
    ASSERT_LE(36u + cmdZ + 4, f.size());
    // One zstd frame carrying its content size (ppdmp.md §2.2, §7 rule 2).
    EXPECT_EQ(ZSTD_getFrameContentSize(&f[36], cmdZ), 27ull);
    const u32 pushZ = readLE32(&f[36 + cmdZ]);
    EXPECT_EQ(size_t(36) + cmdZ + 4 + pushZ, f.size());  // nothing follows the second block
    EXPECT_EQ(ZSTD_getFrameContentSize(&f[40 + cmdZ], pushZ), 20ull);

    Dump back;
    std::string err;
    ASSERT_TRUE(load(f, back, err)) << err;
    EXPECT_EQ(back.version, 6u);
    EXPECT_EQ(back.gameId, "ULUS10598");
    EXPECT_EQ(back.records, d.records);
    EXPECT_EQ(back.pushbuf, d.pushbuf);
}

// ---- DumpWriter -------------------------------------------------------------------------------

TEST(DumpWriterTest, RoundTripThroughFile) {
    u32 ctx[512] = {};
    for (u32 i = 0; i < 512; ++i) ctx[i] = i * 0x01010101u;
    ctx[384] = 0x0C000000;  // END (ppdmp.md §5)
    DumpWriter w("TEST00001");
    w.init(ctx);
    w.display(0x04000000, 512, 3);
    w.registers({0x12000000 | 0x11C, 0xA8000000 | 64});  // VTYPE, TBW0
    w.registers({0xB8000000 | 0x606});                    // merged into the same block
    const std::vector<u8> tex(64 * 8 * 4, 0x5A);
    const u8 verts[6] = {1, 2, 3, 4, 5, 6};
    w.texture(0, tex.data(), u32(tex.size()));
    w.vertices(verts, sizeof(verts));
    w.registers({0x04000000 | (3u << 16) | 2});  // PRIM
    w.texture(0, tex.data(), u32(tex.size()));   // same bytes again: shared payload
    const u8 idx[3] = {0, 1, 0};
    w.indices(idx, 3);
    w.vertices(verts, 3);  // different size: not shared
    w.display(0x04088000, 512, 1);

    const Dump& d = w.dump();
    ASSERT_EQ(d.records.size(), 10u);
    const u8 types[10] = {INIT, DISPLAY, REGISTERS, TEXTURE0, VERTICES, REGISTERS, TEXTURE0, INDICES, VERTICES, DISPLAY};
    for (size_t i = 0; i < 10; ++i) EXPECT_EQ(d.records[i].type, types[i]) << i;
    EXPECT_EQ(d.records[0].size, 2048u);
    EXPECT_EQ(d.records[2].size, 12u);  // 3 words in one block
    EXPECT_EQ(d.records[3].ptr % 16, 0u);
    EXPECT_EQ(d.records[4].ptr % 4, 0u);
    EXPECT_EQ(d.records[6].ptr, d.records[3].ptr);
    EXPECT_EQ(d.records[8].ptr % 4, 0u);
    EXPECT_EQ(d.payloadWord(d.records[2], 2), 0xB8000606u);
    EXPECT_EQ(d.payloadWord(d.records[0], 384), 0x0C000000u);
    EXPECT_EQ(d.payloadWord(d.records[9], 0), 0x04088000u);
    EXPECT_EQ(d.payloadWord(d.records[9], 2), 1u);

    const fs::path p = tempPath("writer.ppdmp");
    std::string err;
    ASSERT_TRUE(w.save(p.string(), err)) << err;
    Dump back;
    ASSERT_TRUE(loadDump(p.string(), back, err)) << err;
    EXPECT_EQ(back.version, 6u);
    EXPECT_EQ(back.gameId, "TEST00001");
    ASSERT_EQ(back.records, d.records);
    for (const Record& r : back.records) {
        const u8* a = back.payload(r);
        const u8* b = d.payload(r);
        ASSERT_NE(a, nullptr);
        ASSERT_NE(b, nullptr);
        EXPECT_EQ(std::memcmp(a, b, r.size), 0) << recordTypeName(r.type);
    }
    EXPECT_EQ(std::memcmp(back.payload(back.records[4]), verts, 6), 0);
    EXPECT_EQ(std::memcmp(back.payload(back.records[3]), tex.data(), tex.size()), 0);
    std::error_code ec;
    fs::remove(p, ec);
}

TEST(DumpWriterTest, FixedLayoutRecords) {
    DumpWriter w;
    EXPECT_EQ(w.dump().gameId, "GE2GL0001");
    const u8 texel[4] = {9, 8, 7, 6};
    w.framebufTexture(2, 0x04088000, 512, 4, texel, 4);
    w.clutAddr(0x04100000, 1);
    w.clut(texel, 4);
    w.transferSrc(texel, 4);
    w.memset(0x04000000, 0xAB, 0x1000);
    w.memcpy(0x04110000, texel, 3);
    w.edramTrans(0x400);
    const Dump& d = w.dump();
    ASSERT_EQ(d.records.size(), 8u);
    // FRAMEBUFn: header u32 address, s32 bufw, u32 flags, u32 0, then the data (ppdmp.md §3.2).
    EXPECT_EQ(d.records[0].type, FRAMEBUF0 + 2);
    EXPECT_EQ(d.records[0].size, 20u);
    EXPECT_EQ(d.payloadWord(d.records[0], 0), 0x04088000u);
    EXPECT_EQ(d.payloadWord(d.records[0], 1), 512u);
    EXPECT_EQ(d.payloadWord(d.records[0], 2), 4u);
    EXPECT_EQ(d.payloadWord(d.records[0], 3), 0u);
    EXPECT_EQ(d.payloadWord(d.records[0], 4), 0x06070809u);
    EXPECT_EQ(d.records[1], (Record{CLUTADDR, 8, d.records[1].ptr}));
    EXPECT_EQ(d.payloadWord(d.records[1], 0), 0x04100000u);
    EXPECT_EQ(d.payloadWord(d.records[1], 1), 1u);
    EXPECT_EQ(d.records[2].type, CLUT);
    EXPECT_EQ(d.records[2].ptr % 16, 0u);
    EXPECT_EQ(d.records[3].ptr, d.records[2].ptr);  // identical bytes, identical alignment: shared
    EXPECT_EQ(d.records[3].type, TRANSFERSRC);
    EXPECT_EQ(d.records[4].type, MEMSET);
    EXPECT_EQ(d.payloadWord(d.records[4], 0), 0x04000000u);
    EXPECT_EQ(d.payloadWord(d.records[4], 1), 0xABu);
    EXPECT_EQ(d.payloadWord(d.records[4], 2), 0x1000u);
    EXPECT_EQ(d.records[5].type, MEMCPYDEST);
    EXPECT_EQ(d.payloadWord(d.records[5], 0), 0x04110000u);
    EXPECT_EQ(d.records[6].type, MEMCPYDATA);
    EXPECT_EQ(d.records[6].size, 3u);
    EXPECT_EQ(d.payload(d.records[6])[2], 7);
    EXPECT_EQ(d.records[7].type, EDRAMTRANS);
    EXPECT_EQ(d.payloadWord(d.records[7], 0), 0x400u);
    EXPECT_THROW(w.texture(8, texel, 4), std::invalid_argument);
    EXPECT_THROW(w.framebufTexture(-1, 0, 0, 0, texel, 4), std::invalid_argument);
    EXPECT_THROW(w.vertices(nullptr, 4), std::invalid_argument);
}

// ---- the frametest dumps ----------------------------------------------------------------------

namespace {

// ppdmp.md §5: the 209 opcodes saved in words 17–225 of INIT, in order.
std::vector<u32> initOpcodes() {
    const std::pair<u32, u32> ranges[] = {{0x00, 0x02}, {0x10, 0x10}, {0x12, 0x28}, {0x2C, 0x33}, {0x36, 0x38},
                                          {0x42, 0x4D}, {0x50, 0x51}, {0x53, 0x58}, {0x5B, 0xB5}, {0xB8, 0xC3},
                                          {0xC5, 0xD0}, {0xD2, 0xE9}, {0xEB, 0xEC}, {0xEE, 0xEE}, {0xF0, 0xF6},
                                          {0xF8, 0xF9}};
    std::vector<u32> ops;
    for (auto [a, b] : ranges)
        for (u32 op = a; op <= b; ++op) ops.push_back(op);
    return ops;
}

}  // namespace

TEST(DumpFrametests, AllLoad) {
    const auto zips = frametestZips();
    if (zips.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    const std::vector<u32> ops = initOpcodes();
    ASSERT_EQ(ops.size(), 209u);
    for (const fs::path& z : zips) {
        SCOPED_TRACE(z.filename().string());
        Dump d;
        std::string err;
        ASSERT_TRUE(loadDump(z.string(), d, err)) << err;
        std::map<std::string, int> counts;
        size_t outOfRange = 0;
        for (const Record& r : d.records) {
            ++counts[recordTypeName(r.type)];
            if (!d.payload(r)) ++outOfRange;
        }
        std::printf("  %-60s v%u %-9s records=%-6zu push=%-8zu REGISTERS=%d VERTICES=%d INDICES=%d DISPLAY=%d\n",
                    z.filename().string().c_str(), d.version, d.gameId.c_str(), d.records.size(), d.pushbuf.size(),
                    counts["REGISTERS"], counts["VERTICES"], counts["INDICES"], counts["DISPLAY"]);
        EXPECT_GE(d.version, 2u);
        EXPECT_LE(d.version, 6u);
        if (d.version >= 4) {
            EXPECT_EQ(d.gameId.size(), 9u) << "game ID present for v>=4";
        } else {
            EXPECT_TRUE(d.gameId.empty());
        }
        ASSERT_FALSE(d.records.empty());
        EXPECT_EQ(outOfRange, 0u);
        for (const Record& r : d.records) EXPECT_TRUE(isKnownRecordType(r.type)) << recordTypeName(r.type);
        EXPECT_EQ(d.records.back().type, DISPLAY);  // ppdmp.md §4: the frame to show ends every sample dump

        // ppdmp.md §5: INIT first, 2048 bytes, with the fixed words of the context layout.
        const Record& init = d.records[0];
        ASSERT_EQ(init.type, INIT);
        ASSERT_EQ(init.size, kInitBytes);
        for (size_t i = 0; i < ops.size(); ++i)
            ASSERT_EQ(d.payloadWord(init, u32(17 + i)) >> 24, ops[i]) << "INIT word " << 17 + i;
        EXPECT_EQ(d.payloadWord(init, 226), 0x2A000000u);
        EXPECT_EQ(d.payloadWord(init, 323), 0x3A000000u);
        EXPECT_EQ(d.payloadWord(init, 336), 0x3C000000u);
        EXPECT_EQ(d.payloadWord(init, 349), 0x3E000000u);
        EXPECT_EQ(d.payloadWord(init, 366), 0x40000000u);
        EXPECT_EQ(d.payloadWord(init, 384), 0x0C000000u);
        for (u32 w = 227; w < 323; ++w) ASSERT_EQ(d.payloadWord(init, w) >> 24, 0x2Bu) << w;

        // ppdmp.md §3.2: REGISTERS hold whole words and never the replaced flow/address commands.
        for (const Record& r : d.records) {
            SCOPED_TRACE(recordTypeName(r.type));
            u32 fixedSize = 0;  // ppdmp.md §3.2 fixed payload sizes
            if (r.type == INIT) fixedSize = kInitBytes;
            if (r.type == DISPLAY || r.type == MEMSET) fixedSize = 12;
            if (r.type == MEMCPYDEST || r.type == EDRAMTRANS) fixedSize = 4;
            if (r.type == CLUTADDR) fixedSize = 8;
            if (fixedSize) {
                EXPECT_EQ(r.size, fixedSize);
            }
            if (framebufLevelOf(r.type) >= 0) {
                // FRAMEBUFn header: the original VRAM address (mirror/cache bits aside).
                EXPECT_GE(r.size, 16u);
                EXPECT_EQ(d.payloadWord(r, 0) & 0x0F000000u, 0x04000000u);
            }
            if (r.type != REGISTERS) continue;
            EXPECT_EQ(r.size % 4, 0u);
            for (u32 i = 0; i < r.size / 4; ++i) {
                const u32 op = d.payloadWord(r, i) >> 24;
                const bool replaced = op == 0x01 || op == 0x02 || op == 0x07 || (op >= 0x08 && op <= 0x0C) ||
                                      op == 0x0E || op == 0x0F || op == 0x10 || op == 0x13 || op == 0x14;
                ASSERT_FALSE(replaced) << "opcode " << op << " in REGISTERS";
            }
        }
    }
}

TEST(DumpFrametests, KnownFacts) {
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    if (!fs::is_directory(dir)) GTEST_SKIP() << "no frametest dumps";
    Dump d;
    std::string err;
    // A ".ppdmp.zip" name is a zip like any other (content decides, not the name).
    ASSERT_TRUE(loadDump((dir / "11216 Pursuit Force UCUS98703.ppdmp.zip").string(), d, err)) << err;
    EXPECT_EQ(d.version, 6u);
    EXPECT_EQ(d.gameId, "UCUS98703");
    EXPECT_EQ(d.records.size(), 19475u);
    EXPECT_EQ(d.pushbuf.size(), 2092768u);

    ASSERT_TRUE(loadDump((dir / "16866 NBA 2K13 ULUS10598_0001.zip").string(), d, err)) << err;
    EXPECT_EQ(d.gameId, "ULUS10598");
    EXPECT_EQ(d.records.size(), 6663u);

    ASSERT_TRUE(loadDump((dir / "10755 Locoroco 2 Muimui house 2 UCUS98731_0001.ppdmp.zip").string(), d, err)) << err;
    EXPECT_EQ(d.version, 3u);
    EXPECT_EQ(d.gameId, "");
    EXPECT_EQ(d.records.size(), 2516u);
    EXPECT_EQ(d.pushbuf.size(), 623392u);
    // ppdmp.md §3.1: this v3 dump has TEXTUREn payloads that are not 16-byte aligned.
    size_t misaligned = 0;
    for (const Record& r : d.records)
        if (textureLevelOf(r.type) >= 0 && r.ptr % 16 != 0) ++misaligned;
    EXPECT_GT(misaligned, 0u);

    // Zip with two dumps and two PNGs: the last .ppdmp entry (436 records) wins over the first (245).
    ASSERT_TRUE(loadDump((dir / "17397 Nova NPUZ00179_nova_culling.zip").string(), d, err)) << err;
    EXPECT_EQ(d.records.size(), 436u);
    EXPECT_EQ(d.pushbuf.size(), 2860328u);

    // Version 2 (snappy) with two entries: the last, NPJH50465_0001.ppdmp (486929 bytes).
    const std::vector<u8> zbytes = readFile(dir / "10928 Project Diva teardrops DUMP.zip");
    std::vector<u8> raw;
    std::string entry;
    ASSERT_TRUE(extractPpdmpFromZip(zbytes.data(), zbytes.size(), raw, err, &entry)) << err;
    EXPECT_EQ(entry, "NPJH50465_0001.ppdmp");
    EXPECT_EQ(raw.size(), 486929u);
    ASSERT_TRUE(loadDumpFromMemory(raw.data(), raw.size(), d, err)) << err;
    EXPECT_EQ(d.version, 2u);
    EXPECT_EQ(d.records.size(), 3900u);
    EXPECT_EQ(d.pushbuf.size(), 1008856u);
}

// Acceptance criterion: read → serialise → read gives identical records and push buffer bytes.
TEST(DumpFrametests, RoundTripAll) {
    const auto zips = frametestZips();
    if (zips.empty()) GTEST_SKIP() << "no frametest dumps in " << GE2GL_FRAMETESTS_DIR;
    for (const fs::path& z : zips) {
        SCOPED_TRACE(z.filename().string());
        Dump d;
        std::string err;
        ASSERT_TRUE(loadDump(z.string(), d, err)) << err;
        const std::vector<u8> bytes = serializeDump(d);
        ASSERT_FALSE(bytes.empty());
        Dump back;
        ASSERT_TRUE(loadDumpFromMemory(bytes.data(), bytes.size(), back, err)) << err;
        EXPECT_EQ(back.version, 6u);
        EXPECT_EQ(back.gameId, d.gameId);
        ASSERT_EQ(back.records.size(), d.records.size());
        EXPECT_TRUE(back.records == d.records);
        EXPECT_TRUE(back.pushbuf == d.pushbuf);
    }
}
