// SPDX-License-Identifier: MIT
// The GL hardware mode (GlMode::Hw): native GL rasterisation at render scale N, VRAM write-back
// box-downsampled to the PSP's pixels, the displayed frame read at N× from the render target.
//
// What must hold: at 1× the hardware mode draws what the software model draws on
// scenes whose pixels GL's float interpolation cannot move (through-mode rectangles, flat colours,
// texels mapped 1:1); at N× a scene without primitive edges inside PSP pixels writes back exactly
// the 1× VRAM (dither indexed by the PSP pixel, not the scaled one); the N× frame really holds
// N× detail along a slanted edge.
#include <cstdlib>
#include <cstring>
#include <functional>

#include "softmodel/soft_renderer.h"
#include "tests/gl_fixture.h"
#include "tests/near_clip_scene.h"

namespace ge::gltest {
namespace {

// Pixels of a 480x272 frame (512-pixel 8888 rows) where GL and the software model disagree on
// coverage or by more than one step in a colour channel (GL interpolates colours in float);
// `covered`: the software model's covered pixels.
size_t pixelsApart(const std::vector<u8>& gl, const std::vector<u8>& soft, size_t& covered) {
    auto rgb = [](const std::vector<u8>& f, int x, int y) { return readLE32(&f[(size_t(y) * 512 + size_t(x)) * 4]) & 0xFFFFFF; };
    size_t differ = 0;
    covered = 0;
    for (int y = 0; y < 272; ++y)
        for (int x = 0; x < 480; ++x) {
            const u32 a = rgb(gl, x, y), b = rgb(soft, x, y);
            covered += b != 0;
            bool close = true;
            for (int c = 0; c < 3; ++c) close &= std::abs(int((a >> (8 * c)) & 0xFF) - int((b >> (8 * c)) & 0xFF)) <= 1;
            differ += !close || ((a == 0) != (b == 0));
        }
    return differ;
}

gl::GlOptions hwOptions(int scale) {
    gl::GlOptions o;
    o.mode = gl::GlMode::Hw;
    o.scale = scale;
    return o;
}

// Runs `build` with the GL renderer made from `opt` (or the software model when opt is null);
// returns VRAM after flushToMemory, or false when GL is unavailable.
bool renderVram(const gl::GlOptions* opt, const std::function<void(ListBuilder&)>& build, std::vector<u8>& vram,
                std::string& err) {
    Memory mem;
    std::unique_ptr<Renderer> r;
    if (opt) {
        r = gl::createGlRenderer(mem, *opt, err);
        if (!r) return false;
    } else {
        soft::SoftOptions so;
        so.threads = 1;
        r = soft::createSoftRenderer(mem, so);
    }
    vram = runListVram(mem, *r, build);
    return true;
}

void frameSetup(ListBuilder& b, u32 fmt = GE_FORMAT_8888) {
    b.drawBuffer(fmt, 0, 64);
    b.depthBuffer(0x100000, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.offset(2048 - 32, 2048 - 32);
    b.viewport(2048, 2048, 64, 64);
    b.depthRange(65535, 0);
}

void throughRect(ListBuilder& b, float x1, float y1, float x2, float y2, u32 color, float u1, float v1, float u2,
                 float v2, u16 z) {
    BuildVertex v[2];
    v[0].x = x1, v[0].y = y1, v[0].z = z, v[0].color = color, v[0].u = u1, v[0].v = v1;
    v[1].x = x2, v[1].y = y2, v[1].z = z, v[1].color = color, v[1].u = u2, v[1].v = v2;
    const u32 vtype = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    const std::vector<u8> data = packVertices(vtype, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
}

// Rectangles on whole pixels: a 1:1 textured sprite (nearest), blending, dithering into a 16-bit
// frame buffer, depth test and writes, a stencil write — no edge crosses a PSP pixel, so every
// texel of a PSP pixel's N×N block computes the same value at any scale.
void edgeFreeScene(ListBuilder& b, u32 fmt) {
    frameSetup(b, fmt);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL | CLEAR_DEPTH, 0x40302010, 0x8000, 0x20);
    std::vector<u32> tex(16 * 16);
    for (int i = 0; i < 256; ++i) tex[size_t(i)] = u32(i * 0x010305) | (u32(255 - i) << 24);
    const u32 addr = b.place(tex.data(), 1024);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, addr, 16, 16, 16);
    b.texFunc(0, true);
    b.texFilter(0, 0);
    b.enable(GE_CMD_TME, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);
    b.enable(GE_CMD_DTE, true);
    const int m[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
    b.setDither(m);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(CMP_GEQUAL);
    throughRect(b, 4, 4, 20, 20, 0xFFFFFFFFu, 0, 0, 16, 16, 0x9000);
    throughRect(b, 12, 30, 28, 46, 0xC080FF40u, 0, 0, 16, 16, 0x7000);  // fails the depth test
    throughRect(b, 30, 8, 46, 24, 0x80FFE0A0u, 0, 0, 16, 16, 0xA000);
    b.enable(GE_CMD_TME, false);
    b.enable(GE_CMD_ABE, false);
    throughRect(b, 40, 36, 60, 60, 0x7F3366CCu, 0, 0, 0, 0, 0xB000);
}

size_t differingBytes(const std::vector<u8>& a, const std::vector<u8>& b, size_t& first) {
    size_t n = 0;
    first = a.size();
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) {
            if (!n) first = i;
            ++n;
        }
    return n;
}

TEST(GlHwMode, OneXMatchesTheSoftwareModelOnAnEdgeFreeScene) {
    for (u32 fmt : {u32(GE_FORMAT_8888), u32(GE_FORMAT_565), u32(GE_FORMAT_4444)}) {
        std::vector<u8> hw, soft;
        std::string err;
        const gl::GlOptions o = hwOptions(1);
        if (!renderVram(&o, [&](ListBuilder& b) { edgeFreeScene(b, fmt); }, hw, err)) GTEST_SKIP() << err;
        renderVram(nullptr, [&](ListBuilder& b) { edgeFreeScene(b, fmt); }, soft, err);
        size_t first;
        EXPECT_EQ(differingBytes(hw, soft, first), 0u) << "format " << fmt << ", first at byte 0x" << std::hex << first;
    }
}

// Rectangles whose far edges lie exactly on pixel centres (float positions at .5): a PSP leaves the
// pixel on the far edge out (geometry/raster.cpp rectangleSetup; pspautotests gpu/filtering/
// precision*), where the reference's 2×2 walk draws it when it is the odd one of a pair, and GL's
// own rasterisation of the quad may do either (found by `ge2gl fuzz --gl-mode hw`, seed 266, when
// the odd-pixel rule held). Flat colour, no texture: at 1× the hardware mode must cover exactly the
// software model's pixels.
TEST(GlHwMode, RectangleFarEdgeOnAPixelCentreCoversTheSoftwareModelsPixels) {
    auto build = [](ListBuilder& b) {
        frameSetup(b);
        b.clear(CLEAR_COLOR, 0, 0);
        BuildVertex v[2];
        const float pos[][4] = {{3.125f, 2.5f, 30.5f, 20.5f},   // 28 columns (odd pixel on the edge) x 18 rows
                                {33.5f, 24.0f, 40.5f, 41.5f},   // far edges on centres, even pair counts
                                {50.5f, 44.5f, 43.0f, 60.5f}};  // v0 right of v1
        const u32 vtype = vt::COL_8888 | vt::POS_F | vt::THROUGH;
        for (const auto& p : pos) {
            v[0].x = p[0], v[0].y = p[1], v[1].x = p[2], v[1].y = p[3];
            v[0].color = v[1].color = 0xFF40C080u;
            const std::vector<u8> data = packVertices(vtype, v, 2);
            b.drawArrayData(GE_PRIM_RECTANGLES, vtype, 2, nullptr, data.data());
        }
    };
    std::vector<u8> hw, soft;
    std::string err;
    const gl::GlOptions o = hwOptions(1);
    if (!renderVram(&o, build, hw, err)) GTEST_SKIP() << err;
    renderVram(nullptr, build, soft, err);
    auto at = [](const std::vector<u8>& v, int x, int y) { return readLE32(&v[(size_t(y) * 64 + size_t(x)) * 4]); };
    // The first rectangle: columns 3..29 (the far edge 30.5 is pixel 30's centre: left out).
    EXPECT_NE(at(soft, 29, 10) & 0xFFFFFF, 0u);
    EXPECT_EQ(at(soft, 30, 10) & 0xFFFFFF, 0u);
    size_t first;
    EXPECT_EQ(differingBytes(hw, soft, first), 0u) << "first at byte 0x" << std::hex << first;
}

TEST(GlHwMode, WriteBackAtTwoAndFourXEqualsTheOneXRender) {
    for (u32 fmt : {u32(GE_FORMAT_8888), u32(GE_FORMAT_5551)}) {
        std::vector<u8> one;
        std::string err;
        const gl::GlOptions o1 = hwOptions(1);
        if (!renderVram(&o1, [&](ListBuilder& b) { edgeFreeScene(b, fmt); }, one, err)) GTEST_SKIP() << err;
        for (int n : {2, 4}) {
            std::vector<u8> scaled;
            const gl::GlOptions on = hwOptions(n);
            ASSERT_TRUE(renderVram(&on, [&](ListBuilder& b) { edgeFreeScene(b, fmt); }, scaled, err)) << err;
            size_t first;
            EXPECT_EQ(differingBytes(one, scaled, first), 0u)
                << "scale " << n << " format " << fmt << ", first at byte 0x" << std::hex << first;
            // Depth (0x100000..) is part of the comparison: written back as u16 from the average.
            EXPECT_EQ(scaled[0x100000 + 2 * (8 * 64 + 8) + 1], 0x90) << "scale " << n;
        }
    }
}

// A triangle whose long edge crosses pixels diagonally: at 2× the frame holds blocks split by
// the edge (finer than any 1× picture repeated), and the box-downsampled frame stays close to 1×.
TEST(GlHwMode, ScaledFrameHoldsDetailFinerThanAPspPixel) {
    Memory mem;
    std::string err;
    auto r = gl::createGlRenderer(mem, hwOptions(2), err);
    if (!r) GTEST_SKIP() << err;
    runListVram(mem, *r, [](ListBuilder& b) {
        frameSetup(b);
        b.clear(CLEAR_COLOR, 0xFF000000u, 0, 0);
        BuildVertex v[3];
        v[0].x = 2, v[0].y = 2, v[1].x = 61, v[1].y = 9, v[2].x = 7, v[2].y = 60;
        for (auto& x : v) x.color = 0xFFFFFFFFu;
        const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        const std::vector<u8> data = packVertices(vtype, v, 3);
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, data.data());
    });
    std::vector<u32> hi;
    ASSERT_EQ(r->readScaledFrame(0x04000000, 64, GE_FORMAT_8888, 64, 64, hi), 2);
    ASSERT_EQ(hi.size(), size_t(128 * 128));
    int split = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const u32 a = hi[size_t(2 * y) * 128 + size_t(2 * x)];
            bool mixed = false;
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) mixed |= hi[size_t(2 * y + j) * 128 + size_t(2 * x + i)] != a;
            split += mixed;
        }
    EXPECT_GT(split, 40) << "no 2x2 block is split by the slanted edges: the frame is a 1x picture repeated";
    // Inside and outside are what they should be.
    EXPECT_EQ(hi[size_t(2 * 20) * 128 + 2 * 20], 0xFFFFFFFFu);
    EXPECT_EQ(hi[size_t(2 * 60) * 128 + 2 * 60], 0xFF000000u);
}

