// SPDX-License-Identifier: MIT
// The GL renderer: consumes the engine's packets, keeps VRAM exact (see gl_renderer.h). This file:
// construction, the draw entry points and stats; the other parts are listed in gl_renderer_impl.h.
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
#include "translator/gl_renderer_impl.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace ge::gl {

namespace {

// The host's bindings of every unit the translator uses are kept (gl_host_state.h).
static_assert(shadergen::kUnitGradients < kHostUnits && shadergen::kUnitClut < kHostUnits &&
              shadergen::kUnitVertexBytes < kHostUnits && shadergen::kUnitRingIds < kHostUnits);

shadergen::HostCaps hostCapsFor(const GlCaps& caps, const GlOptions& opt) {
    // Hardware mode rasterises natively: attributes interpolated by GL (the float path).
    shadergen::HostCaps c = caps.hostCaps(opt.baseline, opt.floatInterpolation || opt.mode == GlMode::Hw);
    if (opt.disableFramebufferFetch) c.fbFetch = c.depthFetch = 0;
    return c;
}

}  // namespace

GlRendererImpl::GlRendererImpl(Memory& mem, const GlOptions& opt, std::unique_ptr<GlContext> ctx,
                               const HostGlState& hostState)
    : hostState_(hostState), mem_(mem), opt_(opt), hw_(opt.mode == GlMode::Hw), ctx_(std::move(ctx)), gl_(ctx_->f()),
      caps_(hostCapsFor(ctx_->caps(), opt)),
      useBarrier_(!opt.baseline && ctx_->caps().textureBarrier),
      programs_(*ctx_, caps_, opt.shaderDumpDir, opt.programCacheDir), textures_(*ctx_),
      fb_(*ctx_, mem, opt.scale), scale_(fb_.scale()), gpu_(*ctx_, opt.accuracy), state_(gl_, fb_, scale_) {
    if (hw_) {
        const std::string& r = ctx_->caps().renderer;
        const bool software = r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
                              r.find("SwiftShader") != std::string::npos;
        gpuVertices_ = opt.vertices == GlOptions::Vertices::Gpu ||
                       (opt.vertices == GlOptions::Vertices::Auto && !software);
    }
    std::memset(static_cast<void*>(&batchSetup_), 0, sizeof batchSetup_);
    pipeline_.setOutputLimit(kBatchTriangles, &GlRendererImpl::drawOutputFull, this);
    pipeline_.setRecords(caps_.exactInterp != 0);
    gl_.GenVertexArrays(1, &vao_);
    gl_.GenBuffers(1, &vbo_);
    gl_.BindVertexArray(vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    state_.useVertexArray(vao_, vbo_);
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
        // The gradient planes of the records that have them likewise, on a unit of their own.
        auto bufferTexture = [&](GLuint& buf, GLuint& tex, GLsizeiptr size, int unit) {
            gl_.GenBuffers(1, &buf);
            gl_.BindBuffer(GL_TEXTURE_BUFFER, buf);
            gl_.BufferData(GL_TEXTURE_BUFFER, size, nullptr, GL_STREAM_DRAW);
            gl_.GenTextures(1, &tex);
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
            gl_.BindTexture(GL_TEXTURE_BUFFER, tex);
            gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32UI, buf);
        };
        bufferTexture(recordBuf_, recordTex_, sizeof(TriRecord), shadergen::kUnitTris);
        bufferTexture(gradientBuf_, gradientTex_, sizeof(GradientRecord), shadergen::kUnitGradients);
        gl_.ActiveTexture(GL_TEXTURE0);
    }
}

GlRendererImpl::~GlRendererImpl() {
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
    if (gradientTex_) gl_.DeleteTextures(1, &gradientTex_);
    if (gradientBuf_) gl_.DeleteBuffers(1, &gradientBuf_);
    if (snapColor_) gl_.DeleteTextures(1, &snapColor_);
    if (snapDepth_) gl_.DeleteTextures(1, &snapDepth_);
    if (snapFbo_) gl_.DeleteFramebuffers(1, &snapFbo_);
    for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
    leaveGuard_.ctx = ctx_.get();  // after the members' own deletes
}

