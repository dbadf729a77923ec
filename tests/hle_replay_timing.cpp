// SPDX-License-Identifier: MIT
// When the GE runs during a dump replay (docs/ppdmp.md §6.2 "When the GE runs"; PPSSPP's
// GPU/Debugger/Playback.cpp DumpExecute + BufMapping), with dumps this file writes itself.
//
// The probe: a FRAMEBUF record's bytes are copied into VRAM at once, without letting the GE catch
// up. A probe placed after record X therefore tells how many draws had run by X: the logging
// target notes the renderer's draw count when the probe's bytes arrive.
#include <gtest/gtest.h>

#include <cstring>

#include "authoring/list_builder.h"
#include "hle/dump/player.h"
#include "hle/dump/replay_memory.h"
#include "softmodel/soft_renderer.h"

using namespace ge;
using dump::ReplayTiming;

namespace {

u32 word(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

// A dump laid out by hand, so that payloads sit exactly where a test needs them in the push
// buffer (which 1 MiB slab, straddling two).
class HandDump {
public:
    dump::Dump d;

    HandDump() {
        d.version = 6;
        GeState st;
        st.reset();
        for (int op = 0; op < 256; ++op) st.regs[op] = u32(op) << 24;
        u32 ctx[512];
        st.saveContext(ctx);
        add(dump::INIT, ctx, sizeof ctx);
    }
    u32 put(const void* p, u32 n, u32 align = 16) {
        while (d.pushbuf.size() % align) d.pushbuf.push_back(0);
        const u32 at = u32(d.pushbuf.size());
        const u8* b = static_cast<const u8*>(p);
        d.pushbuf.insert(d.pushbuf.end(), b, b + n);
        return at;
    }
    void add(u8 type, const void* p, u32 n, u32 align = 16) { d.records.push_back({type, n, put(p, n, align)}); }
    // The push buffer reaches at least `pos` (filler bytes): the next payload starts there.
    void padTo(u32 pos) {
        if (d.pushbuf.size() < pos) d.pushbuf.resize(pos, 0xEE);
    }
    void regs(const std::vector<u32>& w) { add(dump::REGISTERS, w.data(), u32(4 * w.size()), 4); }
    // Two through-mode 16-bit rectangle corners (12 bytes).
    void verts() {
        const s16 v[6] = {0, 0, 0, 8, 8, 0};
        add(dump::VERTICES, v, sizeof v, 4);
    }
    void vertsAt(u32 ptr, u32 size) { d.records.push_back({dump::VERTICES, size, ptr}); }
    void kick() { regs({word(GE_CMD_PRIM, (GE_PRIM_RECTANGLES << 16) | 2)}); }
    void drawState() { regs({word(GE_CMD_VTYPE, vt::POS_16 | vt::THROUGH)}); }
    // FRAMEBUF0 record with 64 bytes of data for VRAM address `addr` (flags 0: copied).
    void probe(u32 addr) {
        u8 p[16 + 64];
        const u32 hdr[4] = {addr, 16, 0, 0};
        std::memcpy(p, hdr, 16);
        std::memset(p + 16, 0x77, 64);
        add(dump::FRAMEBUF0, p, sizeof p);
    }
    void memsetRec(u32 dest, u8 v, u32 size) {
        const u32 m[3] = {dest, v, size};
        add(dump::MEMSET, m, sizeof m, 1);
    }
    void memcpyRec(u32 dest, const std::vector<u8>& data) {
        add(dump::MEMCPYDEST, &dest, 4, 1);
        add(dump::MEMCPYDATA, data.data(), u32(data.size()), 1);
    }
    void display() {
        const u32 v[3] = {0x04000000, 512, GE_FORMAT_8888};
        add(dump::DISPLAY, v, sizeof v, 1);
    }
};

// EngineTarget that notes the draws run so far whenever the player writes guest memory.
class LoggingTarget : public dump::EngineTarget {
public:
    LoggingTarget(GeEngine& e, const NullRenderer& r) : EngineTarget(e), r_(r) {}
    struct Event {
        char kind;  // 'w' write, 'f' fill
        u32 addr, size;
        u64 draws;
    };
    std::vector<Event> events;
    u32 write(u32 addr, const void* data, u32 size) override {
        events.push_back({'w', Memory::normalize(addr), size, r_.prims});
        return EngineTarget::write(addr, data, size);
    }
    u32 fill(u32 addr, u8 value, u32 size) override {
        events.push_back({'f', Memory::normalize(addr), size, r_.prims});
        return EngineTarget::fill(addr, value, size);
    }

private:
    const NullRenderer& r_;
};

struct Replayed {
    Memory mem;
    NullRenderer r;
    dump::ReplayResult res;
    std::vector<LoggingTarget::Event> events;
    // Draws that had run when the first write/fill to `addr` happened; -1 if none did.
    long long drawsAt(u32 addr) const {
        for (const auto& e : events)
            if (e.addr == Memory::normalize(addr)) return (long long)e.draws;
        return -1;
    }
};

void replay(const dump::Dump& d, ReplayTiming timing, Replayed& out) {
    GeEngine eng(out.mem, &out.r);
    LoggingTarget t(eng, out.r);
    dump::ReplayOptions opt;
    opt.timing = timing;
    std::string err;
    ASSERT_TRUE(dump::replayDump(d, t, opt, out.res, err)) << err;
    EXPECT_EQ(out.res.listErrors, 0u) << out.res.warning;
    out.events = t.events;
}

constexpr u32 kProbe1 = 0x04180000, kProbe2 = 0x04180100, kProbe3 = 0x04180200, kProbe4 = 0x04180300;
constexpr u32 kSlab = 1u << 20;

TEST(ReplayTiming, RegistersBlocksWaitForASyncPointUnlessEager) {
    HandDump h;
    h.drawState();
    h.verts();
    h.kick();
    h.probe(kProbe1);
    h.display();
    Replayed p, e;
    replay(h.d, ReplayTiming::Ppsspp, p);
    replay(h.d, ReplayTiming::Eager, e);
    EXPECT_EQ(p.drawsAt(kProbe1), 0);  // the PRIM word sits in the list, not run yet
    EXPECT_EQ(e.drawsAt(kProbe1), 1);
    EXPECT_EQ(p.r.prims, 1u);          // DISPLAY let the GE catch up
    EXPECT_EQ(e.r.prims, 1u);
}

TEST(ReplayTiming, NewSlabRunsTheListFirstAndMappedSlabsDoNot) {
    HandDump h;
    h.drawState();
    h.verts();  // slab 0
    const u32 first = h.d.records.back().ptr;
    h.kick();
    h.padTo(kSlab + 64);
    h.verts();  // slab 1: not mapped yet → the GE catches up before the slab is filled
    h.probe(kProbe1);
    h.kick();
    h.vertsAt(first, 12);  // slab 0 again: still mapped, no catch-up
    h.probe(kProbe2);
    h.kick();
    h.display();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.drawsAt(kProbe1), 1);
    EXPECT_EQ(p.drawsAt(kProbe2), 1);  // the second draw still waits
    EXPECT_EQ(p.r.prims, 3u);
    EXPECT_EQ(p.res.slabMaps, 2u);
}

TEST(ReplayTiming, TenSlabsLeastRecentlyUsedIsReplaced) {
    HandDump h;
    h.drawState();
    u32 slabPtr[10];
    for (u32 s = 0; s < 10; ++s) {
        h.padTo(s * kSlab + 64);
        h.verts();
        slabPtr[s] = h.d.records.back().ptr;
        h.kick();
    }
    h.vertsAt(slabPtr[0], 12);  // slab 0 touched again: slab 1 is now the least recently used
    h.kick();
    h.probe(kProbe1);           // nothing new mapped since slab 9: 9 draws ran (at slab 9's map)
    h.padTo(10 * kSlab + 64);
    h.verts();                  // slab 10 → replaces slab 1 after a catch-up
    h.kick();
    h.probe(kProbe2);
    h.vertsAt(slabPtr[0], 12);  // slab 0 still mapped: no catch-up
    h.kick();
    h.probe(kProbe3);
    h.vertsAt(slabPtr[1], 12);  // slab 1 was replaced: remapped after a catch-up
    h.kick();
    h.probe(kProbe4);
    h.display();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.drawsAt(kProbe1), 9);
    EXPECT_EQ(p.drawsAt(kProbe2), 11);
    EXPECT_EQ(p.drawsAt(kProbe3), 11);
    EXPECT_EQ(p.drawsAt(kProbe4), 13);
    EXPECT_EQ(p.res.slabMaps, 12u);
    EXPECT_EQ(p.r.prims, 14u);
}

