// The GL renderer: consumes the engine's packets, keeps VRAM exact (see gl_renderer.h).
//
// Per draw: the CPU vertex pipeline produces GL-ready vertices in drawing coordinates; the state
// decides a "setup" (shader keys, uniform values, texture, targets, scissor). Consecutive draws
// with byte-identical setups are batched into one GL draw. At flush the targets are made valid,
// the program is fetched from the cache and the batch is drawn:
//  - no destination read: one glDrawArrays;
//  - framebuffer fetch: one glDrawArrays (coherent fetch orders overlapping primitives);
//  - texture reads (texture barrier, or a copy in `baseline`): primitives are grouped so no two
//    primitives of a group overlap; each group gets a barrier (or a copy of its area) first.
#include "translator/gl_renderer.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "hle/pixel_format.h"
#include "hle/texture_decoder.h"
#include "shadergen/keys_from_state.h"
#include "shadergen/shader_gen.h"
#include "translator/framebuffer_manager.h"
#include "translator/gl_context.h"
#include "translator/shader_cache.h"
#include "translator/texture_cache.h"
#include "translator/vertex_pipeline.h"

namespace ge::gl {

namespace {

GLenum glCompare(u8 geFunc) {
    static constexpr GLenum map[8] = {GL_NEVER, GL_ALWAYS, GL_EQUAL, GL_NOTEQUAL, GL_LESS, GL_LEQUAL, GL_GREATER, GL_GEQUAL};
    return map[geFunc & 7];
}

bool overlaps(const PrimBounds& a, const PrimBounds& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

shadergen::HostCaps hostCapsFor(const GlCaps& caps, const GlOptions& opt) {
    shadergen::HostCaps c = caps.hostCaps(opt.baseline, opt.floatInterpolation);
    if (opt.disableFramebufferFetch) c.fbFetch = c.depthFetch = 0;
    return c;
}

// True when the depth buffer rows a draw needs share bytes with colour target t (linear VRAM).
bool depthOverlapsColor(const Target& t, u32 depthAddr, u32 depthStride, int rows) {
    const u64 begin = vramLinear(depthAddr);
    const u64 end = begin + u64(std::clamp(rows, 1, kTargetSize)) * depthStride * 2;
    return begin < t.end() && end > t.addr;
}

// Everything a batch's GL draw depends on. Compared byte-wise: always memset before filling.
struct Setup {
    shadergen::VsKey vs;
    shadergen::FsKey fs;
    shadergen::FixedFunction ff;
    shadergen::FsUniforms u;
    GLuint texture;
    u32 colorAddr, colorStride, colorFormat;
    u32 depthAddr, depthStride, useDepth;
    s32 scissor[4];  // inclusive x0, y0, x1, y1
};

}  // namespace

class GlRenderer final : public Renderer {
public:
    GlRenderer(Memory& mem, const GlOptions& opt, std::unique_ptr<GlContext> ctx)
        : mem_(mem), opt_(opt), ctx_(std::move(ctx)), gl_(ctx_->f()),
          caps_(hostCapsFor(ctx_->caps(), opt)),
          useBarrier_(!opt.baseline && ctx_->caps().textureBarrier),
          programs_(*ctx_, caps_, opt.shaderDumpDir, opt.programCacheDir), textures_(*ctx_), fb_(*ctx_, mem) {
        std::memset(static_cast<void*>(&batchSetup_), 0, sizeof batchSetup_);
        gl_.GenVertexArrays(1, &vao_);
        gl_.GenBuffers(1, &vbo_);
        gl_.BindVertexArray(vao_);
        gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
        const GLsizei stride = sizeof(GlVertex);
        gl_.EnableVertexAttribArray(shadergen::kAttrPos);
        gl_.VertexAttribPointer(shadergen::kAttrPos, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(GlVertex, x)));
        gl_.EnableVertexAttribArray(shadergen::kAttrColor);
        gl_.VertexAttribPointer(shadergen::kAttrColor, 4, GL_UNSIGNED_BYTE, GL_FALSE, stride,
                                reinterpret_cast<void*>(offsetof(GlVertex, color)));
        gl_.EnableVertexAttribArray(shadergen::kAttrColor2);
        gl_.VertexAttribPointer(shadergen::kAttrColor2, 3, GL_UNSIGNED_BYTE, GL_FALSE, stride,
                                reinterpret_cast<void*>(offsetof(GlVertex, color2)));
        gl_.EnableVertexAttribArray(shadergen::kAttrTex);
        gl_.VertexAttribPointer(shadergen::kAttrTex, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(GlVertex, tex)));
        gl_.EnableVertexAttribArray(shadergen::kAttrFog);
        gl_.VertexAttribPointer(shadergen::kAttrFog, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(GlVertex, fog)));
        // Copies of the target for destination reads without barrier/fetch.
        auto makeTex = [&](GLuint& t, GLenum ifmt, GLenum fmt, GLenum type) {
            gl_.GenTextures(1, &t);
            gl_.BindTexture(GL_TEXTURE_2D, t);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            gl_.TexImage2D(GL_TEXTURE_2D, 0, ifmt, kTargetSize, kTargetSize, 0, fmt, type, nullptr);
        };
        if (!useBarrier_) {
            makeTex(snapColor_, GL_RGBA8UI, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE);
            makeTex(snapDepth_, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
            gl_.GenFramebuffers(1, &snapFbo_);
            gl_.BindFramebuffer(GL_FRAMEBUFFER, snapFbo_);
            gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, snapColor_, 0);
            gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, snapDepth_, 0);
        }
        gl_.Enable(GL_DEPTH_CLAMP);  // positions carry z = 0; depth comes from gl_FragDepth
        if (caps_.exactInterp) {
            // Triangle records (tri_setup.h) in a buffer texture on their own unit; the buffer's
            // contents are replaced per flush.
            gl_.GenBuffers(1, &recordBuf_);
            gl_.BindBuffer(GL_TEXTURE_BUFFER, recordBuf_);
            gl_.BufferData(GL_TEXTURE_BUFFER, sizeof(TriRecord), nullptr, GL_STREAM_DRAW);
            gl_.GenTextures(1, &recordTex_);
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitTris));
            gl_.BindTexture(GL_TEXTURE_BUFFER, recordTex_);
            gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32UI, recordBuf_);
            gl_.ActiveTexture(GL_TEXTURE0);
        }
    }

    ~GlRenderer() override {
        ctx_->makeCurrent();
        textures_.clear();
        gl_.DeleteBuffers(1, &vbo_);
        gl_.DeleteVertexArrays(1, &vao_);
        if (recordTex_) gl_.DeleteTextures(1, &recordTex_);
        if (recordBuf_) gl_.DeleteBuffers(1, &recordBuf_);
        if (snapColor_) gl_.DeleteTextures(1, &snapColor_);
        if (snapDepth_) gl_.DeleteTextures(1, &snapDepth_);
        if (snapFbo_) gl_.DeleteFramebuffers(1, &snapFbo_);
        if (presentTex_) gl_.DeleteTextures(1, &presentTex_);
    }

    // ---- Renderer ----
    u64 pixelWork() const override { return pipeline_.pixelWork(); }
    void setPixelBudget(u64 pixels) override { pipeline_.setPixelBudget(pixels); }

    // Geometry is built before the draw's setup: the setup depends on the primitives' colours
    // (the reference's skipped alpha test, softmodel/blend.h referenceSkipsAlphaTest).
    void drawPrim(const PrimPacket& p) override {
        ++stats_.draws;
        const GeState& st = *p.state;
        std::string err;
        drawGeo_.clear();
        if (!pipeline_.processPrim(mem_, st, p, vertexSettings(st), drawGeo_, &err)) noteError(err);
        addDraw(st, shadergen::DrawFlags::fromState(st));
    }

    void drawPatch(const PatchPacket& p) override {
        ++stats_.draws;
        const GeState& st = *p.state;
        std::string err;
        drawGeo_.clear();
        if (!pipeline_.processPatch(mem_, st, p, vertexSettings(st), drawGeo_, &err)) noteError(err);
        addDraw(st, shadergen::DrawFlags::fromState(st));
    }

    void addDraw(const GeState& st, shadergen::DrawFlags flags) {
        if (drawGeo_.empty()) return;
        flags.vertexAlphaFull = pipeline_.drawAlphaFull();
        if (!beginDraw(st, flags)) return;
        geo_.append(drawGeo_);
    }

    void drawImmediate(const ImmPacket& p) override {
        ++stats_.draws;
        if (p.vertices.empty()) return;
        const GeState& st = *p.state;
        // AP2 flag bits 11..23 of the first vertex override the state for this primitive (§3.12).
        const u32 f = p.flags;
        shadergen::DrawFlags df = shadergen::DrawFlags::fromState(st);
        df.gouraud = (f >> 18) & 1;
        df.texture = (f >> 21) & 1;
        df.fog = (f >> 22) & 1;
        df.dither = (f >> 23) & 1;
        VertexSettings vs = vertexSettings(st);
        vs.gouraud = df.gouraud;
        vs.cull = ((f >> 19) & 1) && !st.isClearMode();
        vs.cullCcw = (f >> 20) & 1;
        vs.texture = df.texture && !st.isClearMode();
        vs.fog = df.fog && !st.isThrough();
        drawGeo_.clear();
        pipeline_.processImmediate(st, p, vs, drawGeo_);
        addDraw(st, df);
    }

    void blockTransfer(const TransferPacket& t, Memory& mem) override {
        flush();
        // The source must hold what was drawn; the destination's dirty pixels go to VRAM first so
        // the re-upload after the copy keeps pixels outside the copied rectangle.
        fb_.syncRange(t.srcBegin(), t.srcBytes());
        fb_.syncRange(t.dstBegin(), t.dstBytes());
        performTransfer(mem, t);
        fb_.memoryWritten(t.dstBegin(), t.dstBytes());
        ++generation_;
    }
    void clutLoaded(const GeState&) override { ++generation_; }
    void textureFlush() override { ++generation_; }
    void textureSync() override { flush(); }
    void finish() override { flush(); }
    void syncMemoryForRead(u32 addr, u32 size) override {
        flush();
        fb_.syncRange(addr, size);
    }
    void memoryWritten(u32 addr, u32 size) override {
        flush();
        fb_.memoryWritten(addr, size);
        ++generation_;
    }
    void flushToMemory() override {
        flush();
        fb_.flushAll();
        gl_.Finish();
    }

    GlStats stats() const {
        GlStats s = stats_;
        s.shaderCompiles = programs_.stats().compiles;
        s.shaderCacheHits = programs_.stats().hits;
        s.diskCacheHits = programs_.stats().diskHits;
        s.textureUploads = textures_.stats().uploads;
        s.textureCacheHits = textures_.stats().hits;
        s.readbacks = fb_.readbacks();
        return s;
    }

    unsigned frameTexture(u32 addr, u32 stride, GeBufferFormat fmt) {
        flushToMemory();
        if (stride == 0 || stride > 2048) return 0;
        const u32 w = std::min<u32>(stride, 480), h = 272;
        const u32 bpp = bytesPerPixel(fmt);
        std::vector<u32> px(size_t(w) * h, 0);
        for (u32 y = 0; y < h; ++y) {
            const u32 row = addr + y * stride * bpp;
            const u32 avail = mem_.validSize(row, w * bpp) / bpp;
            if (const u8* src = avail ? mem_.ptr(row, avail * bpp) : nullptr)
                convertToRGBA8888(src, fmt, avail, 1, stride, &px[size_t(y) * w]);
        }
        if (!presentTex_) {
            gl_.GenTextures(1, &presentTex_);
            gl_.BindTexture(GL_TEXTURE_2D, presentTex_);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        }
        gl_.BindTexture(GL_TEXTURE_2D, presentTex_);
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, GLsizei(w), GLsizei(h), 0, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        cache_.valid = false;
        return presentTex_;
    }

    const std::string& lastError() const { return lastError_; }

