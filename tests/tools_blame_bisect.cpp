// SPDX-License-Identifier: MIT
// `ge2gl blame` and `ge2gl bisect` (accuracy tools), driven through the CLI on dumps
// made here with ListBuilder + DumpRecorder (one injected change each) and on a shared frametest
// with one command word changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "hle/dump/player.h"
#include "tools/lib/draw_hook.h"
#include "tools/lib/json_io.h"
#include "tools/lib/render.h"
#include "tests/tools_cli_run.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

using Cli = clitest::CliRun;
using clitest::runCli;

std::string q(const fs::path& p) { return clitest::quote(p.string()); }

fs::path tmpDir(const char* what) {
    fs::path d = fs::temp_directory_path() / ("ge2gl_blame_bisect_" + std::string(what) + "_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// A dump recorded from what `build` emits: boot state, 8888 frame buffer at VRAM 0, stride 512.
dump::Dump record(const std::function<void(ListBuilder&)>& build) {
    Memory mem{16u << 20};
    dump::DumpWriter w;
    DumpRecorder rec(mem, w);
    GeState init;
    init.reset();
    for (int op = 0; op < 256; ++op) init.regs[op] = u32(op) << 24;
    rec.begin(init, Memory::kVramBase, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.depthBuffer(0x110000, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.clear(CLEAR_COLOR | CLEAR_DEPTH, 0xFF203040, 0);  // draw 1
    build(b);
    b.finish();
    rec.end(Memory::kVramBase, 512, GE_FORMAT_8888);
    EXPECT_TRUE(rec.warnings().empty());
    return w.dump();
}

void save(const dump::Dump& d, const fs::path& p) {
    std::string err;
    ASSERT_TRUE(dump::saveDump(p.string(), d, err)) << err;
}

// A --json file read with nlohmann (tools/lib/json_io.h); a test failure when it is not JSON.
tools::Json readJson(const std::string& text) {
    tools::Json j;
    std::string err;
    EXPECT_TRUE(tools::parseJson(text, j, err)) << err << "\n" << text;
    return j;
}

std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// ---------------------------------------------------------------------------------------------

// Four rectangles over a clear; draw 3 (the translucent green one) blends wrongly in the second
// dump: blame against the first dump's render ranks draw 3 first.
TEST(Blame, RanksTheWronglyBlendedDrawFirst) {
    auto scene = [](bool wrong) {
        return record([wrong](ListBuilder& b) {
            b.fillRect(10, 10, 200, 150, 0xFF0000FF);  // draw 2: opaque red
            b.enable(GE_CMD_ABE, true);
            // draw 3: translucent green over the red; the wrong dump adds instead of mixing
            b.blendFunc(BLEQ_ADD, 2, wrong ? 10 : 3, 0, wrong ? 0xFFFFFF : 0);
            b.fillRect(100, 60, 300, 200, 0x8000FF00);
            b.blendFunc(BLEQ_ADD, 2, 3);
            b.fillRect(320, 20, 460, 120, 0x80FF0000);  // draw 4: translucent blue, elsewhere
            b.enable(GE_CMD_ABE, false);
            b.fillRect(20, 210, 150, 260, 0xFF00FFFF);  // draw 5: opaque yellow
        });
    };
    const fs::path t = tmpDir("blame");
    save(scene(false), t / "good.ppdmp");
    save(scene(true), t / "wrong.ppdmp");
    Cli r = runCli("render " + q(t / "good.ppdmp") + " --backend soft -o " + q(t / "ref.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    r = runCli("blame " + q(t / "wrong.ppdmp") + " --ref " + q(t / "ref.png") + " --backend soft --top 3 -o " +
               q(t / "blame.png") + " --json " + q(t / "blame.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    // rank 1 is draw 3, a RECTANGLES prim with 2 vertices and blending on.
    const size_t rank1 = r.out.find("\n   1       3 ");
    ASSERT_NE(rank1, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("prim RECTANGLES, 2 vertices", rank1), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("blend add(srca, fix)", rank1), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("\n   2 "), std::string::npos) << "only draw 3 differs\n" << r.out;
    // The differing pixels are draw 3's rectangle less nothing (it is drawn last there): 200x140.
    EXPECT_NE(r.out.find("differing pixels: 28000 "), std::string::npos) << r.out;
    const std::string text = slurp(t / "blame.json");
    const tools::Json j = readJson(text);
    ASSERT_TRUE(j.is_object()) << text;
    EXPECT_EQ(j.value("differing_pixels", -1), 28000) << text;
    EXPECT_EQ(j.value("draws", -1), 5) << text;
    EXPECT_EQ(j.value("owner_count", -1), 1) << text;
    ASSERT_TRUE(j.contains("top") && j["top"].is_array() && j["top"].size() == 1u) << text;
    const tools::Json& first = j["top"][0];
    EXPECT_EQ(first.value("rank", -1), 1) << text;
    EXPECT_EQ(first.value("draw", -1), 3) << text;
    EXPECT_EQ(first.value("pixels", -1), 28000) << text;
    EXPECT_EQ(first.value("share", -1.0), 1.0) << text;
    EXPECT_EQ(first.value("prim", ""), "RECTANGLES") << text;
    EXPECT_EQ(first.value("bbox", tools::Json()), tools::Json({100, 60, 299, 199})) << text;
    // The layout: one ranked draw per line.
    EXPECT_NE(text.find("\n  \"top\": [\n    {\"rank\": 1, \"draw\": 3, \"pixels\": 28000, \"share\": 1, "),
              std::string::npos)
        << text;
    tools::Image pic;
    std::string err;
    ASSERT_TRUE(tools::readImage((t / "blame.png").string(), pic, err)) << err;
    EXPECT_EQ(pic.at(150, 100), 0xFF0000FFu);  // the top draw's colour inside its rectangle
    // A reference render by the same backend: nothing differs.
    r = runCli("blame " + q(t / "wrong.ppdmp") + " --ref-backend soft --backend soft");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("differing pixels: 0 "), std::string::npos) << r.out;
    // Usage errors.
    EXPECT_EQ(runCli("blame " + q(t / "wrong.ppdmp") + " --backend soft").code, 1);
    fs::remove_all(t);
}

// 500 draws (a clear and 499 small rectangles); the copy changes one rectangle's colour at draw
// 237. One lockstep replay finds it.
TEST(Bisect, FindsTheChangedDrawAmongFiveHundred) {
    auto scene = [](int changed, int last = 500) {
        return record([changed, last](ListBuilder& b) {
            for (int n = 2; n <= last; ++n) {
                const int x = (n * 37) % 460, y = (n * 53) % 256;
                u32 c = 0xFF000000u | (u32(n) * 2654435761u & 0xFFFFFF);
                if (n == changed) c ^= 0x000010;
                b.fillRect(x, y, x + 12, y + 12, c);
            }
        });
    };
    const fs::path t = tmpDir("bisect");
    save(scene(0), t / "a.ppdmp");
    save(scene(237), t / "b.ppdmp");
    Cli r = runCli("bisect " + q(t / "a.ppdmp") + " --backend soft --ref-dump " + q(t / "b.ppdmp") + " --json " +
                   q(t / "b.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("first difference after draw 237 (colour)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("differing: 144 colour pixels, 0 depth values"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("draw 237: prim RECTANGLES, 2 vertices"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("PRIM count=2"), std::string::npos) << r.out;  // the disassembly
    const tools::Json j = readJson(slurp(t / "b.json"));
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j.value("found", false), true);
    EXPECT_EQ(j.value("draw", -1), 237);
    EXPECT_EQ(j.value("draws", -1), 500);
    EXPECT_EQ(j.value("ref_draws", -1), 500);
    EXPECT_EQ(j.value("colour_pixels", -1), 144);
    EXPECT_EQ(j.value("reason", ""), "colour");
    EXPECT_EQ(j.value("prim", ""), "RECTANGLES");
    ASSERT_TRUE(j.contains("commands") && j["commands"].is_array() && !j["commands"].empty());
    EXPECT_NE(j["commands"].back().get<std::string>().find("PRIM count=2"), std::string::npos) << j["commands"];
    // Within tolerance 16 the two agree (the blue channel differs by 16).
    r = runCli("bisect " + q(t / "a.ppdmp") + " --backend soft --ref-dump " + q(t / "b.ppdmp") + " --tolerance 16");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("no difference: 500 draws"), std::string::npos) << r.out;
    // All of VRAM: same draw.
    r = runCli("bisect " + q(t / "a.ppdmp") + " --backend soft --ref-dump " + q(t / "b.ppdmp") + " --all-vram");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("first difference after draw 237 (vram)"), std::string::npos) << r.out;
    // A dump against itself.
    r = runCli("bisect " + q(t / "a.ppdmp") + " --backend soft --ref-dump " + q(t / "a.ppdmp"));
    EXPECT_NE(r.out.find("no difference: 500 draws"), std::string::npos) << r.out;
    // The same draws, 300 of them: the sides part at draw 301, which only one has.
    save(scene(0, 300), t / "short.ppdmp");
    r = runCli("bisect " + q(t / "a.ppdmp") + " --backend soft --ref-dump " + q(t / "short.ppdmp"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("first difference after draw 301 (draw count); 500 draws in"), std::string::npos) << r.out;
    r = runCli("bisect " + q(t / "short.ppdmp") + " --backend soft --ref-dump " + q(t / "a.ppdmp"));
    EXPECT_NE(r.out.find("first difference after draw 301 (draw count); 300 draws in"), std::string::npos) << r.out;
    fs::remove_all(t);
}

// VRAM after draws k-1 and k of a soft replay (DrawHook numbering), one thread.
bool vramAround(const dump::Dump& d, u64 k, std::vector<u8>& before, std::vector<u8>& after) {
    Memory mem;
    tools::RenderOptions ro;
    ro.threads = 1;
    std::string err;
    auto backend = tools::createBackend(ro, mem, err).renderer;
    if (!backend) return false;
    tools::DrawHook hook(*backend);
    GeEngine eng(mem, &hook);
    hook.after = [&](u64 n) {
        if (n != k - 1 && n != k) return;
        backend->flushToMemory();
        (n == k ? after : before).assign(mem.vram(), mem.vram() + Memory::kVramSize);
    };
    dump::ReplayResult res;
    return dump::replayDump(d, eng, {}, res, err) && !before.empty() && !after.empty();
}

// A frametest with one PRIM word's vertex count lowered (a primitive fewer): bisect against the
// original names the draw that PRIM kicks. The candidate is checked first on whole-VRAM
// snapshots of plain replays (equal after draw k-1, different after draw k).
TEST(Bisect, FindsAChangedWordInAFrametest) {
    const fs::path dir = fs::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    const fs::path src = dir / "21391 Coded arms ULUS10019_0001.zip";
    if (!fs::exists(src)) GTEST_SKIP() << "frametests not found at " << dir;
    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(src.string(), d, err)) << err;
    // Draw kicks in REGISTERS order, with where their word is, in records no other record overlaps.
    struct Kick {
        u64 draw;
        size_t byte;
        u32 word;
    };
    std::vector<Kick> kicks;
    // Records whose payload range overlaps another record's (shared payloads) are left alone.
    std::vector<size_t> order;
    for (size_t ri = 0; ri < d.records.size(); ++ri)
        if (d.records[ri].size) order.push_back(ri);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return d.records[a].ptr < d.records[b].ptr; });
    std::vector<bool> sharedRec(d.records.size(), false);
    u64 maxEnd = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        const dump::Record& r = d.records[order[k]];
        const u64 end = u64(r.ptr) + r.size;
        if (maxEnd > r.ptr || (k + 1 < order.size() && d.records[order[k + 1]].ptr < end)) sharedRec[order[k]] = true;
        maxEnd = std::max(maxEnd, end);
    }
    u64 draws = 0;
    for (size_t ri = 0; ri < d.records.size(); ++ri) {
        const dump::Record& r = d.records[ri];
        if (r.type != dump::REGISTERS || !d.payload(r)) continue;
        const bool shared = sharedRec[ri];
        for (u32 k = 0; k < r.size / 4; ++k) {
            const u32 w = readLE32(d.payload(r) + 4 * k);
            const u8 op = u8(w >> 24);
            if (op == GE_CMD_PRIM && (w & 0xFFFF)) {
                ++draws;
                if (!shared) kicks.push_back({draws, r.ptr + 4 * size_t(k), w});
            } else if ((op == GE_CMD_BEZIER || op == GE_CMD_SPLINE) && (w & 0xFF) && (w >> 8 & 0xFF)) {
                ++draws;
            }
        }
    }
    ASSERT_GT(draws, 100u);
    const fs::path t = tmpDir("frametest");
    int tried = 0;
    for (const Kick& k : kicks) {
        if (k.draw < draws / 2) continue;
        const u32 type = (k.word >> 16) & 7, count = k.word & 0xFFFF;
        u32 fewer = 0;
        if (type == GE_PRIM_TRIANGLES && count >= 6) fewer = 3;
        else if (type == GE_PRIM_RECTANGLES && count >= 4) fewer = 2;
        else if ((type == GE_PRIM_TRIANGLE_STRIP || type == GE_PRIM_TRIANGLE_FAN) && count >= 4) fewer = 1;
        if (!fewer) continue;
        ASSERT_LT(++tried, 12) << "no visible single-word change found";
        dump::Dump m = d;
        writeLE32(&m.pushbuf[k.byte], k.word - fewer);
        std::vector<u8> a0, a1, b0, b1;
        ASSERT_TRUE(vramAround(d, k.draw, a0, a1));
        ASSERT_TRUE(vramAround(m, k.draw, b0, b1));
        ASSERT_EQ(a0, b0) << "draw " << k.draw - 1 << " already differs";
        if (a1 == b1) continue;  // the dropped primitive was hidden: try another
        save(m, t / "changed.ppdmp");
        Cli r = runCli("bisect " + q(src) + " --backend soft --ref-dump " + q(t / "changed.ppdmp") + " --json " +
                       q(t / "f.json"));
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_NE(r.out.find("first difference after draw " + std::to_string(k.draw) + " "), std::string::npos)
            << "changed PRIM of draw " << k.draw << "\n" << r.out;
        const tools::Json j = readJson(slurp(t / "f.json"));
        ASSERT_TRUE(j.is_object());
        EXPECT_EQ(j.value("draw", u64(0)), k.draw);
        // Both disassemblies are printed; the changed one shows the lower count.
        char want[40];
        std::snprintf(want, sizeof want, "PRIM count=%u", count - fewer);
        EXPECT_NE(r.out.find(want), std::string::npos) << r.out;
        break;
    }
    ASSERT_GT(tried, 0);
    fs::remove_all(t);
}

}  // namespace
