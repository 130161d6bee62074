# Overlay of the running lambda1 of several `dpend lyapunov` files. Called by
# scripts/plot_chaos.sh --compare as
#   gnuplot -c compare.gp DIR OUTFILE N LABELS LAMBDAS
# DIR: folder of c1.dat .. cN.dat (columns t lambda_1(t)) and final.dat (columns
# lambda1 spread index); OUTFILE: the PNG; N: number of files; LABELS: the N key
# entries (enhanced text, escaped), one per line; LAMBDAS: the N final lambda1.
# The arguments are data: the plot command built below holds only numbers.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
dir = ARG1
n = int(real(ARG3))
labels = ARG4
lambdas = ARG5
# field i of s, fields separated by newlines
field(s, i) = (i <= 1) ? (strstrt(s, "\n") > 0 ? s[1:strstrt(s, "\n") - 1] : s) : \
              field(s[strstrt(s, "\n") + 1:*], i - 1)
label(i) = field(labels, i)
lam(i) = real(word(lambdas, i))
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set output ARG2
set title "Largest Lyapunov exponent: running estimates of several methods / steps"
set xlabel "t [s]"; set ylabel "{/Symbol l}_1(t) [1/s]"
set logscale x; set grid; set key top left box opaque
# Axes fitted to the data: t from the first sample after tmax/1e4 to the error bars of
# the final values (drawn at tmax*1.1^(i+1), right of the curves); lambda over the
# running estimates of the last decade of t (t >= tmax/10, earlier ones are transients
# and leave the plot) and the final values ± spread, with a margin of 5 % each side
tmax = 0; tmin = 1e300
do for [i=1:n] {
  stats dir.sprintf("/c%d.dat", i) u 1 nooutput
  tmax = (STATS_max > tmax) ? STATS_max : tmax
}
ylo = 1e300; yhi = -1e300
do for [i=1:n] {
  stats dir.sprintf("/c%d.dat", i) u ($1 >= tmax/1e4 && $1 > 0 ? $1 : NaN) nooutput
  tmin = (STATS_min < tmin) ? STATS_min : tmin
  stats dir.sprintf("/c%d.dat", i) u ($1 >= tmax/10 ? $2 : NaN) nooutput
  ylo = (STATS_min < ylo) ? STATS_min : ylo; yhi = (STATS_max > yhi) ? STATS_max : yhi
}
stats dir."/final.dat" u ($1 - $2) nooutput
ylo = (STATS_min < ylo) ? STATS_min : ylo
stats dir."/final.dat" u ($1 + $2) nooutput
yhi = (STATS_max > yhi) ? STATS_max : yhi
dy = (yhi > ylo) ? 0.05*(yhi - ylo) : 0.05*(abs(yhi) > 0 ? abs(yhi) : 1)
set yrange [ylo - dy:yhi + dy]
set xrange [tmin:tmax*1.1**(n + 2)]
cmd = "plot"
do for [i=1:n] {
  cmd = cmd.sprintf(" dir.'/c%d.dat' u 1:2 w l lw 1.5 lc %d t label(%d),", i, i, i)
  cmd = cmd.sprintf(" lam(%d) w l lc %d dt 2 notitle,", i, i)
}
cmd = cmd." dir.'/final.dat' u (tmax*1.1**($3 + 1)):1:2:3 w yerrorbars lc variable pt 7 ps 0.6"
cmd = cmd." t 'final value ± spread (batch means)'"
eval cmd
