#!/usr/bin/env bash
# The study with output paths whose directory and file names hold a single quote, a
# double quote, a space, `$` and non-ASCII letters, and an injection attempt: the
# study succeeds, writes its .h5 and .md (and its six figures when gnuplot exists),
# and no command hidden in a name runs (once the plot script ran through a shell
# string with the path inside single quotes).
. "$ROOT/test/reliability/lib.sh"
study=(study --quick --methods rk4 --cases small --threads 1)
figures=(energy_vs_time energy_vs_step error_vs_step work_precision roundoff tao_omega)
have_gnuplot=0
command -v gnuplot > /dev/null 2>&1 && have_gnuplot=1
[ $have_gnuplot = 1 ] || echo "note: no gnuplot: figures not checked"
paths=(
  "O'Brien \"Ünïcødé\" \$HOME dir/Ré'sumé \"q\" \$x.h5"
  "x';touch PWNED;'y/s.h5"
  "a\"; touch PWNED2; \"b/\$(touch PWNED3)\`touch PWNED4\`.h5"
  "plain/O'Brien.h5"
)
for p in "${paths[@]}"; do
  st=0
  timeout 120 "$DPEND" "${study[@]}" --output "$p" > run.out 2> run.err < /dev/null || st=$?
  what="dpend study --output $(printf '%q' "$p")"
  [ $st = 0 ] || bad "$what: exit $st: $(grep -v '^ *$' run.err | tail -n 2 | tr '\n' ' ')"
  [ -f "$p" ] && h5_study_complete "$p" || bad "$what: no complete .h5"
  [ -s "${p%.h5}.md" ] || bad "$what: no .md"
  if [ $have_gnuplot = 1 ]; then
    d=$(dirname -- "$p")
    for f in "${figures[@]}"; do
      [ -s "$d/$f.png" ] || bad "$what: figure $f.png missing"
    done
  fi
done
found=$( { find "$SCRATCH" -name 'PWNED*'; find / -maxdepth 1 -name 'PWNED*'; } 2>/dev/null)
[ -z "$found" ] || bad "a command hidden in a file name ran: $(echo $found)"
finish
