#!/usr/bin/env bash
# Installs the Khronos glTF validator (npm gltf-validator, the official validator compiled to
# JavaScript) into <build>/reference-tools/gltf-validator-<version>, once, and prints the path
# of its package folder. A test-time reference for the glTF writer (issue 34); never needed to
# build or run Vis4GS. Exit 77 with the reason when node, npm or the registry is unavailable
# (also under CI=true; VIS4GS_REQUIRE_NPM=1 makes it a failure), as install-splat-transform.sh.
#
# Usage: install-gltf-validator.sh <build dir> [version, default 2.0.0-dev.3.10]
set -uo pipefail
build="${1:?usage: install-gltf-validator.sh <build dir> [version]}"
version="${2:-2.0.0-dev.3.10}"
prefix="$build/reference-tools/gltf-validator-$version"
package="$prefix/node_modules/gltf-validator"

skip() {
  echo "skipped: $*" >&2
  if [ "${VIS4GS_REQUIRE_NPM:-0}" = "1" ]; then
    echo "FAILED: VIS4GS_REQUIRE_NPM=1 and $*" >&2
    exit 1
  fi
  exit 77
}

for tool in node npm; do
  command -v "$tool" >/dev/null 2>&1 || skip "$tool is not installed (the glTF validator check needs node and npm)"
done
installed() { sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' "$package/package.json" 2>/dev/null; }
if [ "$(installed)" != "$version" ]; then
  mkdir -p "$prefix"
  exec 9>"$prefix/.install-lock" # parallel tests install once
  flock 9
  [ -f "$prefix/package.json" ] || echo '{"private": true}' >"$prefix/package.json"
  if [ "$(installed)" != "$version" ] &&
    ! timeout 300 npm install --prefix "$prefix" --no-audit --no-fund --loglevel=error \
      "gltf-validator@$version" >"$prefix/npm-install.log" 2>&1; then
    tail -5 "$prefix/npm-install.log" >&2
    skip "npm could not install gltf-validator@$version (no registry access?); see $prefix/npm-install.log"
  fi
fi
[ "$(installed)" = "$version" ] || skip "$package is missing after the install"
echo "$package"
