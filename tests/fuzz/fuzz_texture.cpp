// SPDX-License-Identifier: MIT
// Harness (e): texture decoding — every texel format (and the undefined ones), CLUT loads and
// lookups, swizzled storage, DXT1/3/5, all 8 levels — then the software model's texture cache and
// sampler (level of detail, nearest/bilinear, wrap/clamp) at coordinates from the input.
//
// Input: a 16-byte header from which the texture state is derived, up to 8 further state words
// (TFILTER, TLEVEL, TWRAP, TSLOPE, … whatever the fuzzer writes), 8 sample points, then the
// texture and palette bytes. The data lies at one of four places: RAM start, flush against the end
// of RAM, VRAM start, flush against the end of VRAM (reads past the end must stay in bounds).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hle/ge_engine.h"
#include "hle/texture_decoder.h"
#include "softmodel/sampler.h"
#include "softmodel/texture_cache.h"
#include "tests/fuzz/fuzz_common.h"

using namespace ge;

namespace {

u32 cmd(u8 op, u32 arg) { return (u32(op) << 24) | (arg & 0xFFFFFF); }

float floatOf(u32 bits) {
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > fuzz::kMaxInput) return -1;
    fuzz::Bytes in(data, size);
    const u8 fmt = in.u8v();
    const u8 flags = in.u8v();   // bits 0-1 placement, 2 swizzle, 3-5 max level, 6 multi-CLUT
    const u8 tsize = in.u8v();   // level 0: wlog (low nibble), hlog (high nibble)
    const u8 shrink = in.u8v();  // bit n set: level n+1 keeps level n's size, else halves it
    const u16 bufw = in.u16v();
    const u32 clutWord = in.u16v() | (u32(in.u8v()) << 16);
    const u8 cload = in.u8v();
    const u32 clutOffset = u32(in.u16v()) * 16;
    const u32 gap = in.u32v() & 0xFFF;  // extra bytes between levels
    in.u8v();

    static Memory mem;
    static NullRenderer null;
    GeEngine eng(mem, &null);
    fuzz::applyStateWords(eng, in, 8);
    float pts[8][4];
    for (auto& p : pts)
        for (float& f : p) f = floatOf(in.u32v());

    // The data, at one of four places.
    const u8* blob = nullptr;
    const u32 n = u32(in.take(fuzz::kMaxInput, blob));
    const u32 ramEnd = Memory::kRamBase + mem.ramSize(), vramEnd = Memory::kVramBase + Memory::kVramSize;
    u32 base = 0;
    switch (flags & 3) {
    case 0: base = 0x08800000; break;
    case 1: base = ramEnd - n; break;
    case 2: base = Memory::kVramBase; break;
    case 3: base = vramEnd - std::min<u32>(n, Memory::kVramSize); break;
    }
    const u32 stored = (flags & 3) >= 2 ? std::min<u32>(n, Memory::kVramSize) : n;
    if (stored) mem.write(base, blob, stored);

    // Texture state: format, mode, sizes, buffer widths, level addresses one after the other.
    eng.execute(cmd(GE_CMD_TPF, fmt & 0xF));
    eng.execute(cmd(GE_CMD_TMODE, (flags >> 2 & 1) | ((flags >> 6 & 1) << 8) | (u32(flags >> 3 & 7) << 16)));
    // Levels of at most 256x256 (2^8): larger ones decode the same way, only slower (the replay
    // harnesses reach the 512-texel saturation of docs/ge-rules.md §6.2).
    u32 wlog = std::min<u32>(tsize & 0xF, 8), hlog = std::min<u32>(tsize >> 4, 8), bw = bufw, addr = base;
    for (int l = 0; l < 8; ++l) {
        eng.execute(cmd(u8(GE_CMD_TSIZE0 + l), wlog | (hlog << 8)));
        eng.execute(cmd(u8(GE_CMD_TBW0 + l), (bw & 0x7FF) | ((addr >> 8) & 0xFF0000)));
        eng.execute(cmd(u8(GE_CMD_TBP0 + l), addr & 0xFFFFFF));
        addr += textureLevelBytes(eng.state(), l) + gap;
        if (!((shrink >> l) & 1)) {
            wlog = wlog ? wlog - 1 : 0;
            hlog = hlog ? hlog - 1 : 0;
            bw = std::max<u32>(bw / 2, 1);
        }
    }
    // Palette: CLUT mode, then a load from the data.
    const u32 caddr = base + clutOffset;
    eng.execute(cmd(GE_CMD_CBW, (caddr >> 8) & 0xFF0000));
    eng.execute(cmd(GE_CMD_CBP, caddr & 0xFFFFFF));
    eng.execute(cmd(GE_CMD_CLUT, clutWord));
    eng.execute(cmd(GE_CMD_CLOAD, cload));
    const GeState& st = eng.state();

