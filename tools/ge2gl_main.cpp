// SPDX-License-Identifier: MIT
// The ge2gl command-line tool: info, disasm, render, compare, merge, report, bench, blame, bisect, fuzz.
// Errors are one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "geometry/accuracy_profile.h"
#include "hle/disasm.h"
#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/ge_time.h"
#include "tools/lib/bisect.h"
#include "tools/lib/blame.h"
#include "tools/lib/image.h"
#include "tools/lib/render.h"
#include "tools/lib/step.h"
#include "tools/lib/batch.h"
#include "tools/lib/draw_select.h"
#include "tools/lib/difffuzz.h"
#include "tools/lib/report.h"

using namespace ge;
namespace fs = std::filesystem;

#ifdef GE2GL_JEMALLOC
namespace ge::tools {
std::string allocatorDescription();  // tools/cli_allocator.cpp
}
#endif

namespace {

// --version: the release and the allocator this build of the CLI runs with (tools/cli_allocator.cpp).
std::string versionText() {
#ifdef GE2GL_JEMALLOC
    return "ge2gl 0.1.0\n" + tools::allocatorDescription();
#else
    return "ge2gl 0.1.0\nallocator: the C library's malloc";
#endif
}

// A whole number from 0 to `max` in decimal digits: no sign, no wrap-around, no overflow.
CLI::Validator wholeNumber(u64 max) {
    return CLI::Validator(
        [max](std::string& v) -> std::string {
            const std::string why = "must be a whole number from 0 to " + std::to_string(max);
            if (v.empty() || v.size() > 19 || v.find_first_not_of("0123456789") != std::string::npos) return why;
            if (std::stoull(v) > max) return why;
            return {};
        },
        "0.." + std::to_string(max));
}

int fail(const std::string& msg) {
    std::fprintf(stderr, "ge2gl: %s\n", msg.c_str());
    return 1;
}

// `info --timing`: the frame replayed on the software model (its bounding boxes give the pixel
// work) and the GE-time estimate of hle/ge_time.h, in parts (docs/timing.md).
void printTiming(const dump::Dump& d) {
    tools::RenderOptions opt;
    tools::RenderOutput out;
    std::string err;
    if (!tools::renderDump(d, opt, out, err)) {
        std::printf("  GE time:   not measured: %s\n", err.c_str());
        return;
    }
    const GeStats& s = out.engineStats;
    auto ms = [](u64 c) { return getime::msFromCycles(c); };
    const u64 copies = out.replay.geCycles > s.cycles ? out.replay.geCycles - s.cycles : 0;
    std::printf("  GE time:   %.3f ms (%llu ticks at 222 MHz)\n", ms(s.cycles), (unsigned long long)s.cycles);
    std::printf("    commands %.3f ms, vertices %.3f ms, pixels %.3f ms, transfers %.3f ms\n", ms(s.cyclesCommands),
                ms(s.cyclesVertices), ms(s.cyclesPixels), ms(s.cyclesTransfers));
    // PPSSPP's estimate counts the same commands, vertices and transfers (its formulas are the
    // model's) but no pixel fill.
    std::printf("    PPSSPP's model (no pixel fill): %.3f ms\n", ms(s.cycles - s.cyclesPixels));
    std::printf("  replay copies: %.3f ms (memory the dump's player writes, charged as DMA)\n", ms(copies));
    if (out.replay.timeLimitHit) std::printf("  (cut short by the GE-time budget: %s)\n", out.replay.warning.c_str());
}

int cmdInfo(const std::vector<std::string>& files, bool timing) {
    int rc = 0;
    for (const auto& path : files) {
        dump::Dump d;
        std::string err;
        if (!dump::loadDump(path, d, err)) {
            rc = fail(err);  // loader errors name the file
            continue;
        }
        dump::DumpSummary s = dump::summarize(d);
        std::printf("%s\n", path.c_str());
        std::printf("  version:   %u\n", d.version);
        std::printf("  game:      %s\n", d.gameId.empty() ? "(none)" : d.gameId.c_str());
        std::printf("  records:   %zu\n", d.records.size());
        for (int t = 0; t < 32; ++t)
            if (s.recordsByType[t]) std::printf("    %-12s %llu\n", dump::recordTypeName(u8(t)), (unsigned long long)s.recordsByType[t]);
        if (s.unknownRecords) std::printf("    unknown      %llu\n", (unsigned long long)s.unknownRecords);
        std::printf("  pushbuf:   %zu bytes\n", d.pushbuf.size());
        std::printf("  commands:  %llu\n", (unsigned long long)s.commands);
        std::printf("  draws:     %llu (prim %llu, patch %llu)\n", (unsigned long long)s.draws,
                    (unsigned long long)s.prims, (unsigned long long)s.patches);
        std::printf("  transfers: %llu\n  clut loads: %llu\n", (unsigned long long)s.transfers,
                    (unsigned long long)s.clutLoads);
        if (timing) printTiming(d);
    }
    return rc;
}

int cmdDisasm(const std::string& path) {
    dump::Dump d;
    std::string err;
    if (!dump::loadDump(path, d, err)) return fail(err);
    // A block shared by several records is printed once (output bounded by the push buffer).
    std::map<std::pair<u32, u32>, size_t> printed;
    for (size_t i = 0; i < d.records.size(); ++i) {
        const dump::Record& r = d.records[i];
        if (r.type != dump::REGISTERS) {
            std::printf("; record %zu %s size=%u\n", i, dump::recordTypeName(r.type), r.size);
            continue;
        }
        const u8* p = d.payload(r);
        if (!p) {
            std::printf("; record %zu REGISTERS outside the push buffer\n", i);
            continue;
        }
        auto [it, fresh] = printed.try_emplace({r.ptr, r.size}, i);
        if (!fresh && r.size >= 64) {
            std::printf("; record %zu REGISTERS: the %u words of record %zu again\n", i, r.size / 4, it->second);
            continue;
        }
        for (u32 k = 0; k < r.size / 4; ++k) {
            u32 w = readLE32(p + 4 * k);
            std::printf("%08x  %s\n", w, disassemble(w).c_str());
        }
    }
    return 0;
}

// Errors name the file once and say why (errno text): a full disk shows at the flush or close.
bool writeFile(const std::string& path, const void* data, size_t size, std::string& err) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        err = "cannot write " + path + ": " + std::strerror(errno);
        return false;
    }
    const bool ok = std::fwrite(data, 1, size, f) == size && std::fflush(f) == 0;
    const int e = errno;
    if (std::fclose(f) != 0 || !ok) {
        err = "cannot write " + path + ": " + std::strerror(ok ? errno : e);
        return false;
    }
    return true;
}

