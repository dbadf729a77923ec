// SPDX-License-Identifier: MIT
// Render targets as caches of VRAM (see framebuffer_manager.h).
#include "translator/framebuffer_manager.h"

#include <algorithm>
#include <cstring>

#include "hle/pixel_format.h"
#include "shadergen/shader_keys.h"
#include "translator/gl_util.h"

namespace ge::gl {

namespace {
constexpr u32 kVramEnd = Memory::kVramBase + Memory::kVramSize;

const char* const kDepthVs =
    "#version 330 core\n"
    "void main() {\n"
    "  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
    "  gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";
// Depth as u16 in VRAM → z/65536 in the D32F target (exact); each staged PSP pixel covers its
// N×N texels at render scale N.
const char* const kDepthFs =
    "#version 330 core\n"
    "uniform usampler2D u_stage;\n"
    "uniform int u_scale;\n"
    "void main() {\n"
    "  gl_FragDepth = float(texelFetch(u_stage, ivec2(gl_FragCoord.xy) / u_scale, 0).r) * (1.0 / 65536.0);\n"
    "}\n";
// Write-back at render scale N: the mean of a PSP pixel's N×N texels, rounded, per channel (the
// box filter `ge2gl compare` also uses on scaled frames). Depth likewise, as a float.
const char* const kDownColorFs =
    "#version 330 core\n"
    "uniform usampler2D u_src;\n"
    "uniform int u_scale;\n"
    "out uvec4 o_color;\n"
    "void main() {\n"
    "  ivec2 base = ivec2(gl_FragCoord.xy) * u_scale;\n"
    "  uvec4 sum = uvec4(0u);\n"
    "  for (int j = 0; j < u_scale; ++j)\n"
    "    for (int i = 0; i < u_scale; ++i) sum += texelFetch(u_src, base + ivec2(i, j), 0);\n"
    "  uint n = uint(u_scale * u_scale);\n"
    "  o_color = (sum + uvec4(n / 2u)) / n;\n"
    "}\n";
const char* const kDownDepthFs =
    "#version 330 core\n"
    "uniform sampler2D u_src;\n"
    "uniform int u_scale;\n"
    "out float o_depth;\n"
    "void main() {\n"
    "  ivec2 base = ivec2(gl_FragCoord.xy) * u_scale;\n"
    "  float sum = 0.0;\n"
    "  for (int j = 0; j < u_scale; ++j)\n"
    "    for (int i = 0; i < u_scale; ++i) sum += texelFetch(u_src, base + ivec2(i, j), 0).r;\n"
    "  o_depth = sum / float(u_scale * u_scale);\n"
    "}\n";

}  // namespace

FramebufferManager::FramebufferManager(const GlContext& ctx, Memory& mem, int scale)
    : ctx_(ctx), mem_(mem), scale_(std::clamp(scale, 1, 8)) {
    const GlFuncs& gl = ctx_.f();
    gl.GenFramebuffers(1, &drawFbo_);
    gl.GenFramebuffers(1, &readFbo_);
    gl.GenFramebuffers(1, &utilFbo_);
    gl.GenVertexArrays(1, &emptyVao_);
}

FramebufferManager::~FramebufferManager() {
    const GlFuncs& gl = ctx_.f();
    for (auto& t : targets_) gl.DeleteTextures(1, &t->tex);
    for (const SpareTexture& s : spare_) gl.DeleteTextures(1, &s.tex);
    gl.DeleteFramebuffers(1, &drawFbo_);
    gl.DeleteFramebuffers(1, &readFbo_);
    gl.DeleteFramebuffers(1, &utilFbo_);
    if (depthProg_) gl.DeleteProgram(depthProg_);
    if (depthStage_) gl.DeleteTextures(1, &depthStage_);
    for (GLuint p : {downColorProg_, downDepthProg_})
        if (p) gl.DeleteProgram(p);
    for (GLuint t : {colorStage_, downColor_, downDepth_})
        if (t) gl.DeleteTextures(1, &t);
    gl.DeleteVertexArrays(1, &emptyVao_);
}

Target* FramebufferManager::find(bool depth, u32 addr, u32 stride, GeBufferFormat fmt) {
    for (auto& t : targets_)
        if (t->depth == depth && t->addr == addr && t->stride == stride && (depth || t->fmt == fmt)) return t.get();
    return nullptr;
}

GLuint FramebufferManager::allocTexture(bool depth, int w, int h) {
    const GlFuncs& gl = ctx_.f();
    for (size_t i = 0; i < spare_.size(); ++i) {
        if (spare_[i].depth == depth && spare_[i].w == w && spare_[i].h == h) {
            const GLuint tex = spare_[i].tex;
            spare_.erase(spare_.begin() + std::ptrdiff_t(i));
            // Zeroed as Mesa's new textures are, so that reuse changes nothing a renderer can see.
            const GLenum attach = depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0;
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, utilFbo_);
            gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, attach, GL_TEXTURE_2D, tex, 0);
            gl.Disable(GL_SCISSOR_TEST);
            if (depth) {
                const GLfloat zero = 0;
                gl.DepthMask(GL_TRUE);
                gl.ClearBufferfv(GL_DEPTH, 0, &zero);
            } else {
                const GLuint zero[4] = {0, 0, 0, 0};
                gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                gl.ClearBufferuiv(GL_COLOR, 0, zero);
            }
            gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, attach, GL_TEXTURE_2D, 0, 0);
            ++clobbers_;  // masks, scissor and the framebuffer binding changed
            return tex;
        }
    }
    GLuint tex = 0;
    gl.GenTextures(1, &tex);
    nearestTexture(gl, tex);
    if (depth)
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, w, h, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    else
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, w, h, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, nullptr);
    return tex;
}

