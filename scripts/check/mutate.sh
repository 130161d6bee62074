#!/usr/bin/env bash
# The mutation stage: apply source mutants (test/mutants.txt) one at a
# time in a scratch copy of the tree, build the debug profile, run the tests, and
# report which mutants the test suite kills. Run scripts/check/mutate.sh --help for usage.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

usage() {
  cat <<'EOF'
usage: scripts/check/mutate.sh [--all | --sample K --seed S | --only ID[,ID...]] [options]

Applies each selected mutant of the list (default test/mutants.txt; its header
describes the format) alone to a scratch copy of the working tree, rebuilds the
debug profile there (incremental: one copy, reverted after each mutant), and runs
the debug test suite: first the tests the mutant names as its likely killers,
then, only if all of them pass, the whole suite. Each mutant is reported as
  killed (by SUITE/TEST)   a test failed (or crashed, or timed out)
  SURVIVED                 the whole suite passed: a missing test, to be written
  did not apply            its text is not in its file, nor exactly once in one
                           file under src/ (the file may have moved: the text is
                           searched there), or it is there more than once
  did not build            the mutated tree does not compile
The last two are errors of the list, never kills. Closes with
`mutants: N killed, M survived, A did not apply, B did not build (kill rate X %)`
and exits 1 if any mutant survived, did not apply or did not build (2 for a usage
or list error).

selection (exactly one; default --all):
  --all             every mutant of the list
  --sample K        K mutants drawn by --seed (CI: K >= 6, seeded by the commit)
  --seed S          the draw's seed (any text; default: git rev-parse HEAD)
  --only ID[,ID]    these mutants
options:
  --list FILE       the mutant list (default test/mutants.txt)
  --scratch DIR     the scratch copy (default $MUTATE_SCRATCH, else
                    ${TMPDIR:-/tmp}/dpend-mutate-<uid>); kept between runs, so
                    that later runs build incrementally; its src/ app/ test/ are
                    replaced by the working tree's at every start
  --build-only      apply and build each mutant, run no test (checks the list)
  --no-baseline     skip the baseline (by default the selected mutants' killer
                    tests must pass on the unmutated copy first)
  --timeout SEC     limit of one killer test run (default 120; the whole suite
                    gets 12x); a run past it counts as killed (timeout)
  --ids             print the ids of the list (with --sample/--seed: the draw)
  -h, --help        this text
EOF
}

LIST=$ROOT/test/mutants.txt
MODE=all; SAMPLE=0; SEED=; ONLY=; BUILD_ONLY=0; BASELINE=1; TIMEOUT=120; PRINT_IDS=0
SCRATCH=${MUTATE_SCRATCH:-${TMPDIR:-/tmp}/dpend-mutate-$(id -u)}
n_mode=0
while [ $# -gt 0 ]; do
  case $1 in
    --all) MODE=all; n_mode=$((n_mode + 1)); shift ;;
    --sample) MODE=sample; SAMPLE=${2:-}; n_mode=$((n_mode + 1)); shift 2 || break ;;
    --seed) SEED=${2:-}; shift 2 || break ;;
    --only) MODE=only; ONLY=${2:-}; n_mode=$((n_mode + 1)); shift 2 || break ;;
    --list) LIST=${2:-}; shift 2 || break ;;
    --scratch) SCRATCH=${2:-}; shift 2 || break ;;
    --build-only) BUILD_ONLY=1; shift ;;
    --no-baseline) BASELINE=0; shift ;;
    --timeout) TIMEOUT=${2:-}; shift 2 || break ;;
    --ids) PRINT_IDS=1; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "mutate.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ "$n_mode" -le 1 ] || { echo "mutate.sh: give one of --all, --sample, --only" >&2; exit 2; }
if [ "$MODE" = sample ] && ! [[ $SAMPLE =~ ^[1-9][0-9]{0,5}$ ]]; then
  echo "mutate.sh: invalid --sample: '$SAMPLE' (accepted: an integer >= 1)" >&2; exit 2
fi
if ! [[ $TIMEOUT =~ ^[1-9][0-9]{0,5}$ ]]; then
  echo "mutate.sh: invalid --timeout: '$TIMEOUT' (accepted: seconds >= 1)" >&2; exit 2
