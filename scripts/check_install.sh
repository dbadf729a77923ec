#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Checks that ge2gl can be used as an emulator would use it (docs/install.md). Usage:
#   scripts/check_install.sh [BUILD_DIR]        (default: build; BUILD_DIR must be configured)
# 1. cmake --install BUILD_DIR into a temporary prefix; checks the installed files: libge2gl.so →
#    .so.0 → .so.<version> with SONAME libge2gl.so.0, only ge2gl_* symbols exported, no RPATH into
#    the build tree, headers, CMake package (whose target names no other target), ge2gl.pc.
# 2. tests/install_consumer against that prefix with find_package(ge2gl) (CMAKE_PREFIX_PATH): a
#    C host that draws with the software backend and checks pixels, a C++ host of ge2gl.hpp and
#    examples/minimal_host.c; runs all three.
# 3. tests/install_consumer/main.c built with plain `cc $(pkg-config --cflags --libs ge2gl)` and
#    run with LD_LIBRARY_PATH.
# 4. tests/install_consumer/subdir: a parent project that add_subdirectory()s this source tree,
#    asserts that only the library's targets exist, links ge2gl::ge2gl and runs main.c.
# Work files live in BUILD_DIR/install-check; the add_subdirectory build there is kept between
# runs so that a rerun only recompiles what changed. GE2GL_JOBS sets the build parallelism
# (default: all cores). Prints "install check: OK" and exits 0 when everything passes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
jobs=${GE2GL_JOBS:-$(nproc 2>/dev/null || echo 2)}
work=$build/install-check
prefix=$work/prefix
logs=$work/logs
start=$SECONDS

fail() {
  echo "install check: FAIL: $*" >&2
  exit 1
}
# run LOG CMD...: runs CMD with its output in $logs/LOG; on failure shows the log's end.
run() {
  local log=$logs/$1
  shift
  if ! "$@" >"$log" 2>&1; then
    echo "install check: FAIL: $*" >&2
    tail -n 40 "$log" >&2
    exit 1
  fi
}