Target* FramebufferManager::create(bool depth, u32 addr, u32 stride, GeBufferFormat fmt) {
    auto t = std::make_unique<Target>();
    t->depth = depth;
    t->addr = addr;
    t->stride = stride;
    t->fmt = fmt;
    t->allocRows = kTargetSize / 2;
    t->tex = allocTexture(depth, t->texCols() * scale_, t->allocRows * scale_);
    targets_.push_back(std::move(t));
    return targets_.back().get();
}

void FramebufferManager::grow(Target& t, int rows) {
    if (rows <= t.allocRows) return;
    const GlFuncs& gl = ctx_.f();
    const int newRows = kTargetSize;
    GLuint tex = allocTexture(t.depth, t.texCols() * scale_, newRows * scale_);
    // Copy the texels held so far (rows are PSP pixels; the copy is texel for texel).
    const GLenum attach = t.depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, attach, GL_TEXTURE_2D, t.tex, 0);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, attach, GL_TEXTURE_2D, tex, 0);
    const GLenum buf = t.depth ? GL_NONE : GL_COLOR_ATTACHMENT0;
    gl.ReadBuffer(buf);
    gl.DrawBuffer(buf);
    gl.Disable(GL_SCISSOR_TEST);
    const int w = t.texCols() * scale_, h = t.allocRows * scale_;
    gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, t.depth ? GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, attach, GL_TEXTURE_2D, 0, 0);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, attach, GL_TEXTURE_2D, 0, 0);
    if (boundColor_ == t.tex || boundDepth_ == t.tex) boundColor_ = 0, boundDepth_ = ~0u;
    gl.DeleteTextures(1, &t.tex);
    t.tex = tex;
    t.allocRows = newRows;
    ++clobbers_;
}

void FramebufferManager::copyPixels(const Target& src, int sx, int sy, Target& dst, int dx, int dy, int w, int h) {
    const GlFuncs& gl = ctx_.f();
    const int n = scale_;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, src.tex, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, dst.tex, 0);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
    gl.Disable(GL_SCISSOR_TEST);
    gl.BlitFramebuffer(sx * n, sy * n, (sx + w) * n, (sy + h) * n, dx * n, dy * n, (dx + w) * n, (dy + h) * n,
                       GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    dst.dirty.add(Rect{dx, dy, dx + w - 1, dy + h - 1});
    ++clobbers_;
}

Target* FramebufferManager::containing(u32 linearAddr) {
    verifySuspects();
    for (const auto& t : targets_)
        if (!t->depth && t->rowsValid > 0 && linearAddr >= t->addr && linearAddr < t->end()) return t.get();
    return nullptr;
}

