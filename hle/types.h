// SPDX-License-Identifier: MIT
// Basic integer types and small helpers shared by every part of ge2gl.
#pragma once
#include <cstdint>
#include <cstring>

namespace ge {

using u8 = std::uint8_t;
using u16 = std::uint16_t;
using u32 = std::uint32_t;
using u64 = std::uint64_t;
using s8 = std::int8_t;
using s16 = std::int16_t;
using s32 = std::int32_t;
using s64 = std::int64_t;

// GE "float24": the top 24 bits of an IEEE single (docs/ge-rules.md §1.2).
inline float float24(u32 arg) {
    u32 bits = arg << 8;
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}
inline u32 toFloat24(float f) {
    u32 bits;
    std::memcpy(&bits, &f, 4);
    return bits >> 8;  // the SDK truncates
}

inline u32 readLE32(const u8* p) { return u32(p[0]) | u32(p[1]) << 8 | u32(p[2]) << 16 | u32(p[3]) << 24; }
inline u16 readLE16(const u8* p) { return u16(p[0] | p[1] << 8); }
inline void writeLE32(u8* p, u32 v) { p[0] = u8(v); p[1] = u8(v >> 8); p[2] = u8(v >> 16); p[3] = u8(v >> 24); }
inline void writeLE16(u8* p, u16 v) { p[0] = u8(v); p[1] = u8(v >> 8); }

}  // namespace ge
