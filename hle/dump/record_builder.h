// SPDX-License-Identifier: MIT
// RecordBuilder: the recording rules of a `.ppdmp` frame dump (version 6), in one place for both
// recorders: FrameRecorder (hle/dump/recorder.h), which watches a running GeEngine, and the scene
// recorder (authoring/scene_recorder.h), which records the words a ListBuilder emits without
// running them. The rules follow PPSSPP's recorder (GPU/Debugger/Record.cpp; docs/recording.md
// lists every record, docs/ppdmp.md §3–§7 the format):
//   - REGISTERS: every command word except the ones a player replaces or that only steer the list
//     (notRecorded(); Record.cpp NotifyCommand; ppdmp.md §3.2, §7 rule 4);
//   - at PRIM/BEZIER/SPLINE (FlushPrimState): texture levels (TEXTUREn from RAM, FRAMEBUFn with the
//     ppdmp.md §3.3 flags from VRAM), then INDICES, then VERTICES, sized from VTYPE, the count and the
//     state's vertex/index pointers;
//   - at CLOAD (EmitClut): [CLUTADDR] + CLUT; at XSTART (EmitTransfer): TRANSFERSRC, the kick dropped
//     for transfers to RAM;
//   - host writes into VRAM (NotifyMemcpy/NotifyMemset): MEMCPYDEST + MEMCPYDATA, or MEMSET;
//   - VRAM knowledge in 256-byte blocks (dirty / drawn / clean) and the colour/depth buffer starts
//     of the draws, for the §3.3 flags (GetTargetFlags, DirtyDrawnVRAM).
// The caller passes the GE state as it is before each command; the builder reads guest memory.
//
// Two options set what a recorder can know:
//   - Pixels::Unknown: guest VRAM does not hold what the GE drew (the scene recorder does not render).
//     Drawn VRAM is then never copied into the dump: a texture level in it is a header-only
//     FRAMEBUFn with "drawn" | "unchanged" (| "target"), so players keep what they rendered (PPSSPP
//     skips the copy for flag bit 1 in v6); a CLOAD or transfer reading it gets no CLUT /
//     TRANSFERSRC record, so the recorded CBP/CBW or XBP1/XBW1 words keep pointing into VRAM, which
//     players leave as recorded (ppdmp.md §6.4). Transfer destinations count as drawn.
//   - Textures::Sampled: a draw records only the levels it samples (texturing on, not a clear,
//     levels 0 to the TMODE maximum) instead of PPSSPP's safe set (every level with an address when
//     TME or AAE is on or the vertices carry texture coordinates).
#pragma once
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "hle/dump/dump_writer.h"
#include "hle/ge_state.h"
#include "hle/memory.h"

namespace ge::dump {

class RecordBuilder {
public:
    enum class Pixels : u8 { InMemory, Unknown };
    enum class Textures : u8 { MaySample, Sampled };
    struct Options {
        Pixels pixels = Pixels::InMemory;
        Textures textures = Textures::MaySample;
    };

    RecordBuilder(DumpWriter& out, const Memory& mem, Options opt);

    // Opcodes a REGISTERS block must not hold (ppdmp.md §7 rule 4): a player replaces them by its
    // own (pointers from data records) or they steer the list.
    static bool notRecorded(u32 op);

    // Called with (addr, size) before VRAM bytes are read for the dump: a backend drawing on the
    // GPU writes its newest pixels back there (Renderer::syncMemoryForRead).
    void setVramReadHook(std::function<void(u32, u32)> hook) { vramReadHook_ = std::move(hook); }
    // Nothing of VRAM is known to the dump (DirtyAllVRAM(DIRTY)); a player's VRAM starts as zeros
    // (ppdmp.md §6.4), which is what the shadow copy says. No draw targets yet.
    void reset();
    // The dump begins with a CLUT record: the player then points CBP/CBW elsewhere (ppdmp.md §6.2).
    void initialClutWritten() { clutRegsReplaced_ = true; }

    // A command word without data (anything but PRIM/BEZIER/SPLINE, CLOAD, XSTART): into the
    // REGISTERS block unless notRecorded().
    void command(u32 word);
    // A state word written as it is (a restored context).
    void stateWord(u32 word) { block_.push_back(word); }
    // The kicks, with the state before them. `count`: vertices of a PRIM, control points of a patch.
    void draw(const GeState& st, u32 word, u32 count);
    void clut(const GeState& st, u32 word);
    // False when the transfer goes to RAM: then nothing is recorded, the XSTART word included.
    bool transfer(const GeState& st, u32 word);
    // A host (CPU/DMA) write of guest memory that already happened.
    void hostWrite(u32 addr, u32 size);
    // Closes the open REGISTERS block.
    void flushBlock();

    void warn(const std::string& w);
    const std::vector<std::string>& warnings() const { return warnings_; }
    u64 draws() const { return draws_; }

private:
    enum class Vram : u8 { Dirty, Drawn, Clean };
    static constexpr u32 kBlockShift = 8;  // 256-byte blocks of VRAM for the dirty map

    void drawTextures(const GeState& st, u32 count);
    void texture(const GeState& st, int level, u32 addr);
    void markDrawn(const GeState& st);
    void markVram(u32 addr, u32 size, Vram state, bool wholeBlocksOnly);
    bool anyDrawn(u32 addr, u32 size) const;
    u32 targetFlags(u32 addr, u32 size);
    void updateShadow(u32 addr, u32 size);
    // Pointer to `size` readable bytes at addr (after the VRAM read hook), or null.
    const u8* read(u32 addr, u32 size);

    DumpWriter& out_;
    const Memory& mem_;
    Options opt_;
    std::function<void(u32, u32)> vramReadHook_;
    std::vector<u32> block_;
    std::vector<Vram> vram_;   // per 256-byte block: what the dump knows of it
    std::vector<u8> shadow_;   // what the dump has written to VRAM so far (Record.cpp lastVRAM)
    std::set<u32> targets_;    // colour/depth buffer starts used by draws (VRAM offsets)
    // The player queues CBW/CBP for the initial CLUT record (ppdmp.md §6.2): the recorded CBP/CBW no
    // longer hold, so they are written again before the first CLOAD from VRAM.
    bool clutRegsReplaced_ = false;
    u64 draws_ = 0;
    std::vector<std::string> warnings_;
};

}  // namespace ge::dump
