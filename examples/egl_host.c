/* SPDX-License-Identifier: MIT */
/*
 * egl_host: ge2gl drawing in the host's own OpenGL context (GE2GL_BACKEND_GL_CURRENT), in C99.
 *
 * An emulator with its own renderer owns the GL context; ge2gl draws the GE's work into it and hands
 * back the frame as a texture, which the host draws wherever it presents. This host:
 *
 *   1. creates a desktop GL 3.3 core context on EGL's surfaceless platform (Mesa), with no window;
 *      it links libEGL only and loads every GL function it calls through eglGetProcAddress;
 *   2. creates a ge2gl context on it: GE2GL_BACKEND_GL_CURRENT, the hardware mode at render scale N,
 *      and the same loader for ge2gl (config.gl_get_proc_address);
 *   3. replays a GE dump through it (ge2gl_replay_dump) and asks for the displayed frame as a texture
 *      of the frame's size at the render scale (ge2gl_frame_texture_sized);
 *   4. draws that texture 1:1 into a render target of its own, reads it back and writes a binary PPM.
 *
 * Around every ge2gl call it sets a deliberately odd GL state (its own VAO, program, framebuffers,
 * textures on units 0-7, buffers, viewport, scissor, masks, blending, depth and stencil tests,
 * pixel-store parameters, ...) and afterwards checks that all of it is exactly as it left it: the
 * library promises to restore every binding and setting it changes before it returns.
 *
 *   usage: egl_host DUMP.ppdmp OUT.ppm [--scale N]      (N = 1-8, default 2)
 *
 * Exit status: 0 success; 1 a ge2gl or host error; 2 ge2gl changed the host's GL state (each
 * difference is printed); 77 no EGL surfaceless platform or GL 3.3 core context here (a skip).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h> /* types, constants and function-pointer types only: nothing links libGL */

#include "ge2gl/ge2gl.h"

#define EXIT_GE2GL 1
#define EXIT_STATE 2
#define EXIT_SKIP 77

/* ---- GL entry points, loaded through eglGetProcAddress ------------------------------------- */

#define GL_FUNCTIONS(X)                                               \
    X(PFNGLGETSTRINGPROC, GetString)                                  \
    X(PFNGLGETERRORPROC, GetError)                                    \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                              \
    X(PFNGLGETBOOLEANVPROC, GetBooleanv)                              \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                  \
    X(PFNGLISENABLEDPROC, IsEnabled)                                  \
    X(PFNGLENABLEPROC, Enable)                                        \
    X(PFNGLDISABLEPROC, Disable)                                      \
    X(PFNGLVIEWPORTPROC, Viewport)                                    \
    X(PFNGLSCISSORPROC, Scissor)                                      \
    X(PFNGLCOLORMASKPROC, ColorMask)                                  \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                  \
    X(PFNGLSTENCILMASKPROC, StencilMask)                              \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                  \
    X(PFNGLBLENDEQUATIONSEPARATEPROC, BlendEquationSeparate)          \
    X(PFNGLBLENDCOLORPROC, BlendColor)                                \
    X(PFNGLLOGICOPPROC, LogicOp)                                      \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                  \
    X(PFNGLDEPTHRANGEPROC, DepthRange)                                \
    X(PFNGLCULLFACEPROC, CullFace)                                    \
    X(PFNGLFRONTFACEPROC, FrontFace)                                  \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                              \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                      \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                      \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                \
    X(PFNGLCREATESHADERPROC, CreateShader)                            \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                            \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                          \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                              \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                    \
    X(PFNGLDELETESHADERPROC, DeleteShader)                            \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                          \
    X(PFNGLATTACHSHADERPROC, AttachShader)                            \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                              \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                            \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                  \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                          \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                  \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                      \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                      \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)            \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)        \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                \
    X(PFNGLGENTEXTURESPROC, GenTextures)                              \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                              \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                          \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                          \
    X(PFNGLGETTEXLEVELPARAMETERIVPROC, GetTexLevelParameteriv)        \
    X(PFNGLISTEXTUREPROC, IsTexture)                                  \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                        \
    X(PFNGLGENSAMPLERSPROC, GenSamplers)                              \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                              \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                  \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                        \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                \
    X(PFNGLBUFFERDATAPROC, BufferData)                                \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                          \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                \
    X(PFNGLFINISHPROC, Finish)

#define DECLARE_GL(type, name) type name;
static struct {
    GL_FUNCTIONS(DECLARE_GL)
} gl;

