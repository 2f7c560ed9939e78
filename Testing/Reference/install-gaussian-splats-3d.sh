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
source "$(dirname "$0")/npm-tool.sh" || exit 1
version="${VIS4GS_GAUSSIAN_SPLATS_3D_VERSION:-0.4.7}"
three="${VIS4GS_THREE_VERSION:-0.187.0}"
dir="${1:?usage: install-gaussian-splats-3d.sh DIR}"
package="$dir/node_modules/@mkkellogg/gaussian-splats-3d/package.json"

require_node_npm "the .ksplat reference check"
npm_install_once "$dir" "$package" "$version" --no-save --ignore-scripts \
  "@mkkellogg/gaussian-splats-3d@$version" "three@$three"
# Node resolves the package from the driver's folder, so the driver lives next to node_modules.
cp "$(dirname "$0")/make-ksplat.mjs" "$dir/make-ksplat.mjs" || skip "cannot copy make-ksplat.mjs to $dir"
echo "$dir/make-ksplat.mjs"
