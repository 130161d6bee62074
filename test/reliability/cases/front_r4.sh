# Round 4, front end (issue 25): the remaining contradictions (a fixed value with an
# axis that sweeps it, save_every with output_dt, grid settings with a list, a stop
# rule with an indicator), horizons in both units, progress without a terminal,
# summaries with the largest error and a verdict, export of a sweep in long form.
# Runs are tiny in case one is not refused.

_fr4=$FIXTURES
printf '&initial q1 = 0.3 /\n' > "$_fr4/fr4_q1.nml"
printf '&initial w2 = 0.1 /\n' > "$_fr4/fr4_w2.nml"
printf '&pendulum m2 = 2 /\n' > "$_fr4/fr4_m2.nml"
printf '&integration output_dt = 0.01 /\n' > "$_fr4/fr4_odt.nml"
printf '&integration save_every = 3 /\n' > "$_fr4/fr4_se.nml"
printf '&integration save_every = 3, output_dt = 0.01, t_end = 0.1 /\n' > "$_fr4/fr4_both.nml"
printf '&sweep min1 = 0 /\n' > "$_fr4/fr4_min1.nml"
printf "&sweep stop_at = 'either' /\n" > "$_fr4/fr4_stop.nml"
printf '0.1,0.2,0,0\n0.3,0.4,0,0\n' > "$_fr4/fr4_list.csv"

