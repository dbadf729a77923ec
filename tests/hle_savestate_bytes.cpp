// SPDX-License-Identifier: MIT
// The save-state byte format (docs/savestate.md) pinned: a GE with something in every section
// (matrices, palette, vertex latch, statistics, a completed and a stalled list, a paused SIGNAL
// list, callbacks, the eDRAM translation, the host's held interrupt) saves to the very bytes this
// format has always produced for it, and a blob loaded and saved again is the same bytes.
#include <gtest/gtest.h>

#include "authoring/list_builder.h"
#include "hle/ge_engine.h"
#include "hle/memory.h"
#include "hle/savestate.h"
#include "hle/sce_ge.h"

using namespace ge;

namespace {

// Draws a lit, textured, indexed triangle pair with every matrix set, so that the state, the
// statistics and the vertex latch all hold non-default values.
u32 buildDrawingList(Memory& mem, u32 arena) {
    ListBuilder b(&mem, arena);
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0x88000, 512);
    b.viewport(2048, 2048, 480, 272);
    b.offset(2048 - 240, 2048 - 136);
    b.scissor(0, 0, 480, 272);
    float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.25f, -0.5f, -3, 1};
    b.setMatrix(GeMatrix::World, m);
    m[12] = 0, m[13] = 0, m[14] = 0;
    b.setMatrix(GeMatrix::View, m);
    const float proj[16] = {1.5f, 0, 0, 0, 0, 2.5f, 0, 0, 0, 0, -1.01f, -1, 0, 0, -0.2f, 0};
    b.setMatrix(GeMatrix::Proj, proj);
    const float bone[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.125f, 0};
    b.setBoneMatrix(1, bone);
    b.enable(GE_CMD_LTE, true);
    const float pos[3] = {0, 1, 1};
    b.light(0, 0, 1, pos);
    b.lightColor(0, LIGHT_AMBIENT | LIGHT_DIFFUSE, 0x808080);
    b.ambient(0xFF202020);
    b.enable(GE_CMD_TME, true);
    static const u16 tex[16] = {0xF00F, 0x0F0F, 0x00FF, 0xFFFF, 0x1234, 0x5678, 0x9ABC, 0xDEF0,
                                0xF00F, 0x0F0F, 0x00FF, 0xFFFF, 0x1234, 0x5678, 0x9ABC, 0xDEF0};
    const u32 texAddr = b.place(tex, sizeof tex);
    b.texMode(GE_TFMT_4444, 0, false);
    b.setTexture(0, texAddr, 4, 4, 4);
    static const u32 pal[16] = {0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0x80FFFFFF};
    b.clutMode(3, 0, 0xFF, 0);  // ABGR8888 palette entries
    b.clutLoad(b.place(pal, sizeof pal), 2);
    BuildVertex v[4];
    for (int i = 0; i < 4; ++i) {
        v[i].x = float(i & 1) - 0.5f, v[i].y = float(i >> 1) - 0.5f, v[i].z = 0;
        v[i].u = 0.25f * float(i), v[i].v = 0.75f, v[i].nx = 0.f, v[i].ny = 0.6f, v[i].nz = 0.8f;
        v[i].color = 0xFF336699u + u32(i);
    }
    const u32 vt = vt::TC_16 | vt::COL_8888 | vt::NRM_F | vt::POS_F | vt::IDX_16;
    const auto data = packVertices(vt, v, 4);
    const u16 idx[6] = {0, 1, 2, 2, 1, 3};
    b.drawArrayData(GE_PRIM_TRIANGLES, vt, 6, idx, data.data());
    b.finish(0x42);
    return b.placeList();
}

// A list that pauses at a SIGNAL (behaviour 3, pause) and then finishes.
u32 buildPausingList(Memory& mem, u32 arena) {
    ListBuilder b(&mem, arena);
    b.cmd(GE_CMD_FC, 0x123456);
    b.signal(0x03, 0x77);
    b.cmd(GE_CMD_TEC, 0x654321);
    b.finish();
    return b.placeList();
}

