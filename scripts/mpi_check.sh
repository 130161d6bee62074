#!/usr/bin/env bash
# Check the MPI variant against the serial sweep (CI, after scripts/setup.sh --mpi):
#  1. small sweeps (a grid with the Lyapunov exponent and step counts, a list) with
#     `dpend-mpi` on 2 ranks and with `dpend sweep`: identical in content;
#  2. kill -9 of mpirun twice in the middle of a run, then a rerun: identical to an
#     uninterrupted run; an MPI run killed and finished by the serial dpend sweep:
#     identical; a serial run killed is refused by dpend-mpi (its working file
#     carries checksums, which parallel HDF5 cannot write block by block);
#  3. a map of fewer blocks than ranks says so on stderr, with the --block that
#     would share it; a map of enough blocks says nothing.
# "Identical in content": h5diff finds no difference, every dataset is equal bit for
# bit (h5dump -b) and the attributes are equal (h5dump -A). Prints what differs and
# exits 1 on any difference. Usage: scripts/mpi_check.sh [WORKDIR]   (default out/mpi_check)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
. scripts/flags.sh
dir="${1:-out/mpi_check}"
case $dir in /*) ;; *) dir="$root/$dir" ;; esac   # absolute: no name read as an option
mkdir -p -- "$dir"
rm -f -- "$dir"/*.h5 "$dir"/*.h5.part "$dir"/*.bin "$dir"/*.txt "$dir"/*.err   # this script's files only

echo "== mpi_check: build (release): dpend and dpend-mpi"
if ! log=$(fpm build --profile release --flag "$RELEASE_FLAGS" 2>&1); then
  printf '%s\n' "$log" >&2
  exit 1
fi
serial=$(fpm run dpend --profile release --flag "$RELEASE_FLAGS" --runner echo 2>/dev/null |
  tail -n 1)
case "$serial" in /*) ;; *) serial="$root/$serial" ;; esac
mpibin=$(scripts/mpi/build_mpi.sh | tail -n 1)
# its OpenMP regions too share no static string length (docs/architecture.md, "Threads")
bash scripts/check_threads.sh "$mpibin"

mpiflags=(--oversubscribe -np 2)
[[ $(id -u) -eq 0 ]] && mpiflags=(--allow-run-as-root "${mpiflags[@]}")
export OMP_NUM_THREADS=1
mpi() { mpirun "${mpiflags[@]}" "$mpibin" sweep --quiet "$@"; }
ser() { "$serial" sweep --quiet --threads 2 "$@"; }

failures=0
# same_content A B: the two files hold the same datasets, bits and attributes
same_content() {
  local a=$1 b=$2 ok=1 ds
  if ! h5diff -r "$a" "$b" >"$dir/h5diff.txt" 2>&1; then
    echo "DIFFERENT: h5diff $a $b:"
    # leave out the objects that h5diff found equal
    awk '{ l[NR] = $0 } END { for (i = 1; i <= NR; i++) { if (l[i] == "0 differences found")
      continue; if (l[i + 1] == "0 differences found") continue; print l[i] } }' \
      "$dir/h5diff.txt" | head -n 40
    ok=0
  fi
  while read -r ds; do
    h5dump -d "$ds" -b LE -o "$dir/a.bin" "$a" >/dev/null
    h5dump -d "$ds" -b LE -o "$dir/b.bin" "$b" >/dev/null 2>&1 || : >"$dir/b.bin"
    if ! cmp -s "$dir/a.bin" "$dir/b.bin"; then echo "DIFFERENT: bits of $ds"; ok=0; fi
  done < <(h5ls -r "$a" | awk '$2 == "Dataset" {print $1}')
  if ! diff <(h5dump -A "$a" | tail -n +2) <(h5dump -A "$b" | tail -n +2) \
    >"$dir/attrs.txt"; then
    echo "DIFFERENT: attributes of $a and $b:"; head -n 40 "$dir/attrs.txt"; ok=0
  fi
  if ((ok)); then echo "identical: $a $b ($(h5ls -r "$a" | grep -c Dataset) datasets)"
  else failures=$((failures + 1)); fi
}

t0=$SECONDS
echo "== 1. 2 ranks vs serial"
grid=(--config data/sweep_velocities.nml --n1 96 --n2 64 --t-end 20 --block 320)
mpi "${grid[@]}" --output "$dir/grid_mpi.h5" >/dev/null
ser "${grid[@]}" --output "$dir/grid_serial.h5" >/dev/null
same_content "$dir/grid_serial.h5" "$dir/grid_mpi.h5"
list=(--config data/sweep_list.nml --t-end 100 --block 2)
mpi "${list[@]}" --output "$dir/list_mpi.h5" >/dev/null
ser "${list[@]}" --output "$dir/list_serial.h5" >/dev/null
same_content "$dir/list_serial.h5" "$dir/list_mpi.h5"

echo "== 2. kill -9 of mpirun, resume"
classic=(--config data/sweep_classic.nml --n 192 --block 768 --stats)
start=$(date +%s.%N)
mpi "${classic[@]}" --output "$dir/ref.h5" >/dev/null
secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
echo "  uninterrupted run: $secs s"
# kill_at FRACTION PROGRAM...: run, kill -9 after FRACTION of the reference time
kill_at() {
  local frac=$1; shift
  "$@" >/dev/null 2>&1 &
  local pid=$!
  sleep "$(awk -v s="$secs" -v f="$frac" 'BEGIN { print s * f }')"
  kill -9 "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  sleep 0.2
}
# partial FILE: print "k of n blocks done" and succeed if 0 < k < n
partial() {
  local k n
  "$serial" export "$1" /sweep/done >"$dir/done.txt" 2>/dev/null || : >"$dir/done.txt"
  n=$(awk 'NF' "$dir/done.txt" | wc -l)
  k=$(awk '$1 + 0 == 1' "$dir/done.txt" | wc -l)
  echo "  killed: $k of $n blocks done"
  ((k > 0 && k < n))
}
mpirun_cmd=(mpirun "${mpiflags[@]}" "$mpibin" sweep --quiet "${classic[@]}")
interrupted=0
kill_at 0.35 "${mpirun_cmd[@]}" --output "$dir/run.h5"
partial "$dir/run.h5.part" && interrupted=1
kill_at 0.4 "${mpirun_cmd[@]}" --output "$dir/run.h5"
partial "$dir/run.h5.part" && interrupted=1
mpi "${classic[@]}" --output "$dir/run.h5" >/dev/null
((interrupted)) || echo "  (note: no kill hit a run in progress; the machine was fast)"
same_content "$dir/ref.h5" "$dir/run.h5"
echo "== 2b. MPI run killed, finished by the serial dpend sweep"
kill_at 0.5 "${mpirun_cmd[@]}" --output "$dir/cross.h5"
partial "$dir/cross.h5.part" || true
ser "${classic[@]}" --output "$dir/cross.h5" >/dev/null
same_content "$dir/ref.h5" "$dir/cross.h5"

echo "== 2c. serial run killed: dpend-mpi refuses its checksummed working file"
kill_at 0.5 "$serial" sweep --quiet --threads 2 "${classic[@]}" --output "$dir/cross2.h5"
if partial "$dir/cross2.h5.part"; then
  if mpi "${classic[@]}" --output "$dir/cross2.h5" >/dev/null 2>"$dir/cross2.err"; then
    echo "  dpend-mpi resumed a checksummed working file"; failures=$((failures + 1))
  elif grep -q "finish it with dpend sweep" "$dir/cross2.err"; then
    echo "  refused: $(grep -m1 -o 'was started by dpend sweep.*' "$dir/cross2.err" | cut -c1-90)..."
  else
    echo "  unexpected failure:"; cat "$dir/cross2.err"; failures=$((failures + 1))
  fi
fi

echo "== 3. fewer blocks than ranks: said, with the --block that shares them"
small=(--n 16 --t-end 1)   # 16 x 16 in the default 4096-pixel blocks: one block
mpi "${small[@]}" --output "$dir/small.h5" >/dev/null 2>"$dir/small.err"
if grep -q "note: 1 block of 256 pixels for 2 ranks: 1 rank gets no work" "$dir/small.err" &&
   grep -q -- "--block 32 makes 8 blocks" "$dir/small.err"; then
  echo "  said: $(cut -c1-100 "$dir/small.err")..."
else
  echo "  no note about the idle rank:"; cat "$dir/small.err"; failures=$((failures + 1))
fi
mpi --n 128 --t-end 1 --output "$dir/shared.h5" >/dev/null 2>"$dir/shared.err"
if [ -s "$dir/shared.err" ]; then
  echo "  a note where every rank has blocks:"; cat "$dir/shared.err"; failures=$((failures + 1))
fi

echo "== 4. one value per option, as dpend's; a forced chain swept as the serial one"
if mpi --n 4 --n 8 --t-end 1 --output "$dir/twice.h5" >/dev/null 2>"$dir/twice.err"; then
  echo "  an option given twice was taken"; failures=$((failures + 1))
elif grep -q "invalid --n: given twice" "$dir/twice.err"; then
  echo "  refused: $(cut -c1-80 "$dir/twice.err")"
else
  echo "  unexpected failure:"; cat "$dir/twice.err"; failures=$((failures + 1))
fi
forced=(--n 8 --t-end 1 --time-unit s --damping 0.1,0.05 --support-amplitude 0,0.02
        --support-frequency 9 --block 16)
mpi "${forced[@]}" --output "$dir/forced_mpi.h5" >/dev/null
ser "${forced[@]}" --output "$dir/forced_ser.h5" >/dev/null
same_content "$dir/forced_mpi.h5" "$dir/forced_ser.h5"

echo "== mpi_check: $((SECONDS - t0)) s of runs, $failures difference(s)"
((failures == 0))
