# Limits before work and no trap on extreme values (dpend_limits, docs/cli.md
# "Limits"): step and sample counts, memory and disk estimates, threads,
# --max-steps of the adaptive methods, tolerances, and the accepted ranges of
# every input of every command. Boundary values just inside a range succeed.

# fixtures: a list with an angle / a velocity out of range, study configs with
# values whose arithmetic would overflow or never end
printf '1e300 0 0 0\n' > "$FIXTURES/lim_list_angle.txt"
printf '0 0 0 1e7\n' > "$FIXTURES/lim_list_w.txt"
printf '&study\n  t_short = 1e300\n/\n' > "$FIXTURES/lim_study_tshort.nml"
printf '&study\n  ref_dt = 1e-300\n/\n' > "$FIXTURES/lim_study_refdt.nml"
printf "&study\n  case_name(1) = 'x', case_w1(1) = 1e150\n/\n" > "$FIXTURES/lim_study_w.nml"
printf '&study\n  atol_ratio = 1e300\n/\n' > "$FIXTURES/lim_study_atol.nml"
printf '&study\n  tao_dt = 1e-300\n/\n' > "$FIXTURES/lim_study_taodt.nml"
printf '&integration\n  max_steps = 0\n/\n' > "$FIXTURES/lim_maxsteps0.nml"
printf "&integration\n  method = 'dopri5', max_steps = 7, t_end = 5\n/\n" > "$FIXTURES/lim_maxsteps7.nml"

# ---- simulate: counts derived from reals
refuse  lim-sim-dt-1e-19        dt          -- simulate --t-end 1 --dt 1e-19
refuse  lim-sim-dt-1e999        dt          -- simulate --t-end 1 --dt 1e999
refuse  lim-sim-q1-neg-1e999    q1          -- simulate --t-end 1 --q1 -1e999
refuse  lim-sweep-param-max     max1        -- sweep --axis1 m2/m1 --min1 1 --max1 1e13 --axis2 theta1 --n 4 --output o.h5
refuse  lim-sim-dt-denormal     dt          -- simulate --dt 5e-324
refuse  lim-sim-dt-huge         dt          -- simulate --dt 1e300
refuse  lim-sim-outdt-1e-300    output_dt   -- simulate --t-end 1 --output-dt 1e-300
refuse  lim-sim-outdt-huge      output_dt   -- simulate --output-dt 1e300
refuse  lim-sim-save-every-mem  save_every  -- simulate --t-end 10 --dt 1e-9 --save-every 1
refuse  lim-sim-tend-huge       t_end       -- simulate --t-end 1e300
refuse  lim-sim-tend-above      t_end       -- simulate --t-end 1.1e9
# ---- simulate: tolerances and --max-steps of the adaptive methods
refuse  lim-sim-rtol-1e-300     rtol        -- simulate --method dopri5 --rtol 1e-300 --atol 1e-300
refuse  lim-sim-rtol-1e-15      rtol        -- simulate --method dop853 --rtol 1e-15
refuse  lim-sim-atol-1e-300     atol        -- simulate --method dopri5 --atol 1e-300
refuse  lim-sim-atol-10         atol        -- simulate --method dopri5 --atol 10
refuse  lim-sim-maxsteps-0      max_steps   -- simulate --method dopri5 --max-steps 0
refuse  lim-sim-maxsteps-huge   max_steps   -- simulate --max-steps 10000000000000
refuse  lim-sim-maxsteps-text   max-steps   -- simulate --max-steps abc
refuse  lim-sim-maxsteps-nml    max_steps   -- simulate --config lim_maxsteps0.nml
fail    lim-sim-maxsteps-stop   max-steps   -- simulate --method dopri5 --max-steps 10 -o lim_ms.h5
fail    lim-sim-maxsteps-853    max-steps   -- simulate --method dop853 --max-steps 3 -o lim_ms2.h5
fail    lim-sim-maxsteps-key    max-steps   -- simulate --config lim_maxsteps7.nml -o lim_ms3.h5
# ---- simulate: ranges that keep the arithmetic finite
refuse  lim-sim-m1-1e308        m1          -- simulate --m1 1e308
refuse  lim-sim-m2-1e-300       m2          -- simulate --m2 1e-300
refuse  lim-sim-l1-1e-300       l1          -- simulate --l1 1e-300
refuse  lim-sim-l2-1e200        l2          -- simulate --l2 1e200
refuse  lim-sim-g-1e300         g           -- simulate --g 1e300
refuse  lim-sim-g-denormal      g           -- simulate --g 1e-310
refuse  lim-sim-w1-1e150        w1          -- simulate --w1 1e150
refuse  lim-sim-w2-1e150        w2          -- simulate --w2 -1e150
refuse  lim-sim-w1-just-out     w1          -- simulate --w1 1.000001e6
refuse  lim-sim-q1-1e300        q1          -- simulate --q1 1e300
refuse  lim-sim-q2-1e7          q2          -- simulate --q2 -1e7
refuse  lim-sim-omega-1e300     omega       -- simulate --method tao2 --omega 1e300
# ---- simulate: just inside the ranges
succeed lim-sim-masses-bounds       -- simulate --m1 1e6 --m2 1e-6 --t-end 0.05 -o lim_b1.h5
succeed lim-sim-lengths-bounds      -- simulate --l1 1e6 --l2 1e6 --g 1e-6 --t-end 0.05 -o lim_b2.h5
succeed lim-sim-small-bounds        -- simulate --l1 1e-6 --l2 1e-6 --g 1e-6 --t-end 0.05 -o lim_b3.h5
succeed lim-sim-angles-bounds       -- simulate --q1 1e6 --q2 -1e6 --t-end 0.05 -o lim_b4.h5
succeed lim-sim-w-bounds            -- simulate --w1 1e6 --w2 -1e6 --t-end 1e-5 --dt 1e-8 -o lim_b5.h5
succeed lim-sim-rtol-min            -- simulate --method dop853 --rtol 1e-14 --atol 1e-16 --t-end 0.05 -o lim_b6.h5
succeed lim-sim-atol-min            -- simulate --method dopri5 --atol 1e-30 --t-end 0.05 -o lim_b7.h5
succeed lim-sim-atol-max            -- simulate --method dopri5 --atol 1 --t-end 0.05 -o lim_b8.h5
succeed lim-sim-dense-below-dt      -- simulate --method dopri5 --output-dt 1e-4 --t-end 0.01 -o lim_b9.h5
succeed lim-sim-dt-above-tend       -- simulate --dt 1e9 --t-end 0.01 -o lim_b10.h5
succeed lim-sim-tend-zero           -- simulate --t-end 0 -o lim_b11.h5
succeed lim-sim-maxsteps-enough     -- simulate --method dopri5 --max-steps 100000 --t-end 0.05 -o lim_b12.h5

