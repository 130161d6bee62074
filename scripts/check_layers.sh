#!/usr/bin/env bash
# The floors of dpend use only the floors below them (docs/architecture.md, "Layers"):
#
#   core < models < integrators < analysis < lanes < io < settings < engines
#        < commands < front ends (app/, bench/, mpi/, src/capi/)
#
# This check reads every `use` statement of the Fortran sources in src/, app/, bench/
# and mpi/, finds the folder of the module each one names, and fails on any edge
# from a floor to a higher one (a module of the same floor is allowed). A submodule
# (`submodule (parent) name`) counts as the floor of its ancestor module, wherever
# its file lies. A folder of src/ that is not in the order fails too: a new floor
# needs its place here and in docs/architecture.md. Modules not defined in the tree
# (intrinsic modules, hdf5, omp_lib, mpi) are outside the order. test/ may use any
# floor.
#
# Usage: scripts/check_layers.sh [--self-test] [ROOT]
#   ROOT         the tree to read (default: this repository)
#   --self-test  also plant reverse edges in a scratch copy (core using an engine;
#                a submodule of a core module, in src/commands/, using an engine)
#                and show that the check fails on each
# Exit status: 0 no edge against the order; 1 edges against it; 2 usage or no sources.
set -euo pipefail
self_test=0
root=""
for arg in "$@"; do
  case "$arg" in
    --self-test) self_test=1 ;;
    -h | --help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "check_layers: unknown option '$arg' (--self-test, --help)" >&2; exit 2 ;;
    *) root=$arg ;;
  esac
done
[[ -n "$root" ]] || root=$(cd "$(dirname "$0")/.." && pwd)

# The floor of a source file by its folder; -1 for a folder outside the order.
check_tree() {
  local tree=$1
  local -a files
  mapfile -t files < <(cd "$tree" && find src app bench mpi -type f \
    \( -name '*.f90' -o -name '*.F90' -o -name '*.inc' \) 2> /dev/null | LC_ALL=C sort)
  if ((${#files[@]} == 0)); then
    echo "check_layers: no Fortran sources under $tree" >&2
    return 2
  fi
  (cd "$tree" && LC_ALL=C awk '
    function floor_of(path,   parts, n) {
      n = split(path, parts, "/")
      if (parts[1] != "src") return 9          # app/, bench/, mpi/: front ends
      if (parts[2] == "core") return 0
      if (parts[2] == "models") return 1
      if (parts[2] == "integrators") return 2
      if (parts[2] == "analysis") return 3
      if (parts[2] == "lanes") return 4
      if (parts[2] == "io") return 5
      if (parts[2] == "settings") return 6
      if (parts[2] == "engines") return 7
      if (parts[2] == "commands") return 8
      if (parts[2] == "capi") return 9        # src/capi/: the C interface, a front end
      return -1
    }
    # The floor of the code in `path`: that of its ancestor module for a submodule.
    function file_floor(path) {
      if ((path in ancestor) && (ancestor[path] in home)) return floor_of(home[ancestor[path]])
      return floor_of(path)
    }
    # One statement: a module or submodule definition (pass 1) or a use (pass 2).
    function statement(st,   mod, used, from, to, what) {
      sub(/^[ \t]*&?[ \t]*/, "", st)
      if (pass == 1 && st ~ /^module[ \t]+[a-z0-9_]+[ \t]*$/) {
        mod = st
        sub(/^module[ \t]+/, "", mod); sub(/[ \t]*$/, "", mod)
        home[mod] = file
        return
      }
      if (pass == 1 && match(st, /^submodule[ \t]*\([ \t]*[a-z0-9_]+/)) {
        mod = substr(st, RSTART, RLENGTH)
        sub(/^submodule[ \t]*\([ \t]*/, "", mod)
        ancestor[file] = mod
        return
      }
      if (pass != 2) return
      if (!match(st, /^use([ \t]*,[ \t]*(non_)?intrinsic)?[ \t]*(::)?[ \t]*[a-z0-9_]+/)) return
      used = substr(st, RSTART, RLENGTH)
      sub(/^use([ \t]*,[ \t]*(non_)?intrinsic)?[ \t]*(::)?[ \t]*/, "", used)
      uses++
      if (!(used in home)) return
      from = file_floor(file); to = floor_of(home[used])
      if (from < 0) { unknown[file] = 1; return }
      if (to < 0) { unknown[home[used]] = 1; return }
      if (to > from) {
        what = floor_name[from]
        if (file in ancestor) what = what ", submodule of " ancestor[file]
        printf "check_layers: %s:%d (%s) uses %s of %s (%s): against the order\n", \
          file, FNR, what, used, home[used], floor_name[to]
        bad++
      }
      edges++
    }
    BEGIN {
      split("core models integrators analysis lanes io settings engines commands front-ends", name, " ")
      for (i = 1; i <= 10; i++) floor_name[i - 1] = name[i]
    }
    # Each physical line: no CR, lower case, "!$" (OpenMP conditional) kept as code,
    # comments cut, "&" continuations joined; then each ";"-separated statement.
    FNR == 1 {
      file = FILENAME; held = ""
      if (pass == 2 && floor_of(file) < 0) unknown[file] = 1   # a folder in no floor
    }
    {
      line = tolower($0)
      sub(/\r$/, "", line)
      sub(/^[ \t]*!\$/, "", line)
      sub(/!.*/, "", line)
      if (line ~ /&[ \t]*$/) { sub(/&[ \t]*$/, "", line); held = held line; next }
      line = held line
      held = ""
      n = split(line, part, ";")
      for (s = 1; s <= n; s++) statement(part[s])
    }
    END {
      for (f in unknown) {
        printf "check_layers: %s is in no floor of the order (docs/architecture.md)\n", f
        bad++
      }
      printf "check_layers: %d use statements, %d between modules of the tree, %d against the order\n", \
        uses, edges, bad
      exit bad > 0 ? 1 : 0
    }
  ' pass=1 "${files[@]}" pass=2 "${files[@]}")
}

status=0
check_tree "$root" || status=$?
if ((self_test)); then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  (cd "$root" && cp -r src app bench mpi "$scratch"/)
  kinds="$scratch/src/core/dpend_kinds.f90"
  sed -i '0,/^module dpend_kinds/s//&\n   use dpend_sweep_engine, only: run_sweep/' "$kinds"
  echo "check_layers: self-test: a planted 'use dpend_sweep_engine' in src/core/dpend_kinds.f90"
  planted=0
  check_tree "$scratch" || planted=$?
  if ((planted != 1)); then
    echo "check_layers: self-test FAILED: the planted reverse edge was not caught" >&2
    exit 1
  fi
  echo "check_layers: self-test: the planted edge is caught (exit 1, as it should)"
  cp "$root/src/core/dpend_kinds.f90" "$kinds"
  planted_sub="$scratch/src/commands/dpend_kinds_planted.f90"
  printf '%s\n' 'submodule (dpend_kinds) dpend_kinds_planted' \
    '   use dpend_sweep_engine, only: run_sweep' 'end submodule dpend_kinds_planted' \
    > "$planted_sub"
  echo "check_layers: self-test: a planted submodule of dpend_kinds in src/commands/" \
    "using dpend_sweep_engine"
  planted=0
  check_tree "$scratch" || planted=$?
  if ((planted != 1)); then
    echo "check_layers: self-test FAILED: the planted submodule's reverse edge was not" \
      "caught" >&2
    exit 1
  fi
  echo "check_layers: self-test: the planted submodule's edge is caught (exit 1, as it" \
    "should)"
fi
exit "$status"
