# Strict parsing: one strict scalar parser for flags,
# comma lists, namelist files and CSV fields (the whole token is the number; the
# refusal names the field and the offending character, escaped, on one line);
# namelists read strictly ('%', repeated keys, two forms of one quantity); two forms
# on the command line; one range table for g (g = 0 refused by every command);
# sweep --ic-angles without --ic-file. Runs are tiny in case one is not refused.

_prs=$FIXTURES
TAB=$(printf '\t')
NL=$(printf 'x\ny'); NL=${NL:1:1}

# ---------------------------------------------------------------- fixtures ---
printf '&pendulum%%m1 = 2 /\n' > "$_prs/prs_percent.nml"
printf '&pendulum m1 = 2, g = 9.8, m1 = 3 /\n' > "$_prs/prs_repeat.nml"
printf '&pendulum m = 1, 1, m1 = 5 /\n' > "$_prs/prs_forms_m.nml"
printf '&initial q1 = 0.5\n  q = 1, 2 /\n' > "$_prs/prs_forms_q.nml"
printf '&pendulum l2 = 1, l = 1, 1 /\n' > "$_prs/prs_forms_l.nml"
printf '&initial w = 0, 0, w1 = 1 /\n' > "$_prs/prs_forms_w.nml"
printf '&pendulum m(1) = 2, m = 1, 1 /\n' > "$_prs/prs_subscript_whole.nml"
printf '&integration dt = 1;2 /\n' > "$_prs/prs_semicolon.nml"
printf '&pendulum m1 = 1%0999d /\n' 0 > "$_prs/prs_long_mantissa.nml"
printf '&pendulum m1 = 1.5%0999d /\n' 0 > "$_prs/prs_long_ok.nml"
printf '&integration t_end = 0.01, dt = 0x10 /\n' > "$_prs/prs_hex.nml"
printf '&integration t_end = nan /\n' > "$_prs/prs_nan.nml"
printf '&integration t_end = 0.01 /\n&chaos tau = 1;2 /\n' > "$_prs/prs_chaos_semicolon.nml"
printf '&sweep n1 = 4, n2 = 4, n1 = 8 /\n' > "$_prs/prs_sweep_repeat.nml"
printf "&sweep ic_angles = 'theta' /\n" > "$_prs/prs_sweep_ic_angles.nml"
printf '&study n_h = 3, n_h = 4 /\n' > "$_prs/prs_study_repeat.nml"
# logicals: the whole word (fuzz seed 20261128 case 8416: 'false.' was read as .false.)
for _v in false. .true .tx. t. yes; do
  printf '&integration t_end = 0.01 /\n&chaos same_energy = %s /\n' "$_v" > "$_prs/prs_logical_$_v.nml"
