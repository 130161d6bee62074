# Overlay of the running lambda1 of several `dpend lyapunov` files. Called by
# scripts/plot_chaos.sh --compare as
#   gnuplot -c compare.gp DIR OUTFILE N LABELS LAMBDAS
# DIR: folder of c1.dat .. cN.dat (columns t lambda_1(t)) and final.dat (columns
# lambda1 spread index); OUTFILE: the PNG; N: number of files; LABELS: the N key
# entries (enhanced text, escaped), one per line; LAMBDAS: the N final lambda1.
# The arguments are data: the plot command built below holds only numbers.
dir = ARG1
n = int(real(ARG3))
labels = ARG4
lambdas = ARG5
# field i of s, fields separated by newlines
field(s, i) = (i <= 1) ? (strstrt(s, "\n") > 0 ? s[1:strstrt(s, "\n") - 1] : s) : \
              field(s[strstrt(s, "\n") + 1:*], i - 1)
label(i) = field(labels, i)
lam(i) = real(word(lambdas, i))
set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11"
set output ARG2
set title "Largest Lyapunov exponent: running estimates of several methods / steps"
set xlabel "t [s]"; set ylabel "{/Symbol l}_1(t) [1/s]"
set logscale x; set grid; set key top left box opaque
set yrange [0.8:1.6]; set xrange [1:6000]
cmd = "plot"
do for [i=1:n] {
  cmd = cmd.sprintf(" dir.'/c%d.dat' u 1:2 w l lw 1.5 lc %d t label(%d),", i, i, i)
  cmd = cmd.sprintf(" lam(%d) w l lc %d dt 2 notitle,", i, i)
}
cmd = cmd." dir.'/final.dat' u (3300*1.1**$3):1:2:3 w yerrorbars lc variable pt 7 ps 0.6"
cmd = cmd." t 'final value ± spread (batch means)'"
eval cmd
