#!/usr/bin/env bash
# Two runs racing for one new output without --force, 20 times over the writing
# commands: never both succeed, the file is complete, the loser exits non-zero with
# a clear message (once the check came before the computation, the write after, so
# both could exit 0). The sweep is left out: rerunning it on its own
# complete file is a documented success (resume).
. "$ROOT/test/reliability/lib.sh"
commands=(
  "simulate --t-end 2"
  "lyapunov --t-end 2 --tau 0.1"
  "divergence --t-end 1 --pairs 2 --lyapunov-t 0"
  "poincare --ics 2 --t-end 3 --points 5"
  "study --quick --methods rk4 --cases small --no-figures --threads 1"
)
TRAP_RE='Floating point exception|Fortran runtime error|Backtrace|Error termination|HDF5-DIAG'
both=0; one=0
for i in $(seq 1 20); do
  c=${commands[$(( (i - 1) % ${#commands[@]} ))]}
  read -r -a args <<< "$c"
  out=race-$i.h5
  timeout 60 "$DPEND" "${args[@]}" --output "$out" > a.out 2> a.err < /dev/null &
  pa=$!
  timeout 60 "$DPEND" "${args[@]}" --output "$out" > b.out 2> b.err < /dev/null &
  pb=$!
  sa=0; wait $pa || sa=$?
  sb=0; wait $pb || sb=$?
  what="race $i (dpend $c --output $out): exits $sa and $sb"
  if [ $sa = 0 ] && [ $sb = 0 ]; then
    bad "$what: both succeeded"; both=$((both + 1))
  elif [ $sa != 0 ] && [ $sb != 0 ]; then
    bad "$what: neither succeeded ($(head -n 1 a.err) | $(head -n 1 b.err))"
  else
    one=$((one + 1))
    if [ $sa = 0 ]; then loser=b; st=$sb; else loser=a; st=$sa; fi
    case $st in 1|2) ;; *) bad "$what: the loser's exit status is $st (expected 1 or 2)" ;; esac
    [ -s $loser.err ] || bad "$what: the loser printed no message"
    grep -qE "$TRAP_RE" $loser.err && bad "$what: the loser trapped: $(grep -m1 -E "$TRAP_RE" $loser.err)"
    grep -qF "$out" $loser.err || bad "$what: the loser's message does not name $out: $(head -n 1 $loser.err)"
  fi
  h5_valid "$out" || bad "$what: $out is not a complete file"
  case $c in study*) md_complete "race-$i.md" || bad "$what: race-$i.md missing or empty" ;; esac
  stray=$(stray_files . a.out a.err b.out b.err race-*.h5 race-*.md)
  [ -z "$stray" ] || { bad "$what: left $(echo $stray)"; rm -f -- $stray; }
done
echo "20 races: $one with one winner, $both with two"
finish
