// SPDX-License-Identifier: MIT
// `ge2gl fuzz` (difffuzz.h).
#include "tools/lib/difffuzz.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "hle/memory.h"
#include "tools/lib/blame.h"
#include "tools/lib/json_io.h"

namespace ge::tools {

namespace {

constexpr u32 kTexAddr = 0x08C00000, kClutAddr = 0x08D00000;
constexpr u32 kDepthOffset = 0x110000;  // VRAM offset of the depth buffer (stride 512)

// Every draw from the generator is sequenced (locals or braced lists, never two in one call's
// arguments, whose order C++ leaves open), so a seed gives the same case with any compiler.
struct Rng {
    std::mt19937_64 g;
    explicit Rng(u64 s) : g(s) {}
    u32 u(u32 lo, u32 hi) { return lo + u32(g() % (u64(hi) - lo + 1)); }
    bool p(double x) { return double(g() >> 11) * (1.0 / 9007199254740992.0) < x; }
    float f(float lo, float hi) { return lo + float(double(g() >> 11) * (1.0 / 9007199254740992.0)) * (hi - lo); }
    u32 bits() { return u32(g()); }
    u32 color() { return p(0.5) ? (bits() | 0xFF000000u) : bits(); }
};

template <class F>
FuzzItem group(F&& f) {
    ListBuilder s;
    f(s);
    FuzzItem it;
    it.words = s.words();
    return it;
}

void identity(float m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.f : 0.f;
}

u32 primCount(Rng& r, u32 prim) {
    switch (prim) {
    case GE_PRIM_POINTS: return r.u(1, 8);
    case GE_PRIM_LINES: return 2 * r.u(1, 4);
    case GE_PRIM_LINE_STRIP: return r.u(2, 6);
    case GE_PRIM_TRIANGLES: return 3 * r.u(1, 3);
    case GE_PRIM_RECTANGLES: return 2 * r.u(1, 3);
    default: return r.u(3, 8);  // strips, fans
    }
}

// Smallest count that still draws one primitive, and the step between valid counts.
u32 primMin(u32 prim) {
    switch (prim) {
    case GE_PRIM_POINTS: return 1;
    case GE_PRIM_LINES: case GE_PRIM_LINE_STRIP: case GE_PRIM_RECTANGLES: return 2;
    default: return 3;
    }
}
u32 primStep(u32 prim) {
    switch (prim) {
    case GE_PRIM_LINES: case GE_PRIM_RECTANGLES: return 2;
    case GE_PRIM_TRIANGLES: return 3;
    default: return 1;
    }
}

struct CaseShape {
    bool texture = false, lighting = false;
    u32 texW = 0, texH = 0;
    double throughBias = 0.4;
};

FuzzItem makeDraw(Rng& r, const CaseShape& cs, std::vector<FuzzItem>& items) {
    FuzzItem d;
    d.draw = true;
    d.prim = r.u(0, 6);
    const bool through = r.p(cs.throughBias);
    u32 vtype = through ? vt::THROUGH : 0;
    if (cs.texture ? r.p(0.9) : r.p(0.15)) vtype |= r.p(0.5) ? vt::TC_F : r.p(0.5) ? vt::TC_16 : vt::TC_8;
    if (r.p(0.8)) vtype |= u32(r.u(4, 7)) << 2;
    if (cs.lighting || r.p(0.1)) vtype |= u32(r.u(1, 3)) << 5;
    const u32 pr = r.u(0, 99);
    if (through) vtype |= pr < 5 ? vt::POS_8 : pr < 55 ? vt::POS_16 : vt::POS_F;
    else vtype |= pr < 15 ? vt::POS_8 : pr < 50 ? vt::POS_16 : vt::POS_F;
    u32 wcount = 0, mcount = 1;
    if (!through && r.p(0.05)) {
        wcount = r.u(1, 3);
        vtype |= (u32(r.u(1, 3)) << 9) | vt::weights(wcount);
        items.push_back(group([&](ListBuilder& b) {
            for (u32 i = 0; i < wcount; ++i) {
                const float s = r.f(0.5f, 1.2f);
                const float m[12] = {s, 0, 0, 0, s, 0, 0, 0, s, r.f(-0.2f, 0.2f), r.f(-0.2f, 0.2f), 0};
                b.setBoneMatrix(i, m);
            }
        }));
    }
    if (r.p(0.04)) {
        mcount = r.u(2, 3);
        vtype |= vt::morphs(mcount);
        items.push_back(group([&](ListBuilder& b) {
            for (u32 i = 0; i < mcount; ++i) b.setMorphWeight(i, r.f(0.f, 1.f));
        }));
    }
    d.count = primCount(r, d.prim);
    u32 nverts = d.count;
    if (r.p(0.25)) {
        vtype |= r.p(0.5) ? vt::IDX_8 : vt::IDX_16;
        nverts = r.u(2, 12);
        const u32 isz = (vtype & vt::IDX_16) == vt::IDX_16 ? 2 : 1;
        d.indices.resize(size_t(d.count) * isz);
        for (u32 i = 0; i < d.count; ++i) {
            const u32 ix = r.u(0, nverts - 1);
            d.indices[i * isz] = u8(ix);
            if (isz == 2) d.indices[i * isz + 1] = u8(ix >> 8);
        }
    }
    d.vtype = vtype;
    const u32 size = VertexLayout::fromVtype(vtype).size;
    d.vertices.assign(size_t(nverts) * mcount * size, 0);
    const float tw = float(cs.texW ? cs.texW : 16), th = float(cs.texH ? cs.texH : 16);
    for (u32 i = 0; i < nverts; ++i) {
        BuildVertex v;
        if (through) {
            v.x = std::round(r.f(-16, 496)), v.y = std::round(r.f(-16, 288)), v.z = std::round(r.f(0, 65535));
            if ((vtype & vt::POS_F) == vt::POS_F && r.p(0.5)) v.x += r.f(0, 1), v.y += r.f(0, 1);
            v.u = r.f(-0.25f * tw, 1.25f * tw), v.v = r.f(-0.25f * th, 1.25f * th);
            if ((vtype & 3) != vt::TC_F) v.u = std::round(v.u), v.v = std::round(v.v);
        } else {
            v.x = r.f(-1.1f, 1.1f), v.y = r.f(-1.1f, 1.1f), v.z = r.p(0.9) ? r.f(-0.95f, 0.95f) : r.f(-1.3f, 1.3f);
            v.u = r.f(-0.25f, 1.25f), v.v = r.f(-0.25f, 1.25f);
        }
        v.color = r.color();
        v.nx = r.f(-1, 1), v.ny = r.f(-1, 1), v.nz = r.f(-1, 1);
        for (u32 k = 0; k < 8; ++k) v.w[k] = r.f(0, 1);
        for (u32 k = 0; k < mcount; ++k) {
            BuildVertex c = v;
            if (k) c.x += r.f(-0.1f, 0.1f) * (through ? 40 : 1), c.y += r.f(-0.1f, 0.1f) * (through ? 40 : 1), c.color = r.color();
            packVertex(vtype, c, d.vertices.data() + (size_t(i) * mcount + k) * size);
        }
    }
    return d;
}

// A random change between draws: one enable flipped or one test/blend word redrawn.
FuzzItem makeToggle(Rng& r) {
    return group([&](ListBuilder& b) {
        switch (r.u(0, 5)) {
        case 0: b.enable(GE_CMD_ABE, r.p(0.5)); break;
        case 1: b.enable(GE_CMD_ZTE, r.p(0.5)); break;
        case 2: { const u32 a[] = {r.u(0, 5), r.u(0, 10), r.u(0, 10), r.bits() & 0xFFFFFF, r.bits() & 0xFFFFFF}; b.blendFunc(a[0], a[1], a[2], a[3], a[4]); break; }
        case 3: b.enable(GE_CMD_TME, r.p(0.5)); break;
        case 4: b.shadeModel(r.p(0.5)); break;
        default: b.cmd(GE_CMD_CMODE, r.p(0.7) ? 0 : (r.u(0, 7) << 8) | 1); break;
        }
    });
}

}  // namespace

size_t FuzzCase::weight() const {
    size_t w = 0;
    for (const auto& it : items) w += it.draw ? 1 + it.count : it.words.size();
    return w;
}

FuzzCase generateFuzzCase(u64 seed) {
    Rng r(seed * 0x9E3779B97F4A7C15ull + 0x1234567);
    FuzzCase c;
    c.seed = seed;
    c.fbFormat = r.u(0, 3);
    c.clearColor = r.color();
    c.clearDepth = r.p(0.5) ? 0 : r.u(0, 65535);
    CaseShape cs;
    cs.throughBias = r.p(0.4) ? 0.9 : 0.1;
    auto& items = c.items;

    // Transform: simple matrices so things land on screen (viewport/offset in the prologue map
    // [-1, 1] onto the 480x272 frame).
    items.push_back(group([&](ListBuilder& b) {
        float m[16];
        identity(m);
        if (r.p(0.3)) {
            const float a = r.f(-3.2f, 3.2f), s = r.f(0.5f, 1.3f);
            m[0] = std::cos(a) * s, m[1] = std::sin(a) * s, m[4] = -std::sin(a) * s, m[5] = std::cos(a) * s;
            m[12] = r.f(-0.3f, 0.3f), m[13] = r.f(-0.3f, 0.3f);
        }
        b.setMatrix(GeMatrix::World, m);
    }));
    items.push_back(group([&](ListBuilder& b) {
        float m[16];
        identity(m);
        b.setMatrix(GeMatrix::View, m);
    }));
    items.push_back(group([&](ListBuilder& b) {
        float m[16];
        identity(m);
        if (r.p(0.2)) m[11] = r.f(0.f, 0.3f), m[15] = 1.f;  // a little perspective: w from z
        b.setMatrix(GeMatrix::Proj, m);
    }));

    // Texture (~60%).
    if (r.p(0.6)) {
        cs.texture = true;
        const u32 fmt = r.p(0.12) ? r.u(GE_TFMT_DXT1, GE_TFMT_DXT5) : r.u(GE_TFMT_5650, GE_TFMT_CLUT32);
        cs.texW = 1u << r.u(3, 6), cs.texH = 1u << r.u(3, 6);
        const u32 minBufBytes = 16;
        const u32 bppNum = fmt == GE_TFMT_CLUT4 ? 1 : (fmt == GE_TFMT_CLUT8 ? 2 : (fmt == GE_TFMT_8888 || fmt == GE_TFMT_CLUT32) ? 8 : 4);
        u32 bufw = cs.texW;
        while (bufw * bppNum / 2 < minBufBytes) bufw *= 2;
        std::vector<u8> tex(size_t(bufw) * cs.texH * 4 + 64);
        for (auto& b : tex) b = u8(r.bits());
        if (r.p(0.5) && fmt < GE_TFMT_CLUT4)  // games' textures: mostly opaque
            for (size_t i = 0; i + 3 < tex.size(); i += 4) tex[i + 3] |= 0xF0;
        c.data.push_back({kTexAddr, std::move(tex)});
        const bool swz = fmt < GE_TFMT_DXT1 && r.p(0.25);
        items.push_back(group([&](ListBuilder& b) {
            b.setTexture(0, kTexAddr, cs.texW, cs.texH, bufw);
            b.texMode(fmt, 0, swz);
        }));
        if (fmt >= GE_TFMT_CLUT4 && fmt <= GE_TFMT_CLUT32) {
            std::vector<u8> pal(1024);
            for (auto& b : pal) b = u8(r.bits());
            c.data.push_back({kClutAddr, std::move(pal)});
            const u32 cfmt = r.u(0, 3);
            items.push_back(group([&](ListBuilder& b) {
                if (r.p(0.7)) b.clutMode(cfmt, 0, 0xFF, 0);
                else { const u32 a[] = {r.u(0, 31), r.u(0, 255), r.u(0, 31)}; b.clutMode(cfmt, a[0], a[1], a[2]); }
                b.clutLoad(kClutAddr, cfmt == 3 ? 32 : r.u(16, 32));
            }));
        }
        items.push_back(group([&](ListBuilder& b) {
            const u32 a[] = {r.u(0, 4), r.p(0.7), r.p(0.1)};
            b.texFunc(a[0], a[1] != 0, a[2] != 0);
            b.texEnvColor(r.bits() & 0xFFFFFF);
        }));
        items.push_back(group([&](ListBuilder& b) {
            static const u32 mins[] = {0, 1, 4, 5, 6, 7};
            const u32 a[] = {mins[r.u(0, 5)], r.u(0, 1)};
            b.texFilter(a[0], a[1]);
        }));
        items.push_back(group([&](ListBuilder& b) { const bool a[] = {r.p(0.4), r.p(0.4)}; b.texWrap(a[0], a[1]); }));
        items.push_back(group([&](ListBuilder& b) {
            if (r.p(0.8)) b.texScale(1.f, 1.f), b.texOffset(0.f, 0.f);
            else {
                const float a[] = {r.f(-2.f, 2.f), r.f(-2.f, 2.f), r.f(-1.f, 1.f), r.f(-1.f, 1.f)};
                b.texScale(a[0], a[1]), b.texOffset(a[2], a[3]);
            }
        }));
        items.push_back(group([&](ListBuilder& b) { b.enable(GE_CMD_TME, true); }));
    }

    items.push_back(group([&](ListBuilder& b) { b.shadeModel(r.p(0.7)); }));
    if (r.p(0.15)) items.push_back(group([&](ListBuilder& b) { b.enable(GE_CMD_BCE, true), b.cullMode(r.p(0.5)); }));
    if (r.p(0.4))
        items.push_back(group([&](ListBuilder& b) {
            b.enable(GE_CMD_ABE, true);
            const u32 a[] = {r.p(0.7) ? 0 : r.u(0, 5), r.u(0, 10), r.u(0, 10), r.bits() & 0xFFFFFF, r.bits() & 0xFFFFFF};
            b.blendFunc(a[0], a[1], a[2], a[3], a[4]);
        }));
    if (r.p(0.25)) items.push_back(group([&](ListBuilder& b) { const u32 a[] = {r.u(0, 7), r.u(0, 255), r.p(0.8) ? 0xFF : r.u(0, 255)}; b.enable(GE_CMD_ATE, true), b.alphaFunc(a[0], a[1], a[2]); }));
    if (r.p(0.3)) items.push_back(group([&](ListBuilder& b) { b.enable(GE_CMD_ZTE, true), b.depthFunc(r.u(0, 7)), b.depthMask(r.p(0.3)); }));
    if (r.p(0.1))
        items.push_back(group([&](ListBuilder& b) {
            b.enable(GE_CMD_STE, true);
            const u32 a[] = {r.u(0, 7), r.u(0, 255), r.p(0.7) ? 0xFF : r.u(0, 255), r.u(0, 5), r.u(0, 5), r.u(0, 5)};
            b.stencilFunc(a[0], a[1], a[2]);
            b.stencilOp(a[3], a[4], a[5]);
        }));
    if (r.p(0.08)) items.push_back(group([&](ListBuilder& b) { const u32 a[] = {r.u(0, 3), r.bits() & 0xFFFFFF, r.bits() & 0xFFFFFF}; b.enable(GE_CMD_CTE, true), b.colorFunc(a[0], a[1], a[2]); }));
    if (r.p(0.2))
        items.push_back(group([&](ListBuilder& b) {
            b.enable(GE_CMD_FGE, true);
            const float n = r.f(-1.f, 0.5f);
            const float f = n + r.f(0.05f, 2.f);
            b.fog(n, f, r.bits() & 0xFFFFFF);
        }));
    if (r.p(0.05)) items.push_back(group([&](ListBuilder& b) { b.enable(GE_CMD_LOE, true), b.logicOp(r.u(0, 15)); }));
    if (r.p(0.15))
        items.push_back(group([&](ListBuilder& b) {
            b.enable(GE_CMD_DTE, true);
            int m[16];
            for (int& v : m) v = int(r.u(0, 15)) - 8;
            b.setDither(m);
        }));
    if (r.p(0.1)) items.push_back(group([&](ListBuilder& b) { const u32 a[] = {r.p(0.5) ? 0 : r.bits() & 0xFFFFFF, r.p(0.5) ? 0 : r.u(0, 255)}; b.pixelMask(a[0], a[1]); }));
    if (r.p(0.08)) {
        cs.lighting = true;
        items.push_back(group([&](ListBuilder& b) {
            b.enable(GE_CMD_LTE, true);
            b.enable(GE_CMD_LE0, true);
            const float pos[3] = {r.f(-1, 1), r.f(-1, 1), r.f(0.2f, 1)};
            const u32 a[] = {r.u(0, 1), r.u(0, 2)};
            b.light(0, a[0], a[1], pos);
            b.lightColor(0, LIGHT_AMBIENT | LIGHT_DIFFUSE | LIGHT_SPECULAR, r.bits() & 0xFFFFFF);
            b.lightAtt(0, 1.f, 0.f, 0.f);
            b.ambient(r.color());
            b.materialAmbient(r.color());
            b.materialDiffuse(r.bits() & 0xFFFFFF);
            b.materialSpecular(r.bits() & 0xFFFFFF);
            b.specularPower(r.f(1.f, 16.f));
            b.colorMaterial(r.u(0, 7));
            b.lightMode(r.p(0.3));
        }));
    }
    if (r.p(0.08)) items.push_back(group([&](ListBuilder& b) { b.cmd(GE_CMD_CMODE, (r.u(0, 7) << 8) | 1); }));

    const u32 draws = r.u(1, 4);
    for (u32 i = 0; i < draws; ++i) {
        if (i && r.p(0.3)) items.push_back(makeToggle(r));
        FuzzItem d = makeDraw(r, cs, items);
        items.push_back(std::move(d));
    }
    return c;
}

dump::Dump recordFuzzCase(const FuzzCase& c) {
    Memory mem{16u << 20};
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    GeState init;
    init.reset();
    for (int op = 0; op < 256; ++op) init.regs[op] = u32(op) << 24;
    rec.begin(init, Memory::kVramBase, 512, c.fbFormat);
    ListBuilder b(&mem);
    for (const auto& [addr, bytes] : c.data) b.upload(addr, bytes.data(), u32(bytes.size()));
    b.attach(&rec);
    b.drawBuffer(c.fbFormat, 0, 512);
    b.depthBuffer(kDepthOffset, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.viewport(2048, 2048, 480, 272);
    b.offset(2048 - 240, 2048 - 136);
    b.depthRange(65535, 0);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, c.clearColor, u16(c.clearDepth), u8(c.clearColor >> 24));
    for (const auto& it : c.items) {
        if (!it.draw) {
            for (u32 wd : it.words) b.raw(wd);
            continue;
        }
        b.drawArrayData(it.prim, it.vtype, it.count, it.indices.empty() ? nullptr : it.indices.data(), it.vertices.data());
    }
    b.finish();
    rec.end(Memory::kVramBase, 512, c.fbFormat);
    return w.dump();
}

// Backends and memories kept between renders of one side (renderDump's `reuse` / `held`).
struct FuzzSides {
    Memory mem[2];
    backend::Backend backends[2];
    std::vector<u8> vram[2];
    std::vector<u16> depth[2];
};

namespace {

// A side's name in causes: its backend, and its profile when the two sides' differ.
std::string sideName(const FuzzOptions& o, int side) {
    const std::string& acc = side == 1 && !o.refAccuracy.empty() ? o.refAccuracy : o.render.accuracy;
    const bool differ = !o.refAccuracy.empty() && o.refAccuracy != o.render.accuracy;
    return (side == 0 ? o.backend : o.refBackend) + (differ ? "/" + acc : std::string());
}

RenderOptions sideOptions(const FuzzOptions& o, int side) {
    RenderOptions ro = o.render;
    ro.backend = side == 0 ? o.backend : o.refBackend;
    if (side == 1 && !o.refAccuracy.empty()) ro.accuracy = o.refAccuracy;
    ro.scale = 1;
    ro.replayEnd = 0;
    ro.keepDraw = side == 1 ? o.refKeepDraw : nullptr;
    return ro;
}

std::string hex(u32 v, int digits) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
    return buf;
}

}  // namespace

