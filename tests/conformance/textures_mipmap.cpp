// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/textures/mipmap, re-created (gu_sim.h, conformance.h). An 8888
// texture with 8 levels (256x256 halving to 2x2, level l filled with 0x10 * l grey; buffer width at
// least 4, each level 16-byte aligned after the previous one), NEAREST_MIPMAP_LINEAR, clamped,
// DECAL/RGB, texture slope 2.0, drawn by a through-mode sprite at 1:1, magnified 4x, minified 2x,
// 4x in one direction, 64x and 256x; for each level mode (AUTO, CONST, SLOPE, and the undefined 3)
// and each LOD bias (0x00-0xF0, signed 4.4). Pixel 0's RGB is read back after each draw.
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// On a PSP, per mode (AUTO, CONST, SLOPE, 3) and bias, the seven boxes of testMipDrawing().
constexpr u32 kHardware[308] = {
    0x000000, 0x000000, 0x101010, 0x202020, 0x202020, 0x606060, 0x707070,
    0x070707, 0x000000, 0x171717, 0x272727, 0x272727, 0x676767, 0x707070,
    0x080808, 0x000000, 0x181818, 0x282828, 0x282828, 0x686868, 0x707070,
    0x101010, 0x000000, 0x202020, 0x303030, 0x303030, 0x707070, 0x707070,
    0x707070, 0x505050, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x575757, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x585858, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x070707,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x080808,
    0x000000, 0x000000, 0x000000, 0x101010, 0x101010, 0x505050, 0x707070,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x070707, 0x070707, 0x070707, 0x070707, 0x070707, 0x070707, 0x070707,
    0x080808, 0x080808, 0x080808, 0x080808, 0x080808, 0x080808, 0x080808,
    0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x202020, 0x202020, 0x202020, 0x202020, 0x202020, 0x202020, 0x202020,
    0x272727, 0x272727, 0x272727, 0x272727, 0x272727, 0x272727, 0x272727,
    0x282828, 0x282828, 0x282828, 0x282828, 0x282828, 0x282828, 0x282828,
    0x303030, 0x303030, 0x303030, 0x303030, 0x303030, 0x303030, 0x303030,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x070707, 0x070707, 0x070707, 0x070707, 0x070707, 0x070707, 0x070707,
    0x080808, 0x080808, 0x080808, 0x080808, 0x080808, 0x080808, 0x080808,
    0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010, 0x101010,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070, 0x707070,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
    0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000, 0x000000,
};
constexpr u8 kBiases[11] = {0x00, 0x07, 0x08, 0x10, 0x70, 0x77, 0x78, 0x80, 0x87, 0x88, 0xF0};
constexpr const char* kModes[4] = {"AUTO", "CONST", "SLOPE", "3"};
constexpr const char* kBoxes[7] = {"1:1", "Magnify", "Minify 2x WH", "Minify 4x W", "Minify 4x H", "Minify 64x", "Minify 256x"};
// verticesThrough: (u, v, x, y) of the far corner; the near one is all zero.
constexpr u16 kFar[7][4] = {{2, 2, 2, 2}, {2, 2, 8, 8}, {4, 4, 2, 2}, {8, 1, 2, 2}, {1, 8, 2, 2}, {64, 64, 1, 1}, {256, 256, 1, 1}};

constexpr u32 kImage = 0x08400000;  // memalign(16, 4 * 256 * 344)

// getTexturePtr(IMG_HALVES, l): word offset of level l.
u32 levelWords(int l) {
    u32 p = 0, w = 256;
    while (l-- > 0) {
        p += w * w;
        p = (p + 3) & ~3u;
        w >>= 1;
    }
    return p;
}

TestRun runMipmap(GuSim& gu) {
    TestRun run{"textures/mipmap", gu.backend(), {}};
    gu.init();
    ListBuilder& b = gu.start();  // init()
    sdkFrameSetup(b, {});
    b.depthRange(65535, 65500);
    b.shadeModel(true);
    setIdentityMatrices(b);
    gu.finishSync();
    gu.fillVram32(0, 0, 512 * 272);
    // setupTexture(): level l is 0xFF000000 | 0x101010 * l over bufw * w words.
    for (int l = 0; l < 8; ++l) {
        const u32 w = 256u >> l, bufw = w < 4 ? 4 : w;
        const std::vector<u32> texels(bufw * w, 0xFF000000u | (0x101010u * u32(l)));
        gu.cpuWrite(kImage + levelWords(l) * 4, texels.data(), u32(texels.size() * 4));
    }
    gu.start().texFilter(6, 6);  // GU_NEAREST_MIPMAP_LINEAR for both
    gu.finishSync();

    size_t n = 0;
    for (u32 mode = 0; mode < 4; ++mode)
        for (const u8 bias : kBiases)
            for (int box = 0; box < 7; ++box) {
                ListBuilder& l = gu.start();  // drawTexFlush()
                l.enable(GE_CMD_TME, true);
                l.texSync();
                l.texFlush();
                l.cmd(GE_CMD_TLEVEL, (u32(bias) << 16) | mode);
                l.texMode(GE_TFMT_8888, 7, false);
                l.texWrap(true, true);
                l.texFunc(1 /*DECAL*/, false);
                l.texSlope(2.0f);
                for (int lv = 0; lv < 8; ++lv) {
                    const u32 w = 256u >> lv;
                    l.setTexture(u32(lv), kImage + levelWords(lv) * 4, w, w, w < 4 ? 4 : w);
                }
                const std::vector<u8> v = spriteUv16(kFar[box][0], kFar[box][1], kFar[box][2], kFar[box][3]);
                l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, v.data());
                gu.finishSync();
                char name[80];
                std::snprintf(name, sizeof name, "%s +%02x %s", kModes[mode], bias, kBoxes[box]);
                run.checkpoints.push_back({name, kHardware[n++], gu.readVram32(0), 0x00FFFFFF});
                gu.fillVram32(0, 0, 512 * 272);
            }
    return run;
}

CONFORMANCE_TEST(TexturesMipmap, runMipmap)

}  // namespace
}  // namespace ge::conformance
