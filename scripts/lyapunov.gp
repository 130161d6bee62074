# Figures of `dpend lyapunov`. Called by scripts/plot_chaos.sh as
#   gnuplot -c lyapunov.gp RUN SPEC OUTDIR TITLE K
# RUN: columns t lambda_1(t) .. lambda_k(t); SPEC: columns lambda_i spread_i;
# OUTDIR: where the PNGs go; TITLE: enhanced text (escaped); K: number of exponents.
# The arguments are data: never pasted into code.
run = ARG1
spec = ARG2
outdir = ARG3
title = ARG4
k = int(real(ARG5))
set terminal pngcairo size 1000,800 enhanced font "DejaVu Sans,11"
set grid
array col[4] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]
stats run u 1 nooutput
tmax = STATS_max
stats spec u 1 nooutput
l1 = STATS_max

set output outdir."/lyapunov_convergence.png"
set multiplot layout 2,1 title "Lyapunov exponents: running estimates {/Symbol l}_i(t) = (1/t) {/Symbol S} ln R_{ii}  (".title.")"
set logscale x
set format x "10^{%L}"
set xlabel "t [s]"; set ylabel "{/Symbol l}_i(t) [1/s]"
set key outside right
plot for [i=1:k] run u 1:(column(i+1)) w l lw 1.5 lc rgb col[i] t sprintf("{/Symbol l}_%d", i)
set logscale y
set format y "10^{%L}"
set ylabel "|{/Symbol l}_i(t)| [1/s]"
plot for [i=1:k] run u 1:(abs(column(i+1))) w l lw 1.2 lc rgb col[i] t sprintf("|{/Symbol l}_%d|", i), \
     [2.718:tmax] log(x)/x w l dt 2 lw 1.5 lc rgb "black" t "ln(t)/t"
unset multiplot
unset logscale; set format x "%g"; set format y "%g"

set output outdir."/lyapunov_spectrum.png"
if (k == 4) {
  set multiplot title "Lyapunov spectrum and its Hamiltonian pairing (".title.")"
  set size 0.4, 0.95; set origin 0, 0
}
set title "Spectrum at t = ".sprintf("%g", tmax)." s (error bars: batch-means spread)"
set xlabel "i"; set ylabel "{/Symbol l}_i [1/s]"
set xrange [0.5:k+0.5]; set xtics 1
set key off
plot spec u ($0+1):1:2 w yerrorbars pt 7 ps 1.2 lc rgb "#1f77b4", \
     spec u ($0+1):($1 + ($0 == 1 ? 0.08 : ($0 == 2 ? -0.08 : 0))):(sprintf(" %.4g", $1)) \
       w labels left offset 1,0, 0 w l lc rgb "gray" dt 2
if (k == 4) {
  set size 0.6, 0.95; set origin 0.4, 0
  set title "Pairing defects against t"
  set xrange [*:*]; set xtics auto
  set logscale xy
  set format x "10^{%L}"; set format y "10^{%L}"
  set xlabel "t [s]"; set ylabel "[1/s]"
  set key inside bottom left
  plot run u 1:(abs($2 + $5)) w l lw 1.2 lc rgb "#d62728" t "|{/Symbol l}_1 + {/Symbol l}_4|", \
       run u 1:(abs($3 + $4)) w l lw 1.2 lc rgb "#2ca02c" t "|{/Symbol l}_2 + {/Symbol l}_3|", \
       run u 1:(abs($3)) w l lw 0.8 lc rgb "#9467bd" t "|{/Symbol l}_2|", \
       run u 1:(abs($4)) w l lw 0.8 lc rgb "#8c564b" t "|{/Symbol l}_3|", \
       run u 1:(0.01*abs($2)) w l dt 2 lw 1.5 lc rgb "black" t "1 % of {/Symbol l}_1"
  unset multiplot
}