bool fuzzCompare(const dump::Dump& d, const FuzzOptions& o, FuzzSides* sides, bool& differs, std::string& cause,
                 std::string& err) {
    std::optional<FuzzSides> local;
    FuzzSides& s = sides ? *sides : local.emplace();
    RenderOutput out[2];
    for (int side = 0; side < 2; ++side) {
        if (!renderDump(d, sideOptions(o, side), out[side], err, &s.vram[side], o.compareDepth ? &s.depth[side] : nullptr,
                        sides ? &s.mem[side] : nullptr, sides ? &s.backends[side] : nullptr)) {
            err = (side == 0 ? o.backend : o.refBackend) + ": " + err;
            if (sides) s.backends[side] = {};  // start the next case afresh
            return false;
        }
    }
    differs = false;
    cause.clear();
    const u32 fmt = out[1].displayFormat & 3, stride = out[1].displayStride ? out[1].displayStride : 512;
    const u32 bpp = fmt == GE_FORMAT_8888 ? 4 : 2;
    const u32 base = (out[1].displayAddr & 0x1FFFFF);
    const u32 mask = !o.rgbOnly ? 0xFFFFFFFFu
                   : fmt == GE_FORMAT_8888 ? 0x00FFFFFFu
                   : fmt == GE_FORMAT_5551 ? 0x7FFFu
                   : fmt == GE_FORMAT_4444 ? 0x0FFFu
                                           : 0xFFFFu;
    u64 n = 0;
    int fx = -1, fy = -1;
    u32 fa = 0, fb = 0;
    for (u32 y = 0; y < 272; ++y)
        for (u32 x = 0; x < 480; ++x) {
            const size_t off = base + size_t(y * stride + x) * bpp;
            if (off + bpp > Memory::kVramSize) continue;
            u32 a = 0, b = 0;
            std::memcpy(&a, &s.vram[0][off], bpp);
            std::memcpy(&b, &s.vram[1][off], bpp);
            if (((a ^ b) & mask) == 0) continue;
            if (!n++) fx = int(x), fy = int(y), fa = a, fb = b;
        }
    double mse = -1;
    if (n && o.maxMse >= 0) {
        mse = mseRGB(out[0].frame, out[1].frame);
        if (mse <= o.maxMse) n = 0;  // within the pair's tolerance
    }
    if (n) {
        const bool rgb = fmt == GE_FORMAT_565 || ((fa ^ fb) & (fmt == GE_FORMAT_8888 ? 0x00FFFFFFu : fmt == GE_FORMAT_5551 ? 0x7FFFu : 0x0FFFu));
        cause = "colour (" + std::string(bufferFormatName(fmt)) + (rgb ? ", RGB" : ", alpha/stencil only") + ") at (" +
                std::to_string(fx) + "," + std::to_string(fy) + "): " + sideName(o, 0) + " " + hex(fa, bpp * 2) +
                " vs " + sideName(o, 1) + " " + hex(fb, bpp * 2) + ", " + std::to_string(n) + " pixels differ";
        if (mse >= 0) {
            char buf[64];
            std::snprintf(buf, sizeof buf, ", MSE %.4f > %.4f", mse, o.maxMse);
            cause += buf;
        }
        differs = true;
        return true;
    }
    if (o.compareDepth) {
        for (u32 i = 0; i < 480 * 272; ++i)
            if (s.depth[0][i] != s.depth[1][i]) {
                if (!n++) fx = int(i % 480), fy = int(i / 480), fa = s.depth[0][i], fb = s.depth[1][i];
            }
        if (n) {
            cause = "depth at (" + std::to_string(fx) + "," + std::to_string(fy) + "): " + sideName(o, 0) + " " +
                    std::to_string(fa) + " vs " + sideName(o, 1) + " " + std::to_string(fb) + ", " + std::to_string(n) +
                    " pixels differ";
            differs = true;
        }
    }
    return true;
}

