# Figures of one `dpend simulate` run, drawn from the file's own description
# (docs/hdf5-layout.md: the root attributes coordinates and draw_*, the units of q).
# Called by scripts/plot_simulate.sh as
#   gnuplot -c simulate.gp DATAFILE OUTDIR TITLE ESCALE N NAMES UNITS K "STYLE CONSERVED"
# DATAFILE: columns t q_1..q_N E qdot_1..qdot_N, then the K forces of the figure (x, y
# each: for rods F_joint, the force of body i-1 on body i at joint i) and the last
# point of the figure (x, y: the tip of the last link, or the mass); OUTDIR: where the
# PNGs go; TITLE: run description (method and file name, enhanced text, escaped;
# every figure shows it); ESCALE: energy scale [J], at full precision; N: number of
# coordinates; NAMES, UNITS: their names and units, blank-separated ("q1 q2",
# "rad rad"; "r phi", "m rad"); K: number of force rows; STYLE: the figure's style
# (rods, spring) and CONSERVED, in one argument: 1 when the energy is a constant of motion, else 0 (a
# damped or driven run: the figure is the energy's change). Coordinates in rad are wrapped; others are drawn as they are. Axes
# of angles are ticked in multiples of pi, text scales with the canvas (style.gp). The
# arguments are data: never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"
load style_gp
datafile = ARG1
outdir = ARG2
title = ARG3
Escale = real(ARG4)
N = int(real(ARG5))
names = ARG6
units = ARG7
K = int(real(ARG8))
style = word(ARG9, 1)
conserved = (word(ARG9, 2) eq "1")
rods = (style eq "rods")
cE = N + 2                     # column of the energy
cqd = N + 3                    # column of q1dot
cF = 2*N + 3                   # column of the first force (x)
cT = 2*N + 3 + 2*K             # column of the last point (x)
nm(i) = word(names, i)
un(i) = word(units, i)
isrod(i) = (un(i) eq "rad")
allrad = 1
do for [i=1:N] { if (!isrod(i)) { allrad = 0 } }
array linkcol[8] = ["#9400d3", "#009e73", "#56b4e9", "#e69f00", "#0072b2", "#e51e10", \
                    "#f0e442", "#000000"]
lc(i) = linkcol[(i - 1)%8 + 1]
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set grid
set key outside right
isfinite(x) = (x == x && abs(x) < 1e308)
finite_col(c) = isfinite(column(c))
# Escale (J) comes from the file's energy_scale attribute: |E0|, or when E0 ~ 0
# the potential energy with both links upright (docs/hdf5-layout.md)
stats datafile using cE every ::0::0 nooutput
E0 = STATS_min
# every figure has data: each column it draws holds at least two finite values (a
# figure without data is an error, not an empty picture)
do for [c = 1:cT + 1] {
  stats datafile using (finite_col(c) ? column(c) : NaN) nooutput
  if (STATS_records < 2) {
    print sprintf("simulate.gp: column %d of the data has fewer than 2 finite values", c)
    exit status 1
  }
}

# angle wrapped to (-pi, pi]
wrap(a) = a - 2*pi*ceil((a - pi)/(2*pi))
# wrapped value of column c, or NaN where it jumped by more than pi since the previous
# row (a gap in the line instead of a vertical stroke across the plot); one variable
# per column, reset by the first row
array prevw[N]
gap(c, i) = (w = wrap(column(c)), j = ($0 > 0 && abs(w - prevw[i]) > pi), prevw[i] = w, \
             j ? NaN : w)
wraptics = "(".pitics(-pi, pi).")"
# the extent [alo, ahi] of the unwrapped angle columns (all, or column c alone)
alo = 0; ahi = 0
arange(c) = (alo = (column(c) < alo ? column(c) : alo), ahi = (column(c) > ahi ? column(c) : ahi), 0)

# one plot when every coordinate is an angle, else one panel per coordinate
if (allrad) {
  set output outdir."/angles.png"
  set title "Angles from the horizontal x axis, unwrapped (".title.")"
  set xlabel "t [s]"; set ylabel "angle [rad]"
  alo = 1e308; ahi = -1e308
  do for [i=1:N] { stats datafile u (arange(i + 1)) nooutput }
  if (ahi > alo) { eval "set ytics (".pitics(alo, ahi).")" }
  plot for [i=1:N] datafile u 1:(column(i + 1)) w l lw 1.5 t nm(i)

  set output outdir."/angles_wrapped.png"
  set title "Angles from the horizontal x axis, wrapped to (-{/Symbol p}, {/Symbol p}] (".title.")"
  set yrange [-pi*1.05:pi*1.05]
  eval "set ytics ".wraptics
  plot for [i=1:N] datafile u 1:(gap(i + 1, i)) w l lw 1.5 t nm(i)
  set autoscale y; set ytics auto
} else {
  set terminal pngcairo size 1000,130 + 250*N enhanced font fontspec(1000)
  do for [w=0:1] {
    set output outdir.(w ? "/angles_wrapped.png" : "/angles.png")
    set multiplot layout N,1 title "Coordinates".(w ? ", angles wrapped to (-{/Symbol p}, {/Symbol p}]" : "")." (".title.")"
    set key off
    do for [i=1:N] {
      set title nm(i); set ylabel nm(i)." [".un(i)."]"
      if (i < N) { set xlabel "" } else { set xlabel "t [s]" }
      set ytics auto
      if (isrod(i) && !w) {
        alo = 1e308; ahi = -1e308
        stats datafile u (arange(i + 1)) nooutput
        if (ahi > alo) { eval "set ytics (".pitics(alo, ahi).")" }
      }
      if (isrod(i) && w) { eval "set ytics ".wraptics }
      if (w && isrod(i)) {
        plot datafile u 1:(gap(i + 1, i)) w l lw 1.5 lc rgb lc(i)
      } else {
        plot datafile u 1:(column(i + 1)) w l lw 1.5 lc rgb lc(i)
      }
    }
    unset multiplot
  }
  set ytics auto
  set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
  set key outside right
}

