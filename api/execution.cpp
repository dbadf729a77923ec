// SPDX-License-Identifier: MIT
// Running the GE for the plugin API: the call guard, interrupt delivery without the lock, the
// chunked run loop, waits, the worker thread, the peek snapshot and held interrupts (context.h).
#include "api/context.h"

#include <cstdio>
#include <functional>

namespace ge2gl_impl {

namespace {

std::string hex8(u32 v) {
    char b[12];
    std::snprintf(b, sizeof b, "%08x", v);
    return b;
}

// A run stopped at a draw cut at config.run_budget_us (SceRunState::TimeLimit): what and where.
std::string timeCutMessage(const ge2gl_context* h, u32 pc) {
    return "the draw before 0x" + hex8(pc) + " took more than config.run_budget_us of GE time and was cut there (" +
           h->lastDrop + "); the list goes on after it at the next call";
}

ge2gl_interrupt convert(const ge::SceInterrupt& in) {
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
    out.tick = in.tick;
    return out;
}

// The GL scope (context.h): only entered for a backend that offers a HostContextUser.
void glLeave(ge2gl_context* h) { h->drawBackend.host->hostLeave(); }

bool glEnter(ge2gl_context* h, std::string& err) { return h->drawBackend.host->hostEnter(err); }

// Applies mem_written ranges queued by threads that could not reach the GL context or came
// while a draw was in progress. Straight to the backend: the caller holds the lock.
void applyPendingWrites(ge2gl_context* h) {
    if (ge::Renderer* r = h->drawBackend.renderer.get())
        for (auto [a, n] : h->pendingWrites) r->memoryWritten(a, n);
    h->pendingWrites.clear();
}

}  // namespace

void applyDeferred(ge2gl_context* h) {
    if (h->pendingHostWrote) {
        if (ge::Renderer* r = h->drawBackend.renderer.get()) r->hostMayHaveWritten(h->pendingHostWroteFb);
        h->pendingHostWrote = h->pendingHostWroteFb = false;
    }
    // GL_CURRENT's writes from other threads wait for GL (the next call that enters it).
    if (!h->pendingWrites.empty() && (!h->drawBackend.host || h->runGl)) applyPendingWrites(h);
}

void tellHostMayHaveWritten(ge2gl_context* h, bool frameBuffers) {
    if (h->rendering) {
        h->pendingHostWrote = true;
        h->pendingHostWroteFb = h->pendingHostWroteFb || frameBuffers;
        return;
    }
    h->engine->renderer()->hostMayHaveWritten(frameBuffers);
}

// ---- Interrupt delivery -------------------------------------------------------------------

// Runs a host callback with the handle's lock released and the GL scope left, so the callback
// may block on a host thread that calls into ge2gl meanwhile (docs/plugin-api.md "Threads"). The
// GE stands between two commands here (the engine reports interrupts from command boundaries),
// and the lists' states are what the firmware shows during the handler; other threads may
// update stalls, enqueue, break or continue in the meantime, as a callback itself may.
template <class F>
void CListener::deliver(F&& f) {
    std::unique_lock<std::recursive_mutex>* lk = h->runLock;
    if (!lk) {  // not from a run (cannot happen: interrupts arise only while the GE runs)
        f();
        return;
    }
    const bool gl = h->runGl;
    if (gl) glLeave(h);
    refreshSnapshot(h);
    h->deliverThread = std::this_thread::get_id();
    h->runLock = nullptr;
    lk->unlock();
    f();
    lk->lock();
    h->runLock = lk;
    h->deliverThread = std::thread::id();
    if (gl) {
        std::string err;
        if (!glEnter(h, err)) {
            // The context cannot come back to this thread: stop the run; the caller reports it.
            h->runGl = false;
            h->sce->requestYield();
            h->message = "GL context lost during a callback: " + err;
        }
    }
}

void CListener::onSignal(const ge::SceInterrupt& in) {
    if (h->holdInterrupts) {
        h->held = true;
        h->sce->requestYield();
    }
    if (!cb.signal) return;
    ge2gl_interrupt irq = convert(in);
    deliver([&] { cb.signal(cb.user, &irq); });
}

void CListener::onFinish(const ge::SceInterrupt& in) {
    // The list is complete: VRAM holds what it drew before the host hears of it (coherence).
    if (!h->drawBackend.host || h->runGl) {
        if (!h->lazyWriteback) h->engine->renderer()->flushToMemory();
        else announceDirty(h);
    }
    if (h->holdInterrupts) {
        h->held = true;
        h->sce->requestYield();
    }
    if (!cb.finish) return;
    ge2gl_interrupt irq = convert(in);
    irq.behaviour = 0;
    deliver([&] { cb.finish(cb.user, &irq); });
}

void CListener::onEnd(s32 listId, u32 pc) {
    if (cb.end) deliver([&] { cb.end(cb.user, listId, pc); });
}

void CListener::onError(s32 listId, u32 pc, const std::string& message) {
    if (!cb.error) return;
    const std::string copy = message;  // the engine's message may change while unlocked
    deliver([&] { cb.error(cb.user, listId, pc, copy.c_str()); });
}

void CListener::onDrop(s32 listId, u32 pc, const std::string& message) {
    h->lastDrop = message;
    if (!h->drop) return;
    const std::string copy = message;
    auto* fn = h->drop;
    deliver([&] { fn(cb.user, listId, pc, copy.c_str()); });
}

void CListener::onProgress(s32 listId, u32 pc) {
    if (cb.progress) deliver([&] { cb.progress(cb.user, listId, pc); });
}

void announceDirty(ge2gl_context* h) {
    if (!h->lazyWriteback || !h->vramDirty || !h->drawBackend.renderer) return;
    std::vector<std::pair<u32, u32>> ranges;
    h->engine->renderer()->takeDirtyRanges(ranges);
    if (ranges.empty()) return;
    void* user = h->listener.cb.user;
    auto* fn = h->vramDirty;
    if (std::unique_lock<std::recursive_mutex>* lk = h->runLock) {
        // Same rules as any callback: no lock held, GL scope left.
        const bool gl = h->runGl;
        if (gl) glLeave(h);
        h->deliverThread = std::this_thread::get_id();
        h->runLock = nullptr;
        lk->unlock();
        for (auto [a, n] : ranges) fn(user, a, n);
        lk->lock();
        h->runLock = lk;
        h->deliverThread = std::thread::id();
        std::string err;
        if (gl && !glEnter(h, err)) h->runGl = false;
    } else {
        for (auto [a, n] : ranges) fn(user, a, n);
    }
}

// ---- Call guard ---------------------------------------------------------------------------

Call::Call(ge2gl_context* h, CallKind kind) : h_(h), lk_(h->mu, std::defer_lock) {
    h_->waiters.fetch_add(1);
    lk_.lock();
    // Still counted as a waiter: the GE thread lets it in at the next chunk boundary.
    if (kind == CallKind::Waits) h_->renderIdle.wait(lk_, [h] { return !h->rendering; });
    h_->waiters.fetch_sub(1);
    h_->message.clear();
    h_->sce->clearMessage();
}

Call::~Call() {
    if (glEntered_) glLeave(h_);
    refreshSnapshot(h_);
    if (h_->workerMode) h_->wake.notify_all();
}

bool Call::glReachable() const {
    return h_->backend != GE2GL_BACKEND_GL_CURRENT || std::this_thread::get_id() == h_->glThread;
}

ge2gl_status Call::gl() {
    if (!h_->drawBackend.host || glEntered_) return GE2GL_OK;
    if (!glReachable())
        return error(GE2GL_ERR_WRONG_THREAD,
                     "GL_CURRENT draws on the host's context, current on the thread that created the handle; "
                     "call this from that thread");
    std::string err;
    if (!glEnter(h_, err)) {
        // GL_CURRENT enters by checking that the host's context is the one it was created with.
        if (h_->backend == GE2GL_BACKEND_GL_CURRENT) return error(GE2GL_ERR_GL_CONTEXT, err);
        return error(GE2GL_ERR_BACKEND, "cannot make the GL context current here: " + err);
    }
    glEntered_ = true;
    applyPendingWrites(h_);
    return GE2GL_OK;
}

ge2gl_status Call::sceResult(s32 r, int32_t* out) {
    if (r < 0) return error(r, h_->sce->lastMessage());
    if (out) *out = r;
    return GE2GL_OK;
}

ge2gl_status Call::error(ge2gl_status s, const std::string& msg) {
    h_->message = msg.empty() ? ge2gl_status_name(s) : msg;
    return s;
}

// ---- Snapshot, runs, waits ----------------------------------------------------------------

void refreshSnapshot(ge2gl_context* h) {
    // Free slots are answered the locked way (their error carries a message): only lists that
    // exist are asked, so a call costs a few state reads, not 64 formatted errors.
    std::array<s32, ge::SceGe::kMaxLists> lists;
    for (int i = 0; i < ge::SceGe::kMaxLists; ++i) {
        const s32 id = s32(u32(i) ^ ge::SceGe::kIdMask);
        lists[size_t(i)] = h->sce->listState(id) == ge::SceListState::None ? ge::sce::kErrorInvalidId
                                                                             : h->sce->listSync(id, 1);
    }
    const s32 draw = h->sce->drawSync(1);
    std::lock_guard<std::mutex> g(h->snapMu);
    h->peekList = lists;
    h->peekDraw = draw;
}

bool reentrant(const ge2gl_context* h) {
    const std::thread::id me = std::this_thread::get_id();
    return h->deliverThread == me || (h->workerMode && me == h->workerId);
}

bool refuseMidRunCommand(const ge2gl_context* h) { return reentrant(h) || h->sce->inRun(); }

ge::SceRunResult drive(ge2gl_context* h, Call& c, u64 budget, s32 stopAfter) {
    h->runLock = &c.lock();
    h->runThread = std::this_thread::get_id();
    h->runGl = c.glEntered();
    ge::SceRunResult r = h->sce->peekRun();
    u64 used = 0;
    while (used < budget && !h->held) {
        const ge::SceListState before = stopAfter >= 0 ? h->sce->listState(stopAfter) : ge::SceListState::None;
        r = stopAfter >= 0 ? h->sce->runUntil(std::min(kChunk, budget - used), stopAfter)
                           : h->sce->run(std::min(kChunk, budget - used));
        used += r.commands;
        announceDirty(h);
        refreshSnapshot(h);
        if (h->debugger && r.state == ge::SceRunState::Idle) h->debugger->frameEnded();
        if (r.state != ge::SceRunState::Budget || r.commands == 0) break;
        if (stopAfter >= 0 && before != ge::SceListState::Completed && h->sce->listState(stopAfter) == ge::SceListState::Completed)
            break;
        if (c.glEntered() && !h->runGl) break;  // the context could not come back (message set)
        if (h->waiters.load() > 0) {
            // Let waiting callers in (a stall update, a peek of a failed list, a host read).
            const bool gl = h->runGl;
            if (gl) glLeave(h);
            c.lock().unlock();
            std::this_thread::yield();
            c.lock().lock();
            std::string err;
            if (gl && !glEnter(h, err)) {
                h->runGl = false;
                h->message = "cannot make the GL context current again: " + err;
                break;
            }
        }
    }
    h->runLock = nullptr;
    r.commands = used;
    return r;
}

bool waitUntil(ge2gl_context* h, Call& c, const std::function<bool()>& done, std::string& why, s32 stopAfter) {
    h->timeCut = false;
    auto stuck = [&](const ge::SceRunResult& r) {
        char buf[160];
        if (h->held)
            std::snprintf(buf, sizeof buf, "an interrupt is held (config.hold_interrupts): call ge2gl_interrupt_ack");
        else
            std::snprintf(buf, sizeof buf, "the GE is %s at 0x%08x (stall 0x%08x)", ge::sceRunStateName(r.state), r.pc,
                          r.stall);
        why = buf;
    };
    if (!h->workerMode) {
        u64 used = 0;
        for (;;) {
            if (done()) return true;
            if (h->held || !h->sce->canProgress()) {
                stuck(h->sce->peekRun());
                return false;
            }
            if (used >= h->waitBudget) {
                why = "the wait budget was used up (a list that never ends?)";
                return false;
            }
            const ge::SceRunResult r = drive(h, c, std::min<u64>(h->waitBudget - used, u64(1) << 20), stopAfter);
            used += r.commands;
            if (r.state == ge::SceRunState::TimeLimit) {
                h->timeCut = true;
                why = timeCutMessage(h, r.pc);
                return false;
            }
            if (r.commands == 0 && !done() && h->sce->canProgress() && !h->held) {
                why = h->message.empty() ? "the GE made no progress" : h->message;
                return false;
            }
        }
    }
    const u64 start = h->workerCommands;
    h->wake.notify_all();
    for (;;) {
        if (done()) return true;
        if (h->held || !h->sce->canProgress()) {
            stuck(h->sce->peekRun());
            return false;
        }
        if (h->workerCommands - start >= h->waitBudget) {
            why = "the wait budget was used up (a list that never ends?)";
            return false;
        }
        h->idle.wait(c.lock());
    }
}

}  // namespace ge2gl_impl

