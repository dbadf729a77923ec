// SPDX-License-Identifier: MIT
// Near-plane clipping and the discard rules (see clip.h).
#include "geometry/clip.h"

#include <algorithm>
#include <cstdint>

namespace ge::geo {

namespace {

// Signed distance to the near plane z = −w (≥ 0 inside).
inline float nearDist(const ClipVertex& v) { return v.clip[2] + v.clip[3]; }

// Screen X/Y of a clip-space vertex outside [0, 4096), computed as projectToScreen does.
inline bool xyOutside(const TransformState& ts, const ClipVertex& v) {
    const float w = v.clip[3];
    const float xs = v.clip[0] * ts.sx / w + ts.tx;
    const float ys = v.clip[1] * ts.sy / w + ts.ty;
    return !(xs >= 0.0f && xs < 4096.0f && ys >= 0.0f && ys < 4096.0f);
}

}  // namespace

int depthSide(const ClipVertex& v) {
    // 1.00003: the tolerance measured for the depth range (docs/ge-rules.md §8.5).
    constexpr float kBound = 1.00003f;
    const float r = v.clip[2] / v.clip[3];
    if (r >= kBound) return 1;
    if (r <= -kBound) return -1;
    return 0;  // inside, or NaN
}

bool discardPrimitive(const TransformState& ts, const ClipVertex* const* v, int n) {
    if (ts.through) return false;
    int nearCount = 0, farCount = 0;
    for (int i = 0; i < n; ++i) {
        if (!v[i]->valid || v[i]->outside) return true;
        const int side = v[i]->side;  // depthSide, made by projectToScreen
        nearCount += side < 0;
        farCount += side > 0;
    }
    if (!ts.clipEnable) return nearCount + farCount > 0;
    return nearCount == n || farCount == n;
}

void lerpVertex(const TransformState& ts, const ClipVertex& a, const ClipVertex& b, float t, ClipVertex& out) {
    for (int i = 0; i < 4; ++i) out.clip[i] = a.clip[i] + (b.clip[i] - a.clip[i]) * t;
    const ScreenVertex& p = a.sv;
    const ScreenVertex& q = b.sv;
    ScreenVertex& r = out.sv;
    r.s = p.s + (q.s - p.s) * t;
    r.t = p.t + (q.t - p.t) * t;
    r.q = p.q + (q.q - p.q) * t;
    r.fog = p.fog + (q.fog - p.fog) * t;
    // Colours use an 8-bit weight, (a·(256 − k) + b·k) / 256, as PPSSPP's clipper does.
    // Limited in float before the conversion (NaN and out-of-range floats have no int value).
    const float kf = t * 256.0f;
    const int k = kf >= 0.0f ? (kf <= 256.0f ? int(kf) : 256) : 0;
    for (int c = 0; c < 4; ++c) r.color[c] = u8((p.color[c] * (256 - k) + q.color[c] * k) / 256);
    for (int c = 0; c < 3; ++c) r.secondary[c] = u8((p.secondary[c] * (256 - k) + q.secondary[c] * k) / 256);
    out.valid = true;
    out.outside = false;
    projectToScreen(ts, out, false);
}

int clipTriangleNear(const TransformState& ts, const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                     ClipVertex out[4]) {
    // Sutherland–Hodgman against one plane: a triangle gives at most a quadrilateral.
    const ClipVertex* in[3] = {&a, &b, &c};
    int n = 0;
    int tag[4] = {};  // 0–2: input vertex; 3 + i: the point on edge (i, i + 1)
    for (int i = 0; i < 3; ++i) {
        const ClipVertex& p = *in[i];
        const ClipVertex& q = *in[(i + 1) % 3];
        const float dp = nearDist(p), dq = nearDist(q);
        const bool pin = dp >= 0.0f, qin = dq >= 0.0f;
        if (pin) tag[n] = i, out[n++] = p;
        // The new vertex is always interpolated from the outside vertex toward the inside one,
        // t = d_out / (d_out − d_in), as PPSSPP's clipper does (Clipper.cpp CLIP_POLY): the float
        // rounding of the lerp depends on the direction.
        if (pin != qin && n < 4) {
            if (pin) lerpVertex(ts, q, p, dq / (dq - dp), out[n]);
            else lerpVertex(ts, p, q, dp / (dp - dq), out[n]);
            // A new vertex whose screen X or Y is outside [0, 4096) drops every fan triangle that
            // uses it (PPSSPP Clipper.cpp clip_interpolate marks it, ProcessTriangle skips those
            // sub-triangles). Unlike input vertices, no Z-clamp exemption applies and Z is not
            // checked: the Nova frametest is worse with the exemption, and checking Z as well
            // drops whole clipped surfaces there (docs/accuracy.md).
            out[n].outside = xyOutside(ts, out[n]);
            tag[n] = 3 + i;
            ++n;
        }
    }
    if (n < 3) return 0;
    // PPSSPP's rasteriser draws only triangles of one winding (BinManager::AddTriangle keeps
    // cross ≥ 0) and its transform unit submits (c, b, a) as well when that is the drawn order.
    // The new vertices do not depend on the order (interpolated from the outside vertex), but the
    // polygon then starts at a different vertex, so its fan – and which fan triangles the range
    // rule drops – differ. Rotate our polygon (keeping our winding) to start where the reversed
    // clip would start.
    int64_t area2 = 0;
    for (int k = 0; k < n; ++k) {
        const ScreenVertex& p = out[k].sv;
        const ScreenVertex& q = out[(k + 1) % n].sv;
        area2 += int64_t(p.x) * q.y - int64_t(q.x) * p.y;
    }
    if (area2 < 0) {
        int first = -1;
        const int rev[3] = {2, 1, 0};
        for (int i = 0; i < 3 && first < 0; ++i) {
            const int pi = rev[i], qi = rev[(i + 1) % 3];
            if (nearDist(*in[pi]) >= 0.0f) first = pi;
            else if (nearDist(*in[qi]) >= 0.0f) first = 3 + std::min(pi, qi) + (std::max(pi, qi) - std::min(pi, qi) == 2 ? 2 : 0);
        }
        int at = 0;
        while (at < n && tag[at] != first) ++at;
        if (at > 0 && at < n) {
            ClipVertex tmp[4];
            for (int k = 0; k < n; ++k) tmp[k] = out[(at + k) % n];
            for (int k = 0; k < n; ++k) out[k] = tmp[k];
        }
    }
    // The caller fans the polygon from out[0]: (0, 1, 2) and, for a quadrilateral, (0, 2, 3).
    // Keep exactly the fan triangles without an outside vertex, in the same vertex order.
    const bool keep1 = !out[0].outside && !out[1].outside && !out[2].outside;
    if (n == 3) return keep1 ? 3 : 0;
    const bool keep2 = !out[0].outside && !out[2].outside && !out[3].outside;
    if (keep1 && keep2) return 4;
    if (keep1) return 3;
    if (keep2) {
        out[1] = out[2];
        out[2] = out[3];
        return 3;
    }
    return 0;
}

bool clipLineNear(const TransformState& ts, ClipVertex& a, ClipVertex& b) {
    const float da = nearDist(a), db = nearDist(b);
    const bool ain = da >= 0.0f, bin = db >= 0.0f;
    if (ain && bin) return true;
    if (!ain && !bin) return false;
    ClipVertex v;
    if (!ain) {
        lerpVertex(ts, a, b, da / (da - db), v);
        a = v;
    } else {
        lerpVertex(ts, b, a, db / (db - da), v);
        b = v;
    }
    return true;
}

}  // namespace ge::geo
