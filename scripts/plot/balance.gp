# The energy balance of a damped or driven `dpend simulate` run. Called by
# scripts/plot_simulate.sh as
#   gnuplot -c balance.gp DATAFILE OUTDIR TITLE ESCALE TORQUE
# DATAFILE: columns t E W_friction W_support balance_error (relative to the
# energy scale ESCALE [J], as simulate writes it) and, with TORQUE = 1, W_torque (the
# work of applied joint torques); OUTDIR: where balance.png goes;
# TITLE: run description (enhanced text, escaped). The arguments are data: never
# pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
datafile = ARG1
outdir = ARG2
title = ARG3
Escale = real(ARG4)
torque = (ARGC >= 5 ? int(ARG5) : 0)
set terminal pngcairo size 1000,750 enhanced font fontspec(1000)
set output outdir."/balance.png"
set grid
set key outside right
stats datafile using 2 every ::0::0 nooutput
E0 = STATS_min
set multiplot layout 2,1 title "Energy balance (".title.")"
set title (torque ? "Energy change and the work of the friction, the support and the torques" \
                  : "Energy change and the work of the friction and of the support")
set xlabel "t [s]"; set ylabel "[J]"
if (torque) {
  plot datafile using 1:($2 - E0) with lines lw 1.5 lc rgb "#0072b2" title "E(t) - E(0)", \
       datafile using 1:(-$3) with lines lw 1.5 lc rgb "#e51e10" title "-W_{friction}", \
       datafile using 1:4 with lines lw 1.5 lc rgb "#009e73" title "W_{support}", \
       datafile using 1:6 with lines lw 1.5 lc rgb "#e69f00" title "W_{torque}", \
       datafile using 1:($2 - E0 + $3 - $4 - $6) with lines lw 1 dt 2 lc rgb "#000000" \
         title "E - E(0) + W_{fr} - W_{sup} - W_{tq}"
} else {
  plot datafile using 1:($2 - E0) with lines lw 1.5 lc rgb "#0072b2" title "E(t) - E(0)", \
       datafile using 1:(-$3) with lines lw 1.5 lc rgb "#e51e10" title "-W_{friction}", \
       datafile using 1:4 with lines lw 1.5 lc rgb "#009e73" title "W_{support}", \
       datafile using 1:($2 - E0 + $3 - $4) with lines lw 1 dt 2 lc rgb "#000000" \
         title "E - E(0) + W_{fr} - W_{sup}"
}
set title (torque ? sprintf("Balance error |E(t) - E(0) + W_{friction} - W_{support} - W_{torque}| / E_s  (E_s = %.4g J)", Escale) \
                  : sprintf("Balance error |E(t) - E(0) + W_{friction} - W_{support}| / E_s  (E_s = %.4g J)", Escale))
set logscale y
set format y "10^{%L}"
set ylabel "relative error"
plot datafile using 1:(abs($5) > 0 ? abs($5) : NaN) with lines lw 1.2 lc rgb "#9400d3" \
     title "balance error"
unset multiplot
