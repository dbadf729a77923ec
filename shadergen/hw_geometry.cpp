// SPDX-License-Identifier: MIT
// GLSL generator of the GL hardware mode's geometry shader (see hw_vertex.h): everything the CPU
// path does with a whole transform-mode triangle, translator/vertex_pipeline.cpp
// VertexPipeline::triangle line by line:
//   1. geometry/clip.cpp discardPrimitive (docs/ge-rules.md §8.5): an invalid or `outside` vertex
//      drops the triangle; CLE = 0: any vertex beyond a depth side drops it, CLE = 1: only all
//      three beyond the same side; then the triangle whose three vertices have w < 0.
//   2. A vertex beyond the near plane (clip.h beyondNear): clipTriangleNear on the reference's
//      ring order (strips and fans, geometry/assembly.h; clip.h ringReversed), lerpVertex for
//      the new vertices (from the outside vertex toward the inside one, clip-space lerp, 8-bit
//      colour weights, projectToScreen without range check), the fan-piece drop for a new vertex
//      whose screen X/Y leaves [0, 4096), the rotation rule for negatively wound polygons; each
//      piece culled in the primitive's winding, emitted in the polygon's fan order.
//   3. Otherwise culled on (a, b, c), emitted in ring order (strips, fans) or (a, b, c).
// Every emitted vertex gets the fragment shader's inputs as toGl/emitTriangle compute them.
// Through mode (key.through, GE_THROUGH): steps 1 and 2 do not apply (discardPrimitive returns
// false, no near clipping); only a vertex without a position drops the triangle; culling as in 3;
// toGl without perspective (v_tex = (s, t, q, 1)).
//
// Float arithmetic follows the CPU operation by operation, each result in a `precise` variable
// (no fused multiply-add; the CPU is built with -ffp-contract=off); divisions go through double
// where the driver has it (the float quotient then is the correctly rounded one, as on the CPU).
// The 64-bit signed areas of the CPU (VertexPipeline::culled, the polygon area of
// clipTriangleNear) are formed exactly from 32-bit pieces (GLSL 3.30 has no 64-bit integers).
#include <cstddef>
#include <cstdio>
#include <string>

#include "geometry/raster.h"
#include "shadergen/glsl_common.h"
#include "shadergen/hw_uniform_text.h"
#include "shadergen/hw_vertex.h"

namespace ge::shadergen {
namespace {

using namespace hwtext;

// One vertex as the CPU holds it (geometry/transform.h ClipVertex with its ScreenVertex).
const char* const kVertexStruct = R"(struct CV {
  vec4 clip;     // ClipVertex::clip
  vec4 stqf;     // ScreenVertex s, t, q, fog
  ivec4 col;     // ScreenVertex::color
  ivec3 sec;     // ScreenVertex::secondary
  ivec3 scr;     // ScreenVertex x, y (1/16 pixel), z
  bool outside;  // ClipVertex::outside
};
)";

// Fixed text after glsl_common.h's isNan, notFinite, fdiv, to16 and depthToInt: helpers and the
// port of geometry/clip.cpp and VertexPipeline::triangle. The key enters through GE_CLE, GE_PRIM,
// GE_FLAT, GE_TEXTURE, GE_THROUGH; the uniforms through GE_SX … GE_CULL_CCW.
const char* const kBody = R"(
// Exact signed 64-bit products and sums of ints below 2^22 in magnitude (x16 is limited to
// ±2^20, differences of two to ±2^21): value = v.x·2^22 + v.y with 0 ≤ v.y < 2^22.
ivec2 norm64(int hi, int lo) { return ivec2(hi + (lo >> 22), lo & 0x3FFFFF); }
ivec2 mul64(int a, int b) {
  int al = a & 2047, ah = a >> 11, bl = b & 2047, bh = b >> 11;  // a = ah·2^11 + al, 0 ≤ al < 2^11
  int mid = ah * bl + al * bh;                                   // |mid| < 2^23
  return norm64(ah * bh + (mid >> 11), (mid & 2047) * 2048 + al * bl);
}
ivec2 add64(ivec2 a, ivec2 b) { return norm64(a.x + b.x, a.y + b.y); }
ivec2 sub64(ivec2 a, ivec2 b) { return norm64(a.x - b.x, a.y - b.y); }
int sign64(ivec2 v) { return v.x < 0 ? -1 : ((v.x > 0 || v.y > 0) ? 1 : 0); }
// Twice the signed screen area of (a, b, c), as VertexPipeline::culled and emitTriangle form it:
// positive = clockwise on screen (y down).
int areaSign(ivec3 a, ivec3 b, ivec3 c) {
  return sign64(sub64(mul64(b.x - a.x, c.y - a.y), mul64(b.y - a.y, c.x - a.x)));
}

