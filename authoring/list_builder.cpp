// SPDX-License-Identifier: MIT
#include "authoring/list_builder.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "authoring/scene_recorder.h"

namespace ge {

namespace {

// Saturating conversion of a scaled float to an integer range (round half away from zero).
s32 toFixed(float v, float scale, s32 lo, s32 hi) {
    float s = v * scale;
    if (!(s == s)) return 0;  // NaN
    if (s <= float(lo)) return lo;
    if (s >= float(hi)) return hi;
    return s32(std::lround(s));
}

void put16(u8* p, s32 v) { writeLE16(p, u16(v)); }
void putF(u8* p, float f) {
    u32 bits;
    std::memcpy(&bits, &f, 4);
    writeLE32(p, bits);
}

}  // namespace

u32 log2Floor(u32 v) {
    u32 r = 0;
    while (v > 1) {
        v >>= 1;
        ++r;
    }
    return r;
}

// ---------------------------------------------------------------------------------------------
// Vertex packing (ge-rules.md §5.2 layout, §5.4 value scaling)

void packVertex(u32 vtype, const BuildVertex& v, u8* out) {
    const VertexLayout l = VertexLayout::fromVtype(vtype);
    std::memset(out, 0, l.size);
    const bool through = (vtype >> 23) & 1;
    const u32 wt = (vtype >> 9) & 3, wc = ((vtype >> 14) & 7) + 1;
    const u32 tc = vtype & 3, col = (vtype >> 2) & 7, nrm = (vtype >> 5) & 3, pos = (vtype >> 7) & 3;

    if (wt) {
        u8* p = out + l.weightOff;
        for (u32 i = 0; i < wc; ++i) {
            if (wt == 1) p[i] = u8(toFixed(v.w[i], 128.f, 0, 255));
            else if (wt == 2) put16(p + 2 * i, toFixed(v.w[i], 32768.f, 0, 65535));
            else putF(p + 4 * i, v.w[i]);
        }
    }
    if (tc) {
        u8* p = out + l.tcOff;
        if (tc == 1) {
            p[0] = u8(toFixed(v.u, 128.f, 0, 255));
            p[1] = u8(toFixed(v.v, 128.f, 0, 255));
        } else if (tc == 2) {
            // Through mode: 16-bit coordinates are texels; transform mode: 0x8000 = 1.0.
            float scale = through ? 1.f : 32768.f;
            put16(p, toFixed(v.u, scale, 0, 65535));
            put16(p + 2, toFixed(v.v, scale, 0, 65535));
        } else {
            putF(p, v.u);
            putF(p + 4, v.v);
        }
    }
    if (col >= 4) {
        u8* p = out + l.colOff;
        u32 r = v.color & 0xFF, g = (v.color >> 8) & 0xFF, b = (v.color >> 16) & 0xFF, a = v.color >> 24;
        switch (col) {
        case 4: writeLE16(p, u16((r >> 3) | (g >> 2) << 5 | (b >> 3) << 11)); break;
        case 5: writeLE16(p, u16((r >> 3) | (g >> 3) << 5 | (b >> 3) << 10 | (a >> 7) << 15)); break;
        case 6: writeLE16(p, u16((r >> 4) | (g >> 4) << 4 | (b >> 4) << 8 | (a >> 4) << 12)); break;
        default: writeLE32(p, v.color); break;
        }
    }
    if (nrm) {
        u8* p = out + l.nrmOff;
        const float n[3] = {v.nx, v.ny, v.nz};
        for (int i = 0; i < 3; ++i) {
            if (nrm == 1) p[i] = u8(s8(toFixed(n[i], 128.f, -128, 127)));
            else if (nrm == 2) put16(p + 2 * i, toFixed(n[i], 32768.f, -32768, 32767));
            else putF(p + 4 * i, n[i]);
        }
    }
    {
        u8* p = out + l.posOff;
        const float c[3] = {v.x, v.y, v.z};
        for (int i = 0; i < 3; ++i) {
            if (pos == 1 || pos == 0) {
                if (pos == 1) p[i] = u8(s8(toFixed(c[i], 128.f, -128, 127)));
            } else if (pos == 2) {
                if (through) put16(p + 2 * i, i == 2 ? toFixed(c[i], 1.f, 0, 65535) : toFixed(c[i], 1.f, -32768, 32767));
                else put16(p + 2 * i, toFixed(c[i], 32768.f, -32768, 32767));
            } else {
                putF(p + 4 * i, c[i]);
            }
        }
    }
}

std::vector<u8> packVertices(u32 vtype, const BuildVertex* v, u32 count) {
    const u32 size = VertexLayout::fromVtype(vtype).size;
    std::vector<u8> out(size_t(size) * count);
    for (u32 i = 0; i < count; ++i) packVertex(vtype, v[i], out.data() + size_t(i) * size);
    return out;
}

// ---------------------------------------------------------------------------------------------
// ListBuilder

ListBuilder::ListBuilder(Memory* mem, u32 arenaBase) : mem_(mem), arenaNext_(arenaBase), arenaEnd_(0) {
    if (mem_) arenaEnd_ = Memory::kRamBase + mem_->ramSize();
}

u32 ListBuilder::alloc(u32 size, u32 align) {
    if (!mem_ || align == 0 || (align & (align - 1))) return 0;
    const u64 at = (u64(arenaNext_) + align - 1) & ~u64(align - 1);
    if (at + size > arenaEnd_ || !mem_->valid(u32(at), std::max<u32>(size, 1))) return 0;
    arenaNext_ = u32(at + size);
    return u32(at);
}

u32 ListBuilder::place(const void* data, u32 size, u32 align) {
    const u32 at = alloc(size, align);
    if (!at) return 0;
    if (size && !mem_->write(at, data, size)) return 0;
    return at;
}

bool ListBuilder::upload(u32 addr, const void* data, u32 size) {
    if (!mem_ || !mem_->write(addr, data, size)) return false;
    if (rec_) rec_->cpuMemcpy(addr, data, size);
    return true;
}

bool ListBuilder::uploadFill(u32 addr, u8 value, u32 size) {
    if (!mem_ || !mem_->fill(addr, value, size)) return false;
    if (rec_) rec_->cpuMemset(addr, value, size);
    return true;
}

u32 ListBuilder::placeList(u32 align) { return place(words_.data(), u32(words_.size() * 4), std::max<u32>(align, 4)); }

void ListBuilder::raw(u32 word) {
    words_.push_back(word);
    if (rec_) rec_->command(word);
}

void ListBuilder::finish(u32 arg) {
    cmd(GE_CMD_FINISH, arg);
    cmd(GE_CMD_END, 0);
}

void ListBuilder::end(u32 arg) { cmd(GE_CMD_END, arg); }

void ListBuilder::signal(u32 behaviour, u32 arg, u32 endArg) {
    cmd(GE_CMD_SIGNAL, ((behaviour & 0xFF) << 16) | (arg & 0xFFFF));
    cmd(GE_CMD_END, endArg);
}

void ListBuilder::call(u32 addr) {
    base(addr);
    cmd(GE_CMD_CALL, addr & 0xFFFFFC);
}

void ListBuilder::jump(u32 addr) {
    base(addr);
    cmd(GE_CMD_JUMP, addr & 0xFFFFFC);
}

u32 ListBuilder::callList(const ListBuilder& sub) {
    const u32 at = place(sub.words().data(), u32(sub.words().size() * 4), 16);
    if (!at) return 0;
    call(at);
    if (rec_) {
        for (u32 w : sub.words()) {
            const u8 op = u8(w >> 24);
            if (op == GE_CMD_RET) break;
            rec_->command(w);
        }
    }
    return at;
}

void ListBuilder::addressCmd(u8 op, u32 addr) {
    // sceGuDrawArray: BASE carries address bits 27..24 (ge-rules.md §3.1), then the low 24.
    cmd(GE_CMD_BASE, (addr >> 8) & 0x0F0000);
    cmd(op, addr & 0xFFFFFF);
}

void ListBuilder::drawBuffer(u32 fmt, u32 vramOffset, u32 width) {
    cmd(GE_CMD_FPF, fmt);
    cmd(GE_CMD_FBP, vramOffset & 0xFFFFFF);
    cmd(GE_CMD_FBW, ((vramOffset & 0xFF000000) >> 8) | (width & 0x7FF));
}

void ListBuilder::depthBuffer(u32 vramOffset, u32 width) {
    cmd(GE_CMD_ZBP, vramOffset & 0xFFFFFF);
    cmd(GE_CMD_ZBW, ((vramOffset & 0xFF000000) >> 8) | (width & 0x7FF));
}

void ListBuilder::viewport(float cx, float cy, float w, float h) {
    cmdf(GE_CMD_SX, w / 2.f);
    cmdf(GE_CMD_SY, -h / 2.f);
    cmdf(GE_CMD_TX, cx);
    cmdf(GE_CMD_TY, cy);
}

void ListBuilder::offset(u32 x, u32 y) {
    cmd(GE_CMD_OFFSETX, (x << 4) & 0xFFFF);
    cmd(GE_CMD_OFFSETY, (y << 4) & 0xFFFF);
}

void ListBuilder::depthRange(u32 nearZ, u32 farZ) {
    // sceGuDepthRange (ge-rules.md §3.5): integer midpoint, SZ = mid − near, TZ = mid.
    const u32 mid = (nearZ + farZ) >> 1;
    cmdf(GE_CMD_SZ, float(mid) - float(nearZ));
    cmdf(GE_CMD_TZ, float(mid));
    cmd(GE_CMD_MINZ, std::min(nearZ, farZ) & 0xFFFF);
    cmd(GE_CMD_MAXZ, std::max(nearZ, farZ) & 0xFFFF);
}

void ListBuilder::scissor(u32 x1, u32 y1, u32 x2, u32 y2) {
    sx1_ = x1;
    sy1_ = y1;
    sx2_ = x2;
    sy2_ = y2;
    cmd(GE_CMD_SCISSOR1, (y1 & 0x3FF) << 10 | (x1 & 0x3FF));
    cmd(GE_CMD_SCISSOR2, ((y2 - 1) & 0x3FF) << 10 | ((x2 - 1) & 0x3FF));
}

void ListBuilder::region(u32 x, u32 y, u32 w, u32 h) {
    cmd(GE_CMD_REGION1, (y & 0x3FF) << 10 | (x & 0x3FF));
    cmd(GE_CMD_REGION2, ((y + h - 1) & 0x3FF) << 10 | ((x + w - 1) & 0x3FF));
}

void ListBuilder::clear(u32 flags, u32 color, u16 depth, u8 stencil) {
    // sceGuClear: 64-pixel-wide through-mode rectangles, 8888 colour + 16-bit position.
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    std::vector<BuildVertex> v;
    const u32 col = (color & 0xFFFFFF) | (u32(stencil) << 24);
    for (u32 x = sx1_; x < sx2_; x += 64) {
        BuildVertex a, b;
        a.color = b.color = col;
        a.x = float(x);
        a.y = float(sy1_);
        b.x = float(std::min(x + 64, sx2_));
        b.y = float(sy2_);
        a.z = b.z = float(depth);
        v.push_back(a);
        v.push_back(b);
    }
    const std::vector<u8> data = packVertices(vtype, v.data(), u32(v.size()));
    cmd(GE_CMD_CMODE, ((flags & 7) << 8) | 1);
    drawArrayData(GE_PRIM_RECTANGLES, vtype, u32(v.size()), nullptr, data.data());
    cmd(GE_CMD_CMODE, 0);
}

void ListBuilder::fillRect(u32 x1, u32 y1, u32 x2, u32 y2, u32 abgr) {
    constexpr u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    BuildVertex v[2];
    v[0].x = float(x1), v[0].y = float(y1), v[1].x = float(x2), v[1].y = float(y2);
    v[0].color = v[1].color = abgr;
    const std::vector<u8> data = packVertices(vtype, v, 2);
    drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
}

void ListBuilder::setMatrix(GeMatrix kind, const float m[16]) {
    if (kind == GeMatrix::Proj) {
        cmd(GE_CMD_PROJN, 0);
        for (int k = 0; k < 16; ++k) cmdf(GE_CMD_PROJD, m[k]);
        return;
    }
    float e[12];
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 3; ++row) e[col * 3 + row] = m[col * 4 + row];
    setMatrix3x4(kind, e);
}

