# The chain lanes: flip maps of chains of 3 to 8 links go through the
# SIMD lanes (dpend_chain_lanes), others stay on the per-trajectory path (docs/sweep.md,
# "Chain lanes"). Every row succeeds without a trap in the debug build: rods and
# general bodies, every stop rule, grid and list, the lanes' edges (3 and 8 links), the
# paths beside them (9 links, indicators, a parameter axis, two links). The environment
# variable DPEND_SWEEP_KERNEL (rows cannot set it) is checked by
# test/reliability/special/chain_kernel_env.sh.

printf '0.5 1.0 -1.5707963 0 0 0\n2.9 -2.0 0.3 0.5 -4 1\n' > "$FIXTURES/chl_list.txt"
C=(sweep --n 4 --t-end 2 --quiet --output c.h5)
succeed chl-n3                  -- "${C[@]}" --links 3
succeed chl-n3-both             -- "${C[@]}" --links 3 --stop-at both
succeed chl-n3-end              -- "${C[@]}" --links 3 --stop-at end --stats
succeed chl-n3-seconds          -- "${C[@]}" --links 3 --time-unit s --dt 0.002
succeed chl-n3-rates            -- "${C[@]}" --links 3 --axis1 w1 --axis2 theta3 --min1 -20 --max1 20
succeed chl-n5-masses           -- "${C[@]}" --links 5 --m 1,2,0.5,3,1e-3 --l 1,0.2,3,1,1
succeed chl-n8                  -- "${C[@]}" --links 8
succeed chl-n4-bodies           -- "${C[@]}" --links 4 --com 0.3,0.4,0.5,0.6 --inertia 0.01,0.02,0.03,0.04
succeed chl-n3-point            -- "${C[@]}" --links 3 --body point
succeed chl-n3-list             -- sweep --links 3 --ic-file chl_list.txt --t-end 2 --quiet --output c.h5
succeed chl-n3-fast             -- "${C[@]}" --links 3 --w 1e3,-1e3,1e3
succeed chl-n3-big-angles       -- "${C[@]}" --links 3 --axis1 q1 --min1 -1e6 --max1 1e6
# beside the lanes: the per-trajectory path (chl-n3-megno: the lanes since the
# indicators joined them, chain_lanes_indicators.sh)
succeed chl-n9                  -- "${C[@]}" --links 9
succeed chl-n3-megno            -- "${C[@]}" --links 3 --indicator megno
succeed chl-n3-param            -- "${C[@]}" --links 3 --axis1 m1 --min1 0.5 --max1 2
succeed chl-n2                  -- "${C[@]}"
