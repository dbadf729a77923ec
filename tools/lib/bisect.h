// SPDX-License-Identifier: MIT
// `ge2gl bisect`: the first draw after which two replays' VRAM differ (accuracy tools).
//
// One lockstep replay: each side (DUMP on --backend A; DUMP on --ref-backend B, or --ref-dump
// OTHER on A) replays on its own thread with a tools::DrawHook; after every draw each side syncs
// what is compared from its backend into guest memory and waits for the other; the second to
// arrive compares the two snapshots. Once a draw differs, the remaining draws of both sides are
// skipped (DrawHook::keep) and the replays run out without drawing.
//
// What is compared after draw n (each side reading its own state):
//   default: the colour buffer of draw n's target (FBP/FBW/FPF) inside the union of both sides'
//     scissor rectangles, decoded to 8 bits per channel, R, G, B and A (alpha = stencil bits), a
//     pixel differing when any channel differs by more than --tolerance; and, unless
//     --ignore-depth, the 16-bit depth buffer (ZBP/ZBW) in the same rectangle, exactly. A draw
//     writes nothing else, so the first draw that changes its own output is found; a difference
//     made by a block transfer or a CPU copy shows at the next draw whose target holds it.
//   --all-vram: all 2 MiB of VRAM byte for byte (after a sync of all of it), so differences
//     anywhere — other buffers, transfers — show at the next draw.
// A side that runs out of draws first differs at the first draw only the other has.
#pragma once
#include <string>
#include <vector>

#include "hle/dump/player.h"
#include "tools/lib/blame.h"
#include "tools/lib/render.h"

namespace ge::tools {

struct BisectOptions {
    std::string refBackend;  // side B: the same dump on this backend, or
    std::string refDumpPath; // side B: another dump on side A's backend
    bool ignoreDepth = false;
    bool allVram = false;
    int tolerance = 0;       // per channel, 0–255
    std::string jsonPath;
};

struct BisectResult {
    bool found = false;
    u64 draw = 0;                 // first differing draw (DrawHook numbering, from 1)
    u64 drawsA = 0, drawsB = 0;   // draws each side replayed (up to the stop)
    std::string reason;           // "colour", "depth", "target", "vram", "draw count"
    DrawInfo infoA, infoB;        // draw n on each side (infoX.draw 0: that side has no draw n)
    int rx0 = 0, ry0 = 0, rx1 = -1, ry1 = -1;  // compared rectangle (inclusive), colour/depth modes
    u64 colourPixels = 0, depthPixels = 0;     // differing pixels of each kind
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;      // bounding box of all differing pixels (inclusive)
    u64 vramBytes = 0;            // --all-vram: differing bytes
    u32 firstVramAddr = 0, lastVramAddr = 0;
    std::vector<u32> commandsA, commandsB;     // the dump words since draw n-1, up to draw n's kick
};

// Runs the lockstep replay. `b` may be the same object as `a` (--ref-backend).
bool bisectDumps(const dump::Dump& a, const RenderOptions& roA, const dump::Dump& b, const RenderOptions& roB,
                 const BisectOptions& bo, BisectResult& out, std::string& err);

// The command words of a dump's REGISTERS records after draw n-1's kick up to and including draw
// n's kick. Draws are counted as the engine hands them to a backend: PRIM with a non-zero count,
// BEZIER/SPLINE with non-zero control points (immediate-mode draws are not counted here).
// `truncated` is set when more than `maxWords` words lie between them (the last maxWords are kept).
std::vector<u32> commandsBeforeDraw(const dump::Dump& d, u64 n, size_t maxWords, bool& truncated);

int runBisectCommand(const std::string& dumpPath, const RenderOptions& ro, const BisectOptions& bo);

}  // namespace ge::tools
