// SPDX-License-Identifier: MIT
// ListBuilder (hle/list_builder.h): exact command words for known calls (expected values worked
// out by hand from docs/ge-rules.md §3 and the SDK conventions it records), vertex packing against
// the manual's layout examples, execution of built lists on the GeEngine, the DumpRecorder's
// record order, record-for-record equivalence of direct execution and dump replay, and the
// project's own scene dumps in dumps/.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/ge_engine.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

constexpr u32 W(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

std::vector<u32> tail(const ListBuilder& b, size_t from) {
    return std::vector<u32>(b.words().begin() + long(from), b.words().end());
}

// ---------------------------------------------------------------------------------------------
// Exact words

TEST(ListBuilder, ViewportMatchesSdkConvention) {
    ListBuilder b;
    b.viewport(2048, 2048, 480, 272);
    // 240.0f = 0x43700000, −136.0f = 0xC3080000, 2048.0f = 0x45000000 (float24 = top 24 bits).
    const std::vector<u32> want = {0x42437000, 0x43C30800, 0x45450000, 0x46450000};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, OffsetDepthRangeScissorRegion) {
    ListBuilder b;
    b.offset(2048 - 240, 2048 - 136);
    b.depthRange(65535, 0);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    // OFFSETX 1808<<4 = 0x7100, OFFSETY 1912<<4 = 0x7780. depthRange(65535, 0): mid 32767,
    // SZ = 32767 − 65535 = −32768 (0xC7000000), TZ = 32767 (0x46FFFE00). Scissor/region end
    // inclusive: 479 | 271<<10 = 0x043DDF.
    const std::vector<u32> want = {0x4C007100, 0x4D007780, 0x44C70000, 0x4746FFFE, 0xD6000000, 0xD700FFFF,
                                   0xD4000000, 0xD5043DDF, 0x15000000, 0x16043DDF};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, FinishEndSignalCallJump) {
    ListBuilder b;
    b.finish();
    b.end();
    b.signal(0x10, 0x0880, 0x1234);
    b.call(0x08812340);
    b.jump(0x09ABCDE0);
    b.ret();
    const std::vector<u32> want = {0x0F000000, 0x0C000000, 0x0C000000, 0x0E100880, 0x0C001234,
                                   0x10080000, 0x0A812340, 0x10090000, 0x08ABCDE0, 0x0B000000};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, ClearEmitsCmodeAroundThroughRectangles) {
    Memory mem;
    ListBuilder b(&mem);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0x11223344, 0x5566, 0x77);
    // sceGuClear: CMODE (flags<<8 | 1) = 0x501, VTYPE 8888 colour | 16-bit position | through =
    // 0x80011C, BASE/VADR of the arena start, PRIM RECTANGLES with 480/64 → 8 columns = 16
    // vertices, CMODE 0.
    const std::vector<u32> want = {0xD3000501, 0x1280011C, 0x10080000, 0x01800000, 0x04060010, 0xD3000000};
    ASSERT_EQ(b.words(), want);
    // Vertex 0: colour (0x223344 | stencil<<24), x 0, y 0, z depth; vertex 15: x 480, y 272.
    // Layout: colour at 0, position at 4, size 12 (ge-rules.md §5.2).
    const u32 v = 0x08800000;
    EXPECT_EQ(mem.read32(v), 0x77223344u);
    EXPECT_EQ(mem.read16(v + 4), 0);
    EXPECT_EQ(mem.read16(v + 6), 0);
    EXPECT_EQ(mem.read16(v + 8), 0x5566);
    EXPECT_EQ(mem.read16(v + 12 + 4), 64);   // first rectangle's right edge
    EXPECT_EQ(mem.read16(v + 12 + 6), 272);
    EXPECT_EQ(mem.read16(v + 15 * 12 + 4), 480);
    EXPECT_EQ(mem.read16(v + 14 * 12 + 4), 448);
}

TEST(ListBuilder, ClearFollowsTheScissor) {
    Memory mem;
    ListBuilder b(&mem);
    b.scissor(0, 0, 100, 50);
    const size_t n = b.words().size();
    b.clear(CLEAR_COLOR, 0, 0);
    // 100 px → 2 columns (64 + 36) → 4 vertices.
    EXPECT_EQ(tail(b, n)[4], 0x04060004u);
    EXPECT_EQ(mem.read16(0x08800000 + 3 * 12 + 4), 100);
    EXPECT_EQ(mem.read16(0x08800000 + 3 * 12 + 6), 50);
}

