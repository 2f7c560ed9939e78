#!/usr/bin/env bash
# Installs mkkellogg's GaussianSplats3D (npm @mkkellogg/gaussian-splats-3d, with its peer
# dependency three) into a folder of the build tree, once, with our driver make-ksplat.mjs
# next to it, so that the .ksplat reference check can write .ksplat files with the format's
# own writer under node. Never needed to build or run Vis4GS: exit 77 with the reason when
# node, npm or the registry is unavailable (also under CI=true; VIS4GS_REQUIRE_NPM=1 fails).
#
# Usage: install-gaussian-splats-3d.sh DIR     (prints the path of the copied driver)
# Versions are pinned: 0.4.7 writes SplatBuffer version 0.1.
set -uo pipefail
version="${VIS4GS_GAUSSIAN_SPLATS_3D_VERSION:-0.4.7}"
three="${VIS4GS_THREE_VERSION:-0.187.0}"
dir="${1:?usage: install-gaussian-splats-3d.sh DIR}"
package="$dir/node_modules/@mkkellogg/gaussian-splats-3d/package.json"

skip() {
  # Skipped, also under CI=true: the npm registry is outside the project's control, and a
  # reference tool that cannot be fetched says nothing about our code. VIS4GS_REQUIRE_NPM=1
  # makes it a failure (for machines where the registry must be reachable).
  echo "skipped: $*" >&2
  if [ "${VIS4GS_REQUIRE_NPM:-0}" = "1" ]; then
    echo "FAILED: VIS4GS_REQUIRE_NPM=1 and $*" >&2
    exit 1
  fi
  exit 77
}

for tool in node npm; do
  command -v "$tool" >/dev/null 2>&1 || skip "$tool is not installed (the .ksplat reference check needs node >= 18 and npm)"
done
installed() { sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' "$package" 2>/dev/null; }
if [ "$(installed)" != "$version" ]; then
  mkdir -p "$dir"
  exec 9>"$dir/.install-lock" # parallel tests install once
  flock 9
  if [ "$(installed)" != "$version" ] &&
    ! timeout 300 npm install --prefix "$dir" --no-audit --no-fund --no-save --ignore-scripts \
      "@mkkellogg/gaussian-splats-3d@$version" "three@$three" >"$dir/npm-install.log" 2>&1; then
    tail -5 "$dir/npm-install.log" >&2
    skip "npm could not install @mkkellogg/gaussian-splats-3d@$version (no registry access?); see $dir/npm-install.log"
  fi
fi
[ "$(installed)" = "$version" ] || skip "$package is missing after the install"
# Node resolves the package from the driver's folder, so the driver lives next to node_modules.
cp "$(dirname "$0")/make-ksplat.mjs" "$dir/make-ksplat.mjs" || skip "cannot copy make-ksplat.mjs to $dir"
echo "$dir/make-ksplat.mjs"
