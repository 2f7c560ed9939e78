#!/usr/bin/env bash
# Installs the Khronos glTF validator (npm gltf-validator, the official validator compiled to
# JavaScript) into <build>/reference-tools/gltf-validator-<version>, once, and prints the path
# of its package folder. A test-time reference for the glTF writer (issue 34); never needed to
# build or run Vis4GS. Exit 77 with the reason when node, npm or the registry is unavailable
# (also under CI=true; VIS4GS_REQUIRE_NPM=1 makes it a failure): npm-tool.sh.
#
# Usage: install-gltf-validator.sh <build dir> [version, default 2.0.0-dev.3.10]
set -uo pipefail
source "$(dirname "$0")/npm-tool.sh" || exit 1
build="${1:?usage: install-gltf-validator.sh <build dir> [version]}"
version="${2:-2.0.0-dev.3.10}"
prefix="$build/reference-tools/gltf-validator-$version"
package="$prefix/node_modules/gltf-validator"

require_node_npm "the glTF validator check"
npm_install_once "$prefix" "$package/package.json" "$version" "gltf-validator@$version"
echo "$package"
