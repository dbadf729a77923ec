// SPDX-License-Identifier: MIT
// The GL hardware mode's generated vertex shader (shadergen/hw_vertex.*) against the CPU code every
// backend runs: hle/vertex_decoder (formats, morphing, skinning) + geo::makeTransformState /
// geo::transformVertex (matrices, viewport, 1/16-pixel snap, depth, fog, texture mapping, lighting)
// and the docs/ge-rules.md §8.5 discard rules (geometry/clip.cpp), through transform feedback on the headless
// context: every output of every vertex must be the CPU's, bit for bit. The outputs are what the
// geometry shader reads, the CPU's ClipVertex: clip coordinates, colours, s/t/q/fog, x16/y16/z and
// the discard flags. The geometry shader (the fragment shader's inputs, clipping, culling) and
// what the rasteriser draws are tests/gl_hw_clip.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
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
#include "translator/gl_context.h"
#include "translator/gl_renderer.h"

namespace ge::gltest {
namespace {

namespace sg = shadergen;

// ---------------------------------------------------------------------------------------------
// GL harness: one OSMesa context for the whole suite.

// Captured per vertex (interleaved): 19 words.
struct Captured {
    float clip[4];
    s32 color[4], color2[3];
    float stqf[4];
    s32 scr[4];  // x16, y16, z, flags (1 outside, 2 near side, 4 far side, 8 no position)
};
static_assert(sizeof(Captured) == 19 * 4);
const char* const kVaryings[] = {"g_clip", "g_color", "g_color2", "g_stqf", "g_scr"};

struct Harness {
    std::unique_ptr<gl::GlContext> ctx;
    GLuint vao = 0, vtxBuf = 0, vtxTex = 0, tfb = 0;
    std::string error;

    bool init() {
        ctx = gl::GlContext::create(gl::ContextKind::OSMesa, error);
        if (!ctx) return false;
        const gl::GlFuncs& f = ctx->f();
        if (!f.TransformFeedbackVaryings || !f.BeginTransformFeedback || !f.BindBufferBase || !f.GetBufferSubData ||
            !f.Uniform4uiv) {
            error = "transform feedback entry points missing";
            return false;
        }
        f.GenVertexArrays(1, &vao);
        f.BindVertexArray(vao);
        f.GenBuffers(1, &vtxBuf);
        f.GenTextures(1, &vtxTex);
        f.GenBuffers(1, &tfb);
        return true;
    }

    GLuint compile(GLenum type, const std::string& src, std::string& log) const {
        const gl::GlFuncs& f = ctx->f();
        GLuint s = f.CreateShader(type);
        const char* p = src.c_str();
        f.ShaderSource(s, 1, &p, nullptr);
        f.CompileShader(s);
        GLint ok = 0;
        f.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char buf[8192] = {};
            f.GetShaderInfoLog(s, sizeof buf, nullptr, buf);
            log = buf;
            f.DeleteShader(s);
            return 0;
        }
        return s;
    }

    // Vertex shader of `key` (with `defines` after the #version line), plus `fs` when non-empty;
    // transform feedback of kVaryings when `capture`.
    GLuint program(const sg::HwVsKey& key, const std::string& defines, const std::string& fs, bool capture,
                   std::string& log) const {
        const gl::GlFuncs& f = ctx->f();
        std::string src;
        sg::HostCaps caps;
        if (!sg::generateHwVertexShader(key, caps, src, &log)) return 0;
        src.insert(src.find('\n') + 1, defines);
        GLuint vs = compile(GL_VERTEX_SHADER, src, log);
        if (!vs) {
            log += "\n" + src;
            return 0;
        }
        GLuint prog = f.CreateProgram();
        f.AttachShader(prog, vs);
        GLuint fsh = 0;
        if (!fs.empty()) {
            fsh = compile(GL_FRAGMENT_SHADER, fs, log);
            if (!fsh) return 0;
            f.AttachShader(prog, fsh);
        }
        if (capture)
            f.TransformFeedbackVaryings(prog, GLsizei(std::size(kVaryings)), kVaryings, GL_INTERLEAVED_ATTRIBS);
        f.LinkProgram(prog);
        f.DeleteShader(vs);
        if (fsh) f.DeleteShader(fsh);
        GLint ok = 0;
        f.GetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            char buf[8192] = {};
            f.GetProgramInfoLog(prog, sizeof buf, nullptr, buf);
            log = buf;
            f.DeleteProgram(prog);
            return 0;
        }
        return prog;
    }

    // Binds the vertex bytes and the uniforms for `prog`.
    void bindInputs(GLuint prog, const std::vector<u8>& bytes, const sg::HwVsUniforms& u) const {
        const gl::GlFuncs& f = ctx->f();
        f.UseProgram(prog);
        f.BindBuffer(GL_TEXTURE_BUFFER, vtxBuf);
        f.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(bytes.size() + 64), nullptr, GL_STATIC_DRAW);
        f.BufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(bytes.size()), bytes.data());
        f.ActiveTexture(GL_TEXTURE0 + sg::kUnitVertexBytes);
        f.BindTexture(GL_TEXTURE_BUFFER, vtxTex);
        f.TexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, vtxBuf);
        f.ActiveTexture(GL_TEXTURE0);
        f.Uniform1i(f.GetUniformLocation(prog, sg::hwuniform::kVertexBytes), sg::kUnitVertexBytes);
        f.Uniform4uiv(f.GetUniformLocation(prog, sg::hwuniform::kBlock), sg::kHwVsUniformVec4,
                      reinterpret_cast<const GLuint*>(&u));
    }

    // Runs `count` vertices through the program's vertex shader and returns what it wrote:
    // glDrawArrays from `first`, or glDrawElements with `indices` (u16).
    std::vector<Captured> capture(int count, int first = 0, const std::vector<u16>* indices = nullptr) const {
        const gl::GlFuncs& f = ctx->f();
        std::vector<Captured> out(static_cast<size_t>(count));
        GLuint ebo = 0;
        if (indices) {
            f.GenBuffers(1, &ebo);
            f.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
            f.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices->size() * 2), indices->data(), GL_STATIC_DRAW);
        }
        f.BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
        f.BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, GLsizeiptr(out.size() * sizeof(Captured)), nullptr, GL_STATIC_READ);
        f.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
        f.Enable(GL_RASTERIZER_DISCARD);
        f.BeginTransformFeedback(GL_POINTS);
        if (indices) f.DrawElements(GL_POINTS, count, GL_UNSIGNED_SHORT, nullptr);
        else f.DrawArrays(GL_POINTS, first, count);
        f.EndTransformFeedback();
        if (ebo) {
            f.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
            f.DeleteBuffers(1, &ebo);
        }
        f.Disable(GL_RASTERIZER_DISCARD);
        f.GetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(out.size() * sizeof(Captured)), out.data());
        return out;
    }
};

