// SPDX-License-Identifier: MIT
#include "hle/sce_ge.h"

#include <cstdio>

namespace ge {

namespace {

std::string fmt(const char* f, u32 a = 0, u32 b = 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, f, a, b);
    return buf;
}

}  // namespace

const char* sceListStateName(SceListState s) {
    switch (s) {
    case SceListState::None: return "none";
    case SceListState::Queued: return "queued";
    case SceListState::Running: return "running";
    case SceListState::Paused: return "paused";
    case SceListState::Completed: return "completed";
    }
    return "?";
}

const char* sceRunStateName(SceRunState s) {
    switch (s) {
    case SceRunState::Idle: return "idle";
    case SceRunState::Budget: return "budget";
    case SceRunState::Stalled: return "stalled";
    case SceRunState::Paused: return "paused";
    case SceRunState::Hung: return "hung";
    case SceRunState::Reentrant: return "reentrant";
    case SceRunState::Break: return "break";
    case SceRunState::TimeLimit: return "at its time limit";
    }
    return "?";
}

SceGe::SceGe(GeEngine& engine) : engine_(engine) {
    engine_.setListener(this);
    for (int i = 0; i < kMaxLists; ++i) freeSlots_.push_back(i);
}

SceGe::~SceGe() { engine_.setListener(nullptr); }

SceGe::Saved SceGe::saved() const {
    Saved s;
    Saved::fields(s) = savedFields(*this);
    return s;
}

bool SceGe::validSaved(const Saved& s, std::string& why) {
    std::array<int, kMaxLists> seen{};
    for (const auto* d : {&s.queue, &s.freeSlots})
        for (int i : *d) {
            if (i < 0 || i >= kMaxLists) return why = "a list slot out of range", false;
            if (seen[size_t(i)]++) return why = "a list slot queued or freed twice", false;
        }
    if (s.active < -1 || s.active >= kMaxLists) return why = "the active slot is out of range", false;
    if (s.suspendedSlot < -1 || s.suspendedSlot >= kMaxLists) return why = "the suspended slot is out of range", false;
    for (const DisplayList& dl : s.lists) {
        if (dl.state > SceListState::Completed) return why = "a list state out of range", false;
        if (dl.cbid < -1 || dl.cbid >= kMaxCallbacks) return why = "a callback ID out of range", false;
        if (dl.regs.callDepth > 2 || dl.regs.signalStack.size() > 256)
            return why = "a list's call stack is deeper than the GE allows", false;
    }
    return true;
}

void SceGe::restore(const Saved& s) {
    savedFields(*this) = Saved::fields(s);
    inRun_ = yield_ = inEngine_ = false;
    message_.clear();
}

s32 SceGe::fail(s32 code, const std::string& msg) const {
    message_ = msg;
    return code;
}

int SceGe::slotOf(s32 id) const {
    u32 i = u32(id) ^ kIdMask;
    return i < u32(kMaxLists) ? int(i) : -1;
}

// ---------------------------------------------------------------------------------------------
// Binding lists to the engine. The engine holds the execution registers (PC, call stack, signal
// stack, SIGNAL marks) of one list; OFFSET and BASE live in the shared register file. When the
// queue moves to another list the firmware saves these per list and restores them on resume
// (uOFW _sceGeFinishInterrupt / sceGeContinue: LISTADDR, OADR*, RADR*, BASE), and so do we.

bool SceGe::pausePending(const DisplayList& dl) const {
    int slot = int(&dl - lists_.data());
    return slot == active_ ? engine_.list().pauseAtFinish : dl.regs.pauseAtFinish;
}

u32 SceGe::listPc(const DisplayList& dl, int slot) const {
    if (slot == active_) return engine_.list().pc;
    return dl.started ? dl.regs.pc : dl.startPc;
}

bool SceGe::isStalled(const DisplayList& dl, int slot) const { return dl.stall && listPc(dl, slot) == dl.stall; }

void SceGe::saveActive() {
    if (active_ < 0) return;
    DisplayList& dl = lists_[active_];
    if (dl.state != SceListState::None && dl.state != SceListState::Completed) {
        dl.regs = engine_.list();
        dl.offset = engine_.state().offsetAddr;
        dl.base = engine_.state().regs[GE_CMD_BASE];
    }
    active_ = -1;
}

