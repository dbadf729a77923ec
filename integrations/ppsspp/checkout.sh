#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Part of ge2gl's PPSSPP integration (integrations/ppsspp); see README.md there.
#
# Usage: integrations/ppsspp/checkout.sh DEST
#
# Makes DEST a PPSSPP tree at the commit this integration is written for (c09e6bddaa), with the
# submodules PPSSPPHeadless needs at their pinned commits. Repositories come from GitHub, or from
# local clones when GE2GL_GIT_SOURCE names them: a pattern where {owner} and {name} are replaced,
# e.g. GE2GL_GIT_SOURCE='/srv/mirrors/{owner}+{name}/repo' (default https://github.com/{owner}/{name}.git).
# Where a pinned commit is not in the repository at hand (a fork's commit, a rewritten history),
# the commit named after it below is taken instead and the script says so; README.md lists the
# substitutes that are known to build.
set -euo pipefail
[ $# -eq 1 ] || { sed -n '4,13p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
dest=$1
# (The default sits in a variable: a '}' inside ${VAR:-...} would end the expansion early.)
default_pattern='https://github.com/{owner}/{name}.git'
pattern=${GE2GL_GIT_SOURCE:-$default_pattern}
ppsspp_commit=c09e6bddaace3a9f6dfeb48f52a9eef9ae221751

url() { local s=${pattern//\{owner\}/$1}; echo "${s//\{name\}/$2}"; }

# clone OWNER/NAME DIR COMMIT [FALLBACK_OWNER/NAME FALLBACK_COMMIT]
clone() {
  local repo=$1 dir=$2 commit=$3 alt_repo=${4:-} alt_commit=${5:-}
  rm -rf "$dir"
  # A repository that cannot be had at all (no mirror of a fork) counts as one without the commit.
  git clone -q --no-checkout "$(url "${repo%/*}" "${repo#*/}")" "$dir" 2>/dev/null || [ -n "$alt_commit" ] || {
    echo "checkout.sh: cannot clone $repo" >&2; exit 1; }
  if [ -d "$dir/.git" ] && git -C "$dir" cat-file -e "$commit^{commit}" 2>/dev/null; then
    git -C "$dir" checkout -q "$commit"
  elif [ -n "$alt_commit" ]; then
    if [ "$alt_repo" != "$repo" ] || [ ! -d "$dir/.git" ]; then
      rm -rf "$dir"
      git clone -q --no-checkout "$(url "${alt_repo%/*}" "${alt_repo#*/}")" "$dir"
    fi
    echo "checkout.sh: $dir: pinned $commit is not in $repo; taking $alt_repo $alt_commit" >&2
    git -C "$dir" checkout -q "$alt_commit"
  else
    echo "checkout.sh: $dir: pinned $commit is not in $repo" >&2
    exit 1
  fi
}

pin() { git -C "$dest" ls-tree "$ppsspp_commit" "$1" | awk '{print $3}'; }

if [ ! -d "$dest/.git" ]; then
  git clone -q --no-checkout "$(url hrydgard ppsspp)" "$dest"
fi
# Large files may be missing from a mirror (fonts past 4 MiB); the headless runner needs none.
git -C "$dest" checkout -q "$ppsspp_commit" 2>/dev/null || git -C "$dest" checkout -q -f "$ppsspp_commit" || true
[ "$(git -C "$dest" rev-parse HEAD)" = "$ppsspp_commit" ] || { echo "checkout.sh: cannot check out $ppsspp_commit" >&2; exit 1; }

clone hrydgard/glslang "$dest/ext/glslang" "$(pin ext/glslang)" KhronosGroup/glslang b34f619e1c85810dcb3c578107d2e48ba4ee2b37
clone KhronosGroup/SPIRV-Cross "$dest/ext/SPIRV-Cross" "$(pin ext/SPIRV-Cross)"
clone Kingcom/armips "$dest/ext/armips" "$(pin ext/armips)" Kingcom/armips 2d7f351e640ec260b43943f07a00c57211940378
clone gulrak/filesystem "$dest/ext/armips/ext/filesystem" \
  "$(git -C "$dest/ext/armips" ls-tree HEAD ext/filesystem | awk '{print $3}')"
clone RetroAchievements/rcheevos "$dest/ext/rcheevos" "$(pin ext/rcheevos)" RetroAchievements/rcheevos 6755915f2bdf6c11c83b3e0e68c4623a39c0dabe
clone erkkah/naett "$dest/ext/naett" "$(pin ext/naett)"
clone hrydgard/ppsspp-lua "$dest/ext/lua" "$(pin ext/lua)"
clone rtissera/libchdr "$dest/ext/libchdr" "$(pin ext/libchdr)"
clone Kethen/aemu_postoffice "$dest/ext/aemu_postoffice" "$(pin ext/aemu_postoffice)"
clone google/cpu_features "$dest/ext/cpu_features" "$(pin ext/cpu_features)"
clone miniupnp/miniupnp "$dest/ext/miniupnp" "$(pin ext/miniupnp)"  # headers only (USE_MINIUPNPC=OFF)
clone KhronosGroup/OpenXR-SDK "$dest/ext/OpenXR-SDK" "$(pin ext/OpenXR-SDK)"
clone hrydgard/nanosvg "$dest/ext/nanosvg" "$(pin ext/nanosvg)" memononen/nanosvg 66579081d84b613daa49a64f76357ce65925e13b
echo "checkout.sh: $dest is PPSSPP $ppsspp_commit with the submodules PPSSPPHeadless needs"
