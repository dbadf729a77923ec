// SPDX-License-Identifier: MIT
// What the scenes of make_scenes share: small matrix maths, procedural textures, the VRAM layout
// and the 2D drawing helpers on ge::ListBuilder. Header only; all data is generated, so every
// scene's bytes are deterministic.
#pragma once
#include <cmath>
#include <cstring>
#include <vector>

#include "authoring/list_builder.h"

namespace ge::scenes {

// ---------------------------------------------------------------------------------------------
// Small column-major 4×4 matrix maths (m[4·col + row]) for cameras and bones.

struct Mat4 {
    float m[16];
};
struct Vec3 {
    float x, y, z;
};

inline Mat4 identity() {
    Mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.f;
    return r;
}
inline Mat4 mul(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}
inline Mat4 translate(float x, float y, float z) {
    Mat4 r = identity();
    r.m[12] = x;
    r.m[13] = y;
    r.m[14] = z;
    return r;
}
inline Mat4 rotX(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[5] = c;
    r.m[6] = s;
    r.m[9] = -s;
    r.m[10] = c;
    return r;
}
inline Mat4 rotY(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[0] = c;
    r.m[2] = -s;
    r.m[8] = s;
    r.m[10] = c;
    return r;
}
inline Mat4 rotZ(float a) {
    Mat4 r = identity();
    float c = std::cos(a), s = std::sin(a);
    r.m[0] = c;
    r.m[1] = s;
    r.m[4] = -s;
    r.m[5] = c;
    return r;
}
// OpenGL-style perspective: clip z in [−w, w] between near and far (docs/ge-rules.md §8.5).
inline Mat4 perspective(float fovyDeg, float aspect, float n, float f) {
    Mat4 r{};
    float t = 1.f / std::tan(fovyDeg * 3.14159265f / 360.f);
    r.m[0] = t / aspect;
    r.m[5] = t;
    r.m[10] = (f + n) / (n - f);
    r.m[11] = -1.f;
    r.m[14] = 2.f * f * n / (n - f);
    return r;
}
inline Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Vec3 norm(Vec3 a) {
    float l = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return l > 0 ? Vec3{a.x / l, a.y / l, a.z / l} : Vec3{0, 0, 1};
}
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Mat4 lookAt(Vec3 eye, Vec3 center, Vec3 up) {
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
inline void to3x4(const Mat4& a, float out[12]) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) out[c * 3 + r] = a.m[c * 4 + r];
}

constexpr float kPi = 3.14159265f;

// ---------------------------------------------------------------------------------------------
// Procedural textures and pixel helpers. Colours are ABGR8888 (R in bits 7..0).

inline u32 rgba(u32 r, u32 g, u32 b, u32 a = 255) { return (r & 255) | (g & 255) << 8 | (b & 255) << 16 | (a & 255) << 24; }
inline u16 to5650(u32 c) { return u16(((c & 255) >> 3) | (((c >> 8) & 255) >> 2) << 5 | (((c >> 16) & 255) >> 3) << 11); }
inline u16 to5551(u32 c) {
    return u16(((c & 255) >> 3) | (((c >> 8) & 255) >> 3) << 5 | (((c >> 16) & 255) >> 3) << 10 | ((c >> 31) << 15));
}
inline u16 to4444(u32 c) {
    return u16(((c & 255) >> 4) | (((c >> 8) & 255) >> 4) << 4 | (((c >> 16) & 255) >> 4) << 8 | ((c >> 28) << 12));
}
// Standard 565 as used by DXT endpoints (red in bits 15..11, ge-rules.md §6.5).
inline u16 dxt565(u32 r, u32 g, u32 b) { return u16((r >> 3) << 11 | (g >> 2) << 5 | (b >> 3)); }

// A hue wheel colour for i in 0..n-1.
inline u32 hue(u32 i, u32 n, u32 a = 255) {
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

inline std::vector<u8> bytes32(const std::vector<u32>& px) {
    std::vector<u8> out(px.size() * 4);
    for (size_t i = 0; i < px.size(); ++i) writeLE32(&out[i * 4], px[i]);
    return out;
}
inline std::vector<u8> bytes16(const std::vector<u16>& px) {
    std::vector<u8> out(px.size() * 2);
    for (size_t i = 0; i < px.size(); ++i) writeLE16(&out[i * 2], px[i]);
    return out;
}

// Swizzles a linear texture (pitch in bytes, rows) into the GE's 16-byte × 8-row blocks
// (ge-rules.md §6.3).
inline std::vector<u8> swizzle(const std::vector<u8>& lin, u32 pitch, u32 rows) {
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
inline std::vector<u32> checker(u32 w, u32 h, u32 cell, u32 c0, u32 c1) {
    std::vector<u32> px(w * h);
    for (u32 y = 0; y < h; ++y)
        for (u32 x = 0; x < w; ++x) px[y * w + x] = (((x / cell) ^ (y / cell)) & 1) ? c1 : c0;
    return px;
}

// A "target" picture: rings of hue with a cross, a good magnification/filter test.
inline std::vector<u32> rings(u32 w, u32 h, u32 alphaMode) {
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
inline std::vector<u32> halve(const std::vector<u32>& src, u32 w, u32 h) {
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
inline std::vector<u8> makeDxt(u32 fmt, u32 w, u32 h, bool punchThrough) {
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
inline void standardSetup(ListBuilder& b) {
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
inline void rect(ListBuilder& b, int x, int y, int w, int h, u32 color) {
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
inline void texRect(ListBuilder& b, int x, int y, int w, int h, float u0, float v0, float u1, float v1, u32 color = 0xFFFFFFFF) {
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
inline void gradQuad(ListBuilder& b, int x, int y, int w, int h, u32 tl, u32 tr, u32 bl, u32 br) {
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
inline u32 placeTexture(ListBuilder& b, u32 level, const std::vector<u8>& data, u32 w, u32 h, u32 bufw) {
    u32 addr = b.place(data.data(), u32(data.size()), 16);
    b.setTexture(level, addr, w, h, bufw);
    return addr;
}

// Triangle-list grid helper: (n+1)×(m+1) vertices, 16-bit indices.
inline std::vector<u16> gridIndices(u32 n, u32 m) {
    std::vector<u16> idx;
    for (u32 j = 0; j < m; ++j)
        for (u32 i = 0; i < n; ++i) {
            u16 a = u16(j * (n + 1) + i), bb = u16(a + 1), c = u16(a + n + 1), d = u16(c + 1);
            idx.insert(idx.end(), {a, c, bb, bb, c, d});
        }
    return idx;
}

inline Mat4 sceneProjection() { return perspective(60.f, 480.f / 272.f, 0.5f, 30.f); }

}  // namespace ge::scenes
