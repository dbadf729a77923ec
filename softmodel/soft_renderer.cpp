// SPDX-License-Identifier: MIT
// The software model's Renderer: primitive assembly, batching and band threads (see soft_renderer.h).
#include "softmodel/soft_renderer.h"

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "geometry/assembly.h"
#include "geometry/clip.h"
#include "geometry/raster.h"
#include "geometry/spline.h"
#include "geometry/texture_size.h"
#include "geometry/transform.h"
#include "hle/vertex_decoder.h"
#include "softmodel/pixel.h"

namespace ge::soft {

namespace {

constexpr size_t kFragmentBuffer = 1024;       // fragments handed to shadeFragments at a time
constexpr size_t kBatchPrimitives = 8192;      // a batch is dispatched when it holds this many
constexpr size_t kBatchVertices = 24576;
constexpr int kMaxThreads = 32;                // 64 bands of 16 rows cover the 1024-row space

struct RasterPrim {
    geo::PrimKind kind = geo::PrimKind::Point;
    u32 v[3] = {};   // indices into Batch::verts
    u32 prov = 0;    // flat-shading vertex (triangles)
    int y1 = 0, y2 = -1;  // pixel rows the primitive can touch, clipped
};

struct DrawItem {
    PixelState ps;
    geo::RasterParams rp;
    u32 firstPrim = 0, primEnd = 0;
};

// VRAM byte range [begin, end) as linear offsets from 0x04000000 (all mirrors alias, docs/ge-rules.md §7.3).
struct VramRange {
    u32 begin = 0, end = 0;
};

bool overlaps(const VramRange& a, const VramRange& b) { return a.begin < b.end && b.begin < a.end; }

void addRange(std::vector<VramRange>& list, VramRange r) {
    if (r.begin >= r.end) return;
    for (VramRange& e : list) {
        if (r.begin >= e.begin && r.end <= e.end) return;
        if (e.begin >= r.begin && e.end <= r.end) {
            e = r;
            return;
        }
    }
    list.push_back(r);
}

// A draw's render target: frame buffer and (when written or tested) depth buffer, with the VRAM
// bytes each may touch.
struct Target {
    u32 fb = 0, fbStride = 0, fmt = 0, zb = 0, zbStride = 0;
    bool depth = false;
    VramRange fbRange, zbRange;
    bool sameBuffers(const Target& o) const {
        return fb == o.fb && fbStride == o.fbStride && fmt == o.fmt && depth == o.depth &&
               (!depth || (zb == o.zb && zbStride == o.zbStride));
    }
    // Bands own rows, so one batch may only hold targets whose bytes do not alias: two targets
    // sharing bytes at different rows would have two threads write them in either order.
    bool aliases(const Target& o) const {
        if (overlaps(fbRange, o.fbRange)) return true;
        if (depth && (overlaps(zbRange, o.fbRange) || (o.depth && overlaps(zbRange, o.zbRange)))) return true;
        return o.depth && overlaps(fbRange, o.zbRange);
    }
};

struct Batch {
    std::vector<geo::ScreenVertex> verts;
    std::vector<RasterPrim> prims;
    std::vector<DrawItem> draws;
    std::vector<VramRange> writes;  // what the queued draws may write (frame and depth buffers)
    std::vector<Target> targets;    // the render targets of the queued draws
    bool empty() const { return draws.empty(); }
    void clear() {
        verts.clear();
        prims.clear();
        draws.clear();
        writes.clear();
        targets.clear();
    }
};

void shadeCallback(void* ctx, const geo::Fragment* f, size_t n) {
    shadeFragments(*static_cast<const PixelState*>(ctx), f, n);
}

// Rasterises every primitive of a batch that touches the band, draw by draw, in order.
void rasterBatch(const Batch& b, const geo::Band& band, std::vector<geo::Fragment>& buf) {
    geo::FragmentSink sink(buf.data(), buf.size(), shadeCallback, nullptr);
    for (const DrawItem& d : b.draws) {
        sink.setTarget(shadeCallback, const_cast<PixelState*>(&d.ps));
        for (u32 i = d.firstPrim; i < d.primEnd; ++i) {
            const RasterPrim& p = b.prims[i];
            if (!band.overlaps(p.y1, p.y2)) continue;
            const geo::ScreenVertex* v = b.verts.data();
            switch (p.kind) {
            case geo::PrimKind::Triangle:
                geo::rasterTriangle(d.rp, v[p.v[0]], v[p.v[1]], v[p.v[2]], v[p.prov], band, sink);
                break;
            case geo::PrimKind::Rect: geo::rasterRectangle(d.rp, v[p.v[0]], v[p.v[1]], band, sink); break;
            case geo::PrimKind::Line: geo::rasterLine(d.rp, v[p.v[0]], v[p.v[1]], band, sink); break;
            case geo::PrimKind::Point: geo::rasterPoint(d.rp, v[p.v[0]], band, sink); break;
            }
        }
    }
    sink.flush();
}

// Bits per texel of each CMD_TPF format (for the bytes a texture level spans, ge-rules.md §6.1).
u32 texelBits(u32 fmt) {
    static constexpr u8 bits[16] = {16, 16, 16, 32, 4, 8, 16, 32, 4, 8, 8, 32, 32, 32, 32, 32};
    return bits[fmt & 15];
}

VramRange vramRange(u32 addr, u64 bytes) {
    // Linear offset inside the 2 MiB; a range running past the end is cut there (a wrap would be
    // a corrupt setting; the conservative answer for the hazard check is the tail).
    const u32 off = (Memory::normalize(addr) - Memory::kVramBase) & (Memory::kVramSize - 1);
    const u64 end = std::min<u64>(u64(off) + bytes, Memory::kVramSize);
    return {off, u32(end)};
}

geo::RasterParams makeRasterParams(const GeState& st, bool through, bool textured) {
    geo::RasterParams rp;
    // Scissor ∩ REGION2 (ge-rules.md §8.6; REGION1 is kept 0 by games).
    rp.clipX1 = int(st.SCISSOR1_x());
    rp.clipY1 = int(st.SCISSOR1_y());
    rp.clipX2 = int(std::min(st.SCISSOR2_x(), st.REGION2_x()));
    rp.clipY2 = int(std::min(st.SCISSOR2_y(), st.REGION2_y()));
    // Clear mode draws flat: colour from the provoking vertex (PPSSPP's software renderer).
    rp.gouraud = st.SHADE_gouraud() && !st.isClearMode();
    rp.textured = textured && !st.isClearMode();
    const u32 levelMode = st.TLEVEL_mode();
    rp.needLod = rp.textured && levelMode == 0;
    rp.needW = rp.textured && levelMode == 2;
    rp.fog = !through && st.FGE_on();
    rp.through = through;
    rp.texW0 = float(geo::texCoordWidth(st, 0));  // unclamped 2^n (geometry/texture_size.h)
    rp.texH0 = float(geo::texCoordHeight(st, 0));
    return rp;
}

}  // namespace

struct SoftRenderer::Impl {
    Impl(Memory& m, const SoftOptions& opt) : mem(m), cache(createTextureCache()) {
        int n = opt.threads;
        if (n <= 0) n = int(std::thread::hardware_concurrency());
        threads = std::clamp(n, 1, kMaxThreads);
        fragBufs.resize(size_t(threads), std::vector<geo::Fragment>(kFragmentBuffer));
        if (threads > 1) {
            for (int i = 0; i < threads; ++i) workers.emplace_back([this, i] { workerLoop(i); });
        }
    }
    ~Impl() {
        waitIdle();
        {
            std::lock_guard<std::mutex> lk(m);
            quit = true;
        }
        cvWork.notify_all();
        for (std::thread& t : workers) t.join();
    }

