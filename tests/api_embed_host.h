// SPDX-License-Identifier: MIT
// A host that owns RAM and VRAM (used in place by ge2gl) and writes display lists like a game,
// over the C ABI only; what the vram_dirty and drop callbacks tell it is recorded. Shared by the
// embedding tests (api_embed.cpp) and the threaded-host defect tests (api_host_defects.cpp).
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "authoring/list_builder.h"
#include "ge2gl/ge2gl.h"
#include "hle/memory.h"

namespace apitest {

struct GameHost {
    static constexpr uint32_t kRamSize = 8u << 20;
    struct Drop {
        int32_t list;
        uint32_t pc;
        std::string message;
    };

    std::vector<uint8_t> ram = std::vector<uint8_t>(kRamSize), vram = std::vector<uint8_t>(0x200000);
    ge::Memory mem{ram.data(), kRamSize, vram.data()};  // the host's view, for ListBuilder
    ge2gl_context* h = nullptr;
    ge2gl_status status = GE2GL_ERR_BACKEND;
    uint32_t arena = 0x08200000;     // next list's arena
    uint32_t arenaStep = 0x10000;    // room per list (its inline vertex data included)
    std::vector<std::pair<uint32_t, uint32_t>> dirty;
    std::vector<Drop> drops;

    // `backend`: a GE2GL_BACKEND_*; `tweak` adjusts the config before creation.
    template <class Tweak>
    GameHost(int backend, Tweak tweak) {
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.ram = ram.data();
        cfg.ram_size = kRamSize;
        cfg.vram = vram.data();
        cfg.backend = backend;
        cfg.callbacks.user = this;
        cfg.vram_dirty = [](void* u, uint32_t a, uint32_t n) { static_cast<GameHost*>(u)->dirty.emplace_back(a, n); };
        cfg.drop = [](void* u, int32_t id, uint32_t pc, const char* m) {
            static_cast<GameHost*>(u)->drops.push_back({id, pc, m});
        };
        tweak(cfg);
        status = ge2gl_create(&cfg, &h);
    }
    explicit GameHost(int backend) : GameHost(backend, [](ge2gl_config&) {}) {}
    GameHost(const GameHost&) = delete;
    GameHost& operator=(const GameHost&) = delete;
    ~GameHost() { ge2gl_destroy(h); }

    // A list in the next arena: frame buffer 8888 at VRAM 0 (stride 512), then `body`, FINISH.
    template <class Body>
    uint32_t list(Body body) {
        ge::ListBuilder b(&mem, arena);
        arena += arenaStep;
        b.drawBuffer(ge::GE_FORMAT_8888, 0, 512);
        b.scissor(0, 0, 480, 272);
        b.region(0, 0, 480, 272);
        body(b);
        b.finish();
        return b.placeList();
    }
    static void clearTo(ge::ListBuilder& b, uint32_t abgr) { b.clear(ge::CLEAR_COLOR | ge::CLEAR_STENCIL, abgr, 0); }

    ge2gl_status enqueue(uint32_t listAddr) {
        int32_t id = -1;
        return ge2gl_list_enqueue(h, listAddr, 0, -1, nullptr, &id);
    }
    ge2gl_status drawSync() {
        int32_t s = -1;
        return ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &s);
    }
    // Enqueues and waits (draw sync); returns the first failing status.
    ge2gl_status draw(uint32_t listAddr) {
        if (ge2gl_status st = enqueue(listAddr); st != GE2GL_OK) return st;
        return drawSync();
    }
    // The host's own VRAM bytes at (x, y) of the 8888 frame buffer, as ABGR.
    uint32_t hostPixel(int x, int y) const {
        uint32_t v;
        std::memcpy(&v, &vram[(size_t(y) * 512 + size_t(x)) * 4], 4);
        return v;
    }
    void pokePixel(int x, int y, uint32_t abgr) { std::memcpy(&vram[(size_t(y) * 512 + size_t(x)) * 4], &abgr, 4); }
    ge2gl_stats stats() const {
        ge2gl_stats s{};
        s.struct_size = sizeof s;
        EXPECT_EQ(ge2gl_get_stats(h, &s), GE2GL_OK);
        return s;
    }
};

}  // namespace apitest
