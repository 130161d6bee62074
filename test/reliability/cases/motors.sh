# Pendulums with motors. `dpend simulate --torque-file`: torque files refused with
# their line numbers (gaps, NaN, times not increasing, too short, a span that leaves the
# run, wrong columns and units, values beyond the limit), the option refused where it
# does not belong; Coulomb joint friction (--coulomb, --coulomb-speed) out of range or
# of the wrong count; the motors (--rotor-inertia, --gear-ratio) out of range, of the
# wrong count or a gear ratio without a rotor; the chaos commands' torque files; each
# in one line naming the field, exit 2, no file touched; and edge values that must
# succeed without a trap in the debug build.

# fixtures: CSV files, good and bad (each row's problem in its name)
fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
fx tau_ok.csv          't [s],tau1 [N m],tau2 [N m]\n0,0.5,-0.2\n0.5,0.4,0.1\n1,0,0\n'
fx tau_ok_units.csv    '# no units, semicolons\nt;tau2;tau1\n-1;0;1\n2;1;0\n'
fx tau_one_link.csv    't,tau1\n0,1\n1,1\n'
fx tau_gap.csv         't,tau1,tau2\n0,0.5,-0.2\n0.5,,0.1\n1,0,0\n'
fx tau_nan.csv         't,tau1,tau2\n0,0.5,-0.2\n0.5,NaN,0.1\n1,0,0\n'
fx tau_inf.csv         't,tau1,tau2\n0,0.5,-0.2\n0.5,inf,0.1\n1,0,0\n'
fx tau_time_nan.csv    't,tau1,tau2\n0,0.5,-0.2\nnan,0.4,0.1\n1,0,0\n'
fx tau_back.csv        't,tau1,tau2\n0,0.5,-0.2\n0.7,0.4,0.1\n0.6,0,0\n1,0,0\n'
fx tau_repeat.csv      't,tau1,tau2\n0,0.5,-0.2\n0.5,0.4,0.1\n0.5,0,0\n1,0,0\n'
fx tau_one_row.csv     't,tau1,tau2\n0,0.5,-0.2\n'
fx tau_header_only.csv 't,tau1,tau2\n'
fx tau_empty.csv       ''
fx tau_late.csv        't,tau1,tau2\n0.1,0.5,-0.2\n1,0,0\n'
fx tau_short.csv       't,tau1,tau2\n0,0.5,-0.2\n0.5,0,0\n'
fx tau_missing.csv     't,tau1\n0,0.5\n1,0\n'
fx tau_no_t.csv        'time,tau1,tau2\n0,0.5,-0.2\n1,0,0\n'
fx tau_angles.csv      't,theta1,theta2\n0,0.5,-0.2\n1,0,0\n'
fx tau_unit.csv        't,tau1 [N cm],tau2\n0,0.5,-0.2\n1,0,0\n'
fx tau_big.csv         't,tau1,tau2\n0,0.5,-0.2\n1,2e6,0\n'
fx tau_word.csv        't,tau1,tau2\n0,0.5,-0.2\n1,zero,0\n'
fx tau_short_row.csv   't,tau1,tau2\n0,0.5,-0.2\n1,0\n'
fx tau_utf16.csv       '\377\376t\000,\000t\000'
fx coulomb.nml         '&model\n coulomb = 0.5, 0.2\n coulomb_speed = 0.01\n/\n'
fx tau_fit_data.csv     't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
fx motors.nml          '&model\n rotor_inertia = 0.01, 0.002\n gear_ratio = 5, 20\n/\n'
fx tau_long.csv        't,tau1,tau2\n0,0.5,-0.2\n3000,0.4,0.1\n'
fx tau_three.csv       't,tau1,tau2,tau3\n0,0.5,-0.2,0.1\n2,0.4,0.1,0\n'