void SceGe::load(int i) {
    if (active_ == i) return;
    saveActive();
    DisplayList& dl = lists_[i];
    const u64 c0 = engine_.stats().cycles;  // starting the list is its GE time (kListStart)
    if (!dl.started) {
        // The list's context buffer receives the state at the moment the list starts and is
        // restored at its FINISH (docs/ge-rules.md §4.7). (The firmware copies the previous list's saved context
        // when it has one; that equals the current state, which was restored from it.)
        if (dl.contextAddr) {
            u32 ctx[512];
            engine_.state().saveContext(ctx);
            writeContext(dl.contextAddr, ctx);
        }
        engine_.startList(dl.startPc, dl.stall);
        engine_.list().signalStackMax = dl.numStacks;
        dl.started = true;
    } else {
        engine_.startList(dl.regs.pc, dl.stall);
        engine_.list() = dl.regs;
        engine_.setStall(dl.stall);
        engine_.state().offsetAddr = dl.offset;
        engine_.state().regs[GE_CMD_BASE] = dl.base;
    }
    dl.cycles += engine_.stats().cycles - c0;
    active_ = i;
}

// The firmware starts the next list as soon as the previous one finishes (or at enqueue when the
// queue was empty), so its state reads DRAWING, not QUEUED, before the host runs anything.
void SceGe::startFront() {
    if (queue_.empty()) return;
    int i = queue_.front();
    if (lists_[i].state == SceListState::Queued) {
        lists_[i].state = SceListState::Running;
        load(i);
    }
}

void SceGe::writeContext(u32 addr, const u32 ctx[512]) {
    // The firmware writes the context up to its closing END (word 384) and leaves the rest of the
    // 512-word buffer alone (pspautotests gpu/ge/context: word 386 keeps its 0xCCCCCCCC).
    u8 bytes[385 * 4];
    for (int k = 0; k < 385; ++k) writeLE32(bytes + 4 * k, ctx[k]);
    engine_.renderer()->syncMemoryForRead(addr, sizeof bytes);
    if (!engine_.memory().write(addr, bytes, sizeof bytes)) return;
    engine_.renderer()->memoryWritten(addr, sizeof bytes);
}

bool SceGe::readContext(u32 addr, u32 ctx[512]) const {
    engine_.renderer()->syncMemoryForRead(addr, 2048);
    const u8* p = engine_.memory().ptr(addr, 2048);
    if (!p) return false;
    for (int k = 0; k < 512; ++k) ctx[k] = readLE32(p + 4 * k);
    return true;
}

SceInterrupt SceGe::makeInterrupt(int slot, bool finish, u32 arg, u32 pc) const {
    SceInterrupt in;
    const DisplayList& dl = lists_[slot];
    in.listId = idOf(slot);
    in.cbid = dl.cbid;
    in.arg = arg & 0xFFFF;
    // The callback's third argument is the list address, 0 for games built with SDK <= 2.00.10.
    in.pc = sdkOld() ? 0 : pc;
    in.tick = engine_.stats().cycles;
    if (dl.cbid >= 0 && dl.cbid < kMaxCallbacks && callbacks_[dl.cbid].used) {
        const Callback& cb = callbacks_[dl.cbid];
        in.registered = true;
        in.func = finish ? cb.finishFunc : cb.signalFunc;
        in.funcArg = finish ? cb.finishArg : cb.signalArg;
    }
    return in;
}

void SceGe::completeFront(bool error) {
    int i = queue_.front();
    queue_.pop_front();
    DisplayList& dl = lists_[i];
    dl.state = SceListState::Completed;
    if (active_ == i) active_ = -1;  // the engine holds no live list any more
    if (!error) {
        // uOFW _sceGeFinishInterrupt: state COMPLETED, finish callback, then the saved context.
        if (listener_) listener_->onFinish(makeInterrupt(i, true, finishArg_, finishPc_));
        if (dl.contextAddr && dl.state == SceListState::Completed) {
            u32 ctx[512];
            if (readContext(dl.contextAddr, ctx)) engine_.loadContext(ctx);
        }
    }
    if (dl.state == SceListState::Completed) freeSlots_.push_back(i);
    startFront();
}

