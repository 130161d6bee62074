#!/usr/bin/env bash
# Build the optional GPU library of `dpend sweep --device gpu` (docs/gpu.md):
# src/gpu/dpend_sweep_kernel.cu -> build/gpu/libdpend_gpu.so, with nvcc, fp64, the CUDA
# runtime linked statically (at run time only the driver's libcuda.so.1 is needed).
# dpend loads it at run time: $DPEND_GPU_LIB, else libdpend_gpu.so next to the
# executable, else build/gpu/libdpend_gpu.so under the current directory.
#
# usage: scripts/gpu/build_gpu.sh [--out FILE] [--arch sm_NN] [--emulate] [--check]
#   --out FILE   the library to write (default build/gpu/libdpend_gpu.so)
#   --arch A     the GPU architecture of the machine code (default sm_90: H100, H200);
#                PTX of the same architecture is embedded too, for newer GPUs
#   --emulate    no CUDA: build src/gpu/dpend_gpu_emulate.c with cc instead, a stand-in
#                that runs the same per-trajectory code on the host (tests, no GPU)
#   --check      compile only (no library written): the CI's nvcc check
# $NVCC_FLAGS: more nvcc options (e.g. -allow-unsupported-compiler).
# nvcc: $NVCC, else nvcc on PATH, else /usr/local/cuda/bin/nvcc, else the PyPI
# wheels of scripts/setup.sh --gpu (build/cuda/).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=build/gpu/libdpend_gpu.so
arch=sm_90
emulate=0
check=0
while (($#)); do
  case "$1" in
    --out) out="${2:?--out needs a file}"; shift 2 ;;
    --arch)
      arch="${2:?--arch needs a value}"; shift 2
      [[ "$arch" =~ ^sm_[0-9]{2,3}[a-z]?$ ]] || {
        echo "build_gpu.sh: invalid --arch '$arch' (e.g. sm_80, sm_90)" >&2; exit 2; } ;;
    --emulate) emulate=1; shift ;;
    --check) check=1; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | grep '^#' | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "build_gpu.sh: unknown argument '$1' (--help lists them)" >&2; exit 2 ;;
  esac
done
mkdir -p "$(dirname "$out")"

if ((emulate)); then
  cc="${CC:-cc}"
  "$cc" -O2 -fPIC -shared -Wall -Wextra -DDPEND_GPU_EMULATE src/gpu/dpend_gpu_emulate.c \
    -o "$out" -lm
  echo "build_gpu.sh: wrote $out (host emulation, no GPU)"
  exit 0
fi

nvcc="${NVCC:-}"
if [[ -z "$nvcc" ]]; then
  for c in "$(command -v nvcc 2>/dev/null || true)" /usr/local/cuda/bin/nvcc \
           build/cuda/nvidia/cu13/bin/nvcc; do
    if [[ -n "$c" && -x "$c" ]]; then nvcc="$c"; break; fi
  done
fi
if [[ -z "$nvcc" ]]; then
  echo "build_gpu.sh: no nvcc (install the CUDA toolkit, or scripts/setup.sh --gpu; \$NVCC names one)" >&2
  exit 1
fi
cc_arch="${arch#sm_}"
flags=(-O3 -std=c++17 -Xcompiler -fPIC -shared
       -gencode "arch=compute_${cc_arch},code=sm_${cc_arch}"
       -gencode "arch=compute_${cc_arch},code=compute_${cc_arch}"
       -cudart static -Xcompiler -static-libstdc++ -Xcompiler -static-libgcc)
read -r -a extra <<<"${NVCC_FLAGS:-}"
flags+=("${extra[@]}")
if ((check)); then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  "$nvcc" "${flags[@]}" src/gpu/dpend_sweep_kernel.cu -o "$tmp/libdpend_gpu.so"
  echo "build_gpu.sh: src/gpu/dpend_sweep_kernel.cu compiles ($("$nvcc" --version | tail -n 2 | head -n 1))"
  exit 0
fi
"$nvcc" "${flags[@]}" src/gpu/dpend_sweep_kernel.cu -o "$out"
echo "build_gpu.sh: wrote $out ($nvcc, $arch)"
