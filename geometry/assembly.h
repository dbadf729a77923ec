// SPDX-License-Identifier: MIT
// Primitive assembly, the part of the draw front end (draw_front_end.h) that both backends run:
// the walk over a PRIM's vertices (assemblePrimitives), the corners of rectangles drawn as
// triangles, and strip/fan-as-rectangle detection.
//
// PPSSPP's software renderer, which made the reference renders, draws four strip vertices (and a
// fan of exactly four) that form an axis-aligned rectangle with matching attributes as a
// RECTANGLES primitive (TransformUnit's DetectRectangleFromStrip / DetectRectangleFromFan): it
// samples rectangles at pixel centres and steps their texture coordinates differently from
// triangles (raster.cpp), so which quads count decides pixels.
#pragma once
#include <vector>

#include "geometry/transform.h"
#include "hle/ge_state.h"
#include "hle/renderer.h"

namespace ge::geo {

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

// Immediate-mode vertices (CMD_X2 … CMD_AP2) as clip vertices, already in drawing coordinates
// (no transform, lighting or clipping): positions to 1/16 pixel (kept within ±65536 pixels),
// through-mode texels divided by the level-0 size (docs/ge-rules.md §8.10), Q only with texture projection, the
// fog byte as a factor (fogToByte gives the byte back), the secondary colour only with LMODE 1 in
// transform mode (else none; hardware values in assembly.cpp). `out` is resized to the vertices and
// `seq` receives their draw order.
void immediateVertices(const GeState& st, const std::vector<ImmVertex>& in, std::vector<ClipVertex>& out,
                       std::vector<u32>& seq);

// Corner (fx, fy) ∈ {0, 1}² (0: left / top) of the rectangle v0–v1 when it is drawn as two
// triangles (texture projection, ge-rules.md §8.2): the corner's position, colour/Z/fog of v1, W = 1, and s
// and q from the vertex figure 4-14's orientation gives that corner's column, t from the one it
// gives the corner's row.
ScreenVertex rectangleCorner(const ScreenVertex& v0, const ScreenVertex& v1, int fx, int fy);

// The primitive walk both backends share (ge-rules.md §3.2, §4, §8.11): splits `seq` (vertex indices in draw
// order) into the primitives of `prim` and hands them to `sink`, which provides
//   void point(u32 i);  void line(u32 i, u32 j);  void rectangle(u32 v0, u32 v1);
//   void triangle(u32 a, u32 b, u32 c, const u32* ring);  // (a, b, c): winding; c provokes
//   bool quadAsRect(bool fan, const u32 q[4], u32& tl, u32& br);  // stripQuadAsRect / fanQuadAsRect
// `detect`: strip/fan quads may be drawn as rectangles (a fresh PRIM without culling, see
// RectDetect). `stripOdd` carries the strip winding parity across PRIM type 7 continuations.
// `keep` receives what a continuation needs: vertices that do not complete a primitive, the last
// two of a strip, the centre and last vertex of a fan.
template <class Sink>
void assemblePrimitives(GePrimType prim, const std::vector<u32>& seq, bool detect, bool& stripOdd, Sink& sink,
                        std::vector<u32>& keep) {
    const size_t n = seq.size();
    keep.clear();
    switch (prim) {
    case GE_PRIM_POINTS:
        for (size_t i = 0; i < n; ++i) sink.point(seq[i]);
        break;
    case GE_PRIM_LINES:
        for (size_t i = 0; i + 1 < n; i += 2) sink.line(seq[i], seq[i + 1]);
        if (n & 1) keep.push_back(seq[n - 1]);
        break;
    case GE_PRIM_LINE_STRIP:
        for (size_t i = 1; i < n; ++i) sink.line(seq[i - 1], seq[i]);
        if (n) keep.push_back(seq[n - 1]);
        break;
    case GE_PRIM_TRIANGLES:
        for (size_t i = 0; i + 2 < n; i += 3) sink.triangle(seq[i], seq[i + 1], seq[i + 2], nullptr);
        for (size_t i = n - n % 3; i < n; ++i) keep.push_back(seq[i]);
        break;
    case GE_PRIM_TRIANGLE_STRIP: {
        // A fresh strip of an even number of vertices is first read as quads of four, each drawn
        // as a rectangle while it is one; from the first quad that is not, the rest is an
        // ordinary strip.
        size_t start = 0;
        if (detect && !stripOdd && n >= 4 && (n & 1) == 0) {
            for (size_t base = 0; base + 2 < n; base += 2) {
                const u32 quad[4] = {seq[base], seq[base + 1], seq[base + 2], seq[base + 3]};
                u32 tl = 0, br = 0;
                if (!sink.quadAsRect(false, quad, tl, br)) break;
                sink.rectangle(tl, br);
                start = base + 2;
                if (base + 4 >= n) start = n;
            }
        }
        // Every second triangle is wound the other way round; the newest vertex provokes. The
        // reference renderer keeps strip vertices in a ring of three slots (vertex k in slot
        // k mod 3) and rasterises the slots in order (TransformUnit::SubmitPrimitive), which
        // decides the order of its float attribute sums (raster.cpp). (After quads drawn as
        // rectangles, the newest upstream restarts the ring with the last two vertices in slots
        // 2 and 0; the reference renders match counting from the strip start better.)
        for (size_t i = start + 2; i < n; ++i) {
            u32 ring[3];
            for (size_t k = i - 2; k <= i; ++k) ring[k % 3] = seq[k];
            if (!stripOdd) sink.triangle(seq[i - 2], seq[i - 1], seq[i], ring);
            else sink.triangle(seq[i - 1], seq[i - 2], seq[i], ring);
            stripOdd = !stripOdd;
        }
        for (size_t i = n > 2 ? n - 2 : 0; i < n; ++i) keep.push_back(seq[i]);
        break;
    }
    case GE_PRIM_TRIANGLE_FAN:
        if (detect && n == 4) {
            const u32 quad[4] = {seq[0], seq[1], seq[2], seq[3]};
            u32 tl = 0, br = 0;
            if (sink.quadAsRect(true, quad, tl, br)) {
                sink.rectangle(tl, br);
                keep = {seq[0], seq[3]};
                break;
            }
        }
        // The reference's ring for fans: the centre in slot 0, odd-numbered vertices in slot 1,
        // even-numbered ones in slot 2 (see the strip case).
        for (size_t i = 2; i < n; ++i) {
            const u32 ring[3] = {seq[0], (i & 1) ? seq[i] : seq[i - 1], (i & 1) ? seq[i - 1] : seq[i]};
            sink.triangle(seq[0], seq[i - 1], seq[i], ring);
        }
        if (n >= 2) keep = {seq[0], seq[n - 1]};
        else if (n == 1) keep = {seq[0]};
        break;
    case GE_PRIM_RECTANGLES:
        for (size_t i = 0; i + 1 < n; i += 2) sink.rectangle(seq[i], seq[i + 1]);
        if (n & 1) keep.push_back(seq[n - 1]);
        break;
    default: break;
    }
}

}  // namespace ge::geo