// One GL context for the whole test binary, destroyed at static destruction (before
// LeakSanitizer's exit check: its tracer crashed stopping llvmpipe's threads of a context left
// alive).
Harness* harness() {
    static std::unique_ptr<Harness> h = [] {
        // Under the sanitizers, no Mesa shader disk cache: its writer thread still running at exit
        // crashed LeakSanitizer's exit-time tracer after these shader-heavy tests in a fresh CI
        // clone. (Only here: the program-binary tests need the cache.)
        if (std::getenv("GE2GL_SANITIZER_RUN")) setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
        auto x = std::make_unique<Harness>();
        if (!x->init()) {
            std::fprintf(stderr, "GlHwVertex: %s\n", x->error.c_str());
            x->ctx.reset();
        }
        return x;
    }();
    return h->ctx ? h.get() : nullptr;
}

#define REQUIRE_GL()                                            \
    Harness* H = harness();                                     \
    if (!H) GTEST_SKIP() << "no GL context with transform feedback"; \
    H->ctx->makeCurrent()

// ---------------------------------------------------------------------------------------------
// Random GE states and vertices.

float f24(float f) { return float24(toFloat24(f)); }  // a value a display list can hold

// VTYPE from its fields (ge-rules.md §5.1): formats, weight count 1–8, morph count 1–8.
u32 vt_from(u32 tc, u32 col, u32 nrm, u32 pos, u32 wt = 0, u32 wc = 1, u32 mc = 1) {
    return tc | col << 2 | nrm << 5 | pos << 7 | wt << 9 | (wc - 1) << 14 | (mc - 1) << 18;
}

struct Rng {
    std::mt19937 g;
    explicit Rng(u32 seed) : g(seed) {}
    float uni(float a, float b) { return std::uniform_real_distribution<float>(a, b)(g); }
    int irange(int a, int b) { return std::uniform_int_distribution<int>(a, b)(g); }
    bool coin(double p = 0.5) { return std::bernoulli_distribution(p)(g); }
    u32 bits() { return g(); }
};

struct Rig {
    GeState st;
    void set(u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }
    void setf(u8 cmd, float f) { set(cmd, toFloat24(f)); }
    void setColor(u8 cmd, u32 rgb) { set(cmd, rgb & 0xFFFFFF); }
};

// How far the scene sits in front of the camera and how big it is (clip/discard coverage).
struct SceneShape {
    float depth = 10.0f;     // view-space distance of the model origin
    float scale = 1.0f;      // world scale of the model
    float depthJitter = 0;   // random extra distance per draw (negative: behind the near plane)
};

// A typical sceGu setup: perspective projection, viewport 480×272 centred at 2048, depth range
// 65535..0, with random world/view matrices and every lighting/texture/fog value random.
void randomState(Rng& r, Rig& rig, u32 vtype, const SceneShape& shape) {
    GeState& st = rig.st;
    st.reset();
    rig.set(GE_CMD_VTYPE, vtype);
    // World: random rotation-ish matrix with scale, random translation.
    const float ax = r.uni(0, 6.28f), ay = r.uni(0, 6.28f);
    const float ca = std::cos(ax), sa = std::sin(ax), cb = std::cos(ay), sb = std::sin(ay);
    const float rot[9] = {cb, sa * sb, -ca * sb, 0, ca, sa, sb, -sa * cb, ca * cb};
    for (int i = 0; i < 9; ++i) st.world[i] = f24(rot[i] * shape.scale * r.uni(0.8f, 1.2f));
    for (int i = 9; i < 12; ++i) st.world[i] = f24(r.uni(-0.5f, 0.5f));
    // View: near-identity rotation, the model `depth` in front of the camera (−Z forward).
    for (int i = 0; i < 12; ++i) st.view[i] = 0;
    st.view[0] = st.view[4] = st.view[8] = 1;
    st.view[1] = f24(r.uni(-0.1f, 0.1f));
    st.view[3] = f24(r.uni(-0.1f, 0.1f));
    st.view[9] = f24(r.uni(-0.3f, 0.3f));
    st.view[10] = f24(r.uni(-0.3f, 0.3f));
    st.view[11] = f24(-(shape.depth + r.uni(0, 1) * shape.depthJitter));
    // Projection (sceGumPerspective 60°, 480/272, near 0.5, far 1000).
    const float fov = 1.0f / std::tan(0.5f * 1.0471976f), aspect = 480.0f / 272.0f, zn = 0.5f, zf = 1000.0f;
    for (int i = 0; i < 16; ++i) st.proj[i] = 0;
    st.proj[0] = f24(fov / aspect);
    st.proj[5] = f24(fov);
    st.proj[10] = f24((zf + zn) / (zn - zf));
    st.proj[11] = -1;
    st.proj[14] = f24(2 * zf * zn / (zn - zf));
    for (int i = 0; i < 12; ++i) st.tgen[i] = f24(r.uni(-1.5f, 1.5f));
    if (r.coin(0.3)) st.tgen[2] = st.tgen[5] = st.tgen[8] = 0, st.tgen[11] = 1;  // affine projection
    for (int b = 0; b < 8; ++b) {
        for (int i = 0; i < 12; ++i) st.bone[12 * b + i] = f24(r.uni(-0.3f, 0.3f));
        st.bone[12 * b + 0] += 1, st.bone[12 * b + 4] += 1, st.bone[12 * b + 8] += 1;
    }
    for (int i = 0; i < 8; ++i) rig.setf(u8(GE_CMD_WEIGHT0 + i), r.uni(-0.2f, 0.7f));
    rig.setf(GE_CMD_SX, 240), rig.setf(GE_CMD_SY, -136), rig.setf(GE_CMD_SZ, -32767.5f);
    rig.setf(GE_CMD_TX, 2048), rig.setf(GE_CMD_TY, 2048), rig.setf(GE_CMD_TZ, 32767.5f);
    rig.set(GE_CMD_OFFSETX, (2048 - 240) * 16 + r.irange(0, 15));
    rig.set(GE_CMD_OFFSETY, (2048 - 136) * 16 + r.irange(0, 15));
    rig.setf(GE_CMD_SU, r.uni(-2, 2)), rig.setf(GE_CMD_SV, r.uni(-2, 2));
    rig.setf(GE_CMD_TU, r.uni(-1, 1)), rig.setf(GE_CMD_TV, r.uni(-1, 1));
    rig.set(GE_CMD_TSIZE0, 6 | 5 << 8);
    rig.setf(GE_CMD_FOG1, r.uni(5, 20));
    rig.setf(GE_CMD_FOG2, r.uni(0.02f, 0.5f));
    rig.set(GE_CMD_SHADE, 1);
    // Lights and material.
    for (int n = 0; n < 4; ++n) {
        rig.setf(u8(GE_CMD_LX0 + 3 * n), r.uni(-8, 8));
        rig.setf(u8(GE_CMD_LY0 + 3 * n), r.uni(-8, 8));
        rig.setf(u8(GE_CMD_LZ0 + 3 * n), r.uni(-8, 8) - shape.depth * 0.5f);
        rig.setf(u8(GE_CMD_LDX0 + 3 * n), r.uni(-1, 1));
        rig.setf(u8(GE_CMD_LDY0 + 3 * n), r.uni(-1, 1));
        rig.setf(u8(GE_CMD_LDZ0 + 3 * n), r.uni(-1, 1));
        rig.setf(u8(GE_CMD_LKA0 + 3 * n), r.uni(0.3f, 1.5f));
        rig.setf(u8(GE_CMD_LKB0 + 3 * n), r.uni(0, 0.3f));
        rig.setf(u8(GE_CMD_LKC0 + 3 * n), r.uni(0, 0.05f));
        rig.setf(u8(GE_CMD_LKS0 + n), r.coin(0.2) ? 0.0f : r.uni(0.5f, 30));
        rig.setf(u8(GE_CMD_LKO0 + n), r.uni(-0.5f, 0.9f));
        rig.setColor(u8(GE_CMD_LAC0 + 3 * n), r.bits());
        rig.setColor(u8(GE_CMD_LDC0 + 3 * n), r.bits());
        rig.setColor(u8(GE_CMD_LSC0 + 3 * n), r.bits());
    }
    rig.setColor(GE_CMD_MEC, r.bits() & 0x3F3F3F);
    rig.setColor(GE_CMD_MAC, r.bits());
    rig.set(GE_CMD_MAA, r.bits() & 0xFF);
    rig.setColor(GE_CMD_MDC, r.bits());
    rig.setColor(GE_CMD_MSC, r.bits());
    rig.setColor(GE_CMD_AC, r.bits() & 0x7F7F7F);
    rig.set(GE_CMD_AA, r.bits() & 0xFF);
    rig.setf(GE_CMD_MK, r.coin(0.15) ? 0.0f : r.uni(0.5f, 60));
    rig.set(GE_CMD_TSHADE, r.irange(0, 3) | r.irange(0, 3) << 8);
}

