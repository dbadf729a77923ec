/* SPDX-License-Identifier: MIT */
/*
 * install_consumer: a host built against an installed ge2gl, the way an emulator would build
 * (scripts/check_install.sh): through the CMake package (find_package(ge2gl) → ge2gl::ge2gl),
 * with plain `cc $(pkg-config --cflags --libs ge2gl)`, and from a parent project that
 * add_subdirectory()s the source tree. C99, C ABI only.
 *
 * It creates a software-backend context with ge2gl-owned memory, writes a display list into guest
 * RAM with ge2gl_mem_write (frame buffer setup, a CLEAR-mode sprite over the whole screen, then a
 * flat sprite over part of it, FINISH, END), runs it with sceGeDrawSync and checks the FINISH
 * callback, the list state and pixels of the frame read back. Exit status 0 only when all agree.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ge2gl/ge2gl.h>

#define LIST_ADDR 0x08800000u
#define VERTS_ADDR 0x08810000u
#define VRAM_ADDR 0x04000000u
#define WIDTH 480
#define HEIGHT 272
#define STRIDE 512

/* Vertex colours are ABGR; ge2gl_read_frame gives R, G, B, A bytes. */
#define CLEAR_ABGR 0xFF402010u
#define SPRITE_ABGR 0xFF00C0FFu
#define SPRITE_X0 100
#define SPRITE_Y0 50
#define SPRITE_X1 200
#define SPRITE_Y1 150

/* VTYPE: through mode, 8888 colour, 16-bit positions (12 bytes a vertex). */
#define VTYPE_THROUGH_C8888_P16 ((1u << 23) | (7u << 2) | (2u << 7))

static int failures = 0;

#define EXPECT(cond, ...)                                     \
    do {                                                      \
        if (!(cond)) {                                        \
            fprintf(stderr, "install_consumer: FAIL: ");      \
            fprintf(stderr, __VA_ARGS__);                     \
            fputc('\n', stderr);                              \
            ++failures;                                       \
        }                                                     \
    } while (0)

