// SPDX-License-Identifier: MIT
// GE engine state: the 256-word command register file, the matrices, the palette RAM and the
// internal address registers (docs/ge-rules.md §1, §3.4, §4.1). Typed accessors for every field
// are generated from ge_fields.def; backends never shift and mask register words themselves.
#pragma once
#include <algorithm>
#include <array>
#include <string>

#include "hle/types.h"

namespace ge {

// Opcodes, generated from ge_cmds.def: GE_CMD_PRIM, GE_CMD_TBP0, …
enum GeCmd : u8 {
#define GE_OP(op, name, dirty) GE_CMD_##name = op,
#include "hle/ge_cmds.def"
#undef GE_OP
};

// Dirty groups raised when a command changes its register (ge_cmds.def).
enum GeDirty : u32 {
    DIRTY_VERTEX = 1u << 0,        // VTYPE, morph weights
    DIRTY_TRANSFORM = 1u << 1,     // matrices, viewport, offsets, texture scale, fog params
    DIRTY_BONES = 1u << 2,         // bone matrices
    DIRTY_LIGHTING = 1u << 3,      // lights and material
    DIRTY_TEXTURE = 1u << 4,       // texture addresses, sizes, format, filtering, wrap, levels
    DIRTY_CLUT = 1u << 5,          // palette RAM reloaded
    DIRTY_FRAGMENT = 1u << 6,      // texture function, fog colour, colour/alpha test, dither
    DIRTY_BLEND = 1u << 7,         // blending, logic op, plane masks
    DIRTY_DEPTHSTENCIL = 1u << 8,  // depth/stencil tests and ops, depth range
    DIRTY_RASTER = 1u << 9,        // scissor, region, culling, shading
    DIRTY_FRAMEBUF = 1u << 10,     // frame/depth buffer address, width, format
    DIRTY_ALL = 0x7FF,
};

const char* geCmdName(u8 op);   // "PRIM", or "UNKNOWN_03" for the unknown opcodes
u32 geCmdDirty(u8 op);          // dirty groups of an opcode
bool geCmdKnown(u8 op);

enum class GeFieldKind : u8 { U, S, B, F, C, H };
struct GeFieldInfo {
    const char* name;  // "ATEST_ref"
    u8 firstOp, count, stride, lsb, width;
    GeFieldKind kind;
};
// All fields of the table, and the fields of one opcode (index n of an indexed field filled in).
const GeFieldInfo* geFieldTable(size_t* count);
// Formats the fields of a command word, e.g. "func=4 ref=0x80 mask=0xff".
std::string geFormatFields(u32 word);

// Pixel formats (CMD_FPF, CMD_TPF, CMD_CLUT).
enum GeBufferFormat : u8 { GE_FORMAT_565 = 0, GE_FORMAT_5551 = 1, GE_FORMAT_4444 = 2, GE_FORMAT_8888 = 3 };
enum GeTexFormat : u8 {
    GE_TFMT_5650 = 0, GE_TFMT_5551, GE_TFMT_4444, GE_TFMT_8888, GE_TFMT_CLUT4, GE_TFMT_CLUT8,
    GE_TFMT_CLUT16, GE_TFMT_CLUT32, GE_TFMT_DXT1, GE_TFMT_DXT3, GE_TFMT_DXT5
};
enum GePrimType : u8 {
    GE_PRIM_POINTS = 0, GE_PRIM_LINES, GE_PRIM_LINE_STRIP, GE_PRIM_TRIANGLES, GE_PRIM_TRIANGLE_STRIP,
    GE_PRIM_TRIANGLE_FAN, GE_PRIM_RECTANGLES, GE_PRIM_KEEP_PREVIOUS
};
// Comparison functions of the alpha, stencil and depth tests (CMD_ATEST, CMD_STEST, CMD_ZTEST;
// ge-rules.md §3.10), stencil operations (CMD_SOP) and blend equations (CMD_BLEND bits 8–10).
// Codes the software model's pixel pipeline and both backends' reference rules
// (geometry/reference_rules.h) read.
enum GeCompareFunc : u8 { CMP_NEVER = 0, CMP_ALWAYS, CMP_EQUAL, CMP_NOTEQUAL, CMP_LESS, CMP_LEQUAL, CMP_GREATER, CMP_GEQUAL };
enum GeStencilOp : u8 { SOP_KEEP = 0, SOP_ZERO, SOP_REPLACE, SOP_INVERT, SOP_INCR, SOP_DECR };
enum GeBlendEq : u8 { BLEQ_ADD = 0, BLEQ_SUB, BLEQ_REVSUB, BLEQ_MIN, BLEQ_MAX, BLEQ_ABS };

struct GeState {
    // Command register file: the last word executed for each opcode, opcode included.
    std::array<u32, 256> regs{};
    // Matrices, element order as in ge-rules.md §3.4 (3x4: element k = row k%3, column k/3).
    float bone[96] = {};
    float world[12] = {}, view[12] = {}, proj[16] = {}, tgen[12] = {};
    // Upload indices (auto-incremented; keep counting past the end).
    u32 boneNum = 0, worldNum = 0, viewNum = 0, projNum = 0, tgenNum = 0;
    // Internal address registers (ge-rules.md §4.1).
    u32 vertexAddr = 0, indexAddr = 0, offsetAddr = 0;
    // Palette RAM (1024 bytes) and how much of it the last CLOAD filled.
    alignas(16) u8 clut[1024] = {};
    u32 clutLoadedBytes = 0;
    // The vertex unit's last texture coordinate and normal (decoded: morphed, skinned). A draw
    // whose vertex format has no UV or no normal reads these instead: on a PSP the previous
    // draw's last UV (0.75, 0.25) and normal (1, 1, 1) become the texture-matrix source of a draw
    // without them (pspautotests gpu/texmtx/source), and the reference renderer keeps both across
    // draws the same way (PPSSPP GPU/Software/TransformUnit.cpp ReadVertex, lastTC/lastnormal).
    // GeEngine::latchVertexAttributes updates them after each PRIM.
    float latchUV[2] = {};
    float latchNormal[3] = {};
    // What sceGeGetMtx reads: the float24 words as the matrix data ports wrote them, in a layout
    // of its own (bone 0-95, world 96-107, view 108-119, proj 120-135, tgen 136-147). Writes past
    // a matrix's end land here where rendering drops them: a bone or world/view index past the end
    // runs on into the following matrices, the projection index wraps within its 16 words (the
    // port keeps only its low 4 bits), the texgen matrix takes nothing past its 12 (pspautotests
    // gpu/ge/get: 100 bone, 16 world/view, 20 projection words; PPSSPP GPU/Software/SoftGpu.cpp
    // Execute_*MtxData, matrixVisible). docs/ge-rules.md §3.4.
    static constexpr u32 kVisibleMtxWords = 148;
    u32 visibleMtx[kVisibleMtxWords] = {};

