// SPDX-License-Identifier: MIT
// Alpha blending, logic operations, the comparison functions of the alpha/stencil/depth tests and
// the stencil operations, in the software model's exact integer forms (manual §17.4–§17.10;
// docs/ge-rules.md §3.10, §8.3, §8.7). Private to softmodel/; inlined into the shading routines.
#pragma once
#include <algorithm>
#include <cstdlib>

#include "hle/ge_state.h"
#include "hle/types.h"
#include "softmodel/framebuffer.h"

namespace ge::soft {

// ---- Comparisons (ATF/STF/DTF codes GeCompareFunc, hle/ge_state.h; ge-rules.md §3.10) ----
// "a OP b": alpha test a = fragment alpha, b = reference; depth test a = fragment Z, b = stored Z;
// stencil test a = reference, b = stored value (PPSSPP/OpenGL operand order, ge-rules.md §8.7 conflict).
inline bool compare(u32 func, int a, int b) {
    switch (func & 7) {
    case CMP_NEVER: return false;
    case CMP_ALWAYS: return true;
    case CMP_EQUAL: return a == b;
    case CMP_NOTEQUAL: return a != b;
    case CMP_LESS: return a < b;
    case CMP_LEQUAL: return a <= b;
    case CMP_GREATER: return a > b;
    default: return a >= b;
    }
}

// ---- Stencil operations (CMD_SOP codes GeStencilOp; per-format behaviour of ge-rules.md §8.7) ----
// New 8-bit stencil value from the stored one `s` (already expanded to 8 bits by the format's
// read rule). REPLACE writes the whole reference, unmasked; codes 6–7 act as KEEP. The result is
// later truncated to the format's stencil bits by the normal alpha conversion.
inline int stencilOp(u32 op, GeBufferFormat fmt, int s, int ref) {
    switch (op & 7) {
    case SOP_ZERO: return 0;
    case SOP_REPLACE: return ref;
    case SOP_INVERT: return ~s & 255;
    case SOP_INCR:
        // 5551: one bit, INCR sets it; 4444: +0x10 (one step of the 4-bit value); 8888: +1.
        if (fmt == GE_FORMAT_5551) return 255;
        if (fmt == GE_FORMAT_4444) return std::min(s + 0x10, 255);
        return std::min(s + 1, 255);
    case SOP_DECR:
        if (fmt == GE_FORMAT_5551) return 0;
        if (fmt == GE_FORMAT_4444) return std::max(s - 0x10, 0);
        return std::max(s - 1, 0);
    default: return s;  // KEEP, 6, 7
    }
}

// ---- Blending (equations GeBlendEq; ge-rules.md §3.10 factor table, §8.3 arithmetic) ----
struct BlendParams {
    u8 eq = 0, a = 0, b = 0;
    int fixA[3] = {}, fixB[3] = {};
};

// Factor codes fall into four kinds: the other side's colour (A: Cd, B: Cs), its inverse, one
// value for all channels derived from As/Ad, and the fixed colour. Shading routines are
// specialised per kind pair and equation (pickBlend), so only the alpha-derived value needs a
// per-pixel decision.
enum BlendFactorKind : u8 { BFK_COLOR = 0, BFK_INVCOLOR, BFK_ALPHA, BFK_FIX };
inline BlendFactorKind blendFactorKind(u32 code) {
    return code == 0 ? BFK_COLOR : code == 1 ? BFK_INVCOLOR : code <= 9 ? BFK_ALPHA : BFK_FIX;
}

// Codes 2–9 (ge-rules.md §3.10): doubled alphas may reach 510; "255 − 2·A" stops at 0.
inline int alphaBlendFactor(u32 code, int as, int ad) {
    switch (code) {
    case 2: return as;
    case 3: return 255 - as;
    case 4: return ad;
    case 5: return 255 - ad;
    case 6: return 2 * as;
    case 7: return std::max(255 - 2 * as, 0);
    case 8: return 2 * ad;
    default: return std::max(255 - 2 * ad, 0);  // 9
    }
}

// ((2·C + 1)·(2·F + 1)) >> 10: the GE's X⊙Y (ge-rules.md §8.3).
inline int blendTerm(int c, int f) { return ((2 * c + 1) * (2 * f + 1)) >> 10; }

struct Factor3 {
    int r, g, b;
};

template <int KIND>
inline Factor3 blendFactorsT(u32 code, const Rgba& other, int as, int ad, const int fix[3]) {
    if constexpr (KIND == BFK_COLOR) {
        return {other.r, other.g, other.b};
    } else if constexpr (KIND == BFK_INVCOLOR) {
        return {255 - other.r, 255 - other.g, 255 - other.b};
    } else if constexpr (KIND == BFK_ALPHA) {
        const int v = alphaBlendFactor(code, as, ad);
        return {v, v, v};
    } else {
        return {fix[0], fix[1], fix[2]};
    }
}

template <int EQ>
inline int blendChannel(int cs, int fa, int cd, int fb) {
    const int ts = blendTerm(cs, fa), td = blendTerm(cd, fb);
    if constexpr (EQ == BLEQ_ADD) return ts + td;
    else if constexpr (EQ == BLEQ_SUB) return ts > td ? ts - td : 0;
    else return td > ts ? td - ts : 0;
}

// Blends src into dst (both 0–255 per channel). The result is NOT clamped above 255 (it goes to
// dithering first, manual §17.7); SUBTRACT/REVERSE_SUBTRACT results below 0 become 0.
template <int EQ, int KA, int KB>
inline void blendT(const BlendParams& p, Rgba& src, const Rgba& dst) {
    if constexpr (EQ == BLEQ_MIN) {
        src.r = std::min(src.r, dst.r), src.g = std::min(src.g, dst.g), src.b = std::min(src.b, dst.b);
    } else if constexpr (EQ == BLEQ_MAX) {
        src.r = std::max(src.r, dst.r), src.g = std::max(src.g, dst.g), src.b = std::max(src.b, dst.b);
    } else if constexpr (EQ == BLEQ_ABS) {
        src.r = std::abs(src.r - dst.r), src.g = std::abs(src.g - dst.g), src.b = std::abs(src.b - dst.b);
    } else {
        const Factor3 fa = blendFactorsT<KA>(p.a, dst, src.a, dst.a, p.fixA);  // A: code 0/1 use Cd
        const Factor3 fb = blendFactorsT<KB>(p.b, src, src.a, dst.a, p.fixB);  // B: code 0/1 use Cs
        src.r = blendChannel<EQ>(src.r, fa.r, dst.r, fb.r);
        src.g = blendChannel<EQ>(src.g, fa.g, dst.g, fb.g);
        src.b = blendChannel<EQ>(src.b, fa.b, dst.b, fb.b);
    }
}

using BlendFn = void (*)(const BlendParams&, Rgba& src, const Rgba& dst);
// The routine for an equation (0–5) and factor codes; blend.cpp.
BlendFn pickBlend(const BlendParams& p);
inline void blendColor(const BlendParams& p, Rgba& src, const Rgba& dst) { pickBlend(p)(p, src, dst); }

// ---- Logic operations (CMD_LOP, RGB only; ge-rules.md §3.10). s = fragment, d = frame buffer, both as
// packed 24-bit RGB. On 16-bit formats operating on the bit-replicated 8-bit channels and then
// truncating equals operating on the stored bits, since every op is bitwise.
inline u32 logicOp(u32 op, u32 s, u32 d) {
    u32 r;
    switch (op & 15) {
    case 0: r = 0; break;            // CLEAR
    case 1: r = s & d; break;        // AND
    case 2: r = s & ~d; break;       // AND_REVERSE
    case 3: r = s; break;            // COPY
    case 4: r = ~s & d; break;       // AND_INVERTED
    case 5: r = d; break;            // NOOP
    case 6: r = s ^ d; break;        // XOR
    case 7: r = s | d; break;        // OR
    case 8: r = ~(s | d); break;     // NOR
    case 9: r = ~(s ^ d); break;     // EQUIV
    case 10: r = ~d; break;          // INVERT
    case 11: r = s | ~d; break;      // OR_REVERSE
    case 12: r = ~s; break;          // COPY_INVERTED
    case 13: r = ~s | d; break;      // OR_INVERTED
    case 14: r = ~(s & d); break;    // NAND
    default: r = 0xFFFFFF; break;    // SET
    }
    return r & 0xFFFFFF;
}

inline int clamp255(int v) { return v < 0 ? 0 : (v > 255 ? 255 : v); }

}  // namespace ge::soft
