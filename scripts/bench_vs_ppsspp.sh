#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Whole-process speed of ge2gl against PPSSPP's headless build on the same dumps, as
# paired runs: for each dump and mode, N rounds of "ge2gl, PPSSPP" in alternating order, the ratio
# of each pair's wall times, and the median of those ratios (per dump, over all dumps, and over the
# five dumps PPSSPP takes longest on). Peak RSS of each side too.
#
#   PPSSPP_HEADLESS=/path/to/PPSSPPHeadless [BENCH_MODES="soft gl hw"] scripts/bench_vs_ppsspp.sh [BUILD_DIR] [ROUNDS] [DUMP...]
#
# Modes: soft (ge2gl --backend soft vs PPSSPP --graphics=software), gl (ge2gl --backend gl, exact
# mode on OSMesa/llvmpipe, vs PPSSPP --graphics=gles on Mesa's software GL) and hw (ge2gl's
# hardware mode at 1x, same GL, vs --graphics=gles). Both sides write the frame as a PNG. A mode whose PPSSPP run fails (a build without a headless GL context answers
# --graphics=gles with an error) is reported and skipped, not timed. A PPSSPP whose GL context
# needs an X display takes it from DISPLAY (start the server beforehand, so that its start is not
# timed: docs/benchmarks.md). Dumps default to
# ../shared/frametests/dumps. PPSSPP is not a dependency: without PPSSPP_HEADLESS the script says
# so and exits 0. How to build PPSSPPHeadless: docs/benchmarks.md.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
rounds=${2:-2}
shift $(( $# >= 2 ? 2 : $# ))
if [ -z "${PPSSPP_HEADLESS:-}" ] || [ ! -x "$PPSSPP_HEADLESS" ]; then
  echo "bench_vs_ppsspp: set PPSSPP_HEADLESS to a PPSSPPHeadless binary (docs/benchmarks.md); nothing measured"
  exit 0
fi
dumps=("$@")
[ ${#dumps[@]} -gt 0 ] || dumps=("$root"/../shared/frametests/dumps/*)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One timed run: prints "seconds maxrss_kib" (wall seconds to the millisecond, peak RSS in KiB), or
# "fail 0" when the command exits non-zero. GNU time's %e has 10 ms steps, too coarse for a 20-80
# ms process (its ratios came out as 0.02/0.07 and 0.03/0.08), so the wall time is bash's
# EPOCHREALTIME around the run; time itself (forked before, reaped after) adds under 1 ms.
timed() {
  local t0=$EPOCHREALTIME t1
  if /usr/bin/time -f "%M" -o "$tmp/t" "$@" >/dev/null 2>&1; then
    t1=$EPOCHREALTIME
    awk -v a="${t0/,/.}" -v b="${t1/,/.}" -v m="$(tail -1 "$tmp/t")" 'BEGIN { printf "%.3f %d\n", b - a, m }'
  else
    echo "fail 0"
  fi
}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# A PPSSPP built with SDL3 from source (integrations/ppsspp/sdl3.sh) makes its GL context through
# SDL's offscreen driver (EGL) when no X display is given.
[ -n "${DISPLAY:-}" ] || export SDL_VIDEO_DRIVER=${SDL_VIDEO_DRIVER:-offscreen}

for mode in ${BENCH_MODES:-soft gl hw}; do
  case $mode in
    soft) ours=(--backend soft); theirs=(--graphics=software) ;;
    gl) ours=(--backend gl); theirs=(--graphics=gles) ;;
    hw) ours=(--backend gl --gl-mode hw); theirs=(--graphics=gles) ;;
    *) echo "bench_vs_ppsspp: unknown mode $mode (soft, gl, hw)" >&2; exit 2 ;;
  esac
  : > "$tmp/$mode.rows"
  read -r probe _ < <(LIBGL_ALWAYS_SOFTWARE=1 timed "$PPSSPP_HEADLESS" "${theirs[@]}" --timeout=60 --screenshot-save="$tmp/p.png" "${dumps[0]}")
  if [ "$probe" = fail ]; then
    echo "$mode: PPSSPP fails with ${theirs[*]} on $(basename "${dumps[0]}") (no such renderer in this build?): not measured"
    continue
  fi
  printf "== %s ==\n%-58s %9s %9s %7s %8s %8s\n" "$mode" dump "ge2gl s" "ppsspp s" ratio "ge2gl MiB" "ppsspp MiB"
  for d in "${dumps[@]}"; do
    : > "$tmp/ratios"
    for ((r = 0; r < rounds; ++r)); do
      if ((r % 2 == 0)); then
        read -r a am < <(timed "$build/ge2gl" render "$d" "${ours[@]}" -o "$tmp/o.png")
        read -r b bm < <(LIBGL_ALWAYS_SOFTWARE=1 timed "$PPSSPP_HEADLESS" "${theirs[@]}" --timeout=60 --screenshot-save="$tmp/p.png" "$d")
      else
        read -r b bm < <(LIBGL_ALWAYS_SOFTWARE=1 timed "$PPSSPP_HEADLESS" "${theirs[@]}" --timeout=60 --screenshot-save="$tmp/p.png" "$d")
        read -r a am < <(timed "$build/ge2gl" render "$d" "${ours[@]}" -o "$tmp/o.png")
      fi
      awk -v a="$a" -v b="$b" 'BEGIN { if (b > 0) printf "%.4f\n", a / b }' >> "$tmp/ratios"
    done
    ratio=$(median < "$tmp/ratios")
    printf "%-58s %9s %9s %7s %8d %8d\n" "$(basename "$d" | cut -c1-58)" "$a" "$b" "$ratio" $((am / 1024)) $((bm / 1024))
    echo "$ratio $b" >> "$tmp/$mode.rows"
  done
  all=$(awk '{ print $1 }' "$tmp/$mode.rows" | median)
  heavy=$(sort -k2 -gr "$tmp/$mode.rows" | head -5 | awk '{ print $1 }' | median)
  echo "$mode: median of pair ratios (ge2gl / PPSSPP) over ${#dumps[@]} dumps: $all; over the 5 heaviest for PPSSPP: $heavy"
done