    u32 op(u8 cmd) const { return regs[cmd] & 0xFFFFFF; }

    // Typed accessors generated from the field table.
#define GE_FIELD_U(name, op0, cnt, stride, lsb, width) \
    u32 name(int n = 0) const { return (regs[u8(op0 + n * stride)] >> lsb) & ((1u << width) - 1); }
#define GE_FIELD(name, op0, cnt, stride, lsb, width, kind) GE_FIELD_##kind(name, op0, cnt, stride, lsb, width)
#define GE_FIELD_H GE_FIELD_U
#define GE_FIELD_C GE_FIELD_U
#define GE_FIELD_B(name, op0, cnt, stride, lsb, width) \
    bool name(int n = 0) const { return (regs[u8(op0 + n * stride)] >> lsb) & 1; }
#define GE_FIELD_S(name, op0, cnt, stride, lsb, width) \
    int name(int n = 0) const {                           \
        return int(u32(regs[u8(op0 + n * stride)] << (32 - lsb - width))) >> (32 - width); \
    }
#define GE_FIELD_F(name, op0, cnt, stride, lsb, width) \
    float name(int n = 0) const { return float24(regs[u8(op0 + n * stride)]); }
#include "hle/ge_fields.def"
#undef GE_FIELD
#undef GE_FIELD_U
#undef GE_FIELD_H
#undef GE_FIELD_C
#undef GE_FIELD_B
#undef GE_FIELD_S
#undef GE_FIELD_F

