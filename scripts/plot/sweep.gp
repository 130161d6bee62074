# Maps of one `dpend sweep` grid. Called by scripts/plot_sweep.sh as
#   gnuplot -c sweep.gp DIR OUTDIR T_END TAU AX1 AX2 LYAP NAME STATUS
# DIR: folder of the exported matrices (gnuplot nonuniform matrix format); OUTDIR:
# where the PNGs go; T_END: end time [s]; TAU: sqrt(l1/g) [s]; AX1, AX2: axis names;
# LYAP: Lyapunov matrix file [1/s] or ''; NAME: file name for the titles (enhanced
# text, escaped); STATUS: status matrix file or '' (0 not computed, 4 non-finite:
# drawn grey as "not integrated"). DIR/links holds the number of links N (a file:
# gnuplot -c takes nine arguments at most): one map flip_map_linkK.png per link from
# DIR/flipK.dat (in DIR/seconds: 1 s, 0 sqrt(l1/g)); DIR/balance 1 when the energy
# error is that of a damped or driven chain's energy balance; DIR/indicator the code of the sweep's fast indicator (0 none,
# 1 megno, 2 fli, 3 sali, 4 gali2), its matrix DIR/ind.dat. Every map uses the
# perceptual palette viridis (style.gp); angle axes are ticked in multiples of pi; the
# grey "not integrated" key entry is drawn only when a pixel is grey (the key entries
# drawn go to OUTDIR/keys.txt). The arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"
load style_gp
dir = ARG1
outdir = ARG2
tau = real(ARG4)
tend = real(ARG3)/tau
ax1 = ARG5
ax2 = ARG6
lyap = ARG7
name = ARG8
status = ARG9
stats dir.'/links' using 1 nooutput
links = int(STATS_max)
# DIR/seconds: 1 when the times are in s (--time-unit s), 0 in sqrt(l1/g)
stats dir.'/seconds' using 1 nooutput
secs = int(STATS_max)
tscale = (secs ? tau : 1.0)        # a natural time unit in the figures' unit
tunit = (secs ? "s" : "{/Symbol \326}(L/g)")
stats dir.'/indicator' using 1 nooutput
ind = int(STATS_max)
# "not integrated": grey, which viridis does not hold, drawn over the map from the
# status matrix; without a status matrix the NaN pixels of the energy, Lyapunov and
# indicator maps show the grey background instead. The key entry only when a pixel is
# grey: nst pixels of the status matrix, or without one, the map's NaN pixels
grey = "#8c8c8c"
ni(s) = (s == 0 || s == 4)
nst = 0
if (strlen(status) > 0) {
  stats status nonuniform matrix u (ni($3) ? 1 : 0) nooutput
  nst = STATS_sum
}
overlay = (nst > 0) ? \
  "status nonuniform matrix u 1:2:(140):(140):(140):(ni($3) ? 255 : 0) w rgbalpha notitle, " : ""
notint(n) = overlay.(n > 0 ? "NaN w boxes fs solid 1.0 noborder fc rgb grey t 'not integrated'" \
                            : "NaN notitle")
set print ARG2."/keys.txt" append
set key outside bottom center horizontal
set terminal pngcairo size 900,800 enhanced font fontspec(900)
set size ratio -1
set rmargin 14   # room for the colour bar's tic labels (10^{-12}) and its label
set tics out
set border lw 1
axlabel(a) = (a eq "m2/m1" || a eq "l2/l1") ? a : (a eq "g") ? "g [m/s^2]" : \
             (a[1:3] eq "com") ? a." [m]" : (a[1:7] eq "inertia") ? a." [kg m^2]" : \
             (a[1:1] eq "m") ? a." [kg]" : (a[1:1] eq "l") ? a." [m]" : \
             (a[1:5] eq "theta") ? "{/Symbol q}_".a[6:]." [rad] (from hanging)" : \
             (a[1:1] eq "w") ? a." [rad/s]" : a." [rad] (from horizontal)"
set xlabel axlabel(ax1)
set ylabel axlabel(ax2)
set autoscale xfix; set autoscale yfix
# angle axes (theta*, q*, the angles from horizontal): tics in multiples of pi over
# the grid's extent
isangle(a) = (a[1:5] eq "theta" || a eq "q1" || a eq "q2" || a[1:1] eq "q")
stats dir.'/flip.dat' nonuniform matrix u 1 nooutput
if (isangle(ax1) && STATS_max > STATS_min) { eval "set xtics (".pitics(STATS_min, STATS_max).")" }
stats dir.'/flip.dat' nonuniform matrix u 2 nooutput
if (isangle(ax2) && STATS_max > STATS_min) { eval "set ytics (".pitics(STATS_min, STATS_max).")" }
set object 1 rectangle from graph 0,0 to graph 1,1 behind fc rgb "white" fs solid noborder
# flip times: log scale, white = no flip before t_end (NaN pixels are not drawn)
set logscale cb
set cbrange [0.3*tscale:tend*tscale]
set format cb "10^{%L}"
eval "set palette ".viridis
set cblabel "time of the first flip [".tunit."]"
print keyline("flip_map.png", sprintf("colour scale %.6g .. %.6g %s", 0.3*tscale, tend*tscale, \
              secs ? "s" : "sqrt(l1/g)"), 1)

set output outdir."/flip_map.png"
which = (links == 2) ? "either" : "any"
set title "First flip of ".which." link (white: none before ".sprintf("%g", tend*tscale)." ".tunit.")\n".name
if (nst > 0) { print keyline("flip_map.png", "not integrated", nst) }
eval "plot dir.'/flip.dat' nonuniform matrix using 1:2:3 with image notitle, ".notint(nst)

