// SPDX-License-Identifier: MIT
// Per-vertex lighting (manual §9; docs/ge-rules.md §8.3, §8.9, §8.12). See lighting.h.
#include "geometry/lighting.h"

#include <algorithm>
#include <cmath>
#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace ge::geo {

namespace {

// (2·c + 1) per channel of a CMD_xxx RGB colour word (ge-rules.md §8.3 "half offset" products).
void colorFactor(u32 rgb, int out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = 2 * int((rgb >> (8 * i)) & 0xFF) + 1;
}

float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// s = min(512, ceil(512·k + 1)) of ge-rules.md §8.3. k is finite here (callers reject NaN); very large or
// negative products are kept in int range before the conversion.
int lightScale(float k) {
    float s = std::ceil(k * 512.0f + 1.0f);
    if (s > 512.0f) return 512;
    if (s < -512.0f) return -512;
    return int(s);
}

// ((2·Lc + 1)·(2·Mc + 1)·s) >> 19 added to `acc` for three channels.
void addTerm(int acc[3], const int light[3], const int mat[3], int s) {
    for (int i = 0; i < 3; ++i) acc[i] += (light[i] * mat[i] * s) >> 19;
}

// rsqrtss: the approximation PPSSPP's x86 build normalises with (the host's own on x86).
float approxRsqrt(float x) {
#if defined(__SSE__) || defined(_M_X64)
    return _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
#else
    return 1.0f / std::sqrt(x);
#endif
}

// PPSSPP's Vec3<float>::Length on x86 (Math3D.cpp): x² + (y² + z²) in float, then the root.
float floatLength(const float v[3]) {
    const float xx = v[0] * v[0], yy = v[1] * v[1], zz = v[2] * v[2];
    return std::sqrt(xx + (yy + zz));
}

// The spot cosine for every vertex when PPSSPP's LD / |LD| (AccuracyProfile::spotDirectionDivide)
// gives NaN, else −1 and `dir` normalised by that division. On x86 0/0 and ∞/∞ give the default
// NaN, sign set (cosine 0); a NaN component's own NaN reaches the cosine first (its sign: 1 or 0).
float spotByDivision(float dir[3]) {
    for (int i = 0; i < 3; ++i)
        if (std::isnan(dir[i])) return std::signbit(dir[i]) ? 0.0f : 1.0f;
    const float len = floatLength(dir);
    if (len == 0.0f || std::isinf(len)) {
        // A zero vector, or one with an infinite component, has a NaN component after the
        // division; an overflowing finite one divides to zeros (cosine 0 as well); one whose
        // squares underflow to a zero length is taken as zero (not measured).
        return 0.0f;
    }
    for (int i = 0; i < 3; ++i) dir[i] /= len;
    return -1.0f;
}

}  // namespace

void normalizeRsqrtOr001(float v[3]) {
    const float xx = v[0] * v[0], yy = v[1] * v[1], zz = v[2] * v[2];
    const float r = approxRsqrt((xx + yy) + zz);
    for (int i = 0; i < 3; ++i) {
        v[i] *= r;
        if (std::isnan(v[i])) v[i] = i == 2 ? 1.0f : 0.0f;
    }
}

float normalizeOr001(float v[3], bool sse) {
    const double l2 = double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2];
    const float len = sse ? floatLength(v) : float(std::sqrt(l2));
    if (!(len > 0.0f) || !std::isfinite(len)) {
        v[0] = 0.0f, v[1] = 0.0f, v[2] = 1.0f;
        return 0.0f;
    }
    v[0] /= len, v[1] /= len, v[2] /= len;
    return len;
}

float lightPow(float base, float exponent) {
    // ge-rules.md §8.9: exponent ≤ 0 → factor 1; a negative NaN exponent behaves the same (PPSSPP).
    if (exponent <= 0.0f || (std::isnan(exponent) && std::signbit(exponent))) return 1.0f;
    if (base > 0.0f) return std::pow(base, exponent);
    return base;  // a negative base is not raised to the power
}

