// SPDX-License-Identifier: MIT
// Bezier and spline patch tessellation (manual §5, §13.1.1; docs/ge-rules.md §3.2).
//
// Control point (u, v) is vertex number v·Ucount + u (through the index buffer when IT ≠ 0), read
// with VertexReader (morphing applied, skinning not: the reference does not apply it to patches).
// Every output attribute is the same tensor-product combination of the control points:
//   S(u, v) = Σa Σb Nu_a(u) · Nv_b(v) · P(first_u + a, first_v + b)
// with Bernstein weights for Bezier (manual §5.1) and the cubic B-spline basis of the knot
// vector for splines (manual §5.2.1), evaluated in the reference's arithmetic, including its
// weights for a single patch open at both ends (see splineSpans).
//
// Layout of the output (follows PPSSPP, whose software renderer made the reference renders):
// - Bezier: each patch is tessellated on its own into (divU+1)·(divV+1) vertices (edge vertices
//   are duplicated between neighbouring patches), patches in control-point order (V outer).
// - Spline: one shared grid of ((Ucount−3)·divU + 1) · ((Vcount−3)·divV + 1) vertices.
// - Vertices are row-major (U fastest). For grid quad (i, j) with corners
//   q0 = (i, j), q1 = (i+1, j), q2 = (i, j+1), q3 = (i+1, j+1):
//   triangles (q0, q2, q1), (q1, q2, q3); lines q0–q2, q1–q3, q1–q2; points: every vertex once.
#include "geometry/spline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ge::geo {

