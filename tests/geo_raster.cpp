// SPDX-License-Identifier: MIT
// Rasteriser tests: coverage rules (top-left fill, rectangles, lines, points), attribute
// interpolation, rectangle texture orientation (docs/ge-rules.md §8.1, §8.2, §8.11) and bands.
// Expected values are worked out by hand from those rules.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <vector>

#include "geometry/raster.h"

using namespace ge;
using namespace ge::geo;

namespace {

// Collects every fragment the rasteriser emits.
struct Collector {
    std::vector<Fragment> frags;
    Fragment buf[64];
    FragmentSink sink{buf, 64, &Collector::take, this};
    static void take(void* ctx, const Fragment* f, size_t n) {
        auto* c = static_cast<Collector*>(ctx);
        c->frags.insert(c->frags.end(), f, f + n);
    }
    const std::vector<Fragment>& done() {
        sink.flush();
        return frags;
    }
    std::set<std::pair<int, int>> pixels() {
        std::set<std::pair<int, int>> s;
        for (const Fragment& f : done()) s.insert({f.x, f.y});
        return s;
    }
};

RasterParams fullScreen() {
    RasterParams rp;
    rp.clipX1 = 0, rp.clipY1 = 0, rp.clipX2 = 1023, rp.clipY2 = 1023;
    return rp;
}

// A vertex at pixel coordinates (x, y) given in 1/16 pixel.
ScreenVertex sv16(int x, int y) {
    ScreenVertex v;
    v.x = x, v.y = y;
    return v;
}
ScreenVertex px(float x, float y) { return sv16(int(x * 16), int(y * 16)); }

}  // namespace

TEST(GeoRaster, SharedEdgeSquareCoveredOnce) {
    // An 8×8 square split along its diagonal: 64 pixels, 8 of them with centres exactly on the
    // shared edge. Each must be drawn exactly once, whichever triangle and winding.
    for (int winding = 0; winding < 2; ++winding) {
        Collector c;
        ScreenVertex a = px(0, 0), b = px(8, 0), d = px(0, 8), e = px(8, 8);
        if (winding == 0) {
            rasterTriangle(fullScreen(), a, b, d, d, Band{}, c.sink);
            rasterTriangle(fullScreen(), b, e, d, d, Band{}, c.sink);
        } else {
            rasterTriangle(fullScreen(), a, d, b, b, Band{}, c.sink);
            rasterTriangle(fullScreen(), d, e, b, b, Band{}, c.sink);
        }
        std::map<std::pair<int, int>, int> count;
        for (const Fragment& f : c.done()) ++count[{f.x, f.y}];
        EXPECT_EQ(count.size(), 64u);
        for (auto& [p, n] : count) {
            EXPECT_EQ(n, 1) << p.first << "," << p.second;
            EXPECT_TRUE(p.first >= 0 && p.first < 8 && p.second >= 0 && p.second < 8);
        }
    }
}

TEST(GeoRaster, JitteredMeshNoGapsNoOverlap) {
    // A 16×16-cell mesh over [0, 64)² with jittered inner vertices (fractional 1/16 positions),
    // two triangles per cell with both diagonals: the union is the square, so every one of the
    // 4096 pixels must be drawn exactly once.
    constexpr int N = 16, S = 64 * 16 / N;
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> jit(-S / 3, S / 3);
    ScreenVertex grid[N + 1][N + 1];
    for (int j = 0; j <= N; ++j)
        for (int i = 0; i <= N; ++i) {
            int x = i * S, y = j * S;
            if (i > 0 && i < N) x += jit(rng);
            if (j > 0 && j < N) y += jit(rng);
            grid[j][i] = sv16(x, y);
        }
    Collector c;
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            const ScreenVertex &a = grid[j][i], &b = grid[j][i + 1], &d = grid[j + 1][i], &e = grid[j + 1][i + 1];
            if ((i + j) & 1) {
                rasterTriangle(fullScreen(), a, b, e, e, Band{}, c.sink);
                rasterTriangle(fullScreen(), e, d, a, a, Band{}, c.sink);
            } else {
                rasterTriangle(fullScreen(), a, b, d, d, Band{}, c.sink);
                rasterTriangle(fullScreen(), d, e, b, b, Band{}, c.sink);  // opposite winding
            }
        }
    std::map<std::pair<int, int>, int> count;
    for (const Fragment& f : c.done()) ++count[{f.x, f.y}];
    EXPECT_EQ(count.size(), 4096u);
    int twice = 0;
    for (auto& [p, n] : count) twice += n != 1;
    EXPECT_EQ(twice, 0);
}

