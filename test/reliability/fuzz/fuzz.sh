#!/usr/bin/env bash
# The fuzzing stage of the reliability suite (scripts/reliability.sh --fuzz N).
# Run test/reliability/fuzz/fuzz.sh --help for the usage.
#
# Each case I of seed S is generated from its own random stream (a 64-bit LCG
# seeded with S and I), so one case is rerun alone with --seed S --case I. A case
# mutates a valid input of one parser: a number or list of a command-line flag, a
# namelist file (seeds: data/*.nml and seeds/study_tiny.nml), a fit CSV (seed: the
# first 26 samples of data/fit_example.csv) or an HDF5 file read by export,
# animate or sweep-compare (changed by dpend-fuzz-h5, built from fuzz_h5.f90).
# dpend runs from an argv array (never a shell string) under `timeout`, in a
# fresh directory holding only the case's inputs.
set -uo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)

usage() {
  cat <<'EOF'
usage: test/reliability/fuzz/fuzz.sh --dpend BIN [options]

Runs N fuzzed inputs against dpend and checks every outcome. Closes with
`fuzz: N inputs (seed S): K refused, J ran, F failed` (exit 1 if F > 0 or the
budget ran out before N inputs).

options:
  --dpend BIN     the dpend binary (required)
  --gen BIN       the HDF5 mutator (default: dpend-fuzz-h5 beside BIN, i.e.
                  BIN/../../example/dpend-fuzz-h5 in fpm's build tree)
  --count N       inputs; default 10000
  --seed S        seed (a non-negative integer); default: today's date, YYYYMMDD
  --case I        run only case I of seed S (repeatable), verbosely: its input,
                  exit status and stderr; keeps its directory
  --jobs J        cases run in parallel; default 2
  --budget SEC    wall-clock budget: no case starts after it; default 1500
  --timeout SEC   per-input limit (a case running longer is a hang); default 10
  --keep          keep the work directory
  -h, --help      this text

Outcomes: exit 2 with exactly one stderr line, inputs unchanged and no file
created or removed (refused); exit 0 (ran), or exit 1 with a message from a
command that documents run failures (not export or sweep-compare). A failure:
a trap (exit 134/136/139, or stderr with "Floating point exception", "Fortran
runtime error", "Backtrace", "Error termination", "HDF5-DIAG"), "Fortran
runtime warning" on stderr, a hang (over --timeout; a valid number of a flag
or a namelist that makes the run long is a note, "slow", instead, as is another
input dpend may accept that, run again with six times the limit, ends or reports
bounded progress), another exit status, a
changed or replaced input file, an invalid input accepted (a number with a
tab, ';' or letters inside, a '%' key, a repeated key or flag, two forms of one
quantity, NaN in a CSV, an edited file the command must refuse), or a valid
one refused (a CSV with a BOM, quoted header, tab or ';' separators).
Failures print the seed, the case, the mutation and the input escaped
(printf %q), with the command that reruns it.
EOF
}

DPEND="" GEN="" COUNT=10000 SEED="" JOBS=2 BUDGET=1500 TIMEOUT=10 KEEP=0
CASES=()
while [ $# -gt 0 ]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --dpend|--gen|--count|--seed|--case|--jobs|--budget|--timeout)
      [ $# -ge 2 ] || { echo "fuzz: $1 needs a value" >&2; exit 2; }
      case $1 in
        --dpend) DPEND=$2 ;; --gen) GEN=$2 ;; --count) COUNT=$2 ;; --seed) SEED=$2 ;;
        --case) CASES+=("$2") ;; --jobs) JOBS=$2 ;; --budget) BUDGET=$2 ;;
        --timeout) TIMEOUT=$2 ;;
      esac
      shift 2; continue ;;
    --keep) KEEP=1 ;;
    *) echo "fuzz: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$SEED" ] || SEED=$(date -u +%Y%m%d)
for v in "$COUNT" "$SEED" "$JOBS" "$BUDGET" "$TIMEOUT" ${CASES[@]+"${CASES[@]}"}; do
  [[ $v =~ ^[0-9]{1,15}$ ]] || { echo "fuzz: '$v' is not a non-negative integer" >&2; exit 2; }
done
[ "$JOBS" -ge 1 ] && [ "$TIMEOUT" -ge 1 ] || { echo "fuzz: --jobs, --timeout >= 1" >&2; exit 2; }
[ -n "$DPEND" ] || { echo "fuzz: --dpend BIN is required" >&2; exit 2; }
case $DPEND in /*) ;; *) DPEND=$(pwd)/$DPEND ;; esac
[ -x "$DPEND" ] || { echo "fuzz: '$DPEND' is not an executable" >&2; exit 2; }
[ -n "$GEN" ] || GEN=$(dirname "$DPEND")/../example/dpend-fuzz-h5
case $GEN in /*) ;; *) GEN=$(pwd)/$GEN ;; esac
[ -x "$GEN" ] || { echo "fuzz: no HDF5 mutator '$GEN' (fpm build builds it; or --gen)" >&2; exit 2; }
export OMP_NUM_THREADS=1 DPEND_ROOT=$ROOT

WORK=$(mktemp -d "${TMPDIR:-/tmp}/dpend-fuzz.XXXXXX")
cleanup() { if [ $KEEP = 1 ] || [ ${#CASES[@]} -gt 0 ]; then echo "fuzz: kept $WORK";
            else rm -rf "$WORK"; fi; }
trap cleanup EXIT
trap 'exit 130' INT TERM

# ------------------------------------------------------------------ fixtures
F=$WORK/fixtures
mkdir -p "$F"
(
  set -e
  cd "$F"
  cp "$ROOT"/data/*.nml "$HERE"/seeds/*.nml .
  cp "$ROOT"/data/sweep_list.txt .
  # the fit seed: the header and the first 26 samples (0 .. 0.5 s) of the example
  grep -v '^#' "$ROOT"/data/fit_example.csv | head -n 27 > fit.csv
  printf '%s\n' '0.1 0.2 0.0 0.0' '-1.5 -1.5 0.0 0.0' '1.0 1.0 0.5 0.5' > list.txt
  # the motors' seeds: a torque file and 3 s of the robot example (angles, torques)
  printf '%s\n' 't,tau1,tau2' '0,0.5,-0.2' '100,0.1,0.3' > tq.csv
  grep -v '^#' "$ROOT"/data/robot_example.csv | head -n 1501 > robot.csv
  "$DPEND" simulate --t-end 0.2 --save-every 5 --output sim.h5
  "$DPEND" simulate --links 3 --damping 0.1,0,0 --t-end 0.2 --save-every 5 --output sim3.h5
  "$DPEND" sweep --n 3 --t-end 1 --dt 0.01 --threads 1 --output sw_a.h5 --quiet
  "$DPEND" sweep --n 3 --t-end 1 --dt 0.005 --threads 1 --output sw_b.h5 --quiet
  "$DPEND" sweep --n 3 --t-end 1 --indicator megno --threads 1 --output ind_a.h5 --quiet
  "$DPEND" sweep --n 3 --t-end 2 --indicator megno --threads 1 --output ind_b.h5 --quiet
  "$DPEND" lyapunov --t-end 1 --tau 0.1 --batches 2 --output lyap.h5
  for h in *.h5; do
    # one line per object: D PATH TYPE DIMS / A OBJ NAME TYPE DIMS (h5py order; TYPE
    # f float, i integer, s string, o other; DIMS "" for a scalar)
    h5dump -H "$h" | awk '
      function path(n,   p, k) { p = ""; for (k = 2; k <= n; k++) if (name[k] != "") p = p "/" name[k]
                                 return p == "" ? "/" : p }
      /^ *(GROUP|DATASET|ATTRIBUTE) "/ {
        match($0, /"[^"]*"/); nm = substr($0, RSTART + 1, RLENGTH - 2)
        d++; kind[d] = $1; name[d] = (nm == "/" ? "" : nm); next_type = "o"
        o = gsub(/\{/, "{") - 1; for (k = 0; k < o; k++) { d++; kind[d] = "X"; name[d] = "" }
        next }
      /^ *DATATYPE/ { t = "o"
        if ($2 ~ /H5T_IEEE_F/) t = "f"; else if ($2 ~ /H5T_STD_[IU]/) t = "i"
        else if ($2 ~ /H5T_STRING/) t = "s"
        next_type = t }
      /^ *DATASPACE/ { dims = ""
        if ($0 ~ /SIMPLE/) { s = $0; sub(/.*\( */, "", s); sub(/ *\).*/, "", s)
                             s2 = $0; sub(/^[^(]*\( */, "", s2); sub(/ *\).*/, "", s2)
                             dims = s2; gsub(/ /, "", dims) }
        if (kind[d] == "DATASET") print "D", path(d), next_type, dims
        else if (kind[d] == "ATTRIBUTE") print "A", path(d - 1), name[d], next_type, dims }
      { o = gsub(/\{/, "{"); c = gsub(/\}/, "}")
        for (k = 0; k < o; k++) { d++; kind[d] = "X"; name[d] = "" }
        for (k = 0; k < c; k++) d-- }' > "$h.list"
  done
) > "$WORK/fixtures.log" 2>&1 ||
  { tail -n 30 "$WORK/fixtures.log"; echo "fuzz: building the fixtures failed" >&2; exit 1; }

# ---------------------------------------------------------------- randomness
# A 64-bit LCG (Knuth's MMIX constants) in bash arithmetic (wraps mod 2^64):
# rnd N sets R to a number in [0, N).
S=0 R=0
seed_case() { S=$(( $1 * 6364136223846793005 + $2 * 1442695040888963407 + 12345 ))
              rnd 2; rnd 2; }
rnd() { S=$(( S * 6364136223846793005 + 1442695040888963407 ))
        R=$(( ((S >> 33) & 0x7fffffff) % $1 )); }
