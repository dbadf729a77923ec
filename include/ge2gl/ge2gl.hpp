// SPDX-License-Identifier: MIT
// ge2gl C++ wrapper: RAII ownership of a ge2gl_context and std::function callbacks over the C ABI.
// Header-only; it links only against the C functions of ge2gl.h, so any C++14 compiler can use it
// with the shared library whatever compiled that (the example below uses C++20's designated
// initializers; ApiDocs checks the header with -std=c++14). No exceptions cross the C boundary: the callback trampolines catch
// everything a std::function throws (the exception is dropped and reported through
// Context::callbackFailures()).
//
//   ge2gl_config cfg;
//   ge2gl_config_init(&cfg);
//   auto ctx = ge2gl::Context::create(cfg, {.finish = [](const ge2gl_interrupt& i) { ... }});
//   if (!ctx) { puts(ctx.message.c_str()); return; }
//   auto id = ctx.value.enqueue(list, stall);
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ge2gl/ge2gl.h"

namespace ge2gl {

struct Status {
    ge2gl_status code = GE2GL_OK;
    bool ok() const { return code == GE2GL_OK; }
    explicit operator bool() const { return ok(); }
    const char* name() const { return ge2gl_status_name(code); }
};

template <class T>
struct Result {
    Status status;
    T value{};
    std::string message;  // why it failed (empty on success)
    bool ok() const { return status.ok(); }
    explicit operator bool() const { return ok(); }
};

struct Callbacks {
    std::function<void(const ge2gl_interrupt&)> signal;
    std::function<void(const ge2gl_interrupt&)> finish;
    std::function<void(int32_t listId, uint32_t pc)> end;
    std::function<void(int32_t listId, uint32_t pc, const char* message)> error;
    std::function<void(int32_t listId, uint32_t readUpTo)> progress;
    // config.lazy_writeback: [addr, addr+size) of VRAM was drawn into (API 1.2).
    std::function<void(uint32_t addr, uint32_t size)> vramDirty;
};

class Context {
public:
    Context() = default;
    ~Context() { reset(); }
    Context(Context&& o) noexcept : h_(std::exchange(o.h_, nullptr)), cb_(std::move(o.cb_)) {}
    Context& operator=(Context&& o) noexcept {
        if (this != &o) {
            reset();
            h_ = std::exchange(o.h_, nullptr);
            cb_ = std::move(o.cb_);
        }
        return *this;
    }
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Creates a context; config.callbacks is replaced by trampolines to `callbacks`.
    static Result<Context> create(ge2gl_config config, Callbacks callbacks = {}) {
        Result<Context> r;
        auto state = std::make_unique<CallbackState>();
        state->fn = std::move(callbacks);
        config.callbacks.user = state.get();
        config.callbacks.signal = state->fn.signal ? &onSignal : nullptr;
        config.callbacks.finish = state->fn.finish ? &onFinish : nullptr;
        config.callbacks.end = state->fn.end ? &onEnd : nullptr;
        config.callbacks.error = state->fn.error ? &onError : nullptr;
        config.callbacks.progress = state->fn.progress ? &onProgress : nullptr;
        if (config.struct_size >= offsetof(ge2gl_config, vram_dirty) + sizeof(config.vram_dirty))
            config.vram_dirty = state->fn.vramDirty ? &onVramDirty : nullptr;
        ge2gl_context* h = nullptr;
        r.status.code = ge2gl_create(&config, &h);
        if (!r.ok()) {
            const char* why = ge2gl_last_message(nullptr);
            r.message = why && *why ? why : r.status.name();
            return r;
        }
        r.value.h_ = h;
        r.value.cb_ = std::move(state);
        return r;
    }

    void reset() {
        if (h_) ge2gl_destroy(h_);
        h_ = nullptr;
        cb_.reset();
    }
    ge2gl_context* get() const { return h_; }
    explicit operator bool() const { return h_ != nullptr; }
    std::string lastMessage() const { return h_ ? ge2gl_last_message(h_) : "no context"; }
    // Exceptions thrown (and swallowed) by the host's std::function callbacks.
    unsigned callbackFailures() const { return cb_ ? cb_->failures : 0; }

