// SPDX-License-Identifier: MIT
// FrameRecorder: see recorder.h, docs/recording.md and docs/ppdmp.md §3–§7. The structure
// follows PPSSPP's GPU/Debugger/Record.cpp (NotifyCommand, CheckEdramTrans; the record rules are
// in record_builder.cpp); the code is our own.
#include "hle/dump/recorder.h"

#include <cstring>
#include <stdexcept>

namespace ge::dump {

namespace {

bool isMatrixOp(int op) {
    return op == GE_CMD_BONEN || op == GE_CMD_BONED || (op >= GE_CMD_WORLDN && op <= GE_CMD_TGEND);
}

}  // namespace

// Sits between the engine and its backend while recording: every call goes through unchanged;
// memoryWritten() from the host side (the engine's own transfers reach the backend through
// blockTransfer, forwarded whole, so the backend's internal notices never come here) is also a
// CPU/DMA write for the dump.
class FrameRecorder::HostWriteHook final : public Renderer {
public:
    HostWriteHook(FrameRecorder& rec, Renderer& inner) : rec_(rec), in_(inner) {}
    void drawPrim(const PrimPacket& p) override { in_.drawPrim(p); }
    void drawPatch(const PatchPacket& p) override { in_.drawPatch(p); }
    void drawImmediate(const ImmPacket& p) override { in_.drawImmediate(p); }
    void blockTransfer(const TransferPacket& t, Memory& mem) override { in_.blockTransfer(t, mem); }
    void clutLoaded(const GeState& s) override { in_.clutLoaded(s); }
    void textureFlush() override { in_.textureFlush(); }
    void textureSync() override { in_.textureSync(); }
    void finish() override { in_.finish(); }
    void syncMemoryForRead(u32 addr, u32 size) override { in_.syncMemoryForRead(addr, size); }
    void memoryWritten(u32 addr, u32 size) override {
        in_.memoryWritten(addr, size);
        rec_.hostWrote(addr, size);
    }
    void flushToMemory() override { in_.flushToMemory(); }
    void hostMayHaveWritten(bool fb) override { in_.hostMayHaveWritten(fb); }
    void takeDirtyRanges(std::vector<std::pair<u32, u32>>& out) override { in_.takeDirtyRanges(out); }
    bool holdsNewerThanMemory(u32 addr, u32 size) const override { return in_.holdsNewerThanMemory(addr, size); }
    u64 pixelWork() const override { return in_.pixelWork(); }
    void setPixelBudget(u64 pixels) override { in_.setPixelBudget(pixels); }

private:
    FrameRecorder& rec_;
    Renderer& in_;
};

FrameRecorder::FrameRecorder(GeEngine& engine, std::string gameId)
    : eng_(engine), out_(std::move(gameId)), rec_(out_, engine.memory(), {}) {
    // A backend drawing on the GPU holds render targets' newest pixels: bring them to VRAM.
    rec_.setVramReadHook([this](u32 addr, u32 size) { eng_.renderer()->syncMemoryForRead(addr, size); });
}

// Never touches the engine (recorder.h): the owner detaches first, or the engine is gone.
FrameRecorder::~FrameRecorder() = default;

void FrameRecorder::begin() {
    if (attached_) return;
    const GeState& st = eng_.state();
    // Record.cpp BeginRecording: INIT (the context, ppdmp.md §5), then the CLUT cache at the start (the
    // 1024-byte palette RAM; ppdmp.md §2.1 "a CLUT record right after INIT"), then the frame shown.
    u32 ctx[512];
    st.saveContext(ctx);
    out_.init(ctx);
    out_.clut(st.clut, sizeof st.clut);
    rec_.initialClutWritten();
    out_.display(st.framebufAddr(), st.framebufStride(), st.framebufFormat());
    rec_.reset();
    lastEdram_ = 0x400;  // the boot value PPSSPP's recorder assumes
    checkEdram();
    before_ = st;
    lastOp_ = -1;
    lastCount_ = ~u64(0);
    inner_ = eng_.renderer();
    hook_ = std::make_unique<HostWriteHook>(*this, *inner_);
    eng_.setRenderer(hook_.get());
    eng_.addObserver(this);
    attached_ = true;
}

void FrameRecorder::detach() {
    if (!attached_) return;
    eng_.removeObserver(this);
    if (eng_.renderer() == hook_.get()) eng_.setRenderer(inner_);
    attached_ = false;
}

void FrameRecorder::display(u32 addr, u32 stride, u32 format) {
    if (!attached_) return;
    checkEdram();
    rec_.flushBlock();
    out_.display(addr, stride, format & 0xFF);
    haveHostDisplay_ = true;
    dispAddr_ = addr, dispStride_ = stride, dispFormat_ = format & 0xFF;
}

void FrameRecorder::end() {
    if (!attached_) return;
    checkEdram();
    rec_.flushBlock();
    // ppdmp.md §7 rule 3: DISPLAY is the very last record. A DISPLAY the host just gave is that record.
    const std::vector<Record>& recs = out_.dump().records;
    const bool lastIsHostDisplay = haveHostDisplay_ && !recs.empty() && recs.back().type == DISPLAY;
    if (!lastIsHostDisplay) {
        if (haveHostDisplay_) {
            out_.display(dispAddr_, dispStride_, dispFormat_);
        } else {
            const GeState& st = eng_.state();
            out_.display(st.framebufAddr(), st.framebufStride(), st.framebufFormat());
        }
    }
    detach();
}

// Record.cpp CheckEdramTrans: an EDRAMTRANS record whenever the value changed.
void FrameRecorder::checkEdram() {
    const u32 v = eng_.memory().edramTranslation();
    if (v == lastEdram_) return;
    rec_.flushBlock();
    out_.edramTrans(v);
    lastEdram_ = v;
}

// The registers may change without a command: sceGeRestoreContext, a save-state load. A command
// writes only its own register (a matrix port also the matrix and its index; CLOAD the palette),
// so anything else that differs from the state before the previous command came from outside.
// The whole context then goes into the list as state words, as the firmware restores a context
// by running words 17–383 of it (ppdmp.md §5), minus the words a REGISTERS block must not
// hold (ppdmp.md §7 rule 4). PPSSPP's recorder does not notice restores; a dump of a frame with one
// would otherwise replay with the state from before it.
void FrameRecorder::checkExternalChanges() {
    const GeState& s = eng_.state();
    bool changed = false;
    const bool matrixOp = isMatrixOp(lastOp_);
    for (int i = 0; i < 256 && !changed; ++i)
        if (s.regs[i] != before_.regs[i] && i != lastOp_ && !(matrixOp && isMatrixOp(i))) changed = true;
    if (!changed && !matrixOp) {
        changed = std::memcmp(s.bone, before_.bone, sizeof s.bone) || std::memcmp(s.world, before_.world, sizeof s.world) ||
                  std::memcmp(s.view, before_.view, sizeof s.view) || std::memcmp(s.proj, before_.proj, sizeof s.proj) ||
                  std::memcmp(s.tgen, before_.tgen, sizeof s.tgen) || s.boneNum != before_.boneNum ||
                  s.worldNum != before_.worldNum || s.viewNum != before_.viewNum || s.projNum != before_.projNum ||
                  s.tgenNum != before_.tgenNum;
    }
    if (lastOp_ != GE_CMD_CLOAD && std::memcmp(s.clut, before_.clut, sizeof s.clut) != 0)
        rec_.warn("palette RAM changed outside the display list (a context or state load): not in the dump");
    if (!changed) return;
    u32 ctx[512];
    s.saveContext(ctx);
    for (int i = 17; i < 384; ++i) {
        const u32 op = ctx[i] >> 24;
        if (op == GE_CMD_NOP || RecordBuilder::notRecorded(op)) continue;
        rec_.stateWord(ctx[i]);
    }
}

bool FrameRecorder::beforeCommand(u32 pc, u32 word) {
    if (!attached_ || !failure_.empty()) return true;
    // Nothing may escape into the engine's run loop: a dump over the writer's limits ends the
    // recording (end() reports it), the GE goes on.
    try {
        record(pc, word);
    } catch (const std::exception& e) {
        failure_ = std::string("recording stopped: ") + e.what();
    }
    return true;
}

void FrameRecorder::record(u32 pc, u32 word) {
    checkExternalChanges();
    checkEdram();
    // An observer after this one (a debugger breakpoint) may stop the run before the command: the
    // engine then asks again for the same command, which must not be recorded twice. Executed
    // commands advance stats().commands, so the same count and pc mean the same command.
    const u64 count = eng_.stats().commands;
    if (count == lastCount_ && pc == lastPc_) return;
    lastCount_ = count;
    lastPc_ = pc;
    const u32 op = word >> 24;
    const GeState& st = eng_.state();
    switch (op) {
    case GE_CMD_PRIM: rec_.draw(st, word, word & 0xFFFF); break;
    // Patches read Ucount × Vcount control points (Record.cpp EmitBezierSpline).
    case GE_CMD_BEZIER:
    case GE_CMD_SPLINE: rec_.draw(st, word, (word & 0xFF) * ((word >> 8) & 0xFF)); break;
    case GE_CMD_CLOAD: rec_.clut(st, word); break;
    case GE_CMD_XSTART: rec_.transfer(st, word); break;
    default: rec_.command(word); break;
    }
    before_ = eng_.state();
    lastOp_ = int(op);
}

// Record.cpp NotifyMemcpy / NotifyMemset (RecordBuilder::hostWrite).
void FrameRecorder::hostWrote(u32 addr, u32 size) {
    if (!attached_ || !failure_.empty()) return;
    try {
        recordHostWrite(addr, size);
    } catch (const std::exception& e) {
        failure_ = std::string("recording stopped: ") + e.what();
    }
}

void FrameRecorder::recordHostWrite(u32 addr, u32 size) {
    checkEdram();
    rec_.hostWrite(addr, size);
}

}  // namespace ge::dump
