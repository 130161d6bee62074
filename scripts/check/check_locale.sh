#!/usr/bin/env bash
# The figures do not depend on the user's locale: run in the caller's locale (CI:
# LC_ALL=de_DE.UTF-8, a decimal comma), this makes a quick study and one file of each
# kind that a plot script draws (simulate, lyapunov, divergence, poincare, a sweep, a
# fit), draws every figure and checks that each PNG is written. A plot script that
# formats a number in the user's locale (bash printf refused "2.0E-003" under de_DE)
# fails here.
# Usage: scripts/check/check_locale.sh OUTDIR   (the release build, through scripts/dpend)
set -euo pipefail
[[ $# -eq 1 ]] || { echo "usage: scripts/check/check_locale.sh OUTDIR" >&2; exit 2; }
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out=$1
mkdir -p "$out"/{study,sim,lyapunov,divergence,poincare,sweep,fit}
dpend=("$root/scripts/dpend")
echo "check_locale: LC_ALL=${LC_ALL:-} LANG=${LANG:-}"
fail() { echo "check_locale: $*" >&2; exit 1; }
pngs() {   # pngs DIR NAME...: every DIR/NAME.png written
  local d=$1 n
  shift
  for n in "$@"; do [[ -s "$d/$n.png" ]] || fail "missing $d/$n.png"; done
}
"${dpend[@]}" study --quick --output "$out/study/study.h5" --force > "$out/study.log" 2>&1 ||
  { tail -n 20 "$out/study.log"; fail "study --quick failed"; }
pngs "$out/study" energy_vs_time energy_vs_step error_vs_step work_precision roundoff \
  tao_omega
"${dpend[@]}" simulate --t-end 2 --output "$out/sim/sim.h5" --force > /dev/null
bash "$root/scripts/plot_simulate.sh" "$out/sim/sim.h5" "$out/sim" > /dev/null
[[ -n "$(find "$out/sim" -name '*.png' -size +1k)" ]] || fail "plot_simulate.sh drew nothing"
for cmd in lyapunov divergence poincare; do
  "${dpend[@]}" "$cmd" --t-end 20 --output "$out/$cmd/$cmd.h5" --force > /dev/null
  bash "$root/scripts/plot_chaos.sh" "$out/$cmd/$cmd.h5" "$out/$cmd" > /dev/null
  [[ -n "$(find "$out/$cmd" -name '*.png' -size +1k)" ]] || fail "plot_chaos.sh drew no $cmd figure"
done
"${dpend[@]}" sweep --n 32 --t-end 10 --quiet --output "$out/sweep/sweep.h5" --force > /dev/null
bash "$root/scripts/plot_sweep.sh" "$out/sweep/sweep.h5" "$out/sweep" > /dev/null
[[ -n "$(find "$out/sweep" -name '*.png' -size +1k)" ]] || fail "plot_sweep.sh drew nothing"
"${dpend[@]}" fit "$root/data/fit_example.csv" --output "$out/fit/fit.h5" --force > /dev/null
bash "$root/scripts/plot_fit.sh" "$out/fit/fit.h5" "$out/fit" > /dev/null
[[ -n "$(find "$out/fit" -name '*.png' -size +1k)" ]] || fail "plot_fit.sh drew nothing"
echo "check_locale: every figure written in ${LC_ALL:-the default locale}"
