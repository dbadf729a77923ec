// SPDX-License-Identifier: MIT
// make_scenes: writes the project's own GE frame dumps (dumps/*.ppdmp) from scene descriptions
// built with ge::ListBuilder. Every scene draws a 480×272 frame into the 8888 frame buffer at
// VRAM 0x04000000 (stride 512); all data (vertices, textures, palettes) is generated here, so the
// output bytes are deterministic. docs/scenes.md says what each scene shows and exercises.
//
// Usage: make_scenes [--out DIR] [--list]      (DIR defaults to <source>/dumps)
//
// Each scene is built once: the builder places data in a private guest memory, emits the list,
// and a DumpRecorder turns the same command stream into records. The list is then executed on a
// GeEngine (no renderer) as a sanity check that it runs to FINISH without errors.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "hle/dump/dump_writer.h"
#include "hle/ge_engine.h"
#include "hle/list_builder.h"

#ifndef GE2GL_SOURCE_DIR
#define GE2GL_SOURCE_DIR "."
#endif

using namespace ge;

namespace {

// ---------------------------------------------------------------------------------------------
// Small column-major 4×4 matrix maths (m[4·col + row]) for cameras and bones.

struct Mat4 {
    float m[16];
};
struct Vec3 {
    float x, y, z;
};

Mat4 identity() {
    Mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.f;
    return r;
}
Mat4 mul(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}
Mat4 translate(float x, float y, float z) {
    Mat4 r = identity();
    r.m[12] = x;
    r.m[13] = y;
    r.m[14] = z;
    return r;
}
Mat4 rotX(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[5] = c;
    r.m[6] = s;
    r.m[9] = -s;
    r.m[10] = c;
    return r;
}
Mat4 rotY(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[0] = c;
    r.m[2] = -s;
    r.m[8] = s;
    r.m[10] = c;
    return r;
}
Mat4 rotZ(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[0] = c;
    r.m[1] = s;
    r.m[4] = -s;
    r.m[5] = c;
    return r;
}
// OpenGL-style perspective: clip z in [−w, w] between near and far (docs/ge-rules.md §8.5).
Mat4 perspective(float fovyDeg, float aspect, float n, float f) {
    Mat4 r{};
    float t = 1.f / std::tan(fovyDeg * 3.14159265f / 360.f);
    r.m[0] = t / aspect;
    r.m[5] = t;
    r.m[10] = (f + n) / (n - f);
    r.m[11] = -1.f;
    r.m[14] = 2.f * f * n / (n - f);
    return r;
}
Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 norm(Vec3 a) {
    float l = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return l > 0 ? Vec3{a.x / l, a.y / l, a.z / l} : Vec3{0, 0, 1};
}
float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Mat4 lookAt(Vec3 eye, Vec3 center, Vec3 up) {
    Vec3 f = norm(sub(center, eye));
    Vec3 s = norm(cross(f, up));
    Vec3 u = cross(s, f);
    Mat4 r = identity();
    r.m[0] = s.x;
    r.m[4] = s.y;
    r.m[8] = s.z;
    r.m[1] = u.x;
    r.m[5] = u.y;
    r.m[9] = u.z;
    r.m[2] = -f.x;
    r.m[6] = -f.y;
    r.m[10] = -f.z;
    r.m[12] = -dot(s, eye);
    r.m[13] = -dot(u, eye);
    r.m[14] = dot(f, eye);
    return r;
}
// 3×4 GE element order (element k = row k%3, column k/3) from a column-major 4×4.
void to3x4(const Mat4& a, float out[12]) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) out[c * 3 + r] = a.m[c * 4 + r];
}

constexpr float kPi = 3.14159265f;

// ---------------------------------------------------------------------------------------------
// Procedural textures and pixel helpers. Colours are ABGR8888 (R in bits 7..0).

u32 rgba(u32 r, u32 g, u32 b, u32 a = 255) { return (r & 255) | (g & 255) << 8 | (b & 255) << 16 | (a & 255) << 24; }
u16 to5650(u32 c) { return u16(((c & 255) >> 3) | (((c >> 8) & 255) >> 2) << 5 | (((c >> 16) & 255) >> 3) << 11); }
u16 to5551(u32 c) {
    return u16(((c & 255) >> 3) | (((c >> 8) & 255) >> 3) << 5 | (((c >> 16) & 255) >> 3) << 10 | ((c >> 31) << 15));
}
u16 to4444(u32 c) {
    return u16(((c & 255) >> 4) | (((c >> 8) & 255) >> 4) << 4 | (((c >> 16) & 255) >> 4) << 8 | ((c >> 28) << 12));
}
// Standard 565 as used by DXT endpoints (red in bits 15..11, ge-rules.md §6.5).
u16 dxt565(u32 r, u32 g, u32 b) { return u16((r >> 3) << 11 | (g >> 2) << 5 | (b >> 3)); }

// A hue wheel colour for i in 0..n-1.
u32 hue(u32 i, u32 n, u32 a = 255) {
    float h = float(i % n) / float(n) * 6.f;
    int k = int(h);
    float f = h - float(k);
    u32 up = u32(f * 255.f), down = 255 - up;
    switch (k % 6) {
    case 0: return rgba(255, up, 0, a);
    case 1: return rgba(down, 255, 0, a);
    case 2: return rgba(0, 255, up, a);
    case 3: return rgba(0, down, 255, a);
    case 4: return rgba(up, 0, 255, a);
    default: return rgba(255, 0, down, a);
    }
}

std::vector<u8> bytes32(const std::vector<u32>& px) {
    std::vector<u8> out(px.size() * 4);
    for (size_t i = 0; i < px.size(); ++i) writeLE32(&out[i * 4], px[i]);
    return out;
}
std::vector<u8> bytes16(const std::vector<u16>& px) {
    std::vector<u8> out(px.size() * 2);
    for (size_t i = 0; i < px.size(); ++i) writeLE16(&out[i * 2], px[i]);
    return out;
}

// Swizzles a linear texture (pitch in bytes, rows) into the GE's 16-byte × 8-row blocks
// (ge-rules.md §6.3).
std::vector<u8> swizzle(const std::vector<u8>& lin, u32 pitch, u32 rows) {
    std::vector<u8> out(lin.size(), 0);
    const u32 blocksPerRow = pitch / 16;
    for (u32 y = 0; y < rows; ++y)
        for (u32 xb = 0; xb < pitch; ++xb) {
            u32 off = ((y / 8) * blocksPerRow + xb / 16) * 128 + (y % 8) * 16 + xb % 16;
            out[off] = lin[y * pitch + xb];
        }
    return out;
}

// 8888 texture: a checkerboard of two colours with a diagonal gradient in alpha/brightness.
std::vector<u32> checker(u32 w, u32 h, u32 cell, u32 c0, u32 c1) {
    std::vector<u32> px(w * h);
    for (u32 y = 0; y < h; ++y)
        for (u32 x = 0; x < w; ++x) px[y * w + x] = (((x / cell) ^ (y / cell)) & 1) ? c1 : c0;
    return px;
}

// A "target" picture: rings of hue with a cross, a good magnification/filter test.
std::vector<u32> rings(u32 w, u32 h, u32 alphaMode) {
    std::vector<u32> px(w * h);
    for (u32 y = 0; y < h; ++y)
        for (u32 x = 0; x < w; ++x) {
            float dx = float(x) + 0.5f - float(w) / 2, dy = float(y) + 0.5f - float(h) / 2;
            u32 r = u32(std::sqrt(dx * dx + dy * dy) * 8.f / float(w));
            u32 c = hue(r * 3 + (x * 4 / w), 12);
            if (x == w / 2 || y == h / 2) c = rgba(255, 255, 255);
            u32 a = 255;
            if (alphaMode == 1) a = (x * 255) / (w - 1);
            if (alphaMode == 2) a = ((x + y) & 4) ? 255 : 0;
            px[y * w + x] = (c & 0xFFFFFF) | a << 24;
        }
    return px;
}

// Mip chain of an 8888 texture by 2×2 box filtering.
std::vector<u32> halve(const std::vector<u32>& src, u32 w, u32 h) {
    std::vector<u32> out((w / 2) * (h / 2));
    for (u32 y = 0; y < h / 2; ++y)
        for (u32 x = 0; x < w / 2; ++x) {
            u32 acc[4] = {};
            for (u32 k = 0; k < 4; ++k) {
                u32 p = src[(2 * y + k / 2) * w + 2 * x + k % 2];
                for (int c = 0; c < 4; ++c) acc[c] += (p >> (8 * c)) & 255;
            }
            out[y * (w / 2) + x] = rgba(acc[0] / 4, acc[1] / 4, acc[2] / 4, acc[3] / 4);
        }
    return out;
}