    // ---- threads and batches ----
    void workerLoop(int index) {
        u64 seen = 0;
        for (;;) {
            const Batch* b;
            {
                std::unique_lock<std::mutex> lk(m);
                cvWork.wait(lk, [&] { return quit || generation != seen; });
                if (quit) return;
                seen = generation;
                b = job;
            }
            rasterBatch(*b, geo::Band{index, threads}, fragBufs[size_t(index)]);
            {
                std::lock_guard<std::mutex> lk(m);
                if (--remaining == 0) cvDone.notify_all();
            }
        }
    }

    Batch& building() { return batches[buildIndex]; }

    // Drops the texture cache's copies of what a finished batch drew, so later draws texturing
    // from those bytes (render to texture) decode the new contents.
    void retire(Batch& b) {
        for (const VramRange& r : b.writes) invalidateTextureCache(*cache, Memory::kVramBase + r.begin, r.end - r.begin);
        if (!b.writes.empty()) psValid = false;
        b.clear();
    }

    void retireInFlight() {
        if (!inFlight) return;
        {
            std::unique_lock<std::mutex> lk(m);
            cvDone.wait(lk, [&] { return remaining == 0; });
        }
        inFlight = false;
        retire(batches[buildIndex ^ 1]);
    }

    void submit() {
        Batch& b = building();
        if (b.empty()) return;
        ++stats.batches;
        retireInFlight();
        if (threads <= 1) {
            rasterBatch(b, geo::Band{}, fragBufs[0]);
            retire(b);
            return;
        }
        {
            std::lock_guard<std::mutex> lk(m);
            job = &b;
            remaining = threads;
            ++generation;
        }
        cvWork.notify_all();
        inFlight = true;
        buildIndex ^= 1;  // the other batch was retired above: empty
    }

