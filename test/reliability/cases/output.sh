# Output-path problems for every command that writes: an
# existing file without --force, directories, missing directories, unwritable
# directories, empty names, trailing slashes, symbolic links, device nodes, FIFOs,
# a file used as a directory. All are refused before any work: exit 2, one line
# naming --output, nothing created or changed. Runs are tiny in case one is not.

# Extra fixtures: links, a device node (as root a copy of /dev/null's node; else
# /dev/null itself, which a non-root run cannot replace), a FIFO, a study summary.
ln -s existing.h5 "$FIXTURES/link.h5"
ln -s nowhere.h5 "$FIXTURES/dangling.h5"
ln -s dir "$FIXTURES/dirlink"
mkfifo "$FIXTURES/fifo.h5"
if [ "$(id -u)" = 0 ] && mknod "$FIXTURES/null.h5" c 1 3 2>/dev/null; then
  OUT_NULL=null.h5
else
  OUT_NULL=/dev/null
fi
printf '# an earlier study summary\n' > "$FIXTURES/old_study.md"
mkdir "$FIXTURES/dir.md"   # the summary name of --output dir.h5 is a directory

# command word and tiny arguments
out_rows() {  # out_rows KEY ARGS...: the same problems for one command
  local k=$1; shift
  refuse out-$k-exists        output -- "$@" --output existing.h5
  refuse out-$k-dir           output -- "$@" --output dir
  refuse out-$k-dir-force     output -- "$@" --output dir --force
  refuse out-$k-dot           output -- "$@" --output . --force
  refuse out-$k-slash         output -- "$@" --output new.h5/
  refuse out-$k-dir-slash     output -- "$@" --output dir/ --force
  if [ "$k" = stu ]; then
    # the study creates the missing directories of its output (its default is
    # out/study/study.h5), after every other check has passed
    succeed out-$k-nodir              -- "$@" --output nodir/x.h5
    succeed out-$k-nodir-deep         -- "$@" --output nodir/a/b/x.h5 --force
  else
    refuse out-$k-nodir         output -- "$@" --output nodir/x.h5
    refuse out-$k-nodir-deep    output -- "$@" --output nodir/a/b/x.h5 --force
  fi
  refuse out-$k-proc          output -- "$@" --output /proc/x.h5
  refuse out-$k-empty         output -- "$@" --output ''
  refuse out-$k-blank         output -- "$@" --output ' '
  refuse out-$k-file-as-dir   output -- "$@" --output existing.h5/x.h5
  refuse out-$k-link-force    output -- "$@" --output link.h5 --force
  refuse out-$k-dangling      output -- "$@" --output dangling.h5
  refuse out-$k-dirlink       output -- "$@" --output dirlink --force
  refuse out-$k-device        output -- "$@" --output "$OUT_NULL"
  refuse out-$k-device-force  output -- "$@" --output "$OUT_NULL" --force
  refuse out-$k-fifo          output -- "$@" --output fifo.h5
  refuse out-$k-fifo-force    output -- "$@" --output fifo.h5 --force
  refuse out-$k-novalue       output -- "$@" --output
}
out_rows sim simulate --t-end 0.1
out_rows lya lyapunov --t-end 1
out_rows div divergence --t-end 1 --pairs 2 --lyapunov-t 0
out_rows poi poincare --ics 2 --t-end 2 --points 5
out_rows swp sweep --n 4 --t-end 1 --quiet
out_rows stu study --quick --methods rk4 --cases small --no-figures --threads 1

# command-specific
refuse out-swp-other-config  output -- sweep --n 4 --t-end 1 --quiet --output sweep_list.h5
refuse out-swp-other-t-end   output -- sweep --n 8 --t-end 2 --quiet --output sweep.h5
refuse out-stu-md-exists     output -- study --quick --methods rk4 --cases small --no-figures --threads 1 --output old_study.h5
refuse out-stu-md-dir        output -- study --quick --methods rk4 --cases small --no-figures --threads 1 --output dir.h5
succeed out-sim-force        -- simulate --t-end 0.1 --output existing.h5 --force
succeed out-sim-subdir       -- simulate --t-end 0.1 --output dir/new.h5
succeed out-sim-dirlink-in   -- simulate --t-end 0.1 --output dirlink/new.h5
succeed out-sim-space-quote  -- simulate --t-end 0.1 --output "O'Brien \"x\" \$HOME é.h5"
succeed out-lya-force        -- lyapunov --t-end 1 --output existing.h5 --force
succeed out-swp-resume       -- sweep --n 8 --t-end 1 --quiet --output sweep.h5
succeed out-swp-force        -- sweep --n 4 --t-end 1 --quiet --output sweep_list.h5 --force
succeed out-stu-newdir       -- study --quick --methods rk4 --cases small --no-figures --threads 1 --output new/sub/s.h5
