// SPDX-License-Identifier: MIT
// Through-mode PRIMs (VTYPE bit 23) on the GL hardware mode's GPU vertex path: the vertex shader
// (shadergen/hw_vertex.cpp, key.through) and geometry shader (hw_geometry.cpp) against
// translator/vertex_pipeline.cpp VertexPipeline::processPrim on the same state and vertex bytes.
// Transform feedback of the geometry shader's output (GL_TRIANGLES) is compared with
// Geometry::tris vertex for vertex and bit for bit (position, colours, Z, fog, texture
// coordinates), across position formats (s8, s16, float), texture-coordinate formats (u8, u16,
// float), colour formats, with and without indices, lists/strips/fans, culling either way, flat
// shading and clear mode. The transform-mode state (lighting, texture projection, fog, CLE,
// morphing, skinning) is set to values that would change every vertex if through mode used it.
// The harness is tests/gl_hw_clip.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/vertex_decoder.h"
#include "shadergen/hw_vertex.h"
#include "shadergen/shader_gen.h"
#include "translator/gl_context.h"
#include "translator/gl_renderer.h"
#include "translator/vertex_pipeline.h"
#include "tests/gl_hw_harness.h"

namespace ge::gltest {
namespace {

// ---------------------------------------------------------------------------------------------
// Scenes: through-mode vertices in drawing coordinates, written in the scene's VTYPE formats.

struct Vtx {
    double x = 0, y = 0, z = 0;  // written as the position format holds them (s16: integers)
    u32 color = 0xFFFFFFFFu;     // 8888 ABGR, or the 16-bit value of 5650/5551/4444
    double u = 0, v = 0;         // written as the UV format holds them
};

struct Scene {
    GePrimType prim = GE_PRIM_TRIANGLES;
    u32 tc = 3, col = 7, pos = 3;  // VTYPE formats
    u32 nrm = 0, weights = 0, weightCount = 1, morphCount = 1;  // layout only (through ignores them)
    std::vector<Vtx> verts;
    std::vector<u16> indices;  // drawn through 16-bit indices when not empty
    bool cull = false, ccw = false, flat = false, texture = true, clear = false;
    u32 tsize = 6 | 5 << 8;  // TSIZE0: 64 × 32
    std::string name;
};

void setReg(GeState& st, u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }
void setF(GeState& st, u8 cmd, float f) { setReg(st, cmd, toFloat24(f)); }

constexpr float kNdcX = 2.0f / 480.0f, kNdcY = 2.0f / 272.0f;

u32 vtypeOf(const Scene& sc) {
    return sc.tc | sc.col << 2 | sc.nrm << 5 | sc.pos << 7 | sc.weights << 9 | (sc.indices.empty() ? 0u : 2u << 11) |
           (sc.weights ? sc.weightCount - 1 : 0u) << 14 | (sc.morphCount - 1) << 18 | 1u << 23;
}

GeState sceneState(const Scene& sc) {
    GeState st;
    st.reset();
    setReg(st, GE_CMD_VTYPE, vtypeOf(sc));
    // Transform-mode state that through mode must ignore: matrices, viewport, offset, lighting
    // with a material colour, texture projection, fog, CLE, NREV, morph weights, bones.
    for (int i = 0; i < 12; ++i) st.world[i] = st.view[i] = st.tgen[i] = 0.5f + 0.25f * float(i);
    for (int i = 0; i < 16; ++i) st.proj[i] = 0.125f * float(i + 1);
    for (int i = 0; i < 96; ++i) st.bone[i] = 1.5f - 0.03125f * float(i);
    setF(st, GE_CMD_SX, 240), setF(st, GE_CMD_SY, -136), setF(st, GE_CMD_SZ, -32767.5f);
    setF(st, GE_CMD_TX, 2048), setF(st, GE_CMD_TY, 2048), setF(st, GE_CMD_TZ, 32767.5f);
    setReg(st, GE_CMD_OFFSETX, (2048 - 240) * 16 + 5);
    setReg(st, GE_CMD_OFFSETY, (2048 - 136) * 16 + 11);
    setReg(st, GE_CMD_LTE, 1);
    setReg(st, GE_CMD_LE0, 1);
    setReg(st, GE_CMD_LTYPE0, 1 | 1 << 8);
    setReg(st, GE_CMD_TMAP, 1 | 1 << 8);
    setReg(st, GE_CMD_FGE, 1);
    setF(st, GE_CMD_FOG1, 12.0f), setF(st, GE_CMD_FOG2, 0.0625f);
    setReg(st, GE_CMD_CLE, 1);
    setReg(st, GE_CMD_NREV, 1);
    for (int i = 0; i < 8; ++i) setF(st, u8(GE_CMD_WEIGHT0 + i), 0.75f + 0.5f * float(i));
    setF(st, GE_CMD_SU, 1.25f), setF(st, GE_CMD_SV, 0.75f), setF(st, GE_CMD_TU, 0.125f), setF(st, GE_CMD_TV, -0.25f);
    setReg(st, GE_CMD_MAC, 0x3377AA);
    setReg(st, GE_CMD_MAA, 0x5C);
    setReg(st, GE_CMD_SCISSOR1, 0);
    setReg(st, GE_CMD_SCISSOR2, 479 | 271 << 10);
    setReg(st, GE_CMD_REGION2, 479 | 271 << 10);
    setReg(st, GE_CMD_TME, sc.texture);
    setReg(st, GE_CMD_TSIZE0, sc.tsize);
    setReg(st, GE_CMD_BCE, sc.cull);
    setReg(st, GE_CMD_CULL, sc.ccw);
    setReg(st, GE_CMD_SHADE, !sc.flat);
    setReg(st, GE_CMD_CMODE, sc.clear ? 1 | 7 << 8 : 0);
    return st;
}

// Vertex bytes: copy 0 holds the scene's values; the other morph copies and the weight and
// normal bytes hold junk that would change the result if through mode read it.
std::vector<u8> vertexBytes(const Scene& sc) {
    const u32 vtype = vtypeOf(sc);
    const VertexLayout l = VertexLayout::fromVtype(vtype);
    const size_t stride = size_t(l.size) * sc.morphCount;
    std::vector<u8> bytes(stride * sc.verts.size());
    std::mt19937 junk(77);
    for (u8& b : bytes) b = u8(junk());
    auto putF = [](u8* p, double v) {
        const float f = float(v);
        u32 bits;
        std::memcpy(&bits, &f, 4);
        writeLE32(p, bits);
    };
    for (size_t i = 0; i < sc.verts.size(); ++i) {
        u8* p = bytes.data() + i * stride;
        const Vtx& v = sc.verts[i];
        switch (sc.tc) {
        case 1: p[l.tcOff] = u8(v.u), p[l.tcOff + 1] = u8(v.v); break;
        case 2: writeLE16(p + l.tcOff, u16(v.u)), writeLE16(p + l.tcOff + 2, u16(v.v)); break;
        case 3: putF(p + l.tcOff, v.u), putF(p + l.tcOff + 4, v.v); break;
        default: break;
        }
        if (sc.col == 7) writeLE32(p + l.colOff, v.color);
        else if (sc.col >= 4) writeLE16(p + l.colOff, u16(v.color));
        switch (sc.pos) {
        case 1:  // through mode decodes s8 positions as 0: any bytes
            break;
        case 2:
            writeLE16(p + l.posOff, u16(s16(v.x))), writeLE16(p + l.posOff + 2, u16(s16(v.y)));
            writeLE16(p + l.posOff + 4, u16(v.z));
            break;
        default: putF(p + l.posOff, v.x), putF(p + l.posOff + 4, v.y), putF(p + l.posOff + 8, v.z); break;
        }
    }
    return bytes;
}

GLenum glMode(GePrimType p) {
    return p == GE_PRIM_TRIANGLE_STRIP ? GL_TRIANGLE_STRIP : (p == GE_PRIM_TRIANGLE_FAN ? GL_TRIANGLE_FAN : GL_TRIANGLES);
}

int drawCount(const Scene& sc) { return int(sc.indices.empty() ? sc.verts.size() : sc.indices.size()); }

gl::Geometry cpuGeometry(const GeState& st, const Scene& sc, const std::vector<u8>& bytes) {
    Memory mem;
    const u32 base = 0x08800000, ibase = 0x08A00000;
    std::memcpy(mem.ptr(base, u32(bytes.size())), bytes.data(), bytes.size());
    if (!sc.indices.empty())
        std::memcpy(mem.ptr(ibase, u32(sc.indices.size() * 2)), sc.indices.data(), sc.indices.size() * 2);
    PrimPacket p;
    p.state = &st;
    p.prim = sc.prim;
    p.count = u32(drawCount(sc));
    p.vtype = st.op(GE_CMD_VTYPE);
    p.vertexAddr = base;
    p.indexAddr = ibase;
    gl::VertexPipeline vp{geo::AccuracyProfile::ppsspp()};
    gl::Geometry g;
    std::string err;
    EXPECT_TRUE(vp.processPrim(mem, st, p, g, &err)) << err;
    return g;
}

struct Result {
    int gpuVerts = 0, cpuVerts = 0, bad = 0;
    std::string first, error;
    std::string summary() const {
        char buf[128];
        std::snprintf(buf, sizeof buf, "GS %d vertices, CPU %d; %d differ", gpuVerts, cpuVerts, bad);
        return std::string(buf) + (first.empty() ? "" : "\nfirst: " + first) + error;
    }
    bool exact() const { return error.empty() && bad == 0 && gpuVerts == cpuVerts; }
};

bool same(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

sg::HwVsKey sceneKey(const GeState& st, const Scene& sc) {
    sg::HwVsKey key = sg::hwVsKeyFromState(st, st.TME_on() && !st.isClearMode(), st.FGE_on() && !st.isThrough());
    key.primKind = u8(sc.prim == GE_PRIM_TRIANGLE_STRIP ? 1 : (sc.prim == GE_PRIM_TRIANGLE_FAN ? 2 : 0));
    sg::canonicalize(key);
    return key;
}

Result runScene(Harness* H, const Scene& sc, const GsEdit* edit = nullptr) {
    Result r;
    const GeState st = sceneState(sc);
    const std::vector<u8> bytes = vertexBytes(sc);
    const sg::HwVsKey key = sceneKey(st, sc);
    if (!key.through) r.error = "\nkey without through: " + sg::describe(key);
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
        if (sc.texture && !sc.clear) check("tex", g.tex, e.tex, 4);
        if (!what.empty() && r.bad++ == 0) {
            std::snprintf(buf, sizeof buf, "vertex %zu (triangle %zu; CPU x %.4f y %.4f): ", i, i / 3, double(e.x),
                          double(e.y));
            r.first = buf + what;
        }
    }
    return r;
}

#define EXPECT_SCENE(H, sc)                                                                             \
    [&] {                                                                                               \
        const Result r_ = runScene(H, sc);                                                              \
        EXPECT_TRUE(r_.exact()) << (sc).name << ": " << r_.summary();                                   \
        if (std::getenv("GE2GL_HW_VERBOSE")) std::printf("%s: %s\n", (sc).name.c_str(), r_.summary().c_str()); \
        return r_;                                                                                      \
    }()

// The input triangles of a scene (winding order) in x16/y16, as the CPU's through transform
// gives them (for the generator: no zero-area triangle, whose CPU drawing is not GL's).
bool hasZeroArea(const Scene& sc) {
    auto q = [](double f) {
        const double t = std::clamp(double(float(f)) * 16.0, -1048576.0, 1048576.0);
        return s64(t);
    };
    std::vector<const Vtx*> seq;
    for (int i = 0; i < drawCount(sc); ++i) seq.push_back(&sc.verts[sc.indices.empty() ? size_t(i) : sc.indices[size_t(i)]]);
    auto zero = [&](const Vtx* a, const Vtx* b, const Vtx* c) {
        if (sc.pos == 1) return true;
        const s64 ax = q(a->x), ay = q(a->y), bx = q(b->x), by = q(b->y), cx = q(c->x), cy = q(c->y);
        return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) == 0;
    };
    for (size_t i = 2; i < seq.size(); ++i) {
        if (sc.prim == GE_PRIM_TRIANGLES && i % 3 == 2 && zero(seq[i - 2], seq[i - 1], seq[i])) return true;
        if (sc.prim == GE_PRIM_TRIANGLE_STRIP && zero(seq[i - 2], seq[i - 1], seq[i])) return true;
        if (sc.prim == GE_PRIM_TRIANGLE_FAN && zero(seq[0], seq[i - 1], seq[i])) return true;
    }
    return false;
}

// Random vertices in the scene's formats: positions on the 480×272 screen and a little beyond
// (s16 integers; floats with fractions, Z in 0–65535 and beyond for floats), UV spanning the
// format's range, colours of every bit.
void randomVerts(Scene& sc, std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> ux(-40.0, 520.0), uy(-30.0, 300.0), u01(0.0, 1.0);
    for (int tries = 0; tries < 100; ++tries) {
        sc.verts.clear();
        for (int i = 0; i < n; ++i) {
            Vtx v;
            v.x = ux(rng), v.y = uy(rng);
            if (sc.pos == 2) {
                v.x = std::floor(v.x), v.y = std::floor(v.y), v.z = std::floor(u01(rng) * 65535.0);
            } else {
                v.z = u01(rng) * 70000.0 - 2000.0;  // beyond both ends: limited to 0–65535
            }
            v.color = u32(rng());
            switch (sc.tc) {
            case 1: v.u = std::floor(u01(rng) * 256.0), v.v = std::floor(u01(rng) * 256.0); break;
            case 2: v.u = std::floor(u01(rng) * 65536.0), v.v = std::floor(u01(rng) * 65536.0); break;
            default: v.u = u01(rng) * 600.0 - 100.0, v.v = u01(rng) * 300.0 - 50.0; break;
            }
            sc.verts.push_back(v);
        }
        if (!sc.indices.empty())
            for (u16& i : sc.indices) i = u16(rng() % u32(n));
        if (!hasZeroArea(sc)) return;
    }
    sc.verts.clear();
}

const char* const kPrimName[3] = {"list", "strip", "fan"};
const char* const kFmtName[4] = {"-", "8", "16", "f"};
const char* const kColName[8] = {"-", "-", "-", "-", "5650", "5551", "4444", "8888"};

std::string nameOf(const Scene& sc) {
    const int pk = sc.prim == GE_PRIM_TRIANGLE_STRIP ? 1 : (sc.prim == GE_PRIM_TRIANGLE_FAN ? 2 : 0);
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s pos=%s tc=%s col=%s%s%s%s%s%s%s", kPrimName[pk], kFmtName[sc.pos],
                  kFmtName[sc.tc], kColName[sc.col], sc.indices.empty() ? "" : " indexed",
                  sc.cull ? (sc.ccw ? " cull-ccw" : " cull-cw") : "", sc.flat ? " flat" : "", sc.clear ? " clear" : "",
                  sc.texture ? "" : " untextured", sc.morphCount > 1 || sc.weights ? " morph+weights" : "");
    return buf;
}

