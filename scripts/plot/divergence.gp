# Figure of `dpend divergence`. Called by scripts/plot_chaos.sh as
#   gnuplot -c divergence.gp DAT OUTDIR TITLE "SLOPE B T0 T1 SAT LAM NPAIRS DELTA0"
# DAT: columns t mean(log10|delta|) log10|delta| of each pair (NPAIRS columns);
# OUTDIR: where divergence.png goes; TITLE: enhanced text (escaped); then one
# argument of numbers: SLOPE [1/s, natural log], B (log10 intercept), T0, T1 (fit
# window), SAT (saturation, log10), LAM (Benettin lambda1, 0 if not computed),
# NPAIRS, DELTA0. The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
dat = ARG1
outfile = ARG2."/divergence.png"
title = ARG3
slope = real(word(ARG4, 1)); b = real(word(ARG4, 2))
t0 = real(word(ARG4, 3)); t1 = real(word(ARG4, 4)); sat = real(word(ARG4, 5))
lam = real(word(ARG4, 6)); npairs = int(real(word(ARG4, 7))); delta0 = real(word(ARG4, 8))
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set output outfile
set grid
set title sprintf("Divergence of nearby trajectories, {/Symbol d}_0 = %g, %d pair(s) (%s)", delta0, npairs, title)
set xlabel "t [s]"; set ylabel "log_{10} |{/Symbol d}(t)|"
set key bottom right box opaque
tm = 0.5*(t0 + t1)
fit_line(t) = b + slope*t/log(10)
lam_line(t) = fit_line(tm) + lam*(t - tm)/log(10)
set samples 200
stats dat u 2 nooutput
set yrange [floor(STATS_min) - 1 : ceil(sat) + 1]
tl = t1 + (sat - fit_line(t1))*log(10)/(lam > 0 ? lam : 1)
plot for [i=3:npairs+2] dat u 1:(column(i)) w l lw 0.5 lc rgb "#c0c0c0" notitle, \
     dat u 1:2 w l lw 2 lc rgb "#1f77b4" t "mean of log_{10}|{/Symbol d}| over the pairs", \
     [t0:t1] fit_line(x) w l lw 2.5 lc rgb "#d62728" t sprintf("fit over [%.1f, %.1f] s: slope %.4f s^{-1}", t0, t1, slope), \
     [0:tl] (lam > 0 ? lam_line(x) : 1/0) w l dt 2 lw 1.5 lc rgb "black" t sprintf("Benettin {/Symbol l}_1 = %.4f s^{-1}", lam), \
     sat w l dt 3 lw 1.5 lc rgb "#2ca02c" t "saturation"
