#!/usr/bin/env bash
# Special reliability test: every plot script with hostile file and directory names.
# Environment (set by the reliability runner): DPEND (the dpend binary), ROOT (the
# repository root), SCRATCH (an empty temporary directory, the cwd). Exit 0: pass,
# 77: skipped (printed note), other: fail. One line per check.
#
# Inputs are written by dpend itself into a directory whose name holds single and
# double quotes, spaces, $, backticks, a semicolon, non-ASCII letters and a newline,
# then copied under names that try to inject commands; every plot script must draw
# every figure (non-empty PNG, no temporary left) and no PWNED file may appear. A
# failing gnuplot must keep the old figures; a directory in place of a figure is
# refused.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
for tool in gnuplot h5dump; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "SKIP plot_names: $tool not installed"
    exit 77
  fi
done
cd "$SCRATCH" || exit 1
scripts="$ROOT/scripts"
export DPEND
failures=0
checks=0
pass() { checks=$((checks + 1)); printf 'ok   %s\n' "$1"; }
fail() { checks=$((checks + 1)); failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
# show NAME: a name on one line, control characters visible
show() { printf '%q' "$1"; }
log="$SCRATCH/.log"
touch "$SCRATCH/.start"

# ---- inputs, written by dpend into a hostile directory
dir=$'in d\'q "dq" $HOME `id` ;x é ü Ω\nnl'
mkdir -p -- "$dir"
gen() { # gen NAME dpend-args...: one input file, written by dpend
  local name=$1
  shift
  if "$DPEND" "$@" --output "$dir/$name" >"$log" 2>&1; then
    pass "dpend $1 --output $(show "$dir/$name")"
  else
    fail "dpend $1 --output $(show "$dir/$name"): $(tail -n 1 "$log")"
  fi
}
gen "sim O'Brien.h5" simulate --t-end 0.2
gen "lyap O'Brien.h5" lyapunov --t-end 3 --tau 0.5 --batches 2
gen "lyap1 O'Brien.h5" lyapunov --t-end 3 --tau 0.5 --batches 2 --vectors 1
gen "div O'Brien.h5" divergence --t-end 4 --pairs 2 --pair-spacing 1 --lyapunov-t 0
gen "poi O'Brien.h5" poincare --ics 2 --points 10 --t-end 50 --energy -15
gen "sweep O'Brien.h5" sweep --n 8 --t-end 2 --threads 1 --quiet
gen "study O'Brien.h5" study --quick --methods rk4,tao2 --cases small --threads 1 \
  --no-figures

# hostile names: command injection attempts, options, gnuplot pipes and markup
# shellcheck disable=SC2016  # the names are literal on purpose
names=("x';touch PWNED;'y" 'x";touch PWNED;"y' '$(touch PWNED)' '`touch PWNED`'
       '-dash' '<touch PWNED' '|touch PWNED' $'new\nline' 'a_b^c{d}@e&f~g\h%s')
kinds=(sim lyap lyap1 div poi sweep study)
for n in "${names[@]}"; do
  for k in "${kinds[@]}"; do
    cp -- "$dir/$k O'Brien.h5" "$dir/$k $n.h5" 2>/dev/null || true
  done
done

# figures SCRIPT-KIND: the PNG names each kind of input gives
figures() {
  case $1 in
    sim) echo "angles.png energy_error.png reactions.png tip_path.png" ;;
    lyap | lyap1) echo "lyapunov_convergence.png lyapunov_spectrum.png" ;;
    div) echo "divergence.png" ;;
    poi) echo "poincare.png" ;;
    sweep) echo "flip_map.png flip_map_link1.png flip_map_link2.png energy_error.png" ;;
    study) echo "energy_vs_time.png energy_vs_step.png error_vs_step.png" \
      "work_precision.png roundoff.png tao_omega.png" ;;
  esac
}
script_of() {
  case $1 in
    sim) echo plot_simulate.sh ;; sweep) echo plot_sweep.sh ;; study) echo plot_study.sh ;;
    *) echo plot_chaos.sh ;;
  esac
}
# plot KIND INPUT OUTDIR: run the script, check every figure and no temporary left
plot() {
  local kind=$1 in=$2 out=$3 script f missing="" status=0
  script=$(script_of "$kind")
  rm -rf -- "$out"
  bash "$scripts/$script" "$in" "$out" >"$log" 2>&1 || status=$?
  if ((status != 0)); then
    fail "$script $(show "$in") $(show "$out"): exit $status: $(tail -n 1 "$log")"
    return
  fi
  for f in $(figures "$kind"); do [[ -s "$out/$f" ]] || missing+=" $f"; done
  if [[ -n "$missing" ]]; then
    fail "$script $(show "$in") $(show "$out"): missing$missing"
  elif compgen -G "$out/.dpend-plot.*" >/dev/null; then
    fail "$script $(show "$in") $(show "$out"): a temporary directory is left"
  else
    pass "$script $(show "$in") -> $(show "$out")"
  fi
}

