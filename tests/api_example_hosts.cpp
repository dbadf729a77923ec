// SPDX-License-Identifier: MIT
// The API 1.2 example hosts run as an emulator author would run them (examples/egl_host.c,
// examples/threaded_host.c), their outputs checked:
//   - egl_host draws through GE2GL_BACKEND_GL_CURRENT on its own EGL context, checks its GL state
//     around every ge2gl call and presents ge2gl_frame_texture_sized 1:1 into a PPM: the picture must
//     equal `ge2gl render --backend gl --context egl --gl-mode hw --scale 2` pixel for pixel;
//   - threaded_host runs the GE on one thread and the game on another, with callbacks that wait on
//     the game thread (and, with --hold, ge2gl_interrupt_ack): every list, signal and finish must
//     arrive, without a deadlock, and the peek-sync latencies it measured are reported.
#include <gtest/gtest.h>

#include <cstdlib>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/tools_cli_run.h"
#include "tools/lib/image.h"

namespace fs = std::filesystem;

namespace {

using clitest::runCommand;
using HostRun = clitest::CliRun;

std::string quoted(const std::string& s) { return clitest::quote(s); }
std::string exampleBinary(const char* name) { return std::string(GE2GL_BINARY_DIR) + "/examples/" + name; }
std::string cliBinary() { return std::string(GE2GL_BINARY_DIR) + "/ge2gl"; }
std::string dumpPath(const std::string& name) { return std::string(GE2GL_SOURCE_DIR) + "/dumps/" + name + ".ppdmp"; }
bool isFile(const std::string& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

fs::path outDir() {
    fs::path d = fs::path(GE2GL_BINARY_DIR) / ("api_example_hosts_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// Binary PPM (P6, maxval 255) as written by egl_host: RGB triples, top row first.
bool readPpm(const std::string& path, int& w, int& h, std::vector<unsigned char>& rgb, std::string& err) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        err = "cannot open " + path;
        return false;
    }
    std::string magic;
    int maxval = 0;
    f >> magic >> w >> h >> maxval;
    if (magic != "P6" || w <= 0 || h <= 0 || maxval != 255) {
        err = path + ": not an 8-bit binary PPM";
        return false;
    }
    f.get();  // the single whitespace after maxval
    rgb.resize(size_t(w) * h * 3);
    if (!f.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size()))) {
        err = path + ": truncated";
        return false;
    }
    return true;
}

// ---- egl_host against the CLI ------------------------------------------------------------------

class ApiExampleEglHost : public ::testing::TestWithParam<const char*> {};

TEST_P(ApiExampleEglHost, PresentsWhatTheCliRendersAtScaleTwo) {
    const std::string host = exampleBinary("egl_host"), cli = cliBinary(), dump = dumpPath(GetParam());
    if (!isFile(host)) GTEST_SKIP() << "egl_host not built (" << host << ")";
    if (!isFile(cli)) GTEST_SKIP() << "the ge2gl CLI not built (" << cli << ")";
    const fs::path dir = outDir();
    const std::string ppm = (dir / (std::string(GetParam()) + "_egl_host.ppm")).string();
    const std::string png = (dir / (std::string(GetParam()) + "_cli.png")).string();

    // Under the sanitizers, egl_host's own EGL set-up leaves Mesa's process-lifetime allocations
    // that LeakSanitizer cannot attribute (no frames past the driver); the library's leak checks
    // on the same paths run in this binary (ApiGlContext, with tests/lsan_suppressions.cpp).
    const std::string env = std::getenv("GE2GL_SANITIZER_RUN") ? "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 " : "";
    HostRun r = runCommand(env + quoted(host) + " " + quoted(dump) + " " + quoted(ppm) + " --scale 2");
    if (r.code == 77) GTEST_SKIP() << "egl_host: no EGL surfaceless GL 3.3 context here:\n" << r.out;
    ASSERT_EQ(r.code, 0) << r.out;
    std::cout << r.out;

    HostRun c = runCommand(quoted(cli) + " render " + quoted(dump) +
                           " --backend gl --context egl --gl-mode hw --scale 2 -o " + quoted(png));
    ASSERT_EQ(c.code, 0) << c.out;

    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    std::string err;
    ASSERT_TRUE(readPpm(ppm, w, h, rgb, err)) << err;
    ge::tools::Image ref;
    ASSERT_TRUE(ge::tools::readImage(png, ref, err)) << err;
    ASSERT_EQ(w, ref.width);
    ASSERT_EQ(h, ref.height);
    EXPECT_EQ(w, 960);
    EXPECT_EQ(h, 544);

    size_t differing = 0;
    std::ostringstream first;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const unsigned char* p = &rgb[(size_t(y) * w + x) * 3];
            const ge::u32 q = ref.at(x, y);
            const unsigned qr = q & 0xFF, qg = (q >> 8) & 0xFF, qb = (q >> 16) & 0xFF;
            if (p[0] != qr || p[1] != qg || p[2] != qb) {
                if (differing < 8)
                    first << "  (" << x << ", " << y << "): egl_host " << unsigned(p[0]) << "," << unsigned(p[1]) << ","
                          << unsigned(p[2]) << "  cli " << qr << "," << qg << "," << qb << "\n";
                ++differing;
            }
        }
    EXPECT_EQ(differing, 0u) << "pixels differing between egl_host's PPM and the CLI's PNG, first ones:\n"
                             << first.str();
    if (!HasFailure()) {
        fs::remove(ppm);
        fs::remove(png);
        std::error_code ec;
        fs::remove(dir, ec);  // only when empty
    }
}