struct Ge {
    Memory mem;
    GeEngine eng{mem};
    SceGe sce{eng};
};

// Runs the three lists: the first completes, the second pauses at its SIGNAL, the third waits at
// a stall address.
void buildState(Ge& g, s32& stalledId) {
    ASSERT_GE(g.sce.setCallback(0x08801000, 0x11, 0x08801100, 0x22), 0);
    ASSERT_EQ(g.sce.edramSetAddrTranslation(0x800), 0x400);
    const u32 a = buildDrawingList(g.mem, 0x08900000);
    const u32 p = buildPausingList(g.mem, 0x08910000);
    const u32 s = buildPausingList(g.mem, 0x08920000);
    ASSERT_NE(a, 0u);
    ASSERT_NE(p, 0u);
    ASSERT_GE(g.sce.listEnqueue(a, 0, 0, nullptr, false), 0);
    ASSERT_GE(g.sce.listEnqueue(p, 0, 0, nullptr, false), 0);
    stalledId = g.sce.listEnqueue(s, s + 4, 0, nullptr, false);
    ASSERT_GE(stalledId, 0);
    g.sce.run(100000);
}

// An 8-byte little-endian header field (docs/savestate.md: payload size at 16, xxHash64 at 24).
u64 headerField(const std::vector<u8>& blob, size_t at) {
    u64 v = 0;
    for (int i = 0; i < 8; ++i) v |= u64(blob[at + size_t(i)]) << (8 * i);
    return v;
}

}  // namespace

TEST(SaveStateBytes, NontrivialStateSavesToThePinnedBytes) {
    Ge g;
    s32 stalled = -1;
    buildState(g, stalled);
    ASSERT_GT(g.eng.stats().prims, 0u);
    int paused = 0, queued = 0;
    for (const auto& dl : g.sce.saved().lists) {
        paused += dl.state == SceListState::Paused;
        queued += dl.state == SceListState::Queued;
    }
    ASSERT_EQ(paused, 1);
    ASSERT_EQ(queued, 1);
    const std::vector<u8> blob = savestate::save(g.eng, g.sce, nullptr, savestate::HostFlags{true});
    // The header's xxHash64 covers the whole payload: size and hash pin every byte (values from the
    // format-version-3 writer as first released).
    ASSERT_GE(blob.size(), savestate::kHeaderSize);
    EXPECT_EQ(blob.size(), 10469u);
    EXPECT_EQ(headerField(blob, 16), 10437u);
    EXPECT_EQ(headerField(blob, 24), 0xad65dcd020f988c6ull);
}

TEST(SaveStateBytes, LoadThenSaveGivesTheSameBytes) {
    Ge g;
    s32 stalled = -1;
    buildState(g, stalled);
    for (const bool withMemory : {false, true}) {
        SCOPED_TRACE(withMemory);
        const std::vector<u8> blob = savestate::save(g.eng, g.sce, withMemory ? &g.mem : nullptr, savestate::HostFlags{true});
        Ge h;
        savestate::HostFlags host;
        bool hadMemory = false;
        std::string err;
        ASSERT_TRUE(savestate::load(blob, h.eng, h.sce, h.mem, host, hadMemory, err)) << err;
        EXPECT_EQ(hadMemory, withMemory);
        EXPECT_TRUE(host.heldInterrupt);
        EXPECT_EQ(savestate::save(h.eng, h.sce, withMemory ? &h.mem : nullptr, host), blob);
    }
}

TEST(SaveStateBytes, EveryTruncationIsRefused) {
    Ge g;
    s32 stalled = -1;
    buildState(g, stalled);
    const std::vector<u8> blob = savestate::save(g.eng, g.sce, nullptr, savestate::HostFlags{});
    Ge h;
    for (size_t n = 0; n < blob.size(); n += 7) {
        savestate::HostFlags host;
        bool hadMemory = false;
        std::string err;
        EXPECT_FALSE(savestate::load(std::span<const u8>(blob.data(), n), h.eng, h.sce, h.mem, host, hadMemory, err)) << n;
        EXPECT_FALSE(err.empty());
    }
}
