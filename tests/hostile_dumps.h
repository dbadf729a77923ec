// SPDX-License-Identifier: MIT
// Small hostile dumps written with the project's own DumpWriter: each asks for far
// more work than a frame, or for work without end. Shared by the replay-budget tests and by
// write_hostile_dumps, which writes them as files for scripts/check_dumps.sh.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "hle/dump/dump_writer.h"
#include "hle/list_builder.h"

namespace ge::hostile {

inline u32 word(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

// Where the player's list buffer lies (player.cpp: 256 KiB at the top of user memory), so that a
// hostile block can jump into it.
constexpr u32 kListBuf = 0x0A000000 - (256u << 10);

inline dump::DumpWriter start() {
    dump::DumpWriter w;
    GeState st;
    st.reset();
    for (int op = 0; op < 256; ++op) st.regs[op] = u32(op) << 24;
    u32 ctx[512];
    st.saveContext(ctx);
    w.init(ctx);
    w.display(0x04000000, 512, GE_FORMAT_8888);
    return w;
}

// 480×272 8888 frame at VRAM 0, full-screen scissor/region, through-mode 8888 + 16-bit vertices.
inline std::vector<u32> frameState() {
    ListBuilder s;
    s.drawBuffer(GE_FORMAT_8888, 0, 512);
    s.scissor(0, 0, 480, 272);
    s.region(0, 0, 480, 272);
    s.setVertexType(vt::COL_8888 | vt::POS_16 | vt::THROUGH);
    return s.words();
}
constexpr u32 kThroughColor = vt::COL_8888 | vt::POS_16 | vt::THROUGH;

// A block that draws a full-screen rectangle and jumps back to its own start (the BASE + VADR
// the vertices queued, since a draw advances the vertex pointer, docs/ge-rules.md §4.6): each catch-up runs until
// its command budget, the next starts over.
inline dump::Dump rectangleLoop() {
    dump::DumpWriter w = start();
    const std::vector<u32> st = frameState();
    w.registers(st);
    BuildVertex v[2];
    v[1].x = 480;
    v[1].y = 272;
    const auto bytes = packVertices(kThroughColor, v, 2);
    w.vertices(bytes.data(), u32(bytes.size()));
    // List buffer: NOP, the state block, then BASE + VADR (queued by VERTICES) and this block.
    const u32 loopStart = kListBuf + 4 + u32(4 * st.size());
    w.registers({word(GE_CMD_PRIM, (GE_PRIM_RECTANGLES << 16) | 2), word(GE_CMD_BASE, (loopStart >> 8) & 0xFF0000),
                 word(GE_CMD_JUMP, loopStart & 0xFFFFFF)});
    w.display(0x04000000, 512, GE_FORMAT_8888);
    return w.dump();
}

// 200 blocks that each jump to themselves, each followed by a DISPLAY (a catch-up).
inline dump::Dump selfJumps() {
    dump::DumpWriter w = start();
    for (u32 k = 0; k < 200; ++k) {
        const u32 self = kListBuf + 4 + 8 * k + 4;  // block k: after the NOP and k two-word blocks
        w.registers({word(GE_CMD_BASE, (self >> 8) & 0xFF0000), word(GE_CMD_JUMP, self & 0xFFFFFF)});
        w.display(0x04000000, 512, GE_FORMAT_8888);
    }
    return w.dump();
}

// One 2 MiB FRAMEBUF payload behind 20,000 records: the player would copy 40 GB into VRAM.
inline dump::Dump sharedFramebufPayload() {
    dump::DumpWriter w = start();
    std::vector<u8> vram(2u << 20, 0x5A);
    w.framebufTexture(0, 0x04000000, 512, 0, vram.data(), u32(vram.size()));
    dump::Dump d = w.dump();
    const dump::Record fb = d.records.back();
    for (int i = 0; i < 20000; ++i) d.records.push_back(fb);
    return d;
}

// A 57,300-vertex fan of screen-sized triangles (centre, then a zigzag between far corners).
inline dump::Dump hugeFan() {
    dump::DumpWriter w = start();
    w.registers(frameState());
    std::vector<BuildVertex> v(57300);
    v[0].x = 240, v[0].y = 136;
    for (size_t i = 1; i < v.size(); ++i) v[i].x = (i & 1) ? 0 : 479, v[i].y = (i & 2) ? 0 : 271;
    const auto bytes = packVertices(kThroughColor, v.data(), u32(v.size()));
    w.vertices(bytes.data(), u32(bytes.size()));
    w.registers({word(GE_CMD_PRIM, (GE_PRIM_TRIANGLE_FAN << 16) | 57300)});
    w.display(0x04000000, 512, GE_FORMAT_8888);
    return w.dump();
}

// A 100×100-point Bezier surface at division 127: 33 × 33 patches of 128 × 128 vertices, past
// the tessellator's cap of 2^21.
inline dump::Dump patchAtTheCap() {
    dump::DumpWriter w = start();
    std::vector<u32> st = frameState();
    st.push_back(word(GE_CMD_DIVIDE, (127 << 8) | 127));
    w.registers(st);
    std::vector<BuildVertex> v(100 * 100);
    for (size_t i = 0; i < v.size(); ++i) v[i].x = float(i % 100), v[i].y = float(i / 100);
    const auto bytes = packVertices(kThroughColor, v.data(), u32(v.size()));
    w.vertices(bytes.data(), u32(bytes.size()));
    w.registers({word(GE_CMD_BEZIER, (100 << 8) | 100)});
    w.display(0x04000000, 512, GE_FORMAT_8888);
    return w.dump();
}

struct Named {
    const char* name;
    std::function<dump::Dump()> make;
};
inline std::vector<Named> all() {
    return {{"rectangle_loop", rectangleLoop}, {"self_jumps", selfJumps},
            {"shared_framebuf_payload", sharedFramebufPayload}, {"huge_fan", hugeFan},
            {"patch_at_the_cap", patchAtTheCap}};
}

}  // namespace ge::hostile