// Rows past 512 make the scaled targets grow; what they held survives the growth.
TEST(GlHwMode, TargetsGrowPastRow512KeepingTheirPixels) {
    Memory mem;
    std::string err;
    auto r = gl::createGlRenderer(mem, hwOptions(2), err);
    if (!r) GTEST_SKIP() << err;
    const std::vector<u8> vram = runListVram(mem, *r, [](ListBuilder& b) {
        b.drawBuffer(GE_FORMAT_565, 0, 64);
        b.scissor(0, 0, 64, 600);
        b.region(0, 0, 64, 600);
        b.offset(0, 0);
        throughRect(b, 0, 0, 8, 8, 0xFF0000FFu, 0, 0, 0, 0, 0);      // rows 0..7 first
        throughRect(b, 0, 590, 8, 598, 0xFFFF0000u, 0, 0, 0, 0, 0);  // then rows past 512
    });
    EXPECT_EQ(readLE16(&vram[2 * (4 * 64 + 4)]), 0x001Fu);    // red in 565
    EXPECT_EQ(readLE16(&vram[2 * (594 * 64 + 4)]), 0xF800u);  // blue in 565
}

// ---- render-to-texture and block transfers on the GPU ----

// A 64×64 drawing at VRAM offset `off` in format fmt: a slanted white triangle on a coloured
// background with a few flat bands, so both exact colours and sub-pixel edges are present.
void drawSource(ListBuilder& b, u32 off, u32 fmt) {
    b.drawBuffer(fmt, off, 64);
    b.scissor(0, 0, 64, 64);
    b.region(0, 0, 64, 64);
    b.offset(2048 - 32, 2048 - 32);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL, 0x8040C020u, 0, 0x80);
    throughRect(b, 0, 40, 64, 48, 0xF0306090u, 0, 0, 0, 0, 0);
    BuildVertex v[3];
    v[0].x = 2, v[0].y = 2, v[1].x = 61, v[1].y = 9, v[2].x = 7, v[2].y = 60;
    for (auto& x : v) x.color = 0xFFFFFFFFu;
    const u32 vtype = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
    const std::vector<u8> data = packVertices(vtype, v, 3);
    b.drawArrayData(GE_PRIM_TRIANGLES, vtype, 3, nullptr, data.data());
}

