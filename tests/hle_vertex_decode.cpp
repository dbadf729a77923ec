// SPDX-License-Identifier: MIT
// Vertex decoding (manual §6, §7; docs/ge-rules.md §5). Expected values computed by hand from the
// component tables of ge-rules.md §5.2–§5.5.
#include <gtest/gtest.h>

#include "hle/vertex_decoder.h"

using namespace ge;

namespace {

constexpr u32 kV = 0x08200000, kI = 0x08300000;

void set(GeState& st, u8 op, u32 arg) { st.regs[op] = (u32(op) << 24) | (arg & 0xFFFFFF); }
void setF(GeState& st, u8 op, float f) { set(st, op, toFloat24(f)); }
void writeF(Memory& mem, u32 addr, float f) {
    u32 bits;
    std::memcpy(&bits, &f, 4);
    mem.write32(addr, bits);
}

// VTYPE builders (SDK macro layout, ge-rules.md §5.1).
constexpr u32 TT(u32 v) { return v; }
constexpr u32 CT(u32 v) { return v << 2; }
constexpr u32 NT(u32 v) { return v << 5; }
constexpr u32 VT(u32 v) { return v << 7; }
constexpr u32 WT(u32 v) { return v << 9; }
constexpr u32 IT(u32 v) { return v << 11; }
constexpr u32 WC(u32 n) { return (n - 1) << 14; }
constexpr u32 MC(u32 n) { return (n - 1) << 18; }
constexpr u32 THROUGH = 1u << 23;

TEST(VertexDecode, WorkedLayoutsOfSection5_3) {
    Memory mem;
    GeState st;
    struct Case {
        u32 vtype, size, stride, tc, col, nrm, pos, w;
    };
    const Case cases[] = {
        {0x00011D, 16, 16, 0, 4, 0, 8, 0},    // 6.4.1: S,T u8; C 8888; XYZ s16
        {0x008300, 10, 10, 0, 0, 0, 4, 0},    // 6.4.2: 3 u8 weights; XYZ s16
        {0x000080, 3, 3, 0, 0, 0, 0, 0},      // 6.4.3: XYZ s8
        {0x800116, 12, 12, 0, 4, 0, 6, 0},    // 6.4.4: through, U,V u16; C 5551; XYZ s16
        {0x08011D, 16, 48, 0, 4, 0, 8, 0},    // 7.1: 3 morph copies of 6.4.1
        {0x0001FF, 36, 36, 0, 8, 12, 24, 0},  // float UV, 8888, float normal, float XYZ
        {0x00C700, 24, 24, 0, 0, 0, 16, 0},   // 4 float weights, XYZ s16
    };
    for (const Case& c : cases) {
        VertexReader r(mem, st, c.vtype);
        EXPECT_EQ(r.layout().size, c.size) << std::hex << c.vtype;
        EXPECT_EQ(r.stride(), c.stride) << std::hex << c.vtype;
        if (r.hasUV()) {
            EXPECT_EQ(r.layout().tcOff, c.tc);
        }
        if (r.hasColor()) {
            EXPECT_EQ(r.layout().colOff, c.col) << std::hex << c.vtype;
        }
        if (r.hasNormal()) {
            EXPECT_EQ(r.layout().nrmOff, c.nrm);
        }
        EXPECT_EQ(r.layout().posOff, c.pos) << std::hex << c.vtype;
    }
    VertexReader r(mem, st, 0x08C700);
    EXPECT_EQ(r.weightCount(), 4u);
    EXPECT_EQ(r.morphCount(), 3u);
    EXPECT_TRUE(r.hasWeights());
    EXPECT_FALSE(r.through());
    EXPECT_TRUE(VertexReader(mem, st, 0x800116).through());
}

TEST(VertexDecode, TextureCoordinateFormats) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    // TT=1 u8: /128 in both modes.
    mem.write8(kV, 0x80);
    mem.write8(kV + 1, 0x40);
    ASSERT_TRUE(VertexReader(mem, st, TT(1) | VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.uv[0], 1.0f);
    EXPECT_EQ(v.uv[1], 0.5f);
    ASSERT_TRUE(VertexReader(mem, st, TT(1) | VT(2) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.uv[0], 1.0f);
    // TT=2 u16: /32768 in transform mode, texels in through mode.
    mem.write16(kV, 0x8000);
    mem.write16(kV + 2, 0xFFFF);
    ASSERT_TRUE(VertexReader(mem, st, TT(2) | VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.uv[0], 1.0f);
    EXPECT_EQ(v.uv[1], 65535.0f / 32768.0f);
    ASSERT_TRUE(VertexReader(mem, st, TT(2) | VT(2) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.uv[0], 32768.0f);
    EXPECT_EQ(v.uv[1], 65535.0f);
    // TT=3 float as is.
    writeF(mem, kV, 1.5f);
    writeF(mem, kV + 4, -2.25f);
    ASSERT_TRUE(VertexReader(mem, st, TT(3) | VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.uv[0], 1.5f);
    EXPECT_EQ(v.uv[1], -2.25f);
}

TEST(VertexDecode, ColourFormats) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    auto col = [&](u32 vtype) {
        EXPECT_TRUE(VertexReader(mem, st, vtype).read(kV, 0, v));
        return std::array<u8, 4>{v.color[0], v.color[1], v.color[2], v.color[3]};
    };
    mem.write16(kV, 0xF800);  // 5650: blue
    EXPECT_EQ(col(CT(4) | VT(2)), (std::array<u8, 4>{0, 0, 255, 255}));
    mem.write16(kV, 0x801F);  // 5551: red + alpha
    EXPECT_EQ(col(CT(5) | VT(2)), (std::array<u8, 4>{255, 0, 0, 255}));
    mem.write16(kV, 0x1234);  // 4444
    EXPECT_EQ(col(CT(6) | VT(2)), (std::array<u8, 4>{0x44, 0x33, 0x22, 0x11}));
    mem.write32(kV, 0x44332211);  // 8888: bytes R, G, B, A
    EXPECT_EQ(col(CT(7) | VT(2)), (std::array<u8, 4>{0x11, 0x22, 0x33, 0x44}));
    // No colour: MAC (RGB) + MAA.
    set(st, GE_CMD_MAC, 0x112233);
    set(st, GE_CMD_MAA, 0x99);
    EXPECT_EQ(col(VT(2)), (std::array<u8, 4>{0x33, 0x22, 0x11, 0x99}));
    // CT 1–3 are invalid: no bytes, no colour.
    for (u32 ct = 1; ct <= 3; ++ct) {
        VertexReader r(mem, st, CT(ct) | VT(2));
        EXPECT_FALSE(r.hasColor());
        EXPECT_EQ(r.layout().size, 6u);
        EXPECT_EQ(col(CT(ct) | VT(2)), (std::array<u8, 4>{0x33, 0x22, 0x11, 0x99}));
    }
}

TEST(VertexDecode, NormalFormats) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    mem.write8(kV, 0x80);
    mem.write8(kV + 1, 0x40);
    mem.write8(kV + 2, 0x7F);
    ASSERT_TRUE(VertexReader(mem, st, NT(1) | VT(1)).read(kV, 0, v));
    EXPECT_EQ(v.nrm[0], -1.0f);
    EXPECT_EQ(v.nrm[1], 0.5f);
    EXPECT_EQ(v.nrm[2], 127.0f / 128.0f);
    mem.write16(kV, 0x8000);
    mem.write16(kV + 2, 0x4000);
    mem.write16(kV + 4, 0xC000);
    ASSERT_TRUE(VertexReader(mem, st, NT(2) | VT(2)).read(kV, 0, v));
    EXPECT_EQ(v.nrm[0], -1.0f);
    EXPECT_EQ(v.nrm[1], 0.5f);
    EXPECT_EQ(v.nrm[2], -0.5f);
    writeF(mem, kV, 3.0f);
    writeF(mem, kV + 4, 0.0f);
    writeF(mem, kV + 8, -7.5f);
    ASSERT_TRUE(VertexReader(mem, st, NT(3) | VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.nrm[0], 3.0f);
    EXPECT_EQ(v.nrm[2], -7.5f);
}

TEST(VertexDecode, PositionFormatsTransformAndThrough) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    mem.write8(kV, 0x7F);
    mem.write8(kV + 1, 0x80);
    mem.write8(kV + 2, 0x01);
    ASSERT_TRUE(VertexReader(mem, st, VT(1)).read(kV, 0, v));
    EXPECT_EQ(v.pos[0], 127.0f / 128.0f);
    EXPECT_EQ(v.pos[1], -1.0f);
    EXPECT_EQ(v.pos[2], 1.0f / 128.0f);
    // Through mode: s8 positions decode as 0 (observed: SWR).
    ASSERT_TRUE(VertexReader(mem, st, VT(1) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.pos[0], 0.0f);
    EXPECT_EQ(v.pos[1], 0.0f);
    EXPECT_EQ(v.pos[2], 0.0f);
    // s16: /32768 in transform mode; through: signed X, Y, unsigned Z.
    mem.write16(kV, u16(-5));
    mem.write16(kV + 2, 10);
    mem.write16(kV + 4, 0xFFFF);
    ASSERT_TRUE(VertexReader(mem, st, VT(2) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.pos[0], -5.0f);
    EXPECT_EQ(v.pos[1], 10.0f);
    EXPECT_EQ(v.pos[2], 65535.0f);
    ASSERT_TRUE(VertexReader(mem, st, VT(2)).read(kV, 0, v));
    EXPECT_EQ(v.pos[0], -5.0f / 32768.0f);
    EXPECT_EQ(v.pos[2], -1.0f / 32768.0f);
    // Float; through-mode Z is clamped to 0–65535.
    writeF(mem, kV, 1.25f);
    writeF(mem, kV + 4, -3.0f);
    writeF(mem, kV + 8, 70000.0f);
    ASSERT_TRUE(VertexReader(mem, st, VT(3) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.pos[0], 1.25f);
    EXPECT_EQ(v.pos[1], -3.0f);
    EXPECT_EQ(v.pos[2], 65535.0f);
    writeF(mem, kV + 8, -1.0f);
    ASSERT_TRUE(VertexReader(mem, st, VT(3) | THROUGH).read(kV, 0, v));
    EXPECT_EQ(v.pos[2], 0.0f);
    ASSERT_TRUE(VertexReader(mem, st, VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.pos[2], -1.0f);
    // VT = 0: no position (3 bytes reserved).
    VertexReader none(mem, st, 0);
    EXPECT_FALSE(none.hasPosition());
    EXPECT_EQ(none.stride(), 3u);
}

TEST(VertexDecode, WeightFormats) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    mem.write8(kV, 0x80);
    mem.write8(kV + 1, 0x20);
    ASSERT_TRUE(VertexReader(mem, st, WT(1) | WC(2) | VT(1)).read(kV, 0, v));
    EXPECT_EQ(v.weights[0], 1.0f);
    EXPECT_EQ(v.weights[1], 0.25f);
    EXPECT_EQ(v.weights[2], 0.0f);
    mem.write16(kV, 0x4000);
    ASSERT_TRUE(VertexReader(mem, st, WT(2) | WC(1) | VT(2)).read(kV, 0, v));
    EXPECT_EQ(v.weights[0], 0.5f);
    writeF(mem, kV, 0.75f);
    ASSERT_TRUE(VertexReader(mem, st, WT(3) | WC(1) | VT(3)).read(kV, 0, v));
    EXPECT_EQ(v.weights[0], 0.75f);
}

TEST(VertexDecode, MorphWithThreeWeights) {
    Memory mem;
    GeState st;
    setF(st, GE_CMD_WEIGHT0, 0.5f);
    setF(st, GE_CMD_WEIGHT1, 0.25f);
    setF(st, GE_CMD_WEIGHT2, 0.25f);
    // 8888 colour + float XYZ = 16 bytes per copy, 3 copies.
    const u32 vtype = CT(7) | VT(3) | MC(3);
    const float xs[3] = {1.0f, 2.0f, 4.0f};
    const u8 reds[3] = {100, 200, 40};
    for (u32 m = 0; m < 3; ++m) {
        const u32 a = kV + 48 + 16 * m;  // vertex 1
        mem.write32(a, 0xFF000000u | reds[m]);
        writeF(mem, a + 4, xs[m]);
        writeF(mem, a + 8, -xs[m]);
        writeF(mem, a + 12, 8.0f);
    }
    VertexReader r(mem, st, vtype);
    EXPECT_EQ(r.stride(), 48u);
    DecodedVertex v;
    ASSERT_TRUE(r.read(kV, 1, v));
    EXPECT_EQ(v.pos[0], 2.0f);   // 0.5·1 + 0.25·2 + 0.25·4
    EXPECT_EQ(v.pos[1], -2.0f);
    EXPECT_EQ(v.pos[2], 8.0f);
    EXPECT_EQ(v.color[0], 110);  // 50 + 50 + 10
    EXPECT_EQ(v.color[3], 255);
    // Through mode: no morphing, the first copy only.
    ASSERT_TRUE(VertexReader(mem, st, vtype | THROUGH).read(kV, 1, v));
    EXPECT_EQ(v.pos[0], 1.0f);
    EXPECT_EQ(v.color[0], 100);
}

TEST(VertexDecode, SkinningWithTwoBones) {
    Memory mem;
    GeState st;
    // Bone 0: identity + translation (1, 0, 0). Bone 1: uniform scale 2.
    // Element k is row k%3, column k/3; column 3 is the translation (ge-rules.md §3.4).
    float* b0 = st.bone;
    float* b1 = st.bone + 12;
    b0[0] = b0[4] = b0[8] = 1.0f;
    b0[9] = 1.0f;
    b1[0] = b1[4] = b1[8] = 2.0f;
    const u32 vtype = WT(3) | WC(2) | NT(3) | VT(3);
    writeF(mem, kV, 0.25f);
    writeF(mem, kV + 4, 0.75f);
    writeF(mem, kV + 8, 0.0f);  // normal (0, 0, 1)
    writeF(mem, kV + 12, 0.0f);
    writeF(mem, kV + 16, 1.0f);
    writeF(mem, kV + 20, 1.0f);  // position (1, 2, 3)
    writeF(mem, kV + 24, 2.0f);
    writeF(mem, kV + 28, 3.0f);
    std::vector<DecodedVertex> out;
    ASSERT_TRUE(decodeDrawVertices(mem, st, vtype, kV, 0, 1, out));
    // 0.25·(2, 2, 3) + 0.75·(2, 4, 6) = (2, 3.5, 5.25); normal 0.25·1 + 0.75·2 = 1.75.
    EXPECT_EQ(out[0].pos[0], 2.0f);
    EXPECT_EQ(out[0].pos[1], 3.5f);
    EXPECT_EQ(out[0].pos[2], 5.25f);
    EXPECT_EQ(out[0].nrm[0], 0.0f);
    EXPECT_EQ(out[0].nrm[2], 1.75f);
    // Off-axis check of the element order: bone 0 with m3 = 1 (row 0, column 1) adds y to x.
    DecodedVertex v;
    ASSERT_TRUE(VertexReader(mem, st, vtype).read(kV, 0, v));
    b0[3] = 1.0f;
    applySkinning(st, vtype, v);
    EXPECT_EQ(v.pos[0], 0.25f * 4.0f + 0.75f * 2.0f);
    // Through mode is never skinned.
    ASSERT_TRUE(VertexReader(mem, st, vtype | THROUGH).read(kV, 0, v));
    applySkinning(st, vtype | THROUGH, v);
    EXPECT_EQ(v.pos[0], 1.0f);
}

TEST(VertexDecode, IndexFormats) {
    Memory mem;
    GeState st;
    std::vector<u32> idx;
    mem.write8(kI, 7);
    mem.write8(kI + 1, 200);
    ASSERT_TRUE(VertexReader(mem, st, IT(1) | VT(1)).readIndices(kI, 2, idx));
    EXPECT_EQ(idx, (std::vector<u32>{7, 200}));
    mem.write16(kI, 0xBEEF);
    mem.write16(kI + 2, 3);
    ASSERT_TRUE(VertexReader(mem, st, IT(2) | VT(1)).readIndices(kI, 2, idx));
    EXPECT_EQ(idx, (std::vector<u32>{0xBEEF, 3}));
    mem.write32(kI, 0x00012345);
    ASSERT_TRUE(VertexReader(mem, st, IT(3) | VT(1)).readIndices(kI, 1, idx));
    EXPECT_EQ(idx, (std::vector<u32>{0x12345}));
    ASSERT_TRUE(VertexReader(mem, st, VT(1)).readIndices(0, 4, idx));  // IT = 0: 0..count-1
    EXPECT_EQ(idx, (std::vector<u32>{0, 1, 2, 3}));
    EXPECT_EQ(VertexReader(mem, st, IT(3)).indexSize(), 4u);
}

TEST(VertexDecode, DrawVerticesResolveIndices) {
    Memory mem;
    GeState st;
    const u32 vtype = IT(2) | VT(2);  // 6-byte vertices
    for (u32 i = 0; i < 3; ++i) mem.write16(kV + 6 * i, u16(1000 * (i + 1)));
    const u16 ids[4] = {2, 0, 2, 1};
    mem.write(kI, ids, sizeof ids);
    std::vector<DecodedVertex> out;
    ASSERT_TRUE(decodeDrawVertices(mem, st, vtype, kV, kI, 4, out));
    ASSERT_EQ(out.size(), 4u);
    EXPECT_EQ(out[0].pos[0], 3000.0f / 32768.0f);
    EXPECT_EQ(out[1].pos[0], 1000.0f / 32768.0f);
    EXPECT_EQ(out[2].pos[0], 3000.0f / 32768.0f);
    EXPECT_EQ(out[3].pos[0], 2000.0f / 32768.0f);
    // Sparse 32-bit indices take the distinct-index path.
    const u32 vt32 = IT(3) | VT(1);
    mem.write8(kV + 3 * 1000000, 0x40);
    const u32 ids32[3] = {1000000, 0, 1000000};
    mem.write(kI, ids32, sizeof ids32);
    mem.write8(kV, 0x20);
    ASSERT_TRUE(decodeDrawVertices(mem, st, vt32, kV, kI, 3, out));
    EXPECT_EQ(out[0].pos[0], 0.5f);
    EXPECT_EQ(out[1].pos[0], 0.25f);
    EXPECT_EQ(out[2].pos[0], 0.5f);
}

TEST(VertexDecode, BadAddressesFail) {
    Memory mem;
    GeState st;
    DecodedVertex v;
    v.pos[0] = 9.0f;
    EXPECT_FALSE(VertexReader(mem, st, VT(3)).read(0x00000100, 0, v));
    EXPECT_EQ(v.pos[0], 0.0f);  // zeroed
    // Index arithmetic past 4 GiB must not wrap into valid memory.
    EXPECT_FALSE(VertexReader(mem, st, VT(3) | MC(8)).read(kV, 0xFFFFFFFFu, v));
    // The last vertex straddling the end of RAM.
    const u32 end = Memory::kRamBase + mem.ramSize();
    EXPECT_FALSE(VertexReader(mem, st, VT(3)).read(end - 8, 0, v));
    EXPECT_TRUE(VertexReader(mem, st, VT(3)).read(end - 12, 0, v));

    std::vector<DecodedVertex> out;
    std::string err;
    EXPECT_FALSE(decodeDrawVertices(mem, st, VT(3), 0x00000100, 0, 3, out, &err));
    EXPECT_FALSE(err.empty());
    err.clear();
    EXPECT_FALSE(decodeDrawVertices(mem, st, IT(2) | VT(3), kV, 0x00000100, 3, out, &err));
    EXPECT_FALSE(err.empty());
    std::vector<u32> idx;
    EXPECT_FALSE(VertexReader(mem, st, IT(3)).readIndices(end - 4, 2, idx));
    EXPECT_TRUE(decodeDrawVertices(mem, st, VT(3), kV, 0, 0, out));
    EXPECT_TRUE(out.empty());
}

}  // namespace