namespace {

struct Basis1D {
    u32 first = 0;      // first control point index in this direction
    float w[4] = {};    // basis values
    float d[4] = {};    // derivatives with respect to the parameter
};

void bezierDerivs(float t, float d[4]) {
    const float s = 1.0f - t;
    d[0] = -3.0f * s * s;
    d[1] = 3.0f * s * s - 6.0f * t * s;
    d[2] = 6.0f * t * s - 3.0f * t * t;
    d[3] = 3.0f * t * t;
}

// One spline patch's share of the knot vector, in the form the reference evaluates the cubic
// basis (PPSSPP SplineCommon.cpp, Spline3DWeight: CalcKnots / CalcWeights): the three knots
// before the patch's span [U[p+3], U[p+4]] and the reciprocals of the knot differences the
// Cox–de Boor recursion divides by. The rounding of the weights depends on this form.
struct SplineSpan {
    float k0 = 0, k1 = 0, k2 = 0;        // U[p+1], U[p+2], U[p+3]
    float r30 = 0, r41 = 0, r52 = 0;     // 1/(U[p+4]−U[p+1]), 1/(U[p+5]−U[p+2]), 1/(U[p+6]−U[p+3])
    float r31 = 0, r42 = 0, r32 = 0;     // 1/(U[p+4]−U[p+2]), 1/(U[p+5]−U[p+3]), 1/(U[p+4]−U[p+3])
};

// Spans of the count − 3 patches of one direction. Every difference includes the patch's own
// span of length 1 (splineKnots), so none is zero.
std::vector<SplineSpan> splineSpans(int count, int knotType, bool openKnotQuirk) {
    std::vector<float> U;
    splineKnots(count, knotType, U);
    std::vector<SplineSpan> spans(size_t(std::max(count - 3, 0)));
    for (size_t p = 0; p < spans.size(); ++p) {
        SplineSpan& s = spans[p];
        s.k0 = U[p + 1], s.k1 = U[p + 2], s.k2 = U[p + 3];
        s.r30 = 1.0f / (U[p + 4] - U[p + 1]);
        s.r41 = 1.0f / (U[p + 5] - U[p + 2]);
        s.r52 = 1.0f / (U[p + 6] - U[p + 3]);
        s.r31 = 1.0f / (U[p + 4] - U[p + 2]);
        s.r42 = 1.0f / (U[p + 5] - U[p + 3]);
        s.r32 = 1.0f / (U[p + 4] - U[p + 3]);
    }
    // A single patch open at both ends, under AccuracyProfile::splineOpenKnotQuirk: the reference
    // sets 1/(U[5]−U[2]) for the open end (1/2, right when the start is closed) after the open
    // start's value (1, the true one), so its weights are not the Bernstein ones: at t = 1/2 they
    // are (1/8, 1/2, 1/4, 1/8) instead of (1/8, 3/8, 3/8, 1/8). Still a partition of unity with
    // exact ends, so a flat patch stays flat, but its tessellated vertices sit at other places:
    // GachiTora draws its button and speech-bubble text as such 4x4 splines, and only these
    // weights reproduce the reference's bilinear texel fractions there (docs/accuracy.md,
    // "Reference quirks"). Without the quirk the manual's knot vector (§5.2.1) gives the
    // Bernstein weights, as on a PSP.
    if (openKnotQuirk && count == 4 && (knotType & 3) == 3) spans[0].r41 = 0.5f;
    return spans;
}

// Cubic spline basis of patch `patch` at the global parameter t (patch ≤ t ≤ patch + 1), with
// the reference's arithmetic: the de Boor ratios f_ij = (t − U_i)·r_ij, products of the
// degree-1 and degree-2 terms, then the four weights and their derivatives.
Basis1D splineBasis(const SplineSpan& s, u32 patch, float t) {
    const float t0 = t - s.k0, t1 = t - s.k1, t2 = t - s.k2;
    const float f30 = t0 * s.r30, f41 = t1 * s.r41, f52 = t2 * s.r52;
    const float f31 = t1 * s.r31, f42 = t2 * s.r42, f32 = t2 * s.r32;
    const float a = (1.0f - f30) * (1.0f - f31);
    const float b = f31 * f41;
    const float c = (1.0f - f41) * (1.0f - f42);
    const float d = f42 * f52;
    Basis1D r;
    r.first = patch;  // control points patch … patch + 3
    r.w[0] = a * (1.0f - f32);
    r.w[1] = 1.0f - a - b + ((a + b + c - 1.0f) * f32);
    r.w[2] = b + ((1.0f - b - c - d) * f32);
    r.w[3] = d * f32;
    const float i1 = (1.0f - f31) * (1.0f - f32);
    const float i2 = f31 * (1.0f - f32) + (1.0f - f42) * f32;
    const float i3 = f42 * f32;
    const float g30 = i1 * s.r30, g41 = i2 * s.r41, g52 = i3 * s.r52;
    r.d[0] = 3.0f * (0.0f - g30);
    r.d[1] = 3.0f * (g30 - g41);
    r.d[2] = 3.0f * (g41 - g52);
    r.d[3] = 3.0f * (g52 - 0.0f);
    return r;
}

Basis1D bezierBasis(u32 patch, float t) {
    Basis1D b;
    b.first = 3 * patch;
    bezierWeights(t, b.w);
    bezierDerivs(t, b.d);
    return b;
}

struct Surface {
    const std::vector<DecodedVertex>* cps = nullptr;
    u32 ucount = 0;
    bool hasUV = false, hasColor = false, hasNormal = false, hasWeights = false;
    bool genNormals = false, reverseFace = false;
    u32 weightCount = 0;
    bool spline = false;
    bool colourRoundUp = false;  // AccuracyProfile::pspPatchColourRoundUp
    std::vector<SplineSpan> spansU, spansV;

    // t: local parameter (Bezier); g: global parameter patch + t (spline).
    Basis1D basisU(u32 patch, float t, float g) const { return spline ? splineBasis(spansU[patch], patch, g) : bezierBasis(patch, t); }
    Basis1D basisV(u32 patch, float t, float g) const { return spline ? splineBasis(spansV[patch], patch, g) : bezierBasis(patch, t); }
    const DecodedVertex& cp(const Basis1D& bu, const Basis1D& bv, int a, int b) const {
        return (*cps)[size_t(bv.first + u32(b)) * ucount + bu.first + u32(a)];
    }

