// SPDX-License-Identifier: MIT
// GLSL generator of the GL hardware mode's vertex shader (see hw_vertex.h).
//
// Every statement mirrors a line of the CPU code all backends run (named in the comments), in the
// same float operation order: each arithmetic result is assigned to a `precise` variable, so the
// driver neither fuses multiply-adds (the CPU is built with -ffp-contract=off) nor reassociates.
// Float divisions go through double (the quotient rounded once to float is the correctly rounded
// float quotient, whatever the driver's float division is); normalisations use double sums and
// sqrt as geometry/lighting normalizeOr001 does; pow (lighting exponents) is evaluated in double
// and rounded once, which matches glibc's powf except where powf itself is not correctly rounded.
//
// The vertex shader hands on the CPU's ClipVertex (hw_vertex.h); the discard rules, near-plane
// clipping and culling, which need the whole primitive, are the geometry shader's (hw_geometry.cpp),
// exactly as translator/vertex_pipeline.cpp does them.
#include <string>

#include "shadergen/glsl_common.h"
#include "shadergen/hw_uniform_text.h"
#include "shadergen/hw_vertex.h"

namespace ge::shadergen {
namespace {

using namespace hwtext;

const char* const kXyz[3] = {"x", "y", "z"};

// ---- helper functions (fixed text; the float class, fdiv and projectToScreen helpers are
// glsl_common.h's, shared with the geometry shader) ----
const char* const kFetchHelpers = R"(uint rb(int a) { return texelFetch(u_vtx, a).r; }
uint r16(int a) { return rb(a) | (rb(a + 1) << 8); }
uint r32(int a) { return r16(a) | (r16(a + 2) << 16); }
float rf32(int a) { return uintBitsToFloat(r32(a)); }
float rs8(int a) { return float(int(rb(a) << 24) >> 24); }
float rs16(int a) { return float(int(r16(a) << 16) >> 16); }
// GE colour formats expanded by bit replication (hle/pixel_format.h decode5650/5551/4444).
ivec4 col5650(uint v) {
  uvec4 c = uvec4(v & 31u, (v >> 5) & 63u, (v >> 11) & 31u, 255u);
  return ivec4((c.x << 3) | (c.x >> 2), (c.y << 2) | (c.y >> 4), (c.z << 3) | (c.z >> 2), 255u);
}
ivec4 col5551(uint v) {
  uvec3 c = uvec3(v & 31u, (v >> 5) & 31u, (v >> 10) & 31u);
  return ivec4(ivec3((c << 3) | (c >> 2)), (v & 0x8000u) != 0u ? 255 : 0);
}
ivec4 col4444(uint v) { return ivec4(uvec4(v, v >> 4, v >> 8, v >> 12) & 15u) * 17; }
)";
const char* const kSignHelpers = R"(bool signBit(float x) { return (floatBitsToUint(x) & 0x80000000u) != 0u; }
float posInf() { return uintBitsToFloat(0x7F800000u); }
)";
const char* const kGeMathHelpers = R"(// One matrix term as the GE forms it (geometry/transform.cpp geTerm): a zero or denormal factor
// gives 0 whatever the other is; exponent 255 is an ordinary exponent (±1.m·2^128), evaluated as
// (1.m·2^64)·b·2^64 — the exact product rounded once, as the CPU's double product.
float geTermSpecial(float a, float b) {
  bool ea = notFinite(a), eb = notFinite(b);
  if (ea && eb) return uintBitsToFloat(((floatBitsToUint(a) ^ floatBitsToUint(b)) & 0x80000000u) | 0x7F800000u);
  float x = ea ? uintBitsToFloat((floatBitsToUint(a) & 0x807FFFFFu) | 0x3F800000u) * 18446744073709551616.0 : a;
  float y = eb ? uintBitsToFloat((floatBitsToUint(b) & 0x807FFFFFu) | 0x3F800000u) * 18446744073709551616.0 : b;
  PRECISE float p = x * y;
  PRECISE float r = p * 18446744073709551616.0;
  return r;
}
float geTerm(float a, float b) {
  uint ea = floatBitsToUint(a) & 0x7F800000u, eb = floatBitsToUint(b) & 0x7F800000u;
  if (ea == 0u || eb == 0u) return 0.0;
  if (ea == 0x7F800000u || eb == 0x7F800000u) return geTermSpecial(a, b);
  PRECISE float r = a * b;
  return r;
}
// Four terms at once (one matrix column times one coordinate).
vec4 geTerm4(vec4 a, vec4 b) {
  uvec4 ea = floatBitsToUint(a) & 0x7F800000u, eb = floatBitsToUint(b) & 0x7F800000u;
  PRECISE vec4 r = a * b;
  bvec4 big = bvec4(uvec4(equal(ea, uvec4(0x7F800000u))) | uvec4(equal(eb, uvec4(0x7F800000u))));
  if (any(big))
    for (int i = 0; i < 4; ++i)
      if (big[i]) r[i] = geTermSpecial(a[i], b[i]);
  bvec4 zero = bvec4(uvec4(equal(ea, uvec4(0u))) | uvec4(equal(eb, uvec4(0u))));
  return mix(r, vec4(0.0), zero);
}
// geometry/lighting normalizeOr001: double sum of squares and sqrt, float length, float
// divisions; a zero or non-finite length gives (0, 0, 1). Returns the length (0 then).
float normalizeOr001(inout vec3 v) {
#ifdef GE_FP64
  PRECISE double l2 = (double(v.x) * double(v.x) + double(v.y) * double(v.y)) + double(v.z) * double(v.z);
  float len = float(sqrt(l2));
#else
  PRECISE float l2 = (v.x * v.x + v.y * v.y) + v.z * v.z;
  float len = sqrt(l2);
#endif
  if (len <= 0.0 || notFinite(len)) {
    v = vec3(0.0, 0.0, 1.0);
    return 0.0;
  }
  v = vec3(fdiv(v.x, len), fdiv(v.y, len), fdiv(v.z, len));
  return len;
}
// powf(x, y) for x > 0, y > 0 (or +NaN): log and exp in double, rounded once to float.
float gePow(float x, float y) {
  if (x == 1.0) return 1.0;
  if (isNan(y)) return y;
  if (notFinite(y)) return x < 1.0 ? 0.0 : posInf();
  if (notFinite(x)) return posInf();
#ifdef GE_FP64
  uint bx = floatBitsToUint(x);
  int e = int(bx >> 23) - 127;
  if ((bx >> 23) == 0u) {  // denormal x: scale by 2^64 first
    bx = floatBitsToUint(x * 18446744073709551616.0);
    e = int(bx >> 23) - 191;
  }
  double m = double(uintBitsToFloat((bx & 0x7FFFFFu) | 0x3F800000u));
  if (m > 1.4142135623730951lf) {
    m = m * 0.5lf;
    e = e + 1;
  }
  // ln m = 2·atanh(t), t = (m − 1)/(m + 1), |t| ≤ 0.172: the series to t^29.
  PRECISE double t = (m - 1.0lf) / (m + 1.0lf);
  PRECISE double t2 = t * t;
  PRECISE double p = 1.0lf / 29.0lf;
  for (int k = 13; k >= 0; --k) p = p * t2 + 1.0lf / double(2 * k + 1);
  // ln x = e·ln2 (ln2 in a high part exact for any e and a low part) + ln m.
  PRECISE double lnx = double(e) * 6.93147180369123816490e-01lf +
                       (double(e) * 1.90821492927058770002e-10lf + 2.0lf * t * p);
  PRECISE double z = double(y) * lnx;
  if (z > 89.0lf) return posInf();
  if (z < -104.0lf) return 0.0;
  // e^z = 2^n·e^r, |r| ≤ ln2/2: Taylor series to r^16.
  double nf = floor(z * 1.44269504088896338700e+00lf + 0.5lf);
  PRECISE double r = (z - nf * 6.93147180369123816490e-01lf) - nf * 1.90821492927058770002e-10lf;
  PRECISE double q = 1.0lf;
  for (int k = 16; k >= 1; --k) q = q * (r / double(k)) + 1.0lf;
  double scale = packDouble2x32(uvec2(0u, uint(int(nf) + 1023) << 20));
  PRECISE double res = q * scale;
  return float(res);
#else
  return pow(x, y);
#endif
}
// geometry/lighting lightPow: exponent ≤ 0 (or a negative NaN) → 1; a base ≤ 0 stays as it is.
float lightPow(float base, float e) {
  if (e <= 0.0 || (isNan(e) && signBit(e))) return 1.0;
  if (base > 0.0) return gePow(base, e);
  return base;
}
// geometry/lighting lightScale: s = min(512, ceil(512·k + 1)).
int lightScale(float k) {
  PRECISE float s = k * 512.0 + 1.0;
  s = ceil(s);
  if (s > 512.0) return 512;
  if (s < -512.0) return -512;
  return int(s);
}
)";