    // Decoder pieces.
    u64 sum = 0;
    std::vector<u32> out;
    const int maxLevel = int(st.TMODE_maxlevel());
    for (int l = 0; l <= maxLevel; ++l) {
        const TextureLevelInfo li = textureLevelInfo(st, l);
        sum += li.width + li.height + textureLevelBytes(st, l) + hashTextureLevel(mem, st, l);
        decodeTextureLevel(mem, st, l, out);
        if (!out.empty()) sum += out.front() + out.back();
    }
    for (u32 i = 0; i < 16 && 4 * i + 4 <= n; ++i) sum += clutLookup(st, readLE32(blob + 4 * i), int(i & 7));
    u32 block[16];
    for (u32 off = 0; off + 16 <= n && off < 64; off += 16) {
        decodeDxt1Block(blob + off, block);
        decodeDxt3Block(blob + off, block);
        decodeDxt5Block(blob + off, block);
        sum += block[0] + block[15];
    }
    sum += swizzledByteOffset(bufw, tsize, gap) + textureFormatBits(GeTexFormat(fmt & 0xF));

    // The software model's cache and sampler, set up as softmodel/pixel.cpp does for a draw.
    static soft::TextureCache cache(size_t(64) << 20);
    cache.invalidate(0, 0);
    cache.clutChanged();
    soft::Sampler sm;
    soft::LodParams& lp = sm.lod;
    const u32 mode = st.TLEVEL_mode();
    lp.mode = mode == 3 ? 1 : int(mode);
    lp.bias16 = st.TLEVEL_bias();
    lp.slope = st.TSLOPE_value();
    const u32 minf = st.TFILTER_min();
    lp.maxLevel = (minf & 4) ? maxLevel : 0;
    lp.mipLinear = (minf & 2) != 0;
    lp.minLinear = (minf & 1) != 0;
    lp.magLinear = (st.TFILTER_mag() & 1) != 0;
    sm.clampU = st.TWRAP_uclamp();
    sm.clampV = st.TWRAP_vclamp();
    if (lp.mode == 1) {
        sm.fixedChoice = true;
        sm.fixed = soft::chooseLevel(lp, soft::levelOfDetail16(lp, 0, 0));
    }
    const int first = sm.fixedChoice ? sm.fixed.level : 0;
    const int last = soft::highestLevelNeeded(lp, sm.fixedChoice, sm.fixed);
    std::shared_ptr<const soft::DecodedLevel> keep[8];
    for (int l = first; l <= last && l < 8; ++l) {
        keep[l] = cache.level(st, mem, l);
        sm.levels[l].texels = keep[l]->texels.data();
        sm.levels[l].setSize(st.TSIZE_wlog(l), st.TSIZE_hlog(l), int(keep[l]->width), int(keep[l]->height));
    }
    sm.levelCount = std::min(last, 7) + 1;
    sm.finalize();
    for (const auto& p : pts) {
        sum += sm.sample(p[0], p[1], p[2], p[3]);
        sum += soft::sampleNearest(sm.levels[first], p[0], p[1], sm.clampU, sm.clampV);
        sum += soft::sampleBilinear(sm.levels[first], p[0], p[1], sm.clampU, sm.clampV);
        sum += u32(soft::texLog2x16(p[2]) + soft::levelOfDetail16(lp, p[2], p[3]));
    }

    if (stored) mem.fill(base, 0, stored);
    volatile u64 sink = sum;
    (void)sink;
    return 0;
}