// `count` vertices of `vtype` with random bytes, float components in sane ranges.
std::vector<u8> randomVertices(Rng& r, u32 vtype, int count, float posRange = 1.2f) {
    const VertexLayout l = VertexLayout::fromVtype(vtype);
    const int copies = int((vtype >> 18) & 7) + 1;
    const u32 tc = vtype & 3, nrm = (vtype >> 5) & 3, pos = (vtype >> 7) & 3, wt = (vtype >> 9) & 3;
    const u32 wc = ((vtype >> 14) & 7) + 1;
    std::vector<u8> bytes(size_t(l.size) * copies * count);
    for (u8& b : bytes) b = u8(r.bits());
    auto putF = [&](u8* p, float v) {
        u32 bits;
        std::memcpy(&bits, &v, 4);
        writeLE32(p, bits);
    };
    for (size_t v = 0; v < size_t(copies) * count; ++v) {
        u8* p = bytes.data() + v * l.size;
        if (wt == 3)
            for (u32 i = 0; i < wc; ++i) putF(p + l.weightOff + 4 * i, r.coin(0.1) ? 0.0f : r.uni(-0.2f, 1.0f));
        if (tc == 3) putF(p + l.tcOff, r.uni(-2, 2)), putF(p + l.tcOff + 4, r.uni(-2, 2));
        if (nrm == 3)
            for (int i = 0; i < 3; ++i) putF(p + l.nrmOff + 4 * i, r.coin(0.02) ? 0.0f : r.uni(-1, 1));
        if (pos == 3)
            for (int i = 0; i < 3; ++i) putF(p + l.posOff + 4 * i, r.uni(-posRange, posRange));
    }
    return bytes;
}

// ---------------------------------------------------------------------------------------------
// Comparison with the CPU.

struct Expected {
    bool drop = false;        // the geometry shader drops every primitive using the vertex
    bool beyondNear = false;  // the geometry shader clips the primitives using it
    bool valid = true;
    // The ClipVertex as the vertex shader hands it on.
    float clip[4] = {}, color[4] = {}, color2[3] = {}, stq[3] = {}, fog = 1;
    s32 scr[4] = {};  // x16, y16, z, flags
};

Expected cpuVertex(const GeState& st, const Memory& mem, u32 base, u32 index, u32 vtype, const sg::HwVsKey& key) {
    Expected e;
    VertexReader reader(mem, st, vtype);
    DecodedVertex dv;
    const bool ok = reader.read(base, index, dv);
    if (ok) applySkinning(st, vtype, dv);
    const geo::TransformState ts = geo::makeTransformState(st, vtype, reader.hasColor(), reader.hasNormal());
    geo::ClipVertex cv;
    geo::transformVertex(ts, dv, cv);
    cv.valid = ok && reader.hasPosition();
    const int side = geo::depthSide(cv);
    e.drop = !cv.valid || cv.outside || (!ts.clipEnable && side != 0);
    e.beyondNear = geo::beyondNear(cv);
    const geo::ScreenVertex& v = cv.sv;
    for (int i = 0; i < 4; ++i) e.color[i] = float(v.color[i]);
    for (int i = 0; i < 3; ++i) e.color2[i] = float(v.secondary[i]);
    e.fog = key.fog ? v.fog : 1.0f;
    e.valid = cv.valid;
    for (int i = 0; i < 4; ++i) e.clip[i] = cv.clip[i];
    e.stq[0] = v.s, e.stq[1] = v.t, e.stq[2] = v.q;
    e.scr[0] = v.x, e.scr[1] = v.y, e.scr[2] = v.z;
    e.scr[3] = (cv.outside ? 1 : 0) | (side < 0 ? 2 : 0) | (side > 0 ? 4 : 0) | (cv.valid ? 0 : 8);
    return e;
}