    // ---- guest memory ----
    Status memWrite(uint32_t addr, const void* src, uint32_t size) { return {ge2gl_mem_write(h_, addr, src, size)}; }
    Status memRead(uint32_t addr, void* dst, uint32_t size) { return {ge2gl_mem_read(h_, addr, dst, size)}; }
    Status memWritten(uint32_t addr, uint32_t size) { return {ge2gl_mem_written(h_, addr, size)}; }
    Status syncRange(uint32_t addr, uint32_t size) { return {ge2gl_sync_range(h_, addr, size)}; }

    // ---- sceGe ----
    Result<int32_t> enqueue(uint32_t list, uint32_t stall, int32_t cbid = -1, const ge2gl_list_args* args = nullptr) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_list_enqueue(h_, list, stall, cbid, args, v); });
    }
    Result<int32_t> enqueueHead(uint32_t list, uint32_t stall, int32_t cbid = -1, const ge2gl_list_args* args = nullptr) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_list_enqueue_head(h_, list, stall, cbid, args, v); });
    }
    Status dequeue(int32_t id) { return {ge2gl_list_dequeue(h_, id)}; }
    Status updateStall(int32_t id, uint32_t stall) { return {ge2gl_list_update_stall(h_, id, stall)}; }
    Result<int32_t> listSync(int32_t id, int32_t mode) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_list_sync(h_, id, mode, v); });
    }
    Result<int32_t> drawSync(int32_t mode) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_draw_sync(h_, mode, v); });
    }
    Result<int32_t> breakList(int32_t mode) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_break(h_, mode, v); });
    }
    Status continueList() { return {ge2gl_continue(h_)}; }
    Result<int32_t> setCallback(uint32_t signalFunc, uint32_t signalArg, uint32_t finishFunc, uint32_t finishArg) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_set_callback(h_, signalFunc, signalArg, finishFunc, finishArg, v); });
    }
    Status unsetCallback(int32_t cbid) { return {ge2gl_unset_callback(h_, cbid)}; }
    Result<std::array<uint32_t, 512>> saveContext() {
        return call<std::array<uint32_t, 512>>([&](std::array<uint32_t, 512>* v) { return ge2gl_save_context(h_, v->data()); });
    }
    Status restoreContext(const std::array<uint32_t, 512>& ctx) { return {ge2gl_restore_context(h_, ctx.data())}; }
    Result<uint32_t> getCmd(uint32_t op) {
        return call<uint32_t>([&](uint32_t* v) { return ge2gl_get_cmd(h_, op, v); });
    }
    Status setSdkVersion(uint32_t version) { return {ge2gl_set_sdk_version(h_, version)}; }
    Result<std::array<uint32_t, 256>> getRegisters() {
        return call<std::array<uint32_t, 256>>([&](std::array<uint32_t, 256>* v) { return ge2gl_get_registers(h_, v->data()); });
    }
    Result<int32_t> getStack(int32_t index, uint32_t out[8] = nullptr) {
        return call<int32_t>([&](int32_t* v) { return ge2gl_get_stack(h_, index, out, v); });
    }
    Result<std::vector<uint32_t>> getMatrix(int32_t type) {
        return call<std::vector<uint32_t>>([&](std::vector<uint32_t>* v) {
            uint32_t words[16] = {};
            int32_t n = 0;
            ge2gl_status s = ge2gl_get_matrix(h_, type, words, &n);
            if (s == GE2GL_OK) v->assign(words, words + n);
            return s;
        });
    }
    Result<uint32_t> setEdramTranslation(uint32_t value) {
        return call<uint32_t>([&](uint32_t* v) { return ge2gl_edram_set_translation(h_, value, v); });
    }

    // ---- debugger (docs/debugger.md) ----
    Status debugBreakNext(uint32_t flags) { return {ge2gl_debug_break_next(h_, flags)}; }
    Status debugBreakOpcode(uint32_t op, bool on = true) { return {ge2gl_debug_break_opcode(h_, op, on ? 1 : 0)}; }
    Status debugBreakAddress(uint32_t addr, bool on = true) { return {ge2gl_debug_break_address(h_, addr, on ? 1 : 0)}; }
    Status debugClearBreaks() { return {ge2gl_debug_clear_breaks(h_)}; }
    Result<ge2gl_run_info> debugStep(int32_t what) {
        return call<ge2gl_run_info>([&](ge2gl_run_info* v) { return ge2gl_debug_step(h_, what, v); });
    }
    // GE2GL_DEBUG_STATE / LIST / DISASM / REASON.
    Result<std::string> debugText(int32_t what) {
        return call<std::string>([&](std::string* v) {
            size_t need = 0;
            ge2gl_status s = ge2gl_debug_text(h_, what, nullptr, 0, &need);
            if (s != GE2GL_OK) return s;
            std::vector<char> buf(need);
            s = ge2gl_debug_text(h_, what, buf.data(), buf.size(), nullptr);
            if (s == GE2GL_OK) v->assign(buf.data());
            return s;
        });
    }
    Status debugSetRegister(uint32_t word) { return {ge2gl_debug_set_register(h_, word)}; }
    // GE2GL_DEBUG_COLOR (4 bytes a pixel), DEPTH (2), STENCIL (1).
    Result<std::vector<uint8_t>> debugReadBuffer(int32_t which, uint32_t width, uint32_t height) {
        return call<std::vector<uint8_t>>([&](std::vector<uint8_t>* v) {
            const size_t bpp = which == GE2GL_DEBUG_COLOR ? 4 : which == GE2GL_DEBUG_DEPTH ? 2 : 1;
            v->assign(size_t(width) * height * bpp, 0);
            return ge2gl_debug_read_buffer(h_, which, width, height, v->data(), v->size());
        });
    }
    // RGBA8888 texels of a level; width and height through the out-parameters.
    Result<std::vector<uint8_t>> debugReadTexture(int32_t level, uint32_t& width, uint32_t& height) {
        return call<std::vector<uint8_t>>([&](std::vector<uint8_t>* v) {
            ge2gl_status s = ge2gl_debug_read_texture(h_, level, &width, &height, nullptr, 0);
            if (s != GE2GL_OK) return s;
            v->assign(size_t(width) * height * 4, 0);
            return ge2gl_debug_read_texture(h_, level, &width, &height, v->data(), v->size());
        });
    }
    Result<std::vector<uint32_t>> debugReadClut() {
        return call<std::vector<uint32_t>>([&](std::vector<uint32_t>* v) {
            v->assign(512, 0);
            uint32_t n = 0;
            ge2gl_status s = ge2gl_debug_read_clut(h_, v->data(), uint32_t(v->size()), &n);
            v->resize(s == GE2GL_OK ? n : 0);
            return s;
        });
    }
    Result<std::vector<ge2gl_debug_vertex>> debugVertices() {
        return call<std::vector<ge2gl_debug_vertex>>([&](std::vector<ge2gl_debug_vertex>* v) {
            uint32_t n = 0;
            ge2gl_status s = ge2gl_debug_vertices(h_, nullptr, 0, &n);
            if (s != GE2GL_OK) return s;
            v->resize(n);
            return ge2gl_debug_vertices(h_, v->data(), n, &n);
        });
    }

    // ---- save states (docs/savestate.md) ----
    // The blob, copied out of ge2gl's buffer. flags: GE2GL_STATE_WITH_MEMORY or 0.
    Result<std::vector<uint8_t>> saveState(uint32_t flags = 0) {
        return call<std::vector<uint8_t>>([&](std::vector<uint8_t>* v) {
            const void* data = nullptr;
            size_t size = 0;
            ge2gl_status s = ge2gl_state_save(h_, flags, &data, &size);
            if (s == GE2GL_OK) v->assign(static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
            return s;
        });
    }
    Status loadState(const std::vector<uint8_t>& blob) { return {ge2gl_state_load(h_, blob.data(), blob.size())}; }

    // ---- execution and frames ----
    Result<ge2gl_run_info> run(uint64_t maxCommands) {
        return call<ge2gl_run_info>([&](ge2gl_run_info* v) { return ge2gl_run(h_, maxCommands, v); });
    }
    Status interruptAck() { return {ge2gl_interrupt_ack(h_)}; }
    Result<ge2gl_display> replayDump(const char* path) {
        return call<ge2gl_display>([&](ge2gl_display* v) { return ge2gl_replay_dump(h_, path, v); });
    }
    // Frame-dump recording (API 1.3; ge2gl.h "Frame-dump recording").
    Status recordBegin(const char* path) { return {ge2gl_record_begin(h_, path)}; }
    Status recordDisplay(uint32_t addr, uint32_t stride, int32_t format) {
        return {ge2gl_record_display(h_, addr, stride, format)};
    }
    Status recordEnd() { return {ge2gl_record_end(h_)}; }
    Result<std::vector<uint8_t>> readFrame(uint32_t addr, uint32_t stride, int32_t format, uint32_t width, uint32_t height) {
        return call<std::vector<uint8_t>>([&](std::vector<uint8_t>* v) {
            v->assign(size_t(width) * height * 4, 0);
            return ge2gl_read_frame(h_, addr, stride, format, width, height, v->data(), v->size());
        });
    }
    Result<uint32_t> frameTexture(uint32_t addr, uint32_t stride, int32_t format, uint32_t width, uint32_t height) {
        return call<uint32_t>([&](uint32_t* v) { return ge2gl_frame_texture(h_, addr, stride, format, width, height, v); });
    }
    Result<uint32_t> frameTexture(uint32_t addr, uint32_t stride, int32_t format, uint32_t width, uint32_t height,
                                  uint32_t outWidth, uint32_t outHeight) {
        return call<uint32_t>([&](uint32_t* v) {
            return ge2gl_frame_texture_sized(h_, addr, stride, format, width, height, outWidth, outHeight, v);
        });
    }

private:
    struct CallbackState {
        Callbacks fn;
        unsigned failures = 0;
    };

    template <class T, class F>
    Result<T> call(F&& f) {
        Result<T> r;
        r.status.code = f(&r.value);
        if (!r.ok()) r.message = lastMessage();
        return r;
    }

    // Trampolines: never let an exception unwind into C.
    template <class F>
    static void guard(void* user, F&& f) noexcept {
        auto* st = static_cast<CallbackState*>(user);
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
        try {
            f(st->fn);
        } catch (...) {
            ++st->failures;
        }
#else
        f(st->fn);
#endif
    }
    static void onSignal(void* u, const ge2gl_interrupt* i) { guard(u, [&](Callbacks& c) { c.signal(*i); }); }
    static void onFinish(void* u, const ge2gl_interrupt* i) { guard(u, [&](Callbacks& c) { c.finish(*i); }); }
    static void onEnd(void* u, int32_t id, uint32_t pc) { guard(u, [&](Callbacks& c) { c.end(id, pc); }); }
    static void onError(void* u, int32_t id, uint32_t pc, const char* m) { guard(u, [&](Callbacks& c) { c.error(id, pc, m); }); }
    static void onProgress(void* u, int32_t id, uint32_t pc) { guard(u, [&](Callbacks& c) { c.progress(id, pc); }); }
    static void onVramDirty(void* u, uint32_t a, uint32_t n) { guard(u, [&](Callbacks& c) { c.vramDirty(a, n); }); }

    ge2gl_context* h_ = nullptr;
    std::unique_ptr<CallbackState> cb_;
};

}  // namespace ge2gl
