// SPDX-License-Identifier: MIT
// Vertex processing (see transform.h).
#include "geometry/transform.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "geometry/clip.h"
#include "geometry/texture_size.h"

namespace ge::geo {

namespace {

// One term of a matrix row as the GE forms it. The GE has no IEEE specials (docs/ge-rules.md §1.2): a
// zero or denormal factor gives a zero term whatever the other factor is, and an exponent field of
// 255 (IEEE inf/NaN) is an ordinary exponent, ±1.m·2^128. So a NaN coordinate times a zero matrix
// element contributes nothing: Beam 'em up draws its text as transform-mode rectangles whose second
// vertex has z = NaN under an orthographic matrix, and the reference (SWR, which multiplies with the
// GE's term rules) draws them.
inline float geTerm(float a, float b) {
    u32 ba, bb;
    std::memcpy(&ba, &a, 4);
    std::memcpy(&bb, &b, 4);
    const u32 ea = (ba >> 23) & 0xFF, eb = (bb >> 23) & 0xFF;
    if (ea == 0 || eb == 0) return 0.0f;
    if (ea != 255 && eb != 255) return a * b;
    auto value = [](u32 bits, u32 e) {
        if (e != 255) {
            float f;
            std::memcpy(&f, &bits, 4);
            return double(f);
        }
        const double m = 1.0 + double(bits & 0x7FFFFF) / 8388608.0;
        return (bits & 0x80000000u) ? -std::ldexp(m, 128) : std::ldexp(m, 128);
    };
    return float(value(ba, ea) * value(bb, eb));  // overflows to ±inf only for |other| ≥ ~1
}

// The common case, where no factor has exponent 255: geTerm is then the IEEE product, or zero
// where either factor is zero or denormal — a select, done four rows at a time. A matrix column
// (MatrixColumns) is four lanes and each lane does one row's operations in their order,
// out_r = (t(m0r, p0) + t(m1r, p1)) + (t(m2r, p2) + m3r), so every row is bit-identical to geTerm
// row by row (-ffp-contract=off keeps products and sums apart). GCC and Clang vector extensions:
// SSE on x86-64, NEON on AArch64. The scalar form, with the matrix checked for exponent 255 at
// every vertex, was a fifth of Pursuit Force's per-draw profile (three products per vertex,
// 90-200 instructions each).
using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));
constexpr std::int32_t kExpMask = 0x7F800000;

inline F4 load4(const float* c) {
    F4 v;
    std::memcpy(&v, c, 16);
    return v;
}
inline I4 load4i(const std::int32_t* c) {
    I4 v;
    std::memcpy(&v, c, 16);
    return v;
}

// The rows of M·(p, 1) (translation true) or M·d (false) with geTerm row by row: where M or p
// has an exponent-255 factor. Out of line, so the common case below stays a leaf.
template <bool Translation>
[[gnu::noinline]] F4 productSpecial(const MatrixColumns& m, const float p[3]) {
    F4 v;
    for (int r = 0; r < 4; ++r) {
        const float t01 = geTerm(m.col[0][r], p[0]) + geTerm(m.col[1][r], p[1]);
        const float t2 = geTerm(m.col[2][r], p[2]);
        v[r] = Translation ? t01 + (t2 + m.col[3][r]) : t01 + t2;
    }
    return v;
}

// The same rows, four lanes at a time in the common case: each term is the IEEE product where
// neither factor's exponent field is 0 (MatrixColumns::keep for the matrix element, keepP for the
// coordinate), else +0.
template <bool Translation>
inline F4 product(const MatrixColumns& m, const float p[3]) {
    const F4 P = {p[0], p[1], p[2], 0.0f};
    const I4 e = (I4)P & kExpMask;
    const I4 special = e == kExpMask;
    if (m.special || (special[0] | special[1] | special[2])) [[unlikely]]
        return productSpecial<Translation>(m, p);
    const I4 keepP = e != 0;
    const F4 t0 = (F4)((I4)(load4(m.col[0]) * __builtin_shufflevector(P, P, 0, 0, 0, 0)) & load4i(m.keep[0]) &
                       __builtin_shufflevector(keepP, keepP, 0, 0, 0, 0));
    const F4 t1 = (F4)((I4)(load4(m.col[1]) * __builtin_shufflevector(P, P, 1, 1, 1, 1)) & load4i(m.keep[1]) &
                       __builtin_shufflevector(keepP, keepP, 1, 1, 1, 1));
    const F4 t2 = (F4)((I4)(load4(m.col[2]) * __builtin_shufflevector(P, P, 2, 2, 2, 2)) & load4i(m.keep[2]) &
                       __builtin_shufflevector(keepP, keepP, 2, 2, 2, 2));
    return Translation ? (t0 + t1) + (t2 + load4(m.col[3])) : (t0 + t1) + t2;
}

