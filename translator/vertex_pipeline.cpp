// SPDX-License-Identifier: MIT
// CPU vertex processing for the GL path (see vertex_pipeline.h).
#include "translator/vertex_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstring>


namespace ge::gl {

namespace {

constexpr size_t kFragmentBuffer = 1024;

GlVertex toGl(const geo::ScreenVertex& v, bool perspective) {
    GlVertex g;
    g.x = float(v.x) / 16.0f;
    g.y = float(v.y) / 16.0f;
    g.z = float(std::clamp(v.z, 0, 65535));
    std::memcpy(g.color, v.color, 4);
    g.color2[0] = v.secondary[0], g.color2[1] = v.secondary[1], g.color2[2] = v.secondary[2];
    g.color2[3] = 0;
    // Texture coordinates are perspective-correct: s/w, t/w, q/w interpolate linearly in screen
    // space and the fragment shader divides (docs/ge-rules.md §8.1). Through mode and rectangles have w = 1.
    const float w = perspective && std::isfinite(v.w) && v.w != 0.0f ? v.w : 1.0f;
    const float k = 1.0f / w;
    g.tex[0] = v.s * k, g.tex[1] = v.t * k, g.tex[2] = v.q * k, g.tex[3] = w;
    g.fog = v.fog;
    return g;
}

// Grows the triangle g by kGrow pixels on every side: each edge moves outward and the corners
// become the offset edges' intersections (3 vertices in out). Where a corner would move further
// than kMiterLimit (a needle-thin triangle) the corners are bevelled instead: a hexagon with two
// points per corner, one offset along each adjacent edge's normal (6 vertices, convex, in order).
// Returns the number of vertices written (3 unchanged when the triangle is degenerate).
int growTriangle(const GlVertex* g, GlVertex* out) {
    constexpr double kGrow = 1.0 / 16.0, kMiterLimit = 4.0;
    for (int i = 0; i < 3; ++i) out[i] = g[i];
    double px[3], py[3];
    for (int i = 0; i < 3; ++i) px[i] = g[i].x, py[i] = g[i].y;
    const double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (!(std::fabs(area) > 0.0)) return 3;
    const double orient = area > 0 ? 1.0 : -1.0;
    // Edge i from corner i to corner i+1: outward unit normal n_i and offset line n_i·p = c_i.
    double nx[3], ny[3], cc[3];
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const double dx = px[j] - px[i], dy = py[j] - py[i];
        const double len = std::sqrt(dx * dx + dy * dy);
        if (!(len > 0.0)) return 3;
        nx[i] = dy / len * orient, ny[i] = -dx / len * orient;
        cc[i] = nx[i] * px[i] + ny[i] * py[i] + kGrow;
    }
    double qx[3], qy[3];
    bool miter = true;
    for (int i = 0; i < 3 && miter; ++i) {
        const int e0 = (i + 2) % 3, e1 = i;  // the edges meeting at corner i
        const double det = nx[e0] * ny[e1] - ny[e0] * nx[e1];
        if (!(std::fabs(det) > 1e-9)) {
            miter = false;
            break;
        }
        qx[i] = (cc[e0] * ny[e1] - ny[e0] * cc[e1]) / det;
        qy[i] = (nx[e0] * cc[e1] - cc[e0] * nx[e1]) / det;
        miter = std::fabs(qx[i] - px[i]) + std::fabs(qy[i] - py[i]) < kMiterLimit;
    }
    if (miter) {
        for (int i = 0; i < 3; ++i) out[i].x = float(qx[i]), out[i].y = float(qy[i]);
        return 3;
    }
    for (int i = 0; i < 3; ++i) {
        const int e0 = (i + 2) % 3, e1 = i;
        out[2 * i] = out[2 * i + 1] = g[i];
        out[2 * i].x = float(px[i] + kGrow * nx[e0]), out[2 * i].y = float(py[i] + kGrow * ny[e0]);
        out[2 * i + 1].x = float(px[i] + kGrow * nx[e1]), out[2 * i + 1].y = float(py[i] + kGrow * ny[e1]);
    }
    return 6;
}

PrimBounds boundsOf(const GlVertex* v, int n) {
    float x0 = v[0].x, x1 = v[0].x, y0 = v[0].y, y1 = v[0].y;
    for (int i = 1; i < n; ++i) {
        x0 = std::min(x0, v[i].x), x1 = std::max(x1, v[i].x);
        y0 = std::min(y0, v[i].y), y1 = std::max(y1, v[i].y);
    }
    auto clampI = [](float f) { return int(std::clamp(f, -70000.0f, 70000.0f)); };
    return PrimBounds{clampI(std::floor(x0)) - 1, clampI(std::floor(y0)) - 1, clampI(std::ceil(x1)),
                      clampI(std::ceil(y1)), 0};
}

}  // namespace

