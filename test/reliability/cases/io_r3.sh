# IO, round 3 (issue 23, items 2 and 7): export --csv names the columns of q, qdot,
# qddot and p from the file's root attribute `coordinates` (the elastic pendulum:
# r, phi, rdot, ..., p_r; the rods keep q1, qdot1, ...) and every (x, y) vector
# NAME_x, NAME_y. A `coordinates` attribute from elsewhere is checked before it
# reaches a CSV header: one string of as many names (letters, digits, '_') as the
# columns, else a one-line refusal naming it; a file without it keeps the old names.
#
# Fixtures: io3_*.h5, dpend's own files edited by scripts/h5craft.f90 (h5fc).

_io3_tool=$(mktemp -d "${TMPDIR:-/tmp}/io3-h5craft.XXXXXX")
(
  set -e
  cd "$_io3_tool"
  h5fc -o h5craft "$ROOT/scripts/h5craft.f90" > build.log 2>&1
  H=$_io3_tool/h5craft
  cd "$FIXTURES"
  edit() { local to=$1 from=$2; shift 2; cp "$from" "$to"; "$H" "$to" "$@"; }
  "$DPEND" simulate --t-end 0.2 --output io3_sim.h5 > /dev/null
  "$DPEND" simulate --model elastic --m 1 --k 40 --l0 1 --g 9.8 --q 1.2,-1.0 --w 0,0 \
    --t-end 0.2 --output io3_elastic.h5 > /dev/null
  edit io3_comma.h5  io3_sim.h5 attr-sub / coordinates 'q1 q2' 'q1,q2'
  edit io3_count.h5  io3_sim.h5 attr-sub / coordinates 'q1 q2' 'q1'
  edit io3_more.h5   io3_sim.h5 attr-sub / coordinates 'q1 q2' 'q1 q2 q3'
  edit io3_quote.h5  io3_elastic.h5 attr-sub / coordinates 'r phi' 'r "phi'
  edit io3_int.h5    io3_sim.h5 attr-int / coordinates 2
) > /dev/null 2> "$_io3_tool/fixtures.err" ||
  { echo "io_r3.sh: could not make the fixtures:" >&2; cat "$_io3_tool/fixtures.err" >&2
    cat "$_io3_tool/build.log" >&2 2>/dev/null; }
rm -rf "$_io3_tool"

# names from the description
succeed io3-csv-elastic           -- export io3_elastic.h5 --csv t q qdot qddot p rA rC F_joint
succeed io3-csv-pendulum          -- export io3_sim.h5 --csv t q qdot qddot p rB rC2 F01 rC
# a hostile `coordinates` is refused, naming it, when a column would take its names
refuse  io3-coords-comma   coordinates -- export io3_comma.h5 --csv t q
refuse  io3-coords-count   coordinates -- export io3_count.h5 --csv qdot
refuse  io3-coords-more    coordinates -- export io3_more.h5 --csv p
refuse  io3-coords-quote   coordinates -- export io3_quote.h5 --csv qddot
refuse  io3-coords-int     coordinates -- export io3_int.h5 --csv q
# ... and not consulted where no column takes its names
succeed io3-coords-unused         -- export io3_comma.h5 --csv t energy rB
succeed io3-coords-plain          -- export io3_comma.h5 t q
