// SPDX-License-Identifier: MIT
// Per-triangle records for exact interpolation on the GL path (shadergen/shader_gen.h `tri`
// layout, HostCaps::exactInterp).
//
// Why: GL interpolates attributes in float from the vertices; the software model (as the
// reference renderer) evaluates single-precision sums of vertex values (depth included, rounded)
// weighted by exact edge functions, at its own sample point (16·x + 7), in its own vertex order.
// These records carry the software rasteriser's own per-triangle numbers — its oriented edge
// functions and sample offset (geo::triangleSampleOffset), the vertex depths in attribute
// order, its attribute order, weight reciprocal and constant-attribute
// shortcuts — and the fragment shader (shadergen emitExactHelpers) repeats rasterTriangle's
// per-pixel arithmetic on them. Setup changes in geometry/raster.cpp reach GL through the shared
// functions; a change to the per-pixel formulas must be mirrored in shader_gen.cpp (the GlParity
// tests fail until it is).
#pragma once
#include "geometry/raster.h"
#include "hle/types.h"
#include "shadergen/shader_gen.h"

namespace ge::gl {

struct TriRecord {
    u32 w[shadergen::tri::kTexels * 4];
};
// A triangle's colour gradient planes (shadergen tri::kGradTexels), kept apart from the records:
// only triangles under RasterParams::colourGradients with a Gouraud colour have them.
struct GradientRecord {
    u32 w[shadergen::tri::kGradTexels * 4];
};
// The record's gradient planes index (tri::kClipW.w), valid when the record has the flag.
bool hasGradients(const TriRecord& r);
u32& gradientIndex(TriRecord& r);

// Triangle (in0, in1, in2) with flat-shading colour `prov`, as geo::rasterTriangle sees it.
// True when the triangle steps its colours by gradient planes: they are in `grad`, and the
// caller sets gradientIndex(out) to where it keeps them.
bool packTriangle(const geo::RasterParams& rp, const geo::ScreenVertex& in0, const geo::ScreenVertex& in1,
                  const geo::ScreenVertex& in2, const geo::ScreenVertex& prov, TriRecord& out, GradientRecord& grad);
// Rectangle from two corners, as geo::rasterRectangle sees it (both GL triangles get this record).
// False when it covers no pixel; else `box` gets the covered pixels, inclusive (x1, y1, x2, y2):
// the GL quad must cover exactly those.
bool packRectangle(const geo::RasterParams& rp, const geo::ScreenVertex& v0, const geo::ScreenVertex& v1,
                   TriRecord& out, int box[4]);
// One finished fragment (lines and points come from the software rasteriser as fragments).
void packFragment(const geo::Fragment& f, TriRecord& out);

}  // namespace ge::gl
