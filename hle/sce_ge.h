// SPDX-License-Identifier: MIT
// The sceGe kernel module's list semantics on top of GeEngine (docs/ge-rules.md §4.4, §4.5, §4.7;
// behaviour follows the uOFW reimplementation of ge.prx, with PPSSPP's choices where the firmware
// behaviour is unknown or would hang a game).
//
// GeEngine executes one list; SceGe keeps the 64 list slots, the queue order (tail and head
// enqueue), list IDs and states, stall updates, list/draw sync, break/continue, the per-list
// callback IDs (sceGeSetCallback), the per-list saved context, register and matrix readback and
// the eDRAM settings.
//
// Execution model: nothing runs by itself. The GE advances only inside run() and the wait modes
// of listSync()/drawSync(), on the caller's thread, so results are deterministic. Interrupt
// callbacks (SceGeListener) are delivered from inside those calls. A listener may call back into
// SceGe (update a stall address, enqueue, break, continue); calls that would run the GE again
// from inside a callback return kReentrant.
//
// Not thread-safe: the plugin API (api/ge2gl_c.cpp) serialises calls with its own lock.
#pragma once
#include <array>
#include <deque>
#include <string>
#include <tuple>

#include "hle/ge_engine.h"

namespace ge {

// PSP kernel error codes as the sceGe functions return them (uOFW ge.c; ge-rules.md §4.7).
namespace sce {
constexpr s32 kOk = 0;
constexpr s32 kErrorInvalidState = s32(0x80000004);    // uOFW: Break/Continue on a list in no breakable state
constexpr s32 kErrorAlready = s32(0x80000020);
constexpr s32 kErrorBusy = s32(0x80000021);            // also: same list address queued twice
constexpr s32 kErrorOutOfMemory = s32(0x80000022);     // 64 lists queued / 16 callbacks registered
constexpr s32 kErrorBadPointer = s32(0x80000023);      // the firmware's answer to an inaccessible pointer
constexpr s32 kErrorInvalidId = s32(0x80000100);
constexpr s32 kErrorInvalidIndex = s32(0x80000102);
constexpr s32 kErrorInvalidPointer = s32(0x80000103);  // misaligned list/stall/context/stack
constexpr s32 kErrorInvalidSize = s32(0x80000104);
constexpr s32 kErrorInvalidMode = s32(0x80000107);
constexpr s32 kErrorInvalidValue = s32(0x800001FE);
// Not PSP codes: the GE cannot make progress (wait modes), or a wait was asked from a callback.
constexpr s32 kWouldBlock = -5;
constexpr s32 kReentrant = -6;
}  // namespace sce

// sceGeListSync / sceGeDrawSync peek results.
enum SceSyncState : s32 {
    SCE_GE_LIST_COMPLETED = 0,
    SCE_GE_LIST_QUEUED = 1,
    SCE_GE_LIST_DRAWING = 2,
    SCE_GE_LIST_STALLING = 3,
    SCE_GE_LIST_PAUSED = 4,
};

// Internal list state (uOFW SCE_GE_DL_STATE_*).
enum class SceListState : u8 { None, Queued, Running, Paused, Completed };
const char* sceListStateName(SceListState s);

// SceGeListArgs as the game passes it (host-decoded): size 16 enables numStacks/stackAddr.
struct SceListArgs {
    u32 size = 0;
    u32 contextAddr = 0;  // 512-word context saved when the list starts, restored at its FINISH
    u32 numStacks = 0;    // depth of the SIGNAL CALL stack
    u32 stackAddr = 0;    // guest stack buffer (8 words per entry); only checked, ge2gl keeps its own
};

// One interrupt as the game's callback sees it.
struct SceInterrupt {
    s32 listId = 0;
    s32 cbid = -1;        // callback ID given at enqueue; -1: the game registered none
    u32 behaviour = 0;    // SIGNAL behaviour code (signal callbacks)
    u32 arg = 0;          // SIGNAL / FINISH argument, bits 15..0 (the game callback's first argument)
    u32 pc = 0;           // list address after the END (third argument; 0 for SDK <= 2.00.10)
    u32 endArg = 0;       // the END word's argument
    u32 func = 0, funcArg = 0;  // from sceGeSetCallback for cbid (0 when not registered)
    u64 tick = 0;               // the GE-time estimate when it occurred (GeStats::cycles)
    bool registered = false;    // cbid names a registered callback
};

class SceGeListener {
public:
    virtual ~SceGeListener() = default;
    virtual void onSignal(const SceInterrupt&) {}
    virtual void onFinish(const SceInterrupt&) {}
    // Every END the GE reads (INTEND).
    virtual void onEnd(s32 /*listId*/, u32 /*pc*/) {}
    virtual void onError(s32 /*listId*/, u32 /*pc*/, const std::string& /*message*/) {}
    // A draw lost data or was cut and the list goes on (GeListener::onDrop).
    virtual void onDrop(s32 /*listId*/, u32 /*pc*/, const std::string& /*message*/) {}
    // The GE has read list `listId` up to (not including) `pc`.
    virtual void onProgress(s32 /*listId*/, u32 /*pc*/) {}
};

// Why run() stopped.
enum class SceRunState : u8 {
    Idle,      // queue empty
    Budget,    // command budget used up; more work is ready
    Stalled,   // the current list reached its stall address
    Paused,    // the current list is paused (break, signal pause, or head-enqueued awaiting continue)
    Hung,      // the current list hit an END without SIGNAL/FINISH: the GE stops (uOFW, ge-rules.md §4.3)
    Reentrant, // run() was called from inside a callback
    Break,     // a command observer stopped the GE before a command (GeEngine::broke)
    TimeLimit, // the engine's GE-time limit or draw limit stopped it (a draw may have been cut)
};
const char* sceRunStateName(SceRunState s);

struct SceRunResult {
    SceRunState state = SceRunState::Idle;
    u64 commands = 0;  // executed by this call
    s32 listId = -1;   // current list (front of the queue), -1 if none
    u32 pc = 0, stall = 0;
};

class SceGe : private GeListener {
public:
    static constexpr int kMaxLists = 64;
    static constexpr int kMaxCallbacks = 16;
    static constexpr u32 kIdMask = 0x35000000;  // list ID = slot XOR mask (PPSSPP's choice)
    static constexpr u32 kDefaultSdkVersion = 0x06060010;

