// SPDX-License-Identifier: MIT
// The C ABI of the plugin (include/ge2gl/ge2gl.h) over SceGe + GeEngine + a backend: creation,
// guest memory and the sceGe calls. Running the GE, syncs and the worker are in execution.cpp,
// frames and dump replay in frames.cpp; the handle and the call guard in context.h.
//
// Every entry point catches C++ exceptions (allocation failures) and turns them into status codes:
// nothing throws across the C boundary.
#include "api/context.h"
#include "api/render_gate.h"

#include <cstddef>
#include <cstdio>
#include <new>

#include "geometry/accuracy_profile.h"
#include "hle/ge_time.h"
#include "hle/pixel_format.h"

using namespace ge2gl_impl;

namespace {

// Why this thread's last ge2gl_create failed (ge2gl_last_message(NULL)).
thread_local std::string t_createMessage;

ge2gl_status createFailed(ge2gl_status s, const std::string& why) {
    t_createMessage = why;
    return s;
}

// The handle's backend from the config (backend/factory.h); GE2GL_BACKEND_NULL has none (the
// engine's own null backend). A failure is reported through createFailed.
ge2gl_status makeBackend(const ge2gl_config* cfg, int32_t glMode, int32_t scale, bool has12,
                         const ge::geo::AccuracyProfile& accuracy, ge2gl_context& h) {
    namespace be = ge::backend;
    be::BackendOptions bo;
    bo.accuracy = accuracy;
    std::string err;
    switch (cfg->backend) {
    case GE2GL_BACKEND_NULL: return GE2GL_OK;
    case GE2GL_BACKEND_SOFT:
        bo.kind = be::BackendKind::Soft;
        bo.threads = cfg->soft_threads;  // the output is identical for any thread count
        h.drawBackend = be::createBackend(*h.mem, bo, err);
        if (!h.drawBackend) return createFailed(GE2GL_ERR_BACKEND, "the software backend could not start");
        return GE2GL_OK;
    default: break;
    }
    if (!be::backendBuilt(be::BackendKind::Gl))
        return createFailed(GE2GL_ERR_BACKEND, "this library was built without the GL backend (GE2GL_BUILD_GL=OFF)");
    bo.kind = be::BackendKind::Gl;
    bo.glContext = cfg->backend == GE2GL_BACKEND_GL_CURRENT ? be::GlContext::Current
                   : cfg->gl_use_egl                        ? be::GlContext::EGL
                                                            : be::GlContext::OSMesa;
    bo.glMode = glMode == GE2GL_GL_MODE_HW ? be::GlMode::Hw : be::GlMode::Exact;
    bo.scale = scale;
    if (has12) bo.glLoader = cfg->gl_get_proc_address;
    h.drawBackend = be::createBackend(*h.mem, bo, err);
    if (!h.drawBackend) return createFailed(GE2GL_ERR_BACKEND, "GL backend: " + err);
    // Created entered (the new context current, or the host's state saved): hand the thread back
    // as it was.
    if (be::HostContextUser* host = h.drawBackend.host) host->hostLeave();
    h.glThread = std::this_thread::get_id();
    return GE2GL_OK;
}

}  // namespace

