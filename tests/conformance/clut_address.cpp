// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/clut/address, re-created (gu_sim.h, conformance.h). A 1x1
// CLUT32-indexed texture (index 0) covers the screen; the palette is loaded from
// clutPattern + offset (8 words 0x11111111 … 0x88888888) with offsets 0–16 bytes, then from the
// last 16 bytes of VRAM's mirrors (0x047FFFF0) with 0–63 blocks, then from just past the mirrors
// (0x04800010), then from 0x047FFFF0 again. Pixel 0's RGB is read back after each draw. The issue
// lists this test as one where ge2gl fell short.
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

constexpr u32 kPattern = 0x08400000;  // clutPattern (16-byte aligned, as the test's array)
constexpr u32 kImage = 0x08400100;    // imageData[16] = {0}
constexpr u32 kVramEnd = Memory::kVramBase + Memory::kVramSize * 4;

struct Case {
    const char* name;
    u32 clut, blocks;
    u32 hardware;  // RGB of pixel 0 read back on a PSP
};
constexpr Case kCases[] = {
    {"Offset 0", kPattern + 0, 1, 0x111111},   {"Offset 1", kPattern + 1, 1, 0x111111},
    {"Offset 2", kPattern + 2, 1, 0x111111},   {"Offset 3", kPattern + 3, 1, 0x111111},
    {"Offset 4", kPattern + 4, 1, 0x111111},   {"Offset 8", kPattern + 8, 1, 0x111111},
    {"Offset 9", kPattern + 9, 1, 0x111111},   {"Offset 12", kPattern + 12, 1, 0x111111},
    {"Offset 15", kPattern + 15, 1, 0x111111}, {"Offset 16", kPattern + 16, 1, 0x555555},
    {"Blocks near edge 0", kVramEnd - 16, 0, 0x555555},   {"Blocks near edge 1", kVramEnd - 16, 1, 0x111111},
    {"Blocks near edge 2", kVramEnd - 16, 2, 0x111111},   {"Blocks near edge 3", kVramEnd - 16, 3, 0x111111},
    {"Blocks near edge 4", kVramEnd - 16, 4, 0x111111},   {"Blocks near edge 8", kVramEnd - 16, 8, 0x111111},
    {"Blocks near edge 9", kVramEnd - 16, 9, 0x111111},   {"Blocks near edge 12", kVramEnd - 16, 12, 0x111111},
    {"Blocks near edge 15", kVramEnd - 16, 15, 0x111111}, {"Blocks near edge 16", kVramEnd - 16, 16, 0x111111},
    {"Blocks near edge 63", kVramEnd - 16, 63, 0x111111}, {"Outside VRAM", kVramEnd + 16, 1, 0x000000},
    {"Reset", kVramEnd - 16, 1, 0x111111},
};

TestRun runClutAddress(GuSim& gu) {
    TestRun run{"clut/address", gu.backend(), {}};
    gu.init();
    clutInit(gu.start());
    gu.finishSync();
    gu.fillVram32(0, 0, 512 * 272);
    const u32 pattern[8] = {0x11111111, 0x22222222, 0x33333333, 0x44444444,
                            0x55555555, 0x66666666, 0x77777777, 0x88888888};
    gu.cpuWrite(kPattern, pattern, sizeof pattern);
    const u8 image[16] = {};
    gu.cpuWrite(kImage, image, sizeof image);
    gu.start().texFilter(0, 0);
    gu.finishSync();

    const std::vector<u8> verts = spriteUv16(480, 272, 480, 272);
    bool copiedToEdge = false;
    for (const Case& c : kCases) {
        if (!copiedToEdge && c.clut == kVramEnd - 16) {
            gu.start().texFilter(0, 0);  // drawNearEdge: memcpy to the mirrors' end, filter again
            gu.finishSync();
            gu.cpuWrite(kVramEnd - 16, pattern, 16);
            copiedToEdge = true;
        }
        ListBuilder& l = gu.start();
        l.enable(GE_CMD_TME, true);
        l.texMode(GE_TFMT_CLUT32, 0, false);
        l.texFunc(1 /*DECAL*/, false);
        l.setTexture(0, kImage, 1, 1, 16);
        l.clutLoad(c.clut, c.blocks);
        l.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, verts.data());
        gu.finishSync();
        run.checkpoints.push_back({c.name, c.hardware, gu.readVram32(0), 0x00FFFFFF});
        gu.fillVram32(0, 0, 512 * 272);
    }
    return run;
}

CONFORMANCE_TEST(ClutAddress, runClutAddress)

}  // namespace
}  // namespace ge::conformance
