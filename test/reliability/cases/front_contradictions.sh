# Front end, contradictions and summaries: the remaining contradictions (a fixed
# value with an axis that sweeps it, save_every with output_dt, grid settings with a
# list, a stop rule with an indicator), horizons in both units, progress without a
# terminal, summaries with the largest error and a verdict, export of a sweep in long
# form. Runs are tiny in case one is not refused.

_frc=$FIXTURES
printf '&initial q1 = 0.3 /\n' > "$_frc/frc_q1.nml"
printf '&initial w2 = 0.1 /\n' > "$_frc/frc_w2.nml"
printf '&pendulum m2 = 2 /\n' > "$_frc/frc_m2.nml"
printf '&integration output_dt = 0.01 /\n' > "$_frc/frc_odt.nml"
printf '&integration save_every = 3 /\n' > "$_frc/frc_se.nml"
printf '&integration save_every = 3, output_dt = 0.01, t_end = 0.1 /\n' > "$_frc/frc_both.nml"
printf '&sweep min1 = 0 /\n' > "$_frc/frc_min1.nml"
printf "&sweep stop_at = 'either' /\n" > "$_frc/frc_stop.nml"
printf '0.1,0.2,0,0\n0.3,0.4,0,0\n' > "$_frc/frc_list.csv"

