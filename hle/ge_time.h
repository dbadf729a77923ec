// SPDX-License-Identifier: MIT
// The GE-time estimate: how long the GE would take for the work of a list, in cycles of the
// PSP's 222 MHz CPU clock. Used to bound replays in emulated time (ge2gl --max-ge-ms) so that a
// small hostile dump cannot buy minutes of work, and reported by `render --stats`.
//
// Sources (no measured figures exist in this project yet; a hardware measurement beats both):
//  - commands, list start/END, vertices, BBOX and block transfers: PPSSPP's estimates
//    (GPU/GPUCommon.cpp: 2 cycles a command, 60 for a list start and for END, EstimatePerVertexCost
//    per vertex, 22 per BBOX vertex — "approximate based on timings of several counts on a PSP" —
//    and 1.6 cycles per transferred byte);
//  - copies a dump player makes that the PSP never did (mapping payloads, FRAMEBUF data): 1/16
//    cycle a byte, so that they are bounded too without weighing on real frames;
//  - pixels, which PPSSPP does not count: the PSP's published fill rate of 664 Mpixels/s, i.e.
//    222/664 ≈ 1/3 cycle per pixel, charged for the bounding boxes the backend reports
//    (Renderer::pixelWork), an upper bound of what a primitive writes.
#pragma once
#include "hle/ge_state.h"

namespace ge::getime {

constexpr u64 kCyclesPerSecond = 222'000'000;
constexpr u64 kPerCommand = 2;
constexpr u64 kListStart = 60;
constexpr u64 kEnd = 60;
constexpr u64 kPerBBoxVertex = 22;

// PPSSPP's EstimatePerVertexCost: transform 20, lighting 10 + 7 per enabled light, 20 for a
// texture-coordinate generation other than UV, 5 per morph weight when morphing.
inline u64 perVertexCost(const GeState& st) {
    u64 cost = 20;
    if (st.LTE_on()) {
        cost += 10;
        for (int i = 0; i < 4; ++i)
            if (st.LE_on(i)) cost += 7;
    }
    if (st.TMAP_mode() != 0) cost += 20;
    const u64 morphs = ((st.op(GE_CMD_VTYPE) >> 18) & 7) + 1;
    if (morphs > 1) cost += 5 * morphs;
    return cost;
}
inline u64 transferCost(u64 bytes) { return bytes * 16 / 10; }
inline u64 pixelCost(u64 pixels) { return pixels / 3; }
// Copies a dump player makes on its own (no PSP work): a host memcpy's pace, ~16 bytes a cycle.
inline u64 hostCopyCost(u64 bytes) { return bytes / 16; }
inline u64 cyclesFromMs(double ms) { return u64(ms * double(kCyclesPerSecond) / 1000.0); }
inline double msFromCycles(u64 c) { return double(c) * 1000.0 / double(kCyclesPerSecond); }

}  // namespace ge::getime
