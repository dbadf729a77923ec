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

#include "geometry/draw_front_end.h"
#include "geometry/raster.h"
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

}  // namespace

struct SoftRenderer::Impl final : geo::PrimitiveSink {
    Impl(Memory& m, const SoftOptions& opt) : mem(m), cache(createTextureCache()), frontEnd(opt.accuracy) {
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
        const bool alphaFull = frontEnd.drawAlphaFull();
        if (forceRebuild || !psValid || (pendingDirty & kPixelDirty) || through != psThrough || textured != psTextured ||
            alphaFull != psAlphaFull) {
            ps = buildPixelState(st, mem, *cache, frontEnd.accuracy(), textured, alphaFull);
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
        if (b.prims.size() >= kBatchPrimitives || b.verts.size() >= kBatchVertices) submit();
    }

    // ---- the draw front end's sink (geometry/draw_front_end.h): into scratchVerts / scratchPrims ----
    void beginDraw() {
        scratchVerts.clear();
        scratchPrims.clear();
        vertIndex.clear();
    }
    // A vertex of the primitive: one of the draw's transformed vertices is stored once however
    // many primitives use it; a vertex made by the front end (clipping, rectangle corners) once
    // per primitive.
    u32 vertexOf(const geo::Primitive& p, int k) {
        const geo::ScreenVertex* sv = k < 3 ? p.v[k] : p.prov;
        const s32 id = k < 3 ? p.id[k] : p.provId;
        if (id < 0) {
            for (int j = 0; j < k; ++j)
                if (p.v[j] == sv) return primVerts[j];
            scratchVerts.push_back(*sv);
            return u32(scratchVerts.size() - 1);
        }
        if (size_t(id) >= vertIndex.size()) vertIndex.resize(size_t(id) + 1, -1);
        if (vertIndex[size_t(id)] < 0) {
            vertIndex[size_t(id)] = s32(scratchVerts.size());
            scratchVerts.push_back(*sv);
        }
        return u32(vertIndex[size_t(id)]);
    }
    void primitive(const geo::Primitive& p) override {
        if (!p.inside) return;  // covers no pixel: nothing to rasterise
        RasterPrim r;
        r.kind = p.kind;
        for (int k = 0; k < 4; ++k) primVerts[k] = vertexOf(p, k);
        r.v[0] = primVerts[0], r.v[1] = primVerts[1], r.v[2] = primVerts[2];
        r.prov = primVerts[3];
        r.y1 = p.y1, r.y2 = p.y2;
        scratchPrims.push_back(r);
    }

    Memory& mem;
    TextureCachePtr cache;
    SoftStats stats;
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

    // The draw being built: the front end's primitives with their vertices.
    geo::DrawFrontEnd frontEnd;
    std::vector<s32> vertIndex;  // the front end's vertex id → scratchVerts index, -1: not yet stored
    std::vector<geo::ScreenVertex> scratchVerts;
    std::vector<RasterPrim> scratchPrims;
    u32 primVerts[4] = {};
};

SoftRenderer::SoftRenderer(Memory& mem, const SoftOptions& opt) : impl_(std::make_unique<Impl>(mem, opt)) {}
SoftRenderer::~SoftRenderer() = default;

int SoftRenderer::threadCount() const { return impl_->threads; }
const SoftStats& SoftRenderer::stats() const {
    SoftStats& s = impl_->stats;
    const geo::FrontEndStats& f = impl_->frontEnd.stats();
    s.vertices = f.vertices, s.primitives = f.primitives, s.culled = f.culled, s.discarded = f.discarded;
    s.clipped = f.clipped, s.badDraws = f.badDraws, s.budgetDropped = f.budgetDropped, s.culledPatches = f.culledPatches;
    return s;
}

void SoftRenderer::drawPrim(const PrimPacket& p) {
    Impl& I = *impl_;
    const GeState& st = *p.state;
    I.pendingDirty |= p.dirty;
    I.frontEnd.noteDirty(p.dirty);
    ++I.stats.draws;
    I.beginDraw();
    if (!I.frontEnd.prim(I.mem, st, p, I, nullptr)) return;
    I.queueDraw(st, I.frontEnd.rasterParams(), st.TME_on(), false);
}

void SoftRenderer::drawPatch(const PatchPacket& p) {
    Impl& I = *impl_;
    const GeState& st = *p.state;
    I.pendingDirty |= p.dirty;
    I.frontEnd.noteDirty(p.dirty);
    ++I.stats.patches;
    I.beginDraw();
    if (!I.frontEnd.patch(I.mem, st, p, I, nullptr)) return;
    I.queueDraw(st, I.frontEnd.rasterParams(), st.TME_on(), false);
}

void SoftRenderer::drawImmediate(const ImmPacket& p) {
    Impl& I = *impl_;
    I.pendingDirty |= p.dirty;
    I.frontEnd.noteDirty(p.dirty);
    ++I.stats.immediates;
    if (p.vertices.empty()) return;
    // Drawn with a state copy that has the first vertex's AP2 overrides (docs/ge-rules.md §3.12).
    const GeState st = geo::immediateState(*p.state, p.flags);
    I.beginDraw();
    I.frontEnd.immediate(st, p, I);
    // The pixel state is built from the overridden copy and not reused by later draws.
    I.queueDraw(st, I.frontEnd.rasterParams(), st.TME_on(), true);
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

// The front end charges the pixel bounds of the primitives it hands on (geometry/draw_front_end.h).
u64 SoftRenderer::pixelWork() const { return impl_->frontEnd.pixelWork(); }
void SoftRenderer::setPixelBudget(u64 pixels) { impl_->frontEnd.setPixelBudget(pixels); }

std::unique_ptr<ge::Renderer> createSoftRenderer(ge::Memory& mem, const SoftOptions& opt) {
    return std::make_unique<SoftRenderer>(mem, opt);
}

}  // namespace ge::soft