W=(sweep --output s.h5 --n 2 --t-end 0.5 --quiet)
# ---- a fixed initial value or parameter and an axis that sweeps it, either order
refuse  frc-theta1-axis1      '--theta1: axis1'   -- "${W[@]}" --theta1 3.0 --axis1 theta1
refuse  frc-axis1-theta1      '--theta1: axis1'   -- "${W[@]}" --axis1 theta1 --theta1 3.0
refuse  frc-q1-axis-theta1    '--q1: axis1'       -- "${W[@]}" --q1 0.5 --axis1 theta1
refuse  frc-theta1-axis-q1    '--theta1: axis1'   -- "${W[@]}" --axis1 q1 --theta1 3.0
refuse  frc-theta2-default    '--theta2: axis2'   -- "${W[@]}" --theta2 1
refuse  frc-w1-axis1          '--w1: axis1'       -- "${W[@]}" --axis1 w1 --w1 2
refuse  frc-w2-axis2          '--w2: axis2'       -- "${W[@]}" --w2 2 --axis1 w1 --axis2 w2
refuse  frc-m2-axis           '--m2: axis1'       -- "${W[@]}" --m2 2 --axis1 m2 --min1 0.5 --max1 2
refuse  frc-m2-ratio          '--m2: axis2'       -- "${W[@]}" --axis2 m2/m1 --m2 2 --min2 0.5 --max2 2
refuse  frc-l2-ratio          '--l2: axis1'       -- "${W[@]}" --axis1 l2/l1 --l2 2 --min1 0.5 --max1 2
refuse  frc-nml-q1-axis       'q1 [&initial]: axis1' -- "${W[@]}" --config frc_q1.nml
refuse  frc-nml-w2-axis       'w2 [&initial]: axis2' -- "${W[@]}" --config frc_w2.nml --axis1 w1 --axis2 w2
refuse  frc-nml-m2-axis       'm2 [&pendulum]: axis1' -- "${W[@]}" --config frc_m2.nml --axis1 m2/m1 --min1 0.5 --max1 2
refuse  frc-elastic-r         '--q1: axis1'       -- "${W[@]}" --model elastic --k 40 --l0 1 --q1 1.2 --axis1 r --axis2 phi --min1 1 --max1 1.5 --indicator megno
succeed frc-fixed-others-ok      -- "${W[@]}" --axis1 w1 --axis2 w2 --q1 1 --q2 0.5
succeed frc-theta1-other-axis-ok -- "${W[@]}" --theta1 0.2 --axis1 theta2 --axis2 w2
succeed frc-m1-ratio-ok          -- "${W[@]}" --m1 2 --axis1 m2/m1 --min1 0.5 --max1 2
succeed frc-list-holds-swept-ok  -- "${W[@]}" --links 3 --q 0,0,0.5
# ---- save_every with output_dt (simulate: output_dt > 0 would win in any order)
S=(simulate --t-end 0.1 --output o.h5)
refuse  frc-se-odt            '--output-dt: given with --save-every' -- "${S[@]}" --save-every 3 --output-dt 0.01
refuse  frc-odt-se            '--output-dt: given with --save-every' -- "${S[@]}" --output-dt 0.01 --save-every 3
refuse  frc-nml-odt-se        'output_dt [&integration]: given with --save-every' -- "${S[@]}" --config frc_odt.nml --save-every 3
refuse  frc-nml-se-odt        '--output-dt: given with save_every [&integration]' -- "${S[@]}" --config frc_se.nml --output-dt 0.01
refuse  frc-nml-both          'output_dt [&integration]: given with save_every' -- "${S[@]}" --config frc_both.nml
succeed frc-se-same-key-ok       -- "${S[@]}" --config frc_se.nml --save-every 2
succeed frc-odt-only-ok          -- "${S[@]}" --output-dt 0.01
# ---- a list of initial conditions with grid settings or fixed initial values
refuse  frc-list-axis1        '--axis1: given with ic_file' -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --axis1 w1
refuse  frc-list-max1         '--max1: given with ic_file'  -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --max1 1
refuse  frc-list-min2         '--min2: given with ic_file'  -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --min2 0
refuse  frc-list-nml-min1     'min1: given with ic_file'      -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --config frc_min1.nml
refuse  frc-list-q1           '--q1: given with ic_file'    -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --q1 1
refuse  frc-list-theta2       '--theta2: given with ic_file' -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --theta2 1
succeed frc-list-ok              -- sweep --output s.h5 --quiet --t-end 0.5 --ic-file frc_list.csv --m2 2
# ---- a stop rule with an indicator or the Lyapunov exponent (they run to t_end)
refuse  frc-stop-megno        "--stop-at: 'both' given with indicator 'megno'" -- "${W[@]}" --stop-at both --indicator megno
refuse  frc-megno-stop        "--stop-at: 'either' given with indicator 'megno'" -- "${W[@]}" --indicator megno --stop-at either
refuse  frc-stop-lyapunov     '--stop-at'         -- "${W[@]}" --lyapunov --stop-at both
refuse  frc-nml-stop-fli      'stop_at [&sweep]'  -- "${W[@]}" --config frc_stop.nml --indicator fli
succeed frc-stop-end-megno-ok    -- "${W[@]}" --indicator megno --stop-at end
succeed frc-stop-flip-ok         -- "${W[@]}" --stop-at either
# the shipped parameter maps no longer give the m2/l2 their axes replace
succeed frc-data-mass-length     -- sweep --config sweep_mass_length_megno.nml --n 2 --t-end 0.5 --output s.h5 --quiet
succeed frc-data-theta1-ratio    -- sweep --config sweep_theta1_mass_ratio.nml --n 2 --t-end 0.5 --output s.h5 --quiet
# ---- horizons in both units (texts: test_messages simulate_summary_line, sweep_horizon)
succeed frc-horizon-sweep-natural -- sweep --output s.h5 --n 2 --t-end 0.5
succeed frc-horizon-sweep-s      -- sweep --output s.h5 --n 2 --t-end 0.5 --time-unit s
succeed frc-horizon-sweep-l1     -- sweep --output s.h5 --n 2 --t-end 0.5 --axis1 l1 --min1 0.5 --max1 2
succeed frc-horizon-sweep-elastic -- sweep --output s.h5 --n 2 --t-end 0.5 --model elastic --k 40 --l0 1 --q 1.2,-1.0 --axis1 r --axis2 phi --min1 1 --max1 1.5 --indicator megno
succeed frc-horizon-simulate-elastic -- simulate --output o.h5 --t-end 0.1 --model elastic --k 40 --l0 1 --q 1.2,-1.0
# ---- summaries: the largest energy (balance) error and the final one
succeed frc-summary-damped       -- simulate --output o.h5 --t-end 0.1 --damping 0.1,0.1
succeed frc-summary-driven       -- simulate --output o.h5 --t-end 0.1 --support-amplitude 0,0.01 --support-frequency 30
succeed frc-summary-quiet        -- simulate --output o.h5 --t-end 0.1 --quiet
# ---- indicators end with a verdict (texts: test_messages indicators_verdict)
succeed frc-verdict-chaotic      -- indicators --output i.h5 --t-end 40
succeed frc-verdict-regular      -- indicators --output i.h5 --t-end 40 --theta1 1 --theta2 1 --dt 1e-2
succeed frc-verdict-short        -- indicators --output i.h5 --t-end 1
succeed frc-verdict-elastic      -- indicators --output i.h5 --t-end 1 --model elastic --k 40 --l0 1 --q 1.2,-1
# ---- export: a sweep's maps in long form (values: test_messages export_sweep_long_form)
succeed frc-export-long          -- export sweep.h5 --csv t_flip,energy_error
succeed frc-export-long-words    -- export sweep.h5 --csv t_flip final/q1 status
succeed frc-export-long-1d       -- export sweep.h5 --csv axis1
succeed frc-export-wide-plain    -- export sweep.h5 t_flip
refuse  frc-export-empty-name    DATASET -- export sweep.h5 --csv ,
succeed frc-export-mixed-columns -- export sweep.h5 --csv t_flip axis1
# ---- texts: every command's --help mentions --quiet (test_messages help_mentions_quiet)
succeed frc-help-main            -- --help
succeed frc-help-methods         -- methods --help
succeed frc-help-models          -- models --help
succeed frc-help-export          -- export --help
succeed frc-help-compare         -- sweep-compare --help
succeed frc-methods-table        -- methods
