# dpend sweep and the model factory: models only from new_model, and the
# elastic pendulum on the per-trajectory path (docs/sweep.md, "Other models"). Its
# flip map does not apply and is refused in one line; an indicator map over (r, phi)
# and a list of states succeed without a trap in the debug build.

printf '1.2 -1.0 0 0\n1.3 -1.5 0.1 0\n' > "$FIXTURES/swm_list.txt"
printf '1.2 -1.0 0 0\n0 -1.5 0 0\n' > "$FIXTURES/swm_list_collapsed.txt"
E=(sweep --model elastic --q 1.2,-1.0 --n 3 --t-end 1 --quiet --output e.h5)
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
refuse  swm-el-ic-theta         ic_angles     -- "${E[@]}" --indicator megno --ic-file swm_list.txt --ic-angles theta
refuse  swm-el-ic-collapsed     ic_file       -- "${E[@]}" --indicator megno --ic-file swm_list_collapsed.txt
refuse  swm-el-links            links         -- "${E[@]}" --indicator megno --links 3
refuse  swm-el-method           method        -- "${E[@]}" --indicator megno --method verlet
# ---- edge values that must succeed
succeed swm-el-megno-r-phi      -- "${E[@]}" --indicator megno --axis1 r --min1 0.8 --max1 1.6 --axis2 phi --min2 -2.5 --max2 -0.6
succeed swm-el-fli-rates        -- "${E[@]}" --indicator fli --axis1 rdot --axis2 phidot
succeed swm-el-sali-q-w         -- "${E[@]}" --indicator sali --axis1 q1 --min1 1 --max1 1.4 --axis2 w2
succeed swm-el-gali2-seconds    -- "${E[@]}" --indicator gali2 --time-unit s --stats --axis1 phi --min1 -2 --max1 -1 --axis2 w1
succeed swm-el-list             -- "${E[@]}" --indicator megno --ic-file swm_list.txt
succeed swm-el-config           -- sweep --config elastic_sweep.nml --n 3 --t-end 1 --quiet --output e.h5
