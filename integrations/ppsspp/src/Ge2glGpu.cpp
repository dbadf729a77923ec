// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp). This file is compiled into PPSSPP,
// which is licensed under the GNU GPL version 2.0 or later; so is this file.
//
// GPU_Ge2gl (Ge2glGpu.h says how PPSSPP and libge2gl meet).
#include "GPU/Ge2gl/Ge2glGpu.h"

#include <ge2gl/ge2gl.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "Common/Data/Text/StringWriter.h"
#include "Common/GPU/thin3d.h"
#include "Common/Log.h"
#include "Common/Serialize/Serializer.h"
#include "Common/Serialize/SerializeFuncs.h"
#include "Common/Serialize/SerializeSet.h"
#include "Core/Config.h"
#include "Core/CoreParameter.h"
#include "Core/CoreTiming.h"
#include "Core/HLE/ErrorCodes.h"
#include "Core/HLE/sceGe.h"
#include "Core/HLE/sceKernelInterrupt.h"
#include "Core/HLE/sceKernelMemory.h"
#include "Core/HLE/sceKernelThread.h"
#include "Core/MIPS/MIPS.h"
#include "Core/MemMap.h"
#include "Core/SaveState.h"
#include "Core/System.h"
#include "GPU/Common/GPUDebugInterface.h"
#include "GPU/Common/PresentationCommon.h"

namespace {

// list ID = slot ^ this, as ge2gl (hle/sce_ge.h kIdMask) and PPSSPP's sceGe both number lists.
constexpr uint32_t kIdMask = 0x35000000;
constexpr int kSlots = 64;

GPU_Ge2gl *g_active = nullptr;

int SlotOf(int32_t id) {
    const uint32_t slot = uint32_t(id) ^ kIdMask;
    return slot < uint32_t(kSlots) ? int(slot) : -1;
}
int32_t IdOf(int slot) { return int32_t(uint32_t(slot) ^ kIdMask); }

void SliceEvent(u64, int) {
    if (g_active) g_active->OnSliceEvent();
}
void InterruptEvent(u64, int) {
    if (g_active) g_active->OnInterruptEvent();
}

}  // namespace

// The interrupt handler object PPSSPP owns (intrHandlers[PSP_GE_INTR]) and the core share this:
// PPSSPP deletes the handler when it registers its own again (a kernel re-init on LoadExec), and
// the core may be destroyed before the kernel; each side learns of the other's end here.
struct GPU_Ge2gl::Link {
    GPU_Ge2gl *core = nullptr;
    bool handlerRegistered = false;
};

namespace {

// PPSSPP's GE interrupt handler reads PPSSPP's own list records; with ge2gl's GE this one takes
// its place and starts the game's sub-interrupt handler (registered by sceGeSetCallback, as the
// firmware registers them) for what ge2gl reported.
template <class LinkT>
class Ge2glIntrHandler : public IntrHandler {
public:
    explicit Ge2glIntrHandler(std::shared_ptr<LinkT> link) : IntrHandler(PSP_GE_INTR), link_(std::move(link)) {}
    // PPSSPP deletes interrupt handlers when its kernel shuts down (HLEShutdown, before it frees
    // guest memory; also when LoadExec restarts the kernel) or registers its own again.
    ~Ge2glIntrHandler() override {
        link_->handlerRegistered = false;
        if (link_->core) link_->core->KernelStopping();
    }
    bool run(PendingInterrupt &) override { return link_->core ? link_->core->StartInterrupt(*this) : false; }
    void handleResult(PendingInterrupt &) override {
        if (link_->core) link_->core->FinishInterrupt();
    }

private:
    std::shared_ptr<LinkT> link_;
};

}  // namespace

bool Ge2gl_Selected() { return g_Config.iGe2glBackend != 0; }

GPUCommon *Ge2gl_CreateGPU(GraphicsContext *gfxCtx, Draw::DrawContext *draw) {
    GPU_Ge2gl *gpu = new GPU_Ge2gl(gfxCtx, draw);
    if (!gpu->Started()) {
        ERROR_LOG(Log::G3D, "ge2gl: %s", gpu->StartError().c_str());
        fprintf(stderr, "ge2gl: %s\n", gpu->StartError().c_str());
        delete gpu;
        return nullptr;
    }
    return gpu;
}

GPU_Ge2gl *GPU_Ge2gl::Active() { return g_active; }