extern "C" {

uint32_t ge2gl_api_version(void) { return GE2GL_API_VERSION; }

const char* ge2gl_status_name(ge2gl_status s) {
    switch (s) {
    case GE2GL_OK: return "GE2GL_OK";
    case GE2GL_ERR_INVALID_ARGUMENT: return "GE2GL_ERR_INVALID_ARGUMENT";
    case GE2GL_ERR_INVALID_HANDLE: return "GE2GL_ERR_INVALID_HANDLE";
    case GE2GL_ERR_VERSION: return "GE2GL_ERR_VERSION";
    case GE2GL_ERR_BACKEND: return "GE2GL_ERR_BACKEND";
    case GE2GL_ERR_WOULD_BLOCK: return "GE2GL_ERR_WOULD_BLOCK";
    case GE2GL_ERR_REENTRANT: return "GE2GL_ERR_REENTRANT";
    case GE2GL_ERR_BAD_STATE: return "GE2GL_ERR_BAD_STATE";
    case GE2GL_ERR_MEMORY: return "GE2GL_ERR_MEMORY";
    case GE2GL_ERR_OUT_OF_HOST_MEMORY: return "GE2GL_ERR_OUT_OF_HOST_MEMORY";
    case GE2GL_ERR_UNSUPPORTED: return "GE2GL_ERR_UNSUPPORTED";
    case GE2GL_ERR_WRONG_THREAD: return "GE2GL_ERR_WRONG_THREAD";
    case GE2GL_ERR_GL_CONTEXT: return "GE2GL_ERR_GL_CONTEXT";
    case GE2GL_ERR_TIME_BUDGET: return "GE2GL_ERR_TIME_BUDGET";
    case GE2GL_SCE_ERROR_INVALID_STATE: return "SCE_ERROR_INVALID_STATE (0x80000004)";
    case GE2GL_SCE_ERROR_ALREADY: return "SCE_ERROR_ALREADY (0x80000020)";
    case GE2GL_SCE_ERROR_BUSY: return "SCE_ERROR_BUSY (0x80000021)";
    case GE2GL_SCE_ERROR_OUT_OF_MEMORY: return "SCE_ERROR_OUT_OF_MEMORY (0x80000022)";
    case GE2GL_SCE_ERROR_BAD_POINTER: return "SCE_ERROR_BAD_POINTER (0x80000023)";
    case GE2GL_SCE_ERROR_INVALID_ID: return "SCE_ERROR_INVALID_ID (0x80000100)";
    case GE2GL_SCE_ERROR_INVALID_INDEX: return "SCE_ERROR_INVALID_INDEX (0x80000102)";
    case GE2GL_SCE_ERROR_INVALID_POINTER: return "SCE_ERROR_INVALID_POINTER (0x80000103)";
    case GE2GL_SCE_ERROR_INVALID_SIZE: return "SCE_ERROR_INVALID_SIZE (0x80000104)";
    case GE2GL_SCE_ERROR_INVALID_MODE: return "SCE_ERROR_INVALID_MODE (0x80000107)";
    case GE2GL_SCE_ERROR_INVALID_VALUE: return "SCE_ERROR_INVALID_VALUE (0x800001FE)";
    default: return "unknown status";
    }
}

void ge2gl_config_init(ge2gl_config* c) {
    if (!c) return;
    *c = ge2gl_config{};
    c->struct_size = sizeof(ge2gl_config);
    c->api_version = GE2GL_API_VERSION;
    c->backend = GE2GL_BACKEND_SOFT;
}

ge2gl_status ge2gl_create(const ge2gl_config* cfg, ge2gl_context** out) {
    t_createMessage.clear();
    if (!cfg || !out) return createFailed(GE2GL_ERR_INVALID_ARGUMENT, "config or out is NULL");
    *out = nullptr;
    // Structs grow at the end: a 1.0 host's config ends before gl_mode, a 1.1 host's before
    // gl_get_proc_address (their missing fields get defaults).
    constexpr u32 kConfigSize10 = u32(offsetof(ge2gl_config, gl_mode));
    if (cfg->struct_size < kConfigSize10 || cfg->struct_size > sizeof(ge2gl_config))
        return createFailed(GE2GL_ERR_VERSION, "config.struct_size " + std::to_string(cfg->struct_size) +
                                                   " is not the size of any ge2gl_config version (1.0: " +
                                                   std::to_string(kConfigSize10) + ", this library: " +
                                                   std::to_string(sizeof(ge2gl_config)) + ")");
    if ((cfg->api_version >> 16) != GE2GL_API_VERSION_MAJOR || (cfg->api_version & 0xFFFF) > GE2GL_API_VERSION_MINOR) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "config.api_version %u.%u is newer than this library's %u.%u or of another major",
                      cfg->api_version >> 16, cfg->api_version & 0xFFFF, GE2GL_API_VERSION_MAJOR, GE2GL_API_VERSION_MINOR);
        return createFailed(GE2GL_ERR_VERSION, buf);
    }
    auto has = [&](size_t offset, size_t size) { return cfg->struct_size >= offset + size; };
    const bool has11 = has(offsetof(ge2gl_config, render_scale), sizeof(int32_t));
    const bool has12 = has(offsetof(ge2gl_config, vram_dirty), sizeof(cfg->vram_dirty));
    const int32_t glMode = has11 ? cfg->gl_mode : GE2GL_GL_MODE_EXACT;
    const int32_t scale = has11 && cfg->render_scale ? cfg->render_scale : 1;
    if (glMode != GE2GL_GL_MODE_EXACT && glMode != GE2GL_GL_MODE_HW)
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT, "config.gl_mode must be GE2GL_GL_MODE_EXACT or GE2GL_GL_MODE_HW");
    if (scale < 1 || scale > 8 || (scale > 1 && glMode != GE2GL_GL_MODE_HW))
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT,
                            "config.render_scale must be 1-8, and above 1 only with GE2GL_GL_MODE_HW");
    // API 1.6: the accuracy profile; older hosts get the default, psp.
    const int32_t accuracy = has(offsetof(ge2gl_config, accuracy), sizeof(cfg->accuracy)) ? cfg->accuracy
                                                                                          : GE2GL_ACCURACY_PSP;
    if (accuracy != GE2GL_ACCURACY_PSP && accuracy != GE2GL_ACCURACY_PPSSPP)
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT,
                            "config.accuracy must be GE2GL_ACCURACY_PSP or GE2GL_ACCURACY_PPSSPP");
    if (cfg->backend < GE2GL_BACKEND_NULL || cfg->backend > GE2GL_BACKEND_GL_HEADLESS)
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT, "config.backend is not a GE2GL_BACKEND_* value");
    // A host buffer has the size the host says, never an assumed one (a 32 MiB model's buffer
    // must not be read as 64 MiB).
    if (cfg->ram && !cfg->ram_size)
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT, "config.ram_size is required with a host RAM buffer");
    const u32 ramSize = cfg->ram_size ? cfg->ram_size : ge::Memory::kDefaultRamSize;
    // RAM ends at 0x0C000000 in the PSP map (64 MiB models).
    if (ramSize > ge::Memory::kDefaultRamSize)
        return createFailed(GE2GL_ERR_INVALID_ARGUMENT, "config.ram_size above 64 MiB (RAM ends at 0x0C000000)");
    if (cfg->worker_thread && cfg->backend == GE2GL_BACKEND_GL_CURRENT)
        return createFailed(GE2GL_ERR_UNSUPPORTED,
                            "worker_thread with GL_CURRENT: the host's context lives on the host's thread "
                            "(use GL_HEADLESS with a worker, or run the GE on the GL thread)");
    try {
        std::unique_ptr<ge2gl_context> h(new ge2gl_context);
        if (cfg->ram) {
            h->mem = std::make_unique<ge::Memory>(cfg->ram, ramSize, cfg->vram);  // vram NULL: Memory allocates it
        } else if (cfg->vram) {
            // Host VRAM but ge2gl-owned RAM.
            h->ownedRam.reset(new u8[ramSize]());
            h->mem = std::make_unique<ge::Memory>(h->ownedRam.get(), ramSize, cfg->vram);
        } else {
            h->mem = std::make_unique<ge::Memory>(ramSize);
        }
        h->backend = cfg->backend;
        const ge::geo::AccuracyProfile profile =
            accuracy == GE2GL_ACCURACY_PPSSPP ? ge::geo::AccuracyProfile::ppsspp() : ge::geo::AccuracyProfile::psp();
        h->accuracy = profile;
        if (ge2gl_status st = makeBackend(cfg, glMode, scale, has12, profile, *h); st != GE2GL_OK) return st;
        // The engine draws through the gate, which leaves the handle's lock while the backend works.
        if (ge::Renderer* r = h->drawBackend.renderer.get()) h->gate = std::make_unique<RenderGate>(h.get(), r);
        h->engine = std::make_unique<ge::GeEngine>(*h->mem, h->gate.get());
        h->sce = std::make_unique<ge::SceGe>(*h->engine);
        h->listener.h = h.get();
        h->listener.cb = cfg->callbacks;
        h->sce->setListener(&h->listener);
        h->sce->setSdkVersion(cfg->sdk_version ? cfg->sdk_version : ge::SceGe::kDefaultSdkVersion);
        h->waitBudget = cfg->wait_budget ? cfg->wait_budget : (u64(1) << 26);
        h->sce->setWaitBudget(h->waitBudget);
        if (has12) {
            h->lazyWriteback = cfg->lazy_writeback != 0;
            h->holdInterrupts = cfg->hold_interrupts != 0;
            h->sce->setHandlersDeferred(h->holdInterrupts);
            h->vramDirty = cfg->vram_dirty;
        }
        // API 1.5: the run budget (default: ten 60 Hz frames of GE time, dump replay's frame
        // budget) and the drop callback.
        u32 budgetUs = 0;
        if (has(offsetof(ge2gl_config, run_budget_us), sizeof(cfg->run_budget_us))) budgetUs = cfg->run_budget_us;
        if (has(offsetof(ge2gl_config, drop), sizeof(cfg->drop))) h->drop = cfg->drop;
        h->runBudget = budgetUs == UINT32_MAX ? ~u64(0)
                     : budgetUs == 0           ? ge::getime::cyclesFromMs(1000.0 / 6.0)
                                               : u64(budgetUs) * (ge::getime::kCyclesPerSecond / 1'000'000);
        h->engine->setDrawLimit(h->runBudget);
        refreshSnapshot(h.get());
        if (cfg->worker_thread) {
            h->workerMode = true;
            h->worker = std::thread([p = h.get()] { p->workerLoop(); });
            h->workerId = h->worker.get_id();
        }
        *out = h.release();
        return GE2GL_OK;
    } catch (const std::bad_alloc&) {
        return createFailed(GE2GL_ERR_OUT_OF_HOST_MEMORY, "out of host memory");
    } catch (...) {
        return createFailed(GE2GL_ERR_BACKEND, "internal error while creating the backend");
    }
}

