// SPDX-License-Identifier: MIT
// Textures past 512 texels (geometry/texture_size.h): a 1024-wide row and a 1024-high column
// (TSIZE exponent 10; the GE keeps 512 texels) drawn over 64 pixels, in through mode and in
// transform mode. Coordinates scale by the full 1024 and the texel index stops at 511 (or wraps
// with & 511): a PSP reads texel 2 at pixel 0 and 510 at pixel 127 of a 1024-wide row drawn over
// 256 pixels (pspautotests gpu/textures/size, tests/conformance/textures_size.cpp). Texel i holds
// the colour i, so a pixel's RGB is the texel index it read. Coordinates start half a texel in, so
// every sample lies mid-texel. Shared by the software-model and GL tests.
//
// Rows 0–2 through mode (u in texels), rows 3–5 transform mode (s = u / 1024), 1024-wide row:
// u 0.5 … 256.5 (clamp): pixel x reads 4x + 2 (a scale of 512 would give 2x + 1, a through-mode
// u divided by 512 and scaled by 1024 8x + 5); u 0.5 … 1024.5 (clamp): min(16x + 8, 511);
// u 0.5 … 2048.5 (repeat): (32x + 16) & 511. Columns 40 (through) and 41 (transform), 1024-high
// column, v 0.5 … 256.5 (clamp) over rows 0–63: row y reads texel row 4y + 2 (drawn last, over
// those two pixels of rows 0–5).
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "authoring/list_builder.h"
#include "tests/screen_frame.h"

namespace ge::testscene {

inline constexpr int kWideRows = 6;
inline constexpr int kWideColumnX[2] = {40, 41};  // through, transform

// The texel index pixel x of row `row` reads (rows as above).
inline u32 wideRowTexel(int row, int x) {
    switch (row % 3) {
        case 0: return u32(4 * x + 2);
        case 1: return u32(std::min(16 * x + 8, 511));
        default: return u32((32 * x + 16) & 511);
    }
}
// The texel row pixel y of the column reads.
inline u32 wideColumnTexel(int y) { return u32(4 * y + 2); }

// 512-stride 8888 frame at VRAM offset 0, a 64×64 viewport over pixels (0, 0)–(64, 64).
inline void wideTextureScene(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0x88000, 512);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.offset(2048 - 32, 2048 - 32);
    b.viewport(2048, 2048, 64, 64);
    b.depthRange(65535, 0);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    identityTransform(b);
    b.texMode(GE_TFMT_8888, 0, false);
    b.texFunc(3, true);  // REPLACE, RGBA
    b.texFilter(0, 0);   // nearest
    b.texScale(1, 1);    // transform mode's UV scale and offset: s, t as given
    b.texOffset(0, 0);
    b.enable(GE_CMD_TME, true);

    std::vector<u32> row(1024), column(1024 * 4);
    for (u32 i = 0; i < 1024; ++i) row[i] = 0xFF000000u | i, column[i * 4] = 0xFF000000u | i;
    const u32 rowAddr = b.place(row.data(), u32(row.size() * 4));
    const u32 columnAddr = b.place(column.data(), u32(column.size() * 4));

    const float uEnd[3] = {256.5f, 1024.5f, 2048.5f};
    // (x1, y1)-(x2, y2) in pixels with texture coordinates (u1, v1)-(u2, v2) in texels of 1024.
    auto sprite = [&](bool through, float x1, float y1, float x2, float y2, float u1, float v1, float u2, float v2) {
        const u32 vtype = vt::TC_F | vt::POS_F | (through ? vt::THROUGH : 0u);
        BuildVertex v[2];
        const float px[2] = {x1, x2}, py[2] = {y1, y2}, tu[2] = {u1, u2}, tv[2] = {v1, v2};
        for (int k = 0; k < 2; ++k) {
            v[k].x = through ? px[k] : (px[k] - 32.0f) / 32.0f;
            v[k].y = through ? py[k] : (32.0f - py[k]) / 32.0f;
            v[k].u = through ? tu[k] : tu[k] / 1024.0f;
            v[k].v = through ? tv[k] : tv[k] / 1024.0f;
        }
        const std::vector<u8> bytes = packVertices(vtype, v, 2);
        b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, bytes.data());
    };
    b.setTexture(0, rowAddr, 1024, 1, 1024);
    for (int r = 0; r < kWideRows; ++r) {
        const bool through = r < 3;
        b.texWrap(r % 3 != 2, true);  // rows 0, 1: clamp; row 2: repeat
        sprite(through, 0, float(r), 64, float(r + 1), 0.5f, 0.5f, uEnd[r % 3], 0.5f);
    }
    b.setTexture(0, columnAddr, 1, 1024, 4);
    b.texWrap(true, true);
    for (int k = 0; k < 2; ++k) {
        const float x = float(kWideColumnX[k]);
        sprite(k == 0, x, 0, x + 1, 64, 0.5f, 0.5f, 0.5f, 256.5f);
    }
}

// The scene's pixels that did not read the texel above, in the 512-stride 8888 frame at the start
// of `vram`: "row r x: got g, want w" and "column c y: …" (empty when all match).
inline std::vector<std::string> wideTextureMismatches(const u8* vram) {
    std::vector<std::string> bad;
    auto rgb = [&](int x, int y) { return readLE32(vram + (size_t(y) * 512 + size_t(x)) * 4) & 0xFFFFFF; };
    auto check = [&](const std::string& what, u32 got, u32 want) {
        if (got != want) bad.push_back(what + ": got " + std::to_string(got) + ", want " + std::to_string(want));
    };
    for (int r = 0; r < kWideRows; ++r)
        for (int x = 0; x < 64; ++x)
            if (x != kWideColumnX[0] && x != kWideColumnX[1])
                check("row " + std::to_string(r) + " x " + std::to_string(x), rgb(x, r), wideRowTexel(r, x));
    for (int k = 0; k < 2; ++k)
        for (int y = 0; y < 64; ++y)
            check("column " + std::to_string(kWideColumnX[k]) + " y " + std::to_string(y), rgb(kWideColumnX[k], y),
                  wideColumnTexel(y));
    return bad;
}

}  // namespace ge::testscene
