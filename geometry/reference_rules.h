// SPDX-License-Identifier: MIT
// The reference renderer's draw-level state optimizations that change pixels, as rules on GeState
// that both backends apply: the software model when it builds a draw's pixel state
// (softmodel/pixel.cpp buildPixelState), the GL translator when it makes the draw's shader key
// (shadergen/keys_from_state.cpp). One copy, so the two cannot drift apart. Header only.
#pragma once
#include <algorithm>

#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge::geo {

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

}  // namespace ge::geo