done
printf '&integration t_end = 0.01 /\n&chaos same_energy = .T., tau = 5e-3 /\n' > "$_prs/prs_logical_ok1.nml"
printf '&integration t_end = 0.01 /\n&chaos same_energy = False, tau = 5e-3 /\n' > "$_prs/prs_logical_ok2.nml"
# study values without their name (fuzz seed 20261128 case 1531: case 1 without a name
# fell back to the three default cases and ran for minutes)
printf "&study case_name(1) = '', case_q1(1) = -1.27, case_q2(1) = -1.77 /\n" > "$_prs/prs_study_noname.nml"
printf "&study case_name(1) = 'a', case_q1(1) = 0.1, case_q2(2) = 0.1 /\n" > "$_prs/prs_study_noname2.nml"
printf "&study method(1) = 'rk4', h_max(2) = 1e-2 /\n" > "$_prs/prs_study_range.nml"
printf "&study ro_dt(3) = 1e-3 /\n" > "$_prs/prs_study_ro_dt.nml"
printf "&study tao_method(2) = 'tao2' /\n" > "$_prs/prs_study_tao_gap.nml"
# a list entry without the ones before it (the namelist read kept the leading entries
# given: m(2) alone was ignored)
printf '&pendulum m(2) = 3 /\n' > "$_prs/prs_gap_m.nml"
# a quoted number for a key that takes a number (fuzz seed 20261205 case 5130:
# block = "1" was read as 1)
printf "&integration t_end = '0.01' /\n" > "$_prs/prs_quoted_number.nml"
printf "&pendulum body = 'point' /\n&integration t_end = 0.01 /\n" > "$_prs/prs_quoted_body.nml"
printf '&pendulum links = 3 /\n&initial q(3) = 0.5 /\n' > "$_prs/prs_gap_q.nml"
printf '&pendulum links = 3, damping(2) = 0.1 /\n' > "$_prs/prs_gap_damping.nml"
printf "&pendulum body = 'point', com(2) = 0.5 /\n" > "$_prs/prs_gap_com.nml"
printf '&pendulum links = 3, m = 1, 2, 3, damping(1) = 0.1, damping(2) = 0, 0 /\n' > "$_prs/prs_gap_ok.nml"
printf '&pendulum m = 1, 1 /\n&integration t_end = 0.01 /\n' > "$_prs/prs_file_list.nml"
printf "&pendulum m = 2*1.5, l(1) = 2, l(2) = 0.5 /\n&integration method = 'rk4',\tdt = .5e-3, t_end = 5e-3 /\n&output file = 'a%%b=c.h5' /\n" > "$_prs/prs_valid.nml"
printf '0 0 0 1e400\n' > "$_prs/prs_list_huge.txt"
printf '0;1 0 0 0\n' > "$_prs/prs_list_semicolon.txt"
printf '0 0 0x1 0\n' > "$_prs/prs_list_hex.txt"
printf '0\t0.1 0 0\n0.1, 0, 0,0 # a comment\n' > "$_prs/prs_list_ok.txt"
printf 't,theta1\n0,0.1\n0.1,0.09x\n0.2,0.06\n' > "$_prs/prs_fit_junk.csv"
printf 't,theta1\n0,0.1\n0.1,0.0 9\n0.2,0.06\n' > "$_prs/prs_fit_blank.csv"
printf 't,theta1\n0,0.1\n0.1,0x1\n0.2,0.06\n' > "$_prs/prs_fit_hex.csv"
printf 't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n' > "$_prs/prs_fit_ok.csv"