INSTANTIATE_TEST_SUITE_P(Dumps, ApiExampleEglHost, ::testing::Values("render_to_texture", "lit_textured_skinned"),
                         [](const ::testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

// ---- threaded_host -------------------------------------------------------------------------------

// The line "threaded_host: lists=... wall_s=..." as key -> value.
std::map<std::string, std::string> resultLine(const std::string& out) {
    std::map<std::string, std::string> kv;
    const std::string tag = "threaded_host: lists=";
    const size_t at = out.rfind(tag);
    if (at == std::string::npos) return kv;
    const size_t start = at + std::strlen("threaded_host: "), end = out.find('\n', start);
    std::istringstream line(out.substr(start, end == std::string::npos ? std::string::npos : end - start));
    std::string field;
    while (line >> field) {
        const size_t eq = field.find('=');
        if (eq != std::string::npos) kv[field.substr(0, eq)] = field.substr(eq + 1);
    }
    return kv;
}

class ApiExampleThreadedHost : public ::testing::TestWithParam<bool> {};

TEST_P(ApiExampleThreadedHost, ThousandListsWithWaitingCallbacks) {
    const std::string host = exampleBinary("threaded_host");
    if (!isFile(host)) GTEST_SKIP() << "threaded_host not built (" << host << ")";
    const bool hold = GetParam();
    HostRun r = runCommand(quoted(host) + " --lists 1000" + (hold ? " --hold" : ""));
    ASSERT_NE(r.code, 3) << "threaded_host's watchdog fired (a deadlock between the GE and CPU threads):\n" << r.out;
    ASSERT_EQ(r.code, 0) << r.out;
    auto kv = resultLine(r.out);
    ASSERT_FALSE(kv.empty()) << "no result line in:\n" << r.out;
    EXPECT_EQ(kv["lists"], "1000");
    EXPECT_EQ(kv["signals"], "1000");
    EXPECT_EQ(kv["finishes"], "1000");
    EXPECT_GT(std::stol(kv.count("peeks") ? kv["peeks"] : "0"), 0);
    for (const char* key : {"peeks", "peek_us_median", "peek_us_max", "wall_s"})
        if (kv.count(key)) RecordProperty(key, kv[key]);
    std::cout << "threaded_host" << (hold ? " --hold" : "") << ": peeks=" << kv["peeks"]
              << " peek_us_median=" << kv["peek_us_median"] << " peek_us_max=" << kv["peek_us_max"]
              << " wall_s=" << kv["wall_s"] << "\n";
}

INSTANTIATE_TEST_SUITE_P(Modes, ApiExampleThreadedHost, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) {
                             return std::string(i.param ? "HoldInterrupts" : "CallbackWaits");
                         });

}  // namespace