/* Loads the table; returns the name of the first missing function, or NULL. */
static const char* load_gl(void) {
#define LOAD_GL(type, name)                                   \
    gl.name = (type)eglGetProcAddress("gl" #name);            \
    if (!gl.name) return "gl" #name;
    GL_FUNCTIONS(LOAD_GL)
#undef LOAD_GL
    return NULL;
}

/* ge2gl's config.gl_get_proc_address wants void* (*)(const char*); eglGetProcAddress returns a
   function pointer. ISO C has no cast between the two, so the value goes through a union (POSIX
   guarantees that function and object pointers have the same representation). */
typedef char function_pointer_fits_in_void_pointer[sizeof(void*) == sizeof(__eglMustCastToProperFunctionPointerType) ? 1 : -1];

static void* egl_loader(const char* name) {
    union {
        __eglMustCastToProperFunctionPointerType fn;
        void* ptr;
    } u;
    u.ptr = NULL;
    u.fn = eglGetProcAddress(name);
    return u.ptr;
}

/* ---- the host's GL objects ---------------------------------------------------------------- */

#define UNITS 8 /* texture units the host keeps its textures on */

typedef struct host_objects {
    /* bound while ge2gl runs */
    GLuint vao, program, draw_fbo, read_fbo, fbo_tex[2], tex[UNITS];
    GLuint array_buffer, element_buffer, unpack_buffer, pack_buffer, uniform_buffer;
    /* presentation */
    GLuint present_program, present_fbo, present_tex, sampler;
} host_objects;

static host_objects obj;

static GLuint compile(GLenum kind, const char* src) {
    GLuint s = gl.CreateShader(kind);
    GLint ok = 0;
    gl.ShaderSource(s, 1, &src, NULL);
    gl.CompileShader(s);
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        gl.GetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "egl_host: shader compile failed: %s\n", log);
        gl.DeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint link_program(const char* vs_src, const char* fs_src) {
    GLuint vs = compile(GL_VERTEX_SHADER, vs_src), fs = compile(GL_FRAGMENT_SHADER, fs_src), p;
    GLint ok = 0;
    if (!vs || !fs) {
        if (vs) gl.DeleteShader(vs);
        if (fs) gl.DeleteShader(fs);
        return 0;
    }
    p = gl.CreateProgram();
    gl.AttachShader(p, vs);
    gl.AttachShader(p, fs);
    gl.LinkProgram(p);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024];
        gl.GetProgramInfoLog(p, sizeof log, NULL, log);
        fprintf(stderr, "egl_host: program link failed: %s\n", log);
        gl.DeleteProgram(p);
        return 0;
    }
    return p;
}

/* A w x h RGBA8 texture with nearest filtering and no mipmaps (complete as it is). */
static GLuint make_texture(GLsizei w, GLsizei h) {
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    return t;
}

static GLuint make_fbo(GLuint colour) {
    GLuint f = 0;
    gl.GenFramebuffers(1, &f);
    gl.BindFramebuffer(GL_FRAMEBUFFER, f);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "egl_host: framebuffer incomplete\n");
        return 0;
    }
    return f;
}

static GLuint make_buffer(GLenum target, GLsizeiptr size) {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(target, b);
    gl.BufferData(target, size, NULL, GL_STATIC_DRAW);
    return b;
}