// Column c of a 3×4 matrix at word m (GE element order k = row k%3, column k/3), padded to a
// vec4; and of a 4×4 one (k = row k%4, column k/4).
std::string col3(int m, int c) {
    return "vec4(" + uf(m + 3 * c) + ", " + uf(m + 3 * c + 1) + ", " + uf(m + 3 * c + 2) + ", 0.0)";
}
std::string col4(int m, int c) {
    const int w = m + 4 * c;
    if (w % 4 == 0) return "uintBitsToFloat(u_hw[" + std::to_string(w / 4) + "])";
    return "vec4(" + uf(w) + ", " + uf(w + 1) + ", " + uf(w + 2) + ", " + uf(w + 3) + ")";
}

// geometry/transform.cpp mulPoint3x4 / mulDir3x4: out_r = (t0 + t1) + (t2 + m9) per row, or
// (t0 + t1) + t2 for a direction, with the GE's terms; one column (vec4) per coordinate.
void mul3x4(std::string& s, const char* out, int m, const char* p, bool point) {
    const std::string t0 = "geTerm4(" + col3(m, 0) + ", vec4(" + p + ".x))";
    const std::string t1 = "geTerm4(" + col3(m, 1) + ", vec4(" + p + ".y))";
    const std::string t2 = "geTerm4(" + col3(m, 2) + ", vec4(" + p + ".z))";
    s += "  PRECISE vec4 " + std::string(out) + "4 = ";
    if (point) s += "(" + t0 + " + " + t1 + ") + (" + t2 + " + " + col3(m, 3) + ");\n";
    else s += "(" + t0 + " + " + t1 + ") + " + t2 + ";\n";
    s += "  PRECISE vec3 " + std::string(out) + " = " + out + "4.xyz;\n";
}

