// SPDX-License-Identifier: MIT
// DumpWriter: see dump_writer.h and docs/ppdmp.md §4, §7.
#include "hle/dump/dump_writer.h"

#include <xxhash.h>

#include <cstring>
#include <stdexcept>

namespace ge::dump {

namespace {

// ppdmp.md §3.1 / §7 rule 7 alignment of payload offsets in the push buffer.
constexpr u32 kAlignWords = 4;    // REGISTERS, VERTICES, INDICES
constexpr u32 kAlignData = 16;    // TEXTUREn, FRAMEBUFn, CLUT, TRANSFERSRC
constexpr u32 kAlignNone = 1;     // small fixed records, MEMCPYDATA

void checkLevel(int level) {
    if (level < 0 || level > 7) throw std::invalid_argument("DumpWriter: texture level must be 0-7");
}

void checkData(const void* data, u32 size) {
    if (!data && size) throw std::invalid_argument("DumpWriter: null data with non-zero size");
}

}  // namespace

DumpWriter::DumpWriter(std::string gameId) {
    m_dump.version = kWriteVersion;
    if (gameId.size() > kGameIdBytes) gameId.resize(kGameIdBytes);  // ppdmp.md §2: 9 bytes in the header
    m_dump.gameId = std::move(gameId);
}

u32 DumpWriter::placePayload(const u8* data, u32 size, u32 align, bool dedup) {
    std::vector<u8>& push = m_dump.pushbuf;
    u64 hash = 0;
    if (dedup && size) {
        hash = XXH3_64bits(data, size);
        auto [lo, hi] = m_seen.equal_range(hash);
        for (auto it = lo; it != hi; ++it) {
            const Stored& s = it->second;
            if (s.size == size && s.ptr % align == 0 && std::memcmp(push.data() + s.ptr, data, size) == 0)
                return s.ptr;
        }
    }
    const u64 start = (u64(push.size()) + align - 1) / align * align;
    if (start + size > kMaxBlockBytes)
        throw std::length_error("DumpWriter: push buffer would exceed the 1 GiB a reader accepts");
    push.resize(size_t(start), 0);  // zero padding up to the alignment
    push.insert(push.end(), data, data + size);
    if (dedup && size) m_seen.emplace(hash, Stored{u32(start), size});
    return u32(start);
}

void DumpWriter::add(u8 type, const void* data, u32 size, u32 align, bool dedup) {
    checkData(data, size);
    if (u64(m_dump.records.size()) + 1 > kMaxRecords)
        throw std::length_error("DumpWriter: too many records");
    const u32 ptr = placePayload(static_cast<const u8*>(data), size, align, dedup);
    m_dump.records.push_back(Record{type, size, ptr});
}

void DumpWriter::init(const u32 context[512]) {
    if (!context) throw std::invalid_argument("DumpWriter: null context");
    u8 bytes[kInitBytes];
    for (u32 i = 0; i < kInitBytes / 4; ++i) writeLE32(bytes + i * 4, context[i]);
    add(INIT, bytes, kInitBytes, kAlignWords, true);
}

void DumpWriter::display(u32 addr, u32 stride, u32 format) {
    u8 bytes[12];
    writeLE32(bytes, addr);
    writeLE32(bytes + 4, stride);
    writeLE32(bytes + 8, format);
    add(DISPLAY, bytes, sizeof(bytes), kAlignNone, true);
}

void DumpWriter::registers(const std::vector<u32>& words) {
    if (words.empty()) return;
    std::vector<u8> bytes(words.size() * 4);
    for (size_t i = 0; i < words.size(); ++i) writeLE32(bytes.data() + i * 4, words[i]);
    // A REGISTERS block runs until the next data record (ppdmp.md §4), so back-to-back calls extend the
    // previous block. Register blocks are never shared, so the last one ends the push buffer.
    if (!m_dump.records.empty()) {
        Record& last = m_dump.records.back();
        if (last.type == REGISTERS && u64(last.ptr) + last.size == m_dump.pushbuf.size()) {
            if (u64(m_dump.pushbuf.size()) + bytes.size() > kMaxBlockBytes)
                throw std::length_error("DumpWriter: push buffer would exceed the 1 GiB a reader accepts");
            m_dump.pushbuf.insert(m_dump.pushbuf.end(), bytes.begin(), bytes.end());
            last.size += u32(bytes.size());
            return;
        }
    }
    if (bytes.size() > kMaxBlockBytes) throw std::length_error("DumpWriter: REGISTERS block too large");
    add(REGISTERS, bytes.data(), u32(bytes.size()), kAlignWords, false);
}

void DumpWriter::vertices(const void* data, u32 size) { add(VERTICES, data, size, kAlignWords, true); }

void DumpWriter::indices(const void* data, u32 size) { add(INDICES, data, size, kAlignWords, true); }

void DumpWriter::texture(int level, const void* data, u32 size) {
    checkLevel(level);
    add(u8(TEXTURE0 + level), data, size, kAlignData, true);
}

void DumpWriter::framebufTexture(int level, u32 vramAddr, u32 bufw, u32 flags, const void* data, u32 size) {
    checkLevel(level);
    checkData(data, size);
    if (u64(size) + 16 > kMaxBlockBytes) throw std::length_error("DumpWriter: FRAMEBUF payload too large");
    // ppdmp.md §3.2: u32 address, s32 bufw, u32 flags (ppdmp.md §3.3), u32 padding 0, then the texture bytes.
    std::vector<u8> bytes(16 + size_t(size));
    writeLE32(bytes.data(), vramAddr);
    writeLE32(bytes.data() + 4, bufw);
    writeLE32(bytes.data() + 8, flags);
    writeLE32(bytes.data() + 12, 0);
    if (size) std::memcpy(bytes.data() + 16, data, size);
    add(u8(FRAMEBUF0 + level), bytes.data(), u32(bytes.size()), kAlignData, true);
}

void DumpWriter::clut(const void* data, u32 size) { add(CLUT, data, size, kAlignData, true); }

void DumpWriter::clutAddr(u32 vramAddr, u32 flags) {
    u8 bytes[8];
    writeLE32(bytes, vramAddr);
    writeLE32(bytes + 4, flags);
    add(CLUTADDR, bytes, sizeof(bytes), kAlignNone, true);
}

void DumpWriter::transferSrc(const void* data, u32 size) { add(TRANSFERSRC, data, size, kAlignData, true); }

void DumpWriter::memset(u32 dest, u8 value, u32 size) {
    // ppdmp.md §3.2: the value is stored as an s32 of which players use the low byte.
    u8 bytes[12];
    writeLE32(bytes, dest);
    writeLE32(bytes + 4, value);
    writeLE32(bytes + 8, size);
    add(MEMSET, bytes, sizeof(bytes), kAlignNone, true);
}

void DumpWriter::memcpy(u32 dest, const void* data, u32 size) {
    checkData(data, size);
    u8 bytes[4];
    writeLE32(bytes, dest);
    add(MEMCPYDEST, bytes, sizeof(bytes), kAlignNone, true);
    add(MEMCPYDATA, data, size, kAlignNone, true);
}

void DumpWriter::edramTrans(u32 value) {
    u8 bytes[4];
    writeLE32(bytes, value);
    add(EDRAMTRANS, bytes, sizeof(bytes), kAlignNone, true);
}

}  // namespace ge::dump
