#!/usr/bin/env bash
# Figures of the chaos commands (dpend lyapunov / divergence / poincare):
#   scripts/plot_chaos.sh FILE.h5 [OUTDIR]        (OUTDIR defaults to FILE's folder)
# The command that wrote FILE (its root attribute `command`) decides the figures:
#   lyapunov   -> lyapunov_convergence.png (running estimates against t, log time
#                 axis; |lambda_i(t)| on log-log axes with ln(t)/t for reference)
#                 lyapunov_spectrum.png (the exponents with their spread, and the
#                 pairing defects |l1+l4|, |l2+l3| against t beside 1 % of l1)
#   divergence -> divergence.png (log10|delta(t)|: pairs, their mean, fitted slope,
#                 Benettin's lambda1 for comparison, saturation level)
#   poincare   -> poincare.png (the section points, one colour per orbit)
# Several lyapunov files (same vectors): scripts/plot_chaos.sh --compare OUT.png F1.h5 F2.h5 ...
# overlays their running lambda1 with the batch-means spread of each.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() { echo "usage: $0 FILE.h5 [OUTDIR] | $0 --compare OUT.png FILE.h5..." >&2; exit 2; }
[[ $# -ge 1 ]] || usage

# attr FILE NAME: a scalar root attribute (strings without quotes), full precision
attr() {
  h5dump -m %.17g -a "/$2" "$1" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 | tr -d '"' || true
}
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

if [[ "$1" == "--compare" ]]; then
  [[ $# -ge 3 ]] || usage
  out="$2"; shift 2
  plots=""; i=0
  for h5 in "$@"; do
    [[ -r "$h5" ]] || { echo "plot_chaos.sh: cannot read '$h5'" >&2; exit 2; }
    i=$((i + 1))
    "$here/dpend" export "$h5" /lyapunov/t /lyapunov/running > "$tmp/c$i.dat"
    lam=$(h5dump -m %.17g -d /lyapunov/exponents "$h5" | sed -n 's/^ *(0): *\([^,]*\).*/\1/p')
    spr=$(h5dump -m %.17g -d /lyapunov/spread "$h5" | sed -n 's/^ *(0): *\([^,]*\).*/\1/p')
    rtol=$(attr "$h5" rtol)
    if [[ -n "$rtol" ]]; then step=$(printf 'rtol = %g' "$rtol"); else
      step=$(printf 'dt = %g s' "$(attr "$h5" dt)"); fi
    label=$(printf '%s, %s: %.4f ± %.4f' "$(attr "$h5" method)" "$step" "$lam" "$spr")
    plots+="'$tmp/c$i.dat' u 1:2 w l lw 1.5 lc $i t '$label', "
    plots+="${lam} w l lc $i dt 2 notitle, "
    echo "$lam $spr $i" >> "$tmp/final.dat"
  done
  gnuplot <<GP
set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11"
set output "$out"
set title "Largest Lyapunov exponent: running estimates of several methods / steps"
set xlabel "t [s]"; set ylabel "{/Symbol l}_1(t) [1/s]"
set logscale x; set grid; set key top left box opaque
set yrange [0.8:1.6]; set xrange [1:6000]
plot ${plots%, }, '$tmp/final.dat' u (3300*1.1**\$3):1:2:3 w yerrorbars lc variable pt 7 ps 0.6 \
     t "final value ± spread (batch means)"
GP
  echo "plot_chaos.sh: wrote $out"
  exit 0
fi

h5="$1"; out="${2:-$(dirname "$h5")}"
[[ -r "$h5" ]] || { echo "plot_chaos.sh: cannot read '$h5'" >&2; exit 2; }
mkdir -p "$out"
cmd=$(attr "$h5" command)
title="$(attr "$h5" method), dt = $(attr "$h5" dt) s, $(basename "$h5")"
title="${title//_/\\_}"   # gnuplot enhanced text: a literal underscore
case "$cmd" in
  lyapunov)
    "$here/dpend" export "$h5" /lyapunov/t /lyapunov/running > "$tmp/run.dat"
    "$here/dpend" export "$h5" /lyapunov/exponents /lyapunov/spread > "$tmp/spec.dat"
    gnuplot -e "run='$tmp/run.dat'; spec='$tmp/spec.dat'; outdir='$out'; title='$title'; \
      k=$(attr "$h5" vectors); tau=$(attr "$h5" tau)" "$here/lyapunov.gp"
    echo "plot_chaos.sh: wrote $out/lyapunov_convergence.png $out/lyapunov_spectrum.png"
    ;;
  divergence)
    "$here/dpend" export "$h5" /divergence/t /divergence/log10_delta \
      /divergence/log10_delta_pairs > "$tmp/div.dat"
    lam=$(attr "$h5" lyapunov); lam=${lam:-0}
    gnuplot -e "dat='$tmp/div.dat'; outfile='$out/divergence.png'; title='$title'; \
      slope=$(attr "$h5" slope); b=$(attr "$h5" fit_intercept); t0=$(attr "$h5" fit_start); \
      t1=$(attr "$h5" fit_end); sat=$(attr "$h5" saturation); lam=$lam; \
      npairs=$(attr "$h5" pairs); delta0=$(attr "$h5" delta0)" "$here/divergence.gp"
    echo "plot_chaos.sh: wrote $out/divergence.png"
    ;;
  poincare)
    "$here/dpend" export "$h5" /poincare/q /poincare/p /poincare/orbit > "$tmp/sec.dat"
    gnuplot -e "dat='$tmp/sec.dat'; outfile='$out/poincare.png'; title='$title'; \
      E=$(attr "$h5" energy); link=$(attr "$h5" section_link); \
      other=$(attr "$h5" other_link); angle=$(attr "$h5" section_angle); \
      dir=$(attr "$h5" section_direction); norb=$(attr "$h5" n_orbits)" "$here/poincare.gp"
    echo "plot_chaos.sh: wrote $out/poincare.png"
    ;;
  *)
    echo "plot_chaos.sh: '$h5' was not written by dpend lyapunov/divergence/poincare" >&2
    exit 2
    ;;
esac
