// SPDX-License-Identifier: MIT
#include "softmodel/blend.h"

#include <array>
#include <utility>

namespace ge::soft {

namespace {

// Index = eq·16 + kindA·4 + kindB for ADD/SUB/REVERSE_SUBTRACT; MIN/MAX/ABS ignore the factors.
template <size_t... I>
constexpr std::array<BlendFn, sizeof...(I)> factorTable(std::index_sequence<I...>) {
    return {&blendT<int(I / 16), int((I / 4) % 4), int(I % 4)>...};
}
constexpr std::array<BlendFn, 48> kFactorBlends = factorTable(std::make_index_sequence<48>());

}  // namespace

BlendFn pickBlend(const BlendParams& p) {
    switch (p.eq) {
    case BLEQ_MIN: return &blendT<BLEQ_MIN, 0, 0>;
    case BLEQ_MAX: return &blendT<BLEQ_MAX, 0, 0>;
    case BLEQ_ABS: return &blendT<BLEQ_ABS, 0, 0>;
    default: break;
    }
    const u32 eq = p.eq <= BLEQ_REVSUB ? u32(p.eq) : u32(BLEQ_ADD);  // 6–7 never get here (no blending)
    return kFactorBlends[eq * 16 + blendFactorKind(p.a) * 4 + blendFactorKind(p.b)];
}

}  // namespace ge::soft
