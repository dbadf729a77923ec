// SPDX-License-Identifier: MIT
// Harness (b): dump replay with the software model. The bytes are loaded as a dump (a .ppdmp, a
// zip holding one, or the uncompressed "open" form of fuzz_common.h) and replayed with replayDump on a GeEngine over soft::createSoftRenderer with one
// thread (no worker threads: deterministic, and the sanitizers see every access on one stack).
//
// One Memory serves every input (Memory::clear() returns its pages); the renderer is created per
// input, so no cache outlives the memory it describes.
#include <cstdint>
#include <string>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "softmodel/soft_renderer.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    dump::Dump d;
    std::string err;
    if (!fuzz::loadFuzzDump(data, size, d, err)) return 0;
    static Memory mem;
    mem.clear();
    soft::SoftOptions so;
    so.threads = 1;
    auto soft = soft::createSoftRenderer(mem, so);
    fuzz::BoundedRenderer r(*soft);
    r.reset();
    GeEngine eng(mem, &r);
    fuzz::BoundedTarget target(eng, fuzz::Caps{}.commands);
    dump::ReplayOptions opt;
    // Both timings: PPSSPP's (the default) for most inputs, eager for a quarter of them.
    if (!d.records.empty() && (d.records.size() & 3) == 3) opt.timing = dump::ReplayTiming::Eager;
    opt.maxGeMs = fuzz::kMaxGeMs;
    dump::ReplayResult res;
    if (dump::replayDump(d, target, opt, res, err)) {
        u32 addr = 0, stride = 0, fmt = 0;
        dump::displayedFramebuffer(res, eng.state(), addr, stride, fmt);
    }
    return 0;
}
