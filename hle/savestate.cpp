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

// Little-endian writer.
class Writer {
public:
    std::vector<u8> buf;
    void u8v(u8 v) { buf.push_back(v); }
    void b(bool v) { u8v(v ? 1 : 0); }
    void u32v(u32 v) {
        for (int i = 0; i < 4; ++i) buf.push_back(u8(v >> (8 * i)));
    }
    void s32v(s32 v) { u32v(u32(v)); }
    void u64v(u64 v) {
        u32v(u32(v));
        u32v(u32(v >> 32));
    }
    void f(float v) { u32v(std::bit_cast<u32>(v)); }
    void bytes(const void* p, size_t n) {
        const u8* b8 = static_cast<const u8*>(p);
        buf.insert(buf.end(), b8, b8 + n);
    }
    void str(const std::string& s) {
        u32v(u32(s.size()));
        bytes(s.data(), s.size());
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

// Bounds-checked reader: past the end every read yields 0 and ok() turns false.
class Reader {
public:
    Reader(const u8* p, size_t n) : p_(p), end_(p + n) {}
    bool ok() const { return ok_; }
    bool atEnd() const { return p_ == end_; }
    size_t left() const { return size_t(end_ - p_); }
    void failIf(bool bad) { ok_ = ok_ && !bad; }
    u8 u8v() { return need(1) ? *p_++ : 0; }
    bool b() {
        const u8 v = u8v();
        failIf(v > 1);
        return v == 1;
    }
    u32 u32v() {
        if (!need(4)) return 0;
        u32 v = 0;
        for (int i = 0; i < 4; ++i) v |= u32(p_[i]) << (8 * i);
        p_ += 4;
        return v;
    }
    s32 s32v() { return s32(u32v()); }
    u64 u64v() {
        const u64 lo = u32v();
        return lo | u64(u32v()) << 32;
    }
    float f() { return std::bit_cast<float>(u32v()); }
    const u8* bytes(size_t n) {
        if (!need(n)) return nullptr;
        const u8* r = p_;
        p_ += n;
        return r;
    }
    void bytesTo(void* dst, size_t n) {
        if (const u8* s = bytes(n)) std::memcpy(dst, s, n);
    }
    std::string str(size_t maxLen) {
        const u32 n = u32v();
        failIf(n > maxLen);
        if (!ok_) return {};
        const u8* s = bytes(n);
        return s ? std::string(reinterpret_cast<const char*>(s), n) : std::string();
    }
    // An enum stored as a byte, at most `last`.
    template <class E>
    E en(E last) {
        const u8 v = u8v();
        failIf(v > u8(last));
        return E(ok_ ? v : 0);
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

void putState(Writer& w, const GeState& s) {
    for (u32 r : s.regs) w.u32v(r);
    for (float v : s.bone) w.f(v);
    for (float v : s.world) w.f(v);
    for (float v : s.view) w.f(v);
    for (float v : s.proj) w.f(v);
    for (float v : s.tgen) w.f(v);
    for (u32 v : {s.boneNum, s.worldNum, s.viewNum, s.projNum, s.tgenNum, s.vertexAddr, s.indexAddr, s.offsetAddr})
        w.u32v(v);
    w.bytes(s.clut, sizeof s.clut);
    w.u32v(s.clutLoadedBytes);
    for (float v : s.latchUV) w.f(v);
    for (float v : s.latchNormal) w.f(v);
}

void getState(Reader& r, GeState& s, u32 version) {
    for (u32& v : s.regs) v = r.u32v();
    for (float& v : s.bone) v = r.f();
    for (float& v : s.world) v = r.f();
    for (float& v : s.view) v = r.f();
    for (float& v : s.proj) v = r.f();
    for (float& v : s.tgen) v = r.f();
    for (u32* v : {&s.boneNum, &s.worldNum, &s.viewNum, &s.projNum, &s.tgenNum, &s.vertexAddr, &s.indexAddr,
                   &s.offsetAddr})
        *v = r.u32v();
    r.bytesTo(s.clut, sizeof s.clut);
    s.clutLoadedBytes = r.u32v();
    r.failIf(s.clutLoadedBytes > sizeof s.clut);
    // Version 1 had no vertex latch: a state from it resumes with zeros (a fresh GE's values).
    if (version >= 2) {
        for (float& v : s.latchUV) v = r.f();
        for (float& v : s.latchNormal) v = r.f();
    }
    // Until the state's GEV3 section (version 3) says otherwise, the read-back matrix words are
    // the drawn ones.
    const float* mats[5] = {s.bone, s.world, s.view, s.proj, s.tgen};
    const u32 base[5] = {0, 96, 108, 120, 136}, count[5] = {96, 12, 12, 16, 12};
    for (int m = 0; m < 5; ++m)
        for (u32 k = 0; k < count[m]; ++k) s.visibleMtx[base[m] + k] = toFloat24(mats[m][k]);
    // A register word holds its own opcode in bits 31..24 (or 0 when never written).
    for (size_t op = 0; op < s.regs.size(); ++op) r.failIf(s.regs[op] != 0 && (s.regs[op] >> 24) != op);
}

void putList(Writer& w, const ListRegs& l) {
    w.u32v(l.pc);
    w.u32v(l.stall);
    for (const auto& e : l.callStack) w.u32v(e[0]), w.u32v(e[1]);
    w.u32v(l.callDepth);
    w.b(l.bflg);
    w.u32v(u32(l.signalStack.size()));
    for (const auto& f : l.signalStack) w.u32v(f.pc), w.u32v(f.offset), w.u32v(f.base);
    w.u32v(l.signalStackMax);
    w.b(l.pauseAtFinish);
    w.b(l.syncAtFinish);
    w.u32v(l.pauseSignalArg);
    w.u32v(l.pauseEndArg);
    w.u32v(l.lastOp);
    w.u32v(l.lastWord);
}

// The sceGe module keeps at most 255 SIGNAL CALL levels (SceGeListArgs numStacks < 256).
constexpr u32 kMaxSignalStack = 256;

void getList(Reader& r, ListRegs& l) {
    l.pc = r.u32v();
    l.stall = r.u32v();
    for (auto& e : l.callStack) e[0] = r.u32v(), e[1] = r.u32v();
    l.callDepth = r.u32v();
    r.failIf(l.callDepth > 2);  // the GE's two CALL levels (docs/ge-rules.md §4.1)
    l.bflg = r.b();
    const u32 n = r.u32v();
    r.failIf(n > kMaxSignalStack);
    l.signalStack.clear();
    for (u32 i = 0; r.ok() && i < n; ++i) {
        ListRegs::SigFrame f{};
        f.pc = r.u32v(), f.offset = r.u32v(), f.base = r.u32v();
        l.signalStack.push_back(f);
    }
    l.signalStackMax = r.u32v();
    r.failIf(l.signalStackMax > kMaxSignalStack);
    l.pauseAtFinish = r.b();
    l.syncAtFinish = r.b();
    l.pauseSignalArg = r.u32v();
    l.pauseEndArg = r.u32v();
    l.lastOp = r.u32v();
    l.lastWord = r.u32v();
}

void putStats(Writer& w, const GeStats& s) {
    for (u64 v : {s.commands, s.prims, s.patches, s.immediates, s.vertices, s.bboxes, s.transfers, s.clutLoads,
                  s.signals, s.finishes, s.unknownCommands, s.stateChanges, s.cycles, s.cyclesCommands, s.cyclesVertices,
                  s.cyclesPixels, s.cyclesTransfers})
        w.u64v(v);
}

void getStats(Reader& r, GeStats& s) {
    for (u64* v : {&s.commands, &s.prims, &s.patches, &s.immediates, &s.vertices, &s.bboxes, &s.transfers,
                   &s.clutLoads, &s.signals, &s.finishes, &s.unknownCommands, &s.stateChanges, &s.cycles,
                   &s.cyclesCommands, &s.cyclesVertices, &s.cyclesPixels, &s.cyclesTransfers})
        *v = r.u64v();
}

// The engine collects at most 0x10000 immediate-mode vertices (GeEngine::doImmediate).
constexpr u32 kMaxImmVertices = 0x10000;

void putEngine(Writer& w, const GeEngine::Saved& e) {
    putState(w, e.state);
    putList(w, e.list);
    putStats(w, e.stats);
    w.u8v(u8(e.status));
    w.u8v(u8(e.lastError));
    w.str(e.lastErrorMsg);
    w.u64v(e.cycleLimit);
    w.b(e.pauseRequested);
    w.b(e.stopRequested);
    w.u8v(u8(e.stopStatus));
    w.u8v(u8(e.lastPrim));
    w.u32v(u32(e.immVerts.size()));
    for (const ImmVertex& v : e.immVerts) {
        w.f(v.x), w.f(v.y);
        w.u32v(v.z);
        w.f(v.s), w.f(v.t), w.f(v.q);
        w.bytes(v.color, 4);
        w.bytes(v.secondary, 3);
        w.u8v(v.fog);
    }
    w.u32v(e.immFlags);
    w.u8v(u8(e.immPrim));
}

void getEngine(Reader& r, GeEngine::Saved& e, u32 version) {
    getState(r, e.state, version);
    getList(r, e.list);
    getStats(r, e.stats);
    e.status = r.en(RunStatus::Error);
    e.lastError = r.en(GeError::SignalStack);
    e.lastErrorMsg = r.str(4096);
    e.cycleLimit = r.u64v();
    e.pauseRequested = r.b();
    e.stopRequested = r.b();
    e.stopStatus = r.en(RunStatus::Error);
    e.lastPrim = r.en(GE_PRIM_RECTANGLES);
    const u32 n = r.u32v();
    r.failIf(n > kMaxImmVertices || size_t(n) * 32 > r.left());
    e.immVerts.clear();
    for (u32 i = 0; r.ok() && i < n; ++i) {
        ImmVertex v;
        v.x = r.f(), v.y = r.f();
        const u32 z = r.u32v();
        r.failIf(z > 0xFFFF);
        v.z = u16(z);
        v.s = r.f(), v.t = r.f(), v.q = r.f();
        r.bytesTo(v.color, 4);
        r.bytesTo(v.secondary, 3);
        v.fog = r.u8v();
        e.immVerts.push_back(v);
    }
    e.immFlags = r.u32v();
    e.immPrim = r.en(GE_PRIM_KEEP_PREVIOUS);
}

// ---- the sceGe layer -----------------------------------------------------------------------

void putSlots(Writer& w, const std::deque<int>& d) {
    w.u32v(u32(d.size()));
    for (int i : d) w.u32v(u32(i));
}

void getSlots(Reader& r, std::deque<int>& d) {
    const u32 n = r.u32v();
    r.failIf(n > u32(SceGe::kMaxLists));
    d.clear();
    for (u32 i = 0; r.ok() && i < n; ++i) d.push_back(int(r.u32v()));
}

void putSce(Writer& w, const SceGe::Saved& s, u32 edramTranslation) {
    for (const auto& dl : s.lists) {
        w.u8v(u8(dl.state));
        w.u32v(dl.startPc);
        w.u32v(dl.stall);
        w.s32v(dl.cbid);
        w.u32v(dl.contextAddr);
        w.u32v(dl.numStacks);
        w.u32v(dl.stackAddr);
        w.b(dl.started);
        w.b(dl.hung);
        putList(w, dl.regs);
        w.u32v(dl.offset);
        w.u32v(dl.base);
        w.u64v(dl.cycles);
    }
    for (const auto& cb : s.callbacks) {
        w.b(cb.used);
        for (u32 v : {cb.signalFunc, cb.signalArg, cb.finishFunc, cb.finishArg}) w.u32v(v);
    }
    putSlots(w, s.queue);
    putSlots(w, s.freeSlots);
    w.s32v(s.active);
    w.b(s.brokeInCallback);
    w.b(s.finishPending);
    w.u32v(s.finishArg);
    w.u32v(s.finishPc);
    w.u32v(s.sdkVersion);
    w.u32v(edramTranslation);
}

void getSce(Reader& r, SceGe::Saved& s, u32& edramTranslation) {
    for (auto& dl : s.lists) {
        dl.state = r.en(SceListState::Completed);
        dl.startPc = r.u32v();
        dl.stall = r.u32v();
        dl.cbid = r.s32v();
        dl.contextAddr = r.u32v();
        dl.numStacks = r.u32v();
        dl.stackAddr = r.u32v();
        dl.started = r.b();
        dl.hung = r.b();
        getList(r, dl.regs);
        dl.offset = r.u32v();
        dl.base = r.u32v();
        dl.cycles = r.u64v();
    }
    for (auto& cb : s.callbacks) {
        cb.used = r.b();
        for (u32* v : {&cb.signalFunc, &cb.signalArg, &cb.finishFunc, &cb.finishArg}) *v = r.u32v();
    }
    getSlots(r, s.queue);
    getSlots(r, s.freeSlots);
    s.active = r.s32v();
    s.brokeInCallback = r.b();
    s.finishPending = r.b();
    s.finishArg = r.u32v();
    s.finishPc = r.u32v();
    s.sdkVersion = r.u32v();
    edramTranslation = r.u32v();
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
    Writer w;
    w.section(kEngine, [&] { putEngine(w, engine.saved()); });
    w.section(kSce, [&] { putSce(w, sce.saved(), engine.memory().edramTranslation()); });
    w.section(kHost, [&] { w.b(host.heldInterrupt); });
    w.section(kV3, [&] {
        for (u32 v : engine.state().visibleMtx) w.u32v(v);
        const SceGe::Saved s = sce.saved();
        for (const auto& dl : s.lists) w.b(dl.pausedBySignal);
        w.s32v(s.suspendedSlot);
    });
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
        Reader r(body, n);
        for (u32& v : e.state.visibleMtx) v = r.u32v() & 0xFFFFFF;
        for (auto& dl : s.lists) dl.pausedBySignal = r.b();
        s.suspendedSlot = r.s32v();
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
        Reader r(body, n);
        if (t == kEngine) getEngine(r, e, version);
        else if (t == kSce) getSce(r, s, edram);
        else if (t == kHost) hf.heldInterrupt = r.b();
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