// Draws the 64×64 texture at VRAM offset texOff (format tf, buffer width 64) 1:1 into the 8888
// frame buffer at 0 with nearest filtering.
void drawTextured(ListBuilder& b, u32 texOff, u32 tf) {
    frameSetup(b);
    b.texMode(tf, 0, false);
    b.setTexture(0, 0x04000000 + texOff, 64, 64, 64);
    b.texFunc(3, true);  // REPLACE with alpha
    b.texFilter(0, 0);
    b.enable(GE_CMD_TME, true);
    throughRect(b, 0, 0, 64, 64, 0xFFFFFFFFu, 0, 0, 64, 64, 0);
    b.enable(GE_CMD_TME, false);
}

struct Rendered {
    std::vector<u8> vram;
    gl::GlStats stats;
    std::vector<u32> scaled;  // the 8888 frame at 0, 64×64 PSP pixels at render scale
};

bool renderHw(int scale, const std::function<void(ListBuilder&)>& build, Rendered& out, std::string& err) {
    Memory mem;
    auto r = gl::createGlRenderer(mem, hwOptions(scale), err);
    if (!r) return false;
    out.vram = runListVram(mem, *r, build);
    out.stats = r->stats();
    r->readScaledFrame(0x04000000, 64, GE_FORMAT_8888, 64, 64, out.scaled);
    return true;
}