    void derivatives(const Basis1D& bu, const Basis1D& bv, float du[3], float dv[3]) const {
        for (int c = 0; c < 3; ++c) du[c] = dv[c] = 0.0f;
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a) {
                const DecodedVertex& p = cp(bu, bv, a, b);
                const float fu = bu.d[a] * bv.w[b], fv = bu.w[a] * bv.d[b];
                for (int c = 0; c < 3; ++c) {
                    du[c] += fu * p.pos[c];
                    dv[c] += fv * p.pos[c];
                }
            }
    }

    // Tensor-product sums, separably as the reference tessellates (PPSSPP SplineCommon.cpp,
    // Tessellator::SampleU then SampleV): each row of four control points (fixed v) is folded
    // along u (p0·w0 + p1·w1 + p2·w2 + p3·w3, in that order, single precision), then the four
    // row sums are weighted along v the same way. The rounding depends on this order; it moves
    // tessellated vertices by a few ulps, which decides integer Z at vertices and so z-fighting
    // between coplanar patches: Coded Arms draws its floor grate over its lava with GEQUAL, and
    // the reference shows the lava in two streaks around the one grate vertex whose screen Z this
    // order rounds to 2931.998 instead of 2932 (together with depth interpolation rounded to
    // nearest as in raster.cpp; docs/accuracy.md).
    // The u folds depend only on the column's basis and the control row, so they are made once
    // per output column and patch row (foldRows) and shared by every output vertex of that
    // column in the patch row; the sums are the same operations in the same order.
    //
    // The attributes summed, per control point, in one flat array: position (3), texture
    // coordinates (2), normal (3), weights (weightCount), colour (4), as the format has them.
    int nattr = 0;
    std::vector<float> cpAttr;
    void packAttributes() {
        nattr = 3 + (hasUV ? 2 : 0) + (hasNormal ? 3 : 0) + (hasWeights ? int(weightCount) : 0) + (hasColor ? 4 : 0);
        cpAttr.resize(cps->size() * size_t(nattr));
        float* o = cpAttr.data();
        for (const DecodedVertex& p : *cps) {
            o = std::copy(p.pos, p.pos + 3, o);
            if (hasUV) o = std::copy(p.uv, p.uv + 2, o);
            if (hasNormal) o = std::copy(p.nrm, p.nrm + 3, o);
            if (hasWeights) o = std::copy(p.weights, p.weights + weightCount, o);
            if (hasColor)
                for (int c = 0; c < 4; ++c) *o++ = float(p.color[c]);
        }
    }
    // The u folds of control rows row0 … row0 + 3 with the column basis bu: rows[b·nattr + k].
    void foldRows(const Basis1D& bu, u32 row0, float* rows) const {
        const size_t stride = size_t(nattr);
        for (u32 b = 0; b < 4; ++b) {
            const float* p = &cpAttr[(size_t(row0 + b) * ucount + bu.first) * stride];
            float* r = rows + b * stride;
            for (size_t k = 0; k < stride; ++k) {
                float acc = p[k] * bu.w[0];
                for (size_t a = 1; a < 4; ++a) acc = acc + p[a * stride + k] * bu.w[a];
                r[k] = acc;
            }
        }
    }

