# Figures of one `dpend simulate` run. Called by scripts/plot_simulate.sh as
#   gnuplot -c simulate.gp DATAFILE OUTDIR TITLE ESCALE
# DATAFILE: columns t q1 q2 E F01x F01y F21x F21y rC2x rC2y rBx rBy q1dot q2dot; OUTDIR:
# where the PNGs go; TITLE: run description (method and file name, enhanced text,
# escaped; every figure shows it); ESCALE: energy scale [J], at full precision.
# The arguments are data: never pasted into code.
datafile = ARG1
outdir = ARG2
title = ARG3
Escale = real(ARG4)
set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11"
set grid
set key outside right
# Escale (J) comes from the file's energy_scale attribute: |E0|, or when E0 ~ 0
# the potential energy with both links upright (docs/hdf5-layout.md)
stats datafile using 4 every ::0::0 nooutput
E0 = STATS_min

# angle wrapped to (-pi, pi]
wrap(a) = a - 2*pi*ceil((a - pi)/(2*pi))
# wrapped value of column c, or NaN where it jumped by more than pi since the previous
# row (a gap in the line instead of a vertical stroke across the plot); one variable
# per column, reset by the first row
array prevw[2]
gap(c, i) = (w = wrap(column(c)), j = ($0 > 0 && abs(w - prevw[i]) > pi), prevw[i] = w, \
             j ? NaN : w)
pitics = "(\"-{/Symbol p}\" -pi, \"-{/Symbol p}/2\" -pi/2, \"0\" 0, \"{/Symbol p}/2\" pi/2, \"{/Symbol p}\" pi)"

set output outdir."/angles.png"
set title "Angles from the horizontal x axis, unwrapped (".title.")"
set xlabel "t [s]"; set ylabel "angle [rad]"
plot datafile u 1:2 w l lw 1.5 t "q_1", datafile u 1:3 w l lw 1.5 t "q_2"

set output outdir."/angles_wrapped.png"
set title "Angles from the horizontal x axis, wrapped to (-{/Symbol p}, {/Symbol p}] (".title.")"
set yrange [-pi*1.05:pi*1.05]
eval "set ytics ".pitics
plot datafile u 1:(gap(2, 1)) w l lw 1.5 t "q_1", datafile u 1:(gap(3, 2)) w l lw 1.5 t "q_2"
set autoscale y; set ytics auto

set output outdir."/phase.png"
set multiplot layout 1,2 title "Phase portraits, angles wrapped to (-{/Symbol p}, {/Symbol p}] (".title.")"
set key off
set xrange [-pi*1.05:pi*1.05]
eval "set xtics ".pitics
set xlabel "q_1 [rad]"; set ylabel "dq_1/dt [rad/s]"
set title "link 1"
plot datafile u (gap(2, 1)):13 w l lw 0.8 lc rgb "#9400d3"
set xlabel "q_2 [rad]"; set ylabel "dq_2/dt [rad/s]"
set title "link 2"
plot datafile u (gap(3, 2)):14 w l lw 0.8 lc rgb "#009e73"
unset multiplot
set autoscale x; set xtics auto; set key outside right

set output outdir."/energy_error.png"
# E(0) = 0 when the scale is not |E(0)| (relative tolerance: the scale is |E(0)| to
# the last bits when it is one)
scale_is_E0 = abs(abs(E0) - Escale) <= 1e-9*Escale
set title sprintf("Energy error |E(t) - E(0)| / E_s, E(0) = %.6g J, E_s = %.6g J%s\n(%s)", E0, Escale, scale_is_E0 ? " = |E(0)|" : " (E(0) ≈ 0: V with both links upright)", title)
set xlabel "t [s]"; set ylabel "relative energy error"
set logscale y
set format y "10^{%L}"
plot datafile u 1:(abs($4 - E0)/Escale + 1e-18) w l lw 1.2 t "energy error"
unset logscale y; set format y "%g"

set output outdir."/reactions.png"
set title "Joint reactions: F01 ground on link 1 at A, F21 link 2 on link 1 at B (".title.")"
set ylabel "force [N]"
plot datafile u 1:5 w l t "F01x", datafile u 1:6 w l t "F01y", \
     datafile u 1:7 w l t "F21x", datafile u 1:8 w l t "F21y"

set output outdir."/tip_path.png"
set terminal pngcairo size 800,800 enhanced font "DejaVu Sans,11"
set title "Path of the tip of link 2 (y up, pin A at the origin)\n(".title.")"
set xlabel "x [m]"; set ylabel "y [m]"
set size ratio -1
set key off
$origin << EOD
0 0
EOD
plot datafile u (2*$9 - $11):(2*$10 - $12) w l lw 0.8 lc rgb "#1f77b4", \
     $origin w p pt 7 ps 1.5 lc rgb "black"
