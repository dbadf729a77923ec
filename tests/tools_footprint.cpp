// SPDX-License-Identifier: MIT
// What a process that does not draw with GL carries: the GL stack (libOSMesa, libEGL and the
// libLLVM behind llvmpipe, ~60 MiB and ~0.1 s to map) is dlopen()ed by translator/gl_context.cpp
// only when a GL context is created, so rendering with the software model, in this
// process or through the CLI, must not map it.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tools/lib/render.h"

using namespace ge;
namespace fs = std::filesystem;

namespace {

const char* const kGlStack[] = {"libOSMesa", "libEGL", "libLLVM"};

// Lines of `text` that name a library of the GL stack.
std::vector<std::string> glStackLines(const std::string& text) {
    std::vector<std::string> hits;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(pos, end - pos);
        for (const char* lib : kGlStack)
            if (line.find(lib) != std::string::npos) {
                hits.push_back(line);
                break;
            }
        pos = end + 1;
    }
    return hits;
}

std::string readAll(const std::string& path) {
    std::ifstream f(path);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::string scene(const char* name) { return std::string(GE2GL_SOURCE_DIR) + "/dumps/" + name + ".ppdmp"; }
std::string cli() { return std::string(GE2GL_BINARY_DIR) + "/ge2gl"; }

fs::path tmpDir() {
    fs::path d = fs::temp_directory_path() / ("ge2gl_footprint_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// Runs the CLI with the dynamic loader reporting every library it loads (LD_DEBUG=files, on
// stderr, merged into the returned text), including those opened later with dlopen().
std::string runTracingLoads(const std::string& args, int& code) {
    const std::string cmd = "LD_DEBUG=files " + cli() + " " + args + " 2>&1";
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) {
        code = -1;
        return out;
    }
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
    const int status = pclose(p);
    code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

// ctest runs each test in a process of its own; run as one process, this binary's in-process GL
// renders (RenderReuse) may come first and map the GL stack, which then says nothing here.
TEST(Footprint, SoftRenderInProcessMapsNoGlStack) {
    if (!glStackLines(readAll("/proc/self/maps")).empty())
        GTEST_SKIP() << "an earlier test in this process mapped the GL stack";
    tools::RenderOptions opt;
    opt.backend = "soft";
    tools::RenderOutput out;
    std::string err;
    ASSERT_TRUE(tools::renderDumpFile(scene("lit_textured_skinned"), opt, out, err)) << err;
    ASSERT_EQ(out.frame.width, 480);
    const std::string maps = readAll("/proc/self/maps");
    ASSERT_FALSE(maps.empty());
    ASSERT_NE(maps.find("libc.so"), std::string::npos) << "unexpected /proc/self/maps format";
    const auto hits = glStackLines(maps);
    EXPECT_TRUE(hits.empty()) << "mapped after a soft render:\n" << joined(hits);
}

TEST(Footprint, VersionAndSoftRenderProcessesLoadNoGlStack) {
    int code = -1;
    const std::string version = runTracingLoads("--version", code);
    ASSERT_EQ(code, 0) << version;
    // The trace must be there for the absence below to mean anything.
    ASSERT_NE(version.find("file=libc.so"), std::string::npos) << "LD_DEBUG=files gave no trace:\n" << version;
    EXPECT_TRUE(glStackLines(version).empty()) << "ge2gl --version loaded:\n" << joined(glStackLines(version));

    const fs::path png = tmpDir() / "soft.png";
    const std::string render = runTracingLoads("render " + scene("render_to_texture") + " --backend soft -o " + png.string(), code);
    ASSERT_EQ(code, 0) << render;
    EXPECT_TRUE(fs::exists(png));
    EXPECT_TRUE(glStackLines(render).empty()) << "ge2gl render --backend soft loaded:\n" << joined(glStackLines(render));
    fs::remove_all(png.parent_path());
}

#ifdef GE2GL_HAVE_GL
// The other side: a GL render does load OSMesa (and the trace shows it), so the checks above can
// see the stack when it is there.
TEST(Footprint, GlRenderProcessLoadsOsmesaOnDemand) {
    int code = -1;
    const fs::path png = tmpDir() / "gl.png";
    const std::string render = runTracingLoads("render " + scene("render_to_texture") + " --backend gl --context osmesa -o " + png.string(), code);
    EXPECT_NE(render.find("file=libOSMesa"), std::string::npos) << render.substr(0, 4000);
    fs::remove_all(png.parent_path());
}
#endif

}  // namespace
