#!/usr/bin/env bash
# Installs the npm package @playcanvas/splat-transform (PlayCanvas's converter, a test-time
# reference for the compressed PLY / SOG / SPZ readers; never needed to build or run Vis4GS)
# into <build>/reference-tools/<version> and prints the path of its command line tool.
#
# Usage: install-splat-transform.sh <build dir> [version, default 3.7.0]
# Each version goes to its own folder, <build>/reference-tools/<version>. Two are used: 3.7.0
# for compressed PLY and SOG, and 2.7.1 for SPZ, because 2.7.1 reads and writes SPZ through
# Niantic's own WebAssembly library (@adobe/spz) with RUB axes in the file as the SPZ
# specification says, while 3.x decodes SPZ in JavaScript without converting axes.
# Idempotent: an existing install of the same version is reused without network access.
# Exit codes: 0 installed (path on stdout, last line), 77 node/npm or the registry unavailable
# (message on stderr), so tests calling it can skip; also under CI=true (VIS4GS_REQUIRE_NPM=1 makes it 1).
set -u
build="${1:?usage: install-splat-transform.sh <build dir> [version]}"
version="${2:-3.7.0}"
prefix="$build/reference-tools/$version"
cli="$prefix/node_modules/@playcanvas/splat-transform/bin/cli.mjs"

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

node_bin="$(command -v node || true)"
[ -n "$node_bin" ] || skip "node is not installed (splat-transform needs node >= 18)"
major="$("$node_bin" -e 'process.stdout.write(process.versions.node.split(".")[0])' 2>/dev/null || echo 0)"
[ "$major" -ge 18 ] 2>/dev/null || skip "node $major is too old for splat-transform (needs >= 18)"

installed="$("$node_bin" -e "try{process.stdout.write(require('$prefix/node_modules/@playcanvas/splat-transform/package.json').version)}catch(e){}" 2>/dev/null)"
if [ "$installed" != "$version" ] || [ ! -f "$cli" ]; then
  command -v npm >/dev/null || skip "npm is not installed"
  mkdir -p "$prefix"
  # A lock on the prefix so that parallel tests install once.
  exec 9>"$prefix/.install.lock"
  flock 9
  installed="$("$node_bin" -e "try{process.stdout.write(require('$prefix/node_modules/@playcanvas/splat-transform/package.json').version)}catch(e){}" 2>/dev/null)"
  if [ "$installed" != "$version" ] || [ ! -f "$cli" ]; then
    [ -f "$prefix/package.json" ] || echo '{"private": true}' >"$prefix/package.json"
    if ! timeout 600 npm install --prefix "$prefix" --no-audit --no-fund --loglevel=error \
      "@playcanvas/splat-transform@$version" >"$prefix/npm-install.log" 2>&1; then
      skip "npm could not install @playcanvas/splat-transform@$version (network?); see $prefix/npm-install.log"
    fi
  fi
fi
[ -f "$cli" ] || skip "the splat-transform package has no bin/cli.mjs at $cli"
echo "$cli"
