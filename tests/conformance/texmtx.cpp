// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/texmtx/uvs, normals, prims and source, re-created (gu_sim.h,
// conformance.h). A 256x256 8888 texture whose texel (x, y) is 0xFFFF0000 | y << 8 | x (nearest,
// REPLACE/RGBA) is mapped with the texture matrix (TMAP mode 1) from the projection source under
// test — position, UV, normal, normalised normal, the undefined 3 — onto a square covering
// (0, 0)-(256, 256) (offset 2048, viewport 512 x -512, clipping on); the texture matrix makes
// q = 1 + z (onesAddQ) except in texmtx/prims, which keeps the identity. The four corner pixels are read after each draw,
// on a buffer filled once with 0x44444444. The cases: skinned UVs and normals, UV scale and offset,
// a zero normal normalised, primitives of every kind with a normal source, and vertex formats
// without UV or normal (the hardware keeps the previous draw's last values).
#include "tests/conformance/conformance.h"

#include <array>

namespace ge::conformance {
namespace {

using Corners = std::array<u32, 4>;  // TL (0, 0), TR (255, 0), BL (0, 255), BR (255, 255)
constexpr Corners kInitial = {0x44444444, 0x44444444, 0x44444444, 0x44444444};

constexpr u32 kTexture = 0x08400000;
using M16 = std::array<float, 16>;
constexpr M16 kOnes = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
constexpr M16 kOnesAddQ = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1};
constexpr M16 kHalves = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f};
constexpr M16 kOnesOffsetRHalf = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5f, 0, 0, 1};

// sceGuTexProjMapMode sources (pspgu.h): GU_POSITION 0, GU_UV 1, GU_NORMALIZED_NORMAL 2, GU_NORMAL 3.
enum Source : u32 { kPosition = 0, kUv = 1, kNormalizedNormal = 2, kNormal = 3 };

// Vertices whose components are all 32-bit floats, written in order.
std::vector<u8> floats(const std::vector<std::vector<float>>& verts) {
    std::vector<u8> out;
    for (const auto& v : verts)
        for (float f : v) {
            const u32 b = floatBits(f);
            for (int k = 0; k < 4; ++k) out.push_back(u8(b >> (8 * k)));
        }
    return out;
}

class TexMtxTest {
public:
    TexMtxTest(GuSim& gu, const char* test) : gu_(gu), run_{test, gu.backend(), {}} {}

    // initDisplay() (texmtx/shared.cpp), the buffer filled, "Initial", then init(): the texture
    // and (all but texmtx/prims) the onesAddQ texture matrix.
    void init(bool addQ = true) {
        gu_.init();
        ListBuilder& b = gu_.start();
        b.drawBuffer(GE_FORMAT_8888, 0, 512);
        b.depthBuffer(0, 512);
        sdkDispBuffer(b);
        b.depthBuffer(512 * 272 * 4, 512);
        b.offset(2048, 2048);
        b.viewport(2048, 2048, 512, -512);
        b.depthRange(65535, 0);
        b.depthMask(true);
        b.scissor(0, 0, 256, 256);
        b.cullMode(false);
        b.shadeModel(true);
        b.enable(GE_CMD_CLE, true);
        b.enable(GE_CMD_TME, true);
        b.enable(GE_CMD_ABE, false);
        b.texFunc(3 /*REPLACE*/, true);
        for (GeMatrix m : {GeMatrix::World, GeMatrix::View, GeMatrix::Proj, GeMatrix::TexGen}) b.setMatrix(m, kOnes.data());
        b.texFilter(0, 0);
        b.texMode(GE_TFMT_8888, 0, false);
        gu_.finishSync();
        gu_.fillVram32(0, 0x44444444, 512 * 272);
        read("Initial", kInitial);
        std::vector<u32> texels(256 * 256);
        for (u32 y = 0; y < 256; ++y)
            for (u32 x = 0; x < 256; ++x) texels[y * 256 + x] = 0xFFFF0000u | (y << 8) | x;
        gu_.cpuWrite(kTexture, texels.data(), u32(texels.size() * 4));
        ListBuilder& l = gu_.start();
        l.setTexture(0, kTexture, 256, 256, 256);
        l.texFlush();
        l.texSync();
        if (addQ) l.setMatrix(GeMatrix::TexGen, kOnesAddQ.data());
        gu_.finishSync();
    }