inline void store3(F4 v, float out[3]) { out[0] = v[0], out[1] = v[1], out[2] = v[2]; }

// The column form of a 3×4 (rows 3) or 4×4 (rows 4) matrix.
void toColumns(const float* m, int rows, MatrixColumns& out) {
    // Made at every transform-state change (GachiTora: most draws), so in vector form too.
    I4 special = {};
    for (int k = 0; k < 4; ++k) {
        F4 c = {};
        if (rows == 4) std::memcpy(&c, m + 4 * k, 16);
        else std::memcpy(&c, m + 3 * k, 12);
        std::memcpy(out.col[k], &c, 16);
        if (k == 3) break;  // the translation takes no term rule
        const I4 e = (I4)c & kExpMask;
        special |= e == kExpMask;
        const I4 keep = e != 0;
        std::memcpy(out.keep[k], &keep, 16);
    }
    out.special = (special[0] | special[1] | special[2] | special[3]) != 0;
}

}  // namespace

// The products below take finiteTerms unless a factor has exponent 255 (rare: the infinities and
// NaNs games leave in unused vertex components), which takes geTerm itself. transformVertex uses
// the draw's column forms (makeTransformState); these make them for one product.
void mulPoint3x4(const float m[12], const float p[3], float out[3]) {
    // x' = m0·x + m3·y + m6·z + m9, … (element k = row k%3, column k/3; ge-rules.md §3.4)
    MatrixColumns c;
    toColumns(m, 3, c);
    store3(product<true>(c, p), out);
}

float mulPointRow3x4(const float m[12], const float p[3], int r) {
    // Row r of mulPoint3x4: the same operations in the same order (the other rows cost nothing
    // more in the vector form).
    MatrixColumns c;
    toColumns(m, 3, c);
    return product<true>(c, p)[r];
}

void mulDir3x4(const float m[12], const float d[3], float out[3]) {
    // ((t0 + t1) + t2), no translation.
    MatrixColumns c;
    toColumns(m, 3, c);
    store3(product<false>(c, d), out);
}

void mulPoint4x4(const float m[16], const float p[3], float out[4]) {
    // clip = M·(x, y, z, 1), element k = row k%4, column k/4 (equation 3-3).
    MatrixColumns c;
    toColumns(m, 4, c);
    const F4 v = product<true>(c, p);
    std::memcpy(out, &v, 16);
}

