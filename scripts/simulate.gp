# Figures of one `dpend simulate` run. Called by scripts/plot_simulate.sh as
#   gnuplot -c simulate.gp DATAFILE OUTDIR TITLE ESCALE
# DATAFILE: columns t q1 q2 E F01x F01y F21x F21y rC2x rC2y rBx rBy; OUTDIR: where the
# PNGs go; TITLE: run description (enhanced text, escaped); ESCALE: energy scale [J].
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

set output outdir."/angles.png"
set title "Angles from the horizontal x axis (".title.")"
set xlabel "t [s]"; set ylabel "angle [rad]"
plot datafile u 1:2 w l lw 1.5 t "q_1", datafile u 1:3 w l lw 1.5 t "q_2"

set output outdir."/energy_error.png"
set title sprintf("Energy error |E(t) - E(0)| / E_s,  E_s = %.4g J%s", Escale, (abs(abs(E0) - Escale) < 1e-12*Escale) ? " = |E(0)|" : " (E(0) = 0: V with both links upright)")
set ylabel "relative energy error"
set logscale y
set format y "10^{%L}"
plot datafile u 1:(abs($4 - E0)/Escale + 1e-18) w l lw 1.2 t "energy error"
unset logscale y; set format y "%g"

set output outdir."/reactions.png"
set title "Joint reactions: F01 ground on link 1 at A, F21 link 2 on link 1 at B"
set ylabel "force [N]"
plot datafile u 1:5 w l t "F01x", datafile u 1:6 w l t "F01y", \
     datafile u 1:7 w l t "F21x", datafile u 1:8 w l t "F21y"

set output outdir."/tip_path.png"
set terminal pngcairo size 800,800 enhanced font "DejaVu Sans,11"
set title "Path of the tip of link 2 (y up, pin A at the origin)"
set xlabel "x [m]"; set ylabel "y [m]"
set size ratio -1
set key off
$origin << EOD
0 0
EOD
plot datafile u (2*$9 - $11):(2*$10 - $12) w l lw 0.8 lc rgb "#1f77b4", \
     $origin w p pt 7 ps 1.5 lc rgb "black"