// PSP-order DXT blocks (ge-rules.md §6.5), generated directly: endpoints from the block
// position, 2-bit indices from the texel position.
std::vector<u8> makeDxt(u32 fmt, u32 w, u32 h, bool punchThrough) {
    const u32 bw = w / 4, bh = h / 4, blockBytes = fmt == GE_TFMT_DXT1 ? 8 : 16;
    std::vector<u8> out(size_t(bw) * bh * blockBytes);
    for (u32 by = 0; by < bh; ++by)
        for (u32 bx = 0; bx < bw; ++bx) {
            u8* b = &out[(by * bw + bx) * blockBytes];
            u32 c0 = hue(bx + by, bw + bh), c1 = hue(bx + by + (bw + bh) / 2, bw + bh);
            u16 e0 = dxt565(c0 & 255, (c0 >> 8) & 255, (c0 >> 16) & 255);
            u16 e1 = dxt565(((c1 & 255) * 3) / 4, (((c1 >> 8) & 255) * 3) / 4, (((c1 >> 16) & 255) * 3) / 4);
            // Four-colour mode needs e0 > e1; the punch-through mode (DXT1 alpha) e0 <= e1.
            bool want4 = !(punchThrough && ((bx + by) & 1));
            if ((e0 > e1) != want4) std::swap(e0, e1);
            if (e0 == e1) e1 ^= 0x0821;
            if ((e0 > e1) != want4) std::swap(e0, e1);
            // Colour indices: a C0 → C1 ramp across each block row (index order 0, 2, 3, 1 in
            // four-colour mode); punch-through blocks use 0, 2, 1, 3 so column 3 is transparent.
            static constexpr u8 ramp4[4] = {0, 2, 3, 1}, ramp3[4] = {0, 2, 1, 3};
            const u8* ramp = want4 ? ramp4 : ramp3;
            for (u32 r = 0; r < 4; ++r) {
                u8 bits = 0;
                for (u32 x = 0; x < 4; ++x) bits |= u8(ramp[(x + (r & 1)) & 3] << (2 * x));
                b[r] = bits;
            }
            writeLE16(b + 4, e0);
            writeLE16(b + 6, e1);
            if (fmt == GE_TFMT_DXT3) {
                // 4-bit alpha: a vertical ramp over the whole texture.
                for (u32 r = 0; r < 4; ++r) {
                    u16 row = 0;
                    const u32 a = ((by * 4 + r) * 15) / (h - 1);
                    for (u32 x = 0; x < 4; ++x) row |= u16(((a + (x & 1)) & 15) << (4 * x));
                    writeLE16(b + 8 + 2 * r, row);
                }
            } else if (fmt == GE_TFMT_DXT5) {
                // 3-bit alpha indices: a horizontal ramp over each block.
                u64 idx = 0;
                for (u32 i = 0; i < 16; ++i) idx |= u64((i % 4) * 2 + (i / 8)) << (3 * i);
                for (int k = 0; k < 6; ++k) b[8 + k] = u8(idx >> (8 * k));
                bool eightMode = ((bx ^ by) & 1) == 0;
                b[14] = eightMode ? 255 : 40;   // A0
                b[15] = eightMode ? 16 : 230;   // A1 (A0 > A1: 8-value ramp; else 6 values + 0/255)
            }
        }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Scene plumbing

constexpr u32 kFb = 0x000000;       // VRAM offset of the displayed 8888 buffer (stride 512)
constexpr u32 kZb = 0x110000;       // depth buffer
constexpr u32 kOff0 = 0x154000;     // off-screen buffers for render passes
constexpr u32 kOff1 = 0x180000;

// Vertex formats used by the 2D helpers.
constexpr u32 kVt2dCol = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
constexpr u32 kVt2dTex = vt::TC_16 | vt::COL_8888 | vt::POS_16 | vt::THROUGH;

// The state every scene starts from: sceGuInit-like frame setup for a 480×272 8888 frame.
void standardSetup(ListBuilder& b) {
    b.drawBuffer(GE_FORMAT_8888, kFb, 512);
    b.depthBuffer(kZb, 512);
    b.offset(2048 - 240, 2048 - 136);
    b.viewport(2048, 2048, 480, 272);
    b.depthRange(65535, 0);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.enable(GE_CMD_CLE, true);
    b.shadeModel(true);
    b.pixelMask(0, 0);
    b.texScale(1, 1);
    b.texOffset(0, 0);
    b.texMapMode(0);
    b.texLevelMode(0, 0);
    const int sdkDither[16] = {-4, 0, -3, 1, 2, -2, 3, -1, -3, 1, -4, 0, 3, -1, 2, -2};
    b.setDither(sdkDither);
    const Mat4 id = identity();
    b.setMatrix(GeMatrix::World, id.m);
    b.setMatrix(GeMatrix::View, id.m);
    b.setMatrix(GeMatrix::Proj, id.m);
    b.setMatrix(GeMatrix::TexGen, id.m);
}

// Axis-aligned through-mode rectangle with a flat colour (second vertex's colour, ge-rules.md §8.1).
void rect(ListBuilder& b, int x, int y, int w, int h, u32 color) {
    BuildVertex v[2];
    v[0].x = float(x);
    v[0].y = float(y);
    v[1].x = float(x + w);
    v[1].y = float(y + h);
    v[0].color = v[1].color = color;
    auto data = packVertices(kVt2dCol, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, kVt2dCol, 2, nullptr, data.data());
}

// Through-mode textured rectangle: texels (u0,v0)-(u1,v1) stretched over the pixel rectangle.
void texRect(ListBuilder& b, int x, int y, int w, int h, float u0, float v0, float u1, float v1, u32 color = 0xFFFFFFFF) {
    BuildVertex v[2];
    v[0].x = float(x);
    v[0].y = float(y);
    v[1].x = float(x + w);
    v[1].y = float(y + h);
    v[0].u = u0;
    v[0].v = v0;
    v[1].u = u1;
    v[1].v = v1;
    v[0].color = v[1].color = color;
    auto data = packVertices(kVt2dTex, v, 2);
    b.drawArrayData(GE_PRIM_RECTANGLES, kVt2dTex, 2, nullptr, data.data());
}

// Gouraud quad in through mode as a triangle strip with four corner colours (tl, tr, bl, br).
void gradQuad(ListBuilder& b, int x, int y, int w, int h, u32 tl, u32 tr, u32 bl, u32 br) {
    BuildVertex v[4];
    const int xs[4] = {x, x + w, x, x + w}, ys[4] = {y, y, y + h, y + h};
    const u32 cs[4] = {tl, tr, bl, br};
    for (int i = 0; i < 4; ++i) {
        v[i].x = float(xs[i]);
        v[i].y = float(ys[i]);
        v[i].color = cs[i];
    }
    auto data = packVertices(kVt2dCol, v, 4);
    b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, kVt2dCol, 4, nullptr, data.data());
}

// Places a texture level's bytes in the arena and points level n at it.
u32 placeTexture(ListBuilder& b, u32 level, const std::vector<u8>& data, u32 w, u32 h, u32 bufw) {
    u32 addr = b.place(data.data(), u32(data.size()), 16);
    b.setTexture(level, addr, w, h, bufw);
    return addr;
}

// Triangle-list grid helper: (n+1)×(m+1) vertices, 16-bit indices.
std::vector<u16> gridIndices(u32 n, u32 m) {
    std::vector<u16> idx;
    for (u32 j = 0; j < m; ++j)
        for (u32 i = 0; i < n; ++i) {
            u16 a = u16(j * (n + 1) + i), bb = u16(a + 1), c = u16(a + n + 1), d = u16(c + 1);
            idx.insert(idx.end(), {a, c, bb, bb, c, d});
        }
    return idx;
}

Mat4 sceneProjection() { return perspective(60.f, 480.f / 272.f, 0.5f, 30.f); }

// =============================================================================================
// Scene 1: lit_textured_skinned