GPU_Ge2gl::GPU_Ge2gl(GraphicsContext *gfxCtx, Draw::DrawContext *draw)
    : GPUCommon(gfxCtx, draw), link_(std::make_shared<Link>()) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    // PPSSPP's own RAM and VRAM, used in place: the game's writes are the GE's reads.
    cfg.ram = Memory::GetPointerWriteRangeOrException(PSP_GetKernelMemoryBase(), Memory::g_MemorySize);
    cfg.ram_size = Memory::g_MemorySize;
    cfg.vram = Memory::GetPointerWriteRangeOrException(PSP_GetVidMemBase(), 0x00200000);
    cfg.sdk_version = uint32_t(sceKernelGetCompiledSdkVersion());
    cfg.hold_interrupts = 1;
    // One ge2gl_run_until executes at most this many commands; a list that needs more goes on in
    // the next CoreTiming slice, so no single emulated instant blocks on an endless list.
    cfg.wait_budget = uint64_t(1) << 22;
    cfg.callbacks.user = this;
    cfg.callbacks.signal = &GPU_Ge2gl::CbSignal;
    cfg.callbacks.finish = &GPU_Ge2gl::CbFinish;
    cfg.callbacks.error = &GPU_Ge2gl::CbError;
    const char *backendName = "software model";
    switch (g_Config.iGe2glBackend) {
    case 2:
    case 3:
        cfg.backend = GE2GL_BACKEND_GL_HEADLESS;
        cfg.gl_use_egl = g_Config.bGe2glEgl ? 1 : 0;
        cfg.gl_mode = g_Config.iGe2glBackend == 3 ? GE2GL_GL_MODE_HW : GE2GL_GL_MODE_EXACT;
        if (cfg.gl_mode == GE2GL_GL_MODE_HW) {
            // PPSSPP's render-scale setting: the headless runner's --resolution-scale, else
            // the InternalResolution setting (0 = auto, taken as 1x).
            int scale = PSP_CoreParameter().renderScaleFactor;
            if (scale <= 0) scale = g_Config.iInternalResolution;
            cfg.render_scale = std::clamp(scale, 1, 8);
        }
        backendName = cfg.gl_mode == GE2GL_GL_MODE_HW ? "OpenGL hardware mode" : "OpenGL exact mode";
        break;
    default:
        cfg.backend = GE2GL_BACKEND_SOFT;
        break;
    }
    const ge2gl_status s = ge2gl_create(&cfg, &ge_);
    if (s != GE2GL_OK) {
        startError_ = std::string("cannot start the ") + backendName + ": " + ge2gl_status_name(s) + ": " + ge2gl_last_message(nullptr);
        ge_ = nullptr;
        return;
    }
    INFO_LOG(Log::G3D, "ge2gl: GE started (%s%s, scale %d, API %08x)", backendName,
             cfg.backend == GE2GL_BACKEND_GL_HEADLESS ? (cfg.gl_use_egl ? ", EGL" : ", OSMesa") : "", cfg.render_scale,
             ge2gl_api_version());
    g_active = this;
    link_->core = this;
    timeline_.restore(0, int64_t(CoreTiming::GetTicks(currentMIPS)), CoreTiming::GetClockFrequencyHz());
    lookaheadCpu_ = int64_t(CoreTiming::GetClockFrequencyHz());  // one second of emulated time
    sliceEvent_ = CoreTiming::RegisterEvent("Ge2glSlice", &SliceEvent);
    interruptEvent_ = CoreTiming::RegisterEvent("Ge2glInterrupt", &InterruptEvent);
    EnsureIntrHandler();
    SyncSdkVersion();
    RefreshRegisters();
    if (const char *v = getenv("GE2GL_STATE_ROUNDTRIP"); v && *v == '1') stateRoundTrip_ = true;
    // GE2GL_RECORD=FILE: everything this core's GE executes, written as a .ppdmp frame dump when
    // the emulation stops (ge2gl_record_*), for `ge2gl render`/`compare`/`bisect` on the same GE
    // work outside PPSSPP.
    if (const char *path = getenv("GE2GL_RECORD"); path && *path) {
        if (ge2gl_record_begin(ge_, path) == GE2GL_OK) recording_ = true;
        else ERROR_LOG(Log::G3D, "ge2gl: GE2GL_RECORD: %s", ge2gl_last_message(ge_));
    }

    if (gfxCtx && draw) {
        presentation_ = new PresentationCommon(draw_);
        presentation_->SetLanguage(draw_->GetShaderLanguageDesc().shaderLanguage);
        presentation_->UpdateDisplaySize(PSP_CoreParameter().pixelWidth, PSP_CoreParameter().pixelHeight);
        presentation_->UpdateRenderSize(PSP_CoreParameter().renderWidth, PSP_CoreParameter().renderHeight);
    }
}

void GPU_Ge2gl::KernelStopping() {
    // PPSSPP frees guest memory before it destroys the GPU core (PSP_Shutdown: CPU_Shutdown, then
    // GPU_Shutdown): everything that still writes guest memory ends here, while it exists - the
    // software model's rasterising threads finish their queued draws, a GL backend writes its
    // targets back, a recording is written.
    if (!ge_ || kernelStopped_) return;
    kernelStopped_ = true;
    if (recording_) {
        recording_ = false;
        if (displayFramebuf_) ge2gl_record_display(ge_, displayFramebuf_, displayStride_, int32_t(displayFormat_));
        if (ge2gl_record_end(ge_) != GE2GL_OK) ERROR_LOG(Log::G3D, "ge2gl: GE2GL_RECORD: %s", ge2gl_last_message(ge_));
    }
    ge2gl_sync_range(ge_, PSP_GetVidMemBase(), 0x00200000);
    ge2gl_sync_range(ge_, PSP_GetKernelMemoryBase(), Memory::g_MemorySize);
}

GPU_Ge2gl::~GPU_Ge2gl() {
    if (stateRoundTrip_) fprintf(stderr, "ge2gl: %d save-state round trips, %d failed\n", roundTrips_, roundTripFailures_);
    KernelStopping();
    link_->core = nullptr;
    if (g_active == this) g_active = nullptr;
    if (frameTexture_) frameTexture_->Release();
    delete presentation_;
    ge2gl_destroy(ge_);
}

void GPU_Ge2gl::EnsureIntrHandler() {
    if (link_->handlerRegistered) return;
    link_->handlerRegistered = true;
    kernelStopped_ = false;
    __RegisterIntrHandler(PSP_GE_INTR, new Ge2glIntrHandler<Link>(link_));
}

int64_t GPU_Ge2gl::Now() const { return int64_t(CoreTiming::GetTicks(currentMIPS)); }

uint64_t GPU_Ge2gl::GeTick() const {
    uint64_t t = 0;
    ge2gl_get_tick(ge_, &t);
    return t;
}

int32_t GPU_Ge2gl::Reported(int32_t s, const char *what) const {
    // sceGe failures are PSP kernel error codes, handed to the game as they are. The API's own
    // (small negative) codes mean this glue used the API wrongly: say so loudly.
    if (s < 0 && s > -100) ERROR_LOG(Log::sceGe, "ge2gl: %s: %s (%s)", what, ge2gl_status_name(s), ge2gl_last_message(ge_));
    return s;
}

// ---------------------------------------------------------------------------------------------
// Running the GE.

void GPU_Ge2gl::SyncSdkVersion() {
    // Games may change it at run time (sceKernelSetCompiledSdkVersion*; pspautotests gpu/ge/queue
    // switches between 0 and 2.00 to test both behaviours).
    const uint32_t v = uint32_t(sceKernelGetCompiledSdkVersion());
    if (v == sdkVersion_ || !ge_) return;
    sdkVersion_ = v;
    ge2gl_set_sdk_version(ge_, v);
}