S=(simulate --t-end 1 --output g.h5)
# ---- the torque file
refuse  torque-missing-file    'no such file'       -- "${S[@]}" --torque-file nosuch.csv
refuse  torque-directory       'directory'          -- "${S[@]}" --torque-file dir
refuse  torque-empty-path      'empty path'         -- "${S[@]}" --torque-file ''
refuse  torque-twice           'given twice'        -- "${S[@]}" --torque-file tau_ok.csv --torque-file tau_ok.csv
refuse  torque-no-value        'needs a value'      -- "${S[@]}" --torque-file
refuse  torque-gap             'line 3'             -- "${S[@]}" --torque-file tau_gap.csv
refuse  torque-nan             'line 3'             -- "${S[@]}" --torque-file tau_nan.csv
refuse  torque-inf             'line 3'             -- "${S[@]}" --torque-file tau_inf.csv
refuse  torque-time-nan        'line 3'             -- "${S[@]}" --torque-file tau_time_nan.csv
refuse  torque-back            'line 4'             -- "${S[@]}" --torque-file tau_back.csv
refuse  torque-repeat          'line 4'             -- "${S[@]}" --torque-file tau_repeat.csv
refuse  torque-one-row         'at least 2'         -- "${S[@]}" --torque-file tau_one_row.csv
refuse  torque-header-only     'no data rows'       -- "${S[@]}" --torque-file tau_header_only.csv
refuse  torque-empty           'no header'          -- "${S[@]}" --torque-file tau_empty.csv
refuse  torque-starts-late     'not extrapolated'   -- "${S[@]}" --torque-file tau_late.csv
refuse  torque-ends-early      'not extrapolated'   -- "${S[@]}" --torque-file tau_short.csv
refuse  torque-missing-column  'missing column tau2' -- "${S[@]}" --torque-file tau_missing.csv
refuse  torque-no-t            "column 't'"         -- "${S[@]}" --torque-file tau_no_t.csv
refuse  torque-angles          'no columns tau1'    -- "${S[@]}" --torque-file tau_angles.csv
refuse  torque-unit            "unit '[n cm]'"      -- "${S[@]}" --torque-file tau_unit.csv
refuse  torque-big             'line 3'             -- "${S[@]}" --torque-file tau_big.csv
refuse  torque-word            'line 3'             -- "${S[@]}" --torque-file tau_word.csv
refuse  torque-short-row       'line 3'             -- "${S[@]}" --torque-file tau_short_row.csv
refuse  torque-utf16           'UTF-16'             -- "${S[@]}" --torque-file tau_utf16.csv
refuse  torque-links           'missing column tau3' -- "${S[@]}" --links 3 --torque-file tau_ok.csv
refuse  torque-elastic         'no joints'          -- "${S[@]}" --model elastic --torque-file tau_ok.csv
refuse  torque-hamiltonian     'torque'             -- "${S[@]}" --method verlet --torque-file tau_ok.csv
# 4 sqrt(l1/g) = 1.28 s: beyond the series' 1 s (1 sqrt(l1/g) = 0.32 s is within)
refuse  torque-natural-span    'not extrapolated'   -- simulate --t-end 4 --time-unit natural --output g.h5 --torque-file tau_ok.csv
succeed torque-ok-natural      -- simulate --t-end 1 --time-unit natural --output g.h5 --torque-file tau_ok.csv
# ---- the sweep takes torques (one trajectory at a time, over [0, t_end] of every pixel)
W=(sweep --n 4 --t-end 1 --time-unit s --quiet --output g.h5)
succeed torque-sweep           -- "${W[@]}" --torque-file tau_ok.csv
succeed torque-sweep-natural   -- sweep --n 4 --t-end 3 --time-unit natural --quiet --output g.h5 --torque-file tau_ok.csv
succeed torque-sweep-megno     -- "${W[@]}" --torque-file tau_ok.csv --indicator megno
succeed torque-sweep-param     -- "${W[@]}" --torque-file tau_ok.csv --axis1 m1 --min1 0.5 --max1 2
succeed torque-sweep-named     -- "${W[@]}" --torque-file tau_ok.csv --axis1 g --min1 5 --max1 10
succeed torque-sweep-one-link  -- "${W[@]}" --torque-file tau_one_link.csv --links 1 --axis1 theta1 --axis2 w1
succeed torque-sweep-everything -- "${W[@]}" --torque-file tau_ok.csv --rotor-inertia 0.01,0.01 --coulomb 0.1,0.1 --damping 0.1,0 --support-amplitude 0.01,0 --support-frequency 3
# the default t_end, 100 sqrt(l1/g) = 31.9 s, leaves the series' [0, 1] s (3.2 too)
refuse  torque-sweep-span      'not extrapolated'   -- sweep --n 4 --output g.h5 --torque-file tau_ok.csv
refuse  torque-sweep-span-nat  'spans [0, 1.0222] s' -- sweep --n 4 --t-end 3.2 --time-unit natural --output g.h5 --torque-file tau_ok.csv
refuse  torque-sweep-huge-t    'not extrapolated'   -- sweep --n 4 --t-end 1e300 --time-unit natural --l1 1e6 --output g.h5 --torque-file tau_ok.csv
refuse  torque-sweep-lyapunov  "double pendulum's kernel only" -- "${W[@]}" --torque-file tau_ok.csv --lyapunov
refuse  torque-sweep-lambda1   'indicator: lambda1' -- "${W[@]}" --torque-file tau_ok.csv --indicator lambda1
refuse  torque-sweep-gpu       'two-link pendulum only, without damping' -- "${W[@]}" --torque-file tau_ok.csv --device gpu
refuse  torque-sweep-twice     'given twice'        -- "${W[@]}" --torque-file tau_ok.csv --torque-file tau_ok.csv
refuse  torque-sweep-empty     'an empty path'      -- "${W[@]}" --torque-file ''
refuse  torque-sweep-novalue   'needs a value'      -- "${W[@]}" --torque-file
refuse  torque-sweep-gap       'line 3'             -- "${W[@]}" --torque-file tau_gap.csv
refuse  torque-sweep-nan       'line 3'             -- "${W[@]}" --torque-file tau_nan.csv
refuse  torque-sweep-back      'line 4'             -- "${W[@]}" --torque-file tau_back.csv
refuse  torque-sweep-one-row   'at least 2'              -- "${W[@]}" --torque-file tau_one_row.csv
refuse  torque-sweep-links     'missing column tau3' -- "${W[@]}" --links 3 --torque-file tau_ok.csv
refuse  torque-sweep-elastic   'no joints'          -- "${W[@]}" --model elastic --torque-file tau_ok.csv
refuse  torque-sweep-missing   'no such file'       -- "${W[@]}" --torque-file nosuch.csv
refuse  torque-sweep-output    'an output never replaces an input' -- sweep --n 4 --t-end 1 --time-unit s --quiet --force --output tau_ok.csv --torque-file tau_ok.csv
refuse  torque-sweep-axis      "invalid axis1: 'damping1'" -- "${W[@]}" --damping 0.1,0.1 --axis1 damping1 --min1 0 --max1 1
# ---- where the option does not belong (poincare: conservative; the study's cases), and fit
refuse  torque-poincare        'energy-shell sections' -- poincare --t-end 1 --output g.h5 --torque-file tau_ok.csv
# the study: a case carries its torques (case_torque_file in &study), not a flag
refuse  torque-study           'unknown option'     -- study --torque-file tau_ok.csv
ST="order_case = 'd', drift_case = 'd', ro_case = 'd', tao_case = 'd'"
fx st_tq.nml      "&study\n case_name(1) = 'd', case_q1(1) = 0.3, case_torque_file(1) = 'tau_long.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_short.nml "&study\n case_name(1) = 'd', case_torque_file(1) = 'tau_ok.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_gap.nml  "&study\n case_name(1) = 'd', case_torque_file(1) = 'tau_gap.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_none.nml "&study\n case_name(1) = 'd', case_torque_file(1) = 'nosuch.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_links.nml "&study\n case_name(1) = 'd', case_links(1) = 3, case_torque_file(1) = 'tau_long.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_verlet.nml "&study\n case_name(1) = 'd', case_torque_file(1) = 'tau_long.csv'\n method(1) = 'verlet'\n $ST\n/\n"
fx st_tq_gap_case.nml "&study\n case_name(1) = 'd', case_torque_file(2) = 'tau_long.csv'\n method(1) = 'rk4'\n $ST\n/\n"
fx st_tq_elastic.nml "&model\n name = 'elastic'\n/\n&study\n case_name(1) = 'd', case_q1(1) = 1.2, case_torque_file(1) = 'tau_long.csv'\n method(1) = 'rk4'\n $ST\n/\n"
succeed study-torque           -- study --quick --no-figures --config st_tq.nml --output s.h5
refuse  study-torque-span      'not extrapolated'   -- study --quick --no-figures --config st_tq_short.nml --output s.h5
refuse  study-torque-gap       'line 3'             -- study --quick --no-figures --config st_tq_gap.nml --output s.h5
refuse  study-torque-missing   'no such file'       -- study --quick --no-figures --config st_tq_none.nml --output s.h5
refuse  study-torque-links     'missing column tau3' -- study --quick --no-figures --config st_tq_links.nml --output s.h5
refuse  study-torque-verlet    'needs a Hamiltonian' -- study --quick --no-figures --config st_tq_verlet.nml --output s.h5
refuse  study-torque-no-case   'case_torque_file(2)' -- study --quick --no-figures --config st_tq_gap_case.nml --output s.h5
refuse  study-torque-elastic   'has no joints'      -- study --quick --no-figures --config st_tq_elastic.nml --output s.h5
refuse  study-torque-output    'an output never replaces an input' -- study --quick --no-figures --force --config st_tq.nml --output tau_long.csv
# fit applies torques (the motion a robot's measured torques drove): over the data's times
succeed torque-fit-ok          -- fit --output g.h5 --torque-file tau_ok.csv tau_fit_data.csv
refuse  torque-fit-span        'not extrapolated'   -- fit --output g.h5 --torque-file tau_late.csv tau_fit_data.csv
refuse  torque-fit-twice       'given twice'        -- fit --output g.h5 --torque-file tau_ok.csv --torque-file tau_ok.csv tau_fit_data.csv
refuse  torque-fit-missing     'no such file'       -- fit --output g.h5 --torque-file nosuch.csv tau_fit_data.csv
refuse  torque-fit-output      'input'              -- fit tau_fit_data.csv --torque-file tau_ok.csv --output tau_ok.csv --force
refuse  torque-simulate-output 'input'              -- simulate --t-end 0.5 --torque-file tau_ok.csv --output tau_ok.csv --force
# the chaos commands apply torques over their runs' span
succeed torque-lyapunov-ok     -- lyapunov --t-end 1 --tau 0.5 --output g.h5 --torque-file tau_ok.csv
succeed torque-indicators-ok   -- indicators --t-end 1 --tau 0.5 --output g.h5 --torque-file tau_ok.csv
succeed torque-divergence-ok   -- divergence --t-end 1 --output-dt 0.1 --lyapunov-t 0 --pairs 1 --output g.h5 --torque-file tau_ok.csv
refuse  torque-lyapunov-span   'not extrapolated'   -- lyapunov --t-end 2 --output g.h5 --torque-file tau_ok.csv
refuse  torque-indicators-span 'not extrapolated'   -- indicators --t-end 2 --output g.h5 --torque-file tau_ok.csv
refuse  torque-divergence-lyap 'lyapunov-t 0'       -- divergence --t-end 1 --output-dt 0.1 --pairs 1 --output g.h5 --torque-file tau_ok.csv
refuse  torque-divergence-pairs 'pair_spacing'      -- divergence --t-end 1 --output-dt 0.1 --lyapunov-t 0 --pairs 3 --pair-spacing 1 --output g.h5 --torque-file tau_ok.csv
# pair p runs [(p - 1) pair_spacing, (p - 1) pair_spacing + t_end] of the forced orbit
refuse  torque-divergence-pair-end 'pair_spacing + t_end' -- divergence --t-end 1 --output-dt 0.1 --lyapunov-t 0 --pairs 2 --pair-spacing 0.5 --output g.h5 --torque-file tau_ok.csv
succeed torque-divergence-pair-fits -- divergence --t-end 0.75 --output-dt 0.05 --lyapunov-t 0 --pairs 2 --pair-spacing 0.25 --output g.h5 --torque-file tau_ok.csv
succeed torque-divergence-long -- divergence --t-end 1 --output-dt 0.1 --pairs 2 --pair-spacing 0.5 --lyapunov-t 2 --output g.h5 --torque-file tau_long.csv
refuse  torque-lyapunov-twice  'given twice'        -- lyapunov --t-end 1 --output g.h5 --torque-file tau_ok.csv --torque-file tau_ok.csv
refuse  torque-lyapunov-missing 'no such file'      -- lyapunov --t-end 1 --output g.h5 --torque-file nosuch.csv
refuse  torque-lyapunov-nan    'line 3'             -- lyapunov --t-end 1 --output g.h5 --torque-file tau_nan.csv
refuse  torque-lyapunov-output 'input'              -- lyapunov --t-end 0.5 --torque-file tau_ok.csv --output tau_ok.csv --force
refuse  torque-indicators-verlet 'torque'           -- indicators --t-end 1 --method verlet --output g.h5 --torque-file tau_ok.csv

