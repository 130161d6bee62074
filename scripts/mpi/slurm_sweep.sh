#!/usr/bin/env bash
# Example Slurm batch script: the classic flip map over 4 nodes, 2 MPI ranks per
# node (one per socket), 16 OpenMP threads per rank. Adapt the #SBATCH lines, the
# modules and the options to your cluster and submit from the dpend directory:
#   sbatch scripts/mpi/slurm_sweep.sh [dpend sweep options]
#   sbatch scripts/mpi/slurm_sweep.sh --config data/sweep_classic.nml --n 4096 --block 4096
# Resubmitting the same command after a time-out or a node failure resumes: only the
# blocks not yet flagged in the file are computed (docs/mpi.md).
#SBATCH --job-name=dpend-sweep
#SBATCH --nodes=4
#SBATCH --ntasks-per-node=2
#SBATCH --cpus-per-task=16
#SBATCH --time=01:00:00
#SBATCH --output=dpend-sweep-%j.log
set -euo pipefail

# module load gcc openmpi hdf5/parallel     # site-specific: MPI wrapper + parallel HDF5
# The HDF5 module's pkg-config name, if it is not Debian's hdf5-openmpi:
# export DPEND_HDF5_PC=hdf5
# A file system without file locks (some Lustre mounts):
# export HDF5_USE_FILE_LOCKING=FALSE

cd "${SLURM_SUBMIT_DIR:-.}"
# Build once, on the first node, before the ranks start (the build directory is on
# the shared file system).
bin=$(scripts/mpi/build_mpi.sh | tail -n 1)

export OMP_NUM_THREADS="${SLURM_CPUS_PER_TASK:-1}"
export OMP_PLACES=cores OMP_PROC_BIND=close    # threads pinned inside the rank's cores
# The output must be on a file system that every node sees (MPI-IO: Lustre, GPFS,
# BeeGFS; NFS only with care). Default: the options' --output or the config's file.
if [[ $# -eq 0 ]]; then set -- --config data/sweep_classic.nml; fi

# srun starts the ranks with --cpus-per-task cores each (Slurm >= 22.05 needs it
# passed on explicitly); with Open MPI built without Slurm/PMIx support use
#   mpirun --map-by ppr:${SLURM_NTASKS_PER_NODE}:node:PE=${SLURM_CPUS_PER_TASK} "$bin" ...
srun --cpus-per-task="${SLURM_CPUS_PER_TASK:-1}" "$bin" sweep --block-times \
  "dpend-sweep-${SLURM_JOB_ID:-local}-blocks.txt" "$@"
