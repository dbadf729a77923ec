#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job: set up, build, render the bundled dumps/ into out/ with both backends and print
# comparison tables (each backend against the checked-in expected images, GL against the software model).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" "$root/build"
cd "$root"
mkdir -p out
shopt -s nullglob
dumps=(dumps/*.ppdmp)
[ ${#dumps[@]} -gt 0 ] || { echo "main: no dumps in dumps/"; exit 1; }
for d in "${dumps[@]}"; do
  n=$(basename "$d" .ppdmp)
  ./build/ge2gl render "$d" --backend soft -o "out/$n-soft.png"
  ./build/ge2gl render "$d" --backend gl -o "out/$n-gl.png" || echo "main: GL render of $n failed"
done
echo "== software model vs expected images (dumps/expected) =="
./build/ge2gl compare "${dumps[@]}" --backend soft --accuracy ppsspp --ref-dir dumps/expected --diff-dir out/diff-soft || true
echo "== GL translator vs expected images =="
./build/ge2gl compare "${dumps[@]}" --backend gl --accuracy ppsspp --ref-dir dumps/expected --diff-dir out/diff-gl || true
if [ -d ../shared/frametests/dumps ]; then
  echo "== software model vs frametest references (../shared/frametests) =="
  ./build/ge2gl compare ../shared/frametests/dumps/* --backend soft --accuracy ppsspp --ref-dir ../shared/frametests/ref --json out/frametests-soft.json || true
fi
echo "main: images in out/"
