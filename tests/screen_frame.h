// SPDX-License-Identifier: MIT
// The full PSP screen as the scene headers draw it: a 512-stride 8888 frame at VRAM offset 0
// (depth at 0x88000), scissor and region over 480x272, the screen offset and viewport that map
// clip (−1..1, 1..−1) onto those pixels, and sceGuDepthRange(65535, 0). Shared by
// the scene headers and tests/gl_accuracy_profiles.cpp.
#pragma once
#include "authoring/list_builder.h"

namespace ge::testscene {

inline void screenFrame(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0x88000, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.offset(2048 - 240, 2048 - 136);
    b.viewport(2048, 2048, 480, 272);
    b.depthRange(65535, 0);
}

// Identity world, view and projection matrices and no back-face culling: clip space is model
// space, so a scene places its vertices in clip coordinates directly.
inline void identityTransform(ListBuilder& b) {
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    b.setMatrix(GeMatrix::World, id);
    b.setMatrix(GeMatrix::View, id);
    b.setMatrix(GeMatrix::Proj, id);
    b.enable(GE_CMD_BCE, false);
}

}  // namespace ge::testscene
