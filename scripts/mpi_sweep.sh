#!/usr/bin/env bash
# Run `dpend sweep` over NP MPI ranks on this machine (the MPI variant, built on
# first use by scripts/mpi/build_mpi.sh), from any directory:
#   scripts/mpi_sweep.sh NP [dpend sweep options]
#   scripts/mpi_sweep.sh 2 --config data/sweep_classic.nml
# OpenMP threads per rank: OMP_NUM_THREADS, default cores / NP (at least 1).
# Extra mpirun options: MPIRUN_FLAGS. On a cluster use scripts/mpi/slurm_sweep.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ $# -lt 1 || ! "$1" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/mpi_sweep.sh NP [dpend sweep options]" >&2
  exit 2
fi
np=$1
shift
bin=$("$root/scripts/mpi/build_mpi.sh" | tail -n 1)
cores=$(nproc)
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-$((cores / np > 0 ? cores / np : 1))}"
# no binding (a rank's threads must not share one core); more ranks than cores
# need --oversubscribe
flags=(--bind-to none)
((np > cores)) && flags+=(--oversubscribe)
[[ $(id -u) -eq 0 ]] && flags+=(--allow-run-as-root)
# MPIRUN_FLAGS: split into words (no glob expansion, no other shell syntax)
read -r -a extra <<<"${MPIRUN_FLAGS:-}" || true
exec mpirun "${flags[@]}" "${extra[@]}" -np "$np" "$bin" sweep "$@"
