/* SPDX-License-Identifier: MIT */
/*
 * ge2gl plugin API: the PSP Graphics Engine as a library for emulators. Plain C ABI (C99).
 *
 * An emulator hands ge2gl its emulated RAM and VRAM, forwards the game's sceGe calls
 * (sceGeListEnQueue, sceGeListUpdateStallAddr, sceGeListSync, sceGeDrawSync, sceGeBreak,
 * sceGeContinue, sceGeSetCallback, sceGeSaveContext, sceGeGetCmd, sceGeGetMtx, ...) to the
 * functions below, and receives the GE interrupts (signal, finish, end, error, progress) through
 * callbacks. Drawing goes to the software model or to OpenGL; frames are read back as RGBA8888
 * or, with OpenGL, as a texture.
 *
 * Conventions
 * - Every function returns a ge2gl_status. 0 is success. Failures of the sceGe functions are the
 *   PSP kernel error codes the firmware returns (GE2GL_SCE_ERROR_*), so an HLE can hand the value
 *   to the game unchanged; failures of the API itself are small negative numbers (GE2GL_ERR_*).
 *   ge2gl_last_message() explains the last failure on a handle; ge2gl_last_message(NULL) explains
 *   the calling thread's last failed ge2gl_create().
 * - Results come back through out-parameters (list IDs, sync states, register values).
 * - Nothing runs behind the host's back: by default the GE executes only inside ge2gl_run() and
 *   the wait modes of the sync functions, on the calling thread. Callbacks are delivered from
 *   inside those calls and may call back into the API (update a stall address, enqueue, break,
 *   continue); a wait or run from inside a callback returns GE2GL_ERR_REENTRANT.
 * - With config.worker_thread the GE runs on a ge2gl thread instead; callbacks then arrive on
 *   that thread. Callbacks never run with a ge2gl lock held. All functions are safe to call from
 *   any thread (GL_CURRENT: see Threads and GL below).
 * - Threads and GL (docs/plugin-api.md, "Threads"): calls on one handle are serialised. A headless
 *   GL context is made current on the calling thread for the duration of a call and the thread's
 *   previous context restored, so any thread may call. GL_CURRENT draws on the host's context:
 *   calls that need GL from a thread other than the creating one fail with GE2GL_ERR_WRONG_THREAD.
 * - GL state (GL_CURRENT): every binding and setting ge2gl changes is restored before a call
 *   returns; ge2gl sets what it needs on entry and never relies on what it left.
 * - Memory (docs/plugin-api.md, "Coherence"): after a list completes and whenever a sync returns,
 *   guest VRAM holds what was drawn (config.lazy_writeback defers that to ge2gl_sync_range). Guest
 *   memory the CPU wrote is noticed without ge2gl_mem_written: textures and CLUT-indexed data by
 *   hashing on use after every enqueue, continue and stall update, frame and depth buffers by a
 *   hash check before the GE draws over them.
 * - Guest addresses are PSP addresses (0x08800000, 0x44000000, ...). Bad addresses, IDs or sizes
 *   give a status code and change nothing.
 */
#ifndef GE2GL_H
#define GE2GL_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(GE2GL_BUILDING_LIBRARY)
#define GE2GL_API __declspec(dllexport)
#elif defined(_WIN32)
#define GE2GL_API __declspec(dllimport)
#elif defined(__GNUC__)
#define GE2GL_API __attribute__((visibility("default")))
#else
#define GE2GL_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* API version: major in bits 31..16, minor in 15..0. A host built against major M works with any
 * library of major M and a minor at least its own. */
#define GE2GL_API_VERSION_MAJOR 1
#define GE2GL_API_VERSION_MINOR 6
#define GE2GL_API_VERSION ((uint32_t)((GE2GL_API_VERSION_MAJOR << 16) | GE2GL_API_VERSION_MINOR))

typedef struct ge2gl_context ge2gl_context; /* opaque handle */
typedef int32_t ge2gl_status;

/* ---- Status codes ---------------------------------------------------------------------- */
#define GE2GL_OK 0
/* API errors. */
#define GE2GL_ERR_INVALID_ARGUMENT (-1) /* NULL pointer, bad enum value, too small buffer */
#define GE2GL_ERR_INVALID_HANDLE (-2)
#define GE2GL_ERR_VERSION (-3)          /* config.api_version / struct_size not supported */
#define GE2GL_ERR_BACKEND (-4)          /* the backend is not built in or failed to start */
#define GE2GL_ERR_WOULD_BLOCK (-5)      /* a wait cannot finish: the GE is stalled, paused, hung,
                                           or used up config.wait_budget commands */
