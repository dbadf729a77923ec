// SPDX-License-Identifier: MIT
// The GL renderer: consumes the engine's packets, keeps VRAM exact (see gl_renderer.h).
//
// Per draw: the CPU vertex pipeline produces GL-ready vertices in drawing coordinates; the state
// decides a "setup" (shader keys, uniform values, texture, targets, scissor). Consecutive draws
// with byte-identical setups are batched into one GL draw, up to kGlBatchTriangles GL triangles
// (a larger draw is drawn in parts as the vertex pipeline builds it: docs/timing.md). At flush the targets are made valid,
// the program is fetched from the cache and the batch is drawn:
//  - no destination read: one glDrawArrays;
//  - framebuffer fetch: one glDrawArrays (coherent fetch orders overlapping primitives);
//  - texture reads (texture barrier, or a copy in `baseline`): primitives are grouped so no two
//    primitives of a group overlap; each group gets a barrier (or a copy of its area) first.
#include "translator/gl_renderer.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "geometry/texture_size.h"
#include "hle/pixel_format.h"
#include "hle/texture_decoder.h"
#include "shadergen/keys_from_state.h"
#include "shadergen/shader_gen.h"
#include "translator/framebuffer_manager.h"
#include "translator/gl_context.h"
#include "translator/gl_host_state.h"
#include "translator/gpu_vertex_path.h"
#include "translator/present.h"
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
    // Hardware mode rasterises natively: attributes interpolated by GL (the float path).
    shadergen::HostCaps c = caps.hostCaps(opt.baseline, opt.floatInterpolation || opt.mode == GlMode::Hw);
    if (opt.disableFramebufferFetch) c.fbFetch = c.depthFetch = 0;
    return c;
}

// True when the depth buffer rows a draw needs share bytes with colour target t (linear VRAM).
bool depthOverlapsColor(const Target& t, u32 depthAddr, u32 depthStride, int rows) {
    const u64 begin = Memory::drawingAddress(depthAddr);
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
    GLuint clutTexture;  // palette of a CLUT16/32 texture read from a render target
    u32 colorAddr, colorStride, colorFormat;
    u32 depthAddr, depthStride, useDepth;
    s32 scissor[4];  // inclusive x0, y0, x1, y1
};

}  // namespace

class GlRenderer final : public Renderer {
public:
    // `hostState`: what the host's context held before creation (Current contexts), restored by
    // the first hostLeave().
    GlRenderer(Memory& mem, const GlOptions& opt, std::unique_ptr<GlContext> ctx, const HostGlState& hostState)
        : hostState_(hostState), mem_(mem), opt_(opt), hw_(opt.mode == GlMode::Hw), ctx_(std::move(ctx)), gl_(ctx_->f()),
          caps_(hostCapsFor(ctx_->caps(), opt)),
          useBarrier_(!opt.baseline && ctx_->caps().textureBarrier),
          programs_(*ctx_, caps_, opt.shaderDumpDir, opt.programCacheDir), textures_(*ctx_),
          fb_(*ctx_, mem, opt.scale), scale_(fb_.scale()), gpu_(*ctx_) {
        if (hw_) {
            const std::string& r = ctx_->caps().renderer;
            const bool software = r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
                                  r.find("SwiftShader") != std::string::npos;
            gpuVertices_ = opt.vertices == GlOptions::Vertices::Gpu ||
                           (opt.vertices == GlOptions::Vertices::Auto && !software);
        }
        std::memset(static_cast<void*>(&batchSetup_), 0, sizeof batchSetup_);
        pipeline_.setOutputLimit(kBatchTriangles, &GlRenderer::drawOutputFull, this);
        gl_.GenVertexArrays(1, &vao_);
        gl_.GenBuffers(1, &vbo_);
        gl_.BindVertexArray(vao_);
        gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
        if (!ctx_->headless() && gl_.ObjectLabel) {
            // GL_CURRENT: the vertex buffer doubles as the probe that tells our context (or one
            // sharing its objects) from another one current at a later call (currentIsOurs).
            char label[48];
            std::snprintf(label, sizeof label, "ge2gl renderer %p", static_cast<void*>(this));
            probeLabel_ = label;
            gl_.ObjectLabel(GL_BUFFER, vbo_, -1, probeLabel_.c_str());
        }
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
            gl_.TexImage2D(GL_TEXTURE_2D, 0, ifmt, kTargetSize * scale_, kTargetSize * scale_, 0, fmt, type, nullptr);
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
        std::string err;
        // A host context that is gone or not current: its objects go with it; deleting names in
        // whatever context is current would delete the host's objects.
        if (!ctx_->headless() && !currentIsOurs(err)) ctx_->disarm();
        ctx_->enter(err);  // headless: ours current for the deletes, the thread's previous after
        presenter_.reset();
        textures_.clear();
        gl_.DeleteBuffers(1, &vbo_);
        gl_.DeleteVertexArrays(1, &vao_);
        if (recordTex_) gl_.DeleteTextures(1, &recordTex_);
        if (recordBuf_) gl_.DeleteBuffers(1, &recordBuf_);
        if (snapColor_) gl_.DeleteTextures(1, &snapColor_);
        if (snapDepth_) gl_.DeleteTextures(1, &snapDepth_);
        if (snapFbo_) gl_.DeleteFramebuffers(1, &snapFbo_);
        for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
        leaveGuard_.ctx = ctx_.get();  // after the members' own deletes
    }

