// SPDX-License-Identifier: MIT
// Rasterisation as the software model does it: triangles, rectangles, lines and points in drawing
// coordinates → Fragments (manual §3.6, §4, §8; docs/ge-rules.md §8.1, §8.2, §8.6, §8.11, §6.6).
//
// Positions are fixed point with 4 fraction bits (1/16 pixel, ge-rules.md §8.1); pixel centres are at +0.5
// (manual §3.6), i.e. at 16·x + 8 — except that triangles sample at 16·x + 7 unless
// RasterParams::sampleCentre, as the reference renderer (PPSSPP's software GE) does. Coverage is decided with exact 64-bit integer edge functions:
//   - triangles: top-left fill rule — pixels whose sample point is exactly on a right edge or on a
//     bottom edge parallel to X are not drawn (manual Figure 4-9, ge-rules.md §8.1); zero-area triangles draw
//     the samples exactly on their line when the fill rule allows it, as the reference renderer
//     does (ge-rules.md §8.11);
//   - rectangles: centres in [x1, x2) × [y1, y2), independent of vertex order (ge-rules.md §8.1), plus a far
//     edge exactly on the centre of the second pixel of a 2×2 quad (the reference's quad walk);
//   - lines: the reference renderer's walk of max(|dx|, |dy|) / 16 double-precision steps,
//     leaving out the end pixel (ge-rules.md §8.11);
//   - points: the one pixel containing the vertex (manual §4.1).
// Attributes (ge-rules.md §8.1): triangle Z and colours interpolated linearly in screen space in single
// precision and rounded to nearest (the reference renderer's x86 arithmetic); fog in
// screen space; texture coordinates perspective-correct (linear for rectangles and through mode,
// where W = 1). The level of detail for TLEVEL mode 0 is derived per 2×2 pixel quad from the
// change of s across X and of t down Y (ge-rules.md §6.6).
//
// Everything is limited to the clip rectangle (scissor ∩ REGION2, ge-rules.md §8.6) and to the rows of one
// Band, so several threads can rasterise the same primitives into disjoint rows.
//
// Both backends run this code: the software model rasterises everything with it; the GL
// translator's exact mode takes its triangle and rectangle setup (the block at the end) and the
// fragments of lines and points, so the two cover the same pixels with the same attributes.
#pragma once
#include <cmath>
#include <cstddef>

#include "geometry/fragment.h"
#include "hle/types.h"

