// SPDX-License-Identifier: MIT
// The GE debugger (docs/debugger.md): breakpoints and read-outs over a GeEngine, shared
// by the plugin API (ge2gl_debug_*) and `ge2gl step`.
//
// Breakpoints is a CommandObserver: before each command it decides whether the GE stops there
// (next command, next draw, next PRIM, next list, next frame, an opcode, an address). A run that
// stops leaves the pc on the command; the next run executes it (the stop is taken once per
// arrival). The read-outs decode what the engine holds — registers with their fields named from
// the field table, matrices, the list's execution registers, disassembly, the frame/depth/stencil
// buffers, the bound texture's levels, the CLUT, the vertices of the draw at the pc before and
// after transform — from guest memory: the caller makes the backend write its pixels back first.
#pragma once
#include <bitset>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "hle/ge_engine.h"
#include "hle/vertex_decoder.h"

namespace ge::debug {

enum BreakFlag : u32 {
    kNextCommand = 1,  // before the next command
    kNextDraw = 2,     // before the next PRIM, BEZIER or SPLINE
    kNextPrim = 4,     // before the next PRIM
    kNextList = 8,     // before the first command of a list other than the last one seen
    kNextFrame = 16,   // before the first command after a frame ended (frameEnded())
};

bool isDrawKick(u32 word);  // PRIM, BEZIER, SPLINE

class Breakpoints : public CommandObserver {
public:
    // `currentList` tells which list the GE runs (the sceGe ID); may be empty (no list breaks).
    explicit Breakpoints(std::function<s32()> currentList = {}) : currentList_(std::move(currentList)) {}

    void breakOnce(u32 flags) { once_ |= flags; }
    u32 pending() const { return once_; }
    void clearOnce() { once_ = 0; }
    void setOpcode(u8 op, bool on) { ops_.set(op, on); }
    void setAddress(u32 addr, bool on);
    void clearAll();
    // The GE ran out of lists at a FINISH: the next command starts a frame.
    void frameEnded() { frameEnded_ = true; }
    // When set, called where the GE would stop; returning false lets it go on (a tool inspecting
    // in place). Default: stop.
    std::function<bool(u32 pc, u32 word)> onBreak;

    bool beforeCommand(u32 pc, u32 word) override;

    u64 draws() const { return draws_; }         // draw kicks executed since creation
    const std::string& reason() const { return reason_; }  // why the last stop happened

private:
    bool wants(u32 pc, u32 word);

    std::function<s32()> currentList_;
    u32 once_ = 0;
    std::bitset<256> ops_;
    std::set<u32> addrs_;
    bool frameEnded_ = false;
    s32 lastList_ = -1;
    bool haveLastList_ = false;
    bool resuming_ = false;  // stopped at resumePc_: let it run once
    u32 resumePc_ = 0;
    u64 draws_ = 0;
    std::string reason_;
};

// ---- Read-outs ----

// Every register word the GE holds, one line each ("0x9e FBW width=512 high=0"), then the
// matrices as floats, the address registers and the palette's loaded size.
std::string stateText(const GeState& st);
// The running list: pc, stall, CALL stack, SIGNAL stack depth, BASE, OFFSET, BFLG.
std::string listText(const ListRegs& l, const GeState& st);
// `count` commands from `addr`, one line each, the line of `mark` flagged with '>'.
std::string disassembly(const Memory& mem, u32 addr, u32 count, u32 mark);

// The current frame buffer (FBP/FBW/FPF) as RGBA8888 (R first) rows, width x height.
bool readColor(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u8>& rgba);
// The depth buffer (ZBP/ZBW), 16-bit values.
bool readDepth(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u16>& out);
// Stencil: the frame buffer's alpha bits (5551: 1 bit, 4444: 4, 8888: 8; 565 has none: zeros).
bool readStencil(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u8>& out);
// A texture level of the current texture state decoded (through the CLUT) to RGBA8888 rows.
bool readTexture(const Memory& mem, const GeState& st, int level, u32& width, u32& height, std::vector<u8>& rgba);
// The palette RAM decoded in the CLUT format: 256 entries (32-bit) or 512 (16-bit), RGBA8888.
std::vector<u32> readClut(const GeState& st);

// The vertices of the draw at `word` (a PRIM; the state as it is before the draw): as decoded
// (model space, or drawing coordinates in through mode) and after transform (screen position in
// pixels, depth, the colour and texture coordinates the rasteriser gets).
struct DrawVertex {
    DecodedVertex in;
    float screenX = 0, screenY = 0;  // drawing coordinates, pixels
    int screenZ = 0;
    float s = 0, t = 0, q = 1;
    u8 color[4] = {};
    bool outside = false;  // breaks the docs/ge-rules.md §8.5 screen range rule (the primitive is dropped)
};
// `acc`: the backend's profile (transform-mode sprite positions: AccuracyProfile::pspSpritePosition).
bool drawVertices(const Memory& mem, const GeState& st, u32 word, const geo::AccuracyProfile& acc,
                  std::vector<DrawVertex>& out, std::string& err);

}  // namespace ge::debug
