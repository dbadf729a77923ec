// SPDX-License-Identifier: MIT
// The ge2gl CLI as users and scripts drive it: outputs, file formats, exit codes, error lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <sys/wait.h>
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "hle/dump/player.h"
#include "tools/lib/image.h"
#include "tools/lib/png_encode.h"
#include "tools/lib/render.h"
#include "tests/tools_cli_run.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

using clitest::CliRun;
std::string scene(const char* name) { return std::string(GE2GL_SOURCE_DIR) + "/dumps/" + name + ".ppdmp"; }

CliRun run(const std::string& args, bool withStderr = true) { return clitest::runCli(args, withStderr); }

fs::path tmpDir() {
    fs::path d = fs::temp_directory_path() / ("ge2gl_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

size_t countLines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

TEST(Cli, InfoReportsCounts) {
    CliRun r = run("info " + scene("lit_textured_skinned"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("version:   6"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("draws:"), std::string::npos);
    EXPECT_NE(r.out.find("INIT"), std::string::npos);
}

// info --timing: the GE-time estimate of the frame and its parts (docs/timing.md), which add up.
TEST(Cli, InfoTimingReportsTheGeTimeInParts) {
    CliRun r = run("info --timing " + scene("lit_textured_skinned"));
    ASSERT_EQ(r.code, 0) << r.out;
    double total = 0, c = 0, v = 0, p = 0, t = 0, pp = 0;
    const size_t at = r.out.find("GE time:");
    ASSERT_NE(at, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "GE time: %lf ms", &total), 1) << r.out;
    const size_t parts = r.out.find("commands ", at);
    ASSERT_NE(parts, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + parts, "commands %lf ms, vertices %lf ms, pixels %lf ms, transfers %lf ms", &c, &v, &p, &t), 4)
        << r.out;
    const size_t model = r.out.find("PPSSPP's model (no pixel fill): ");
    ASSERT_NE(model, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + model, "PPSSPP's model (no pixel fill): %lf", &pp), 1);
    EXPECT_GT(v, 0.1);   // a lit, skinned scene: vertex work
    EXPECT_GT(p, 0.01);  // and pixels filled
    EXPECT_NEAR(total, c + v + p + t, 0.0021);
    EXPECT_NEAR(pp, total - p, 0.0011);
}

TEST(Cli, DisasmPrintsEveryCommand) {
    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(scene("blend_stencil_logic"), d, err)) << err;
    const dump::DumpSummary s = dump::summarize(d);
    CliRun r = run("disasm " + scene("blend_stencil_logic"), false);
    ASSERT_EQ(r.code, 0);
    // One line per command plus one comment line per non-REGISTERS record.
    EXPECT_EQ(countLines(r.out), s.commands + d.records.size() - s.recordsByType[dump::REGISTERS]);
    EXPECT_NE(r.out.find("PRIM count="), std::string::npos);
}

TEST(Cli, RenderWritesPngDepthAndVram) {
    fs::path t = tmpDir();
    CliRun r = run("render " + scene("lit_textured_skinned") + " --backend soft -o " + (t / "f.png").string() + " --depth-out " +
                (t / "d.bin").string() + " --vram-out " + (t / "v.bin").string() + " --stats");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("draws:"), std::string::npos);
    tools::Image img;
    std::string err;
    ASSERT_TRUE(tools::readImage((t / "f.png").string(), img, err)) << err;
    EXPECT_EQ(img.width, 480);
    EXPECT_EQ(img.height, 272);
    EXPECT_EQ(fs::file_size(t / "d.bin"), 8u + 480 * 272 * 2);
    EXPECT_EQ(fs::file_size(t / "v.bin"), 2u * 1024 * 1024);
    std::ifstream f(t / "d.bin", std::ios::binary);
    u8 hdr[8];
    f.read(reinterpret_cast<char*>(hdr), 8);
    EXPECT_EQ(readLE32(hdr), 480u);
    EXPECT_EQ(readLE32(hdr + 4), 272u);
    // The picture is not blank.
    size_t nonBlack = 0;
    for (u32 p : img.rgba) nonBlack += (p & 0xFFFFFF) != 0;
    EXPECT_GT(nonBlack, 1000u);
    fs::remove_all(t);
}

