// SPDX-License-Identifier: MIT
// .ppdmp reader/writer; see ppdmp.h and docs/ppdmp.md §1–§3, §5, §7.
#include "hle/dump/ppdmp.h"

#include <minizip/unzip.h>
#include <snappy.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <type_traits>

namespace ge::dump {

namespace {

constexpr char kMagic[8] = {'P', 'P', 'S', 'S', 'P', 'P', 'G', 'E'};  // ppdmp.md §2, no NUL
constexpr int kZstdLevel = 6;  // ppdmp.md §2.2 / §7: what PPSSPP's writer uses

// ---------------------------------------------------------------------------------------------
// Record type names, built at compile time so recordTypeName() can hand out stable pointers
// without any mutable static state.
struct NameTable {
    std::array<std::array<char, 16>, 256> names{};
};

constexpr void copyName(std::array<char, 16>& dst, const char* src) {
    size_t i = 0;
    for (; src[i] != 0 && i + 1 < dst.size(); ++i) dst[i] = src[i];
    dst[i] = 0;
}

constexpr NameTable makeNameTable() {
    NameTable t{};
    constexpr const char* kFixed[12] = {"INIT",        "REGISTERS", "VERTICES",   "INDICES",
                                        "CLUT",        "TRANSFERSRC", "MEMSET",   "MEMCPYDEST",
                                        "MEMCPYDATA",  "DISPLAY",   "CLUTADDR",   "EDRAMTRANS"};
    constexpr char kHex[] = "0123456789ABCDEF";
    for (int i = 0; i < 256; ++i) {
        auto& n = t.names[size_t(i)];
        if (i < 12) {
            copyName(n, kFixed[i]);
        } else if (i >= TEXTURE0 && i < TEXTURE0 + 8) {
            copyName(n, "TEXTURE0");
            n[7] = char('0' + (i - TEXTURE0));
        } else if (i >= FRAMEBUF0 && i < FRAMEBUF0 + 8) {
            copyName(n, "FRAMEBUF0");
            n[8] = char('0' + (i - FRAMEBUF0));
        } else {
            copyName(n, "UNKNOWN_00");
            n[8] = kHex[(i >> 4) & 0xF];
            n[9] = kHex[i & 0xF];
        }
    }
    return t;
}

constexpr NameTable kNameTable = makeNameTable();

// ---------------------------------------------------------------------------------------------
// Bounds-checked cursor over the raw file bytes.
class ByteReader {
public:
    ByteReader(const u8* data, size_t size) : m_data(data), m_size(size) {}
    size_t remaining() const { return m_size - m_pos; }
    size_t pos() const { return m_pos; }
    bool readU32(u32& v) {
        if (remaining() < 4) return false;
        v = readLE32(m_data + m_pos);
        m_pos += 4;
        return true;
    }
    bool take(size_t n, const u8*& p) {
        if (remaining() < n) return false;
        p = m_data + m_pos;
        m_pos += n;
        return true;
    }

private:
    const u8* m_data;
    size_t m_size;
    size_t m_pos = 0;
};

// Allocates `n` bytes, turning an allocation failure into an error instead of an exception
// escaping the loader (n is already capped by kMaxBlockBytes / kMaxFileBytes).
bool tryResize(std::vector<u8>& v, size_t n, std::string& err) {
    try {
        v.resize(n);
    } catch (const std::bad_alloc&) {
        err = "out of memory allocating " + std::to_string(n) + " bytes";
        return false;
    } catch (const std::length_error&) {
        err = "out of memory allocating " + std::to_string(n) + " bytes";
        return false;
    }
    return true;
}

// ppdmp.md §2.2: versions 5–6 use one zstd frame per block. Streamed into a buffer that grows only as
// output arrives and never past `expected` (itself capped by the header checks), so a frame that
// claims or produces more than the header says costs no more than the header's size, and a frame
// without a content size is bounded the same way.
struct ZstdDCtxFree {
    void operator()(ZSTD_DCtx* c) const { ZSTD_freeDCtx(c); }
};

bool decompressZstd(const u8* src, size_t n, u64 expected, std::vector<u8>& out, const char* what,
                    std::string& err) {
    const unsigned long long fcs = ZSTD_getFrameContentSize(src, n);
    if (fcs == ZSTD_CONTENTSIZE_ERROR) {
        err = std::string("corrupt zstd frame in ") + what;
        return false;
    }
    if (fcs != ZSTD_CONTENTSIZE_UNKNOWN && fcs != expected) {
        err = std::string(what) + " decompresses to " + std::to_string(fcs) + " bytes, header says " +
              std::to_string(expected);
        return false;
    }
    std::unique_ptr<ZSTD_DCtx, ZstdDCtxFree> dctx(ZSTD_createDCtx());
    if (!dctx) {
        err = "out of memory (zstd context)";
        return false;
    }
    out.clear();
    ZSTD_inBuffer in{src, n, 0};
    size_t produced = 0;
    for (;;) {
        if (produced == out.size() && out.size() < expected) {
            // Grow geometrically from 1 MiB: memory follows the output actually produced.
            const u64 next = std::min<u64>(expected, std::max<u64>(u64(1) << 20, u64(out.size()) * 2));
            if (!tryResize(out, size_t(next), err)) return false;
        }
        u8 spare = 0;  // room to detect output beyond `expected`
        ZSTD_outBuffer ob = produced < out.size() ? ZSTD_outBuffer{out.data(), out.size(), produced}
                                                  : ZSTD_outBuffer{&spare, 1, 0};
        const size_t r = ZSTD_decompressStream(dctx.get(), &ob, &in);
        if (ZSTD_isError(r)) {
            err = std::string("corrupt zstd data in ") + what + ": " + ZSTD_getErrorName(r);
            return false;
        }
        if (ob.dst == &spare) {
            if (ob.pos) {
                err = std::string(what) + " decompresses to more than the " + std::to_string(expected) +
                      " bytes the header says";
                return false;
            }
        } else {
            produced = ob.pos;
        }
        if (r == 0) break;  // frame complete
        if (in.pos == in.size && ob.pos < ob.size) {
            err = std::string("truncated zstd data in ") + what;
            return false;
        }
    }
    if (produced != expected) {
        err = std::string(what) + " decompresses to " + std::to_string(produced) + " bytes, header says " +
              std::to_string(expected);
        return false;
    }
    out.resize(produced);
    return true;
}

// ppdmp.md §2.2: versions 2–4 use raw snappy (varint length + tagged elements), not the framed format.
bool decompressSnappy(const u8* src, size_t n, u64 expected, std::vector<u8>& out, const char* what,
                      std::string& err) {
    const char* s = reinterpret_cast<const char*>(src);
    size_t ulen = 0;
    if (!snappy::GetUncompressedLength(s, n, &ulen)) {
        err = std::string("corrupt snappy length in ") + what;
        return false;
    }
    if (ulen != expected) {
        err = std::string(what) + " decompresses to " + std::to_string(ulen) + " bytes, header says " +
              std::to_string(expected);
        return false;
    }
    // No separate IsValidCompressedBuffer pass: RawUncompress checks every copy and literal
    // against both buffers and answers false for corrupt data (snappy.h), and the output size is
    // already bounded by the header check above. The pass was a second decompression of every
    // snappy dump (7 % of `ge2gl info` on Hokuto no Ken's).
    if (!tryResize(out, size_t(expected), err)) return false;
    char dummy = 0;
    if (!snappy::RawUncompress(s, n, expected ? reinterpret_cast<char*>(out.data()) : &dummy)) {
        err = std::string("corrupt snappy data in ") + what;
        return false;
    }
    return true;
}

bool decompressBlock(u32 version, const u8* src, size_t n, u64 expected, std::vector<u8>& out,
                     const char* what, std::string& err) {
    if (version >= 5) return decompressZstd(src, n, expected, out, what, err);
    return decompressSnappy(src, n, expected, out, what, err);
}

bool compressZstd(const u8* src, size_t n, std::vector<u8>& out) {
    const size_t bound = ZSTD_compressBound(n);
    if (ZSTD_isError(bound)) return false;
    out.resize(bound);
    u8 dummy = 0;
    const size_t r = ZSTD_compress(out.data(), out.size(), n ? src : &dummy, n, kZstdLevel);
    if (ZSTD_isError(r)) return false;
    out.resize(r);
    return true;
}

bool isZipSignature(const u8* data, size_t size) {
    // Local file header, or the end-of-central-directory record of an empty archive.
    return size >= 4 && data[0] == 'P' && data[1] == 'K' &&
           ((data[2] == 3 && data[3] == 4) || (data[2] == 5 && data[3] == 6));
}

// Zip archives are read with minizip (zlib's contrib/minizip), which needs only zlib. libzip,
// used before, links OpenSSL's libcrypto for encrypted entries: about 1.3 ms of loading and
// relocating in every process that maps libge2gl (docs/benchmarks.md, "Sixth round").
//
// minizip reads through these callbacks from the archive already in memory.
struct ZipMemory {
    const u8* data = nullptr;
    u64 size = 0, pos = 0;
};

voidpf ZCALLBACK zipMemOpen(voidpf opaque, const void*, int mode) {
    if (mode & ZLIB_FILEFUNC_MODE_WRITE) return nullptr;
    static_cast<ZipMemory*>(opaque)->pos = 0;
    return opaque;
}
uLong ZCALLBACK zipMemRead(voidpf, voidpf stream, void* buf, uLong size) {
    auto* m = static_cast<ZipMemory*>(stream);
    const u64 n = std::min<u64>(size, m->size - m->pos);
    if (n) std::memcpy(buf, m->data + m->pos, size_t(n));
    m->pos += n;
    return uLong(n);
}
uLong ZCALLBACK zipMemWrite(voidpf, voidpf, const void*, uLong) { return 0; }
ZPOS64_T ZCALLBACK zipMemTell(voidpf, voidpf stream) { return static_cast<ZipMemory*>(stream)->pos; }
long ZCALLBACK zipMemSeek(voidpf, voidpf stream, ZPOS64_T offset, int origin) {
    auto* m = static_cast<ZipMemory*>(stream);
    u64 base = 0;
    if (origin == ZLIB_FILEFUNC_SEEK_CUR) base = m->pos;
    else if (origin == ZLIB_FILEFUNC_SEEK_END) base = m->size;
    else if (origin != ZLIB_FILEFUNC_SEEK_SET) return -1;
    if (offset > m->size - base) return -1;  // past the end (no wrap: base <= size)
    m->pos = base + offset;
    return 0;
}
int ZCALLBACK zipMemClose(voidpf, voidpf) { return 0; }
int ZCALLBACK zipMemError(voidpf, voidpf) { return 0; }

struct UnzClose {
    void operator()(unzFile f) const { unzClose(f); }
};
using UnzHandle = std::unique_ptr<std::remove_pointer_t<unzFile>, UnzClose>;

std::string unzMessage(int code) {
    switch (code) {
    case UNZ_ERRNO: return "read error";
    case UNZ_EOF: return "unexpected end of data";
    case UNZ_PARAMERROR: return "bad parameter";
    case UNZ_BADZIPFILE: return "damaged archive";
    case UNZ_INTERNALERROR: return "internal error";
    case UNZ_CRCERROR: return "CRC mismatch";
    case Z_DATA_ERROR: return "damaged compressed data";
    case Z_MEM_ERROR: return "out of memory";
    default: return "error " + std::to_string(code);
    }
}

std::string lowerAscii(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return s;
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

// -------------------------------------------------------------------------------------------------

const char* recordTypeName(u8 type) { return kNameTable.names[type].data(); }

bool isKnownRecordType(u8 type) {
    return type <= EDRAMTRANS || (type >= TEXTURE0 && type < FRAMEBUF0 + 8);
}

bool Dump::payloadInRange(const Record& r) const {
    return u64(r.ptr) + u64(r.size) <= u64(pushbuf.size());
}

const u8* Dump::payload(const Record& r) const {
    if (!payloadInRange(r)) return nullptr;
    if (pushbuf.empty()) {
        // A zero-sized record at offset 0 of an empty push buffer is in range; give it a
        // non-null pointer to an immutable byte so callers can tell it apart from "outside".
        static constexpr u8 kEmpty = 0;
        return &kEmpty;
    }
    return pushbuf.data() + r.ptr;
}

u32 Dump::payloadWord(const Record& r, u32 index, u32 fallback) const {
    const u8* p = payload(r);
    if (!p || u64(index) * 4 + 4 > r.size) return fallback;
    return readLE32(p + size_t(index) * 4);
}

bool loadDumpFromMemory(const u8* data, size_t size, Dump& out, std::string& err) {
    out = Dump{};
    err.clear();
    if (!data && size) {
        err = "null buffer";
        return false;
    }
    ByteReader rd(data, size);
    const u8* magic = nullptr;
    if (!rd.take(8, magic)) {
        err = "truncated header (" + std::to_string(size) + " bytes)";
        return false;
    }
    if (std::memcmp(magic, kMagic, 8) != 0) {
        err = "bad magic (not a PPSSPPGE dump)";
        return false;
    }
    Dump d;
    if (!rd.readU32(d.version)) {
        err = "truncated header (no version)";
        return false;
    }
    if (d.version < kMinVersion || d.version > kMaxVersion) {
        err = "unsupported version " + std::to_string(d.version);
        return false;
    }
    if (d.version >= 4) {
        // ppdmp.md §2: 9-byte NUL-padded game ID (may use all 9 bytes), then 3 padding bytes.
        const u8* id = nullptr;
        const u8* pad = nullptr;
        if (!rd.take(kGameIdBytes, id) || !rd.take(3, pad)) {
            err = "truncated header (game ID)";
            return false;
        }
        size_t len = 0;
        while (len < kGameIdBytes && id[len] != 0) ++len;
        d.gameId.assign(reinterpret_cast<const char*>(id), len);
    }
    u32 commandCount = 0, pushbufSize = 0, cmdCompressed = 0;
    if (!rd.readU32(commandCount) || !rd.readU32(pushbufSize) || !rd.readU32(cmdCompressed)) {
        err = "truncated header (block sizes)";
        return false;
    }
    // Never trust the sizes: 64-bit products and caps before anything is allocated (ppdmp.h).
    const u64 cmdBytes = u64(commandCount) * kRecordBytes;
    if (commandCount > kMaxRecords) {
        err = "command block too large (" + std::to_string(commandCount) + " records; at most " +
              std::to_string(kMaxRecords) + ")";
        return false;
    }
    if (u64(pushbufSize) > kMaxPushbufBytes) {
        err = "push buffer too large (" + std::to_string(pushbufSize) + " bytes; at most " +
              std::to_string(kMaxPushbufBytes) + ")";
        return false;
    }
    const u8* cmdSrc = nullptr;
    if (!rd.take(cmdCompressed, cmdSrc)) {
        err = "truncated command block (need " + std::to_string(cmdCompressed) + " bytes, have " +
              std::to_string(rd.remaining()) + ")";
        return false;
    }
    std::vector<u8> cmd;
    if (!decompressBlock(d.version, cmdSrc, cmdCompressed, cmdBytes, cmd, "command block", err))
        return false;

    u32 pushCompressed = 0;
    if (!rd.readU32(pushCompressed)) {
        err = "truncated push buffer block (no size)";
        return false;
    }
    const u8* pushSrc = nullptr;
    if (!rd.take(pushCompressed, pushSrc)) {
        err = "truncated push buffer block (need " + std::to_string(pushCompressed) +
              " bytes, have " + std::to_string(rd.remaining()) + ")";
        return false;
    }
    if (!decompressBlock(d.version, pushSrc, pushCompressed, pushbufSize, d.pushbuf, "push buffer", err))
        return false;
    // Bytes after the second block are ignored, as PPSSPP does (ppdmp.md §2: nothing should follow).

    d.records.resize(commandCount);
    for (u32 i = 0; i < commandCount; ++i) {
        const u8* p = cmd.data() + size_t(i) * kRecordBytes;  // ppdmp.md §3.1: packed u8, u32, u32
        d.records[i].type = p[0];
        d.records[i].size = readLE32(p + 1);
        d.records[i].ptr = readLE32(p + 5);
    }
    out = std::move(d);
    return true;
}

bool extractPpdmpFromZip(const u8* data, size_t size, std::vector<u8>& out, std::string& err,
                         std::string* entryName) {
    out.clear();
    err.clear();
    if (entryName) entryName->clear();
    if (!data || size < 22) {  // 22 = smallest end-of-central-directory record
        err = "not a zip archive (too short)";
        return false;
    }
    if (u64(size) > kMaxFileBytes) {
        err = "zip archive too large";
        return false;
    }
    // The archive must end with its end-of-central-directory record and that record's comment
    // (APPNOTE.TXT 4.3.16): a cut archive is refused here, where minizip would accept a record
    // whose comment length runs past the end.
    bool ends = false;
    for (size_t i = size - 22;; --i) {
        if (data[i] == 'P' && data[i + 1] == 'K' && data[i + 2] == 5 && data[i + 3] == 6 &&
            i + 22 + (size_t(data[i + 20]) | size_t(data[i + 21]) << 8) == size) {
            ends = true;
            break;
        }
        if (i == 0 || size - 22 - i >= 0xFFFF) break;
    }
    if (!ends) {
        err = "zip: no end-of-central-directory record at the end (a cut or damaged archive)";
        return false;
    }
    ZipMemory mem{data, u64(size), 0};
    zlib_filefunc64_def io{};
    io.zopen64_file = zipMemOpen;
    io.zread_file = zipMemRead;
    io.zwrite_file = zipMemWrite;
    io.ztell64_file = zipMemTell;
    io.zseek64_file = zipMemSeek;
    io.zclose_file = zipMemClose;
    io.zerror_file = zipMemError;
    io.opaque = &mem;
    UnzHandle uz(unzOpen2_64("memory", &io));
    if (!uz) {
        err = "zip: not a zip archive or a damaged one";
        return false;
    }

    // ppdmp.md §1: the last entry whose lower-cased name ends in .ppdmp wins; __macosx/ is skipped.
    // Names are compared as bytes (the suffix and prefix are ASCII in every encoding a zip uses).
    unz64_file_pos chosen{};
    bool found = false;
    std::string chosenName;
    std::vector<char> name(size_t(0xFFFF) + 1);  // a zip name is at most 65,535 bytes
    int r = unzGoToFirstFile(uz.get());
    while (r == UNZ_OK) {
        unz_file_info64 info{};
        if (unzGetCurrentFileInfo64(uz.get(), &info, name.data(), uLong(name.size()), nullptr, 0, nullptr, 0) != UNZ_OK)
            break;
        const std::string n(name.data(), std::min<size_t>(info.size_filename, name.size() - 1));
        const std::string lower = lowerAscii(n);
        if (lower.rfind("__macosx/", 0) != 0 && endsWith(lower, ".ppdmp") &&
            unzGetFilePos64(uz.get(), &chosen) == UNZ_OK) {
            found = true;
            chosenName = n;
        }
        r = unzGoToNextFile(uz.get());
    }
    if (r != UNZ_OK && r != UNZ_END_OF_LIST_OF_FILE) {
        err = "zip: " + unzMessage(r) + " in the central directory";
        return false;
    }
    if (!found) {
        err = "zip holds no .ppdmp entry";
        return false;
    }
    unz_file_info64 st{};
    if (unzGoToFilePos64(uz.get(), &chosen) != UNZ_OK ||
        unzGetCurrentFileInfo64(uz.get(), &st, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK) {
        err = "zip: cannot stat entry " + chosenName;
        return false;
    }
    if (st.uncompressed_size > kMaxFileBytes) {
        err = "zip entry " + chosenName + " too large (" + std::to_string(st.uncompressed_size) + " bytes)";
        return false;
    }
    // Bit 0 of the flags: encrypted. No password is known, and minizip would hand back the
    // ciphertext as the data.
    if (st.flag & 1) {
        err = "zip entry " + chosenName + " is encrypted";
        return false;
    }
    if (st.compression_method != 0 && st.compression_method != Z_DEFLATED) {
        err = "zip entry " + chosenName + ": compression method " + std::to_string(st.compression_method) +
              " (only stored and deflated entries are read)";
        return false;
    }
    if (const int o = unzOpenCurrentFile(uz.get()); o != UNZ_OK) {
        err = "zip: cannot open entry " + chosenName + ": " + unzMessage(o);
        return false;
    }
    // The directory's size is a claim: read the real stream in pieces, the buffer growing only
    // with what arrives, and stop at the claimed size.
    size_t got = 0;
    while (got < st.uncompressed_size) {
        if (got == out.size()) {
            const u64 next = std::min<u64>(st.uncompressed_size, std::max<u64>(u64(1) << 20, u64(out.size()) * 2));
            if (!tryResize(out, size_t(next), err)) {
                unzCloseCurrentFile(uz.get());
                return false;
            }
        }
        const unsigned ask = unsigned(std::min<size_t>(out.size() - got, size_t(1) << 30));
        const int n = unzReadCurrentFile(uz.get(), out.data() + got, ask);
        if (n <= 0) {
            err = n == 0 ? "zip: entry " + chosenName + " is truncated"
                         : "zip: reading " + chosenName + ": " + unzMessage(n);
            unzCloseCurrentFile(uz.get());
            out.clear();
            return false;
        }
        got += size_t(n);
    }
    out.resize(got);
    // minizip checks the CRC when the whole entry has been read, on closing it.
    if (const int c = unzCloseCurrentFile(uz.get()); c != UNZ_OK) {
        err = "zip: reading " + chosenName + ": " + unzMessage(c);
        out.clear();
        return false;
    }
    if (entryName) *entryName = chosenName;
    return true;
}

bool loadZipFromMemory(const u8* data, size_t size, Dump& out, std::string& err) {
    out = Dump{};
    std::vector<u8> raw;
    std::string entry;
    if (!extractPpdmpFromZip(data, size, raw, err, &entry)) return false;
    if (!loadDumpFromMemory(raw.data(), raw.size(), out, err)) {
        err = entry + ": " + err;
        return false;
    }
    return true;
}

bool loadDump(const std::string& path, Dump& out, std::string& err) {
    out = Dump{};
    err.clear();
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) {
        err = "cannot open " + path + ": no such file";
        return false;
    }
    if (ec) {
        err = "cannot open " + path + ": " + ec.message();
        return false;
    }
    if (!fs::is_regular_file(status)) {
        err = "cannot open " + path + ": not a regular file";
        return false;
    }
    const std::uintmax_t fileSize = fs::file_size(path, ec);
    if (ec) {
        err = "cannot open " + path + ": " + ec.message();
        return false;
    }
    if (fileSize > kMaxFileBytes) {
        err = path + ": file too large (" + std::to_string(fileSize) + " bytes)";
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        err = "cannot open " + path;
        return false;
    }
    std::vector<u8> bytes;
    if (!tryResize(bytes, size_t(fileSize), err)) return false;
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    if (size_t(in.gcount()) != bytes.size()) {
        err = "cannot read " + path;
        return false;
    }
    bool ok = false;
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0) {
        ok = loadDumpFromMemory(bytes.data(), bytes.size(), out, err);
    } else if (isZipSignature(bytes.data(), bytes.size())) {
        ok = loadZipFromMemory(bytes.data(), bytes.size(), out, err);
    } else {
        err = "bad magic (neither a .ppdmp nor a .zip)";
    }
    if (!ok) err = path + ": " + err;
    return ok;
}

std::vector<u8> serializeDump(const Dump& d) {
    const u64 cmdBytes = u64(d.records.size()) * kRecordBytes;
    if (u64(d.records.size()) > kMaxRecords || u64(d.pushbuf.size()) > kMaxPushbufBytes) return {};

    std::vector<u8> cmd(static_cast<size_t>(cmdBytes));
    for (size_t i = 0; i < d.records.size(); ++i) {
        u8* p = cmd.data() + i * kRecordBytes;
        p[0] = d.records[i].type;
        writeLE32(p + 1, d.records[i].size);
        writeLE32(p + 5, d.records[i].ptr);
    }
    std::vector<u8> cmdZ, pushZ;
    if (!compressZstd(cmd.data(), cmd.size(), cmdZ) || !compressZstd(d.pushbuf.data(), d.pushbuf.size(), pushZ))
        return {};

    // ppdmp.md §7: magic, version 6, 9-byte NUL-padded game ID, 3 zero bytes, then the two blocks.
    std::vector<u8> out;
    out.reserve(24 + 12 + cmdZ.size() + 4 + pushZ.size());
    auto put32 = [&out](u32 v) {
        u8 b[4];
        writeLE32(b, v);
        out.insert(out.end(), b, b + 4);
    };
    out.insert(out.end(), kMagic, kMagic + 8);
    put32(kWriteVersion);
    u8 id[kGameIdBytes + 3] = {};
    std::memcpy(id, d.gameId.data(), std::min(d.gameId.size(), kGameIdBytes));
    out.insert(out.end(), id, id + sizeof(id));
    put32(u32(d.records.size()));
    put32(u32(d.pushbuf.size()));
    put32(u32(cmdZ.size()));
    out.insert(out.end(), cmdZ.begin(), cmdZ.end());
    put32(u32(pushZ.size()));
    out.insert(out.end(), pushZ.begin(), pushZ.end());
    return out;
}

bool saveDump(const std::string& path, const Dump& d, std::string& err) {
    err.clear();
    const std::vector<u8> bytes = serializeDump(d);
    if (bytes.empty()) {
        err = "cannot serialise dump (block larger than 1 GiB or compression failed)";
        return false;
    }
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) {
        err = "cannot create " + path;
        return false;
    }
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    f.close();
    if (!f) {
        err = "error writing " + path;
        return false;
    }
    return true;
}

}  // namespace ge::dump