TEST(ReplayTiming, StraddlingPayloadGetsAnExtraAndReusesIt) {
    HandDump h;
    h.drawState();
    h.verts();
    h.kick();
    h.padTo(kSlab - 4);
    h.verts();  // bytes kSlab−4 … kSlab+8: an extra, after a catch-up
    const u32 straddle = h.d.records.back().ptr;
    h.probe(kProbe1);
    h.kick();
    h.vertsAt(straddle, 12);  // same start, same size: the extra is reused without a catch-up
    h.probe(kProbe2);
    h.kick();
    h.padTo(straddle + 24);
    h.vertsAt(straddle, 24);  // same start, larger: a new extra, after a catch-up
    h.probe(kProbe3);
    h.kick();
    h.display();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.drawsAt(kProbe1), 1);
    EXPECT_EQ(p.drawsAt(kProbe2), 1);
    EXPECT_EQ(p.drawsAt(kProbe3), 3);
    EXPECT_EQ(p.res.extraMaps, 2u);
}

TEST(ReplayTiming, ListBufferWrapRunsTheList) {
    // The 256 KiB list buffer: one NOP, then blocks; a block that (with the queued words and 8
    // bytes for BASE + JUMP) would reach the end wraps the buffer, and the GE catches up.
    auto build = [](u32 secondBlockWords) {
        HandDump h;
        h.drawState();
        h.verts();
        std::vector<u32> big(60000, 0);  // 240,000 bytes of NOPs after the kick
        big[0] = word(GE_CMD_PRIM, (GE_PRIM_RECTANGLES << 16) | 2);
        h.regs(big);
        h.probe(kProbe1);
        h.regs(std::vector<u32>(secondBlockWords, 0));
        h.probe(kProbe2);
        h.display();
        return h;
    };
    // 4 (NOP) + 4 (VTYPE) + 8 (BASE, VADR) + 240,000 = 240,016 bytes used of 262,144.
    Replayed fits, wraps;
    replay(build(5000).d, ReplayTiming::Ppsspp, fits);   // + 20,000 + 8 < 262,144: no wrap
    replay(build(5600).d, ReplayTiming::Ppsspp, wraps);  // + 22,400 + 8 ≥ 262,144: wrap
    EXPECT_EQ(fits.drawsAt(kProbe2), 0);
    EXPECT_EQ(fits.res.listWraps, 0u);
    EXPECT_EQ(wraps.drawsAt(kProbe1), 0);
    EXPECT_EQ(wraps.drawsAt(kProbe2), 1);
    EXPECT_EQ(wraps.res.listWraps, 1u);
    EXPECT_EQ(wraps.r.prims, 1u);
}