// GL hardware mode at render scale 2: the PNG is 960x544; compare box-downsamples to 480x272;
// bench with the null GL prints the CPU time per draw. Skipped where no GL context can be made.
TEST(Cli, HardwareModeRendersAtScaleAndBenchesWithNullGl) {
    fs::path t = tmpDir();
    CliRun r = run("render " + scene("render_to_texture") + " --backend gl --gl-mode hw --scale 2 -o " + (t / "s.png").string());
    if (r.code != 0 && r.out.find("GL") != std::string::npos && r.out.find("OSMesa") != std::string::npos)
        GTEST_SKIP() << r.out;
    ASSERT_EQ(r.code, 0) << r.out;
    tools::Image img;
    std::string err;
    ASSERT_TRUE(tools::readImage((t / "s.png").string(), img, err)) << err;
    EXPECT_EQ(img.width, 960);
    EXPECT_EQ(img.height, 544);
    CliRun c = run("compare " + scene("render_to_texture") + " --backend gl --gl-mode hw --scale 2 --ref-backend soft");
    EXPECT_EQ(c.code, 0) << c.out;
    EXPECT_NE(c.out.find("summary: 1 dumps, 1 rendered"), std::string::npos) << c.out;
    CliRun b = run("bench " + scene("render_to_texture") + " --backend gl --gl-mode hw --null-gl --repeat 1");
    EXPECT_EQ(b.code, 0) << b.out;
    EXPECT_NE(b.out.find("us/draw"), std::string::npos) << b.out;
    EXPECT_NE(b.out.find("translator CPU per draw"), std::string::npos) << b.out;
    // --warm reuses one backend per dump (and replays into it again): same draws, no error.
    CliRun w = run("bench " + scene("lit_textured_skinned") + " --backend gl --gl-mode hw --gl-vertices gpu --null-gl --warm --repeat 2");
    EXPECT_EQ(w.code, 0) << w.out;
    EXPECT_NE(w.out.find("translator CPU per draw"), std::string::npos) << w.out;
    CliRun ws = run("bench " + scene("lit_textured_skinned") + " --backend soft --warm --repeat 2");
    EXPECT_EQ(ws.code, 0) << ws.out;
    // Scale needs the hardware mode.
    CliRun e = run("render " + scene("render_to_texture") + " --backend gl --scale 2 -o " + (t / "e.png").string());
    EXPECT_EQ(e.code, 1);
    EXPECT_NE(e.out.find("--gl-mode hw"), std::string::npos) << e.out;
    fs::remove_all(t);
}

// GL program binaries: by default under $XDG_CACHE_HOME/ge2gl/programs, so that a second render
// compiles nothing; --no-program-cache keeps none; --program-cache DIR chooses the place; bench
// uses none unless asked. Skipped where no GL context can be made.
TEST(Cli, ProgramBinariesAreCachedUnderXdgCacheHomeByDefault) {
    const fs::path t = tmpDir() / "xdg";
    fs::remove_all(t);
    auto render = [&](const std::string& extra) {
        return clitest::runCommand("XDG_CACHE_HOME=" + clitest::quote(t.string()) + " " + clitest::cliPath() +
                                   " render " + scene("render_to_texture") + " --backend gl --stats -o " +
                                   clitest::quote((t.parent_path() / "p.png").string()) + extra);
    };
    auto counter = [](const std::string& out, const char* name) {
        const size_t at = out.find(name);
        return at == std::string::npos ? -1L : std::strtol(out.c_str() + at + std::strlen(name), nullptr, 10);
    };
    const CliRun first = render("");
    if (first.code != 0 && first.out.find("OSMesa") != std::string::npos) GTEST_SKIP() << first.out;
    ASSERT_EQ(first.code, 0) << first.out;
    const fs::path dir = t / "ge2gl" / "programs";
    ASSERT_TRUE(fs::is_directory(dir)) << first.out;
    const auto bins = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    EXPECT_GT(counter(first.out, "shaderCompiles"), 0) << first.out;
    EXPECT_EQ(counter(first.out, "diskCacheHits"), 0) << first.out;
    EXPECT_EQ(bins, counter(first.out, "shaderCompiles")) << first.out;
    const CliRun second = render("");
    ASSERT_EQ(second.code, 0) << second.out;
    EXPECT_EQ(counter(second.out, "shaderCompiles"), 0) << second.out;
    EXPECT_EQ(counter(second.out, "diskCacheHits"), counter(first.out, "shaderCompiles")) << second.out;
    const CliRun none = render(" --no-program-cache");
    ASSERT_EQ(none.code, 0) << none.out;
    EXPECT_EQ(counter(none.out, "diskCacheHits"), 0) << none.out;
    EXPECT_GT(counter(none.out, "shaderCompiles"), 0) << none.out;
    const CliRun elsewhere = render(" --program-cache " + clitest::quote((t / "mine").string()));
    ASSERT_EQ(elsewhere.code, 0) << elsewhere.out;
    EXPECT_GT(counter(elsewhere.out, "shaderCompiles"), 0) << elsewhere.out;
    EXPECT_TRUE(fs::is_directory(t / "mine"));
    // Both at once is a usage error.
    EXPECT_EQ(render(" --no-program-cache --program-cache " + clitest::quote(t.string())).code, 2);
    fs::remove_all(t.parent_path());
}

