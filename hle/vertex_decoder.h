// SPDX-License-Identifier: MIT
// Vertex decoding (manual §6, §7; docs/ge-rules.md §5): the one reference implementation of the
// VTYPE formats, morphing, skinning and index reading, shared by both backends and BBOX.
#pragma once
#include <string>
#include <vector>

#include "hle/ge_state.h"
#include "hle/memory.h"
#include "hle/types.h"

namespace ge {

struct DecodedVertex {
    // Transform mode: model space (s8 /128, s16 /32768, float). Through mode: x, y drawing
    // coordinates, z 0..65535 (ge-rules.md §5.4).
    float pos[3] = {};
    // Transform mode: u8 /128, u16 /32768, float. Through mode: texels.
    // A format without UV or normal gives the vertex unit's last ones (GeState::latchUV/Normal).
    float uv[2] = {};
    float nrm[3] = {};
    float weights[8] = {};
    // RGBA; MAC RGB + MAA alpha when the format has no colour (ge-rules.md §5.5).
    u8 color[4] = {};
};

class VertexReader {
public:
    VertexReader(const Memory& mem, const GeState& st, u32 vtype);

    u32 stride() const;  // bytes per vertex including morph copies
    const VertexLayout& layout() const;
    bool hasColor() const { return ((vtype_ >> 2) & 7) >= 4; }  // CT 1–3: invalid, no colour (ge-rules.md §5.1)
    bool hasNormal() const { return ((vtype_ >> 5) & 3) != 0; }
    bool hasUV() const { return (vtype_ & 3) != 0; }
    bool hasWeights() const { return ((vtype_ >> 9) & 3) != 0; }
    bool hasPosition() const { return ((vtype_ >> 7) & 3) != 0; }
    bool through() const { return (vtype_ >> 23) & 1; }
    u32 morphCount() const;   // 1..8
    u32 weightCount() const;  // 0 when there are no weights, else 1..8
    u32 indexSize() const;    // 0, 1, 2 or 4 bytes

    // Decodes vertex number `index` of the array at `base` with morphing applied (MC>0, transform
    // mode, every component incl. colour weighted by CMD_WEIGHTn). Returns false (out zeroed) if
    // the bytes are not valid memory.
    bool read(u32 base, u32 index, DecodedVertex& out) const;
    // The bytes of vertices first … first + count − 1 of the array at `base` when they are all
    // valid memory (null otherwise): a draw's index range is checked and looked up once, and each
    // vertex decoded from it with decodeAt(span + k · stride()), which gives what read() gives.
    const u8* span(u32 base, u32 first, u32 count) const;
    void decodeAt(const u8* p, DecodedVertex& out) const;
    // Reads `count` indices at iaddr (u8/u16/u32 per IT); IT==0 gives 0..count-1. False on bad memory.
    bool readIndices(u32 iaddr, u32 count, std::vector<u32>& out) const;
    // The smallest and largest of those indices and the last one, read in place (no copy).
    // False on bad memory; with IT==0 the range 0..count-1.
    bool indexBounds(u32 iaddr, u32 count, u32& lo, u32& hi, u32& last) const;

private:
    void materialColor(DecodedVertex& out) const;
    const Memory& mem_;
    const GeState& st_;
    u32 vtype_;
    VertexLayout layout_;
    u32 stride_;
    u32 morphs_;
    float morphW_[8] = {};
};

// Skinning (WT≠0, transform mode): pos = Σ w_i·(Bone_i·(pos,1)), nrm = Σ w_i·(Bone_i 3x3·nrm),
// in place (manual §7.2, ge-rules.md §5.5).
void applySkinning(const GeState& st, u32 vtype, DecodedVertex& v);

// Convenience: the draw's vertices in draw order (indices resolved), skinning applied.
// Decodes each distinct vertex once (index range); false + err on bad memory.
bool decodeDrawVertices(const Memory& mem, const GeState& st, u32 vtype, u32 vaddr, u32 iaddr, u32 count,
                        std::vector<DecodedVertex>& out, std::string* err = nullptr);

}  // namespace ge
