// SPDX-License-Identifier: MIT
// Test helper: an "emulator" that owns PSP RAM/VRAM, writes display lists into it like a game,
// and talks to ge2gl only through the C ABI (include/ge2gl/ge2gl.h).
#pragma once
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "ge2gl/ge2gl.h"

namespace apitest {

constexpr uint32_t kRamBase = 0x08000000;
constexpr uint32_t kRamSize = 4u << 20;  // enough for the tests; addresses 0x08000000–0x083FFFFF

struct Event {
    char kind = 0;  // 'S' signal, 'F' finish, 'E' end, 'X' error, 'P' progress
    int32_t list = 0, cbid = 0, registered = 0;
    uint32_t behaviour = 0, arg = 0, pc = 0, endArg = 0, func = 0, funcArg = 0;
    std::string message;
};

class Host {
public:
    explicit Host(int backend = GE2GL_BACKEND_NULL, uint32_t sdk = 0, bool worker = false, bool hold = false)
        : ram(kRamSize), vram(0x200000) {
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.ram = ram.data();
        cfg.ram_size = kRamSize;
        cfg.vram = vram.data();
        cfg.backend = backend;
        cfg.sdk_version = sdk;
        cfg.worker_thread = worker ? 1 : 0;
        cfg.hold_interrupts = hold ? 1 : 0;
        cfg.wait_budget = 1u << 20;
        cfg.callbacks.user = this;
        cfg.callbacks.signal = [](void* u, const ge2gl_interrupt* i) { static_cast<Host*>(u)->interrupt('S', *i); };
        cfg.callbacks.finish = [](void* u, const ge2gl_interrupt* i) { static_cast<Host*>(u)->interrupt('F', *i); };
        cfg.callbacks.end = [](void* u, int32_t id, uint32_t pc) {
            Event e;
            e.kind = 'E', e.list = id, e.pc = pc;
            static_cast<Host*>(u)->push(e);
        };
        cfg.callbacks.error = [](void* u, int32_t id, uint32_t pc, const char* m) {
            Event e;
            e.kind = 'X', e.list = id, e.pc = pc, e.message = m;
            static_cast<Host*>(u)->push(e);
        };
        cfg.callbacks.progress = [](void* u, int32_t id, uint32_t pc) {
            Event e;
            e.kind = 'P', e.list = id, e.pc = pc;
            static_cast<Host*>(u)->push(e);
        };
        status = ge2gl_create(&cfg, &h);
    }
    ~Host() { ge2gl_destroy(h); }
    Host(const Host&) = delete;
    Host& operator=(const Host&) = delete;

    void interrupt(char kind, const ge2gl_interrupt& i) {
        Event e;
        e.kind = kind, e.list = i.list_id, e.cbid = i.cbid, e.registered = i.registered;
        e.behaviour = i.behaviour, e.arg = i.arg, e.pc = i.pc, e.endArg = i.end_arg, e.func = i.func, e.funcArg = i.func_arg;
        push(e);
        if (kind == 'S' && onSignal) onSignal(i);
        if (kind == 'F' && onFinish) onFinish(i);
    }
    void push(const Event& e) { events.push_back(e); }
    // Events of the given kinds, in order.
    std::vector<Event> only(const char* kinds) const {
        std::vector<Event> out;
        for (const Event& e : events)
            if (std::strchr(kinds, e.kind)) out.push_back(e);
        return out;
    }

    void write32(uint32_t addr, uint32_t v) {
        uint32_t o = (addr & 0x0FFFFFFF) - kRamBase;
        ram[o] = uint8_t(v), ram[o + 1] = uint8_t(v >> 8), ram[o + 2] = uint8_t(v >> 16), ram[o + 3] = uint8_t(v >> 24);
    }
    uint32_t cmd(uint32_t op) {
        uint32_t v = 0;
        if (ge2gl_get_cmd(h, op, &v) != GE2GL_OK) return 0xDEADBEEF;
        return v;
    }
    ge2gl_run_info run(uint64_t n = 1u << 20) {
        ge2gl_run_info info{};
        ge2gl_run(h, n, &info);
        return info;
    }
    int32_t peek(int32_t id) {
        int32_t s = -1;
        ge2gl_status st = ge2gl_list_sync(h, id, GE2GL_SYNC_PEEK, &s);
        return st == GE2GL_OK ? s : st;
    }

    std::vector<uint8_t> ram, vram;
    ge2gl_context* h = nullptr;
    ge2gl_status status = GE2GL_OK;
    std::vector<Event> events;
    std::function<void(const ge2gl_interrupt&)> onSignal, onFinish;
};

// Emits command words into the host's RAM like a game building a list.
class ListWriter {
public:
    ListWriter(Host& host, uint32_t start) : host_(host), start_(start), pos_(start) {}
    // Returns the address of the word written.
    uint32_t put(uint32_t op, uint32_t arg = 0) {
        host_.write32(pos_, (op << 24) | (arg & 0xFFFFFF));
        pos_ += 4;
        return pos_ - 4;
    }
    uint32_t signal(uint32_t behaviour, uint32_t arg, uint32_t endArg = 0) {
        uint32_t a = put(0x0E, (behaviour << 16) | (arg & 0xFFFF));
        put(0x0C, endArg);
        return a;
    }
    // SIGNAL + END carrying a 32-bit address/offset split in two halves (docs/ge-rules.md §4.4 jump/call forms).
    uint32_t signalAddr(uint32_t behaviour, uint32_t value) { return signal(behaviour, value >> 16, value & 0xFFFF); }
    uint32_t finish(uint32_t arg = 0) {
        uint32_t a = put(0x0F, arg);
        put(0x0C, 0);
        return a;
    }
    uint32_t start() const { return start_; }
    uint32_t here() const { return pos_; }

private:
    Host& host_;
    uint32_t start_, pos_;
};

}  // namespace apitest
