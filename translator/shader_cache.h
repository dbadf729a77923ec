// SPDX-License-Identifier: MIT
// Program cache: (VsKey, FsKey) → linked GL program with its uniform locations.
//
// Invalidation contract: programs never go stale (keys fully determine the source). The optional
// disk cache stores program binaries under programCacheDir, named by a hash of the exact vertex +
// fragment source plus the driver's version string, so a generator change or a driver update
// simply misses (no hand-bumped version). A binary the driver rejects is recompiled and rewritten.
#pragma once
#include <memory>
#include <string>
#include <unordered_map>

#include "shadergen/hw_vertex.h"
#include "shadergen/shader_keys.h"
#include "translator/gl_context.h"

namespace ge::gl {

struct Program {
    GLuint id = 0;
    // Uniform locations (−1 when the program does not use it).
    GLint ndcScale = -1, tex = -1, dstColor = -1, dstDepth = -1, texEnv = -1, fogColor = -1, alphaTest = -1,
          colorRef = -1, colorMask = -1, stencil = -1, fixA = -1, fixB = -1, dither = -1, keep = -1, zRange = -1,
          texLevels = -1, texParams = -1, texSlope = -1, pixScale = -1, texScale = -1, clut = -1;
    GLint hwBlock = -1;  // hardware-mode vertex shader: the HwVsUniforms words (shadergen/hw_vertex.h)
};

struct ProgramCacheStats {
    u64 compiles = 0, hits = 0, diskHits = 0;
};

class ProgramCache {
public:
    // The on-disk directory's bound (trimDisk).
    static constexpr size_t kMaxDiskPrograms = 2048;
    ProgramCache(const GlContext& ctx, const shadergen::HostCaps& caps, std::string dumpDir, std::string diskDir);
    ~ProgramCache();
    // nullptr + err when generation or compilation fails.
    const Program* get(const shadergen::VsKey& vs, const shadergen::FsKey& fs, std::string* err);
    // A program whose vertex shader does the GE's vertex work (GL hardware mode, hw_vertex.h).
    const Program* getHw(const shadergen::HwVsKey& vs, const shadergen::FsKey& fs, std::string* err);
    const ProgramCacheStats& stats() const { return stats_; }

private:
    struct Key {
        shadergen::VsKey vs;
        shadergen::HwVsKey hw;  // zero for the CPU-vertex programs
        shadergen::FsKey fs;
        u32 hwVertex;           // 1: the vertex shader is generateHwVertexShader(hw)
    };
    struct KeyHash {
        size_t operator()(const Key& k) const { return size_t(shadergen::hashBytes(&k, sizeof k)); }
    };
    struct KeyEq {
        bool operator()(const Key& a, const Key& b) const { return std::memcmp(&a, &b, sizeof a) == 0; }
    };
    const Program* getImpl(const Key& key, std::string* err);
    bool build(const std::string& vsSrc, const std::string& fsSrc, const std::string& gsSrc, Program& out,
               std::string* err);
    bool loadBinary(const std::string& path, GLuint prog);
    void saveBinary(const std::string& path, GLuint prog);
    void trimDisk();
    void lookupUniforms(Program& p);

    const GlContext& ctx_;
    shadergen::HostCaps caps_;
    std::string dumpDir_, diskDir_;
    bool trimmed_ = false;  // trimDisk has looked at diskDir_
    u64 tmpSerial_ = 0;
    std::unordered_map<Key, Program, KeyHash, KeyEq> programs_;
    ProgramCacheStats stats_;
};

}  // namespace ge::gl
