#!/usr/bin/env bash
# Did a change leave the results (and the speed) as they were? Builds a base revision
# (in a temporary git worktree) and the current working tree in the release profile
# with the same flags, runs the same commands with both, compares the HDF5 files
# dataset by dataset and attribute by attribute, and optionally runs both benchmarks.
# Run scripts/compare_builds.sh --help for the usage; docs/compare-builds.md explains it.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/compare_builds.sh [options] [WORKDIR]

Builds REV (a detached git worktree WORKDIR/base, removed at the end unless
--keep) and the current working tree (uncommitted changes included; the
user's tree only gets its usual build/ directory), both with
`fpm build --profile release --flag "$RELEASE_FLAGS"` (the current tree's
scripts/flags.sh for both), runs the same commands with both binaries in
WORKDIR/run-base and WORKDIR/run-new:
  simulate with every method of `dpend methods` (of the current build),
  lyapunov, divergence, poincare, a 128x128 sweep (--lyapunov --stats),
  study --quick --no-figures,
and compares the files: every dataset and attribute, values only (type and
storage changes are listed as notes). Timing and machine data are excluded
(see docs/compare-builds.md). One line per file, then
  compare: N files identical, M within R, K differ

options:
  --base REV      the revision to compare against; default: the merge base
                  with `main` if HEAD is not on main's line, else HEAD when
                  the working tree has changes to tracked files, else HEAD~1
  --rel R         largest accepted relative difference |a-b|/max(|a|,|b|)
                  of one element; default 1e-13
  --allow-added   datasets and attributes that only the new build writes (new
                  outputs) are listed as notes, not differences; removed or
                  changed ones still differ
  --exclude NAME  also exclude datasets or attributes called NAME (a name or
                  a full path such as /summary/markdown or /x@attr); repeatable
  --quick         smaller runs (about 4x cheaper; study restricted to 3
                  methods and one case); for iterating, not for the final check
  --bench         also run dpend-bench of both builds back to back and print
                  every figure with the ratio new/base
  --repeat N      bench rounds, 1 or 2 (2: base new new base); default 1
  --keep          keep the worktree and, for a temporary WORKDIR, all files
  -h, --help      this text

WORKDIR: where the worktree, runs and logs go; default a new temporary
directory (removed at the end unless --keep). With --keep and the same
WORKDIR and REV, a second run reuses the base build.

Exit status: 0 every file identical or within R; 1 a file differs (or is
missing, or a command's exit status differs); 2 invalid usage; 3 a build or
the worktree failed.
EOF
}

die() { echo "compare_builds: $2" >&2; exit "$1"; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
caller_pwd=$PWD
base_rev=""
rel=1e-13
bench=0
repeat=1
quick=0
keep=0
workdir=""
extra_excludes=()
allow_added=0

while [[ $# -gt 0 ]]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --base) [[ $# -ge 2 ]] || die 2 "--base needs a value"; base_rev=$2; shift 2 ;;
    --base=*) base_rev=${1#--base=}; shift ;;
    --rel) [[ $# -ge 2 ]] || die 2 "--rel needs a value"; rel=$2; shift 2 ;;
    --rel=*) rel=${1#--rel=}; shift ;;
    --allow-added) allow_added=1; shift ;;
    --exclude) [[ $# -ge 2 ]] || die 2 "--exclude needs a value"; extra_excludes+=("$2"); shift 2 ;;
    --exclude=*) extra_excludes+=("${1#--exclude=}"); shift ;;
    --repeat) [[ $# -ge 2 ]] || die 2 "--repeat needs a value"; repeat=$2; shift 2 ;;
    --repeat=*) repeat=${1#--repeat=}; shift ;;
    --bench) bench=1; shift ;;
    --quick) quick=1; shift ;;
    --keep) keep=1; shift ;;
    --) shift; break ;;
    -*) die 2 "unknown option '$1' (see --help)" ;;
    *) [[ -z "$workdir" ]] || die 2 "one WORKDIR only (got '$workdir' and '$1')"
       workdir=$1; shift ;;
  esac
