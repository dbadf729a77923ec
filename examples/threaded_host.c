/* SPDX-License-Identifier: MIT */
/*
 * threaded_host: ge2gl driven from two threads, the way an emulator runs the PSP (C99 + POSIX threads).
 *
 *   - The GE thread owns the GE: it loops ge2gl_run(h, 4096, &info) and naps 50 us whenever the GE
 *     has nothing to do (idle, stalled on the list being written, paused, or holding an interrupt).
 *   - The CPU thread (main) plays the game: it writes display lists into guest memory block by block
 *     while the GE reads them, moving the stall address after each block as libgu does
 *     (sceGeListEnQueue + sceGeListUpdateStallAddr), polls them with sceGeListSync(id, 1) /
 *     sceGeDrawSync(1) until they complete, and runs the game's GE interrupt handlers.
 *
 * Every list clears the screen, raises SIGNAL with behaviour 1 (HANDLER_SUSPEND), draws sprites and
 * ends with FINISH. Interrupts are delivered on the GE thread but the game's handlers run on the CPU
 * thread, so the signal and finish callbacks hand each interrupt to the CPU thread:
 *
 *   default   the callback posts the interrupt and blocks until the CPU thread has run the handler
 *             (as the PSP's GE waits for its interrupt handler). This works only because ge2gl calls
 *             callbacks with no ge2gl lock held: the CPU thread keeps calling ge2gl_* meanwhile.
 *   --hold    config.hold_interrupts: the callback only posts the interrupt and returns; the GE then
 *             stops (GE2GL_GE_INTERRUPT) until the CPU thread calls ge2gl_interrupt_ack() after
 *             running the handler.
 *
 * Guest memory is owned by ge2gl (config.ram = NULL, 64 MiB); the game writes it with
 * ge2gl_mem_write, which is safe from any thread. Two list buffers are used in turn, so the game
 * writes list k+1 while the GE may still be drawing list k.
 *
 * The CPU thread times every peek-mode sync (CLOCK_MONOTONIC) and finally prints one line:
 *
 *   threaded_host: lists=1000 signals=1000 finishes=1000 peeks=P peek_us_median=X peek_us_max=Y wall_s=Z
 *
 * Exit status: 0 when every list completed, every signal and finish arrived in order and the frame
 * holds the colours the last list drew; 1 on an error; 3 when the watchdog fires (a deadlock).
 *
 *   usage: threaded_host [--lists N] [--hold] [--backend null|soft|gl] [--timeout SECONDS]
 *          (defaults: 1000 lists, soft backend, 120 s; gl = GE2GL_BACKEND_GL_HEADLESS on OSMesa,
 *          --egl for its EGL context)
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ge2gl/ge2gl.h"

/* ---- guest memory layout ------------------------------------------------------------------ */

#define LIST_SLOTS 2                /* list buffers used in turn */
#define LIST_BASE 0x08100000u       /* list buffer k at LIST_BASE + k * LIST_SLOT_SIZE */
#define LIST_SLOT_SIZE 0x1000u
#define DATA_BASE 0x08200000u       /* its vertex data at DATA_BASE + k * DATA_SLOT_SIZE */
#define DATA_SLOT_SIZE 0x1000u
#define FRAME_ADDR 0x04000000u      /* frame buffer: VRAM offset 0, 512 pixels per row, 8888 */
#define DEPTH_OFFSET 0x88000u       /* depth buffer after it */
#define FRAME_STRIDE 512u
#define WIDTH 480
#define HEIGHT 272

/* The game's sceGeSetCallback: guest function addresses and arguments (opaque to ge2gl). */
#define SIGNAL_FUNC 0x08900000u
#define SIGNAL_ARG 0x5157u
#define FINISH_FUNC 0x08900100u
#define FINISH_ARG 0xF157u

/* The sprites every list draws after its signal: PSP rectangles (x0, y0, x1, y1). */
#define SPRITES 3
static const int sprite_rect[SPRITES][4] = {{40, 40, 120, 100}, {200, 96, 280, 176}, {360, 180, 440, 240}};

/* VTYPE: colour 8888, 16-bit positions, through mode. One vertex: colour, x, y, z, pad = 12 bytes. */
#define VTYPE_THROUGH_C8888_P16 ((1u << 23) | (7u << 2) | (2u << 7))
#define VERTEX_SIZE 12u

