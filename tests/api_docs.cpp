// SPDX-License-Identifier: MIT
// docs/plugin-api.md's C examples compile as written: every ```c block is a translation unit,
// compiled as strict C99 (and as C++, which hosts also are) against include/.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> cBlocks(const std::string& markdown) {
    std::vector<std::string> blocks;
    std::istringstream in(markdown);
    std::string line, cur;
    bool inC = false;
    while (std::getline(in, line)) {
        if (!inC && line == "```c") {
            inC = true;
            cur.clear();
        } else if (inC && line == "```") {
            inC = false;
            blocks.push_back(cur);
        } else if (inC) {
            cur += line + "\n";
        }
    }
    return blocks;
}

}  // namespace

TEST(ApiDocs, ExamplesCompileAsWritten) {
    if (std::system("cc --version > /dev/null 2>&1") != 0 || std::system("c++ --version > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "no cc/c++ on PATH";
    std::ifstream f(std::string(GE2GL_SOURCE_DIR) + "/docs/plugin-api.md");
    ASSERT_TRUE(f) << "docs/plugin-api.md missing";
    std::stringstream ss;
    ss << f.rdbuf();
    const std::vector<std::string> blocks = cBlocks(ss.str());
    ASSERT_GE(blocks.size(), 4u) << "the page's C examples are gone";
    const std::string tmp = std::string(GE2GL_BINARY_DIR) + "/api_docs_check";
    std::system(("mkdir -p '" + tmp + "'").c_str());
    const std::string flags = " -Wall -Wextra -Werror -pedantic -c -o /dev/null -I'" + std::string(GE2GL_SOURCE_DIR) + "/include' ";
    for (size_t i = 0; i < blocks.size(); ++i) {
        const std::string file = tmp + "/example" + std::to_string(i) + ".c";
        std::ofstream(file) << blocks[i];
        EXPECT_EQ(std::system(("cc -std=c99" + flags + "'" + file + "'").c_str()), 0) << "block " << i << ":\n" << blocks[i];
        EXPECT_EQ(std::system(("c++ -std=c++17 -x c++" + flags + "'" + file + "'").c_str()), 0) << "block " << i << " as C++";
    }
}

// ge2gl.hpp says it needs C++14: it compiles there without warnings, and not with C++11 (so the
// statement stays true if the header starts using something newer, this fails).
TEST(ApiDocs, CppWrapperNeedsCpp14) {
    if (std::system("c++ --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no c++ on PATH";
    const std::string tmp = std::string(GE2GL_BINARY_DIR) + "/api_docs_check";
    std::system(("mkdir -p '" + tmp + "'").c_str());
    const std::string file = tmp + "/wrapper.cpp";
    std::ofstream(file) << "#include \"ge2gl/ge2gl.hpp\"\nint main() { return 0; }\n";
    const std::string cmd = " -Wall -Wextra -Werror -pedantic -fsyntax-only -I'" + std::string(GE2GL_SOURCE_DIR) +
                            "/include' '" + file + "' > /dev/null 2>&1";
    EXPECT_EQ(std::system(("c++ -std=c++14" + cmd).c_str()), 0);
    EXPECT_NE(std::system(("c++ -std=c++11" + cmd).c_str()), 0);
}

// Loading the library without asking for a headless context maps no OSMesa, EGL or LLVM
// (tools/load_probe.c in a fresh process; its cost is the LibraryLoad benchmark's).
TEST(ApiFootprint, LoadingTheLibraryMapsNoGlStack) {
    const std::string probe = std::string(GE2GL_BINARY_DIR) + "/ge2gl_load_probe";
    const std::string lib = std::string(GE2GL_BINARY_DIR) + "/api/libge2gl.so.0";
    FILE* p = popen(("'" + probe + "' '" + lib + "'").c_str(), "r");
    ASSERT_NE(p, nullptr);
    char line[256] = {};
    const bool got = std::fgets(line, sizeof line, p) != nullptr;
    ASSERT_EQ(pclose(p), 0) << line;
    ASSERT_TRUE(got);
    double ms = 0;
    int os = -1, egl = -1, llvm = -1;
    ASSERT_EQ(std::sscanf(line, "load_probe: load_ms=%lf osmesa=%d egl=%d llvm=%d", &ms, &os, &egl, &llvm), 4) << line;
    EXPECT_EQ(os, 0);
    EXPECT_EQ(egl, 0);
    EXPECT_EQ(llvm, 0);
    std::printf("library load + soft create/destroy: %.2f ms\n", ms);
}