Scene makeScene(std::mt19937& rng, GePrimType prim, u32 pos, u32 tc, u32 col, int n, bool indexed) {
    Scene sc;
    sc.prim = prim;
    sc.pos = pos, sc.tc = tc, sc.col = col;
    if (indexed) sc.indices.resize(size_t(n) + 3);
    randomVerts(sc, rng, n);
    sc.name = nameOf(sc);
    return sc;
}

// ---------------------------------------------------------------------------------------------
// Tests.

TEST(GlHwThrough, KeyFromStateAndCanonicalForm) {
    Scene sc;
    sc.nrm = 2, sc.weights = 2, sc.weightCount = 3, sc.morphCount = 2;
    const GeState st = sceneState(sc);
    const sg::HwVsKey k = sg::hwVsKeyFromState(st, true, true);
    EXPECT_EQ(k.through, 1);
    // Transform-only settings cleared; layout and texturing kept.
    EXPECT_EQ(k.lighting, 0);
    EXPECT_EQ(k.lightType[0], 0);
    EXPECT_EQ(k.texMap, 0);
    EXPECT_EQ(k.projSource, 0);
    EXPECT_EQ(k.fog, 0);
    EXPECT_EQ(k.normalReverse, 0);
    EXPECT_EQ(k.clipEnable, 0);
    EXPECT_EQ(k.texture, 1);
    EXPECT_EQ(k.nrm, 2);
    EXPECT_EQ(k.weights, 2);
    EXPECT_EQ(k.weightCount, 3);
    EXPECT_EQ(k.morphCount, 2);
    EXPECT_EQ(sg::hwVsStride(k), u32(VertexLayout::fromVtype(vtypeOf(sc)).size) * 2);
    EXPECT_NE(sg::describe(k).find("through"), std::string::npos);
    // The same draw in transform mode keeps them.
    GeState tm = st;
    setReg(tm, GE_CMD_VTYPE, vtypeOf(sc) & ~(1u << 23));
    const sg::HwVsKey t = sg::hwVsKeyFromState(tm, true, true);
    EXPECT_EQ(t.through, 0);
    EXPECT_EQ(t.lighting, 1);
    EXPECT_EQ(t.fog, 1);
    EXPECT_EQ(t.clipEnable, 1);
    // texScale: 1/64, 1/32 for TSIZE0 6, 5.
    sg::HwVsUniforms u;
    sg::hwVsUniformsFromState(st, u);
    EXPECT_EQ(u.texScale[0], 1.0f / 64.0f);
    EXPECT_EQ(u.texScale[1], 1.0f / 32.0f);
    // The vertex and geometry shader sources generate.
    std::string src;
    EXPECT_TRUE(sg::generateHwVertexShader(k, sg::HostCaps{}, src));
    EXPECT_TRUE(sg::generateHwGeometryShader(k, sg::HostCaps{}, src));
    EXPECT_NE(src.find("#define GE_THROUGH 1"), std::string::npos);
}

