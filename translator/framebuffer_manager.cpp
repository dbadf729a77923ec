// Render targets as caches of VRAM (see framebuffer_manager.h).
#include "translator/framebuffer_manager.h"

#include <algorithm>
#include <cstring>

#include "hle/pixel_format.h"

namespace ge::gl {

u32 vramLinear(u32 addr) {
    const u32 a = Memory::normalize(addr);
    if (a >= Memory::kVramBase && a < Memory::kVramMirrorsEnd) return Memory::kVramBase | (a & (Memory::kVramSize - 1));
    return a;
}

namespace {
constexpr u32 kVramEnd = Memory::kVramBase + Memory::kVramSize;

const char* const kDepthVs =
    "#version 330 core\n"
    "void main() {\n"
    "  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
    "  gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";
// Depth as u16 in VRAM → z/65536 in the D32F target (exact).
const char* const kDepthFs =
    "#version 330 core\n"
    "uniform usampler2D u_stage;\n"
    "void main() {\n"
    "  gl_FragDepth = float(texelFetch(u_stage, ivec2(gl_FragCoord.xy), 0).r) * (1.0 / 65536.0);\n"
    "}\n";
}  // namespace

FramebufferManager::FramebufferManager(const GlContext& ctx, Memory& mem) : ctx_(ctx), mem_(mem) {
    const GlFuncs& gl = ctx_.f();
    gl.GenFramebuffers(1, &drawFbo_);
    gl.GenFramebuffers(1, &readFbo_);
    gl.GenFramebuffers(1, &utilFbo_);
    gl.GenVertexArrays(1, &emptyVao_);
}

FramebufferManager::~FramebufferManager() {
    const GlFuncs& gl = ctx_.f();
    for (auto& t : targets_) gl.DeleteTextures(1, &t->tex);
    gl.DeleteFramebuffers(1, &drawFbo_);
    gl.DeleteFramebuffers(1, &readFbo_);
    gl.DeleteFramebuffers(1, &utilFbo_);
    if (depthProg_) gl.DeleteProgram(depthProg_);
    if (depthStage_) gl.DeleteTextures(1, &depthStage_);
    gl.DeleteVertexArrays(1, &emptyVao_);
}

Target* FramebufferManager::find(bool depth, u32 addr, u32 stride, GeBufferFormat fmt) {
    for (auto& t : targets_)
        if (t->depth == depth && t->addr == addr && t->stride == stride && (depth || t->fmt == fmt)) return t.get();
    return nullptr;
}

Target* FramebufferManager::create(bool depth, u32 addr, u32 stride, GeBufferFormat fmt) {
    const GlFuncs& gl = ctx_.f();
    auto t = std::make_unique<Target>();
    t->depth = depth;
    t->addr = addr;
    t->stride = stride;
    t->fmt = fmt;
    gl.GenTextures(1, &t->tex);
    gl.BindTexture(GL_TEXTURE_2D, t->tex);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    if (depth)
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, kTargetSize, kTargetSize, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      nullptr);
    else
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, kTargetSize, kTargetSize, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE,
                      nullptr);
    targets_.push_back(std::move(t));
    return targets_.back().get();
}

void FramebufferManager::destroy(Target* t) {
    const GlFuncs& gl = ctx_.f();
    if (boundColor_ == t->tex || boundDepth_ == t->tex) boundColor_ = 0, boundDepth_ = ~0u;  // force re-attach
    gl.DeleteTextures(1, &t->tex);
    targets_.erase(std::remove_if(targets_.begin(), targets_.end(), [t](const auto& p) { return p.get() == t; }),
                   targets_.end());
}

Target* FramebufferManager::colorTarget(u32 addr, u32 stride, GeBufferFormat fmt, int rows) {
    if (stride == 0) return nullptr;
    addr = vramLinear(addr);
    Target* t = find(false, addr, stride, fmt);
    if (!t) t = create(false, addr, stride, fmt);
    ensureRows(*t, rows);
    return t;
}

Target* FramebufferManager::depthTarget(u32 addr, u32 stride, int rows) {
    if (stride == 0) return nullptr;
    addr = vramLinear(addr);
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
            u32* dst = &pixels_[size_t(y) * size_t(w)];
            if (t.fmt == GE_FORMAT_8888) {
                for (u32 x = 0; x < avail; ++x) dst[x] = readLE32(src + 4 * x);
            } else {
                // Stored form = what a GE read expands to (bit replication, ref §8.8).
                for (u32 x = 0; x < avail; ++x) dst[x] = decodePixel16(readLE16(src + 2 * x), t.fmt);
            }
        }
        gl.BindTexture(GL_TEXTURE_2D, t.tex);
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
        return;
    }
    // Depth: stage the u16 values, then draw them into the D32F target as gl_FragDepth.
    if (!depthProg_ && !buildDepthProgram()) return;
    depth16_.assign(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        const u32 rowAddr = t.addr + (u32(y0 + y) * t.stride + u32(x0)) * 2;
        const u32 avail = mem_.validSize(rowAddr, u32(w) * 2) / 2;
        const u8* src = mem_.ptr(rowAddr, std::max<u32>(avail * 2, 1));
        if (!src || avail == 0) continue;
        for (u32 x = 0; x < avail; ++x) depth16_[size_t(y) * size_t(w) + x] = readLE16(src + 2 * x);
    }
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.BindTexture(GL_TEXTURE_2D, depthStage_);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, x0, y0, w, h, GL_RED_INTEGER, GL_UNSIGNED_SHORT, depth16_.data());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.BindFramebuffer(GL_FRAMEBUFFER, utilFbo_);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.tex, 0);
    gl.DrawBuffer(GL_NONE);
    gl.ReadBuffer(GL_NONE);
    gl.Viewport(0, 0, kTargetSize, kTargetSize);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(x0, y0, w, h);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_ALWAYS);
    gl.DepthMask(GL_TRUE);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.UseProgram(depthProg_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, depthStage_);
    gl.BindVertexArray(emptyVao_);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    ++clobbers_;
}

