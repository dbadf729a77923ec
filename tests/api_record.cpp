// SPDX-License-Identifier: MIT
// Frame-dump recording through the C ABI (ge2gl_record_begin/display/end; docs/recording.md):
// the project's five scenes replayed through the plugin API (ge2gl_replay_dump) with recording on
// give dumps that `ge2gl render` replays to the identical picture, that the .ppdmp reader and the
// DumpWriter round-trip byte for byte, and host writes into VRAM come out as MEMCPY/MEMSET.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <unistd.h>

#include "ge2gl/ge2gl.h"
#include "ge2gl/ge2gl.hpp"
#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

std::vector<u8> readBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::vector<u8>(std::istreambuf_iterator<char>(f), {});
}

fs::path tempPath(const std::string& name) {
    return fs::temp_directory_path() / ("ge2gl_record_" + std::to_string(::getpid()) + "_" + name);
}

// Writes a loaded dump again through the DumpWriter, record by record, and serialises it.
std::vector<u8> rewriteWithWriter(const dump::Dump& d) {
    dump::DumpWriter w(d.gameId);
    u32 memcpyDest = 0;
    for (const dump::Record& r : d.records) {
        const u8* p = d.payload(r);
        if (!p) throw std::runtime_error("record outside the push buffer");
        const int tex = dump::textureLevelOf(r.type), fb = dump::framebufLevelOf(r.type);
        auto word = [&](u32 i) { return d.payloadWord(r, i); };
        if (tex >= 0) {
            w.texture(tex, p, r.size);
        } else if (fb >= 0) {
            if (r.size < 16) throw std::runtime_error("short FRAMEBUF record");
            w.framebufTexture(fb, word(0), word(1), word(2), p + 16, r.size - 16);
        } else {
            switch (r.type) {
            case dump::INIT: {
                u32 ctx[512] = {};
                for (u32 i = 0; i < 512 && 4 * i + 4 <= r.size; ++i) ctx[i] = readLE32(p + 4 * i);
                w.init(ctx);
                break;
            }
            case dump::REGISTERS: {
                std::vector<u32> words(r.size / 4);
                for (size_t i = 0; i < words.size(); ++i) words[i] = readLE32(p + 4 * i);
                w.registers(words);
                break;
            }
            case dump::VERTICES: w.vertices(p, r.size); break;
            case dump::INDICES: w.indices(p, r.size); break;
            case dump::CLUT: w.clut(p, r.size); break;
            case dump::TRANSFERSRC: w.transferSrc(p, r.size); break;
            case dump::MEMSET: w.memset(word(0), u8(word(1)), word(2)); break;
            case dump::MEMCPYDEST: memcpyDest = word(0); break;
            case dump::MEMCPYDATA: w.memcpy(memcpyDest, p, r.size); break;
            case dump::DISPLAY: w.display(word(0), word(1), word(2)); break;
            case dump::CLUTADDR: w.clutAddr(word(0), word(1)); break;
            case dump::EDRAMTRANS: w.edramTrans(word(0)); break;
            default: throw std::runtime_error("unknown record type");
            }
        }
    }
    return dump::serializeDump(w.dump());
}

size_t differingPixels(const tools::Image& a, const tools::Image& b) {
    if (a.rgba.size() != b.rgba.size()) return std::max(a.rgba.size(), b.rgba.size());
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) n += a.rgba[i] != b.rgba[i];
    return n;
}

