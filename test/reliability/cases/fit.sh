# `dpend fit`: measured series refused with their line numbers, bad flags
# refused before any work (one line naming the field, exit 2, no file touched), edge
# values that must succeed without a trap in the debug build, and a fit that fails
# partway (exit 1, its file with the status).

# fixtures: CSV files, good and bad (each row's problem in its name)
fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
fx fit_ok.csv         't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
fx fit_q.csv          '# q columns, units\nt [s],q1 [rad],q2 [rad]\n0,-1.5,-1.5\n0.1,-1.51,-1.49\n0.2,-1.53,-1.47\n0.3,-1.56,-1.46\n'
fx fit_word.csv       't,theta1\n0,0.1\n0.1,zero\n0.2,0.06\n'
fx fit_nan.csv        't,theta1\n0,0.1\n0.1,0.09\n0.2,NaN\n'
fx fit_inf.csv        't,theta1\n0,0.1\n0.1,-inf\n'
fx fit_time_nan.csv   't,theta1\n0,0.1\nnan,0.1\n'
fx fit_back.csv       't,theta1\n0,0.1\n0.2,0.09\n0.1,0.06\n0.3,0.02\n'
fx fit_repeat.csv     't,theta1\n0,0.1\n0.1,0.09\n0.1,0.06\n'
fx fit_short_row.csv  't,theta1,theta2\n0,0.1,0.2\n0.1,0.09\n'
fx fit_long_row.csv   't,theta1\n0,0.1\n0.1,0.09,7\n'
fx fit_no_t.csv       'time,theta1\n0,0.1\n'
fx fit_no_angle.csv   't,z1,w1\n0,0.1,0.2\n'
fx fit_xy.csv         't,x1 [cm],y1 [cm]\n0,50,-86.6\n0.1,45,-89.3\n0.2,38,-92.5\n0.3,29,-95.7\n'
fx fit_xy_gap.csv     't,x1,y1,x2\n0,0.5,-0.8,1\n'
fx fit_xy_unit.csv    't,x1 [in],y1 [in]\n0,0.5,-0.8\n'
fx fit_xy_word.csv    't,x1,y1\n0,0.5,-0.8\n0.1,0.4,minus\n'
fx fit_gap.csv        't,theta1,theta3\n0,0.1,0.2\n'
fx fit_mixed.csv      't,theta1,q2\n0,0.1,0.2\n'
fx fit_dup.csv        't,theta1,theta1\n0,0.1,0.2\n'
fx fit_unit.csv       't [ms],theta1\n0,0.1\n'
fx fit_deg.csv        't,theta1 [grad]\n0,10\n'
fx fit_header_only.csv 't,theta1\n'
fx fit_empty.csv      ''
fx fit_two.csv        't,theta1\n0,0.1\n0.1,0.09\n'
fx fit_binary.csv     't,theta1\n0,0.1\n\001\002,3\n'
fx fit_huge.csv       't,theta1\n0,0.1\n0.1,1e999\n0.2,0.06\n'
fx fit_big_value.csv  't,theta1\n0,0.1\n0.1,2e6\n0.2,0.06\n'
fx fit_big_time.csv   't,theta1\n0,0.1\n1e300,0.09\n'
fx fit_tiny_step.csv  't,theta1\n0,0.1\n1e-200,0.09\n2e-200,0.06\n'
cp "$ROOT/data/fit_example.csv" "$FIXTURES/fit_example.csv"

