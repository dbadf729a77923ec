// SPDX-License-Identifier: MIT
// Save states through the C ABI (include/ge2gl/ge2gl.h "Save states"; format docs/savestate.md):
// the handle's GE, sceGe layer and held-interrupt flag, plus guest memory on request. The
// serialisation itself is hle/savestate.cpp; here the backend is brought to guest memory first
// (save) and told everything changed (load).
#include "api/context.h"

#include "hle/savestate.h"

using namespace ge2gl_impl;

namespace {

// Saving or loading from inside a callback or while the GE is mid-command would catch a command
// half done.
ge2gl_status refuseMidRun(ge2gl_context* h, Call& c) {
    if (reentrant(h)) return c.error(GE2GL_ERR_REENTRANT, "save states are taken between commands, not from a callback");
    if (h->sce->inRun()) return c.error(GE2GL_ERR_BAD_STATE, "the GE is executing a command");
    return GE2GL_OK;
}

}  // namespace

extern "C" {

ge2gl_status ge2gl_state_save(ge2gl_context* h, uint32_t flags, const void** out_data, size_t* out_size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_data || !out_size) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_data or out_size is NULL");
        if (flags & ~GE2GL_STATE_WITH_MEMORY) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown state flags");
        if (ge2gl_status s = refuseMidRun(h, c); s != GE2GL_OK) return s;
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        // What the backend drew lives in guest VRAM from here on: the state needs nothing of it.
        h->engine->renderer()->flushToMemory();
        announceDirty(h);
        ge::savestate::HostFlags host;
        host.heldInterrupt = h->held;
        h->stateBlob = ge::savestate::save(*h->engine, *h->sce, (flags & GE2GL_STATE_WITH_MEMORY) ? h->mem.get() : nullptr,
                                           host);
        *out_data = h->stateBlob.data();
        *out_size = h->stateBlob.size();
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_state_load(ge2gl_context* h, const void* data, size_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!data && size) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "data is NULL");
        if (ge2gl_status s = refuseMidRun(h, c); s != GE2GL_OK) return s;
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        ge::savestate::HostFlags host;
        bool hadMemory = false;
        std::string err;
        if (!ge::savestate::load({static_cast<const ge::u8*>(data), data ? size : 0}, *h->engine, *h->sce, *h->mem, host, hadMemory,
                                 err))
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "save state not loaded: " + err);
        // Every cache the backend holds may be stale now: textures, CLUTs and render targets are
        // read again from guest memory.
        ge::Renderer* r = h->engine->renderer();
        r->memoryWritten(ge::Memory::kVramBase, ge::Memory::kVramSize);
        r->memoryWritten(ge::Memory::kRamBase, h->mem->ramSize());
        r->hostMayHaveWritten(true);
        h->pendingWrites.clear();
        h->held = host.heldInterrupt;
        return GE2GL_OK;
    });
}

}  // extern "C"
