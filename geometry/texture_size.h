// SPDX-License-Identifier: MIT
// The texture size rule both backends share: the size the GE scales texture coordinates by, and
// the bounds of the texel index. The software model (geometry/transform.cpp and assembly.cpp for
// through mode's texel coordinates, softmodel/sampler.cpp TexLevel::setSize, the level of detail's
// RasterParams::texW0) and the GL translator (the same geometry, translator/gl_batch.cpp
// u_texLevels.yz, the samplers shadergen/shader_gen.cpp generates for exact and hardware mode)
// take it from here, so the two cannot drift apart. Header only.
//
// TSIZE holds 4-bit exponents n (0 to 15). The GE keeps at most 512 texels per side
// (GeState::textureWidth/Height, the decoded level), but it scales texture coordinates by the
// full 2^n: s·2^n in transform mode, and through mode's texel coordinates u are divided by 2^n
// (so that the sampler's ·2^n gives u back). The texel index is then clamped to
// min(2^n, 512) − 1, or wrapped with (2^n − 1) & 511 (docs/ge-rules.md §8.10). Measured on a PSP (pspautotests
// gpu/textures/size, tests/conformance/textures_size.cpp): a 1024-wide row drawn over 256 pixels
// reads texel 2 at pixel 0 and texel 510 at pixel 127 (0xf00002, 0xf001fe), one 32768 wide texel
// 64 at pixel 0 (0xf00040), in transform mode (s 0..1) and in through mode (u 0..w) alike; a
// 1024-high column, through mode, row 2 at pixel 0 (0xf00008, 4 texels a row) and a 2048-high one
// row 511 from pixel 127 on (0xf007fc). The reference renderer does the same: PPSSPP
// GPU/Software/FuncId.cpp caches the level sizes as gstate.getTextureWidth (1 << (texsize & 0xF),
// not clamped), Sampler.cpp GetTexelCoordinates scales s by that width and ApplyTexelClamp /
// ApplyTexelClampQuad clamp to (width > 512 ? 511 : width − 1) or wrap with (width − 1) & 511, and
// Rasterizer.cpp divides through-mode coordinates by 1 << samplerID.width0Shift and forms the
// level of detail from the same unclamped size (CalculateSamplingParams).
#pragma once
#include <algorithm>

#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge::geo {

// 2^n for a TSIZE exponent n (beyond 15 taken as 15: only a 4-bit field reaches here from state).
constexpr u32 texCoordSize(u32 log2) { return 1u << std::min<u32>(log2, 15); }
// The largest texel index a clamped coordinate reaches: min(2^n, 512) − 1.
constexpr int texelClampMax(u32 log2) { return int(std::min<u32>(texCoordSize(log2), 512) - 1); }
// The mask a wrapped (repeating) coordinate is taken with: (2^n − 1) & 511.
constexpr int texelWrapMask(u32 log2) { return int((texCoordSize(log2) - 1) & 511); }

// A level's coordinate scale from state (level 0's also scales through mode and the level of detail).
inline u32 texCoordWidth(const GeState& st, int level) { return texCoordSize(st.TSIZE_wlog(level)); }
inline u32 texCoordHeight(const GeState& st, int level) { return texCoordSize(st.TSIZE_hlog(level)); }

}  // namespace ge::geo
