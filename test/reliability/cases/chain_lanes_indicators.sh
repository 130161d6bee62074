# The chain lanes' indicators: MEGNO, FLI, SALI and GALI_2 maps of
# chains of 3 to 8 links go through the chain lanes (dpend_chain_lanes; docs/sweep.md,
# "Chain lanes"). Every row succeeds without a trap in the debug build: each indicator,
# the lanes' edges (3 and 8 links), general bodies, a list, initial states far above
# (runaway rates: NaN indicators) and far below the flip bounds (integrated all the same).
printf '0.5 1.0 -1.5707963 0 0 0\n2.9 -2.0 0.3 0.5 -4 1\n' > "$FIXTURES/chi_list.txt"
I=(sweep --n 4 --t-end 2 --quiet --output c.h5)
succeed chi-n3-megno            -- "${I[@]}" --links 3 --indicator megno
succeed chi-n3-fli              -- "${I[@]}" --links 3 --indicator fli
succeed chi-n3-sali             -- "${I[@]}" --links 3 --indicator sali
succeed chi-n3-gali2            -- "${I[@]}" --links 3 --indicator gali2
succeed chi-n8-megno            -- "${I[@]}" --links 8 --indicator megno
succeed chi-n8-sali             -- "${I[@]}" --links 8 --indicator sali
succeed chi-n4-bodies-gali2     -- "${I[@]}" --links 4 --com 0.3,0.4,0.5,0.6 --inertia 0.01,0.02,0.03,0.04 --indicator gali2
succeed chi-n3-list-megno       -- sweep --links 3 --ic-file chi_list.txt --t-end 2 --quiet --output c.h5 --indicator megno
succeed chi-n3-runaway-sali     -- "${I[@]}" --links 3 --w 1e3,-1e3,1e3 --indicator sali
succeed chi-n3-rest-megno       -- "${I[@]}" --links 3 --min1 -0.1 --max1 0.1 --min2 -0.1 --max2 0.1 --indicator megno
succeed chi-n3-seconds-fli      -- "${I[@]}" --links 3 --time-unit s --dt 0.002 --indicator fli
