#!/usr/bin/env bash
# 24 runs of mixed commands in parallel in one directory, each with its own output:
# all succeed, every file is complete, nothing else is left behind, and a user file
# named .dpend-write-probe is untouched (dpend's write probe once had that fixed name).
. "$ROOT/test/reliability/lib.sh"
printf 'my own file, keep me\n' > .dpend-write-probe
probe_sha=$(sha .dpend-write-probe)
printf '%s\n' '0.1 0.2 0 0' '-1.5 -1.5 0 0' '1 1 0.5 0.5' > list.txt
run() {  # run I: the I-th run (0..23), output out-I.h5
  local i=$1 out=out-$1.h5
  case $((i % 6)) in
    0) "$DPEND" simulate --t-end 0.5 --q1 0.$i --output "$out" ;;
    1) "$DPEND" lyapunov --t-end 2 --tau 0.1 --output "$out" ;;
    2) "$DPEND" divergence --t-end 1 --pairs 2 --lyapunov-t 0 --output "$out" ;;
    3) "$DPEND" poincare --ics 2 --t-end 2 --points 5 --output "$out" ;;
    4) "$DPEND" sweep --n 4 --t-end 1 --quiet --threads 1 --output "$out" ;;
    5) "$DPEND" sweep --ic-file list.txt --t-end 1 --quiet --threads 1 --output "$out" ;;
  esac
}
pids=()
for i in $(seq 0 23); do
  run "$i" > "log-$i.txt" 2>&1 &
  pids+=($!)
done
for i in $(seq 0 23); do
  st=0; wait "${pids[$i]}" || st=$?
  [ $st = 0 ] || bad "run $i exited $st: $(tail -n 2 "log-$i.txt" | tr '\n' ' ')"
done
names=(.dpend-write-probe list.txt)
for i in $(seq 0 23); do
  names+=("out-$i.h5" "log-$i.txt")
  [ -f "out-$i.h5" ] || { bad "run $i: out-$i.h5 missing"; continue; }
  h5_valid "out-$i.h5" || bad "run $i: out-$i.h5 is not a complete file"
done
[ -f .dpend-write-probe ] && [ "$(sha .dpend-write-probe)" = "$probe_sha" ] ||
  bad "the user's file .dpend-write-probe was removed or changed"
stray=$(stray_files . "${names[@]}")
[ -z "$stray" ] || bad "stray files: $(echo $stray)"
finish