TEST(Cli, ReplayEndStopsEarly) {
    fs::path t = tmpDir();
    CliRun a = run("render " + scene("blend_stencil_logic") + " --backend soft -o " + (t / "a.png").string() + " --replay-end 1");
    CliRun b = run("render " + scene("blend_stencil_logic") + " --backend soft -o " + (t / "b.png").string());
    ASSERT_EQ(a.code, 0) << a.out;
    ASSERT_EQ(b.code, 0) << b.out;
    tools::Image ia, ib;
    std::string err;
    ASSERT_TRUE(tools::readImage((t / "a.png").string(), ia, err));
    ASSERT_TRUE(tools::readImage((t / "b.png").string(), ib, err));
    EXPECT_GT(tools::mseRGB(ia, ib), 0.0);
    fs::remove_all(t);
}

TEST(Cli, CompareAgainstItselfIsExactAndMaxMseFails) {
    fs::path t = tmpDir();
    CliRun r = run("compare " + scene("render_to_texture") + " --backend soft --ref-backend soft --json " + (t / "r.json").string());
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("0.0000"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(t / "r.json"));
    // Against a reference directory of the wrong pictures, --max-mse makes the exit code non-zero.
    fs::create_directories(t / "refs");
    tools::Image white;
    white.width = 480, white.height = 272;
    white.rgba.assign(480 * 272, 0xFFFFFFFFu);
    std::string err;
    ASSERT_TRUE(tools::writePng((t / "refs" / "render_to_texture-soft.png").string(), white, err)) << err;
    CliRun bad = run("compare " + scene("render_to_texture") + " --backend soft --ref-dir " + (t / "refs").string() +
                  " --max-mse 1 --diff-dir " + (t / "diff").string());
    EXPECT_NE(bad.code, 0) << bad.out;
    EXPECT_TRUE(fs::exists(t / "diff" / "render_to_texture-diff.png"));
    fs::remove_all(t);
}

TEST(Cli, ErrorsAreOneLineAndNonZero) {
    CliRun missing = run("info /nonexistent/file.ppdmp");
    EXPECT_NE(missing.code, 0);
    EXPECT_EQ(countLines(missing.out), 1u) << missing.out;
    EXPECT_EQ(missing.out.rfind("ge2gl: ", 0), 0u) << missing.out;

    fs::path t = tmpDir();
    std::ofstream(t / "junk.ppdmp") << "PPSSPPGE\x06garbage";
    CliRun corrupt = run("render " + (t / "junk.ppdmp").string() + " --backend soft -o " + (t / "x.png").string());
    EXPECT_NE(corrupt.code, 0);
    EXPECT_EQ(countLines(corrupt.out), 1u) << corrupt.out;

    CliRun backend = run("render " + scene("bezier_spline") + " --backend vulkan -o " + (t / "x.png").string());
    EXPECT_NE(backend.code, 0);
    EXPECT_EQ(countLines(backend.out), 1u) << backend.out;
    CliRun noArgs = run("");
    EXPECT_NE(noArgs.code, 0);
    fs::remove_all(t);
}

