// SPDX-License-Identifier: MIT
// The GE debugger through the C ABI (include/ge2gl/ge2gl.h "Debugger",
// docs/debugger.md): stepping draw by draw through the five scenes (replayed the way an emulator
// drives the GE) reaches FINISH with the uninterrupted picture on both backends, every stop is
// before a draw whose vertices can be read; breakpoints on opcodes, addresses, lists and frames
// stop where they say; texture, CLUT, buffer and register read-outs return what was sent.
#include "tests/savestate_switch.h"

using namespace savestate_test;

namespace {

// The player's calls on one handle; every run goes draw by draw with ge2gl_debug_step.
class SteppingTarget : public dump::ReplayTarget {
public:
    explicit SteppingTarget(int backend) { h_ = createHandle(backend); }
    ~SteppingTarget() override { ge2gl_destroy(h_); }
    ge2gl_context* handle() const { return h_; }
    u64 stops = 0, primStops = 0;
    std::string failure;

    u32 ramSize() const override { return probe_.ramSize(); }
    u32 write(u32 addr, const void* data, u32 size) override {
        const u32 n = probe_.validSize(addr, size);
        if (n) ge2gl_mem_write(h_, addr, data, n);
        return n;
    }
    u32 fill(u32 addr, u8 value, u32 size) override {
        const u32 n = probe_.validSize(addr, size);
        std::vector<u8> b(n, value);
        if (n) ge2gl_mem_write(h_, addr, b.data(), n);
        return n;
    }
    void loadContext(const u32 ctx[512]) override { ge2gl_restore_context(h_, ctx); }
    void startList(u32 pc, u32 stall) override { ge2gl_list_enqueue(h_, pc, stall, -1, nullptr, &id_); }
    RunStatus runTo(u32 stall, u64) override {
        ge2gl_list_update_stall(h_, id_, stall);
        ge2gl_run_info info{};
        for (;;) {
            if (ge2gl_debug_step(h_, GE2GL_STEP_DRAW, &info) != GE2GL_OK) {
                note(std::string("step: ") + ge2gl_last_message(h_));
                return RunStatus::Error;
            }
            if (info.ge_state != GE2GL_GE_BREAK) break;
            ++stops;
            checkStop(info);
        }
        switch (info.ge_state) {
        case GE2GL_GE_IDLE: return RunStatus::Completed;
        case GE2GL_GE_STALLED: return RunStatus::Stalled;
        case GE2GL_GE_READY: return RunStatus::Budget;
        default: return RunStatus::Ended;
        }
    }
    std::string lastError() override { return ge2gl_last_message(h_); }
    u32 readRegister(u8 op) override {
        uint32_t w = 0;
        ge2gl_get_cmd(h_, op, &w);
        return w;
    }
    bool setEdramTranslation(u32 v) override { return ge2gl_edram_set_translation(h_, v, nullptr) == GE2GL_OK; }
    void finishFrame() override {
        int32_t s = 0;
        ge2gl_draw_sync(h_, GE2GL_SYNC_WAIT, &s);
    }

private:
    void note(const std::string& s) {
        if (failure.empty()) failure = s;
    }
    // A stop is before a draw kick; a PRIM's vertices are there to read, as many as it draws.
    void checkStop(const ge2gl_run_info& info) {
        u32 word = 0;
        if (ge2gl_mem_read(h_, info.pc, &word, 4) != GE2GL_OK) return note("pc unreadable");
        const u32 op = word >> 24;
        if (op != 0x04 && op != 0x05 && op != 0x06) return note("a stop not before a draw");
        char reason[64];
        if (ge2gl_debug_text(h_, GE2GL_DEBUG_REASON, reason, sizeof reason, nullptr) != GE2GL_OK ||
            std::string(reason) != "next draw")
            return note(std::string("reason: ") + reason);
        if (op != 0x04) return;
        ++primStops;
        uint32_t n = 0;
        if (ge2gl_debug_vertices(h_, nullptr, 0, &n) != GE2GL_OK) return note(std::string("vertices: ") + ge2gl_last_message(h_));
        if (n != (word & 0xFFFF)) return note("vertex count is not the PRIM's");
    }

