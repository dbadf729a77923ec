// SPDX-License-Identifier: MIT
// The plugin API's handle and the guard every entry point runs under (api/*.cpp).
//
// Locking (docs/plugin-api.md "Threads"): one recursive mutex per handle serialises calls. The
// thread that runs the GE (ge2gl_run, a wait, or the worker) holds it while it executes
// commands, in chunks of kChunk commands with waiting callers let in between; it releases it
// while the backend draws, flushes or writes back (RenderGate, render_gate.h: `rendering`), when
// light calls (Call::Light) go on and the others wait; and around every host callback
// (CListener::deliver), so a callback may block on another host thread that calls into ge2gl.
// Peek syncs read a snapshot of the list states (snapshot mutex only), refreshed after every
// chunk and every call, so they never wait for a draw.
//
// GL: a backend that works in a GL context offers backend/capabilities.h HostContextUser; a call
// that touches GL enters its host scope through Call::gl() — the headless context made current on
// this thread, or the host's state saved — and leaves it when the call returns; around callbacks
// the scope is left and re-entered.
#pragma once
#define GE2GL_BUILDING_LIBRARY 1
#include "ge2gl/ge2gl.h"

#include <array>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "backend/factory.h"
#include "debugger/debugger.h"
#include "hle/ge_engine.h"
#include "hle/memory.h"
#include "hle/sce_ge.h"

namespace ge2gl_impl {
class RenderGate;
}

namespace ge2gl_impl {

using ge::s32;
using ge::u32;
using ge::u64;
using ge::u8;

// Commands run between two looks at waiting callers and two snapshot refreshes.
constexpr u64 kChunk = 512;

class CListener : public ge::SceGeListener {
public:
    ge2gl_context* h = nullptr;
    ge2gl_callbacks cb{};
    void onSignal(const ge::SceInterrupt& in) override;
    void onFinish(const ge::SceInterrupt& in) override;
    void onEnd(s32 listId, u32 pc) override;
    void onError(s32 listId, u32 pc, const std::string& message) override;
    void onProgress(s32 listId, u32 pc) override;
    void onDrop(s32 listId, u32 pc, const std::string& message) override;

private:
    template <class F>
    void deliver(F&& f);
};

}  // namespace ge2gl_impl

struct ge2gl_context {
    std::unique_ptr<ge::u8[]> ownedRam;  // only when the host gives VRAM but not RAM
    std::unique_ptr<ge::Memory> mem;
    // The backend (backend/factory.h); its renderer is null for GE2GL_BACKEND_NULL (the engine's own
    // null backend).
    ge::backend::Backend drawBackend;
    std::unique_ptr<ge2gl_impl::RenderGate> gate;  // what the engine draws through (render_gate.h)
    std::unique_ptr<ge::GeEngine> engine;
    std::unique_ptr<ge::SceGe> sce;
    ge2gl_impl::CListener listener;
    int backend = GE2GL_BACKEND_NULL;
    ge::geo::AccuracyProfile accuracy = ge::geo::AccuracyProfile::psp();  // config.accuracy (API 1.6)
    ge::u64 waitBudget = ge::u64(1) << 26;
    bool lazyWriteback = false, holdInterrupts = false;
    void (*vramDirty)(void*, uint32_t, uint32_t) = nullptr;
    void (*drop)(void*, int32_t, uint32_t, const char*) = nullptr;  // config.drop
    std::string lastDrop;                                          // ge2gl_stats.last_drop
    ge::u64 runBudget = ~ge::u64(0);  // config.run_budget_us in GE cycles (~0: none)
    bool timeCut = false;             // the last wait stopped at a draw cut at runBudget
    std::thread::id glThread;  // GL_CURRENT: the thread whose context ge2gl draws on

    std::recursive_mutex mu;
    std::string message;
    std::atomic<int> waiters{0};  // callers waiting for mu (the GE-running thread yields to them)

    // The thread running the GE under mu: its lock (released around callbacks) and whether it
    // entered the GL scope. Set only while the GE runs.
    std::unique_lock<std::recursive_mutex>* runLock = nullptr;
    std::thread::id runThread;
    bool runGl = false;
    // The GE-running thread is inside the backend with mu released (RenderGate). Calls that are
    // not light wait on renderIdle until it is back; light calls defer what they would tell the
    // backend to pendingWrites / pendingHostWrote, handed over when it is back (applyDeferred).
    bool rendering = false;
    std::condition_variable_any renderIdle;
    bool pendingHostWrote = false, pendingHostWroteFb = false;
    std::thread::id deliverThread;  // the thread inside a host callback (runs/waits: reentrant)
    bool held = false;              // hold_interrupts: waiting for ge2gl_interrupt_ack
    // mem_written from a thread that cannot reach GL_CURRENT's context: applied on next entry.
    std::vector<std::pair<ge::u32, ge::u32>> pendingWrites;
    // The last ge2gl_state_save's blob (valid until the next save or destroy).
    std::vector<ge::u8> stateBlob;
    // ge2gl_debug_*: breakpoints observing the engine, made at the first debugger call.
    std::unique_ptr<ge::debug::Breakpoints> debugger;

