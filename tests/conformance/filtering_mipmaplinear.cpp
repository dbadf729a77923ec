// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/filtering/mipmaplinear, re-created (gu_sim.h, conformance.h). Two
// mipmap levels — level 0 a 2x2 8888 texture of one colour, level 1 a 1x1 texture of another (buffer
// width 4 each) — are drawn with NEAREST_MIPMAP_LINEAR for both filters by the transform-mode sprite
// of the filtering tests (pixels (0, 0)-(2, 2), float texture coordinates 0..1, REPLACE/RGBA), in
// the level mode SLOPE with bias 0 and a texture slope walked from 0 to 1.0625: first blue against
// green, then 0xfdfeff against transparent black in 1/256 steps, then every grey level against
// transparent black at slope 0.5. Pixel 0 is read back after each draw (the first 512 words of VRAM
// are reset to 0x44444444; stencil is off, so alpha stays 0x44). The values show where the GE moves
// from level 0 to level 1 and how it weighs the two levels.
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// On a PSP: pixel 0 after each draw, in order (Initial, Common, Offsets, Blend at, Half blends).
constexpr u32 kHardware[530] = {
    0x44444444, 0x440000ff, 0x4400ff00, 0x4400ff00, 0x4400ff00, 0x4400ff00, 0x4400ff00, 0x4400ff00,
    0x4400ff00, 0x440000ff, 0x440000ff, 0x440000ff, 0x440000ff, 0x440000ff, 0x440000ff, 0x440000ff,
    0x440000ff, 0x440000ff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff, 0x44fdfeff,
    0x44fdfeff, 0x44fdfeff, 0x44edeeef, 0x44edeeef, 0x44edeeef, 0x44edeeef, 0x44edeeef, 0x44edeeef,
    0x44edeeef, 0x44edeeef, 0x44dddedf, 0x44dddedf, 0x44dddedf, 0x44dddedf, 0x44dddedf, 0x44dddedf,
    0x44dddedf, 0x44dddedf, 0x44cdcecf, 0x44cdcecf, 0x44cdcecf, 0x44cdcecf, 0x44cdcecf, 0x44cdcecf,
    0x44cdcecf, 0x44cdcecf, 0x44bdbebf, 0x44bdbebf, 0x44bdbebf, 0x44bdbebf, 0x44bdbebf, 0x44bdbebf,
    0x44bdbebf, 0x44bdbebf, 0x44adaeaf, 0x44adaeaf, 0x44adaeaf, 0x44adaeaf, 0x44adaeaf, 0x44adaeaf,
    0x44adaeaf, 0x44adaeaf, 0x449e9e9f, 0x449e9e9f, 0x449e9e9f, 0x449e9e9f, 0x449e9e9f, 0x449e9e9f,
    0x449e9e9f, 0x449e9e9f, 0x448e8e8f, 0x448e8e8f, 0x448e8e8f, 0x448e8e8f, 0x448e8e8f, 0x448e8e8f,
    0x448e8e8f, 0x448e8e8f, 0x447e7f7f, 0x447e7f7f, 0x447e7f7f, 0x447e7f7f, 0x447e7f7f, 0x447e7f7f,
    0x447e7f7f, 0x447e7f7f, 0x446e6f6f, 0x446e6f6f, 0x446e6f6f, 0x446e6f6f, 0x446e6f6f, 0x446e6f6f,
    0x446e6f6f, 0x446e6f6f, 0x445e5f5f, 0x445e5f5f, 0x445e5f5f, 0x445e5f5f, 0x445e5f5f, 0x445e5f5f,
    0x445e5f5f, 0x445e5f5f, 0x444f4f4f, 0x444f4f4f, 0x444f4f4f, 0x444f4f4f, 0x444f4f4f, 0x444f4f4f,
    0x444f4f4f, 0x444f4f4f, 0x443f3f3f, 0x443f3f3f, 0x443f3f3f, 0x443f3f3f, 0x443f3f3f, 0x443f3f3f,
    0x443f3f3f, 0x443f3f3f, 0x442f2f2f, 0x442f2f2f, 0x442f2f2f, 0x442f2f2f, 0x442f2f2f, 0x442f2f2f,
    0x442f2f2f, 0x442f2f2f, 0x441f1f1f, 0x441f1f1f, 0x441f1f1f, 0x441f1f1f, 0x441f1f1f, 0x441f1f1f,
    0x441f1f1f, 0x441f1f1f, 0x440f0f0f, 0x440f0f0f, 0x440f0f0f, 0x440f0f0f, 0x440f0f0f, 0x440f0f0f,
    0x440f0f0f, 0x440f0f0f, 0x44000000, 0x44010101, 0x44020202, 0x44030303, 0x44040404, 0x44050505,
    0x44060606, 0x44070707, 0x44080808, 0x44090909, 0x440a0a0a, 0x440b0b0b, 0x440c0c0c, 0x440d0d0d,
    0x440e0e0e, 0x440f0f0f, 0x44101010, 0x44111111, 0x44121212, 0x44131313, 0x44141414, 0x44151515,
    0x44161616, 0x44171717, 0x44181818, 0x44191919, 0x441a1a1a, 0x441b1b1b, 0x441c1c1c, 0x441d1d1d,
    0x441e1e1e, 0x441f1f1f, 0x44202020, 0x44212121, 0x44222222, 0x44232323, 0x44242424, 0x44252525,
    0x44262626, 0x44272727, 0x44282828, 0x44292929, 0x442a2a2a, 0x442b2b2b, 0x442c2c2c, 0x442d2d2d,
    0x442e2e2e, 0x442f2f2f, 0x44303030, 0x44313131, 0x44323232, 0x44333333, 0x44343434, 0x44353535,
    0x44363636, 0x44373737, 0x44383838, 0x44393939, 0x443a3a3a, 0x443b3b3b, 0x443c3c3c, 0x443d3d3d,
    0x443e3e3e, 0x443f3f3f, 0x44404040, 0x44414141, 0x44424242, 0x44434343, 0x44444444, 0x44454545,
    0x44464646, 0x44474747, 0x44484848, 0x44494949, 0x444a4a4a, 0x444b4b4b, 0x444c4c4c, 0x444d4d4d,
    0x444e4e4e, 0x444f4f4f, 0x44505050, 0x44515151, 0x44525252, 0x44535353, 0x44545454, 0x44555555,
    0x44565656, 0x44575757, 0x44585858, 0x44595959, 0x445a5a5a, 0x445b5b5b, 0x445c5c5c, 0x445d5d5d,
    0x445e5e5e, 0x445f5f5f, 0x44606060, 0x44616161, 0x44626262, 0x44636363, 0x44646464, 0x44656565,
    0x44666666, 0x44676767, 0x44686868, 0x44696969, 0x446a6a6a, 0x446b6b6b, 0x446c6c6c, 0x446d6d6d,
    0x446e6e6e, 0x446f6f6f, 0x44707070, 0x44717171, 0x44727272, 0x44737373, 0x44747474, 0x44757575,
    0x44767676, 0x44777777, 0x44787878, 0x44797979, 0x447a7a7a, 0x447b7b7b, 0x447c7c7c, 0x447d7d7d,
    0x447e7e7e, 0x447f7f7f, 0x44808080, 0x44818181, 0x44828282, 0x44838383, 0x44848484, 0x44858585,
    0x44868686, 0x44878787, 0x44888888, 0x44898989, 0x448a8a8a, 0x448b8b8b, 0x448c8c8c, 0x448d8d8d,
    0x448e8e8e, 0x448f8f8f, 0x44909090, 0x44919191, 0x44929292, 0x44939393, 0x44949494, 0x44959595,
    0x44969696, 0x44979797, 0x44989898, 0x44999999, 0x449a9a9a, 0x449b9b9b, 0x449c9c9c, 0x449d9d9d,
    0x449e9e9e, 0x449f9f9f, 0x44a0a0a0, 0x44a1a1a1, 0x44a2a2a2, 0x44a3a3a3, 0x44a4a4a4, 0x44a5a5a5,
    0x44a6a6a6, 0x44a7a7a7, 0x44a8a8a8, 0x44a9a9a9, 0x44aaaaaa, 0x44ababab, 0x44acacac, 0x44adadad,
    0x44aeaeae, 0x44afafaf, 0x44b0b0b0, 0x44b1b1b1, 0x44b2b2b2, 0x44b3b3b3, 0x44b4b4b4, 0x44b5b5b5,
    0x44b6b6b6, 0x44b7b7b7, 0x44b8b8b8, 0x44b9b9b9, 0x44bababa, 0x44bbbbbb, 0x44bcbcbc, 0x44bdbdbd,
    0x44bebebe, 0x44bfbfbf, 0x44c0c0c0, 0x44c1c1c1, 0x44c2c2c2, 0x44c3c3c3, 0x44c4c4c4, 0x44c5c5c5,
    0x44c6c6c6, 0x44c7c7c7, 0x44c8c8c8, 0x44c9c9c9, 0x44cacaca, 0x44cbcbcb, 0x44cccccc, 0x44cdcdcd,
    0x44cecece, 0x44cfcfcf, 0x44d0d0d0, 0x44d1d1d1, 0x44d2d2d2, 0x44d3d3d3, 0x44d4d4d4, 0x44d5d5d5,
    0x44d6d6d6, 0x44d7d7d7, 0x44d8d8d8, 0x44d9d9d9, 0x44dadada, 0x44dbdbdb, 0x44dcdcdc, 0x44dddddd,
    0x44dedede, 0x44dfdfdf, 0x44e0e0e0, 0x44e1e1e1, 0x44e2e2e2, 0x44e3e3e3, 0x44e4e4e4, 0x44e5e5e5,
    0x44e6e6e6, 0x44e7e7e7, 0x44e8e8e8, 0x44e9e9e9, 0x44eaeaea, 0x44ebebeb, 0x44ececec, 0x44ededed,
    0x44eeeeee, 0x44efefef, 0x44f0f0f0, 0x44f1f1f1, 0x44f2f2f2, 0x44f3f3f3, 0x44f4f4f4, 0x44f5f5f5,
    0x44f6f6f6, 0x44f7f7f7, 0x44f8f8f8, 0x44f9f9f9, 0x44fafafa, 0x44fbfbfb, 0x44fcfcfc, 0x44fdfdfd,
    0x44fefefe, 0x44ffffff,
};