S=(simulate --t-end 0.01 --output o.h5)
# ---- a number with a tab, ';' or newline inside
refuse  prs-q1-tab            q1            -- "${S[@]}" --q1 "0.7${TAB}1"
refuse  prs-dt-semicolon      dt            -- "${S[@]}" --dt '1;2'
refuse  prs-q-list-tab        q             -- "${S[@]}" --links 3 --q "0.7${TAB}1,0,0"
refuse  prs-q1-newline        q1            -- "${S[@]}" --q1 "0.7${NL}1"
refuse  prs-m-list-newline    m             -- "${S[@]}" --links 3 --m "1,1${NL}2,1"
# ---- every kind of invalid token, flags and lists
refuse  prs-dt-comma          dt            -- "${S[@]}" --dt 1,2
refuse  prs-dt-blank          dt            -- "${S[@]}" --dt '1 2'
refuse  prs-dt-leading-blank  dt            -- "${S[@]}" --dt ' 1e-3'
refuse  prs-dt-hex            dt            -- "${S[@]}" --dt 0x10
refuse  prs-dt-inf            dt            -- "${S[@]}" --dt inf
refuse  prs-dt-nan            dt            -- "${S[@]}" --dt nan
refuse  prs-dt-junk           dt            -- "${S[@]}" --dt 1e-3s
refuse  prs-dt-kind           dt            -- "${S[@]}" --dt 1e-3_dp
refuse  prs-dt-exponent       dt            -- "${S[@]}" --dt 1e
refuse  prs-dt-point          dt            -- "${S[@]}" --dt .
refuse  prs-dt-huge           dt            -- "${S[@]}" --dt "1$(printf '%0999d' 0)"
refuse  prs-g-cr              g             -- "${S[@]}" --g "$(printf '9.8\r')"
refuse  prs-save-every-float  save-every    -- "${S[@]}" --save-every 1.5
refuse  prs-save-every-big    save-every    -- "${S[@]}" --save-every 99999999999
refuse  prs-links-tab         links         -- "${S[@]}" --links "3${TAB}"
refuse  prs-max-steps-junk    max-steps     -- "${S[@]}" --max-steps 10k
refuse  prs-damping-semicolon damping       -- "${S[@]}" --damping '0.1;0.2'
refuse  prs-support-tab       support-amplitude -- "${S[@]}" --support-amplitude "0.1${TAB},0"
refuse  prs-lyapunov-tau      tau           -- lyapunov --t-end 0.01 --output o.h5 --tau '1;2'
refuse  prs-sweep-min1-tab    min1          -- sweep --output s.h5 --min1 "0.5${TAB}"
refuse  prs-sweep-n1-junk     n1            -- sweep --output s.h5 --n1 8x
refuse  prs-fit-window-semi   fit-window    -- fit prs_fit_ok.csv --output f.h5 --fit-window '1;2'
refuse  prs-method-newline    method        -- "${S[@]}" --method "rk${NL}4"
refuse  prs-option-newline    unknown       -- "${S[@]}" "--d${NL}t" 1
succeed prs-valid-forms          -- "${S[@]}" --force --dt .5e-3 --q1 -1.5 --q2 5. --w1 +0 --g 9.81e0
succeed prs-valid-list           -- "${S[@]}" --force --links 3 --q 0.5,-.25,1D-1 --m 1,2,3e0
# ---- namelist files read strictly
refuse  prs-nml-percent       'component syntax' -- "${S[@]}" --config prs_percent.nml
refuse  prs-nml-repeat        'given twice'      -- "${S[@]}" --config prs_repeat.nml
refuse  prs-nml-forms-m       'two forms'        -- "${S[@]}" --config prs_forms_m.nml
refuse  prs-nml-forms-q       'two forms'        -- "${S[@]}" --config prs_forms_q.nml
refuse  prs-nml-forms-l       'two forms'        -- "${S[@]}" --config prs_forms_l.nml
refuse  prs-nml-forms-w       'two forms'        -- "${S[@]}" --config prs_forms_w.nml
refuse  prs-nml-subscript     'given twice'      -- "${S[@]}" --config prs_subscript_whole.nml
refuse  prs-nml-semicolon     'not a number'     -- "${S[@]}" --config prs_semicolon.nml
refuse  prs-nml-long-mantissa 'largest double'   -- "${S[@]}" --config prs_long_mantissa.nml
refuse  prs-nml-hex           'not a number'     -- "${S[@]}" --config prs_hex.nml
refuse  prs-nml-nan           'not finite'       -- "${S[@]}" --config prs_nan.nml
refuse  prs-nml-chaos-semi    'not a number'     -- lyapunov --config prs_chaos_semicolon.nml --output o.h5
refuse  prs-nml-sweep-repeat  'given twice'      -- sweep --config prs_sweep_repeat.nml --output s.h5
refuse  prs-nml-study-repeat  'given twice'      -- study --config prs_study_repeat.nml --output s.md
succeed prs-nml-long-ok          -- "${S[@]}" --config prs_long_ok.nml --force
succeed prs-nml-valid            -- simulate --config prs_valid.nml
for _v in false. .true .tx. t. yes; do
  refuse "prs-nml-logical-$_v" 'same_energy' -- lyapunov --config "prs_logical_$_v.nml" --tau 5e-3 --output o.h5