int cmdRender(const std::string& path, const tools::RenderOptions& opt, const std::string& outPng,
              const std::string& depthOut, const std::string& vramOut, bool stats) {
    tools::RenderOutput out;
    std::string err;
    std::vector<u8> vram;
    std::vector<u16> depth;
    if (!tools::renderDumpFile(path, opt, out, err, vramOut.empty() ? nullptr : &vram, depthOut.empty() ? nullptr : &depth))
        return fail(err);
    if (!out.replay.warning.empty()) std::fprintf(stderr, "ge2gl: warning: %s\n", out.replay.warning.c_str());
    if (!tools::writePng(outPng, out.frameScaled.rgba.empty() ? out.frame : out.frameScaled, err)) return fail(err);
    if (!depthOut.empty()) {
        std::vector<u8> buf(8 + depth.size() * 2);
        writeLE32(buf.data(), 480);
        writeLE32(buf.data() + 4, 272);
        for (size_t i = 0; i < depth.size(); ++i) writeLE16(buf.data() + 8 + 2 * i, depth[i]);
        if (!writeFile(depthOut, buf.data(), buf.size(), err)) return fail(err);
    }
    if (!vramOut.empty() && !writeFile(vramOut, vram.data(), vram.size(), err)) return fail(err);
    if (stats) {
        const GeStats& s = out.engineStats;
        std::printf("draws: %llu\ncommands: %llu\nprims: %llu\npatches: %llu\nvertices: %llu\ntransfers: %llu\n"
                    "clut loads: %llu\nstate changes: %llu\ntime: %.3f s\n",
                    (unsigned long long)out.replay.draws, (unsigned long long)s.commands, (unsigned long long)s.prims,
                    (unsigned long long)s.patches, (unsigned long long)s.vertices, (unsigned long long)s.transfers,
                    (unsigned long long)s.clutLoads, (unsigned long long)s.stateChanges, out.seconds);
        const dump::ReplayResult& r = out.replay;
        std::printf("GE time: %.3f ms\n", getime::msFromCycles(r.geCycles));
        std::printf("replay timing: %s\nreplay syncs: %llu\nslab maps: %llu\nextra maps: %llu\nlist wraps: %llu\n",
                    dump::replayTimingName(opt.replayTiming), (unsigned long long)r.syncs,
                    (unsigned long long)r.slabMaps, (unsigned long long)r.extraMaps, (unsigned long long)r.listWraps);
        std::printf("register blocks scanned: %llu (%llu bytes)\nlist bytes written: %llu\n",
                    (unsigned long long)r.blockScans, (unsigned long long)r.scannedBytes,
                    (unsigned long long)r.listBytes);
        if (!out.backendStats.empty()) std::printf("%s", out.backendStats.c_str());
    }
    return 0;
}

