// SPDX-License-Identifier: MIT
// Harness (c): dump replay with the GL translator ("GL exact") on an OSMesa context. Input as for
// fuzz_replay_soft (a .ppdmp, a zip, or the open form of fuzz_common.h).
//
// Creating a context and compiling the first programs costs far more than a replay, so one
// renderer serves the whole process: before each input its memory is cleared and the renderer
// forgets every render target, texture and palette (GlRenderer::forgetGuestMemory), which leaves it
// equivalent to a fresh one for that input (generated programs are a pure function of their
// keys). Re-uploading the zeros into every target instead (memoryWritten over all of VRAM) took
// 60% of the harness's time. Without a GL context every input is a no-op (said once).
//
// The renderer keeps every program it compiles (a game uses a few hundred; fuzzed state words
// ask for thousands), and llvmpipe's code for each stays resident: a long run grew by ~70 MB a
// minute towards -rss_limit_mb. So the renderer is made anew once it has compiled kMaxPrograms.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "tests/fuzz/fuzz_common.h"
#include "translator/gl_renderer.h"

using namespace ge;

namespace {

constexpr u64 kMaxPrograms = 512;

Memory* gMem = nullptr;
gl::GlRenderer* gGl = nullptr;

gl::GlRenderer* makeRenderer() {
    gl::GlOptions go;
    go.context = gl::ContextKind::OSMesa;
    std::string err;
    gl::GlRenderer* r = gl::createGlRenderer(*gMem, go, err).release();
    if (!r) std::fprintf(stderr, "fuzz_replay_gl: no GL context (%s): every input is skipped\n", err.c_str());
    return r;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // llvmpipe rasterises on the calling thread: one core per fuzzing job, reproducible timing.
    setenv("LP_NUM_THREADS", "0", 0);
    gMem = new Memory();
    gGl = makeRenderer();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    if (!gGl) return 0;
    dump::Dump d;
    std::string err;
    if (!fuzz::loadFuzzDump(data, size, d, err)) return 0;
    gMem->clear();
    if (gGl->stats().shaderCompiles >= kMaxPrograms) {
        delete gGl;
        gGl = makeRenderer();
        if (!gGl) return 0;
    }
    gGl->forgetGuestMemory();
    fuzz::BoundedRenderer r(*gGl);
    r.reset();
    GeEngine eng(*gMem, &r);
    fuzz::BoundedTarget target(eng, fuzz::Caps{}.commands);
    dump::ReplayOptions opt;
    if (!d.records.empty() && (d.records.size() & 3) == 3) opt.timing = dump::ReplayTiming::Eager;
    opt.maxGeMs = fuzz::kMaxGeMs;
    dump::ReplayResult res;
    dump::replayDump(d, target, opt, res, err);
    gGl->flushToMemory();
    return 0;
}