TEST(GlHwThrough, PositionAndUvFormats) {
    REQUIRE_GL();
    // Every position format (s16, float) × UV format (none, u8, u16, float) × prim kind, 8888
    // colour, drawn directly and through indices.
    std::mt19937 rng(1234);
    int drawn = 0;
    for (u32 pos : {2u, 3u})
        for (u32 tc : {0u, 1u, 2u, 3u})
            for (GePrimType prim : {GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN})
                for (bool indexed : {false, true}) {
                    Scene sc = makeScene(rng, prim, pos, tc, 7, prim == GE_PRIM_TRIANGLES ? 12 : 9, indexed);
                    ASSERT_FALSE(sc.verts.empty()) << sc.name;
                    drawn += EXPECT_SCENE(H, sc).gpuVerts;
                }
    EXPECT_GT(drawn, 0);
}

TEST(GlHwThrough, ColourFormatsAndMaterialColour) {
    REQUIRE_GL();
    // 5650, 5551, 4444, 8888 and no colour (MAC/MAA), with float and u16 UV; flat and Gouraud.
    std::mt19937 rng(99);
    for (u32 col : {0u, 4u, 5u, 6u, 7u})
        for (bool flat : {false, true})
            for (GePrimType prim : {GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN}) {
                Scene sc = makeScene(rng, prim, col & 1 ? 2u : 3u, col & 1 ? 3u : 2u, col, 9, col == 5);
                ASSERT_FALSE(sc.verts.empty()) << sc.name;
                sc.flat = flat;
                sc.name = nameOf(sc);
                EXPECT_SCENE(H, sc);
            }
}