TEST(ReplayTiming, CpuWritesToVramRunTheListAndToRamAreNotReplayed) {
    HandDump h;
    h.drawState();
    h.verts();
    h.kick();
    h.memsetRec(0x08900000, 0x5A, 16);  // RAM: nothing at all
    h.memcpyRec(0x08900100, std::vector<u8>(16, 0x5B));
    h.probe(kProbe1);
    h.memsetRec(0x04100000, 0x5C, 16);  // VRAM: catch-up, then the fill
    h.kick();
    h.memcpyRec(0x04100100, std::vector<u8>(16, 0x5D));  // VRAM: catch-up, then the copy
    h.display();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.drawsAt(kProbe1), 0);
    EXPECT_EQ(p.drawsAt(0x08900000), -1);
    EXPECT_EQ(p.drawsAt(0x08900100), -1);
    EXPECT_EQ(p.mem.read8(0x08900000), 0);
    EXPECT_EQ(p.mem.read8(0x08900100), 0);
    EXPECT_EQ(p.drawsAt(0x04100000), 1);
    EXPECT_EQ(p.drawsAt(0x04100100), 2);
    EXPECT_EQ(p.mem.read8(0x04100000), 0x5C);
    EXPECT_EQ(p.mem.read8(0x04100100), 0x5D);
}