const Target* FramebufferManager::findColor(u32 addr, u32 stride, GeBufferFormat fmt) {
    verifySuspects();
    addr = Memory::drawingAddress(addr);
    for (const auto& t : targets_)
        if (!t->depth && t->addr == addr && t->stride == stride && t->fmt == fmt && t->rowsValid > 0) return t.get();
    return nullptr;
}

void FramebufferManager::readScaled(const Target& t, int w, int h, std::vector<u32>& out) {
    w = std::min(w, int(t.width()));
    h = std::min(h, t.rowsValid);
    if (w <= 0 || h <= 0) return;
    const GlFuncs& gl = ctx_.f();
    const size_t W = size_t(w) * scale_, H = size_t(h) * scale_;
    out.resize(std::max(out.size(), W * H));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.tex, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.ReadPixels(0, 0, GLsizei(W), GLsizei(H), GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, out.data());
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    ++readbacks_;
}

void FramebufferManager::destroy(Target* t) {
    const GlFuncs& gl = ctx_.f();
    if (boundColor_ == t->tex || boundDepth_ == t->tex) boundColor_ = 0, boundDepth_ = ~0u;  // force re-attach
    gl.DeleteTextures(1, &t->tex);
    ++clobbers_;  // the renderer may hold this texture name bound as a destination copy
    targets_.erase(std::remove_if(targets_.begin(), targets_.end(), [t](const auto& p) { return p.get() == t; }),
                   targets_.end());
}

Target* FramebufferManager::colorTarget(u32 addr, u32 stride, GeBufferFormat fmt, int rows) {
    if (stride == 0) return nullptr;
    verifySuspects();
    addr = Memory::drawingAddress(addr);
    Target* t = find(false, addr, stride, fmt);
    if (!t) t = create(false, addr, stride, fmt);
    ensureRows(*t, rows);
    return t;
}

Target* FramebufferManager::depthTarget(u32 addr, u32 stride, int rows) {
    if (stride == 0) return nullptr;
    verifySuspects();
    addr = Memory::drawingAddress(addr);
    Target* t = find(true, addr, stride, GE_FORMAT_565);
    if (!t) t = create(true, addr, stride, GE_FORMAT_565);
    ensureRows(*t, rows);
    return t;
}

void FramebufferManager::ensureRows(Target& t, int rows) {
    rows = std::clamp(rows, 1, kTargetSize);
    // Rows starting beyond VRAM cannot hold anything.
    const u32 pitch = t.stride * t.bpp();
    const int maxRows = int((kVramEnd - t.addr + pitch - 1) / pitch);
    rows = std::min(rows, maxRows);
    if (rows <= t.rowsValid) return;
    const u32 begin = t.end();
    const u32 end = t.addr + u32(rows) * pitch;
    claim(begin, end, &t);
    grow(t, rows);
    const int y0 = t.rowsValid;
    t.rowsValid = rows;
    uploadRows(t, y0, rows);
}

void FramebufferManager::claim(u32 begin, u32 end, const Target* owner) {
    for (size_t i = 0; i < targets_.size();) {
        Target* o = targets_[i].get();
        if (o == owner || o->rowsValid == 0 || o->end() <= begin || o->addr >= end) {
            ++i;
            continue;
        }
        writeBack(*o);
        if (o->addr >= begin) {
            destroy(o);  // erases index i
            continue;
        }
        o->rowsValid = int((begin - o->addr) / (o->stride * o->bpp()));
        if (o->rowsValid == 0) {
            destroy(o);
            continue;
        }
        o->dirty.y1 = std::min(o->dirty.y1, o->rowsValid - 1);
        ++i;
    }
}

void FramebufferManager::uploadRows(Target& t, int y0, int y1) {
    if (y1 > y0) uploadRect(t, 0, y0, int(t.width()), y1 - y0);
}

