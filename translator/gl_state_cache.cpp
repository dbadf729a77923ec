// SPDX-License-Identifier: MIT
#include "translator/gl_state_cache.h"

#include <cstring>

#include "shadergen/shader_gen.h"

namespace ge::gl {

namespace {

GLenum glCompare(u8 geFunc) {
    static constexpr GLenum map[8] = {GL_NEVER, GL_ALWAYS, GL_EQUAL, GL_NOTEQUAL, GL_LESS, GL_LEQUAL, GL_GREATER, GL_GEQUAL};
    return map[geFunc & 7];
}

}  // namespace

void GlStateCache::forget() {
    cache_ = StateCache{};
    seenClobbers_ = fb_.clobbers();
}

void GlStateCache::apply(const DrawSetup& s, const Program& prog, GLuint dstColor, GLuint dstDepth) {
    if (fb_.clobbers() != seenClobbers_) {
        seenClobbers_ = fb_.clobbers();
        cache_.valid = false;
    }
    if (!cache_.valid) {
        cache_ = StateCache{};
        cache_.valid = true;
        // Drawing coordinates map to the target's texels at render scale N (u_ndcScale).
        gl_.Viewport(0, 0, kTargetSize * scale_, kTargetSize * scale_);
        gl_.Enable(GL_SCISSOR_TEST);
        gl_.BindVertexArray(vao_);
        gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
        gl_.DrawBuffer(GL_COLOR_ATTACHMENT0);
        cache_.scissor[2] = -2;
        cache_.depthTest = !s.ff.depthTest;
        cache_.depthMask = !s.ff.depthMask;
        for (int i = 0; i < 4; ++i) cache_.colorMask[i] = !s.ff.colorMask[i];
    }
    if (cache_.program != prog.id) {
        gl_.UseProgram(prog.id);
        cache_.program = prog.id;
        ++counters_.stateChanges;
    }
    if (std::memcmp(cache_.scissor, s.scissor, sizeof s.scissor) != 0) {
        gl_.Scissor(s.scissor[0] * scale_, s.scissor[1] * scale_, (s.scissor[2] - s.scissor[0] + 1) * scale_,
                    (s.scissor[3] - s.scissor[1] + 1) * scale_);
        std::memcpy(cache_.scissor, s.scissor, sizeof s.scissor);
        ++counters_.stateChanges;
    }
    // With a destination read the shader merges masks itself and writes every channel.
    bool cm[4];
    for (int i = 0; i < 4; ++i) cm[i] = s.fs.dstRead != shadergen::DstRead::None ? true : s.ff.colorMask[i];
    if (std::memcmp(cm, cache_.colorMask, sizeof cm) != 0) {
        gl_.ColorMask(cm[0], cm[1], cm[2], cm[3]);
        std::memcpy(cache_.colorMask, cm, sizeof cm);
        ++counters_.stateChanges;
    }
    if (s.ff.depthTest != cache_.depthTest) {
        if (s.ff.depthTest)
            gl_.Enable(GL_DEPTH_TEST);
        else
            gl_.Disable(GL_DEPTH_TEST);
        cache_.depthTest = s.ff.depthTest;
        ++counters_.stateChanges;
    }
    if (s.ff.depthTest && s.ff.depthFunc != cache_.depthFunc) {
        gl_.DepthFunc(glCompare(s.ff.depthFunc));
        cache_.depthFunc = s.ff.depthFunc;
        ++counters_.stateChanges;
    }
    if (s.ff.depthMask != cache_.depthMask) {
        gl_.DepthMask(s.ff.depthMask ? GL_TRUE : GL_FALSE);
        cache_.depthMask = s.ff.depthMask;
        ++counters_.stateChanges;
    }
    auto bindUnit = [&](int unit, GLuint tex, GLuint& cached) {
        if (tex == cached) return;
        gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl_.BindTexture(GL_TEXTURE_2D, tex);
        gl_.ActiveTexture(GL_TEXTURE0);
        cached = tex;
        ++counters_.stateChanges;
    };
    if (s.fs.tex) bindUnit(shadergen::kUnitTex, s.texture, cache_.texture);
    if (s.clutTexture) bindUnit(shadergen::kUnitClut, s.clutTexture, cache_.clutTexture);
    if (s.fs.dstRead == shadergen::DstRead::Texture) bindUnit(shadergen::kUnitDstColor, dstColor, cache_.dstColor);
    if (s.fs.depthRead == shadergen::DepthRead::Texture) bindUnit(shadergen::kUnitDstDepth, dstDepth, cache_.dstDepth);

    // Uniforms are program state: a program whose last values are these needs no upload (a
    // glUniform call makes the driver re-validate the program's constants before the next
    // draw). The shadow is dropped whenever a program is created (an id could come back).
    UniformShadow& shadow = uniformShadow_[prog.id];
    if (shadow.valid && std::memcmp(&shadow.u, &s.u, sizeof s.u) == 0) {
        ++counters_.uniformUploadsSkipped;
        return;
    }
    shadow.u = s.u;
    shadow.valid = true;
    ++counters_.uniformUploads;
    const shadergen::FsUniforms& u = s.u;
    if (prog.ndcScale >= 0) gl_.Uniform2f(prog.ndcScale, 2.0f / kTargetSize, 2.0f / kTargetSize);
    if (prog.texEnv >= 0) gl_.Uniform3iv(prog.texEnv, 1, u.texEnv);
    if (prog.fogColor >= 0) gl_.Uniform3iv(prog.fogColor, 1, u.fogColor);
    const s32 at[2] = {u.alphaRef, u.alphaMask};
    if (prog.alphaTest >= 0) gl_.Uniform2iv(prog.alphaTest, 1, at);
    if (prog.colorRef >= 0) gl_.Uniform3iv(prog.colorRef, 1, u.colorRef);
    if (prog.colorMask >= 0) gl_.Uniform3iv(prog.colorMask, 1, u.colorMask);
    const s32 sr[2] = {u.stencilRef, u.stencilMask};
    if (prog.stencil >= 0) gl_.Uniform2iv(prog.stencil, 1, sr);
    if (prog.fixA >= 0) gl_.Uniform3iv(prog.fixA, 1, u.fixA);
    if (prog.fixB >= 0) gl_.Uniform3iv(prog.fixB, 1, u.fixB);
    if (prog.dither >= 0) gl_.Uniform1iv(prog.dither, 16, u.dither);
    if (prog.keep >= 0) gl_.Uniform4iv(prog.keep, 1, u.keepMask);
    const s32 zr[2] = {u.minZ, u.maxZ};
    if (prog.zRange >= 0) gl_.Uniform2iv(prog.zRange, 1, zr);
    if (prog.texLevels >= 0) gl_.Uniform4iv(prog.texLevels, 8, &u.texLevels[0][0]);
    const s32 tp[2] = {u.texMaxLevel, u.texLodBias};
    if (prog.texParams >= 0) gl_.Uniform2iv(prog.texParams, 1, tp);
    if (prog.texSlope >= 0) gl_.Uniform1f(prog.texSlope, u.texSlope);
    if (prog.pixScale >= 0) gl_.Uniform1i(prog.pixScale, scale_);
    if (prog.texScale >= 0) gl_.Uniform1i(prog.texScale, u.texScale);
    const s32 cl[2] = {u.clutShift, u.clutMask};
    if (prog.clut >= 0) gl_.Uniform2iv(prog.clut, 1, cl);
}

}  // namespace ge::gl
