#!/usr/bin/env bash
# --force while another process holds the old file open (as h5py in a notebook
# would): the holder still reads the old bytes, the new file is complete, nothing
# else is left (once the old file was truncated to 0 bytes, then the run failed). For every command that writes.
. "$ROOT/test/reliability/lib.sh"
printf '%s\n' '0.1 0.2 0 0' '-1.5 -1.5 0 0' > list.txt
# old run | new run (each then gets --output FILE; the new one also --force)
pairs=(
  "simulate --t-end 0.1|simulate --t-end 0.5"
  "lyapunov --t-end 1|lyapunov --t-end 2 --tau 0.1"
  "divergence --t-end 1 --pairs 2 --lyapunov-t 0|divergence --t-end 2 --pairs 2 --lyapunov-t 0"
  "poincare --ics 2 --t-end 2 --points 5|poincare --ics 3 --t-end 2 --points 5"
  "sweep --n 8 --t-end 1 --quiet --threads 1|sweep --n 4 --t-end 1 --quiet --threads 1"
  "sweep --n 4 --t-end 1 --quiet --threads 1|sweep --ic-file list.txt --t-end 1 --quiet --threads 1"
  "study --quick --methods rk4 --cases small --no-figures --threads 1|study --quick --methods verlet --cases small --no-figures --threads 1"
)
for i in "${!pairs[@]}"; do
  IFS='|' read -r old new <<< "${pairs[$i]}"
  read -r -a a_old <<< "$old"
  read -r -a a_new <<< "$new"
  f=held-$i.h5
  "$DPEND" "${a_old[@]}" --output "$f" > /dev/null 2>&1 || { bad "dpend $old: failed"; continue; }
  old_sha=$(sha "$f")
  rm -f go
  ( exec 3< "$f"; touch opened; while [ ! -e go ]; do sleep 0.02; done; cat <&3 > held.bin ) &
  holder=$!
  while [ ! -e opened ]; do sleep 0.02; done
  st=0
  timeout 60 "$DPEND" "${a_new[@]}" --output "$f" --force > run.out 2> run.err < /dev/null || st=$?
  touch go; wait $holder
  what="dpend $new --output $f --force (old file held open)"
  [ $st = 0 ] || bad "$what: exit $st: $(head -n 2 run.err | tr '\n' ' ')"
  [ "$(sha held.bin)" = "$old_sha" ] || bad "$what: the holder no longer reads the old bytes" \
    "($(stat -c %s held.bin) bytes read)"
  [ "$(sha "$f")" != "$old_sha" ] || bad "$what: $f is still the old file"
  h5_valid "$f" || bad "$what: $f is not a complete file"
  rm -f held.bin opened go run.out run.err
  stray=$(stray_files . list.txt held-*.h5 held-*.md)
  [ -z "$stray" ] || { bad "$what: left $(echo $stray)"; rm -f -- $stray; }
done
finish
