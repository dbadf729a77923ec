// SPDX-License-Identifier: MIT
// Texture functions, colour doubling, colour addition and fog: the software model's exact integer
// forms (manual §13.13, §14, §15, §16; docs/ge-rules.md §8.3, §8.13). Private to softmodel/.
//
// Every value is an integer 0–255 on input; ">> n" is a floor shift. The texture function may
// produce values above 255 (ADD, doubling); the caller clamps after adding the secondary colour
// (ge-rules.md §8.4 step 1), which gives the same result as clamping twice since nothing here is negative.
#pragma once
#include <algorithm>

#include "hle/types.h"
#include "softmodel/framebuffer.h"

namespace ge::soft {

enum TexFunc : u8 { TFUNC_MODULATE = 0, TFUNC_DECAL, TFUNC_BLEND, TFUNC_REPLACE, TFUNC_ADD };

inline int texR(u32 t) { return int(t & 255); }
inline int texG(u32 t) { return int((t >> 8) & 255); }
inline int texB(u32 t) { return int((t >> 16) & 255); }
inline int texA(u32 t) { return int(t >> 24); }

// One texture function, specialised on function, TCC (RGBA) and colour doubling. `c` holds the
// primary colour on entry and Cv on exit; `env` is CMD_TEC's RGB.
template <int FUNC, bool RGBA, bool DBL>
inline void textureFunction(Rgba& c, u32 texel, const int env[3]) {
    const int tr = texR(texel), tg = texG(texel), tb = texB(texel), ta = texA(texel);
    // ge-rules.md §8.3: "alpha as MODULATE" for BLEND and ADD; MODULATE alpha itself with TCC = 1.
    const int modA = RGBA ? ((c.a + 1) * ta) >> 8 : c.a;
    constexpr int mul = DBL ? 2 : 1;       // REPLACE/ADD/DECAL(TCC=0): ×2 (ge-rules.md §8.3 doubling row)
    constexpr int shift = DBL ? 7 : 8;     // DECAL/BLEND keep a bit of precision when doubling
    if constexpr (FUNC == TFUNC_MODULATE) {
        // (P + 1)·T >> 8; doubled: ((P + 1)·T·2) >> 8.
        c.r = ((c.r + 1) * tr * mul) >> 8;
        c.g = ((c.g + 1) * tg * mul) >> 8;
        c.b = ((c.b + 1) * tb * mul) >> 8;
        c.a = modA;
    } else if constexpr (FUNC == TFUNC_DECAL) {
        if constexpr (RGBA) {
            // ((P + 1)·(255 − At) + (T + 1)·At) >> 8 (>> 7 doubled); alpha stays Ap.
            const int inv = 255 - ta;
            c.r = ((c.r + 1) * inv + (tr + 1) * ta) >> shift;
            c.g = ((c.g + 1) * inv + (tg + 1) * ta) >> shift;
            c.b = ((c.b + 1) * inv + (tb + 1) * ta) >> shift;
        } else {
            c.r = tr * mul;
            c.g = tg * mul;
            c.b = tb * mul;
        }
    } else if constexpr (FUNC == TFUNC_BLEND) {
        // ((255 − T)·P + T·TEC + 255) >> 8: always rounds up (>> 7 doubled).
        c.r = ((255 - tr) * c.r + tr * env[0] + 255) >> shift;
        c.g = ((255 - tg) * c.g + tg * env[1] + 255) >> shift;
        c.b = ((255 - tb) * c.b + tb * env[2] + 255) >> shift;
        c.a = modA;
    } else if constexpr (FUNC == TFUNC_REPLACE) {
        c.r = tr * mul;
        c.g = tg * mul;
        c.b = tb * mul;
        if constexpr (RGBA) c.a = ta;
    } else {  // ADD (and the undefined codes 5–7, which behave as ADD, ge-rules.md §3.8)
        c.r = (c.r + tr) * mul;
        c.g = (c.g + tg) * mul;
        c.b = (c.b + tb) * mul;
        c.a = modA;
    }
}

using TextureFunctionFn = void (*)(Rgba& c, u32 texel, const int env[3]);

// The specialised routine for a CMD_TFUNC setting (func 5–7 → ADD).
inline TextureFunctionFn pickTextureFunction(u32 func, bool rgba, bool dbl) {
#define GE2GL_TF(F)                                                                       \
    return rgba ? (dbl ? &textureFunction<F, true, true> : &textureFunction<F, true, false>) \
                : (dbl ? &textureFunction<F, false, true> : &textureFunction<F, false, false>)
    switch (func) {
    case TFUNC_MODULATE: GE2GL_TF(TFUNC_MODULATE);
    case TFUNC_DECAL: GE2GL_TF(TFUNC_DECAL);
    case TFUNC_BLEND: GE2GL_TF(TFUNC_BLEND);
    case TFUNC_REPLACE: GE2GL_TF(TFUNC_REPLACE);
    default: GE2GL_TF(TFUNC_ADD);
    }
#undef GE2GL_TF
}

// ge-rules.md §8.4 step 1, manual §15: Cv + Cs, clamped to 0–255 (doubling never touches Cs, ge-rules.md §8.13).
inline void addSecondaryAndClamp(Rgba& c, const u8 sec[3]) {
    c.r = std::min(c.r + sec[0], 255);
    c.g = std::min(c.g + sec[1], 255);
    c.b = std::min(c.b + sec[2], 255);
    c.a = std::min(c.a, 255);
}

// ge-rules.md §8.3 fog: (C·f + FC·(255 − f) + 255) >> 8 with the 8-bit fog factor f (255 = no fog).
inline int fogChannel(int c, int fc, int f) { return (c * f + fc * (255 - f) + 255) >> 8; }
inline void applyFog(Rgba& c, const int fogColor[3], int f) {
    c.r = fogChannel(c.r, fogColor[0], f);
    c.g = fogChannel(c.g, fogColor[1], f);
    c.b = fogChannel(c.b, fogColor[2], f);
}

}  // namespace ge::soft
