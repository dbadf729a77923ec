// SPDX-License-Identifier: MIT
// ge2gl_mutate: writes the seeded mutant of a dump (tools/lib/mutate.h) for scripts/fuzz_mutate.sh.
//   ge2gl_mutate SEED IN OUT     IN: a .ppdmp or a .zip holding one; OUT: the mutant (.ppdmp)
// Prints one line per mutation applied. Exit status 0, or 1 with a message when IN cannot be
// loaded or OUT written.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "tools/lib/mutate.h"

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: ge2gl_mutate SEED IN OUT\n");
        return 2;
    }
    char* end = nullptr;
    errno = 0;
    const unsigned long long seed = std::strtoull(argv[1], &end, 0);
    if (errno || !end || *end) {
        std::fprintf(stderr, "ge2gl_mutate: bad seed '%s'\n", argv[1]);
        return 2;
    }
    ge::dump::Dump d;
    std::string err;
    if (!ge::dump::loadDump(argv[2], d, err)) {
        std::fprintf(stderr, "ge2gl_mutate: %s: %s\n", argv[2], err.c_str());
        return 1;
    }
    const ge::tools::Mutant m = ge::tools::mutateDump(d, seed);
    const std::vector<ge::u8> bytes = ge::tools::mutantFile(m);
    std::FILE* f = std::fopen(argv[3], "wb");
    if (!f || (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) || std::fclose(f) != 0) {
        std::fprintf(stderr, "ge2gl_mutate: cannot write %s\n", argv[3]);
        return 1;
    }
    for (const std::string& s : m.steps) std::printf("%s\n", s.c_str());
    if (m.truncate) std::printf("file cut to %zu bytes\n", bytes.size());
    return 0;
}
