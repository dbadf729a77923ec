// SPDX-License-Identifier: MIT
#include "authoring/scene_recorder.h"

#include "hle/dump/dump_writer.h"

namespace ge {

DumpRecorder::DumpRecorder(const Memory& mem, dump::DumpWriter& out)
    : out_(out), rec_(out, mem, {dump::RecordBuilder::Pixels::Unknown, dump::RecordBuilder::Textures::Sampled}) {}

void DumpRecorder::begin(const GeState& initial, u32 displayAddr, u32 stride, u32 format) {
    st_ = initial;
    u32 ctx[512];
    st_.saveContext(ctx);
    out_.init(ctx);
    out_.display(displayAddr, stride, format);
    rec_.reset();
}

void DumpRecorder::end(u32 displayAddr, u32 stride, u32 format) {
    rec_.flushBlock();
    out_.display(displayAddr, stride, format);
}

u32 DumpRecorder::formAddress(u32 arg) const {
    // ge-rules.md §4.2: (BASE-high | arg) + OFFSET, 28 bits (PPSSPP keeps BASE bits 19..16).
    u32 hi = (st_.regs[GE_CMD_BASE] & 0x000F0000) << 8;
    return ((hi | (arg & 0xFFFFFF)) + st_.offsetAddr) & 0x0FFFFFFF;
}

// Follows the words' effect on the state (the GE does not run here) and hands each to the
// record builder with the state before it.
void DumpRecorder::command(u32 word) {
    const u8 op = u8(word >> 24);
    const u32 arg = word & 0xFFFFFF;
    switch (op) {
    case GE_CMD_VADR: st_.vertexAddr = formAddress(arg); break;
    case GE_CMD_IADR: st_.indexAddr = formAddress(arg); break;
    case GE_CMD_OFFSET: st_.offsetAddr = arg << 8; return;
    case GE_CMD_JUMP: case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET:
    case GE_CMD_END: case GE_CMD_SIGNAL: case GE_CMD_FINISH:
        return;  // the builder's words are already in execution order
    case GE_CMD_ORIGIN:
        rec_.warn("ORIGIN: the recorder does not know list addresses; OFFSET left as is");
        return;
    case GE_CMD_BBOX: {
        // BBOX advances the pointers like a draw (ge-rules.md §4.6); its result is not replayed.
        const u32 count = arg & 0xFFFF;
        if (st_.VTYPE_idx()) st_.indexAddr += count * st_.indexSize();
        else st_.vertexAddr += count * st_.vertexStride();
        return;
    }
    case GE_CMD_PRIM: case GE_CMD_BEZIER: case GE_CMD_SPLINE: recordDraw(word); return;
    case GE_CMD_CLOAD:
        rec_.clut(st_, word);
        ++kicks_;
        break;
    case GE_CMD_XSTART:
        // PPSSPP records only transfers into VRAM; the XSTART word itself is dropped (ppdmp.md §3.2).
        if (!rec_.transfer(st_, word)) {
            rec_.warn("transfer to RAM dropped from the dump");
            return;
        }
        ++kicks_;
        break;
    default: rec_.command(word); break;
    }
    if (geCmdKnown(op)) st_.regs[op] = word;
}

void DumpRecorder::recordDraw(u32 word) {
    const u8 op = u8(word >> 24);
    u32 count;
    if (op == GE_CMD_PRIM) count = word & 0xFFFF;
    else count = (word & 0xFF) * ((word >> 8) & 0xFF);  // control points of a patch (ge-rules.md §4.6)
    rec_.draw(st_, word, count);
    if (count > 0) {
        // The GE advances the pointer it read (ge-rules.md §4.6): past the indices of an indexed
        // draw, else past the vertices.
        if (st_.VTYPE_idx()) st_.indexAddr += count * st_.indexSize();
        else st_.vertexAddr += count * st_.vertexStride();
    }
    st_.regs[op] = word;
    ++kicks_;
}

void DumpRecorder::cpuMemcpy(u32 dest, const void*, u32 size) { rec_.hostWrite(dest, size); }

void DumpRecorder::cpuMemset(u32 dest, u8, u32 size) { rec_.hostWrite(dest, size); }

}  // namespace ge