    explicit SceGe(GeEngine& engine);
    ~SceGe() override;
    SceGe(const SceGe&) = delete;
    SceGe& operator=(const SceGe&) = delete;

    void setListener(SceGeListener* l) { listener_ = l; }
    // sceKernelGetCompiledSdkVersion() of the game: selects old-SDK behaviours (ge-rules.md §4.4, §4.7).
    void setSdkVersion(u32 v) { sdkVersion_ = v; }
    // The host runs the game's signal and finish handlers after the callback returns (the plugin
    // API's hold_interrupts): what the firmware does when a handler returns waits for
    // handlersReturned() instead of happening when the callback returns.
    void setHandlersDeferred(bool on) { handlersDeferred_ = on; }
    void handlersReturned();
    u32 sdkVersion() const { return sdkVersion_; }
    // Commands a wait-mode sync may execute before it gives up with kWouldBlock.
    void setWaitBudget(u64 n) { waitBudget_ = n ? n : 1; }

    GeEngine& engine() { return engine_; }
    // Why the last failing call failed (also GE errors and hangs reported during run()).
    const std::string& lastMessage() const { return message_; }
    void clearMessage() { message_.clear(); }

    // ---- sceGe functions. Results: >= 0 as the firmware returns them, < 0 error codes. ----
    // Returns the list ID or an error.
    s32 listEnqueue(u32 list, u32 stall, s32 cbid, const SceListArgs* args, bool head);
    s32 listDequeue(s32 id);
    s32 listUpdateStallAddr(s32 id, u32 stall);
    // mode 0 waits (runs the GE until the list completes), mode 1 peeks (SceSyncState).
    s32 listSync(s32 id, int mode);
    s32 drawSync(int mode);
    // mode 0 pauses the current list (returns its ID); mode 1 resets the whole queue.
    s32 breakList(int mode);
    s32 continueList();
    s32 setCallback(u32 signalFunc, u32 signalArg, u32 finishFunc, u32 finishArg);
    s32 unsetCallback(s32 cbid);
    // 512-word context (docs/ppdmp.md §5 layout); fail with kErrorBusy while a list is drawing.
    s32 saveContext(u32 out[512]);
    s32 restoreContext(const u32 in[512]);
    // Same through guest memory (alignment and range checked).
    s32 saveContextTo(u32 addr);
    s32 restoreContextFrom(u32 addr);
    // sceGeGetCmd: register word for opcode `op` (< 0xFF).
    s32 getCmd(u32 op, u32* out) const;
    // sceGeGetMtx: types 0–7 bones, 8 world, 9 view, 10 proj (16 words), 11 tgen; float24 words.
    s32 getMtx(int type, u32 out[16], int* count) const;
    // sceGeGetStack: the SIGNAL CALL depth of the list the GE is in (0 without one); for
    // 0 <= index < depth entry `index` (0 = the first call) goes to out[0..7] when out is given:
    // word 1 the return address, 2 its OFFSET, 7 its BASE register word, the rest 0 (the words PPSSPP's
    // GPUCommon::GetStack fills; the PSP's other words are unknown). index >= depth: invalid index.
    s32 getStack(s32 index, u32 out[8]) const;
    // Returns the previous translation value, or kErrorInvalidValue.
    s32 edramSetAddrTranslation(u32 value);
    static u32 edramGetAddr() { return Memory::kVramBase; }
    static u32 edramGetSize() { return Memory::kVramSize; }

