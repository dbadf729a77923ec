// SPDX-License-Identifier: MIT
// Shared pieces of the libFuzzer harnesses (docs/fuzzing.md): a forward byte reader, the work caps
// that keep one input well under a second whatever it asks for, and a Renderer / ReplayTarget
// pair that applies them.
//
// Why bounds in the harness: the tools bound a replay in emulated GE time (ReplayOptions::maxGeMs,
// ten frames by default), which under the sanitizers and coverage tracing still buys seconds of
// shading. A fuzzer that waits seconds per input finds little, and libFuzzer's -timeout would
// report valid (if slow) behaviour as a finding. So each input gets 0.1 ms of GE time (kMaxGeMs)
// and, as backstops, caps on draws, vertices, tessellated vertices, transfer bytes, bounding-box
// pixels and commands (Caps); draws are clipped to the last 64x64 pixels of their clip rectangle
// (the rasteriser and pixel pipeline run the same code for every pixel, so many small draws
// cover more than a few large ones). Work beyond the caps is dropped; the rest runs exactly as
// it does in the tools.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/ge_engine.h"
#include "hle/ge_time.h"
#include "hle/renderer.h"

namespace ge::fuzz {

// Largest input a harness looks at (scripts/fuzz.sh passes a -max_len of at most this).
constexpr size_t kMaxInput = size_t(1) << 20;

// Reads little-endian values front to back; past the end it yields zeros.
class Bytes {
public:
    Bytes(const u8* data, size_t size) : p_(data), n_(size) {}
    bool empty() const { return i_ >= n_; }
    size_t left() const { return n_ - i_; }
    const u8* here() const { return p_ + i_; }
    u8 u8v() { return i_ < n_ ? p_[i_++] : 0; }
    u16 u16v() {
        u16 lo = u8v();
        return u16(lo | (u16(u8v()) << 8));
    }
    u32 u32v() {
        u32 lo = u16v();
        return lo | (u32(u16v()) << 16);
    }
    // Up to `n` bytes; advances past them.
    size_t take(size_t n, const u8*& out) {
        n = std::min(n, left());
        out = p_ + i_;
        i_ += n;
        return n;
    }

private:
    const u8* p_;
    size_t n_;
    size_t i_ = 0;
};

// The replay harnesses take a dump in either of two forms:
//  - a .ppdmp file or a zip holding one (recognised by "PPSSPPGE" / "PK"), loaded as the tools do;
//  - the "open" form, which leaves the records and payloads uncompressed so that mutations reach
//    them instead of breaking a zstd stream: u8 version, u16 record count n, n records of 9 bytes
//    (u8 type, u32 size, u32 ptr, as in the file, docs/ppdmp.md §3.1), then the push buffer.
// fuzz_seeds writes every seed dump in the open form (toOpenForm).
inline bool loadFuzzDump(const u8* data, size_t size, dump::Dump& d, std::string& err) {
    if (size >= 8 && std::memcmp(data, "PPSSPPGE", 8) == 0) return dump::loadDumpFromMemory(data, size, d, err);
    if (size >= 2 && data[0] == 'P' && data[1] == 'K') return dump::loadZipFromMemory(data, size, d, err);
    Bytes in(data, size);
    d.version = std::clamp<u32>(in.u8v(), dump::kMinVersion, dump::kMaxVersion);
    const u32 n = in.u16v();
    if (u64(n) * dump::kRecordBytes > in.left()) return false;
    d.records.resize(n);
    for (dump::Record& r : d.records) {
        r.type = in.u8v();
        r.size = in.u32v();
        r.ptr = in.u32v();
    }
    d.pushbuf.assign(in.here(), in.here() + in.left());
    return true;
}
inline std::vector<u8> toOpenForm(const dump::Dump& d) {
    std::vector<u8> out;
    auto put = [&](u32 v, int bytes) {
        for (int i = 0; i < bytes; ++i) out.push_back(u8(v >> (8 * i)));
    };
    const size_t n = std::min<size_t>(d.records.size(), 0xFFFF);
    put(d.version, 1);
    put(u32(n), 2);
    for (size_t i = 0; i < n; ++i) {
        put(d.records[i].type, 1);
        put(d.records[i].size, 4);
        put(d.records[i].ptr, 4);
    }
    out.insert(out.end(), d.pushbuf.begin(), d.pushbuf.end());
    return out;
}

// What one input may cost. Pixels are the backend's bounding-box count (Renderer::pixelWork,
// when the backend reports it).
struct Caps {
    u64 draws = 4096;                // PRIM / patch / immediate packets handed on
    u64 vertices = u64(1) << 18;     // sum of PRIM counts
    u32 drawVertices = 4096;         // one PRIM's count is cut to this
    u64 patchVertices = u64(1) << 14;  // tessellated vertices over all patches (an upper bound)
    u64 transferBytes = u64(32) << 20;
    u64 pixels = u64(4) << 20;       // bounding-box pixels (Renderer::pixelWork)
    u64 commands = u64(1) << 20;     // GE commands over all runs (BoundedTarget)
    // Draws go to at most the last window x window pixels of their clip rectangle (scissor ∩
    // REGION2): the far corner, where a frame buffer runs off the end of VRAM, stays reachable.
    // 0 = the whole clip rectangle.
    u32 window = 64;
};

// Hands packets on to `inner` until a cap is reached, then drops them (counted).
class BoundedRenderer : public Renderer {
public:
    BoundedRenderer(Renderer& inner, const Caps& caps = {}) : in_(inner), caps_(caps) {}

