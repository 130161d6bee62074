#!/usr/bin/env bash
# Special reliability test: every option a command's parser accepts is named in its
# --help. The candidates are every '--name' the sources of the commands and settings
# match (src/commands, src/settings, app), every parameter of `dpend models` as a flag
# (its '_' written '-'), and per-link forms (--com1 .. --inertia3). Each command is
# run as `dpend CMD [its input] --CANDIDATE 1 --zz-not-an-option`: the parser reads in
# order, so an unknown candidate is refused by name ("unknown option '--CANDIDATE'"
# or "unexpected argument"), an accepted one is not, and nothing is computed (the
# last option is always refused). An accepted option missing from `CMD --help` fails,
# as does a flag that spells a parameter with '_' (one name per quantity).
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
. "$ROOT/test/reliability/lib.sh"

"$DPEND" simulate --t-end 0.1 --output s.h5 --quiet > /dev/null 2>&1 &&
  "$DPEND" sweep --n 4 --t-end 1 --output w.h5 --quiet > /dev/null 2>&1 ||
  die "the input files"

mapfile -t sources < <(find "$ROOT/src/commands" "$ROOT/src/settings" "$ROOT/app" -name '*.f90')
mapfile -t candidates < <(
  { grep -hoE "'--[a-z0-9-]+'" "${sources[@]}" | tr -d "'"
    "$DPEND" models | sed -n 's/^    \([a-z_0-9]*\) .*/--\1/p' | tr '_' '-'
    "$DPEND" models | sed -n 's/^    \([a-z_0-9]*\) .*/--\1/p' | grep '_'   # the '_' form
    for n in com inertia damping m l q w; do printf -- '--%s1\n--%s3\n' "$n" "$n"; done
  } | sort -u | grep -v -x -e '--help')
[ "${#candidates[@]}" -gt 80 ] || die "only ${#candidates[@]} candidate options found"

checked=0
for cmd in simulate lyapunov indicators divergence poincare sweep study fit animate export \
           sweep-compare methods models torques identify; do
  case $cmd in
    fit|torques) input=("$ROOT/data/fit_example.csv") ;;
    identify) input=("$ROOT/data/robot_example.csv") ;;
    animate|export) input=(s.h5) ;;
    sweep-compare) input=(w.h5 w.h5) ;;
    *) input=() ;;
  esac
  help=$("$DPEND" "$cmd" --help 2>&1) || { bad "$cmd --help exits $?"; continue; }
  for c in "${candidates[@]}"; do
    msg=$("$DPEND" "$cmd" "${input[@]}" "$c" 1 --zz-not-an-option 2>&1 > /dev/null | head -n 1)
    case $msg in
      *"unknown option '$c'"*|*"unexpected argument '$c'"*) continue ;;
    esac
    checked=$((checked + 1))
    if [[ $c == *_* ]]; then
      bad "$cmd accepts $c: a parameter's flag is spelled with '-' ($msg)"
    elif ! grep -qE -- "$c([^a-z0-9-]|$)" <<< "$help"; then
      bad "$cmd accepts $c, which its --help does not name ($msg)"
    fi
  done
done
echo "accepted options checked: $checked"
finish
