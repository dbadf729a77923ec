// SPDX-License-Identifier: MIT
// Vertex decoding (manual §6, §7; docs/ge-rules.md §5).
#include "hle/vertex_decoder.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <type_traits>

#include "hle/pixel_format.h"

namespace ge {

namespace {

inline float readF32(const u8* p) {
    u32 bits = readLE32(p);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

// The decoded components of one stored copy, before morph blending (everything as float so that
// morphing can weight every component, colour included: manual Equation 7-1).
struct RawVertex {
    float pos[3] = {}, uv[2] = {}, nrm[3] = {}, w[8] = {}, col[4] = {};
};

inline float* weightsOf(RawVertex& r) { return r.w; }
inline float* weightsOf(DecodedVertex& v) { return v.weights; }

}  // namespace

VertexReader::VertexReader(const Memory& mem, const GeState& st, u32 vtype)
    : mem_(mem), st_(st), vtype_(vtype & 0xFFFFFF), layout_(VertexLayout::fromVtype(vtype)) {
    morphs_ = ((vtype_ >> 18) & 7) + 1;
    stride_ = u32(layout_.size) * morphs_;
    for (u32 i = 0; i < morphs_; ++i) morphW_[i] = st.WEIGHT_value(int(i));
}

u32 VertexReader::stride() const { return stride_; }
const VertexLayout& VertexReader::layout() const { return layout_; }
u32 VertexReader::morphCount() const { return morphs_; }
u32 VertexReader::weightCount() const { return hasWeights() ? ((vtype_ >> 14) & 7) + 1 : 0; }
u32 VertexReader::indexSize() const {
    static constexpr u32 sizes[4] = {0, 1, 2, 4};
    return sizes[(vtype_ >> 11) & 3];
}

namespace {

// The colour bytes (R, G, B, A) of a stored colour (ge-rules.md §5.4): 16-bit formats expand by
// bit replication; 8888 as stored.
inline u32 storedColor(const u8* q, u32 col) {
    switch (col) {
    case 4: return decode5650(readLE16(q));
    case 5: return decode5551(readLE16(q));
    case 6: return decode4444(readLE16(q));
    default: return readLE32(q);
    }
}

// Decodes one stored copy at p (layout size bytes, already bounds-checked) per ge-rules.md §5.4.
// Out is RawVertex (every component as float, for morphing) or DecodedVertex (one copy: the
// colour's bytes kept as they are, which is what a float round trip would give back).
template <class Out>
void decodeRaw(const u8* p, u32 vtype, const VertexLayout& l, bool through, Out& r) {
    constexpr bool raw = std::is_same_v<Out, RawVertex>;
    const u32 tc = vtype & 3, col = (vtype >> 2) & 7, nrm = (vtype >> 5) & 3, pos = (vtype >> 7) & 3;
    const u32 wt = (vtype >> 9) & 3, wc = ((vtype >> 14) & 7) + 1;

    // Weights: u8 /128, u16 /32768, float; not renormalised (ge-rules.md §5.4).
    if (wt) {
        const u8* q = p + l.weightOff;
        for (u32 i = 0; i < wc; ++i) {
            switch (wt) {
            case 1: weightsOf(r)[i] = float(q[i]) / 128.0f; break;
            case 2: weightsOf(r)[i] = float(readLE16(q + 2 * i)) / 32768.0f; break;
            default: weightsOf(r)[i] = readF32(q + 4 * i); break;
            }
        }
    }
    // Texture coordinates: transform mode u8 /128, u16 /32768; through mode u16 are texels and
    // u8 keeps /128 as PPSSPP does (ge-rules.md §5.4).
    if (tc) {
        const u8* q = p + l.tcOff;
        switch (tc) {
        case 1:
            r.uv[0] = float(q[0]) / 128.0f;
            r.uv[1] = float(q[1]) / 128.0f;
            break;
        case 2:
            if (through) {
                r.uv[0] = float(readLE16(q));
                r.uv[1] = float(readLE16(q + 2));
            } else {
                r.uv[0] = float(readLE16(q)) / 32768.0f;
                r.uv[1] = float(readLE16(q + 2)) / 32768.0f;
            }
            break;
        default:
            r.uv[0] = readF32(q);
            r.uv[1] = readF32(q + 4);
            break;
        }
    }
    // Colour: 16-bit formats expand by bit replication (ge-rules.md §5.4); 8888 bytes R, G, B, A.
    if (col >= 4) {
        const u32 c = storedColor(p + l.colOff, col);
        if constexpr (raw) {
            for (int i = 0; i < 4; ++i) r.col[i] = float((c >> (8 * i)) & 0xFF);
        } else {
            for (int i = 0; i < 4; ++i) r.color[i] = u8(c >> (8 * i));
        }
    }
    // Normal: s8 /128, s16 /32768, float.
    if (nrm) {
        const u8* q = p + l.nrmOff;
        for (int i = 0; i < 3; ++i) {
            switch (nrm) {
            case 1: r.nrm[i] = float(s8(q[i])) / 128.0f; break;
            case 2: r.nrm[i] = float(s16(readLE16(q + 2 * i))) / 32768.0f; break;
            default: r.nrm[i] = readF32(q + 4 * i); break;
            }
        }
    }
    // Position (ge-rules.md §5.4): transform mode s8 /128, s16 /32768, float. Through mode: s8 decodes as 0
    // (observed: SWR), s16 gives signed X, Y and unsigned Z, float Z is clamped to 0–65535.
    if (pos) {
        const u8* q = p + l.posOff;
        switch (pos) {
        case 1:
            if (!through)
                for (int i = 0; i < 3; ++i) r.pos[i] = float(s8(q[i])) / 128.0f;
            break;
        case 2:
            if (through) {
                r.pos[0] = float(s16(readLE16(q)));
                r.pos[1] = float(s16(readLE16(q + 2)));
                r.pos[2] = float(readLE16(q + 4));
            } else {
                for (int i = 0; i < 3; ++i) r.pos[i] = float(s16(readLE16(q + 2 * i))) / 32768.0f;
            }
            break;
        default:
            for (int i = 0; i < 3; ++i) r.pos[i] = readF32(q + 4 * i);
            // std::clamp keeps a NaN as is; the range check below maps it to 0 so Z stays defined.
            if (through) r.pos[2] = (r.pos[2] >= 0.0f) ? std::min(r.pos[2], 65535.0f) : 0.0f;
            break;
        }
    }
}

inline u8 colorToU8(float c) {
    // Morphed colours are truncated after clamping to 0–255 (a NaN becomes 0).
    if (!(c > 0.0f)) return 0;
    if (c >= 255.0f) return 255;
    return u8(c);
}

}  // namespace

bool VertexReader::read(u32 base, u32 index, DecodedVertex& out) const {
    const u8* p = span(base, index, 1);
    if (!p) {
        out = DecodedVertex{};
        return false;
    }
    decodeAt(p, out);
    return true;
}

const u8* VertexReader::span(u32 base, u32 first, u32 count) const {
    if (count == 0) return nullptr;
    // Morphing is not executed in through mode (manual §7.1): only the first copy is read.
    const u32 copies = through() ? 1 : morphs_;
    const u64 addr = u64(base) + u64(first) * stride_;
    const u64 need = u64(count - 1) * stride_ + u64(layout_.size) * copies;
    if (addr + need > 0x100000000ull || need > 0xFFFFFFFFull) return nullptr;
    return mem_.ptr(u32(addr), u32(need));
}

void VertexReader::decodeAt(const u8* p, DecodedVertex& out) const {
    out = DecodedVertex{};
    const bool thru = through();
    const u32 copies = thru ? 1 : morphs_;
    if (copies == 1) {
        // One copy: decoded straight into `out` (the same values as through RawVertex below).
        decodeRaw(p, vtype_, layout_, thru, out);
        if (!hasUV()) std::copy(st_.latchUV, st_.latchUV + 2, out.uv);
        if (!hasNormal()) std::copy(st_.latchNormal, st_.latchNormal + 3, out.nrm);
        if (!hasColor()) materialColor(out);
        return;
    }
    RawVertex sum;
    {
        // P' = Σ Mi·Pi over every component (manual Equation 7-1, ge-rules.md §5.5); weights not normalised.
        for (u32 m = 0; m < copies; ++m) {
            RawVertex r;
            decodeRaw(p + size_t(m) * layout_.size, vtype_, layout_, thru, r);
            const float w = morphW_[m];
            for (int i = 0; i < 3; ++i) sum.pos[i] += w * r.pos[i];
            for (int i = 0; i < 2; ++i) sum.uv[i] += w * r.uv[i];
            for (int i = 0; i < 3; ++i) sum.nrm[i] += w * r.nrm[i];
            for (int i = 0; i < 8; ++i) sum.w[i] += w * r.w[i];
            for (int i = 0; i < 4; ++i) sum.col[i] += w * r.col[i];
        }
    }
    std::copy(sum.pos, sum.pos + 3, out.pos);
    // An attribute the format lacks is the vertex unit's last value (GeState::latchUV/latchNormal).
    if (hasUV()) std::copy(sum.uv, sum.uv + 2, out.uv);
    else std::copy(st_.latchUV, st_.latchUV + 2, out.uv);
    if (hasNormal()) std::copy(sum.nrm, sum.nrm + 3, out.nrm);
    else std::copy(st_.latchNormal, st_.latchNormal + 3, out.nrm);
    std::copy(sum.w, sum.w + 8, out.weights);
    if (hasColor()) {
        for (int i = 0; i < 4; ++i) out.color[i] = colorToU8(sum.col[i]);
    } else {
        materialColor(out);
    }
}

// No vertex colour: material ambient colour and alpha (ge-rules.md §5.5).
void VertexReader::materialColor(DecodedVertex& out) const {
    const u32 mac = st_.MAC_rgb();
    out.color[0] = u8(mac);
    out.color[1] = u8(mac >> 8);
    out.color[2] = u8(mac >> 16);
    out.color[3] = u8(st_.MAA_alpha());
}

bool VertexReader::readIndices(u32 iaddr, u32 count, std::vector<u32>& out) const {
    out.assign(count, 0);
    const u32 isz = indexSize();
    if (isz == 0) {
        std::iota(out.begin(), out.end(), 0u);
        return true;
    }
    const u64 bytes = u64(count) * isz;
    if (bytes == 0) return true;
    if (u64(iaddr) + bytes > 0x100000000ull) return false;
    const u8* p = mem_.ptr(iaddr, u32(bytes));
    if (!p) return false;
    switch (isz) {
    case 1:
        for (u32 i = 0; i < count; ++i) out[i] = p[i];
        break;
    case 2:
        for (u32 i = 0; i < count; ++i) out[i] = readLE16(p + 2 * i);
        break;
    default:
        for (u32 i = 0; i < count; ++i) out[i] = readLE32(p + 4 * i);
        break;
    }
    return true;
}

bool VertexReader::indexBounds(u32 iaddr, u32 count, u32& lo, u32& hi, u32& last) const {
    const u32 isz = indexSize();
    if (count == 0) return false;
    if (isz == 0) {
        lo = 0, hi = last = count - 1;
        return true;
    }
    const u64 bytes = u64(count) * isz;
    if (u64(iaddr) + bytes > 0x100000000ull) return false;
    const u8* p = mem_.ptr(iaddr, u32(bytes));
    if (!p) return false;
    u32 mn = ~0u, mx = 0;
    auto scan = [&](auto read) {
        for (u32 i = 0; i < count; ++i) {
            const u32 v = read(i);
            mn = std::min(mn, v);
            mx = std::max(mx, v);
        }
        last = read(count - 1);
    };
    switch (isz) {
    case 1: scan([p](u32 i) { return u32(p[i]); }); break;
    case 2: scan([p](u32 i) { return u32(readLE16(p + 2 * i)); }); break;
    default: scan([p](u32 i) { return readLE32(p + 4 * i); }); break;
    }
    lo = mn, hi = mx;
    return true;
}

void applySkinning(const GeState& st, u32 vtype, DecodedVertex& v) {
    const u32 wt = (vtype >> 9) & 3;
    if (wt == 0 || ((vtype >> 23) & 1)) return;  // skinning is transform-mode only (ge-rules.md §5.5)
    const u32 n = ((vtype >> 14) & 7) + 1;
    float pos[3] = {}, nrm[3] = {};
    for (u32 b = 0; b < n; ++b) {
        const float w = v.weights[b];
        // A zero weight contributes nothing; skipping it keeps unused (possibly garbage) bone
        // matrices from turning the result into NaN.
        if (w == 0.0f) continue;
        const float* m = st.bone + 12 * b;  // element k = row k%3, column k/3 (ge-rules.md §3.4)
        for (int r = 0; r < 3; ++r) {
            const float p = m[r] * v.pos[0] + m[3 + r] * v.pos[1] + m[6 + r] * v.pos[2] + m[9 + r];
            const float q = m[r] * v.nrm[0] + m[3 + r] * v.nrm[1] + m[6 + r] * v.nrm[2];
            pos[r] += w * p;
            nrm[r] += w * q;
        }
    }
    std::copy(pos, pos + 3, v.pos);
    std::copy(nrm, nrm + 3, v.nrm);
}

bool decodeDrawVertices(const Memory& mem, const GeState& st, u32 vtype, u32 vaddr, u32 iaddr, u32 count,
                        std::vector<DecodedVertex>& out, std::string* err) {
    out.assign(count, DecodedVertex{});
    if (count == 0) return true;
    VertexReader reader(mem, st, vtype);
    std::vector<u32> indices;
    char buf[128];
    if (!reader.readIndices(iaddr, count, indices)) {
        if (err) {
            std::snprintf(buf, sizeof buf, "index buffer 0x%08x (%u x %u bytes) is not readable", iaddr, count,
                          reader.indexSize());
            *err = buf;
        }
        return false;
    }
    bool ok = true;
    u32 badIndex = 0;
    auto decode = [&](u32 index, DecodedVertex& v) {
        if (!reader.read(vaddr, index, v)) {
            if (ok) badIndex = index;
            ok = false;
            return;
        }
        applySkinning(st, vtype, v);
    };

    const auto [mnIt, mxIt] = std::minmax_element(indices.begin(), indices.end());
    const u32 mn = *mnIt, mx = *mxIt;
    const u64 range = u64(mx) - mn + 1;
    if (range <= u64(count) * 2 + 64) {
        // Dense: decode the index range once, then gather.
        std::vector<DecodedVertex> verts(static_cast<size_t>(range));
        for (u32 i = 0; i < range; ++i) decode(mn + i, verts[i]);
        for (u32 i = 0; i < count; ++i) out[i] = verts[indices[i] - mn];
    } else {
        // Sparse (wild indices): decode each distinct index once.
        std::vector<u32> uniq(indices);
        std::sort(uniq.begin(), uniq.end());
        uniq.erase(std::unique(uniq.begin(), uniq.end()), uniq.end());
        std::vector<DecodedVertex> verts(uniq.size());
        for (size_t i = 0; i < uniq.size(); ++i) decode(uniq[i], verts[i]);
        for (u32 i = 0; i < count; ++i)
            out[i] = verts[size_t(std::lower_bound(uniq.begin(), uniq.end(), indices[i]) - uniq.begin())];
    }
    if (!ok && err) {
        std::snprintf(buf, sizeof buf, "vertex %u at 0x%08x + %u * %u bytes is not readable", badIndex, vaddr,
                      badIndex, reader.stride());
        *err = buf;
    }
    return ok;
}

}  // namespace ge