using namespace ge2gl_impl;

void ge2gl_context::workerLoop() {
    std::unique_lock<std::recursive_mutex> lk(mu);
    while (!quit) {
        if (!held && sce->canProgress()) {
            if (waiters.load() > 0) {
                lk.unlock();
                std::this_thread::yield();
                lk.lock();
                continue;
            }
            std::string err;
            const bool gl = drawBackend.host && glEnter(this, err);
            if (drawBackend.host && !gl) {
                // The context is busy elsewhere (a host thread inside a call holds it current
                // cannot happen: calls hold the lock). Report and wait for the next kick.
                message = "worker: " + err;
                wake.wait(lk);
                continue;
            }
            if (gl) applyPendingWrites(this);
            runLock = &lk;
            runThread = std::this_thread::get_id();
            runGl = gl;
            const ge::SceRunResult r = sce->run(kChunk);
            announceDirty(this);
            runLock = nullptr;
            if (runGl) glLeave(this);
            runGl = false;
            workerCommands += r.commands;
            refreshSnapshot(this);
            idle.notify_all();
            continue;
        }
        idle.notify_all();
        wake.wait(lk);
    }
    idle.notify_all();
}

namespace ge2gl_impl {

ge2gl_status runFor(ge2gl_context* h, uint64_t max_commands, uint64_t tick, ge2gl_run_info* out) {
    Call c(h);
    if (h->workerMode) return c.error(GE2GL_ERR_BAD_STATE, "the worker thread runs the GE; use the sync functions to wait");
    if (reentrant(h)) return c.error(GE2GL_ERR_REENTRANT, "ge2gl_run cannot be called from inside a GE callback");
    ge::SceRunResult r = h->sce->peekRun();
    if (max_commands && !h->held && h->sce->canProgress()) {
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        // The call's GE-time budget ends the run between commands like a tick (no draw is cut).
        const u64 now = h->engine->stats().cycles;
        if (h->runBudget != ~u64(0)) tick = std::min<u64>(tick, now + std::min(h->runBudget, ~u64(0) - now - 1));
        h->sce->setTickStop(tick);
        r = drive(h, c, max_commands);
        h->sce->setTickStop(~u64(0));
        // The software model rasterises on band threads behind the GE. When the GE stops where the
        // host may write guest memory itself (a stall, idle, a pause, a held interrupt), those
        // draws finish first: a host write in place must land after the draws issued before it.
        // With the lock released like any draw (render_gate.h).
        if (h->backend == GE2GL_BACKEND_SOFT && (r.state != ge::SceRunState::Budget || h->held)) {
            h->runLock = &c.lock();
            h->runThread = std::this_thread::get_id();
            h->engine->renderer()->flushToMemory();
            h->runLock = nullptr;
        }
        if (r.state == ge::SceRunState::Reentrant)
            return c.error(GE2GL_ERR_REENTRANT, "ge2gl_run cannot be called from inside a GE callback");
    }
    ge2gl_status status = GE2GL_OK;
    if (r.state == ge::SceRunState::TimeLimit) {
        status = c.error(GE2GL_ERR_TIME_BUDGET, timeCutMessage(h, r.pc));
        r.state = ge::SceRunState::Budget;
    }
    if (out) {
        switch (r.state) {
        case ge::SceRunState::Idle: out->ge_state = GE2GL_GE_IDLE; break;
        case ge::SceRunState::Stalled: out->ge_state = GE2GL_GE_STALLED; break;
        case ge::SceRunState::Paused: out->ge_state = GE2GL_GE_PAUSED; break;
        case ge::SceRunState::Hung: out->ge_state = GE2GL_GE_HUNG; break;
        case ge::SceRunState::Break: out->ge_state = GE2GL_GE_BREAK; break;
        default: out->ge_state = GE2GL_GE_READY; break;
        }
        if (h->held) out->ge_state = GE2GL_GE_INTERRUPT;
        out->list_id = r.listId;
        out->pc = r.pc;
        out->stall = r.stall;
        out->commands = max_commands ? r.commands : 0;
    }
    return status;
}

}  // namespace ge2gl_impl