static int create_objects(GLsizei out_w, GLsizei out_h) {
    static const char* trivial_vs = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    static const char* trivial_fs = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0, 0.0, 1.0, 1.0); }\n";
    /* One triangle covering the target; each fragment fetches the texel at its own pixel. */
    static const char* present_vs =
        "#version 330 core\n"
        "void main() {\n"
        "    vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n"
        "    gl_Position = vec4(p, 0.0, 1.0);\n"
        "}\n";
    static const char* present_fs =
        "#version 330 core\n"
        "uniform sampler2D frame;\n"
        "out vec4 colour;\n"
        "void main() { colour = texelFetch(frame, ivec2(gl_FragCoord.xy), 0); }\n";
    int u;

    obj.program = link_program(trivial_vs, trivial_fs);
    obj.present_program = link_program(present_vs, present_fs);
    if (!obj.program || !obj.present_program) return 0;

    gl.GenVertexArrays(1, &obj.vao);
    gl.BindVertexArray(obj.vao);
    obj.element_buffer = make_buffer(GL_ELEMENT_ARRAY_BUFFER, 64); /* part of the VAO */
    gl.BindVertexArray(0);
    obj.array_buffer = make_buffer(GL_ARRAY_BUFFER, 256);
    obj.unpack_buffer = make_buffer(GL_PIXEL_UNPACK_BUFFER, 4096);
    obj.pack_buffer = make_buffer(GL_PIXEL_PACK_BUFFER, 4096);
    obj.uniform_buffer = make_buffer(GL_UNIFORM_BUFFER, 256);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.BindBuffer(GL_UNIFORM_BUFFER, 0);

    gl.ActiveTexture(GL_TEXTURE0);
    for (u = 0; u < UNITS; ++u) obj.tex[u] = make_texture(4, 4);
    obj.fbo_tex[0] = make_texture(16, 16);
    obj.fbo_tex[1] = make_texture(16, 16);
    obj.present_tex = make_texture(out_w, out_h);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    obj.draw_fbo = make_fbo(obj.fbo_tex[0]);
    obj.read_fbo = make_fbo(obj.fbo_tex[1]);
    obj.present_fbo = make_fbo(obj.present_tex);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!obj.draw_fbo || !obj.read_fbo || !obj.present_fbo) return 0;

    /* Nearest, no mipmaps: the sampler decides completeness and filtering, so ge2gl's texture is
       sampled as it is without touching its parameters. */
    gl.GenSamplers(1, &obj.sampler);
    gl.SamplerParameteri(obj.sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.SamplerParameteri(obj.sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.SamplerParameteri(obj.sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(obj.sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return gl.GetError() == GL_NO_ERROR;
}

static void delete_objects(void) {
    GLuint buffers[5];
    gl.UseProgram(0);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (obj.program) gl.DeleteProgram(obj.program);
    if (obj.present_program) gl.DeleteProgram(obj.present_program);
    gl.DeleteVertexArrays(1, &obj.vao);
    buffers[0] = obj.array_buffer;
    buffers[1] = obj.element_buffer;
    buffers[2] = obj.unpack_buffer;
    buffers[3] = obj.pack_buffer;
    buffers[4] = obj.uniform_buffer;
    gl.DeleteBuffers(5, buffers);
    gl.DeleteFramebuffers(1, &obj.draw_fbo);
    gl.DeleteFramebuffers(1, &obj.read_fbo);
    gl.DeleteFramebuffers(1, &obj.present_fbo);
    gl.DeleteTextures(UNITS, obj.tex);
    gl.DeleteTextures(2, obj.fbo_tex);
    gl.DeleteTextures(1, &obj.present_tex);
    gl.DeleteSamplers(1, &obj.sampler);
}

/* ---- the scrambled state and its check ------------------------------------------------------ */

static const GLint odd_viewport[4] = {3, 5, 17, 19};
static const GLint odd_scissor[4] = {7, 11, 13, 23};
static const GLfloat odd_blend_colour[4] = {0.25f, 0.5f, 0.75f, 0.125f};
static const GLfloat odd_clear_colour[4] = {0.125f, 0.75f, 0.5f, 0.25f};
static const GLfloat odd_depth_range[2] = {0.25f, 0.75f};
#define ACTIVE_UNIT 3

/* Sets the host's odd state: nothing in it is a GL default, so a library that resets to defaults
   instead of restoring is caught as surely as one that leaves its own state behind. */
static void scramble(void) {
    int u;
    while (gl.GetError() != GL_NO_ERROR) {
    }
    gl.BindVertexArray(obj.vao);
    gl.UseProgram(obj.program);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, obj.draw_fbo);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, obj.read_fbo);
    gl.Viewport(odd_viewport[0], odd_viewport[1], odd_viewport[2], odd_viewport[3]);
    gl.Scissor(odd_scissor[0], odd_scissor[1], odd_scissor[2], odd_scissor[3]);
    gl.Enable(GL_SCISSOR_TEST);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.DepthMask(GL_FALSE);
    gl.StencilMask(0x5Au);
    gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_COLOR, GL_ONE_MINUS_DST_ALPHA, GL_CONSTANT_ALPHA, GL_DST_COLOR);
    gl.BlendEquationSeparate(GL_FUNC_REVERSE_SUBTRACT, GL_MAX);
    gl.BlendColor(odd_blend_colour[0], odd_blend_colour[1], odd_blend_colour[2], odd_blend_colour[3]);
    gl.Enable(GL_COLOR_LOGIC_OP);
    gl.LogicOp(GL_COPY_INVERTED);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_NEVER);
    gl.DepthRange(odd_depth_range[0], odd_depth_range[1]);
    gl.Enable(GL_STENCIL_TEST);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(GL_FRONT_AND_BACK);
    gl.FrontFace(GL_CW);
    gl.Enable(GL_CLIP_DISTANCE0);
    gl.ClearColor(odd_clear_colour[0], odd_clear_colour[1], odd_clear_colour[2], odd_clear_colour[3]);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 7);
    gl.PixelStorei(GL_UNPACK_SKIP_ROWS, 2);
    gl.PixelStorei(GL_UNPACK_SKIP_PIXELS, 3);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 5);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 1);
    gl.BindBuffer(GL_ARRAY_BUFFER, obj.array_buffer);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, obj.unpack_buffer);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, obj.pack_buffer);
    gl.BindBuffer(GL_UNIFORM_BUFFER, obj.uniform_buffer);
    for (u = 0; u < UNITS; ++u) {
        gl.ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        gl.BindTexture(GL_TEXTURE_2D, obj.tex[u]);
        gl.BindSampler((GLuint)u, 0);
    }
    gl.ActiveTexture(GL_TEXTURE0 + ACTIVE_UNIT);
}