// compare and merge: tools/lib/batch.cpp (runCompare, runMerge; JSON through tools/lib/json_io.h).

int cmdBench(const std::vector<std::string>& files, const tools::RenderOptions& opt, int repeat, bool warm) {
    // Per draw: the median replay time over the dump's draws. With the null GL, also the same
    // replay on the null backend (engine and replay alone, alternated run by run) and the
    // difference per draw: the translator's own CPU cost, GL driver excluded.
    const bool nullGl = opt.backend == "gl" && opt.glContext == "null";
    std::printf("%-60s %10s %10s %8s %10s", "dump", "median s", "min s", "draws", "us/draw");
    if (nullGl) std::printf(" %12s %14s", "engine s", "transl us/draw");
    std::printf("\n");
    std::vector<double> medians, perDraw;
    Memory mem;  // one emulated memory for every run, cleared before each (Memory::clear)
    // --warm measures an emulator's next frame: its memory stays resident between frames.
    mem.keepPagesOnClear(warm);
    tools::RenderOptions engineOnly = opt;
    engineOnly.backend = "null";
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    for (const auto& path : files) {
        dump::Dump d;
        std::string err;
        if (!dump::loadDump(path, d, err)) return fail(err);
        std::vector<double> t, e;
        u64 draws = 0;
        // --warm: one backend per dump for all runs, after an untimed first run (the steady state
        // of an emulator's next frame: textures decoded, programs compiled, targets allocated).
        backend::Backend be, engineBe;
        backend::Backend* keep = warm ? &be : nullptr;
        backend::Backend* keepEngine = warm ? &engineBe : nullptr;
        for (int i = warm ? -1 : 0; i < repeat; ++i) {
            tools::RenderOutput out;
            if (!tools::renderDump(d, opt, out, err, nullptr, nullptr, &mem, keep)) return fail(path + ": " + err);
            if (nullGl) {
                tools::RenderOutput eo;
                if (!tools::renderDump(d, engineOnly, eo, err, nullptr, nullptr, &mem, keepEngine))
                    return fail(path + ": " + err);
                if (i >= 0) e.push_back(eo.seconds);
            }
            if (i < 0) continue;
            t.push_back(out.seconds);
            draws = out.replay.draws;
        }
        const double m = median(t);
        medians.push_back(m);
        std::printf("%-60s %10.4f %10.4f %8llu %10.2f", tools::dumpName(path).c_str(), m,
                    *std::min_element(t.begin(), t.end()), (unsigned long long)draws, draws ? m * 1e6 / double(draws) : 0.0);
        if (nullGl) {
            const double me = median(e), pd = draws ? (m - me) * 1e6 / double(draws) : 0.0;
            perDraw.push_back(pd);
            std::printf(" %12.4f %14.2f", me, pd);
        }
        std::printf("\n");
    }
    if (!medians.empty()) std::printf("median over dumps: %.4f s (replay only, dump already loaded)\n", median(medians));
    if (!perDraw.empty()) std::printf("translator CPU per draw, median over dumps: %.2f us\n", median(perDraw));
    return 0;
}