fi
[ -f "$LIST" ] || { echo "mutate.sh: no mutant list '$LIST'" >&2; exit 2; }
case $SCRATCH in
  "" | / | "$ROOT" | "$ROOT"/*) echo "mutate.sh: invalid --scratch: '$SCRATCH'" \
    "(accepted: a directory outside the tree)" >&2; exit 2 ;;
esac

# ---------------------------------------------------------------- the list
# Blocks of `key: value` lines separated by blank lines; `#` starts a comment line.
ids=(); files=(); finds=(); repls=(); killers=(); bugs=()
list_error() { echo "mutate.sh: $LIST:$1: $2" >&2; exit 2; }
flush_block() {
  [ -n "${b_id}${b_file}${b_find}${b_repl}${b_kill}${b_bug}" ] || return 0
  local f
  for f in id file find replace killers bug; do
    case $f in
      id) [ -n "$b_id" ] ;; file) [ -n "$b_file" ] ;; find) [ -n "$b_find" ] ;;
      replace) [ -n "$b_repl" ] ;; killers) [ -n "$b_kill" ] ;; bug) [ -n "$b_bug" ] ;;
    esac || list_error "$b_line" "mutant '${b_id:-?}' has no '$f:'"
  done
  [[ $b_id =~ ^[a-z0-9][a-z0-9_-]*$ ]] || list_error "$b_line" "bad id '$b_id'"
  [ "$b_find" != "$b_repl" ] || list_error "$b_line" "mutant '$b_id': replace equals find"
  local i
  for i in "${ids[@]}"; do
    [ "$i" != "$b_id" ] || list_error "$b_line" "mutant id '$b_id' repeated"
  done
  ids+=("$b_id"); files+=("$b_file"); finds+=("$b_find"); repls+=("$b_repl")
  killers+=("$b_kill"); bugs+=("$b_bug")
}
b_id=; b_file=; b_find=; b_repl=; b_kill=; b_bug=; b_line=0; lineno=0
while IFS= read -r line || [ -n "$line" ]; do
  lineno=$((lineno + 1))
  [[ $line =~ ^[[:space:]]*# ]] && continue
  if [[ $line =~ ^[[:space:]]*$ ]]; then
    flush_block; b_id=; b_file=; b_find=; b_repl=; b_kill=; b_bug=; continue
  fi
  [[ $line =~ ^([a-z]+):[[:space:]]?(.*)$ ]] || list_error "$lineno" "not 'key: value'"
  key=${BASH_REMATCH[1]}; val=${BASH_REMATCH[2]}
  val=${val#"${val%%[![:space:]]*}"}   # leading blanks are layout, not text
  [ -n "$b_id$b_file$b_find$b_repl$b_kill$b_bug" ] || b_line=$lineno
  case $key in
    id) b_id=$val ;; file) b_file=$val ;; find) b_find=$val ;; replace) b_repl=$val ;;
    killers) b_kill=$val ;; bug) b_bug=$val ;;
    *) list_error "$lineno" "unknown key '$key' (accepted: id file find replace killers bug)" ;;
  esac
done < "$LIST"
flush_block
[ ${#ids[@]} -gt 0 ] || { echo "mutate.sh: $LIST holds no mutant" >&2; exit 2; }

# ---------------------------------------------------------------- selection
sel=()
case $MODE in
  all) sel=("${!ids[@]}") ;;
  only)
    IFS=, read -r -a want <<< "$ONLY"
    for w in "${want[@]}"; do
      found=
      for i in "${!ids[@]}"; do [ "${ids[$i]}" = "$w" ] && found=$i; done
      [ -n "$found" ] || { echo "mutate.sh: invalid --only: '$w' (not in $LIST)" >&2; exit 2; }
      sel+=("$found")
    done ;;
  sample)
    [ -n "$SEED" ] || SEED=$(git -C "$ROOT" rev-parse HEAD 2>/dev/null || echo 0)
    # a rotating draw: the K ids of least cksum("seed:id")
    mapfile -t sel < <(for i in "${!ids[@]}"; do
      printf '%s %s\n' "$(printf '%s:%s' "$SEED" "${ids[$i]}" | cksum | cut -d' ' -f1)" "$i"
    done | sort -n | head -n "$SAMPLE" | cut -d' ' -f2 | sort -n) ;;
esac
if [ "$PRINT_IDS" = 1 ]; then
  for i in "${sel[@]}"; do echo "${ids[$i]}"; done
  exit 0
fi
echo "mutate: ${#sel[@]} of ${#ids[@]} mutants (${MODE}${SEED:+, seed $SEED}); scratch $SCRATCH"

# ---------------------------------------------------------------- the scratch copy
. "$ROOT/scripts/flags.sh"
mkdir -p "$SCRATCH" || exit 2
inc_sum() { find "$SCRATCH/src" -name '*.inc' -type f 2>/dev/null | sort | xargs -r cat | cksum; }
old_inc=$(inc_sum)
rm -rf "$SCRATCH/src" "$SCRATCH/app" "$SCRATCH/test"
# tracked and untracked-but-not-ignored files, mtimes kept (unchanged files are not
# rebuilt); build/ of earlier runs stays
(cd "$ROOT" && git ls-files -z -c -o --exclude-standard | grep -z -v '^build/' |
  tar --null -T - -cf -) | (cd "$SCRATCH" && tar -xpf -) ||
  { echo "mutate.sh: cannot copy the tree to $SCRATCH" >&2; exit 2; }
cd "$SCRATCH" || exit 2
# fpm tracks a source by its digest, not by the files it includes: a changed include
# file would leave a stale object, so the build starts over
[ "$old_inc" = "$(inc_sum)" ] || rm -rf "$SCRATCH/build"
LOG=$SCRATCH/mutate-logs
rm -rf "$LOG"; mkdir -p "$LOG"

build() {   # build the debug profile; binaries removed first (fpm may keep stale ones)
  rm -f build/gfortran_*/test/dpend-tests build/gfortran_*/app/dpend
  fpm build --tests --flag "$DEBUG_FLAGS" > "$1" 2>&1
}
test_bin() { ls -t build/gfortran_*/test/dpend-tests 2>/dev/null | head -n 1; }