static int g_differences;
static const char* g_after; /* the ge2gl call just made */

static void differs(const char* what, const char* want, const char* got) {
    fprintf(stderr, "egl_host: after %s: %s is %s, the host set %s\n", g_after, what, got, want);
    ++g_differences;
}

static void expect_ints(const char* what, GLenum pname, const GLint* want, int n) {
    GLint got[4] = {0, 0, 0, 0};
    int i;
    gl.GetIntegerv(pname, got);
    for (i = 0; i < n; ++i)
        if (got[i] != want[i]) {
            char w[64], g[64];
            if (n == 1) {
                sprintf(w, "%d (0x%x)", (int)want[0], (unsigned)want[0]);
                sprintf(g, "%d (0x%x)", (int)got[0], (unsigned)got[0]);
            } else {
                sprintf(w, "{%d, %d, %d, %d}", (int)want[0], (int)want[1], n > 2 ? (int)want[2] : 0, n > 3 ? (int)want[3] : 0);
                sprintf(g, "{%d, %d, %d, %d}", (int)got[0], (int)got[1], n > 2 ? (int)got[2] : 0, n > 3 ? (int)got[3] : 0);
            }
            differs(what, w, g);
            return;
        }
}

static void expect_int(const char* what, GLenum pname, GLint want) { expect_ints(what, pname, &want, 1); }
static void expect_name(const char* what, GLenum pname, GLuint want) { expect_int(what, pname, (GLint)want); }

static void expect_floats(const char* what, GLenum pname, const GLfloat* want, int n) {
    GLfloat got[4] = {0, 0, 0, 0};
    int i;
    gl.GetFloatv(pname, got);
    for (i = 0; i < n; ++i)
        if (got[i] != want[i]) {
            char w[96], g[96];
            sprintf(w, "{%g, %g, %g, %g}", want[0], want[1], n > 2 ? want[2] : 0.0, n > 3 ? want[3] : 0.0);
            sprintf(g, "{%g, %g, %g, %g}", got[0], got[1], n > 2 ? got[2] : 0.0, n > 3 ? got[3] : 0.0);
            differs(what, w, g);
            return;
        }
}

static void expect_enabled(const char* what, GLenum cap, GLboolean want) {
    GLboolean got = gl.IsEnabled(cap);
    if (!got != !want) differs(what, want ? "enabled" : "disabled", got ? "enabled" : "disabled");
}

static void expect_bools(const char* what, GLenum pname, const GLboolean* want, int n) {
    GLboolean got[4] = {0, 0, 0, 0};
    int i;
    gl.GetBooleanv(pname, got);
    for (i = 0; i < n; ++i)
        if (!got[i] != !want[i]) {
            char w[40], g[40];
            sprintf(w, "{%d, %d, %d, %d}", want[0], n > 1 ? want[1] : 0, n > 2 ? want[2] : 0, n > 3 ? want[3] : 0);
            sprintf(g, "{%d, %d, %d, %d}", got[0], n > 1 ? got[1] : 0, n > 2 ? got[2] : 0, n > 3 ? got[3] : 0);
            differs(what, w, g);
            return;
        }
}

