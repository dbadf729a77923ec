// SPDX-License-Identifier: MIT
// Sprites (RECTANGLES) as a PSP draws them, not as the reference renderer does (docs/conformance.md
// "Sprites"): in transform mode the viewport arithmetic is float24 and the screen position rounds up
// to the next 1/16 pixel before OFFSETX/Y is taken off (geometry/transform.cpp projectToScreen); in
// either mode the pixel whose centre is on the far edge is left out (geometry/raster.cpp
// rectangleSetup). Each case below is a value a PSP printed in pspautotests gpu/filtering/nearest,
// linear, precision*, textures/size or depth/precision; the reference renderer's rule gives the
// other value named beside it. Shared by the software-model (through a recorded dump) and GL tests.
//
// Cases 0-4 are the filtering tests' sprite: 2x2 pixels from clip (−1, 1) to (−1 + 2/240,
// 1 − 2/136) with SX = 240, SY = −136 and the viewport centre at 2048, over a 2x2 8888 texture with
// REPLACE; the screen offset moves each case to its own place (8 pixels apart along row 0) and,
// for one case, by a sixteenth of a pixel more. Case 5 is a through-mode sprite.
#pragma once
#include <functional>

#include <gtest/gtest.h>

#include "authoring/list_builder.h"
#include "tests/screen_frame.h"

namespace ge::testscene {

inline void spritePositionScene(ListBuilder& b) {
    screenFrame(b);
    b.cmdf(GE_CMD_SZ, -32767.5f);  // depth/precision's viewport Z (sceGuDepthRange's is −32768, 32767)
    b.cmdf(GE_CMD_TZ, 32767.5f);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0x1234);
    identityTransform(b);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.texFunc(3, true);  // REPLACE, RGBA (manual §13.13)
    b.texWrap(false, false);
    b.texScale(1.0f, 1.0f);
    b.texOffset(0.0f, 0.0f);
    // Columns red, green (rows 4 texels apart: the smallest 8888 buffer width, manual §6.2); and
    // rows red, blue.
    const u32 columns[8] = {0xFF0000FFu, 0xFF00FF00u, 0, 0, 0xFF0000FFu, 0xFF00FF00u, 0, 0};
    const u32 rows[8] = {0xFF0000FFu, 0xFF0000FFu, 0, 0, 0xFFFF0000u, 0xFFFF0000u, 0, 0};
    const u32 columnTex = b.place(columns, sizeof columns), rowTex = b.place(rows, sizeof rows);
    constexpr u32 vtype = vt::TC_F | vt::COL_8888 | vt::POS_F;
    // Case k at pixels (8k, 0)-(8k + 1, 1); `sub` sixteenths more to the upper left.
    auto sprite = [&](int k, u32 tex, bool linear, float u0, float v0, float y0, int sub, float z = 0) {
        b.setTexture(0, tex, 2, 2, 4);
        b.texFlush();
        b.texFilter(linear ? 1 : 0, linear ? 1 : 0);
        b.cmd(GE_CMD_OFFSETX, u32((2048 - 240 - 8 * k) << 4) + u32(sub));
        b.cmd(GE_CMD_OFFSETY, u32((2048 - 136) << 4) + u32(sub));
        BuildVertex v[2];
        v[0].x = -1.0f, v[0].y = y0, v[0].u = u0, v[0].v = v0;
        v[1].x = -1.0f + 2 / 240.0f, v[1].y = 1.0f - 2 / 136.0f, v[1].u = 1.0f + u0, v[1].v = 1.0f + v0;
        v[0].z = v[1].z = z;
        v[0].color = v[1].color = 0xFFFFFFFFu;
        const auto bytes = packVertices(vtype, v, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, bytes.data());
    };
    // 0, 1: the far corner at −1 + 2/240 is 1809.999998 in single precision but 1810.003 from
    // float24, rounded up to 1810.0625: nearest reads texel 1 only from u0 = 132/512 (filtering/
    // nearest "Blend at 131" and "132"; the reference renderer from 128/512).
    sprite(0, columnTex, false, 131 / 512.0f, 0, 1.0f, 0);
    sprite(1, columnTex, false, 132 / 512.0f, 0, 1.0f, 0);
    // 2: OFFSETX/Y 3/16 pixel past the sprite's screen corner: it starts at −3/16, not −2/16 (the
    // reference renderer takes the offset off before rounding toward zero); linear reads 2/16 of
    // green (filtering/linear "Pos offset 3": 0x001fdf; the reference 0x002fcf).
    sprite(2, columnTex, true, 0, 0, 1.0f, 3);
    // 3: the top edge at 32767/32768 is 1/256 pixel below row 0's top; rounded up it is 1/16
    // below, and nearest reads row 0 at the first row (textures/size's 1/16; the reference renderer
    // puts the edge on row 0's top and reads row 1).
    sprite(3, rowTex, false, 0, 0.25f, 32767.0f / 32768.0f, 0);
    // 4: Z 0x6DCC/32768 with SZ = −32767.5, TZ = 32767.5 is stored as 4660 = 0x1234: the cut
    // product −28107.5 plus the centre (depth/precision, "1234 >= 1234" passes; in single
    // precision 4659.93, truncated to 4659, it fails and the sprite is not drawn).
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);  // GEQUAL (manual §17.6)
    sprite(4, columnTex, false, 0, 0, 1.0f, 0, float(0x6DCC) / 32768.0f);
    b.enable(GE_CMD_ZTE, false);
    // 5: a through-mode sprite from x 40 to 41.5: the far edge is pixel 41's centre and the PSP
    // leaves it out (filtering/precisionnearest2d "Pos X offset 8": a sprite from −0.5 to 1.5
    // draws pixel 0 only); the reference's 2x2 walk draws it as the odd pixel of the pair.
    {
        constexpr u32 through = vt::TC_F | vt::COL_8888 | vt::POS_F | vt::THROUGH;
        BuildVertex v[2];
        v[0].x = 40.0f, v[0].y = 0.0f, v[0].u = 0.0f, v[0].v = 0.0f;
        v[1].x = 41.5f, v[1].y = 2.0f, v[1].u = 1.0f, v[1].v = 2.0f;
        v[0].color = v[1].color = 0xFFFFFFFFu;
        const auto bytes = packVertices(through, v, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, through, 2, nullptr, bytes.data());
    }
}

