// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp). This file is compiled into PPSSPP,
// which is licensed under the GNU GPL version 2.0 or later; so is this file.
//
// The GE's clock against the emulated CPU's. ge2gl counts GE time in ticks of the PSP's 222 MHz
// clock, and only while the GE works (ge2gl_get_tick; docs/timing.md). PPSSPP counts CoreTiming
// ticks at the CPU's frequency (222 MHz unless a game changes it). The GE runs ahead of the CPU
// (ge2gl executes a list as soon as it is given one, as PPSSPP's own GE does), but what the game
// can observe of it - interrupts, a sync returning, the state a peek reports - happens at the CPU
// tick the GE's work reaches, so this class maps one clock onto the other:
//   - the GE's time runs from an anchor: GE tick g0 happened at CPU tick c0, and GE tick g at
//     c0 + (g - g0) * cpuHz / 222 MHz;
//   - when the GE has stood still (no list, stalled, paused, waiting for an interrupt handler)
//     and is given work at CPU tick `now`, its work cannot start in the past: the anchor moves to
//     (its current tick, now) if that is later than where the old anchor puts it.
// No PPSSPP header: tests/ drive it with a real ge2gl instance (integrations/ppsspp/test).
#pragma once

#include <cstdint>

namespace ge2gl_ppsspp {

class Timeline {
public:
    static constexpr int64_t kGeHz = 222000000;

    // The CPU tick at which the GE reaches GE tick `ge` (ge >= the anchor's GE tick).
    int64_t cpuTickOf(uint64_t ge) const {
        const uint64_t d = ge >= geAnchor_ ? ge - geAnchor_ : 0;
        return cpuAnchor_ + scale(d, cpuHz_, kGeHz);
    }
    // The GE tick reached at CPU tick `cpu` (the anchor's GE tick for earlier ticks).
    uint64_t geTickAt(int64_t cpu) const {
        if (cpu <= cpuAnchor_) return geAnchor_;
        return geAnchor_ + static_cast<uint64_t>(scale(static_cast<uint64_t>(cpu - cpuAnchor_), kGeHz, cpuHz_));
    }
    // The GE, at GE tick `ge`, stood still and gets work at CPU tick `now`.
    void resume(uint64_t ge, int64_t now) {
        const int64_t at = cpuTickOf(ge);
        if (at < now) anchor(ge, now);
    }
    // The CPU's clock changed frequency (sceKernelSetCpuClock...): the GE's time so far keeps the
    // old rate, what follows the new one.
    void setCpuHz(uint64_t ge, int64_t hz) {
        if (hz <= 0 || hz == cpuHz_) return;
        anchor(ge, cpuTickOf(ge));
        cpuHz_ = hz;
    }
    int64_t cpuHz() const { return cpuHz_; }
    // Save states: the anchor and the rate.
    uint64_t geAnchor() const { return geAnchor_; }
    int64_t cpuAnchor() const { return cpuAnchor_; }
    void restore(uint64_t ge, int64_t cpu, int64_t hz) {
        geAnchor_ = ge;
        cpuAnchor_ = cpu;
        cpuHz_ = hz > 0 ? hz : kGeHz;
    }

private:
    void anchor(uint64_t ge, int64_t cpu) {
        geAnchor_ = ge;
        cpuAnchor_ = cpu;
    }
    // d * num / den without overflow for any tick count a session reaches.
    static int64_t scale(uint64_t d, int64_t num, int64_t den) {
        if (num == den) return static_cast<int64_t>(d);
        return static_cast<int64_t>((static_cast<unsigned __int128>(d) * static_cast<uint64_t>(num)) / static_cast<uint64_t>(den));
    }

    uint64_t geAnchor_ = 0;
    int64_t cpuAnchor_ = 0;
    int64_t cpuHz_ = kGeHz;
};

// What a peek sync (sceGeListSync / sceGeDrawSync mode 1) shows at CPU tick `now` of a list that
// ge2gl reports in `state` (GE2GL_LIST_*) since CPU tick `since`: a state the GE reached ahead of
// the CPU (completed, stalled or paused at a later tick) still reads DRAWING until then.
inline int32_t visibleListState(int32_t state, int64_t since, int64_t now) {
    constexpr int32_t kCompleted = 0, kDrawing = 2, kStalling = 3, kPaused = 4;
    if (since > now && (state == kCompleted || state == kStalling || state == kPaused)) return kDrawing;
    return state;
}

}  // namespace ge2gl_ppsspp
