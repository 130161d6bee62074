# Links of any mass distribution: --body rod|point, --com, --inertia and
# &pendulum body/com/inertia; contradictions and invalid bodies refused in one line.
P=(--t-end 0.2 --q 0.5,1.0)
printf "&pendulum\n body = 'point'\n/\n" > "$FIXTURES/body_point.nml"
printf "&pendulum\n com = 0.6, 0.5\n inertia = 0.05, 0\n/\n" > "$FIXTURES/body_general.nml"
printf "&pendulum\n body = 'stick'\n/\n" > "$FIXTURES/body_bad.nml"
printf "&pendulum\n body = 'point', com = 1, 1\n/\n" > "$FIXTURES/body_contra.nml"
printf "&pendulum\n com = 0.5, x\n/\n" > "$FIXTURES/body_com_text.nml"

succeed bod-point                      -- simulate "${P[@]}" --body point --output b.h5
succeed bod-rod                        -- simulate "${P[@]}" --body rod --output b.h5
succeed bod-general                    -- simulate "${P[@]}" --com 0.6,0.8 --inertia 0.05,0 --output b.h5
succeed bod-com-only                   -- simulate "${P[@]}" --com 0.6,1.5 --output b.h5
succeed bod-point-chain3               -- simulate --t-end 0.2 --links 3 --body point --output b.h5
succeed bod-point-damped               -- simulate "${P[@]}" --body point --damping 0.1,0.1 --output b.h5
succeed bod-point-gauss6               -- simulate "${P[@]}" --body point --method gauss6 --dt 0.01 --output b.h5
succeed bod-point-nml                  -- simulate --config body_point.nml --t-end 0.2 --output b.h5
succeed bod-general-nml                -- simulate --config body_general.nml --t-end 0.2 --output b.h5
succeed bod-point-lyap                 -- lyapunov "${P[@]}" --body point --output b.h5
refuse  bod-name            body       -- simulate "${P[@]}" --body stick --output x.h5
refuse  bod-name-nml        body       -- simulate --config body_bad.nml --output x.h5
refuse  bod-point-com       body       -- simulate "${P[@]}" --body point --com 1,1 --output x.h5
refuse  bod-rod-inertia     body       -- simulate "${P[@]}" --body rod --inertia 0,0 --output x.h5
refuse  bod-contra-nml      body       -- simulate --config body_contra.nml --output x.h5
refuse  bod-com-neg         com1       -- simulate "${P[@]}" --com -0.1,0.5 --output x.h5
refuse  bod-com-nan         com        -- simulate "${P[@]}" --com nan,0.5 --output x.h5
refuse  bod-com-count       com        -- simulate "${P[@]}" --com 0.5 --output x.h5
refuse  bod-com-text        com        -- simulate "${P[@]}" --com 0.5,abc --output x.h5
refuse  bod-com-text-nml    com        -- simulate --config body_com_text.nml --output x.h5
refuse  bod-inertia-neg     inertia2   -- simulate "${P[@]}" --inertia 0.1,-1 --output x.h5
refuse  bod-inertia-inf     inertia    -- simulate "${P[@]}" --inertia inf,0 --output x.h5
refuse  bod-no-inertia      com2       -- simulate "${P[@]}" --com 0.5,0 --inertia 0.1,0 --output x.h5
refuse  bod-chain-no-inert  com2       -- simulate --links 3 --com 0.5,0,1 --inertia 0.1,0,0 --output x.h5
refuse  bod-elastic         body       -- simulate --model elastic --body point --output x.h5
refuse  bod-elastic-com     com        -- simulate --model elastic --com 0.5 --output x.h5
refuse  bod-repeated        body       -- simulate "${P[@]}" --body point --body rod --output x.h5
succeed bod-sweep-point                -- sweep --body point --n1 4 --n2 4 --t-end 1 --quiet --output s.h5
succeed bod-sweep-axis-ok             -- sweep --body point --axis1 l2 --min1 0.5 --max1 1 --n1 4 --n2 4 --t-end 1 --output s.h5
refuse  bod-sweep-axis-com  axis       -- sweep --com 0.4,0.4 --axis1 l2 --min1 0.5 --max1 1 --n1 4 --n2 4 --t-end 1 --output s.h5
refuse  bod-huge-l-com      l2         -- simulate "${P[@]}" --l2 1e200 --com 1,1 --output x.h5
refuse  bod-huge-l-point    l2         -- simulate "${P[@]}" --l2 1e200 --body point --output x.h5
refuse  bod-huge-l-chain    l1         -- simulate --links 3 --l 1e300,1,1 --inertia 0,0,0 --output x.h5
