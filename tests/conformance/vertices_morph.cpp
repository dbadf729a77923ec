// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/vertices/morph, re-created (gu_sim.h, conformance.h,
// screenshot.h). Twelve 32x32 transform-mode sprites, eleven a row from (10, 10), 42 pixels apart,
// each with 1, 2 or 4 morph copies of its two vertices (VTYPE morph count): copy 0 the box, in
// COLORS[0] (red), with UV (0, 0)-(1, 1); the other copies the box moved by (4, 4) with UV + 0.5 in
// COLORS[i] ("type 0") or position (0, 0, 0), UV (0.5, 0.5), normal 0 in COLORS[i] ("type 1");
// under several morph weights; textured (a 4x4 texture of COLORS, DECAL), lit (one directional
// light), in clear mode, and indexed. The vertices are written as vertices/shared.cpp's Vertices
// class writes them (each morph copy's fields aligned to their size, the vertex aligned at its end).
// The screenshot is the check. What the PSP shows: a single copy ignores the weights; copies blend
// position, colour and UV by the weights (0.5/0.5: moved 2 pixels, (0x7F, 0x7F, 0); 0.75/0.25:
// moved 1, (0xBF, 0x3F, 0)), sums over 1 saturate; clear mode blends too. The lit box and the
// ones after it (lighting stays on) show only the light's ambient colour (0x7F red) times the vertex
// colour: the SDK's sceGuLightColor(GU_AMBIENT_AND_DIFFUSE) sends the ambient colour alone.
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr int kBoxW = 32, kBoxH = 32, kBoxOff = 4, kBoxSpace = 10;
constexpr float kUvOff = 0.5f;
constexpr u32 kImage = 0x08400000;
// COLORS[] of vertices/shared.h, the first seven (ABGR).
constexpr u32 kColors[7] = {0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFF00FFFF, 0xFFFF00FF, 0xFFFFFF00, 0xFFFFFFFF};

// vertices/shared.cpp's Vertices: fields written in VTYPE order, each aligned to its own size.
class VertexWriter {
public:
    explicit VertexWriter(u32 vtype) : vtype_(vtype) {}
    void texcoord(float u, float v) {
        const u32 f = vtype_ & 3;
        align(f);
        write(f, u), write(f, v);
    }
    void color(u32 c) {
        const u32 f = (vtype_ >> 2) & 7;
        align(f);
        if (f == 7) put32(c);
    }
    void normal(float x, float y, float z) {
        const u32 f = (vtype_ >> 5) & 3;
        align(f);
        write(f, x), write(f, y), write(f, z);
    }
    // Pos(x, y, z) in transform mode with float positions: norm32x/y of the pixel.
    void pos(int x, int y) {
        const u32 f = (vtype_ >> 7) & 3;
        align(f);
        write(f, 2.0f * float(x) / 480 - 1.0f), write(f, 1.0f - 2.0f * float(y) / 272), write(f, 0.0f);
    }
    void posDirect(float x, float y, float z) {
        const u32 f = (vtype_ >> 7) & 3;
        align(f);
        write(f, x), write(f, y), write(f, z);
    }
    void endVert() {
        for (u32 f : {vtype_ & 3, (vtype_ >> 2) & 7, (vtype_ >> 5) & 3, (vtype_ >> 7) & 3, (vtype_ >> 9) & 3}) align(f);
    }
    const std::vector<u8>& bytes() const { return buf_; }

private:
    void align(u32 fmt) {
        static constexpr u32 kSizes[8] = {1, 1, 2, 4, 2, 2, 2, 4};
        while (buf_.size() % kSizes[fmt]) buf_.push_back(0);
    }
    void put32(u32 v) {
        for (int i = 0; i < 4; ++i) buf_.push_back(u8(v >> (8 * i)));
    }
    void write(u32 fmt, float v) {
        if (fmt == 3) put32(floatBits(v));  // the test only uses float components here
    }
    u32 vtype_;
    std::vector<u8> buf_;
};

void writeOffCP(VertexWriter& w, int morphCount, int morphType, float u, float v, int x, int y) {
    w.texcoord(u, v);
    w.color(kColors[0]);
    w.normal(5, 5, 1);
    w.pos(x, y);
    for (int i = 1; i < morphCount; ++i) {
        if (morphType == 0) {
            w.texcoord(u + kUvOff, v + kUvOff);
            w.color(kColors[i]);
            w.normal(1, 1, 1);
            w.pos(x + kBoxOff, y + kBoxOff);
        } else {
            w.texcoord(kUvOff, kUvOff);
            w.color(kColors[i]);
            w.normal(0, 0, 0);
            w.posDirect(0, 0, 0);
        }
    }
    w.endVert();
}

