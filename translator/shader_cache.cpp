// SPDX-License-Identifier: MIT
// Program cache (see shader_cache.h).
#include "translator/shader_cache.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "shadergen/shader_gen.h"

namespace ge::gl {

namespace {

std::string hex64(u64 v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// On-disk binary layout: magic "GE2GLPB1", u32 format, u32 length, bytes.
constexpr char kMagic[8] = {'G', 'E', '2', 'G', 'L', 'P', 'B', '1'};

}  // namespace

ProgramCache::ProgramCache(const GlContext& ctx, const shadergen::HostCaps& caps, std::string dumpDir,
                           std::string diskDir)
    : ctx_(ctx), caps_(caps), dumpDir_(std::move(dumpDir)), diskDir_(std::move(diskDir)) {
    std::error_code ec;
    if (!dumpDir_.empty()) std::filesystem::create_directories(dumpDir_, ec);
    if (!diskDir_.empty()) std::filesystem::create_directories(diskDir_, ec);
    if (!ctx_.caps().programBinary) diskDir_.clear();  // nothing to store binaries with
}

ProgramCache::~ProgramCache() {
    for (auto& kv : programs_)
        if (kv.second.id) ctx_.f().DeleteProgram(kv.second.id);
}

const Program* ProgramCache::get(const shadergen::VsKey& vs, const shadergen::FsKey& fs, std::string* err) {
    Key key;
    std::memset(static_cast<void*>(&key), 0, sizeof key);
    key.vs = vs;
    key.fs = fs;
    return getImpl(key, err);
}

const Program* ProgramCache::getHw(const shadergen::HwVsKey& vs, const shadergen::FsKey& fs, std::string* err) {
    Key key;
    std::memset(static_cast<void*>(&key), 0, sizeof key);
    key.hw = vs;
    key.fs = fs;
    key.hwVertex = 1;
    return getImpl(key, err);
}

const Program* ProgramCache::getImpl(const Key& key, std::string* err) {
    auto it = programs_.find(key);
    if (it != programs_.end()) {
        ++stats_.hits;
        return &it->second;
    }
    std::string vsSrc, fsSrc, gsSrc;
    const bool vsOk = key.hwVertex ? shadergen::generateHwVertexShader(key.hw, caps_, vsSrc, err)
                                   : shadergen::generateVertexShader(key.vs, caps_, vsSrc, err);
    if (!vsOk) return nullptr;
    if (key.hwVertex && !shadergen::generateHwGeometryShader(key.hw, caps_, gsSrc, err))
        return nullptr;
    if (!shadergen::generateFragmentShader(key.fs, caps_, fsSrc, err)) return nullptr;
    const std::string all =
        vsSrc + '\0' + gsSrc + '\0' + fsSrc + '\0' + ctx_.caps().version + '\0' + ctx_.caps().renderer;
    const std::string name = hex64(shadergen::hashBytes(all.data(), all.size()));
    if (!dumpDir_.empty()) {
        std::ofstream(dumpDir_ + "/" + name + ".vert") << vsSrc;
        std::ofstream(dumpDir_ + "/" + name + ".frag") << fsSrc;
        if (!gsSrc.empty()) std::ofstream(dumpDir_ + "/" + name + ".geom") << gsSrc;
    }
    Program p;
    p.id = ctx_.f().CreateProgram();
    bool ok = false;
    if (!diskDir_.empty() && loadBinary(diskDir_ + "/" + name + ".bin", p.id)) {
        ok = true;
        ++stats_.diskHits;
    } else {
        ok = build(vsSrc, fsSrc, gsSrc, p, err);
        if (ok) {
            ++stats_.compiles;
            if (!diskDir_.empty()) saveBinary(diskDir_ + "/" + name + ".bin", p.id);
        }
    }
    if (!ok) {
        ctx_.f().DeleteProgram(p.id);
        return nullptr;
    }
    lookupUniforms(p);
    return &programs_.emplace(key, p).first->second;
}

bool ProgramCache::build(const std::string& vsSrc, const std::string& fsSrc, const std::string& gsSrc, Program& p,
                         std::string* err) {
    const GlFuncs& gl = ctx_.f();
    auto compile = [&](GLenum type, const std::string& src) -> GLuint {
        GLuint sh = gl.CreateShader(type);
        const char* text = src.c_str();
        gl.ShaderSource(sh, 1, &text, nullptr);
        gl.CompileShader(sh);
        GLint okc = 0;
        gl.GetShaderiv(sh, GL_COMPILE_STATUS, &okc);
        if (!okc) {
            char log[4096] = {};
            gl.GetShaderInfoLog(sh, sizeof log - 1, nullptr, log);
            const char* stage = type == GL_VERTEX_SHADER ? "vertex" : (type == GL_GEOMETRY_SHADER ? "geometry" : "fragment");
            if (err) *err = std::string(stage) + " shader: " + log + "\n" + src;
            gl.DeleteShader(sh);
            return 0;
        }
        return sh;
    };
    GLuint v = compile(GL_VERTEX_SHADER, vsSrc);
    if (!v) return false;
    GLuint f = compile(GL_FRAGMENT_SHADER, fsSrc);
    if (!f) {
        gl.DeleteShader(v);
        return false;
    }
    GLuint g = 0;
    if (!gsSrc.empty() && !(g = compile(GL_GEOMETRY_SHADER, gsSrc))) {
        gl.DeleteShader(v);
        gl.DeleteShader(f);
        return false;
    }
    gl.AttachShader(p.id, v);
    gl.AttachShader(p.id, f);
    if (g) gl.AttachShader(p.id, g);
    if (!diskDir_.empty()) gl.ProgramParameteri(p.id, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    gl.LinkProgram(p.id);
    gl.DetachShader(p.id, v);
    gl.DetachShader(p.id, f);
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    if (g) {
        gl.DetachShader(p.id, g);
        gl.DeleteShader(g);
    }
    GLint linked = 0;
    gl.GetProgramiv(p.id, GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[4096] = {};
        gl.GetProgramInfoLog(p.id, sizeof log - 1, nullptr, log);
        if (err) *err = std::string("link: ") + log;
        return false;
    }
    return true;
}

bool ProgramCache::loadBinary(const std::string& path, GLuint prog) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    char magic[8];
    u32 format = 0, length = 0;
    if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) return false;
    if (!in.read(reinterpret_cast<char*>(&format), 4) || !in.read(reinterpret_cast<char*>(&length), 4)) return false;
    if (length == 0 || length > (64u << 20)) return false;
    std::vector<char> data(length);
    if (!in.read(data.data(), length)) return false;
    const GlFuncs& gl = ctx_.f();
    gl.ProgramBinary(prog, GLenum(format), data.data(), GLsizei(length));
    GLint linked = 0;
    gl.GetProgramiv(prog, GL_LINK_STATUS, &linked);
    while (gl.GetError() != GL_NO_ERROR) {
    }
    return linked != 0;
}

void ProgramCache::saveBinary(const std::string& path, GLuint prog) {
    const GlFuncs& gl = ctx_.f();
    GLint length = 0;
    gl.GetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) return;
    std::vector<char> data(static_cast<size_t>(length));
    GLenum format = 0;
    GLsizei got = 0;
    gl.GetProgramBinary(prog, length, &got, &format, data.data());
    if (got <= 0) return;
    // Write to a temporary name first so a concurrent reader never sees a half file; the name is
    // this process's and this cache's own, so concurrent writers (renders run in parallel) never
    // share one.
    trimDisk();
    const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." +
                            std::to_string(reinterpret_cast<uintptr_t>(this)) + "." + std::to_string(++tmpSerial_);
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return;
        const u32 fmt = u32(format), len = u32(got);
        out.write(kMagic, 8);
        out.write(reinterpret_cast<const char*>(&fmt), 4);
        out.write(reinterpret_cast<const char*>(&len), 4);
        out.write(data.data(), got);
        if (!out) return;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
}