    void waitIdle() {
        submit();
        retireInFlight();
    }

    bool hasWork() const { return inFlight || !batches[buildIndex].empty(); }

    // True when r overlaps what the building or the in-flight batch may write.
    bool queuedWritesOverlap(const VramRange& r) const {
        for (int k = 0; k < 2; ++k) {
            if (k == 1 && !inFlight) continue;
            for (const VramRange& w : batches[k == 0 ? buildIndex : buildIndex ^ 1].writes)
                if (overlaps(r, w)) return true;
        }
        return false;
    }

    // True when the texture of the coming draw may overlap what queued draws write.
    bool textureHazard(const GeState& st) const {
        if (!hasWork()) return false;
        const u32 maxLevel = std::min<u32>(st.TMODE_maxlevel(), 7);
        const u32 bits = texelBits(st.TPF_format());
        for (u32 l = 0; l <= maxLevel; ++l) {
            const u32 addr = st.textureAddr(int(l));
            if (!Memory::isVram(addr)) continue;
            const u64 bytes = u64(st.textureBufWidth(int(l))) * st.textureHeight(int(l)) * bits / 8 + 16;
            if (queuedWritesOverlap(vramRange(addr, bytes))) return true;
        }
        return false;
    }

    // True when bytes the host writes at [addr, addr + size) may be ones queued or running draws
    // read or write. Draws keep their own copies of vertices and decoded textures, so they touch
    // guest memory only in the frame and depth buffers (Batch::writes, in the plain VRAM view):
    // RAM writes (the dump player's vertex and texture payloads) need no wait. A write reaching
    // a VRAM mirror, or of unknown size, is answered conservatively.
    bool queuedTouches(u32 addr, u32 size) const {
        if (!hasWork()) return false;
        const u32 a = Memory::normalize(addr);
        const u64 end = u64(a) + (size ? size : 1);
        if (end <= Memory::kVramBase || a >= Memory::kVramMirrorsEnd) return false;
        if (size == 0 || a < Memory::kVramBase || end > u64(Memory::kVramBase) + Memory::kVramSize) return true;
        return queuedWritesOverlap(VramRange{a - Memory::kVramBase, u32(end - Memory::kVramBase)});
    }

    // The render target of a draw with this state and clip rectangle: the frame/depth buffer
    // bytes it may write.
    static Target targetOf(const GeState& st, const geo::RasterParams& rp) {
        Target t;
        const int rows = std::clamp(rp.clipY2 + 1, 0, 1024);
        const u32 bpp = st.framebufFormat() == GE_FORMAT_8888 ? 4 : 2;
        t.fb = st.framebufAddr(), t.fbStride = st.framebufStride(), t.fmt = u32(st.framebufFormat());
        t.fbRange = vramRange(t.fb, u64(t.fbStride) * rows * bpp);
        t.depth = st.ZTE_on() || st.isClearMode();
        if (t.depth) {
            t.zb = st.depthbufAddr(), t.zbStride = st.depthbufStride();
            t.zbRange = vramRange(t.zb, u64(t.zbStride) * rows * 2);
        }
        return t;
    }

    // Records the draw's target in the building batch; a target aliasing another one already
    // there first sends the batch off (batches run one after the other, in order).
    void noteTarget(const Target& t) {
        for (const Target& e : building().targets) {
            if (threads <= 1) break;  // one thread draws everything in order
            if (e.sameBuffers(t)) continue;
            if (e.aliases(t)) {
                submit();
                break;
            }
        }
        Batch& b = building();
        for (const Target& e : b.targets)
            if (e.sameBuffers(t)) return;
        b.targets.push_back(t);
        addRange(b.writes, t.fbRange);
        if (t.depth) addRange(b.writes, t.zbRange);
    }

    // ---- per draw ----
    // Whether every primary colour of the assembled primitives that reaches a fragment has alpha
    // 255: all vertices with Gouraud shading, the provoking one with flat shading and for
    // rectangles (as the reference's CalculateRasterStateFlags reads them).
    bool colorsReachingFragmentsFullAlpha(const geo::RasterParams& rp) const {
        for (const RasterPrim& p : scratchPrims) {
            if (scratchVerts[p.prov].color[3] != 255) return false;
            if (!rp.gouraud || p.kind == geo::PrimKind::Rect) continue;
            const int n = p.kind == geo::PrimKind::Triangle ? 3 : (p.kind == geo::PrimKind::Line ? 2 : 1);
            for (int k = 0; k < n; ++k)
                if (scratchVerts[p.v[k]].color[3] != 255) return false;
        }
        return true;
    }

