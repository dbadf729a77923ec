// The C ABI of the plugin (include/ge2gl/ge2gl.h) over SceGe + GeEngine + a backend.
//
// Every entry point catches C++ exceptions (allocation failures) and turns them into status codes:
// nothing throws across the C boundary. One recursive mutex per handle serialises calls; it is
// recursive so that host callbacks, which run inside ge2gl_run/sync on the thread running the GE,
// can call back into the API.
#define GE2GL_BUILDING_LIBRARY 1
#include "ge2gl/ge2gl.h"

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "hle/ge_engine.h"
#include "hle/memory.h"
#include "hle/pixel_format.h"
#include "hle/sce_ge.h"

#include "softmodel/soft_renderer.h"
#ifdef GE2GL_HAVE_GL
#include "translator/gl_renderer.h"
#endif

namespace {

using ge::s32;
using ge::u32;
using ge::u64;
using ge::u8;

// Commands the worker executes between two looks at the lock (keeps API calls responsive).
constexpr u64 kWorkerSlice = 1u << 14;

class CListener : public ge::SceGeListener {
public:
    ge2gl_callbacks cb{};

    static ge2gl_interrupt convert(const ge::SceInterrupt& in) {
        ge2gl_interrupt out{};
        out.list_id = in.listId;
        out.cbid = in.cbid;
        out.registered = in.registered ? 1 : 0;
        out.behaviour = in.behaviour;
        out.arg = in.arg;
        out.pc = in.pc;
        out.end_arg = in.endArg;
        out.func = in.func;
        out.func_arg = in.funcArg;
        return out;
    }
    void onSignal(const ge::SceInterrupt& in) override {
        if (!cb.signal) return;
        ge2gl_interrupt irq = convert(in);
        cb.signal(cb.user, &irq);
    }
    void onFinish(const ge::SceInterrupt& in) override {
        if (!cb.finish) return;
        ge2gl_interrupt irq = convert(in);
        irq.behaviour = 0;
        cb.finish(cb.user, &irq);
    }
    void onEnd(s32 listId, u32 pc) override {
        if (cb.end) cb.end(cb.user, listId, pc);
    }
    void onError(s32 listId, u32 pc, const std::string& message) override {
        if (cb.error) cb.error(cb.user, listId, pc, message.c_str());
    }
    void onProgress(s32 listId, u32 pc) override {
        if (cb.progress) cb.progress(cb.user, listId, pc);
    }
};

}  // namespace

struct ge2gl_context {
    std::unique_ptr<u8[]> ownedRam;  // only when the host gives VRAM but not RAM
    std::unique_ptr<ge::Memory> mem;
    std::unique_ptr<ge::Renderer> renderer;  // null for GE2GL_BACKEND_NULL (the engine's own null backend)
    std::unique_ptr<ge::GeEngine> engine;
    std::unique_ptr<ge::SceGe> sce;
    CListener listener;
    int backend = GE2GL_BACKEND_NULL;
    u64 waitBudget = u64(1) << 26;

    std::recursive_mutex mu;
    std::string message;

    // Worker-thread mode.
    bool workerMode = false;
    bool quit = false;
    std::thread worker;
    std::thread::id workerId;
    std::condition_variable_any wake;   // work may be available
    std::condition_variable_any idle;   // the worker made progress or stopped
    u64 workerCommands = 0;

    void workerLoop();
};

void ge2gl_context::workerLoop() {
    std::unique_lock<std::recursive_mutex> lk(mu);
    while (!quit) {
        if (sce->canProgress()) {
            ge::SceRunResult r = sce->run(kWorkerSlice);
            workerCommands += r.commands;
            idle.notify_all();
            // Let host threads in between slices.
            lk.unlock();
            std::this_thread::yield();
            lk.lock();
            continue;
        }
        idle.notify_all();
        wake.wait(lk);
    }
    idle.notify_all();
}