TEST(GlHwThrough, CullingBothWaysAndFlatShading) {
    REQUIRE_GL();
    // Culling on (CW or CCW culled) removes a share of the random triangles of either winding;
    // the survivors and their order are the CPU's. A list of a triangle and its mirror image:
    // exactly one survives.
    std::mt19937 rng(5);
    for (bool ccw : {false, true})
        for (GePrimType prim : {GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN})
            for (bool flat : {false, true}) {
                Scene sc = makeScene(rng, prim, 3, 3, 7, 31, prim == GE_PRIM_TRIANGLE_STRIP);
                ASSERT_FALSE(sc.verts.empty()) << sc.name;
                sc.cull = true, sc.ccw = ccw, sc.flat = flat;
                sc.name = nameOf(sc);
                const Result all = [&] {
                    Scene open = sc;
                    open.cull = false;
                    return runScene(H, open);
                }();
                const Result r = EXPECT_SCENE(H, sc);
                EXPECT_LT(r.gpuVerts, all.gpuVerts) << sc.name << ": culling removed nothing";
            }
    Scene pair;
    pair.name = "triangle and mirror, cull";
    pair.verts = {Vtx{10, 10, 100, 0xFF0000FF, 1, 2}, Vtx{200, 20, 200, 0xFF00FF00, 30, 4},
                  Vtx{50, 150, 300, 0xFFFF0000, 5, 60}};
    pair.verts.push_back(pair.verts[2]), pair.verts.push_back(pair.verts[1]), pair.verts.push_back(pair.verts[0]);
    pair.cull = true;
    for (bool ccw : {false, true}) {
        pair.ccw = ccw;
        EXPECT_EQ(EXPECT_SCENE(H, pair).gpuVerts, 3);
    }
}