void GPU_Ge2gl::RunGe() {
    if (!ge_ || running_) return;
    running_ = true;
    EnsureIntrHandler();
    if (!held_) {
        const int64_t now = Now();
        uint64_t ge = GeTick();
        timeline_.setCpuHz(ge, CoreTiming::GetClockFrequencyHz());
        if (geWaiting_) timeline_.resume(ge, now);
        ge2gl_run_info info{};
        const ge2gl_status s = ge2gl_run_until(ge_, timeline_.geTickAt(now + lookaheadCpu_), &info);
        if (s != GE2GL_OK) Reported(s, "run_until");
        ge = GeTick();
        const int64_t stopped = timeline_.cpuTickOf(ge);
        switch (info.ge_state) {
        case GE2GL_GE_READY:
            // The look-ahead or the command budget ran out: go on once the CPU has caught up
            // half of the way (at once after a budget stop short of the look-ahead).
            geWaiting_ = false;
            CoreTiming::ScheduleEvent(std::max<int64_t>(0, stopped - now - lookaheadCpu_ / 2), sliceEvent_, 0);
            break;
        case GE2GL_GE_INTERRUPT:
            held_ = true;
            geWaiting_ = true;  // resumes when the handler returns
            break;
        default:  // idle, stalled, paused, hung: the GE waits for the CPU
            geWaiting_ = true;
            if (SlotOf(info.list_id) >= 0) reachedAt_[SlotOf(info.list_id)] = stopped;
            break;
        }
    }
    RefreshRegisters();
    ResolveWaits();
    running_ = false;
}

void GPU_Ge2gl::OnSliceEvent() { RunGe(); }

void GPU_Ge2gl::CbSignal(void *user, const ge2gl_interrupt *irq) { static_cast<GPU_Ge2gl *>(user)->QueueInterrupt(*irq, false); }
void GPU_Ge2gl::CbFinish(void *user, const ge2gl_interrupt *irq) { static_cast<GPU_Ge2gl *>(user)->QueueInterrupt(*irq, true); }
void GPU_Ge2gl::CbError(void *, int32_t listId, uint32_t pc, const char *message) {
    ERROR_LOG(Log::sceGe, "ge2gl: list %08x at %08x: %s", uint32_t(listId), pc, message);
}

// Inside ge2gl_run_until: ge2gl will hold the GE after this callback. The interrupt reaches the
// game at the CPU tick the GE's work got to.
void GPU_Ge2gl::QueueInterrupt(const ge2gl_interrupt &irq, bool finish) {
    Pending p;
    p.listId = irq.list_id;
    p.cbid = irq.cbid;
    p.arg = irq.arg;
    p.pc = irq.pc;
    p.finish = finish;
    p.cpuTick = timeline_.cpuTickOf(irq.tick);
    const int slot = SlotOf(irq.list_id);
    p.guest = slot >= 0 && !noInterrupts_[slot];
    if (finish && slot >= 0) reachedAt_[slot] = p.cpuTick;
    pending_.push_back(p);
    CoreTiming::ScheduleEvent(std::max<int64_t>(0, p.cpuTick - Now()), interruptEvent_, 0);
}

void GPU_Ge2gl::OnInterruptEvent() {
    // GE2GL_STATE_ROUNDTRIP=1 (a test knob, docs in README.md): at every GE interrupt - mid-list,
    // with the GE holding the interrupt and events pending - PPSSPP's whole state, this core's
    // included, is saved to memory and loaded back before the emulation goes on; the output of a
    // run must not change.
    if (stateRoundTrip_) {
        std::vector<u8> state;
        std::string why;
        const bool ok = SaveState::SaveToRam(state) == CChunkFileReader::ERROR_NONE &&
                        SaveState::LoadFromRam(state, &why) == CChunkFileReader::ERROR_NONE;
        ++(ok ? roundTrips_ : roundTripFailures_);
        if (!ok) ERROR_LOG(Log::G3D, "ge2gl: save state round trip failed: %s", why.c_str());
    }
    // As PPSSPP's own GE does: the interrupt is raised at its tick and runs when the CPU can take
    // it (interrupts enabled, not already in one).
    __TriggerInterrupt(PSP_INTR_IMMEDIATE, PSP_GE_INTR, PSP_INTR_SUB_NONE);
}

bool GPU_Ge2gl::StartInterrupt(IntrHandler &handler) {
    if (pending_.empty()) return false;
    const Pending &p = pending_.front();
    if (p.guest && p.cbid >= 0) {
        SubIntrHandler *sub = handler.get(p.cbid * 2 + (p.finish ? PSP_GE_SUBINTR_FINISH : PSP_GE_SUBINTR_SIGNAL));
        if (sub && sub->enabled) {
            // The callback's arguments (pspsdk PspGeCallback): the SIGNAL/FINISH argument, the
            // argument given to sceGeSetCallback, the list address (ge2gl gives 0 for old SDKs).
            currentMIPS->pc = sub->handlerAddress;
            currentMIPS->r[MIPS_REG_A0] = p.arg & 0xFFFF;
            currentMIPS->r[MIPS_REG_A1] = sub->handlerArg;
            currentMIPS->r[MIPS_REG_A2] = p.pc;
            return true;
        }
    }
    FinishInterrupt();
    return false;
}

void GPU_Ge2gl::FinishInterrupt() {
    if (pending_.empty()) return;
    pending_.pop_front();
    if (pending_.empty() && held_) {
        held_ = false;
        Reported(ge2gl_interrupt_ack(ge_), "interrupt_ack");
    }
    RunGe();
}

bool GPU_Ge2gl::PendingFor(int32_t id) const {
    for (const Pending &p : pending_)
        if (p.listId == id) return true;
    return false;
}

// A sync call does not wait for an interrupt that is already due: on a PSP it would have run the
// moment the GE raised it, before the CPU got to the call; here it runs once the call returns, as
// with PPSSPP's own GE (pspautotests gpu/bounding/*: sceGuSync right after a short list does not
// reschedule). id < 0: any list.
bool GPU_Ge2gl::PendingLater(int32_t id, int64_t now) const {
    for (const Pending &p : pending_)
        if ((id < 0 || p.listId == id) && p.cpuTick > now) return true;
    return false;
}

