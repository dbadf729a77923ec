// SPDX-License-Identifier: MIT
// The GL harness of the hardware mode's geometry tests (tests/gl_hw_clip.cpp, gl_hw_through.cpp):
// one OSMesa context for the test binary, programs of the hw vertex + geometry shader whose output
// is captured with transform feedback, and the REQUIRE_GL() opening of each test.
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "shadergen/hw_vertex.h"
#include "shadergen/shader_gen.h"
#include "translator/gl_context.h"
#include "translator/gl_renderer.h"

namespace ge::gltest {

namespace sg = shadergen;

// ---------------------------------------------------------------------------------------------
// GL harness: one OSMesa context for the suite; programs of the hw vertex + geometry shader.

// One captured vertex of the geometry shader's output (interleaved, 17 floats).
struct Out {
    float pos[4], color[4], color2[3], tex[4], fog, z;
};
static_assert(sizeof(Out) == 17 * 4);
inline const char* const kVaryings[] = {"gl_Position", "v_color", "v_color2", "v_tex", "v_fog", "v_z"};

// A change of the geometry shader's text (EachRuleIsNeeded): `from` replaced by `to`.
struct GsEdit {
    std::string from, to;
};

struct Harness {
    std::unique_ptr<gl::GlContext> ctx;
    GLuint vao = 0, vtxBuf = 0, vtxTex = 0, tfb = 0, ebo = 0, ringBuf = 0, ringTex = 0;
    std::string error;
    std::map<std::string, GLuint> programs;  // llvmpipe compiles slowly: each program once

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
        f.GenBuffers(1, &ebo);
        f.GenBuffers(1, &ringBuf);
        f.GenTextures(1, &ringTex);
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
            log = std::string(buf) + "\n" + src;
            f.DeleteShader(s);
            return 0;
        }
        return s;
    }

    // Vertex + geometry shader of `key` (the geometry shader's text changed by `edit`), plus `fs`
    // when non-empty; transform feedback of kVaryings when `capture`. Owned by the harness.
    GLuint program(const sg::HwVsKey& key, const GsEdit* edit, const std::string& fs, bool capture, std::string& log) {
        std::string id(reinterpret_cast<const char*>(&key), sizeof key);
        id += (edit ? edit->from + '\1' + edit->to : std::string()) + '\2' + fs + (capture ? "c" : "");
        auto it = programs.find(id);
        if (it != programs.end()) return it->second;
        const GLuint prog = build(key, edit, fs, capture, log);
        if (prog) programs.emplace(id, prog);
        return prog;
    }
    GLuint build(const sg::HwVsKey& key, const GsEdit* edit, const std::string& fs, bool capture, std::string& log) const {
        const gl::GlFuncs& f = ctx->f();
        std::string vsSrc, gsSrc;
        sg::HostCaps caps;
        if (!sg::generateHwVertexShader(key, caps, vsSrc, &log) || !sg::generateHwGeometryShader(key, caps, gsSrc, &log))
            return 0;
        if (edit) {
            const size_t at = gsSrc.find(edit->from);
            if (at == std::string::npos) {
                log = "edit not applicable: " + edit->from;
                return 0;
            }
            gsSrc.replace(at, edit->from.size(), edit->to);
        }
        GLuint sh[3] = {compile(GL_VERTEX_SHADER, vsSrc, log), compile(GL_GEOMETRY_SHADER, gsSrc, log), 0};
        if (!fs.empty()) sh[2] = compile(GL_FRAGMENT_SHADER, fs, log);
        if (!sh[0] || !sh[1] || (!fs.empty() && !sh[2])) return 0;
        GLuint prog = f.CreateProgram();
        for (GLuint s : sh)
            if (s) f.AttachShader(prog, s);
        if (capture)
            f.TransformFeedbackVaryings(prog, GLsizei(std::size(kVaryings)), kVaryings, GL_INTERLEAVED_ATTRIBS);
        f.LinkProgram(prog);
        for (GLuint s : sh)
            if (s) f.DeleteShader(s);
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

    // `size` bytes (and 64 spare) in `buf`, read through the R8UI buffer texture `tex` on `unit`.
    void byteTexture(GLuint buf, GLuint tex, int unit, const void* data, size_t size) const {
        const gl::GlFuncs& f = ctx->f();
        f.BindBuffer(GL_TEXTURE_BUFFER, buf);
        f.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(size + 64), nullptr, GL_STATIC_DRAW);
        f.BufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(size), data);
        f.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        f.BindTexture(GL_TEXTURE_BUFFER, tex);
        f.TexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, buf);
        f.ActiveTexture(GL_TEXTURE0);
    }

    // The vertex bytes, u_hw and u_ndcScale for `prog`.
    void bindInputs(GLuint prog, const std::vector<u8>& bytes, const sg::HwVsUniforms& u, float ndcX, float ndcY) const {
        const gl::GlFuncs& f = ctx->f();
        f.UseProgram(prog);
        byteTexture(vtxBuf, vtxTex, sg::kUnitVertexBytes, bytes.data(), bytes.size());
        f.Uniform1i(f.GetUniformLocation(prog, sg::hwuniform::kVertexBytes), sg::kUnitVertexBytes);
        f.Uniform1i(f.GetUniformLocation(prog, sg::hwuniform::kRingIds), sg::kUnitRingIds);  // -1: no strip/fan
        f.Uniform4uiv(f.GetUniformLocation(prog, sg::hwuniform::kBlock), sg::kHwVsUniformVec4,
                      reinterpret_cast<const GLuint*>(&u));
        f.Uniform2f(f.GetUniformLocation(prog, sg::hwuniform::kNdcScale), ndcX, ndcY);
    }

    // The PRIM of `mode` (GL_TRIANGLES, _STRIP, _FAN) over vertices 0..count-1, or over `indices`
    // when not empty, as the translator draws it: the triangle list of sg::hwTriangleList with
    // the ring ids in u_ring (no GL culling, no clip distance).
    void draw(GLenum mode, int count, const std::vector<u16>& indices) const {
        const gl::GlFuncs& f = ctx->f();
        std::vector<u32> seq(indices.begin(), indices.end());
        if (indices.empty())
            for (int i = 0; i < count; ++i) seq.push_back(u32(i));
        const u8 primKind = mode == GL_TRIANGLE_STRIP ? 1 : (mode == GL_TRIANGLE_FAN ? 2 : 0);
        std::vector<u32> list;
        std::vector<u8> ringIds;
        sg::hwTriangleList(primKind, seq.data(), u32(seq.size()), 0, list, ringIds);
        byteTexture(ringBuf, ringTex, sg::kUnitRingIds, ringIds.data(), ringIds.size());
        f.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
        f.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(list.size() * 4), list.data(), GL_STATIC_DRAW);
        f.DrawElements(GL_TRIANGLES, GLsizei(list.size()), GL_UNSIGNED_INT, nullptr);
    }

    // The geometry shader's output vertices for a draw. The buffer is filled with NaN first; every
    // emitted vertex has gl_Position.w = 1, which ends the list.
    std::vector<Out> capture(GLenum mode, int count, const std::vector<u16>& indices) const {
        const gl::GlFuncs& f = ctx->f();
        const int prims = indices.empty() ? count : int(indices.size());
        std::vector<Out> out(size_t(prims) * 6 + 6);
        std::memset(static_cast<void*>(out.data()), 0xFF, out.size() * sizeof(Out));
        f.BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
        f.BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, GLsizeiptr(out.size() * sizeof(Out)), out.data(), GL_STATIC_READ);
        f.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
        f.Enable(GL_RASTERIZER_DISCARD);
        f.BeginTransformFeedback(GL_TRIANGLES);
        draw(mode, count, indices);
        f.EndTransformFeedback();
        f.Disable(GL_RASTERIZER_DISCARD);
        f.GetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(out.size() * sizeof(Out)), out.data());
        size_t n = 0;
        while (n < out.size() && out[n].pos[3] == 1.0f) ++n;
        out.resize(n);
        return out;
    }
};

// One GL context for the whole test binary, destroyed at static destruction (before
// LeakSanitizer's exit check: its tracer crashed stopping llvmpipe's threads of a context left
// alive).
inline Harness* harness() {
    static std::unique_ptr<Harness> h = [] {
        // Under the sanitizers, no Mesa shader disk cache: its writer thread still running at exit
        // crashed LeakSanitizer's exit-time tracer after these shader-heavy tests in a fresh CI
        // clone. (Only here: the program-binary tests need the cache.)
        if (std::getenv("GE2GL_SANITIZER_RUN")) setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
        auto x = std::make_unique<Harness>();
        if (!x->init()) {
            std::fprintf(stderr, "GL hw harness: %s\n", x->error.c_str());
            x->ctx.reset();
        }
        return x;
    }();
    return h->ctx ? h.get() : nullptr;
}

#define REQUIRE_GL()                                                 \
    Harness* H = harness();                                          \
    if (!H) GTEST_SKIP() << "no GL context with transform feedback"; \
    H->ctx->makeCurrent()

}  // namespace ge::gltest