void ListBuilder::setMatrix3x4(GeMatrix kind, const float m[12]) {
    u8 num = GE_CMD_WORLDN, data = GE_CMD_WORLDD;
    switch (kind) {
    case GeMatrix::World: break;
    case GeMatrix::View: num = GE_CMD_VIEWN; data = GE_CMD_VIEWD; break;
    case GeMatrix::TexGen: num = GE_CMD_TGENN; data = GE_CMD_TGEND; break;
    case GeMatrix::Proj: {
        // A 3×4 given for the projection: complete it with the row (0, 0, 0, 1).
        float p[16];
        for (int col = 0; col < 4; ++col) {
            for (int row = 0; row < 3; ++row) p[col * 4 + row] = m[col * 3 + row];
            p[col * 4 + 3] = col == 3 ? 1.f : 0.f;
        }
        setMatrix(GeMatrix::Proj, p);
        return;
    }
    }
    cmd(num, 0);
    for (int k = 0; k < 12; ++k) cmdf(data, m[k]);
}

void ListBuilder::setBoneMatrix(u32 i, const float m[12]) {
    cmd(GE_CMD_BONEN, (12 * (i & 7)) & 0x7F);
    for (int k = 0; k < 12; ++k) cmdf(GE_CMD_BONED, m[k]);
}

