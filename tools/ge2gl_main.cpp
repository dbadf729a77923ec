// The ge2gl command-line tool: info, disasm, render, compare, bench.
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

#include "hle/disasm.h"
#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/ge_time.h"
#include "tools/lib/image.h"
#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

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

int cmdInfo(const std::vector<std::string>& files) {
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
    if (!tools::writePng(outPng, out.frame, err)) return fail(err);
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
        if (!out.backendStats.empty()) std::printf("%s", out.backendStats.c_str());
    }
    return 0;
}

std::string jsonEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        o += c;
    }
    return o;
}

int cmdCompare(const std::vector<std::string>& files, const tools::RenderOptions& opt, const std::string& refDir,
               const std::string& refBackend, double maxMse, const std::string& jsonPath, const std::string& diffDir) {
    if (refDir.empty() == refBackend.empty()) return fail("compare needs exactly one of --ref-dir or --ref-backend");
    if (!diffDir.empty()) {
        std::error_code ec;
        fs::create_directories(diffDir, ec);
    }
    struct Row {
        std::string name, error;
        double mse = -1, psnr = 0, seconds = 0;
    };
    std::vector<Row> rows;
    int failures = 0;
    std::printf("%-60s %12s %9s %8s\n", "dump", "MSE", "PSNR", "time s");
    for (const auto& path : files) {
        Row row;
        row.name = tools::dumpName(path);
        tools::RenderOutput out;
        std::string err;
        tools::Image ref;
        if (!tools::renderDumpFile(path, opt, out, err)) {
            row.error = err;
        } else if (!refDir.empty()) {
            if (!tools::readImage((fs::path(refDir) / (row.name + "-soft.png")).string(), ref, err)) row.error = err;
        } else {
            tools::RenderOptions ro = opt;
            ro.backend = refBackend;
            tools::RenderOutput refOut;
            if (!tools::renderDumpFile(path, ro, refOut, err)) row.error = "reference: " + err;
            else ref = refOut.frame;
        }
        if (row.error.empty()) {
            row.mse = tools::mseRGB(out.frame, ref);
            if (row.mse < 0) row.error = "reference image smaller than 480x272";
            row.psnr = tools::psnrFromMse(row.mse);
            row.seconds = out.seconds;
            if (!diffDir.empty() && row.mse > 0) {
                std::string e2;
                tools::writePng((fs::path(diffDir) / (row.name + "-diff.png")).string(), tools::diffImage(out.frame, ref), e2);
                tools::writePng((fs::path(diffDir) / (row.name + "-" + opt.backend + ".png")).string(), out.frame, e2);
            }
        }
        if (!row.error.empty()) {
            ++failures;
            std::printf("%-60s %12s  %s\n", row.name.c_str(), "ERROR", row.error.c_str());
        } else {
            if (maxMse >= 0 && row.mse > maxMse) ++failures;
            std::printf("%-60s %12.4f %9.2f %8.3f\n", row.name.c_str(), row.mse, row.psnr, row.seconds);
        }
        std::fflush(stdout);
        rows.push_back(row);
    }
    std::vector<double> mses, times;
    int within01 = 0, within10 = 0;
    for (const Row& r : rows)
        if (r.error.empty()) {
            mses.push_back(r.mse);
            times.push_back(r.seconds);
            within01 += r.mse <= 0.1;
            within10 += r.mse <= 10;
        }
    auto median = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::sort(v.begin(), v.end());
        size_t n = v.size();
        return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
    };
    std::printf("summary: %zu dumps, %zu rendered, %d within MSE 0.1, %d within MSE 10, median MSE %.4f, median time %.3f s\n",
                rows.size(), mses.size(), within01, within10, median(mses), median(times));
    if (!jsonPath.empty()) {
        std::ofstream j(jsonPath);
        j << "{\n  \"backend\": \"" << opt.backend << "\",\n  \"results\": [\n";
        for (size_t i = 0; i < rows.size(); ++i) {
            const Row& r = rows[i];
            j << "    {\"name\": \"" << jsonEscape(r.name) << "\"";
            if (r.error.empty()) j << ", \"mse\": " << r.mse << ", \"psnr\": " << (std::isinf(r.psnr) ? 999.0 : r.psnr) << ", \"seconds\": " << r.seconds;
            else j << ", \"error\": \"" << jsonEscape(r.error) << "\"";
            j << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
        }
        j << "  ],\n  \"median_mse\": " << median(mses) << ",\n  \"median_seconds\": " << median(times)
          << ",\n  \"within_0_1\": " << within01 << ",\n  \"within_10\": " << within10 << "\n}\n";
    }
    return failures ? 1 : 0;
}