void sceneLitTexturedSkinned(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(24, 32, 48), 0);

    const Mat4 proj = sceneProjection();
    const Mat4 view = lookAt({0.f, 2.2f, 5.5f}, {0.f, 0.7f, 0.f}, {0.f, 1.f, 0.f});
    b.setMatrix(GeMatrix::Proj, proj.m);
    b.setMatrix(GeMatrix::View, view.m);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);  // GEQUAL: depthRange(65535, 0) puts near objects at high Z
    b.depthMask(false);

    // Lighting: global ambient, a directional light with specular, a red point light with
    // attenuation, and a cyan spot light aimed at the floor.
    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(40, 40, 48));
    b.materialAmbient(rgba(255, 255, 255));
    b.materialDiffuse(rgba(230, 230, 230));
    b.materialSpecular(rgba(255, 255, 255));
    b.materialEmissive(0);
    b.colorMaterial(0);
    b.specularPower(20.f);
    b.lightMode(true);  // separate specular: goes to the secondary colour, added after texturing

    const float dirPos[3] = {-0.4f, 1.f, 0.7f};
    b.light(0, 0, 1, dirPos);
    b.lightColor(0, LIGHT_AMBIENT, rgba(0, 0, 0));
    b.lightColor(0, LIGHT_DIFFUSE, rgba(150, 150, 140));
    b.lightColor(0, LIGHT_SPECULAR, rgba(255, 255, 255));

    const float pointPos[3] = {1.6f, 0.9f, 1.2f};
    b.light(1, 1, 1, pointPos);
    b.lightColor(1, LIGHT_AMBIENT, rgba(20, 0, 0));
    b.lightColor(1, LIGHT_DIFFUSE, rgba(255, 60, 40));
    b.lightColor(1, LIGHT_SPECULAR, rgba(255, 160, 120));
    b.lightAtt(1, 0.6f, 0.3f, 0.15f);

    // LD points from the lit floor back toward the light (a PSP's sign, pspautotests
    // gpu/commands/light: cos = LD·(light − vertex); the manual's 9-4 reads the other way).
    const float spotPos[3] = {-1.6f, 3.f, 0.6f};
    const float spotDir[3] = {-0.35f, 1.f, 0.15f};
    b.light(2, 2, 0, spotPos);
    b.lightColor(2, LIGHT_AMBIENT, rgba(0, 0, 0));
    b.lightColor(2, LIGHT_DIFFUSE, rgba(40, 220, 255));
    b.lightColor(2, LIGHT_SPECULAR, rgba(0, 0, 0));
    b.lightAtt(2, 1.f, 0.f, 0.f);
    b.lightSpot(2, spotDir, 6.f, 0.82f);
    for (u32 n = 0; n < 3; ++n) b.enable(u8(GE_CMD_LE0 + n), true);
    b.enable(GE_CMD_LE0 + 3, false);

    // Texturing: modulate, trilinear mip-mapped floor texture (3 levels).
    b.enable(GE_CMD_TME, true);
    b.texFunc(0, false);
    b.texWrap(false, false);

    // ---- floor: 16×16 grid, y = 0, float UV/normal/position, 16-bit indices ----
    {
        std::vector<u32> l0 = checker(64, 64, 8, rgba(235, 225, 200), rgba(90, 110, 140));
        for (u32 y = 0; y < 64; ++y)  // a thin diagonal accent so the mip levels differ visibly
            for (u32 x = 0; x < 64; ++x)
                if (((x + y) & 31) < 2) l0[y * 64 + x] = rgba(200, 60, 40);
        std::vector<u32> l1 = halve(l0, 64, 64), l2 = halve(l1, 32, 32);
        b.texMode(GE_TFMT_8888, 2, false);
        placeTexture(b, 0, bytes32(l0), 64, 64, 64);
        placeTexture(b, 1, bytes32(l1), 32, 32, 32);
        placeTexture(b, 2, bytes32(l2), 16, 16, 16);
        b.texFilter(7, 1);  // LINEAR_MIPMAP_LINEAR / LINEAR
        b.texLevelMode(0, 0.f);

        const u32 n = 16;
        std::vector<BuildVertex> v;
        for (u32 j = 0; j <= n; ++j)
            for (u32 i = 0; i <= n; ++i) {
                BuildVertex p;
                p.x = -3.5f + 7.f * float(i) / n;
                p.z = -4.f + 7.f * float(j) / n;
                p.y = 0.f;
                p.nx = 0;
                p.ny = 1;
                p.nz = 0;
                p.u = 4.f * float(i) / n;
                p.v = 4.f * float(j) / n;
                v.push_back(p);
            }
        const u32 vtype = vt::TC_F | vt::NRM_F | vt::POS_F | vt::IDX_16;
        auto data = packVertices(vtype, v.data(), u32(v.size()));
        auto idx = gridIndices(n, n);
        b.setMatrix(GeMatrix::World, identity().m);
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
    }

    // ---- skinned arm: a cylinder on two bones, u8 weights, 16-bit UV and normal ----
    {
        // Texture: swizzled 5650 stripes, single level, bilinear.
        std::vector<u16> tex(32 * 32);
        for (u32 y = 0; y < 32; ++y)
            for (u32 x = 0; x < 32; ++x) {
                u32 c = ((y / 4) & 1) ? rgba(250, 200, 60) : rgba(60, 120, 230);
                if ((x / 8) & 1) c = rgba(((c & 255) * 3) / 4, (((c >> 8) & 255) * 3) / 4, (((c >> 16) & 255) * 3) / 4);
                tex[y * 32 + x] = to5650(c);
            }
        b.texMode(GE_TFMT_5650, 0, true);
        placeTexture(b, 0, swizzle(bytes16(tex), 64, 32), 32, 32, 32);
        b.texFilter(1, 1);

        // Bone 0 holds the lower half, bone 1 bends the upper half around the joint at y = 1.
        const Mat4 bone0 = identity();
        const Mat4 bone1 = mul(translate(0, 1.f, 0), mul(rotZ(0.75f), translate(0, -1.f, 0)));
        float m[12];
        to3x4(bone0, m);
        b.setBoneMatrix(0, m);
        to3x4(bone1, m);
        b.setBoneMatrix(1, m);

        const u32 seg = 12, rings = 10;
        std::vector<BuildVertex> v;
        for (u32 r = 0; r <= rings; ++r)
            for (u32 s = 0; s <= seg; ++s) {
                float a = 2.f * kPi * float(s) / seg, y = 2.f * float(r) / rings;
                BuildVertex p;
                p.x = 0.28f * std::cos(a);
                p.z = 0.28f * std::sin(a);
                p.y = y;
                p.nx = std::cos(a);
                p.ny = 0;
                p.nz = std::sin(a);
                p.u = float(s) / seg;
                p.v = float(r) / rings * 1.5f;
                float w1 = std::clamp((y - 0.7f) / 0.6f, 0.f, 1.f);
                p.w[0] = 1.f - w1;
                p.w[1] = w1;
                v.push_back(p);
            }
        const u32 vtype = vt::W_8 | vt::weights(2) | vt::TC_16 | vt::NRM_16 | vt::POS_F | vt::IDX_16;
        auto data = packVertices(vtype, v.data(), u32(v.size()));
        auto idx = gridIndices(seg, rings);
        // World: stand the arm slightly left of centre, turned towards the camera.
        b.setMatrix(GeMatrix::World, mul(translate(-0.6f, 0.f, 0.3f), rotY(0.4f)).m);
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
    }

    // ---- a second skinned object with float weights: a bent box on the right, vertex colours ----
    {
        b.enable(GE_CMD_TME, false);
        b.colorMaterial(3);  // ambient + diffuse from the vertex colour
        const Mat4 bone0 = identity();
        const Mat4 bone1 = mul(translate(0, 0.6f, 0), mul(rotX(-0.6f), translate(0, -0.6f, 0)));
        float m[12];
        to3x4(bone0, m);
        b.setBoneMatrix(0, m);
        to3x4(bone1, m);
        b.setBoneMatrix(1, m);

        // Box from y 0..1.2 as 6 faces × 2×2 quads, flat normals per face.
        std::vector<BuildVertex> v;
        std::vector<u16> idx;
        const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        const u32 faceCol[6] = {rgba(240, 80, 80), rgba(80, 240, 80), rgba(240, 240, 90),
                                rgba(90, 90, 240), rgba(240, 140, 40), rgba(200, 90, 220)};
        for (int f = 0; f < 6; ++f) {
            Vec3 nrm = normals[f];
            Vec3 t1 = std::fabs(nrm.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            Vec3 t2 = cross(nrm, t1);
            u16 base = u16(v.size());
            for (int j = 0; j <= 2; ++j)
                for (int i = 0; i <= 2; ++i) {
                    float s = float(i) - 1.f, t = float(j) - 1.f;
                    BuildVertex p;
                    p.x = 0.3f * (nrm.x + s * t1.x + t * t2.x);
                    p.y = 0.6f + 0.6f * (nrm.y + s * t1.y + t * t2.y);
                    p.z = 0.3f * (nrm.z + s * t1.z + t * t2.z);
                    p.nx = nrm.x;
                    p.ny = nrm.y;
                    p.nz = nrm.z;
                    p.color = faceCol[f];
                    float w1 = std::clamp(p.y / 1.2f, 0.f, 1.f);
                    p.w[0] = 1.f - w1;
                    p.w[1] = w1;
                    v.push_back(p);
                }
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) {
                    u16 a = u16(base + j * 3 + i);
                    idx.insert(idx.end(), {a, u16(a + 3), u16(a + 1), u16(a + 1), u16(a + 3), u16(a + 4)});
                }
        }
        const u32 vtype = vt::W_F | vt::weights(2) | vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::IDX_16;
        auto data = packVertices(vtype, v.data(), u32(v.size()));
        b.setMatrix(GeMatrix::World, mul(translate(1.1f, 0.f, 0.4f), rotY(-0.5f)).m);
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
    }

    b.enable(GE_CMD_LTE, false);
    b.finish();
}