TEST(GeoRaster, TopLeftRuleOnPixelCentres) {
    // Triangles sample pixel p at p + 7/16 (raster.h triangleSampleOffset with
    // RasterParams::sampleCentre off: the reference renderer's point).
    // Right triangle with edges through sample points: top edge y = 7/16 and left edge x = 7/16
    // are drawn; the hypotenuse (a right edge) is not: pixels with x + y ≤ 3.
    {
        Collector c;
        rasterTriangle(fullScreen(), px(0.4375f, 0.4375f), px(4.4375f, 0.4375f), px(0.4375f, 4.4375f),
                       px(0.4375f, 4.4375f), Band{}, c.sink);
        std::set<std::pair<int, int>> expect;
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x + y <= 3; ++x) expect.insert({x, y});
        EXPECT_EQ(c.pixels(), expect);
    }
    // Flat bottom edge through sample points: not drawn; the diagonal y = x bounds it on the
    // right (not drawn), the left edge is drawn: pixels 0 ≤ x < y ≤ 3.
    {
        Collector c;
        rasterTriangle(fullScreen(), px(0.4375f, 0.4375f), px(4.4375f, 4.4375f), px(0.4375f, 4.4375f),
                       px(0.4375f, 4.4375f), Band{}, c.sink);
        std::set<std::pair<int, int>> expect;
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < y; ++x) expect.insert({x, y});
        EXPECT_EQ(c.pixels(), expect);
    }
    // Half a pixel is not the sample point: a left edge at x = 0.5 leaves column 0 out.
    {
        Collector c;
        rasterTriangle(fullScreen(), px(0.5f, 0), px(4.5f, 0), px(0.5f, 4), px(0.5f, 4), Band{}, c.sink);
        for (auto [x, y] : c.pixels()) EXPECT_GE(x, 1);
        EXPECT_FALSE(c.pixels().empty());
    }
    // Zero area: see ZeroAreaTrianglesDrawSamplesOnTheirLine.
}