# run_tests LOGFILE LIMIT [FILTER]: 0 when every test passed; else sets $why
run_tests() {
  local log=$1 limit=$2 filter=${3:-} rc
  { timeout "$limit" "$BIN" $filter > "$log" 2>&1; } 2> /dev/null   # (no job notice)
  rc=$?
  [ $rc -eq 0 ] && grep -q ' passed, 0 failed' "$log" && return 0
  why=$(grep -m 1 '^  FAIL ' "$log" | sed -e 's/^  FAIL \([^:]*\):.*/\1/')
  if [ $rc -eq 124 ]; then why="timeout after ${limit} s in ${filter:-the whole suite}"
  elif [ -z "$why" ]; then why="${filter:-the whole suite} (crashed, exit $rc)"; fi
  if [ -n "$filter" ] && ! grep -q '^  ok \|^  FAIL ' "$log"; then
    why="$filter: no such test ($(tail -n 1 "$log"))"; return 2
  fi
  return 1
}

t0=$SECONDS
if ! build "$LOG/baseline-build.log"; then
  tail -n 30 "$LOG/baseline-build.log"
  echo "mutate.sh: the unmutated copy does not build" >&2; exit 2
fi
BIN=$(test_bin)
# the unmutated binaries, kept to tell a mutant's failures from the tree's own
# (tests find the app as ../app/dpend from their own path)
rm -rf "$SCRATCH/baseline-bin"; mkdir -p "$SCRATCH/baseline-bin/test" "$SCRATCH/baseline-bin/app"
cp "$BIN" "$SCRATCH/baseline-bin/test/dpend-tests" &&
  cp "$(dirname "$BIN")/../app/dpend" "$SCRATCH/baseline-bin/app/dpend" ||
  { echo "mutate.sh: cannot keep the baseline binaries" >&2; exit 2; }
BASE_BIN=$SCRATCH/baseline-bin/test/dpend-tests
echo "mutate: baseline build $((SECONDS - t0)) s"
if [ "$BUILD_ONLY" = 0 ] && [ "$BASELINE" = 1 ]; then
  declare -A seen=()
  for i in "${sel[@]}"; do
    for k in ${killers[$i]}; do
      [ -n "${seen[$k]:-}" ] && continue
      seen[$k]=1
      t1=$SECONDS
      if ! run_tests "$LOG/baseline-$(echo "$k" | tr / _).log" $((12 * TIMEOUT)) "$k"; then
        echo "mutate.sh: baseline: '$k' fails on the unmutated copy: $why" >&2; exit 2
      fi
      echo "mutate: baseline $k passes ($((SECONDS - t1)) s)"
    done
  done
fi

