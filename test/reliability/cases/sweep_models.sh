# dpend sweep and the model factory: models only from new_model, and the
# elastic pendulum on the per-trajectory path (docs/sweep.md, "Other models"). Its
# flip map does not apply and is refused in one line; an indicator map over (r, phi)
# and a list of states succeed without a trap in the debug build.

printf '1.2 -1.0 0 0\n1.3 -1.5 0.1 0\n' > "$FIXTURES/swm_list.txt"
printf '1.2 -1.0 0 0\n0 -1.5 0 0\n' > "$FIXTURES/swm_list_collapsed.txt"
E=(sweep --model elastic --q 1.2,-1.0 --n 3 --t-end 1 --quiet --output e.h5)
# a list gives every initial state: no --q beside it (a dummy one was needed before)
EL=(sweep --model elastic --n 3 --t-end 1 --quiet --output e.h5)
# ---- what the elastic pendulum refuses
refuse  swm-el-flip-map         indicator     -- "${E[@]}"
refuse  swm-el-flip-explicit    indicator     -- "${E[@]}" --indicator flip
refuse  swm-el-lyapunov         lyapunov      -- "${E[@]}" --indicator megno --lyapunov
refuse  swm-el-lambda1          indicator     -- "${E[@]}" --indicator lambda1
refuse  swm-el-theta-axis       axis1         -- "${E[@]}" --indicator megno --axis1 theta1 --axis2 r
refuse  swm-el-default-axes     axis1         -- "${E[@]}" --indicator megno
refuse  swm-el-param-axis       axis1         -- "${E[@]}" --indicator megno --axis1 m2/m1 --min1 1 --max1 2
refuse  swm-el-unknown-axis     axis2         -- "${E[@]}" --indicator megno --axis1 r --axis2 rho
refuse  swm-el-same-axis        axis2         -- "${E[@]}" --indicator megno --axis1 r --axis2 q1
refuse  swm-el-r-collapsed      'min1, max1'  -- "${E[@]}" --indicator megno --axis1 r --min1 0 --max1 1.5 --axis2 phi
refuse  swm-el-r-nan            min1          -- "${E[@]}" --indicator megno --axis1 r --min1 nan --max1 1.5 --axis2 phi
refuse  swm-el-fixed-r-zero     q1            -- sweep --model elastic --indicator megno --n 3 --t-end 1 --quiet --output e.h5
refuse  swm-el-ic-theta         ic_angles     -- "${EL[@]}" --indicator megno --ic-file swm_list.txt --ic-angles theta
refuse  swm-el-ic-collapsed     ic_file       -- "${EL[@]}" --indicator megno --ic-file swm_list_collapsed.txt
refuse  swm-el-links            links         -- "${E[@]}" --indicator megno --links 3
refuse  swm-el-method           method        -- "${E[@]}" --indicator megno --method verlet
# ---- edge values that must succeed
succeed swm-el-megno-r-phi      -- "${E[@]}" --indicator megno --axis1 r --min1 0.8 --max1 1.6 --axis2 phi --min2 -2.5 --max2 -0.6
succeed swm-el-fli-rates        -- "${E[@]}" --indicator fli --axis1 rdot --axis2 phidot
succeed swm-el-sali-q-w         -- "${E[@]}" --indicator sali --axis1 q1 --min1 1 --max1 1.4 --axis2 w2
succeed swm-el-gali2-seconds    -- "${E[@]}" --indicator gali2 --time-unit s --stats --axis1 phi --min1 -2 --max1 -1 --axis2 w1
succeed swm-el-list             -- "${EL[@]}" --indicator megno --ic-file swm_list.txt
succeed swm-el-config           -- sweep --config elastic_sweep.nml --n 3 --t-end 1 --quiet --output e.h5
# ---- parameter axes of other bodies and models: point masses over the mass and
# length axes, the elastic pendulum over its own parameters (and beside r)
succeed swm-point-ratios-ok   -- sweep --output s.h5 --quiet --body point --axis1 m2/m1 --axis2 l2/l1 --min1 0.5 --max1 2 --min2 0.5 --max2 2 --n 3 --t-end 1 --q1 0.3
succeed swm-elastic-k-l0-ok   -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --axis1 k --axis2 l0 --min1 20 --max1 60 --min2 0.5 --max2 1.5 --n 3 --t-end 1 --indicator megno
succeed swm-elastic-r-k-ok    -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --axis1 r --axis2 k --min1 1 --max1 1.5 --min2 20 --max2 60 --n 3 --t-end 1 --indicator fli
refuse  swm-elastic-k-fixed   "invalid k: axis1 'k' sweeps the value it fixes" -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --k 30 --axis1 k --axis2 l0 --min1 20 --max1 60 --min2 0.5 --max2 1.5 --n 3 --t-end 1 --indicator megno
refuse  swm-elastic-k-range   'invalid min1, max1, min2, max2: the pixel at' -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --axis1 k --axis2 l0 --min1 -5 --max1 60 --min2 0.5 --max2 1.5 --n 3 --t-end 1 --indicator megno
refuse  swm-elastic-same-axis "invalid axis2: 'k' sweeps the same value" -- sweep --output s.h5 --quiet --model elastic --q 1.2,-1 --axis1 k --axis2 k --min1 20 --max1 60 --min2 20 --max2 60 --n 3 --t-end 1 --indicator megno
refuse  swm-com-ratio         'invalid axis1, axis2: a mass or length axis sweeps uniform rods or point masses only' -- sweep --output s.h5 --quiet --com 0.4,0.4 --axis1 m2/m1 --axis2 l2/l1 --min1 0.5 --max1 2 --min2 0.5 --max2 2 --n 3 --t-end 1
refuse  swm-list-with-q       'invalid q: given with ic_file' -- "${EL[@]}" --indicator megno --ic-file swm_list.txt --q 1.2,-1
refuse  swm-pend-list-with-q  'invalid q: given with ic_file' -- sweep --ic-file swm_list.txt --q 1,1 --t-end 1 --quiet --output p.h5
# ---- the pendulum's other parameters by name (per-trajectory path, any body):
# g, com_k, inertia_k, m_k and l_k beyond the coded axes; ranges from the catalogue
succeed swm-named-g-theta1-ok     -- sweep --output s.h5 --quiet --axis1 g --min1 1 --max1 10 --axis2 theta1 --n 3 --t-end 1
succeed swm-named-com-inertia-ok  -- sweep --output s.h5 --quiet --com 0.4,0.6 --inertia 0.1,0.05 --axis1 com1 --min1 0.1 --max1 0.9 --axis2 inertia2 --min2 0 --max2 0.2 --n 3 --t-end 1
succeed swm-named-point-g-ok      -- sweep --output s.h5 --quiet --body point --axis1 theta2 --axis2 g --min2 2 --max2 20 --n 3 --t-end 1
succeed swm-named-ratio-g-ok      -- sweep --output s.h5 --quiet --axis1 m2/m1 --min1 0.5 --max1 2 --axis2 g --min2 4 --max2 16 --n 3 --t-end 1 --indicator megno
succeed swm-named-m3-ok           -- sweep --output s.h5 --quiet --links 3 --axis1 m3 --min1 0.5 --max1 2 --axis2 l3 --min2 0.5 --max2 2 --n 3 --t-end 1
refuse  swm-named-g-range         'invalid min1, max1, min2, max2: the pixel at (0, -3) is refused: invalid g: 0 m/s^2 is outside' -- sweep --output s.h5 --quiet --axis1 g --min1 0 --max1 10 --n 3 --t-end 1
refuse  swm-named-inertia-range   'invalid inertia2: -1 kg m^2 is outside' -- sweep --output s.h5 --quiet --axis1 inertia2 --min1 -1 --max1 1 --n 3 --t-end 1
refuse  swm-named-g-fixed         "invalid g: axis1 'g' sweeps the value it fixes" -- sweep --output s.h5 --quiet --g 3 --axis1 g --min1 1 --max1 2 --n 3 --t-end 1
refuse  swm-named-same-axis       "invalid axis2: 'g' sweeps the same value" -- sweep --output s.h5 --quiet --axis1 g --axis2 g --min1 1 --max1 2 --min2 1 --max2 2 --n 3 --t-end 1
refuse  swm-named-damping         "invalid axis1: 'damping1'" -- sweep --output s.h5 --quiet --axis1 damping1 --min1 0 --max1 1 --n 3 --t-end 1
refuse  swm-named-m3-two-links    "invalid axis1: 'm3'" -- sweep --output s.h5 --quiet --axis1 m3 --min1 1 --max1 2 --n 3 --t-end 1