// Threads waiting in sceGeListSync / sceGeDrawSync wake once their list is gone or complete and
// its finish interrupt has been handled (the firmware wakes them from that interrupt).
void GPU_Ge2gl::ResolveWaits() {
    for (auto it = waitingLists_.begin(); it != waitingLists_.end();) {
        int32_t state = -1;
        const int32_t id = IdOf(*it);
        const ge2gl_status s = ge2gl_list_sync(ge_, id, GE2GL_SYNC_PEEK, &state);
        if ((s != GE2GL_OK || state == GE2GL_LIST_COMPLETED) && !PendingFor(id)) {
            __GeTriggerWait(GPU_SYNC_LIST, *it);
            it = waitingLists_.erase(it);
        } else {
            ++it;
        }
    }
    if (drawWaiting_) {
        int32_t state = -1;
        if (ge2gl_draw_sync(ge_, GE2GL_SYNC_PEEK, &state) == GE2GL_OK && state == GE2GL_LIST_COMPLETED && pending_.empty()) {
            drawWaiting_ = false;
            __GeTriggerWait(GPU_SYNC_DRAW, 1);
        }
    }
}

void GPU_Ge2gl::RefreshRegisters() {
    // PPSSPP code outside the GE reads `gstate` (the dump player: TRANSFERSRCW); keep it ge2gl's.
    if (ge2gl_get_registers(ge_, gstate.cmdmem) != GE2GL_OK) return;
    const uint8_t *g = reinterpret_cast<const uint8_t *>(&gstate);
    shadow_.assign(g, g + sizeof(gstate));
}

void GPU_Ge2gl::ReapplyGfxState() {
    // Called after PPSSPP code restored `gstate` itself (the dump player's INIT record, a save
    // state of another core) and at every host frame: push it into ge2gl only if it changed.
    if (!ge_) return;
    const uint8_t *g = reinterpret_cast<const uint8_t *>(&gstate);
    if (shadow_.size() == sizeof(gstate) && std::memcmp(shadow_.data(), g, sizeof(gstate)) == 0) return;
    u32_le ctx[512] = {};
    gstate.Save(ctx);
    uint32_t words[512];
    for (int i = 0; i < 512; ++i) words[i] = ctx[i];
    // gstate.Save takes the matrices from the GPU core (GetMatrix24: ge2gl's, not the ones PPSSPP
    // just restored into gstate): the matrix part of the context (words 226-384, the layout
    // sceGeSaveContext writes: each matrix's number command, its data commands, then the five
    // upload indices and END) is written here from gstate's own matrices.
    struct Mtx { const float *m; int n; u32 numOp, dataOp; };
    const Mtx mats[5] = {{gstate.boneMatrix, 96, GE_CMD_BONEMATRIXNUMBER, GE_CMD_BONEMATRIXDATA},
                         {gstate.worldMatrix, 12, GE_CMD_WORLDMATRIXNUMBER, GE_CMD_WORLDMATRIXDATA},
                         {gstate.viewMatrix, 12, GE_CMD_VIEWMATRIXNUMBER, GE_CMD_VIEWMATRIXDATA},
                         {gstate.projMatrix, 16, GE_CMD_PROJMATRIXNUMBER, GE_CMD_PROJMATRIXDATA},
                         {gstate.tgenMatrix, 12, GE_CMD_TGENMATRIXNUMBER, GE_CMD_TGENMATRIXDATA}};
    int w = 226;
    for (const Mtx &m : mats) {
        words[w++] = m.numOp << 24;
        for (int k = 0; k < m.n; ++k) words[w++] = (m.dataOp << 24) | toFloat24(m.m[k]);
    }
    words[w++] = gstate.boneMatrixNumber & 0xFF00007F;
    words[w++] = gstate.worldmtxnum & 0xFF00000F;
    words[w++] = gstate.viewmtxnum & 0xFF00000F;
    words[w++] = gstate.projmtxnum & 0xFF00000F;
    words[w++] = gstate.texmtxnum & 0xFF00000F;
    words[w] = GE_CMD_END << 24;
    const ge2gl_status s = ge2gl_restore_context(ge_, words);
    if (s != GE2GL_OK)
        WARN_LOG(Log::G3D, "ge2gl: PPSSPP's register state could not be applied: %s (%s)", ge2gl_status_name(s), ge2gl_last_message(ge_));
    RefreshRegisters();
}

// ---------------------------------------------------------------------------------------------
// sceGe in the game's terms.

int32_t GPU_Ge2gl::SceEnqueue(uint32_t list, uint32_t stall, int32_t cbid, uint32_t argsAddr, bool head) {
    SyncSdkVersion();
    ge2gl_list_args args{};
    const ge2gl_list_args *pargs = nullptr;
    if (argsAddr != 0 && Memory::IsValidRange(argsAddr, 16)) {
        args.size = Memory::ReadUnchecked_U32(argsAddr);
        args.context = Memory::ReadUnchecked_U32(argsAddr + 4);
        args.num_stacks = Memory::ReadUnchecked_U32(argsAddr + 8);
        args.stacks = Memory::ReadUnchecked_U32(argsAddr + 12);
        pargs = &args;
    }
    int32_t id = -1;
    const ge2gl_status s = head ? ge2gl_list_enqueue_head(ge_, list, stall, cbid, pargs, &id)
                                : ge2gl_list_enqueue(ge_, list, stall, cbid, pargs, &id);
    if (s != GE2GL_OK) return Reported(s, "list_enqueue");
    const int slot = SlotOf(id);
    if (slot >= 0) {
        noInterrupts_[slot] = !interruptsEnabled_;
        reachedAt_[slot] = Now();
    }
    RunGe();
    return id;
}

int32_t GPU_Ge2gl::SceDequeue(int32_t id) {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_list_dequeue(ge_, id);
    RunGe();
    return s == GE2GL_OK ? 0 : Reported(s, "list_dequeue");
}

int32_t GPU_Ge2gl::SceUpdateStall(int32_t id, uint32_t stall) {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_list_update_stall(ge_, id, stall);
    RunGe();
    return s == GE2GL_OK ? 0 : Reported(s, "list_update_stall");
}

