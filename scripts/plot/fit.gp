# Figures of `dpend fit`. Called by scripts/plot_fit.sh as
#   gnuplot -c fit.gp fit DATAFILE OUTDIR TITLE M TWINDOW TOL RMS KIND
#     DATAFILE: columns t data(1..M) model(1..M) residual(1..M) in_window; KIND q: M = N
#     angles from the horizontal x axis (rad), KIND xy: M = 2N positions x1 y1 ... of
#     the link ends (m); TWINDOW: end of the fit window (s); TOL: the horizon
#     tolerance, RMS: the RMS residual of the window (rad or m); KIND model NAME:UNIT ...:
#     M = the model's coordinates, named with their units ("model r:m phi:rad")
#   gnuplot -c fit.gp horizon DATAFILE OUTDIR TITLE
#     DATAFILE: columns t1 t_window horizon censored (s, s, s, 0/1)
# TITLE: file name, enhanced text, escaped. Panels share one left margin (the plot
# areas line up); angle panels of the overlay are ticked in multiples of pi; text
# scales with the canvas (style.gp). The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"
load style_gp
kind = ARG1
datafile = ARG2
outdir = ARG3
title = ARG4
array linkcol[8] = ["#9400d3", "#009e73", "#56b4e9", "#e69f00", "#0072b2", "#e51e10", \
                    "#f0e442", "#000000"]
lc(i) = linkcol[(i - 1)%8 + 1]
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set grid
set key outside right

if (kind eq "horizon") {
  set output outdir."/fit_horizon.png"
  set title "Prediction horizon against the fit window (".title.")"
  set xlabel "length of the fit window T - t_1 [s]"
  set ylabel "horizon after T [s]"
  set yrange [0:*]
  plot datafile using ($2 - $1):($4 < 0.5 ? $3 : NaN) with linespoints pt 7 lc rgb "#0072b2" \
         title "left the tolerance", \
       datafile using ($2 - $1):($4 > 0.5 ? $3 : NaN) with points pt 6 ps 1.5 \
         lc rgb "#e51e10" title "within it to the data's end (lower bound)"
  unset output
  exit
}

N = int(real(ARG5))
Tw = real(ARG6)
tol = real(ARG7)
rms = real(ARG8)
xy = (ARG9 eq "xy")
model = (word(ARG9, 1) eq "model")
unit = xy ? "m" : (model ? "(units of each panel)" : "rad")
labels = model ? ARG9[7:] : ""
# panel i: q_i, or x_k / y_k of link k = (i + 1)/2, or the model's coordinate i
wlabel(w) = sprintf("%s [%s]", w[1:strstrt(w, ":") - 1], w[strstrt(w, ":") + 1:])
label(i) = xy ? sprintf("%s_%d [m]", (i%2 == 1 ? "x" : "y"), (i + 1)/2) : \
           (model ? wlabel(word(labels, i)) : sprintf("q_%d [rad]", i))
colour(i) = xy ? lc((i + 1)/2) : lc(i)
isangle(i) = (!xy && (!model || word(labels, i)[strstrt(word(labels, i), ":") + 1:] eq "rad"))
# the same left margin for every panel: the plot areas line up whatever the tic labels
set lmargin at screen 0.12
cin = 3*N + 2                  # column of in_window
set arrow 1 from first Tw, graph 0 to first Tw, graph 1 nohead dt 2 lc rgb "#555555"

set output outdir."/fit_overlay.png"
set multiplot layout N, 1 title "Data and fitted model (".title."); dashed: end of the fit window"
set xlabel "t [s]"
do for [i = 1:N] {
  set ylabel label(i)
  set ytics auto
  if (isangle(i)) {
    stats datafile using (column(1 + i)) nooutput
    if (STATS_max > STATS_min) { eval "set ytics (".pitics(STATS_min, STATS_max).")" }
  }
  plot datafile using 1:(column(cin) > 0.5 ? column(1 + i) : NaN) with points pt 7 ps 0.4 \
         lc rgb colour(i) title "data (fit window)", \
       datafile using 1:(column(cin) < 0.5 ? column(1 + i) : NaN) with points pt 6 ps 0.4 \
         lc rgb "#888888" title "data (after)", \
       datafile using 1:(column(1 + N + i)) with lines lw 1.5 lc rgb "#000000" title "model"
}
unset multiplot
unset output

set output outdir."/fit_residuals.png"
set multiplot layout N, 1 title sprintf("Residuals data - model (%s); RMS in the window %.3g %s, band: tolerance %.3g %s", title, rms, unit, tol, unit)
do for [i = 1:N] {
  set ylabel "residual ".label(i)
  set yrange [*:*]
  set ytics auto
  plot tol with lines dt 3 lc rgb "#e51e10" notitle, \
       -tol with lines dt 3 lc rgb "#e51e10" notitle, \
       datafile using 1:(column(1 + 2*N + i)) with points pt 7 ps 0.4 lc rgb colour(i) \
         notitle
}
unset multiplot
unset output
