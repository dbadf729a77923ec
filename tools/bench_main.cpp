// SPDX-License-Identifier: MIT
// Google Benchmark suite: replay time per dump and backend. Speed targets live here, not in tests.
//   ./build/ge2gl_bench [--benchmark_filter=soft] — dumps from ../shared/frametests and dumps/.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

void replayBench(benchmark::State& state, dump::Dump d, std::string backend) {
    tools::RenderOptions opt;
    opt.backend = backend;
    Memory mem;  // reused by every iteration, as `ge2gl bench` does
    for (auto _ : state) {
        tools::RenderOutput out;
        std::string err;
        if (!tools::renderDump(d, opt, out, err, nullptr, nullptr, &mem)) {
            state.SkipWithError(err.c_str());
            break;
        }
        benchmark::DoNotOptimize(out.frame.rgba.data());
    }
}

void registerDir(const fs::path& dir, const char* ext) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return;
    std::vector<fs::path> files;
    for (auto& e : fs::directory_iterator(dir)) {
        std::string n = e.path().filename().string();
        if (n.size() >= std::strlen(ext) && n.compare(n.size() - std::strlen(ext), std::strlen(ext), ext) == 0) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
        dump::Dump d;
        std::string err;
        if (!dump::loadDump(f.string(), d, err)) continue;
        for (const char* backend : {"null", "soft", "gl"}) {
            Memory probe(1u << 20);
            tools::RenderOptions o;
            o.backend = backend;
            if (!tools::createBackend(o, probe, err)) continue;
            std::string name = std::string(backend) + "/" + tools::dumpName(f.string());
            benchmark::RegisterBenchmark(name.c_str(), replayBench, d, std::string(backend))->Unit(benchmark::kMillisecond)->UseRealTime();
        }
    }
}

#ifdef GE2GL_LOAD_PROBE
// A host loading libge2gl without asking for a headless GL context (the target: at most 20 ms, and no
// OSMesa/EGL/LLVM mapped): ge2gl_load_probe in a fresh process per iteration; the counter
// load_ms is the probe's own dlopen + create + destroy time, real time includes the spawn.
void libraryLoadBench(benchmark::State& state) {
    double sum = 0;
    int n = 0, glMapped = 0;
    for (auto _ : state) {
        const std::string cmd = std::string("'") + GE2GL_LOAD_PROBE + "' '" + GE2GL_LIBRARY + "'";
        FILE* p = popen(cmd.c_str(), "r");
        char line[256] = {};
        const bool got = p && std::fgets(line, sizeof line, p);
        if (p) pclose(p);
        double ms = 0;
        int os = 0, egl = 0, llvm = 0;
        if (!got || std::sscanf(line, "load_probe: load_ms=%lf osmesa=%d egl=%d llvm=%d", &ms, &os, &egl, &llvm) != 4) {
            state.SkipWithError("ge2gl_load_probe failed");
            break;
        }
        sum += ms;
        ++n;
        glMapped += os + egl + llvm;
    }
    if (n) state.counters["load_ms"] = sum / n;
    state.counters["gl_libs_mapped"] = glMapped;
}
#endif

}  // namespace

int main(int argc, char** argv) {
#ifdef GE2GL_LOAD_PROBE
    benchmark::RegisterBenchmark("LibraryLoad", libraryLoadBench)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
    registerDir(fs::path(GE2GL_SOURCE_DIR) / "dumps", ".ppdmp");
    registerDir(fs::path(GE2GL_FRAMETESTS_DIR) / "dumps", ".zip");
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
