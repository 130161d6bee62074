#!/usr/bin/env bash
# Special reliability test: threads asked for through the environment are bounded as
# --threads is. With OMP_NUM_THREADS=100000 the OpenMP runtime crashed (SIGSEGV,
# a sweep's working file left behind); dpend now uses 1024 threads at most and says
# so in one line. A sweep, a study and poincare (the three threaded loops) run.
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0
run() {
  local what=$1 out=$2 rc=0
  shift 2
  OMP_NUM_THREADS=100000 timeout -k 5 120 "$DPEND" "$@" > out.log 2> err.log < /dev/null ||
    rc=$?
  if [ $rc != 0 ] || [ ! -s "$out" ] || ! grep -q 'OMP_NUM_THREADS asks for 100000 threads, above 1024: using 1024' err.log; then
    failures=$((failures + 1))
    printf 'FAIL %s: exit %s, %s\n' "$what" "$rc" "$(head -n 2 err.log | tr '\n' ' ')"
  else
    printf 'ok   %s\n' "$what"
  fi
}
run sweep s.h5 sweep --n 16 --t-end 5 --quiet --output s.h5
printf "&study case_name(1)='a', case_q1(1)=0.1, case_q2(1)=0.1, order_case='a', drift_case='a', ro_case='a', tao_case='a' /\n" > st.nml
run study st.h5 study --config st.nml --quick --no-figures --methods rk4 --output st.h5
run poincare p.h5 poincare --t-end 20 --output p.h5
[ $failures = 0 ]