int32_t GPU_Ge2gl::SceListSync(int32_t id, int32_t mode) {
    SyncSdkVersion();
    if (mode != GE2GL_SYNC_WAIT && mode != GE2GL_SYNC_PEEK) return int32_t(GE2GL_SCE_ERROR_INVALID_MODE);
    int32_t state = -1;
    const ge2gl_status s = ge2gl_list_sync(ge_, id, GE2GL_SYNC_PEEK, &state);
    if (s != GE2GL_OK) return Reported(s, "list_sync");
    const int slot = SlotOf(id);
    const int64_t now = Now();
    if (mode == GE2GL_SYNC_PEEK) return ge2gl_ppsspp::visibleListState(state, slot >= 0 ? reachedAt_[slot] : 0, now);
    // Waiting is the kernel's business: the same checks PPSSPP's own sceGeListSync makes.
    if (!__KernelIsDispatchEnabled()) return SCE_KERNEL_ERROR_CAN_NOT_WAIT;
    if (__IsInInterrupt()) return SCE_KERNEL_ERROR_ILLEGAL_CONTEXT;
    if (state == GE2GL_LIST_COMPLETED && !PendingLater(id, now)) return 0;
    waitingLists_.insert(slot);
    __GeWaitCurrentThread(GPU_SYNC_LIST, slot, "GeListSync");
    return 0;
}

int32_t GPU_Ge2gl::SceDrawSync(int32_t mode) {
    SyncSdkVersion();
    if (mode != GE2GL_SYNC_WAIT && mode != GE2GL_SYNC_PEEK) return int32_t(GE2GL_SCE_ERROR_INVALID_MODE);
    int32_t state = -1;
    const ge2gl_status s = ge2gl_draw_sync(ge_, GE2GL_SYNC_PEEK, &state);
    if (s != GE2GL_OK) return Reported(s, "draw_sync");
    const int64_t now = Now();
    if (mode == GE2GL_SYNC_PEEK) {
        // A finish handler already sees its list complete (pspautotests gpu/signals/*: drawsync
        // reads 0 there). Until the CPU reaches the tick of the GE's last stop or completion, the GE draws.
        int64_t since = 0;
        for (int i = 0; i < kSlots; ++i) since = std::max(since, reachedAt_[i]);
        return ge2gl_ppsspp::visibleListState(state, since, now);
    }
    if (!__KernelIsDispatchEnabled()) return SCE_KERNEL_ERROR_CAN_NOT_WAIT;
    if (__IsInInterrupt()) return SCE_KERNEL_ERROR_ILLEGAL_CONTEXT;
    if (state == GE2GL_LIST_COMPLETED && !PendingLater(-1, now)) return 0;
    drawWaiting_ = true;
    __GeWaitCurrentThread(GPU_SYNC_DRAW, 1, "GeDrawSync");
    return 0;
}

int32_t GPU_Ge2gl::SceBreak(int32_t mode) {
    SyncSdkVersion();
    int32_t id = -1;
    const ge2gl_status s = ge2gl_break(ge_, mode, &id);
    RunGe();
    if (s != GE2GL_OK) return Reported(s, "break");
    return mode == 0 ? id : 0;
}

int32_t GPU_Ge2gl::SceContinue() {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_continue(ge_);
    RunGe();
    return s == GE2GL_OK ? 0 : Reported(s, "continue");
}

int32_t GPU_Ge2gl::SceSetCallback(uint32_t structAddr) {
    SyncSdkVersion();
    if (!Memory::IsValidRange(structAddr, 16)) return int32_t(GE2GL_SCE_ERROR_BAD_POINTER);
    const uint32_t signalFunc = Memory::ReadUnchecked_U32(structAddr);
    const uint32_t signalArg = Memory::ReadUnchecked_U32(structAddr + 4);
    const uint32_t finishFunc = Memory::ReadUnchecked_U32(structAddr + 8);
    const uint32_t finishArg = Memory::ReadUnchecked_U32(structAddr + 12);
    int32_t cbid = -1;
    const ge2gl_status s = ge2gl_set_callback(ge_, signalFunc, signalArg, finishFunc, finishArg, &cbid);
    if (s != GE2GL_OK) return Reported(s, "set_callback");
    // As the firmware does: the functions become sub-interrupts 2*cbid (signal) and 2*cbid+1
    // (finish) of the GE interrupt.
    EnsureIntrHandler();
    if (finishFunc != 0) {
        sceKernelRegisterSubIntrHandler(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_FINISH, finishFunc, finishArg);
        sceKernelEnableSubIntr(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_FINISH);
    }
    if (signalFunc != 0) {
        sceKernelRegisterSubIntrHandler(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_SIGNAL, signalFunc, signalArg);
        sceKernelEnableSubIntr(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_SIGNAL);
    }
    return cbid;
}

int32_t GPU_Ge2gl::SceUnsetCallback(int32_t cbid) {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_unset_callback(ge_, cbid);
    if (s != GE2GL_OK) return Reported(s, "unset_callback");
    sceKernelReleaseSubIntrHandler(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_FINISH);
    sceKernelReleaseSubIntrHandler(PSP_GE_INTR, cbid * 2 + PSP_GE_SUBINTR_SIGNAL);
    return 0;
}

int32_t GPU_Ge2gl::SceSaveContext(uint32_t addr) {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_save_context_at(ge_, addr);
    return s == GE2GL_OK ? 0 : Reported(s, "save_context_at");
}

int32_t GPU_Ge2gl::SceRestoreContext(uint32_t addr) {
    SyncSdkVersion();
    const ge2gl_status s = ge2gl_restore_context_at(ge_, addr);
    RefreshRegisters();
    return s == GE2GL_OK ? 0 : Reported(s, "restore_context_at");
}

uint32_t GPU_Ge2gl::SceGetCmd(int32_t op) {
    SyncSdkVersion();
    uint32_t word = 0;
    const ge2gl_status s = ge2gl_get_cmd(ge_, uint32_t(op), &word);
    return s == GE2GL_OK ? word : uint32_t(Reported(s, "get_cmd"));
}

int32_t GPU_Ge2gl::SceGetMtx(int32_t type, uint32_t addr) {
    SyncSdkVersion();
    uint32_t words[16];
    int32_t n = 0;
    const ge2gl_status s = ge2gl_get_matrix(ge_, type, words, &n);
    if (s != GE2GL_OK) return Reported(s, "get_matrix");
    if (!Memory::IsValidRange(addr, uint32_t(n) * 4)) return int32_t(GE2GL_SCE_ERROR_BAD_POINTER);
    for (int32_t i = 0; i < n; ++i) Memory::WriteUnchecked_U32(words[i], addr + 4 * i);
    return 0;
}