void recordScenes(int apiBackend, const std::string& cliBackend) {
    const fs::path dir = fs::path(GE2GL_SOURCE_DIR) / "dumps";
    int scenes = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".ppdmp") continue;
        SCOPED_TRACE(e.path().string());
        ++scenes;
        std::string err;
        tools::RenderOptions opt;
        opt.backend = cliBackend;
        tools::RenderOutput original;
        ASSERT_TRUE(tools::renderDumpFile(e.path().string(), opt, original, err)) << err;

        // Record the scene as an emulator would while replaying it through the handle.
        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.backend = apiBackend;
        ge2gl_context* h = nullptr;
        ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK) << ge2gl_last_message(nullptr);
        const fs::path out = tempPath(cliBackend + "_" + e.path().filename().string());
        ASSERT_EQ(ge2gl_record_begin(h, out.c_str()), GE2GL_OK) << ge2gl_last_message(h);
        ge2gl_display disp{};
        ASSERT_EQ(ge2gl_replay_dump(h, e.path().c_str(), &disp), GE2GL_OK) << ge2gl_last_message(h);
        ASSERT_EQ(ge2gl_record_display(h, disp.addr, disp.stride, disp.format), GE2GL_OK) << ge2gl_last_message(h);
        ASSERT_EQ(ge2gl_record_end(h), GE2GL_OK) << ge2gl_last_message(h);
        EXPECT_STREQ(ge2gl_last_message(h), "") << "the recorder could not express everything";
        ge2gl_destroy(h);

        // `ge2gl render` of the recorded file: the same picture, every pixel.
        tools::RenderOutput replayed;
        ASSERT_TRUE(tools::renderDumpFile(out.string(), opt, replayed, err)) << err;
        EXPECT_EQ(replayed.displayAddr, original.displayAddr);
        EXPECT_EQ(replayed.replay.listErrors, 0u);
        EXPECT_EQ(replayed.replay.draws, original.replay.draws);
        const size_t diff = differingPixels(replayed.frame, original.frame);
        EXPECT_EQ(diff, 0u);
        size_t lit = 0;
        for (u32 p : original.frame.rgba) lit += (p & 0xFFFFFF) != 0;
        EXPECT_GT(lit, 1000u);  // not two blank frames

        // The reader round-trips the file byte for byte, and so does the DumpWriter.
        const std::vector<u8> bytes = readBytes(out);
        dump::Dump d;
        ASSERT_TRUE(dump::loadDump(out.string(), d, err)) << err;
        EXPECT_EQ(d.version, 6u);
        ASSERT_FALSE(d.records.empty());
        EXPECT_EQ(d.records.front().type, dump::INIT);
        EXPECT_EQ(d.records.back().type, dump::DISPLAY);
        EXPECT_TRUE(dump::serializeDump(d) == bytes) << "reader + serializer changed the bytes";
        EXPECT_TRUE(rewriteWithWriter(d) == bytes) << "DumpWriter rewrite changed the bytes";

        std::cout << "[ record ] " << cliBackend << " " << e.path().filename().string() << ": "
                  << (diff == 0 ? "identical" : "DIFFERENT (" + std::to_string(diff) + " pixels)") << ", "
                  << bytes.size() << " bytes, " << d.records.size() << " records, " << replayed.replay.draws
                  << " draws\n";
        if (!std::getenv("GE2GL_KEEP_RECORDINGS")) fs::remove(out);  // set it to look at the files
    }
    EXPECT_GE(scenes, 5);
}

TEST(ApiRecord, ScenesRecordedThroughApiReplayIdentically) { recordScenes(GE2GL_BACKEND_SOFT, "soft"); }

TEST(ApiRecord, ScenesRecordedThroughApiReplayIdenticallyWithGl) {
    {
        Memory probe(1u << 20);
        std::string err;
        tools::RenderOptions o;
        o.backend = "gl";
        if (!tools::createBackend(o, probe, err)) GTEST_SKIP() << "GL backend unavailable: " << err;
    }
    recordScenes(GE2GL_BACKEND_GL_HEADLESS, "gl");
}

