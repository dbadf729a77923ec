// SPDX-License-Identifier: MIT
#include "hle/savestate.h"

#include <xxhash.h>
#include <zstd.h>

#include <bit>
#include <cstring>

namespace ge::savestate {

namespace {

// Header (docs/savestate.md): magic, format version, flags, payload size, xxHash64 of the payload.
constexpr char kMagic[8] = {'G', 'E', '2', 'G', 'L', 'S', 'T', '\x1a'};
constexpr u32 kFlagMemory = 1;

constexpr u32 tag(const char (&s)[5]) { return u32(u8(s[0])) | u32(u8(s[1])) << 8 | u32(u8(s[2])) << 16 | u32(u8(s[3])) << 24; }
constexpr u32 kEngine = tag("ENGN"), kSce = tag("SCGE"), kHost = tag("HOST");
// Version 3's additions, in a section of their own after HOST so that a state without it (versions
// 1 and 2) still reads: the read-back matrix words, which lists a signal paused, the old-SDK
// suspended list waiting for its handler.
constexpr u32 kV3 = tag("GEV3");
constexpr u32 kRam = tag("RAM "), kVram = tag("VRAM"), kScratch = tag("SCRA");

// Little-endian writer, for the header, section framing and compressed memory (the sections'
// bodies go through an Archive).
class Writer {
public:
    std::vector<u8> buf;
    void u32v(u32 v) {
        for (int i = 0; i < 4; ++i) buf.push_back(u8(v >> (8 * i)));
    }
    void u64v(u64 v) {
        u32v(u32(v));
        u32v(u32(v >> 32));
    }
    void bytes(const void* p, size_t n) {
        const u8* b8 = static_cast<const u8*>(p);
        buf.insert(buf.end(), b8, b8 + n);
    }
    // A section: tag, byte size, body written by `body`.
    template <class F>
    void section(u32 t, F&& body) {
        u32v(t);
        const size_t at = buf.size();
        u32v(0);
        body();
        const u32 n = u32(buf.size() - at - 4);
        for (int i = 0; i < 4; ++i) buf[at + size_t(i)] = u8(n >> (8 * i));
    }
};

// One sequence of values in either direction, as Dolphin's PointerWrap: writing, each call
// appends its value to the writer; reading, each call reads the next value into its argument.
// A section is described once, by a serialise() function that runs in both modes. Reading is
// bounds-checked: past the end every value reads as 0 and ok() turns false; require() fails the
// read when a value read is out of its range (writing, the values are the engine's own and never
// checked). version() is the blob's format version (kFormatVersion when writing).
class Archive {
public:
    explicit Archive(Writer& w) : w_(&w), version_(kFormatVersion) {}
    Archive(const u8* p, size_t n, u32 version) : p_(p), end_(p + n), version_(version) {}
    bool reading() const { return w_ == nullptr; }
    u32 version() const { return version_; }
    bool ok() const { return ok_; }
    bool atEnd() const { return p_ == end_; }
    size_t left() const { return size_t(end_ - p_); }
    void require(bool good) { ok_ = ok_ && (!reading() || good); }