namespace ge::geo {

// Round to nearest, ties to even, as std::nearbyint in the default rounding mode (and as the
// reference's cvtps2dq) — without the library call baseline x86-64 makes for it (no SSE4.1
// roundss): adding and subtracting 1.5·2^23 leaves the integer part rounded that way for
// |x| < 2^22 (the project builds with -ffp-contract=off and without -ffast-math, so the two
// additions stay). The sign of a zero result may differ from nearbyint's; every caller converts
// to an integer.
inline float roundHalfEven(float x) {
    if (!(std::fabs(x) < 4194304.0f)) return std::nearbyint(x);  // large, infinite or NaN
    return (x + 12582912.0f) - 12582912.0f;
}

// A vertex in drawing coordinates, ready to rasterise.
struct ScreenVertex {
    int x = 0, y = 0;      // drawing coordinates × 16 (OFFSETX/Y already removed)
    int z = 0;             // screen Z, 0–65535
    float fog = 1.0f;      // fog factor f (1 = no fog, 0 = fog colour); becomes 8 bits per pixel
    float s = 0, t = 0;    // texture coordinates, units of the level-0 size (SU/SV/TU/TV applied)
    float q = 1;           // projective divisor (texture projection mapping), else 1
    float w = 1;           // clip-space W (1 in through mode and for immediate vertices)
    u8 color[4] = {};      // primary RGBA
    u8 secondary[3] = {};  // secondary RGB
};

// Per-draw rasteriser settings.
struct RasterParams {
    // Inclusive clip rectangle in drawing coordinates (scissor ∩ REGION2, ge-rules.md §8.6).
    int clipX1 = 0, clipY1 = 0, clipX2 = -1, clipY2 = -1;
    bool gouraud = true;     // CMD_SHADE (rectangles always use their second vertex, manual §8)
    bool textured = false;   // compute s, t (and lod)
    bool needLod = false;    // TLEVEL mode 0: compute the per-quad level of detail
    bool needW = false;      // TLEVEL mode 2: per-pixel clip W
    bool fog = false;        // convert the interpolated fog factor (else fog = 255)
    bool through = false;    // through mode: texture coordinates screen-linear (no 1/w weighting)
    // A RECTANGLES draw (TransformState::sprite), not a strip or fan quad drawn as a rectangle
    // (assembly.h): the pixel on its far edge is left out, as on a PSP (rectangleSetup).
    bool sprite = false;
    // Zero-area triangles draw the samples exactly on their line, as PPSSPP does
    // (AccuracyProfile::zeroAreaTriangles; rasterTriangle); else they draw nothing.
    bool zeroAreaTriangles = true;
    // Triangles sample at the pixel centre (AccuracyProfile::pspTriangleSampleCentre;
    // triangleSampleOffset).
    bool sampleCentre = false;
    // Gouraud colours stepped from the top vertex by gradients of 8 fraction bits, rounded down
    // (AccuracyProfile::pspColourGradients; colourGradientReference); else interpolated in float
    // and rounded to nearest, as PPSSPP does.
    bool colourGradients = false;
    // Lines sampled at pixel centres along their longer axis (AccuracyProfile::pspLineCentres;
    // rasterLine); else PPSSPP's walk of whole steps.
    bool lineCentres = false;
    float texW0 = 1, texH0 = 1;  // level-0 coordinate size 2^n, unclamped (level of detail; texture_size.h)
};

// Rows owned by one rasterising thread: blocks of 16 rows are dealt round-robin to `count` bands,
// so every pixel belongs to exactly one band. Blocks are even-aligned, so 2×2 quads never straddle.
struct Band {
    static constexpr int kShift = 4;
    int index = 0, count = 1;
    bool owns(int y) const { return count <= 1 || ((y >> kShift) % count) == index; }
    // True when some row in [y1, y2] belongs to this band.
    bool overlaps(int y1, int y2) const;
};

// Fragment collector: buffers fragments and hands them on in order (to shadeFragments in the
// renderer, to a test callback in the tests).
class FragmentSink {
public:
    using FlushFn = void (*)(void* ctx, const Fragment* frags, size_t n);
    FragmentSink(Fragment* buffer, size_t capacity, FlushFn fn, void* ctx)
        : buf_(buffer), cap_(capacity), fn_(fn), ctx_(ctx) {}
    Fragment& next() {
        if (n_ == cap_) flush();
        return buf_[n_++];
    }
    void flush() {
        if (n_) fn_(ctx_, buf_, n_);
        n_ = 0;
    }
    void setTarget(FlushFn fn, void* ctx) {
        flush();
        fn_ = fn, ctx_ = ctx;
    }

private:
    Fragment* buf_;
    size_t cap_;
    size_t n_ = 0;
    FlushFn fn_;
    void* ctx_;
};

// Triangle; the vertex order may be either winding (culling is the caller's job). `provoking`
// gives the flat-shading colour (ge-rules.md §8.1: the last vertex of the triangle).
void rasterTriangle(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                    const ScreenVertex& provoking, const Band& band, FragmentSink& sink);
// Rectangle from two opposite corners; colour, Z and fog from v1, texture orientation per ge-rules.md §8.2.
void rasterRectangle(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const Band& band,
                     FragmentSink& sink);
// Line from v0 to v1 without its end pixel; flat colour from v1 (ge-rules.md §8.1).
void rasterLine(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const Band& band,
                FragmentSink& sink);
void rasterPoint(const RasterParams& rp, const ScreenVertex& v, const Band& band, FragmentSink& sink);

enum class PrimKind : u8 { Point, Line, Triangle, Rect };

// Inclusive pixel-row range a primitive can touch after clipping (for skipping whole bands);
// false when it certainly covers nothing. `v` holds 1 (point), 2 (line, rectangle) or 3 vertices.
bool primitiveRows(const RasterParams& rp, PrimKind kind, const ScreenVertex* const* v, int& y1, int& y2);
// An upper bound of the pixels the primitive can write, for the GE-time estimate (hle/ge_time.h):
// the clip-rectangle-limited bounding box of a triangle or rectangle, the longer axis of a line,
// 1 for a point. Rows y1..y2 as primitiveRows gave them.
u64 primitivePixelBound(const RasterParams& rp, PrimKind kind, const ScreenVertex* const* v, int y1, int y2);

// Helpers exposed for tests.
// Fog factor → 8 bits (ge-rules.md §8.9): 0 for f ≤ 0 (sign set), 255 for f ≥ 1, else floor(f·256).
u8 fogToByte(float f);
// log2 as the software GE approximates it: exponent plus the mantissa as a linear fraction
// (8 fraction bits), sign ignored; 0 gives −127. Exact for powers of two.
float texLog2(float v);

// ---- Interpolation setup shared with the GL translator (translator/tri_setup.h) ----
// The GL backend evaluates triangle attributes per pixel from the very numbers this rasteriser
// uses, so changes to this arithmetic reach both backends.
// Which attributes of a triangle are the same at its three vertices (rasterTriangle's shortcuts,
// shared with the GL records): Z; primary and secondary colours (always with flat shading);
// fog when it is off or no vertex is fogged (the reference interpolates fog even between equal
// factors, and the float sum need not give the value back). `source` gives the colours when
// they are constant: in0, or the provoking vertex with flat shading.
struct TriangleConstants {
    bool z = false, color = false, secondary = false, fog = false;
    const ScreenVertex* source = nullptr;
};
TriangleConstants triangleConstants(const RasterParams& rp, const ScreenVertex& in0, const ScreenVertex& in1,
                                    const ScreenVertex& in2, const ScreenVertex& prov);
// Gouraud colour under RasterParams::colourGradients (AccuracyProfile::pspColourGradients).
// Each channel (primary RGBA, secondary RGB) is stepped from a reference vertex, the top one:
// with E_k = A_k·sx + B_k·sy + C_k the edge function weighting vertex k and area = ΣE_k, the
// per-pixel gradients 16·Σc_k·A_k / area and 16·Σc_k·B_k / area are held to 8 fraction bits,
// rounded toward −∞ (gx, gy = ⌊4096·Σc_k·A_k / area⌋, …), and the value at the sample point
// (sx, sy) (1/16 pixel) is ⌊(4096·c_ref + gx·(sx − x_ref) + gy·(sy − y_ref)) / 4096⌋, kept to
// 0–255. Equal vertex values give the value back exactly (zero gradients). The GL exact shader
// evaluates the same integers from the record (translator/tri_setup.cpp). This returns the index
// in `o` of the reference vertex: the least y, then the least x.
inline int colourGradientReference(const ScreenVertex* const o[3]) {
    int r = 0;
    for (int i = 1; i < 3; ++i)
        if (o[i]->y < o[r]->y || (o[i]->y == o[r]->y && o[i]->x < o[r]->x)) r = i;
    return r;
}

// The gradient planes of a triangle of positive `area` (twice its signed area, 1/16 units), its
// vertices in attribute order `o`, and rasterTriangle's edge coefficients A, B (the edge weighting
// o[k] is k, or (k + 1) % 3 when the triangle was `swapped` to clockwise order): channels 0–3
// primary RGBA, 4–6 secondary RGB; `ref` the index of the reference vertex in o, refC its values.
// The software rasteriser and the GL exact record (translator/tri_setup.cpp) both use this.
struct GradientPlanes {
    int ref = 0;
    int refC[7] = {};
    s64 gx[7] = {}, gy[7] = {};
};
GradientPlanes colourGradientPlanes(const ScreenVertex* const o[3], const s64 A[3], const s64 B[3], bool swapped,
                                    s64 area);

// A rectangle as rasterRectangle walks it: the covered pixels (inclusive, clipped) and the texture
// coordinates in single precision — s, t at the first pixel centre and their change per two
// pixels along X and down Y (an odd pixel of a pair adds half a step). False when it covers
// nothing.
struct RectSetup {
    int px1 = 0, py1 = 0, px2 = -1, py2 = -1;
    float rowS = 0, rowT = 0, stxS = 0, stxT = 0, styS = 0, styT = 0;
};
bool rectangleSetup(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, RectSetup& out);
// 1/w as rasterTriangle weights perspective-correct texture coordinates with (w near 0 kept away
// from a division by zero).
double perspectiveRecip(float w);
// Level of detail from the per-pixel steps of s across X and of t down Y (ge-rules.md §6.6 mode 0), as
// rasterTriangle / rasterRectangle form Fragment::lod.
float lodFromTexSteps(const RasterParams& rp, double ds, double dt);
// Where rasterTriangle samples pixel (x, y): (16·x + o, 16·y + o) in 1/16 pixel, o returned here.
// PPSSPP's software renderer samples at o = 7, half a pixel less 1/16 (TriangleEdge::Start,
// "centerOff = SCREEN_SCALE_FACTOR / 2 - 1"): coverage, colours, depth, fog and texture
// coordinates all come from the edge functions there, and sampling elsewhere shifts every texture
// coordinate by a sixteenth of a pixel (docs/accuracy.md). The PSP samples at the centre, o = 8
// (AccuracyProfile::pspTriangleSampleCentre).
inline int triangleSampleOffset(const RasterParams& rp) { return rp.sampleCentre ? 8 : 7; }

}  // namespace ge::geo
