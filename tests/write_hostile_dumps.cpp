// SPDX-License-Identifier: MIT
// Writes the hostile dumps of tests/hostile_dumps.h into a folder, for scripts/check_dumps.sh
// (every dump of at most 1 MiB must end cleanly within 10 s and 1 GiB with either backend).
#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/hostile_dumps.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_hostile_dumps DIR\n");
        return 2;
    }
    std::filesystem::create_directories(argv[1]);
    for (const auto& h : ge::hostile::all()) {
        const std::string path = std::string(argv[1]) + "/" + h.name + ".ppdmp";
        std::string err;
        if (!ge::dump::saveDump(path, h.make(), err)) {
            std::fprintf(stderr, "write_hostile_dumps: %s\n", err.c_str());
            return 1;
        }
        std::printf("%s\n", path.c_str());
    }
    return 0;
}