#define GE2GL_ERR_REENTRANT (-6)        /* a run or wait from inside a ge2gl callback */
#define GE2GL_ERR_BAD_STATE (-7)        /* e.g. ge2gl_run() in worker-thread mode */
#define GE2GL_ERR_MEMORY (-8)           /* guest address range outside RAM/VRAM/scratchpad */
#define GE2GL_ERR_OUT_OF_HOST_MEMORY (-9)
#define GE2GL_ERR_UNSUPPORTED (-10)     /* e.g. a GL texture from the software backend */
#define GE2GL_ERR_WRONG_THREAD (-11)    /* GL work asked on a thread that cannot reach the host's
                                           GL context (GL_CURRENT: not the creating thread) */
#define GE2GL_ERR_GL_CONTEXT (-12)      /* API 1.5, GL_CURRENT: the context current on the calling
                                           thread is not the one the instance was created with (nor
                                           one sharing its objects), or none is; nothing was drawn */
#define GE2GL_ERR_TIME_BUDGET (-13)     /* API 1.5: a draw took more than config.run_budget_us of GE
                                           time and was cut there (the message says where) */
/* PSP kernel error codes returned by the sceGe functions (values as on hardware). */
#define GE2GL_SCE_ERROR_INVALID_STATE ((ge2gl_status)0x80000004u)
#define GE2GL_SCE_ERROR_ALREADY ((ge2gl_status)0x80000020u)
#define GE2GL_SCE_ERROR_BUSY ((ge2gl_status)0x80000021u)          /* also: list queued twice */
#define GE2GL_SCE_ERROR_OUT_OF_MEMORY ((ge2gl_status)0x80000022u) /* 64 lists / 16 callbacks */
#define GE2GL_SCE_ERROR_BAD_POINTER ((ge2gl_status)0x80000023u)   /* outside guest memory */
#define GE2GL_SCE_ERROR_INVALID_ID ((ge2gl_status)0x80000100u)
#define GE2GL_SCE_ERROR_INVALID_INDEX ((ge2gl_status)0x80000102u)
#define GE2GL_SCE_ERROR_INVALID_POINTER ((ge2gl_status)0x80000103u) /* misaligned */
#define GE2GL_SCE_ERROR_INVALID_SIZE ((ge2gl_status)0x80000104u)
#define GE2GL_SCE_ERROR_INVALID_MODE ((ge2gl_status)0x80000107u)
#define GE2GL_SCE_ERROR_INVALID_VALUE ((ge2gl_status)0x800001FEu)

/* ---- Enumerations ------------------------------------------------------------------------ */
/* Backends. */
#define GE2GL_BACKEND_NULL 0        /* decode and execute, draw nothing (transfers still happen) */
#define GE2GL_BACKEND_SOFT 1        /* the bit-accurate software model, draws into VRAM */
#define GE2GL_BACKEND_GL_CURRENT 2  /* OpenGL on the context the host made current */
#define GE2GL_BACKEND_GL_HEADLESS 3 /* OpenGL on a context ge2gl creates (OSMesa/EGL) */

/* GL backends' mode (config.gl_mode, API 1.1). */
#define GE2GL_GL_MODE_EXACT 0 /* the software model's rasteriser arithmetic per pixel, 1x only */
#define GE2GL_GL_MODE_HW 1    /* native GL rasterisation at config.render_scale */

/* Accuracy profile (config.accuracy, API 1.6; docs/accuracy.md "Accuracy profiles"). */
#define GE2GL_ACCURACY_PSP 0    /* what the PSP's GE does: every hardware-measured rule (default) */
#define GE2GL_ACCURACY_PPSSPP 1 /* PPSSPP's software renderer's pixels, its optimisation artefacts
                                   included (to compare with its renders) */

/* sceGeListSync / sceGeDrawSync peek results. */
#define GE2GL_LIST_COMPLETED 0
#define GE2GL_LIST_QUEUED 1
#define GE2GL_LIST_DRAWING 2
#define GE2GL_LIST_STALLING 3
#define GE2GL_LIST_PAUSED 4

/* Sync modes. */
#define GE2GL_SYNC_WAIT 0
#define GE2GL_SYNC_PEEK 1

/* Where the GE stands after ge2gl_run(). */
#define GE2GL_GE_IDLE 0    /* no list queued */
#define GE2GL_GE_READY 1   /* budget used up, more commands ready: run again */
#define GE2GL_GE_STALLED 2 /* the current list reached its stall address */
#define GE2GL_GE_PAUSED 3  /* the current list is paused (break, signal pause, head enqueue) */
#define GE2GL_GE_HUNG 4    /* END without SIGNAL/FINISH: the list never finishes (reset with
                              ge2gl_break(h, 1, NULL)) */
#define GE2GL_GE_INTERRUPT 5 /* config.hold_interrupts: a signal or finish callback was delivered
                                and the GE waits for ge2gl_interrupt_ack() */
#define GE2GL_GE_BREAK 6     /* API 1.3: a debugger breakpoint stopped the GE before the command at
                                info.pc; the next run executes it */

