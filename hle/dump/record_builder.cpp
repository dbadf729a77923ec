// SPDX-License-Identifier: MIT
// RecordBuilder: see record_builder.h, docs/recording.md and docs/ppdmp.md §3–§7. The structure
// follows PPSSPP's GPU/Debugger/Record.cpp (FlushPrimState, EmitTextureData, EmitClut,
// EmitTransfer, NotifyMemcpy/NotifyMemset, GetTargetFlags, DirtyDrawnVRAM); the code is our own.
#include "hle/dump/record_builder.h"

#include <algorithm>
#include <cstring>

namespace ge::dump {

namespace {

// Bits per texel of a texture format (docs/ge-rules.md §6.1; PPSSPP textureBitsPerPixel).
u32 texelBits(u32 fmt) {
    static constexpr u8 bits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8, 0, 0, 0, 0, 0};
    return bits[fmt & 15];
}

// Byte offset inside the 2 MiB of VRAM, mirrors folded (Record.cpp masks with 0x1FFFFF too).
u32 vramOffset(u32 addr) { return Memory::normalize(addr) & (Memory::kVramSize - 1); }

}  // namespace

RecordBuilder::RecordBuilder(DumpWriter& out, const Memory& mem, Options opt) : out_(out), mem_(mem), opt_(opt) {}

bool RecordBuilder::notRecorded(u32 op) {
    switch (op) {
    case GE_CMD_VADR: case GE_CMD_IADR: case GE_CMD_BASE: case GE_CMD_OFFSET: case GE_CMD_ORIGIN:
    case GE_CMD_JUMP: case GE_CMD_BJUMP: case GE_CMD_CALL: case GE_CMD_RET:
    case GE_CMD_END: case GE_CMD_SIGNAL: case GE_CMD_FINISH: case GE_CMD_BBOX:
        return true;
    default: return false;
    }
}

void RecordBuilder::reset() {
    vram_.assign(Memory::kVramSize >> kBlockShift, Vram::Dirty);
    shadow_.assign(Memory::kVramSize, 0);
    targets_.clear();
}

void RecordBuilder::warn(const std::string& w) {
    if (warnings_.size() < 32) warnings_.push_back(w);
}

void RecordBuilder::flushBlock() {
    if (block_.empty()) return;
    out_.registers(block_);
    block_.clear();
}

// Everything else (NOPs and unknown opcodes included, as PPSSPP) except what the player replaces
// or what steers the list; BBOX/BJUMP: the path taken is what gets recorded.
void RecordBuilder::command(u32 word) {
    if (!notRecorded(word >> 24)) block_.push_back(word);
}

const u8* RecordBuilder::read(u32 addr, u32 size) {
    if (!size) return nullptr;
    if (Memory::isVram(addr) && vramReadHook_) vramReadHook_(addr, size);
    return mem_.ptr(addr, size);
}

