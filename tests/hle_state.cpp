// SPDX-License-Identifier: MIT
// Field accessors, vertex layout, context layout and memory (docs/ge-rules.md §1, §3, §5, §7).
#include <gtest/gtest.h>

#include "hle/disasm.h"
#include "hle/ge_state.h"
#include "hle/memory.h"

using namespace ge;

namespace {

u32 W(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

TEST(Fields, AlphaTestFields) {
    GeState st;
    st.regs[GE_CMD_ATEST] = W(GE_CMD_ATEST, (0xF0 << 16) | (0x80 << 8) | 6);
    EXPECT_EQ(st.ATEST_func(), 6u);
    EXPECT_EQ(st.ATEST_ref(), 0x80u);
    EXPECT_EQ(st.ATEST_mask(), 0xF0u);
}

TEST(Fields, SignedLevelBias) {
    GeState st;
    st.regs[GE_CMD_TLEVEL] = W(GE_CMD_TLEVEL, (0xF0 << 16) | 1);  // −16 = −1.0 level
    EXPECT_EQ(st.TLEVEL_mode(), 1u);
    EXPECT_EQ(st.TLEVEL_bias(), -16);
    st.regs[GE_CMD_TLEVEL] = W(GE_CMD_TLEVEL, 0x7F << 16);
    EXPECT_EQ(st.TLEVEL_bias(), 127);
}

TEST(Fields, IndexedFieldsUseTheirOpcodeStride) {
    GeState st;
    st.regs[0x63 + 3 * 2] = W(0x63 + 3 * 2, toFloat24(1.5f));  // LX2
    st.regs[0x65 + 3 * 3] = W(0x65 + 3 * 3, toFloat24(-4.0f));  // LZ3
    st.regs[GE_CMD_TBP5] = W(GE_CMD_TBP5, 0x123450);
    st.regs[GE_CMD_TBW5] = W(GE_CMD_TBW5, 0x090000 | 256);
    st.regs[GE_CMD_LTYPE2] = W(GE_CMD_LTYPE2, (2 << 8) | 1);
    EXPECT_EQ(st.LX_value(2), 1.5f);
    EXPECT_EQ(st.LZ_value(3), -4.0f);
    EXPECT_EQ(st.textureAddr(5), 0x09123450u);
    EXPECT_EQ(st.TBW_width(5), 256u);
    EXPECT_EQ(st.LTYPE_type(2), 2u);
    EXPECT_EQ(st.LTYPE_comp(2), 1u);
}

TEST(Fields, BlendStencilDither) {
    GeState st;
    st.regs[GE_CMD_BLEND] = W(GE_CMD_BLEND, (5 << 8) | (10 << 4) | 3);
    EXPECT_EQ(st.BLEND_a(), 3u);
    EXPECT_EQ(st.BLEND_b(), 10u);
    EXPECT_EQ(st.BLEND_eq(), 5u);
    st.regs[GE_CMD_SOP] = W(GE_CMD_SOP, (5 << 16) | (4 << 8) | 2);
    EXPECT_EQ(st.SOP_sfail(), 2u);
    EXPECT_EQ(st.SOP_zfail(), 4u);
    EXPECT_EQ(st.SOP_zpass(), 5u);
    // SDK default matrix row 0: (−4, 0, −3, 1) → nibbles C, 0, D, 1.
    st.regs[GE_CMD_DTTH1] = W(GE_CMD_DTTH1, 0x1D0C);
    EXPECT_EQ(st.ditherValue(0, 0), -4);
    EXPECT_EQ(st.ditherValue(1, 0), 0);
    EXPECT_EQ(st.ditherValue(2, 0), -3);
    EXPECT_EQ(st.ditherValue(3, 0), 1);
    EXPECT_EQ(st.ditherValue(4, 4), -4);  // wraps every 4 pixels
}

TEST(Fields, BufferAddressesAndWidths) {
    GeState st;
    st.regs[GE_CMD_FBP] = W(GE_CMD_FBP, 0x088000);
    st.regs[GE_CMD_FBW] = W(GE_CMD_FBW, 0x040000 | 512);
    st.regs[GE_CMD_ZBP] = W(GE_CMD_ZBP, 0x110000);
    EXPECT_EQ(st.framebufAddr(), 0x04088000u);
    EXPECT_EQ(st.framebufStride(), 512u);
    EXPECT_EQ(st.depthbufAddr(), 0x04110000u);
    // Texture buffer width alignment (ge-rules.md §6.2): CLUT4 needs multiples of 32; 0 → minimum.
    st.regs[GE_CMD_TPF] = W(GE_CMD_TPF, GE_TFMT_CLUT4);
    st.regs[GE_CMD_TBW0] = W(GE_CMD_TBW0, 40);
    EXPECT_EQ(st.textureBufWidth(0), 32u);
    st.regs[GE_CMD_TBW0] = W(GE_CMD_TBW0, 0);
    EXPECT_EQ(st.textureBufWidth(0), 32u);
    st.regs[GE_CMD_TPF] = W(GE_CMD_TPF, GE_TFMT_8888);
    st.regs[GE_CMD_TBW0] = W(GE_CMD_TBW0, 6);
    EXPECT_EQ(st.textureBufWidth(0), 4u);
    // TSIZE exponents above 9 saturate at 512.
    st.regs[GE_CMD_TSIZE0] = W(GE_CMD_TSIZE0, (3 << 8) | 12);
    EXPECT_EQ(st.textureWidth(0), 512u);
    EXPECT_EQ(st.textureHeight(0), 8u);
}

TEST(Fields, TableCoversEveryDefinedCommandWithArguments) {
    size_t n = 0;
    const GeFieldInfo* f = geFieldTable(&n);
    EXPECT_GT(n, 150u);
    for (size_t i = 0; i < n; ++i) {
        EXPECT_LE(f[i].lsb + f[i].width, 24) << f[i].name;
        for (int k = 0; k < f[i].count; ++k) EXPECT_TRUE(geCmdKnown(u8(f[i].firstOp + k * f[i].stride))) << f[i].name;
    }
}

TEST(Fields, Float24RoundTrip) {
    EXPECT_EQ(float24(toFloat24(1.0f)), 1.0f);
    EXPECT_EQ(toFloat24(1.0f), 0x3F8000u);
    EXPECT_EQ(float24(0x3F8000), 1.0f);
    EXPECT_EQ(toFloat24(-136.0f), 0xC30800u);
}

TEST(Disasm, NamesCommandsAndFields) {
    EXPECT_EQ(disassemble(W(GE_CMD_ATEST, (0xFF << 16) | (0x80 << 8) | 4)), "ATEST func=4 ref=0x80 mask=0xff");
    EXPECT_EQ(disassemble(W(GE_CMD_PRIM, (3 << 16) | 6)), "PRIM count=6 type=3");
    EXPECT_EQ(disassemble(W(GE_CMD_SX, toFloat24(240.0f))), "SX value=240");
    EXPECT_EQ(disassemble(W(0x03, 0x12)), "UNKNOWN_03 0x000012");
    EXPECT_EQ(disassemble(W(GE_CMD_TFLUSH, 0)), "TFLUSH");
    EXPECT_EQ(disassemble(W(GE_CMD_ZTE, 1)), "ZTE on=on");
}

// ---- Vertex layout (ge-rules.md §5.3 worked examples) ----

struct LayoutCase {
    u32 vtype;
    u32 size, stride;
};

TEST(VertexLayout, WorkedExamples) {
    const LayoutCase cases[] = {
        {0x00011D, 16, 16}, {0x008300, 10, 10}, {0x000080, 3, 3}, {0x800116, 12, 12},
        {0x08011D, 16, 48}, {0x0001FF, 36, 36}, {0x00C700, 24, 24},
    };
    for (const auto& c : cases) {
        GeState st;
        st.regs[GE_CMD_VTYPE] = W(GE_CMD_VTYPE, c.vtype);
        EXPECT_EQ(st.vertexSize(), c.size) << std::hex << c.vtype;
        EXPECT_EQ(st.vertexStride(), c.stride) << std::hex << c.vtype;
    }
    VertexLayout l = VertexLayout::fromVtype(0x00011D);
    EXPECT_EQ(l.tcOff, 0);
    EXPECT_EQ(l.colOff, 4);
    EXPECT_EQ(l.posOff, 8);
    l = VertexLayout::fromVtype(0x0001FF);
    EXPECT_EQ(l.colOff, 8);
    EXPECT_EQ(l.nrmOff, 12);
    EXPECT_EQ(l.posOff, 24);
}

// ---- Context (docs/ppdmp.md §5) ----

TEST(Context, LayoutAndRoundTrip) {
    GeState st;
    for (int op = 0; op < 256; ++op) st.regs[op] = W(u8(op), u32(op * 0x10101) & 0xFFFFFF);
    for (int i = 0; i < 96; ++i) st.bone[i] = float(i) * 0.5f;
    for (int i = 0; i < 12; ++i) st.world[i] = float(i) + 100, st.view[i] = -float(i), st.tgen[i] = float(i) * 3;
    for (int i = 0; i < 16; ++i) st.proj[i] = float(i) * 0.25f;
    // The context holds the matrices as the data ports last wrote them (GeState::visibleMtx):
    // here the same values as the drawn ones.
    for (int i = 0; i < 96; ++i) st.visibleMtx[i] = toFloat24(st.bone[i]);
    for (int i = 0; i < 12; ++i) {
        st.visibleMtx[96 + i] = toFloat24(st.world[i]);
        st.visibleMtx[108 + i] = toFloat24(st.view[i]);
        st.visibleMtx[136 + i] = toFloat24(st.tgen[i]);
    }
    for (int i = 0; i < 16; ++i) st.visibleMtx[120 + i] = toFloat24(st.proj[i]);
    st.boneNum = 130;  // stored masked to 7 bits
    st.worldNum = 13;
    st.vertexAddr = 0x08812340;
    st.indexAddr = 0x08812000;
    st.offsetAddr = 0x100;
    u32 ctx[512];
    st.saveContext(ctx);
    EXPECT_EQ(ctx[5], 0x08812340u);
    EXPECT_EQ(ctx[17] >> 24, 0x00u);
    EXPECT_EQ(ctx[17 + 208] >> 24, 0xF9u);  // last saved opcode
    EXPECT_EQ(ctx[226], 0x2A000000u);
    EXPECT_EQ(ctx[323], 0x3A000000u);
    EXPECT_EQ(ctx[336], 0x3C000000u);
    EXPECT_EQ(ctx[349], 0x3E000000u);
    EXPECT_EQ(ctx[366], 0x40000000u);
    EXPECT_EQ(ctx[379], 0x2A000000u | 2);  // 130 & 0x7F
    EXPECT_EQ(ctx[380], 0x3A000000u | 13);
    EXPECT_EQ(ctx[384], 0x0C000000u);
    EXPECT_EQ(ctx[385], 0u);
    GeState back;
    EXPECT_TRUE(back.loadContext(ctx));
    for (u8 op : geContextOpcodes()) EXPECT_EQ(back.regs[op], st.regs[op]) << int(op);
    for (int i = 0; i < 96; ++i) EXPECT_EQ(back.bone[i], st.bone[i]);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(back.proj[i], st.proj[i]);
    EXPECT_EQ(back.worldNum, 13u);
    EXPECT_EQ(back.vertexAddr, st.vertexAddr);
    for (u32 i = 0; i < GeState::kVisibleMtxWords; ++i) EXPECT_EQ(back.visibleMtx[i], st.visibleMtx[i]) << i;
    ctx[300] = 0x12345678;  // wrong opcode inside the bone data
    EXPECT_FALSE(back.loadContext(ctx));
}

// ---- Memory (ge-rules.md §7) ----

TEST(MemoryMap, RegionsAndBounds) {
    Memory mem(32u << 20);
    EXPECT_NE(mem.ptr(0x08000000, 4), nullptr);
    EXPECT_NE(mem.ptr(0x09FFFFFC, 4), nullptr);
    EXPECT_EQ(mem.ptr(0x09FFFFFE, 4), nullptr);  // crosses the end of RAM
    EXPECT_EQ(mem.ptr(0x0A000000, 1), nullptr);  // 32 MiB model
    EXPECT_NE(mem.ptr(0x00010000, 0x4000), nullptr);
    EXPECT_EQ(mem.ptr(0x00013FFF, 2), nullptr);
    EXPECT_EQ(mem.ptr(0x00000000, 1), nullptr);
    // Uncached and kernel views alias.
    mem.write32(0x48800000, 0xCAFEBABE);
    EXPECT_EQ(mem.read32(0x08800000), 0xCAFEBABEu);
    EXPECT_EQ(mem.read32(0x88800000), 0xCAFEBABEu);
    // VRAM and its linear mirror 2.
    mem.write32(0x04000010, 0x11223344);
    EXPECT_EQ(mem.read32(0x04400010), 0x11223344u);
    EXPECT_EQ(mem.ptr(0x041FFFFE, 4), nullptr);  // crosses a mirror boundary
    EXPECT_EQ(mem.validSize(0x041FFFF0, 100), 16u);
    // Wild accesses are counted and read as zero.
    u64 before = mem.badAccesses();
    EXPECT_EQ(mem.read32(0x12345678), 0u);
    mem.write32(0xFFFFFFFC, 1);
    EXPECT_EQ(mem.badAccesses(), before + 2);
    EXPECT_FALSE(mem.write(0x09FFFFF0, "0123456789abcdefXYZ", 19));
    Memory big;
    EXPECT_NE(big.ptr(0x0BFFFFFC, 4), nullptr);  // 64 MiB by default
}

TEST(MemoryMap, EdramMirrorPermutation) {
    Memory mem(1u << 20);
    // Default translation 0x400: linear 0x0000 appears at mirror 1 offset 0x2040 and at mirror 3
    // offset 0x2020 (ge-rules.md §7.3 example).
    EXPECT_EQ(mem.edramTranslation(), 0x400u);
    EXPECT_EQ(mem.linearToMirror(0x0000, 1), 0x2040u);
    EXPECT_EQ(mem.linearToMirror(0x0000, 3), 0x2020u);
    mem.vram()[0] = 0x5A;
    EXPECT_EQ(mem.readMirrored(0x04202040), 0x5A);
    EXPECT_EQ(mem.readMirrored(0x04602020), 0x5A);
    EXPECT_EQ(mem.readMirrored(0x04400000), 0x5A);
    // The mirror-3 map is a permutation: its inverse undoes it everywhere in a 64 KiB block.
    for (u32 i = 0; i < 0x10000; i += 0x35) EXPECT_EQ(mem.mirrorToLinear(mem.linearToMirror(i, 3), 3), i);
    EXPECT_FALSE(mem.setEdramTranslation(0x300));
    EXPECT_TRUE(mem.setEdramTranslation(0));
    EXPECT_EQ(mem.linearToMirror(0x0000, 1), 0x0600u);
    EXPECT_EQ(mem.linearToMirror(0x0000, 3), 0x0600u);
    EXPECT_EQ(mem.linearToMirror(0x0200, 3), 0x0200u);
}

}  // namespace
