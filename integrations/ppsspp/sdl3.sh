#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Part of ge2gl's PPSSPP integration (integrations/ppsspp); see README.md there, "SDL3 from source".
#
# Usage: integrations/ppsspp/sdl3.sh PREFIX
#
# Builds SDL3 and SDL3_ttf from their release tags and installs them under PREFIX, for hosts whose
# distribution has no SDL3 (Debian 12). PPSSPPHeadless needs SDL3 for its own GL context
# (--graphics=gles), which scripts/bench_vs_ppsspp.sh compares ge2gl's GL modes against; SDL3_ttf
# only because PPSSPP's CMakeLists requires it next to SDL3. Then build PPSSPP with
#   PKG_CONFIG_PATH=PREFIX/lib/pkgconfig CMAKE_PREFIX_PATH=PREFIX \
#     LD_LIBRARY_PATH=PREFIX/lib integrations/ppsspp/build.sh SRC OUT
# and run PPSSPPHeadless with LD_LIBRARY_PATH=PREFIX/lib and SDL_VIDEO_DRIVER=offscreen: SDL's
# offscreen video driver makes its GL context through EGL (Mesa's llvmpipe on a machine without a
# display or GPU), so no X server is needed.
#
# Environment: SDL3_TAG (default release-3.4.14), SDL3_TTF_TAG (default release-3.2.2),
#   GE2GL_GIT_SOURCE (as in checkout.sh: a template with {owner} and {name} for a local mirror;
#   default https://github.com/{owner}/{name}.git), JOBS (default: nproc).
set -euo pipefail
if [ $# -ne 1 ]; then
  sed -n '4,19p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
mkdir -p "$1"
prefix=$(cd "$1" && pwd)
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
default_pattern='https://github.com/{owner}/{name}.git'
source_template=${GE2GL_GIT_SOURCE:-$default_pattern}
work="$prefix/src"
mkdir -p "$work"

clone() {  # clone OWNER NAME TAG -> $work/NAME at TAG
  local url=${source_template//\{owner\}/$1}
  url=${url//\{name\}/$2}
  if [ ! -d "$work/$2/.git" ]; then
    git clone -q "$url" "$work/$2"
  fi
  git -C "$work/$2" -c advice.detachedHead=false checkout -q "$3"
}

clone libsdl-org SDL "${SDL3_TAG:-release-3.4.14}"
clone libsdl-org SDL_ttf "${SDL3_TTF_TAG:-release-3.2.2}"

# SDL3: the offscreen driver with EGL is what a headless host uses; audio, cameras, joysticks and
# the window-system drivers are left out (PPSSPPHeadless opens none of them; SDL_UNIX_CONSOLE_BUILD
# is how SDL lets a build go without X11 or Wayland).
cmake -S "$work/SDL" -B "$work/SDL-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX="$prefix" -DSDL_SHARED=ON -DSDL_STATIC=OFF -DSDL_TESTS=OFF \
  -DSDL_EXAMPLES=OFF -DSDL_OFFSCREEN=ON -DSDL_OPENGL=ON -DSDL_OPENGLES=ON -DSDL_X11=OFF \
  -DSDL_WAYLAND=OFF -DSDL_KMSDRM=OFF -DSDL_VULKAN=OFF -DSDL_AUDIO=OFF -DSDL_CAMERA=OFF \
  -DSDL_JOYSTICK=OFF -DSDL_HAPTIC=OFF -DSDL_HIDAPI=OFF -DSDL_SENSOR=OFF -DSDL_DIALOG=OFF \
  -DSDL_GPU=OFF -DSDL_RENDER_GPU=OFF -DSDL_UNIX_CONSOLE_BUILD=ON -Wno-dev >/dev/null
ninja -C "$work/SDL-build" -j"$jobs"
cmake --install "$work/SDL-build" >/dev/null

# SDL3_ttf with the system FreeType, no HarfBuzz or plutosvg (PPSSPPHeadless draws no text).
cmake -S "$work/SDL_ttf" -B "$work/SDL_ttf-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_PREFIX_PATH="$prefix" -DSDLTTF_VENDORED=OFF \
  -DSDLTTF_HARFBUZZ=OFF -DSDLTTF_PLUTOSVG=OFF -DSDLTTF_SAMPLES=OFF -Wno-dev >/dev/null
ninja -C "$work/SDL_ttf-build" -j"$jobs"
cmake --install "$work/SDL_ttf-build" >/dev/null

PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --modversion sdl3 >/dev/null || {
  echo "sdl3.sh: SDL3 installed under $prefix but pkg-config does not find it" >&2; exit 1; }
echo "installed: SDL3 $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --modversion sdl3) and SDL3_ttf under $prefix"
