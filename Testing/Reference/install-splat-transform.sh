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
source "$(dirname "$0")/npm-tool.sh" || exit 1
build="${1:?usage: install-splat-transform.sh <build dir> [version]}"
version="${2:-3.7.0}"
prefix="$build/reference-tools/$version"
cli="$prefix/node_modules/@playcanvas/splat-transform/bin/cli.mjs"

require_node_npm "splat-transform"
npm_install_once "$prefix" "$prefix/node_modules/@playcanvas/splat-transform/package.json" \
  "$version" "@playcanvas/splat-transform@$version"
[ -f "$cli" ] || skip "the splat-transform package has no bin/cli.mjs at $cli"
echo "$cli"