void ge2gl_destroy(ge2gl_context* h) {
    if (!h) return;
    if (h->worker.joinable()) {
        {
            std::lock_guard<std::recursive_mutex> lk(h->mu);
            h->quit = true;
        }
        h->wake.notify_all();
        h->worker.join();
    }
    // The SceGe detaches from the engine, the engine from the renderer, in this order. The GL
    // renderer makes its context current for its own deletes and restores the thread's after.
    h->sce.reset();
    h->engine.reset();
    h->gate.reset();
    h->drawBackend = {};
    delete h;
}

const char* ge2gl_last_message(ge2gl_context* h) {
    if (!h) return t_createMessage.c_str();
    return h->message.c_str();
}

// ---- Guest memory ----
//
// Host reads and writes must see and leave VRAM as the GE would: dirty render targets are written
// back first, written bytes dropped from the backend's caches. Those are GL calls: a thread that
// cannot reach GL_CURRENT's context reads directly when no target holds newer pixels there, and
// has its writes' cache updates applied on the GL thread's next call.

namespace {

ge2gl_status memCheck(Call& c, ge2gl_context* h, uint32_t addr, uint32_t size) {
    if (!h->mem->valid(addr, size)) {
        char buf[120];
        std::snprintf(buf, sizeof buf, "range 0x%08x + 0x%x is outside guest memory (RAM 0x08000000 + 0x%x, VRAM, scratchpad)",
                      addr, size, h->mem->ramSize());
        return c.error(GE2GL_ERR_MEMORY, buf);
    }
    return GE2GL_OK;
}

}  // namespace

