// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/fog, re-created (gu_sim.h, conformance.h). A
// transform-mode sprite from (-1, -1, 0) to (1, 1, 0) with fog on over a 10x10 scissor, for fog
// near/far pairs (fog = (far - z) * 1/(far - near), sceGuFog sends 0 for 1/(far - near) when
// far == near); then immediate-mode sprites (CMD_X2 ... CMD_AP2 with the fog flag) whose fog factor
// is given per vertex (CMD_F2), 0x00, 0x80, 0xFF and then every value 0-255 with colour 0x11881100
// over fog colour 0xFFFF33FF: the rounding of the fog blend. VRAM's first 32 words are set to the
// previous colour 0x44444444 before each draw and pixel 0 is read back (alpha is kept: stencil off).
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// "Rounding:" on a PSP: RGB of pixel 0 for fog factors 0x00-0xFF (alpha 0x44 throughout).
constexpr u32 kRounding[256] = {
    0xff33ff, 0xfe33fe, 0xfe33fd, 0xfd33fc, 0xfd33fb, 0xfc33fa, 0xfc33f9, 0xfb32f8,
    0xfb32f7, 0xfa32f6, 0xfa32f5, 0xf932f4, 0xf932f3, 0xf832f2, 0xf831f1, 0xf831f0,
    0xf731ef, 0xf731ee, 0xf631ed, 0xf631ec, 0xf531eb, 0xf531ea, 0xf430e9, 0xf430e8,
    0xf330e7, 0xf330e6, 0xf230e5, 0xf230e4, 0xf130e3, 0xf12fe2, 0xf12fe1, 0xf02fe0,
    0xf02fdf, 0xef2fde, 0xef2fdd, 0xee2fdc, 0xee2fdb, 0xed2eda, 0xed2ed9, 0xec2ed8,
    0xec2ed7, 0xeb2ed6, 0xeb2ed5, 0xeb2ed4, 0xea2dd3, 0xea2dd2, 0xe92dd1, 0xe92dd0,
    0xe82dcf, 0xe82dce, 0xe72dcd, 0xe72dcc, 0xe62ccb, 0xe62cca, 0xe52cc9, 0xe52cc8,
    0xe42cc7, 0xe42cc6, 0xe42cc5, 0xe32bc4, 0xe32bc3, 0xe22bc2, 0xe22bc1, 0xe12bc0,
    0xe12bbf, 0xe02bbe, 0xe02bbd, 0xdf2abc, 0xdf2abb, 0xde2aba, 0xde2ab9, 0xdd2ab8,
    0xdd2ab7, 0xdd2ab6, 0xdc29b5, 0xdc29b4, 0xdb29b3, 0xdb29b2, 0xda29b1, 0xda29b0,
    0xd929af, 0xd929ae, 0xd828ad, 0xd828ac, 0xd728ab, 0xd728aa, 0xd728a9, 0xd628a8,
    0xd628a7, 0xd527a6, 0xd527a5, 0xd427a4, 0xd427a3, 0xd327a2, 0xd327a1, 0xd227a0,
    0xd2279f, 0xd1269e, 0xd1269d, 0xd0269c, 0xd0269b, 0xd0269a, 0xcf2699, 0xcf2698,
    0xce2597, 0xce2596, 0xcd2595, 0xcd2594, 0xcc2593, 0xcc2592, 0xcb2591, 0xcb2590,
    0xca248f, 0xca248e, 0xca248d, 0xc9248c, 0xc9248b, 0xc8248a, 0xc82489, 0xc72388,
    0xc72387, 0xc62386, 0xc62385, 0xc52384, 0xc52383, 0xc42382, 0xc42381, 0xc32280,
    0xc3227f, 0xc3227e, 0xc2227d, 0xc2227c, 0xc1227b, 0xc1227a, 0xc02279, 0xc02178,
    0xbf2177, 0xbf2176, 0xbe2175, 0xbe2174, 0xbd2173, 0xbd2172, 0xbc2071, 0xbc2070,
    0xbc206f, 0xbb206e, 0xbb206d, 0xba206c, 0xba206b, 0xb9206a, 0xb91f69, 0xb81f68,
    0xb81f67, 0xb71f66, 0xb71f65, 0xb61f64, 0xb61f63, 0xb61e62, 0xb51e61, 0xb51e60,
    0xb41e5f, 0xb41e5e, 0xb31e5d, 0xb31e5c, 0xb21e5b, 0xb21d5a, 0xb11d59, 0xb11d58,
    0xb01d57, 0xb01d56, 0xaf1d55, 0xaf1d54, 0xaf1c53, 0xae1c52, 0xae1c51, 0xad1c50,
    0xad1c4f, 0xac1c4e, 0xac1c4d, 0xab1c4c, 0xab1b4b, 0xaa1b4a, 0xaa1b49, 0xa91b48,
    0xa91b47, 0xa91b46, 0xa81b45, 0xa81a44, 0xa71a43, 0xa71a42, 0xa61a41, 0xa61a40,
    0xa51a3f, 0xa51a3e, 0xa41a3d, 0xa4193c, 0xa3193b, 0xa3193a, 0xa21939, 0xa21938,
    0xa21937, 0xa11936, 0xa11835, 0xa01834, 0xa01833, 0x9f1832, 0x9f1831, 0x9e1830,
    0x9e182f, 0x9d182e, 0x9d172d, 0x9c172c, 0x9c172b, 0x9b172a, 0x9b1729, 0x9b1728,
    0x9a1727, 0x9a1626, 0x991625, 0x991624, 0x981623, 0x981622, 0x971621, 0x971620,
    0x96161f, 0x96151e, 0x95151d, 0x95151c, 0x95151b, 0x94151a, 0x941519, 0x931518,
    0x931417, 0x921416, 0x921415, 0x911414, 0x911413, 0x901412, 0x901411, 0x8f1410,
    0x8f130f, 0x8e130e, 0x8e130d, 0x8e130c, 0x8d130b, 0x8d130a, 0x8c1309, 0x8c1208,
    0x8b1207, 0x8b1206, 0x8a1205, 0x8a1204, 0x891203, 0x891202, 0x881201, 0x881100,
};