    void reset() { draws_ = vertices_ = patchVerts_ = transferBytes_ = dropped_ = 0, pixelBase_ = in_.pixelWork(); }
    u64 dropped() const { return dropped_; }

    void drawPrim(const PrimPacket& p) override {
        if (!room(p.count)) return;
        PrimPacket q = p;
        q.state = windowed(*p.state);
        q.count = std::min(q.count, caps_.drawVertices);
        vertices_ += q.count;
        in_.drawPrim(q);
    }
    void drawPatch(const PatchPacket& p) override {
        // The tessellator's own output bound (geometry/spline.cpp), per direction.
        const u64 du = std::max<u32>(p.divU, 1), dv = std::max<u32>(p.divV, 1);
        const u64 est = (u64(p.ucount) * du + 1) * (u64(p.vcount) * dv + 1);
        if (!room(0) || patchVerts_ + est > caps_.patchVertices) {
            ++dropped_;
            return;
        }
        patchVerts_ += est;
        PatchPacket q = p;
        q.state = windowed(*p.state);
        in_.drawPatch(q);
    }
    void drawImmediate(const ImmPacket& p) override {
        if (!room(u32(std::min<size_t>(p.vertices.size(), ~0u)))) return;
        vertices_ += p.vertices.size();
        ImmPacket q = p;
        q.state = windowed(*p.state);
        in_.drawImmediate(q);
    }
    void blockTransfer(const TransferPacket& t, Memory& mem) override {
        const u64 bytes = u64(t.width) * t.height * t.bpp;
        if (transferBytes_ + bytes > caps_.transferBytes) {
            ++dropped_;
            return;
        }
        transferBytes_ += bytes;
        in_.blockTransfer(t, mem);
    }
    void clutLoaded(const GeState& st) override { in_.clutLoaded(st); }
    void textureFlush() override { in_.textureFlush(); }
    void textureSync() override { in_.textureSync(); }
    void finish() override { in_.finish(); }
    void syncMemoryForRead(u32 addr, u32 size) override { in_.syncMemoryForRead(addr, size); }
    void memoryWritten(u32 addr, u32 size) override { in_.memoryWritten(addr, size); }
    void flushToMemory() override { in_.flushToMemory(); }
    // The engine charges GE time for the inner backend's pixels (hle/ge_time.h).
    u64 pixelWork() const override { return in_.pixelWork(); }

private:
    // The packet's state with SCISSOR1 moved up to the last window x window pixels of the clip
    // rectangle (a copy: packets may point at it only during the call, renderer.h).
    const GeState* windowed(const GeState& st) {
        if (!caps_.window) return &st;
        const u32 x2 = std::min(st.SCISSOR2_x(), st.REGION2_x()), y2 = std::min(st.SCISSOR2_y(), st.REGION2_y());
        const u32 x1 = std::max(st.SCISSOR1_x(), x2 >= caps_.window ? x2 - caps_.window + 1 : 0);
        const u32 y1 = std::max(st.SCISSOR1_y(), y2 >= caps_.window ? y2 - caps_.window + 1 : 0);
        copy_ = st;
        copy_.regs[GE_CMD_SCISSOR1] = (u32(GE_CMD_SCISSOR1) << 24) | (y1 << 10) | x1;
        return &copy_;
    }
    bool room(u32 count) {
        const bool ok = draws_ < caps_.draws && vertices_ + std::min(count, caps_.drawVertices) <= caps_.vertices &&
                        in_.pixelWork() - pixelBase_ < caps_.pixels;
        if (ok) ++draws_;
        else ++dropped_;
        return ok;
    }

