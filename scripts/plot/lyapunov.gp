# Figures of `dpend lyapunov`. Called by scripts/plot_chaos.sh as
#   gnuplot -c lyapunov.gp RUN SPEC OUTDIR TITLE K LINKS
# RUN: columns t lambda_1(t) .. lambda_k(t); SPEC: columns lambda_i spread_i;
# OUTDIR: where the PNGs go; TITLE: enhanced text (escaped); K: number of exponents;
# LINKS: the number of links N. With the full spectrum (K = 2N) the pairing defects
# |lambda_i + lambda_(2N+1-i)|, i = 1..N, are drawn beside the spectrum.
# The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
run = ARG1
spec = ARG2
outdir = ARG3
title = ARG4
k = int(real(ARG5))
N = int(real(ARG6))
pairs = (k == 2*N)
set terminal pngcairo size 1000,800 enhanced font fontspec(1000)
set grid
array cols[10] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", \
                   "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
col(i) = cols[(i - 1)%10 + 1]
# pairing defects (pair i: lambda_i + lambda_(k+1-i)); the middle pair's own |lambda|
array pcols[10] = ["#d62728", "#2ca02c", "#1f77b4", "#ff7f0e", "#e377c2", "#7f7f7f", \
                   "#bcbd22", "#17becf", "#9467bd", "#8c564b"]
pcol(i) = pcols[(i - 1)%10 + 1]
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
plot for [i=1:k] run u 1:(column(i+1)) w l lw 1.5 lc rgb col(i) t sprintf("{/Symbol l}_%d", i)
set logscale y
set format y "10^{%L}"
set ylabel "|{/Symbol l}_i(t)| [1/s]"
plot for [i=1:k] run u 1:(abs(column(i+1))) w l lw 1.2 lc rgb col(i) t sprintf("|{/Symbol l}_%d|", i), \
     [2.718:tmax] log(x)/x w l dt 2 lw 1.5 lc rgb "black" t "ln(t)/t"
unset multiplot
unset logscale; set format x "%g"; set format y "%g"

set output outdir."/lyapunov_spectrum.png"
if (pairs) {
  set multiplot title "Lyapunov spectrum and its Hamiltonian pairing (".title.")"
  set size 0.4, 0.95; set origin 0, 0
}
set title "Spectrum at t = ".sprintf("%g", tmax)." s (error bars: batch-means spread)"
set xlabel "i"; set ylabel "{/Symbol l}_i [1/s]"
set xrange [0.5:k+0.5]; set xtics 1
set key off
plot spec u ($0+1):1:2 w yerrorbars pt 7 ps 1.2 lc rgb "#1f77b4", \
     spec u ($0+1):($1 + ($0 == k/2 - 1 ? 0.08 : ($0 == k/2 ? -0.08 : 0))):(sprintf(" %.4g", $1)) \
       w labels left offset 1,0, 0 w l lc rgb "gray" dt 2
if (pairs) {
  set size 0.6, 0.95; set origin 0.4, 0
  set title "Pairing defects against t"
  set xrange [*:*]; set xtics auto
  set logscale xy
  set format x "10^{%L}"; set format y "10^{%L}"
  set xlabel "t [s]"; set ylabel "[1/s]"
  set key inside bottom left
  # N = 2: |l1 + l4|, |l2 + l3|, then |l2| and |l3| (the pair that tends to 0)
  plot for [i=1:N] run u 1:(abs(column(i + 1) + column(k + 2 - i))) w l lw 1.2 \
         lc rgb pcol(i) t sprintf("|{/Symbol l}_%d + {/Symbol l}_%d|", i, k + 1 - i), \
       run u 1:(abs(column(N + 1))) w l lw 0.8 lc rgb "#9467bd" t sprintf("|{/Symbol l}_%d|", N), \
       run u 1:(abs(column(N + 2))) w l lw 0.8 lc rgb "#8c564b" \
         t sprintf("|{/Symbol l}_%d|", N + 1), \
       run u 1:(0.01*abs($2)) w l dt 2 lw 1.5 lc rgb "black" t "1 % of {/Symbol l}_1"
  unset multiplot
}
