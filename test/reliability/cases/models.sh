# The model factory and the elastic pendulum: --model, parameters by name,
# the &model group, the model's own check of the initial state, and the commands that
# do not take other models yet refusing in one line.
E=(--model elastic --m 1 --k 40 --l0 1 --g 9.8 --q 1.2,-1.0 --w 0,0 --t-end 0.5)
B=(--model elastic --l0 1 --w 0,0 --t-end 0.5)   # the rows below add what they test
printf "&model\n name = 'elastic'\n k = 40, l0 = 1\n/\n&initial\n q = 1.2, -1.0\n/\n" \
  > "$FIXTURES/elastic_ok.nml"
printf "&model\n name = 'elastic'\n kk = 3\n/\n" > "$FIXTURES/model_badkey.nml"
printf "&model\n name = 'elastic', k = 1;2\n/\n" > "$FIXTURES/model_badnum.nml"
printf "&model\n name = 'elastic', k = 4, k = 5\n/\n" > "$FIXTURES/model_twice.nml"
printf "&model\n name = 'nope'\n/\n" > "$FIXTURES/model_unknown.nml"

succeed mod-models                    -- models
refuse  mod-models-arg      argument  -- models --links
succeed mod-elastic                   -- simulate "${E[@]}" --output e.h5
succeed mod-elastic-nml               -- simulate --config elastic_ok.nml --t-end 0.5 --output e.h5
succeed mod-elastic-lyap              -- lyapunov "${E[@]}" --output e.h5
succeed mod-elastic-ind               -- indicators "${E[@]}" --output e.h5
succeed mod-elastic-div               -- divergence "${E[@]}" --output e.h5
refuse  mod-unknown         model     -- simulate --model nope --output x.h5
refuse  mod-unknown-nml     model     -- simulate --config model_unknown.nml --output x.h5
refuse  mod-pendulum-k      k         -- simulate --k 3 --output x.h5
refuse  mod-elastic-links   links     -- simulate "${E[@]}" --links 3 --output x.h5
refuse  mod-elastic-damping damping   -- simulate "${E[@]}" --damping 0.1,0.1 --output x.h5
refuse  mod-elastic-k0      k         -- simulate "${B[@]}" --q 1.2,-1 --k 0 --output x.h5
refuse  mod-elastic-k-tab   k         -- simulate "${B[@]}" --q 1.2,-1 --k "$(printf '4\t0')" --output x.h5
refuse  mod-elastic-g0      g         -- simulate "${B[@]}" --q 1.2,-1 --g 0 --output x.h5
refuse  mod-elastic-m2      m         -- simulate "${B[@]}" --q 1.2,-1 --m 1,2 --output x.h5
refuse  mod-elastic-r0      q1        -- simulate --model elastic --k 40 --l0 1 --q 0,-1 --output x.h5
refuse  mod-repeated-k      k         -- simulate "${E[@]}" --k 30 --output x.h5
refuse  mod-elastic-q3      q         -- simulate "${B[@]}" --q 1,-1,0 --output x.h5
refuse  mod-elastic-badkey  config    -- simulate --config model_badkey.nml --output x.h5
refuse  mod-elastic-badnum  config    -- simulate --config model_badnum.nml --output x.h5
refuse  mod-elastic-twice   config    -- simulate --config model_twice.nml --output x.h5
refuse  mod-elastic-sweep   model     -- sweep "${E[@]}" --n 4 --output x.h5
# (mod-elastic-fit: dpend fit takes the elastic pendulum; its rows: fit_models.sh)
refuse  mod-elastic-poinc   poincare  -- poincare "${E[@]}" --output x.h5