/* Checks every piece of state scramble() set; returns the number of differences. */
static int check_state(const char* after) {
    static const GLboolean no_colour[4] = {GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE};
    static const GLboolean no_depth[1] = {GL_FALSE};
    GLenum err;
    int u;
    g_after = after;
    g_differences = 0;
    if ((err = gl.GetError()) != GL_NO_ERROR) {
        /* Not part of the state contract, but a host would trip over it in its own error checks. */
        fprintf(stderr, "egl_host: note: after %s the GL error flag holds 0x%04x\n", after, (unsigned)err);
        while (gl.GetError() != GL_NO_ERROR) {
        }
    }
    /* Active texture unit first: the per-unit checks below change it. */
    expect_int("GL_ACTIVE_TEXTURE", GL_ACTIVE_TEXTURE, (GLint)(GL_TEXTURE0 + ACTIVE_UNIT));
    expect_name("GL_VERTEX_ARRAY_BINDING", GL_VERTEX_ARRAY_BINDING, obj.vao);
    expect_name("GL_ELEMENT_ARRAY_BUFFER_BINDING (of the host's VAO)", GL_ELEMENT_ARRAY_BUFFER_BINDING, obj.element_buffer);
    expect_name("GL_CURRENT_PROGRAM", GL_CURRENT_PROGRAM, obj.program);
    expect_name("GL_DRAW_FRAMEBUFFER_BINDING", GL_DRAW_FRAMEBUFFER_BINDING, obj.draw_fbo);
    expect_name("GL_READ_FRAMEBUFFER_BINDING", GL_READ_FRAMEBUFFER_BINDING, obj.read_fbo);
    expect_ints("GL_VIEWPORT", GL_VIEWPORT, odd_viewport, 4);
    expect_ints("GL_SCISSOR_BOX", GL_SCISSOR_BOX, odd_scissor, 4);
    expect_enabled("GL_SCISSOR_TEST", GL_SCISSOR_TEST, GL_TRUE);
    expect_bools("GL_COLOR_WRITEMASK", GL_COLOR_WRITEMASK, no_colour, 4);
    expect_bools("GL_DEPTH_WRITEMASK", GL_DEPTH_WRITEMASK, no_depth, 1);
    expect_int("GL_STENCIL_WRITEMASK", GL_STENCIL_WRITEMASK, 0x5A);
    expect_enabled("GL_BLEND", GL_BLEND, GL_TRUE);
    expect_int("GL_BLEND_SRC_RGB", GL_BLEND_SRC_RGB, GL_SRC_COLOR);
    expect_int("GL_BLEND_DST_RGB", GL_BLEND_DST_RGB, GL_ONE_MINUS_DST_ALPHA);
    expect_int("GL_BLEND_SRC_ALPHA", GL_BLEND_SRC_ALPHA, GL_CONSTANT_ALPHA);
    expect_int("GL_BLEND_DST_ALPHA", GL_BLEND_DST_ALPHA, GL_DST_COLOR);
    expect_int("GL_BLEND_EQUATION_RGB", GL_BLEND_EQUATION_RGB, GL_FUNC_REVERSE_SUBTRACT);
    expect_int("GL_BLEND_EQUATION_ALPHA", GL_BLEND_EQUATION_ALPHA, GL_MAX);
    expect_floats("GL_BLEND_COLOR", GL_BLEND_COLOR, odd_blend_colour, 4);
    expect_enabled("GL_COLOR_LOGIC_OP", GL_COLOR_LOGIC_OP, GL_TRUE);
    expect_int("GL_LOGIC_OP_MODE", GL_LOGIC_OP_MODE, GL_COPY_INVERTED);
    expect_enabled("GL_DEPTH_TEST", GL_DEPTH_TEST, GL_TRUE);
    expect_int("GL_DEPTH_FUNC", GL_DEPTH_FUNC, GL_NEVER);
    expect_floats("GL_DEPTH_RANGE", GL_DEPTH_RANGE, odd_depth_range, 2);
    expect_enabled("GL_STENCIL_TEST", GL_STENCIL_TEST, GL_TRUE);
    expect_enabled("GL_CULL_FACE", GL_CULL_FACE, GL_TRUE);
    expect_int("GL_CULL_FACE_MODE", GL_CULL_FACE_MODE, GL_FRONT_AND_BACK);
    expect_int("GL_FRONT_FACE", GL_FRONT_FACE, GL_CW);
    expect_enabled("GL_CLIP_DISTANCE0", GL_CLIP_DISTANCE0, GL_TRUE);
    expect_floats("GL_COLOR_CLEAR_VALUE", GL_COLOR_CLEAR_VALUE, odd_clear_colour, 4);
    expect_int("GL_UNPACK_ALIGNMENT", GL_UNPACK_ALIGNMENT, 1);
    expect_int("GL_PACK_ALIGNMENT", GL_PACK_ALIGNMENT, 1);
    expect_int("GL_UNPACK_ROW_LENGTH", GL_UNPACK_ROW_LENGTH, 7);
    expect_int("GL_PACK_ROW_LENGTH", GL_PACK_ROW_LENGTH, 7);
    expect_int("GL_UNPACK_SKIP_ROWS", GL_UNPACK_SKIP_ROWS, 2);
    expect_int("GL_UNPACK_SKIP_PIXELS", GL_UNPACK_SKIP_PIXELS, 3);
    expect_int("GL_PACK_SKIP_ROWS", GL_PACK_SKIP_ROWS, 5);
    expect_int("GL_PACK_SKIP_PIXELS", GL_PACK_SKIP_PIXELS, 1);
    expect_name("GL_ARRAY_BUFFER_BINDING", GL_ARRAY_BUFFER_BINDING, obj.array_buffer);
    expect_name("GL_PIXEL_UNPACK_BUFFER_BINDING", GL_PIXEL_UNPACK_BUFFER_BINDING, obj.unpack_buffer);
    expect_name("GL_PIXEL_PACK_BUFFER_BINDING", GL_PIXEL_PACK_BUFFER_BINDING, obj.pack_buffer);
    expect_name("GL_UNIFORM_BUFFER_BINDING", GL_UNIFORM_BUFFER_BINDING, obj.uniform_buffer);
    for (u = 0; u < UNITS; ++u) {
        char what[64];
        gl.ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        sprintf(what, "GL_TEXTURE_BINDING_2D of unit %d", u);
        expect_name(what, GL_TEXTURE_BINDING_2D, obj.tex[u]);
        sprintf(what, "GL_SAMPLER_BINDING of unit %d", u);
        expect_name(what, GL_SAMPLER_BINDING, 0);
    }
    gl.ActiveTexture(GL_TEXTURE0 + ACTIVE_UNIT);
    return g_differences;
}