TEST(ListBuilder, BuffersTexturesAndClut) {
    ListBuilder b;
    b.drawBuffer(GE_FORMAT_8888, 0x88000, 512);
    b.depthBuffer(0x110000, 512);
    b.setTexture(0, 0x08901230, 64, 32, 64);
    b.setTexture(3, 0x04154000, 128, 128, 128);
    b.texMode(GE_TFMT_CLUT8, 2, true, true);
    b.clutMode(GE_FORMAT_5551, 4, 0x3F, 2);
    b.clutLoad(0x09123450, 4);
    const std::vector<u32> want = {
        0xD2000003, 0x9C088000, 0x9D000200, 0x9E110000, 0x9F000200,
        // TBP low 24 bits, TBW (addr bits 27..24 in 19..16) | bufw, TSIZE (log2 h << 8 | log2 w), TFLUSH.
        0xA0901230, 0xA8080040, 0xB8000506, 0xCB000000,
        0xA3154000, 0xAB040080, 0xBB000707, 0xCB000000,
        // TMODE max level 2, multi-CLUT, swizzle; TPF 5; TFLUSH.
        0xC2020101, 0xC3000005, 0xCB000000,
        // CLUT start 2 <<16 | mask 0x3F <<8 | shift 4 <<2 | format 1.
        0xC5023F11,
        0xB0123450, 0xB1090000, 0xC4000004};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, PixelOperations) {
    ListBuilder b;
    b.blendFunc(1, 2, 3, 0x112233, 0x445566);
    b.alphaFunc(6, 0x80, 0xFE);
    b.stencilFunc(2, 0x30, 0xF0);
    b.stencilOp(1, 4, 2);
    b.depthFunc(7);
    b.depthMask(true);
    b.logicOp(6);
    b.colorFunc(3, 0x00FF00, 0xF0F0F0);
    b.pixelMask(0x00FF00, 0x0F);
    b.enable(GE_CMD_ABE, true);
    b.texFunc(2, true, true);
    b.texFilter(7, 1);
    b.texWrap(true, false);
    b.texLevelMode(1, -1.5f);
    const std::vector<u32> want = {0xDF000132, 0xE0112233, 0xE1445566, 0xDBFE8006, 0xDCF03002, 0xDD020401,
                                   0xDE000007, 0xE7000001, 0xE6000006, 0xD8000003, 0xD900FF00, 0xDAF0F0F0,
                                   0xE800FF00, 0xE900000F, 0x21000001, 0xC9010102, 0xC6000107, 0xC7000001,
                                   // −1.5·16 = −24 = 0xE8 in bits 23..16, mode 1.
                                   0xC8E80001};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, DitherMatrixRows) {
    ListBuilder b;
    // The SDK's default matrix (ge-rules.md §3.10).
    const int m[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
    b.setDither(m);
    // Row 0: −4 → 0xC, 0, −3 → 0xD, 1 → nibbles 0..3 = 0x1D0C.
    const std::vector<u32> want = {0xE2001D0C, 0xE300F3E2, 0xE4000C1D, 0xE500E2F3};
    EXPECT_EQ(b.words(), want);
    GeState st;
    for (u32 w : b.words()) st.regs[w >> 24] = w;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(st.ditherValue(x, y), m[y * 4 + x]) << x << "," << y;
}

TEST(ListBuilder, MatricesInGeElementOrder) {
    ListBuilder b;
    float m[16];
    for (int i = 0; i < 16; ++i) m[i] = float(i + 1);  // column-major: column c = m[4c..4c+3]
    b.setMatrix(GeMatrix::World, m);
    b.setMatrix(GeMatrix::Proj, m);
    const float bone[12] = {0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 1, 2, 3};
    b.setBoneMatrix(3, bone);
    const auto& w = b.words();
    ASSERT_EQ(w.size(), 13u + 17u + 13u);
    EXPECT_EQ(w[0], 0x3A000000u);
    // 3×4: rows 0..2 of each column: 1 2 3, 5 6 7, 9 10 11, 13 14 15.
    const float want3x4[12] = {1, 2, 3, 5, 6, 7, 9, 10, 11, 13, 14, 15};
    for (int k = 0; k < 12; ++k) EXPECT_EQ(w[1 + k], W(GE_CMD_WORLDD, toFloat24(want3x4[k]))) << k;
    EXPECT_EQ(w[13], 0x3E000000u);
    for (int k = 0; k < 16; ++k) EXPECT_EQ(w[14 + k], W(GE_CMD_PROJD, toFloat24(float(k + 1)))) << k;
    EXPECT_EQ(w[30], 0x2A000024u);  // BONEN 36 = 12·3
    EXPECT_EQ(w[31], 0x2B3F0000u);  // 0.5f = 0x3F000000
    EXPECT_EQ(w[42], 0x2B404000u);  // 3.0f = 0x40400000
}

TEST(ListBuilder, LightsMaterialFog) {
    ListBuilder b;
    const float pos[3] = {1.f, -2.f, 0.5f};
    b.light(2, 1, 1, pos);
    b.lightColor(2, LIGHT_DIFFUSE | LIGHT_SPECULAR, 0x102030);
    b.lightAtt(1, 1.f, 0.f, 0.25f);
    const float dir[3] = {0.f, -1.f, 0.f};
    b.lightSpot(3, dir, 2.f, 0.5f);
    b.ambient(0x80112233);
    b.materialAmbient(0x40FFEEDD);
    b.fog(1.f, 5.f, 0xABCDEF);
    const std::vector<u32> want = {
        // LX2 0x69, LY2 0x6A, LZ2 0x6B, LTYPE2 (point << 8 | 1).
        0x693F8000, 0x6AC00000, 0x6B3F0000, 0x61000101,
        // LDC2 0x96, LSC2 0x97.
        0x96102030, 0x97102030,
        // LKA1 0x7E, LKB1 0x7F, LKC1 0x80.
        0x7E3F8000, 0x7F000000, 0x803E8000,
        // LDX3 0x78.., LKS3 0x8A, LKO3 0x8E.
        0x78000000, 0x79BF8000, 0x7A000000, 0x8A400000, 0x8E3F0000,
        0x5C112233, 0x5D000080, 0x55FFEEDD, 0x58000040,
        // FC, FOG1 = far 5.0, FOG2 = 1/(5 − 1) = 0.25.
        0xCFABCDEF, 0xCD40A000, 0xCE3E8000};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, DrawCallsAndPatches) {
    Memory mem;
    ListBuilder b(&mem);
    b.drawArray(GE_PRIM_TRIANGLES, 0x11C, 6, 0x0A000100, 0x08812340);
    b.drawArray(GE_PRIM_KEEP_PREVIOUS, 0, 3, 0, 0);
    b.drawBezier(0x183, 7, 4, 0, 0x08900000);
    b.drawSpline(0x180, 6, 5, 3, 1, 0x08900400, 0x08900000);
    b.patchDivide(10, 8);
    const std::vector<u32> want = {0x1200011C, 0x100A0000, 0x02000100, 0x10080000, 0x01812340, 0x04030006,
                                   0x04070003,
                                   0x12000183, 0x10080000, 0x01900000, 0x05000407,
                                   0x12000180, 0x10080000, 0x02900400, 0x10080000, 0x01900000, 0x06070506,
                                   0x3600080A};
    EXPECT_EQ(b.words(), want);
}

TEST(ListBuilder, CopyImageAsSdk) {
    ListBuilder b;
    b.copyImage(GE_FORMAT_8888, 8, 4, 48, 40, 64, 0x08912340, 400, 220, 512, 0x04000000);
    const std::vector<u32> want = {0xB2912340, 0xB3080040, 0xEB001008, 0xB4000000, 0xB5040200,
                                   0xEC037190, 0xEE009C2F, 0xEA000001};
    EXPECT_EQ(b.words(), want);
    ListBuilder c;
    c.copyImage(GE_FORMAT_565, 0, 0, 1, 1, 8, 0x04000000, 0, 0, 8, 0x04100000);
    EXPECT_EQ(c.words().back(), 0xEA000000u);  // 16-bit pixels
}

// ---------------------------------------------------------------------------------------------
// Arena and vertex packing

TEST(ListBuilder, ArenaAlignsAndRefusesOverflow) {
    Memory mem(1u << 24);  // 16 MiB: RAM ends at 0x09000000
    ListBuilder b(&mem);
    const u8 data[3] = {1, 2, 3};
    EXPECT_EQ(b.place(data, 3), 0x08800000u);
    EXPECT_EQ(b.place(data, 3), 0x08800010u);
    EXPECT_EQ(b.place(data, 3, 4), 0x08800014u);
    EXPECT_EQ(mem.read8(0x08800012), 3);
    EXPECT_EQ(b.alloc(0x01000000), 0u);           // past the end of RAM
    EXPECT_EQ(b.alloc(16, 3), 0u);                // not a power of two
    ListBuilder none;
    EXPECT_EQ(none.place(data, 3), 0u);           // no memory
    EXPECT_FALSE(none.upload(0x04000000, data, 3));
    EXPECT_FALSE(b.upload(0x02000000, data, 3));  // unmapped address
}

TEST(ListBuilder, PackVertexManualExamples) {
    // Manual §6.4.1: S,T u8; C 8888; XYZ s16 → 16 bytes: S 0, T 1, C 4, X 8, Y 10, Z 12.
    BuildVertex v;
    v.u = 0.5f;
    v.v = 1.0f;
    v.color = 0x80402010;
    v.x = 0.5f;
    v.y = -0.25f;
    v.z = 2.f;  // saturates to 32767
    u8 out[16];
    packVertex(0x00011D, v, out);
    EXPECT_EQ(out[0], 64);
    EXPECT_EQ(out[1], 128);
    EXPECT_EQ(readLE32(out + 4), 0x80402010u);
    EXPECT_EQ(readLE16(out + 8), 16384);
    EXPECT_EQ(s16(readLE16(out + 10)), -8192);
    EXPECT_EQ(readLE16(out + 12), 32767);
    EXPECT_EQ(readLE16(out + 14), 0);  // padding zeroed

    // manual §6.4.4 (through): U,V u16 texels; C 5551; XYZ s16 → U 0, V 2, C 4, X 6, Y 8, Z 10.
    BuildVertex t;
    t.u = 300;
    t.v = 7;
    t.color = 0xFF0000FF;  // opaque red
    t.x = -10;
    t.y = 272;
    t.z = 65535;
    u8 o2[12];
    packVertex(0x800116, t, o2);
    EXPECT_EQ(readLE16(o2 + 0), 300);
    EXPECT_EQ(readLE16(o2 + 2), 7);
    EXPECT_EQ(readLE16(o2 + 4), 0x801F);  // R 31, A 1
    EXPECT_EQ(s16(readLE16(o2 + 6)), -10);
    EXPECT_EQ(readLE16(o2 + 8), 272);
    EXPECT_EQ(readLE16(o2 + 10), 65535);

    // 2 u8 weights, 16-bit TC, 16-bit normal, float position: W 0–1, TC 2, N 6, P 12, size 24.
    const u32 vt = vt::W_8 | vt::weights(2) | vt::TC_16 | vt::NRM_16 | vt::POS_F;
    EXPECT_EQ(VertexLayout::fromVtype(vt).size, 24);
    BuildVertex s;
    s.w[0] = 0.25f;
    s.w[1] = 0.75f;
    s.u = 0.5f;
    s.nx = -1.f;
    s.x = 1.5f;
    u8 o3[24];
    packVertex(vt, s, o3);
    EXPECT_EQ(o3[0], 32);
    EXPECT_EQ(o3[1], 96);
    EXPECT_EQ(readLE16(o3 + 2), 16384);
    EXPECT_EQ(s16(readLE16(o3 + 6)), -32768);
    float x;
    std::memcpy(&x, o3 + 12, 4);
    EXPECT_EQ(x, 1.5f);

    // 16-bit colour formats truncate: 5650 and 4444.
    BuildVertex c;
    c.color = 0xFFFFFFFF;
    c.x = 0;
    u8 o4[8];
    packVertex(vt::COL_5650 | vt::POS_16, c, o4);
    EXPECT_EQ(readLE16(o4), 0xFFFF);
    c.color = 0x12345678;  // R 0x78, G 0x56, B 0x34, A 0x12
    packVertex(vt::COL_4444 | vt::POS_16, c, o4);
    EXPECT_EQ(readLE16(o4), 0x1357);
}

// ---------------------------------------------------------------------------------------------
// Execution on the engine

struct CapturedDraw {
    u32 prim = 0, count = 0, vtype = 0;
    bool patch = false;
    std::vector<u8> vertexBytes, indexBytes, texBytes, clut;
};

// Captures what each draw reads (by content, not address), so a direct run and a dump replay can
// be compared draw by draw.
struct CaptureRenderer : Renderer {
    explicit CaptureRenderer(Memory& m) : mem(m) {}
    Memory& mem;
    std::vector<CapturedDraw> draws;
    u32 transfers = 0;

    void capture(const GeState& st, u32 count, u32 vtype, u32 vaddr, u32 iaddr, CapturedDraw& d) {
        d.count = count;
        d.vtype = vtype;
        const u32 stride = st.vertexStride();
        u32 nverts = count;
        if (st.VTYPE_idx()) {
            const u32 isz = st.indexSize();
            d.indexBytes.resize(size_t(count) * isz);
            mem.read(iaddr, d.indexBytes.data(), u32(d.indexBytes.size()));
            u32 maxIdx = 0;
            for (u32 i = 0; i < count; ++i) {
                const u8* p = d.indexBytes.data() + size_t(i) * isz;
                maxIdx = std::max<u32>(maxIdx, isz == 1 ? p[0] : isz == 2 ? readLE16(p) : readLE32(p));
            }
            nverts = maxIdx + 1;
        }
        d.vertexBytes.resize(size_t(nverts) * stride);
        mem.read(vaddr, d.vertexBytes.data(), u32(d.vertexBytes.size()));
        if (st.TME_on() && !st.CMODE_on()) {
            const u32 addr = st.textureAddr(0);
            static constexpr u32 bits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8};
            const u32 bytes = st.textureBufWidth(0) * st.textureHeight(0) * bits[st.TPF_format()] / 8;
            d.texBytes.resize(bytes);
            mem.read(addr, d.texBytes.data(), bytes);
            d.clut.assign(st.clut, st.clut + 1024);
        }
    }
    void drawPrim(const PrimPacket& p) override {
        CapturedDraw d;
        d.prim = p.prim;
        capture(*p.state, p.count, p.vtype, p.vertexAddr, p.indexAddr, d);
        draws.push_back(std::move(d));
    }
    void drawPatch(const PatchPacket& p) override {
        CapturedDraw d;
        d.patch = true;
        capture(*p.state, p.ucount * p.vcount, p.vtype, p.vertexAddr, p.indexAddr, d);
        draws.push_back(std::move(d));
    }
    void drawImmediate(const ImmPacket&) override {}
    void blockTransfer(const TransferPacket& t, Memory& m) override {
        ++transfers;
        Renderer::blockTransfer(t, m);
    }
};

