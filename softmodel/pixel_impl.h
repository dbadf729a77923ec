// SPDX-License-Identifier: MIT
// PixelState::Impl: everything the per-pixel pipeline needs, resolved once per draw by
// buildPixelState (softmodel/pixel.cpp) and read-only while shading. Private to softmodel/.
#pragma once
#include <memory>

#include "softmodel/blend.h"
#include "softmodel/pixel.h"
#include "softmodel/sampler.h"
#include "softmodel/texfunc.h"
#include "softmodel/texture_cache.h"

namespace ge::soft {

struct PixelState::Impl {
    using ShadeFn = void (*)(const PixelState&, const Impl&, const geo::Fragment*, size_t);
    ShadeFn shade = nullptr;  // the routine specialised for this state (pixel.cpp)

    // Buffers: pixels addressable from fb/zb without leaving VRAM (offset y·stride + x must be
    // below these), and whether this draw touches the depth buffer at all.
    u32 fbPixels = 0, zbPixels = 0;
    bool usesDepthBuffer = false;

    // Mode.
    bool clearMode = false, through = false;
    bool clearColor = false, clearAlpha = false, clearDepth = false;  // CMODE CEN/AEN/ZEN

    // Texturing (manual §13; docs/ge-rules.md §8.3, §8.10).
    bool texture = false;
    Sampler sampler;
    std::shared_ptr<const DecodedLevel> levelData[8];  // keeps the decoded levels alive
    TextureFunctionFn texFunc = nullptr;
    int texEnv[3] = {};

    // Fog (ge-rules.md §8.3, §8.9).
    bool fog = false;
    int fogColor[3] = {};

    // Tests (ge-rules.md §8.4 steps 2–7).
    bool depthRange = false;
    int minZ = 0, maxZ = 65535;
    bool alphaTest = false;
    u8 alphaFunc = 0;
    int alphaRef = 0, alphaMask = 0;  // ref already masked
    bool colorTest = false;
    u8 colorFunc = 0;
    u32 colorRef = 0, colorMask = 0;  // packed RGB (R in 7..0), ref already masked
    bool stencilTest = false;
    u8 stencilFunc = 0;
    int stencilRefMasked = 0, stencilMask = 0, stencilRef = 0;
    u8 sfail = 0, zfail = 0, zpass = 0;
    bool depthTest = false;
    u8 depthFunc = 0;
    bool depthWrite = false;

    // Blending, dithering, logic op (ge-rules.md §8.4 steps 9–11).
    bool blend = false;
    BlendParams blendParams;
    BlendFn blendFn = nullptr;  // pickBlend(blendParams)
    int dither[4][4] = {};  // all zero when DTE is off
    bool logicOpOn = false;
    u8 logicOp = 3;

    // Write masks in the frame-buffer format (ge-rules.md §8.4 step 12, §8.7, §8.8): a 1 bit keeps the stored
    // bit. keepMask applies to full pixel writes (PMSK1/PMSK2, plus the alpha/stencil bits when no
    // stencil value is written, plus RGB in clear mode without CEN); stencilWriteBits is the set of
    // bits a stencil-only write (failed stencil/depth test) may change: alpha bits & ~PMSK2.
    u32 keepMask = 0;
    u32 stencilWriteBits = 0;
};

}  // namespace ge::soft
