// SPDX-License-Identifier: MIT
// texcache::ValidatedCache, the validity core both backends' texture caches run (the software
// model's decoded levels, the GL translator's textures): reuse, re-hash on events, rebuild on
// changed content, and the eviction budget.
#include <gtest/gtest.h>

#include "tests/soft_pixel_fixture.h"
#include "texcache/texture_validity.h"

namespace {

using namespace ge;
using soft::testing::PixelRig;
using Cache = texcache::ValidatedCache<int>;

// 1×1 8888 textures, one every 0x100 bytes from PixelRig::kTex.
u32 texAt(int i) { return PixelRig::kTex + u32(i) * 0x100; }

struct Rig {
    PixelRig px;
    Cache cache;
    std::vector<int> dropped;
    explicit Rig(texcache::Budget b = {}) : cache(b) {}
    // Looks up texture i (building its payload as i when asked); returns what the cache said.
    Cache::Use use(int i) {
        px.texture8888(0, texAt(i), 0, 0, {px.mem.read32(texAt(i))});
        const texcache::TextureKey key = texcache::textureKey(px.st, 0, 1, 0);
        auto onDrop = [this](Cache::Entry& e) { dropped.push_back(e.payload); };
        auto [e, u] = cache.find(key, px.st, px.mem, 0, 1, onDrop);
        if (u != Cache::Use::Reuse) {
            e.payload = i;
            cache.setBytes(e, 10, onDrop);
        }
        return u;
    }
};

TEST(TextureValidity, ReusesUntilAnEventAndTheContentChange) {
    Rig r;
    EXPECT_EQ(r.use(0), Cache::Use::Build);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    // A write without an event is not looked for (events drive validity).
    r.px.mem.write32(texAt(0), 0x12345678);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    // An event elsewhere changes nothing; an overlapping one (through the uncached mirror) makes
    // the entry re-hash, and the new bytes rebuild it.
    r.cache.invalidate(texAt(0) + 0x10, 4);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    EXPECT_EQ(r.cache.stats().rehashes, 0u);
    r.cache.invalidate(texAt(0) | 0x40000000, 1);
    EXPECT_EQ(r.use(0), Cache::Use::Rebuild);
    // Suspect again but unchanged: re-hashed and reused.
    r.cache.invalidate(0, 0);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    EXPECT_EQ(r.cache.stats().rehashes, 2u);
    EXPECT_EQ(r.cache.stats().builds, 2u);
    // A palette reload does not touch a direct-colour texture.
    r.px.mem.write32(texAt(0), 0x1);
    r.cache.clutChanged();
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
}

// Writes are filtered by 64 KiB page before the walk over the entries: a write one page away
// from every entry finds nothing, a write that spans pages finds the entry in its last page, and
// after an eviction the evicted entry's page still answers (a walk, never a missed entry).
TEST(TextureValidity, WritesAwayFromEveryEntryAreFilteredByPage) {
    Rig r;
    EXPECT_EQ(r.use(0), Cache::Use::Build);
    r.px.mem.write32(texAt(0), 0x0BADF00D);
    r.cache.invalidate(texAt(0) + 0x10000, 0x100);  // the next page
    r.cache.invalidate(texAt(0) - 0x10000, 0x100);  // the page before
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    EXPECT_EQ(r.cache.stats().rehashes, 0u);
    // From two pages below up to the texture's first byte: found.
    r.cache.invalidate(texAt(0) - 0x20000, 0x20001);
    EXPECT_EQ(r.use(0), Cache::Use::Rebuild);
    // A page past the 2^28 mark shares the last bit: far writes are still looked at.
    r.cache.invalidate(0x7FFF0000, 0x100);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
}

TEST(TextureValidity, EvictsLeastRecentlyUsedToThreeQuartersOfTheBudget) {
    Rig r(texcache::Budget{1000, 4});
    for (int i = 0; i < 4; ++i) EXPECT_EQ(r.use(i), Cache::Use::Build);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);  // 0 is now the most recent
    // The fifth entry passes the count of 4: down to 3 before it is made, oldest first (1).
    EXPECT_EQ(r.use(4), Cache::Use::Build);
    EXPECT_EQ(r.dropped, (std::vector<int>{1}));
    EXPECT_EQ(r.cache.entries(), 4u);
    EXPECT_EQ(r.use(0), Cache::Use::Reuse);
    EXPECT_EQ(r.use(1), Cache::Use::Build);

    // Byte budget: an entry over it alone stays while in use.
    Rig b(texcache::Budget{15, 100});
    EXPECT_EQ(b.use(0), Cache::Use::Build);  // 10 bytes
    EXPECT_EQ(b.use(1), Cache::Use::Build);  // 20 > 15: 0 goes, 1 stays
    EXPECT_EQ(b.dropped, (std::vector<int>{0}));
    EXPECT_EQ(b.cache.bytes(), 10u);
}

TEST(TextureValidity, KeysSeparateWhatTheDecoderReads) {
    PixelRig px;
    px.texture8888(0, texAt(0), 0, 0, {0});
    const texcache::TextureKey a = texcache::textureKey(px.st, 0, 1, 0);
    EXPECT_EQ(a, texcache::textureKey(px.st, 0, 1, 0));
    px.set(GE_CMD_TMODE, 1);  // swizzled
    EXPECT_FALSE(a == texcache::textureKey(px.st, 0, 1, 0));
    px.set(GE_CMD_TMODE, 0);
    // The CLUT register only counts for palette formats.
    px.set(GE_CMD_CLUT, 0xFF00);
    EXPECT_EQ(a, texcache::textureKey(px.st, 0, 1, 0));
    px.set(GE_CMD_TPF, GE_TFMT_CLUT8);
    const texcache::TextureKey c = texcache::textureKey(px.st, 0, 1, 0);
    EXPECT_FALSE(a == c);
    EXPECT_FALSE(c == texcache::textureKey(px.st, 0, 1, 77));  // a palette hash, where a backend keys on it
    u32 begin = 0, end = 0;
    px.set(GE_CMD_TPF, GE_TFMT_8888);
    texcache::sourceRange(px.st, 0, 1, begin, end);
    EXPECT_EQ(begin, Memory::drawingAddress(texAt(0)));
    EXPECT_EQ(end, begin + 4u);
}

}  // namespace
