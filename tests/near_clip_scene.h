// SPDX-License-Identifier: MIT
// A triangle with one vertex behind the camera (w < 0) that still passes CLE = 0's discard rule
// (|z/w| < 1, screen X/Y/Z in range): near clipping happens whatever CLE says (docs/ge-rules.md §8.5;
// PPSSPP Clipper::ProcessTriangle), so both CLE values draw the clipped quadrilateral,
// never the inverted triangle the unclipped vertex projects to. Shared by the software-model and
// GL tests.
//
// Projection: x_c = x, y_c = y, z_c = −0.25, w = z. A (−0.5, −0.5, 1) and B (0.5, −0.5, 1) are in
// front; C (0, 0.9, −0.5) is behind the camera. The near plane z_c = −w cuts AC and BC halfway, at
// w = 0.25: A' = (−0.25, 0.2) → screen (0, 27.2), B' → (480, 27.2). A and B land at (120, 204) and
// (360, 204). Clipped: the quadrilateral A B B' A' (rows 28–203). Unclipped, C would project to
// (240, 380.8) and the triangle would cover rows 204 and below instead.
#pragma once
#include "authoring/list_builder.h"
#include "tests/screen_frame.h"

namespace ge::testscene {

// Frame, identity world/view, the projection above, CLE, no culling.
inline void nearClipFrame(ListBuilder& b, bool cle) {
    screenFrame(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF000000, 0);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    b.setMatrix(GeMatrix::World, id);
    b.setMatrix(GeMatrix::View, id);
    // Column-major: column 2 (z) feeds w, column 3 (translation) gives z_c = −0.25.
    const float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, -0.25f, 0};
    b.setMatrix(GeMatrix::Proj, proj);
    b.enable(GE_CMD_CLE, cle);
    b.enable(GE_CMD_BCE, false);
}

inline void nearClipScene(ListBuilder& b, bool cle) {
    nearClipFrame(b, cle);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
    BuildVertex v[3];
    v[0].x = -0.5f, v[0].y = -0.5f, v[0].z = 1.0f;
    v[1].x = 0.5f, v[1].y = -0.5f, v[1].z = 1.0f;
    v[2].x = 0.0f, v[2].y = 0.9f, v[2].z = -0.5f;
    const auto bytes = packVertices(vtype, v, 3);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, bytes.data());
}

// Pixels of the 512-stride 8888 frame at VRAM offset 0 the scene must (not) cover.
struct ClipProbe {
    int x, y;
    bool covered;
};
inline constexpr ClipProbe kNearClipProbes[] = {
    {240, 120, true}, {240, 30, true}, {10, 30, true}, {470, 30, true},  // inside A B B' A'
    {10, 200, false}, {240, 20, false},                                   // outside its edges
    {240, 210, false}, {240, 240, false},                                 // where the inverted one would be
};

// A fan whose centre is behind the camera: centre C and A, B as above, then D (5, −0.5, 1), which
// lands off screen to the right (x = 1440, still inside the 4096 range). The second fan triangle
// (C, B, D) crosses the near plane at B' (480, 27.2) on CB and at D' (2.5, 0.2) on CD, which
// projects to x ≥ 4096: out of range, so every piece of the clipped polygon that uses D' is
// dropped. The reference keeps the fan's odd vertices in slot 1 and clips (C, D, B) — its reverse
// (B, D, C) is the one wound positively on screen, giving the polygon B D D' B' split from B into
// (B, D, D') and (B, D', B'): both use D', nothing is drawn. Clipping in winding order (C, B, D)
// instead would split B' B D D' from the other diagonal and keep (D, B, B').
// With `asTriangles` the same two triangles are drawn as GE_PRIM_TRIANGLES (C, A, B), (C, B, D):
// the reference then clips (C, B, D) in that order and keeps the piece (D, B, B').
inline void nearClipFanScene(ListBuilder& b, bool asTriangles) {
    nearClipFrame(b, false);
    constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
    BuildVertex c, va, vb, vd;
    c.x = 0.0f, c.y = 0.9f, c.z = -0.5f;
    va.x = -0.5f, va.y = -0.5f, va.z = 1.0f;
    vb.x = 0.5f, vb.y = -0.5f, vb.z = 1.0f;
    vd.x = 5.0f, vd.y = -0.5f, vd.z = 1.0f;
    if (asTriangles) {
        const BuildVertex v[6] = {c, va, vb, c, vb, vd};
        const auto bytes = packVertices(vtype, v, 6);
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 6, nullptr, bytes.data());
    } else {
        const BuildVertex v[4] = {c, va, vb, vd};
        const auto bytes = packVertices(vtype, v, 4);
        b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 4, nullptr, bytes.data());
    }
}
// (240, 120) lies in the first triangle's clipped quad; (470, 180) in the piece (D, B, B').
inline constexpr ClipProbe kFanProbeFirst = {240, 120, true};
inline constexpr int kFanWedgeX = 470, kFanWedgeY = 180;

}  // namespace ge::testscene
