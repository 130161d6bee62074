#!/usr/bin/env bash
# Special reliability test: every model of the catalogue, with every body kind it
# has, runs every command on a tiny configuration, or refuses it in one line.
# The test names no model: it reads `dpend models` (names, the state of rest, the
# parameters with their defaults and counts), starts 0.4 away from rest in every
# coordinate, and runs simulate, export, animate, lyapunov, divergence, indicators,
# poincare, a sweep indicator map over a coordinate and a rate, a sweep over each
# parameter, a tiny study (the default experiments on one case, two methods) and a
# fit of each parameter to the model's own simulated motion. Each run must exit 0,
# or exit 2 with exactly one line on stderr (a capability the model or the body
# lacks); never exit 1, never a trap of the debug build.
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd);
# DPEND_MODELS (optional): only these models of the catalogue, blank- or
# comma-separated (default: every model); a name not in the catalogue fails.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
for tool in gnuplot h5dump awk; do
  if ! command -v "$tool" > /dev/null 2>&1; then
    echo "SKIP every_model_command: $tool not installed"
    exit 77
  fi
done
cd "$SCRATCH" || exit 1
export DPEND_ROOT="$ROOT"
failures=0
runs=0
refused=0
TRAP_RE='Floating point exception|Fortran runtime error|Backtrace|Error termination|HDF5-DIAG'

# check WHAT ARGS...: run dpend with ARGS (timeout 60 s) and judge the outcome.
check() {
  local what=$1 rc=0 lines
  shift
  runs=$((runs + 1))
  timeout -k 5 60 "$DPEND" "$@" > out.log 2> err.log < /dev/null || rc=$?
  lines=$(grep -c '' err.log)
  if grep -qE "$TRAP_RE" err.log || [ $rc -gt 2 ]; then
    failures=$((failures + 1))
    printf 'FAIL %s: exit %s, trap: %s (dpend %s)\n' "$what" "$rc" \
      "$(grep -m1 -E "$TRAP_RE" err.log | cut -c1-100)" "$*"
  elif [ $rc = 1 ]; then
    failures=$((failures + 1))
    printf 'FAIL %s: exit 1: %s (dpend %s)\n' "$what" "$(head -n 1 err.log | cut -c1-160)" "$*"
  elif [ $rc = 2 ] && [ "$lines" != 1 ]; then
    failures=$((failures + 1))
    printf 'FAIL %s: refused in %s lines (dpend %s)\n' "$what" "$lines" "$*"
  elif [ $rc = 2 ]; then
    refused=$((refused + 1))
    printf 'ok   %s: refused: %s\n' "$what" "$(cut -c1-140 err.log)"
  else
    printf 'ok   %s\n' "$what"
  fi
  return $rc
}