/* ---- presentation --------------------------------------------------------------------------- */

/* Draws ge2gl's texture 1:1 into the host's render target and reads it back as RGBA rows.
 *
 * Orientation: ge2gl's texture has row 0 = the frame's top line. Fragment (x, y) of the target
 * fetches texel (x, y), so the target's row 0 is the top line too, and glReadPixels (which returns
 * rows from y = 0 upwards) hands back the top line first: the rows go to the PPM in the order they
 * are read. (A host presenting to a window's default framebuffer, whose row 0 is the bottom of
 * the screen, fetches texel (x, height - 1 - y) instead.) */
static int present(GLuint frame_tex, GLsizei w, GLsizei h, uint8_t* rgba) {
    GLint tw = 0, th = 0;
    gl.BindFramebuffer(GL_FRAMEBUFFER, obj.present_fbo);
    gl.Viewport(0, 0, w, h);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_COLOR_LOGIC_OP);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_CLIP_DISTANCE0);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.BindVertexArray(obj.vao); /* no attributes: the vertex shader works from gl_VertexID */
    gl.UseProgram(obj.present_program);
    gl.Uniform1i(gl.GetUniformLocation(obj.present_program, "frame"), 0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, frame_tex);
    gl.BindSampler(0, obj.sampler);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &tw);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &th);
    if (tw != w || th != h) {
        fprintf(stderr, "egl_host: ge2gl's texture is %dx%d, asked for %dx%d\n", (int)tw, (int)th, (int)w, (int)h);
        return 0;
    }
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindSampler(0, 0);

    /* The read: tightly packed rows into client memory. */
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    gl.Finish();
    if (gl.GetError() != GL_NO_ERROR) {
        fprintf(stderr, "egl_host: GL error while presenting\n");
        return 0;
    }
    return 1;
}

static int write_ppm(const char* path, const uint8_t* rgba, uint32_t w, uint32_t h) {
    FILE* f = fopen(path, "wb");
    uint8_t* row = (uint8_t*)malloc((size_t)w * 3);
    uint32_t x, y;
    int ok = f && row && fprintf(f, "P6\n%u %u\n255\n", (unsigned)w, (unsigned)h) > 0;
    for (y = 0; ok && y < h; ++y) {
        const uint8_t* src = rgba + (size_t)y * w * 4;
        for (x = 0; x < w; ++x) {
            row[x * 3 + 0] = src[x * 4 + 0];
            row[x * 3 + 1] = src[x * 4 + 1];
            row[x * 3 + 2] = src[x * 4 + 2];
        }
        ok = fwrite(row, 1, (size_t)w * 3, f) == (size_t)w * 3;
    }
    if (f && fclose(f) != 0) ok = 0;
    free(row);
    return ok;
}