TEST(GeoRaster, ZeroAreaTrianglesDrawSamplesOnTheirLine) {
    // The reference renderer draws a zero-area triangle in both vertex orders wherever all three
    // biased edge functions are ≥ 0: sample points exactly on the line, no edge biased, within the
    // pixel box of the vertices (raster.cpp rasterZeroAreaTriangle).
    // A strip join (P, Q, Q) from a quad's corner P at a sample point (pixel (3, 2): 16·3 + 7,
    // 16·2 + 7) to Q above it: no bias (P lies below the zero edge Q–Q), so pixel (3, 2), the only
    // sample on the segment, is drawn once per order.
    const ScreenVertex P = sv16(55, 39), Q = sv16(49, -10);
    {
        Collector c;
        rasterTriangle(fullScreen(), P, Q, Q, Q, Band{}, c.sink);
        ASSERT_EQ(c.done().size(), 2u);
        for (const Fragment& f : c.done()) EXPECT_EQ(std::make_pair(f.x, f.y), std::make_pair(3, 2));
    }
    // (Q, P, P): Q lies above the zero edge P–P, a flat bottom for it (bias −1): nothing.
    {
        Collector c;
        rasterTriangle(fullScreen(), Q, P, P, P, Band{}, c.sink);
        EXPECT_TRUE(c.done().empty());
    }
    // Three distinct points on y = x from (0, 0) to (8, 8) pixels: no edge biased (the line's x at
    // each vertex's y is the vertex's own), samples (16p + 7, 16p + 7) for p = 0…8 — pixel 8's
    // sample lies past the last vertex but inside its pixel — twice each.
    {
        Collector c;
        rasterTriangle(fullScreen(), px(0, 0), px(4, 4), px(8, 8), px(8, 8), Band{}, c.sink);
        std::set<std::pair<int, int>> expect;
        for (int p = 0; p <= 8; ++p) expect.insert({p, p});
        EXPECT_EQ(c.pixels(), expect);
        EXPECT_EQ(c.done().size(), 18u);
    }
    // Depth that differs between the vertices is NaN there: outside through mode the depth range
    // test rejects it (nothing drawn); in through mode it is written as 0.
    {
        ScreenVertex a = px(0, 0), b = px(4, 4), d = px(8, 8);
        a.z = 100, b.z = 200, d.z = 300;
        Collector c;
        rasterTriangle(fullScreen(), a, b, d, d, Band{}, c.sink);
        EXPECT_TRUE(c.done().empty());
        RasterParams rp = fullScreen();
        rp.through = true;
        Collector t;
        rasterTriangle(rp, a, b, d, d, Band{}, t.sink);
        ASSERT_EQ(t.done().size(), 18u);
        for (const Fragment& f : t.done()) EXPECT_EQ(f.z, 0);
    }
    // Three equal x (or three equal y) are dropped before rasterising.
    {
        Collector c;
        rasterTriangle(fullScreen(), px(2.4375f, 0), px(2.4375f, 4), px(2.4375f, 8), px(2.4375f, 8), Band{}, c.sink);
        rasterTriangle(fullScreen(), px(0, 2.4375f), px(4, 2.4375f), px(8, 2.4375f), px(8, 2.4375f), Band{}, c.sink);
        EXPECT_TRUE(c.done().empty());
    }
}

TEST(GeoRaster, GouraudColourAndZRounded) {
    // v0 (0,0), v1 (10,0), v2 (0,10) pixels; pixel (2,3) is sampled at (2 + 7/16, 3 + 7/16):
    // barycentrics b1 = 0.24375, b2 = 0.34375, b0 = 0.4125. Colours round to nearest (the
    // reference renderer's float interpolation), and so does Z: the reference converts its float
    // depth with cvtps2dq (round to nearest even), not by truncation.
    ScreenVertex v0 = px(0, 0), v1 = px(10, 0), v2 = px(0, 10);
    v0.color[0] = 0, v1.color[0] = 101, v2.color[0] = 203;  // 24.61875 + 69.78125 = 94.4 → 94
    v0.color[1] = 0, v1.color[1] = 0, v2.color[1] = 2;      // 0.6875 → 1 (rounded, not floored)
    v0.color[3] = v1.color[3] = v2.color[3] = 255;
    v0.z = 1000, v1.z = 2000, v2.z = 3001;                   // 412.5 + 487.5 + 1031.59 → 1932
    v0.secondary[1] = 10, v1.secondary[1] = 20, v2.secondary[1] = 31;  // 4.125 + 4.875 + 10.656 = 19.66 → 20
    RasterParams rp = fullScreen();
    Collector c;
    rasterTriangle(rp, v0, v1, v2, v2, Band{}, c.sink);
    bool found = false;
    for (const Fragment& f : c.done()) {
        if (f.x == 2 && f.y == 3) {
            found = true;
            EXPECT_EQ(f.color[0], 94);
            EXPECT_EQ(f.color[1], 1);
            EXPECT_EQ(f.color[3], 255);
            EXPECT_EQ(f.z, 1932);
            EXPECT_EQ(f.secondary[1], 20);
            EXPECT_EQ(f.fog, 255);  // fog off
        }
    }
    EXPECT_TRUE(found);

    // Flat shading: every pixel gets the provoking (third) vertex's colour; Z still interpolates.
    rp.gouraud = false;
    Collector flat;
    rasterTriangle(rp, v0, v1, v2, v2, Band{}, flat.sink);
    for (const Fragment& f : flat.done()) {
        EXPECT_EQ(f.color[0], 203);
        if (f.x == 2 && f.y == 3) {
            EXPECT_EQ(f.z, 1932);
        }
    }
}