// Geometry is built before the draw's setup: the setup depends on the primitives' colours
// (the reference's skipped alpha test, geometry/reference_rules.h referenceSkipsAlphaTest).
void GlRendererImpl::drawPrim(const PrimPacket& p) {
    noteDirty(p.dirty);
    ++stats_.draws;
    if (gpuVertices_ && drawPrimOnGpu(p)) return;
    const GeState& st = *p.state;
    std::string err;
    startDraw(st, shadergen::DrawFlags::fromState(st, opt_.accuracy));
    if (!pipeline_.processPrim(mem_, st, p, drawGeo_, &err)) noteError(err);
    addDraw();
}

void GlRendererImpl::drawPatch(const PatchPacket& p) {
    noteDirty(p.dirty);
    ++stats_.draws;
    if (gpuVertices_ && drawPatchOnGpu(p)) return;
    const GeState& st = *p.state;
    std::string err;
    startDraw(st, shadergen::DrawFlags::fromState(st, opt_.accuracy));
    if (!pipeline_.processPatch(mem_, st, p, drawGeo_, &err)) noteError(err);
    addDraw();
}

// The draw whose geometry the pipeline builds next (addDraw hands it to the batch).
void GlRendererImpl::startDraw(const GeState& st, const shadergen::DrawFlags& flags) {
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
void GlRendererImpl::addDraw() {
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

void GlRendererImpl::drawImmediate(const ImmPacket& p) {
    noteDirty(p.dirty);
    ++stats_.draws;
    if (p.vertices.empty()) return;
    const GeState& st = *p.state;
    // AP2 flag bits 11..23 of the first vertex override the state for this primitive (docs/ge-rules.md §3.12).
    const u32 f = p.flags;
    shadergen::DrawFlags df = shadergen::DrawFlags::fromState(st, opt_.accuracy);
    df.gouraud = (f >> 18) & 1;
    df.texture = (f >> 21) & 1;
    df.fog = (f >> 22) & 1;
    df.dither = (f >> 23) & 1;
    startDraw(st, df);
    pipeline_.processImmediate(st, p, drawGeo_);  // the geometry's own overrides: geo::immediateState
    addDraw();
}

void GlRendererImpl::syncMemoryForRead(u32 addr, u32 size) {
    flush();
    fb_.syncRange(addr, size);
}

void GlRendererImpl::memoryWritten(u32 addr, u32 size) {
    flush();
    fb_.memoryWritten(addr, size);
    // Only the textures whose bytes were written are re-hashed: a replay writes every display
    // list block and vertex payload through here, and a generation change would re-hash every
    // cached texture at its next use. (The batch is empty after the flush, so no pending draw
    // uses a texture that is rebuilt.)
    if (size) textures_.invalidate(addr, size);
    else ++generation_;
}

void GlRendererImpl::flushToMemory() {
    flush();
    fb_.flushAll();
    gl_.Finish();
}

void GlRendererImpl::noteError(const std::string& e) {
    if (lastError_.empty()) lastError_ = e;
    ++errors_;
}

GlStats GlRendererImpl::stats() const {
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
    s.culledPatches = pipeline_.frontEndStats().culledPatches;
    s.cpuTriangleCycles = pipeline_.hostPixels() / 3;  // pixels at 1/3 cycle (hle/ge_time.h)
    s.cpuGeometryBytes = geo_.reservedBytes() + drawGeo_.reservedBytes();
    s.stateChanges = state_.counters().stateChanges;
    s.uniformUploads = state_.counters().uniformUploads;
    s.uniformUploadsSkipped = state_.counters().uniformUploadsSkipped;
    return s;
}

std::unique_ptr<GlRenderer> createGlRenderer(Memory& mem, const GlOptions& opt, std::string& err) {
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
    return std::make_unique<GlRendererImpl>(mem, opt, std::move(ctx), host);
}

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
    line("culledPatches", s.culledPatches);
    for (size_t i = 0; i < size_t(CpuReason::Count) && i < 8; ++i)
        if (s.cpuVertexByReason[i]) {
            char name[64];
            std::snprintf(name, sizeof name, "  cpu: %s", cpuReasonName(CpuReason(i)));
            line(name, s.cpuVertexByReason[i]);
        }
    return out;
}

}  // namespace ge::gl