# ---- lyapunov
refuse  lim-lya-dt-1e-300       dt          -- lyapunov --dt 1e-300
refuse  lim-lya-tau-1e-17       tau         -- lyapunov --tau 1e-17
refuse  lim-lya-tau-1e-17-dopri tau         -- lyapunov --method dopri5 --tau 1e-17
refuse  lim-lya-tau-below-dt    tau         -- lyapunov --tau 1e-4
refuse  lim-lya-tau-huge        tau         -- lyapunov --tau 1e300
refuse  lim-lya-m1-1e308        m1          -- lyapunov --m1 1e308
refuse  lim-lya-w2-1e150        w2          -- lyapunov --w2 1e150
refuse  lim-lya-l1-1e-300       l1          -- lyapunov --l1 1e-300
refuse  lim-lya-rtol-1e-300     rtol        -- lyapunov --method dop853 --rtol 1e-300 --atol 1e-300
refuse  lim-lya-tend-huge       t_end       -- lyapunov --t-end 1e300
refuse  lim-lya-maxsteps-neg    max_steps   -- lyapunov --method dopri5 --max-steps -5
fail    lim-lya-maxsteps-stop   max-steps   -- lyapunov --method dopri5 --max-steps 5 --t-end 1 -o lim_l0.h5
succeed lim-lya-tau-eq-dt           -- lyapunov --t-end 0.05 --tau 1e-3 -o lim_l1.h5
succeed lim-lya-short-tau-adaptive  -- lyapunov --method dopri5 --t-end 0.05 --tau 1e-6 -o lim_l2.h5

# ---- divergence
refuse  lim-div-delta0-denormal delta0       -- divergence --delta0 5e-324
refuse  lim-div-delta0-1e-14    delta0       -- divergence --delta0 1e-14
refuse  lim-div-pairs-spacing   pair_spacing -- divergence --pairs 100000 --pair-spacing 1e9
refuse  lim-div-spacing-huge    pair_spacing -- divergence --pair-spacing 1e300
refuse  lim-div-spacing-steps   pair_spacing -- divergence --pairs 1000 --pair-spacing 1e6 --dt 1e-6
refuse  lim-div-lyap-t-1e9      lyapunov_t   -- divergence --lyapunov-t 1e9
refuse  lim-div-lyap-t-huge     lyapunov_t   -- divergence --lyapunov-t 1e300
refuse  lim-div-outdt-1e-300    output_dt    -- divergence --t-end 1 --output-dt 1e-300
refuse  lim-div-dt-1e-300       dt           -- divergence --dt 1e-300
refuse  lim-div-fit-end-huge    fit_         -- divergence --fit-end 1e300
refuse  lim-div-m2-1e308        m2           -- divergence --m2 1e308
refuse  lim-div-w1-1e150        w1           -- divergence --w1 1e150
succeed lim-div-delta0-min          -- divergence --delta0 1e-13 --t-end 0.2 --pairs 1 --lyapunov-t 0 -o lim_d1.h5
succeed lim-div-small               -- divergence --t-end 0.2 --pairs 2 --pair-spacing 0.1 --lyapunov-t 0.5 -o lim_d2.h5

