// SPDX-License-Identifier: MIT
// Whole-GE save states through the C ABI (include/ge2gl/ge2gl.h "Save states",
// docs/savestate.md). A dump is replayed the way an emulator drives the GE (memory writes,
// enqueue, stall updates, runs); every 100 commands the state is saved (with guest memory) and
// loaded into a fresh instance of the other backend, which goes on with the frame. The finished
// frame must equal an uninterrupted replay on the software backend, pixel for pixel; and a state
// saved again right after a load must be the same bytes.
#include "tests/savestate_switch.h"

#include <xxhash.h>

using namespace savestate_test;

namespace {

class SaveStateSwitch : public ::testing::Test {
protected:
    void SetUp() override {
        if (!glAvailable()) GTEST_SKIP() << "GL backend unavailable: " << ge2gl_last_message(nullptr);
    }
};

// One test per first backend, so that ctest runs the two side by side.
void projectScenesFrom(int firstBackend) {
    int scenes = 0;
    for (auto& e : fs::directory_iterator(fs::path(GE2GL_SOURCE_DIR) / "dumps")) {
        if (e.path().extension() != ".ppdmp") continue;
        ++scenes;
        checkDump(e.path(), firstBackend);
    }
    EXPECT_EQ(scenes, 5);
}

TEST_F(SaveStateSwitch, ProjectScenesEveryHundredCommandsStartingOnSoft) { projectScenesFrom(GE2GL_BACKEND_SOFT); }
TEST_F(SaveStateSwitch, ProjectScenesEveryHundredCommandsStartingOnGl) { projectScenesFrom(GE2GL_BACKEND_GL_HEADLESS); }

// ---- A list stalled mid-way with an interrupt held, moved between backends ----------------

struct Irqs {
    int signals = 0, finishes = 0;
    ge2gl_context* saveFrom = nullptr;  // a save tried from inside the callback
    ge2gl_status saveInCallback = GE2GL_OK;
};

ge2gl_context* createHeld(int backend, Irqs& irqs) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = backend;
    cfg.hold_interrupts = 1;
    cfg.callbacks.user = &irqs;
    cfg.callbacks.signal = [](void* u, const ge2gl_interrupt*) {
        auto* q = static_cast<Irqs*>(u);
        ++q->signals;
        if (q->saveFrom) {
            const void* d = nullptr;
            size_t n = 0;
            q->saveInCallback = ge2gl_state_save(q->saveFrom, 0, &d, &n);
        }
    };
    cfg.callbacks.finish = [](void* u, const ge2gl_interrupt*) { ++static_cast<Irqs*>(u)->finishes; };
    ge2gl_context* h = nullptr;
    return ge2gl_create(&cfg, &h) == GE2GL_OK ? h : nullptr;
}

void put(ge2gl_context* h, uint32_t& at, uint32_t op, uint32_t arg) {
    const uint32_t w = op << 24 | (arg & 0xFFFFFF);
    ASSERT_EQ(ge2gl_mem_write(h, at, &w, 4), GE2GL_OK);
    at += 4;
}

// A list: two register writes, SIGNAL (behaviour 2, continue) + END, a stall point, a CALL into a
// sub-list that sets a third register, FINISH + END.
uint32_t writeHeldList(ge2gl_context* h, uint32_t& stallAt) {
    const uint32_t list = 0x08100000, sub = 0x08100800;
    uint32_t at = list;
    put(h, at, 0x98, 0x000123);    // TBP0 (any register the GE keeps)
    put(h, at, 0xD5, 0x000456);    // CBP
    put(h, at, 0x0E, 0x02 << 16 | 0x77);  // SIGNAL continue, arg 0x77
    put(h, at, 0x0C, 0);           // END
    stallAt = at;
    put(h, at, 0x10, (sub >> 8) & 0x0F0000);  // BASE
    put(h, at, 0x0A, sub & 0xFFFFFF);          // CALL
    put(h, at, 0x0F, 0);           // FINISH
    put(h, at, 0x0C, 0);
    uint32_t s = sub;
    put(h, s, 0xD6, 0x000789);     // CBW... any register: CBW
    put(h, s, 0x0B, 0);            // RET
    return list;
}

