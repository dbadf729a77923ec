// SPDX-License-Identifier: MIT
// GL hardware mode: the GE's vertex work in a generated vertex shader, and the
// whole-primitive work (discard rules, near-plane clipping, culling) in a generated geometry shader.
//
// The vertex shader reproduces, per vertex and with the same float operation order, what every
// backend runs on the CPU today:
//   hle/vertex_decoder      VTYPE formats, morphing (8 weights), skinning (8 bones)
//   geometry/transform      makeTransformState / transformVertex / projectToScreen: the folded
//                           world·view·proj or view·proj product, the GE's matrix term rule
//                           (geTerm), viewport, 1/16-pixel snap x16 = trunc(Xs·16 + 0.375) − OFFX,
//                           depth clamp, fog factor, texture mapping (UV, projection, shade)
//   geometry/lighting       the fixed-point light combination of docs/ge-rules.md §8.3
// The geometry shader (generateHwGeometryShader) reproduces translator/vertex_pipeline.cpp
// VertexPipeline::triangle for transform-mode triangles:
//   geometry/clip           discardPrimitive (ge-rules.md §8.5), the all-w < 0 drop, clipTriangleNear with
//                           lerpVertex (clip-space interpolation, 8-bit colour weights, the new
//                           vertex projected and snapped), the fan-piece drop for new vertices off
//                           the 4096² screen, the rotation rule for negatively wound polygons, in
//                           the reference's strip/fan ring order (geometry/assembly.h, ringReversed)
//   VertexPipeline::culled  GE culling on the snapped positions of every piece (area 0 never culled)
//   toGl / emitTriangle     what the fragment shader gets (shader_gen.h non-exact attribute set)
// so that its output vertex stream is VertexPipeline's Geometry::tris, triangle for triangle and
// vertex for vertex (tests/gl_hw_clip.cpp compares them by transform feedback).
//
// Vertex fetch: the draw's vertex bytes are a buffer texture `u_vtx` (internal format R8UI, one
// byte per texel); vertex v starts at byte v·stride (stride = the GE vertex size times the morph
// count, fixed by the key: hwVsStride). v is gl_VertexID, so the caller draws with glDrawArrays
// (`first` = the first vertex) or glDrawElements with the GE's indices rebased so that index 0 is
// the first byte of the buffer. The shader decodes every format itself instead of using GL vertex
// attributes because morphing needs up to 8 copies of every attribute (8 × 5 attributes + weights
// is more than GL's 16 attribute slots) and because the GE's formats (s8 positions /128, u16
// weights /32768, 5650/5551/4444 colours with bit replication) are not all GL attribute formats.
// GL guarantees only 65536 texels in a buffer texture (GL_MAX_TEXTURE_BUFFER_SIZE; llvmpipe and
// desktop drivers allow far more): a draw needs its vertex bytes to fit in the caller's limit.
//
// Vertex shader outputs, read only by the geometry shader (per vertex, the CPU's ClipVertex):
//   g_clip    vec4         clip coordinates (ClipVertex::clip; its w is ScreenVertex::w)
//   g_color   flat ivec4   primary RGBA 0..255 (ScreenVertex::color, lit or the vertex colour)
//   g_color2  flat ivec3   secondary RGB 0..255 (ScreenVertex::secondary)
//   g_stqf    vec4         s, t, q, fog factor (ScreenVertex::s/t/q/fog; s, t, q = 0, 0, 1
//                          without texturing, fog 1 without fog)
//   g_scr     flat ivec4   x16, y16 (drawing position in 1/16 pixel), z (depthToInt of the
//                          clamped screen Z), flags: 1 outside (ge-rules.md §8.5 range rule), 2 beyond the
//                          near side and 4 beyond the far side of the depth range (depthSide),
//                          8 no position (ge-rules.md §8.11: every primitive using it is dropped)
// Geometry shader outputs (the fragment shader's non-exact inputs, shader_gen.cpp, as toGl and
// emitTriangle compute them from ScreenVertex):
//   v_color  (flat | noperspective) vec4   primary RGBA 0..255 (flat: the original triangle's
//                                           provoking vertex c on every vertex, clipped pieces too)
//   v_color2 (same)                 vec3   secondary RGB 0..255
//   v_tex    noperspective          vec4   (s·k, t·k, q·k, w), k = 1/w (w: 1 if 0 or not finite)
//   v_fog    noperspective          float  fog factor
//   v_z      noperspective          float  float(z)
//   gl_Position  (x·u_ndcScale.x − 1, y·u_ndcScale.y − 1, 0, 1), x = x16/16 + (8 − 7)/16 (the
//                triangleSampleOffset shift of emitTriangle); w = 1, so GL's own clipping never
//                changes a triangle (x and y stay within ±65536 pixels).
// Each emitted triangle is its own 3-vertex strip (EndPrimitive after it), in VertexPipeline's
// vertex order: the ring order for strips and fans, the winding (a, b, c) for lists, pieces of a
// clipped polygon as its fan (0, k, k + 1). GL therefore must NOT cull or clip: the caller draws
// WITHOUT GL_CULL_FACE and WITHOUT GL_CLIP_DISTANCE0 (the shader writes neither cull nor clip
// distances, and a piece's vertex order may run against the primitive's winding, as on the CPU).
// Every draw is a GL_TRIANGLES list (hwTriangleList): triangle i of a strip is given as its
// vertices (i, i + 1, i + 2) for even i and (i + 1, i, i + 2) for odd i, triangle i of a fan as
// (0, i + 1, i + 2) — the CPU's winding (a, b, c), the order the core spec's strips and fans hand
// a geometry shader — and the geometry shader reads i mod 6 from the buffer texture u_ring at
// gl_PrimitiveIDIn (the reference's ring order depends on it). So one GL draw can hold several
// strips and fans (the translator joins consecutive draws of equal state), and nothing rests on a
// driver's strip or fan order, provoking vertex convention or primitive restart. The draw must
// still start its strip or fan (no PRIM type 7 continuation).
// Through mode (key.through = 1, VTYPE bit 23): the vertex shader decodes the first stored copy
// only (no morphing, no skinning; the stride still counts every copy) with through mode's rules
// (hle/vertex_decoder.cpp: s8 positions 0, s16 X/Y signed and Z unsigned, float Z limited to
// 0–65535; u16 UV as texels, u8 UV /128, float as stored) and transformVertex's through branch
// (x16 = trunc(x·16) limited to ±2^20, z = depthToInt(Z), s = u·invTexW0, t = v·invTexH0 from
// HwVsUniforms::texScale, q = 1, w = 1, fog 1, the vertex colour, no secondary); g_clip is
// (x, y, z, 1) and no flag but 8 is ever set. The geometry shader then applies no discard rule and
// no near clipping, culls as in transform mode and emits v_tex = (s, t, q, 1) (toGl without
// perspective). Tested by tests/gl_hw_through.cpp.
// Known differences from the CPU path: a zero-area triangle (or piece) is not emitted, where the
// CPU draws the samples on its line as one-pixel quads (geometry/raster.cpp
// rasterZeroAreaTriangle; emitted, GL would rasterise nothing of it anyway); the GE-time pixel
// budget (VertexPipeline::notePrimitive) is not applied; strips whose quads the CPU draws as
// rectangles (geometry/assembly.h stripQuadAsRect, culling off) are the caller's to keep away.
//
// Host features: the shaders are GLSL 3.30 and enable, where the driver has them,
// GL_ARB_gpu_shader_fp64 (correctly rounded float divisions, the double-precision normalisation
// of geometry/lighting normalizeOr001 and an accurate pow) and GL_ARB_gpu_shader5 (`precise`: no
// fused multiply-add). Without them they still compile, with float approximations (divisions,
// normalisation, pow may then differ by an ulp). llvmpipe and desktop GL 4.5 drivers have both.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/accuracy_profile.h"
#include "hle/ge_state.h"
#include "hle/types.h"
#include "shadergen/shader_keys.h"