// Frame and depth buffers live in VRAM (manual §9.1, FBP/ZBP): a backend holds pixels newer than
// guest memory only there. A write to RAM therefore cannot overwrite a draw's output and goes
// on while the GE thread draws (the backend hears of it when the draw returns); one to VRAM
// waits for the draw in progress.
static CallKind writeKind(uint32_t addr) { return ge::Memory::isVram(addr) ? CallKind::Waits : CallKind::Light; }

ge2gl_status ge2gl_mem_write(ge2gl_context* h, uint32_t addr, const void* src, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, writeKind(addr));
        if (!src && size) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "src is NULL");
        if (ge2gl_status s = memCheck(c, h, addr, size); s != GE2GL_OK) return s;
        if (h->rendering || !c.glReachable()) {
            h->mem->write(addr, src, size);
            h->pendingWrites.emplace_back(addr, size);  // applyDeferred / the next GL call hands it over
            return GE2GL_OK;
        }
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        h->engine->renderer()->syncMemoryForRead(addr, size);  // partial overwrite of a cached range
        h->mem->write(addr, src, size);
        h->engine->renderer()->memoryWritten(addr, size);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_mem_read(ge2gl_context* h, uint32_t addr, void* dst, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!dst && size) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "dst is NULL");
        if (ge2gl_status s = memCheck(c, h, addr, size); s != GE2GL_OK) return s;
        if (c.glReachable()) {
            if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
            h->engine->renderer()->syncMemoryForRead(addr, size);
        } else if (h->engine->renderer()->holdsNewerThanMemory(addr, size)) {
            return c.error(GE2GL_ERR_WRONG_THREAD,
                           "the GPU holds newer pixels in this range and GL_CURRENT's context is on the creating "
                           "thread: read from there, or after the list completes (VRAM is written back then)");
        }
        h->mem->read(addr, dst, size);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_mem_pointer(ge2gl_context* h, uint32_t addr, uint32_t size, uint8_t** out) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL");
        *out = h->mem->ptr(addr, size);
        return *out ? GE2GL_OK : memCheck(c, h, addr, size == 0 ? 1 : size);
    });
}

