# Inverse dynamics, `dpend torques DATA.csv`: data files refused with their line
# numbers (gaps, NaN, times not increasing, too few samples for the filter, positions
# instead of angles, partial or mis-united torque and rate columns), the filter's
# options out of range (--degree, --window, --sigma), the model's flags checked as
# every command checks them, options of other commands refused, outputs that would
# replace the data; each in one line naming the field, exit 2, no file touched; and
# edge values that must succeed without a trap in the debug build.

# fixtures: N samples of a smooth motion every 10 ms (t, q1, q2), with rates (qdot1,
# qdot2) and torques (tau1, tau2) when asked; each bad file's problem in its name
fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
motion() {  # motion FILE N COLUMNS...  (COLUMNS among q, qdot, tau)
  local file=$1 n=$2; shift 2
  awk -v n="$n" -v cols="$*" 'BEGIN {
      m = split(cols, c, " "); h = "t"
      for (i = 1; i <= m; i++) h = h "," c[i] "1," c[i] "2"
      print h
      for (k = 0; k < n; k++) { t = k/100; r = sprintf("%.6g", t)
        for (i = 1; i <= m; i++) {
          if (c[i] == "q")    r = r sprintf(",%.9g,%.9g", -1.2 + 0.3*sin(2*t), -1 + 0.2*sin(3*t))
          if (c[i] == "qdot") r = r sprintf(",%.9g,%.9g", 0.6*cos(2*t), 0.6*cos(3*t))
          if (c[i] == "tau")  r = r sprintf(",%.9g,%.9g", 0.1*sin(t), 0.05) }
        print r } }' > "$FIXTURES/$file"
}
motion id_ok.csv        15 q
motion id_ok_tau.csv    15 q tau
motion id_ok_rates.csv  15 q qdot tau
motion id_ok_long.csv   400 q tau
motion id_few.csv       6 q
motion id_one_link.csv  15 q
sed -i 's/,[^,]*$//; 1s/.*/t,q1/' "$FIXTURES/id_one_link.csv"
fx id_gap.csv          't,q1,q2\n0,-1.2,-1\n0.01,,-0.99\n0.02,-1.18,-0.98\n'
fx id_nan.csv          't,q1,q2\n0,-1.2,-1\n0.01,NaN,-0.99\n0.02,-1.18,-0.98\n'
fx id_back.csv         't,q1,q2\n0,-1.2,-1\n0.02,-1.19,-0.99\n0.01,-1.18,-0.98\n'
fx id_positions.csv    't,x1,y1\n0,0.1,-0.9\n0.01,0.11,-0.9\n'
fx id_tau_partial.csv  't,q1,q2,tau1\n0,-1.2,-1,0.1\n0.01,-1.19,-0.99,0.1\n'
fx id_tau_unit.csv     't,q1,q2,tau1 [N cm],tau2\n0,-1.2,-1,0.1,0\n0.01,-1.19,-0.99,0.1,0\n'
fx id_tau_nan.csv      't,q1,q2,tau1,tau2\n0,-1.2,-1,0.1,0\n0.01,-1.19,-0.99,nan,0\n'
fx id_tau_big.csv      't,q1,q2,tau1,tau2\n0,-1.2,-1,0.1,0\n0.01,-1.19,-0.99,3e6,0\n'
fx id_rates_unit.csv   't,q1,q2,qdot1 [deg/s],qdot2\n0,-1.2,-1,1,0\n0.01,-1.19,-0.99,1,0\n'
fx id_rates_twice.csv  't,q1,q2,qdot1,qdot1,qdot2\n0,-1.2,-1,1,1,0\n0.01,-1.19,-0.99,1,1,0\n'
fx id_no_angles.csv    't,tau1,tau2\n0,0.1,0\n0.01,0.1,0\n'
fx id_utf16.csv        '\377\376t\000,\000q\000'

