// SPDX-License-Identifier: MIT
// pspautotests tests/gpu/commands/material, re-created (gu_sim.h, conformance.h,
// screenshot.h). A background sprite (0, 0)-(479, 272) whose texels are all transparent, then 17
// through-mode sprites of 40x20 (ten a row from (10, 10), 47 pixels apart, rows 26 apart) with a 4x4
// CLUT8 checkerboard (index 0: 0xAAAAAAAA, 1: opaque white; DECAL), each drawn as its own list, under
// MATERIAL (colour material), MAC/MAA (material ambient), AC/AA (scene ambient) and lighting on or
// off, without a vertex colour (the first four and the last) and with one (0x77333388 -> 0x77338833,
// or the same with alpha 0; TFUNC RGBA or RGB). The whole frame is drawn 120 times (draw() in a
// loop), so from the second time on the background is drawn with the state the previous frame left
// (lighting on). The screenshot is the check. What the PSP shows: a sprite without a vertex colour
// takes MAC as its colour (background 0x550055 through its transparent texels); the checkerboard's
// index-0 texels (alpha 0xAA) blend with the sprite's colour by DECAL, one colour per sprite.
#include "tests/conformance/conformance.h"
#include "tests/conformance/screenshot.h"

namespace ge::conformance {
namespace {

constexpr u32 kClut = 0x08400000, kBgData = 0x08400040, kImageData = 0x08400080;

// The index-0 texels' colour per sprite, as the PSP shows it (the index-1 texels are white).
constexpr u32 kBoxDark[17] = {0x717171, 0x7171C6, 0x71C671, 0xC67171, 0x829F82, 0x829F82, 0x829F82, 0x829F82, 0x829F82,
                              0x829F82, 0xAAAAAA, 0xAAAAAA, 0xAAAAAA, 0xAAAAAA, 0xAAAAAA, 0xAAAAAA, 0x717171};

std::vector<ScreenSpan> materialScreen() {
    std::vector<ScreenSpan> s = {{0, 272, 479, 480, 0, 0, 0x000000}};  // the column the background leaves out
    for (int i = 0; i < 17; ++i) {
        const int x = 10 + 47 * (i % 10), y = 10 + 26 * (i / 10);
        for (int ty = 0; ty < 4; ++ty)
            for (int tx = 0; tx < 4; ++tx)
                s.push_back({y + 5 * ty, y + 5 * ty + 5, x + 10 * tx, x + 10 * tx + 10, 0, 0,
                             ((tx + ty) & 1) ? 0xFFFFFFu : kBoxDark[i]});
    }
    return s;
}

struct Cursor {
    int x = 10, y = 10;
    void next() {
        x += 47;
        if (x >= 470) {
            x = 10;
            y += 26;
        }
    }
};

enum HasColor : u32 { kRgba = 0x00, kRgb = 0x01, kRgbaTransparent = 0x10, kRgbTransparent = 0x11 };

class MaterialProgram {
public:
    explicit MaterialProgram(GuSim& gu) : gu_(gu) {}

    void draw() {
        Cursor at;
        ListBuilder* b = &gu_.start();
        b->clear(CLEAR_COLOR, 0, 0);
        b->clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        b->clutLoad(kClut, 1);
        // drawBG()
        b->cmd(GE_CMD_MATERIAL, 0xFF);
        b->cmd(GE_CMD_MAC, 0x550055);
        texture(*b, kBgData, 1 /*RGBA*/);
        b->drawArrayData(GE_PRIM_RECTANGLES, kType, 2, nullptr, sprite(0, 0, 479, 272, 0, false).data());
        // Reset things.
        b->cmd(GE_CMD_LTE, 0);
        b->cmd(GE_CMD_MAA, 0);
        b->cmd(GE_CMD_AC, 0);
        b->cmd(GE_CMD_AA, 0);

        auto set = [&](u32 update, u32 ambient) {
            b->cmd(GE_CMD_MATERIAL, update);
            b->cmd(GE_CMD_MAC, ambient);
        };
        auto lit = [&](u32 update, u32 matAlpha, u32 matAmbient, u32 ambient, u32 ambientAlpha) {
            b->cmd(GE_CMD_MATERIAL, update);
            b->cmd(GE_CMD_MAA, matAlpha);
            b->cmd(GE_CMD_MAC, matAmbient);
            b->cmd(GE_CMD_AC, ambient);
            b->cmd(GE_CMD_AA, ambientAlpha);
            b->cmd(GE_CMD_LTE, 1);
        };
        set(0, 0);
        b = &box(*b, at, -1);
        set(0xFF, 0xFF0000);
        b = &box(*b, at, -1);
        b->cmd(GE_CMD_MAC, 0x00FF00);
        b = &box(*b, at, -1);
        set(0, 0x0000FF);
        b = &box(*b, at, -1);
        for (u32 mode : {kRgba, kRgbaTransparent, kRgb, kRgbTransparent}) {
            const u32 alpha = mode == kRgba ? 0x80 : 0x10;
            set(0, 0);
            b = &box(*b, at, int(mode));
            lit(1 /*GU_AMBIENT*/, 0, 0xFF0000, 0x0000FF, 0);
            b = &box(*b, at, int(mode));
            lit(0xFF, alpha, 0xFFFFFF, 0xFFFFFF, alpha);
            b = &box(*b, at, int(mode));
        }
        set(0, 0);
        b = &box(*b, at, -1);
        gu_.finishSync();
    }

private:
    static constexpr u32 kType = vt::TC_16 | vt::POS_16 | vt::THROUGH;
    static constexpr u32 kColorType = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;

