// SPDX-License-Identifier: MIT
#include "debugger/debugger.h"

#include <cstdio>

#include "geometry/transform.h"
#include "hle/disasm.h"
#include "hle/pixel_format.h"
#include "hle/texture_decoder.h"
#include "hle/vertex_decoder.h"

namespace ge::debug {

namespace {

std::string format(const char* f, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof buf, f, args...);
    return buf;
}

u8 opOf(u32 word) { return u8(word >> 24); }

// RGBA8888 with R in bits 7..0 to bytes R, G, B, A.
void putRgba(std::vector<u8>& out, u32 c) {
    for (int k = 0; k < 4; ++k) out.push_back(u8(c >> (8 * k)));
}

// Reads a pixel of a buffer in `fmt` at byte address `a`; false when the bytes are not memory.
bool pixelAt(const Memory& mem, u32 a, GeBufferFormat fmt, u32& raw) {
    const u32 bpp = fmt == GE_FORMAT_8888 ? 4 : 2;
    const u8* p = mem.ptr(a, bpp);
    if (!p) return false;
    raw = bpp == 4 ? readLE32(p) : readLE16(p);
    return true;
}

}  // namespace

bool isDrawKick(u32 word) {
    const u8 op = opOf(word);
    return op == GE_CMD_PRIM || op == GE_CMD_BEZIER || op == GE_CMD_SPLINE;
}

void Breakpoints::setAddress(u32 addr, bool on) {
    if (on) addrs_.insert(Memory::normalize(addr));
    else addrs_.erase(Memory::normalize(addr));
}

void Breakpoints::clearAll() {
    once_ = 0;
    ops_.reset();
    addrs_.clear();
}

bool Breakpoints::wants(u32 pc, u32 word) {
    const u8 op = opOf(word);
    if (once_ & kNextCommand) reason_ = "next command";
    else if ((once_ & kNextDraw) && isDrawKick(word)) reason_ = "next draw";
    else if ((once_ & kNextPrim) && op == GE_CMD_PRIM) reason_ = "next PRIM";
    else if ((once_ & kNextList) && currentList_ && (!haveLastList_ || currentList_() != lastList_)) reason_ = "next list";
    else if ((once_ & kNextFrame) && frameEnded_) reason_ = "next frame";
    else if (ops_[op]) reason_ = std::string("opcode ") + geCmdName(op);
    else if (addrs_.count(Memory::normalize(pc))) reason_ = format("address 0x%08x", Memory::normalize(pc));
    else return false;
    return true;
}

bool Breakpoints::beforeCommand(u32 pc, u32 word) {
    if (resuming_ && pc == resumePc_) {
        resuming_ = false;  // the command the GE stopped at: it runs now
    } else {
        resuming_ = false;
        if (wants(pc, word) && (!onBreak || onBreak(pc, word))) {
            // A stop is a one-shot step target: every pending "next ..." is taken by it.
            once_ = 0;
            resuming_ = true;
            resumePc_ = pc;
            return false;
        }
    }
    if (isDrawKick(word)) ++draws_;
    if (currentList_) {
        lastList_ = currentList_();
        haveLastList_ = true;
    }
    frameEnded_ = false;
    return true;
}

// ---- Read-outs ----

std::string stateText(const GeState& st) {
    std::string s;
    for (int op = 0; op < 256; ++op) {
        if (!geCmdKnown(u8(op))) continue;
        const u32 w = st.regs[size_t(op)];
        s += format("0x%02x %-8s %06x", op, geCmdName(u8(op)), w & 0xFFFFFF);
        const std::string fields = geFormatFields((u32(op) << 24) | (w & 0xFFFFFF));
        if (!fields.empty()) s += "  " + fields;
        s += '\n';
    }
    auto matrix = [&](const char* name, const float* m, int rows, int cols, u32 index) {
        s += format("%s (upload index %u):\n", name, index);
        // GE element order (docs/ge-rules.md §3.4): element k of a 3x4 is row k % 3, column k / 3; 4x4 row k % 4.
        for (int r = 0; r < rows; ++r) {
            s += " ";
            for (int c = 0; c < cols; ++c) s += format(" %12.6g", double(m[c * rows + r]));
            s += '\n';
        }
    };
    matrix("world", st.world, 3, 4, st.worldNum);
    matrix("view", st.view, 3, 4, st.viewNum);
    matrix("projection", st.proj, 4, 4, st.projNum);
    matrix("texgen", st.tgen, 3, 4, st.tgenNum);
    for (int b = 0; b < 8; ++b) matrix(format("bone %d", b).c_str(), st.bone + 12 * b, 3, 4, st.boneNum);
    s += format("vertex address 0x%08x, index address 0x%08x, OFFSET 0x%08x, palette bytes loaded %u\n", st.vertexAddr,
                st.indexAddr, st.offsetAddr, st.clutLoadedBytes);
    return s;
}

std::string listText(const ListRegs& l, const GeState& st) {
    std::string s = format("pc 0x%08x, stall 0x%08x, BASE 0x%08x, OFFSET 0x%08x, BFLG %d\n", l.pc, l.stall,
                           (st.regs[GE_CMD_BASE] & 0x00FF0000) << 8, st.offsetAddr, l.bflg ? 1 : 0);
    s += format("CALL depth %u", l.callDepth);
    for (u32 i = 0; i < l.callDepth && i < 2; ++i) s += format(", return 0x%08x (OFFSET 0x%08x)", l.callStack[i][0], l.callStack[i][1]);
    s += format("\nSIGNAL stack depth %zu of %u\n", l.signalStack.size(), l.signalStackMax);
    return s;
}

