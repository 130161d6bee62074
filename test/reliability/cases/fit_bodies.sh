# `dpend fit` with links that are not rods: --body, --com, --inertia
# accepted by fit; a fitted length places observed tip positions (data/fit_bob.csv:
# one link with a bob, l, com and damping recovered); a point body's fitted length
# moves its mass; sets the data cannot determine refused naming the combination (the
# mass scale of point masses before any work; a length that angles do not see after
# the fit, nothing written); a wrong fixed length runs (exit 0) and warns (the text is
# checked by test/reliability/special/fit_misfit_warning.sh).

cp "$ROOT/data/fit_bob.csv" "$FIXTURES/fitb_bob.csv"
cp "$ROOT/data/fit_mass_length.csv" "$FIXTURES/fitb_ml.csv"
# the first 80 samples of the two-link series
head -n 88 "$ROOT/data/fit_mass_length.csv" > "$FIXTURES/fitb_ml80.csv"

F=(fit --output g.h5)
B=(fit fitb_bob.csv --output g.h5 --links 1 --inertia 0.01)
# ---- runs
succeed fitb-bob-l-com-damping   -- "${B[@]}" --l 0.75 --com 0.5 --fit-param l,com,damping
succeed fitb-bob-wrong-length    -- "${B[@]}" --l 0.7 --com 0.5 --fit-param com,damping
succeed fitb-bob-sigma           -- "${B[@]}" --l 0.8 --com 0.6 --fit-param com --sigma 0.002
succeed fitb-point               -- "${F[@]}" fitb_ml80.csv --body point
succeed fitb-point-m2-l2         -- "${F[@]}" fitb_ml80.csv --body point --fit-param m2,l2
succeed fitb-rod-body            -- "${F[@]}" fitb_ml80.csv --body rod --fit-param l2
succeed fitb-bobs-com2-inertia2  -- "${F[@]}" fitb_ml80.csv --com 0.5,0.4 --inertia 0.08,0.03 \
    --fit-param com2,inertia2
# ---- refusals
refuse  fitb-point-mass-scale 'fit parameters' -- "${F[@]}" fitb_ml80.csv --body point \
    --fit-param m1,m2
refuse  fitb-point-mass-all   'fit parameters' -- "${F[@]}" fitb_ml80.csv --body point --fit-param m
refuse  fitb-bobs-l2-angles   'fit parameters' -- "${F[@]}" fitb_ml80.csv --com 0.5,0.4 \
    --inertia 0.08,0.03 --fit-param l2
refuse  fitb-body-name        body      -- "${F[@]}" fitb_ml80.csv --body stick
refuse  fitb-body-empty       body      -- "${F[@]}" fitb_ml80.csv --body ''
refuse  fitb-body-missing     body      -- "${F[@]}" fitb_ml80.csv --body
refuse  fitb-body-point-com   body      -- "${F[@]}" fitb_ml80.csv --body point --com 1,1
refuse  fitb-body-rod-inertia body      -- "${F[@]}" fitb_ml80.csv --body rod --inertia 0.1,0.1
refuse  fitb-com-negative     com1      -- "${F[@]}" fitb_ml80.csv --com -0.1,0.5
refuse  fitb-com-count        com       -- "${F[@]}" fitb_ml80.csv --com 0.5
refuse  fitb-com-nan          com       -- "${F[@]}" fitb_ml80.csv --com nan,0.5
refuse  fitb-inertia-text     inertia   -- "${F[@]}" fitb_ml80.csv --inertia 0.1,abc
refuse  fitb-inertia-negative inertia2  -- "${F[@]}" fitb_ml80.csv --inertia 0.1,-1
refuse  fitb-bob-l-zero       l1        -- "${B[@]}" --l 0 --fit-param l
# ---- a body named by --body fixes com and inertia: fitting them is refused
refuse  fitb-point-fit-com2     'com2 is fixed by --body point'   -- "${F[@]}" fitb_ml80.csv \
    --body point --fit-param com2
refuse  fitb-point-fit-inertia2 'inertia2 is fixed by --body point' -- "${F[@]}" fitb_ml80.csv \
    --body point --fit-param inertia2
refuse  fitb-rod-fit-com2       'com2 is fixed by --body rod'     -- "${F[@]}" fitb_ml80.csv \
    --body rod --fit-param com2
refuse  fitb-rod-fit-com        'com is fixed by --body rod'      -- "${F[@]}" fitb_ml80.csv \
    --body rod --fit-param l2,com