// Every option's storage and the subcommands, declared in the order --help lists them.
struct Cli {
    CLI::App app{"ge2gl — PSP GE frame-dump replay, rendering and comparison"};
    tools::RenderOptions ropt;
    std::string replayTiming = "ppsspp";
    std::optional<std::string> skipDraws, onlyDraws;  // --skip / --only (tools/lib/draw_select.h)
    std::vector<std::string> infoFiles;
    bool infoTiming = false;
    std::string disasmFile;
    std::string renderFile, outPng, depthOut, vramOut;
    bool stats = false;
    std::vector<std::string> cmpFiles;
    std::string refDir, refBackend, jsonPath, diffDir;
    double maxMse = -1;
    std::string shardText;
    bool jsonNoTimes = false;
    std::vector<std::string> benchFiles;
    int repeat = 3;
    tools::StepOptions stepOpt;
    std::string stepFile;
    bool nullGl = false, warm = false, noProgramCache = false;
    std::string blameFile;
    tools::BlameOptions blameOpt;
    std::string bisectFile;
    tools::BisectOptions bisectOpt;
    std::vector<std::string> mergeFiles;
    std::string mergeOut;
    tools::FuzzOptions fuzzOpt;
    tools::ReportArgs reportArgs;
    CLI::App *info = nullptr, *disasm = nullptr, *render = nullptr, *compare = nullptr, *step = nullptr,
             *bench = nullptr, *blame = nullptr, *bisect = nullptr, *fuzz = nullptr, *merge = nullptr,
             *report = nullptr;
    CLI::Option* shardOpt = nullptr;
    tools::Shard shard;  // --shard i/n, parsed

    Cli() {
        app.require_subcommand(1);
        app.set_version_flag("--version", versionText());
        declareInspect();
        declareCompare();
        declareStepBench();
        declareBlameBisect();
        declareFuzzMergeReport();
    }

