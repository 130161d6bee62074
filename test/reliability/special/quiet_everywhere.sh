#!/usr/bin/env bash
# Special reliability test: every command obeys --quiet the same way (docs/cli.md).
# A command with a summary prints only its last line on stdout (exit 0, nothing on
# stderr), and that line is the last line the same run prints without --quiet (its
# first 30 characters: some closing lines end with a wall time);
# export, methods and models print their data unchanged. explore is run too when
# DPEND_PYTHON names an interpreter with the package (its address line only).
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
. "$ROOT/test/reliability/lib.sh"
pass() { printf 'ok   %s\n' "$1"; }

"$DPEND" simulate --t-end 0.4 --output s.h5 --quiet > /dev/null 2>&1 &&
  "$DPEND" sweep --n 8 --t-end 2 --output w.h5 --quiet > /dev/null 2>&1 &&
  "$DPEND" sweep --n 8 --t-end 2 --dt 0.005 --output w2.h5 --quiet > /dev/null 2>&1 &&
  "$DPEND" sweep --n 8 --t-end 2 --indicator megno --output m.h5 --quiet > /dev/null 2>&1 &&
  "$DPEND" sweep --n 8 --t-end 3 --indicator megno --output m2.h5 --quiet > /dev/null 2>&1 ||
  { echo "FAIL the input files"; exit 1; }

# ID, then the command's words; run once with --quiet, once without (other outputs)
summary() {
  local id=$1; shift
  local -a loud=() quiet=() words=("$@")
  local w
  for w in "${words[@]}"; do
    loud+=("${w//@/loud}")
    quiet+=("${w//@/quiet}")
  done
  "$DPEND" "${quiet[@]}" --quiet > "q_$id.out" 2> "q_$id.err"
  local st=$?
  "$DPEND" "${loud[@]}" > "l_$id.out" 2> /dev/null
  local last lines
  lines=$(wc -l < "q_$id.out")
  last=$(tail -n 1 "l_$id.out" | sed 's/loud/quiet/g')
  # the same line (its first 30 characters: the closing lines of simulate, sweep and
  # study end with their wall times)
  local line
  line=$(cat "q_$id.out")
  if [[ $st -eq 0 && $lines -eq 1 && ! -s "q_$id.err" && "${line:0:30}" == "${last:0:30}" ]]
  then
    pass "$id: one line ($(head -c 80 "q_$id.out"))"
  else
    bad "$id: exit $st, $lines lines on stdout, stderr '$(head -c 200 "q_$id.err")'," \
      "stdout '$(head -c 300 "q_$id.out")', without --quiet the last line '$last'"
  fi
}
summary simulate   simulate --t-end 0.3 --output @_sim.h5
summary lyapunov   lyapunov --t-end 1 --output @_lyap.h5
summary indicators indicators --t-end 1 --output @_ind.h5
summary divergence divergence --t-end 1 --output @_div.h5
summary poincare   poincare --t-end 5 --output @_poi.h5
summary sweep      sweep --n 8 --t-end 2 --output @_sweep.h5
summary compare    sweep-compare w.h5 w2.h5
summary agreement  sweep-compare m.h5 m2.h5 --agreement --output @_agree.h5
summary fit        fit "$ROOT/data/fit_example.csv" --fit-damping --output @_fit.h5
summary study      study --quick --no-figures --methods rk4,verlet --output @_study.h5
summary sweep-point sweep --n 4 --t-end 2 --body point --output @_swp.h5
summary torques    torques "$ROOT/data/fit_example.csv" --output @_tq.h5 --csv @_tq.csv
summary identify   identify "$ROOT/data/robot_example.csv" --m 1,0.7 --l 0.8,0.6 --output @_id.h5
if command -v gnuplot > /dev/null 2>&1; then
  summary animate  animate s.h5 --output @_anim.gif --size 64x64 --fps 5
  # the figures' script says nothing with --quiet: the study's line is the last
  mkdir -p quiet_st loud_st
  summary study-figures study --quick --methods rk4 --cases small --output @_st/study.h5
else
  bad "animate: gnuplot is not installed"
fi

# a fit that does not describe its data: --quiet keeps its warning, on stderr
"$DPEND" fit "$ROOT/data/fit_mass_length.csv" --output misfit.h5 --quiet > q_misfit.out 2> q_misfit.err
st=$?
if [[ $st -eq 0 && $(wc -l < q_misfit.out) -eq 1 ]] && grep -q "dpend fit: wrote" q_misfit.out &&
   grep -q "warning: the RMS residual" q_misfit.err; then
  pass "fit-misfit: one line on stdout, the warning on stderr"
else
  bad "fit-misfit: exit $st, stdout '$(head -c 300 q_misfit.out)', stderr '$(head -c 300 q_misfit.err)'"
fi

# data commands: the same output with and without --quiet
data() {
  local id=$1; shift
  "$DPEND" "$@" --quiet > "q_$id.out" 2> "q_$id.err"
  local st=$?
  "$DPEND" "$@" > "l_$id.out" 2> /dev/null
  if [[ $st -eq 0 && ! -s "q_$id.err" && -s "q_$id.out" ]] && cmp -s "q_$id.out" "l_$id.out"; then
    pass "$id: the data as always"
  else
    bad "$id: exit $st, stderr '$(head -c 200 "q_$id.err")', differs: $(cmp "q_$id.out" "l_$id.out" 2>&1)"
  fi
}
data export  export s.h5 /trajectory/t
data methods methods
data models  models

py="${DPEND_PYTHON:-}"
if [[ -n "$py" ]] && "$py" -c 'import dpend.explore' 2> /dev/null; then
  DPEND_PYTHON="$py" "$DPEND" explore w.h5 --port 0 --quiet > q_explore.out 2> q_explore.err &
  server=$!
  for _ in $(seq 1 100); do
    [[ -s q_explore.out ]] && break
    sleep 0.2
  done
  sleep 0.5
  kill -TERM "$server" 2> /dev/null
  wait "$server"
  if [[ $(wc -l < q_explore.out) -eq 1 ]] && grep -q '^dpend explore: serving at http' q_explore.out; then
    pass "explore: the address only"
  else
    bad "explore: '$(cat q_explore.out)' '$(head -c 200 q_explore.err)'"
  fi
else
  echo "note: explore not run (DPEND_PYTHON does not name a python with dpend)"
fi
finish
