#!/usr/bin/env bash
# Installs the test-time reference converter @playcanvas/splat-transform (npm) into a folder of
# the build tree, once. Never needed to build or run Vis4GS: the reference tests call this and
# are skipped (exit 77, with the reason) when node, npm or the registry is unavailable; under
# CI=true that is a failure.
#
# Usage: install-splat-transform.sh DIR     (prints the path of the splat-transform command)
# The version is pinned so that conventions do not change under the tests: 2.7.1 reads and
# writes SPZ through Niantic's own WebAssembly library (@adobe/spz) with RDF (PLY) axes on its
# side and RUB in the file, as the SPZ specification says. (Its GitHub master, 3.x, reads SPZ
# with its own JavaScript decoder and does not convert axes.)
set -uo pipefail
version="${VIS4GS_SPLAT_TRANSFORM_VERSION:-2.7.1}"
dir="${1:?usage: install-splat-transform.sh DIR}"
bin="$dir/node_modules/.bin/splat-transform"

skip() {
  echo "skipped: $1" >&2
  if [ "${CI:-}" = "true" ]; then
    echo "FAILED: CI=true and $1" >&2
    exit 1
  fi
  exit 77
}

for tool in node npm; do
  command -v "$tool" >/dev/null 2>&1 || skip "$tool is not installed (the SPZ reference check needs node >= 18 and npm)"
done
installed="$(cat "$dir/node_modules/@playcanvas/splat-transform/package.json" 2>/dev/null |
  sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p')"
if [ "$installed" != "$version" ]; then
  mkdir -p "$dir"
  # A lock keeps parallel tests from installing twice.
  exec 9>"$dir/.install-lock"
  flock 9
  installed="$(sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' \
    "$dir/node_modules/@playcanvas/splat-transform/package.json" 2>/dev/null)"
  if [ "$installed" != "$version" ]; then
    if ! timeout 300 npm install --prefix "$dir" --no-audit --no-fund --no-save --ignore-scripts \
      "@playcanvas/splat-transform@$version" >"$dir/npm-install.log" 2>&1; then
      tail -5 "$dir/npm-install.log" >&2
      skip "npm could not install @playcanvas/splat-transform@$version (no registry access?); see $dir/npm-install.log"
    fi
  fi
fi
[ -x "$bin" ] || skip "$bin is missing after the install"
echo "$bin"
