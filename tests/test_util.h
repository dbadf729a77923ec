// SPDX-License-Identifier: MIT
// Small helpers shared by test files.
#pragma once
#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "hle/dump/ppdmp.h"

// The real game dumps (../shared/frametests/dumps), sorted; empty when the folder is absent.
inline std::vector<std::string> frametestDumps() {
    std::vector<std::string> out;
    std::filesystem::path dir = std::filesystem::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return out;
    for (auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

// Mutates a dump at random: REGISTERS words (including flow-control opcodes with wild
// arguments), record types, sizes and pointers, and payload bytes.
inline void mutateDump(ge::dump::Dump& d, std::mt19937& rng, int edits) {
    std::uniform_int_distribution<ge::u32> any;
    for (int e = 0; e < edits && !d.records.empty(); ++e) {
        ge::dump::Record& r = d.records[any(rng) % d.records.size()];
        switch (any(rng) % 6) {
        case 0: r.type = ge::u8(any(rng) % 0x20); break;
        case 1: r.size = any(rng) % 3 ? any(rng) % 0x10000 : any(rng); break;
        case 2: r.ptr = any(rng) % (ge::u32(d.pushbuf.size()) + 64); break;
        default: {
            if (d.pushbuf.empty()) break;
            static const ge::u8 ops[] = {0x08, 0x09, 0x0A, 0x0B, 0x0C, 0x0E, 0x0F, 0x10, 0x13, 0x14, 0x04, 0x05,
                                     0x06, 0x07, 0xC4, 0xEA, 0x01, 0x02, 0x12, 0xF7, 0x12, 0xB8, 0xA8, 0xC3,
                                         0xC2, 0x9C, 0x9D, 0x9E, 0x36, 0xC5, 0xC8, 0xD2, 0x04, 0x2B, 0xF0};
            size_t at = any(rng) % d.pushbuf.size() & ~size_t(3);
            if (at + 4 > d.pushbuf.size()) break;
            ge::u32 w = (ge::u32(ops[any(rng) % sizeof ops]) << 24) | (any(rng) & 0xFFFFFF);
            ge::writeLE32(&d.pushbuf[at], w);
            break;
        }
        }
    }
}