namespace ge::geo {
struct MatrixFold;
}

namespace ge::shadergen {

// Zero-initialised POD compared and hashed byte-wise (keyEqual / KeyHash), canonical after
// canonicalize(): fields that cannot change the generated source are cleared.
struct HwVsKey {
    // ---- vertex format (CMD_VTYPE, ge-rules.md §5.1). All layout fields are kept even when
    // their value is not used, because they set the component offsets and the stride (ge-rules.md §5.2). ----
    u8 tc = 0;           // texture coordinates: 0 none, 1 u8, 2 u16, 3 float
    u8 col = 0;          // colour: 0 none (1–3 canonicalised to 0: no bytes, no colour), 4 5650,
                         // 5 5551, 6 4444, 7 8888
    u8 nrm = 0;          // normal: 0 none, 1 s8, 2 s16, 3 float
    u8 pos = 0;          // position: 1 s8, 2 s16, 3 float; 0 = none: every vertex dropped (ge-rules.md §8.11)
    u8 weights = 0;      // skinning weights: 0 none, 1 u8, 2 u16, 3 float
    u8 weightCount = 0;  // 1–8 with weights, else 0
    u8 morphCount = 0;   // 1–8 stored copies (MC + 1)
    // ---- lighting (CMD_LTE, LE, LTYPE, MATERIAL, LMODE; ge-rules.md §3.6, §8.3, §8.12) ----
    u8 lighting = 0;
    u8 lightType[4] = {};  // 0 off (LE = 0), 1 directional, 2 point, 3 spot (LTYPE type 2 and 3)
    u8 lightComp[4] = {};  // 0 ambient + diffuse, 1 + specular, 2 powered diffuse (3 → 0)
    u8 ambientFromVertex = 0;   // MATERIAL bits, kept only with a vertex colour (ge-rules.md §3.6)
    u8 diffuseFromVertex = 0;
    u8 specularFromVertex = 0;
    u8 separateSpecular = 0;    // LMODE = 1 (kept only with a specular light)
    // ---- texture coordinates (CMD_TMAP, manual §13.1, §13.2, ge-rules.md §8.10) ----
    u8 texture = 0;      // texturing on: v_tex is computed
    u8 texMap = 0;       // 0 UV (TMAP mode 3 behaves as 0), 1 projection, 2 shade mapping
    u8 projSource = 0;   // TMAP bits 9..8 with projection: 0 model position, 1 UV, 2 normalised
                         // normal, 3 normal
    // ---- the rest ----
    u8 fog = 0;          // fog factor per vertex (FGE; else v_fog = 1)
    u8 normalReverse = 0;  // NREV, kept only when a normal is read and used
    u8 clipEnable = 0;   // CLE: depth clamp and the discard rule (ge-rules.md §8.5)
    u8 flatShade = 0;    // SHADE = 0 or clear mode: colour outputs are `flat`
    // ---- set by the caller after hwVsKeyFromState (which leaves it 0) ----
    u8 primKind = 0;     // the PRIM type drawn (the geometry shader's ring order): 0 triangles
                         // (GL_TRIANGLES), 1 triangle strip (GL_TRIANGLE_STRIP), 2 triangle fan
                         // (GL_TRIANGLE_FAN); canonicalised to 0 when above 2
    u8 sampleCentre = 0;  // triangles sample at the pixel centre (geo::RasterParams::sampleCentre,
                          // the geometry shader's GE_SHIFT)
    // ---- through mode (VTYPE bit 23, ge-rules.md §5.5, §8.1) ----
    u8 through = 0;      // 1: positions and UV as given (no normalisation, no morphing, no
                         // skinning), no transform, lighting, texture mapping, fog, discard rules
                         // or near clipping; culling and flat shading as in transform mode.
                         // canonicalize clears lighting, lightType/lightComp, the MATERIAL and
                         // LMODE flags, texMap, projSource, fog, normalReverse and clipEnable
                         // (the CPU ignores them), and keeps every layout field (tc, col, nrm, pos,
                         // weights, weightCount, morphCount: they set the offsets and the stride)
    u8 reserved[2] = {};
};
static_assert(sizeof(HwVsKey) == 32, "HwVsKey: every byte must be a named field");

void canonicalize(HwVsKey& k);
std::string describe(const HwVsKey& k);

// The key of a draw (`through` from VTYPE bit 23). `texture`: texturing on (TME and not clear
// mode); `fog`: FGE (as the draw front end reads it: ignored in through mode). Canonicalised.
HwVsKey hwVsKeyFromState(const GeState& st, bool texture, bool fog);
// The same for vertices of format `vtype` rather than the state's VTYPE (the GPU path's
// tessellated patches: float vertices made on the CPU).
HwVsKey hwVsKeyFromState(const GeState& st, u32 vtype, bool texture, bool fog);

// Bytes per vertex (one vertex times its morph copies, ge-rules.md §5.2) of a key.
u32 hwVsStride(const HwVsKey& k);

// Every value the shader reads, as 4-byte words, uploaded in one call:
//   glUniform4uiv(location of hwuniform::kBlock, kHwVsUniformVec4, reinterpret_cast<const GLuint*>(&u))
// (floats travel as their bit patterns, so NaN and infinity arrive as the GE has them). The GLSL
// side addresses the words by offsetof, so the layout here is the only definition.
struct HwVsUniforms {
    // Folded matrices of geometry/transform makeTransformState (row-vector 4×4, element
    // [row·4 + col]): world·view·proj applied to the model position, or view·proj applied to the
    // world position when a positional light needs the world position.
    float worldViewProj[16];
    float viewProj[16];
    float world[12], view[12], tgen[12];  // 3×4, element k = row k%3, column k/3 (ge-rules.md §3.4)
    float bones[96];                      // 8 bone matrices, 3×4 each
    float morph[8];                       // CMD_WEIGHT0–7
    float viewport[8];                    // SX, SY, SZ, TX, TY, TZ, 0, 0
    s32 offset16[4];                      // OFFSETX, OFFSETY (1/16 pixel), 0, 0
    float uvScale[4];                     // SU, SV, TU, TV
    float fog[4];                         // end (FOG1), slope (FOG2 after the ge-rules.md §8.9 rule), 0, 0
    s32 fogFixed[4];                      // −1 per vertex; 0/1: the whole draw (FOG1 not finite)
    u32 matColor[4];                      // MAC | MAA << 24: the colour of a vertex without one
    float shadeLight[8];                  // normalised TSHADE light positions (u: 0–2, v: 4–6)
    // Lighting (geometry/lighting makeLightingState): (2·c + 1) colour factors, MEC plain.
    s32 emissive[4];
    s32 globalAmbient[4];
    s32 matAmbient[4];
    s32 matDiffuse[4];
    s32 matSpecular[4];
    float specularExp[4];                 // MK, 0, 0, 0
    float lightPos[16];                   // per light xyz (directional: normalised), pad
    float lightAtt[16];                   // LKA, LKB, LKC, pad
    float lightSpotDir[16];               // normalised LD, pad
    float lightSpot[16];                  // LKS, LKO (−NaN → 0), forced spot cosine (−1: none), pad
    s32 lightAmbient[16];
    s32 lightDiffuse[16];
    s32 lightSpecular[16];
    // Added for the geometry shader (geo::DrawFrontEnd::culled, geometry/draw_front_end.cpp):
    s32 cull[4];                          // BCE on and not clear mode, CULL (1: counter-clockwise
                                          // culled), 0, 0
    // Added for through mode (geometry/transform.cpp transformVertex, makeTransformState):
    float texScale[4];                    // invTexW0 = 1/width0, invTexH0 = 1/height0, 0, 0
};
static_assert(sizeof(HwVsUniforms) % 16 == 0 && sizeof(HwVsUniforms) / 4 * 4 == sizeof(HwVsUniforms));
inline constexpr int kHwVsUniformVec4 = int(sizeof(HwVsUniforms) / 16);

// Fills every field from the state (through geo::makeTransformState, so the folded matrices,
// normalised directions and fog specials are the CPU's own values). The vertex format is the
// state's VTYPE.
// `acc`: the profile's lighting switches that the uniforms carry (spotDirectionDivide: the spot
// cosine forced for an LD that cannot be normalised); sseVectorArithmetic's approximations are
// not reproduced on the GPU.
void hwVsUniformsFromState(const GeState& st, HwVsUniforms& u, const geo::AccuracyProfile& acc = {});
// The same for vertices of format `vtype`; `fold` (may be null) keeps the folded matrices between
// draws whose matrices are unchanged (geo::MatrixFold).
void hwVsUniformsFromState(const GeState& st, u32 vtype, HwVsUniforms& u, const geo::AccuracyProfile& acc,
                           geo::MatrixFold* fold);

// GLSL for a key. False + err only for keys the generator cannot express (none today).
bool generateHwVertexShader(const HwVsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);

// GLSL of the geometry shader that goes with generateHwVertexShader(key) (implemented in
// hw_geometry.cpp). It reads u_hw (viewport, offsets, cull) and u_ndcScale, and depends on the
// key's primKind, clipEnable, flatShade, texture and through. False + err only for keys the
// generator cannot express (none today).
//
// What the caller does per draw (translator/gpu_vertex_path.cpp):
//   key = hwVsKeyFromState(st, texture, fog);
//   key.primKind = 0 / 1 / 2 for GE_PRIM_TRIANGLES / _TRIANGLE_STRIP / _TRIANGLE_FAN;
//   program = VS(key) + GS(key) + FS; u_hw = hwVsUniformsFromState(st) (which fills `cull`:
//   culling now follows BCE/CULL from the state, as the draw front end); u_ndcScale;
//   hwTriangleList(primKind, the PRIM's vertex sequence) → indices (+ u_ring for strips and
//   fans); draw GL_TRIANGLES with those indices, with GL_CULL_FACE and GL_CLIP_DISTANCE0
//   disabled. Transform feedback of the GS output (GL_TRIANGLES) is VertexPipeline's
//   Geometry::tris for the same PRIM.
bool generateHwGeometryShader(const HwVsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);

// Names the translator looks up.
namespace hwuniform {
inline constexpr const char* kBlock = "u_hw";          // uvec4[kHwVsUniformVec4]: HwVsUniforms
inline constexpr const char* kVertexBytes = "u_vtx";   // usamplerBuffer (R8UI): the draw's vertex bytes
inline constexpr const char* kRingIds = "u_ring";      // usamplerBuffer (R8UI): strip/fan triangle number mod 6
inline constexpr const char* kNdcScale = "u_ndcScale";  // vec2: as shader_gen.h uniform::kNdcScale
                                                        // (read by the geometry shader)
}  // namespace hwuniform
// Texture unit suggested for u_vtx (units 0–3 are the fragment shader's, shader_gen.h).
inline constexpr int kUnitVertexBytes = 4;
// Texture unit suggested for u_ring (5 and 6 are the fragment shader's, shader_gen.h).
inline constexpr int kUnitRingIds = 7;

// The triangle list a GE triangle PRIM is drawn as (see the geometry shader's contract above).
// `primKind` as HwVsKey::primKind; `seq` the PRIM's `count` vertex numbers in draw order (the
// rebased indices, or 0..count-1). Appends 3 indices per triangle, each plus `base`, to `indices`
// and, for strips and fans, the triangle's number in its PRIM mod 6 to `ringIds` (R8UI texels of
// u_ring, one per triangle). A list drops an incomplete last triangle, a strip or fan of fewer
// than 3 vertices gives none, as GL draws them.
void hwTriangleList(u8 primKind, const u32* seq, u32 count, u32 base, std::vector<u32>& indices,
                    std::vector<u8>& ringIds);

}  // namespace ge::shadergen