T=(torques id_ok.csv --output g.h5)
# ---- the data file
refuse  id-no-data            'no data file'         -- torques --output g.h5
refuse  id-two-data           'unexpected argument'  -- torques id_ok.csv id_ok_tau.csv --output g.h5
refuse  id-missing-file       'no such file'         -- torques nosuch.csv --output g.h5
refuse  id-directory          'directory'            -- torques dir --output g.h5
refuse  id-gap                'line 3'               -- torques id_gap.csv --output g.h5
refuse  id-nan                'line 3'               -- torques id_nan.csv --output g.h5
refuse  id-back               'line 4'               -- torques id_back.csv --output g.h5
refuse  id-few                'needs at least 7'     -- torques id_few.csv --output g.h5
refuse  id-positions          'positions'            -- torques id_positions.csv --output g.h5
refuse  id-no-angles          'no angle columns'     -- torques id_no_angles.csv --output g.h5
refuse  id-tau-partial        'missing column tau2'  -- torques id_tau_partial.csv --output g.h5
refuse  id-tau-unit           "unit '[n cm]'"        -- torques id_tau_unit.csv --output g.h5
refuse  id-tau-nan            'line 3'               -- torques id_tau_nan.csv --output g.h5
refuse  id-tau-big            'measured torques'     -- torques id_tau_big.csv --output g.h5
refuse  id-rates-unit         "unit '[deg/s]'"       -- torques id_rates_unit.csv --output g.h5
refuse  id-rates-twice        'appears twice'        -- torques id_rates_twice.csv --output g.h5
refuse  id-utf16              'UTF-16'               -- torques id_utf16.csv --output g.h5
# ---- the filter
refuse  id-degree-low         'outside [2, 8]'       -- "${T[@]}" --degree 1
refuse  id-degree-high        'outside [2, 8]'       -- "${T[@]}" --degree 9
refuse  id-degree-word        'degree'               -- "${T[@]}" --degree four
refuse  id-degree-real        'degree'               -- "${T[@]}" --degree 4.0
refuse  id-window-even        'even'                 -- "${T[@]}" --window 8
refuse  id-window-small       'window'               -- "${T[@]}" --window 3
refuse  id-window-degree      'degree + 1'           -- "${T[@]}" --degree 6 --window 5
refuse  id-window-big         'outside [5, 4001]'    -- "${T[@]}" --window 4003
refuse  id-window-samples     'needs at least 21'    -- "${T[@]}" --window 21
refuse  id-window-negative    'window'               -- "${T[@]}" --window -5
refuse  id-sigma-zero         'sigma'                -- "${T[@]}" --sigma 0
refuse  id-sigma-negative     'sigma'                -- "${T[@]}" --sigma -1e-3
refuse  id-sigma-big          'sigma'                -- "${T[@]}" --sigma 2
refuse  id-sigma-nan          'sigma'                -- "${T[@]}" --sigma nan
refuse  id-window-twice       'given twice'          -- "${T[@]}" --window 5 --window 7
# ---- the model
refuse  id-links              'angle columns'        -- "${T[@]}" --links 3
refuse  id-elastic            'no joints'            -- "${T[@]}" --model elastic
refuse  id-damping-count      'damping'              -- "${T[@]}" --damping 0.1
refuse  id-coulomb-negative   'coulomb'              -- "${T[@]}" --coulomb -1,0
refuse  id-mass-zero          'm'                    -- "${T[@]}" --m 0,1
refuse  id-body-com           'com'                  -- "${T[@]}" --body point --com 0.5,0.5
# ---- options of other commands, and outputs that would replace the data
refuse  id-config             "unknown option '--config'" -- "${T[@]}" --config coulomb.nml
refuse  id-t-end              'unknown option'       -- "${T[@]}" --t-end 5
refuse  id-method             'unknown option'       -- "${T[@]}" --method rk4
refuse  id-torque-file        'unknown option'       -- "${T[@]}" --torque-file tau_ok.csv
refuse  id-time-unit          'unknown option'       -- "${T[@]}" --time-unit natural
refuse  id-output-is-data     'input'                -- torques id_ok.csv --output id_ok.csv --force
refuse  id-csv-is-data        'input'                -- "${T[@]}" --csv id_ok.csv --force
refuse  id-csv-is-output      'also the HDF5 output' -- "${T[@]}" --csv g.h5
refuse  id-csv-no-value       'needs a value'        -- "${T[@]}" --csv

# edge values that must succeed
succeed id-ok                 -- "${T[@]}"
succeed id-ok-measured-csv    -- torques id_ok_tau.csv --output g.h5 --csv g.csv
succeed id-ok-rates           -- torques id_ok_rates.csv --output g.h5
succeed id-ok-one-link        -- torques id_one_link.csv --output g.h5
succeed id-ok-long            -- torques id_ok_long.csv --output g.h5 --degree 8
succeed id-ok-degree2-window5 -- "${T[@]}" --degree 2 --window 5
succeed id-ok-window-all      -- "${T[@]}" --window 15
succeed id-ok-sigma           -- "${T[@]}" --sigma 1e-12
succeed id-ok-friction        -- "${T[@]}" --damping 0.1,0.2 --coulomb 0.05,0.02 --coulomb-speed 1e-6
succeed id-ok-bodies          -- "${T[@]}" --com 0.3,0.4 --inertia 0.02,0.01 --support-amplitude 0.01,0.02 --support-frequency 3
succeed id-ok-point           -- "${T[@]}" --body point
succeed id-ok-quiet           -- torques id_ok_tau.csv --output g.h5 --quiet
succeed id-ok-motors          -- "${T[@]}" --rotor-inertia 1e-3,2e-4 --gear-ratio 10,30
refuse  id-rotors             'unknown option'       -- "${T[@]}" --rotors estimate
refuse  id-motor-big          'rotor_inertia I_r1'   -- "${T[@]}" --rotor-inertia 1e7,0

