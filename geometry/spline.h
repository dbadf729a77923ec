// SPDX-License-Identifier: MIT
// Bezier and spline patch tessellation (manual §5; docs/ge-rules.md §3.2). Both backends draw the
// output through their usual vertex path (transform.h onwards).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "hle/renderer.h"
#include "hle/vertex_decoder.h"

namespace ge::geo {

struct TessOutput {
    std::vector<DecodedVertex> verts;
    std::vector<u32> indices;
    GePrimType prim = GE_PRIM_TRIANGLES;
};

// Tessellates a PatchPacket (Bezier or spline with its knot types, division counts, PPM
// triangles/lines/points, PFACE): control points read through VertexReader (+indices), generated
// UVs when the vertex has none, generated normals when lighting needs them, colours/UVs/positions
// interpolated with the same basis. Output in model space. Returns false + err on bad input;
// counts below the minimum draw nothing (true, empty). `acc`: AccuracyProfile::splineOpenKnotQuirk.
// `skip`, when given, is called with the control points once they are read (ucount × vcount, row
// by row, morphing applied); returning true leaves the output empty (the call succeeds). The draw
// front end culls patches this way (DrawFrontEnd::patch).
using PatchSkip = std::function<bool(const std::vector<DecodedVertex>& controlPoints)>;
bool tessellatePatch(const Memory& mem, const GeState& st, const PatchPacket& p, const AccuracyProfile& acc,
                     TessOutput& out, std::string* err = nullptr, const PatchSkip& skip = {});

// Basis helpers exposed for tests: cubic Bezier (Bernstein) weights at t, and the spline knot
// vector for n control points and a knot type (bit 0 start open, bit 1 end open).
void bezierWeights(float t, float w[4]);
void splineKnots(int n, int knotType, std::vector<float>& knots);

}  // namespace ge::geo
