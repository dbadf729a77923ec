// SPDX-License-Identifier: MIT
// The scene recorder: turns the command stream a ListBuilder emits into a `.ppdmp` frame dump
// without running it (tools/make_scenes, tests). Authoring code: linked by tools and tests only.
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

namespace ge {

namespace dump {
class DumpWriter;
}

// Turns an executed command stream into .ppdmp records the way PPSSPP's recorder orders them
// (ppdmp.md §4, §7): REGISTERS blocks of state and kick words; before each kick the data it
// consumes (texture levels, then INDICES, then VERTICES; CLUT before CLOAD; TRANSFERSRC before
// XSTART). Data is read from `mem` at the time of the kick, so the builder must have placed it.
//
// VRAM textures become FRAMEBUFn records. When the range was (possibly) drawn by the GE earlier
// in the recording — a colour or depth buffer or a transfer destination — the recorder cannot
// know its pixels (it does not render), so it writes the 16-byte header only, with flags
// "drawn" | "unchanged" (| "target" when the address is a buffer start): players then keep what
// they rendered (PPSSPP skips the copy for flag bit 1 in v6; a zero-length copy is a no-op
// anyway). Other VRAM textures carry their bytes with flags 0 (ppdmp.md §7 rule 5). Likewise a transfer
// whose source, or a CLOAD whose palette, lies in GE-drawn VRAM gets no TRANSFERSRC / CLUT record:
// the recorded XBP1/XBW1 or CBP/CBW words keep pointing at VRAM, which players leave as recorded
// (ppdmp.md §6.4), so they read the pixels they rendered.
class DumpRecorder {
public:
    DumpRecorder(const Memory& mem, dump::DumpWriter& out);

    // INIT (initial.saveContext) and the first DISPLAY.
    void begin(const GeState& initial, u32 displayAddr, u32 stride, u32 format);
    // One command word as the GE executes it.
    void command(u32 word);
    // CPU writes into guest memory (already done by the caller). VRAM destinations are recorded
    // as MEMCPYDEST + MEMCPYDATA / MEMSET; RAM destinations need no record (draws capture the
    // RAM they read).
    void cpuMemcpy(u32 dest, const void* data, u32 size);
    void cpuMemset(u32 dest, u8 value, u32 size);
    // Closes the open REGISTERS block and writes the final DISPLAY record.
    void end(u32 displayAddr, u32 stride, u32 format);

    const GeState& state() const { return st_; }
    // Things the recorder could not express faithfully (e.g. a transfer whose source was drawn
    // by the GE). Empty for a well-formed scene.
    const std::vector<std::string>& warnings() const { return warnings_; }
    u32 kicks() const { return kicks_; }

private:
    struct Range {
        u32 begin, end;  // normalised addresses, [begin, end)
    };
    void flushBlock();
    void recordDraw(u32 word);
    void recordTextures();
    void recordClut(u32 word);
    bool recordTransfer(u32 word);
    void markDrawnBuffers(bool depthWritten);
    bool overlapsDrawn(u32 addr, u32 size) const;
    // Bytes the CPU wrote are known again: cuts [dest, dest + size) out of the drawn ranges.
    void forgetDrawn(u32 dest, u32 size);
    bool isTarget(u32 addr) const;
    u32 formAddress(u32 arg) const;

    const Memory& mem_;
    dump::DumpWriter& out_;
    GeState st_;
    std::vector<u32> block_;
    std::vector<Range> drawn_;
    std::vector<u32> targets_;
    std::vector<std::string> warnings_;
    u32 kicks_ = 0;
    bool begun_ = false;
};

}  // namespace ge
