#!/usr/bin/env bash
# Special reliability test: messages and labels that name what is wrong, not a
# neighbour of it. sweep-compare of the elastic pendulum's indicator maps (its
# values, its own time unit sqrt(l0/g), another spring refused); the elastic
# pendulum given the pendulum's damping; an elastic fit CSV with r <= 0; a fraction
# for a whole-number namelist key; a resumed sweep whose configuration gained a key;
# plot_simulate.sh on a file whose q lost its units; the units of an elastic
# divergence file. Environment (set by the reliability runner): DPEND, ROOT, SCRATCH
# (the cwd). Exit 0: pass, other: fail. One line per check.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
# expect NAME STATUS TEXT CMD...: CMD exits with STATUS and its output holds TEXT
expect() {
  local name=$1 want=$2 text=$3 st; shift 3
  "$@" > "$name.out" 2>&1; st=$?
  if [[ $st == "$want" ]] && grep -qF -- "$text" "$name.out"; then pass "$name"
  else fail "$name: exit $st, '$(head -c 300 "$name.out")'"; fi
}
attr() { h5dump -a "$2" "$1" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n 1 | sed 's/^"\(.*\)"$/\1/'; }
E=(--model elastic --q 1.2,-1)
M=(sweep "${E[@]}" --axis1 r --axis2 phi --min1 1 --max1 1.4 --min2 -1 --max2 1 --n 4 --t-end 1 --indicator megno --quiet)
"$DPEND" "${M[@]}" --output a.h5 > /dev/null 2>&1
"$DPEND" "${M[@]}" --dt 0.005 --output b.h5 > /dev/null 2>&1
expect compare-indicator-maps 0 'MEGNO <Y> changes by more than 0.01 relative at' \
  "$DPEND" sweep-compare a.h5 b.h5
expect compare-indicator-unit 0 't_end_a: 1 sqrt(l0/g) = 0.319438 s' \
  "$DPEND" sweep-compare a.h5 b.h5 --agreement
"$DPEND" "${M[@]}" --k 50 --output k.h5 > /dev/null 2>&1
expect compare-other-spring 2 "not comparable: k = 4.0000000000000000E+001 in 'a.h5'" \
  "$DPEND" sweep-compare a.h5 k.h5
expect elastic-damping 2 'invalid damping: not a parameter of model elastic' \
  "$DPEND" simulate "${E[@]}" --damping 0.1 --output e.h5
printf 't [s],r [m],phi [rad]\n0,1.2,-1\n0.05,-0.1,-0.98\n0.1,1.23,-0.97\n0.15,1.24,-0.97\n0.2,1.25,-0.96\n' > neg.csv
expect elastic-fit-r-negative 2 "invalid data file 'neg.csv' line 3: not a state of model elastic" \
  "$DPEND" fit neg.csv --model elastic --output f.h5
printf '&sweep gpu_repack = 1.5 /\n' > repack.nml
expect whole-number-key 2 'invalid gpu_repack' \
  "$DPEND" sweep --config repack.nml --n 2 --t-end 0.1 --quiet --output s.h5
# a sweep stopped partway, resumed with a key its file lacks (com1, com2 of point masses)
(timeout -s KILL 2 "$DPEND" sweep --n 1000 --t-end 100 --quiet --output r.h5 > /dev/null 2>&1) 2> /dev/null
if [[ -f r.h5.part ]]; then
  expect resume-key-added 2 'another configuration (com1 = 1 here, com1 (none) in the file)' \
    "$DPEND" sweep --n 1000 --t-end 100 --quiet --body point --output r.h5
else
  fail 'resume-key-added: the sweep left no r.h5.part after 2 s'
fi
# plot_simulate.sh on a file without the units of q: a note, the figures
if h5fc -o h5craft "$ROOT/scripts/check/h5craft.f90" > h5craft.log 2>&1; then
  "$DPEND" simulate --t-end 0.5 --output nu.h5 > /dev/null 2>&1
  ./h5craft nu.h5 attr-del /trajectory/q units
  if DPEND=$DPEND bash "$ROOT/scripts/plot_simulate.sh" nu.h5 > plot.out 2>&1 &&
     grep -q 'gives no units; taken as rad' plot.out && [[ -s angles.png ]]; then
    pass 'plot-simulate-no-units'
  else
    fail "plot-simulate-no-units: '$(head -c 300 plot.out)'"
  fi
else
  fail "plot-simulate-no-units: h5craft did not build: $(tail -n 2 h5craft.log)"
fi
"$DPEND" divergence "${E[@]}" --t-end 1 --output-dt 0.1 --lyapunov-t 0 --output d.h5 > /dev/null 2>&1
u=$(attr d.h5 /divergence/start/units)
[[ $u == 'm, rad, m/s, rad/s' ]] && pass "elastic-divergence-units: $u" || fail "elastic-divergence-units: '$u'"
exit $((failures > 0))
