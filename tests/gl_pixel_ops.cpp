// SPDX-License-Identifier: MIT
// GL translator: the GE pixel pipeline in the fragment shader, checked byte-exactly against the
// fixed-point formulas of docs/ge-rules.md §8.3, §8.7, §8.8 — in both the extension path
// (framebuffer fetch) and `baseline` (destination copies).
#include <algorithm>
#include <vector>

#include "hle/pixel_format.h"
#include "tests/gl_fixture.h"

namespace ge::gltest {
namespace {

using GlPixel = GlScene;

u32 rgba(u32 r, u32 g, u32 b, u32 a) { return r | g << 8 | b << 16 | a << 24; }
u32 ch(u32 c, int i) { return (c >> (8 * i)) & 0xFF; }

// Places an 8×8 8888 texture of one colour in RAM and selects it (REPLACE etc. set by caller).
u32 solidTexture(ListBuilder& b, u32 color) {
    std::vector<u32> t(64, color);
    const u32 addr = b.place(t.data(), 64 * 4);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, addr, 8, 8, 8);
    b.texFilter(0, 0);
    b.texWrap(false, false);
    return addr;
}

// ---- texture functions (ge-rules.md §8.3) ----
TEST_P(GlPixel, TextureFunctionsMatchFixedPointFormulas) {
    const u32 P = rgba(0x10, 0x80, 0xFF, 0x60);
    const u32 T = rgba(0x20, 0x40, 0xC0, 0x80);
    const u32 TEC = rgba(0xC0, 0xB0, 0xA0, 0);
    struct Case {
        u32 func;
        bool tcc, dbl;
    };
    std::vector<Case> cases;
    for (u32 f = 0; f <= 4; ++f)
        for (int tcc = 0; tcc < 2; ++tcc)
            for (int dbl = 0; dbl < 2; ++dbl) cases.push_back({f, tcc != 0, dbl != 0});
    auto expected = [&](const Case& c, u32& outA) {
        u32 out = 0;
        for (int i = 0; i < 3; ++i) {
            const int p = int(ch(P, i)), t = int(ch(T, i)), at = int(ch(T, 3)), e = int(ch(TEC, i));
            int v = 0;
            switch (c.func) {
                case 0: v = ((p + 1) * t * (c.dbl ? 2 : 1)) >> 8; break;
                case 1: v = c.tcc ? ((p + 1) * (255 - at) + (t + 1) * at) >> (c.dbl ? 7 : 8) : t * (c.dbl ? 2 : 1); break;
                case 2: v = ((255 - t) * p + t * e + 255) >> (c.dbl ? 7 : 8); break;
                case 3: v = t * (c.dbl ? 2 : 1); break;
                default: v = (p + t) * (c.dbl ? 2 : 1); break;
            }
            out |= u32(std::clamp(v, 0, 255)) << (8 * i);
        }
        const int pa = int(ch(P, 3)), ta = int(ch(T, 3));
        const int modA = c.tcc ? ((pa + 1) * ta) >> 8 : pa;
        outA = u32(c.func == 1 ? pa : c.func == 3 ? (c.tcc ? ta : pa) : modA);
        return out;
    };
    // Spot checks computed by hand: MODULATE red (0x10+1)·0x20 >> 8 = 2; BLEND green
    // ((255−0x40)·0x80 + 0x40·0xB0 + 255) >> 8 = (24448 + 11264 + 255) >> 8 = 140.
    u32 a;
    EXPECT_EQ(ch(expected({0, false, false}, a), 0), 2u);
    EXPECT_EQ(ch(expected({2, false, false}, a), 1), 140u);

    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00000000, 0, 0);
    solidTexture(*b, T);
    b->texEnvColor(TEC);
    b->enable(GE_CMD_TME, true);
    b->enable(GE_CMD_ATE, true);
    for (size_t i = 0; i < cases.size(); ++i) {
        u32 ea;
        expected(cases[i], ea);
        b->texFunc(cases[i].func, cases[i].tcc, cases[i].dbl);
        // The alpha result is checked through an EQUAL alpha test: a wrong alpha leaves black.
        b->alphaFunc(2, ea, 0xFF);
        const float x = float((i % 8) * 8), y = float((i / 8) * 8);
        rect(x, y, x + 8, y + 8, P, 0, 0, 8, 8);
    }
    run();
    for (size_t i = 0; i < cases.size(); ++i) {
        u32 ea;
        const u32 e = expected(cases[i], ea);
        const int x = int(i % 8) * 8 + 3, y = int(i / 8) * 8 + 3;
        EXPECT_EQ(px32(x, y) & 0xFFFFFF, e) << "func " << cases[i].func << " tcc " << cases[i].tcc << " dbl "
                                            << cases[i].dbl;
    }
}

