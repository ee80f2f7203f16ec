#!/usr/bin/env bash
# Installs the Debian 12 packages rbcflow needs (run as root). Idempotent: installs only what
# is missing, and touches apt's lists only when something is.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libeigen3-dev libfftw3-dev libgmsh-dev gmsh libvtk9-dev libcgal-dev libhdf5-dev libboost-dev
  libgtest-dev libbenchmark-dev libtoml11-dev
  xvfb xauth
  clang libclang-rt-14-dev
  pybind11-dev python3-dev python3-numpy python3-matplotlib
  libopenmpi-dev openmpi-bin libfftw3-mpi-dev libhdf5-openmpi-dev

)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run this script as root (or: sudo apt-get install ${missing[*]})" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
