// SPDX-License-Identifier: MIT
// Test helper (tests/api_savestate.cpp, accuracy_savestate.cpp): a dump replayed through the C ABI
// the way an emulator drives the GE (memory writes, enqueue, stall updates, runs), with the state
// saved every `every` executed commands (with guest memory) and loaded into a fresh instance of
// the other backend, which goes on with the frame. checkDump compares the finished frame with an
// uninterrupted replay on the software backend, pixel for pixel, and checks that a state saved
// right after a load is the same bytes as the state loaded.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "ge2gl/ge2gl.h"
#include "hle/dump/player.h"

namespace savestate_test {

using namespace ge;
namespace fs = std::filesystem;

inline bool glAvailable() {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_GL_HEADLESS;
    ge2gl_context* h = nullptr;
    if (ge2gl_create(&cfg, &h) != GE2GL_OK) return false;
    ge2gl_destroy(h);
    return true;
}

inline ge2gl_context* createHandle(int backend) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = backend;  // RAM: ge2gl's own 64 MiB, as dump replay needs
    ge2gl_context* h = nullptr;
    return ge2gl_create(&cfg, &h) == GE2GL_OK ? h : nullptr;
}

// The player's calls on a handle that is swapped for a fresh one of the other backend every
// `every` executed commands.
class SwitchingTarget : public dump::ReplayTarget {
public:
    // onlyAt 0: switch at every save point (a chain); k: only at the kth, the rest of the frame on
    // that one instance.
    SwitchingTarget(int firstBackend, u64 every, int onlyAt = 0) : backend_(firstBackend), every_(every), onlyAt_(onlyAt) {
        h_ = createHandle(backend_);
    }
    ~SwitchingTarget() override { ge2gl_destroy(h_); }
    ge2gl_context* handle() const { return h_; }
    int switches() const { return switches_; }
    int savePoints() const { return points_; }
    const std::string& failure() const { return failure_; }

    u32 ramSize() const override { return probe_.ramSize(); }
    u32 write(u32 addr, const void* data, u32 size) override {
        const u32 n = probe_.validSize(addr, size);
        if (n) check(ge2gl_mem_write(h_, addr, data, n), "mem_write");
        return n;
    }
    u32 fill(u32 addr, u8 value, u32 size) override {
        const u32 n = probe_.validSize(addr, size);
        std::vector<u8> b(n, value);
        if (n) check(ge2gl_mem_write(h_, addr, b.data(), n), "mem_write");
        return n;
    }
    void loadContext(const u32 ctx[512]) override { check(ge2gl_restore_context(h_, ctx), "restore_context"); }
    void startList(u32 pc, u32 stall) override {
        check(ge2gl_list_enqueue(h_, pc, stall, -1, nullptr, &id_), "list_enqueue");
    }
    RunStatus runTo(u32 stall, u64 budget) override {
        check(ge2gl_list_update_stall(h_, id_, stall), "update_stall");
        u64 used = 0;
        ge2gl_run_info info{};
        for (;;) {
            const u64 step = std::min(budget - used, every_ - sinceSwitch_);
            if (!check(ge2gl_run(h_, step, &info), "run")) return RunStatus::Error;
            used += info.commands;
            sinceSwitch_ += info.commands;
            // Mid-list, at a stall, or idle between lists: wherever the count lands.
            if (sinceSwitch_ >= every_) {
                sinceSwitch_ = 0;
                ++points_;
                if (onlyAt_ == 0 || points_ == onlyAt_) switchBackend();
            }
            if (info.ge_state != GE2GL_GE_READY || used >= budget || !failure_.empty()) break;
        }
        switch (info.ge_state) {
        case GE2GL_GE_IDLE: return RunStatus::Completed;
        case GE2GL_GE_STALLED: return RunStatus::Stalled;
        case GE2GL_GE_READY: return RunStatus::Budget;
        case GE2GL_GE_PAUSED:
        case GE2GL_GE_INTERRUPT: return RunStatus::Paused;
        default: return RunStatus::Ended;
        }
    }
    std::string lastError() override { return ge2gl_last_message(h_); }
    u32 readRegister(u8 op) override {
        uint32_t w = 0;
        check(ge2gl_get_cmd(h_, op, &w), "get_cmd");
        return w;
    }
    bool setEdramTranslation(u32 v) override { return ge2gl_edram_set_translation(h_, v, nullptr) == GE2GL_OK; }
    void finishFrame() override {
        int32_t state = 0;
        check(ge2gl_draw_sync(h_, GE2GL_SYNC_WAIT, &state), "draw_sync");
    }

private:
    bool check(ge2gl_status s, const char* what) {
        if (s != GE2GL_OK && failure_.empty()) failure_ = std::string(what) + ": " + ge2gl_last_message(h_);
        return s == GE2GL_OK;
    }
    void switchBackend() {
        sinceSwitch_ = 0;
        const void* data = nullptr;
        size_t size = 0;
        if (!check(ge2gl_state_save(h_, 0, &data, &size), "state_save")) return;
        const std::vector<u8> bare(static_cast<const u8*>(data), static_cast<const u8*>(data) + size);
        if (!check(ge2gl_state_save(h_, GE2GL_STATE_WITH_MEMORY, &data, &size), "state_save")) return;
        const std::vector<u8> full(static_cast<const u8*>(data), static_cast<const u8*>(data) + size);
        const int next = backend_ == GE2GL_BACKEND_SOFT ? GE2GL_BACKEND_GL_HEADLESS : GE2GL_BACKEND_SOFT;
        ge2gl_context* fresh = createHandle(next);
        if (!fresh) {
            failure_ = "cannot create the other backend";
            return;
        }
        if (ge2gl_state_load(fresh, full.data(), full.size()) != GE2GL_OK) {
            failure_ = std::string("state_load: ") + ge2gl_last_message(fresh);
            ge2gl_destroy(fresh);
            return;
        }
        ge2gl_destroy(h_);
        h_ = fresh;
        backend_ = next;
        ++switches_;
        // The loaded GE saves to the same bytes: nothing of the state was lost on the way.
        if (check(ge2gl_state_save(h_, 0, &data, &size), "state_save") &&
            std::vector<u8>(static_cast<const u8*>(data), static_cast<const u8*>(data) + size) != bare && failure_.empty())
            failure_ = "a state saved right after loading differs from the state loaded (switch " +
                       std::to_string(switches_) + ")";
    }

