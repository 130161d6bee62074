# Round 2 (issue 24), the strict parsing half: one strict scalar parser for flags,
# comma lists, namelist files and CSV fields (the whole token is the number; the
# refusal names the field and the offending character, escaped, on one line);
# namelists read strictly ('%', repeated keys, two forms of one quantity); two forms
# on the command line; one range table for g (g = 0 refused by every command);
# sweep --ic-angles without --ic-file. Runs are tiny in case one is not refused.

_r2p=$FIXTURES
TAB=$(printf '\t')
NL=$(printf 'x\ny'); NL=${NL:1:1}

# ---------------------------------------------------------------- fixtures ---
printf '&pendulum%%m1 = 2 /\n' > "$_r2p/r2p_percent.nml"
printf '&pendulum m1 = 2, g = 9.8, m1 = 3 /\n' > "$_r2p/r2p_repeat.nml"
printf '&pendulum m = 1, 1, m1 = 5 /\n' > "$_r2p/r2p_forms_m.nml"
printf '&initial q1 = 0.5\n  q = 1, 2 /\n' > "$_r2p/r2p_forms_q.nml"
printf '&pendulum l2 = 1, l = 1, 1 /\n' > "$_r2p/r2p_forms_l.nml"
printf '&initial w = 0, 0, w1 = 1 /\n' > "$_r2p/r2p_forms_w.nml"
printf '&pendulum m(1) = 2, m = 1, 1 /\n' > "$_r2p/r2p_subscript_whole.nml"
printf '&integration dt = 1;2 /\n' > "$_r2p/r2p_semicolon.nml"
printf '&pendulum m1 = 1%0999d /\n' 0 > "$_r2p/r2p_long_mantissa.nml"
printf '&pendulum m1 = 1.5%0999d /\n' 0 > "$_r2p/r2p_long_ok.nml"
printf '&integration t_end = 0.01, dt = 0x10 /\n' > "$_r2p/r2p_hex.nml"
printf '&integration t_end = nan /\n' > "$_r2p/r2p_nan.nml"
printf '&integration t_end = 0.01 /\n&chaos tau = 1;2 /\n' > "$_r2p/r2p_chaos_semicolon.nml"
printf '&sweep n1 = 4, n2 = 4, n1 = 8 /\n' > "$_r2p/r2p_sweep_repeat.nml"
printf "&sweep ic_angles = 'theta' /\n" > "$_r2p/r2p_sweep_ic_angles.nml"
printf '&study n_h = 3, n_h = 4 /\n' > "$_r2p/r2p_study_repeat.nml"
# logicals: the whole word (fuzz seed 20261128 case 8416: 'false.' was read as .false.)
for _v in false. .true .tx. t. yes; do
  printf '&integration t_end = 0.01 /\n&chaos same_energy = %s /\n' "$_v" > "$_r2p/r2p_logical_$_v.nml"
