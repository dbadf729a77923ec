// SPDX-License-Identifier: MIT
#include "authoring/scene_recorder.h"

#include <algorithm>

#include "hle/dump/dump_writer.h"

namespace ge {

namespace {

// VRAM addresses compared without the mirror bits (all four mirrors are the same bytes for
// drawing, docs/ge-rules.md §7.3); other addresses just drop bits 31..28.
u32 canonical(u32 addr) {
    u32 a = Memory::normalize(addr);
    if (Memory::isVram(a)) return Memory::kVramBase | (a & (Memory::kVramSize - 1));
    return a;
}

// Bits per texel of a texture format (ge-rules.md §6.1).
u32 texelBits(u32 fmt) {
    static constexpr u8 bits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8, 0, 0, 0, 0, 0};
    return bits[fmt & 15];
}

}  // namespace

DumpRecorder::DumpRecorder(const Memory& mem, dump::DumpWriter& out) : mem_(mem), out_(out) {}

void DumpRecorder::begin(const GeState& initial, u32 displayAddr, u32 stride, u32 format) {
    st_ = initial;
    u32 ctx[512];
    st_.saveContext(ctx);
    out_.init(ctx);
    out_.display(displayAddr, stride, format);
    begun_ = true;
}

void DumpRecorder::end(u32 displayAddr, u32 stride, u32 format) {
    flushBlock();
    out_.display(displayAddr, stride, format);
}

u32 DumpRecorder::formAddress(u32 arg) const {
    // ge-rules.md §4.2: (BASE-high | arg) + OFFSET, 28 bits (PPSSPP keeps BASE bits 19..16).
    u32 hi = (st_.regs[GE_CMD_BASE] & 0x000F0000) << 8;
    return ((hi | (arg & 0xFFFFFF)) + st_.offsetAddr) & 0x0FFFFFFF;
}

void DumpRecorder::flushBlock() {
    if (block_.empty()) return;
    out_.registers(block_);
    block_.clear();
}

void DumpRecorder::command(u32 word) {
    const u8 op = u8(word >> 24);
    const u32 arg = word & 0xFFFFFF;
    switch (op) {
    // Words the recorder replaces by data records or that only steer the list: never stored in
    // REGISTERS (docs/ppdmp.md §3.2, §7 rule 4). Their effect on the pointers is tracked.
    case GE_CMD_NOP: return;
    case GE_CMD_VADR:
        st_.regs[op] = word;
        st_.vertexAddr = formAddress(arg);
        return;
    case GE_CMD_IADR:
        st_.regs[op] = word;
        st_.indexAddr = formAddress(arg);
        return;
    case GE_CMD_BASE: st_.regs[op] = word; return;
    case GE_CMD_OFFSET: st_.offsetAddr = arg << 8; return;
    case GE_CMD_ORIGIN:
        warnings_.push_back("ORIGIN: the recorder does not know list addresses; OFFSET left as is");
        return;
    case GE_CMD_JUMP: case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET:
    case GE_CMD_END: case GE_CMD_SIGNAL: case GE_CMD_FINISH:
        return;
    case GE_CMD_BBOX: {
        // BBOX advances the pointers like a draw (ge-rules.md §4.6); its result is not replayed.
        u32 count = arg & 0xFFFF;
        if (st_.VTYPE_idx()) st_.indexAddr += count * st_.indexSize();
        else st_.vertexAddr += count * st_.vertexStride();
        return;
    }
    case GE_CMD_PRIM: case GE_CMD_BEZIER: case GE_CMD_SPLINE: recordDraw(word); return;
    case GE_CMD_CLOAD: recordClut(word); return;
    case GE_CMD_XSTART: recordTransfer(word); return;
    default: break;
    }
    if (!geCmdKnown(op)) return;  // unknown opcodes are no-ops; nothing worth recording
    st_.regs[op] = word;
    block_.push_back(word);
}