# ---- dpend identify: the same data checks, the torques required, what it estimates
motion id_ok_long_rates.csv 400 q qdot tau
motion id_few_tau.csv 6 q tau
I=(identify id_ok_long.csv --output g.h5)
refuse  ident-no-data         'no data file'         -- identify --output g.h5
refuse  ident-no-torques      'no measured torques'  -- identify id_ok.csv --output g.h5
refuse  ident-few             'needs at least 7'     -- identify id_few_tau.csv --output g.h5
refuse  ident-tau-partial     'missing column tau2'  -- identify id_tau_partial.csv --output g.h5
refuse  ident-positions       'positions'            -- identify id_positions.csv --output g.h5
refuse  ident-friction-word   'friction'             -- "${I[@]}" --friction dry
refuse  ident-friction-empty  'friction'             -- "${I[@]}" --friction ''
refuse  ident-friction-twice  'given twice'          -- "${I[@]}" --friction none --friction viscous
refuse  ident-damping-fitted  'estimates the viscous' -- "${I[@]}" --damping 0.1,0.1
refuse  ident-coulomb-fitted  'estimates the Coulomb' -- "${I[@]}" --coulomb 0.1,0.1
refuse  ident-rotors-word     "rotors: 'maybe'"      -- "${I[@]}" --rotors maybe
refuse  ident-rotors-case     "rotors: 'Estimate'"   -- "${I[@]}" --rotors Estimate
refuse  ident-rotors-twice    'given twice'          -- "${I[@]}" --rotors known --rotors estimate
refuse  ident-rotors-given    'estimates the reflected' -- "${I[@]}" --rotors estimate --rotor-inertia 0.1,0.1
refuse  ident-gear-given      'estimates the reflected' -- "${I[@]}" --rotors estimate --rotor-inertia 0,0 --gear-ratio 2,2
refuse  ident-gear-alone      'without a rotor_inertia' -- "${I[@]}" --gear-ratio 2,2
refuse  ident-com             'estimates'            -- "${I[@]}" --com 0.4,0.3
refuse  ident-inertia         'estimates'            -- "${I[@]}" --inertia 0.1,0.1
refuse  ident-body            'estimates'            -- "${I[@]}" --body point
refuse  ident-csv             'unknown option'       -- "${I[@]}" --csv g.csv
refuse  ident-method          'unknown option'       -- "${I[@]}" --method rk4
refuse  ident-degree          'outside [2, 8]'       -- "${I[@]}" --degree 0
refuse  ident-window-even     'even'                 -- "${I[@]}" --window 10
refuse  ident-links           'angle columns'        -- "${I[@]}" --links 1
refuse  ident-elastic         'no joints'            -- "${I[@]}" --model elastic
refuse  ident-output-is-data  'input'                -- identify id_ok_long.csv --output id_ok_long.csv --force
# a motion that does not excite every direction: 15 samples of slow sines in one
# window, far too few rows; and a wide window that leaves too few rows
refuse  ident-too-few-rows    'rows are needed'      -- identify id_ok_tau.csv --output g.h5
refuse  ident-window-rows     'rows are needed'      -- "${I[@]}" --window 201
succeed ident-ok              -- "${I[@]}"
succeed ident-ok-viscous      -- "${I[@]}" --friction viscous --coulomb 0.01,0.02
succeed ident-ok-none         -- "${I[@]}" --friction none --damping 0.1,0.1 --coulomb 0.01,0.02 --coulomb-speed 0.2
succeed ident-ok-rates        -- identify id_ok_long_rates.csv --output g.h5 --m 1,0.7 --degree 2
succeed ident-ok-rotors       -- "${I[@]}" --rotors estimate
succeed ident-ok-rotors-known -- "${I[@]}" --rotors known --rotor-inertia 1e-3,1e-3 --gear-ratio 5,5

