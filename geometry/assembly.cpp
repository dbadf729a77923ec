// SPDX-License-Identifier: MIT
// Rectangle detection and rectangle corners of primitive assembly (see assembly.h).
#include "geometry/assembly.h"

#include <algorithm>
#include <cstring>

#include "geometry/texture_size.h"

namespace ge::geo {

RectDetect RectDetect::fromState(const GeState& st, bool through, bool textured, bool fresh) {
    RectDetect rd;
    rd.allowed = fresh;
    rd.through = through;
    rd.textured = textured && !st.isClearMode();
    rd.fog = st.FGE_on() && !through && !st.isClearMode();
    rd.depthMatters = st.isClearMode() ? st.CMODE_depth()
                                       : st.ZTE_on() && (st.ZTEST_func() != 1 || !st.ZMSK_nowrite());
    return rd;
}

namespace {

// The reference's conditions shared by strips and fans: same primary colour; same Z unless depth
// does not matter; in transform mode also the same secondary colour, no vertex outside the screen
// range, W ≥ 0 and Z ≥ −W, W within 1/512 and equal Q when texturing, fog within half a step when
// fogging. `itl`/`ibr` get the top-left and bottom-right corners (indices 0–3).
bool quadIsFlat(const RectDetect& rd, const ClipVertex* const d[4], int& itl, int& ibr) {
    for (int i = 0; i < 4; ++i)
        if (!d[i]->valid) return false;
    const bool through = rd.through;
    auto compatible = [&](const ClipVertex& c) {
        return through || !(c.outside || c.clip[3] < 0.0f || c.clip[2] < -c.clip[3]);
    };
    if (!compatible(*d[0])) return false;
    itl = 0, ibr = 0;
    for (int i = 1; i < 4; ++i) {
        const ScreenVertex &a = d[0]->sv, &b = d[i]->sv;
        if (std::memcmp(a.color, b.color, 4) != 0) return false;
        if (a.z != b.z && rd.depthMatters) return false;
        if (!through) {
            if (std::memcmp(a.secondary, b.secondary, 3) != 0 || !compatible(*d[i])) return false;
            if (rd.textured && d[i]->clip[3] != d[0]->clip[3]) {
                constexpr float halfTexel = 0.5f / 512.0f;
                if (d[i]->clip[3] - halfTexel > d[0]->clip[3] || d[i]->clip[3] + halfTexel < d[0]->clip[3])
                    return false;
            }
            if (rd.textured && b.q != a.q) return false;
            if (rd.fog && b.fog != a.fog) {
                constexpr float halfStep = 0.5f / 255.0f;
                if (b.fog - halfStep > a.fog || b.fog + halfStep < a.fog) return false;
            }
        }
        if (b.x <= d[itl]->sv.x && b.y <= d[itl]->sv.y) itl = i;
        if (b.x >= d[ibr]->sv.x && b.y >= d[ibr]->sv.y) ibr = i;
    }
    return true;
}

}  // namespace

bool stripQuadAsRect(const RectDetect& rd, const ClipVertex* const d[4], int& tl, int& br) {
    if (!quadIsFlat(rd, d, tl, br)) return false;
    const ScreenVertex &p0 = d[0]->sv, &p1 = d[1]->sv, &p2 = d[2]->sv, &p3 = d[3]->sv;
    // Through-mode texture coordinates are compared in texels as given; s and t here are scaled
    // by the same level-0 size for every vertex, so equality is unchanged.
    if (p0.x == p1.x && p0.y == p2.y && p2.x == p3.x && p1.y == p3.y)
        return !rd.textured || (p0.s == p1.s && p0.t == p2.t && p2.s == p3.s && p1.t == p3.t);
    if (p0.x == p2.x && p0.y == p1.y && p1.x == p3.x && p2.y == p3.y)
        return !rd.textured || (p0.s == p2.s && p0.t == p1.t && p1.s == p3.s && p2.t == p3.t);
    return false;
}

bool fanQuadAsRect(const RectDetect& rd, const ClipVertex* const d[4], int& tl, int& br) {
    int itl = 0, ibr = 0;
    if (!quadIsFlat(rd, d, itl, ibr)) return false;
    // The two other corners: bottom-left and top-right; each corner must be found once.
    int itr = 1, ibl = 1;
    for (int i = 0; i < 4; ++i) {
        if (i == itl || i == ibr) continue;
        if (d[i]->sv.x <= d[itl]->sv.x && d[i]->sv.y >= d[itl]->sv.y) ibl = i;
        if (d[i]->sv.x >= d[ibr]->sv.x && d[i]->sv.y <= d[ibr]->sv.y) itr = i;
    }
    if (itl + itr + ibl + ibr != 6) return false;
    const ScreenVertex &ptl = d[itl]->sv, &ptr = d[itr]->sv, &pbl = d[ibl]->sv, &pbr = d[ibr]->sv;
    if (ptl.x != pbl.x || ptr.x != pbr.x || ptl.y != ptr.y || pbl.y != pbr.y) return false;
    tl = itl, br = ibr;
    if (!rd.textured) return true;
    // Matching texture coordinates along the edges, and texture not mirrored against the screen.
    if (ptl.s != pbl.s || ptr.s != pbr.s || ptl.t != ptr.t || pbl.t != pbr.t) return false;
    return ptl.t < pbr.t && ptl.y < pbr.y && ptl.s < pbr.s && ptl.x < pbr.x;
}

void immediateVertices(const GeState& st, const std::vector<ImmVertex>& in, std::vector<ClipVertex>& out,
                       std::vector<u32>& seq) {
    const bool through = st.isThrough();
    const bool projective = !through && st.TMAP_mode() == 1;
    // The secondary colour (I2) is added only with separate specular (LMODE 1) in transform mode;
    // otherwise the vertices have none. Hardware (pspautotests gpu/primitives/immediate, I2 =
    // 0x7F7F7F): a flat fan of (0, 127, 255) shows 0x7FFEFF with LMODE 1 in transform mode, 0x007FFF
    // with LMODE 1 in through mode, and every primitive drawn with LMODE 0 (points, lines, strips,
    // the Gouraud fan, the fogged sprite, the textured fans) shows its primary colour alone.
    // Lighting (LTE) is off there: the condition does not read it. The reference renderer agrees
    // (GPU/Software/TransformUnit.cpp: color1 = isUsingSecondaryColor() && !isModeThrough() ? I2 : 0).
    const bool secondary = !through && st.LMODE_separate();
    // Through mode's texel coordinates over the unclamped 2^n (texture_size.h), as in transform.cpp.
    const float invW = 1.0f / float(texCoordWidth(st, 0)), invH = 1.0f / float(texCoordHeight(st, 0));
    auto to16 = [](float v) {
        float t = v * 16.0f;
        if (!(t > -1048576.0f)) t = -1048576.0f;  // also NaN
        if (t > 1048576.0f) t = 1048576.0f;
        return int(t);
    };
    out.resize(in.size());
    seq.clear();
    for (size_t i = 0; i < in.size(); ++i) {
        const ImmVertex& iv = in[i];
        ClipVertex& cv = out[i];
        cv = ClipVertex{};
        ScreenVertex& sv = cv.sv;
        sv.x = to16(iv.x);
        sv.y = to16(iv.y);
        sv.z = iv.z;
        sv.s = through ? iv.s * invW : iv.s;
        sv.t = through ? iv.t * invH : iv.t;
        sv.q = projective ? iv.q : 1.0f;
        sv.w = 1.0f;
        sv.fog = float(iv.fog) / 255.0f;
        std::memcpy(sv.color, iv.color, 4);
        if (secondary) std::memcpy(sv.secondary, iv.secondary, 3);
        seq.push_back(u32(i));
    }
}

ScreenVertex rectangleCorner(const ScreenVertex& v0, const ScreenVertex& v1, int fx, int fy) {
    ScreenVertex c = v1;
    c.x = fx ? std::max(v0.x, v1.x) : std::min(v0.x, v1.x);
    c.y = fy ? std::max(v0.y, v1.y) : std::min(v0.y, v1.y);
    c.w = 1.0f;
    const bool left = v0.x < v1.x, above = v0.y < v1.y;
    const ScreenVertex* sFrom;
    const ScreenVertex* tFrom;
    if (left && above) sFrom = fx ? &v1 : &v0, tFrom = fy ? &v1 : &v0;
    else if (left) sFrom = fy ? &v0 : &v1, tFrom = fx ? &v1 : &v0;
    else if (above) sFrom = fy ? &v1 : &v0, tFrom = fx ? &v0 : &v1;
    else sFrom = fx ? &v0 : &v1, tFrom = fy ? &v0 : &v1;
    c.s = sFrom->s, c.q = sFrom->q, c.t = tFrom->t;
    return c;
}

}  // namespace ge::geo