#define OP_VADR 0x01u
#define OP_PRIM 0x04u
#define OP_END 0x0Cu
#define OP_SIGNAL 0x0Eu
#define OP_FINISH 0x0Fu
#define OP_BASE 0x10u
#define OP_VTYPE 0x12u
#define PRIM_SPRITES 6u
#define SIGNAL_SUSPEND 1u /* HANDLER_SUSPEND: the GE waits while the handler runs */

/* The colour list k clears to (ABGR, alpha 255), and the colour of its sprites. */
static uint32_t clear_colour(uint32_t k) {
    uint32_t x = (k + 1) * 0x9E3779B1u;
    x ^= x >> 15;
    return 0xFF000000u | (x & 0xFFFFFFu);
}
static uint32_t sprite_colour(uint32_t k) { return clear_colour(k) ^ 0x00FFFFFFu; }

/* ---- shared state between the two threads ------------------------------------------------- */

#define KIND_SIGNAL 0
#define KIND_FINISH 1
#define MAILBOX_SIZE 64

typedef struct posted_irq {
    int kind;
    ge2gl_interrupt irq;
} posted_irq;

typedef struct host {
    ge2gl_context* ge;
    int hold; /* config.hold_interrupts */

    pthread_mutex_t mu;   /* guards everything below */
    pthread_cond_t done;  /* the CPU thread handled interrupts (a waiting callback may go on) */
    posted_irq mailbox[MAILBOX_SIZE];
    unsigned long posted;  /* interrupts posted by the callbacks (GE thread) */
    unsigned long taken;   /* ... taken by the CPU thread */
    unsigned long handled; /* ... whose handler has run */
    int quit;              /* the GE thread stops */
    int abandon;           /* callbacks stop waiting for the CPU thread (shutdown after a failure) */
    int overflow;          /* the mailbox was full */
    unsigned long ge_errors;       /* error callbacks */
    char ge_error_text[256];       /* the first one */
    ge2gl_status ge_thread_status; /* a failed ge2gl_run */
    char ge_thread_text[256];
    unsigned long runs; /* ge2gl_run calls */
} host;

static void lock(host* s) { pthread_mutex_lock(&s->mu); }
static void unlock(host* s) { pthread_mutex_unlock(&s->mu); }