// =============================================================================================
// Scene 2: clut_dxt_sprites

void sceneClutDxtSprites(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(0, 0, 0), 0);
    // A gouraud background so alpha shows.
    gradQuad(b, 0, 0, 480, 272, rgba(40, 40, 80), rgba(120, 40, 40), rgba(30, 90, 60), rgba(200, 200, 200));

    b.enable(GE_CMD_TME, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);  // ADD, As, 1 − As
    b.texFunc(0, true);    // MODULATE, RGBA
    b.texWrap(false, false);
    b.texLevelMode(1, 0.f);  // constant level 0

    const int cell = 52, pitchX = 60, pitchY = 88, x0 = 4, y0 = 10;
    auto cx = [&](int c) { return x0 + c * pitchX; };
    auto cy = [&](int r) { return y0 + r * pitchY; };

    // ---- palettes ----
    std::vector<u16> pal16a(16), pal16b(32);
    for (u32 i = 0; i < 16; ++i) pal16a[i] = to5650(hue(i, 16));
    for (u32 i = 0; i < 32; ++i) pal16b[i] = to4444(i < 16 ? rgba(255, 0, 255) : hue(i * 3, 48, 128 + (i - 16) * 8));
    std::vector<u32> pal32(256);
    // Low nibble picks the hue, high nibble shifts it a little: masks/shifts of the index give
    // visibly different pictures.
    for (u32 i = 0; i < 256; ++i) pal32[i] = hue((i & 15) * 16 + (i >> 4), 256, 255 - (i >> 4) * 4);
    std::vector<u16> pal5551(256);
    for (u32 i = 0; i < 256; ++i) pal5551[i] = to5551(hue(255 - i, 256, (i & 8) ? 255 : 0));
    const u32 palA = b.place(bytes16(pal16a).data(), 32, 16);
    const u32 palB = b.place(bytes16(pal16b).data(), 64, 16);
    const u32 pal32Addr = b.place(bytes32(pal32).data(), 1024, 16);
    const u32 pal5551Addr = b.place(bytes16(pal5551).data(), 512, 16);

    // ---- index textures ----
    // CLUT4 32×32: 16 concentric bands.
    std::vector<u8> t4(32 * 32 / 2);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) {
            u32 d = u32(std::abs(int(x) - 16) + std::abs(int(y) - 16)) / 2;
            u32 v = d & 15;
            t4[(y * 32 + x) / 2] |= u8(v << ((x & 1) * 4));
        }
    // CLUT8 64×64: angle/radius pattern.
    std::vector<u8> t8(64 * 64);
    for (u32 y = 0; y < 64; ++y)
        for (u32 x = 0; x < 64; ++x) {
            float dx = float(x) - 31.5f, dy = float(y) - 31.5f;
            float ang = std::atan2(dy, dx) / (2 * kPi) + 0.5f;
            u32 r = u32(std::sqrt(dx * dx + dy * dy) / 2.f);
            t8[y * 64 + x] = u8((u32(ang * 240.f) & 0xF0) | (r & 0x0F));
        }
    // CLUT16 32×32: index in bits 11..4 (shift 4), junk in the other bits.
    std::vector<u16> t16(32 * 32);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) t16[y * 32 + x] = u16((((x * 8) ^ (y * 4)) & 0xFF) << 4 | 0xF00F);
    // CLUT32 32×32: index in bits 23..16 (shift 16).
    std::vector<u32> t32(32 * 32);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) t32[y * 32 + x] = ((x * 8 + y) & 0xFF) << 16 | 0xAB00CD12u;

    const u32 t4Addr = b.place(t4.data(), u32(t4.size()), 16);
    const auto t4sw = swizzle(t4, 16, 32);
    const u32 t4SwAddr = b.place(t4sw.data(), u32(t4sw.size()), 16);
    const u32 t8Addr = b.place(t8.data(), u32(t8.size()), 16);
    const auto t8sw = swizzle(t8, 64, 64);
    const u32 t8SwAddr = b.place(t8sw.data(), u32(t8sw.size()), 16);
    const auto t16b = bytes16(t16);
    const u32 t16Addr = b.place(t16b.data(), u32(t16b.size()), 16);
    const auto t32b = bytes32(t32);
    const u32 t32Addr = b.place(t32b.data(), u32(t32b.size()), 16);

    // ---- row 0: CLUT formats ----
    // c0: CLUT4, 5650 palette, nearest.
    b.clutMode(GE_FORMAT_565, 0, 0x0F, 0);
    b.clutLoad(palA, 1);  // 16 entries × 2 bytes = one 32-byte block
    b.texMode(GE_TFMT_CLUT4, 0, false);
    b.setTexture(0, t4Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, cx(0), cy(0), cell, cell, 0, 0, 32, 32);
    // c1: CLUT4, 4444 palette, start 1 (entries 16–31 OR-ed in, ge-rules.md §6.4), bilinear, swizzled.
    b.clutMode(GE_FORMAT_4444, 0, 0x0F, 1);
    b.clutLoad(palB, 2);
    b.texMode(GE_TFMT_CLUT4, 0, true);
    b.setTexture(0, t4SwAddr, 32, 32, 32);
    b.texFilter(1, 1);
    texRect(b, cx(1), cy(0), cell, cell, 0, 0, 32, 32);
    // c2: CLUT8, 8888 palette, linear storage, nearest.
    b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
    b.clutLoad(pal32Addr, 32);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.setTexture(0, t8Addr, 64, 64, 64);
    b.texFilter(0, 0);
    texRect(b, cx(2), cy(0), cell, cell, 0, 0, 64, 64);
    // c3: CLUT8 swizzled, shift 4 mask 0x0F (angle bands only), bilinear.
    b.clutMode(GE_FORMAT_8888, 4, 0x0F, 0);
    b.texMode(GE_TFMT_CLUT8, 0, true);
    b.setTexture(0, t8SwAddr, 64, 64, 64);
    b.texFilter(1, 1);
    texRect(b, cx(3), cy(0), cell, cell, 0, 0, 64, 64);
    // c4: CLUT8 mask 0x0F with start 2 and shift 0 (radius bands from entries 32–47).
    b.clutMode(GE_FORMAT_8888, 0, 0x0F, 2);
    b.texMode(GE_TFMT_CLUT8, 0, false);
    b.setTexture(0, t8Addr, 64, 64, 64);
    b.texFilter(0, 0);
    texRect(b, cx(4), cy(0), cell, cell, 0, 0, 64, 64);
    // c5: CLUT16, 5551 palette (alpha 0/255), shift 4, mask 0xFF.
    b.clutMode(GE_FORMAT_5551, 4, 0xFF, 0);
    b.clutLoad(pal5551Addr, 16);
    b.texMode(GE_TFMT_CLUT16, 0, false);
    b.setTexture(0, t16Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, cx(5), cy(0), cell, cell, 0, 0, 32, 32);
    // c6: CLUT32, 8888 palette reloaded, shift 16, mask 0xFF, bilinear.
    b.clutMode(GE_FORMAT_8888, 16, 0xFF, 0);
    b.clutLoad(pal32Addr, 32);
    b.texMode(GE_TFMT_CLUT32, 0, false);
    b.setTexture(0, t32Addr, 32, 32, 32);
    b.texFilter(1, 1);
    texRect(b, cx(6), cy(0), cell, cell, 0, 0, 32, 32);
    // c7: CLUT4 repeated 2×2 with the 5650 palette reloaded (palette RAM reuse after a bigger load).
    b.clutMode(GE_FORMAT_565, 0, 0x0F, 0);
    b.clutLoad(palA, 1);
    b.texMode(GE_TFMT_CLUT4, 0, false);
    b.setTexture(0, t4Addr, 32, 32, 32);
    b.texFilter(0, 0);
    texRect(b, cx(7), cy(0), cell, cell, 0, 0, 64, 64);

    // ---- row 1: DXT and direct-colour formats ----
    const auto dxt1 = makeDxt(GE_TFMT_DXT1, 32, 32, false);
    const auto dxt1a = makeDxt(GE_TFMT_DXT1, 32, 32, true);
    const auto dxt3 = makeDxt(GE_TFMT_DXT3, 32, 32, false);
    const auto dxt5 = makeDxt(GE_TFMT_DXT5, 32, 32, false);
    b.texFilter(0, 0);
    b.texMode(GE_TFMT_DXT1, 0, false);
    placeTexture(b, 0, dxt1, 32, 32, 32);
    texRect(b, cx(0), cy(1), cell, cell, 0, 0, 32, 32);
    // DXT1 with punch-through alpha, plus an alpha test that drops the transparent texels.
    b.enable(GE_CMD_ATE, true);
    b.alphaFunc(6, 0x10, 0xFF);  // GREATER 0x10
    placeTexture(b, 0, dxt1a, 32, 32, 32);
    texRect(b, cx(1), cy(1), cell, cell, 0, 0, 32, 32);
    b.enable(GE_CMD_ATE, false);
    b.texMode(GE_TFMT_DXT3, 0, false);
    placeTexture(b, 0, dxt3, 32, 32, 32);
    texRect(b, cx(2), cy(1), cell, cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_DXT5, 0, false);
    b.texFilter(1, 1);
    placeTexture(b, 0, dxt5, 32, 32, 32);
    texRect(b, cx(3), cy(1), cell, cell, 0, 0, 32, 32);

    const std::vector<u32> pic = rings(32, 32, 0), picA = rings(32, 32, 1), picB = rings(32, 32, 2);
    std::vector<u16> p5650(32 * 32), p5551(32 * 32), p4444(32 * 32);
    for (u32 i = 0; i < 32 * 32; ++i) {
        p5650[i] = to5650(pic[i]);
        p5551[i] = to5551(picB[i]);
        p4444[i] = to4444(picA[i]);
    }
    b.texFilter(0, 0);
    b.texMode(GE_TFMT_5650, 0, false);
    placeTexture(b, 0, bytes16(p5650), 32, 32, 32);
    texRect(b, cx(4), cy(1), cell, cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_5551, 0, true);
    placeTexture(b, 0, swizzle(bytes16(p5551), 64, 32), 32, 32, 32);
    texRect(b, cx(5), cy(1), cell, cell, 0, 0, 32, 32);
    b.texFilter(1, 1);
    b.texMode(GE_TFMT_4444, 0, false);
    // Buffer width 64 > texture width 32: rows are 128 bytes apart.
    std::vector<u16> p4444wide(64 * 32, 0);
    for (u32 y = 0; y < 32; ++y)
        for (u32 x = 0; x < 32; ++x) p4444wide[y * 64 + x] = p4444[y * 32 + x];
    placeTexture(b, 0, bytes16(p4444wide), 32, 32, 64);
    texRect(b, cx(6), cy(1), cell, cell, 0, 0, 32, 32);
    b.texMode(GE_TFMT_8888, 0, true);
    placeTexture(b, 0, swizzle(bytes32(picA), 128, 32), 32, 32, 32);
    texRect(b, cx(7), cy(1), cell, cell, 0, 0, 32, 32);

    // ---- row 2: filtering, wrapping and texture functions on a small 8888 texture ----
    const std::vector<u32> small = checker(8, 8, 2, rgba(255, 255, 255, 255), rgba(20, 60, 200, 160));
    b.texMode(GE_TFMT_8888, 0, false);
    const u32 smallAddr = placeTexture(b, 0, bytes32(small), 8, 8, 8);
    (void)smallAddr;
    b.texFilter(0, 0);
    texRect(b, cx(0), cy(2), cell, cell, 0, 0, 8, 8);          // nearest magnification
    b.texFilter(1, 1);
    texRect(b, cx(1), cy(2), cell, cell, 0, 0, 8, 8);          // bilinear magnification
    b.texWrap(true, true);
    texRect(b, cx(2), cy(2), cell, cell, 0, 0, 16, 16);        // clamp both: the last texel repeats
    b.texWrap(false, true);
    texRect(b, cx(3), cy(2), cell, cell, 0, 0, 24, 16);        // repeat U, clamp V
    b.texWrap(false, false);
    b.texFilter(0, 0);
    // Texture functions with a coloured vertex.
    const u32 vcol = rgba(255, 160, 60, 200);
    b.texFunc(0, true);  // MODULATE
    texRect(b, cx(4), cy(2), cell, cell, 0, 0, 16, 16, vcol);
    b.texFunc(1, true);  // DECAL
    texRect(b, cx(5), cy(2), cell, cell, 0, 0, 16, 16, vcol);
    b.texFunc(2, true);  // BLEND with the environment colour
    b.texEnvColor(rgba(40, 255, 80));
    texRect(b, cx(6), cy(2), cell, cell, 0, 0, 16, 16, vcol);
    b.texFunc(4, false, true);  // ADD, RGB only, colour doubling
    texRect(b, cx(7), cy(2), cell, cell, 0, 0, 16, 16, rgba(60, 30, 10, 255));
    b.texFunc(3, true);  // REPLACE: a narrow strip under the row
    texRect(b, 4, 262, 472, 8, 0, 0, 128, 2, vcol);

    b.enable(GE_CMD_ABE, false);
    b.enable(GE_CMD_TME, false);
    b.finish();
}

