// SPDX-License-Identifier: MIT
// The GE debugger through the C ABI (include/ge2gl/ge2gl.h "Debugger", docs/debugger.md): stops
// and steps on ge::debug::Breakpoints observing the handle's engine, and read-outs of
// debugger/debugger.h. The breakpoints are made at the first debugger call, so a host that never
// debugs pays nothing per command.
#include "api/context.h"

#include <cstring>

using namespace ge2gl_impl;

namespace {

ge::debug::Breakpoints& breakpoints(ge2gl_context* h) {
    if (!h->debugger) {
        h->debugger = std::make_unique<ge::debug::Breakpoints>([h] { return h->sce->currentListId(); });
        h->engine->addObserver(h->debugger.get());
    }
    return *h->debugger;
}

// Copies text with its NUL, or says how much room it needs.
ge2gl_status putText(Call& c, const std::string& text, char* buf, size_t size, size_t* needed) {
    if (needed) *needed = text.size() + 1;
    if (!buf) return needed ? GE2GL_OK : c.error(GE2GL_ERR_INVALID_ARGUMENT, "buf and needed are NULL");
    if (size < text.size() + 1) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "buffer too small: " + std::to_string(text.size() + 1) + " bytes needed");
    std::memcpy(buf, text.c_str(), text.size() + 1);
    return GE2GL_OK;
}

// Opcodes a register poke may not send: they draw, jump, end lists, transfer or load.
bool refusedPoke(ge::u8 op) {
    using namespace ge;
    switch (op) {
    case GE_CMD_PRIM: case GE_CMD_BEZIER: case GE_CMD_SPLINE: case GE_CMD_BBOX: case GE_CMD_JUMP: case GE_CMD_BJUMP:
    case GE_CMD_CALL: case GE_CMD_RET: case GE_CMD_END: case GE_CMD_SIGNAL: case GE_CMD_FINISH: case GE_CMD_XSTART:
    case GE_CMD_CLOAD: case GE_CMD_TFLUSH: case GE_CMD_TSYNC: return true;
    default: return op >= GE_CMD_X2 && op <= GE_CMD_I2;  // immediate-mode vertices (AP2 kicks a draw)
    }
}

// What was drawn so far, in guest memory (GL backends write their render targets back).
ge2gl_status syncPixels(ge2gl_context* h, Call& c) {
    if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
    h->engine->renderer()->flushToMemory();
    return GE2GL_OK;
}

}  // namespace

extern "C" {

ge2gl_status ge2gl_debug_break_next(ge2gl_context* h, uint32_t flags) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (flags & ~31u) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown break flags");
        breakpoints(h).breakOnce(flags);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_break_opcode(ge2gl_context* h, uint32_t op, int32_t on) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (op > 255) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "opcode beyond 255");
        breakpoints(h).setOpcode(ge::u8(op), on != 0);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_break_address(ge2gl_context* h, uint32_t addr, int32_t on) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (addr & 3) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "a command address is word-aligned");
        breakpoints(h).setAddress(addr, on != 0);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_clear_breaks(ge2gl_context* h) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (h->debugger) h->debugger->clearAll();
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_step(ge2gl_context* h, int32_t what, ge2gl_run_info* out) {
    return guarded(h, [&]() -> ge2gl_status {
        {
            Call c(h);
            if (what != GE2GL_STEP_COMMAND && what != GE2GL_STEP_DRAW) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown step");
            breakpoints(h).breakOnce(what == GE2GL_STEP_COMMAND ? ge::debug::kNextCommand : ge::debug::kNextDraw);
        }
        return runFor(h, h->waitBudget, ~uint64_t(0), out);
    });
}

ge2gl_status ge2gl_debug_text(ge2gl_context* h, int32_t what, char* buf, size_t size, size_t* needed) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        const ge::GeEngine& e = *h->engine;
        switch (what) {
        case GE2GL_DEBUG_STATE: return putText(c, ge::debug::stateText(e.state()), buf, size, needed);
        case GE2GL_DEBUG_LIST: {
            const ge::s32 id = h->sce->currentListId();
            std::string t = id < 0 ? std::string("no list queued\n") : "list 0x" + [&] {
                char b[16];
                std::snprintf(b, sizeof b, "%08x", ge::u32(id));
                return std::string(b);
            }() + "\n" + ge::debug::listText(e.list(), e.state());
            return putText(c, t, buf, size, needed);
        }
        case GE2GL_DEBUG_DISASM: {
            const ge::u32 pc = e.list().pc;
            return putText(c, ge::debug::disassembly(h->engine->memory(), pc - 16, 16, pc), buf, size, needed);
        }
        case GE2GL_DEBUG_REASON: return putText(c, h->debugger ? h->debugger->reason() : std::string(), buf, size, needed);
        default: return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown text kind");
        }
    });
}