# pick WORD...: P is one of the words
pick() { rnd $#; local i=$((R + 1)); P=${!i}; }

# ---------------------------------------------------------- number mutation
# mutate_number TOKEN: N is a mutated TOKEN; VERDICT refuse where N is certainly
# not a number (a strict parser must refuse it), else any.
VALID_POOL=(0 -0 1 -1 0.5 2 3 7 10 100 1e6 1e9 1e12 1e-6 1e-12 1e-300 1e300 1e308 1.8e308
  -1e308 4.9e-324 2147483647 2147483648 -2147483649 9223372036854775808 1d0 1D3 +1 .5 5.
  1e+02 1.0E-3 nan NaN -nan inf -inf Infinity 0.0001 1000000000000000000000 -5 33 65
  10000 100000)
BAD_POOL=('' ' ' 'x' '1x' '1.0abc' '1..0' '1e' 'e5' '--' '-' '+' '.' '1e5e5' '0x10'
  '1,,2' '1 2' '2*0.5' "1'" '"1"' '(1)' '1/2' '1;2' '1:2' '1_dp' 'NaNx' '1.0.0' '１'
  '1·0' '++1' '1e+' '#1' 'true' '$1' '1%' '1&' '=1')
CTRL=($'\t' $'\n' $'\r' ';' ' ' $'\x01' $'\x7f' $'\x1b' '/' '*' ',' "'" '!' $'\v' $'\f')
long_digits() { local d=1234567890 s="" k; for ((k = 0; k < $1; k += 10)); do s+=$d; done
                N=${s:0:$1}; }
mutate_number() {
  local t=$1 k
  VERDICT=any
  rnd 12
  case $R in
    0|1|2) pick "${VALID_POOL[@]}"; N=$P; MKIND="number from the pool" ;;
    3|4) pick "${BAD_POOL[@]}"; N=$P; VERDICT=refuse; MKIND="malformed token" ;;
    5|6) # a separator or control byte inside, then more digits
         pick "${CTRL[@]}"; local c=$P; rnd 3; MKIND="separator or control byte in a number"
         case $R in 0) N=$t$c'1' ;; 1) N=$t$c ;; 2) N=$c$t ;; esac
         # a leading or trailing blank may be trimmed; everything else is refused
         case $c in ' ') [ "$R" = 0 ] && VERDICT=refuse ;; *) VERDICT=refuse ;; esac ;;
    7) MKIND="huge digit string"; rnd 4; case $R in 0) long_digits 1000 ;; 1) long_digits 400; N=0.$N ;;
                         2) long_digits 1000; N=$N'e-1000' ;; 3) long_digits 5000 ;; esac ;;
    8) # a letter or stray character spliced into the token
       MKIND="character spliced into a number"
       pick a z q x D _ - + . e E '%' '#' '@' ; rnd $(( ${#t} + 1 ))
       N=${t:0:R}$P${t:R}
       case $P in a|z|q|x|_|'%'|'#'|'@') VERDICT=refuse ;; esac ;;
    9) # a byte removed or repeated
       MKIND="byte removed or repeated"; rnd $(( ${#t} + 1 )); k=$R; rnd 2
       if [ "$R" = 0 ]; then N=${t:0:k}${t:k+1}; else N=${t:0:k+1}${t:k}; fi ;;
    10) MKIND="exponent appended"; pick '1e' 'e' '1e3' 'e-9' 'E+400' 'e400' 'e-400' 'd0' '0'; N=$t$P
        case $P in e|'1e') VERDICT=refuse ;; esac ;;
    11) MKIND="sign prefixed"; pick '-' '+' '--' '+-' '0' '00' ' '; N=$P$t
        case $P in '--'|'+-') VERDICT=refuse ;; esac ;;
  esac
  [ -n "$N" ] || VERDICT=refuse
}

# mutate_value TOKEN: N, VERDICT for a flag value (a number or a comma list).
mutate_value() {
  local t=$1
  if [[ $t == *,* ]]; then
    local -a el
    IFS=, read -ra el <<< "$t"
    rnd 6
    case $R in
      0) N=$t,${el[0]}; VERDICT=any; MKIND="list one longer" ;;
      1) N=${t%,*}; VERDICT=any; MKIND="list one shorter" ;;
      2) N=$t,; VERDICT=refuse; MKIND="list with a trailing comma" ;;
      3) N=${t/,/,,}; VERDICT=refuse; MKIND="list with an empty element" ;;
      *) rnd ${#el[@]}; local k=$R
         mutate_number "${el[k]}"; el[k]=$N
         local IFS=,; N="${el[*]}"; unset IFS; MKIND="list element: $MKIND"
         # an element turned into two by a comma is a valid list of another length
         [[ ${el[k]} == *,* ]] && [[ ${el[k]} != *,,* ]] && [[ ${el[k]} != ,* ]] &&
           [[ ${el[k]} != *, ]] && VERDICT=any ;;
    esac
  else
    mutate_number "$t"
  fi
}

# ------------------------------------------------------------ flag families
# Valid, tiny command lines. A word "#V" is a numeric value V that may be
# mutated; "@V" a value mutated with an open verdict.
FLAG_BASES=(
  "simulate --t-end #0.02 --dt #0.001 --q1 #0.5 --q2 #-0.3 --w1 #0 --m1 #1 --l2 #1 --g #9.8 --save-every #5 --output out.h5"
  "simulate --links #3 --q #0.7,0,0 --m #1,1,1 --l #1,1,1 --t-end #0.02 --damping #0.1,0,0 --output out.h5"
  "simulate --method dopri5 --rtol #1e-6 --atol #1e-9 --t-end #0.02 --max-steps #1000 --output-dt #0.005 --output out.h5"
  "simulate --support-amplitude #0.1,0 --support-frequency #3 --support-phase #0,0 --t-end #0.02 --output out.h5"
  "simulate --method tao2 --omega #20 --theta1 #1 --theta2 #2 --w2 #0.5 --m2 #2 --l1 #0.5 --t-end #0.02 --output out.h5"
  "simulate --links #1 --g #9.8 --q #0.3 --t-end #0.02 --output out.h5"
  "lyapunov --t-end #0.5 --tau #0.1 --vectors #2 --batches #2 --q1 #0.3 --output out.h5"
  "lyapunov --links #3 --t-end #0.2 --tau #0.1 --batches #2 --m #1,2,1 --output out.h5"
  "divergence --t-end #0.3 --pairs #2 --pair-spacing #0.1 --output-dt #0.05 --delta0 #1e-9 --lyapunov-t #0 --output out.h5"
  "divergence --t-end #0.3 --pairs #2 --pair-spacing #0.1 --fit-start #0.05 --fit-end #0.2 --lyapunov-t #0.2 --same-energy --output out.h5"
  "indicators --t-end #0.2 --tau #0.05 --q1 #0.2 --w2 #0.1 --output out.h5"
  "indicators --links #3 --t-end #0.1 --tau #0.05 --output out.h5"
  "poincare --t-end #1 --ics #2 --points #3 --section-link #1 --section-angle #-1.5 --section-direction #1 --energy #-5 --output out.h5"
  "sweep --n #2 --t-end #0.5 --dt #0.05 --min1 #-1 --max1 #1 --min2 #-1 --max2 #1 --block #2 --threads #1 --output out.h5 --quiet"
  "sweep --n1 #2 --n2 #3 --axis1 m2/m1 --axis2 theta1 --min1 #0.5 --max1 #2 --t-end #0.5 --indicator megno --threads #1 --output out.h5 --quiet"
  "sweep --links #3 --n #2 --axis1 theta1 --axis2 theta3 --t-end #0.3 --time-unit s --dt #0.05 --g #9.8 --threads #1 --output out.h5 --quiet"
  "sweep --links #1 --n #2 --axis1 theta1 --axis2 w1 --t-end #0.3 --time-unit s --dt #0.05 --threads #1 --output out.h5 --quiet"
  "sweep --ic-file list.txt --t-end #0.5 --m1 #1 --threads #1 --lyapunov --output out.h5 --quiet"
  "sweep --body point --n #2 --axis1 m2/m1 --axis2 l2/l1 --min1 #0.5 --max1 #2 --min2 #0.5 --max2 #2 --q1 #0.3 --t-end #0.5 --dt #0.05 --threads #1 --output out.h5 --quiet"
  "sweep --com #0.5,0.5 --n #2 --axis1 g --axis2 com1 --min1 #2 --max1 #12 --min2 #0.2 --max2 #0.8 --t-end #0.3 --dt #0.05 --threads #1 --output out.h5 --quiet"
  "sweep --n #2 --t-end #0.3 --time-unit s --dt #0.05 --torque-file tq.csv --damping #0.1,0 --coulomb #0.05,0.02 --threads #1 --output out.h5 --quiet"
  "sweep --links #3 --n #2 --axis1 m1 --axis2 theta2 --min1 #0.5 --max1 #2 --t-end #0.3 --dt #0.05 --support-amplitude #0,0.02 --support-frequency #9 --indicator megno --threads #1 --output out.h5 --quiet"
  "sweep --model elastic --q #1.2,-1 --n #2 --axis1 k --axis2 l0 --min1 #20 --max1 #60 --min2 #0.5 --max2 #1.5 --t-end #0.3 --dt #0.05 --indicator megno --threads #1 --output out.h5 --quiet"
  "simulate --model elastic --q #1.2,-1 --w #0,0 --m #1 --k #40 --l0 #1 --g #9.8 --t-end #0.02 --output out.h5"
  "sweep --n #2 --t-end #0.5 --dt #0.05 --device auto --gpu-repack #2048 --block #4 --threads #1 --output out.h5 --quiet"
  "study --config study_tiny.nml --no-figures --threads #1 --m1 #1 --l2 #1 --g #9.8 --output st.h5"
  "study --config study_tiny.nml --no-figures --quick --m #1,1 --l #1,1 --output st.h5"
  "fit fit.csv --fit-window #0.3 --horizon-tolerance #0.1 --starts #1 --dt #0.01 --rtol #1e-6 --atol #1e-9 --max-steps #10000 --m1 #1 --g #9.8 --output out.h5"
  "fit fit.csv --fit-damping --damping #0.05,0.03 --l #1,1 --output out.h5"
  "fit fit.csv --fit-param com2,c2 --com #0.6,0.5 --inertia #0.08,0.03 --sigma #0.005 --output out.h5"
  "fit fit.csv --body point --fit-param m2,l2 --sigma #0.01 --m #1,1 --output out.h5"
  "simulate --body point --q #0.5,1 --t-end #0.02 --output out.h5"
  "simulate --com #0.6,0.8 --inertia #0.05,0 --damping #0.1,0 --t-end #0.02 --output out.h5"
  "lyapunov --model elastic --q #1.2,-1 --k #40 --l0 #1 --t-end #0.3 --tau #0.1 --batches #2 --output out.h5"
  "indicators --body point --q1 #0.3 --m2 #0.5 --l2 #0.8 --t-end #0.2 --tau #0.05 --output out.h5"
  "divergence --com #0.6,0.5 --inertia #0.08,0.03 --g #9.8 --t-end #0.3 --pairs #2 --pair-spacing #0.1 --output-dt #0.05 --lyapunov-t #0 --output out.h5"
  "simulate --rotor-inertia #0.01,0.02 --gear-ratio #10,5 --coulomb #0.1,0 --coulomb-speed #0.01 --t-end #0.02 --output out.h5"
  "simulate --angles relative --q #0.3,-0.5 --w #0.1,0 --torque-file tq.csv --t-end #0.02 --output out.h5"
  "lyapunov --torque-file tq.csv --rotor-inertia #0.01,0 --angles relative --q2 #0.4 --t-end #0.2 --tau #0.1 --batches #2 --output out.h5"
  "torques robot.csv --degree #4 --window #9 --m #1,0.7 --l #0.8,0.6 --coulomb-speed #0.5 --rotor-inertia #1e-4,0 --output out.h5 --quiet"
  "identify robot.csv --degree #2 --m #1,0.7 --l #0.8,0.6 --coulomb-speed #0.5 --rotors estimate --output out.h5 --quiet"
  "animate sim.h5 --fps #25 --duration #0.04 --speed #1 --size @64x64 --output a.gif"
  "animate sim.h5 --overlay sim.h5 --reactions --fps #10 --duration #0.1 --size @64x64 --output a.gif"
  "export sw_a.h5 --matrix t_flip axis1 axis2 #2"
  "sweep-compare sw_a.h5 sw_b.h5 --rel #0.01"
  "sweep-compare ind_a.h5 ind_b.h5 --agreement --threshold-a #2.5 --threshold-b #2.5 --output ag.h5"
)
# Files a base needs in its directory (copied from the fixtures).
needs_of() {
  NEEDS=()
  local w
  for w in "${ARGS[@]}"; do
    case $w in *.h5|*.nml|*.csv|*.txt) [ -f "$F/$w" ] && NEEDS+=("$w") ;; esac
  done
}