# ---- the robotics convention: phi columns (relative angles) and export --angles
fx ang_phi.csv         't,phi1,phi2\n0,0.3,0.2\n0.02,0.31,0.19\n0.04,0.32,0.18\n0.06,0.33,0.17\n0.08,0.34,0.16\n0.1,0.35,0.15\n0.12,0.36,0.14\n0.14,0.37,0.13\n'
fx ang_mixed.csv       't,phi1,q2\n0,0.3,0.2\n0.02,0.31,0.19\n'
fx ang_phi_gap.csv     't,phi1,phi2\n0,0.3,0.2\n0.02,,0.19\n'
fx ang_phi_unit.csv    't,phi1 [m],phi2\n0,0.3,0.2\n0.02,0.31,0.19\n'
fx ang_phi_missing.csv 't,phi1,phi3\n0,0.3,0.2\n0.02,0.31,0.19\n'
"$DPEND" simulate --t-end 0.2 --output "$FIXTURES/ang_sim.h5" --quiet > /dev/null 2>&1 || true
"$DPEND" simulate --model elastic --q 1.2,-1 --t-end 0.2 --output "$FIXTURES/ang_el.h5" --quiet > /dev/null 2>&1 || true
refuse  ang-mixed             'mixes phi and q'      -- fit ang_mixed.csv --output g.h5
refuse  ang-gap               'line 3'               -- fit ang_phi_gap.csv --output g.h5
refuse  ang-unit              "unit '[m]'"           -- fit ang_phi_unit.csv --output g.h5
refuse  ang-missing           'missing column phi2'  -- torques ang_phi_missing.csv --output g.h5
refuse  ang-export-value      "invalid angles: 'up'" -- export ang_sim.h5 --angles up t q
refuse  ang-export-no-value   'needs a value'        -- export ang_sim.h5 t q --angles
refuse  ang-export-twice      'given twice'          -- export ang_sim.h5 --angles relative --angles absolute t q
refuse  ang-export-none       'none of the datasets' -- export ang_sim.h5 --angles relative t energy
refuse  ang-export-elastic    'none of the datasets' -- export ang_el.h5 --angles relative t q
refuse  ang-export-list       'not with --list or --matrix' -- export ang_sim.h5 --angles relative --list
refuse  ang-export-matrix     'not with --list or --matrix' -- export ang_sim.h5 --angles relative --matrix q
succeed ang-ok-fit-phi        -- fit ang_phi.csv --output g.h5
succeed ang-ok-torques-phi    -- torques ang_phi.csv --output g.h5
succeed ang-ok-export-rel     -- export ang_sim.h5 --angles relative --csv t q qdot qddot energy
succeed ang-ok-export-abs     -- export ang_sim.h5 --angles absolute t q
# the initial state in the relative convention (simulate and the chaos commands)
refuse  ang-initial-word      "invalid angles: 'hanging'" -- simulate --t-end 0.1 --output g.h5 --angles hanging
refuse  ang-initial-case      "invalid angles: 'Relative'" -- simulate --t-end 0.1 --output g.h5 --angles Relative
refuse  ang-initial-twice     'given twice'          -- simulate --t-end 0.1 --output g.h5 --angles relative --angles absolute
refuse  ang-initial-no-value  'needs a value'        -- simulate --t-end 0.1 --output g.h5 --angles
refuse  ang-initial-theta     'theta1/--theta2'      -- simulate --t-end 0.1 --output g.h5 --angles relative --theta1 0.3
refuse  ang-initial-elastic   'relative needs links' -- simulate --t-end 0.1 --output g.h5 --model elastic --angles relative
refuse  ang-initial-sweep     'unknown option'       -- sweep --n 4 --output g.h5 --angles relative
refuse  ang-initial-fit       'unknown option'       -- fit ang_phi.csv --output g.h5 --angles relative
refuse  ang-initial-nan       'not finite'           -- simulate --t-end 0.1 --output g.h5 --angles relative --q nan,0
refuse  ang-initial-big       'q2'                   -- simulate --t-end 0.1 --output g.h5 --angles relative --q 1e6,1e6
succeed ang-ok-initial        -- simulate --t-end 0.1 --output g.h5 --angles relative --q 0.3,-0.5 --w 0.1,0.2
succeed ang-ok-initial-abs    -- simulate --t-end 0.1 --output g.h5 --angles absolute --q1 0.3
succeed ang-ok-initial-chain  -- simulate --t-end 0.1 --output g.h5 --links 4 --angles relative --q 0.1,0.2,0.3,0.4
succeed ang-ok-initial-lyap   -- lyapunov --t-end 1 --tau 0.5 --output g.h5 --angles relative --q2 0.4
succeed ang-ok-initial-div    -- divergence --t-end 1 --output-dt 0.1 --pairs 1 --lyapunov-t 0 --output g.h5 --angles relative