    // ---- Execution ----
    // Runs queued lists in order for at most `maxCommands` commands.
    SceRunResult run(u64 maxCommands);
    // The same, stopping right after list `stopAfterId` completes (a wait for that list).
    SceRunResult runUntil(u64 maxCommands, s32 stopAfterId);
    // Current position without running.
    SceRunResult peekRun() const;
    // True when run() would execute at least one command.
    bool canProgress() const;
    // Makes the current run() return after the command being executed (or at once between
    // commands), with the lists' states as they are: the plugin API stops there to hand an
    // interrupt to a host that holds interrupts until it acknowledges them. The next run() goes on.
    void requestYield();
    // Peek state of a list, or an error (for tests and the API's run info).
    SceListState listState(s32 id) const;
    // The list the GE runs or will run next (the queue's front), -1 when none.
    s32 currentListId() const { return queue_.empty() ? -1 : idOf(queue_.front()); }
    // GE time spent running list `id` so far (-1 when the ID names no list).
    s64 listCycles(s32 id) const;
    // run() stops between commands once the GE-time estimate reaches `cycles` (~0: no stop).
    void setTickStop(u64 cycles) {
        tickStop_ = cycles;
        engine_.setCycleStop(cycles);
    }

    // The list slots and callbacks (public for save states, hle/savestate.h).
    struct DisplayList {
        SceListState state = SceListState::None;
        u32 startPc = 0, stall = 0;
        s32 cbid = -1;
        u32 contextAddr = 0, numStacks = 32, stackAddr = 0;
        bool started = false;  // it has run: its execution registers live in `regs` or the engine
        bool hung = false;
        bool pausedBySignal = false;  // Paused by a SIGNAL HANDLER_PAUSE (not by sceGeBreak)
        ListRegs regs;
        u32 offset = 0, base = 0;
        u64 cycles = 0;  // GE time spent running this list (PPSSPP's GetListTicks)
    };
    struct Callback {
        bool used = false;
        u32 signalFunc = 0, signalArg = 0, finishFunc = 0, finishArg = 0;
    };