/* Frame-buffer pixel formats (CMD_FPF codes). */
#define GE2GL_FORMAT_565 0
#define GE2GL_FORMAT_5551 1
#define GE2GL_FORMAT_4444 2
#define GE2GL_FORMAT_8888 3

/* ---- Callbacks --------------------------------------------------------------------------- */
/* One GE interrupt, as the game's sceGe callback would see it. */
typedef struct ge2gl_interrupt {
    int32_t list_id;
    int32_t cbid;        /* callback ID given at enqueue; -1: the game asked for none */
    int32_t registered;  /* 1 when cbid names a callback registered with ge2gl_set_callback */
    uint32_t behaviour;  /* SIGNAL behaviour code (1 suspend, 2 continue, 3 pause); 0 for finish */
    uint32_t arg;        /* SIGNAL/FINISH argument, bits 15..0: the callback's first argument */
    uint32_t pc;         /* list address after the END: the third argument (0 for SDK <= 2.00.10) */
    uint32_t end_arg;    /* argument of the END word after the SIGNAL */
    uint32_t func;       /* guest function registered for this callback (signal or finish) */
    uint32_t func_arg;   /* its second argument */
    /* API 1.3: the GE time at which it occurred, in ticks of the PSP's 222 MHz clock since the
       handle was created (docs/timing.md; ge2gl_get_tick). */
    uint64_t tick;
} ge2gl_interrupt;

/* Host callbacks; every pointer may be NULL. They run on the thread that runs the GE (inside
   ge2gl_run or a wait, or on the worker) with no ge2gl lock held: a callback may call ge2gl
   (except run and the wait syncs) and may block on another thread of the host that calls ge2gl. */
typedef struct ge2gl_callbacks {
    void* user;
    /* SIGNAL with a handler behaviour (sub-interrupt 2*cbid). For behaviour 3 (pause) the list is
       already paused; the game resumes it with sceGeContinue. */
    void (*signal)(void* user, const ge2gl_interrupt* irq);
    /* FINISH + END: the list is complete (sub-interrupt 2*cbid+1). */
    void (*finish)(void* user, const ge2gl_interrupt* irq);
    /* Every END the GE reads (INTEND). */
    void (*end)(void* user, int32_t list_id, uint32_t pc);
    /* A list fault (bad address, stack overflow, hang). The faulting list is dropped (or, for a
       hang, stays unfinished); message is valid during the call. */
    void (*error)(void* user, int32_t list_id, uint32_t pc, const char* message);
    /* The GE has finished reading list_id up to (not including) read_up_to. */
    void (*progress)(void* user, int32_t list_id, uint32_t read_up_to);
} ge2gl_callbacks;