// sceGeRestoreContext changes the registers without a command: the recording must still carry
// the state. Each scene is rewritten so that its first REGISTERS block (frame buffer, viewport,
// matrices, ...; state words only) lives in INIT instead; ge2gl_replay_dump restores that INIT
// with ge2gl_restore_context while recording, and the recorded dump must still give the scene.
TEST(ApiRecord, ContextRestoredWhileRecordingIsInTheDump) {
    const fs::path dir = fs::path(GE2GL_SOURCE_DIR) / "dumps";
    int scenes = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".ppdmp") continue;
        SCOPED_TRACE(e.path().string());
        ++scenes;
        std::string err;
        dump::Dump d;
        ASSERT_TRUE(dump::loadDump(e.path().string(), d, err)) << err;
        ASSERT_GE(d.records.size(), 3u);
        ASSERT_EQ(d.records[0].type, dump::INIT);
        ASSERT_EQ(d.records[2].type, dump::REGISTERS);
        Memory mem;
        GeEngine eng(mem);
        u32 ctx[512];
        for (u32 i = 0; i < 512; ++i) ctx[i] = d.payloadWord(d.records[0], i);
        eng.loadContext(ctx);
        const dump::Record& block = d.records[2];
        for (u32 i = 0; i < block.size / 4; ++i) {
            const u32 w = d.payloadWord(block, i);
            const u8 op = u8(w >> 24);
            ASSERT_FALSE(op == GE_CMD_PRIM || op == GE_CMD_BEZIER || op == GE_CMD_SPLINE || op == GE_CMD_CLOAD ||
                         op == GE_CMD_XSTART);
            eng.execute(w);
        }
        eng.state().saveContext(ctx);
        for (u32 i = 0; i < 512; ++i) writeLE32(d.pushbuf.data() + d.records[0].ptr + 4 * i, ctx[i]);
        d.records.erase(d.records.begin() + 2);
        const fs::path moved = tempPath("ctx_" + e.path().filename().string());
        ASSERT_TRUE(dump::saveDump(moved.string(), d, err)) << err;

        tools::RenderOptions opt;
        tools::RenderOutput original, fromMoved, recorded;
        ASSERT_TRUE(tools::renderDumpFile(e.path().string(), opt, original, err)) << err;
        ASSERT_TRUE(tools::renderDumpFile(moved.string(), opt, fromMoved, err)) << err;
        ASSERT_EQ(differingPixels(fromMoved.frame, original.frame), 0u) << "the rewritten scene is not the scene";

        ge2gl_config cfg;
        ge2gl_config_init(&cfg);
        cfg.backend = GE2GL_BACKEND_SOFT;
        ge2gl_context* h = nullptr;
        ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);
        const fs::path out = tempPath("ctx_rec_" + e.path().filename().string());
        ASSERT_EQ(ge2gl_record_begin(h, out.c_str()), GE2GL_OK) << ge2gl_last_message(h);
        ASSERT_EQ(ge2gl_replay_dump(h, moved.c_str(), nullptr), GE2GL_OK) << ge2gl_last_message(h);
        ASSERT_EQ(ge2gl_record_end(h), GE2GL_OK) << ge2gl_last_message(h);
        ge2gl_destroy(h);
        ASSERT_TRUE(tools::renderDumpFile(out.string(), opt, recorded, err)) << err;
        EXPECT_EQ(differingPixels(recorded.frame, original.frame), 0u);
        fs::remove(moved);
        fs::remove(out);
    }
    EXPECT_GE(scenes, 5);
}

// Host writes while recording: VRAM writes become MEMCPYDEST + MEMCPYDATA (or MEMSET for one
// repeated byte) with the bytes written; RAM writes need no record (draws carry what they read).
TEST(ApiRecord, HostVramWritesBecomeMemcpyAndMemset) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    auto created = ge2gl::Context::create(cfg);
    ASSERT_TRUE(created.ok()) << created.message;
    ge2gl::Context ctx = std::move(created.value);
    const fs::path out = tempPath("hostwrites.ppdmp");
    ASSERT_TRUE(ctx.recordBegin(out.c_str()).ok()) << ctx.lastMessage();
    std::vector<u8> pattern(64);
    for (size_t i = 0; i < pattern.size(); ++i) pattern[i] = u8(i * 7 + 1);
    const std::vector<u8> fill(32, 0x7F), ram(16, 0x55);
    ASSERT_TRUE(ctx.memWrite(0x04100000, pattern.data(), u32(pattern.size())).ok());
    ASSERT_TRUE(ctx.memWrite(0x04100100, fill.data(), u32(fill.size())).ok());
    ASSERT_TRUE(ctx.memWrite(0x08900000, ram.data(), u32(ram.size())).ok());
    ASSERT_TRUE(ctx.recordEnd().ok()) << ctx.lastMessage();

    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(out.string(), d, err)) << err;
    fs::remove(out);
    int memcpys = 0, memsets = 0;
    for (size_t i = 0; i < d.records.size(); ++i) {
        const dump::Record& r = d.records[i];
        if (r.type == dump::MEMCPYDEST) {
            ++memcpys;
            EXPECT_EQ(d.payloadWord(r, 0), 0x04100000u);
            ASSERT_LT(i + 1, d.records.size());
            const dump::Record& data = d.records[i + 1];
            ASSERT_EQ(data.type, dump::MEMCPYDATA);
            ASSERT_EQ(data.size, pattern.size());
            EXPECT_TRUE(std::equal(pattern.begin(), pattern.end(), d.payload(data)));
        } else if (r.type == dump::MEMSET) {
            ++memsets;
            EXPECT_EQ(d.payloadWord(r, 0), 0x04100100u);
            EXPECT_EQ(d.payloadWord(r, 1) & 0xFF, 0x7Fu);
            EXPECT_EQ(d.payloadWord(r, 2), 32u);
        }
    }
    EXPECT_EQ(memcpys, 1);  // the RAM write made none
    EXPECT_EQ(memsets, 1);
    EXPECT_EQ(d.records.front().type, dump::INIT);
    EXPECT_EQ(d.records.back().type, dump::DISPLAY);
}