TEST(GeoRaster, FogInterpolatedAndConverted) {
    ScreenVertex v0 = px(0, 0), v1 = px(10, 0), v2 = px(0, 10);
    v0.fog = 1.0f, v1.fog = 0.0f, v2.fog = 0.5f;  // at (2.4375, 3.4375): 0.4125 + 0 + 0.171875 = 0.584375
    RasterParams rp = fullScreen();
    rp.fog = true;
    Collector c;
    rasterTriangle(rp, v0, v1, v2, v2, Band{}, c.sink);
    for (const Fragment& f : c.done())
        if (f.x == 2 && f.y == 3) {
            EXPECT_EQ(f.fog, 149);  // floor(0.584375·256) = 149
        }
    EXPECT_EQ(fogToByte(-0.5f), 0);
    EXPECT_EQ(fogToByte(0.002f), 0);  // below 1/256
    EXPECT_EQ(fogToByte(0.5f), 128);
    EXPECT_EQ(fogToByte(1.0f), 255);
    EXPECT_EQ(fogToByte(7.0f), 255);
}

TEST(GeoRaster, PerspectiveCorrectTextureCoordinates) {
    // Along the top edge y → pixel row 0 with v0 w = 1, v1 w = 3: at the screen-space fraction a
    // the texture coordinate is (a/3) / ((1 − a) + a/3) of the way (perspective-correct).
    ScreenVertex v0 = px(0, 0), v1 = px(16, 0), v2 = px(0, 16);
    v0.w = 1, v1.w = 3, v2.w = 1;
    v0.s = 0, v1.s = 1, v2.s = 0;
    v0.t = v1.t = v2.t = 0.25f;
    RasterParams rp = fullScreen();
    rp.textured = true;
    Collector c;
    rasterTriangle(rp, v0, v1, v2, v2, Band{}, c.sink);
    int checked = 0;
    for (const Fragment& f : c.done()) {
        if (f.y != 0) continue;
        // Sample point (x + 7/16, 7/16): barycentrics b1 = (x + 7/16)/16, b2 = (7/16)/16.
        const double b1 = (f.x + 0.4375) / 16, b2 = 0.4375 / 16, b0 = 1 - b1 - b2;
        const double s = (b1 / 3) / (b0 / 1 + b1 / 3 + b2 / 1);
        EXPECT_NEAR(f.s, s, 1e-6) << f.x;
        EXPECT_NEAR(f.t, 0.25, 1e-6);
        ++checked;
    }
    EXPECT_EQ(checked, 16);  // (15 + 7/16) + 7/16 < 16: pixel 15 is inside the hypotenuse

    // The level of detail (TLEVEL mode 0): a 1:1 linear mapping of a 256-texel texture over 256
    // pixels gives log2(1) = 0; over 64 pixels log2(4) = 2.
    ScreenVertex a = px(0, 0), b = px(256, 0), d = px(0, 256);
    b.s = 1, d.t = 1;
    rp.needLod = true;
    rp.texW0 = rp.texH0 = 256;
    Collector one;
    rasterTriangle(rp, a, b, d, d, Band{}, one.sink);
    for (const Fragment& f : one.done()) ASSERT_NEAR(f.lod, 0.0f, 1e-3);
    b = px(64, 0), d = px(0, 64);
    b.s = 1, d.t = 1;
    Collector four;
    rasterTriangle(rp, a, b, d, d, Band{}, four.sink);
    for (const Fragment& f : four.done()) ASSERT_NEAR(f.lod, 2.0f, 1e-3);
}