# ---------------------------------------------------------------- the mutants
n_kill=0; n_surv=0; n_noapply=0; n_nobuild=0; bad_ids=()
for i in "${sel[@]}"; do
  id=${ids[$i]}; file=${files[$i]}; find=${finds[$i]}; repl=${repls[$i]}
  t1=$SECONDS
  # locate: the named file, else the one file under src/ that holds the text
  count_in() {
    local c
    c=$(cat "$1"; printf x); c=${c%x}
    local rest=${c//"$find"/}
    echo $(((${#c} - ${#rest}) / ${#find}))
  }
  target=; note=
  if [ -f "$file" ] && [ "$(count_in "$file")" -ge 1 ]; then
    n=$(count_in "$file")
    [ "$n" -eq 1 ] && target=$file || note="$n matches in $file"
  else
    mapfile -t hits < <(grep -rlF --include='*.f90' --include='*.inc' --include='*.c' \
      -e "$find" src 2>/dev/null)
    if [ ${#hits[@]} -eq 1 ] && [ "$(count_in "${hits[0]}")" -eq 1 ]; then
      target=${hits[0]}; [ "$file" = "*" ] || note="(moved: found in $target)"
    elif [ ${#hits[@]} -eq 0 ]; then note="text not found under src/"
    else note="text in ${#hits[@]} files or more than once"; fi
  fi
  if [ -z "$target" ]; then
    printf '%-28s did not apply: %s\n' "$id" "$note"
    n_noapply=$((n_noapply + 1)); bad_ids+=("$id"); continue
  fi
  orig=$(cat "$target"; printf x); orig=${orig%x}
  printf '%s' "${orig/"$find"/"$repl"}" > "$target"
  # fpm does not see a change of an include file: mark the files that include it
  incs=(); inc_orig=()
  if [[ $target == *.inc ]]; then
    mapfile -t incs < <(grep -rlE "^[[:space:]]*include[[:space:]]+['\"]([^'\"]*/)?${target##*/}['\"]" \
      src --include='*.f90')
    for f in "${incs[@]}"; do
      c=$(cat "$f"; printf x); inc_orig+=("${c%x}")
      printf '%s\n! mutant %s\n' "${c%x}" "$id" > "$f"
    done
  fi
  revert() {   # new mtimes and digests: the next build recompiles them
    local j
    printf '%s' "$orig" > "$target"
    for j in "${!incs[@]}"; do printf '%s' "${inc_orig[$j]}" > "${incs[$j]}"; done
  }
  if ! build "$LOG/$id-build.log"; then
    revert
    printf '%-28s did not build (%s; log %s)\n' "$id" "$target" "$LOG/$id-build.log"
    n_nobuild=$((n_nobuild + 1)); bad_ids+=("$id"); continue
  fi
  BIN=$(test_bin)
  if [ "$BUILD_ONLY" = 1 ]; then
    revert
    printf '%-28s applies and builds (%s) %s\n' "$id" "$target" "$note"
    continue
  fi
  verdict=; why=
  for k in ${killers[$i]}; do
    run_tests "$LOG/$id-$(echo "$k" | tr / _).log" "$TIMEOUT" "$k"
    case $? in
      0) ;;
      1) verdict="killed by $why"; break ;;
      2) verdict="list error: $why"; break ;;
    esac
  done
  if [ -z "$verdict" ]; then
    if run_tests "$LOG/$id-all.log" $((12 * TIMEOUT)); then verdict=SURVIVED
    else
      # failures that the unmutated tree has too are not kills
      verdict=SURVIVED; own=
      while IFS= read -r name; do
        if timeout "$TIMEOUT" "$BASE_BIN" "$name" > /dev/null 2>&1; then
          verdict="killed by $name (not by its killers: ${killers[$i]})"; break
        fi
        own="$own $name"
      done < <(grep '^  FAIL ' "$LOG/$id-all.log" | sed -e 's/^  FAIL \([^:]*\):.*/\1/')
      if [ "$verdict" = SURVIVED ] && ! grep -q '^  FAIL ' "$LOG/$id-all.log"; then
        verdict="killed by $why (not by its killers: ${killers[$i]})"
      fi
      [ -n "$own" ] && note="$note (failing without the mutant too:$own)"
    fi
  fi
  revert
  case $verdict in
    killed*) n_kill=$((n_kill + 1)) ;;
    SURVIVED) n_surv=$((n_surv + 1)); bad_ids+=("$id") ;;
    *) n_noapply=$((n_noapply + 1)); bad_ids+=("$id") ;;
  esac
  [ ${#incs[@]} -gt 0 ] && note="$note (included by ${incs[*]})"
  printf '%-28s %s (%s, %d s) %s\n' "$id" "$verdict" "$target" $((SECONDS - t1)) "$note"
  [ "$verdict" = SURVIVED ] && printf '%-28s   models: %s\n' "" "${bugs[$i]}"
done
# leave the copy built unmutated, for the next run
build "$LOG/final-build.log" || echo "mutate.sh: warning: the reverted copy does not build" >&2

if [ "$BUILD_ONLY" = 1 ]; then
  echo "mutants: $((${#sel[@]} - n_noapply - n_nobuild)) apply and build," \
    "$n_noapply did not apply, $n_nobuild did not build ($((SECONDS - t0)) s)"
else
  total=$((n_kill + n_surv))
  rate=$([ $total -gt 0 ] && echo $((100 * n_kill / total)) || echo 0)
  echo "mutants: $n_kill killed, $n_surv survived, $n_noapply did not apply," \
    "$n_nobuild did not build (kill rate $rate %; $((SECONDS - t0)) s)"
fi
[ ${#bad_ids[@]} -eq 0 ] || { echo "mutate: failing: ${bad_ids[*]}"; exit 1; }
exit 0