done
printf '&integration t_end = 0.01 /\n&chaos same_energy = .T., tau = 5e-3 /\n' > "$_r2p/r2p_logical_ok1.nml"
printf '&integration t_end = 0.01 /\n&chaos same_energy = False, tau = 5e-3 /\n' > "$_r2p/r2p_logical_ok2.nml"
# study values without their name (fuzz seed 20261128 case 1531: case 1 without a name
# fell back to the three default cases and ran for minutes)
printf "&study case_name(1) = '', case_q1(1) = -1.27, case_q2(1) = -1.77 /\n" > "$_r2p/r2p_study_noname.nml"
printf "&study case_name(1) = 'a', case_q1(1) = 0.1, case_q2(2) = 0.1 /\n" > "$_r2p/r2p_study_noname2.nml"
printf "&study method(1) = 'rk4', h_max(2) = 1e-2 /\n" > "$_r2p/r2p_study_range.nml"
printf "&study ro_dt(3) = 1e-3 /\n" > "$_r2p/r2p_study_ro_dt.nml"
printf "&study tao_method(2) = 'tao2' /\n" > "$_r2p/r2p_study_tao_gap.nml"
# a list entry without the ones before it (the namelist read kept the leading entries
# given: m(2) alone was ignored)
printf '&pendulum m(2) = 3 /\n' > "$_r2p/r2p_gap_m.nml"
# a quoted number for a key that takes a number (fuzz seed 20261205 case 5130:
# block = "1" was read as 1)
printf "&integration t_end = '0.01' /\n" > "$_r2p/r2p_quoted_number.nml"
printf "&pendulum body = 'point' /\n&integration t_end = 0.01 /\n" > "$_r2p/r2p_quoted_body.nml"
printf '&pendulum links = 3 /\n&initial q(3) = 0.5 /\n' > "$_r2p/r2p_gap_q.nml"
printf '&pendulum links = 3, damping(2) = 0.1 /\n' > "$_r2p/r2p_gap_damping.nml"
printf "&pendulum body = 'point', com(2) = 0.5 /\n" > "$_r2p/r2p_gap_com.nml"
printf '&pendulum links = 3, m = 1, 2, 3, damping(1) = 0.1, damping(2) = 0, 0 /\n' > "$_r2p/r2p_gap_ok.nml"
printf '&pendulum m = 1, 1 /\n&integration t_end = 0.01 /\n' > "$_r2p/r2p_file_list.nml"
printf "&pendulum m = 2*1.5, l(1) = 2, l(2) = 0.5 /\n&integration method = 'rk4',\tdt = .5e-3, t_end = 5e-3 /\n&output file = 'a%%b=c.h5' /\n" > "$_r2p/r2p_valid.nml"
printf '0 0 0 1e400\n' > "$_r2p/r2p_list_huge.txt"
printf '0;1 0 0 0\n' > "$_r2p/r2p_list_semicolon.txt"
printf '0 0 0x1 0\n' > "$_r2p/r2p_list_hex.txt"
printf '0\t0.1 0 0\n0.1, 0, 0,0 # a comment\n' > "$_r2p/r2p_list_ok.txt"
printf 't,theta1\n0,0.1\n0.1,0.09x\n0.2,0.06\n' > "$_r2p/r2p_fit_junk.csv"
printf 't,theta1\n0,0.1\n0.1,0.0 9\n0.2,0.06\n' > "$_r2p/r2p_fit_blank.csv"
printf 't,theta1\n0,0.1\n0.1,0x1\n0.2,0.06\n' > "$_r2p/r2p_fit_hex.csv"
printf 't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n' > "$_r2p/r2p_fit_ok.csv"