bool FramebufferManager::buildDepthProgram() {
    const GlFuncs& gl = ctx_.f();
    auto compile = [&](GLenum type, const char* src) {
        GLuint sh = gl.CreateShader(type);
        gl.ShaderSource(sh, 1, &src, nullptr);
        gl.CompileShader(sh);
        return sh;
    };
    GLuint v = compile(GL_VERTEX_SHADER, kDepthVs), f = compile(GL_FRAGMENT_SHADER, kDepthFs);
    depthProg_ = gl.CreateProgram();
    gl.AttachShader(depthProg_, v);
    gl.AttachShader(depthProg_, f);
    gl.LinkProgram(depthProg_);
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    GLint ok = 0;
    gl.GetProgramiv(depthProg_, GL_LINK_STATUS, &ok);
    if (!ok) {
        gl.DeleteProgram(depthProg_);
        depthProg_ = 0;
        return false;
    }
    gl.UseProgram(depthProg_);
    gl.Uniform1i(gl.GetUniformLocation(depthProg_, "u_stage"), 0);
    gl.GenTextures(1, &depthStage_);
    gl.BindTexture(GL_TEXTURE_2D, depthStage_);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R16UI, kTargetSize, kTargetSize, 0, GL_RED_INTEGER, GL_UNSIGNED_SHORT, nullptr);
    ++clobbers_;
    return true;
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

void FramebufferManager::writeBack(Target& t) {
    Rect r = t.dirty;
    t.dirty = Rect{};
    r.x0 = std::max(r.x0, 0), r.y0 = std::max(r.y0, 0);
    r.x1 = std::min(r.x1, int(t.width()) - 1), r.y1 = std::min(r.y1, t.rowsValid - 1);
    if (r.empty()) return;
    const GlFuncs& gl = ctx_.f();
    const int w = r.x1 - r.x0 + 1, h = r.y1 - r.y0 + 1;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo_);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    const u32 bpp = t.bpp();
    if (!t.depth) {
        gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.tex, 0);
        gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
        pixels_.resize(size_t(w) * size_t(h));
        gl.ReadPixels(r.x0, r.y0, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, pixels_.data());
        gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        for (int y = 0; y < h; ++y) {
            const u32 rowAddr = t.addr + (u32(r.y0 + y) * t.stride + u32(r.x0)) * bpp;
            const u32 avail = mem_.validSize(rowAddr, u32(w) * bpp) / bpp;
            u8* dst = mem_.ptr(rowAddr, std::max<u32>(avail * bpp, 1));
            if (!dst || avail == 0) continue;
            const u32* src = &pixels_[size_t(y) * size_t(w)];
            if (t.fmt == GE_FORMAT_8888) {
                for (u32 x = 0; x < avail; ++x) writeLE32(dst + 4 * x, src[x]);
            } else {
                // Truncation keeps the stored high bits exactly (ref §8.8).
                for (u32 x = 0; x < avail; ++x) writeLE16(dst + 2 * x, encodePixel16(src[x], t.fmt));
            }
        }
    } else {
        gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.tex, 0);
        gl.ReadBuffer(GL_NONE);
        depthPixels_.resize(size_t(w) * size_t(h));
        gl.ReadPixels(r.x0, r.y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depthPixels_.data());
        gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
        for (int y = 0; y < h; ++y) {
            const u32 rowAddr = t.addr + (u32(r.y0 + y) * t.stride + u32(r.x0)) * 2;
            const u32 avail = mem_.validSize(rowAddr, u32(w) * 2) / 2;
            u8* dst = mem_.ptr(rowAddr, std::max<u32>(avail * 2, 1));
            if (!dst || avail == 0) continue;
            const float* src = &depthPixels_[size_t(y) * size_t(w)];
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
    const u32 begin = vramLinear(addr);
    const u32 end = size ? begin + size : ~0u;
    for (auto& t : targets_)
        if (!t->dirty.empty() && t->addr < end && t->end() > begin) writeBack(*t);
}

void FramebufferManager::memoryWritten(u32 addr, u32 size) {
    const u32 begin = vramLinear(addr);
    if (begin < Memory::kVramBase || begin >= kVramEnd) return;
    const u32 end = size ? std::min<u32>(begin + size, kVramEnd) : kVramEnd;
    for (auto& t : targets_)
        if (t->addr < end && t->end() > begin) uploadSpan(*t, begin, end);
}

void FramebufferManager::flushAll() {
    for (auto& t : targets_)
        if (!t->dirty.empty()) writeBack(*t);
}

}  // namespace ge::gl