TEST(GeoRaster, SlopeModeWPerQuadScreenLinear) {
    // TLEVEL mode 2 takes one W per 2×2 quad (quads start at the triangle box's top-left pixel):
    // clip W interpolated linearly in screen space at the quad's top-left sample point, as the
    // reference renderer does. v0 w = 1, v1 w = 3, v2 w = 1 over a 16-pixel right triangle:
    // at sample (x + 7/16, 7/16) W = 1 + 2·(x + 7/16)/16.
    ScreenVertex v0 = px(0, 0), v1 = px(16, 0), v2 = px(0, 16);
    v0.w = 1, v1.w = 3, v2.w = 1;
    RasterParams rp = fullScreen();
    rp.textured = true;
    rp.needW = true;
    Collector c;
    rasterTriangle(rp, v0, v1, v2, v2, Band{}, c.sink);
    int checked = 0;
    for (const Fragment& f : c.done()) {
        if (f.y > 1 || f.x > 3) continue;
        const double qx = f.x & ~1;  // quads (0,1) and (2,3), rows 0–1
        EXPECT_NEAR(f.w, 1.0 + 2.0 * (qx + 0.4375) / 16.0, 1e-6) << f.x << "," << f.y;
        ++checked;
    }
    EXPECT_EQ(checked, 8);
}

TEST(GeoRaster, TexLog2Approximation) {
    EXPECT_EQ(texLog2(1.0f), 0.0f);
    EXPECT_EQ(texLog2(8.0f), 3.0f);
    EXPECT_EQ(texLog2(0.25f), -2.0f);
    EXPECT_EQ(texLog2(1.5f), 0.5f);  // the mantissa is taken as a linear fraction
    EXPECT_EQ(texLog2(-4.0f), 2.0f); // sign ignored
    EXPECT_EQ(texLog2(0.0f), -127.0f);
}

TEST(GeoRaster, RectangleCoverageAnyVertexOrder) {
    // Corners (1, 1) and (4, 3): columns 1..3, rows 1..2, whichever corner comes first.
    std::set<std::pair<int, int>> expect;
    for (int y = 1; y <= 2; ++y)
        for (int x = 1; x <= 3; ++x) expect.insert({x, y});
    const ScreenVertex c[4] = {px(1, 1), px(4, 1), px(1, 3), px(4, 3)};
    for (int k = 0; k < 4; ++k) {
        Collector col;
        rasterRectangle(fullScreen(), c[k], c[3 - k], Band{}, col.sink);
        EXPECT_EQ(col.pixels(), expect) << k;
    }
    // Fractional corners: a near edge on a pixel centre includes that pixel (1.5 → column 1). A far
    // edge on a centre includes the pixel only when it is the second of a pair counted from the
    // first drawn pixel (the reference renderer's 2×2 quads): 4.5 is column 4, the second of the
    // pair (3, 4), so it is drawn; 3.5 would be column 3, the first of a pair, so it is not.
    Collector frac;
    rasterRectangle(fullScreen(), px(1.5f, 1), px(4.5f, 3), Band{}, frac.sink);
    std::set<std::pair<int, int>> expectFrac = expect;
    for (int y = 1; y <= 2; ++y) expectFrac.insert({4, y});
    EXPECT_EQ(frac.pixels(), expectFrac);
    Collector even;
    rasterRectangle(fullScreen(), px(1.5f, 1), px(3.5f, 3), Band{}, even.sink);
    std::set<std::pair<int, int>> expectEven;
    for (int y = 1; y <= 2; ++y)
        for (int x = 1; x <= 2; ++x) expectEven.insert({x, y});
    EXPECT_EQ(even.pixels(), expectEven);
    // The same in Y: rows from 1 (edge at 1.5) to the edge at 3.5 (row 3 = second of the pair 2, 3).
    Collector rows;
    rasterRectangle(fullScreen(), px(1, 0.5f), px(2, 3.5f), Band{}, rows.sink);
    const std::set<std::pair<int, int>> expectRows = {{1, 0}, {1, 1}, {1, 2}, {1, 3}};
    EXPECT_EQ(rows.pixels(), expectRows);
    // Zero width draws nothing.
    Collector zero;
    rasterRectangle(fullScreen(), px(2, 1), px(2, 5), Band{}, zero.sink);
    EXPECT_TRUE(zero.done().empty());
}

