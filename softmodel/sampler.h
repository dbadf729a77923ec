// SPDX-License-Identifier: MIT
// Texture sampling for the software model: level-of-detail selection, nearest and bilinear
// filtering, repeat/clamp, mipmap blending (manual §13.10–§13.12; docs/ge-rules.md §6.6, §8.10).
//
// Levels are sampled from textures already decoded to RGBA8888 (R in bits 7..0, CLUT applied) by
// the texture cache; sampling itself is integer except the first multiply of the coordinate.
// A Sampler is built once per draw and is read-only afterwards (shared by shading threads).
#pragma once
#include <memory>
#include <vector>

#include "geometry/fragment.h"
#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge::soft {

// One decoded level as the sampler sees it.
struct TexLevel {
    const u32* texels = nullptr;  // storedW × storedH texels, row-major; null → samples read 0
    int storedW = 1, storedH = 1;
    // Coordinate scale: the level's nominal size 1 << TSIZE (up to 2^15, ge-rules.md §6.2) times 256,
    // so s·scale is the texel position with 8 fraction bits.
    float scaleU = 256, scaleV = 256;
    int wrapMaskU = 0, wrapMaskV = 0;  // (w − 1) & 511, further limited to the stored size
    int clampMaxU = 0, clampMaxV = 0;  // min(w, 512) − 1, further limited to the stored size
    // Bilinear: the position truncated as for nearest (geo::AccuracyProfile::pspBilinearTruncation),
    // else rounded to nearest (texelFixedRound).
    bool linearTruncates = false;

    // Fills the addressing fields for a level of nominal size 2^wlog × 2^hlog whose decoded
    // texels are storedW × storedH.
    void setSize(u32 wlog, u32 hlog, int storedW, int storedH);
};

struct LevelChoice {
    int level = 0;     // level to sample
    int frac = 0;      // 4-bit blend weight towards level + 1 (mipmap-linear only)
    bool linear = false;
};

// Level-of-detail parameters (ge-rules.md §6.6).
struct LodParams {
    int mode = 1;            // CMD_TLEVEL mode: 0 auto, 1 constant, 2 slope (3 → 1)
    int bias16 = 0;          // OFFL, signed with 4 fraction bits
    float slope = 0;         // CMD_TSLOPE
    int maxLevel = 0;        // MXL when mipmapping is on (TFILTER min bit 2), else 0
    bool mipLinear = false;  // TFILTER min bit 1
    bool minLinear = false;  // TFILTER min bit 0
    bool magLinear = false;  // TFILTER mag bit 0 (bit 8 of the command)
};

// log2(x) with 4 fraction bits as the GE forms it: exponent and the top 4 mantissa bits of the
// float (a piecewise-linear log2, truncated; the sign is ignored) [SWR]. x = 0 gives −2032.
int texLog2x16(float x);

// Level of detail d in 1/16 units, OFFL included, for one pixel. `lod` is Fragment::lod
// (log2 texels per pixel at level 0 as the GE forms it, mode 0): d = floor(lod·16). `w` is
// Fragment::w (mode 2): d = texLog2x16(2·TSLOPE·W).
int levelOfDetail16(const LodParams& p, float lod, float w);

// Which level(s) and which filter a detail value selects (ge-rules.md §6.6): the minification filter when
// d > 0, else magnification; with mipmaps (maxLevel > 0) and d > 0, level = floor(min(d, MXL) + 0.5)
// or, mipmap-linear, floor(min(d, MXL)) plus a 4-bit fraction towards the next level.
LevelChoice chooseLevel(const LodParams& p, int detail16);

// Single-level filters (ge-rules.md §8.10). Nearest: u = trunc(s·w·256) >> 8. Bilinear: the sample point
// moves half a texel back, u0 = (round(s·w·256) − 128) >> 8 with the 4-bit fraction of the same
// value (s·w·256 rounded to nearest-even, as the reference renderer's x86 sampler converts it);
// the four texels are wrapped/clamped separately and weighted (16 − fu)(16 − fv), … >> 8.
u32 sampleNearest(const TexLevel& lv, float s, float t, bool clampU, bool clampV);
u32 sampleBilinear(const TexLevel& lv, float s, float t, bool clampU, bool clampV);
// (c_next·frac + c·(16 − frac)) >> 4 per channel.
u32 mixLevels(u32 c, u32 cNext, int frac);

struct Sampler {
    TexLevel levels[8];
    int levelCount = 0;  // decoded levels available (0 … levelCount − 1)
    LodParams lod;
    bool clampU = false, clampV = false;
    // For CMD_TLEVEL constant mode the choice is the same for every pixel and made once.
    bool fixedChoice = false;
    LevelChoice fixed;

    using SampleFn = u32 (*)(const Sampler&, float s, float t, float lod, float w);
    SampleFn fn = nullptr;

    u32 sample(float s, float t, float lodValue, float w) const { return fn(*this, s, t, lodValue, w); }

    // The texture colours of n fragments (out[i] = sample(f[i].s, f[i].t, f[i].lod, f[i].w), the
    // same values). Where one level and one filter serve every pixel (the routines of
    // sampleFixedT), four fragments' texel coordinates are formed together (SSE2).
    void sampleFragments(const geo::Fragment* f, size_t n, u32* out) const;
    using Sample4Fn = void (*)(const Sampler&, const geo::Fragment* f, u32* out);
    Sample4Fn fn4 = nullptr;

    // Picks the specialised routine; call after levels, lod, clamp flags and the fixed choice
    // are set.
    void finalize();
};

// Which levels a draw needs decoded, given the sampler parameters (before finalize()):
// returns the highest level index that any pixel may sample.
int highestLevelNeeded(const LodParams& p, bool fixedChoice, const LevelChoice& fixed);

}  // namespace ge::soft