int splitBlocks(const std::vector<u32>& hi, int n) {
    int split = 0;
    const size_t W = size_t(64 * n);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const u32 a = hi[size_t(n * y) * W + size_t(n * x)];
            bool mixed = false;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) mixed |= hi[size_t(n * y + j) * W + size_t(n * x + i)] != a;
            split += mixed;
        }
    return split;
}

// A 16-bit frame buffer read as another 16-bit texture format (5551 drawn, 4444 sampled), and an
// 8888 one as 8888: the GPU samples the render target in place and reinterprets the bits as the
// software model does through VRAM.
TEST(GlHwMode, RenderToTextureReinterpretsFormatsOnTheGpu) {
    struct Case {
        u32 fbFmt, texFmt;
    };
    for (Case c : {Case{GE_FORMAT_5551, GE_TFMT_4444}, Case{GE_FORMAT_565, GE_TFMT_5551},
                   Case{GE_FORMAT_4444, GE_TFMT_5650}, Case{GE_FORMAT_8888, GE_TFMT_8888}}) {
        auto build = [&](ListBuilder& b) {
            drawSource(b, 0x80000, c.fbFmt);
            drawTextured(b, 0x80000, c.texFmt);
        };
        Rendered hw;
        std::string err;
        if (!renderHw(1, build, hw, err)) GTEST_SKIP() << err;
        std::vector<u8> soft;
        renderVram(nullptr, build, soft, err);
        size_t first;
        EXPECT_EQ(differingBytes(hw.vram, soft, first), 0u)
            << "fb " << c.fbFmt << " as " << c.texFmt << ", first at byte 0x" << std::hex << first;
        EXPECT_EQ(hw.stats.rttGpu, 1u) << "the render target was not sampled in place";
        // At 2× the textured copy keeps the source's sub-pixel edges (no trip through 1× VRAM).
        Rendered hw2;
        ASSERT_TRUE(renderHw(2, build, hw2, err)) << err;
        EXPECT_GT(splitBlocks(hw2.scaled, 2), 40) << "fb " << c.fbFmt << ": the texture lost the 2x detail";
    }
}

// A frame buffer read through a palette, one index per pixel: CLUT32 over an 8888 buffer picking
// one channel with the shift (G: shift 8, mask 0xFF), CLUT16 over a 5551 buffer with CSA, and
// CLUT16 over 565 with a 16-bit palette. Sampled in place on the GPU, equal to the software model
// at 1×, 2× detail kept.
TEST(GlHwMode, ClutLookupOfAFrameBufferRunsOnTheGpu) {
    struct Case {
        u32 fbFmt, texFmt, cpf, shift, mask, csa;
    };
    for (Case c : {Case{GE_FORMAT_8888, GE_TFMT_CLUT32, 3, 8, 0xFF, 0}, Case{GE_FORMAT_5551, GE_TFMT_CLUT16, 3, 2, 0x7F, 8},
                   Case{GE_FORMAT_565, GE_TFMT_CLUT16, 1, 5, 0xFF, 1}}) {
        auto build = [&](ListBuilder& b) {
            drawSource(b, 0x80000, c.fbFmt);
            std::vector<u32> pal(512);
            for (int i = 0; i < 512; ++i) pal[size_t(i)] = 0xFF000000u | u32(i * 0x00030507) | (u32(i & 1) << 31);
            const u32 palAddr = b.place(pal.data(), 2048, 64);
            b.clutMode(c.cpf, c.shift, c.mask, c.csa);
            b.clutLoad(palAddr, 64);
            drawTextured(b, 0x80000, c.texFmt);
        };
        Rendered hw;
        std::string err;
        if (!renderHw(1, build, hw, err)) GTEST_SKIP() << err;
        std::vector<u8> soft;
        renderVram(nullptr, build, soft, err);
        size_t first;
        EXPECT_EQ(differingBytes(hw.vram, soft, first), 0u)
            << "fb " << c.fbFmt << " CLUT " << c.texFmt << ", first at byte 0x" << std::hex << first;
        EXPECT_EQ(hw.stats.rttGpu, 1u);
        Rendered hw2;
        ASSERT_TRUE(renderHw(2, build, hw2, err)) << err;
        EXPECT_GT(splitBlocks(hw2.scaled, 2), 40) << "fb " << c.fbFmt << ": the lookup lost the 2x detail";
    }
}