/* ---- EGL ------------------------------------------------------------------------------------ */

static int has_extension(const char* list, const char* name) {
    size_t n = strlen(name);
    const char* p = list;
    while (p && (p = strstr(p, name)) != NULL) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
        p += n;
    }
    return 0;
}

static EGLDisplay g_display = EGL_NO_DISPLAY;
static EGLContext g_context = EGL_NO_CONTEXT;

/* A desktop GL 3.3 core context on the surfaceless platform, current without a surface. Returns
   NULL on success, or why not. */
static const char* create_egl_context(void) {
    static const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                            EGL_NONE};
    static const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION_KHR, 3, EGL_CONTEXT_MINOR_VERSION_KHR, 3,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR, EGL_NONE};
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display;
    EGLConfig config;
    EGLint major = 0, minor = 0, count = 0;

    if (!client || !has_extension(client, "EGL_EXT_platform_base") ||
        !has_extension(client, "EGL_MESA_platform_surfaceless"))
        return "EGL has no EGL_MESA_platform_surfaceless";
    get_platform_display = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_platform_display) return "eglGetPlatformDisplayEXT is missing";
    g_display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (g_display == EGL_NO_DISPLAY || !eglInitialize(g_display, &major, &minor))
        return "the surfaceless EGL display does not initialise";
    if (!has_extension(eglQueryString(g_display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        return "EGL_KHR_surfaceless_context is missing";
    if (!has_extension(eglQueryString(g_display, EGL_EXTENSIONS), "EGL_KHR_create_context") &&
        !(major > 1 || (major == 1 && minor >= 5)))
        return "EGL cannot create a core-profile context (EGL_KHR_create_context)";
    if (!eglBindAPI(EGL_OPENGL_API)) return "EGL has no desktop OpenGL";
    if (!eglChooseConfig(g_display, config_attribs, &config, 1, &count) || count < 1)
        return "no EGL config for desktop OpenGL";
    g_context = eglCreateContext(g_display, config, EGL_NO_CONTEXT, context_attribs);
    if (g_context == EGL_NO_CONTEXT) return "no OpenGL 3.3 core context";
    if (!eglMakeCurrent(g_display, EGL_NO_SURFACE, EGL_NO_SURFACE, g_context))
        return "eglMakeCurrent without a surface failed";
    return NULL;
}

static void destroy_egl_context(void) {
    if (g_display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(g_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (g_context != EGL_NO_CONTEXT) eglDestroyContext(g_display, g_context);
    eglTerminate(g_display);
    eglReleaseThread();
}

/* ---- main ----------------------------------------------------------------------------------- */

static void on_ge_error(void* user, int32_t list_id, uint32_t pc, const char* message) {
    (void)user;
    fprintf(stderr, "egl_host: GE error in list 0x%08x at 0x%08x: %s\n", (unsigned)list_id, (unsigned)pc, message);
}

/* After each ge2gl call: the state check (exit 2 on a difference), then its status (exit 1). */
static int after_call(const char* name, ge2gl_status st, ge2gl_context* h) {
    int diffs = check_state(name);
    if (st != GE2GL_OK) {
        fprintf(stderr, "egl_host: %s failed: %s (%s)\n", name, ge2gl_status_name(st),
                h ? ge2gl_last_message(h) : ge2gl_last_message(NULL));
        return EXIT_GE2GL;
    }
    if (diffs) {
        fprintf(stderr, "egl_host: %s left %d piece(s) of the host's GL state changed\n", name, diffs);
        return EXIT_STATE;
    }
    return 0;
}

int main(int argc, char** argv) {
    const char *dump = NULL, *out = NULL, *why;
    unsigned long scale = 2;
    ge2gl_context* h = NULL;
    ge2gl_config cfg;
    ge2gl_display disp;
    uint32_t tex = 0, out_w, out_h;
    uint8_t* rgba = NULL;
    int i, rc = EXIT_GE2GL;

    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--scale") && i + 1 < argc) {
            char* end;
            scale = strtoul(argv[++i], &end, 10);
            if (*end || scale < 1 || scale > 8) {
                fprintf(stderr, "egl_host: --scale takes 1-8\n");
                return 1;
            }
        } else if (!dump) {
            dump = argv[i];
        } else if (!out) {
            out = argv[i];
        } else {
            dump = NULL;
            break;
        }
    }
    if (!dump || !out) {
        fprintf(stderr, "usage: egl_host DUMP.ppdmp OUT.ppm [--scale N]\n");
        return 1;
    }
    if (ge2gl_api_version() >> 16 != GE2GL_API_VERSION_MAJOR || (ge2gl_api_version() & 0xFFFF) < 2) {
        fprintf(stderr, "egl_host: the ge2gl library is older than API 1.2\n");
        return 1;
    }

    /* 1. The host's GL context and its own objects. */
    if ((why = create_egl_context()) != NULL) {
        fprintf(stderr, "egl_host: skipped: %s\n", why);
        destroy_egl_context();
        return EXIT_SKIP;
    }
    if ((why = load_gl()) != NULL) {
        fprintf(stderr, "egl_host: skipped: eglGetProcAddress has no %s\n", why);
        destroy_egl_context();
        return EXIT_SKIP;
    }
    printf("egl_host: GL_RENDERER %s, GL_VERSION %s\n", (const char*)gl.GetString(GL_RENDERER),
           (const char*)gl.GetString(GL_VERSION));

    /* 2. ge2gl on this context: hardware mode at render scale N, GL loaded through EGL. */
    ge2gl_config_init(&cfg);
    cfg.backend = GE2GL_BACKEND_GL_CURRENT;
    cfg.gl_mode = GE2GL_GL_MODE_HW;
    cfg.render_scale = (int32_t)scale;
    cfg.gl_get_proc_address = egl_loader;
    cfg.callbacks.error = on_ge_error;
    /* ram = NULL: ge2gl owns the 64 MiB of RAM a dump replay needs. */

    /* The presentation target's size is known only after the replay; objects are made for the
       PSP's 480x272 and the target is resized below if the dump displays something else. */
    if (!create_objects((GLsizei)(480 * scale), (GLsizei)(272 * scale))) {
        fprintf(stderr, "egl_host: cannot create the host's GL objects\n");
        goto done;
    }

    scramble();
    if ((rc = after_call("ge2gl_create", ge2gl_create(&cfg, &h), NULL)) != 0) goto done;

    /* 3. The replay, and the displayed frame as a texture at the render scale. */
    scramble();
    if ((rc = after_call("ge2gl_replay_dump", ge2gl_replay_dump(h, dump, &disp), h)) != 0) goto done;
    out_w = disp.width * (uint32_t)scale;
    out_h = disp.height * (uint32_t)scale;
    printf("egl_host: %s displays 0x%08x (stride %u, format %d, %ux%u); texture %ux%u at scale %lu\n", dump,
           (unsigned)disp.addr, (unsigned)disp.stride, (int)disp.format, (unsigned)disp.width, (unsigned)disp.height,
           (unsigned)out_w, (unsigned)out_h, scale);

    scramble();
    if ((rc = after_call("ge2gl_frame_texture_sized",
                         ge2gl_frame_texture_sized(h, disp.addr, disp.stride, disp.format, disp.width, disp.height,
                                                   out_w, out_h, &tex),
                         h)) != 0)
        goto done;
    rc = EXIT_GE2GL;

    /* 4. Present into the host's own target (valid until the next ge2gl call) and save it. */
    if (out_w != 480 * scale || out_h != 272 * scale) {
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, obj.present_tex);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, (GLsizei)out_w, (GLsizei)out_h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    }
    rgba = (uint8_t*)malloc((size_t)out_w * out_h * 4);
    if (!rgba || !present(tex, (GLsizei)out_w, (GLsizei)out_h, rgba)) goto done;
    if (!write_ppm(out, rgba, out_w, out_h)) {
        fprintf(stderr, "egl_host: cannot write %s\n", out);
        goto done;
    }
    printf("egl_host: wrote %s (%ux%u, from ge2gl texture %u)\n", out, (unsigned)out_w, (unsigned)out_h, (unsigned)tex);

    /* 5. Destroy on this thread, with this context current. */
    scramble();
    ge2gl_destroy(h);
    h = NULL;
    if ((rc = after_call("ge2gl_destroy", GE2GL_OK, NULL)) != 0) goto done;
    printf("egl_host: the host's GL state was intact after every ge2gl call\n");
    rc = 0;

done:
    ge2gl_destroy(h);
    free(rgba);
    if (gl.DeleteTextures) delete_objects();
    destroy_egl_context();
    return rc;
}
