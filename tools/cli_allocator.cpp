// SPDX-License-Identifier: MIT
// The ge2gl CLI's memory allocator (tools/CMakeLists.txt, GE2GL_CLI_JEMALLOC): jemalloc asked to
// back its memory with transparent huge pages.
//
// Why: a `ge2gl render` process lives a fraction of a second, and much of that is the kernel
// faulting in fresh 4 KiB pages one by one: the render targets, the emulated memory, and above all
// Mesa's own allocations (llvmpipe's textures and tiles, the GLSL compiler's heap). With 2 MiB
// pages a GL exact render of Valkyria Chronicles takes 6,100 minor faults instead of 23,400, and
// over the 20 frametests (five alternating runs each, medians) the whole process is 12 % faster in
// the exact mode, 8 % in the hardware mode, 1 % with the software model, for 15-20 % more peak
// RSS (docs/benchmarks.md, "Sixth round"). jemalloc without huge pages was 5 % slower than glibc's
// malloc, so the setting, not the allocator, is the gain; glibc can only be told the same through
// the GLIBC_TUNABLES environment variable, which a program cannot set for itself.
// Only the CLI gets this: libge2gl leaves the allocator to its host.
//
// The setting is jemalloc's documented `malloc_conf` symbol, read at its first allocation; the
// MALLOC_CONF environment variable still overrides it (MALLOC_CONF=thp:default turns it off).
#include <jemalloc/jemalloc.h>

#include <string>

extern "C" {
// jemalloc(3), "TUNING": thp:always marks the arenas' memory MADV_HUGEPAGE (the host's THP mode
// "madvise" then grants it), metadata_thp:always does the same for jemalloc's own bookkeeping.
const char* malloc_conf = "thp:always,metadata_thp:always";
}

namespace ge::tools {

// For --version: the allocator this process really runs with, as jemalloc reports it.
std::string allocatorDescription() {
    const char* thp = nullptr;
    size_t len = sizeof thp;
    if (mallctl("opt.thp", &thp, &len, nullptr, 0) != 0 || !thp) return "allocator: jemalloc";
    return std::string("allocator: jemalloc (thp:") + thp + ")";
}

}  // namespace ge::tools