// A small scene touching every record kind: RAM texture + CLUT + indexed draw + patch + VRAM
// upload + RAM→VRAM transfer.
void buildMiniScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.clear(CLEAR_COLOR, 0xFF000000, 0);
    // CLUT8 texture with a 16-entry 5650 palette.
    std::vector<u8> tex(16 * 16);
    for (u32 i = 0; i < tex.size(); ++i) tex[i] = u8(i * 7);
    std::vector<u8> pal(32);
    for (u32 i = 0; i < 32; ++i) pal[i] = u8(0x11 * i);
    const u32 palAddr = b.place(pal.data(), 32);
    b.clutMode(GE_FORMAT_565, 0, 0x0F, 0);
    b.clutLoad(palAddr, 1);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.setTexture(0, b.place(tex.data(), u32(tex.size())), 16, 16, 16);
    const u32 vt = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH | vt::IDX_8;
    BuildVertex v[4];
    for (int i = 0; i < 4; ++i) {
        v[i].x = float((i & 1) * 100);
        v[i].y = float((i >> 1) * 100);
        v[i].u = float((i & 1) * 16);
        v[i].v = float((i >> 1) * 16);
        v[i].color = 0xFF00FF00u + u32(i);
    }
    const auto vdata = packVertices(vt, v, 4);
    const u8 idx[6] = {0, 1, 2, 2, 1, 3};
    b.drawArrayData(GE_PRIM_TRIANGLES, vt, 6, idx, vdata.data());
    // Continue with the same vertex pointer (no VADR): a second non-indexed draw reads on.
    b.enable(GE_CMD_TME, false);
    const u32 vt2 = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    const auto v2 = packVertices(vt2, v, 4);
    b.drawArray(GE_PRIM_RECTANGLES, vt2, 2, 0, b.place(v2.data(), u32(v2.size()), 4));
    b.drawArray(GE_PRIM_RECTANGLES, 0, 2, 0, 0);
    // A Bezier patch.
    std::vector<BuildVertex> cp(16);
    for (int i = 0; i < 16; ++i) {
        cp[size_t(i)].x = float(i % 4) / 4.f;
        cp[size_t(i)].y = float(i / 4) / 4.f;
    }
    const auto cpData = packVertices(vt::POS_F, cp.data(), 16);
    b.drawBezier(vt::POS_F, 4, 4, 0, b.place(cpData.data(), u32(cpData.size()), 4));
    // CPU upload to VRAM, then textured from there (5650), then a RAM → VRAM transfer.
    std::vector<u8> vtex(8 * 8 * 2);
    for (u32 i = 0; i < vtex.size(); ++i) vtex[i] = u8(i ^ 0x5A);
    ASSERT_TRUE(b.upload(0x04180000, vtex.data(), u32(vtex.size())));
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_5650, 0, false);
    b.setTexture(0, 0x04180000, 8, 8, 8);
    const auto v3 = packVertices(vt2 | vt::TC_16, v, 2);
    b.drawArray(GE_PRIM_RECTANGLES, vt2 | vt::TC_16, 2, 0, b.place(v3.data(), u32(v3.size()), 4));
    b.enable(GE_CMD_TME, false);
    std::vector<u8> img(32 * 8 * 4);
    for (u32 i = 0; i < img.size(); ++i) img[i] = u8(i);
    b.copyImage(GE_FORMAT_8888, 2, 1, 16, 4, 32, b.place(img.data(), u32(img.size())), 10, 20, 512, 0x04000000);
    b.finish();
}

