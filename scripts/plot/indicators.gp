# Figure of `dpend indicators`. Called by scripts/plot_chaos.sh as
#   gnuplot -c indicators.gp DAT OUTDIR TITLE "K N TEND FLIEND GALI_2 .. GALI_K"
# DAT: columns t Y(t) <Y>(t) FLI(t) SALI(t) GALI_2(t) .. GALI_K(t);
# OUTDIR: where indicators.png goes (and keys.txt, the key entries drawn: style.gp);
# TITLE: enhanced text (escaped); then one argument of numbers: K (deviation vectors,
# 2N), N (links = degrees of freedom), TEND (last sample time [s]), FLIEND (FLI
# there), the final GALI_k. The reference behaviours: regular orbits <Y> -> 2,
# FLI ~ ln t + c (|delta| ~ t), SALI and GALI_k (k <= N) bounded, GALI_k ~
# t^(-2(k-N)) for k > N; chaotic orbits <Y> ~ lambda1 t/2, FLI ~ lambda1 t, GALI_2 ~
# exp(-(lambda1 - lambda2) t) with lambda2 ~ 0. Only the references of the orbit's
# kind are drawn: chaotic when <Y>(TEND) > 4 or GALI_2(TEND) < 1e-8 (then lambda1 is
# estimated as FLIEND/TEND), else regular (the power laws go through the final
# GALI_k; ln t + c is fitted to the whole run, on a chaotic orbit to its first two
# Lyapunov times, where FLI still grows slowly). The power laws of GALI_k (k > N) are fitted to the
# second half of the run (their amplitude; the exponent is the theory's). Log axes span the data only. Keys sit below the
# panels. The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"
load style_gp
dat = ARG1
outfile = ARG2."/indicators.png"
keys = ARG2."/keys.txt"
title = ARG3
k = int(real(word(ARG4, 1))); N = int(real(word(ARG4, 2)))
tend = real(word(ARG4, 3)); fliend = real(word(ARG4, 4))
ga(i) = real(word(ARG4, 3 + i))
lam = fliend/tend
# the last <Y>, the first sample time > 0, the smallest SALI/GALI > 0
ylast = NaN; t0 = tend
stats dat u (ylast = $3, t0 = ($1 > 0 && $1 < t0 ? $1 : t0), 0) nooutput
chaotic = (ylast > 4 || (ga(2) == ga(2) && ga(2) < 1e-8))
ymin = 1.0
do for [i = 5:4 + k] {
  stats dat u (ymin = (pos(column(i)) < ymin ? column(i) : ymin), 0) nooutput
}
ylo = 10**floor(log10(ymin) - 0.01)
# ln t + c: c the mean of FLI - ln t over the whole run (regular) or, on a chaotic
# orbit, over its first two Lyapunov times 2/lambda1 (at least the first sample),
# while |delta| has not yet grown exponentially
tfit = (chaotic ? (2/lam > t0 ? 2/lam : t0) : tend)
STATS_records = 0
stats dat u (($1 > 0 && $1 <= tfit && has($4)) ? $4 - log($1) : NaN) nooutput
c = (STATS_records > 0 ? STATS_mean : fliend - log(tend))
# the power law of GALI_k (k > N) fitted to the second half of a regular run:
# amp[k] = exp(mean(ln GALI_k + 2(k - N) ln(t/TEND))) over t >= TEND/2
array amp[20]
do for [i = N + 1:k] {
  amp[i] = NaN; STATS_records = 0
  stats dat u (($1 >= tend/2 && pos(column(i + 4)) == pos(column(i + 4))) ? \
    log(column(i + 4)) + 2*(i - N)*log($1/tend) : NaN) nooutput
  if (STATS_records > 0) { amp[i] = exp(STATS_mean) }
}
# points with data of each series (the key lists only those with data)
array npts[20]
stats dat u (has($2) ? 1 : 0) nooutput; npts[1] = STATS_sum
stats dat u (has($3) ? 1 : 0) nooutput; npts[2] = STATS_sum
stats dat u (has($4) ? 1 : 0) nooutput; npts[3] = STATS_sum
stats dat u (pos($5) == pos($5) ? 1 : 0) nooutput; npts[4] = STATS_sum
do for [i = 2:k] {
  stats dat u (pos(column(i + 4)) == pos(column(i + 4)) ? 1 : 0) nooutput
  npts[3 + i] = STATS_sum
}
array cols[10] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", \
                   "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
col(i) = cols[(i - 1)%10 + 1]
tt(n, s) = (n > 0 ? s : "")
set terminal pngcairo size 1200,1000 enhanced font fontspec(1200)
set output outfile
set grid
set samples 400
verdict = chaotic ? sprintf("chaotic: <Y>(t_{end}) = %.3g; {/Symbol l}_1 ≈ FLI/t = %.4g s^{-1}", ylast, lam) \
  : sprintf("regular: <Y>(t_{end}) = %.3g", ylast)
