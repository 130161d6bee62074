#!/usr/bin/env bash
# Special reliability test: one sign convention for a fit's residuals, data − model.
# The file's /fit/residual is /fit/xy_data − /fit/xy_model (positions, data/fit_bob.csv)
# and says so in its description; docs/fit.md, docs/hdf5-layout.md and the figure
# script (scripts/plot/fit.gp) name the same sign, and no page of docs/ says
# "model minus data" or "model − data".
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
. "$ROOT/test/reliability/lib.sh"
command -v h5dump > /dev/null || skip "h5dump not found"

"$DPEND" fit "$ROOT/data/fit_bob.csv" --links 1 --inertia 0.01 --l 0.8 --com 0.65 \
  --fit-param damping --output fit.h5 --quiet > /dev/null 2> fit.err ||
  die "the fit of data/fit_bob.csv failed: $(head -c 300 fit.err)"

# the values: residual = data - model at every sample (to the rounding of h5dump's text)
values() { h5dump -d "$1" -y -w 0 -m '%.17g' fit.h5 | sed -n '/DATA {/,/}/p' |
             tr ', ' '\n\n' | grep -E '^-?[0-9]' ; }
paste <(values /fit/xy_data) <(values /fit/xy_model) <(values /fit/residual) > v.txt
n=$(wc -l < v.txt)
[ "$n" -gt 100 ] || bad "too few residual values read ($n)"
worst=$(awk '{ d = ($1 - $2) - $3; if (d < 0) d = -d; if (d > w) w = d } END { printf "%.3g", w }' v.txt)
awk -v w="$worst" 'BEGIN { exit !(w < 1e-12) }' ||
  bad "/fit/residual is not xy_data - xy_model (largest difference $worst m)"
desc=$(h5dump -a /fit/residual/description fit.h5 2>/dev/null | sed -n 's/.*(0): \(.*\)/\1/p')
[[ $desc == *"data minus model"* ]] || bad "/fit/residual's description: $desc"

grep -q 'data − model' "$ROOT/docs/fit.md" || bad "docs/fit.md does not name data − model"
grep -q 'data − model' "$ROOT/docs/hdf5-layout.md" || bad "docs/hdf5-layout.md: data − model"
grep -q 'data - model' "$ROOT/scripts/plot/fit.gp" || bad "scripts/plot/fit.gp: data - model"
if grep -rn -i -E 'model (minus|−|-) data' "$ROOT/docs" "$ROOT/README.md" "$ROOT/scripts/plot"; then
  bad "a page names the other sign (model minus data)"
fi
finish
