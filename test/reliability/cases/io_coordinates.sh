# IO, the coordinates' names: export --csv names the columns of q, qdot,
# qddot and p from the file's root attribute `coordinates` (the elastic pendulum:
# r, phi, rdot, ..., p_r; the rods keep q1, qdot1, ...) and every (x, y) vector
# NAME_x, NAME_y. A `coordinates` attribute from elsewhere is checked before it
# reaches a CSV header: one string of as many names (letters, digits, '_') as the
# columns, else a one-line refusal naming it; a file without it keeps the old names.
#
# Fixtures: ioc_*.h5, dpend's own files edited by scripts/check/h5craft.f90 (h5fc).

_ioc_tool=$(mktemp -d "${TMPDIR:-/tmp}/ioc-h5craft.XXXXXX")
(
  set -e
  cd "$_ioc_tool"
  h5fc -o h5craft "$ROOT/scripts/check/h5craft.f90" > build.log 2>&1
  H=$_ioc_tool/h5craft
  cd "$FIXTURES"
  edit() { local to=$1 from=$2; shift 2; cp "$from" "$to"; "$H" "$to" "$@"; }
  "$DPEND" simulate --t-end 0.2 --output ioc_sim.h5 > /dev/null
  "$DPEND" simulate --model elastic --m 1 --k 40 --l0 1 --g 9.8 --q 1.2,-1.0 --w 0,0 \
    --t-end 0.2 --output ioc_elastic.h5 > /dev/null
  edit ioc_comma.h5  ioc_sim.h5 attr-sub / coordinates 'q1 q2' 'q1,q2'
  edit ioc_count.h5  ioc_sim.h5 attr-sub / coordinates 'q1 q2' 'q1'
  edit ioc_more.h5   ioc_sim.h5 attr-sub / coordinates 'q1 q2' 'q1 q2 q3'
  edit ioc_quote.h5  ioc_elastic.h5 attr-sub / coordinates 'r phi' 'r "phi'
  edit ioc_int.h5    ioc_sim.h5 attr-int / coordinates 2
) > /dev/null 2> "$_ioc_tool/fixtures.err" ||
  { echo "io_coordinates.sh: could not make the fixtures:" >&2; cat "$_ioc_tool/fixtures.err" >&2
    cat "$_ioc_tool/build.log" >&2 2>/dev/null; }
rm -rf "$_ioc_tool"

# names from the description
succeed ioc-csv-elastic           -- export ioc_elastic.h5 --csv t q qdot qddot p rA rC F_joint
succeed ioc-csv-pendulum          -- export ioc_sim.h5 --csv t q qdot qddot p rB rC2 F01 rC
# a hostile `coordinates` is refused, naming it, when a column would take its names
refuse  ioc-coords-comma   coordinates -- export ioc_comma.h5 --csv t q
refuse  ioc-coords-count   coordinates -- export ioc_count.h5 --csv qdot
refuse  ioc-coords-more    coordinates -- export ioc_more.h5 --csv p
refuse  ioc-coords-quote   coordinates -- export ioc_quote.h5 --csv qddot
refuse  ioc-coords-int     coordinates -- export ioc_int.h5 --csv q
# ... and not consulted where no column takes its names
succeed ioc-coords-unused         -- export ioc_comma.h5 --csv t energy rB
succeed ioc-coords-plain          -- export ioc_comma.h5 t q
