// SPDX-License-Identifier: MIT
// Small hostile dumps written with the project's own DumpWriter: each asks for far
// more work than a frame, or for work without end. Shared by the replay-budget tests and by
// write_hostile_dumps, which writes them as files for scripts/check_dumps.sh.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "authoring/list_builder.h"
#include "hle/dump/dump_writer.h"

namespace ge::hostile {

inline u32 word(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

// Where the player's list buffer lies (player.cpp: 256 KiB at the top of user memory), so that a
// hostile block can jump into it.
constexpr u32 kListBuf = 0x0A000000 - (256u << 10);
constexpr u32 kListBufWords = (256u << 10) / 4;

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

// The shape of a dump that costs nothing to store: one large payload behind many records. The
// last `group` records of `w` (one record, or a MEMCPYDEST/CLUTADDR and the record it applies to)
// are repeated until the dump holds `count` groups, then a DISPLAY ends it. A file of a few
// hundred bytes (zstd compresses the repeats away) that asks the player to handle gigabytes.
inline dump::Dump repeatLast(dump::DumpWriter& w, size_t group, u32 count) {
    dump::Dump d = w.dump();
    const std::vector<dump::Record> g(d.records.end() - std::ptrdiff_t(group), d.records.end());
    for (u32 i = 1; i < count; ++i) d.records.insert(d.records.end(), g.begin(), g.end());
    d.records.push_back(d.records[1]);  // the DISPLAY start() wrote
    return d;
}
constexpr u32 kSharedRecords = 200000;
constexpr u32 kSharedBytes = 4u << 20;

// One 4 MiB REGISTERS payload (NOPs) behind 200,000 records: 2^38 words for the player to
// translate and write into its list buffer, and for the GE to run.
inline dump::Dump sharedRegistersPayload() {
    dump::DumpWriter w = start();
    w.registers(std::vector<u32>(kSharedBytes / 4, 0));
    return repeatLast(w, 1, kSharedRecords);
}

// A 192 KiB block of NOPs behind 200,000 records: it fits the 256 KiB list buffer, so every
// record wraps the list, and the wrap's catch-up finds the GE already at the buffer's start, where
// the stall address goes (docs/ppdmp.md §6.2): the GE runs none of it, and the player's copies
// are all the work there is.
inline dump::Dump sharedRegistersBlock() {
    dump::DumpWriter w = start();
    w.registers(std::vector<u32>(48u << 10, 0));
    return repeatLast(w, 1, kSharedRecords);
}

// The same with words the player rewrites (TBWn with changing widths, TBPn, BASE): every word of
// the block needs its translation, and the translated block differs from the payload.
inline dump::Dump sharedRegistersRewrites() {
    dump::DumpWriter w = start();
    std::vector<u32> words(kSharedBytes / 4);
    for (size_t i = 0; i < words.size(); ++i) {
        const u32 k = u32(i % 4);
        words[i] = k == 0 ? word(GE_CMD_TBW0, 64) : k == 1 ? word(GE_CMD_TBW0, 128)
                 : k == 2 ? word(GE_CMD_TBP0 + 3, 0x1000) : word(GE_CMD_BASE, 0);
    }
    w.registers(words);
    return repeatLast(w, 1, kSharedRecords);
}

// 65,536 REGISTERS records over one 4 MiB block of NOPs, each a different window of it (offset
// and size move by 4 bytes): no two records share a payload, so a cache of translated payloads
// does not help, and each still asks for about 4 MiB of words.
inline dump::Dump slidingRegistersPayloads() {
    dump::DumpWriter w = start();
    w.registers(std::vector<u32>(kSharedBytes / 4, 0));
    dump::Dump d = w.dump();
    const dump::Record r = d.records.back();
    for (u32 i = 1; i < 65536; ++i) d.records.push_back(dump::Record{r.type, r.size - 4 * i, r.ptr + 4 * i});
    d.records.push_back(d.records[1]);
    return d;
}

// One 4 MiB payload behind 200,000 records of each data type the player maps or copies.
inline std::vector<u8> bigPayload() {
    std::vector<u8> b(kSharedBytes);
    for (size_t i = 0; i < b.size(); ++i) b[i] = u8(i * 7);
    return b;
}
inline dump::Dump sharedVerticesPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.vertices(b.data(), u32(b.size()));
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedIndicesPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.indices(b.data(), u32(b.size()));
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedTexturePayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.texture(0, b.data(), u32(b.size()));
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedClutPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.clut(b.data(), u32(b.size()));
    return repeatLast(w, 1, kSharedRecords);
}
// CLUTADDR + CLUT: the player copies the CLUT bytes into VRAM at once.
inline dump::Dump sharedVramClutPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.clutAddr(0x04000000, 0);
    w.clut(b.data(), u32(b.size()));
    return repeatLast(w, 2, kSharedRecords);
}
inline dump::Dump sharedTransferSrcPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.transferSrc(b.data(), u32(b.size()));
    return repeatLast(w, 1, kSharedRecords);
}
// MEMSET of all of VRAM and past it (the size is the file's to choose).
inline dump::Dump sharedMemset() {
    dump::DumpWriter w = start();
    w.memset(0x04000000, 0x33, 0xFFFFFFFF);
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedMemcpyPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.memcpy(0x04000000, b.data(), u32(b.size()));
    return repeatLast(w, 2, kSharedRecords);
}
inline dump::Dump sharedDisplay() {
    dump::DumpWriter w = start();
    w.registers(frameState());
    w.display(0x04000000, 512, GE_FORMAT_8888);
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedEdramTrans() {
    dump::DumpWriter w = start();
    w.edramTrans(0x200);
    return repeatLast(w, 1, kSharedRecords);
}
inline dump::Dump sharedClutAddr() {
    dump::DumpWriter w = start();
    w.clutAddr(0x04000000, 0);
    return repeatLast(w, 1, kSharedRecords);
}
// INIT with a 4 MiB payload (only its first 2,048 bytes are the context), again and again.
inline dump::Dump sharedInitPayload() {
    dump::DumpWriter w = start();
    const auto b = bigPayload();
    w.vertices(b.data(), u32(b.size()));
    dump::Dump d = w.dump();
    d.records.back().type = dump::INIT;
    for (u32 i = 1; i < kSharedRecords; ++i) d.records.push_back(d.records.back());
    d.records.push_back(d.records[1]);
    return d;
}
// A 2 MiB FRAMEBUF payload behind 200,000 records (sharedFramebufPayload's shape, ten times
// the records).
inline dump::Dump sharedFramebufPayloadMany() {
    dump::DumpWriter w = start();
    std::vector<u8> vram(2u << 20, 0x5A);
    w.framebufTexture(0, 0x04000000, 512, 0, vram.data(), u32(vram.size()));
    return repeatLast(w, 1, kSharedRecords);
}

// Draws whose primitives are cheap for the GE but not for the GL translator, which builds two
// GL triangles per line or point fragment and a record per triangle on the CPU
// (translator/vertex_pipeline.h kHostPixelsPerGlTriangle): one PRIM of `v` repeated `draws` times.
inline dump::Dump repeatedDraw(u32 prim, const std::vector<BuildVertex>& v, u32 draws) {
    dump::DumpWriter w = start();
    w.registers(frameState());
    const auto bytes = packVertices(kThroughColor, v.data(), u32(v.size()));
    w.vertices(bytes.data(), u32(bytes.size()));
    w.registers({word(GE_CMD_PRIM, (prim << 16) | u32(v.size()))});
    return repeatLast(w, 2, draws);
}
// 999 screen-wide lines a draw, 1,000 draws: 480 fragments a line.
inline dump::Dump lineStrips() {
    std::vector<BuildVertex> v(1000);
    for (size_t i = 0; i < v.size(); ++i) v[i].x = (i & 1) ? 479 : 0, v[i].y = (i & 2) ? 271 : 0, v[i].color = 0xFF00FF00;
    return repeatedDraw(GE_PRIM_LINE_STRIP, v, 1000);
}
// 65,535 points a draw over the screen, 2,000 draws.
inline dump::Dump pointClouds() {
    std::vector<BuildVertex> v(65535);
    for (size_t i = 0; i < v.size(); ++i) v[i].x = float(i % 480), v[i].y = float((i / 480) % 272), v[i].color = ~0u;
    return repeatedDraw(GE_PRIM_POINTS, v, 2000);
}
// A 65,535-vertex strip of one-pixel triangles, 1,000 draws.
inline dump::Dump tinyTriangleStrips() {
    std::vector<BuildVertex> v(65535);
    for (size_t i = 0; i < v.size(); ++i) {
        v[i].x = float((i / 2) % 400) + float(i & 1) * 0.5f;
        v[i].y = float((i / 800) % 200) + float(i & 1);
        v[i].color = 0xFF0000FF;
    }
    return repeatedDraw(GE_PRIM_TRIANGLE_STRIP, v, 1000);
}
// 32,767 2×2 rectangles a draw, 2,000 draws.
inline dump::Dump smallRectangles() {
    std::vector<BuildVertex> v(65534);
    for (size_t i = 0; i < v.size(); ++i) {
        v[i].x = float((i / 2) % 470) + float(i & 1) * 2;
        v[i].y = float((i / 940) % 270) + float(i & 1) * 2;
        v[i].color = ~0u;
    }
    return repeatedDraw(GE_PRIM_RECTANGLES, v, 2000);
}

struct Named {
    const char* name;
    std::function<dump::Dump()> make;
};
inline std::vector<Named> all() {
    return {{"rectangle_loop", rectangleLoop}, {"self_jumps", selfJumps},
            {"shared_framebuf_payload", sharedFramebufPayload}, {"huge_fan", hugeFan},
            {"patch_at_the_cap", patchAtTheCap},
            {"shared_registers_payload", sharedRegistersPayload},
            {"shared_registers_block", sharedRegistersBlock},
            {"shared_registers_rewrites", sharedRegistersRewrites},
            {"sliding_registers_payloads", slidingRegistersPayloads},
            {"shared_vertices_payload", sharedVerticesPayload},
            {"shared_indices_payload", sharedIndicesPayload},
            {"shared_texture_payload", sharedTexturePayload},
            {"shared_clut_payload", sharedClutPayload},
            {"shared_vram_clut_payload", sharedVramClutPayload},
            {"shared_transfersrc_payload", sharedTransferSrcPayload},
            {"shared_memset", sharedMemset},
            {"shared_memcpy_payload", sharedMemcpyPayload},
            {"shared_display", sharedDisplay},
            {"shared_edramtrans", sharedEdramTrans},
            {"shared_clutaddr", sharedClutAddr},
            {"shared_init_payload", sharedInitPayload},
            {"shared_framebuf_payload_many", sharedFramebufPayloadMany},
            {"line_strips", lineStrips},
            {"point_clouds", pointClouds},
            {"tiny_triangle_strips", tinyTriangleStrips},
            {"small_rectangles", smallRectangles}};
}

}  // namespace ge::hostile