S=(simulate --t-end 0.01 --output o.h5)
# ---- the reproducers of the issue: a number with a tab, ';' or newline inside
refuse  r2p-q1-tab            q1            -- "${S[@]}" --q1 "0.7${TAB}1"
refuse  r2p-dt-semicolon      dt            -- "${S[@]}" --dt '1;2'
refuse  r2p-q-list-tab        q             -- "${S[@]}" --links 3 --q "0.7${TAB}1,0,0"
refuse  r2p-q1-newline        q1            -- "${S[@]}" --q1 "0.7${NL}1"
refuse  r2p-m-list-newline    m             -- "${S[@]}" --links 3 --m "1,1${NL}2,1"
# ---- every kind of invalid token, flags and lists
refuse  r2p-dt-comma          dt            -- "${S[@]}" --dt 1,2
refuse  r2p-dt-blank          dt            -- "${S[@]}" --dt '1 2'
refuse  r2p-dt-leading-blank  dt            -- "${S[@]}" --dt ' 1e-3'
refuse  r2p-dt-hex            dt            -- "${S[@]}" --dt 0x10
refuse  r2p-dt-inf            dt            -- "${S[@]}" --dt inf
refuse  r2p-dt-nan            dt            -- "${S[@]}" --dt nan
refuse  r2p-dt-junk           dt            -- "${S[@]}" --dt 1e-3s
refuse  r2p-dt-kind           dt            -- "${S[@]}" --dt 1e-3_dp
refuse  r2p-dt-exponent       dt            -- "${S[@]}" --dt 1e
refuse  r2p-dt-point          dt            -- "${S[@]}" --dt .
refuse  r2p-dt-huge           dt            -- "${S[@]}" --dt "1$(printf '%0999d' 0)"
refuse  r2p-g-cr              g             -- "${S[@]}" --g "$(printf '9.8\r')"
refuse  r2p-save-every-float  save-every    -- "${S[@]}" --save-every 1.5
refuse  r2p-save-every-big    save-every    -- "${S[@]}" --save-every 99999999999
refuse  r2p-links-tab         links         -- "${S[@]}" --links "3${TAB}"
refuse  r2p-max-steps-junk    max-steps     -- "${S[@]}" --max-steps 10k
refuse  r2p-damping-semicolon damping       -- "${S[@]}" --damping '0.1;0.2'
refuse  r2p-support-tab       support-amplitude -- "${S[@]}" --support-amplitude "0.1${TAB},0"
refuse  r2p-lyapunov-tau      tau           -- lyapunov --t-end 0.01 --output o.h5 --tau '1;2'
refuse  r2p-sweep-min1-tab    min1          -- sweep --output s.h5 --min1 "0.5${TAB}"
refuse  r2p-sweep-n1-junk     n1            -- sweep --output s.h5 --n1 8x
refuse  r2p-fit-window-semi   fit-window    -- fit r2p_fit_ok.csv --output f.h5 --fit-window '1;2'
refuse  r2p-method-newline    method        -- "${S[@]}" --method "rk${NL}4"
refuse  r2p-option-newline    unknown       -- "${S[@]}" "--d${NL}t" 1
succeed r2p-valid-forms          -- "${S[@]}" --force --dt .5e-3 --q1 -1.5 --q2 5. --w1 +0 --g 9.81e0
succeed r2p-valid-list           -- "${S[@]}" --force --links 3 --q 0.5,-.25,1D-1 --m 1,2,3e0
# ---- namelist files read strictly
refuse  r2p-nml-percent       'component syntax' -- "${S[@]}" --config r2p_percent.nml
refuse  r2p-nml-repeat        'given twice'      -- "${S[@]}" --config r2p_repeat.nml
refuse  r2p-nml-forms-m       'two forms'        -- "${S[@]}" --config r2p_forms_m.nml
refuse  r2p-nml-forms-q       'two forms'        -- "${S[@]}" --config r2p_forms_q.nml
refuse  r2p-nml-forms-l       'two forms'        -- "${S[@]}" --config r2p_forms_l.nml
refuse  r2p-nml-forms-w       'two forms'        -- "${S[@]}" --config r2p_forms_w.nml
refuse  r2p-nml-subscript     'given twice'      -- "${S[@]}" --config r2p_subscript_whole.nml
refuse  r2p-nml-semicolon     'not a number'     -- "${S[@]}" --config r2p_semicolon.nml
refuse  r2p-nml-long-mantissa 'largest double'   -- "${S[@]}" --config r2p_long_mantissa.nml
refuse  r2p-nml-hex           'not a number'     -- "${S[@]}" --config r2p_hex.nml
refuse  r2p-nml-nan           'not finite'       -- "${S[@]}" --config r2p_nan.nml
refuse  r2p-nml-chaos-semi    'not a number'     -- lyapunov --config r2p_chaos_semicolon.nml --output o.h5
refuse  r2p-nml-sweep-repeat  'given twice'      -- sweep --config r2p_sweep_repeat.nml --output s.h5
refuse  r2p-nml-study-repeat  'given twice'      -- study --config r2p_study_repeat.nml --output s.md
succeed r2p-nml-long-ok          -- "${S[@]}" --config r2p_long_ok.nml --force
succeed r2p-nml-valid            -- simulate --config r2p_valid.nml
for _v in false. .true .tx. t. yes; do
  refuse "r2p-nml-logical-$_v" 'same_energy' -- lyapunov --config "r2p_logical_$_v.nml" --tau 5e-3 --output o.h5