    // geometry/accuracy_profile.h; docs/accuracy.md "Accuracy profiles".
    void addAccuracyOpt(CLI::App* sc) {
        sc->add_option("--accuracy", ropt.accuracy,
                       "psp (what the GE does: every hardware-measured rule; default) | ppsspp (PPSSPP's software "
                       "renderer's pixels, its optimisation artefacts included: compare against PPSSPP references); "
                       "either may be followed by +SWITCH or -SWITCH to turn one rule on or off, e.g. "
                       "ppsspp+pspColourGradients (switches: docs/accuracy.md)")
            ->check(accuracyValidator());
    }
    static CLI::Validator accuracyValidator() {
        return CLI::Validator(
            [](std::string& v) {
                geo::AccuracyProfile a;
                if (geo::AccuracyProfile::fromName(v.c_str(), a)) return std::string();
                std::string names;
                for (const geo::AccuracySwitch& sw : geo::kAccuracySwitches) names += std::string(" ") + sw.name;
                return "unknown accuracy profile '" + v + "': psp or ppsspp, then +SWITCH/-SWITCH of" + names;
            },
            "PROFILE[+SWITCH|-SWITCH...]");
    }
    void addBackendOpts(CLI::App* sc) {
        sc->add_option("--replay-timing", replayTiming,
                       "when the GE runs during replay: ppsspp (as PPSSPP's player: at its sync points; "
                       "dumps PPSSPP recorded) | eager (after every REGISTERS block; dumps from other tools)")
            ->check(CLI::IsMember({"ppsspp", "eager"}));
        sc->add_option("--max-ge-ms", ropt.maxGeMs,
                       "budget of emulated GE time for the replay in ms (0 = none); the rest of the frame is cut "
                       "with a warning (default 166.7: 10 frames)")
            ->check(CLI::Range(0.0, 1e7));
        sc->add_option("--backend", ropt.backend, "soft | gl | null")->check(CLI::IsMember({"soft", "gl", "null"}));
        addAccuracyOpt(sc);
        sc->add_option("--threads", ropt.threads, "software model threads (0 = all cores)")->check(wholeNumber(256));
        sc->add_option("--context", ropt.glContext,
                       "GL context: osmesa | egl | null (GL calls do nothing: the translator's CPU cost alone)")
            ->check(CLI::IsMember({"osmesa", "egl", "null"}));
        sc->add_flag("--gl-baseline", ropt.glBaseline, "GL: force the GL 3.3 baseline paths");
        sc->add_option("--gl-mode", ropt.glMode,
                       "GL: exact (the software model's rasteriser arithmetic per pixel, 1x; default) | hw "
                       "(native GL rasterisation, render scale)")
            ->check(CLI::IsMember({"exact", "hw"}));
        sc->add_option("--scale", ropt.scale,
                       "GL hw: render scale 1-8 (render writes 480N x 272N; compare box-downsamples to 480x272)")
            ->check(CLI::Range(1, 8));
        sc->add_option("--gl-vertices", ropt.glVertices,
                       "GL hw: where vertices are transformed and lit: gpu (generated vertex shaders) | cpu | auto "
                       "(default: cpu on a software rasteriser such as llvmpipe, else gpu)")
            ->check(CLI::IsMember({"auto", "gpu", "cpu"}));
        sc->add_option("--dump-shaders", ropt.shaderDumpDir, "GL: write generated shaders to DIR");
        CLI::Option* cacheDir = sc->add_option(
            "--program-cache", ropt.programCacheDir,
            "GL: on-disk program binary cache DIR (render, compare, step, report, blame, bisect default to "
            "$XDG_CACHE_HOME/ge2gl/programs, else ~/.cache/ge2gl/programs; bench and fuzz to none)");
        sc->add_flag("--no-program-cache", noProgramCache, "GL: compile every program, keep no binaries on disk")
            ->excludes(cacheDir);
    }
    // --skip / --only (render, compare, bench): tools/lib/draw_select.h.
    void addDrawSelectOpts(CLI::App* sc) {
        sc->add_option_function<std::string>("--skip", [&](const std::string& v) { skipDraws = v; },
                                              "leave these draws out: comma-separated numbers and ranges such as "
                                              "3,10-12, draws numbered from 1 as --replay-end counts them");
        sc->add_option_function<std::string>("--only", [&](const std::string& v) { onlyDraws = v; },
                                              "draw only these draws (same syntax; with --skip, these less the skipped)");
    }

    // info, disasm, render
    void declareInspect() {
        info = app.add_subcommand("info", "version, game ID, record counts, draws and commands");
        info->add_option("DUMP", infoFiles)->required();
        info->add_flag("--timing", infoTiming,
                       "replay on the software model and print the GE-time estimate of the frame, in parts (docs/timing.md)");

        disasm = app.add_subcommand("disasm", "one line per command");
        disasm->add_option("DUMP", disasmFile)->required();

        render = app.add_subcommand("render", "replay a dump and write the displayed frame as an image");
        render->add_option("DUMP", renderFile)->required();
        render->add_option("-o,--output", outPng,
                           "output image, 480x272 (480N x 272N with --scale N; .png, other extensions through OpenImageIO)")
            ->required();
        render->add_option("--depth-out", depthOut, "write u32 width, u32 height, u16 depth per pixel");
        render->add_option("--vram-out", vramOut, "write the 2 MiB of VRAM after the frame");
        render->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
        render->add_flag("--stats", stats, "print counters");
        addBackendOpts(render);
        addDrawSelectOpts(render);
    }