/* ---- Creation ---------------------------------------------------------------------------- */
typedef struct ge2gl_config {
    uint32_t struct_size; /* sizeof(ge2gl_config) */
    uint32_t api_version; /* GE2GL_API_VERSION */
    /* Emulated RAM at 0x08000000 and VRAM (2 MiB) at 0x04000000, owned by the host and used in
       place (no copies). NULL: ge2gl allocates zeroed memory; the host then moves data with
       ge2gl_mem_write/ge2gl_mem_read or ge2gl_mem_pointer. */
    uint8_t* ram;
    uint32_t ram_size;    /* bytes at ram (or to allocate), respected exactly: the GE reads
                             nothing past it. Required with a host ram; 0 without: 64 MiB */
    uint8_t* vram;        /* 0x200000 bytes */
    int32_t backend;      /* GE2GL_BACKEND_* */
    uint32_t sdk_version; /* the game's sceKernelGetCompiledSdkVersion(); 0 = 0x06060010 */
    int32_t worker_thread;/* nonzero: run the GE on a ge2gl thread (not with GL backends) */
    uint64_t wait_budget; /* commands one wait-mode sync may execute; 0 = 2^26 */
    int32_t soft_threads; /* software backend rasterising threads; 0 = all cores (same output) */
    int32_t gl_use_egl;   /* GE2GL_BACKEND_GL_HEADLESS: nonzero = EGL surfaceless, 0 = OSMesa */
    ge2gl_callbacks callbacks;
    /* API 1.1. A host built against 1.0 passes the smaller struct_size and gets the defaults. */
    int32_t gl_mode;      /* GE2GL_GL_MODE_EXACT (default) or GE2GL_GL_MODE_HW */
    int32_t render_scale; /* GL_MODE_HW: internal resolution 1-8 x the PSP's; 0 = 1. VRAM and the
                             frame read back stay in PSP pixels (box-downsampled) */
    /* API 1.2. */
    /* GL_CURRENT: the host's GL loader (SDL_GL_GetProcAddress, glfwGetProcAddress,
       eglGetProcAddress, ...); every GL entry point ge2gl calls is loaded through it. NULL: the
       loader of whichever of EGL or OSMesa has a context current. */
    void* (*gl_get_proc_address)(const char* name);
    /* GL backends. 0: after every list that completes and before every sync returns, guest VRAM
       holds what was drawn. Nonzero: VRAM is written only by ge2gl_sync_range, ge2gl_mem_read and
       ge2gl_read_frame; vram_dirty announces ranges the GPU drew into since their last write. */
    int32_t lazy_writeback;
    /* Nonzero: after a signal or finish callback the GE stops (ge2gl_run reports
       GE2GL_GE_INTERRUPT, waits return GE2GL_ERR_WOULD_BLOCK) until ge2gl_interrupt_ack(), so the
       host can run the guest handler before the list goes on, as the PSP does. */
    int32_t hold_interrupts;
    /* lazy_writeback: the GPU drew into [addr, addr+size) of VRAM (once per range until it is
       written back). Called on the thread that runs the GE, with callbacks.user. May be NULL. */
    void (*vram_dirty)(void* user, uint32_t addr, uint32_t size);
    /* API 1.5. The emulated GE time, in microseconds of the PSP's GE clock, that one ge2gl_run or
       ge2gl_run_until call may spend and that one draw may take anywhere: 0 = 166,667 (ten 60 Hz
       frames, what dump replay allows a frame); UINT32_MAX = no limit. A run stops between
       commands once the call has spent it (GE2GL_OK, ge_state GE2GL_GE_READY). A draw that alone
       would take longer is cut there (its vertex work past the budget is not drawn, its pixels
       stop at it) and the run or wait returns GE2GL_ERR_TIME_BUDGET; the list goes on after that
       command at the next call. Counted in ge2gl_stats.draws_cut. */
    uint32_t run_budget_us;
    /* API 1.5. A draw lost data and the list went on: vertices or indices outside guest memory
       (the vertices there are not drawn), a patch past the tessellator's cap of 2^21 vertices (not
       drawn), a draw cut at run_budget_us. `pc` is the address after the draw command. Called on
       the thread that runs the GE, with callbacks.user, under the same rules as the other
       callbacks. May be NULL: ge2gl_get_stats counts them and keeps the last message. */
    void (*drop)(void* user, int32_t list_id, uint32_t pc, const char* message);
    /* API 1.6. GE2GL_ACCURACY_PSP (0, the default, also for hosts built against an older API) or
       GE2GL_ACCURACY_PPSSPP: which rules the backend follows where the PSP and PPSSPP's software
       renderer differ. */
    int32_t accuracy;
} ge2gl_config;

/* The version of the library actually loaded. */
GE2GL_API uint32_t ge2gl_api_version(void);
/* "GE2GL_ERR_WOULD_BLOCK", "SCE_ERROR_BUSY", ... (static strings). */
GE2GL_API const char* ge2gl_status_name(ge2gl_status status);
/* Fills *config with defaults (soft backend, ge2gl-owned 64 MiB RAM and VRAM). */
GE2GL_API void ge2gl_config_init(ge2gl_config* config);
/* On failure *out is NULL and ge2gl_last_message(NULL) says why (per thread). */
GE2GL_API ge2gl_status ge2gl_create(const ge2gl_config* config, ge2gl_context** out);
/* Stops the worker thread (if any) and frees everything. NULL is allowed. GL_CURRENT: call it on
   the creating thread with the host's context current, or the GL objects are left to the host's
   context. A headless context is released and the thread's previous context restored. */
GE2GL_API void ge2gl_destroy(ge2gl_context* h);
/* Why the last failing call on h failed ("" if it succeeded). Valid until the next call on h.
   NULL: why this thread's last ge2gl_create failed ("" if it succeeded). */
GE2GL_API const char* ge2gl_last_message(ge2gl_context* h);

/* API 1.5: counters since creation (or the last state load). */
typedef struct ge2gl_stats {
    uint32_t struct_size;   /* sizeof(ge2gl_stats), set by the caller */
    uint64_t commands;      /* GE commands executed */
    uint64_t draws;         /* PRIM, BEZIER and SPLINE commands */
    uint64_t ge_ticks;      /* ge2gl_get_tick */
    uint64_t draws_dropped; /* draws that lost data (config.drop) */
    uint64_t draws_cut;     /* draws cut at config.run_budget_us */
    char last_drop[256];    /* the last drop's message ("" if none) */
} ge2gl_stats;
GE2GL_API ge2gl_status ge2gl_get_stats(ge2gl_context* h, ge2gl_stats* out);

