/* SPDX-License-Identifier: MIT */
/*
 * minimal_host: the smallest complete ge2gl host, in C99, using only the C ABI (ge2gl/ge2gl.h).
 *
 * It plays the part of an emulator running a game: it owns the PSP's RAM and VRAM, registers a
 * GE callback (sceGeSetCallback), enqueues a display list (sceGeListEnQueue) and writes the list
 * while the GE reads it, moving the stall address (sceGeListUpdateStallAddr) after each block as
 * libgu does. The list clears the screen, raises a SIGNAL, draws a gouraud-shaded triangle and
 * ends with FINISH. The host then waits (sceGeDrawSync), reads the frame and writes it as a PNG.
 *
 *   usage: minimal_host [out.png]      (default: minimal_host.png)
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ge2gl/ge2gl.h"

#define RAM_BASE 0x08000000u
#define RAM_SIZE (8u << 20)
#define LIST_ADDR 0x08100000u /* where the "game" writes its display list */
#define DATA_ADDR 0x08200000u /* vertex data */
#define WIDTH 480
#define HEIGHT 272

/* ---- the "game" side: guest memory and a list writer ---------------------------------------- */

static uint8_t* g_ram;

static void poke32(uint32_t addr, uint32_t v) {
    uint8_t* p = g_ram + (addr - RAM_BASE);
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t g_pc = LIST_ADDR; /* next word the game writes */

static void emit(uint32_t op, uint32_t arg) {
    poke32(g_pc, (op << 24) | (arg & 0xFFFFFFu));
    g_pc += 4;
}

/* One through-mode vertex as VTYPE (COL_8888 | POS_16 | THROUGH) lays it out: colour (4 bytes),
 * x, y, z as 16-bit values, padded to 12 bytes. */
static uint32_t put_vertex(uint32_t addr, uint32_t abgr, int x, int y) {
    poke32(addr, abgr);
    poke32(addr + 4, ((uint32_t)(uint16_t)y << 16) | (uint16_t)x);
    poke32(addr + 8, 0);
    return addr + 12;
}

#define VTYPE_THROUGH_C8888_P16 ((1u << 23) | (7u << 2) | (2u << 7))

/* ---- the host side: callbacks ----------------------------------------------------------------- */

static void on_signal(void* user, const ge2gl_interrupt* irq) {
    (void)user;
    /* An emulator would now run the game's signal handler irq->func(irq->arg, irq->func_arg, irq->pc). */
    printf("signal: list 0x%08x behaviour %u arg 0x%04x pc 0x%08x (callback 0x%08x, arg 0x%08x)\n",
           (unsigned)irq->list_id, (unsigned)irq->behaviour, (unsigned)irq->arg, (unsigned)irq->pc,
           (unsigned)irq->func, (unsigned)irq->func_arg);
}

static void on_finish(void* user, const ge2gl_interrupt* irq) {
    int* finished = (int*)user;
    ++*finished;
    printf("finish: list 0x%08x arg 0x%04x pc 0x%08x\n", (unsigned)irq->list_id, (unsigned)irq->arg,
           (unsigned)irq->pc);
}

static void on_error(void* user, int32_t list_id, uint32_t pc, const char* message) {
    (void)user;
    fprintf(stderr, "GE error in list 0x%08x at 0x%08x: %s\n", (unsigned)list_id, (unsigned)pc, message);
}

/* ---- a tiny PNG writer: zlib "stored" deflate blocks, no compression ------------------------- */

static uint32_t crc_table[256];

static void crc_init(void) {
    uint32_t n, k;
    for (n = 0; n < 256; ++n) {
        uint32_t c = n;
        for (k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        crc_table[n] = c;
    }
}

static uint32_t crc_update(uint32_t crc, const uint8_t* p, size_t n) {
    while (n--) crc = crc_table[(crc ^ *p++) & 0xFF] ^ (crc >> 8);
    return crc;
}

static void put_be32(uint8_t* p, uint32_t v) {
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static int write_chunk(FILE* f, const char* type, const uint8_t* data, uint32_t size) {
    uint8_t head[8], tail[4];
    uint32_t crc;
    put_be32(head, size);
    memcpy(head + 4, type, 4);
    crc = crc_update(0xFFFFFFFFu, head + 4, 4);
    crc = crc_update(crc, data, size) ^ 0xFFFFFFFFu;
    put_be32(tail, crc);
    return fwrite(head, 1, 8, f) == 8 && (size == 0 || fwrite(data, 1, size, f) == size) && fwrite(tail, 1, 4, f) == 4;
}

static int write_png(const char* path, const uint8_t* rgba, uint32_t w, uint32_t h) {
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    const uint32_t row = w * 4 + 1, raw_size = row * h;
    const uint32_t blocks = (raw_size + 65534) / 65535;
    const uint32_t idat_size = 2 + raw_size + blocks * 5 + 4;
    uint8_t ihdr[13];
    uint8_t *raw, *idat, *q;
    uint32_t y, a = 1, b = 0, i, left;
    FILE* f;
    int ok;

    crc_init();
    raw = (uint8_t*)malloc(raw_size);
    idat = (uint8_t*)malloc(idat_size);
    if (!raw || !idat) {
        free(raw);
        free(idat);
        return 0;
    }
    for (y = 0; y < h; ++y) {
        raw[y * row] = 0; /* filter: none */
        memcpy(raw + y * row + 1, rgba + (size_t)y * w * 4, (size_t)w * 4);
    }
    q = idat;
    *q++ = 0x78; /* zlib header: deflate, 32K window, no preset dictionary */
    *q++ = 0x01;
    for (i = 0, left = raw_size; left > 0;) {
        uint32_t n = left > 65535 ? 65535 : left;
        *q++ = (uint8_t)(left == n ? 1 : 0); /* BFINAL on the last block, BTYPE 00 = stored */
        *q++ = (uint8_t)n;
        *q++ = (uint8_t)(n >> 8);
        *q++ = (uint8_t)~n;
        *q++ = (uint8_t)(~n >> 8);
        memcpy(q, raw + i, n);
        q += n;
        i += n;
        left -= n;
    }
    for (i = 0; i < raw_size; ++i) { /* Adler-32 of the uncompressed bytes */
        a = (a + raw[i]) % 65521u;
        b = (b + a) % 65521u;
    }
    put_be32(q, (b << 16) | a);

    put_be32(ihdr, w);
    put_be32(ihdr + 4, h);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 6;  /* RGBA */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering */
    ihdr[12] = 0; /* no interlace */
    f = fopen(path, "wb");
    ok = f && fwrite(sig, 1, 8, f) == 8 && write_chunk(f, "IHDR", ihdr, 13) && write_chunk(f, "IDAT", idat, idat_size) &&
         write_chunk(f, "IEND", NULL, 0);
    if (f && fclose(f) != 0) ok = 0;
    free(raw);
    free(idat);
    return ok;
}

/* ---- main --------------------------------------------------------------------------------- */

#define CHECK(call)                                                                                        \
    do {                                                                                                   \
        ge2gl_status st_ = (call);                                                                         \
        if (st_ != GE2GL_OK) {                                                                             \
            fprintf(stderr, "%s failed: %s (%s)\n", #call, ge2gl_status_name(st_), ge2gl_last_message(h)); \
            goto fail;                                                                                     \
        }                                                                                                  \
    } while (0)

int main(int argc, char** argv) {
    const char* out = argc > 1 ? argv[1] : "minimal_host.png";
    uint8_t* vram = (uint8_t*)calloc(0x200000, 1);
    uint8_t* rgba = (uint8_t*)malloc(WIDTH * HEIGHT * 4);
    ge2gl_context* h = NULL;
    ge2gl_config cfg;
    ge2gl_run_info info;
    int32_t cbid = -1, list_id = -1, state = -1;
    int finished = 0, rc = 1;
    uint32_t v, i;

    g_ram = (uint8_t*)calloc(RAM_SIZE, 1);
    if (!g_ram || !vram || !rgba) goto fail;
    if (ge2gl_api_version() >> 16 != GE2GL_API_VERSION_MAJOR) {
        fprintf(stderr, "ge2gl library has an incompatible API version\n");
        goto fail;
    }

    /* 1. Create the GE: our memory, the software backend, our callbacks. */
    ge2gl_config_init(&cfg);
    cfg.ram = g_ram;
    cfg.ram_size = RAM_SIZE;
    cfg.vram = vram;
    cfg.backend = GE2GL_BACKEND_SOFT;
    cfg.callbacks.user = &finished;
    cfg.callbacks.signal = on_signal;
    cfg.callbacks.finish = on_finish;
    cfg.callbacks.error = on_error;
    if (ge2gl_create(&cfg, &h) != GE2GL_OK) {
        fprintf(stderr, "ge2gl_create failed\n");
        goto fail;
    }

    /* 2. The game registers its GE callbacks (guest function addresses; opaque to ge2gl). */
    CHECK(ge2gl_set_callback(h, 0x08900000u, 0x1234u, 0x08900100u, 0x5678u, &cbid));

    /* 3. The game starts an empty list: the stall address is the list start. */
    CHECK(ge2gl_list_enqueue(h, LIST_ADDR, LIST_ADDR, cbid, NULL, &list_id));

    /* 4. Block 1: frame buffer and clear (sceGuDrawBuffer, sceGuScissor, sceGuClear). */
    emit(0x9C, 0);                            /* FBP: VRAM offset 0 */
    emit(0x9D, 512);                          /* FBW: stride 512 */
    emit(0xD2, 3);                            /* FPF: 8888 */
    emit(0x9E, 0x88000);                      /* ZBP: depth buffer after the frame buffer */
    emit(0x9F, 512);                          /* ZBW */
    emit(0x15, 0);                            /* REGION1 */
    emit(0x16, (271u << 10) | 479u);          /* REGION2 */
    emit(0xD4, 0);                            /* SCISSOR1 */
    emit(0xD5, (271u << 10) | 479u);          /* SCISSOR2 */
    v = put_vertex(DATA_ADDR, 0xFF402010u, 0, 0);
    put_vertex(v, 0xFF402010u, WIDTH, HEIGHT);
    emit(0xD3, (7u << 8) | 1u);               /* CMODE: clear colour, stencil, depth */
    emit(0x12, VTYPE_THROUGH_C8888_P16);      /* VTYPE */
    emit(0x10, (DATA_ADDR >> 8) & 0x0F0000u); /* BASE */
    emit(0x01, DATA_ADDR & 0xFFFFFFu);        /* VADR */
    emit(0x04, (6u << 16) | 2u);              /* PRIM: rectangles, 2 vertices */
    emit(0xD3, 0);                            /* CMODE off */
    CHECK(ge2gl_list_update_stall(h, list_id, g_pc));
    CHECK(ge2gl_run(h, 1000, &info)); /* the GE catches up while the game writes on */
    printf("after block 1: GE at 0x%08x, stall 0x%08x, state %d\n", (unsigned)info.pc, (unsigned)info.stall,
           (int)info.ge_state);

    /* 5. Block 2: a signal to the game (HANDLER_CONTINUE, id 1), then a gouraud triangle. */
    emit(0x0E, (0x02u << 16) | 1u); /* SIGNAL */
    emit(0x0C, 0);                  /* END */
    v = DATA_ADDR + 0x100;
    v = put_vertex(v, 0xFF0000FFu, 240, 30);
    v = put_vertex(v, 0xFF00FF00u, 400, 240);
    put_vertex(v, 0xFFFF0000u, 80, 240);
    emit(0x50, 1);                                    /* SHADE: gouraud */
    emit(0x01, (DATA_ADDR + 0x100) & 0xFFFFFFu);      /* VADR */
    emit(0x04, (3u << 16) | 3u);                      /* PRIM: triangles, 3 vertices */
    CHECK(ge2gl_list_update_stall(h, list_id, g_pc));
    CHECK(ge2gl_run(h, 1000, &info));

    /* 6. Block 3: sceGuFinish, then the last stall update (sceGuSync waits below). */
    emit(0x0F, 0xABCu); /* FINISH */
    emit(0x0C, 0);      /* END */
    CHECK(ge2gl_list_update_stall(h, list_id, g_pc));

    /* 7. sceGeDrawSync(0): run the GE until every list has finished. */
    CHECK(ge2gl_draw_sync(h, GE2GL_SYNC_WAIT, &state));
    if (finished != 1) {
        fprintf(stderr, "expected one FINISH callback, got %d\n", finished);
        goto fail;
    }

    /* 8. Present: read the displayed frame buffer as RGBA8888 and save it. */
    CHECK(ge2gl_read_frame(h, 0x04000000u, 512, GE2GL_FORMAT_8888, WIDTH, HEIGHT, rgba, WIDTH * HEIGHT * 4));
    for (i = 0; i < WIDTH * HEIGHT; ++i) rgba[i * 4 + 3] = 255; /* the display ignores alpha */
    if (!write_png(out, rgba, WIDTH, HEIGHT)) {
        fprintf(stderr, "cannot write %s\n", out);
        goto fail;
    }
    printf("wrote %s\n", out);
    rc = 0;

fail:
    ge2gl_destroy(h);
    free(g_ram);
    free(vram);
    free(rgba);
    return rc;
}
