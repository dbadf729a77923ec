// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp). This file is compiled into PPSSPP,
// which is licensed under the GNU GPL version 2.0 or later; so is this file.
//
// GPU_Ge2gl: a PPSSPP GPU core whose GE is libge2gl, reached through its public C ABI only
// (<ge2gl/ge2gl.h>). PPSSPP keeps the CPU, the kernel (threads, interrupts, CoreTiming) and the
// display; ge2gl keeps the GE: the list queue and its semantics (stalls, signals, break/continue,
// contexts, callbacks, eDRAM translation), the register file, and the drawing (its software model,
// or OpenGL in exact or hardware mode in a context of its own).
//
// How the two meet (integrations/ppsspp/README.md has the full story):
//   - the game's sceGe calls reach this class through the sceGe_user module of Ge2glSceGe.cpp,
//     PPSSPP's dump player and PPGe through the GPUCommon functions it overrides;
//   - the GE runs as soon as it has work (ge2gl_run_until, bounded), and whatever the game can
//     observe of it happens at the CPU tick its work reaches (Ge2glTimeline.h): interrupts are
//     CoreTiming events at those ticks, delivered through PPSSPP's interrupt machinery to the
//     sub-interrupt handlers sceGeSetCallback registered; ge2gl holds the GE at each signal and
//     finish until the guest's handler has returned (config.hold_interrupts);
//   - guest RAM and VRAM are PPSSPP's own memory, used in place; PPSSPP's memory hooks
//     (InvalidateCache, PerformMemoryCopy, ...) become ge2gl_mem_written / ge2gl_sync_range;
//   - PPSSPP's register mirror `gstate` is refreshed from ge2gl after every run (its dump player
//     reads it), and pushed into ge2gl when PPSSPP code restored it (ReapplyGfxState);
//   - save states carry ge2gl's whole-GE state blob (ge2gl_state_save) and this class's own.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "GPU/GPUCommon.h"
#include "GPU/GPUState.h"
#include "GPU/Ge2gl/Ge2glTimeline.h"

struct ge2gl_context;
struct ge2gl_interrupt;
class IntrHandler;
class PresentationCommon;
namespace Draw {
class Texture;
}

// The factory case of GPU/GPU.cpp. nullptr (with the reason logged and printed) when libge2gl
// cannot be started with the configured backend.
GPUCommon *Ge2gl_CreateGPU(GraphicsContext *gfxCtx, Draw::DrawContext *draw);
// Whether PPSSPP's config selects ge2gl's GE (setting Ge2glBackend, --graphics=ge2gl...).
bool Ge2gl_Selected();

class GPU_Ge2gl : public GPUCommon {
public:
    GPU_Ge2gl(GraphicsContext *gfxCtx, Draw::DrawContext *draw);
    ~GPU_Ge2gl() override;

    bool Started() const { return ge_ != nullptr; }
    const std::string &StartError() const { return startError_; }
    // The core of the running emulation (the sceGe module and the CoreTiming events reach it
    // through this); nullptr when another core runs.
    static GPU_Ge2gl *Active();

    // ---- sceGe, in the game's terms (list IDs as the game sees them; results as the firmware
    // returns them). The sceGe_user module (Ge2glSceGe.cpp) calls these. ----
    int32_t SceEnqueue(uint32_t list, uint32_t stall, int32_t cbid, uint32_t argsAddr, bool head);
    int32_t SceDequeue(int32_t id);
    int32_t SceUpdateStall(int32_t id, uint32_t stall);
    int32_t SceListSync(int32_t id, int32_t mode);
    int32_t SceDrawSync(int32_t mode);
    int32_t SceBreak(int32_t mode);
    int32_t SceContinue();
    int32_t SceSetCallback(uint32_t structAddr);
    int32_t SceUnsetCallback(int32_t cbid);
    int32_t SceSaveContext(uint32_t addr);
    int32_t SceRestoreContext(uint32_t addr);
    uint32_t SceGetCmd(int32_t op);
    int32_t SceGetMtx(int32_t type, uint32_t addr);
    int32_t SceGetStack(int32_t index, uint32_t addr);
    int32_t SceEdramSetAddrTranslation(uint32_t value);