set multiplot layout 2,2 title "Chaos indicators (".title."); ".verdict
set key below left Left reverse samplen 3 spacing 1.1 maxrows 2

set print keys append
set title "MEGNO"
set xlabel "t [s]"; set ylabel "Y, <Y>"
print keyline("indicators.png", "Y(t)", npts[1])
print keyline("indicators.png", "<Y>(t)", npts[2])
print keyline("indicators.png", "regular: <Y> = 2", npts[2])
if (chaotic) { print keyline("indicators.png", "chaotic: λ1 t/2", npts[2]) }
plot dat u 1:2 w l lw 0.6 lc rgb "#a0c4e8" t tt(npts[1], "Y(t)"), \
     dat u 1:3 w l lw 2 lc rgb "#1f77b4" t tt(npts[2], "<Y>(t)"), \
     2 w l dt 2 lw 1.5 lc rgb "black" t "regular: <Y> = 2", \
     [0:tend] (chaotic ? lam*x/2 : NaN) w l dt 3 lw 1.5 lc rgb "#d62728" \
       t (chaotic ? "chaotic: {/Symbol l}_1 t/2" : "")

set title "Fast Lyapunov indicator"
set key maxcols auto maxrows 2
set ylabel "FLI = max_i ln|{/Symbol d}_i|"
print keyline("indicators.png", "FLI(t)", npts[3])
print keyline("indicators.png", "regular: ln t + c", npts[3])
if (chaotic) { print keyline("indicators.png", "chaotic: λ1 t", npts[3]) }
plot dat u 1:4 w l lw 2 lc rgb "#2ca02c" t tt(npts[3], "FLI(t)"), \
     [t0:tend] log(x) + c w l dt 2 lw 1.5 lc rgb "black" \
       t sprintf("regular: ln t + c (fit: t ≤ %.4g s)", tfit), \
     [t0:tend] (chaotic ? lam*x : NaN) w l dt 3 lw 1.5 lc rgb "#d62728" \
       t (chaotic ? "chaotic: {/Symbol l}_1 t" : "")

set title "SALI and GALI_k (log-log)"
set key maxcols auto maxrows 2
set ylabel "GALI_k, SALI"
set logscale xy; set format x "10^{%L}"; set format y "10^{%L}"
set xrange [t0:tend]
set yrange [ylo:3]
print keyline("indicators.png", "SALI", npts[4])
do for [i = 2:k] { print keyline("indicators.png", sprintf("GALI_%d", i), npts[3 + i]) }
if (!chaotic) {
  do for [i = N + 1:k] {
    if (amp[i] > 0) { print keyline("indicators.png", sprintf("t^-%d", 2*(i - N)), npts[3 + i]) }
  }
}
plot for [i=2:k] dat u 1:(pos(column(i+4))) w l lw 1.8 lc rgb col(i) t tt(npts[3 + i], sprintf("GALI_%d", i)), \
     for [i=N+1:k] [t0:tend] ((!chaotic && amp[i] > 0) ? amp[i]*(x/tend)**(-2*(i-N)) : NaN) \
       w l dt (10,6) lw 2.5 lc rgb col(i) \
       t ((!chaotic && amp[i] > 0) ? sprintf("t^{-%d} (GALI_%d, regular)", 2*(i-N), i) : ""), \
     dat u 1:(pos($5)) w l lw 2.5 dt (4,4) lc rgb "black" t tt(npts[4], "SALI (≈ GALI_2)")

set title "SALI, GALI_2 against t (semi-log)"
unset logscale x; set format x "%g"
# the time GALI_2 needs to reach roundoff on a chaotic orbit, or the whole run
set xrange [0:(chaotic && lam > 0 && 45/lam < tend ? 45/lam : tend)]
stats dat u (pos($6) == pos($6) ? $6 : 1) nooutput
set yrange [10**floor(log10(STATS_min) - 0.01):3]
if (chaotic) { print keyline("indicators.png", "chaotic: e^-(λ1-λ2)t", npts[5]) }
plot dat u 1:(pos($6)) w l lw 1.8 lc rgb col(2) t tt(npts[5], "GALI_2"), \
     [0:tend] (chaotic ? exp(-lam*x) : NaN) w l dt 3 lw 1.5 lc rgb "#d62728" \
       t (chaotic ? "chaotic: e^{-({/Symbol l}_1 - {/Symbol l}_2) t}, {/Symbol l}_2 ≈ 0" : ""), \
     dat u 1:(pos($5)) w l lw 2.5 dt (4,4) lc rgb "black" t tt(npts[4], "SALI")
set print
unset multiplot
