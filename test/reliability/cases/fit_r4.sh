# `dpend fit` of physical parameters (issue 26, round 4): --fit-param NAME,... (synonym
# of --fit-parameters) fits any parameter of the model by name or component (m2, l2,
# g, c2); sets the data cannot determine are refused in one line naming the
# combination (the mass scale before any work, a parameter without effect after the
# fit, nothing written); --sigma gives the noise of the misfit warning; CSV angle
# columns in degrees.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
cp "$ROOT/data/fit_mass_length.csv" "$FIXTURES/r4_ml.csv"
# the first 100 samples of it, as theta in degrees (x 180/pi, 9 digits) with a rate column
awk -F, 'BEGIN { OFS = ","
   print "t [s],theta1 [deg],theta2 [deg],thetadot1 [deg/s]" }
   /^[0-9]/ && n < 100 { n++; printf "%s,%.9f,%.9f,0\n", $1, $2 * 57.29577951308232,
   $3 * 57.29577951308232 }' "$ROOT/data/fit_mass_length.csv" > "$FIXTURES/r4_deg.csv"
fx r4_qdeg.csv   't,q1 [deg],q2 [deg]\n0,-30,-60\n0.1,-31,-59\n0.2,-33,-57\n0.3,-36,-55\n0.4,-40,-52\n'
fx r4_grad.csv   't,theta1 [grad]\n0,0.1\n0.1,0.09\n0.2,0.06\n'
fx r4_el_deg.csv 't [s],r [m],phi [deg]\n0,1.2,-57.2957795\n0.05,1.2003236,-57.6112787\n0.1,1.2014768,-58.5513936\n0.15,1.2041019,-60.0967524\n0.2,1.2096028,-62.2152868\n0.25,1.2197855,-64.8590115\n0.3,1.2363776,-67.9646834\n'
fx r4_el_rdeg.csv 't,r [deg],phi\n0,1.2,-1\n0.1,1.2,-1\n'

F=(fit --output g.h5)
E=(fit --output g.h5 --model elastic)
# ---- runs
succeed fitr4-default-misfit        -- "${F[@]}" r4_ml.csv
succeed fitr4-m2-l2                 -- "${F[@]}" r4_ml.csv --fit-param m2,l2
succeed fitr4-synonym               -- "${F[@]}" r4_ml.csv --fit-parameters l2,m2 --sigma 0.01
succeed fitr4-g                     -- "${F[@]}" r4_deg.csv --fit-param g
succeed fitr4-component-c2          -- "${F[@]}" r4_deg.csv --fit-param c2 --damping 0,0.01
succeed fitr4-m-with-damping        -- "${F[@]}" r4_deg.csv --fit-param m1 --damping 0.02,0.01
succeed fitr4-deg-theta             -- "${F[@]}" r4_deg.csv
succeed fitr4-deg-q                 -- "${F[@]}" r4_qdeg.csv
succeed fitr4-deg-elastic-phi       -- "${E[@]}" r4_el_deg.csv
succeed fitr4-elastic-m             -- "${E[@]}" r4_el_deg.csv --fit-param m
# ---- refusals: what the data cannot determine, names, --sigma, units
refuse  fitr4-mass-scale     'fit parameters'  -- "${F[@]}" r4_ml.csv --fit-param m1,m2
refuse  fitr4-mass-all       'fit parameters'  -- "${F[@]}" r4_ml.csv --fit-param m
refuse  fitr4-mass-damping   'fit parameters'  -- "${F[@]}" r4_ml.csv --fit-param m,damping \
    --damping 0.1,0.1
refuse  fitr4-elastic-m-k    'fit parameters'  -- "${E[@]}" r4_el_deg.csv --fit-param m,k
refuse  fitr4-length-scale  'fit parameters'  -- "${F[@]}" r4_deg.csv --fit-param l,g
refuse  fitr4-no-effect      'fit parameters'  -- "${F[@]}" r4_qdeg.csv --fit-param support_phase1
refuse  fitr4-links          'fit parameter'   -- "${F[@]}" r4_qdeg.csv --fit-param links
refuse  fitr4-unknown        'fit parameter'   -- "${F[@]}" r4_qdeg.csv --fit-param mass
refuse  fitr4-component-3    'fit parameter'   -- "${F[@]}" r4_qdeg.csv --fit-param m3
refuse  fitr4-component-0    'fit parameter'   -- "${F[@]}" r4_qdeg.csv --fit-param l0
refuse  fitr4-scalar-index   'fit parameter'   -- "${F[@]}" r4_qdeg.csv --fit-param g1
refuse  fitr4-component-twice 'fit parameters' -- "${F[@]}" r4_qdeg.csv --fit-param l,l2
refuse  fitr4-param-empty    'fit-parameters'  -- "${F[@]}" r4_qdeg.csv --fit-param l2,
refuse  fitr4-param-missing  'fit-param'       -- "${F[@]}" r4_qdeg.csv --fit-param
refuse  fitr4-sigma-zero     'sigma'           -- "${F[@]}" r4_qdeg.csv --sigma 0
refuse  fitr4-sigma-negative 'sigma'           -- "${F[@]}" r4_qdeg.csv --sigma -0.01
refuse  fitr4-sigma-text     'sigma'           -- "${F[@]}" r4_qdeg.csv --sigma 1e-2x
refuse  fitr4-sigma-nan      'sigma'           -- "${F[@]}" r4_qdeg.csv --sigma nan
refuse  fitr4-sigma-huge     'sigma'           -- "${F[@]}" r4_qdeg.csv --sigma 1e300
refuse  fitr4-deg-grad       'unit'            -- "${F[@]}" r4_grad.csv
refuse  fitr4-deg-r          'unit'            -- "${E[@]}" r4_el_rdeg.csv