    // ---- GPUCommon list functions (slot numbers, as PPSSPP's player and PPGe use them). ----
    u32 EnqueueList(u32 listpc, u32 stall, int subIntrBase, PSPPointer<PspGeListArgs> args, bool head, bool *runList) override;
    u32 DequeueList(int listid) override;
    u32 UpdateStall(int listid, u32 newstall, bool *runList) override;
    int ListSync(int listid, int mode) override;
    u32 DrawSync(int mode) override;
    u32 Continue(bool *runList) override;
    u32 Break(int mode) override;
    int GetStack(int index, u32 stackPtr) override;
    bool BusyDrawing() override;
    DLResult ProcessDLQueue() override;
    uint32_t SetAddrTranslation(uint32_t value) override;
    uint32_t GetAddrTranslation() override;
    s64 GetListTicks(int listid) const override;
    bool GetMatrix24(GEMatrixType type, u32_le *result, u32 cmdbits) override;
    void ResetMatrices() override {}
    void ReapplyGfxState() override;
    void Reinitialize() override;
    void DoState(PointerWrap &p) override;
    void Flush() override {}

    // ---- Interrupt delivery (Ge2glIntrHandler). ----
    // The GE interrupt fired: starts the guest's sub-interrupt handler for the oldest pending
    // interrupt (true), or finishes it at once when the game has none (false).
    bool StartInterrupt(IntrHandler &handler);
    // The guest's handler returned (or there was none): the GE may go on.
    void FinishInterrupt();
    // The kernel shuts down (or restarts): nothing may write guest memory after this.
    void KernelStopping();
    // CoreTiming events.
    void OnSliceEvent();
    void OnInterruptEvent();

    // ---- Memory coherence. ----
    void InvalidateCache(u32 addr, int size, GPUInvalidationType type) override;
    bool PerformMemoryCopy(u32 dest, u32 src, int size, GPUCopyFlag flags = GPUCopyFlag::NONE) override;
    bool PerformMemorySet(u32 dest, u8 v, int size) override;
    bool PerformReadbackToMemory(u32 dest, int size) override;
    bool PerformWriteColorFromMemory(u32 dest, int size) override;
    void PerformWriteFormattedFromMemory(u32 addr, int size, int width, GEBufferFormat format) override;
    bool PerformWriteStencilFromMemory(u32 dest, int size, WriteStencil flags) override;

    // ---- Display and debugger read-outs. ----
    void SetDisplayFramebuffer(u32 framebuf, u32 stride, GEBufferFormat format) override;
    void SetCurFramebufferDirty(bool dirty) override {}
    void PrepareCopyDisplayToOutput(const DisplayLayoutConfig &config) override;
    void CopyDisplayToOutput(const DisplayLayoutConfig &config) override;
    bool PresentedThisFrame() const override;
    void BeginHostFrame(const DisplayLayoutConfig &config) override;
    bool FramebufferDirty() override { return true; }
    bool FramebufferReallyDirty() override { return true; }
    bool GetCurrentFramebuffer(GPUDebugBuffer &buffer, GPUDebugFramebufferType type, int maxRes = -1) override;
    bool GetOutputFramebuffer(GPUDebugBuffer &buffer) override;
    bool GetCurrentDepthbuffer(GPUDebugBuffer &buffer) override;
    bool GetCurrentStencilbuffer(GPUDebugBuffer &buffer) override;
    bool GetCurrentTexture(GPUDebugBuffer &buffer, int level, bool *isFramebuffer) override;
    bool GetCurrentClut(GPUDebugBuffer &buffer) override;