    // Queues the primitives assembled in `scratch` as one draw with the given state.
    void queueDraw(const GeState& st, const geo::RasterParams& rp, bool textured, bool forceRebuild) {
        if (scratchPrims.empty()) return;
        // Render to texture: the texture must see every earlier draw's pixels (ge-rules.md §8.13).
        if (rp.textured && textureHazard(st)) waitIdle();
        const bool through = st.isThrough();
        constexpr u32 kPixelDirty = DIRTY_TEXTURE | DIRTY_CLUT | DIRTY_FRAGMENT | DIRTY_BLEND | DIRTY_DEPTHSTENCIL |
                                    DIRTY_RASTER | DIRTY_FRAMEBUF;
        // Before the pixel state is built: sending the batch off may retire one whose writes
        // invalidate cached textures.
        noteTarget(targetOf(st, rp));
        const bool alphaFull = colorsReachingFragmentsFullAlpha(rp);
        if (forceRebuild || !psValid || (pendingDirty & kPixelDirty) || through != psThrough || textured != psTextured ||
            alphaFull != psAlphaFull) {
            ps = buildPixelState(st, mem, *cache, textured, alphaFull);
            psValid = !forceRebuild;
            psThrough = through;
            psTextured = textured;
            psAlphaFull = alphaFull;
            pendingDirty = 0;
        }
        Batch& b = building();
        const u32 base = u32(b.verts.size());
        b.verts.insert(b.verts.end(), scratchVerts.begin(), scratchVerts.end());
        DrawItem d;
        d.ps = ps;
        d.rp = rp;
        d.firstPrim = u32(b.prims.size());
        for (RasterPrim p : scratchPrims) {
            p.v[0] += base, p.v[1] += base, p.v[2] += base, p.prov += base;
            b.prims.push_back(p);
        }
        d.primEnd = u32(b.prims.size());
        b.draws.push_back(std::move(d));
        stats.primitives += scratchPrims.size();
        if (b.prims.size() >= kBatchPrimitives || b.verts.size() >= kBatchVertices) submit();
    }

    // ---- primitive assembly (into scratchVerts / scratchPrims) ----
    u32 pushVertex(u32 ci) {
        if (vertIndex[ci] < 0) {
            vertIndex[ci] = s32(scratchVerts.size());
            scratchVerts.push_back(cverts[ci].sv);
        }
        return u32(vertIndex[ci]);
    }
    u32 pushNew(const geo::ScreenVertex& sv) {
        scratchVerts.push_back(sv);
        return u32(scratchVerts.size() - 1);
    }
    void addPrim(geo::PrimKind kind, u32 a, u32 b, u32 c, u32 prov) {
        RasterPrim p;
        p.kind = kind;
        p.v[0] = a, p.v[1] = b, p.v[2] = c;
        p.prov = prov;
        const geo::ScreenVertex* v[3] = {&scratchVerts[a], &scratchVerts[b], &scratchVerts[c]};
        if (!geo::primitiveRows(rp, kind, v, p.y1, p.y2)) return;  // wholly outside the clip rectangle
        const u64 bound = geo::primitivePixelBound(rp, kind, v, p.y1, p.y2);
        if (bound > pixelBudgetLeft) {  // the GE-time limit reached into this draw: dropped,
            pixelBudgetLeft = 0;        // but charged, so the engine sees the limit passed
            pixelWork += bound;
            ++stats.budgetDropped;
            return;
        }
        pixelBudgetLeft -= bound;
        pixelWork += bound;
        scratchPrims.push_back(p);
    }

    // Back-face culling (ge-rules.md §3.6): CULL = 0 culls triangles clockwise on screen (y down), 1 counter-
    // clockwise ones. Zero-area triangles are never culled: the rasteriser draws the samples they
    // pass through as the reference does (raster.cpp rasterZeroAreaTriangle).
    bool culled(const geo::ScreenVertex& a, const geo::ScreenVertex& b, const geo::ScreenVertex& c) const {
        const s64 area = s64(b.x - a.x) * (c.y - a.y) - s64(b.y - a.y) * (c.x - a.x);
        if (!cullOn || area == 0) return false;
        return cullClockwise ? area > 0 : area < 0;
    }