std::string disassembly(const Memory& mem, u32 addr, u32 count, u32 mark) {
    std::string s;
    for (u32 i = 0; i < count; ++i) {
        const u32 a = Memory::normalize(addr + 4 * i);
        const u8* p = mem.ptr(a, 4);
        if (!p) {
            s += format("  0x%08x: (not memory)\n", a);
            break;
        }
        const u32 w = readLE32(p);
        s += format("%c 0x%08x: %08x  ", a == Memory::normalize(mark) ? '>' : ' ', a, w) + disassemble(w) + '\n';
    }
    return s;
}

// Calls fn(raw) for each pixel of the frame buffer's width x height corner, rows top to bottom;
// false when a pixel lies outside memory.
template <class F>
bool forEachFramePixel(const Memory& mem, const GeState& st, u32 width, u32 height, F&& fn) {
    const GeBufferFormat fmt = st.framebufFormat();
    const u32 bpp = fmt == GE_FORMAT_8888 ? 4 : 2;
    for (u32 y = 0; y < height; ++y)
        for (u32 x = 0; x < width; ++x) {
            u32 raw = 0;
            if (!pixelAt(mem, st.framebufAddr() + (y * st.framebufStride() + x) * bpp, fmt, raw)) return false;
            fn(raw);
        }
    return true;
}

bool readColor(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u8>& rgba) {
    rgba.clear();
    const GeBufferFormat fmt = st.framebufFormat();
    return forEachFramePixel(mem, st, width, height,
                             [&](u32 raw) { putRgba(rgba, fmt == GE_FORMAT_8888 ? raw : decodePixel16(u16(raw), fmt)); });
}

bool readDepth(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u16>& out) {
    out.clear();
    for (u32 y = 0; y < height; ++y)
        for (u32 x = 0; x < width; ++x) {
            const u8* p = mem.ptr(st.depthbufAddr() + (y * st.depthbufStride() + x) * 2, 2);
            if (!p) return false;
            out.push_back(readLE16(p));
        }
    return true;
}

bool readStencil(const Memory& mem, const GeState& st, u32 width, u32 height, std::vector<u8>& out) {
    out.clear();
    // The stencil lives in the colour buffer's alpha bits (manual §15; ge-rules.md §3.10).
    const GeBufferFormat fmt = st.framebufFormat();
    const int shift = fmt == GE_FORMAT_5551 ? 15 : fmt == GE_FORMAT_4444 ? 12 : 24;
    return forEachFramePixel(mem, st, width, height,
                             [&](u32 raw) { out.push_back(fmt == GE_FORMAT_565 ? 0 : u8(raw >> shift)); });
}

bool readTexture(const Memory& mem, const GeState& st, int level, u32& width, u32& height, std::vector<u8>& rgba) {
    if (level < 0 || level > 7) return false;
    std::vector<u32> texels;
    if (!decodeTextureLevel(mem, st, level, texels)) return false;
    width = st.textureWidth(level);
    height = st.textureHeight(level);
    rgba.clear();
    rgba.reserve(texels.size() * 4);
    for (u32 c : texels) putRgba(rgba, c);
    return texels.size() == size_t(width) * height;
}

std::vector<u32> readClut(const GeState& st) {
    std::vector<u32> out;
    const GeBufferFormat fmt = GeBufferFormat(st.CLUT_format());
    if (fmt == GE_FORMAT_8888) {
        for (u32 i = 0; i < 256; ++i) out.push_back(readLE32(st.clut + 4 * i));
    } else {
        for (u32 i = 0; i < 512; ++i) out.push_back(decodePixel16(readLE16(st.clut + 2 * i), fmt));
    }
    return out;
}

bool drawVertices(const Memory& mem, const GeState& st, u32 word, const geo::AccuracyProfile& acc,
                  std::vector<DrawVertex>& out, std::string& err) {
    out.clear();
    if (opOf(word) != GE_CMD_PRIM) {
        err = "the command at the pc is not a PRIM";
        return false;
    }
    const u32 count = word & 0xFFFF, vtype = st.op(GE_CMD_VTYPE);
    std::vector<DecodedVertex> in;
    if (!decodeDrawVertices(mem, st, vtype, st.vertexAddr, st.indexAddr, count, in, &err)) return false;
    const VertexReader reader(mem, st, vtype);
    geo::TransformState ts =
        geo::makeTransformState(st, vtype, reader.hasColor(), /*hasNormal: the format's or the latched one*/ true, nullptr, acc);
    ts.sprite = ((word >> 16) & 7) == GE_PRIM_RECTANGLES && acc.pspSpritePosition;
    for (const DecodedVertex& v : in) {
        geo::ClipVertex cv;
        geo::transformVertex(ts, v, cv);
        DrawVertex d;
        d.in = v;
        d.screenX = float(cv.sv.x) / 16.0f;
        d.screenY = float(cv.sv.y) / 16.0f;
        d.screenZ = cv.sv.z;
        d.s = cv.sv.s, d.t = cv.sv.t, d.q = cv.sv.q;
        for (int k = 0; k < 4; ++k) d.color[k] = cv.sv.color[k];
        d.outside = cv.outside || !cv.valid;
        out.push_back(d);
    }
    return true;
}

}  // namespace ge::debug