TransformState makeTransformState(const GeState& st, u32 vtype, bool hasColor, bool hasNormal, MatrixFold* fold,
                                  const AccuracyProfile& acc) {
    TransformState ts;
    ts.sseNormalise = acc.sseVectorArithmetic;
    ts.through = (vtype >> 23) & 1;
    ts.hasColor = hasColor;
    ts.hasNormal = hasNormal;
    // Through mode divides by the unclamped 2^n, as the sampler multiplies by it (texture_size.h).
    ts.invTexW0 = 1.0f / float(texCoordWidth(st, 0));
    ts.invTexH0 = 1.0f / float(texCoordHeight(st, 0));
    if (ts.through) return ts;

    ts.clipEnable = st.CLE_on();
    std::memcpy(ts.world, st.world, sizeof ts.world);
    std::memcpy(ts.view, st.view, sizeof ts.view);
    std::memcpy(ts.proj, st.proj, sizeof ts.proj);
    std::memcpy(ts.tgen, st.tgen, sizeof ts.tgen);
    ts.sx = st.SX_value(), ts.sy = st.SY_value(), ts.sz = st.SZ_value();
    ts.tx = st.TX_value(), ts.ty = st.TY_value(), ts.tz = st.TZ_value();
    ts.offX16 = int(st.OFFSETX_value());
    ts.offY16 = int(st.OFFSETY_value());

    // PPSSPP's software renderer (TransformUnit ComputeTransformState, POS_TO_CLIP) multiplies the
    // 4×4 forms of world, view and projection once per draw and transforms positions with that
    // product: its float rounding differs from three chained products, and the references show
    // the difference (docs/accuracy.md). Fog does not change this (its depth is computed
    // separately), nor does lighting when every enabled light is directional (lighting then
    // needs only the world normal). A positional or spot light needs the world position, so the
    // position goes model → world and then through view·proj folded into one matrix
    // (WORLD_TO_CLIP).
    bool needWorldPos = false;
    if (st.LTE_on()) {
        for (int n = 0; n < 4; ++n)
            if (st.LE_on(n) && st.LTYPE_type(n) != 0) needWorldPos = true;
    }
    ts.combinedClip = !needWorldPos;
    ts.worldToClip = needWorldPos;
    const bool reuse = fold && fold->valid && !std::memcmp(fold->world, ts.world, sizeof ts.world) &&
                       !std::memcmp(fold->view, ts.view, sizeof ts.view) && !std::memcmp(fold->proj, ts.proj, sizeof ts.proj);
    if (reuse) {
        std::memcpy(ts.worldViewProj, fold->worldViewProj, sizeof ts.worldViewProj);
        std::memcpy(ts.viewProj, fold->viewProj, sizeof ts.viewProj);
    } else {
        float w4[16], v4[16], wv[16];
        auto to4x4 = [](const float* m, float* o) {
            for (int c = 0; c < 4; ++c) {
                for (int r = 0; r < 3; ++r) o[c * 4 + r] = m[c * 3 + r];
                o[c * 4 + 3] = c == 3 ? 1.0f : 0.0f;
            }
        };
        // o = a·b, each element summed left to right.
        auto mul4 = [](const float* a, const float* b, float* o) {
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j)
                    o[i * 4 + j] = ((a[i * 4] * b[j] + a[i * 4 + 1] * b[4 + j]) + a[i * 4 + 2] * b[8 + j]) +
                                   a[i * 4 + 3] * b[12 + j];
        };
        to4x4(ts.world, w4);
        to4x4(ts.view, v4);
        mul4(w4, v4, wv);
        mul4(wv, ts.proj, ts.worldViewProj);
        mul4(v4, ts.proj, ts.viewProj);
        if (fold) {
            std::memcpy(fold->world, ts.world, sizeof ts.world);
            std::memcpy(fold->view, ts.view, sizeof ts.view);
            std::memcpy(fold->proj, ts.proj, sizeof ts.proj);
            std::memcpy(fold->worldViewProj, ts.worldViewProj, sizeof ts.worldViewProj);
            std::memcpy(fold->viewProj, ts.viewProj, sizeof ts.viewProj);
            fold->valid = true;
        }
    }

    const u32 map = st.TMAP_mode();
    ts.texMap = map == 3 ? 0 : int(map);  // 3 behaves as UV (ge-rules.md §3.8)
    ts.projSource = int(st.TMAP_proj());
    // A texture-projection rectangle is drawn as triangles (ge-rules.md §8.2) — unless the texture matrix
    // gives Q = 1 for every vertex: its Q column is zero for X and Y, for Z too (or the source is
    // UV, whose Z is 0), and its translation Q is exactly 1. Then the rectangle keeps the
    // rectangle walk, as PPSSPP's software renderer does (Rasterizer.cpp ComputeRasterizerState
    // clears textureProj in that case). NFS Carbon draws its HUD this way; the rectangle's centre
    // sampling puts the texel columns where the reference has them.
    const bool qIsOne = ts.tgen[2] == 0.0f && ts.tgen[5] == 0.0f && (ts.tgen[8] == 0.0f || ts.projSource == 1) &&
                        ts.tgen[11] == 1.0f;
    ts.rectAsTriangles = !ts.through && ts.texMap == 1 && !qIsOne;
    ts.su = st.SU_value(), ts.sv = st.SV_value(), ts.tu = st.TU_value(), ts.tv = st.TV_value();

    ts.fog = st.FGE_on();
    if (ts.fog) {
        // ge-rules.md §8.9: FOG2 infinite → ±262144; FOG1 infinite or NaN → f is ±∞·FOG2 for the whole
        // draw: 1 when the signs agree, 0 otherwise or when FOG2 = 0 (∞·0 is NaN → 0).
        float end = st.FOG1_value(), slope = st.FOG2_value();
        if (!std::isfinite(slope)) slope = std::signbit(slope) ? -262144.0f : 262144.0f;
        if (!std::isfinite(end)) ts.fogFixed = (slope != 0.0f && std::signbit(end) == std::signbit(slope)) ? 1 : 0;
        ts.fogEnd = end;
        ts.fogSlope = slope;
    }

    ts.lighting = st.LTE_on();
    if (ts.lighting) ts.light = makeLightingState(st, hasColor, acc);
    ts.normalReverse = st.NREV_on();
    if (ts.texMap == 2) {
        // Shade mapping uses the raw light positions, normalised (zero → (0, 0, 1)), whatever
        // the light's type and even with lighting off (ge-rules.md §8.10).
        const int lu = int(st.TSHADE_u()), lv = int(st.TSHADE_v());
        const int lights[2] = {lu, lv};
        for (int k = 0; k < 2; ++k) {
            ts.shadeLight[k][0] = st.LX_value(lights[k]);
            ts.shadeLight[k][1] = st.LY_value(lights[k]);
            ts.shadeLight[k][2] = st.LZ_value(lights[k]);
            normalizeOr001(ts.shadeLight[k]);
        }
    }
    // The column forms transformVertex reads, only those it reads (made at every transform-state
    // change): the clip matrix always; world for the world position (fog, lighting, the chained
    // products) and the world normal (lighting, shade mapping); view for fog's view Z; the
    // texture matrix for projection mapping.
    const bool fogZ = ts.fog && ts.fogFixed < 0;
    const bool clipFromView = !ts.combinedClip && !ts.worldToClip;
    toColumns(ts.combinedClip ? ts.worldViewProj : ts.worldToClip ? ts.viewProj : ts.proj, 4, ts.clipCols);
    if (fogZ || !ts.combinedClip || ts.lighting || ts.texMap == 2) toColumns(ts.world, 3, ts.worldCols);
    if (fogZ || clipFromView) toColumns(ts.view, 3, ts.viewCols);
    if (ts.texMap == 1) toColumns(ts.tgen, 3, ts.tgenCols);
    return ts;
}

