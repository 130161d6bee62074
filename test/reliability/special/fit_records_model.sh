#!/usr/bin/env bash
# Special reliability test: the fit file records the model it fitted, so that the
# model can be rebuilt from the file: every parameter under the model's name for it
# (m1, l2, g, com2, inertia1, ...), the body of links other than uniform rods, the
# model's name; and data at rest, which show no noise, raise no "times the noise 0"
# warning. Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, other: fail. One line per check.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
attr() { h5dump -a "$2" "$1" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n 1 | sed 's/^"\(.*\)"$/\1/'; }
near() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && (a - b) ^ 2 < 1e-24) }'; }
head -n 88 "$ROOT/data/fit_mass_length.csv" > ml80.csv
if "$DPEND" fit ml80.csv --com 0.5,0.4 --inertia 0.08,0.03 --m 1.5,0.7 --fit-param com2 \
     --output bodies.h5 > bodies.out 2>&1; then
  pass 'bodies: exit 0'
else
  fail "bodies: exit status: $(tail -n 1 bodies.out)"
fi
for kv in m1=1.5 m2=0.7 com1=0.5 com2=0.4 inertia1=0.08 inertia2=0.03 g=9.8; do
  k=${kv%%=*}; v=${kv#*=}
  if near "$(attr bodies.h5 "/$k")" "$v"; then pass "bodies: /$k = $v"
  else fail "bodies: /$k is '$(attr bodies.h5 "/$k")', not $v"; fi
done
case $(attr bodies.h5 /body) in
  'general bodies'*) pass 'bodies: /body says general bodies' ;;
  *) fail "bodies: /body is '$(attr bodies.h5 /body)'" ;;
esac
[ "$(attr bodies.h5 /model)" = pendulum ] && pass 'bodies: /model' || fail "bodies: /model '$(attr bodies.h5 /model)'"
if "$DPEND" fit ml80.csv --body point --fit-param l2 --output point.h5 > point.out 2>&1; then
  pass 'point: exit 0'
else
  fail "point: exit status: $(tail -n 1 point.out)"
fi
case $(attr point.h5 /body) in
  'point masses'*) pass 'point: /body says point masses' ;;
  *) fail "point: /body is '$(attr point.h5 /body)'" ;;
esac
near "$(attr point.h5 /inertia2)" 0 && pass 'point: /inertia2 = 0' || fail "point: /inertia2 '$(attr point.h5 /inertia2)'"
printf 't,q1,q2\n' > rest.csv
for i in 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
  printf '%s.0,-1.5707963267948966,-1.5707963267948966\n' "$i" >> rest.csv
done
if "$DPEND" fit rest.csv --output rest.h5 > rest.out 2>&1; then
  pass 'rest: the state fitted, exit 0'
else
  fail "rest: exit status: $(tail -n 1 rest.out)"
fi
if grep -q 'times the noise' rest.out; then
  fail "rest: a misfit warning: $(grep 'times the noise' rest.out)"
else
  pass 'rest: no misfit warning'
fi
exit $((failures > 0))