// mulPoint4x4: clip = M·(p, 1) (equation 3-3), (t0 + t1) + (t2 + m12) per row.
void mul4x4(std::string& s, const char* out, int m, const char* p) {
    s += "  PRECISE vec4 " + std::string(out) + " = (geTerm4(" + col4(m, 0) + ", vec4(" + p + ".x)) + geTerm4(" +
         col4(m, 1) + ", vec4(" + p + ".y))) + (geTerm4(" + col4(m, 2) + ", vec4(" + p + ".z)) + " + col4(m, 3) +
         ");\n";
}

// Decode expressions of one stored copy at byte `o` (hle/vertex_decoder.cpp decodeRaw, transform
// mode): 8-bit /128, 16-bit /32768 (exact power-of-two scalings), floats as stored.
std::string fixedOrFloat(int fmt, bool isSigned, const std::string& at) {
    switch (fmt) {
    case 1: return std::string(isSigned ? "rs8(" : "float(rb(") + at + (isSigned ? ")" : "))") + " * 0.0078125";
    case 2: return std::string(isSigned ? "rs16(" : "float(r16(") + at + (isSigned ? ")" : "))") + " * 0.000030517578125";
    default: return "rf32(" + at + ")";
    }
}
std::string at(const std::string& base, int off) { return off ? base + " + " + std::to_string(off) : base; }
int compSize(int fmt) { return fmt == 1 ? 1 : (fmt == 2 ? 2 : 4); }

struct Need {
    bool uv, normal, color, world, worldPos, fogZ;
};

// The layout of one stored copy (ge-rules.md §5.2).
VertexLayout layoutOf(const HwVsKey& k) {
    const u32 vtype = u32(k.tc) | u32(k.col) << 2 | u32(k.nrm) << 5 | u32(k.pos) << 7 | u32(k.weights) << 9 |
                      u32(k.weights ? k.weightCount - 1 : 0) << 14;
    return VertexLayout::fromVtype(vtype);
}

// Skinning (hle/vertex_decoder.cpp applySkinning): Σ w_b·(Bone_b·(pos, 1)) and
// Σ w_b·(Bone_b 3×3·nrm), plain float products (no GE term rule), zero weights skipped.
void emitSkinning(std::string& s, const HwVsKey& k, const Need& need) {
    const int wc = k.weightCount;
    s += "  {\n"
         "    PRECISE vec3 sp = vec3(0.0);\n"
         "    PRECISE vec3 sn = vec3(0.0);\n";
    for (int bn = 0; bn < wc; ++bn) {
        const int m = HW_WORD(bones) + 12 * bn;
        s += "    if (wt[" + std::to_string(bn) + "] != 0.0) {\n";
        // Row r: ((m_r·x + m_{3+r}·y) + m_{6+r}·z) + m_{9+r}, as three columns at once.
        auto c = [&](int k) { return vec3At(m + 3 * k); };
        s += "      PRECISE vec3 p = ((" + c(0) + " * pos.x + " + c(1) + " * pos.y) + " + c(2) + " * pos.z) + " + c(3) +
             ";\n";
        s += "      sp = sp + wt[" + std::to_string(bn) + "] * p;\n";
        if (need.normal && k.nrm) {
            s += "      PRECISE vec3 q = (" + c(0) + " * nrm.x + " + c(1) + " * nrm.y) + " + c(2) + " * nrm.z;\n";
            s += "      sn = sn + wt[" + std::to_string(bn) + "] * q;\n";
        }
        s += "    }\n";
    }
    s += "    pos = sp;\n";
    if (need.normal && k.nrm) s += "    nrm = sn;\n";
    s += "  }\n";
}

