// SPDX-License-Identifier: MIT
// Harness (a): the .ppdmp / zip loader from bytes (hle/dump/ppdmp.h).
//
// Every input must either fail with a message or give a Dump whose payload() answers lie inside
// the push buffer; a loaded dump must serialise and load back to the same records and payloads,
// and summarize() and the disassembler must take any REGISTERS word.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "hle/disasm.h"
#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;
using namespace ge::dump;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_ppdmp_load: %s\n", what);
    __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    const bool zip = size >= 2 && data[0] == 'P' && data[1] == 'K';
    Dump d;
    std::string err;
    const bool ok = zip ? loadZipFromMemory(data, size, d, err) : loadDumpFromMemory(data, size, d, err);
    if (zip) {
        // The raw-entry path must agree with the zip loader about whether there is an entry.
        std::vector<u8> raw;
        std::string err2;
        if (extractPpdmpFromZip(data, size, raw, err2) && raw.size() <= fuzz::kMaxInput) {
            Dump e;
            std::string err3;
            if (loadDumpFromMemory(raw.data(), raw.size(), e, err3) != ok) fail("zip and raw entry disagree");
        }
    }
    if (!ok) {
        if (err.empty()) fail("load failed without a message");
        return 0;
    }
    if (d.version < kMinVersion || d.version > kMaxVersion) fail("loaded an unsupported version");
    if (d.gameId.size() > kGameIdBytes) fail("game ID longer than 9 bytes");
    u64 sum = 0;
    size_t words = 0;
    for (const Record& r : d.records) {
        (void)recordTypeName(r.type);
        const u8* p = d.payload(r);
        if (p != nullptr) {
            if (!d.payloadInRange(r)) fail("payload() outside payloadInRange()");
            if (r.size) sum += u64(p[0]) + p[r.size - 1];  // ASan checks both ends
        } else if (d.payloadInRange(r)) {
            fail("payload() null for an in-range record");
        }
        sum += d.payloadWord(r, 0) + d.payloadWord(r, 2) + d.payloadWord(r, ~0u);
        if (r.type == REGISTERS && p) {
            for (u32 i = 0; i + 4 <= r.size && words < 4096; i += 4, ++words) sum += disassemble(readLE32(p + i)).size();
        }
    }
    const DumpSummary s = summarize(d);
    sum += s.commands + s.draws;
    // Round trip through the v6 writer (small dumps: level-6 zstd of a large push buffer is slow).
    if (d.pushbuf.size() + d.records.size() * kRecordBytes <= (size_t(4) << 20)) {
        const std::vector<u8> bytes = serializeDump(d);
        if (bytes.empty()) fail("a loaded dump does not serialise");
        Dump e;
        if (!loadDumpFromMemory(bytes.data(), bytes.size(), e, err)) fail(("reload: " + err).c_str());
        if (e.records != d.records || e.pushbuf != d.pushbuf) fail("round trip changed records or payloads");
    }
    volatile u64 sink = sum;
    (void)sink;
    return 0;
}
