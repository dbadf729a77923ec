// SPDX-License-Identifier: MIT
// The GL hardware mode's geometry shader (shadergen/hw_geometry.cpp, contract in hw_vertex.h)
// against the CPU path it replaces: translator/vertex_pipeline.cpp VertexPipeline::processPrim on
// the same state and vertex bytes gives Geometry::tris, the GlVertex stream (drawing coordinates)
// the geometry shader must emit, in the same order. Transform feedback of the geometry shader's
// output (GL_TRIANGLES) is compared vertex for vertex and bit for bit: position (x, y on the 1/16
// grid plus the sample shift, to NDC), primary and secondary colours, Z, fog, texture coordinates.
// The scenes put vertices beyond the near plane (geometry/clip.cpp clipTriangleNear; docs/ge-rules.md
// §8.5), behind the camera, off the 4096² screen, in lists, strips and fans (the reference's ring
// order, geometry/assembly.h), with culling either way and flat shading. EachRuleIsNeeded breaks
// one rule of the shader at a time and checks that the comparison then fails; the rendering tests
// check what GL draws from the emitted triangles against the software rasteriser.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "geometry/clip.h"
#include "geometry/raster.h"
#include "geometry/transform.h"
#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/vertex_decoder.h"
#include "shadergen/hw_vertex.h"
#include "shadergen/keys_from_state.h"
#include "shadergen/shader_gen.h"
#include "translator/gl_context.h"
#include "translator/gl_renderer.h"
#include "translator/vertex_pipeline.h"
#include "tests/gl_hw_harness.h"

