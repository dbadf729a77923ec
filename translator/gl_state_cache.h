// SPDX-License-Identifier: MIT
// The GL state a batch's draw needs — program, scissor, colour and depth masks, depth test,
// texture units, fragment uniforms — applied through a cache of what GL holds, so that only
// changes reach the driver (a glUniform call makes the driver re-validate the program's
// constants before the next draw). The renderer tells the cache when GL changed behind its back.
#pragma once
#include <unordered_map>

#include "shadergen/keys_from_state.h"
#include "shadergen/shader_keys.h"
#include "translator/framebuffer_manager.h"
#include "translator/gl_funcs.h"
#include "translator/shader_cache.h"

namespace ge::gl {

// Everything a batch's GL draw depends on (gl_batch.cpp). Compared byte-wise: always memset
// before filling.
struct DrawSetup {
    shadergen::VsKey vs;
    shadergen::FsKey fs;
    shadergen::FixedFunction ff;
    shadergen::FsUniforms u;
    GLuint texture;
    GLuint clutTexture;  // palette of a CLUT16/32 texture read from a render target
    u32 colorAddr, colorStride, colorFormat;
    u32 depthAddr, depthStride, useDepth;
    s32 scissor[4];  // inclusive x0, y0, x1, y1
};

class GlStateCache {
public:
    struct Counters {
        u64 stateChanges = 0;
        // Fragment-uniform sets: uploaded / skipped because the program already held them.
        u64 uniformUploads = 0, uniformUploadsSkipped = 0;
    };

    // `fb`: its clobber count says when a pass of its own changed GL bindings. `scale`: the
    // render scale (targets hold scale×scale texels per PSP pixel).
    GlStateCache(const GlFuncs& gl, const FramebufferManager& fb, int scale) : gl_(gl), fb_(fb), scale_(scale) {}
    // The vertex array and buffer every batch draws from (bound again whenever the cache is rebuilt).
    void useVertexArray(GLuint vao, GLuint vbo) {
        vao_ = vao;
        vbo_ = vbo;
    }

    // Makes GL hold what `s` draws with `prog`; dstColor/dstDepth: the textures a
    // DstRead::Texture / DepthRead::Texture draw reads the destination from.
    void apply(const DrawSetup& s, const Program& prog, GLuint dstColor, GLuint dstDepth);

    // Drops every assumption about GL state (the host or another pass changed it).
    void forget();
    // GL state changed in ways the cache does not track (blits, reads): rebuilt at the next apply.
    void invalidate() { cache_.valid = false; }
    // A program was created: rebuilt at the next apply, and every uniform shadow dropped (an id
    // could come back).
    void programsCreated() {
        cache_.valid = false;
        uniformShadow_.clear();
    }
    // Texture unit 0 was bound to something else (uploads, decoding into a cached texture).
    void textureUnitUsed() { cache_.texture = ~0u; }
    // The palette textures were deleted.
    void clutTexturesDeleted() { cache_.clutTexture = ~0u; }

    const Counters& counters() const { return counters_; }

private:
    struct StateCache {
        bool valid = false;
        GLuint program = ~0u, texture = ~0u, dstColor = ~0u, dstDepth = ~0u, clutTexture = ~0u;
        s32 scissor[4] = {};
        bool colorMask[4] = {};
        bool depthTest = false, depthMask = false;
        u8 depthFunc = 0xFF;
    };
    // Per program: the fragment uniforms last uploaded.
    struct UniformShadow {
        shadergen::FsUniforms u;
        bool valid = false;
    };

    const GlFuncs& gl_;
    const FramebufferManager& fb_;
    const int scale_;
    GLuint vao_ = 0, vbo_ = 0;
    StateCache cache_;
    std::unordered_map<GLuint, UniformShadow> uniformShadow_;
    u64 seenClobbers_ = 0;
    Counters counters_;
};

}  // namespace ge::gl
