#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
# Part of ge2gl's PPSSPP integration (integrations/ppsspp); see README.md there.
"""Registers ge2gl's GPU core in a PPSSPP source tree (pinned at c09e6bddaa).

Usage: edit_ppsspp.py PPSSPP_SRC [--without-sdl] [--check]

Copies the core's sources (src/) to PPSSPP_SRC/GPU/Ge2gl/ and makes the few edits that register
it, each anchored on an identifier of PPSSPP's source and marked with "ge2gl" so that running the
script again changes nothing. An anchor that is not found exactly once stops the script with a
message naming it: the tree is not the commit this integration was written for.

The edits (README.md says why each is needed):
  registration  the GPUCORE_GE2GL enumerator, the GPU factory case, the Ge2glBackend/Ge2glEgl
                settings, --graphics=ge2gl[-soft|-gl|-hw][-egl], the core chosen from the setting,
                CMake linking find_package(ge2gl);
  seams         `virtual` on the GPUCommon list functions that PPSSPP's dump player and PPGe call
                directly, and sceGe_user registered from the core's module when ge2gl is selected;
  --without-sdl building PPSSPPHeadless where SDL3 is not installed (Debian 12): no SDL frontend
                definitions, the headless runner's no-window branch;
  offscreen GL  (with SDL) the headless GL context on SDL's offscreen driver (EGL, no X display):
                GLEW's missing GLX display accepted.
--check only reports whether the tree already carries every edit (exit 0) or not (exit 1).
"""
import os
import re
import shutil
import sys

MARK = "ge2gl"


class EditError(Exception):
    pass