int32_t GPU_Ge2gl::SceGetStack(int32_t index, uint32_t addr) {
    SyncSdkVersion();
    uint32_t frame[8];
    int32_t depth = 0;
    const ge2gl_status s = ge2gl_get_stack(ge_, index, frame, &depth);
    if (s != GE2GL_OK) return Reported(s, "get_stack");
    if (index >= 0 && index < depth && addr != 0 && Memory::IsValidRange(addr, 32))
        for (int i = 0; i < 8; ++i) Memory::WriteUnchecked_U32(frame[i], addr + 4 * i);
    return depth;
}

int32_t GPU_Ge2gl::SceEdramSetAddrTranslation(uint32_t value) {
    SyncSdkVersion();
    uint32_t previous = 0;
    const ge2gl_status s = ge2gl_edram_set_translation(ge_, value, &previous);
    if (s != GE2GL_OK) return Reported(s, "edram_set_translation");
    edramTranslation_ = value;
    return int32_t(previous);
}

// ---------------------------------------------------------------------------------------------
// GPUCommon's list functions: slots in, slots out (sceGe.cpp and the player XOR the magic).

u32 GPU_Ge2gl::EnqueueList(u32 listpc, u32 stall, int subIntrBase, PSPPointer<PspGeListArgs> args, bool head, bool *runList) {
    *runList = false;
    const int32_t cbid = subIntrBase < 0 ? -1 : subIntrBase / 2;
    const int32_t r = SceEnqueue(listpc, stall, cbid, args.ptr, head);
    return r < 0 ? u32(r) : u32(SlotOf(r));
}

u32 GPU_Ge2gl::DequeueList(int listid) { return u32(SceDequeue(IdOf(listid))); }

u32 GPU_Ge2gl::UpdateStall(int listid, u32 newstall, bool *runList) {
    *runList = false;
    return u32(SceUpdateStall(IdOf(listid), newstall));
}

int GPU_Ge2gl::ListSync(int listid, int mode) { return SceListSync(IdOf(listid), mode); }
u32 GPU_Ge2gl::DrawSync(int mode) { return u32(SceDrawSync(mode)); }

u32 GPU_Ge2gl::Continue(bool *runList) {
    *runList = false;
    return u32(SceContinue());
}

u32 GPU_Ge2gl::Break(int mode) {
    const int32_t r = SceBreak(mode);
    return (mode == 0 && r >= 0) ? u32(SlotOf(r)) : u32(r);
}

int GPU_Ge2gl::GetStack(int index, u32 stackPtr) { return SceGetStack(index, stackPtr); }

bool GPU_Ge2gl::BusyDrawing() {
    int32_t state = -1;
    if (ge2gl_draw_sync(ge_, GE2GL_SYNC_PEEK, &state) != GE2GL_OK) return false;
    return state == GE2GL_LIST_DRAWING || state == GE2GL_LIST_STALLING;
}

DLResult GPU_Ge2gl::ProcessDLQueue() {
    RunGe();
    return DLResult::Done;
}

uint32_t GPU_Ge2gl::SetAddrTranslation(uint32_t value) {
    const int32_t r = SceEdramSetAddrTranslation(value);
    return r < 0 ? edramTranslation_ : uint32_t(r);
}

uint32_t GPU_Ge2gl::GetAddrTranslation() { return edramTranslation_; }

s64 GPU_Ge2gl::GetListTicks(int listid) const {
    // PPSSPP's player moves the CPU's clock up to here after each stall update: the tick the GE's
    // work on this list reaches.
    if (listid < 0 || listid >= kSlots || !ge_) return -1;
    int32_t state = -1;
    if (ge2gl_list_sync(ge_, IdOf(listid), GE2GL_SYNC_PEEK, &state) != GE2GL_OK) return -1;
    if (state == GE2GL_LIST_COMPLETED) return reachedAt_[listid];
    return timeline_.cpuTickOf(GeTick());
}

bool GPU_Ge2gl::GetMatrix24(GEMatrixType type, u32_le *result, u32 cmdbits) {
    uint32_t words[16];
    int32_t n = 0;
    if (ge2gl_get_matrix(ge_, int32_t(type), words, &n) != GE2GL_OK) return false;
    for (int32_t i = 0; i < n; ++i) result[i] = words[i] | cmdbits;
    return true;
}

void GPU_Ge2gl::Reinitialize() {
    // LoadExec: the kernel was set up again (and PPSSPP's GE interrupt handler with it); the
    // game starts over with an empty queue.
    GPUCommon::Reinitialize();
    if (!ge_) return;
    int32_t ignored;
    ge2gl_break(ge_, 1, &ignored);
    if (held_) {
        held_ = false;
        ge2gl_interrupt_ack(ge_);
    }
    pending_.clear();
    waitingLists_.clear();
    drawWaiting_ = false;
    geWaiting_ = true;
    EnsureIntrHandler();
    RefreshRegisters();
}

// ---------------------------------------------------------------------------------------------
// Save states: ge2gl's whole-GE blob (docs/savestate.md of ge2gl) and this core's bookkeeping.
// PPSSPP saves guest memory itself, so the blob leaves it out.