// geometry/clip.cpp nearDist: signed distance to the near plane z = −w (≥ 0 inside).
float nearDist(CV v) {
  PRECISE float d = v.clip.z + v.clip.w;
  return d;
}
bool inside(float d) { return !isNan(d) && d >= 0.0; }

// geometry/transform.cpp projectToScreen(rangeCheck = false) of a new vertex, and clip.cpp
// xyOutside on the same screen X/Y (no Z-clamp exemption, Z not checked).
void project(inout CV v) {
  PRECISE float w = v.clip.w;
  PRECISE float xm = v.clip.x * GE_SX;
  PRECISE float ym = v.clip.y * GE_SY;
  PRECISE float zm = v.clip.z * GE_SZ;
  PRECISE float xs = fdiv(xm, w) + GE_TX;
  PRECISE float ys = fdiv(ym, w) + GE_TY;
  PRECISE float zs = fdiv(zm, w) + GE_TZ;
#if GE_CLE
  if (isNan(zs) || zs < 0.0) zs = 0.0;
  else if (zs > 65535.0) zs = 65535.0;
#endif
  v.scr = ivec3(to16(xs, GE_OFFX), to16(ys, GE_OFFY), depthToInt(zs));
  v.outside = isNan(xs) || isNan(ys) || xs < 0.0 || xs >= 4096.0 || ys < 0.0 || ys >= 4096.0;
}

// geometry/clip.cpp lerpVertex: the point at t on a → b.
CV lerpV(CV a, CV b, float t) {
  CV r;
  PRECISE vec4 dc = b.clip - a.clip;
  PRECISE vec4 mc = dc * t;
  r.clip = a.clip + mc;
  PRECISE vec4 da = b.stqf - a.stqf;
  PRECISE vec4 ma = da * t;
  r.stqf = a.stqf + ma;
  // Colours with an 8-bit weight k = trunc(t·256) limited to [0, 256]: (a·(256 − k) + b·k) / 256.
  PRECISE float kf = t * 256.0;
  int k = (isNan(kf) || kf < 0.0) ? 0 : (kf > 256.0 ? 256 : int(kf));
  r.col = (a.col * (256 - k) + b.col * k) / 256;
  r.sec = (a.sec * (256 - k) + b.sec * k) / 256;
  project(r);
  return r;
}