static void nap_us(long us) {
    struct timespec t;
    t.tv_sec = us / 1000000;
    t.tv_nsec = (us % 1000000) * 1000;
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* ---- callbacks: they run on the GE thread, inside ge2gl_run -------------------------------- */

/* Hands the interrupt to the CPU thread. Without hold_interrupts, blocks until its handler ran. */
static void post_interrupt(host* s, int kind, const ge2gl_interrupt* irq) {
    unsigned long seq;
    lock(s);
    if (s->posted - s->taken >= MAILBOX_SIZE) {
        s->overflow = 1; /* cannot happen: at most one interrupt is outstanding */
        unlock(s);
        return;
    }
    s->mailbox[s->posted % MAILBOX_SIZE].kind = kind;
    s->mailbox[s->posted % MAILBOX_SIZE].irq = *irq;
    seq = ++s->posted;
    if (!s->hold)
        while (s->handled < seq && !s->abandon) pthread_cond_wait(&s->done, &s->mu);
    unlock(s);
}

static void on_signal(void* user, const ge2gl_interrupt* irq) { post_interrupt((host*)user, KIND_SIGNAL, irq); }
static void on_finish(void* user, const ge2gl_interrupt* irq) { post_interrupt((host*)user, KIND_FINISH, irq); }

static void on_error(void* user, int32_t list_id, uint32_t pc, const char* message) {
    host* s = (host*)user;
    lock(s);
    if (s->ge_errors++ == 0)
        snprintf(s->ge_error_text, sizeof s->ge_error_text, "list 0x%08x at 0x%08x: %s", (unsigned)list_id,
                 (unsigned)pc, message);
    unlock(s);
}

/* ---- the GE thread ------------------------------------------------------------------------ */

static void* ge_thread_main(void* arg) {
    host* s = (host*)arg;
    ge2gl_run_info info;
    for (;;) {
        ge2gl_status st;
        int quit;
        lock(s);
        quit = s->quit;
        unlock(s);
        if (quit) break;
        st = ge2gl_run(s->ge, 4096, &info);
        lock(s);
        ++s->runs;
        if (st != GE2GL_OK) {
            s->ge_thread_status = st;
            snprintf(s->ge_thread_text, sizeof s->ge_thread_text, "ge2gl_run failed: %s (%s)", ge2gl_status_name(st),
                     ge2gl_last_message(s->ge));
        } else if (info.ge_state == GE2GL_GE_HUNG) {
            s->ge_thread_status = GE2GL_ERR_BAD_STATE;
            snprintf(s->ge_thread_text, sizeof s->ge_thread_text, "the GE hung in list 0x%08x at 0x%08x",
                     (unsigned)info.list_id, (unsigned)info.pc);
        }
        unlock(s);
        if (st != GE2GL_OK || info.ge_state == GE2GL_GE_HUNG) break;
        switch (info.ge_state) {
        case GE2GL_GE_IDLE:      /* nothing queued */
        case GE2GL_GE_STALLED:   /* waiting for the game to write more */
        case GE2GL_GE_PAUSED:    /* waiting for sceGeContinue */
        case GE2GL_GE_INTERRUPT: /* waiting for ge2gl_interrupt_ack */
            nap_us(50);
            break;
        default: /* READY: the budget ran out, go on */
            break;
        }
    }
    return NULL;
}

/* ---- the CPU thread: the game ------------------------------------------------------------- */

typedef struct game {
    host* s;
    uint32_t lists;
    int32_t cbid;
    int32_t* ids; /* list ID of each list, -1 before its enqueue */
    uint32_t signals, finishes; /* handlers run */
    int failed;
    /* peek-mode sync latencies, microseconds */
    double* peek_us;
    size_t peeks, peek_cap;
    size_t list_peeks, draw_peeks;
    double list_peek_max, draw_peek_max;
    unsigned long calls_while_pending; /* ge2gl calls made while an interrupt waited for us */
} game;

static int fail(game* g, const char* what) {
    fprintf(stderr, "threaded_host: %s\n", what);
    g->failed = 1;
    return 0;
}

static int check(game* g, ge2gl_status st, const char* call) {
    char buf[400];
    if (st == GE2GL_OK) return 1;
    snprintf(buf, sizeof buf, "%s failed: %s (%s)", call, ge2gl_status_name(st), ge2gl_last_message(g->s->ge));
    return fail(g, buf);
}

/* "Runs the guest handler" of one interrupt: checks what the game would be handed and counts it. */
static void run_handler(game* g, const posted_irq* p) {
    const ge2gl_interrupt* irq = &p->irq;
    char buf[300];
    if (p->kind == KIND_SIGNAL) {
        uint32_t k = g->signals++;
        if (k >= g->lists || irq->list_id != g->ids[k] || irq->behaviour != SIGNAL_SUSPEND || irq->arg != (k & 0xFFFFu) ||
            !irq->registered || irq->cbid != g->cbid || irq->func != SIGNAL_FUNC || irq->func_arg != SIGNAL_ARG) {
            snprintf(buf, sizeof buf,
                     "signal %u: unexpected interrupt (list 0x%08x behaviour %u arg 0x%04x cbid %d registered %d "
                     "func 0x%08x func_arg 0x%08x)",
                     (unsigned)k, (unsigned)irq->list_id, (unsigned)irq->behaviour, (unsigned)irq->arg, (int)irq->cbid,
                     (int)irq->registered, (unsigned)irq->func, (unsigned)irq->func_arg);
            fail(g, buf);
        }
    } else {
        uint32_t k = g->finishes++;
        if (k >= g->lists || irq->list_id != g->ids[k] || irq->behaviour != 0 || irq->arg != (k & 0xFFFFu) ||
            !irq->registered || irq->func != FINISH_FUNC || irq->func_arg != FINISH_ARG) {
            snprintf(buf, sizeof buf, "finish %u: unexpected interrupt (list 0x%08x arg 0x%04x func 0x%08x)",
                     (unsigned)k, (unsigned)irq->list_id, (unsigned)irq->arg, (unsigned)irq->func);
            fail(g, buf);
        }
    }
}

/* The CPU thread's interrupt dispatch: runs the handlers of everything posted so far, then lets
   the GE go on (wakes the waiting callback, or acknowledges the held interrupt). */
static int service_interrupts(game* g) {
    host* s = g->s;
    posted_irq batch[MAILBOX_SIZE];
    unsigned long n = 0, i;
    int ge_failed, overflow;
    char buf[600];
    lock(s);
    while (s->taken < s->posted) batch[n++] = s->mailbox[s->taken++ % MAILBOX_SIZE];
    ge_failed = s->ge_thread_status != GE2GL_OK || s->ge_errors != 0;
    overflow = s->overflow;
    if (ge_failed)
        snprintf(buf, sizeof buf, "%s%s%s", s->ge_thread_text, s->ge_thread_text[0] && s->ge_errors ? "; " : "",
                 s->ge_errors ? s->ge_error_text : "");
    unlock(s);
    for (i = 0; i < n; ++i) run_handler(g, &batch[i]);
    if (n) {
        lock(s);
        s->handled += n;
        pthread_cond_broadcast(&s->done);
        unlock(s);
        if (s->hold && !check(g, ge2gl_interrupt_ack(s->ge), "ge2gl_interrupt_ack")) return 0;
    }
    if (ge_failed) return fail(g, buf);
    if (overflow) return fail(g, "interrupt mailbox overflow");
    return !g->failed;
}

/* Whether an interrupt posted to this thread is not yet handled: a callback blocked on us, or (with
   --hold) the GE holding. Only this thread makes it false, so a ge2gl call made while it is true ran
   entirely while the callback was blocked, or the GE held. */
static int interrupt_pending(game* g) {
    int pending;
    lock(g->s);
    pending = g->s->posted > g->s->handled;
    unlock(g->s);
    return pending;
}

static void record_peek(game* g, double us) {
    if (g->peeks == g->peek_cap) {
        size_t cap = g->peek_cap ? g->peek_cap * 2 : 4096;
        double* p = (double*)realloc(g->peek_us, cap * sizeof *p);
        if (!p) return; /* keep the samples so far */
        g->peek_us = p;
        g->peek_cap = cap;
    }
    g->peek_us[g->peeks++] = us;
}

/* sceGeListSync(id, 1), timed. */
static int peek_list(game* g, int32_t id, int32_t* state) {
    const int pending = interrupt_pending(g);
    double t0 = now_s(), us;
    ge2gl_status st = ge2gl_list_sync(g->s->ge, id, GE2GL_SYNC_PEEK, state);
    us = (now_s() - t0) * 1e6;
    g->calls_while_pending += (unsigned long)pending;
    record_peek(g, us);
    ++g->list_peeks;
    if (us > g->list_peek_max) g->list_peek_max = us;
    return check(g, st, "ge2gl_list_sync(PEEK)");
}

/* sceGeDrawSync(1), timed. */
static int peek_draw(game* g, int32_t* state) {
    const int pending = interrupt_pending(g);
    double t0 = now_s(), us;
    ge2gl_status st = ge2gl_draw_sync(g->s->ge, GE2GL_SYNC_PEEK, state);
    us = (now_s() - t0) * 1e6;
    g->calls_while_pending += (unsigned long)pending;
    record_peek(g, us);
    ++g->draw_peeks;
    if (us > g->draw_peek_max) g->draw_peek_max = us;
    return check(g, st, "ge2gl_draw_sync(PEEK)");
}

/* Polls a list until it has completed, running interrupt handlers meanwhile (a game thread that
   polls sceGeListSync(id, 1) while its GE callbacks run). */
static int wait_list(game* g, int32_t id) {
    unsigned long round;
    for (round = 0;; ++round) {
        int32_t state = -1, draw_state = -1;
        if (!service_interrupts(g)) return 0;
        if (!peek_list(g, id, &state)) return 0;
        if (state == GE2GL_LIST_COMPLETED) return 1;
        if (round % 4 == 3 && !peek_draw(g, &draw_state)) return 0;
        nap_us(20);
    }
}

/* A list block: words collected here, then written to guest memory in one go. */
typedef struct block {
    uint32_t addr; /* guest address of words[0] */
    uint32_t n;
    uint8_t bytes[256 * 4];
} block;

static void emit(block* b, uint32_t op, uint32_t arg) {
    uint32_t w = (op << 24) | (arg & 0xFFFFFFu);
    uint8_t* p = b->bytes + b->n * 4;
    p[0] = (uint8_t)w;
    p[1] = (uint8_t)(w >> 8);
    p[2] = (uint8_t)(w >> 16);
    p[3] = (uint8_t)(w >> 24);
    ++b->n;
}

/* Writes the block into guest memory and moves the list's stall address past it (libgu's
   sceGuSendList / sceGuFinish pattern). The next block starts where this one ended. */
static int flush_block(game* g, block* b, int32_t id) {
    const uint32_t end = b->addr + b->n * 4;
    const int pending = interrupt_pending(g);
    if (!check(g, ge2gl_mem_write(g->s->ge, b->addr, b->bytes, b->n * 4), "ge2gl_mem_write(list)")) return 0;
    if (!check(g, ge2gl_list_update_stall(g->s->ge, id, end), "ge2gl_list_update_stall")) return 0;
    g->calls_while_pending += 2 * (unsigned long)pending;
    b->addr = end;
    b->n = 0;
    return service_interrupts(g);
}

static void put_vertex(uint8_t* p, uint32_t abgr, int x, int y) {
    uint32_t xy = ((uint32_t)(uint16_t)y << 16) | (uint16_t)x;
    int i;
    for (i = 0; i < 4; ++i) {
        p[i] = (uint8_t)(abgr >> (8 * i));
        p[4 + i] = (uint8_t)(xy >> (8 * i));
        p[8 + i] = 0; /* z = 0, padding */
    }
}

/* Writes list k into list buffer k % LIST_SLOTS while the GE may be reading the previous one. */
static int run_list(game* g, uint32_t k) {
    const uint32_t slot = k % LIST_SLOTS;
    const uint32_t list = LIST_BASE + slot * LIST_SLOT_SIZE, data = DATA_BASE + slot * DATA_SLOT_SIZE;
    uint8_t vertices[(2 + 2 * SPRITES) * VERTEX_SIZE];
    block b;
    int32_t id = -1;
    int i;

    /* Vertex data first: the clear rectangle, then the sprites. */
    put_vertex(vertices, clear_colour(k), 0, 0);
    put_vertex(vertices + VERTEX_SIZE, clear_colour(k), WIDTH, HEIGHT);
    for (i = 0; i < SPRITES; ++i) {
        put_vertex(vertices + (2 + 2 * i) * VERTEX_SIZE, sprite_colour(k), sprite_rect[i][0], sprite_rect[i][1]);
        put_vertex(vertices + (3 + 2 * i) * VERTEX_SIZE, sprite_colour(k), sprite_rect[i][2], sprite_rect[i][3]);
    }
    if (!check(g, ge2gl_mem_write(g->s->ge, data, vertices, sizeof vertices), "ge2gl_mem_write(vertices)")) return 0;

    /* sceGeListEnQueue of an empty list: the stall address is the list start. */
    if (!check(g, ge2gl_list_enqueue(g->s->ge, list, list, g->cbid, NULL, &id), "ge2gl_list_enqueue")) return 0;
    g->ids[k] = id;
    b.addr = list;
    b.n = 0;

    /* Block 1: frame buffer, region, scissor, and a clear of the whole screen. */
    emit(&b, 0x9C, 0);                          /* FBP: VRAM offset 0 */
    emit(&b, 0x9D, FRAME_STRIDE);               /* FBW */
    emit(&b, 0xD2, 3);                          /* FPF: 8888 */
    emit(&b, 0x9E, DEPTH_OFFSET);               /* ZBP */
    emit(&b, 0x9F, FRAME_STRIDE);               /* ZBW */
    emit(&b, 0x15, 0);                          /* REGION1 */
    emit(&b, 0x16, (271u << 10) | 479u);        /* REGION2 */
    emit(&b, 0xD4, 0);                          /* SCISSOR1 */
    emit(&b, 0xD5, (271u << 10) | 479u);        /* SCISSOR2 */
    emit(&b, 0xD3, (7u << 8) | 1u);             /* CMODE: clear colour, stencil, depth */
    emit(&b, OP_VTYPE, VTYPE_THROUGH_C8888_P16);
    emit(&b, OP_BASE, (data >> 8) & 0x0F0000u);
    emit(&b, OP_VADR, data & 0xFFFFFFu);
    emit(&b, OP_PRIM, (PRIM_SPRITES << 16) | 2u);
    emit(&b, 0xD3, 0);                          /* CMODE off */
    if (!flush_block(g, &b, id)) return 0;

    /* Block 2: the signal to the game (HANDLER_SUSPEND, argument k). SIGNAL is followed by END. */
    emit(&b, OP_SIGNAL, (SIGNAL_SUSPEND << 16) | (k & 0xFFFFu));
    emit(&b, OP_END, 0);
    if (!flush_block(g, &b, id)) return 0;

    /* Block 3: the sprites. */
    emit(&b, OP_VADR, (data + 2 * VERTEX_SIZE) & 0xFFFFFFu);
    emit(&b, OP_PRIM, (PRIM_SPRITES << 16) | (2u * SPRITES));
    if (!flush_block(g, &b, id)) return 0;

    /* Block 4: sceGuFinish. */
    emit(&b, OP_FINISH, k & 0xFFFFu);
    emit(&b, OP_END, 0);
    return flush_block(g, &b, id);
}

/* ---- watchdog ------------------------------------------------------------------------------ */

static const char* const phase_names[] = {"starting", "writing and polling lists", "waiting for the last lists",
                                          "waiting for the last interrupts", "stopping the GE thread", "checking"};
static volatile sig_atomic_t g_phase = 0;
static volatile sig_atomic_t g_current_list = 0;

static void write_str(const char* s) {
    ssize_t r = write(2, s, strlen(s));
    (void)r;
}

static void on_watchdog(int sig) {
    char num[24];
    int n = 0, v = (int)g_current_list;
    (void)sig;
    do num[n++] = (char)('0' + v % 10), v /= 10;
    while (v && n < 20);
    write_str("threaded_host: watchdog: no result in time (deadlock?) while ");
    write_str(phase_names[g_phase]);
    write_str(", list ");
    while (n) {
        char c = num[--n];
        ssize_t r = write(2, &c, 1);
        (void)r;
    }
    write_str("\n");
    _exit(3);
}

/* ---- main ---------------------------------------------------------------------------------- */

static int cmp_double(const void* a, const void* b) {
    double x = *(const double*)a, y = *(const double*)b;
    return x < y ? -1 : x > y;
}

static int parse_uint(const char* s, unsigned long max, unsigned long* out) {
    char* end;
    unsigned long v;
    if (!s || !*s) return 0;
    errno = 0;
    v = strtoul(s, &end, 10);
    if (errno || *end || v == 0 || v > max) return 0;
    *out = v;
    return 1;
}

static int usage(void) {
    fprintf(stderr, "usage: threaded_host [--lists N] [--hold] [--backend null|soft|gl] [--egl] [--timeout SECONDS]\n");
    return 1;
}

static double median_of(double* v, size_t n) {
    if (!n) return 0.0;
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct options {
    unsigned long lists, timeout;
    int backend, use_egl, hold;
    const char* backend_name;
} options;

static int parse_args(int argc, char** argv, options* o) {
    int i;
    o->lists = 1000;
    o->timeout = 120;
    o->backend = GE2GL_BACKEND_SOFT;
    o->use_egl = 0;
    o->hold = 0;
    o->backend_name = "soft";
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--lists") && i + 1 < argc) {
            if (!parse_uint(argv[++i], 1000000, &o->lists)) return 0;
        } else if (!strcmp(argv[i], "--timeout") && i + 1 < argc) {
            if (!parse_uint(argv[++i], 100000, &o->timeout)) return 0;
        } else if (!strcmp(argv[i], "--hold")) {
            o->hold = 1;
        } else if (!strcmp(argv[i], "--egl")) {
            o->use_egl = 1;
        } else if (!strcmp(argv[i], "--backend") && i + 1 < argc) {
            o->backend_name = argv[++i];
            if (!strcmp(o->backend_name, "null")) o->backend = GE2GL_BACKEND_NULL;
            else if (!strcmp(o->backend_name, "soft")) o->backend = GE2GL_BACKEND_SOFT;
            else if (!strcmp(o->backend_name, "gl")) o->backend = GE2GL_BACKEND_GL_HEADLESS;
            else return 0;
        } else {
            return 0;
        }
    }
    return 1;
}

