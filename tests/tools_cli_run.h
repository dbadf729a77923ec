// SPDX-License-Identifier: MIT
// Test helper: runs the ge2gl CLI of this build, or any command line, and collects its output
// (the tools tests and the API example-host tests).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace clitest {

struct CliRun {
    int code = -1;    // exit status, -1 when it did not exit normally
    std::string out;  // stdout (and stderr unless left out)
};

inline std::string cliPath() { return std::string(GE2GL_BINARY_DIR) + "/ge2gl"; }

// `s` in single quotes for the shell, quotes inside escaped.
inline std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// Any shell command line; stderr joins stdout unless `withStderr` is false (then it is dropped).
// Through a pipe, so neither is a terminal.
inline CliRun runCommand(const std::string& cmdLine, bool withStderr = true) {
    CliRun r;
    const std::string cmd = cmdLine + (withStderr ? " 2>&1" : " 2>/dev/null");
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// `ge2gl ARGS` of this build.
inline CliRun runCli(const std::string& args, bool withStderr = true) {
    return runCommand(cliPath() + " " + args, withStderr);
}

}  // namespace clitest
