// SPDX-License-Identifier: MIT
// What the rasteriser (raster.h) hands on for every covered pixel: the software model shades it
// with its per-pixel pipeline (softmodel/pixel.h shadeFragments); the GL translator's exact mode
// packs lines and points into per-fragment records (translator/tri_setup.h packFragment). Its own
// header so that geometry/ does not depend on either backend.
#pragma once
#include "hle/types.h"

namespace ge::geo {

struct Fragment {
    int x = 0, y = 0;        // drawing coordinates, inside the scissor
    u16 z = 0;               // screen Z, 0–65535
    u8 color[4] = {};        // primary RGBA (Gouraud-interpolated and truncated, or flat)
    u8 secondary[3] = {};    // secondary RGB (separate specular), 0 when none
    u8 fog = 255;            // fog factor f as 8 bits: 255 no fog, 0 full fog colour (docs/ge-rules.md §8.9)
    float s = 0, t = 0;      // texture coordinates in units of the level-0 size (1.0 = full width),
                             // perspective-divided, not yet wrapped/clamped, SU/SV/TU/TV applied
    float lod = 0;           // texture level of detail d for TLEVEL mode 0 (log2 texels per pixel
                             // at level 0), computed by the rasteriser from neighbouring pixels
    float w = 1;             // clip-space W, for TLEVEL mode 2 (slope)
};

}  // namespace ge::geo
