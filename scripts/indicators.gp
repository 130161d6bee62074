# Figure of `dpend indicators`. Called by scripts/plot_chaos.sh as
#   gnuplot -c indicators.gp DAT OUTDIR TITLE "K N TEND FLIEND GALI_2 .. GALI_K"
# DAT: columns t Y(t) <Y>(t) FLI(t) SALI(t) GALI_2(t) .. GALI_K(t);
# OUTDIR: where indicators.png goes; TITLE: enhanced text (escaped); then one
# argument of numbers: K (deviation vectors, 2N), N (links = degrees of freedom),
# TEND (last sample time [s]), FLIEND (FLI there), the final GALI_k (the power
# laws are drawn through them). The reference behaviours:
# regular orbits <Y> -> 2, FLI ~ ln t (|delta| ~ t), SALI and GALI_k (k <= N)
# bounded, GALI_k ~ t^(-2(k-N)) for k > N; chaotic orbits <Y> ~ lambda1 t/2,
# FLI ~ lambda1 t, GALI_2 ~ exp(-(lambda1 - lambda2) t) with lambda2 ~ 0. lambda1
# is estimated as FLI(TEND)/TEND. The arguments are data: never pasted into code.
dat = ARG1
outfile = ARG2."/indicators.png"
title = ARG3
k = int(real(word(ARG4, 1))); N = int(real(word(ARG4, 2)))
tend = real(word(ARG4, 3)); fliend = real(word(ARG4, 4))
lam = fliend/tend
pos(y) = (y > 0 ? y : NaN)
array cols[10] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", \
                   "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
col(i) = cols[(i - 1)%10 + 1]
set terminal pngcairo size 1200,900 enhanced font "DejaVu Sans,10"
set output outfile
set grid
set samples 400
set multiplot layout 2,2 title "Chaos indicators (".title."); {/Symbol l}_1 estimate FLI(t)/t = ".sprintf("%.4g", lam)." s^{-1}"

set title "MEGNO"
set xlabel "t [s]"; set ylabel "Y, <Y>"
set key top left box opaque
plot dat u 1:2 w l lw 0.6 lc rgb "#a0c4e8" t "Y(t)", \
     dat u 1:3 w l lw 2 lc rgb "#1f77b4" t "<Y>(t)", \
     2 w l dt 2 lw 1.5 lc rgb "black" t "regular: <Y> = 2", \
     [0:tend] lam*x/2 w l dt 3 lw 1.5 lc rgb "#d62728" t "chaotic: {/Symbol l}_1 t/2"

set title "Fast Lyapunov indicator"
set ylabel "FLI = max_i ln|{/Symbol d}_i|"
stats dat u 1 nooutput
t0 = STATS_min
c = fliend - log(tend)
plot dat u 1:4 w l lw 2 lc rgb "#2ca02c" t "FLI(t)", \
     [t0:tend] log(x) + c w l dt 2 lw 1.5 lc rgb "black" t "regular: ln t + c (|{/Symbol d}| ∝ t)", \
     [t0:tend] lam*x w l dt 3 lw 1.5 lc rgb "#d62728" t "chaotic: {/Symbol l}_1 t"

set title "SALI and GALI_k (log-log)"
set ylabel "GALI_k, SALI"
set logscale xy; set format x "10^{%L}"; set format y "10^{%L}"
set yrange [1e-30:3]
set key bottom left box opaque
# power laws through each curve's last value (regular orbits, k > N)
ga(i) = real(word(ARG4, 3 + i))
plot dat u 1:(pos($5)) w l lw 1 dt 2 lc rgb "black" t "SALI", \
     for [i=2:k] dat u 1:(pos(column(i+4))) w l lw 1.8 lc rgb col(i) t sprintf("GALI_%d", i), \
     for [i=N+1:k] [t0:tend] (ga(i) > 0 ? ga(i)*(x/tend)**(-2*(i-N)) : NaN) w l dt 3 lw 1.3 lc rgb col(i) \
       t sprintf("t^{-%d}", 2*(i-N))

set title "SALI, GALI_2 against t (semi-log)"
unset logscale x; set format x "%g"
# the time GALI_2 needs to reach roundoff on a chaotic orbit, or the whole run
set xrange [0:(lam > 0 && 45/lam < tend ? 45/lam : tend)]
set yrange [1e-18:3]
plot dat u 1:(pos($5)) w l lw 1 dt 2 lc rgb "black" t "SALI", \
     dat u 1:(pos($6)) w l lw 1.8 lc rgb col(2) t "GALI_2", \
     [0:tend] exp(-lam*x) w l dt 3 lw 1.5 lc rgb "#d62728" \
       t "chaotic: e^{-({/Symbol l}_1 - {/Symbol l}_2) t}, {/Symbol l}_2 ≈ 0"
unset multiplot
