// SPDX-License-Identifier: MIT
// Per-vertex lighting of the software model, run by both backends (manual §9, equations 9-1 …
// 9-10; docs/ge-rules.md §3.6, §8.3 last two rows, §8.9, §8.12).
//
// Lighting runs in world space on the world-space normal (normalised, (0, 0, 1) when zero or
// absent) with the eye vector fixed at (0, 0, 1) (ge-rules.md §8.12; manual §9.2.3 says view space — PPSSPP's
// software renderer, which matches hardware tests, uses world space).
// Colours are combined with the measured fixed-point forms of ge-rules.md §8.3:
//   global ambient  ((2·MAC + 1)·(2·AC + 1)) >> 10     per channel, alpha: MAA (or vertex A) with AA
//   per-light term  ((2·Lc + 1)·(2·Mc + 1)·s) >> 19,  s = min(512, ceil(512·k + 1))
// where k is attenuation·spot·(N·L, its power, or the specular power).
#pragma once
#include "geometry/accuracy_profile.h"
#include "hle/ge_state.h"
#include "hle/types.h"

namespace ge::geo {

struct LightSource {
    bool enabled = false;
    bool directional = false;  // LTYPE type 0
    bool spot = false;         // LTYPE type 2 (and 3, which behaves as spot)
    bool specular = false;     // LTYPE comp 1: ambient + diffuse + specular
    bool poweredDiffuse = false;  // LTYPE comp 2: ambient + diffuse^K, no specular
    float pos[3] = {};         // directional: normalised direction toward the light
    float att[3] = {};         // LKA, LKB, LKC
    float spotDir[3] = {};     // normalised LDX/LDY/LDZ
    // ≥ 0: the spot cosine for every vertex, LD being a direction that cannot be normalised
    // (a zero vector: 0; a NaN or infinite component: 1 or 0 by its sign); −1: LD·L.
    float spotForced = -1;
    float spotExp = 0, spotCutoff = 0;
    // (2·c + 1) factors of the light colours (ge-rules.md §8.3).
    int ambient[3] = {}, diffuse[3] = {}, specularColor[3] = {};
};

// Everything lighting needs for one draw, derived once from GeState.
struct LightingState {
    LightSource lights[4];
    int emissive[3] = {};            // MEC, plain 0–255
    int globalAmbient[4] = {};       // (2·AC + 1), alpha (2·AA + 1)
    int matAmbient[4] = {};          // (2·MAC + 1), alpha (2·MAA + 1)
    int matDiffuse[3] = {}, matSpecular[3] = {};
    // CMD_MATERIAL update flags, only effective when the vertex format has a colour (ge-rules.md §3.6).
    bool ambientFromVertex = false, diffuseFromVertex = false, specularFromVertex = false;
    bool separateSpecular = false;   // CMD_LMODE = 1: specular goes to the secondary colour
    float specularExp = 0;           // CMD_MK
    bool sse = false;                // AccuracyProfile::sseVectorArithmetic (normalizeOr001)
};

// `acc`: the spot direction and vector arithmetic switches (spotDirectionDivide,
// sseVectorArithmetic).
LightingState makeLightingState(const GeState& st, bool vertexHasColor, const AccuracyProfile& acc = {});

// The GE's power function for lighting (ge-rules.md §8.9): an exponent ≤ 0 (or a negative NaN) gives 1, and a
// base ≤ 0 is returned unchanged (not raised to the power).
float lightPow(float base, float exponent);

// Lights one vertex. `worldPos` is the world-space position, `worldNormal` the normalised world
// normal, `vertexColor` the vertex colour (or MAC/MAA when the format has none). Writes the
// primary RGBA and the secondary RGB (0 unless LMODE = 1).
void lightVertex(const LightingState& ls, const float worldPos[3], const float worldNormal[3],
                 const u8 vertexColor[4], u8 primary[4], u8 secondary[3]);

// Normalises v in place and returns its previous length; a zero (or non-finite) vector becomes
// (0, 0, 1) as the GE's lighting does (ge-rules.md §8.12). The length is summed in double, or
// with `sse` (AccuracyProfile::sseVectorArithmetic) as PPSSPP's Vec3<float>::Length sums it in
// float: x² + (y² + z²).
float normalizeOr001(float v[3], bool sse = false);
// PPSSPP's x86 NormalizedOr001 (Math3D.cpp, SSE4), as Lighting.cpp normalises the half vector:
// v times the approximate reciprocal square root of (x² + y²) + z² (dpps, rsqrtps; the host's
// own rsqrtss on x86, where PPSSPP's renders come from; 1/sqrt elsewhere); components that come
// out NaN take (0, 0, 1)'s, lane by lane as PPSSPP's mask does.
void normalizeRsqrtOr001(float v[3]);

}  // namespace ge::geo