    Memory probe_;  // only for clipping writes to valid memory, as the player expects
    ge2gl_context* h_ = nullptr;
    int backend_;
    u64 every_, sinceSwitch_ = 0;
    int onlyAt_;
    int switches_ = 0, points_ = 0;
    int32_t id_ = -1;
    std::string failure_;
};

inline std::vector<u8> readDisplayed(ge2gl_context* h, const ge2gl_display& d) {
    std::vector<u8> rgba(480 * 272 * 4);
    if (ge2gl_read_frame(h, d.addr, d.stride, d.format, 480, 272, rgba.data(), rgba.size()) != GE2GL_OK) rgba.clear();
    return rgba;
}

// Replays `path` through a SwitchingTarget and returns the pixels of the displayed frame that
// differ from `want` (~0 on a failure, reported with ADD_FAILURE).
inline size_t replaySwitching(const fs::path& path, const dump::Dump& d, const ge2gl_display& disp,
                              const std::vector<u8>& want, int firstBackend, int onlyAt, int* points = nullptr) {
    SwitchingTarget target(firstBackend, 100, onlyAt);
    if (!target.handle()) return ADD_FAILURE() << "no handle", ~size_t(0);
    dump::ReplayResult res;
    std::string err;
    if (!dump::replayDump(d, target, {}, res, err)) return ADD_FAILURE() << err, ~size_t(0);
    if (!target.failure().empty()) return ADD_FAILURE() << target.failure(), ~size_t(0);
    if (points) *points = target.savePoints();
    const std::vector<u8> got = readDisplayed(target.handle(), disp);
    if (got.size() != want.size()) return ADD_FAILURE() << path << ": no frame", ~size_t(0);
    size_t differing = 0;
    for (size_t i = 0; i < got.size(); i += 4) differing += std::memcmp(&got[i], &want[i], 3) != 0;
    return differing;
}

// Saves every 100 commands. Chain: each state loads into a fresh instance of the other backend,
// which goes on to the next save point. Then, for every save point k, a replay that switches only
// there: the state loaded into a fresh instance of the other backend finishes the frame itself.
// Both give the uninterrupted soft frame exactly.
inline void checkDump(const fs::path& path, int firstBackend) {
    SCOPED_TRACE(path.string());
    ge2gl_context* ref = createHandle(GE2GL_BACKEND_SOFT);
    ASSERT_NE(ref, nullptr);
    ge2gl_display disp{};
    ASSERT_EQ(ge2gl_replay_dump(ref, path.c_str(), &disp), GE2GL_OK) << ge2gl_last_message(ref);
    const std::vector<u8> want = readDisplayed(ref, disp);
    ge2gl_destroy(ref);
    ASSERT_FALSE(want.empty());

    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(path.string(), d, err)) << err;
    int points = 0;
    EXPECT_EQ(replaySwitching(path, d, disp, want, firstBackend, 0, &points), 0u) << "chain of " << points << " switches";
    ASSERT_GT(points, 0);
    for (int k = 1; k <= points; ++k)
        EXPECT_EQ(replaySwitching(path, d, disp, want, firstBackend, k), 0u) << "switched only at save point " << k;
    std::cout << path.filename().string() << ": " << points << " save points\n";
}

}  // namespace savestate_test
