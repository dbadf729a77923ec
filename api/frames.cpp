// SPDX-License-Identifier: MIT
// Frames for the host (RGBA8888 in host memory, or a GL texture made on the GPU) and dump replay
// through a handle (plugin API; context.h).
#include "api/context.h"

#include <cstdio>

#include "hle/dump/player.h"
#include "hle/dump/ppdmp.h"
#include "hle/pixel_format.h"

using namespace ge2gl_impl;

namespace {

// Common checks of a frame's geometry; the byte span it covers in *bytes.
ge2gl_status frameArgs(Call& c, ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                       uint32_t height, u32* bytes) {
    if (format < GE2GL_FORMAT_565 || format > GE2GL_FORMAT_8888) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown pixel format");
    if (!width || !height || width > 4096 || height > 4096 || stride < width || stride > 4096)
        return c.error(GE2GL_ERR_INVALID_ARGUMENT, "width/height must be 1-4096 and stride at least width (at most 4096)");
    // The GE addresses frame buffers in whole pixels (manual §11.5, FBP: 16-byte aligned): an
    // address inside a pixel names no frame.
    const u32 bpp = ge::bytesPerPixel(ge::GeBufferFormat(format));
    if (addr % bpp) {
        char buf[100];
        std::snprintf(buf, sizeof buf, "frame address 0x%08x is not aligned to its %u-byte pixels", addr, bpp);
        return c.error(GE2GL_ERR_INVALID_ARGUMENT, buf);
    }
    *bytes = ((height - 1) * stride + width) * bpp;
    if (!h->mem->valid(addr, *bytes)) {
        char buf[100];
        std::snprintf(buf, sizeof buf, "frame buffer 0x%08x + 0x%x is outside guest memory", addr, *bytes);
        return c.error(GE2GL_ERR_MEMORY, buf);
    }
    return GE2GL_OK;
}

// ge2gl_replay_dump's target: the public calls an emulator would make, one handle.
class HandleTarget : public ge::dump::ReplayTarget {
public:
    explicit HandleTarget(ge2gl_context* h) : h_(h) {}
    u32 ramSize() const override { return h_->mem->ramSize(); }
    u32 write(u32 addr, const void* data, u32 size) override {
        // Clip to valid memory as the player expects (a dump may write past the end of RAM).
        const u32 n = h_->mem->validSize(addr, size);
        if (n && ge2gl_mem_write(h_, addr, data, n) != GE2GL_OK) note();
        return n;
    }
    u32 fill(u32 addr, u8 value, u32 size) override {
        const u32 n = h_->mem->validSize(addr, size);
        std::vector<u8> b(n, value);
        if (n && ge2gl_mem_write(h_, addr, b.data(), n) != GE2GL_OK) note();
        return n;
    }
    void loadContext(const u32 ctx[512]) override {
        if (ge2gl_restore_context(h_, ctx) != GE2GL_OK) note();
    }
    void startList(u32 pc, u32 stall) override {
        if (ge2gl_list_enqueue(h_, pc, stall, -1, nullptr, &id_) != GE2GL_OK) note();
    }
    ge::RunStatus runTo(u32 stall, u64 budget) override {
        if (ge2gl_list_update_stall(h_, id_, stall) != GE2GL_OK) note();
        ge2gl_run_info info{};
        if (ge2gl_run(h_, budget, &info) != GE2GL_OK) {
            note();
            return ge::RunStatus::Error;
        }
        switch (info.ge_state) {
        case GE2GL_GE_IDLE: return ge::RunStatus::Completed;
        case GE2GL_GE_STALLED: return ge::RunStatus::Stalled;
        case GE2GL_GE_READY: return ge::RunStatus::Budget;
        case GE2GL_GE_PAUSED:
        case GE2GL_GE_INTERRUPT: return ge::RunStatus::Paused;
        default: return ge::RunStatus::Ended;
        }
    }
    std::string lastError() override { return error_.empty() ? ge2gl_last_message(h_) : error_; }
    u32 readRegister(u8 op) override {
        uint32_t w = 0;
        ge2gl_get_cmd(h_, op, &w);
        return w;
    }
    bool setEdramTranslation(u32 v) override { return ge2gl_edram_set_translation(h_, v, nullptr) == GE2GL_OK; }
    void finishFrame() override {
        int32_t state = 0;
        if (ge2gl_draw_sync(h_, GE2GL_SYNC_WAIT, &state) != GE2GL_OK) note();
    }

private:
    void note() {
        if (error_.empty()) error_ = ge2gl_last_message(h_);
    }
    ge2gl_context* h_;
    int32_t id_ = -1;
    std::string error_;
};

}  // namespace

