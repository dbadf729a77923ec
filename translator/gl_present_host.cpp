// SPDX-License-Identifier: MIT
// The GL renderer's host calls (gl_renderer_impl.h; plugin API and tools): entering and leaving
// the host's thread or context (gl_host_state.h), presenting a frame (present.h), the frame at
// render scale, and what the host changed in guest memory.
#include <algorithm>

#include "hle/pixel_format.h"
#include "translator/gl_renderer_impl.h"

namespace ge::gl {

// A renderer is created entered (depth 1): the host's thread gets its own state or context
// back at the first hostLeave().
bool GlRendererImpl::hostEnter(std::string& err) {
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
bool GlRendererImpl::currentIsOurs(std::string& err) const {
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

void GlRendererImpl::hostLeave() {
    if (hostDepth_ == 0 || --hostDepth_ > 0) return;
    if (ctx_->headless()) {
        ctx_->leave();  // making another context current flushes ours
    } else {
        hostState_.restore(gl_);
    }
}

// Drops every assumption about GL bindings (the host or another pass changed them).
void GlRendererImpl::forgetGlState() {
    fb_.forgetBindings();
    state_.forget();
}

void GlRendererImpl::hostMayHaveWritten(bool frameBuffers) {
    ++generation_;  // cached textures are re-hashed against their bytes when next used
    if (frameBuffers) fb_.markSuspect();
}

bool GlRendererImpl::holdsNewerThanMemory(u32 addr, u32 size) const {
    // A batch not yet drawn may write anywhere in its targets; otherwise the dirty targets.
    return pending() || fb_.dirtyOverlaps(addr, size);
}

void GlRendererImpl::takeDirtyRanges(std::vector<std::pair<u32, u32>>& out) {
    flush();
    fb_.takeNewlyDirty(out);
}

unsigned GlRendererImpl::presentFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, int outW, int outH,
                                      std::string& err) {
    flush();
    if (!presenter_) presenter_ = std::make_unique<Presenter>(*ctx_, fb_, mem_);
    const GLuint tex = presenter_->frame(addr, stride, fmt, w, h, outW, outH, err);
    forgetGlState();
    return tex;
}

void GlRendererImpl::forgetGuestMemory() {
    flush();
    presenter_.reset();
    fb_.forgetAll();
    textures_.clear();
    for (auto& kv : palettes_) gl_.DeleteTextures(1, &kv.second);
    palettes_.clear();
    ++generation_;
    forgetGlState();  // the state cache may name deleted textures
}

int GlRendererImpl::readScaledFrame(u32 addr, u32 stride, GeBufferFormat fmt, int w, int h, std::vector<u32>& rgba) {
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
    state_.invalidate();
    return n;
}

}  // namespace ge::gl