void emitDecode(std::string& s, const HwVsKey& k, const Need& need) {
    const VertexLayout l = layoutOf(k);
    const int mc = k.morphCount;
    const int wc = k.weights ? k.weightCount : 0;
    s += "  int base = gl_VertexID * " + std::to_string(hwVsStride(k)) + ";\n";
    s += "  PRECISE vec3 pos = vec3(0.0);\n"
         "  PRECISE vec2 uv = vec2(0.0);\n"
         "  PRECISE vec3 nrm = vec3(0.0);\n"
         "  PRECISE float wt[8] = float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);\n"
         "  PRECISE vec4 colf = vec4(0.0);\n";
    const bool decColor = need.color && k.col != 0;
    for (int m = 0; m < mc; ++m) {
        const std::string b = at("base", m * l.size);
        // One copy directly (VertexReader::read, copies == 1); several summed with CMD_WEIGHTm
        // from 0 in copy order (manual equation 7-1): P += Wm·Pm for every component.
        const bool morph = mc > 1;
        const std::string mw = morph ? uf(HW_WORD(morph) + m) + " * " : "";
        auto acc = [&](const std::string& dst, const std::string& val) {
            if (morph) s += "  " + dst + " = " + dst + " + " + mw + "(" + val + ");\n";
            else s += "  " + dst + " = " + val + ";\n";
        };
        for (int i = 0; i < wc; ++i)
            acc("wt[" + std::to_string(i) + "]",
                fixedOrFloat(k.weights, false, at(b, l.weightOff + i * compSize(k.weights))));
        if (need.uv && k.tc)
            for (int i = 0; i < 2; ++i)
                acc(std::string("uv.") + kXyz[i], fixedOrFloat(k.tc, false, at(b, l.tcOff + i * compSize(k.tc))));
        if (decColor) {
            std::string c;
            switch (k.col) {
            case 4: c = "col5650(r16(" + at(b, l.colOff) + "))"; break;
            case 5: c = "col5551(r16(" + at(b, l.colOff) + "))"; break;
            case 6: c = "col4444(r16(" + at(b, l.colOff) + "))"; break;
            default:
                c = "ivec4(rb(" + at(b, l.colOff) + "), rb(" + at(b, l.colOff + 1) + "), rb(" + at(b, l.colOff + 2) +
                    "), rb(" + at(b, l.colOff + 3) + "))";
                break;
            }
            acc("colf", "vec4(" + c + ")");
        }
        if (need.normal && k.nrm)
            for (int i = 0; i < 3; ++i)
                acc(std::string("nrm.") + kXyz[i], fixedOrFloat(k.nrm, true, at(b, l.nrmOff + i * compSize(k.nrm))));
        for (int i = 0; i < 3; ++i)
            acc(std::string("pos.") + kXyz[i], fixedOrFloat(k.pos, true, at(b, l.posOff + i * compSize(k.pos))));
    }
    // Vertex colour: morphed sums truncated after limiting to 0–255 (colorToU8); without a colour
    // in the format, MAC and MAA (docs/ge-rules.md §5.5).
    if (decColor) {
        s += "  ivec4 vcol;\n"
             "  for (int i = 0; i < 4; ++i) vcol[i] = colf[i] > 0.0 ? (colf[i] >= 255.0 ? 255 : int(colf[i])) : 0;\n";
    } else if (need.color) {
        const std::string mc0 = word(HW_WORD(matColor));
        s += "  ivec4 vcol = ivec4(uvec4(" + mc0 + ", " + mc0 + " >> 8, " + mc0 + " >> 16, " + mc0 + " >> 24) & 255u);\n";
    }
    if (wc) emitSkinning(s, k, need);
}

