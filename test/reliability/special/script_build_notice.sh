#!/usr/bin/env bash
# Special reliability test: scripts/dpend says that it builds when the build takes
# longer than 2 s (the first build compiles every file for about 3 minutes), and
# nothing when dpend is up to date; with --quiet it is silent; a failed build
# prints the compiler's log and exits 1. fpm is replaced by a stand-in on PATH
# that sleeps (DELAY s), prints a percentage line as fpm does, and names a
# stand-in binary for `fpm run --runner echo`.
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
. "$ROOT/test/reliability/lib.sh"
mkdir -p fake
cat > fake/fpm <<'FPM'
#!/usr/bin/env bash
case "$1" in
  build) sleep "${DELAY:-0}"; echo "[ 42%]  dpend_model.f90  done."
         [ "${FAIL:-0}" = 0 ] || { echo "Error: a compiler error"; exit 1; } ;;
  run) echo "$SCRATCH/fake/dpend-bin" ;;
esac
FPM
printf '#!/usr/bin/env bash\necho "ran $*"\n' > fake/dpend-bin
chmod +x fake/fpm fake/dpend-bin
run() { env PATH="$SCRATCH/fake:$PATH" SCRATCH="$SCRATCH" "$@" "$ROOT/scripts/dpend" methods "${ARGS[@]}"; }

ARGS=()
run DELAY=3 > out.txt 2> err.txt || bad "a slow build: exit $?"
grep -q '^ran methods$' out.txt || bad "a slow build: dpend not run ($(cat out.txt))"
grep -q 'scripts/dpend: building dpend (release profile' err.txt ||
  bad "a slow build said nothing: $(cat err.txt)"
grep -q 'scripts/dpend: built in [0-9]* s' err.txt || bad "no closing line: $(cat err.txt)"

run DELAY=0 > out.txt 2> err.txt || bad "up to date: exit $?"
[ ! -s err.txt ] || bad "up to date, yet it said: $(cat err.txt)"

ARGS=(--quiet)
run DELAY=3 > out.txt 2> err.txt || bad "--quiet: exit $?"
[ ! -s err.txt ] || bad "--quiet, yet it said: $(cat err.txt)"
grep -q '^ran methods --quiet$' out.txt || bad "--quiet: dpend not run ($(cat out.txt))"

ARGS=()
run DELAY=0 FAIL=1 > out.txt 2> err.txt && bad "a failed build exits 0"
grep -q 'a compiler error' err.txt && grep -q 'scripts/dpend: build failed' err.txt ||
  bad "a failed build: $(cat err.txt)"
[ ! -s out.txt ] || bad "a failed build ran dpend"
finish
