#!/usr/bin/env bash
# A device node or a FIFO as --output, with and without --force, for every command
# that writes: refused with exit 2 and one line, the node untouched, nothing left
# beside it (sweep --force once renamed its file over a device node).
. "$ROOT/test/reliability/lib.sh"
mkfifo fifo || die "mkfifo failed"
# As root, never the real /dev/null (a faulty --force would replace it for the
# whole machine): a copy of its node in the scratch directory, where dpend can
# write. Otherwise /dev/null itself (a non-root run cannot replace it).
targets=(fifo)
if [ "$(id -u)" = 0 ]; then
  mknod nulldev c 1 3 || skip "running as root but mknod failed"
  targets+=(nulldev)
else
  targets+=(/dev/null)
fi
printf '%s\n' '0.1 0.2 0 0' '-1.5 -1.5 0 0' > list.txt
commands=(
  "simulate --t-end 0.1"
  "lyapunov --t-end 1"
  "divergence --t-end 1 --pairs 2 --lyapunov-t 0"
  "poincare --ics 2 --t-end 2 --points 5"
  "sweep --n 4 --t-end 1 --quiet --threads 1"
  "sweep --ic-file list.txt --t-end 1 --quiet --threads 1"
  "study --quick --methods rk4 --cases small --no-figures --threads 1"
)
restore() {  # restore NODE: make the FIFO or device node again
  case $1 in
    fifo) rm -f fifo; mkfifo fifo ;;
    nulldev) rm -f nulldev; mknod nulldev c 1 3 ;;
  esac
}
node_id() { stat -L -c '%F %t:%T %i' "$1" 2>/dev/null || stat -c '%F %t:%T %i' "$1"; }
n=0
for t in "${targets[@]}"; do
  before=$(node_id "$t")
  for c in "${commands[@]}"; do
    for force in "" --force; do
      read -r -a args <<< "$c"
      n=$((n + 1))
      st=0
      timeout 5 "$DPEND" "${args[@]}" --output "$t" $force > out.txt 2> err.txt < /dev/null ||
        st=$?
      lines=$(grep -c '' err.txt)
      what="dpend $c --output $t $force"
      [ $st = 124 ] && bad "$what: hangs (killed after 5 s)"
      [ $st = 2 ] || bad "$what: exit $st, expected 2 ($(head -n 1 err.txt))"
      [ "$lines" = 1 ] || bad "$what: $lines stderr lines, expected 1"
      grep -qi output err.txt || bad "$what: the message does not name --output"
      if [ "$(node_id "$t")" != "$before" ]; then
        bad "$what: $t was replaced ($(node_id "$t" | cut -d' ' -f1-2))"
        restore "$t"; before=$(node_id "$t")
      fi
      rm -f out.txt err.txt
      stray=$(stray_files . fifo nulldev list.txt)
      [ -z "$stray" ] || { bad "$what: left $(echo $stray)"; rm -rf -- $stray; }
    done
  done
done
ls -a /dev | grep -q '^\.null\.tmp-' && bad "temporary files left in /dev: $(ls -a /dev | grep '^\.null')"
echo "$n runs checked"
finish
