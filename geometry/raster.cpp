// SPDX-License-Identifier: MIT
// Rasterisation of triangles, rectangles, lines and points (see raster.h for the rules followed).
#include "geometry/raster.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>

namespace ge::geo {

namespace {

// Floor/ceil division for a positive divisor.
inline s64 floorDiv(s64 a, s64 b) {
    s64 q = a / b;
    if ((a % b) != 0 && a < 0) --q;
    return q;
}
inline s64 ceilDiv(s64 a, s64 b) { return -floorDiv(-a, b); }

inline float finiteOr0(float v) { return std::isfinite(v) ? v : 0.0f; }

// 1/w for perspective weights, keeping clear of a division by zero.
inline double recipW(float w) {
    double d = w;
    if (!(std::fabs(d) >= 1e-20)) d = std::signbit(w) ? -1e-20 : 1e-20;
    return 1.0 / d;
}

inline int sampleRowsOfTriangle(int sample, int minY, int maxY, int& y1, int& y2) {
    y1 = int(ceilDiv(minY - sample, 16));
    y2 = int(floorDiv(maxY - sample, 16));
    return y1 <= y2;
}

// Screen-linear interpolation as the reference renderer does it in single precision: the sum of
// value·weight over the three vertices, in vertex order, times the float reciprocal of the weight
// sum (EdgeRecip/Interpolate in PPSSPP's Rasterizer.cpp). Weights are the edge functions at the
// sample point.
inline float interpolateF(float a, float b, float c, float w0, float w1, float w2, float recip) {
    float acc = a * w0;
    acc = acc + b * w1;
    acc = acc + c * w2;
    return acc * recip;
}
// Colours: rounded to nearest (the SSE conversion cvtps2dq, round-half-even), then kept to 0–255.
inline u8 interpolateColor(int a, int b, int c, float w0, float w1, float w2, float recip) {
    const float v = interpolateF(float(a), float(b), float(c), w0, w1, w2, recip);
    const float r = roundHalfEven(v);
    return u8(r <= 0.0f ? 0 : (r >= 255.0f ? 255 : int(r)));
}

// A channel's value from its gradient plane (raster.h colourGradientReference): the products are
// taken modulo 2^64, which is exact because the sum itself is small (the value within 0–255
// inside the triangle, off by the gradients' rounding over the distance from the reference).
inline u8 colourFromGradients(int cref, s64 gx, s64 gy, s64 dx, s64 dy) {
    const s64 v = s64(u64(s64(cref) * 4096) + u64(gx) * u64(dx) + u64(gy) * u64(dy));
    const s64 q = v >> 12;  // rounded toward −∞ (arithmetic shift)
    return u8(q < 0 ? 0 : (q > 255 ? 255 : q));
}

void clipRows(const RasterParams& rp, int& y1, int& y2) {
    y1 = std::max(y1, rp.clipY1);
    y2 = std::min(y2, rp.clipY2);
}

// Level of detail from per-pixel texture-coordinate steps (docs/ge-rules.md §6.6 mode 0).
inline float lodFromSteps(const RasterParams& rp, double ds, double dt) {
    return texLog2(float(std::max(std::fabs(ds) * rp.texW0, std::fabs(dt) * rp.texH0)));
}
// The same from single-precision steps, as the reference forms it (CalculateSamplingParams):
// max(|ds·w|, |dt·h|) in float.
inline float lodFromStepsF(const RasterParams& rp, float ds, float dt) {
    return texLog2(std::max(std::fabs(ds * rp.texW0), std::fabs(dt * rp.texH0)));
}

}  // namespace

GradientPlanes colourGradientPlanes(const ScreenVertex* const o[3], const s64 A[3], const s64 B[3], bool swapped,
                                    s64 area) {
    GradientPlanes g;
    g.ref = colourGradientReference(o);
    auto plane = [&](int ch, const int c[3]) {
        s64 sumA = 0, sumB = 0;
        for (int k = 0; k < 3; ++k) {
            const int e = swapped ? (k + 1) % 3 : k;  // the edge weighting o[k] (orderWeights)
            sumA += c[k] * A[e], sumB += c[k] * B[e];
        }
        g.refC[ch] = c[g.ref];
        g.gx[ch] = floorDiv(4096 * sumA, area);
        g.gy[ch] = floorDiv(4096 * sumB, area);
    };
    for (int ch = 0; ch < 4; ++ch) {
        const int c[3] = {o[0]->color[ch], o[1]->color[ch], o[2]->color[ch]};
        plane(ch, c);
    }
    for (int ch = 0; ch < 3; ++ch) {
        const int c[3] = {o[0]->secondary[ch], o[1]->secondary[ch], o[2]->secondary[ch]};
        plane(4 + ch, c);
    }
    return g;
}

u8 fogToByte(float f) {
    u32 bits;
    std::memcpy(&bits, &f, 4);
    if (bits & 0x80000000u) return 0;    // negative (and −0, negative NaN)
    if (bits >= 0x3F800000u) return 255;  // ≥ 1, +inf, positive NaN
    return u8(int(f * 256.0f));           // floor(f·256), < 1/256 gives 0
}

float texLog2(float v) {
    u32 bits;
    std::memcpy(&bits, &v, 4);
    const int useful = int((bits >> 15) & 0xFFFF);  // exponent and top 8 mantissa bits, no sign
    return float(useful - 127 * 256) / 256.0f;
}

double perspectiveRecip(float w) { return recipW(w); }

float lodFromTexSteps(const RasterParams& rp, double ds, double dt) { return lodFromSteps(rp, ds, dt); }

bool Band::overlaps(int y1, int y2) const {
    if (y1 > y2) return false;
    if (count <= 1) return true;
    const int b1 = y1 >> kShift, b2 = y2 >> kShift;
    if (b2 - b1 + 1 >= count) return true;
    for (int b = b1; b <= b2; ++b)
        if (b % count == index) return true;
    return false;
}

u64 primitivePixelBound(const RasterParams& rp, PrimKind kind, const ScreenVertex* const* v, int y1, int y2) {
    if (y2 < y1) return 0;
    const int n = kind == PrimKind::Triangle ? 3 : (kind == PrimKind::Point ? 1 : 2);
    int lo = v[0]->x, hi = v[0]->x;
    for (int k = 1; k < n; ++k) lo = std::min(lo, v[k]->x), hi = std::max(hi, v[k]->x);
    const int x1 = std::max(int(floorDiv(lo, 16)), rp.clipX1), x2 = std::min(int(floorDiv(hi, 16)), rp.clipX2);
    if (x2 < x1) return 0;
    const u64 w = u64(x2 - x1 + 1), h = u64(y2 - y1 + 1);
    if (kind == PrimKind::Point) return 1;
    if (kind == PrimKind::Line) return std::max(w, h);
    return w * h;
}

bool primitiveRows(const RasterParams& rp, PrimKind kind, const ScreenVertex* const* v, int& y1, int& y2) {
    switch (kind) {
    case PrimKind::Point:
        y1 = y2 = int(floorDiv(v[0]->y, 16));
        break;
    case PrimKind::Line: {
        const int lo = std::min(v[0]->y, v[1]->y), hi = std::max(v[0]->y, v[1]->y);
        y1 = int(floorDiv(lo - 1, 16));
        y2 = int(floorDiv(hi, 16));
        break;
    }
    case PrimKind::Rect: {
        const int lo = std::min(v[0]->y, v[1]->y), hi = std::max(v[0]->y, v[1]->y);
        y1 = int(ceilDiv(lo - 8, 16));
        y2 = int(floorDiv(hi - 8, 16));  // may include a row whose centre is on the edge
        break;
    }
    case PrimKind::Triangle: {
        const int lo = std::min({v[0]->y, v[1]->y, v[2]->y}), hi = std::max({v[0]->y, v[1]->y, v[2]->y});
        const s64 area = s64(v[1]->x - v[0]->x) * (v[2]->y - v[0]->y) - s64(v[1]->y - v[0]->y) * (v[2]->x - v[0]->x);
        if (area == 0) {  // rasterZeroAreaTriangle: every row the vertices' box touches
            if (!rp.zeroAreaTriangles) return false;
            y1 = int(floorDiv(lo, 16));
            y2 = int(floorDiv(hi, 16));
        } else {
            sampleRowsOfTriangle(triangleSampleOffset(rp), lo, hi, y1, y2);
        }
        break;
    }
    }
    clipRows(rp, y1, y2);
    return y1 <= y2;
}

namespace {

// The reference's edge bias (PPSSPP Rasterizer.cpp IsRightSideOrFlatBottomLine): −1 (exclusive)
// when `p` lies above a horizontal edge a–b, or left of a slanted/vertical one, the line's x at
// p.y formed with C++'s truncating integer division.
inline bool refRightOrFlatBottom(const ScreenVertex& p, const ScreenVertex& a, const ScreenVertex& b) {
    if (a.y == b.y) return p.y < a.y;
    return s64(p.x) < s64(a.x) + (s64(b.x) - a.x) * (s64(p.y) - a.y) / (s64(b.y) - a.y);
}

// A zero-area triangle as the reference renders rasterise it — a reference quirk (ge-rules.md §8.11;
// the renderer's caller decides whether such triangles get here).
// PPSSPP's software renderer submits a triangle as (a, b, c) and again as (c, b, a) with culling
// off (TransformUnit::SendTriangle; one order only with culling on, not modelled: no reference
// dump tells) and keeps an order unless its cross product is negative (BinManager::AddTriangle),
// so a zero-area triangle is drawn in both orders; only one whose three x or three y are all
// equal is dropped there. Its three edge functions sum
// to zero, so a sample passes (all E_i + bias_i ≥ 0) only where every E_i is 0 — on the line
// through the vertices — and no edge is biased: a thin line of pixels whose sample point lies
// exactly on it, within the pixel box of the vertices (the reference walks every pixel the box
// touches, not only centres inside it). Valkyria Chronicles draws a ring of 2×2 quads as one
// strip joined by repeated vertices; the join (v, w, w) from one quad's corner to the next quad
// draws that corner's pixel in the reference. Weights are all 0 and their reciprocal infinite, so
// attributes that are not constant come out NaN: colour and fog convert to 0, texture coordinates
// to 0 (as finiteOr0 elsewhere), depth as below.
void rasterZeroAreaTriangle(const RasterParams& rp, const ScreenVertex& in0, const ScreenVertex& in1,
                            const ScreenVertex& in2, const ScreenVertex& prov, const Band& band,
                            FragmentSink& sink) {
    if ((in0.x == in1.x && in0.x == in2.x) || (in0.y == in1.y && in0.y == in2.y)) return;
    const int minX = std::min({in0.x, in1.x, in2.x}), maxX = std::max({in0.x, in1.x, in2.x});
    const int minY = std::min({in0.y, in1.y, in2.y}), maxY = std::max({in0.y, in1.y, in2.y});
    const int px1 = std::max<int>(int(floorDiv(minX, 16)), rp.clipX1);
    const int px2 = std::min<int>(int(floorDiv(maxX, 16)), rp.clipX2);
    const int py1 = std::max<int>(int(floorDiv(minY, 16)), rp.clipY1);
    const int py2 = std::min<int>(int(floorDiv(maxY, 16)), rp.clipY2);
    if (px1 > px2 || !band.overlaps(py1, py2)) return;

    const TriangleConstants same = triangleConstants(rp, in0, in1, in2, prov);
    const ScreenVertex& cs = *same.source;
    const bool zConst = same.z, colConst = same.color, secConst = same.secondary, fogConst = same.fog;
    // NaN depth converts to INT_MIN, which the reference's depth range test (every pixel outside
    // through mode: PixelFuncID applyDepthRange) rejects whatever MINZ is; in through mode it is
    // written as its low 16 bits, 0.
    if (!zConst && !rp.through) return;

    // The level of detail from NaN steps: the reference's max(|ds·w|, |dt·h|) is a positive NaN,
    // whose float-bits log2 (texLog2) is about 128.5 levels: the smallest mipmap level.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float lod = rp.textured && rp.needLod ? lodFromStepsF(rp, nan, nan) : 0.0f;
    const int sample = triangleSampleOffset(rp);
    const ScreenVertex* orders[2][3] = {{&in0, &in1, &in2}, {&in2, &in1, &in0}};
    for (const auto& p : orders) {
        s64 A[3], B[3], C[3], bias[3];
        for (int i = 0; i < 3; ++i) {
            const ScreenVertex& a = *p[(i + 1) % 3];
            const ScreenVertex& b = *p[(i + 2) % 3];
            A[i] = s64(a.y) - b.y;
            B[i] = s64(b.x) - a.x;
            C[i] = s64(b.y) * a.x - s64(b.x) * a.y;
            bias[i] = refRightOrFlatBottom(*p[i], a, b) ? -1 : 0;
        }
        // The three E_i sum to 0, so E_i + bias_i ≥ 0 for all i needs every bias 0 and every E_i
        // exactly 0: the sample on the line. The line is not horizontal (equal y were dropped), so
        // each row has at most one such sample, found from an edge with A ≠ 0 — the same pixels,
        // in the same order, as testing every sample of the box, without walking the box.
        if (bias[0] || bias[1] || bias[2]) continue;
        const int k = A[0] != 0 ? 0 : (A[1] != 0 ? 1 : 2);
        for (int y = py1; y <= py2; ++y) {
            if (!band.owns(y)) continue;
            const s64 sy = 16 * s64(y) + sample;
            const s64 num = -(B[k] * sy + C[k]);
            if (num % A[k] != 0) continue;
            const s64 sx = num / A[k];
            const s64 xs = floorDiv(sx - sample, 16);
            if (xs * 16 != sx - sample || xs < px1 || xs > px2) continue;  // not a sample point
            Fragment& f = sink.next();
            f.x = int(xs);
            f.y = y;
            f.z = zConst ? u16(in0.z) : 0;
            for (int c = 0; c < 4; ++c) f.color[c] = colConst ? cs.color[c] : 0;
            for (int c = 0; c < 3; ++c) f.secondary[c] = secConst ? cs.secondary[c] : 0;
            f.fog = fogConst ? 255 : 0;
            f.s = f.t = 0.0f;
            f.lod = lod;
            f.w = rp.needW ? nan : 1.0f;
        }
    }
}

// One triangle's edge functions and attribute interpolation, set up once and evaluated per pixel
// and per 2×2 quad by rasterTriangle.
struct TriangleWalk {
    const RasterParams& rp;
    const ScreenVertex* v[3];  // clockwise on screen (all three edge functions positive inside)
    bool swapped = false;      // v is in0, in2, in1
    // Edge function i (opposite vertex i) from a = v[i+1] to b = v[i+2]:
    //   E_i(p) = (b.x − a.x)·(p.y − a.y) − (b.y − a.y)·(p.x − a.x) = A·p.x + B·p.y + C.
    // Top-left rule (Figure 4-9): a left edge (going up, dy < 0) or a top edge (horizontal,
    // going right) includes centres exactly on it (E ≥ 0); right and flat bottom edges do not
    // (E ≥ 1).
    s64 A[3], B[3], C[3], thr[3];
    // Attribute order (the reference's): PPSSPP's software renderer submits every triangle as
    // (a, b, c) and as (c, b, a) and draws the one with positive area (TransformUnit /
    // BinManager::AddTriangle), so a triangle of negative area is interpolated in the order
    // in2, in1, in0. Sums of float products depend on that order. o[] is that order.
    const ScreenVertex* o[3];
    TriangleConstants same;
    float wsumRecip = 0;  // the edge functions sum to the (positive) area everywhere
    float os[3] = {}, ot[3] = {}, oq[3] = {}, orw[3] = {}, ocw[3] = {}, oz[3] = {};
    // Colour gradient planes (RasterParams::colourGradients; raster.h colourGradientReference):
    // channels 0–3 primary RGBA, 4–6 secondary RGB.
    bool gradients = false;
    s64 refX = 0, refY = 0;
    int refC[7] = {};
    s64 gx[7] = {}, gy[7] = {};