    // Everything of the sceGe layer a save state keeps. Taken and restored outside run() only
    // (between calls; never from a callback).
    struct Saved {
        std::array<DisplayList, kMaxLists> lists{};
        std::array<Callback, kMaxCallbacks> callbacks{};
        std::deque<int> queue, freeSlots;
        int active = -1;
        bool brokeInCallback = false, finishPending = false;
        u32 finishArg = 0, finishPc = 0;
        u32 sdkVersion = kDefaultSdkVersion;  // the game's; the host's wait budget is not state
        int suspendedSlot = -1;
        // The fields in order (of a Saved or a const one): saved() and restore() copy them to and
        // from the layer's members (savedFields()) as one tuple each way.
        template <class S>
        static auto fields(S& s) {
            return std::tie(s.lists, s.callbacks, s.queue, s.freeSlots, s.active, s.brokeInCallback, s.finishPending,
                            s.finishArg, s.finishPc, s.sdkVersion, s.suspendedSlot);
        }
    };
    Saved saved() const;
    // Checks the queue and slot structure (false with `why` when it is not one SceGe could reach)
    // before anything is changed.
    static bool validSaved(const Saved& s, std::string& why);
    void restore(const Saved& s);
    bool inRun() const { return inRun_; }

private:
    // The members Saved keeps, in Saved::fields() order (for the layer itself or a const one).
    template <class Self>
    static auto savedFields(Self& g) {
        return std::tie(g.lists_, g.callbacks_, g.queue_, g.freeSlots_, g.active_, g.brokeInCallback_, g.finishPending_,
                        g.finishArg_, g.finishPc_, g.sdkVersion_, g.suspendedSlot_);
    }

    // GeListener
    void onSignal(u32 behaviour, u32 signalArg, u32 endArg, u32 pc) override;
    void onFinish(u32 finishArg, u32 pc) override;
    void onEnd(u32 pc) override;
    void onError(GeError e, u32 pc, const std::string& message) override;
    void onDrop(u32 pc, const std::string& message) override;
    void onProgress(u32 pc) override;

    s32 fail(s32 code, const std::string& msg) const;
    int slotOf(s32 id) const;  // -1 when the ID is out of range
    static s32 idOf(int slot) { return s32(u32(slot) ^ kIdMask); }
    bool sdkOld() const { return sdkVersion_ <= 0x02000010; }
    // Make slot `i` the list the engine executes (saving the previous one's registers).
    void load(int i);
    void saveActive();
    void startFront();
    void completeFront(bool error);
    bool pausePending(const DisplayList& dl) const;
    u32 listPc(const DisplayList& dl, int slot) const;
    bool busyDrawing() const;
    bool isStalled(const DisplayList& dl, int slot) const;
    SceInterrupt makeInterrupt(int slot, bool finish, u32 arg, u32 pc) const;
    void writeContext(u32 addr, const u32 ctx[512]);
    bool readContext(u32 addr, u32 ctx[512]) const;
    SceRunResult runInternal(u64 maxCommands, int stopAfter);
    s32 waitFor(int slot);

    GeEngine& engine_;
    SceGeListener* listener_ = nullptr;
    std::array<DisplayList, kMaxLists> lists_{};
    std::array<Callback, kMaxCallbacks> callbacks_{};
    std::deque<int> queue_;      // slots in execution order; front is the current list
    std::deque<int> freeSlots_;  // reused oldest-freed first, so finished IDs stay queryable longer
    int active_ = -1;            // slot whose registers the engine holds
    bool inRun_ = false;
    bool brokeInCallback_ = false;
    bool finishPending_ = false;
    bool yield_ = false, inEngine_ = false;
    u32 finishArg_ = 0, finishPc_ = 0;
    u32 sdkVersion_ = kDefaultSdkVersion;
    bool handlersDeferred_ = false;
    int suspendedSlot_ = -1;  // an old-SDK HANDLER_SUSPEND list reading PAUSED until its handler returns
    u64 waitBudget_ = u64(1) << 26;
    u64 tickStop_ = ~u64(0);
    mutable std::string message_;
};

}  // namespace ge
