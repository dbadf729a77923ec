// SPDX-License-Identifier: MIT
// make_scenes Scene 4: blend_stencil_logic (docs/scenes.md).
#include "tools/scenes/scene_kit.h"
#include "tools/scenes/scenes.h"

namespace ge::scenes {

namespace {

// Pass 1: pass 1: a 4444 off-screen buffer (128×128, stride 128) with 4-bit stencil and dither.
void drawOffscreenPass(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_4444, kOff0, 128);
    b.scissor(0, 0, 128, 128);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL, rgba(30, 30, 30), 0, 0x00);
    // Dithered gradient across the whole buffer (16-bit truncation after dithering, ge-rules.md §8.8).
    b.enable(GE_CMD_DTE, true);
    gradQuad(b, 0, 0, 128, 128, rgba(0, 0, 0), rgba(255, 64, 0), rgba(0, 128, 255), rgba(255, 255, 255));
    b.enable(GE_CMD_DTE, false);
    // Stencil: write 0x30 inside a diamond, then INCR in an overlapping square, then draw a
    // colour where stencil == 0x40 (INCR on 4444 adds 0x10, ge-rules.md §8.7) and another where it is 0x30.
    b.enable(GE_CMD_STE, true);
    b.pixelMask(0xFFFFFF, 0);  // keep RGB while writing stencil
    b.stencilFunc(1, 0x30);   // ALWAYS
    b.stencilOp(0, 0, 2);     // zpass REPLACE
    {
        BuildVertex v[4];
        const float xs[4] = {64, 112, 64, 16}, ys[4] = {16, 64, 112, 64};
        for (int i = 0; i < 4; ++i) {
            v[i].x = xs[i];
            v[i].y = ys[i];
            v[i].color = rgba(255, 255, 255, 255);
        }
        auto data = packVertices(kVt2dCol, v, 4);
        b.drawArrayData(GE_PRIM_TRIANGLE_FAN, kVt2dCol, 4, nullptr, data.data());
    }
    b.stencilOp(0, 0, 4);  // INCR
    rect(b, 40, 40, 80, 80, rgba(255, 255, 255));
    b.pixelMask(0, 0);
    b.stencilOp(0, 0, 0);  // KEEP
    b.stencilFunc(2, 0x40, 0xF0);  // EQUAL (masked)
    rect(b, 0, 0, 128, 128, rgba(255, 220, 0));
    b.stencilFunc(2, 0x30, 0xF0);
    rect(b, 0, 0, 128, 128, rgba(0, 200, 255));
    b.stencilFunc(3, 0x00, 0xFF);  // NOTEQUAL 0 → INVERT where anything was written
    b.stencilOp(0, 0, 3);
    b.pixelMask(0xFFFFFF, 0);
    rect(b, 0, 96, 128, 32, 0);
    b.pixelMask(0, 0);
    b.enable(GE_CMD_STE, false);
}

