// SPDX-License-Identifier: MIT
// The GE machine: executes display lists (manual §20, §11.1; docs/ge-rules.md §4) against a
// GeState and guest Memory, and hands draws, transfers and syncs to a Renderer.
//
// One list executes at a time; queueing several lists, list IDs and sync are the sceGe layer's
// job (hle/sce_ge.h). The engine never blocks and never starts threads: run() executes until the
// list ends, reaches its stall address, pauses, errors, or the command budget is used up.
#pragma once
#include <string>
#include <tuple>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/renderer.h"

namespace ge {

enum class GeError {
    None,
    BadListAddress,   // the PC left valid memory
    BadJumpTarget,    // JUMP/BJUMP/CALL/signal jump to an invalid address
    CallDepth,        // CALL beyond the hardware's two levels
    SignalStack,      // signal CALL beyond the software stack / signal RET with an empty stack
};
const char* geErrorName(GeError e);

enum class RunStatus {
    Idle,             // no list started
    Completed,        // FINISH + END: list done
    Ended,            // END without SIGNAL/FINISH: the GE stops (uOFW behaviour; ge-rules.md §4.3)
    Stalled,          // PC reached the stall address; setStall() resumes
    Paused,           // a SIGNAL pause (HANDLER_PAUSE at FINISH, or requestPause()); resume() continues
    Budget,           // command budget exhausted; run() again continues
    TimeLimit,        // the GE-time limit (setTimeLimit) is used up; raise it to continue
    Error,            // see lastError()
};
const char* runStatusName(RunStatus s);

// Interrupts and notifications for the host (manual §21). All callbacks run on the caller's thread
// from inside run().
class GeListener {
public:
    virtual ~GeListener() = default;
    // SIGNAL + END pair with a handler behaviour (0x01 suspend, 0x02 continue, 0x03 pause
    // delivered at the following FINISH). `pc` is the address after the END.
    virtual void onSignal(u32 /*behaviour*/, u32 /*signalArg*/, u32 /*endArg*/, u32 /*pc*/) {}
    virtual void onFinish(u32 /*finishArg*/, u32 /*pc*/) {}
    virtual void onEnd(u32 /*pc*/) {}
    virtual void onError(GeError, u32 /*pc*/, const std::string& /*message*/) {}
    // A draw at `pc` (the address after it) lost data or was cut, and the list goes on: vertices
    // or indices outside guest memory, a patch past the tessellator's cap, a draw cut at the
    // host's draw limit. Counted in GeStats::drawsDropped / drawsCut.
    virtual void onDrop(u32 /*pc*/, const std::string& /*message*/) {}
    // The GE has read the list up to (not including) `pc`.
    virtual void onProgress(u32 /*pc*/) {}
};

// Execution registers of the running list (ge-rules.md §4.1).
struct ListRegs {
    u32 pc = 0;
    u32 stall = 0;        // 0: no stall address
    u32 callStack[2][2] = {};  // (return PC, OFFSET) for CALL depth 1 and 2
    u32 callDepth = 0;
    bool bflg = true;     // result of the last BBOX (1 = inside)
    // Software stack for SIGNAL CALL/RET (PC, OFFSET, BASE), like the sceGe module's.
    struct SigFrame { u32 pc, offset, base; };
    std::vector<SigFrame> signalStack;
    u32 signalStackMax = 32;
    // Marks set by SIGNAL behaviours, acted on at the next FINISH + END.
    bool pauseAtFinish = false, syncAtFinish = false;
    u32 pauseSignalArg = 0, pauseEndArg = 0;
    u32 lastOp = 0;       // previous command word's opcode (SIGNAL/FINISH before END)
    u32 lastWord = 0;
};

// Sees every command before the GE executes it (a debugger's breakpoints, a frame recorder).
// Callbacks run on the caller's thread from inside run(), between commands.
class CommandObserver {
public:
    virtual ~CommandObserver() = default;
    // `word` was read at `pc` and is about to execute. Returning false stops the run before it
    // (run() returns RunStatus::Budget with broke() set; the pc still points at the word, and the
    // next run() asks again).
    virtual bool beforeCommand(u32 pc, u32 word) = 0;
};

struct GeStats {
    u64 commands = 0, prims = 0, patches = 0, immediates = 0, vertices = 0, bboxes = 0;
    u64 transfers = 0, clutLoads = 0, signals = 0, finishes = 0, unknownCommands = 0;
    u64 stateChanges = 0;  // register words that changed value
    u64 cycles = 0;        // GE-time estimate (hle/ge_time.h), 222 MHz cycles
    // Where the cycles went (docs/timing.md): commands (with list starts, ENDs and BBOX tests),
    // vertex work of draws, pixel fill, block transfers. They add up to `cycles` except when the
    // GE-time limit cut a draw short.
    u64 cyclesCommands = 0, cyclesVertices = 0, cyclesPixels = 0, cyclesTransfers = 0;
    u64 drawsDropped = 0;  // draws that lost data (GeListener::onDrop)
    u64 drawsCut = 0;      // draws cut at the host's draw limit (setDrawLimit)
};

class GeEngine {
public:
    explicit GeEngine(Memory& mem, Renderer* renderer = nullptr);

