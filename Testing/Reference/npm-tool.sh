# Sourced by the install-*.sh scripts of the test-time reference tools from npm (never needed to
# build or run Vis4GS): one way to skip, to check node and npm, and to install a pinned package
# version once into a folder of the build tree.

# Skipped (exit 77), also under CI=true: the npm registry is outside the project's control, and
# a reference tool that cannot be fetched says nothing about our code. VIS4GS_REQUIRE_NPM=1
# makes it a failure (for machines where the registry must be reachable).
skip() {
  echo "skipped: $*" >&2
  if [ "${VIS4GS_REQUIRE_NPM:-0}" = "1" ]; then
    echo "FAILED: VIS4GS_REQUIRE_NPM=1 and $*" >&2
    exit 1
  fi
  exit 77
}

# require_node_npm WHAT: node >= 18 and npm on PATH, or skip naming WHAT needs them.
require_node_npm() {
  local tool major
  for tool in node npm; do
    command -v "$tool" >/dev/null 2>&1 || skip "$tool is not installed ($1 needs node >= 18 and npm)"
  done
  major="$(node -e 'process.stdout.write(process.versions.node.split(".")[0])' 2>/dev/null || echo 0)"
  [ "$major" -ge 18 ] 2>/dev/null || skip "node $major is too old ($1 needs node >= 18)"
}

# The "version" of a package.json, empty when there is none.
package_version() {
  sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' "$1" 2>/dev/null | head -n 1
}

# npm_install_once PREFIX PACKAGE_JSON VERSION SPEC... [-- NPM_FLAGS...]: installs SPEC (one or
# more name@version) into PREFIX once; a lock on PREFIX so that parallel tests install once;
# skips naming the log when npm fails or the package is still missing. "Installed" is a marker
# written after npm has finished, never the package's own package.json: npm extracts packages one
# by one, so a test that saw the main package could start before its dependencies (e.g. three
# for GaussianSplats3D) were there.
npm_install_once() {
  local prefix="$1" package="$2" version="$3"
  shift 3
  local marker="$prefix/.installed" want="$version $*"
  if [ "$(cat "$marker" 2>/dev/null)" != "$want" ]; then
    mkdir -p "$prefix" || skip "cannot create $prefix"
    exec 9>"$prefix/.install-lock"
    flock 9
    if [ "$(cat "$marker" 2>/dev/null)" != "$want" ]; then
      [ -f "$prefix/package.json" ] || echo '{"private": true}' >"$prefix/package.json"
      if ! timeout 600 npm install --prefix "$prefix" --no-audit --no-fund --loglevel=error "$@" \
        >"$prefix/npm-install.log" 2>&1; then
        tail -5 "$prefix/npm-install.log" >&2
        skip "npm could not install $* (no registry access?); see $prefix/npm-install.log"
      fi
      [ "$(package_version "$package")" = "$version" ] || skip "$package is missing after the install"
      printf '%s' "$want" >"$marker.tmp" && mv -f "$marker.tmp" "$marker" ||
        skip "cannot write $marker"
    fi
    exec 9>&-
  fi
  [ "$(package_version "$package")" = "$version" ] || skip "$package is missing after the install"
}
