#!/usr/bin/env bash
# Build the MPI variant of the sweep (the fpm package in mpi/, release profile) and
# print the path of the dpend-mpi binary on the last line. Usage: scripts/mpi/build_mpi.sh
#
# The package needs the MPI compiler wrapper and parallel HDF5. fpm's hdf5
# metapackage reads the pkg-config package `hdf5`, which on Debian is the serial
# library (scripts/setup.sh pins it); this script puts a generated hdf5.pc for the
# parallel library first on PKG_CONFIG_PATH, for this build only. Environment:
#   DPEND_HDF5_PC  pkg-config name of the parallel HDF5 (default hdf5-openmpi;
#                  on a cluster, whatever its HDF5 module provides, e.g. hdf5)
#   FPM_FC         MPI Fortran compiler wrapper (default mpif90)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
. "$root/scripts/flags.sh"
pcname="${DPEND_HDF5_PC:-hdf5-openmpi}"
[[ $pcname =~ ^[A-Za-z0-9_][A-Za-z0-9_.+-]*$ ]] ||
  { echo "build_mpi.sh: DPEND_HDF5_PC is not a pkg-config package name: '$pcname'" >&2; exit 2; }
export FPM_FC="${FPM_FC:-mpif90}"
command -v "$FPM_FC" >/dev/null 2>&1 ||
  { echo "build_mpi.sh: no $FPM_FC (run: bash scripts/setup.sh --mpi)" >&2; exit 1; }
pcdir=$(pkg-config --variable=pcfiledir "$pcname" 2>/dev/null) ||
  { echo "build_mpi.sh: pkg-config has no $pcname (run: bash scripts/setup.sh --mpi)" >&2
    exit 1; }
# The copy drops `Requires:` (the MPI wrapper links MPI itself): with it, fpm takes
# the MPI library directory for HDF5's and misses the Fortran HDF5 libraries.
gen="$root/mpi/build/pkgconfig"
mkdir -p "$gen"
sed '/^Requires/d' "$pcdir/$pcname.pc" >"$gen/hdf5.pc.new"
mv "$gen/hdf5.pc.new" "$gen/hdf5.pc"
export PKG_CONFIG_PATH="$gen${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
cd "$root/mpi"
# the build in the background: after 2 s a notice on stderr of what is happening
# and how long it takes, then progress every 30 s (an up-to-date build says nothing)
log=$(mktemp "${TMPDIR:-/tmp}/dpend-mpi-build.XXXXXX")
trap 'rm -f "$log"' EXIT
fpm build --profile release --flag "$RELEASE_FLAGS" > "$log" 2>&1 &
pid=$!
trap 'kill "$pid" 2> /dev/null; rm -f "$log"; exit 130' INT TERM
ticks=0   # tenths of a second
while kill -0 "$pid" 2> /dev/null; do
  sleep 0.1
  ticks=$((ticks + 1))
  if [ "$ticks" = 20 ]; then
    echo "build_mpi.sh: building the MPI variant of the sweep (release profile, once:" \
         "about 1.5 minutes on 2 cores; later builds only what changed)" >&2
  elif [ $((ticks % 300)) = 0 ]; then
    done_pct=$(grep -o '^\[ *[0-9]*%\]' "$log" | tail -n 1 | tr -d '[] ' || true)
    echo "build_mpi.sh: still building ($((ticks / 10)) s${done_pct:+, $done_pct of the files})" >&2
  fi
done
if ! wait "$pid"; then
  cat "$log" >&2
  echo "build_mpi.sh: build failed (after sources moved or changed interfaces, fpm may" \
    "keep stale objects: remove mpi/build and rerun)" >&2
  exit 1
fi
[ "$ticks" -lt 20 ] || echo "build_mpi.sh: built in $((ticks / 10)) s" >&2
trap - INT TERM EXIT
rm -f "$log"
bin=$(fpm run dpend-mpi --profile release --flag "$RELEASE_FLAGS" --runner echo 2>/dev/null |
  tail -n 1)
case "$bin" in /*) ;; *) bin="$root/mpi/$bin" ;; esac
echo "$bin"
