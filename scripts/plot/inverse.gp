# The figures of `dpend torques` and `dpend identify`. Called by
# scripts/plot_torques.sh as
#   gnuplot -c inverse.gp KIND DATAFILE OUTDIR TITLE N MEASURED BANDS WINDOW
# KIND torques: DATAFILE columns t, tau_1..N [, tau_measured_1..N, residual_1..N];
#   inverse_torques.png (computed, and measured when MEASURED is 1) and, with them,
#   inverse_residual.png with the predicted error +-BANDS(i) (N values) as a band;
# KIND identify: DATAFILE columns t, residual_1..N; identify_residual.png with the
#   residual scatter BANDS(i) of each joint.
# TITLE: the file's name (enhanced text, escaped); WINDOW: the filter's window
# (samples). The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
kind = ARG1
datafile = ARG2
outdir = ARG3
title = ARG4
n = int(ARG5)
measured = int(ARG6)
bands = ARG7
window = int(ARG8)
band(i) = real(word(bands, i))
h = 300*n + 100
if (kind eq "torques") {
   set terminal pngcairo size 1000,h enhanced font fontspec(1000)
   set output outdir."/inverse_torques.png"
   set multiplot layout n,1 title sprintf("Joint torques the motion requires (%s; filter window %d samples)", title, window)
   set grid
   set key outside right
   do for [i=1:n] {
      set xlabel (i == n ? "t [s]" : "")
      set ylabel sprintf("{/Symbol t}_%d [N m]", i)
      if (measured) {
         plot datafile using 1:(column(1 + n + i)) with lines lw 1 lc rgb "#999999" title "measured", \
              datafile using 1:(column(1 + i)) with lines lw 1.5 lc rgb "#1f77b4" title "Newton-Euler"
      } else {
         plot datafile using 1:(column(1 + i)) with lines lw 1.5 lc rgb "#1f77b4" title "Newton-Euler"
      }
   }
   unset multiplot
   if (measured) {
      set output outdir."/inverse_residual.png"
      set multiplot layout n,1 title sprintf("Measured minus computed torques (%s)", title)
      do for [i=1:n] {
         set xlabel (i == n ? "t [s]" : "")
         set ylabel sprintf("residual %d [N m]", i)
         b = band(i)
         plot datafile using 1:(-b):(b) with filledcurves lc rgb "#ffe0b0" title "predicted error of the filter", \
              datafile using 1:(column(1 + 2*n + i)) with lines lw 1 lc rgb "#d62728" title "residual"
      }
      unset multiplot
   }
}
if (kind eq "identify") {
   set terminal pngcairo size 1000,h enhanced font fontspec(1000)
   set output outdir."/identify_residual.png"
   set multiplot layout n,1 title sprintf("Torque residual of the identified model (%s)", title)
   set grid
   set key outside right
   do for [i=1:n] {
      set xlabel (i == n ? "t [s]" : "")
      set ylabel sprintf("residual %d [N m]", i)
      b = band(i)
      plot datafile using 1:(-b):(b) with filledcurves lc rgb "#e0e0ff" title sprintf("scatter %.3g N m", b), \
           datafile using 1:(column(1 + i)) with points pt 7 ps 0.5 lc rgb "#d62728" title "residual at the rows used"
   }
   unset multiplot
}
