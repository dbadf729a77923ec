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
 *   ge2gl_last_message() explains the last failure on a handle.
 * - Results come back through out-parameters (list IDs, sync states, register values).
 * - Nothing runs behind the host's back: by default the GE executes only inside ge2gl_run() and
 *   the wait modes of the sync functions, on the calling thread. Callbacks are delivered from
 *   inside those calls and may call back into the API (update a stall address, enqueue, break,
 *   continue); a wait or run from inside a callback returns GE2GL_ERR_REENTRANT.
 * - With config.worker_thread the GE runs on a ge2gl thread instead; callbacks then arrive on
 *   that thread. All functions are safe to call from any thread in that mode.
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
#define GE2GL_API_VERSION_MINOR 0
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
} ge2gl_interrupt;

/* Host callbacks; every pointer may be NULL. They run on the thread that runs the GE. */
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
    uint32_t ram_size;    /* bytes at ram (or to allocate); 0 = 64 MiB */
    uint8_t* vram;        /* 0x200000 bytes */
    int32_t backend;      /* GE2GL_BACKEND_* */
    uint32_t sdk_version; /* the game's sceKernelGetCompiledSdkVersion(); 0 = 0x06060010 */
    int32_t worker_thread;/* nonzero: run the GE on a ge2gl thread (not with GL backends) */
    uint64_t wait_budget; /* commands one wait-mode sync may execute; 0 = 2^26 */
    int32_t soft_threads; /* software backend rasterising threads; 0 = all cores (same output) */
    int32_t gl_use_egl;   /* GE2GL_BACKEND_GL_HEADLESS: nonzero = EGL surfaceless, 0 = OSMesa */
    ge2gl_callbacks callbacks;
} ge2gl_config;

/* The version of the library actually loaded. */
GE2GL_API uint32_t ge2gl_api_version(void);
/* "GE2GL_ERR_WOULD_BLOCK", "SCE_ERROR_BUSY", ... (static strings). */
GE2GL_API const char* ge2gl_status_name(ge2gl_status status);
/* Fills *config with defaults (soft backend, ge2gl-owned 64 MiB RAM and VRAM). */
GE2GL_API void ge2gl_config_init(ge2gl_config* config);
GE2GL_API ge2gl_status ge2gl_create(const ge2gl_config* config, ge2gl_context** out);
/* Stops the worker thread (if any) and frees everything. NULL is allowed. */
GE2GL_API void ge2gl_destroy(ge2gl_context* h);
/* Why the last failing call on h failed ("" if it succeeded). Valid until the next call on h. */
GE2GL_API const char* ge2gl_last_message(ge2gl_context* h);

/* ---- Guest memory ------------------------------------------------------------------------ */
GE2GL_API ge2gl_status ge2gl_mem_write(ge2gl_context* h, uint32_t addr, const void* src, uint32_t size);
GE2GL_API ge2gl_status ge2gl_mem_read(ge2gl_context* h, uint32_t addr, void* dst, uint32_t size);
/* Host pointer to [addr, addr+size) (one region), or GE2GL_ERR_MEMORY. */
GE2GL_API ge2gl_status ge2gl_mem_pointer(ge2gl_context* h, uint32_t addr, uint32_t size, uint8_t** out);
/* The host wrote guest memory directly (textures, CLUTs): backends drop what they cached. */
GE2GL_API ge2gl_status ge2gl_mem_written(ge2gl_context* h, uint32_t addr, uint32_t size);

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

/* ---- Frames ------------------------------------------------------------------------------ */
/* Pixels of a frame buffer as RGBA8888 (R in the first byte), width*height*4 bytes, rows top to
   bottom. addr is a VRAM address, stride in pixels, format GE2GL_FORMAT_*. Everything drawn so far
   is flushed to VRAM first. */
GE2GL_API ge2gl_status ge2gl_read_frame(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format,
                                        uint32_t width, uint32_t height, uint8_t* out_rgba, size_t out_size);
/* GL backends: the GL texture holding that frame buffer (valid on the GL context until the next
   GE call). GE2GL_ERR_UNSUPPORTED for other backends. */
GE2GL_API ge2gl_status ge2gl_frame_texture(ge2gl_context* h, uint32_t addr, uint32_t stride, int32_t format,
                                           uint32_t width, uint32_t height, uint32_t* out_texture);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* GE2GL_H */
