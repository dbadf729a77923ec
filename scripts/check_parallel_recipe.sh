#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the README's GNU parallel recipe (the sh block after "with GNU parallel") exactly as it is
# written, from the project root, and checks that the merged file holds every frametest once
# (the README promises that the recipe works as written).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
block=$(awk '/with GNU parallel/ {f = 1} f && /^```sh/ {g = 1; next} g && /^```/ {exit} g {print}' README.md)
if [ -z "$block" ]; then
  echo "check_parallel_recipe: no GNU parallel block in README.md" >&2
  exit 1
fi
files="out-1.json out-2.json out-3.json out-4.json all.json"
for f in $files; do
  if [ -e "$f" ]; then
    echo "check_parallel_recipe: $f exists in $root; not overwriting it" >&2
    exit 1
  fi
done
trap 'rm -f $files' EXIT
printf '%s\n' "$block"
# --will-cite: parallel's one-time citation notice, through its documented options variable.
PARALLEL="--will-cite" bash -euo pipefail -c "$block" >/dev/null
want=$(find ../shared/frametests/dumps -maxdepth 1 -type f | wc -l)
got=$(grep -c '"index": ' all.json)
if [ "$got" != "$want" ]; then
  echo "check_parallel_recipe: all.json holds $got results, the frametests are $want dumps" >&2
  exit 1
fi
echo "check_parallel_recipe: the recipe ran as written; all.json holds all $got dumps once"