    // Vertex {u16 a, b, x, y, z} or VertexColor {u16 a, b; u32 color; u16 x, y, z}: UV (0, 0)-(u, u).
    static std::vector<u8> sprite(int x0, int y0, int x1, int y1, int uv, bool withColor, u32 c0 = 0, u32 c1 = 0) {
        const u32 size = withColor ? 16 : 10, posAt = withColor ? 8 : 4;
        std::vector<u8> out(2 * size, 0);
        const int pts[2][3] = {{x0, y0, 0}, {x1, y1, uv}};
        for (int i = 0; i < 2; ++i) {
            u8* p = &out[size_t(i) * size];
            writeLE16(p, u16(pts[i][2])), writeLE16(p + 2, u16(pts[i][2]));
            if (withColor) writeLE32(p + 4, i ? c1 : c0);
            writeLE16(p + posAt, u16(pts[i][0])), writeLE16(p + posAt + 2, u16(pts[i][1]));
        }
        return out;
    }

    static void texture(ListBuilder& b, u32 image, u32 rgba) {
        b.enable(GE_CMD_TME, true);
        b.texMode(GE_TFMT_CLUT8, 0, false);
        b.texFunc(1 /*DECAL*/, rgba != 0);
        b.setTexture(0, image, 4, 4, 16);
    }

    // nextBox (mode -1) or nextBoxHasColor(mode): the sprite, then sceGuFinish, sceGuSync and a new
    // sceGuStart; returns the new list.
    ListBuilder& box(ListBuilder& b, Cursor& at, int mode) {
        const bool withColor = mode >= 0;
        const bool transparent = withColor && (mode & kRgbaTransparent);
        texture(b, kImageData, withColor && (mode & kRgb) ? 0 : 1);
        const u32 a = transparent ? 0 : 0x77000000u;
        const std::vector<u8> v = sprite(at.x, at.y, at.x + 40, at.y + 20, 4, withColor, a | 0x333388, a | 0x338833);
        at.next();
        b.drawArrayData(GE_PRIM_RECTANGLES, withColor ? kColorType : kType, 2, nullptr, v.data());
        gu_.finishSync();
        return gu_.start();
    }

    GuSim& gu_;
};

TestRun runMaterial(GuSim& gu) {
    TestRun run{"commands/material", gu.backend(), {}};
    gu.init();
    clutInit(gu.start());  // init(): draw buffer, display region, scissor
    gu.finishSync();
    const u32 clut[8] = {0xAAAAAAAA, 0xFFFFFFFF, 0, 0, 0, 0, 0, 0};
    gu.cpuWrite(kClut, clut, sizeof clut);
    u8 bg[64] = {}, image[64] = {};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            bg[r * 16 + c] = 2;
            image[r * 16 + c] = u8((r + c) & 1);
        }
    gu.cpuWrite(kBgData, bg, sizeof bg);
    gu.cpuWrite(kImageData, image, sizeof image);
    MaterialProgram program(gu);
    for (int frame = 0; frame < 120; ++frame) program.draw();
    compareScreen(gu, run, 0, GE_FORMAT_8888, 0x550055, materialScreen());
    return run;
}

CONFORMANCE_TEST(CommandsMaterial, runMaterial)

}  // namespace
}  // namespace ge::conformance