bool same(float a, float b) {
    if (std::isnan(a) && std::isnan(b)) return true;
    return a == b;  // +0 == −0: the sign of a zero is not observable downstream
}
// Distance in representable floats (for the report).
double ulps(float a, float b) {
    if (same(a, b)) return 0;
    if (!std::isfinite(a) || !std::isfinite(b)) return 1e30;
    auto key = [](float f) {
        s32 i;
        std::memcpy(&i, &f, 4);
        return i < 0 ? s64(0x80000000LL) - s64(i) : s64(i);
    };
    return double(std::llabs(key(a) - key(b)));
}

// Report fields: the discard flags, x16/y16, colour, secondary, z, fog, s/t/q, clip coordinates.
enum Field { kFlags, kPos, kColor, kColor2, kZ, kFog, kTex, kClip, kFields };

struct Report {
    int vertices = 0, drawn = 0, dropped = 0, beyondNear = 0;
    int bad[kFields] = {};
    double maxUlp[kFields] = {};
    std::string first;
    int total() const {
        int t = 0;
        for (int b : bad) t += b;
        return t;
    }
    std::string summary() const {
        static const char* const names[kFields] = {"flags", "pos", "color", "color2", "z", "fog", "tex", "clip"};
        char buf[512];
        std::snprintf(buf, sizeof buf, "%d vertices (%d drawn, %d dropped, %d beyond near)", vertices, drawn, dropped,
                      beyondNear);
        std::string s = buf;
        for (int i = 0; i < kFields; ++i)
            if (bad[i]) {
                std::snprintf(buf, sizeof buf, "; %s: %d mismatches, max %.3g ulp", names[i], bad[i], maxUlp[i]);
                s += buf;
            }
        if (!first.empty()) s += "\nfirst: " + first;
        return s;
    }
};

struct Case {
    Rig rig;
    u32 vtype = 0;
    bool texture = false, fog = false;
    std::vector<u8> bytes;
    int count = 0;
    int first = 0;             // glDrawArrays(first, count)
    std::vector<u16> indices;  // or glDrawElements with these
    std::string defines;  // injected after #version (e.g. "#define GE_NO_FP64\n")
    std::function<void(sg::HwVsUniforms&)> perturbGl;  // changes what GL gets (self-test)
};

// Compares every output of one vertex with the CPU's (the flags of every vertex, the values of
// every vertex with a position, dropped ones too: the flags tell the geometry shader which rule a
// vertex breaks).
void compareVertex(Report& rep, const Captured& q, const Expected& e, bool texture, u32 index, const sg::HwVsKey& key) {
    auto note = [&](int field, const char* name, int k, double gv, double ev, double ulp) {
        if (rep.bad[field]++ == 0 && rep.first.empty()) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "%s[%d] %.9g, CPU %.9g", name, k, gv, ev);
            rep.first = "vertex " + std::to_string(index) + " " + buf + " (" + sg::describe(key) + ")";
        }
        if (ulp > rep.maxUlp[field]) rep.maxUlp[field] = ulp;
    };
    // First differing component of an output; integers report the absolute difference.
    auto ints = [&](int field, const char* name, const s32* gv, const s32* ev, int count) {
        for (int k = 0; k < count; ++k)
            if (gv[k] != ev[k]) return note(field, name, k, gv[k], ev[k], std::abs(gv[k] - ev[k]));
    };
    auto floats = [&](int field, const char* name, const float* gv, const float* ev, int count) {
        for (int k = 0; k < count; ++k)
            if (!same(gv[k], ev[k])) return note(field, name, k, gv[k], ev[k], ulps(gv[k], ev[k]));
    };
    if ((q.scr[3] & 8) != (e.scr[3] & 8) || (e.valid && q.scr[3] != e.scr[3])) {
        note(kFlags, "flags", 3, q.scr[3], e.scr[3], 0);
        return;
    }
    if (!e.valid) return;
    ints(kPos, "scr", q.scr, e.scr, 2);
    ints(kZ, "z", &q.scr[2], &e.scr[2], 1);
    float color[4], color2[3];
    for (int k = 0; k < 4; ++k) color[k] = float(q.color[k]);
    for (int k = 0; k < 3; ++k) color2[k] = float(q.color2[k]);
    floats(kColor, "color", color, e.color, 4);
    floats(kColor2, "color2", color2, e.color2, 3);
    if (texture) floats(kTex, "stq", q.stqf, e.stq, 3);
    floats(kFog, "fog", &q.stqf[3], &e.fog, 1);
    floats(kClip, "clip", q.clip, e.clip, 4);
}

// Runs the case on GL and on the CPU and compares every output of every vertex.
Report runCase(Harness* H, const Case& c) {
    Report rep;
    const sg::HwVsKey key = sg::hwVsKeyFromState(c.rig.st, c.texture, c.fog);
    sg::HwVsUniforms u;
    sg::hwVsUniformsFromState(c.rig.st, u);
    if (c.perturbGl) c.perturbGl(u);
    EXPECT_EQ(sg::hwVsStride(key), c.rig.st.vertexStride());
    std::string log;
    const GLuint prog = H->program(key, c.defines, "", true, log);
    if (!prog) {
        ADD_FAILURE() << "program for " << sg::describe(key) << ": " << log;
        return rep;
    }
    H->bindInputs(prog, c.bytes, u);
    const bool indexed = !c.indices.empty();
    const int n = indexed ? int(c.indices.size()) : c.count;
    const std::vector<Captured> got = H->capture(n, c.first, indexed ? &c.indices : nullptr);
    H->ctx->f().DeleteProgram(prog);

    Memory mem;
    const u32 base = 0x08800000;
    std::memcpy(mem.ptr(base, u32(c.bytes.size())), c.bytes.data(), c.bytes.size());
    rep.vertices = n;
    for (int i = 0; i < n; ++i) {
        const u32 index = indexed ? c.indices[size_t(i)] : u32(c.first + i);
        const Expected e = cpuVertex(c.rig.st, mem, base, index, c.vtype, key);
        compareVertex(rep, got[size_t(i)], e, c.texture, index, key);
        if (e.drop) {
            ++rep.dropped;
            continue;
        }
        ++rep.drawn;
        if (e.beyondNear) ++rep.beyondNear;
    }
    return rep;
}

// Builds a random case for vtype with the given switches.
Case makeCase(u32 seed, u32 vtype, int count, const std::function<void(Rng&, Rig&)>& tweak = {},
              const SceneShape& shape = {}) {
    Rng r(seed);
    Case c;
    c.vtype = vtype;
    randomState(r, c.rig, vtype, shape);
    if (tweak) tweak(r, c.rig);
    c.bytes = randomVertices(r, vtype, count);
    c.count = count;
    return c;
}

bool verbose() { return std::getenv("GE2GL_HW_VERBOSE") != nullptr; }