/* ---- Guest memory ------------------------------------------------------------------------ */
GE2GL_API ge2gl_status ge2gl_mem_write(ge2gl_context* h, uint32_t addr, const void* src, uint32_t size);
GE2GL_API ge2gl_status ge2gl_mem_read(ge2gl_context* h, uint32_t addr, void* dst, uint32_t size);
/* Host pointer to [addr, addr+size) (one region), or GE2GL_ERR_MEMORY. */
GE2GL_API ge2gl_status ge2gl_mem_pointer(ge2gl_context* h, uint32_t addr, uint32_t size, uint8_t** out);
/* The host wrote guest memory directly (textures, CLUTs, frame buffers): the fast path; ge2gl
   also finds unreported writes by hashing (see Memory above). */
GE2GL_API ge2gl_status ge2gl_mem_written(ge2gl_context* h, uint32_t addr, uint32_t size);
/* Writes what the GPU drew over [addr, addr+size) into guest memory in place (the host's VRAM
   when it gave one). Needed only with config.lazy_writeback; harmless otherwise. */
GE2GL_API ge2gl_status ge2gl_sync_range(ge2gl_context* h, uint32_t addr, uint32_t size);

/* ---- sceGe ------------------------------------------------------------------------------- */
/* SceGeListArgs as the game passed it (read it from guest memory yourself). */
typedef struct ge2gl_list_args {
    uint32_t size;       /* 16 enables num_stacks/stacks */
    uint32_t context;    /* guest address of a 512-word context, or 0 */
    uint32_t num_stacks; /* SIGNAL CALL depth (< 256) */
    uint32_t stacks;     /* guest address of the stack buffer (8 words per entry), or 0 */
} ge2gl_list_args;

/* sceGeListEnQueue / sceGeListEnQueueHead. args may be NULL. */
GE2GL_API ge2gl_status ge2gl_list_enqueue(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid,
                                          const ge2gl_list_args* args, int32_t* out_id);
GE2GL_API ge2gl_status ge2gl_list_enqueue_head(ge2gl_context* h, uint32_t list, uint32_t stall, int32_t cbid,
                                               const ge2gl_list_args* args, int32_t* out_id);
GE2GL_API ge2gl_status ge2gl_list_dequeue(ge2gl_context* h, int32_t id);
GE2GL_API ge2gl_status ge2gl_list_update_stall(ge2gl_context* h, int32_t id, uint32_t stall);
/* mode GE2GL_SYNC_WAIT runs the GE until the list completes (GE2GL_ERR_WOULD_BLOCK when it
   cannot); GE2GL_SYNC_PEEK stores a GE2GL_LIST_* state. out_state may be NULL. */
GE2GL_API ge2gl_status ge2gl_list_sync(ge2gl_context* h, int32_t id, int32_t mode, int32_t* out_state);
GE2GL_API ge2gl_status ge2gl_draw_sync(ge2gl_context* h, int32_t mode, int32_t* out_state);
/* sceGeBreak: mode 0 pauses the current list (its ID in *out_id), mode 1 resets the queue. */
GE2GL_API ge2gl_status ge2gl_break(ge2gl_context* h, int32_t mode, int32_t* out_id);
GE2GL_API ge2gl_status ge2gl_continue(ge2gl_context* h);
/* sceGeSetCallback: guest function addresses and arguments (opaque to ge2gl, handed back in
   ge2gl_interrupt). *out_cbid is 0-15. */
GE2GL_API ge2gl_status ge2gl_set_callback(ge2gl_context* h, uint32_t signal_func, uint32_t signal_arg,
                                          uint32_t finish_func, uint32_t finish_arg, int32_t* out_cbid);
GE2GL_API ge2gl_status ge2gl_unset_callback(ge2gl_context* h, int32_t cbid);
/* sceGeSaveContext / sceGeRestoreContext with a host buffer or at a guest address. */
GE2GL_API ge2gl_status ge2gl_save_context(ge2gl_context* h, uint32_t ctx[512]);
GE2GL_API ge2gl_status ge2gl_restore_context(ge2gl_context* h, const uint32_t ctx[512]);
GE2GL_API ge2gl_status ge2gl_save_context_at(ge2gl_context* h, uint32_t guest_addr);
GE2GL_API ge2gl_status ge2gl_restore_context_at(ge2gl_context* h, uint32_t guest_addr);
/* sceGeGetCmd: the register word of opcode op (0-0xFE). */
GE2GL_API ge2gl_status ge2gl_get_cmd(ge2gl_context* h, uint32_t op, uint32_t* out_word);
/* API 1.4: the game's sceKernelGetCompiledSdkVersion() changed (a game may set it at run time with
   sceKernelSetCompiledSdkVersion*): behaviours that depend on it follow from the next call. 0 is
   the value of a program built without one, which the firmware treats as an old SDK (unlike
   config.sdk_version, where 0 asks for the default). */
GE2GL_API ge2gl_status ge2gl_set_sdk_version(ge2gl_context* h, uint32_t version);
/* API 1.4: every register word at once, out[op] as ge2gl_get_cmd gives it for op 0-0xFE (out[0xFF]
   is 0): one call for a host that keeps its own copy of the register file (an emulator whose
   other parts read its GE state struct) and refreshes it after each run. */