    Renderer& in_;
    Caps caps_;
    GeState copy_;
    u64 draws_ = 0, vertices_ = 0, patchVerts_ = 0, transferBytes_ = 0, dropped_ = 0, pixelBase_ = 0;
};

// The dump player's target with a cap on the GE commands of all its runs together.
class BoundedTarget : public dump::EngineTarget {
public:
    BoundedTarget(GeEngine& e, u64 maxCommands) : EngineTarget(e), eng_(e), left_(maxCommands) {}
    RunStatus runTo(u32 stall, u64 budget) override {
        if (left_ == 0) return RunStatus::Budget;
        const u64 before = eng_.stats().commands;
        const RunStatus s = EngineTarget::runTo(stall, std::min(budget, left_));
        const u64 ran = eng_.stats().commands - before;
        left_ -= std::min(ran, left_);
        return s;
    }

private:
    GeEngine& eng_;
    u64 left_;
};

// Executes up to `maxWords` state words from the input (a count byte, then the words) on `eng`,
// as a list would: matrices upload, CLOAD reads its palette. Flow control, kicks and transfers
// are left out (the harnesses that use this drive one piece of the pipeline directly).
inline void applyStateWords(GeEngine& eng, Bytes& in, u32 maxWords) {
    const u32 n = std::min<u32>(in.u8v(), maxWords);
    for (u32 i = 0; i < n; ++i) {
        const u32 w = in.u32v();
        if (u8(w >> 24) >= GE_CMD_X2) continue;  // immediate-mode vertices and what follows them
        switch (u8(w >> 24)) {
        case GE_CMD_PRIM: case GE_CMD_BEZIER: case GE_CMD_SPLINE: case GE_CMD_BBOX: case GE_CMD_JUMP:
        case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET: case GE_CMD_END: case GE_CMD_SIGNAL:
        case GE_CMD_FINISH: case GE_CMD_XSTART:
            break;
        default:
            eng.execute(w);
        }
    }
}

// GE time one replay may use (ReplayOptions::maxGeMs, hle/ge_time.h):
// 0.1 ms, about 66,000 bounding-box pixels (16 draws filling the 64x64 window) plus commands and
// vertices. Shading dominates a replay's cost under the sanitizers and coverage tracing (~50 ms
// for a full 480x272 scene), so the replay harnesses draw little of each input; the seeds are
// cut into short pieces of the real dumps (fuzz_seeds) so that more of their draws get reached.
// Measured on fuzz_replay_soft's corpus (1,584 inputs): 0.5 ms ran it in 23-29 s and reached
// 4,120 edges, 0.2 ms 16 s and 4,059, 0.1 ms 10 s and 3,952 -- 2.5 times the executions for 4%
// of the edges, which mutations that drop records reach again.
constexpr double kMaxGeMs = 0.1;
// The same for a GeEngine run directly (GeEngine::setTimeLimit).
constexpr u64 kGeTimeCycles = u64(kMaxGeMs * getime::kCyclesPerSecond / 1000);

}  // namespace ge::fuzz