struct BoxCursor {
    int x = 10, y = 10;
};

// nextBox(t, morphType, useInds): a sprite from (x, y) to (x + 32, y + 32); with indices, an extra
// first vertex and the 16-bit indices {1, 2} right after the vertices.
void nextBox(ListBuilder& b, BoxCursor& at, u32 vtype, int morphType = 0, bool useInds = false) {
    const int morphCount = int((vtype >> 18) & 7) + 1;
    VertexWriter w(vtype);
    if (useInds) writeOffCP(w, morphCount, morphType, 2.0f, 0.0f, at.x - 5, at.y + 5);
    writeOffCP(w, morphCount, morphType, 0.0f, 0.0f, at.x, at.y);
    writeOffCP(w, morphCount, morphType, 1.0f, 1.0f, at.x + kBoxW, at.y + kBoxH);
    w.endVert();
    std::vector<u8> data = w.bytes();
    const u32 vertexBytes = u32(data.size());
    if (useInds) data.insert(data.end(), {1, 0, 2, 0});
    const u32 addr = b.place(data.data(), u32(data.size()), 16);  // sceGuGetMemory
    b.drawArray(GE_PRIM_RECTANGLES, vtype, 2, useInds ? addr + vertexBytes : 0, addr);
    at.x += kBoxW + kBoxSpace;
    if (at.x + kBoxW >= 480) {
        at.x = 10;
        at.y += kBoxH + kBoxSpace;
    }
}

// The PSP's screenshot (black elsewhere), box by box.
const std::vector<ScreenSpan> kScreen = {
    {10, 42, 10, 42, 0, 0, 0xFF0000},    // 1 copy, weights 0.5/0.5 ignored
    {12, 44, 54, 86, 0, 0, 0x7F7F00},    // 2 copies 0.5/0.5
    {11, 43, 95, 127, 0, 0, 0xBF3F00},   // 0.75/0.25
    {13, 45, 139, 171, 0, 0, 0x7F7F3F},  // 4 copies 0.25 each
    {10, 42, 178, 210, 0, 0, 0xFF7F3F},  // type 1, 1/0.25/0.25/0.25
    {10, 42, 220, 252, 0, 0, 0xFFFFFF},  // type 1, all 1
    // textured, 1 copy: the 4x4 texture in 8-pixel texels
    {10, 18, 262, 270, 0, 0, 0xFF0000}, {10, 18, 270, 278, 0, 0, 0x00FF00}, {10, 18, 278, 286, 0, 0, 0x0000FF},
    {10, 18, 286, 294, 0, 0, 0xFFFF00}, {18, 26, 262, 270, 0, 0, 0x00FF00}, {18, 26, 270, 278, 0, 0, 0x0000FF},
    {18, 26, 278, 286, 0, 0, 0xFFFF00}, {18, 26, 286, 294, 0, 0, 0xFF00FF}, {26, 34, 262, 270, 0, 0, 0x0000FF},
    {26, 34, 270, 278, 0, 0, 0xFFFF00}, {26, 34, 278, 286, 0, 0, 0xFF00FF}, {26, 34, 286, 294, 0, 0, 0x00FFFF},
    {34, 42, 262, 270, 0, 0, 0xFFFF00}, {34, 42, 270, 278, 0, 0, 0xFF00FF}, {34, 42, 278, 286, 0, 0, 0x00FFFF},
    {34, 42, 286, 294, 0, 0, 0xFFFFFF},
    // textured, 2 copies of type 1 (weights 1/1): the texture moved by two texels
    {10, 18, 304, 312, 0, 0, 0xFF00FF}, {10, 18, 312, 320, 0, 0, 0x00FFFF}, {10, 18, 320, 328, 0, 0, 0x0000FF},
    {10, 18, 328, 336, 0, 0, 0xFFFF00}, {18, 26, 304, 312, 0, 0, 0x00FFFF}, {18, 26, 312, 320, 0, 0, 0xFFFFFF},
    {18, 26, 320, 328, 0, 0, 0xFFFF00}, {18, 26, 328, 336, 0, 0, 0xFF00FF}, {26, 34, 304, 312, 0, 0, 0x0000FF},
    {26, 34, 312, 320, 0, 0, 0xFFFF00}, {26, 34, 320, 328, 0, 0, 0xFF0000}, {26, 34, 328, 336, 0, 0, 0x00FF00},
    {34, 42, 304, 312, 0, 0, 0xFFFF00}, {34, 42, 312, 320, 0, 0, 0xFF00FF}, {34, 42, 320, 328, 0, 0, 0x00FF00},
    {34, 42, 328, 336, 0, 0, 0x0000FF},
    {10, 42, 346, 378, 0, 0, 0x7F0000},  // lit
    {10, 42, 388, 420, 0, 0, 0x7F0000},  // clear mode, 1 copy
    {12, 44, 432, 464, 0, 0, 0x3F7F00},  // clear mode, 2 copies
    {54, 86, 12, 44, 0, 0, 0x3F7F00},    // indexed
};