// =============================================================================================
// Scene 3: bezier_spline

void sceneBezierSpline(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(16, 16, 24), 0);

    const Mat4 proj = sceneProjection();
    const Mat4 view = lookAt({0.f, 2.6f, 3.9f}, {0.f, 0.1f, 0.2f}, {0.f, 1.f, 0.f});
    b.setMatrix(GeMatrix::Proj, proj.m);
    b.setMatrix(GeMatrix::View, view.m);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);

    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(50, 50, 60));
    b.materialAmbient(rgba(255, 255, 255));
    b.materialDiffuse(rgba(255, 255, 255));
    b.materialSpecular(rgba(255, 255, 255));
    b.specularPower(12.f);
    b.lightMode(false);
    const float dirPos[3] = {0.3f, 1.f, 0.6f};
    b.light(0, 0, 1, dirPos);
    b.lightColor(0, LIGHT_AMBIENT, 0);
    b.lightColor(0, LIGHT_DIFFUSE, rgba(220, 215, 200));
    b.lightColor(0, LIGHT_SPECULAR, rgba(120, 120, 120));
    const float pointPos[3] = {0.f, 1.2f, 1.8f};
    b.light(1, 1, 0, pointPos);
    b.lightColor(1, LIGHT_AMBIENT, 0);
    b.lightColor(1, LIGHT_DIFFUSE, rgba(80, 120, 255));
    b.lightAtt(1, 0.5f, 0.4f, 0.f);
    b.enable(GE_CMD_LE0, true);
    b.enable(GE_CMD_LE0 + 1, true);
    b.enable(GE_CMD_LE0 + 2, false);
    b.enable(GE_CMD_LE0 + 3, false);

    b.enable(GE_CMD_TME, true);
    b.texFunc(0, false);
    b.texMode(GE_TFMT_8888, 0, false);
    placeTexture(b, 0, bytes32(checker(32, 32, 4, rgba(250, 250, 250), rgba(200, 70, 50))), 32, 32, 32);
    b.texFilter(1, 1);
    b.texWrap(false, false);
    b.texLevelMode(1, 0.f);
    b.patchPrim(0);
    b.patchFace(false);

    // ---- Bezier: 7×4 control points = 2×1 patches, UV in the vertices, no normals (generated) ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 4; ++j)
            for (u32 i = 0; i < 7; ++i) {
                BuildVertex p;
                p.x = -2.6f + 2.2f * float(i) / 6.f;
                p.z = -1.2f + 2.4f * float(j) / 3.f;
                p.y = 0.6f * std::sin(float(i) * 1.3f) * std::cos(float(j) * 1.1f) + 0.2f;
                p.u = 2.f * float(i) / 6.f;
                p.v = float(j) / 3.f;
                cp.push_back(p);
            }
        const u32 vtype = vt::TC_F | vt::POS_F;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 addr = b.place(data.data(), u32(data.size()), 4);
        b.patchDivide(10, 8);
        b.setMatrix(GeMatrix::World, identity().m);
        b.patchFace(true);  // generated normals towards +Y (the light) for this control-point order
        b.drawBezier(vtype, 7, 4, 0, addr);
        b.patchFace(false);
    }

    // ---- Spline A: 6×5 control points, knots OPEN/OPEN in U, CLOSE/CLOSE in V, vertex colours
    //      and normals, 8-bit indices, generated texture coordinates scaled by SU/SV ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 5; ++j)
            for (u32 i = 0; i < 6; ++i) {
                BuildVertex p;
                p.x = 0.3f + 2.4f * float(i) / 5.f;
                p.z = -1.4f + 2.8f * float(j) / 4.f;
                p.y = 0.5f * std::cos(float(i) * 1.7f + float(j));
                p.nx = -0.3f * std::sin(float(i));
                p.ny = 1.f;
                p.nz = 0.2f;
                p.color = hue(i + j * 2, 10);
                cp.push_back(p);
            }
        // Indices walk the control points in reverse row order, to make the index path matter.
        std::vector<u8> idx;
        for (u32 j = 0; j < 5; ++j)
            for (u32 i = 0; i < 6; ++i) idx.push_back(u8((4 - j) * 6 + i));
        const u32 vtype = vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::IDX_8;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 vaddr = b.place(data.data(), u32(data.size()), 4);
        const u32 iaddr = b.place(idx.data(), u32(idx.size()), 4);
        b.colorMaterial(3);
        b.texScale(0.5f, 0.5f);
        b.patchDivide(6, 12);
        b.drawSpline(vtype, 6, 5, 3, 0, iaddr, vaddr);
        b.colorMaterial(0);
        b.texScale(1, 1);
    }

    // ---- Spline B: 5×4 control points, knots OPEN/CLOSE (1) in U and CLOSE/OPEN (2) in V,
    //      drawn as lines, untextured, reversed face ----
    {
        std::vector<BuildVertex> cp;
        for (u32 j = 0; j < 4; ++j)
            for (u32 i = 0; i < 5; ++i) {
                BuildVertex p;
                p.x = -1.2f + 2.4f * float(i) / 4.f;
                p.z = 1.6f + 0.8f * float(j) / 3.f;
                p.y = 0.9f + 0.3f * std::sin(float(i + j));
                cp.push_back(p);
            }
        const u32 vtype = vt::POS_F;
        auto data = packVertices(vtype, cp.data(), u32(cp.size()));
        const u32 addr = b.place(data.data(), u32(data.size()), 4);
        b.enable(GE_CMD_TME, false);
        b.patchPrim(1);
        b.patchFace(true);
        b.patchDivide(8, 4);
        b.materialAmbient(rgba(255, 240, 120));
        b.drawSpline(vtype, 5, 4, 1, 2, 0, addr);
        b.patchPrim(0);
        b.patchFace(false);
    }

    b.enable(GE_CMD_LTE, false);
    b.finish();
}