void projectToScreen(const TransformState& ts, ClipVertex& v, bool rangeCheck) {
    const float w = v.clip[3];
    // Scale first, then divide by w, then add the centre: the reference renderer's order (PPSSPP
    // TransformUnit: clippos·screenScale / w + screenAdd); float rounding differs from x/w·scale.
    float xs = v.clip[0] * ts.sx / w + ts.tx;
    float ys = v.clip[1] * ts.sy / w + ts.ty;
    float zs = v.clip[2] * ts.sz / w + ts.tz;
    if (ts.sprite) {
        // Transform-mode sprites (RECTANGLES), measured on a PSP: the viewport arithmetic is
        // float24, the GE's own float (ge-rules.md §1.2: its registers and matrices keep the top
        // 15 mantissa bits) — the clip coordinate, its product with the scale and the quotient by
        // W each cut toward zero, then the centre added. gpu/filtering/nearest and linear: a
        // sprite's far corner at −1 + 2/240 with SX = 240 lands at 1810.003, past the pixel edge
        // that single precision puts it on (1809.999998 → 1810.0), and the PSP samples its texture
        // as from a corner 1/16 pixel further (below: rounded up). gpu/depth/precision: Z 0x6DCC
        // with SZ = −32767.5 and TZ = 32767.5 is stored as 4660 (single precision 4659.93,
        // truncated 4659; the cut product −28107.5 gives 4660.0).
        auto cut = [](float f) { return float24(toFloat24(f)); };
        xs = cut(cut(cut(v.clip[0]) * ts.sx) / w) + ts.tx;
        ys = cut(cut(cut(v.clip[1]) * ts.sy) / w) + ts.ty;
        zs = cut(cut(cut(v.clip[2]) * ts.sz) / w) + ts.tz;
    }
    bool outside = false, zClamped = false;
    if (ts.clipEnable) {
        // CLE = 1: Z is clamped, and a clamped vertex is exempt from the X/Y range check (ge-rules.md §8.5;
        // PPSSPP's software renderer, matched to hardware tests, exempts exactly these).
        if (!(zs >= 0.0f)) zs = 0.0f, zClamped = true;
        else if (zs > 65535.0f) zs = 65535.0f, zClamped = true;
    } else if (!(zs >= 0.0f && zs < 65536.0f)) {
        outside = true;
    }
    if (!zClamped && !(xs >= 0.0f && xs < 4096.0f && ys >= 0.0f && ys < 4096.0f)) outside = true;
    if (rangeCheck) v.outside = outside;

    // ge-rules.md §8.1: round to 1/16 pixel, rounding up from 0.625 of a subpixel. The screen offset is taken
    // off in float BEFORE the truncating conversion, as the reference renderer does (PPSSPP
    // TransformUnit ClipToScreenInternal: int(x·16 + 0.375 − OFFX16)): a vertex left of / above
    // the drawing area therefore rounds toward zero, not down. For on-screen vertices the two
    // orders agree; off-screen ones move 1/16 pixel, which shifts the whole interpolation of big
    // triangles (the frametests need this order, docs/accuracy.md). The value is
    // limited first so wild (dropped or exempt) vertices convert safely; ±2^20 sixteenths is far
    // off screen.
    auto limit16 = [](double t) {
        if (!(t > -1048576.0)) t = -1048576.0;  // also NaN
        if (t > 1048576.0) t = 1048576.0;
        return int(t);
    };
    auto to16 = [&](float f, int off) { return limit16(f * 16.0f + 0.375f - float(off)); };  // in float
    // Transform-mode sprites: the screen position rounds up to the next 1/16 pixel, in screen
    // space, and the offset is taken off the result (measured on a PSP: gpu/textures/size's top
    // edge at 1920.0039 samples as from 1920.0625; gpu/filtering/precision*3d's corner at screen
    // X 2048.0 with OFFSETX 2048 + i/16 lands at −i/16, where the float subtraction above keeps
    // −(i − 1)/16). Triangles, lines and points keep the reference renderer's rule above: applied
    // to every primitive, this rule passes no further hardware checkpoint and costs most
    // frametests (docs/conformance.md, "Sprites").
    // Exact in double: f·16 is a float times a power of two.
    auto spriteTo16 = [&](float f, int off) { return limit16(std::ceil(double(f) * 16.0) - off); };
    v.sv.x = ts.sprite ? spriteTo16(xs, ts.offX16) : to16(xs, ts.offX16);
    v.sv.y = ts.sprite ? spriteTo16(ys, ts.offY16) : to16(ys, ts.offY16);
    v.sv.z = depthToInt(zs);
    v.sv.w = w;
    v.side = s8(depthSide(v));
}

