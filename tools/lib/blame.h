// SPDX-License-Identifier: MIT
// `ge2gl blame`: which draw last wrote each displayed pixel, and which draws own the pixels that
// differ from a reference (accuracy tools). Also the per-draw helpers `ge2gl bisect`
// shares (tools/lib/bisect.h): a one-line state summary, a draw's description.
//
// How ownership is found: the dump is replayed twice. The first replay, on the null backend, only
// learns the displayed frame buffer (dump::displayedFramebuffer: the last DISPLAY record, else the
// last FBP/FBW/FPF); the second replays on the chosen backend with a tools::DrawHook whose
// `after(n)` syncs that region (Renderer::syncMemoryForRead), reads its bytes from guest memory and
// compares them with the snapshot taken after the previous draw: every pixel whose bytes changed
// is owned by draw n from then on. A draw that writes the value a pixel already holds is not seen
// (the earlier owner keeps it). Pixels changed outside draws — VRAM written by the dump's CPU
// copies, block transfers, or never written — belong to "draw 0". If the second replay ends up
// displaying another buffer than the first predicted (a GE-time cut that differs between the null
// and the real backend), it is run again on the buffer it displayed.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "hle/dump/player.h"
#include "hle/renderer.h"
#include "tools/lib/image.h"
#include "tools/lib/draw_hook.h"
#include "tools/lib/render.h"

namespace ge::tools {

const char* primTypeName(GePrimType p);  // "TRIANGLES", …
const char* bufferFormatName(u32 fmt);   // "565" | "5551" | "4444" | "8888"
// One line: through/transform, clear mode, texture (format, CLUT, filter, function), blending,
// logic op, alpha/colour/depth/stencil tests, masks, fog, lighting, target buffers.
std::string stateSummary(const GeState& st);
// "prim TRIANGLES, 36 vertices" / "bezier 4x4 control points".
std::string drawDescription(const DrawInfo& d);

struct BlameOptions {
    std::string refPng;      // reference picture (480x272 or larger), or
    std::string refBackend;  // a render of the same dump by this backend
    int top = 10;            // draws listed (and tinted in the picture)
    std::string picturePath; // -o: the render with the top draws' differing pixels tinted
    std::string jsonPath;
};

struct BlameOwner {
    DrawInfo info;          // info.draw 0: pixels no draw changed (initial VRAM, transfers, CPU copies)
    u64 pixels = 0;         // differing pixels it owns
    double sqErr = 0;       // their summed squared RGB error
    double mse = 0;         // sqErr / (480*272*3): the owner's part of the frame's MSE
    double share = 0;       // sqErr / total squared error
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // bounding box of its differing pixels (inclusive)
};

struct BlameResult {
    u32 displayAddr = 0, displayStride = 0, displayFormat = 0;
    u64 draws = 0;              // draws replayed
    u64 differing = 0;          // pixels whose RGB differs from the reference
    double mse = 0;             // of the whole frame (PPSSPP's measure, tools::mseRGB)
    std::vector<BlameOwner> owners;  // every owner of a differing pixel, largest error first
    Image frame, reference;
    std::vector<u32> owner;     // 480*272: draw that last changed each pixel
    std::string warning;
};

// Replays `d` (options `ro`, scale 1) and attributes the differences from the reference.
bool blameDump(const dump::Dump& d, const RenderOptions& ro, const BlameOptions& bo, BlameResult& out, std::string& err);
// The picture for -o: the render dimmed, each of the top `top` owners' differing pixels in its own
// colour with its bounding box outlined, other differing pixels white.
Image blamePicture(const BlameResult& r, int top);

// The whole subcommand: prints the ranking, writes -o and --json. Returns the exit code.
int runBlameCommand(const std::string& dumpPath, const RenderOptions& ro, const BlameOptions& bo);

}  // namespace ge::tools
