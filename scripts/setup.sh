#!/usr/bin/env bash
# Install what dpend needs on a fresh Debian/Ubuntu machine. Idempotent: skips
# what is already there. Usage: scripts/setup.sh [--mpi]
set -euo pipefail

packages=(gfortran liblapack-dev libblas-dev libhdf5-dev pkg-config gnuplot-nox hdf5-tools)
# Python: the recipes of docs/python.md and scripts/check_python.py (h5py, pandas, xarray).
packages+=(python3 python3-h5py python3-pandas python3-xarray)
if [[ "${1:-}" == "--mpi" ]]; then
  packages+=(libopenmpi-dev openmpi-bin libhdf5-openmpi-dev)
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
    echo "setup.sh: not root and no sudo; install as root: ${packages[*]}" >&2; exit 1
  fi
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup.sh: installing ${missing[*]}"
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
else
  echo "setup.sh: Debian packages already installed"
fi

# Debian's libhdf5-openmpi-dev (setup.sh --mpi) takes over the hdf5.pc alternative,
# which fpm's hdf5 metapackage reads: pin the serial HDF5 for the default build (the
# MPI variant asks for hdf5-openmpi by name).
serial_pc=/usr/lib/x86_64-linux-gnu/pkgconfig/hdf5-serial.pc
if [[ -e $serial_pc ]] && command -v update-alternatives >/dev/null 2>&1 &&
   [[ "$(readlink -f /usr/lib/x86_64-linux-gnu/pkgconfig/hdf5.pc)" != "$(readlink -f $serial_pc)" ]]; then
  echo "setup.sh: pinning pkg-config hdf5 to the serial HDF5"
  "${sudo[@]}" update-alternatives --set hdf5.pc "$serial_pc" >/dev/null
fi

if ! command -v fpm >/dev/null 2>&1; then
  echo "setup.sh: installing fpm from PyPI"
  if ! python3 -m pip --version >/dev/null 2>&1; then
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq python3-pip >/dev/null
  fi
  python3 -m pip install --quiet fpm 2>/dev/null || python3 -m pip install --quiet \
    --break-system-packages fpm
  command -v pyenv >/dev/null 2>&1 && pyenv rehash
  hash -r
fi
command -v fpm >/dev/null 2>&1 || { echo "setup.sh: fpm not on PATH after install" >&2; exit 1; }
echo "setup.sh: ready: $(gfortran --version | head -n1); fpm $(fpm --version | head -n1 | awk '{print $2}')"
