// Per-triangle records for exact interpolation (see tri_setup.h). Every number mirrors
// softmodel/raster.cpp: rasterTriangle's oriented edges and sample offset, attribute order,
// constant-attribute shortcuts, depth plane and weight reciprocal; rasterRectangle's orientation
// table and linear s, t.
#include "translator/tri_setup.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace ge::gl {

namespace {

namespace T = shadergen::tri;

void putU32(TriRecord& r, int texel, int comp, u32 v) { r.w[texel * 4 + comp] = v; }
void putF32(TriRecord& r, int texel, int comp, float v) {
    u32 b;
    std::memcpy(&b, &v, 4);
    putU32(r, texel, comp, b);
}
void putD(TriRecord& r, int i, double v) {
    u64 b;
    std::memcpy(&b, &v, 8);
    const int k = T::kDoubles * 4 + 2 * i;
    r.w[k] = u32(b), r.w[k + 1] = u32(b >> 32);
}
void putI(TriRecord& r, int i, s64 v) {
    const u64 b = u64(v);
    const int k = T::kInts * 4 + 2 * i;
    r.w[k] = u32(b), r.w[k + 1] = u32(b >> 32);
}
void putPlane(TriRecord& r, const soft::AttrPlane& p) {
    putI(r, T::kIZ, p.base);
    putI(r, T::kIZ + 1, p.kx);
    putI(r, T::kIZ + 2, p.ky);
}
u32 packColor(const u8* c, int n) {
    u32 v = 0;
    for (int i = 0; i < n; ++i) v |= u32(c[i]) << (8 * i);
    return v;
}
// Constant attributes (rectangles, fragments): flags clear, so vertex 0's values everywhere.
void putConstAttributes(TriRecord& r, u16 z, const u8 color[4], const u8 secondary[3]) {
    putPlane(r, soft::AttrPlane{s64(z) * 16384, 0, 0});
    putU32(r, T::kColors, 0, packColor(color, 4));
    putU32(r, T::kSecondary, 0, packColor(secondary, 3));
}

}  // namespace

void packTriangle(const soft::RasterParams& rp, const soft::ScreenVertex& in0, const soft::ScreenVertex& in1,
                  const soft::ScreenVertex& in2, const soft::ScreenVertex& prov, TriRecord& r) {
    std::memset(&r, 0, sizeof r);
    u32 flags = T::kKindTriangle;
    if (rp.through) flags |= T::kFlagThrough;
    putF32(r, T::kHeader, 2, 0.0f);
    putF32(r, T::kHeader, 3, 1.0f);
    putU32(r, T::kColors, 3, u32(soft::triangleSampleOffset()));
    // rasterTriangle works on the clockwise (on screen) order v = in0, in2, in1 when the signed
    // area is negative; its edge functions follow v. Attributes are summed in the order o.
    const soft::ScreenVertex* v[3] = {&in0, &in1, &in2};
    const soft::ScreenVertex* o[3] = {&in0, &in1, &in2};
    s64 area = s64(in1.x - in0.x) * (in2.y - in0.y) - s64(in1.y - in0.y) * (in2.x - in0.x);
    if (area < 0) {
        std::swap(v[1], v[2]);
        std::swap(o[0], o[2]);
        area = -area;
        flags |= T::kFlagSwapped;
    }
    for (int i = 0; i < 3; ++i) {
        const soft::ScreenVertex& a = *v[(i + 1) % 3];
        const soft::ScreenVertex& b = *v[(i + 2) % 3];
        const s64 dx = s64(b.x) - a.x, dy = s64(b.y) - a.y;
        putI(r, T::kIA + i, -dy);
        putI(r, T::kIB + i, dx);
        putI(r, T::kIC + i, dy * a.x - dx * a.y);
        // Top-left rule: left edges (going up) and top edges (horizontal, going right) include
        // sample points exactly on them, the others do not.
        if (!(dy < 0 || (dy == 0 && dx > 0))) flags |= 1u << (T::kEdgeThresholdShift + i);
    }
    // The edge functions sum to the area: one float reciprocal for every weighted sum.
    putF32(r, T::kFog, 3, area ? 1.0f / float(area) : 0.0f);
    // 2×2 quads (level of detail, slope-mode W) start at the box's top-left pixel, scissored.
    const int minX = std::min({in0.x, in1.x, in2.x}), minY = std::min({in0.y, in1.y, in2.y});
    const int qx0 = std::max(minX >> 4, rp.clipX1), qy0 = std::max(minY >> 4, rp.clipY1);
    putU32(r, T::kSecondary, 3, (u32(qx0) & 0xFFFFu) | (u32(qy0) << 16));
    putF32(r, T::kS, 3, rp.texW0);
    putF32(r, T::kT, 3, rp.texH0);
    for (int i = 0; i < 3; ++i) {
        putF32(r, T::kS, i, o[i]->s);
        putF32(r, T::kT, i, o[i]->t);
        putF32(r, T::kQ, i, o[i]->q);
        putF32(r, T::kRecipW, i, rp.through ? 1.0f : 1.0f / o[i]->w);
        putF32(r, T::kClipW, i, o[i]->w);
    }

    // Depth plane over the original vertex order (a plane does not depend on it); constant when
    // all three agree (rasterTriangle's shortcut: the value as is).
    if (in0.z == in1.z && in1.z == in2.z) {
        putPlane(r, soft::AttrPlane{s64(u16(in0.z)) * 16384, 0, 0});
    } else {
        const s64 X[3] = {in0.x, in1.x, in2.x}, Y[3] = {in0.y, in1.y, in2.y};
        const s64 Z[3] = {in0.z, in1.z, in2.z};
        putPlane(r, soft::attributePlane(X, Y, Z));
    }
    // Colours of o[], or the constant source (in0, or the provoking vertex when flat shading)
    // in every slot.
    const bool colConst = !rp.gouraud || (std::memcmp(in0.color, in1.color, 4) == 0 &&
                                          std::memcmp(in1.color, in2.color, 4) == 0);
    const bool secConst = !rp.gouraud || (std::memcmp(in0.secondary, in1.secondary, 3) == 0 &&
                                          std::memcmp(in1.secondary, in2.secondary, 3) == 0);
    const soft::ScreenVertex& cs = rp.gouraud ? in0 : prov;
    for (int i = 0; i < 3; ++i) {
        putU32(r, T::kColors, i, packColor((colConst ? cs : *o[i]).color, 4));
        putU32(r, T::kSecondary, i, packColor((secConst ? cs : *o[i]).secondary, 3));
    }
    if (!colConst) flags |= T::kFlagColorVaries;
    if (!secConst) flags |= T::kFlagSecVaries;

    // Fog is interpolated unless fog is off or no vertex is fogged (then the byte is 255).
    putU32(r, T::kHeader, 1, 255u);
    if (rp.fog && !(in0.fog >= 1.0f && in1.fog >= 1.0f && in2.fog >= 1.0f)) {
        flags |= T::kFlagFogVaries;
        for (int i = 0; i < 3; ++i) putF32(r, T::kFog, i, o[i]->fog);
    }
    putU32(r, T::kHeader, 0, flags);
}