GeState bootState() {
    GeState st;
    st.reset();
    for (int op = 0; op < 256; ++op) st.regs[op] = u32(op) << 24;
    return st;
}

TEST(ListBuilder, BuiltListRunsOnTheEngine) {
    Memory mem;
    ListBuilder b(&mem);
    b.viewport(2048, 2048, 480, 272);
    buildMiniScene(b);
    const u32 list = b.placeList();
    ASSERT_NE(list, 0u);
    CaptureRenderer r(mem);
    GeEngine eng(mem, &r);
    eng.startList(list, 0);
    EXPECT_EQ(eng.run(100000), RunStatus::Completed) << eng.lastErrorMessage();
    EXPECT_FLOAT_EQ(eng.state().SX_value(), 240.f);
    EXPECT_FLOAT_EQ(eng.state().SY_value(), -136.f);
    // clear, indexed triangles, 2 rectangle draws, Bezier, VRAM-textured rectangle.
    ASSERT_EQ(r.draws.size(), 6u);
    EXPECT_EQ(r.draws[0].count, 16u);
    EXPECT_EQ(r.draws[1].count, 6u);
    EXPECT_EQ(r.draws[1].indexBytes, std::vector<u8>({0, 1, 2, 2, 1, 3}));
    // The second rectangle draw continued after the first one's vertices (ge-rules.md §4.6).
    EXPECT_EQ(r.draws[3].vertexBytes.size(), 2u * 12);
    EXPECT_EQ(readLE16(r.draws[3].vertexBytes.data() + 4), 0);  // vertex 2: x 0
    EXPECT_EQ(readLE16(r.draws[3].vertexBytes.data() + 6), 100);
    EXPECT_TRUE(r.draws[4].patch);
    EXPECT_EQ(r.transfers, 1u);
    // The transfer landed: row 0 of the copy = source pixel (2, 1) at (10, 20).
    // Source bytes are their own offsets: pixel (2, 1) of a 32-pixel stride starts at byte 136.
    EXPECT_EQ(mem.read32(0x04000000 + (20 * 512 + 10) * 4), 136u | 137u << 8 | 138u << 16 | 139u << 24);
}