# gen_flag: ARGS, INPUTS, VERDICT, WHAT for a flag case.
gen_flag() {
  pick "${FLAG_BASES[@]}"
  local -a words
  read -ra words <<< "$P"
  ARGS=(); local -a slots=() anyslots=()
  local w
  for w in "${words[@]}"; do
    case $w in
      '#'*) slots+=(${#ARGS[@]}); ARGS+=("${w:1}") ;;
      '@'*) anyslots+=(${#ARGS[@]}); ARGS+=("${w:1}") ;;
      *) ARGS+=("$w") ;;
    esac
  done
  local cmd=${ARGS[0]}
  rnd 20
  if [ "$R" -lt 13 ] && [ ${#slots[@]} -gt 0 ]; then
    pick "${slots[@]}"; local k=$P
    mutate_value "${ARGS[k]}"
    WHAT="value of ${ARGS[k-1]}: ${ARGS[k]} -> $N"; TAG="flag value, $MKIND"
    ARGS[k]=$N
    # a flag whose value starts with '-' may read as a missing value: still refused
  elif [ "$R" -lt 14 ] && [ ${#anyslots[@]} -gt 0 ]; then
    pick "${anyslots[@]}"; local k=$P
    pick 64 64x 64x64x64 0x0 65536x64 64X64 ' 64x64' '64x64 ' 1e2x64 -64x64 64x1e9 \
         $'64\tx64' 64,64 x64 '' 999999999999x64
    ARGS[k]=$P; VERDICT=any; WHAT="value of ${ARGS[k-1]}"; TAG="flag value WxH"
    case $P in 64x64x64|65536x64|-64x64|64x1e9|$'64\tx64'|x64|''|999999999999x64|0x0|64x)
      VERDICT=refuse ;;
    esac
  elif [ "$R" -lt 16 ] && [ ${#slots[@]} -gt 0 ]; then
    # a flag repeated with another value
    pick "${slots[@]}"; local k=$P
    mutate_value "${ARGS[k]}"
    ARGS+=("${ARGS[k-1]}" "$N")
    VERDICT=refuse; WHAT="repeated flag ${ARGS[k-1]}"; TAG="repeated flag"
  elif [ "$R" -lt 17 ] && two_places "$cmd"; then
    :   # the same quantity in a flag and in the file, or in two groups of the file
  elif [ "$R" -lt 17 ]; then
    # two forms of one quantity
    case $cmd in
      simulate|lyapunov|divergence|indicators|poincare)
        pick "--m 1,2 --m1 3" "--m1 3 --m 1,2" "--q 0.1,0.2 --q1 0.5" "--q1 0.5 --theta1 1" \
             "--w 0,0 --w2 1" "--l 1,1 --l2 2" "--theta2 1 --q2 0.5" "--q 0.1,0.2 --theta1 1" ;;
      sweep) pick "--m 1,1 --m1 2" "--q 0,0 --q1 0.5" "--n 2 --n1 3" "--l 1,1 --l1 2" ;;
      fit) pick "--m 1,1 --m1 2" "--l 1,1 --l2 2" "--body point --com 1,1" \
                "--body rod --inertia 0.1,0.1" ;;
      study) pick "--m 1,1 --m1 2" "--l 1,1 --l2 2" ;;
      *) pick "" ;;
    esac
    if [ -n "$P" ]; then
      local -a extra; read -ra extra <<< "$P"
      ARGS+=("${extra[@]}"); VERDICT=refuse; WHAT="two forms: $P"; TAG="two forms of one quantity (flags)"
    else
      ARGS+=(--fuzz-unknown); VERDICT=refuse; WHAT="unknown flag"; TAG="unknown flag"
    fi
  elif [ "$R" -lt 18 ]; then
    # a flag without its value, or an unknown flag
    pick "${ARGS[@]:1}"
    case $P in
      --*) ARGS+=("$P"); VERDICT=refuse
           case $P in --force|--quiet|--no-figures|--quick|--reactions|--same-energy|--lyapunov|\
                      --fit-damping|--stats|--agreement|--list|--csv|--matrix)
                      WHAT="flag $P repeated"; TAG="repeated flag" ;;
                      *) WHAT="flag $P without a value at the end"; TAG="flag without its value" ;;
           esac ;;
      *) ARGS+=(--fuzz_x "1"); VERDICT=refuse; WHAT="unknown flag"; TAG="unknown flag" ;;
    esac
  else
    # the output names an input, with or without --force
    local out=""
    for w in "${ARGS[@]:1}"; do
      case $w in *.h5|*.nml|*.csv|*.txt) [ -f "$F/$w" ] && { out=$w; break; } ;; esac
    done
    if [ -n "$out" ] && [ "$cmd" != export ]; then
      ARGS+=(--output "$out"); rnd 2; [ "$R" = 0 ] && ARGS+=(--force)
      VERDICT=refuse; WHAT="output over the input $out"; TAG="output names an input"
    else
      mutate_value 1; ARGS+=(--fuzz-value "$N"); VERDICT=refuse; WHAT="unknown flag"
      TAG="unknown flag"
    fi
  fi
  needs_of
  [ -f two.nml ] && NEEDS+=(two.nml)
  return 0
}