void FramebufferManager::uploadRect(Target& t, int x0, int y0, int w, int h) {
    if (w <= 0 || h <= 0) return;
    const GlFuncs& gl = ctx_.f();
    const u32 bpp = t.bpp();
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    if (!t.depth) {
        pixels_.assign(size_t(w) * size_t(h), 0);
        for (int y = 0; y < h; ++y) {
            const u32 rowAddr = t.addr + (u32(y0 + y) * t.stride + u32(x0)) * bpp;
            const u32 avail = mem_.validSize(rowAddr, u32(w) * bpp) / bpp;
            const u8* src = mem_.ptr(rowAddr, std::max<u32>(avail * bpp, 1));
            if (!src || avail == 0) continue;
            // Stored form = what a GE read expands to (bit replication, docs/ge-rules.md §8.8).
            convertToRGBA8888(src, t.fmt, avail, 1, 0, &pixels_[size_t(y) * size_t(w)]);
        }
        if (scale_ == 1) {
            gl.BindTexture(GL_TEXTURE_2D, t.tex);
            gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
        } else {
            uploadColor(t, x0, y0, w, h);
        }
        return;
    }
    // Depth: the u16 values, held by the D32F target as z / 65536 (exact in float: what kDepthFs
    // writes as gl_FragDepth).
    depth16_.assign(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        const u32 rowAddr = t.addr + (u32(y0 + y) * t.stride + u32(x0)) * 2;
        const u32 avail = mem_.validSize(rowAddr, u32(w) * 2) / 2;
        const u8* src = mem_.ptr(rowAddr, std::max<u32>(avail * 2, 1));
        if (!src || avail == 0) continue;
        for (u32 x = 0; x < avail; ++x) depth16_[size_t(y) * size_t(w) + x] = readLE16(src + 2 * x);
    }
    if (scale_ == 1) {
        // At 1x the values go straight into the depth texture (desktop GL takes DEPTH_COMPONENT
        // data there), so no program draws them and none is compiled for it (llvmpipe's JIT:
        // hot pixel's whole GL hw render went from 0.19 to 0.18 s).
        depthF_.resize(depth16_.size());
        for (size_t i = 0; i < depth16_.size(); ++i) depthF_[i] = float(depth16_[i]) * (1.0f / 65536.0f);
        gl.BindTexture(GL_TEXTURE_2D, t.tex);
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depthF_.data());
        ++clobbers_;
        return;
    }
    // At N× the staged values are stretched onto the target as gl_FragDepth.
    if (!depthProg_ && !buildDepthProgram()) return;
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.BindTexture(GL_TEXTURE_2D, depthStage_);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_RED_INTEGER, GL_UNSIGNED_SHORT, depth16_.data());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.BindFramebuffer(GL_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.tex, 0);
    gl.DrawBuffer(GL_NONE);
    gl.ReadBuffer(GL_NONE);
    gl.Viewport(0, 0, kTargetSize * scale_, kTargetSize * scale_);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(x0 * scale_, y0 * scale_, w * scale_, h * scale_);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_ALWAYS);
    gl.DepthMask(GL_TRUE);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.UseProgram(depthProg_);
    gl.Uniform1i(depthScaleLoc_, scale_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, depthStage_);
    gl.BindVertexArray(emptyVao_);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    ++clobbers_;
}

bool FramebufferManager::buildDepthProgram() {
    const GlFuncs& gl = ctx_.f();
    depthProg_ = linkProgram(gl, kDepthVs, kDepthFs);
    if (!depthProg_) return false;
    depthScaleLoc_ = gl.GetUniformLocation(depthProg_, "u_scale");
    gl.UseProgram(depthProg_);
    gl.Uniform1i(gl.GetUniformLocation(depthProg_, "u_stage"), 0);
    gl.GenTextures(1, &depthStage_);
    nearestTexture(gl, depthStage_);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R16UI, kTargetSize, kTargetSize, 0, GL_RED_INTEGER, GL_UNSIGNED_SHORT, nullptr);
    ++clobbers_;
    return true;
}

// Scale > 1: the pixels go to a 1× staging texture and are stretched onto the target (nearest:
// each PSP pixel fills its N×N texels).
void FramebufferManager::uploadColor(Target& t, int x0, int y0, int w, int h) {
    const GlFuncs& gl = ctx_.f();
    if (!colorStage_) colorStage_ = allocTexture(false, kTargetSize, kTargetSize);
    gl.BindTexture(GL_TEXTURE_2D, colorStage_);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorStage_, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.tex, 0);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
    gl.Disable(GL_SCISSOR_TEST);
    const int n = scale_;
    gl.BlitFramebuffer(x0, y0, x0 + w, y0 + h, x0 * n, y0 * n, (x0 + w) * n, (y0 + h) * n, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    ++clobbers_;
}