// geometry/clip.cpp clipTriangleNear: the polygon left of (a, b, c) on z ≥ −w, as a fan from
// o[0]; returns its vertex count (0, 3 or 4) after the rotation and screen-range rules.
int clipNear(CV a, CV b, CV c, out CV o[4]) {
  CV inp[3] = CV[3](a, b, c);
  int n = 0;
  int tag[4] = int[4](0, 0, 0, 0);  // 0–2: input vertex; 3 + i: the point on edge (i, i + 1)
  for (int i = 0; i < 3; ++i) {
    int j = i == 2 ? 0 : i + 1;
    float dp = nearDist(inp[i]), dq = nearDist(inp[j]);
    bool pin = inside(dp), qin = inside(dq);
    if (pin) {
      tag[n] = i;
      o[n] = inp[i];
      ++n;
    }
    if (pin != qin && n < 4) {
      // Always from the outside vertex toward the inside one, t = d_out / (d_out − d_in).
      if (pin) {
        PRECISE float den = dq - dp;
        o[n] = lerpV(inp[j], inp[i], fdiv(dq, den));
      } else {
        PRECISE float den = dp - dq;
        o[n] = lerpV(inp[i], inp[j], fdiv(dp, den));
      }
      tag[n] = 3 + i;
      ++n;
    }
  }
  if (n < 3) return 0;
  // A polygon wound negatively on screen starts where clipping (c, b, a) would start.
  ivec2 area2 = ivec2(0);
  for (int k = 0; k < n; ++k) {
    ivec3 p = o[k].scr, q = o[k + 1 == n ? 0 : k + 1].scr;
    area2 = add64(area2, sub64(mul64(p.x, q.y), mul64(q.x, p.y)));
  }
  if (sign64(area2) < 0) {
    int first = -1;
    for (int i = 0; i < 3 && first < 0; ++i) {
      int pi = 2 - i, qi = i == 2 ? 2 : 1 - i;  // (rev[i], rev[(i + 1) % 3]), rev = (2, 1, 0)
      if (inside(nearDist(inp[pi]))) first = pi;
      else if (inside(nearDist(inp[qi]))) first = 3 + min(pi, qi) + (abs(pi - qi) == 2 ? 2 : 0);
    }
    int at = 0;
    while (at < n && tag[at] != first) ++at;
    if (at > 0 && at < n) {
      CV tmp[4] = o;
      for (int k = 0; k < n; ++k) o[k] = tmp[(at + k) % n];
    }
  }
  // Fan (0, 1, 2) and (0, 2, 3): keep exactly the triangles without an outside vertex.
  bool keep1 = !o[0].outside && !o[1].outside && !o[2].outside;
  if (n == 3) return keep1 ? 3 : 0;
  bool keep2 = !o[0].outside && !o[2].outside && !o[3].outside;
  if (keep1 && keep2) return 4;
  if (keep1) return 3;
  if (keep2) {
    o[1] = o[2];
    o[2] = o[3];
    return 3;
  }
  return 0;
}

// VertexPipeline::culled: CULL 0 culls clockwise, 1 counter-clockwise; area 0 never.
bool culled(ivec3 a, ivec3 b, ivec3 c) {
  if (GE_CULL_ON == 0) return false;
  int s = areaSign(a, b, c);
  if (s == 0) return false;
  return GE_CULL_CCW != 0 ? s < 0 : s > 0;
}

// toGl + emitTriangle for one vertex: drawing position moved by (8 − o)/16 to GL's pixel-centre
// sampling, then to NDC; colours of `prov` with flat shading.
void emitVertex(CV v, CV prov) {
  PRECISE float gx = float(v.scr.x) * 0.0625;
  PRECISE float gy = float(v.scr.y) * 0.0625;
  gx = gx + GE_SHIFT;
  gy = gy + GE_SHIFT;
  PRECISE float nx = gx * u_ndcScale.x - 1.0;
  PRECISE float ny = gy * u_ndcScale.y - 1.0;
  gl_Position = vec4(nx, ny, 0.0, 1.0);
#if GE_FLAT
  v_color = vec4(prov.col);
  v_color2 = vec3(prov.sec);
#else
  v_color = vec4(v.col);
  v_color2 = vec3(v.sec);
#endif
#if GE_TEXTURE && GE_THROUGH
  // Through mode: toGl without perspective (w = 1).
  v_tex = vec4(v.stqf.xyz, 1.0);
#elif GE_TEXTURE
  // Perspective: s/w, t/w, q/w interpolate linearly on screen; w (finite, non-zero) for TLEVEL.
  PRECISE float w = v.clip.w;
  PRECISE float tw = (notFinite(w) || w == 0.0) ? 1.0 : w;
  float kw = fdiv(1.0, tw);
  PRECISE vec4 tex = vec4(v.stqf.x * kw, v.stqf.y * kw, v.stqf.z * kw, tw);
  v_tex = tex;
#else
  v_tex = vec4(0.0, 0.0, 1.0, 1.0);
#endif
  v_fog = v.stqf.w;
  v_z = float(v.scr.z);
  EmitVertex();
}
// emitTriangle: a zero-area triangle is the CPU rasteriser's (one-pixel quads of the samples on
// its line, geometry/raster.cpp rasterZeroAreaTriangle); GL would draw nothing of it.
void emitTriangle(CV a, CV b, CV c, CV prov) {
  if (areaSign(a.scr, b.scr, c.scr) == 0) return;
  emitVertex(a, prov);
  emitVertex(b, prov);
  emitVertex(c, prov);
  EndPrimitive();
}

