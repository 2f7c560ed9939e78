#!/usr/bin/env bash
# Makes the SwiftShader Vulkan driver that Debian's chromium package ships available and prints
# the path of its ICD file (for VK_ICD_FILENAMES). Only CompareFloaterFilter.py needs it:
# splat-transform's --filter-floaters runs on WebGPU (Dawn), and on a machine without a GPU
# bookworm's own software Vulkan (Mesa lavapipe) lacks a feature Dawn needs, while SwiftShader
# works (slowly). Never needed to build or run Vis4GS, so Scripts/setup-deps.sh does not install
# chromium.
#
# Usage: install-swiftshader.sh
# Installs chromium with apt-get when the driver is missing and the user is root (or has sudo
# without a password). Exit codes: 0 found (path on stdout, last line), 77 not available and
# cannot be installed here (message on stderr), so callers can skip.
set -u
icd=/usr/lib/chromium/vk_swiftshader_icd.json
if [ ! -f "$icd" ]; then
  if [ "$(id -u)" = 0 ]; then
    apt_get=(apt-get)
  elif sudo -n true 2>/dev/null; then
    apt_get=(sudo -n apt-get)
  else
    echo "skipped: $icd is missing; install Debian's chromium package (apt-get install chromium)" >&2
    exit 77
  fi
  log="${TMPDIR:-/tmp}/install-swiftshader-$$.log"
  if ! DEBIAN_FRONTEND=noninteractive timeout 1200 "${apt_get[@]}" install -y chromium >"$log" 2>&1; then
    tail -5 "$log" >&2
    echo "skipped: apt-get could not install chromium (no package archive?); see $log" >&2
    exit 77
  fi
  [ -f "$icd" ] || { echo "skipped: chromium is installed but has no $icd" >&2; exit 77; }
fi
echo "$icd"