done
succeed r2p-nml-logical-dots     -- lyapunov --config r2p_logical_ok1.nml --output o1.h5
succeed r2p-nml-logical-word     -- lyapunov --config r2p_logical_ok2.nml --output o2.h5
refuse  r2p-study-case-noname  'case_name(1)' -- study --config r2p_study_noname.nml --output s.md
refuse  r2p-study-case-noname2 'case_name(2)' -- study --config r2p_study_noname2.nml --output s.md
refuse  r2p-study-range-nomethod 'method(2)'  -- study --config r2p_study_range.nml --output s.md
refuse  r2p-study-ro-dt-nomethod 'ro_dt(3)'   -- study --config r2p_study_ro_dt.nml --output s.md
refuse  r2p-study-tao-gap      'tao_method(1)' -- study --config r2p_study_tao_gap.nml --output s.md
refuse  r2p-nml-gap-m          'm(2)'         -- "${S[@]}" --config r2p_gap_m.nml
refuse  r2p-nml-gap-q          'q(3)'         -- "${S[@]}" --config r2p_gap_q.nml
refuse  r2p-nml-gap-damping    'damping(2)'   -- "${S[@]}" --config r2p_gap_damping.nml
refuse  r2p-nml-gap-com        'com(2)'       -- "${S[@]}" --config r2p_gap_com.nml
succeed r2p-nml-gap-ok            -- "${S[@]}" --force --config r2p_gap_ok.nml
refuse  r2p-nml-quoted-number  't_end'        -- simulate --config r2p_quoted_number.nml --output o.h5
succeed r2p-nml-quoted-body       -- simulate --config r2p_quoted_body.nml --output o4.h5
# ---- two forms of one quantity on the command line (a flag over a file stays)
refuse  r2p-flags-m-m1        m1            -- "${S[@]}" --m 1,2 --m1 3
refuse  r2p-flags-m1-m        m             -- "${S[@]}" --m1 3 --m 1,2
refuse  r2p-flags-q1-theta1   theta1        -- "${S[@]}" --q1 1 --theta1 0.5
refuse  r2p-flags-q-theta2    theta2        -- "${S[@]}" --q 1,1 --theta2 0.5
refuse  r2p-flags-l2-l        l             -- "${S[@]}" --l2 2 --l 1,1
refuse  r2p-flags-w-w1        w1            -- "${S[@]}" --w 0,0 --w1 1
refuse  r2p-flags-sweep-m-m1  m1            -- sweep --output s.h5 --m 1,2 --m1 3
succeed r2p-flag-over-file       -- "${S[@]}" --force --config r2p_file_list.nml --m1 3
refuse  r2p-flag-repeated   q1   -- "${S[@]}" --force --q1 1 --q1 2
# ---- one range table: g = 0 refused by every command
refuse  r2p-g0-sweep-3        g             -- sweep --output s.h5 --links 3 --g 0
refuse  r2p-g0-sweep-1-s      g             -- sweep --output s.h5 --links 1 --g 0 --time-unit s
refuse  r2p-g0-simulate-1     g             -- "${S[@]}" --links 1 --g 0
refuse  r2p-g0-simulate-2     g             -- "${S[@]}" --g 0
refuse  r2p-g0-simulate-3     g             -- "${S[@]}" --links 3 --g 0
refuse  r2p-g-tiny-simulate-3 g             -- "${S[@]}" --links 3 --g 1e-7
refuse  r2p-g0-lyapunov-3     g             -- lyapunov --t-end 0.01 --output o.h5 --links 3 --g 0
refuse  r2p-g0-study          g             -- study --output s.md --g 0
refuse  r2p-g0-fit            g             -- fit r2p_fit_ok.csv --output f.h5 --g 0
refuse  r2p-g0-fit-links-2    g             -- fit r2p_fit_ok.csv --output f.h5 --links 2 --g 0
# ---- CSV fields through the strict parser
refuse  r2p-csv-junk          'line 3'      -- fit r2p_fit_junk.csv --output f.h5
refuse  r2p-csv-blank         'line 3'      -- fit r2p_fit_blank.csv --output f.h5
refuse  r2p-csv-hex           'line 3'      -- fit r2p_fit_hex.csv --output f.h5
# ---- sweep: a list's options without the list
refuse  r2p-ic-angles-no-file ic_angles     -- sweep --output s.h5 --ic-angles theta
refuse  r2p-ic-dataset-no-file ic_dataset   -- sweep --output s.h5 --ic-dataset /x
refuse  r2p-ic-angles-nml     ic_angles     -- sweep --output s.h5 --config r2p_sweep_ic_angles.nml
# ---- sweep: the text list of initial conditions through the strict parser
refuse  r2p-list-huge         ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file r2p_list_huge.txt
refuse  r2p-list-semicolon    ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file r2p_list_semicolon.txt
refuse  r2p-list-hex          ic_file       -- sweep --output s.h5 --t-end 0.01 --ic-file r2p_list_hex.txt
succeed r2p-list-ok              -- sweep --output s.h5 --t-end 0.01 --quiet --ic-file r2p_list_ok.txt