// =============================================================================================
// Scene 4: blend_stencil_logic

void sceneBlendStencilLogic(ListBuilder& b) {
    standardSetup(b);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH | CLEAR_STENCIL, rgba(0, 0, 0, 0), 0);

    // ---- pass 1: a 4444 off-screen buffer (128×128, stride 128) with 4-bit stencil and dither ----
    b.drawBuffer(GE_FORMAT_4444, kOff0, 128);
    b.scissor(0, 0, 128, 128);
    b.clear(CLEAR_COLOR | CLEAR_STENCIL, rgba(30, 30, 30), 0, 0x00);
    // Dithered gradient across the whole buffer (16-bit truncation after dithering, ge-rules.md §8.8).
    b.enable(GE_CMD_DTE, true);
    gradQuad(b, 0, 0, 128, 128, rgba(0, 0, 0), rgba(255, 64, 0), rgba(0, 128, 255), rgba(255, 255, 255));
    b.enable(GE_CMD_DTE, false);
    // Stencil: write 0x30 inside a diamond, then INCR in an overlapping square, then draw a
    // colour where stencil == 0x40 (INCR on 4444 adds 0x10, ge-rules.md §8.7) and another where it is 0x30.
    b.enable(GE_CMD_STE, true);
    b.pixelMask(0xFFFFFF, 0);  // keep RGB while writing stencil
    b.stencilFunc(1, 0x30);   // ALWAYS
    b.stencilOp(0, 0, 2);     // zpass REPLACE
    {
        BuildVertex v[4];
        const float xs[4] = {64, 112, 64, 16}, ys[4] = {16, 64, 112, 64};
        for (int i = 0; i < 4; ++i) {
            v[i].x = xs[i];
            v[i].y = ys[i];
            v[i].color = rgba(255, 255, 255, 255);
        }
        auto data = packVertices(kVt2dCol, v, 4);
        b.drawArrayData(GE_PRIM_TRIANGLE_FAN, kVt2dCol, 4, nullptr, data.data());
    }
    b.stencilOp(0, 0, 4);  // INCR
    rect(b, 40, 40, 80, 80, rgba(255, 255, 255));
    b.pixelMask(0, 0);
    b.stencilOp(0, 0, 0);  // KEEP
    b.stencilFunc(2, 0x40, 0xF0);  // EQUAL (masked)
    rect(b, 0, 0, 128, 128, rgba(255, 220, 0));
    b.stencilFunc(2, 0x30, 0xF0);
    rect(b, 0, 0, 128, 128, rgba(0, 200, 255));
    b.stencilFunc(3, 0x00, 0xFF);  // NOTEQUAL 0 → INVERT where anything was written
    b.stencilOp(0, 0, 3);
    b.pixelMask(0xFFFFFF, 0);
    rect(b, 0, 96, 128, 32, 0);
    b.pixelMask(0, 0);
    b.enable(GE_CMD_STE, false);

    // ---- pass 2: the main 8888 buffer ----
    b.drawBuffer(GE_FORMAT_8888, kFb, 512);
    b.scissor(0, 0, 480, 272);
    b.texSync();

    // Background: vertical colour bars with a horizontal alpha ramp in the frame buffer alpha.
    for (int i = 0; i < 8; ++i) {
        u32 c = hue(u32(i), 8);
        gradQuad(b, i * 60, 0, 60, 272, c & 0xFFFFFF, c & 0xFFFFFF, c | 0xFF000000, c | 0xFF000000);
    }
    // The gradients above wrote no alpha (no stencil test, ge-rules.md §8.7): set the frame-buffer alpha
    // (= stencil) to 0xC0 everywhere through a clear that writes alpha only.
    b.clear(CLEAR_STENCIL, 0, 0, 0xC0);

    // Row 0: blend equations and factors over the bars; the source is a white→red gradient with
    // alpha 0→255.
    struct BlendCase {
        u32 eq, a, bb, fixA, fixB;
    };
    const BlendCase cases[8] = {
        {0, 2, 3, 0, 0},                              // ADD  As, 1−As
        {0, 10, 10, rgba(128, 128, 128), rgba(64, 64, 64)},  // ADD  FIXA, FIXB
        {1, 2, 10, 0, rgba(255, 255, 255)},           // SUB  As, FIX(white)
        {2, 6, 4, 0, 0},                              // REVSUB 2·As, Ad
        {3, 0, 0, 0, 0},                              // MIN
        {4, 0, 0, 0, 0},                              // MAX
        {5, 0, 0, 0, 0},                              // ABS
        {0, 0, 1, 0, 0},                              // ADD  Cd, 1−Cs
    };
    b.enable(GE_CMD_ABE, true);
    for (int i = 0; i < 8; ++i) {
        b.blendFunc(cases[i].eq, cases[i].a, cases[i].bb, cases[i].fixA, cases[i].fixB);
        gradQuad(b, i * 60 + 4, 6, 52, 52, rgba(255, 255, 255, 0), rgba(255, 255, 255, 255), rgba(255, 0, 0, 0),
                 rgba(255, 0, 0, 255));
    }
    b.enable(GE_CMD_ABE, false);

    // Row 1: logic ops 0–15 in 16 small cells (30×30).
    b.enable(GE_CMD_LOE, true);
    for (u32 op = 0; op < 16; ++op) {
        b.logicOp(op);
        rect(b, int(op) * 30, 66, 28, 30, rgba(0xF0, 0x3C, 0xAA));
    }
    b.enable(GE_CMD_LOE, false);

    // Row 2: alpha test, colour test, pixel masks, dither on/off.
    gradQuad(b, 4, 104, 112, 52, rgba(255, 255, 0, 0), rgba(255, 255, 0, 255), rgba(0, 255, 255, 0),
             rgba(0, 255, 255, 255));  // reference (no test)
    b.enable(GE_CMD_ATE, true);
    b.alphaFunc(6, 0x80, 0xFF);  // GREATER 0x80: the right half survives
    gradQuad(b, 124, 104, 112, 52, rgba(255, 255, 0, 0), rgba(255, 255, 0, 255), rgba(0, 255, 255, 0),
             rgba(0, 255, 255, 255));
    b.alphaFunc(4, 0x40, 0xC0);  // LESS with mask: (A & 0xC0) < 0x40
    gradQuad(b, 244, 104, 112, 52, rgba(255, 0, 255, 0), rgba(255, 0, 255, 255), rgba(255, 255, 255, 0),
             rgba(255, 255, 255, 255));
    b.enable(GE_CMD_ATE, false);
    // Colour test NOTEQUAL against green (masking the low bits): stripes of green are dropped.
    b.enable(GE_CMD_CTE, true);
    b.colorFunc(3, rgba(0, 255, 0), rgba(0xF0, 0xF0, 0xF0));
    for (int i = 0; i < 8; ++i) rect(b, 364 + i * 14, 104, 14, 52, (i & 1) ? rgba(4, 250, 8) : rgba(250, 120, 20));
    b.enable(GE_CMD_CTE, false);

    // Row 3: PMSK (keep green bits), dither on vs off on a dark ramp, depth write/test interplay.
    b.pixelMask(rgba(0, 0xFF, 0), 0);
    rect(b, 4, 164, 112, 40, rgba(255, 255, 255));
    b.pixelMask(0, 0);
    gradQuad(b, 124, 164, 112, 40, rgba(0, 0, 0), rgba(40, 40, 40), rgba(0, 0, 0), rgba(40, 40, 40));
    b.enable(GE_CMD_DTE, true);
    gradQuad(b, 244, 164, 112, 40, rgba(0, 0, 0), rgba(40, 40, 40), rgba(0, 0, 0), rgba(40, 40, 40));
    b.enable(GE_CMD_DTE, false);
    // Stencil on the 8888 target: frame-buffer alpha is 0xC0 from the clear above; ZERO it where
    // the stencil equals 0xC0 in the left half, DECR the right quarter, then show the stencil
    // through a destination-alpha blend of white.
    b.enable(GE_CMD_STE, true);
    b.stencilFunc(2, 0xC0, 0xFF);
    b.stencilOp(0, 0, 1);  // ZERO
    b.pixelMask(0xFFFFFF, 0);
    rect(b, 364, 164, 56, 40, 0);
    b.stencilOp(0, 0, 5);  // DECR
    rect(b, 448, 164, 28, 40, 0);
    b.pixelMask(0, 0);
    b.stencilFunc(1, 0, 0);
    b.stencilOp(0, 0, 0);
    b.enable(GE_CMD_STE, false);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 4, 5);  // Ad, 1 − Ad
    rect(b, 364, 164, 112, 40, rgba(255, 255, 255));
    b.enable(GE_CMD_ABE, false);

    // Row 4: the 4444 pass, sampled as a texture (same bytes, texture format 4444), twice:
    // as is, and with alpha blending so its stencil/alpha nibble shows.
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_4444, 0, false);
    b.setTexture(0, 0x04000000 + kOff0, 128, 128, 128);
    b.texFunc(3, false);  // REPLACE, RGB
    b.texFilter(0, 0);
    b.texWrap(true, true);
    texRect(b, 4, 210, 60, 60, 0, 0, 128, 128);
    b.texFunc(3, true);
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 2, 3);
    texRect(b, 70, 210, 60, 60, 0, 0, 128, 128);
    b.enable(GE_CMD_ABE, false);
    b.enable(GE_CMD_TME, false);

    // Depth: two overlapping through-mode rectangles with Z; the second (lower Z) fails GEQUAL.
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);
    {
        const u32 vt = vt::COL_8888 | vt::POS_16 | vt::THROUGH;
        BuildVertex v[4];
        v[0].x = 150; v[0].y = 214; v[0].z = 40000; v[0].color = rgba(200, 60, 200);
        v[1].x = 230; v[1].y = 266; v[1].z = 40000; v[1].color = rgba(200, 60, 200);
        v[2].x = 190; v[2].y = 230; v[2].z = 20000; v[2].color = rgba(60, 200, 60);
        v[3].x = 280; v[3].y = 270; v[3].z = 20000; v[3].color = rgba(60, 200, 60);
        auto data = packVertices(vt, v, 4);
        b.drawArrayData(GE_PRIM_RECTANGLES, vt, 4, nullptr, data.data());
    }
    b.enable(GE_CMD_ZTE, false);

    b.finish();
}

