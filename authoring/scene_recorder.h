// SPDX-License-Identifier: MIT
// The scene recorder: turns the command stream a ListBuilder emits into a `.ppdmp` frame dump
// without running it (tools/make_scenes, tests). Authoring code: linked by tools and tests only.
#pragma once
#include <string>
#include <vector>

#include "hle/dump/record_builder.h"
#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

namespace ge {

// Turns an executed command stream into .ppdmp records with the recording rules FrameRecorder
// uses (dump::RecordBuilder, hle/dump/record_builder.h): REGISTERS blocks of state and kick words;
// before each kick the data it consumes (texture levels, then INDICES, then VERTICES; CLUT before
// CLOAD; TRANSFERSRC before XSTART). Data is read from `mem` at the time of the kick, so the
// builder must have placed it. The recorder keeps its own GeState from the words (the GE does not
// run), so it can follow only what the words say: no list addresses (ORIGIN), no bounding-box
// results.
//
// Two of the builder's options fit a recorder that does not render (record_builder.h):
// Pixels::Unknown, so VRAM the GE drew in this recording is never copied into the dump (players
// keep what they rendered), and Textures::Sampled, so a draw records only the texture levels it
// samples.
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
    // Things the recorder could not express faithfully (e.g. a transfer to RAM). Empty for a
    // well-formed scene.
    const std::vector<std::string>& warnings() const { return rec_.warnings(); }
    u32 kicks() const { return kicks_; }

private:
    void recordDraw(u32 word);
    u32 formAddress(u32 arg) const;

    dump::DumpWriter& out_;
    dump::RecordBuilder rec_;
    GeState st_;
    u32 kicks_ = 0;
};

}  // namespace ge
