#!/usr/bin/env bash
# Special reliability test: `dpend animate` keeps gnuplot's messages off
# stderr when gnuplot succeeds ("N frames in animation sequence" and the like), shows
# them when it fails (a copy of scripts/plot/animate.gp with an invalid last line, through
# DPEND_ROOT: exit 1, gnuplot's error and "gnuplot failed" on stderr), and prints
# the summary's times to 4 significant digits (no 0.9666666666666667).
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
if ! command -v gnuplot >/dev/null 2>&1; then
  echo "SKIP animate_quiet: gnuplot not installed"
  exit 77
fi
cd "$SCRATCH" || exit 1
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
"$DPEND" simulate --t-end 1 --dt 1e-3 --save-every 10 --output sim.h5 > /dev/null 2>&1 ||
  { echo "FAIL simulate"; exit 1; }
"$DPEND" animate sim.h5 --output a.gif --fps 30 --size 64x64 > out.txt 2> err.txt
st=$?
[[ $st -eq 0 ]] && pass "animate exits 0" || fail "animate exits $st"
[[ ! -s err.txt ]] && pass "nothing on stderr" || fail "stderr: $(head -c 300 err.txt)"
if grep -q '31 frames, 1.033 s at 30 fps, t = 0 .. 1 s' out.txt; then
  pass "summary times to 4 digits"
else
  fail "summary: $(cat out.txt)"
fi
mkdir -p root/scripts/plot && cp "$ROOT/scripts/plot/animate.gp" root/scripts/plot/ &&
  echo 'no_such_command_25' >> root/scripts/plot/animate.gp
DPEND_ROOT="$SCRATCH/root" "$DPEND" animate sim.h5 --output b.gif --fps 5 --size 64x64 \
  > out2.txt 2> err2.txt
st=$?
[[ $st -eq 1 ]] && pass "broken animate.gp: exit 1" || fail "broken animate.gp: exit $st"
if grep -q 'no_such_command_25' err2.txt && grep -q 'gnuplot failed' err2.txt; then
  pass "broken animate.gp: gnuplot's message shown"
else
  fail "broken animate.gp: stderr $(head -c 300 err2.txt)"
fi
[[ ! -e b.gif ]] && pass "no GIF left" || fail "b.gif written"
leftover=$(find . -maxdepth 1 -name '.b.gif*' | head -n 3)
[[ -z "$leftover" ]] && pass "no temporary left" || fail "temporaries: $leftover"
exit $((failures > 0))
