// SPDX-License-Identifier: MIT
// Seeded mutations of real .ppdmp dumps (scripts/fuzz_mutate.sh, docs/fuzzing.md "Mutation fuzzing
// of real dumps"). Coverage-guided fuzzing (tests/fuzz/) starts from small pieces of frames; this
// takes whole recorded frames and changes a few things in them — GE words inside REGISTERS
// payloads, record fields, payload bytes, the record list (duplicates, deletions, truncation) —
// so that what follows a mutation is a real game's frame, with its draws, textures and transfers.
//
// A mutant is a function of (dump, seed) alone: the generator is splitmix64 with integer
// arithmetic of our own (no standard-library distribution, whose results differ between library
// implementations), so a seed reproduces its mutant on any machine.
#pragma once
#include <string>
#include <vector>

#include "hle/dump/ppdmp.h"

namespace ge::tools {

// splitmix64: the whole state is one u64.
class MutationRng {
public:
    explicit MutationRng(u64 seed) : s_(seed) {}
    u64 next() {
        u64 z = (s_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // [0, n); n > 0. The modulo bias is irrelevant here and keeps the sequence portable.
    u64 below(u64 n) { return next() % n; }
    bool chance(u32 percent) { return below(100) < percent; }

private:
    u64 s_;
};

struct Mutant {
    dump::Dump dump;                 // the mutated dump
    std::vector<std::string> steps;  // one line per mutation applied, for the failure log
    // When non-zero: the serialized file is cut to truncate/65536 of its length (a truncated
    // download); the dump above is what was serialized.
    u32 truncate = 0;
};

// Applies 1–4 mutations chosen by `seed` to a copy of `d`.
Mutant mutateDump(const dump::Dump& d, u64 seed);

// The mutant as the bytes of a .ppdmp file (version 6, docs/ppdmp.md §7), truncated when the
// mutant says so; empty when the dump cannot be serialized.
std::vector<u8> mutantFile(const Mutant& m);

}  // namespace ge::tools