// =============================================================================================
// Scene 5: render_to_texture

void sceneRenderToTexture(ListBuilder& b) {
    standardSetup(b);

    // ---- pass 1: a lit, vertex-coloured cube into an 8888 off-screen buffer (128×128) ----
    b.drawBuffer(GE_FORMAT_8888, kOff0, 128);
    b.depthBuffer(kZb, 128);
    b.offset(2048 - 64, 2048 - 64);
    b.viewport(2048, 2048, 128, 128);
    b.scissor(0, 0, 128, 128);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, rgba(20, 40, 70), 0);
    b.enable(GE_CMD_ZTE, true);
    b.depthFunc(7);
    b.setMatrix(GeMatrix::Proj, perspective(50.f, 1.f, 0.5f, 20.f).m);
    b.setMatrix(GeMatrix::View, lookAt({2.2f, 1.8f, 2.6f}, {0, 0, 0}, {0, 1, 0}).m);
    b.setMatrix(GeMatrix::World, rotY(0.3f).m);
    b.enable(GE_CMD_LTE, true);
    b.ambient(rgba(60, 60, 60));
    b.colorMaterial(3);
    b.materialSpecular(0);
    const float lp[3] = {0.5f, 1.f, 0.8f};
    b.light(0, 0, 0, lp);
    b.lightColor(0, LIGHT_AMBIENT | LIGHT_SPECULAR, 0);
    b.lightColor(0, LIGHT_DIFFUSE, rgba(230, 230, 230));
    b.enable(GE_CMD_LE0, true);
    for (u32 n = 1; n < 4; ++n) b.enable(u8(GE_CMD_LE0 + n), false);
    {
        // 24 vertices (4 per face), 16-bit colour 5650 per face, 8-bit normals, 16-bit positions.
        const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        std::vector<BuildVertex> v;
        std::vector<u16> idx;
        for (int f = 0; f < 6; ++f) {
            Vec3 nrm = normals[f];
            Vec3 t1 = std::fabs(nrm.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            Vec3 t2 = cross(nrm, t1);
            u16 base = u16(v.size());
            for (int k = 0; k < 4; ++k) {
                float s = (k & 1) ? 1.f : -1.f, t = (k & 2) ? 1.f : -1.f;
                BuildVertex p;
                p.x = 0.7f * (nrm.x + s * t1.x + t * t2.x);
                p.y = 0.7f * (nrm.y + s * t1.y + t * t2.y);
                p.z = 0.7f * (nrm.z + s * t1.z + t * t2.z);
                p.nx = nrm.x;
                p.ny = nrm.y;
                p.nz = nrm.z;
                p.color = hue(u32(f * 2 + (k == 3)), 12);
                v.push_back(p);
            }
            idx.insert(idx.end(), {base, u16(base + 1), u16(base + 2), u16(base + 1), u16(base + 3), u16(base + 2)});
        }
        const u32 vtype = vt::COL_5650 | vt::NRM_8 | vt::POS_16 | vt::IDX_16;
        auto data = packVertices(vtype, v.data(), u32(v.size()));
        b.drawArrayData(GE_PRIM_TRIANGLES, vtype, u32(idx.size()), idx.data(), data.data());
    }
    b.enable(GE_CMD_LTE, false);
    b.enable(GE_CMD_ZTE, false);

    // ---- pass 2: a 5650 off-screen buffer (64×64, stride 64) with a pattern whose raw 16-bit
    //      values are later used as CLUT16 indices ----
    b.drawBuffer(GE_FORMAT_565, kOff1, 64);
    b.scissor(0, 0, 64, 64);
    b.clear(CLEAR_COLOR, rgba(0, 0, 0), 0);
    for (int i = 0; i < 8; ++i) rect(b, i * 8, 0, 8, 64, rgba(u32(i) * 36, 0, 0));  // R 5 bits: index low bits
    b.enable(GE_CMD_ABE, true);
    b.blendFunc(0, 10, 10, rgba(255, 255, 255), rgba(255, 255, 255));  // additive
    for (int j = 0; j < 8; ++j) rect(b, 0, j * 8, 64, 8, rgba(0, u32(j) * 36, 0));    // G adds upper bits
    b.enable(GE_CMD_ABE, false);

    // ---- main pass ----
    b.drawBuffer(GE_FORMAT_8888, kFb, 512);
    b.depthBuffer(kZb, 512);
    b.offset(2048 - 240, 2048 - 136);
    b.viewport(2048, 2048, 480, 272);
    b.scissor(0, 0, 480, 272);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, rgba(40, 40, 40), 0);
    b.texSync();
    b.texFlush();

    // A perspective quad textured with the rendered 8888 buffer (bilinear).
    b.setMatrix(GeMatrix::Proj, sceneProjection().m);
    b.setMatrix(GeMatrix::View, lookAt({0, 0, 4.f}, {0, 0, 0}, {0, 1, 0}).m);
    b.setMatrix(GeMatrix::World, mul(translate(-1.3f, 0.2f, 0), rotY(0.5f)).m);
    b.enable(GE_CMD_TME, true);
    b.texMode(GE_TFMT_8888, 0, false);
    b.setTexture(0, 0x04000000 + kOff0, 128, 128, 128);
    b.texFunc(3, false);
    b.texFilter(1, 1);
    b.texWrap(true, true);
    b.texLevelMode(1, 0.f);
    {
        BuildVertex v[4];
        const float xs[4] = {-1, 1, -1, 1}, ys[4] = {1, 1, -1, -1};
        for (int i = 0; i < 4; ++i) {
            v[i].x = xs[i];
            v[i].y = ys[i];
            v[i].z = 0;
            v[i].u = (xs[i] + 1) / 2;
            v[i].v = (1 - ys[i]) / 2;
        }
        const u32 vtype = vt::TC_F | vt::POS_F;
        auto data = packVertices(vtype, v, 4);
        b.drawArrayData(GE_PRIM_TRIANGLE_STRIP, vtype, 4, nullptr, data.data());
    }

    // The 5650 buffer read as CLUT16: index = (pixel >> 0) & 0xFF with an 8888 rainbow palette.
    {
        std::vector<u32> pal(256);
        for (u32 i = 0; i < 256; ++i) pal[i] = hue(i * 7, 256);
        const auto palBytes = bytes32(pal);
        const u32 palAddr = b.place(palBytes.data(), 1024, 16);
        b.clutMode(GE_FORMAT_8888, 0, 0xFF, 0);
        b.clutLoad(palAddr, 32);
        b.texMode(GE_TFMT_CLUT16, 0, false);
        b.setTexture(0, 0x04000000 + kOff1, 64, 64, 64);
        b.texFilter(0, 0);
        texRect(b, 300, 20, 128, 128, 0, 0, 64, 64);
        // And the same bytes as a plain 5650 texture.
        b.texMode(GE_TFMT_5650, 0, false);
        b.setTexture(0, 0x04000000 + kOff1, 64, 64, 64);
        texRect(b, 300, 156, 64, 64, 0, 0, 64, 64);
    }
    b.enable(GE_CMD_TME, false);

    // Block transfers: a procedural 8888 image from RAM into the frame buffer, and a VRAM→VRAM
    // copy of part of the rendered cube (the source is GE-drawn, so the dump keeps the VRAM
    // source address instead of a TRANSFERSRC copy).
    {
        std::vector<u32> img = rings(64, 64, 0);
        const auto bytes = bytes32(img);
        const u32 src = b.place(bytes.data(), u32(bytes.size()), 16);
        b.copyImage(GE_FORMAT_8888, 8, 4, 48, 40, 64, src, 400, 220, 512, 0x04000000 + kFb);
        b.copyImage(GE_FORMAT_8888, 32, 32, 64, 64, 128, 0x04000000 + kOff0, 20, 190, 512, 0x04000000 + kFb);
    }

    b.finish();
}