// ---- blending (ge-rules.md §3.10 factors, §8.3 arithmetic) ----
TEST_P(GlPixel, BlendEquationsAndFactorsAreExact) {
    const u32 Cd = rgba(0x40, 0x80, 0xC0, 0x90);  // Ad = 0x90 (stencil byte)
    const u32 Cs = rgba(0xE0, 0x60, 0x20, 0xA0);  // As = 0xA0
    const u32 FIXA = rgba(0x11, 0x22, 0x33, 0), FIXB = rgba(0x80, 0x40, 0xFF, 0);
    auto term = [](int c, int f) { return ((2 * c + 1) * (2 * f + 1)) >> 10; };
    auto factor = [&](u32 code, bool isA, int i) {
        const int as = 0xA0, ad = 0x90;
        const int other = int(isA ? ch(Cd, i) : ch(Cs, i));
        switch (code) {
            case 0: return other;
            case 1: return 255 - other;
            case 2: return as;
            case 3: return 255 - as;
            case 4: return ad;
            case 5: return 255 - ad;
            case 6: return 2 * as;
            case 7: return std::max(255 - 2 * as, 0);
            case 8: return 2 * ad;
            case 9: return std::max(255 - 2 * ad, 0);
            default: return int(ch(isA ? FIXA : FIXB, i));
        }
    };
    struct Case {
        u32 eq, a, b;
    };
    std::vector<Case> cases;
    for (u32 f = 0; f <= 10; ++f) cases.push_back({0, f, 10 - f});  // ADD over every factor code
    cases.push_back({1, 2, 3});
    cases.push_back({1, 10, 10});
    cases.push_back({2, 2, 3});
    cases.push_back({2, 6, 8});
    cases.push_back({3, 0, 0});
    cases.push_back({4, 0, 0});
    cases.push_back({5, 0, 0});
    auto expected = [&](const Case& c) {
        u32 out = 0;
        for (int i = 0; i < 3; ++i) {
            const int s = int(ch(Cs, i)), d = int(ch(Cd, i));
            const int ts = term(s, factor(c.a, true, i)), td = term(d, factor(c.b, false, i));
            int v = 0;
            switch (c.eq) {
                case 0: v = ts + td; break;
                case 1: v = std::max(ts - td, 0); break;
                case 2: v = std::max(td - ts, 0); break;
                case 3: v = std::min(s, d); break;
                case 4: v = std::max(s, d); break;
                default: v = std::abs(s - d); break;
            }
            out |= u32(std::clamp(v, 0, 255)) << (8 * i);
        }
        return out | (Cd & 0xFF000000);  // blending never writes alpha (ge-rules.md §8.7)
    };
    // Hand check: ADD with A = As (0xA0), B = 1−As on red: ((2·0xE0+1)(2·0xA0+1))>>10 = 449·321>>10
    // = 140; ((2·0x40+1)(2·0x5F+1))>>10 = 129·191>>10 = 24; sum 164.
    EXPECT_EQ(ch(expected({0, 2, 3}), 0), 164u);

    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, Cd & 0xFFFFFF, 0, u8(Cd >> 24));
    b->enable(GE_CMD_ABE, true);
    for (size_t i = 0; i < cases.size(); ++i) {
        b->blendFunc(cases[i].eq, cases[i].a, cases[i].b, FIXA, FIXB);
        const float x = float((i % 8) * 8), y = float((i / 8) * 8);
        rect(x, y, x + 8, y + 8, Cs);
    }
    run();
    for (size_t i = 0; i < cases.size(); ++i) {
        const int x = int(i % 8) * 8 + 4, y = int(i / 8) * 8 + 4;
        EXPECT_EQ(px32(x, y), expected(cases[i])) << "eq " << cases[i].eq << " a " << cases[i].a << " b " << cases[i].b;
    }
}

