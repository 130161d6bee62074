# Figures: animate at the sizes whose text now scales with the
# image (360 px and 800 px, with the reaction labels), an overlay (the overlay's
# links in their own colours), a three-link figure (a colour per link). The summary's
# tidy times and gnuplot's quiet stderr: test/reliability/special/animate_quiet.sh
# and `fpm test -- animate/tidy_summary_quiet_gnuplot`. Tiny runs (a few frames).

FA=(animate existing.h5 --output f.gif --fps 5)

succeed fig-ani-360-reactions      -- "${FA[@]}" --size 360x360 --reactions
succeed fig-ani-800-reactions      -- "${FA[@]}" --size 800x800 --reactions
succeed fig-ani-wide               -- "${FA[@]}" --size 800x360
succeed fig-ani-overlay-colours    -- "${FA[@]}" --size 360x360 --overlay existing.h5
