# Inputs of the per-pixel indicators and the parameter axes of dpend sweep: refused
# before any work (one line naming the field, exit 2, no file touched), and their
# edge values succeed without a trap in the debug build.

printf '0 0 0 0\n0.5 0.5 0 0\n1 1 0 0\n' > "$FIXTURES/swi_list.txt"
W=(sweep --n 4 --t-end 1 --quiet --output g.h5)
# ---- --indicator
refuse  swi-ind-unknown         indicator -- "${W[@]}" --indicator gali3
refuse  swi-ind-empty           indicator -- "${W[@]}" --indicator ''
refuse  swi-ind-two-words       indicator -- "${W[@]}" --indicator 'megno fli'
refuse  swi-ind-missing         indicator -- "${W[@]}" --indicator
refuse  swi-ind-with-lyapunov   indicator -- "${W[@]}" --indicator sali --lyapunov
refuse  swi-ind-lambda1-3links  indicator -- "${W[@]}" --links 3 --indicator lambda1
# ---- parameter axes
refuse  swi-par-unknown         axis1   -- "${W[@]}" --axis1 m3 --min1 1 --max1 2
refuse  swi-par-zero            min1    -- "${W[@]}" --axis1 m2/m1 --min1 0 --max1 2
refuse  swi-par-negative        min2    -- "${W[@]}" --axis2 l2 --min2 -1 --max2 2
refuse  swi-par-nan             max1    -- "${W[@]}" --axis1 m1 --min1 1 --max1 nan
refuse  swi-par-inf             max1    -- "${W[@]}" --axis1 l1 --min1 1 --max1 inf
refuse  swi-par-same            axis2   -- "${W[@]}" --axis1 l2 --min1 1 --max1 2 --axis2 l2/l1 --min2 1 --max2 2
refuse  swi-par-twice           axis2   -- "${W[@]}" --axis1 m1 --min1 1 --max1 2 --axis2 m1 --min2 1 --max2 2
refuse  swi-par-mass-huge       'm2 of a pixel'  -- "${W[@]}" --axis1 m2/m1 --min1 1 --max1 1e7
refuse  swi-par-length-tiny     'l2 of a pixel'  -- "${W[@]}" --axis2 l2/l1 --min2 1e-9 --max2 1 --l1 1e-3
refuse  swi-par-mass-tiny       'm1 of a pixel'  -- "${W[@]}" --axis1 m1 --min1 1e-9 --max1 1
refuse  swi-par-one-link        axis1   -- "${W[@]}" --links 1 --axis1 l1 --min1 1 --max1 2 --axis2 q1
refuse  swi-par-empty-grid      empty   -- "${W[@]}" --axis1 m2/m1 --min1 1 --max1 1
# edge values that must succeed
succeed swi-ok-megno            -- "${W[@]}" --indicator megno
succeed swi-ok-fli              -- "${W[@]}" --indicator fli
succeed swi-ok-sali             -- "${W[@]}" --indicator sali
succeed swi-ok-gali2            -- "${W[@]}" --indicator gali2
succeed swi-ok-lambda1          -- "${W[@]}" --indicator lambda1
succeed swi-ok-flip             -- "${W[@]}" --indicator flip
succeed swi-ok-megno-list       -- sweep --ic-file "$FIXTURES/swi_list.txt" --t-end 1 --quiet --indicator megno --output g.h5
succeed swi-ok-megno-3links     -- "${W[@]}" --links 3 --indicator megno
succeed swi-ok-par-edges        -- sweep --n 4 --quiet --output g.h5 --axis1 m2/m1 --min1 1e-6 --max1 1e6 --axis2 l2/l1 --min2 1e-6 --max2 1e6 --t-end 0.01
succeed swi-ok-par-one-point    -- sweep --n2 4 --t-end 1 --quiet --output g.h5 --axis1 m1 --n1 1 --min1 2 --max1 2 --axis2 l1 --min2 0.5 --max2 2
succeed swi-ok-par-3links       -- "${W[@]}" --links 3 --axis1 m2/m1 --min1 0.5 --max1 2 --axis2 theta3 --indicator gali2
succeed swi-ok-par-natural-l1   -- "${W[@]}" --axis1 l1 --min1 0.1 --max1 10 --time-unit natural --indicator fli
# ---- sweep-compare --agreement (fixtures: 6 x 6 maps, debug build well under a second)
_swi_sweep() {  # NAME ARGS...
  local name=$1; shift
  local n=(--n 6)   # unless ARGS give their own (an option given twice is refused)
  [[ " $* " == *" --n "* ]] && n=()
  (cd "$FIXTURES" && "$DPEND" sweep --quiet "${n[@]}" "$@" --output "$name" > /dev/null 2>&1) ||
    echo "sweep_indicators.sh: could not make $name" >&2
}
_swi_sweep swi_megno.h5 --t-end 3 --indicator megno
_swi_sweep swi_lambda1.h5 --t-end 30 --indicator lambda1
_swi_sweep swi_fli.h5 --t-end 3 --indicator fli
_swi_sweep swi_flip.h5 --t-end 3
_swi_sweep swi_megno5.h5 --t-end 3 --indicator megno --n 5
_swi_sweep swi_megno_pt.h5 --t-end 3 --indicator megno --body point
_swi_sweep swi_flip_pt.h5 --t-end 3 --body point
succeed swi-agr-ok              -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement
succeed swi-agr-thresholds      -- sweep-compare --agreement swi_megno.h5 swi_lambda1.h5 --threshold-a 3 --threshold-b=0.1 --output a.h5
succeed swi-agr-fli             -- sweep-compare swi_fli.h5 swi_megno.h5 --agreement --threshold-a 2
succeed swi-agr-help            -- sweep-compare --agreement --help
refuse  swi-agr-rel             '--rel'      -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --rel 0.1
refuse  swi-agr-flag-value      'takes no value'  -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement=1
refuse  swi-agr-force-value     'takes no value'  -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --force=yes
refuse  swi-agr-thr-nan         threshold-a       -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --threshold-a nan
refuse  swi-agr-thr-junk        threshold-b       -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --threshold-b x
refuse  swi-agr-thr-missing     'needs a value'   -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --threshold-a
refuse  swi-agr-unknown         'unknown option'  -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --threshold-c 1
refuse  swi-agr-no-indicator    'no indicator'    -- sweep-compare swi_megno.h5 swi_flip.h5 --agreement
refuse  swi-agr-fli-no-thr      threshold         -- sweep-compare swi_fli.h5 swi_megno.h5 --agreement
refuse  swi-agr-other-pixels    n1                -- sweep-compare swi_megno.h5 swi_megno5.h5 --agreement
refuse  swi-agr-other-bodies    'com1 = '         -- sweep-compare swi_megno.h5 swi_megno_pt.h5 --agreement
refuse  swi-cmp-other-bodies    'com1 = '         -- sweep-compare swi_flip.h5 swi_flip_pt.h5
succeed swi-agr-same-bodies     -- sweep-compare swi_megno_pt.h5 swi_megno_pt.h5 --agreement --threshold-a 2
refuse  swi-agr-one-file        'two files'       -- sweep-compare swi_megno.h5 --agreement
refuse  swi-agr-not-hdf5        'not an HDF5'     -- sweep-compare swi_list.txt swi_megno.h5 --agreement
refuse  swi-agr-output-dir      directory         -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --output no/dir/a.h5
refuse  swi-cmp-thr-no-agree    threshold-a       -- sweep-compare swi_megno.h5 swi_lambda1.h5 --threshold-a 3
refuse  swi-cmp-out-no-agree    output            -- sweep-compare swi_megno.h5 swi_lambda1.h5 --output a.h5
refuse  swi-agr-force-no-output --force           -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --force
refuse  swi-agr-output-empty    output            -- sweep-compare swi_megno.h5 swi_lambda1.h5 --agreement --output ''
# ---- sweep-compare of two maps of one indicator compares its values and classes
succeed swi-cmp-megno           -- sweep-compare swi_megno.h5 swi_megno.h5
succeed swi-cmp-fli             -- sweep-compare swi_fli.h5 swi_fli.h5 --rel 0.1
refuse  swi-cmp-megno-flip      'flip times'      -- sweep-compare swi_megno.h5 swi_flip.h5
refuse  swi-cmp-megno-lambda1   'maps lambda1'    -- sweep-compare swi_megno.h5 swi_lambda1.h5
refuse  swi-cmp-megno-pixels    n1                -- sweep-compare swi_megno.h5 swi_megno5.h5