    // compare
    void declareCompare() {
        compare = app.add_subcommand("compare", "render dumps and compare with reference images (PPSSPP's MSE)");
        compare->add_option("DUMP", cmpFiles)->required();
        compare->add_option("--ref-dir", refDir, "folder with NAME-soft.png references");
        compare->add_option("--ref-backend", refBackend, "compare against another backend's render instead");
        compare->add_option("--max-mse", maxMse, "non-zero exit when any dump exceeds this MSE")->check(CLI::Range(0.0, 65025.0));
        compare->add_option("--json", jsonPath, "write results as JSON (schema: tools/lib/batch.h)");
        shardOpt = compare->add_option("--shard", shardText,
                            "i/n: run only shard i of n (dumps in name order, every n-th from the i-th); join the "
                            "shards' --json files with ge2gl merge");
        compare->add_flag("--json-no-times", jsonNoTimes, "leave the run times out of the JSON (same file every run)");
        compare->add_option("--diff-dir", diffDir, "write difference pictures here");
        compare->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
        addBackendOpts(compare);
        addDrawSelectOpts(compare);
    }

    // step, bench
    void declareStepBench() {
        step = app.add_subcommand("step", "replay a dump to one command with the GE debugger and print the state there");
        step->add_option("DUMP", stepFile)->required();
        step->add_option("--break", stepOpt.breakAt,
                         "where: draw:N (Nth PRIM/BEZIER/SPLINE), prim:N, command:N, op:NAME[:N], addr:ADDR[:N]; "
                         "N counts from 1")
            ->required();
        step->add_option("--out-dir", stepOpt.outDir,
                         "write color.png, depth.png, stencil.png (after the command), texture-L*.png and clut.png "
                         "(before it)");
        addBackendOpts(step);

        bench = app.add_subcommand("bench", "time the replay of dumps (median of --repeat runs)");
        bench->add_option("DUMP", benchFiles)->required();
        bench->add_option("--repeat", repeat, "runs per dump")->check(CLI::Range(1, 1000));
        bench->add_flag("--null-gl", nullGl, "GL: replay with a GL whose calls do nothing (same as --context null)");
        bench->add_flag("--warm", warm,
                        "one backend per dump for every run, after an untimed first run: the steady-state cost of a "
                        "frame (textures decoded, programs compiled, guest memory pages kept resident), as in an emulator");
        addBackendOpts(bench);
        addDrawSelectOpts(bench);
    }

    // blame, bisect
    void declareBlameBisect() {
        // blame and bisect: tools/lib/blame.h, tools/lib/bisect.h.
        blame = app.add_subcommand("blame", "which draws own the pixels that differ from a reference, ranked by "
                                                  "their share of the squared error");
        blame->add_option("DUMP", blameFile)->required();
        blame->add_option("--ref", blameOpt.refPng, "reference picture (480x272 PNG, e.g. a frametest's NAME-soft.png)");
        blame->add_option("--ref-backend", blameOpt.refBackend, "reference: the same dump rendered by this backend")
            ->check(CLI::IsMember({"soft", "gl", "null"}));
        blame->add_option("--top", blameOpt.top, "draws to list (default 10)")->check(CLI::Range(0, 100000));
        blame->add_option("-o,--output", blameOpt.picturePath,
                          "picture: the render dimmed, the top draws' differing pixels tinted and outlined, one colour "
                          "each (others white)");
        blame->add_option("--json", blameOpt.jsonPath, "write the ranking as JSON");
        blame->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
        addBackendOpts(blame);

        bisect = app.add_subcommand("bisect", "the first draw after which two replays differ (one lockstep replay: "
                                                    "DUMP on --backend vs --ref-backend, or vs --ref-dump on --backend)");
        bisect->add_option("DUMP", bisectFile)->required();
        bisect->add_option("--ref-backend", bisectOpt.refBackend, "other side: the same dump on this backend")
            ->check(CLI::IsMember({"soft", "gl", "null"}));
        bisect->add_option("--ref-dump", bisectOpt.refDumpPath, "other side: this dump on --backend");
        bisect->add_flag("--ignore-depth", bisectOpt.ignoreDepth, "compare colour only (default: colour and depth)");
        bisect->add_flag("--all-vram", bisectOpt.allVram,
                         "compare all 2 MiB of VRAM byte for byte after each draw (default: the draw's target colour and "
                         "depth inside its scissor)");
        bisect->add_option("--tolerance", bisectOpt.tolerance, "per-channel colour difference allowed (0-255, default 0)")
            ->check(CLI::Range(0, 255));
        bisect->add_option("--json", bisectOpt.jsonPath, "write the result as JSON");
        bisect->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
        addBackendOpts(bisect);
    }