#define EXPECT_EXACT(H, c)                                          \
    do {                                                            \
        const Report rep_ = runCase(H, c);                          \
        if (verbose()) std::printf("%s\n", rep_.summary().c_str()); \
        EXPECT_EQ(rep_.total(), 0) << rep_.summary();               \
        EXPECT_GT(rep_.drawn, 0) << rep_.summary();                 \
    } while (0)

// ---------------------------------------------------------------------------------------------
// Tests.

// The triangle list a PRIM is drawn as: strip triangle i in the CPU's winding (i, i + 1, i + 2),
// odd ones (i + 1, i, i + 2); fan triangle i as (0, i + 1, i + 2); ring ids i mod 6; a list's
// incomplete last triangle and strips or fans under 3 vertices dropped; `base` added.
TEST(GlHwVertex, PrimsBecomeTriangleListsWithRingIds) {
    const u32 seq[8] = {10, 11, 12, 13, 14, 15, 16, 17};
    std::vector<u32> idx;
    std::vector<u8> ring;
    sg::hwTriangleList(1, seq, 8, 0, idx, ring);
    EXPECT_EQ(idx, (std::vector<u32>{10, 11, 12, 12, 11, 13, 12, 13, 14, 14, 13, 15, 14, 15, 16, 16, 15, 17}));
    EXPECT_EQ(ring, (std::vector<u8>{0, 1, 2, 3, 4, 5}));
    idx.clear(), ring.clear();
    sg::hwTriangleList(2, seq, 5, 100, idx, ring);
    EXPECT_EQ(idx, (std::vector<u32>{110, 111, 112, 110, 112, 113, 110, 113, 114}));
    EXPECT_EQ(ring, (std::vector<u8>{0, 1, 2}));
    idx.clear(), ring.clear();
    sg::hwTriangleList(0, seq, 8, 0, idx, ring);
    EXPECT_EQ(idx, (std::vector<u32>{10, 11, 12, 13, 14, 15}));
    EXPECT_TRUE(ring.empty());
    idx.clear();
    sg::hwTriangleList(1, seq, 2, 0, idx, ring);
    sg::hwTriangleList(2, seq, 2, 0, idx, ring);
    EXPECT_TRUE(idx.empty() && ring.empty());
    std::vector<u32> longStrip(20, 0);
    sg::hwTriangleList(1, longStrip.data(), 20, 0, idx, ring);
    ASSERT_EQ(ring.size(), 18u);
    EXPECT_EQ(ring[6], 0u);
    EXPECT_EQ(ring[17], 5u);
}

TEST(GlHwVertex, KeysAreCanonicalAndDescribed) {
    Rig a;
    a.st.reset();
    a.set(GE_CMD_VTYPE, vt_from(3, 7, 0, 3));
    sg::HwVsKey k1 = sg::hwVsKeyFromState(a.st, false, false);
    a.set(GE_CMD_TMAP, 1 | 2 << 8);  // texture mapping without texturing: no change
    a.set(GE_CMD_NREV, 1);            // no normal: no change
    a.set(GE_CMD_LMODE, 1);           // no lighting: no change
    a.set(GE_CMD_MATERIAL, 7);
    sg::HwVsKey k2 = sg::hwVsKeyFromState(a.st, false, false);
    EXPECT_TRUE(sg::keyEqual(k1, k2)) << sg::describe(k1) << " / " << sg::describe(k2);
    // Colour formats 1–3 carry no bytes and no colour: the same as none.
    sg::HwVsKey c1, c2;
    c1.pos = c2.pos = 3;
    c1.col = 2;
    sg::canonicalize(c1);
    sg::canonicalize(c2);
    EXPECT_TRUE(sg::keyEqual(c1, c2));
    // Lighting: disabled lights and comp 3 canonicalised; LMODE only with a specular light.
    sg::HwVsKey l1;
    l1.pos = 3, l1.lighting = 1, l1.lightType[1] = 2, l1.lightComp[1] = 3, l1.separateSpecular = 1;
    l1.lightComp[2] = 1;  // light 2 off
    sg::canonicalize(l1);
    EXPECT_EQ(l1.lightComp[1], 0);
    EXPECT_EQ(l1.lightComp[2], 0);
    EXPECT_EQ(l1.separateSpecular, 0);
    EXPECT_NE(sg::describe(l1).find("point:ad"), std::string::npos) << sg::describe(l1);
    // Stride: layout of every format times the morph count.
    for (u32 vtype : {0x00011Du, 0x008300u, 0x000080u, 0x0001FFu, 0x00C700u, 0x08011Du}) {
        a.set(GE_CMD_VTYPE, vtype);
        EXPECT_EQ(sg::hwVsStride(sg::hwVsKeyFromState(a.st, true, true)), a.st.vertexStride()) << std::hex << vtype;
    }
}

// Lighting / texture / fog switches of a case.
struct Switches {
    bool lighting = false, texture = false, fog = false, cle = true, nrev = false, flat = false;
    int lightType[4] = {-1, -1, -1, -1};  // −1 off, else LTYPE type 0–3
    int lightComp[4] = {0, 0, 0, 0};
    u32 material = 0;  // MATERIAL bits (ambient 1, diffuse 2, specular 4)
    bool separate = false;
    int texMap = 0, projSource = 0;
};
void applySwitches(Case& c, const Switches& sw) {
    Rig& rig = c.rig;
    rig.set(GE_CMD_LTE, sw.lighting);
    for (int n = 0; n < 4; ++n) {
        rig.set(u8(GE_CMD_LE0 + n), sw.lightType[n] >= 0);
        rig.set(u8(GE_CMD_LTYPE0 + n), u32(sw.lightComp[n]) | u32(sw.lightType[n] < 0 ? 0 : sw.lightType[n]) << 8);
    }
    rig.set(GE_CMD_MATERIAL, sw.material);
    rig.set(GE_CMD_LMODE, sw.separate);
    rig.set(GE_CMD_TMAP, u32(sw.texMap) | u32(sw.projSource) << 8);
    rig.set(GE_CMD_FGE, sw.fog);
    rig.set(GE_CMD_CLE, sw.cle);
    rig.set(GE_CMD_NREV, sw.nrev);
    rig.set(GE_CMD_SHADE, !sw.flat);
    c.texture = sw.texture;
    c.fog = sw.fog;
}
Switches randomSwitches(Rng& r) {
    Switches sw;
    sw.lighting = r.coin(0.6);
    for (int n = 0; n < 4; ++n) {
        sw.lightType[n] = r.coin(0.6) ? r.irange(0, 3) : -1;
        sw.lightComp[n] = r.irange(0, 3);
    }
    sw.material = u32(r.irange(0, 7));
    sw.separate = r.coin();
    sw.texture = r.coin(0.8);
    sw.texMap = r.irange(0, 3);
    sw.projSource = r.irange(0, 3);
    sw.fog = r.coin(0.6);
    sw.cle = r.coin(0.7);
    sw.nrev = r.coin(0.3);
    sw.flat = r.coin(0.2);
    return sw;
}

