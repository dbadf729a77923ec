// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/texcolors/rgb565, rgba5551 and rgba4444, re-created (gu_sim.h,
// conformance.h). An 8x8 texture of one 16-bit texel value (white, a dark red, a grey, a brown),
// nearest filtering, DECAL/RGB, clamped, drawn by a 2x2 through-mode sprite at (0, 0) into an 8888
// buffer; pixel 0's RGB is read back and the buffer zeroed. The values show how each 16-bit
// format widens to 8 bits (bit replication: 5 bits -> (v << 3) | (v >> 2), 4 bits -> v * 17).
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

struct Image {
    const char* name;
    u16 texel;
    u32 hardware;  // RGB of pixel 0 on a PSP
};
struct TexColorsTest {
    const char* test;
    u32 format;
    Image images[4];
};
constexpr TexColorsTest kTests[] = {
    {"texcolors/rgb565",
     GE_TFMT_5650,
     {{"White", 0xFFFF, 0xFFFFFF}, {"Red", 0x000E, 0x000073}, {"Gray", 0x8410, 0x848284}, {"Brown", 0x2825, 0x290429}}},
    {"texcolors/rgba5551",
     GE_TFMT_5551,
     {{"White", 0xFFFF, 0xFFFFFF}, {"Red", 0x000E, 0x000073}, {"Gray", 0x4210, 0x848484}, {"Brown", 0x9425, 0x290829}}},
    {"texcolors/rgba4444",
     GE_TFMT_4444,
     {{"White", 0xFFFF, 0xFFFFFF}, {"Red", 0x000F, 0x0000FF}, {"Gray", 0x8888, 0x888888}, {"Brown", 0x0525, 0x552255}}},
};

constexpr u32 kImages = 0x08400000;  // four memalign(16, 8 * 8 * 2) blocks, 256 bytes apart

TestRun runTexColors(GuSim& gu, const TexColorsTest& t) {
    TestRun run{t.test, gu.backend(), {}};
    gu.init();
    ListBuilder& b = gu.start();  // init(): as initDisplay, but depth range 65535-65500, dither off
    sdkFrameSetup(b, {});
    b.depthRange(65535, 65500);
    b.enable(GE_CMD_DTE, false);
    b.shadeModel(true);
    setIdentityMatrices(b);
    gu.finishSync();
    gu.fillVram32(0, 0, 512 * 272);
    gu.start().texFilter(0, 0);  // GU_NEAREST, GU_NEAREST
    gu.finishSync();

    // verticesThrough: (0, 0, 0, 0, 0) - (2, 2, 2, 2, 0).
    const std::vector<u8> verts = spriteUv16(2, 2, 2, 2);
    for (u32 i = 0; i < 4; ++i) {  // setupTexture()
        const std::vector<u16> texels(64, t.images[i].texel);
        gu.cpuWrite(kImages + i * 256, texels.data(), 128);
    }
    for (u32 i = 0; i < 4; ++i) {
        const Image& img = t.images[i];
        ListBuilder& l = gu.start();  // drawTexFlush()
        l.enable(GE_CMD_TME, true);
        l.texSync();
        l.texFlush();
        l.texMode(t.format, 0, false);
        l.texWrap(true, true);
        l.texFunc(1 /*DECAL*/, false);
        l.texSlope(2.0f);
        l.setTexture(0, kImages + i * 256, 8, 8, 8);
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, verts.data());
        gu.finishSync();
        run.checkpoints.push_back({img.name, img.hardware, gu.readVram32(0), 0x00FFFFFF});
        gu.fillVram32(0, 0, 512 * 272);
    }
    return run;
}

TestRun runRgb565(GuSim& gu) { return runTexColors(gu, kTests[0]); }
TestRun runRgba5551(GuSim& gu) { return runTexColors(gu, kTests[1]); }
TestRun runRgba4444(GuSim& gu) { return runTexColors(gu, kTests[2]); }

CONFORMANCE_TEST(TexColorsRgb565, runRgb565)
CONFORMANCE_TEST(TexColorsRgba5551, runRgba5551)
CONFORMANCE_TEST(TexColorsRgba4444, runRgba4444)

}  // namespace
}  // namespace ge::conformance