[ -f "$build/CMakeCache.txt" ] || fail "$build is not a configured build directory"
gen=()
command -v ninja >/dev/null 2>&1 && gen=(-G Ninja)
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
libdir=$(sed -n 's/^CMAKE_INSTALL_LIBDIR:PATH=//p' "$build/CMakeCache.txt")
[ -n "$version" ] || fail "no CMAKE_PROJECT_VERSION in $build/CMakeCache.txt"
[ -n "$libdir" ] || fail "no CMAKE_INSTALL_LIBDIR in $build/CMakeCache.txt (GE2GL_INSTALL off?)"
case $libdir in /*) fail "CMAKE_INSTALL_LIBDIR is absolute ($libdir): cannot install into a temporary prefix" ;; esac

rm -rf "$prefix" "$work/consumer" "$work/pc" "$logs"
mkdir -p "$prefix" "$work/pc" "$logs"

echo "-- install: $build → $prefix"
run build-lib.log cmake --build "$build" --target ge2gl_api --parallel "$jobs"
run install.log cmake --install "$build" --prefix "$prefix"
lib=$prefix/$libdir
[ "$(readlink "$lib/libge2gl.so" || true)" = libge2gl.so.0 ] || fail "$lib/libge2gl.so is not a symlink to libge2gl.so.0"
[ "$(readlink "$lib/libge2gl.so.0" || true)" = "libge2gl.so.$version" ] ||
  fail "$lib/libge2gl.so.0 is not a symlink to libge2gl.so.$version"
[ -f "$lib/libge2gl.so.$version" ] || fail "no $lib/libge2gl.so.$version"
soname=$(readelf -d "$lib/libge2gl.so.$version" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
[ "$soname" = libge2gl.so.0 ] || fail "SONAME is '$soname', expected libge2gl.so.0"
if readelf -d "$lib/libge2gl.so.$version" | grep -E '\((RPATH|RUNPATH)\)' | grep -qF "$build"; then
  fail "the installed library has an RPATH into the build tree"
fi
# Hidden visibility and --exclude-libs: the library exports the ge2gl_* functions and nothing of
# its own besides. libstdc++ declares namespace std with default visibility, so weak or unique
# (nm V/W/u) instantiations of std:: templates (shared_ptr's typeinfo and vtables) still appear;
# they are merged with the host's copies and are not part of the API.
nm -D --defined-only "$lib/libge2gl.so.$version" >"$logs/exports.txt"
nexports=$(awk '$3 ~ /^ge2gl_/' "$logs/exports.txt" | wc -l)
nstd=0
while read -r _ type name; do
  [ -n "$name" ] || continue
  case $name in ge2gl_*) continue ;; esac
  case $type in
    V | W | u)
      if echo "$name" | c++filt | grep -qE '^((typeinfo|typeinfo name|vtable|VTT) for )?std::'; then
        nstd=$((nstd + 1))
        continue
      fi
      ;;
  esac
  fail "libge2gl exports $name ($(echo "$name" | c++filt)), not a ge2gl_* function"
done <"$logs/exports.txt"
[ "$nexports" -gt 0 ] || fail "libge2gl exports no ge2gl_* function"
for f in include/ge2gl/ge2gl.h include/ge2gl/ge2gl.hpp "$libdir/cmake/ge2gl/ge2glConfig.cmake" \
  "$libdir/cmake/ge2gl/ge2glConfigVersion.cmake" "$libdir/cmake/ge2gl/ge2glTargets.cmake" "$libdir/pkgconfig/ge2gl.pc"; do
  [ -f "$prefix/$f" ] || fail "not installed: $f"
done
# The package must not need the static GE libraries (ge_hle, ge_softmodel, ...).
if grep -hE '(^|[^a-z0-9_])ge_[a-z]+' "$lib"/cmake/ge2gl/ge2glTargets*.cmake >/dev/null; then
  fail "the exported targets name internal libraries: $(grep -hoE '(^|[^a-z0-9_])ge_[a-z]+' "$lib"/cmake/ge2gl/ge2glTargets*.cmake | sort -u | tr '\n' ' ')"
fi
echo "   libge2gl.so → libge2gl.so.0 → libge2gl.so.$version, SONAME $soname, $nexports ge2gl_* exports (+$nstd weak std:: instantiations)"

echo "-- find_package(ge2gl) consumer (tests/install_consumer)"
run consumer-configure.log cmake -S "$root/tests/install_consumer" -B "$work/consumer" "${gen[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" -DGE2GL_EXAMPLES_DIR="$root/examples"
found=$(sed -n 's/^ge2gl_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[ "$found" = "$lib/cmake/ge2gl" ] || fail "find_package(ge2gl) found '$found', not the package in $prefix"
run consumer-build.log cmake --build "$work/consumer" --parallel "$jobs"
resolved=$(ldd "$work/consumer/install_consumer" | awk '$1 == "libge2gl.so.0" { print $3 }')
[ "$resolved" = "$lib/libge2gl.so.0" ] || fail "install_consumer loads libge2gl.so.0 from '$resolved', not $lib"
run consumer-run.log "$work/consumer/install_consumer"
cat "$logs/consumer-run.log"
run consumer-cxx-run.log "$work/consumer/install_consumer_cxx"
cat "$logs/consumer-cxx-run.log"
run minimal-host-run.log "$work/consumer/minimal_host_installed" "$work/consumer/minimal_host.png"
[ "$(head -c 8 "$work/consumer/minimal_host.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  fail "minimal_host_installed wrote no PNG"
echo "   examples/minimal_host.c built against the package: $(tail -n 1 "$logs/minimal-host-run.log")"

echo "-- pkg-config: cc \$(pkg-config --cflags --libs ge2gl)"
export PKG_CONFIG_PATH=$lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
pcversion=$(pkg-config --modversion ge2gl) || fail "pkg-config cannot find ge2gl in $lib/pkgconfig"
[ "$pcversion" = "$version" ] || fail "pkg-config says ge2gl $pcversion, expected $version"
[ "$(pkg-config --variable=libdir ge2gl)" = "$lib" ] || fail "ge2gl.pc's libdir is $(pkg-config --variable=libdir ge2gl), not $lib"
# shellcheck disable=SC2046
run pc-build.log cc -std=c99 -Wall -Wextra -pedantic -Werror "$root/tests/install_consumer/main.c" \
  $(pkg-config --cflags --libs ge2gl) -o "$work/pc/pc_consumer"
LD_LIBRARY_PATH=$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} run pc-run.log "$work/pc/pc_consumer"
echo "   $(cat "$logs/pc-run.log")"

echo "-- add_subdirectory(ge2gl) from a parent project (tests/install_consumer/subdir)"
# GE2GL_BUILD_GL=OFF: the translator and shader generator are the largest part of the library's
# compile time and the top-level build above already compiles and installs them; this step checks
# that a parent project builds the library (hle, geometry, softmodel, api sources) without ge2gl's
# tools, tests and their dependencies, and that takes the GL-free library only.
run subdir-configure.log cmake -S "$root/tests/install_consumer/subdir" -B "$work/subdir" "${gen[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DGE2GL_SOURCE_DIR="$root" -DGE2GL_BUILD_GL=OFF
run subdir-build.log cmake --build "$work/subdir" --target subdir_consumer --parallel "$jobs"
subsoname=$(readelf -d "$work/subdir/ge2gl/api/libge2gl.so.0" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
[ "$subsoname" = libge2gl.so.0 ] || fail "the add_subdirectory build's SONAME is '$subsoname'"
run subdir-run.log "$work/subdir/subdir_consumer"
echo "   $(grep -o 'ge2gl targets in the parent project: .*' "$logs/subdir-configure.log")"
echo "   $(cat "$logs/subdir-run.log")"

echo "install check: OK ($((SECONDS - start)) s)"