# two_places CMD: (half the time, for a command that reads --config and has none yet)
# a namelist two.nml giving a quantity the flags give too (VERDICT any: the flag
# wins, which the provenance check sees) or giving one quantity in two groups
# (refused naming both). False when not done.
two_places() {
  rnd 2; [ "$R" = 0 ] && return 1
  case $1 in simulate|lyapunov|divergence|indicators|poincare|sweep|fit) ;; *) return 1 ;; esac
  [[ " ${ARGS[*]} " == *" --config "* ]] && return 1
  local key="" k
  for k in --m1 --m2 --l1 --l2 --g --k --l0; do
    [[ " ${ARGS[*]} " == *" $k "* ]] && { key=${k#--}; break; }
  done
  rnd 2
  if [ -n "$key" ] && [ "$R" = 0 ]; then
    local grp=pendulum
    [[ $key == k || $key == l0 ]] && grp=model
    printf '&%s %s = 7.25 /\n' "$grp" "$key" > two.nml
    VERDICT=any; WHAT="$key as a flag and in &$grp of the file (the flag wins)"
    TAG="quantity as a flag and in the file"
  elif [[ " ${ARGS[*]} " != *" elastic "* ]]; then
    printf '&model m = 1.5, 2.5 /\n&pendulum m1 = 3 /\n' > two.nml
    VERDICT=refuse; WHAT="m in &model and m1 in &pendulum"; TAG="namelist two groups give one quantity"
  else
    return 1
  fi
  ARGS+=(--config two.nml)
}

# ------------------------------------------------------------ namelist family
# seed file and the flags that keep its run tiny
NML_SEEDS=(
  "simulate.nml|simulate --t-end 0.02 --output out.h5"
  "elastic.nml|simulate --t-end 0.02 --output out.h5"
  "point_mass.nml|simulate --t-end 0.02 --output out.h5"
  "chaos.nml|lyapunov --t-end 0.5 --tau 0.1 --batches 2 --output out.h5"
  "chaos.nml|divergence --t-end 0.3 --pairs 2 --pair-spacing 0.1 --output-dt 0.05 --lyapunov-t 0 --output out.h5"
  "chaos.nml|poincare --t-end 1 --ics 2 --points 3 --output out.h5"
  "chaos.nml|indicators --t-end 0.2 --tau 0.05 --output out.h5"
  "sweep_classic.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_lambda1.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_list.nml|sweep --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_mass_length_megno.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_megno.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_theta1_mass_ratio.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_triple.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "sweep_velocities.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "study_tiny.nml|study --no-figures --threads 1 --output st.h5"
  "bob_pendulum.nml|simulate --t-end 0.02 --output out.h5"
  "elastic_sweep.nml|sweep --n1 2 --n2 2 --t-end 0.5 --dt 0.05 --threads 1 --output out.h5 --quiet"
  "study.nml|study --quick --no-figures --methods rk4 --threads 1 --output st.h5"
  "study_chain.nml|study --quick --no-figures --methods rk4 --threads 1 --output st.h5"
  "study_damped.nml|study --quick --no-figures --methods rk4 --threads 1 --output st.h5"
  "elastic_study.nml|study --quick --no-figures --methods rk4 --threads 1 --output st.h5"
)
declare -A SEED_TEXT=()
RE_ASSIGN='[A-Za-z_][A-Za-z0-9_]*(\([0-9]+\))?[[:space:]]*='
load_seed() {  # TEXT: the seed file's content (cached)
  if [ -z "${SEED_TEXT[$1]+x}" ]; then SEED_TEXT[$1]=$(< "$F/$1"); fi
  TEXT=${SEED_TEXT[$1]}
}

# gen_nml: a mutated namelist in case.nml, its command in ARGS.
gen_nml() {
  pick "${NML_SEEDS[@]}"
  local seed=${P%%|*} cmdline=${P#*|}
  read -ra ARGS <<< "$cmdline"
  local cmd=${ARGS[0]}
  ARGS=("$cmd" --config case.nml "${ARGS[@]:1}")
  NEEDS=()
  [ "$seed" = sweep_list.nml ] && NEEDS+=(sweep_list.txt)
  load_seed "$seed"; SEEDFILE=$seed
  local -a lines; mapfile -t lines <<< "$TEXT"
  local n=${#lines[@]} i k
  # the lines holding an assignment "key = value" (not in a comment)
  local -a alines=()
  for ((i = 0; i < n; i++)); do
    local code=${lines[i]%%!*}
    [[ $code =~ $RE_ASSIGN ]] && alines+=("$i")
  done
  VERDICT=any
  rnd 16
  case $R in
    0|1|2|3) # a numeric value mutated
      local tries
      for tries in 1 2 3 4 5 6 7 8; do
        pick "${alines[@]}"; i=$P
        local code=${lines[i]%%!*} rest=""
        [ "$code" != "${lines[i]}" ] && rest="!${lines[i]#*!}"
        # the values of the line: KEY = VALUE pairs split at ", KEY ="
        local re_num='^(.*[A-Za-z0-9_)][[:space:]]*=[[:space:]]*)([-+.0-9][-+.0-9eEdD]*)(.*)$'
        if [[ $code =~ $re_num ]]; then
          local pre=${BASH_REMATCH[1]} val=${BASH_REMATCH[2]} post=${BASH_REMATCH[3]}
          # the first number of the line (pre is greedy: the last one; either is fine)
          mutate_number "$val"
          # in a namelist, '!' starts a comment, ',' '/' and blanks separate values
          case $N in *'!'*|*','*|*'/'*|*' '*|*$'\t'*|*$'\n'*|*$'\r'*|*'*'*|*"'"*|*$'\v'*|*$'\f'*)
            VERDICT=any ;; esac
          [ "$N" = "$val" ] && VERDICT=any   # the mutation changed nothing
          lines[i]="$pre$N$post$rest"; WHAT="value of line $((i + 1)): $val -> $N"; TAG="namelist value, $MKIND"
          break
        fi
      done
      [ -n "${WHAT:-}" ] || { WHAT="no numeric line"; } ;;
    4) # a repeated key: the assignment line again with another value
      pick "${alines[@]}"; i=$P
      local code=${lines[i]%%!*}
      local re_key='^[[:space:]]*(&[A-Za-z_]+[[:space:]]+)?([A-Za-z_][A-Za-z0-9_]*(\([0-9]+\))?)[[:space:]]*=[[:space:]]*([^,/]*)'
      if [[ $code =~ $re_key ]]; then
        local key=${BASH_REMATCH[2]} val=${BASH_REMATCH[4]}
        val=${val%"${val##*[![:space:]]}"}
        if [[ ${BASH_REMATCH[1]} == '&'* ]]; then
          lines[i]="${lines[i]/$key/$key = $val, $key}"
        else
          lines[i]="${lines[i]}"$'\n'"  $key = $val"
        fi
        VERDICT=refuse; WHAT="repeated key $key"; TAG="namelist repeated key"
      else
        WHAT="repeated key: none found"
      fi ;;
    5) # a '%' component
      pick "${alines[@]}"; i=$P
      if [[ ${lines[i]} =~ ([A-Za-z_][A-Za-z0-9_]*)[[:space:]]*= ]]; then
        local key=${BASH_REMATCH[1]}
        pick "$key%x" "pendulum%$key" "$key%$key" "$key % y"
        lines[i]=${lines[i]/$key/$P}; VERDICT=refuse; WHAT="'%' key $P"; TAG="namelist '%' key"
      fi ;;
    6) # two forms of one quantity
      local g
      for ((i = 0; i < n; i++)); do
        case ${lines[i]} in
          *'&pendulum'*) pick "m = 1.0, 1.0" "l = 1.0, 1.0"; g=$P
                         [[ $TEXT == *m1* || $TEXT == *l1* ]] || continue
                         lines[i]="${lines[i]/&pendulum/&pendulum $g,}"
                         VERDICT=refuse; WHAT="two forms: $g with m1/l1"; TAG="namelist two forms of one quantity"; break ;;
          *'&initial'*) pick "q = 0.0, 0.0" "w = 0.0, 0.0"; g=$P
                        [[ $TEXT == *q1* || $TEXT == *w1* ]] || continue
                        lines[i]="${lines[i]/&initial/&initial $g,}"
                        VERDICT=refuse; WHAT="two forms: $g with q1/w1"; TAG="namelist two forms of one quantity"; break ;;
        esac
      done
      if [ "$VERDICT" != refuse ]; then
        lines+=("&pendulum m = 1.0, 1.0, m1 = 5.0 /"); VERDICT=refuse
        WHAT="two forms: m with m1 in a new group"; TAG="namelist two forms of one quantity"
      fi ;;
    7) # a key misspelled or changed in case
      pick "${alines[@]}"; i=$P
      if [[ ${lines[i]} =~ ([A-Za-z_][A-Za-z0-9_]*)[[:space:]]*= ]]; then
        local key=${BASH_REMATCH[1]}
        rnd 4
        case $R in
          3) if [[ ${lines[i]} != *'&'* && ${lines[i]} != *'/'* ]]; then
               lines[i]="! removed: ${lines[i]}"; WHAT="assignment of $key removed (line $((i + 1)))"
             else
               lines[i]=${lines[i]/$key/${key}x}; VERDICT=refuse; WHAT="unknown key ${key}x"
             fi
             TAG="namelist key removed or renamed" ;;
          0) lines[i]=${lines[i]/$key/${key}x}; VERDICT=refuse; WHAT="unknown key ${key}x"; TAG="namelist unknown key" ;;
          1) lines[i]=${lines[i]/$key/${key^^}}; WHAT="key in capitals ${key^^}"; TAG="namelist key in capitals" ;;
          2) lines[i]=${lines[i]/$key/${key}(99999)}; WHAT="key $key(99999)"; TAG="namelist key index 99999" ;;
        esac
      fi ;;
    8) TAG="namelist group edited" # a group: renamed, its end removed, repeated, or its '&' removed
      local -a glines=()
      for ((i = 0; i < n; i++)); do [[ ${lines[i]} == *'&'[a-z]* ]] && glines+=("$i"); done
      pick "${glines[@]}"; i=$P
      rnd 4
      case $R in
        0) lines[i]=${lines[i]/&/&x}; WHAT="group renamed" ;;
        1) lines[i]=${lines[i]/&/}; WHAT="group without &" ;;
        2) lines+=("${lines[i]}"); WHAT="group line repeated at the end" ;;
        3) for ((k = i; k < n; k++)); do
             if [[ ${lines[k]%%!*} == *'/'* ]]; then
               local c=${lines[k]%%!*}; lines[k]=${c%/*}${c##*/}; break; fi
           done; WHAT="group end removed" ;;
      esac ;;
    9) TAG="namelist separator swapped" # separators: ',' '=' swapped for another byte
      pick "${alines[@]}"; i=$P
      pick ';' $'\t' ' ' '' ',,' '==' ':' $'\n' '/' '&'
      local sep=$P; rnd 2
      if [ "$R" = 0 ]; then lines[i]=${lines[i]/=/$sep}; WHAT="'=' -> $(printf %q "$sep")"
      else lines[i]=${lines[i]/,/$sep}; WHAT="',' -> $(printf %q "$sep")"; fi ;;
    10) TAG="namelist value huge, NaN, Inf or of another type" # huge, NaN, Inf as the value of a key
      pick "${alines[@]}"; i=$P
      local big; long_digits 1000; big=$N
      pick nan inf -inf 1e999 "$big" "0.$big" "${big}e-990" 1.8e308 4e-330 -0 "'x'" ".true."
      local v=$P
      if [[ ${lines[i]} =~ ^([^=]*=[[:space:]]*)([^,/!]*)(.*)$ ]]; then
        lines[i]="${BASH_REMATCH[1]}$v${BASH_REMATCH[3]}"
      fi
      WHAT="value of line $((i + 1)) -> ${v:0:20}" ;;
    11) TAG="namelist control byte" # a control byte somewhere
      pick "${alines[@]}"; i=$P
      pick $'\x00' $'\x01' $'\x1b' $'\x7f' $'\t' $'\r' $'\x80' $'\xff' $'\xef\xbb\xbf'
      local c=$P; rnd $(( ${#lines[i]} + 1 ))
      lines[i]="${lines[i]:0:R}$c${lines[i]:R}"; WHAT="byte $(printf %q "$c") in line $((i + 1))" ;;
    12) TAG="namelist truncated" # the file truncated
      local all; all=$(printf '%s\n' "${lines[@]}")
      rnd $(( ${#all} + 1 )); lines=("${all:0:R}"); WHAT="truncated at byte $R" ;;
    13) TAG="namelist string value" # a string value changed
      pick "${alines[@]}"; i=$P
      pick "'" "'rk4" "''" "'$(printf 'x%.0s' {1..300})'" '"rk4"' "rk4" "'r k4'" $'\'rk4\n\'' \
           "'rk4'" "'dop853'" "'gauss8'" "'tao2'" "'verlet'" "'theta1'" "'w2'" "'m2/m1'" \
           "'../../etc/passwd'" "'/dev/null'" "'case.nml'"
      local v=$P
      if [[ ${lines[i]} =~ ^([^=]*=[[:space:]]*)([^,/!]*)(.*)$ ]]; then
        lines[i]="${BASH_REMATCH[1]}$v${BASH_REMATCH[3]}"
      fi
      WHAT="value of line $((i + 1)) -> $(printf %q "$v" | cut -c1-30)" ;;
    14) TAG="namelist repeat count or list for a scalar" # a repeat count or a list where a scalar goes
      pick "${alines[@]}"; i=$P
      pick "2*1.0" "1.0, 2.0" "3*" "1.0 2.0" "," "0, 0, 0, 0, 0"
      local v=$P
      if [[ ${lines[i]} =~ ^([^=]*=[[:space:]]*)([^,/!]*)(.*)$ ]]; then
        lines[i]="${BASH_REMATCH[1]}$v${BASH_REMATCH[3]}"
      fi
      WHAT="value of line $((i + 1)) -> $v" ;;
    15) TAG="namelist byte edits" # byte-level edits
      local all; all=$(printf '%s\n' "${lines[@]}")
      local e
      for e in 1 2 3; do
        rnd $(( ${#all} + 1 )); k=$R; rnd 3
        case $R in
          0) all=${all:0:k}${all:k+1} ;;
          1) pick '=' ',' '/' '&' '!' "'" '%' '(' ')' ' ' 1 e; all=${all:0:k}$P${all:k} ;;
          2) all=${all:0:k}${all:k:1}${all:k} ;;
        esac
      done
      lines=("$all"); WHAT="three byte edits" ;;
  esac
  printf '%s\n' "${lines[@]}" > case.nml
  INPUTS=(case.nml "${NEEDS[@]}")
}

# ------------------------------------------------------------------ CSV family
# gen_csv: a mutated fit CSV in case.csv.
gen_csv() {
  load_seed fit.csv
  local -a lines; mapfile -t lines <<< "$TEXT"
  local n=${#lines[@]} i k
  ARGS=(fit case.csv --output out.h5)
  rnd 4; [ "$R" = 0 ] && ARGS+=(--fit-window 0.3)
  VERDICT=any
  local out
  rnd 22
  case $R in
    0) lines[0]=$'\xef\xbb\xbf'${lines[0]}; VERDICT=accept; WHAT="UTF-8 BOM" ;;
    1) lines[0]='"t","theta1","theta2"'; VERDICT=accept; WHAT="quoted header" ;;
    2) for ((i = 0; i < n; i++)); do lines[i]=${lines[i]//,/$'\t'}; done
       VERDICT=accept; WHAT="tab separators" ;;
    3) for ((i = 0; i < n; i++)); do lines[i]=${lines[i]//,/;}; done
       VERDICT=accept; WHAT="';' separators" ;;
    4) lines[0]='t [s],theta1 [rad],theta2 [rad]'; VERDICT=accept; WHAT="units in the header" ;;
    5) for ((i = 0; i < n; i++)); do lines[i]=${lines[i]}$'\r'; done; WHAT="CRLF line ends" ;;
    6) rnd $((n - 1)); i=$((R + 1)); lines[i]=${lines[i]%,*}
       VERDICT=refuse; WHAT="row $((i + 1)) truncated" ;;
    7) rnd $((n - 1)); i=$((R + 1)); lines[i]=${lines[i]},1.0
       VERDICT=refuse; WHAT="row $((i + 1)) with an extra field" ;;
    8) rnd $((n - 1)); i=$((R + 1)); pick nan NaN inf -inf Infinity -nan
       local -a f; IFS=, read -ra f <<< "${lines[i]}"; rnd 3; f[R]=$P
       lines[i]=$(IFS=,; echo "${f[*]}"); VERDICT=refuse; WHAT="$P in row $((i + 1))" ;;
    9) rnd $((n - 1)); i=$((R + 1)); pick 1e300 -1e300 1e308 1e200 1e9 1e-300
       local -a f; IFS=, read -ra f <<< "${lines[i]}"; rnd 2; f[R+1]=$P
       lines[i]=$(IFS=,; echo "${f[*]}"); WHAT="angle $P in row $((i + 1))" ;;
    10) rnd $((n - 2)); i=$((R + 1))
        local a=${lines[i]%%,*} b=${lines[i+1]%%,*}
        lines[i]=$b,${lines[i]#*,}; lines[i+1]=$a,${lines[i+1]#*,}
        VERDICT=refuse; WHAT="times of rows $((i + 1)), $((i + 2)) swapped" ;;
    11) rnd $((n - 2)); i=$((R + 1))
        lines[i+1]=${lines[i]%%,*},${lines[i+1]#*,}
        VERDICT=refuse; WHAT="time of row $((i + 2)) repeated" ;;
    12) rnd $((n - 1)); i=$((R + 1))
        local -a f; IFS=, read -ra f <<< "${lines[i]}"; rnd 3; k=$R
        mutate_number "${f[k]}"
        # a quoted number is a CSV field (the quotes are removed), and blanks (space,
        # tab) around a field are ignored (src/io/dpend_csv.f90): still numbers
        [ "$N" = '"1"' ] && VERDICT=any
        local core=$N
        while [[ $core == [$' \t']* ]]; do core=${core:1}; done
        while [[ $core == *[$' \t'] ]]; do core=${core%?}; done
        [ "$core" != "$N" ] && [ "$core" = "${f[k]}" ] && VERDICT=any
        # a CR after the row's last field is a CRLF line end (accepted, as case 5)
        [ "$k" = 2 ] && [ "$N" = "${f[k]}"$'\r' ] && VERDICT=any
        f[k]=$N
        case $N in *,*) VERDICT=refuse ;; esac
        local row=${lines[i]}
        # (the command substitution drops a trailing newline: then nothing changed)
        lines[i]=$(IFS=,; echo "${f[*]}"); WHAT="field $((k + 1)) of row $((i + 1))"
        [ "${lines[i]}" = "$row" ] && VERDICT=any ;;
    13) pick 1e8 1e6 1e9 1e10 3600; local sc=$P
        # rebuild: row i at t = (i-1) * 10^k s with the seed's angles
        mapfile -t lines <<< "$TEXT"
        for ((i = 1; i < n; i++)); do lines[i]="$((i - 1))e${sc#1e},${lines[i]#*,}"; done
        [ "$sc" = 3600 ] && for ((i = 1; i < n; i++)); do lines[i]="$(( (i - 1) * 3600 )),${lines[i]#*,}"; done
        WHAT="samples ${sc} s apart" ;;
    14) lines=("${lines[0]}"); VERDICT=refuse; WHAT="header only" ;;
    15) lines=(""); VERDICT=refuse; WHAT="empty file" ;;
    16) lines=("${lines[@]:1}"); VERDICT=refuse; WHAT="no header" ;;
    17) pick 't,theta2,theta1' 'theta1,t,theta2' 't,q1,q2' 't,x1,y1' 'time,theta1,theta2' \
             'T,THETA1,THETA2' 't,theta1,theta2,theta3' 't,theta1' 't,theta1,theta1' ' t , theta1 , theta2'
        lines[0]=$P; WHAT="header '$P'"
        case $P in time,*|'t,theta1,theta2,theta3'|'t,theta1,theta1') VERDICT=refuse ;; esac ;;
    18) rnd $n; i=$R; local big; long_digits 100000; lines[i]=${lines[i]},$N
        VERDICT=refuse; WHAT="a 100000-digit field in line $((i + 1))" ;;
    19) local all; all=$(printf '%s\n' "${lines[@]}")
        local e
        for e in 1 2 3; do
          rnd $(( ${#all} + 1 )); k=$R; rnd 3
          case $R in
            0) all=${all:0:k}${all:k+1} ;;
            1) pick ',' '"' $'\t' ';' ' ' '#' $'\n' $'\x00' $'\xff' e -; all=${all:0:k}$P${all:k} ;;
            2) all=${all:0:k}${all:k:1}${all:k} ;;
          esac
        done
        lines=("$all"); WHAT="three byte edits" ;;
    20) rnd $((n - 1)); i=$((R + 1))
        pick $'\t' ';' ' ' $'\x01' 'x' '"' "'"; local c=$P
        local -a f; IFS=, read -ra f <<< "${lines[i]}"; rnd 3; k=$R
        f[k]=${f[k]}$c'5'
        lines[i]=$(IFS=,; echo "${f[*]}"); VERDICT=refuse
        [ "$c" = ' ' ] && VERDICT=any
        WHAT="$(printf %q "$c")5 after field $((k + 1)) of row $((i + 1))" ;;
    21) rnd $((n - 1)); i=$((R + 1)); lines[i]="# comment"$'\n'"${lines[i]}"$'\n'
        WHAT="comment and blank line before row $((i + 1))" ;;
  esac
  printf '%s\n' "${lines[@]}" > case.csv
  INPUTS=(case.csv)
  TAG="csv: ${WHAT%% in row*}"; TAG=${TAG%% of row*}; TAG=${TAG%% before row*}
  TAG=${TAG%% in line*}; TAG=${TAG//[0-9]/N}
}

