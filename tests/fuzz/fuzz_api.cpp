// SPDX-License-Identifier: MIT
// Harness (h): the plugin C ABI (include/ge2gl/ge2gl.h) driven by a byte stream. An instance with
// the software backend (one thread) is created, then each opcode byte of the stream selects a call
// — guest memory writes (the lists and the data they point at), enqueue / enqueue-head with list
// arguments, dequeue, stall updates, list and draw syncs (peek and wait), break / continue,
// callbacks, context save / restore (host buffer and guest address), register and matrix reads,
// eDRAM translation, runs, frame reads, destroy and re-create — with arguments from the stream.
// The host callbacks may call back into the API (continue, stall update, enqueue, break, and a
// wait, which must be refused as reentrant).
//
// Checked: every call returns a status the ABI defines; nothing crashes, leaks or reads out of
// bounds. Bounded: at most 64 KiB of input, at most 32 calls that run the GE per input, each with
// a budget of at most 256 commands, and small draws: the ABI has no work limit of its own (a host
// meters its GE by commands), so every aligned word the stream writes into guest memory is tamed
// before the GE can read it (tame(): at most 16 vertices a PRIM/BBOX, 7x7 control points and
// divisions a patch, a 32x32 scissor/region, 32x32-pixel transfers). What a single draw costs is
// fuzzed by the other harnesses.
#include <cstdint>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <vector>

#include "ge2gl/ge2gl.h"

namespace {

constexpr size_t kMaxStream = 64 << 10;

struct Reader {
    const uint8_t* p;
    size_t n, i = 0;
    bool empty() const { return i >= n; }
    uint8_t u8() { return i < n ? p[i++] : 0; }
    uint16_t u16() { return uint16_t(u8() | (u8() << 8)); }
    uint32_t u32() { return u16() | (uint32_t(u16()) << 16); }
};

[[noreturn]] void fail(const char* what, ge2gl_status s) {
    std::fprintf(stderr, "fuzz_api: %s returned an undefined status %d\n", what, int(s));
    __builtin_trap();
}

// Every status a call returns must be one the header defines.
ge2gl_status check(const char* what, ge2gl_status s) {
    if (std::strcmp(ge2gl_status_name(s), "unknown status") == 0) fail(what, s);
    return s;
}

// Keeps a command word's work small (see the top of the file); other words pass unchanged.
uint32_t tame(uint32_t w) {
    const uint32_t op = w >> 24, arg = w & 0xFFFFFF;
    auto low = [](uint32_t v, uint32_t max) { return v < max ? v : max; };
    switch (op) {
    case 0x04: return (w & 0xFFFF0000u) | low(arg & 0xFFFF, 16);                                     // PRIM
    case 0x07: return (w & 0xFFFF0000u) | low(arg & 0xFFFF, 16);                                     // BBOX
    case 0x05: case 0x06: return (w & 0xFFFF0000u) | low(arg & 0xFF, 7) | (low((arg >> 8) & 0xFF, 7) << 8);  // patches
    case 0x36: return (w & 0xFFFF0000u) | low(arg & 0xFF, 7) | (low((arg >> 8) & 0xFF, 7) << 8);  // DIVIDE
    case 0x16: case 0xD5: case 0xEE:  // REGION2, SCISSOR2, XSIZE: x/width bits 0-9, y/height 10-19
        return (w & 0xFFF00000u) | low(arg & 0x3FF, 31) | (low((arg >> 10) & 0x3FF, 31) << 10);
    default: return w;
    }
}

// Writes bytes into guest memory, then tames every aligned word they touched.
ge2gl_status writeTamed(ge2gl_context* h, uint32_t a, const std::vector<uint8_t>& bytes) {
    const ge2gl_status s = ge2gl_mem_write(h, a, bytes.data(), uint32_t(bytes.size()));
    if (s != GE2GL_OK || bytes.empty()) return s;
    const uint32_t lo = a & ~3u, hi = (a + uint32_t(bytes.size()) + 3) & ~3u;
    std::vector<uint8_t> words(hi - lo);
    if (ge2gl_mem_read(h, lo, words.data(), hi - lo) != GE2GL_OK) return s;
    for (size_t i = 0; i < words.size(); i += 4) {
        uint32_t w;
        std::memcpy(&w, &words[i], 4);
        w = tame(w);
        std::memcpy(&words[i], &w, 4);
    }
    ge2gl_mem_write(h, lo, words.data(), hi - lo);
    return s;
}

struct Host {
    ge2gl_context* h = nullptr;
    int32_t ids[16] = {};
    unsigned nids = 0;
    uint32_t lastList = 0x08800000;
    uint8_t actions = 0;  // what the callbacks do (bits below)
    unsigned nested = 0;  // calls made from callbacks (bounded)
    uint32_t ctx[512] = {};