void main() {
  CV v[3];
  int flags[3];
  for (int i = 0; i < 3; ++i) {
    v[i].clip = g_clip[i];
    v[i].stqf = g_stqf[i];
    v[i].col = g_color[i];
    v[i].sec = g_color2[i];
    v[i].scr = g_scr[i].xyz;
    flags[i] = g_scr[i].w;
    v[i].outside = (flags[i] & 1) != 0;
  }
#if GE_THROUGH
  // Through mode: no discard rules and no near clipping (VertexPipeline::triangle), only a
  // vertex without a position drops the triangle (ClipVertex::valid, ge-rules.md §8.11).
  for (int i = 0; i < 3; ++i)
    if ((flags[i] & 8) != 0) return;
#else
  // discardPrimitive (ge-rules.md §8.5).
  int nearCount = 0, farCount = 0;
  for (int i = 0; i < 3; ++i) {
    if ((flags[i] & 9) != 0) return;  // outside, or no position (ge-rules.md §8.11)
    nearCount += (flags[i] >> 1) & 1;
    farCount += (flags[i] >> 2) & 1;
  }
#if GE_CLE
  if (nearCount == 3 || farCount == 3) return;
#else
  if (nearCount + farCount > 0) return;
#endif
  if (v[0].clip.w < 0.0 && v[1].clip.w < 0.0 && v[2].clip.w < 0.0) return;
#endif
  // The reference's ring (geometry/assembly.h assemblePrimitives) as input indices; the inputs
  // come in the CPU's winding (a, b, c) (hwTriangleList): strip triangle i is the strip's vertices
  // (i, i + 1, i + 2), odd ones as (i + 1, i, i + 2), and vertex k sits in ring slot k mod 3; fan
  // triangle i is (0, i + 1, i + 2), the centre in slot 0, odd-numbered vertices in slot 1.
  int ring[3] = int[3](0, 1, 2);
#if GE_PRIM != 0
  int id = int(texelFetch(u_ring, gl_PrimitiveIDIn).r);  // i mod 6 (hwTriangleList)
#endif
#if GE_PRIM == 1
  {
    bool odd = (id & 1) != 0;
    ring[(odd ? id + 1 : id) % 3] = 0;
    ring[(odd ? id : id + 1) % 3] = 1;
    ring[(id + 2) % 3] = 2;
  }
#elif GE_PRIM == 2
  if ((id & 1) != 0) {  // vertex i + 2 odd: it takes slot 1
    ring[1] = 2;
    ring[2] = 1;
  }
#endif
  // clip.h ringReversed(ring, a, b).
#if !GE_THROUGH
  int pa = ring[0] == 0 ? 0 : (ring[1] == 0 ? 1 : 2);
  bool reversed = ring[(pa + 1) % 3] != 1;
  bool beyond = false;
  for (int i = 0; i < 3; ++i) beyond = beyond || v[i].clip.z < -v[i].clip.w;
  if (beyond) {
    CV poly[4];
    int n = clipNear(v[ring[0]], v[ring[1]], v[ring[2]], poly);
    for (int k = 1; k + 1 < n; ++k) {
      int k1 = reversed ? k + 1 : k, k2 = reversed ? k : k + 1;  // the primitive's winding
      if (culled(poly[0].scr, poly[k1].scr, poly[k2].scr)) continue;
      emitTriangle(poly[0], poly[k], poly[k + 1], v[2]);  // flat: the original provoking vertex
    }
    return;
  }
#endif
  if (culled(v[0].scr, v[1].scr, v[2].scr)) return;
  emitTriangle(v[ring[0]], v[ring[1]], v[ring[2]], v[2]);
}
)";

}  // namespace

