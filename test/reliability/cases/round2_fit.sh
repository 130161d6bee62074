# `dpend fit` and CSV input, issue 24 (round 2): the fit's work and memory are bounded
# before it starts (refused in one line naming the fit work, its value and the limit,
# exit 2, no file touched), its time options are within the documented ranges, and
# CSV files as spreadsheets write them (BOM, quoted headers, ';' or tab separators)
# are accepted; what is still refused names the real cause.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
fx fit2_far.csv       't,theta1\n0,0.1\n1e8,0.09\n2e8,0.06\n3e8,0.02\n'
fx fit2_ok.csv        't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'

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
