// SPDX-License-Identifier: MIT
#include "hle/ge_state.h"

#include <array>
#include <cstdio>
#include <vector>

namespace ge {

namespace {

struct CmdInfo {
    const char* name = nullptr;
    u32 dirty = 0;
};

const std::array<CmdInfo, 256>& cmdTable() {
    static const std::array<CmdInfo, 256> table = [] {
        std::array<CmdInfo, 256> t{};
#define GE_OP(op, nm, dirty) t[op] = CmdInfo{#nm, u32(dirty)};
#include "hle/ge_cmds.def"
#undef GE_OP
        return t;
    }();
    return table;
}

const GeFieldInfo kFields[] = {
#define GE_FIELD(nm, op0, cnt, stride, lsb, width, kind) {#nm, op0, cnt, stride, lsb, width, GeFieldKind::kind},
#include "hle/ge_fields.def"
#undef GE_FIELD
};

// Per opcode: indices into kFields.
const std::array<std::vector<u16>, 256>& fieldsByOp() {
    static const std::array<std::vector<u16>, 256> byOp = [] {
        std::array<std::vector<u16>, 256> t;
        for (u16 i = 0; i < sizeof(kFields) / sizeof(kFields[0]); ++i)
            for (int n = 0; n < kFields[i].count; ++n) t[u8(kFields[i].firstOp + n * kFields[i].stride)].push_back(i);
        return t;
    }();
    return byOp;
}

}  // namespace

const char* geCmdName(u8 op) {
    static char unknown[256][12];
    static bool init = [] {
        for (int i = 0; i < 256; ++i) std::snprintf(unknown[i], sizeof(unknown[i]), "UNKNOWN_%02X", i);
        return true;
    }();
    (void)init;
    const char* n = cmdTable()[op].name;
    return n ? n : unknown[op];
}

u32 geCmdDirty(u8 op) { return cmdTable()[op].dirty; }
bool geCmdKnown(u8 op) { return cmdTable()[op].name != nullptr; }

const GeFieldInfo* geFieldTable(size_t* count) {
    if (count) *count = sizeof(kFields) / sizeof(kFields[0]);
    return kFields;
}

std::string geFormatFields(u32 word) {
    std::string out;
    char buf[64];
    for (u16 i : fieldsByOp()[word >> 24]) {
        const GeFieldInfo& f = kFields[i];
        u32 v = (word >> f.lsb) & ((1u << f.width) - 1);
        const char* fieldName = f.name;
        if (const char* us = std::strchr(f.name, '_')) fieldName = us + 1;
        switch (f.kind) {
        case GeFieldKind::U: std::snprintf(buf, sizeof buf, "%s=%u", fieldName, v); break;
        case GeFieldKind::S: {
            int s = int(v << (32 - f.width)) >> (32 - f.width);
            std::snprintf(buf, sizeof buf, "%s=%d", fieldName, s);
            break;
        }
        case GeFieldKind::B: std::snprintf(buf, sizeof buf, "%s=%s", fieldName, v ? "on" : "off"); break;
        case GeFieldKind::F: std::snprintf(buf, sizeof buf, "%s=%g", fieldName, double(float24(word))); break;
        case GeFieldKind::C: std::snprintf(buf, sizeof buf, "%s=#%06x", fieldName, v); break;
        case GeFieldKind::H: std::snprintf(buf, sizeof buf, "%s=0x%x", fieldName, v); break;
        }
        if (!out.empty()) out += ' ';
        out += buf;
    }
    return out;
}

u32 GeState::textureBufWidth(int level) const {
    u32 w = TBW_width(level);
    // Row must be a multiple of 16 bytes: round down to the format's alignment, 0 → minimum.
    static constexpr u32 align[16] = {8, 8, 8, 4, 32, 16, 8, 4, 8, 4, 4, 4, 4, 4, 4, 4};
    u32 a = align[TPF_format()];
    w &= ~(a - 1);
    return w ? w : a;
}

namespace {

constexpr VertexLayout computeLayout(u32 vtype) {
    constexpr u8 tcSize[4] = {0, 2, 4, 8}, tcAlign[4] = {1, 1, 2, 4};
    constexpr u8 colSize[8] = {0, 0, 0, 0, 2, 2, 2, 4}, colAlign[8] = {1, 1, 1, 1, 2, 2, 2, 4};
    constexpr u8 nrmSize[4] = {0, 3, 6, 12}, nrmAlign[4] = {1, 1, 2, 4};
    constexpr u8 posSize[4] = {3, 3, 6, 12}, posAlign[4] = {1, 1, 2, 4};  // VT=0: 3 bytes reserved
    constexpr u8 wSize[4] = {0, 1, 2, 4};
    VertexLayout l;
    u32 off = 0;
    u8 maxAlign = 1;
    auto place = [&](u32 size, u8 align) -> u8 {
        off = (off + align - 1) & ~u32(align - 1);
        const u8 at = u8(off);
        off += size;
        if (align > maxAlign) maxAlign = align;
        return at;
    };
    const u32 wt = (vtype >> 9) & 3, wc = ((vtype >> 14) & 7) + 1;
    const u32 tc = vtype & 3, col = (vtype >> 2) & 7, nrm = (vtype >> 5) & 3, pos = (vtype >> 7) & 3;
    if (wt) l.weightOff = place(wSize[wt] * wc, wSize[wt]);
    if (tc) l.tcOff = place(tcSize[tc], tcAlign[tc]);
    if (colSize[col]) l.colOff = place(colSize[col], colAlign[col]);
    if (nrm) l.nrmOff = place(nrmSize[nrm], nrmAlign[nrm]);
    l.posOff = place(posSize[pos], posAlign[pos]);
    l.size = u8((off + maxAlign - 1) & ~u32(maxAlign - 1));
    l.align = maxAlign;
    return l;
}

// The layout depends on 14 bits of VTYPE (TT, CT, NT, VT, WT: bits 0–10; the weight count:
// 14–16). Every reader of a draw asks for it (several times a draw), so all 16,384 are made at
// compile time: a lookup is an index, with no initialisation guard.
constexpr u32 layoutIndex(u32 vtype) { return (vtype & 0x7FF) | ((vtype >> 3) & 0x3800u); }
constexpr auto kLayouts = [] {
    std::array<VertexLayout, 1u << 14> t{};
    for (u32 i = 0; i < t.size(); ++i) t[i] = computeLayout((i & 0x7FF) | ((i & 0x3800u) << 3));
    return t;
}();

}  // namespace

VertexLayout VertexLayout::fromVtype(u32 vtype) { return kLayouts[layoutIndex(vtype)]; }

u32 GeState::vertexSize() const { return VertexLayout::fromVtype(regs[GE_CMD_VTYPE]).size; }

const std::array<u8, 209>& geContextOpcodes() {
    static const std::array<u8, 209> ops = [] {
        std::array<u8, 209> t{};
        const std::pair<int, int> ranges[] = {{0x00, 0x02}, {0x10, 0x10}, {0x12, 0x28}, {0x2C, 0x33},
                                              {0x36, 0x38}, {0x42, 0x4D}, {0x50, 0x51}, {0x53, 0x58},
                                              {0x5B, 0xB5}, {0xB8, 0xC3}, {0xC5, 0xD0}, {0xD2, 0xE9},
                                              {0xEB, 0xEC}, {0xEE, 0xEE}, {0xF0, 0xF6}, {0xF8, 0xF9}};
        size_t i = 0;
        for (auto [a, b] : ranges)
            for (int op = a; op <= b; ++op) t[i++] = u8(op);
        return t;
    }();
    return ops;
}

namespace {
struct MatrixSlot {
    u8 numOp, dataOp;
    int count;
};
constexpr MatrixSlot kMatrixSlots[5] = {{0x2A, 0x2B, 96}, {0x3A, 0x3B, 12}, {0x3C, 0x3D, 12}, {0x3E, 0x3F, 16}, {0x40, 0x41, 12}};
// Where each matrix starts in GeState::visibleMtx (bone, world, view, proj, tgen).
constexpr u32 visibleBase(int m) { return m == 0 ? 0 : m == 1 ? 96 : m == 2 ? 108 : m == 3 ? 120 : 136; }
}  // namespace

void GeState::saveContext(u32 out[512]) const {
    std::memset(out, 0, 512 * 4);
    out[5] = vertexAddr;
    out[6] = indexAddr;
    out[7] = offsetAddr;
    const auto& ops = geContextOpcodes();
    for (size_t i = 0; i < ops.size(); ++i) out[17 + i] = (u32(ops[i]) << 24) | (regs[ops[i]] & 0xFFFFFF);
    const u32 nums[5] = {boneNum & 0x7F, worldNum & 0xF, viewNum & 0xF, projNum & 0xF, tgenNum & 0xF};
    u32 w = 226;
    // The matrices as sceGeGetMtx reads them (visibleMtx), which is what the firmware saves: they
    // differ from the ones drawn with only where a list wrote past a matrix's end (PPSSPP
    // GPU/GPUState.cpp GEState::Save saves its CPU-visible copy too).
    for (int m = 0; m < 5; ++m) {
        out[w++] = u32(kMatrixSlots[m].numOp) << 24;
        for (int k = 0; k < kMatrixSlots[m].count; ++k)
            out[w++] = (u32(kMatrixSlots[m].dataOp) << 24) | (visibleMtx[visibleBase(m) + u32(k)] & 0xFFFFFF);
    }
    for (int m = 0; m < 5; ++m) out[w++] = (u32(kMatrixSlots[m].numOp) << 24) | nums[m];
    out[w] = u32(GE_CMD_END) << 24;  // word 384
}

bool GeState::loadContext(const u32 in[512]) {
    bool ok = true;
    vertexAddr = in[5];
    indexAddr = in[6];
    offsetAddr = in[7];
    const auto& ops = geContextOpcodes();
    for (size_t i = 0; i < ops.size(); ++i) {
        u32 word = in[17 + i];
        if ((word >> 24) != ops[i]) ok = false;
        regs[ops[i]] = (u32(ops[i]) << 24) | (word & 0xFFFFFF);
    }
    float* mats[5] = {bone, world, view, proj, tgen};
    u32* nums[5] = {&boneNum, &worldNum, &viewNum, &projNum, &tgenNum};
    u32 w = 226;
    for (int m = 0; m < 5; ++m) {
        if ((in[w] >> 24) != kMatrixSlots[m].numOp) ok = false;
        ++w;
        for (int k = 0; k < kMatrixSlots[m].count; ++k, ++w) {
            if ((in[w] >> 24) != kMatrixSlots[m].dataOp) ok = false;
            mats[m][k] = float24(in[w]);
            // Restoring writes through the data ports: drawn and read-back values agree again.
            visibleMtx[visibleBase(m) + u32(k)] = in[w] & 0xFFFFFF;
        }
    }
    for (int m = 0; m < 5; ++m, ++w) {
        if ((in[w] >> 24) != kMatrixSlots[m].numOp) ok = false;
        *nums[m] = in[w] & (m == 0 ? 0x7F : 0xF);
        regs[kMatrixSlots[m].numOp] = (u32(kMatrixSlots[m].numOp) << 24) | *nums[m];
    }
    return ok;
}

void GeState::reset() { *this = GeState{}; }

}  // namespace ge