// Numeric arguments are range-checked (no wrap-around), errors name the file once and
// say why (errno text for I/O).
TEST(Cli, NumbersAreRangeCheckedAndErrorsSayWhy) {
    fs::path t = tmpDir();
    const std::string out = " -o " + (t / "x.png").string();
    for (const char* bad : {"-1", "99999999999999999999999", "1e3", "0x10", ""}) {
        CliRun r = run("render " + scene("bezier_spline") + out + " --replay-end '" + bad + "'");
        EXPECT_EQ(r.code, 2) << bad << ": " << r.out;
        EXPECT_NE(r.out.find("--replay-end"), std::string::npos) << r.out;
    }
    EXPECT_EQ(run("render " + scene("bezier_spline") + out + " --replay-end 3").code, 0);
    EXPECT_EQ(run("render " + scene("bezier_spline") + out + " --threads -2").code, 2);
    EXPECT_EQ(run("compare " + scene("bezier_spline") + " --ref-backend soft --max-mse -1").code, 2);

    CliRun missing = run("render /nonexistent/file.ppdmp" + out);
    EXPECT_EQ(countLines(missing.out), 1u) << missing.out;
    const size_t first = missing.out.find("/nonexistent/file.ppdmp");
    ASSERT_NE(first, std::string::npos) << missing.out;
    EXPECT_EQ(missing.out.find("/nonexistent/file.ppdmp", first + 1), std::string::npos) << missing.out;

    if (fs::exists("/dev/full")) {
        CliRun full = run("render " + scene("bezier_spline") + out + " --vram-out /dev/full");
        EXPECT_EQ(full.code, 1);
        EXPECT_NE(full.out.find("/dev/full: No space left on device"), std::string::npos) << full.out;
    }
    fs::remove_all(t);
}

}  // namespace

namespace {

tools::Image testPattern(int w, int h) {
    tools::Image img;
    img.width = w;
    img.height = h;
    img.rgba.resize(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.rgba[size_t(y) * w + x] = (u32(x * 7) & 0xFF) | (u32(y * 13) & 0xFF) << 8 | u32((x ^ y) & 0xFF) << 16 |
                                          u32(255 - ((x + y) & 0x7F)) << 24;
    return img;
}

}  // namespace

TEST(ImageIo, PngRoundTripKeepsEveryByteIncludingAlpha) {
    const fs::path t = tmpDir();
    const tools::Image img = testPattern(37, 19);
    std::string err;
    ASSERT_TRUE(tools::writePng((t / "rt.png").string(), img, err)) << err;
    tools::Image back;
    ASSERT_TRUE(tools::readImage((t / "rt.png").string(), back, err)) << err;
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 19);
    EXPECT_EQ(back.rgba, img.rgba);
}

// The encoder deflates pieces of rows on separate threads (tools/lib/png_encode.cpp): whatever the
// split, the file is one valid PNG that libpng decodes to the same pixels; opaque images are RGB.
TEST(ImageIo, PngPiecesDeflatedOnThreadsMakeOneValidImage) {
    const fs::path t = tmpDir();
    auto roundTrip = [&](const tools::Image& img, int threads, const char* name) {
        const std::vector<u8> png = tools::encodePng(img.rgba.data(), img.width, img.height, threads);
        EXPECT_FALSE(png.empty());
        {
            std::ofstream out(t / name, std::ios::binary | std::ios::trunc);
            out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        }
        tools::Image back;
        std::string err;
        EXPECT_TRUE(tools::readImage((t / name).string(), back, err)) << name << ": " << err;
        EXPECT_EQ(back.width, img.width);
        EXPECT_EQ(back.height, img.height);
        EXPECT_TRUE(back.rgba == img.rgba) << name;
        return png.size() > 25 ? int(png[25]) : -1;  // IHDR colour type
    };
    // 1920 x 1088 is 6 MiB of scanlines: up to 48 pieces of 128 KiB, so every thread count splits.
    tools::Image big = testPattern(1920, 1088);
    tools::Image opaque = big;
    for (u32& p : opaque.rgba) p |= 0xFF000000u;
    for (int threads : {1, 2, 3, 8}) {
        const std::string n = std::to_string(threads);
        EXPECT_EQ(roundTrip(big, threads, ("alpha" + n + ".png").c_str()), 6) << threads;
        EXPECT_EQ(roundTrip(opaque, threads, ("opaque" + n + ".png").c_str()), 2) << threads;
    }
    // More threads than rows, and one pixel.
    EXPECT_EQ(roundTrip(testPattern(700, 3), 8, "wide.png"), 6);
    EXPECT_EQ(roundTrip(testPattern(1, 1), 4, "one.png"), 2);  // its one alpha is 255
    EXPECT_TRUE(tools::encodePng(nullptr, 0, 5, 2).empty());
}

