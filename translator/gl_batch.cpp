// SPDX-License-Identifier: MIT
// The GL renderer's batching (gl_renderer_impl.h): a draw's setup, the batch it joins, and the
// batch's GL draw with its destination-read grouping (see gl_renderer.cpp); hardware mode's PRIM
// draws with their vertex work in the vertex shader.
#include <algorithm>
#include <cstring>

#include "geometry/texture_size.h"
#include "translator/gl_renderer_impl.h"

namespace ge::gl {

namespace {

bool overlaps(const PrimBounds& a, const PrimBounds& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

// The end of the group of primitives from `first` on that never touch the same pixel (at most 256,
// a piece of a convex shape joining the previous one): each reads the destination as it was
// before the group, which is exact because no member sees another's write. `area` gets the
// group's bounds clipped to the scissor `sc` (empty: nothing of it is drawn).
size_t groupEnd(const std::vector<PrimBounds>& bounds, size_t first, const Rect& sc, std::vector<size_t>& members,
                Rect& area) {
    members.clear();
    area = Rect{};
    size_t end = first;
    for (; end < bounds.size(); ++end) {
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
        area.add(Rect{std::max(b.x0, sc.x0), std::max(b.y0, sc.y0), std::min(b.x1, sc.x1), std::min(b.y1, sc.y1)});
    }
    return end;
}

// True when the depth buffer rows a draw needs share bytes with colour target t (linear VRAM).
bool depthOverlapsColor(const Target& t, u32 depthAddr, u32 depthStride, int rows) {
    const u64 begin = Memory::drawingAddress(depthAddr);
    const u64 end = begin + u64(std::clamp(rows, 1, kTargetSize)) * depthStride * 2;
    return begin < t.end() && end > t.addr;
}

}  // namespace

// Computes the setup of a draw; flushes the pending batch when it differs. False when the
// draw cannot produce pixels (empty scissor, unusable buffers).
bool GlRendererImpl::beginDraw(const GeState& st, const shadergen::DrawFlags& flags) {
    DrawSetup s;
    if (!makeSetup(st, flags, s)) return false;
    if (geo_.empty() || std::memcmp(&s, &batchSetup_, sizeof s) != 0) {
        flush();
        std::memcpy(static_cast<void*>(&batchSetup_), &s, sizeof s);
        batchGeneration_ = generation_;
    }
    return true;
}

// Keys and fragment uniforms are functions of the registers and the draw's flags alone
// (keysFromState, uniformsFromState; the host caps and baseline switch are fixed): they are made
// again only when a register group changed since (the packets' GeDirty groups, which every draw
// entry point hands to noteDirty first; bone matrices excepted, which neither reads), the flags
// differ or another state object asks. Most draws change only addresses or bones (Monster Hunter
// 3rd: 5,931 of 6,608 draws with no other group dirty), as PPSSPP's dirty flags find.
GlRendererImpl::KeyCache& GlRendererImpl::setupFor(const GeState& st, const shadergen::DrawFlags& flags) {
    constexpr u32 kReads = DIRTY_ALL & ~DIRTY_BONES;
    KeyCache& c = keyCache_;
    if (c.valid && c.state == &st && !(setupDirty_ & kReads) && c.flags == flags) return c;
    c.keys = shadergen::keysFromState(st, flags, caps_, opt_.baseline);
    std::memset(static_cast<void*>(&c.u), 0, sizeof c.u);  // as makeSetup's zeroed DrawSetup had it
    shadergen::uniformsFromState(st, c.u);
    c.flags = flags;
    c.state = &st;
    c.clutHashed = false;
    c.valid = true;
    setupDirty_ = 0;
    return c;
}

// The setup of a draw (keys, uniforms, targets, scissor, texture made ready). False when the
// draw cannot produce pixels.
bool GlRendererImpl::makeSetup(const GeState& st, const shadergen::DrawFlags& flags, DrawSetup& s) {
    std::memset(static_cast<void*>(&s), 0, sizeof s);
    KeyCache& kc = setupFor(st, flags);
    const shadergen::PipelineKeys& keys = kc.keys;
    s.vs = keys.vs;
    s.fs = keys.fs;
    s.ff = keys.ff;
    s.u = kc.u;
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
        if (pending() && batchOverlaps(lin, linEnd)) flush();
        const u64 wb = fb_.writeBacks();
        fb_.syncRange(lin, std::max<u32>(linEnd - lin, 1));
        if (fb_.writeBacks() != wb) ++generation_;
        // A re-upload reuses the GL texture object: draw what is pending with the old contents.
        if (pending() && generation_ != batchGeneration_) flush();
        const bool clut = st.textureFormat() >= GE_TFMT_CLUT4 && st.textureFormat() <= GE_TFMT_CLUT32;
        // The palette changes only with a CLUT load (DIRTY_CLUT), which remakes the key cache.
        if (clut && !kc.clutHashed) kc.clutHash = shadergen::hashBytes(st.clut, sizeof st.clut), kc.clutHashed = true;
        const u64 clutHash = clut ? kc.clutHash : 0;
        const TextureEntry* e = textures_.get(mem_, st, levels, generation_, clutHash);
        state_.textureUnitUsed();  // the cache may have rebound unit 0
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
// What a draw on the GPU vertex path reads of the state (the front end's rules,
// geometry/draw_front_end.cpp): texturing and culling never in clear mode, fog only in transform
// mode; whether the fragment shader reads the destination through a texture.
GlRendererImpl::GpuDrawState GlRendererImpl::gpuDrawState(const GeState& st) {
    GpuDrawState g;
    g.flags = shadergen::DrawFlags::fromState(st, opt_.accuracy);
    // The colours reaching the fragments only matter to the reference's skipped alpha test;
    // GpuVertexPath keeps the draws where that rule could fire on the CPU.
    g.flags.vertexAlphaFull = true;
    g.dstTexture = setupFor(st, g.flags).keys.fs.dstRead == shadergen::DstRead::Texture;
    g.texture = st.TME_on() && !st.isClearMode();
    g.fog = st.FGE_on() && !st.isThrough();
    g.cull = st.BCE_on() && !st.isClearMode();
    return g;
}

bool GlRendererImpl::drawPrimOnGpu(const PrimPacket& p) {
    const GeState& st = *p.state;
    const GpuDrawState g = gpuDrawState(st);
    if (!gpu_.prepare(mem_, st, p, g.texture, g.fog, g.cull, g.dstTexture, gpuDraw_)) return false;
    // A PRIM type 7 after this one continues from its open vertices (on the CPU path).
    pipeline_.keepOpenVertices(mem_, st, p);
    submitGpuDraw(st, g.flags);
    return true;
}

// Tessellated on the CPU as the CPU path does (geo::tessellatePatch), transformed and lit on
// the GPU; culled as there when wholly beyond a side of the clip rectangle (the front end's
// test). A patch the tessellator refuses goes to the CPU path, which reports it.
bool GlRendererImpl::drawPatchOnGpu(const PatchPacket& p) {
    const GeState& st = *p.state;
    const GpuDrawState g = gpuDrawState(st);
    if (!gpu_.acceptPatch(st, p, g.texture, g.dstTexture)) return false;
    if (!geo::tessellatePatch(mem_, st, p, opt_.accuracy, tess_, nullptr, pipeline_.patchOffClipTest(mem_, st, p)))
        return false;
    pipeline_.endOpenPrim();
    if (!tess_.verts.empty()) {
        // The tessellator generates normals when lighting needs them (geo::DrawFrontEnd::patch).
        const VertexReader probe(mem_, st, p.vtype);
        if (!gpu_.preparePatch(st, tess_, probe.hasColor(), probe.hasNormal() || st.LTE_on(), g.texture, g.fog,
                               gpuDraw_))
            return false;
        submitGpuDraw(st, g.flags);
    }
    // A patch's tessellation can be far larger than any PRIM: not kept past it.
    constexpr size_t kKeep = size_t(1) << 17;
    if (tess_.verts.capacity() > kKeep) tess_ = geo::TessOutput{};
    return true;
}

// Queues gpuDraw_ (prepared by GpuVertexPath) with the draw's fragment state: joined to the
// waiting GPU draws when the setup (fragment state, targets, texture) and the vertex key and
// uniforms are the same (GpuVertexPath::joinable), else after drawing what waits. Consecutive
// draws of one object differ mostly in their vertex addresses (--stats glDrawCalls).
void GlRendererImpl::submitGpuDraw(const GeState& st, const shadergen::DrawFlags& flags) {
    DrawSetup s;
    if (!makeSetup(st, flags, s)) {
        flush();
        return;
    }
    if (gpuBatch_.draws != 0 && std::memcmp(&s, &batchSetup_, sizeof s) == 0 &&
        GpuVertexPath::joinable(gpuBatch_, gpuDraw_)) {
        GpuVertexPath::join(gpuBatch_, gpuDraw_);
        return;
    }
    flush();  // what waits (CPU triangles or GPU draws) draws first
    std::memcpy(static_cast<void*>(&batchSetup_), &s, sizeof s);
    batchGeneration_ = generation_;
    std::swap(gpuBatch_, gpuDraw_);  // gpuDraw_ keeps the old batch's capacity for the next draw
}

// Draws the waiting GPU draws as one GL draw.
void GlRendererImpl::flushGpu() {
    const DrawSetup& s = batchSetup_;
    gpuBatch_.draws = 0;
    Target* ct = fb_.colorTarget(s.colorAddr, s.colorStride, GeBufferFormat(s.colorFormat), s.scissor[3] + 1);
    if (!ct) return;
    const bool depthOnColor = s.useDepth && s.depthStride &&
                              depthOverlapsColor(*ct, s.depthAddr, s.depthStride, s.scissor[3] + 1);
    Target* dt = s.useDepth && !depthOnColor ? fb_.depthTarget(s.depthAddr, s.depthStride, s.scissor[3] + 1)
                                             : nullptr;
    const u64 compiles = programs_.stats().compiles + programs_.stats().diskHits;
    std::string err;
    const Program* prog = programs_.getHw(gpuBatch_.key, s.fs, &err);
    if (programs_.stats().compiles + programs_.stats().diskHits != compiles) state_.programsCreated();
    if (!prog) {
        noteError(err);
        return;
    }
    fb_.bindDraw(ct, dt);
    state_.apply(s, *prog, 0, 0);
    if (gpu_.draw(gpuBatch_, *prog)) ++stats_.glDrawCalls;
    // Without CPU geometry the drawn area is bounded by the scissor.
    const Rect drawn{s.scissor[0], s.scissor[1], s.scissor[2], s.scissor[3]};
    const bool colorWrites = s.fs.dstRead != shadergen::DstRead::None || s.ff.colorMask[0] || s.ff.colorMask[1] ||
                             s.ff.colorMask[2] || s.ff.colorMask[3];
    if (colorWrites) ct->dirty.add(drawn);
    if (dt && s.ff.depthMask) dt->dirty.add(drawn);
}

bool GlRendererImpl::batchOverlaps(u32 begin, u32 end) const {
    const DrawSetup& s = batchSetup_;
    const u32 bpp = s.colorFormat == GE_FORMAT_8888 ? 4 : 2;
    const u32 cEnd = s.colorAddr + u32(s.scissor[3] + 1) * s.colorStride * bpp;
    if (s.colorAddr < end && cEnd > begin) return true;
    if (s.useDepth) {
        const u32 dEnd = s.depthAddr + u32(s.scissor[3] + 1) * s.depthStride * 2;
        if (s.depthAddr < end && dEnd > begin) return true;
    }
    return false;
}

void GlRendererImpl::flush() {
    if (gpuBatch_.draws != 0) flushGpu();
    if (geo_.empty()) return;
    const DrawSetup& s = batchSetup_;
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
    if (programs_.stats().compiles + programs_.stats().diskHits != compiles) state_.programsCreated();
    if (!prog) {
        noteError(err);
        geo_.clear();
        return;
    }
    fb_.bindDraw(ct, dt);
    const bool dstTex = s.fs.dstRead == shadergen::DstRead::Texture;
    GLuint dstColor = 0, dstDepth = 0;
    if (dstTex) {
        dstColor = useBarrier_ ? ct->tex : snapColor_;
        dstDepth = useBarrier_ ? (dt ? dt->tex : 0) : snapDepth_;
    }
    state_.apply(s, *prog, dstColor, dstDepth);

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
        if (!geo_.gradients.empty()) {
            gl_.BindBuffer(GL_TEXTURE_BUFFER, gradientBuf_);
            gl_.BufferData(GL_TEXTURE_BUFFER, GLsizeiptr(geo_.gradients.size() * sizeof(GradientRecord)),
                           geo_.gradients.data(), GL_STREAM_DRAW);
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + shadergen::kUnitGradients));
            gl_.BindTexture(GL_TEXTURE_BUFFER, gradientTex_);
        }
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
        // Groups of primitives that never touch the same pixel (groupEnd).
        const size_t n = bounds.size();
        size_t first = 0;
        std::vector<size_t> members;
        while (first < n) {
            Rect area;
            const size_t end = groupEnd(bounds, first, sc, members, area);
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

}  // namespace ge::gl