// Checks the scene's pixels; `rgb(x, y)` reads the 512-stride 8888 frame's RGB.
inline void checkSpritePositionScene(const std::function<u32(int, int)>& rgb) {
    EXPECT_EQ(rgb(0, 0), 0x0000FFu) << "u0 = 131/512: texel 0 (reference renderer: texel 1, 0x00ff00)";
    EXPECT_EQ(rgb(8, 0), 0x00FF00u) << "u0 = 132/512: texel 1";
    EXPECT_EQ(rgb(16, 0), 0x001FDFu) << "offset + 3/16: 2/16 green (reference renderer: 0x002fcf)";
    EXPECT_EQ(rgb(24, 0), 0x0000FFu) << "top edge 1/256 below row 0: row 0 (reference renderer: row 1, 0xff0000)";
    EXPECT_EQ(rgb(32, 0), 0x0000FFu) << "Z stored as 0x1234 passes GEQUAL 0x1234 (reference renderer: 0x1233, not drawn)";
    EXPECT_EQ(rgb(40, 1), 0x0000FFu) << "through-mode sprite from x 40: pixel 40";
    EXPECT_EQ(rgb(41, 1), 0u) << "far edge 41.5 on pixel 41's centre: left out (reference renderer: drawn)";
    EXPECT_EQ(rgb(4, 0), 0u) << "nothing between the cases";
}

}  // namespace ge::testscene
