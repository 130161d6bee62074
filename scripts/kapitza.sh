#!/usr/bin/env bash
# Kapitza's pendulum (docs/kapitza.md): the compound pendulum (--links 1: one uniform rod,
# m = 1 kg, L = 1 m, g = 9.81 m/s^2) upside down on a pin vibrating vertically,
# y_A = a cos(w t), with w = sqrt(4 g / (3 L)) / 0.01 = 361.66 rad/s, so that the derived
# threshold of the inverted position is a_c = sqrt(4 g L / 3) / w = 0.01 m:
#   scripts/kapitza.sh [OUTDIR]        (OUTDIR defaults to docs/img)
# Runs `dpend simulate` (rk4, 64 steps a period of the pin) from 0.05 rad off upright, at
# rest, for a = 0.012 m (above a_c: stays up) and a = 0.008 m (below: falls), and for a
# sweep of a over [0.00525, 0.01975] m in steps of 0.0005 m (30 s each, the largest angle
# from upright reached, and the frequency of the slow oscillation of those that stay up),
# and draws OUTDIR/kapitza.png: the angle from the upward vertical against time for the
# two runs, and the sweep with a_c and Kapitza's slow frequency drawn in; prints the
# sweep (a [m], largest |angle| [rad], 1 stays up / 0 falls, slow angular frequency
# [rad/s] or NaN).
# DPEND: the dpend executable to use (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init kapitza.sh
[[ $# -le 1 ]] || { echo "usage: $0 [OUTDIR]" >&2; exit 2; }
if [[ $# -ge 1 ]]; then plot_abs out "$1"; else out="$(cd "$here/.." && pwd)/docs/img"; fi
plot_dpend
plot_tmpdir

# the case of docs/kapitza.md, at full precision
w=$(awk 'BEGIN { printf "%.17g", sqrt(4 * 9.81 / 3) / 0.01 }')
dt=$(awk -v w="$w" 'BEGIN { printf "%.17g", 2 * atan2(0, -1) / w / 64 }')
q0=$(awk 'BEGIN { printf "%.17g", atan2(1, 0) + 0.05 }')
a_c=0.01
fall=0.5                       # fallen: more than this from upright [rad]
up=$(awk 'BEGIN { printf "%.17g", atan2(1, 0) }')

# run A T_END DT_OUT NAME: simulate amplitude A [m] until T_END [s], sampled every
# DT_OUT [s], into $tmp/NAME.h5 and export t and the angle q (from the x axis) to
# $tmp/NAME.dat
run() {
  "$dpend" simulate --links 1 --m 1 --l 1 --g 9.81 --q "$q0" --w 0 \
    --support-amplitude "0,$1" --support-frequency "$w" --method rk4 --dt "$dt" \
    --t-end "$2" --output-dt "$3" --output "$tmp/$4.h5" > /dev/null ||
    plot_fail 1 "dpend simulate failed for a = $1 m"
  "$dpend" export "$tmp/$4.h5" /trajectory/t /trajectory/q > "$tmp/$4.dat" ||
    plot_fail 1 "dpend export failed for a = $1 m"
}

run 0.012 10 0.001 above
run 0.008 10 0.001 below
: > "$tmp/sweep.dat"
for k in $(seq 0 29); do
  a=$(awk -v k="$k" 'BEGIN { printf "%.5f", 0.00525 + 0.0005 * k }')
  run "$a" 30 0.005 sweep_run
  # largest |phi| (phi = q - pi/2), stays up (1) or falls (0), and for those that stay
  # up the frequency of the slow oscillation from the zero crossings of phi (linearly
  # interpolated; the fast ripple k a sin(phi) cos(w t) vanishes with phi)
  awk -v a="$a" -v fall="$fall" -v up="$up" '
    { d = $2 - up; ad = (d < 0 ? -d : d); if (ad > m) m = ad
      if (NR > 1 && (d > 0) != (dp > 0)) {
        tc = tp + ($1 - tp) * dp / (dp - d); n++; if (n == 1) t1 = tc; tn = tc }
      tp = $1; dp = d }
    END { st = (m < fall)
      if (st && n >= 3) om = sprintf("%.6g", atan2(0, -1) * (n - 1) / (tn - t1))
      else om = "NaN"
      printf "%s %.6g %d %s\n", a, m, st, om }' "$tmp/sweep_run.dat" >> "$tmp/sweep.dat"
  rm -f -- "$tmp/sweep_run.h5"
done

plot_begin "$out" kapitza.png
plot_run gnuplot -c "$here/plot/kapitza.gp" "$tmp/above.dat" "$tmp/below.dat" "$tmp/sweep.dat" \
  "$figdir/kapitza.png" "$a_c" "$fall" "$w" 9.81 1
printf '# a [m], largest |phi| [rad], stays up (1) or falls (0), slow frequency [rad/s]\n'
cat -- "$tmp/sweep.dat"
printf 'kapitza.sh: wrote %s/kapitza.png\n' "$out"