int cmdBench(const std::vector<std::string>& files, const tools::RenderOptions& opt, int repeat) {
    std::printf("%-60s %10s %10s\n", "dump", "median s", "min s");
    std::vector<double> medians;
    Memory mem;  // one emulated memory for every run, cleared before each (Memory::clear)
    for (const auto& path : files) {
        dump::Dump d;
        std::string err;
        if (!dump::loadDump(path, d, err)) return fail(err);
        std::vector<double> t;
        for (int i = 0; i < repeat; ++i) {
            tools::RenderOutput out;
            if (!tools::renderDump(d, opt, out, err, nullptr, nullptr, &mem)) return fail(path + ": " + err);
            t.push_back(out.seconds);
        }
        std::sort(t.begin(), t.end());
        medians.push_back(t[t.size() / 2]);
        std::printf("%-60s %10.4f %10.4f\n", tools::dumpName(path).c_str(), t[t.size() / 2], t[0]);
    }
    std::sort(medians.begin(), medians.end());
    if (!medians.empty()) std::printf("median over dumps: %.4f s (replay only, dump already loaded)\n", medians[medians.size() / 2]);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ge2gl — PSP GE frame-dump replay, rendering and comparison"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "ge2gl 0.1.0");

    tools::RenderOptions ropt;
    std::string replayTiming = "ppsspp";
    auto addBackendOpts = [&](CLI::App* sc) {
        sc->add_option("--replay-timing", replayTiming,
                       "when the GE runs during replay: ppsspp (as PPSSPP's player: at its sync points; "
                       "dumps PPSSPP recorded) | eager (after every REGISTERS block; dumps from other tools)")
            ->check(CLI::IsMember({"ppsspp", "eager"}));
        sc->add_option("--max-ge-ms", ropt.maxGeMs,
                       "budget of emulated GE time for the replay in ms (0 = none); the rest of the frame is cut "
                       "with a warning (default 166.7: 10 frames)")
            ->check(CLI::Range(0.0, 1e7));
        sc->add_option("--backend", ropt.backend, "soft | gl | null")->check(CLI::IsMember({"soft", "gl", "null"}));
        sc->add_option("--threads", ropt.threads, "software model threads (0 = all cores)")->check(wholeNumber(256));
        sc->add_option("--context", ropt.glContext, "GL context: osmesa | egl");
        sc->add_flag("--gl-baseline", ropt.glBaseline, "GL: force the GL 3.3 baseline paths");
        sc->add_option("--dump-shaders", ropt.shaderDumpDir, "GL: write generated shaders to DIR");
        sc->add_option("--program-cache", ropt.programCacheDir, "GL: on-disk program binary cache DIR");
    };

    std::vector<std::string> infoFiles;
    auto* info = app.add_subcommand("info", "version, game ID, record counts, draws and commands");
    info->add_option("DUMP", infoFiles)->required();

    std::string disasmFile;
    auto* disasm = app.add_subcommand("disasm", "one line per command");
    disasm->add_option("DUMP", disasmFile)->required();

    std::string renderFile, outPng, depthOut, vramOut;
    bool stats = false;
    auto* render = app.add_subcommand("render", "replay a dump and write the displayed frame as an image");
    render->add_option("DUMP", renderFile)->required();
    render->add_option("-o,--output", outPng, "output image, 480x272 (.png; other extensions through OpenImageIO)")->required();
    render->add_option("--depth-out", depthOut, "write u32 width, u32 height, u16 depth per pixel");
    render->add_option("--vram-out", vramOut, "write the 2 MiB of VRAM after the frame");
    render->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
    render->add_flag("--stats", stats, "print counters");
    addBackendOpts(render);

    std::vector<std::string> cmpFiles;
    std::string refDir, refBackend, jsonPath, diffDir;
    double maxMse = -1;
    auto* compare = app.add_subcommand("compare", "render dumps and compare with reference images (PPSSPP's MSE)");
    compare->add_option("DUMP", cmpFiles)->required();
    compare->add_option("--ref-dir", refDir, "folder with NAME-soft.png references");
    compare->add_option("--ref-backend", refBackend, "compare against another backend's render instead");
    compare->add_option("--max-mse", maxMse, "non-zero exit when any dump exceeds this MSE")->check(CLI::Range(0.0, 65025.0));
    compare->add_option("--json", jsonPath, "write results as JSON");
    compare->add_option("--diff-dir", diffDir, "write difference pictures here");
    compare->add_option("--replay-end", ropt.replayEnd, "stop after the Nth draw")->check(wholeNumber(u64(1) << 40));
    addBackendOpts(compare);

    std::vector<std::string> benchFiles;
    int repeat = 3;
    auto* bench = app.add_subcommand("bench", "time the replay of dumps (median of --repeat runs)");
    bench->add_option("DUMP", benchFiles)->required();
    bench->add_option("--repeat", repeat, "runs per dump")->check(CLI::Range(1, 1000));
    addBackendOpts(bench);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "ge2gl: %s\n", e.what());
        return 2;
    }
    dump::parseReplayTiming(replayTiming, ropt.replayTiming);
    if (*info) return cmdInfo(infoFiles);
    if (*disasm) return cmdDisasm(disasmFile);
    if (*render) return cmdRender(renderFile, ropt, outPng, depthOut, vramOut, stats);
    if (*compare) return cmdCompare(cmpFiles, ropt, refDir, refBackend, maxMse, jsonPath, diffDir);
    if (*bench) return cmdBench(benchFiles, ropt, repeat);
    return 0;
}