namespace {

// Per-call guard: locks the handle, clears the message, wakes the worker afterwards.
class Call {
public:
    explicit Call(ge2gl_context* h) : h_(h), lk_(h->mu) {
        h_->message.clear();
        h_->sce->clearMessage();
    }
    ~Call() {
        if (h_->workerMode) h_->wake.notify_all();
    }
    std::unique_lock<std::recursive_mutex>& lock() { return lk_; }
    // Turns an sceGe result into a status and out-value: values >= 0 are results, < 0 errors.
    ge2gl_status sceResult(s32 r, int32_t* out) {
        if (r < 0) return error(r, h_->sce->lastMessage());
        if (out) *out = r;
        return GE2GL_OK;
    }
    ge2gl_status error(ge2gl_status s, const std::string& msg) {
        h_->message = msg.empty() ? ge2gl_status_name(s) : msg;
        return s;
    }

private:
    ge2gl_context* h_;
    std::unique_lock<std::recursive_mutex> lk_;
};

template <class F>
ge2gl_status guarded(ge2gl_context* h, F&& f) {
    if (!h) return GE2GL_ERR_INVALID_HANDLE;
    try {
        return f();
    } catch (const std::bad_alloc&) {
        h->message = "out of host memory";
        return GE2GL_ERR_OUT_OF_HOST_MEMORY;
    } catch (...) {
        h->message = "internal error";
        return GE2GL_ERR_BAD_STATE;
    }
}

bool onWorkerThread(const ge2gl_context* h) { return h->workerMode && std::this_thread::get_id() == h->workerId; }

// Worker mode: waits until `done` holds, or the GE cannot progress, or the wait budget is spent.
// Returns true when `done` holds.
template <class Pred>
bool waitWorker(ge2gl_context* h, std::unique_lock<std::recursive_mutex>& lk, Pred done, std::string& why) {
    const u64 start = h->workerCommands;
    h->wake.notify_all();
    for (;;) {
        if (done()) return true;
        if (!h->sce->canProgress()) {
            ge::SceRunResult r = h->sce->peekRun();
            char buf[120];
            std::snprintf(buf, sizeof buf, "the GE is %s at 0x%08x (stall 0x%08x)", ge::sceRunStateName(r.state), r.pc, r.stall);
            why = buf;
            return false;
        }
        if (h->workerCommands - start >= h->waitBudget) {
            why = "the wait budget was used up (a list that never ends?)";
            return false;
        }
        h->idle.wait(lk);
    }
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
    if (!cfg || !out) return GE2GL_ERR_INVALID_ARGUMENT;
    *out = nullptr;
    if (cfg->struct_size != sizeof(ge2gl_config) || (cfg->api_version >> 16) != GE2GL_API_VERSION_MAJOR ||
        (cfg->api_version & 0xFFFF) > GE2GL_API_VERSION_MINOR)
        return GE2GL_ERR_VERSION;
    if (cfg->backend < GE2GL_BACKEND_NULL || cfg->backend > GE2GL_BACKEND_GL_HEADLESS) return GE2GL_ERR_INVALID_ARGUMENT;
    const u32 ramSize = cfg->ram_size ? cfg->ram_size : ge::Memory::kDefaultRamSize;
    // RAM ends at 0x0C000000 in the PSP map (64 MiB models).
    if (ramSize > ge::Memory::kDefaultRamSize) return GE2GL_ERR_INVALID_ARGUMENT;
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
        switch (cfg->backend) {
        case GE2GL_BACKEND_NULL: break;
        case GE2GL_BACKEND_SOFT: {
            ge::soft::SoftOptions so;
            so.threads = cfg->soft_threads;  // the output is identical for any thread count
            h->renderer = ge::soft::createSoftRenderer(*h->mem, so);
            if (!h->renderer) return GE2GL_ERR_BACKEND;
            break;
        }
        default: {
            // A GL context belongs to one thread; the worker would draw on another.
            if (cfg->worker_thread) return GE2GL_ERR_UNSUPPORTED;
#ifdef GE2GL_HAVE_GL
            ge::gl::GlOptions go;
            go.context = cfg->backend == GE2GL_BACKEND_GL_CURRENT ? ge::gl::ContextKind::Current
                         : cfg->gl_use_egl                        ? ge::gl::ContextKind::EGL
                                                                  : ge::gl::ContextKind::OSMesa;
            std::string err;
            h->renderer = ge::gl::createGlRenderer(*h->mem, go, err);
            if (!h->renderer) return GE2GL_ERR_BACKEND;
            break;
#else
            return GE2GL_ERR_BACKEND;  // built without GE2GL_BUILD_GL
#endif
        }
        }
        h->engine = std::make_unique<ge::GeEngine>(*h->mem, h->renderer.get());
        h->sce = std::make_unique<ge::SceGe>(*h->engine);
        h->listener.cb = cfg->callbacks;
        h->sce->setListener(&h->listener);
        h->sce->setSdkVersion(cfg->sdk_version ? cfg->sdk_version : ge::SceGe::kDefaultSdkVersion);
        h->waitBudget = cfg->wait_budget ? cfg->wait_budget : (u64(1) << 26);
        h->sce->setWaitBudget(h->waitBudget);
        if (cfg->worker_thread) {
            h->workerMode = true;
            h->worker = std::thread([p = h.get()] { p->workerLoop(); });
            h->workerId = h->worker.get_id();
        }
        *out = h.release();
        return GE2GL_OK;
    } catch (const std::bad_alloc&) {
        return GE2GL_ERR_OUT_OF_HOST_MEMORY;
    } catch (...) {
        return GE2GL_ERR_BACKEND;
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
    // The SceGe detaches from the engine, the engine from the renderer, in this order.
    h->sce.reset();
    h->engine.reset();
    h->renderer.reset();
    delete h;
}

const char* ge2gl_last_message(ge2gl_context* h) {
    if (!h) return "invalid handle";
    return h->message.c_str();
}

// ---- Guest memory ----

ge2gl_status ge2gl_mem_write(ge2gl_context* h, uint32_t addr, const void* src, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!src && size) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "src is NULL");
        if (!h->mem->valid(addr, size)) return c.error(GE2GL_ERR_MEMORY, "range outside guest memory");
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
        if (!h->mem->valid(addr, size)) return c.error(GE2GL_ERR_MEMORY, "range outside guest memory");
        h->engine->renderer()->syncMemoryForRead(addr, size);
        h->mem->read(addr, dst, size);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_mem_pointer(ge2gl_context* h, uint32_t addr, uint32_t size, uint8_t** out) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL");
        *out = h->mem->ptr(addr, size);
        return *out ? GE2GL_OK : c.error(GE2GL_ERR_MEMORY, "range outside guest memory");
    });
}