class FogTest {
public:
    explicit FogTest(GuSim& gu) : gu_(gu) {}

    TestRun run() {
        TestRun out{"commands/fog", gu_.backend(), {}};
        run_ = &out;
        gu_.init();
        commandsInitDisplay(gu_.start(), {480, 272, 10, 10});  // init(): initDisplay with a 10x10 scissor
        gu_.finishSync();
        gu_.fillVram32(0, 0x44444444, 32);
        read("Initial", 0x44444444);

        fog("Basic", 1.0f, 1.0f, 0x44FFFFFF);
        fog("Near neg", -1.0f, 1.0f, 0x44C3C3C3);
        fog("Far neg", 1.0f, -1.0f, 0x44C3C3C3);
        fog("Both neg", -1.0f, -1.0f, 0x44FFFFFF);
        fog("Near zero", 0.0f, 1.0f, 0x44888888);
        fog("Far zero", 1.0f, 0.0f, 0x44FFFFFF);
        immFog("Direct fog 00", 0x88888888, 0xFFFFFFFF, 0x00, 0x44FFFFFF);
        immFog("Direct fog 80", 0x88888888, 0xFFFFFFFF, 0x80, 0x44C3C3C3);
        immFog("Direct fog FF", 0x88888888, 0xFFFFFFFF, 0xFF, 0x44888888);
        for (u32 i = 0; i < 256; ++i) {
            char name[32];
            std::snprintf(name, sizeof name, "Fog value %02x", i);
            immFog(name, 0x11881100, 0xFFFF33FF, u8(i), 0x44000000 | kRounding[i]);
        }
        return out;
    }

private:
    // displayBuffer(): pixel 0, then the 32 words reset to 0x44444444.
    void read(const std::string& name, u32 hardware) {
        run_->checkpoints.push_back({name, hardware, gu_.readVram32(0)});
        gu_.fillVram32(0, 0x44444444, 32);
    }

    ListBuilder& begin(float fogNear, float fogFar, u32 fogColor) {
        gu_.fillVram32(0, 0x44444444, 32);  // prev
        ListBuilder& b = gu_.start();
        b.enable(GE_CMD_ABE, false);
        b.enable(GE_CMD_STE, false);
        b.enable(GE_CMD_FGE, true);
        b.fog(fogNear, fogFar, fogColor);
        return b;
    }

    void fog(const std::string& name, float fogNear, float fogFar, u32 hardware) {
        ListBuilder& b = begin(fogNear, fogFar, 0xFFFFFFFF);
        // drawBoxCommands(0x88888888): VertexColorF32 {colour, x, y, z}, GU_TRANSFORM_3D sprites.
        BuildVertex v[2];
        v[0].color = v[1].color = 0x88888888;
        v[0].x = v[0].y = -1.0f;
        v[1].x = v[1].y = 1.0f;
        const std::vector<u8> data = packVertices(vt::COL_8888 | vt::POS_F, v, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, vt::COL_8888 | vt::POS_F, 2, nullptr, data.data());
        gu_.finishSync();
        read(name, hardware);
    }

    void immFog(const std::string& name, u32 c, u32 fogColor, u8 factor, u32 hardware) {
        ListBuilder& b = begin(0.0f, 1.0f, fogColor);
        // drawBoxCommandsImm: the vertex type, then two immediate vertices (GU_IMM_FOG is bit 22).
        constexpr u32 kImmFog = 0x00400000;
        b.cmd(GE_CMD_VTYPE, vt::COL_8888 | vt::POS_F);
        b.cmd(GE_CMD_X2, (2048 - 480 / 2) << 4);
        b.cmd(GE_CMD_Y2, (2048 - 272 / 2) << 4);
        b.cmd(GE_CMD_Z2, 0);
        b.cmd(GE_CMD_RGB2, c & 0x00FFFFFF);
        b.cmd(GE_CMD_I2, 0);
        b.cmd(GE_CMD_F2, factor);
        b.cmd(GE_CMD_AP2, kImmFog | (u32(GE_PRIM_RECTANGLES) << 8) | (c >> 24));
        b.cmd(GE_CMD_X2, (2048 + 480 / 2) << 4);
        b.cmd(GE_CMD_Y2, (2048 + 272 / 2) << 4);
        b.cmd(GE_CMD_AP2, kImmFog | (7u << 8) | (c >> 24));
        gu_.finishSync();
        read(name, hardware);
    }

    GuSim& gu_;
    TestRun* run_ = nullptr;
};

TestRun runFog(GuSim& gu) { return FogTest(gu).run(); }

CONFORMANCE_TEST(CommandsFog, runFog)

}  // namespace
}  // namespace ge::conformance
