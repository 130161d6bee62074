#!/usr/bin/env bash
# Coverage of the fit's 95 % intervals on tip-only data (docs/fit.md, "A pendulum
# seen at its tip"): a double pendulum of point masses (m1 = 0.3 kg fixed, m2 =
# 0.2 kg, l1 = 0.25 m, l2 = 0.18 m, joint damping 0.002 and 0.001 N m s), released
# at rest from q = (-0.5, 0.3) rad, simulated once (dop853, rtol 1e-12, 8 s, a sample
# every 0.02 s); COUNT series of its tip's positions x2, y2 with Gaussian noise of
# 1 mm (awk's generator, seed 1..COUNT, Box-Muller), each fitted as a student would:
#   dpend fit tip.csv --body point --m1 0.3 --m2 0.25 --l1 0.24 --l2 0.19 \
#       --fit-param m2,l,damping
# Prints for m2, l1, l2, c1, c2 how many 95 % intervals hold the truth, and fails
# (exit 1) if any parameter is covered in fewer than MIN series (default 45 of 50).
# Usage: scripts/check/tip_coverage.sh [--count N] [--min K] [--dpend BIN] [--keep DIR]
#   BIN: the dpend binary (default: the release build, as scripts/dpend builds it).
# Nothing is built from the data into a shell command: file names are fixed, numbers
# pass through awk.
set -euo pipefail
export LC_ALL=C
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
count=50 min=45 dpend="" keep=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --count) count=${2:?--count needs N}; shift 2 ;;
    --min) min=${2:?--min needs K}; shift 2 ;;
    --dpend) dpend=${2:?--dpend needs a binary}; shift 2 ;;
    --keep) keep=${2:?--keep needs a directory}; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tip_coverage.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ $count =~ ^[1-9][0-9]{0,3}$ ]] || { echo "tip_coverage.sh: --count must be 1 to 9999" >&2; exit 2; }
[[ $min =~ ^[0-9]{1,4}$ ]] || { echo "tip_coverage.sh: --min must be 0 to 9999" >&2; exit 2; }
if [[ -z $dpend ]]; then
  . "$root/scripts/flags.sh"
  (cd "$root" && fpm build --profile release --flag "$RELEASE_FLAGS" > /dev/null)
  dpend=$(cd "$root" && fpm run dpend --profile release --flag "$RELEASE_FLAGS" --runner echo \
    2>/dev/null | tail -n 1)
  case "$dpend" in /*) ;; *) dpend="$root/$dpend" ;; esac
fi
if [[ -n $keep ]]; then
  mkdir -p -- "$keep"; work=$(cd -- "$keep" && pwd)
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/dpend-coverage.XXXXXX"); trap 'rm -rf -- "$work"' EXIT
fi
cd -- "$work"
"$dpend" simulate --body point --m1 0.3 --m2 0.2 --l1 0.25 --l2 0.18 --damping 0.002,0.001 \
  --q1 -0.5 --q2 0.3 --method dop853 --rtol 1e-12 --atol 1e-14 --t-end 8 --output-dt 0.02 \
  --output truth.h5 --force --quiet > /dev/null
"$dpend" export truth.h5 /trajectory/t /trajectory/q > truth.txt
truth=(0.2 0.25 0.18 0.002 0.001)
names=(m2 l1 l2 c1 c2)
covered=(0 0 0 0 0)
fitted=0
start=$SECONDS
for ((s = 1; s <= count; s++)); do
  awk -v seed="$s" 'BEGIN { srand(seed); print "t,x2,y2" }
    { x = 0.25 * cos($2) + 0.18 * cos($3); y = 0.25 * sin($2) + 0.18 * sin($3)
      u1 = rand(); u2 = rand(); if (u1 < 1e-300) u1 = 1e-300
      r = sqrt(-2 * log(u1)); nx = 0.001 * r * cos(6.283185307179586 * u2)
      ny = 0.001 * r * sin(6.283185307179586 * u2)
      printf "%.4f,%.7f,%.7f\n", $1, x + nx, y + ny }' truth.txt > tip.csv
  if ! "$dpend" fit tip.csv --body point --m1 0.3 --m2 0.25 --l1 0.24 --l2 0.19 \
       --fit-param m2,l,damping --output fit.h5 --force --quiet > fit.log 2>&1; then
    echo "series $s: the fit failed: $(tail -n 1 fit.log)"
    continue
  fi
  fitted=$((fitted + 1))
  # /fit/interval95 (P, 2): rows q1(t1) q2(t1) qdot1(t1) qdot2(t1) m2 l1 l2 c1 c2
  mapfile -t rows < <("$dpend" export fit.h5 /fit/interval95 | tail -n 5)
  for ((j = 0; j < 5; j++)); do
    if awk -v row="${rows[$j]}" -v v="${truth[$j]}" \
         'BEGIN { split(row, a, " "); exit !(a[1] <= v && v <= a[2]) }'; then
      covered[j]=$((covered[j] + 1))
    fi
  done
done
echo "tip_coverage: $fitted of $count tip-only series fitted in $((SECONDS - start)) s" \
     "(noise 1 mm, $(wc -l < truth.txt) samples each)"
fail=0
for ((j = 0; j < 5; j++)); do
  echo "  ${names[$j]} = ${truth[$j]}: its 95 % interval holds it in ${covered[$j]} of $count"
  ((covered[j] >= min)) || fail=1
done
if ((fail)); then
  echo "tip_coverage: FAIL (at least $min of $count needed for each)"; exit 1
fi
echo "tip_coverage: ok (at least $min of $count for each)"