    void setRenderer(Renderer* r);
    Renderer* renderer() const { return renderer_; }
    void setListener(GeListener* l) { listener_ = l; }
    // Observers are called in the order added; a null-safe remove.
    void addObserver(CommandObserver* o) { observers_.push_back(o); }
    void removeObserver(CommandObserver* o) { std::erase(observers_, o); }
    // The last run() stopped because an observer refused a command.
    bool broke() const { return broke_; }

    GeState& state() { return state_; }
    const GeState& state() const { return state_; }
    Memory& memory() { return mem_; }
    const Memory& memory() const { return mem_; }
    ListRegs& list() { return list_; }
    const ListRegs& list() const { return list_; }
    const GeStats& stats() const { return stats_; }

    // Starts executing a list at `pc` (masked to 28 bits) with a stall address (0 = none).
    // OFFSET starts at 0 and the call stack empty; BASE and all other state is kept.
    void startList(u32 pc, u32 stall);
    void setStall(u32 stall) { list_.stall = stall ? Memory::normalize(stall) : 0; }
    RunStatus run(u64 maxCommands = ~u64(0));
    // Stop with RunStatus::TimeLimit once the GE-time estimate (stats().cycles, hle/ge_time.h)
    // reaches `cycles` (~0: no limit, the default).
    void setTimeLimit(u64 cycles) { cycleLimit_ = cycles; }
    // Stop with RunStatus::Budget between commands once stats().cycles reaches `cycles` (a host
    // running the GE to an emulated time; ~0: none). Unlike the limit, it never cuts a draw: the
    // command that crosses it completes.
    void setCycleStop(u64 cycles) { cycleStop_ = cycles; }
    // A host's bound on one draw (the plugin API's run budget; ~0: none): a draw whose vertex work
    // alone would take more than `cycles` of GE time is not drawn, one whose pixels reach it is cut
    // there (the renderer's pixel budget), and either way the run stops with RunStatus::TimeLimit
    // after that command; the next run goes on with the command after it. drawCut() says a stop
    // was such a cut (cleared when the next run starts).
    void setDrawLimit(u64 cycles) { drawLimit_ = cycles; }
    bool drawCut() const { return drawCut_; }
    RunStatus status() const { return status_; }
    // Ask the running list to pause after the current command (sceGeBreak); resume() clears it.
    void requestPause() { pauseRequested_ = true; }
    void resume();

    // Executes one command word as if read from the list at the current PC (PC already advanced).
    void execute(u32 word);
    // Restores a 512-word context and marks all state dirty.
    bool loadContext(const u32 ctx[512]);

    GeError lastError() const { return lastError_; }
    const std::string& lastErrorMessage() const { return lastErrorMsg_; }
    u32 takeDirty() { u32 d = dirty_; dirty_ = 0; return d; }
    void markDirty(u32 groups) { dirty_ |= groups; }

    // Address formation of ge-rules.md §4.2: (BASE-high | arg) + OFFSET, masked to 28 bits.
    u32 formAddress(u32 arg24) const;

