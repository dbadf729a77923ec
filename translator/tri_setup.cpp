// SPDX-License-Identifier: MIT
// Per-triangle records for exact interpolation (see tri_setup.h). Every number mirrors
// geometry/raster.cpp: rasterTriangle's oriented edges and sample offset, attribute order,
// constant-attribute shortcuts, depth values and weight reciprocal; rasterRectangle's covered
// box, orientation table and single-precision steps.
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
void putI(TriRecord& r, int i, s64 v) {
    const u64 b = u64(v);
    const int k = T::kInts * 4 + 2 * i;
    r.w[k] = u32(b), r.w[k + 1] = u32(b >> 32);
}
// Depth of o[0], o[1], o[2] in the three depth slots. The shader interpolates them as
// rasterTriangle does (single-precision weighted sum, rounded to nearest even) unless all three
// are equal, which is rasterTriangle's constant shortcut (the value as is).
void putDepths(TriRecord& r, int z0, int z1, int z2) {
    putI(r, T::kIZ, z0);
    putI(r, T::kIZ + 1, z1);
    putI(r, T::kIZ + 2, z2);
}
u32 packColor(const u8* c, int n) {
    u32 v = 0;
    for (int i = 0; i < n; ++i) v |= u32(c[i]) << (8 * i);
    return v;
}
// Constant attributes (rectangles, fragments): flags clear, so vertex 0's values everywhere.
void putConstAttributes(TriRecord& r, u16 z, const u8 color[4], const u8 secondary[3]) {
    putDepths(r, z, z, z);
    putU32(r, T::kColors, 0, packColor(color, 4));
    putU32(r, T::kSecondary, 0, packColor(secondary, 3));
}

}  // namespace

bool hasGradients(const TriRecord& r) { return (r.w[T::kHeader * 4] & T::kFlagColourGradients) != 0; }
u32& gradientIndex(TriRecord& r) { return r.w[T::kClipW * 4 + 3]; }