    // A triangle in primitive order; the third vertex is the provoking one (ge-rules.md §8.1).
    // `ring`, when given, is the order the vertices are handed to the rasteriser in (see assemble);
    // (ia, ib, ic) is the winding order used for culling and clipping.
    void triangle(u32 ia, u32 ib, u32 ic, const u32* ring = nullptr) {
        const geo::ClipVertex& a = cverts[ia];
        const geo::ClipVertex& b = cverts[ib];
        const geo::ClipVertex& c = cverts[ic];
        const geo::ClipVertex* v[3] = {&a, &b, &c};
        if (!a.valid || !b.valid || !c.valid || geo::discardPrimitive(*ts, v, 3)) {
            ++stats.discarded;
            return;
        }
        if (!ts->through) {
            if (a.clip[3] < 0.0f && b.clip[3] < 0.0f && c.clip[3] < 0.0f) {  // ge-rules.md §8.5
                ++stats.discarded;
                return;
            }
            // Near clipping whatever CLE says: CLE selects only the depth clamp and the discard
            // rule (ge-rules.md §8.5; PPSSPP Clipper::ProcessTriangle).
            if (geo::beyondNear(a) || geo::beyondNear(b) || geo::beyondNear(c)) {
                // Clipped in the reference's vertex order (the strip/fan ring, clip.h).
                const bool reversed = ring && geo::ringReversed(ring, ia, ib);
                geo::ClipVertex poly[4];
                const int n = ring ? geo::clipTriangleNear(*ts, cverts[ring[0]], cverts[ring[1]], cverts[ring[2]], poly)
                                   : geo::clipTriangleNear(*ts, a, b, c, poly);
                ++stats.clipped;
                if (n < 3) return;
                // Flat shading keeps the original provoking vertex's colour.
                const u32 prov = pushVertex(ic);
                u32 idx[4];
                bool pushed[4] = {};
                for (int k = 1; k + 1 < n; ++k) {
                    const int k1 = reversed ? k + 1 : k, k2 = reversed ? k : k + 1;  // primitive's winding
                    if (culled(poly[0].sv, poly[k1].sv, poly[k2].sv)) {
                        ++stats.culled;
                        continue;
                    }
                    for (int j : {0, k, k + 1}) {
                        if (!pushed[j]) idx[j] = pushNew(poly[j].sv), pushed[j] = true;
                    }
                    addPrim(geo::PrimKind::Triangle, idx[0], idx[k], idx[k + 1], prov);
                }
                return;
            }
        }
        if (culled(a.sv, b.sv, c.sv)) {
            ++stats.culled;
            return;
        }
        if (ring) {
            addPrim(geo::PrimKind::Triangle, pushVertex(ring[0]), pushVertex(ring[1]), pushVertex(ring[2]), pushVertex(ic));
        } else {
            addPrim(geo::PrimKind::Triangle, pushVertex(ia), pushVertex(ib), pushVertex(ic), pushVertex(ic));
        }
    }

    void line(u32 ia, u32 ib) {
        const geo::ClipVertex* v[2] = {&cverts[ia], &cverts[ib]};
        if (!v[0]->valid || !v[1]->valid || geo::discardPrimitive(*ts, v, 2)) {
            ++stats.discarded;
            return;
        }
        if (!ts->through && (geo::beyondNear(*v[0]) || geo::beyondNear(*v[1]))) {  // whatever CLE says (ge-rules.md §8.5)
            geo::ClipVertex a = *v[0], b = *v[1];
            ++stats.clipped;
            if (!geo::clipLineNear(*ts, a, b)) return;
            const u32 i0 = pushNew(a.sv), i1 = pushNew(b.sv);
            addPrim(geo::PrimKind::Line, i0, i1, i1, i1);
            return;
        }
        const u32 i0 = pushVertex(ia), i1 = pushVertex(ib);
        addPrim(geo::PrimKind::Line, i0, i1, i1, i1);
    }

    void point(u32 ia) {
        const geo::ClipVertex* v[1] = {&cverts[ia]};
        if (!v[0]->valid || geo::discardPrimitive(*ts, v, 1)) {
            ++stats.discarded;
            return;
        }
        const u32 i = pushVertex(ia);
        addPrim(geo::PrimKind::Point, i, i, i, i);
    }

    void rectangle(u32 ia, u32 ib) {
        const geo::ClipVertex* v[2] = {&cverts[ia], &cverts[ib]};
        if (!v[0]->valid || !v[1]->valid || geo::discardPrimitive(*ts, v, 2)) {
            ++stats.discarded;
            return;
        }
        if (ts->rectAsTriangles) {
            rectangleAsTriangles(v[0]->sv, v[1]->sv);
            return;
        }
        const u32 i0 = pushVertex(ia), i1 = pushVertex(ib);
        addPrim(geo::PrimKind::Rect, i0, i1, i1, i1);
    }