ge2gl_status ge2gl_mem_written(ge2gl_context* h, uint32_t addr, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, writeKind(addr));
        if (ge2gl_status s = memCheck(c, h, addr, size); s != GE2GL_OK) return s;
        if (h->rendering || !c.glReachable()) {
            h->pendingWrites.emplace_back(addr, size);  // applyDeferred / the next GL call hands it over
            return GE2GL_OK;
        }
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        h->engine->renderer()->memoryWritten(addr, size);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_sync_range(ge2gl_context* h, uint32_t addr, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (ge2gl_status s = memCheck(c, h, addr, size); s != GE2GL_OK) return s;
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        h->engine->renderer()->syncMemoryForRead(addr, size);
        return GE2GL_OK;
    });
}

// ---- sceGe ----

static ge2gl_status enqueue(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid, const ge2gl_list_args* args,
                            int32_t* outId, bool head) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        ge::SceListArgs a;
        if (args) {
            a.size = args->size;
            a.contextAddr = args->context;
            a.numStacks = args->num_stacks;
            a.stackAddr = args->stacks;
        }
        // The CPU wrote the list's textures, CLUTs and perhaps frame buffers before queueing it.
        tellHostMayHaveWritten(h, true);
        return c.sceResult(h->sce->listEnqueue(list, stall, cbid, args ? &a : nullptr, head), outId);
    });
}

ge2gl_status ge2gl_list_enqueue(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid,
                                const ge2gl_list_args* args, int32_t* out_id) {
    return enqueue(h, list, stall, cbid, args, out_id, false);
}

ge2gl_status ge2gl_list_enqueue_head(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid,
                                     const ge2gl_list_args* args, int32_t* out_id) {
    return enqueue(h, list, stall, cbid, args, out_id, true);
}

ge2gl_status ge2gl_list_dequeue(ge2gl_context* h, int32_t id) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->listDequeue(id), nullptr);
    });
}

ge2gl_status ge2gl_list_update_stall(ge2gl_context* h, int32_t id, uint32_t stall) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        // Data for the commands up to the new stall may be new (textures; frame buffers are
        // checked at enqueue and continue only: a per-stall check would hash them per block).
        tellHostMayHaveWritten(h, false);
        return c.sceResult(h->sce->listUpdateStallAddr(id, stall), nullptr);
    });
}

