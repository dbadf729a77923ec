// Near-plane clipping and the discard rules (see clip.h).
#include "softmodel/clip.h"

namespace ge::soft {

namespace {

// Signed distance to the near plane z = −w (≥ 0 inside).
inline float nearDist(const ClipVertex& v) { return v.clip[2] + v.clip[3]; }

}  // namespace

int depthSide(const ClipVertex& v) {
    // 1.00003: the tolerance measured for the depth range (§8.5).
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
        const int side = depthSide(*v[i]);
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
    int k = int(t * 256.0f);
    k = k < 0 ? 0 : (k > 256 ? 256 : k);
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
    for (int i = 0; i < 3; ++i) {
        const ClipVertex& p = *in[i];
        const ClipVertex& q = *in[(i + 1) % 3];
        const float dp = nearDist(p), dq = nearDist(q);
        const bool pin = dp >= 0.0f, qin = dq >= 0.0f;
        if (pin) out[n++] = p;
        if (pin != qin && n < 4) lerpVertex(ts, p, q, dp / (dp - dq), out[n++]);
    }
    return n >= 3 ? n : 0;
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

}  // namespace ge::soft