// ---------------------------------------------------------------------------------------------
// Engine notifications. They arrive from inside engine_.run(), for the active list.

void SceGe::onSignal(u32 behaviour, u32 signalArg, u32 endArg, u32 pc) {
    if (active_ < 0) return;
    DisplayList& dl = lists_[active_];
    SceInterrupt in = makeInterrupt(active_, false, signalArg, pc);
    in.behaviour = behaviour;
    in.endArg = endArg;
    switch (behaviour) {
    case 0x01: {  // HANDLER_SUSPEND
        // SDK <= 2.00.10: the list reads PAUSED while the callback runs. (The firmware then sets the
        // state to END bits 7..0; SDK lists put 0 there, which no state uses, so we go back to
        // running, as the GE keeps reading either way.)
        const bool old = sdkOld();
        if (old) dl.state = SceListState::Paused;
        brokeInCallback_ = false;
        if (old && handlersDeferred_) suspendedSlot_ = active_;
        if (listener_) listener_->onSignal(in);
        if (old && !handlersDeferred_ && dl.state == SceListState::Paused && !brokeInCallback_) dl.state = SceListState::Running;
        break;
    }
    case 0x03:  // HANDLER_PAUSE, delivered at the FINISH: the list is paused before the callback
        dl.state = SceListState::Paused;
        dl.pausedBySignal = true;
        if (listener_) listener_->onSignal(in);
        break;
    default:  // 0x02 HANDLER_CONTINUE: the GE resumes first, then the callback runs
        if (listener_) listener_->onSignal(in);
        break;
    }
}

void SceGe::handlersReturned() {
    // pspautotests gpu/signals/suspend: an old-SDK list reads PAUSED during its suspend handler
    // and goes on once the handler returned, unless the handler broke it.
    if (suspendedSlot_ >= 0) {
        DisplayList& dl = lists_[size_t(suspendedSlot_)];
        if (dl.state == SceListState::Paused && !brokeInCallback_) dl.state = SceListState::Running;
        suspendedSlot_ = -1;
    }
}

void SceGe::onFinish(u32 finishArg, u32 pc) {
    finishPending_ = true;
    finishArg_ = finishArg;
    finishPc_ = pc;
}

void SceGe::onEnd(u32 pc) {
    if (listener_ && active_ >= 0) listener_->onEnd(idOf(active_), pc);
}

void SceGe::onError(GeError, u32 pc, const std::string& message) {
    message_ = message;
    if (listener_ && active_ >= 0) listener_->onError(idOf(active_), pc, message);
}

void SceGe::onDrop(u32 pc, const std::string& message) {
    if (listener_ && active_ >= 0) listener_->onDrop(idOf(active_), pc, message);
}

void SceGe::onProgress(u32 pc) {
    if (listener_ && active_ >= 0) listener_->onProgress(idOf(active_), pc);
}

// ---------------------------------------------------------------------------------------------
// Queue management.