// Pass 2: pass 2: the main 8888 buffer.
void drawMainPass(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, kFb, 512);
    b.scissor(0, 0, 480, 272);
    b.texSync();

    // Background: vertical colour bars with a horizontal alpha ramp in the frame buffer alpha.
    for (int i = 0; i < 8; ++i) {
        u32 c = hue(u32(i), 8);
        gradQuad(b, i * 60, 0, 60, 272, c & 0xFFFFFF, c & 0xFFFFFF, c | 0xFF000000, c | 0xFF000000);
    }
    // The gradients above wrote no alpha (no stencil test, ge-rules.md §8.7): set the frame-buffer alpha
    // (= stencil) to 0xC0 everywhere through a clear that writes alpha only.
    b.clear(CLEAR_STENCIL, 0, 0, 0xC0);

    // Row 0: blend equations and factors over the bars; the source is a white→red gradient with
    // alpha 0→255.
    struct BlendCase {
        u32 eq, a, bb, fixA, fixB;
    };
    const BlendCase cases[8] = {
        {0, 2, 3, 0, 0},                              // ADD  As, 1−As
        {0, 10, 10, rgba(128, 128, 128), rgba(64, 64, 64)},  // ADD  FIXA, FIXB
        {1, 2, 10, 0, rgba(255, 255, 255)},           // SUB  As, FIX(white)
        {2, 6, 4, 0, 0},                              // REVSUB 2·As, Ad
        {3, 0, 0, 0, 0},                              // MIN
        {4, 0, 0, 0, 0},                              // MAX
        {5, 0, 0, 0, 0},                              // ABS
        {0, 0, 1, 0, 0},                              // ADD  Cd, 1−Cs
    };
    b.enable(GE_CMD_ABE, true);
    for (int i = 0; i < 8; ++i) {
        b.blendFunc(cases[i].eq, cases[i].a, cases[i].bb, cases[i].fixA, cases[i].fixB);
        gradQuad(b, i * 60 + 4, 6, 52, 52, rgba(255, 255, 255, 0), rgba(255, 255, 255, 255), rgba(255, 0, 0, 0),
                 rgba(255, 0, 0, 255));
    }
    b.enable(GE_CMD_ABE, false);

    // Row 1: logic ops 0–15 in 16 small cells (30×30).
    b.enable(GE_CMD_LOE, true);
    for (u32 op = 0; op < 16; ++op) {
        b.logicOp(op);
        rect(b, int(op) * 30, 66, 28, 30, rgba(0xF0, 0x3C, 0xAA));
    }
    b.enable(GE_CMD_LOE, false);

    // Row 2: alpha test, colour test, pixel masks, dither on/off.
    gradQuad(b, 4, 104, 112, 52, rgba(255, 255, 0, 0), rgba(255, 255, 0, 255), rgba(0, 255, 255, 0),
             rgba(0, 255, 255, 255));  // reference (no test)
    b.enable(GE_CMD_ATE, true);
    b.alphaFunc(6, 0x80, 0xFF);  // GREATER 0x80: the right half survives
    gradQuad(b, 124, 104, 112, 52, rgba(255, 255, 0, 0), rgba(255, 255, 0, 255), rgba(0, 255, 255, 0),
             rgba(0, 255, 255, 255));
    b.alphaFunc(4, 0x40, 0xC0);  // LESS with mask: (A & 0xC0) < 0x40
    gradQuad(b, 244, 104, 112, 52, rgba(255, 0, 255, 0), rgba(255, 0, 255, 255), rgba(255, 255, 255, 0),
             rgba(255, 255, 255, 255));
    b.enable(GE_CMD_ATE, false);
    // Colour test NOTEQUAL against green (masking the low bits): stripes of green are dropped.
    b.enable(GE_CMD_CTE, true);
    b.colorFunc(3, rgba(0, 255, 0), rgba(0xF0, 0xF0, 0xF0));
    for (int i = 0; i < 8; ++i) rect(b, 364 + i * 14, 104, 14, 52, (i & 1) ? rgba(4, 250, 8) : rgba(250, 120, 20));
    b.enable(GE_CMD_CTE, false);

    // Row 3: PMSK (keep green bits), dither on vs off on a dark ramp, depth write/test interplay.
    b.pixelMask(rgba(0, 0xFF, 0), 0);
    rect(b, 4, 164, 112, 40, rgba(255, 255, 255));
    b.pixelMask(0, 0);
    gradQuad(b, 124, 164, 112, 40, rgba(0, 0, 0), rgba(40, 40, 40), rgba(0, 0, 0), rgba(40, 40, 40));
    b.enable(GE_CMD_DTE, true);
    gradQuad(b, 244, 164, 112, 40, rgba(0, 0, 0), rgba(40, 40, 40), rgba(0, 0, 0), rgba(40, 40, 40));
    b.enable(GE_CMD_DTE, false);
    // Stencil on the 8888 target: frame-buffer alpha is 0xC0 from the clear above; ZERO it where
    // the stencil equals 0xC0 in the left half, DECR the right quarter, then show the stencil
    // through a destination-alpha blend of white.
    b.enable(GE_CMD_STE, true);
    b.stencilFunc(2, 0xC0, 0xFF);
    b.stencilOp(0, 0, 1);  // ZERO
    b.pixelMask(0xFFFFFF, 0);
    rect(b, 364, 164, 56, 40, 0);
    b.stencilOp(0, 0, 5);  // DECR
    rect(b, 448, 164, 28, 40, 0);
    b.pixelMask(0, 0);
    b.stencilFunc(1, 0, 0);
    b.stencilOp(0, 0, 0);
    b.enable(GE_CMD_STE, false);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 4, 5);  // Ad, 1 − Ad
    rect(b, 364, 164, 112, 40, rgba(255, 255, 255));
    b.enable(GE_CMD_ABE, false);

    // Row 4: the 4444 pass, sampled as a texture (same bytes, texture format 4444), twice:
    // as is, and with alpha blending so its stencil/alpha nibble shows.
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_4444, 0, false);
    b.setTexture(0, 0x04000000 + kOff0, 128, 128, 128);
    b.texFunc(3, false);  // REPLACE, RGB
    b.texFilter(0, 0);
    b.texWrap(true, true);
    texRect(b, 4, 210, 60, 60, 0, 0, 128, 128);
    b.texFunc(3, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);
    texRect(b, 70, 210, 60, 60, 0, 0, 128, 128);
    b.enable(GE_CMD_ABE, false);
    b.enable(GE_CMD_TME, false);

    // Depth: two overlapping through-mode rectangles with Z; the second (lower Z) fails GEQUAL.
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);
    {
        const u32 vt = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        BuildVertex v[4];
        v[0].x = 150; v[0].y = 214; v[0].z = 40000; v[0].color = rgba(200, 60, 200);
        v[1].x = 230; v[1].y = 266; v[1].z = 40000; v[1].color = rgba(200, 60, 200);
        v[2].x = 190; v[2].y = 230; v[2].z = 20000; v[2].color = rgba(60, 200, 60);
        v[3].x = 280; v[3].y = 270; v[3].z = 20000; v[3].color = rgba(60, 200, 60);
        auto data = packVertices(vt, v, 4);
        b.drawArrayData(GE_PRIM_RECTANGLES, vt, 4, nullptr, data.data());
    }
    b.enable(GE_CMD_ZTE, false);
}

}  // namespace

void sceneBlendStencilLogic(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(0, 0, 0, 0), 0);

    drawOffscreenPass(b);
    drawMainPass(b);
    b.finish();
}

}  // namespace ge::scenes
