#!/usr/bin/env bash
# The six figures of `dpend study` from its HDF5 file (gnuplot, pngcairo):
#   scripts/plot_study.sh FILE.h5 [OUTDIR]      (OUTDIR defaults to FILE's folder)
# Writes energy_vs_time.png, energy_vs_step.png, error_vs_step.png,
# work_precision.png, roundoff.png, tao_omega.png, and balance.png when the study
# has damped or driven cases (the energy balance error against time and step), each
# through a temporary file in OUTDIR, moved into place once all are drawn
# (scripts/lib/output.sh); on a failure the old figures are kept. `dpend study` runs it at the end, without a
# shell, as the argument vector
#   bash SCRIPTS/plot_study.sh FILE.h5 OUTDIR        (environment: DPEND=its own path)
# DPEND: the dpend executable (default: the release build, built once). `dpend
# export` turns the datasets into text columns (layout: docs/study-hdf5.md);
# `dpend methods --plot-styles` gives each method's colour and group and the
# panels (the method registry, src/integrators/dpend_method_registry.f90).
# File names and the case names of the study reach gnuplot only as data (gnuplot -c
# with ARG1..); the gnuplot code generated below holds only numbers and method names
# checked to be plain words.
# shellcheck disable=SC2154  # variables set with printf -v by lib/output.sh
set -euo pipefail
# numbers are read and printed in the C locale whatever the user's (a German
# locale made printf refuse "2.0E-003" and the figures fail)
export LC_ALL=C
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source-path=SCRIPTDIR source=lib/output.sh
. "$here/lib/output.sh"
plot_init plot_study.sh
[[ $# -ge 1 && $# -le 2 ]] || { echo "usage: $0 FILE.h5 [OUTDIR]" >&2; exit 2; }
plot_abs h5 "$1"
if [[ $# -ge 2 ]]; then out=$2; else plot_dir out "$1"; fi
[[ -f "$h5" && -r "$h5" ]] || plot_fail 2 "cannot read '$1'"
command -v gnuplot >/dev/null || plot_fail 1 "gnuplot not found"
command -v h5dump >/dev/null || plot_fail 1 "h5dump not found"
plot_dpend
plot_tmpdir

# attribute value (first element), strings without quotes
attr() { h5dump -w 0 -a "$1" "$h5" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n1 |
  sed 's/^"\(.*\)"$/\1/'; }
# numeric attribute: nattr VAR PATH
nattr() { plot_number "$1" "$(attr "$2")" "the attribute $2 of '$h5name'"; }
# a value read from the exported data: number VAR VALUE
number() { plot_number "$1" "$2" "a value read from '$h5name'"; }
# a row index: index VAR PATH
index() {
  local v
  v=$(attr "$2")
  [[ $v =~ ^[0-9]{1,9}$ ]] || plot_fail 2 "the attribute $2 of '$h5name' is not an index: '$v'"
  printf -v "$1" '%d' "$((10#$v))"
}
has() { h5dump -w 0 -H -d "$1" "$h5" >/dev/null 2>&1; }
ex() { "$dpend" export "$h5" "$@"; }
# words VAR LIST: VAR := the array of the words of LIST (no glob expansion)
words() { read -r -a "$1" <<<"$2" || true; }
# method names become part of the gnuplot code and of file names: plain words only
plain() {
  local w
  for w in "${@:2}"; do
    [[ $w =~ ^[A-Za-z0-9_]+$ ]] ||
      plot_fail 2 "$1 of '$h5name' holds '$w', not a method name"
  done
}
# a data file of $tmp as a gnuplot string expression (D is ARG1, the folder)
df() { printf "D.'/%s'" "$1"; }

h5name=$1
words cases "$(attr /cases)"; words methods "$(attr /methods)"
# the damped or driven cases (energy balance); 'none' or absent (older files): none
bal_attr=$(attr /balance_cases); [[ -n "$bal_attr" ]] || bal_attr=none
words balance_cases "$bal_attr"
[[ "$bal_attr" == none ]] && balance_cases=()
oc=$(attr /order_case); dc=$(attr /drift_case)
words ro_methods "$(attr /roundoff_methods)"; words tao_methods "$(attr /tao_methods)"
plain "the attribute methods" "${methods[@]}"
plain "the attribute roundoff_methods" "${ro_methods[@]}"
plain "the attribute tao_methods" "${tao_methods[@]}"
quick=$(attr /config/quick)
note=""; [[ "$quick" == "1" ]] && note=" (--quick)"
# cases by their index: c1, c2, ... in file names; oi and di the verdict cases
oi=0; di=0
for i in "${!cases[@]}"; do
  [[ "${cases[$i]}" == "$oc" ]] && oi=$((i + 1))
  [[ "${cases[$i]}" == "$dc" ]] && di=$((i + 1))
done
((oi > 0 && di > 0)) ||
  plot_fail 2 "the attributes order_case and drift_case of '$h5name' name no case of /cases"
plot_enhanced oc_text "$oc"
plot_enhanced dc_text "$dc"
is_balance() { [[ " ${balance_cases[*]} " == *" $1 "* ]]; }
# the energy error's name in the titles: the balance for a damped or driven case
e_name() {
  if is_balance "$1"; then echo "energy balance error |E(t) - E(0) + W_f - W_s| / E_s"
  else echo "relative energy error |H(t) - H(0)| / E_s"; fi
}

# the colour and plot group of each method and the panel of each group, from the
# method registry: `dpend methods --plot-styles` prints `group ID TITLE...` and
# `method NAME #RRGGBB ID` lines (src/commands/dpend_methods_command.f90). Checked
# word by word: they become part of the gnuplot code.
declare -A colour_of=() group_of=()
group_ids=(); titles=(); registry_methods=()
while read -r kind a b c; do
  case "$kind" in
    group)
      t="$b${c:+ $c}"
      [[ $a =~ ^[a-z0-9_]+$ && -n "$t" ]] ||
        plot_fail 1 "dpend methods --plot-styles: bad group line '$kind $a $t'"
      case "$t" in *\'* | *\"* | *\\*)
        plot_fail 1 "dpend methods --plot-styles: quote in the title of group '$a'";;
      esac
      group_ids+=("$a"); titles+=("$t");;
    method)
      [[ $a =~ ^[a-z0-9_]+$ && $b =~ ^#[0-9a-f]{6}$ && $c =~ ^[a-z0-9_]+$ ]] ||
        plot_fail 1 "dpend methods --plot-styles: bad method line '$kind $a $b $c'"
      registry_methods+=("$a"); colour_of[$a]=$b; group_of[$a]=$c;;
    *) plot_fail 1 "dpend methods --plot-styles failed or printed '$kind'";;
  esac
done < <("$dpend" methods --plot-styles || echo "failed")
((${#group_ids[@]} > 0)) || plot_fail 1 "dpend methods --plot-styles printed no group"
# colour of method $1; grey for a method the registry does not know
color() { echo "${colour_of[$1]:-#7f7f7f}"; }
# the explicit Runge-Kutta methods (group rk) are drawn dashed
dashed() { [[ "${group_of[$1]:-}" == rk ]]; }
# the methods of the registry in group $1, in the registry's order
group_members() {
  local m list=()
  for m in "${registry_methods[@]}"; do [[ ${group_of[$m]} == "$1" ]] && list+=("$m"); done
  echo "${list[*]}"
}
in_list() { [[ " $2 " == *" $1 "* ]]; }

# ---- data: one file per case, method and sweep
for ci in "${!cases[@]}"; do
  c=${cases[$ci]}
  for m in "${methods[@]}"; do
    g="/cases/$c/$m"
    f="$tmp/c$((ci + 1))_${m}"
    ex "$g/step/h" "$g/step/global_error" "$g/step/energy_max_short" \
      "$g/step/energy_max_long" "$g/step/short_rhs" "$g/step/wall_short" "$g/step/status" \
      > "${f}_step.dat"
    ex "$g/step/t_bins" "$g/step/energy_bins" > "${f}_step_bins.dat"
    if has "$g/tol/rtol"; then
      ex "$g/tol/mean_step_short" "$g/tol/global_error" "$g/tol/energy_max_short" \
        "$g/tol/energy_max_long" "$g/tol/short_rhs" "$g/tol/wall_short" "$g/tol/status" \
        > "${f}_tol.dat"
      ex "$g/tol/t_bins" "$g/tol/energy_bins" > "${f}_tol_bins.dat"
    fi
  done
done

# value in column $2 of row $3 (0-based) of file $1
cell() { awk -v c="$2" -v r="$3" 'NR == r + 1 { print $c }' "$1"; }
# reference line through row r of a data file: "x0 y0"
anchor() { awk -v cx="$2" -v cy="$3" -v r="$4" 'NR == r + 1 { print $cx, $cy }' "$1"; }

# a panel with nothing to show (a family or experiment absent from the study): a grey
# "not run" and the reason in its middle
empty_panel() {
  echo "set label 10 'not run' at graph 0.5, graph 0.56 center font F20 tc rgb 'gray40'"
  echo "set label 11 '$1' at graph 0.5, graph 0.46 center tc rgb 'gray40'; unset logscale; unset key"
  echo "unset xtics; unset ytics; set xrange [0:1]; set yrange [0:1]; plot -1 notitle"
  echo "unset label 10; unset label 11; set logscale xy; set xtics; set ytics; set key; set autoscale"
}

# the generated script: gnuplot -c study.gp DATADIR FIGDIR ORDER_CASE DRIFT_CASE STYLE_GP
gp="$tmp/study.gp"
cat > "$gp" <<'EOF'
D = ARG1
O = ARG2
OC = ARG3
DC = ARG4
load ARG5
# text scales with the canvas (style.gp), the study's 1400 px at 0.75 of the rule
fk = 0.75*font_pt(1400)/11.0
F9 = sprintf(",%.3g", 9*fk); F10 = sprintf(",%.3g", 10*fk); F13 = sprintf(",%.3g", 13*fk)
F20 = sprintf(",%.3g", 20*fk)
set terminal pngcairo size 1400,900 enhanced font sprintf("DejaVu Sans,%.3g", 11*fk)
set print O.'/keys.txt' append
set logscale xy
set format x "10^{%L}"; set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top spacing 1.1
set datafile missing NaN
EOF

# ---- figure 1: energy error against time at the middle step, the methods grouped by
# family (the registry's plot groups, in its order; a method it does not know last):
# one colour each (the registry's, shades of the family's hue) and, within a family,
# one dash type each (solid, dashed, dash-dot, dash-dot-dot, dotted), a key line naming
# each family above its members; the key lists only curves with data (keys.txt)
ms=" ${methods[*]} "   # the method list, for in_list
dts=(1 2 4 5 3)
{
  echo "set output O.'/energy_vs_time.png'"
  en=$(e_name "$dc")
  echo "set title \"${en^} against time, case \".DC.\",\\neach method at its middle step (maximum per logarithmic time bin)$note\""
  echo "set xlabel 't [s]'; set ylabel '${en#* error }'"
  echo "set key outside right top Left reverse samplen 4"
  plot="plot"
  guide=""
  ordered=()
  for i in "${!group_ids[@]}"; do
    for m in $(group_members "${group_ids[$i]}"); do in_list "$m" "$ms" && ordered+=("$m:$i"); done
  done
  for m in "${methods[@]}"; do [[ -n "${group_of[$m]:-}" ]] || ordered+=("$m:-1"); done
  last=-2; j=0; n=0
  for mi in "${ordered[@]}"; do
    m=${mi%%:*}; gi=${mi##*:}
    if [[ $gi != "$last" ]]; then
      j=0; last=$gi
      if ((gi >= 0)); then gt=${titles[$gi]}; else gt="other methods"; fi
      plot="$plot keyentry w l lc rgb 'white' t '{/:Bold $gt}',"
    fi
    f="c${di}_${m}"
    mode=step; [[ -f "$tmp/${f}_tol.dat" ]] && mode=tol
    index mid "/cases/$dc/$m/$mode/mid"
    col=$((mid + 2))
    if [[ $mode == step ]]; then
      number h "$(cell "$tmp/${f}_step.dat" 1 "$mid")"
      lab="$m, h = $(printf '%.2g' "$h") s"
    else
      number rt "$(ex "/cases/$dc/$m/tol/rtol" | awk -v r="$mid" 'NR == r + 1 {print $1}')"
      lab="$m, rtol = $(printf '%.0e' "$rt")"
    fi
    dash=${dts[$((j % ${#dts[@]}))]}; lw=2.2
    j=$((j + 1)); n=$((n + 1))
    if dashed "$m" && [[ -z "$guide" ]]; then
      # a t^1 guide 3 decades long, a factor 3 below the end of the first explicit method
      read -r gx gy < <(awk -v c="$col" '$c != "NaN" { x = $1; y = $c } END { print x, y }' \
        "$tmp/${f}_${mode}_bins.dat")
      number gx "$gx"; number gy "$gy"
      guide="(x >= $gx/1000 && x <= $gx ? $gy/3*(x/$gx) : NaN) w l lw 2 dt 3 lc rgb 'black' t 'slope 1: linear drift',"
    fi
    echo "stats $(df "${f}_${mode}_bins.dat") u (has(column($col)) && column($col) > 0 ? 1 : 0) nooutput; n$n = STATS_sum"
    echo "print keyline('energy_vs_time.png', '$lab', n$n)"
    plot="$plot $(df "${f}_${mode}_bins.dat") u 1:$col w l lw $lw dt $dash lc rgb '$(color "$m")' t (n$n > 0 ? '$lab' : ''),"
  done
  # no drift guide for a damped or driven case (no conserved energy to drift)
  if is_balance "$dc"; then guide=""; fi
  plot="$plot $guide"
  echo "${plot%,}"
} >> "$gp"

# ---- figures 2 and 3: errors against the step, 2x2 panels by family, reference slopes
# reference line of slope p through (x0, y0), drawn over [xa/1.3, xb*1.3] only
ref() { echo "(x >= $3/1.3 && x <= $4*1.3 ? $2*(x/$1)**$5 : NaN)"; }
panels() { # $1 output, $2 title (a gnuplot string expression), $3 case index, $4 column,
           # $5 ylabel, $6 fit attribute,
           # [$7 case index of the second curve, $8 its column, $9 its fit attribute]
  local c1=${cases[$3 - 1]} c2=""
  [[ -z "${7:-}" ]] || c2=${cases[$7 - 1]}
  # taller than the others: each panel's key sits below it
  echo "set terminal pngcairo size 1400,1100 enhanced font sprintf('DejaVu Sans,%.3g', 11*fk)"
  echo "set output O.'/$1'"
  echo "set multiplot layout $(((${#group_ids[@]} + 1) / 2)),2 title $2 font F13"
  echo "set xlabel 'step h [s]'; set ylabel '$5'; set key below left Left reverse maxrows 2 font F10"
  for i in "${!group_ids[@]}"; do
    members=$(group_members "${group_ids[$i]}")
    echo "set title '${titles[$i]}'"
    # x from the smallest step / 1.5 to the largest × 1.5 (the key sits below)
    files=()
    for m in $members; do in_list "$m" "$ms" && files+=("$tmp/c${3}_${m}_step.dat"); done
    if [[ ${#files[@]} -gt 0 ]]; then
      number lo "$(cat "${files[@]}" | awk 'NR == 1 || $1 < m { m = $1 } END { print m/1.5 }')"
      number hi "$(cat "${files[@]}" | awk 'NR == 1 || $1 > m { m = $1 } END { print m*1.5 }')"
      echo "set xrange [$lo:$hi]"
    fi
    plot="plot"
    n=0
    for m in $members; do
      in_list "$m" "$ms" || continue
      f="$tmp/c${3}_${m}_step.dat"
      index mid "/cases/$c1/$m/step/mid"
      nattr p "/cases/$c1/$m/step/order"
      read -r x0 y0 < <(anchor "$f" 1 "$4" "$mid")
      number x0 "$x0"; number y0 "$y0"
      number xa "$(awk 'NR == 1 || $1 < m { m = $1 } END { print m }' "$f")"
      number xb "$(awk 'NR == 1 || $1 > m { m = $1 } END { print m }' "$f")"
      nattr fit "/cases/$c1/$m/step/$6"
      lab="$m (p = $p): $(printf '%.2f' "$fit")"
      if [[ -n "${7:-}" ]]; then
        nattr fit "/cases/$c2/$m/step/$9"
        lab="$lab, long run $(printf '%.2f' "$fit")"
      fi
      plot="$plot $(df "c${3}_${m}_step.dat") u 1:(\$$4 > 0 ? \$$4 : NaN) w lp lw 2 pt 7 ps 1 lc rgb '$(color "$m")' t '$lab',"
      plot="$plot $(ref "$x0" "$y0" "$xa" "$xb" "$p") w l lw 1.2 dt 2 lc rgb 'black' notitle,"
      if [[ -n "${7:-}" ]]; then
        plot="$plot $(df "c${7}_${m}_step.dat") u 1:(\$$8 > 0 ? \$$8 : NaN) w lp lw 1.5 dt 4 pt 6 ps 1 lc rgb '$(color "$m")' notitle,"
      fi
      n=$((n + 1))
    done
    if [[ $n -eq 0 ]]; then empty_panel "no method of this family among the methods of this study"; else echo "${plot%,}"; fi
  done
  echo "unset multiplot; set autoscale x"
  echo "set terminal pngcairo size 1400,900 enhanced font sprintf('DejaVu Sans,%.3g', 11*fk)"
}
nattr ts /config/t_short
# units of the global error: the reference state's, as the file labels them (the
# chain's and double pendulum's rad, rad/s; another model's, e.g. m, rad, m/s,
# rad/s); only letters, '/', ',' and blanks reach gnuplot, else the default
su=$(attr "/cases/${cases[0]}/reference/state/units")
[[ $su =~ ^[A-Za-z/,\ ]{1,40}$ ]] || su="rad, rad/s"
ylab="max |H - H(0)| / E_s"; bnote=""
if is_balance "$oc" || is_balance "$dc"; then
  ylab="max energy (balance) error / E_s"; bnote=" (damped or driven: the energy balance error)"
fi
# shellcheck disable=SC2129
panels error_vs_step.png \
  "\"Global error over t ≤ $ts s against the step, case \".OC.\"; legend: fitted slope; dashed: slope p$note\"" \
  "$oi" 2 "max |Δq|, |Δq̇| [$su]" order_global >> "$gp"
panels energy_vs_step.png \
  "\"Maximum energy error$bnote against the step: filled, t ≤ $ts s (case \".OC.\"); open, whole long run (case \".DC.\"); dashed: slope p$note\"" \
  "$oi" 3 "$ylab" order_energy "$di" 4 order_energy_long >> "$gp"

# ---- figure 4: work-precision
{
  echo "set output O.'/work_precision.png'"
  echo "set multiplot layout 1,2 title \"Work-precision, case \".OC.\": global error at t ≤ $ts s (fixed steps; dopri5, dop853 over tolerances)$note\" font F13"
  echo "set ylabel 'max |Δq|, |Δq̇| [$su]'; set key inside right top font F9"
  for panel in wall rhs; do
    if [[ $panel == wall ]]; then
      echo "set title 'against wall time'; set xlabel 'wall time of one run [s]'"; col=6
    else
      echo "set title 'against right-hand-side evaluations'; set xlabel 'evaluations of the vector field'"; col=5
    fi
    plot="plot"
    for m in "${methods[@]}"; do
      mode=step; [[ -f "$tmp/c${oi}_${m}_tol.dat" ]] && mode=tol
      dash=1; dashed "$m" && dash=2
      plot="$plot $(df "c${oi}_${m}_${mode}.dat") u $col:(\$2 > 0 ? \$2 : NaN) w lp lw 2 dt $dash pt 7 ps 0.8 lc rgb '$(color "$m")' t '$m',"
    done
    echo "${plot%,}"
  done
  echo "unset multiplot"
} >> "$gp"

# ---- figure 5: roundoff (Brouwer's law)
{
  fit_t=""
  ro=()
  for m in "${ro_methods[@]}"; do
    [[ "$m" == none ]] && continue
    ro+=("$m")
    for mode in compensated plain; do
      ex "/roundoff/$m/t" "/roundoff/$m/rms_$mode" > "$tmp/ro_${m}_${mode}.dat"
    done
    nattr fit_t "/roundoff/$m/fit_t_min"
  done
  # why an empty panel: a fixed text chosen by the verdict (never the file's text)
  ro_why="no roundoff method among the methods of this study"
  [[ "$(attr /summary/roundoff)" == "not run for the N-link chain"* ]] &&
    ro_why="not run for the N-link chain (H in quadruple precision: double pendulum only)"
  [[ "$(attr /summary/roundoff)" == "not run for model "* ]] &&
    ro_why="not run: the model has no H in quadruple precision (double pendulum only)"
  is_balance "$(attr /config/ro_case)" &&
    ro_why="the roundoff case is damped or driven (no conserved H)"
  # one y range for both panels, so that the two magnitudes compare
  yr=""
  if ((${#ro[@]})); then
    yr=$(cat "$tmp"/ro_*.dat | awk '$2 != "NaN" && $2 > 0 { if (!n || $2 < lo) lo = $2; if (!n || $2 > hi) hi = $2; n = 1 }
      END { if (n) printf "set yrange [%g:%g]", lo / 3, hi * 3 }')
  fi
  echo "set output O.'/roundoff.png'"
  if ((${#ro[@]})); then
    # shellcheck disable=SC2028  # the \n is gnuplot's, inside its string
    echo "set multiplot layout 1,2 title \"Roundoff: RMS over runs of (H - H(0))/E_s, H in quadruple precision at the compensated state;\ndotted: √t (Brouwer's law) over the fit window t ≥ $fit_t s, offset below the data$note\" font F13"
  else
    echo "set multiplot layout 1,2 title \"Roundoff: RMS over runs of (H - H(0))/E_s (Brouwer's law)$note\" font F13"
  fi
  echo "set xlabel 't [s]'; set ylabel 'RMS of (H - H(0)) / E_s'; set key inside left top font F10"
  echo "$yr"
  [[ -n "$fit_t" ]] && echo "set arrow 2 from $fit_t, graph 0 to $fit_t, graph 1 nohead dt 2 lc rgb 'gray50'"
  for mode in compensated plain; do
    if [[ $mode == compensated ]]; then echo "set title 'with compensated summation'"; else echo "set title 'without compensated summation'"; fi
    plot="plot"
    k=0
    for m in "${ro[@]}"; do
      g="/roundoff/$m"
      f="ro_${m}_${mode}.dat"
      read -r x0 y0 < <(tail -n 1 "$tmp/$f")
      number x0 "$x0"; number y0 "$y0"
      nattr e "$g/exponent_$mode"
      nattr dt "$g/dt"
      rc=("#1f77b4" "#d62728" "#2ca02c" "#9467bd")
      plot="$plot $(df "$f") u 1:(\$2 > 0 ? \$2 : NaN) w lp lw 2 pt 7 ps 0.7 lc rgb '${rc[$k]}' t '$m, h = $(printf '%.1e' "$dt") s: fitted exponent $(printf '%.2f' "$e")',"
      plot="$plot (x >= $fit_t ? $y0/2.5*(x/$x0)**0.5 : NaN) w l lw 2 dt 3 lc rgb '${rc[$k]}' notitle,"
      k=$((k + 1))
    done
    if [[ $k -eq 0 ]]; then empty_panel "$ro_why"; else echo "${plot%,}"; fi
  done
  echo "unset multiplot; unset arrow 2; set autoscale y"
} >> "$gp"

# ---- figure 6: Tao's binding constant
{
  tao=()
  for m in "${tao_methods[@]}"; do [[ "$m" == none ]] || tao+=("$m"); done
  echo "set output O.'/tao_omega.png'"
  if ((${#tao[@]})); then
    echo "set multiplot layout 1,2 title \"Tao's methods against the binding constant ω (gray dashed: default ω = 20/s; red dotted: 2ωh = 2πk)$note\" font F13"
  else
    echo "set multiplot layout 1,2 title \"Tao's methods against the binding constant ω$note\" font F13"
  fi
  echo "set xlabel 'ω [1/s]'; set key inside left top font F10"
  echo "set arrow 1 from 20, graph 0 to 20, graph 1 nohead dt 2 lc rgb 'gray40'"
  # resonances 2 ω h = 2π k: the binding rotation is the identity
  if ((${#tao[@]})); then
    nattr tdt "/tao/${tao[0]}/dt"
    for k in 1 2 3 4 5 6; do
      echo "set arrow $((k + 2)) from $k*pi/$tdt, graph 0 to $k*pi/$tdt, graph 1 nohead dt 3 lc rgb '#e08080'"
    done
  fi
  for panel in energy global; do
    if [[ $panel == energy ]]; then
      echo "set title 'maximum energy error'; set ylabel 'max |H - H(0)| / E_s'"; col=2
    else
      echo "set title 'global error at t ≤ $ts s'; set ylabel 'max |Δq|, |Δq̇| [$su]'"; col=3
    fi
    plot="plot"
    k=0
    for m in "${tao[@]}"; do
      g="/tao/$m"
      f="tao_$m.dat"
      ex "$g/omega" "$g/energy_max" "$g/global_error" > "$tmp/$f"
      nattr dt "$g/dt"
      nattr te "$g/t_end"
      plot="$plot $(df "$f") u 1:(\$$col > 0 ? \$$col : NaN) w lp lw 2 pt 7 ps 0.8 lc rgb '$(color "$m")' t '$m, h = $(printf '%.1e' "$dt") s, t = $te s',"
      k=$((k + 1))
    done
    tao_why="no Tao method among the methods of this study"
    is_balance "$(attr /config/tao_case)" &&
      tao_why="the Tao case is damped or driven (the Tao methods need a Hamiltonian)"
    if [[ $k -eq 0 ]]; then empty_panel "$tao_why"; else echo "${plot%,}"; fi
  done
  echo "unset multiplot; unset arrow"
} >> "$gp"

# ---- figure 7 (damped or driven cases only): the energy balance error against time
# (each method at its middle step) and against the step (maximum up to t_short,
# filled, and over the long run, open), one row per case
figures=(energy_vs_time.png energy_vs_step.png error_vs_step.png work_precision.png
  roundoff.png tao_omega.png)
if ((${#balance_cases[@]})); then
  figures+=(balance.png)
  {
    nb=${#balance_cases[@]}
    echo "set output O.'/balance.png'"
    echo "set terminal pngcairo size 1400,$((150 + 380 * nb)) enhanced font sprintf('DejaVu Sans,%.3g', 11*fk)"
    echo "set multiplot layout $nb,2 title \"Energy balance |E(t) - E(0) + W_{friction}(t) - W_{support}(t)| / E_s of the damped and driven cases (fixed steps)$note\" font F13"
    echo "set key outside right top font F9"
    for bc in "${balance_cases[@]}"; do
      bi=0
      for i in "${!cases[@]}"; do [[ "${cases[$i]}" == "$bc" ]] && bi=$((i + 1)); done
      ((bi > 0)) || plot_fail 2 "the attribute balance_cases of '$h5name' names no case of /cases"
      # the case name becomes part of the gnuplot code: letters, digits, '_', '-' only
      # (as dpend study accepts them)
      [[ $bc =~ ^[A-Za-z0-9_-]+$ ]] ||
        plot_fail 2 "the attribute balance_cases of '$h5name' holds '$bc', not a case name"
      plot_enhanced bc_text "$bc"
      echo "CASE = '$bc_text'"
      echo "set title 'against time, each method at its middle step, case '.CASE"
      echo "set xlabel 't [s]'; set ylabel 'max per time bin'"
      plot="plot"
      for m in "${methods[@]}"; do
        f="c${bi}_${m}"
        index mid "/cases/$bc/$m/step/mid"
        number h "$(cell "$tmp/${f}_step.dat" 1 "$mid")"
        dash=1; dashed "$m" && dash=2
        plot="$plot $(df "${f}_step_bins.dat") u 1:$((mid + 2)) w l lw 2 dt $dash lc rgb '$(color "$m")' t '$m, h = $(printf '%.2g' "$h") s',"
      done
      echo "${plot%,}"
      echo "set title 'against the step (filled: t ≤ $ts s; open: the long run), case '.CASE"
      echo "set xlabel 'step h [s]'; set ylabel 'max |E - E(0) + W_f - W_s| / E_s'"
      plot="plot"
      for m in "${methods[@]}"; do
        f="c${bi}_${m}_step.dat"
        nattr p "/cases/$bc/$m/step/order"
        nattr fit "/cases/$bc/$m/step/order_energy"
        dash=1; dashed "$m" && dash=2
        plot="$plot $(df "$f") u 1:(\$3 > 0 ? \$3 : NaN) w lp lw 2 dt $dash pt 7 ps 0.8 lc rgb '$(color "$m")' t '$m (p = $p): $(printf '%.2f' "$fit")',"
        plot="$plot $(df "$f") u 1:(\$4 > 0 ? \$4 : NaN) w lp lw 1.5 dt 4 pt 6 ps 0.8 lc rgb '$(color "$m")' notitle,"
      done
      echo "${plot%,}"
    done
    echo "unset multiplot"
  } >> "$gp"
fi

plot_begin "$out" "${figures[@]}"
plot_run gnuplot -c "$gp" "$tmp" "$figdir" "$oc_text" "$dc_text" "$here/plot/style.gp"
fig_list=$(IFS=,; echo "${figures[*]%.png}")
# DPEND_PLOT_QUIET=1 (dpend study --quiet): the caller's line is the last
[[ ${DPEND_PLOT_QUIET:-0} == 1 ]] || printf 'plot_study.sh: wrote %s/{%s}.png\n' "$out" "$fig_list"