    // fuzz, merge, report
    void declareFuzzMergeReport() {
        fuzz = app.add_subcommand("fuzz", "differential fuzzer: random valid GE scenes rendered by --backend (default "
                                                "gl) and --ref-backend, compared exactly; failing cases minimised");
        fuzz->add_option("--ref-backend", fuzzOpt.refBackend, "reference backend (default soft)")
            ->check(CLI::IsMember({"soft", "gl", "null"}));
        fuzz->add_option("--ref-accuracy", fuzzOpt.refAccuracy,
                         "accuracy profile of the reference side (default: --accuracy's); with --accuracy psp "
                         "--ref-accuracy ppsspp the divergences are those of the profiles' switches")
            ->check(accuracyValidator());
        fuzz->add_option("--seed", fuzzOpt.seed, "first seed (case i uses seed + i; default 1)");
        fuzz->add_option("--count", fuzzOpt.count, "cases (default 100)")->check(wholeNumber(u64(1) << 40));
        fuzz->add_option("--out", fuzzOpt.outDir, "write minimised failing cases as DIR/case-SEED.ppdmp");
        fuzz->add_option("--json", fuzzOpt.jsonPath, "write the summary and the failing seeds as JSON");
        fuzz->add_option("--minimise-tries", fuzzOpt.minimiseTries, "renders spent minimising one failing case (default 300)")
            ->check(CLI::Range(0, 1000000));
        fuzz->add_flag("--rgb-only", fuzzOpt.rgbOnly, "ignore the alpha/stencil bits of the colour buffer");
        fuzz->add_flag("--depth", fuzzOpt.compareDepth, "also compare the depth buffer");
        fuzz->add_option("--max-mse", fuzzOpt.maxMse,
                         "diverge only when the frames' RGB MSE exceeds this (a pair that is not bit-exact: "
                         "--gl-mode hw against soft, docs/accuracy.md; default: exact)")
            ->check(CLI::Range(0.0, 65025.0));
        fuzz->add_flag("--quiet", fuzzOpt.quiet, "summary only");
        addBackendOpts(fuzz);
        addDrawSelectOpts(fuzz);  // fuzz: --skip/--only act on the --ref-backend side only (forces divergences)

        merge = app.add_subcommand("merge", "join the --json files of compare --shard i/n runs into the JSON one "
                                                  "unsharded run writes; missing or duplicate shards are errors");
        merge->add_option("JSON", mergeFiles)->required();
        merge->add_option("-o,--output", mergeOut, "merged JSON file")->required();

        report = app.add_subcommand("report", "a static HTML page (no server, no network) of compare --json results: "
                                                    "per dump the reference, render, heat map and blame table; sortable "
                                                    "summary; before/after with --before");
        report->add_option("JSON", reportArgs.runFiles, "compare --json file of the run, or the files of all its shards")
            ->required();
        report->add_option("-o,--output", reportArgs.outDir, "folder to write index.html and img/ into")->required();
        report->add_option("--before", reportArgs.beforeFiles,
                           "compare --json file of an earlier run (repeat for its shards): which dumps got better or worse")
            ->expected(1)
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        report->add_option("--title", reportArgs.title, "page title");
        report->add_option("--top", reportArgs.top, "blame rows per dump (default 10)")->check(CLI::Range(1, 1000));
        report->add_option("--threads", ropt.threads, "software model threads (0 = all cores)")->check(wholeNumber(256));
        addAccuracyOpt(report);
        report->add_option("--context", ropt.glContext, "GL context for a gl run: osmesa | egl")
            ->check(CLI::IsMember({"osmesa", "egl"}));
        report->add_option("--replay-timing", replayTiming, "as given to compare (default ppsspp)")
            ->check(CLI::IsMember({"ppsspp", "eager"}));
    }