# ---- poincare
refuse  lim-poi-energy-1e300    energy        -- poincare --energy 1e300
refuse  lim-poi-energy-neg      energy        -- poincare --energy -1e300
refuse  lim-poi-points          n_points      -- poincare --ics 1000000 --points 100000
refuse  lim-poi-angle-1e300     section_angle -- poincare --section-angle 1e300
refuse  lim-poi-m1-1e308        m1            -- poincare --m1 1e308
refuse  lim-poi-dt-1e-300       dt            -- poincare --dt 1e-300
refuse  lim-poi-tend-huge       t_end         -- poincare --t-end 1e300
refuse  lim-poi-rtol-1e-300     rtol          -- poincare --method dopri5 --rtol 1e-300
succeed lim-poi-small               -- poincare --ics 2 --points 3 --t-end 1 --energy 5 -o lim_p1.h5

# ---- sweep
refuse  lim-swp-n1-1e9          n1          -- sweep --n1 1000000000 --n2 1
refuse  lim-swp-n-46340         n1          -- sweep --n 46340
refuse  lim-swp-n2-2e6          n2          -- sweep --n1 1 --n2 2000000
refuse  lim-swp-dt-denormal     dt          -- sweep --dt 5e-324
refuse  lim-swp-dt-1e-19        dt          -- sweep --dt 1e-19
refuse  lim-swp-threads-1e5     threads     -- sweep --threads 100000
refuse  lim-swp-threads-neg     threads     -- sweep --threads -1
refuse  lim-swp-block-2e9       block       -- sweep --block 2000000000
refuse  lim-swp-max1-1e300      max1        -- sweep --max1 1e300
refuse  lim-swp-w-axis          min1        -- sweep --axis1 w1 --min1 -1e7
refuse  lim-swp-tend-natural    t_end       -- sweep --t-end 1e9 --l1 1e6 --g 1e-6
refuse  lim-swp-m1-1e308        m1          -- sweep --m1 1e308
refuse  lim-swp-l1-1e-300       l1          -- sweep --l1 1e-300
refuse  lim-swp-w2-1e150        w2          -- sweep --w2 1e150
refuse  lim-swp-maxsteps        max-steps   -- sweep --max-steps 10
refuse  lim-swp-list-angle      ic_file     -- sweep --ic-file lim_list_angle.txt
refuse  lim-swp-list-w          ic_file     -- sweep --ic-file lim_list_w.txt
succeed lim-swp-threads-max         -- sweep --n 2 --t-end 0.5 --threads 1024 --quiet -o lim_s1.h5
succeed lim-swp-w-bounds            -- sweep --n 2 --axis1 w1 --min1 -1e6 --max1 1e6 --t-end 1e-5 --dt 1e-8 --quiet -o lim_s2.h5

# ---- study (numeric validation only; refused before any directory is made)
refuse  lim-stu-threads-1e5     threads     -- study --threads 100000
refuse  lim-stu-m1-1e308        m1          -- study --m1 1e308
refuse  lim-stu-l2-1e-300       l2          -- study --l2 1e-300
refuse  lim-stu-tshort          t_short     -- study --config lim_study_tshort.nml
refuse  lim-stu-refdt           ref_dt      -- study --config lim_study_refdt.nml
refuse  lim-stu-case-w          case_w1     -- study --config lim_study_w.nml
refuse  lim-stu-atol-ratio      atol_ratio  -- study --config lim_study_atol.nml
refuse  lim-stu-taodt           tao_dt      -- study --config lim_study_taodt.nml
# a run that fails before its first sample still writes its file with its status
fail    lim-ind-first-sample    'run stopped'  -- indicators --w1 1e6 --w2 -1e6 --dt 0.1 --t-end 20 --output lim_ind0.h5
fail    lim-lya-first-sample    'run stopped'  -- lyapunov --w1 1e6 --w2 -1e6 --dt 0.1 --t-end 20 --output lim_lya0.h5