void ListBuilder::setTexture(u32 level, u32 addr, u32 w, u32 h, u32 bufw) {
    level &= 7;
    cmd(u8(GE_CMD_TBP0 + level), addr & 0xFFFFFF);
    cmd(u8(GE_CMD_TBW0 + level), ((addr >> 8) & 0x0F0000) | (bufw & 0x7FF));
    cmd(u8(GE_CMD_TSIZE0 + level), (log2Floor(h) << 8) | log2Floor(w));
    texFlush();
}

void ListBuilder::texMode(u32 format, u32 maxLevel, bool swizzle, bool multiClut) {
    cmd(GE_CMD_TMODE, ((maxLevel & 7) << 16) | (u32(multiClut) << 8) | u32(swizzle));
    cmd(GE_CMD_TPF, format & 0xF);
    texFlush();
}

void ListBuilder::texFunc(u32 func, bool rgba, bool doubling) {
    cmd(GE_CMD_TFUNC, (u32(doubling) << 16) | (u32(rgba) << 8) | (func & 7));
}

void ListBuilder::texLevelMode(u32 mode, float bias) {
    int offl = int(bias * 16.f);  // truncation, as the SDK
    offl = std::clamp(offl, -128, 127);
    cmd(GE_CMD_TLEVEL, (u32(offl & 0xFF) << 16) | (mode & 3));
}

