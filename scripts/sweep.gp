# Maps of one `dpend sweep` grid. Called by scripts/plot_sweep.sh as
#   gnuplot -c sweep.gp DIR OUTDIR T_END TAU AX1 AX2 LYAP NAME STATUS
# DIR: folder of the exported matrices (gnuplot nonuniform matrix format); OUTDIR:
# where the PNGs go; T_END: end time [s]; TAU: sqrt(l1/g) [s]; AX1, AX2: axis names;
# LYAP: Lyapunov matrix file [1/s] or ''; NAME: file name for the titles (enhanced
# text, escaped); STATUS: status matrix file or '' (0 not computed, 4 non-finite:
# drawn grey as "not integrated"). DIR/links holds the number of links N (a file:
# gnuplot -c takes nine arguments at most): one map flip_map_linkK.png per link from
# DIR/flipK.dat; DIR/indicator the code of the sweep's fast indicator (0 none,
# 1 megno, 2 fli, 3 sali, 4 gali2), its matrix DIR/ind.dat. The arguments are
# data: never pasted into code.
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
stats dir.'/indicator' using 1 nooutput
ind = int(STATS_max)
# "not integrated": grey, which none of the palettes below holds (their ends are
# white, red and near-white), drawn over the map from the status matrix, with a key
# entry; without a status matrix the NaN pixels of the energy and Lyapunov maps show
# the grey background instead
grey = "#8c8c8c"
ni(s) = (s == 0 || s == 4)
notint = (strlen(status) > 0) ? \
  "status nonuniform matrix u 1:2:(140):(140):(140):(ni($3) ? 255 : 0) w rgbalpha notitle, " : ""
notint = notint."NaN w boxes fs solid 1.0 noborder fc rgb grey t 'not integrated'"
set key outside bottom center horizontal
set terminal pngcairo size 900,800 enhanced font "DejaVu Sans,11"
set size ratio -1
set tics out
set border lw 1
axlabel(a) = (a eq "m1" || a eq "m2") ? a." [kg]" : (a eq "l1" || a eq "l2") ? a." [m]" : \
             (a eq "m2/m1" || a eq "l2/l1") ? a : \
             (a[1:5] eq "theta") ? "{/Symbol q}_".a[6:]." [rad] (from hanging)" : \
             (a[1:1] eq "w") ? a." [rad/s]" : a." [rad] (from horizontal)"
set xlabel axlabel(ax1)
set ylabel axlabel(ax2)
set autoscale xfix; set autoscale yfix
set object 1 rectangle from graph 0,0 to graph 1,1 behind fc rgb "white" fs solid noborder
# flip times: log scale, white = no flip before t_end (NaN pixels are not drawn)
set logscale cb
set cbrange [0.3:tend]
set format cb "10^{%L}"
set palette defined (0 "#1a9850", 1 "#fee08b", 2 "#d73027", 3 "#762a83", 4 "#2166ac")
set cblabel "time of the first flip [{/Symbol \326}(L/g)]"

set output outdir."/flip_map.png"
which = (links == 2) ? "either" : "any"
set title "First flip of ".which." link (white: none before ".sprintf("%g", tend)." {/Symbol \326}(L/g))\n".name
eval "plot dir.'/flip.dat' nonuniform matrix using 1:2:3 with image notitle, ".notint

do for [k = 1:links] {
  set output outdir."/flip_map_link".k.".png"
  set title "First flip of link ".k." (white: none)\n".name
  eval "plot dir.'/flip".k.".dat' nonuniform matrix using 1:2:3 with image notitle, ".notint
}

# NaN here means not integrated: the background is the grey of the key entry
set object 1 rectangle from graph 0,0 to graph 1,1 behind fc rgb grey fs solid noborder
set output outdir."/energy_error.png"
set title "Maximum energy error |E(t) - E(0)| / (V_{max} - V_{min})\n".name
set autoscale cb
set cblabel "relative energy error"
set palette rgb 33,13,10
eval "plot dir.'/eerr.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 1e-16 ? $3 : 1e-16)) with image notitle, ".notint

if (strlen(lyap) > 0) {
  set output outdir."/lyapunov.png"
  set title "Largest Lyapunov exponent\n".name
  unset logscale cb
  set format cb "%g"
  set autoscale cb
  set cblabel "{/Symbol l} [1/{/Symbol \326}(L/g)]"
  set palette rgb 21,22,23
  eval "plot lyap nonuniform matrix using 1:2:($3*tau) with image notitle, ".notint
}

# the fast indicator: a scale for each (NaN, not finite: the grey background)
if (ind == 1) {
  # MEGNO <Y>: diverging around 2, the limit of regular orbits (white); blue below
  # (isochronous, stable), red above (chaotic: <Y> ~ lambda1 t/2), saturated at 4
  set output outdir."/megno.png"
  set title "MEGNO <Y> at t_{end} (2: regular; > 2: chaotic)\n".name
  unset logscale cb
  set format cb "%g"
  set cbrange [0:4]
  set cbtics ("0" 0, "1" 1, "2" 2, "3" 3, "{/Symbol \263} 4" 4)
  set cblabel "<Y>"
  set palette defined (0 "#2166ac", 1 "#92c5de", 2 "#f7f7f7", 3 "#f4a582", 4 "#b2182b")
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 4 ? 4 : ($3 < 0 ? 0 : $3))) with image notitle, ".notint
}
if (ind == 2) {
  # FLI = ln |delta|: grows like ln t (regular) or lambda1 t (chaotic); linear scale
  set output outdir."/fli.png"
  set title "Fast Lyapunov indicator ln |{/Symbol d}(t_{end})|\n".name
  unset logscale cb
  set format cb "%g"
  set autoscale cb
  set cblabel "FLI"
  set palette defined (0 "#fde725", 1 "#35b779", 2 "#31688e", 3 "#440154")
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:3 with image notitle, ".notint
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
  set palette defined (0 "#000004", 1 "#57106e", 2 "#bc3754", 3 "#f98e09", 4 "#fcffa4")
  eval "plot dir.'/ind.dat' nonuniform matrix using 1:2:(($3 != $3) ? NaN : ($3 > 1e-16 ? $3 : 1e-16)) with image notitle, ".notint
}
