# The applied joint torques of a `dpend simulate --torque-file` run. Called by
# scripts/plot_simulate.sh as
#   gnuplot -c torques.gp DATAFILE OUTDIR TITLE N
# DATAFILE: columns t tau_1 .. tau_N [N m] (as /trajectory/tau holds them); OUTDIR:
# where torques.png goes; TITLE: run description (enhanced text, escaped); N: joints.
# The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
datafile = ARG1
outdir = ARG2
title = ARG3
n = int(ARG4)
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set output outdir."/torques.png"
set grid
set key outside right
set title "Applied joint torques (".title.")"
set xlabel "t [s]"; set ylabel "torque [N m]"
plot for [i=1:n] datafile using 1:(column(i + 1)) with lines lw 1.5 \
     title sprintf("{/Symbol t}_%d (joint %d on link %d)", i, i, i)