ge2gl_status ge2gl_debug_set_register(ge2gl_context* h, uint32_t word) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        const ge::u8 op = ge::u8(word >> 24);
        if (refusedPoke(op)) return c.error(GE2GL_ERR_INVALID_ARGUMENT, std::string("a poke cannot send ") + ge::geCmdName(op));
        if (refuseMidRunCommand(h)) return c.error(GE2GL_ERR_REENTRANT, "not from inside a callback");
        if (ge2gl_status s = c.gl(); s != GE2GL_OK) return s;
        // As if the list sent it: matrix data uploads, address registers and dirty state follow.
        h->engine->execute(word);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_read_buffer(ge2gl_context* h, int32_t which, uint32_t width, uint32_t height, void* out,
                                     size_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out || width == 0 || height == 0 || width > 1024 || height > 1024)
            return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is NULL or the size is not 1-1024");
        const size_t bpp = which == GE2GL_DEBUG_COLOR ? 4 : which == GE2GL_DEBUG_DEPTH ? 2 : which == GE2GL_DEBUG_STENCIL ? 1 : 0;
        if (!bpp) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "unknown buffer");
        if (size < size_t(width) * height * bpp) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is too small");
        if (refuseMidRunCommand(h)) return c.error(GE2GL_ERR_REENTRANT, "not from inside a callback");
        if (ge2gl_status s = syncPixels(h, c); s != GE2GL_OK) return s;
        const ge::Memory& mem = *h->mem;
        const ge::GeState& st = h->engine->state();
        bool ok = false;
        if (which == GE2GL_DEBUG_COLOR) {
            std::vector<ge::u8> v;
            ok = ge::debug::readColor(mem, st, width, height, v);
            if (ok) std::memcpy(out, v.data(), v.size());
        } else if (which == GE2GL_DEBUG_DEPTH) {
            std::vector<ge::u16> v;
            ok = ge::debug::readDepth(mem, st, width, height, v);
            if (ok) std::memcpy(out, v.data(), v.size() * 2);
        } else {
            std::vector<ge::u8> v;
            ok = ge::debug::readStencil(mem, st, width, height, v);
            if (ok) std::memcpy(out, v.data(), v.size());
        }
        return ok ? GE2GL_OK : c.error(GE2GL_ERR_MEMORY, "the buffer lies outside VRAM at that size");
    });
}

ge2gl_status ge2gl_debug_read_texture(ge2gl_context* h, int32_t level, uint32_t* out_w, uint32_t* out_h, uint8_t* out,
                                      size_t size) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_w || !out_h || level < 0 || level > 7) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "no size pointers or level not 0-7");
        const ge::GeState& st = h->engine->state();
        *out_w = st.textureWidth(level);
        *out_h = st.textureHeight(level);
        if (!out) return GE2GL_OK;
        if (size < size_t(*out_w) * *out_h * 4) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out is too small");
        if (refuseMidRunCommand(h)) return c.error(GE2GL_ERR_REENTRANT, "not from inside a callback");
        if (ge2gl_status s = syncPixels(h, c); s != GE2GL_OK) return s;  // a texture may be a render target
        ge::u32 w = 0, hh = 0;
        std::vector<ge::u8> v;
        if (!ge::debug::readTexture(*h->mem, st, level, w, hh, v)) return c.error(GE2GL_ERR_MEMORY, "the texture lies outside memory");
        std::memcpy(out, v.data(), v.size());
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_read_clut(ge2gl_context* h, uint32_t* out, uint32_t capacity, uint32_t* out_count) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_count) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_count is NULL");
        const std::vector<ge::u32> pal = ge::debug::readClut(h->engine->state());
        *out_count = uint32_t(pal.size());
        if (!out) return GE2GL_OK;
        if (capacity < pal.size()) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out holds fewer entries than the CLUT");
        std::memcpy(out, pal.data(), pal.size() * 4);
        return GE2GL_OK;
    });
}

ge2gl_status ge2gl_debug_vertices(ge2gl_context* h, ge2gl_debug_vertex* out, uint32_t capacity, uint32_t* out_count) {
    return guarded(h, [&]() -> ge2gl_status {
        Call c(h);
        if (!out_count) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out_count is NULL");
        const ge::u8* p = h->mem->ptr(h->engine->list().pc, 4);
        if (!p) return c.error(GE2GL_ERR_BAD_STATE, "the pc is outside memory");
        if (ge2gl_status s = syncPixels(h, c); s != GE2GL_OK) return s;  // vertices the GPU wrote are rare, but in memory
        std::vector<ge::debug::DrawVertex> v;
        std::string err;
        if (!ge::debug::drawVertices(*h->mem, h->engine->state(), ge::readLE32(p), h->accuracy, v, err))
            return c.error(GE2GL_ERR_BAD_STATE, "no vertices: " + err);
        *out_count = uint32_t(v.size());
        if (!out) return GE2GL_OK;
        if (capacity < v.size()) return c.error(GE2GL_ERR_INVALID_ARGUMENT, "out holds fewer vertices than the draw");
        for (size_t i = 0; i < v.size(); ++i) {
            ge2gl_debug_vertex& o = out[i];
            o = {};
            std::memcpy(o.pos, v[i].in.pos, sizeof o.pos);
            std::memcpy(o.uv, v[i].in.uv, sizeof o.uv);
            std::memcpy(o.normal, v[i].in.nrm, sizeof o.normal);
            std::memcpy(o.color, v[i].in.color, 4);
            o.screen_x = v[i].screenX;
            o.screen_y = v[i].screenY;
            o.screen_z = v[i].screenZ;
            o.s = v[i].s, o.t = v[i].t, o.q = v[i].q;
            std::memcpy(o.lit_color, v[i].color, 4);
            o.outside = v[i].outside ? 1 : 0;
        }
        return GE2GL_OK;
    });
}

}  // extern "C"
