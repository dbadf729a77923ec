// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/clut/shifts, masks and offset, re-created (gu_sim.h,
// conformance.h). A 1x1 CLUT32 texture covers the screen (DECAL/RGB, nearest); the palette (word i
// = i * 0x01010101 for i < 256, then 256 words of 0xDEADBEEF) is loaded with 0xFF blocks and the
// CLUT mode's index shift, mask and start (offset) are varied, with 8888 and 4444 palette entries;
// pixel 0's RGB is read back after each draw. The values show the index the GE forms:
// ((texel >> shift) & mask) | (start << 4), the shift field 5 bits wide.
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

// On a PSP, RGB of pixel 0 in drawing order (8888 palette first, then 4444).
// clut/shifts: per shift, texel 0xFFFFFFFF then 0x12345678.
constexpr u32 kShiftsHardware[88] = {
    0xffffff, 0x787878, 0xffffff, 0x3c3c3c, 0xffffff, 0x9e9e9e, 0xffffff, 0xcfcfcf,
    0xffffff, 0x676767, 0xffffff, 0xb3b3b3, 0xffffff, 0x595959, 0xffffff, 0xacacac,
    0xffffff, 0x565656, 0xffffff, 0x2b2b2b, 0xffffff, 0x454545, 0xffffff, 0x686868,
    0xffffff, 0x343434, 0xffffff, 0x1a1a1a, 0xffffff, 0x232323, 0xffffff, 0x919191,
    0xffffff, 0x121212, 0x0f0f0f, 0x010101, 0x030303, 0x000000, 0x010101, 0x000000,
    0xffffff, 0x787878, 0xffffff, 0x3c3c3c, 0xff77ff, 0xcc33cc, 0xff77ff, 0xee11ee,
    0xff77ff, 0xff44ff, 0xff77ff, 0x776677, 0xff77ff, 0x333333, 0xff77ff, 0x995599,
    0xff77ff, 0xcc22cc, 0xff77ff, 0x665566, 0xff77ff, 0xbb22bb, 0xff77ff, 0x551155,
    0xff77ff, 0x222222, 0xff77ff, 0x443344, 0xff77ff, 0xaa11aa, 0xff77ff, 0xdd00dd,
    0xff77ff, 0x111111, 0xff77ff, 0x884488, 0xff77ff, 0x990099, 0x770077, 0x000000,
    0x110011, 0x000000, 0x000000, 0x000000, 0xff77ff, 0xcc33cc, 0xff77ff, 0xee11ee,
};
constexpr int kShifts[22] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 15, 16, 17, 20, 21, 24, 28, 30, 31, 32, 33};
// clut/masks: texel 255.
constexpr u32 kMasksHardware[16] = {
    0x000000, 0x010101, 0x020202, 0x0f0f0f, 0xf0f0f0, 0x777777, 0x808080,
    0x555555, 0x000000, 0x000000, 0x110011, 0x770077, 0x887788, 0xbb33bb,
    0x004400, 0xaa22aa,
};
constexpr int kMasks[8] = {0x00, 0x01, 0x02, 0x0F, 0xF0, 0x77, 0x80, 0x55};
// clut/offset: per offset, texels 0, 1, 15, 16, 255.
constexpr u32 kOffsetHardware[170] = {
    0x000000, 0x010101, 0x0f0f0f, 0x101010, 0xffffff, 0x101010, 0x111111,
    0x1f1f1f, 0x101010, 0xffffff, 0x202020, 0x212121, 0x2f2f2f, 0x303030, 0xffffff,
    0x303030, 0x313131, 0x3f3f3f, 0x303030, 0xffffff, 0x404040, 0x414141, 0x4f4f4f,
    0x505050, 0xffffff, 0x505050, 0x515151, 0x5f5f5f, 0x505050, 0xffffff, 0x606060,
    0x616161, 0x6f6f6f, 0x707070, 0xffffff, 0x707070, 0x717171, 0x7f7f7f, 0x707070,
    0xffffff, 0x808080, 0x818181, 0x8f8f8f, 0x909090, 0xffffff, 0x909090, 0x919191,
    0x9f9f9f, 0x909090, 0xffffff, 0xc0c0c0, 0xc1c1c1, 0xcfcfcf, 0xd0d0d0, 0xffffff,
    0xf0f0f0, 0xf1f1f1, 0xffffff, 0xf0f0f0, 0xffffff, 0x000000, 0x010101, 0x0f0f0f,
    0x101010, 0xffffff, 0x101010, 0x111111, 0x1f1f1f, 0x101010, 0xffffff, 0x505050,
    0x515151, 0x5f5f5f, 0x505050, 0xffffff, 0xe0e0e0, 0xe1e1e1, 0xefefef, 0xf0f0f0,
    0xffffff, 0xf0f0f0, 0xf1f1f1, 0xffffff, 0xf0f0f0, 0xffffff, 0x000000,
    0x000000, 0x770077, 0x880088, 0xff77ff, 0x880088, 0x880088, 0xff00ff, 0x880088,
    0xff77ff, 0x001100, 0x001100, 0x771177, 0x881188, 0xff77ff, 0x881188, 0x881188,
    0xff11ff, 0x881188, 0xff77ff, 0x002200, 0x002200, 0x772277, 0x882288, 0xff77ff,
    0x882288, 0x882288, 0xff22ff, 0x882288, 0xff77ff, 0x003300, 0x003300, 0x773377,
    0x883388, 0xff77ff, 0x883388, 0x883388, 0xff33ff, 0x883388, 0xff77ff, 0x004400,
    0x004400, 0x774477, 0x884488, 0xff77ff, 0x884488, 0x884488, 0xff44ff, 0x884488,
    0xff77ff, 0x006600, 0x006600, 0x776677, 0x886688, 0xff77ff, 0x887788, 0x887788,
    0xff77ff, 0x887788, 0xff77ff, 0x008800, 0x008800, 0x778877, 0x888888, 0xffffff,
    0x888888, 0x888888, 0xff88ff, 0x888888, 0xffffff, 0x88aa88, 0x88aa88, 0xffaaff,
    0x88aa88, 0xffffff, 0x00ff00, 0x00ff00, 0x77ff77, 0x88ff88, 0xffffff, 0x88ff88,
    0x88ff88, 0xffffff, 0x88ff88, 0xffffff,
};
constexpr int kOffsets[17] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 15, 16, 17, 21, 30, 31};