namespace ge::gltest {
namespace {

// ---------------------------------------------------------------------------------------------
// Scenes: vertices in view space (camera at the origin looking down −Z), a sceGu perspective
// (near 0.5, far 1000), viewport 480×272 centred at 2048. On the near plane (view z −0.5) screen
// X is 240 + 471·x and Y 136 − 471·y, so a new vertex stays on the 4096² screen for x in
// (−0.51, 8.2) and y in (−8.4, 0.29); the scenes mostly keep their cuts there.

struct Vtx {
    float x, y, z;
    u32 abgr = 0xFFFFFFFFu;
    float u = 0, v = 0;
};

struct Scene {
    GePrimType prim = GE_PRIM_TRIANGLES;
    std::vector<Vtx> verts;
    std::vector<u16> indices;  // drawn through 16-bit indices when not empty
    bool cle = true, cull = false, ccw = false, flat = false, texture = true, fog = true;
    std::function<void(GeState&)> tweak;
};

void setReg(GeState& st, u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }
void setF(GeState& st, u8 cmd, float f) { setReg(st, cmd, toFloat24(f)); }

constexpr u32 kVtype = 3 | 7 << 2 | 3 << 7;  // float UV, 8888 colour, float position
constexpr float kNdcX = 2.0f / 480.0f, kNdcY = 2.0f / 272.0f;

GeState sceneState(const Scene& sc) {
    GeState st;
    st.reset();
    setReg(st, GE_CMD_VTYPE, kVtype | (sc.indices.empty() ? 0u : 2u << 11));
    for (int i = 0; i < 12; ++i) st.world[i] = st.view[i] = 0;
    st.world[0] = st.world[4] = st.world[8] = 1;
    st.view[0] = st.view[4] = st.view[8] = 1;
    const float fov = 1.0f / std::tan(0.5f * 1.0471976f), aspect = 480.0f / 272.0f, zn = 0.5f, zf = 1000.0f;
    for (int i = 0; i < 16; ++i) st.proj[i] = 0;
    st.proj[0] = float24(toFloat24(fov / aspect));
    st.proj[5] = float24(toFloat24(fov));
    st.proj[10] = float24(toFloat24((zf + zn) / (zn - zf)));
    st.proj[11] = -1;
    st.proj[14] = float24(toFloat24(2 * zf * zn / (zn - zf)));
    setF(st, GE_CMD_SX, 240), setF(st, GE_CMD_SY, -136), setF(st, GE_CMD_SZ, -32767.5f);
    setF(st, GE_CMD_TX, 2048), setF(st, GE_CMD_TY, 2048), setF(st, GE_CMD_TZ, 32767.5f);
    setReg(st, GE_CMD_OFFSETX, (2048 - 240) * 16 + 5);
    setReg(st, GE_CMD_OFFSETY, (2048 - 136) * 16 + 11);
    setReg(st, GE_CMD_SCISSOR1, 0);
    setReg(st, GE_CMD_SCISSOR2, 479 | 271 << 10);
    setReg(st, GE_CMD_REGION2, 479 | 271 << 10);
    setReg(st, GE_CMD_TME, sc.texture);
    setReg(st, GE_CMD_TSIZE0, 6 | 5 << 8);
    setF(st, GE_CMD_SU, 1.25f), setF(st, GE_CMD_SV, 0.75f), setF(st, GE_CMD_TU, 0.125f), setF(st, GE_CMD_TV, -0.25f);
    setReg(st, GE_CMD_FGE, sc.fog);
    setF(st, GE_CMD_FOG1, 12.0f), setF(st, GE_CMD_FOG2, 0.0625f);
    setReg(st, GE_CMD_CLE, sc.cle);
    setReg(st, GE_CMD_BCE, sc.cull);
    setReg(st, GE_CMD_CULL, sc.ccw);
    setReg(st, GE_CMD_SHADE, !sc.flat);
    if (sc.tweak) sc.tweak(st);
    return st;
}

std::vector<u8> vertexBytes(const Scene& sc) {
    const VertexLayout l = VertexLayout::fromVtype(kVtype);
    std::vector<u8> bytes(size_t(l.size) * sc.verts.size());
    auto putF = [](u8* p, float v) {
        u32 bits;
        std::memcpy(&bits, &v, 4);
        writeLE32(p, bits);
    };
    for (size_t i = 0; i < sc.verts.size(); ++i) {
        u8* p = bytes.data() + i * size_t(l.size);
        const Vtx& v = sc.verts[i];
        putF(p + l.tcOff, v.u), putF(p + l.tcOff + 4, v.v);
        writeLE32(p + l.colOff, v.abgr);
        putF(p + l.posOff, v.x), putF(p + l.posOff + 4, v.y), putF(p + l.posOff + 8, v.z);
    }
    return bytes;
}

GLenum glMode(GePrimType p) {
    return p == GE_PRIM_TRIANGLE_STRIP ? GL_TRIANGLE_STRIP : (p == GE_PRIM_TRIANGLE_FAN ? GL_TRIANGLE_FAN : GL_TRIANGLES);
}

// The CPU path: VertexPipeline on the scene, as the translator runs it for this PRIM.
gl::Geometry cpuGeometry(const GeState& st, const Scene& sc, const std::vector<u8>& bytes) {
    Memory mem;
    const u32 base = 0x08800000, ibase = 0x08A00000;
    std::memcpy(mem.ptr(base, u32(bytes.size())), bytes.data(), bytes.size());
    if (!sc.indices.empty())
        std::memcpy(mem.ptr(ibase, u32(sc.indices.size() * 2)), sc.indices.data(), sc.indices.size() * 2);
    PrimPacket p;
    p.state = &st;
    p.prim = sc.prim;
    p.count = u32(sc.indices.empty() ? sc.verts.size() : sc.indices.size());
    p.vtype = st.op(GE_CMD_VTYPE);
    p.vertexAddr = base;
    p.indexAddr = ibase;
    gl::VertexPipeline vp{geo::AccuracyProfile::ppsspp()};
    gl::Geometry g;
    std::string err;
    EXPECT_TRUE(vp.processPrim(mem, st, p, g, &err)) << err;
    return g;
}

// How the scene's input triangles meet the near plane: [k] = triangles with k vertices beyond it.
std::array<int, 4> beyondCounts(const GeState& st, const Scene& sc) {
    const geo::TransformState ts = geo::makeTransformState(st, kVtype, true, false);
    std::vector<geo::ClipVertex> cv(sc.verts.size());
    for (size_t i = 0; i < sc.verts.size(); ++i) {
        DecodedVertex dv;
        dv.pos[0] = sc.verts[i].x, dv.pos[1] = sc.verts[i].y, dv.pos[2] = sc.verts[i].z;
        geo::transformVertex(ts, dv, cv[i]);
    }
    std::vector<u32> seq;
    for (size_t i = 0; i < (sc.indices.empty() ? sc.verts.size() : sc.indices.size()); ++i)
        seq.push_back(sc.indices.empty() ? u32(i) : sc.indices[i]);
    std::array<int, 4> n{};
    auto tri = [&](u32 a, u32 b, u32 c) {
        ++n[size_t(geo::beyondNear(cv[a]) + geo::beyondNear(cv[b]) + geo::beyondNear(cv[c]))];
    };
    for (size_t i = 2; i < seq.size(); ++i) {
        if (sc.prim == GE_PRIM_TRIANGLES && i % 3 == 2) tri(seq[i - 2], seq[i - 1], seq[i]);
        if (sc.prim == GE_PRIM_TRIANGLE_STRIP) tri(seq[i - 2], seq[i - 1], seq[i]);
        if (sc.prim == GE_PRIM_TRIANGLE_FAN) tri(seq[0], seq[i - 1], seq[i]);
    }
    return n;
}

// ---------------------------------------------------------------------------------------------
// Comparison.

struct Result {
    int gpuVerts = 0, cpuVerts = 0;  // emitted vertices (3 per triangle)
    int bad = 0;                     // vertices that differ in any output
    std::array<int, 4> beyond{};     // input triangles by vertices beyond the near plane
    std::string first, error;
    std::string summary() const {
        char buf[256];
        std::snprintf(buf, sizeof buf, "GS %d vertices, CPU %d; %d differ; input triangles beyond near 0/1/2/3: %d/%d/%d/%d",
                      gpuVerts, cpuVerts, bad, beyond[0], beyond[1], beyond[2], beyond[3]);
        return std::string(buf) + (first.empty() ? "" : "\nfirst: " + first) + error;
    }
    bool exact() const { return error.empty() && bad == 0 && gpuVerts == cpuVerts; }
};

bool same(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

Result runScene(Harness* H, const Scene& sc, const GsEdit* edit = nullptr) {
    Result r;
    const GeState st = sceneState(sc);
    const std::vector<u8> bytes = vertexBytes(sc);
    sg::HwVsKey key = sg::hwVsKeyFromState(st, st.TME_on() && !st.isClearMode(), st.FGE_on() && !st.isThrough());
    key.primKind = u8(sc.prim == GE_PRIM_TRIANGLE_STRIP ? 1 : (sc.prim == GE_PRIM_TRIANGLE_FAN ? 2 : 0));
    sg::canonicalize(key);
    sg::HwVsUniforms u;
    sg::hwVsUniformsFromState(st, u);
    std::string log;
    const GLuint prog = H->program(key, edit, "", true, log);
    if (!prog) {
        r.error = "\nprogram for " + sg::describe(key) + ": " + log;
        return r;
    }
    H->bindInputs(prog, bytes, u, kNdcX, kNdcY);
    const std::vector<Out> got = H->capture(glMode(sc.prim), int(sc.verts.size()), sc.indices);
    const gl::Geometry cpu = cpuGeometry(st, sc, bytes);
    r.gpuVerts = int(got.size());
    r.cpuVerts = int(cpu.tris.size());
    r.beyond = beyondCounts(st, sc);
    for (size_t i = 0; i < std::min(got.size(), cpu.tris.size()); ++i) {
        const Out& g = got[i];
        const gl::GlVertex& e = cpu.tris[i];
        const float pos[4] = {e.x * kNdcX - 1.0f, e.y * kNdcY - 1.0f, 0.0f, 1.0f};
        std::string what;
        char buf[200];
        auto check = [&](const char* name, const float* gv, const float* ev, int n) {
            for (int k = 0; k < n && what.empty(); ++k)
                if (!same(gv[k], ev[k])) {
                    std::snprintf(buf, sizeof buf, "%s[%d] %.9g, CPU %.9g", name, k, double(gv[k]), double(ev[k]));
                    what = buf;
                }
        };
        const float col[4] = {float(e.color[0]), float(e.color[1]), float(e.color[2]), float(e.color[3])};
        const float col2[3] = {float(e.color2[0]), float(e.color2[1]), float(e.color2[2])};
        check("position", g.pos, pos, 4);
        check("colour", g.color, col, 4);
        check("secondary", g.color2, col2, 3);
        check("z", &g.z, &e.z, 1);
        check("fog", &g.fog, &e.fog, 1);
        if (sc.texture) check("tex", g.tex, e.tex, 4);
        if (!what.empty() && r.bad++ == 0) {
            std::snprintf(buf, sizeof buf, "vertex %zu (triangle %zu; CPU x %.4f y %.4f): ", i, i / 3, double(e.x), double(e.y));
            r.first = buf + what;
        }
    }
    return r;
}

#define EXPECT_SCENE(H, sc, name)                                                   \
    [&] {                                                                           \
        const Result r_ = runScene(H, sc);                                          \
        EXPECT_TRUE(r_.exact()) << (name) << ": " << r_.summary();                  \
        if (std::getenv("GE2GL_HW_VERBOSE")) std::printf("%s: %s\n", (name), r_.summary().c_str()); \
        return r_;                                                                  \
    }()

u32 rgba(u32 r, u32 g, u32 b, u32 a = 255) { return r | g << 8 | b << 16 | a << 24; }

// A triangle list: every triangle of `tris` as given (and, with `both`, also reversed).
Scene listScene(const std::vector<std::array<Vtx, 3>>& tris, bool both = true) {
    Scene sc;
    sc.prim = GE_PRIM_TRIANGLES;
    for (const auto& t : tris) {
        sc.verts.insert(sc.verts.end(), t.begin(), t.end());
        if (both) sc.verts.insert(sc.verts.end(), {t[2], t[1], t[0]});
    }
    return sc;
}

// A band of `n` vertices from z = z0 to z1 (view space), alternating between x = xl and xr: as a
// strip it is a floor running toward the camera; colours and UV vary along it.
std::vector<Vtx> band(int n, float z0, float z1, float xl = -0.4f, float xr = 1.8f) {
    std::vector<Vtx> v;
    for (int i = 0; i < n; ++i) {
        const float t = float(i) / float(n - 1);
        const bool right = i & 1;
        v.push_back({(right ? xr : xl) + 0.3f * t, -1.0f + 0.3f * t * t, z0 + (z1 - z0) * t,
                     rgba(u32(40 + 200 * t), u32(250 - 37 * i % 200), u32(17 * i % 256), u32(255 - 5 * i)),
                     0.1f * float(i), right ? 1.0f : 0.0f});
    }
    return v;
}

// A fan around a centre in front of the camera with rim vertices reaching behind it.
std::vector<Vtx> fan(int rim, float cz, float reach) {
    std::vector<Vtx> v;
    v.push_back({0.8f, -0.5f, cz, rgba(255, 255, 255), 0.5f, 0.5f});
    for (int i = 0; i < rim; ++i) {
        const float a = 6.2831853f * float(i) / float(rim) + 0.3f;
        v.push_back({0.9f + 1.2f * std::cos(a), 0.6f * std::sin(a) - 0.5f, cz + reach * std::sin(a * 1.7f + 0.5f),
                     rgba(u32(128 + 127 * std::cos(a)), u32(30 * i % 256), u32(255 - 20 * i), 200),
                     std::cos(a), std::sin(a)});
    }
    return v;
}

// Clip z = view z = −w: every vertex exactly on the near plane (neither beyond nor on a depth
// side), so the "three vertices with w < 0" rule alone drops the first two triangles; the last
// two (one vertex with w > 0) are drawn.
Scene wOnPlaneScene() {
    Scene sc = listScene({{Vtx{-1, -1, 4}, Vtx{1, -1, 4}, Vtx{0, 1, 5}}, {Vtx{-1, -1, 4}, Vtx{1, -1, 4}, Vtx{0, 1, -5}}});
    sc.tweak = [](GeState& st) {
        st.proj[10] = 1;
        st.proj[14] = 0;
    };
    return sc;
}

// ---------------------------------------------------------------------------------------------
// Tests: the emitted triangles are the CPU's.

TEST(GlHwClip, UnclippedTrianglesAreTheCpuTriangles) {
    REQUIRE_GL();
    // Nothing beyond the near plane: the triangles as they are (winding for lists, ring order
    // for strips and fans), every attribute toGl's.
    Scene list = listScene({{Vtx{-3, -1, -5, rgba(255, 0, 0), 0, 0}, Vtx{3, -1, -5, rgba(0, 255, 0), 1, 0},
                             Vtx{0, 1.5f, -8, rgba(0, 0, 255, 9), 0.5f, 1}},
                            {Vtx{-1, 0, -2, rgba(9, 99, 199)}, Vtx{0.5f, 0.7f, -3, rgba(200, 100, 0)},
                             Vtx{0.2f, -0.6f, -1.5f, rgba(1, 2, 3)}}});
    EXPECT_SCENE(H, list, "list");
    Scene strip;
    strip.prim = GE_PRIM_TRIANGLE_STRIP;
    strip.verts = band(11, -20, -2);
    const Result rs = EXPECT_SCENE(H, strip, "strip");
    EXPECT_EQ(rs.cpuVerts, 9 * 3);
    Scene f;
    f.prim = GE_PRIM_TRIANGLE_FAN;
    f.verts = fan(9, -6, 1.5f);
    const Result rf = EXPECT_SCENE(H, f, "fan");
    EXPECT_EQ(rf.cpuVerts, 8 * 3);
    // Indexed strip (the ring follows draw positions, not index values) and no texture/fog.
    strip.indices = {10, 3, 7, 1, 0, 9, 2, 5, 4};
    strip.texture = strip.fog = false;
    EXPECT_SCENE(H, strip, "indexed strip");
}

TEST(GlHwClip, OneVertexBeyondTheNearPlane) {
    REQUIRE_GL();
    // One vertex between the camera and the near plane (w > 0) or behind the camera (w < 0),
    // in each position of the triangle, both windings: a quadrilateral fanned in two pieces.
    for (float zOut : {-0.3f, 0.0f, 2.0f, 25.0f}) {
        std::vector<std::array<Vtx, 3>> tris;
        const Vtx in1{-0.3f, -0.5f, -1.5f, rgba(255, 0, 0), 0, 0}, in2{0.4f, -0.6f, -1.2f, rgba(0, 255, 0, 128), 1, 0};
        const Vtx out{0.1f, -0.5f, zOut, rgba(0, 0, 255), 0.5f, 1};
        tris.push_back({in1, in2, out});
        tris.push_back({out, in1, in2});
        tris.push_back({in2, out, in1});
        Scene sc = listScene(tris);
        char name[64];
        std::snprintf(name, sizeof name, "one beyond at z %g", double(zOut));
        const Result r = EXPECT_SCENE(H, sc, name);
        EXPECT_EQ(r.beyond[1], 6) << name;
        EXPECT_EQ(r.cpuVerts, 6 * 6) << name;  // every triangle: two pieces
    }
}

TEST(GlHwClip, TwoVerticesBeyondTheNearPlane) {
    REQUIRE_GL();
    for (float zOut : {-0.4f, 1.0f, 3.0f}) {
        std::vector<std::array<Vtx, 3>> tris;
        const Vtx in{0.1f, -0.5f, -3, rgba(255, 128, 0), 0.25f, 0.75f};
        const Vtx o1{-0.3f, -0.5f, zOut, rgba(0, 255, 64, 77), 0, 0}, o2{0.3f, -0.4f, zOut + 0.5f, rgba(10, 20, 255), 1, 0};
        tris.push_back({in, o1, o2});
        tris.push_back({o2, in, o1});
        tris.push_back({o1, o2, in});
        Scene sc = listScene(tris);
        char name[64];
        std::snprintf(name, sizeof name, "two beyond at z %g", double(zOut));
        const Result r = EXPECT_SCENE(H, sc, name);
        EXPECT_EQ(r.beyond[2], 6) << name;
        EXPECT_EQ(r.cpuVerts, 6 * 3) << name;  // every triangle: one piece
    }
}

TEST(GlHwClip, StripsCrossingTheNearPlane) {
    REQUIRE_GL();
    // Floors running through the near plane and past the camera: odd and even triangles, one
    // and two vertices beyond, the ring starting at every slot; as arrays and through indices.
    int clipped = 0;
    for (int n : {4, 5, 9, 14}) {
        for (float z1 : {0.2f, 3.0f}) {
            Scene sc;
            sc.prim = GE_PRIM_TRIANGLE_STRIP;
            sc.verts = band(n, -4, z1);
            const Result r = EXPECT_SCENE(H, sc, "strip");
            clipped += r.beyond[1] + r.beyond[2];
            std::vector<u16> idx;
            for (int i = 0; i < n; ++i) idx.push_back(u16(n - 1 - i));  // the other way round
            sc.indices = idx;
            const Result ri = EXPECT_SCENE(H, sc, "indexed strip");
            clipped += ri.beyond[1] + ri.beyond[2];
        }
    }
    EXPECT_GT(clipped, 20);
}

TEST(GlHwClip, FansCrossingTheNearPlane) {
    REQUIRE_GL();
    int clipped = 0;
    for (int rim : {3, 4, 7, 12}) {
        for (float cz : {-1.2f, -3.0f}) {
            Scene sc;
            sc.prim = GE_PRIM_TRIANGLE_FAN;
            sc.verts = fan(rim, cz, 3.5f);
            const Result r = EXPECT_SCENE(H, sc, "fan");
            clipped += r.beyond[1] + r.beyond[2];
            sc.indices.clear();
            for (int i = 0; i <= rim; ++i) sc.indices.push_back(u16(i == 0 ? 0 : rim + 1 - i));
            const Result ri = EXPECT_SCENE(H, sc, "indexed fan");
            clipped += ri.beyond[1] + ri.beyond[2];
        }
    }
    EXPECT_GT(clipped, 20);
}

TEST(GlHwClip, NewVertexOffScreenDropsItsPieces) {
    REQUIRE_GL();
    // The outside vertex far to the side: the cut lands left of screen X 0 on one edge only, so
    // the fan pieces using that new vertex are dropped (clipTriangleNear's screen-range rule).
    // Which pieces use it depends on where the polygon starts, the triangle's first vertex and
    // the rotation rule: from a, one piece is kept (either winding), from far1, none.
    const Vtx a{6, -1, -20, rgba(255, 0, 0), 0, 0}, b{0, -1, -4, rgba(0, 255, 0), 1, 0};
    const Vtx far1{-30, -1, 40, rgba(0, 0, 255), 0, 1};
    Scene sc = listScene({{a, b, far1}, {far1, a, b}});
    const Result r = EXPECT_SCENE(H, sc, "one new vertex off screen");
    EXPECT_EQ(r.beyond[1], 4);
    EXPECT_EQ(r.cpuVerts, 2 * 3);
    // Both new vertices off screen: the whole triangle goes.
    const Vtx far3{400, -1, 40, rgba(0, 0, 255), 0, 1}, far4{-400, -1, 40, rgba(0, 0, 255), 0, 1};
    Scene both = listScene({{Vtx{0, -1, -3, rgba(9, 9, 9)}, far3, far4}});
    const Result r2 = EXPECT_SCENE(H, both, "both new vertices off screen");
    EXPECT_EQ(r2.cpuVerts, 0);
}

TEST(GlHwClip, CullingOfClippedPieces) {
    REQUIRE_GL();
    // GE culling on each piece in the primitive's winding (pieces of reversed rings are emitted
    // the other way round), clockwise and counter-clockwise culled; CLE-independent.
    for (int ccw = 0; ccw < 2; ++ccw) {
        int drawn = 0, culled = 0;
        for (GePrimType prim : {GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN, GE_PRIM_TRIANGLES}) {
            Scene sc;
            sc.prim = prim;
            sc.cull = true;
            sc.ccw = ccw;
            sc.verts = prim == GE_PRIM_TRIANGLE_FAN ? fan(10, -1.5f, 3.0f) : band(12, -5, 2.5f);
            const Result r = EXPECT_SCENE(H, sc, ccw ? "cull ccw" : "cull cw");
            EXPECT_GT(r.beyond[1] + r.beyond[2], 0);
            sc.cull = false;
            const Result all = runScene(H, sc);
            drawn += r.cpuVerts;
            culled += all.cpuVerts - r.cpuVerts;
        }
        EXPECT_GT(drawn, 0);
        EXPECT_GT(culled, 0);
    }
}

TEST(GlHwClip, FlatShadingKeepsTheProvokingColour) {
    REQUIRE_GL();
    for (GePrimType prim : {GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN, GE_PRIM_TRIANGLES}) {
        Scene sc;
        sc.prim = prim;
        sc.flat = true;
        sc.verts = prim == GE_PRIM_TRIANGLE_FAN ? fan(8, -2.0f, 3.0f) : band(9, -4, 2.0f);
        const Result r = EXPECT_SCENE(H, sc, "flat");
        EXPECT_GT(r.beyond[1] + r.beyond[2], 0);
        EXPECT_GT(r.cpuVerts, 0);
    }
}

TEST(GlHwClip, DiscardRulesCle0AndCle1) {
    REQUIRE_GL();
    const Vtx a{-1, -1, -4, rgba(255, 0, 0)}, b{1, -1, -4, rgba(0, 255, 0)}, c{0, 1, -5, rgba(0, 0, 255)};
    for (int cle = 0; cle < 2; ++cle) {
        auto run = [&](const std::vector<std::array<Vtx, 3>>& tris, const char* name) {
            Scene sc = listScene(tris);
            sc.cle = cle;
            return EXPECT_SCENE(H, sc, (std::string(name) + (cle ? " (CLE 1)" : " (CLE 0)")).c_str());
        };
        // Reference: drawn.
        EXPECT_EQ(run({{a, b, c}}, "plain").cpuVerts, 6);
        // A vertex off the 4096² screen: dropped with either CLE.
        EXPECT_EQ(run({{a, b, Vtx{-200, 1, -5}}}, "off screen").cpuVerts, 0);
        // One vertex beyond the far plane: CLE 0 drops, CLE 1 draws (Z clamped).
        EXPECT_EQ(run({{a, b, Vtx{0, 1, -2000}}}, "one far").cpuVerts, cle ? 6 : 0);
        // All three beyond the far plane: dropped with either CLE.
        EXPECT_EQ(run({{Vtx{-900, -900, -2000}, Vtx{900, -900, -2000}, Vtx{0, 900, -2500}}}, "all far").cpuVerts, 0);
        // One vertex beyond the near plane: CLE 0 drops the triangle, CLE 1 clips it.
        EXPECT_EQ(run({{a, b, Vtx{0, -1, -0.2f}}}, "one near").cpuVerts, cle ? 12 : 0);
        // All three behind the camera (w < 0): dropped.
        EXPECT_EQ(run({{Vtx{-1, -1, 4}, Vtx{1, -1, 4}, Vtx{0, 1, 5}}}, "all w < 0").cpuVerts, 0);
        // All three with w < 0 but on the near plane (a projection with z_clip = −w): only the
        // w rule drops them; one with w > 0 keeps the triangle.
        Scene onPlane = wOnPlaneScene();
        onPlane.cle = cle;
        EXPECT_EQ(EXPECT_SCENE(H, onPlane, "w < 0 on the near plane").cpuVerts, 6);
    }
    // No position in the format: every vertex and so every triangle is dropped.
    Scene none = listScene({{a, b, c}});
    none.tweak = [](GeState& st) { setReg(st, GE_CMD_VTYPE, kVtype & ~(3u << 7)); };
    const Result r = runScene(H, none);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.gpuVerts, 0);
}

// Random vertices around the near plane in lists, strips and fans, with random switches.
Scene randomScene(std::mt19937& g, int i) {
    auto uni = [&](float a, float b) { return std::uniform_real_distribution<float>(a, b)(g); };
    Scene sc;
    sc.prim = i % 3 == 0 ? GE_PRIM_TRIANGLES : (i % 3 == 1 ? GE_PRIM_TRIANGLE_STRIP : GE_PRIM_TRIANGLE_FAN);
    const int n = sc.prim == GE_PRIM_TRIANGLES ? 60 : 24;
    for (int k = 0; k < n; ++k) {
        // Mostly where cuts stay on screen, some anywhere.
        const bool wide = g() % 6 == 0;
        Vtx v{wide ? uni(-4, 4) : uni(-0.6f, 3), wide ? uni(-3, 3) : uni(-2, 0.4f), uni(-6, 3), u32(g()), uni(-2, 2),
              uni(-2, 2)};
        if (sc.prim == GE_PRIM_TRIANGLE_STRIP) v.z = -4.0f + 0.3f * float(k) + uni(-1, 1);
        if (sc.prim == GE_PRIM_TRIANGLE_FAN && k == 0) v.z = uni(-3, -1);
        sc.verts.push_back(v);
    }
    sc.cle = g() % 8 != 0;
    sc.cull = g() % 2;
    sc.ccw = g() % 2;
    sc.flat = g() % 4 == 0;
    sc.texture = g() % 4 != 0;
    sc.fog = g() % 2;
    return sc;
}

TEST(GlHwClip, RandomScenesAroundTheNearPlane) {
    REQUIRE_GL();
    std::mt19937 g(1234);
    int clipped = 0, emitted = 0;
    for (int i = 0; i < 40; ++i) {
        const Scene sc = randomScene(g, i);
        const Result r = runScene(H, sc);
        EXPECT_TRUE(r.exact()) << "random scene " << i << ": " << r.summary();
        clipped += r.beyond[1] + r.beyond[2];
        emitted += r.cpuVerts / 3;
    }
    std::printf("random scenes: %d clipped input triangles, %d triangles emitted\n", clipped, emitted);
    EXPECT_GT(clipped, 200);
}

TEST(GlHwClip, EachRuleIsNeeded) {
    REQUIRE_GL();
    // The comparison must see each rule of the shader: with one broken at a time, at least one
    // of the scenes differs from the CPU. (Otherwise "exact" would prove little.)
    struct Break {
        const char* name;
        const char* from;
        const char* to;
    };
    const Break breaks[] = {
        {"strip ring", "#if GE_PRIM == 1", "#if GE_PRIM == 99"},
        {"fan ring", "if ((id & 1) != 0) {", "if (false) {"},
        {"ring ids", "int(texelFetch(u_ring, gl_PrimitiveIDIn).r)", "0"},
        {"colour weights", "r.col = (a.col * (256 - k) + b.col * k) / 256;", "r.col = ivec4(mix(vec4(a.col), vec4(b.col), t));"},
        {"lerp direction", "o[n] = lerpV(inp[j], inp[i], fdiv(dq, den));",
         "o[n] = lerpV(inp[i], inp[j], fdiv(dp, dp - dq));"},
        {"rotation rule", "if (sign64(area2) < 0) {", "if (false) {"},
        {"off-screen pieces", "v.outside = isNan(xs)", "v.outside = false;\n  bool unused = isNan(xs)"},
        {"cull sense", "return GE_CULL_CCW != 0 ? s < 0 : s > 0;", "return GE_CULL_CCW != 0 ? s > 0 : s < 0;"},
        {"cull winding of reversed pieces", "int k1 = reversed ? k + 1 : k, k2 = reversed ? k : k + 1;",
         "int k1 = k, k2 = k + 1;"},
        {"flat provoking vertex", "emitTriangle(poly[0], poly[k], poly[k + 1], v[2]);",
         "emitTriangle(poly[0], poly[k], poly[k + 1], poly[k + 1]);"},
        {"CLE 1 all-far rule", "if (nearCount == 3 || farCount == 3) return;", ""},
        {"w < 0 rule", "if (v[0].clip.w < 0.0 && v[1].clip.w < 0.0 && v[2].clip.w < 0.0) return;", ""},
        {"sample shift", "gx = gx + GE_SHIFT;", "gx = gx;"},
        {"snap of new vertices", "v.scr = ivec3(to16(xs, GE_OFFX)", "v.scr = ivec3(to16(xs + 0.03, GE_OFFX)"},
        {"fog lerp", "r.stqf = a.stqf + ma;", "r.stqf = a.stqf + vec4(ma.xyz, 0.0);"},
    };
    std::vector<Scene> scenes;  // tried in order until one differs
    for (GePrimType prim : {GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN}) {
        Scene sc;
        sc.prim = prim;
        sc.verts = prim == GE_PRIM_TRIANGLE_FAN ? fan(10, -1.5f, 3.0f) : band(12, -5, 2.5f);
        sc.flat = true;
        scenes.push_back(sc);
        sc.flat = false, sc.cull = true;
        scenes.push_back(sc);
    }
    scenes.push_back(listScene({{Vtx{6, -1, -20}, Vtx{0, -1, -4}, Vtx{-30, -1, 40}},
                                {Vtx{-900, -900, -2000}, Vtx{900, -900, -2000}, Vtx{0, 900, -2500}}}));
    scenes.push_back(wOnPlaneScene());
    std::mt19937 g(99);
    for (int i = 0; i < 6; ++i) scenes.push_back(randomScene(g, i));
    for (const Scene& sc : scenes) {
        const Result r = runScene(H, sc);
        ASSERT_TRUE(r.exact()) << r.summary();
    }
    for (const Break& br : breaks) {
        const GsEdit edit{br.from, br.to};
        bool noticed = false;
        for (size_t i = 0; i < scenes.size() && !noticed; ++i) {
            const Result r = runScene(H, scenes[i], &edit);
            ASSERT_TRUE(r.error.empty()) << br.name << r.error;
            noticed = !r.exact();
            if (noticed && std::getenv("GE2GL_HW_VERBOSE"))
                std::printf("broken %s: scene %zu differs: %s\n", br.name, i, r.summary().c_str());
        }
        EXPECT_TRUE(noticed) << "breaking the " << br.name << " went unnoticed";
    }
}

TEST(GlHwClip, LinksWithTheFragmentShaders) {
    REQUIRE_GL();
    // The geometry shader's outputs are the translator's fragment shader inputs (names, types and
    // interpolation qualifiers must match to link): flat and Gouraud, textured or not, per prim.
    int linked = 0;
    for (int i = 0; i < 12; ++i) {
        Scene sc;
        sc.prim = i % 3 == 0 ? GE_PRIM_TRIANGLES : (i % 3 == 1 ? GE_PRIM_TRIANGLE_STRIP : GE_PRIM_TRIANGLE_FAN);
        sc.flat = i % 2;
        sc.texture = i % 4 < 2;
        sc.fog = i % 5 < 3;
        sc.cle = i % 3 != 2;
        const GeState st = sceneState(sc);
        const sg::HostCaps caps = H->ctx->caps().hostCaps(false, true);
        const sg::DrawFlags flags = sg::DrawFlags::fromState(st, ge::geo::AccuracyProfile::ppsspp());
        const sg::PipelineKeys keys = sg::keysFromState(st, flags, caps, false);
        std::string fs, log;
        ASSERT_TRUE(sg::generateFragmentShader(keys.fs, caps, fs, &log)) << log;
            sg::HwVsKey key = sg::hwVsKeyFromState(st, st.TME_on() && !st.isClearMode(), st.FGE_on() && !st.isThrough());
        key.primKind = u8(i % 3);
        // Every other one as drivers without doubles get it (float divisions).
        const GsEdit noFp64{"#extension GL_ARB_gpu_shader_fp64 : enable\n",
                            "#extension GL_ARB_gpu_shader_fp64 : enable\n#define GE_NO_FP64\n"};
        const GLuint prog = H->program(key, i % 2 ? &noFp64 : nullptr, fs, false, log);
        EXPECT_NE(prog, 0u) << sg::describe(key) << "\n" << log;
        linked += prog != 0;
    }
    EXPECT_EQ(linked, 12);
}

// ---------------------------------------------------------------------------------------------
// Rendering: what GL draws from the emitted triangles, against the software rasteriser.

constexpr int kTargetW = 480, kTargetH = 272;
const char* const kColorFs =
    "#version 330 core\nnoperspective in vec4 v_color;\nout vec4 o_color;\n"
    "void main() { o_color = vec4(v_color.rgb / 255.0, 1.0); }\n";

// Draws the scene into a cleared 480×272 RGBA8 target (row y = drawing row y) and returns its
// pixels (R in bits 0–7).
std::vector<u32> render(Harness* H, const Scene& sc) {
    static GLuint fbo = 0, tex = 0;
    const gl::GlFuncs& f = H->ctx->f();
    if (!fbo) {
        f.GenTextures(1, &tex);
        f.BindTexture(GL_TEXTURE_2D, tex);
        f.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kTargetW, kTargetH, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        f.GenFramebuffers(1, &fbo);
        f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
        f.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    }
    std::vector<u32> px(size_t(kTargetW) * kTargetH, 0);
    const GeState st = sceneState(sc);
    sg::HwVsKey key = sg::hwVsKeyFromState(st, false, false);
    key.primKind = u8(sc.prim == GE_PRIM_TRIANGLE_STRIP ? 1 : (sc.prim == GE_PRIM_TRIANGLE_FAN ? 2 : 0));
    sg::HwVsUniforms u;
    sg::hwVsUniformsFromState(st, u);
    std::string log;
    const GLuint prog = H->program(key, nullptr, kColorFs, false, log);
    if (!prog) {
        ADD_FAILURE() << log;
        return px;
    }
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f.Viewport(0, 0, kTargetW, kTargetH);
    const float zero[4] = {0, 0, 0, 0};
    f.ClearBufferfv(GL_COLOR, 0, zero);
    H->bindInputs(prog, vertexBytes(sc), u, 2.0f / kTargetW, 2.0f / kTargetH);
    H->draw(glMode(sc.prim), int(sc.verts.size()), sc.indices);
    f.ReadPixels(0, 0, kTargetW, kTargetH, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    f.BindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
}

// The CPU path's pixels: VertexPipeline's clipped, culled triangles through the software
// rasteriser (colour only), in the emitted order.
std::vector<u32> cpuRender(const Scene& sc) {
    std::vector<u32> px(size_t(kTargetW) * kTargetH, 0);
    const GeState st = sceneState(sc);
    const gl::Geometry g = cpuGeometry(st, sc, vertexBytes(sc));
    geo::RasterParams rp;
    rp.clipX1 = 0, rp.clipY1 = 0, rp.clipX2 = kTargetW - 1, rp.clipY2 = kTargetH - 1;
    std::vector<geo::Fragment> buf(1024);
    auto flush = [](void* ctx, const geo::Fragment* f, size_t count) {
        auto* out = static_cast<std::vector<u32>*>(ctx);
        for (size_t i = 0; i < count; ++i)
            (*out)[size_t(f[i].y) * kTargetW + size_t(f[i].x)] =
                f[i].color[0] | u32(f[i].color[1]) << 8 | u32(f[i].color[2]) << 16 | 0xFF000000u;
    };
    geo::FragmentSink sink(buf.data(), buf.size(), flush, &px);
    // GlVertex back to the rasteriser's ScreenVertex (x16 from the shifted drawing position).
    const float shift = float(8 - geo::triangleSampleOffset(rp)) / 16.0f;
    auto sv = [&](const gl::GlVertex& v) {
        geo::ScreenVertex s;
        s.x = int(std::lround((v.x - shift) * 16.0f));
        s.y = int(std::lround((v.y - shift) * 16.0f));
        s.z = int(v.z);
        std::memcpy(s.color, v.color, 4);
        return s;
    };
    for (size_t i = 0; i + 2 < g.tris.size(); i += 3)
        geo::rasterTriangle(rp, sv(g.tris[i]), sv(g.tris[i + 1]), sv(g.tris[i + 2]), sv(g.tris[i + 2]), geo::Band{},
                            sink);
    sink.flush();
    return px;
}

u32 at(const std::vector<u32>& px, int x, int y) { return px[size_t(y) * kTargetW + size_t(x)]; }

TEST(GlHwClip, RenderedPixelsMatchTheCpuRasteriser) {
    REQUIRE_GL();
    // Coverage exact and colours within GL's float interpolation (±1), clipped or not; before
    // the geometry shader, GL's own clipper moved the cut edge and extrapolated colours.
    struct Case {
        const char* name;
        std::vector<std::array<float, 3>> pos;
    };
    const Case cases[] = {
        {"in front", {{-3, -1, -5}, {3, -1, -5}, {0, 1.5f, -8}}},
        {"behind the camera", {{-0.4f, -1, -5}, {3, -1, -5}, {0.3f, -1, 2}}},
        {"between camera and near plane", {{-3, -1, -5}, {3, -1, -5}, {0, -1, -0.3f}}},
        {"two vertices behind", {{-0.3f, -1, 3}, {0.9f, -1, 3}, {0.3f, -1, -6}}},
    };
    const u32 colors[3] = {0xFF0000F0u, 0xFF00F000u, 0xFFF00000u};
    for (const Case& c : cases) {
        Scene sc;
        sc.texture = sc.fog = false;
        for (int i = 0; i < 3; ++i) sc.verts.push_back({c.pos[size_t(i)][0], c.pos[size_t(i)][1], c.pos[size_t(i)][2], colors[i]});
        const std::vector<u32> glPx = render(H, sc), cpu = cpuRender(sc);
        int both = 0, onlyGl = 0, onlyCpu = 0, maxDiff = 0;
        for (size_t i = 0; i < glPx.size(); ++i) {
            const bool g = glPx[i] != 0, k = cpu[i] != 0;
            if (g && k)
                for (int ch = 0; ch < 3; ++ch)
                    maxDiff = std::max(maxDiff, std::abs(int((glPx[i] >> (8 * ch)) & 255) - int((cpu[i] >> (8 * ch)) & 255)));
            both += g && k, onlyGl += g && !k, onlyCpu += k && !g;
        }
        std::printf("near clip, %s: %d pixels both, %d GL only, %d CPU only, max colour difference %d\n", c.name, both,
                    onlyGl, onlyCpu, maxDiff);
        EXPECT_GT(both, 1000) << c.name;
        EXPECT_EQ(onlyGl + onlyCpu, 0) << c.name;
        EXPECT_LE(maxDiff, 1) << c.name;
    }
}

TEST(GlHwClip, DiscardRulesOnTheRasteriser) {
    REQUIRE_GL();
    // Strip v0 v1 v2 v3 (view space at z −2, so x ±1.1 is about ±240 pixels): with v0 off the
    // 4096² screen the first triangle draws nothing while its neighbour draws; with v0 on screen
    // both draw.
    Scene sc;
    sc.prim = GE_PRIM_TRIANGLE_STRIP;
    sc.texture = sc.fog = false;
    const u32 red = 0xFF0000FFu;
    sc.verts = {{-40, 0.4f, -2, red}, {-0.3f, 0.4f, -2, red}, {-0.3f, -0.4f, -2, red}, {0.5f, 0, -2, red}};
    auto px = render(H, sc);
    EXPECT_EQ(at(px, 190, 136), 0u) << "the primitive of an off-screen vertex was drawn";
    EXPECT_EQ(at(px, 240, 136), red) << "its neighbour was not drawn";
    sc.verts[0].x = -0.9f;
    px = render(H, sc);
    EXPECT_EQ(at(px, 190, 136), red);
    EXPECT_EQ(at(px, 240, 136), red);
    // A vertex beyond the near plane: CLE = 1 clips (and draws), CLE = 0 drops.
    Scene nearTri;
    nearTri.texture = nearTri.fog = false;
    nearTri.verts = {{-3, -1, -5, red}, {3, -1, -5, red}, {0, -1, -0.1f, red}};
    px = render(H, nearTri);
    EXPECT_EQ(at(px, 240, 230), red) << "clipped triangle (CLE = 1)";
    nearTri.cle = false;
    px = render(H, nearTri);
    EXPECT_EQ(at(px, 240, 230), 0u) << "vertex beyond the near plane (CLE = 0)";
}

}  // namespace
}  // namespace ge::gltest