    int parse(int argc, char** argv);
    int run();
};

int Cli::parse(int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "ge2gl: %s\n", e.what());
        return 2;
    }
    dump::parseReplayTiming(replayTiming, ropt.replayTiming);
    if (nullGl) ropt.glContext = "null";
    // Program binaries on disk by default, as Mesa keeps its own shader cache: a second GL render
    // of the same kind of frame compiles nothing (docs/benchmarks.md, "Sixth round"). Not for bench,
    // which measures ge2gl's own work, nor for fuzz, whose random states would fill the directory.
    if (ropt.programCacheDir.empty() && !noProgramCache && !*bench && !*fuzz)
        ropt.programCacheDir = tools::defaultProgramCacheDir();
    if (ropt.scale > 1 && (ropt.backend != "gl" || ropt.glMode != "hw"))
        return fail("--scale above 1 needs --backend gl --gl-mode hw");
    std::string optErr;  // usage errors: exit 2, as CLI11's
    if (shardOpt->count() && !tools::parseShard(shardText, shard, optErr)) optErr = "--shard '" + shardText + "': " + optErr;
    if (!optErr.empty() || !tools::makeDrawFilter(skipDraws, onlyDraws, ropt.keepDraw, optErr)) {
        std::fprintf(stderr, "ge2gl: %s\n", optErr.c_str());
        return 2;
    }
    return -1;
}

// Runs the subcommand given.
int Cli::run() {
    if (*info) return cmdInfo(infoFiles, infoTiming);
    if (*disasm) return cmdDisasm(disasmFile);
    if (*render) return cmdRender(renderFile, ropt, outPng, depthOut, vramOut, stats);
    if (*compare)
        return tools::runCompare({cmpFiles, ropt, refDir, refBackend, jsonPath, diffDir, maxMse, shardOpt->count() > 0, shard, !jsonNoTimes});
    if (*merge) return tools::runMerge(mergeFiles, mergeOut);
    if (*report) {
        reportArgs.render = ropt;
        return tools::runReport(reportArgs);
    }
    if (*step) {
        stepOpt.render = ropt;
        tools::StepResult res;
        std::string err;
        if (!tools::stepDump(stepFile, stepOpt, res, err)) return fail(err);
        std::fputs(res.report.c_str(), stdout);
        if (!res.hit) {
            std::fprintf(stderr, "ge2gl: the frame ended before --break %s\n", stepOpt.breakAt.c_str());
            return 1;
        }
        return 0;
    }
    if (*bench) return cmdBench(benchFiles, ropt, repeat, warm);
    if (*blame) return tools::runBlameCommand(blameFile, ropt, blameOpt);
    if (*bisect) return tools::runBisectCommand(bisectFile, ropt, bisectOpt);
    if (*fuzz) {
        fuzzOpt.render = ropt;
        fuzzOpt.render.keepDraw = nullptr;
        fuzzOpt.refKeepDraw = ropt.keepDraw;
        fuzzOpt.backend = fuzz->count("--backend") ? ropt.backend : "gl";
        if (!fuzz->count("--ref-accuracy")) fuzzOpt.refAccuracy = ropt.accuracy;
        if (!fuzz->count("--threads")) fuzzOpt.render.threads = 1;  // tiny scenes: threads cost more than they give
        return tools::runFuzzCommand(fuzzOpt);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Cli cli;
    const int rc = cli.parse(argc, argv);
    return rc >= 0 ? rc : cli.run();
}
