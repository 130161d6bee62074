# Figure of `dpend poincare`. Called by scripts/plot_chaos.sh as
#   gnuplot -c poincare.gp DAT OUTDIR TITLE "E LINK OTHER ANGLE DIR NORB"
# DAT: columns q_o p_o orbit; OUTDIR: where poincare.png goes; TITLE: enhanced text
# (escaped); then one argument of numbers: E (energy, J), LINK (section link),
# OTHER, ANGLE (section angle), DIR (direction), NORB (orbits). The angle axis is
# ticked in multiples of pi (style.gp), the section angle printed as one (−π/2). The
# arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"
load style_gp
dat = ARG1
outfile = ARG2."/poincare.png"
title = ARG3
E = real(word(ARG4, 1)); link = int(real(word(ARG4, 2))); other = int(real(word(ARG4, 3)))
angle = real(word(ARG4, 4)); dir = real(word(ARG4, 5)); norb = int(real(word(ARG4, 6)))
set terminal pngcairo size 900,800 enhanced font fontspec(900)
set output outfile
set title sprintf("Poincaré section q_%d = %s (mod 2π), d q_%d/dt %s 0, E = %g J\n%d orbits (%s)", \
    link, pistr(angle), link, (dir > 0 ? ">" : (dir < 0 ? "<" : "≷")), E, norb, title)
set xlabel sprintf("q_%d [rad]", other); set ylabel sprintf("p_%d [kg m^2/s]", other)
# Axes fitted to the points with a margin of 4 % of their extent on each side (the angle
# kept within [-pi, pi], where the section wraps it); multiples of pi as tics
stats dat u 1:2 nooutput
margin(lo, hi) = 0.04*((hi > lo) ? hi - lo : ((abs(lo) > 0) ? abs(lo) : 1))
xlo = STATS_min_x - margin(STATS_min_x, STATS_max_x)
xhi = STATS_max_x + margin(STATS_min_x, STATS_max_x)
set xrange [(xlo > -pi ? xlo : -pi):(xhi < pi ? xhi : pi)]
set yrange [STATS_min_y - margin(STATS_min_y, STATS_max_y):STATS_max_y + margin(STATS_min_y, STATS_max_y)]
xlo = (xlo > -pi ? xlo : -pi); xhi = (xhi < pi ? xhi : pi)
eval "set xtics (".pitics(xlo, xhi).")"
set palette defined (0 "#1f77b4", 1 "#2ca02c", 2 "#bcbd22", 3 "#ff7f0e", 4 "#d62728", 5 "#9467bd")
set cbrange [1:(norb > 1 ? norb : 2)]
unset colorbox
set key off
plot dat u 1:2:3 w p pt 7 ps 0.12 lc palette
