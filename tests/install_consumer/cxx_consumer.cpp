// SPDX-License-Identifier: MIT
// The C++ wrapper header of an installed ge2gl compiles and links in a C++17 host: a null-backend
// context created through ge2gl::Context (RAII over the C ABI).
#include <ge2gl/ge2gl.h>
#include <ge2gl/ge2gl.hpp>

#include <cstdio>

int main() {
    ge2gl_config cfg;
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_NULL;
    auto ctx = ge2gl::Context::create(cfg);
    if (!ctx) {
        std::fprintf(stderr, "install_consumer_cxx: FAIL: Context::create: %s\n", ctx.message.c_str());
        return 1;
    }
    std::printf("install_consumer_cxx: OK\n");
    return 0;
}
