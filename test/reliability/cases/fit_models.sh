# `dpend fit` with a model other than the pendulum: the
# elastic pendulum fitted from its coordinates (t, r [m], phi [rad]), its spring by
# --fit-parameters k,l0; what the model cannot fit, columns of the wrong model and
# bad parameter lists refused in one line naming the field, before any work.

fx() { printf '%b' "$2" > "$FIXTURES/$1"; }
# (r, phi) of the elastic pendulum (m 1, k 40, l0 1, g 9.8) from r 1.2, phi -1 at rest
fx el_ok.csv      't [s],r [m],phi [rad]\n0,1.2,-1\n0.05,1.2003236,-1.0055065\n0.1,1.2014768,-1.0219146\n0.15,1.2041019,-1.0488862\n0.2,1.2096028,-1.0858616\n0.25,1.2197855,-1.1320033\n0.3,1.2363776,-1.1862075\n0.35,1.2602989,-1.2470805\n0.4,1.2912162,-1.3129244\n0.45,1.3274064,-1.3816966\n0.5,1.3660044,-1.4509773\n'
fx el_theta.csv   't,theta1,theta2\n0,0.1,0.2\n0.1,0.1,0.2\n0.2,0.1,0.2\n'
fx el_xy.csv      't,x1,y1\n0,0.6,-1\n0.1,0.6,-1\n0.2,0.6,-1\n'
fx el_cm.csv      't,r [cm],phi\n0,120,-1\n0.1,120,-1\n'
fx el_no_phi.csv  't,r\n0,1.2\n0.1,1.2\n'
fx el_dup.csv     't,r,phi,r\n0,1.2,-1,1.2\n'
fx el_two.csv     't,r,phi\n0,1.2,-1\n0.05,1.2003236,-1.0055065\n'
fx el_zero.csv    't,r,phi\n0,0,-1\n0.05,0,-1\n0.1,0,-1\n0.15,0,-1\n'
fx pend_ok.csv    't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n'

F=(fit --output g.h5)
E=(fit --output g.h5 --model elastic)
# ---- runs
succeed fitm-elastic-state          -- "${E[@]}" el_ok.csv
succeed fitm-elastic-spring         -- "${E[@]}" el_ok.csv --fit-parameters k,l0 --k 35 --l0 1.1
succeed fitm-elastic-window         -- "${E[@]}" el_ok.csv --fit-parameters l0 --fit-window 0.3
succeed fitm-pendulum-params-damping -- "${F[@]}" pend_ok.csv --fit-parameters damping
refuse  fitm-elastic-collapsed 'not a state of model elastic'  -- "${E[@]}" el_zero.csv
# ---- refusals: the model, its columns, the parameters
refuse  fitm-elastic-damping  'fit parameter'   -- "${E[@]}" el_ok.csv --fit-damping
refuse  fitm-elastic-m        'fit parameter'   -- "${E[@]}" el_ok.csv --fit-parameters m,k
refuse  fitm-pendulum-k       'fit parameter'   -- "${F[@]}" pend_ok.csv --fit-parameters m
refuse  fitm-params-empty     'fit-parameters'  -- "${E[@]}" el_ok.csv --fit-parameters k,,l0
refuse  fitm-params-twice     'fit-parameters'  -- "${E[@]}" el_ok.csv --fit-parameters k,k
refuse  fitm-params-odd       'fit-parameters'  -- "${E[@]}" el_ok.csv --fit-parameters 'k;rm'
refuse  fitm-params-missing   'fit-parameters'  -- "${E[@]}" el_ok.csv --fit-parameters
refuse  fitm-elastic-theta    'no columns r'    -- "${E[@]}" el_theta.csv
refuse  fitm-elastic-xy       'no columns r'    -- "${E[@]}" el_xy.csv
refuse  fitm-elastic-cm       'unit'            -- "${E[@]}" el_cm.csv
refuse  fitm-elastic-no-phi   'phi'             -- "${E[@]}" el_no_phi.csv
refuse  fitm-elastic-dup      'twice'           -- "${E[@]}" el_dup.csv
refuse  fitm-elastic-few      'samples'         -- "${E[@]}" el_two.csv
refuse  fitm-elastic-links    'links'           -- "${E[@]}" el_ok.csv --links 3
refuse  fitm-elastic-l-flag   ' l:'             -- "${E[@]}" el_ok.csv --l 2
refuse  fitm-elastic-l0       'l0'              -- "${E[@]}" el_ok.csv --l0 0
refuse  fitm-elastic-k-nan    'k'               -- "${E[@]}" el_ok.csv --k nan
refuse  fitm-model-unknown    'model'           -- "${F[@]}" pend_ok.csv --model nosuch
refuse  fitm-elastic-q-flag   'unknown'         -- "${E[@]}" el_ok.csv --q 1,2