# every script on the input in the hostile directory, figures in another one
for k in "${kinds[@]}"; do plot "$k" "$dir/$k O'Brien.h5" "$dir/figs $k"; done
# the hostile names as input and as (relative) output directory: the three injection
# attempts with quotes through every script, the other names through two each
scripts5=(sim lyap div sweep study)
for i in "${!names[@]}"; do
  n=${names[$i]}
  if ((i < 3)); then some=("${scripts5[@]}"); else
    some=("${scripts5[$((i % 5))]}" "${scripts5[$(((i + 2) % 5))]}"); fi
  for k in "${some[@]}"; do plot "$k" "$dir/$k $n.h5" "$n $k"; done
done
plot sim "$SCRATCH/$dir/sim -dash.h5" "$SCRATCH/-out é"
# OUTDIR left out: the figures go next to the input (a relative name with a dash)
cp -- "$dir/sim O'Brien.h5" "-sim'.h5"
if bash "$scripts/plot_simulate.sh" "-sim'.h5" >"$log" 2>&1 && [[ -s angles.png ]]; then
  pass "plot_simulate.sh -sim\\'.h5 (figures beside it)"
else
  fail "plot_simulate.sh -sim\\'.h5 (figures beside it): $(tail -n 1 "$log")"
fi

# --compare: hostile inputs and output file
for n in "${names[@]:0:3}" '-dash' $'new\nline'; do
  out="cmp $n.png"
  rm -f -- "$out"
  if bash "$scripts/plot_chaos.sh" --compare "$out" "$dir/lyap $n.h5" "$dir/lyap1 $n.h5" \
    >"$log" 2>&1 && [[ -s "$out" ]]; then
    pass "plot_chaos.sh --compare $(show "$out")"
  else
    fail "plot_chaos.sh --compare $(show "$out"): $(tail -n 1 "$log")"
  fi
done

# ---- a failing gnuplot keeps the old figures and leaves no temporary
mkdir -p fakebin
printf '#!/bin/sh\necho "fake gnuplot: failing on purpose" >&2\nexit 1\n' >fakebin/gnuplot
chmod +x fakebin/gnuplot
keep="$dir/figs sim"
before=$(cd -- "$keep" 2>/dev/null && sha256sum -- *.png 2>&1)
if PATH="$SCRATCH/fakebin:$PATH" bash "$scripts/plot_simulate.sh" "$dir/sim O'Brien.h5" \
  "$keep" >"$log" 2>&1; then
  fail "failing gnuplot: exit 0"
elif [[ "$(cd -- "$keep" 2>/dev/null && sha256sum -- *.png 2>&1)" != "$before" ]]; then
  fail "failing gnuplot: the old figures changed"
elif compgen -G "$keep/.dpend-plot.*" >/dev/null; then
  fail "failing gnuplot: a temporary directory is left"
else
  pass "failing gnuplot: exit 1, old figures kept, no temporary left"
fi

# ---- a directory where a figure goes is refused, nothing changed
mkdir -p "blocked/angles.png"
if bash "$scripts/plot_simulate.sh" "$dir/sim O'Brien.h5" blocked >"$log" 2>&1; then
  fail "directory in place of a figure: exit 0"
elif [[ -n "$(ls -A blocked/angles.png)" ]] || compgen -G "blocked/*.png" | grep -qv angles; then
  fail "directory in place of a figure: something was written"
else
  pass "directory in place of a figure: refused ($(tail -n 1 "$log"))"
fi

# ---- no injection anywhere
found=$({ find "$SCRATCH" "$ROOT" -maxdepth 6 -name 'PWNED*' -newer "$SCRATCH/.start"
  find "${TMPDIR:-/tmp}" "${HOME:-/nonexistent}" -maxdepth 2 -name 'PWNED*' \
    -newer "$SCRATCH/.start"; } 2>/dev/null | head -n 5)
if [[ -n "$found" ]]; then fail "injection: created $found"; else pass "no PWNED file"; fi

echo "plot_names: $((checks - failures)) of $checks checks passed"
((failures == 0))
