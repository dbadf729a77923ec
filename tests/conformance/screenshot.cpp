// SPDX-License-Identifier: MIT
#include "tests/conformance/screenshot.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hle/memory.h"

namespace ge::conformance {

std::vector<u32> screenRow(u32 background, const std::vector<ScreenSpan>& spans, int y) {
    std::vector<u32> row(480, background);
    for (const ScreenSpan& s : spans) {
        if (y < s.y0 || y >= s.y1) continue;
        const int n = y - s.y0;
        for (int x = std::max(0, s.x0 + s.dx0 * n); x < std::min(480, s.x1 + s.dx1 * n); ++x) row[size_t(x)] = s.rgb;
    }
    return row;
}

std::vector<u32> displayedFrame(GuSim& gu, u32 fb, u32 format) {
    const bool wide = format == GE_FORMAT_8888;
    const u8* p = gu.readBytes(Memory::kVramBase + fb, 512 * 272 * (wide ? 4 : 2));
    std::vector<u32> out(480 * 272, 0);
    if (!p) return out;
    auto e5 = [](u32 c) { return (c << 3) | (c >> 2); };
    auto e6 = [](u32 c) { return (c << 2) | (c >> 4); };
    auto e4 = [](u32 c) { return (c << 4) | c; };
    for (u32 y = 0; y < 272; ++y)
        for (u32 x = 0; x < 480; ++x) {
            const u32 i = y * 512 + x;
            u32 r, g, b;
            if (wide) {
                const u32 c = readLE32(p + i * 4);
                r = c & 0xFF, g = (c >> 8) & 0xFF, b = (c >> 16) & 0xFF;
            } else {
                const u32 c = readLE16(p + i * 2);
                if (format == GE_FORMAT_565) {
                    r = e5(c & 31), g = e6((c >> 5) & 63), b = e5((c >> 11) & 31);
                } else if (format == GE_FORMAT_5551) {
                    r = e5(c & 31), g = e5((c >> 5) & 31), b = e5((c >> 10) & 31);
                } else {
                    r = e4(c & 15), g = e4((c >> 4) & 15), b = e4((c >> 8) & 15);
                }
            }
            out[y * 480 + x] = (r << 16) | (g << 8) | b;
        }
    return out;
}

void compareScreen(GuSim& gu, TestRun& run, u32 fb, u32 format, u32 background, const std::vector<ScreenSpan>& spans) {
    compareScreen(gu, run, fb, format, [&](int y) { return screenRow(background, spans, y); });
}

void compareScreen(GuSim& gu, TestRun& run, u32 fb, u32 format, const std::function<std::vector<u32>(int)>& row) {
    const std::vector<u32> frame = displayedFrame(gu, fb, format);
    // GE2GL_SCREENSHOT_DIR=dir writes what ge2gl shows as dir/<test with '_' for '/'>.<backend>.rgb
    // (480x272, 3 bytes a pixel, R first) for a closer look at failing rows.
    if (const char* dir = std::getenv("GE2GL_SCREENSHOT_DIR")) {
        std::string name = run.test;
        for (char& c : name)
            if (c == '/') c = '_';
        if (FILE* f = std::fopen((std::string(dir) + "/" + name + "." + run.backend + ".rgb").c_str(), "wb")) {
            for (u32 p : frame) {
                const u8 rgb[3] = {u8(p >> 16), u8(p >> 8), u8(p)};
                std::fwrite(rgb, 1, 3, f);
            }
            std::fclose(f);
        }
    }
    for (int y = 0; y < 272; ++y) {
        const std::vector<u32> want = row(y);
        u32 differing = 0;
        int first = -1;
        for (int x = 0; x < 480; ++x)
            if (frame[size_t(y) * 480 + size_t(x)] != want[size_t(x)]) {
                if (first < 0) first = x;
                ++differing;
            }
        char name[160];
        if (first < 0)
            std::snprintf(name, sizeof name, "row %d (pixels differing)", y);
        else
            std::snprintf(name, sizeof name, "row %d (pixels differing; first x=%d: %06x, PSP %06x)", y, first,
                          frame[size_t(y) * 480 + size_t(first)], want[size_t(first)]);
        run.checkpoints.push_back({name, 0, differing});
    }
}

}  // namespace ge::conformance
