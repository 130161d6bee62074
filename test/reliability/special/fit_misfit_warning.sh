#!/usr/bin/env bash
# Special reliability test: a fit with a wrong fixed length warns that the
# residuals are model error and names the length as the first suspect; the right
# length gives no warning. Environment (set by the reliability runner): DPEND (the
# dpend binary), ROOT (the repository root), SCRATCH (an empty temporary directory,
# the cwd). Exit 0: pass, other: fail. One line per check.
#
# data/fit_bob.csv: the tip of a one-link pendulum with a bob (l = 0.8 m, com 0.65 m,
# inertia 0.01 kg m^2, damping 0.02 N m s), noise 0.002 m; fitted for com and damping
# with l fixed at 0.7 m, then at 0.8 m.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
fit() { # fit L OUT: the fit with l fixed at L, stdout to OUT; its exit status
  "$DPEND" fit "$ROOT/data/fit_bob.csv" --links 1 --l "$1" --com 0.5 --inertia 0.01 \
    --fit-param com,damping --output "fit_$1.h5" > "$2" 2> "$2.err"
}
if fit 0.7 wrong.out; then pass 'wrong length: exit 0'; else fail 'wrong length: exit status'; fi
if grep -q 'the residuals are model error' wrong.out; then
  pass 'wrong length: the residuals are model error'
else
  fail "wrong length: no model-error warning: $(grep -i 'rms' wrong.out | head -1)"
fi
if grep -q 'parameters that may be wrong, by the RMS residual fitting each too would leave (linearized): l (' wrong.out &&
   grep -q 'fit them with --fit-param l$' wrong.out; then
  pass 'wrong length: l the first suspect'
else
  fail "wrong length: l not the first suspect: $(grep 'may be wrong' wrong.out)"
fi
if fit 0.8 right.out; then pass 'right length: exit 0'; else fail 'right length: exit status'; fi
if grep -q 'warning' right.out; then
  fail "right length: a warning: $(grep warning right.out)"
else
  pass 'right length: no warning'
fi
exit $((failures > 0))
