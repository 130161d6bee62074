#!/usr/bin/env bash
# Turn the .h5 of `dpend simulate` into PNG figures:
#   scripts/plot_simulate.sh FILE.h5 [OUTDIR]   (OUTDIR defaults to FILE's folder)
# Draws what the file describes (its root attributes coordinates, draw_points,
# draw_forces, draw_style and the units of /trajectory/q: docs/hdf5-layout.md), for
# every model; it never infers the model from the number of links.
# Writes angles.png (the coordinates, unwrapped), angles_wrapped.png (angles wrapped
# to (-pi, pi]), phase.png (qdot against q, one panel per coordinate),
# energy_error.png, reactions.png (the figure's forces, for rods F_joint, the force of
# body i-1 on body i at joint i: one panel per joint up to 4, the magnitudes beyond),
# tip_path.png (the last point: the free end of link N, or the mass), and for a
# damped or driven run balance.png (the energy
# balance), with applied joint torques torques.png (each through a temporary file, moved into place once all
# are drawn: scripts/lib/output.sh). Attributes are read at full precision
# (h5dump -m %.17g). DPEND: the dpend executable to use (default: the release build).
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
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
# attr NAME: a scalar root attribute, numbers at full precision, strings without quotes
attr() {
  h5dump -m %.17g -a "/$1" "$h5" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 |
    sed 's/^"\(.*\)"$/\1/' || true
}
# rows DATASET COLS: the numbers of DATASET, full precision, COLS to a row (a
# (samples, N, 2) dataset: one row per sample; dpend export reads 1-D and 2-D only)
rows() {
  h5dump -m %.17g -y -w 0 -d "$1" -o "$tmp/raw.txt" "$h5" > /dev/null ||
    plot_fail 1 "cannot read $1 of '$h5'"
  tr -s ', \t' '\n' < "$tmp/raw.txt" | awk -v c="$2" 'NF {
      line = line (k ? " " : "") $1; k++
      if (k == c) { print line; line = ""; k = 0 } }'
}
# dims DATASET: its dimensions as h5py shows them, blank-separated ("101 2 2")
dims() {
  h5dump -H -d "$1" "$h5" 2>/dev/null | sed -n 's/.*DATASPACE *SIMPLE *{ *( *\([0-9, ]*\) *).*/\1/p' |
    head -n1 | tr -d ','
}
# has NAME: the file holds the dataset /trajectory/NAME
has() { grep -qx " *dataset */trajectory/$1" "$tmp/contents.txt"; }
h5dump -n "$h5" > "$tmp/contents.txt" 2>/dev/null || plot_fail 1 "cannot list '$1'"
# The figure as the file describes it (root attributes coordinates, draw_points,
# draw_forces, draw_style; the units of /trajectory/q). A file from before the
# description (without them) is the pendulum of `links` rods.
coords=$(attr coordinates)
points=$(attr draw_points)
forces=$(attr draw_forces)
style=$(attr draw_style)
if [[ -z $coords ]]; then
  links=$(attr links)
  links=${links:-2}
  [[ $links =~ ^[1-9][0-9]*$ ]] ||
    plot_fail 2 "the attribute links of '$1' is not a count: '$links'"
  coords=$(seq -f 'q%g' -s ' ' 1 "$links")
  style=rods
  if has rJ; then points=rJ; forces=F_joint; fi