    // startFrame(); sceGuTexMapMode(GU_TEXTURE_MATRIX, 0, 0); sceGuTexProjMapMode(source). The SDK
    // keeps both halves of TMAP in its context and sends them whole each time.
    ListBuilder& begin(u32 source) {
        ListBuilder& l = gu_.start();
        mapMode_ = 1;
        l.cmd(GE_CMD_TMAP, (projMode_ << 8) | mapMode_);
        l.cmd(GE_CMD_TSHADE, 0);
        projMode_ = source & 3;
        l.cmd(GE_CMD_TMAP, (projMode_ << 8) | mapMode_);
        return l;
    }

    void draw(ListBuilder& l, u32 prim, u32 vtype, const std::vector<std::vector<float>>& verts) {
        const std::vector<u8> data = floats(verts);
        l.drawArrayData(prim, vtype, u32(verts.size()), nullptr, data.data());
    }

    static std::array<float, 12> to3x4(const M16& m) {
        std::array<float, 12> e{};
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 3; ++row) e[size_t(col * 3 + row)] = m[size_t(col * 4 + row)];
        return e;
    }

    // endFrame() then displayBuffer(title).
    void end(const std::string& name, const Corners& hw) {
        gu_.finishSync();
        read(name, hw);
    }

    TestRun run() { return run_; }

private:
    void read(const std::string& name, const Corners& hw) {
        static const char* kCorner[4] = {"TL", "TR", "BL", "BR"};
        static constexpr u32 kAt[4][2] = {{0, 0}, {255, 0}, {0, 255}, {255, 255}};
        for (int i = 0; i < 4; ++i)
            run_.checkpoints.push_back(
                {name + " " + kCorner[i], hw[size_t(i)], gu_.readVram32((kAt[i][1] * 512 + kAt[i][0]) * 4)});
    }

    GuSim& gu_;
    TestRun run_;
    u32 mapMode_ = 0, projMode_ = 0;
};

constexpr u32 kWeightUvPos = vt::W_F | vt::weights(1) | vt::TC_F | vt::POS_F;
constexpr u32 kUvNormalPos = vt::TC_F | vt::NRM_F | vt::POS_F;

TestRun runUvs(GuSim& gu) {
    TexMtxTest t(gu, "texmtx/uvs");
    t.init();
    {  // testWeightedUV: one bone of halves, weight 1
        ListBuilder& l = t.begin(kUv);
        l.setBoneMatrix(0, TexMtxTest::to3x4(kHalves).data());
        t.draw(l, GE_PRIM_TRIANGLE_FAN, kWeightUvPos,
               {{1, 0, 2, 0, 0, 0}, {1, 2, 2, 2, 0, 0}, {1, 2, 0, 2, 2, 0}, {1, 0, 0, 0, 2, 0}});
        t.end("Weighted UV", {0x44ffff01, 0x44ffffff, 0x44ff0101, 0x44ff01ff});
    }
    {  // testScaleUV: offset 0.25, scale 2
        ListBuilder& l = t.begin(kUv);
        l.texOffset(0.25f, 0.25f);
        l.texScale(2.0f, 2.0f);
        t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos,
               {{0, 1, 0, 2, 1, 0, 0, 0}, {1, 1, 2, 2, 1, 1, 0, 0}, {1, 0, 2, 0, 1, 1, 1, 0}, {0, 0, 0, 0, 1, 0, 1, 0}});
        l.texOffset(0.0f, 0.0f);
        l.texScale(1.0f, 1.0f);
        t.end("UV scaled UV", {0x44ffff00, 0x44ffffff, 0x44ff0000, 0x44ff00ff});
    }
    return t.run();
}

// The quad most tests draw: UV (0.25..0.75), normals (0,1,1) (1,1,1) (1,0,1) (0,0,0.5), corners
// (0,0,-0.5) (1,0,0) (1,1,0) (0,1,0).
const std::vector<std::vector<float>> kQuadAll = {{0.25f, 0.25f, 0, 1, 1, 0, 0, -0.5f},
                                                  {0.75f, 0.25f, 1, 1, 1, 1, 0, 0},
                                                  {0.75f, 0.75f, 1, 0, 1, 1, 1, 0},
                                                  {0.25f, 0.75f, 0, 0, 0.5f, 0, 1, 0}};