void ListBuilder::texScale(float su, float sv) {
    cmdf(GE_CMD_SU, su);
    cmdf(GE_CMD_SV, sv);
}

void ListBuilder::texOffset(float tu, float tv) {
    cmdf(GE_CMD_TU, tu);
    cmdf(GE_CMD_TV, tv);
}

void ListBuilder::clutMode(u32 fmt, u32 shift, u32 mask, u32 start) {
    cmd(GE_CMD_CLUT, ((start & 0x1F) << 16) | ((mask & 0xFF) << 8) | ((shift & 0x1F) << 2) | (fmt & 3));
}

void ListBuilder::clutLoad(u32 addr, u32 blocks) {
    cmd(GE_CMD_CBP, addr & 0xFFFFFF);
    cmd(GE_CMD_CBW, (addr >> 8) & 0x0F0000);
    cmd(GE_CMD_CLOAD, blocks & 0x7F);
}

void ListBuilder::blendFunc(u32 eq, u32 a, u32 b, u32 fixA, u32 fixB) {
    cmd(GE_CMD_BLEND, ((eq & 7) << 8) | ((b & 0xF) << 4) | (a & 0xF));
    cmd(GE_CMD_FIXA, fixA);
    cmd(GE_CMD_FIXB, fixB);
}

void ListBuilder::colorFunc(u32 func, u32 ref, u32 mask) {
    cmd(GE_CMD_CTEST, func & 3);
    cmd(GE_CMD_CREF, ref);
    cmd(GE_CMD_CMSK, mask);
}