fi
read -r -a cnames <<< "$coords"
n=${#cnames[@]}
((n >= 1 && n <= 1000)) || plot_fail 2 "the attribute coordinates of '$1' names no coordinate"
for w in "${cnames[@]}"; do
  [[ $w =~ ^[A-Za-z][A-Za-z0-9_]*$ ]] ||
    plot_fail 2 "coordinate name '$w' of '$1' is not a plain name"
done
# the units of q: one for all ("rad") or one per coordinate ("m, rad")
qunits=$( (h5dump -a /trajectory/q/units "$h5" 2>/dev/null || true) |
  sed -n 's/^ *(0): *"\(.*\)"$/\1/p' | head -n1)
if [[ -z $qunits ]]; then
  # a file from before the units (the pendulum's angles), or one that lost them
  echo "plot_simulate.sh: note: /trajectory/q of '$1' gives no units; taken as rad" >&2
  qunits=rad
fi
IFS=', ' read -r -a ulist <<< "$qunits"
if ((${#ulist[@]} == 1)); then
  for ((i = 1; i < n; i++)); do ulist+=("${ulist[0]}"); done
fi
((${#ulist[@]} == n)) ||
  plot_fail 2 "the units of /trajectory/q of '$1' do not match its $n coordinates"
for w in "${ulist[@]}"; do
  [[ $w =~ ^[A-Za-z0-9^/._-]+$ ]] || plot_fail 2 "unit '$w' of '$1' is not a plain unit"
done
[[ $style =~ ^[a-z]*$ ]] || plot_fail 2 "the attribute draw_style of '$1' is not a style"
"$dpend" export "$h5" /trajectory/t /trajectory/q /trajectory/energy /trajectory/qdot \
  > "$tmp/a.dat"
samples=$(wc -l < "$tmp/a.dat")
if [[ -n $points ]]; then
  [[ $points =~ ^[A-Za-z][A-Za-z0-9_]*$ && $forces =~ ^[A-Za-z][A-Za-z0-9_]*$ ]] ||
    plot_fail 2 "the attributes draw_points, draw_forces of '$1' are not dataset names"
  # the forces (x, y of each row) and the last point of the figure
  read -r -a fd <<< "$(dims "/trajectory/$forces")"
  read -r -a pd <<< "$(dims "/trajectory/$points")"
  if ((${#fd[@]} == 3)); then k=${fd[1]}; else k=1; fi
  if ((${#pd[@]} == 3)); then np=${pd[1]}; else np=1; fi
  [[ ${fd[0]:-} == "$samples" && ${pd[0]:-} == "$samples" ]] ||
    plot_fail 1 "the /trajectory datasets of '$1' differ in length"
  rows "/trajectory/$forces" $((2 * k)) > "$tmp/f.dat"
  rows "/trajectory/$points" $((2 * np)) | awk '{ print $(NF - 1), $NF }' > "$tmp/tip.dat"
elif has F01; then
  # a double pendulum file from before the per-link layout: F01, -F21 (joint 2: link 1
  # on link 2) and the tip 2 rC2 - rB
  k=2
  "$dpend" export "$h5" /trajectory/F01 /trajectory/F21 /trajectory/rC2 /trajectory/rB |
    awk -v tip="$tmp/tip.dat" '{ print $1, $2, -$3, -$4; print 2 * $5 - $7, 2 * $6 - $8 > tip }' \
    > "$tmp/f.dat"
else
  plot_fail 2 "'$1' describes no figure (no draw_points attribute, no F01)"
fi
[[ $(wc -l < "$tmp/f.dat") -eq $samples && $(wc -l < "$tmp/tip.dat") -eq $samples ]] ||
  plot_fail 1 "the /trajectory datasets of '$1' differ in length"
paste -d ' ' "$tmp/a.dat" "$tmp/f.dat" "$tmp/tip.dat" > "$tmp/sim.dat"
# a damped or driven run writes its energy balance: its energy is not conserved
if has balance_error; then conserved=0; else conserved=1; fi
method=$(attr method)
escale=$(attr energy_scale)
plot_number escale "${escale:-1.0}" "the attribute energy_scale of '$1'"
plot_base name "$1"
plot_enhanced title "${method:-dpend}, $name"
plot_begin "$out" angles.png angles_wrapped.png phase.png energy_error.png reactions.png \
  tip_path.png
plot_run gnuplot -c "$here/plot/simulate.gp" "$tmp/sim.dat" "$figdir" "$title" "$escale" "$n" \
  "${cnames[*]}" "${ulist[*]}" "$k" "${style:-rods} $conserved"
printf 'plot_simulate.sh: wrote %s/{angles,angles_wrapped,phase,energy_error,reactions,tip_path}.png\n' "$out"
if ((conserved == 0)); then
  # a damped or driven run: E(t) - E(0), the work of the friction, of the support
  # (and of applied joint torques), and the balance error E(t) - E(0) + W_friction -
  # W_support (- W_torque)
  columns=(/trajectory/t /trajectory/energy /trajectory/W_friction /trajectory/W_support
    /trajectory/balance_error)
  if has W_torque; then columns+=(/trajectory/W_torque); torque=1; else torque=0; fi
  "$dpend" export "$h5" "${columns[@]}" > "$tmp/balance.dat"
  plot_begin "$out" balance.png
  plot_run gnuplot -c "$here/plot/balance.gp" "$tmp/balance.dat" "$figdir" "$title" "$escale" \
    "$torque"
  printf 'plot_simulate.sh: wrote %s/balance.png\n' "$out"
fi
if has tau; then
  # applied joint torques: tau_1 .. tau_N against t
  "$dpend" export "$h5" /trajectory/t /trajectory/tau > "$tmp/tau.dat"
  plot_begin "$out" torques.png
  plot_run gnuplot -c "$here/plot/torques.gp" "$tmp/tau.dat" "$figdir" "$title" "$n"
  printf 'plot_simulate.sh: wrote %s/torques.png\n' "$out"
fi