TEST(ListBuilder, CallListRunsASubList) {
    Memory mem;
    ListBuilder sub(&mem, 0x08900000);
    sub.cmd(GE_CMD_FPF, 2);
    sub.ret();
    ListBuilder b(&mem);
    ASSERT_NE(b.callList(sub), 0u);
    b.cmd(GE_CMD_FBW, 256);
    b.finish();
    NullRenderer r;
    GeEngine eng(mem, &r);
    eng.startList(b.placeList(), 0);
    EXPECT_EQ(eng.run(1000), RunStatus::Completed) << eng.lastErrorMessage();
    EXPECT_EQ(eng.state().FPF_format(), 2u);
    EXPECT_EQ(eng.state().FBW_width(), 256u);
}

// ---------------------------------------------------------------------------------------------
// Recording

bool forbiddenInRegisters(u8 op) {
    // docs/ppdmp.md §7 rule 4.
    switch (op) {
    case GE_CMD_VADR: case GE_CMD_IADR: case GE_CMD_BASE: case GE_CMD_OFFSET: case GE_CMD_ORIGIN:
    case GE_CMD_JUMP: case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET: case GE_CMD_END:
    case GE_CMD_SIGNAL: case GE_CMD_FINISH: case GE_CMD_BBOX:
        return true;
    default: return false;
    }
}
bool isKick(u8 op) {
    return op == GE_CMD_PRIM || op == GE_CMD_BEZIER || op == GE_CMD_SPLINE || op == GE_CMD_CLOAD || op == GE_CMD_XSTART;
}