GE2GL_API ge2gl_status ge2gl_get_registers(ge2gl_context* h, uint32_t out[256]);
/* API 1.4: sceGeGetStack. *out_depth (may be NULL) gets the SIGNAL CALL depth of the list the GE
   is in (0 when it is in none); for 0 <= index < depth, entry index is written to out (8 words;
   may be NULL): word 1 the return address, 2 its OFFSET, 7 its BASE register word, the others 0. An index at
   or past the depth inside a list gives GE2GL_SCE_ERROR_INVALID_INDEX. */
GE2GL_API ge2gl_status ge2gl_get_stack(ge2gl_context* h, int32_t index, uint32_t out[8], int32_t* out_depth);
/* sceGeGetMtx: type 0-7 bones, 8 world, 9 view, 10 projection (16 words), 11 texgen; float24
   words (bits 31..8 of the IEEE value, shifted down). out must hold 16 words. */
GE2GL_API ge2gl_status ge2gl_get_matrix(ge2gl_context* h, int32_t type, uint32_t out[16], int32_t* out_count);
/* sceGeEdramSetAddrTranslation: 0, 0x200, 0x400, 0x800 or 0x1000; *out_previous may be NULL. */
GE2GL_API ge2gl_status ge2gl_edram_set_translation(ge2gl_context* h, uint32_t value, uint32_t* out_previous);
/* sceGeEdramGetAddr (0x04000000) / sceGeEdramGetSize (0x00200000). */
GE2GL_API ge2gl_status ge2gl_edram_get_addr(ge2gl_context* h, uint32_t* out);
GE2GL_API ge2gl_status ge2gl_edram_get_size(ge2gl_context* h, uint32_t* out);

/* ---- Execution --------------------------------------------------------------------------- */
typedef struct ge2gl_run_info {
    int32_t ge_state;  /* GE2GL_GE_* */
    int32_t list_id;   /* current list, -1 if none */
    uint32_t pc;       /* its read position */
    uint32_t stall;    /* its stall address (0 = none) */
    uint64_t commands; /* commands this call executed */
} ge2gl_run_info;

/* Runs queued lists in order for at most max_commands commands (0 only reports the position).
   out may be NULL. GE2GL_ERR_BAD_STATE in worker-thread mode. */
GE2GL_API ge2gl_status ge2gl_run(ge2gl_context* h, uint64_t max_commands, ge2gl_run_info* out);
/* ---- GE time (API 1.3; docs/timing.md) ---- */
/* The GE-time estimate so far: ticks of the PSP's 222 MHz clock the GE's work would have taken
   since the handle was created (commands, vertices, pixels, transfers). */
GE2GL_API ge2gl_status ge2gl_get_tick(ge2gl_context* h, uint64_t* out_tick);
/* GE time spent running list id (PPSSPP's GetListTicks): GE2GL_SCE_ERROR_INVALID_ID for an ID
   that names no list. */
GE2GL_API ge2gl_status ge2gl_list_ticks(ge2gl_context* h, int32_t id, uint64_t* out_ticks);
/* As ge2gl_run, but runs until the GE time reaches `tick` (the command that crosses it completes),
   the GE cannot go on, or config.wait_budget commands ran: a host that schedules the GE in
   emulated time calls it with its own next event's time, and interrupts come at their tick. */
GE2GL_API ge2gl_status ge2gl_run_until(ge2gl_context* h, uint64_t tick, ge2gl_run_info* out);

/* config.hold_interrupts: the host has handled the interrupt(s) delivered so far; the GE goes on.
   GE2GL_ERR_BAD_STATE when no interrupt is held. */
GE2GL_API ge2gl_status ge2gl_interrupt_ack(ge2gl_context* h);

/* ---- Frames ------------------------------------------------------------------------------ */
/* Pixels of a frame buffer as RGBA8888 (R in the first byte), width*height*4 bytes, rows top to
   bottom. addr is a VRAM address, stride in pixels, format GE2GL_FORMAT_*. Everything drawn so far
   is flushed to VRAM first. */
GE2GL_API ge2gl_status ge2gl_read_frame(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format,
                                        uint32_t width, uint32_t height, uint8_t* out_rgba, size_t out_size);
/* GL backends: a GL_TEXTURE_2D (RGBA8, row 0 = top line, alpha 255) holding the width x height
   frame at addr (VRAM or RAM), at the render scale (width*N x height*N). Drawn on the GPU from the
   render target that holds the frame, or uploaded from guest memory where none does. Owned by
   ge2gl, valid on the GL context until the next call on h. GE2GL_ERR_UNSUPPORTED for other
   backends. */
GE2GL_API ge2gl_status ge2gl_frame_texture(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format,
                                           uint32_t width, uint32_t height, uint32_t* out_texture);
