// SPDX-License-Identifier: MIT
// LeakSanitizer suppressions for the test binaries (and the sanitizer build of the ge2gl CLI): Mesa's OSMesa/llvmpipe/EGL keep a few process-lifetime
// allocations (driver screens, LLVM state) that are never freed; they are not ge2gl leaks.
// Compiled into every test binary (GL backends appear in test_gl, test_api and the tools tests);
// the hook is looked up by the sanitizer runtime when it is present.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa\n"
           "leak:libLLVM\n"
           "leak:libgallium\n"
           "leak:libEGL_mesa\n"
           "leak:libglapi\n"
           "leak:swrast_dri\n"
           "leak:libdrm\n";
}
