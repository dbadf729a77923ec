// SPDX-License-Identifier: MIT
// State → keys, fixed-function decision and uniform values (see keys_from_state.h).
#include "shadergen/keys_from_state.h"
#include "geometry/reference_rules.h"

#include <xxhash.h>

namespace ge::shadergen {

u64 hashBytes(const void* p, size_t n) { return XXH3_64bits(p, n); }

DrawFlags DrawFlags::fromState(const GeState& st, const geo::AccuracyProfile& acc) {
    DrawFlags f;
    f.accuracy = acc;
    f.through = st.isThrough();
    f.texture = st.TME_on();
    f.fog = st.FGE_on();
    f.dither = st.DTE_on();
    f.gouraud = st.SHADE_gouraud();
    return f;
}

void formatChannelBits(u8 fbFormat, u8 out[4]) {
    switch (fbFormat & 3) {
        case GE_FORMAT_565: out[0] = 0xF8, out[1] = 0xFC, out[2] = 0xF8, out[3] = 0x00; break;
        case GE_FORMAT_5551: out[0] = 0xF8, out[1] = 0xF8, out[2] = 0xF8, out[3] = 0x80; break;
        case GE_FORMAT_4444: out[0] = out[1] = out[2] = out[3] = 0xF0; break;
        default: out[0] = out[1] = out[2] = out[3] = 0xFF; break;
    }
}

void canonicalize(VsKey& k) {
    k.flatShade = k.flatShade ? 1 : 0;
    k.reserved[0] = k.reserved[1] = k.reserved[2] = 0;
}

void canonicalize(FsKey& k) {
    for (u8& r : k.reserved) r = 0;
    if (k.fbFormat == GE_FORMAT_565) {
        // 5650 has no alpha/stencil bits to write or protect (docs/ge-rules.md §8.7).
        k.clearAlpha = 0;
        k.writeAlpha = 0;
        k.maskAlpha = 0;
    }
    if (k.clearMode) {
        // Clear mode: no texturing, fog, tests, blending or logic op (ge-rules.md §8.4).
        k.tex = 0;
        k.fog = 0;
        k.alphaTest = k.colorTest = 0;
        k.stencilTest = k.sopFail = k.sopZFail = k.sopZPass = 0;
        k.depthTest = 0;
        k.blend = k.blendA = k.blendB = 0;
        k.logicOp = 0;
        k.writeAlpha = k.clearAlpha;
        k.depthWrite = k.clearDepth;
    } else {
        k.clearColor = k.clearAlpha = k.clearDepth = 0;
    }
    if (!k.tex) k.texTarget = 0;
    if (!k.texTarget) k.texFormat = 0;
    if (!k.tex) {
        k.texFunc = k.texAlpha = k.texDouble = 0;
        k.texMagLinear = k.texMinLinear = k.texMip = k.texLodMode = 0;
        k.texClampU = k.texClampV = 0;
        k.texLinearTrunc = 0;
    } else {
        if (k.texFunc > 4) k.texFunc = 4;  // 5–7 behave as ADD (ge-rules.md §3.8)
        // The level of detail only matters when it can change the filter or the level.
        if (k.texMip == 0 && k.texMinLinear == k.texMagLinear) k.texLodMode = 0;
        if (!k.texMinLinear && !k.texMagLinear) k.texLinearTrunc = 0;  // no bilinear sample
    }
    if (!k.stencilTest) k.sopFail = k.sopZFail = k.sopZPass = 0;
    if (!k.blend) k.blendA = k.blendB = 0;
    if (k.blend >= 4) k.blendA = k.blendB = 0;  // MIN, MAX, ABS ignore the factors (ge-rules.md §3.10)
    if (k.dstRead == DstRead::None) {
        k.maskRgb = k.maskAlpha = 0;
        k.depthRead = DepthRead::None;
    }
    // The depth test moves into the shader only for stencil ops that depend on it.
    if (!(k.stencilTest && k.depthTest)) k.depthRead = DepthRead::None;
}

PipelineKeys keysFromState(const GeState& st, const DrawFlags& flags, const HostCaps& caps, bool baseline) {
    PipelineKeys out;
    FsKey& k = out.fs;
    FixedFunction& ff = out.ff;
    const bool clear = st.isClearMode();
    const u8 fmt = u8(st.framebufFormat());
    u8 bits[4];
    formatChannelBits(fmt, bits);

    out.vs.flatShade = flags.gouraud ? 0 : 1;
    k.flatShade = out.vs.flatShade;
    k.fbFormat = fmt;
    k.dither = flags.dither ? 1 : 0;
    k.depthRange = flags.through ? 0 : 1;  // ge-rules.md §8.4 step 2: skipped in through mode only

    // PMSK1/PMSK2 in the frame-buffer format (ge-rules.md §8.8): a 1 bit protects the stored bit.
    const u32 pm1 = st.PMSK1_rgb();
    const u8 keep[4] = {u8(pm1 & bits[0]), u8((pm1 >> 8) & bits[1]), u8((pm1 >> 16) & bits[2]),
                        u8(st.PMSK2_alpha() & bits[3])};

    bool writeRgb, writeA;
    if (clear) {
        k.clearMode = 1;
        k.clearColor = st.CMODE_color() ? 1 : 0;
        k.clearAlpha = (st.CMODE_alpha() && fmt != GE_FORMAT_565) ? 1 : 0;
        k.clearDepth = st.CMODE_depth() ? 1 : 0;
        writeRgb = k.clearColor;
        writeA = k.clearAlpha;
        ff.depthTest = k.clearDepth;  // GL needs the test enabled to write depth
        ff.depthFunc = 1;             // ALWAYS
        ff.depthMask = k.clearDepth;
        ff.usesDepth = k.clearDepth;
        k.depthWrite = k.clearDepth;
    } else {
        k.tex = flags.texture ? 1 : 0;
        if (k.tex) {
            k.texFunc = u8(st.TFUNC_func());
            k.texAlpha = st.TFUNC_rgba() ? 1 : 0;
            k.texDouble = st.TFUNC_double() ? 1 : 0;
            k.texMagLinear = st.TFILTER_mag() & 1;
            const u32 minf = st.TFILTER_min();
            k.texMinLinear = minf & 1;
            if ((minf & 4) && st.TMODE_maxlevel() > 0) k.texMip = (minf & 2) ? 2 : 1;
            u32 lm = st.TLEVEL_mode();
            k.texLodMode = u8(lm == 3 ? 1 : lm);
            k.texClampU = st.TWRAP_uclamp() ? 1 : 0;
            k.texClampV = st.TWRAP_vclamp() ? 1 : 0;
            k.texLinearTrunc = flags.accuracy.pspBilinearTruncation ? 1 : 0;
        }
        k.fog = (flags.fog && !flags.through) ? 1 : 0;  // fog is off in through mode (ge-rules.md §3.9)
        const geo::AccuracyProfile& acc = flags.accuracy;
        if (st.ATE_on() && st.ATEST_func() != 1 &&
            !(acc.clutSkipsAlphaTest && geo::referenceSkipsAlphaTest(st, flags.texture, flags.vertexAlphaFull)))
            k.alphaTest = u8(st.ATEST_func() + 1);
        // The reference's implicit alpha != 0 test (geometry/reference_rules.h): code 9.
        if (acc.implicitAlphaNonZeroTest && geo::referenceDropsZeroAlpha(st, flags.texture)) k.alphaTest = 9;
        if (st.CTE_on() && st.CTEST_func() != 1) k.colorTest = u8(st.CTEST_func() + 1);
        if (st.STE_on() && fmt != GE_FORMAT_565) {
            // 5650 has no stencil bits: the stored value reads as 0 and is never written, but
            // the test itself still runs against 0 (ge-rules.md §8.7).
            k.stencilTest = u8(st.STEST_func() + 1);
            k.sopFail = u8(st.SOP_sfail() > 5 ? 0 : st.SOP_sfail());
            k.sopZFail = u8(st.SOP_zfail() > 5 ? 0 : st.SOP_zfail());
            k.sopZPass = u8(st.SOP_zpass() > 5 ? 0 : st.SOP_zpass());
        } else if (st.STE_on()) {
            k.stencilTest = u8(st.STEST_func() + 1);
        }
        if (st.ZTE_on()) {
            k.depthTest = u8(st.ZTEST_func() + 1);
            k.depthWrite = st.ZMSK_nowrite() ? 0 : 1;
        }
        if (st.ABE_on() && st.BLEND_eq() <= 5) {
            k.blend = u8(st.BLEND_eq() + 1);
            k.blendA = u8(st.BLEND_a());
            k.blendB = u8(st.BLEND_b());
        }
        if (st.LOE_on() && st.LOP_op() != 3) k.logicOp = u8(st.LOP_op() + 1);
        writeRgb = true;
        writeA = k.stencilTest && fmt != GE_FORMAT_565;
    }
    k.writeAlpha = writeA ? 1 : 0;

    // Which channels GL's colour mask can handle: fully protected or fully written.
    bool partialRgb = false, partialA = false;
    for (int c = 0; c < 3; ++c)
        if (writeRgb && keep[c] != 0 && keep[c] != bits[c]) partialRgb = true;
    if (writeA && keep[3] != 0 && keep[3] != bits[3]) partialA = true;
    for (int c = 0; c < 3; ++c) ff.colorMask[c] = writeRgb && keep[c] != bits[c];
    ff.colorMask[3] = writeA && keep[3] != bits[3];

    const bool needDst = k.stencilTest || k.blend || k.logicOp || partialRgb || partialA;
    if (needDst) {
        k.dstRead = (!baseline && caps.fbFetch) ? DstRead::FbFetch : DstRead::Texture;
        // With a destination read the shader merges PMSK itself (a zero mask is a no-op).
        k.maskRgb = 1;
        k.maskAlpha = fmt != GE_FORMAT_565 ? 1 : 0;
    }

    if (!clear) {
        ff.usesDepth = k.depthTest != 0;
        if (needDst && k.stencilTest && k.depthTest) {
            // The stencil ZFAIL/ZPASS ops need the depth result inside the shader: it reads the
            // stored depth and writes back either the new or the old value (GL test ALWAYS).
            k.depthRead = (!baseline && caps.depthFetch) ? DepthRead::Fetch : DepthRead::Texture;
            ff.depthTest = true;
            ff.depthFunc = 1;
            ff.depthMask = true;
        } else if (k.depthTest) {
            ff.depthTest = true;
            ff.depthFunc = u8(k.depthTest - 1);
            ff.depthMask = k.depthWrite;
        }
    }

    canonicalize(out.vs);
    canonicalize(k);
    return out;
}

static void rgbOf(u32 v, s32 out[3]) {
    out[0] = s32(v & 0xFF);
    out[1] = s32((v >> 8) & 0xFF);
    out[2] = s32((v >> 16) & 0xFF);
}

void uniformsFromState(const GeState& st, FsUniforms& u) {
    rgbOf(st.TEC_rgb(), u.texEnv);
    rgbOf(st.FC_rgb(), u.fogColor);
    u.alphaRef = s32(st.ATEST_ref());
    u.alphaMask = s32(st.ATEST_mask());
    rgbOf(st.CREF_rgb(), u.colorRef);
    rgbOf(st.CMSK_rgb(), u.colorMask);
    u.stencilRef = s32(st.STEST_ref());
    u.stencilMask = s32(st.STEST_mask());
    rgbOf(st.FIXA_rgb(), u.fixA);
    rgbOf(st.FIXB_rgb(), u.fixB);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) u.dither[y * 4 + x] = st.ditherValue(x, y);
    u8 bits[4];
    formatChannelBits(u8(st.framebufFormat()), bits);
    const u32 pm1 = st.PMSK1_rgb();
    u.keepMask[0] = s32(pm1 & bits[0]);
    u.keepMask[1] = s32((pm1 >> 8) & bits[1]);
    u.keepMask[2] = s32((pm1 >> 16) & bits[2]);
    u.keepMask[3] = s32(st.PMSK2_alpha() & bits[3]);
    u.minZ = s32(st.MINZ_value());
    u.maxZ = s32(st.MAXZ_value());
    u.texMaxLevel = s32(st.TMODE_maxlevel());
    u.texLodBias = st.TLEVEL_bias();
    u.texSlope = st.TSLOPE_value();
}

}  // namespace ge::shadergen
