# Figures of `dpend fit`. Called by scripts/plot_fit.sh as
#   gnuplot -c fit.gp fit DATAFILE OUTDIR TITLE M TWINDOW TOL "RMS HORIZON" KIND
#     DATAFILE: columns t data(1..M) model(1..M) residual(1..M) in_window; KIND q: M = N
#     angles from the horizontal x axis (rad), KIND xy: M = 2N positions x1 y1 ... of
#     the link ends (m), or "xy K ..." the points K observed (M = 2 per point); TWINDOW: end of the fit window (s); TOL: the horizon
#     tolerance, RMS: the RMS residual of the window (rad or m); KIND model NAME:UNIT ...:
#     M = the model's coordinates, named with their units ("model r:m phi:rad");
#     HORIZON (one argument with RMS: gnuplot -c takes nine): the prediction horizon
#     after TWINDOW (s), -1 without samples after it
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
# a tic step of 1, 2 or 5 times a power of ten giving about four intervals over r > 0
nice_p(r) = 10**floor(log10(r/4.0))
nice_m(r) = r/4.0/nice_p(r)
nicestep(r) = nice_p(r)*(nice_m(r) < 1.5 ? 1 : (nice_m(r) < 3.5 ? 2 : (nice_m(r) < 7.5 ? 5 : 10)))
ntics(lo, hi, st) = int(floor(hi/st + 1e-9) - ceil(lo/st - 1e-9)) + 1
set print ARG3."/keys.txt" append

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
rms = real(word(ARG8, 1))
xy = (word(ARG9, 1) eq "xy")
# the point of panel i (x_k, y_k): the observed points after "xy", else 1, 2, ...
pnt(i) = (xy && words(ARG9) > 1 ? int(word(ARG9, 1 + (i + 1)/2)) : (i + 1)/2)
model = (word(ARG9, 1) eq "model")
unit = xy ? "m" : (model ? "(units of each panel)" : "rad")
labels = model ? ARG9[7:] : ""
# panel i: q_i, or x_k / y_k of link k = (i + 1)/2, or the model's coordinate i
wlabel(w) = sprintf("%s [%s]", w[1:strstrt(w, ":") - 1], w[strstrt(w, ":") + 1:])
label(i) = xy ? sprintf("%s_%d [m]", (i%2 == 1 ? "x" : "y"), pnt(i)) : \
           (model ? wlabel(word(labels, i)) : sprintf("q_%d [rad]", i))
colour(i) = xy ? lc(pnt(i)) : lc(i)
isangle(i) = (!xy && (!model || word(labels, i)[strstrt(word(labels, i), ":") + 1:] eq "rad"))
# the same left and right margins for every panel: the plot areas line up whatever
# the tic labels, the key (top panel only) in the right margin; each panel about 190
# px high, x labelled below the last only
set lmargin at screen 0.12
set rmargin at screen 0.76
H = (N*190 + 110 > 600) ? N*190 + 110 : 600
panel_px = int((H - 110)/N)
set terminal pngcairo size 1000,H enhanced font fontspec(1000)
cin = 3*N + 2                  # column of in_window
set arrow 1 from first Tw, graph 0 to first Tw, graph 1 nohead dt 2 lc rgb "#555555"
set key at screen 0.985, screen 1 - 60.0/H right top

