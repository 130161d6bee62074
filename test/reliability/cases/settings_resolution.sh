# One resolution of every setting: a quantity given in two groups of one file is
# refused naming both; the flags override the file whatever group gave it (&model or
# &pendulum); a setting the model or the command has no use for is refused, never
# dropped (the pendulum's flags for the elastic pendulum; the body, damping and
# support of &pendulum in a study, whose cases carry their own).

_set=$FIXTURES
printf "&model name='pendulum', m = 2, 3 /\n" > "$_set/set_model_m.nml"
printf "&model name='pendulum', m = 2, 3 /\n&pendulum m1 = 2 /\n" > "$_set/set_m_twice.nml"
printf "&model name='pendulum', g = 3 /\n&pendulum g = 2 /\n" > "$_set/set_g_twice.nml"
printf "&model name='pendulum', com = 0.5, 0.5 /\n&pendulum com = 0.4, 0.4 /\n" > "$_set/set_com_twice.nml"
printf "&model links = 3 /\n" > "$_set/set_links3.nml"
printf "&model name='elastic', k = 40, l0 = 1 /\n&pendulum support_frequency = 2 /\n&initial q = 1.2, -1 /\n" > "$_set/set_el_support.nml"
_study="&study case_name(1)='a', case_q1(1)=0.1, case_q2(1)=0.1, method(1)='rk4', order_case='a', drift_case='a', ro_case='a', tao_case='a' /"
printf "%s\n&pendulum body = 'point' /\n" "$_study" > "$_set/set_st_body.nml"
printf "%s\n&pendulum damping = 0.1, 0.1 /\n" "$_study" > "$_set/set_st_damping.nml"
printf "%s\n&pendulum com = 0.5, 0.5 /\n" "$_study" > "$_set/set_st_com.nml"
printf "%s\n&model com = 0.5, 0.5 /\n" "$_study" > "$_set/set_st_model_com.nml"
printf "%s\n&pendulum support_amplitude = 0.1, 0 /\n" "$_study" > "$_set/set_st_support.nml"

S=(simulate --t-end 0.1 --output o.h5)
# ---- two groups of one file giving one quantity
refuse  set-m-two-groups      'm is given in &model and as m1 in &pendulum' -- "${S[@]}" --config set_m_twice.nml
refuse  set-g-two-groups      'g is given in &model and as g in &pendulum'  -- "${S[@]}" --config set_g_twice.nml
refuse  set-com-two-groups    'com is given in &model and as com in &pendulum' -- "${S[@]}" --config set_com_twice.nml
refuse  set-sweep-m-two       'm is given in &model' -- sweep --output s.h5 --n 2 --t-end 0.5 --quiet --config set_m_twice.nml
# ---- &model's fields are the run's: flags override them; links = 3 is three links
succeed set-model-m-flags-ok  -- "${S[@]}" --config set_model_m.nml --m 4,5
succeed set-model-links3-ok   -- "${S[@]}" --config set_links3.nml
succeed set-model-m-sweep-ok  -- sweep --output s.h5 --n 2 --t-end 0.5 --quiet --config set_model_m.nml
# ---- the pendulum's settings for the elastic pendulum
E=(simulate --model elastic --q 1.2,-1 --t-end 0.1 --output e.h5)
refuse  set-el-l1             'invalid l1: not a parameter of model elastic'  -- "${E[@]}" --l1 2
refuse  set-el-m2             'invalid m2: not a parameter of model elastic'  -- "${E[@]}" --m2 3
refuse  set-el-support-freq   'invalid support_frequency: not a parameter'    -- "${E[@]}" --support-frequency 3
refuse  set-el-support-phase  'invalid support_phase: not a parameter'        -- "${E[@]}" --support-phase 1,1
refuse  set-el-theta          'invalid theta1: not a parameter of model elastic' -- simulate --model elastic --theta1 2 --theta2 0 --t-end 0.1 --output e.h5
refuse  set-el-nml-support    'invalid support_frequency: not a parameter'    -- simulate --config set_el_support.nml --t-end 0.1 --output e.h5
refuse  set-el-lyapunov-l1    'invalid l1: not a parameter of model elastic'  -- lyapunov --model elastic --q 1.2,-1 --l1 2 --t-end 1 --output l.h5
succeed set-el-m1-ok          -- "${E[@]}" --m1 2
# ---- the study's &pendulum: only m, l, g (the cases carry damping and support)
T=(study --quick --no-figures --output st.h5)
refuse  set-study-body        'body is not a setting of dpend study'           -- "${T[@]}" --config set_st_body.nml
refuse  set-study-damping     'damping is not a setting of &pendulum in dpend study' -- "${T[@]}" --config set_st_damping.nml
refuse  set-study-com         "com is not a setting of dpend study's pendulum" -- "${T[@]}" --config set_st_com.nml
refuse  set-study-model-com   "com is not a setting of dpend study's pendulum" -- "${T[@]}" --config set_st_model_com.nml
refuse  set-study-support     'support_amplitude is not a setting of &pendulum in dpend study' -- "${T[@]}" --config set_st_support.nml
# ---- &model values the model cannot take stay the factory's to refuse, named
printf "&model name='elastic', links = 2 /\n&study case_name(1)='a', case_q1(1)=1.3, case_q2(1)=-1.4, order_case='a', drift_case='a', ro_case='a', tao_case='a' /\n" > "$_set/set_st_el_links.nml"
printf "&model name='elastic', m = 1, 2 /\n&initial q = 1.2, -1 /\n" > "$_set/set_el_m2.nml"
refuse  set-study-el-links    'links is not a parameter of model elastic'  -- "${T[@]}" --config set_st_el_links.nml
refuse  set-el-model-m-count  'invalid m'                                    -- "${S[@]}" --config set_el_m2.nml
refuse  set-el-axis-m-given   "invalid m: axis2 'm' sweeps the value it fixes" -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --m1 2 --axis1 r --axis2 m --min1 1 --max1 1.4 --min2 0.5 --max2 2 --n 2 --t-end 0.5 --indicator megno
