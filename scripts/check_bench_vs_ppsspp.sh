#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs scripts/bench_vs_ppsspp.sh against a stand-in for PPSSPPHeadless (CI has no PPSSPP): a
# script that accepts PPSSPP's options, writes the screenshot, takes a fixed 0.2 s for
# --graphics=software and fails for --graphics=gles as a build without a headless GL context does.
# Checks that the soft mode prints a row per dump and its medians, and that the gl and hw modes
# (both against --graphics=gles) are reported as not measured instead of being timed.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/PPSSPPHeadless" <<'STANDIN'
#!/usr/bin/env bash
out=""
for a in "$@"; do
  case $a in
    --graphics=gles) echo "Headless graphics context creation is not supported on this platform." >&2; exit 1 ;;
    --screenshot-save=*) out=${a#--screenshot-save=} ;;
  esac
done
sleep 0.2
[ -n "$out" ] && : > "$out"
exit 0
STANDIN
chmod +x "$tmp/PPSSPPHeadless"
dumps=("$root"/dumps/clut_dxt_sprites.ppdmp "$root"/dumps/render_to_texture.ppdmp)
PPSSPP_HEADLESS="$tmp/PPSSPPHeadless" bash "$root/scripts/bench_vs_ppsspp.sh" "$build" 2 "${dumps[@]}" > "$tmp/out" 2>&1
cat "$tmp/out"
fail() { echo "check_bench_vs_ppsspp: $1" >&2; exit 1; }
grep -q '^== soft ==' "$tmp/out" || fail "no soft table"
for d in "${dumps[@]}"; do
  grep -q "^$(basename "$d") .* [0-9.][0-9.]* " "$tmp/out" || fail "no row for $(basename "$d")"
done
grep -Eq '^soft: median of pair ratios \(ge2gl / PPSSPP\) over 2 dumps: [0-9.]+; over the 5 heaviest for PPSSPP: [0-9.]+$' "$tmp/out" ||
  fail "no soft medians"
for mode in gl hw; do
  grep -q "^$mode: PPSSPP fails with --graphics=gles" "$tmp/out" || fail "the failing $mode mode was not reported"
  grep -q "^== $mode ==" "$tmp/out" && fail "the failing $mode mode was timed"
done
echo "check_bench_vs_ppsspp: ok"