ge2gl_status ge2gl_break(ge2gl_context* h, int32_t mode, int32_t* out_id) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->breakList(mode), out_id);
    });
}

ge2gl_status ge2gl_continue(ge2gl_context* h) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        h->engine->renderer()->hostMayHaveWritten(true);
        return c.sceResult(h->sce->continueList(), nullptr);
    });
}

ge2gl_status ge2gl_set_callback(ge2gl_context* h, uint32_t signal_func, uint32_t signal_arg, uint32_t finish_func,
                                uint32_t finish_arg, int32_t* out_cbid) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->setCallback(signal_func, signal_arg, finish_func, finish_arg), out_cbid);
    });
}

ge2gl_status ge2gl_unset_callback(ge2gl_context* h, int32_t cbid) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->unsetCallback(cbid), nullptr);
    });
}

ge2gl_status ge2gl_save_context(ge2gl_context* h, uint32_t ctx[512]) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!ctx) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "ctx is NULL");
        return c.sceResult(h->sce->saveContext(ctx), nullptr);
    });
}

ge2gl_status ge2gl_restore_context(ge2gl_context* h, const uint32_t ctx[512]) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!ctx) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "ctx is NULL");
        return c.sceResult(h->sce->restoreContext(ctx), nullptr);
    });
}

ge2gl_status ge2gl_save_context_at(ge2gl_context* h, uint32_t guest_addr) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->saveContextTo(guest_addr), nullptr);
    });
}

ge2gl_status ge2gl_restore_context_at(ge2gl_context* h, uint32_t guest_addr) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        return c.sceResult(h->sce->restoreContextFrom(guest_addr), nullptr);
    });
}

ge2gl_status ge2gl_get_cmd(ge2gl_context* h, uint32_t op, uint32_t* out_word) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out_word) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_word is NULL");
        return c.sceResult(h->sce->getCmd(op, out_word), nullptr);
    });
}

ge2gl_status ge2gl_set_sdk_version(ge2gl_context* h, uint32_t version) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        h->sce->setSdkVersion(version);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_get_registers(ge2gl_context* h, uint32_t out[256]) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL");
        for (u32 op = 0; op < 0xFF; ++op) {
            s32 r = h->sce->getCmd(op, &out[op]);
            if (r < 0) return c.sceResult(r, nullptr);
        }
        out[0xFF] = 0;
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_get_stack(ge2gl_context* h, int32_t index, uint32_t out[8], int32_t* out_depth) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        s32 r = h->sce->getStack(index, out);
        if (r >= 0 && out_depth) *out_depth = r;
        return c.sceResult(r, nullptr);
    });
}

ge2gl_status ge2gl_get_matrix(ge2gl_context* h, int32_t type, uint32_t out[16], int32_t* out_count) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL");
        int n = 0;
        s32 r = h->sce->getMtx(type, out, &n);
        if (r >= 0 && out_count) *out_count = n;
        return c.sceResult(r, nullptr);
    });
}

ge2gl_status ge2gl_edram_set_translation(ge2gl_context* h, uint32_t value, uint32_t* out_previous) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        s32 r = h->sce->edramSetAddrTranslation(value);
        if (r >= 0 && out_previous) *out_previous = u32(r);
        return c.sceResult(r, nullptr);
    });
}

ge2gl_status ge2gl_edram_get_addr(ge2gl_context* h, uint32_t* out) {
    return guarded(h, [&]() -> ge2gl_status {
        if (!out) return GE2GL_ERR_INVALID_ARGUMENT;
        *out = ge::SceGe::edramGetAddr();
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_edram_get_size(ge2gl_context* h, uint32_t* out) {
    return guarded(h, [&]() -> ge2gl_status {
        if (!out) return GE2GL_ERR_INVALID_ARGUMENT;
        *out = ge::SceGe::edramGetSize();
        return GE2GL_OK;
    });
}

}  // extern "C"