s32 SceGe::listEnqueue(u32 list, u32 stall, s32 cbid, const SceListArgs* args, bool head) {
    // Without args (or with size < 16) the firmware gives SDK >= 2.0 games no signal stack; we keep
    // PPSSPP's 32 entries so a list using SIGNAL CALL still runs (shipped games pass stacks anyway).
    u32 ctx = 0, numStacks = 32, stackAddr = 0;
    if (args) {
        ctx = args->contextAddr;
        if (args->size >= 16) {
            if (args->numStacks >= 256) return fail(sce::kErrorInvalidSize, fmt("numStacks %u is not below 256", args->numStacks));
            numStacks = args->numStacks;
            stackAddr = args->stackAddr;
        }
    }
    if ((list | stall | ctx | stackAddr) & 3)
        return fail(sce::kErrorInvalidPointer, fmt("list 0x%08x / stall 0x%08x: addresses must be 4-byte aligned", list, stall) +
                                                   (((ctx | stackAddr) & 3) ? " (context or stack misaligned)" : ""));
    const Memory& mem = engine_.memory();
    const u32 pc = Memory::normalize(list);
    if (!mem.valid(pc, 4)) return fail(sce::kErrorBadPointer, fmt("list address 0x%08x is outside guest memory", list));
    if (ctx && !mem.valid(ctx, 2048)) return fail(sce::kErrorBadPointer, fmt("context 0x%08x (2048 bytes) is outside guest memory", ctx));
    if (stackAddr && numStacks && !mem.valid(stackAddr, numStacks * 32))
        return fail(sce::kErrorBadPointer, fmt("signal stack 0x%08x (%u entries) is outside guest memory", stackAddr, numStacks));
    // SDK >= 2.0: the same list address may not be queued twice (uOFW _sceGeListEnQueue).
    if (sdkVersion_ > 0x01FFFFFF)
        for (int q : queue_)
            if (lists_[q].startPc == pc) return fail(sce::kErrorBusy, fmt("list 0x%08x is already queued", pc));
    if (freeSlots_.empty()) return fail(sce::kErrorOutOfMemory, "all 64 display lists are in use");
    if (head && !queue_.empty() && lists_[queue_.front()].state != SceListState::Paused)
        return fail(sce::kErrorInvalidValue, "head enqueue needs the current list to be paused");

    const int i = freeSlots_.front();
    freeSlots_.pop_front();
    DisplayList& dl = lists_[i];
    dl = DisplayList{};
    dl.startPc = pc;
    dl.stall = stall ? Memory::normalize(stall) : 0;
    dl.cbid = cbid < -1 ? -1 : cbid;
    dl.contextAddr = ctx;
    dl.numStacks = numStacks;
    dl.stackAddr = stackAddr;
    if (head) {
        // The new list goes in front, paused until sceGeContinue; the paused current list waits
        // behind it (uOFW). Its pending signal pause is dropped so it is not paused twice (PPSSPP).
        if (!queue_.empty()) {
            int cur = queue_.front();
            lists_[cur].state = SceListState::Queued;
            lists_[cur].regs.pauseAtFinish = false;
            if (active_ == cur) engine_.list().pauseAtFinish = false;
        }
        dl.state = SceListState::Paused;
        queue_.push_front(i);
    } else {
        dl.state = SceListState::Queued;
        queue_.push_back(i);
        if (queue_.size() == 1) startFront();
    }
    return idOf(i);
}

s32 SceGe::listDequeue(s32 id) {
    int i = slotOf(id);
    if (i < 0 || lists_[i].state == SceListState::None) return fail(sce::kErrorInvalidId, fmt("list ID 0x%08x is not queued", u32(id)));
    // A list that has started (or finished) cannot be dequeued (uOFW: ctxUpToDate → busy).
    if (lists_[i].started) return fail(sce::kErrorBusy, fmt("list ID 0x%08x has already started", u32(id)));
    for (auto it = queue_.begin(); it != queue_.end(); ++it)
        if (*it == i) {
            queue_.erase(it);
            break;
        }
    lists_[i].state = SceListState::None;
    freeSlots_.push_back(i);
    startFront();
    return sce::kOk;
}

s32 SceGe::listUpdateStallAddr(s32 id, u32 stall) {
    int i = slotOf(id);
    if (i < 0 || lists_[i].state == SceListState::None) return fail(sce::kErrorInvalidId, fmt("list ID 0x%08x is not queued", u32(id)));
    if (lists_[i].state == SceListState::Completed) return fail(sce::kErrorAlready, fmt("list ID 0x%08x has completed", u32(id)));
    if (stall & 3) return fail(sce::kErrorInvalidPointer, fmt("stall address 0x%08x is not 4-byte aligned", stall));
    lists_[i].stall = stall ? Memory::normalize(stall) : 0;
    if (active_ == i) engine_.setStall(lists_[i].stall);
    return sce::kOk;
}

SceListState SceGe::listState(s32 id) const {
    int i = slotOf(id);
    return i < 0 ? SceListState::None : lists_[i].state;
}

s64 SceGe::listCycles(s32 id) const {
    const int i = slotOf(id);
    return i < 0 || lists_[i].state == SceListState::None ? -1 : s64(lists_[i].cycles);
}

