// Rendering a dump with a chosen backend: shared by the CLI, the tests and the benchmarks.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "hle/dump/player.h"
#include "hle/ge_engine.h"
#include "tools/lib/image.h"

namespace ge::tools {

struct RenderOptions {
    std::string backend = "soft";  // "soft" | "gl" | "null"
    u64 replayEnd = 0;             // stop after the Nth draw (0 = all)
    dump::ReplayTiming replayTiming = dump::ReplayTiming::Ppsspp;  // when the GE runs (player.h)
    double maxGeMs = dump::ReplayOptions::kDefaultMaxGeMs;  // GE-time budget (player.h), 0 = none
    int threads = 0;               // software model threads (0 = all cores)
    std::string glContext = "osmesa";  // "osmesa" | "egl"
    bool glBaseline = false;       // GL: force the GL 3.3 baseline paths
    std::string shaderDumpDir, programCacheDir;
};

struct RenderOutput {
    Image frame;                   // 480x272 RGBA, alpha 255
    u32 displayAddr = 0, displayStride = 0, displayFormat = 0;
    u32 depthAddr = 0, depthStride = 0;
    dump::ReplayResult replay;
    GeStats engineStats;
    std::string backendStats;      // backend's own counters (GL), may be empty
    double seconds = 0;            // load + replay + readback
};

// Backends by name; a backend not compiled in gives a clear error.
std::unique_ptr<Renderer> createBackend(const RenderOptions& opt, Memory& mem, std::string& err);
std::string backendStats(const std::string& backend, const Renderer& r);

// Loads and replays one dump file. `vramOut`, when non-null, receives the 2 MiB of VRAM after the
// frame (linear view, exactly as a game reading 0x04000000–0x041FFFFF sees it).
bool renderDumpFile(const std::string& path, const RenderOptions& opt, RenderOutput& out, std::string& err,
                    std::vector<u8>* vramOut = nullptr, std::vector<u16>* depthOut = nullptr);
// `reuse`, when non-null, is cleared (Memory::clear) and replayed into instead of a fresh Memory:
// `ge2gl bench` keeps one for all its runs; it holds the frame afterwards.
bool renderDump(const dump::Dump& d, const RenderOptions& opt, RenderOutput& out, std::string& err,
                std::vector<u8>* vramOut = nullptr, std::vector<u16>* depthOut = nullptr, Memory* reuse = nullptr);

// "NAME" of a dump path: file name without directories and without .zip / .ppdmp suffixes.
std::string dumpName(const std::string& path);

}  // namespace ge::tools