F=(fit --output g.h5)
# ---- the data file
refuse  fit-no-file           'data file'       -- "${F[@]}"
refuse  fit-missing-file      'no such file'    -- "${F[@]}" nosuch.csv
refuse  fit-directory         'directory'       -- "${F[@]}" dir
refuse  fit-two-files         'unexpected'      -- "${F[@]}" fit_ok.csv fit_ok.csv
refuse  fit-word              'line 3'          -- "${F[@]}" fit_word.csv
refuse  fit-nan               'line 4'          -- "${F[@]}" fit_nan.csv
refuse  fit-huge-number       'line 3'          -- "${F[@]}" fit_huge.csv
refuse  fit-big-value         'line 3'          -- "${F[@]}" fit_big_value.csv
refuse  fit-big-time          'line 3'          -- "${F[@]}" fit_big_time.csv
refuse  fit-tiny-step         'line 3'          -- "${F[@]}" fit_tiny_step.csv
refuse  fit-inf               'line 3'          -- "${F[@]}" fit_inf.csv
refuse  fit-time-nan          'line 3'          -- "${F[@]}" fit_time_nan.csv
refuse  fit-back              'line 4'          -- "${F[@]}" fit_back.csv
refuse  fit-repeat            'line 4'          -- "${F[@]}" fit_repeat.csv
refuse  fit-short-row         'line 3'          -- "${F[@]}" fit_short_row.csv
refuse  fit-long-row          'line 3'          -- "${F[@]}" fit_long_row.csv
refuse  fit-no-t              "column 't'"      -- "${F[@]}" fit_no_t.csv
refuse  fit-no-angle          'no angle'        -- "${F[@]}" fit_no_angle.csv
refuse  fit-gap               'theta2'          -- "${F[@]}" fit_gap.csv
refuse  fit-mixed             'mixes'           -- "${F[@]}" fit_mixed.csv
refuse  fit-dup               'twice'           -- "${F[@]}" fit_dup.csv
refuse  fit-unit              'unit'            -- "${F[@]}" fit_unit.csv
refuse  fit-deg               'unit'            -- "${F[@]}" fit_deg.csv
refuse  fit-header-only       'no data rows'    -- "${F[@]}" fit_header_only.csv
refuse  fit-empty             'no header'       -- "${F[@]}" fit_empty.csv
refuse  fit-too-few           'samples'         -- "${F[@]}" fit_two.csv
refuse  fit-too-few-damping   'samples'         -- "${F[@]}" fit_ok.csv --fit-damping --fit-window 0.1
refuse  fit-binary            'line 3'          -- "${F[@]}" fit_binary.csv
refuse  fit-xy-gap            'y2'              -- "${F[@]}" fit_xy_gap.csv
refuse  fit-xy-unit           'unit'            -- "${F[@]}" fit_xy_unit.csv
refuse  fit-xy-word           'line 3'          -- "${F[@]}" fit_xy_word.csv
refuse  fit-xy-tol-huge       horizon-tolerance -- "${F[@]}" fit_xy.csv --horizon-tolerance 1e7
# ---- flags
refuse  fit-links-mismatch    links             -- "${F[@]}" fit_ok.csv --links 2
refuse  fit-window-before     fit-window        -- "${F[@]}" fit_ok.csv --fit-window -1
refuse  fit-window-nan        fit-window        -- "${F[@]}" fit_ok.csv --fit-window nan
refuse  fit-window-missing    fit-window        -- "${F[@]}" fit_ok.csv --fit-window
refuse  fit-tol-zero          horizon-tolerance -- "${F[@]}" fit_ok.csv --horizon-tolerance 0
refuse  fit-tol-big           horizon-tolerance -- "${F[@]}" fit_ok.csv --horizon-tolerance 4
refuse  fit-starts-zero       starts            -- "${F[@]}" fit_ok.csv --starts 0
refuse  fit-starts-huge       starts            -- "${F[@]}" fit_ok.csv --starts 1001
refuse  fit-method-canonical  method            -- "${F[@]}" fit_ok.csv --method gauss6
refuse  fit-method-unknown    method            -- "${F[@]}" fit_ok.csv --method nosuch
refuse  fit-m-wrong-count     m                 -- "${F[@]}" fit_ok.csv --m 1,1
refuse  fit-damping-negative  c1                -- "${F[@]}" fit_ok.csv --damping -1
refuse  fit-q-flag            unknown           -- "${F[@]}" fit_ok.csv --q1 0
refuse  fit-t-end-flag        unknown           -- "${F[@]}" fit_ok.csv --t-end 3
refuse  fit-damping-flag-value fit-damping      -- "${F[@]}" fit_ok.csv --fit-damping=1
refuse  fit-existing-output   exists            -- fit fit_ok.csv --output existing.h5

# edge values that must succeed
succeed fit-ok-one-link             -- "${F[@]}" fit_ok.csv
succeed fit-ok-damping              -- "${F[@]}" fit_ok.csv --fit-damping
succeed fit-ok-q-columns-window     -- "${F[@]}" fit_q.csv --fit-window 0.2 --horizon-tolerance 3.14159
succeed fit-ok-positions            -- "${F[@]}" fit_xy.csv --horizon-tolerance 5
succeed fit-ok-starts               -- "${F[@]}" fit_ok.csv --starts 5 --method rk4 --dt 0.01

# a fit that fails partway: exit 1, and its file holds the settings and the status
fail    fit-fails-partway  'max-steps'  -- "${F[@]}" fit_example.csv --method dopri5 --max-steps 10