// The directory is bounded: before this cache's first write, when it holds more than
// kMaxDiskPrograms binaries, the oldest (by modification time) go until half remain. A program
// binary is 10-20 KiB, so the directory stays under about 40 MiB; a removed binary is compiled and
// stored again when next needed. Files that are not the cache's are left alone. Another process
// may remove the same file first: every failure here is ignored. A temporary file left by a
// process that died while writing it (saveBinary) goes once it is an hour old.
void ProgramCache::trimDisk() {
    if (trimmed_) return;
    trimmed_ = true;
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_time_type staleBefore = fs::file_time_type::clock::now() - std::chrono::hours(1);
    std::vector<std::pair<fs::file_time_type, fs::path>> bins;
    for (fs::directory_iterator it(diskDir_, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& f = it->path();
        const std::string name = f.filename().string();
        std::error_code tec;
        const fs::file_time_type t = fs::last_write_time(f, tec);
        if (tec) continue;
        if (name.size() > 21 && name.compare(16, 9, ".bin.tmp.") == 0) {
            if (t < staleBefore) fs::remove(f, tec);
            continue;
        }
        if (f.extension() == ".bin" && f.stem().string().size() == 16) bins.emplace_back(t, f);
    }
    if (bins.size() <= kMaxDiskPrograms) return;
    std::sort(bins.begin(), bins.end());
    for (size_t i = 0; i < bins.size() - kMaxDiskPrograms / 2; ++i) fs::remove(bins[i].second, ec);
}

void ProgramCache::lookupUniforms(Program& p) {
    const GlFuncs& gl = ctx_.f();
    namespace U = shadergen::uniform;
    auto loc = [&](const char* n) { return gl.GetUniformLocation(p.id, n); };
    p.ndcScale = loc(U::kNdcScale);
    p.tex = loc(U::kTex);
    p.dstColor = loc(U::kDstColor);
    p.dstDepth = loc(U::kDstDepth);
    p.texEnv = loc(U::kTexEnv);
    p.fogColor = loc(U::kFogColor);
    p.alphaTest = loc(U::kAlphaTest);
    p.colorRef = loc(U::kColorRef);
    p.colorMask = loc(U::kColorMask);
    p.stencil = loc(U::kStencil);
    p.fixA = loc(U::kFixA);
    p.fixB = loc(U::kFixB);
    p.dither = loc(U::kDither);
    p.keep = loc(U::kKeep);
    p.zRange = loc(U::kZRange);
    p.texLevels = loc(U::kTexLevels);
    p.texParams = loc(U::kTexParams);
    p.texSlope = loc(U::kTexSlope);
    p.pixScale = loc(U::kPixScale);
    p.texScale = loc(U::kTexScale);
    p.clut = loc(U::kClut);
    p.hwBlock = loc(shadergen::hwuniform::kBlock);
    // Samplers never change unit: set once.
    gl.UseProgram(p.id);
    if (p.tex >= 0) gl.Uniform1i(p.tex, shadergen::kUnitTex);
    if (p.dstColor >= 0) gl.Uniform1i(p.dstColor, shadergen::kUnitDstColor);
    if (p.dstDepth >= 0) gl.Uniform1i(p.dstDepth, shadergen::kUnitDstDepth);
    const GLint tris = loc(shadergen::kTrisUniform);
    if (tris >= 0) gl.Uniform1i(tris, shadergen::kUnitTris);
    const GLint grads = loc(shadergen::kGradientsUniform);
    if (grads >= 0) gl.Uniform1i(grads, shadergen::kUnitGradients);
    const GLint clutTex = loc(shadergen::kClutTexUniform);
    if (clutTex >= 0) gl.Uniform1i(clutTex, shadergen::kUnitClut);
    const GLint vtx = loc(shadergen::hwuniform::kVertexBytes);
    if (vtx >= 0) gl.Uniform1i(vtx, shadergen::kUnitVertexBytes);
    const GLint ring = loc(shadergen::hwuniform::kRingIds);
    if (ring >= 0) gl.Uniform1i(ring, shadergen::kUnitRingIds);
    gl.UseProgram(0);
}

}  // namespace ge::gl
