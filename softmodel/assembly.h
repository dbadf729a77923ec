// Primitive-assembly rules shared by the software model (soft_renderer.cpp) and the GL translator
// (translator/vertex_pipeline.cpp), so that both backends build the same primitives from a draw.
//
// PPSSPP's software renderer, which made the reference renders, draws four strip vertices (and a
// fan of exactly four) that form an axis-aligned rectangle with matching attributes as a
// RECTANGLES primitive (TransformUnit's DetectRectangleFromStrip / DetectRectangleFromFan): it
// samples rectangles at pixel centres and steps their texture coordinates differently from
// triangles (raster.cpp), so which quads count decides pixels.
#pragma once
#include "hle/ge_state.h"
#include "softmodel/transform.h"

namespace ge::soft {

// What the detection needs from the state, per PRIM. `allowed` only for a fresh PRIM (no vertices
// still open from a continued one); the caller also requires culling off.
struct RectDetect {
    bool allowed = false;
    bool depthMatters = false;  // Z must match unless depth is neither tested nor written
    bool textured = false;      // texture coordinates must match along the edges
    bool fog = false;           // fog factors within half a step
    bool through = false;
    // `textured`: CMD_TME as the caller draws it; `fresh`: no vertices pending.
    static RectDetect fromState(const GeState& st, bool through, bool textured, bool fresh);
};

// Four strip vertices q[0..3] (in strip order) forming a rectangle: true with `tl`/`br` the indices
// (0–3) of the top-left and bottom-right vertices (the rectangle's v0 and v1).
bool stripQuadAsRect(const RectDetect& rd, const ClipVertex* const q[4], int& tl, int& br);
// A fan of exactly four vertices (centre first) forming a rectangle with texture growing towards
// the bottom-right: true with `tl`/`br` as above.
bool fanQuadAsRect(const RectDetect& rd, const ClipVertex* const q[4], int& tl, int& br);

}  // namespace ge::soft