/* The same at out_width x out_height (1-8192), bilinearly resampled on the GPU: an exact copy when
   the size is the frame's at the render scale. */
GE2GL_API ge2gl_status ge2gl_frame_texture_sized(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format,
                                                 uint32_t width, uint32_t height, uint32_t out_width,
                                                 uint32_t out_height, uint32_t* out_texture);

/* ---- Debugger (API 1.3; docs/debugger.md) ----------------------------------------------- */
/* One-shot stops, OR'd together; the first that applies stops ge2gl_run / ge2gl_run_until
   (GE2GL_GE_BREAK) and clears them all. Sync waits and the worker thread run through stops. */
#define GE2GL_BREAK_NEXT_COMMAND 1u /* before the next command */
#define GE2GL_BREAK_NEXT_DRAW 2u    /* before the next PRIM, BEZIER or SPLINE */
#define GE2GL_BREAK_NEXT_PRIM 4u    /* before the next PRIM */
#define GE2GL_BREAK_NEXT_LIST 8u    /* before the first command of another list */
#define GE2GL_BREAK_NEXT_FRAME 16u  /* before the first command after the GE ran out of lists */
GE2GL_API ge2gl_status ge2gl_debug_break_next(ge2gl_context* h, uint32_t flags);
/* Lasting breakpoints: before every command with opcode op (0-255), before the command at addr. */
GE2GL_API ge2gl_status ge2gl_debug_break_opcode(ge2gl_context* h, uint32_t op, int32_t on);
GE2GL_API ge2gl_status ge2gl_debug_break_address(ge2gl_context* h, uint32_t addr, int32_t on);
GE2GL_API ge2gl_status ge2gl_debug_clear_breaks(ge2gl_context* h);
/* Executes the command (GE2GL_STEP_COMMAND) or runs through the next draw (GE2GL_STEP_DRAW) and
   stops before the command after it: ge2gl_run with one stop set. */
#define GE2GL_STEP_COMMAND 0
#define GE2GL_STEP_DRAW 1
GE2GL_API ge2gl_status ge2gl_debug_step(ge2gl_context* h, int32_t what, ge2gl_run_info* out);
/* Text: GE2GL_DEBUG_STATE every register with its fields named and the matrices; GE2GL_DEBUG_LIST
   the running list's pc, stall, CALL/SIGNAL stacks, BASE, OFFSET; GE2GL_DEBUG_DISASM 16 commands
   from 4 before the pc; GE2GL_DEBUG_REASON why the GE last stopped. *needed (may be NULL) gets the
   size with the terminating NUL; a buffer too small gives GE2GL_ERR_INVALID_ARGUMENT. */
#define GE2GL_DEBUG_STATE 0
#define GE2GL_DEBUG_LIST 1
#define GE2GL_DEBUG_DISASM 2
#define GE2GL_DEBUG_REASON 3
GE2GL_API ge2gl_status ge2gl_debug_text(ge2gl_context* h, int32_t what, char* buf, size_t size, size_t* needed);
/* Sets a register as if the list had sent the word (opcode in bits 31..24), without its side
   effects (no draw, jump or transfer is started: those opcodes are refused). */
GE2GL_API ge2gl_status ge2gl_debug_set_register(ge2gl_context* h, uint32_t word);
/* The buffers the GE draws into now (FBP/FBW/FPF, ZBP/ZBW): GE2GL_DEBUG_COLOR as RGBA8888 (4 bytes
   a pixel), GE2GL_DEBUG_DEPTH as uint16_t values, GE2GL_DEBUG_STENCIL one byte a pixel (the colour
   buffer's alpha bits). Rows top to bottom; what was drawn so far is written back first. */
#define GE2GL_DEBUG_COLOR 0
#define GE2GL_DEBUG_DEPTH 1
#define GE2GL_DEBUG_STENCIL 2
GE2GL_API ge2gl_status ge2gl_debug_read_buffer(ge2gl_context* h, int32_t which, uint32_t width, uint32_t height,
                                               void* out, size_t size);
/* Level 0-7 of the bound texture decoded (CLUT applied) to RGBA8888. *out_w / *out_h get its
   size; out may be NULL to ask only that. */
GE2GL_API ge2gl_status ge2gl_debug_read_texture(ge2gl_context* h, int32_t level, uint32_t* out_w, uint32_t* out_h,
                                                uint8_t* out, size_t size);
/* The palette RAM decoded in the CLUT format to RGBA8888 words (R in bits 7..0): 256 entries for
   a 32-bit CLUT, 512 for 16-bit. */
GE2GL_API ge2gl_status ge2gl_debug_read_clut(ge2gl_context* h, uint32_t* out, uint32_t capacity, uint32_t* out_count);
/* The vertices of the PRIM at the pc (stopped before it), in draw order: as decoded (model space,
   or drawing coordinates in through mode) and after transform, as the rasteriser gets them. */