    TriangleWalk(const RasterParams& p, const ScreenVertex& in0, const ScreenVertex& in1, const ScreenVertex& in2,
                 const ScreenVertex& prov, s64 area)
        : rp(p), v{&in0, &in1, &in2}, o{&in0, &in1, &in2} {
        swapped = area < 0;
        if (swapped) {
            // Either winding rasterises the same pixels; work with the clockwise (on screen) order.
            std::swap(v[1], v[2]);
            std::swap(o[0], o[2]);
            area = -area;
        }
        for (int i = 0; i < 3; ++i) {
            const ScreenVertex& a = *v[(i + 1) % 3];
            const ScreenVertex& b = *v[(i + 2) % 3];
            const s64 dx = s64(b.x) - a.x, dy = s64(b.y) - a.y;
            A[i] = -dy;
            B[i] = dx;
            C[i] = dy * a.x - dx * a.y;
            thr[i] = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : 1;
        }
        // Constant attributes are detected once so the common cases cost nothing per pixel.
        same = triangleConstants(rp, in0, in1, in2, prov);
        wsumRecip = 1.0f / float(area);
        if (rp.colourGradients && (!same.color || !same.secondary)) setupGradients(area);
        // Texture coordinates as the reference computes them (texAt below): q_i = 1/w_i.
        for (int i = 0; i < 3; ++i) {
            os[i] = o[i]->s, ot[i] = o[i]->t, oq[i] = o[i]->q, ocw[i] = o[i]->w, oz[i] = float(o[i]->z);
            orw[i] = rp.through ? 1.0f : 1.0f / o[i]->w;
        }
    }