TestRun runNormals(GuSim& gu) {
    TexMtxTest t(gu, "texmtx/normals");
    t.init();
    {  // testNormalizedZero: zero normals normalised, the matrix adding 0.5 to U from q
        ListBuilder& l = t.begin(kNormalizedNormal);
        l.setMatrix(GeMatrix::TexGen, kOnesOffsetRHalf.data());
        t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos,
               {{0.25f, 0.25f, 0, 0, 0, 0, 0, -0.5f}, {0.75f, 0.25f, 0, 0, 0, 1, 0, 0}, {0.75f, 0.75f, 0, 0, 0, 1, 1, 0},
                {0.25f, 0.75f, 0, 0, 0, 0, 1, 0}});
        l.setMatrix(GeMatrix::TexGen, kOnesAddQ.data());
        t.end("Normalized zero", {0x44ff0000, 0x44ff0000, 0x44ff0000, 0x44ff0000});
    }
    for (const auto& [name, source, hw] :
         {std::tuple<const char*, u32, Corners>{"Reversed normals", kNormal, {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f}},
          std::tuple<const char*, u32, Corners>{"Reversed normalized normals", kNormalizedNormal,
                                                {0x44ff6900, 0x44ff5d5d, 0x44ff0000, 0x44ff0069}}}) {
        ListBuilder& l = t.begin(source);  // the test's reverse flag is commented out
        t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos, kQuadAll);
        t.end(name, hw);
    }
    {  // testWeightedNormals
        ListBuilder& l = t.begin(kNormal);
        l.setBoneMatrix(0, TexMtxTest::to3x4(kHalves).data());
        t.draw(l, GE_PRIM_TRIANGLE_FAN, vt::W_F | vt::weights(1) | vt::NRM_F | vt::POS_F,
               {{1, 0, 2, 2, 0, 0, 0}, {1, 2, 2, 2, 2, 0, 0}, {1, 2, 0, 2, 2, 2, 0}, {1, 0, 0, 1, 0, 2, 0}});
        t.end("Weighted normal", {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f});
    }
    {  // testScaleUVNormals
        ListBuilder& l = t.begin(kNormal);
        l.texOffset(0.25f, 0.25f);
        l.texScale(2.0f, 2.0f);
        t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos,
               {{0, 0, 0, 2, 1, 0, 0, 0}, {0, 0, 2, 2, 1, 1, 0, 0}, {0, 0, 2, 0, 1, 1, 1, 0}, {0, 0, 0, 0, 1, 0, 1, 0}});
        l.texOffset(0.0f, 0.0f);
        l.texScale(1.0f, 1.0f);
        t.end("UV scaled normal", {0x44ffff00, 0x44ffffff, 0x44ff0000, 0x44ff00ff});
    }
    return t.run();
}

TestRun runPrims(GuSim& gu) {
    TexMtxTest t(gu, "texmtx/prims");
    t.init(false);
    constexpr float kEnd = 1.0f - 1.0f / 256.0f;
    struct Case {
        const char* name;
        u32 prim;
        Corners hw;
    };
    const Case cases[] = {{"Points", GE_PRIM_POINTS, {0x44ff0000, 0x44ff0080, 0x44ff0000, 0x44ff8080}},
                          {"Lines", GE_PRIM_LINE_STRIP, {0x44ff0000, 0x44ff0080, 0x44ffff00, 0x44ff8080}},
                          {"Triangles", GE_PRIM_TRIANGLE_FAN, {0x44ff0000, 0x44ff00ff, 0x44fffd00, 0x44ffffff}},
                          {"Rectangles", GE_PRIM_RECTANGLES, {0x44ff0000, 0x44ff00fd, 0x44ffff00, 0x44fffdfd}}};
    for (const Case& c : cases) {
        // testPrimType: {nx, ny, nz, x, y, z}, normal source.
        std::vector<std::vector<float>> v;
        if (c.prim == GE_PRIM_POINTS || c.prim == GE_PRIM_LINE_STRIP)
            v = {{0, 0, 1, 0, 0, 0}, {0.5f, 0, 1, kEnd, 0, 0}, {0.5f, 0.5f, 1, kEnd, kEnd, 0}, {0, 0.5f, 0.5f, 0, kEnd, 0}};
        else if (c.prim == GE_PRIM_RECTANGLES)
            v = {{0, 0, 1, 0, 0, 0}, {0.5f, 1, 1, 0.5f, 1, 0}, {0.5f, 0, 1, 0.5f, 0, 0}, {1, 1, 0.5f, 1, 1, 0}};
        else
            v = {{0, 0, 1, 0, 0, 0}, {1, 0, 1, 1, 0, 0}, {1, 1, 1, 1, 1, 0}, {0, 1, 0.5f, 0, 1, 0}};
        ListBuilder& l = t.begin(kNormal);
        t.draw(l, c.prim, vt::NRM_F | vt::POS_F, v);
        t.end(c.name, c.hw);
    }
    return t.run();
}

