#!/usr/bin/env bash
# Install what dpend needs on a fresh Debian/Ubuntu machine. Idempotent: skips
# what is already there. Usage: scripts/setup.sh [--mpi] [--gpu]
#   --mpi  the MPI build's packages (docs/mpi.md)
#   --gpu  nvcc for the optional GPU library (docs/gpu.md, scripts/gpu/build_gpu.sh): the
#          system's if present, else NVIDIA's CUDA compiler wheels from PyPI into
#          build/cuda/ (about 350 MB; no GPU needed to compile)
set -euo pipefail
mpi=0; gpu=0
for a in "$@"; do
  case "$a" in
    --mpi) mpi=1 ;;
    --gpu) gpu=1 ;;
    *) echo "setup.sh: unknown option '$a' (--mpi, --gpu)" >&2; exit 2 ;;
  esac
done

packages=(gfortran liblapack-dev libblas-dev libhdf5-dev zlib1g-dev pkg-config gnuplot-nox hdf5-tools locales)
# Python: the recipes of docs/python.md and scripts/check_python.py (h5py, pandas, xarray).
packages+=(python3 python3-h5py python3-pandas python3-xarray)
# The Python package (pip install ., meson-python from PyPI) in a virtual environment.
packages+=(python3-venv)
# dpend explore's browser test (python/tests/test_explore.py, Playwright from PyPI drives
# Debian's chromium headless; its own browser download is not used) and its fonts.
packages+=(chromium fonts-dejavu-core)
if ((mpi)); then
  packages+=(libopenmpi-dev openmpi-bin libhdf5-openmpi-dev)
fi
if ((gpu)); then
  packages+=(g++)   # nvcc's host compiler
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

# A German locale (decimal comma) for CI's check that the figures do not depend on
# the user's locale (.ci/run); generated once.
if [[ -w /etc/locale.gen ]] && ! locale -a 2>/dev/null | grep -qi '^de_DE.utf8$'; then
  "${sudo[@]}" sed -i 's/^# *de_DE.UTF-8 UTF-8/de_DE.UTF-8 UTF-8/' /etc/locale.gen
  "${sudo[@]}" locale-gen > /dev/null 2>&1 || echo "setup.sh: locale-gen failed (de_DE.UTF-8)"
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

# --gpu: nvcc. The CUDA 13 wheels: the cu12 ones ship ptxas but no nvcc.
if ((gpu)); then
  cd "$(dirname "$0")/.."   # build/cuda/ of this checkout
  nvcc=$(command -v nvcc 2>/dev/null || true)
  [[ -z "$nvcc" && -x /usr/local/cuda/bin/nvcc ]] && nvcc=/usr/local/cuda/bin/nvcc
  [[ -z "$nvcc" && -x build/cuda/nvidia/cu13/bin/nvcc ]] && nvcc=build/cuda/nvidia/cu13/bin/nvcc
  if [[ -z "$nvcc" ]]; then
    echo "setup.sh: installing nvcc from PyPI into build/cuda/"
    wheels=(nvidia-cuda-nvcc nvidia-cuda-crt nvidia-nvvm nvidia-cuda-runtime nvidia-cuda-cccl)
    python3 -m pip install --quiet --target build/cuda "${wheels[@]}" 2>/dev/null ||
      python3 -m pip install --quiet --break-system-packages --target build/cuda "${wheels[@]}" ||
      { echo "setup.sh: nvcc did not install from PyPI (the GPU library needs the CUDA toolkit)" >&2
        exit 1; }
    nvcc=build/cuda/nvidia/cu13/bin/nvcc
  fi
  "$nvcc" --version >/dev/null 2>&1 || { echo "setup.sh: $nvcc does not run" >&2; exit 1; }
  echo "setup.sh: nvcc: $nvcc ($("$nvcc" --version | grep -o 'release [0-9.]*'))"
fi
