// SPDX-License-Identifier: MIT
// Seeded mutations of real dumps (see mutate.h).
#include "tools/lib/mutate.h"

#include <algorithm>
#include <cstdio>

#include "hle/ge_state.h"

namespace ge::tools {

namespace {

using dump::Record;

std::string hex(u64 v) {
    char b[24];
    std::snprintf(b, sizeof b, "0x%llx", (unsigned long long)v);
    return b;
}

// Opcodes whose arguments decide how much work a frame asks for or where the list goes: draws
// and their sizes, flow control, addresses, buffer and texture geometry, transfers, patches
// (docs/ge-rules.md §2). A random opcode mostly lands on a harmless state register; these are
// drawn more often.
constexpr u8 kHeavyOps[] = {
    GE_CMD_PRIM,   GE_CMD_BEZIER, GE_CMD_SPLINE,   GE_CMD_BBOX,     GE_CMD_JUMP,    GE_CMD_BJUMP,  GE_CMD_CALL,
    GE_CMD_RET,    GE_CMD_END,    GE_CMD_SIGNAL,   GE_CMD_FINISH,   GE_CMD_BASE,    GE_CMD_VTYPE,  GE_CMD_OFFSET,
    GE_CMD_ORIGIN, GE_CMD_VADR,   GE_CMD_IADR,     GE_CMD_REGION1,  GE_CMD_REGION2, GE_CMD_DIVIDE, GE_CMD_PPM,
    GE_CMD_FBP,    GE_CMD_FBW,    GE_CMD_ZBP,      GE_CMD_ZBW,      GE_CMD_TBW0,    GE_CMD_TSIZE0, GE_CMD_TMODE,
    GE_CMD_TPF,    GE_CMD_CLOAD,  GE_CMD_CLUT,     GE_CMD_TLEVEL,   GE_CMD_FPF,     GE_CMD_SCISSOR1, GE_CMD_SCISSOR2,
    GE_CMD_XSTART, GE_CMD_XBW1,   GE_CMD_XBW2,     GE_CMD_XPOS1,    GE_CMD_XPOS2,   GE_CMD_XSIZE,  GE_CMD_SX,
    GE_CMD_SY,     GE_CMD_TX,     GE_CMD_TY,       GE_CMD_PROJD,    GE_CMD_WORLDD,  GE_CMD_BONED,  GE_CMD_AP2,
};

u32 interestingArg(MutationRng& rng) {
    static constexpr u32 k[] = {0, 1, 2, 3, 0xFFFFFF, 0x7FFFFF, 0x800000, 0xFFFF, 0x10000, 0x3FF, 0x400, 0x1000, 0xFF};
    return rng.chance(50) ? k[rng.below(sizeof k / sizeof k[0])] : u32(rng.next() & 0xFFFFFF);
}

std::vector<size_t> recordsOf(const dump::Dump& d, bool (*pick)(const Record&)) {
    std::vector<size_t> out;
    for (size_t i = 0; i < d.records.size(); ++i)
        if (pick(d.records[i]) && d.payloadInRange(d.records[i])) out.push_back(i);
    return out;
}

// A GE word inside a REGISTERS payload (docs/ppdmp.md §3.2): a new argument, a new opcode, a
// flipped bit, a word of random bits, or one of the heavy opcodes; sometimes a run of words.
bool mutateGeWord(dump::Dump& d, MutationRng& rng, std::string& step) {
    const auto regs = recordsOf(d, [](const Record& r) { return r.type == dump::REGISTERS && r.size >= 4; });
    if (regs.empty()) return false;
    const Record& r = d.records[regs[rng.below(regs.size())]];
    const u32 words = r.size / 4;
    const u32 run = rng.chance(80) ? 1 : u32(1 + rng.below(8));
    const u32 first = u32(rng.below(words));
    step = "GE words in REGISTERS @" + hex(r.ptr) + ":";
    for (u32 k = 0; k < run && first + k < words; ++k) {
        u8* at = d.pushbuf.data() + r.ptr + 4 * (first + k);
        const u32 old = readLE32(at);
        u32 w = old;
        switch (rng.below(5)) {
            case 0: w = (old & 0xFF000000u) | interestingArg(rng); break;
            case 1: w = (u32(rng.below(256)) << 24) | (old & 0xFFFFFF); break;
            case 2: w = old ^ (1u << rng.below(32)); break;
            case 3: w = u32(rng.next()); break;
            default: w = (u32(kHeavyOps[rng.below(sizeof kHeavyOps)]) << 24) | interestingArg(rng); break;
        }
        writeLE32(at, w);
        step += " [" + std::to_string(first + k) + "] " + hex(old) + "->" + hex(w);
    }
    return true;
}

// A record's type, size or offset (docs/ppdmp.md §3.1).
bool mutateRecordField(dump::Dump& d, MutationRng& rng, std::string& step) {
    if (d.records.size() < 2) return false;
    const size_t i = 1 + rng.below(d.records.size() - 1);  // INIT stays: without it nothing replays
    Record& r = d.records[i];
    const Record old = r;
    const u64 push = d.pushbuf.size();
    switch (rng.below(7)) {
        case 0: {
            static constexpr u8 types[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 0x10, 0x13, 0x17, 0x18, 0x1F, 0x0C, 0x20, 0xFF};
            r.type = types[rng.below(sizeof types)];
            break;
        }
        case 1: r.size = u32(rng.below(push + 1)); break;
        case 2: r.size = rng.chance(50) ? r.size * 2 + 4 : r.size / 2; break;
        case 3: r.size = u32(rng.next()); break;
        case 4: r.ptr = u32(rng.below(push + 1)); break;
        case 5: r.ptr = u32(rng.next()); break;
        default: r.ptr = u32(std::min<u64>(push, r.ptr + 4 * rng.below(64))); break;
    }
    step = "record " + std::to_string(i) + " " + dump::recordTypeName(old.type) + " (size " + hex(old.size) + ", ptr " +
           hex(old.ptr) + ") -> type " + dump::recordTypeName(r.type) + ", size " + hex(r.size) + ", ptr " + hex(r.ptr);
    return true;
}

// Bytes of a data payload: vertices, indices, textures, palettes, transfer sources, the small
// fixed-layout records (DISPLAY, MEMSET, CLUTADDR, FRAMEBUF header, EDRAMTRANS) and INIT.
bool mutatePayloadBytes(dump::Dump& d, MutationRng& rng, std::string& step) {
    const auto data = recordsOf(d, [](const Record& r) { return r.type != dump::REGISTERS && r.size > 0; });
    if (data.empty()) return false;
    const Record& r = d.records[data[rng.below(data.size())]];
    u8* p = d.pushbuf.data() + r.ptr;
    step = std::string("payload of ") + dump::recordTypeName(r.type) + " @" + hex(r.ptr) + ":";
    if (rng.chance(50) || r.size < 16) {
        // A whole u32 of the payload (the fixed-layout records are words).
        const u32 at = u32(rng.below(std::max<u32>(r.size / 4, 1))) * 4;
        if (at + 4 > r.size) return false;
        static constexpr u32 k[] = {0, 0xFFFFFFFFu, 0x80000000u, 0x7FFFFFFFu, 0x04000000u, 0x08800000u, 0x04200000u, 1u << 20};
        const u32 w = rng.chance(50) ? k[rng.below(sizeof k / sizeof k[0])] : u32(rng.next());
        char b[80];
        std::snprintf(b, sizeof b, " word %u 0x%x->0x%x", at / 4, readLE32(p + at), w);
        step += b;
        writeLE32(p + at, w);
    } else {
        const u32 n = u32(1 + rng.below(16));
        for (u32 k = 0; k < n; ++k) p[rng.below(r.size)] = u8(rng.next());
        // Appended piece by piece: GCC 12's -Wrestrict misreads `" " + std::to_string(n)` (GCC bug 105329).
        step += ' ';
        step += std::to_string(n);
        step += " random bytes";
    }
    return true;
}

// The record list: duplicated records or runs of them, deletions, swaps, truncation.
bool mutateRecordList(dump::Dump& d, MutationRng& rng, std::string& step) {
    auto& recs = d.records;
    if (recs.size() < 3) return false;
    const size_t n = recs.size();
    switch (rng.below(5)) {
        case 0:
        case 1: {
            // A run of 1–8 records repeated 2–2,000 times (docs/ppdmp.md §3.1: records may share payloads).
            const size_t at = 1 + rng.below(n - 1), len = std::min<size_t>(n - at, 1 + rng.below(8));
            const size_t times = rng.chance(70) ? 2 + rng.below(8) : 2 + rng.below(2000);
            if (n + len * times > dump::kMaxRecords) return false;
            const std::vector<Record> run(recs.begin() + std::ptrdiff_t(at), recs.begin() + std::ptrdiff_t(at + len));
            for (size_t t = 0; t < times; ++t) recs.insert(recs.begin() + std::ptrdiff_t(at), run.begin(), run.end());
            step = "records " + std::to_string(at) + ".." + std::to_string(at + len - 1) + " repeated " +
                   std::to_string(times) + " more times";
            return true;
        }
        case 2: {
            const size_t at = 1 + rng.below(n - 1), len = std::min<size_t>(n - at, 1 + rng.below(16));
            recs.erase(recs.begin() + std::ptrdiff_t(at), recs.begin() + std::ptrdiff_t(at + len));
            step = "records " + std::to_string(at) + ".." + std::to_string(at + len - 1) + " deleted";
            return true;
        }
        case 3: {
            const size_t a = 1 + rng.below(n - 1), b = 1 + rng.below(n - 1);
            std::swap(recs[a], recs[b]);
            step = "records " + std::to_string(a) + " and " + std::to_string(b) + " swapped";
            return true;
        }
        default: {
            const size_t keep = 1 + rng.below(n - 1);
            recs.resize(keep);
            step = "record list cut to " + std::to_string(keep) + " of " + std::to_string(n);
            return true;
        }
    }
}

}  // namespace

Mutant mutateDump(const dump::Dump& d, u64 seed) {
    Mutant m;
    m.dump = d;
    MutationRng rng(seed);
    const int count = int(1 + rng.below(4));
    for (int i = 0, tries = 0; i < count && tries < 64; ++tries) {
        std::string step;
        const u64 kind = rng.below(100);
        bool done;
        if (kind < 45) done = mutateGeWord(m.dump, rng, step);
        else if (kind < 62) done = mutateRecordField(m.dump, rng, step);
        else if (kind < 80) done = mutatePayloadBytes(m.dump, rng, step);
        else done = mutateRecordList(m.dump, rng, step);
        if (!done) continue;
        m.steps.push_back(step);
        ++i;
    }
    // One mutant in 32 is also a cut file (which the loader must refuse cleanly).
    if (rng.below(32) == 0) m.truncate = u32(1 + rng.below(65535));
    return m;
}

std::vector<u8> mutantFile(const Mutant& m) {
    std::vector<u8> f = dump::serializeDump(m.dump);
    if (m.truncate) f.resize(size_t(u64(f.size()) * m.truncate / 65536));
    return f;
}

}  // namespace ge::tools
