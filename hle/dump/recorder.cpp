// SPDX-License-Identifier: MIT
// FrameRecorder: see recorder.h, docs/recording.md and docs/ppdmp.md §3–§7. The structure
// follows PPSSPP's GPU/Debugger/Record.cpp (NotifyCommand, FlushPrimState, EmitTextureData,
// EmitClut, EmitTransfer, NotifyMemcpy/NotifyMemset, GetTargetFlags, DirtyDrawnVRAM,
// CheckEdramTrans); the code is our own.
#include "hle/dump/recorder.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace ge::dump {

namespace {

// Bits per texel of a texture format (docs/ge-rules.md §6.1; PPSSPP textureBitsPerPixel).
u32 texelBits(u32 fmt) {
    static constexpr u8 bits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8, 0, 0, 0, 0, 0};
    return bits[fmt & 15];
}

// Byte offset inside the 2 MiB of VRAM, mirrors folded (Record.cpp masks with 0x1FFFFF too).
u32 vramOffset(u32 addr) { return Memory::normalize(addr) & (Memory::kVramSize - 1); }

bool isMatrixOp(int op) {
    return op == GE_CMD_BONEN || op == GE_CMD_BONED || (op >= GE_CMD_WORLDN && op <= GE_CMD_TGEND);
}

