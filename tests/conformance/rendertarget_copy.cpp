// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/rendertarget/copy, re-created (gu_sim.h, conformance.h). A 2x2
// CLUT8 texture (indices 1 2 / 2 1, buffer width 16) is drawn, DECAL/RGB, as a through-mode sprite
// over (10, 10)-(470, 262) with texture coordinates 0..2: with the palette "add one" (entry i = i + 1)
// into frame buffer 0 and "add three" (i + 3) into frame buffer 1, for nearest and linear filtering,
// clamped and repeated. Buffer 1 is read back, then buffer 0 is copied over it by the CPU
// (sceDmacMemcpy) and buffer 1 read back again. Then buffer 0 is drawn once more (linear, repeat)
// and its lower half copied over its upper half by the CPU; last, a CPU-written pattern
// ((x & 1) + (y & 1)) replaces buffer 0 after a draw. The PSP's frames (one line of hex values per
// row, a space for 0) are rectangles of one value each; each row of each frame is a checkpoint
// whose value is the count of pixels that differ from the PSP's row (0 on hardware).
#include "tests/conformance/conformance.h"

#include <cstdio>

namespace ge::conformance {
namespace {

constexpr u32 kClutAddOne = 0x08400000, kClutAddThree = 0x08400020, kImage = 0x08400040;
constexpr u32 kFrameBytes = 512 * 272 * 4;  // sizeof(copybuf)
constexpr u32 kBuffer1 = kFrameBytes;        // getBufAddr(1), bytes from VRAM's start

// A frame on a PSP: these rectangles [x0, x1) x [y0, y1) painted in order over 0.
struct Rect {
    u16 x0, x1, y0, y1;
    u32 value;
};
using Frame = std::vector<Rect>;

// The sprite's frames for palette entries a (index 1) and b (index 2).
Frame nearestFrame(u32 a, u32 b) {
    return {{10, 240, 10, 136, a}, {240, 470, 10, 136, b}, {10, 240, 136, 262, b}, {240, 470, 136, 262, a}};
}
Frame linearClampFrame(u32 a, u32 b) { return {{10, 470, 10, 262, a}, {355, 470, 10, 81, b}, {10, 139, 199, 262, b}}; }
Frame linearWrapFrame(u32 a, u32 b) { return {{10, 470, 10, 262, a}, {355, 369, 73, 81, b}, {125, 139, 199, 207, b}}; }
// Buffer 0 after "Spliced buffer": rows 136..271 of the linear-wrap frame ("add one") also in 0..135.
const Frame kSpliced = {{10, 470, 0, 126, 2}, {125, 139, 63, 71, 3}, {10, 470, 136, 262, 2}, {125, 139, 199, 207, 3}};

// A frame's 480x272 values, row by row.
std::vector<u32> paint(const Frame& rects) {
    std::vector<u32> out(480 * 272, 0);
    for (const Rect& r : rects)
        for (u32 y = r.y0; y < r.y1; ++y)
            for (u32 x = r.x0; x < r.x1; ++x) out[y * 480 + x] = r.value;
    return out;
}
// "Pattern": the CPU's (x & 1) + (y & 1), as the PSP read it back.
std::vector<u32> patternFrame() {
    std::vector<u32> out(480 * 272);
    for (u32 y = 0; y < 272; ++y)
        for (u32 x = 0; x < 480; ++x) out[y * 480 + x] = (x & 1) + (y & 1);
    return out;
}

class CopyTest {
public:
    explicit CopyTest(GuSim& gu) : gu_(gu), run_{"rendertarget/copy", gu.backend(), {}} {}

    TestRun run() {
        gu_.init();
        clutInit(gu_.start());  // init(): 8888 buffer 0, display region, the full scissor
        gu_.finishSync();
        drawbuf_ = 0;
        gu_.fillVram32(0, 0, 512 * 272);  // resetBuffer()
        const u32 addOne[8] = {1, 2, 3, 4, 5, 6, 7, 8}, addThree[8] = {3, 4, 5, 6, 7, 8, 9, 10};
        gu_.cpuWrite(kClutAddOne, addOne, sizeof addOne);
        gu_.cpuWrite(kClutAddThree, addThree, sizeof addThree);
        u8 image[32] = {};
        image[0] = 1, image[1] = 2, image[16] = 2, image[17] = 1;
        gu_.cpuWrite(kImage, image, sizeof image);

        struct Mode {
            const char* name;
            bool linear, clamp;
        };
        for (const Mode m : {Mode{"Nearest, clamp", false, true}, Mode{"Linear, clamp", true, true},
                             Mode{"Nearest, wrap", false, false}, Mode{"Linear, wrap", true, false}}) {
            ListBuilder& l = gu_.start();
            l.texFilter(m.linear, m.linear);
            l.texWrap(m.clamp, m.clamp);
            gu_.finishSync();
            drawInterTransfer(m.name, m.linear, m.clamp);
        }
        drawIntraTransfer();
        drawUploadTransfer();
        return run_;
    }

private:
    // switchBuf(i, GU_PSM_8888): sceGuDrawBuffer also sends the depth buffer, which the SDK now puts
    // after the display's 272 rows (0x88000, buffer 1: depth writes are off, as the test is).
    void switchBuf(u32 i) {
        drawbuf_ = i * kFrameBytes;
        ListBuilder& s = gu_.start();
        s.drawBuffer(GE_FORMAT_8888, drawbuf_, 512);
        s.depthBuffer(272 * 512 * 4, 512);
        sdkDispBuffer(s);
        gu_.finishSync();
    }