TEST(ImageIo, OtherFormatsGoThroughTheOpenImageIoModule) {
    const fs::path t = tmpDir();
    const tools::Image img = testPattern(16, 9);
    std::string err;
    ASSERT_TRUE(tools::writePng((t / "rt.tif").string(), img, err)) << err;
    tools::Image back;
    ASSERT_TRUE(tools::readImage((t / "rt.tif").string(), back, err)) << err;
    EXPECT_EQ(back.rgba, img.rgba);
    // An extension no format claims is refused with a message, not a crash.
    EXPECT_FALSE(tools::writePng((t / "rt.notaformat").string(), img, err));
    EXPECT_FALSE(err.empty());
}

TEST(ImageIo, DamagedPngsAreRefusedWithAMessage) {
    const fs::path t = tmpDir();
    std::string err;
    ASSERT_TRUE(tools::writePng((t / "ok.png").string(), testPattern(64, 64), err)) << err;
    std::vector<char> bytes(fs::file_size(t / "ok.png"));
    {
        std::ifstream in(t / "ok.png", std::ios::binary);
        in.read(bytes.data(), std::streamsize(bytes.size()));
    }
    // Truncated at several points (the last inside the image data), and with corrupted data. Only
    // the 12-byte IEND trailer may go missing: the image is complete without it.
    for (size_t keep : {size_t(0), size_t(8), size_t(30), bytes.size() / 2, bytes.size() - 20}) {
        {
            std::ofstream out(t / "bad.png", std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(keep));
        }
        tools::Image img;
        err.clear();
        EXPECT_FALSE(tools::readImage((t / "bad.png").string(), img, err)) << "kept " << keep;
        EXPECT_FALSE(err.empty());
    }
    std::vector<char> corrupt = bytes;
    for (size_t i = 40; i < corrupt.size(); i += 17) corrupt[i] = char(corrupt[i] ^ 0x5A);
    {
        std::ofstream out(t / "bad.png", std::ios::binary | std::ios::trunc);
        out.write(corrupt.data(), std::streamsize(corrupt.size()));
    }
    tools::Image img;
    EXPECT_FALSE(tools::readImage((t / "bad.png").string(), img, err));
    EXPECT_FALSE(tools::readImage((t / "missing.png").string(), img, err));
    EXPECT_NE(err.find("missing.png"), std::string::npos);
}

// bench --warm's reuse of one backend (tools/lib/render.h renderDump `backend`): a second replay
// into the same backend and cleared memory gives the frame a fresh backend gives.
TEST(RenderReuse, WarmReplayDrawsTheSameFrame) {
    dump::Dump d;
    std::string err;
    ASSERT_TRUE(dump::loadDump(scene("render_to_texture"), d, err)) << err;
    for (const char* mode : {"soft", "exact", "hw"}) {
        tools::RenderOptions o;
        o.backend = std::string(mode) == "soft" ? "soft" : "gl";
        o.glMode = std::string(mode) == "hw" ? "hw" : "exact";
        o.glVertices = "gpu";
        tools::RenderOutput fresh, first, second;
        if (!tools::renderDump(d, o, fresh, err)) {
            if (o.backend == "gl") GTEST_SKIP() << err;
            FAIL() << err;
        }
        Memory mem;
        backend::Backend be;
        ASSERT_TRUE(tools::renderDump(d, o, first, err, nullptr, nullptr, &mem, &be)) << err;
        ASSERT_TRUE(tools::renderDump(d, o, second, err, nullptr, nullptr, &mem, &be)) << err;
        EXPECT_EQ(tools::mseRGB(fresh.frame, first.frame), 0.0) << mode;
        EXPECT_EQ(tools::mseRGB(fresh.frame, second.frame), 0.0) << mode;
    }
}
