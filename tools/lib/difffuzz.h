// SPDX-License-Identifier: MIT
// `ge2gl fuzz`: a differential fuzzer (accuracy tools). Each case is a small random but
// valid GE scene — state drawn from the field table's legal ranges, weighted toward what games use,
// 1–4 PRIM draws of every primitive type and vertex format, a random texture of any format — made
// with ListBuilder + DumpRecorder into an in-memory dump and rendered by two backends (gl exact 1x
// against soft by default). The frame buffers are compared exactly; a case that differs is
// minimised (state groups, draws and vertices dropped while it still differs, a bounded number of
// tries) and written as DIR/case-SEED.ppdmp with a one-line cause.
//
// What is compared: the 480x272 colour buffer as stored in VRAM (every bit of each pixel: RGB and,
// for 5551/4444/8888, the alpha/stencil bits), and the depth buffer with `compareDepth`. With
// `rgbOnly` the alpha/stencil bits are masked out (what a screen shows); with `maxMse` the frames
// may differ up to that MSE (a pair that is not bit-exact, such as GL hardware mode against soft).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "hle/dump/ppdmp.h"
#include "tools/lib/render.h"

namespace ge::tools {

struct FuzzItem {
    bool draw = false;
    std::vector<u32> words;   // state group (draw false): command words emitted as they are
    u32 prim = 0, vtype = 0, count = 0;  // draw: PRIM type, VTYPE, vertex (index) count
    std::vector<u8> indices, vertices;   // draw data (indices empty unless vtype has IDX)
};

// One case: a frame-buffer prologue that minimisation keeps (FPF/FBP/FBW, depth buffer, scissor,
// region, viewport, offset, depth range, a clear), RAM data (texture, CLUT) and the items.
struct FuzzCase {
    u64 seed = 0;
    u32 fbFormat = 3;
    u32 clearColor = 0, clearDepth = 0;
    std::vector<std::pair<u32, std::vector<u8>>> data;  // guest RAM address, bytes
    std::vector<FuzzItem> items;
    size_t weight() const;  // words + vertex count: what minimisation shrinks
};

FuzzCase generateFuzzCase(u64 seed);
dump::Dump recordFuzzCase(const FuzzCase& c);

struct FuzzOptions {
    RenderOptions render;  // base options (backend names are replaced by the two below)
    std::string backend = "gl", refBackend = "soft";
    // The reference side's accuracy profile (the first side's is render.accuracy); empty: the same.
    std::string refAccuracy;
    u64 seed = 1, count = 100;
    std::string outDir;    // minimised failing cases go here (none written when empty)
    std::string jsonPath;
    bool rgbOnly = false, compareDepth = false;
    // >= 0: the colour buffers need not match bit for bit; a case diverges when the displayed
    // frames' RGB MSE (PPSSPP's measure, image.h mseRGB) exceeds this. For a backend pair that is
    // not meant to be bit-exact (GL hardware mode against soft: the tolerance docs/accuracy.md
    // gives that mode). The depth comparison (compareDepth) stays exact.
    double maxMse = -1;
    int minimiseTries = 300;  // renders of candidate cases per failing case (0: no minimisation)
    bool quiet = false;
    // Test seam: when set, the reference side's RenderOptions::keepDraw (forces divergences).
    std::function<bool(u64 draw)> refKeepDraw;
};

struct FuzzFailure {
    u64 seed = 0;
    std::string cause;       // first differing pixel, both values, owning draw and its state
    std::string path;        // written dump ("" when no --out)
    size_t weightBefore = 0, weightAfter = 0;
    size_t bytesBefore = 0, bytesAfter = 0;  // push-buffer bytes of the recorded dump
    dump::Dump minimised;
};

struct FuzzSummary {
    u64 cases = 0, divergences = 0, errors = 0;
    double seconds = 0;
    std::vector<FuzzFailure> failures;
    std::vector<std::string> errorMessages;
};

// Renders `d` on both sides and compares. Returns false on a render error (err set). `differs` and
// `cause` (first difference) are filled. Backends and memories are reused between calls when the
// state pointers are given (null: fresh ones).
struct FuzzSides;
bool fuzzCompare(const dump::Dump& d, const FuzzOptions& o, FuzzSides* sides, bool& differs, std::string& cause,
                 std::string& err);

bool runFuzz(const FuzzOptions& o, FuzzSummary& out, std::string& err);
// The subcommand: progress, summary, --json. Exit code 0 when no case diverged, 1 when some did, 2 on errors.
int runFuzzCommand(const FuzzOptions& o);

}  // namespace ge::tools