typedef struct ge2gl_debug_vertex {
    float pos[3], uv[2], normal[3];
    uint8_t color[4];
    float screen_x, screen_y; /* drawing coordinates in pixels (1/16 precision) */
    int32_t screen_z;         /* 0-65535 */
    float s, t, q;            /* texture coordinates, units of the level-0 size */
    uint8_t lit_color[4];     /* after lighting */
    int32_t outside;          /* breaks the screen range rule: its primitive is dropped */
} ge2gl_debug_vertex;
GE2GL_API ge2gl_status ge2gl_debug_vertices(ge2gl_context* h, ge2gl_debug_vertex* out, uint32_t capacity,
                                            uint32_t* out_count);

/* ---- Save states (API 1.3; format: docs/savestate.md) ------------------------------------ */
/* Include guest RAM, VRAM and the scratchpad (zstd-compressed) in the state. Without it the host
   saves its own memory; VRAM still holds every pixel drawn (GL render targets are written back). */
#define GE2GL_STATE_WITH_MEMORY 1u

/* Serialises the whole GE at this point (between commands, including mid-list at a stall or with
   an interrupt held): registers, matrices, palette, every list's state and the queue, callbacks,
   the GE-time count. *out_data points to the blob, owned by ge2gl and valid until the next
   ge2gl_state_save or ge2gl_destroy on h. GE2GL_ERR_REENTRANT from inside a callback. */
GE2GL_API ge2gl_status ge2gl_state_save(ge2gl_context* h, uint32_t flags, const void** out_data, size_t* out_size);
/* Restores a blob from ge2gl_state_save of any backend. The blob is checked whole first: a corrupt,
   truncated or foreign one gives GE2GL_ERR_INVALID_ARGUMENT with the reason in
   ge2gl_last_message() and leaves the GE as it was. Every backend cache is dropped (guest memory
   is read again when next used): a host that restores its own memory does so before this call,
   or calls ge2gl_mem_written after it. */
GE2GL_API ge2gl_status ge2gl_state_load(ge2gl_context* h, const void* data, size_t size);

/* ---- Frame-dump recording (API 1.3; docs/recording.md) --------------------------------- */
/* Records what the GE executes on h between ge2gl_record_begin and ge2gl_record_end as a PPSSPP
   frame dump (.ppdmp version 6, as PPSSPP's GE recorder writes it): the GE context at the start,
   every state command, the vertices, indices, texture levels, CLUTs and transfer sources the
   draws read, and the host's writes into VRAM (ge2gl_mem_write, ge2gl_mem_written) as
   MEMCPY/MEMSET records. PPSSPP's player and `ge2gl render` replay the file to the same picture.
   Call between GE commands (not from a callback: GE2GL_ERR_REENTRANT).
   begin: GE2GL_ERR_INVALID_ARGUMENT for a NULL/empty path or one that cannot be written (the
   message carries the system's error text; the file is created at end); GE2GL_ERR_BAD_STATE when
   already recording. end: writes the file; GE2GL_ERR_BAD_STATE when not recording,
   GE2GL_ERR_INVALID_ARGUMENT with the system's error text when the file cannot be written (the
   recording is dropped either way). After a successful end, ge2gl_last_message(h) lists what the
   dump could not express ("" when nothing). Destroying h while recording drops the recording. */
GE2GL_API ge2gl_status ge2gl_record_begin(ge2gl_context* h, const char* path);
/* The frame buffer the host displays (sceDisplaySetFrameBuf) while recording: a DISPLAY record.
   The dump ends with the last one given (or, without one, with the GE's current frame buffer).
   format: GE2GL_FORMAT_*. GE2GL_ERR_BAD_STATE when not recording. */
GE2GL_API ge2gl_status ge2gl_record_display(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format);
GE2GL_API ge2gl_status ge2gl_record_end(ge2gl_context* h);

/* ---- Dump replay (integration testing) -------------------------------------------------- */
/* The frame buffer a dump displays (its last DISPLAY record, or the last drawing target). */
typedef struct ge2gl_display {
    uint32_t addr;   /* guest address */
    uint32_t stride; /* pixels */
    int32_t format;  /* GE2GL_FORMAT_* */
    uint32_t width, height; /* 480 x 272 */
} ge2gl_display;

/* Replays a PPSSPP GE dump (.ppdmp, or a .zip holding one) through h the way PPSSPP's player does
   (guest memory writes, list enqueues, stall updates and runs on h, callbacks delivered), so a host
   can check its integration (its GL context, threads, presentation) against `ge2gl render` on the
   same file. h needs 64 MiB of RAM; not in worker-thread mode. out may be NULL. */
GE2GL_API ge2gl_status ge2gl_replay_dump(ge2gl_context* h, const char* path, ge2gl_display* out);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* GE2GL_H */