constexpr float kOffsets[15] = {1.0625f,    1.001953125f, 1.0009765625f, 1.00048828125f, 1.000244140625f,
                                1.0001220703125f, 0.5f, 0.25f, 0.125f, 0.0625f, 0.03125f, 0.015625f,
                                0.0078125f, 0.00390625f, 0.001953125f};

constexpr u32 kTexture = 0x08400000, kTexture2 = 0x08400040;  // texdata[16], texdata2[16], 16-byte aligned

class MipmapLinearTest {
public:
    explicit MipmapLinearTest(GuSim& gu) : gu_(gu), run_{"filtering/mipmaplinear", gu.backend(), {}} {}

    TestRun run() {
        gu_.init();
        filteringInitDisplay(gu_.start());
        gu_.finishSync();
        clear();
        read("Initial");

        draw("Even (slope 0)", 0xFF0000FF, 0xFF00FF00, 0.0f);
        draw("One level offset (slope 1)", 0xFF0000FF, 0xFF00FF00, 1.0f);
        for (const float off : kOffsets) {
            char name[64];
            std::snprintf(name, sizeof name, "Offset (slope %.13g)", double(off));
            draw(name, 0xFF0000FF, 0xFF00FF00, off);
        }
        for (int i = 0; i < 256; ++i)
            draw("Blend at " + std::to_string(i) + " (slope " + std::to_string(i) + "/256)", 0xFFFDFEFF, 0,
                 float(i) / 256.0f);
        for (u32 i = 0; i < 256; ++i)
            draw(std::to_string(i) + " * half (slope 0.5)", 0xFF000000 | (i << 16) | (i << 8) | i, 0, 0.5f);
        return run_;
    }

private:
    // clearDispBuffer(0x44444444) with readFull off: the first 512 words.
    void clear() { gu_.fillVram32(0, 0x44444444, 512); }

