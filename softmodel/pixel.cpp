// SPDX-License-Identifier: MIT
// The software model's per-pixel pipeline (manual §13–§19; docs/ge-rules.md §8.3, §8.4, §8.7–§8.10).
//
// buildPixelState resolves the GE state of one draw into PixelState::Impl (decoded textures,
// masked references, masks converted to the frame-buffer format, …) and picks a shading routine
// specialised on the frame-buffer format and the hot switches (texturing, blending, depth test,
// and whether any of the rarer per-pixel stages is on), so shadeFragments runs integer code with
// no per-pixel decisions about which stages exist. Stage order is ge-rules.md §8.4 exactly.
#include <algorithm>
#include <array>
#include <utility>

#include "geometry/reference_rules.h"
#include "softmodel/pixel_impl.h"

namespace ge::soft {

namespace {

using Impl = PixelState::Impl;
using ShadeFn = Impl::ShadeFn;

inline u32 packRgb(int r, int g, int b) { return u32(r) | u32(g) << 8 | u32(b) << 16; }

// A stencil-only write (stencil test or depth test failed, ge-rules.md §8.4 steps 6–7): the new stencil value
// lands in the alpha bits that PMSK2 leaves writable; colour is untouched.
template <GeBufferFormat F>
inline void writeStencilOnly(const Impl& im, u8* p, u32 old, int stencil) {
    using FB = Fb<F>;
    if constexpr (FB::kAlphaBits == 0) {
        return;  // 5650 has no stencil (ge-rules.md §8.7)
    } else {
        const u32 v = FB::encode(0, 0, 0, stencil);
        FB::store(p, (old & ~im.stencilWriteBits) | (v & im.stencilWriteBits));
    }
}

// Normal drawing. TEX: texture function on; BLEND: alpha blending on; ZTEST: depth test on;
// FULL: at least one of depth range, alpha test, fog, colour test, stencil test, logic op.
template <GeBufferFormat F, bool TEX, bool BLEND, bool ZTEST, bool FULL>
void shadeNormal(const PixelState& ps, const Impl& im, const geo::Fragment* frags, size_t n) {
    using FB = Fb<F>;
    // Texture colours are sampled for a run of fragments first (Sampler::sampleFragments forms four
    // pixels' texel coordinates at once), then each fragment goes through the stages below.
    // Sampling reads only the fragment and the decoded texture, so it may run ahead, for the
    // fragments the checks below drop too.
    constexpr size_t kRun = 64;
    u32 texel[TEX ? kRun : 1];
    for (size_t i = 0; i < n; ++i) {
        if constexpr (TEX) {
            if (i % kRun == 0) im.sampler.sampleFragments(frags + i, std::min(kRun, n - i), texel);
        }
        const geo::Fragment& f = frags[i];
        if (f.x < 0 || f.y < 0) continue;
        const u64 off = u64(f.y) * ps.fbStride + u64(f.x);
        if (off >= im.fbPixels) continue;  // outside VRAM: dropped
        u8* zp = nullptr;
        if constexpr (ZTEST) {
            const u64 zoff = u64(f.y) * ps.zbStride + u64(f.x);
            if (zoff >= im.zbPixels) continue;
            zp = ps.zb + zoff * 2;
        }

        // 1. Texture function (with doubling) + secondary colour, clamped.
        Rgba c{f.color[0], f.color[1], f.color[2], f.color[3]};
        if constexpr (TEX) im.texFunc(c, texel[i % kRun], im.texEnv);
        addSecondaryAndClamp(c, f.secondary);

        if constexpr (FULL) {
            // 2. Depth range (never in through mode). 3. Alpha test. 4. Fog. 5. Colour test.
            if (im.depthRange && (f.z < im.minZ || f.z > im.maxZ)) continue;
            if (im.alphaTest && !compare(im.alphaFunc, c.a & im.alphaMask, im.alphaRef)) continue;
            if (im.fog) applyFog(c, im.fogColor, f.fog);
            if (im.colorTest) {
                const bool equal = (packRgb(c.r, c.g, c.b) & im.colorMask) == im.colorRef;
                // CTEST: 0 NEVER, 1 ALWAYS, 2 EQUAL, 3 NOTEQUAL.
                const bool pass = im.colorFunc == 1 || (im.colorFunc == 2 && equal) || (im.colorFunc == 3 && !equal);
                if (!pass) continue;
            }
        }

        u8* p = ps.fb + off * FB::kBytes;
        const u32 old = FB::load(p);

        // 6. Stencil test (operands: reference OP stored, both masked).
        int stencil = 0;
        if constexpr (FULL) {
            if (im.stencilTest) {
                stencil = FB::stencil(old);
                if (!compare(im.stencilFunc, im.stencilRefMasked, stencil & im.stencilMask)) {
                    writeStencilOnly<F>(im, p, old, stencilOp(im.sfail, F, stencil, im.stencilRef));
                    continue;
                }
            }
        }
        // 7. Depth test; 8. ZPASS and the depth write.
        if constexpr (ZTEST) {
            if (!compare(im.depthFunc, f.z, readLE16(zp))) {
                if (FULL && im.stencilTest)
                    writeStencilOnly<F>(im, p, old, stencilOp(im.zfail, F, stencil, im.stencilRef));
                continue;
            }
            if (im.depthWrite) writeLE16(zp, f.z);
        }
        if (FULL && im.stencilTest) stencil = stencilOp(im.zpass, F, stencil, im.stencilRef);

        // 9. Blending (unclamped), dither, clamp.
        if constexpr (BLEND) im.blendFn(im.blendParams, c, FB::decode(old));
        const int dv = im.dither[f.y & 3][f.x & 3];
        int r = clamp255(c.r + dv), g = clamp255(c.g + dv), b = clamp255(c.b + dv);

        // 11. Logic op on RGB (10, the alpha byte = stencil, is the `stencil` argument below).
        if constexpr (FULL) {
            if (im.logicOpOn) {
                const Rgba d = FB::decode(old);
                const u32 v = logicOp(im.logicOp, packRgb(r, g, b), packRgb(d.r, d.g, d.b));
                r = int(v & 255);
                g = int((v >> 8) & 255);
                b = int(v >> 16);
            }
        }
        // 12. Conversion by truncation, write masks, write.
        const u32 nv = FB::encode(r, g, b, stencil);
        FB::store(p, (nv & ~im.keepMask) | (old & im.keepMask));
    }
}

// Clear mode (ge-rules.md §8.4 last paragraph): depth range (outside through mode), dither, PMSK; colour,
// alpha (= stencil, the vertex alpha) and depth written as CEN/AEN/ZEN say (keepMask holds the
// CEN/AEN part).
template <GeBufferFormat F, bool ZEN>
void shadeClear(const PixelState& ps, const Impl& im, const geo::Fragment* frags, size_t n) {
    using FB = Fb<F>;
    for (size_t i = 0; i < n; ++i) {
        const geo::Fragment& f = frags[i];
        if (f.x < 0 || f.y < 0) continue;
        const u64 off = u64(f.y) * ps.fbStride + u64(f.x);
        if (off >= im.fbPixels) continue;
        if (im.depthRange && (f.z < im.minZ || f.z > im.maxZ)) continue;
        if constexpr (ZEN) {
            const u64 zoff = u64(f.y) * ps.zbStride + u64(f.x);
            if (zoff < im.zbPixels) writeLE16(ps.zb + zoff * 2, f.z);
        }
        const int dv = im.dither[f.y & 3][f.x & 3];
        const u32 nv = FB::encode(clamp255(f.color[0] + dv), clamp255(f.color[1] + dv), clamp255(f.color[2] + dv), f.color[3]);
        u8* p = ps.fb + off * FB::kBytes;
        const u32 old = FB::load(p);
        FB::store(p, (nv & ~im.keepMask) | (old & im.keepMask));
    }
}

template <GeBufferFormat F, size_t... K>
constexpr std::array<ShadeFn, sizeof...(K)> normalTable(std::index_sequence<K...>) {
    return {&shadeNormal<F, (K & 8) != 0, (K & 4) != 0, (K & 2) != 0, (K & 1) != 0>...};
}

template <GeBufferFormat F>
ShadeFn pickShade(const Impl& im) {
    if (im.clearMode) return im.clearDepth ? &shadeClear<F, true> : &shadeClear<F, false>;
    static constexpr std::array<ShadeFn, 16> table = normalTable<F>(std::make_index_sequence<16>());
    const bool full = im.depthRange || im.alphaTest || im.fog || im.colorTest || im.stencilTest || im.logicOpOn;
    return table[(im.texture ? 8 : 0) | (im.blend ? 4 : 0) | (im.depthTest ? 2 : 0) | (full ? 1 : 0)];
}

void setupTexture(Impl& im, const GeState& st, Memory& mem, TextureCache& cache, const geo::AccuracyProfile& acc) {
    Sampler& sm = im.sampler;
    LodParams& lp = sm.lod;
    const u32 mode = st.TLEVEL_mode();
    lp.mode = mode == 3 ? 1 : int(mode);
    lp.bias16 = st.TLEVEL_bias();
    lp.slope = st.TSLOPE_value();
    const u32 minf = st.TFILTER_min();
    lp.maxLevel = (minf & 4) ? int(st.TMODE_maxlevel()) : 0;  // MXL only counts with mipmapping
    lp.mipLinear = (minf & 2) != 0;
    lp.minLinear = (minf & 1) != 0;
    lp.magLinear = (st.TFILTER_mag() & 1) != 0;
    sm.clampU = st.TWRAP_uclamp();
    sm.clampV = st.TWRAP_vclamp();

    // Constant level mode: one choice for the whole draw. Without mipmaps and with the same
    // filter both ways the detail value cannot change anything either.
    if (lp.mode == 1) {
        sm.fixedChoice = true;
        sm.fixed = chooseLevel(lp, levelOfDetail16(lp, 0, 0));
    } else if (lp.maxLevel == 0 && lp.minLinear == lp.magLinear) {
        sm.fixedChoice = true;
        sm.fixed = LevelChoice{0, 0, lp.minLinear};
    }
    const int first = sm.fixedChoice ? sm.fixed.level : 0;
    const int last = highestLevelNeeded(lp, sm.fixedChoice, sm.fixed);
    for (int l = first; l <= last; ++l) {
        auto data = cache.level(st, mem, l);
        sm.levels[l].texels = data->texels.data();
        sm.levels[l].setSize(st.TSIZE_wlog(l), st.TSIZE_hlog(l), int(data->width), int(data->height));
        sm.levels[l].linearTruncates = acc.pspBilinearTruncation;
        im.levelData[l] = std::move(data);
    }
    sm.levelCount = last + 1;
    sm.finalize();

    im.texFunc = pickTextureFunction(st.TFUNC_func(), st.TFUNC_rgba(), st.TFUNC_double());
    const u32 tec = st.TEC_rgb();
    im.texEnv[0] = int(tec & 255);
    im.texEnv[1] = int((tec >> 8) & 255);
    im.texEnv[2] = int((tec >> 16) & 255);
}

// Frame/depth buffer pointer and the pixels reachable from it inside VRAM.
u8* bufferPointer(Memory& mem, u32 addr, u32 bpp, u32& pixels) {
    const u32 avail = mem.validSize(addr, Memory::kVramSize);
    pixels = avail / bpp;
    return pixels ? mem.ptr(addr, pixels * bpp) : nullptr;
}

int rowsReachable(u32 pixels, u32 stride) {
    if (pixels == 0) return 0;
    if (stride == 0) return 1024;
    return int(std::min<u64>((u64(pixels) + stride - 1) / stride, 1024));
}

}  // namespace

PixelState buildPixelState(const GeState& st, Memory& mem, TextureCache& cache, const geo::AccuracyProfile& acc,
                           bool textureEnabled, bool vertexAlphaFull) {
    PixelState ps;
    auto im = std::make_shared<Impl>();
    const GeBufferFormat fmt = st.framebufFormat();
    const u32 bpp = fmt == GE_FORMAT_8888 ? 4 : 2;

    ps.fbFormat = fmt;
    ps.fbStride = st.framebufStride();
    const u32 fbAddr = st.framebufAddr();
    ps.fb = bufferPointer(mem, fbAddr, bpp, im->fbPixels);
    ps.fbMaxY = rowsReachable(im->fbPixels, ps.fbStride);
    ps.zbStride = st.depthbufStride();
    const u32 zbAddr = st.depthbufAddr();
    ps.zb = bufferPointer(mem, zbAddr, 2, im->zbPixels);
    ps.zbMaxY = rowsReachable(im->zbPixels, ps.zbStride);

    im->through = st.isThrough();
    im->clearMode = st.isClearMode();
    const bool clear = im->clearMode;
    im->clearColor = st.CMODE_color();
    im->clearAlpha = st.CMODE_alpha();
    im->clearDepth = st.CMODE_depth();

    // Texturing: never in clear mode (manual §19.6).
    im->texture = textureEnabled && !clear;
    if (im->texture) setupTexture(*im, st, mem, cache, acc);

    // Fog: off in through and clear mode (ge-rules.md §3.9, §8.4).
    im->fog = st.FGE_on() && !im->through && !clear;
    const u32 fc = st.FC_rgb();
    im->fogColor[0] = int(fc & 255);
    im->fogColor[1] = int((fc >> 8) & 255);
    im->fogColor[2] = int((fc >> 16) & 255);

    // Depth range: skipped in through mode, applied even in clear mode (ge-rules.md §8.4 step 2).
    im->minZ = int(st.MINZ_value());
    im->maxZ = int(st.MAXZ_value());
    im->depthRange = !im->through && (im->minZ > 0 || im->maxZ < 65535);

    // Alpha test.
    im->alphaFunc = u8(st.ATEST_func());
    im->alphaMask = int(st.ATEST_mask());
    im->alphaRef = int(st.ATEST_ref()) & im->alphaMask;
    im->alphaTest = st.ATE_on() && !clear && im->alphaFunc != CMP_ALWAYS;
    // The reference renderer's skipped alpha test for CLUT textures (geometry/reference_rules.h,
    // which the GL translator's shader keys apply too).
    if (acc.clutSkipsAlphaTest && im->alphaTest && geo::referenceSkipsAlphaTest(st, im->texture, vertexAlphaFull))
        im->alphaTest = false;
    // The reference renderer's implicit "alpha != 0" test for source-alpha blending (ditto).
    if (acc.implicitAlphaNonZeroTest && !clear && geo::referenceDropsZeroAlpha(st, im->texture)) {
        im->alphaTest = true;
        im->alphaFunc = CMP_NOTEQUAL;
        im->alphaMask = 0xFF;
        im->alphaRef = 0;
    }

    // Colour test.
    im->colorFunc = u8(st.CTEST_func());
    im->colorMask = st.CMSK_rgb();
    im->colorRef = st.CREF_rgb() & im->colorMask;
    im->colorTest = st.CTE_on() && !clear && im->colorFunc != 1;

    // Stencil test and operations.
    im->stencilTest = st.STE_on() && !clear;
    im->stencilFunc = u8(st.STEST_func());
    im->stencilMask = int(st.STEST_mask());
    im->stencilRef = int(st.STEST_ref());
    im->stencilRefMasked = im->stencilRef & im->stencilMask;
    im->sfail = u8(st.SOP_sfail());
    im->zfail = u8(st.SOP_zfail());
    im->zpass = u8(st.SOP_zpass());

    // Depth test and write (ZTE = 0: no test and no write, manual §17.6).
    im->depthTest = st.ZTE_on() && !clear;
    im->depthFunc = u8(st.ZTEST_func());
    im->depthWrite = im->depthTest && !st.ZMSK_nowrite();
    im->usesDepthBuffer = clear ? im->clearDepth : im->depthTest;

    // Blending (equations 6–7: no blending, ge-rules.md §3.10).
    im->blend = st.ABE_on() && !clear && st.BLEND_eq() <= BLEQ_ABS;
    im->blendParams.eq = u8(st.BLEND_eq());
    im->blendParams.a = u8(st.BLEND_a());
    im->blendParams.b = u8(st.BLEND_b());
    const u32 fixa = st.FIXA_rgb(), fixb = st.FIXB_rgb();
    for (int i = 0; i < 3; ++i) {
        im->blendParams.fixA[i] = int((fixa >> (8 * i)) & 255);
        im->blendParams.fixB[i] = int((fixb >> (8 * i)) & 255);
    }
    im->blendFn = pickBlend(im->blendParams);

    // Dither matrix (DTE), in clear mode too.
    if (st.DTE_on())
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) im->dither[y][x] = st.ditherValue(x, y);