TEST(SaveState, StalledListWithAHeldInterruptMovesToTheOtherBackend) {
    const bool gl = glAvailable();
    for (int target : {GE2GL_BACKEND_SOFT, gl ? GE2GL_BACKEND_GL_HEADLESS : GE2GL_BACKEND_SOFT}) {
        SCOPED_TRACE(target);
        Irqs a, b;
        ge2gl_context* h = createHeld(GE2GL_BACKEND_SOFT, a);
        ASSERT_NE(h, nullptr);
        uint32_t stallAt = 0;
        const uint32_t list = writeHeldList(h, stallAt);
        int32_t id = -1;
        ASSERT_EQ(ge2gl_list_enqueue(h, list, stallAt, -1, nullptr, &id), GE2GL_OK);
        ge2gl_run_info info{};
        a.saveFrom = h;
        ASSERT_EQ(ge2gl_run(h, 1000, &info), GE2GL_OK);
        EXPECT_EQ(a.saveInCallback, GE2GL_ERR_REENTRANT);  // not from inside a callback
        ASSERT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);
        ASSERT_EQ(a.signals, 1);

        const void* data = nullptr;
        size_t size = 0;
        ASSERT_EQ(ge2gl_state_save(h, GE2GL_STATE_WITH_MEMORY, &data, &size), GE2GL_OK) << ge2gl_last_message(h);
        const std::vector<uint8_t> blob(static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
        ge2gl_destroy(h);

        ge2gl_context* g = createHeld(target, b);
        ASSERT_NE(g, nullptr);
        ASSERT_EQ(ge2gl_state_load(g, blob.data(), blob.size()), GE2GL_OK) << ge2gl_last_message(g);
        // The interrupt is still held: nothing runs until the host acknowledges it.
        ASSERT_EQ(ge2gl_run(g, 1000, &info), GE2GL_OK);
        EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);
        EXPECT_EQ(info.commands, 0u);
        ASSERT_EQ(ge2gl_interrupt_ack(g), GE2GL_OK);
        ASSERT_EQ(ge2gl_run(g, 1000, &info), GE2GL_OK);
        EXPECT_EQ(info.ge_state, GE2GL_GE_STALLED);
        EXPECT_EQ(info.list_id, id);  // the same list ID on the new instance
        EXPECT_EQ(info.pc, stallAt);
        int32_t st = -1;
        ASSERT_EQ(ge2gl_list_sync(g, id, GE2GL_SYNC_PEEK, &st), GE2GL_OK);
        EXPECT_EQ(st, GE2GL_LIST_STALLING);
        uint32_t w = 0;
        ASSERT_EQ(ge2gl_get_cmd(g, 0x98, &w), GE2GL_OK);
        EXPECT_EQ(w, 0x98000123u);
        // The rest of the list, with its CALL, runs on the new instance.
        ASSERT_EQ(ge2gl_list_update_stall(g, id, 0), GE2GL_OK);
        ASSERT_EQ(ge2gl_run(g, 1000, &info), GE2GL_OK);
        EXPECT_EQ(info.ge_state, GE2GL_GE_INTERRUPT);  // the finish interrupt, held
        EXPECT_EQ(b.finishes, 1);
        EXPECT_EQ(b.signals, 0);  // the signal was delivered before the save, not again
        ASSERT_EQ(ge2gl_get_cmd(g, 0xD6, &w), GE2GL_OK);
        EXPECT_EQ(w, 0xD6000789u);
        ASSERT_EQ(ge2gl_interrupt_ack(g), GE2GL_OK);
        ASSERT_EQ(ge2gl_list_sync(g, id, GE2GL_SYNC_PEEK, &st), GE2GL_OK);
        EXPECT_EQ(st, GE2GL_LIST_COMPLETED);
        ge2gl_destroy(g);
    }
}

// ---- Corrupt and foreign blobs ------------------------------------------------------------

// Re-signs a blob whose payload was edited (header: magic 8, version 4, flags 4, size 8, hash 8).
void resign(std::vector<uint8_t>& b) {
    const uint64_t hsh = XXH64(b.data() + 32, b.size() - 32, 0);
    for (int i = 0; i < 8; ++i) b[24 + size_t(i)] = uint8_t(hsh >> (8 * i));
}

std::vector<uint8_t> saveBytes(ge2gl_context* h, uint32_t flags) {
    const void* d = nullptr;
    size_t n = 0;
    if (ge2gl_state_save(h, flags, &d, &n) != GE2GL_OK) return {};
    return {static_cast<const uint8_t*>(d), static_cast<const uint8_t*>(d) + n};
}