    void read(const std::string& name) {
        const size_t n = run_.checkpoints.size();
        run_.checkpoints.push_back({name, kHardware[n], gu_.readVram32(0)});
        clear();
    }

    // testTexLinear(title, c1, c2, slope) in the test's TEST_SLOPE mode: level 0 all c1, level 1 all
    // c2; the texture words are rewritten, and TEX images/flush/sync sent, only when they change.
    void draw(const std::string& name, u32 c1, u32 c2, float slope) {
        ListBuilder& l = gu_.start();
        l.texFilter(6, 6);                 // GU_NEAREST_MIPMAP_LINEAR, both
        l.texMode(GE_TFMT_8888, 1, false);  // sceGuTexMode(GU_PSM_8888, 1, 0, 0)
        l.cmd(GE_CMD_TLEVEL, 2);            // sceGuTexLevelMode(GU_TEXTURE_SLOPE, 0.0f)
        l.texSlope(slope);
        if (tex_[0] != c1 || tex2_[0] != c2 || texDirty_) {
            for (u32& t : tex_) t = c1;
            for (u32& t : tex2_) t = c2;
            gu_.cpuWrite(kTexture, tex_, sizeof tex_);
            gu_.cpuWrite(kTexture2, tex2_, sizeof tex2_);
            l.setTexture(0, kTexture, 2, 2, 4);   // sceGuTexImage(0, 2, 2, 4, texdata)
            l.setTexture(1, kTexture2, 1, 1, 4);  // sceGuTexImage(1, 1, 1, 4, texdata2)
            l.texFlush();
            l.texSync();
            texDirty_ = false;
        }
        // drawBoxCommands(0xFFFFFFFF, slope, slope): the TEST_SLOPE box, 2/240 by 2/136.
        const float wv = float(2.0 / 240.0), hv = float(2.0 / 136.0);
        const std::vector<u8> data =
            uvColorPosF({{0.0f, 0.0f, -1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, -1.0f + wv, 1.0f - hv, 0.0f}}, 0xFFFFFFFF);
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_F | vt::COL_8888 | vt::POS_F, 2, nullptr, data.data());
        gu_.finishSync();
        read(name);
    }

    GuSim& gu_;
    TestRun run_;
    u32 tex_[16] = {0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF,
                    0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF};
    u32 tex2_[16] = {0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF,
                     0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF};
    bool texDirty_ = true;
};

TestRun runMipmapLinear(GuSim& gu) { return MipmapLinearTest(gu).run(); }

CONFORMANCE_TEST(FilteringMipmapLinear, runMipmapLinear)

}  // namespace
}  // namespace ge::conformance
