// SPDX-License-Identifier: MIT
// Vertex processing with the software model's arithmetic, run by both backends (manual §3, §7, §9,
// §13.1, §13.2, §16; docs/ge-rules.md §3.4, §3.5, §3.9, §5.5, §8.1, §8.9, §8.10).
//
// Model → world → view (3×4 matrices) → clip (4×4), viewport to screen (Xs = SX·Xc/Wc + TX),
// screen → drawing coordinates in 1/16 pixel with x16 = trunc(Xs·16 + 0.375 − OFFSETX) (ge-rules.md §8.1;
// transform-mode sprites: ceil(Xs·16) − OFFSETX, Xs from float24 arithmetic, measured on a PSP),
// screen Z to 16 bits; per-vertex fog factor, lighting and texture-coordinate generation.
// Through mode skips all of it: positions are drawing coordinates, texture coordinates texels.
#pragma once
#include <cstdint>

#include "geometry/lighting.h"
#include "geometry/raster.h"
#include "hle/ge_state.h"
#include "hle/vertex_decoder.h"

namespace ge::geo {

// Screen Z as an integer 0–65535, truncated; NaN gives 0. Clamped in float before the conversion:
// converting an out-of-range or NaN float to int is undefined behaviour.
inline int depthToInt(float z) { return z >= 0.0f ? (z <= 65535.0f ? int(z) : 65535) : 0; }

// A processed vertex: clip-space position plus everything the rasteriser needs.
struct ClipVertex {
    float clip[4] = {0, 0, 0, 1};  // clip coordinates (through mode: unused)
    ScreenVertex sv;               // drawing-space vertex (x, y, z valid after projectToScreen)
    // The vertex breaks the screen range rule of ge-rules.md §8.5 (X/Y outside [0, 4096), or with CLE = 0 a
    // screen Z outside [0, 65536)): a primitive using it is dropped.
    bool outside = false;
    bool valid = true;             // false: unreadable memory or no position (dropped, ge-rules.md §8.11)
    // Beyond the near (−1) or far (+1) side of the depth range, or 0 (clip.h depthSide of clip[]):
    // set by projectToScreen, once per vertex, for the discard rule of each primitive using it.
    s8 side = 0;
};

// A matrix of the per-vertex products in column form: column k of a 3×4 (GE element order) or
// 4×4 as four floats (a 3×4's fourth lane 0), and whether its linear part (columns 0–2) has an
// element with exponent 255, where the GE's term rule leaves IEEE arithmetic (transform.cpp).
// Made once per draw by makeTransformState, so a vertex's product is a few vector operations.
struct MatrixColumns {
    alignas(16) float col[4][4] = {};
    alignas(16) std::int32_t keep[3][4] = {};  // −1 where col[k][r]'s exponent field is not 0
    bool special = false;
};

// Per-draw constants derived once from GeState.
struct TransformState {
    bool through = false;
    bool clipEnable = false;  // CMD_CLE: depth clamp and the discard rule (ge-rules.md §8.5); not near clipping
    float world[12] = {}, view[12] = {}, proj[16] = {}, tgen[12] = {};
    float sx = 0, sy = 0, sz = 0, tx = 0, ty = 0, tz = 0;
    int offX16 = 0, offY16 = 0;  // OFFSETX/OFFSETY in 1/16 pixel
    int texMap = 0;              // 0 UV, 1 projection (TGEN), 2 shade mapping (3 behaves as 0)
    int projSource = 0;          // TMAP bits 9..8
    // Transform-mode rectangles drawn as two triangles: texture projection whose Q can vary over
    // the rectangle (see makeTransformState).
    bool rectAsTriangles = false;
    // The draw is a RECTANGLES draw (a sprite) that follows the PSP's sprite rule
    // (AccuracyProfile::pspSpritePosition): in transform mode its vertices reach the screen by it
    // (projectToScreen; docs/conformance.md "Sprites"); through-mode positions are drawing
    // coordinates as given. Set by the caller, which knows the primitive and the profile;
    // makeTransformState leaves it false.
    bool sprite = false;
    float su = 1, sv = 1, tu = 0, tv = 0;
    float invTexW0 = 1, invTexH0 = 1;  // 1 / level-0 2^n, unclamped (through-mode texel coordinates; texture_size.h)
    bool fog = false;
    int fogFixed = -1;           // −1: per vertex; 0/1: the whole draw gets f = 0/1 (ge-rules.md §8.9 specials)
    float fogEnd = 0, fogSlope = 0;
    bool lighting = false;
    LightingState light;
    // The world normal's length summed in float, as PPSSPP's NormalizeOr001 does
    // (AccuracyProfile::sseVectorArithmetic).
    bool sseNormalise = false;
    bool normalReverse = false;  // CMD_NREV
    bool hasNormal = false, hasColor = false;
    float shadeLight[2][3] = {};  // normalised positions of the TSHADE lights (S, T)
    // Without fog and lighting the reference renderer folds world·view·proj into one 4×4 matrix
    // (row-vector layout, element [row·4 + col]) and transforms positions with it in one step.
    bool combinedClip = false;
    float worldViewProj[16] = {};
    // With lighting that needs the world position (a non-directional light), the reference
    // renderer transforms to world space and then applies view·proj folded into one 4×4 matrix.
    bool worldToClip = false;
    float viewProj[16] = {};
    // world, view, the clip matrix transformVertex uses (worldViewProj, viewProj or proj) and
    // TGEN in column form, by makeTransformState (those the draw's vertices need).
    MatrixColumns worldCols, viewCols, clipCols, tgenCols;
};

// `vtype` is the draw's CMD_VTYPE word; `hasColor` whether its format carries a colour;
// `hasNormal` whether the decoded vertices hold a normal: always for PRIM vertices (the format's,
// or the vertex unit's latched one, GeState::latchNormal), for patches when the format has one or
// tessellation generates them. Without, the normal is (0, 0, 1).
// The per-draw matrix products (world·view·proj, view·proj) of the last call that passed it, with
// the matrices they came from: a caller making transform states draw after draw (the draw front
// end) passes one, and the products are reused while the three matrices stay the same — which
// they do for most consecutive draws. The result is the same either way.
struct MatrixFold {
    float world[12] = {}, view[12] = {}, proj[16] = {};
    float worldViewProj[16] = {}, viewProj[16] = {};
    bool valid = false;
};
// `acc`: the vector arithmetic switches lighting and texture generation read
// (AccuracyProfile::spotDirectionDivide, sseVectorArithmetic).
TransformState makeTransformState(const GeState& st, u32 vtype, bool hasColor, bool hasNormal,
                                  MatrixFold* fold = nullptr, const AccuracyProfile& acc = {});

// Processes one decoded vertex (morphing and skinning already applied) into `out`, including the
// screen mapping and the range flags.
void transformVertex(const TransformState& ts, const DecodedVertex& in, ClipVertex& out);

// Viewport + drawing-coordinate mapping of out.clip into out.sv.x/y/z (and sv.w). With
// `rangeCheck` the ge-rules.md §8.5 flags are set; vertices made by near clipping are not range checked.
void projectToScreen(const TransformState& ts, ClipVertex& v, bool rangeCheck);

// 3×4 (GE element order, ge-rules.md §3.4) times (x, y, z, 1) and the 3×3 part times a direction.
// Each term as the GE forms it (docs/ge-rules.md §1.2: a zero or denormal factor gives 0, exponent
// 255 is an ordinary exponent); per row (t0 + t1) + (t2 + m_translation), or (t0 + t1) + t2.
void mulPoint3x4(const float m[12], const float in[3], float out[3]);
// Row r (0–2) of mulPoint3x4 alone, bit for bit.
float mulPointRow3x4(const float m[12], const float in[3], int r);
void mulDir3x4(const float m[12], const float in[3], float out[3]);
void mulPoint4x4(const float m[16], const float in[3], float out[4]);

}  // namespace ge::geo