// Checks the structural rules of ppdmp.md §4/§7 on a dump; returns the kick count.
u32 checkDumpStructure(const dump::Dump& d) {
    EXPECT_GE(d.records.size(), 3u);
    if (d.records.size() < 3) return 0;
    EXPECT_EQ(d.records.front().type, dump::INIT);
    EXPECT_EQ(d.records.front().size, 2048u);
    EXPECT_EQ(d.records[1].type, dump::DISPLAY);
    EXPECT_EQ(d.records.back().type, dump::DISPLAY);
    EXPECT_EQ(d.payloadWord(d.records.back(), 0), 0x04000000u);
    EXPECT_EQ(d.payloadWord(d.records.back(), 1), 512u);
    bool tbwSeen[8] = {};
    u32 kicks = 0;
    std::vector<u8> pendingData;  // data record types since the last REGISTERS block
    for (size_t i = 0; i < d.records.size(); ++i) {
        const dump::Record& r = d.records[i];
        SCOPED_TRACE("record " + std::to_string(i) + " " + dump::recordTypeName(r.type));
        EXPECT_TRUE(dump::isKnownRecordType(r.type));
        EXPECT_NE(d.payload(r), nullptr);
        if (i > 0) {
            EXPECT_NE(r.type, dump::INIT);
        }
        if (r.type == dump::REGISTERS) {
            EXPECT_EQ(r.size % 4, 0u);
            EXPECT_GT(r.size, 0u);
            for (u32 k = 0; k < r.size / 4; ++k) {
                const u32 w = d.payloadWord(r, k);
                const u8 op = u8(w >> 24);
                EXPECT_FALSE(forbiddenInRegisters(op)) << std::hex << w;
                if (op >= GE_CMD_TBW0 && op <= GE_CMD_TBW7) tbwSeen[op - GE_CMD_TBW0] = true;
                // A kick inside a block consumed no data records (e.g. an XSTART from GE-drawn
                // VRAM); one that did opens its block (checked below).
                if (isKick(op)) ++kicks;
            }
            const u8 first = u8(d.payloadWord(r, 0) >> 24);
            // Data records before a block are consumed by its first word.
            if (!pendingData.empty()) {
                EXPECT_TRUE(isKick(first)) << "data records before a block not opened by a kick";
                bool sawIndices = false, sawVertices = false;
                for (u8 t : pendingData) {
                    if (dump::textureLevelOf(t) >= 0 || dump::framebufLevelOf(t) >= 0) {
                        EXPECT_FALSE(sawIndices || sawVertices) << "texture after geometry";
                    }
                    if (t == dump::INDICES) {
                        EXPECT_FALSE(sawVertices) << "indices after vertices";
                        sawIndices = true;
                    }
                    if (t == dump::VERTICES) sawVertices = true;
                    if (t == dump::CLUT) {
                        EXPECT_EQ(first, GE_CMD_CLOAD);
                    }
                    if (t == dump::TRANSFERSRC) {
                        EXPECT_EQ(first, GE_CMD_XSTART);
                    }
                }
            }
            pendingData.clear();
        } else if (r.type == dump::DISPLAY || r.type == dump::INIT || r.type == dump::MEMSET ||
                   r.type == dump::MEMCPYDEST || r.type == dump::MEMCPYDATA || r.type == dump::EDRAMTRANS) {
            EXPECT_TRUE(pendingData.empty()) << "data records not consumed before " << dump::recordTypeName(r.type);
            pendingData.clear();
        } else {
            if (int n = dump::textureLevelOf(r.type); n >= 0) {
                EXPECT_TRUE(tbwSeen[n]) << "TEXTURE without a TBW before it";
            }
            if (int n = dump::framebufLevelOf(r.type); n >= 0) {
                EXPECT_GE(r.size, 16u);
                EXPECT_TRUE(Memory::isVram(d.payloadWord(r, 0)));
            }
            pendingData.push_back(r.type);
        }
    }
    EXPECT_TRUE(pendingData.empty());
    return kicks;
}