    Memory probe_;
    ge2gl_context* h_ = nullptr;
    int32_t id_ = -1;
};

TEST(Debugger, SteppingDrawByDrawReachesFinishWithTheSamePicture) {
    std::vector<int> backends = {GE2GL_BACKEND_SOFT};
    if (glAvailable()) backends.push_back(GE2GL_BACKEND_GL_HEADLESS);
    int scenes = 0;
    for (auto& e : fs::directory_iterator(fs::path(GE2GL_SOURCE_DIR) / "dumps")) {
        if (e.path().extension() != ".ppdmp") continue;
        ++scenes;
        dump::Dump d;
        std::string err;
        ASSERT_TRUE(dump::loadDump(e.path().string(), d, err)) << err;
        const u64 draws = dump::summarize(d).draws;
        for (int backend : backends) {
            SCOPED_TRACE(e.path().filename().string() + " backend " + std::to_string(backend));
            ge2gl_context* ref = createHandle(backend);
            ASSERT_NE(ref, nullptr);
            ge2gl_display disp{};
            ASSERT_EQ(ge2gl_replay_dump(ref, e.path().c_str(), &disp), GE2GL_OK) << ge2gl_last_message(ref);
            const std::vector<u8> want = readDisplayed(ref, disp);
            ge2gl_destroy(ref);

            SteppingTarget t(backend);
            dump::ReplayResult res;
            ASSERT_TRUE(dump::replayDump(d, t, {}, res, err)) << err;
            ASSERT_EQ(t.failure, "");
            EXPECT_EQ(t.stops, draws);  // one stop before every draw of the frame
            EXPECT_GT(t.primStops, 0u);
            const std::vector<u8> got = readDisplayed(t.handle(), disp);
            ASSERT_EQ(got.size(), want.size());
            size_t differing = 0;
            for (size_t i = 0; i < got.size(); i += 4) differing += std::memcmp(&got[i], &want[i], 3) != 0;
            EXPECT_EQ(differing, 0u);
        }
    }
    EXPECT_EQ(scenes, 5);
}

void put(ge2gl_context* h, uint32_t& at, uint32_t word) {
    ASSERT_EQ(ge2gl_mem_write(h, at, &word, 4), GE2GL_OK);
    at += 4;
}

// A list drawing two through-mode sprites: the first plain red over (0,0)-(8,8), the second
// textured with a 4x4 CLUT8 texture (palette: 4 entries) over (8,0)-(12,4); FINISH, END.
struct Scene {
    uint32_t list = 0x08100000, prim1 = 0, prim2 = 0, tex = 0x08110000, clut = 0x08110100, verts = 0x08110200;
};

Scene writeScene(ge2gl_context* h) {
    Scene s;
    const uint32_t pal[4] = {0xFF0000FFu, 0xFF00FF00u, 0xFFFF0000u, 0xFFFFFFFFu};
    EXPECT_EQ(ge2gl_mem_write(h, s.clut, pal, sizeof pal), GE2GL_OK);
    uint8_t texels[16];
    for (int i = 0; i < 16; ++i) texels[i] = uint8_t(i & 3);
    EXPECT_EQ(ge2gl_mem_write(h, s.tex, texels, sizeof texels), GE2GL_OK);
    // Sprite vertices: u16 u, v; u32 colour; s16 x, y, z (through mode, TC_16 | COL_8888 | POS_16).
    struct V {
        uint16_t u, v;
        uint32_t c;
        int16_t x, y, z, pad;
    };
    const V v[4] = {{0, 0, 0xFF0000FF, 0, 0, 0, 0}, {0, 0, 0xFF0000FF, 8, 8, 0, 0}, {0, 0, 0xFFFFFFFF, 8, 0, 0, 0}, {4, 4, 0xFFFFFFFF, 12, 4, 0, 0}};
    EXPECT_EQ(ge2gl_mem_write(h, s.verts, v, sizeof v), GE2GL_OK);
    uint32_t at = s.list;
    put(h, at, 0x9C000000);                       // FBP 0
    put(h, at, 0x9D000000 | 512);                 // FBW 512
    put(h, at, 0xD2000003);                       // FPF 8888
    put(h, at, 0x15000000);                       // REGION1 (0, 0)
    put(h, at, 0x16000000 | 271 << 10 | 479);     // REGION2 (479, 271)
    put(h, at, 0xD4000000);                       // SCISSOR1
    put(h, at, 0xD5000000 | 271 << 10 | 479);     // SCISSOR2
    put(h, at, 0x12000000 | 1u << 23 | 7 << 2 | 2 << 7 | 2);  // VTYPE through, COL_8888, POS_16, TC_16
    put(h, at, 0x10000000 | ((s.verts >> 8) & 0xF0000));    // BASE
    put(h, at, 0x01000000 | (s.verts & 0xFFFFFF));          // VADR
    s.prim1 = at;
    put(h, at, 0x04000000 | 6 << 16 | 2);         // PRIM rectangles, 2
    put(h, at, 0x1E000001);                       // TME on
    put(h, at, 0xC3000005);                       // TPF CLUT8
    put(h, at, 0xA0000000 | (s.tex & 0xFFFFFF));  // TBP0
    put(h, at, 0xA8000000 | (s.tex >> 8 & 0xF0000) | 16);  // TBW0 16, high byte
    put(h, at, 0xB8000000 | 2 << 8 | 2);          // TSIZE0 4x4
    put(h, at, 0xC5000003 | 0xFF << 8);           // CLUT 8888, mask 0xff
    put(h, at, 0xB0000000 | (s.clut & 0xFFFFFF)); // CBP
    put(h, at, 0xB1000000 | (s.clut >> 8 & 0xF0000));  // CBW (high byte)
    put(h, at, 0xC4000001);                       // CLOAD 1 block (8 entries of 32 bits)
    put(h, at, 0xC9000001);                       // TFUNC replace, RGBA
    s.prim2 = at;
    put(h, at, 0x04000000 | 6 << 16 | 2);         // PRIM rectangles, 2
    put(h, at, 0x0F000000);                       // FINISH
    put(h, at, 0x0C000000);                       // END
    return s;
}

TEST(Debugger, BreakpointsStopWhereTheySayAndReadOutsHoldWhatWasSent) {
    ge2gl_context* h = createHandle(GE2GL_BACKEND_SOFT);
    ASSERT_NE(h, nullptr);
    const Scene s = writeScene(h);
    ASSERT_EQ(ge2gl_debug_break_opcode(h, 0x04, 1), GE2GL_OK);  // every PRIM
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(h, s.list, 0, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    ASSERT_EQ(info.ge_state, GE2GL_GE_BREAK);
    EXPECT_EQ(info.pc, s.prim1);
    char text[8192];
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_REASON, text, sizeof text, nullptr), GE2GL_OK);
    EXPECT_STREQ(text, "opcode PRIM");
    // The first sprite's vertices, before and after transform.
    ge2gl_debug_vertex v[4];
    uint32_t n = 0;
    ASSERT_EQ(ge2gl_debug_vertices(h, v, 4, &n), GE2GL_OK) << ge2gl_last_message(h);
    ASSERT_EQ(n, 2u);
    EXPECT_EQ(v[1].pos[0], 8.0f);
    EXPECT_EQ(v[1].screen_x, 8.0f);
    EXPECT_EQ(v[1].screen_y, 8.0f);
    EXPECT_EQ(v[0].color[0], 0xFF);
    EXPECT_EQ(v[0].color[2], 0x00);
    // Nothing drawn yet.
    std::vector<uint8_t> px(16 * 16 * 4);
    ASSERT_EQ(ge2gl_debug_read_buffer(h, GE2GL_DEBUG_COLOR, 16, 16, px.data(), px.size()), GE2GL_OK);
    EXPECT_EQ(px[0], 0);
    // A poke before the draw: FPF stays 8888, but the sprite's region is cut by a scissor of 4x4.
    ASSERT_EQ(ge2gl_debug_set_register(h, 0xD5000000 | 3 << 10 | 3), GE2GL_OK);
    uint32_t w = 0;
    ASSERT_EQ(ge2gl_get_cmd(h, 0xD5, &w), GE2GL_OK);
    EXPECT_EQ(w, 0xD5000000u | 3 << 10 | 3);
    EXPECT_EQ(ge2gl_debug_set_register(h, 0x04000000), GE2GL_ERR_INVALID_ARGUMENT);  // a PRIM is no poke