void packRectangle(const soft::RasterParams& rp, const soft::ScreenVertex& v0, const soft::ScreenVertex& v1,
                   TriRecord& r) {
    std::memset(&r, 0, sizeof r);
    putU32(r, T::kHeader, 0, T::kKindLinear);
    const int xl = std::min(v0.x, v1.x), xr = std::max(v0.x, v1.x);
    const int yt = std::min(v0.y, v1.y), yb = std::max(v0.y, v1.y);
    // Texture orientation by where v0 lies relative to v1 (§8.2), as rasterRectangle.
    float sBase = 0, sDx = 0, sDy = 0, tBase = 0, tDx = 0, tDy = 0;
    const bool left = v0.x < v1.x, above = v0.y < v1.y;
    if (left && above) {
        sBase = v0.s, sDx = v1.s - v0.s, tBase = v0.t, tDy = v1.t - v0.t;
    } else if (left) {
        sBase = v1.s, sDy = v0.s - v1.s, tBase = v0.t, tDx = v1.t - v0.t;
    } else if (above) {
        sBase = v0.s, sDy = v1.s - v0.s, tBase = v1.t, tDx = v0.t - v1.t;
    } else {
        sBase = v1.s, sDx = v0.s - v1.s, tBase = v1.t, tDy = v0.t - v1.t;
    }
    const double invW = xr > xl ? 1.0 / double(xr - xl) : 0.0, invH = yb > yt ? 1.0 / double(yb - yt) : 0.0;
    float lod = 0.0f;
    if (rp.textured && rp.needLod) lod = soft::lodFromTexSteps(rp, 16.0 * sDx * invW, 16.0 * tDy * invH);
    if (rp.textured) {
        putD(r, T::kDSBase, sBase), putD(r, T::kDSDx, sDx), putD(r, T::kDSDy, sDy);
        putD(r, T::kDTBase, tBase), putD(r, T::kDTDx, tDx), putD(r, T::kDTDy, tDy);
    }
    putD(r, T::kDX0, double(xl)), putD(r, T::kDY0, double(yt));
    putD(r, T::kDInvW, invW), putD(r, T::kDInvH, invH);
    putU32(r, T::kHeader, 1, rp.fog ? soft::fogToByte(v1.fog) : 255u);
    putF32(r, T::kHeader, 2, lod);
    putF32(r, T::kHeader, 3, rp.needW ? v1.w : 1.0f);
    putConstAttributes(r, u16(v1.z), v1.color, v1.secondary);
}

void packFragment(const soft::Fragment& f, TriRecord& r) {
    std::memset(&r, 0, sizeof r);
    putU32(r, T::kHeader, 0, T::kKindLinear);
    // s = sBase + fx·0 + fy·0 = f.s exactly (fx, fy finite).
    putD(r, T::kDSBase, f.s);
    putD(r, T::kDTBase, f.t);
    putU32(r, T::kHeader, 1, f.fog);
    putF32(r, T::kHeader, 2, f.lod);
    putF32(r, T::kHeader, 3, f.w);
    putConstAttributes(r, f.z, f.color, f.secondary);
}

}  // namespace ge::gl