    // Logic op (RGB only; COPY is the identity).
    im->logicOp = u8(st.LOP_op());
    im->logicOpOn = st.LOE_on() && !clear && im->logicOp != 3;

    // Write masks in the frame-buffer format (ge-rules.md §8.7, §8.8): PMSK converted by truncation.
    const u32 pm1 = st.PMSK1_rgb();
    const u32 pmask = fbEncode(fmt, int(pm1 & 255), int((pm1 >> 8) & 255), int((pm1 >> 16) & 255), int(st.PMSK2_alpha()));
    const u32 alphaBits = fbAlphaBits(fmt), rgbBits = fbRgbBits(fmt);
    u32 keep = pmask;
    if (clear) {
        if (!im->clearColor) keep |= rgbBits;
        if (!im->clearAlpha) keep |= alphaBits;
    } else if (!im->stencilTest) {
        keep |= alphaBits;  // no stencil test: alpha/stencil bits never change (ge-rules.md §8.7)
    }
    im->keepMask = keep;
    im->stencilWriteBits = alphaBits & ~pmask;

    switch (fmt) {
    case GE_FORMAT_565: im->shade = pickShade<GE_FORMAT_565>(*im); break;
    case GE_FORMAT_5551: im->shade = pickShade<GE_FORMAT_5551>(*im); break;
    case GE_FORMAT_4444: im->shade = pickShade<GE_FORMAT_4444>(*im); break;
    default: im->shade = pickShade<GE_FORMAT_8888>(*im); break;
    }

    // This draw writes VRAM inside the scissor rectangle: decoded textures read from there must
    // be re-checked before later draws use them (render-to-texture). Conservative byte range.
    const u32 x1 = st.SCISSOR1_x(), y1 = st.SCISSOR1_y(), x2 = st.SCISSOR2_x(), y2 = st.SCISSOR2_y();
    if (x2 >= x1 && y2 >= y1) {
        auto written = [&](u32 base, u32 stride, u32 size) {
            const u64 b = u64(y1) * stride + x1, e = u64(y2) * stride + x2 + 1;
            invalidateTextureCache(cache, base + u32(b * size), u32(std::min<u64>((e - b) * size, Memory::kVramSize)));
        };
        if (ps.fb) written(fbAddr, ps.fbStride, bpp);
        if (ps.zb && (im->clearMode ? im->clearDepth : im->depthWrite)) written(zbAddr, ps.zbStride, 2);
    }

    ps.impl = std::move(im);
    return ps;
}

void shadeFragments(const PixelState& ps, const geo::Fragment* frags, size_t n) {
    if (!ps.impl || !ps.impl->shade || !ps.fb || !frags) return;
    ps.impl->shade(ps, *ps.impl, frags, n);
}

}  // namespace ge::soft
