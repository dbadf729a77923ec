// SPDX-License-Identifier: MIT
// Whole-GE save states (the byte format is docs/savestate.md).
//
// A state holds what cannot be re-derived: the engine (registers, matrices and their upload
// indices, palette RAM, the running list's execution registers, an immediate-mode primitive being
// collected, the GE-time count), the sceGe layer (the 64 list slots with every list's state, pc,
// stall, stacks, BASE/OFFSET and IDs, the queue order, callbacks, a FINISH interrupt still owed,
// SDK version), a few host-level flags the caller adds (the plugin API's held interrupt), and,
// when asked, guest memory (RAM, VRAM, scratchpad; zstd-compressed). Backend caches are not in it:
// the caller writes everything a backend holds back to guest memory before saving, and a load
// drops every cache, so a state saved on one backend loads on any other.
//
// Loading is all or nothing: the blob is checked whole (magic, version, size, xxHash64 of the
// payload, every section and value range) before anything changes; a corrupt or foreign blob is
// refused with a reason and leaves the GE as it was.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "hle/memory.h"
#include "hle/sce_ge.h"

namespace ge::savestate {

// Version 2 added the vertex unit's latched UV and normal (GeState::latchUV/latchNormal) at the
// end of the engine's state; version 1 blobs still load (the latch starts at zero).
constexpr u32 kFormatVersion = 3;
constexpr u32 kOldestFormatVersion = 1;
constexpr u32 kHeaderSize = 32;

struct HostFlags {
    bool heldInterrupt = false;  // plugin API hold_interrupts: the GE waits for an acknowledgement
};

// Serialises the engine and sceGe layer (and guest memory when `mem` is given).
std::vector<u8> save(const GeEngine& engine, const SceGe& sce, const Memory* mem, const HostFlags& host);

// Checks and applies a blob. Guest memory is restored when the blob holds it (its RAM size must be
// `mem`'s); `hadMemory` says whether it did. On failure returns false with `err` and changes nothing.
bool load(std::span<const u8> blob, GeEngine& engine, SceGe& sce, Memory& mem, HostFlags& host, bool& hadMemory,
          std::string& err);

// Reads the header only: format version and whether guest memory is included (for tools).
bool inspect(std::span<const u8> blob, u32& version, bool& hasMemory, std::string& err);

}  // namespace ge::savestate
