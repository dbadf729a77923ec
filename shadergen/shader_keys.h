// SPDX-License-Identifier: MIT
// Shader keys: small POD descriptions of one GE pixel/vertex pipeline configuration, and the host
// capabilities the generated GLSL may use.
//
// Rules:
//  - Keys are zero-initialised PODs compared and hashed byte-wise; every byte is a named field
//    (no implicit padding: the static_asserts below fail if a field is added carelessly).
//  - Keys are canonical: a field that cannot influence the output is cleared (canonicalize()),
//    so two states that render identically share one program.
//  - keys_from_state.cpp is the only code that reads GeState to build them; the generators
//    (shader_gen.cpp) are pure functions of (key, caps).
//
// Division of work between the key (compiled in) and uniforms (values): the key holds every
// *switch* of the pixel pipeline (which test, which function, which equation); the numbers they
// work on (references, masks, colours, dither matrix, texture level sizes) are uniforms, so a
// game changing an alpha reference does not compile a new program.
#pragma once
#include <cstddef>
#include <cstring>
#include <string>

#include "hle/types.h"

namespace ge::shadergen {

// What the host GL offers. Part of the program identity (the disk cache key hashes the source,
// which already reflects these).
struct HostCaps {
    u8 fbFetch = 0;         // GL_EXT_shader_framebuffer_fetch (coherent): read the colour target in the shader
    u8 depthFetch = 0;      // GL_ARM_shader_framebuffer_fetch_depth_stencil: read the depth target
    u8 textureBarrier = 0;  // GL_ARB_texture_barrier / GL 4.5: sample the bound target between barriers
    u8 programBinary = 0;   // GL_ARB_get_program_binary with at least one format
    // GLSL 4.00 with ARB_gpu_shader_fp64 + ARB_gpu_shader_int64: triangle attributes are evaluated
    // per pixel from the software rasteriser's own per-triangle setup (exact parity with it);
    // without, GL interpolates them in float (one step off at colour/texel boundaries).
    u8 exactInterp = 0;
    u8 reserved[3] = {};
};
static_assert(sizeof(HostCaps) == 8);

// How the fragment shader sees the destination (frame-buffer) pixel.
enum class DstRead : u8 {
    None = 0,     // no read: colour masks and the depth test are GL fixed function
    FbFetch = 1,  // `inout` colour output (EXT_shader_framebuffer_fetch)
    Texture = 2,  // texelFetch of a texture holding the target (itself after a barrier, or a copy)
};
enum class DepthRead : u8 {
    None = 0,     // GL's depth test decides (exact: D32F holds z/65536)
    Fetch = 1,    // gl_LastFragDepthARM
    Texture = 2,  // texelFetch of the depth target (after a barrier) or of a copy
};

struct VsKey {
    u8 flatShade = 0;  // SHADE = 0: colours come from the provoking (last) vertex
    u8 reserved[3] = {};
};
static_assert(sizeof(VsKey) == 4);

struct FsKey {
    // ---- colour source ----
    u8 clearMode = 0;    // CMODE bit 0: vertex colour written as is (docs/ge-rules.md §8.4)
    u8 clearColor = 0;   // CEN (clear mode only)
    u8 clearAlpha = 0;   // AEN (clear mode only; never for 5650)
    u8 clearDepth = 0;   // ZEN (clear mode only)
    u8 flatShade = 0;    // must match the VsKey (interpolation qualifiers)
    // ---- texture (ge-rules.md §8.3, §8.10, §6.6) ----
    u8 tex = 0;          // texturing on
    u8 texFunc = 0;      // 0 MODULATE, 1 DECAL, 2 BLEND, 3 REPLACE, 4 ADD (5–7 canonicalised to 4)
    u8 texAlpha = 0;     // TCC
    u8 texDouble = 0;    // colour doubling
    u8 texMagLinear = 0;
    u8 texMinLinear = 0;
    u8 texMip = 0;       // 0 level 0 only, 1 nearest level, 2 blend two levels
    u8 texLodMode = 0;   // TLEVEL mode: 0 auto, 1 constant, 2 slope (only kept when it matters)
    u8 texClampU = 0;
    u8 texClampV = 0;
    // ---- per-fragment tests and colour ops ----
    u8 fog = 0;
    u8 alphaTest = 0;    // ATF + 1 (0 = no test); ALWAYS canonicalised to 0; 9 = alpha != 0
                         // (the reference renderer's implicit test, geometry/reference_rules.h)
    u8 colorTest = 0;    // CTF + 1 (0 = no test)
    u8 depthRange = 0;   // MINZ/MAXZ test (not in through mode)
    u8 stencilTest = 0;  // STF + 1 (0 = no test)
    u8 sopFail = 0, sopZFail = 0, sopZPass = 0;
    u8 depthTest = 0;    // ZTF + 1 (0 = no test)
    u8 depthWrite = 0;   // ZTE && !ZMSK (or ZEN in clear mode)
    u8 blend = 0;        // 1 + equation (0 = no blending)
    u8 blendA = 0, blendB = 0;
    u8 logicOp = 0;      // 1 + LOP (0 = off; COPY canonicalised to 0)
    u8 dither = 0;
    u8 fbFormat = 0;     // GeBufferFormat
    u8 maskRgb = 0;      // PMSK1 partially protects RGB bits: merge in the shader
    u8 maskAlpha = 0;    // PMSK2 partially protects alpha/stencil bits
    u8 writeAlpha = 0;   // the alpha byte (stencil) may change in this draw
    // ---- how the destination is read ----
    DstRead dstRead = DstRead::None;
    DepthRead depthRead = DepthRead::None;
    // ---- texture read from a render target (GL hardware mode, render-to-texture on the GPU) ----
    // 0: the decoded atlas. 1 + GeBufferFormat: u_tex is the colour target of that format at
    // render scale (u_texScale texels per PSP texel), sampled in place; its stored pixels are
    // re-encoded to the frame buffer's 16 bits and decoded as texFormat (a 16-bit buffer read as
    // another 16-bit format, ge-rules.md §8.8, §6.3).
    u8 texTarget = 0;
    u8 texFormat = 0;   // GeTextureFormat when texTarget: 0–3 (5650, 5551, 4444, 8888), or 6/7
                        // (CLUT16 / CLUT32: the pixel is the index, looked up in u_clutTex)
    // Bilinear position truncated, not rounded (geo::AccuracyProfile::pspBilinearTruncation).
    u8 texLinearTrunc = 0;
    u8 reserved[1] = {};
};
static_assert(sizeof(FsKey) == 40, "FsKey: every byte must be a named field");

template <typename K>
inline bool keyEqual(const K& a, const K& b) { return std::memcmp(&a, &b, sizeof(K)) == 0; }
u64 hashBytes(const void* p, size_t n);
template <typename K>
struct KeyHash {
    size_t operator()(const K& k) const { return size_t(hashBytes(&k, sizeof(K))); }
};
template <typename K>
struct KeyEq {
    bool operator()(const K& a, const K& b) const { return keyEqual(a, b); }
};

// Clears don't-care fields (texture fields without texturing, tests in clear mode, …).
void canonicalize(FsKey& k);
void canonicalize(VsKey& k);

// Human-readable one-line descriptions (used as the first line of generated shaders).
std::string describe(const FsKey& k);
std::string describe(const VsKey& k);
std::string describe(const HostCaps& c);

}  // namespace ge::shadergen