namespace {

// Shrinks `c` while it still differs: drops items (state groups and draws), then words inside
// groups, then vertices of draws. At most `tries` candidate renders.
FuzzCase minimise(const FuzzCase& start, const FuzzOptions& o, FuzzSides& sides) {
    FuzzCase best = start;
    int tries = o.minimiseTries;
    auto fails = [&](const FuzzCase& cand) {
        if (tries <= 0) return false;
        --tries;
        bool differs = false;
        std::string cause, err;
        return fuzzCompare(recordFuzzCase(cand), o, &sides, differs, cause, err) && differs;
    };
    bool progress = true;
    while (progress && tries > 0) {
        progress = false;
        // Whole items, last first (later state depends on earlier less often than the reverse).
        for (size_t i = best.items.size(); i-- > 0 && tries > 0;) {
            if (i >= best.items.size()) continue;
            FuzzCase cand = best;
            cand.items.erase(cand.items.begin() + long(i));
            if (fails(cand)) best = std::move(cand), progress = true;
        }
        // Words inside groups.
        for (size_t i = 0; i < best.items.size() && tries > 0; ++i) {
            if (best.items[i].draw) continue;
            for (size_t k = best.items[i].words.size(); k-- > 0 && tries > 0;) {
                if (best.items[i].words.size() <= 1 || k >= best.items[i].words.size()) continue;
                FuzzCase cand = best;
                cand.items[i].words.erase(cand.items[i].words.begin() + long(k));
                if (fails(cand)) best = std::move(cand), progress = true;
            }
        }
        // Vertices: the smallest valid count first, then one primitive less.
        for (size_t i = 0; i < best.items.size() && tries > 0; ++i) {
            FuzzItem& it = best.items[i];
            if (!it.draw) continue;
            const u32 mn = primMin(it.prim), step = primStep(it.prim);
            if (it.count <= mn) continue;
            for (u32 target : {mn, it.count - step}) {
                if (target >= best.items[i].count || target < mn) continue;
                FuzzCase cand = best;
                FuzzItem& ci = cand.items[i];
                ci.count = target;
                if (!ci.indices.empty()) ci.indices.resize(size_t(ci.count) * ((((ci.vtype >> 11) & 3) == 2) ? 2 : 1));
                if (fails(cand)) {
                    best = std::move(cand), progress = true;
                    break;
                }
            }
        }
        // Unused data (a texture or CLUT no remaining group points at still costs bytes).
        for (size_t i = best.data.size(); i-- > 0 && tries > 0;) {
            FuzzCase cand = best;
            cand.data.erase(cand.data.begin() + long(i));
            if (fails(cand)) best = std::move(cand), progress = true;
        }
    }
    return best;
}

// Owning draw of pixel (x, y) on the first side with its state summary (ge2gl blame's replay).
std::string ownerText(const dump::Dump& d, const FuzzOptions& o, int x, int y) {
    BlameOptions bo;
    bo.refBackend = o.refBackend;
    bo.top = 1000;
    BlameResult br;
    std::string err;
    RenderOptions ro = sideOptions(o, 0);
    if (o.refKeepDraw) return {};  // the reference side is not a plain render of the dump
    if (!blameDump(d, ro, bo, br, err) || br.owner.size() != 480 * 272) return {};
    const u32 draw = br.owner[size_t(y) * 480 + size_t(x)];
    if (draw == 0) return "; owner: no draw (clear/initial VRAM)";
    for (const auto& ow : br.owners)
        if (ow.info.draw == draw) return "; owner: draw " + std::to_string(draw) + " (" + drawDescription(ow.info) + "): " + ow.info.state;
    return "; owner: draw " + std::to_string(draw);
}

size_t dumpBytes(const dump::Dump& d) { return d.pushbuf.size(); }

}  // namespace

