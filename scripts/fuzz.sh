#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer harnesses (clang, ASan + UBSan + float-cast-overflow; tests/fuzz/) in
# build-fuzz/, makes their seed corpora from the project's dumps (and ../shared/frametests when
# present), and runs each harness for SECONDS. docs/fuzzing.md.
#
#   bash scripts/fuzz.sh [SECONDS_PER_HARNESS] [HARNESS...]
#
# Harnesses: ppdmp_load replay_soft replay_gl list texture vertex spline api savestate (default: all).
# Prints per harness: executions, exec/s, coverage (cov/ft of libFuzzer's last status line), corpus
# size (inputs kept, in build-fuzz/corpus/NAME, seeds not counted) and findings; exits non-zero
# when any harness finds a crash, leak, timeout or out-of-memory, naming the reproducer (run
# `build-fuzz/fuzz/fuzz_NAME FILE` to replay it).
# Environment: GE2GL_FUZZ_BUILD (build dir, default build-fuzz), GE2GL_FUZZ_JOBS (ninja -j,
# default: all cores), GE2GL_FUZZ_ARGS (extra libFuzzer flags, e.g. "-runs=1000000"),
# GE2GL_FUZZ_PARALLEL (harnesses run at once, default 1: one after the other; each takes a core),
# GE2GL_FUZZ_TESTS=ON (build the test suite too), GE2GL_FUZZ_BUILD_ONLY=1 (build, do not run).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
secs=${1:-60}
shift || true
all=(ppdmp_load replay_soft replay_gl list texture vertex spline api savestate)
harnesses=("$@")
((${#harnesses[@]})) || harnesses=("${all[@]}")
build=${GE2GL_FUZZ_BUILD:-$root/build-fuzz}
jobs=${GE2GL_FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}

for h in "${harnesses[@]}"; do
  [[ " ${all[*]} " == *" $h "* ]] || { echo "fuzz.sh: unknown harness '$h' (${all[*]})" >&2; exit 2; }
done

parallel=${GE2GL_FUZZ_PARALLEL:-1}
[[ "$parallel" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: GE2GL_FUZZ_PARALLEL must be a positive count" >&2; exit 2; }

echo "== fuzz: building the harnesses in $build =="
# GE2GL_FUZZ_TESTS=ON builds the test suite in the same configuration (scripts/test.sh runs it
# there under the same sanitizers: one clang build serves both).
tests=${GE2GL_FUZZ_TESTS:-OFF}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DGE2GL_FUZZ=ON \
  -DGE2GL_BUILD_TESTS="$tests" -DGE2GL_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only" >/dev/null
if [ "$tests" = ON ]; then
  nice -n 10 ninja -C "$build" -j"$jobs" >/dev/null
else
  nice -n 10 ninja -C "$build" -j"$jobs" ge2gl_fuzzers >/dev/null
fi
[ "${GE2GL_FUZZ_BUILD_ONLY:-0}" = 1 ] && exit 0

# Seeds: remade when a dump or the seed maker is newer than the stamp.
seeds=$build/seeds
shopt -s nullglob
dumps=("$root"/dumps/*.ppdmp "$root"/../shared/frametests/dumps/*.zip)
stamp=$seeds/.stamp
remake=0
[ -f "$stamp" ] || remake=1
for f in "$build/fuzz/fuzz_seeds" "${dumps[@]}"; do [ "$remake" = 1 ] || [ "$f" -nt "$stamp" ] && remake=1; done
if [ "$remake" = 1 ]; then
  rm -rf "$seeds"
  mkdir -p "$seeds"
  "$build/fuzz/fuzz_seeds" "$seeds" "${dumps[@]}"
  touch "$stamp"
fi
dicts=$build/dict
mkdir -p "$dicts"
cat "$root/tests/fuzz/ppdmp.dict" "$root/tests/fuzz/ge_cmds.dict" >"$dicts/replay.dict"

# Per harness: seed directory, dictionary, largest input.
seedsOf() { case $1 in ppdmp_load) echo load ;; replay_*) echo replay ;; *) echo "$1" ;; esac; }
dictOf() {
  case $1 in
  ppdmp_load) echo "$root/tests/fuzz/ppdmp.dict" ;;
  replay_*) echo "$dicts/replay.dict" ;;
  *) echo "$root/tests/fuzz/ge_cmds.dict" ;;
  esac
}
maxLenOf() { case $1 in ppdmp_load) echo 1048576 ;; replay_* | texture) echo 262144 ;; *) echo 65536 ;; esac; }
# replay_gl keeps a GL context, llvmpipe's JIT code and its compiled programs for the whole run
# (1.2-2.9 GB resident under ASan; 2,845 MB at the peak of a million-execution run).
rssLimitOf() { case $1 in replay_gl) echo 4096 ;; *) echo 2048 ;; esac; }
# replay_gl's renderer keeps what it compiles (programs, llvmpipe code) from one input to the next,
# so libFuzzer's per-input leak check (an input that frees less than it allocates is run again
# under a full LeakSanitizer scan) fired on every new program and scanned a 1-2 GB heap each time:
# replay_gl ran at 60 exec/s and slowed the harness beside it. LeakSanitizer still checks the whole
# run when the process exits.
extraFlagsOf() { case $1 in replay_gl) echo -detect_leaks=0 ;; esac; }

# allocator_release_to_os_interval_ms=-1: ASan's allocator otherwise hands freed pages back to the
# system several hundred times a second (madvise, then page faults to get them back), which cost
# replay_gl a third of its executions (129 -> 187 exec/s beside replay_soft).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1:allocator_release_to_os_interval_ms=-1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Runs one harness; leaves its summary line in logs/NAME.summary and, when it found something,
# logs/NAME.found (the runs may go side by side).
runHarness() {
  local h=$1
  local bin=$build/fuzz/fuzz_$h
  local sum=$build/logs/$h.summary
  mkdir -p "$build/logs"
  rm -f "$sum" "$build/logs/$h.found"
  if [ ! -x "$bin" ]; then
    printf '%-12s not built (GL or the plugin API is off in this build)\n' "$h" >"$sum"
    return 0
  fi
  local corpus artifacts log rc execs rate last cov ft kept repro kind findings
  corpus=$build/corpus/$h
  artifacts=$build/findings/$h
  log=$build/logs/$h.log
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  echo "== fuzz: $h for ${secs}s =="
  rc=0
  # shellcheck disable=SC2086
  # -purge_allocator_interval=-1: libFuzzer otherwise purges the allocator every second once RSS
  # passes half of -rss_limit_mb, and replay_gl lives there: about 2,900 madvise calls a second,
  # each a TLB flush across cores, 20-40% of its time in the kernel.
  nice -n 10 "$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb="$(rssLimitOf "$h")" -purge_allocator_interval=-1 -max_len="$(maxLenOf "$h")" \
    -dict="$(dictOf "$h")" $(extraFlagsOf "$h") -artifact_prefix="$artifacts/" -print_final_stats=1 -print_pcs=0 \
    ${GE2GL_FUZZ_ARGS:-} "$corpus" "$seeds/$(seedsOf "$h")" >"$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  kept=$(find "$corpus" -type f | wc -l)
  repro=$(grep -hoE '(Test unit written to|artifact_prefix.*; Test unit written to) [^ ]+' "$log" | awk '{print $NF}' | tail -1 || true)
  if [ "$rc" != 0 ] || [ -n "$repro" ]; then
    touch "$build/logs/$h.found"
    kind=$(grep -oE 'ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)[^:]*: [a-z-]+|runtime error|deadly signal|timeout|out-of-memory' "$log" | head -1 || true)
    findings="FOUND ${kind:-exit code $rc}: ${repro:-see $log}"
  else
    findings="none"
  fi
  printf '%-12s executions %-9s exec/s %-6s cov %-6s ft %-7s corpus %-6s findings: %s\n' \
    "$h" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$kept" "$findings" >"$sum"
}

for h in "${harnesses[@]}"; do
  if ((parallel > 1)); then
    while (($(jobs -rp | wc -l) >= parallel)); do wait -n || true; done
    runHarness "$h" &
  else
    runHarness "$h"
  fi
done
wait
found=0
summary=()
for h in "${harnesses[@]}"; do
  summary+=("$(cat "$build/logs/$h.summary")")
  [ ! -f "$build/logs/$h.found" ] || found=1
done
echo "== fuzz summary (${secs}s per harness; logs in $build/logs) =="
printf '%s\n' "${summary[@]}"
if [ "$found" != 0 ]; then
  echo "fuzz: findings (reproduce with $build/fuzz/fuzz_NAME FILE)" >&2
  exit 1
fi