TestRun runMorph(GuSim& gu) {
    TestRun run{"vertices/morph", gu.backend(), {}};
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();
    u32 image[16];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) image[r * 4 + c] = kColors[r + c];
    gu.cpuWrite(kImage, image, sizeof image);

    ListBuilder& b = gu.start();
    b.clear(CLEAR_COLOR, 0, 0);  // startFrame()
    BoxCursor at;
    const u32 colPos = vt::COL_8888 | vt::POS_F;
    b.setMorphWeight(0, 0.5f), b.setMorphWeight(1, 0.5f);
    nextBox(b, at, colPos | vt::morphs(1));
    nextBox(b, at, colPos | vt::morphs(2));
    b.setMorphWeight(0, 0.75f), b.setMorphWeight(1, 0.25f);
    nextBox(b, at, colPos | vt::morphs(2));
    for (u32 i = 0; i < 4; ++i) b.setMorphWeight(i, 0.25f);
    nextBox(b, at, colPos | vt::morphs(4));
    b.setMorphWeight(0, 1.0f);
    for (u32 i = 1; i < 4; ++i) b.setMorphWeight(i, 0.25f);
    nextBox(b, at, colPos | vt::morphs(4), 1);
    for (u32 i = 0; i < 4; ++i) b.setMorphWeight(i, 1.0f);
    nextBox(b, at, colPos | vt::morphs(4), 1);

    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.texFilter(0, 0);
    b.texFunc(1 /*DECAL*/, false);
    b.texWrap(false, false);
    b.setTexture(0, kImage, 4, 4, 4);
    nextBox(b, at, vt::TC_F | vt::POS_F | vt::morphs(1));
    nextBox(b, at, vt::TC_F | vt::POS_F | vt::morphs(2), 1);

    b.enable(GE_CMD_TME, false);
    b.enable(GE_CMD_LTE, true);
    b.enable(GE_CMD_LE0, true);
    const float one[3] = {1, 1, 1};
    b.light(0, 0 /*DIRECTIONAL*/, 0 /*AMBIENT_AND_DIFFUSE*/, one);
    b.lightMode(false);
    // sceGuLightSpot(0, {1, 1, 1}, 1.0f, 1.0f): exponent, cutoff, then the direction.
    b.cmdf(GE_CMD_LKS0, 1.0f);
    b.cmdf(GE_CMD_LKO0, 1.0f);
    b.cmdf(GE_CMD_LDX0, 1.0f), b.cmdf(GE_CMD_LDY0, 1.0f), b.cmdf(GE_CMD_LDZ0, 1.0f);
    // sceGuLightColor(0, GU_AMBIENT_AND_DIFFUSE, 0xFFFF7F): that SDK's case breaks after the
    // ambient word, so only LAC0 is sent and the diffuse colour stays 0 (sceGuInit's reset).
    b.lightColor(0, LIGHT_AMBIENT, 0xFFFF7F);
    nextBox(b, at, vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::morphs(1));

    b.cmd(GE_CMD_CMODE, 1 | ((CLEAR_COLOR | CLEAR_STENCIL) << 8));
    b.setMorphWeight(0, 0.5f), b.setMorphWeight(1, 0.5f);
    nextBox(b, at, colPos | vt::morphs(1));
    nextBox(b, at, colPos | vt::morphs(2));
    b.cmd(GE_CMD_CMODE, 0);
    nextBox(b, at, colPos | vt::morphs(2) | vt::IDX_16, 0, true);
    gu.finishSync();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x000000, kScreen);
    return run;
}

CONFORMANCE_TEST(VerticesMorph, runMorph)

}  // namespace
}  // namespace ge::conformance