bool generateHwGeometryShader(const HwVsKey& key, const HostCaps& caps, std::string& out, std::string* err) {
    (void)caps;  // host features are chosen by the GLSL preprocessor (hw_vertex.h)
    (void)err;
    HwVsKey k = key;
    canonicalize(k);
    std::string s;
    glsl::hwPreamble(s, "geometry " + describe(k));
    s += "#define GE_CLE " + std::to_string(k.clipEnable ? 1 : 0) + "\n";
    s += "#define GE_PRIM " + std::to_string(k.primKind) + "\n";
    s += "#define GE_FLAT " + std::to_string(k.flatShade ? 1 : 0) + "\n";
    s += "#define GE_TEXTURE " + std::to_string(k.texture ? 1 : 0) + "\n";
    s += "#define GE_THROUGH " + std::to_string(k.through ? 1 : 0) + "\n";
    const int vp = HW_WORD(viewport);
    static const char* const kVp[6] = {"SX", "SY", "SZ", "TX", "TY", "TZ"};
    for (int i = 0; i < 6; ++i) s += std::string("#define GE_") + kVp[i] + " " + uf(vp + i) + "\n";
    s += "#define GE_OFFX " + ui(HW_WORD(offset16)) + "\n";
    s += "#define GE_OFFY " + ui(HW_WORD(offset16) + 1) + "\n";
    s += "#define GE_CULL_ON " + ui(HW_WORD(cull)) + "\n";
    s += "#define GE_CULL_CCW " + ui(HW_WORD(cull) + 1) + "\n";
    geo::RasterParams sampling;
    sampling.sampleCentre = k.sampleCentre != 0;
    s += "#define GE_SHIFT " + flit(float(8 - geo::triangleSampleOffset(sampling)) / 16.0f) + "\n";
    s += "layout(triangles) in;\n"
         "layout(triangle_strip, max_vertices = 6) out;\n"  // a clipped quadrilateral: 2 pieces
         "uniform uvec4 u_hw[" + std::to_string(kHwVsUniformVec4) + "];\n"
         "uniform vec2 u_ndcScale;\n"
         "in vec4 g_clip[];\n"
         "flat in ivec4 g_color[];\n"
         "flat in ivec3 g_color2[];\n"
         "in vec4 g_stqf[];\n"
         "flat in ivec4 g_scr[];\n";
    const std::string interp = k.flatShade ? "flat" : "noperspective";
    // Strips and fans arrive as triangle lists (hwTriangleList), with each triangle's number in
    // its strip or fan (mod 6) in a buffer texture read at gl_PrimitiveIDIn.
    if (k.primKind != 0) s += std::string("uniform usamplerBuffer ") + hwuniform::kRingIds + ";\n";
    s += interp + " out vec4 v_color;\n";
    s += interp + " out vec3 v_color2;\n";
    s += "noperspective out vec4 v_tex;\n"
         "noperspective out float v_fog;\n"
         "noperspective out float v_z;\n";
    s += kVertexStruct;
    s += glsl::kFloatClass;
    s += glsl::kFdiv;
    s += glsl::kScreenRound;
    // No position in the format (k.pos == 0): the vertex shader flags every vertex (8), so
    // discardPrimitive drops every primitive (ge-rules.md §8.11).
    s += kBody;
    out = std::move(s);
    return true;
}

}  // namespace ge::shadergen