# edge values that must succeed
succeed torque-ok              -- "${S[@]}" --torque-file tau_ok.csv
succeed torque-ok-order-units  -- "${S[@]}" --torque-file tau_ok_units.csv --method dop853
succeed torque-ok-one-link     -- "${S[@]}" --links 1 --q -1 --torque-file tau_one_link.csv
succeed torque-ok-damped-gauss -- "${S[@]}" --torque-file tau_ok.csv --damping 0.1,0.2 --method gauss6
succeed torque-ok-output-dt    -- "${S[@]}" --torque-file tau_ok.csv --method dopri5 --output-dt 0.1

# ---- Coulomb joint friction
refuse  coulomb-negative       'coulomb c_f1'       -- "${S[@]}" --coulomb -1,0
refuse  coulomb-nan            'coulomb'            -- "${S[@]}" --coulomb nan,0
refuse  coulomb-big            'outside [0, 1e6]'   -- "${S[@]}" --coulomb 0,2e6
refuse  coulomb-count          'one per link (2)'   -- "${S[@]}" --coulomb 0.1
refuse  coulomb-count-links    'one per link (3)'   -- "${S[@]}" --links 3 --coulomb 0.1,0.1
refuse  coulomb-twice          'given twice'        -- "${S[@]}" --coulomb 0.1,0.1 --coulomb 0.2,0.2
refuse  coulomb-speed-zero     'outside [1e-6, 1000]' -- "${S[@]}" --coulomb 0.1,0.1 --coulomb-speed 0
refuse  coulomb-speed-big      'outside [1e-6, 1000]' -- "${S[@]}" --coulomb-speed 1e4
refuse  coulomb-speed-word     'coulomb-speed'      -- "${S[@]}" --coulomb-speed fast
refuse  coulomb-speed-list     'coulomb_speed'      -- "${S[@]}" --coulomb-speed 1,2
refuse  coulomb-underscore     'unknown option'     -- "${S[@]}" --coulomb_speed 0.1
refuse  coulomb-elastic        'not a parameter of model elastic' -- "${S[@]}" --model elastic --coulomb 1
refuse  coulomb-verlet         'Hamiltonian'        -- "${S[@]}" --method verlet --coulomb 0.1,0.1
succeed coulomb-sweep          -- sweep --n 4 --t-end 1 --quiet --output g.h5 --coulomb 0.1,0.1
refuse  coulomb-sweep-count    'one per link (2)'   -- sweep --n 4 --t-end 1 --quiet --output g.h5 --coulomb 0.1
succeed coulomb-ok             -- "${S[@]}" --coulomb 0.5,0.2 --coulomb-speed 0.01 --method dop853
succeed coulomb-ok-config      -- "${S[@]}" --config coulomb.nml
succeed coulomb-ok-zero        -- "${S[@]}" --coulomb 0,0
succeed coulomb-ok-torques     -- "${S[@]}" --torque-file tau_ok.csv --coulomb 0.5,0.2 --method gauss4
succeed coulomb-ok-one-link-rk4 -- "${S[@]}" --links 1 --coulomb 0.3 --coulomb-speed 1e-6 --method rk4