// Light n of lightVertex (geometry/lighting.cpp), HwVsKey's type (1 directional, 2 point, 3 spot)
// and components (0 ambient + diffuse, 1 + specular, 2 powered diffuse): its terms added to lc
// and spec.
void emitLight(std::string& s, int n, int type, int comp) {
    const std::string mk = uf(HW_WORD(specularExp));
    const int p = HW_WORD(lightPos) + 4 * n, a = HW_WORD(lightAtt) + 4 * n, sd = HW_WORD(lightSpotDir) + 4 * n;
    const int sp = HW_WORD(lightSpot) + 4 * n;
    s += "  {  // light " + std::to_string(n) + "\n";
    s += "    PRECISE vec3 L = " + vec3At(p) + ";\n"
         "    PRECISE float attspot = 1.0;\n";
    if (type >= 2) {
        // L = light − vertex, d = |L|; attenuation 1/(a + b·d + c·d²) limited to [0, 1] (9-3).
        s += "    L = L - world;\n"
             "    float d = normalizeOr001(L);\n"
             "    PRECISE float den = (" + uf(a) + " + " + uf(a + 1) + " * d) + (" + uf(a + 2) + " * d) * d;\n"
             "    float att = fdiv(1.0, den);\n"
             "    if (isNan(att) || att <= 0.0) att = 0.0;\n"
             "    else if (att > 1.0) att = 1.0;\n"
             "    attspot = att;\n";
    }
    if (type == 3) {
        // Spot: cos = LD·L, L = light − vertex (geometry/lighting.cpp: hardware-measured sign,
        // not the manual's 9-4); counts when cos ≥ LKO (ge-rules.md §8.9).
        // A forced cosine (≥ 0) stands for a direction that cannot be normalised.
        s += "    PRECISE float raw = " + uf(sp + 2) + " >= 0.0 ? " + uf(sp + 2) + " : (" + uf(sd) + " * L.x + " +
             uf(sd + 1) + " * L.y) + " + uf(sd + 2) + " * L.z;\n"
             "    if (isNan(raw)) raw = signBit(raw) ? 0.0 : 1.0;\n"
             "    float spot = 0.0;\n"
             "    if (raw >= " + uf(sp + 1) + ") {\n"
             "      spot = lightPow(raw, " + uf(sp) + ");\n"
             "      if (isNan(spot)) spot = 0.0;\n"
             "    }\n"
             "    attspot = attspot * spot;\n";
    }
    s += "    if (!isNan(attspot)) {\n";
    s += "      lc.rgb += (" + ivec3At(HW_WORD(lightAmbient) + 4 * n) + " * mac.rgb * lightScale(attspot)) >> 19;\n";
    s += "      PRECISE float ndotl = (L.x * wn.x + L.y * wn.y) + L.z * wn.z;\n";
    if (comp == 2) s += "      float diffuse = lightPow(ndotl, " + mk + ");\n";  // 9-7
    else s += "      float diffuse = ndotl;\n";
    s += "      if (diffuse > 0.0) {\n"
         "        PRECISE float kd = attspot * diffuse;\n"
         "        lc.rgb += (" + ivec3At(HW_WORD(lightDiffuse) + 4 * n) + " * mdc * lightScale(kd)) >> 19;\n"
         "      }\n";
    if (comp == 1) {
        // H = normalize(L + (0, 0, 1)) (9-8); specular only when N·L ≥ 0 (ge-rules.md §8.12).
        s += "      if (ndotl >= 0.0) {\n"
             "        PRECISE vec3 H = vec3(L.x, L.y, L.z + 1.0);\n"
             "        normalizeOr001(H);\n"
             "        PRECISE float hn = (H.x * wn.x + H.y * wn.y) + H.z * wn.z;\n"
             "        float sp = lightPow(hn, " + mk + ");\n"
             "        if (sp > 0.0) {\n"
             "          PRECISE float ks = attspot * sp;\n"
             "          spec += (" + ivec3At(HW_WORD(lightSpecular) + 4 * n) + " * msc * lightScale(ks)) >> 19;\n"
             "        }\n"
             "      }\n";
    }
    s += "    }\n  }\n";
}

// geometry/lighting lightVertex, unrolled for the key's lights. Inputs: world (world position),
// wn (normalised world normal), vcol; outputs lc (primary RGBA), spec (secondary RGB), as ints.
void emitLighting(std::string& s, const HwVsKey& k) {
    if (k.ambientFromVertex || k.diffuseFromVertex || k.specularFromVertex) s += "  ivec4 vc = 2 * vcol + 1;\n";
    const int ma = HW_WORD(matAmbient);
    s += std::string("  ivec4 mac = ") + (k.ambientFromVertex ? "vc" : "ivec4(" + ivec3At(ma) + ", " + ui(ma + 3) + ")") +
         ";\n";
    s += std::string("  ivec3 mdc = ") + (k.diffuseFromVertex ? "vc.rgb" : ivec3At(HW_WORD(matDiffuse))) + ";\n";
    s += std::string("  ivec3 msc = ") + (k.specularFromVertex ? "vc.rgb" : ivec3At(HW_WORD(matSpecular))) + ";\n";
    // Emission + global ambient (equation 9-1, ge-rules.md §8.3); lit alpha = AA ⊙ MAA (ge-rules.md §8.12).
    s += "  ivec4 lc;\n"
         "  lc.rgb = " + ivec3At(HW_WORD(emissive)) + " + ((" + ivec3At(HW_WORD(globalAmbient)) + " * mac.rgb) >> 10);\n"
         "  lc.a = (" + ui(HW_WORD(globalAmbient) + 3) + " * mac.a) >> 10;\n"
         "  ivec3 spec = ivec3(0);\n";
    for (int n = 0; n < 4; ++n)
        if (k.lightType[n]) emitLight(s, n, k.lightType[n], k.lightComp[n]);
    if (!k.separateSpecular) s += "  lc.rgb += spec;\n  spec = ivec3(0);\n";
    s += "  ivec4 prim = clamp(lc, 0, 255);\n"
         "  ivec3 sec = clamp(spec, 0, 255);\n";
}