extern "C" {

ge2gl_status ge2gl_list_sync(ge2gl_context* h, int32_t id, int32_t mode, int32_t* out_state) {
    if (h && mode == GE2GL_SYNC_PEEK) {
        // From the snapshot: answers at once even while a list is drawing.
        const u32 slot = u32(id) ^ ge::SceGe::kIdMask;
        if (slot < u32(ge::SceGe::kMaxLists)) {
            s32 r;
            {
                std::lock_guard<std::mutex> g(h->snapMu);
                r = h->peekList[slot];
            }
            if (r >= 0) {
                if (out_state) *out_state = r;
                return GE2GL_OK;
            }
        }
        // Errors go the locked way, which sets the message.
    }
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, mode == GE2GL_SYNC_WAIT ? CallKind::Waits : CallKind::Light);
        if (mode != GE2GL_SYNC_WAIT) return c.sceResult(h->sce->listSync(id, mode), out_state);
        if (reentrant(h)) return c.error(GE2GL_ERR_REENTRANT, "a wait-mode sync cannot run from inside a GE callback");
        // Validate the ID first (peek), then wait.
        s32 r = h->sce->listSync(id, GE2GL_SYNC_PEEK);
        if (r < 0 && r != ge::sce::kErrorInvalidId) return c.sceResult(r, nullptr);
        if (r == ge::sce::kErrorInvalidId) {
            if (h->sce->listState(id) == ge::SceListState::None && (u32(id) ^ ge::SceGe::kIdMask) < 64u) {
                if (out_state) *out_state = GE2GL_LIST_COMPLETED;  // free slot: nothing to wait for
                return GE2GL_OK;
            }
            return c.sceResult(r, nullptr);
        }
        // The worker runs the GE (and holds the GL context while it does): only inline waits enter.
        if (!h->workerMode)
            if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        std::string why;
        auto done = [&] {
            ge::SceListState s = h->sce->listState(id);
            return s == ge::SceListState::Completed || s == ge::SceListState::None;
        };
        if (!waitUntil(h, c, done, why, id))
            return c.error(h->timeCut ? GE2GL_ERR_TIME_BUDGET : GE2GL_ERR_WOULD_BLOCK, "list cannot complete: " + why);
        if (out_state) *out_state = GE2GL_LIST_COMPLETED;
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_draw_sync(ge2gl_context* h, int32_t mode, int32_t* out_state) {
    if (h && mode == GE2GL_SYNC_PEEK) {
        s32 r;
        {
            std::lock_guard<std::mutex> g(h->snapMu);
            r = h->peekDraw;
        }
        if (r >= 0) {
            if (out_state) *out_state = r;
            return GE2GL_OK;
        }
    }
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, mode == GE2GL_SYNC_WAIT ? CallKind::Waits : CallKind::Light);
        if (mode == GE2GL_SYNC_WAIT) {
            if (reentrant(h)) return c.error(GE2GL_ERR_REENTRANT, "a wait-mode sync cannot run from inside a GE callback");
            if (!h->workerMode)
                if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
            std::string why;
            auto done = [&] { return h->sce->drawSync(GE2GL_SYNC_PEEK) == GE2GL_LIST_COMPLETED; };
            if (!waitUntil(h, c, done, why))
                return c.error(h->timeCut ? GE2GL_ERR_TIME_BUDGET : GE2GL_ERR_WOULD_BLOCK, "drawing cannot complete: " + why);
            // The queue is empty: this only frees the completed lists.
        }
        return c.sceResult(h->sce->drawSync(mode), out_state);
    });
}