/* The watchdog: a deadlock between the threads ends the process with status 3. */
static void start_watchdog(unsigned long timeout) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_watchdog;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGALRM, &sa, NULL);
    alarm((unsigned)timeout);
}

/* 4. The game: write and queue every list, keeping at most LIST_SLOTS in flight, then wait until
   every list has completed and its interrupts were handled. */
static int play_lists(game* g) {
    uint32_t k;
    g_phase = 1;
    for (k = 0; k < g->lists; ++k) {
        g_current_list = (sig_atomic_t)k;
        /* The list buffer is free again once the list that used it has completed. */
        if (k >= LIST_SLOTS && !wait_list(g, g->ids[k - LIST_SLOTS])) return 0;
        if (!run_list(g, k)) return 0;
    }
    g_phase = 2;
    for (k = g->lists > LIST_SLOTS ? g->lists - LIST_SLOTS : 0; k < g->lists; ++k) {
        g_current_list = (sig_atomic_t)k;
        if (!wait_list(g, g->ids[k])) return 0;
    }
    /* A list reads COMPLETED before its finish callback has returned: handle the last ones, and
       wait for the GE to become idle (sceGeDrawSync(1)). */
    g_phase = 3;
    for (;;) {
        int32_t state = -1;
        if (!service_interrupts(g)) return 0;
        if (!peek_draw(g, &state)) return 0;
        if (state == GE2GL_LIST_COMPLETED && g->finishes >= g->lists) return 1;
        nap_us(20);
    }
}