TEST(ReplayTiming, TransferSourceEdramAndDisplayRunTheList) {
    HandDump h;
    h.drawState();
    h.verts();
    h.kick();
    const u8 src[64] = {};
    h.add(dump::TRANSFERSRC, src, sizeof src);  // same slab as the vertices: still a catch-up
    h.probe(kProbe1);
    h.kick();
    const u32 trans = 0x400;
    h.add(dump::EDRAMTRANS, &trans, 4, 1);
    h.probe(kProbe2);
    h.kick();
    const u32 disp[3] = {0x04000000, 512, GE_FORMAT_8888};
    h.add(dump::DISPLAY, disp, sizeof disp, 1);
    h.probe(kProbe3);
    h.kick();
    h.display();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.drawsAt(kProbe1), 1);
    EXPECT_EQ(p.drawsAt(kProbe2), 2);
    EXPECT_EQ(p.drawsAt(kProbe3), 3);
    EXPECT_EQ(p.r.prims, 4u);
}

// Words queued by data records after the last REGISTERS block are dropped at the end, as
// PPSSPP's SubmitListEnd does; the list still completes.
TEST(ReplayTiming, EndRunsTheListToCompletion) {
    HandDump h;
    h.drawState();
    h.verts();
    h.kick();
    h.verts();
    Replayed p;
    replay(h.d, ReplayTiming::Ppsspp, p);
    EXPECT_EQ(p.r.prims, 1u);
    EXPECT_FALSE(p.res.hasDisplay);
}

// ---- pixels: the order PPSSPP's timing gives to FRAMEBUF bytes and pending GE work -------------

u32 pixel(const Memory& m, u32 addr, u32 x, u32 y, u32 stride) { return m.read32(addr + (y * stride + x) * 4); }

void replaySoft(const dump::Dump& d, ReplayTiming timing, Memory& mem) {
    soft::SoftOptions so;
    so.threads = 1;
    auto r = soft::createSoftRenderer(mem, so);
    GeEngine eng(mem, r.get());
    dump::ReplayOptions opt;
    opt.timing = timing;
    dump::ReplayResult res;
    std::string err;
    ASSERT_TRUE(dump::replayDump(d, eng, opt, res, err)) << err;
    EXPECT_EQ(res.listErrors, 0u) << res.warning;
}

// FRAMEBUF header + `rows` rows of `bufw` 8888 pixels of one colour, for VRAM address `addr`.
std::vector<u8> framebufRecord(u32 addr, u32 bufw, u32 rows, u32 color) {
    std::vector<u8> p(16 + size_t(bufw) * rows * 4);
    const u32 hdr[4] = {addr, bufw, 0, 0};
    std::memcpy(p.data(), hdr, 16);
    for (size_t i = 0; i < size_t(bufw) * rows; ++i) writeLE32(&p[16 + 4 * i], color);
    return p;
}

// A FRAMEBUF record written after a transfer kick lands first; the transfer, run at the next
// sync point, overwrites it. Eager timing runs the transfer at its block: the FRAMEBUF bytes win.
TEST(ReplayTimingPixels, FramebufAfterATransferKickIsOverwrittenByTheTransfer) {
    constexpr u32 dst = 0x04100000, stride = 64;
    HandDump h;
    h.regs({word(GE_CMD_XBW1, 16), word(GE_CMD_XPOS1, 0), word(GE_CMD_XBP2, dst & 0xFFFFFF),
            word(GE_CMD_XBW2, ((dst >> 8) & 0xFF0000) | stride), word(GE_CMD_XPOS2, 0),
            word(GE_CMD_XSIZE, (3u << 10) | 15)});
    std::vector<u8> src(16 * 4 * 4);
    for (size_t i = 0; i < src.size() / 4; ++i) writeLE32(&src[4 * i], 0xFF00C000);
    h.add(dump::TRANSFERSRC, src.data(), u32(src.size()));
    h.regs({word(GE_CMD_XSTART, 1)});
    const auto fb = framebufRecord(dst, stride, 4, 0xFF0000AA);
    h.add(dump::FRAMEBUF0, fb.data(), u32(fb.size()));
    h.display();
    Memory p, e;
    replaySoft(h.d, ReplayTiming::Ppsspp, p);
    replaySoft(h.d, ReplayTiming::Eager, e);
    for (u32 y = 0; y < 4; ++y)
        for (u32 x = 0; x < 16; x += 5) {
            EXPECT_EQ(pixel(p, dst, x, y, stride), 0xFF00C000u) << x << "," << y;
            EXPECT_EQ(pixel(e, dst, x, y, stride), 0xFF0000AAu) << x << "," << y;
        }
    // Outside the transfer rectangle the FRAMEBUF bytes stay in both timings.
    EXPECT_EQ(pixel(p, dst, 20, 1, stride), 0xFF0000AAu);
}

