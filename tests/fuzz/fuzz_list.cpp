// SPDX-License-Identifier: MIT
// Harness (d): raw display lists executed from guest memory by a GeEngine drawing with the
// software model (one thread): every command, flow control (JUMP/BJUMP/CALL/RET, SIGNAL with all
// behaviours, END/FINISH), stall addresses moving in steps, pauses, draws, patches, immediate
// vertices, transfers and CLUT loads, with whatever data the list points at.
//
// Input: u8 flags (bits 0-1 where the bytes go: RAM start, flush against the end of RAM, VRAM,
// the scratchpad; bit 2 run against a stall address that moves in steps; bit 3 request a pause
// once; bit 4 load the saved context into a second engine at the end), u8 unused, u16 start
// offset in words, u32 stall step in bytes; then the bytes, placed in guest memory, executed from
// the start offset. Bounded by a command cap over all runs, the harness's draw caps and, where
// the engine has it, the GE-time limit.
#include <cstdint>

#include "hle/ge_engine.h"
#include "softmodel/soft_renderer.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;

namespace {

// Records the interrupts; a SIGNAL pause is resumed by the run loop.
struct Listener : GeListener {
    u64 events = 0;
    void onSignal(u32, u32, u32, u32) override { ++events; }
    void onFinish(u32, u32) override { ++events; }
    void onEnd(u32) override { ++events; }
    void onError(GeError, u32, const std::string& m) override { events += m.size(); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    fuzz::Bytes in(data, size);
    const u8 flags = in.u8v();
    in.u8v();
    const u32 start = u32(in.u16v()) * 4;
    const u32 step = std::max<u32>(in.u32v() & 0xFFFF, 4);
    const u8* blob = nullptr;
    u32 n = u32(in.take(fuzz::kMaxInput, blob));

    static Memory mem;
    mem.clear();
    u32 base = 0;
    switch (flags & 3) {
    case 0: base = 0x08800000; break;
    case 1: n &= ~3u, base = Memory::kRamBase + mem.ramSize() - n; break;
    case 2: n = std::min<u32>(n, Memory::kVramSize), base = Memory::kVramBase; break;
    case 3: n = std::min<u32>(n, Memory::kScratchSize), base = Memory::kScratchBase; break;
    }
    if (n) mem.write(base, blob, n);

    soft::SoftOptions so;
    so.threads = 1;
    auto soft = soft::createSoftRenderer(mem, so);
    fuzz::BoundedRenderer r(*soft);
    r.reset();
    GeEngine eng(mem, &r);
    Listener listener;
    eng.setListener(&listener);
    eng.setTimeLimit(fuzz::kGeTimeCycles);

    const bool stalls = (flags >> 2) & 1;
    u32 stall = stalls ? base + std::min(start + step, n) : 0;
    eng.startList(base + start, stall);
    if ((flags >> 3) & 1) eng.requestPause();
    // 32K commands: a list that runs off its end into zeroed memory executes NOPs until then.
    u64 left = u64(1) << 15;
    for (int i = 0; i < 64 && left; ++i) {
        const u64 before = eng.stats().commands;
        const RunStatus s = eng.run(std::min<u64>(left, 4096));
        left -= std::min(left, eng.stats().commands - before);
        if (s == RunStatus::Stalled) {
            stall += step;
            eng.setStall(stall >= base + n ? 0 : stall);
        } else if (s == RunStatus::Paused) {
            eng.resume();
        } else if (s != RunStatus::Budget) {
            break;
        }
    }
    r.flushToMemory();
    if ((flags >> 4) & 1) {
        u32 ctx[512];
        eng.state().saveContext(ctx);
        NullRenderer null;
        GeEngine other(mem, &null);
        other.loadContext(ctx);
    }
    return 0;
}