// CLUT8 and CLUT4 textures over a frame buffer's bytes and nibbles (the texture's buffer width
// counts them: 2 or 4 texels per 16-bit pixel, 4 or 8 per 8888 pixel) are read on the GPU too and
// match the software model; a swizzled one goes through VRAM (counted as rttVram) and matches.
TEST(GlHwMode, ClutLookupOfTheBytesOfAFrameBufferOnTheGpuAndThroughVram) {
    struct Case {
        u32 fbFmt, texFmt, perPixel;
        bool swizzle;
    };
    for (Case c : {Case{GE_FORMAT_5551, GE_TFMT_CLUT8, 2, false}, Case{GE_FORMAT_8888, GE_TFMT_CLUT8, 4, false},
                   Case{GE_FORMAT_8888, GE_TFMT_CLUT4, 8, false}, Case{GE_FORMAT_565, GE_TFMT_CLUT4, 4, false},
                   Case{GE_FORMAT_5551, GE_TFMT_CLUT8, 2, true}}) {
        auto build = [&](ListBuilder& b) {
            drawSource(b, 0x80000, c.fbFmt);
            std::vector<u32> pal(256);
            for (int i = 0; i < 256; ++i) pal[size_t(i)] = 0xFF000000u | u32(i * 0x00010203);
            const u32 palAddr = b.place(pal.data(), 1024, 64);
            b.clutMode(3, 1, 0x7F, 0);
            b.clutLoad(palAddr, 32);
            frameSetup(b);
            b.texMode(c.texFmt, 0, c.swizzle);
            const u32 w = 64 * c.perPixel;  // texels per row = the buffer's pixels × perPixel
            b.setTexture(0, 0x04080000, w, 64, w);
            b.texFunc(3, true);
            b.texFilter(0, 0);
            b.enable(GE_CMD_TME, true);
            // Two halves a texel apart, so both even and odd bytes/nibbles of the pixels are read.
            throughRect(b, 0, 0, 64, 32, 0xFFFFFFFFu, 0.5f, 0, float(w) + 0.5f, 32, 0);
            throughRect(b, 0, 32, 64, 64, 0xFFFFFFFFu, 1.5f, 32, float(w) + 1.5f, 64, 0);
        };
        Rendered hw;
        std::string err;
        if (!renderHw(1, build, hw, err)) GTEST_SKIP() << err;
        std::vector<u8> soft;
        renderVram(nullptr, build, soft, err);
        size_t first;
        EXPECT_EQ(differingBytes(hw.vram, soft, first), 0u)
            << "fb " << c.fbFmt << " tex " << c.texFmt << " swizzle " << c.swizzle << ", first at byte 0x" << std::hex
            << first;
        EXPECT_EQ(hw.stats.rttGpu, c.swizzle ? 0u : 2u);  // two draws
        EXPECT_EQ(hw.stats.rttVram, c.swizzle ? 2u : 0u);
        Rendered hw2;
        ASSERT_TRUE(renderHw(2, build, hw2, err)) << err;
        EXPECT_EQ(hw2.stats.rttGpu, c.swizzle ? 0u : 2u);
    }
}

// A block transfer from one render target into another happens on the GPU: equal to the
// software model at 1×, and at 2× the copied pixels keep their sub-pixel detail.
TEST(GlHwMode, BlockTransferBetweenRenderTargetsStaysOnTheGpu) {
    auto build = [&](ListBuilder& b) {
        frameSetup(b);
        b.clear(CLEAR_COLOR, 0xFF000000u, 0, 0);  // the display target exists
        drawSource(b, 0x80000, GE_FORMAT_8888);
        b.copyImage(GE_FORMAT_8888, 0, 0, 64, 64, 64, 0x04080000, 0, 0, 64, 0x04000000);
    };
    Rendered hw;
    std::string err;
    if (!renderHw(1, build, hw, err)) GTEST_SKIP() << err;
    std::vector<u8> soft;
    renderVram(nullptr, build, soft, err);
    size_t first;
    EXPECT_EQ(differingBytes(hw.vram, soft, first), 0u) << "first at byte 0x" << std::hex << first;
    EXPECT_EQ(hw.stats.transfersGpu, 1u);
    Rendered hw2;
    ASSERT_TRUE(renderHw(2, build, hw2, err)) << err;
    EXPECT_EQ(hw2.stats.transfersGpu, 1u);
    EXPECT_GT(splitBlocks(hw2.scaled, 2), 40) << "the copy went through 1x VRAM";
}

// ---- GPU vertices (gpu_vertex_path.h, shadergen/hw_vertex.h, hw_geometry.cpp) ----

