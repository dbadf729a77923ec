#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Mutation fuzzing of real dumps (docs/fuzzing.md "Mutation fuzzing of real dumps"): seeded mutants
# of the frametests (build/ge2gl_mutate, tools/lib/mutate.h) rendered by `ge2gl render` with the
# software model, GL exact and GL hw at 2x; every run must end cleanly (exit 0 or 1, at most one
# message line besides warnings) within the time limit (10 s) and peak RSS limit (1 GiB).
#
#   bash scripts/fuzz_mutate.sh [-n COUNT] [-s FIRST_SEED] [-j JOBS] [-b BACKENDS] [-d DUMPS_DIR]
#                               [-B BUILD_DIR] [-o OUT_DIR] [-t SECONDS] [-m MIB]
#
# Defaults: 1,000 mutants from seed 1, 2 at a time (niced), backends soft,gl,hw2, dumps from
# ../shared/frametests/dumps, build/, results in BUILD_DIR/fuzz-mutate. Mutant SEED is made from
# dump number SEED % (number of dumps) in name order, so `-s SEED -n 1` redoes one (without the
# default dumps folder the script says so and exits 0). Output:
# results.tsv (seed, dump, backend, exit status, seconds, peak KiB, verdict), failures/ (each
# failing mutant as seed-SEED.ppdmp with its mutations in seed-SEED.txt), then per backend the
# runs, failures, slowest run and largest peak RSS. A run over a limit is run again alone (no other
# run beside it) before it counts, so that machine load is not reported as a finding; verdicts:
# ok, crash, time, memory, output (more than one message line). Exit status 1 when any run failed.
# The full test tier (scripts/test.sh) runs -n 30.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
count=1000 first=1 jobs=2 backends=soft,gl,hw2 dumpsDir=$root/../shared/frametests/dumps build=$root/build
out="" limitS=10 limitMiB=1024 dumpsGiven=0
while getopts "n:s:j:b:d:B:o:t:m:" opt; do
  case $opt in
    n) count=$OPTARG ;; s) first=$OPTARG ;; j) jobs=$OPTARG ;; b) backends=$OPTARG ;; d) dumpsDir=$OPTARG dumpsGiven=1 ;;
    B) build=$OPTARG ;; o) out=$OPTARG ;; t) limitS=$OPTARG ;; m) limitMiB=$OPTARG ;;
    *) sed -n '8,9p' "$0" >&2; exit 2 ;;
  esac
done
out=${out:-$build/fuzz-mutate}
for b in "$build/ge2gl" "$build/ge2gl_mutate"; do
  [ -x "$b" ] || { echo "fuzz_mutate.sh: $b missing (ninja -C $build ge2gl_cli ge2gl_mutate)" >&2; exit 2; }