bool runFuzz(const FuzzOptions& o, FuzzSummary& out, std::string& err) {
    out = {};
    if (!o.outDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.outDir, ec);
        if (ec) return err = "cannot create " + o.outDir + ": " + ec.message(), false;
    }
    auto sides = std::make_unique<FuzzSides>();
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    for (u64 i = 0; i < o.count; ++i) {
        const u64 seed = o.seed + i;
        const FuzzCase c = generateFuzzCase(seed);
        const dump::Dump d = recordFuzzCase(c);
        bool differs = false;
        std::string cause, e;
        ++out.cases;
        if (!fuzzCompare(d, o, sides.get(), differs, cause, e)) {
            ++out.errors;
            out.errorMessages.push_back("seed " + std::to_string(seed) + ": " + e);
            if (!o.quiet) std::fprintf(stderr, "seed %llu: error: %s\n", (unsigned long long)seed, e.c_str());
            continue;
        }
        if (differs) {
            ++out.divergences;
            FuzzFailure f;
            f.seed = seed;
            f.weightBefore = c.weight();
            f.bytesBefore = dumpBytes(d);
            FuzzCase m = minimise(c, o, *sides);
            f.minimised = recordFuzzCase(m);
            // The cause is that of the minimised case, on fresh backends (no state from earlier cases).
            bool still = false;
            std::string mc, me;
            if (fuzzCompare(f.minimised, o, nullptr, still, mc, me) && still) {
                f.cause = mc;
                f.weightAfter = m.weight();
            } else {  // not reproducible from scratch: keep the whole case
                f.minimised = d;
                f.weightAfter = f.weightBefore;
                f.cause = cause + " (minimised case did not reproduce on fresh backends)";
            }
            f.bytesAfter = dumpBytes(f.minimised);
            int x = -1, y = -1;
            if (std::sscanf(f.cause.c_str() + std::min(f.cause.find(" at ("), f.cause.size()), " at (%d,%d)", &x, &y) == 2 &&
                f.cause.rfind("colour", 0) == 0)
                f.cause += ownerText(f.minimised, o, x, y);
            if (!o.outDir.empty()) {
                f.path = (std::filesystem::path(o.outDir) / ("case-" + std::to_string(seed) + ".ppdmp")).string();
                std::string se;
                if (!dump::saveDump(f.path, f.minimised, se)) {
                    ++out.errors;
                    out.errorMessages.push_back("seed " + std::to_string(seed) + ": " + se);
                    f.path.clear();
                }
            }
            if (!o.quiet)
                std::printf("seed %llu: DIVERGES (%zu -> %zu items+vertices): %s%s%s\n", (unsigned long long)seed,
                            f.weightBefore, f.weightAfter, f.cause.c_str(), f.path.empty() ? "" : " -> ",
                            f.path.c_str());
            out.failures.push_back(std::move(f));
            // Minimisation rendered on the reused backends in between: fine, every render starts
            // from cleared memory.
        }
        const auto now = std::chrono::steady_clock::now();
        if (!o.quiet && std::chrono::duration<double>(now - last).count() > 5.0) {
            last = now;
            const double s = std::chrono::duration<double>(now - t0).count();
            std::printf("%llu/%llu cases, %llu divergences, %.1f cases/s\n", (unsigned long long)(i + 1),
                        (unsigned long long)o.count, (unsigned long long)out.divergences, double(i + 1) / s);
            std::fflush(stdout);
        }
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

int runFuzzCommand(const FuzzOptions& o) {
    FuzzSummary s;
    std::string err;
    if (!runFuzz(o, s, err)) {
        std::fprintf(stderr, "ge2gl: fuzz: %s\n", err.c_str());
        return 2;
    }
    const double rate = s.seconds > 0 ? double(s.cases) / s.seconds : 0;
    std::printf("fuzz %s vs %s, seeds %llu-%llu: %llu cases, %llu divergences, %llu errors, %.2f s, %.1f cases/s\n",
                sideName(o, 0).c_str(), sideName(o, 1).c_str(), (unsigned long long)o.seed,
                (unsigned long long)(o.seed + (o.count ? o.count - 1 : 0)), (unsigned long long)s.cases,
                (unsigned long long)s.divergences, (unsigned long long)s.errors, s.seconds, rate);
    if (!o.jsonPath.empty()) {
        Json j;
        j["backend"] = o.backend;
        j["refBackend"] = o.refBackend;
        j["accuracy"] = o.render.accuracy;
        j["refAccuracy"] = o.refAccuracy.empty() ? o.render.accuracy : o.refAccuracy;
        j["seed"] = o.seed;
        j["cases"] = s.cases;
        j["divergences"] = s.divergences;
        j["errors"] = s.errors;
        // Times with 6 significant digits, as this file has always had them.
        j["seconds"] = number6Value(s.seconds);
        j["casesPerSecond"] = number6Value(rate);
        Json& seeds = j["failingSeeds"] = Json::array();
        for (const auto& f : s.failures) seeds.push_back(f.seed);
        Json& failures = j["failures"] = Json::array();
        for (const auto& f : s.failures) {
            Json e;
            e["seed"] = f.seed;
            e["cause"] = f.cause;
            e["path"] = f.path;
            e["weightBefore"] = f.weightBefore;
            e["weightAfter"] = f.weightAfter;
            e["bytesBefore"] = f.bytesBefore;
            e["bytesAfter"] = f.bytesAfter;
            failures.push_back(std::move(e));
        }
        j["errorMessages"] = s.errorMessages;
        JsonLayout layout;
        layout.rowArrays = {"failures"};
        std::ofstream f(o.jsonPath);
        f << jsonDocument(j, layout);
        if (!f) {
            std::fprintf(stderr, "ge2gl: fuzz: cannot write %s\n", o.jsonPath.c_str());
            return 2;
        }
    }
    if (s.errors) return 2;
    return s.divergences ? 1 : 0;
}

}  // namespace ge::tools
