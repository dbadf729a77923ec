#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Part of ge2gl's PPSSPP integration (integrations/ppsspp); see README.md there.
#
# Usage: integrations/ppsspp/build.sh PPSSPP_SRC OUT_DIR
#
# PPSSPP_SRC: a PPSSPP checkout at c09e6bddaa with its submodules (README.md, "A PPSSPP tree";
#             checkout.sh makes one). It is edited in place (edit_ppsspp.py; running again is
#             harmless).
# OUT_DIR:    gets ge2gl-build/ (libge2gl and the ge2gl CLI built from this checkout),
#             ge2gl-prefix/ (libge2gl installed: what PPSSPP's find_package(ge2gl) finds),
#             ppsspp-build/ and OUT_DIR/PPSSPPHeadless (a link to the binary in ppsspp-build, which
#             finds its assets/ beside it).
# Environment: JOBS (default: nproc), PPSSPP_BUILD_TYPE (default Release).
set -euo pipefail
if [ $# -ne 2 ]; then
  sed -n '4,16p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
src=$(cd "$1" && pwd)
mkdir -p "$2"
out=$(cd "$2" && pwd)
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
[ -f "$src/GPU/GPUCommon.h" ] || { echo "build.sh: $src is not a PPSSPP source tree" >&2; exit 2; }
for sub in ext/glslang ext/SPIRV-Cross ext/armips ext/rcheevos ext/naett ext/lua ext/libchdr ext/cpu_features ext/miniupnp; do
  [ -n "$(ls -A "$src/$sub" 2>/dev/null)" ] || { echo "build.sh: $src/$sub is empty: PPSSPP needs its submodules (README.md)" >&2; exit 2; }
done

echo "== ge2gl: library and CLI from $root =="
cmake -S "$root" -B "$out/ge2gl-build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGE2GL_BUILD_TESTS=OFF \
  -DGE2GL_BUILD_BENCH=OFF -DGE2GL_BUILD_EXAMPLES=OFF -DGE2GL_BUILD_CLI=ON >/dev/null
ninja -C "$out/ge2gl-build" -j"$jobs" ge2gl_api ge2gl_cli
cmake --install "$out/ge2gl-build" --prefix "$out/ge2gl-prefix" >/dev/null

echo "== PPSSPP: registering ge2gl's core in $src =="
edit_flags=()
if ! pkg-config --exists sdl3 2>/dev/null; then
  # Debian 12 has no SDL3; PPSSPPHeadless needs it only for --graphics=gles/vulkan.
  echo "SDL3 not found: building PPSSPPHeadless without it (README.md, 'Without SDL3')"
  edit_flags+=(--without-sdl)
  without_sdl=ON
  # Without SDL nothing brings libGL to the link after PPSSPP's static libraries: legacy libGL and
  # --no-as-needed keep the GL library its Common code calls into on the executable's link line.
  link_flags=(-DOpenGL_GL_PREFERENCE=LEGACY "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--no-as-needed")
else
  without_sdl=OFF
  link_flags=()
fi
python3 "$here/edit_ppsspp.py" "$src" "${edit_flags[@]}"

echo "== PPSSPP: PPSSPPHeadless =="
cmake -S "$src" -B "$out/ppsspp-build" -G Ninja -DCMAKE_BUILD_TYPE="${PPSSPP_BUILD_TYPE:-Release}" \
  -DHEADLESS=ON -DUNITTEST=OFF -DUSE_FFMPEG=OFF -DUSE_DISCORD=OFF -DUSE_MINIUPNPC=OFF \
  -DUSE_SYSTEM_ZSTD=ON -DUSE_SYSTEM_FREETYPE=ON -DUSE_SYSTEM_LIBZIP=ON -DUSE_SYSTEM_SNAPPY=ON \
  -DUSE_SYSTEM_RAPIDJSON=ON -DUSE_SYSTEM_LIBCHDR=OFF -DGE2GL_HEADLESS_WITHOUT_SDL="$without_sdl" \
  -DCMAKE_PREFIX_PATH="$out/ge2gl-prefix" "${link_flags[@]}" -Wno-dev >/dev/null
ninja -C "$out/ppsspp-build" -j"$jobs" PPSSPPHeadless
ln -sfn "$out/ppsspp-build/PPSSPPHeadless" "$out/PPSSPPHeadless"
"$out/PPSSPPHeadless" --help 2>&1 | grep -q "ge2gl" || { echo "build.sh: the built PPSSPPHeadless does not know --graphics=ge2gl" >&2; exit 1; }
echo "built: $out/PPSSPPHeadless (--graphics=ge2gl, ge2gl-gl, ge2gl-hw; ge2gl CLI: $out/ge2gl-build/ge2gl)"