// Texture coordinates s, t, q (geometry/transform.cpp transformVertex, manual §13.1, §13.2; ge-rules.md §8.10).
void emitTexture(std::string& s, const HwVsKey& k) {
    s += "  PRECISE float ts = 0.0, tt = 0.0, tq = 1.0;\n";
    if (k.texMap == 1) {
        // Projection: (S, T, Q) = TGEN·source.
        s += "  PRECISE vec3 src = vec3(0.0);\n";
        switch (k.projSource) {
        case 0: s += "  src = model;\n"; break;
        case 1: s += "  src = vec3(uv, 0.0);\n"; break;
        case 2:
            // Normalised normal, divided in double; a zero normal stays zero.
            s += "#ifdef GE_FP64\n"
                 "  {\n"
                 "    dvec3 dn = dvec3(normal);\n"
                 "    PRECISE double l = sqrt((dn.x * dn.x + dn.y * dn.y) + dn.z * dn.z);\n"
                 "    if (l > 0.0lf) src = vec3(float(dn.x / l), float(dn.y / l), float(dn.z / l));\n"
                 "  }\n"
                 "#else\n"
                 "  {\n"
                 "    PRECISE float l = sqrt((normal.x * normal.x + normal.y * normal.y) + normal.z * normal.z);\n"
                 "    if (l > 0.0) src = normal / l;\n"
                 "  }\n"
                 "#endif\n";
            break;
        default: s += "  src = normal;\n"; break;
        }
        mul3x4(s, "stq", HW_WORD(tgen), "src", true);
        s += "  ts = stq.x;\n  tt = stq.y;\n  tq = stq.z;\n";
    } else if (k.texMap == 2) {
        // Shade mapping: s = (normalize(Lu)·N + 1)/2, t likewise.
        const int l = HW_WORD(shadeLight);
        s += "  PRECISE float du = (" + uf(l) + " * wn.x + " + uf(l + 1) + " * wn.y) + " + uf(l + 2) + " * wn.z;\n"
             "  PRECISE float dv = (" + uf(l + 4) + " * wn.x + " + uf(l + 5) + " * wn.y) + " + uf(l + 6) + " * wn.z;\n"
             "  ts = (du + 1.0) * 0.5;\n"
             "  tt = (dv + 1.0) * 0.5;\n";
    } else {
        // UV with scale and offset (equation 13-3).
        const int u = HW_WORD(uvScale);
        s += "  ts = " + uf(u) + " * uv.x + " + uf(u + 2) + ";\n"
             "  tt = " + uf(u + 1) + " * uv.y + " + uf(u + 3) + ";\n";
    }
}

// Through mode (key.through = 1): hle/vertex_decoder.cpp decodeRaw/VertexReader::read with
// through = true (the first stored copy only: no morphing; no skinning): position and colour.
void emitThroughDecode(std::string& s, const HwVsKey& k) {
    const VertexLayout l = layoutOf(k);
    // The stride still counts every morph copy (VertexReader::stride).
    s += "  int base = gl_VertexID * " + std::to_string(hwVsStride(k)) + ";\n";
    // Position: s8 decodes as 0; s16 signed X, Y and unsigned Z; float with Z limited to
    // 0–65535 (NaN → 0).
    switch (k.pos) {
    case 1: s += "  PRECISE vec3 pos = vec3(0.0);\n"; break;
    case 2:
        s += "  PRECISE vec3 pos = vec3(rs16(" + at("base", l.posOff) + "), rs16(" + at("base", l.posOff + 2) +
             "), float(r16(" + at("base", l.posOff + 4) + ")));\n";
        break;
    default:
        s += "  PRECISE vec3 pos = vec3(rf32(" + at("base", l.posOff) + "), rf32(" + at("base", l.posOff + 4) +
             "), rf32(" + at("base", l.posOff + 8) + "));\n"
             "  if (isNan(pos.z) || pos.z < 0.0) pos.z = 0.0;\n"
             "  else if (pos.z > 65535.0) pos.z = 65535.0;\n";
        break;
    }
    // Colour as decoded (one copy: the bytes themselves), else MAC and MAA.
    switch (k.col) {
    case 4: s += "  ivec4 vcol = col5650(r16(" + at("base", l.colOff) + "));\n"; break;
    case 5: s += "  ivec4 vcol = col5551(r16(" + at("base", l.colOff) + "));\n"; break;
    case 6: s += "  ivec4 vcol = col4444(r16(" + at("base", l.colOff) + "));\n"; break;
    case 7:
        s += "  ivec4 vcol = ivec4(rb(" + at("base", l.colOff) + "), rb(" + at("base", l.colOff + 1) + "), rb(" +
             at("base", l.colOff + 2) + "), rb(" + at("base", l.colOff + 3) + "));\n";
        break;
    default: {
        const std::string mc0 = word(HW_WORD(matColor));
        s += "  ivec4 vcol = ivec4(uvec4(" + mc0 + ", " + mc0 + " >> 8, " + mc0 + " >> 16, " + mc0 + " >> 24) & 255u);\n";
        break;
    }
    }
}

