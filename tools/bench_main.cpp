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

}  // namespace

int main(int argc, char** argv) {
    registerDir(fs::path(GE2GL_SOURCE_DIR) / "dumps", ".ppdmp");
    registerDir(fs::path(GE2GL_FRAMETESTS_DIR) / "dumps", ".zip");
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