private:
    VertexSettings vertexSettings(const GeState& st) const {
        VertexSettings vs = VertexSettings::fromState(st);
        vs.records = caps_.exactInterp != 0;
        return vs;
    }

    void noteError(const std::string& e) {
        if (lastError_.empty()) lastError_ = e;
        ++errors_;
    }

    // Computes the setup of a draw; flushes the pending batch when it differs. False when the
    // draw cannot produce pixels (empty scissor, unusable buffers).
    bool beginDraw(const GeState& st, const shadergen::DrawFlags& flags) {
        Setup s;
        std::memset(static_cast<void*>(&s), 0, sizeof s);
        const shadergen::PipelineKeys keys = shadergen::keysFromState(st, flags, caps_, opt_.baseline);
        s.vs = keys.vs;
        s.fs = keys.fs;
        s.ff = keys.ff;
        shadergen::uniformsFromState(st, s.u);
        s.colorAddr = vramLinear(st.framebufAddr());
        s.colorStride = st.framebufStride();
        s.colorFormat = st.framebufFormat();
        s.useDepth = (keys.ff.usesDepth || keys.fs.depthRead != shadergen::DepthRead::None) ? 1 : 0;
        if (s.useDepth) {
            s.depthAddr = vramLinear(st.depthbufAddr());
            s.depthStride = st.depthbufStride();
        }
        // Scissor ∩ REGION2, inclusive (ref §8.6), limited to the buffer width and target size.
        s.scissor[0] = s32(st.SCISSOR1_x());
        s.scissor[1] = s32(st.SCISSOR1_y());
        s.scissor[2] = std::min({s32(st.SCISSOR2_x()), s32(st.REGION2_x()), s32(s.colorStride) - 1, kTargetSize - 1});
        s.scissor[3] = std::min({s32(st.SCISSOR2_y()), s32(st.REGION2_y()), kTargetSize - 1});
        if (s.colorStride == 0 || s.scissor[2] < s.scissor[0] || s.scissor[3] < s.scissor[1]) {
            flush();
            return false;
        }
        if (s.useDepth && s.depthStride == 0) s.useDepth = 0;
        if (s.fs.tex) {
            const int levels = s.fs.texMip ? int(std::min<u32>(st.TMODE_maxlevel(), 7)) + 1 : 1;
            // Render-to-texture: pending draws into the texture's bytes, then the targets' pixels,
            // must be in VRAM before the texture is decoded.
            u32 srcBegin, srcEnd;
            TextureCache::sourceRange(st, levels, srcBegin, srcEnd);
            const u32 lin = vramLinear(srcBegin);
            const u32 linEnd = lin + (srcEnd - srcBegin);
            if (!geo_.empty() && batchOverlaps(lin, linEnd)) flush();
            const u64 wb = fb_.writeBacks();
            fb_.syncRange(lin, std::max<u32>(linEnd - lin, 1));
            if (fb_.writeBacks() != wb) ++generation_;
            // A re-upload reuses the GL texture object: draw what is pending with the old contents.
            if (!geo_.empty() && generation_ != batchGeneration_) flush();
            const bool clut = st.textureFormat() >= GE_TFMT_CLUT4 && st.textureFormat() <= GE_TFMT_CLUT32;
            const u64 clutHash = clut ? shadergen::hashBytes(st.clut, sizeof st.clut) : 0;
            const TextureEntry* e = textures_.get(mem_, st, levels, generation_, clutHash);
            cache_.texture = ~0u;  // the cache may have rebound unit 0
            if (!e) {
                flush();
                return false;
            }
            s.texture = e->tex;
            for (int l = 0; l < 8; ++l)
                for (int i = 0; i < 4; ++i) s.u.texLevels[l][i] = e->placement[std::min(l, e->levels - 1)][i];
            s.u.texMaxLevel = e->levels - 1;
        }
        if (geo_.empty() || std::memcmp(&s, &batchSetup_, sizeof s) != 0) {
            flush();
            std::memcpy(static_cast<void*>(&batchSetup_), &s, sizeof s);
            batchGeneration_ = generation_;
        }
        return true;
    }

    bool batchOverlaps(u32 begin, u32 end) const {
        const Setup& s = batchSetup_;
        const u32 bpp = s.colorFormat == GE_FORMAT_8888 ? 4 : 2;
        const u32 cEnd = s.colorAddr + u32(s.scissor[3] + 1) * s.colorStride * bpp;
        if (s.colorAddr < end && cEnd > begin) return true;
        if (s.useDepth) {
            const u32 dEnd = s.depthAddr + u32(s.scissor[3] + 1) * s.depthStride * 2;
            if (s.depthAddr < end && dEnd > begin) return true;
        }
        return false;
    }

    // ---- GL state cache ----
    struct StateCache {
        bool valid = false;
        GLuint program = ~0u, texture = ~0u, dstColor = ~0u, dstDepth = ~0u;
        s32 scissor[4] = {};
        bool colorMask[4] = {};
        bool depthTest = false, depthMask = false;
        u8 depthFunc = 0xFF;
    };

    void applyState(const Setup& s, const Program& prog, GLuint dstColor, GLuint dstDepth) {
        if (fb_.clobbers() != seenClobbers_) {
            seenClobbers_ = fb_.clobbers();
            cache_.valid = false;
        }
        if (!cache_.valid) {
            cache_ = StateCache{};
            cache_.valid = true;
            gl_.Viewport(0, 0, kTargetSize, kTargetSize);
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
            ++stats_.stateChanges;
        }
        if (std::memcmp(cache_.scissor, s.scissor, sizeof s.scissor) != 0) {
            gl_.Scissor(s.scissor[0], s.scissor[1], s.scissor[2] - s.scissor[0] + 1, s.scissor[3] - s.scissor[1] + 1);
            std::memcpy(cache_.scissor, s.scissor, sizeof s.scissor);
            ++stats_.stateChanges;
        }
        // With a destination read the shader merges masks itself and writes every channel.
        bool cm[4];
        for (int i = 0; i < 4; ++i) cm[i] = s.fs.dstRead != shadergen::DstRead::None ? true : s.ff.colorMask[i];
        if (std::memcmp(cm, cache_.colorMask, sizeof cm) != 0) {
            gl_.ColorMask(cm[0], cm[1], cm[2], cm[3]);
            std::memcpy(cache_.colorMask, cm, sizeof cm);
            ++stats_.stateChanges;
        }
        if (s.ff.depthTest != cache_.depthTest) {
            if (s.ff.depthTest)
                gl_.Enable(GL_DEPTH_TEST);
            else
                gl_.Disable(GL_DEPTH_TEST);
            cache_.depthTest = s.ff.depthTest;
            ++stats_.stateChanges;
        }
        if (s.ff.depthTest && s.ff.depthFunc != cache_.depthFunc) {
            gl_.DepthFunc(glCompare(s.ff.depthFunc));
            cache_.depthFunc = s.ff.depthFunc;
            ++stats_.stateChanges;
        }
        if (s.ff.depthMask != cache_.depthMask) {
            gl_.DepthMask(s.ff.depthMask ? GL_TRUE : GL_FALSE);
            cache_.depthMask = s.ff.depthMask;
            ++stats_.stateChanges;
        }
        auto bindUnit = [&](int unit, GLuint tex, GLuint& cached) {
            if (tex == cached) return;
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
            gl_.BindTexture(GL_TEXTURE_2D, tex);
            gl_.ActiveTexture(GL_TEXTURE0);
            cached = tex;
            ++stats_.stateChanges;
        };
        if (s.fs.tex) bindUnit(shadergen::kUnitTex, s.texture, cache_.texture);
        if (s.fs.dstRead == shadergen::DstRead::Texture) bindUnit(shadergen::kUnitDstColor, dstColor, cache_.dstColor);
        if (s.fs.depthRead == shadergen::DepthRead::Texture) bindUnit(shadergen::kUnitDstDepth, dstDepth, cache_.dstDepth);

        // Uniforms: set per flush (cheap next to a draw; keeps no per-program shadow copies).
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
    }

    void flush() {
        if (geo_.empty()) return;
        const Setup& s = batchSetup_;
        const std::vector<GlVertex>& verts = geo_.tris;
        const std::vector<PrimBounds>& bounds = geo_.triBounds;
        const int perPrim = 3;
        if (verts.empty()) {
            geo_.clear();
            return;
        }
        Target* ct = fb_.colorTarget(s.colorAddr, s.colorStride, GeBufferFormat(s.colorFormat), s.scissor[3] + 1);
        // A depth buffer sharing bytes with the colour target is not used: taking its target would
        // claim those bytes and free the colour target this draw binds (targets never alias,
        // framebuffer_manager.h; found by fuzz_replay_gl). PPSSPP likewise drops a depth buffer at
        // the colour buffer's address (FramebufferManagerCommon: "the game doesn't care about Z").
        const bool depthOnColor = ct && s.useDepth && s.depthStride &&
                                  depthOverlapsColor(*ct, s.depthAddr, s.depthStride, s.scissor[3] + 1);
        Target* dt = s.useDepth && !depthOnColor ? fb_.depthTarget(s.depthAddr, s.depthStride, s.scissor[3] + 1)
                                                 : nullptr;
        if (!ct) {
            geo_.clear();
            return;
        }
        const u64 compiles = programs_.stats().compiles + programs_.stats().diskHits;
        std::string err;
        const Program* prog = programs_.get(s.vs, s.fs, &err);
        if (programs_.stats().compiles + programs_.stats().diskHits != compiles) cache_.valid = false;
        if (!prog) {
            noteError(err);
            geo_.clear();
            return;
        }
        fb_.bindDraw(ct, dt);
        if (fb_.clobbers() != seenClobbers_) cache_.valid = false;
        const bool dstTex = s.fs.dstRead == shadergen::DstRead::Texture;
        GLuint dstColor = 0, dstDepth = 0;
        if (dstTex) {
            dstColor = useBarrier_ ? ct->tex : snapColor_;
            dstDepth = useBarrier_ ? (dt ? dt->tex : 0) : snapDepth_;
        }
        applyState(s, *prog, dstColor, dstDepth);

        gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(verts.size() * sizeof(GlVertex)), verts.data(), GL_STREAM_DRAW);
        if (caps_.exactInterp) {
            if (geo_.records.size() * 3 != verts.size()) {
                noteError("internal: triangle records out of step with vertices");
                geo_.clear();
                return;
            }
            gl_.BindBuffer(GL_TEXTURE_BUFFER, recordBuf_);
            gl_.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(geo_.records.size() * sizeof(TriRecord)),
                           geo_.records.data(), GL_STREAM_DRAW);
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitTris));
            gl_.BindTexture(GL_TEXTURE_BUFFER, recordTex_);
            gl_.ActiveTexture(GL_TEXTURE0);
        }
        const GLenum mode = GL_TRIANGLES;
        Rect drawn;
        const Rect sc{s.scissor[0], s.scissor[1], s.scissor[2], s.scissor[3]};
        auto clipRect = [&](const PrimBounds& b) {
            Rect r{std::max(b.x0, sc.x0), std::max(b.y0, sc.y0), std::min(b.x1, sc.x1), std::min(b.y1, sc.y1)};
            return r;
        };
        if (!dstTex) {
            gl_.DrawArrays(mode, 0, GLsizei(verts.size()));
            ++stats_.glDrawCalls;
            for (const PrimBounds& b : bounds) drawn.add(clipRect(b));
        } else {
            // Groups of primitives that never touch the same pixel: each reads the destination
            // as it was before the group, which is exact because no member sees another's write.
            const size_t n = bounds.size();
            size_t first = 0;
            std::vector<size_t> members;
            while (first < n) {
                members.clear();
                Rect area;
                size_t end = first;
                for (; end < n; ++end) {
                    const PrimBounds& b = bounds[end];
                    bool clash = false;
                    if (!(b.joinPrev && end > first))
                        for (size_t m : members)
                            if (overlaps(bounds[m], b)) {
                                clash = true;
                                break;
                            }
                    if (clash || members.size() >= 256) break;
                    members.push_back(end);
                    area.add(clipRect(b));
                }
                if (!area.empty()) {
                    if (useBarrier_) {
                        gl_.TextureBarrier();
                    } else {
                        // Copy the group's area of the target (and depth) into the snapshot.
                        gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fb_.drawFbo());
                        gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, snapFbo_);
                        gl_.Disable(GL_SCISSOR_TEST);
                        GLbitfield mask = GL_COLOR_BUFFER_BIT;
                        if (s.fs.depthRead == shadergen::DepthRead::Texture && dt) mask |= GL_DEPTH_BUFFER_BIT;
                        gl_.BlitFramebuffer(area.x0, area.y0, area.x1 + 1, area.y1 + 1, area.x0, area.y0, area.x1 + 1,
                                            area.y1 + 1, mask, GL_NEAREST);
                        gl_.Enable(GL_SCISSOR_TEST);
                        gl_.BindFramebuffer(GL_FRAMEBUFFER, fb_.drawFbo());
                    }
                    gl_.DrawArrays(mode, GLint(first * size_t(perPrim)), GLsizei((end - first) * size_t(perPrim)));
                    ++stats_.glDrawCalls;
                    drawn.add(area);
                }
                first = end;
            }
        }
        // Dirty tracking for write-back (conservative bounds, clipped to the scissor).
        const bool colorWrites = s.fs.dstRead != shadergen::DstRead::None || s.ff.colorMask[0] || s.ff.colorMask[1] ||
                                 s.ff.colorMask[2] || s.ff.colorMask[3];
        if (colorWrites) ct->dirty.add(drawn);
        if (dt && s.ff.depthMask) dt->dirty.add(drawn);
        geo_.clear();
    }

    Memory& mem_;
    GlOptions opt_;
    std::unique_ptr<GlContext> ctx_;
    const GlFuncs& gl_;
    shadergen::HostCaps caps_;
    bool useBarrier_ = false;
    ProgramCache programs_;
    TextureCache textures_;
    FramebufferManager fb_;
    VertexPipeline pipeline_;
    u64 batchGeneration_ = 0;
    Geometry geo_;
    Geometry drawGeo_;  // the current draw's geometry, before it joins the batch
    Setup batchSetup_;
    StateCache cache_;
    u64 seenClobbers_ = 0;
    u64 generation_ = 1;
    GLuint vao_ = 0, vbo_ = 0;
    GLuint snapColor_ = 0, snapDepth_ = 0, snapFbo_ = 0, presentTex_ = 0;
    GLuint recordBuf_ = 0, recordTex_ = 0;
    GlStats stats_;
    std::string lastError_;
    u64 errors_ = 0;
};