    // The gradient planes of channels 0–3 (primary RGBA) and 4–6 (secondary RGB).
    void setupGradients(s64 area) {
        gradients = true;
        const GradientPlanes g = colourGradientPlanes(o, A, B, swapped, area);
        refX = o[g.ref]->x, refY = o[g.ref]->y;
        std::copy(g.refC, g.refC + 7, refC);
        std::copy(g.gx, g.gx + 7, gx);
        std::copy(g.gy, g.gy + 7, gy);
    }

    s64 edgeAt(int i, s64 px, s64 py) const {
        const int sample = triangleSampleOffset(rp);
        return A[i] * (16 * px + sample) + B[i] * (16 * py + sample) + C[i];
    }
    // The edge-function weights of o[] from those of v[].
    void orderWeights(s64 e0, s64 e1, s64 e2, float& w0, float& w1, float& w2) const {
        if (!swapped) w0 = float(e0), w1 = float(e1), w2 = float(e2);
        else w0 = float(e1), w1 = float(e2), w2 = float(e0);
    }
    void weightsAt(s64 px, s64 py, float& w0, float& w1, float& w2) const {
        orderWeights(edgeAt(0, px, py), edgeAt(1, px, py), edgeAt(2, px, py), w0, w1, w2);
    }

    // Texture coordinates as the reference computes them, in single precision (PPSSPP
    // Rasterizer.cpp GetTextureCoordinates[Proj]): weights wq_i = E_i·q_i,
    // s = (Σ wq_i·s_i)·(1 / Σ wq_i·Q_i) with the sums taken in attribute order (Q = 1 without
    // texture projection, where the two forms agree). Through mode is screen-linear:
    // s = (Σ E_i·s_i)·(1/area). Level 0 scaling (through mode) is by a power of two and commutes.
    void texAt(float w0, float w1, float w2, float& s, float& t) const {
        if (rp.through) {
            s = interpolateF(os[0], os[1], os[2], w0, w1, w2, wsumRecip);
            t = interpolateF(ot[0], ot[1], ot[2], w0, w1, w2, wsumRecip);
            return;
        }
        const float a = w0 * orw[0], b = w1 * orw[1], c = w2 * orw[2];
        const float qRecip = 1.0f / interpolateF(oq[0], oq[1], oq[2], a, b, c, 1.0f);
        s = interpolateF(os[0], os[1], os[2], a, b, c, qRecip);
        t = interpolateF(ot[0], ot[1], ot[2], a, b, c, qRecip);
    }

