#!/usr/bin/env bash
# Measure how the sweep scales over MPI ranks and OpenMP threads on this machine
# (docs/mpi.md): the same map with dpend sweep (1 and 2 threads) and dpend-mpi
# (1 rank x 1 thread, 2 ranks x 1 thread, 1 rank x 2 threads), best of REPEAT runs
# each, then the per-rank load balance and the per-block costs, and the predicted
# behaviour on more ranks (scripts/mpi/mpi_scaling.py).
#   scripts/mpi/mpi_scaling.sh [OUTDIR]        (default out/mpi_scaling; REPEAT=2)
# Map: MAP="..." overrides the options (default: classic map, 512 x 512, t_end 100).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
. scripts/flags.sh
out="${1:-out/mpi_scaling}"
case $out in /*) ;; *) out="$root/$out" ;; esac   # absolute: no name read as an option
repeat="${REPEAT:-2}"
read -r -a map <<<"${MAP:---config data/sweep_classic.nml --n 512 --t-end 100 --block 4096 --stats}"
mkdir -p -- "$out"
fpm build --profile release --flag "$RELEASE_FLAGS" >/dev/null 2>&1
serial=$(fpm run dpend --profile release --flag "$RELEASE_FLAGS" --runner echo 2>/dev/null |
  tail -n 1)
mpibin=$(scripts/mpi/build_mpi.sh | tail -n 1)
asroot=()
[[ $(id -u) -eq 0 ]] && asroot=(--allow-run-as-root)

echo "map: ${map[*]}"
echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores"
# run LABEL RANKS THREADS: best wall time of REPEAT runs; keeps the best run's output
run() {
  local label=$1 np=$2 nt=$3 best="" k wall load
  for ((k = 1; k <= repeat; k++)); do
    load=$(cut -d' ' -f1 /proc/loadavg)
    if [[ $np == 0 ]]; then
      OMP_NUM_THREADS=$nt "$serial" sweep "${map[@]}" --threads "$nt" --quiet --force \
        --output "$out/$label.h5" >"$out/$label.try"
      wall=$(sed -n 's/.* in \([0-9.]*\) s,.*/\1/p' "$out/$label.try")
    else
      OMP_NUM_THREADS=$nt mpirun "${asroot[@]}" --bind-to none --oversubscribe -np "$np" \
        "$mpibin" sweep "${map[@]}" --quiet --force --output "$out/$label.h5" \
        --block-times "$out/$label.blocks.try" >"$out/$label.try"
      wall=$(sed -n 's/^wall_s: \([0-9.]*\).*/\1/p' "$out/$label.try")
    fi
    echo "  $label try $k: $wall s (load average before: $load)"
    if [[ -z $best ]] || awk -v a="$wall" -v b="$best" 'BEGIN { exit !(a < b) }'; then
      best=$wall
      mv "$out/$label.try" "$out/$label.txt"
      [[ -e "$out/$label.blocks.try" ]] && mv "$out/$label.blocks.try" "$out/$label.blocks.txt"
    fi
    rm -f "$out/$label.try" "$out/$label.blocks.try"
  done
  echo "$label $np $nt $best" >>"$out/walls.txt"
}
rm -f -- "$out/walls.txt"
run serial_1t 0 1
run mpi_1r_1t 1 1
run mpi_2r_1t 2 1
run mpi_1r_2t 1 2
run serial_2t 0 2
for f in mpi_1r_2t mpi_2r_1t serial_2t; do
  h5diff "$out/serial_1t.h5" "$out/$f.h5" >/dev/null && echo "$f.h5: identical to serial_1t.h5"
done
echo
echo "| run | ranks x threads | wall [s] | speed-up vs 1 x 1 |"
echo "| --- | --- | --- | --- |"
base=$(awk '$1 == "mpi_1r_1t" { print $4 }' "$out/walls.txt")
awk -v b="$base" '{ how = ($2 == 0 ? "serial, " $3 " thread(s)" : $2 " x " $3)
  printf "| %s | %s | %.2f | %.2f |\n", $1, how, $4, b / $4 }' \
  "$out/walls.txt"
for f in mpi_1r_1t mpi_2r_1t mpi_1r_2t; do
  echo
  echo "== $f"
  sed -n '/^rank /,$p' "$out/$f.txt"
done
echo
python3 scripts/mpi/mpi_scaling.py "$out/mpi_1r_1t.blocks.txt"