bool FramebufferManager::buildDownsamplePrograms() {
    const GlFuncs& gl = ctx_.f();
    downColorProg_ = linkProgram(gl, kDepthVs, kDownColorFs);
    downDepthProg_ = linkProgram(gl, kDepthVs, kDownDepthFs);
    if (!downColorProg_ || !downDepthProg_) return false;
    downColor_ = allocTexture(false, kTargetSize, kTargetSize);
    gl.GenTextures(1, &downDepth_);
    nearestTexture(gl, downDepth_);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, kTargetSize, kTargetSize, 0, GL_RED, GL_FLOAT, nullptr);
    ++clobbers_;
    return true;
}

// Box average of r (PSP pixels) of t into the 1× scratch texture (downColor_ or downDepth_),
// left attached to readFbo_ for ReadPixels.
void FramebufferManager::downsample(const Target& t, const Rect& r) {
    const GlFuncs& gl = ctx_.f();
    const GLuint prog = t.depth ? downDepthProg_ : downColorProg_;
    const GLuint dst = t.depth ? downDepth_ : downColor_;
    gl.BindFramebuffer(GL_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, dst, 0);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
    gl.Viewport(0, 0, kTargetSize, kTargetSize);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(r.x0, r.y0, r.x1 - r.x0 + 1, r.y1 - r.y0 + 1);
    gl.Disable(GL_DEPTH_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.UseProgram(prog);
    gl.Uniform1i(gl.GetUniformLocation(prog, "u_src"), 0);
    gl.Uniform1i(gl.GetUniformLocation(prog, "u_scale"), scale_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, t.tex);
    gl.BindVertexArray(emptyVao_);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, dst, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    ++clobbers_;
}

void FramebufferManager::uploadSpan(Target& t, u32 begin, u32 end) {
    const u32 pitch = t.stride * t.bpp();
    begin = std::max(begin, t.addr);
    end = std::min(end, t.end());
    if (begin >= end) return;
    const int yA = int((begin - t.addr) / pitch), yB = int((end - 1 - t.addr) / pitch);
    const int w = int(t.width());
    auto rowSpan = [&](int y, int& x0, int& x1) {
        const u32 rs = t.addr + u32(y) * pitch;
        const u32 b = std::max(begin, rs), e = std::min(end, rs + pitch);
        x0 = int((b - rs) / t.bpp());
        x1 = std::min(w, int((e - rs + t.bpp() - 1) / t.bpp()));
    };
    int y = yA;
    while (y <= yB) {
        int x0, x1;
        rowSpan(y, x0, x1);
        if (x0 == 0 && x1 == w) {
            int y2 = y;
            while (y2 + 1 <= yB) {
                int a, b;
                rowSpan(y2 + 1, a, b);
                if (a != 0 || b != w) break;
                ++y2;
            }
            uploadRect(t, 0, y, w, y2 - y + 1);
            y = y2 + 1;
        } else {
            uploadRect(t, x0, y, x1 - x0, 1);
            ++y;
        }
    }
}

void FramebufferManager::bindDraw(Target* color, Target* depth) {
    const GlFuncs& gl = ctx_.f();
    gl.BindFramebuffer(GL_FRAMEBUFFER, drawFbo_);
    const GLuint c = color ? color->tex : 0, d = depth ? depth->tex : 0;
    if (c != boundColor_) {
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c, 0);
        boundColor_ = c;
    }
    if (d != boundDepth_) {
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, d, 0);
        boundDepth_ = d;
    }
}