TEST(GlHwThrough, ClearModeDrawsFlatAndUnculled) {
    REQUIRE_GL();
    // Clear mode: no culling whatever BCE says, flat colours, no texture.
    std::mt19937 rng(31);
    for (GePrimType prim : {GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP, GE_PRIM_TRIANGLE_FAN}) {
        Scene sc = makeScene(rng, prim, 2, 2, 6, 11, false);
        ASSERT_FALSE(sc.verts.empty()) << sc.name;
        sc.clear = true, sc.cull = true;
        sc.name = nameOf(sc);
        const Result r = EXPECT_SCENE(H, sc);
        const int tris = prim == GE_PRIM_TRIANGLES ? 11 / 3 : 11 - 2;
        EXPECT_EQ(r.gpuVerts, 3 * tris) << sc.name;
    }
}

TEST(GlHwThrough, MorphWeightsNormalsAndTransformStateIgnored) {
    REQUIRE_GL();
    // Weights, normals and a second morph copy in the layout (junk bytes): the stride counts
    // them, the values do not matter (no morphing or skinning in through mode).
    std::mt19937 rng(8);
    for (u32 pos : {2u, 3u})
        for (u32 tc : {1u, 2u, 3u}) {
            Scene sc = makeScene(rng, GE_PRIM_TRIANGLE_STRIP, pos, tc, pos == 2 ? 4u : 7u, 9, tc == 2);
            ASSERT_FALSE(sc.verts.empty()) << sc.name;
            sc.nrm = 3, sc.weights = tc, sc.weightCount = 3 + tc, sc.morphCount = 1 + tc;
            sc.name = nameOf(sc);
            EXPECT_SCENE(H, sc);
        }
}