    // ---- Host calls (plugin API; gl_host_state.h) ----
    // A renderer is created entered (depth 1): the host's thread gets its own state or context
    // back at the first hostLeave().
    bool hostEnter(std::string& err) {
        if (hostDepth_++ > 0) return true;
        if (ctx_->headless()) {
            if (!ctx_->enter(err)) {
                --hostDepth_;
                return false;
            }
        } else {
            if (!currentIsOurs(err)) {
                --hostDepth_;
                return false;
            }
            hostState_.save(gl_);
        }
        establishTranslatorState(gl_);
        forgetGlState();
        return true;
    }
    // GL_CURRENT: is the context current on this thread the one this renderer was created on
    // (or one sharing its objects)? A GL call with none current does nothing and returns 0 (GL
    // 4.6 core profile §2.1.1, "no current context"); another context does not know our buffer,
    // or gives it another label (KHR_debug; without it only the name is checked).
    bool currentIsOurs(std::string& err) const {
        if (!gl_.GetString(GL_VERSION)) {
            err = "no GL context is current on this thread (GL_CURRENT needs the context it was created with)";
            return false;
        }
        bool ours = gl_.IsBuffer(vbo_) == GL_TRUE;
        if (ours && !probeLabel_.empty() && gl_.GetObjectLabel) {
            char label[48] = {};
            GLsizei n = 0;
            gl_.GetObjectLabel(GL_BUFFER, vbo_, GLsizei(sizeof label), &n, label);
            ours = probeLabel_ == std::string(label, size_t(std::max(n, 0)));
        }
        if (!ours)
            err = "the GL context current on this thread is not the one this GL_CURRENT instance was created with "
                  "(nor one sharing its objects)";
        return ours;
    }
    void hostLeave() {
        if (hostDepth_ == 0 || --hostDepth_ > 0) return;
        if (ctx_->headless()) {
            ctx_->leave();  // making another context current flushes ours
        } else {
            hostState_.restore(gl_);
        }
    }
    // Drops every assumption about GL bindings (the host or another pass changed them).
    void forgetGlState() {
        cache_ = StateCache{};
        fb_.forgetBindings();
        seenClobbers_ = fb_.clobbers();
    }
    void hostMayHaveWritten(bool frameBuffers) override {
        ++generation_;  // cached textures are re-hashed against their bytes when next used
        if (frameBuffers) fb_.markSuspect();
    }
    bool holdsNewerThanMemory(u32 addr, u32 size) const override {
        // A batch not yet drawn may write anywhere in its targets; otherwise the dirty targets.
        return !geo_.empty() || fb_.dirtyOverlaps(addr, size);
    }
    void takeDirtyRanges(std::vector<std::pair<u32, u32>>& out) override {
        flush();
        fb_.takeNewlyDirty(out);
    }
    GLuint presentFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH, std::string& err) {
        flush();
        if (!presenter_) presenter_ = std::make_unique<Presenter>(*ctx_, fb_, mem_);
        const GLuint tex = presenter_->frame(addr, stride, fmt, w, h, outW, outH, err);
        forgetGlState();
        return tex;
    }
    int scale() const { return scale_; }

    // ---- Renderer ----
    u64 pixelWork() const override { return pipeline_.pixelWork(); }
    void setPixelBudget(u64 pixels) override { pipeline_.setPixelBudget(pixels); }

    // Geometry is built before the draw's setup: the setup depends on the primitives' colours
    // (the reference's skipped alpha test, geometry/reference_rules.h referenceSkipsAlphaTest).
    void drawPrim(const PrimPacket& p) override {
        ++stats_.draws;
        if (gpuVertices_ && drawPrimOnGpu(p)) return;
        const GeState& st = *p.state;
        std::string err;
        startDraw(st, shadergen::DrawFlags::fromState(st));
        if (!pipeline_.processPrim(mem_, st, p, vertexSettings(st), drawGeo_, &err)) noteError(err);
        addDraw();
    }

    void drawPatch(const PatchPacket& p) override {
        ++stats_.draws;
        const GeState& st = *p.state;
        std::string err;
        startDraw(st, shadergen::DrawFlags::fromState(st));
        if (!pipeline_.processPatch(mem_, st, p, vertexSettings(st), drawGeo_, &err)) noteError(err);
        addDraw();
    }

    // The draw whose geometry the pipeline builds next (addDraw hands it to the batch).
    void startDraw(const GeState& st, const shadergen::DrawFlags& flags) {
        drawGeo_.clear();
        drawState_ = &st;
        drawFlags_ = flags;
    }
    // The draw's geometry (all of it, or what the pipeline has built when it reached
    // kBatchTriangles) joins the batch. A batch holds at most kBatchTriangles GL triangles: the
    // CPU arrays of one batch (vertices, bounds, triangle records) stay bounded, whatever a draw
    // or a run of draws with one setup asks for, and the arrays are trimmed after each flush.
    // A draw split this way decides its setup per part, each part with the colours of the
    // primitives so far (the reference's skipped alpha test, referenceSkipsAlphaTest, looks at
    // the whole draw): only a draw of more than kBatchTriangles GL triangles can tell.
    void addDraw() {
        if (drawGeo_.empty()) return;
        shadergen::DrawFlags flags = drawFlags_;
        flags.vertexAlphaFull = pipeline_.drawAlphaFull();
        if (!beginDraw(*drawState_, flags)) {
            drawGeo_.clear();
            return;
        }
        if (geo_.triangles() + drawGeo_.triangles() > kBatchTriangles) {
            flush();
            batchGeneration_ = generation_;
        }
        geo_.append(drawGeo_);
        drawGeo_.clear();
    }
    static void drawOutputFull(void* self) { static_cast<GlRenderer*>(self)->addDraw(); }
    static constexpr size_t kBatchTriangles = kGlBatchTriangles;

    void drawImmediate(const ImmPacket& p) override {
        ++stats_.draws;
        if (p.vertices.empty()) return;
        const GeState& st = *p.state;
        // AP2 flag bits 11..23 of the first vertex override the state for this primitive (docs/ge-rules.md §3.12).
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
        startDraw(st, df);
        pipeline_.processImmediate(st, p, vs, drawGeo_);
        addDraw();
    }

    void blockTransfer(const TransferPacket& t, Memory& mem) override {
        flush();
        if (hw_ && transferOnGpu(t)) {
            ++stats_.transfersGpu;
            ++generation_;
            return;
        }
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
    void forgetGuestMemory() {
        flush();
        presenter_.reset();
        fb_.forgetAll();
        textures_.clear();
        for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
        palettes_.clear();
        ++generation_;
        forgetGlState();  // the state cache may name deleted textures
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
        s.gpuVertexDraws = gpu_.stats().gpu;
        for (u64 c : gpu_.stats().cpu) s.cpuVertexDraws += c;
        for (size_t i = 0; i < size_t(CpuReason::Count) && i < 8; ++i) s.cpuVertexByReason[i] = gpu_.stats().cpu[i];
        s.textureCacheHits = textures_.stats().hits;
        s.readbacks = fb_.readbacks();
        s.cpuTriangles = pipeline_.glTriangles();
        s.cpuTriangleCycles = pipeline_.hostPixels() / 3;  // pixels at 1/3 cycle (hle/ge_time.h)
        s.cpuGeometryBytes = geo_.reservedBytes() + drawGeo_.reservedBytes();
        return s;
    }

    const std::string& lastError() const { return lastError_; }

    int readScaledFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, std::vector<u32>& rgba) {
        flush();
        const int n = scale_;
        const size_t W = size_t(w) * n;
        rgba.assign(W * size_t(h) * n, 0xFF000000u);
        // VRAM first (pixels no target holds), each pixel repeated over its N×N block.
        const u32 bpp = bytesPerPixel(fmt);
        std::vector<u32> row(static_cast<size_t>(w));
        for (int y = 0; y < h; ++y) {
            std::fill(row.begin(), row.end(), 0u);
            const u32 a = addr + u32(y) * stride * bpp;
            const u32 avail = std::min<u32>(mem_.validSize(a, u32(w) * bpp) / bpp, u32(w));
            if (const u8* src = avail ? mem_.ptr(a, avail * bpp) : nullptr)
                convertToRGBA8888(src, fmt, avail, 1, stride, row.data());
            for (int sy = 0; sy < n; ++sy)
                for (int x = 0; x < w; ++x)
                    for (int sx = 0; sx < n; ++sx)
                        rgba[(size_t(y) * n + sy) * W + size_t(x) * n + sx] = row[size_t(x)] | 0xFF000000u;
        }
        const Target* t = fb_.findColor(addr, stride, fmt);
        if (!t) return n;
        // The target's stored pixels are the frame's bytes (16-bit formats bit-replicated, what a
        // read expands to), row 0 first: the same RGBA8888 the VRAM conversion gives.
        std::vector<u32> texels;
        fb_.readScaled(*t, w, h, texels);
        const int tw = std::min(w, int(t->width())) * n, th = std::min(h, t->rowsValid) * n;
        for (int y = 0; y < th; ++y)
            for (int x = 0; x < tw; ++x) rgba[size_t(y) * W + size_t(x)] = texels[size_t(y) * size_t(tw) + size_t(x)] | 0xFF000000u;
        cache_.valid = false;
        return n;
    }

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
        if (!makeSetup(st, flags, s)) return false;
        if (geo_.empty() || std::memcmp(&s, &batchSetup_, sizeof s) != 0) {
            flush();
            std::memcpy(static_cast<void*>(&batchSetup_), &s, sizeof s);
            batchGeneration_ = generation_;
        }
        return true;
    }

    // The setup of a draw (keys, uniforms, targets, scissor, texture made ready). False when the
    // draw cannot produce pixels.
    bool makeSetup(const GeState& st, const shadergen::DrawFlags& flags, Setup& s) {
        std::memset(static_cast<void*>(&s), 0, sizeof s);
        const shadergen::PipelineKeys keys = shadergen::keysFromState(st, flags, caps_, opt_.baseline);
        s.vs = keys.vs;
        s.fs = keys.fs;
        s.ff = keys.ff;
        shadergen::uniformsFromState(st, s.u);
        s.colorAddr = Memory::drawingAddress(st.framebufAddr());
        s.colorStride = st.framebufStride();
        s.colorFormat = st.framebufFormat();
        s.useDepth = (keys.ff.usesDepth || keys.fs.depthRead != shadergen::DepthRead::None) ? 1 : 0;
        if (s.useDepth) {
            s.depthAddr = Memory::drawingAddress(st.depthbufAddr());
            s.depthStride = st.depthbufStride();
        }
        // Scissor ∩ REGION2, inclusive (ge-rules.md §8.6), limited to the buffer width and target size.
        s.scissor[0] = s32(st.SCISSOR1_x());
        s.scissor[1] = s32(st.SCISSOR1_y());
        s.scissor[2] = std::min({s32(st.SCISSOR2_x()), s32(st.REGION2_x()), s32(s.colorStride) - 1, kTargetSize - 1});
        s.scissor[3] = std::min({s32(st.SCISSOR2_y()), s32(st.REGION2_y()), kTargetSize - 1});
        if (s.colorStride == 0 || s.scissor[2] < s.scissor[0] || s.scissor[3] < s.scissor[1]) {
            flush();
            return false;
        }
        if (s.useDepth && s.depthStride == 0) s.useDepth = 0;
        s.u.texScale = 1;
        if (s.fs.tex && hw_ && sampleTarget(st, s)) {
            // Render-to-texture on the GPU: the render target is the texture (no VRAM round trip).
        } else if (s.fs.tex) {
            const int levels = s.fs.texMip ? int(std::min<u32>(st.TMODE_maxlevel(), 7)) + 1 : 1;
            // Render-to-texture: pending draws into the texture's bytes, then the targets' pixels,
            // must be in VRAM before the texture is decoded.
            u32 srcBegin, srcEnd;
            TextureCache::sourceRange(st, levels, srcBegin, srcEnd);
            const u32 lin = Memory::drawingAddress(srcBegin);
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
            // (atlas y, 2^n w, 2^n h, 0): the shader scales coordinates by the unclamped 2^n and
            // addresses the min(2^n, 512) texels placed in the atlas (geometry/texture_size.h).
            for (int l = 0; l < 8; ++l) {
                const int pl = std::min(l, e->levels - 1);
                for (int i = 0; i < 4; ++i) s.u.texLevels[l][i] = e->placement[pl][i];
                s.u.texLevels[l][1] = int(geo::texCoordWidth(st, pl));
                s.u.texLevels[l][2] = int(geo::texCoordHeight(st, pl));
            }
            s.u.texMaxLevel = e->levels - 1;
        }
        return true;
    }

    // Hardware mode: the PRIM draw with its vertex work in the vertex shader (gpu_vertex_path.h);
    // false when it stays on the CPU path.
    bool drawPrimOnGpu(const PrimPacket& p) {
        const GeState& st = *p.state;
        const VertexSettings vs = vertexSettings(st);
        shadergen::DrawFlags flags = shadergen::DrawFlags::fromState(st);
        // The colours reaching the fragments only matter to the reference's skipped alpha test;
        // prepare() keeps the draws where that rule could fire on the CPU.
        flags.vertexAlphaFull = true;
        const bool dstTexture =
            shadergen::keysFromState(st, flags, caps_, opt_.baseline).fs.dstRead == shadergen::DstRead::Texture;
        if (!gpu_.prepare(mem_, st, p, vs.texture, vs.fog, vs.cull, vs.cullCcw, dstTexture, gpuDraw_)) return false;
        // A PRIM type 7 after this one continues from its open vertices (on the CPU path).
        pipeline_.keepOpenVertices(mem_, st, p);
        Setup s;
        if (!makeSetup(st, flags, s)) {
            flush();
            return true;
        }
        flush();  // what the CPU path has batched draws first
        Target* ct = fb_.colorTarget(s.colorAddr, s.colorStride, GeBufferFormat(s.colorFormat), s.scissor[3] + 1);
        if (!ct) return true;
        const bool depthOnColor = s.useDepth && s.depthStride &&
                                  depthOverlapsColor(*ct, s.depthAddr, s.depthStride, s.scissor[3] + 1);
        Target* dt = s.useDepth && !depthOnColor ? fb_.depthTarget(s.depthAddr, s.depthStride, s.scissor[3] + 1)
                                                 : nullptr;
        const u64 compiles = programs_.stats().compiles + programs_.stats().diskHits;
        std::string err;
        const Program* prog = programs_.getHw(gpuDraw_.key, s.fs, &err);
        if (programs_.stats().compiles + programs_.stats().diskHits != compiles) cache_.valid = false, uniformShadow_.clear();
        if (!prog) {
            noteError(err);
            return true;
        }
        fb_.bindDraw(ct, dt);
        if (fb_.clobbers() != seenClobbers_) cache_.valid = false;
        applyState(s, *prog, 0, 0);
        gpu_.draw(gpuDraw_, *prog);
        ++stats_.glDrawCalls;
        // Without CPU geometry the drawn area is bounded by the scissor.
        const Rect drawn{s.scissor[0], s.scissor[1], s.scissor[2], s.scissor[3]};
        const bool colorWrites = s.fs.dstRead != shadergen::DstRead::None || s.ff.colorMask[0] || s.ff.colorMask[1] ||
                                 s.ff.colorMask[2] || s.ff.colorMask[3];
        if (colorWrites) ct->dirty.add(drawn);
        if (dt && s.ff.depthMask) dt->dirty.add(drawn);
        return true;
    }

    // Hardware mode: a block transfer whose source and destination rectangles both lie inside
    // colour render targets of the same format (whole rows of the rectangle within the target's
    // width and valid rows) is a GPU copy at render scale; the destination target holds the result
    // (dirty) until a write-back, so scaled detail survives. Anything else goes through VRAM.
    bool transferOnGpu(const TransferPacket& t) {
        struct Side {
            Target* target;
            int x, y;
        };
        auto locate = [&](u32 base, u32 stride, u32 x, u32 y, Side& out) {
            const u32 begin = Memory::drawingAddress(base + (y * stride + x) * t.bpp);
            Target* tg = fb_.containing(begin);
            if (!tg || tg->stride != stride || tg->bpp() != t.bpp) return false;
            const u32 px = (begin - tg->addr) / t.bpp;
            if ((begin - tg->addr) % t.bpp) return false;
            out = Side{tg, int(px % stride), int(px / stride)};
            return u32(out.x) + t.width <= tg->width() && out.y + int(t.height) <= tg->rowsValid;
        };
        Side src{}, dst{};
        if (!locate(t.src, t.srcStride, t.srcX, t.srcY, src) || !locate(t.dst, t.dstStride, t.dstX, t.dstY, dst))
            return false;
        if (src.target->fmt != dst.target->fmt) return false;  // bytes reinterpreted: through VRAM
        if (src.target == dst.target) {
            const bool overlap = src.x < dst.x + int(t.width) && dst.x < src.x + int(t.width) &&
                                 src.y < dst.y + int(t.height) && dst.y < src.y + int(t.height);
            if (overlap) return false;  // the GE's row order matters; a blit's is undefined
        }
        fb_.copyPixels(*src.target, src.x, src.y, *dst.target, dst.x, dst.y, int(t.width), int(t.height));
        cache_.valid = false;
        return true;
    }

    // Hardware mode: when the texture's level 0 lies in a colour render target whose pixels a
    // texture of its format reads directly (8888 as 8888, a 16-bit buffer as any 16-bit format),
    // the draw samples the target in place at render scale (FsKey::texTarget). CLUT16 over a 16-bit
    // buffer and CLUT32 over an 8888 one (one index per pixel: how games read a buffer's channel
    // through a palette) look the pixel up in a palette texture. Not for mipmaps, CLUT4/8 (several
    // indices per pixel), swizzled textures or the draw's own colour target (a feedback loop):
    // those go through VRAM.
    bool sampleTarget(const GeState& st, Setup& s) {
        const Target* t = fb_.containing(Memory::drawingAddress(st.textureAddr(0)));
        if (!t) return false;
        const u32 tf = st.TPF_format();
        const bool fb32 = t->fmt == GE_FORMAT_8888;
        // Texels per pixel: CLUT4/CLUT8 read a buffer's nibbles/bytes (the texture's buffer width
        // then counts them), CLUT16 over 16-bit and CLUT32 over 8888 one index per pixel.
        u32 perPixel = 0;
        if (tf == GE_TFMT_CLUT4) perPixel = fb32 ? 8 : 4;
        else if (tf == GE_TFMT_CLUT8) perPixel = fb32 ? 4 : 2;
        else if (fb32 ? (tf == GE_TFMT_CLUT32 || tf == GE_TFMT_8888) : (tf <= GE_TFMT_4444 || tf == GE_TFMT_CLUT16))
            perPixel = 1;
        const bool clut = tf >= GE_TFMT_CLUT4 && tf <= GE_TFMT_CLUT32;
        const u32 off = Memory::drawingAddress(st.textureAddr(0)) - t->addr;
        if (!perPixel || s.fs.texMip || st.TMODE_swizzle() || st.textureBufWidth(0) != t->stride * perPixel ||
            off % t->bpp() ||
            (t->addr == s.colorAddr && t->stride == s.colorStride)) {
            ++stats_.rttVram;
            return false;
        }
        // Pending draws into the source target first (the batch may be drawing into it).
        const u32 lin = Memory::drawingAddress(st.textureAddr(0));
        if (!geo_.empty() && batchOverlaps(lin, lin + 1)) flush();
        const u32 px = off / t->bpp();
        s.fs.texTarget = u8(1 + t->fmt);
        s.fs.texFormat = u8(tf);
        shadergen::canonicalize(s.fs);
        s.texture = t->tex;
        s.u.texLevels[0][0] = int(px / t->stride) * scale_;
        s.u.texLevels[0][1] = int(geo::texCoordWidth(st, 0));  // unclamped 2^n (geometry/texture_size.h)
        s.u.texLevels[0][2] = int(geo::texCoordHeight(st, 0));
        s.u.texLevels[0][3] = int(px % t->stride) * scale_;
        s.u.texMaxLevel = 0;
        s.u.texScale = scale_;
        if (clut) {
            s.u.clutShift = s32(st.CLUT_shift());
            s.u.clutMask = s32(st.CLUT_mask());
            s.clutTexture = paletteTexture(st);
        }
        cache_.texture = ~0u;
        ++stats_.rttGpu;
        return true;
    }

    // A 256×1 RGBA8UI texture of the palette per masked index (hle maskedPalette), one per
    // distinct palette; the set is dropped (after drawing what uses it) past 64.
    GLuint paletteTexture(const GeState& st) {
        u32 pal[256];
        maskedPalette(st, 0, pal);
        const u64 h = shadergen::hashBytes(pal, sizeof pal);
        if (auto it = palettes_.find(h); it != palettes_.end()) return it->second;
        if (palettes_.size() >= 64) {
            flush();
            for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
            palettes_.clear();
            cache_.clutTexture = ~0u;
        }
        GLuint tex = 0;
        gl_.GenTextures(1, &tex);
        gl_.BindTexture(GL_TEXTURE_2D, tex);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, 256, 1, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pal);
        palettes_.emplace(h, tex);
        cache_.texture = ~0u;  // unit 0 was used for the upload
        return tex;
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
        GLuint program = ~0u, texture = ~0u, dstColor = ~0u, dstDepth = ~0u, clutTexture = ~0u;
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
            ++stats_.stateChanges;
        }
        if (std::memcmp(cache_.scissor, s.scissor, sizeof s.scissor) != 0) {
            gl_.Scissor(s.scissor[0] * scale_, s.scissor[1] * scale_, (s.scissor[2] - s.scissor[0] + 1) * scale_,
                        (s.scissor[3] - s.scissor[1] + 1) * scale_);
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
        if (s.clutTexture) bindUnit(shadergen::kUnitClut, s.clutTexture, cache_.clutTexture);
        if (s.fs.dstRead == shadergen::DstRead::Texture) bindUnit(shadergen::kUnitDstColor, dstColor, cache_.dstColor);
        if (s.fs.depthRead == shadergen::DepthRead::Texture) bindUnit(shadergen::kUnitDstDepth, dstDepth, cache_.dstDepth);

        // Uniforms are program state: a program whose last values are these needs no upload (a
        // glUniform call makes the driver re-validate the program's constants before the next
        // draw). The shadow is dropped whenever a program is created (an id could come back).
        UniformShadow& shadow = uniformShadow_[prog.id];
        if (shadow.valid && std::memcmp(&shadow.u, &s.u, sizeof s.u) == 0) {
            ++stats_.uniformUploadsSkipped;
            return;
        }
        shadow.u = s.u;
        shadow.valid = true;
        ++stats_.uniformUploads;
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
        if (programs_.stats().compiles + programs_.stats().diskHits != compiles) cache_.valid = false, uniformShadow_.clear();
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
                        const int n = scale_;
                        gl_.BlitFramebuffer(area.x0 * n, area.y0 * n, (area.x1 + 1) * n, (area.y1 + 1) * n, area.x0 * n,
                                            area.y0 * n, (area.x1 + 1) * n, (area.y1 + 1) * n, mask, GL_NEAREST);
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
        const size_t drawnTriangles = geo_.triangles();
        stats_.batchPeak = std::max<u64>(stats_.batchPeak, drawnTriangles);
        geo_.clear();
        geo_.trim(drawnTriangles);
        drawGeo_.trim(drawnTriangles);
    }

    HostGlState hostState_;  // Current contexts: the host's state while ge2gl works (hostEnter)
    Memory& mem_;
    GlOptions opt_;
    const bool hw_;  // GlMode::Hw
    bool gpuVertices_ = false;  // hw mode with GlOptions::vertices resolved to Gpu
    std::unique_ptr<GlContext> ctx_;
    // Destroyed after every member below (they delete GL objects in their destructors) and before
    // the context: the destructor enters the context, this leaves it once they are gone, so a
    // headless context's deletes never land in a host's context current on the thread.
    struct LeaveWhenDestroyed {
        GlContext* ctx = nullptr;
        ~LeaveWhenDestroyed() {
            if (ctx) ctx->leave();
        }
    } leaveGuard_;
    const GlFuncs& gl_;
    shadergen::HostCaps caps_;
    bool useBarrier_ = false;
    ProgramCache programs_;
    TextureCache textures_;
    FramebufferManager fb_;
    const int scale_;
    VertexPipeline pipeline_;
    GpuVertexPath gpu_;
    GpuDraw gpuDraw_;
    u64 batchGeneration_ = 0;
    Geometry geo_;
    Geometry drawGeo_;  // the current draw's geometry, before it joins the batch
    const GeState* drawState_ = nullptr;  // the current draw's state and flags (startDraw)
    shadergen::DrawFlags drawFlags_{};
    Setup batchSetup_;
    StateCache cache_;
    // Per program: the fragment uniforms last uploaded (applyState).
    struct UniformShadow {
        shadergen::FsUniforms u;
        bool valid = false;
    };
    std::unordered_map<GLuint, UniformShadow> uniformShadow_;
    u64 seenClobbers_ = 0;
    u64 generation_ = 1;
    GLuint vao_ = 0, vbo_ = 0;
    std::string probeLabel_;  // GL_CURRENT with KHR_debug: vbo_'s label (currentIsOurs)
    GLuint snapColor_ = 0, snapDepth_ = 0, snapFbo_ = 0;
    std::unique_ptr<Presenter> presenter_;
    int hostDepth_ = 1;
    GLuint recordBuf_ = 0, recordTex_ = 0;
    std::unordered_map<u64, GLuint> palettes_;  // paletteTexture
    GlStats stats_;
    std::string lastError_;
    u64 errors_ = 0;
};

