#!/usr/bin/env bash
# Set up, build and run the whole test suite, then the same tests under ASan+UBSan, then the
# software model's tests and every dump with 4 band threads under ThreadSanitizer, then every
# libFuzzer harness for 30 s (scripts/fuzz.sh; fails on any finding).
# GE2GL_SKIP_SANITIZE=1 skips the sanitizer passes and GE2GL_SKIP_FUZZ=1 the fuzzing (quick local runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
jobs=$(nproc 2>/dev/null || echo 2)
bash "$root/scripts/build.sh" "$root/build"
echo "== tests (Release) =="
(cd "$root/build" && ctest --output-on-failure -j"$jobs" --timeout 1200)
echo "== hostile dumps: clean exit within 10 s and 1 GiB, both backends =="
bash "$root/scripts/check_dumps.sh" "$root/build"
if [ "${GE2GL_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== tests (ASan + UBSan) =="
  bash "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_BUILD_TYPE=Debug -DGE2GL_SANITIZE=ON -DGE2GL_BUILD_BENCH=OFF
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # Accuracy runs over all frametests are slow under the sanitizers and add nothing there.
  (cd "$root/build-asan" && GE2GL_SANITIZER_RUN=1 ctest --output-on-failure -j"$jobs" --timeout 2400 -LE accuracy)
  echo "== software model under ThreadSanitizer (4 band threads) =="
  cmake -S "$root" -B "$root/build-tsan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGE2GL_TSAN=ON \
    -DGE2GL_BUILD_GL=OFF -DGE2GL_BUILD_BENCH=OFF >/dev/null
  ninja -C "$root/build-tsan" -j"$jobs" test_soft ge2gl_cli
  export TSAN_OPTIONS=halt_on_error=1:exitcode=66
  (cd "$root/build-tsan" && ctest --output-on-failure -j"$jobs" --timeout 2400 -L soft)
  shopt -s nullglob
  for d in "$root"/dumps/*.ppdmp "$root"/../shared/frametests/dumps/*.zip; do
    "$root/build-tsan/ge2gl" render "$d" --backend soft --threads 4 -o "$root/build-tsan/tsan.png" >/dev/null
  done
fi
if [ "${GE2GL_SKIP_FUZZ:-0}" != 1 ]; then
  echo "== fuzzing: every libFuzzer harness for 30 s (docs/fuzzing.md) =="
  bash "$root/scripts/fuzz.sh" 30
fi