Case switchedCase(u32 seed, u32 vtype, int count, const Switches& sw, const SceneShape& shape = {}) {
    Case c = makeCase(seed, vtype, count, {}, shape);
    applySwitches(c, sw);
    return c;
}

const u32 kColors[5] = {0, 4, 5, 6, 7};
const char* const kSimpleFs = "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n";

TEST(GlHwVertex, GeneratesAndCompilesForAKeySweep) {
    REQUIRE_GL();
    Rng r(7);
    int compiled = 0;
    for (int i = 0; i < 60; ++i) {
        sg::HwVsKey k;
        k.tc = u8(i % 4);
        k.col = u8(kColors[i % 5]);
        k.nrm = u8((i / 4) % 4);
        k.pos = u8(i % 7 == 6 ? 0 : 1 + i % 3);
        k.weights = u8((i / 3) % 4);
        k.weightCount = u8(1 + (i % 8));
        k.morphCount = u8(1 + ((i * 5) % 8));
        k.lighting = u8(r.coin(0.7));
        for (int n = 0; n < 4; ++n) k.lightType[n] = u8(r.irange(0, 3)), k.lightComp[n] = u8(r.irange(0, 3));
        k.ambientFromVertex = u8(r.coin()), k.diffuseFromVertex = u8(r.coin()), k.specularFromVertex = u8(r.coin());
        k.separateSpecular = u8(r.coin());
        k.texture = u8(r.coin(0.8));
        k.texMap = u8(i % 4);
        k.projSource = u8((i / 4) % 4);
        k.fog = u8(r.coin()), k.normalReverse = u8(r.coin()), k.clipEnable = u8(r.coin()), k.flatShade = u8(r.coin());
        k.primKind = u8(i % 3);
        sg::canonicalize(k);
        // The fallback for drivers without doubles compiles too. The outputs go nowhere here
        // (gl_hw_clip.cpp links the geometry shader).
        const char* defines = i % 10 == 3 || i % 10 == 7 ? "#define GE_NO_FP64\n" : "";
        std::string log;
        const GLuint prog = H->program(k, defines, kSimpleFs, false, log);
        EXPECT_NE(prog, 0u) << sg::describe(k) << "\n" << log;
        if (prog) {
            ++compiled;
            H->ctx->f().DeleteProgram(prog);
        }
    }
    EXPECT_EQ(compiled, 60);
}

