#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Part of ge2gl's PPSSPP integration (integrations/ppsspp); see README.md there.
#
# Usage: integrations/ppsspp/check.sh OUT_DIR PSPAUTOTESTS [FRAMETESTS]
#
# Runs every pspautotests tests/gpu/**.prx with PPSSPPHeadless --compare (printed values against
# .expected, screenshots against .expected.bmp, as PPSSPP's own test runner compares them) under
# PPSSPP's software core and under ge2gl's core, and prints a table: a test per row, a column per
# core, the sceGe tests (ge/, signals/, displaylist/, callbacks/) first; then the pass counts and
# the whole run's time per core as a ratio to PPSSPP's. Logs: OUT_DIR/check/CORE/TEST.log.
# With FRAMETESTS (a folder with dumps/*.zip, as ../shared/frametests), each dump is also replayed
# by PPSSPP's own dump player on ge2gl's core and compared with `ge2gl render` of the same dump
# (soft: must be identical), and played with GL hardware mode at 2x (must run).
#
# Then the sceGe tests once more on ge2gl's soft core with PPSSPP's whole state saved and loaded
# back at every GE interrupt: each must end as without.
# OUT_DIR is build.sh's. Environment: CORES (default "software ge2gl ge2gl-gl": --graphics= values),
# TIMEOUT (seconds per test, default 60), ONLY (a grep -E pattern on test names), STATE_ROUNDTRIP
# (0 skips the save-state pass).
# Exit status: 1 when a sceGe test PPSSPP's core passes fails on ge2gl (soft), when ge2gl passes
# fewer tests than PPSSPP's core on any core, or when a frametest check fails; else 0.
set -euo pipefail
[ $# -ge 2 ] && [ $# -le 3 ] || { sed -n '4,20p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
out=$(cd "$1" && pwd)
autotests=$(cd "$2" && pwd)
frametests=${3:+$(cd "$3" && pwd)}
headless="$out/PPSSPPHeadless"
[ -x "$headless" ] || { echo "check.sh: no $headless (run build.sh first)" >&2; exit 2; }
read -r -a cores <<<"${CORES:-software ge2gl ge2gl-gl}"
timeout_s=${TIMEOUT:-60}
work="$out/check"
mkdir -p "$work"
# PPSSPPHeadless writes __testcompare.png / __testfailure.bmp into its working directory.
cd "$work"

mapfile -t tests < <(cd "$autotests" && find tests/gpu -name '*.prx' | sed 's/\.prx$//' | sort | grep -E "${ONLY:-.}")
[ ${#tests[@]} -gt 0 ] || { echo "check.sh: no tests/gpu/*.prx under $autotests" >&2; exit 2; }

results="$work/results.tsv"
: >"$results"
for core in "${cores[@]}"; do
  mkdir -p "$work/$core"
  start=$(date +%s.%N)
  for t in "${tests[@]}"; do
    log="$work/$core/$(echo "$t" | tr / _).log"
    t0=$(date +%s.%N)
    set +e
    timeout $((timeout_s + 30)) "$headless" --root "$autotests" --compare --timeout="$timeout_s" \
      --graphics="$core" "$autotests/$t.prx" >"$log" 2>&1
    rc=$?
    set -e
    t1=$(date +%s.%N)
    pass=0
    grep -q " - passed!" "$log" && pass=1
    printf '%s\t%s\t%s\t%s\t%s\n' "$core" "$t" "$pass" "$rc" "$(awk -v a="$t0" -v b="$t1" "BEGIN{print b-a}")" >>"$results"
  done
  end=$(date +%s.%N)
  printf '%s\t__total__\t-\t-\t%s\n' "$core" "$(awk -v a="$start" -v b="$end" "BEGIN{print b-a}")" >>"$results"
done

status=0
python3 - "$results" "${cores[@]}" <<'EOF' || status=1
import sys, collections
path, cores = sys.argv[1], sys.argv[2:]
rows = collections.OrderedDict()
total = {}
for line in open(path):
    core, test, ok, rc, secs = line.rstrip("\n").split("\t")
    if test == "__total__":
        total[core] = float(secs)
        continue
    rows.setdefault(test, {})[core] = (ok == "1", float(secs))
names = {"software": "PPSSPP soft", "ge2gl": "ge2gl soft", "ge2gl-gl": "ge2gl GL exact",
         "ge2gl-hw": "ge2gl GL hw"}
sce = ("tests/gpu/ge/", "tests/gpu/signals/", "tests/gpu/displaylist/", "tests/gpu/callbacks/")
groups = [("sceGe semantics", [t for t in rows if t.startswith(sce)]),
          ("rendering and the rest of tests/gpu", [t for t in rows if not t.startswith(sce)])]
head = "| test | " + " | ".join(names.get(c, c) for c in cores) + " |"
bad = False
for title, tests in groups:
    print(f"\n### {title}\n")
    print(head)
    print("|---|" + "---|" * len(cores))
    for t in tests:
        cells = ["pass" if rows[t].get(c, (False, 0))[0] else "**fail**" for c in cores]
        print(f"| {t[len('tests/gpu/'):]} | " + " | ".join(cells) + " |")
    counts = [sum(rows[t].get(c, (False, 0))[0] for t in tests) for c in cores]
    print("| **passed** | " + " | ".join(f"**{n} of {len(tests)}**" for n in counts) + " |")
    if title.startswith("sceGe") and "software" in cores and "ge2gl" in cores:
        lost = [t for t in tests if rows[t]["software"][0] and not rows[t]["ge2gl"][0]]
        if lost:
            bad = True
            print("\nsceGe tests PPSSPP's core passes and ge2gl's fails: " + ", ".join(lost))
print("\n### whole run\n")
print("| core | passed | time s | time / PPSSPP soft |")
print("|---|---|---|---|")
for c in cores:
    n = sum(rows[t].get(c, (False, 0))[0] for t in rows)
    ratio = total[c] / total["software"] if "software" in total and total["software"] > 0 else float("nan")
    print(f"| {names.get(c, c)} | {n} of {len(rows)} | {total.get(c, 0):.1f} | {ratio:.2f} |")
if "software" in cores:
    base = sum(rows[t]["software"][0] for t in rows)
    for c in cores:
        if c.startswith("ge2gl") and c != "ge2gl-hw" and sum(rows[t].get(c, (False, 0))[0] for t in rows) < base:
            bad = True
            print(f"\n{names.get(c, c)} passes fewer tests than PPSSPP's software core")
sys.exit(1 if bad else 0)
EOF

# Save states: the sceGe tests again on ge2gl's soft core with PPSSPP's whole state saved and
# loaded back at every GE interrupt (GE2GL_STATE_ROUNDTRIP; PPSSPP's interpreter, as a state
# loaded from inside a CoreTiming event cannot return into JIT code): each must pass as without.
if [ "${STATE_ROUNDTRIP:-1}" = 1 ]; then
  mkdir -p "$work/roundtrip"
  rt_pass=0 rt_same=0 rt_total=0 rt_trips=0 rt_failed=0 rt_nocount=0
  for t in "${tests[@]}"; do
    case "$t" in tests/gpu/ge/*|tests/gpu/signals/*|tests/gpu/displaylist/*|tests/gpu/callbacks/*) ;; *) continue ;; esac
    log="$work/roundtrip/$(echo "$t" | tr / _).log"
    set +e
    GE2GL_STATE_ROUNDTRIP=1 timeout $((timeout_s + 30)) "$headless" --root "$autotests" --compare --timeout="$timeout_s" \
      --graphics=ge2gl --cpu=interpreter "$autotests/$t.prx" >"$log" 2>&1
    set -e
    rt_total=$((rt_total + 1))
    p=0
    grep -q " - passed!" "$log" && p=1 && rt_pass=$((rt_pass + 1))
    base=$(awk -F'\t' -v t="$t" '$1 == "ge2gl" && $2 == t {print $3}' "$results")
    [ "$p" = "${base:-x}" ] && rt_same=$((rt_same + 1))
    n=$(sed -n 's/^ge2gl: \([0-9]*\) save-state round trips, \([0-9]*\) failed$/\1 \2/p' "$log" | head -1)
    # The count is printed when the core shuts down: a run killed by the timeout has none.
    [ -n "$n" ] || { rt_nocount=$((rt_nocount + 1)); n="0 0"; echo "save states: $t printed no count (log $log)" >&2; }
    rt_trips=$((rt_trips + ${n%% *}))
    rt_failed=$((rt_failed + ${n##* }))
  done
  echo
  echo "### save states"
  echo
  echo "sceGe tests with a save-state round trip at every GE interrupt: $rt_pass of $rt_total pass," \
       "$rt_same of $rt_total as without; $rt_trips round trips, $rt_failed failed" \
       "$([ "$rt_nocount" = 0 ] || echo "; $rt_nocount runs ended without their count")"
  { [ "$rt_same" = "$rt_total" ] && [ "$rt_failed" = 0 ] && [ "$rt_nocount" = 0 ]; } || status=1
fi

if [ -n "$frametests" ]; then
  cli="$out/ge2gl-build/ge2gl"
  mkdir -p "$work/frames/soft" "$work/frames/hw2"
  echo
  echo "### frametests through PPSSPP's dump player"
  echo
  fail=0
  shopt -s nullglob
  dumps=("$frametests"/dumps/*.zip "$frametests"/dumps/*.ZIP)
  for d in "${dumps[@]}"; do
    name=$(basename "$d")
    name=${name%.zip}
    name=${name%.ZIP}
    name=${name%.ppdmp}
    set +e
    timeout 300 "$headless" --graphics=ge2gl --timeout=120 --screenshot-save="$work/frames/soft/$name-soft.png" "$d" \
      >"$work/frames/soft/$name.log" 2>&1
    timeout 300 "$headless" --graphics=ge2gl-hw --resolution-scale=2 --timeout=120 \
      --screenshot-save="$work/frames/hw2/$name.png" "$d" >"$work/frames/hw2/$name.log" 2>&1
    rc=$?
    set -e
    if [ $rc -ne 0 ] || [ ! -s "$work/frames/hw2/$name.png" ]; then
      echo "GL hw 2x: $name did not run (exit $rc, log $work/frames/hw2/$name.log)"
      fail=1
    fi
  done
  echo "GL hw at 2x: ${#dumps[@]} dumps played$([ $fail = 0 ] && echo ', all wrote their frame')"
  echo
  echo "ge2gl render --backend soft against PPSSPP's player on ge2gl's soft core (MSE 0 = identical pixels):"
  set +e
  "$cli" compare "${dumps[@]}" --backend soft --ref-dir "$work/frames/soft" --max-mse 0 --json "$work/frames/soft.json"
  [ $? -eq 0 ] || fail=1
  set -e
  [ $fail = 0 ] || status=1
fi
exit $status