TestRun runSource(GuSim& gu) {
    TexMtxTest t(gu, "texmtx/source");
    t.init();
    static constexpr const char* kGroups[4] = {"Common", "Without UV / normal", "Flat", "Through"};
    static constexpr const char* kSources[5] = {"Position", "UV", "Normal", "Normalized normal", "Unknown"};
    // On a PSP, per group (drawBoxCommandsAll, drawBoxCommandsPos, flat, through) and source.
    static constexpr Corners kHardware[4][5] = {
        {{0x44ff0000, 0x44ff00ff, 0x44ffff00, 0x44ffffff}, {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf},
         {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f}, {0x44ff6900, 0x44ff5d5d, 0x44ff0000, 0x44ff0069},
         {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f}},
        {{0x44ff0000, 0x44ff00ff, 0x44ffff00, 0x44ffffff}, {0x44ff40c0, 0x44ff40c0, 0x44ff40c0, 0x44ff40c0},
         {0x44ff8080, 0x44ff8080, 0x44ff8080, 0x44ff8080}, {0x44ff5d5d, 0x44ff5d5d, 0x44ff5d5d, 0x44ff5d5d},
         {0x44ff8080, 0x44ff8080, 0x44ff8080, 0x44ff8080}},
        {{0x44ff0000, 0x44ff00ff, 0x44ffff00, 0x44ffffff}, {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf},
         {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f}, {0x44ff6900, 0x44ff5d5d, 0x44ff0000, 0x44ff0069},
         {0x44ff7f00, 0x44ff7f7f, 0x44ff0000, 0x44ff007f}},
        {{0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf}, {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf},
         {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf}, {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf},
         {0x44ff4040, 0x44ff40bf, 0x44ffbf40, 0x44ffbfbf}}};
    for (int g = 0; g < 4; ++g)
        for (u32 src = 0; src < 5; ++src) {
            // testSource's modes in order: GU_POSITION, GU_UV, GU_NORMAL, GU_NORMALIZED_NORMAL, and 3
            // as "Unknown" (which is GU_NORMAL's value).
            static constexpr u32 kModes[5] = {kPosition, kUv, kNormal, kNormalizedNormal, 3};
            ListBuilder& l = t.begin(kModes[src]);
            l.shadeModel(g != 2);
            if (g == 0 || g == 2) {
                t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos, kQuadAll);
            } else if (g == 1) {
                // drawBoxCommandsPos: a sprite with UV and normal first, then the quad with positions only.
                t.draw(l, GE_PRIM_RECTANGLES, kUvNormalPos, {{0, 0, 0, 1, 1, 0, 0, 0}, {0.75f, 0.25f, 1, 1, 1, 1, 0, 0}});
                t.draw(l, GE_PRIM_TRIANGLE_FAN, vt::POS_F, {{0, 0, -0.5f}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
            } else {
                t.draw(l, GE_PRIM_TRIANGLE_FAN, kUvNormalPos | vt::THROUGH,
                       {{64, 64, 0, 1, 1, 0, 0, -32767}, {192, 64, 1, 1, 1, 256, 0, 0}, {192, 192, 1, 0, 1, 256, 256, 0},
                        {64, 192, 0, 0, 0.5f, 0, 256, 0}});
            }
            t.end(std::string(kGroups[g]) + ": " + kSources[src], kHardware[g][src]);
        }
    return t.run();
}

CONFORMANCE_TEST(TexMtxUvs, runUvs)
CONFORMANCE_TEST(TexMtxNormals, runNormals)
CONFORMANCE_TEST(TexMtxPrims, runPrims)
CONFORMANCE_TEST(TexMtxSource, runSource)

}  // namespace
}  // namespace ge::conformance
