// SPDX-License-Identifier: MIT
// From GE state to shader keys, uniform values and the fixed-function part of the pipeline.
// This is the only place in shadergen/ that reads GeState: it decides,
// per draw, which parts of the GE pixel pipeline run in the shader and which in GL fixed
// function; the translator only maps that decision to GL calls.
#pragma once
#include "geometry/accuracy_profile.h"
#include "hle/ge_state.h"
#include "shadergen/shader_keys.h"

namespace ge::shadergen {

// Per-draw switches that do not come from the register file alone (immediate-mode vertices carry
// their own texture/fog/dither/shade flags, docs/ge-rules.md §3.12).
struct DrawFlags {
    bool through = false;
    bool texture = false;
    bool fog = false;
    bool dither = false;
    bool gouraud = true;
    // Every primary colour of the draw's primitives that reaches a fragment has alpha 255
    // (geometry/reference_rules.h referenceSkipsAlphaTest); known once the geometry is built.
    bool vertexAlphaFull = false;
    // Which of the reference's alpha-test rules apply (AccuracyProfile::clutSkipsAlphaTest,
    // implicitAlphaNonZeroTest): the translator's profile.
    geo::AccuracyProfile accuracy = geo::AccuracyProfile::psp();
    static DrawFlags fromState(const GeState& st, const geo::AccuracyProfile& acc);
    bool operator==(const DrawFlags&) const = default;
};

// The fixed-function GL state that goes with a key.
struct FixedFunction {
    bool colorMask[4] = {true, true, true, true};  // used when fs.dstRead == None
    bool depthTest = false;                        // GL depth test enabled
    u8 depthFunc = 1;                              // GE code (0 NEVER … 7 GEQUAL) for glDepthFunc
    bool depthMask = false;                        // GL depth writes
    bool usesDepth = false;                        // the depth buffer must hold VRAM's values
};

struct PipelineKeys {
    VsKey vs;
    FsKey fs;
    FixedFunction ff;
};

// Builds canonical keys. `baseline` forces the GL 3.3 paths (no framebuffer fetch).
PipelineKeys keysFromState(const GeState& st, const DrawFlags& flags, const HostCaps& caps, bool baseline);

// Uniform values of the generated fragment shader (names in shader_gen.h). Texture level
// geometry is filled in by the texture cache (atlas placement), not from state.
struct FsUniforms {
    s32 texEnv[3] = {}, fogColor[3] = {};
    s32 alphaRef = 0, alphaMask = 0;
    s32 colorRef[3] = {}, colorMask[3] = {};
    s32 stencilRef = 0, stencilMask = 0;
    s32 fixA[3] = {}, fixB[3] = {};
    s32 dither[16] = {};
    s32 keepMask[4] = {};  // write-protect bits, already limited to the frame-buffer format's bits
    s32 minZ = 0, maxZ = 0xFFFF;
    // per level: atlas y offset, coordinate size 2^n w, h (unclamped, geometry/texture_size.h), 0
    // (render target: y, 2^n w, h, x origin in target texels)
    s32 texLevels[8][4] = {};
    s32 texScale = 1;          // texels of u_tex per PSP texel (render scale of a render-target texture)
    s32 clutShift = 0, clutMask = 0;  // CLUT16/32 read from a render target (FsKey::texTarget)
    s32 texMaxLevel = 0;
    s32 texLodBias = 0;        // OFFL in 1/16 levels
    float texSlope = 0;        // TSLOPE
};
void uniformsFromState(const GeState& st, FsUniforms& u);

// Bits of each 8-bit channel a frame-buffer format keeps (ge-rules.md §8.8): 5650 F8/FC/F8/00, 5551
// F8/F8/F8/80, 4444 F0 each, 8888 FF each.
void formatChannelBits(u8 fbFormat, u8 out[4]);

}  // namespace ge::shadergen
