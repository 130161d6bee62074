#!/usr/bin/env bash
# The GPU measurements (docs/gpu.md), one script for a machine with an
# NVIDIA GPU and nvcc but possibly no Fortran compiler nor HDF5: run from the
# repository root with carry/dpend (a release build) and carry/lib/ (its ldd
# libraries and ld-linux-x86-64.so.2). Writes logs and small figures under $OUT
# (default out/gpu_check), the summary in $OUT/gpu_figures.txt; the maps go to
# $WORK (default /tmp/dpend_gpu_check). Every step logs and continues: the script
# never stops half-way, and finishes in well under 300 s on an H100.
#   the GPU, driver and nvcc; build the library (scripts/gpu/build_gpu.sh);
#   the library alone on the classic map (scripts/gpu/kernel_check.py, python3 + numpy);
#   the classic 1024^2 map (data/sweep_classic.nml) through dpend on the GPU, with
#   and without re-packing (end-to-end wall time and the library's kernel time),
#   on the CPU (16 threads), both at dt/2; sweep-compare GPU vs CPU, dt vs dt/2.
set -u
cd "$(dirname "$0")/../.."
OUT="${OUT:-out/gpu_check}"
WORK="${WORK:-/tmp/dpend_gpu_check}"
mkdir -p "$OUT" "$WORK"
rm -f "$WORK"/*.h5 "$WORK"/*.h5.part   # no stale maps from an earlier run
LOG="$OUT/gpu_check.log"
FIG="$OUT/gpu_figures.txt"
: >"$LOG"
: >"$FIG"
T0=$(date +%s.%N)
since() { awk -v a="$(date +%s.%N)" -v b="$1" 'BEGIN { printf "%.2f", a - b }'; }
log() { echo "[$(since "$T0") s] $*" | tee -a "$LOG"; }
fig() { echo "$*" | tee -a "$FIG" >>"$LOG"; }
THREADS="${THREADS:-16}"
CONFIG=data/sweep_classic.nml
LIBGPU="${LIBGPU:-$PWD/build/gpu/libdpend_gpu.so}"
# for a dry run without a GPU: SKIP_BUILD=1 LIBGPU=<scripts/gpu/build_gpu.sh --emulate's library>
# and CHECK_EXTRA="--n 16 --t-end 20" (appended to every map), KCHECK_N=16
read -r -a EXTRA <<<"${CHECK_EXTRA:-}"

fig "# dpend GPU check (scripts/gpu/gpu_device_check.sh), $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')"

# ---- the machine
log "nvidia-smi"
if command -v nvidia-smi >/dev/null 2>&1; then
  timeout 30 nvidia-smi >"$OUT/nvidia-smi.txt" 2>&1
  fig "gpu: $(timeout 30 nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | head -n 1)"
else
  fig "gpu: none (no nvidia-smi)"
fi
fig "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
NVCC="${NVCC:-$(command -v nvcc || true)}"
[[ -z "$NVCC" && -x /usr/local/cuda/bin/nvcc ]] && NVCC=/usr/local/cuda/bin/nvcc
if [[ -n "$NVCC" ]]; then
  "$NVCC" --version >"$OUT/nvcc.txt" 2>&1
  fig "nvcc: $(grep -m1 -o 'release [0-9.]*, V[0-9.]*' "$OUT/nvcc.txt")"
else
  fig "nvcc: none"
fi

# ---- build the library
log "build: scripts/gpu/build_gpu.sh"
t=$(date +%s.%N)
if [[ -n "${SKIP_BUILD:-}" ]]; then
  fig "build: skipped (SKIP_BUILD), library $LIBGPU"
elif [[ -n "$NVCC" ]] && { NVCC="$NVCC" timeout 120 scripts/gpu/build_gpu.sh --out "$LIBGPU" >>"$LOG" 2>&1 ||
     { log "build failed; again with -allow-unsupported-compiler";
       NVCC="$NVCC" NVCC_FLAGS=-allow-unsupported-compiler timeout 120 scripts/gpu/build_gpu.sh \
         --out "$LIBGPU" >>"$LOG" 2>&1; }; }; then
  fig "build: ok in $(since "$t") s ($LIBGPU)"
else
  fig "build: FAILED after $(since "$t") s (see gpu_check.log)"
fi
if [[ -f "$LIBGPU" ]]; then
  { ldd "$LIBGPU"; echo "glibc versions needed:"
    objdump -T "$LIBGPU" 2>/dev/null | grep -o 'GLIBC_[0-9.]*' | sort -uV | tr '\n' ' '; echo
    objdump -T "$LIBGPU" 2>/dev/null | grep -E 'GLIBC_2\.(3[7-9]|[4-9][0-9])'; } \
    >"$OUT/lib_deps.txt" 2>&1
  fig "library needs: $(sed -n '/glibc versions needed/{n;p}' "$OUT/lib_deps.txt")"
fi

# ---- dpend: the carried build through its loader; falls back to the system loader
# with the carried libraries less glibc's (should the carried glibc refuse the library)
DP=(carry/lib/ld-linux-x86-64.so.2 --library-path carry/lib carry/dpend)
if [[ ! -x carry/dpend ]]; then
  fig "dpend: no carry/dpend here; the dpend steps fail below"
fi
export DPEND_GPU_LIB="$LIBGPU" DPEND_GPU_TIMING=1
alt_mode() {
  mkdir -p "$WORK/lib"
  for f in carry/lib/*; do
    case "$(basename "$f")" in
      ld-linux*|libc.so*|libm.so*|libpthread*|libdl.so*|librt.so*|libresolv*) ;;
      *) ln -sf "$PWD/$f" "$WORK/lib/" ;;
    esac
  done
  DP=(env LD_LIBRARY_PATH="$WORK/lib" carry/dpend)
  log "dpend mode: system loader, LD_LIBRARY_PATH=$WORK/lib (carried libraries less glibc)"
}
"${DP[@]}" version >"$OUT/dpend_version.txt" 2>&1 || log "dpend version failed: $(head -c 300 "$OUT/dpend_version.txt")"
fig "dpend: $(head -n 1 "$OUT/dpend_version.txt")"

# sweep NAME ARGS...: one timed dpend sweep of the classic map into $WORK/NAME.h5
sweep() {
  local name=$1; shift
  local t rc
  if awk -v e="$(since "$T0")" 'BEGIN { exit !(e > 240) }'; then
    fig "$name: skipped (240 s used; the script keeps under 300 s)"
    return
  fi
  log "sweep $name: $*"
  t=$(date +%s.%N)
  timeout 100 "${DP[@]}" sweep --config "$CONFIG" --output "$WORK/$name.h5" --force --quiet "$@" \
    "${EXTRA[@]}" >"$OUT/$name.out" 2>"$OUT/$name.err"
  rc=$?
  local wall; wall=$(since "$t")
  if ((rc != 0)) && grep -q 'cannot be loaded' "$OUT/$name.err" && [[ "${DP[0]}" != env ]]; then
    log "$name: the library did not load under the carried loader: $(head -c 300 "$OUT/$name.err")"
    alt_mode
    t=$(date +%s.%N)
    timeout 100 "${DP[@]}" sweep --config "$CONFIG" --output "$WORK/$name.h5" --force --quiet "$@" \
      "${EXTRA[@]}" >"$OUT/$name.out" 2>"$OUT/$name.err"
    rc=$?
    wall=$(since "$t")
  fi
  local kern; kern=$(grep -o 'kernel time [0-9.]* s, [0-9]* launch' "$OUT/$name.err" | head -n 1)
  if ((rc == 0)); then
    fig "$name: wall $wall s${kern:+, $kern(es)} ($*) -- $(tail -n 1 "$OUT/$name.out")"
  else
    fig "$name: FAILED rc=$rc after $wall s ($*): $(head -c 300 "$OUT/$name.err")"
  fi
}

# ---- the library alone (python3 + numpy; no dpend)
log "kernel_check.py"
if python3 -c 'import numpy' 2>/dev/null && [[ -f "$LIBGPU" ]]; then
  timeout 120 python3 scripts/gpu/kernel_check.py "$LIBGPU" --n "${KCHECK_N:-1024}" --repack 2048 0 --json "$OUT/kernel_check.json" \
    >"$OUT/kernel_check.txt" 2>&1 || log "kernel_check.py failed: $(tail -c 300 "$OUT/kernel_check.txt")"
  while read -r line; do fig "kernel_check: $line"; done <"$OUT/kernel_check.txt"
else
  fig "kernel_check: skipped (no numpy or no library)"
fi

# ---- the classic map
sweep gpu_repack2048 --device gpu --block 1048576 --gpu-repack 2048
sweep gpu_norepack --device gpu --block 1048576 --gpu-repack 0
sweep gpu_repack512 --device gpu --block 1048576 --gpu-repack 512
sweep gpu_repack8192 --device gpu --block 1048576 --gpu-repack 8192
sweep cpu --device cpu --threads "$THREADS"
sweep gpu_half --device gpu --block 1048576 --gpu-repack 2048 --dt 0.0025
sweep cpu_half --device cpu --threads "$THREADS" --dt 0.0025

# ---- refusals and auto (small, fast)
log "refusals"
"${DP[@]}" sweep --n 8 --device gpu --lyapunov --output "$WORK/r.h5" --force >"$OUT/refusal.txt" 2>&1
fig "refusal (--lyapunov on gpu): rc=$? $(head -n 1 "$OUT/refusal.txt")"
"${DP[@]}" sweep --n 8 --device auto --output "$WORK/auto.h5" --force >"$OUT/auto.txt" 2>&1
fig "auto: rc=$? $(grep -m1 'GPU\|CPU' "$OUT/auto.txt")"

# compare A B: dpend sweep-compare, the whole report in $OUT, its key lines in the summary
compare() {
  local a=$1 b=$2
  if [[ -f "$WORK/$a.h5" && -f "$WORK/$b.h5" ]]; then
    timeout 60 "${DP[@]}" sweep-compare "$WORK/$a.h5" "$WORK/$b.h5" >"$OUT/compare_${a}_vs_$b.txt" 2>&1
    fig "compare $a vs $b: $(grep -E '^(pixels_changed|changed_fraction|changed_fraction_of_flipping|pixels_changed_no_flip_in_a):' \
      "$OUT/compare_${a}_vs_$b.txt" | tr '\n' ';' | tr -s ' ')"
  else
    fig "compare $a vs $b: skipped (a map is missing)"
  fi
}
compare gpu_repack2048 cpu
compare cpu cpu_half
compare gpu_repack2048 gpu_half
compare gpu_repack2048 gpu_norepack
compare gpu_half cpu_half

# re-packing must not change a bit: the GPU maps side by side (python3 + h5py)
if python3 -c 'import h5py' 2>/dev/null; then
  python3 - "$WORK" >"$OUT/repack_identity.txt" 2>&1 <<'PY'
import sys, h5py, numpy as np
w = sys.argv[1]
names = ["gpu_repack2048", "gpu_norepack", "gpu_repack512", "gpu_repack8192"]
ref = None
for n in names:
    try:
        with h5py.File(f"{w}/{n}.h5", "r") as f:
            d = {k: f["/sweep/" + k][()] for k in ("t_flip", "t_stop", "status", "energy_error")}
            dev = f["/sweep"].attrs.get("device")
    except Exception as e:
        print(n, "unreadable:", e); continue
    if ref is None:
        ref = d; print(n, "reference; device attribute:", dev); continue
    same = all(np.array_equal(ref[k], d[k], equal_nan=True) for k in ref)
    print(n, "bit-identical to", names[0], ":", same)
PY
  while read -r line; do fig "repack identity: $line"; done <"$OUT/repack_identity.txt"
  if [[ -f "$WORK/cpu.h5" && -f "$LIBGPU" ]]; then
    timeout 60 python3 scripts/gpu/kernel_check.py "$LIBGPU" --n "${KCHECK_N:-1024}" --repack 2048 --compare "$WORK/cpu.h5" \
      >"$OUT/kernel_vs_cpu.txt" 2>&1
    fig "kernel_check vs cpu map: $(tail -n 1 "$OUT/kernel_vs_cpu.txt")"
  fi
fi
fig "total: $(since "$T0") s"
log "done: $FIG"
exit 0