TEST(GeoRaster, RectangleColourZFogFromSecondVertex) {
    ScreenVertex a = px(0, 0), b = px(2, 2);
    a.color[0] = 10, b.color[0] = 200;
    a.z = 5, b.z = 600;
    a.fog = 0.0f, b.fog = 0.5f;
    RasterParams rp = fullScreen();
    rp.fog = true;
    Collector c;
    rasterRectangle(rp, a, b, Band{}, c.sink);
    ASSERT_EQ(c.done().size(), 4u);
    for (const Fragment& f : c.done()) {
        EXPECT_EQ(f.color[0], 200);
        EXPECT_EQ(f.z, 600);
        EXPECT_EQ(f.fog, 128);
    }
}

TEST(GeoRaster, RectangleTextureOrientation) {
    // A 4×4 rectangle with v0 texture (0, 0) and v1 texture (1, 1), for each position of v0
    // relative to v1 (ge-rules.md §8.2). Pixel centres sit at fractions 1/8, 3/8, 5/8, 7/8 of the box.
    RasterParams rp = fullScreen();
    rp.textured = true;
    struct Case {
        ScreenVertex v0, v1;
        // expected (s, t) at pixel (x, y): s = sa + sx·fx + sy·fy, t = ta + tx·fx + ty·fy
        float sa, sx, sy, ta, tx, ty;
    };
    auto mk = [](float x0, float y0, float x1, float y1) {
        ScreenVertex a = px(x0, y0), b = px(x1, y1);
        a.s = 0, a.t = 0, b.s = 1, b.t = 1;
        return std::pair{a, b};
    };
    std::vector<Case> cases;
    {
        auto [a, b] = mk(0, 0, 4, 4);  // left and above: top-left (v0.s, v0.t), S along X, T along Y
        cases.push_back({a, b, 0, 1, 0, 0, 0, 1});
    }
    {
        auto [a, b] = mk(0, 4, 4, 0);  // left and below: top-left (v1.s, v0.t); +X T v0→v1; +Y S v1→v0
        cases.push_back({a, b, 1, 0, -1, 0, 1, 0});
    }
    {
        auto [a, b] = mk(4, 0, 0, 4);  // right and above: top-left (v0.s, v1.t); +X T v1→v0; +Y S v0→v1
        cases.push_back({a, b, 0, 0, 1, 1, -1, 0});
    }
    {
        auto [a, b] = mk(4, 4, 0, 0);  // right and below: top-left (v1.s, v1.t); +X S v1→v0; +Y T v1→v0
        cases.push_back({a, b, 1, -1, 0, 1, 0, -1});
    }
    for (size_t k = 0; k < cases.size(); ++k) {
        const Case& cs = cases[k];
        Collector c;
        rasterRectangle(rp, cs.v0, cs.v1, Band{}, c.sink);
        ASSERT_EQ(c.done().size(), 16u);
        for (const Fragment& f : c.done()) {
            const float fx = (f.x + 0.5f) / 4, fy = (f.y + 0.5f) / 4;
            EXPECT_NEAR(f.s, cs.sa + cs.sx * fx + cs.sy * fy, 1e-6) << "case " << k << " at " << f.x << "," << f.y;
            EXPECT_NEAR(f.t, cs.ta + cs.tx * fx + cs.ty * fy, 1e-6) << "case " << k << " at " << f.x << "," << f.y;
        }
    }
}

