// SPDX-License-Identifier: MIT
// Accuracy tools in the ge2gl CLI: --skip / --only draw selection (tools/lib/draw_select.h
// through the DrawHook in tools::renderDump), compare --shard i/n and ge2gl merge
// (tools/lib/batch.h), and the JSON they exchange.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

#include "authoring/list_builder.h"
#include "authoring/scene_recorder.h"
#include "hle/dump/dump_writer.h"
#include "tools/lib/batch.h"
#include "tools/lib/draw_select.h"
#include "tools/lib/image.h"
#include "tools/lib/render.h"
#include "tests/tools_cli_run.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

using clitest::CliRun;
using clitest::quote;
CliRun run(const std::string& args) { return clitest::runCli(args); }

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

fs::path tmpDir(const char* what) {
    fs::path d = fs::temp_directory_path() / ("ge2gl_batch_" + std::string(what) + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// ABGR colours (R in bits 7..0) as the vertex colour; readFrame gives the same layout.
constexpr u32 kBlue = 0xFFFF0000u, kRed = 0xFF0000FFu, kGreen = 0xFF00FF00u;

struct Rect {
    u32 x0, y0, x1, y1;  // exclusive end
};
constexpr Rect kRedRect{40, 30, 120, 100}, kGreenRect{300, 150, 420, 230};

void fill(ListBuilder& b, const Rect& r, u32 c) { b.fillRect(r.x0, r.y0, r.x1, r.y1, c); }

// A dump at `path` of an 8888 frame at VRAM 0 (stride 512, full-screen scissor, nothing
// write-protected) and the draws `body` adds.
fs::path writeDump(const fs::path& path, const std::function<void(ListBuilder&)>& body) {
    Memory mem;
    dump::DumpWriter writer("GE2GL0001");
    DumpRecorder rec(mem, writer);
    GeState init;
    init.reset();
    for (int op = 0; op < 256; ++op) init.regs[op] = u32(op) << 24;
    rec.begin(init, 0x04000000, 512, GE_FORMAT_8888);
    ListBuilder b(&mem);
    b.attach(&rec);
    b.drawBuffer(GE_FORMAT_8888, 0, 512);
    b.scissor(0, 0, 480, 272);
    b.region(0, 0, 480, 272);
    b.pixelMask(0, 0);
    body(b);
    b.finish();
    b.attach(nullptr);
    rec.end(0x04000000, 512, GE_FORMAT_8888);
    std::string err;
    EXPECT_TRUE(writer.save(path.string(), err)) << err;
    EXPECT_TRUE(rec.warnings().empty());
    return path;
}

// Draw 1 clears the screen to blue, draw 2 is a red rectangle, draw 3 a green one.
fs::path writeThreeDrawDump(const fs::path& dir) {
    return writeDump(dir / "three_draws.ppdmp", [](ListBuilder& b) {
        b.clear(CLEAR_COLOR, kBlue, 0);
        fill(b, kRedRect, kRed);
        fill(b, kGreenRect, kGreen);
    });
}

u32 px(const tools::Image& img, u32 x, u32 y) { return img.rgba[size_t(y) * img.width + x] | 0xFF000000u; }
u32 inside(const tools::Image& img, const Rect& r) { return px(img, (r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2); }

// Every pixel of `r` has colour c and (with `edges`) the pixels just outside it do not.
void expectRect(const tools::Image& img, const Rect& r, u32 c, const std::string& what, bool edges = true) {
    size_t wrong = 0;
    for (u32 y = r.y0; y < r.y1; ++y)
        for (u32 x = r.x0; x < r.x1; ++x) wrong += px(img, x, y) != c;
    EXPECT_EQ(wrong, 0u) << what;
    if (!edges) return;
    EXPECT_NE(px(img, r.x1, r.y0), c) << what;
    EXPECT_NE(px(img, r.x0, r.y1), c) << what;
}

}  // namespace

// ---- draw selection ----

TEST(DrawSelect, ParsesNumbersAndRanges) {
    tools::DrawSet s;
    std::string err;
    ASSERT_TRUE(tools::parseDrawList("3,10-12", s, err)) << err;
    EXPECT_EQ(s.text(), "3,10-12");
    for (u64 d : {3, 10, 11, 12}) EXPECT_TRUE(s.contains(d)) << d;
    for (u64 d : {1, 2, 4, 9, 13, 1000}) EXPECT_FALSE(s.contains(d)) << d;
    // Overlapping and adjacent items merge; order does not matter.
    ASSERT_TRUE(tools::parseDrawList("12,5-7,8,1-2,6", s, err)) << err;
    EXPECT_EQ(s.text(), "1-2,5-8,12");
    ASSERT_TRUE(tools::parseDrawList("1099511627776", s, err)) << err;  // 2^40, the --replay-end limit
    EXPECT_TRUE(s.contains(u64(1) << 40));
    for (const char* bad : {"", "0", "1,", ",1", "1,,2", "a", "3-", "-3", "5-3", "1 ,2", "+1", "1-2-3", "0x10",
                            "1099511627777", "99999999999999999999"}) {
        err.clear();
        EXPECT_FALSE(tools::parseDrawList(bad, s, err)) << bad;
        EXPECT_FALSE(err.empty()) << bad;
    }
}

TEST(DrawSelect, SkipAndOnlyCombine) {
    std::function<bool(u64)> keep;
    std::string err;
    ASSERT_TRUE(tools::makeDrawFilter(std::nullopt, std::nullopt, keep, err));
    EXPECT_FALSE(keep);  // nothing given: no hook at all
    ASSERT_TRUE(tools::makeDrawFilter(std::string("2"), std::nullopt, keep, err));
    EXPECT_TRUE(keep(1) && !keep(2) && keep(3));
    ASSERT_TRUE(tools::makeDrawFilter(std::nullopt, std::string("2-4"), keep, err));
    EXPECT_TRUE(!keep(1) && keep(2) && keep(4) && !keep(5));
    ASSERT_TRUE(tools::makeDrawFilter(std::string("3"), std::string("2-4"), keep, err));
    EXPECT_TRUE(!keep(1) && keep(2) && !keep(3) && keep(4) && !keep(5));
    EXPECT_FALSE(tools::makeDrawFilter(std::string("2,x"), std::nullopt, keep, err));
    EXPECT_EQ(err.rfind("--skip '2,x': ", 0), 0u) << err;
    EXPECT_FALSE(tools::makeDrawFilter(std::nullopt, std::string(""), keep, err));
    EXPECT_EQ(err.rfind("--only '': ", 0), 0u) << err;
}

// A dump of three draws: blue clear, red rectangle, green rectangle. Leaving draws out changes
// exactly the pixels they cover, in render and in compare (whose MSE is then known exactly).
TEST(DrawSelect, SkipAndOnlyChangeKnownPixels) {
    const fs::path t = tmpDir("select");
    const fs::path dump = writeThreeDrawDump(t);
    auto render = [&](const std::string& sel, tools::Image& img) {
        const fs::path png = t / "f.png";
        fs::remove(png);
        CliRun r = run("render " + quote(dump.string()) + " --backend soft -o " + quote(png.string()) + " " + sel);
        ASSERT_EQ(r.code, 0) << sel << ": " << r.out;
        std::string err;
        ASSERT_TRUE(tools::readImage(png.string(), img, err)) << err;
    };
    const u32 cleared = 0xFF000000u;  // VRAM before the clear: zero
    tools::Image all, img;
    render("", all);
    expectRect(all, kRedRect, kRed, "all");
    expectRect(all, kGreenRect, kGreen, "all");
    EXPECT_EQ(px(all, 0, 0), kBlue);
    EXPECT_EQ(px(all, 479, 271), kBlue);

    render("--skip 2", img);
    expectRect(img, kRedRect, kBlue, "--skip 2", false);  // the clear colour where the red rectangle was
    expectRect(img, kGreenRect, kGreen, "--skip 2");
    render("--only 1", img);
    EXPECT_EQ(inside(img, kRedRect), kBlue);
    EXPECT_EQ(inside(img, kGreenRect), kBlue);
    EXPECT_EQ(px(img, 0, 0), kBlue);
    render("--only 2-3", img);
    expectRect(img, kRedRect, kRed, "--only 2-3");
    expectRect(img, kGreenRect, kGreen, "--only 2-3");
    EXPECT_EQ(px(img, 0, 0), cleared);
    render("--skip 1,3", img);
    expectRect(img, kRedRect, kRed, "--skip 1,3");
    EXPECT_EQ(inside(img, kGreenRect), cleared);
    EXPECT_EQ(px(img, 479, 271), cleared);
    render("--only 1-3 --skip 3", img);
    EXPECT_EQ(inside(img, kRedRect), kRed);
    EXPECT_EQ(inside(img, kGreenRect), kBlue);
    render("--skip 4-100", img);  // draws the dump does not have: nothing changes
    EXPECT_EQ(tools::mseRGB(img, all), 0.0);

    // compare against the full frame as reference: --skip 2 turns 80x70 red pixels blue, each
    // (255² + 255²) of squared difference over 480·272·3 values.
    fs::create_directories(t / "ref");
    std::string err;
    ASSERT_TRUE(tools::writePng((t / "ref" / "three_draws-soft.png").string(), all, err)) << err;
    const std::string cmp = "compare " + quote(dump.string()) + " --backend soft --ref-dir " + quote((t / "ref").string());
    CliRun same = run(cmp + " --json " + quote((t / "a.json").string()));
    ASSERT_EQ(same.code, 0) << same.out;
    CliRun skipped = run(cmp + " --skip 2 --json " + quote((t / "b.json").string()));
    ASSERT_EQ(skipped.code, 0) << skipped.out;
    tools::CompareReport a, b;
    ASSERT_TRUE(tools::parseCompareJson(readText(t / "a.json"), a, err)) << err;
    ASSERT_TRUE(tools::parseCompareJson(readText(t / "b.json"), b, err)) << err;
    ASSERT_EQ(a.rows.size(), 1u);
    ASSERT_EQ(b.rows.size(), 1u);
    EXPECT_EQ(a.rows[0].mse, 0.0);
    EXPECT_DOUBLE_EQ(b.rows[0].mse, 80.0 * 70 * (255.0 * 255 * 2) / (480.0 * 272 * 3));
    // --ref-backend: both sides leave the draw out, so they agree again.
    CliRun both = run("compare " + quote(dump.string()) + " --backend soft --ref-backend soft --skip 2 --max-mse 0");
    EXPECT_EQ(both.code, 0) << both.out;
    CliRun bench = run("bench " + quote(dump.string()) + " --backend soft --repeat 1 --only 1");
    EXPECT_EQ(bench.code, 0) << bench.out;

    // Usage errors: one line, exit 2, naming the option and the bad item.
    for (const char* bad : {"--skip 0", "--skip 2,x", "--only ''", "--only 3-1", "--skip=-1"}) {
        CliRun r = run("render " + quote(dump.string()) + " -o " + quote((t / "x.png").string()) + " " + bad);
        EXPECT_EQ(r.code, 2) << bad << ": " << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_NE(r.out.find(std::string(bad).substr(0, 6)), std::string::npos) << r.out;
    }
    fs::remove_all(t);
}

// A draw left out still had its register changes: the next draw that reaches the backend is
// drawn with them. Draw 1 fills the screen blue (a rectangle, not a clear, so that the backends'
// draw paths see it); the green channel is then write-protected (PMSK1) for
// draw 2, a red rectangle, and draw 3, a green one, which changes no register. With draw 2 left
// out, draw 3 must still find green protected: its rectangle comes out black (R and B from the
// source's 0, G kept from the blue's 0), not green; the backends' caches that follow the
// packets' dirty register groups (the draw front end's transform state, the GL key cache) must
// see the groups of the draw they never got.
TEST(DrawSelect, ALeftOutDrawsRegisterChangesStillApply) {
    const fs::path t = tmpDir("dirty");
    const fs::path dump = writeDump(t / "masked.ppdmp", [](ListBuilder& b) {
        b.fillRect(0, 0, 480, 272, kBlue);
        b.pixelMask(0x00FF00, 0);
        fill(b, kRedRect, kRed);
        fill(b, kGreenRect, kGreen);
    });
    std::string err;
    for (const char* backend : {"--backend soft", "--backend gl", "--backend gl --gl-mode hw"}) {
        for (const char* sel : {"", "--skip 2"}) {
            const fs::path png = t / "f.png";
            fs::remove(png);
            CliRun r = run("render " + quote(dump.string()) + " " + backend + " -o " + quote(png.string()) + " " + sel);
            ASSERT_EQ(r.code, 0) << backend << " " << sel << ": " << r.out;
            tools::Image img;
            ASSERT_TRUE(tools::readImage(png.string(), img, err)) << err;
            const std::string what = std::string(backend) + " " + sel;
            expectRect(img, kGreenRect, 0xFF000000u, what);
            if (*sel) expectRect(img, kRedRect, kBlue, what, false);
            else expectRect(img, kRedRect, kRed, what);
        }
    }
    fs::remove_all(t);
}

// ---- shards and merge (library) ----

TEST(Batch, ShardsTakeEveryNthDumpInNameOrder) {
    tools::Shard s;
    std::string err;
    ASSERT_TRUE(tools::parseShard("2/4", s, err)) << err;
    EXPECT_EQ(s.index, 2u);
    EXPECT_EQ(s.count, 4u);
    for (const char* bad : {"", "0/4", "5/4", "1/0", "2", "/4", "2/", "a/4", "-1/4", "1/100001", "1/4/2", " 1/4"})
        EXPECT_FALSE(tools::parseShard(bad, s, err)) << bad;
    // Name order (file name without .zip/.ppdmp, then the whole path), whatever the given order.
    const std::vector<std::string> given = {"d/e.zip", "x/a.ppdmp", "b/c.ppdmp", "a/a.ppdmp.zip", "f"};
    const auto all = tools::sortDumps(given);
    std::vector<std::string> order;
    for (const auto& d : all) order.push_back(d.path);
    EXPECT_EQ(order, (std::vector<std::string>{"a/a.ppdmp.zip", "x/a.ppdmp", "b/c.ppdmp", "d/e.zip", "f"}));
    for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].index, i + 1);
    const auto s2 = tools::shardDumps(all, tools::Shard{2, 2});
    ASSERT_EQ(s2.size(), 2u);
    EXPECT_EQ(s2[0].path, "x/a.ppdmp");
    EXPECT_EQ(s2[1].path, "d/e.zip");
    EXPECT_EQ(tools::shardDumps(all, tools::Shard{1, 2}).size(), 3u);
    EXPECT_TRUE(tools::shardDumps(all, tools::Shard{7, 8}).empty());
}