TEST_P(GlPixel, OverlappingBlendedPrimitivesInOneDrawAccumulate) {
    // Three overlapping additive rectangles in a single PRIM: each must read the previous one's
    // result (tests destination reads between overlapping primitives of one batch).
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->enable(GE_CMD_ABE, true);
    b->blendFunc(0, 10, 10, rgba(0xFF, 0xFF, 0xFF, 0), rgba(0xFF, 0xFF, 0xFF, 0));  // Cs·1 + Cd·1
    BuildVertex v[6];
    for (int i = 0; i < 3; ++i) {
        v[2 * i].x = float(4 * i), v[2 * i].y = 0, v[2 * i].color = rgba(0x20, 0x10, 0x01, 0xFF);
        v[2 * i + 1].x = float(4 * i + 20), v[2 * i + 1].y = 8, v[2 * i + 1].color = rgba(0x20, 0x10, 0x01, 0xFF);
    }
    const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    const std::vector<u8> data = packVertices(vtype, v, 6);
    b->drawArrayData(GE_PRIM_RECTANGLES, vtype, 6, nullptr, data.data());
    run();
    // term(0x20, 255) = (65·511)>>10 = 32; the fixed factor 255 gives C·511/1024 ≈ C.
    auto t = [](int c) { return ((2 * c + 1) * 511) >> 10; };
    const int r1 = t(0x20), r2 = t(0x20) + t(r1), r3 = t(0x20) + t(r2);
    EXPECT_EQ(ch(px32(2, 2), 0), u32(r1));
    EXPECT_EQ(ch(px32(6, 2), 0), u32(r2));
    EXPECT_EQ(ch(px32(10, 2), 0), u32(r3));
    EXPECT_EQ(ch(px32(22, 2), 0), u32(r2));
}

// ---- stencil (ge-rules.md §8.7) ----
TEST_P(GlPixel, StencilOpsPerFormat) {
    struct Case {
        u32 fmt, clearStencil, func, ref, sfail, zpass;
        u32 expectAlphaBits;  // stored alpha/stencil bits in the format
        bool colorWritten;
    };
    // 8888: INCR 5→6, DECR 5→4, REPLACE →0x33, INVERT 5→0xFA, ZERO; NEVER + sfail REPLACE keeps colour.
    const std::vector<Case> cases = {
        {GE_FORMAT_8888, 5, 1, 0x33, 0, 4, 6, true},
        {GE_FORMAT_8888, 5, 1, 0x33, 0, 5, 4, true},
        {GE_FORMAT_8888, 5, 1, 0x33, 0, 2, 0x33, true},
        {GE_FORMAT_8888, 5, 1, 0x33, 0, 3, 0xFA, true},
        {GE_FORMAT_8888, 5, 1, 0x33, 0, 1, 0, true},
        {GE_FORMAT_8888, 5, 0, 0x33, 2, 0, 0x33, false},
        {GE_FORMAT_8888, 0xFF, 1, 0, 0, 4, 0xFF, true},       // INCR saturates
        {GE_FORMAT_8888, 5, 4, 3, 1, 2, 3, true},             // LESS: (3 & m) < (5 & m) passes (ge-rules.md §8.7 order)
        {GE_FORMAT_8888, 5, 4, 7, 1, 2, 0, false},            // LESS fails → sfail ZERO
    };
    for (const Case& c : cases) {
        setupFrame(c.fmt);
        b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x000000, 0, u8(c.clearStencil));
        b->enable(GE_CMD_STE, true);
        b->stencilFunc(c.func, c.ref, 0xFF);
        b->stencilOp(c.sfail, 0, c.zpass);
        rect(0, 0, 8, 8, rgba(0x10, 0x20, 0x30, 0x99));
        b->enable(GE_CMD_STE, false);
        run();
        const u32 p = px32(2, 2);
        EXPECT_EQ(p >> 24, c.expectAlphaBits) << "zpass " << c.zpass << " func " << c.func;
        EXPECT_EQ(p & 0xFFFFFF, c.colorWritten ? 0x302010u : 0u) << "zpass " << c.zpass << " func " << c.func;
    }
}

TEST_P(GlPixel, Stencil4444And5551) {
    setupFrame(GE_FORMAT_4444);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0x50);  // stored nibble 5
    b->enable(GE_CMD_STE, true);
    b->stencilFunc(1, 0, 0xFF);
    b->stencilOp(0, 0, 4);  // INCR: +0x10 → nibble 6
    rect(0, 0, 4, 4, rgba(0xFF, 0, 0, 0));
    b->stencilOp(0, 0, 5);  // DECR: −0x10 → nibble 4
    rect(4, 0, 8, 4, rgba(0xFF, 0, 0, 0));
    b->enable(GE_CMD_STE, false);
    run();
    EXPECT_EQ(px16(1, 1), u16(0xF | 0x6000));
    EXPECT_EQ(px16(5, 1), u16(0xF | 0x4000));
    setupFrame(GE_FORMAT_5551);
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->enable(GE_CMD_STE, true);
    b->stencilFunc(1, 0, 0xFF);
    b->stencilOp(0, 0, 4);  // INCR on 5551 → 255 → bit 15 set
    rect(0, 0, 4, 4, rgba(0, 0, 0, 0));
    b->enable(GE_CMD_STE, false);
    run();
    EXPECT_EQ(px16(1, 1), u16(0x8000));
}