// A triangle with a vertex behind the camera, through the renderer with the vertex work on the GPU:
// the geometry shader near-clips it as the GE does (the clipped quadrilateral, never the inverted
// triangle), with either CLE value; the pixels equal the software model's. Then the fan whose
// second triangle's clipped pieces all leave the screen range (nothing of it drawn), as a
// triangle list on the GPU (the 4-vertex fan itself stays on the CPU: the reference's rectangle
// detection).
TEST(GlHwMode, GpuVerticesNearClipAVertexBehindTheCamera) {
    using namespace testscene;
    gl::GlOptions o = hwOptions(1);
    o.vertices = gl::GlOptions::Vertices::Gpu;
    for (bool cle : {false, true}) {
        SCOPED_TRACE(cle ? "CLE = 1" : "CLE = 0");
        Memory mem;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        if (!r) GTEST_SKIP() << err;
        const std::vector<u8> vram = runListVram(mem, *r, [cle](ListBuilder& b) { nearClipScene(b, cle); });
        EXPECT_EQ(r->stats().gpuVertexDraws, 1u);
        for (const auto& p : kNearClipProbes) {
            const size_t at = (size_t(p.y) * 512 + size_t(p.x)) * 4;
            EXPECT_EQ(readLE32(&vram[at]) & 0xFFFFFF, p.covered ? 0xFFFFFFu : 0u) << p.x << "," << p.y;
        }
        std::vector<u8> soft;
        renderVram(nullptr, [cle](ListBuilder& b) { nearClipScene(b, cle); }, soft, err);
        size_t first;
        EXPECT_EQ(differingBytes(vram, soft, first), 0u) << "first at byte 0x" << std::hex << first;
    }
    for (bool asTriangles : {true, false}) {
        SCOPED_TRACE(asTriangles ? "triangle list" : "fan");
        Memory mem;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        ASSERT_NE(r, nullptr) << err;
        const std::vector<u8> vram =
            runListVram(mem, *r, [asTriangles](ListBuilder& b) { nearClipFanScene(b, asTriangles); });
        EXPECT_EQ(r->stats().gpuVertexDraws, asTriangles ? 1u : 0u);
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 512 + size_t(x)) * 4]) & 0xFFFFFF; };
        EXPECT_EQ(rgb(kFanProbeFirst.x, kFanProbeFirst.y), 0xFFFFFFu);
        EXPECT_EQ(rgb(kFanWedgeX, kFanWedgeY), asTriangles ? 0xFFFFFFu : 0u);
    }
}

// A PRIM type 7 continuing a strip the GPU drew: the CPU path picks up the GPU-drawn PRIM's open
// vertices and strip parity (VertexPipeline::keepOpenVertices) and draws what the software model
// draws.
TEST(GlHwMode, ContinuationAfterAGpuDrawnStrip) {
    auto build = [](ListBuilder& b) {
        testscene::nearClipFrame(b, false);
        constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
        BuildVertex v[7];
        const float xy[7][2] = {{-0.9f, -0.6f}, {-0.9f, 0.1f}, {-0.5f, -0.7f}, {-0.4f, 0.2f}, {0.0f, -0.6f},
                                {0.1f, 0.3f}, {0.6f, -0.5f}};
        for (int i = 0; i < 7; ++i) {
            v[i].x = xy[i][0], v[i].y = xy[i][1], v[i].z = 1.0f;
            v[i].color = 0xFF000000u | u32(0x203040 * (i + 1));
        }
        const auto first = packVertices(vtype, v, 5);
        b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 5, nullptr, first.data());  // odd: GPU
        const auto more = packVertices(vtype, v + 5, 2);
        b.drawArrayData(GE_PRIM_KEEP_PREVIOUS, vtype, 2, nullptr, more.data());  // continues the strip
    };
    gl::GlOptions o = hwOptions(1);
    o.vertices = gl::GlOptions::Vertices::Gpu;
    Memory mem;
    std::string err;
    auto r = gl::createGlRenderer(mem, o, err);
    if (!r) GTEST_SKIP() << err;
    const std::vector<u8> vram = runListVram(mem, *r, build);
    EXPECT_EQ(r->stats().gpuVertexDraws, 1u);
    std::vector<u8> soft;
    renderVram(nullptr, build, soft, err);
    // The continued triangles (vertices 3-4-5 and 4-5-6) cover x around 330-390 at row 150.
    EXPECT_NE(readLE32(&soft[(150 * 512 + 300) * 4]) & 0xFFFFFF, 0u);
    size_t covered = 0;
    EXPECT_EQ(pixelsApart(vram, soft, covered), 0u);
    EXPECT_GT(covered, 10000u);
}

