/* SPDX-License-Identifier: MIT */
/*
 * ge2gl_load_probe: what loading libge2gl costs a host that does not ask for a headless GL
 * context. In a fresh process: dlopen the library, create and destroy a software-backend
 * context, then look at /proc/self/maps. Prints one line:
 *   load_probe: load_ms=<dlopen+create+destroy> osmesa=<0|1> egl=<0|1> llvm=<0|1>
 * Used by test_api (ApiFootprint) and ge2gl_bench (LibraryLoad). Exit 0 when it ran.
 *
 *   usage: ge2gl_load_probe PATH/TO/libge2gl.so.0
 */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "ge2gl/ge2gl.h"

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

typedef void (*config_init_fn)(ge2gl_config*);
typedef ge2gl_status (*create_fn)(const ge2gl_config*, ge2gl_context**);
typedef void (*destroy_fn)(ge2gl_context*);

int main(int argc, char** argv) {
    double t0, t1;
    void* lib;
    config_init_fn init;
    create_fn create;
    destroy_fn destroy;
    ge2gl_config cfg;
    ge2gl_context* h = NULL;
    FILE* maps;
    char line[4096];
    int osmesa = 0, egl = 0, llvm = 0;
    if (argc < 2) {
        fprintf(stderr, "usage: ge2gl_load_probe LIBGE2GL\n");
        return 2;
    }
    t0 = now_ms();
    lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "load_probe: %s\n", dlerror());
        return 1;
    }
    /* POSIX allows this conversion of dlsym's result; C99 -pedantic does not know it. */
    *(void**)&init = dlsym(lib, "ge2gl_config_init");
    *(void**)&create = dlsym(lib, "ge2gl_create");
    *(void**)&destroy = dlsym(lib, "ge2gl_destroy");
    if (!init || !create || !destroy) {
        fprintf(stderr, "load_probe: missing entry points\n");
        return 1;
    }
    init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    if (create(&cfg, &h) != GE2GL_OK) {
        fprintf(stderr, "load_probe: ge2gl_create failed\n");
        return 1;
    }
    destroy(h);
    t1 = now_ms();
    maps = fopen("/proc/self/maps", "r");
    while (maps && fgets(line, sizeof line, maps)) {
        if (strstr(line, "libOSMesa")) osmesa = 1;
        if (strstr(line, "libEGL")) egl = 1;
        if (strstr(line, "libLLVM")) llvm = 1;
    }
    if (maps) fclose(maps);
    printf("load_probe: load_ms=%.3f osmesa=%d egl=%d llvm=%d\n", t1 - t0, osmesa, egl, llvm);
    return 0;
}
