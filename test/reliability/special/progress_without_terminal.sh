#!/usr/bin/env bash
# Special reliability test: every command whose work the limits let run for days
# reports its progress on stderr without a terminal (a line at most every 10 s, the
# time left marked as an estimate, "ETA ~"): lyapunov, indicators, divergence,
# poincare, simulate with and without --output-dt, and the fit (its ETA grew from
# 463 s to 1119 s within 30 s when it was called an upper bound). Each runs for
# 12.5 s (stderr a file), then is stopped. Environment (set by the reliability runner): DPEND, ROOT,
# SCRATCH (the cwd). Exit 0: pass, other: fail. One line per check.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
names=(lyapunov indicators divergence poincare simulate simulate_dt fit)
runs=(
  "lyapunov --t-end 1e8 --tau 1"
  "indicators --t-end 1e8 --tau 1000"
  "divergence --t-end 1e6 --output-dt 1"
  "poincare --t-end 1e6 --points 1000000"
  "simulate --t-end 1e8 --save-every 100000"
  "simulate --t-end 1e7 --output-dt 10"
  "fit $ROOT/data/fit_elastic.csv --model elastic --fit-parameters k --k 1e6"
)
pids=()
for i in "${!names[@]}"; do
  read -r -a args <<< "${runs[$i]}"
  OMP_NUM_THREADS=1 timeout -s KILL 12.5 "$DPEND" "${args[@]}" --output "${names[$i]}.h5" \
    < /dev/null > "${names[$i]}.out" 2> "${names[$i]}.err" &
  pids+=($!)
done
for p in "${pids[@]}"; do wait "$p"; done
for i in "${!names[@]}"; do
  cmd=${runs[$i]%% *}
  # (the fit counts step-equivalents: 'dpend fit (step-equivalents of at most 7.73e8,
  # up to 7777 integrations): 0.2% (1501105/772811246), 150000 steps/s, ...')
  if grep -Eq "^dpend $cmd( \(step-equivalents of at most [0-9.e+]+, up to [0-9.e+]+ integrations\))?: [0-9.e-]+%( \([0-9]+/[0-9]+\), [0-9.e+]+ steps/s)?, elapsed 0:00:1[0-9], ETA ~([0-9]+:[0-9]{2}:[0-9]{2}|--)$" "${names[$i]}.err"; then
    pass "${names[$i]}: $(head -n 1 "${names[$i]}.err")"
  else
    fail "${names[$i]}: no progress line in 12 s: '$(head -c 300 "${names[$i]}.err")'"
  fi
done
exit $((failures > 0))
