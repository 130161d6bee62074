# `dpend fit` and CSV input, issue 24 (round 2): the fit's work and memory are bounded
# before it starts (refused in one line naming the fit work, its value and the limit,
# exit 2, no file touched), its time options are within the documented ranges, and
# CSV files as spreadsheets write them (BOM, quoted headers, ';' or tab separators)
# are accepted; what is still refused names the real cause.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
fx fit2_far.csv       't,theta1\n0,0.1\n1e8,0.09\n2e8,0.06\n3e8,0.02\n'
fx fit2_ok.csv        't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
# the same samples as spreadsheets write them (reproducer 12 of issue 24)
fx fit2_bom.csv       '\xef\xbb\xbft,theta1\r\n0,0.1\r\n0.1,0.09\r\n0.2,0.06\r\n0.3,0.02\r\n0.4,-0.03\r\n'
fx fit2_quoted.csv    '"t","theta1"\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
fx fit2_tab.csv       't\ttheta1\n0\t0.1\n0.1\t0.09\n0.2\t0.06\n0.3\t0.02\n0.4\t-0.03\n'
fx fit2_semi.csv      't;theta1\n0;0.1\n0.1;0.09\n0.2;0.06\n0.3;0.02\n0.4;-0.03\n'
fx fit2_sheet.csv     '\xef\xbb\xbf"t [s]";"theta1 [rad]"\r\n0;"0.1"\r\n0.1;0.09\r\n0.2;0.06\r\n0.3;0.02\r\n0.4;-0.03\r\n'
# still refused, naming the real cause
fx fit2_one_field.csv 't theta1\n0 0.1\n'
fx fit2_semi_no_t.csv '\xef\xbb\xbftime;theta1\n0;0.1\n'
fx fit2_open_quote.csv '"t,theta1\n0,0.1\n'
fx fit2_after_quote.csv '"t"x,theta1\n0,0.1\n'
fx fit2_utf16.csv     '\xff\xfet\x00,\x00t\x00'
fx fit2_dec_comma.csv 't;theta1\n0;0,1\n0.1;0,09\n0.2;0,06\n'
fx fit2_ctl_value.csv 't,theta1\n0,0.1\n0.1,"0.\n1"\n'
fx fit2_ctl_unit.csv  't,theta1 [r\001ad]\n0,0.1\n'
fx fit2_semi_value.csv 't,theta1\n0,0.1\n0.1,0.1;2\n0.2,0.06\n'

F=(fit --output g.h5)
# ---- bounded work (reproducer 2 of issue 24)
refuse  fit2-far-samples        'fit work'      -- "${F[@]}" fit2_far.csv
refuse  fit2-far-samples-damping 'fit work'     -- "${F[@]}" fit2_far.csv --fit-damping
refuse  fit2-far-samples-starts 'fit work'      -- "${F[@]}" fit2_far.csv --starts 1000
refuse  fit2-window-huge        'fit-window'    -- "${F[@]}" fit2_ok.csv --fit-window 1e300
refuse  fit2-window-beyond-max  'fit-window'    -- "${F[@]}" fit2_ok.csv --fit-window 1.1e9
refuse  fit2-window-inf         'fit-window'    -- "${F[@]}" fit2_ok.csv --fit-window inf
refuse  fit2-rk4-tiny-dt        'fit work'      -- "${F[@]}" fit2_ok.csv --method rk4 --dt 1e-9
succeed fit2-window-at-max                      -- "${F[@]}" fit2_ok.csv --fit-window 1e9
succeed fit2-far-window-first                   -- "${F[@]}" fit2_ok.csv --fit-window 0.3
# ---- CSV from spreadsheets: accepted (the unit test estimate/command_csv_forms checks
# that the report equals the comma file's)
succeed fit2-csv-bom                            -- "${F[@]}" fit2_bom.csv
succeed fit2-csv-quoted                         -- "${F[@]}" fit2_quoted.csv
succeed fit2-csv-tab                            -- "${F[@]}" fit2_tab.csv
succeed fit2-csv-semicolon                      -- "${F[@]}" fit2_semi.csv
succeed fit2-csv-sheet                          -- "${F[@]}" fit2_sheet.csv
# ---- still refused: the message names the real cause, one line
refuse  fit2-csv-one-field      'separators tried' -- "${F[@]}" fit2_one_field.csv
refuse  fit2-csv-no-t-listed    "among the 2 fields 'time'" -- "${F[@]}" fit2_semi_no_t.csv
refuse  fit2-csv-open-quote     'not closed'    -- "${F[@]}" fit2_open_quote.csv
refuse  fit2-csv-after-quote    'after the quote' -- "${F[@]}" fit2_after_quote.csv
refuse  fit2-csv-utf16          'UTF-16'        -- "${F[@]}" fit2_utf16.csv
refuse  fit2-csv-decimal-comma  'decimal comma' -- "${F[@]}" fit2_dec_comma.csv
refuse  fit2-csv-newline-value  'not closed'    -- "${F[@]}" fit2_ctl_value.csv
refuse  fit2-csv-control-unit   "'[r\\x01ad]'"  -- "${F[@]}" fit2_ctl_unit.csv
refuse  fit2-csv-semicolon-value "'0.1;2' is not a number" -- "${F[@]}" fit2_semi_value.csv
refuse  fit2-csv-newline-name   'file'          -- "${F[@]}" "$(printf 'a\nb.csv')"
