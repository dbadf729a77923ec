// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/rendertarget/depal, re-created (gu_sim.h, conformance.h). A 1x1
// CLUT8 texture (index 0, palette "add one": entry i = i + 1) is drawn as a sprite over
// (10, 10)-(470, 262) into frame buffer 0; buffer 0 is then used as a 512x512 CLUT32 texture with the
// same palette over the whole screen of buffer 1; then buffer 1 is used as the texture of a draw
// into itself with a palette that moves red to green (entry i = i << 8). The whole 480x272 frame of
// buffer 1 is read back. The PSP's frame (printed as one line of hex values per row) is 0x200
// inside (10, 10)-(470, 262) and 0x100 elsewhere; each row is a checkpoint whose value is the count
// of pixels that differ from it (0 on hardware).
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

constexpr u32 kClutAddOne = 0x08400000, kClutRedToGreen = 0x08400020, kImage = 0x08400040;
constexpr u32 kBuffer1 = 512 * 272 * 4;  // getBufAddr(1), bytes from VRAM's start

u32 hardwarePixel(u32 x, u32 y) { return (x >= 10 && x < 470 && y >= 10 && y < 262) ? 0x200 : 0x100; }

TestRun runDepal(GuSim& gu) {
    TestRun run{"rendertarget/depal", gu.backend(), {}};
    gu.init();
    clutInit(gu.start());  // init()
    gu.finishSync();
    gu.fillVram32(0, 0, 512 * 272);
    const u32 addOne[8] = {1, 2, 3, 4, 5, 6, 7, 8}, redToGreen[8] = {0, 0x100, 0x200, 0x300, 0x400, 0x500, 0x600, 0x700};
    gu.cpuWrite(kClutAddOne, addOne, sizeof addOne);
    gu.cpuWrite(kClutRedToGreen, redToGreen, sizeof redToGreen);
    const u8 image[16] = {};
    gu.cpuWrite(kImage, image, sizeof image);
    gu.start().texFilter(0, 0);
    gu.finishSync();

    // switchBuf(i, 8888), then drawTexFlush(w, h, stride, fmt, tex, clut, verts).
    auto pass = [&](u32 buffer, u32 w, u32 h, u32 stride, u32 fmt, u32 tex, u32 clut, const std::vector<u8>& verts) {
        ListBuilder& s = gu.start();
        s.drawBuffer(GE_FORMAT_8888, buffer, 512);
        sdkDispBuffer(s);
        gu.finishSync();
        ListBuilder& l = gu.start();
        l.enable(GE_CMD_TME, true);
        l.texMode(fmt, 0, false);
        l.texFunc(1 /*DECAL*/, false);
        l.setTexture(0, tex, w, h, stride);
        l.clutLoad(clut, 1);
        l.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, verts.data());
        gu.finishSync();
    };
    // vertices1: (0, 0, 10, 10, 0) - (1, 1, 470, 262, 0); vertices2: (0, 0, 0, 0, 0) - (480, 272, 480, 272, 0).
    std::vector<u8> verts1 = spriteUv16(1, 1, 470, 262);
    writeLE16(&verts1[4], 10), writeLE16(&verts1[6], 10);
    const std::vector<u8> verts2 = spriteUv16(480, 272, 480, 272);
    pass(0, 1, 1, 16, GE_TFMT_CLUT8, kImage, kClutAddOne, verts1);
    pass(kBuffer1, 512, 512, 512, GE_TFMT_CLUT32, Memory::kVramBase, kClutAddOne, verts2);
    pass(kBuffer1, 512, 512, 512, GE_TFMT_CLUT32, Memory::kVramBase + kBuffer1, kClutRedToGreen, verts2);

    for (u32 y = 0; y < 272; ++y) {
        u32 differing = 0;
        for (u32 x = 0; x < 480; ++x) differing += gu.readVram32(kBuffer1 + (y * 512 + x) * 4) != hardwarePixel(x, y);
        run.checkpoints.push_back({"row " + std::to_string(y) + " (pixels differing)", 0, differing});
    }
    return run;
}

CONFORMANCE_TEST(RenderTargetDepal, runDepal)

}  // namespace
}  // namespace ge::conformance