TEST(DumpRecorder, RecordOrderFollowsThePpssppRecorder) {
    Memory mem;
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    rec.begin(bootState(), 0x04000000, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    buildMiniScene(b);
    rec.end(0x04000000, 512, GE_FORMAT_8888);
    EXPECT_TRUE(rec.warnings().empty());
    const dump::Dump& d = w.dump();
    // clear, CLOAD, triangles, 2 rectangles, Bezier, VRAM-textured rectangle, XSTART.
    EXPECT_EQ(rec.kicks(), 8u);
    EXPECT_EQ(checkDumpStructure(d), 8u);

    std::vector<u8> types;
    for (const auto& r : d.records) types.push_back(r.type);
    using namespace dump;
    const std::vector<u8> want = {INIT, DISPLAY, REGISTERS, VERTICES,           // state, clear data
                                  REGISTERS, CLUT,                              // PRIM …, palette
                                  REGISTERS, TEXTURE0, INDICES, VERTICES,      // CLOAD …, draw data
                                  REGISTERS, VERTICES,                          // PRIM …
                                  REGISTERS, VERTICES,                          // PRIM …, continued draw
                                  REGISTERS, VERTICES,                          // PRIM …, Bezier points
                                  REGISTERS, MEMCPYDEST, MEMCPYDATA,            // BEZIER …, upload
                                  REGISTERS, FRAMEBUF0, VERTICES,               // state, VRAM texture
                                  REGISTERS, TRANSFERSRC,                       // PRIM …
                                  REGISTERS, DISPLAY};                          // XSTART
    EXPECT_EQ(types, want);
    // The uploaded (not drawn) VRAM texture carries its bytes with flags 0.
    const Record& fb = d.records[20];
    EXPECT_EQ(d.payloadWord(fb, 0), 0x04180000u);
    EXPECT_EQ(d.payloadWord(fb, 1), 8u);
    EXPECT_EQ(d.payloadWord(fb, 2), 0u);
    EXPECT_EQ(fb.size, 16u + 8 * 8 * 2);
    // Transfer source: ((sy + h − 1)·stride + sx + w)·4 = ((1 + 3)·32 + 2 + 16)·4 bytes.
    EXPECT_EQ(d.records[23].size, ((1u + 3) * 32 + 2 + 16) * 4);
    // Indexed draw: 6 indices, vertices 0..3.
    EXPECT_EQ(d.records[8].size, 6u);
    EXPECT_EQ(d.records[9].size, 4u * 16);  // TC 0, colour 4, position 8: 16 bytes (ge-rules.md §5.2)
}

TEST(DumpRecorder, DrawnVramTexturesAreHeaderOnly) {
    Memory mem;
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    rec.begin(bootState(), 0x04000000, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    b.drawBuffer(GE_FORMAT_565, 0x154000, 64);
    b.scissor(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, 0xFF0000FF, 0);
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_5650, 0, false);
    b.setTexture(0, 0x04154000, 64, 64, 64);
    BuildVertex v[2];
    v[1].x = 64;
    v[1].y = 64;
    v[1].u = 64;
    v[1].v = 64;
    const u32 vt = vt::TC_16 | vt::POS_16 | vt::THROUGH;
    const auto data = packVertices(vt, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, vt, 2, nullptr, data.data());
    // Copy the drawn buffer: no TRANSFERSRC (the source is GE-drawn VRAM).
    b.copyImage(GE_FORMAT_565, 0, 0, 8, 8, 64, 0x04154000, 0, 0, 512, 0x04100000);
    b.finish();
    rec.end(0x04000000, 512, GE_FORMAT_8888);
    const dump::Dump& d = w.dump();
    checkDumpStructure(d);
    int framebufs = 0, transferSrcs = 0;
    for (const auto& r : d.records) {
        if (r.type == dump::FRAMEBUF0) {
            ++framebufs;
            EXPECT_EQ(r.size, 16u);
            EXPECT_EQ(d.payloadWord(r, 0), 0x04154000u);
            EXPECT_EQ(d.payloadWord(r, 2), 7u);  // target | unchanged | drawn
        }
        if (r.type == dump::TRANSFERSRC) ++transferSrcs;
    }
    EXPECT_EQ(framebufs, 1);
    EXPECT_EQ(transferSrcs, 0);
}

TEST(DumpRecorder, TransfersToRamAreDropped) {
    Memory mem;
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    rec.begin(bootState(), 0x04000000, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    b.copyImage(GE_FORMAT_8888, 0, 0, 4, 4, 64, 0x04000000, 0, 0, 64, 0x08900000);
    rec.end(0x04000000, 512, GE_FORMAT_8888);
    for (const auto& r : w.dump().records) {
        EXPECT_NE(r.type, dump::TRANSFERSRC);
        if (r.type == dump::REGISTERS) {
            for (u32 k = 0; k < r.size / 4; ++k) EXPECT_NE(w.dump().payloadWord(r, k) >> 24, u32(GE_CMD_XSTART));
        }
    }
    EXPECT_EQ(rec.warnings().size(), 1u);
}

// Direct execution of the built list and replay of its recording give the same draws, reading
// the same bytes (vertices, indices, texture, palette), and the same transfer result.
TEST(DumpRecorder, ReplayMatchesDirectExecution) {
    Memory mem;
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    const GeState init = bootState();
    rec.begin(init, 0x04000000, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    buildMiniScene(b);
    b.attach(nullptr);
    rec.end(0x04000000, 512, GE_FORMAT_8888);

    CaptureRenderer direct(mem);
    {
        GeEngine eng(mem, &direct);
        u32 ctx[512];
        init.saveContext(ctx);
        eng.loadContext(ctx);
        eng.startList(b.placeList(), 0);
        ASSERT_EQ(eng.run(100000), RunStatus::Completed);
    }
    Memory mem2;
    CaptureRenderer replay(mem2);
    {
        GeEngine eng(mem2, &replay);
        dump::ReplayResult res;
        std::string err;
        ASSERT_TRUE(dump::replayDump(w.dump(), eng, {}, res, err)) << err;
        EXPECT_EQ(res.listErrors, 0u) << res.warning;
    }
    ASSERT_EQ(replay.draws.size(), direct.draws.size());
    for (size_t i = 0; i < direct.draws.size(); ++i) {
        SCOPED_TRACE("draw " + std::to_string(i));
        EXPECT_EQ(replay.draws[i].count, direct.draws[i].count);
        EXPECT_EQ(replay.draws[i].vtype, direct.draws[i].vtype);
        EXPECT_EQ(replay.draws[i].patch, direct.draws[i].patch);
        EXPECT_EQ(replay.draws[i].indexBytes, direct.draws[i].indexBytes);
        EXPECT_EQ(replay.draws[i].vertexBytes, direct.draws[i].vertexBytes);
        EXPECT_EQ(replay.draws[i].texBytes, direct.draws[i].texBytes);
        EXPECT_EQ(replay.draws[i].clut, direct.draws[i].clut);
    }
    EXPECT_EQ(replay.transfers, direct.transfers);
    for (u32 y = 20; y < 24; ++y)
        for (u32 x = 10; x < 26; ++x) {
            const u32 a = 0x04000000 + (y * 512 + x) * 4;
            EXPECT_EQ(mem2.read32(a), mem.read32(a)) << x << "," << y;
        }
}

// ---------------------------------------------------------------------------------------------
// The project's scene dumps (written by tools/make_scenes)

const char* const kSceneNames[] = {"lit_textured_skinned", "clut_dxt_sprites", "bezier_spline",
                                   "blend_stencil_logic", "render_to_texture"};

TEST(SceneDumps, LoadWithTheRecorderRulesAndReplayCleanly) {
    for (const char* name : kSceneNames) {
        SCOPED_TRACE(name);
        const fs::path path = fs::path(GE2GL_SOURCE_DIR) / "dumps" / (std::string(name) + ".ppdmp");
        ASSERT_TRUE(fs::exists(path)) << path;
        EXPECT_LT(fs::file_size(path), 200u * 1024);
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(path.string(), d, err)) << err;
        EXPECT_EQ(d.version, 6u);
        const u32 kicks = checkDumpStructure(d);
        EXPECT_GT(kicks, 3u);
        // Frame buffer shown: VRAM 0x04000000, stride 512, 8888.
        EXPECT_EQ(d.payloadWord(d.records.back(), 2) & 0xFF, u32(GE_FORMAT_8888));

        const dump::DumpSummary s = dump::summarize(d);
        Memory mem;
        NullRenderer r;
        GeEngine eng(mem, &r);
        dump::ReplayResult res;
        ASSERT_TRUE(dump::replayDump(d, eng, {}, res, err)) << err;
        EXPECT_EQ(res.listErrors, 0u) << res.warning;
        EXPECT_EQ(res.draws, s.draws);
        EXPECT_EQ(r.prims + r.patches, s.draws);  // every kick has vertices
        EXPECT_EQ(res.displayAddr, 0x04000000u);
        EXPECT_EQ(res.displayStride, 512u);
    }
}

// Scene-specific content the docs promise (docs/scenes.md).
TEST(SceneDumps, ScenesUseTheFeaturesTheyAreNamedFor) {
    auto load = [](const char* name, dump::Dump& d) {
        std::string err;
        const fs::path path = fs::path(GE2GL_SOURCE_DIR) / "dumps" / (std::string(name) + ".ppdmp");
        return dump::loadDump(path.string(), d, err);
    };
    auto opsOf = [](const dump::Dump& d) {
        std::multiset<u32> words;
        for (const auto& r : d.records)
            if (r.type == dump::REGISTERS)
                for (u32 k = 0; k < r.size / 4; ++k) words.insert(d.payloadWord(r, k));
        return words;
    };
    auto hasOp = [](const std::multiset<u32>& words, u8 op, u32 mask, u32 value) {
        return std::any_of(words.begin(), words.end(), [&](u32 w) { return (w >> 24) == op && (w & mask) == value; });
    };
    dump::Dump d;
    ASSERT_TRUE(load("lit_textured_skinned", d));
    auto w = opsOf(d);
    EXPECT_TRUE(hasOp(w, GE_CMD_LTYPE0, 0x300, 0x000));      // directional
    EXPECT_TRUE(hasOp(w, GE_CMD_LTYPE0 + 1, 0x300, 0x100));  // point
    EXPECT_TRUE(hasOp(w, GE_CMD_LTYPE0 + 2, 0x300, 0x200));  // spot
    EXPECT_TRUE(hasOp(w, GE_CMD_VTYPE, 0x600, 0x200));       // u8 weights
    EXPECT_TRUE(hasOp(w, GE_CMD_VTYPE, 0x600, 0x600));       // float weights
    EXPECT_TRUE(hasOp(w, GE_CMD_ZTE, 1, 1));
    EXPECT_GE(w.count(0x2B000000 | toFloat24(1.f)), 2u);     // bone data

    ASSERT_TRUE(load("clut_dxt_sprites", d));
    w = opsOf(d);
    for (u32 fmt = GE_TFMT_5650; fmt <= GE_TFMT_DXT5; ++fmt) EXPECT_TRUE(hasOp(w, GE_CMD_TPF, 0xF, fmt)) << fmt;
    EXPECT_TRUE(hasOp(w, GE_CMD_TMODE, 1, 1));               // swizzled
    EXPECT_TRUE(hasOp(w, GE_CMD_TFILTER, 0x101, 0x101));     // bilinear
    EXPECT_TRUE(hasOp(w, GE_CMD_CLUT, 0x1F0000, 0x010000));  // CLUT start
    EXPECT_TRUE(hasOp(w, GE_CMD_CLUT, 0x7C, 4 << 2));        // shift

    ASSERT_TRUE(load("bezier_spline", d));
    w = opsOf(d);
    EXPECT_TRUE(hasOp(w, GE_CMD_BEZIER, 0, 0));
    EXPECT_TRUE(hasOp(w, GE_CMD_SPLINE, 0xF0000, 0x30000));
    EXPECT_TRUE(hasOp(w, GE_CMD_SPLINE, 0xF0000, 0x90000));  // U open/close, V close/open

    ASSERT_TRUE(load("blend_stencil_logic", d));
    w = opsOf(d);
    for (u32 eq = 0; eq < 6; ++eq) EXPECT_TRUE(hasOp(w, GE_CMD_BLEND, 0x700, eq << 8)) << eq;
    for (u32 op = 0; op < 16; ++op) EXPECT_TRUE(hasOp(w, GE_CMD_LOP, 0xF, op)) << op;
    EXPECT_TRUE(hasOp(w, GE_CMD_FPF, 3, GE_FORMAT_4444));
    EXPECT_TRUE(hasOp(w, GE_CMD_DTE, 1, 1));
    EXPECT_TRUE(hasOp(w, GE_CMD_STE, 1, 1));

    ASSERT_TRUE(load("render_to_texture", d));
    int framebufRecords = 0;
    for (const auto& r : d.records) framebufRecords += dump::framebufLevelOf(r.type) >= 0;
    EXPECT_GE(framebufRecords, 2);
    w = opsOf(d);
    EXPECT_TRUE(hasOp(w, GE_CMD_XSTART, 0, 0));
    EXPECT_TRUE(hasOp(w, GE_CMD_TPF, 0xF, GE_TFMT_CLUT16));
}

}  // namespace
