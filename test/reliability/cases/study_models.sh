# dpend study on a model other than the pendulum: the
# elastic pendulum through &model (data/elastic_study.nml), and the refusals of what
# such a case cannot have. The study's roundoff runs need H in quadruple precision
# (the double pendulum's alone): on the elastic pendulum they are left out.
S=(--quick --no-figures --cases small --methods rk4,verlet,gauss8 --threads 1)
M="&model\n name = 'elastic', k = 40, l0 = 1\n/\n"
printf "$M&study case_name(1) = 'a', case_q1(1) = 1.3, case_q2(1) = -1.4,\n case_damping(1:2, 1) = 0.1, 0.1 /\n" \
  > "$FIXTURES/study_el_damped.nml"
# the pendulum's lengths are no parameter of the elastic pendulum (its mass and g
# are: &pendulum m1 or --m1 is the bob's mass, as in simulate)
printf "$M&pendulum l1 = 2 /\n&study case_name(1) = 'a', case_q1(1) = 1.3 /\n" \
  > "$FIXTURES/study_el_pendulum.nml"
printf "$M&study case_name(1) = 'a', case_q1(1) = 0, case_q2(1) = -1.4 /\n" \
  > "$FIXTURES/study_el_r_zero.nml"
printf "$M&study case_name(1) = 'a', case_links(1) = 3, case_q(1:3, 1) = 1.3, -1.4, 0 /\n" \
  > "$FIXTURES/study_el_links.nml"
printf "&model\n name = 'elastic', k = -4\n/\n&study case_name(1) = 'a', case_q1(1) = 1.3 /\n" \
  > "$FIXTURES/study_el_k.nml"

succeed std-elastic                    -- study --config data/elastic_study.nml "${S[@]}" --output o/s.h5
refuse  std-elastic-damped  case_damping -- study --config study_el_damped.nml --output o/s.h5
refuse  std-elastic-pendulum pendulum  -- study --config study_el_pendulum.nml --output o/s.h5
refuse  std-elastic-flag    pendulum   -- study --config data/elastic_study.nml --l1 2 --output o/s.h5
refuse  std-elastic-r-zero  q1         -- study --config study_el_r_zero.nml --output o/s.h5
refuse  std-elastic-links   case_links -- study --config study_el_links.nml --output o/s.h5
refuse  std-elastic-k       k          -- study --config study_el_k.nml --output o/s.h5
# the study's check tolerance within what double precision honours (1e-300 trapped in
# dop853: fuzz seed 20261129)
printf "&study case_name(1)='a', case_q1(1)=0.1, case_q2(1)=0.1, order_case='a', drift_case='a', ro_case='a', tao_case='a', check_rtol = 1e-300 /\n" > "$FIXTURES/std_check_rtol.nml"
refuse  std-check-rtol      check_rtol -- study --config std_check_rtol.nml --no-figures --output o/s.h5
# a list longer than any case's links would be dropped without a word: refused
refuse  study-list-longer-than-cases 'invalid l: 3 values, but the cases have at most 2 links' -- \
    study --quick --no-figures --output st.h5 --l 1,1,1
