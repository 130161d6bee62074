# Shared helpers of the special tests in test/reliability/special/ (sourced, not run).
# They run with DPEND (absolute binary), ROOT (repo root) and SCRATCH (an empty
# temporary directory, the cwd); exit 0 passes, 77 skips, anything else fails.
set -uo pipefail
: "${DPEND:?DPEND not set}" "${ROOT:?ROOT not set}" "${SCRATCH:?SCRATCH not set}"
cd "$SCRATCH" || exit 1
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}

FAILURES=0
# bad MESSAGE: record a failure (the test goes on, and exits 1 at `finish`).
bad() { echo "FAIL: $*"; FAILURES=$((FAILURES + 1)); }
# die MESSAGE: fail now.
die() { echo "FAIL: $*"; exit 1; }
# skip MESSAGE: skip the test with a note.
skip() { echo "skipped: $*"; exit 77; }
finish() {
  if [ "$FAILURES" -gt 0 ]; then echo "$FAILURES check(s) failed"; exit 1; fi
  echo "ok"; exit 0
}

sha() { sha256sum "$1" | cut -d' ' -f1; }

# h5_status FILE: the root attribute "status" of a dpend HDF5 file ("" if unreadable).
h5_status() {
  h5dump -a /status "$1" 2>/dev/null | sed -n 's/.*(0): "\(.*\)".*/\1/p' | head -n 1
}
# h5_sweep_complete FILE: a sweep file whose /sweep attribute "complete" is 1.
h5_sweep_complete() {
  h5dump -A "$1" > /dev/null 2>&1 || return 1
  [ "$(h5dump -a /sweep/complete "$1" 2>/dev/null | sed -n 's/.*(0): \([0-9]*\).*/\1/p')" = 1 ]
}
# h5_study_complete FILE: a study file (it has no status attribute): every byte
# readable (full h5dump) with its root attribute "wall_time", written last.
h5_study_complete() {
  h5dump "$1" > /dev/null 2>&1 || return 1
  h5dump -a /wall_time "$1" > /dev/null 2>&1
}
# h5_valid FILE: a complete file of any command (status completed, a complete sweep,
# or a complete study).
h5_valid() { h5_complete "$1" || h5_sweep_complete "$1" || h5_study_complete "$1"; }
# h5_header FILE: the structure (groups, datasets, shapes, attributes) without the file name.
h5_header() { h5dump -H "$1" 2>/dev/null | tail -n +2; }
# h5_complete FILE [REF]: readable (h5dump -A), status completed, and, with REF, the
# same structure and shapes as REF (a complete file of the same run).
h5_complete() {
  h5dump -A "$1" > /dev/null 2>&1 || return 1
  [ "$(h5_status "$1")" = completed ] || return 1
  if [ $# -ge 2 ]; then
    [ "$(h5_header "$1")" = "$(h5_header "$2")" ] || return 1
  fi
  return 0
}
# md_complete FILE: a non-empty Markdown file.
md_complete() { [ -s "$1" ]; }

# stray_files DIR NAME...: files in DIR (hidden ones too) other than NAME...
stray_files() {
  local dir=$1; shift
  local f b keep
  for f in "$dir"/* "$dir"/.[!.]* "$dir"/..?*; do
    [ -e "$f" ] || [ -L "$f" ] || continue
    b=${f##*/}
    keep=0
    for n in "$@"; do [ "$b" = "$n" ] && keep=1; done
    [ $keep = 1 ] || echo "$b"
  done
}

# now: seconds since the epoch with nanoseconds.
now() { date +%s.%N; }
# fsleep SECONDS: sleep a fraction of a second.
fsleep() { sleep "$1"; }
# fmul A B: A*B with 3 decimals.
fmul() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a * b }'; }

# kill9_series SMALL_ARGS -- FULL_ARGS: `kill -9` a run of `dpend FULL_ARGS --output
# out.h5 --force` over an existing out.h5 (written by `dpend SMALL_ARGS`) at ten
# moments: five delays from 20 % to 120 % of the run's duration, five when the temporary file
# reaches 10..90 % of the final size. Each time out.h5 must be the old file (same
# sha256) or a complete new one (status completed, same structure as a full run);
# the only debris allowed is the temporary file .out.h5.tmp-XXXXXX (removed).
kill9_series() {
  local -a small=() full=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do small+=("$1"); shift; done
  shift
  full=("$@")
  "$DPEND" "${small[@]}" --output old.h5 > /dev/null 2>&1 || die "cannot write the old file"
  local old_sha t0 t1 dur size
  old_sha=$(sha old.h5)
  t0=$(now)
  "$DPEND" "${full[@]}" --output ref.h5 > /dev/null 2>&1 || die "the full run failed"
  t1=$(now)
  dur=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  size=$(stat -c %s ref.h5)
  h5_complete ref.h5 || die "the full run's file is not complete"
  echo "full run: ${dur} s, ${size} bytes"
  local n_old=0 n_new=0 n_killed=0 n_write=0 i pid st what stray
  local -a moments=(t0.2 t0.5 t0.8 t1.0 t1.2 s0.1 s0.3 s0.5 s0.7 s0.9)
  for what in "${moments[@]}"; do
    cp old.h5 out.h5
    "$DPEND" "${full[@]}" --output out.h5 --force > /dev/null 2>&1 &
    pid=$!
    case $what in
      t*) sleep "$(fmul "$dur" "${what#t}")" ;;
      s*) local limit tmp cur
          limit=$(awk -v a="$size" -v f="${what#s}" 'BEGIN { printf "%d", a * f }')
          while kill -0 "$pid" 2>/dev/null; do
            cur=0
            for tmp in .out.h5.tmp-*; do
              [ -f "$tmp" ] && cur=$(stat -c %s "$tmp" 2>/dev/null || echo 0)
            done
            if [ "$cur" -ge "$limit" ]; then n_write=$((n_write + 1)); break; fi
            sleep 0.002
          done ;;
    esac
    kill -9 "$pid" 2>/dev/null
    st=0; wait "$pid" 2>/dev/null || st=$?
    [ $st = 137 ] && n_killed=$((n_killed + 1))
    if [ ! -f out.h5 ]; then
      bad "kill at $what (exit $st): out.h5 is gone"
    elif [ "$(sha out.h5)" = "$old_sha" ]; then
      n_old=$((n_old + 1))
    elif h5_complete out.h5 ref.h5; then
      n_new=$((n_new + 1))
    else
      bad "kill at $what (exit $st): out.h5 is neither the old file nor a complete new one" \
          "(status '$(h5_status out.h5)')"
    fi
    stray=$(stray_files . old.h5 ref.h5 out.h5 | grep -v '^\.out\.h5\.tmp-......$')
    [ -z "$stray" ] || bad "kill at $what: debris other than the temporary file: $stray"
    rm -f .out.h5.tmp-*
  done
  echo "10 kills ($n_killed while running, $n_write of them while writing):" \
       "$n_old times the old file, $n_new times a new one"
  [ $n_killed -gt 0 ] || bad "no kill hit the running process (machine too fast?)"
}