    // Colours as the reference interpolates them: float sums rounded to nearest.
    void shadeColoursF(Fragment& f, const ScreenVertex& cs, float fw0, float fw1, float fw2) const {
        if (same.color) {
            std::memcpy(f.color, cs.color, 4);
        } else {
            for (int c = 0; c < 4; ++c)
                f.color[c] = interpolateColor(o[0]->color[c], o[1]->color[c], o[2]->color[c], fw0, fw1, fw2, wsumRecip);
        }
        if (same.secondary) {
            std::memcpy(f.secondary, cs.secondary, 3);
        } else {
            for (int c = 0; c < 3; ++c)
                f.secondary[c] =
                    interpolateColor(o[0]->secondary[c], o[1]->secondary[c], o[2]->secondary[c], fw0, fw1, fw2, wsumRecip);
        }
    }

    // Depth, colours and fog of the fragment with attribute-order weights w.
    void shade(Fragment& f, float fw0, float fw1, float fw2) const {
        const ScreenVertex& cs = *same.source;  // colour source when constant
        if (same.z) {
            f.z = u16(v[0]->z);
        } else {
            // Depth as the reference interpolates it (PPSSPP Rasterizer.cpp DrawTriangleSlice):
            // (E0·z0 + E1·z1 + E2·z2)·(1/area) in single precision, attribute order, converted
            // with Vec4<float>::Cast<int>, which on x86-64 is cvtps2dq: round to nearest, ties
            // to even (not truncation). Coplanar geometry drawn twice (decals) z-fights exactly
            // where these roundings decide; an integer depth plane and float with truncation
            // both lose against the references (docs/accuracy.md).
            const float zf = interpolateF(oz[0], oz[1], oz[2], fw0, fw1, fw2, wsumRecip);
            const float zr = roundHalfEven(zf);
            f.z = u16(!(zr > 0.0f) ? 0 : (zr >= 65535.0f ? 65535 : int(zr)));
        }
        if (gradients) {
            const int sample = triangleSampleOffset(rp);
            const s64 dx = 16 * s64(f.x) + sample - refX, dy = 16 * s64(f.y) + sample - refY;
            for (int c = 0; c < 4; ++c)
                f.color[c] = same.color ? cs.color[c] : colourFromGradients(refC[c], gx[c], gy[c], dx, dy);
            for (int c = 0; c < 3; ++c)
                f.secondary[c] = same.secondary ? cs.secondary[c]
                                                : colourFromGradients(refC[4 + c], gx[4 + c], gy[4 + c], dx, dy);
        } else {
            shadeColoursF(f, cs, fw0, fw1, fw2);
        }
        f.fog = same.fog ? u8(255) : fogToByte(interpolateF(o[0]->fog, o[1]->fog, o[2]->fog, fw0, fw1, fw2, wsumRecip));
    }