void DumpRecorder::recordDraw(u32 word) {
    const u8 op = u8(word >> 24);
    u32 count;
    if (op == GE_CMD_PRIM) count = word & 0xFFFF;
    else count = (word & 0xFF) * ((word >> 8) & 0xFF);  // control points of a patch (ge-rules.md §4.6)

    flushBlock();
    if (count > 0) {
        if (st_.TME_on() && !st_.CMODE_on()) recordTextures();
        const u32 stride = st_.vertexStride();
        u32 vertexCount = count;
        if (st_.VTYPE_idx()) {
            const u32 isz = st_.indexSize();
            std::vector<u8> idx(size_t(count) * isz);
            if (!mem_.read(st_.indexAddr, idx.data(), u32(idx.size()))) {
                warnings_.push_back("draw reads indices outside memory");
                idx.assign(idx.size(), 0);
            }
            u32 maxIndex = 0;
            for (u32 i = 0; i < count; ++i) {
                const u8* p = idx.data() + size_t(i) * isz;
                u32 v = isz == 1 ? p[0] : isz == 2 ? readLE16(p) : readLE32(p);
                maxIndex = std::max(maxIndex, v);
            }
            out_.indices(idx.data(), u32(idx.size()));
            vertexCount = maxIndex + 1;
            st_.indexAddr += count * isz;
        }
        // ppdmp.md §3.2: vertex bytes for the draw: count × stride (indexed: (maxIndex+1) × stride).
        const u32 bytes = vertexCount * stride;
        const u32 avail = mem_.validSize(st_.vertexAddr, bytes);
        if (avail < bytes) warnings_.push_back("draw reads vertices outside memory");
        if (const u8* p = mem_.ptr(st_.vertexAddr, avail)) out_.vertices(p, avail);
        if (!st_.VTYPE_idx()) st_.vertexAddr += bytes;
        const bool depthWritten = (st_.CMODE_on() && st_.CMODE_depth()) || (!st_.CMODE_on() && st_.ZTE_on() && !st_.ZMSK_nowrite());
        markDrawnBuffers(depthWritten);
    }
    st_.regs[op] = word;
    block_.push_back(word);
    ++kicks_;
}

void DumpRecorder::recordTextures() {
    // Levels 0..MXL with a non-zero address (ppdmp.md §3.2: the recorder records every
    // level it may sample; levels above MXL are never read).
    const u32 maxLevel = std::min<u32>(st_.TMODE_maxlevel(), 7);
    const u32 bits = texelBits(st_.TPF_format());
    if (bits == 0) {
        warnings_.push_back("texturing with an invalid texture format");
        return;
    }
    for (u32 level = 0; level <= maxLevel; ++level) {
        const u32 addr = st_.textureAddr(int(level));
        if (addr == 0) continue;
        const u32 bufw = st_.textureBufWidth(int(level));
        const u32 w = st_.textureWidth(int(level)), h = st_.textureHeight(int(level));
        // ppdmp.md §3.2: bpp·(bufw·h + max(0, w − bufw))/8, cut at the end of valid memory.
        const u64 texels = u64(bufw) * h + (w > bufw ? w - bufw : 0);
        const u32 want = u32(std::min<u64>(texels * bits / 8, 0x7FFFFFFF));
        const u32 size = mem_.validSize(addr, want);
        const u8* data = size ? mem_.ptr(addr, size) : nullptr;
        if (Memory::isVram(addr)) {
            const u32 rawBufw = st_.TBW_width(int(level));
            if (overlapsDrawn(addr, want)) {
                // Pixels drawn by the GE in this recording: header only, "drawn" | "unchanged"
                // (| "target"), so players keep what they rendered (ppdmp.md §3.3).
                u32 flags = 4 | 2 | (isTarget(addr) ? 1 : 0);
                out_.framebufTexture(int(level), addr, rawBufw, flags, nullptr, 0);
            } else {
                out_.framebufTexture(int(level), addr, rawBufw, 0, data, size);
            }
        } else {
            if (size < want) warnings_.push_back("texture level reaches past the end of memory");
            out_.texture(int(level), data, size);
        }
    }
}

void DumpRecorder::recordClut(u32 word) {
    flushBlock();
    const u32 arg = word & 0xFFFFFF;
    // ge-rules.md §3.8: NP blocks of 32 bytes; (arg & 0x7F) == 0x40 counts as 64; palette RAM is 1024 bytes.
    u32 blocks = (arg & 0x7F) == 0x40 ? 64 : (arg & 0x3F);
    const u32 want = std::min<u32>(blocks * 32, 1024);
    const u32 addr = st_.clutAddr();
    const u32 size = mem_.validSize(addr, want);
    if (want > 0) {
        if (Memory::isVram(addr) && overlapsDrawn(addr, want)) {
            // A palette drawn by the GE in this recording: its bytes are only known to a renderer.
            // No CLUT record: the CBP/CBW words stay as recorded (VRAM CLUT addresses are kept,
            // ppdmp.md §6.4), so the player's CLOAD reads the pixels it rendered.
        } else {
            if (Memory::isVram(addr)) out_.clutAddr(addr, 0);
            out_.clut(size ? mem_.ptr(addr, size) : nullptr, size);
        }
    }
    st_.regs[GE_CMD_CLOAD] = word;
    block_.push_back(word);
    ++kicks_;
}

