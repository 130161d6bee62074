# `dpend fit` with links that are not rods (issue 26, round 5): --body, --com, --inertia
# accepted by fit; a fitted length places observed tip positions (data/fit_bob.csv:
# one link with a bob, l, com and damping recovered); a point body's fitted length
# moves its mass; sets the data cannot determine refused naming the combination (the
# mass scale of point masses before any work; a length that angles do not see after
# the fit, nothing written); a wrong fixed length runs (exit 0) and warns (the text is
# checked by test/reliability/special/fit_misfit_warning.sh).

cp "$ROOT/data/fit_bob.csv" "$FIXTURES/r5_bob.csv"
cp "$ROOT/data/fit_mass_length.csv" "$FIXTURES/r5_ml.csv"
# the first 80 samples of the two-link series
head -n 88 "$ROOT/data/fit_mass_length.csv" > "$FIXTURES/r5_ml80.csv"

F=(fit --output g.h5)
B=(fit r5_bob.csv --output g.h5 --links 1 --inertia 0.01)
# ---- runs
succeed fitr5-bob-l-com-damping   -- "${B[@]}" --l 0.75 --com 0.5 --fit-param l,com,damping
succeed fitr5-bob-wrong-length    -- "${B[@]}" --l 0.7 --com 0.5 --fit-param com,damping
succeed fitr5-bob-sigma           -- "${B[@]}" --l 0.8 --com 0.6 --fit-param com --sigma 0.002
succeed fitr5-point               -- "${F[@]}" r5_ml80.csv --body point
succeed fitr5-point-m2-l2         -- "${F[@]}" r5_ml80.csv --body point --fit-param m2,l2
succeed fitr5-rod-body            -- "${F[@]}" r5_ml80.csv --body rod --fit-param l2
succeed fitr5-bobs-com2-inertia2  -- "${F[@]}" r5_ml80.csv --com 0.5,0.4 --inertia 0.08,0.03 \
    --fit-param com2,inertia2
# ---- refusals
refuse  fitr5-point-mass-scale 'fit parameters' -- "${F[@]}" r5_ml80.csv --body point \
    --fit-param m1,m2
refuse  fitr5-point-mass-all   'fit parameters' -- "${F[@]}" r5_ml80.csv --body point --fit-param m
refuse  fitr5-bobs-l2-angles   'fit parameters' -- "${F[@]}" r5_ml80.csv --com 0.5,0.4 \
    --inertia 0.08,0.03 --fit-param l2
refuse  fitr5-body-name        body      -- "${F[@]}" r5_ml80.csv --body stick
refuse  fitr5-body-empty       body      -- "${F[@]}" r5_ml80.csv --body ''
refuse  fitr5-body-missing     body      -- "${F[@]}" r5_ml80.csv --body
refuse  fitr5-body-point-com   body      -- "${F[@]}" r5_ml80.csv --body point --com 1,1
refuse  fitr5-body-rod-inertia body      -- "${F[@]}" r5_ml80.csv --body rod --inertia 0.1,0.1
refuse  fitr5-com-negative     com1      -- "${F[@]}" r5_ml80.csv --com -0.1,0.5
refuse  fitr5-com-count        com       -- "${F[@]}" r5_ml80.csv --com 0.5
refuse  fitr5-com-nan          com       -- "${F[@]}" r5_ml80.csv --com nan,0.5
refuse  fitr5-inertia-text     inertia   -- "${F[@]}" r5_ml80.csv --inertia 0.1,abc
refuse  fitr5-inertia-negative inertia2  -- "${F[@]}" r5_ml80.csv --inertia 0.1,-1
refuse  fitr5-bob-l-zero       l1        -- "${B[@]}" --l 0 --fit-param l