constexpr u32 kPattern = 0x08400000;  // clutPattern: 512 words, 16-byte aligned
constexpr u32 kImages = 0x08400800;   // the tests' 16-byte image arrays, one per texel value

class ClutIndexTest {
public:
    ClutIndexTest(GuSim& gu, const char* test) : gu_(gu), run_{test, gu.backend(), {}} {
        gu_.init();
        clutInit(gu_.start());
        gu_.finishSync();
        gu_.fillVram32(0, 0, 512 * 272);
        std::vector<u32> pattern(512, 0xDEADBEEF);
        for (u32 i = 0; i < 256; ++i) pattern[i] = i * 0x01010101u;
        gu_.cpuWrite(kPattern, pattern.data(), 2048);
        gu_.start().texFilter(0, 0);  // drawWithIndexOffsets(): GU_NEAREST, GU_NEAREST
        gu_.finishSync();
    }

    // drawTexFlush(1, 1, 16, GU_PSM_T32, image, clutPattern, fmt, 0xFF, vertices2, ...) with
    // sceGuClutMode(fmt, shift, mask, start), which sends fmt | shift << 2 | mask << 8 | start << 16
    // unmasked (shift 32 and 33 set bit 7 and leave 0 and 1 in the 5-bit field), then displayBuffer().
    void draw(const std::string& name, u32 texel, u32 fmt, u32 shift, u32 mask, u32 start, u32 hardware) {
        const u32 image = kImages + (nextImage_++ % 8) * 16;
        u8 bytes[16] = {};
        writeLE32(bytes, texel);
        gu_.cpuWrite(image, bytes, 16);
        const std::vector<u8> verts = spriteUv16(480, 272, 480, 272);  // vertices2
        ListBuilder& l = gu_.start();
        l.enable(GE_CMD_TME, true);
        l.texMode(GE_TFMT_CLUT32, 0, false);
        l.texFunc(1 /*DECAL*/, false);
        l.setTexture(0, image, 1, 1, 16);
        l.clutLoad(kPattern, 0xFF);
        l.cmd(GE_CMD_CLUT, fmt | (shift << 2) | (mask << 8) | (start << 16));
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, verts.data());
        gu_.finishSync();
        run_.checkpoints.push_back({name, hardware, gu_.readVram32(0), 0x00FFFFFF});
        gu_.fillVram32(0, 0, 512 * 272);
    }

    TestRun& run() { return run_; }

private:
    GuSim& gu_;
    TestRun run_;
    u32 nextImage_ = 0;
};

constexpr u32 kFormats[2] = {GE_FORMAT_8888, GE_FORMAT_4444};
const char* formatName(u32 fmt) { return fmt == GE_FORMAT_8888 ? "8888" : "4444"; }

TestRun runClutShifts(GuSim& gu) {
    ClutIndexTest t(gu, "clut/shifts");
    int n = 0;
    char name[64];
    for (const u32 fmt : kFormats)
        for (const int shift : kShifts)
            for (const u32 texel : {0xFFFFFFFFu, 0x12345678u}) {
                std::snprintf(name, sizeof name, "%s index shift %d (%08X)", formatName(fmt), shift, texel);
                t.draw(name, texel, fmt, u32(shift), 0xFF, 0, kShiftsHardware[n++]);
            }
    return t.run();
}

TestRun runClutMasks(GuSim& gu) {
    ClutIndexTest t(gu, "clut/masks");
    int n = 0;
    char name[64];
    for (const u32 fmt : kFormats)
        for (const int mask : kMasks) {
            std::snprintf(name, sizeof name, "%s index mask %02x", formatName(fmt), mask);
            t.draw(name, 255, fmt, 0, u32(mask), 0, kMasksHardware[n++]);
        }
    return t.run();
}

TestRun runClutOffset(GuSim& gu) {
    ClutIndexTest t(gu, "clut/offset");
    int n = 0;
    char name[64];
    for (const u32 fmt : kFormats)
        for (const int offset : kOffsets)
            for (const u32 texel : {0u, 1u, 15u, 16u, 255u}) {
                std::snprintf(name, sizeof name, "%s index offset %d (%u)", formatName(fmt), offset, texel);
                t.draw(name, texel, fmt, 0, 0xFF, u32(offset), kOffsetHardware[n++]);
            }
    return t.run();
}

CONFORMANCE_TEST(ClutShifts, runClutShifts)
CONFORMANCE_TEST(ClutMasks, runClutMasks)
CONFORMANCE_TEST(ClutOffset, runClutOffset)

}  // namespace
}  // namespace ge::conformance