bool packTriangle(const geo::RasterParams& rp, const geo::ScreenVertex& in0, const geo::ScreenVertex& in1,
                  const geo::ScreenVertex& in2, const geo::ScreenVertex& prov, TriRecord& r, GradientRecord& grad) {
    std::memset(&r, 0, sizeof r);
    u32 flags = T::kKindTriangle;
    if (rp.through) flags |= T::kFlagThrough;
    putF32(r, T::kHeader, 2, 0.0f);
    putF32(r, T::kHeader, 3, 1.0f);
    putU32(r, T::kColors, 3, u32(geo::triangleSampleOffset(rp)));
    // rasterTriangle works on the clockwise (on screen) order v = in0, in2, in1 when the signed
    // area is negative; its edge functions follow v. Attributes are summed in the order o.
    const geo::ScreenVertex* v[3] = {&in0, &in1, &in2};
    const geo::ScreenVertex* o[3] = {&in0, &in1, &in2};
    s64 area = s64(in1.x - in0.x) * (in2.y - in0.y) - s64(in1.y - in0.y) * (in2.x - in0.x);
    if (area < 0) {
        std::swap(v[1], v[2]);
        std::swap(o[0], o[2]);
        area = -area;
        flags |= T::kFlagSwapped;
    }
    s64 A[3], B[3];
    for (int i = 0; i < 3; ++i) {
        const geo::ScreenVertex& a = *v[(i + 1) % 3];
        const geo::ScreenVertex& b = *v[(i + 2) % 3];
        const s64 dx = s64(b.x) - a.x, dy = s64(b.y) - a.y;
        A[i] = -dy, B[i] = dx;
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

    // Depth in attribute order; three equal values are rasterTriangle's constant shortcut.
    putDepths(r, o[0]->z, o[1]->z, o[2]->z);
    // Colours of o[], or the constant source (in0, or the provoking vertex when flat shading)
    // in every slot.
    const geo::TriangleConstants same = geo::triangleConstants(rp, in0, in1, in2, prov);
    const bool colConst = same.color, secConst = same.secondary;
    const geo::ScreenVertex& cs = *same.source;
    for (int i = 0; i < 3; ++i) {
        putU32(r, T::kColors, i, packColor((colConst ? cs : *o[i]).color, 4));
        putU32(r, T::kSecondary, i, packColor((secConst ? cs : *o[i]).secondary, 3));
    }
    if (!colConst) flags |= T::kFlagColorVaries;
    if (!secConst) flags |= T::kFlagSecVaries;
    // Colour gradient planes (rasterTriangle's setupGradients), made once per triangle here as
    // there: the shader steps each channel from the reference vertex (a zero-area triangle has
    // none; the shader's weights draw it).
    if (rp.colourGradients && (!colConst || !secConst) && area > 0) {
        const geo::GradientPlanes g = geo::colourGradientPlanes(o, A, B, (flags & T::kFlagSwapped) != 0, area);
        flags |= T::kFlagColourGradients | (u32(g.ref) << T::kGradientRefShift);
        putU32(r, T::kQ, 3, u32(o[g.ref]->x));
        putU32(r, T::kRecipW, 3, u32(o[g.ref]->y));
        for (int ch = 0; ch < 7; ++ch) {
            const u64 gx = u64(g.gx[ch]), gy = u64(g.gy[ch]);
            u32* t = &grad.w[4 * ch];
            t[0] = u32(gx), t[1] = u32(gx >> 32), t[2] = u32(gy), t[3] = u32(gy >> 32);
        }
    }

    // Fog is interpolated unless fog is off or no vertex is fogged (then the byte is 255).
    putU32(r, T::kHeader, 1, 255u);
    if (!same.fog) {
        flags |= T::kFlagFogVaries;
        for (int i = 0; i < 3; ++i) putF32(r, T::kFog, i, o[i]->fog);
    }
    putU32(r, T::kHeader, 0, flags);
    return (flags & T::kFlagColourGradients) != 0;
}

bool packRectangle(const geo::RasterParams& rp, const geo::ScreenVertex& v0, const geo::ScreenVertex& v1,
                   TriRecord& r, int box[4]) {
    std::memset(&r, 0, sizeof r);
    putU32(r, T::kHeader, 0, T::kKindRect);
    // Covered pixels and texture stepping exactly as rasterRectangle (geo::rectangleSetup); the
    // shader repeats its running sums (shader_gen.cpp exactTexInputs).
    geo::RectSetup rs;
    if (!geo::rectangleSetup(rp, v0, v1, rs)) return false;
    box[0] = rs.px1, box[1] = rs.py1, box[2] = rs.px2, box[3] = rs.py2;
    putU32(r, T::kRectBox, 0, u32(rs.px1)), putU32(r, T::kRectBox, 1, u32(rs.py1));
    putU32(r, T::kRectBox, 2, u32(rs.px2)), putU32(r, T::kRectBox, 3, u32(rs.py2));
    putF32(r, T::kRectStart, 0, rs.rowS), putF32(r, T::kRectStart, 1, rs.rowT);
    putF32(r, T::kRectStart, 2, rs.stxS), putF32(r, T::kRectStart, 3, rs.stxT);
    putF32(r, T::kRectRow, 0, rs.styS), putF32(r, T::kRectRow, 1, rs.styT);
    putF32(r, T::kRectRow, 2, rp.texW0), putF32(r, T::kRectRow, 3, rp.texH0);
    putU32(r, T::kHeader, 1, rp.fog ? geo::fogToByte(v1.fog) : 255u);
    putF32(r, T::kHeader, 2, 0.0f);
    putF32(r, T::kHeader, 3, rp.needW ? v1.w : 1.0f);
    putConstAttributes(r, u16(v1.z), v1.color, v1.secondary);
    return true;
}

void packFragment(const geo::Fragment& f, TriRecord& r) {
    std::memset(&r, 0, sizeof r);
    putU32(r, T::kHeader, 0, T::kKindLinear);
    putF32(r, T::kRectStart, 0, f.s);
    putF32(r, T::kRectStart, 1, f.t);
    putU32(r, T::kHeader, 1, f.fog);
    putF32(r, T::kHeader, 2, f.lod);
    putF32(r, T::kHeader, 3, f.w);
    putConstAttributes(r, f.z, f.color, f.secondary);
}

}  // namespace ge::gl