// Through mode, then geometry/transform.cpp transformVertex's through branch and the ClipVertex.
void emitThrough(std::string& s, const HwVsKey& k) {
    emitThroughDecode(s, k);
    const VertexLayout l = layoutOf(k);
    // Texture coordinates: u8 /128, u16 texels as they are, float as stored; then s = u/width0,
    // t = v/height0 (ge-rules.md §8.10), q = 1.
    s += "  PRECISE float ts = 0.0, tt = 0.0;\n";
    if (k.texture && k.tc) {
        const int c = compSize(k.tc);
        auto comp = [&](int i) {
            const std::string a = at("base", l.tcOff + i * c);
            if (k.tc == 1) return "float(rb(" + a + ")) * 0.0078125";
            if (k.tc == 2) return "float(r16(" + a + "))";
            return "rf32(" + a + ")";
        };
        s += "  PRECISE vec2 uv = vec2(" + comp(0) + ", " + comp(1) + ");\n";
        s += "  ts = uv.x * " + uf(HW_WORD(texScale)) + ";\n"
             "  tt = uv.y * " + uf(HW_WORD(texScale) + 1) + ";\n";
    }
    // Drawing coordinates: x16 = trunc(x·16) limited to ±2^20 (NaN → −2^20); Z as an integer.
    s += "  PRECISE float x16f = pos.x * 16.0;\n"
         "  PRECISE float y16f = pos.y * 16.0;\n"
         "  if (isNan(x16f) || x16f <= -1048576.0) x16f = -1048576.0;\n"
         "  if (x16f > 1048576.0) x16f = 1048576.0;\n"
         "  if (isNan(y16f) || y16f <= -1048576.0) y16f = -1048576.0;\n"
         "  if (y16f > 1048576.0) y16f = 1048576.0;\n"
         "  int x16 = int(x16f);\n"
         "  int y16 = int(y16f);\n"
         "  int zi = depthToInt(pos.z);\n";
    // ClipVertex: clip = (x, y, z, 1); never outside, on a depth side or beyond the near plane.
    s += "  g_clip = vec4(pos, 1.0);\n"
         "  g_color = vcol;\n"
         "  g_color2 = ivec3(0);\n"
         "  g_stqf = vec4(ts, tt, 1.0, 1.0);\n"
         "  g_scr = ivec4(x16, y16, zi, 0);\n"
         "}\n";
}

// Transform (geometry/transform.cpp transformVertex): model position and normal, world position,
// clip coordinates.
void emitTransform(std::string& s, const HwVsKey& k, const Need& need) {
    s += "  PRECISE vec3 model = pos;\n";
    if (need.normal) {
        if (k.nrm) s += k.normalReverse ? "  PRECISE vec3 normal = -nrm;\n" : "  PRECISE vec3 normal = nrm;\n";
        else s += "  PRECISE vec3 normal = vec3(0.0, 0.0, 1.0);\n";
    }
    if (need.world) mul3x4(s, "world", HW_WORD(world), "model", true);
    // Without a positional light the reference folds world·view·proj into one matrix applied to
    // the model position; with one, view·proj applied to the world position.
    if (need.worldPos) mul4x4(s, "clip", HW_WORD(viewProj), "world");
    else mul4x4(s, "clip", HW_WORD(worldViewProj), "model");
}

// Fog factor from view-space Z (ge-rules.md §3.9): (z_view + end)·slope, or the draw's fixed value.
void emitFogFactor(std::string& s) {
    const int v = HW_WORD(view);
    s += "  PRECISE float fogF;\n"
         "  if (" + ui(HW_WORD(fogFixed)) + " >= 0) fogF = float(" + ui(HW_WORD(fogFixed)) + ");\n"
         "  else {\n"
         "    PRECISE float vz = (geTerm(" + uf(v + 2) + ", world.x) + geTerm(" + uf(v + 5) + ", world.y)) + (geTerm(" +
         uf(v + 8) + ", world.z) + " + uf(v + 11) + ");\n"
         "    fogF = (vz + " + uf(HW_WORD(fog)) + ") * " + uf(HW_WORD(fog) + 1) + ";\n"
         "  }\n";
}

// Screen (projectToScreen): scale, divide by w, add the centre; the range flags (ge-rules.md
// §8.5), the 1/16-pixel snap and the depth side by |z/w| ≥ 1.00003 (geometry/clip.cpp depthSide).
void emitProjectToScreen(std::string& s, const HwVsKey& k) {
    const int vp = HW_WORD(viewport);
    s += "  PRECISE float w = clip.w;\n"
         "  PRECISE float xm = clip.x * " + uf(vp) + ";\n"
         "  PRECISE float ym = clip.y * " + uf(vp + 1) + ";\n"
         "  PRECISE float zm = clip.z * " + uf(vp + 2) + ";\n"
         "  PRECISE float xs = fdiv(xm, w) + " + uf(vp + 3) + ";\n"
         "  PRECISE float ys = fdiv(ym, w) + " + uf(vp + 4) + ";\n"
         "  PRECISE float zs = fdiv(zm, w) + " + uf(vp + 5) + ";\n"
         "  bool outside = false;\n"
         "  bool zClamped = false;\n";
    if (k.clipEnable) {
        // CLE = 1: Z clamped; a clamped vertex is exempt from the X/Y check.
        s += "  if (isNan(zs) || zs < 0.0) { zs = 0.0; zClamped = true; }\n"
             "  else if (zs > 65535.0) { zs = 65535.0; zClamped = true; }\n";
    } else {
        s += "  if (isNan(zs) || zs < 0.0 || zs >= 65536.0) outside = true;\n";
    }
    s += "  if (!zClamped && (isNan(xs) || isNan(ys) || xs < 0.0 || xs >= 4096.0 || ys < 0.0 || ys >= 4096.0))\n"
         "    outside = true;\n";
    const int off = HW_WORD(offset16);
    s += "  int x16 = to16(xs, " + ui(off) + ");\n"
         "  int y16 = to16(ys, " + ui(off + 1) + ");\n";
    s += "  float zr = fdiv(clip.z, clip.w);\n"
         "  int side = zr >= " + flit(1.00003f) + " ? 1 : (zr <= " + flit(-1.00003f) + " ? -1 : 0);\n";
}