# progressing FILE: two or more progress lines of dpend_progress in FILE
# ("12.5% (6/48), 0.59 runs/s, elapsed 0:00:10, ETA 0:00:20") whose count went up:
# work estimated and bounded before it started, and advancing.
progressing() {
  local -a k
  mapfile -t k < <(grep -Eo '% \([0-9]+/[0-9]+\).*ETA' "$1" | sed -E 's/^% \(([0-9]+)\/.*/\1/')
  if [ ${#k[@]} -ge 2 ]; then [ "${k[${#k[@]} - 1]}" -gt "${k[0]}" ]; return; fi
  # a fraction of a horizon ("dpend lyapunov: 0.0017%, elapsed 0:00:10, ETA ~...")
  mapfile -t k < <(grep -E '^dpend [a-z-]+: [0-9.e+-]+%, .*elapsed .*ETA' "$1" |
                   sed -E 's/^dpend [a-z-]+: ([0-9.e+-]+)%.*/\1/')
  [ ${#k[@]} -ge 2 ] && awk -v a="${k[0]}" -v b="${k[${#k[@]} - 1]}" 'BEGIN { exit !(b + 0 > a + 0) }'
}

# ------------------------------------------------------------- HDF5 family
declare -A LIST_TEXT=()
# objects FILE KIND: OBJS, the lines of FILE's listing of KIND (D or A)
objects() {
  [ -n "${LIST_TEXT[$1]+x}" ] || LIST_TEXT[$1]=$(< "$F/$1.list")
  local line; OBJS=()
  while IFS= read -r line; do [[ $line == "$2 "* ]] && OBJS+=("$line"); done <<< "${LIST_TEXT[$1]}"
}
# gen_h5: a command reading HDF5 files; one of them (case.h5) mutated.
gen_h5() {
  local src other=""
  rnd 12
  case $R in
    0|1) pick sim.h5 sim3.h5 sw_a.h5 ind_a.h5 lyap.h5; src=$P; ARGS=(export case.h5 --list)
         WHAT="export --list" ;;
    2|3) pick sim.h5 sim3.h5 sw_a.h5 ind_a.h5 lyap.h5; src=$P; objects "$src" D
         ARGS=(export case.h5); rnd 3; [ "$R" = 0 ] && ARGS+=(--csv)
         local j; rnd 3
         for ((j = 0; j <= R; j++)); do pick "${OBJS[@]}"; local -a o; read -ra o <<< "$P"
                                          ARGS+=("${o[1]}"); done
         WHAT="export datasets" ;;
    4) src=sw_a.h5; ARGS=(export case.h5 --matrix t_flip axis1 axis2); WHAT="export --matrix" ;;
    5) src=ind_a.h5; ARGS=(export case.h5 --matrix megno axis1 axis2 2); WHAT="export --matrix" ;;
    6|7) pick sim.h5 sim3.h5; src=$P
         ARGS=(animate case.h5 --duration 0.04 --size 64x64 --output a.gif); WHAT="animate"
         rnd 3; [ "$R" = 0 ] && ARGS+=(--reactions)
         [ "$R" = 1 ] && { ARGS+=(--overlay "$src"); other=$src; } ;;
    8|9) pick sw_a.h5 sw_b.h5; src=$P
         if [ "$src" = sw_a.h5 ]; then other=sw_b.h5; ARGS=(sweep-compare case.h5 sw_b.h5)
         else other=sw_a.h5; ARGS=(sweep-compare sw_a.h5 case.h5); fi
         WHAT="sweep-compare" ;;
    *) pick ind_a.h5 ind_b.h5; src=$P
       if [ "$src" = ind_a.h5 ]; then other=ind_b.h5; ARGS=(sweep-compare case.h5 ind_b.h5)
       else other=ind_a.h5; ARGS=(sweep-compare ind_a.h5 case.h5); fi
       ARGS+=(--agreement --output ag.h5); WHAT="sweep-compare --agreement" ;;
  esac
  NEEDS=(); [ -n "${other:-}" ] && NEEDS=("$other")
  # the mutation
  local -a o; local op
  VERDICT=any
  rnd 14
  case $R in
    0) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"; GENARGS=(delete "${o[1]}") ;;
    1) objects "$src" A; pick "${OBJS[@]}"; read -ra o <<< "$P"; GENARGS=(delete-attr "${o[1]}" "${o[2]}") ;;
    2|3) objects "$src" A; pick "${OBJS[@]}"; read -ra o <<< "$P"
         pick "" 3 2 0 "1,1" 1000; local d=$P
         pick 0 1 -1 7 99 2147483647 -2147483648 nan inf -inf 1e300 -0.5 1e-300; local v=$P
         rnd 2
         if [ "$R" = 0 ]; then GENARGS=(attr-int "${o[1]}" "${o[2]}" "$d" "$v")
         else GENARGS=(attr-real "${o[1]}" "${o[2]}" "$d" "$v"); fi ;;
    4) objects "$src" A; pick "${OBJS[@]}"; read -ra o <<< "$P"
       pick "" x rk4 megno theta1 "1.0" "nan" "$(printf 'y%.0s' {1..2000})" $'a\nb' "m1=2" '&x /'
       GENARGS=(attr-str "${o[1]}" "${o[2]}" "$P") ;;
    5|6) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
         [ "${o[2]}" = s ] && { GENARGS=(delete "${o[1]}"); } ||
         { pick nan inf -inf 0 -1 1e300 -1e300 1e-310 7; GENARGS=(fill "${o[1]}" "$P"); } ;;
    7) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
       [ "${o[2]}" = s ] && { GENARGS=(delete "${o[1]}"); } ||
       { rnd 1000; local kk=$R; pick nan inf -inf 1e300 -1e300 0 1e-310 -5
         GENARGS=(poke "${o[1]}" "$kk" "$P"); } ;;
    8|9) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
         pick f64 f32 i32 str; local ty=$P
         pick "" 0 1 2 7 "0,2" "1,1" "2,2" "3,3,3" "7,2" "2,7" "3" "100,2" "1,4"; local d=$P
         GENARGS=(replace "${o[1]}" "$ty" "$d" 0.5) ;;
    10) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
        pick "1099511627776,2" "2,1099511627776" "4294967296" "1099511627776,3,3" \
             "1000000000,1000000000" "9223372036854775807" "65536,65536"
        GENARGS=(chunked "${o[1]}" "$P") ;;
    11) objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
        pick group softlink softlink2; case $P in
          group) GENARGS=(group "${o[1]}") ;;
          softlink) GENARGS=(softlink "${o[1]}" /nowhere) ;;
          softlink2) GENARGS=(softlink "${o[1]}" "${o[1]}") ;; esac ;;
    12) # what the command must refuse
        case ${ARGS[0]} in
          animate) pick "fill /trajectory/t 0" "poke /trajectory/q 3 1e300" \
                        "poke /trajectory/t 2 -1" "fill /trajectory/q nan"
                   read -ra GENARGS <<< "$P"; VERDICT=refuse ;;
          sweep-compare)
            if [[ $WHAT == *agreement* ]]; then
              pick "fill /sweep/megno nan" "fill /sweep/megno inf" "fill /sweep/megno -3" \
                   "delete /sweep/status" "delete /sweep/axis1" "replace /sweep/axis1 f64 7 0.5" \
                   "attr-real /sweep t_end  nan" "attr-int /sweep links  99"
            else
              # (t_flip NaN is "no flip": a valid value where the status allows it)
              pick "fill /sweep/t_flip inf" "delete /sweep/status" "delete /sweep/axis1" \
                   "replace /sweep/axis1 f64 7 0.5" "attr-real /sweep t_end  nan" \
                   "attr-int /sweep links  99" "replace /sweep/status i32 2 0"
            fi
            # "" (an empty DIMS, a scalar) is kept by splitting on two blanks
            local -a parts=(); local s=$P
            while [[ $s == *' '* ]]; do
              if [[ $s == ' '* ]]; then parts+=(""); s=${s:1}
              else parts+=("${s%% *}"); s=${s#* }; fi
            done
            parts+=("$s"); GENARGS=("${parts[@]}"); VERDICT=refuse ;;
          export)
            if [[ ${ARGS[*]} == *--matrix* ]]; then
              GENARGS=(replace /sweep/"${ARGS[3]}" f64 9 0.5); VERDICT=refuse
            else
              objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
              GENARGS=(attr-int "${o[1]}" units 3 7)
            fi ;;
        esac ;;
    13) # a wide dataset for export --csv (linear time)
        objects "$src" D; pick "${OBJS[@]}"; read -ra o <<< "$P"
        pick "2,20000" "2,50000" "3,10000"
        GENARGS=(replace "${o[1]}" f64 "$P" 0.25)
        [ "${ARGS[0]}" = export ] && ARGS=(export case.h5 --csv "${o[1]}") ;;
  esac
  SRC=$src
  "$GEN" "$F/$src" case.h5 "${GENARGS[@]}" > gen.log 2>&1 || GENFAIL=1
  TAG="hdf5: $WHAT, ${GENARGS[0]}"
  WHAT="$WHAT of $src: ${GENARGS[*]:0:3}"
  INPUTS=(case.h5 "${NEEDS[@]}")
}

