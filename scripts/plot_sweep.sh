#!/usr/bin/env bash
# Turn the .h5 of `dpend sweep` (a grid) into PNG maps:
#   scripts/plot_sweep.sh FILE.h5 [OUTDIR]   (OUTDIR defaults to FILE's folder)
# Writes flip_map.png (first flip of either link, log colour scale in sqrt(l1/g),
# white: no flip before the end), flip_map_link1.png, flip_map_link2.png,
# energy_error.png and, if the sweep has it, lyapunov.png.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
[[ $# -ge 1 ]] || { echo "usage: $0 FILE.h5 [OUTDIR]" >&2; exit 2; }
h5="$1"; out="${2:-$(dirname "$h5")}"
[[ -r "$h5" ]] || { echo "plot_sweep.sh: cannot read '$h5'" >&2; exit 2; }
mkdir -p "$out"
attr() { h5dump -a "/sweep/$1" "$h5" 2>/dev/null | sed -n 's/^ *(0): *"\{0,1\}\([^"]*\)"\{0,1\}.*/\1/p' | head -n1; }
[[ "$(attr initial)" == grid ]] || { echo "plot_sweep.sh: '$h5' is not a grid sweep" >&2; exit 2; }
tau=$(attr sqrt_l1_over_g); t_end=$(attr t_end); ax1=$(attr axis1); ax2=$(attr axis2)
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
ex() { "$here/dpend" export "$h5" --matrix "$1" /sweep/axis1 /sweep/axis2 "$2" > "$tmp/$3"; }
ex /sweep/t_flip "$tau" flip.dat
ex /sweep/t_flip1 "$tau" flip1.dat
ex /sweep/t_flip2 "$tau" flip2.dat
ex /sweep/energy_error 1 eerr.dat
lyap=""
if h5dump -H -d /sweep/lyapunov "$h5" >/dev/null 2>&1; then
  ex /sweep/lyapunov "$(awk "BEGIN { print 1 / $tau }")" lyap.dat   # x tau: in 1/sqrt(l1/g)
  lyap="$tmp/lyap.dat"
fi
gnuplot -e "dir='$tmp'; outdir='$out'; tend=$t_end/$tau; ax1='$ax1'; ax2='$ax2'; \
  lyap='$lyap'; name='$(basename "$h5" | sed 's/_/\\_/g')'" "$here/sweep.gp" \
  2> >(grep -v -e 'matrix contains missing or undefined values' >&2)
# (no-flip pixels are NaN on purpose: gnuplot leaves them white and warns)
echo "plot_sweep.sh: wrote $out/{flip_map,flip_map_link1,flip_map_link2,energy_error}.png${lyap:+ and lyapunov.png}"
