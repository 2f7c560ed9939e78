#!/usr/bin/env bash
# Installs the Debian bookworm packages Vis4GS needs, and only those that are missing.
# Run as root (as on the project's machines) or through sudo; a non-root user runs
#   sudo apt-get install $(bash Scripts/setup-deps.sh --list)
# With --paraview first, the ParaView plugin's packages instead (see below).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvtk9-dev libvtk9-qt-dev python3-vtk9 qtbase5-dev
  libeigen3-dev libhdf5-dev nlohmann-json3-dev libgtest-dev
  libpng-dev libjpeg-dev
  zlib1g-dev libzstd-dev
  libwebp-dev libzip-dev
  openmpi-bin libopenmpi-dev
  xvfb xauth clang clang-format libclang-rt-14-dev
  python3-numpy python3-h5py python3-pytest python3-torch python3-pip
)

# --paraview: what the ParaView plugin's own build needs instead (Plugins/ParaView): Debian's
# ParaView 5.11 and the Qt parts its CMake package asks for. pvbatch's Python modules
# (python3-paraview) conflict with python3-vtk9 and are unpacked by the tests instead
# (Scripts/unpack-paraview-python.sh).
if [ "${1:-}" = "--paraview" ]; then
  shift
  packages=(paraview paraview-dev libqt5svg5-dev qtxmlpatterns5-dev-tools libhdf5-openmpi-dev
    xvfb xauth)
fi

if [ "${1:-}" = "--list" ]; then
  echo "${packages[@]}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "vis4gs setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