ge2gl_status ge2gl_mem_written(ge2gl_context* h, uint32_t addr, uint32_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!h->mem->valid(addr, size)) return c.error(GE2GL_ERR_MEMORY, "range outside guest memory");
        h->engine->renderer()->memoryWritten(addr, size);
        return GE2GL_OK;
    });
}

// ---- sceGe ----

static ge2gl_status enqueue(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid, const ge2gl_list_args* args,
                            int32_t* outId, bool head) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        ge::SceListArgs a;
        if (args) {
            a.size = args->size;
            a.contextAddr = args->context;
            a.numStacks = args->num_stacks;
            a.stackAddr = args->stacks;
        }
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
        Call c(h);
        return c.sceResult(h->sce->listUpdateStallAddr(id, stall), nullptr);
    });
}

ge2gl_status ge2gl_list_sync(ge2gl_context* h, int32_t id, int32_t mode, int32_t* out_state) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (mode == GE2GL_SYNC_WAIT && h->workerMode) {
            if (onWorkerThread(h)) return c.error(GE2GL_ERR_REENTRANT, "a wait-mode sync cannot run from inside a GE callback");
            // Validate the ID first (peek), then let the worker do the work.
            s32 r = h->sce->listSync(id, GE2GL_SYNC_PEEK);
            if (r < 0 && r != ge::sce::kErrorInvalidId) return c.sceResult(r, nullptr);
            if (r == ge::sce::kErrorInvalidId) {
                if (h->sce->listState(id) == ge::SceListState::None && (u32(id) ^ ge::SceGe::kIdMask) < 64u) {
                    if (out_state) *out_state = GE2GL_LIST_COMPLETED;  // free slot: nothing to wait for
                    return GE2GL_OK;
                }
                return c.sceResult(r, nullptr);
            }
            std::string why;
            auto done = [&] {
                ge::SceListState s = h->sce->listState(id);
                return s == ge::SceListState::Completed || s == ge::SceListState::None;
            };
            if (!waitWorker(h, c.lock(), done, why)) return c.error(GE2GL_ERR_WOULD_BLOCK, "list cannot complete: " + why);
            if (out_state) *out_state = GE2GL_LIST_COMPLETED;
            return GE2GL_OK;
        }
        return c.sceResult(h->sce->listSync(id, mode), out_state);
    });
}

ge2gl_status ge2gl_draw_sync(ge2gl_context* h, int32_t mode, int32_t* out_state) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (mode == GE2GL_SYNC_WAIT && h->workerMode) {
            if (onWorkerThread(h)) return c.error(GE2GL_ERR_REENTRANT, "a wait-mode sync cannot run from inside a GE callback");
            std::string why;
            auto done = [&] { return h->sce->drawSync(GE2GL_SYNC_PEEK) == GE2GL_LIST_COMPLETED; };
            if (!waitWorker(h, c.lock(), done, why)) return c.error(GE2GL_ERR_WOULD_BLOCK, "drawing cannot complete: " + why);
            // The queue is empty: this only frees the completed lists.
        }
        return c.sceResult(h->sce->drawSync(mode), out_state);
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
        Call c(h);
        if (!out_word) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_word is NULL");
        return c.sceResult(h->sce->getCmd(op, out_word), nullptr);
    });
}