s32 SceGe::listSync(s32 id, int mode) {
    int i = slotOf(id);
    if (i < 0) return fail(sce::kErrorInvalidId, fmt("list ID 0x%08x is out of range", u32(id)));
    if (mode == 0) return waitFor(i);
    if (mode != 1) return fail(sce::kErrorInvalidMode, fmt("sync mode %u is neither 0 (wait) nor 1 (peek)", u32(mode)));
    const DisplayList& dl = lists_[i];
    switch (dl.state) {
    case SceListState::Queued: return dl.started ? SCE_GE_LIST_PAUSED : SCE_GE_LIST_QUEUED;
    case SceListState::Running:
        // HANDLER_PAUSE marks the list PAUSED as soon as the SIGNAL is read (uOFW), although the
        // GE reads on up to the FINISH.
        if (pausePending(dl)) return SCE_GE_LIST_PAUSED;
        return isStalled(dl, i) ? SCE_GE_LIST_STALLING : SCE_GE_LIST_DRAWING;
    case SceListState::Paused: return SCE_GE_LIST_PAUSED;
    case SceListState::Completed: return SCE_GE_LIST_COMPLETED;
    case SceListState::None: break;
    }
    return fail(sce::kErrorInvalidId, fmt("list ID 0x%08x is not queued", u32(id)));
}

s32 SceGe::waitFor(int i) {
    if (inRun_) return fail(sce::kReentrant, "a wait-mode sync cannot run from inside a GE callback");
    // A slot that is free (never used, dequeued, or reset by a draw sync) counts as done, as the
    // firmware's event flag bit is set for it.
    auto done = [&] { return lists_[i].state == SceListState::None || lists_[i].state == SceListState::Completed; };
    if (done()) return SCE_GE_LIST_COMPLETED;
    SceRunResult r = runInternal(waitBudget_, i);
    if (done()) return SCE_GE_LIST_COMPLETED;
    return fail(sce::kWouldBlock, fmt("list ID 0x%08x cannot complete: the GE is ", u32(idOf(i))) + sceRunStateName(r.state) +
                                      fmt(" at 0x%08x (stall 0x%08x)", r.pc, r.stall));
}

s32 SceGe::drawSync(int mode) {
    if (mode == 0) {
        if (inRun_) return fail(sce::kReentrant, "a wait-mode sync cannot run from inside a GE callback");
        SceRunResult r = runInternal(waitBudget_, -1);
        if (!queue_.empty())
            return fail(sce::kWouldBlock, std::string("drawing cannot complete: the GE is ") + sceRunStateName(r.state) +
                                              fmt(" at 0x%08x (stall 0x%08x)", r.pc, r.stall));
        // After a completed draw sync the firmware frees every completed list (uOFW sceGeDrawSync).
        for (auto& dl : lists_)
            if (dl.state == SceListState::Completed) dl.state = SceListState::None;
        return SCE_GE_LIST_COMPLETED;
    }
    if (mode != 1) return fail(sce::kErrorInvalidMode, fmt("sync mode %u is neither 0 (wait) nor 1 (peek)", u32(mode)));
    if (queue_.empty()) return SCE_GE_LIST_COMPLETED;
    // The firmware answers for the first unfinished list with DRAWING or STALLING only.
    int i = queue_.front();
    const DisplayList& dl = lists_[i];
    return dl.state == SceListState::Running && isStalled(dl, i) ? SCE_GE_LIST_STALLING : SCE_GE_LIST_DRAWING;
}

