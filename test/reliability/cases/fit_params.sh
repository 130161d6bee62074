# `dpend fit` of physical parameters: --fit-param NAME,... (synonym
# of --fit-parameters) fits any parameter of the model by name or component (m2, l2,
# g, c2); sets the data cannot determine are refused in one line naming the
# combination (the mass scale before any work, a parameter without effect after the
# fit, nothing written); --sigma gives the noise of the misfit warning; CSV angle
# columns in degrees.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
cp "$ROOT/data/fit_mass_length.csv" "$FIXTURES/fitp_ml.csv"
# the first 100 samples of it, as theta in degrees (x 180/pi, 9 digits) with a rate column
awk -F, 'BEGIN { OFS = ","
   print "t [s],theta1 [deg],theta2 [deg],thetadot1 [deg/s]" }
   /^[0-9]/ && n < 100 { n++; printf "%s,%.9f,%.9f,0\n", $1, $2 * 57.29577951308232,
   $3 * 57.29577951308232 }' "$ROOT/data/fit_mass_length.csv" > "$FIXTURES/fitp_deg.csv"
fx fitp_qdeg.csv   't,q1 [deg],q2 [deg]\n0,-30,-60\n0.1,-31,-59\n0.2,-33,-57\n0.3,-36,-55\n0.4,-40,-52\n'
fx fitp_grad.csv   't,theta1 [grad]\n0,0.1\n0.1,0.09\n0.2,0.06\n'
fx fitp_el_deg.csv 't [s],r [m],phi [deg]\n0,1.2,-57.2957795\n0.05,1.2003236,-57.6112787\n0.1,1.2014768,-58.5513936\n0.15,1.2041019,-60.0967524\n0.2,1.2096028,-62.2152868\n0.25,1.2197855,-64.8590115\n0.3,1.2363776,-67.9646834\n'
fx fitp_el_rdeg.csv 't,r [deg],phi\n0,1.2,-1\n0.1,1.2,-1\n'

F=(fit --output g.h5)
E=(fit --output g.h5 --model elastic)
# ---- runs
succeed fitp-default-misfit        -- "${F[@]}" fitp_ml.csv
succeed fitp-m2-l2                 -- "${F[@]}" fitp_ml.csv --fit-param m2,l2
succeed fitp-synonym               -- "${F[@]}" fitp_ml.csv --fit-parameters l2,m2 --sigma 0.01
succeed fitp-g                     -- "${F[@]}" fitp_deg.csv --fit-param g
succeed fitp-component-c2          -- "${F[@]}" fitp_deg.csv --fit-param c2 --damping 0,0.01
succeed fitp-m-with-damping        -- "${F[@]}" fitp_deg.csv --fit-param m1 --damping 0.02,0.01
succeed fitp-deg-theta             -- "${F[@]}" fitp_deg.csv
succeed fitp-deg-q                 -- "${F[@]}" fitp_qdeg.csv
succeed fitp-deg-elastic-phi       -- "${E[@]}" fitp_el_deg.csv
succeed fitp-elastic-m             -- "${E[@]}" fitp_el_deg.csv --fit-param m
# ---- refusals: what the data cannot determine, names, --sigma, units
refuse  fitp-mass-scale     'fit parameters'  -- "${F[@]}" fitp_ml.csv --fit-param m1,m2
refuse  fitp-mass-all       'fit parameters'  -- "${F[@]}" fitp_ml.csv --fit-param m
refuse  fitp-mass-damping   'fit parameters'  -- "${F[@]}" fitp_ml.csv --fit-param m,damping \
    --damping 0.1,0.1
refuse  fitp-elastic-m-k    'fit parameters'  -- "${E[@]}" fitp_el_deg.csv --fit-param m,k
refuse  fitp-length-scale  'fit parameters'  -- "${F[@]}" fitp_deg.csv --fit-param l,g --quiet
refuse  fitp-no-effect      'fit parameters'  -- "${F[@]}" fitp_qdeg.csv --fit-param support_phase1
refuse  fitp-links          'fit parameter'   -- "${F[@]}" fitp_qdeg.csv --fit-param links
refuse  fitp-unknown        'fit parameter'   -- "${F[@]}" fitp_qdeg.csv --fit-param mass
refuse  fitp-component-3    'fit parameter'   -- "${F[@]}" fitp_qdeg.csv --fit-param m3
refuse  fitp-component-0    'fit parameter'   -- "${F[@]}" fitp_qdeg.csv --fit-param l0
refuse  fitp-scalar-index   'fit parameter'   -- "${F[@]}" fitp_qdeg.csv --fit-param g1
refuse  fitp-component-twice 'fit parameters' -- "${F[@]}" fitp_qdeg.csv --fit-param l,l2
refuse  fitp-param-empty    'fit-parameters'  -- "${F[@]}" fitp_qdeg.csv --fit-param l2,
refuse  fitp-param-missing  'fit-param'       -- "${F[@]}" fitp_qdeg.csv --fit-param
refuse  fitp-sigma-zero     'sigma'           -- "${F[@]}" fitp_qdeg.csv --sigma 0
refuse  fitp-sigma-negative 'sigma'           -- "${F[@]}" fitp_qdeg.csv --sigma -0.01
refuse  fitp-sigma-text     'sigma'           -- "${F[@]}" fitp_qdeg.csv --sigma 1e-2x
refuse  fitp-sigma-nan      'sigma'           -- "${F[@]}" fitp_qdeg.csv --sigma nan
refuse  fitp-sigma-huge     'sigma'           -- "${F[@]}" fitp_qdeg.csv --sigma 1e300
refuse  fitp-deg-grad       'unit'            -- "${F[@]}" fitp_grad.csv
refuse  fitp-deg-r          'unit'            -- "${E[@]}" fitp_el_rdeg.csv
# ---- data that cannot see a parameter: at rest in the hanging position, no
# parameter acts (each column of sensitivities is rounding error, which scaling the
# columns to unit length made look determined: m2 = 1 ± 0.27 kg, condition 2.7)
printf 't,q1,q2\n' > "$FIXTURES/fitp_rest.csv"
for i in 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
  printf '%s,-1.5707963267948966,-1.5707963267948966\n' "$(awk -v i=$i 'BEGIN { printf "%.1f", i / 10 }')" \
    >> "$FIXTURES/fitp_rest.csv"
done
R=(fit fitp_rest.csv --output r.h5)
refuse  fitp-rest-m2        'm2 is not determined by the data'       -- "${R[@]}" --fit-param m2
refuse  fitp-rest-l2        'l2 is not determined by the data'       -- "${R[@]}" --fit-param l2
refuse  fitp-rest-g         'g is not determined by the data'        -- "${R[@]}" --fit-param g
refuse  fitp-rest-damping   'c1, c2 are not determined by the data'  -- "${R[@]}" --fit-param damping
refuse  fitp-rest-sigma     'less than the noise 0.01 rad (given by --sigma)' -- "${R[@]}" \
    --fit-param m2 --sigma 0.01
succeed fitp-rest-state     -- "${R[@]}"
