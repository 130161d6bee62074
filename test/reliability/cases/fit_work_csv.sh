# `dpend fit` and CSV input: the fit's work and memory are bounded
# before it starts (refused in one line naming the fit work, its value and the limit,
# exit 2, no file touched), its time options are within the documented ranges, and
# CSV files as spreadsheets write them (BOM, quoted headers, ';' or tab separators)
# are accepted; what is still refused names the real cause.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
fx fitw_far.csv       't,theta1\n0,0.1\n1e8,0.09\n2e8,0.06\n3e8,0.02\n'
fx fitw_ok.csv        't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
# the same samples as spreadsheets write them
fx fitw_bom.csv       '\xef\xbb\xbft,theta1\r\n0,0.1\r\n0.1,0.09\r\n0.2,0.06\r\n0.3,0.02\r\n0.4,-0.03\r\n'
fx fitw_quoted.csv    '"t","theta1"\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'
fx fitw_tab.csv       't\ttheta1\n0\t0.1\n0.1\t0.09\n0.2\t0.06\n0.3\t0.02\n0.4\t-0.03\n'
fx fitw_semi.csv      't;theta1\n0;0.1\n0.1;0.09\n0.2;0.06\n0.3;0.02\n0.4;-0.03\n'
fx fitw_sheet.csv     '\xef\xbb\xbf"t [s]";"theta1 [rad]"\r\n0;"0.1"\r\n0.1;0.09\r\n0.2;0.06\r\n0.3;0.02\r\n0.4;-0.03\r\n'
# still refused, naming the real cause
fx fitw_one_field.csv 't theta1\n0 0.1\n'
fx fitw_semi_no_t.csv '\xef\xbb\xbftime;theta1\n0;0.1\n'
fx fitw_open_quote.csv '"t,theta1\n0,0.1\n'
fx fitw_after_quote.csv '"t"x,theta1\n0,0.1\n'
fx fitw_utf16.csv     '\xff\xfet\x00,\x00t\x00'
fx fitw_dec_comma.csv 't;theta1\n0;0,1\n0.1;0,09\n0.2;0,06\n'
fx fitw_ctl_value.csv 't,theta1\n0,0.1\n0.1,"0.\n1"\n'
fx fitw_ctl_unit.csv  't,theta1 [r\001ad]\n0,0.1\n'
fx fitw_semi_value.csv 't,theta1\n0,0.1\n0.1,0.1;2\n0.2,0.06\n'

F=(fit --output g.h5)
# ---- bounded work
refuse  fitw-far-samples        'fit work'      -- "${F[@]}" fitw_far.csv
refuse  fitw-far-samples-damping 'fit work'     -- "${F[@]}" fitw_far.csv --fit-damping
refuse  fitw-far-samples-starts 'fit work'      -- "${F[@]}" fitw_far.csv --starts 1000
refuse  fitw-window-huge        'fit-window'    -- "${F[@]}" fitw_ok.csv --fit-window 1e300
refuse  fitw-window-beyond-max  'fit-window'    -- "${F[@]}" fitw_ok.csv --fit-window 1.1e9
refuse  fitw-window-inf         'fit-window'    -- "${F[@]}" fitw_ok.csv --fit-window inf
refuse  fitw-rk4-tiny-dt        'fit work'      -- "${F[@]}" fitw_ok.csv --method rk4 --dt 1e-9
succeed fitw-window-at-max                      -- "${F[@]}" fitw_ok.csv --fit-window 1e9
succeed fitw-far-window-first                   -- "${F[@]}" fitw_ok.csv --fit-window 0.3
# ---- CSV from spreadsheets: accepted (the unit test estimate/command_csv_forms checks
# that the report equals the comma file's)
succeed fitw-csv-bom                            -- "${F[@]}" fitw_bom.csv
succeed fitw-csv-quoted                         -- "${F[@]}" fitw_quoted.csv
succeed fitw-csv-tab                            -- "${F[@]}" fitw_tab.csv
succeed fitw-csv-semicolon                      -- "${F[@]}" fitw_semi.csv
succeed fitw-csv-sheet                          -- "${F[@]}" fitw_sheet.csv
# ---- still refused: the message names the real cause, one line
refuse  fitw-csv-one-field      'separators tried' -- "${F[@]}" fitw_one_field.csv
refuse  fitw-csv-no-t-listed    "among the 2 fields 'time'" -- "${F[@]}" fitw_semi_no_t.csv
refuse  fitw-csv-open-quote     'not closed'    -- "${F[@]}" fitw_open_quote.csv
refuse  fitw-csv-after-quote    'after the quote' -- "${F[@]}" fitw_after_quote.csv
refuse  fitw-csv-utf16          'UTF-16'        -- "${F[@]}" fitw_utf16.csv
refuse  fitw-csv-decimal-comma  'decimal comma' -- "${F[@]}" fitw_dec_comma.csv
refuse  fitw-csv-newline-value  'not closed'    -- "${F[@]}" fitw_ctl_value.csv
refuse  fitw-csv-control-unit   "'[r\\x01ad]'"  -- "${F[@]}" fitw_ctl_unit.csv
refuse  fitw-csv-semicolon-value "'0.1;2' is not a number" -- "${F[@]}" fitw_semi_value.csv
refuse  fitw-csv-newline-name   'file'          -- "${F[@]}" "$(printf 'a\nb.csv')"