// Consecutive GPU-path draws with the same state become one GL draw (GpuVertexPath::join): a
// one-triangle fan, then the near-clip fan of near_clip_scene.h with a fifth vertex. Joined, the
// second fan's triangles are triangles 1-3 of the GL draw, but the geometry shader must still
// take its second triangle (C, B, D) as odd (the ring ids, shadergen::hwTriangleList): taken as
// even it would keep the wedge piece at (470, 180) that the reference drops. The fifth vertex E
// lies right of D; (C, D, E) crosses the near plane with both new vertices beyond x = 4096, so
// nothing of it is drawn. A MAC command between the draws (a uniform the vertex colours hide)
// keeps them apart: one GL draw more, the same pixels.
TEST(GlHwMode, ConsecutiveGpuDrawsOfOneStateJoinIntoOneGlDraw) {
    auto build = [](ListBuilder& b, bool apart) {
        testscene::nearClipFrame(b, false);
        constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
        auto vtx = [](float x, float y, float z) {
            BuildVertex v;
            v.x = x, v.y = y, v.z = z;
            v.color = 0xFFFFFFFFu;
            return v;
        };
        const BuildVertex small[3] = {vtx(-0.9f, -0.9f, 1), vtx(-0.7f, -0.9f, 1), vtx(-0.8f, -0.7f, 1)};
        const auto first = packVertices(vtype, small, 3);
        b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 3, nullptr, first.data());
        if (apart) b.cmd(GE_CMD_MAC, 0x123456);
        const BuildVertex fan[5] = {vtx(0, 0.9f, -0.5f), vtx(-0.5f, -0.5f, 1), vtx(0.5f, -0.5f, 1), vtx(5, -0.5f, 1),
                                    vtx(6, -0.4f, 1)};
        const auto second = packVertices(vtype, fan, 5);
        b.drawArrayData(GE_PRIM_TRIANGLE_FAN, vtype, 5, nullptr, second.data());
    };
    gl::GlOptions o = hwOptions(1);
    o.vertices = gl::GlOptions::Vertices::Gpu;
    u64 glDraws[2] = {};
    for (bool apart : {false, true}) {
        SCOPED_TRACE(apart ? "MAC between the draws" : "one state");
        Memory mem;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        if (!r) GTEST_SKIP() << err;
        const std::vector<u8> vram = runListVram(mem, *r, [&](ListBuilder& b) { build(b, apart); });
        EXPECT_EQ(r->stats().gpuVertexDraws, 2u);
        glDraws[apart] = r->stats().glDrawCalls;
        auto rgb = [&](int x, int y) { return readLE32(&vram[(size_t(y) * 512 + size_t(x)) * 4]) & 0xFFFFFF; };
        EXPECT_EQ(rgb(testscene::kFanProbeFirst.x, testscene::kFanProbeFirst.y), 0xFFFFFFu);
        EXPECT_EQ(rgb(testscene::kFanWedgeX, testscene::kFanWedgeY), 0u);
        EXPECT_EQ(rgb(48, 250), 0xFFFFFFu);  // the small fan
        std::vector<u8> soft;
        renderVram(nullptr, [&](ListBuilder& b) { build(b, apart); }, soft, err);
        size_t covered = 0;
        EXPECT_EQ(pixelsApart(vram, soft, covered), 0u);
        EXPECT_GT(covered, 40000u);
    }
    EXPECT_EQ(glDraws[1], glDraws[0] + 1);
}

// A Bezier patch with the vertex work on the GPU: the CPU tessellates (geo::tessellatePatch), the
// vertex shader transforms the generated float vertices (GpuVertexPath::preparePatch), as
// PPSSPP's GL backend does with its CPU tessellation. The pixels are the software model's, colours
// within one step (GL interpolates in float). Drawn as lines (PPM 1) the patch stays on the CPU.
TEST(GlHwMode, GpuVerticesDrawATessellatedPatch) {
    auto build = [](ListBuilder& b, u32 ppm) {
        testscene::nearClipFrame(b, false);
        b.patchDivide(6, 5);
        b.patchPrim(ppm);
        constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
        BuildVertex v[16];
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                BuildVertex& c = v[j * 4 + i];
                c.x = -0.8f + 0.5f * float(i) + 0.05f * float(j);
                c.y = -0.6f + 0.4f * float(j) + (i == 1 || i == 2 ? 0.1f : 0.0f);
                c.z = 1.0f;
                c.color = 0xFF000000u | u32(40 + 60 * i) | u32(30 + 70 * j) << 8 | u32(200 - 50 * i) << 16;
            }
        const auto data = packVertices(vtype, v, 16);
        b.drawBezier(vtype, 4, 4, 0, b.place(data.data(), u32(data.size()), 4));
    };
    gl::GlOptions o = hwOptions(1);
    o.vertices = gl::GlOptions::Vertices::Gpu;
    for (u32 ppm : {0u, 1u}) {
        SCOPED_TRACE(ppm ? "lines" : "triangles");
        Memory mem;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        if (!r) GTEST_SKIP() << err;
        auto scene = [&](ListBuilder& b) { build(b, ppm); };
        const std::vector<u8> vram = runListVram(mem, *r, scene);
        EXPECT_EQ(r->stats().gpuVertexDraws, ppm ? 0u : 1u);
        std::vector<u8> soft;
        renderVram(nullptr, scene, soft, err);
        size_t covered = 0;
        EXPECT_EQ(pixelsApart(vram, soft, covered), 0u);
        EXPECT_GT(covered, ppm ? 500u : 20000u);
    }
}