void transformVertex(const TransformState& ts, const DecodedVertex& in, ClipVertex& out) {
    ScreenVertex& sv = out.sv;
    if (ts.through) {
        // Drawing coordinates as given (ge-rules.md §8.1), Z 0–65535, texels divided by the level-0 size
        // (ge-rules.md §8.10); no lighting, fog or clipping (ge-rules.md §5.5).
        auto to16 = [](float f) {
            float t = f * 16.0f;
            if (!(t > -1048576.0f)) t = -1048576.0f;
            if (t > 1048576.0f) t = 1048576.0f;
            return int(t);
        };
        sv.x = to16(in.pos[0]);
        sv.y = to16(in.pos[1]);
        sv.z = depthToInt(in.pos[2]);
        sv.w = 1.0f;
        sv.s = in.uv[0] * ts.invTexW0;
        sv.t = in.uv[1] * ts.invTexH0;
        sv.q = 1.0f;
        sv.fog = 1.0f;
        std::memcpy(sv.color, in.color, 4);
        sv.secondary[0] = sv.secondary[1] = sv.secondary[2] = 0;
        out.clip[0] = in.pos[0], out.clip[1] = in.pos[1], out.clip[2] = in.pos[2], out.clip[3] = 1.0f;
        out.outside = false;
        return;
    }

    float model[3] = {in.pos[0], in.pos[1], in.pos[2]};
    float normal[3] = {0.0f, 0.0f, 1.0f};
    if (ts.hasNormal) {
        const float k = ts.normalReverse ? -1.0f : 1.0f;  // CMD_NREV (manual §9)
        normal[0] = in.nrm[0] * k, normal[1] = in.nrm[1] * k, normal[2] = in.nrm[2] * k;
    }
    // World and view positions only where something reads them: the clip position when it is not
    // made from the combined matrix, lighting (world), fog (view Z). The products are the same
    // when they are made; skipping them changes nothing else.
    float world[3] = {}, viewPos[3] = {};
    const bool clipFromView = !ts.combinedClip && !ts.worldToClip;
    const bool fogZ = ts.fog && ts.fogFixed < 0;
    const bool needView = clipFromView || fogZ;
    // The products inline (mulPoint3x4, mulPointRow3x4, mulPoint4x4 with the draw's columns).
    if (needView || !ts.combinedClip || ts.lighting) store3(product<true>(ts.worldCols, model), world);
    if (clipFromView) store3(product<true>(ts.viewCols, world), viewPos);
    else if (fogZ) viewPos[2] = product<true>(ts.viewCols, world)[2];  // fog reads only view Z
    // clipCols: worldViewProj, viewProj or proj (makeTransformState), applied to its input.
    const F4 clip = product<true>(ts.clipCols, ts.combinedClip ? model : ts.worldToClip ? world : viewPos);
    std::memcpy(out.clip, &clip, sizeof clip);

    // Fog factor per vertex from view-space Z (ge-rules.md §3.9).
    if (!ts.fog) sv.fog = 1.0f;
    else if (ts.fogFixed >= 0) sv.fog = float(ts.fogFixed);
    else sv.fog = (viewPos[2] + ts.fogEnd) * ts.fogSlope;

    // World-space normal for lighting and shade mapping, normalised; (0, 0, 1) without one.
    float worldNormal[3] = {0.0f, 0.0f, 1.0f};
    if (ts.hasNormal && (ts.lighting || ts.texMap == 2)) {
        store3(product<false>(ts.worldCols, normal), worldNormal);
        normalizeOr001(worldNormal, ts.sseNormalise);
    }

    // Texture coordinates (manual §13.1, §13.2).
    sv.q = 1.0f;
    switch (ts.texMap) {
    case 1: {
        // Projection mapping: (S, T, Q) = TGEN·source; SU/SV/TU/TV not applied; Q divides per pixel.
        float src[3] = {0.0f, 0.0f, 0.0f};
        switch (ts.projSource) {
        case 0: std::memcpy(src, model, sizeof src); break;
        case 1: src[0] = in.uv[0], src[1] = in.uv[1]; break;
        case 2: {
            // Normalised normal; a zero normal stays zero (no (0, 0, 1) substitute here).
            const double l = std::sqrt(double(normal[0]) * normal[0] + double(normal[1]) * normal[1] +
                                       double(normal[2]) * normal[2]);
            if (l > 0.0) {
                for (int i = 0; i < 3; ++i) src[i] = float(normal[i] / l);
            }
            break;
        }
        default: std::memcpy(src, normal, sizeof src); break;
        }
        float stq[3];
        store3(product<true>(ts.tgenCols, src), stq);
        sv.s = stq[0], sv.t = stq[1], sv.q = stq[2];
        break;
    }
    case 2: {
        // Shade mapping: s = (normalize(Lu)·N + 1)/2, t likewise (manual §13.1.3; ge-rules.md §8.10).
        const float* lu = ts.shadeLight[0];
        const float* lv = ts.shadeLight[1];
        const float du = lu[0] * worldNormal[0] + lu[1] * worldNormal[1] + lu[2] * worldNormal[2];
        const float dv = lv[0] * worldNormal[0] + lv[1] * worldNormal[1] + lv[2] * worldNormal[2];
        sv.s = (du + 1.0f) / 2.0f;
        sv.t = (dv + 1.0f) / 2.0f;
        break;
    }
    default:
        // UV mapping with scale and offset (equation 13-3).
        sv.s = ts.su * in.uv[0] + ts.tu;
        sv.t = ts.sv * in.uv[1] + ts.tv;
        break;
    }

    // Colours (manual §9.2.4): lit, or the vertex colour (MAC/MAA without one) and no secondary.
    if (ts.lighting) {
        lightVertex(ts.light, world, worldNormal, in.color, sv.color, sv.secondary);
    } else {
        std::memcpy(sv.color, in.color, 4);
        sv.secondary[0] = sv.secondary[1] = sv.secondary[2] = 0;
    }

    projectToScreen(ts, out, true);
}

}  // namespace ge::geo