    // Step one command: the PRIM draws, the stop is before the next command.
    ASSERT_EQ(ge2gl_debug_step(h, GE2GL_STEP_COMMAND, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_BREAK);
    EXPECT_EQ(info.pc, s.prim1 + 4);
    ASSERT_EQ(ge2gl_debug_read_buffer(h, GE2GL_DEBUG_COLOR, 16, 16, px.data(), px.size()), GE2GL_OK);
    EXPECT_EQ(px[0], 0xFF);                      // (0, 0) red
    EXPECT_EQ(px[(3 * 16 + 3) * 4], 0xFF);       // (3, 3) inside the poked scissor
    EXPECT_EQ(px[(5 * 16 + 5) * 4], 0x00);       // (5, 5) cut by it
    ASSERT_EQ(ge2gl_debug_set_register(h, 0xD5000000 | 271 << 10 | 479), GE2GL_OK);

    // Run to the second PRIM: the texture and CLUT are bound and loaded.
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    ASSERT_EQ(info.ge_state, GE2GL_GE_BREAK);
    EXPECT_EQ(info.pc, s.prim2);
    uint32_t tw = 0, th = 0;
    ASSERT_EQ(ge2gl_debug_read_texture(h, 0, &tw, &th, nullptr, 0), GE2GL_OK);
    ASSERT_EQ(tw, 4u);
    ASSERT_EQ(th, 4u);
    std::vector<uint8_t> tex(4 * 4 * 4);
    ASSERT_EQ(ge2gl_debug_read_texture(h, 0, &tw, &th, tex.data(), tex.size()), GE2GL_OK) << ge2gl_last_message(h);
    // Texel (1, 0) is index 1: green; texel (2, 0) index 2: blue.
    EXPECT_EQ(tex[4 * 1 + 1], 0xFF);
    EXPECT_EQ(tex[4 * 1 + 0], 0x00);
    EXPECT_EQ(tex[4 * 2 + 2], 0xFF);
    uint32_t pal[256];
    ASSERT_EQ(ge2gl_debug_read_clut(h, pal, 256, &n), GE2GL_OK);
    EXPECT_EQ(n, 256u);
    EXPECT_EQ(pal[0], 0xFF0000FFu);
    EXPECT_EQ(pal[3], 0xFFFFFFFFu);
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_DISASM, text, sizeof text, nullptr), GE2GL_OK);
    EXPECT_NE(std::string(text).find("> 0x08100054: 04060002  PRIM"), std::string::npos) << text;
    size_t need = 0;
    EXPECT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_STATE, text, 16, &need), GE2GL_ERR_INVALID_ARGUMENT);  // too small
    std::vector<char> big(need);
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_STATE, big.data(), big.size(), nullptr), GE2GL_OK);
    EXPECT_NE(std::string(big.data()).find("0xc3 TPF      000005"), std::string::npos);
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_LIST, text, sizeof text, nullptr), GE2GL_OK);
    EXPECT_NE(std::string(text).find("pc 0x08100054"), std::string::npos) << text;

    // Clear the breakpoints and continue to FINISH: the textured sprite is drawn.
    ASSERT_EQ(ge2gl_debug_clear_breaks(h), GE2GL_OK);
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_IDLE);
    ASSERT_EQ(ge2gl_debug_read_buffer(h, GE2GL_DEBUG_COLOR, 16, 16, px.data(), px.size()), GE2GL_OK);
    EXPECT_EQ(px[(0 * 16 + 9) * 4 + 1], 0xFF);  // (9, 0): texel 1, green
    EXPECT_EQ(px[(0 * 16 + 10) * 4 + 2], 0xFF); // (10, 0): texel 2, blue

    // Address, list and frame breaks on the same list queued again.
    ASSERT_EQ(ge2gl_debug_break_address(h, s.prim2, 1), GE2GL_OK);
    ASSERT_EQ(ge2gl_debug_break_next(h, GE2GL_BREAK_NEXT_FRAME), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_enqueue(h, s.list, 0, -1, nullptr, &id), GE2GL_OK);
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_BREAK);
    EXPECT_EQ(info.pc, s.list);  // the frame's first command
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_REASON, text, sizeof text, nullptr), GE2GL_OK);
    EXPECT_STREQ(text, "next frame");
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_BREAK);
    EXPECT_EQ(info.pc, s.prim2);
    ASSERT_EQ(ge2gl_debug_text(h, GE2GL_DEBUG_REASON, text, sizeof text, nullptr), GE2GL_OK);
    EXPECT_STREQ(text, "address 0x08100054");
    ASSERT_EQ(ge2gl_debug_break_address(h, s.prim2, 0), GE2GL_OK);
    ASSERT_EQ(ge2gl_debug_break_next(h, GE2GL_BREAK_NEXT_LIST), GE2GL_OK);
    ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
    EXPECT_EQ(info.ge_state, GE2GL_GE_IDLE);  // no other list: no stop
    // Bad arguments.
    EXPECT_EQ(ge2gl_debug_break_next(h, 64), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_debug_break_opcode(h, 256, 1), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_debug_break_address(h, 0x08100002, 1), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_debug_step(h, 7, &info), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_debug_read_buffer(h, 9, 4, 4, px.data(), px.size()), GE2GL_ERR_INVALID_ARGUMENT);
    ge2gl_destroy(h);
}

}  // namespace