// A patch whose control points all lie beyond the right edge of the clip rectangle is not
// tessellated, on the GPU vertex path (the front end's test, geo::DrawFrontEnd::offClipTest) as
// on the CPU path; moved to reach into the screen, it is drawn. The pixels are the software
// model's either way.
TEST(GlHwMode, PatchesWhollyBeyondTheClipRectangleAreCulledOnBothVertexPaths) {
    auto build = [](ListBuilder& b, float dx) {
        testscene::nearClipFrame(b, false);
        b.patchDivide(6, 5);
        constexpr u32 vtype = vt::COL_8888 | vt::POS_F;
        BuildVertex v[16];
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                BuildVertex& c = v[j * 4 + i];
                c.x = dx + 0.3f * float(i);
                c.y = -0.6f + 0.4f * float(j);
                c.z = 1.0f;
                c.color = 0xFF00C000u | u32(40 + 60 * i);
            }
        const auto data = packVertices(vtype, v, 16);
        b.drawBezier(vtype, 4, 4, 0, b.place(data.data(), u32(data.size()), 4));
    };
    for (auto path : {gl::GlOptions::Vertices::Gpu, gl::GlOptions::Vertices::Cpu})
        for (float dx : {1.1f, 0.5f}) {  // beyond the right edge; reaching into the screen
            SCOPED_TRACE(std::string(path == gl::GlOptions::Vertices::Gpu ? "gpu" : "cpu") + (dx > 1 ? " off" : " in"));
            gl::GlOptions o = hwOptions(1);
            o.vertices = path;
            Memory mem;
            std::string err;
            auto r = gl::createGlRenderer(mem, o, err);
            if (!r) GTEST_SKIP() << err;
            auto scene = [&](ListBuilder& b) { build(b, dx); };
            const std::vector<u8> vram = runListVram(mem, *r, scene);
            EXPECT_EQ(r->stats().culledPatches, dx > 1 ? 1u : 0u);
            EXPECT_EQ(r->stats().gpuVertexDraws, path == gl::GlOptions::Vertices::Gpu && dx < 1 ? 1u : 0u);
            std::vector<u8> soft;
            renderVram(nullptr, scene, soft, err);
            size_t covered = 0;
            EXPECT_EQ(pixelsApart(vram, soft, covered), 0u);
            if (dx < 1) EXPECT_GT(covered, 1000u);
            else EXPECT_EQ(covered, 0u);
        }
}

// Auto picks the CPU vertex path on a software rasteriser (llvmpipe here) and Gpu forces it.
TEST(GlHwMode, VertexPathAutoIsCpuOnASoftwareRasteriser) {
    using namespace testscene;
    for (auto v : {gl::GlOptions::Vertices::Auto, gl::GlOptions::Vertices::Gpu, gl::GlOptions::Vertices::Cpu}) {
        gl::GlOptions o = hwOptions(1);
        o.vertices = v;
        Memory mem;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        if (!r) GTEST_SKIP() << err;
        runListVram(mem, *r, [](ListBuilder& b) { nearClipScene(b, false); });
        EXPECT_EQ(r->stats().gpuVertexDraws, v == gl::GlOptions::Vertices::Gpu ? 1u : 0u);
    }
}

// The null GL (translator/null_gl.h): a replay runs through the whole translator with a dispatch
// table that does nothing — draws counted, programs "compiled", nothing drawn into VRAM.
TEST(GlNullContext, ReplaysThroughTheTranslatorWithoutADriver) {
    for (gl::GlMode mode : {gl::GlMode::Exact, gl::GlMode::Hw}) {
        Memory mem;
        gl::GlOptions o;
        o.context = gl::ContextKind::Null;
        o.mode = mode;
        std::string err;
        auto r = gl::createGlRenderer(mem, o, err);
        ASSERT_NE(r, nullptr) << err;
        const std::vector<u8> vram = runListVram(mem, *r, [](ListBuilder& b) { edgeFreeScene(b, GE_FORMAT_8888); });
        const gl::GlStats st = r->stats();
        EXPECT_EQ(st.draws, 5u);  // the clear (one PRIM for 64 columns) + 4 rectangles
        EXPECT_GT(st.glDrawCalls, 0u);
        EXPECT_GT(st.shaderCompiles, 0u);
    }
}

TEST(GlHwMode, ScaleNeedsHwModeAndStaysInRange) {
    Memory mem;
    std::string err;
    gl::GlOptions o;
    o.scale = 2;  // exact mode
    EXPECT_EQ(gl::createGlRenderer(mem, o, err), nullptr);
    EXPECT_NE(err.find("hardware mode"), std::string::npos) << err;
    o = hwOptions(9);
    err.clear();
    EXPECT_EQ(gl::createGlRenderer(mem, o, err), nullptr);
    EXPECT_NE(err.find("out of range"), std::string::npos) << err;
}

}  // namespace
}  // namespace ge::gltest