    // drawTexFlush(2, 2, 16, GU_PSM_T8, imageData, clut, vertices1).
    void drawTexFlush(u32 clut) {
        ListBuilder& l = gu_.start();
        l.enable(GE_CMD_TME, true);
        l.texMode(GE_TFMT_CLUT8, 0, false);
        l.texFunc(1 /*DECAL*/, false);
        l.setTexture(0, kImage, 2, 2, 16);
        l.clutLoad(clut, 1);
        l.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        // vertices1: (u, v, x, y, z) (0, 0, 10, 10, 0) - (2, 2, 470, 262, 0).
        std::vector<u8> v = spriteUv16(2, 2, 470, 262);
        writeLE16(&v[4], 10), writeLE16(&v[6], 10);
        l.drawArrayData(GE_PRIM_RECTANGLES, vt::TC_16 | vt::POS_16 | vt::THROUGH, 2, nullptr, v.data());
        gu_.finishSync();
    }

    // sceDmacMemcpy within VRAM (offsets from its start).
    void copyVram(u32 dst, u32 src, u32 size) {
        const u8* p = gu_.readBytes(Memory::kVramBase + src, size);
        const std::vector<u8> bytes(p, p + size);
        gu_.writeVram(dst, bytes.data(), size);
    }

    // displayBuffer(reason): the 480x272 frame of drawbuf, one checkpoint per row against the PSP's.
    void displayBuffer(const std::string& reason, const std::vector<u32>& hw) {
        const u8* frame = gu_.readBytes(Memory::kVramBase + drawbuf_, kFrameBytes);
        for (u32 y = 0; y < 272; ++y) {
            u32 differing = 0;
            for (u32 x = 0; x < 480; ++x) differing += readLE32(frame + (y * 512 + x) * 4) != hw[y * 480 + x];
            run_.checkpoints.push_back({reason + " row " + std::to_string(y) + " (pixels differing)", 0, differing});
        }
    }

    void drawInterTransfer(const std::string& mode, bool linear, bool clamp) {
        switchBuf(0);
        drawTexFlush(kClutAddOne);
        switchBuf(1);
        drawTexFlush(kClutAddThree);
        auto frame = [&](u32 a, u32 b) {
            return !linear ? nearestFrame(a, b) : clamp ? linearClampFrame(a, b) : linearWrapFrame(a, b);
        };
        displayBuffer(mode + ": Initial download", paint(frame(4, 5)));
        copyVram(kBuffer1, 0, kFrameBytes);
        displayBuffer(mode + ": Copied buffer", paint(frame(2, 3)));
    }

    void drawIntraTransfer() {
        gu_.start().texFilter(1, 1);
        gu_.finishSync();
        switchBuf(0);
        drawTexFlush(kClutAddOne);
        copyVram(0, kFrameBytes / 2, kFrameBytes / 2);
        displayBuffer("Linear, wrap: Spliced buffer", paint(kSpliced));
    }

    void drawUploadTransfer() {
        gu_.start().texFilter(1, 1);
        gu_.finishSync();
        switchBuf(0);
        drawTexFlush(kClutAddOne);
        std::vector<u32> pattern(512 * 272);
        for (u32 y = 0; y < 272; ++y)
            for (u32 x = 0; x < 512; ++x) pattern[y * 512 + x] = (x & 1) + (y & 1);
        gu_.writeVram(0, pattern.data(), kFrameBytes);
        displayBuffer("Linear, wrap: Pattern", patternFrame());
    }

    GuSim& gu_;
    TestRun run_;
    u32 drawbuf_ = 0;
};

TestRun runCopy(GuSim& gu) { return CopyTest(gu).run(); }

CONFORMANCE_TEST(RenderTargetCopy, runCopy)

}  // namespace
}  // namespace ge::conformance