done
shopt -s nullglob
dumps=("$dumpsDir"/*)
if ((${#dumps[@]} == 0)); then
  # Without the shared frametests (a checkout on its own) there is nothing to mutate.
  [ "$dumpsGiven" = 1 ] && { echo "fuzz_mutate.sh: no dumps in $dumpsDir" >&2; exit 2; }
  echo "fuzz_mutate: skipped, no dumps in $dumpsDir"
  exit 0
fi
IFS=, read -r -a backendList <<<"$backends"
for b in "${backendList[@]}"; do
  case $b in soft | gl | hw2) ;; *) echo "fuzz_mutate.sh: unknown backend '$b' (soft, gl, hw2)" >&2; exit 2 ;; esac
done
rm -rf "$out/failures"
mkdir -p "$out/failures"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export build work limitS limitMiB out
export dumpList=$work/dumps.txt backendsCsv=$backends
printf '%s\n' "${dumps[@]}" >"$dumpList"

# One render: prints "rc secs kib verdict". Mutants leave no program binaries in the user's cache
# (--no-program-cache): their random states would only fill it.
render() {
  local mutant=$1 backend=$2 tag=$3 args=()
  case $backend in
    soft) args=(--backend soft --threads 1) ;;
    gl) args=(--backend gl) ;;
    hw2) args=(--backend gl --gl-mode hw --scale 2) ;;
  esac
  nice -n 10 /usr/bin/time -f "%e %M" -o "$work/$tag.time" timeout -s KILL $((limitS + 5)) \
    "$build/ge2gl" render "$mutant" "${args[@]}" --no-program-cache -o "$work/$tag.png" >/dev/null 2>"$work/$tag.err"
  local rc=$? secs kib lines verdict=ok
  read -r secs kib < <(tail -1 "$work/$tag.time" 2>/dev/null || echo "99 0")
  [[ "$secs" =~ ^[0-9.]+$ ]] || secs=99
  [[ "$kib" =~ ^[0-9]+$ ]] || kib=0
  lines=$(grep -vc "^ge2gl: warning:" "$work/$tag.err" || true)
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 1 ] && [ "$rc" -ne 137 ]; then verdict=crash
  elif [ "$rc" -eq 137 ] || awk -v s="$secs" -v l="$limitS" 'BEGIN { exit !(s > l) }'; then verdict=time
  elif [ "$kib" -gt $((limitMiB * 1024)) ]; then verdict=memory
  elif [ "$lines" -gt 1 ]; then verdict=output
  fi
  rm -f "$work/$tag.png"
  echo "$rc $secs $kib $verdict"
}
export -f render

# One seed: the mutant, then each backend; one TSV line per run.
one() {
  local seed=$1 n dump mutant
  n=$(wc -l <"$dumpList")
  dump=$(sed -n "$((seed % n + 1))p" "$dumpList")
  mutant=$work/m$seed.ppdmp
  "$build/ge2gl_mutate" "$seed" "$dump" "$mutant" >"$work/m$seed.txt" 2>&1 || { echo "mutate failed: $seed" >&2; return; }
  local b
  IFS=, read -r -a bl <<<"$backendsCsv"
  for b in "${bl[@]}"; do
    read -r rc secs kib verdict < <(render "$mutant" "$b" "r$seed-$b")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$seed" "$(basename "$dump")" "$b" "$rc" "$secs" "$kib" "$verdict"
    if [ "$verdict" != ok ]; then
      cp "$mutant" "$out/failures/seed-$seed.ppdmp"
      { echo "dump: $dump"; cat "$work/m$seed.txt"; echo "$b: exit $rc, ${secs} s, ${kib} KiB: $verdict";
        head -c 400 "$work/r$seed-$b.err"; } >>"$out/failures/seed-$seed.txt"
    fi
    rm -f "$work/r$seed-$b".*
  done
  rm -f "$mutant" "$work/m$seed.txt"
}
export -f one

echo "fuzz_mutate: $count mutants from seed $first of ${#dumps[@]} dumps, backends $backends, $jobs at a time"
seq "$first" $((first + count - 1)) | xargs -P "$jobs" -I{} bash -c 'one {}' >"$work/results.tsv"
# Runs over the time or memory limit again, alone.
: >"$out/results.tsv"
while IFS=$'\t' read -r seed dump backend rc secs kib verdict; do
  if [ "$verdict" = time ] || [ "$verdict" = memory ]; then
    n=$(wc -l <"$dumpList")
    full=$(sed -n "$((seed % n + 1))p" "$dumpList")
    "$build/ge2gl_mutate" "$seed" "$full" "$work/again.ppdmp" >/dev/null 2>&1
    read -r rc secs kib verdict < <(render "$work/again.ppdmp" "$backend" again)
    if [ "$verdict" = ok ]; then
      echo "seed $seed $backend: over a limit beside another run, ${secs} s ${kib} KiB alone" >>"$out/failures/seed-$seed.txt"
    fi
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$seed" "$dump" "$backend" "$rc" "$secs" "$kib" "$verdict" >>"$out/results.tsv"
done < <(sort -n "$work/results.tsv")
# Failure files of runs that passed alone are not findings.
for f in "$out"/failures/seed-*.ppdmp; do
  s=${f##*/seed-}; s=${s%.ppdmp}
  awk -F'\t' -v s="$s" '$1 == s && $7 != "ok" { bad = 1 } END { exit !bad }' "$out/results.tsv" ||
    rm -f "$f"
done
awk -F'\t' '
  { n[$3]++; if ($7 != "ok") { bad[$3]++; kind[$3 " " $7]++ }
    if ($5 + 0 > t[$3]) { t[$3] = $5 + 0; ts[$3] = $1 } if ($6 + 0 > m[$3]) { m[$3] = $6 + 0; ms[$3] = $1 } }
  END {
    for (b in n) {
      k = ""; for (x in kind) { split(x, p, " "); if (p[1] == b) k = k " " p[2] "=" kind[x] }
      printf "%-5s %5d runs, %d failed%s; slowest %.2f s (seed %s), peak %d MiB (seed %s)\n",
             b, n[b], bad[b] + 0, k, t[b], ts[b], m[b] / 1024, ms[b]
      total += bad[b] + 0
    }
    exit total > 0
  }' "$out/results.tsv"
rc=$?
echo "fuzz_mutate: results in $out/results.tsv$([ $rc -ne 0 ] && echo ", failing mutants in $out/failures")"
exit $rc