void GPU_Ge2gl::DoState(PointerWrap &p) {
    auto s = p.Section("GPU_Ge2gl", 1);
    if (!s) return;
    std::vector<uint8_t> blob;
    if (p.mode != PointerWrap::MODE_READ) {
        const void *data = nullptr;
        size_t size = 0;
        const ge2gl_status st = ge2gl_state_save(ge_, 0, &data, &size);
        if (st != GE2GL_OK) {
            ERROR_LOG(Log::G3D, "ge2gl: cannot save the GE: %s (%s)", ge2gl_status_name(st), ge2gl_last_message(ge_));
            p.SetError(PointerWrap::ERROR_FAILURE);
            return;
        }
        blob.assign(static_cast<const uint8_t *>(data), static_cast<const uint8_t *>(data) + size);
    }
    Do(p, blob);
    uint64_t geAnchor = timeline_.geAnchor();
    int64_t cpuAnchor = timeline_.cpuAnchor(), hz = timeline_.cpuHz();
    Do(p, geAnchor);
    Do(p, cpuAnchor);
    Do(p, hz);
    Do(p, held_);
    Do(p, geWaiting_);
    DoArray(p, reachedAt_, kSlots);
    DoArray(p, noInterrupts_, kSlots);
    Do(p, waitingLists_);
    Do(p, drawWaiting_);
    Do(p, edramTranslation_);
    Do(p, displayFramebuf_);
    Do(p, displayStride_);
    Do(p, displayFormat_);
    int count = int(pending_.size());
    Do(p, count);
    if (p.mode == PointerWrap::MODE_READ) pending_.assign(size_t(std::max(count, 0)), Pending{});
    for (Pending &q : pending_) {
        Do(p, q.listId);
        Do(p, q.cbid);
        Do(p, q.arg);
        Do(p, q.pc);
        Do(p, q.finish);
        Do(p, q.guest);
        Do(p, q.cpuTick);
    }
    Do(p, sliceEvent_);
    CoreTiming::RestoreRegisterEvent(sliceEvent_, "Ge2glSlice", &SliceEvent);
    Do(p, interruptEvent_);
    CoreTiming::RestoreRegisterEvent(interruptEvent_, "Ge2glInterrupt", &InterruptEvent);
    if (p.mode == PointerWrap::MODE_READ) {
        timeline_.restore(geAnchor, cpuAnchor, hz);
        const ge2gl_status st = ge2gl_state_load(ge_, blob.data(), blob.size());
        if (st != GE2GL_OK) {
            ERROR_LOG(Log::G3D, "ge2gl: cannot load the GE: %s (%s)", ge2gl_status_name(st), ge2gl_last_message(ge_));
            p.SetError(PointerWrap::ERROR_FAILURE);
            return;
        }
        EnsureIntrHandler();
        RefreshRegisters();
    }
}

// ---------------------------------------------------------------------------------------------
// Memory: PPSSPP tells its GPU core about CPU and DMA writes and about reads of what the GPU may
// hold; with ge2gl these are ge2gl_mem_written (ge2gl re-reads what it cached) and
// ge2gl_sync_range (what a GL backend drew is written back first).

void GPU_Ge2gl::InvalidateCache(u32 addr, int size, GPUInvalidationType type) {
    // PPSSPP calls this for the game's data-cache writebacks (HINT for a range, ALL for the whole
    // cache): the CPU *may* have written there. ge2gl finds such writes itself, by hashing what it
    // cached when the game next enqueues, continues or moves a stall (docs/plugin-api.md,
    // "Coherence"); declaring the range written instead would drop pixels a GL backend drew into
    // a render target that is not written back yet (a list still open, as a GU_DIRECT list is).
    // SAFE and FORCE come from PPSSPP's own HLE code writing the bytes (font glyphs, replaced
    // textures): those are writes.
    if (!ge_ || size <= 0 || type == GPU_INVALIDATE_ALL || type == GPU_INVALIDATE_HINT) return;
    ge2gl_mem_written(ge_, addr, u32(size));
}

bool GPU_Ge2gl::PerformMemoryCopy(u32 dest, u32 src, int size, GPUCopyFlag flags) {
    if (!ge_ || size <= 0 || !Memory::IsValidRange(dest, u32(size)) || !Memory::IsValidRange(src, u32(size))) return false;
    ge2gl_sync_range(ge_, src, u32(size));
    if (dest != src) {
        ge2gl_sync_range(ge_, dest, u32(size));
        std::memmove(Memory::GetPointerWriteUnchecked(dest), Memory::GetPointerUnchecked(src), size_t(size));
    }
    ge2gl_mem_written(ge_, dest, u32(size));
    return true;
}

bool GPU_Ge2gl::PerformMemorySet(u32 dest, u8 v, int size) {
    if (!ge_ || size <= 0 || !Memory::IsValidRange(dest, u32(size))) return false;
    ge2gl_sync_range(ge_, dest, u32(size));
    std::memset(Memory::GetPointerWriteUnchecked(dest), v, size_t(size));
    ge2gl_mem_written(ge_, dest, u32(size));
    return true;
}

bool GPU_Ge2gl::PerformReadbackToMemory(u32 dest, int size) {
    if (!ge_ || size <= 0) return false;
    return ge2gl_sync_range(ge_, dest, u32(size)) == GE2GL_OK;
}

bool GPU_Ge2gl::PerformWriteColorFromMemory(u32 dest, int size) {
    if (!ge_ || size <= 0) return false;
    return ge2gl_mem_written(ge_, dest, u32(size)) == GE2GL_OK;
}

void GPU_Ge2gl::PerformWriteFormattedFromMemory(u32 addr, int size, int width, GEBufferFormat format) {
    if (ge_ && size > 0) ge2gl_mem_written(ge_, addr, u32(size));
}

bool GPU_Ge2gl::PerformWriteStencilFromMemory(u32 dest, int size, WriteStencil flags) {
    if (!ge_ || size <= 0) return false;
    return ge2gl_mem_written(ge_, dest, u32(size)) == GE2GL_OK;
}

// ---------------------------------------------------------------------------------------------
// Display and debugger read-outs, all through ge2gl (what it drew, written back to VRAM first).

void GPU_Ge2gl::SetDisplayFramebuffer(u32 framebuf, u32 stride, GEBufferFormat format) {
    displayFramebuf_ = framebuf;
    displayStride_ = stride;
    displayFormat_ = format;
}

static bool ReadFrame(ge2gl_context *ge, u32 addr, u32 stride, GEBufferFormat format, u32 height, GPUDebugBuffer &buffer) {
    if (!ge || stride == 0 || stride > 4096 || height == 0) return false;
    buffer.Allocate(stride, height, GPU_DBG_FORMAT_8888);
    const ge2gl_status s = ge2gl_read_frame(ge, addr, stride, int32_t(format), stride, height, buffer.GetData(), size_t(stride) * height * 4);
    if (s != GE2GL_OK) {
        WARN_LOG(Log::G3D, "ge2gl: cannot read the frame at %08x: %s (%s)", addr, ge2gl_status_name(s), ge2gl_last_message(ge));
        return false;
    }
    return true;
}

