// SPDX-License-Identifier: MIT
// Reader and writer for PPSSPP's `.ppdmp` GE frame dumps (docs/ppdmp.md §1–§3, §5, §7).
//
// A dump is a header, an array of 9-byte records and one "push buffer" byte array that the
// records point into. This module only moves bytes: it decompresses/compresses the two blocks,
// checks every size taken from the file, and hands out payloads by range. Interpreting records
// (placing payloads in guest memory, building the display list) is the player's job (ppdmp.md §6).
//
// Nothing read from a file is trusted: sizes are capped before allocating, blocks must be
// complete, and a record whose payload range lies outside the push buffer loads fine but
// Dump::payload() returns nullptr for it (PPSSPP also only notices such records when it plays
// them).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "hle/types.h"

namespace ge::dump {

// Record types (ppdmp.md §3.2). TEXTUREn = TEXTURE0 + n, FRAMEBUFn = FRAMEBUF0 + n.
enum RecordType : u8 {
    INIT = 0,
    REGISTERS = 1,
    VERTICES = 2,
    INDICES = 3,
    CLUT = 4,
    TRANSFERSRC = 5,
    MEMSET = 6,
    MEMCPYDEST = 7,
    MEMCPYDATA = 8,
    DISPLAY = 9,
    CLUTADDR = 10,
    EDRAMTRANS = 11,
    TEXTURE0 = 0x10,  // .. 0x17
    FRAMEBUF0 = 0x18, // .. 0x1F
};

// "INIT", "TEXTURE3", "FRAMEBUF7", or "UNKNOWN_0C" for types the format does not define.
// The returned string is a constant with static storage.
const char* recordTypeName(u8 type);
// True for 0–11 and 0x10–0x1F (the types PPSSPP's player accepts, ppdmp.md §3.2).
bool isKnownRecordType(u8 type);
// TEXTUREn / FRAMEBUFn helpers: the level n, or -1 when the type is neither.
inline int textureLevelOf(u8 type) { return (type >= TEXTURE0 && type < TEXTURE0 + 8) ? type - TEXTURE0 : -1; }
inline int framebufLevelOf(u8 type) { return (type >= FRAMEBUF0 && type < FRAMEBUF0 + 8) ? type - FRAMEBUF0 : -1; }

// One 9-byte record (ppdmp.md §3.1): payload is push[ptr, ptr + size).
struct Record {
    u8 type = 0;
    u32 size = 0;
    u32 ptr = 0;
    friend bool operator==(const Record&, const Record&) = default;
};

// Limits on what one frame's dump can legitimately hold, applied to everything read from a file
// (a header's sizes are refused above them before anything is allocated, and decompression stops
// at them whatever the compressed stream says). A frame reads at most the PSP's 32/64 MiB of RAM
// and 2 MiB of VRAM; the 20 real frametests hold at most 3.5 MB of payloads and 22,069 records,
// and the heaviest PSP frames carry about 10,700 draws (a handful of records each).
inline constexpr u64 kMaxPushbufBytes = u64(256) << 20;  // 256 MiB of payloads
inline constexpr u64 kMaxRecords = u64(2) << 20;         // 2,097,152 records (18 MiB)
inline constexpr u64 kMaxBlockBytes = kMaxPushbufBytes;  // any one decompressed block
inline constexpr u64 kMaxFileBytes = u64(256) << 20;     // a .ppdmp file, or the entry taken from a .zip
inline constexpr u32 kRecordBytes = 9;               // ppdmp.md §3.1
inline constexpr u32 kInitBytes = 2048;              // ppdmp.md §5: 512 words
inline constexpr u32 kMinVersion = 2;                // ppdmp.md §2.1: version 1 is not loadable
inline constexpr u32 kMaxVersion = 6;
inline constexpr u32 kWriteVersion = 6;              // ppdmp.md §7
inline constexpr size_t kGameIdBytes = 9;            // ppdmp.md §2

struct Dump {
    u32 version = kWriteVersion;
    std::string gameId;  // up to 9 chars (v≥4 files); empty for v2–3
    std::vector<Record> records;
    std::vector<u8> pushbuf;

    // True when [ptr, ptr + size) lies inside the push buffer (computed without overflow).
    bool payloadInRange(const Record& r) const;
    // Payload bytes of a record, or nullptr when [ptr, ptr + size) is outside pushbuf. A
    // zero-sized record at a valid offset gives a non-null pointer that must not be read.
    // Payloads may be misaligned (old dumps, ppdmp.md §3.1): copy them out, do not cast in place.
    const u8* payload(const Record& r) const;
    // The i-th little-endian u32 of a payload, or `fallback` when it is outside the payload or
    // the payload is outside the push buffer. Handy for the small fixed-layout records
    // (DISPLAY, MEMSET, CLUTADDR, FRAMEBUF header, EDRAMTRANS).
    u32 payloadWord(const Record& r, u32 index, u32 fallback = 0) const;
};

// Loads a .ppdmp file or a .zip holding one (the last entry whose lower-cased name ends in
// ".ppdmp", skipping "__macosx/", ppdmp.md §1). The container is recognised by content (the PPSSPPGE
// magic or a zip signature), not by the file name. Versions 2–6 (snappy for 2–4, zstd for 5–6).
// Returns false with a one-line human error (e.g. "truncated command block", "unsupported
// version 1", "bad magic") on any problem; `out` is then left empty-initialised.
bool loadDump(const std::string& path, Dump& out, std::string& err);
// Raw .ppdmp bytes.
bool loadDumpFromMemory(const u8* data, size_t size, Dump& out, std::string& err);
// Zip bytes.
bool loadZipFromMemory(const u8* data, size_t size, Dump& out, std::string& err);
// Extracts the raw .ppdmp bytes from zip bytes (same entry choice as loadZipFromMemory).
bool extractPpdmpFromZip(const u8* data, size_t size, std::vector<u8>& out, std::string& err,
                         std::string* entryName = nullptr);

// Serialises as version 6 (ppdmp.md §7): header with the game ID (truncated to 9 bytes, NUL-padded),
// then each block as u32 compressed size + one zstd frame (level 6, with content size).
// Returns an empty vector when the dump cannot be expressed (a block over kMaxBlockBytes, which
// no reader would accept) or compression fails.
std::vector<u8> serializeDump(const Dump& d);
bool saveDump(const std::string& path, const Dump& d, std::string& err);

}  // namespace ge::dump
