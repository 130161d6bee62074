#!/usr/bin/env bash
# Figures of `dpend torques` and `dpend identify`:
#   scripts/plot_torques.sh TORQUES.h5 [OUTDIR]
#     inverse_torques.png: the joint torques the motion requires against t, one panel
#     per joint, with the measured torques when the file has them; and, with them,
#     inverse_residual.png: measured - computed, with the filter's predicted error
#     (noise and bias combined) as a band.
#   scripts/plot_torques.sh IDENTIFY.h5 [OUTDIR]
#     identify_residual.png: the torque residual of the identified model at the rows
#     used, one panel per joint, with its RMS.
#   OUTDIR defaults to the file's folder.
# Figures go through a temporary directory and are moved into place once all are drawn
# (scripts/lib/output.sh); names and values reach gnuplot only as data (gnuplot -c).
# DPEND: the dpend executable to use (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_torques.sh
usage="usage: $0 TORQUES.h5|IDENTIFY.h5 [OUTDIR]"
[[ $# -ge 1 && $# -le 2 ]] || { echo "$usage" >&2; exit 2; }
# attr NAME FILE: a root attribute at full precision, strings without quotes
attr() {
  h5dump -m %.17g -a "/$1" "$2" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 |
    sed 's/^"\(.*\)"$/\1/' || true
}
# attr_list NAME FILE: every value of a root attribute, blank-separated
attr_list() {
  h5dump -m %.17g -a "/$1" "$2" 2>/dev/null | sed -n 's/^ *([0-9]*): *//p' | tr ',' ' ' |
    tr -s ' \n' ' ' || true
}
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
plot_dpend
plot_tmpdir
command=$(attr command "$h5")
links=$(attr links "$h5")
[[ $links =~ ^[1-9][0-9]*$ ]] || plot_fail 2 "'$1' is not a dpend torques or identify file"
plot_base name "$1"
plot_enhanced title "$name"
case $command in
  torques)
    measured=0
    if "$dpend" export "$h5" --list | grep -q '^/torques/tau_measured '; then measured=1; fi
    if ((measured)); then
      "$dpend" export "$h5" /torques/t /torques/tau /torques/tau_measured \
        /torques/residual > "$tmp/t.dat" || plot_fail 2 "'$1' is not a dpend torques file"
    else
      "$dpend" export "$h5" /torques/t /torques/tau > "$tmp/t.dat" ||
        plot_fail 2 "'$1' is not a dpend torques file"
    fi
    # the predicted error per joint: sqrt(noise^2 + bias^2)
    read -r -a noise <<< "$(attr_list predicted_tau_noise "$h5")"
    read -r -a bias <<< "$(attr_list predicted_tau_bias "$h5")"
    band=
    for ((i = 0; i < links; i++)); do
      plot_number nz "${noise[i]:-0}" "the predicted noise of '$1'"
      plot_number bz "${bias[i]:-0}" "the predicted bias of '$1'"
      band="$band $(awk -v a="$nz" -v b="$bz" 'BEGIN { printf "%.6g", sqrt(a*a + b*b) }')"
    done
    window=$(attr window "$h5")
    plot_number window "$window" "the window of '$1'"
    if ((measured)); then
      plot_begin "$out" inverse_torques.png inverse_residual.png
    else
      plot_begin "$out" inverse_torques.png
    fi
    plot_run gnuplot -c "$here/plot/inverse.gp" torques "$tmp/t.dat" "$figdir" "$title" \
      "$links" "$measured" "${band# }" "$window"
    if ((measured)); then
      printf 'plot_torques.sh: wrote %s/{inverse_torques,inverse_residual}.png\n' "$out"
    else
      printf 'plot_torques.sh: wrote %s/inverse_torques.png\n' "$out"
    fi
    ;;
  identify)
    "$dpend" export "$h5" /identify/t /identify/residual > "$tmp/t.dat" ||
      plot_fail 2 "'$1' is not a dpend identify file"
    rms=$("$dpend" export "$h5" /identify/sigma_joint | tr -s ' \n' ' ')
    plot_begin "$out" identify_residual.png
    plot_run gnuplot -c "$here/plot/inverse.gp" identify "$tmp/t.dat" "$figdir" "$title" \
      "$links" 1 "${rms# }" 0
    printf 'plot_torques.sh: wrote %s/identify_residual.png\n' "$out"
    ;;
  *) plot_fail 2 "'$1' is not a dpend torques or identify file (command '$command')" ;;
esac