# ------------------------------------------------------------------ one case
TRAP_RE='Floating point exception|Fortran runtime error|Backtrace|Error termination|HDF5-DIAG'
RE_WHERE='(In file .|at )(\./)+(src|app)/[A-Za-z0-9_./]+(:[0-9]+|., around line [0-9]+)'
RUN_FAIL_CMDS=" simulate lyapunov divergence indicators poincare sweep study fit animate "

# esc WORD...: ESC, the words escaped with printf %q, blank-separated (no fork)
esc() { local a q out=""; for a in "$@"; do printf -v q '%q' "$a"; out+=" $q"; done
        ESC=${out# }; }

# show_file NAME SEED: FILETEXT, the lines of NAME that differ from the fixture
# SEED (diff), escaped; only for a failure.
show_file() {
  local d
  d=$(diff "$F/$2" "$1" 2>/dev/null | grep '^[<>]' | head -n 6 | head -c 600)
  printf -v FILETEXT '%q' "$d"
  FILETEXT=" $1 differs from $2: $FILETEXT"
}

# run_case I DIR: generates and runs case I in DIR (created), appends one result
# line to $RESULTS: "I ok refused|ran" or "I FAIL CLASS<TAB>details".
# ---------------------------------------------------------------- results read
# The output of a run that exits 0 is read back: the settings the case gave (the
# model's quantities PROV_KEYS, from the flags, else from the namelist file) must be
# those the file records (an attribute of /, /sweep or /config under the model's
# name for it: m1, l2, g, k, ...; a list given as --m a,b as m1, m2 or as m).
PROV_KEYS=" m1 m2 l1 l2 g k l0 m l com inertia "
# h5num FILE NAME: the numeric attribute NAME of /, /sweep or /config, comma-separated
h5num() {
  local g v
  for g in / /sweep /config; do
    v=$(h5dump -m %.17g -a "${g%/}/$2" "$1" 2>/dev/null | sed -n '/DATA {/,/}/p' |
        sed -n 's/^ *([0-9,]*): *//p' | tr -d ' \n')
    [[ $v =~ ^[-+0-9.eE,]+$ ]] && { printf '%s' "$v"; return; }
  done
}
# same_numbers A B: comma lists of equal length, each within 1e-12 (relative); A
# may hold Fortran's d exponents
same_numbers() {
  awk -v a="${1//[dD]/e}" -v b="$2" 'BEGIN { n = split(a, x, ","); m = split(b, y, ",")
    if (n != m) exit 1
    for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d
      s = (x[i] < 0 ? -x[i] : x[i]); if (d > 1e-12 * (s > 1 ? s : 1)) exit 1 }
    exit 0 }'
}
# provenance OUT: PROVOK=1 when some setting was compared; PROVFAIL the first
# disagreement ('' if none)
provenance() {
  local out=$1 i k v got
  PROVOK=0 PROVFAIL=""
  local -A given=()
  for ((i = 1; i < ${#ARGS[@]} - 1; i++)); do
    case ${ARGS[i]} in --*) k=${ARGS[i]#--}; [[ $PROV_KEYS == *" $k "* ]] && given[$k]=${ARGS[i+1]} ;; esac
  done
  local f
  for f in case.nml two.nml; do
    [ -f "$f" ] || continue
    [[ " ${ARGS[*]} " == *" $f "* ]] || continue
    local line code rest re='(^|[^A-Za-z0-9_%(])(m1|m2|l1|l2|g|k|l0)[[:space:]]*=[[:space:]]*([-+]?[0-9]*\.?[0-9]+([eEdD][-+]?[0-9]+)?|[-+]?[0-9]+\.)[[:space:]]*(,|/|$)(.*)'
    while IFS= read -r line; do
      code=${line%%!*}
      while [[ $code =~ $re ]]; do
        k=${BASH_REMATCH[2]} v=${BASH_REMATCH[3]} rest=${BASH_REMATCH[6]}
        [ -n "${given[$k]+x}" ] || given[$k]=$v
        code=$rest
      done
    done < "$f"
  done
  for k in "${!given[@]}"; do
    v=${given[$k]}
    [[ $v =~ ^[-+0-9.eEdD,]+$ ]] || continue
    if [[ $v == *,* ]] || [ -z "$(h5num "$out" "$k")" ]; then
      got=$(h5num "$out" "${k}1")
      if [ -n "$got" ]; then   # a list as its components k1, k2, ...
        local -a el; IFS=, read -ra el <<< "$v"
        got=""
        for ((i = 1; i <= ${#el[@]}; i++)); do got+="${got:+,}$(h5num "$out" "$k$i")"; done
      else
        got=$(h5num "$out" "$k")
      fi
    else
      got=$(h5num "$out" "$k")
    fi
    [ -n "$got" ] || continue   # the file has no such attribute: not compared
    PROVOK=1
    if ! same_numbers "$v" "$got"; then PROVFAIL="records $k = $got, given $v"; return; fi
  done
}
# has_status OUT: the file exists and its root attribute status says why the run
# stopped (not 'completed')
has_status() {
  local st
  st=$(h5dump -a /status "$1" 2>/dev/null | sed -n 's/^ *(0): *"\(.*\)"$/\1/p' | head -n 1)
  [ -n "$st" ] && [ "$st" != completed ]
}
# output_of: the value of --output in ARGS ('' if none)
output_of() {
  local i; OUTFILE=""
  for ((i = 1; i < ${#ARGS[@]} - 1; i++)); do [ "${ARGS[i]}" = --output ] && OUTFILE=${ARGS[i+1]}; done
}
HAS_DE=0
locale -a 2> /dev/null | grep -qi '^de_DE.utf8$' && HAS_DE=1

run_case() {
  local i=$1 d=$2 t0=$EPOCHREALTIME
  mkdir -p "$d" && cd "$d" || return
  seed_case "$SEED" "$i"
  ARGS=() INPUTS=() NEEDS=() VERDICT=any WHAT="" TAG="" GENARGS=() GENFAIL=0 SRC="" PROVOK=0 PROVFAIL=""
  local fam
  rnd 100
  if [ "$R" -lt 40 ]; then fam=flag; gen_flag; INPUTS=("${NEEDS[@]}")
  elif [ "$R" -lt 62 ]; then fam=nml; gen_nml
  elif [ "$R" -lt 75 ]; then fam=csv; gen_csv
  else fam=h5; gen_h5; fi
  # threads and the locale vary (the results must not)
  local -a CASE_ENV
  pick 1 1 2 3; CASE_ENV=(OMP_NUM_THREADS=$P)
  if [ $HAS_DE = 1 ]; then pick C C.UTF-8 de_DE.UTF-8; else pick C C.UTF-8; fi
  CASE_ENV+=(LC_ALL=$P)
  WHAT="$WHAT [${CASE_ENV[*]}]"
  local f
  for f in "${NEEDS[@]}"; do [ -e "$f" ] || cp "$F/$f" "$f"; done
  if [ "$GENFAIL" = 1 ]; then
    esc "${GENARGS[@]}"
    printf '%s FAIL fuzzer: dpend-fuzz-h5 failed\tdpend-fuzz-h5 %s case.h5 %s: %s\n' \
      "$i" "$SRC" "$ESC" "$(tr '\n' ' ' < gen.log)" >> "$RESULTS"
    return
  fi
  : > stdout; : > stderr; : > sums
  local -a before_names=(* .*) after_names
  [ ${#INPUTS[@]} = 0 ] || sha256sum -- "${INPUTS[@]}" > sums 2>&1
  local rc=0
  timeout -k 2 "$TIMEOUT" env "${CASE_ENV[@]}" "$DPEND" "${ARGS[@]}" > stdout 2> stderr < /dev/null || rc=$?
  local long=0 progressed=0
  if { [ $rc = 124 ] || [ $rc = 137 ]; } && [ "$VERDICT" != refuse ]; then
    # A valid input can make a run long (a CSV angle of 1e-300 sends the fit's trial
    # trajectories to hundreds of rad/s; a namelist cut after &pendulum is the default
    # study): run it again with six times the limit. A run that ends there, or that
    # reports bounded work advancing on stderr (`progressing`), is slow (a note) if
    # nothing else is wrong; one that does neither is a hang. (The killed run's
    # temporary files stay: the rerun's refusal is judged against what it found.)
    # A changed number (--t-end 1e6) gets three times the limit: its progress must
    # show up and advance (lines every 10 s), else it is a hang.
    before_names=(* .*)
    rc=0
    local factor=6
    [[ $TAG == 'flag value'* || $TAG == 'namelist value'* ]] && factor=3
    # (without --quiet: the progress is what the rerun looks at)
    local -a rerun=()
    local w
    for w in "${ARGS[@]}"; do [ "$w" = --quiet ] || rerun+=("$w"); done
    timeout -k 2 $((factor * TIMEOUT)) env "${CASE_ENV[@]}" "$DPEND" "${rerun[@]}" > stdout \
      2> stderr < /dev/null || rc=$?
    if [ $rc != 124 ] && [ $rc != 137 ]; then long=1
    elif progressing stderr; then long=1; progressed=1; rc=0
    elif { [ "${ARGS[0]}" = sweep ] && grep -q '^dpend sweep: t_end = .*, dt = ' stderr; } ||
         { [ "${ARGS[0]}" = study ] && grep -q '^dpend study: [0-9]* runs on [0-9]* thread' stderr; }; then
      # a sweep reports progress per block of trajectories, a study per run (its
      # longest first), either of which may take days: their work was bounded
      # before they started (the sweep's horizon line, the study's run count, after
      # the checks of work and memory)
      long=1; progressed=1; rc=0
    fi
  fi
  local -a errl; mapfile -t errl < stderr
  local nlines=${#errl[@]} err=""
  [ "$nlines" = 0 ] || printf -v err '%s\n' "${errl[@]:0:40}"
  local changed=0
  if [ ${#INPUTS[@]} -gt 0 ]; then sha256sum --quiet -c sums > /dev/null 2>&1 || changed=1; fi
  local cls="" cmd=${ARGS[0]}
  local slow=0
  if [ $rc = 124 ] || [ $rc = 137 ]; then
    # A valid number that makes a run long (--t-end 1e6) is slow, not a hang: a
    # note, not a failure. Over the limit on anything else is a hang.
    # (a changed number ran three times the limit without advancing progress)
    if [ "$VERDICT" = refuse ]; then cls="invalid input accepted (ran over the limit): $TAG"
    else cls="hang: $cmd over ${TIMEOUT} s ($TAG)"; fi
  elif [ $rc = 134 ] || [ $rc = 136 ] || [ $rc = 139 ] || [[ $err =~ $TRAP_RE ]]; then
    # the class of a trap: its first source line in the backtrace, else the command
    local where=""
    [[ $err =~ $RE_WHERE ]] && where=${BASH_REMATCH[0]}
    [[ $err == *'Error allocating'* ]] && where="$where, Error allocating"
    cls="trap: $cmd exit $rc ${where:-(no backtrace; $TAG)}"
  elif [[ $err == *'Fortran runtime warning'* ]]; then
    # libgfortran's own warning (a namelist string truncated on read): not one line
    # of dpend's, and the value was cut short
    cls="Fortran runtime warning: $cmd ($TAG)"
  elif [ $changed = 1 ]; then cls="input changed or replaced: $cmd ($TAG)"
  else
    case $rc in
      2) # the refusal is one line; progress lines before it do not count (a fit that
         # finds its parameters not determined by the data refuses after its work)
         local nref
         nref=$(grep -cvE '% \([0-9]+/[0-9]+\), .*elapsed' stderr)
         if [ "$nref" != 1 ]; then cls="refusal of $nref stderr lines: $cmd ($TAG)"
         elif [ "$VERDICT" = accept ]; then cls="valid input refused: $TAG"
         else
           after_names=(* .*)
           [ "${before_names[*]}" = "${after_names[*]}" ] ||
             cls="refusal created or removed a file: $cmd ($TAG)"
         fi ;;
      0) if [ "$VERDICT" = refuse ]; then cls="invalid input accepted (exit 0): $TAG"
         elif [ $progressed = 0 ]; then
           # the output read back: the settings given are those it records
           output_of
           if [[ $OUTFILE == *.h5 && -f $OUTFILE ]]; then
             provenance "$OUTFILE"
             [ -n "$PROVFAIL" ] && cls="provenance: $cmd $PROVFAIL ($TAG)"
           fi
         fi ;;
      1) if [[ $RUN_FAIL_CMDS != *" $cmd "* ]]; then cls="exit 1 from $cmd ($TAG)"
         elif [ "$nlines" = 0 ]; then cls="exit 1 without a message: $cmd ($TAG)"
         elif [ "$VERDICT" = refuse ]; then cls="invalid input ran and failed (exit 1): $TAG"
         elif [[ " simulate lyapunov divergence indicators poincare fit " == *" $cmd "* ]]; then
           # a run that failed partway says why in its file
           output_of
           has_status "$OUTFILE" || cls="exit 1 without its file's status: $cmd ($TAG)"
         fi ;;
      *) cls="exit $rc: $cmd ($TAG)" ;;
    esac
  fi
  if [ ${#CASES[@]} -gt 0 ]; then
    esc "${ARGS[@]}"
    echo "case $i ($fam: $WHAT; verdict $VERDICT) in $d"
    echo "  input: dpend $ESC"
    case $fam in nml|csv) echo "  file: ${INPUTS[0]} (kept in $d)" ;;
                 h5) esc "${GENARGS[@]}"; echo "  file: case.h5 = dpend-fuzz-h5 $SRC case.h5 $ESC" ;; esac
    echo "  exit $rc; stderr ($nlines lines):"; head -n 20 stderr | sed 's/^/    /'
  fi
  [ $long = 1 ] && [ -z "$cls" ] && slow=1   # ended after the limit, or progressing
  if [ $slow = 1 ]; then
    esc "${ARGS[@]}"
    printf '%s slow %s\t%s; input: dpend %s\n' "$i" "$cmd ($TAG)" "${WHAT//$'\n'/\\n}" "$ESC" >> "$RESULTS"
  elif [ -z "$cls" ]; then
    local t1=$EPOCHREALTIME kind=ran prov=""
    [ $rc = 2 ] && kind=refused
    [ "${PROVOK:-0}" = 1 ] && prov=" provenance"
    echo "$i ok $kind $cmd $fam $(( (${t1/./} - ${t0/./}) / 1000 ))$prov" >> "$RESULTS"
  else
    FILETEXT=""
    case $fam in
      nml) show_file case.nml "$SEEDFILE" ;;
      csv) show_file case.csv fit.csv ;;
      h5) esc "${GENARGS[@]}"; FILETEXT=" case.h5: dpend-fuzz-h5 $SRC case.h5 $ESC" ;;
    esac
    local key=${cls//[0-9]/N} first="" what l
    [[ $cls == trap:* ]] && key=$cls  # a trap's source line is its class
    for l in "${errl[@]}"; do [[ $l == *[![:space:]]* ]] && { first=$l; break; }; done
    esc "${ARGS[@]}"
    printf -v first '%q' "${first:0:200}"
    printf -v what '%q' "${WHAT:0:200}"
    printf '%s FAIL %s\t%s; input: dpend %s;%s; exit %s; stderr: %s\n' "$i" "${key:0:140}" \
      "$what" "$ESC" "$FILETEXT" "$rc" "$first" >> "$RESULTS"
  fi
}

# --------------------------------------------------------------------- run
# the seeds and listings, read once here (the cases run in subshells)
for f in "$F"/*.nml fit.csv; do load_seed "${f##*/}"; done
for f in "$F"/*.h5; do objects "${f##*/}" D; done
START=$SECONDS
RUNDIR=$WORK/run
mkdir -p "$RUNDIR"
if [ ${#CASES[@]} -gt 0 ]; then
  RESULTS=$WORK/results.case
  : > "$RESULTS"
  for i in "${CASES[@]}"; do ( run_case "$i" "$RUNDIR/c$i" ) 2>> "$WORK/runner.err"; done
  sed -n 's/^\([0-9]*\) FAIL /FAIL case \1: /p; s/^\([0-9]*\) ok \([a-z]*\).*/case \1: \2/p
         s/^\([0-9]*\) slow /slow case \1: /p' "$RESULTS"
  grep -q '^[0-9]* FAIL ' "$RESULTS" && exit 1
  exit 0
fi

worker() {  # worker W: cases W, W + JOBS, ... until COUNT or the budget
  local w=$1 i
  RESULTS=$WORK/results.$w
  : > "$RESULTS"
  for ((i = w; i < COUNT; i += JOBS)); do
    if [ $((SECONDS - START)) -ge "$BUDGET" ]; then echo "$i budget" >> "$RESULTS"; break; fi
    run_case "$i" "$RUNDIR/w$w/c$i" 2>> "$WORK/runner.err"
    cd "$RUNDIR" || exit 1
    (( i % (50 * JOBS) < JOBS )) && rm -rf "$RUNDIR/w$w"
  done
  rm -rf "$RUNDIR/w$w"
}
for ((w = 0; w < JOBS; w++)); do worker "$w" & done
wait

cat "$WORK"/results.[0-9]* | sort -n > "$WORK/results"
refused=$(grep -c '^[0-9]* ok refused ' "$WORK/results")
ran=$(grep -c '^[0-9]* ok ran ' "$WORK/results")
failed=$(grep -c '^[0-9]* FAIL ' "$WORK/results")
slow=$(grep -c '^[0-9]* slow ' "$WORK/results")
total=$((refused + ran + failed + slow))
# slow runs (valid numbers that make a run longer than --timeout): a note per class
if [ "$slow" -gt 0 ]; then
  awk -F'\t' '/^[0-9]* slow / { split($1, a, " slow "); c = a[2]; gsub(/[0-9]+/, "N", c); n[c]++
                          if (n[c] == 1) { order[++k] = c; ex[c] = "case " a[1] ": " $2 } }
    END { for (j = 1; j <= k; j++) printf "note: slow (over the per-input limit: a valid value, or a rerun that ended or progressed): %s: %d case(s), e.g. %s\n", order[j], n[order[j]], substr(ex[order[j]], 1, 300) }' "$WORK/results"
fi
# every failure class once, with its count and its first three cases
if [ "$failed" -gt 0 ]; then
  awk -F'\t' -v seed="$SEED" -v dp="$DPEND" '
    /^[0-9]* FAIL / { split($1, a, " FAIL "); c = a[2]; n[c]++
               if (n[c] == 1) order[++k] = c
               if (n[c] <= 3) ex[c] = ex[c] sprintf("    case %s: %s\n      rerun: scripts/reliability.sh --dpend %s --seed %s --fuzz-case %s\n", a[1], $2, dp, seed, a[1]) }
    END { for (j = 1; j <= k; j++) { c = order[j]
            printf "FAIL fuzz (seed %s): %s: %d case(s)\n%s", seed, c, n[c], ex[c] } }' \
    "$WORK/results"
fi
status=0
[ "$failed" = 0 ] || status=1
if grep -q '^[0-9]* budget$' "$WORK/results"; then
  echo "FAIL fuzz: the budget of $BUDGET s ran out after $total of $COUNT inputs"; status=1
fi
prov=$(grep -c '^[0-9]* ok ran .* provenance$' "$WORK/results")
closing="fuzz: $total inputs (seed $SEED): $refused refused, $ran ran, $failed failed"
[ "$slow" = 0 ] || closing+=", $slow slow"
closing+="; $prov outputs checked for provenance"
echo "$closing ($((SECONDS - START)) s)"
exit $status