set output outdir."/fit_overlay.png"
set multiplot layout N, 1 title "Data and fitted model (".title."); dashed: end of the fit window"
do for [i = 1:N] {
  set ylabel label(i)
  set xlabel (i == N ? "t [s]" : "")
  set format x (i == N ? "% h" : "")
  if (i == 1) { set key } else { unset key }
  stats datafile using (column(1 + i)) nooutput
  lo = STATS_min; hi = STATS_max; nd = STATS_records
  stats datafile using (column(1 + N + i)) nooutput
  lo = (STATS_min < lo ? STATS_min : lo); hi = (STATS_max > hi ? STATS_max : hi)
  set yrange [*:*]
  set ytics auto
  if (hi > lo) {
    if (isangle(i)) {
      eval "set ytics (".pitics(lo, hi).")"
    } else {
      set ytics nicestep(hi - lo)
      print keyline("fit_overlay.png", sprintf("tics %s: %d in %d px", label(i), \
                    ntics(lo, hi, nicestep(hi - lo)), panel_px), nd)
    }
  }
  if (i == 1) {
    print keyline("fit_overlay.png", "data (fit window)", nd)
    print keyline("fit_overlay.png", "model", nd)
  }
  plot datafile using 1:(column(cin) > 0.5 ? column(1 + i) : NaN) with points pt 7 ps 0.4 \
         lc rgb colour(i) title "data (fit window)", \
       datafile using 1:(column(cin) < 0.5 ? column(1 + i) : NaN) with points pt 6 ps 0.4 \
         lc rgb "#888888" title "data (after)", \
       datafile using 1:(column(1 + N + i)) with lines lw 1.5 lc rgb "#000000" title "model"
}
unset multiplot
unset output

# residuals: each panel to its own scale, +-5 times the RMS of its residuals in the fit
# window; points beyond are drawn at the edge (triangles), the tolerance band only
# where it falls inside (else said in the panel)
hz = real(word(ARG8, 2))
if (hz >= 0) { set arrow 2 from first Tw + hz, graph 0 to first Tw + hz, graph 1 nohead dt 3 lw 1.5 lc rgb "#e51e10" }
set output outdir."/fit_residuals.png"
set multiplot layout N, 1 title sprintf("Residuals data - model (%s), RMS in the window %.3g %s\ndashed: end of the fit window; red: the prediction horizon", title, rms, unit)
do for [i = 1:N] {
  r(k) = column(1 + 2*N + i)
  set ylabel "residual ".label(i)
  set xlabel (i == N ? "t [s]" : "")
  set format x (i == N ? "% h" : "")
  stats datafile using (column(cin) > 0.5 ? r(0)**2 : NaN) nooutput
  rms_i = sqrt(STATS_mean)
  nwin = STATS_records
  lim = (rms_i > 0 ? 5*rms_i : (tol > 0 ? tol : 1))
  stats datafile using (abs(r(0)) > lim ? 1 : 0) nooutput
  nout = int(STATS_sum)
  set yrange [-lim:lim]
  set ytics nicestep(2*lim)
  unset label 1
  if (tol >= lim) { set label 1 sprintf("horizon tolerance ±%.3g %s: beyond this range", tol, unit) at graph 0.01, graph 0.92 left front }
  unset label 2
  if (hz >= 0 && i == 1) { set label 2 " horizon" at first Tw + hz, graph 0.06 left front textcolor rgb "#e51e10" }
  set key
  print keyline("fit_residuals.png", sprintf("range %s: ±%.4g (5 RMS of the window, RMS %.4g)", \
                label(i), lim, rms_i), nwin)
  if (nout > 0) { print keyline("fit_residuals.png", "beyond ±5 RMS (at the edge)", nout) }
  if (tol < lim) { print keyline("fit_residuals.png", "tolerance", 2) }
  plot datafile using 1:(abs(r(0)) <= lim ? r(0) : NaN) with points pt 7 ps 0.4 \
         lc rgb colour(i) title (i == 1 ? "data - model" : ""), \
       datafile using 1:(r(0) > lim ? lim : (r(0) < -lim ? -lim : NaN)) with points \
         pt 9 ps 0.8 lc rgb "#e51e10" title (nout > 0 ? "beyond ±5 RMS (at the edge)" : ""), \
       (tol < lim ? tol : NaN) with lines dt 3 lc rgb "#e51e10" title (tol < lim && i == 1 ? "tolerance" : ""), \
       (tol < lim ? -tol : NaN) with lines dt 3 lc rgb "#e51e10" notitle
}
unset multiplot
unset output