TEST(SaveState, CorruptOrForeignBlobsAreRefusedAndChangeNothing) {
    ge2gl_context* h = createHandle(GE2GL_BACKEND_SOFT);
    ASSERT_NE(h, nullptr);
    // Some state to lose: a list stalled at its start, registers set.
    uint32_t at = 0x08000100;
    put(h, at, 0x98, 0x000ABC);
    put(h, at, 0x0F, 0);
    put(h, at, 0x0C, 0);
    int32_t id = -1;
    ASSERT_EQ(ge2gl_list_enqueue(h, 0x08000100, 0x08000104, -1, nullptr, &id), GE2GL_OK);
    ge2gl_run_info info{};
    ASSERT_EQ(ge2gl_run(h, 100, &info), GE2GL_OK);
    ASSERT_EQ(info.ge_state, GE2GL_GE_STALLED);
    const std::vector<uint8_t> good = saveBytes(h, 0);
    ASSERT_GT(good.size(), 32u);

    // A different GE state to load the bad blobs into; it must stay as it is.
    ge2gl_context* other = createHandle(GE2GL_BACKEND_SOFT);
    ASSERT_NE(other, nullptr);
    const std::vector<uint8_t> before = saveBytes(other, 0);
    auto refused = [&](std::vector<uint8_t> b, const char* why) {
        SCOPED_TRACE(why);
        EXPECT_EQ(ge2gl_state_load(other, b.data(), b.size()), GE2GL_ERR_INVALID_ARGUMENT);
        const std::string msg = ge2gl_last_message(other);
        EXPECT_NE(msg.find(why), std::string::npos) << msg;
        EXPECT_EQ(saveBytes(other, 0), before);
    };
    std::vector<uint8_t> b = good;
    b[100] ^= 0x10;
    refused(b, "checksum");
    refused(std::vector<uint8_t>(good.begin(), good.end() - 7), "truncated");
    refused(std::vector<uint8_t>(good.begin(), good.begin() + 20), "not a ge2gl save state");
    b = good;
    b[0] = 'X';
    refused(b, "not a ge2gl save state");
    b = good;
    b[8] = 4;  // format version 4
    refused(b, "version 4");
    // Well signed, but values no GE can hold: the engine section's CALL depth (payload: tag 4,
    // size 4, registers 1024, matrices 592, indices and addresses 32, palette 1024, its count 4,
    // the vertex latch 20, pc 4, stall 4, call stack 16) set to 3, beyond the GE's two levels.
    b = good;
    const size_t callDepth = 32 + 8 + 1024 + 592 + 32 + 1024 + 4 + 20 + 24;
    ASSERT_EQ(b[callDepth], 0u);
    b[callDepth] = 3;
    resign(b);
    refused(b, "malformed");
    // A register word whose opcode byte is not its slot's.
    b = good;
    b[32 + 8 + 4 * 0x98 + 3] = 0x99;
    resign(b);
    refused(b, "malformed");
    refused({}, "not a ge2gl save state");
    EXPECT_EQ(ge2gl_state_load(other, nullptr, 10), GE2GL_ERR_INVALID_ARGUMENT);

    // A version-1 blob (no vertex latch in the engine section) still loads: the same state with
    // the latch's 20 bytes taken out, the section size and the header's payload size less 20.
    {
        std::vector<uint8_t> v1 = good;
        const size_t latch = 32 + 8 + 1024 + 592 + 32 + 1024 + 4;
        v1.erase(v1.begin() + std::ptrdiff_t(latch), v1.begin() + std::ptrdiff_t(latch + 20));
        auto sub20 = [&](size_t at, int bytes) {
            uint64_t v = 0;
            for (int i = 0; i < bytes; ++i) v |= uint64_t(v1[at + size_t(i)]) << (8 * i);
            v -= 20;
            for (int i = 0; i < bytes; ++i) v1[at + size_t(i)] = uint8_t(v >> (8 * i));
        };
        sub20(32 + 4, 4);  // ENGN section size
        sub20(16, 8);      // payload size in the header
        v1[8] = 1;
        resign(v1);
        ge2gl_context* old = createHandle(GE2GL_BACKEND_SOFT);
        ASSERT_NE(old, nullptr);
        EXPECT_EQ(ge2gl_state_load(old, v1.data(), v1.size()), GE2GL_OK) << ge2gl_last_message(old);
        // Saved again it is the current-version state it came from (this list never drew: latch zero).
        EXPECT_EQ(saveBytes(old, 0), good);
        ge2gl_destroy(old);
    }

    // The good blob still loads, and the loaded GE goes on from the stall.
    ASSERT_EQ(ge2gl_state_load(other, good.data(), good.size()), GE2GL_OK) << ge2gl_last_message(other);
    // Guest memory was not in the blob: this host (ge2gl's memory) brings the list over itself.
    std::vector<uint8_t> words(12);
    ASSERT_EQ(ge2gl_mem_read(h, 0x08000100, words.data(), 12), GE2GL_OK);
    ASSERT_EQ(ge2gl_mem_write(other, 0x08000100, words.data(), 12), GE2GL_OK);
    ASSERT_EQ(ge2gl_list_update_stall(other, id, 0), GE2GL_OK);
    int32_t st = -1;
    ASSERT_EQ(ge2gl_list_sync(other, id, GE2GL_SYNC_WAIT, &st), GE2GL_OK) << ge2gl_last_message(other);
    uint32_t w = 0;
    ASSERT_EQ(ge2gl_get_cmd(other, 0x98, &w), GE2GL_OK);
    EXPECT_EQ(w, 0x98000ABCu);
    ge2gl_destroy(other);

    // A state with memory needs a GE with the same RAM size.
    const std::vector<uint8_t> withMem = saveBytes(h, GE2GL_STATE_WITH_MEMORY);
    std::vector<uint8_t> ram(4u << 20), vram(0x200000);
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.ram = ram.data();
    cfg.ram_size = uint32_t(ram.size());
    cfg.vram = vram.data();
    ge2gl_context* small = nullptr;
    ASSERT_EQ(ge2gl_create(&cfg, &small), GE2GL_OK);
    EXPECT_EQ(ge2gl_state_load(small, withMem.data(), withMem.size()), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ge2gl_last_message(small)).find("size"), std::string::npos) << ge2gl_last_message(small);
    ge2gl_destroy(small);
    ge2gl_destroy(h);
}

}  // namespace