    // Evaluates one output vertex at local parameters (tu, tv) of patch (pu, pv), with the basis
    // values the caller computed once per column (bu) and per row (bv): basisU/basisV at the
    // local parameter (Bezier) or at the global one (splines, as the reference computes them).
    // `rows`: foldRows of the vertex's column for the control rows bv.first … bv.first + 3.
    // The vertex is written in place (into the output vector) and each sum straight into its
    // field: staging the sums in an array and copying them out read two 4-byte stores back as one
    // 8-byte load, which misses store forwarding (a quarter of this function's time in Pursuit
    // Force's profile), as did returning the vertex by value.
    void eval(u32 pu, float tu, const Basis1D& bu, u32 pv, float tv, const Basis1D& bv, const float* rows,
              DecodedVertex& out) const {
        const size_t stride = size_t(nattr);
        size_t k = 0;
        auto foldInto = [&](float* dst, size_t n) {
            for (size_t c = 0; c < n; ++c, ++k) {
                float acc = rows[k] * bv.w[0];
                for (size_t b = 1; b < 4; ++b) acc = acc + rows[b * stride + k] * bv.w[b];
                dst[c] = acc;
            }
        };
        foldInto(out.pos, 3);
        if (hasUV) foldInto(out.uv, 2);
        if (hasNormal) foldInto(out.nrm, 3);
        if (hasWeights) foldInto(out.weights, weightCount);
        if (hasColor) {
            float col[4];
            foldInto(col, 4);
            for (int c = 0; c < 4; ++c) {
                // To nearest as PPSSPP's ToRGBA, or up as the PSP (AccuracyProfile::
                // pspPatchColourRoundUp); a sum within 1/1024 above a whole number is that number
                // (the float evaluation's own error, e.g. at a corner where one weight is 1).
                const float v = colourRoundUp ? std::ceil(col[c] - 1.0f / 1024) : std::floor(col[c] + 0.5f);
                out.color[c] = !(v > 0.0f) ? 0 : v >= 255.0f ? 255 : u8(v);
            }
        } else {
            // No vertex colour: every control point carries the material colour (MAC/MAA).
            std::copy((*cps)[0].color, (*cps)[0].color + 4, out.color);
        }
        if (!hasUV) {
            // Generated texture coordinates: S = patch_u + i/divU, T = patch_v + j/divV (ge-rules.md §3.2, manual §13.1.1).
            out.uv[0] = float(pu) + tu;
            out.uv[1] = float(pv) + tv;
        }
        if (genNormals) {
            float du[3], dv[3];
            derivatives(bu, bv, du, dv);
            float n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
            float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            if (!(len2 > 1e-30f)) {
                // Degenerate derivative (collapsed edge, e.g. a pole): take the normal a little way
                // inside the patch, which is the limit the surface approaches.
                const float nu = tu < 0.5f ? tu + 1.0f / 64 : tu - 1.0f / 64;
                const float nv = tv < 0.5f ? tv + 1.0f / 64 : tv - 1.0f / 64;
                derivatives(basisU(pu, nu, float(pu) + nu), basisV(pv, nv, float(pv) + nv), du, dv);
                n[0] = du[1] * dv[2] - du[2] * dv[1];
                n[1] = du[2] * dv[0] - du[0] * dv[2];
                n[2] = du[0] * dv[1] - du[1] * dv[0];
                len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            }
            if (len2 > 1e-30f) {
                // PFACE = 1 reverses the generated normals (ge-rules.md §3.2).
                const float inv = (reverseFace ? -1.0f : 1.0f) / std::sqrt(len2);
                for (int c = 0; c < 3; ++c) out.nrm[c] = n[c] * inv;
            }
        }
    }
};

void appendGridIndices(u32 base, u32 nu, u32 nv, u32 patchPrim, std::vector<u32>& idx) {
    // nu × nv quads over a (nu+1) × (nv+1) vertex grid starting at `base`, six indices each,
    // written in place (an insert per quad was 3.6 % of Pursuit Force's profile).
    const size_t at = idx.size();
    idx.resize(at + size_t(nu) * nv * 6);
    u32* o = idx.data() + at;
    const bool lines = patchPrim == 1;
    for (u32 j = 0; j < nv; ++j)
        for (u32 i = 0; i < nu; ++i, o += 6) {
            const u32 q0 = base + j * (nu + 1) + i, q1 = q0 + 1, q2 = q0 + nu + 1, q3 = q2 + 1;
            o[0] = q0, o[1] = q2, o[2] = q1;
            if (lines) o[3] = q3, o[4] = q1, o[5] = q2;
            else o[3] = q1, o[4] = q2, o[5] = q3;
        }
}