# panels: one row up to 3 links, then a near-square grid
pcols = (N <= 3 ? N : ceil(sqrt(N)))
prows = ceil(real(N)/pcols)
if (prows > 1) { set terminal pngcairo size 1000,350*prows enhanced font fontspec(1000) }
set output outdir."/phase.png"
set multiplot layout prows,pcols title "Phase portraits".(allrad ? ", angles wrapped to (-{/Symbol p}, {/Symbol p}]" : "")." (".title.")"
set key off
do for [i=1:N] {
  set xlabel nm(i)." [".un(i)."]"; set ylabel "d".nm(i)."/dt [".un(i)."/s]"
  set title (rods ? sprintf("link %d", i) : nm(i))
  if (isrod(i)) {
    set xrange [-pi*1.05:pi*1.05]
    eval "set xtics ".wraptics
    plot datafile u (gap(i + 1, i)):(column(cqd + i - 1)) w l lw 0.8 lc rgb lc(i)
  } else {
    set autoscale x; set xtics auto
    plot datafile u (column(i + 1)):(column(cqd + i - 1)) w l lw 0.8 lc rgb lc(i)
  }
}
unset multiplot
set terminal pngcairo size 1000,600 enhanced font fontspec(1000)
set autoscale x; set xtics auto; set key outside right

set output outdir."/energy_error.png"
# E(0) = 0 when the scale is not |E(0)| (relative tolerance: the scale is |E(0)| to
# the last bits when it is one)
scale_is_E0 = abs(abs(E0) - Escale) <= 1e-9*Escale
what = conserved ? "Energy error" : "Energy change (damped or driven: see balance.png)"
set title sprintf("%s |E(t) - E(0)| / E_s, E(0) = %.6g J,\nE_s = %.6g J%s (%s)", what, E0, Escale, scale_is_E0 ? " = |E(0)|" : (rods ? (N == 2 ? \
  " (E(0) ≈ 0: V with both links upright)" : " (E(0) ≈ 0: V with all links upright)") : \
  " (E(0) ≈ 0: the model's energy scale)"), title)
set xlabel "t [s]"; set ylabel (conserved ? "relative energy error |E(t) - E(0)| / E_s" : "relative energy change |E(t) - E(0)| / E_s")
set logscale y
set format y "10^{%L}"
plot datafile u 1:(abs(column(cE) - E0)/Escale + 1e-18) w l lw 1.2 t (conserved ? "energy error" : "energy change")
unset logscale y; set format y "%g"

set ylabel "force [N]"
# ftitle(i): what force row i is (rods: the joint reactions, F01 at the pin A)
ftitle(i) = rods ? (i == 1 ? "joint 1 (pin A): F01, ground on link 1" : \
  (N == 2 ? "joint 2 (B): F12 = -F21, link 1 on link 2" : \
   sprintf("joint %d: link %d on link %d", i, i - 1, i))) : \
  (K == 1 ? "force of the support on the body at A" : sprintf("force %d", i))
if (K <= 4) {
  # one panel per force: its x and y
  set terminal pngcairo size 1000,130 + 250*K enhanced font fontspec(1000)
  set output outdir."/reactions.png"
  set multiplot layout K,1 title (rods ? "Joint reactions F_{i-1,i}: force of body i-1 on body i at joint i, body 0 the ground" : "Forces")." (".title.")"
  do for [i=1:K] {
    set title ftitle(i)
    if (i < K) { set xlabel "" } else { set xlabel "t [s]" }
    plot datafile u 1:(column(cF + 2*i - 2)) w l lc 1 t "x", \
         datafile u 1:(column(cF + 2*i - 1)) w l lc 2 t "y"
  }
  unset multiplot
  set xlabel "t [s]"
} else {
  set output outdir."/reactions.png"
  set title "Joint reactions |F_{i-1,i}|: force of body i-1 on body i at joint i, body 0 the ground\n(".title.")"
  plot for [i=1:K] datafile u 1:(sqrt(column(cF + 2*i - 2)**2 + column(cF + 2*i - 1)**2)) \
    w l lc rgb lc(i) t sprintf("|F_{%d,%d}|", i - 1, i)
}

set output outdir."/tip_path.png"
set terminal pngcairo size 800,800 enhanced font fontspec(800)
set title sprintf("Path of %s (y up, pin A at the origin)\n(%s)", \
  rods ? sprintf("the tip of link %d", N) : "the mass", title)
set xlabel "x [m]"; set ylabel "y [m]"
set size ratio -1
set key off
$origin << EOD
0 0
EOD
plot datafile u (column(cT)):(column(cT + 1)) w l lw 0.8 lc rgb "#1f77b4", \
     $origin w p pt 7 ps 1.5 lc rgb "black"