    void addId(int32_t id) { ids[nids++ % 16] = id; }
    int32_t id(uint8_t sel) const {
        if (sel >= 0xF0) return int32_t(sel) - 0xF8;  // a few invalid IDs
        return nids ? ids[sel % std::min(nids, 16u)] : 0;
    }
};

// Guest addresses: mostly inside the list/data area and VRAM, sometimes anything.
uint32_t addr(Reader& r) {
    const uint8_t sel = r.u8();
    const uint32_t off = r.u32();
    switch (sel & 3) {
    case 0: return 0x08800000 + (off & 0xFFFC);
    case 1: return 0x04000000 + (off & 0x1FFFFF);
    case 2: return 0x08800000 + (off & 0x3FFFFF);
    default: return off;
    }
}

void cbSignal(void* user, const ge2gl_interrupt* irq) {
    Host& H = *static_cast<Host*>(user);
    if (H.nested >= 16) return;
    ++H.nested;
    if (H.actions & 1) check("continue (callback)", ge2gl_continue(H.h));
    if (H.actions & 2) check("update_stall (callback)", ge2gl_list_update_stall(H.h, irq->list_id, 0));
    if (H.actions & 4) {
        int32_t st = 0;
        const ge2gl_status s = check("draw_sync (callback)", ge2gl_draw_sync(H.h, GE2GL_SYNC_WAIT, &st));
        if (s != GE2GL_ERR_REENTRANT) fail("draw_sync wait inside a callback was not refused", s);
    }
}
void cbFinish(void* user, const ge2gl_interrupt* irq) {
    Host& H = *static_cast<Host*>(user);
    if (H.nested >= 16) return;
    ++H.nested;
    if (H.actions & 8) {
        int32_t id = -1;
        if (check("enqueue (callback)", ge2gl_list_enqueue(H.h, H.lastList, 0, irq->cbid, nullptr, &id)) == GE2GL_OK)
            H.addId(id);
    }
    if (H.actions & 16) check("break (callback)", ge2gl_break(H.h, 0, nullptr));
}
void cbEnd(void* user, int32_t, uint32_t) {
    Host& H = *static_cast<Host*>(user);
    if ((H.actions & 32) && H.nested < 16) {
        ++H.nested;
        ge2gl_run_info info;
        const ge2gl_status s = check("run (callback)", ge2gl_run(H.h, 16, &info));
        if (s != GE2GL_ERR_REENTRANT) fail("run inside a callback was not refused", s);
    }
}
void cbError(void*, int32_t, uint32_t, const char* message) {
    if (!message) __builtin_trap();
}
void cbProgress(void*, int32_t, uint32_t) {}

bool create(Host& H, Reader& r) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.soft_threads = 1;
    cfg.ram_size = (r.u8() & 1) ? 32u << 20 : 0;
    const uint8_t sdk = r.u8();
    cfg.sdk_version = sdk < 0x80 ? 0 : (sdk < 0xC0 ? 0x02000010 : 0x06060010);
    cfg.wait_budget = 1 + (r.u16() & 0xFF);
    cfg.callbacks = ge2gl_callbacks{&H, cbSignal, cbFinish, cbEnd, cbError, cbProgress};
    H.nids = 0;
    return check("create", ge2gl_create(&cfg, &H.h)) == GE2GL_OK;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > kMaxStream) return -1;
    Reader r{data, size};
    Host H;
    if (!create(H, r)) return 0;
    int runs = 0;
    std::vector<uint8_t> buf;
    // A last resort against inputs that still find something slow: stop after two seconds.
    const auto t0 = std::chrono::steady_clock::now();
    while (!r.empty() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2)) {
        ge2gl_context* h = H.h;
        const uint8_t op = r.u8();
        switch (op % 22) {
        case 0: {  // guest memory write (lists, vertices, textures, contexts …)
            const uint32_t a = addr(r);
            const uint16_t len = r.u16() & 0xFFF;
            buf.assign(len, 0);
            for (auto& b : buf) b = r.u8();
            check("mem_write", writeTamed(h, a, buf));
            break;
        }
        case 1:
        case 2: {  // enqueue / enqueue head
            const uint32_t list = addr(r);
            const uint8_t stallSel = r.u8();
            const uint32_t stall = stallSel == 0 ? 0 : (stallSel < 0x80 ? list + 4u * (stallSel & 0x7F) : addr(r));
            const int32_t cbid = int32_t(int8_t(r.u8())) % 20;
            const uint8_t argSel = r.u8();
            ge2gl_list_args args{};
            args.size = (argSel & 1) ? 16 : 8;
            args.context = (argSel & 2) ? addr(r) : 0;
            args.num_stacks = (argSel & 4) ? r.u16() & 0x1FF : 0;
            args.stacks = (argSel & 8) ? addr(r) : 0;
            int32_t id = -1;
            H.lastList = list;
            const ge2gl_status s =
                op % 22 == 1 ? ge2gl_list_enqueue(h, list, stall, cbid, (argSel & 16) ? &args : nullptr, &id)
                             : ge2gl_list_enqueue_head(h, list, stall, cbid, (argSel & 16) ? &args : nullptr, &id);
            if (check("enqueue", s) == GE2GL_OK) H.addId(id);
            break;
        }
        case 3: check("dequeue", ge2gl_list_dequeue(h, H.id(r.u8()))); break;
        case 4: {
            const int32_t id = H.id(r.u8());
            check("update_stall", ge2gl_list_update_stall(h, id, addr(r)));
            break;
        }
        case 5: {
            const int32_t id = H.id(r.u8());
            const int32_t mode = int32_t(r.u8() % 3);
            if (mode == GE2GL_SYNC_WAIT && ++runs > 32) break;
            int32_t st = 0;
            check("list_sync", ge2gl_list_sync(h, id, mode, &st));
            break;
        }
        case 6: {
            const int32_t mode = int32_t(r.u8() % 3);
            if (mode == GE2GL_SYNC_WAIT && ++runs > 32) break;
            int32_t st = 0;
            check("draw_sync", ge2gl_draw_sync(h, mode, (r.u8() & 1) ? &st : nullptr));
            break;
        }
        case 7: {
            int32_t id = 0;
            check("break", ge2gl_break(h, int32_t(r.u8() % 3), &id));
            break;
        }
        case 8: check("continue", ge2gl_continue(h)); break;
        case 9: {
            int32_t cbid = -1;
            const uint32_t a = r.u32(), b = r.u32(), c = r.u32(), d = r.u32();
            check("set_callback", ge2gl_set_callback(h, a, b, c, d, &cbid));
            break;
        }
        case 10: check("unset_callback", ge2gl_unset_callback(h, int32_t(int8_t(r.u8())))); break;
        case 11: check("save_context", ge2gl_save_context(h, H.ctx)); break;
        case 12: {  // restore a saved context with one word changed
            const uint16_t i = r.u16() % 512;
            H.ctx[i] = tame(r.u32());
            check("restore_context", ge2gl_restore_context(h, H.ctx));
            break;
        }
        case 13: check("save_context_at", ge2gl_save_context_at(h, addr(r))); break;
        case 14: check("restore_context_at", ge2gl_restore_context_at(h, addr(r))); break;
        case 15: {
            uint32_t w = 0, m[16];
            int32_t count = 0;
            const uint8_t a = r.u8(), b = r.u8();
            check("get_cmd", ge2gl_get_cmd(h, a, &w));
            check("get_matrix", ge2gl_get_matrix(h, int32_t(int8_t(b)) % 14, m, &count));
            break;
        }
        case 16: {
            static const uint32_t values[] = {0, 0x200, 0x400, 0x800, 0x1000, 0x100, 0xFFFFFFFF};
            const uint8_t v = r.u8();
            uint32_t prev = 0, a = 0;
            check("edram_set_translation",
                  ge2gl_edram_set_translation(h, v < 0xF0 ? values[v % 5] : values[v % 7], &prev));
            check("edram_get_addr", ge2gl_edram_get_addr(h, &a));
            check("edram_get_size", ge2gl_edram_get_size(h, &a));
            break;
        }
        case 17: {
            if (++runs > 32) break;
            ge2gl_run_info info;
            check("run", ge2gl_run(h, r.u16() & 0xFF, (r.u8() & 1) ? &info : nullptr));
            break;
        }
        case 18: {
            const uint32_t a = addr(r);
            const uint32_t stride = r.u16() & 0x7FF;
            const int32_t fmt = int32_t(r.u8() % 5);
            const uint32_t w = r.u8() % 65, hgt = r.u8() % 65;
            buf.assign(size_t(w) * hgt * 4 + (r.u8() & 4), 0);
            check("read_frame", ge2gl_read_frame(h, a, stride, fmt, w, hgt, buf.data(), buf.size()));
            uint32_t tex = 0;
            check("frame_texture", ge2gl_frame_texture(h, a, stride, fmt, w, hgt, &tex));
            break;
        }
        case 19: {
            const uint32_t a = addr(r);
            const uint32_t len = r.u16() & 0xFFF;
            buf.assign(len, 0);
            uint8_t* p = nullptr;
            check("mem_read", ge2gl_mem_read(h, a, buf.data(), len));
            check("mem_pointer", ge2gl_mem_pointer(h, a, len, &p));
            check("mem_written", ge2gl_mem_written(h, a, len));
            break;
        }
        case 20:  // destroy and start over
            ge2gl_destroy(h);
            H.h = nullptr;
            if (!create(H, r)) return 0;
            break;
        case 21: H.actions = r.u8(); break;
        }
        if (!ge2gl_last_message(H.h)) __builtin_trap();
    }
    ge2gl_destroy(H.h);
    return 0;
}
