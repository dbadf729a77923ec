// SPDX-License-Identifier: MIT
// Rendering a dump with a chosen backend: shared by the CLI, the tests and the benchmarks.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend/factory.h"
#include "hle/dump/player.h"
#include "hle/ge_engine.h"
#include "tools/lib/image.h"

namespace ge::tools {

struct RenderOptions {
    std::string backend = "soft";  // "soft" | "gl" | "null"
    // "psp" | "ppsspp" (geometry/accuracy_profile.h): what the GE does, or PPSSPP's software
    // renderer's pixels (its frametest references).
    std::string accuracy = "psp";
    u64 replayEnd = 0;             // stop after the Nth draw (0 = all)
    dump::ReplayTiming replayTiming = dump::ReplayTiming::Ppsspp;  // when the GE runs (player.h)
    double maxGeMs = dump::ReplayOptions::kDefaultMaxGeMs;  // GE-time budget (player.h), 0 = none
    int threads = 0;               // software model threads (0 = all cores)
    std::string glContext = "osmesa";  // "osmesa" | "egl" | "null" (GL calls do nothing: CPU cost only)
    bool glBaseline = false;       // GL: force the GL 3.3 baseline paths
    std::string glMode = "exact";  // GL: "exact" | "hw" (gl_renderer.h GlMode)
    int scale = 1;                 // GL hw: render scale 1–8
    std::string glVertices = "auto";  // GL hw: "auto" | "gpu" | "cpu" (GlOptions::vertices)
    std::string shaderDumpDir, programCacheDir;
    // --skip / --only (tools/lib/draw_select.h): when set, a DrawHook between the engine and the
    // backend passes draw n (numbered from 1) on only if keepDraw(n). Null: every draw, no hook.
    std::function<bool(u64 draw)> keepDraw;
};

struct RenderOutput {
    Image frame;                   // 480x272 RGBA, alpha 255 (at render scale N: frameScaled box-downsampled)
    Image frameScaled;             // 480N x 272N at render scale N > 1 (GL hw), else empty
    u32 displayAddr = 0, displayStride = 0, displayFormat = 0;
    u32 depthAddr = 0, depthStride = 0;
    dump::ReplayResult replay;
    GeStats engineStats;
    std::string backendStats;      // backend's own counters (GL), may be empty
    double seconds = 0;            // load + replay + readback
};

// Where the CLI keeps GL program binaries unless told otherwise: $XDG_CACHE_HOME/ge2gl/programs,
// else $HOME/.cache/ge2gl/programs (XDG Base Directory), else "" (none).
std::string defaultProgramCacheDir();

// Backends by name (backend/factory.h); a backend not compiled in gives a clear error.
backend::Backend createBackend(const RenderOptions& opt, Memory& mem, std::string& err);
// The backend's own counters (those that offer them: GL), else empty.
std::string backendStats(const backend::Backend& b);

// Loads and replays one dump file. `vramOut`, when non-null, receives the 2 MiB of VRAM after the
// frame (linear view, exactly as a game reading 0x04000000–0x041FFFFF sees it).
bool renderDumpFile(const std::string& path, const RenderOptions& opt, RenderOutput& out, std::string& err,
                    std::vector<u8>* vramOut = nullptr, std::vector<u16>* depthOut = nullptr);
// `reuse`, when non-null, is cleared (Memory::clear) and replayed into instead of a fresh Memory:
// `ge2gl bench` keeps one for all its runs; it holds the frame afterwards.
// `held`, when non-null, keeps the backend between calls (with `reuse`): a held one is told that
// all of memory changed and replayed into again — the steady state of an emulator's next frame
// (textures decoded, programs compiled); an empty one is filled.
bool renderDump(const dump::Dump& d, const RenderOptions& opt, RenderOutput& out, std::string& err,
                std::vector<u8>* vramOut = nullptr, std::vector<u16>* depthOut = nullptr, Memory* reuse = nullptr,
                backend::Backend* held = nullptr);

// "NAME" of a dump path: file name without directories and without .zip / .ppdmp suffixes.
std::string dumpName(const std::string& path);

}  // namespace ge::tools
