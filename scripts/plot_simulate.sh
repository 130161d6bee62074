#!/usr/bin/env bash
# Turn the .h5 of `dpend simulate` into PNG figures:
#   scripts/plot_simulate.sh FILE.h5 [OUTDIR]   (OUTDIR defaults to FILE's folder)
# Works for any number of links N (the root attribute `links`; 2 when absent).
# Writes angles.png (unwrapped), angles_wrapped.png (wrapped to (-pi, pi]), phase.png
# (qdot against wrapped q, one panel per link), energy_error.png, reactions.png (N = 2:
# F01 and F21, the forces on link 1; other N: F_joint, the force of body i-1 on body i
# at joint i, one panel per joint up to 4 links, the magnitudes beyond), tip_path.png
# (the free end of link N), and for a damped or driven run balance.png (the energy
# balance) (each through a temporary file, moved into place once all
# are drawn: scripts/lib/output.sh). Attributes are read at full precision
# (h5dump -m %.17g). DPEND: the dpend executable to use (default: the release build).
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
links=$(attr links)
links=${links:-2}
[[ $links =~ ^[1-9][0-9]*$ ]] ||
  plot_fail 2 "the attribute links of '$1' is not a count: '$links'"
# has NAME: the file holds the dataset /trajectory/NAME
has() { grep -qx " *dataset */trajectory/$1" "$tmp/contents.txt"; }
h5dump -n "$h5" > "$tmp/contents.txt" 2>/dev/null || plot_fail 1 "cannot list '$1'"
if ((links == 2)) && has F01; then
  # the double pendulum (also its files from before --links): F01, F21 on link 1, and
  # the tip 2 rC2 - rB; columns t q1 q2 E qdot1 qdot2 F01 F21 rC2 rB
  "$dpend" export "$h5" /trajectory/t /trajectory/q /trajectory/energy /trajectory/qdot \
    /trajectory/F01 /trajectory/F21 /trajectory/rC2 /trajectory/rB > "$tmp/sim.dat"
else
  # columns t q(1..N) E qdot(1..N) F_joint(x, y of joints 1..N) rJ(x, y of link N)
  "$dpend" export "$h5" /trajectory/t /trajectory/q /trajectory/energy /trajectory/qdot \
    > "$tmp/a.dat"
  rows /trajectory/F_joint $((2 * links)) > "$tmp/f.dat"
  rows /trajectory/rJ $((2 * links)) | awk '{ print $(NF - 1), $NF }' > "$tmp/tip.dat"
  n=$(wc -l < "$tmp/a.dat")
  [[ $(wc -l < "$tmp/f.dat") -eq $n && $(wc -l < "$tmp/tip.dat") -eq $n ]] ||
    plot_fail 1 "the /trajectory datasets of '$1' differ in length"
  paste -d ' ' "$tmp/a.dat" "$tmp/f.dat" "$tmp/tip.dat" > "$tmp/sim.dat"
fi
method=$(attr method)
escale=$(attr energy_scale)
plot_number escale "${escale:-1.0}" "the attribute energy_scale of '$1'"
plot_base name "$1"
plot_enhanced title "${method:-dpend}, $name"
plot_begin "$out" angles.png angles_wrapped.png phase.png energy_error.png reactions.png \
  tip_path.png
plot_run gnuplot -c "$here/simulate.gp" "$tmp/sim.dat" "$figdir" "$title" "$escale" "$links"
printf 'plot_simulate.sh: wrote %s/{angles,angles_wrapped,phase,energy_error,reactions,tip_path}.png\n' "$out"
if has balance_error; then
  # a damped or driven run (issue 13): E(t) - E(0), the work of the friction and of the
  # support, and the balance error E(t) - E(0) + W_friction - W_support
  "$dpend" export "$h5" /trajectory/t /trajectory/energy /trajectory/W_friction \
    /trajectory/W_support /trajectory/balance_error > "$tmp/balance.dat"
  plot_begin "$out" balance.png
  plot_run gnuplot -c "$here/balance.gp" "$tmp/balance.dat" "$figdir" "$title" "$escale"
  printf 'plot_simulate.sh: wrote %s/balance.png\n' "$out"
fi