    // Rectangles with texture projection are drawn as two triangles (ge-rules.md §8.2), corners textured by
    // the orientation table, colour/Z/fog of the second vertex.
    void rectangleAsTriangles(const geo::ScreenVertex& v0, const geo::ScreenVertex& v1) {
        if (v0.x == v1.x || v0.y == v1.y) return;
        const u32 tl = pushNew(geo::rectangleCorner(v0, v1, 0, 0)), tr = pushNew(geo::rectangleCorner(v0, v1, 1, 0));
        const u32 bl = pushNew(geo::rectangleCorner(v0, v1, 0, 1)), br = pushNew(geo::rectangleCorner(v0, v1, 1, 1));
        addPrim(geo::PrimKind::Triangle, tl, tr, bl, bl);
        addPrim(geo::PrimKind::Triangle, tr, br, bl, bl);
    }

    // Strip/fan quads drawn as rectangles (geometry/assembly.h, shared with the GL translator):
    // `tl`/`br` get the top-left and bottom-right vertices (the rectangle's v0 and v1).
    bool quadAsRect(bool fan, const u32 q[4], u32& tl, u32& br) const {
        const geo::ClipVertex* d[4] = {&cverts[q[0]], &cverts[q[1]], &cverts[q[2]], &cverts[q[3]]};
        int itl = 0, ibr = 0;
        const bool rect = fan ? geo::fanQuadAsRect(rectDetect, d, itl, ibr) : geo::stripQuadAsRect(rectDetect, d, itl, ibr);
        if (!rect) return false;
        tl = q[itl], br = q[ibr];
        return true;
    }

    // Assembles `seq` (indices into cverts, in draw order) as `prim` (assembly.h); what does not
    // complete a primitive, and the strip/fan state, is kept in `pending` for PRIM type 7 (ge-rules.md §3.2,
    // §8.11).
    void assemble(GePrimType prim, const std::vector<u32>& seq, bool keepPending) {
        geo::assemblePrimitives(prim, seq, rectDetect.allowed && !cullOn, stripOdd, *this, keepScratch);
        if (keepPending) {
            pending.clear();
            for (u32 k : keepScratch) pending.push_back(cverts[k]);
        }
    }

    void beginAssembly(const geo::TransformState& t, const geo::RasterParams& r, bool cull, bool cullCw) {
        ts = &t;
        rp = r;
        cullOn = cull;
        cullClockwise = cullCw;
        scratchVerts.clear();
        scratchPrims.clear();
        vertIndex.assign(cverts.size(), -1);
    }

    // Decodes the vertices a draw uses (each distinct one once) into cverts after `first`
    // entries already there, and the draw order into `seq`. False on unreadable data.
    bool decodeDraw(const GeState& st, u32 vtype, u32 vaddr, u32 iaddr, u32 count, const geo::TransformState& t,
                    std::vector<u32>& seq) {
        VertexReader reader(mem, st, vtype);
        if (!reader.readIndices(iaddr, count, indices)) return false;
        const bool skin = reader.hasWeights() && !reader.through();
        const size_t first = cverts.size();
        bool anyBad = false;
        auto process = [&](u32 index, geo::ClipVertex& out) {
            DecodedVertex dv;
            bool ok = reader.read(vaddr, index, dv);
            anyBad |= !ok;
            if (ok && skin) applySkinning(st, vtype, dv);
            geo::transformVertex(t, dv, out);
            out.valid = ok && reader.hasPosition();  // no position: dropped (ge-rules.md §8.11)
        };
        u32 lo = ~0u, hi = 0;
        for (u32 i : indices) lo = std::min(lo, i), hi = std::max(hi, i);
        seq.clear();
        if (indices.empty()) return true;
        if (u64(hi) - lo < u64(count) * 2 + 64) {
            // Dense index range: transform each vertex of the range once.
            cverts.resize(first + (hi - lo + 1));
            std::vector<u8> used(hi - lo + 1, 0);
            for (u32 i : indices) used[i - lo] = 1;
            for (u32 k = 0; k <= hi - lo; ++k)
                if (used[k]) process(lo + k, cverts[first + k]);
            for (u32 i : indices) seq.push_back(u32(first + (i - lo)));
            stats.vertices += std::count(used.begin(), used.end(), u8(1));
        } else {
            cverts.resize(first + indices.size());
            for (size_t k = 0; k < indices.size(); ++k) {
                process(indices[k], cverts[first + k]);
                seq.push_back(u32(first + k));
            }
            stats.vertices += indices.size();
        }
        if (anyBad) ++stats.badDraws;  // drawn without the unreadable vertices
        return true;
    }

    Memory& mem;
    TextureCachePtr cache;
    SoftStats stats;
    u64 pixelWork = 0;  // Renderer::pixelWork: bounding boxes of the primitives queued
    u64 pixelBudgetLeft = ~u64(0);  // Renderer::setPixelBudget
    int threads = 1;