done
succeed prs-nml-logical-dots     -- lyapunov --config prs_logical_ok1.nml --output o1.h5
succeed prs-nml-logical-word     -- lyapunov --config prs_logical_ok2.nml --output o2.h5
refuse  prs-study-case-noname  'case_name(1)' -- study --config prs_study_noname.nml --output s.md
refuse  prs-study-case-noname2 'case_name(2)' -- study --config prs_study_noname2.nml --output s.md
refuse  prs-study-range-nomethod 'method(2)'  -- study --config prs_study_range.nml --output s.md
refuse  prs-study-ro-dt-nomethod 'ro_dt(3)'   -- study --config prs_study_ro_dt.nml --output s.md
refuse  prs-study-tao-gap      'tao_method(1)' -- study --config prs_study_tao_gap.nml --output s.md
refuse  prs-nml-gap-m          'm(2)'         -- "${S[@]}" --config prs_gap_m.nml
refuse  prs-nml-gap-q          'q(3)'         -- "${S[@]}" --config prs_gap_q.nml
refuse  prs-nml-gap-damping    'damping(2)'   -- "${S[@]}" --config prs_gap_damping.nml
refuse  prs-nml-gap-com        'com(2)'       -- "${S[@]}" --config prs_gap_com.nml
succeed prs-nml-gap-ok            -- "${S[@]}" --force --config prs_gap_ok.nml
refuse  prs-nml-quoted-number  't_end'        -- simulate --config prs_quoted_number.nml --output o.h5
succeed prs-nml-quoted-body       -- simulate --config prs_quoted_body.nml --output o4.h5
# ---- two forms of one quantity on the command line (a flag over a file stays)
refuse  prs-flags-m-m1        m1            -- "${S[@]}" --m 1,2 --m1 3
refuse  prs-flags-m1-m        m             -- "${S[@]}" --m1 3 --m 1,2
refuse  prs-flags-q1-theta1   theta1        -- "${S[@]}" --q1 1 --theta1 0.5
refuse  prs-flags-q-theta2    theta2        -- "${S[@]}" --q 1,1 --theta2 0.5
refuse  prs-flags-l2-l        l             -- "${S[@]}" --l2 2 --l 1,1
refuse  prs-flags-w-w1        w1            -- "${S[@]}" --w 0,0 --w1 1
refuse  prs-flags-sweep-m-m1  m1            -- sweep --output s.h5 --m 1,2 --m1 3
succeed prs-flag-over-file       -- "${S[@]}" --force --config prs_file_list.nml --m1 3
refuse  prs-flag-repeated   q1   -- "${S[@]}" --force --q1 1 --q1 2
# ---- one range table: g = 0 refused by every command
refuse  prs-g0-sweep-3        g             -- sweep --output s.h5 --links 3 --g 0
refuse  prs-g0-sweep-1-s      g             -- sweep --output s.h5 --links 1 --g 0 --time-unit s
refuse  prs-g0-simulate-1     g             -- "${S[@]}" --links 1 --g 0
refuse  prs-g0-simulate-2     g             -- "${S[@]}" --g 0
refuse  prs-g0-simulate-3     g             -- "${S[@]}" --links 3 --g 0
refuse  prs-g-tiny-simulate-3 g             -- "${S[@]}" --links 3 --g 1e-7
refuse  prs-g0-lyapunov-3     g             -- lyapunov --t-end 0.01 --output o.h5 --links 3 --g 0
refuse  prs-g0-study          g             -- study --output s.md --g 0
refuse  prs-g0-fit            g             -- fit prs_fit_ok.csv --output f.h5 --g 0
refuse  prs-g0-fit-links-2    g             -- fit prs_fit_ok.csv --output f.h5 --links 2 --g 0
# ---- CSV fields through the strict parser
refuse  prs-csv-junk          'line 3'      -- fit prs_fit_junk.csv --output f.h5
refuse  prs-csv-blank         'line 3'      -- fit prs_fit_blank.csv --output f.h5
refuse  prs-csv-hex           'line 3'      -- fit prs_fit_hex.csv --output f.h5
# ---- sweep: a list's options without the list
refuse  prs-ic-angles-no-file ic_angles     -- sweep --output s.h5 --ic-angles theta
refuse  prs-ic-dataset-no-file ic_dataset   -- sweep --output s.h5 --ic-dataset /x
refuse  prs-ic-angles-nml     ic_angles     -- sweep --output s.h5 --config prs_sweep_ic_angles.nml
# ---- sweep: the text list of initial conditions through the strict parser
refuse  prs-list-huge         ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file prs_list_huge.txt
refuse  prs-list-semicolon    ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file prs_list_semicolon.txt
refuse  prs-list-hex          ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file prs_list_hex.txt
succeed prs-list-ok              -- sweep --output s.h5 --t-end 0.01 --quiet --ic-file prs_list_ok.txt