namespace {

tools::CompareReport report(u64 index, u64 count, u64 dumps, const std::string& backend = "soft") {
    tools::CompareReport r;
    r.backend = backend;
    r.sharded = true;
    r.shard = {index, count};
    r.dumps = dumps;
    for (u64 k = index; k <= dumps; k += count) {
        tools::CompareRow row;
        row.index = k;
        row.name = "dump \"" + std::to_string(k) + "\"";
        if (k == 3) row.error = "cannot read x/dump-soft.png: No such file or directory";
        else row.mse = 0.1 * double(k), row.psnr = 60.0 - double(k), row.seconds = 0.01 * double(k);
        r.rows.push_back(row);
    }
    return r;
}

}  // namespace

TEST(Batch, MergeRebuildsTheUnshardedReport) {
    // The whole run as one report, and its JSON.
    tools::CompareReport whole = report(1, 1, 7);
    whole.sharded = false;
    const std::string want = tools::compareJson(whole);
    EXPECT_EQ(want.find("\"shard\""), std::string::npos);
    EXPECT_NE(want.find("\"median_seconds\""), std::string::npos);
    // Three shards written to JSON, read back (in any order) and merged.
    std::vector<tools::CompareReport> shards;
    for (u64 i : {3, 1, 2}) {
        tools::CompareReport back;
        std::string err;
        const std::string text = tools::compareJson(report(i, 3, 7));
        EXPECT_NE(text.find("\"shard\": {\"index\": " + std::to_string(i) + ", \"count\": 3, \"dumps\": 7}"),
                  std::string::npos)
            << text;
        ASSERT_TRUE(tools::parseCompareJson(text, back, err)) << err;
        shards.push_back(back);
    }
    const std::vector<std::string> names = {"c.json", "a.json", "b.json"};
    tools::CompareReport merged;
    std::string err;
    ASSERT_TRUE(tools::mergeReports(shards, names, merged, err)) << err;
    EXPECT_EQ(tools::compareJson(merged), want);
    const tools::CompareSummary s = tools::summarize(merged.rows);
    EXPECT_EQ(s.dumps, 7u);
    EXPECT_EQ(s.rendered, 6u);
    EXPECT_EQ(s.within01, 1);
    EXPECT_DOUBLE_EQ(s.medianMse, (0.4 + 0.5) / 2);  // of 0.1 0.2 0.4 0.5 0.6 0.7
    // Without times the same.
    whole.times = false;
    for (auto& r : shards) r.times = false;
    ASSERT_TRUE(tools::mergeReports(shards, names, merged, err)) << err;
    EXPECT_EQ(tools::compareJson(merged), tools::compareJson(whole));
    EXPECT_EQ(tools::compareJson(merged).find("seconds"), std::string::npos);

    // Missing, duplicate, foreign and incomplete shards are refused with a message.
    auto refuse = [&](std::vector<tools::CompareReport> in, const std::string& expect) {
        std::vector<std::string> n;
        for (size_t i = 0; i < in.size(); ++i) n.push_back(std::string("s").append(std::to_string(i)).append(".json"));
        tools::CompareReport out;
        std::string e;
        EXPECT_FALSE(tools::mergeReports(in, n, out, e)) << expect;
        EXPECT_NE(e.find(expect), std::string::npos) << e;
    };
    refuse({report(1, 3, 7), report(3, 3, 7)}, "missing shard 2/3 (2 of 3 given)");
    refuse({report(1, 3, 7)}, "missing shards 2/3, 3/3");
    refuse({report(1, 3, 7), report(2, 3, 7), report(2, 3, 7), report(3, 3, 7)}, "duplicate shard 2/3: s1.json and s2.json");
    refuse({report(1, 2, 7), report(2, 3, 7)}, "not one run");
    refuse({report(1, 2, 7), report(2, 2, 8)}, "run of 8 dumps");
    refuse({report(1, 2, 7), report(2, 2, 7, "gl")}, "'gl' run");
    tools::CompareReport cut = report(2, 2, 7);
    cut.rows.pop_back();
    refuse({report(1, 2, 7), cut}, "result 6 of shard 2/2 is missing");
    tools::CompareReport wrong = report(2, 2, 7);
    wrong.rows[0].index = 1;
    refuse({report(1, 2, 7), wrong}, "does not belong to shard 2/2");
}

