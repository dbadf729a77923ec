// SPDX-License-Identifier: MIT
// Scenes for the reference renderer's state optimizations that change pixels (geometry/reference_rules.h),
// shared by the software-model and GL tests.
#pragma once
#include <vector>

#include "authoring/list_builder.h"

namespace ge::testscene {

// The skipped alpha test (geometry/reference_rules.h referenceSkipsAlphaTest): a 4×4 CLUT4 texture, texels
// alternating palette entries 0 and 1 (entries 1–15 opaque red), drawn 1:1 as a through-mode rectangle at (0, 0) over a
// frame cleared to black, with the alpha test GREATER 0 and TFUNC MODULATE RGBA. Entry 1 is opaque
// red; entry 0 has alpha 0 and colour `entry0`. With `vertexAlpha` 255 and entries whose AND is
// non-zero (entry0 = 0x00000001: red bit 0 common to both), the reference drops the alpha test,
// so entry-0 texels are written (RGB 0x000001); with entry0 = 0 (AND zero) or a vertex alpha
// below 255 the test stays and those pixels keep the clear colour.
inline void skippedAlphaTestScene(ListBuilder& b, u32 entry0, u8 vertexAlpha) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.clear(CLEAR_COLOR, 0xFF000000, 0);
    u32 palette[16];
    for (u32& e : palette) e = 0xFF0000FF;  // all 16 entries of a CLUT4 palette take part
    palette[0] = entry0;
    const u32 clut = b.place(palette, sizeof palette);
    std::vector<u8> tex(16 * 4, 0);  // bufw 32 texels = 16 bytes per row
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            if ((x + y) & 1) tex[size_t(y) * 16 + size_t(x) / 2] |= u8(1 << ((x & 1) * 4));
    const u32 texAddr = b.place(tex.data(), u32(tex.size()));
    b.clutMode(3, 0, 0xFF, 0);
    b.clutLoad(clut, 2);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_CLUT4, 0, false);
    b.setTexture(0, texAddr, 4, 4, 32);
    b.texFunc(0, true);
    b.texFilter(0, 0);
    b.enable(GE_CMD_ATE, true);
    b.alphaFunc(6, 0);  // GREATER 0
    constexpr u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[2];
    v[0].color = v[1].color = 0x00FFFFFFu | (u32(vertexAlpha) << 24);
    v[1].x = v[1].u = 4;
    v[1].y = v[1].v = 4;
    const auto bytes = packVertices(vtype, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, bytes.data());
}

}  // namespace ge::testscene
