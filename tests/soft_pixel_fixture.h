// SPDX-License-Identifier: MIT
// A small rig for the pixel-side tests (tests/soft_pixel.cpp, soft_sampler.cpp, soft_blend.cpp):
// a Memory with the frame buffer at 0x04000000 (stride 512) and the depth buffer at 0x04110000,
// a GeState built through its register words, and helpers to draw single fragments through
// buildPixelState + shadeFragments and read the buffers back.
#pragma once
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "softmodel/pixel.h"

namespace ge::soft::testing {

struct PixelRig {
    static constexpr u32 kFb = 0x04000000, kZb = 0x04110000, kTex = 0x08000000;
    static constexpr u32 kStride = 512;

    Memory mem{1u << 20};  // 1 MiB of RAM is plenty and keeps each rig cheap
    GeState st;
    TextureCachePtr cache = createTextureCache();
    GeBufferFormat fmt;

    explicit PixelRig(GeBufferFormat f = GE_FORMAT_8888) : fmt(f) {
        set(GE_CMD_FBP, kFb & 0xFFFFFF);
        set(GE_CMD_FBW, kStride);
        set(GE_CMD_FPF, f);
        set(GE_CMD_ZBP, kZb & 0xFFFFFF);
        set(GE_CMD_ZBW, kStride);
        set(GE_CMD_SCISSOR1, 0);
        set(GE_CMD_SCISSOR2, 479 | 271 << 10);
        set(GE_CMD_MINZ, 0);
        set(GE_CMD_MAXZ, 0xFFFF);
        set(GE_CMD_LOP, 3);  // COPY
    }

    void set(u8 cmd, u32 arg) { st.regs[cmd] = u32(cmd) << 24 | (arg & 0xFFFFFF); }

    u32 bpp() const { return fmt == GE_FORMAT_8888 ? 4 : 2; }
    u32 pixelAddr(int x, int y) const { return kFb + (u32(y) * kStride + u32(x)) * bpp(); }
    u32 pixel(int x, int y) const { return bpp() == 4 ? mem.read32(pixelAddr(x, y)) : mem.read16(pixelAddr(x, y)); }
    void setPixel(int x, int y, u32 v) {
        if (bpp() == 4) mem.write32(pixelAddr(x, y), v);
        else mem.write16(pixelAddr(x, y), u16(v));
    }
    u16 depth(int x, int y) const { return mem.read16(kZb + (u32(y) * kStride + u32(x)) * 2); }
    void setDepth(int x, int y, u16 z) { mem.write16(kZb + (u32(y) * kStride + u32(x)) * 2, z); }

    static geo::Fragment frag(int x, int y, u8 r, u8 g, u8 b, u8 a, u16 z = 0) {
        geo::Fragment f;
        f.x = x;
        f.y = y;
        f.z = z;
        f.color[0] = r;
        f.color[1] = g;
        f.color[2] = b;
        f.color[3] = a;
        return f;
    }

    void draw(const geo::Fragment& f, bool texture = false) {
        PixelState ps = buildPixelState(st, mem, *cache, geo::AccuracyProfile::ppsspp(), texture);
        shadeFragments(ps, &f, 1);
    }
    void draw(const std::vector<geo::Fragment>& fs, bool texture = false) {
        PixelState ps = buildPixelState(st, mem, *cache, geo::AccuracyProfile::ppsspp(), texture);
        shadeFragments(ps, fs.data(), fs.size());
    }

    // An 8888 texture at `addr` for level `level`: w × h texels (R in bits 7..0), buffer width
    // max(w, 4) (the 16-byte row rule for 32-bit texels).
    void texture8888(int level, u32 addr, u32 wlog, u32 hlog, const std::vector<u32>& texels) {
        const u32 w = 1u << wlog, h = 1u << hlog, bufw = w < 4 ? 4 : w;
        set(u8(GE_CMD_TBP0 + level), addr & 0xFFFFFF);
        set(u8(GE_CMD_TBW0 + level), bufw | ((addr >> 24) & 0xF) << 16);
        set(u8(GE_CMD_TSIZE0 + level), wlog | hlog << 8);
        set(GE_CMD_TPF, GE_TFMT_8888);
        for (u32 y = 0; y < h; ++y)
            for (u32 x = 0; x < w; ++x) mem.write32(addr + (y * bufw + x) * 4, texels[y * w + x]);
    }
};

inline u32 rgba(u32 r, u32 g, u32 b, u32 a) { return r | g << 8 | b << 16 | a << 24; }

}  // namespace ge::soft::testing
