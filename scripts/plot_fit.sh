#!/usr/bin/env bash
# Figures of `dpend fit`:
#   scripts/plot_fit.sh FIT.h5 [OUTDIR]
#     fit_overlay.png (data and fitted model against t, one panel per link, or per
#     coordinate x_i, y_i for positions, the end of the fit window marked) and
#     fit_residuals.png (data - model, the horizon tolerance as a band); OUTDIR
#     defaults to FIT.h5's folder.
#   scripts/plot_fit.sh --horizon DATA.csv OUTDIR WINDOW... [-- FIT-OPTION...]
#     runs `dpend fit DATA.csv --fit-window W FIT-OPTION...` for every WINDOW (s) and
#     draws fit_horizon.png: the prediction horizon against the length of the fit
#     window (open marks: the model never left the tolerance before the data ended,
#     a lower bound).
# Figures go through a temporary directory and are moved into place once all are drawn
# (scripts/lib/output.sh); names and values reach gnuplot only as data (gnuplot -c).
# DPEND: the dpend executable to use (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_fit.sh
usage="usage: $0 FIT.h5 [OUTDIR] | $0 --horizon DATA.csv OUTDIR WINDOW... [-- FIT-OPTION...]"
[[ $# -ge 1 ]] || { echo "$usage" >&2; exit 2; }
# attr OBJECT NAME FILE: a scalar attribute at full precision, strings without quotes
attr() {
  h5dump -m %.17g -a "$1/$2" "$3" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 |
    sed 's/^"\(.*\)"$/\1/' || true
}

if [[ $1 == --horizon ]]; then
  [[ $# -ge 4 ]] || { echo "$usage" >&2; exit 2; }
  plot_abs csv "$2"
  plot_abs out "$3"
  shift 3
  [[ -f "$csv" && -r "$csv" ]] || plot_fail 2 "cannot read the data file"
  windows=()
  while [[ $# -gt 0 && $1 != -- ]]; do
    plot_number w "$1" "the fit window"
    windows+=("$w")
    shift
  done
  [[ ${#windows[@]} -ge 1 ]] || plot_fail 2 "give at least one WINDOW (s)"
  [[ $# -gt 0 ]] && shift   # the --
  plot_dpend
  plot_tmpdir
  : > "$tmp/horizon.dat"
  for a in "$@"; do   # the script's own scratch file: never the user's
    case $a in
      -o | --output | --output=* | --force | --fit-window | --fit-window=*)
        plot_fail 2 "fit option '$a' is set by the script (only model and fit options after --)" ;;
    esac
  done
  for w in "${windows[@]}"; do
    # a refusal (exit 2: bad data, the fit's work beyond its limit) stays exit 2; the
    # last line of the log is dpend's message (progress lines come before it)
    st=0
    "$dpend" fit "$csv" "$@" --fit-window "$w" --output "$tmp/w.h5" --force \
      > "$tmp/fit.log" 2>&1 || st=$?
    ((st == 0)) || plot_fail $((st == 2 ? 2 : 1)) \
      "dpend fit --fit-window $w failed: $(tail -n1 "$tmp/fit.log")"
    t1=$("$dpend" export "$tmp/w.h5" /fit/t | awk 'NR == 1 { print $1 }')
    tw=$("$dpend" export "$tmp/w.h5" /fit/t_window | tr -d ' ')
    hz=$("$dpend" export "$tmp/w.h5" /fit/horizon | tr -d ' ')
    after=$(attr /fit has_after "$tmp/w.h5")
    cens=$(attr /fit horizon_censored "$tmp/w.h5")
    [[ $after == 1 ]] || continue   # no samples after the window: no horizon
    printf '%s %s %s %s\n' "$t1" "$tw" "$hz" "${cens:-0}" >> "$tmp/horizon.dat"
  done
  [[ -s "$tmp/horizon.dat" ]] || plot_fail 2 "no window leaves samples after it"
  plot_base name "$csv"
  plot_enhanced title "$name"
  plot_begin "$out" fit_horizon.png
  plot_run gnuplot -c "$here/plot/fit.gp" horizon "$tmp/horizon.dat" "$figdir" "$title"
  printf 'plot_fit.sh: wrote %s/fit_horizon.png\n' "$out"
  exit 0
fi

[[ $# -le 2 ]] || { echo "$usage" >&2; exit 2; }
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
plot_dpend
plot_tmpdir
links=$(attr "" links "$h5")
labels=
if [[ $(attr /fit observations "$h5") == coordinates ]]; then
  # a model's coordinates (dpend fit --model): their count, names and units
  links=$(attr /fit n_coordinates "$h5")
  labels=$(attr /fit coordinate_labels "$h5")
  [[ $labels =~ ^[A-Za-z0-9_]+:[A-Za-z0-9/^_]+( [A-Za-z0-9_]+:[A-Za-z0-9/^_]+)*$ ]] ||
    plot_fail 2 "'$1' is not a dpend fit file (coordinate_labels)"
fi
[[ $links =~ ^[1-9][0-9]*$ ]] || plot_fail 2 "'$1' is not a dpend fit file (no links)"
# columns: t data(1..M) model(1..M) residual(1..M) in_window, M = N angles or 2N
# positions (x1 y1 ... xN yN of the link ends) or the model's coordinates
if [[ -n $labels ]]; then
  kind=model
  cols=$links
  "$dpend" export "$h5" /fit/t /fit/q_data /fit/q_model /fit/residual /fit/in_window \
    > "$tmp/fit.dat" || plot_fail 2 "'$1' is not a dpend fit file"
elif [[ $(attr /fit observations "$h5") == positions ]]; then
  kind=xy
  cols=$((2 * links))
  # the points observed (a tip-only series: '2'), in the order of the columns
  points=$(attr /fit observed_points "$h5")
  if [[ -n $points ]]; then
    [[ $points =~ ^[1-9][0-9]?( [1-9][0-9]?)*$ ]] ||
      plot_fail 2 "'$1' is not a dpend fit file (observed_points)"
    read -r -a pts <<< "$points"
    cols=$((2 * ${#pts[@]}))
    kind="xy $points"
  fi
  "$dpend" export "$h5" /fit/t /fit/xy_data /fit/xy_model /fit/residual /fit/in_window \
    > "$tmp/fit.dat" || plot_fail 2 "'$1' is not a dpend fit file"
else
  kind=q
  cols=$links
  "$dpend" export "$h5" /fit/t /fit/q_data /fit/q_model /fit/residual /fit/in_window \
    > "$tmp/fit.dat" || plot_fail 2 "'$1' is not a dpend fit file"
fi
tw=$("$dpend" export "$h5" /fit/t_window | tr -d ' ')
tol=$(attr /fit horizon_tolerance "$h5")
rms=$(attr /fit rms_residual "$h5")
plot_number tw "$tw" "the fit window of '$1'"
plot_number tol "${tol:-0.1}" "the horizon tolerance of '$1'"
plot_number rms "${rms:-0}" "the RMS residual of '$1'"
# the prediction horizon after the window (s), when samples follow it; else -1
hz=-1
if [[ $(attr /fit has_after "$h5") == 1 ]]; then
  hz=$("$dpend" export "$h5" /fit/horizon | tr -d ' ')
  plot_number hz "$hz" "the prediction horizon of '$1'"
fi
plot_base name "$1"
plot_enhanced title "$name"
plot_begin "$out" fit_overlay.png fit_residuals.png
plot_run gnuplot -c "$here/plot/fit.gp" fit "$tmp/fit.dat" "$figdir" "$title" "$cols" "$tw" \
  "$tol" "$rms $hz" "$kind${labels:+ $labels}"
printf 'plot_fit.sh: wrote %s/{fit_overlay,fit_residuals}.png\n' "$out"