    // Peek snapshot (snapMu only).
    std::mutex snapMu;
    std::array<ge::s32, ge::SceGe::kMaxLists> peekList{};
    ge::s32 peekDraw = 0;

    // Worker-thread mode.
    bool workerMode = false;
    bool quit = false;
    std::thread worker;
    std::thread::id workerId;
    std::condition_variable_any wake;  // work may be available
    std::condition_variable_any idle;  // the worker made progress or stopped
    ge::u64 workerCommands = 0;

    std::shared_ptr<struct ge2gl_recording> recording;  // ge2gl_record_begin/end (api/record.cpp)
    void workerLoop();
};

namespace ge2gl_impl {

// What a call needs of the backend while the GE thread draws (render_gate.h).
enum class CallKind {
    Waits,  // touches the backend or needs the engine between commands: waits while `rendering`
    Light,  // reads engine/queue state or writes guest memory only: goes on during a draw
};

// Per-call guard: takes the handle's lock (announcing itself to the GE-running thread), waits
// until no draw is in progress unless the call is light, clears the message; on return leaves
// the GL scope, refreshes the peek snapshot, wakes the worker.
class Call {
public:
    explicit Call(ge2gl_context* h, CallKind kind = CallKind::Waits);
    ~Call();
    std::unique_lock<std::recursive_mutex>& lock() { return lk_; }
    // Enters the GL scope for this call (no-op for backends without a HostContextUser). Fails with
    // GE2GL_ERR_WRONG_THREAD (GL_CURRENT on another thread), GE2GL_ERR_GL_CONTEXT (GL_CURRENT with
    // another context or none current) or GE2GL_ERR_BACKEND.
    ge2gl_status gl();
    bool glEntered() const { return glEntered_; }
    // True when GL work is possible from this thread (GL_CURRENT: the creating thread).
    bool glReachable() const;
    // Turns an sceGe result into a status and out-value: values >= 0 are results, < 0 errors.
    ge2gl_status sceResult(s32 r, int32_t* out);
    ge2gl_status error(ge2gl_status s, const std::string& msg);

private:
    ge2gl_context* h_;
    std::unique_lock<std::recursive_mutex> lk_;
    bool glEntered_ = false;
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

void refreshSnapshot(ge2gl_context* h);
// The GE thread, back from the backend with the lock: hands over what light calls deferred.
void applyDeferred(ge2gl_context* h);
// For light calls: the host may have written, told to the backend now or, while a draw is in
// progress, when it returns (applyDeferred).
void tellHostMayHaveWritten(ge2gl_context* h, bool frameBuffers);
// Lazy write-back: hands newly drawn VRAM ranges to config.vram_dirty (lock released).
void announceDirty(ge2gl_context* h);
// Runs or waits from inside a callback, or on the worker, are refused.
bool reentrant(const ge2gl_context* h);
// Waits (running the GE on this thread, or letting the worker run it) until `done` holds, the GE
// cannot progress, an interrupt is held, or the wait budget is spent. Returns true when done;
// else `why` says what stopped it.
// `stopAfter`: a list ID the inline run stops after (-1: none), so a wait for one list does not
// run the next.
bool waitUntil(ge2gl_context* h, Call& c, const std::function<bool()>& done, std::string& why, s32 stopAfter = -1);
// ge2gl_run, ge2gl_run_until, ge2gl_debug_step: at most max_commands, stopping between commands
// once the GE time reaches `tick`; fills `out` (may be null).
ge2gl_status runFor(ge2gl_context* h, uint64_t max_commands, uint64_t tick, ge2gl_run_info* out);
// Save states, debugger pokes and read-outs are refused from inside a callback (a command is half
// done there) and while the GE executes a command.
bool refuseMidRunCommand(const ge2gl_context* h);
// Runs the GE on this thread for up to `budget` commands (non-worker mode).
ge::SceRunResult drive(ge2gl_context* h, Call& c, u64 budget, s32 stopAfter = -1);

}  // namespace ge2gl_impl
