// SPDX-License-Identifier: MIT
// FrameRecorder: records what a running GeEngine executes as a `.ppdmp` frame dump (version 6),
// the way PPSSPP's recorder does (GPU/Debugger/Record.cpp, GPURecord::Recorder), so that PPSSPP's
// player and `ge2gl render` replay it to the same picture (docs/ppdmp.md §4, §6, §7;
// docs/recording.md lists every record and where it comes from).
//
// It is a CommandObserver (hle/ge_engine.h): the engine calls it before every command, with its
// state and guest memory as they are before that command runs, and it hands them to a
// RecordBuilder (hle/dump/record_builder.h), which holds the recording rules: REGISTERS blocks, the
// data records of draws, CLOADs and transfers, and the VRAM knowledge behind the ppdmp.md §3.3
// flags. The recorder itself adds EDRAMTRANS whenever the eDRAM translation differs from the last
// value recorded (0x400 at first, Record.cpp CheckEdramTrans).
// While it records, a Renderer in front of the engine's backend passes every call through and
// turns the host's memoryWritten() notices (ge2gl_mem_write, ge2gl_mem_written, a save state
// load) into MEMCPYDEST + MEMCPYDATA, or MEMSET for a run of one byte value (NotifyMemcpy,
// NotifyMemset): only VRAM destinations, as PPSSPP (draws capture the RAM they read).
//
// Context restores (sceGeRestoreContext, a save state) change the registers without a command:
// the recorder notices them (a register that changed although the command that ran did not write
// it) and writes the whole context as state words, as the firmware restores one (ppdmp.md §5).
//
// Backends that draw elsewhere than guest memory (GL) are asked for the bytes the recorder reads
// from VRAM (Renderer::syncMemoryForRead) first, so render targets used as textures, CLUTs or
// transfer sources carry the pixels drawn so far, as PPSSPP's recorder reads them from its VRAM.
//
// No global state: each recorder belongs to one engine. It must be end()ed or detach()ed while
// the engine lives; its destructor never touches the engine (a host handle destroys the engine
// first and the recorder with the handle: the engine then holds a dead pointer nobody calls).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "hle/dump/dump_writer.h"
#include "hle/dump/record_builder.h"
#include "hle/ge_engine.h"

namespace ge::dump {

class FrameRecorder final : public CommandObserver {
public:
    explicit FrameRecorder(GeEngine& engine, std::string gameId = "GE2GL0001");
    ~FrameRecorder() override;
    FrameRecorder(const FrameRecorder&) = delete;
    FrameRecorder& operator=(const FrameRecorder&) = delete;

    // Writes INIT (the engine's context), CLUT (its palette RAM) and a DISPLAY (the current frame
    // buffer), then attaches to the engine. Between commands only (not from inside run()).
    void begin();
    // The host showed a frame buffer (sceDisplaySetFrameBuf; Record.cpp NotifyDisplay): a DISPLAY
    // record. Format 0–3 as CMD_FPF.
    void display(u32 addr, u32 stride, u32 format);
    // Closes the last REGISTERS block, writes the final DISPLAY (the last one the host gave if no
    // GE work followed it, else that frame buffer again, else the current one) and detaches.
    void end();
    // Detaches from the engine without finishing the dump.
    void detach();
    bool attached() const { return attached_; }

    // A host (CPU/DMA) write of guest memory that already happened.
    void hostWrote(u32 addr, u32 size);

    const Dump& dump() const { return out_.dump(); }
    // Things the dump cannot express (e.g. a palette changed outside the list). Empty for the
    // project's scenes.
    const std::vector<std::string>& warnings() const { return rec_.warnings(); }
    u64 draws() const { return rec_.draws(); }
    // Non-empty when the recording had to stop (the dump grew past the writer's limits): the dump
    // is then incomplete and must not be written.
    const std::string& failure() const { return failure_; }

    bool beforeCommand(u32 pc, u32 word) override;

private:
    class HostWriteHook;

    void record(u32 pc, u32 word);
    void recordHostWrite(u32 addr, u32 size);
    void checkEdram();
    void checkExternalChanges();

    GeEngine& eng_;
    DumpWriter out_;
    RecordBuilder rec_;
    std::unique_ptr<HostWriteHook> hook_;
    Renderer* inner_ = nullptr;
    bool attached_ = false;
    u32 lastEdram_ = 0x400;
    // External-change detection: the state before the last command and that command's opcode.
    GeState before_;
    int lastOp_ = -1;
    u64 lastCount_ = ~u64(0);  // stats().commands and pc at the last command seen
    u32 lastPc_ = 0;
    bool haveHostDisplay_ = false;
    u32 dispAddr_ = 0, dispStride_ = 0, dispFormat_ = 0;
    std::string failure_;
};

}  // namespace ge::dump
