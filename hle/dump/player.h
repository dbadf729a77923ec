// SPDX-License-Identifier: MIT
// Replays a .ppdmp frame dump on a GeEngine (docs/ppdmp.md §6): rebuilds guest memory and a
// runnable display list from the records, executes it with the engine's current backend, and
// reports the frame buffer to show.
#pragma once
#include <string>

#include "hle/dump/ppdmp.h"
#include "hle/ge_engine.h"

namespace ge::dump {

// Counts that need no replay: commands in REGISTERS blocks and draw kicks (PRIM/BEZIER/SPLINE).
struct DumpSummary {
    u64 commands = 0, draws = 0, prims = 0, patches = 0, transfers = 0, clutLoads = 0;
    u64 recordsByType[32] = {};
    u64 unknownRecords = 0;
};
DumpSummary summarize(const Dump& d);

// When the GE runs during a replay (ppdmp.md §6.2 "When the GE runs").
enum class ReplayTiming {
    // As PPSSPP's player (GPU/Debugger/Playback.cpp DumpExecute): REGISTERS blocks are appended
    // without moving the stall address; the GE catches up only at the player's sync points (a
    // payload that needs a new slab or extra, TRANSFERSRC, the list-buffer wrap, MEMSET/MEMCPYDATA
    // to VRAM, EDRAMTRANS, DISPLAY, the end). FRAMEBUF and VRAM CLUT bytes land at once, before
    // draws recorded ahead of them that have not run. What dumps recorded by PPSSPP need.
    Ppsspp,
    // The list runs after every REGISTERS block: for dumps written by tools that expect each
    // block to have executed before the next data record is applied.
    Eager,
};
const char* replayTimingName(ReplayTiming t);
bool parseReplayTiming(const std::string& s, ReplayTiming& out);

struct ReplayOptions {
    // Stop after the Nth draw kick (PRIM/BEZIER/SPLINE, counted from 1); 0 = whole frame.
    u64 replayEnd = 0;
    ReplayTiming timing = ReplayTiming::Ppsspp;
    // The replay's budget in emulated GE time (hle/ge_time.h), milliseconds; 0 = no limit. The
    // GE's work and the CPU/DMA copies the dump replays (charged like block transfers) count;
    // once it is used up the rest of the frame is not drawn and ReplayResult::warning says so.
    // Default: 10 frames at 60 Hz. A real frame stays far below (the 20 frametests: docs/timing.md).
    double maxGeMs = kDefaultMaxGeMs;
    static constexpr double kDefaultMaxGeMs = 1000.0 / 6.0;
};

struct ReplayResult {
    bool hasDisplay = false;        // a DISPLAY record was seen
    u32 displayAddr = 0, displayStride = 512, displayFormat = GE_FORMAT_8888;
    u64 draws = 0, records = 0;
    u64 listErrors = 0;             // list errors met (the player restarts the list and goes on)
    u64 syncs = 0;                  // times the GE was let catch up (stall address moved)
    u64 slabMaps = 0, extraMaps = 0, listWraps = 0;  // push-buffer mappings, list-buffer wraps
    // The player's own work on REGISTERS records (docs/ppdmp.md §6.2): distinct payloads scanned
    // for the words it rewrites (once per payload offset and size; a record that repeats one
    // reuses the scan) and the bytes it scanned, and the bytes it wrote into its list buffer.
    // Both byte counts are charged to the GE-time budget at a host copy's pace (hle/ge_time.h).
    u64 blockScans = 0, scannedBytes = 0, listBytes = 0;
    // Other copies: the player's own (push-buffer slabs and extras, FRAMEBUF and VRAM CLUT
    // bytes), charged like the above, and the game's CPU/DMA writes (MEMSET, MEMCPYDATA into
    // VRAM), charged as block transfers.
    u64 playerBytes = 0, cpuBytes = 0;
    u64 geCycles = 0;               // GE-time estimate of the replay (hle/ge_time.h), copies included
    bool timeLimitHit = false;      // the GE-time budget ran out: the frame is cut short
    std::string warning;            // first non-fatal problem, if any
};

// What the player drives: a GE plus its memory, as an emulator would see it. replayDump() on a
// GeEngine uses EngineTarget; the plugin API tests implement it over the C ABI, so both replay the
// same command stream.
class ReplayTarget {
public:
    virtual ~ReplayTarget() = default;
    virtual u32 ramSize() const = 0;
    // A host (CPU/DMA) write into guest memory; returns the bytes written (clipped to valid memory).
    virtual u32 write(u32 addr, const void* data, u32 size) = 0;
    virtual u32 fill(u32 addr, u8 value, u32 size) = 0;
    virtual void loadContext(const u32 ctx[512]) = 0;
    virtual void startList(u32 pc, u32 stall) = 0;
    // Moves the stall address and lets the GE run until it stalls, ends or spends the budget.
    virtual RunStatus runTo(u32 stall, u64 budget) = 0;
    virtual std::string lastError() = 0;
    virtual u32 readRegister(u8 op) = 0;
    virtual bool setEdramTranslation(u32 value) = 0;
    // The frame is complete: make emulated VRAM hold every pixel drawn.
    virtual void finishFrame() = 0;
    // The GE-time estimate so far (hle/ge_time.h) and a limit at which runTo stops with
    // RunStatus::TimeLimit. A target without a cost model returns 0 and ignores the limit.
    virtual u64 geCycles() { return 0; }
    virtual void setTimeLimit(u64 /*cycles*/) {}
};

class EngineTarget : public ReplayTarget {
public:
    explicit EngineTarget(GeEngine& e) : eng_(e) {}
    u32 ramSize() const override { return eng_.memory().ramSize(); }
    u32 write(u32 addr, const void* data, u32 size) override;
    u32 fill(u32 addr, u8 value, u32 size) override;
    void loadContext(const u32 ctx[512]) override { eng_.loadContext(ctx); }
    void startList(u32 pc, u32 stall) override { eng_.startList(pc, stall); }
    RunStatus runTo(u32 stall, u64 budget) override {
        eng_.setStall(stall);
        return eng_.run(budget);
    }
    std::string lastError() override { return eng_.lastErrorMessage(); }
    u32 readRegister(u8 op) override { return eng_.state().regs[op]; }
    bool setEdramTranslation(u32 v) override { return eng_.memory().setEdramTranslation(v); }
    void finishFrame() override { eng_.renderer()->flushToMemory(); }
    u64 geCycles() override { return eng_.stats().cycles; }
    void setTimeLimit(u64 cycles) override { eng_.setTimeLimit(cycles); }

private:
    GeEngine& eng_;
};

bool replayDump(const Dump& d, ReplayTarget& target, const ReplayOptions& opt, ReplayResult& result, std::string& err);

// Frame buffer of the result: the last DISPLAY record, else the last frame buffer set (FBP/FBW/FPF).
void displayedFramebuffer(const ReplayResult& r, const GeState& st, u32& addr, u32& stride, u32& format);

// Replays the whole dump. Returns false with a one-line error for an unplayable dump (unknown
// record type, missing INIT); memory and engine are left in a defined state either way.
// The engine's renderer has flushToMemory() called at the end.
bool replayDump(const Dump& d, GeEngine& engine, const ReplayOptions& opt, ReplayResult& result, std::string& err);

}  // namespace ge::dump