void FramebufferManager::writeBack(Target& t, u32 lo, u32 hi) {
    Rect r = t.dirty;
    r.x0 = std::max(r.x0, 0), r.y0 = std::max(r.y0, 0);
    r.x1 = std::min(r.x1, int(t.width()) - 1), r.y1 = std::min(r.y1, t.rowsValid - 1);
    const u32 bpp = t.bpp();
    auto rowStart = [&](int y) { return t.addr + (u32(y) * t.stride + u32(r.x0)) * bpp; };
    auto rowEnd = [&](int y) { return t.addr + (u32(y) * t.stride + u32(r.x1) + 1) * bpp; };
    if (!r.empty() && (lo > rowStart(r.y0) || hi < rowEnd(r.y1))) {
        // Only [lo, hi) is asked for (ge2gl_sync_range): the bytes outside it may hold CPU writes
        // the host did not report, which a write-back must not overwrite. Rows wholly inside the
        // range at the top or bottom of the dirty area leave it; the rest stays dirty.
        int y0 = r.y0, y1 = r.y1;
        while (y0 <= y1 && rowEnd(y0) <= lo) ++y0;
        while (y1 >= y0 && rowStart(y1) >= hi) --y1;
        if (y0 > y1) return;
        r.y0 = y0, r.y1 = y1;
        int top = t.dirty.y0, bottom = t.dirty.y1;
        while (top <= y1 && top >= y0 && rowStart(top) >= lo && rowEnd(top) <= hi) ++top;
        while (bottom >= top && bottom <= y1 && bottom >= y0 && rowStart(bottom) >= lo && rowEnd(bottom) <= hi) --bottom;
        t.dirty.y0 = top, t.dirty.y1 = bottom;
        if (t.dirty.empty()) t.dirty = Rect{}, t.announced = Rect{};
    } else {
        t.dirty = Rect{};
        t.announced = Rect{};
        lo = 0, hi = ~0u;
    }
    if (r.empty()) return;
    const GlFuncs& gl = ctx_.f();
    const int w = r.x1 - r.x0 + 1, h = r.y1 - r.y0 + 1;
    // The pixels of row y (from r.x0) that lie in [lo, hi): [first, first + count).
    auto span = [&](int y, u32 pixelBytes, u32& first, u32& count) {
        const u32 start = t.addr + (u32(r.y0 + y) * t.stride + u32(r.x0)) * pixelBytes;
        const u32 a = std::max(start, lo), b = std::min(start + u32(w) * pixelBytes, hi);
        first = a > start ? (a - start + pixelBytes - 1) / pixelBytes : 0;
        count = b > start + first * pixelBytes ? (b - start) / pixelBytes - first : 0;
    };
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    const bool scaled = scale_ > 1;
    if (scaled) {
        if (!downColorProg_ && !buildDownsamplePrograms()) return;
        downsample(t, r);  // leaves the 1× result attached to readFbo_
    }
    if (!t.depth) {
        if (!scaled) {
            gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.tex, 0);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
        }
        pixels_.resize(size_t(w) * size_t(h));
        gl.ReadPixels(r.x0, r.y0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
        gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        for (int y = 0; y < h; ++y) {
            u32 first, count;
            span(y, bpp, first, count);
            const u32 rowAddr = t.addr + (u32(r.y0 + y) * t.stride + u32(r.x0) + first) * bpp;
            const u32 avail = mem_.validSize(rowAddr, count * bpp) / bpp;
            u8* dst = mem_.ptr(rowAddr, std::max<u32>(avail * bpp, 1));
            if (!dst || avail == 0) continue;
            // Truncation keeps the stored high bits exactly (ge-rules.md §8.8).
            convertFromRGBA8888(&pixels_[size_t(y) * size_t(w) + first], t.fmt, avail, dst);
        }
    } else {
        depthPixels_.resize(size_t(w) * size_t(h));
        if (scaled) {
            gl.ReadPixels(r.x0, r.y0, w, h, GL_RED, GL_FLOAT, depthPixels_.data());
            gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        } else {
            gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.tex, 0);
            gl.ReadBuffer(GL_NONE);
            gl.ReadPixels(r.x0, r.y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depthPixels_.data());
            gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
        }
        for (int y = 0; y < h; ++y) {
            u32 first, count;
            span(y, 2, first, count);
            const u32 rowAddr = t.addr + (u32(r.y0 + y) * t.stride + u32(r.x0) + first) * 2;
            const u32 avail = mem_.validSize(rowAddr, count * 2) / 2;
            u8* dst = mem_.ptr(rowAddr, std::max<u32>(avail * 2, 1));
            if (!dst || avail == 0) continue;
            const float* src = &depthPixels_[size_t(y) * size_t(w) + first];
            for (u32 x = 0; x < avail; ++x) {
                const float z = std::clamp(src[x] * 65536.0f + 0.5f, 0.0f, 65535.0f);
                writeLE16(dst + 2 * x, u16(z));
            }
        }
    }
    ++readbacks_;
    ++writeBacks_;
}