TEST_P(GlPixel, StencilWithDepthFailUsesZFailOp) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0, 1000, 5);
    b->enable(GE_CMD_ZTE, true);
    b->depthFunc(6);  // GREATER: z 500 fails against 1000
    b->enable(GE_CMD_STE, true);
    b->stencilFunc(1, 0x40, 0xFF);
    b->stencilOp(0, 2, 1);  // zfail REPLACE, zpass ZERO
    rect(0, 0, 8, 8, rgba(0xFF, 0xFF, 0xFF, 0), 0, 0, 0, 0, 500);
    rect(8, 0, 16, 8, rgba(0xFF, 0xFF, 0xFF, 0), 0, 0, 0, 0, 2000);  // passes → ZERO, colour, depth
    b->enable(GE_CMD_STE, false);
    b->enable(GE_CMD_ZTE, false);
    run();
    EXPECT_EQ(px32(2, 2), 0x40000000u);
    EXPECT_EQ(depth(2, 2), 1000);
    EXPECT_EQ(px32(10, 2), 0x00FFFFFFu);
    EXPECT_EQ(depth(10, 2), 2000);
}

// ---- depth test (fixed-function path) ----
TEST_P(GlPixel, DepthTestAndWriteMask) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0, 3000, 0);
    b->enable(GE_CMD_ZTE, true);
    b->depthFunc(7);  // GEQUAL
    rect(0, 0, 8, 8, 0xFF0000FF, 0, 0, 0, 0, 3000);   // equal → passes, writes
    rect(8, 0, 16, 8, 0xFF0000FF, 0, 0, 0, 0, 2999);  // fails
    b->depthMask(true);
    rect(16, 0, 24, 8, 0xFF00FF00, 0, 0, 0, 0, 4000);  // passes, no depth write
    b->depthMask(false);
    b->enable(GE_CMD_ZTE, false);
    run();
    EXPECT_EQ(px32(1, 1), 0x000000FFu);
    EXPECT_EQ(px32(9, 1), 0u);
    EXPECT_EQ(px32(17, 1), 0x0000FF00u);
    EXPECT_EQ(depth(1, 1), 3000);
    EXPECT_EQ(depth(17, 1), 3000);
}

// ---- logic ops (ge-rules.md §3.10) ----
TEST_P(GlPixel, LogicOps) {
    const u32 d = 0x0055AA0F, s = 0x003C3CF0;
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, d, 0, 0x12);
    b->enable(GE_CMD_LOE, true);
    for (u32 op = 0; op < 16; ++op) {
        b->logicOp(op);
        rect(float(op * 4), 0, float(op * 4 + 4), 4, s | 0xFF000000);
    }
    b->enable(GE_CMD_LOE, false);
    run();
    for (u32 op = 0; op < 16; ++op) {
        u32 e = 0;
        switch (op) {
            case 0: e = 0; break;
            case 1: e = s & d; break;
            case 2: e = s & ~d; break;
            case 3: e = s; break;
            case 4: e = ~s & d; break;
            case 5: e = d; break;
            case 6: e = s ^ d; break;
            case 7: e = s | d; break;
            case 8: e = ~(s | d); break;
            case 9: e = ~(s ^ d); break;
            case 10: e = ~d; break;
            case 11: e = s | ~d; break;
            case 12: e = ~s; break;
            case 13: e = ~s | d; break;
            case 14: e = ~(s & d); break;
            default: e = 0xFFFFFF; break;
        }
        EXPECT_EQ(px32(int(op * 4) + 1, 1), (e & 0xFFFFFF) | 0x12000000u) << "op " << op;
    }
}

// ---- alpha and colour tests ----
TEST_P(GlPixel, AlphaAndColorTests) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    b->enable(GE_CMD_ATE, true);
    b->alphaFunc(6, 0x7F);  // GREATER 0x7F: alpha 0x80 passes
    rect(0, 0, 4, 4, 0x80FFFFFF);
    b->alphaFunc(6, 0x80);  // fails
    rect(4, 0, 8, 4, 0x80FFFFFF);
    b->alphaFunc(2, 0x00, 0x0F);  // (0x80 & 0x0F) == (0 & 0x0F): passes
    rect(8, 0, 12, 4, 0x80FFFFFF);
    b->enable(GE_CMD_ATE, false);
    b->enable(GE_CMD_CTE, true);
    b->colorFunc(2, 0x000011, 0x0000FF);  // EQUAL on red only
    rect(12, 0, 16, 4, 0xFF123411);
    rect(16, 0, 20, 4, 0xFF123412);
    b->colorFunc(3, 0x000011, 0x0000FF);  // NOTEQUAL
    rect(20, 0, 24, 4, 0xFF123411);
    b->enable(GE_CMD_CTE, false);
    run();
    EXPECT_EQ(px32(1, 1), 0x00FFFFFFu);
    EXPECT_EQ(px32(5, 1), 0u);
    EXPECT_EQ(px32(9, 1), 0x00FFFFFFu);
    EXPECT_EQ(px32(13, 1), 0x00123411u);
    EXPECT_EQ(px32(17, 1), 0u);
    EXPECT_EQ(px32(21, 1), 0u);
}