/* 6. The frame: the last list's clear colour around its sprites, its sprite colour inside. */
static int check_frame(game* g, uint8_t* rgba, int backend) {
    static const int probes[][3] = {{0, 0, 0}, {479, 0, 0}, {0, 271, 0}, {479, 271, 0}, {300, 20, 0},
                                    {80, 70, 1}, {240, 136, 1}, {439, 239, 1}, {120, 100, 0}};
    const uint32_t last = g->lists - 1;
    size_t p;
    if (!check(g, ge2gl_read_frame(g->s->ge, FRAME_ADDR, FRAME_STRIDE, GE2GL_FORMAT_8888, WIDTH, HEIGHT, rgba,
                                   WIDTH * HEIGHT * 4),
               "ge2gl_read_frame"))
        return 0;
    if (backend == GE2GL_BACKEND_NULL) {
        printf("threaded_host: null backend draws nothing; frame not checked\n");
        return 1;
    }
    for (p = 0; p < sizeof probes / sizeof probes[0]; ++p) {
        const uint8_t* px = rgba + ((size_t)probes[p][1] * WIDTH + (size_t)probes[p][0]) * 4;
        const uint32_t want = probes[p][2] ? sprite_colour(last) : clear_colour(last);
        const uint32_t got = (uint32_t)px[0] | ((uint32_t)px[1] << 8) | ((uint32_t)px[2] << 16);
        if (got != (want & 0xFFFFFFu)) {
            char buf[200];
            snprintf(buf, sizeof buf, "frame pixel (%d, %d) is 0x%06x (BGR), expected the last list's %s 0x%06x",
                     probes[p][0], probes[p][1], (unsigned)got, probes[p][2] ? "sprite colour" : "clear colour",
                     (unsigned)(want & 0xFFFFFFu));
            fail(g, buf);
        }
    }
    return !g->failed;
}