    // The level of detail and the slope-mode W of the 2×2 quad whose top-left pixel is (qx, qy),
    // from its top-left, top-right and bottom-left pixels (also outside the triangle: the edge
    // functions are planes).
    void quadValues(int qx, int qy, float& lod, float& quadW) const {
        float a0, a1, a2;
        weightsAt(qx, qy, a0, a1, a2);
        if (rp.needLod) {
            float b0, b1, b2, c0, c1, c2, s00, t00, s10, t10, s01, t01;
            weightsAt(qx + 1, qy, b0, b1, b2);
            weightsAt(qx, qy + 1, c0, c1, c2);
            texAt(a0, a1, a2, s00, t00);
            texAt(b0, b1, b2, s10, t10);
            texAt(c0, c1, c2, s01, t01);
            lod = lodFromStepsF(rp, s10 - s00, t01 - t00);
        }
        // Slope mode: clip W screen-linear at the quad's top-left pixel (the reference's "one
        // value for the slope").
        if (rp.needW) quadW = interpolateF(ocw[0], ocw[1], ocw[2], a0, a1, a2, wsumRecip);
    }
};

}  // namespace

void rasterTriangle(const RasterParams& rp, const ScreenVertex& in0, const ScreenVertex& in1, const ScreenVertex& in2,
                    const ScreenVertex& prov, const Band& band, FragmentSink& sink) {
    const s64 area = s64(in1.x - in0.x) * (in2.y - in0.y) - s64(in1.y - in0.y) * (in2.x - in0.x);
    if (area == 0) {
        if (rp.zeroAreaTriangles) rasterZeroAreaTriangle(rp, in0, in1, in2, prov, band, sink);
        return;
    }
    // Pixel box whose centres lie within the vertices' extent, clipped.
    const int minX = std::min({in0.x, in1.x, in2.x}), maxX = std::max({in0.x, in1.x, in2.x});
    const int minY = std::min({in0.y, in1.y, in2.y}), maxY = std::max({in0.y, in1.y, in2.y});
    const int sample = triangleSampleOffset(rp);
    const int px1 = std::max<int>(int(ceilDiv(minX - sample, 16)), rp.clipX1);
    const int px2 = std::min<int>(int(floorDiv(maxX - sample, 16)), rp.clipX2);
    int py1, py2;
    sampleRowsOfTriangle(sample, minY, maxY, py1, py2);
    clipRows(rp, py1, py2);
    if (px1 > px2 || !band.overlaps(py1, py2)) return;

    const TriangleWalk tw(rp, in0, in1, in2, prov, area);
    // 2×2 quads, as the reference walks them, start at the top-left pixel of the triangle's box
    // (BinManager::Range: the vertices' pixel floor, scissor applied): the level of detail and the
    // slope-mode W come from each quad's pixels.
    const int quadX0 = std::max<int>(int(floorDiv(minX, 16)), rp.clipX1);
    const int quadY0 = std::max<int>(int(floorDiv(minY, 16)), rp.clipY1);

    for (int y = py1; y <= py2; ++y) {
        if (!band.owns(y)) {
            // Jump to the next block of rows (blocks are 16 rows).
            y |= (1 << Band::kShift) - 1;
            continue;
        }
        const s64 cy = 16 * s64(y) + sample;
        s64 K[3], step[3];
        s64 xl = px1, xr = px2;
        bool empty = false;
        for (int i = 0; i < 3; ++i) {
            K[i] = tw.A[i] * sample + tw.B[i] * cy + tw.C[i];
            step[i] = 16 * tw.A[i];
            // Solve step·x + K ≥ thr for x.
            if (step[i] > 0) xl = std::max(xl, ceilDiv(tw.thr[i] - K[i], step[i]));
            else if (step[i] < 0) xr = std::min(xr, floorDiv(K[i] - tw.thr[i], -step[i]));
            else if (K[i] < tw.thr[i]) empty = true;
        }
        if (empty || xl > xr) continue;

        const int qy = quadY0 + ((y - quadY0) & ~1);
        int quadX = INT_MIN;
        float lod = 0.0f, quadW = 1.0f;
        for (s64 x = xl; x <= xr; ++x) {
            Fragment& f = sink.next();
            f.x = int(x);
            f.y = y;
            float fw0, fw1, fw2;
            tw.orderWeights(step[0] * x + K[0], step[1] * x + K[1], step[2] * x + K[2], fw0, fw1, fw2);
            tw.shade(f, fw0, fw1, fw2);
            if (rp.textured || rp.needW) {
                const int qx = quadX0 + ((int(x) - quadX0) & ~1);
                if ((rp.needLod || rp.needW) && qx != quadX) {
                    quadX = qx;
                    tw.quadValues(qx, qy, lod, quadW);
                }
            }
            if (rp.textured) {
                float s, t;
                tw.texAt(fw0, fw1, fw2, s, t);
                f.s = finiteOr0(s);
                f.t = finiteOr0(t);
                f.lod = rp.needLod ? lod : 0.0f;
            } else {
                f.s = f.t = 0.0f;
                f.lod = 0.0f;
            }
            f.w = rp.needW ? finiteOr0(quadW) : 1.0f;
        }
    }
}

TriangleConstants triangleConstants(const RasterParams& rp, const ScreenVertex& in0, const ScreenVertex& in1,
                                    const ScreenVertex& in2, const ScreenVertex& prov) {
    TriangleConstants k;
    k.z = in0.z == in1.z && in1.z == in2.z;
    k.color = !rp.gouraud || (std::memcmp(in0.color, in1.color, 4) == 0 && std::memcmp(in1.color, in2.color, 4) == 0);
    k.secondary = !rp.gouraud || (std::memcmp(in0.secondary, in1.secondary, 3) == 0 &&
                                  std::memcmp(in1.secondary, in2.secondary, 3) == 0);
    k.fog = !rp.fog || (in0.fog >= 1.0f && in1.fog >= 1.0f && in2.fog >= 1.0f);
    k.source = rp.gouraud ? &in0 : &prov;
    return k;
}

bool rectangleSetup(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, RectSetup& out) {
    const int xl = std::min(v0.x, v1.x), xr = std::max(v0.x, v1.x);
    const int yt = std::min(v0.y, v1.y), yb = std::max(v0.y, v1.y);
    if (xl == xr || yt == yb) return false;  // zero width or height draws nothing (ge-rules.md §8.11)
    // The reference renderer (PPSSPP's software GE, Rasterizer.cpp DrawRectangle) walks the box in
    // 2×2 pixel quads starting at the first covered pixel: a left/top edge up to the pixel centre
    // includes the pixel (centres 16·p + 8 ≥ edge, ge-rules.md §8.1). Towards the far edge, the first pixel of
    // each pair needs its centre strictly inside (16·p + 8 < edge) but the second pixel of a pair
    // is also drawn when its centre lies exactly on the edge — so an edge on a pixel centre covers
    // that pixel only when it falls on the odd pixel of a pair counted from the first one.
    const int px1 = std::max<int>(int(ceilDiv(xl - 8, 16)), rp.clipX1);
    const int py1 = std::max<int>(int(ceilDiv(yt - 8, 16)), rp.clipY1);
    // A RECTANGLES draw leaves the pixel whose centre is on its far edge out, odd or not, as a PSP
    // does in either mode (pspautotests gpu/filtering/precision*2d and *3d: a 2x2 sprite from
    // −8/16 to 1.5 draws pixel 0 only; docs/conformance.md "Sprites"). Strip and fan quads that
    // the reference draws as rectangles (assembly.h; triangles on the GE) keep its walk.
    auto lastCovered = [&rp](int first, int far, int clip) {
        int last = int(ceilDiv(far - 8, 16)) - 1;  // centre strictly before the far edge
        if (!rp.sprite && ((far - 8) & 15) == 0 && ((last + 1 - first) & 1) == 1) ++last;  // odd pixel on the edge
        return std::min(last, clip);
    };
    const int px2 = lastCovered(px1, xr, rp.clipX2);
    const int py2 = lastCovered(py1, yb, rp.clipY2);
    if (px1 > px2 || py1 > py2) return false;
    // Texture coordinates in single precision as the reference steps them (ge-rules.md §8.2 orientation): the
    // change per two pixels, 2·Δ / (size in pixels), from the box's top-left corner moved to the
    // first pixel centre; then added once per pair of columns along a row and once per pair of rows
    // down the box, the odd pixel of a pair adding half a step. The level of detail comes from those
    // half steps, per quad (ge-rules.md §6.6).
    float rowS = 0, rowT = 0, stxS = 0, stxT = 0, styS = 0, styT = 0;
    if (rp.textured) {
        const float diffX = float(xr - xl) / 16.0f, diffY = float(yb - yt) / 16.0f;
        const float diffS = v1.s - v0.s, diffT = v1.t - v0.t;
        const bool left = v0.x < v1.x, above = v0.y < v1.y;
        if (left && above) {  // top-left gets (v0.s, v0.t); +X: S v0→v1; +Y: T v0→v1
            rowS = v0.s, rowT = v0.t;
            stxS = 2.0f * diffS / diffX, styT = 2.0f * diffT / diffY;
        } else if (left) {  // v0 left and below: (v1.s, v0.t); +X: T v0→v1; +Y: S v1→v0
            rowS = v1.s, rowT = v0.t;
            stxT = 2.0f * diffT / diffX, styS = 2.0f * -diffS / diffY;
        } else if (above) {  // v0 right and above: (v0.s, v1.t); +X: T v1→v0; +Y: S v0→v1
            rowS = v0.s, rowT = v1.t;
            stxT = 2.0f * -diffT / diffX, styS = 2.0f * diffS / diffY;
        } else {  // v0 right and below: (v1.s, v1.t); +X: S v1→v0; +Y: T v1→v0
            rowS = v1.s, rowT = v1.t;
            stxS = 2.0f * -diffS / diffX, styT = 2.0f * -diffT / diffY;
        }
        const float offX = float(16 * px1 + 8 - xl), offY = float(16 * py1 + 8 - yt);
        rowS = rowS + (stxS / 32.0f) * offX;
        rowT = rowT + (stxT / 32.0f) * offX;
        rowS = rowS + (styS / 32.0f) * offY;
        rowT = rowT + (styT / 32.0f) * offY;
    }
    out = RectSetup{px1, py1, px2, py2, rowS, rowT, stxS, stxT, styS, styT};
    return true;
}

void rasterRectangle(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const Band& band,
                     FragmentSink& sink) {
    RectSetup rs;
    if (!rectangleSetup(rp, v0, v1, rs) || !band.overlaps(rs.py1, rs.py2)) return;
    const int px1 = rs.px1, px2 = rs.px2, py1 = rs.py1, py2 = rs.py2;
    float rowS = rs.rowS, rowT = rs.rowT;
    const float stxS = rs.stxS, stxT = rs.stxT, styS = rs.styS, styT = rs.styT;
    const float hxS = 0.5f * stxS, hxT = 0.5f * stxT, hyS = 0.5f * styS, hyT = 0.5f * styT;

    // Colour, Z and fog of the second vertex for every pixel (manual §4.4, §8).
    const u16 z = u16(v1.z);
    const u8 fog = rp.fog ? fogToByte(v1.fog) : 255;
    const float w = rp.needW ? v1.w : 1.0f;
    // Rows go in pairs from py1; every band replays the same float additions, so the result does
    // not depend on the band split.
    for (int y0 = py1; y0 <= py2; y0 += 2, rowS = rowS + styS, rowT = rowT + styT) {
        for (int dy = 0; dy < 2 && y0 + dy <= py2; ++dy) {
            const int y = y0 + dy;
            if (!band.owns(y)) continue;
            float s = rowS, t = rowT;
            for (int x0 = px1; x0 <= px2; x0 += 2, s = s + stxS, t = t + stxT) {
                float qs[4] = {s, s + hxS, s + hyS, s + (hxS + hyS)};
                float qt[4] = {t, t + hxT, t + hyT, t + (hxT + hyT)};
                float lod = 0.0f;
                if (rp.textured && rp.needLod) lod = lodFromSteps(rp, qs[1] - qs[0], qt[2] - qt[0]);
                for (int dx = 0; dx < 2 && x0 + dx <= px2; ++dx) {
                    Fragment& f = sink.next();
                    f.x = x0 + dx;
                    f.y = y;
                    f.z = z;
                    std::memcpy(f.color, v1.color, 4);
                    std::memcpy(f.secondary, v1.secondary, 3);
                    f.fog = fog;
                    if (rp.textured) {
                        f.s = finiteOr0(qs[2 * dy + dx]);
                        f.t = finiteOr0(qt[2 * dy + dx]);
                        f.lod = lod;
                    } else {
                        f.s = f.t = 0.0f;
                        f.lod = 0.0f;
                    }
                    f.w = w;
                }
            }
        }
    }
}

namespace {

// A line as a PSP draws it (RasterParams::lineCentres, AccuracyProfile::pspLineCentres): along the
// longer axis every pixel whose centre lies in [start, end) — (end, start] for a line running
// backwards —, the other coordinate taken at that centre (exactly, in sixteenths) and rounded
// down to its pixel. Each pixel's attributes are those at the centre's place t = num / len along
// the line: Gouraud colours c0 + ⌊(c1 − c0)·num / len⌋ (a flat line takes the end vertex's),
// depth, fog and clip W linear in t, texture coordinates linear in t in through mode and
// perspective-correct otherwise, the level of detail from the next centre's.
void rasterLineAtCentres(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const Band& band,
                         FragmentSink& sink) {
    const s64 dx = s64(v1.x) - v0.x, dy = s64(v1.y) - v0.y;
    const bool xMajor = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy);
    const s64 s0 = xMajor ? v0.x : v0.y, m0 = xMajor ? v0.y : v0.x;
    const s64 len = xMajor ? dx : dy, mlen = xMajor ? dy : dx;
    if (len == 0) return;  // zero-length lines draw nothing (ge-rules.md §8.11)
    const s64 dir = len > 0 ? 1 : -1, alen = len * dir;
    const float q0 = 1.0f / v0.w, q1 = 1.0f / v1.w;
    auto texAt = [&](double t, float& s, float& tt) {
        if (rp.through) {
            s = v0.s + (v1.s - v0.s) * float(t);
            tt = v0.t + (v1.t - v0.t) * float(t);
            return;
        }
        const float wq0 = float(1.0 - t) * q0, wq1 = float(t) * q1;
        const float qr = 1.0f / (v0.q * wq0 + v1.q * wq1);
        s = (v0.s * wq0 + v1.s * wq1) * qr;
        tt = (v0.t * wq0 + v1.t * wq1) * qr;
    };
    for (s64 p = dir > 0 ? ceilDiv(s0 - 8, 16) : floorDiv(s0 - 8, 16);; p += dir) {
        const s64 num = (16 * p + 8 - s0) * dir;  // 0 ≤ num < alen inside the line
        if (num >= alen) break;
        const s64 minor = floorDiv(m0 + floorDiv(mlen * num, alen), 16);
        const s64 px = xMajor ? p : minor, py = xMajor ? minor : p;
        if (px < rp.clipX1 || px > rp.clipX2 || py < rp.clipY1 || py > rp.clipY2 || !band.owns(int(py))) continue;
        const double t = double(num) / double(alen);
        Fragment& f = sink.next();
        f.x = int(px);
        f.y = int(py);
        f.z = u16(int(double(v0.z) + double(s64(v1.z) - v0.z) * t));
        if (rp.gouraud) {
            auto at = [&](int c0, int c1) { return u8(c0 + floorDiv(s64(c1 - c0) * num, alen)); };
            for (int c = 0; c < 4; ++c) f.color[c] = at(v0.color[c], v1.color[c]);
            for (int c = 0; c < 3; ++c) f.secondary[c] = at(v0.secondary[c], v1.secondary[c]);
        } else {
            std::memcpy(f.color, v1.color, 4);
            std::memcpy(f.secondary, v1.secondary, 3);
        }
        f.fog = rp.fog ? fogToByte(v0.fog + (v1.fog - v0.fog) * float(t)) : 255;
        f.s = f.t = 0.0f;
        f.lod = 0.0f;
        if (rp.textured) {
            float s, tt;
            texAt(t, s, tt);
            f.s = finiteOr0(s);
            f.t = finiteOr0(tt);
            if (rp.needLod) {
                float sn, tn;
                texAt(double(num + 16) / double(alen), sn, tn);
                f.lod = lodFromSteps(rp, double(sn) - f.s, double(tn) - f.t);
            }
        }
        f.w = rp.needW ? finiteOr0(v0.w + (v1.w - v0.w) * float(t)) : 1.0f;
    }
}

}  // namespace