def read(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.read()


def write(root, rel, text):
    with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
        f.write(text)


def once(text, anchor, rel):
    n = text.count(anchor)
    if n != 1:
        raise EditError(f"{rel}: anchor {anchor!r} found {n} times (expected once)")
    return text.index(anchor)


def insert_after(root, rel, anchor, addition, done_marker):
    """Inserts `addition` right after the line holding `anchor`, unless `done_marker` is there."""
    text = read(root, rel)
    if done_marker in text:
        return False
    at = once(text, anchor, rel)
    eol = text.index("\n", at) + 1
    write(root, rel, text[:eol] + addition + text[eol:])
    return True


def insert_before(root, rel, anchor, addition, done_marker):
    """Inserts `addition` before the line holding `anchor`, unless `done_marker` is there."""
    text = read(root, rel)
    if done_marker in text:
        return False
    at = once(text, anchor, rel)
    bol = text.rfind("\n", 0, at) + 1
    write(root, rel, text[:bol] + addition + text[bol:])
    return True


def replace(root, rel, anchor, new, done_marker):
    text = read(root, rel)
    if done_marker in text:
        return False
    once(text, anchor, rel)
    write(root, rel, text.replace(anchor, new))
    return True


def replace_all(root, rel, anchor, new, count, done_marker):
    """Replaces each of the `count` occurrences of `anchor` (a line PPSSPP repeats)."""
    text = read(root, rel)
    if text.count(done_marker) >= count:
        return False
    n = text.count(anchor)
    if n != count:
        raise EditError(f"{rel}: anchor {anchor!r} found {n} times (expected {count})")
    write(root, rel, text.replace(anchor, new))
    return True


def make_virtual(root, rel, names):
    """Puts `virtual` before the member declarations of `names` (one line each, tab-indented)."""
    text = read(root, rel)
    changed = False
    for name in names:
        pat = re.compile(r"^(\t)((?!virtual )(?:[A-Za-z_][\w:<>*&]*[ *&]+)+" + re.escape(name) + r"\()", re.M)
        hits = pat.findall(text)
        if len(hits) > 1:
            raise EditError(f"{rel}: declaration of {name} found {len(hits)} times")
        if not hits:
            if not re.search(r"^\tvirtual [^\n]*\b" + re.escape(name) + r"\(", text, re.M):
                raise EditError(f"{rel}: no declaration of {name}")
            continue
        text = pat.sub(r"\1virtual \2", text, count=1)
        changed = True
    if changed:
        write(root, rel, text)
    return changed


# Member functions of GPUCommon that sceGe.cpp, PPGe (Core/Util/PPGeDraw.cpp) and the dump player
# (GPU/Debugger/Playback.cpp) call on `gpu`, and that are not virtual at the pinned commit.
GPUCOMMON_SEAMS = [
    "ProcessDLQueue", "UpdateStall", "EnqueueList", "DequeueList", "GetStack", "BusyDrawing",
    "Continue", "Break", "SetAddrTranslation", "GetAddrTranslation", "GetListTicks",
]


def registration_edits(root):
    yield insert_after(root, "Core/CoreParameter.h", "GPUCORE_VULKAN = 4,",
                       "\tGPUCORE_GE2GL = 5,  // ge2gl: libge2gl's GE (ge2gl integrations/ppsspp)\n",
                       "GPUCORE_GE2GL")
    yield insert_after(root, "GPU/GPU.cpp", '#include "GPU/Software/SoftGpu.h"',
                       '#include "GPU/Ge2gl/Ge2glGpu.h"  // ge2gl\n', "Ge2glGpu.h")
    yield insert_before(root, "GPU/GPU.cpp", "\tcase GPUCORE_SOFTWARE:",
                        "\tcase GPUCORE_GE2GL:  // ge2gl\n\t\treturn Ge2gl_CreateGPU(ctx, draw);\n",
                        "case GPUCORE_GE2GL")
    # GPU_Init asserts (debug builds) that only the software core runs without a DrawContext;
    # ge2gl's core draws through libge2gl and needs none either.
    yield replace(root, "GPU/GPU.cpp", "draw || gpuCore == GPUCORE_SOFTWARE)",
                  "draw || gpuCore == GPUCORE_SOFTWARE || gpuCore == GPUCORE_GE2GL)",
                  "gpuCore == GPUCORE_GE2GL)")
    yield insert_after(root, "Core/Config.h", "\tbool bSoftwareRendering;",
                       "\tint iGe2glBackend;  // ge2gl: 0 off, 1 software model, 2 GL exact, 3 GL hardware mode\n"
                       "\tbool bGe2glEgl;  // ge2gl's GL backends: EGL surfaceless instead of OSMesa\n",
                       "iGe2glBackend")
    yield insert_after(root, "Core/Config.cpp", 'ConfigSetting("SoftwareRenderer", SETTING(g_Config, bSoftwareRendering)',
                       '\tConfigSetting("Ge2glBackend", SETTING(g_Config, iGe2glBackend), 0, CfgFlag::DEFAULT),  // ge2gl\n'
                       '\tConfigSetting("Ge2glEgl", SETTING(g_Config, bGe2glEgl), false, CfgFlag::DEFAULT),  // ge2gl\n',
                       "Ge2glBackend")
    yield insert_after(root, "Core/CmdLine.h", "\tstd::optional<bool> softwareRendering;",
                       "\tstd::optional<int> ge2glBackend;  // ge2gl\n\tstd::optional<bool> ge2glEgl;  // ge2gl\n",
                       "ge2glBackend")
    yield insert_after(root, "Core/CmdLine.cpp", 'options: gles, software, etc.',
                       '\tPRINT_STDOUT("  --graphics=ge2gl[-soft|-gl|-hw][-egl]  ge2gl\'s GE: software model, GL exact or GL hardware mode\\n");\n',
                       "--graphics=ge2gl")
    yield insert_before(root, "Core/CmdLine.cpp", '} else if (restOfOption == "gles" || restOfOption == "opengl") {',
                        '\t\t\t} else if (restOfOption == "ge2gl" || restOfOption.rfind("ge2gl-", 0) == 0) {  // ge2gl\n'
                        '\t\t\t\tstd::string mode = restOfOption.size() > 6 ? restOfOption.substr(6) : "soft";\n'
                        '\t\t\t\tconst bool egl = mode.size() > 4 && mode.compare(mode.size() - 4, 4, "-egl") == 0;\n'
                        '\t\t\t\tif (egl)\n\t\t\t\t\tmode.resize(mode.size() - 4);\n'
                        '\t\t\t\tconst int backend = mode == "soft" ? 1 : mode == "gl" ? 2 : mode == "hw" ? 3 : 0;\n'
                        '\t\t\t\tif (backend == 0) {\n'
                        '\t\t\t\t\tPRINT_STDERR("Invalid value for --graphics=: %s", restOfOption.c_str());\n'
                        '\t\t\t\t\treturn CommandLineParseResult::Error;\n\t\t\t\t}\n'
                        '\t\t\t\t// No host graphics context: ge2gl draws into guest memory or its own GL context.\n'
                        '\t\t\t\tgpuBackend = GPUBackend::OPENGL;\n\t\t\t\tsoftwareRendering = true;\n'
                        '\t\t\t\tge2glBackend = backend;\n\t\t\t\tge2glEgl = egl;\n',
                        'restOfOption == "ge2gl"')
    yield insert_before(root, "Core/CmdLine.cpp", "\tif (enableLogging.has_value()) {",
                        "\tif (ge2glBackend.has_value()) {  // ge2gl\n"
                        "\t\tg_Config.iGe2glBackend = ge2glBackend.value();\n"
                        "\t\tg_Config.DoNotSaveSetting(&g_Config.iGe2glBackend);\n\t}\n"
                        "\tif (ge2glEgl.has_value()) {  // ge2gl\n"
                        "\t\tg_Config.bGe2glEgl = ge2glEgl.value();\n"
                        "\t\tg_Config.DoNotSaveSetting(&g_Config.bGe2glEgl);\n\t}\n",
                        "g_Config.iGe2glBackend = ge2glBackend")
    # After the software renderer is chosen from the config, ge2gl's setting picks its core.
    text = read(root, "Core/System.cpp")
    if "GPUCORE_GE2GL" not in text:
        at = once(text, "g_CoreParameter.compat.flags().ForceSoftwareRenderer) {", "Core/System.cpp")
        close = text.index("\t}\n", at) + 3
        text = (text[:close] + "\tif (g_Config.iGe2glBackend != 0)  // ge2gl: the GE is libge2gl's\n"
                "\t\tg_CoreParameter.gpuCore = GPUCORE_GE2GL;\n" + text[close:])
        write(root, "Core/System.cpp", text)
        yield True
    yield make_virtual(root, "GPU/GPUCommon.h", GPUCOMMON_SEAMS)
    yield insert_after(root, "Core/HLE/sceGe.cpp", '#include "GPU/GPUCommon.h"',
                       '#include "GPU/Ge2gl/Ge2glSceGe.h"  // ge2gl\n', "Ge2glSceGe.h")
    yield insert_after(root, "Core/HLE/sceGe.cpp", "void Register_sceGe_user() {",
                       "\tif (Ge2gl_RegisterSceGeModule())  // ge2gl: its sceGe_user when the ge2gl core is selected\n\t\treturn;\n",
                       "Ge2gl_RegisterSceGeModule")
    gpu_cmake = read(root, "GPU/CMakeLists.txt")
    if MARK not in gpu_cmake:
        gpu_cmake += (
            "\n# ge2gl's GPU core (ge2gl integrations/ppsspp): libge2gl through its C ABI.\n"
            "find_package(ge2gl 0.1 REQUIRED)\n"
            "target_sources(GPU PRIVATE Ge2gl/Ge2glGpu.cpp Ge2gl/Ge2glGpu.h Ge2gl/Ge2glSceGe.cpp\n"
            "\tGe2gl/Ge2glSceGe.h Ge2gl/Ge2glTimeline.h)\n"
            "target_link_libraries(GPU PUBLIC ge2gl::ge2gl)\n")
        write(root, "GPU/CMakeLists.txt", gpu_cmake)
        yield True


def without_sdl_edits(root):
    # SDL3 is required for every desktop build at the pinned commit; PPSSPPHeadless itself needs
    # it only for --graphics=gles/vulkan. With GE2GL_HEADLESS_WITHOUT_SDL=ON the SDL3 lookup and
    # the frontend's SDL definition are skipped and the headless runner takes the branch PPSSPP
    # already has for platforms without SDL (no host graphics context).
    yield replace(root, "CMakeLists.txt",
                  "if(NOT LIBRETRO AND NOT IOS AND NOT LOONGARCH64_DEVICE AND NOT ANDROID)\n\tfind_package(SDL3 QUIET)",
                  "if(NOT LIBRETRO AND NOT IOS AND NOT LOONGARCH64_DEVICE AND NOT ANDROID AND NOT GE2GL_HEADLESS_WITHOUT_SDL)  # ge2gl\n\tfind_package(SDL3 QUIET)",
                  "NOT GE2GL_HEADLESS_WITHOUT_SDL)")
    yield replace(root, "CMakeLists.txt", "\t# Require SDL\n\tadd_compile_definitions(SDL)\n",
                  "\t# Require SDL\n\tif(GE2GL_HEADLESS_WITHOUT_SDL)  # ge2gl: headless only, no SDL3\n"
                  "\t\tadd_compile_definitions(GE2GL_HEADLESS_WITHOUT_SDL)\n\telse()\n"
                  "\t\tadd_compile_definitions(SDL)\n\tendif()\n",
                  "add_compile_definitions(GE2GL_HEADLESS_WITHOUT_SDL)")
    yield replace(root, "headless/Headless.cpp", "#elif PPSSPP_ARCH(LOONGARCH64)\n",
                  "#elif PPSSPP_ARCH(LOONGARCH64) || defined(GE2GL_HEADLESS_WITHOUT_SDL)  // ge2gl\n",
                  "defined(GE2GL_HEADLESS_WITHOUT_SDL)  // ge2gl\n")
    # ... and skips the hidden window the GL/Vulkan contexts need (made and destroyed in main()).
    yield replace_all(root, "headless/Headless.cpp", "#if PPSSPP_PLATFORM(ANDROID) || PPSSPP_ARCH(LOONGARCH64)\n",
                      "#if PPSSPP_PLATFORM(ANDROID) || PPSSPP_ARCH(LOONGARCH64) || defined(GE2GL_HEADLESS_WITHOUT_SDL)  // ge2gl\n",
                      2, "#if PPSSPP_PLATFORM(ANDROID) || PPSSPP_ARCH(LOONGARCH64) || defined(GE2GL_HEADLESS_WITHOUT_SDL)")


def offscreen_gl_edits(root):
    # With SDL3 built from source (sdl3.sh) the headless runner makes its GL context through SDL's
    # offscreen video driver, that is EGL, with no X display. The system GLEW is built for GLX:
    # glewInit loads the GL entry points (glewContextInit, through GLVND's dispatch, which serves
    # an EGL context as well) and then fails in glxewInit with GLEW_ERROR_NO_GLX_DISPLAY, since
    # there is no GLX display to query. The headless runner uses no GLX extension, so that one
    # result is accepted (GLEW's glew.c, glewInit).
    yield replace(root, "headless/SDLHeadlessGLGraphicsContext.cpp",
                  "\tif (GLEW_OK != glewInit()) {\n",
                  "\tconst GLenum glewResult = glewInit();  // ge2gl: an EGL context has no GLX display\n"
                  "\tif (glewResult != GLEW_OK && glewResult != GLEW_ERROR_NO_GLX_DISPLAY) {\n",
                  "ge2gl: an EGL context has no GLX display")


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    flags = {a for a in argv[1:] if a.startswith("--")}
    unknown = flags - {"--without-sdl", "--check"}
    if len(args) != 1 or unknown:
        print(__doc__, file=sys.stderr)
        return 2
    root = args[0]
    if not os.path.isfile(os.path.join(root, "GPU/GPUCommon.h")):
        print(f"edit_ppsspp: {root} is not a PPSSPP source tree (no GPU/GPUCommon.h)", file=sys.stderr)
        return 2
    here = os.path.dirname(os.path.abspath(__file__))
    if "--check" in flags:
        needed = ["GPUCORE_GE2GL", "Ge2gl_RegisterSceGeModule"]
        ok = all(MARK in read(root, f) for f in ["Core/CoreParameter.h", "Core/HLE/sceGe.cpp", "GPU/CMakeLists.txt"])
        ok = ok and all(n in read(root, "Core/CoreParameter.h") + read(root, "Core/HLE/sceGe.cpp") for n in needed)
        print("edited" if ok else "not edited")
        return 0 if ok else 1
    dest = os.path.join(root, "GPU", "Ge2gl")
    os.makedirs(dest, exist_ok=True)
    for name in sorted(os.listdir(os.path.join(here, "src"))):
        shutil.copyfile(os.path.join(here, "src", name), os.path.join(dest, name))
    try:
        changed = sum(1 for c in registration_edits(root) if c)
        if "--without-sdl" in flags:
            changed += sum(1 for c in without_sdl_edits(root) if c)
        else:
            changed += sum(1 for c in offscreen_gl_edits(root) if c)
    except EditError as e:
        print(f"edit_ppsspp: {e}", file=sys.stderr)
        return 1
    print(f"edit_ppsspp: {changed} edits applied in {root} (sources copied to GPU/Ge2gl/)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
