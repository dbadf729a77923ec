// Per-triangle records for exact interpolation (see tri_setup.h). Every number mirrors
// softmodel/raster.cpp: rasterTriangle's oriented edges and sample offset, attribute order,
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

    // Depth in attribute order; three equal values are rasterTriangle's constant shortcut.
    putDepths(r, o[0]->z, o[1]->z, o[2]->z);
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

namespace {
s64 floorDiv16(s64 a) { return a >= 0 ? a / 16 : -((15 - a) / 16); }
s64 ceilDiv16(s64 a) { return -floorDiv16(-a); }
}  // namespace

bool packRectangle(const soft::RasterParams& rp, const soft::ScreenVertex& v0, const soft::ScreenVertex& v1,
                   TriRecord& r, int box[4]) {
    std::memset(&r, 0, sizeof r);
    putU32(r, T::kHeader, 0, T::kKindRect);
    const int xl = std::min(v0.x, v1.x), xr = std::max(v0.x, v1.x);
    const int yt = std::min(v0.y, v1.y), yb = std::max(v0.y, v1.y);
    if (xl == xr || yt == yb) return false;  // zero width or height draws nothing (§8.11)
    // Covered pixels as rasterRectangle: from the first centre at or after the near edge; towards
    // the far edge centres strictly inside, plus a centre exactly on the edge when it is the odd
    // pixel of a pair counted from the first one (the reference's 2×2 quad walk); then clipped.
    const int px1 = std::max(int(ceilDiv16(s64(xl) - 8)), rp.clipX1);
    const int py1 = std::max(int(ceilDiv16(s64(yt) - 8)), rp.clipY1);
    auto lastCovered = [](int first, int far, int clip) {
        int last = int(ceilDiv16(s64(far) - 8)) - 1;
        if (((far - 8) & 15) == 0 && ((last + 1 - first) & 1) == 1) ++last;
        return std::min(last, clip);
    };
    const int px2 = lastCovered(px1, xr, rp.clipX2), py2 = lastCovered(py1, yb, rp.clipY2);
    if (px1 > px2 || py1 > py2) return false;
    box[0] = px1, box[1] = py1, box[2] = px2, box[3] = py2;
    putU32(r, T::kRectBox, 0, u32(px1)), putU32(r, T::kRectBox, 1, u32(py1));
    putU32(r, T::kRectBox, 2, u32(px2)), putU32(r, T::kRectBox, 3, u32(py2));

    // Texture coordinates as rasterRectangle steps them in single precision (§8.2 orientation):
    // the change per two pixels, 2·Δ / size, and the start moved from the box corner to the
    // first pixel centre. The shader repeats the running sums (shader_gen.cpp exactTexInputs).
    float rowS = 0, rowT = 0, stxS = 0, stxT = 0, styS = 0, styT = 0;
    if (rp.textured) {
        const float diffX = float(xr - xl) / 16.0f, diffY = float(yb - yt) / 16.0f;
        const float diffS = v1.s - v0.s, diffT = v1.t - v0.t;
        const bool left = v0.x < v1.x, above = v0.y < v1.y;
        if (left && above) {
            rowS = v0.s, rowT = v0.t;
            stxS = 2.0f * diffS / diffX, styT = 2.0f * diffT / diffY;
        } else if (left) {
            rowS = v1.s, rowT = v0.t;
            stxT = 2.0f * diffT / diffX, styS = 2.0f * -diffS / diffY;
        } else if (above) {
            rowS = v0.s, rowT = v1.t;
            stxT = 2.0f * -diffT / diffX, styS = 2.0f * diffS / diffY;
        } else {
            rowS = v1.s, rowT = v1.t;
            stxS = 2.0f * -diffS / diffX, styT = 2.0f * -diffT / diffY;
        }
        const float offX = float(16 * px1 + 8 - xl), offY = float(16 * py1 + 8 - yt);
        rowS = rowS + (stxS / 32.0f) * offX;
        rowT = rowT + (stxT / 32.0f) * offX;
        rowS = rowS + (styS / 32.0f) * offY;
        rowT = rowT + (styT / 32.0f) * offY;
    }
    putF32(r, T::kRectStart, 0, rowS), putF32(r, T::kRectStart, 1, rowT);
    putF32(r, T::kRectStart, 2, stxS), putF32(r, T::kRectStart, 3, stxT);
    putF32(r, T::kRectRow, 0, styS), putF32(r, T::kRectRow, 1, styT);
    putF32(r, T::kRectRow, 2, rp.texW0), putF32(r, T::kRectRow, 3, rp.texH0);
    putU32(r, T::kHeader, 1, rp.fog ? soft::fogToByte(v1.fog) : 255u);
    putF32(r, T::kHeader, 2, 0.0f);
    putF32(r, T::kHeader, 3, rp.needW ? v1.w : 1.0f);
    putConstAttributes(r, u16(v1.z), v1.color, v1.secondary);
    return true;
}

void packFragment(const soft::Fragment& f, TriRecord& r) {
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