done
if [[ $# -gt 0 ]]; then
  [[ -z "$workdir" && $# -eq 1 ]] || die 2 "one WORKDIR only"
  workdir=$1
fi
[[ "$rel" =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] \
  || die 2 "invalid --rel: '$rel' is not a number; a relative difference >= 0, e.g. 1e-13"
[[ "$repeat" == 1 || "$repeat" == 2 ]] || die 2 "invalid --repeat: '$repeat'; 1 or 2"
for x in "${extra_excludes[@]+"${extra_excludes[@]}"}"; do
  [[ -n "$x" && "$x" != *$'\t'* && "$x" != *$'\n'* ]] \
    || die 2 "invalid --exclude: empty or with a tab or newline"
done
for tool in git fpm h5dump awk; do
  command -v "$tool" >/dev/null || die 3 "$tool not found"
done

# ---- the base revision -------------------------------------------------------------
cd "$root"
git rev-parse --git-dir >/dev/null 2>&1 || die 3 "'$root' is not a git repository"
base_why=""
if [[ -z "$base_rev" ]]; then
  head=$(git rev-parse HEAD)
  mb=""
  if git rev-parse --verify --quiet main >/dev/null; then
    mb=$(git merge-base HEAD main 2>/dev/null || true)
  fi
  if [[ -n "$mb" && "$mb" != "$head" ]]; then
    base_rev=$mb; base_why="merge base with main"
  elif ! git diff --quiet HEAD -- 2>/dev/null; then
    base_rev=HEAD; base_why="HEAD (the working tree has changes)"
  else
    base_rev=HEAD~1; base_why="HEAD~1 (HEAD is on main's line, the working tree is clean)"
  fi
fi
[[ "$base_rev" != -* ]] || die 2 "invalid --base: '$base_rev' starts with '-'"
base_commit=$(git rev-parse --verify --quiet "${base_rev}^{commit}") \
  || die 2 "invalid --base: '$base_rev' is not a commit of this repository"
base_label="$(git log -1 --format='%h %s' "$base_commit" | cut -c1-70)"

# ---- work directory and cleanup ----------------------------------------------------
made_tmp=0
if [[ -z "$workdir" ]]; then
  workdir=$(mktemp -d "${TMPDIR:-/tmp}/compare_builds.XXXXXX")
  made_tmp=1
else
  [[ "$workdir" == /* ]] || workdir=$caller_pwd/$workdir
  workdir=$(realpath -m -- "$workdir")
  case "$workdir/" in
    "$root"/*) [[ "$workdir" == "$root"/build/* ]] \
      || die 2 "invalid WORKDIR: '$workdir' is inside the working tree (use one outside it, or under build/)" ;;
  esac
  mkdir -p -- "$workdir" || die 2 "invalid WORKDIR: cannot create '$workdir'"
fi
wt=$workdir/base
own_wt=0   # 1 once $wt is a worktree this script made or reuses: removed unless --keep
# shellcheck disable=SC2317  # invoked by the EXIT trap
cleanup() {
  if [[ $keep -eq 0 ]]; then
    if [[ $own_wt -eq 1 ]]; then
      git -C "$root" worktree remove --force -- "$wt" >/dev/null 2>&1 || true
    fi
    if [[ $made_tmp -eq 1 ]]; then rm -rf -- "$workdir"; fi
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# shellcheck source-path=SCRIPTDIR source=flags.sh disable=SC1091
. "$root/scripts/flags.sh"
flags=$RELEASE_FLAGS

t_all=$SECONDS
echo "compare_builds: base $base_label${base_why:+ ($base_why)}"
echo "compare_builds: new  the working tree of $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- || echo ' with uncommitted changes')"
echo "compare_builds: flags $flags"
echo "compare_builds: workdir $workdir"

# ---- builds ------------------------------------------------------------------------
# fpm_path DIR TARGET...: the path of a built executable (fpm run --runner echo)
fpm_path() {
  local dir=$1 out
  shift
  out=$(cd "$dir" && fpm run "$@" --profile release --flag "$flags" --runner echo 2>/dev/null \
    | tail -n 1) || return 1
  case "$out" in /*) ;; *) out="$dir/$out" ;; esac
  [[ -x "$out" && -f "$out" ]] || return 1
  printf '%s\n' "$out"
}
build_tree() {   # build_tree DIR LOG
  (cd "$1" && fpm build --profile release --flag "$flags") >"$2" 2>&1
}

t0=$SECONDS
if [[ -d "$wt" ]]; then
  have=$(git -C "$wt" rev-parse HEAD 2>/dev/null || true)
  if [[ "$have" != "$base_commit" ]] || ! git -C "$wt" diff --quiet HEAD -- 2>/dev/null \
     || ! git -C "$root" worktree list --porcelain | grep -qxF "worktree $wt"; then
    die 2 "invalid WORKDIR: '$wt' exists and is not a clean worktree of $base_rev of this repository"
  fi
  own_wt=1
  echo "compare_builds: reusing the worktree $wt"
else
  git -C "$root" worktree add --detach -- "$wt" "$base_commit" >"$workdir/worktree.log" 2>&1 \
    || { cat "$workdir/worktree.log" >&2; die 3 "git worktree add failed"; }
  own_wt=1
fi
if [[ -f "$wt/scripts/flags.sh" ]] && ! cmp -s "$wt/scripts/flags.sh" "$root/scripts/flags.sh"; then
  echo "note: scripts/flags.sh differs between the builds; both are built with the current one"
fi
build_tree "$root" "$workdir/build-new.log" \
  || { tail -n 30 "$workdir/build-new.log" >&2; die 3 "the build of the working tree failed (log: $workdir/build-new.log)"; }
t_build_new=$((SECONDS - t0)); t0=$SECONDS
build_tree "$wt" "$workdir/build-base.log" \
  || { tail -n 30 "$workdir/build-base.log" >&2; die 3 "the build of $base_rev failed (log: $workdir/build-base.log)"; }
t_build_base=$((SECONDS - t0))
new_bin=$(fpm_path "$root" dpend) || die 3 "dpend of the working tree not found"
base_bin=$(fpm_path "$wt" dpend) || die 3 "dpend of $base_rev not found"

# ---- the method names, from the current build ----------------------------------------
# `dpend methods --names` or `dpend methods`: one line of names, or a table whose first
# column holds them (header and separator lines skipped, `|` borders allowed).
parse_methods() {
  awk '
    { sub(/\r$/, ""); line = $0; gsub(/\|/, " ", line); gsub(/`/, "", line)
      n = split(line, f, /[ \t]+/); k = 0
      for (i = 1; i <= n; i++) if (f[i] != "") w[++k] = f[i]
      if (k == 0 || w[1] ~ /^#/ || w[1] ~ /^[-=+:]+$/) next
      rows++; first[rows] = w[1]; all[rows] = ""
      for (i = 1; i <= k; i++) all[rows] = all[rows] " " w[i]
    }
    END {
      if (rows == 1) { n = split(all[1], w, " "); for (i = 1; i <= n; i++) out(w[i]) }
      else for (r = 1; r <= rows; r++) out(first[r])
    }
    function out(x) {
      x = tolower(x)
      if (x !~ /^[a-z][a-z0-9_]*$/ || x == "name" || x == "method" || x == "methods") return
      if (!(x in seen)) { seen[x] = 1; print x }
    }'
}
methods=()
for try in names plain; do
  if [[ $try == names ]]; then raw=$("$new_bin" methods --names 2>/dev/null) || raw=""
  else raw=$("$new_bin" methods 2>/dev/null) || raw=""; fi
  mapfile -t methods < <(printf '%s\n' "$raw" | parse_methods)
  [[ ${#methods[@]} -gt 0 ]] && break
done
[[ ${#methods[@]} -gt 0 ]] || die 3 "no method names from '$new_bin methods'"

# ---- the runs ------------------------------------------------------------------------
if [[ $quick -eq 1 ]]; then
  sim=(--t-end 2); lya=(--t-end 200); div=(--pairs 5 --lyapunov-t 100)
  poi=(--ics 10 --points 100 --t-end 500); swp=(--n 64 --t-end 10)
  stu=(--methods "rk4,gauss6,dopri5" --cases small)
else
  sim=(--t-end 10); lya=(--t-end 500); div=(--pairs 10 --lyapunov-t 300)
  poi=(--ics 20 --points 200 --t-end 1000); swp=(--n 128 --t-end 20)
  stu=()
fi
# run_set BIN DIR: every command in DIR; exit statuses in DIR/status.txt
run_set() {
  local bin=$1 dir=$2 m
  mkdir -p -- "$dir"
  : >"$dir/status.txt"
  one() {   # one NAME ARGS...
    local name=$1 st=0
    shift
    (cd "$dir" && "$bin" "$@" >"$dir/$name.out" 2>"$dir/$name.err") || st=$?
    printf '%s %s\n' "$name" "$st" >>"$dir/status.txt"
  }
  for m in "${methods[@]}"; do
    one "simulate_$m" simulate --method "$m" "${sim[@]}" --output "simulate_$m.h5" --force
  done
  one lyapunov lyapunov "${lya[@]}" --output lyapunov.h5 --force
  one divergence divergence "${div[@]}" --output divergence.h5 --force
  one poincare poincare "${poi[@]}" --output poincare.h5 --force
  one sweep sweep "${swp[@]}" --lyapunov --stats --quiet --output sweep.h5 --force
  one study study --quick --no-figures "${stu[@]+"${stu[@]}"}" --output study/study.h5 --force
}
t0=$SECONDS
run_set "$base_bin" "$workdir/run-base"
t_run_base=$((SECONDS - t0)); t0=$SECONDS
run_set "$new_bin" "$workdir/run-new"
t_run_new=$((SECONDS - t0)); t0=$SECONDS

# ---- the comparison -------------------------------------------------------------------
# flatten: h5dump -p -y -m %.17g -w 0 output -> one line per group, dataset and attribute:
#   kind TAB path TAB type TAB dataspace TAB layout TAB filters TAB data
# (attributes as OBJECT@NAME; %.17g prints every double so that it reads back exactly)
flatten_awk=$(cat <<'AWK'
function trim(s) { sub(/^[ \t]+/, "", s); sub(/[ \t]+$/, "", s); return s }
function push(m) { depth++; mode[depth] = m; rec[depth] = rec[depth - 1] }
function newrec(kind, key) {
  push(kind); rec[depth] = key; nrec++; order[nrec] = key; K[key] = kind
  T[key] = ""; S[key] = ""; L[key] = ""; F[key] = ""; V[key] = ""
}
function qname(s) { sub(/^[A-Z_]+ "/, "", s); sub(/" \{$/, "", s); return s }
BEGIN { depth = 0; mode[0] = "top"; rec[0] = ""; path[0] = "" }
{
  line = trim($0); m = mode[depth]; r = rec[depth]
  if (m == "data") {
    if (line == "}") depth--; else V[r] = V[r] (V[r] == "" ? "" : " ") line
    next
  }
  if (m == "dtype") {
    T[r] = T[r] " " line
    if (line ~ /\{$/) push("dtype"); else if (line ~ /^\}/) depth--
    next
  }
  if (m == "layout") {
    if (line == "}") depth--
    else if (line !~ /^(SIZE|OFFSET) /) L[r] = L[r] (L[r] == "" ? "" : " ") line
    next
  }
  if (m == "filters") {
    if (line == "}") depth--; else F[r] = F[r] (F[r] == "" ? "" : "; ") line
    next
  }
  if (m == "ignore") {
    if (line ~ /\{$/) push("ignore"); else if (line == "}") depth--
    next
  }
  if (line ~ /^GROUP ".*" \{$/) {
    n = qname(line); p = (n == "/") ? "/" : (cur == "/" ? "" : cur) "/" n
    newrec("G", p); gpath[depth] = p; cur = p; next
  }
  if (line ~ /^DATASET ".*" \{$/) {
    n = qname(line); newrec("D", (cur == "/" ? "" : cur) "/" n); next
  }
  if (line ~ /^ATTRIBUTE ".*" \{$/) {
    n = qname(line); newrec("A", r "@" n); next
  }
  if (line ~ /^HDF5 ".*" \{$/) { push("file"); next }
  if (line ~ /^DATATYPE /) {
    t = trim(substr(line, 9))
    if (t ~ /\{$/) { T[r] = t; push("dtype") } else T[r] = t
    next
  }
  if (line ~ /^DATASPACE /) { S[r] = trim(substr(line, 10)); next }
  if (line == "STORAGE_LAYOUT {") { push("layout"); next }
  if (line == "FILTERS {") { push("filters"); next }
  if (line == "DATA {") { push("data"); next }
  if (line == "}") {
    if (mode[depth] == "G") {   # back to the enclosing group
      for (d = depth - 1; d > 0 && !(d in gpath); d--) ;
      cur = (d > 0) ? gpath[d] : ""
    }
    delete gpath[depth]; depth--; next
  }
  if (line ~ /\{$/) { push("ignore"); next }
  if (r != "" && line != "") V[r] = V[r] (V[r] == "" ? "" : " ") line   # links and the like
}
END {
  for (i = 1; i <= nrec; i++) {
    k = order[i]
    printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n", K[k], k, T[k], S[k], L[k], F[k], V[k]
  }
}
AWK
)

# compare: base flat file, new flat file -> report lines, the last one
#   RESULT identical|within|differ DATASETS ATTRIBUTES EXCLUDED
compare_awk=$(cat <<'AWK'
BEGIN { FS = "\t"; thr = ENVIRON["CB_REL"] + 0; n_ex = split(ENVIRON["CB_EXCLUDES"], EX, "\n"); for (i = 1; i <= n_ex; i++) XL[EX[i]] = 1
  n_info = split("version program compiler compiler_options threads", IN, " ")
  for (i = 1; i <= n_info; i++) INFO[IN[i]] = 1 }
function leaf(key,   s) { s = key; if (s ~ /@/) sub(/^.*@/, "", s); else sub(/^.*\//, "", s); return s }
# Timing and machine data: never results (docs/compare-builds.md)
function excluded(key,   nm) {
  nm = leaf(key)
  if (key in XL || nm in XL) return 1
  if (nm == "created" || nm == "date" || nm == "host" || nm == "hostname" || nm == "cpu") return 1
  if (nm == "wall_time" || nm ~ /^wall_/ || nm ~ /seconds$/ || nm ~ /^elapsed/) return 1
  if (key == "/summary/markdown") return 1
  if (key ~ /(^|\/)timing(\/|@|$)/) return 1
  return 0
}
function short(s) { return length(s) > 60 ? substr(s, 1, 57) "..." : s }
function num(s) { return s ~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/ }
function special(s) { return tolower(s) ~ /(nan|inf)/ }
# note(KEY, WHAT): notes with the same WHAT are printed once, with their keys
function note(key, what) {
  if (!(what in NK)) { NW[++nn] = what; NK[what] = key; NC[what] = 1 }
  else { NC[what]++; if (NC[what] <= 4) NK[what] = NK[what] ", " key }
}
function filterdiff(a, b,   x, y, i, n, s, A, B) {   # "+ added; - removed" filters
  n = split(a, x, "; "); for (i = 1; i <= n; i++) A[x[i]] = 1
  n = split(b, y, "; "); for (i = 1; i <= n; i++) B[y[i]] = 1
  s = ""
  for (i in B) if (!(i in A)) s = s (s == "" ? "" : ", ") "+ " i
  for (i in A) if (!(i in B)) s = s (s == "" ? "" : ", ") "- " i
  return s == "" ? "order " a " -> " b : s
}
function bad(s) { lines[++nl] = "  " s; worst = 2 }
function within(s) { lines[++nl] = "  " s; if (worst < 1) worst = 1 }
function cmpdata(key, a, b, isnum,   na, nb, x, y, i, nd, mr, r, d, m) {
  if (a == b) return
  if (!isnum) {
    if (leaf(key) in INFO) note(key, short(a) " -> " short(b))
    else bad(key ": text differs: " short(a) " -> " short(b))
    return
  }
  gsub(/[ \t]/, "", a); gsub(/[ \t]/, "", b)
  if (a == b) return
  na = split(a, x, ","); nb = split(b, y, ",")
  if (na != nb) { bad(key ": " na " elements in base, " nb " in new"); return }
  nd = 0; mr = 0
  for (i = 1; i <= na; i++) {
    if (x[i] == y[i]) continue
    if (special(x[i]) || special(y[i]) || !num(x[i]) || !num(y[i])) {
      if (tolower(x[i]) ~ /nan/ && tolower(y[i]) ~ /nan/) continue
      nd++; mr = "inf"; continue
    }
    d = x[i] - y[i]; if (d < 0) d = -d
    m = (x[i] < 0 ? -x[i] : x[i]); if ((y[i] < 0 ? -y[i] : y[i]) > m) m = (y[i] < 0 ? -y[i] : y[i])
    nd++
    if (d == 0) continue                        # -0 against 0
    r = d / m
    if (mr != "inf" && r > mr) mr = r
  }
  if (nd == 0) return
  msg = sprintf("%s: %d of %d elements differ, max rel %s", key, nd, na, \
                mr == "inf" ? "inf (nan or inf against a number)" : sprintf("%.2e", mr))
  if (leaf(key) in INFO) { note(key, sprintf("%d of %d elements differ", nd, na)); return }
  if (mr == "inf" || mr > thr) bad(msg); else within(msg)
}
NR == FNR { BK[$2] = $1; BT[$2] = $3; BS[$2] = $4; BL[$2] = $5; BF[$2] = $6; BV[$2] = $7
            border[++nb0] = $2; next }
{
  key = $2; seen[key] = 1
  if (excluded(key)) { nex++; next }
  if ($1 == "D") nds++; else if ($1 == "A") nat++
  if (!(key in BK)) {
    if (ENVIRON["CB_ALLOW_ADDED"] == "1") note(key, "only in new")
    else bad("only in new: " key)
    next
  }
  if (BK[key] != $1) { bad(key ": kind " BK[key] " in base, " $1 " in new"); next }
  if (BS[key] != $4) { bad(key ": dataspace " BS[key] " -> " $4); next }
  if (BT[key] != $3) note(key, "type " BT[key] " -> " $3)
  if (BL[key] != $5) note(key, "layout " (BL[key] == "" ? "-" : BL[key]) " -> " ($5 == "" ? "-" : $5))
  if (BF[key] != $6) note(key, "filters " filterdiff(BF[key], $6))
  isnum = ($3 !~ /H5T_STRING/ && $7 !~ /"/)
  cmpdata(key, BV[key], $7, isnum)
}
END {
  for (i = 1; i <= nb0; i++) { key = border[i]
    if (!(key in seen) && !excluded(key)) bad("only in base: " key) }
  for (i = 1; i <= nl; i++) print lines[i]
  for (i = 1; i <= nn; i++) { w = NW[i]
    printf "  note: %s: %s%s\n", w, NK[w], (NC[w] > 4 ? sprintf(", ... (%d in all)", NC[w]) : "") }
  printf "RESULT %s %d %d %d %d\n", (worst == 2 ? "differ" : worst == 1 ? "within" : "identical"), \
    nds, nat, nex, nn
}
AWK
)

excl_list=$(printf '%s\n' "${extra_excludes[@]+"${extra_excludes[@]}"}")
flat() {   # flat FILE OUT: 0 on success
  h5dump -p -y -m %.17g -w 0 -- "$1" 2>/dev/null | awk "$flatten_awk" >"$2"
  [[ ${PIPESTATUS[0]} -eq 0 ]]
}
n_ident=0; n_within=0; n_differ=0
mkdir -p -- "$workdir/flat"
declare -A st_base=() st_new=()
while read -r name st; do st_base[$name]=$st; done <"$workdir/run-base/status.txt"
while read -r name st; do st_new[$name]=$st; done <"$workdir/run-new/status.txt"
echo
for name in "${methods[@]/#/simulate_}" lyapunov divergence poincare sweep study; do
  if [[ $name == study ]]; then rel_path=study/study.h5; else rel_path=$name.h5; fi
  fb=$workdir/run-base/$rel_path; fn=$workdir/run-new/$rel_path
  head_note=""
  if [[ "${st_base[$name]:-}" != "${st_new[$name]:-}" ]]; then
    head_note="exit status ${st_base[$name]:-?} (base) against ${st_new[$name]:-?} (new)"
  elif [[ "${st_new[$name]:-}" != 0 ]]; then
    head_note="exit status ${st_new[$name]:-?} in both"
  fi
  if [[ ! -f "$fb" || ! -f "$fn" ]]; then
    missing=""; [[ -f "$fb" ]] || missing="base"; [[ -f "$fn" ]] || missing="${missing:+$missing and }new"
    echo "differ: $rel_path (no file from $missing${head_note:+; $head_note})"
    for side in base new; do
      if [[ -s "$workdir/run-$side/$name.err" ]]; then
        echo "  $side: $(tail -n 1 "$workdir/run-$side/$name.err" | cut -c1-150)"
      fi
    done
    n_differ=$((n_differ + 1)); continue
  fi
  tb=$workdir/flat/base-$name.tsv; tn=$workdir/flat/new-$name.tsv
  if ! flat "$fb" "$tb" || ! flat "$fn" "$tn"; then
    echo "differ: $rel_path (h5dump cannot read it)"; n_differ=$((n_differ + 1)); continue
  fi
  report=$(CB_REL=$rel CB_EXCLUDES=$excl_list CB_ALLOW_ADDED=$allow_added \
    awk "$compare_awk" "$tb" "$tn")
  read -r _ result nds nat nex nnotes <<<"$(tail -n 1 <<<"$report")"
  detail=$(sed '$d' <<<"$report")
  if [[ $head_note == "exit status "*"against"* ]]; then result=differ; fi
  counts="$nds datasets, $nat attributes"
  if [[ $nex -gt 0 ]]; then counts+=", $nex excluded"; fi
  if [[ $nnotes -eq 1 ]]; then counts+="; 1 note"; elif [[ $nnotes -gt 1 ]]; then counts+="; $nnotes notes"; fi
  if [[ -n "$head_note" ]]; then counts+="; $head_note"; fi
  case $result in
    identical) echo "identical: $rel_path ($counts)"; n_ident=$((n_ident + 1)) ;;
    within) echo "within $rel: $rel_path ($counts)"; n_within=$((n_within + 1)) ;;
    *) echo "differ: $rel_path ($counts)"; n_differ=$((n_differ + 1)) ;;
  esac
  if [[ -n "$detail" ]]; then printf '%s\n' "$detail"; fi
done
t_compare=$((SECONDS - t0))
echo "compare: $n_ident files identical, $n_within within $rel, $n_differ differ"
echo "times: build new ${t_build_new} s, build base ${t_build_base} s, runs ${t_run_base} s" \
  "+ ${t_run_new} s, compare ${t_compare} s"

# ---- the benchmark --------------------------------------------------------------------
if [[ $bench -eq 1 ]]; then
  bench_path() {   # bench_path DIR: dpend-bench as an executable, else as an example
    fpm_path "$1" dpend-bench || fpm_path "$1" --example dpend-bench
  }
  base_bench=$(bench_path "$wt") || die 3 "dpend-bench of $base_rev not found"
  new_bench=$(bench_path "$root") || die 3 "dpend-bench of the working tree not found"
  echo
  echo "bench: cpu $(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null)," \
    "$(nproc 2>/dev/null || echo '?') CPUs; base $base_bench; new $new_bench"
  echo "bench: flags $flags"
  load=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '? ? ?')
  ncpu=$(nproc 2>/dev/null || echo 1)
  echo "bench: load average at start $load"
  if awk -v l="${load%% *}" -v n="$ncpu" 'BEGIN { exit !(l + 0 > 0.5 * n) }'; then
    echo "bench: warning: the machine is busy (load ${load%% *} on $ncpu CPUs); timings are unreliable"
  fi
  order=(base new)
  [[ $repeat -eq 2 ]] && order=(base new new base)
  i=0
  t0=$SECONDS
  for side in "${order[@]}"; do
    i=$((i + 1))
    if [[ $side == base ]]; then exe=$base_bench; dir=$wt; else exe=$new_bench; dir=$root; fi
    echo "bench: round $i: $side"
    (cd "$dir" && "$exe") >"$workdir/bench-$i-$side.txt" 2>&1 \
      || die 3 "dpend-bench ($side) failed: $(tail -n 1 "$workdir/bench-$i-$side.txt")"
  done
  # key TAB value TAB unit, from `key: value unit` lines and the `wp:` table
  bench_awk=$(cat <<'AWK'
    /^wp:/ { if (NF >= 7 && $NF ~ /^[0-9.]+$/ && $3 ~ /=$/) {
               k = $3; sub(/=$/, "", k); print "wp_" $2 "_" k "=" $4 "_us\t" $NF "\tus" }
             next }
    /^[A-Za-z0-9_]+: / { k = $1; sub(/:$/, "", k)
      if ($2 !~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/) next
      if (k == "checksum") next
      u = ""; for (i = 3; i <= NF; i++) u = u (u == "" ? "" : " ") $i
      print k "\t" $2 "\t" u }
AWK
)
  for f in "$workdir"/bench-*-*.txt; do awk "$bench_awk" "$f" >"${f%.txt}.tsv"; done
  # mean of the rounds of each build; flag: a time more than 5 % longer, a rate 5 % lower
  awk -F'\t' '
    FILENAME ~ /-base\.tsv$/ { side = "b" } FILENAME ~ /-new\.tsv$/ { side = "n" }
    { if (!($1 in U)) { order[++n] = $1; U[$1] = $3 }
      S[side, $1] += $2; C[side, $1]++ }
    END {
      printf "%-44s %14s %14s %9s\n", "figure", "base", "new", "new/base"
      slow = 0; timed = 0
      for (i = 1; i <= n; i++) { k = order[i]; u = U[k]
        b = C["b", k] ? S["b", k] / C["b", k] : ""; v = C["n", k] ? S["n", k] / C["n", k] : ""
        ratio = (b != "" && v != "" && b != 0) ? v / b : ""
        flag = ""
        if (ratio != "" && k !~ /^load_average/) {
          if (u == "ns" || u == "us" || u == "s" || u == "min") {
            timed++; if (ratio > 1.05) { flag = "  SLOWER"; slow++ } }
          else if (u == "1/s") { timed++; if (ratio < 1 / 1.05) { flag = "  SLOWER"; slow++ } }
        }
        printf "%-44s %14s %14s %9s%s\n", k " [" u "]", (b == "" ? "-" : sprintf("%.4g", b)), \
          (v == "" ? "-" : sprintf("%.4g", v)), (ratio == "" ? "-" : sprintf("%.3f", ratio)), flag
      }
      printf "bench: %d of %d timed figures more than 5 %% slower\n", slow, timed
    }' "$workdir"/bench-*-*.tsv
  echo "bench: ${#order[@]} rounds in $((SECONDS - t0)) s; load average at the end" \
    "$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
fi
kept=""
if [[ $keep -eq 1 ]]; then kept="; kept $workdir"; fi
echo "compare_builds: done in $((SECONDS - t_all)) s$kept"
[[ $n_differ -eq 0 ]] || exit 1
exit 0