void rasterLine(const RasterParams& rp, const ScreenVertex& v0, const ScreenVertex& v1, const Band& band,
                FragmentSink& sink) {
    if (rp.lineCentres) {
        rasterLineAtCentres(rp, v0, v1, band, sink);
        return;
    }
    // The reference renderer's line walk (PPSSPP GPU/Software DrawLine): max(|dx|, |dy|) / 16
    // steps of (dx, dy) / steps accumulated in double precision from the start vertex (one
    // subpixel back along an axis the line runs backwards on), each step drawing the pixel that
    // contains the truncated position; the end pixel is left out (ge-rules.md §8.11). A line shorter than one
    // pixel backwards is shortened by one subpixel so it does not run into the next pixel.
    // Positions outside the line's bounding box (rounded out to whole pixels) or the clip
    // rectangle draw nothing.
    s64 dx = s64(v1.x) - v0.x, dy = s64(v1.y) - v0.y;
    const s64 steps = std::max(dx < 0 ? -dx : dx, dy < 0 ? -dy : dy) / 16;
    if (steps == 0) return;  // zero-length lines draw nothing (ge-rules.md §8.11)
    if (dx < 0 && dx >= -16) ++dx;
    if (dy < 0 && dy >= -16) ++dy;
    const double xinc = double(dx) / double(steps), yinc = double(dy) / double(steps);
    const double zinc = double(s64(v1.z) - v0.z) / double(steps);
    const s64 bx1 = std::max<s64>(std::min(v0.x, v1.x) & ~s64(15), s64(rp.clipX1) * 16);
    const s64 by1 = std::max<s64>(std::min(v0.y, v1.y) & ~s64(15), s64(rp.clipY1) * 16);
    const s64 bx2 = std::min<s64>(std::max(v0.x, v1.x) | 15, s64(rp.clipX2) * 16 + 15);
    const s64 by2 = std::min<s64>(std::max(v0.y, v1.y) | 15, s64(rp.clipY2) * 16 + 15);
    // Gouraud lines interpolate in whole steps, flat lines take the end vertex's colours (ge-rules.md §8.1).
    // (The reference renderer's line code has the flat/Gouraud choice inverted — it interpolates
    // flat lines and gives Gouraud lines with different end colours the end colour; no frametest
    // tells the two apart, so the manual's rule stands.)
    const bool interpolateColor = rp.gouraud;
    const float q0 = 1.0f / v0.w, q1 = 1.0f / v1.w;
    // Texture coordinates in single precision, as the reference: perspective-correct with weight
    // p = a / steps on v0.
    // Through mode: linear in whole steps; a and b are the step weights of v0 and v1.
    auto texAt = [&](s64 a, s64 b, float& s, float& t) {
        if (rp.through) {
            s = (v0.s * float(a) + v1.s * float(b)) / float(steps);
            t = (v0.t * float(a) + v1.t * float(b)) / float(steps);
            return;
        }
        const float p = float(a) / float(steps);
        const float wq0 = p * q0, wq1 = (1.0f - p) * q1;
        const float qr = 1.0f / (v0.q * wq0 + v1.q * wq1);
        s = (v0.s * wq0 + v1.s * wq1) * qr;
        t = (v0.t * wq0 + v1.t * wq1) * qr;
    };
    double x = v0.x > v1.x ? double(v0.x) - 1 : double(v0.x);
    double y = v0.y > v1.y ? double(v0.y) - 1 : double(v0.y);
    double z = double(v0.z);
    for (s64 i = 0; i < steps; ++i, x += xinc, y += yinc, z += zinc) {
        if (!(x >= double(bx1) && y >= double(by1) && x <= double(bx2) && y <= double(by2))) continue;
        const int px = int(x) / 16, py = int(y) / 16;
        if (!band.owns(py)) continue;
        const s64 a = steps - i, b = i;
        Fragment& f = sink.next();
        f.x = px;
        f.y = py;
        f.z = u16(int(z));
        if (interpolateColor) {
            for (int c = 0; c < 4; ++c) f.color[c] = u8((v0.color[c] * a + v1.color[c] * b) / steps);
            for (int c = 0; c < 3; ++c) f.secondary[c] = u8((v0.secondary[c] * a + v1.secondary[c] * b) / steps);
        } else {
            std::memcpy(f.color, v1.color, 4);
            std::memcpy(f.secondary, v1.secondary, 3);
        }
        f.fog = rp.fog ? fogToByte((v0.fog * float(a) + v1.fog * float(b)) / float(steps)) : 255;
        f.s = f.t = 0.0f;
        f.lod = 0.0f;
        if (rp.textured) {
            float s, t;
            texAt(a, b, s, t);
            f.s = finiteOr0(s);
            f.t = finiteOr0(t);
            if (rp.needLod) {
                float sn, tn;
                texAt(a - 1, b + 1, sn, tn);
                f.lod = lodFromSteps(rp, double(sn) - f.s, double(tn) - f.t);
            }
        }
        f.w = rp.needW ? finiteOr0((v0.w * float(a) + v1.w * float(b)) / float(steps)) : 1.0f;
    }
}

void rasterPoint(const RasterParams& rp, const ScreenVertex& v, const Band& band, FragmentSink& sink) {
    const s64 px = floorDiv(v.x, 16), py = floorDiv(v.y, 16);
    if (px < rp.clipX1 || px > rp.clipX2 || py < rp.clipY1 || py > rp.clipY2) return;
    if (!band.owns(int(py))) return;
    Fragment& f = sink.next();
    f.x = int(px);
    f.y = int(py);
    f.z = u16(v.z);
    std::memcpy(f.color, v.color, 4);
    std::memcpy(f.secondary, v.secondary, 3);
    f.fog = rp.fog ? fogToByte(v.fog) : 255;
    if (rp.textured) {
        f.s = finiteOr0(v.s / v.q);
        f.t = finiteOr0(v.t / v.q);
    } else {
        f.s = f.t = 0.0f;
    }
    f.lod = texLog2(0.0f);  // a point has no footprint: level 0, magnification filter
    f.w = v.w;
}

}  // namespace ge::geo
