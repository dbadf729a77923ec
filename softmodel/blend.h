// Alpha blending, logic operations, the comparison functions of the alpha/stencil/depth tests and
// the stencil operations, in the software model's exact integer forms (manual §17.4–§17.10;
// ge-reference.md §3.10, §8.3, §8.7). Private to softmodel/; inlined into the shading routines.
#pragma once
#include <algorithm>
#include <cstdlib>

#include "hle/ge_state.h"
#include "hle/types.h"
#include "softmodel/framebuffer.h"

namespace ge::soft {

// ---- Comparisons (ATF/STF/DTF codes, ref §3.10) ----
enum CompareFunc : u8 { CMP_NEVER = 0, CMP_ALWAYS, CMP_EQUAL, CMP_NOTEQUAL, CMP_LESS, CMP_LEQUAL, CMP_GREATER, CMP_GEQUAL };

// "a OP b": alpha test a = fragment alpha, b = reference; depth test a = fragment Z, b = stored Z;
// stencil test a = reference, b = stored value (PPSSPP/OpenGL operand order, ref §8.7 conflict).
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

// ---- Stencil operations (CMD_SOP codes; per-format behaviour of ref §8.7) ----
enum StencilOp : u8 { SOP_KEEP = 0, SOP_ZERO, SOP_REPLACE, SOP_INVERT, SOP_INCR, SOP_DECR };

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

// ---- Blending (ref §3.10 factor table, §8.3 arithmetic) ----
enum BlendEq : u8 { BLEQ_ADD = 0, BLEQ_SUB, BLEQ_REVSUB, BLEQ_MIN, BLEQ_MAX, BLEQ_ABS };

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

// Codes 2–9 (ref §3.10): doubled alphas may reach 510; "255 − 2·A" stops at 0.
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

// ((2·C + 1)·(2·F + 1)) >> 10: the GE's X⊙Y (§8.3).
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

// ---- Logic operations (CMD_LOP, RGB only; ref §3.10). s = fragment, d = frame buffer, both as
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

// ---- The reference renderer's look at the palette's alpha ----
// PPSSPP's software renderer (Rasterizer.cpp CheckClutAlphaFull) decides two state optimizations
// from the palette of a CLUT texture: the entries used (the first 16 for CLUT4, else 256, limited
// by the index mask + 1) are ANDed together, whole entries with their colour bits. `full`: every
// entry has full alpha. `nonZero`: the AND is not zero, taken upstream as "no entry has alpha 0"
// although a colour bit common to all entries is enough. Not checked (checked = false) for
// non-CLUT textures, with an index offset (CLUT start) or per-level palettes.
struct ReferenceClutAlpha {
    bool checked = false, full = false, nonZero = false;
};
inline ReferenceClutAlpha referenceClutAlpha(const GeState& st) {
    ReferenceClutAlpha r;
    const u32 tfmt = st.TPF_format();
    if ((tfmt & 4) == 0 || tfmt > 7) return r;
    const bool sharedClut = tfmt != 4 || st.TMODE_maxlevel() == 0 || (st.TFILTER_min() & 4) == 0 || !st.TMODE_multiclut();
    if (st.CLUT_start() != 0 || !sharedClut) return r;
    u32 count = tfmt == 4 ? 16 : 256;
    if (st.CLUT_mask() != 0xFF) count = std::min<u32>(count, st.CLUT_mask() + 1);
    const u32 cfmt = st.CLUT_format();
    u32 all = 0xFFFFFFFFu;
    for (u32 i = 0; i < count; ++i) all &= cfmt == 3 ? readLE32(st.clut + 4 * i) : u32(readLE16(st.clut + 2 * i));
    r.checked = true;
    r.full = cfmt == 1 ? (all & 0x8000) != 0
           : cfmt == 2 ? (all & 0xF000) == 0xF000
           : cfmt == 3 ? (all & 0xFF000000u) == 0xFF000000u
                       : true;  // 5650: no alpha
    r.nonZero = all != 0;
    return r;
}

// ---- The reference renderer's skipped alpha test ----
// The converse optimization (DetectStateOptimizations, OPTIMIZED_ALPHATEST_OFF_NE/GT): with a CLUT
// texture whose alpha is used (TFUNC RGBA) and every primary colour reaching a fragment at full
// alpha, an alpha test GREATER or NOTEQUAL (after the reference's rewrite of GREATER 0 and LESS 255
// into NOTEQUAL; reference below 255, mask 0xFF) is dropped when the palette has full alpha, or —
// for a reference of 0 — when the ANDed entries are non-zero (`nonZero` above, colour bits
// included). Texels of alpha 0 then pass: a source-alpha blend leaves the pixel, but dithering
// still moves it by the dither value. `vertexAlphaFull`: the draw's colours that reach fragments
// (all vertices with Gouraud shading, the provoking one with flat shading, the second corner of a
// rectangle) have alpha 255 — upstream accumulates this over the draws sharing a state; here it is
// taken per draw.
inline bool referenceSkipsAlphaTest(const GeState& st, bool textured, bool vertexAlphaFull) {
    if (!textured || !vertexAlphaFull || st.isClearMode() || !st.ATE_on() || !st.TFUNC_rgba()) return false;
    if (st.ATEST_mask() != 0xFF) return false;
    u32 func = st.ATEST_func();
    const u32 ref = st.ATEST_ref();
    if ((func == CMP_GREATER && ref == 0) || (func == CMP_LESS && ref == 0xFF)) func = CMP_NOTEQUAL;
    if ((func != CMP_NOTEQUAL && func != CMP_GREATER) || ref >= 0xFF) return false;
    const ReferenceClutAlpha c = referenceClutAlpha(st);
    return c.checked && (c.full || (c.nonZero && ref == 0));
}

// ---- The reference renderer's implicit "alpha != 0" test ----
// PPSSPP's software renderer, which made the reference renders, replaces a disabled (or always
// passing) alpha test by "alpha NOTEQUAL 0" when it blends with A = source alpha, B = 1 − source
// alpha, writes no depth and runs no stencil test, reasoning that such fragments change nothing
// (Rasterizer.cpp DetectStateOptimizations, OPTIMIZED_ALPHATEST_ON). They do change the pixel when
// dithering is on: the dither value is added to the unchanged destination colour. Monster
// Hunter 3rd's HUD gradient (dithered 5650, alpha 0 along its bottom row) shows the reference
// leaving those pixels alone. Conditions as there:
//  - blending on (ABE, equation 0–5; A/B codes 2/3 exclude the "FIXA white + FIXB black" case
//    that turns blending off), not clear mode;
//  - the alpha test off or trivially true (GEQUAL 0, LEQUAL 255 after the mask);
//  - no depth write (ZTE with ZMSK clear) and no effective stencil test (STE, unless the test
//    always passes and writes no stencil bits);
//  - the texture could give alpha 0: not for a CLUT texture whose palette entries (the first 16
//    for CLUT4, else 256, limited by the index mask + 1; not checked with an index offset or
//    per-level palettes) all have full alpha, or whose entries ANDed together are non-zero
//    (upstream ANDs whole entries, colour bits included, as its "cannot contain zero" check).
// Where the vertex alphas are all full and texture alpha is unused, the reference skips this, but
// every fragment then has alpha 255 and the test passes anyway, so it is not checked here.
inline bool referenceDropsZeroAlpha(const GeState& st, bool textured) {
    if (st.isClearMode() || !st.ABE_on() || st.BLEND_eq() > BLEQ_ABS) return false;
    if (st.BLEND_a() != 2 || st.BLEND_b() != 3) return false;
    if (st.ATE_on()) {
        const u32 func = st.ATEST_func(), ref = st.ATEST_ref() & st.ATEST_mask();
        const bool always = func == CMP_ALWAYS || (func == CMP_GEQUAL && ref == 0) || (func == CMP_LEQUAL && ref == 0xFF);
        if (!always) return false;
    }
    if (st.ZTE_on() && !st.ZMSK_nowrite()) return false;
    if (st.STE_on()) {
        // Upstream ComputePixelFuncID: a stencil test that always passes counts only if it can
        // write stencil bits (PMSK2, not 5650) with an operation other than KEEP (codes 6–7 act
        // as KEEP; ZFAIL only matters with a depth test). GEQUAL 0 / LEQUAL 255 (reference
        // masked) pass always too and are dropped when no operation writes.
        const bool is565 = st.framebufFormat() == GE_FORMAT_565;
        auto writes = [&](u32 op) { return !is565 && op != SOP_KEEP && op <= SOP_DECR; };
        const bool depthTested = st.ZTE_on() && st.ZTEST_func() != CMP_ALWAYS;
        const bool opsWrite = writes(st.SOP_zpass()) || (depthTested && writes(st.SOP_zfail()));
        const u32 sfunc = st.STEST_func(), sref = st.STEST_ref() & st.STEST_mask();
        bool stencil;
        if (sfunc == CMP_ALWAYS) {
            stencil = st.PMSK2_alpha() != 0xFF && opsWrite;
        } else {
            const bool always = (sfunc == CMP_GEQUAL && sref == 0) || (sfunc == CMP_LEQUAL && sref == 0xFF);
            stencil = !(always && !opsWrite);
        }
        if (stencil) return false;
    }
    if (textured) {
        const ReferenceClutAlpha c = referenceClutAlpha(st);
        if (c.checked && (c.full || c.nonZero)) return false;
    }
    return true;
}

}  // namespace ge::soft