    // ---- Derived values every backend needs (one definition each) ----
    bool isThrough() const { return VTYPE_through(); }
    bool isClearMode() const { return CMODE_on(); }
    // Frame/depth buffers always live in VRAM (ge-rules.md §7.2): PPSSPP's mask 0x1FFFF0.
    u32 framebufAddr() const { return 0x04000000 | (FBP_addr() & 0x1FFFF0); }
    u32 framebufStride() const { return FBW_width() & 0x7FC; }
    GeBufferFormat framebufFormat() const { return GeBufferFormat(FPF_format()); }
    u32 depthbufAddr() const { return 0x04000000 | (ZBP_addr() & 0x1FFFF0); }
    u32 depthbufStride() const { return ZBW_width() & 0x7FC; }
    u32 textureAddr(int level) const { return (TBP_addr(level) & 0xFFFFF0) | (TBW_high(level) << 24); }
    // Buffer width of a level in texels, with the format's 16-byte row alignment applied (ge-rules.md §6.2).
    u32 textureBufWidth(int level) const;
    u32 textureWidth(int level) const { return 1u << std::min<u32>(TSIZE_wlog(level), 9); }
    u32 textureHeight(int level) const { return 1u << std::min<u32>(TSIZE_hlog(level), 9); }
    GeTexFormat textureFormat() const { return GeTexFormat(TPF_format()); }
    u32 clutAddr() const { return (CBP_addr() & 0xFFFFF0) | (CBW_high() << 24); }
    u32 transferSrcAddr() const { return (XBP1_addr() & 0xFFFFF0) | (XBW1_high() << 24); }
    u32 transferDstAddr() const { return (XBP2_addr() & 0xFFFFF0) | (XBW2_high() << 24); }
    u32 transferSrcStride() const { return XBW1_width() & 0x7F8; }
    u32 transferDstStride() const { return XBW2_width() & 0x7F8; }
    // Dither matrix value at (x, y), signed −8…7 (ge-rules.md §3.10).
    int ditherValue(int x, int y) const {
        int v = (DTTH_row(y & 3) >> (4 * (x & 3))) & 0xF;
        return v >= 8 ? v - 16 : v;
    }
    // Vertex stride in bytes including morph copies, and the single-vertex size.
    u32 vertexSize() const;
    u32 vertexStride() const { return vertexSize() * (VTYPE_mcount() + 1); }
    u32 indexSize() const {
        static constexpr u32 sizes[4] = {0, 1, 2, 4};
        return sizes[VTYPE_idx()];
    }

    // ---- 512-word context (sceGeSaveContext layout == .ppdmp INIT record, docs/ppdmp.md §5) ----
    void saveContext(u32 out[512]) const;
    // Restores registers, matrices, indices and address registers. Returns false if the context
    // does not have the expected shape (it is still applied as far as it goes).
    bool loadContext(const u32 in[512]);
    // Registers a freshly booted GE holds (all zero except what the firmware sets).
    void reset();
};

// Opcodes stored in words 17–225 of a context, in order (ppdmp.md §5).
const std::array<u8, 209>& geContextOpcodes();

// Vertex layout of a VTYPE word (ge-rules.md §5.2): offsets of each component.
struct VertexLayout {
    u8 weightOff = 0, tcOff = 0, colOff = 0, nrmOff = 0, posOff = 0;
    u8 size = 0;       // one vertex
    u8 align = 1;
    u8 unused = 0;     // eight bytes: a lookup copies one word (seven made the copy stall on x86)
    static VertexLayout fromVtype(u32 vtype);
};

}  // namespace ge
