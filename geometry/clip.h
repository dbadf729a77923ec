// SPDX-License-Identifier: MIT
// Clipping and discard rules of the software model, run by both backends (manual §10;
// docs/ge-rules.md §8.5).
//
//  - The only geometric clipping is against the near plane (z < −w), whatever CMD_CLE says: CLE
//    selects only the depth clamp and the discard rule (ge-rules.md §8.5; PPSSPP's
//    Clipper::ProcessTriangle/ProcessLine clip on negative Z in both cases). There is no X/Y
//    clipping (drawing is limited by the scissor instead).
//  - A vertex outside screen X/Y [0, 4096) drops the whole primitive (CLE = 1 exempts vertices
//    whose Z was clamped); with CLE = 0 so does a screen Z outside [0, 65536).
//  - CLE = 0: any vertex with |z/w| ≥ 1.00003 drops the primitive. CLE = 1: only when all its
//    vertices are beyond the same plane (near or far).
//  - Triangles whose three vertices have w < 0 are dropped.
//  - None of this applies in through mode.
#pragma once
#include "geometry/transform.h"

namespace ge::geo {

// −1 beyond the near plane, +1 beyond the far plane, 0 inside, by |z/w| ≥ 1.00003 (ge-rules.md §8.5).
int depthSide(const ClipVertex& v);
// Strictly behind the near clip plane z = −w: the part that near clipping removes.
inline bool beyondNear(const ClipVertex& v) { return v.clip[2] < -v.clip[3]; }

// The ge-rules.md §8.5 discard decision for a primitive of n (1–3) transformed, non-through vertices
// (their ClipVertex::side, which projectToScreen sets).
bool discardPrimitive(const TransformState& ts, const ClipVertex* const* v, int n);

// Point on segment a→b at parameter t (clip space; colours with 8-bit weights as the GE's
// interpolators), projected to the screen without a range check.
void lerpVertex(const TransformState& ts, const ClipVertex& a, const ClipVertex& b, float t, ClipVertex& out);

// Clips triangle (a, b, c) against the near plane z ≥ −w. Writes the remaining convex polygon
// in the same winding to `out` and returns its vertex count (0, 3 or 4); the caller draws it as a
// fan from out[0]. As upstream PPSSPP's clipper: new vertices are interpolated from the outside
// vertex toward the inside one; a new vertex landing outside the [0, 4096) screen range drops the
// fan triangles that use it (the polygon is shortened accordingly); and when the clipped polygon
// winds negatively on screen it is rotated to start where clipping (c, b, a) would start.
int clipTriangleNear(const TransformState& ts, const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                     ClipVertex out[4]);
// The reference renderer clips a triangle of a strip or fan in the order it keeps the vertices in
// (TransformUnit::SubmitPrimitive: strip vertex k in slot k mod 3; fan centre in slot 0, then odd
// and even vertices in slots 1 and 2), handing that order and its reverse to
// Clipper::ProcessTriangle. Which polygon vertex the clip starts at, and so the fan that splits
// it and which pieces the screen-range rule drops, follow that order — not the winding order.
// True when `ring` (a permutation of the winding order a, b, c) runs the other way round, so
// the pieces of its clipped polygon are wound opposite to the primitive.
inline bool ringReversed(const u32 ring[3], u32 a, u32 b) {
    const int p = ring[0] == a ? 0 : (ring[1] == a ? 1 : 2);
    return ring[(p + 1) % 3] != b;
}

// Clips a line to z ≥ −w in place; false when nothing is left.
bool clipLineNear(const TransformState& ts, ClipVertex& a, ClipVertex& b);

}  // namespace ge::geo
