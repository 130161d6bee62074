#!/usr/bin/env bash
# The reliability suite: table-driven bad-input cases (test/reliability/cases/*.sh),
# fault-injection tests (test/reliability/special/*.sh) and the fuzzing stage
# (test/reliability/fuzz/fuzz.sh) against the dpend binary.
# Run scripts/reliability.sh --help for the usage and the row format.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CASEDIR=$ROOT/test/reliability/cases
SPECIALDIR=$ROOT/test/reliability/special

usage() {
  cat <<'EOF'
usage: scripts/reliability.sh [options]

Runs the reliability suite: every row of test/reliability/cases/*.sh (sorted),
each in a fresh copy of the fixture directory as its cwd under `timeout 30`,
then every executable test/reliability/special/*.sh, then the fuzzing stage
(10000 fuzzed inputs; it counts as one test). Prints one line per failure and
closes with `reliability: N passed, M failed, K skipped`; exit status 1 on
any failure. With DPEND_TEST_NO_SKIP=1 in the environment (set by CI) a skipped
special test is a failure, unless its name is in DPEND_TEST_MAY_SKIP (a
space-separated list of special tests whose skip depends on privileges or timing,
not on a missing tool: CI names full_disk, device_output, corrupt_block).

options:
  --dpend PATH      binary to test (default: $DPEND, else build the debug
                    profile: . scripts/flags.sh; fpm build --flag "$DEBUG_FLAGS")
  --cases FILE...   run only these case files (no special tests unless --special)
  --special NAME... run only these special tests (kill9_simulate or
                    kill9_simulate.sh or a path; no cases unless --cases)
  --fuzz N          the fuzzing stage with N inputs: alone, or after --cases and
                    --special if given (default 10000 when the whole suite
                    runs, none with --cases or --special; --fuzz 0: the whole
                    suite without it)
  --seed S          seed of the fuzzing stage; default today's date (YYYYMMDD,
                    UTC), so a day's runs are the same and every day differs
  --fuzz-case I     rerun case I of seed S alone, verbosely (repeatable; only
                    the fuzzing stage runs): its input, exit status and stderr
  --fuzz-budget SEC wall-clock budget of the fuzzing stage (default 1500 s; no
                    case starts after it, and a stage cut short fails)
  --list            list the rows (ID, kind, file) and the special tests; run nothing
  --jobs N          rows run in parallel; default 2
  --keep            keep the temporary directory (fixtures, scratch dirs, logs)
  -v, --verbose     print every row and special test with its result
  -h, --help        this text

Row forms in a case file (bash function calls; the words after -- are the
arguments of dpend, run with the scratch directory as cwd):
  refuse  ID  FIELD  -- ARGS...   exit 2, exactly one stderr line containing FIELD
                                  (case-insensitive, - and _ alike), no file in the scratch dir
                                  created, removed or changed (names incl. hidden
                                  ones, sha256 of every file), no trap
  fail    ID  TEXT   -- ARGS...   exit 1, stderr contains TEXT (case-insensitive),
                                  no trap
  succeed ID         -- ARGS...   exit 0, no trap; and the result checked (below)
A trap: exit 134, 136 or 139, or stderr with "Floating point exception",
"Fortran runtime error", "Backtrace", "Error termination" or "HDF5-DIAG".
The result of a succeed or fail row whose command writes a file (simulate,
lyapunov, indicators, divergence, poincare, sweep, fit, study, animate,
sweep-compare --agreement; not with --help): the file is the --output/-o
value, else the namelist's &output file of --config, else the command's default
(simulate.h5, ..., out/study/study.h5, agreement.h5; animate: a new .gif). A
succeed row's file must have been written by the run (created or modified; a
complete sweep resumed says 'is complete (nothing to compute)' instead), be
HDF5 (a GIF for animate), complete as docs/hdf5-layout.md records it (root
attribute status = "completed"; a sweep's /sweep complete = 1; a study's
wall_time and its .md; fit: status "completed" and /fit converged; agreement:
/agreement) and one dataset of it finite (e.g. /trajectory/t, /sweep/energy0,
/fit/estimate). A fail row's partial file (of the commands that write a status:
simulate, lyapunov, indicators, divergence, poincare, fit) must exist, be HDF5,
and hold a status other than "completed" that stderr repeats. Files outside the
scratch directory (/dev/null, absolute paths) are not checked. A succeed row
whose command writes no file (export, sweep-compare's report, methods, --help)
must print something on stdout.
IDs are unique across all files. A case file may add fixtures with plain bash
at its top into "$FIXTURES" (also "$DPEND", "$ROOT" are set).
Fixtures: existing.h5 (simulate output), sweep.h5 (complete 8x8 grid sweep),
sweep_list.h5 (complete 3-point list sweep), list.txt (its 3-line list),
copies of data/*.nml (both as NAME.nml and data/NAME.nml), an empty dir/.
They are verified (complete, finite values) before any row runs.
  --fixture-dpend PATH  build the fixtures (and source the case files) with this
                    binary, run the rows with --dpend: e.g. to count the rows a
                    binary that only exits 0 passes (none that expects a file)

Special tests get DPEND (absolute binary), ROOT (repo root) and SCRATCH (an
empty temporary directory, also their cwd); exit 0 passes, 77 skips (its
output is shown as the note), anything else fails (its output tail is shown).

The fuzzing stage (test/reliability/fuzz/fuzz.sh --help for the details):
seeded and reproducible, 2 jobs, `timeout 10` per input. Each input mutates a
valid one: a number or list of a flag of every command, a namelist file
(data/*.nml), a fit CSV (data/fit_example.csv) or an HDF5 file read by export,
animate or sweep-compare (changed by the fpm example dpend-fuzz-h5: deleted
objects, attributes of another type, NaN/Inf, other shapes and types, huge
declared dimensions with chunked storage). Every outcome must be a one-line
refusal (exit 2, nothing touched) or a run (exit 0; exit 1 with a message
from a command that documents run failures), never a trap, a hang, a changed
input file or an invalid input accepted. It prints every failure class with
up to three cases (seed, case, input escaped, rerun command) and closes with
`fuzz: N inputs (seed S): K refused, J ran, F failed`.
EOF
}

DPEND_ARG=""
FIXTURE_DPEND=""
CASE_FILES=()
SPECIALS=()
SELECT_CASES=0
SELECT_SPECIALS=0
LIST=0
FUZZ=""
FUZZ_SEED=""
FUZZ_CASES=()
FUZZ_BUDGET=1500
JOBS=2
KEEP=0
VERBOSE=0
mode=""
while [ $# -gt 0 ]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --dpend) [ $# -ge 2 ] || { echo "reliability: --dpend needs a path" >&2; exit 2; }
             DPEND_ARG=$2; shift 2; mode=""; continue ;;
    --dpend=*) DPEND_ARG=${1#--dpend=}; mode="" ;;
    --fixture-dpend) [ $# -ge 2 ] || { echo "reliability: --fixture-dpend needs a path" >&2; exit 2; }
             FIXTURE_DPEND=$2; shift 2; mode=""; continue ;;
    --jobs) [ $# -ge 2 ] || { echo "reliability: --jobs needs a number" >&2; exit 2; }
            JOBS=$2; shift 2; mode=""; continue ;;
    --fuzz|--seed|--fuzz-budget)
      [ $# -ge 2 ] || { echo "reliability: $1 needs a number" >&2; exit 2; }
      [[ $2 =~ ^[0-9]{1,15}$ ]] || { echo "reliability: $1 needs a non-negative integer" >&2; exit 2; }
      case $1 in --fuzz) FUZZ=$2 ;; --seed) FUZZ_SEED=$2 ;; --fuzz-budget) FUZZ_BUDGET=$2 ;; esac
      shift 2; mode=""; continue ;;
    --fuzz-case) mode=fuzzcase ;;
    --cases) SELECT_CASES=1; mode=cases ;;
    --special) SELECT_SPECIALS=1; mode=special ;;
    --list) LIST=1; mode="" ;;
    --keep) KEEP=1; mode="" ;;
    -v|--verbose) VERBOSE=1; mode="" ;;
    -*) echo "reliability: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) case $mode in
         cases) CASE_FILES+=("$1") ;;
         special) SPECIALS+=("$1") ;;
         fuzzcase) [[ $1 =~ ^[0-9]{1,15}$ ]] ||
                     { echo "reliability: --fuzz-case needs case numbers" >&2; exit 2; }
                   FUZZ_CASES+=("$1") ;;
         *) echo "reliability: unexpected argument '$1' (see --help)" >&2; exit 2 ;;
       esac ;;
  esac
  shift
done
[[ $JOBS =~ ^[1-9][0-9]*$ ]] || { echo "reliability: --jobs needs a positive integer" >&2; exit 2; }

# What to run: everything by default; with --cases, --special, --fuzz or
# --fuzz-case, only those.
# (--fuzz 0 alone: the cases and special tests without the fuzzing stage)
if [ ${#FUZZ_CASES[@]} -gt 0 ] && [ -z "$FUZZ" ]; then FUZZ=0; fi
if [ $SELECT_CASES = 0 ] && [ $SELECT_SPECIALS = 0 ] && [ -z "$FUZZ" ]; then
  RUN_CASES=1; RUN_SPECIALS=1; FUZZ=10000
elif [ $SELECT_CASES = 0 ] && [ $SELECT_SPECIALS = 0 ] && [ "$FUZZ" = 0 ] &&
     [ ${#FUZZ_CASES[@]} = 0 ]; then
  RUN_CASES=1; RUN_SPECIALS=1
elif [ $SELECT_CASES = 0 ] && [ $SELECT_SPECIALS = 0 ]; then
  RUN_CASES=0; RUN_SPECIALS=0
else
  RUN_CASES=$SELECT_CASES; RUN_SPECIALS=$SELECT_SPECIALS
fi
[ -n "$FUZZ" ] || FUZZ=0
if [ $RUN_CASES = 1 ] && [ ${#CASE_FILES[@]} = 0 ]; then
  shopt -s nullglob
  CASE_FILES=("$CASEDIR"/*.sh)
  shopt -u nullglob
fi
if [ $RUN_SPECIALS = 1 ]; then
  if [ ${#SPECIALS[@]} = 0 ]; then
    shopt -s nullglob
    for f in "$SPECIALDIR"/*.sh; do
      if [ -x "$f" ]; then SPECIALS+=("$f")
      else echo "reliability: note: $f is not executable, not run"; fi
    done
    shopt -u nullglob
  else
    resolved=()
    for s in "${SPECIALS[@]}"; do
      if [ -f "$s" ]; then resolved+=("$(cd "$(dirname "$s")" && pwd)/$(basename "$s")")
      elif [ -f "$SPECIALDIR/$s" ]; then resolved+=("$SPECIALDIR/$s")
      elif [ -f "$SPECIALDIR/$s.sh" ]; then resolved+=("$SPECIALDIR/$s.sh")
      else echo "reliability: no special test '$s' in $SPECIALDIR" >&2; exit 2; fi
    done
    SPECIALS=("${resolved[@]}")
  fi
fi

WORK=$(mktemp -d "${TMPDIR:-/tmp}/dpend-reliability.XXXXXX")
cleanup() { if [ $KEEP = 1 ]; then echo "reliability: kept $WORK"; else rm -rf "$WORK"; fi; }
trap cleanup EXIT
trap 'exit 130' INT TERM

# The binary: --dpend, else $DPEND, else the debug build.
if [ -n "$DPEND_ARG" ]; then DPEND=$DPEND_ARG; fi
if [ -z "${DPEND:-}" ]; then
  if [ $LIST = 1 ]; then
    DPEND=/bin/false
  else
    (cd "$ROOT" && . scripts/flags.sh && fpm build --flag "$DEBUG_FLAGS") > "$WORK/build.log" 2>&1 ||
      { tail -n 40 "$WORK/build.log"; echo "reliability: debug build failed" >&2; exit 1; }
    DPEND=$(cd "$ROOT" && . scripts/flags.sh &&
            fpm run dpend --flag "$DEBUG_FLAGS" --runner echo 2>/dev/null | tail -n 1)
    DPEND=$ROOT/$DPEND
  fi
fi
case $DPEND in /*) ;; */*) DPEND=$(pwd)/$DPEND ;; *) DPEND=$(command -v "$DPEND" || echo "$DPEND") ;; esac
if [ $LIST = 0 ] && [ ! -x "$DPEND" ]; then
  echo "reliability: '$DPEND' is not an executable" >&2; exit 2