    // ---- The rest of GPUCommon's interface: nothing of PPSSPP's own drawing runs here. ----
    void GetStats(StringWriter &w) override;
    std::vector<const VirtualFramebuffer *> GetFramebufferList() const override { return {}; }
    void DeviceLost() override;
    void DeviceRestore(Draw::DrawContext *draw) override;
    u32 CheckGPUFeatures() const override { return 0; }
    void UpdateCmdInfo() override {}
    void CheckDisplayResized() override {}
    void CheckConfigChanged(const DisplayLayoutConfig &config) override {}
    void ExecuteOp(u32 op, u32 diff) override {}
    void GetReportingInfo(std::string &primaryInfo, std::string &fullInfo) const override;
    // No JIT of PPSSPP's vertex decoder runs here: nothing to describe (crash reports, profiler).
    bool DescribeCodePtr(const u8 *ptr, std::string &name) override { return false; }

protected:
    // PPSSPP's command interpreter never runs: the lists run inside libge2gl.
    void FastRunLoop(DisplayList &list) override {}
    void BuildReportingInfo() override {}

private:
    struct Pending {
        int32_t listId = 0, cbid = -1;
        uint32_t arg = 0, pc = 0;
        bool finish = false, guest = false;
        int64_t cpuTick = 0;
    };
    struct Link;  // shared with the interrupt handler object PPSSPP owns

    static void CbSignal(void *user, const ge2gl_interrupt *irq);
    static void CbFinish(void *user, const ge2gl_interrupt *irq);
    static void CbError(void *user, int32_t listId, uint32_t pc, const char *message);
    void QueueInterrupt(const ge2gl_interrupt &irq, bool finish);

    int64_t Now() const;
    uint64_t GeTick() const;
    // Runs the GE as far as it may go now, then refreshes `gstate` and wakes finished waits.
    void RunGe();
    void ResolveWaits();
    bool PendingFor(int32_t id) const;
    bool PendingLater(int32_t id, int64_t now) const;
    void RefreshRegisters();
    void EnsureIntrHandler();
    void SyncSdkVersion();
    int32_t Reported(int32_t s, const char *what) const;

    ge2gl_context *ge_ = nullptr;
    std::string startError_;
    ge2gl_ppsspp::Timeline timeline_;
    std::shared_ptr<Link> link_;
    int sliceEvent_ = -1, interruptEvent_ = -1;

    std::deque<Pending> pending_;
    bool held_ = false;       // ge2gl holds the GE until every pending interrupt is handled
    bool geWaiting_ = true;   // the GE stopped with nothing it can do: new work starts at "now"
    bool running_ = false;    // inside RunGe (callbacks run inside ge2gl_run_until)
    int64_t reachedAt_[64] = {};  // per list slot: CPU tick at which its ge2gl state was reached
    bool noInterrupts_[64] = {};  // per list slot: enqueued with interrupts disabled (PPGe, player)
    std::set<int> waitingLists_;  // slots some thread waits on (sceGeListSync)
    bool drawWaiting_ = false;    // some thread waits in sceGeDrawSync
    int64_t lookaheadCpu_ = 0;    // how far the GE may run ahead of the CPU

    uint32_t edramTranslation_ = 0x400;
    uint32_t sdkVersion_ = 0xFFFFFFFF;  // what ge2gl was last told
    u32 displayFramebuf_ = 0, displayStride_ = 512;
    GEBufferFormat displayFormat_ = GE_FORMAT_8888;
    std::vector<uint8_t> shadow_;  // `gstate` as this core last wrote it

    bool recording_ = false;  // GE2GL_RECORD
    bool stateRoundTrip_ = false;  // GE2GL_STATE_ROUNDTRIP
    int roundTrips_ = 0, roundTripFailures_ = 0;
    bool kernelStopped_ = false;  // KernelStopping ran since the handler was registered
    PresentationCommon *presentation_ = nullptr;
    Draw::Texture *frameTexture_ = nullptr;
    std::vector<uint8_t> frameRgba_;
};
