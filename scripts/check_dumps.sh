#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every dump of at most 1 MiB must end with a clean exit (0 or 1, one message line) within 10 s and
# 1 GiB peak memory, with either backend. Usage:
#   scripts/check_dumps.sh [BUILD_DIR] DUMP_OR_DIR...
# With no dumps given it checks the hostile dumps of tests/hostile_dumps.h (written by
# write_hostile_dumps). Prints one line per dump and backend, then a summary; exits non-zero when
# any run breaks a limit.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
files=()
if [ $# -eq 0 ]; then
  "$build/write_hostile_dumps" "$tmp/hostile" >/dev/null || exit 1
  set -- "$tmp/hostile"
fi
for a in "$@"; do
  if [ -d "$a" ]; then
    while IFS= read -r f; do files+=("$f"); done < <(find "$a" -type f -size -1025k | sort)
  else
    files+=("$a")
  fi
done
bad=0 runs=0 maxs=0 maxkb=0
# --no-program-cache: hostile dumps leave no program binaries in the user's cache.
for f in "${files[@]}"; do
  for backend in soft gl; do
    runs=$((runs + 1))
    /usr/bin/time -f "%e %M" -o "$tmp/time" timeout -s KILL 15 "$build/ge2gl" render "$f" --backend "$backend" \
      --no-program-cache -o "$tmp/out.png" >/dev/null 2>"$tmp/err"
    rc=$?
    read -r secs kb < <(tail -1 "$tmp/time" 2>/dev/null || echo "99 0")
    lines=$(grep -vc "^ge2gl: warning:" "$tmp/err" || true)
    ok=1
    { [ "$rc" -eq 0 ] || [ "$rc" -eq 1 ]; } || ok=0
    awk -v s="$secs" 'BEGIN { exit !(s <= 10) }' || ok=0
    [ "${kb:-0}" -le $((1024 * 1024)) ] || ok=0
    [ "$lines" -le 1 ] || ok=0
    awk -v s="$secs" -v m="$maxs" 'BEGIN { exit !(s > m) }' && maxs=$secs
    [ "${kb:-0}" -gt "$maxkb" ] && maxkb=${kb:-0}
    if [ $ok -eq 0 ]; then
      bad=$((bad + 1))
      echo "FAIL $backend rc=$rc ${secs}s ${kb}KiB $f: $(head -c 200 "$tmp/err")"
    elif [ ${#files[@]} -le 50 ]; then
      echo "ok   $backend rc=$rc ${secs}s $((kb / 1024))MiB $(basename "$f")"
    fi
  done
done
echo "check_dumps: $runs runs over ${#files[@]} dumps, $bad over the limits; slowest ${maxs}s, peak $((maxkb / 1024)) MiB"
[ $bad -eq 0 ]