// Transform mode: decode, transform, fog, world normal, texture coordinates, lighting, screen;
// then the ClipVertex. Everything whole-primitive (discard, near clipping, culling, the fragment
// shader's inputs) is the geometry shader's (hw_geometry.cpp).
void emitTransformMode(std::string& s, const HwVsKey& k) {
    Need need{};
    // A positional light needs the world position (makeTransformState).
    for (int n = 0; n < 4; ++n) need.worldPos = need.worldPos || (k.lighting && k.lightType[n] >= 2);
    need.uv = k.texture && (k.texMap == 0 || (k.texMap == 1 && k.projSource == 1));
    const bool worldNormal = k.lighting || (k.texture && k.texMap == 2);
    need.normal = worldNormal || (k.texture && k.texMap == 1 && k.projSource >= 2);
    need.color = !k.lighting || k.ambientFromVertex || k.diffuseFromVertex || k.specularFromVertex;
    need.fogZ = k.fog != 0;
    need.world = need.worldPos || need.fogZ;

    emitDecode(s, k, need);
    emitTransform(s, k, need);
    if (k.fog) emitFogFactor(s);
    // World normal for lighting and shade mapping, normalised; (0, 0, 1) without a normal.
    if (worldNormal) {
        if (k.nrm) {
            mul3x4(s, "wn", HW_WORD(world), "normal", false);
            s += "  normalizeOr001(wn);\n";
        } else {
            s += "  PRECISE vec3 wn = vec3(0.0, 0.0, 1.0);\n";
        }
    }
    if (k.texture) emitTexture(s, k);
    if (k.lighting) {
        emitLighting(s, k);
    } else {
        s += "  ivec4 prim = vcol;\n  ivec3 sec = ivec3(0);\n";
    }
    emitProjectToScreen(s, k);
    s += "  g_clip = clip;\n"
         "  g_color = prim;\n"
         "  g_color2 = sec;\n";
    s += std::string("  g_stqf = vec4(") + (k.texture ? "ts, tt, tq" : "0.0, 0.0, 1.0") + ", " +
         (k.fog ? "fogF" : "1.0") + ");\n";
    s += "  g_scr = ivec4(x16, y16, depthToInt(zs), (outside ? 1 : 0) | (side == -1 ? 2 : 0) | (side == 1 ? 4 : 0));\n"
         "}\n";
}

}  // namespace

bool generateHwVertexShader(const HwVsKey& key, const HostCaps& caps, std::string& out, std::string* err) {
    (void)caps;  // host features are chosen by the GLSL preprocessor (hw_vertex.h)
    (void)err;
    HwVsKey k = key;
    canonicalize(k);
    std::string s;
    glsl::hwPreamble(s, describe(k));
    s += "uniform usamplerBuffer u_vtx;\n"
         "uniform uvec4 u_hw[" + std::to_string(kHwVsUniformVec4) + "];\n";
    // The CPU's ClipVertex, for the geometry shader (hw_vertex.h; names shared with
    // hw_geometry.cpp).
    s += "out vec4 g_clip;\n"
         "flat out ivec4 g_color;\n"
         "flat out ivec3 g_color2;\n"
         "out vec4 g_stqf;\n"
         "flat out ivec4 g_scr;\n";
    s += kFetchHelpers;
    s += glsl::kFloatClass;
    s += kSignHelpers;
    s += glsl::kFdiv;
    s += kGeMathHelpers;
    s += glsl::kScreenRound;
    s += "void main() {\n";
    if (k.pos == 0) {
        // No position: the vertex is dropped (ge-rules.md §8.11).
        s += "  g_clip = vec4(0.0, 0.0, 0.0, 1.0);\n  g_color = ivec4(0);\n  g_color2 = ivec3(0);\n"
             "  g_stqf = vec4(0.0, 0.0, 1.0, 1.0);\n  g_scr = ivec4(0, 0, 0, 8);\n}\n";
    } else if (k.through) {
        emitThrough(s, k);
    } else {
        emitTransformMode(s, k);
    }
    out = std::move(s);
    return true;
}

}  // namespace ge::shadergen
