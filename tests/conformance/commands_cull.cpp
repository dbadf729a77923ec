// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/cull, re-created (gu_sim.h, conformance.h). Eight
// 40x30 boxes per pass, left to right from (10, 10) with 15 pixels between them, each drawn as a
// 4-vertex fan (clockwise or counter-clockwise in screen order) or a 2-vertex sprite (corners in
// either diagonal), with culling off or on and CULL 0 or 1; four passes: through mode, transform
// mode, and both again with clear mode on (CLEAR 0x101, colour written). The frame was cleared to
// 0x003F3F3F first; after the frame the top-left pixel of every box is read. What the values show:
// CULL 0 drops the clockwise fan and CULL 1 the counter-clockwise one, in both vertex modes;
// sprites are never culled; nothing is culled in clear mode.
#include "tests/conformance/conformance.h"

namespace ge::conformance {
namespace {

constexpr int kBoxW = 40, kBoxH = 30, kBoxSpace = 15;
constexpr u32 kDrawn = 0x001F1FFF, kCleared = 0x003F3F3F;

// Per pass, the hardware values of the eight boxes of cullBoxes() in order: (enable, face, shape)
// = (0,0,cw) (0,0,ccw) (1,0,cw) (1,0,ccw) (1,1,cw) (1,1,ccw) (1,1,sprite) (1,1,sprite swapped).
constexpr u32 kCullPass[8] = {kDrawn, kDrawn, kCleared, kDrawn, kDrawn, kCleared, kDrawn, kDrawn};
constexpr u32 kClearPass[8] = {kDrawn, kDrawn, kDrawn, kDrawn, kDrawn, kDrawn, kDrawn, kDrawn};

struct BoxCursor {
    int x = 10, y = 10;
    void next() {
        x += kBoxW + kBoxSpace;
        if (x + kBoxW >= 480) {
            x = 10;
            y += kBoxH + kBoxSpace;
        }
    }
};

void nextBox(ListBuilder& b, BoxCursor& at, bool through, int shape) {
    const u32 c = 0xFF1F1FFF;
    const int x = at.x, y = at.y;
    std::vector<ColorPos> v;
    switch (shape) {
    case 0: v = {{c, x, y}, {c, x, y + kBoxH}, {c, x + kBoxW, y + kBoxH}, {c, x + kBoxW, y}}; break;
    case 1: v = {{c, x, y}, {c, x + kBoxW, y}, {c, x + kBoxW, y + kBoxH}, {c, x, y + kBoxH}}; break;
    case 2: v = {{c, x, y}, {c, x + kBoxW, y + kBoxH}}; break;
    default: v = {{c, x, y + kBoxH}, {c, x + kBoxW, y}}; break;
    }
    const std::vector<u8> data = colorPos16(v, through);
    b.drawArrayData(shape & 2 ? GE_PRIM_RECTANGLES : GE_PRIM_TRIANGLE_FAN, colorPos16Type(through), u32(v.size()),
                    nullptr, data.data());
    at.next();
}

TestRun runCull(GuSim& gu) {
    TestRun run{"commands/cull", gu.backend(), {}};
    gu.init();
    commandsInitDisplay(gu.start());
    gu.finishSync();

    ListBuilder& b = gu.start();  // draw(): startFrame() clears to 0, then to the grey
    b.clear(CLEAR_COLOR, 0, 0, 0);
    b.enable(GE_CMD_STE, false);  // sceGuDisable(GU_TEXTURE): GU_TEXTURE is 3, GU_STENCIL_TEST's number
    b.enable(GE_CMD_ABE, false);
    b.clear(CLEAR_COLOR, kCleared, 0, 0);
    BoxCursor at;
    for (int pass = 0; pass < 4; ++pass) {
        const bool through = (pass & 1) == 0;
        const u32 clearVal = pass >= 2 ? 1 | (CLEAR_COLOR << 8) : 0;
        // cullBox(transform, clearVal, enable, face, shape), as cullBoxes() calls it.
        static constexpr int kBoxes[8][3] = {{0, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0},
                                             {1, 1, 1}, {1, 1, 0}, {1, 1, 2}, {1, 1, 3}};
        for (const auto& box : kBoxes) {
            b.enable(GE_CMD_BCE, box[0] != 0);
            b.cmd(GE_CMD_CULL, u32(box[1]));
            b.cmd(GE_CMD_CMODE, clearVal);
            nextBox(b, at, through, box[2]);
            b.cmd(GE_CMD_CMODE, 0);
        }
    }
    gu.finishSync();

    static const char* kPassNames[4] = {"Transform 2D", "Transform 3D", "Clear 2D", "Clear 3D"};
    static const char* kBoxNames[8] = {"0/0, cw",     "0/0, ccw",     "type=0, cw",        "type=0, ccw",
                                       "type=1, cw", "type=1, ccw", "type=1, cw sprite", "type=1, ccw sprite"};
    BoxCursor log;
    for (int pass = 0; pass < 4; ++pass)
        for (int i = 0; i < 8; ++i) {
            const u32 got = gu.readVram32(u32(log.y * 512 + log.x) * 4);
            const u32 want = pass >= 2 ? kClearPass[i] : kCullPass[i];
            run.checkpoints.push_back({std::string(kPassNames[pass]) + " (" + kBoxNames[i] + ")", want, got});
            log.next();
        }
    return run;
}

CONFORMANCE_TEST(CommandsCull, runCull)

}  // namespace
}  // namespace ge::conformance
