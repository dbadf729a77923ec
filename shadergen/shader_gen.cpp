// SPDX-License-Identifier: MIT
// GLSL generators. Every formula cites the docs/ge-rules.md section it implements; integer
// arithmetic throughout so the result is the GE's, not an approximation in float.
#include "shadergen/shader_gen.h"

#include <string>

#include "hle/ge_state.h"  // format enumerations only

namespace ge::shadergen {
namespace {

const char* compareExpr(int func) {
    // GE compare codes (ge-rules.md §3.10): 0 NEVER, 1 ALWAYS, 2 EQUAL, 3 NOTEQUAL, 4 LESS, 5 LEQUAL,
    // 6 GREATER, 7 GEQUAL; the expression compares a OP b.
    switch (func & 7) {
        case 0: return "false";
        case 1: return "true";
        case 2: return "(a == b)";
        case 3: return "(a != b)";
        case 4: return "(a < b)";
        case 5: return "(a <= b)";
        case 6: return "(a > b)";
        default: return "(a >= b)";
    }
}

void emitCompare(std::string& s, const char* name, int func) {
    s += "bool ";
    s += name;
    s += "(int a, int b) { return ";
    s += compareExpr(func);
    s += "; }\n";
}

// Blend factor code → GLSL expression of an ivec3 (ge-rules.md §3.10 factor table). cs/cd: source and
// destination colour, as/ad: alphas, fix: FIXA or FIXB.
std::string blendFactor(int code, bool isA) {
    const char* other = isA ? "cd" : "cs";  // code 0/1: A uses Cd, B uses Cs
    const char* fix = isA ? "u_fixA" : "u_fixB";
    switch (code) {
        case 0: return std::string(other);
        case 1: return std::string("(ivec3(255) - ") + other + ")";
        case 2: return "ivec3(as)";
        case 3: return "ivec3(255 - as)";
        case 4: return "ivec3(ad)";
        case 5: return "ivec3(255 - ad)";
        case 6: return "ivec3(2 * as)";
        case 7: return "ivec3(max(255 - 2 * as, 0))";
        case 8: return "ivec3(2 * ad)";
        case 9: return "ivec3(max(255 - 2 * ad, 0))";
        default: return fix;  // 10–15: the fixed colour (ge-rules.md §3.10)
    }
}

std::string logicExpr(int op) {
    // CMD_LOP codes (ge-rules.md §3.10), s = fragment, d = frame buffer, 8-bit per channel.
    switch (op & 15) {
        case 0: return "ivec3(0)";
        case 1: return "s & d";
        case 2: return "s & ~d";
        case 3: return "s";
        case 4: return "~s & d";
        case 5: return "d";
        case 6: return "s ^ d";
        case 7: return "s | d";
        case 8: return "~(s | d)";
        case 9: return "~(s ^ d)";
        case 10: return "~d";
        case 11: return "s | ~d";
        case 12: return "~s";
        case 13: return "~s | d";
        case 14: return "~(s & d)";
        default: return "ivec3(255)";
    }
}

void header(std::string& s, const HostCaps& caps, const FsKey* fk, const std::string& desc) {
    if (caps.exactInterp) {
        // GLSL 4.00: doubles, `precise`; int64 from ARB_gpu_shader_int64 (exact interpolation).
        s += "#version 400 core\n";
        if (fk) s += "#extension GL_ARB_gpu_shader_int64 : require\n";
    } else {
        s += "#version 330 core\n";
    }
    if (fk && fk->dstRead == DstRead::FbFetch) s += "#extension GL_EXT_shader_framebuffer_fetch : require\n";
    if (fk && fk->depthRead == DepthRead::Fetch)
        s += "#extension GL_ARM_shader_framebuffer_fetch_depth_stencil : require\n";
    s += "// ge2gl ";
    s += desc;
    s += "\n";
}

// ---- exact interpolation (HostCaps::exactInterp, layout in shader_gen.h `tri`) ----
std::string recTexel(int texel) { return "v_rec[" + std::to_string(texel) + "]"; }
// Double / int64 number i of the record as a GLSL expression.
std::string recI(int i) {
    return "packInt2x32(ivec2(" + recTexel(tri::kInts + i / 2) + ((i & 1) ? ".zw))" : ".xy))");
}
// Depth at the sample point (raster.cpp rasterTriangle): the three depth slots hold Z of o[0..2].
std::string zExpr() {
    return "depthAt(" + recI(tri::kIZ) + ", " + recI(tri::kIZ + 1) + ", " + recI(tri::kIZ + 2) + ")";
}

// Helper functions of the exact path. Each mirrors geometry/raster.cpp (rasterTriangle,
// rasterRectangle): `precise` keeps every float/double operation separately rounded, in the
// software model's order, with no fused multiply-adds. Divisions the software model does in
// float are done in double and rounded once to float, which gives the correctly rounded float
// quotient (double has more than 2·24 + 2 bits) whatever the driver's float division is.

// A flag of the record's header (tri::kFlag*) as a GLSL bool expression.
std::string recFlag(u32 f) { return "((" + recTexel(tri::kHeader) + ".x & " + std::to_string(f) + "u) != 0u)"; }

// The record, the sample point's edge functions and weights, and the single-precision sum every
// interpolated attribute uses (rasterTriangle's coverage test, orderWeights, interpolateF).
void emitExactEdges(std::string& s) {
    const std::string hdr = recTexel(tri::kHeader);
    s += "flat in uvec4 v_rec[" + std::to_string(tri::kTexels) + "];\n"
         "uniform usamplerBuffer " + std::string(kGradientsUniform) + ";\n";
    s += "int64_t g_cx, g_cy;\n"
         "vec3 g_w;\n";  // edge weights of the sample point in attribute order
    // Edge function i at drawing position (cx, cy) (1/16 units): rasterTriangle's e_i.
    s += "int64_t edgeAt(int i, int64_t cx, int64_t cy) {\n"
         "  if (i == 0) return " + recI(tri::kIA) + " * cx + " + recI(tri::kIB) + " * cy + " + recI(tri::kIC) + ";\n"
         "  if (i == 1) return " + recI(tri::kIA + 1) + " * cx + " + recI(tri::kIB + 1) + " * cy + " + recI(tri::kIC + 1) + ";\n"
         "  return " + recI(tri::kIA + 2) + " * cx + " + recI(tri::kIB + 2) + " * cy + " + recI(tri::kIC + 2) + ";\n"
         "}\n"
         "int sampleOffset() { return int(" + recTexel(tri::kColors) + ".w); }\n"
         // rasterTriangle's coverage test at the sample point (GL's own coverage is a superset).
         "bool edgeTestFails(int64_t cx, int64_t cy) {\n"
         "  uint h = " + hdr + ".x;\n"
         "  if ((h & 15u) != " + std::to_string(tri::kKindTriangle) + "u) return false;\n"
         "  for (int i = 0; i < 3; ++i)\n"
         "    if (edgeAt(i, cx, cy) < int64_t((h >> (" + std::to_string(tri::kEdgeThresholdShift) + " + i)) & 1u)) return true;\n"
         "  return false;\n"
         "}\n"
         // orderWeights: float(e) per vertex in attribute order (e1, e2, e0 when swapped).
         "vec3 weightsAt(int x, int y) {\n"
         "  int o = sampleOffset();\n"
         "  int64_t cx = int64_t(16 * x + o), cy = int64_t(16 * y + o);\n"
         "  vec3 e = vec3(float(edgeAt(0, cx, cy)), float(edgeAt(1, cx, cy)), float(edgeAt(2, cx, cy)));\n"
         "  return " + recFlag(tri::kFlagSwapped) + " ? e.yzx : e;\n"
         "}\n"
         "float wsumRecip() { return uintBitsToFloat(" + recTexel(tri::kFog) + ".w); }\n"
         // interpolateF: ((a·w0 + b·w1) + c·w2)·recip in single precision.
         "float interpF(vec3 v, vec3 w, float recip) {\n"
         "  precise float acc = v.x * w.x;\n"
         "  acc = acc + v.y * w.y;\n"
         "  acc = acc + v.z * w.z;\n"
         "  precise float r = acc * recip;\n"
         "  return r;\n"
         "}\n"
         "vec3 recF(uvec4 t) { return uintBitsToFloat(t.xyz); }\n";
}

// Depth and colours at the sample point.
void emitExactDepthColor(std::string& s) {
    // Depth (rasterTriangle): three equal values are used as they are; otherwise the float sum
    // interpF in attribute order, rounded to nearest even (the reference's cvtps2dq) and kept to
    // 0–65535.
    s += "int depthAt(int64_t a, int64_t b, int64_t c) {\n"
         "  if (a == b && b == c) return a < int64_t(0) ? 0 : (a > int64_t(65535) ? 65535 : int(a));\n"
         "  float r = roundEven(interpF(vec3(float(a), float(b), float(c)), g_w, wsumRecip()));\n"
         "  return r > 0.0 ? (r >= 65535.0 ? 65535 : int(r)) : 0;\n"
         "}\n";
    // interpolateColor: rounded to nearest even, kept to 0–255.
    s += "ivec4 bytes4(uint p) { return ivec4(uvec4(p, p >> 8, p >> 16, p >> 24) & 255u); }\n"
         "ivec4 interpColor(uvec3 pc, bool varies) {\n"
         "  if (!varies) return bytes4(pc.x);\n"
         "  vec4 c0 = vec4(bytes4(pc.x)), c1 = vec4(bytes4(pc.y)), c2 = vec4(bytes4(pc.z));\n"
         "  float r = wsumRecip();\n"
         "  vec4 v = vec4(interpF(vec3(c0.x, c1.x, c2.x), g_w, r), interpF(vec3(c0.y, c1.y, c2.y), g_w, r),\n"
         "                interpF(vec3(c0.z, c1.z, c2.z), g_w, r), interpF(vec3(c0.w, c1.w, c2.w), g_w, r));\n"
         "  return ivec4(clamp(roundEven(v), 0.0, 255.0));\n"
         "}\n";
    // Gradient planes (geo::colourGradientPlanes, raster.cpp colourFromGradients): channel ch's
    // gx, gy from texel first + ch of the triangle's planes; the value
    // floor((4096·c_ref + gx·dx + gy·dy) / 4096) from the reference vertex, kept to 0–255.
    const std::string hdr = recTexel(tri::kHeader);
    s += "ivec4 gradColor(uvec3 pc, int first) {\n"
         "  int r = int((" + hdr + ".x >> " + std::to_string(tri::kGradientRefShift) + "u) & 3u);\n"
         "  int64_t dx = g_cx - int64_t(int(" + recTexel(tri::kQ) + ".w));\n"
         "  int64_t dy = g_cy - int64_t(int(" + recTexel(tri::kRecipW) + ".w));\n"
         "  ivec4 cr = bytes4(r == 0 ? pc.x : (r == 1 ? pc.y : pc.z));\n"
         "  ivec4 outc;\n"
         "  for (int ch = 0; ch < 4; ++ch) {\n"
         "    uvec4 g = texelFetch(" + std::string(kGradientsUniform) + ", int(" + recTexel(tri::kClipW) + ".w) * " +
             std::to_string(tri::kGradTexels) + " + min(first + ch, 6));\n"
         "    int64_t gx = packInt2x32(ivec2(g.xy)), gy = packInt2x32(ivec2(g.zw));\n"
         "    int64_t q = (int64_t(cr[ch]) * int64_t(4096) + gx * dx + gy * dy) >> 12;\n"
         "    outc[ch] = q < int64_t(0) ? 0 : (q > int64_t(255) ? 255 : int(q));\n"
         "  }\n"
         "  return outc;\n"
         "}\n";
    s += "ivec4 vertexColor(uvec3 pc, bool varies, int first) {\n"
         "  return varies && " + recFlag(tri::kFlagColourGradients) + " ? gradColor(pc, first) : interpColor(pc, varies);\n"
         "}\n";
}

// Texture coordinates, level of detail and W of a triangle's sample point (rasterTriangle).
void emitExactTexTriangle(std::string& s, const FsKey& k) {
    s += "  if ((h.x & 15u) == " + std::to_string(tri::kKindTriangle) + "u) {\n"
         "    vec2 st = texAt(g_w);\n"
         "    g_st = vec2(finiteOr0(st.x), finiteOr0(st.y));\n";
    if (k.texLodMode == 0 || k.texLodMode == 2) {
        // 2×2 quads anchored at the triangle box's top-left pixel (scissored).
        s += "    uint qo = " + recTexel(tri::kSecondary) + ".w;\n"
             "    ivec2 q0 = ivec2(int(qo & 0xFFFFu), int(qo >> 16));\n"
             "    ivec2 q = q0 + ((pix - q0) & ivec2(~1));\n"
             "    vec3 a = weightsAt(q.x, q.y);\n";
    }
    if (k.texLodMode == 0) {
        // lodFromStepsF: texLog2(max(|Δs·w0|, |Δt·h0|)) in float.
        s += "    vec2 p00 = texAt(a), p10 = texAt(weightsAt(q.x + 1, q.y)), p01 = texAt(weightsAt(q.x, q.y + 1));\n"
             "    precise float ds = p10.x - p00.x;\n"
             "    precise float dt = p01.y - p00.y;\n"
             "    precise float ma = abs(ds * uintBitsToFloat(" + recTexel(tri::kS) + ".w));\n"
             "    precise float mb = abs(dt * uintBitsToFloat(" + recTexel(tri::kT) + ".w));\n"
             "    uint bits = floatBitsToUint(ma < mb ? mb : ma);\n"
             "    g_lod = float(int((bits >> 15) & 0xFFFFu) - 127 * 256) / 256.0;\n";
    }
    if (k.texLodMode == 2) {
        // Slope mode: clip W screen-linear at the quad's top-left pixel.
        s += "    g_wclip = finiteOr0(interpF(recF(" + recTexel(tri::kClipW) + "), a, wsumRecip()));\n";
    }
}

// Texture coordinates and level of detail of a rectangle's pixel (rasterRectangle).
void emitExactTexRect(std::string& s, const FsKey& k) {
    s += "  } else if ((h.x & 15u) == " + std::to_string(tri::kKindRect) + "u) {\n"
         // rasterRectangle: the row value advanced once per pair of rows, then once per pair of
         // columns, each a separately rounded float addition; the odd pixel of a pair adds half
         // a step (and the odd row of a pair half a row step) to the pair's value.
         "    uvec4 a = " + recTexel(tri::kRectStart) + ", b = " + recTexel(tri::kRectRow) + ";\n"
         "    ivec2 d = pix - ivec2(" + recTexel(tri::kRectBox) + ".xy);\n"
         "    vec2 stx = uintBitsToFloat(a.zw), sty = uintBitsToFloat(b.xy);\n"
         "    precise vec2 p = uintBitsToFloat(a.xy);\n"
         "    for (int i = 0; i < (d.y >> 1); ++i) p = p + sty;\n"
         "    for (int i = 0; i < (d.x >> 1); ++i) p = p + stx;\n"
         "    precise vec2 hx = 0.5 * stx;\n"
         "    precise vec2 hy = 0.5 * sty;\n"
         "    precise vec2 p10 = p + hx;\n"
         "    precise vec2 p01 = p + hy;\n"
         "    precise vec2 p11 = p + (hx + hy);\n"
         "    vec2 st = (d.y & 1) == 0 ? ((d.x & 1) == 0 ? p : p10) : ((d.x & 1) == 0 ? p01 : p11);\n"
         "    g_st = vec2(finiteOr0(st.x), finiteOr0(st.y));\n";
    if (k.texLodMode == 0) {
        // lodFromSteps on the quad's half steps: max(|Δs·w0|, |Δt·h0|) (float products of
        // floats round the same as the software model's double ones).
        s += "    precise float ds = p10.x - p.x;\n"
             "    precise float dt = p01.y - p.y;\n"
             "    precise float ma = abs(ds * uintBitsToFloat(b.z));\n"
             "    precise float mb = abs(dt * uintBitsToFloat(b.w));\n"
             "    uint bits = floatBitsToUint(ma < mb ? mb : ma);\n"
             "    g_lod = float(int((bits >> 15) & 0xFFFFu) - 127 * 256) / 256.0;\n";
    }
}

// exactTexInputs(pix): g_st, g_lod, g_wclip of the pixel for sampleTexture().
void emitExactTexInputs(std::string& s, const FsKey& k) {
    const std::string hdr = recTexel(tri::kHeader);
    s += "float finiteOr0(float v) { return (isnan(v) || isinf(v)) ? 0.0 : v; }\n";
    // texAt: through mode screen-linear; else weights w_i/w_i-clip, s = Σ·(1/Σ q).
    s += "vec2 texAt(vec3 w) {\n"
         "  vec3 S = recF(" + recTexel(tri::kS) + "), T = recF(" + recTexel(tri::kT) + ");\n"
         "  if (" + recFlag(tri::kFlagThrough) + ") return vec2(interpF(S, w, wsumRecip()), interpF(T, w, wsumRecip()));\n"
         "  precise vec3 a = w * recF(" + recTexel(tri::kRecipW) + ");\n"
         "  float qs = interpF(recF(" + recTexel(tri::kQ) + "), a, 1.0);\n"
         "  float qRecip = float(1.0lf / double(qs));\n"
         "  return vec2(interpF(S, a, qRecip), interpF(T, a, qRecip));\n"
         "}\n";
    s += "vec2 g_st;\n"
         "float g_lod, g_wclip;\n"
         "void exactTexInputs(ivec2 pix) {\n"
         "  uvec4 h = " + hdr + ";\n"
         "  g_lod = uintBitsToFloat(h.z);\n"
         "  g_wclip = uintBitsToFloat(h.w);\n";
    emitExactTexTriangle(s, k);
    emitExactTexRect(s, k);
    s += "  } else {\n"
         // Fragments: the software rasteriser's finished values.
         "    g_st = uintBitsToFloat(" + recTexel(tri::kRectStart) + ".xy);\n"
         "  }\n"
         "}\n";
}

void emitExactHelpers(std::string& s, const FsKey& k) {
    emitExactEdges(s);
    emitExactDepthColor(s);
    if (k.tex) emitExactTexInputs(s, k);
    if (k.fog) {
        const std::string hdr = recTexel(tri::kHeader);
        // fogToByte (raster.cpp, ge-rules.md §8.9) of the interpolated factor, or the record's byte.
        s += "int fogFactor() {\n"
             "  if (!" + recFlag(tri::kFlagFogVaries) + ") return int(" + hdr + ".y);\n"
             "  float f = interpF(recF(" + recTexel(tri::kFog) + "), g_w, wsumRecip());\n"
             "  uint b = floatBitsToUint(f);\n"
             "  if ((b & 0x80000000u) != 0u) return 0;\n"
             "  if (b >= 0x3F800000u) return 255;\n"
             "  precise float f256 = f * 256.0;\n"
             "  return int(f256);\n"
             "}\n";
    }
}

// The end of texel() for a CLUT texture over a buffer of format fb (c: the stored pixel): the
// pixel's bits give the index (the whole pixel for CLUT16 over a 16-bit buffer and CLUT32 over
// 8888, a byte or nibble of it for CLUT8/CLUT4, `bits` wide, perPixel of them), masked as
// ((t >> SFT) & MSK) and looked up in the palette resolved per masked value (ge-rules.md §6.4;
// hle/texture_decoder maskedPalette, which folds in CSA and the palette size).
void emitTargetClut(std::string& s, int fb, int bits, int perPixel) {
    if (fb == GE_FORMAT_8888) {
        s += "  uint raw = uint(c.r) | (uint(c.g) << 8) | (uint(c.b) << 16) | (uint(c.a) << 24);\n";
    } else {
        switch (fb) {
            case GE_FORMAT_565: s += "  uint raw = uint((c.r >> 3) | ((c.g >> 2) << 5) | ((c.b >> 3) << 11));\n"; break;
            case GE_FORMAT_5551:
                s += "  uint raw = uint((c.r >> 3) | ((c.g >> 3) << 5) | ((c.b >> 3) << 10) | ((c.a >> 7) << 15));\n";
                break;
            default: s += "  uint raw = uint((c.r >> 4) | ((c.g >> 4) << 4) | ((c.b >> 4) << 8) | ((c.a >> 4) << 12));\n"; break;
        }
    }
    if (bits)
        s += "  raw = (raw >> uint(((u / u_texScale) % " + std::to_string(perPixel) + ") * " + std::to_string(bits) +
             ")) & " + std::to_string((1 << bits) - 1) + "u;\n";
    s += "  int m = int((raw >> uint(u_clut.x)) & uint(u_clut.y));\n"
         "  return ivec4(texelFetch(u_clutTex, ivec2(m, 0), 0));\n"
         "}\n";
}

// Texel fetch from a render target sampled in place (FsKey::texTarget, hardware mode). u, v count
// the target's texels (u_texScale per PSP texel); wrap and clamp work on the scaled sizes (ref
// ge-rules.md §8.10: clamp to min(w, 512) − 1, repeat modulo the power-of-two size). The origin (x, y) of the
// texture in the target is u_texLevels[0].wx. The stored pixel (bit-replicated channels of the
// frame-buffer format) is what a texture of the same format decodes to; another 16-bit format
// re-encodes the buffer's 16 bits and decodes them as the texture's format (ge-rules.md §6.3).
void emitTargetTexel(std::string& s, const FsKey& k) {
    const int fb = k.texTarget - 1;
    s += "ivec4 texel(int lv, int u, int v) {\n"
         "  ivec4 L = u_texLevels[lv];\n"
         "  int W = min(L.y, 512) * u_texScale, H = min(L.z, 512) * u_texScale;\n";
    s += k.texClampU ? "  u = clamp(u, 0, W - 1);\n" : "  u = ((u % W) + W) % W;\n";
    s += k.texClampV ? "  v = clamp(v, 0, H - 1);\n" : "  v = ((v % H) + H) % H;\n";
    // CLUT4/CLUT8 over a buffer: k texels share one pixel (its bytes or nibbles, low first, ref
    // ge-rules.md §6.1). u counts the texture's texels times u_texScale, so the pixel's scaled column is u / k
    // and the texel's place within the pixel (u / u_texScale) mod k.
    const bool clut = k.texFormat >= GE_TFMT_CLUT4 && k.texFormat <= GE_TFMT_CLUT32;
    const int bits = k.texFormat == GE_TFMT_CLUT4 ? 4 : (k.texFormat == GE_TFMT_CLUT8 ? 8 : 0);
    const int perPixel = bits ? (fb == GE_FORMAT_8888 ? 32 : 16) / bits : 1;
    if (perPixel > 1)
        s += "  ivec4 c = ivec4(texelFetch(u_tex, ivec2(L.w + u / " + std::to_string(perPixel) + ", L.x + v), 0));\n";
    else
        s += "  ivec4 c = ivec4(texelFetch(u_tex, ivec2(L.w + u, L.x + v), 0));\n";
    if (clut) {
        emitTargetClut(s, fb, bits, perPixel);
        return;
    }
    if (fb == GE_FORMAT_8888 || fb == k.texFormat) {
        if (k.texFormat == GE_TFMT_5650) s += "  c.a = 255;\n";  // 5650 texels are opaque
        s += "  return c;\n}\n";
        return;
    }
    // The frame buffer's 16 bits (ge-rules.md §8.8 stored form: the high bits of each channel).
    switch (fb) {
        case GE_FORMAT_565: s += "  int b16 = (c.r >> 3) | ((c.g >> 2) << 5) | ((c.b >> 3) << 11);\n"; break;
        case GE_FORMAT_5551:
            s += "  int b16 = (c.r >> 3) | ((c.g >> 3) << 5) | ((c.b >> 3) << 10) | ((c.a >> 7) << 15);\n";
            break;
        default: s += "  int b16 = (c.r >> 4) | ((c.g >> 4) << 4) | ((c.b >> 4) << 8) | ((c.a >> 4) << 12);\n"; break;
    }
    // Decoded as the texture format, with bit replication (hle/pixel_format decodePixel16).
    switch (k.texFormat) {
        case GE_TFMT_5650:
            s += "  ivec3 q = ivec3(b16 & 31, (b16 >> 5) & 63, (b16 >> 11) & 31);\n"
                 "  return ivec4((q.r << 3) | (q.r >> 2), (q.g << 2) | (q.g >> 4), (q.b << 3) | (q.b >> 2), 255);\n";
            break;
        case GE_TFMT_5551:
            s += "  ivec3 q = ivec3(b16 & 31, (b16 >> 5) & 31, (b16 >> 10) & 31);\n"
                 "  return ivec4((q << 3) | (q >> 2), ((b16 >> 15) & 1) * 255);\n";
            break;
        default:
            s += "  return ivec4(b16 & 15, (b16 >> 4) & 15, (b16 >> 8) & 15, (b16 >> 12) & 15) * 17;\n";
            break;
    }
    s += "}\n";
}

// ---- fragment shader, one emitter per stage of the pixel pipeline ----
// The stages and their order are softmodel/pixel.cpp shadeNormal/shadeClear's (ge-rules.md §8.4):
// 1 texture function and secondary colour, 2 depth range, 3 alpha test, 4 fog, 5 colour test,
// 6–8 stencil and depth tests, 9 blending, dither and clamp, 10 the alpha byte (stencil), 11 logic
// op, 12 format conversion, write masks and the write. Declarations (uniforms, functions) come
// first, then main() calls the stages in that order; the depth range, a plain discard, runs
// before the colour work (what it drops cannot depend on it), and the texture is sampled before
// any discard (the implicit derivatives of the non-exact level of detail need the whole quad).

// What every emitter needs: the key, the switches derived from it and the text so far.
struct FsText {
    const FsKey& k;
    bool exact;          // HostCaps::exactInterp: inputs from the triangle record (tri)
    bool dst;            // the destination pixel is read (`dst`)
    bool depthInShader;  // the depth test runs here (DepthRead), not in GL
    bool stencilWrites;  // stencil test on a format with stencil bits (not 5650)
    std::string& s;
};

// Inputs, the colour output and the uniforms every program has.
void emitInterface(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    if (g.exact) {
        emitExactHelpers(s, k);
    } else {
        const char* colorInterp = k.flatShade ? "flat" : "noperspective";
        s += std::string(colorInterp) + " in vec4 v_color;\n";
        s += std::string(colorInterp) + " in vec3 v_color2;\n";
        s += "noperspective in vec4 v_tex;\n"
             "noperspective in float v_fog;\n"
             "noperspective in float v_z;\n";
    }
    if (k.dstRead == DstRead::FbFetch)
        s += "layout(location = 0) inout uvec4 o_color;\n";
    else
        s += "layout(location = 0) out uvec4 o_color;\n";
    // u_pixScale: render scale N of the hardware mode. gl_FragCoord counts the target's texels;
    // the dither matrix is indexed by the PSP pixel (ge-rules.md §8.4 step 9) and the level of detail is
    // per PSP pixel (ge-rules.md §6.6), so both divide by N.
    s += "uniform int u_dither[16];\n"
         "uniform int u_pixScale;\n"
         "uniform ivec4 u_keep;\n"
         "uniform ivec2 u_zRange;\n";
    if (k.dstRead == DstRead::Texture) s += "uniform usampler2D u_dstColor;\n";
    if (k.depthRead == DepthRead::Texture) s += "uniform sampler2D u_dstDepth;\n";
}

// texel(lv, u, v) from the decoded atlas. L.yz is the level's coordinate size 2^n, past 512 too;
// the atlas holds its min(2^n, 512) texels, all the index below can reach (geometry/texture_size.h
// texelClampMax, texelWrapMask).
void emitAtlasTexel(std::string& s, const FsKey& k) {
    s += "ivec4 texel(int lv, int u, int v) {\n"
         "  ivec4 L = u_texLevels[lv];\n";
    // Clamp: 0 … min(w, 512) − 1; repeat: & (w − 1) & 511 (ge-rules.md §8.10).
    s += k.texClampU ? "  u = clamp(u, 0, min(L.y, 512) - 1);\n" : "  u = u & (L.y - 1) & 511;\n";
    s += k.texClampV ? "  v = clamp(v, 0, min(L.z, 512) - 1);\n" : "  v = v & (L.z - 1) & 511;\n";
    s += "  return ivec4(texelFetch(u_tex, ivec2(u, L.x + v), 0));\n"
         "}\n";
}

// Nearest and bilinear filtering of one level. Texel coordinates with 8 fraction bits; nearest
// takes the integer part, linear moves the sample point half a texel and keeps a 4-bit fraction
// (ge-rules.md §8.10). The scale is the unclamped 2^n of u_texLevels.yz (geometry/texture_size.h:
// a PSP reads texel 2 at pixel 0 of a 1024-wide texture over 256 pixels).
void emitTexelFilters(std::string& s, const FsKey& k) {
    const std::string scale = k.texTarget ? "u_texScale" : "1";
    // Truncated toward zero; out of int range (and NaN) → INT_MIN (sampler.cpp texelFixed).
    // Linear rounds to nearest, ties to even, instead (sampler.cpp texelFixedRound), unless the
    // key asks for the PSP's truncation (texLinearTrunc).
    s += "int fixc(float p) { return (p >= -2147483648.0 && p < 2147483648.0) ? int(p) : int(0x80000000u); }\n";
    s += k.texLinearTrunc
             ? "int fixr(float p) { return fixc(p); }\n"
             : "int fixr(float p) { return (p >= -2147483648.0 && p < 2147483648.0) ? int(roundEven(p)) : int(0x80000000u); }\n";
    s += // A render-target texture is addressed in its own (scaled) texels: u_texScale per texel.
         "ivec2 fixCoord(int lv, vec2 st) {\n"
         "  vec2 p = st * (vec2(u_texLevels[lv].yz * " + scale + ") * 256.0);\n"
         "  return ivec2(fixc(p.x), fixc(p.y));\n"
         "}\n"
         "ivec2 fixCoordRound(int lv, vec2 st) {\n"
         "  vec2 p = st * (vec2(u_texLevels[lv].yz * " + scale + ") * 256.0);\n"
         "  return ivec2(fixr(p.x), fixr(p.y));\n"
         "}\n"
         "ivec4 sampleNearest(int lv, vec2 st) {\n"
         "  ivec2 p = fixCoord(lv, st) >> 8;\n"
         "  return texel(lv, p.x, p.y);\n"
         "}\n"
         // p − 128 split so it cannot overflow: integer part and 4-bit fraction.
         "ivec4 sampleLinear(int lv, vec2 st) {\n"
         "  ivec2 q = fixCoordRound(lv, st);\n"
         "  ivec2 lo = q & 255;\n"
         "  ivec2 i0 = (q >> 8) - ivec2(lessThan(lo, ivec2(128)));\n"
         "  ivec2 f = ((lo - 128) & 255) >> 4;\n"
         "  ivec4 c00 = texel(lv, i0.x, i0.y), c10 = texel(lv, i0.x + 1, i0.y);\n"
         "  ivec4 c01 = texel(lv, i0.x, i0.y + 1), c11 = texel(lv, i0.x + 1, i0.y + 1);\n"
         "  return (c00 * ((16 - f.x) * (16 - f.y)) + c10 * (f.x * (16 - f.y)) +\n"
         "          c01 * ((16 - f.x) * f.y) + c11 * (f.x * f.y)) >> 8;\n"
         "}\n";
}

// `int lod`: the level of detail in 1/16 steps (ge-rules.md §6.6) before the bias.
void emitLevelOfDetail(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    const bool varies = k.texMip || k.texMinLinear != k.texMagLinear;  // else nothing reads it
    if (g.exact && k.texLodMode == 0 && varies) {
        // sampler.cpp levelOfDetail16, mode 0.
        s += "  float x16 = g_lod * 16.0;\n"
             "  int lod = x16 >= 4096.0 ? 4096 : (x16 > -4096.0 ? int(floor(x16)) : -4096);\n";
    } else if (g.exact && k.texLodMode == 2) {
        // sampler.cpp levelOfDetail16, mode 2: texLog2x16(2·W·TSLOPE).
        s += "  precise float m = 2.0 * g_wclip * u_texSlope;\n"
             "  int lod = clamp(int((floatBitsToUint(m) >> 19) & 0xFFFu) - 127 * 16, -4096, 4096);\n";
    } else if (k.texLodMode == 0 && varies) {
        s += "  vec2 size0 = vec2(u_texLevels[0].yz);\n"
             "  float m = max(abs(dFdx(st.x)) * size0.x, abs(dFdy(st.y)) * size0.y) * float(max(u_pixScale, 1));\n"
             "  int lod = m > 0.0 ? int(floor(clamp(log2(m), -64.0, 64.0) * 16.0)) : -1024;\n";
    } else if (k.texLodMode == 2) {
        s += "  float m = u_texSlope * v_tex.w;\n"
             "  int lod = m > 0.0 ? int(floor((clamp(log2(m), -64.0, 64.0) + 1.0) * 16.0)) : -1024;\n";
    } else {
        s += "  int lod = 0;\n";
    }
}

// sampleTexture(): the level(s) chosen from the level of detail, filtered, mipmaps blended.
void emitSampleTexture(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    s += "ivec4 sampleTexture() {\n";
    s += g.exact ? "  vec2 st = g_st;\n" : "  vec2 st = v_tex.xy / v_tex.z;\n";
    emitLevelOfDetail(g);
    s += "  lod += u_texParams.y;\n"
         "  bool minify = lod > 0;\n"
         "  int level = 0;\n"
         "  int frac = 0;\n";
    if (k.texMip) {
        s += "  if (minify && u_texParams.x > 0) {\n"
             "    int d = min(lod, u_texParams.x * 16);\n";
        if (k.texMip == 2)
            s += "    level = d >> 4;\n"
                 "    frac = level < u_texParams.x ? (d & 15) : 0;\n";
        else
            s += "    level = (d + 8) >> 4;\n";
        s += "  }\n";
    }
    if (k.texMinLinear == k.texMagLinear) {
        s += k.texMinLinear ? "  ivec4 c = sampleLinear(level, st);\n" : "  ivec4 c = sampleNearest(level, st);\n";
        if (k.texMip == 2)
            s += std::string("  if (frac > 0) c = (") + (k.texMinLinear ? "sampleLinear" : "sampleNearest") +
                 "(level + 1, st) * frac + c * (16 - frac)) >> 4;\n";
    } else {
        s += "  bool lin = minify ? ";
        s += k.texMinLinear ? "true" : "false";
        s += " : ";
        s += k.texMagLinear ? "true" : "false";
        s += ";\n"
             "  ivec4 c = lin ? sampleLinear(level, st) : sampleNearest(level, st);\n";
        if (k.texMip == 2)
            s += "  if (frac > 0) c = ((lin ? sampleLinear(level + 1, st) : sampleNearest(level + 1, st)) * frac"
                 " + c * (16 - frac)) >> 4;\n";
    }
    s += "  return c;\n"
         "}\n";
}

// Texture sampling declarations (ge-rules.md §8.10, §6.6): uniforms, texel fetch, filters,
// sampleTexture().
void emitTextureDecls(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    if (!k.tex) return;
    s += "uniform usampler2D u_tex;\n"
         "uniform ivec4 u_texLevels[8];\n"
         "uniform ivec2 u_texParams;\n"
         "uniform float u_texSlope;\n"
         "uniform ivec3 u_texEnv;\n";
    if (k.texTarget) s += "uniform int u_texScale;\n";
    if (k.texTarget && k.texFormat >= GE_TFMT_CLUT4) s += "uniform usampler2D u_clutTex;\nuniform ivec2 u_clut;\n";
    if (!k.texTarget)
        emitAtlasTexel(s, k);
    else
        emitTargetTexel(s, k);
    emitTexelFilters(s, k);
    emitSampleTexture(g);
}

// Fog's uniform and, without the exact helpers' version, fogFactor().
void emitFogDecls(FsText& g) {
    if (g.k.fog && g.exact)
        g.s += "uniform ivec3 u_fogColor;\n";  // fogFactor() in the exact helpers
    else if (g.k.fog)
        g.s += "uniform ivec3 u_fogColor;\n"
               // f becomes 8-bit: 0 at or below 0, 255 at or above 1, else floor(f·256) (ge-rules.md §8.9).
               "int fogFactor() {\n"
               "  if (!(v_fog > 0.0)) return 0;\n"
               "  if (v_fog >= 1.0) return 255;\n"
               "  return min(int(floor(v_fog * 256.0)), 255);\n"
               "}\n";
}

// The tests' and blending's uniforms and compare functions.
void emitTestDecls(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    // alphaTest 9: the reference renderer's implicit "alpha != 0" test (geometry/reference_rules.h
    // referenceDropsZeroAlpha), which replaces an off or trivially true alpha test: no uniforms.
    if (k.alphaTest && k.alphaTest != 9) {
        s += "uniform ivec2 u_alphaTest;\n";
        emitCompare(s, "alphaCompare", k.alphaTest - 1);
    }
    if (k.colorTest) s += "uniform ivec3 u_colorRef;\nuniform ivec3 u_colorMask;\n";
    if (k.stencilTest) {
        s += "uniform ivec2 u_stencil;\n";
        emitCompare(s, "stencilCompare", k.stencilTest - 1);
    }
    if (g.depthInShader) emitCompare(s, "depthCompare", k.depthTest - 1);
    if (k.blend) s += "uniform ivec3 u_fixA;\nuniform ivec3 u_fixB;\n";
}

// Storage conversion (truncate to the frame-buffer format, keep the replicated form) and the
// stencil operations.
void emitFormatDecls(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    s += "ivec4 formatBits() {\n";
    switch (k.fbFormat & 3) {
        case 0: s += "  return ivec4(0xF8, 0xFC, 0xF8, 0x00);\n"; break;
        case 1: s += "  return ivec4(0xF8, 0xF8, 0xF8, 0x80);\n"; break;
        case 2: s += "  return ivec4(0xF0);\n"; break;
        default: s += "  return ivec4(0xFF);\n"; break;
    }
    s += "}\n"
         "ivec4 expandBits(ivec4 t) {\n";
    switch (k.fbFormat & 3) {
        case 0: s += "  return ivec4(t.r | (t.r >> 5), t.g | (t.g >> 6), t.b | (t.b >> 5), 255);\n"; break;
        case 1: s += "  return ivec4(t.r | (t.r >> 5), t.g | (t.g >> 5), t.b | (t.b >> 5), t.a != 0 ? 255 : 0);\n"; break;
        case 2: s += "  return t | (t >> 4);\n"; break;
        default: s += "  return t;\n"; break;
    }
    s += "}\n";
    if (g.stencilWrites) {
        // Stencil operations per frame-buffer format (ge-rules.md §8.7). s is the 8-bit stored value.
        s += "int stencilOp(int op, int s) {\n"
             "  if (op == 1) return 0;\n"
             "  if (op == 2) return u_stencil.x;\n"
             "  if (op == 3) return ~s & 255;\n";
        switch (k.fbFormat & 3) {
            case 1: s += "  if (op == 4) return 255;\n  if (op == 5) return 0;\n"; break;
            case 2: s += "  if (op == 4) return min(s + 0x10, 255);\n  if (op == 5) return max(s - 0x10, 0);\n"; break;
            default: s += "  if (op == 4) return min(s + 1, 255);\n  if (op == 5) return max(s - 1, 0);\n"; break;
        }
        s += "  return s;\n"
             "}\n";
    }
}

// main() up to the colour work: the pixel, its coverage and Z, the texel (sampled before any
// discard), the depth range (stage 2) and the destination pixel.
void emitFragmentStart(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    s += "void main() {\n"
         "  ivec2 pix = ivec2(gl_FragCoord.xy);\n";
    if (g.exact) {
        // Sample point in 1/16 units; edge values as rasterTriangle (only triangles use them).
        s += "  g_cx = int64_t(16 * pix.x + sampleOffset());\n"
             "  g_cy = int64_t(16 * pix.y + sampleOffset());\n"
             "  if (edgeTestFails(g_cx, g_cy)) discard;\n"
             "  g_w = weightsAt(pix.x, pix.y);\n"
             "  int z = " + zExpr() + ";\n";
        if (k.tex) s += "  exactTexInputs(pix);\n";
    } else {
        // Z is linear in screen space and rounded to nearest (as rasterTriangle rounds it).
        s += "  int z = int(clamp(floor(v_z + 0.5), 0.0, 65535.0));\n";
    }
    s += "  float zOut = float(z) * (1.0 / 65536.0);\n";
    if (k.tex) s += "  ivec4 t = sampleTexture();\n";  // before any discard: derivatives
    if (k.depthRange)
        s += "  if (z < u_zRange.x || z > u_zRange.y) discard;\n";  // ge-rules.md §8.4 step 2
    if (k.dstRead == DstRead::FbFetch) s += "  ivec4 dst = ivec4(o_color);\n";
    if (k.dstRead == DstRead::Texture) s += "  ivec4 dst = ivec4(texelFetch(u_dstColor, pix, 0));\n";
    if (g.dst && k.fbFormat == 0) s += "  dst.a = 0;\n";  // 5650 reads Ad = 0 (ge-rules.md §8.8)
}

// Stage 1: the texture function (exact forms of ge-rules.md §8.3) with colour doubling, then the
// secondary colour and the clamp (ge-rules.md §8.4 step 1). Clear mode: the vertex colour as is.
void emitTextureFunction(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    if (g.exact)
        s += "  ivec4 prim = vertexColor(" + recTexel(tri::kColors) + ".xyz, (" + recTexel(tri::kHeader) + ".x & " +
             std::to_string(tri::kFlagColorVaries) + "u) != 0u, 0);\n";
    else
        s += "  ivec4 prim = ivec4(v_color + vec4(1.0 / 1024.0));\n";
    s += "  ivec4 c;\n";
    if (k.clearMode) {
        s += "  c = prim;\n";
        return;
    }
    if (g.exact)
        s += "  ivec3 sec = vertexColor(" + recTexel(tri::kSecondary) + ".xyz, (" + recTexel(tri::kHeader) +
             ".x & " + std::to_string(tri::kFlagSecVaries) + "u) != 0u, 4).rgb;\n";
    else
        s += "  ivec3 sec = ivec3(v_color2 + vec3(1.0 / 1024.0));\n";
    if (k.tex) {
        const bool d = k.texDouble;
        s += "  ivec4 p = prim;\n";
        const char* modA = k.texAlpha ? "((p.a + 1) * t.a) >> 8" : "p.a";
        switch (k.texFunc) {
            case 0:  // MODULATE
                s += d ? "  c.rgb = ((p.rgb + 1) * t.rgb * 2) >> 8;\n" : "  c.rgb = ((p.rgb + 1) * t.rgb) >> 8;\n";
                s += std::string("  c.a = ") + modA + ";\n";
                break;
            case 1:  // DECAL
                if (k.texAlpha)
                    s += std::string("  c.rgb = ((p.rgb + 1) * (255 - t.a) + (t.rgb + 1) * t.a) >> ") + (d ? "7" : "8") +
                         ";\n";
                else
                    s += d ? "  c.rgb = t.rgb * 2;\n" : "  c.rgb = t.rgb;\n";
                s += "  c.a = p.a;\n";
                break;
            case 2:  // BLEND
                s += std::string("  c.rgb = ((ivec3(255) - t.rgb) * p.rgb + t.rgb * u_texEnv + 255) >> ") +
                     (d ? "7" : "8") + ";\n";
                s += std::string("  c.a = ") + modA + ";\n";
                break;
            case 3:  // REPLACE
                s += d ? "  c.rgb = t.rgb * 2;\n" : "  c.rgb = t.rgb;\n";
                s += k.texAlpha ? "  c.a = t.a;\n" : "  c.a = p.a;\n";
                break;
            default:  // ADD
                s += d ? "  c.rgb = (p.rgb + t.rgb) * 2;\n" : "  c.rgb = p.rgb + t.rgb;\n";
                s += std::string("  c.a = ") + modA + ";\n";
                break;
        }
    } else {
        s += "  c = prim;\n";
    }
    s += "  c.rgb = clamp(c.rgb + sec, 0, 255);\n"
         "  c.a = clamp(c.a, 0, 255);\n";
}

// Stage 3 (not in clear mode).
void emitAlphaTest(FsText& g) {
    if (g.k.clearMode) return;
    if (g.k.alphaTest == 9)
        g.s += "  if (c.a == 0) discard;\n";
    else if (g.k.alphaTest)
        g.s += "  if (!alphaCompare(c.a & u_alphaTest.y, u_alphaTest.x & u_alphaTest.y)) discard;\n";
}

// Stage 4 (not in clear mode), ge-rules.md §8.3.
void emitFog(FsText& g) {
    if (g.k.clearMode || !g.k.fog) return;
    g.s += "  {\n"
           "    int f = fogFactor();\n"
           "    c.rgb = (c.rgb * f + u_fogColor * (255 - f) + 255) >> 8;\n"
           "  }\n";
}

// Stage 5 (not in clear mode): CTEST 0 NEVER, 1 ALWAYS, 2 EQUAL, 3 NOTEQUAL.
void emitColorTest(FsText& g) {
    const FsKey& k = g.k;
    if (k.clearMode || !k.colorTest) return;
    if (k.colorTest - 1 == 0)
        g.s += "  discard;\n";
    else
        g.s += std::string("  if (") + (k.colorTest - 1 == 2 ? "!" : "") +
               "all(equal(c.rgb & u_colorMask, u_colorRef & u_colorMask))) discard;\n";
}

// Stages 6–8: the stencil test and (in the shader) the depth test, with the stencil operation of
// their outcome (ge-rules.md §8.4 steps 6–8). A failed test with a stencil to write keeps the
// colour (keepColor) instead of discarding.
void emitStencilDepthTests(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    if (!k.stencilTest) return;
    s += "  int dstS = dst.a;\n"
         "  int newS = dstS;\n";
    if (g.depthInShader) {
        if (k.depthRead == DepthRead::Fetch)
            s += "  float oldDepth = gl_LastFragDepthARM;\n";
        else
            s += "  float oldDepth = texelFetch(u_dstDepth, pix, 0).r;\n";
    } else {
        s += "  float oldDepth = zOut;\n";
    }
    // Compare order as PPSSPP/JPCSP: (ref & mask) OP (stored & mask) (ge-rules.md §8.7).
    s += "  bool keepColor = false;\n"
         "  if (!stencilCompare(u_stencil.x & u_stencil.y, dstS & u_stencil.y)) {\n";
    if (g.stencilWrites) s += "    newS = stencilOp(" + std::to_string(k.sopFail) + ", dstS);\n";
    s += "    keepColor = true;\n"
         "  } else {\n";
    if (g.depthInShader) {
        s += "    int oldZ = int(oldDepth * 65536.0 + 0.5);\n"
             "    if (!depthCompare(z, oldZ)) {\n";
        if (g.stencilWrites) s += "      newS = stencilOp(" + std::to_string(k.sopZFail) + ", dstS);\n";
        s += "      keepColor = true;\n"
             "    } else {\n";
        if (g.stencilWrites) s += "      newS = stencilOp(" + std::to_string(k.sopZPass) + ", dstS);\n";
        s += "    }\n";
    } else if (g.stencilWrites) {
        s += "    newS = stencilOp(" + std::to_string(k.sopZPass) + ", dstS);\n";
    }
    s += "  }\n";
    if (!g.stencilWrites) s += "  if (keepColor) discard;\n";
}

// Stage 9: blending, unclamped (ge-rules.md §8.4 step 9, §3.10).
void emitBlend(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    s += "  ivec3 rgb = c.rgb;\n";
    if (!k.blend) return;
    s += "  {\n"
         "    ivec3 cs = c.rgb, cd = dst.rgb;\n"
         "    int as = c.a, ad = dst.a;\n";
    const int eq = k.blend - 1;
    if (eq <= 2) {
        s += "    ivec3 fa = " + blendFactor(k.blendA, true) + ";\n";
        s += "    ivec3 fb = " + blendFactor(k.blendB, false) + ";\n";
        s += "    ivec3 ts = ((2 * cs + 1) * (2 * fa + 1)) >> 10;\n"
             "    ivec3 td = ((2 * cd + 1) * (2 * fb + 1)) >> 10;\n";
        if (eq == 0) s += "    rgb = ts + td;\n";
        if (eq == 1) s += "    rgb = max(ts - td, ivec3(0));\n";
        if (eq == 2) s += "    rgb = max(td - ts, ivec3(0));\n";
    } else if (eq == 3) {
        s += "    rgb = min(cs, cd);\n";
    } else if (eq == 4) {
        s += "    rgb = max(cs, cd);\n";
    } else {
        s += "    rgb = abs(cs - cd);\n";
    }
    s += "  }\n";
}

// Stage 9, end: dither by the PSP pixel (ge-rules.md §8.3), then the clamp.
void emitDither(FsText& g) {
    if (g.k.dither) g.s += "  ivec2 psp = pix / max(u_pixScale, 1);\n  rgb += ivec3(u_dither[(psp.y & 3) * 4 + (psp.x & 3)]);\n";
    g.s += "  rgb = clamp(rgb, 0, 255);\n";
}

// Stage 10: the alpha byte is the stencil (ge-rules.md §8.4 step 10, §8.7).
void emitAlphaByte(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    s += "  int a = ";
    if (k.clearMode)
        s += k.clearAlpha ? "c.a" : (g.dst ? "dst.a" : "0");
    else if (g.stencilWrites)
        s += "newS";
    else
        s += g.dst ? "dst.a" : "0";
    s += ";\n";
}

// Stage 11: the logic op on RGB; then the colour the draw leaves unchanged (clear mode without
// CEN, a failed stencil or depth test that still writes the stencil).
void emitLogicOp(FsText& g) {
    const FsKey& k = g.k;
    std::string& s = g.s;
    if (k.logicOp) {
        s += "  {\n"
             "    ivec3 s = rgb, d = dst.rgb;\n"
             "    rgb = (" + logicExpr(k.logicOp - 1) + ") & 255;\n"
             "  }\n";
    }
    if (k.clearMode && !k.clearColor && g.dst) s += "  rgb = dst.rgb;\n";
    if (k.stencilTest && g.stencilWrites) s += "  if (keepColor) rgb = dst.rgb;\n";
}

// Stage 12: masks, format truncation, write (ge-rules.md §8.4 step 12, §8.8), and the depth.
void emitWrite(FsText& g) {
    std::string& s = g.s;
    s += "  ivec4 bits = formatBits();\n"
         "  ivec4 res = ivec4(rgb, a) & bits;\n";
    if (g.dst) s += "  res = (res & ~u_keep) | (dst & bits & u_keep);\n";
    s += "  o_color = uvec4(expandBits(res));\n";
    if (g.depthInShader) {
        s += "  gl_FragDepth = keepColor";
        s += g.k.depthWrite ? " ? oldDepth : zOut;\n" : " ? oldDepth : oldDepth;\n";
    } else {
        s += "  gl_FragDepth = zOut;\n";
    }
    s += "}\n";
}

}  // namespace

bool generateVertexShader(const VsKey& key, const HostCaps& caps, std::string& out, std::string* err) {
    (void)err;
    std::string s;
    header(s, caps, nullptr, describe(key));
    if (caps.exactInterp) {
        // The triangle's record (gl_VertexID / 3: three vertices per triangle, glDrawArrays
        // `first` included) goes to the fragment shader as flat varyings.
        s += "layout(location = 0) in vec3 a_pos;\n"
             "uniform vec2 u_ndcScale;\n"
             "uniform usamplerBuffer u_tris;\n"
             "flat out uvec4 v_rec[" + std::to_string(tri::kTexels) + "];\n"
             "void main() {\n"
             "  int base = (gl_VertexID / 3) * " + std::to_string(tri::kTexels) + ";\n"
             "  for (int i = 0; i < " + std::to_string(tri::kTexels) + "; ++i) v_rec[i] = texelFetch(u_tris, base + i);\n"
             "  gl_Position = vec4(a_pos.x * u_ndcScale.x - 1.0, a_pos.y * u_ndcScale.y - 1.0, 0.0, 1.0);\n"
             "}\n";
        out = std::move(s);
        return true;
    }
    // Everything arrives in drawing coordinates from the CPU transform; GL only rasterises.
    // Colours, Z and fog are linear in screen space (ge-rules.md §8.1): noperspective. Texture
    // coordinates arrive pre-multiplied by 1/w and are divided per pixel in the fragment shader.
    const char* colorInterp = key.flatShade ? "flat" : "noperspective";
    s += "layout(location = 0) in vec3 a_pos;\n"
         "layout(location = 1) in vec4 a_color;\n"
         "layout(location = 2) in vec3 a_color2;\n"
         "layout(location = 3) in vec4 a_tex;\n"
         "layout(location = 4) in float a_fog;\n"
         "uniform vec2 u_ndcScale;\n";
    s += std::string(colorInterp) + " out vec4 v_color;\n";
    s += std::string(colorInterp) + " out vec3 v_color2;\n";
    s += "noperspective out vec4 v_tex;\n"
         "noperspective out float v_fog;\n"
         "noperspective out float v_z;\n"
         "void main() {\n"
         "  v_color = a_color;\n"
         "  v_color2 = a_color2;\n"
         "  v_tex = a_tex;\n"
         "  v_fog = a_fog;\n"
         "  v_z = a_pos.z;\n"
         // The target's row 0 is drawing row 0; with GL's lower-left window origin this makes
         // llvmpipe's fill convention the GE's top-left rule (min-x and min-y edges drawn).
         "  gl_Position = vec4(a_pos.x * u_ndcScale.x - 1.0, a_pos.y * u_ndcScale.y - 1.0, 0.0, 1.0);\n"
         "}\n";
    out = std::move(s);
    return true;
}

bool generateFragmentShader(const FsKey& k, const HostCaps& caps, std::string& out, std::string* err) {
    if (k.dstRead == DstRead::FbFetch && !caps.fbFetch) {
        if (err) *err = "framebuffer fetch requested but not available";
        return false;
    }
    if (k.depthRead == DepthRead::Fetch && !caps.depthFetch) {
        if (err) *err = "depth fetch requested but not available";
        return false;
    }
    if (k.depthRead != DepthRead::None && k.dstRead == DstRead::None) {
        if (err) *err = "depth read without colour read";
        return false;
    }
    std::string s;
    header(s, caps, &k, describe(k));
    FsText g{k, caps.exactInterp != 0, k.dstRead != DstRead::None, k.depthRead != DepthRead::None,
             k.stencilTest && k.fbFormat != 0, s};
    // Declarations.
    emitInterface(g);
    emitTextureDecls(g);
    emitFogDecls(g);
    emitTestDecls(g);
    emitFormatDecls(g);
    // main(), stage by stage.
    emitFragmentStart(g);
    emitTextureFunction(g);
    emitAlphaTest(g);
    emitFog(g);
    emitColorTest(g);
    emitStencilDepthTests(g);
    emitBlend(g);
    emitDither(g);
    emitAlphaByte(g);
    emitLogicOp(g);
    emitWrite(g);
    out = std::move(s);
    return true;
}

}  // namespace ge::shadergen