# The catalogue: "NAME|q at rest|param:units:default:count;..." per model.
"$DPEND" models > models.txt 2>&1 || { echo "FAIL dpend models"; exit 1; }
mapfile -t catalogue < <(LC_ALL=C awk '
  function flush() { if (name != "") print name "|" rest "|" params }
  /^[a-z0-9_]+: / { flush(); name = $1; sub(/:$/, "", name); rest = ""; params = ""; next }
  /^  at rest: / { rest = $0; sub(/.*q = /, "", rest); sub(/ \(.*/, "", rest); gsub(/ /, "", rest); next }
  /^    [a-z_0-9]+ / {
    count = "1"
    if ($0 ~ /one per link/) count = "link"; else if ($0 ~ /, [0-9]+ values/) count = "n"
    d = $0; sub(/.*default /, "", d); sub(/[,:].*/, "", d)
    params = params $1 ":" d ":" count ";"
  }
  END { flush() }' models.txt)
[ ${#catalogue[@]} -gt 0 ] || { echo "FAIL no model in 'dpend models'"; exit 1; }
if [ -n "${DPEND_MODELS:-}" ]; then   # only the models asked for, each of them listed
  wanted=()
  for want in ${DPEND_MODELS//,/ }; do
    found=0
    for entry in "${catalogue[@]}"; do
      if [ "${entry%%|*}" = "$want" ]; then wanted+=("$entry"); found=1; fi
    done
    [ $found = 1 ] || { echo "FAIL DPEND_MODELS: no model '$want' in 'dpend models'"; exit 1; }
  done
  [ ${#wanted[@]} -gt 0 ] || { echo "FAIL DPEND_MODELS='$DPEND_MODELS' names no model"; exit 1; }
  catalogue=("${wanted[@]}")
fi

for entry in "${catalogue[@]}"; do
  IFS='|' read -r model rest params <<< "$entry"
  # 0.4 away from rest in every coordinate, at rest in the rates
  q0=$(LC_ALL=C awk -v r="$rest" 'BEGIN { n = split(r, a, ","); s = "";
    for (i = 1; i <= n; i++) s = s (i > 1 ? "," : "") sprintf("%.6f", a[i] + 0.4); print s }')
  q1=${q0%%,*}
  bodies=("")
  [[ ";$params" == *";com:"* ]] && bodies+=("point")
  for body in "${bodies[@]}"; do
    F=(--model "$model")   # the fit takes the initial state from its data
    tag=$model
    if [ -n "$body" ]; then F+=(--body "$body"); tag="$model/$body"; fi
    M=("${F[@]}" --q "$q0")
    check "$tag simulate" simulate "${M[@]}" --t-end 0.5 --output s.h5 --force
    check "$tag export" export s.h5 t q energy kinetic potential --csv
    check "$tag export t, q" export s.h5 t q --csv && cp out.log data.csv   # the fit's data
    check "$tag animate" animate s.h5 --output a.gif --fps 5 --force
    check "$tag lyapunov" lyapunov "${M[@]}" --t-end 1 --output l.h5 --force
    check "$tag divergence" divergence "${M[@]}" --t-end 1 --output d.h5 --force
    check "$tag indicators" indicators "${M[@]}" --t-end 1 --output i.h5 --force
    check "$tag poincare" poincare "${M[@]}" --t-end 2 --output p.h5 --force
    check "$tag sweep (q1, w1)" sweep "${M[@]}" --axis1 q1 --axis2 w1 \
      --min1 "$q1" --max1 "$q1" --min2 -0.1 --max2 0.1 --n1 1 --n2 3 --t-end 1 \
      --indicator megno --quiet --output sw.h5 --force
    IFS=';' read -r -a plist <<< "$params"
    for p in "${plist[@]}"; do
      [ -n "$p" ] || continue
      IFS=':' read -r pname pdefault pcount <<< "$p"
      axes=()
      case $pcount in
        1) axes=("$pname") ;;
        link) axes=("${pname}1" "${pname}2") ;;
      esac
      lo=$(LC_ALL=C awk -v d="$pdefault" 'BEGIN { print (d == 0) ? 0 : 0.9 * d }')
      hi=$(LC_ALL=C awk -v d="$pdefault" 'BEGIN { print (d == 0) ? 0.1 : 1.1 * d }')
      for axis in "${axes[@]}"; do
        check "$tag sweep (q1, $axis)" sweep "${M[@]}" --axis1 q1 --axis2 "$axis" \
          --min1 "$q1" --max1 "$q1" --min2 "$lo" --max2 "$hi" --n1 1 --n2 2 --t-end 1 \
          --indicator megno --quiet --output sp.h5 --force
      done
      check "$tag fit $pname" fit data.csv "${F[@]}" --fit-parameters "$pname" \
        --output f.h5 --force
    done
    # the study's default experiments on one case (two methods, --quick)
    IFS=',' read -r -a qs <<< "$q0"
    {
      printf "&model name = '%s' /\n" "$model"
      [ -n "$body" ] && printf "&pendulum body = '%s' /\n" "$body"
      if [ ${#qs[@]} = 2 ]; then
        printf "&study case_name(1) = 'a', case_q1(1) = %s, case_q2(1) = %s,\n" \
          "${qs[0]}" "${qs[1]}"
      else   # another count of coordinates: the list form, case_links of them
        printf "&study case_name(1) = 'a', case_links(1) = %s, case_q(1:%s, 1) = %s,\n" \
          "${#qs[@]}" "${#qs[@]}" "$q0"
      fi
      printf " order_case = 'a', drift_case = 'a', ro_case = 'a', tao_case = 'a' /\n"
    } > study.nml
    check "$tag study" study --config study.nml --quick --no-figures --methods rk4,gauss4 \
      --threads 1 --output st.h5 --force
  done
done
printf '%s runs: %s ran, %s refused in one line, %s failed\n' "$runs" \
  "$((runs - refused - failures))" "$refused" "$failures"
[ $failures = 0 ]
