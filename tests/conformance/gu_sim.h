// SPDX-License-Identifier: MIT
// Hardware conformance (docs/conformance.md): the environment a pspautotests GPU test runs in, re-created
// around ge2gl's engine so that the test's GE state and draws can be replayed as the SDK calls of
// its C source would emit them, and its read-backs compared with the values recorded on a PSP.
//
// GuSim owns the emulated memory, one backend and one GeEngine for a whole test program: state
// carries over from one checkpoint to the next as on the PSP. What the SDK does around the GE is
// reproduced where it matters:
//  - sceGuInit enqueues a list that writes 0 to every state register except TBW0 (0x040004:
//    buffer width 4, address bits 0x04 << 24) and TSIZE0 (0x101: 2x2), so registers start as that
//    list leaves them (pspsdk src/gu/sceGuInit.c);
//  - the first sceGuStart also sends the dither matrix {-4 0 -3 1 / 2 -2 3 -1 / -3 1 -4 0 /
//    3 -1 2 -2}, patch divide 16x16, colour material AMBIENT|DIFFUSE|SPECULAR, specular power 1.0
//    and texture scale 1,1 (pspsdk src/gu/sceGuStart.c);
//  - the tests' binaries were built with the original pspsdk, whose sceGuDispBuffer also sets the
//    drawing region (conformance.h sdkDispBuffer); today's pspsdk differs there;
//  - sceDmacMemcpy to and from VRAM are CPU accesses: the backend is told of a write, and a read
//    sees what the GE drew (Renderer::memoryWritten / flushToMemory).
// The sceGu wrappers the tests call live in ListBuilder (hle/list_builder.h), which emits the same
// words as the SDK functions of the same name.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "authoring/list_builder.h"
#include "hle/ge_engine.h"
#include "hle/memory.h"

namespace ge::conformance {

// "soft" or "gl" (GL exact mode on the default headless context).
struct Backend {
    std::string name;
};

class GuSim {
public:
    // False (and `err`) when the backend cannot be created (no GL here).
    bool create(const std::string& backend, std::string& err);

    // sceGuInit: the register-reset list, run to completion.
    void init();
    // sceGuStart(GU_DIRECT): a new list (the first one also gets the SDK's first-start state).
    ListBuilder& start();
    ListBuilder& list() { return *b_; }
    // sceGuFinish + sceGuSync(0, 0): FINISH/END appended, the list run to completion.
    void finishSync();

    // A CPU write (memcpy, sceDmacMemcpy) of host bytes to guest memory at `addr`.
    void cpuWrite(u32 addr, const void* data, u32 size);
    // sceDmacMemcpy of host words into VRAM at `offset` (bytes from 0x04000000), and back.
    void writeVram(u32 offset, const void* data, u32 size) { cpuWrite(Memory::kVramBase + offset, data, size); }
    void fillVram32(u32 offset, u32 value, u32 words);
    u32 readVram32(u32 offset);
    // A CPU read of guest memory after the GE's work has landed (nullptr outside valid memory).
    const u8* readBytes(u32 addr, u32 size);
    u16 readVram16(u32 offset);

    Memory& memory() { return *mem_; }
    const std::string& backend() const { return backend_; }

private:
    std::string backend_;
    std::unique_ptr<Memory> mem_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<GeEngine> engine_;
    std::unique_ptr<ListBuilder> b_;
    u32 arena_ = ListBuilder::kDefaultArena;
    bool firstStart_ = true;
};

// The read-backs of one test program on one backend, against the values recorded on hardware.
struct Checkpoint {
    std::string name;
    u32 expected = 0, got = 0, mask = 0xFFFFFFFFu;
    bool pass() const { return ((expected ^ got) & mask) == 0; }
};

struct TestRun {
    std::string test, backend;
    std::vector<Checkpoint> checkpoints;
    int passed() const;
    int total() const { return int(checkpoints.size()); }
    // "commands/blend [soft]: 62/62 checkpoints" and one line per failure.
    std::string report() const;
};

}  // namespace ge::conformance