bool GPU_Ge2gl::GetCurrentFramebuffer(GPUDebugBuffer &buffer, GPUDebugFramebufferType type, int maxRes) {
    if (type == GPU_DBG_FRAMEBUF_DISPLAY) return ReadFrame(ge_, displayFramebuf_, displayStride_, displayFormat_, 272, buffer);
    // The target the GE draws into: FBP/FBW/FPF as ge2gl holds them.
    const u32 fbp = gstate.cmdmem[GE_CMD_FRAMEBUFPTR], fbw = gstate.cmdmem[GE_CMD_FRAMEBUFWIDTH];
    const u32 addr = 0x04000000 | (fbp & 0x001FFFF0);
    const u32 stride = fbw & 0x07FC;
    return ReadFrame(ge_, addr, stride, GEBufferFormat(gstate.cmdmem[GE_CMD_FRAMEBUFPIXFORMAT] & 3), 272, buffer);
}

bool GPU_Ge2gl::GetOutputFramebuffer(GPUDebugBuffer &buffer) {
    return ReadFrame(ge_, displayFramebuf_, displayStride_, displayFormat_, 272, buffer);
}

bool GPU_Ge2gl::GetCurrentDepthbuffer(GPUDebugBuffer &buffer) {
    if (!ge_) return false;
    const u32 w = std::max<u32>(1, gstate.cmdmem[GE_CMD_ZBUFWIDTH] & 0x07FC);
    buffer.Allocate(w, 272, GPU_DBG_FORMAT_16BIT);
    return ge2gl_debug_read_buffer(ge_, GE2GL_DEBUG_DEPTH, w, 272, buffer.GetData(), size_t(w) * 272 * 2) == GE2GL_OK;
}

bool GPU_Ge2gl::GetCurrentStencilbuffer(GPUDebugBuffer &buffer) {
    if (!ge_) return false;
    const u32 w = std::max<u32>(1, gstate.cmdmem[GE_CMD_FRAMEBUFWIDTH] & 0x07FC);
    buffer.Allocate(w, 272, GPU_DBG_FORMAT_8BIT);
    return ge2gl_debug_read_buffer(ge_, GE2GL_DEBUG_STENCIL, w, 272, buffer.GetData(), size_t(w) * 272) == GE2GL_OK;
}

bool GPU_Ge2gl::GetCurrentTexture(GPUDebugBuffer &buffer, int level, bool *isFramebuffer) {
    if (!ge_) return false;
    if (isFramebuffer) *isFramebuffer = false;
    uint32_t w = 0, h = 0;
    if (ge2gl_debug_read_texture(ge_, level, &w, &h, nullptr, 0) != GE2GL_OK || w == 0 || h == 0) return false;
    buffer.Allocate(w, h, GPU_DBG_FORMAT_8888);
    return ge2gl_debug_read_texture(ge_, level, &w, &h, buffer.GetData(), size_t(w) * h * 4) == GE2GL_OK;
}

bool GPU_Ge2gl::GetCurrentClut(GPUDebugBuffer &buffer) {
    if (!ge_) return false;
    uint32_t words[512];
    uint32_t n = 0;
    if (ge2gl_debug_read_clut(ge_, words, 512, &n) != GE2GL_OK || n == 0) return false;
    buffer.Allocate(n, 1, GPU_DBG_FORMAT_8888);
    std::memcpy(buffer.GetData(), words, size_t(n) * 4);
    return true;
}

// A windowed PPSSPP shows the displayed frame through its presentation code, as its software
// core does, from ge2gl's RGBA read-back (ge2gl draws in a context of its own, not PPSSPP's).
void GPU_Ge2gl::PrepareCopyDisplayToOutput(const DisplayLayoutConfig &config) {
    if (!draw_ || !presentation_) return;
    if (frameTexture_) {
        frameTexture_->Release();
        frameTexture_ = nullptr;
    }
    GPUDebugBuffer frame;
    if (!ReadFrame(ge_, displayFramebuf_, displayStride_, displayFormat_, 272, frame)) {
        presentation_->SourceBlank();
        presentation_->NotifyPresent();
        return;
    }
    frameRgba_.assign(frame.GetData(), frame.GetData() + size_t(displayStride_) * 272 * 4);
    Draw::TextureDesc desc{};
    desc.type = Draw::TextureType::LINEAR2D;
    desc.format = Draw::DataFormat::R8G8B8A8_UNORM;
    desc.width = int(displayStride_);
    desc.height = 272;
    desc.depth = 1;
    desc.mipLevels = 1;
    desc.tag = "ge2gl frame";
    desc.initData.push_back(frameRgba_.data());
    frameTexture_ = draw_->CreateTexture(desc);
    OutputFlags flags = config.iDisplayFilter == SCALE_NEAREST ? OutputFlags::NEAREST : OutputFlags::LINEAR;
    if (GetGPUBackend() == GPUBackend::OPENGL) flags |= OutputFlags::BACKBUFFER_FLIPPED;
    presentation_->SourceTexture(frameTexture_, desc.width, desc.height);
    presentation_->RunPostshaderPasses(config, flags, config.iInternalScreenRotation, 0.0f, 0.0f, 480.0f / float(displayStride_), 1.0f);
}

void GPU_Ge2gl::CopyDisplayToOutput(const DisplayLayoutConfig &config) {
    if (presentation_) presentation_->CopyToOutput(config);
}

bool GPU_Ge2gl::PresentedThisFrame() const { return presentation_ ? presentation_->PresentedThisFrame() : false; }

void GPU_Ge2gl::BeginHostFrame(const DisplayLayoutConfig &config) {
    GPUCommon::BeginHostFrame(config);
    if (presentation_) presentation_->BeginFrame(config);
}

void GPU_Ge2gl::DeviceLost() {
    if (presentation_) presentation_->DeviceLost();
    if (frameTexture_) {
        frameTexture_->Release();
        frameTexture_ = nullptr;
    }
    draw_ = nullptr;
}

void GPU_Ge2gl::DeviceRestore(Draw::DrawContext *draw) {
    draw_ = draw;
    if (presentation_) presentation_->DeviceRestore(draw_);
}

void GPU_Ge2gl::GetStats(StringWriter &w) {
    uint64_t tick = 0;
    ge2gl_get_tick(ge_, &tick);
    w.F("ge2gl GE: %llu GE ticks, %d interrupts pending%s\n", (unsigned long long)tick, int(pending_.size()),
        held_ ? " (held)" : "");
}

void GPU_Ge2gl::GetReportingInfo(std::string &primaryInfo, std::string &fullInfo) const {
    primaryInfo = "ge2gl";
    fullInfo = "ge2gl (libge2gl GE)";
}
