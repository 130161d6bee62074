# Help and messages: `dpend methods` with its one option, refused
# arguments of it, and the closing lines of simulate and sweep (also --quiet),
# which must never trap whatever the numbers they print.

succeed msg-methods-table        -- methods
succeed msg-methods-names        -- methods --names
succeed msg-methods-help         -- methods --help
refuse  msg-methods-unknown  'unknown option' -- methods --bogus
refuse  msg-methods-last     'unknown option' -- methods --names --bogus
refuse  msg-methods-value    'unexpected argument' -- methods rk4
refuse  msg-methods-names-eq 'unknown option' -- methods --names=1

# closing lines: a tiny run, a zero-length run, a run whose energy error is large
succeed msg-simulate-summary     -- simulate --t-end 0.01 --output m.h5
succeed msg-simulate-zero        -- simulate --t-end 0 --output m.h5
succeed msg-simulate-large-error -- simulate --dt 0.1 --t-end 5 --w1 5 --output m.h5
fail    msg-simulate-stopped 'run stopped' -- simulate --dt 0.1 --t-end 5 --w1 5 --method dopri5 --rtol 0.5 --atol 1 --output m.h5
succeed msg-simulate-adaptive    -- simulate --method dop853 --t-end 0.1 --output m.h5
succeed msg-sweep-quiet          -- sweep --n 2 --t-end 0.1 --quiet --output m.h5
succeed msg-sweep-complete       -- sweep --n 8 --t-end 1 --quiet --output sweep.h5
