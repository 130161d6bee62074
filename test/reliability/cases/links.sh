# Inputs of the N-link chain, damping and the moving support, the chaos indicators
# and export --csv/--list:
# refused before any work (one line naming the field, exit 2, no file touched),
# and their edge values succeed without a trap in the debug build.

# fixture: a three-link simulate file for export
"$DPEND" simulate --links 3 --t-end 0.05 --output "$FIXTURES/links3.h5" > /dev/null 2>&1 ||
  echo "links.sh: could not make links3.h5" >&2

S=(simulate --t-end 0.05 --output g.h5)
# ---- --links
refuse  lnk-links-zero          links   -- "${S[@]}" --links 0
refuse  lnk-links-33            links   -- "${S[@]}" --links 33
refuse  lnk-links-negative      links   -- "${S[@]}" --links -2
refuse  lnk-links-fraction      links   -- "${S[@]}" --links 2.5
refuse  lnk-links-junk          links   -- "${S[@]}" --links three
refuse  lnk-links-missing       links   -- "${S[@]}" --links
# ---- per-link lists
refuse  lnk-m-short             m       -- "${S[@]}" --links 3 --m 1,1
refuse  lnk-m-long              m       -- "${S[@]}" --links 2 --m 1,1,1
refuse  lnk-m-nan               m       -- "${S[@]}" --links 3 --m 1,nan,1
refuse  lnk-m-zero              m2      -- "${S[@]}" --links 3 --m 1,0,1
refuse  lnk-m-empty-item        m       -- "${S[@]}" --links 3 --m 1,,1
refuse  lnk-m-too-many          m       -- "${S[@]}" --m "$(printf '1,%.0s' $(seq 32))1"
refuse  lnk-l-negative          l3      -- "${S[@]}" --links 3 --l 1,1,-1
refuse  lnk-l-huge              l1      -- "${S[@]}" --links 3 --l 1e300,1,1
refuse  lnk-q-short             q       -- "${S[@]}" --links 3 --q 0,0
refuse  lnk-q-huge              q3      -- "${S[@]}" --links 3 --q 0,0,1e300
refuse  lnk-w-inf               w       -- "${S[@]}" --links 3 --w 0,inf,0
refuse  lnk-w-huge              w2      -- "${S[@]}" --links 3 --w 0,1e150,0
refuse  lnk-m-missing           m       -- "${S[@]}" --m
# ---- commands that need two links or a Hamiltonian
refuse  lnk-poincare-3          poincare -- poincare --links 3 --ics 2 --t-end 2 --points 5 --output g.h5
refuse  lnk-lya-vectors-7       vectors -- lyapunov --links 3 --t-end 1 --vectors 7 --output g.h5
refuse  lnk-sweep-axis-theta4   axis1   -- sweep --links 3 --n 4 --t-end 1 --quiet --axis1 theta4 --output g.h5
refuse  lnk-sweep-lyapunov      lyapunov -- sweep --links 3 --n 4 --t-end 1 --quiet --lyapunov --output g.h5
refuse  lnk-verlet-damped        method  -- "${S[@]}" --method verlet --damping 0.1,0.1
refuse  lnk-tao4-driven         method  -- "${S[@]}" --method tao4 --support-amplitude 0,0.01 --support-frequency 5
# ---- damping and support
refuse  lnk-damping-short       damping -- "${S[@]}" --links 3 --damping 0.1,0.1
refuse  lnk-damping-negative    c1      -- "${S[@]}" --damping -0.1,0
refuse  lnk-damping-nan         damping -- "${S[@]}" --damping nan,0
refuse  lnk-support-amp-one     support -- "${S[@]}" --support-amplitude 0.1
refuse  lnk-support-amp-huge    support -- "${S[@]}" --support-amplitude 1e300,0
refuse  lnk-support-freq-neg    support -- "${S[@]}" --support-amplitude 0,0.01 --support-frequency -1
refuse  lnk-support-freq-nan    support -- "${S[@]}" --support-amplitude 0,0.01 --support-frequency nan
succeed lnk-sweep-damping       -- sweep --n 4 --t-end 1 --quiet --damping 0.1,0.1 --output g.h5
succeed lnk-sweep-damping-3     -- sweep --links 3 --n 4 --t-end 1 --quiet --damping 0.1,0.1,0 --output g.h5
succeed lnk-sweep-support       -- sweep --n 4 --t-end 1 --quiet --support-amplitude 0,0.01 --support-frequency 20 --output g.h5
refuse  lnk-sweep-damping-short damping -- sweep --n 4 --t-end 1 --quiet --damping 0.1 --output g.h5
refuse  lnk-sweep-damping-lyap  "double pendulum's kernel only" -- sweep --n 4 --t-end 1 --quiet --damping 0.1,0.1 --lyapunov --output g.h5
# ---- indicators
refuse  lnk-ind-tau-zero        tau     -- indicators --t-end 1 --tau 0 --output g.h5
refuse  lnk-ind-tau-nan         tau     -- indicators --t-end 1 --tau nan --output g.h5
refuse  lnk-ind-unknown         unknown -- indicators --t-end 1 --bogus --output g.h5
# ---- export
refuse  lnk-export-unknown-name 'nosuch' -- export links3.h5 nosuch
refuse  lnk-export-list-names   list    -- export --list links3.h5 t
refuse  lnk-export-csv-matrix   csv     -- export --csv --matrix links3.h5 q

# edge values that must succeed
succeed lnk-ok-one-link             -- "${S[@]}" --links 1
succeed lnk-ok-32-links             -- simulate --links 32 --t-end 0.002 --output g.h5
succeed lnk-ok-lists                -- "${S[@]}" --links 3 --m 1e-6,1e6,1 --l 1e6,1e-6,1 --q 0,0.5,-1 --w 0,1,0
succeed lnk-ok-two-links-lists      -- "${S[@]}" --links 2 --m 1,2 --l 1,0.5 --q 0.1,0.2
succeed lnk-ok-gauss6-damped-driven -- "${S[@]}" --dt 0.01 --method gauss6 --damping 0.1,0.1 --support-amplitude 0,0.01 --support-frequency 5
succeed lnk-ok-midpoint-3-damped    -- "${S[@]}" --dt 0.01 --method midpoint --links 3 --damping 0.1,0,1e6
succeed lnk-ok-damped-forced        -- "${S[@]}" --links 3 --damping 0.1,0,1e3 --support-amplitude 0.01,0.02 --support-frequency 10 --method dop853
succeed lnk-ok-lya-3                -- lyapunov --links 3 --t-end 1 --output g.h5
succeed lnk-ok-div-3                -- divergence --links 3 --t-end 1 --pairs 2 --lyapunov-t 0 --output g.h5
succeed lnk-ok-sweep-3              -- sweep --links 3 --n 4 --t-end 1 --quiet --axis1 theta3 --axis2 w1 --output g.h5
succeed lnk-ok-indicators-3         -- indicators --links 3 --t-end 1 --output g.h5
