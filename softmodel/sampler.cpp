// SPDX-License-Identifier: MIT
#include "softmodel/sampler.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "geometry/raster.h"
#include "geometry/texture_size.h"

namespace ge::soft {

void TexLevel::setSize(u32 wlog, u32 hlog, int sw, int sh) {
    storedW = std::max(sw, 1);
    storedH = std::max(sh, 1);
    // The scale is the full 2^n, past 512 too; only the texel index stops at 511
    // (geometry/texture_size.h, with the PSP's values). Exact powers of two: s·scale equals the
    // reference's (s·w)·256 bit for bit.
    scaleU = float(geo::texCoordSize(wlog)) * 256.0f;
    scaleV = float(geo::texCoordSize(hlog)) * 256.0f;
    // docs/ge-rules.md §8.10: repeat u & (w − 1) & 511; clamp 0 … min(w, 512) − 1. The stored size bound only
    // matters if a decoder ever returned fewer texels than the nominal size.
    wrapMaskU = geo::texelWrapMask(wlog);
    wrapMaskV = geo::texelWrapMask(hlog);
    clampMaxU = geo::texelClampMax(wlog);
    clampMaxV = geo::texelClampMax(hlog);
    if (wrapMaskU > storedW - 1) wrapMaskU = storedW - 1;
    if (wrapMaskV > storedH - 1) wrapMaskV = storedH - 1;
    clampMaxU = std::min(clampMaxU, storedW - 1);
    clampMaxV = std::min(clampMaxV, storedH - 1);
}

int texLog2x16(float x) {
    u32 bits;
    std::memcpy(&bits, &x, 4);
    // Exponent (8 bits) and the top 4 mantissa bits: 16·(e − 127) + m4; bit 31 (sign) dropped.
    return int((bits >> 19) & 0xFFF) - 127 * 16;
}

int levelOfDetail16(const LodParams& p, float lod, float w) {
    int d;
    switch (p.mode) {
    case 0: {
        // Fragment::lod is the rasteriser's log2 of the texel/pixel ratio, formed the GE's way
        // (exponent + top mantissa bits of the ratio, geometry/raster.cpp texLog2): the 4-bit
        // detail is its floor in 1/16 steps, i.e. the exponent and the top 4 mantissa bits.
        const float x16 = lod * 16.0f;
        d = x16 >= 4096.0f ? 4096 : (x16 > -4096.0f ? int(std::floor(x16)) : -4096);  // NaN → −4096
        break;
    }
    case 2:
        // ge-rules.md §6.6: d = log2(TSLOPE·W) + 1, the +1 measured; formed as log2(2·TSLOPE·W).
        d = texLog2x16(2.0f * w * p.slope);
        break;
    default: d = 0; break;  // constant mode (1, and 3 which behaves as 1)
    }
    // Clamp before adding so NaN/inf-derived values cannot overflow.
    d = std::clamp(d, -4096, 4096);
    return d + p.bias16;
}

LevelChoice chooseLevel(const LodParams& p, int detail16) {
    LevelChoice c;
    if (detail16 > 0) {
        c.linear = p.minLinear;
        if (p.maxLevel > 0) {
            int l = std::min(detail16, p.maxLevel * 16);
            if (!p.mipLinear) l += 8;  // nearest level: round at .5
            c.level = l >> 4;
            c.frac = p.mipLinear ? (l & 15) : 0;
        }
    } else {
        c.linear = p.magLinear;
    }
    return c;
}

int highestLevelNeeded(const LodParams& p, bool fixedChoice, const LevelChoice& fixed) {
    if (fixedChoice) return std::min(fixed.level + (fixed.frac ? 1 : 0), 7);
    return std::clamp(p.maxLevel, 0, 7);
}

namespace {

// A texel coordinate with 8 fraction bits, truncated toward zero like the float→int conversion
// of the reference; values outside int range (and NaN) become INT_MIN.
inline s64 texelFixed(float f) {
    return (f >= -2147483648.0f && f < 2147483648.0f) ? s64(s32(f)) : s64(INT32_MIN);
}

// The same position rounded to nearest (ties to even) for the bilinear path: upstream SWR's x86
// sampler JIT converts s·w·256 with CVTPS2DQ (current rounding mode, nearest-even) for the
// four-texel quad, but with CVTTPS2DQ (truncation) for nearest sampling (SamplerX86.cpp
// Jit_GetTexelCoordsQuad vs Jit_GetTexelCoords). Out of range and NaN give INT_MIN as the
// instruction's "integer indefinite" value.
inline s64 texelFixedRound(float f) {
    return (f >= -2147483648.0f && f < 2147483648.0f) ? s64(s32(geo::roundHalfEven(f))) : s64(INT32_MIN);
}

template <bool CLAMP>
inline int addressTexel(s64 u, int mask, int maxIndex) {
    if constexpr (CLAMP) return u < 0 ? 0 : (u > maxIndex ? maxIndex : int(u));
    else return int(u & mask);
}

// Channels spread into four 16-bit lanes so one multiply weights all of them.
inline u64 spread(u32 c) {
    u64 x = c;
    x = (x | x << 16) & 0x0000FFFF0000FFFFull;
    return (x | x << 8) & 0x00FF00FF00FF00FFull;
}
inline u32 compact(u64 x) {
    x &= 0x00FF00FF00FF00FFull;
    x = (x | x >> 8) & 0x0000FFFF0000FFFFull;
    return u32(x | x >> 16);
}

// The bilinear sum of four texels (a above b, 0 left of 1) with 4-bit fractions fu, fv: per channel
// (Σ texel·weight) >> 8, the weights (16 − fu)(16 − fv), fu(16 − fv), (16 − fu)fv, fu·fv summing
// to 256. Every product and the sum fit 16 bits (≤ 255·256), so SSE2 weighs the four texels'
// sixteen channels with two 16-bit multiplies; without SSE2 the channels are spread into 16-bit
// lanes of a 64-bit word. Both give the same integers.
inline u32 weighQuad(u32 a0, u32 a1, u32 b0, u32 b1, int fu, int fv) {
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    const __m128i top = _mm_unpacklo_epi8(_mm_unpacklo_epi32(_mm_cvtsi32_si128(int(a0)), _mm_cvtsi32_si128(int(a1))), zero);
    const __m128i bot = _mm_unpacklo_epi8(_mm_unpacklo_epi32(_mm_cvtsi32_si128(int(b0)), _mm_cvtsi32_si128(int(b1))), zero);
    const short wa0 = short((16 - fu) * (16 - fv)), wa1 = short(fu * (16 - fv));
    const short wb0 = short((16 - fu) * fv), wb1 = short(fu * fv);
    const __m128i sum = _mm_add_epi16(_mm_mullo_epi16(top, _mm_setr_epi16(wa0, wa0, wa0, wa0, wa1, wa1, wa1, wa1)),
                                      _mm_mullo_epi16(bot, _mm_setr_epi16(wb0, wb0, wb0, wb0, wb1, wb1, wb1, wb1)));
    const __m128i both = _mm_srli_epi16(_mm_add_epi16(sum, _mm_srli_si128(sum, 8)), 8);
    return u32(_mm_cvtsi128_si32(_mm_packus_epi16(both, zero)));
#else
    const u64 sum = spread(a0) * u64((16 - fu) * (16 - fv)) + spread(a1) * u64(fu * (16 - fv)) +
                    spread(b0) * u64((16 - fu) * fv) + spread(b1) * u64(fu * fv);
    return compact(sum >> 8);
#endif
}

template <bool CU, bool CV>
inline u32 nearestT(const TexLevel& lv, float s, float t) {
    if (!lv.texels) return 0;
    const int u = addressTexel<CU>(texelFixed(s * lv.scaleU) >> 8, lv.wrapMaskU, lv.clampMaxU);
    const int v = addressTexel<CV>(texelFixed(t * lv.scaleV) >> 8, lv.wrapMaskV, lv.clampMaxV);
    return lv.texels[size_t(v) * size_t(lv.storedW) + size_t(u)];
}

template <bool CU, bool CV>
inline u32 bilinearT(const TexLevel& lv, float s, float t) {
    if (!lv.texels) return 0;
    // Rounded (texelFixedRound) or truncated position (TexLevel::linearTruncates), half a texel
    // back (128/256), then 8 integer bits and the top 4 of the fraction.
    const s64 bu = (lv.linearTruncates ? texelFixed(s * lv.scaleU) : texelFixedRound(s * lv.scaleU)) - 128;
    const s64 bv = (lv.linearTruncates ? texelFixed(t * lv.scaleV) : texelFixedRound(t * lv.scaleV)) - 128;
    const int fu = int((bu >> 4) & 15), fv = int((bv >> 4) & 15);
    const s64 u0 = bu >> 8, v0 = bv >> 8;
    const int ua = addressTexel<CU>(u0, lv.wrapMaskU, lv.clampMaxU);
    const int ub = addressTexel<CU>(u0 + 1, lv.wrapMaskU, lv.clampMaxU);
    const u32* rowA = lv.texels + size_t(addressTexel<CV>(v0, lv.wrapMaskV, lv.clampMaxV)) * size_t(lv.storedW);
    const u32* rowB = lv.texels + size_t(addressTexel<CV>(v0 + 1, lv.wrapMaskV, lv.clampMaxV)) * size_t(lv.storedW);
    return weighQuad(rowA[ua], rowA[ub], rowB[ua], rowB[ub], fu, fv);
}

template <bool LINEAR, bool CU, bool CV>
inline u32 filterT(const TexLevel& lv, float s, float t) {
    if constexpr (LINEAR) return bilinearT<CU, CV>(lv, s, t);
    else return nearestT<CU, CV>(lv, s, t);
}

u32 filterLevel(const TexLevel& lv, float s, float t, bool linear, bool cu, bool cv) {
    const int k = (linear ? 4 : 0) | (cu ? 2 : 0) | (cv ? 1 : 0);
    switch (k) {
    case 0: return filterT<false, false, false>(lv, s, t);
    case 1: return filterT<false, false, true>(lv, s, t);
    case 2: return filterT<false, true, false>(lv, s, t);
    case 3: return filterT<false, true, true>(lv, s, t);
    case 4: return filterT<true, false, false>(lv, s, t);
    case 5: return filterT<true, false, true>(lv, s, t);
    case 6: return filterT<true, true, false>(lv, s, t);
    default: return filterT<true, true, true>(lv, s, t);
    }
}

// One known level, one known filter: the common case (no mipmaps, or constant level mode).
template <bool LINEAR, bool CU, bool CV>
u32 sampleFixedT(const Sampler& sm, float s, float t, float, float) {
    return filterT<LINEAR, CU, CV>(sm.levels[sm.fixed.level], s, t);
}

#if defined(__SSE2__)
// Four fragments through filterT<LINEAR, CU, CV> on one level: the coordinate products, their
// conversion to 8-fraction-bit fixed point and the wrap/clamp addressing are done for the four
// pixels at once; the texel loads and the bilinear weighting stay per pixel. Each lane repeats
// the scalar routine's operations: the same float products; cvttps2dq truncates as texelFixed
// does and cvtps2dq rounds to nearest-even as texelFixedRound does (MXCSR's default mode, which
// the scalar roundHalfEven also assumes), both giving INT32_MIN out of range and for NaN. The
// scalar code then works in 64 bits; lanes within 128 of INT32_MIN would wrap in 32, so a group
// holding one goes through the scalar routine instead.
template <bool CLAMP>
inline __m128i addressTexels(__m128i u, int mask, int maxIndex) {
    if constexpr (CLAMP) {
        const __m128i zero = _mm_setzero_si128(), hi = _mm_set1_epi32(maxIndex);
        u = _mm_andnot_si128(_mm_cmplt_epi32(u, zero), u);  // u < 0 → 0
        const __m128i over = _mm_cmpgt_epi32(u, hi);
        return _mm_or_si128(_mm_and_si128(over, hi), _mm_andnot_si128(over, u));
    } else {
        return _mm_and_si128(u, _mm_set1_epi32(mask));
    }
}

template <bool LINEAR, bool CU, bool CV>
void sampleFixed4T(const Sampler& sm, const geo::Fragment* f, u32* out) {
    const TexLevel& lv = sm.levels[sm.fixed.level];
    if (!lv.texels) {
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    const __m128 s = _mm_setr_ps(f[0].s, f[1].s, f[2].s, f[3].s);
    const __m128 t = _mm_setr_ps(f[0].t, f[1].t, f[2].t, f[3].t);
    const __m128 su = _mm_mul_ps(s, _mm_set1_ps(lv.scaleU)), tv = _mm_mul_ps(t, _mm_set1_ps(lv.scaleV));
    alignas(16) s32 ua[4], va[4];
    if constexpr (!LINEAR) {
        // u = trunc(s·w·256) >> 8 (texelFixed; INT32_MIN >> 8 needs no 64 bits).
        _mm_store_si128(reinterpret_cast<__m128i*>(ua),
                        addressTexels<CU>(_mm_srai_epi32(_mm_cvttps_epi32(su), 8), lv.wrapMaskU, lv.clampMaxU));
        _mm_store_si128(reinterpret_cast<__m128i*>(va),
                        addressTexels<CV>(_mm_srai_epi32(_mm_cvttps_epi32(tv), 8), lv.wrapMaskV, lv.clampMaxV));
        for (int k = 0; k < 4; ++k) out[k] = lv.texels[size_t(va[k]) * size_t(lv.storedW) + size_t(ua[k])];
    } else {
        const __m128i pu = lv.linearTruncates ? _mm_cvttps_epi32(su) : _mm_cvtps_epi32(su);
        const __m128i pv = lv.linearTruncates ? _mm_cvttps_epi32(tv) : _mm_cvtps_epi32(tv);
        const __m128i low = _mm_set1_epi32(INT32_MIN + 128);
        if (_mm_movemask_epi8(_mm_or_si128(_mm_cmplt_epi32(pu, low), _mm_cmplt_epi32(pv, low)))) {
            for (int k = 0; k < 4; ++k) out[k] = filterT<true, CU, CV>(lv, f[k].s, f[k].t);
            return;
        }
        const __m128i bu = _mm_sub_epi32(pu, _mm_set1_epi32(128)), bv = _mm_sub_epi32(pv, _mm_set1_epi32(128));
        const __m128i fifteen = _mm_set1_epi32(15), one = _mm_set1_epi32(1);
        alignas(16) s32 fu[4], fv[4], ub[4], vb[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(fu), _mm_and_si128(_mm_srai_epi32(bu, 4), fifteen));
        _mm_store_si128(reinterpret_cast<__m128i*>(fv), _mm_and_si128(_mm_srai_epi32(bv, 4), fifteen));
        const __m128i u0 = _mm_srai_epi32(bu, 8), v0 = _mm_srai_epi32(bv, 8);
        _mm_store_si128(reinterpret_cast<__m128i*>(ua), addressTexels<CU>(u0, lv.wrapMaskU, lv.clampMaxU));
        _mm_store_si128(reinterpret_cast<__m128i*>(ub),
                        addressTexels<CU>(_mm_add_epi32(u0, one), lv.wrapMaskU, lv.clampMaxU));
        _mm_store_si128(reinterpret_cast<__m128i*>(va), addressTexels<CV>(v0, lv.wrapMaskV, lv.clampMaxV));
        _mm_store_si128(reinterpret_cast<__m128i*>(vb),
                        addressTexels<CV>(_mm_add_epi32(v0, one), lv.wrapMaskV, lv.clampMaxV));
        for (int k = 0; k < 4; ++k) {
            const u32* rowA = lv.texels + size_t(va[k]) * size_t(lv.storedW);
            const u32* rowB = lv.texels + size_t(vb[k]) * size_t(lv.storedW);
            out[k] = weighQuad(rowA[ua[k]], rowA[ub[k]], rowB[ua[k]], rowB[ub[k]], fu[k], fv[k]);
        }
    }
}
#endif

u32 sampleWithChoice(const Sampler& sm, const LevelChoice& c, float s, float t) {
    const int last = std::max(sm.levelCount - 1, 0);
    const int l = std::min(c.level, last);
    u32 col = filterLevel(sm.levels[l], s, t, c.linear, sm.clampU, sm.clampV);
    if (c.frac && l + 1 <= last) {
        const u32 next = filterLevel(sm.levels[l + 1], s, t, c.linear, sm.clampU, sm.clampV);
        col = mixLevels(col, next, c.frac);
    }
    return col;
}

u32 sampleFixedGeneral(const Sampler& sm, float s, float t, float, float) {
    return sampleWithChoice(sm, sm.fixed, s, t);
}

u32 sampleDynamic(const Sampler& sm, float s, float t, float lod, float w) {
    return sampleWithChoice(sm, chooseLevel(sm.lod, levelOfDetail16(sm.lod, lod, w)), s, t);
}

}  // namespace

u32 sampleNearest(const TexLevel& lv, float s, float t, bool clampU, bool clampV) {
    return filterLevel(lv, s, t, false, clampU, clampV);
}
u32 sampleBilinear(const TexLevel& lv, float s, float t, bool clampU, bool clampV) {
    return filterLevel(lv, s, t, true, clampU, clampV);
}

u32 mixLevels(u32 c, u32 cNext, int frac) {
    return compact((spread(cNext) * u64(frac) + spread(c) * u64(16 - frac)) >> 4);
}

void Sampler::sampleFragments(const geo::Fragment* f, size_t n, u32* out) const {
    size_t i = 0;
    if (fn4)
        for (; i + 4 <= n; i += 4) fn4(*this, f + i, out + i);
    for (; i < n; ++i) out[i] = fn(*this, f[i].s, f[i].t, f[i].lod, f[i].w);
}

void Sampler::finalize() {
    fn4 = nullptr;
    if (fixedChoice && fixed.frac == 0 && fixed.level < std::max(levelCount, 1)) {
        const int k = (fixed.linear ? 4 : 0) | (clampU ? 2 : 0) | (clampV ? 1 : 0);
        static constexpr SampleFn table[8] = {
            &sampleFixedT<false, false, false>, &sampleFixedT<false, false, true>,
            &sampleFixedT<false, true, false>,  &sampleFixedT<false, true, true>,
            &sampleFixedT<true, false, false>,  &sampleFixedT<true, false, true>,
            &sampleFixedT<true, true, false>,   &sampleFixedT<true, true, true>,
        };
        fn = table[k];
#if defined(__SSE2__)
        static constexpr Sample4Fn table4[8] = {
            &sampleFixed4T<false, false, false>, &sampleFixed4T<false, false, true>,
            &sampleFixed4T<false, true, false>,  &sampleFixed4T<false, true, true>,
            &sampleFixed4T<true, false, false>,  &sampleFixed4T<true, false, true>,
            &sampleFixed4T<true, true, false>,   &sampleFixed4T<true, true, true>,
        };
        fn4 = table4[k];
#endif
    } else if (fixedChoice) {
        fn = &sampleFixedGeneral;
    } else {
        fn = &sampleDynamic;
    }
}

}  // namespace ge::soft
