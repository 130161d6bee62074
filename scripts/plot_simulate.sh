#!/usr/bin/env bash
# Turn the .h5 of `dpend simulate` into PNG figures:
#   scripts/plot_simulate.sh FILE.h5 [OUTDIR]   (OUTDIR defaults to FILE's folder)
# Writes angles.png, energy_error.png, reactions.png, tip_path.png.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
[[ $# -ge 1 ]] || { echo "usage: $0 FILE.h5 [OUTDIR]" >&2; exit 2; }
h5="$1"; out="${2:-$(dirname "$h5")}"
[[ -r "$h5" ]] || { echo "plot_simulate.sh: cannot read '$h5'" >&2; exit 2; }
mkdir -p "$out"
dat="$(mktemp)"; trap 'rm -f "$dat"' EXIT
"$here/dpend" export "$h5" /trajectory/t /trajectory/q /trajectory/energy \
  /trajectory/F01 /trajectory/F21 /trajectory/rC2 /trajectory/rB > "$dat"
method=$(h5dump -a /method "$h5" 2>/dev/null | sed -n 's/.*(0): "\(.*\)".*/\1/p' | head -n1)
escale=$(h5dump -a /energy_scale "$h5" 2>/dev/null | sed -n 's/.*(0): \([-+0-9.eE]*\).*/\1/p' | head -n1)
gnuplot -e "datafile='$dat'; outdir='$out'; Escale=${escale:-1.0}; title='${method:-dpend}, $(basename "$h5")'" \
  "$here/simulate.gp"
echo "plot_simulate.sh: wrote $out/{angles,energy_error,reactions,tip_path}.png"