W=(sweep --output s.h5 --n 2 --t-end 0.5 --quiet)
# ---- a fixed initial value or parameter and an axis that sweeps it, either order
refuse  fr4-theta1-axis1      '--theta1: axis1'   -- "${W[@]}" --theta1 3.0 --axis1 theta1
refuse  fr4-axis1-theta1      '--theta1: axis1'   -- "${W[@]}" --axis1 theta1 --theta1 3.0
refuse  fr4-q1-axis-theta1    '--q1: axis1'       -- "${W[@]}" --q1 0.5 --axis1 theta1
refuse  fr4-theta1-axis-q1    '--theta1: axis1'   -- "${W[@]}" --axis1 q1 --theta1 3.0
refuse  fr4-theta2-default    '--theta2: axis2'   -- "${W[@]}" --theta2 1
refuse  fr4-w1-axis1          '--w1: axis1'       -- "${W[@]}" --axis1 w1 --w1 2
refuse  fr4-w2-axis2          '--w2: axis2'       -- "${W[@]}" --w2 2 --axis1 w1 --axis2 w2
refuse  fr4-m2-axis           '--m2: axis1'       -- "${W[@]}" --m2 2 --axis1 m2 --min1 0.5 --max1 2
refuse  fr4-m2-ratio          '--m2: axis2'       -- "${W[@]}" --axis2 m2/m1 --m2 2 --min2 0.5 --max2 2
refuse  fr4-l2-ratio          '--l2: axis1'       -- "${W[@]}" --axis1 l2/l1 --l2 2 --min1 0.5 --max1 2
refuse  fr4-nml-q1-axis       'q1 [&initial]: axis1' -- "${W[@]}" --config fr4_q1.nml
refuse  fr4-nml-w2-axis       'w2 [&initial]: axis2' -- "${W[@]}" --config fr4_w2.nml --axis1 w1 --axis2 w2
refuse  fr4-nml-m2-axis       'm2 [&pendulum]: axis1' -- "${W[@]}" --config fr4_m2.nml --axis1 m2/m1 --min1 0.5 --max1 2
refuse  fr4-elastic-r         '--q1: axis1'       -- "${W[@]}" --model elastic --k 40 --l0 1 --q1 1.2 --axis1 r --axis2 phi --min1 1 --max1 1.5 --indicator megno
succeed fr4-fixed-others-ok      -- "${W[@]}" --axis1 w1 --axis2 w2 --q1 1 --q2 0.5
succeed fr4-theta1-other-axis-ok -- "${W[@]}" --theta1 0.2 --axis1 theta2 --axis2 w2
succeed fr4-m1-ratio-ok          -- "${W[@]}" --m1 2 --axis1 m2/m1 --min1 0.5 --max1 2
succeed fr4-list-holds-swept-ok  -- "${W[@]}" --links 3 --q 0,0,0.5
# ---- save_every with output_dt (simulate: output_dt > 0 would win in any order)
S=(simulate --t-end 0.1 --output o.h5)
refuse  fr4-se-odt            '--output-dt: given with --save-every' -- "${S[@]}" --save-every 3 --output-dt 0.01
refuse  fr4-odt-se            '--output-dt: given with --save-every' -- "${S[@]}" --output-dt 0.01 --save-every 3
refuse  fr4-nml-odt-se        'output_dt [&integration]: given with --save-every' -- "${S[@]}" --config fr4_odt.nml --save-every 3
refuse  fr4-nml-se-odt        '--output-dt: given with save_every [&integration]' -- "${S[@]}" --config fr4_se.nml --output-dt 0.01
refuse  fr4-nml-both          'output_dt [&integration]: given with save_every' -- "${S[@]}" --config fr4_both.nml
succeed fr4-se-same-key-ok       -- "${S[@]}" --config fr4_se.nml --save-every 2
succeed fr4-odt-only-ok          -- "${S[@]}" --output-dt 0.01
# ---- a list of initial conditions with grid settings or fixed initial values
refuse  fr4-list-axis1        '--axis1: given with ic_file' -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --axis1 w1
refuse  fr4-list-max1         '--max1: given with ic_file'  -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --max1 1
refuse  fr4-list-min2         '--min2: given with ic_file'  -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --min2 0
refuse  fr4-list-nml-min1     'min1: given with ic_file'      -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --config fr4_min1.nml
refuse  fr4-list-q1           '--q1: given with ic_file'    -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --q1 1
refuse  fr4-list-theta2       '--theta2: given with ic_file' -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --theta2 1
succeed fr4-list-ok              -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file fr4_list.csv --m2 2
# ---- a stop rule with an indicator or the Lyapunov exponent (they run to t_end)
refuse  fr4-stop-megno        "--stop-at: 'both' given with indicator 'megno'" -- "${W[@]}" --stop-at both --indicator megno
refuse  fr4-megno-stop        "--stop-at: 'either' given with indicator 'megno'" -- "${W[@]}" --indicator megno --stop-at either
refuse  fr4-stop-lyapunov     '--stop-at'         -- "${W[@]}" --lyapunov --stop-at both
refuse  fr4-nml-stop-fli      'stop_at [&sweep]'  -- "${W[@]}" --config fr4_stop.nml --indicator fli
succeed fr4-stop-end-megno-ok    -- "${W[@]}" --indicator megno --stop-at end
succeed fr4-stop-flip-ok         -- "${W[@]}" --stop-at either
# the shipped parameter maps no longer give the m2/l2 their axes replace
succeed fr4-data-mass-length     -- sweep --config sweep_mass_length_megno.nml --n 2 --t-end 0.5 --output s.h5 --quiet
succeed fr4-data-theta1-ratio    -- sweep --config sweep_theta1_mass_ratio.nml --n 2 --t-end 0.5 --output s.h5 --quiet
# ---- horizons in both units (texts: test_messages simulate_summary_line, sweep_horizon)
succeed fr4-horizon-sweep-natural -- sweep --output s.h5 --n 2 --t-end 0.5
succeed fr4-horizon-sweep-s      -- sweep --output s.h5 --n 2 --t-end 0.5 --time-unit s
succeed fr4-horizon-sweep-l1     -- sweep --output s.h5 --n 2 --t-end 0.5 --axis1 l1 --min1 0.5 --max1 2
succeed fr4-horizon-sweep-elastic -- sweep --output s.h5 --n 2 --t-end 0.5 --model elastic --k 40 --l0 1 --q 1.2,-1.0 --axis1 r --axis2 phi --min1 1 --max1 1.5 --indicator megno
succeed fr4-horizon-simulate-elastic -- simulate --output o.h5 --t-end 0.1 --model elastic --k 40 --l0 1 --q 1.2,-1.0
# ---- summaries: the largest energy (balance) error and the final one
succeed fr4-summary-damped       -- simulate --output o.h5 --t-end 0.1 --damping 0.1,0.1
succeed fr4-summary-driven       -- simulate --output o.h5 --t-end 0.1 --support-amplitude 0,0.01 --support-frequency 30
succeed fr4-summary-quiet        -- simulate --output o.h5 --t-end 0.1 --quiet
# ---- indicators end with a verdict (texts: test_messages indicators_verdict)
succeed fr4-verdict-chaotic      -- indicators --output i.h5 --t-end 40
succeed fr4-verdict-regular      -- indicators --output i.h5 --t-end 40 --theta1 1 --theta2 1 --dt 1e-2
succeed fr4-verdict-short        -- indicators --output i.h5 --t-end 1
succeed fr4-verdict-elastic      -- indicators --output i.h5 --t-end 1 --model elastic --k 40 --l0 1 --q 1.2,-1
# ---- export: a sweep's maps in long form (values: test_messages export_sweep_long_form)
succeed fr4-export-long          -- export sweep.h5 --csv t_flip,energy_error
succeed fr4-export-long-words    -- export sweep.h5 --csv t_flip final/q1 status
succeed fr4-export-long-1d       -- export sweep.h5 --csv axis1
succeed fr4-export-wide-plain    -- export sweep.h5 t_flip
refuse  fr4-export-empty-name    DATASET -- export sweep.h5 --csv ,
succeed fr4-export-mixed-columns -- export sweep.h5 --csv t_flip axis1
# ---- texts: every command's --help mentions --quiet (test_messages help_mentions_quiet)
succeed fr4-help-main            -- --help
succeed fr4-help-methods         -- methods --help
succeed fr4-help-models          -- models --help
succeed fr4-help-export          -- export --help
succeed fr4-help-compare         -- sweep-compare --help
succeed fr4-methods-table        -- methods