LightingState makeLightingState(const GeState& st, bool vertexHasColor, const AccuracyProfile& acc) {
    LightingState ls;
    ls.sse = acc.sseVectorArithmetic;
    for (int n = 0; n < 4; ++n) {
        LightSource& L = ls.lights[n];
        L.enabled = st.LE_on(n);
        if (!L.enabled) continue;
        const u32 type = st.LTYPE_type(n);  // 3 behaves as spot (ge-rules.md §3.6)
        const u32 comp = st.LTYPE_comp(n);  // 3 behaves as 0
        L.directional = type == 0;
        L.spot = type >= 2;
        L.specular = comp == 1;
        L.poweredDiffuse = comp == 2;
        L.pos[0] = st.LX_value(n), L.pos[1] = st.LY_value(n), L.pos[2] = st.LZ_value(n);
        if (L.directional) normalizeOr001(L.pos, ls.sse);  // ge-rules.md §8.12: zero → (0, 0, 1)
        L.att[0] = st.LKA_value(n), L.att[1] = st.LKB_value(n), L.att[2] = st.LKC_value(n);
        if (L.spot) {
            // LD need not be normalised (manual §9.2.3). One that cannot be (measured on a PSP,
            // pspautotests gpu/commands/light "Spot zero vector / NAN / -NAN / INFINITY /
            // -INFINITY", each with all three components equal): a zero vector gives no light;
            // a NaN or infinite component makes the cosine a NaN of that component's sign, which
            // the NaN rule below turns into 1 (positive: full light) or 0. With mixed special
            // components the first one decides (not measured).
            L.spotDir[0] = st.LDX_value(n), L.spotDir[1] = st.LDY_value(n), L.spotDir[2] = st.LDZ_value(n);
            if (acc.spotDirectionDivide) {
                L.spotForced = spotByDivision(L.spotDir);
            } else {
                for (float c : L.spotDir)
                    if (!std::isfinite(c)) {
                        L.spotForced = std::signbit(c) ? 0.0f : 1.0f;
                        break;
                    }
                if (L.spotForced < 0 && L.spotDir[0] == 0.0f && L.spotDir[1] == 0.0f && L.spotDir[2] == 0.0f)
                    L.spotForced = 0.0f;
                if (L.spotForced < 0) normalizeOr001(L.spotDir);
            }
            L.spotExp = st.LKS_value(n);
            L.spotCutoff = st.LKO_value(n);
            if (std::isnan(L.spotCutoff) && std::signbit(L.spotCutoff)) L.spotCutoff = 0.0f;
        }
        colorFactor(st.LAC_rgb(n), L.ambient);
        colorFactor(st.LDC_rgb(n), L.diffuse);
        colorFactor(st.LSC_rgb(n), L.specularColor);
    }
    for (int i = 0; i < 3; ++i) ls.emissive[i] = int((st.MEC_rgb() >> (8 * i)) & 0xFF);
    colorFactor(st.AC_rgb(), ls.globalAmbient);
    ls.globalAmbient[3] = 2 * int(st.AA_alpha()) + 1;
    colorFactor(st.MAC_rgb(), ls.matAmbient);
    ls.matAmbient[3] = 2 * int(st.MAA_alpha()) + 1;
    colorFactor(st.MDC_rgb(), ls.matDiffuse);
    colorFactor(st.MSC_rgb(), ls.matSpecular);
    // The update flags take effect only when the vertex carries a colour (ge-rules.md §3.6).
    ls.ambientFromVertex = vertexHasColor && st.MATERIAL_ambient();
    ls.diffuseFromVertex = vertexHasColor && st.MATERIAL_diffuse();
    ls.specularFromVertex = vertexHasColor && st.MATERIAL_specular();
    ls.separateSpecular = st.LMODE_separate();
    ls.specularExp = st.MK_value();
    return ls;
}

