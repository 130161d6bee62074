# Round 3, front end (issues 23 and 25): a namelist scalar given two values is
# refused naming the key (every command's pre-scan); typos get a suggestion; names
# are case-insensitive; contradictory flags are refused naming both; --quiet
# everywhere. Runs are tiny in case one is not refused.

_fr3=$FIXTURES
printf '&integration\n dt = 0.001 0.002\n/\n' > "$_fr3/fr3_dt_two.nml"
printf '&integration t_end = 2*0.01 /\n' > "$_fr3/fr3_t_end_repeat.nml"
printf "&integration method = 'rk4' 'dop853' /\n" > "$_fr3/fr3_method_two.nml"
printf '&pendulum g = 9.8, 9.81 /\n' > "$_fr3/fr3_g_two.nml"
printf '&integration t_end = 0.01 /\n&chaos tau = 0.5 0.6 /\n' > "$_fr3/fr3_chaos_two.nml"
printf '&sweep n1 = 4 8 /\n' > "$_fr3/fr3_sweep_two.nml"
printf '&study ref_dt = 1e-3 2e-3 /\n' > "$_fr3/fr3_study_two.nml"
printf '&pendulum m = 1 1, damping = 0 0 /\n&initial q = 0.1 0.2, w(1) = 0 0 /\n&integration t_end = 0.01 /\n' \
   > "$_fr3/fr3_lists_ok.nml"

S=(simulate --t-end 0.01 --output o.h5)
# ---- issue 23: one value for a key that takes one, in every pre-scan
refuse  fr3-nml-dt-two        "key 'dt'"      -- "${S[@]}" --config fr3_dt_two.nml
refuse  fr3-nml-t-end-repeat  "key 't_end'"   -- "${S[@]}" --config fr3_t_end_repeat.nml
refuse  fr3-nml-method-two    "key 'method'"  -- "${S[@]}" --config fr3_method_two.nml
refuse  fr3-nml-g-two         "key 'g'"       -- "${S[@]}" --config fr3_g_two.nml
refuse  fr3-nml-chaos-two     "key 'tau'"     -- lyapunov --output o.h5 --config fr3_chaos_two.nml
refuse  fr3-nml-sweep-two     "key 'n1'"      -- sweep --output s.h5 --config fr3_sweep_two.nml
refuse  fr3-nml-study-two     "key 'ref_dt'"  -- study --output s.md --config fr3_study_two.nml
refuse  fr3-nml-dt-two-sweep  "key 'dt'"      -- sweep --output s.h5 --config fr3_dt_two.nml
succeed fr3-nml-lists-ok         -- "${S[@]}" --config fr3_lists_ok.nml
# ---- issue 23: divergence without an exponential phase (the line says why; see
# test_messages divergence_without_slope)
succeed fr3-divergence-no-slope  -- divergence --t-end 1 --q1 -1.5 --q2 -1.5 --pairs 2 --lyapunov-t 0 --output d.h5