// ---- dithering (ge-rules.md §3.10, §8.8) ----
TEST_P(GlPixel, DitherMatrixBeforeTruncation) {
    const int m[16] = {-8, 0, 7, -1, 3, -4, 1, 6, 2, -2, -3, 4, 5, -5, -6, -7};
    setupFrame(GE_FORMAT_565);
    b->clear(CLEAR_COLOR, 0, 0, 0);
    b->setDither(m);
    b->enable(GE_CMD_DTE, true);
    rect(0, 0, 8, 8, rgba(0x87, 0x42, 0xFE, 0xFF));
    b->enable(GE_CMD_DTE, false);
    run();
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const int d = m[(y & 3) * 4 + (x & 3)];
            const u32 r = u32(std::clamp(0x87 + d, 0, 255)) >> 3, g = u32(std::clamp(0x42 + d, 0, 255)) >> 2,
                      bl = u32(std::clamp(0xFE + d, 0, 255)) >> 3;
            EXPECT_EQ(px16(x, y), u16(r | g << 5 | bl << 11)) << x << "," << y;
        }
}

// ---- write masks (ge-rules.md §8.8) ----
TEST_P(GlPixel, PixelMasksProtectBits) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0x00A5A5A5, 0, 0x5A);
    b->pixelMask(0x00FF0F, 0x00);  // keep low nibble of R... no: keep bits 0x0F of R and all of G
    rect(0, 0, 4, 4, 0xFF000000 | 0x00123456);
    b->pixelMask(0x0000FF, 0x00);  // whole R protected (fixed-function colour mask)
    rect(4, 0, 8, 4, 0xFF000000 | 0x00123456);
    b->pixelMask(0, 0);
    run();
    // R: new 0x56, keep mask 0x0F → (0x56 & 0xF0) | (0xA5 & 0x0F) = 0x55; G kept 0xA5; B new 0x12.
    EXPECT_EQ(px32(1, 1), 0x5A12A555u);
    EXPECT_EQ(px32(5, 1), 0x5A1234A5u);
}

// ---- fog (ge-rules.md §3.9, §8.3) in transform mode ----
TEST_P(GlPixel, FogBlendsTowardFogColor) {
    setupFrame();
    b->clear(CLEAR_COLOR | CLEAR_STENCIL, 0, 0, 0);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    b->setMatrix(GeMatrix::World, id);
    b->setMatrix(GeMatrix::View, id);
    b->setMatrix(GeMatrix::Proj, id);
    // f = (Zview + FOG1)·FOG2 = (0 + 0.5)·1 → floor(0.5·256) = 128.
    b->cmdf(GE_CMD_FOG1, 0.5f);
    b->cmdf(GE_CMD_FOG2, 1.0f);
    b->cmd(GE_CMD_FC, rgba(50, 0, 255, 0));
    b->enable(GE_CMD_FGE, true);
    BuildVertex v[2];
    v[0].x = -1, v[0].y = 1, v[0].z = 0, v[0].color = rgba(200, 100, 0, 255);
    v[1].x = 1, v[1].y = -1, v[1].z = 0, v[1].color = rgba(200, 100, 0, 255);
    const u32 vtype = vt::COL_8888 | vt::POS_F;
    const std::vector<u8> data = packVertices(vtype, v, 2);
    b->drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
    b->enable(GE_CMD_FGE, false);
    run();
    // (C·f + FC·(255 − f) + 255) >> 8: R (200·128 + 50·127 + 255) >> 8 = 125,
    // G (100·128 + 0 + 255) >> 8 = 13055 >> 8 = 50, B (0 + 255·127 + 255) >> 8 = 127.
    EXPECT_EQ(px32(10, 10), rgba(125, 50, 127, 0));
    EXPECT_EQ(px32(63, 63), rgba(125, 50, 127, 0));
}

INSTANTIATE_TEST_SUITE_P(Paths, GlPixel, GE2GL_GL_PATHS);

}  // namespace
}  // namespace ge::gltest