// A buffer cleared earlier (the clear has run at a sync point), then a blended draw recorded, then
// a FRAMEBUF record covering the buffer: in PPSSPP's timing the FRAMEBUF bytes land before the
// draw runs, so the draw blends with them.
TEST(ReplayTimingPixels, FramebufCoveringAClearedBufferIsBlendedByPendingDraws) {
    HandDump h;
    ListBuilder s;  // state words only
    s.drawBuffer(GE_FORMAT_8888, 0, 512);
    s.scissor(0, 0, 480, 272);
    s.region(0, 0, 480, 272);
    s.setVertexType(vt::COL_8888 | vt::POS_16 | vt::THROUGH);
    h.regs(s.words());
    auto rect = [&](u32 abgr) {
        BuildVertex v[2];
        v[0].color = v[1].color = abgr;
        v[1].x = 16;
        v[1].y = 8;
        const auto data = packVertices(vt::COL_8888 | vt::POS_16 | vt::THROUGH, v, 2);
        h.add(dump::VERTICES, data.data(), u32(data.size()), 4);
    };
    rect(0xFF000000);  // the "clear": opaque black
    ListBuilder blend;
    blend.enable(GE_CMD_ABE, true);
    blend.blendFunc(0, 10, 10, 0xFFFFFF, 0xFFFFFF);  // Cs + Cd
    std::vector<u32> w = {word(GE_CMD_PRIM, (GE_PRIM_RECTANGLES << 16) | 2)};
    w.insert(w.end(), blend.words().begin(), blend.words().end());
    h.regs(w);
    h.memsetRec(0x04150000, 0, 16);  // a sync point: the clear runs here
    rect(0xFF202020);
    h.kick();                        // the blended draw, pending
    const auto fb = framebufRecord(0x04000000, 512, 8, 0xFF101010);
    h.add(dump::FRAMEBUF0, fb.data(), u32(fb.size()));
    h.display();
    Memory p, e;
    replaySoft(h.d, ReplayTiming::Ppsspp, p);
    replaySoft(h.d, ReplayTiming::Eager, e);
    for (u32 y = 0; y < 8; y += 3)
        for (u32 x = 0; x < 16; x += 5) {
            EXPECT_EQ(pixel(p, 0x04000000, x, y, 512) & 0xFFFFFF, 0x303030u) << x << "," << y;
            EXPECT_EQ(pixel(e, 0x04000000, x, y, 512) & 0xFFFFFF, 0x101010u) << x << "," << y;
        }
    // Beside the draw only the FRAMEBUF bytes.
    EXPECT_EQ(pixel(p, 0x04000000, 100, 4, 512) & 0xFFFFFF, 0x101010u);
}

// ---- the allocator behind the mapping ---------------------------------------------------------

TEST(GuestHeap, FirstFitFromTheBottomLastFitFromTheTop) {
    dump::GuestHeap heap(0x08800000, 0x08810000);
    const u32 a = heap.alloc(100, false);
    const u32 b = heap.alloc(0x1000, false);
    const u32 top = heap.alloc(0x100, true);
    EXPECT_EQ(a, 0x08800000u);
    EXPECT_EQ(b, 0x08800100u);  // sizes round up to 256 bytes
    EXPECT_EQ(top, 0x0880FF00u);
    heap.free(a);
    EXPECT_EQ(heap.alloc(0x80, false), 0x08800000u);  // the freed gap is reused first
    EXPECT_EQ(heap.alloc(0x10000, false), 0u);        // no room
    EXPECT_EQ(heap.alloc(0, false), 0u);
}

}  // namespace