bool DumpRecorder::recordTransfer(u32 word) {
    const u32 dst = st_.transferDstAddr();
    if (!Memory::isVram(dst)) {
        // PPSSPP records only transfers into VRAM; the XSTART word itself is dropped (ppdmp.md §3.2).
        warnings_.push_back("transfer to RAM dropped from the dump");
        return false;
    }
    const u32 bpp = (word & 1) ? 4 : 2;
    const u32 w = st_.XSIZE_w1() + 1, h = st_.XSIZE_h1() + 1;
    const u32 sx = st_.XPOS1_x(), sy = st_.XPOS1_y();
    const u32 src = st_.transferSrcAddr(), srcStride = st_.transferSrcStride();
    // ppdmp.md §3.2: bytes from the source base up to the last pixel used.
    const u32 want = ((sy + h - 1) * srcStride + sx + w) * bpp;
    flushBlock();
    if (Memory::isVram(src) && overlapsDrawn(src, want)) {
        // The source pixels were drawn by the GE in this recording and only a renderer knows
        // them. Without a TRANSFERSRC record the XBP1/XBW1 words stay as recorded (they point
        // into VRAM), so players copy what they rendered (ppdmp.md §6.4).
    } else {
        const u32 size = mem_.validSize(src, want);
        if (size < want) warnings_.push_back("transfer source reaches past the end of memory");
        out_.transferSrc(size ? mem_.ptr(src, size) : nullptr, size);
    }
    st_.regs[GE_CMD_XSTART] = word;
    block_.push_back(word);
    ++kicks_;
    // The destination rows now hold GE-written pixels.
    const u32 dstStride = st_.transferDstStride();
    const u32 dstBegin = dst + (st_.XPOS2_y() * dstStride + st_.XPOS2_x()) * bpp;
    drawn_.push_back({canonical(dstBegin), canonical(dstBegin) + ((h - 1) * dstStride + w) * bpp});
    return true;
}

void DumpRecorder::markDrawnBuffers(bool depthWritten) {
    // Conservative extent: every row up to the scissor's bottom edge (ge-rules.md §8.6: the scissor always limits drawing).
    const u32 rows = st_.SCISSOR2_y() + 1;
    const u32 bpp = st_.FPF_format() == GE_FORMAT_8888 ? 4 : 2;
    const u32 fb = canonical(st_.framebufAddr());
    drawn_.push_back({fb, fb + rows * std::max<u32>(st_.framebufStride(), 1) * bpp});
    if (std::find(targets_.begin(), targets_.end(), fb) == targets_.end()) targets_.push_back(fb);
    if (depthWritten) {
        const u32 zb = canonical(st_.depthbufAddr());
        drawn_.push_back({zb, zb + rows * std::max<u32>(st_.depthbufStride(), 1) * 2});
        if (std::find(targets_.begin(), targets_.end(), zb) == targets_.end()) targets_.push_back(zb);
    }
    // Keep the list short: merge ranges that touch.
    std::sort(drawn_.begin(), drawn_.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
    std::vector<Range> merged;
    for (const Range& r : drawn_) {
        if (!merged.empty() && r.begin <= merged.back().end) merged.back().end = std::max(merged.back().end, r.end);
        else merged.push_back(r);
    }
    drawn_.swap(merged);
}

bool DumpRecorder::overlapsDrawn(u32 addr, u32 size) const {
    const u32 b = canonical(addr), e = b + size;
    for (const Range& r : drawn_)
        if (b < r.end && r.begin < e) return true;
    return false;
}

bool DumpRecorder::isTarget(u32 addr) const {
    return std::find(targets_.begin(), targets_.end(), canonical(addr)) != targets_.end();
}

void DumpRecorder::forgetDrawn(u32 dest, u32 size) {
    const u32 b = canonical(dest), e = b + size;
    std::vector<Range> kept;
    for (const Range& r : drawn_) {
        if (r.end <= b || e <= r.begin) {
            kept.push_back(r);
            continue;
        }
        if (r.begin < b) kept.push_back({r.begin, b});
        if (e < r.end) kept.push_back({e, r.end});
    }
    drawn_.swap(kept);
}

void DumpRecorder::cpuMemcpy(u32 dest, const void* data, u32 size) {
    if (!Memory::isVram(dest) || size == 0) return;
    // The copy happens between GE commands: close the open block so players run the list up
    // to here first (ppdmp.md §6.2 MEMCPYDATA).
    flushBlock();
    out_.memcpy(dest, data, size);
    forgetDrawn(dest, size);
}

void DumpRecorder::cpuMemset(u32 dest, u8 value, u32 size) {
    if (!Memory::isVram(dest) || size == 0) return;
    flushBlock();
    out_.memset(dest, value, size);
    forgetDrawn(dest, size);
}

}  // namespace ge