static void put32(uint8_t* p, uint32_t v) {
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* A display list assembled on the host, then copied into guest RAM in one ge2gl_mem_write. */
typedef struct list_writer {
    uint8_t bytes[256];
    uint32_t size;
} list_writer;

static void emit(list_writer* w, uint32_t op, uint32_t arg) {
    put32(w->bytes + w->size, (op << 24) | (arg & 0xFFFFFFu));
    w->size += 4;
}

static void put_vertex(uint8_t* p, uint32_t abgr, int x, int y) {
    put32(p, abgr);
    put32(p + 4, ((uint32_t)(uint16_t)y << 16) | (uint16_t)x);
    put32(p + 8, 0); /* z = 0, padding */
}

static void on_finish(void* user, const ge2gl_interrupt* irq) {
    int* finished = (int*)user;
    (void)irq;
    ++*finished;
}

static void on_error(void* user, int32_t list_id, uint32_t pc, const char* message) {
    (void)user;
    fprintf(stderr, "install_consumer: GE error in list %d at 0x%08x: %s\n", (int)list_id, (unsigned)pc, message);
    ++failures;
}

static int pixel_is(const uint8_t* rgba, int x, int y, uint32_t abgr) {
    const uint8_t* p = rgba + ((size_t)y * WIDTH + (size_t)x) * 4;
    return p[0] == (uint8_t)abgr && p[1] == (uint8_t)(abgr >> 8) && p[2] == (uint8_t)(abgr >> 16);
}

int main(void) {
    ge2gl_config cfg;
    ge2gl_context* h = NULL;
    ge2gl_status st;
    list_writer w;
    uint8_t verts[48];
    uint8_t* rgba = (uint8_t*)malloc((size_t)WIDTH * HEIGHT * 4);
    int32_t cbid = -1, list_id = -1, state = -1;
    int finished = 0;
    uint32_t version = ge2gl_api_version();

    if (!rgba) return 1;
    EXPECT(version >> 16 == GE2GL_API_VERSION_MAJOR && (version & 0xFFFFu) >= GE2GL_API_VERSION_MINOR,
           "library API version 0x%08x, header 0x%08x", (unsigned)version, (unsigned)GE2GL_API_VERSION);

    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.soft_threads = 1;
    cfg.callbacks.user = &finished;
    cfg.callbacks.finish = on_finish;
    cfg.callbacks.error = on_error;
    st = ge2gl_create(&cfg, &h);
    if (st != GE2GL_OK || !h) {
        fprintf(stderr, "install_consumer: FAIL: ge2gl_create: %s\n", ge2gl_status_name(st));
        free(rgba);
        return 1;
    }

    /* The clear rectangle (whole screen) and the sprite, 2 vertices each. */
    put_vertex(verts, CLEAR_ABGR, 0, 0);
    put_vertex(verts + 12, CLEAR_ABGR, WIDTH, HEIGHT);
    put_vertex(verts + 24, SPRITE_ABGR, SPRITE_X0, SPRITE_Y0);
    put_vertex(verts + 36, SPRITE_ABGR, SPRITE_X1, SPRITE_Y1);

    w.size = 0;
    emit(&w, 0x9C, 0);                               /* FBP: VRAM offset 0 */
    emit(&w, 0x9D, STRIDE);                          /* FBW */
    emit(&w, 0xD2, GE2GL_FORMAT_8888);               /* FPF */
    emit(&w, 0x9E, 0x88000);                         /* ZBP: after the frame buffer */
    emit(&w, 0x9F, STRIDE);                          /* ZBW */
    emit(&w, 0x15, 0);                               /* REGION1 */
    emit(&w, 0x16, ((HEIGHT - 1u) << 10) | (WIDTH - 1u)); /* REGION2 */
    emit(&w, 0xD4, 0);                               /* SCISSOR1 */
    emit(&w, 0xD5, ((HEIGHT - 1u) << 10) | (WIDTH - 1u)); /* SCISSOR2 */
    emit(&w, 0x12, VTYPE_THROUGH_C8888_P16);         /* VTYPE */
    emit(&w, 0x10, (VERTS_ADDR >> 8) & 0x0F0000u);   /* BASE */
    emit(&w, 0x01, VERTS_ADDR & 0xFFFFFFu);          /* VADR */
    emit(&w, 0xD3, (7u << 8) | 1u);                  /* CMODE: clear colour, stencil, depth */
    emit(&w, 0x04, (6u << 16) | 2u);                 /* PRIM: sprites, 2 vertices */
    emit(&w, 0xD3, 0);                               /* CMODE off */
    emit(&w, 0x04, (6u << 16) | 2u);                 /* PRIM: the next 2 vertices */
    emit(&w, 0x0F, 0);                               /* FINISH */
    emit(&w, 0x0C, 0);                               /* END */

    EXPECT(ge2gl_mem_write(h, VERTS_ADDR, verts, sizeof verts) == GE2GL_OK, "mem_write vertices: %s",
           ge2gl_last_message(h));
    EXPECT(ge2gl_mem_write(h, LIST_ADDR, w.bytes, w.size) == GE2GL_OK, "mem_write list: %s", ge2gl_last_message(h));
    /* Outside guest memory: refused, nothing changes. */
    EXPECT(ge2gl_mem_write(h, 0x00000010u, verts, 4) == GE2GL_ERR_MEMORY, "mem_write to 0x10 was not refused");

    EXPECT(ge2gl_set_callback(h, 0x08900000u, 0, 0x08900100u, 0, &cbid) == GE2GL_OK, "set_callback: %s",
           ge2gl_last_message(h));
    EXPECT(ge2gl_list_enqueue(h, LIST_ADDR, 0, cbid, NULL, &list_id) == GE2GL_OK, "list_enqueue: %s",
           ge2gl_last_message(h));
    EXPECT(ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &state) == GE2GL_OK, "draw_sync: %s", ge2gl_last_message(h));
    EXPECT(finished == 1, "%d FINISH callbacks, expected 1", finished);
    state = -1;
    EXPECT(ge2gl_draw_sync(h, GE2GL_SYNC_PEEK, &state) == GE2GL_OK && state == GE2GL_LIST_COMPLETED,
           "draw_sync peek: state %d, expected completed", (int)state);

    memset(rgba, 0, (size_t)WIDTH * HEIGHT * 4);
    st = ge2gl_read_frame(h, VRAM_ADDR, STRIDE, GE2GL_FORMAT_8888, WIDTH, HEIGHT, rgba, (size_t)WIDTH * HEIGHT * 4);
    EXPECT(st == GE2GL_OK, "read_frame: %s", ge2gl_status_name(st));
    if (st == GE2GL_OK) {
        EXPECT(pixel_is(rgba, 0, 0, CLEAR_ABGR), "pixel (0,0) is not the clear colour");
        EXPECT(pixel_is(rgba, WIDTH - 1, HEIGHT - 1, CLEAR_ABGR), "last pixel is not the clear colour");
        EXPECT(pixel_is(rgba, SPRITE_X0 - 1, SPRITE_Y0, CLEAR_ABGR), "pixel left of the sprite is not the clear colour");
        EXPECT(pixel_is(rgba, SPRITE_X0, SPRITE_Y0, SPRITE_ABGR), "sprite's first pixel is not the sprite colour");
        EXPECT(pixel_is(rgba, SPRITE_X1 - 1, SPRITE_Y1 - 1, SPRITE_ABGR), "sprite's last pixel is not the sprite colour");
        EXPECT(pixel_is(rgba, SPRITE_X1, SPRITE_Y1 - 1, CLEAR_ABGR), "pixel right of the sprite is not the clear colour");
    }

    ge2gl_destroy(h);
    free(rgba);
    if (failures) {
        fprintf(stderr, "install_consumer: %d check(s) failed\n", failures);
        return 1;
    }
    printf("install_consumer: OK (API %u.%u, soft backend drew a cleared frame and a sprite)\n",
           (unsigned)(version >> 16), (unsigned)(version & 0xFFFFu));
    return 0;
}