bool fail(std::string* err, const char* msg, u32 a = 0, u32 b = 0) {
    if (err) {
        char buf[160];
        std::snprintf(buf, sizeof buf, msg, a, b);
        *err = buf;
    }
    return false;
}

}  // namespace

void bezierWeights(float t, float w[4]) {
    // Bernstein basis (manual §5.1).
    const float s = 1.0f - t;
    w[0] = s * s * s;
    w[1] = 3.0f * t * s * s;
    w[2] = 3.0f * t * t * s;
    w[3] = t * t * t;
}

void splineKnots(int n, int knotType, std::vector<float>& knots) {
    // Manual §5.2.1 with m = n − 1: {−3, −2, −1, 0, …, m−2, m−1, m, m+1}; an open start replaces
    // the first three knots by 0, an open end the last three by m−2 (= n − 3).
    knots.assign(size_t(std::max(n, 0) + 4), 0.0f);
    for (int i = 0; i < n + 4; ++i) knots[size_t(i)] = float(i - 3);
    if (knotType & 1)
        for (int i = 0; i < 3; ++i) knots[size_t(i)] = 0.0f;
    if (knotType & 2)
        for (int i = n + 1; i < n + 4; ++i) knots[size_t(i)] = float(n - 3);
}

bool tessellatePatch(const Memory& mem, const GeState& st, const PatchPacket& p, const AccuracyProfile& acc,
                     TessOutput& out, std::string* err, const PatchSkip& skip) {
    out.verts.clear();
    out.indices.clear();
    out.prim = p.patchPrim == 0 ? GE_PRIM_TRIANGLES : p.patchPrim == 1 ? GE_PRIM_LINES : GE_PRIM_POINTS;

    const u32 ucount = p.ucount, vcount = p.vcount;
    // Fewer than 4 control points in either direction draws nothing (ge-rules.md §3.2, observed: PPSSPP).
    if (ucount < 4 || vcount < 4) return true;
    const u32 divU = std::max<u32>(p.divU, 1), divV = std::max<u32>(p.divV, 1);
    const u32 patchesU = p.spline ? ucount - 3 : (ucount - 1) / 3;
    const u32 patchesV = p.spline ? vcount - 3 : (vcount - 1) / 3;
    // Guard against absurd division counts (255·252 per direction would be 4·10^9 vertices).
    const u64 total = patchOutputVertices(p);
    if (total > kMaxPatchOutputVertices)
        return fail(err, "patch too large: %u x %u divisions", divU, divV);

    // Control points.
    VertexReader reader(mem, st, p.vtype);
    const u32 n = ucount * vcount;
    std::vector<u32> indices;
    if (!reader.readIndices(p.indexAddr, n, indices))
        return fail(err, "patch index buffer 0x%08x (%u indices) is not readable", p.indexAddr, n);
    std::vector<DecodedVertex> cps(n);
    for (u32 i = 0; i < n; ++i)
        if (!reader.read(p.vertexAddr, indices[i], cps[i]))
            return fail(err, "patch control point %u (vertex %u) is not readable", i, indices[i]);
    if (skip && skip(cps)) return true;

    Surface s;
    s.cps = &cps;
    s.ucount = ucount;
    s.spline = p.spline;
    s.hasUV = reader.hasUV();
    s.hasColor = reader.hasColor();
    s.hasNormal = reader.hasNormal();
    s.hasWeights = reader.hasWeights();
    s.weightCount = std::min(reader.weightCount(), 8u);  // DecodedVertex::weights
    s.reverseFace = p.reverseFace;
    s.colourRoundUp = acc.pspPatchColourRoundUp;
    // Normals are generated when the vertex has none and something reads them: lighting (ge-rules.md §3.2),
    // shade mapping, or projection mapping from the normal (TMAP source 2/3).
    s.genNormals = !s.hasNormal && (st.LTE_on() || st.TMAP_mode() == 2 || (st.TMAP_mode() == 1 && st.TMAP_proj() >= 2));
    if (p.spline) {
        s.spansU = splineSpans(int(ucount), int(p.uknot & 3), acc.splineOpenKnotQuirk);
        s.spansV = splineSpans(int(vcount), int(p.vknot & 3), acc.splineOpenKnotQuirk);
    }
    s.packAttributes();

    out.verts.reserve(size_t(total));
    const float invU = 1.0f / float(divU), invV = 1.0f / float(divV);
    // Local parameter of step i in a patch of `div` steps; exact 0 and 1 at the ends.
    auto local = [](u32 i, u32 div, float inv) { return i == div ? 1.0f : float(i) * inv; };

    if (p.spline) {
        // As the reference: the weights at the global parameter (step index)·(1/div), the
        // generated texture coordinates patch + (step in patch)·(1/div).
        const u32 nu = patchesU * divU, nv = patchesV * divV;
        // The u basis of every column, computed once for all rows.
        std::vector<Basis1D> bus(nu + 1);
        for (u32 i = 0; i <= nu; ++i) {
            const u32 pu = std::min(i / divU, patchesU - 1);
            bus[i] = s.basisU(pu, float(i - pu * divU) * invU, float(i) * invU);
        }
        std::vector<float> folds((nu + 1) * 4 * size_t(s.nattr));
        u32 foldedRow0 = ~0u;
        for (u32 j = 0; j <= nv; ++j) {
            const u32 pv = std::min(j / divV, patchesV - 1);
            const float tv = float(j - pv * divV) * invV, gv = float(j) * invV;
            const Basis1D bv = s.basisV(pv, tv, gv);
            if (bv.first != foldedRow0) {
                foldedRow0 = bv.first;
                for (u32 i = 0; i <= nu; ++i) s.foldRows(bus[i], bv.first, &folds[i * 4 * size_t(s.nattr)]);
            }
            for (u32 i = 0; i <= nu; ++i) {
                const u32 pu = std::min(i / divU, patchesU - 1);
                const float tu = float(i - pu * divU) * invU;
                s.eval(pu, tu, bus[i], pv, tv, bv, &folds[i * 4 * size_t(s.nattr)], out.verts.emplace_back());
            }
        }
        if (out.prim == GE_PRIM_POINTS) {
            for (u32 k = 0; k < out.verts.size(); ++k) out.indices.push_back(k);
        } else {
            appendGridIndices(0, nu, nv, p.patchPrim, out.indices);
        }
        return true;
    }

    std::vector<Basis1D> bus(divU + 1);
    std::vector<float> folds((divU + 1) * 4 * size_t(s.nattr));
    for (u32 pv = 0; pv < patchesV; ++pv)
        for (u32 pu = 0; pu < patchesU; ++pu) {
            const u32 base = u32(out.verts.size());
            for (u32 i = 0; i <= divU; ++i) {
                const float tu = local(i, divU, invU);
                bus[i] = s.basisU(pu, tu, tu);
                s.foldRows(bus[i], 3 * pv, &folds[i * 4 * size_t(s.nattr)]);  // bezierBasis: rows 3·pv …
            }
            for (u32 j = 0; j <= divV; ++j) {
                const float tv = local(j, divV, invV);
                const Basis1D bv = s.basisV(pv, tv, tv);
                for (u32 i = 0; i <= divU; ++i)
                    s.eval(pu, local(i, divU, invU), bus[i], pv, tv, bv, &folds[i * 4 * size_t(s.nattr)],
                           out.verts.emplace_back());
            }
            if (out.prim != GE_PRIM_POINTS) appendGridIndices(base, divU, divV, p.patchPrim, out.indices);
        }
    if (out.prim == GE_PRIM_POINTS)
        for (u32 k = 0; k < out.verts.size(); ++k) out.indices.push_back(k);
    return true;
}

}  // namespace ge::geo