std::unique_ptr<Renderer> createGlRenderer(Memory& mem, const GlOptions& opt, std::string& err) {
    std::unique_ptr<GlContext> ctx = GlContext::create(opt.context, err);
    if (!ctx) return nullptr;
    return std::make_unique<GlRenderer>(mem, opt, std::move(ctx));
}

GlStats glStats(const Renderer& r) { return static_cast<const GlRenderer&>(r).stats(); }

std::string glStatsText(const GlStats& s) {
    std::string out;
    auto line = [&](const char* name, u64 v) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%-18s %llu\n", name, static_cast<unsigned long long>(v));
        out += buf;
    };
    line("draws", s.draws);
    line("glDrawCalls", s.glDrawCalls);
    line("stateChanges", s.stateChanges);
    line("shaderCompiles", s.shaderCompiles);
    line("shaderCacheHits", s.shaderCacheHits);
    line("diskCacheHits", s.diskCacheHits);
    line("textureUploads", s.textureUploads);
    line("textureCacheHits", s.textureCacheHits);
    line("readbacks", s.readbacks);
    return out;
}

unsigned glFrameTexture(Renderer& r, u32 vramAddr, u32 stride, GeBufferFormat fmt) {
    return static_cast<GlRenderer&>(r).frameTexture(vramAddr, stride, fmt);
}

}  // namespace ge::gl