void ListBuilder::pixelMask(u32 rgbKeep, u32 alphaKeep) {
    cmd(GE_CMD_PMSK1, rgbKeep);
    cmd(GE_CMD_PMSK2, alphaKeep & 0xFF);
}

void ListBuilder::setDither(const int m[16]) {
    for (int row = 0; row < 4; ++row) {
        u32 v = 0;
        for (int col = 0; col < 4; ++col) v |= u32(m[row * 4 + col] & 0xF) << (4 * col);
        cmd(u8(GE_CMD_DTTH1 + row), v);
    }
}

void ListBuilder::light(u32 n, u32 type, u32 comps, const float pos[3]) {
    n &= 3;
    cmdf(u8(GE_CMD_LX0 + 3 * n), pos[0]);
    cmdf(u8(GE_CMD_LY0 + 3 * n), pos[1]);
    cmdf(u8(GE_CMD_LZ0 + 3 * n), pos[2]);
    cmd(u8(GE_CMD_LTYPE0 + n), ((type & 3) << 8) | (comps & 3));
}

void ListBuilder::lightColor(u32 n, u32 components, u32 rgb) {
    n &= 3;
    if (components & LIGHT_AMBIENT) cmd(u8(GE_CMD_LAC0 + 3 * n), rgb);
    if (components & LIGHT_DIFFUSE) cmd(u8(GE_CMD_LDC0 + 3 * n), rgb);
    if (components & LIGHT_SPECULAR) cmd(u8(GE_CMD_LSC0 + 3 * n), rgb);
}

void ListBuilder::lightAtt(u32 n, float a, float b, float c) {
    n &= 3;
    cmdf(u8(GE_CMD_LKA0 + 3 * n), a);
    cmdf(u8(GE_CMD_LKB0 + 3 * n), b);
    cmdf(u8(GE_CMD_LKC0 + 3 * n), c);
}

void ListBuilder::lightSpot(u32 n, const float dir[3], float exponent, float cutoff) {
    n &= 3;
    cmdf(u8(GE_CMD_LDX0 + 3 * n), dir[0]);
    cmdf(u8(GE_CMD_LDY0 + 3 * n), dir[1]);
    cmdf(u8(GE_CMD_LDZ0 + 3 * n), dir[2]);
    cmdf(u8(GE_CMD_LKS0 + n), exponent);
    cmdf(u8(GE_CMD_LKO0 + n), cutoff);
}

void ListBuilder::ambient(u32 abgr) {
    cmd(GE_CMD_AC, abgr & 0xFFFFFF);
    cmd(GE_CMD_AA, abgr >> 24);
}

void ListBuilder::materialAmbient(u32 abgr) {
    cmd(GE_CMD_MAC, abgr & 0xFFFFFF);
    cmd(GE_CMD_MAA, abgr >> 24);
}

void ListBuilder::fog(float nearZ, float farZ, u32 rgb) {
    float dist = farZ - nearZ;
    if (dist != 0.f) dist = 1.f / dist;
    cmd(GE_CMD_FC, rgb);
    cmdf(GE_CMD_FOG1, farZ);
    cmdf(GE_CMD_FOG2, dist);
}

