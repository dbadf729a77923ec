#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages ge2gl needs, only those that are missing. Run as root (or with sudo).
set -euo pipefail
pkgs=(cmake ninja-build g++ pkg-config libosmesa6-dev libegl-dev libgl-dev libglm-dev libgtest-dev libgmock-dev
      libpng-dev libopenimageio-dev libzstd-dev libsnappy-dev libminizip-dev libxxhash-dev libcli11-dev libbenchmark-dev zlib1g-dev
      nlohmann-json3-dev  # the tools' JSON files (tools/lib/json_io.h)
      libjemalloc-dev  # the CLI's allocator (tools/cli_allocator.cpp; optional, found by pkg-config)
      libzip-dev  # tests only: the dump tests write zip archives (the library reads them with minizip)
      clang libclang-rt-14-dev  # clang + its libFuzzer/sanitizer runtimes: scripts/fuzz.sh
      chromium parallel)  # tests only: the report's browser test (tests/tools_report.cpp), the README's
                          # GNU parallel recipe (scripts/check_parallel_recipe.sh)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