TEST(Batch, ProgressLine) {
    EXPECT_EQ(tools::progressText(0, 20, 0.0), "0/20 dumps");
    EXPECT_EQ(tools::progressText(5, 20, 2.0), "5/20 dumps, 2.5/s, ETA 0:06");
    EXPECT_EQ(tools::progressText(1, 400, 1.0), "1/400 dumps, 1.0/s, ETA 6:39");
    EXPECT_EQ(tools::progressText(20, 20, 4.0), "20/20 dumps, 5.0/s, ETA 0:00");
}

// ---- the 20 frametests: 4 shards merged = one unsharded run ----

TEST(Batch, FourShardsOfTheFrametestsMergeToTheUnshardedRun) {
    const fs::path ft = GE2GL_FRAMETESTS_DIR;
    if (!fs::is_directory(ft / "dumps") || !fs::is_directory(ft / "ref")) GTEST_SKIP() << "no frametests at " << ft;
    std::vector<std::string> dumps;
    for (const auto& e : fs::directory_iterator(ft / "dumps")) dumps.push_back(e.path().string());
    ASSERT_GE(dumps.size(), 4u);
    std::sort(dumps.rbegin(), dumps.rend());  // given in reverse: compare orders them itself
    std::string args;
    for (const auto& d : dumps) args += " " + quote(d);
    const fs::path t = tmpDir("shards");
    const std::string base = "compare" + args + " --backend soft --ref-dir " + quote((ft / "ref").string());
    auto j = [&](const std::string& n) { return quote((t / n).string()); };

    for (const char* times : {" --json-no-times", ""}) {
        CliRun whole = run(base + times + " --json " + j("all.json"));
        ASSERT_LE(whole.code, 1) << whole.out;  // 1: some dump failed, still reported
        EXPECT_EQ(whole.out.find('\r'), std::string::npos);  // no progress line off a terminal
        std::string merge = "merge";
        for (int i = 1; i <= 4; ++i) {
            const std::string n = "s" + std::to_string(i) + ".json";
            CliRun s = run(base + times + " --shard " + std::to_string(i) + "/4 --json " + j(n));
            ASSERT_LE(s.code, 1) << s.out;
            EXPECT_NE(s.out.find("shard " + std::to_string(i) + "/4: "), std::string::npos) << s.out;
            merge += " " + j(n);
        }
        CliRun m = run(merge + " -o " + j("merged.json"));
        ASSERT_EQ(m.code, 0) << m.out;
        const std::string all = readText(t / "all.json"), merged = readText(t / "merged.json");
        EXPECT_NE(all.find("\"index\": " + std::to_string(dumps.size()) + ","), std::string::npos) << all;
        // The summary line merge prints is the unsharded run's (less the time with --json-no-times).
        const size_t at = whole.out.find("summary: ");
        ASSERT_NE(at, std::string::npos) << whole.out;
        const std::string summary = whole.out.substr(at, whole.out.find(", median time", at) - at);
        EXPECT_EQ(m.out.rfind(summary, 0), 0u) << m.out << "\nwant: " << summary;
        if (*times) {
            EXPECT_EQ(merged, all);  // byte for byte
            EXPECT_EQ(all.find("seconds"), std::string::npos);
        } else {
            // Times differ from run to run: equal once they are blanked out.
            const std::regex secs("\"(median_)?seconds\": [0-9.e+-]+");
            EXPECT_NE(all.find("\"seconds\": "), std::string::npos);
            EXPECT_EQ(std::regex_replace(merged, secs, "T"), std::regex_replace(all, secs, "T"));
        }
    }
    // A missing shard and a duplicate one: exit 1, one line saying which.
    CliRun missing = run("merge " + j("s1.json") + " " + j("s2.json") + " " + j("s4.json") + " -o " + j("x.json"));
    EXPECT_EQ(missing.code, 1) << missing.out;
    EXPECT_EQ(missing.out, "ge2gl: missing shard 3/4 (3 of 4 given)\n");
    CliRun dup = run("merge " + j("s1.json") + " " + j("s2.json") + " " + j("s3.json") + " " + j("s2.json") + " " +
                     j("s4.json") + " -o " + j("x.json"));
    EXPECT_EQ(dup.code, 1) << dup.out;
    EXPECT_NE(dup.out.find("ge2gl: duplicate shard 2/4: "), std::string::npos) << dup.out;
    EXPECT_FALSE(fs::exists(t / "x.json"));
    // Shards of a different split do not mix.
    CliRun other = run(base + " --shard 1/2 --json " + j("h1.json"));
    ASSERT_LE(other.code, 1) << other.out;
    CliRun mixed = run("merge " + j("h1.json") + " " + j("s2.json") + " " + j("s3.json") + " " + j("s4.json") + " -o " + j("x.json"));
    EXPECT_EQ(mixed.code, 1) << mixed.out;
    EXPECT_NE(mixed.out.find("not one run"), std::string::npos) << mixed.out;
    fs::remove_all(t);
}

// The progress line goes to a terminal only: through script(1)'s pseudo-terminal compare draws
// "k/N dumps" lines rewritten with \r and erases them; off a terminal (the other tests) none.
TEST(Batch, ProgressLineOnATerminalOnly) {
    if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1) to make a terminal";
    const std::string dumps = std::string(GE2GL_SOURCE_DIR) + "/dumps/";
    const std::string cmd = std::string(GE2GL_BINARY_DIR) + "/ge2gl compare " + dumps + "bezier_spline.ppdmp " + dumps +
                            "render_to_texture.ppdmp --backend soft --ref-backend soft >/dev/null";
    CliRun r;
    FILE* p = popen(("script -qec " + quote(cmd) + " /dev/null 2>&1").c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    const int status = pclose(p);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << r.out;
    EXPECT_NE(r.out.find("\r\033[K0/2 dumps"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\r\033[K1/2 dumps, "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\r\033[K2/2 dumps, "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.substr(r.out.size() - 4), "\r\033[K") << r.out;  // erased at the end
}