void ListBuilder::drawArray(u32 prim, u32 vtype, u32 count, u32 indexAddr, u32 vertexAddr) {
    if (vtype) setVertexType(vtype);
    if (indexAddr) addressCmd(GE_CMD_IADR, indexAddr);
    if (vertexAddr) addressCmd(GE_CMD_VADR, vertexAddr);
    cmd(GE_CMD_PRIM, ((prim & 7) << 16) | (count & 0xFFFF));
}

u32 ListBuilder::indexBytes(u32 vtype, u32 count) const {
    static constexpr u32 sizes[4] = {0, 1, 2, 4};
    return sizes[(vtype >> 11) & 3] * count;
}

void ListBuilder::drawArrayData(u32 prim, u32 vtype, u32 count, const void* indices, const void* vertices) {
    u32 idxAddr = 0, vtxAddr = 0;
    const u32 stride = VertexLayout::fromVtype(vtype).size * (((vtype >> 18) & 7) + 1);
    u32 vertexCount = count;
    if (indices && ((vtype >> 11) & 3)) {
        const u32 isz = indexBytes(vtype, 1);
        idxAddr = place(indices, indexBytes(vtype, count), 4);
        // Indexed: the vertex array must cover the largest index.
        u32 maxIndex = 0;
        const u8* p = static_cast<const u8*>(indices);
        for (u32 i = 0; i < count; ++i) {
            const u8* q = p + size_t(i) * isz;
            maxIndex = std::max<u32>(maxIndex, isz == 1 ? q[0] : isz == 2 ? readLE16(q) : readLE32(q));
        }
        vertexCount = maxIndex + 1;
    }
    if (vertices) vtxAddr = place(vertices, vertexCount * stride, 4);
    drawArray(prim, vtype, count, idxAddr, vtxAddr);
}

void ListBuilder::drawBezier(u32 vtype, u32 ucount, u32 vcount, u32 indexAddr, u32 vertexAddr) {
    if (vtype) setVertexType(vtype);
    if (indexAddr) addressCmd(GE_CMD_IADR, indexAddr);
    if (vertexAddr) addressCmd(GE_CMD_VADR, vertexAddr);
    cmd(GE_CMD_BEZIER, ((vcount & 0xFF) << 8) | (ucount & 0xFF));
}

void ListBuilder::drawSpline(u32 vtype, u32 ucount, u32 vcount, u32 uedge, u32 vedge, u32 indexAddr, u32 vertexAddr) {
    if (vtype) setVertexType(vtype);
    if (indexAddr) addressCmd(GE_CMD_IADR, indexAddr);
    if (vertexAddr) addressCmd(GE_CMD_VADR, vertexAddr);
    cmd(GE_CMD_SPLINE, ((vedge & 3) << 18) | ((uedge & 3) << 16) | ((vcount & 0xFF) << 8) | (ucount & 0xFF));
}

void ListBuilder::copyImage(u32 psm, u32 sx, u32 sy, u32 width, u32 height, u32 srcStride, u32 src, u32 dx, u32 dy,
                            u32 dstStride, u32 dst) {
    // sceGuCopyImage (ge-rules.md §3.11): XBW carries address bits 31..24 in bits 23..16.
    cmd(GE_CMD_XBP1, src & 0xFFFFFF);
    cmd(GE_CMD_XBW1, ((src & 0xFF000000) >> 8) | (srcStride & 0x7FF));
    cmd(GE_CMD_XPOS1, (sy & 0x3FF) << 10 | (sx & 0x3FF));
    cmd(GE_CMD_XBP2, dst & 0xFFFFFF);
    cmd(GE_CMD_XBW2, ((dst & 0xFF000000) >> 8) | (dstStride & 0x7FF));
    cmd(GE_CMD_XPOS2, (dy & 0x3FF) << 10 | (dx & 0x3FF));
    cmd(GE_CMD_XSIZE, ((height - 1) & 0x3FF) << 10 | ((width - 1) & 0x3FF));
    cmd(GE_CMD_XSTART, psm == GE_FORMAT_8888 ? 1 : 0);
}

}  // namespace ge