// =============================================================================================

struct Scene {
    const char* name;
    void (*build)(ListBuilder&);
};
const Scene kScenes[] = {
    {"lit_textured_skinned", sceneLitTexturedSkinned},
    {"clut_dxt_sprites", sceneClutDxtSprites},
    {"bezier_spline", sceneBezierSpline},
    {"blend_stencil_logic", sceneBlendStencilLogic},
    {"render_to_texture", sceneRenderToTexture},
};

// The INIT state: a booted GE with identity matrices (the scene sets everything it uses).
GeState initialState() {
    GeState st;
    st.reset();
    const Mat4 id = identity();
    float m[12];
    to3x4(id, m);
    std::memcpy(st.world, m, sizeof m);
    std::memcpy(st.view, m, sizeof m);
    std::memcpy(st.tgen, m, sizeof m);
    std::memcpy(st.proj, id.m, sizeof id.m);
    for (int i = 0; i < 8; ++i) std::memcpy(st.bone + 12 * i, m, sizeof m);
    for (int op = 0; op < 256; ++op) st.regs[op] = u32(op) << 24;
    return st;
}

bool writeScene(const Scene& s, const std::string& dir) {
    Memory mem;
    dump::DumpWriter writer("GE2GL0001");
    DumpRecorder rec(mem, writer);
    ListBuilder b(&mem);
    const GeState init = initialState();
    rec.begin(init, 0x04000000, 512, GE_FORMAT_8888);
    b.attach(&rec);
    s.build(b);
    b.attach(nullptr);
    rec.end(0x04000000, 512, GE_FORMAT_8888);

    bool ok = true;
    for (const std::string& w : rec.warnings()) std::fprintf(stderr, "%s: warning: %s\n", s.name, w.c_str());

    // Sanity check: the executable list runs to FINISH on the engine without errors.
    const u32 list = b.placeList();
    GeEngine engine(mem);
    u32 ctx[512];
    init.saveContext(ctx);
    engine.loadContext(ctx);
    engine.startList(list, 0);
    RunStatus st = engine.run(1u << 24);
    if (st != RunStatus::Completed) {
        std::fprintf(stderr, "%s: list ended with %s (%s)\n", s.name, runStatusName(st), engine.lastErrorMessage().c_str());
        ok = false;
    }

    std::string err;
    const std::string path = dir + "/" + s.name + ".ppdmp";
    if (!writer.save(path, err)) {
        std::fprintf(stderr, "%s: %s\n", path.c_str(), err.c_str());
        return false;
    }
    std::printf("%-24s %5zu records, %7zu push bytes, %4u kicks, %5zu words, engine: %llu prims %llu patches\n", s.name,
                writer.dump().records.size(), writer.dump().pushbuf.size(), rec.kicks(), b.words().size(),
                (unsigned long long)engine.stats().prims, (unsigned long long)engine.stats().patches);
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = std::string(GE2GL_SOURCE_DIR) + "/dumps";
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--out" && i + 1 < argc) {
            dir = argv[++i];
        } else if (a == "--list") {
            for (const Scene& s : kScenes) std::printf("%s\n", s.name);
            return 0;
        } else {
            std::fprintf(stderr, "usage: make_scenes [--out DIR] [--list]\n");
            return 2;
        }
    }
    bool ok = true;
    for (const Scene& s : kScenes) ok = writeScene(s, dir) && ok;
    return ok ? 0 : 1;
}