ge2gl_status ge2gl_get_matrix(ge2gl_context* h, int32_t type, uint32_t out[16], int32_t* out_count) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
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

// ---- Execution ----

ge2gl_status ge2gl_run(ge2gl_context* h, uint64_t max_commands, ge2gl_run_info* out) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (h->workerMode) return c.error(GE2GL_ERR_BAD_STATE, "the worker thread runs the GE; use the sync functions to wait");
        ge::SceRunResult r = max_commands ? h->sce->run(max_commands) : h->sce->peekRun();
        if (r.state == ge::SceRunState::Reentrant)
            return c.error(GE2GL_ERR_REENTRANT, "ge2gl_run cannot be called from inside a GE callback");
        if (out) {
            switch (r.state) {
            case ge::SceRunState::Idle: out->ge_state = GE2GL_GE_IDLE; break;
            case ge::SceRunState::Stalled: out->ge_state = GE2GL_GE_STALLED; break;
            case ge::SceRunState::Paused: out->ge_state = GE2GL_GE_PAUSED; break;
            case ge::SceRunState::Hung: out->ge_state = GE2GL_GE_HUNG; break;
            default: out->ge_state = GE2GL_GE_READY; break;
            }
            out->list_id = r.listId;
            out->pc = r.pc;
            out->stall = r.stall;
            out->commands = r.commands;
        }
        return GE2GL_OK;
    });
}

// ---- Frames ----

ge2gl_status ge2gl_read_frame(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                              uint32_t height, uint8_t* out_rgba, size_t out_size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (format < GE2GL_FORMAT_565 || format > GE2GL_FORMAT_8888) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown pixel format");
        if (!width || !height || width > 4096 || height > 4096 || stride < width || stride > 4096)
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "width/height must be 1-4096 and stride at least width (at most 4096)");
        if (!out_rgba || out_size < size_t(width) * height * 4) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "output buffer too small");
        const ge::GeBufferFormat fmt = ge::GeBufferFormat(format);
        const u32 bpp = ge::bytesPerPixel(fmt);
        const u32 bytes = ((height - 1) * stride + width) * bpp;
        ge::Renderer* r = h->engine->renderer();
        r->flushToMemory();
        r->syncMemoryForRead(addr, bytes);
        const u8* src = h->mem->ptr(addr, bytes);
        if (!src) return c.error(GE2GL_ERR_MEMORY, "frame buffer range outside guest memory");
        // Convert into aligned words, then store them byte by byte (R first) into the host buffer,
        // which need not be 4-byte aligned.
        std::vector<u32> px(size_t(width) * height);
        ge::convertToRGBA8888(src, fmt, width, height, stride, px.data());
        for (size_t k = 0; k < px.size(); ++k) ge::writeLE32(out_rgba + 4 * k, px[k]);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_frame_texture(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format, uint32_t width,
                                 uint32_t height, uint32_t* out_texture) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_texture) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_texture is NULL");
        if (format < GE2GL_FORMAT_565 || format > GE2GL_FORMAT_8888) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown pixel format");
        if (!width || !height || width > 4096 || height > 4096 || stride < width || stride > 4096)
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "width/height must be 1-4096 and stride at least width (at most 4096)");
        if (h->backend != GE2GL_BACKEND_GL_CURRENT && h->backend != GE2GL_BACKEND_GL_HEADLESS)
            return c.error(GE2GL_ERR_UNSUPPORTED, "this backend has no GL textures");
#ifdef GE2GL_HAVE_GL
        const ge::GeBufferFormat fmt = ge::GeBufferFormat(format);
        const u32 bytes = ((height - 1) * stride + width) * ge::bytesPerPixel(fmt);
        if (!h->mem->valid(addr, bytes) || !ge::Memory::isVram(addr))
            return c.error(GE2GL_ERR_MEMORY, "frame buffer range is not inside VRAM");
        const unsigned tex = ge::gl::glFrameTexture(*h->renderer, addr, stride, fmt);
        if (!tex) return c.error(GE2GL_ERR_BACKEND, "the GL backend could not produce the frame texture");
        *out_texture = tex;
        return GE2GL_OK;
#else
        (void)addr;
        return c.error(GE2GL_ERR_UNSUPPORTED, "built without GL");
#endif
    });
}

}  // extern "C"
