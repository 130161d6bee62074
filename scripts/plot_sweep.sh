#!/usr/bin/env bash
# Turn the .h5 of `dpend sweep` (a grid) into PNG maps:
#   scripts/plot_sweep.sh FILE.h5 [OUTDIR] [--time-unit natural|s]
#   (OUTDIR defaults to FILE's folder; the time unit to the sweep's own, its
#   attribute time_unit: natural unless the sweep ran with --time-unit s)
# Writes flip_map.png (first flip of any link, log colour scale in sqrt(l1/g) or
# in s, white: no flip before the end), flip_map_link1.png .. flip_map_linkN.png (N the
# attribute /sweep@links, 2 for files without it),
# energy_error.png and, if the sweep has them, lyapunov.png and the map of its
# indicator (dpend sweep --indicator): megno.png (<Y> over [0, 4], 2 the value of
# regular orbits), fli.png, sali.png or gali2.png (log scales, 0 for
# chaos); every map in viridis (scripts/plot/style.gp); angle axes ticked in multiples of
# pi; parameter axes (m1 .. l2/l1) are labelled in kg, m or as ratios; on every map the initial
# conditions not integrated (status 0 or 4: a partial file, a non-finite state) are
# grey, a colour viridis does not hold, with a key entry only when a pixel is grey
# (the key entries drawn: $DPEND_PLOT_KEYS, scripts/lib/output.sh). Figures are written
# through temporary files and moved into place once drawn (scripts/lib/output.sh).
# DPEND: the dpend executable (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_sweep.sh
# --time-unit natural (sqrt(l1/g)) or s: the unit of the flip-time colour scales
# and of the Lyapunov map (1/sqrt(l1/g) or 1/s); default: the sweep's own unit
unit=
args=()
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) sed -n '2,/^# DPEND:/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; exit 0 ;;
    --time-unit) [[ $# -ge 2 ]] || { echo "$0: --time-unit needs natural or s" >&2; exit 2; }
                 unit=$2; shift 2 ;;
    --time-unit=*) unit=${1#--time-unit=}; shift ;;
    *) args+=("$1"); shift ;;
  esac
done
[[ -z $unit || $unit == natural || $unit == s ]] ||
  { echo "$0: invalid --time-unit '$unit' (accepted: natural, s)" >&2; exit 2; }
set -- "${args[@]}"
[[ $# -ge 1 && $# -le 2 ]] || { echo "usage: $0 FILE.h5 [OUTDIR] [--time-unit natural|s]" >&2; exit 2; }
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
# a scalar attribute of /sweep, numbers at full precision, strings without quotes
attr() { h5dump -m %.17g -a "/sweep/$1" "$h5" 2>/dev/null | sed -n 's/^ *(0): *"\{0,1\}\([^"]*\)"\{0,1\}.*/\1/p' | head -n1; }
[[ "$(attr initial)" == grid ]] || plot_fail 2 "'$1' is not a grid sweep"
# a model without flips (the elastic pendulum) has no t_flip maps to draw here
if [[ -n "$(attr model)" && -z "$(attr sqrt_l1_over_g)" ]]; then
  plot_fail 2 "'$1' is a sweep of model $(attr model), which has no flip maps; this script draws the pendulum's (export its indicator map with dpend export FILE --matrix /sweep/megno /sweep/axis1 /sweep/axis2)"
fi
plot_number tau "$(attr sqrt_l1_over_g)" "the attribute sqrt_l1_over_g of '$1'"
if [[ -z $unit ]]; then   # the sweep's own unit (files before it: natural)
  unit=$(attr time_unit || true)
  [[ $unit == s ]] || unit=natural
fi
plot_number t_end "$(attr t_end)" "the attribute t_end of '$1'"
ax1=$(attr axis1); ax2=$(attr axis2)
links=$(attr links)
[[ -z "$links" ]] && links=2   # files written before the N-link chain: the double pendulum
[[ "$links" =~ ^[1-9][0-9]?$ ]] || plot_fail 2 "the attribute links of '$1' is not 1 to 99"
plot_dpend
plot_tmpdir
ex() { "$dpend" export "$h5" --matrix "$1" /sweep/axis1 /sweep/axis2 "$2" > "$tmp/$3"; }
fscale=$tau   # the flip times' unit: sqrt(l1/g), or s
[[ $unit == s ]] && fscale=1
ex /sweep/t_flip "$fscale" flip.dat
figures=(flip_map.png)
printf '%s\n' "$links" > "$tmp/links"   # read by sweep.gp
printf '%s\n' "$([[ $unit == s ]] && echo 1 || echo 0)" > "$tmp/seconds"   # read by sweep.gp
for ((k = 1; k <= links; k++)); do
  ex "/sweep/t_flip$k" "$fscale" "flip$k.dat"
  figures+=("flip_map_link$k.png")
done
ex /sweep/energy_error 1 eerr.dat
# a damped or driven chain's energy_error is that of its energy balance (its description)
balance=0
h5dump -a /sweep/energy_error/description "$h5" 2> /dev/null | grep -q 'energy balance' && balance=1
printf '%s\n' "$balance" > "$tmp/balance"   # read by sweep.gp
lyap=""
figures+=(energy_error.png)
if h5dump -H -d /sweep/lyapunov "$h5" >/dev/null 2>&1; then
  # in 1/s (sweep.gp multiplies by tau): no SCALE above 1 for `dpend export`
  "$dpend" export "$h5" --matrix /sweep/lyapunov /sweep/axis1 /sweep/axis2 > "$tmp/lyap.dat"
  lyap="$tmp/lyap.dat"
  figures+=(lyapunov.png)
fi
# the fast indicator, if any: its code in $tmp/indicator (read by sweep.gp: 0 none,
# 1 megno, 2 fli, 3 sali, 4 gali2), its matrix in $tmp/ind.dat
ind=0
for name_code in megno:1 fli:2 sali:3 gali2:4; do
  if h5dump -H -d "/sweep/${name_code%%:*}" "$h5" >/dev/null 2>&1; then
    ind=${name_code##*:}
    ex "/sweep/${name_code%%:*}" 1 ind.dat
    figures+=("${name_code%%:*}.png")
    break
  fi
done
printf '%s\n' "$ind" > "$tmp/indicator"
# status of every initial condition: 0 (not computed) and 4 (non-finite) are drawn
# grey, "not integrated", on every map
status=""
if h5dump -H -d /sweep/status "$h5" >/dev/null 2>&1; then
  ex /sweep/status 1 status.dat
  status="$tmp/status.dat"
fi
plot_base name "$1"
# links other than uniform rods say so in every title: 'point masses on massless rods'
body=$(attr body || true)   # (none for uniform rods)
if [[ -n $body ]]; then
  body=${body%% (*}
  name="$name: ${body%%;*}"
fi
plot_enhanced name "$name"
plot_begin "$out" "${figures[@]}"
# (no-flip pixels are NaN on purpose: gnuplot leaves them white and warns)
plot_run gnuplot -c "$here/plot/sweep.gp" "$tmp" "$figdir" "$t_end" "$tau" "$ax1" "$ax2" \
  "$lyap" "$name" "$status" 2> >(grep -v -e 'matrix contains missing or undefined values' >&2)
if [[ $links == 2 ]]; then
  printf 'plot_sweep.sh: wrote %s/{flip_map,flip_map_link1,flip_map_link2,energy_error}.png%s\n' \
    "$out" "${lyap:+ and lyapunov.png}"
  ((ind > 0)) && printf 'plot_sweep.sh: wrote %s/%s\n' "$out" "${figures[-1]}"
else
  maps=flip_map_link1
  ((links > 1)) && maps+="..$links"
  printf 'plot_sweep.sh: wrote %s/{flip_map,%s,energy_error}.png%s\n' \
    "$out" "$maps" "${lyap:+ and lyapunov.png}"
  ((ind > 0)) && printf 'plot_sweep.sh: wrote %s/%s\n' "$out" "${figures[-1]}"
fi
exit 0