void FramebufferManager::syncRange(u32 addr, u32 size) {
    const u32 begin = Memory::drawingAddress(addr);
    const u32 end = size ? begin + size : ~0u;
    for (auto& t : targets_)
        if (!t->dirty.empty() && t->addr < end && t->end() > begin) writeBack(*t, begin, end);
}

bool FramebufferManager::dirtyOverlaps(u32 addr, u32 size) const {
    const u32 begin = Memory::drawingAddress(addr);
    const u32 end = size ? begin + size : ~0u;
    for (const auto& t : targets_)
        if (!t->dirty.empty() && t->addr < end && t->end() > begin) return true;
    return false;
}

void FramebufferManager::memoryWritten(u32 addr, u32 size) {
    const u32 begin = Memory::drawingAddress(addr);
    if (begin < Memory::kVramBase || begin >= kVramEnd) return;
    const u32 end = size ? std::min<u32>(begin + size, kVramEnd) : kVramEnd;
    for (auto& t : targets_)
        if (t->addr < end && t->end() > begin) uploadSpan(*t, begin, end);
}

void FramebufferManager::flushAll() {
    for (auto& t : targets_) {
        if (!t->dirty.empty()) writeBack(*t);
        hashRows(*t);  // VRAM and the target agree now
    }
}

void FramebufferManager::forgetAll() {
    const GlFuncs& gl = ctx_.f();
    for (auto& t : targets_) {
        if (spare_.size() < kSpareTextures)
            spare_.push_back({t->depth, t->texCols() * scale_, t->allocRows * scale_, t->tex});
        else
            gl.DeleteTextures(1, &t->tex);
    }
    targets_.clear();
    boundColor_ = 0, boundDepth_ = ~0u;  // force re-attach
    ++clobbers_;  // the renderer may hold a deleted texture name bound as a destination copy
    suspect_ = false;
}

void FramebufferManager::hashRows(Target& t) {
    const u32 pitch = t.stride * t.bpp();
    t.rowHashes.resize(size_t(t.rowsValid));
    for (int y = 0; y < t.rowsValid; ++y) {
        const u32 a = t.addr + u32(y) * pitch;
        const u32 n = mem_.validSize(a, pitch);
        const u8* p = n ? mem_.ptr(a, n) : nullptr;
        t.rowHashes[size_t(y)] = p ? shadergen::hashBytes(p, n) : 0;
    }
}

void FramebufferManager::verifySuspects() {
    if (!suspect_) return;
    suspect_ = false;
    for (auto& tp : targets_) {
        Target& t = *tp;
        // Only targets VRAM agreed with at the last flush, with the same rows: a dirty target holds
        // newer pixels than VRAM, and rows added since were uploaded from VRAM anyway.
        if (!t.dirty.empty() || t.rowHashes.size() != size_t(t.rowsValid)) continue;
        const u32 pitch = t.stride * t.bpp();
        for (int y = 0; y < t.rowsValid;) {
            auto changed = [&](int row) {
                const u32 a = t.addr + u32(row) * pitch;
                const u32 n = mem_.validSize(a, pitch);
                const u8* p = n ? mem_.ptr(a, n) : nullptr;
                const u64 h = p ? shadergen::hashBytes(p, n) : 0;
                if (h == t.rowHashes[size_t(row)]) return false;
                t.rowHashes[size_t(row)] = h;
                return true;
            };
            if (!changed(y)) {
                ++y;
                continue;
            }
            int y1 = y + 1;
            while (y1 < t.rowsValid && changed(y1)) ++y1;
            uploadRows(t, y, y1);
            cpuWriteReuploads_ += u64(y1 - y);
            y = y1;
        }
    }
}

void FramebufferManager::takeNewlyDirty(std::vector<std::pair<u32, u32>>& out) {
    for (auto& t : targets_) {
        if (t->dirty.empty()) continue;
        const int y0 = std::max(t->dirty.y0, 0), y1 = std::min(t->dirty.y1, t->rowsValid - 1);
        if (!t->announced.empty() && t->announced.y0 <= y0 && t->announced.y1 >= y1) continue;
        t->announced = Rect{0, y0, 0, y1};
        const u32 pitch = t->stride * t->bpp();
        if (y1 < y0) continue;
        out.emplace_back(t->addr + u32(y0) * pitch, u32(y1 - y0 + 1) * pitch);
    }
}

}  // namespace ge::gl
