# Front end, keys and names: a namelist scalar given two values is
# refused naming the key (every command's pre-scan); typos get a suggestion; names
# are case-insensitive; contradictory flags are refused naming both; --quiet
# everywhere. Runs are tiny in case one is not refused.

_frn=$FIXTURES
printf '&integration\n dt = 0.001 0.002\n/\n' > "$_frn/frn_dt_two.nml"
printf '&integration t_end = 2*0.01 /\n' > "$_frn/frn_t_end_repeat.nml"
printf "&integration method = 'rk4' 'dop853' /\n" > "$_frn/frn_method_two.nml"
printf '&pendulum g = 9.8, 9.81 /\n' > "$_frn/frn_g_two.nml"
printf '&integration t_end = 0.01 /\n&chaos tau = 0.5 0.6 /\n' > "$_frn/frn_chaos_two.nml"
printf '&sweep n1 = 4 8 /\n' > "$_frn/frn_sweep_two.nml"
printf '&study ref_dt = 1e-3 2e-3 /\n' > "$_frn/frn_study_two.nml"
printf "&integration method = 'DOP853', t_end = 0.01 /\n" > "$_frn/frn_method_upper.nml"
printf '&pendulum m = 1 1, damping = 0 0 /\n&initial q = 0.1 0.2, w(1) = 0 0 /\n&integration t_end = 0.01 /\n' \
   > "$_frn/frn_lists_ok.nml"
printf 't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n' > "$_frn/frn_fit.csv"

S=(simulate --t-end 0.01 --output o.h5)
# ---- one value for a key that takes one, in every pre-scan
refuse  frn-nml-dt-two        "key 'dt'"      -- "${S[@]}" --config frn_dt_two.nml
refuse  frn-nml-t-end-repeat  "key 't_end'"   -- "${S[@]}" --config frn_t_end_repeat.nml
refuse  frn-nml-method-two    "key 'method'"  -- "${S[@]}" --config frn_method_two.nml
refuse  frn-nml-g-two         "key 'g'"       -- "${S[@]}" --config frn_g_two.nml
refuse  frn-nml-chaos-two     "key 'tau'"     -- lyapunov --output o.h5 --config frn_chaos_two.nml
refuse  frn-nml-sweep-two     "key 'n1'"      -- sweep --output s.h5 --config frn_sweep_two.nml
refuse  frn-nml-study-two     "key 'ref_dt'"  -- study --output s.md --config frn_study_two.nml
refuse  frn-nml-dt-two-sweep  "key 'dt'"      -- sweep --output s.h5 --config frn_dt_two.nml
succeed frn-nml-lists-ok         -- "${S[@]}" --config frn_lists_ok.nml
# ---- divergence without an exponential phase (the line says why; see
# test_messages divergence_without_slope)
succeed frn-divergence-no-slope  -- divergence --t-end 1 --q1 -1.5 --q2 -1.5 --pairs 2 --lyapunov-t 0 --output d.h5
# ---- a typo gets the nearest name (refusals name it; see test_parse
# names_suggested for the texts)
refuse  frn-typo-t_end        'did you mean --t-end'  -- "${S[@]}" --t_end 1
refuse  frn-typo-tend         'did you mean --t-end'  -- "${S[@]}" --tend 1
refuse  frn-typo-sweep-t_end  'did you mean --t-end'  -- sweep --output s.h5 --t_end 1
refuse  frn-typo-lyapunov-tua 'did you mean --tau'    -- lyapunov --output o.h5 --tua 1
refuse  frn-typo-study-quik   'did you mean --quick'  -- study --output s.md --quik
refuse  frn-typo-animate-fsp  'did you mean --fps'    -- animate existing.h5 --output a.gif --fsp 10
refuse  frn-typo-fit          'did you mean --fit-damping' -- fit frn_fit.csv --output f.h5 --fit_damping
refuse  frn-typo-export-cvs   'did you mean --csv'    -- export existing.h5 --cvs
refuse  frn-typo-methods      'did you mean --names'  -- methods --name
refuse  frn-typo-compare      'did you mean --threshold-a' -- sweep-compare sweep.h5 sweep.h5 --threshold_a 1
refuse  frn-typo-command      'did you mean simulate' -- simulat
refuse  frn-typo-method       'did you mean dopri5'   -- "${S[@]}" --method dopri
refuse  frn-typo-model        'did you mean elastic'  -- "${S[@]}" --model elastc
refuse  frn-typo-indicator    'did you mean megno'    -- sweep --output s.h5 --indicator mgeno
refuse  frn-typo-axis         'did you mean theta1'   -- sweep --output s.h5 --axis1 thta1
refuse  frn-typo-far          'unknown option'        -- "${S[@]}" --x 1
# ---- names without regard to case (results as the lower-case name)
succeed frn-case-method          -- "${S[@]}" --method RK4
succeed frn-case-method-nml      -- "${S[@]}" --config frn_method_upper.nml
succeed frn-case-model           -- "${S[@]}" --model Elastic --k 40 --l0 1 --q 1.2,-1.0
succeed frn-case-indicator       -- sweep --output s.h5 --n 2 --t-end 0.5 --quiet --indicator MEGNO
succeed frn-case-axes            -- sweep --output s.h5 --n 2 --t-end 0.5 --quiet --axis1 Theta1 --axis2 W2
succeed frn-case-lyapunov        -- lyapunov --output o.h5 --t-end 0.5 --method Gauss4
# ---- contradictory flags refused naming both, in either order
refuse  frn-both-theta1-q1    theta1   -- "${S[@]}" --theta1 3.0 --q1 0.5
refuse  frn-both-q1-theta1    theta1   -- "${S[@]}" --q1 0.5 --theta1 3.0
refuse  frn-both-q-q1         q1       -- "${S[@]}" --q 1,2 --q1 0.5
refuse  frn-both-q1-q         q1       -- "${S[@]}" --q1 0.5 --q 1,2
refuse  frn-both-w-w1         w1       -- "${S[@]}" --w 0,0 --w1 1
refuse  frn-both-w1-w         w1       -- "${S[@]}" --w1 1 --w 0,0
refuse  frn-both-m2-m         m2       -- "${S[@]}" --m2 2 --m 1,1
refuse  frn-both-l-l1         l1       -- lyapunov --output o.h5 --l 1,1 --l1 2
refuse  frn-both-o-output     '-o and --output' -- simulate --t-end 0.01 -o a.h5 --output=b.h5
refuse  frn-both-output-o     '-o and --output' -- study --output a.md -o b.md
# ---- every command takes --quiet
succeed frn-quiet-simulate       -- "${S[@]}" --quiet
succeed frn-quiet-lyapunov       -- lyapunov --output o.h5 --t-end 0.5 --quiet
succeed frn-quiet-divergence     -- divergence --output d.h5 --t-end 1 --pairs 2 --lyapunov-t 0 --quiet
succeed frn-quiet-indicators     -- indicators --output i.h5 --t-end 0.5 --quiet
succeed frn-quiet-poincare       -- poincare --output p.h5 --t-end 1 --ics 1 --points 2 --quiet
succeed frn-quiet-export         -- export existing.h5 --list --quiet
succeed frn-quiet-methods        -- methods --quiet
succeed frn-quiet-models         -- models --quiet
succeed frn-quiet-compare        -- sweep-compare sweep.h5 sweep.h5 --quiet
succeed frn-quiet-fit            -- fit frn_fit.csv --output f.h5 --quiet
refuse  frn-quiet-twice          quiet    -- "${S[@]}" --quiet --quiet
succeed frn-quiet-animate        -- animate existing.h5 --output a.gif --quiet
