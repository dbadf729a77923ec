// Replays a .ppdmp frame dump on a GeEngine (ppdmp-format.md §6): rebuilds guest memory and a
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

struct ReplayOptions {
    // Stop after the Nth draw kick (PRIM/BEZIER/SPLINE, counted from 1); 0 = whole frame.
    u64 replayEnd = 0;
};

struct ReplayResult {
    bool hasDisplay = false;        // a DISPLAY record was seen
    u32 displayAddr = 0, displayStride = 512, displayFormat = GE_FORMAT_8888;
    u64 draws = 0, records = 0;
    u64 listErrors = 0;             // list errors met (the player restarts the list and goes on)
    std::string warning;            // first non-fatal problem, if any
};

// Frame buffer of the result: the last DISPLAY record, else the last frame buffer set (FBP/FBW/FPF).
void displayedFramebuffer(const ReplayResult& r, const GeState& st, u32& addr, u32& stride, u32& format);

// Replays the whole dump. Returns false with a one-line error for an unplayable dump (unknown
// record type, missing INIT); memory and engine are left in a defined state either way.
// The engine's renderer has flushToMemory() called at the end.
bool replayDump(const Dump& d, GeEngine& engine, const ReplayOptions& opt, ReplayResult& result, std::string& err);

}  // namespace ge::dump