    void u8v(u8& v) {
        if (!reading()) w_->buf.push_back(v);
        else v = need(1) ? *p_++ : 0;
    }
    void u32v(u32& v) {
        if (!reading()) return w_->u32v(v);
        v = 0;
        if (!need(4)) return;
        for (int i = 0; i < 4; ++i) v |= u32(p_[i]) << (8 * i);
        p_ += 4;
    }
    void s32v(s32& v) { cast<u32>(v, [this](u32& x) { u32v(x); }); }
    void u64v(u64& v) {
        u32 lo = u32(v), hi = u32(v >> 32);
        u32v(lo);
        u32v(hi);
        v = lo | u64(hi) << 32;
    }
    void f(float& v) { cast<u32>(v, [this](u32& x) { u32v(x); }); }
    void b(bool& v) {
        u8 x = v ? 1 : 0;
        u8v(x);
        require(x <= 1);
        v = x == 1;
    }
    // An enum stored as a byte, at most `last`.
    template <class E>
    void en(E& v, E last) {
        u8 x = u8(v);
        u8v(x);
        require(x <= u8(last));
        v = E(ok_ ? x : 0);
    }
    void bytes(void* p, size_t n) {
        if (!reading()) return w_->bytes(p, n);
        if (!need(n)) return;
        std::memcpy(p, p_, n);
        p_ += n;
    }
    // A u32 length, then the characters; reading refuses more than `maxLen`.
    void str(std::string& s, size_t maxLen) {
        u32 n = u32(s.size());
        u32v(n);
        require(n <= maxLen);
        if (!reading()) return w_->bytes(s.data(), s.size());
        s.clear();
        if (ok_ && need(n)) {
            s.assign(reinterpret_cast<const char*>(p_), n);
            p_ += n;
        }
    }
    // Reading: a container gets `n` default elements once `n` passed its checks.
    template <class C>
    void resize(C& c, u32 n) {
        if (reading()) c.resize(ok_ ? n : 0);
    }

private:
    // A value stored as the bits of another type T.
    template <class T, class V, class F>
    void cast(V& v, F&& io) {
        T x = std::bit_cast<T>(v);
        io(x);
        v = std::bit_cast<V>(x);
    }
    bool need(size_t n) {
        if (!ok_ || left() < n) return ok_ = false;
        return true;
    }
    Writer* w_ = nullptr;
    const u8* p_ = nullptr;
    const u8* end_ = nullptr;
    u32 version_;
    bool ok_ = true;
};

// Bounds-checked reader for the header and section framing.
class Reader {
public:
    Reader(const u8* p, size_t n) : p_(p), end_(p + n) {}
    bool ok() const { return ok_; }
    bool atEnd() const { return p_ == end_; }
    size_t left() const { return size_t(end_ - p_); }
    u32 u32v() {
        if (!need(4)) return 0;
        u32 v = 0;
        for (int i = 0; i < 4; ++i) v |= u32(p_[i]) << (8 * i);
        p_ += 4;
        return v;
    }
    u64 u64v() {
        const u64 lo = u32v();
        return lo | u64(u32v()) << 32;
    }
    const u8* bytes(size_t n) {
        if (!need(n)) return nullptr;
        const u8* r = p_;
        p_ += n;
        return r;
    }

private:
    bool need(size_t n) {
        if (!ok_ || size_t(end_ - p_) < n) return ok_ = false;
        return true;
    }
    const u8* p_;
    const u8* end_;
    bool ok_ = true;
};

// ---- the engine ----------------------------------------------------------------------------

void serialise(Archive& a, GeState& s) {
    for (u32& v : s.regs) a.u32v(v);
    auto floats = [&a](auto& arr) {
        for (float& v : arr) a.f(v);
    };
    floats(s.bone), floats(s.world), floats(s.view), floats(s.proj), floats(s.tgen);
    for (u32* v : {&s.boneNum, &s.worldNum, &s.viewNum, &s.projNum, &s.tgenNum, &s.vertexAddr, &s.indexAddr,
                   &s.offsetAddr})
        a.u32v(*v);
    a.bytes(s.clut, sizeof s.clut);
    a.u32v(s.clutLoadedBytes);
    a.require(s.clutLoadedBytes <= sizeof s.clut);
    // Version 1 had no vertex latch: a state from it resumes with zeros (a fresh GE's values).
    if (a.version() >= 2) {
        for (float& v : s.latchUV) a.f(v);
        for (float& v : s.latchNormal) a.f(v);
    }
    if (!a.reading()) return;
    // Until the state's GEV3 section (version 3) says otherwise, the read-back matrix words are
    // the drawn ones.
    const float* mats[5] = {s.bone, s.world, s.view, s.proj, s.tgen};
    const u32 base[5] = {0, 96, 108, 120, 136}, count[5] = {96, 12, 12, 16, 12};
    for (int m = 0; m < 5; ++m)
        for (u32 k = 0; k < count[m]; ++k) s.visibleMtx[base[m] + k] = toFloat24(mats[m][k]);
    // A register word holds its own opcode in bits 31..24 (or 0 when never written).
    for (size_t op = 0; op < s.regs.size(); ++op) a.require(s.regs[op] == 0 || (s.regs[op] >> 24) == op);
}

// The sceGe module keeps at most 255 SIGNAL CALL levels (SceGeListArgs numStacks < 256).
constexpr u32 kMaxSignalStack = 256;

void serialise(Archive& a, ListRegs& l) {
    a.u32v(l.pc);
    a.u32v(l.stall);
    for (auto& e : l.callStack) a.u32v(e[0]), a.u32v(e[1]);
    a.u32v(l.callDepth);
    a.require(l.callDepth <= 2);  // the GE's two CALL levels (docs/ge-rules.md §4.1)
    a.b(l.bflg);
    u32 n = u32(l.signalStack.size());
    a.u32v(n);
    a.require(n <= kMaxSignalStack);
    a.resize(l.signalStack, n);
    for (auto& f : l.signalStack) a.u32v(f.pc), a.u32v(f.offset), a.u32v(f.base);
    a.u32v(l.signalStackMax);
    a.require(l.signalStackMax <= kMaxSignalStack);
    a.b(l.pauseAtFinish), a.b(l.syncAtFinish);
    for (u32* v : {&l.pauseSignalArg, &l.pauseEndArg, &l.lastOp, &l.lastWord}) a.u32v(*v);
}

void serialise(Archive& a, GeStats& s) {
    for (u64* v : {&s.commands, &s.prims, &s.patches, &s.immediates, &s.vertices, &s.bboxes, &s.transfers,
                   &s.clutLoads, &s.signals, &s.finishes, &s.unknownCommands, &s.stateChanges, &s.cycles,
                   &s.cyclesCommands, &s.cyclesVertices, &s.cyclesPixels, &s.cyclesTransfers})
        a.u64v(*v);
}

// The engine collects at most 0x10000 immediate-mode vertices (GeEngine::doImmediate).
constexpr u32 kMaxImmVertices = 0x10000;

void serialise(Archive& a, ImmVertex& v) {
    a.f(v.x), a.f(v.y);
    u32 z = v.z;
    a.u32v(z);
    a.require(z <= 0xFFFF);
    v.z = u16(z);
    a.f(v.s), a.f(v.t), a.f(v.q);
    a.bytes(v.color, 4);
    a.bytes(v.secondary, 3);
    a.u8v(v.fog);
}

void serialise(Archive& a, GeEngine::Saved& e) {
    serialise(a, e.state);
    serialise(a, e.list);
    serialise(a, e.stats);
    a.en(e.status, RunStatus::Error);
    a.en(e.lastError, GeError::SignalStack);
    a.str(e.lastErrorMsg, 4096);
    a.u64v(e.cycleLimit);
    a.b(e.pauseRequested);
    a.b(e.stopRequested);
    a.en(e.stopStatus, RunStatus::Error);
    a.en(e.lastPrim, GE_PRIM_RECTANGLES);
    u32 n = u32(e.immVerts.size());
    a.u32v(n);
    a.require(n <= kMaxImmVertices && size_t(n) * 32 <= a.left());  // 32 bytes a vertex
    a.resize(e.immVerts, n);
    for (ImmVertex& v : e.immVerts) serialise(a, v);
    a.u32v(e.immFlags);
    a.en(e.immPrim, GE_PRIM_KEEP_PREVIOUS);
}

// ---- the sceGe layer -----------------------------------------------------------------------

void serialise(Archive& a, std::deque<int>& d) {
    u32 n = u32(d.size());
    a.u32v(n);
    a.require(n <= u32(SceGe::kMaxLists));
    a.resize(d, n);
    for (int& i : d) {
        u32 v = u32(i);
        a.u32v(v);
        i = int(v);
    }
}

void serialise(Archive& a, SceGe::Saved& s, u32& edramTranslation) {
    for (auto& dl : s.lists) {
        a.en(dl.state, SceListState::Completed);
        a.u32v(dl.startPc), a.u32v(dl.stall);
        a.s32v(dl.cbid);
        for (u32* v : {&dl.contextAddr, &dl.numStacks, &dl.stackAddr}) a.u32v(*v);
        a.b(dl.started), a.b(dl.hung);
        serialise(a, dl.regs);
        a.u32v(dl.offset), a.u32v(dl.base);
        a.u64v(dl.cycles);
    }
    for (auto& cb : s.callbacks) {
        a.b(cb.used);
        for (u32* v : {&cb.signalFunc, &cb.signalArg, &cb.finishFunc, &cb.finishArg}) a.u32v(*v);
    }
    serialise(a, s.queue);
    serialise(a, s.freeSlots);
    a.s32v(s.active);
    a.b(s.brokeInCallback), a.b(s.finishPending);
    for (u32* v : {&s.finishArg, &s.finishPc, &s.sdkVersion, &edramTranslation}) a.u32v(*v);
}

void serialise(Archive& a, HostFlags& h) { a.b(h.heldInterrupt); }

// Version 3's GEV3 section: the read-back matrix words (24 bits), which lists a signal paused,
// the old-SDK suspended list.
void serialiseV3(Archive& a, GeState& st, SceGe::Saved& s) {
    for (u32& v : st.visibleMtx) {
        a.u32v(v);
        if (a.reading()) v &= 0xFFFFFF;
    }
    for (auto& dl : s.lists) a.b(dl.pausedBySignal);
    a.s32v(s.suspendedSlot);
}

// ---- guest memory --------------------------------------------------------------------------

void putCompressed(Writer& w, const u8* p, size_t n) {
    w.u32v(u32(n));
    std::vector<u8> z(ZSTD_compressBound(n));
    // Level 1: a 64 MiB RAM is mostly zeros or game data that zstd's fastest level already packs.
    const size_t got = ZSTD_compress(z.data(), z.size(), p, n, 1);
    if (ZSTD_isError(got)) throw std::bad_alloc();
    w.bytes(z.data(), got);
}

// Decompresses a section body into exactly `expect` bytes.
bool getCompressed(const u8* p, size_t n, size_t expect, std::vector<u8>& out, std::string& err) {
    Reader r(p, n);
    const u32 raw = r.u32v();
    if (!r.ok() || raw != expect) {
        err = "a memory section's size is not this GE's (" + std::to_string(raw) + " bytes, " +
              std::to_string(expect) + " expected)";
        return false;
    }
    const u8* z = p + 4;
    const size_t zn = n - 4;
    if (ZSTD_getFrameContentSize(z, zn) != expect) {
        err = "a memory section's compressed data does not hold its stated size";
        return false;
    }
    out.resize(expect);
    const size_t got = ZSTD_decompress(out.data(), out.size(), z, zn);
    if (ZSTD_isError(got) || got != expect) {
        err = "a memory section's compressed data is corrupt";
        return false;
    }
    return true;
}

void writeHeader(std::vector<u8>& out, u32 flags, const std::vector<u8>& payload) {
    Writer h;
    h.bytes(kMagic, sizeof kMagic);
    h.u32v(kFormatVersion);
    h.u32v(flags);
    h.u64v(payload.size());
    h.u64v(XXH64(payload.data(), payload.size(), 0));
    out = std::move(h.buf);
    out.insert(out.end(), payload.begin(), payload.end());
}

bool readHeader(std::span<const u8> blob, u32& version, u32& flags, std::span<const u8>& payload, std::string& err) {
    if (blob.size() < kHeaderSize || std::memcmp(blob.data(), kMagic, sizeof kMagic) != 0) {
        err = "not a ge2gl save state (no GE2GLST header)";
        return false;
    }
    Reader r(blob.data() + 8, kHeaderSize - 8);
    version = r.u32v();
    flags = r.u32v();
    const u64 size = r.u64v(), hash = r.u64v();
    if (version < kOldestFormatVersion || version > kFormatVersion) {
        err = "save state format version " + std::to_string(version) + " (this ge2gl reads versions " +
              std::to_string(kOldestFormatVersion) + " to " + std::to_string(kFormatVersion) + ")";
        return false;
    }
    if (size != blob.size() - kHeaderSize) {
        err = "save state is " + std::to_string(blob.size()) + " bytes, its header says " +
              std::to_string(size + kHeaderSize) + " (truncated or padded)";
        return false;
    }
    payload = blob.subspan(kHeaderSize);
    if (XXH64(payload.data(), payload.size(), 0) != hash) {
        err = "save state checksum mismatch (corrupt data)";
        return false;
    }
    if (flags & ~kFlagMemory) {
        err = "save state has unknown flags";
        return false;
    }
    return true;
}

}  // namespace

std::vector<u8> save(const GeEngine& engine, const SceGe& sce, const Memory* mem, const HostFlags& host) {
    // Copies: the serialise functions take their values by reference in both directions.
    GeEngine::Saved e = engine.saved();
    SceGe::Saved s = sce.saved();
    u32 edram = engine.memory().edramTranslation();
    HostFlags hf = host;
    Writer w;
    Archive a(w);
    w.section(kEngine, [&] { serialise(a, e); });
    w.section(kSce, [&] { serialise(a, s, edram); });
    w.section(kHost, [&] { serialise(a, hf); });
    w.section(kV3, [&] { serialiseV3(a, e.state, s); });
    if (mem) {
        w.section(kRam, [&] { putCompressed(w, mem->ram(), mem->ramSize()); });
        w.section(kVram, [&] { putCompressed(w, mem->vram(), Memory::kVramSize); });
        w.section(kScratch, [&] { putCompressed(w, mem->ptr(Memory::kScratchBase, Memory::kScratchSize), Memory::kScratchSize); });
    }
    std::vector<u8> out;
    writeHeader(out, mem ? kFlagMemory : 0, w.buf);
    return out;
}

bool inspect(std::span<const u8> blob, u32& version, bool& hasMemory, std::string& err) {
    u32 flags = 0;
    std::span<const u8> payload;
    if (!readHeader(blob, version, flags, payload, err)) return false;
    hasMemory = flags & kFlagMemory;
    return true;
}

bool load(std::span<const u8> blob, GeEngine& engine, SceGe& sce, Memory& mem, HostFlags& host, bool& hadMemory,
          std::string& err) {
    u32 version = 0, flags = 0;
    std::span<const u8> payload;
    if (!readHeader(blob, version, flags, payload, err)) return false;
    const bool withMemory = flags & kFlagMemory;

    // Parse everything into temporaries first: nothing changes unless all of it is valid.
    GeEngine::Saved e;
    SceGe::Saved s;
    HostFlags hf;
    u32 edram = 0;
    std::vector<u8> ram, vram, scratch;
    const u32 want[] = {kEngine, kSce, kHost, kRam, kVram, kScratch};
    const size_t sections = withMemory ? 6 : 3;
    Reader top(payload.data(), payload.size());
    // The optional GEV3 section that follows HOST.
    auto readV3 = [&]() -> bool {
        if (top.left() < 8) return true;
        Reader peek = top;
        if (peek.u32v() != kV3) return true;
        const u32 n = peek.u32v();
        const u8* body = peek.bytes(n);
        if (!peek.ok()) return false;
        top = peek;
        Archive r(body, n, version);
        serialiseV3(r, e.state, s);
        return r.ok() && r.atEnd();
    };
    for (size_t k = 0; k < sections; ++k) {
        if (k == 3 && !readV3()) {
            err = "save state section GEV3 is malformed";
            return false;
        }
        const u32 t = top.u32v(), n = top.u32v();
        const u8* body = top.bytes(n);
        if (!top.ok() || t != want[k]) {
            err = "save state section " + std::to_string(k) + " is missing or out of order";
            return false;
        }
        Archive r(body, n, version);
        if (t == kEngine) serialise(r, e);
        else if (t == kSce) serialise(r, s, edram);
        else if (t == kHost) serialise(r, hf);
        else {
            std::vector<u8>& dst = t == kRam ? ram : t == kVram ? vram : scratch;
            const size_t expect = t == kRam ? mem.ramSize() : t == kVram ? Memory::kVramSize : Memory::kScratchSize;
            if (!getCompressed(body, n, expect, dst, err)) return false;
            continue;
        }
        if (!r.ok() || !r.atEnd()) {
            err = "save state section " + std::to_string(k) + " is malformed (a value out of range or the wrong size)";
            return false;
        }
    }
    if (sections == 3 && !readV3()) {
        err = "save state section GEV3 is malformed";
        return false;
    }
    if (!top.atEnd()) {
        err = "save state has data after its last section";
        return false;
    }
    std::string why;
    if (!SceGe::validSaved(s, why)) {
        err = "save state's list queue is inconsistent: " + why;
        return false;
    }
    if (edram != 0 && edram != 0x200 && edram != 0x400 && edram != 0x800 && edram != 0x1000) {
        err = "save state's eDRAM translation value is invalid";
        return false;
    }

    // Commit.
    if (withMemory) {
        std::memcpy(mem.ram(), ram.data(), ram.size());
        std::memcpy(mem.vram(), vram.data(), vram.size());
        std::memcpy(mem.ptr(Memory::kScratchBase, Memory::kScratchSize), scratch.data(), scratch.size());
    }
    mem.setEdramTranslation(edram);
    sce.restore(s);
    engine.restore(e);
    host = hf;
    hadMemory = withMemory;
    return true;
}

}  // namespace ge::savestate