# ---- motors: rotor inertia and gear ratio per joint
refuse  rotor-negative         'rotor_inertia I_r1' -- "${S[@]}" --rotor-inertia -0.1,0
refuse  rotor-nan              "--rotor-inertia: 'nan' is not finite" -- "${S[@]}" --rotor-inertia 0,nan
refuse  rotor-inf              "--rotor-inertia: 'inf' is not finite" -- "${S[@]}" --rotor-inertia inf,0
refuse  rotor-big              'outside [0, 1e6]'   -- "${S[@]}" --rotor-inertia 2e6,0
refuse  rotor-count            'one per link (2)'   -- "${S[@]}" --rotor-inertia 0.1
refuse  rotor-count-links      'one per link (3)'   -- "${S[@]}" --links 3 --rotor-inertia 0.1,0.1
refuse  rotor-twice            'given twice'        -- "${S[@]}" --rotor-inertia 0.1,0.1 --rotor-inertia 0.2,0.2
refuse  rotor-word             'rotor-inertia'      -- "${S[@]}" --rotor-inertia heavy,0
refuse  rotor-trailing         'rotor-inertia'      -- "${S[@]}" --rotor-inertia 0.1x,0
refuse  gear-zero              'gear_ratio g_r1'    -- "${S[@]}" --rotor-inertia 0.1,0.1 --gear-ratio 0,1
refuse  gear-negative          'outside [0.001, 10000]' -- "${S[@]}" --rotor-inertia 0.1,0.1 --gear-ratio 1,-5
refuse  gear-big               'outside [0.001, 10000]' -- "${S[@]}" --rotor-inertia 0.1,0.1 --gear-ratio 1e5,1
refuse  gear-nan               "--gear-ratio: 'nan' is not finite" -- "${S[@]}" --rotor-inertia 0.1,0.1 --gear-ratio 1,nan
refuse  gear-count             'one per link (2)'   -- "${S[@]}" --rotor-inertia 0.1,0.1 --gear-ratio 10
refuse  gear-without-rotor     'without a rotor_inertia' -- "${S[@]}" --gear-ratio 10,10
succeed gear-ok-rotor-zero     -- "${S[@]}" --rotor-inertia 0,0 --gear-ratio 10,10
refuse  rotor-sweep-lyapunov   "double pendulum's kernel only" -- sweep --n 4 --lyapunov --output g.h5 --rotor-inertia 0.1,0.1
refuse  rotor-sweep-lambda1    'indicator: lambda1'  -- sweep --n 4 --indicator lambda1 --output g.h5 --rotor-inertia 0.1,0.1
refuse  reflected-big          'times gear_ratio'   -- "${S[@]}" --rotor-inertia 1e5,0 --gear-ratio 1e4,1
refuse  rotor-elastic          'not a parameter of model elastic' -- "${S[@]}" --model elastic --rotor-inertia 1
refuse  rotor-underscore       'unknown option'     -- "${S[@]}" --rotor_inertia 0.1,0.1
refuse  rotor-poincare         'energy-shell sections' -- poincare --t-end 1 --output g.h5 --rotor-inertia 0.1,0.1
refuse  rotor-sweep-gpu        'motors or torques'   -- sweep --n 4 --device gpu --output g.h5 --rotor-inertia 0.1,0.1
refuse  rotor-sweep-axis       'the motors are not axes' -- sweep --n 4 --axis1 rotor_inertia1 --output g.h5 --rotor-inertia 0.1,0.1
succeed rotor-ok               -- "${S[@]}" --rotor-inertia 0.01,0.002 --gear-ratio 5,20 --method dop853
succeed rotor-ok-config        -- "${S[@]}" --config motors.nml
succeed rotor-ok-zero          -- "${S[@]}" --rotor-inertia 0,0
succeed rotor-ok-one-gear-edge -- "${S[@]}" --rotor-inertia 1e-3,1e-3 --gear-ratio 1e-3,1e4 --method gauss4
succeed rotor-ok-verlet        -- "${S[@]}" --rotor-inertia 0.01,0.01 --method verlet
succeed rotor-ok-chain-torques -- "${S[@]}" --links 3 --rotor-inertia 0.01,0.01,0.01 --torque-file tau_three.csv --coulomb 0.1,0.1,0.1 --method rk4
succeed rotor-ok-sweep         -- sweep --n 4 --t-end 2 --output g.h5 --rotor-inertia 0.01,0.02 --gear-ratio 3,2
succeed rotor-ok-lyapunov      -- lyapunov --t-end 1 --tau 0.5 --output g.h5 --rotor-inertia 0.01,0.02
# the per-trajectory path has no Lyapunov exponent: a map over a parameter by name
refuse  sweep-lyapunov-named   'axis by name (g)'   -- sweep --n 3 --axis1 g --axis2 theta1 --min1 5 --max1 10 --lyapunov --output g.h5
succeed sweep-lyapunov-coded   -- sweep --n 3 --axis1 m1 --axis2 theta1 --min1 0.5 --max1 2 --t-end 1 --lyapunov --output g.h5