ge2gl_status ge2gl_run(ge2gl_context* h, uint64_t max_commands, ge2gl_run_info* out) {
    return guarded(h, [&]() -> ge2gl_status { return runFor(h, max_commands, ~uint64_t(0), out); });
}

ge2gl_status ge2gl_run_until(ge2gl_context* h, uint64_t tick, ge2gl_run_info* out) {
    return guarded(h, [&]() -> ge2gl_status { return runFor(h, h->waitBudget, tick, out); });
}

ge2gl_status ge2gl_get_stats(ge2gl_context* h, ge2gl_stats* out) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out || out->struct_size < sizeof(ge2gl_stats))
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL or its struct_size is not sizeof(ge2gl_stats)");
        const ge::GeStats& st = h->engine->stats();
        out->commands = st.commands;
        out->draws = st.prims + st.patches;
        out->ge_ticks = st.cycles;
        out->draws_dropped = st.drawsDropped;
        out->draws_cut = st.drawsCut;
        std::snprintf(out->last_drop, sizeof out->last_drop, "%s", h->lastDrop.c_str());
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_get_tick(ge2gl_context* h, uint64_t* out_tick) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out_tick) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_tick is NULL");
        *out_tick = h->engine->stats().cycles;
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_list_ticks(ge2gl_context* h, int32_t id, uint64_t* out_ticks) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h, CallKind::Light);
        if (!out_ticks) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_ticks is NULL");
        const ge::s64 t = h->sce->listCycles(id);
        if (t < 0) return c.error(GE2GL_SCE_ERROR_INVALID_ID, "no list with this ID");
        *out_ticks = uint64_t(t);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_interrupt_ack(ge2gl_context* h) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!h->held) return c.error(GE2GL_ERR_BAD_STATE, "no interrupt is held");
        h->held = false;
        h->sce->handlersReturned();
        return GE2GL_OK;
    });
}

}  // extern "C"