std::unique_ptr<Renderer> createGlRenderer(Memory& mem, const GlOptions& opt, std::string& err) {
    if (opt.scale < 1 || opt.scale > 8) {
        err = "render scale " + std::to_string(opt.scale) + " out of range (1-8)";
        return nullptr;
    }
    if (opt.scale > 1 && opt.mode != GlMode::Hw) {
        err = "render scale above 1 needs the GL hardware mode (exact mode evaluates the PSP's own pixels)";
        return nullptr;
    }
    std::unique_ptr<GlContext> ctx = GlContext::create(opt.context, err, opt.loader);
    if (!ctx) return nullptr;
    // A host's context: what it holds now is what the first hostLeave() gives back.
    HostGlState host;
    if (opt.context == ContextKind::Current) host.save(ctx->f());
    return std::make_unique<GlRenderer>(mem, opt, std::move(ctx), host);
}

GlStats glStats(const Renderer& r) { return static_cast<const GlRenderer&>(r).stats(); }
void glForgetGuestMemory(Renderer& r) { static_cast<GlRenderer&>(r).forgetGuestMemory(); }

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
    line("uniformUploads", s.uniformUploads);
    line("uniformSkipped", s.uniformUploadsSkipped);
    line("shaderCompiles", s.shaderCompiles);
    line("shaderCacheHits", s.shaderCacheHits);
    line("diskCacheHits", s.diskCacheHits);
    line("textureUploads", s.textureUploads);
    line("textureCacheHits", s.textureCacheHits);
    line("readbacks", s.readbacks);
    line("rttGpu", s.rttGpu);
    line("rttVram", s.rttVram);
    line("transfersGpu", s.transfersGpu);
    line("gpuVertexDraws", s.gpuVertexDraws);
    line("cpuVertexDraws", s.cpuVertexDraws);
    line("cpuTriangles", s.cpuTriangles);
    line("cpuTriangleCycles", s.cpuTriangleCycles);
    line("batchPeak", s.batchPeak);
    line("cpuGeometryBytes", s.cpuGeometryBytes);
    for (size_t i = 0; i < size_t(CpuReason::Count) && i < 8; ++i)
        if (s.cpuVertexByReason[i]) {
            char name[64];
            std::snprintf(name, sizeof name, "  cpu: %s", cpuReasonName(CpuReason(i)));
            line(name, s.cpuVertexByReason[i]);
        }
    return out;
}

int glReadScaledFrame(Renderer& r, u32 vramAddr, u32 stride, GeBufferFormat fmt, int w, int h, std::vector<u32>& rgba) {
    return static_cast<GlRenderer&>(r).readScaledFrame(vramAddr, stride, fmt, w, h, rgba);
}

unsigned glPresentFrame(Renderer& r, u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH,
                        std::string& err) {
    return static_cast<GlRenderer&>(r).presentFrame(addr, stride, fmt, w, h, outW, outH, err);
}

int glRenderScale(const Renderer& r) { return static_cast<const GlRenderer&>(r).scale(); }

bool glHostEnter(Renderer& r, std::string& err) { return static_cast<GlRenderer&>(r).hostEnter(err); }
void glHostLeave(Renderer& r) { static_cast<GlRenderer&>(r).hostLeave(); }

}  // namespace ge::gl