    Batch batches[2];
    int buildIndex = 0;
    bool inFlight = false;
    std::vector<std::thread> workers;
    std::mutex m;
    std::condition_variable cvWork, cvDone;
    u64 generation = 0;
    int remaining = 0;
    bool quit = false;
    const Batch* job = nullptr;
    std::vector<std::vector<geo::Fragment>> fragBufs;

    PixelState ps;
    bool psValid = false, psThrough = false, psTextured = false, psAlphaFull = false;
    u32 pendingDirty = DIRTY_ALL;

    // Assembly state of the draw being built.
    const geo::TransformState* ts = nullptr;
    geo::RasterParams rp;
    bool cullOn = false, cullClockwise = false;
    std::vector<geo::ClipVertex> cverts;
    std::vector<s32> vertIndex;
    std::vector<geo::ScreenVertex> scratchVerts;
    std::vector<RasterPrim> scratchPrims;
    std::vector<u32> indices, seq;
    // PRIM type 7 continuation: the transformed vertices still open, and the strip parity.
    std::vector<geo::ClipVertex> pending;
    std::vector<u32> keepScratch;  // assemble's continuation indices (reused)
    bool stripOdd = false;
    // Strip/fan-as-rectangle detection (assembly.h) for the PRIM being assembled: allowed only for
    // a fresh PRIM (no open vertices), with what the comparison needs from the state.
    geo::RectDetect rectDetect;
};

SoftRenderer::SoftRenderer(Memory& mem, const SoftOptions& opt) : impl_(std::make_unique<Impl>(mem, opt)) {}
SoftRenderer::~SoftRenderer() = default;

int SoftRenderer::threadCount() const { return impl_->threads; }
const SoftStats& SoftRenderer::stats() const { return impl_->stats; }

void SoftRenderer::drawPrim(const PrimPacket& p) {
    Impl& I = *impl_;
    const GeState& st = *p.state;
    I.pendingDirty |= p.dirty;
    ++I.stats.draws;
    if (!p.continuation) {
        I.pending.clear();
        I.stripOdd = false;
    }
    VertexReader probe(I.mem, st, p.vtype);
    geo::TransformState ts = geo::makeTransformState(st, p.vtype, probe.hasColor(), /*hasNormal: the format's or the latched one*/ true);
    ts.sprite = p.prim == GE_PRIM_RECTANGLES;
    // The still-open vertices of the previous PRIM come first.
    I.cverts.assign(I.pending.begin(), I.pending.end());
    std::vector<u32>& seq = I.seq;
    if (!I.decodeDraw(st, p.vtype, p.vertexAddr, p.indexAddr, p.count, ts, seq)) {
        ++I.stats.badDraws;
        I.pending.clear();
        return;
    }
    std::vector<u32> full;
    full.reserve(I.pending.size() + seq.size());
    for (u32 i = 0; i < I.pending.size(); ++i) full.push_back(i);
    full.insert(full.end(), seq.begin(), seq.end());

    const bool textured = st.TME_on();
    geo::RasterParams rp = makeRasterParams(st, ts.through, textured);
    rp.sprite = ts.sprite;
    I.beginAssembly(ts, rp, st.BCE_on() && !st.isClearMode(), !st.CULL_ccw());
    I.rectDetect = geo::RectDetect::fromState(st, ts.through, textured, I.pending.empty());
    I.assemble(p.prim, full, true);
    I.rectDetect.allowed = false;
    I.queueDraw(st, rp, textured, false);
}

void SoftRenderer::drawPatch(const PatchPacket& p) {
    Impl& I = *impl_;
    const GeState& st = *p.state;
    I.pendingDirty |= p.dirty;
    ++I.stats.patches;
    I.pending.clear();
    I.stripOdd = false;
    geo::TessOutput tess;
    std::string err;
    if (!geo::tessellatePatch(I.mem, st, p, tess, &err)) {
        ++I.stats.badDraws;
        return;
    }
    if (tess.verts.empty()) return;
    VertexReader probe(I.mem, st, p.vtype);
    // The tessellator generates normals when lighting needs them (ge-rules.md §3.2).
    const bool hasNormal = probe.hasNormal() || st.LTE_on();
    const geo::TransformState ts = geo::makeTransformState(st, p.vtype, probe.hasColor(), hasNormal);
    I.cverts.resize(tess.verts.size());
    for (size_t i = 0; i < tess.verts.size(); ++i) {
        geo::transformVertex(ts, tess.verts[i], I.cverts[i]);
        I.cverts[i].valid = true;
    }
    I.stats.vertices += tess.verts.size();
    std::vector<u32>& seq = I.seq;
    seq.clear();
    for (u32 i : tess.indices)
        if (i < tess.verts.size()) seq.push_back(i);

    const bool textured = st.TME_on();
    const geo::RasterParams rp = makeRasterParams(st, ts.through, textured);
    I.beginAssembly(ts, rp, st.BCE_on() && !st.isClearMode(), !st.CULL_ccw());
    // Patch culling (CMD_PCE, manual §11.2) removes patches outside the drawing region; the clip
    // rectangle already includes REGION2, so those pixels are never drawn either way.
    const bool odd = I.stripOdd;
    I.assemble(tess.prim, seq, false);
    I.stripOdd = odd;
    I.queueDraw(st, rp, textured, false);
}

void SoftRenderer::drawImmediate(const ImmPacket& p) {
    Impl& I = *impl_;
    I.pendingDirty |= p.dirty;
    ++I.stats.immediates;
    if (p.vertices.empty()) return;
    // The AP2 flags of the first vertex override shading, culling, texturing, fog, dither and
    // antialiasing for this primitive (ge-rules.md §3.12): draw with a state copy that has them.
    GeState st = *p.state;
    auto setFlag = [&](GeCmd op, bool on) { st.regs[op] = (u32(op) << 24) | (on ? 1u : 0u); };
    const u32 f = p.flags;
    setFlag(GE_CMD_AAE, (f >> 11) & 1);
    setFlag(GE_CMD_SHADE, (f >> 18) & 1);
    setFlag(GE_CMD_BCE, (f >> 19) & 1);
    setFlag(GE_CMD_CULL, (f >> 20) & 1);
    setFlag(GE_CMD_TME, (f >> 21) & 1);
    setFlag(GE_CMD_FGE, (f >> 22) & 1);
    setFlag(GE_CMD_DTE, (f >> 23) & 1);

    // Immediate vertices are already in drawing coordinates: no transform, lighting or clipping.
    geo::TransformState ts;
    ts.through = true;
    const bool through = st.isThrough();
    std::vector<u32>& seq = I.seq;
    geo::immediateVertices(st, p.vertices, I.cverts, seq);
    const bool textured = st.TME_on();
    geo::RasterParams rp = makeRasterParams(st, true, textured);
    rp.fog = st.FGE_on() && !through;
    I.beginAssembly(ts, rp, st.BCE_on() && !st.isClearMode(), !st.CULL_ccw());
    const bool odd = I.stripOdd;
    I.stripOdd = false;
    I.assemble(p.prim, seq, false);
    I.stripOdd = odd;
    // The pixel state is built from the overridden copy and not reused by later draws.
    I.queueDraw(st, rp, textured, true);
}

void SoftRenderer::blockTransfer(const TransferPacket& t, Memory& mem) {
    Impl& I = *impl_;
    I.waitIdle();  // the source may be a frame buffer still being drawn; the destination too
    performTransfer(mem, t);
    memoryWritten(t.dstBegin(), t.dstBytes());
}

void SoftRenderer::clutLoaded(const GeState&) {
    clutChanged(*impl_->cache);
    impl_->psValid = false;
}

void SoftRenderer::textureFlush() {
    invalidateTextureCache(*impl_->cache, 0, 0);
    impl_->psValid = false;
}

void SoftRenderer::textureSync() {
    // Drawing is ordered, and draws texturing from memory that queued draws write wait for them
    // (queueDraw), so TSYNC needs nothing more.
}

void SoftRenderer::finish() { impl_->waitIdle(); }

void SoftRenderer::syncMemoryForRead(u32 addr, u32 size) {
    Impl& I = *impl_;
    // Only the frame and depth buffers of queued draws are drawn into (size 0 = unknown extent:
    // any VRAM).
    if (I.queuedTouches(addr, size)) I.waitIdle();
}

void SoftRenderer::memoryWritten(u32 addr, u32 size) {
    Impl& I = *impl_;
    // Queued draws must not see (or be overwritten by) the new bytes out of order.
    if (I.queuedTouches(addr, size)) I.waitIdle();
    invalidateTextureCache(*I.cache, addr, size);
    I.psValid = false;
}

void SoftRenderer::flushToMemory() { impl_->waitIdle(); }

// Frame buffers are guest memory itself here; textures are re-hashed on next use.
void SoftRenderer::hostMayHaveWritten(bool) { textureFlush(); }

u64 SoftRenderer::pixelWork() const { return impl_->pixelWork; }
void SoftRenderer::setPixelBudget(u64 pixels) { impl_->pixelBudgetLeft = pixels; }

std::unique_ptr<ge::Renderer> createSoftRenderer(ge::Memory& mem, const SoftOptions& opt) {
    return std::make_unique<SoftRenderer>(mem, opt);
}

}  // namespace ge::soft
