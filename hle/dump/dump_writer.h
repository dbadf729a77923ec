// SPDX-License-Identifier: MIT
// DumpWriter: authors .ppdmp dumps in the record order PPSSPP's recorder produces
// (docs/ppdmp.md §4, §7), for the project's scene generator and for tests.
//
// The caller is responsible for the order of calls (the writer does not interpret GE words):
//   init(context); display(...);                    // ppdmp.md §7 rule 3: start with INIT and a DISPLAY
//   registers({... TBWn, TSIZEn, VTYPE ...});       // state, with TBWn before TEXTUREn (ppdmp.md §7 rule 6)
//   texture(n, ...) / framebufTexture(n, ...);      // texture levels of the next draw
//   indices(...); vertices(...);                    // then the draw's geometry
//   registers({PRIM ..., next state ...});          // the kick opens the next block (ppdmp.md §7 rule 5)
//   ...
//   display(...);                                   // ppdmp.md §7 rule 3: the very last record
//
// Payload alignment in the push buffer follows ppdmp.md §3.1/§7 rule 7: 4 for REGISTERS, VERTICES and INDICES,
// 16 for TEXTUREn, FRAMEBUFn, CLUT and TRANSFERSRC, 1 for everything else. Identical payloads
// are stored once (records then share a ptr, as PPSSPP's writer does), except REGISTERS, and
// consecutive registers() calls are merged into one block, because a REGISTERS block always
// runs up to the next data record (ppdmp.md §4).
//
// Misuse (a texture level outside 0–7, a null pointer with a non-zero size, a push buffer that
// would exceed the 1 GiB the reader accepts) throws std::invalid_argument / std::length_error;
// these are programming errors of the caller, not data errors.
#pragma once
#include <string>
#include <unordered_map>
#include <vector>

#include "hle/dump/ppdmp.h"

namespace ge::dump {

class DumpWriter {
public:
    explicit DumpWriter(std::string gameId = "GE2GL0001");

    void init(const u32 context[512]);               // INIT record (2048 bytes, ppdmp.md §5)
    void display(u32 addr, u32 stride, u32 format);  // DISPLAY record (12 bytes)
    void registers(const std::vector<u32>& words);   // REGISTERS block (state + kick words)
    void vertices(const void* data, u32 size);       // VERTICES (4-aligned)
    void indices(const void* data, u32 size);        // INDICES (4-aligned)
    void texture(int level, const void* data, u32 size);  // TEXTUREn (16-aligned)
    // FRAMEBUFn: 16-byte header (u32 VRAM address, s32 bufw, u32 flags ppdmp.md §3.3, u32 0) + data.
    void framebufTexture(int level, u32 vramAddr, u32 bufw, u32 flags, const void* data, u32 size);
    void clut(const void* data, u32 size);      // CLUT (16-aligned)
    void clutAddr(u32 vramAddr, u32 flags);     // CLUTADDR (8 bytes), before a VRAM CLUT record
    void transferSrc(const void* data, u32 size);  // TRANSFERSRC (16-aligned)
    void memset(u32 dest, u8 value, u32 size);  // MEMSET (12 bytes: dest, s32 value, size)
    void memcpy(u32 dest, const void* data, u32 size);  // MEMCPYDEST + MEMCPYDATA
    void edramTrans(u32 value);                 // EDRAMTRANS (4 bytes)

    const Dump& dump() const { return m_dump; }
    bool save(const std::string& path, std::string& err) const { return saveDump(path, m_dump, err); }

private:
    // Appends (or reuses) a payload and records it.
    void add(u8 type, const void* data, u32 size, u32 align, bool dedup);
    u32 placePayload(const u8* data, u32 size, u32 align, bool dedup);

    Dump m_dump;
    struct Stored {
        u32 ptr;
        u32 size;
    };
    // Content hash → payloads already in the push buffer with that hash (candidates for reuse;
    // a hit is confirmed by comparing the bytes).
    std::unordered_multimap<u64, Stored> m_seen;
};

}  // namespace ge::dump