s32 SceGe::breakList(int mode) {
    if (u32(mode) >= 2) return fail(sce::kErrorInvalidMode, fmt("break mode %u is neither 0 nor 1", u32(mode)));
    if (queue_.empty()) return fail(sce::kErrorAlready, "no display list to break");
    if (mode == 1) {
        // Reset the whole queue (the GE state itself is kept, as _sceGeReset restores it).
        for (auto& dl : lists_) dl = DisplayList{};
        queue_.clear();
        freeSlots_.clear();
        for (int k = 0; k < kMaxLists; ++k) freeSlots_.push_back(k);
        active_ = -1;
        if (inRun_) engine_.requestPause();  // stop the engine at once; run() then finds no work
        return sce::kOk;
    }
    const int i = queue_.front();
    DisplayList& dl = lists_[i];
    const bool newSdk = sdkVersion_ >= 0x02000000;
    switch (dl.state) {
    case SceListState::Running:
        if (pausePending(dl)) return fail(sce::kErrorBusy, "cannot break a list with a signal pause pending");
        dl.state = SceListState::Paused;
        brokeInCallback_ = true;
        // From a callback the engine is mid-list: stop it after the current command. Otherwise the
        // engine already stands between commands and simply is not run.
        if (inRun_ && active_ == i) engine_.requestPause();
        return idOf(i);
    case SceListState::Paused:
        // Paused by a HANDLER_PAUSE signal the firmware answers busy, by a break already
        // (pspautotests gpu/ge/break "Pause signal"; PPSSPP GPUCommon::Break).
        if (dl.pausedBySignal) return fail(sce::kErrorBusy, "the current list is paused by a signal");
        return fail(sdkVersion_ > 0x02000010 ? sce::kErrorAlready : sce::kErrorBusy, "the current list is already paused");
    case SceListState::Queued: dl.state = SceListState::Paused; return idOf(i);
    default: return fail(newSdk ? sce::kErrorInvalidState : -1, "the current list cannot be paused");
    }
}

s32 SceGe::continueList() {
    if (queue_.empty()) return sce::kOk;
    const int i = queue_.front();
    DisplayList& dl = lists_[i];
    const bool newSdk = sdkVersion_ >= 0x02000000;
    if (dl.state == SceListState::Paused) {
        // The engine is resumed by run() when it next looks at this list (safe from callbacks too).
        dl.state = SceListState::Running;
        dl.pausedBySignal = false;
        return sce::kOk;
    }
    if (dl.state == SceListState::Running && pausePending(dl))
        return fail(sce::kErrorBusy, "the list is on its way to a signal pause");
    if (dl.state == SceListState::Running) return fail(newSdk ? sce::kErrorAlready : -1, "the current list is not paused");
    return fail(newSdk ? sce::kErrorInvalidState : -1, "the current list cannot be continued");
}

s32 SceGe::setCallback(u32 signalFunc, u32 signalArg, u32 finishFunc, u32 finishArg) {
    for (int k = 0; k < kMaxCallbacks; ++k)
        if (!callbacks_[k].used) {
            callbacks_[k] = Callback{true, signalFunc, signalArg, finishFunc, finishArg};
            return k;
        }
    return fail(sce::kErrorOutOfMemory, "all 16 callback slots are in use");
}

s32 SceGe::unsetCallback(s32 cbid) {
    if (cbid < 0 || cbid >= kMaxCallbacks) return fail(sce::kErrorInvalidId, fmt("callback ID %u is out of range 0-15", u32(cbid)));
    callbacks_[cbid] = Callback{};
    return sce::kOk;
}

// ---------------------------------------------------------------------------------------------
// Context and readback.

bool SceGe::busyDrawing() const { return !queue_.empty() && lists_[queue_.front()].state == SceListState::Running; }

s32 SceGe::saveContext(u32 out[512]) {
    // The firmware refuses while the GE executes (uOFW returns -1, PPSSPP busy); a stalled list
    // still counts as executing.
    // pspautotests gpu/ge/context: -1 (the restore answers busy); uOFW sceGeSaveContext too.
    if (busyDrawing()) return fail(-1, "cannot save the context while a list is drawing (the firmware returns -1)");
    engine_.state().saveContext(out);
    return sce::kOk;
}

s32 SceGe::restoreContext(const u32 in[512]) {
    if (busyDrawing()) return fail(sce::kErrorBusy, "cannot restore the context while a list is drawing");
    // Check the layout on a copy first, so a corrupt context changes nothing.
    GeState probe = engine_.state();
    if (!probe.loadContext(in)) return fail(sce::kErrorInvalidValue, "context words do not have the sceGeSaveContext layout; nothing restored");
    engine_.loadContext(in);
    return sce::kOk;
}

s32 SceGe::saveContextTo(u32 addr) {
    if (addr & 3) return fail(sce::kErrorInvalidPointer, fmt("context address 0x%08x is not 4-byte aligned", addr));
    if (!engine_.memory().valid(addr, 2048)) return fail(sce::kErrorBadPointer, fmt("context 0x%08x (2048 bytes) is outside guest memory", addr));
    u32 ctx[512];
    s32 r = saveContext(ctx);
    if (r < 0) return r;
    writeContext(addr, ctx);
    return sce::kOk;
}