// Opcodes a REGISTERS block must not hold (ppdmp.md §7 rule 4): a player replaces them by
// its own (pointers from data records) or they steer the list.
bool notRecorded(u32 op) {
    switch (op) {
    case GE_CMD_VADR: case GE_CMD_IADR: case GE_CMD_BASE: case GE_CMD_OFFSET: case GE_CMD_ORIGIN:
    case GE_CMD_JUMP: case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET:
    case GE_CMD_END: case GE_CMD_SIGNAL: case GE_CMD_FINISH: case GE_CMD_BBOX:
        return true;
    default: return false;
    }
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

FrameRecorder::FrameRecorder(GeEngine& engine, std::string gameId) : eng_(engine), out_(std::move(gameId)) {}

// Never touches the engine (recorder.h): the owner detaches first, or the engine is gone.
FrameRecorder::~FrameRecorder() = default;

void FrameRecorder::warn(const std::string& w) {
    if (warnings_.size() < 32) warnings_.push_back(w);
}

void FrameRecorder::begin() {
    if (attached_) return;
    const GeState& st = eng_.state();
    // Record.cpp BeginRecording: INIT (the context, ppdmp.md §5), then the CLUT cache at the start (the
    // 1024-byte palette RAM; ppdmp.md §2.1 "a CLUT record right after INIT"), then the frame shown.
    u32 ctx[512];
    st.saveContext(ctx);
    out_.init(ctx);
    out_.clut(st.clut, sizeof st.clut);
    clutRegsReplaced_ = true;
    out_.display(st.framebufAddr(), st.framebufStride(), st.framebufFormat());
    // Nothing of VRAM is known to the dump yet (DirtyAllVRAM(DIRTY)); a player's VRAM starts as
    // zeros (ppdmp.md §6.4), which is what the shadow copy says.
    vram_.assign(Memory::kVramSize >> kBlockShift, Vram::Dirty);
    shadow_.assign(Memory::kVramSize, 0);
    targets_.clear();
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
    flushBlock();
    out_.display(addr, stride, format & 0xFF);
    haveHostDisplay_ = true;
    dispAddr_ = addr, dispStride_ = stride, dispFormat_ = format & 0xFF;
}

void FrameRecorder::end() {
    if (!attached_) return;
    checkEdram();
    flushBlock();
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

void FrameRecorder::flushBlock() {
    if (block_.empty()) return;
    out_.registers(block_);
    block_.clear();
}

// Record.cpp CheckEdramTrans: an EDRAMTRANS record whenever the value changed.
void FrameRecorder::checkEdram() {
    const u32 v = eng_.memory().edramTranslation();
    if (v == lastEdram_) return;
    flushBlock();
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
        warn("palette RAM changed outside the display list (a context or state load): not in the dump");
    if (!changed) return;
    u32 ctx[512];
    s.saveContext(ctx);
    for (int i = 17; i < 384; ++i) {
        const u32 op = ctx[i] >> 24;
        if (op == GE_CMD_NOP || notRecorded(op)) continue;
        block_.push_back(ctx[i]);
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
    switch (op) {
    case GE_CMD_PRIM: emitDraw(word, word & 0xFFFF); break;
    // Patches read Ucount × Vcount control points (Record.cpp EmitBezierSpline).
    case GE_CMD_BEZIER:
    case GE_CMD_SPLINE: emitDraw(word, (word & 0xFF) * ((word >> 8) & 0xFF)); break;
    case GE_CMD_CLOAD: emitClut(word); break;
    case GE_CMD_XSTART: emitTransfer(word); break;
    default:
        // Everything else (NOPs and unknown opcodes included, as PPSSPP) except what the player
        // replaces or what steers the list; BBOX/BJUMP: the path taken is what gets recorded.
        if (!notRecorded(op)) block_.push_back(word);
        break;
    }
    before_ = eng_.state();
    lastOp_ = int(op);
}

const u8* FrameRecorder::readGuest(u32 addr, u32 size) {
    if (!size) return nullptr;
    // A backend drawing on the GPU holds render targets' newest pixels: bring them to VRAM.
    if (Memory::isVram(addr)) eng_.renderer()->syncMemoryForRead(addr, size);
    return eng_.memory().ptr(addr, size);
}

// Record.cpp FlushPrimState + EmitPrim: texture levels, INDICES, VERTICES, then the kick word.
void FrameRecorder::emitDraw(u32 word, u32 count) {
    const GeState& st = eng_.state();
    // lastRenderTargets: colour and depth buffer of every draw (flag bit 0 of ppdmp.md §3.3).
    targets_.insert(vramOffset(st.framebufAddr()));
    targets_.insert(vramOffset(st.depthbufAddr()));

    // Every level with an address, when texturing or antialiasing is on or the vertices carry
    // texture coordinates (PPSSPP plays it safe the same way; ppdmp.md §3.2).
    const bool texturing = st.TME_on() || st.AAE_on();
    const bool texCoords = st.VTYPE_tc() != 0;
    if (texturing || texCoords) {
        for (int level = 0; level < 8; ++level)
            if (const u32 addr = st.textureAddr(level)) emitTexture(level, addr);
    }

    if (count > 0) {
        Memory& mem = eng_.memory();
        const u32 stride = st.vertexStride();
        u64 vertexCount = count;
        if (const u32 isz = st.indexSize()) {
            // ppdmp.md §3.2: indexed draws carry (maxIndex + 1) vertices so the index values stay valid.
            const u32 want = count * isz;
            const u32 n = mem.validSize(st.indexAddr, want);
            const u8* p = readGuest(st.indexAddr, n);
            if (n < want) warn("a draw reads indices outside guest memory");
            u32 maxIndex = 0;
            for (u32 i = 0; p && i + isz <= n; i += isz)
                maxIndex = std::max(maxIndex, isz == 1 ? u32(p[i]) : isz == 2 ? u32(readLE16(p + i)) : readLE32(p + i));
            if (n) {
                flushBlock();
                out_.indices(p, n);
            }
            vertexCount = u64(maxIndex) + 1;
        }
        const u64 want = std::min<u64>(vertexCount * stride, 0x7FFFFFFF);
        const u32 n = mem.validSize(st.vertexAddr, u32(want));
        if (n < want) warn("a draw reads vertices outside guest memory");
        if (n) {
            const u8* p = readGuest(st.vertexAddr, n);
            flushBlock();
            out_.vertices(p, n);
        }
    }
    block_.push_back(word);
    markDrawn();
    ++draws_;
}

// Record.cpp EmitTextureData: `bpp·(bufw·h + max(0, w − bufw))/8` bytes of level n (ppdmp.md §3.2), cut at
// the end of valid memory. VRAM levels become FRAMEBUFn with the address, the TBW width (players
// turn it into the TBWn word, ppdmp.md §6.2) and the ppdmp.md §3.3 flags, and always carry their bytes.
void FrameRecorder::emitTexture(int level, u32 addr) {
    const GeState& st = eng_.state();
    const u32 bits = texelBits(st.TPF_format());
    if (!bits) {
        warn("texturing with an invalid texture format");
        return;
    }
    const u32 w = st.textureWidth(level), h = st.textureHeight(level), bufw = st.textureBufWidth(level);
    const u64 texels = u64(bufw) * h + (w > bufw ? w - bufw : 0);
    const u32 want = u32(std::min<u64>(texels * bits / 8, 0x7FFFFFFF));
    const u32 n = eng_.memory().validSize(addr, want);
    if (Memory::isVram(addr)) {
        const u8* p = readGuest(addr, n);
        const u32 flags = targetFlags(addr, n);
        flushBlock();
        out_.framebufTexture(level, addr, st.TBW_width(level), flags, p, n);
        if (!(flags & 2)) updateShadow(addr, n);
    } else if (n) {
        if (n < want) warn("a texture level reaches past the end of guest memory");
        const u8* p = readGuest(addr, n);
        flushBlock();
        out_.texture(level, p, n);
    }
}

// Record.cpp EmitClut: NP × 32 bytes (NP = 64 for 0x40), CLUTADDR first when in VRAM.
void FrameRecorder::emitClut(u32 word) {
    const GeState& st = eng_.state();
    const u32 addr = st.clutAddr();
    const u32 blocks = (word & 0x7F) == 0x40 ? 0x40 : (word & 0x3F);
    const u32 n = eng_.memory().validSize(addr, blocks * 32);
    if (n) {
        const u8* p = readGuest(addr, n);
        if (Memory::isVram(addr)) {
            // The player leaves CBP/CBW as recorded for a VRAM palette (ppdmp.md §6.2): put them back if
            // the initial CLUT record made the player point them elsewhere.
            if (clutRegsReplaced_) {
                block_.push_back(st.regs[GE_CMD_CBP]);
                block_.push_back(st.regs[GE_CMD_CBW]);
                clutRegsReplaced_ = false;
            }
            const u32 flags = targetFlags(addr, n);
            flushBlock();
            out_.clutAddr(addr, flags);
            if (!(flags & 2)) updateShadow(addr, n);
        }
        flushBlock();
        out_.clut(p, n);
    }
    block_.push_back(word);
}

// Record.cpp EmitTransfer: only transfers into VRAM (the XSTART word of others is dropped too);
// the source from its base up to the last pixel used (ppdmp.md §3.2).
void FrameRecorder::emitTransfer(u32 word) {
    const GeState& st = eng_.state();
    flushBlock();
    const u32 dst = st.transferDstAddr();
    if (!Memory::isVram(dst)) return;
    const u32 bpp = (word & 1) ? 4 : 2;  // this XSTART's pixel size, not the previous one's
    const u32 w = st.XSIZE_w1() + 1, h = st.XSIZE_h1() + 1;
    const u32 src = st.transferSrcAddr();
    const u64 srcWant = (u64(st.XPOS1_y() + h - 1) * st.transferSrcStride() + st.XPOS1_x() + w) * bpp;
    const u64 dstWant = (u64(st.XPOS2_y() + h - 1) * st.transferDstStride() + st.XPOS2_x() + w) * bpp;
    const u32 n = eng_.memory().validSize(src, u32(std::min<u64>(srcWant, 0x7FFFFFFF)));
    const u32 dn = eng_.memory().validSize(dst, u32(std::min<u64>(dstWant, 0x7FFFFFFF)));
    if (n) {
        out_.transferSrc(readGuest(src, n), n);
        markVram(dst, dn, Vram::Dirty, false);
    }
    block_.push_back(word);
}

// Record.cpp DirtyDrawnVRAM: the rows up to the scissor/region bottom of the colour buffer, and of
// the depth buffer when the draw writes depth.
void FrameRecorder::markDrawn() {
    const GeState& st = eng_.state();
    const u32 w = std::min(st.SCISSOR2_x(), st.REGION2_x()) + 1;
    const u32 h = std::min(st.SCISSOR2_y(), st.REGION2_y()) + 1;
    const bool clear = st.CMODE_on();
    if ((!clear && !st.ZMSK_nowrite() && st.ZTE_on()) || (clear && st.CMODE_depth())) {
        const u32 zs = st.depthbufStride();
        markVram(st.depthbufAddr(), 2 * (zs * h + (w > zs ? w - zs : 0)), Vram::Drawn, false);
    }
    const u32 bpp = st.framebufFormat() == GE_FORMAT_8888 ? 4 : 2;
    const u32 fs = st.framebufStride();
    markVram(st.framebufAddr(), bpp * (fs * h + (w > fs ? w - fs : 0)), Vram::Drawn, false);
}

void FrameRecorder::markVram(u32 addr, u32 size, Vram state, bool wholeBlocksOnly) {
    if (!size || !Memory::isVram(addr)) return;
    const u32 off = vramOffset(addr);
    const u32 end = std::min<u64>(u64(off) + size, Memory::kVramSize);
    const u32 bs = 1u << kBlockShift;
    u32 first = off >> kBlockShift, last = (end - 1) >> kBlockShift;  // inclusive
    if (wholeBlocksOnly) {
        first = (off + bs - 1) >> kBlockShift;
        if ((end >> kBlockShift) == 0) return;
        last = (end >> kBlockShift) - 1;
        if (first > last) return;
    }
    for (u32 b = first; b <= last; ++b) vram_[b] = state;
}

// Record.cpp GetTargetFlags (ppdmp.md §3.3). The host may write VRAM without telling
// (ge2gl_mem_pointer), so "clean" blocks are always checked against the shadow copy, as PPSSPP
// does for blocks in its UNKNOWN state after the CPU ran.
u32 FrameRecorder::targetFlags(u32 addr, u32 size) {
    const u32 off = vramOffset(addr);
    const bool target = targets_.count(off) != 0;
    if (!size || u64(off) + size > Memory::kVramSize) return target ? 1 : 0;
    bool dirty = false, drawn = false;
    const u32 first = off >> kBlockShift, last = (off + size - 1) >> kBlockShift;
    const u32 bs = 1u << kBlockShift;
    for (u32 b = first; b <= last; ++b) {
        dirty = dirty || vram_[b] != Vram::Clean;
        drawn = drawn || vram_[b] == Vram::Drawn;
        // The bytes go into the dump now: whole blocks not drawn by the GE become known.
        const bool whole = b * bs >= off && (b + 1) * bs <= off + size;
        if (vram_[b] == Vram::Dirty && whole) vram_[b] = Vram::Clean;
    }
    bool unchanged = false;
    if (!dirty) {
        const u8* p = eng_.memory().ptr(addr, size);
        unchanged = p && std::memcmp(shadow_.data() + off, p, size) == 0;
    }
    return (target ? 1 : 0) | (unchanged ? 2 : 0) | (drawn ? 4 : 0);
}

void FrameRecorder::updateShadow(u32 addr, u32 size) {
    if (!size || !Memory::isVram(addr)) return;
    const u32 off = vramOffset(addr);
    const u32 n = u32(std::min<u64>(size, Memory::kVramSize - off));
    if (const u8* p = eng_.memory().ptr(addr, n)) std::memcpy(shadow_.data() + off, p, n);
}

// Record.cpp NotifyMemcpy / NotifyMemset: VRAM destinations only. A write of one repeated byte
// is a MEMSET (what a memset or ge2gl's player's fill looks like), anything else MEMCPYDATA with
// the bytes now in memory.
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
    if (!size || !Memory::isVram(addr)) return;
    Memory& mem = eng_.memory();
    const u32 n = mem.validSize(addr, size);
    const u8* p = n ? mem.ptr(addr, n) : nullptr;
    if (!p) return;
    flushBlock();
    const bool uniform = std::all_of(p, p + n, [&](u8 b) { return b == p[0]; });
    if (uniform) out_.memset(addr, p[0], n);
    else out_.memcpy(addr, p, n);
    updateShadow(addr, n);
    markVram(addr, n, Vram::Clean, true);
}

}  // namespace ge::dump
