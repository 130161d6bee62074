# Figures of one `dpend simulate` run. Called by scripts/plot_simulate.sh as
#   gnuplot -c simulate.gp DATAFILE OUTDIR TITLE ESCALE LINKS
# DATAFILE: columns t q1..qN E q1dot..qNdot, then for N = 2 F01x F01y F21x F21y rC2x rC2y
# rBx rBy, for other N the joint reactions F_joint (x, y of joints 1..N: the force of
# body i-1 on body i at joint i) and the tip xT yT (the free end of link N); OUTDIR:
# where the PNGs go; TITLE: run description (method and file name, enhanced text,
# escaped; every figure shows it); ESCALE: energy scale [J], at full precision;
# LINKS: the number of links N. The arguments are data: never pasted into code.
datafile = ARG1
outdir = ARG2
title = ARG3
Escale = real(ARG4)
N = int(real(ARG5))
cE = N + 2                     # column of the energy
cqd = N + 3                    # column of q1dot
cF = 2*N + 3                   # column of the first reaction (F01x)
array linkcol[8] = ["#9400d3", "#009e73", "#56b4e9", "#e69f00", "#0072b2", "#e51e10", \
                    "#f0e442", "#000000"]
lc(i) = linkcol[(i - 1)%8 + 1]
set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11"
set grid
set key outside right
# Escale (J) comes from the file's energy_scale attribute: |E0|, or when E0 ~ 0
# the potential energy with both links upright (docs/hdf5-layout.md)
stats datafile using cE every ::0::0 nooutput
E0 = STATS_min

# angle wrapped to (-pi, pi]
wrap(a) = a - 2*pi*ceil((a - pi)/(2*pi))
# wrapped value of column c, or NaN where it jumped by more than pi since the previous
# row (a gap in the line instead of a vertical stroke across the plot); one variable
# per column, reset by the first row
array prevw[N]
gap(c, i) = (w = wrap(column(c)), j = ($0 > 0 && abs(w - prevw[i]) > pi), prevw[i] = w, \
             j ? NaN : w)
pitics = "(\"-{/Symbol p}\" -pi, \"-{/Symbol p}/2\" -pi/2, \"0\" 0, \"{/Symbol p}/2\" pi/2, \"{/Symbol p}\" pi)"

set output outdir."/angles.png"
set title "Angles from the horizontal x axis, unwrapped (".title.")"
set xlabel "t [s]"; set ylabel "angle [rad]"
plot for [i=1:N] datafile u 1:(column(i + 1)) w l lw 1.5 t sprintf("q_%d", i)

set output outdir."/angles_wrapped.png"
set title "Angles from the horizontal x axis, wrapped to (-{/Symbol p}, {/Symbol p}] (".title.")"
set yrange [-pi*1.05:pi*1.05]
eval "set ytics ".pitics
plot for [i=1:N] datafile u 1:(gap(i + 1, i)) w l lw 1.5 t sprintf("q_%d", i)
set autoscale y; set ytics auto

# panels: one row up to 3 links, then a near-square grid
pcols = (N <= 3 ? N : ceil(sqrt(N)))
prows = ceil(real(N)/pcols)
if (prows > 1) { set terminal pngcairo size 1000,350*prows enhanced font "DejaVu Sans,11" }
set output outdir."/phase.png"
set multiplot layout prows,pcols title "Phase portraits, angles wrapped to (-{/Symbol p}, {/Symbol p}] (".title.")"
set key off
set xrange [-pi*1.05:pi*1.05]
eval "set xtics ".pitics
do for [i=1:N] {
  set xlabel sprintf("q_%d [rad]", i); set ylabel sprintf("dq_%d/dt [rad/s]", i)
  set title sprintf("link %d", i)
  plot datafile u (gap(i + 1, i)):(column(cqd + i - 1)) w l lw 0.8 lc rgb lc(i)
}
unset multiplot
set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11"
set autoscale x; set xtics auto; set key outside right

set output outdir."/energy_error.png"
# E(0) = 0 when the scale is not |E(0)| (relative tolerance: the scale is |E(0)| to
# the last bits when it is one)
scale_is_E0 = abs(abs(E0) - Escale) <= 1e-9*Escale
set title sprintf("Energy error |E(t) - E(0)| / E_s, E(0) = %.6g J, E_s = %.6g J%s\n(%s)", E0, Escale, scale_is_E0 ? " = |E(0)|" : (N == 2 ? " (E(0) ≈ 0: V with both links upright)" : \
  " (E(0) ≈ 0: V with all links upright)"), title)
set xlabel "t [s]"; set ylabel "relative energy error"
set logscale y
set format y "10^{%L}"
plot datafile u 1:(abs(column(cE) - E0)/Escale + 1e-18) w l lw 1.2 t "energy error"
unset logscale y; set format y "%g"

set ylabel "force [N]"
if (N == 2) {
  set output outdir."/reactions.png"
  set title "Joint reactions: F01 ground on link 1 at A, F21 link 2 on link 1 at B (".title.")"
  plot datafile u 1:7 w l t "F01x", datafile u 1:8 w l t "F01y", \
       datafile u 1:9 w l t "F21x", datafile u 1:10 w l t "F21y"
} else {
  if (N <= 4) {
    # one panel per joint: x and y of F_{i-1,i}, the force of body i-1 on body i
    set terminal pngcairo size 1000,130 + 250*N enhanced font "DejaVu Sans,11"
    set output outdir."/reactions.png"
    set multiplot layout N,1 title "Joint reactions F_{i-1,i}: force of body i-1 on body i at joint i, body 0 the ground (".title.")"
    do for [i=1:N] {
      set title (i == 1 ? "joint 1 (pin A): ground on link 1" : \
                 sprintf("joint %d: link %d on link %d", i, i - 1, i))
      if (i < N) { set xlabel "" } else { set xlabel "t [s]" }
      plot datafile u 1:(column(cF + 2*i - 2)) w l lc 1 t sprintf("F_{%d%d,x}", i - 1, i), \
           datafile u 1:(column(cF + 2*i - 1)) w l lc 2 t sprintf("F_{%d%d,y}", i - 1, i)
    }
    unset multiplot
    set xlabel "t [s]"
  } else {
    set output outdir."/reactions.png"
    set title "Joint reactions |F_{i-1,i}|: force of body i-1 on body i at joint i, body 0 the ground\n(".title.")"
    plot for [i=1:N] datafile u 1:(sqrt(column(cF + 2*i - 2)**2 + column(cF + 2*i - 1)**2)) \
      w l lc rgb lc(i) t sprintf("|F_{%d,%d}|", i - 1, i)
  }
}

set output outdir."/tip_path.png"
set terminal pngcairo size 800,800 enhanced font "DejaVu Sans,11"
set title sprintf("Path of the tip of link %d (y up, pin A at the origin)\n(%s)", N, title)
set xlabel "x [m]"; set ylabel "y [m]"
set size ratio -1
set key off
$origin << EOD
0 0
EOD
# N = 2: the tip is 2 rC2 - rB; otherwise the last two columns
tx(dummy) = (N == 2 ? 2*$11 - $13 : column(4*N + 3))
ty(dummy) = (N == 2 ? 2*$12 - $14 : column(4*N + 4))
plot datafile u (tx(0)):(ty(0)) w l lw 0.8 lc rgb "#1f77b4", \
     $origin w p pt 7 ps 1.5 lc rgb "black"