TEST(ApiRecord, ErrorsAreReportedNotSwallowed) {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    ge2gl_context* h = nullptr;
    ASSERT_EQ(ge2gl_create(&cfg, &h), GE2GL_OK);

    EXPECT_EQ(ge2gl_record_end(h), GE2GL_ERR_BAD_STATE);
    EXPECT_NE(std::string(ge2gl_last_message(h)).find("not recording"), std::string::npos) << ge2gl_last_message(h);
    EXPECT_EQ(ge2gl_record_display(h, 0x04000000, 512, GE2GL_FORMAT_8888), GE2GL_ERR_BAD_STATE);
    EXPECT_EQ(ge2gl_record_begin(h, nullptr), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_record_begin(h, ""), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_record_begin(nullptr, "x.ppdmp"), GE2GL_ERR_INVALID_HANDLE);

    // A path that cannot be written fails at begin, with the system's reason.
    const fs::path bad = tempPath("no_such_dir") / "frame.ppdmp";
    EXPECT_EQ(ge2gl_record_begin(h, bad.c_str()), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ge2gl_last_message(h)).find("No such file or directory"), std::string::npos)
        << ge2gl_last_message(h);
    EXPECT_EQ(ge2gl_record_end(h), GE2GL_ERR_BAD_STATE);  // nothing started

    const fs::path good = tempPath("errors.ppdmp");
    ASSERT_EQ(ge2gl_record_begin(h, good.c_str()), GE2GL_OK) << ge2gl_last_message(h);
    EXPECT_FALSE(fs::exists(good));  // the probe leaves nothing behind
    EXPECT_EQ(ge2gl_record_begin(h, good.c_str()), GE2GL_ERR_BAD_STATE);
    EXPECT_NE(std::string(ge2gl_last_message(h)).find("already recording"), std::string::npos) << ge2gl_last_message(h);
    EXPECT_EQ(ge2gl_record_display(h, 0x04000000, 512, 7), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(ge2gl_record_display(h, 0x04088000, 512, GE2GL_FORMAT_565), GE2GL_OK);
    ASSERT_EQ(ge2gl_record_end(h), GE2GL_OK) << ge2gl_last_message(h);
    EXPECT_EQ(ge2gl_record_end(h), GE2GL_ERR_BAD_STATE);  // ended already

    // The empty recording is a valid dump ending with the DISPLAY the host gave.
    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(good.string(), d, err)) << err;
    ASSERT_FALSE(d.records.empty());
    EXPECT_EQ(d.records.back().type, dump::DISPLAY);
    EXPECT_EQ(d.payloadWord(d.records.back(), 0), 0x04088000u);
    EXPECT_EQ(d.payloadWord(d.records.back(), 2), u32(GE2GL_FORMAT_565));

    // An I/O error at the end (the directory vanished) is reported with the system's reason.
    const fs::path dir = tempPath("vanishing_dir");
    fs::create_directories(dir);
    const fs::path inDir = dir / "frame.ppdmp";
    ASSERT_EQ(ge2gl_record_begin(h, inDir.c_str()), GE2GL_OK) << ge2gl_last_message(h);
    fs::remove_all(dir);
    EXPECT_EQ(ge2gl_record_end(h), GE2GL_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(ge2gl_last_message(h)).find("No such file or directory"), std::string::npos)
        << ge2gl_last_message(h);
    EXPECT_EQ(ge2gl_record_end(h), GE2GL_ERR_BAD_STATE);  // the failed end still ended it

    // Destroying a handle that records drops the recording.
    ASSERT_EQ(ge2gl_record_begin(h, good.c_str()), GE2GL_OK);
    ge2gl_destroy(h);
    fs::remove(good);
}

}  // namespace
