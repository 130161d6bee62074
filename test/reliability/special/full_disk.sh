#!/usr/bin/env bash
# A full disk (a 300 kB tmpfs, filled up) with and without --force, for every
# command that writes: exit 1 with a message naming "no space left on device" (or
# exit 2 with one line about the space, when the run is refused before any work),
# the old file byte-identical, no temporary file left (once --force destroyed the
# previous result; lyapunov left a `completed` file holding only
# /lyapunov/t; poincare printed "wrote" and crashed). Needs root (mount); else skipped.
. "$ROOT/test/reliability/lib.sh"
[ "$(id -u)" = 0 ] || skip "not root: cannot mount a tmpfs (run as root to test a full disk)"
mkdir disk
mount -t tmpfs -o size=300k tmpfs "$SCRATCH/disk" 2>/dev/null ||
  skip "mount -t tmpfs failed (no privilege in this container?)"
trap 'cd /; umount "$SCRATCH/disk" 2>/dev/null' EXIT
printf '%s\n' '0.1 0.2 0 0' '-1.5 -1.5 0 0' > list.txt
# old run (writes the old file) | new run (its output fills the disk)
pairs=(
  "simulate --t-end 0.1|simulate --t-end 20 --save-every 1"
  "lyapunov --t-end 1|lyapunov --t-end 50 --tau 0.01"
  "divergence --t-end 1 --pairs 2 --lyapunov-t 0|divergence --t-end 20 --pairs 2 --lyapunov-t 0 --output-dt 0.001"
  "poincare --ics 2 --t-end 2 --points 5|poincare --ics 20 --t-end 200 --points 400"
  "sweep --n 4 --t-end 1 --quiet --threads 1|sweep --n 64 --t-end 1 --quiet --threads 1"
  "study --quick --methods rk4 --cases small --no-figures --threads 1|study --quick --methods verlet --cases small --no-figures --threads 1"
)
fill() {  # fill FREE_KB: fill the disk up, leaving FREE_KB kB (0: the last bytes too)
  local free=$1 avail
  if [ "$free" = 0 ]; then
    dd if=/dev/zero of=disk/fill bs=4k > /dev/null 2>&1
    dd if=/dev/zero of=disk/fill2 bs=64 > /dev/null 2>&1
    dd if=/dev/zero of=disk/fill3 bs=1 > /dev/null 2>&1
  else
    avail=$(df -k --output=avail disk | tail -n 1 | tr -d ' ')
    [ "$avail" -gt "$free" ] &&
      dd if=/dev/zero of=disk/fill bs=1k count=$((avail - free)) > /dev/null 2>&1
  fi
  true
}
check_run() {  # check_run WHAT STATUS
  local what=$1 st=$2
  echo "$what: exit $st: $(grep -m1 -v '^ *$' run.err | cut -c1-150)"
  case $st in
    1) grep -qi "no space left on device" run.err ||
         bad "$what: exit 1 without 'no space left on device': $(head -n 1 run.err)" ;;
    2) [ "$(grep -c '' run.err)" = 1 ] && grep -qiE 'space|disk' run.err ||
         bad "$what: exit 2 without one line about the space: $(head -n 2 run.err | tr '\n' ' ')" ;;
    *) bad "$what: exit $st, expected 1: $(head -n 2 run.err | tr '\n' ' ')" ;;
  esac
  grep -qE 'Floating point exception|Fortran runtime error|Backtrace|Error termination|HDF5-DIAG' \
    run.err && bad "$what: trap or HDF5 error stack: $(grep -m1 -E 'Fortran|HDF5|Backtrace' run.err)"
}
# A disk with no byte left (creating the temporary file fails), and one with 16 kB
# left (the write fails partway: every new output is larger).
for free in 0 16; do
for i in "${!pairs[@]}"; do
  IFS='|' read -r old new <<< "${pairs[$i]}"
  read -r -a a_old <<< "$old"
  read -r -a a_new <<< "$new"
  rm -rf disk/* disk/.[!.]* 2>/dev/null
  "$DPEND" "${a_old[@]}" --output disk/old.h5 > /dev/null 2>&1 || { bad "dpend $old: failed"; continue; }
  [ -f disk/old.md ] && md_sha=$(sha disk/old.md) || md_sha=""
  old_sha=$(sha disk/old.h5)
  fill $free
  # with --force over the old file
  st=0
  timeout 60 "$DPEND" "${a_new[@]}" --output disk/old.h5 --force > run.out 2> run.err < /dev/null || st=$?
  what="full disk ($free kB free): dpend $new --output old.h5 --force"
  check_run "$what" $st
  [ -f disk/old.h5 ] && [ "$(sha disk/old.h5)" = "$old_sha" ] || bad "$what: the old file was changed"
  [ -z "$md_sha" ] || [ "$(sha disk/old.md)" = "$md_sha" ] || bad "$what: the old .md was changed"
  stray=$(stray_files disk old.h5 old.md fill fill2 fill3)
  [ -z "$stray" ] || bad "$what: left $(echo $stray)"
  rm -f -- $(printf 'disk/%s ' $stray) 2>/dev/null
  # without --force, a new name
  st=0
  timeout 60 "$DPEND" "${a_new[@]}" --output disk/new.h5 > run.out 2> run.err < /dev/null || st=$?
  what="full disk ($free kB free): dpend $new --output new.h5"
  check_run "$what" $st
  if [ -e disk/new.h5 ]; then
    # only a readable file saying why (the sweep keeps its working file to resume)
    h5dump -A disk/new.h5 > /dev/null 2>&1 || bad "$what: left an unreadable new.h5"
  fi
  stray=$(stray_files disk old.h5 old.md new.h5 fill fill2 fill3)
  [ -z "$stray" ] || bad "$what: left $(echo $stray)"
done
done
finish
