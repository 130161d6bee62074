# Sweeps over parameters with every lane its own pendulum: the
# lanes of one block hold pixels of very different constants (ratios 1e-5 to 1e5,
# fast spins on the fallback path, runaway lanes, blocks that are no multiple of
# the lane width) and must finish without a trap in the debug build, with every
# indicator and on two threads.
L=(sweep --n 5 --t-end 1 --quiet --output g.h5 --q1 0 --q2 0)
R=(--axis1 m2/m1 --min1 1e-5 --max1 1e5 --axis2 l2/l1 --min2 1e-5 --max2 1e5)
succeed lanes-ratio-extremes       -- "${L[@]}" "${R[@]}" --stats
succeed lanes-ratio-extremes-sali  -- "${L[@]}" "${R[@]}" --indicator sali
succeed lanes-ratio-extremes-gali2 -- "${L[@]}" "${R[@]}" --indicator gali2 --block 7
succeed lanes-ratio-extremes-l1    -- "${L[@]}" "${R[@]}" --lyapunov --threads 2 --block 3
succeed lanes-ratio-spin-megno     -- "${L[@]}" --axis1 m2/m1 --min1 0.1 --max1 10 --axis2 l2/l1 --min2 0.1 --max2 10 --w1 300 --indicator megno --block 9
succeed lanes-m1-l2-either         -- "${L[@]}" --axis1 m1 --min1 1e-3 --max1 1e3 --axis2 l2 --min2 1e-3 --max2 1e3 --stop-at either --threads 2 --block 5
succeed lanes-m2-theta1-fli        -- sweep --n 5 --t-end 1 --quiet --output g.h5 --axis1 theta1 --axis2 m2 --min2 1e-4 --max2 1e4 --indicator fli --block 11
