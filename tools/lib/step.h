// SPDX-License-Identifier: MIT
// `ge2gl step DUMP --break KIND:N`: replays a dump on a backend and stops at one place with the GE
// debugger (debugger/debugger.h): before the command, the state, list, disassembly, the draw's
// vertices, texture and CLUT are taken; right after it has executed, the frame, depth and stencil
// buffers. docs/debugger.md.
#pragma once
#include <string>

#include "tools/lib/render.h"

namespace ge::tools {

struct StepOptions {
    // "draw:N" (the Nth PRIM/BEZIER/SPLINE from 1), "prim:N" (the Nth PRIM), "op:NAME[:N]" (the Nth
    // command with that opcode name, e.g. op:CLOAD:2), "addr:ADDR[:N]" (the Nth time the command at
    // that address runs), "command:N" (the Nth command).
    std::string breakAt;
    std::string outDir;  // PNGs: color, depth, stencil, texture-L0…, clut; empty: none
    RenderOptions render;
};

struct StepResult {
    bool hit = false;    // the break was reached
    std::string report;  // the text printed
    Image color, depth, stencil;  // after the command (480 x 272)
    u32 fbAddr = 0, fbStride = 0, fbFormat = 0;  // the frame buffer `color` was read from
};

// False with `err` for a bad break spec or an unplayable dump; a break never reached is a
// result with hit = false.
bool stepDump(const std::string& path, const StepOptions& opt, StepResult& out, std::string& err);

}  // namespace ge::tools