fi
# The binary of the fixtures (and of the case files' own fixtures): --fixture-dpend,
# else the tested one.
ROW_DPEND=$DPEND
if [ -n "$FIXTURE_DPEND" ]; then
  case $FIXTURE_DPEND in /*) ;; *) FIXTURE_DPEND=$(pwd)/$FIXTURE_DPEND ;; esac
  [ -x "$FIXTURE_DPEND" ] || { echo "reliability: '$FIXTURE_DPEND' is not an executable" >&2; exit 2; }
  DPEND=$FIXTURE_DPEND
fi
export DPEND ROOT

# h5_finite FILE DATASET: the dataset exists, holds at least one value, all finite.
h5_finite() {
  local dump
  dump=$(h5dump -d "$2" -y -w 0 "$1" 2>/dev/null) || return 1
  # the dataset's own DATA block only (the attributes' blocks follow it)
  dump=$(printf '%s\n' "$dump" | awk '/DATA \{/ { f = 1; next } f && /^ *\}/ { exit } f')
  # bash's own matching: `printf | grep -q` under pipefail fails at random when grep
  # exits on its first match while printf still writes (SIGPIPE, exit 141)
  [[ $dump =~ [0-9] ]] || return 1
  [[ ! ${dump,,} =~ nan|inf ]]
}
# h5_attr FILE PATH: the first value of the attribute PATH (/status, /sweep/complete),
# quotes removed ("" when absent or unreadable).
h5_attr() {
  h5dump -a "$2" "$1" 2>/dev/null | sed -n 's/^ *(0): *//p' | head -n 1 | sed 's/^"\(.*\)"$/\1/'
}
# check_h5 KIND FILE: a complete file of the command KIND with one dataset finite;
# prints why not (nothing when it is).
check_h5() {
  local kind=$1 f=$2 st
  head -c 8 "$f" 2>/dev/null | cmp -s - <(printf '\211HDF\r\n\032\n') ||
    { echo "not an HDF5 file"; return; }
  h5dump -A "$f" > /dev/null 2>&1 || { echo "HDF5 file unreadable (h5dump -A)"; return; }
  case $kind in
    simulate|lyapunov|indicators|divergence|poincare)
      st=$(h5_attr "$f" /status)
      [ "$st" = completed ] || { echo "status '$st', expected 'completed'"; return; } ;;
    sweep)
      [ "$(h5_attr "$f" /sweep/complete)" = 1 ] || { echo "/sweep complete is not 1"; return; } ;;
    study)
      h5dump -a /wall_time "$f" > /dev/null 2>&1 || { echo "no /wall_time (incomplete study)"; return; }
      [ -s "${f%.h5}.md" ] || { echo "no summary ${f%.h5}.md"; return; } ;;
    fit)
      st=$(h5_attr "$f" /status)
      [ "$st" = completed ] || { echo "status '$st', expected 'completed'"; return; }
      [[ $(h5_attr "$f" /fit/converged) =~ ^[01]$ ]] || { echo "no /fit converged attribute"; return; } ;;
  esac
  local ds
  case $kind in
    simulate) ds=/trajectory/t ;;
    lyapunov) ds=/lyapunov/t ;;
    indicators) ds=/indicators/t ;;
    divergence) ds=/divergence/t ;;
    poincare) ds=/poincare/energy ;;
    sweep) ds=/sweep/energy0 ;;
    study) ds=$(h5ls -r "$f" 2>/dev/null | awk '$1 ~ /^\/cases\/.*\/step\/h$/ { print $1; exit }') ;;
    fit) ds=/fit/estimate ;;
    sweep-compare) ds=/agreement/class_a ;;
  esac
  [ -n "$ds" ] || { echo "no dataset to check"; return; }
  h5_finite "$f" "$ds" || echo "dataset $ds missing, empty or not finite"
}
# row_output ARGS...: the file the command writes, relative to the cwd ("" when it
# writes none; "*.gif" for animate without --output: some new .gif).
row_output() {
  local cmd=${1:-} a prev="" out="" cfg="" help=0 agreement=0
  shift || true
  for a in "$@"; do
    if [ -n "$prev" ]; then
      case $prev in output) out=$a ;; config) cfg=$a ;; esac
      prev=""; continue
    fi
    case $a in
      -h|--help) help=1 ;;
      --output|-o) prev=output ;;
      --output=*) out=${a#--output=} ;;
      --config) prev=config ;;
      --config=*) cfg=${a#--config=} ;;
      --agreement) agreement=1 ;;
    esac
  done
  [ $help = 0 ] || return 0
  case $cmd in
    simulate|lyapunov|indicators|divergence|poincare|sweep|fit|study|animate) ;;
    sweep-compare) [ $agreement = 1 ] && [ -n "$out" ] || return 0 ;;   # a file only with --output
    *) return 0 ;;
  esac
  if [ -z "$out" ] && [ -n "$cfg" ] && [ -f "$cfg" ]; then
    out=$(sed -n "/^[[:space:]]*&[oO][uU][tT][pP][uU][tT]/,/\//{
                  s/.*[fF][iI][lL][eE][[:space:]]*=[[:space:]]*['\"]\([^'\"]*\)['\"].*/\1/p
                }" "$cfg" 2>/dev/null | head -n 1)
  fi
  if [ -z "$out" ]; then
    case $cmd in
      study) out=out/study/study.h5 ;;
      animate) out='*.gif' ;;
      *) out=$cmd.h5 ;;
    esac
  fi
  printf '%s' "$out"
}
# check_result KIND RC OUT MARKER STDERR: the result of a succeed (KIND succeed) or
# fail row whose command writes OUT; prints the reasons it is wrong, one a line.
check_result() {
  local kind=$1 cmd=$2 out=$3 marker=$4 err=$5 f why st
  case $out in /*|*/../*|../*) return ;; esac   # outside the scratch directory
  if [ "$out" = '*.gif' ]; then
    f=$(find . -name '*.gif' -type f -newer "$marker" 2>/dev/null | head -n 1)
    if [ "$kind" = succeed ]; then
      [ -n "$f" ] || { echo "no new .gif written"; return; }
      out=$f
    else
      return
    fi
  fi
  if [ "$kind" = succeed ]; then
    [ -e "$out" ] || { echo "output $out not written"; return; }
    [ -f "$out" ] || return   # a device or a fifo given as the output
    # a complete sweep resumed: nothing to compute, the file stays as it was
    if [ ! "$out" -nt "$marker" ] && ! { [ "$cmd" = sweep ] &&
         grep -qF "is complete (nothing to compute)" "$err" "${err%/stderr}/stdout"; }; then
      echo "output $out not written by this run (older)"; return
    fi
    if [ "$cmd" = animate ]; then
      head -c 6 "$out" | grep -qE '^GIF8[79]a$' || { echo "output $out is not a GIF"; return; }
      [ "$(tail -c 1 "$out" | od -An -tx1 | tr -d ' ')" = 3b ] ||
        { echo "output $out: GIF without its trailer"; return; }
      return
    fi
    why=$(check_h5 "$cmd" "$out")
    [ -z "$why" ] || { echo "output $out: $why"; return; }
    if [ "$cmd" = study ]; then
      h5dump "$out" > /dev/null 2>&1 || echo "output $out: not every byte readable (h5dump)"
    fi
  else
    case $cmd in simulate|lyapunov|indicators|divergence|poincare|fit) ;; *) return ;; esac
    [ -f "$out" ] || { echo "no partial file $out"; return; }
    h5dump -A "$out" > /dev/null 2>&1 || { echo "partial file $out unreadable"; return; }
    st=$(h5_attr "$out" /status)
    [ -n "$st" ] && [ "$st" != completed ] ||
      { echo "partial file $out: status '$st', expected why the run stopped"; return; }
    grep -qF -- "$st" "$err" || echo "partial file $out: status '$st' not the message on stderr"
  fi
}

# Fixtures, built once.
FIXTURES=$WORK/fixtures
mkdir -p "$FIXTURES/dir" "$FIXTURES/data"
export FIXTURES
if [ $LIST = 0 ] && [ $RUN_CASES = 1 ]; then
  (
    set -e
    cd "$FIXTURES"
    cp "$ROOT"/data/*.nml .
    cp "$ROOT"/data/*.nml data/
    printf '%s\n' '0.1 0.2 0.0 0.0' '-1.5 -1.5 0.0 0.0' '1.0 1.0 0.5 0.5' > list.txt
    "$DPEND" simulate --t-end 0.1 --output existing.h5
    "$DPEND" sweep --n 8 --t-end 1 --output sweep.h5 --quiet
    "$DPEND" sweep --ic-file list.txt --t-end 1 --output sweep_list.h5 --quiet
  ) > "$WORK/fixtures.log" 2>&1 ||
    { cat "$WORK/fixtures.log"; echo "reliability: building the fixtures failed" >&2; exit 1; }
  # verified before use: complete files with finite values, the list of 3 lines
  fx_bad=""
  for fx in existing.h5:simulate sweep.h5:sweep sweep_list.h5:sweep; do
    why=$(check_h5 "${fx#*:}" "$FIXTURES/${fx%%:*}")
    [ -z "$why" ] || fx_bad+=" ${fx%%:*}: $why;"
  done
  [ "$(h5_attr "$FIXTURES/sweep.h5" /sweep/initial)" = grid ] || fx_bad+=" sweep.h5: not a grid;"
  [ "$(h5_attr "$FIXTURES/sweep_list.h5" /sweep/initial)" = list ] ||
    fx_bad+=" sweep_list.h5: not a list;"
  [ "$(grep -c '' "$FIXTURES/list.txt")" = 3 ] || fx_bad+=" list.txt: not 3 lines;"
  if [ -n "$fx_bad" ]; then
    cat "$WORK/fixtures.log"
    echo "reliability: the fixtures are wrong:$fx_bad" >&2; exit 1
  fi
fi

# Rows: registered by the case files, stored one per directory entry.
ROWS=$WORK/rows
mkdir -p "$ROWS"
NROWS=0
SETUP_FAILS=()
declare -A ROW_FILE=()
CURRENT_FILE=""

register() {  # register KIND ID TEXT ARGS...  (ARGS after the --)
  local kind=$1 id=$2 text=$3; shift 3
  if [ -z "$id" ]; then
    SETUP_FAILS+=("FAIL (row without ID) in $CURRENT_FILE: $kind $*"); return
  fi
  if [ -n "${ROW_FILE[$id]:-}" ]; then
    SETUP_FAILS+=("FAIL $id: duplicate ID in $CURRENT_FILE (first in ${ROW_FILE[$id]})")
    return
  fi
  ROW_FILE[$id]=$CURRENT_FILE
  NROWS=$((NROWS + 1))
  local r=$ROWS/$(printf '%05d' $NROWS)
  mkdir "$r"
  printf '%s\n' "$kind" > "$r/kind"
  printf '%s\n' "$id" > "$r/id"
  printf '%s' "$text" > "$r/text"
  printf '%s\n' "$CURRENT_FILE" > "$r/file"
  if [ $# -gt 0 ]; then printf '%s\0' "$@" > "$r/args"; else : > "$r/args"; fi
}
refuse() {
  if [ $# -lt 3 ] || [ "$3" != "--" ]; then
    SETUP_FAILS+=("FAIL ${1:-?}: malformed row in $CURRENT_FILE (refuse ID FIELD -- ARGS)")
    return
  fi
  local id=$1 field=$2; shift 3; register refuse "$id" "$field" "$@"
}
fail() {
  if [ $# -lt 3 ] || [ "$3" != "--" ]; then
    SETUP_FAILS+=("FAIL ${1:-?}: malformed row in $CURRENT_FILE (fail ID TEXT -- ARGS)")
    return
  fi
  local id=$1 text=$2; shift 3; register fail "$id" "$text" "$@"
}
succeed() {
  if [ $# -lt 2 ] || [ "$2" != "--" ]; then
    SETUP_FAILS+=("FAIL ${1:-?}: malformed row in $CURRENT_FILE (succeed ID -- ARGS)")
    return
  fi
  local id=$1; shift 2; register succeed "$id" "" "$@"
}

if [ $RUN_CASES = 1 ]; then
  for f in "${CASE_FILES[@]}"; do
    [ -f "$f" ] || { echo "reliability: no case file '$f'" >&2; exit 2; }
    case $f in /*) ;; *) f=$(pwd)/$f ;; esac
    CURRENT_FILE=${f#"$ROOT"/}
    # shellcheck disable=SC1090
    pushd "$FIXTURES" > /dev/null || exit 1
    if [ $LIST = 1 ]; then
      . "$f" 2> /dev/null  # the fixtures are not made for --list
    else
      . "$f" || SETUP_FAILS+=("FAIL $CURRENT_FILE: sourcing it ended with status $?")
    fi
    popd > /dev/null || exit 1
  done
fi

DPEND=$ROW_DPEND   # the rows run the tested binary (--fixture-dpend built the fixtures)
export DPEND

if [ $LIST = 1 ]; then
  for r in "$ROWS"/*; do
    [ -d "$r" ] || continue
    printf '%-28s %-8s %s\n' "$(cat "$r/id")" "$(cat "$r/kind")" "$(cat "$r/file")"
  done
  for s in "${SPECIALS[@]}"; do printf '%-28s %-8s %s\n' "$(basename "$s" .sh)" special "${s#"$ROOT"/}"; done
  for m in "${SETUP_FAILS[@]}"; do echo "$m"; done
  echo "reliability: $NROWS rows, ${#SPECIALS[@]} special tests"
  [ ${#SETUP_FAILS[@]} = 0 ]; exit
fi

# Snapshot of a directory: every name (hidden ones too) with its type and link
# target, and the sha256 of every regular file.
snapshot() {
  ( cd "$1" && find . -mindepth 1 -printf '%y %p -> %l\n' | LC_ALL=C sort &&
    find . -type f -print0 | LC_ALL=C sort -z | xargs -0 -r sha256sum )
}

TRAP_RE='Floating point exception|Fortran runtime error|Backtrace|Error termination|HDF5-DIAG'

# run_row DIR: runs one row, writes DIR/result ("pass" or "FAIL ID: reason; command").
run_row() {
  local r=$1 kind id text file
  kind=$(cat "$r/kind"); id=$(cat "$r/id"); text=$(cat "$r/text"); file=$(cat "$r/file")
  local -a args=()
  mapfile -d '' -t args < "$r/args"
  local cmd="dpend"
  local a
  for a in "${args[@]}"; do cmd+=" $(printf '%q' "$a")"; done
  local s=$r/scratch
  mkdir "$s" && cp -a "$FIXTURES/." "$s/"
  [ "$kind" = refuse ] && snapshot "$s" > "$r/before"
  local out=""
  if [ "$kind" != refuse ]; then
    out=$(cd "$s" && row_output "${args[@]}")
    # files written by the run are newer (50 ms back: file times lag the clock)
    touch -d "$(date -d '-0.05 seconds' '+%Y-%m-%d %H:%M:%S.%N')" "$r/marker"
  fi
  local rc=0
  ( cd "$s" && exec timeout -k 5 30 "$DPEND" "${args[@]}" ) > "$r/stdout" 2> "$r/stderr" < /dev/null ||
    rc=$?
  local reasons=() first nlines
  first=$(grep -m1 -v "^[[:space:]]*$" "$r/stderr" | cut -c1-160)
  nlines=$(grep -c '' "$r/stderr")
  if [ $rc = 124 ] || [ $rc = 137 ]; then reasons+=("hang: killed after 30 s"); fi
  case $rc in 134|136|139) reasons+=("trap: exit $rc") ;; esac
  if grep -qE "$TRAP_RE" "$r/stderr"; then
    reasons+=("trap: $(grep -m1 -E "$TRAP_RE" "$r/stderr" | cut -c1-120)")
  fi
  case $kind in
    refuse)
      [ $rc = 2 ] || reasons+=("exit $rc, expected 2")
      [ "$nlines" = 1 ] || reasons+=("$nlines stderr lines, expected 1")
      # FIELD matches case-insensitively, with - and _ alike (--save-every, save_every)
      local low_err low_text
      low_err=$(tr 'A-Z_' 'a-z-' < "$r/stderr"); low_text=$(printf '%s' "$text" | tr 'A-Z_' 'a-z-')
      [[ $low_err == *"$low_text"* ]] || reasons+=("stderr lacks '$text'")
      snapshot "$s" > "$r/after"
      if ! cmp -s "$r/before" "$r/after"; then
        local changed
        changed=$(diff "$r/before" "$r/after" | awk '
          /^[<>] [a-z] \.\// { n = $3; sub(/^\.\//, "", n)
                                names[n] = 1; kind[n] = kind[n] $1 }
          /^[<>] [0-9a-f]+  \.\// { n = $3; sub(/^\.\//, "", n); sums[n] = 1 }
          END { for (n in names) { k = (kind[n] == ">" ? "created " : \
                                        kind[n] == "<" ? "removed " : "retyped ")
                                   printf "%s%s, ", k, n; delete sums[n] }
                for (n in sums) printf "changed %s, ", n }' | head -c 300)
        reasons+=("files ${changed%, }")
      fi ;;
    fail)
      [ $rc = 1 ] || reasons+=("exit $rc, expected 1")
      grep -qiF -- "$text" "$r/stderr" || reasons+=("stderr lacks '$text'") ;;
    succeed)
      [ $rc = 0 ] || reasons+=("exit $rc, expected 0") ;;
  esac
  # a succeed row that writes no file prints its result (a report, a table, help)
  if [ "$kind" = succeed ] && [ -z "$out" ] && [ ${#reasons[@]} = 0 ] && [ ! -s "$r/stdout" ]; then
    reasons+=("nothing on stdout (a command that writes no file prints its result)")
  fi
  if [ -n "$out" ] && [ ${#reasons[@]} = 0 ]; then
    local line
    while IFS= read -r line; do
      [ -z "$line" ] || reasons+=("$line")
    done < <(cd "$s" && check_result "$kind" "${args[0]}" "$out" "$r/marker" "$r/stderr")
    echo "$out" > "$r/output"
  fi
  if [ ${#reasons[@]} = 0 ]; then
    echo "pass" > "$r/result"
  else
    local why
    why=$(IFS=';'; echo "${reasons[*]}" | sed 's/;/; /g')
    if [ -n "$first" ]; then why+="; stderr: $first"; fi
    printf 'FAIL %s (%s): %s; command: %s\n' "$id" "$file" "$why" "$cmd" > "$r/result"
  fi
  [ $KEEP = 1 ] || rm -rf "$s"
}

START=$SECONDS
passed=0; failed=0; skipped=0
for m in "${SETUP_FAILS[@]}"; do echo "$m"; failed=$((failed + 1)); done

if [ $NROWS -gt 0 ]; then
  running=0
  for r in "$ROWS"/*; do
    [ -d "$r" ] || continue
    run_row "$r" 2> "$r/runner.err" &
    running=$((running + 1))
    if [ $running -ge "$JOBS" ]; then wait -n; running=$((running - 1)); fi
  done
  wait
  for r in "$ROWS"/*; do
    [ -d "$r" ] || continue
    res=$(cat "$r/result" 2>/dev/null || echo "FAIL $(cat "$r/id"): the runner lost this row")
    if [ "$res" = pass ]; then
      passed=$((passed + 1))
      if [ $VERBOSE = 1 ]; then
        if [ -f "$r/output" ]; then echo "pass $(cat "$r/id") (checked $(cat "$r/output"))"
        else echo "pass $(cat "$r/id")"; fi
      fi
    else
      failed=$((failed + 1)); echo "$res"
    fi
  done
fi

# Special tests, one after the other.
for s in "${SPECIALS[@]}"; do
  name=$(basename "$s" .sh)
  sd=$WORK/special-$name
  mkdir -p "$sd"
  t0=$SECONDS
  rc=0
  ( cd "$sd" && DPEND=$DPEND ROOT=$ROOT SCRATCH=$sd exec timeout -k 10 600 "$s" ) \
    > "$WORK/special-$name.log" 2>&1 < /dev/null || rc=$?
  dt=$((SECONDS - t0))
  case $rc in
    0) passed=$((passed + 1)); [ $VERBOSE = 0 ] || echo "pass special $name (${dt} s)" ;;
    77) note=$(tail -n 3 "$WORK/special-$name.log" | tr '\n' ' ')
        if [ "${DPEND_TEST_NO_SKIP:-}" = 1 ] && [[ " ${DPEND_TEST_MAY_SKIP:-} " != *" $name "* ]]
        then
          failed=$((failed + 1))
          echo "FAIL special $name: skipped, and DPEND_TEST_NO_SKIP=1 expects it to run: $note"
        else
          skipped=$((skipped + 1)); echo "skip special $name: $note"
        fi ;;
    *) failed=$((failed + 1))
       echo "FAIL special $name: exit $rc after ${dt} s; command: $s"
       tail -n 30 "$WORK/special-$name.log" | sed 's/^/    /' ;;
  esac
done

# The fuzzing stage: N inputs (or the cases asked for), one test.
if [ $LIST = 0 ] && { [ "$FUZZ" -gt 0 ] || [ ${#FUZZ_CASES[@]} -gt 0 ]; }; then
  GEN=$(dirname "$DPEND")/../example/dpend-fuzz-h5
  if [ ! -x "$GEN" ]; then  # a binary from elsewhere: the mutator of the debug build
    (cd "$ROOT" && . scripts/flags.sh && fpm build --flag "$DEBUG_FLAGS") > "$WORK/build-fuzz.log" 2>&1
    GEN=$ROOT/$(cd "$ROOT" && . scripts/flags.sh &&
                fpm run --example dpend-fuzz-h5 --flag "$DEBUG_FLAGS" --runner echo 2>/dev/null |
                tail -n 1)
  fi
  fuzz_args=(--dpend "$DPEND" --gen "$GEN" --count "$FUZZ" --budget "$FUZZ_BUDGET" --jobs "$JOBS")
  [ -z "$FUZZ_SEED" ] || fuzz_args+=(--seed "$FUZZ_SEED")
  for c in ${FUZZ_CASES[@]+"${FUZZ_CASES[@]}"}; do fuzz_args+=(--case "$c"); done
  rc=0
  "$ROOT/test/reliability/fuzz/fuzz.sh" "${fuzz_args[@]}" < /dev/null || rc=$?
  if [ $rc = 0 ]; then passed=$((passed + 1))
  else failed=$((failed + 1)); echo "FAIL fuzz: the fuzzing stage failed (exit $rc; lines above)"; fi
fi

# A safety net: a faulty --force must not have replaced the machine's /dev/null.
if [ ! -c /dev/null ]; then
  echo "FAIL: /dev/null is no longer a device (restore: mknod -m 666 /dev/null c 1 3)"
  failed=$((failed + 1))
fi
[ $VERBOSE = 0 ] || echo "reliability: $((SECONDS - START)) s"
echo "reliability: $passed passed, $failed failed, $skipped skipped"
[ $failed = 0 ]