TEST(GlHwThrough, S8PositionsAndFarCoordinates) {
    REQUIRE_GL();
    // s8 positions decode as 0 in through mode: every triangle has zero area (the CPU draws the
    // sample on its point, GL nothing: hw_vertex.h), so the geometry shader emits none.
    std::mt19937 rng(3);
    Scene s8 = makeScene(rng, GE_PRIM_TRIANGLES, 3, 3, 7, 9, false);
    s8.pos = 1;
    s8.name = nameOf(s8);
    EXPECT_EQ(runScene(H, s8).gpuVerts, 0);
    // Float coordinates far off the screen (limited to ±2^20 sixteenths), Z beyond 65535 and
    // negative, a texture of 512 × 1: every rule of the through transform at its limits.
    Scene far;
    far.name = "far float coordinates";
    far.tsize = 9 | 0 << 8;
    far.verts = {Vtx{-1.0e6, -20, -5, 0x80FF00FF, -3.5, 1e-3}, Vtx{300, 1.0e7, 1.0e6, 0x1234567, 511.75, -2},
                 Vtx{70000, 100, 65535.9, 0xFEDCBA98, 1e5, 0.5}, Vtx{65535.97, -65536.5, 3, 0x11223344, 7, 8},
                 Vtx{-0.03, 0.97, 12.5, 0xFFFFFFFF, -0.0, 1e-30}};
    far.prim = GE_PRIM_TRIANGLE_FAN;
    const Result r = EXPECT_SCENE(H, far);
    EXPECT_EQ(r.cpuVerts, 9);
}

TEST(GlHwThrough, CullingIsNeeded) {
    REQUIRE_GL();
    // The geometry shader without its culling line draws what the CPU culls (the comparison can
    // fail).
    std::mt19937 rng(11);
    Scene sc = makeScene(rng, GE_PRIM_TRIANGLES, 2, 2, 7, 30, false);
    sc.cull = true;
    const GsEdit noCull{"if (culled(v[0].scr, v[1].scr, v[2].scr)) return;", ""};
    EXPECT_TRUE(runScene(H, sc).exact());
    EXPECT_FALSE(runScene(H, sc, &noCull).exact());
}

}  // namespace
}  // namespace ge::gltest
