#!/usr/bin/env bash
# Set up, build and run the whole test suite, then the same tests under ASan+UBSan.
# GE2GL_SKIP_SANITIZE=1 skips the sanitizer pass (for quick local runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
jobs=$(nproc 2>/dev/null || echo 2)
bash "$root/scripts/build.sh" "$root/build"
echo "== tests (Release) =="
(cd "$root/build" && ctest --output-on-failure -j"$jobs" --timeout 1200)
if [ "${GE2GL_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== tests (ASan + UBSan) =="
  bash "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_BUILD_TYPE=Debug -DGE2GL_SANITIZE=ON -DGE2GL_BUILD_BENCH=OFF
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # Accuracy runs over all frametests are slow under the sanitizers and add nothing there.
  (cd "$root/build-asan" && GE2GL_SANITIZER_RUN=1 ctest --output-on-failure -j"$jobs" --timeout 2400 -LE accuracy)
fi