/* 7. The result line. */
static void print_result(game* g, const host* s, unsigned long lists, int hold, double wall) {
    double peak = g->list_peek_max > g->draw_peek_max ? g->list_peek_max : g->draw_peek_max;
    double med = median_of(g->peek_us, g->peeks);
    printf("threaded_host: GE thread ran %lu slices; %lu list peeks (max %.1f us), %lu draw peeks (max %.1f us)\n",
           s->runs, (unsigned long)g->list_peeks, g->list_peek_max, (unsigned long)g->draw_peeks, g->draw_peek_max);
    printf("threaded_host: %lu ge2gl calls (peeks, memory writes, stall updates) returned while %s\n",
           g->calls_while_pending, hold ? "the GE held an interrupt" : "a GE callback was blocked waiting for this thread");
    printf("threaded_host: lists=%lu signals=%lu finishes=%lu peeks=%lu peek_us_median=%.2f peek_us_max=%.2f "
           "wall_s=%.3f\n",
           lists, (unsigned long)g->signals, (unsigned long)g->finishes, (unsigned long)g->peeks, med, peak, wall);
}

int main(int argc, char** argv) {
    options o;
    int rc = 1, thread_started = 0;
    host s;
    game g;
    ge2gl_config cfg;
    pthread_t ge_thread;
    double t0, wall;
    uint8_t* rgba = NULL;
    uint32_t k;

    setvbuf(stdout, NULL, _IOLBF, 0); /* lines reach a pipe even when the watchdog ends the process */
    if (!parse_args(argc, argv, &o)) return usage();
    start_watchdog(o.timeout);

    memset(&s, 0, sizeof s);
    memset(&g, 0, sizeof g);
    pthread_mutex_init(&s.mu, NULL);
    pthread_cond_init(&s.done, NULL);
    s.hold = o.hold;
    g.s = &s;
    g.lists = (uint32_t)o.lists;
    g.cbid = -1;
    g.ids = (int32_t*)malloc(o.lists * sizeof *g.ids);
    rgba = (uint8_t*)malloc(WIDTH * HEIGHT * 4);
    if (!g.ids || !rgba) {
        fprintf(stderr, "threaded_host: out of memory\n");
        goto done;
    }
    for (k = 0; k < g.lists; ++k) g.ids[k] = -1;

    if (ge2gl_api_version() >> 16 != GE2GL_API_VERSION_MAJOR || (ge2gl_api_version() & 0xFFFF) < 2) {
        fprintf(stderr, "threaded_host: the ge2gl library is older than API 1.2\n");
        goto done;
    }

    /* 1. The GE: ge2gl-owned guest memory (64 MiB RAM, VRAM), our callbacks. */
    ge2gl_config_init(&cfg);
    cfg.ram = NULL;
    cfg.vram = NULL;
    cfg.backend = o.backend;
    cfg.gl_use_egl = o.use_egl;
    cfg.hold_interrupts = o.hold;
    cfg.callbacks.user = &s;
    cfg.callbacks.signal = on_signal;
    cfg.callbacks.finish = on_finish;
    cfg.callbacks.error = on_error;
    if (ge2gl_create(&cfg, &s.ge) != GE2GL_OK) {
        fprintf(stderr, "threaded_host: ge2gl_create (%s backend) failed: %s\n", o.backend_name, ge2gl_last_message(NULL));
        goto done;
    }
    printf("threaded_host: %s backend, %lu lists, interrupts %s\n", o.backend_name, o.lists,
           o.hold ? "held until ge2gl_interrupt_ack (--hold)" : "handled while the callback waits");

    /* 2. sceGeSetCallback. */
    if (!check(&g, ge2gl_set_callback(s.ge, SIGNAL_FUNC, SIGNAL_ARG, FINISH_FUNC, FINISH_ARG, &g.cbid),
               "ge2gl_set_callback"))
        goto done;

    /* 3. The GE thread. */
    if (pthread_create(&ge_thread, NULL, ge_thread_main, &s) != 0) {
        fprintf(stderr, "threaded_host: cannot start the GE thread\n");
        goto done;
    }
    thread_started = 1;

    t0 = now_s();
    if (!play_lists(&g)) goto done;
    wall = now_s() - t0;

    /* 5. Stop the GE thread, then a wait-mode sceGeDrawSync(0) from this thread: the queue must be
       empty (it also frees the completed lists). */
    g_phase = 4;
    lock(&s);
    s.quit = 1;
    unlock(&s);
    pthread_join(ge_thread, NULL);
    thread_started = 0;
    g_phase = 5;
    if (!service_interrupts(&g)) goto done;
    {
        int32_t state = -1;
        if (!check(&g, ge2gl_draw_sync(s.ge, GE2GL_SYNC_WAIT, &state), "ge2gl_draw_sync(WAIT)")) goto done;
        if (state != GE2GL_LIST_COMPLETED) {
            fail(&g, "ge2gl_draw_sync(WAIT) did not report COMPLETED");
            goto done;
        }
    }

    if (!check_frame(&g, rgba, o.backend)) goto done;
    if (g.signals != g.lists || g.finishes != g.lists) {
        fail(&g, "the signal and finish counts do not match the lists");
    }
    print_result(&g, &s, o.lists, o.hold, wall);
    rc = g.failed ? 1 : 0;

done:
    if (thread_started) {
        /* After a failure: release a callback that waits for us, stop the GE thread. */
        lock(&s);
        s.quit = 1;
        s.abandon = 1;
        pthread_cond_broadcast(&s.done);
        unlock(&s);
        if (s.hold) ge2gl_interrupt_ack(s.ge); /* a held GE would only nap; harmless either way */
        pthread_join(ge_thread, NULL);
    }
    ge2gl_destroy(s.ge);
    alarm(0);
    pthread_cond_destroy(&s.done);
    pthread_mutex_destroy(&s.mu);
    free(g.ids);
    free(g.peek_us);
    free(rgba);
    return rc;
}
