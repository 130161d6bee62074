#!/usr/bin/env bash
# Figures of the chaos commands (dpend lyapunov / divergence / poincare / indicators):
#   scripts/plot_chaos.sh FILE.h5 [OUTDIR]        (OUTDIR defaults to FILE's folder)
# The command that wrote FILE (its root attribute `command`) decides the figures:
#   lyapunov   -> lyapunov_convergence.png (running estimates against t, log time
#                 axis; |lambda_i(t)| on log-log axes with ln(t)/t for reference)
#                 lyapunov_spectrum.png (the exponents with their spread, and for
#                 the full spectrum of N links (2N exponents) the pairing defects
#                 |l_i + l_(2N+1-i)|, i = 1..N, against t beside 1 % of l1)
#   divergence -> divergence.png (log10|delta(t)|: pairs, their mean, fitted slope,
#                 Benettin's lambda1 for comparison, saturation level)
#   poincare   -> poincare.png (the section points, one colour per orbit)
#   indicators -> indicators.png (MEGNO Y and <Y>, FLI, SALI and GALI_k against t,
#                 with the reference behaviours of the orbit's kind, regular or
#                 chaotic, drawn in: scripts/plot/indicators.gp)
# Every figure: text scaled with the canvas, pi tics on angle axes (scripts/plot/style.gp);
# the key entries drawn go to $DPEND_PLOT_KEYS when set (the figure test).
# Several lyapunov files (same vectors): scripts/plot_chaos.sh --compare OUT.png F1.h5 F2.h5 ...
# overlays their running lambda1 with the batch-means spread of each.
# Figures are written through temporary files and moved into place once drawn
# (scripts/lib/output.sh). DPEND: the dpend executable (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_chaos.sh
usage() { echo "usage: $0 FILE.h5 [OUTDIR] | $0 --compare OUT.png FILE.h5..." >&2; exit 2; }
[[ $# -ge 1 ]] || usage

# attr FILE NAME: a scalar root attribute (strings without quotes), full precision
attr() {
  h5dump -m %.17g -a "/$2" "$1" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 | tr -d '"' || true
}
# num VAR FILE NAME [DEFAULT]: VAR := the numeric root attribute NAME of FILE
num() {
  local v
  v=$(attr "$2" "$3")
  [[ -n "$v" || $# -lt 4 ]] || v=$4
  plot_number "$1" "$v" "the attribute $3 of '$2'"
}

if [[ "$1" == "--compare" ]]; then
  [[ $# -ge 3 ]] || usage
  out=$2; shift 2
  [[ "$out" != */ ]] || plot_fail 2 "--compare wants a file name, not '$out'"
  plot_dir outdir "$out"; plot_base outname "$out"
  plot_dpend
  plot_tmpdir
  labels=""; lams=""; i=0
  for f in "$@"; do
    [[ -f "$f" && -r "$f" ]] || plot_fail 2 "cannot read '$f'"
    plot_abs h5 "$f"
    i=$((i + 1))
    "$dpend" export "$h5" /lyapunov/t /lyapunov/running > "$tmp/c$i.dat"
    # lambda1 and its spread: the first row (h5dump's "(0):" would also match the
    # datasets' string attributes)
    "$dpend" export "$h5" /lyapunov/exponents /lyapunov/spread > "$tmp/s$i.dat"
    read -r lam spr _ < "$tmp/s$i.dat" || true
    plot_number lam "$lam" "lambda1 of '$f'"
    plot_number spr "$spr" "the spread of lambda1 of '$f'"
    rtol=$(attr "$h5" rtol)
    if [[ -n "$rtol" ]]; then
      plot_number rtol "$rtol" "the attribute rtol of '$f'"
      step=$(printf 'rtol = %g' "$rtol")
    else
      num dt "$h5" dt
      step=$(printf 'dt = %g s' "$dt")
    fi
    plot_enhanced method "$(attr "$h5" method)"
    label=$(printf '%s, %s: %.4f ± %.4f' "$method" "$step" "$lam" "$spr")
    labels+="${labels:+$'\n'}$label"
    lams+="${lams:+ }$lam"
    echo "$lam $spr $i" >> "$tmp/final.dat"
  done
  plot_begin "$outdir" "$outname"
  plot_run gnuplot -c "$here/plot/compare.gp" "$tmp" "$figdir/$outname" "$i" "$labels" "$lams"
  printf 'plot_chaos.sh: wrote %s\n' "$out"
  exit 0
fi

[[ $# -le 2 ]] || usage
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
plot_dpend
plot_tmpdir
cmd=$(attr "$h5" command)
plot_base name "$1"
plot_enhanced title "$(attr "$h5" method), dt = $(attr "$h5" dt) s, $name"
case "$cmd" in
  lyapunov)
    "$dpend" export "$h5" /lyapunov/t /lyapunov/running > "$tmp/run.dat"
    "$dpend" export "$h5" /lyapunov/exponents /lyapunov/spread > "$tmp/spec.dat"
    num k "$h5" vectors
    num links "$h5" links 2   # files from before --links: the double pendulum
    plot_begin "$out" lyapunov_convergence.png lyapunov_spectrum.png
    plot_run gnuplot -c "$here/plot/lyapunov.gp" "$tmp/run.dat" "$tmp/spec.dat" "$figdir" \
      "$title" "$k" "$links"
    printf 'plot_chaos.sh: wrote %s/lyapunov_convergence.png %s/lyapunov_spectrum.png\n' \
      "$out" "$out"
    ;;
  divergence)
    "$dpend" export "$h5" /divergence/t /divergence/log10_delta \
      /divergence/log10_delta_pairs > "$tmp/div.dat"
    num slope "$h5" slope; num b "$h5" fit_intercept; num t0 "$h5" fit_start
    num t1 "$h5" fit_end; num sat "$h5" saturation; num lam "$h5" lyapunov 0
    num npairs "$h5" pairs; num delta0 "$h5" delta0
    plot_begin "$out" divergence.png
    plot_run gnuplot -c "$here/plot/divergence.gp" "$tmp/div.dat" "$figdir" "$title" \
      "$slope $b $t0 $t1 $sat $lam $npairs $delta0"
    printf 'plot_chaos.sh: wrote %s/divergence.png\n' "$out"
    ;;
  poincare)
    "$dpend" export "$h5" /poincare/q /poincare/p /poincare/orbit > "$tmp/sec.dat"
    num E "$h5" energy; num link "$h5" section_link; num other "$h5" other_link
    num angle "$h5" section_angle; num dir "$h5" section_direction
    num norb "$h5" n_orbits
    plot_begin "$out" poincare.png
    plot_run gnuplot -c "$here/plot/poincare.gp" "$tmp/sec.dat" "$figdir" "$title" \
      "$E $link $other $angle $dir $norb"
    printf 'plot_chaos.sh: wrote %s/poincare.png\n' "$out"
    ;;
  indicators)
    "$dpend" export "$h5" /indicators/t /indicators/megno /indicators/megno_mean \
      /indicators/fli /indicators/sali /indicators/gali > "$tmp/ind.dat"
    num k "$h5" vectors; num links "$h5" links 2
    num tend "$h5" t_reached; num fli "$h5" fli_final
    # the final GALI_2 .. GALI_K (h5dump: "(i): v1, v2, ..." lines)
    read -r -a gvals <<< "$(h5dump -m %.17g -a /gali_final "$h5" 2>/dev/null \
      | sed -n 's/^ *([0-9]*): *//p' | tr ',\n' '  ')"
    [[ ${#gvals[@]} -eq $((k - 1)) ]] ||
      plot_fail 2 "'$1': gali_final holds ${#gvals[@]} values, not $((k - 1))"
    gal=""
    for v in "${gvals[@]}"; do
      plot_number g "$v" "a value of the attribute gali_final of '$1'"
      gal+=" $g"
    done
    plot_begin "$out" indicators.png
    plot_run gnuplot -c "$here/plot/indicators.gp" "$tmp/ind.dat" "$figdir" "$title" \
      "$k $links $tend $fli$gal"
    printf 'plot_chaos.sh: wrote %s/indicators.png\n' "$out"
    ;;
  *)
    plot_fail 2 "'$1' was not written by dpend lyapunov/divergence/poincare/indicators"
    ;;
esac