TEST(GeoRaster, LinesLeaveOutEndPixel) {
    RasterParams rp = fullScreen();
    Collector h;
    rasterLine(rp, px(0.5f, 0.5f), px(4.5f, 0.5f), Band{}, h.sink);
    EXPECT_EQ(h.pixels(), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
    Collector back;  // the same line drawn right to left: starts at 4, leaves out 0
    rasterLine(rp, px(4.5f, 0.5f), px(0.5f, 0.5f), Band{}, back.sink);
    EXPECT_EQ(back.pixels(), (std::set<std::pair<int, int>>{{4, 0}, {3, 0}, {2, 0}, {1, 0}}));
    Collector diag;
    rasterLine(rp, px(0.5f, 0.5f), px(3.5f, 3.5f), Band{}, diag.sink);
    EXPECT_EQ(diag.pixels(), (std::set<std::pair<int, int>>{{0, 0}, {1, 1}, {2, 2}}));
    Collector zero;
    rasterLine(rp, px(2.5f, 2.5f), px(2.5f, 2.5f), Band{}, zero.sink);
    EXPECT_TRUE(zero.done().empty());
    // Gouraud colour along the line: (c0·(4 − i) + c1·i) / 4; flat: the end vertex.
    ScreenVertex a = px(0.5f, 0.5f), b = px(4.5f, 0.5f);
    a.color[1] = 0, b.color[1] = 255;
    Collector g;
    rasterLine(rp, a, b, Band{}, g.sink);
    std::map<int, int> green;
    for (const Fragment& f : g.done()) green[f.x] = f.color[1];
    EXPECT_EQ(green, (std::map<int, int>{{0, 0}, {1, 63}, {2, 127}, {3, 191}}));
    rp.gouraud = false;
    Collector fl;
    rasterLine(rp, a, b, Band{}, fl.sink);
    for (const Fragment& f : fl.done()) EXPECT_EQ(f.color[1], 255);
}

// The reference renderer walks lines by accumulating (dx, dy) / steps in double precision and
// truncating: from (0, 0) to (1.5, 9) px the X after six steps of 24/9 subpixels is
// 15.999999999999998, still pixel 0, where exact arithmetic would reach pixel 1 (the Virtua
// Tennis frametest's court lines need this walk; docs/accuracy.md).
TEST(GeoRaster, LinesAccumulateTheirStepInDoublePrecision) {
    Collector c;
    rasterLine(fullScreen(), sv16(0, 0), sv16(24, 144), Band{}, c.sink);
    EXPECT_EQ(c.pixels(), (std::set<std::pair<int, int>>{
                              {0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}, {0, 6}, {1, 7}, {1, 8}}));
    // Depth steps the same way and truncates: 0 -> 900 over 9 steps.
    ScreenVertex a = sv16(0, 0), b = sv16(24, 144);
    a.z = 0, b.z = 900;
    Collector z;
    rasterLine(fullScreen(), a, b, Band{}, z.sink);
    for (const Fragment& f : z.done()) EXPECT_EQ(f.z, f.y * 100) << f.y;
    // A line running backwards by less than a pixel is shortened by one subpixel: from x = 2.0
    // px to 1.5 px over 3 rows it starts one subpixel back (1.9375 px) and stays in pixel 1.
    Collector back;
    rasterLine(fullScreen(), sv16(32, 0), sv16(24, 48), Band{}, back.sink);
    EXPECT_EQ(back.pixels(), (std::set<std::pair<int, int>>{{1, 0}, {1, 1}, {1, 2}}));
}

TEST(GeoRaster, PointsCoverOnePixel) {
    Collector c;
    rasterPoint(fullScreen(), px(7.9375f, 3.0f), Band{}, c.sink);
    EXPECT_EQ(c.pixels(), (std::set<std::pair<int, int>>{{7, 3}}));
    Collector neg;  // just left of the screen: not pixel 0
    rasterPoint(fullScreen(), sv16(-1, 5), Band{}, neg.sink);
    EXPECT_TRUE(neg.done().empty());
}

TEST(GeoRaster, ClipRectangleLimitsAllPrimitives) {
    RasterParams rp = fullScreen();
    rp.clipX1 = 2, rp.clipY1 = 3, rp.clipX2 = 5, rp.clipY2 = 6;
    Collector c;
    rasterRectangle(rp, px(0, 0), px(20, 20), Band{}, c.sink);
    rasterTriangle(rp, px(0, 0), px(40, 0), px(0, 40), px(0, 40), Band{}, c.sink);
    rasterLine(rp, px(0.5f, 4.5f), px(19.5f, 4.5f), Band{}, c.sink);
    rasterPoint(rp, px(1, 1), Band{}, c.sink);
    size_t n = 0;
    for (const Fragment& f : c.done()) {
        EXPECT_TRUE(f.x >= 2 && f.x <= 5 && f.y >= 3 && f.y <= 6) << f.x << "," << f.y;
        ++n;
    }
    EXPECT_EQ(n, 16u + 16u + 4u);
}

TEST(GeoRaster, BandsPartitionPixelsExactly) {
    // The same primitives rasterised into 3 bands give, together, exactly the fragments of one
    // band covering everything, each pixel in exactly one band.
    std::mt19937 rng(99);
    std::uniform_int_distribution<int> coord(-100, 120 * 16);
    std::vector<ScreenVertex> tris;
    for (int i = 0; i < 60; ++i) {
        ScreenVertex v = sv16(coord(rng), coord(rng));
        v.color[0] = u8(i * 4), v.z = i * 100;
        tris.push_back(v);
    }
    RasterParams rp = fullScreen();
    auto run = [&](const Band& band) {
        Collector c;
        for (size_t i = 0; i + 2 < tris.size(); i += 3) rasterTriangle(rp, tris[i], tris[i + 1], tris[i + 2], tris[i + 2], band, c.sink);
        for (size_t i = 0; i + 1 < tris.size(); i += 2) rasterRectangle(rp, tris[i], tris[i + 1], band, c.sink);
        for (size_t i = 0; i + 1 < tris.size(); i += 2) rasterLine(rp, tris[i], tris[i + 1], band, c.sink);
        return c.done();
    };
    std::vector<Fragment> whole = run(Band{});
    std::vector<Fragment> parts;
    for (int b = 0; b < 3; ++b) {
        std::vector<Fragment> p = run(Band{b, 3});
        for (const Fragment& f : p) EXPECT_EQ((f.y >> Band::kShift) % 3, b);
        parts.insert(parts.end(), p.begin(), p.end());
    }
    ASSERT_EQ(parts.size(), whole.size());
    auto key = [](const Fragment& f) { return std::tuple{f.y, f.x, f.z, f.color[0]}; };
    std::multiset<std::tuple<int, int, int, int>> a, b;
    for (const Fragment& f : whole) a.insert(key(f));
    for (const Fragment& f : parts) b.insert(key(f));
    EXPECT_TRUE(a == b);
}

// roundHalfEven is std::nearbyint in the default rounding mode for every value a caller converts
// to an integer: ties to even on both signs, the 2^22 boundary, huge values, infinities, and a
// million random floats over ±2^24.
TEST(RoundHalfEven, EqualsNearbyint) {
    auto same = [](float x) {
        const float a = roundHalfEven(x), b = std::nearbyint(x);
        return (std::isnan(a) && std::isnan(b)) || a == b;
    };
    for (float x : {0.5f, 1.5f, 2.5f, -0.5f, -1.5f, -2.5f, 254.5f, 255.5f, 65534.5f, 4194303.5f, 4194304.0f,
                    4194304.5f, -4194303.5f, 8388607.5f, 1e30f, -1e30f, 0.0f, -0.0f, 0.49999997f})
        EXPECT_TRUE(same(x)) << x;
    EXPECT_TRUE(same(INFINITY));
    EXPECT_TRUE(same(-INFINITY));
    EXPECT_TRUE(std::isnan(roundHalfEven(NAN)));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> dist(-16777216.0f, 16777216.0f);
    std::uniform_real_distribution<float> small(-300.0f, 300.0f);
    for (int i = 0; i < 1000000; ++i) {
        const float x = (i & 1) ? dist(rng) : small(rng);
        ASSERT_TRUE(same(x)) << x;
    }
}