extern "C" {

ge2gl_status ge2gl_read_frame(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                              uint32_t height, uint8_t* out_rgba, size_t out_size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        u32 bytes = 0;
        if (ge2gl_status s = frameArgs(c, h, addr, stride, format, width, height, &bytes); s != GE2GL_OK) return s;
        if (!out_rgba || out_size < size_t(width) * height * 4) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "output buffer too small");
        const ge::GeBufferFormat fmt = ge::GeBufferFormat(format);
        ge::Renderer* r = h->engine->renderer();
        if (c.glReachable()) {
            if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
            r->syncMemoryForRead(addr, bytes);
        } else if (r->holdsNewerThanMemory(addr, bytes)) {
            return c.error(GE2GL_ERR_WRONG_THREAD, "the GPU holds newer pixels of this frame and GL_CURRENT's context is "
                                                   "on the creating thread: read it from there");
        }
        const u8* src = h->mem->ptr(addr, bytes);
        // Convert into aligned words, then store them byte by byte (R first) into the host buffer,
        // which need not be 4-byte aligned.
        std::vector<u32> px(size_t(width) * height);
        ge::convertToRGBA8888(src, fmt, width, height, stride, px.data());
        for (size_t k = 0; k < px.size(); ++k) ge::writeLE32(out_rgba + 4 * k, px[k]);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_frame_texture_sized(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                                       uint32_t height, uint32_t out_width, uint32_t out_height, uint32_t* out_texture) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_texture) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_texture is NULL");
        u32 bytes = 0;
        if (ge2gl_status s = frameArgs(c, h, addr, stride, format, width, height, &bytes); s != GE2GL_OK) return s;
        if (!out_width || !out_height || out_width > 8192 || out_height > 8192)
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_width/out_height must be 1-8192");
        ge::backend::FramePresenter* presenter = h->drawBackend.presenter;
        if (!presenter) return c.error(GE2GL_ERR_UNSUPPORTED, "this backend has no GL textures (use ge2gl_read_frame)");
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        std::string err;
        const unsigned tex = presenter->presentFrame(addr, stride, ge::GeBufferFormat(format), int(width), int(height),
                                                     int(out_width), int(out_height), err);
        if (!tex) return c.error(GE2GL_ERR_BACKEND, "the GL backend could not make the frame texture: " + err);
        *out_texture = tex;
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_frame_texture(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                                 uint32_t height, uint32_t* out_texture) {
    uint32_t n = 1;
    if (h && h->drawBackend.scaled) n = uint32_t(h->drawBackend.scaled->renderScale());
    return ge2gl_frame_texture_sized(h, addr, stride, format, width, height, width * n, height * n, out_texture);
}

ge2gl_status ge2gl_replay_dump(ge2gl_context* h, const char* path, ge2gl_display* out) {
    if (!h) return GE2GL_ERR_INVALID_HANDLE;
    {
        Call c(h);
        if (!path) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "path is NULL");
        if (h->workerMode) return c.error(GE2GL_ERR_BAD_STATE, "dump replay runs the GE itself: not in worker-thread mode");
        if (h->mem->ramSize() < ge::Memory::kDefaultRamSize)
            return c.error(GE2GL_ERR_UNSUPPORTED, "dump replay needs 64 MiB of RAM (PPSSPP's dump layout)");
    }
    try {
        // No lock around the replay: it goes through the public calls, each taking it in turn
        // (interrupts are delivered unlocked, as for any host).
        ge::dump::Dump d;
        std::string err;
        if (!ge::dump::loadDump(path, d, err)) {
            Call c(h);
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "cannot load the dump: " + err);
        }
        HandleTarget target(h);
        ge::dump::ReplayResult res;
        const bool ok = ge::dump::replayDump(d, target, {}, res, err);
        Call c(h);
        if (!ok) return c.error(GE2GL_ERR_BAD_STATE, "the dump did not replay: " + err);
        if (out) {
            u32 addr = 0, stride = 0, format = 0;
            ge::dump::displayedFramebuffer(res, h->engine->state(), addr, stride, format);
            out->addr = addr;
            out->stride = stride;
            out->format = int32_t(format);
            out->width = 480;
            out->height = 272;
        }
        return GE2GL_OK;
    } catch (const std::bad_alloc&) {
        Call c(h);
        return c.error(GE2GL_ERR_OUT_OF_HOST_MEMORY, "out of host memory");
    }
}

}  // extern "C"
