#!/usr/bin/env bash
# Turn the .h5 of `dpend simulate` into PNG figures:
#   scripts/plot_simulate.sh FILE.h5 [OUTDIR]   (OUTDIR defaults to FILE's folder)
# Writes angles.png (unwrapped), angles_wrapped.png (wrapped to (-pi, pi]), phase.png
# (qdot against wrapped q, one panel per link), energy_error.png, reactions.png,
# tip_path.png (each through a temporary file, moved into place once all are drawn:
# scripts/lib/output.sh). Attributes are read at full precision (h5dump -m %.17g).
# DPEND: the dpend executable to use (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_simulate.sh
[[ $# -ge 1 && $# -le 2 ]] || { echo "usage: $0 FILE.h5 [OUTDIR]" >&2; exit 2; }
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
plot_dpend
plot_tmpdir
"$dpend" export "$h5" /trajectory/t /trajectory/q /trajectory/energy \
  /trajectory/F01 /trajectory/F21 /trajectory/rC2 /trajectory/rB /trajectory/qdot \
  > "$tmp/sim.dat"
# attr NAME: a scalar root attribute, numbers at full precision, strings without quotes
attr() {
  h5dump -m %.17g -a "/$1" "$h5" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 |
    sed 's/^"\(.*\)"$/\1/' || true
}
method=$(attr method)
escale=$(attr energy_scale)
plot_number escale "${escale:-1.0}" "the attribute energy_scale of '$1'"
plot_base name "$1"
plot_enhanced title "${method:-dpend}, $name"
plot_begin "$out" angles.png angles_wrapped.png phase.png energy_error.png reactions.png \
  tip_path.png
plot_run gnuplot -c "$here/simulate.gp" "$tmp/sim.dat" "$figdir" "$title" "$escale"
printf 'plot_simulate.sh: wrote %s/{angles,angles_wrapped,phase,energy_error,reactions,tip_path}.png\n' "$out"
