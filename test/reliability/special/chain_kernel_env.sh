#!/usr/bin/env bash
# DPEND_SWEEP_KERNEL: 'trajectory' sends a chain's flip map through the
# per-trajectory path, 'lanes' or empty through the chain lanes, both succeed; any
# other value (a typo, too long, a quote) is refused in one stderr line naming the
# variable, exit 2, before any file is written.
. "$ROOT/test/reliability/lib.sh"
run=(sweep --links 3 --n 3 --t-end 1 --quiet)
for v in trajectory lanes ''; do
  st=0
  DPEND_SWEEP_KERNEL=$v timeout 60 "$DPEND" "${run[@]}" --output "ok_$v.h5" \
    > run.out 2> run.err < /dev/null || st=$?
  [ $st = 0 ] || bad "DPEND_SWEEP_KERNEL='$v': exit $st: $(head -n 2 run.err | tr '\n' ' ')"
  [ -s "ok_$v.h5" ] || bad "DPEND_SWEEP_KERNEL='$v': no file"
done
for v in Trajectory 'lanes ' "x'y" "$(printf 'a%.0s' {1..40})"; do
  st=0
  DPEND_SWEEP_KERNEL=$v timeout 60 "$DPEND" "${run[@]}" --output bad.h5 \
    > run.out 2> run.err < /dev/null || st=$?
  what="DPEND_SWEEP_KERNEL=$(printf '%q' "$v")"
  [ $st = 2 ] || bad "$what: exit $st, expected 2"
  [ "$(grep -c '' run.err)" = 1 ] || bad "$what: $(grep -c '' run.err) stderr lines, expected 1"
  grep -q 'DPEND_SWEEP_KERNEL' run.err || bad "$what: stderr does not name the variable"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.part ] || bad "$what: a file was written"
done
finish