do for [k = 1:links] {
  set output outdir."/flip_map_link".k.".png"
  set title "First flip of link ".k." (white: none)\n".name
  if (nst > 0) { print keyline("flip_map_link".k.".png", "not integrated", nst) }
  eval "plot dir.'/flip".k.".dat' nonuniform matrix using 1:2:3 with image notitle, ".notint(nst)
}

# NaN here means not integrated: the background is the grey of the key entry
set object 1 rectangle from graph 0,0 to graph 1,1 behind fc rgb grey fs solid noborder
# the sweep's energy error is in units of the potential's range V_max - V_min (one
# scale for the whole map), not the relative energy error |E(t) - E(0)| / E_s of
# simulate and study: the label says which
# (a damped or driven chain: the error of its energy balance, with the works of the
# friction, the support and the torques)
stats dir.'/balance' using 1 nooutput
balance = int(STATS_max)
set output outdir."/energy_error.png"
if (balance) {
  set title "Largest error of the energy balance in units of the potential's range\nmax_t |E(t) - E(0) + W_{friction} - W_{support} - W_{torque}| / (V_{max} - V_{min})\n".name
  set cblabel "max_t |E - E(0) + W_f - W_s - W_{/Symbol t}| / (V_{max} - V_{min})"
} else {
  set title "Largest energy error in units of the potential's range, max_t |E(t) - E(0)| / (V_{max} - V_{min})\n".name
  set cblabel "max_t |E(t) - E(0)| / (V_{max} - V_{min})"
}
set autoscale cb
# grey: not integrated (status 0 or 4), and the pixels below the flip energy bound,
# which cannot flip and are not integrated (status 3; their energy error is NaN)
stats dir.'/eerr.dat' nonuniform matrix u ($3 != $3 ? 1 : 0) nooutput
nnan = int(STATS_sum)
ng = (strlen(status) > 0 ? nst : nnan)
nb = (strlen(status) > 0 && nnan > nst ? nnan - nst : 0)
below = "NaN w boxes fs solid 1.0 noborder fc rgb grey t 'cannot flip (below the energy bound): not integrated'"
if (ng > 0) { print keyline("energy_error.png", "not integrated", ng) }
if (nb > 0) { print keyline("energy_error.png", "cannot flip (below the energy bound): not integrated", nb) }
eval "plot dir.'/eerr.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 1e-16 ? $3 : 1e-16)) with image notitle, ".notint(ng).(nb > 0 ? ", ".below : "")

if (strlen(lyap) > 0) {
  set output outdir."/lyapunov.png"
  set title "Largest Lyapunov exponent\n".name
  unset logscale cb
  set format cb "%g"
  set autoscale cb
  set cblabel "{/Symbol l} [1/".tunit."]"
  ng = nst
  if (strlen(status) == 0) { stats lyap nonuniform matrix u ($3 != $3 ? 1 : 0) nooutput; ng = STATS_sum }
  if (ng > 0) { print keyline("lyapunov.png", "not integrated", ng) }
  eval "plot lyap nonuniform matrix using 1:2:($3*tau/tscale) with image notitle, ".notint(ng)
}

# the fast indicator: a scale for each (NaN, not finite: the grey background)
ng = nst
if (ind > 0 && strlen(status) == 0) {
  stats dir.'/ind.dat' nonuniform matrix u ($3 != $3 ? 1 : 0) nooutput; ng = STATS_sum
}
indfig = (ind == 1 ? "megno.png" : (ind == 2 ? "fli.png" : (ind == 3 ? "sali.png" : "gali2.png")))
if (ind > 0 && ng > 0) { print keyline(indfig, "not integrated", ng) }
if (ind == 1) {
  # MEGNO <Y>: 2 is the limit of regular orbits (the middle of the scale); below:
  # isochronous, stable; above: chaotic (<Y> ~ lambda1 t/2), saturated at 4
  set output outdir."/megno.png"
  set title "MEGNO <Y> at t_{end} (2: regular; > 2: chaotic)\n".name
  unset logscale cb
  set format cb "%g"
  set cbrange [0:4]
  set cbtics ("0" 0, "1" 1, "2" 2, "3" 3, "{/Symbol \263} 4" 4)
  set cblabel "<Y>"
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 4 ? 4 : ($3 < 0 ? 0 : $3))) with image notitle, ".notint(ng)
}
if (ind == 2) {
  # FLI = ln |delta|: grows like ln t (regular) or lambda1 t (chaotic); linear scale
  set output outdir."/fli.png"
  set title "Fast Lyapunov indicator ln |{/Symbol d}(t_{end})|\n".name
  unset logscale cb
  set format cb "%g"
  set autoscale cb
  set cblabel "FLI"
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:3 with image notitle, ".notint(ng)
}
if (ind == 3 || ind == 4) {
  # SALI in [0, sqrt 2], GALI_2 in [0, 1]: log scale, near 0 (dark) for chaos, the
  # rounding floor 1e-16 at the bottom
  what = (ind == 3) ? "sali" : "gali2"
  set output outdir."/".what.".png"
  set title ((ind == 3) ? "SALI" : "GALI_2")." at t_{end} (0: chaotic)\n".name
  set logscale cb
  set cbrange [1e-16:((ind == 3) ? sqrt(2) : 1)]
  set format cb "10^{%L}"
  set cblabel (ind == 3) ? "SALI" : "GALI_2"
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 1e-16 ? $3 : 1e-16)) with image notitle, ".notint(ng)
}
set print
