#!/usr/bin/env bash
# Unpacks Debian's python3-paraview (pvbatch's Python modules) into a folder, without
# installing it: it cannot be installed beside python3-vtk9, which the rest of Vis4GS needs
# (both ship /usr/lib/python3/dist-packages/vtkmodules). The ParaView plugin's tests run
#   PYTHONPATH=DIR/usr/lib/python3/dist-packages pvbatch ...
# Usage: Scripts/unpack-paraview-python.sh DIR
# Exits 77 (CTest's skip code) when the package cannot be downloaded (no network), unless
# CI=true, where that is an error.
set -euo pipefail
dir="${1:?usage: $0 DIR}"
if [ -f "$dir/usr/lib/python3/dist-packages/paraview/simple.py" ]; then
  echo "python3-paraview already unpacked in $dir"
  exit 0
fi
version="$(dpkg-query -W -f='${Version}' paraview 2>/dev/null || true)"
if [ -z "$version" ]; then
  echo "FAILED: Debian's paraview is not installed (bash Scripts/setup-deps.sh --paraview)"
  exit 1
fi
mkdir -p "$dir"
download="$(mktemp -d)"
trap 'rm -rf "$download"' EXIT
# The same version as the installed paraview: its modules must match pvbatch's libraries.
if ! (cd "$download" && apt-get download -q "python3-paraview=$version" >/dev/null 2>&1); then
  message="python3-paraview $version could not be downloaded (apt-get download; no network?)"
  if [ "${CI:-}" = "true" ]; then
    echo "FAILED: $message"
    exit 1
  fi
  echo "$message: skipped"
  exit 77
fi
dpkg-deb -x "$download"/python3-paraview_*.deb "$dir"
echo "python3-paraview $version unpacked in $dir"