TEST(GlHwVertex, EveryVertexFormatMatchesTheCpu) {
    REQUIRE_GL();
    // Each texture-coordinate, colour, normal and position format, in 20 combinations; colours
    // are checked unlit (passed through) in half of them and through material-from-vertex
    // lighting in the other half.
    for (int i = 0; i < 20; ++i) {
        const u32 vtype = vt_from(u32(i % 4), kColors[i % 5], u32((i / 5) % 4), u32(1 + i % 3));
        Switches sw;
        sw.texture = true;
        sw.fog = true;
        sw.lighting = i % 2 == 1;
        sw.lightType[0] = 1, sw.lightComp[0] = 1;
        sw.lightType[1] = 0, sw.lightComp[1] = 0;
        sw.material = 7;
        sw.texMap = i % 4 == 3 ? 1 : 0;
        sw.projSource = 2;
        const Case c = switchedCase(100 + u32(i), vtype, 600, sw);
        SCOPED_TRACE(testing::Message() << "vtype 0x" << std::hex << vtype);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, ComparisonDetectsSmallChanges) {
    REQUIRE_GL();
    // The harness must see small changes of what GL gets: otherwise "0 mismatches" would prove
    // nothing. A matrix element 1 + 2^-12 larger, the viewport centre moved by half a subpixel,
    // a light colour factor + 2, one ulp of the view matrix (fog) and of SU (texture).
    Switches sw;
    sw.lighting = true, sw.texture = true, sw.fog = true;
    sw.lightType[0] = 0, sw.lightComp[0] = 1;
    const u32 vtype = vt_from(3, 7, 3, 3);
    Case c = switchedCase(5, vtype, 400, sw);
    struct Probe {
        std::function<void(sg::HwVsUniforms&)> change;
        int field;
    };
    const Probe probes[] = {
        {[](sg::HwVsUniforms& u) { u.worldViewProj[0] *= 1.0f + 1.0f / 4096.0f; }, kClip},
        {[](sg::HwVsUniforms& u) { u.viewport[3] += 1.0f / 32.0f; }, kPos},
        {[](sg::HwVsUniforms& u) { u.lightDiffuse[0] += 2; }, kColor},
        {[](sg::HwVsUniforms& u) { u.view[11] = std::nextafter(u.view[11], 1e9f); }, kFog},
        {[](sg::HwVsUniforms& u) { u.uvScale[0] = std::nextafter(u.uvScale[0], 1e9f); }, kTex},
    };
    for (const Probe& p : probes) {
        c.perturbGl = p.change;
        const Report rep = runCase(H, c);
        EXPECT_GT(rep.bad[p.field], 0) << rep.summary();
    }
}

TEST(GlHwVertex, MorphingWith2To8Weights) {
    REQUIRE_GL();
    for (u32 mc = 2; mc <= 8; ++mc) {
        const u32 wt = mc % 2 ? 0 : 1 + mc % 3;
        const u32 vtype = vt_from(1 + mc % 3, kColors[1 + mc % 4], 1 + mc % 3, 1 + (mc + 1) % 3, wt, wt ? mc : 1, mc);
        Switches sw;
        sw.texture = true, sw.fog = true;
        sw.texMap = mc % 3 == 0 ? 1 : 0;
        sw.projSource = 3;
        // Unlit: the morphed colour reaches the output; lit with material-from-vertex otherwise.
        sw.lighting = mc % 2 == 1;
        sw.lightType[2] = 1, sw.lightComp[2] = 1, sw.material = 7;
        const Case c = switchedCase(200 + mc, vtype, 500, sw);
        SCOPED_TRACE(testing::Message() << "morph " << mc << " vtype 0x" << std::hex << vtype);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, SkinningWith1To8Bones) {
    REQUIRE_GL();
    for (u32 wc = 1; wc <= 8; ++wc) {
        const u32 wt = 1 + wc % 3;
        const u32 vtype = vt_from(2, 7, 1 + (wc + 1) % 3, 1 + wc % 3, wt, wc, wc == 5 ? 3 : 1);
        Switches sw;
        sw.texture = true, sw.fog = true;
        sw.texMap = 1, sw.projSource = wc % 4;  // positions and normals after skinning feed the projection
        sw.lighting = true;
        sw.lightType[0] = 1, sw.lightComp[0] = 1;  // point light: world position
        sw.lightType[1] = 0, sw.lightComp[1] = 2;
        const Case c = switchedCase(300 + wc, vtype, 500, sw);
        SCOPED_TRACE(testing::Message() << "bones " << wc << " vtype 0x" << std::hex << vtype);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, EachLightTypeAndComponent) {
    REQUIRE_GL();
    // LTYPE type 0 directional, 1 point, 2 spot, 3 (spot); comp 0 ambient+diffuse, 1 +specular,
    // 2 powered diffuse, 3 (as 0). Point and spot lights attenuate.
    for (int type = 0; type < 4; ++type)
        for (int comp = 0; comp < 4; ++comp) {
            Switches sw;
            sw.lighting = true;
            const int n = (type + comp) % 4;
            sw.lightType[n] = type, sw.lightComp[n] = comp;
            sw.separate = comp == 1 && type % 2 == 0;
            sw.texture = true;
            const u32 vtype = vt_from(0, type == 1 ? 0 : 7, 3, 3);
            const Case c = switchedCase(400 + u32(type * 4 + comp), vtype, 800, sw);
            SCOPED_TRACE(testing::Message() << "type " << type << " comp " << comp);
            EXPECT_EXACT(H, c);
        }
    // All four lights at once, mixed, and lights seen from both sides (NREV).
    for (int i = 0; i < 6; ++i) {
        Switches sw;
        sw.lighting = true;
        for (int n = 0; n < 4; ++n) sw.lightType[n] = (n + i) % 4, sw.lightComp[n] = (n * 3 + i) % 4;
        sw.nrev = i % 2;
        sw.material = u32(i);
        const Case c = switchedCase(420 + u32(i), vt_from(1, 7, 1 + i % 3, 3), 800, sw);
        SCOPED_TRACE(testing::Message() << "mixed " << i);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, MaterialFromVertexAndSeparateSpecular) {
    REQUIRE_GL();
    for (u32 material = 0; material < 8; ++material)
        for (int separate = 0; separate < 2; ++separate) {
            Switches sw;
            sw.lighting = true;
            sw.lightType[0] = 0, sw.lightComp[0] = 1;
            sw.lightType[1] = 1, sw.lightComp[1] = 1;
            sw.lightType[3] = 2, sw.lightComp[3] = 0;
            sw.material = material;
            sw.separate = separate;
            const u32 vtype = vt_from(0, kColors[1 + material % 4], 2, 3);
            const Case c = switchedCase(500 + material * 2 + u32(separate), vtype, 600, sw);
            SCOPED_TRACE(testing::Message() << "material " << material << " lmode " << separate);
            EXPECT_EXACT(H, c);
        }
}

TEST(GlHwVertex, TextureMappingModes) {
    REQUIRE_GL();
    // UV with scale/offset for each coordinate format (also TMAP mode 3, which behaves as UV).
    for (u32 tc = 0; tc < 4; ++tc) {
        Switches sw;
        sw.texture = true;
        sw.texMap = tc == 2 ? 3 : 0;
        const Case c = switchedCase(600 + tc, vt_from(tc, 0, 0, 3), 600, sw);
        SCOPED_TRACE(testing::Message() << "uv tc " << tc);
        EXPECT_EXACT(H, c);
    }
    // Projection from the model position, UV, normalised normal, normal; with and without a
    // normal in the format (no normal: (0, 0, 1)).
    for (int src = 0; src < 4; ++src)
        for (u32 nrm : {0u, 1u, 3u}) {
            Switches sw;
            sw.texture = true, sw.texMap = 1, sw.projSource = src;
            sw.nrev = nrm == 1;
            const Case c = switchedCase(610 + u32(src) * 4 + nrm, vt_from(2, 0, nrm, 1 + u32(src) % 3), 600, sw);
            SCOPED_TRACE(testing::Message() << "projection source " << src << " nrm " << nrm);
            EXPECT_EXACT(H, c);
        }
    // Shade mapping, with and without lighting, with and without a normal.
    for (int i = 0; i < 4; ++i) {
        Switches sw;
        sw.texture = true, sw.texMap = 2;
        sw.lighting = i % 2;
        sw.lightType[0] = 2, sw.lightComp[0] = 0;
        const Case c = switchedCase(640 + u32(i), vt_from(0, 0, i < 2 ? 3u : 0u, 3), 600, sw);
        SCOPED_TRACE(testing::Message() << "shade " << i);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, FogFactorAndItsSpecials) {
    REQUIRE_GL();
    // Per-vertex (z_view + FOG1)·FOG2, FOG1 infinite or NaN (the whole draw 0 or 1), FOG2
    // infinite (±262144), ge-rules.md §8.9.
    const u32 fog1[] = {0, 0x7F8000, 0xFF8000, 0x7FC000, 0};
    const u32 fog2[] = {0, 0x3F8000, 0xBF8000, 0x3F8000, 0x7F8000};
    for (int i = 0; i < 5; ++i) {
        Switches sw;
        sw.fog = true;
        sw.lighting = i == 1;
        sw.lightType[0] = 1;
        Case c = switchedCase(700 + u32(i), vt_from(0, 4, 1, 2), 600, sw);
        if (fog1[i]) c.rig.set(GE_CMD_FOG1, fog1[i]);
        if (fog2[i]) c.rig.set(GE_CMD_FOG2, fog2[i]);
        SCOPED_TRACE(testing::Message() << "fog case " << i);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, RandomStatesAndFormats) {
    REQUIRE_GL();
    // Everything at once, 24 random configurations (each a different program).
    Rng r(99);
    for (int i = 0; i < 24; ++i) {
        const u32 wt = u32(r.irange(0, 3));
        const u32 vtype = vt_from(u32(r.irange(0, 3)), kColors[r.irange(0, 4)], u32(r.irange(0, 3)), u32(r.irange(1, 3)),
                                  wt, u32(r.irange(1, 8)), u32(r.coin(0.3) ? r.irange(2, 8) : 1));
        const Switches sw = randomSwitches(r);
        SceneShape shape;
        shape.depth = r.uni(3, 12);
        shape.depthJitter = r.coin(0.3) ? -r.uni(0, 4) : 0;
        const Case c = switchedCase(800 + u32(i), vtype, 400, sw, shape);
        SCOPED_TRACE(testing::Message() << "random " << i << " vtype 0x" << std::hex << vtype);
        EXPECT_EXACT(H, c);
    }
}

TEST(GlHwVertex, DiscardRulesAndDepthClampPerVertex) {
    REQUIRE_GL();
    // Vertices off the 4096² screen, beyond the far plane, behind the near plane (and the
    // camera), with CLE = 0 and 1: the drop decision of every vertex and, for kept ones, every
    // output (Z clamped with CLE = 1).
    const SceneShape shapes[] = {
        {10.0f, 40.0f, 0.0f},   // huge: many vertices off the screen
        {1.2f, 1.5f, 0.0f},     // crossing the near plane and the camera
        {0.4f, 1.0f, 0.0f},     // mostly behind the near plane
        {900.0f, 400.0f, 400.0f},  // around the far plane
    };
    int si = 0;
    for (const SceneShape& shape : shapes) {
        for (int cle = 0; cle < 2; ++cle) {
            Switches sw;
            sw.cle = cle;
            sw.texture = true, sw.fog = true;
            Case c = switchedCase(900 + u32(si * 2 + cle), vt_from(3, 7, 0, 3), 1500, sw, shape);
            const Report rep = runCase(H, c);
            if (verbose()) std::printf("%s\n", rep.summary().c_str());
            SCOPED_TRACE(testing::Message() << "shape " << si << " cle " << cle);
            EXPECT_EQ(rep.total(), 0) << rep.summary();
            // The scenes exercise the rules: vertices dropped (CLE = 0: off-screen, beyond a
            // plane), or kept with Z clamped and the X/Y check waived (CLE = 1).
            if (!cle) {
                EXPECT_GT(rep.dropped, 0) << rep.summary();
            }
            EXPECT_GT(rep.drawn, 0) << rep.summary();
        }
        ++si;
    }
}

TEST(GlHwVertex, GeMatrixTermRulesForFloatSpecials) {
    REQUIRE_GL();
    // geometry/transform.cpp geTerm: a zero or denormal factor gives a zero term whatever the
    // other is (NaN, ∞); an exponent of 255 is an ordinary exponent (1.m·2^128). Orthographic
    // projection whose z column feeds only y through a tiny factor; positions with NaN, ±∞,
    // ±0 and denormal components.
    Rng r(31);
    Case c = makeCase(1000, vt_from(0, 7, 0, 3), 1000);
    Rig& rig = c.rig;
    for (int i = 0; i < 12; ++i) rig.st.world[i] = rig.st.view[i] = 0;
    rig.st.world[0] = rig.st.world[4] = rig.st.world[8] = 1;
    rig.st.view[0] = rig.st.view[4] = rig.st.view[8] = 1;
    for (int i = 0; i < 16; ++i) rig.st.proj[i] = 0;
    rig.st.proj[0] = 0.9f;
    rig.st.proj[5] = 0.8f;
    rig.st.proj[9] = 2.5e-38f;   // z → y: finite for z = ±∞ (±1·2^128 · 2.5e-38 ≈ 8.5)
    rig.st.proj[4] = 1e-40f;     // y → x: denormal, always a zero term
    rig.st.proj[15] = 1;
    rig.set(GE_CMD_CLE, 1);      // NaN/∞ Z is clamped, and a clamped vertex is kept
    const float specials[] = {0.0f, -0.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), 1e-41f, 0.5f, -0.75f};
    const VertexLayout l = VertexLayout::fromVtype(c.vtype);
    for (int v = 0; v < c.count; ++v) {
        u8* p = c.bytes.data() + size_t(v) * l.size + l.posOff;
        float xyz[3] = {r.uni(-0.9f, 0.9f), r.uni(-0.9f, 0.9f), specials[v % 8]};
        if (v % 16 == 9) xyz[1] = specials[(v / 16) % 8];  // y special: x gets its denormal-factor term
        for (int i = 0; i < 3; ++i) {
            u32 bits;
            std::memcpy(&bits, &xyz[i], 4);
            writeLE32(p + 4 * i, bits);
        }
    }
    const Report rep = runCase(H, c);
    if (verbose()) std::printf("%s\n", rep.summary().c_str());
    EXPECT_EQ(rep.total(), 0) << rep.summary();
    EXPECT_GT(rep.drawn, c.count / 2) << rep.summary();
}

TEST(GlHwVertex, DriversWithoutDoublesStayClose) {
    REQUIRE_GL();
    // The fallback for drivers without GL_ARB_gpu_shader_fp64 (float division, float
    // normalisation, GLSL pow): measured, not required to be exact. Printed with
    // GE2GL_HW_VERBOSE; positions must still be right for almost every vertex.
    Switches sw;
    sw.lighting = true, sw.texture = true, sw.fog = true;
    for (int n = 0; n < 4; ++n) sw.lightType[n] = n % 4, sw.lightComp[n] = n % 3;
    Case c = switchedCase(1100, vt_from(3, 7, 3, 3), 2000, sw);
    c.defines = "#define GE_NO_FP64\n";
    const Report rep = runCase(H, c);
    std::printf("without doubles: %s\n", rep.summary().c_str());
    EXPECT_LE(rep.bad[kFlags] + rep.bad[kPos], rep.vertices / 50) << rep.summary();
}

TEST(GlHwVertex, VertexIdFromDrawArraysFirstAndFromIndices) {
    REQUIRE_GL();
    // gl_VertexID selects the bytes at id·stride: glDrawArrays with `first`, glDrawElements with
    // the GE's indices rebased to the buffer (here a scrambled, repeating index list).
    Switches sw;
    sw.texture = true, sw.fog = true, sw.lighting = true;
    sw.lightType[0] = 1, sw.lightComp[0] = 1;
    Case c = switchedCase(1200, vt_from(1, 5, 2, 2, 2, 3, 2), 300, sw);
    c.first = 150, c.count = 100;
    EXPECT_EXACT(H, c);
    c.first = 0;
    for (int i = 0; i < 200; ++i) c.indices.push_back(u16(299 - i * 7 % 300));
    EXPECT_EXACT(H, c);
}

TEST(GlHwVertex, VerticesWithoutPositionAreDropped) {
    REQUIRE_GL();
    // VT = 0: three reserved bytes, the vertex is dropped (ge-rules.md §8.11).
    Case c = makeCase(1300, vt_from(2, 7, 1, 0), 50);
    const Report rep = runCase(H, c);
    EXPECT_EQ(rep.total(), 0) << rep.summary();
    EXPECT_EQ(rep.dropped, 50) << rep.summary();
}

}  // namespace
}  // namespace ge::gltest