// Record.cpp FlushPrimState + EmitPrim: texture levels, INDICES, VERTICES, then the kick word.
void RecordBuilder::draw(const GeState& st, u32 word, u32 count) {
    // lastRenderTargets: colour and depth buffer of every draw (flag bit 0 of ppdmp.md §3.3).
    targets_.insert(vramOffset(st.framebufAddr()));
    targets_.insert(vramOffset(st.depthbufAddr()));
    drawTextures(st, count);
    if (count > 0) {
        const u32 stride = st.vertexStride();
        u64 vertexCount = count;
        if (const u32 isz = st.indexSize()) {
            // ppdmp.md §3.2: indexed draws carry (maxIndex + 1) vertices so the index values stay valid.
            const u32 want = count * isz;
            const u32 n = mem_.validSize(st.indexAddr, want);
            const u8* p = read(st.indexAddr, n);
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
        const u32 n = mem_.validSize(st.vertexAddr, u32(want));
        if (n < want) warn("a draw reads vertices outside guest memory");
        if (n) {
            const u8* p = read(st.vertexAddr, n);
            flushBlock();
            out_.vertices(p, n);
        }
    }
    block_.push_back(word);
    markDrawn(st);
    ++draws_;
}

void RecordBuilder::drawTextures(const GeState& st, u32 count) {
    if (opt_.textures == Textures::Sampled) {
        // Levels 0..MXL with an address, when the draw samples them.
        if (count == 0 || !st.TME_on() || st.CMODE_on()) return;
        const int maxLevel = int(std::min<u32>(st.TMODE_maxlevel(), 7));
        for (int level = 0; level <= maxLevel; ++level)
            if (const u32 addr = st.textureAddr(level)) texture(st, level, addr);
        return;
    }
    // Every level with an address, when texturing or antialiasing is on or the vertices carry
    // texture coordinates (PPSSPP plays it safe the same way; ppdmp.md §3.2).
    const bool texturing = st.TME_on() || st.AAE_on();
    const bool texCoords = st.VTYPE_tc() != 0;
    if (texturing || texCoords) {
        for (int level = 0; level < 8; ++level)
            if (const u32 addr = st.textureAddr(level)) texture(st, level, addr);
    }
}

// Record.cpp EmitTextureData: `bpp·(bufw·h + max(0, w − bufw))/8` bytes of level n (ppdmp.md §3.2), cut at
// the end of valid memory. VRAM levels become FRAMEBUFn with the address, the TBW width (players
// turn it into the TBWn word, ppdmp.md §6.2) and the ppdmp.md §3.3 flags, and carry their bytes
// unless the pixels are unknown (record_builder.h, Pixels::Unknown).
void RecordBuilder::texture(const GeState& st, int level, u32 addr) {
    const u32 bits = texelBits(st.TPF_format());
    if (!bits) {
        warn("texturing with an invalid texture format");
        return;
    }
    const u32 w = st.textureWidth(level), h = st.textureHeight(level), bufw = st.textureBufWidth(level);
    const u64 texels = u64(bufw) * h + (w > bufw ? w - bufw : 0);
    const u32 want = u32(std::min<u64>(texels * bits / 8, 0x7FFFFFFF));
    const u32 n = mem_.validSize(addr, want);
    if (Memory::isVram(addr)) {
        const u8* p = read(addr, n);
        const u32 flags = targetFlags(addr, n);
        flushBlock();
        if (opt_.pixels == Pixels::Unknown && (flags & 4)) {
            out_.framebufTexture(level, addr, st.TBW_width(level), flags | 2, nullptr, 0);
            return;
        }
        out_.framebufTexture(level, addr, st.TBW_width(level), flags, p, n);
        if (!(flags & 2)) updateShadow(addr, n);
    } else if (n) {
        if (n < want) warn("a texture level reaches past the end of guest memory");
        const u8* p = read(addr, n);
        flushBlock();
        out_.texture(level, p, n);
    }
}

// Record.cpp EmitClut: NP × 32 bytes (NP = 64 for 0x40), CLUTADDR first when in VRAM.
void RecordBuilder::clut(const GeState& st, u32 word) {
    const u32 addr = st.clutAddr();
    const u32 blocks = (word & 0x7F) == 0x40 ? 0x40 : (word & 0x3F);
    const u32 n = mem_.validSize(addr, blocks * 32);
    const bool unknown = opt_.pixels == Pixels::Unknown && Memory::isVram(addr) && anyDrawn(addr, n);
    if (n && !unknown) {
        const u8* p = read(addr, n);
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
bool RecordBuilder::transfer(const GeState& st, u32 word) {
    flushBlock();
    const u32 dst = st.transferDstAddr();
    if (!Memory::isVram(dst)) return false;
    const u32 bpp = (word & 1) ? 4 : 2;  // this XSTART's pixel size, not the previous one's
    const u32 w = st.XSIZE_w1() + 1, h = st.XSIZE_h1() + 1;
    const u32 src = st.transferSrcAddr();
    const u64 srcWant = (u64(st.XPOS1_y() + h - 1) * st.transferSrcStride() + st.XPOS1_x() + w) * bpp;
    const u64 dstWant = (u64(st.XPOS2_y() + h - 1) * st.transferDstStride() + st.XPOS2_x() + w) * bpp;
    const u32 n = mem_.validSize(src, u32(std::min<u64>(srcWant, 0x7FFFFFFF)));
    const u32 dn = mem_.validSize(dst, u32(std::min<u64>(dstWant, 0x7FFFFFFF)));
    if (opt_.pixels == Pixels::Unknown) {
        if (n && !(Memory::isVram(src) && anyDrawn(src, n))) out_.transferSrc(read(src, n), n);
        markVram(dst, dn, Vram::Drawn, false);  // the GE's pixels, which this recorder does not know
    } else if (n) {
        out_.transferSrc(read(src, n), n);
        markVram(dst, dn, Vram::Dirty, false);
    }
    block_.push_back(word);
    return true;
}

// Record.cpp DirtyDrawnVRAM: the rows up to the scissor/region bottom of the colour buffer, and of
// the depth buffer when the draw writes depth.
void RecordBuilder::markDrawn(const GeState& st) {
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

void RecordBuilder::markVram(u32 addr, u32 size, Vram state, bool wholeBlocksOnly) {
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

bool RecordBuilder::anyDrawn(u32 addr, u32 size) const {
    if (!size) return false;
    const u32 off = vramOffset(addr);
    const u32 end = std::min<u64>(u64(off) + size, Memory::kVramSize);
    for (u32 b = off >> kBlockShift; b <= (end - 1) >> kBlockShift; ++b)
        if (vram_[b] == Vram::Drawn) return true;
    return false;
}

// Record.cpp GetTargetFlags (ppdmp.md §3.3). The host may write VRAM without telling
// (ge2gl_mem_pointer), so "clean" blocks are always checked against the shadow copy, as PPSSPP
// does for blocks in its UNKNOWN state after the CPU ran.
u32 RecordBuilder::targetFlags(u32 addr, u32 size) {
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
        const u8* p = mem_.ptr(addr, size);
        unchanged = p && std::memcmp(shadow_.data() + off, p, size) == 0;
    }
    return (target ? 1 : 0) | (unchanged ? 2 : 0) | (drawn ? 4 : 0);
}

void RecordBuilder::updateShadow(u32 addr, u32 size) {
    if (!size || !Memory::isVram(addr)) return;
    const u32 off = vramOffset(addr);
    const u32 n = u32(std::min<u64>(size, Memory::kVramSize - off));
    if (const u8* p = mem_.ptr(addr, n)) std::memcpy(shadow_.data() + off, p, n);
}

// Record.cpp NotifyMemcpy / NotifyMemset: VRAM destinations only. A write of one repeated byte
// is a MEMSET (what a memset or ge2gl's player's fill looks like), anything else MEMCPYDATA with
// the bytes now in memory.
void RecordBuilder::hostWrite(u32 addr, u32 size) {
    if (!size || !Memory::isVram(addr)) return;
    const u32 n = mem_.validSize(addr, size);
    const u8* p = n ? mem_.ptr(addr, n) : nullptr;
    if (!p) return;
    flushBlock();
    const bool uniform = std::all_of(p, p + n, [&](u8 b) { return b == p[0]; });
    if (uniform) out_.memset(addr, p[0], n);
    else out_.memcpy(addr, p, n);
    updateShadow(addr, n);
    markVram(addr, n, Vram::Clean, true);
}

}  // namespace ge::dump
