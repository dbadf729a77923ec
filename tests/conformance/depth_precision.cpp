// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/depth/precision, re-created (gu_sim.h). A textured sprite at
// depth 0x1234 (through mode) or at a 16-bit transform-mode Z that the viewport maps to about
// 0x1234 is drawn over a depth buffer cleared to 0x1233, 0x1234 or 0x1235 with each depth
// function; pixel 0's red byte says whether it passed. Then the same with the projection moved by
// ±0.00005 / ±0.00002 in Z and with viewport Z centres of 32767.0, 32768.0 and 32767.5: where
// the GE's depth arithmetic rounds. PPSSPP fails parts of this test (docs/conformance.md).
#include "tests/conformance/conformance.h"

#include <cstring>

namespace ge::conformance {
namespace {

// The test's Vertex {u16 u, v; s16 x, y, z} for GU_TEXTURE_16BIT | GU_VERTEX_16BIT.
std::vector<u8> spriteVertices(const s32 (&v)[2][5]) {
    std::vector<u8> out(20);
    for (int i = 0; i < 2; ++i)
        for (int k = 0; k < 5; ++k) writeLE16(&out[size_t(i) * 10 + size_t(k) * 2], u16(v[i][k]));
    return out;
}

constexpr s32 kThrough[2][5] = {{0, 0, 0, 0, 0x1234}, {2, 2, 32, 32, 0x1234}};
constexpr s32 kTransform[2][5] = {{0, 0, -32768, 32767, 0x6DCC}, {32768, 32768, 32767, -32768, 0x6DCC}};

struct Row {
    const char* name;
    u16 initZ;
    u32 func;  // GE depth function: 1 ALWAYS, 4 LESS, 5 LEQUAL, 6 GREATER, 7 GEQUAL
};
constexpr Row kRows[13] = {{"1234 -> 0000", 0, 1},        {"1234 <  1233", 0x1233, 4}, {"1234 <= 1233", 0x1233, 5},
                           {"1234 >  1233", 0x1233, 6},   {"1234 >= 1233", 0x1233, 7}, {"1234 <  1234", 0x1234, 4},
                           {"1234 <= 1234", 0x1234, 5},   {"1234 >  1234", 0x1234, 6}, {"1234 >= 1234", 0x1234, 7},
                           {"1234 <  1235", 0x1235, 4},   {"1234 <= 1235", 0x1235, 5}, {"1234 >  1235", 0x1235, 6},
                           {"1234 >= 1235", 0x1235, 7}};

struct Group {
    const char* name;
    bool through;
    float projZ;   // projection element 11 (the Z row's translation), 0: identity
    float zScale;  // viewport Z scale and centre (VIEWPORTZ1/Z2)
    float zCentre;
    u8 hardware[13];  // pixel 0's red byte read back on a PSP, per row
};
constexpr Group kGroups[] = {
    {"Through mode", true, 0, -32767.5f, 32767.5f, {0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0}},
    {"Full transform", false, 0, -32767.5f, 32767.5f, {0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0}},
    {"Full transform (+0.00005f)", false, 0.00005f, -32767.5f, 32767.5f,
     {0xff, 0, 0, 0xff, 0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff}},
    {"Full transform (+0.00002f)", false, 0.00002f, -32767.5f, 32767.5f,
     {0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0}},
    {"Full transform (-0.00005f)", false, -0.00005f, -32767.5f, 32767.5f,
     {0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0, 0xff, 0xff, 0, 0}},
    {"Full transform (-0.00002f)", false, -0.00002f, -32767.5f, 32767.5f,
     {0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0}},
    {"Full transform (depth range = 32767.0f)", false, 0, -32767.5f, 32767.0f,
     {0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0, 0xff, 0xff, 0, 0}},
    {"Full transform (depth range = 32768.0f)", false, 0, -32767.5f, 32768.0f,
     {0xff, 0, 0, 0xff, 0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff}},
    {"Full transform (depth range = 32767.5f)", false, 0, -32767.5f, 32767.5f,
     {0xff, 0, 0, 0xff, 0xff, 0, 0xff, 0, 0xff, 0xff, 0xff, 0, 0}},
};

void setZViewport(ListBuilder& b, float scale, float centre) {
    b.cmdf(GE_CMD_SZ, scale);
    b.cmdf(GE_CMD_TZ, centre);
    b.cmd(GE_CMD_MINZ, 0);
    b.cmd(GE_CMD_MAXZ, 65535);
}

TestRun runDepthPrecision(GuSim& gu) {
    TestRun run{"depth/precision", gu.backend(), {}};
    constexpr u32 kDepth = 512 * 272 * 4;  // dbp0
    gu.init();
    ListBuilder& b = gu.start();
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0, 512);
    b.depthBuffer(kDepth, 512);
    sdkDispBuffer(b);
    b.scissor(0, 0, 480, 272);
    b.offset(2048 - 240, 2048 - 136);
    b.viewport(2048, 2048, 480, 272);
    b.depthMask(false);
    setZViewport(b, -32767.5f, 32767.5f);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(1);
    b.cullMode(false);
    b.shadeModel(true);
    setIdentityMatrices(b);
    gu.finishSync();

    const u32 image[8] = {0x000000FF, 0x000000FF, 0, 0, 0x000000FF, 0x000000FF, 0, 0};
    for (const Group& g : kGroups) {
        if (!g.through) {
            // setTranslateMatrix(GU_PROJECTION, amount) / setDepthRange(range): a list of their own.
            ListBuilder& m = gu.start();
            float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
            proj[11] = g.projZ;
            static constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
            m.setMatrix(GeMatrix::World, kIdentity);
            m.setMatrix(GeMatrix::View, kIdentity);
            m.setMatrix(GeMatrix::Proj, proj);
            setZViewport(m, g.zScale, g.zCentre);
            gu.finishSync();
        }
        for (int r = 0; r < 13; ++r) {
            const Row& row = kRows[r];
            // resetDepth: the CPU writes a cleared frame and the 2x2 depth corner, then a clear.
            gu.fillVram32(0, 0, 512 * 272);
            std::vector<u16> depth(512 * 272, 0);
            depth[0] = depth[1] = depth[512] = depth[513] = row.initZ;
            gu.writeVram(kDepth, depth.data(), u32(depth.size() * 2));
            ListBuilder& c = gu.start();
            c.clear(CLEAR_DEPTH | CLEAR_COLOR, 0, row.initZ);
            gu.finishSync();
            // drawTexFlush
            ListBuilder& d = gu.start();
            d.enable(GE_CMD_TME, true);
            d.texMode(GE_TFMT_8888, 0, false);
            d.texFunc(1 /*DECAL*/, false);
            d.setTexture(0, d.place(image, sizeof image), 2, 2, 4);
            d.depthFunc(row.func);
            const u32 vtype = vt::TC_16 | vt::POS_16 | (g.through ? vt::THROUGH : 0);
            const std::vector<u8> verts = spriteVertices(g.through ? kThrough : kTransform);
            d.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, verts.data());
            gu.finishSync();
            run.checkpoints.push_back({std::string(g.name) + ": " + row.name, g.hardware[r], gu.readVram32(0), 0xFF});
        }
    }
    return run;
}

CONFORMANCE_TEST(DepthPrecision, runDepthPrecision)

}  // namespace
}  // namespace ge::conformance
