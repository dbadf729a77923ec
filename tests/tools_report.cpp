// SPDX-License-Identifier: MIT
// `ge2gl report` (tools/lib/report.h): the page lists every dump of a compare run with
// its pictures and blame table, compares two runs, and renders in headless Chromium (the browser
// test: images loaded, sorting, a screenshot with the pictures on it).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "tests/tools_cli_run.h"
#include "tools/lib/batch.h"
#include "tools/lib/image.h"
#include "tools/lib/report.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

using clitest::quote;

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void writeText(const fs::path& p, const std::string& s) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f << s;
}

fs::path freshDir(const std::string& name) {
    const fs::path d = fs::path(GE2GL_BINARY_DIR) / ("report_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

// The data-index of the rows of the dumps table, in page order.
std::vector<int> rowOrder(const std::string& page) {
    std::vector<int> out;
    const std::regex re("<tr data-index=\"([0-9]+)\"");
    for (auto it = std::sregex_iterator(page.begin(), page.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back(std::stoi((*it)[1]));
    return out;
}

bool frametestsHere() {
    const fs::path ft = GE2GL_FRAMETESTS_DIR;
    return fs::is_directory(ft / "dumps") && fs::is_directory(ft / "ref");
}

// compare --json over the frametests (soft against PPSSPP's references): `limit` dumps, 0 = all.
std::string frametestRun(const fs::path& dir, size_t limit = 0) {
    const fs::path ft = GE2GL_FRAMETESTS_DIR;
    std::vector<std::string> dumps;
    for (const auto& e : fs::directory_iterator(ft / "dumps")) dumps.push_back(e.path().string());
    std::sort(dumps.begin(), dumps.end());
    if (limit && dumps.size() > limit) dumps.resize(limit);
    std::string args = "compare --backend soft --ref-dir " + quote((ft / "ref").string()) + " --json " +
                       quote((dir / "run.json").string());
    for (const auto& d : dumps) args += " " + quote(d);
    const auto r = clitest::runCli(args);
    EXPECT_EQ(r.code, 0) << r.out;
    return (dir / "run.json").string();
}

// The project's own scenes, soft against soft (identical pictures).
std::string sceneRun(const fs::path& dir) {
    std::string args = "compare --backend soft --ref-backend soft --json " + quote((dir / "run.json").string());
    for (const auto& e : fs::directory_iterator(fs::path(GE2GL_SOURCE_DIR) / "dumps"))
        if (e.path().extension() == ".ppdmp") args += " " + quote(e.path().string());
    const auto r = clitest::runCli(args);
    EXPECT_EQ(r.code, 0) << r.out;
    return (dir / "run.json").string();
}

TEST(Report, FrametestsPageHasEveryDumpPictureAndBlameTable) {
    if (!frametestsHere()) GTEST_SKIP() << "no frametests at " << GE2GL_FRAMETESTS_DIR;
    const fs::path dir = freshDir("frametests");
    // Under the sanitizers (slow, and the accuracy figures add nothing there) the first 5.
    const size_t n = std::getenv("GE2GL_SANITIZER_RUN") ? 5 : 20;
    const std::string json = frametestRun(dir, n);
    tools::CompareReport run;
    std::string err;
    ASSERT_TRUE(tools::parseCompareJson(readText(json), run, err)) << err;
    ASSERT_EQ(run.rows.size(), n);
    const auto r = clitest::runCli("report " + quote(json) + " -o " + quote((dir / "out").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(std::to_string(n) + " dumps, " + std::to_string(n) + " with pictures"), std::string::npos) << r.out;
    const std::string page = readText(dir / "out" / "index.html");
    EXPECT_EQ(rowOrder(page).size(), n);
    size_t differing = 0;
    for (const tools::CompareRow& row : run.rows) {
        SCOPED_TRACE(row.name);
        ASSERT_TRUE(row.error.empty()) << row.error;
        const std::string id = "d" + std::to_string(row.index);
        EXPECT_NE(page.find("<section class=\"dump\" id=\"" + id + "\">"), std::string::npos);
        tools::Image img[4];
        const char* kinds[4] = {"ref", "render", "heat", "blame"};
        for (int k = 0; k < 4; ++k) {
            ASSERT_TRUE(tools::readImage((dir / "out" / "img" / (id + "-" + kinds[k] + ".png")).string(), img[k], err)) << err;
            EXPECT_EQ(img[k].width, 480);
            EXPECT_EQ(img[k].height, 272);
        }
        // The pictures are what compare measured: the same MSE from the written reference and render.
        EXPECT_NEAR(tools::mseRGB(img[1], img[0]), row.mse, 1e-9);
        // The heat map is coloured exactly where reference and render differ.
        size_t coloured = 0, diff = 0;
        for (size_t i = 0; i < img[2].rgba.size(); ++i) {
            const u32 h = img[2].rgba[i];
            coloured += !((h & 0xFF) == ((h >> 8) & 0xFF) && (h & 0xFF) == ((h >> 16) & 0xFF));
            diff += (img[0].rgba[i] & 0xFFFFFF) != (img[1].rgba[i] & 0xFFFFFF);
        }
        EXPECT_EQ(coloured, diff);
        differing += row.mse > 0;
    }
    EXPECT_GT(differing, 0u);
    EXPECT_EQ(count(page, "<table class=\"blame\">"), differing);
    const tools::CompareSummary s = tools::summarize(run.rows);
    EXPECT_NE(page.find("<tr><th>within MSE 0.1</th><td class=\"n\">" + std::to_string(s.within01) + "</td></tr>"),
              std::string::npos);
}

// Two runs: a dump whose MSE fell is "better", one that rose "worse", one that rendered where it
// failed before "fixed"; unchanged dumps are not listed.
TEST(Report, BeforeAndAfterListTheDumpsThatChanged) {
    const fs::path dir = freshDir("before_after");
    const std::string after = sceneRun(dir);
    tools::CompareReport run;
    std::string err;
    ASSERT_TRUE(tools::parseCompareJson(readText(after), run, err)) << err;
    ASSERT_GE(run.rows.size(), 3u);
    tools::CompareReport before = run;
    before.rows[0].mse = 5.0;  // after: 0, better
    before.rows[1].error = "an old failure";  // fixed
    writeText(dir / "before.json", tools::compareJson(before));
    tools::CompareReport worse = run;  // and the other way round: a run where row 0 got worse
    worse.rows[0].mse = 5.0;
    worse.rows[0].psnr = tools::psnrFromMse(5.0);
    writeText(dir / "worse.json", tools::compareJson(worse));

    auto r = clitest::runCli("report " + quote(after) + " --before " + quote((dir / "before.json").string()) + " -o " +
                             quote((dir / "out").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    std::string page = readText(dir / "out" / "index.html");
    EXPECT_NE(page.find("<span class=\"better\">1 better</span>"), std::string::npos);
    EXPECT_NE(page.find("<span class=\"fixed\">1 fixed</span>"), std::string::npos);
    EXPECT_NE(page.find("<tr data-verdict=\"better\"><td data-v=\"" + run.rows[0].name + "\">"), std::string::npos);
    EXPECT_NE(page.find("<tr data-verdict=\"fixed\"><td data-v=\"" + run.rows[1].name + "\">"), std::string::npos);
    EXPECT_EQ(count(page, "<tr data-verdict="), 2u);

    r = clitest::runCli("report " + quote((dir / "worse.json").string()) + " --before " + quote(after) + " -o " +
                        quote((dir / "out2").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    page = readText(dir / "out2" / "index.html");
    EXPECT_NE(page.find("<span class=\"worse\">1 worse</span>"), std::string::npos);
    EXPECT_NE(page.find("<tr data-verdict=\"worse\"><td data-v=\"" + run.rows[0].name + "\">"), std::string::npos);
    // The worse run's MSE of 5 was not measured by this build: the page says what this render gives.
    EXPECT_NE(page.find("(this render: MSE 0.0000)"), std::string::npos);

    EXPECT_TRUE(tools::mseChanged(0.10, 0.12));
    EXPECT_FALSE(tools::mseChanged(0.1, 0.1005));   // under 1%
    EXPECT_FALSE(tools::mseChanged(0.0, 0.00005));  // under 1e-4
}

TEST(Report, UnreadableResultsAreAnError) {
    const fs::path dir = freshDir("errors");
    writeText(dir / "bad.json", "{\"backend\": 3}");
    auto r = clitest::runCli("report " + quote((dir / "bad.json").string()) + " -o " + quote((dir / "out").string()));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("ge2gl: " + (dir / "bad.json").string() + ": no \"backend\" string"), std::string::npos) << r.out;
    r = clitest::runCli("report " + quote((dir / "missing.json").string()) + " -o " + quote((dir / "out").string()));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("cannot read"), std::string::npos) << r.out;
}

// The browser test. Chromium is not part of the build; CI installs Debian's package (.ci/run) and
// sets GE2GL_REQUIRE_CHROMIUM=1, so that there a missing browser fails instead of skipping.
std::string chromium() {
    if (const char* c = std::getenv("GE2GL_CHROMIUM")) return c;
    for (const char* c : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
        if (fs::exists(c)) return c;
    return {};
}

TEST(Report, RendersInHeadlessChromium) {
    const std::string browser = chromium();
    if (browser.empty()) {
        const char* req = std::getenv("GE2GL_REQUIRE_CHROMIUM");
        if (req && std::string(req) == "1") FAIL() << "GE2GL_REQUIRE_CHROMIUM=1 but no Chromium found";
        GTEST_SKIP() << "missing: headless Chromium (install Debian's chromium) — the report's browser test did not run";
    }
    const fs::path dir = freshDir("chromium");
    const std::string json = frametestsHere() ? frametestRun(dir, 6) : sceneRun(dir);
    tools::CompareReport run;
    std::string err;
    ASSERT_TRUE(tools::parseCompareJson(readText(json), run, err)) << err;
    const auto r = clitest::runCli("report " + quote(json) + " -o " + quote((dir / "out").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string url = "file://" + fs::absolute(dir / "out" / "index.html").string();
    const std::string flags = " --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars "
                              "--user-data-dir=" + quote((dir / "profile").string()) + " --virtual-time-budget=10000 ";

    // The DOM after load: every image decoded, and the table sorted by MSE, largest first.
    const auto dom = clitest::runCommand(quote(browser) + flags + "--dump-dom " + quote(url + "#sort=mse-desc"), false);
    ASSERT_EQ(dom.code, 0) << dom.out;
    const size_t images = run.rows.size() * 4;
    EXPECT_NE(dom.out.find("data-images-loaded=\"" + std::to_string(images) + "\" data-images-total=\"" +
                           std::to_string(images) + "\""),
              std::string::npos)
        << dom.out.substr(0, 2000);
    EXPECT_NE(dom.out.find("data-sorted=\"mse-desc\""), std::string::npos);
    std::vector<const tools::CompareRow*> byMse;
    for (const auto& row : run.rows) byMse.push_back(&row);
    std::stable_sort(byMse.begin(), byMse.end(), [](auto* a, auto* b) { return a->mse > b->mse; });
    std::vector<int> want;
    for (auto* row : byMse) want.push_back(int(row->index));
    EXPECT_EQ(rowOrder(dom.out), want);

    // A screenshot tall enough to hold the summary, the table and the first dump's four pictures:
    // the pictures must be on it (many saturated pixels; a page of text alone has almost none).
    const fs::path shot = dir / "shot.png";
    const auto s = clitest::runCommand(quote(browser) + flags + "--window-size=1280,2200 --screenshot=" +
                                       quote(shot.string()) + " " + quote(url));
    ASSERT_EQ(s.code, 0) << s.out;
    tools::Image img;
    ASSERT_TRUE(tools::readImage(shot.string(), img, err)) << err << "\n" << s.out;
    EXPECT_EQ(img.width, 1280);
    EXPECT_EQ(img.height, 2200);
    size_t saturated = 0;
    for (u32 p : img.rgba) {
        const int r8 = p & 0xFF, g8 = (p >> 8) & 0xFF, b8 = (p >> 16) & 0xFF;
        saturated += std::max({r8, g8, b8}) - std::min({r8, g8, b8}) > 40;
    }
    EXPECT_GT(saturated, 20000u);
    std::cout << "screenshot: " << saturated << " saturated pixels of " << img.rgba.size() << "\n";
}

}  // namespace