void VertexPipeline::emitTriangle(const geo::ScreenVertex& a, const geo::ScreenVertex& b,
                                  const geo::ScreenVertex& c, const geo::ScreenVertex& prov, int joinPrev) {
    const geo::RasterParams& rp = frontEnd_.rasterParams();
    if (s64(b.x - a.x) * (c.y - a.y) - s64(b.y - a.y) * (c.x - a.x) == 0) {
        // A zero-area triangle covers only samples exactly on its line, with the reference's
        // degenerate attributes (geometry/raster.cpp rasterZeroAreaTriangle): the software
        // rasteriser decides them and each becomes a one-pixel quad, as lines do.
        fragBuf_.resize(kFragmentBuffer);
        geo::FragmentSink sink(fragBuf_.data(), fragBuf_.size(), &VertexPipeline::sinkFlush, this);
        geo::rasterTriangle(rp, a, b, c, prov, geo::Band{}, sink);
        sink.flush();
        return;
    }
    const bool persp = !rp.through;
    GlVertex g[3] = {toGl(a, persp), toGl(b, persp), toGl(c, persp)};
    // The software rasteriser samples triangles at 16·x + o (raster.h triangleSampleOffset), GL
    // at the pixel centre 16·x + 8: moving the triangle by (8 − o)/16 pixel (exact in float on
    // the 1/16 grid) makes GL cover the same pixels.
    const float shift = float(8 - geo::triangleSampleOffset(rp)) / 16.0f;
    for (GlVertex& v : g) v.x += shift, v.y += shift;
    if (!rp.gouraud) {
        // Flat shading: the provoking (last) vertex's colours (ge-rules.md §8.1).
        for (GlVertex& v : g) {
            std::memcpy(v.color, prov.color, 4);
            v.color2[0] = prov.secondary[0], v.color2[1] = prov.secondary[1], v.color2[2] = prov.secondary[2];
        }
    }
    if (!records_) {
        emitting(1);
        out_->tris.insert(out_->tris.end(), g, g + 3);
        PrimBounds bb = boundsOf(g, 3);
        bb.joinPrev = joinPrev;
        out_->triBounds.push_back(bb);
        return;
    }
    // With exact interpolation the fragment shader also applies the software rasteriser's edge
    // test (its top-left rule on the exact edge functions) and discards what that excludes. GL
    // then only has to cover a superset: the triangle is grown by a small margin, so that neither
    // GL's own tie rule nor its clipping of triangles reaching outside the target (which moves
    // their edges by rounding) can lose a pixel on an edge.
    GlVertex grown[6];
    int n = growTriangle(g, grown);
    TriRecord rec;
    GradientRecord grad;
    if (packTriangle(rp, a, b, c, prov, rec, grad)) {
        gradientIndex(rec) = u32(out_->gradients.size());
        out_->gradients.push_back(grad);
    }
    PrimBounds bb = boundsOf(grown, n);
    if (n == 6) {
        // A needle-thin triangle's bevelled hexagon, drawn as a fan, had sliver triangles (two
        // points 1/8 pixel apart, the third hundreds of pixels away) whose orientation GL's
        // subpixel snapping can flip: a flipped sliver covers its neighbours' pixels, so a pixel
        // got two or three fragments — blended two or three times where the shader reads the
        // destination (framebuffer fetch, texture barrier; found by `ge2gl fuzz`, seed 2000953).
        // The hexagon's bounding rectangle on whole pixels is drawn instead: its corners are exact
        // in float and on any subpixel grid, and its two triangles cover each pixel once. The edge
        // test discards the rest; the bevel case is rare (corners sharper than the miter limit).
        float x0 = grown[0].x, x1 = x0, y0 = grown[0].y, y1 = y0;
        for (int i = 1; i < 6; ++i) {
            x0 = std::min(x0, grown[i].x), x1 = std::max(x1, grown[i].x);
            y0 = std::min(y0, grown[i].y), y1 = std::max(y1, grown[i].y);
        }
        auto whole = [](float f) { return std::clamp(f, -70000.0f, 70000.0f); };
        x0 = whole(std::floor(x0)), y0 = whole(std::floor(y0)), x1 = whole(std::ceil(x1)), y1 = whole(std::ceil(y1));
        const float corner[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
        for (int i = 0; i < 4; ++i) grown[i] = g[0], grown[i].x = corner[i][0], grown[i].y = corner[i][1];
        n = 4;
    }
    emitting(u64(n - 2));
    for (int k = 1; k + 1 < n; ++k) {
        const GlVertex t[3] = {grown[0], grown[k], grown[k + 1]};
        out_->tris.insert(out_->tris.end(), t, t + 3);
        bb.joinPrev = k == 1 ? joinPrev : 1;
        out_->triBounds.push_back(bb);
        out_->records.push_back(rec);
    }
}

void VertexPipeline::emitRect(const geo::ScreenVertex& v0, const geo::ScreenVertex& v1) {
    const geo::RasterParams& rp = frontEnd_.rasterParams();
    const int xl = std::min(v0.x, v1.x), xr = std::max(v0.x, v1.x);
    const int yt = std::min(v0.y, v1.y), yb = std::max(v0.y, v1.y);
    if (xl == xr || yt == yb) return;  // zero-size rectangles draw nothing (ge-rules.md §8.11)
    // Texture orientation from where v0 lies relative to v1 (ge-rules.md §8.2 table); colour, Z and fog
    // from the second vertex; coordinates linear across the rectangle (w = 1).
    const bool left = v0.x < v1.x, above = v0.y < v1.y;
    auto corner = [&](int fx, int fy) {
        geo::ScreenVertex c = v1;
        c.x = fx ? xr : xl;
        c.y = fy ? yb : yt;
        c.w = 1.0f;
        const geo::ScreenVertex* sFrom;
        const geo::ScreenVertex* tFrom;
        if (left && above) sFrom = fx ? &v1 : &v0, tFrom = fy ? &v1 : &v0;
        else if (left) sFrom = fy ? &v0 : &v1, tFrom = fx ? &v1 : &v0;
        else if (above) sFrom = fy ? &v1 : &v0, tFrom = fx ? &v0 : &v1;
        else sFrom = fx ? &v0 : &v1, tFrom = fy ? &v0 : &v1;
        c.s = sFrom->s, c.q = sFrom->q, c.t = tFrom->t;
        return toGl(c, false);
    };
    GlVertex tl = corner(0, 0), tr = corner(1, 0), bl = corner(0, 1), br = corner(1, 1);
    if (records_) {
        // Exact interpolation: the record decides the covered pixels (rasterRectangle's far-edge
        // pair rule and clipping) and the shader the texture coordinates; the quad covers
        // exactly that pixel box.
        TriRecord rec;
        int box[4];
        if (!packRectangle(rp, v0, v1, rec, box)) return;
        emitting(2);
        tl.x = bl.x = float(box[0]), tr.x = br.x = float(box[2] + 1);
        tl.y = tr.y = float(box[1]), bl.y = br.y = float(box[3] + 1);
        out_->records.push_back(rec);
        out_->records.push_back(rec);
    } else {
        // GL's top-left rule on [x1, x2) × [y1, y2) covers what the reference covers except where
        // a far edge lies exactly on a pixel centre: the reference's 2×2 walk then also draws that
        // pixel when it is the odd one of a pair (geo::rectangleSetup; transform-mode sprites and
        // float positions at .5, found by `ge2gl fuzz --gl-mode hw`, seed 266). The quad is moved
        // to the reference's pixel box, its texture coordinates extended along the same linear map.
        geo::RectSetup rs;
        if (!geo::rectangleSetup(rp, v0, v1, rs)) return;
        emitting(2);
        const GlVertex otl = tl, otr = tr, obl = bl, obr = br;
        auto at = [&](float x, float y) {
            const float u = (x - otl.x) / (otr.x - otl.x), v = (y - otl.y) / (obl.y - otl.y);
            GlVertex g = otl;
            g.x = x, g.y = y;
            for (int k = 0; k < 4; ++k) {
                const float top = otl.tex[k] + (otr.tex[k] - otl.tex[k]) * u;
                const float bottom = obl.tex[k] + (obr.tex[k] - obl.tex[k]) * u;
                g.tex[k] = top + (bottom - top) * v;
            }
            return g;
        };
        const float x0 = float(rs.px1), x1 = float(rs.px2 + 1), y0 = float(rs.py1), y1 = float(rs.py2 + 1);
        tl = at(x0, y0), tr = at(x1, y0), bl = at(x0, y1), br = at(x1, y1);
    }
    GlVertex q[6] = {tl, tr, bl, tr, br, bl};
    out_->tris.insert(out_->tris.end(), q, q + 6);
    PrimBounds bb = boundsOf(q, 6);
    out_->triBounds.push_back(bb);
    bb.joinPrev = 1;
    out_->triBounds.push_back(bb);
}

void VertexPipeline::sinkFlush(void* ctx, const geo::Fragment* f, size_t n) {
    static_cast<VertexPipeline*>(ctx)->emitFragments(f, n);
}

void VertexPipeline::emitFragments(const geo::Fragment* f, size_t n) {
    // Each fragment of a line or point becomes a one-pixel quad with the fragment's attributes:
    // the GE's line DDA (shared with the software model) decides coverage, not GL.
    emitting(2 * u64(n));
    for (size_t i = 0; i < n; ++i) {
        GlVertex g;
        g.z = float(f[i].z);
        std::memcpy(g.color, f[i].color, 4);
        g.color2[0] = f[i].secondary[0], g.color2[1] = f[i].secondary[1], g.color2[2] = f[i].secondary[2];
        g.tex[0] = f[i].s, g.tex[1] = f[i].t, g.tex[2] = 1.0f, g.tex[3] = f[i].w;
        // The byte back from the shader's floor(f·256) (ge-rules.md §8.9).
        g.fog = (float(f[i].fog) + 0.5f) / 256.0f;
        const float x = float(f[i].x), y = float(f[i].y);
        GlVertex q[6] = {g, g, g, g, g, g};
        q[0].x = x, q[0].y = y;
        q[1].x = x + 1, q[1].y = y;
        q[2].x = x, q[2].y = y + 1;
        q[3].x = x + 1, q[3].y = y;
        q[4].x = x + 1, q[4].y = y + 1;
        q[5].x = x, q[5].y = y + 1;
        out_->tris.insert(out_->tris.end(), q, q + 6);
        PrimBounds bb{f[i].x, f[i].y, f[i].x, f[i].y, 0};
        out_->triBounds.push_back(bb);
        bb.joinPrev = 1;
        out_->triBounds.push_back(bb);
        if (records_) {
            out_->records.emplace_back();
            packFragment(f[i], out_->records.back());
            out_->records.push_back(out_->records.back());
        }
    }
}

void VertexPipeline::primitive(const geo::Primitive& p) {
    switch (p.kind) {
        case geo::PrimKind::Triangle: emitTriangle(*p.v[0], *p.v[1], *p.v[2], *p.prov, p.joinPrev); return;
        case geo::PrimKind::Rect: emitRect(*p.v[0], *p.v[1]); return;
        case geo::PrimKind::Line:
        case geo::PrimKind::Point: break;
    }
    // Lines and points: the GE's DDA (shared with the software model) decides coverage, each
    // fragment a one-pixel quad (emitFragments).
    fragBuf_.resize(kFragmentBuffer);
    geo::FragmentSink sink(fragBuf_.data(), fragBuf_.size(), &VertexPipeline::sinkFlush, this);
    if (p.kind == geo::PrimKind::Line) geo::rasterLine(frontEnd_.rasterParams(), *p.v[0], *p.v[1], geo::Band{}, sink);
    else geo::rasterPoint(frontEnd_.rasterParams(), *p.v[0], geo::Band{}, sink);
    sink.flush();
}

bool VertexPipeline::processPrim(const Memory& mem, const GeState& st, const PrimPacket& p, Geometry& out,
                                 std::string* err) {
    out_ = &out;
    return frontEnd_.prim(mem, st, p, *this, err);
}

bool VertexPipeline::processPatch(const Memory& mem, const GeState& st, const PatchPacket& p, Geometry& out,
                                  std::string* err) {
    out_ = &out;
    return frontEnd_.patch(mem, st, p, *this, err);
}

void VertexPipeline::processImmediate(const GeState& st, const ImmPacket& p, Geometry& out) {
    out_ = &out;
    frontEnd_.immediate(geo::immediateState(st, p.flags), p, *this);
}

}  // namespace ge::gl