void lightVertex(const LightingState& ls, const float worldPos[3], const float N[3], const u8 vertexColor[4],
                 u8 primary[4], u8 secondary[3]) {
    int vc[4];
    for (int i = 0; i < 4; ++i) vc[i] = 2 * int(vertexColor[i]) + 1;
    const int* mac = ls.ambientFromVertex ? vc : ls.matAmbient;
    const int* mdc = ls.diffuseFromVertex ? vc : ls.matDiffuse;
    const int* msc = ls.specularFromVertex ? vc : ls.matSpecular;

    // Emission + global ambient (equation 9-1, ge-rules.md §8.3 row "global ambient").
    int color[4], spec[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) color[i] = ls.emissive[i] + ((ls.globalAmbient[i] * mac[i]) >> 10);
    // Lit alpha = AA ⊙ (vertex alpha or MAA) (ge-rules.md §8.12); lights add nothing to alpha.
    color[3] = (ls.globalAmbient[3] * mac[3]) >> 10;

    for (const LightSource& L : ls.lights) {
        if (!L.enabled) continue;
        float Lv[3] = {L.pos[0], L.pos[1], L.pos[2]};
        float attspot = 1.0f;
        if (!L.directional) {
            // L = light − vertex, d = |L| (ge-rules.md §8.12); attenuation 9-3 clamped to [0, 1].
            Lv[0] -= worldPos[0], Lv[1] -= worldPos[1], Lv[2] -= worldPos[2];
            const float d = normalizeOr001(Lv, ls.sse);
            float att = 1.0f / (L.att[0] + L.att[1] * d + L.att[2] * d * d);
            if (!(att > 0.0f)) att = 0.0f;  // negative, NaN
            else if (att > 1.0f) att = 1.0f;
            attspot = att;
        }
        if (L.spot) {
            // The cosine is LD·L with L = light − vertex: the spot direction points from the lit
            // surface toward the light. The manual's equation 9-4 takes V = light → vertex, the
            // opposite sign; a PSP does not (pspautotests gpu/commands/light, tests/conformance/:
            // a spot light straight above a quad with LD = (0, 0, 1) lights it fully, with
            // LD = (1, 1, 1) by cos 0.577), and neither does the reference renderer
            // (GPU/Software/Lighting.cpp: Dot33(spotDir, L)). The light counts when the cosine
            // is ≥ LKO (ge-rules.md §8.9, measured; the manual says >).
            float raw = L.spotForced >= 0 ? L.spotForced : dot3(L.spotDir, Lv);
            if (std::isnan(raw)) raw = std::signbit(raw) ? 0.0f : 1.0f;
            float spot = 0.0f;
            if (raw >= L.spotCutoff) {
                spot = lightPow(raw, L.spotExp);
                if (std::isnan(spot)) spot = 0.0f;
            }
            attspot *= spot;
        }
        if (std::isnan(attspot)) continue;

        // Ambient (9-5): k = att·spot.
        addTerm(color, L.ambient, mac, lightScale(attspot));

        const float ndotl = dot3(Lv, N);
        float diffuse = ndotl;
        if (L.poweredDiffuse) diffuse = lightPow(ndotl, ls.specularExp);  // 9-7
        if (diffuse > 0.0f) {  // "Diffuse counts only when N·L > 0" (ge-rules.md §8.12)
            addTerm(color, L.diffuse, mdc, lightScale(attspot * diffuse));
        }
        if (L.specular && ndotl >= 0.0f) {  // specular only when N·L ≥ 0 (ge-rules.md §8.12)
            // H = normalize(normalize(L) + E), E = (0, 0, 1) (9-8).
            float H[3] = {Lv[0], Lv[1], Lv[2] + 1.0f};
            if (ls.sse) normalizeRsqrtOr001(H);
            else normalizeOr001(H);
            const float sp = lightPow(dot3(H, N), ls.specularExp);
            if (sp > 0.0f) addTerm(spec, L.specularColor, msc, lightScale(attspot * sp));
        }
    }

    if (!ls.separateSpecular) {
        for (int i = 0; i < 3; ++i) color[i] += spec[i], spec[i] = 0;
    }
    for (int i = 0; i < 4; ++i) primary[i] = u8(std::clamp(color[i], 0, 255));
    for (int i = 0; i < 3; ++i) secondary[i] = u8(std::clamp(spec[i], 0, 255));
}

}  // namespace ge::geo