    // Everything of the engine a save state keeps (hle/savestate.h): what cannot be re-derived.
    // Taken and restored between commands only (never from inside run()).
    struct Saved {
        GeState state;
        ListRegs list;
        GeStats stats;
        RunStatus status = RunStatus::Idle;
        GeError lastError = GeError::None;
        std::string lastErrorMsg;
        u64 cycleLimit = ~u64(0);
        bool pauseRequested = false, stopRequested = false;
        RunStatus stopStatus = RunStatus::Idle;
        GePrimType lastPrim = GE_PRIM_POINTS;
        std::vector<ImmVertex> immVerts;  // an immediate-mode primitive being collected
        u32 immFlags = 0;
        GePrimType immPrim = GE_PRIM_POINTS;
        // The fields in order (of a Saved or a const one): saved() and restore() copy them to and
        // from the engine's members (savedFields()) as one tuple each way.
        template <class S>
        static auto fields(S& s) {
            return std::tie(s.state, s.list, s.stats, s.status, s.lastError, s.lastErrorMsg, s.cycleLimit, s.pauseRequested,
                            s.stopRequested, s.stopStatus, s.lastPrim, s.immVerts, s.immFlags, s.immPrim);
        }
    };
    Saved saved() const;
    // Restores a saved engine: every dirty group is raised and the renderer is told the palette
    // changed, so a backend re-derives all it caches from the state.
    void restore(const Saved& s);

private:
    // The members Saved keeps, in Saved::fields() order (for the engine itself or a const one).
    template <class Self>
    static auto savedFields(Self& e) {
        return std::tie(e.state_, e.list_, e.stats_, e.status_, e.lastError_, e.lastErrorMsg_, e.cycleLimit_,
                        e.pauseRequested_, e.stopRequested_, e.stopStatus_, e.lastPrim_, e.immVerts_, e.immFlags_,
                        e.immPrim_);
    }
    void fail(GeError e, const std::string& msg);
    void doPrim(u32 arg);
    void latchVertexAttributes(const PrimPacket& p);
    void doPatch(u32 word);
    void doBBox(u32 arg);
    void doTransfer(u32 arg);
    void doClutLoad(u32 arg);
    void doImmediate(u32 arg);
    void flushImmediate();
    void doEnd(u32 arg);
    bool jumpTo(u32 target);
    void matrixData(u8 op, u32 arg);
    // Adds to the GE-time estimate and to one of its parts.
    void charge(u64 cycles, u64 GeStats::*part) {
        stats_.cycles += cycles;
        stats_.*part += cycles;
    }
    void chargePixels();  // adds the renderer's new pixel work to the GE-time estimate
    // Charges the vertex work of a draw; false (and the run stops with TimeLimit) when it does not
    // fit in what is left of the GE-time limit. Hands the renderer the pixels that remain.
    bool chargeDraw(u64 vertexCycles);
    // Reports (onDrop) what of a draw's vertex and index data lies outside guest memory.
    void checkDrawData(const char* what, u32 vtype, u32 vertexAddr, u32 indexAddr, u32 count);
    void reportDrop(const std::string& message, bool cut = false);  // counts it, tells the listener

    Memory& mem_;
    Renderer* renderer_ = nullptr;
    NullRenderer nullRenderer_;
    GeListener* listener_ = nullptr;
    std::vector<CommandObserver*> observers_;
    bool broke_ = false;
    GeState state_;
    std::vector<u32> latchIndices_;  // latchVertexAttributes' scratch
    ListRegs list_;
    GeStats stats_;
    RunStatus status_ = RunStatus::Idle;
    GeError lastError_ = GeError::None;
    std::string lastErrorMsg_;
    u32 dirty_ = DIRTY_ALL;
    u64 cycleLimit_ = ~u64(0);
    u64 cycleStop_ = ~u64(0);
    u64 drawLimit_ = ~u64(0);
    u64 drawEnd_ = ~u64(0);  // this draw's cut point under drawLimit_ (chargeDraw/chargePixels)
    bool drawCut_ = false;
    u64 pixelWorkSeen_ = 0;
    bool pixelBudgetSet_ = false;
    bool pauseRequested_ = false;
    bool stopRequested_ = false;
    RunStatus stopStatus_ = RunStatus::Idle;
    GePrimType lastPrim_ = GE_PRIM_POINTS;
    std::vector<ImmVertex> immVerts_;
    u32 immFlags_ = 0;
    GePrimType immPrim_ = GE_PRIM_POINTS;
};

}  // namespace ge