s32 SceGe::restoreContextFrom(u32 addr) {
    if (addr & 3) return fail(sce::kErrorInvalidPointer, fmt("context address 0x%08x is not 4-byte aligned", addr));
    u32 ctx[512];
    if (!readContext(addr, ctx)) return fail(sce::kErrorBadPointer, fmt("context 0x%08x (2048 bytes) is outside guest memory", addr));
    return restoreContext(ctx);
}

s32 SceGe::getCmd(u32 op, u32* out) const {
    // uOFW rejects op >= 0xFF (0xFF is an unknown opcode anyway).
    if (op >= 0xFF) return fail(sce::kErrorInvalidIndex, fmt("opcode 0x%x is out of range 0-0xFE", op));
    const GeState& st = engine_.state();
    const u32 hi = op << 24;
    u32 v;
    switch (op) {
    // Matrix data ports read back as the bare opcode; number registers as the current upload
    // index (ge-rules.md §1).
    case GE_CMD_BONED:
    case GE_CMD_WORLDD:
    case GE_CMD_VIEWD:
    case GE_CMD_PROJD:
    case GE_CMD_TGEND: v = hi; break;
    case GE_CMD_BONEN: v = hi | (st.boneNum & 0x7F); break;
    case GE_CMD_WORLDN: v = hi | (st.worldNum & 0xF); break;
    case GE_CMD_VIEWN: v = hi | (st.viewNum & 0xF); break;
    case GE_CMD_PROJN: v = hi | (st.projNum & 0xF); break;
    case GE_CMD_TGENN: v = hi | (st.tgenNum & 0xF); break;
    // The register file latches whole words; a slot never written since power-on holds what the
    // firmware's boot-time context list wrote: the bare opcode.
    default: v = hi | (st.regs[op] & 0xFFFFFF); break;
    }
    if (out) *out = v;
    return sce::kOk;
}

s32 SceGe::getMtx(int type, u32 out[16], int* count) const {
    if (type < 0 || type >= 12) return fail(sce::kErrorInvalidIndex, fmt("matrix type %u is out of range 0-11", u32(type)));
    // The words as the data ports wrote them, overflow included (GeState::visibleMtx).
    const GeState& st = engine_.state();
    u32 base;
    int n = 12;
    if (type < 8) base = 12 * u32(type);
    else if (type == 8) base = 96;
    else if (type == 9) base = 108;
    else if (type == 10) base = 120, n = 16;
    else base = 136;
    for (int k = 0; k < n; ++k) out[k] = st.visibleMtx[base + u32(k)];
    if (count) *count = n;
    return sce::kOk;
}

s32 SceGe::getStack(s32 index, u32 out[8]) const {
    // pspautotests gpu/ge/get: 0 outside a list for any index; inside a SIGNAL CALL handler the
    // depth for index -1 and 0 and an invalid index error for 255.
    if (active_ < 0) return 0;
    const auto& frames = engine_.list().signalStack;
    const s32 depth = s32(frames.size());
    if (index >= depth) return fail(sce::kErrorInvalidIndex, fmt("stack index %d is not below the depth %d", index, depth));
    if (index >= 0 && out) {
        for (int k = 0; k < 8; ++k) out[k] = 0;
        out[1] = frames[size_t(index)].pc;
        out[2] = frames[size_t(index)].offset;
        out[7] = frames[size_t(index)].base;
    }
    return depth;
}

s32 SceGe::edramSetAddrTranslation(u32 value) {
    const u32 prev = engine_.memory().edramTranslation();
    if (!engine_.memory().setEdramTranslation(value))
        return fail(sce::kErrorInvalidValue, fmt("eDRAM translation 0x%x is not one of 0, 0x200, 0x400, 0x800, 0x1000", value));
    return s32(prev);
}

// ---------------------------------------------------------------------------------------------
// Execution.

bool SceGe::canProgress() const {
    if (queue_.empty()) return false;
    const int i = queue_.front();
    const DisplayList& dl = lists_[i];
    switch (dl.state) {
    case SceListState::Queued: return true;
    case SceListState::Running: return !dl.hung && !isStalled(dl, i);
    default: return false;
    }
}

SceRunResult SceGe::peekRun() const {
    SceRunResult r;
    if (queue_.empty()) return r;
    const int i = queue_.front();
    const DisplayList& dl = lists_[i];
    r.listId = idOf(i);
    r.pc = listPc(dl, i);
    r.stall = dl.stall;
    if (dl.state == SceListState::Paused) r.state = SceRunState::Paused;
    else if (dl.state == SceListState::Running && dl.hung) r.state = SceRunState::Hung;
    else if (dl.state == SceListState::Running && isStalled(dl, i)) r.state = SceRunState::Stalled;
    else r.state = SceRunState::Budget;
    return r;
}

SceRunResult SceGe::run(u64 maxCommands) { return runInternal(maxCommands, -1); }

SceRunResult SceGe::runUntil(u64 maxCommands, s32 stopAfterId) { return runInternal(maxCommands, slotOf(stopAfterId)); }

void SceGe::requestYield() {
    if (!inRun_) return;  // between runs there is nothing to stop
    yield_ = true;
    // Inside the engine: stop after the current command (run() resumes a list it finds paused
    // this way, as it does after a pause requested from a callback that was then continued).
    if (inEngine_) engine_.requestPause();
}

SceRunResult SceGe::runInternal(u64 maxCommands, int stopAfter) {
    if (inRun_) {
        message_ = "run() cannot be called from inside a GE callback";
        SceRunResult r = peekRun();
        r.state = SceRunState::Reentrant;
        return r;
    }
    inRun_ = true;
    u64 used = 0;
    bool broke = false, timeLimit = false;
    for (;;) {
        if (queue_.empty()) break;
        if (engine_.stats().cycles >= tickStop_) break;
        const int i = queue_.front();
        DisplayList& dl = lists_[i];
        if (dl.state == SceListState::Queued) startFront();
        if (dl.state != SceListState::Running || dl.hung) break;
        load(i);
        if (isStalled(dl, i) || used >= maxCommands) break;
        // A pause requested from a callback that has since been continued (or a finished signal
        // pause): the list is running again, so let the engine go on.
        if (engine_.status() == RunStatus::Paused) engine_.resume();
        finishPending_ = false;
        const u64 before = engine_.stats().commands, cyclesBefore = engine_.stats().cycles;
        inEngine_ = true;
        const RunStatus s = engine_.run(maxCommands - used);
        inEngine_ = false;
        // The GE time of this pass is the list's (load() charged its start; the next list's
        // start, when this one completes below, is that list's).
        dl.cycles += engine_.stats().cycles - cyclesBefore;
        used += engine_.stats().commands - before;
        if (engine_.broke()) {
            broke = true;
            break;
        }
        if (s == RunStatus::TimeLimit) {
            // The host's limit, not the list's: the list stays running and the next run goes on.
            timeLimit = true;
            break;
        }
        if (s == RunStatus::Completed || s == RunStatus::Error) {
            // An error drops the list and the queue moves on (PPSSPP); the error callback has
            // already been delivered.
            if (!queue_.empty() && queue_.front() == i && active_ == i) completeFront(s == RunStatus::Error);
            if (i == stopAfter) break;
        } else if (s == RunStatus::Ended && active_ == i) {
            // END without SIGNAL/FINISH: the GE stops and the list never finishes (uOFW; ge-rules.md §4.3).
            dl.hung = true;
            const u32 pc = engine_.list().pc;
            message_ = fmt("END without SIGNAL or FINISH before 0x%08x: the GE stops and list ", pc) +
                       fmt("0x%08x stays unfinished (uOFW behaviour); sceGeBreak(1) resets the queue", u32(idOf(i)));
            if (listener_) listener_->onError(idOf(i), pc, message_);
        }
        if (yield_) break;
    }
    yield_ = false;
    inRun_ = false;
    SceRunResult r = peekRun();
    r.commands = used;
    if (broke) r.state = SceRunState::Break;
    else if (timeLimit) r.state = SceRunState::TimeLimit;
    return r;
}

}  // namespace ge
