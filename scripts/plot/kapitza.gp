# Kapitza's pendulum figure. Called by scripts/kapitza.sh as
#   gnuplot -c kapitza.gp ABOVE BELOW SWEEP OUTFILE A_C FALL OMEGA G L
# ABOVE, BELOW: columns t q (q the angle from the horizontal x axis) of the runs with the
# amplitude above and below the threshold; SWEEP: columns a [m], largest angle from
# upright [rad], 1 (stays up) or 0 (falls), angular frequency of the slow oscillation
# [rad/s] (NaN if it falls); OUTFILE: the PNG; A_C: the derived threshold [m]; FALL: the
# angle from upright counted as fallen [rad]; OMEGA: the pin's angular frequency
# [rad/s]; G, L: gravity [m/s^2] and the rod's length [m]. The arguments are data:
# never pasted into code.
sdir(s, i) = (i < 1 ? "" : (s[i:i] eq "/" ? s[1:i] : sdir(s, i - 1)))
style_gp = sdir(ARG0, strlen(ARG0))."style.gp"  # text scales with the canvas
load style_gp
above = ARG1
below = ARG2
sweep = ARG3
outfile = ARG4
a_c = real(ARG5)
fall = real(ARG6)
omega = real(ARG7)
g = real(ARG8)
L = real(ARG9)
k = 3/(2*L)                    # m (L/2) / I_A of the uniform rod
# Kapitza's slow frequency about upright: Omega^2 = k g ((a/a_c)^2 - 1)
slow(a) = (a > a_c ? sqrt(k*g*((a/a_c)**2 - 1)) : NaN)
set terminal pngcairo size 1000,1050 enhanced font fontspec(1000)
set output outfile
set grid
set multiplot layout 3,1 title sprintf("Kapitza's pendulum: one uniform rod (L = %g m) on a pin y_A = a cos({/Symbol w} t), {/Symbol w} = %.2f rad/s", L, omega)

# the angle from the upward vertical, counter-clockwise: phi = q - pi/2
set title "Angle from the upward vertical, started 0.05 rad off upright at rest"
set xlabel "t [s]"; set ylabel "{/Symbol f} [rad]"
set key top right
# tics in multiples of pi over the angles reached (style.gp)
alo = 0; ahi = 0
stats above u (alo = ($2 - pi/2 < alo ? $2 - pi/2 : alo), ahi = ($2 - pi/2 > ahi ? $2 - pi/2 : ahi), 0) nooutput
stats below u (alo = ($2 - pi/2 < alo ? $2 - pi/2 : alo), ahi = ($2 - pi/2 > ahi ? $2 - pi/2 : ahi), 0) nooutput
if (ahi > alo) { eval "set ytics (".pitics(alo, ahi).")" }
plot above u 1:($2 - pi/2) w l lw 1.5 lc rgb "#009e73" \
       t sprintf("a = 0.012 m = %.1f a_c: stays up", 0.012/a_c), \
     below u 1:($2 - pi/2) w l lw 1.5 lc rgb "#e51e10" \
       t sprintf("a = 0.008 m = %.1f a_c: falls", 0.008/a_c)

set title "The one that stays up, magnified: the slow oscillation and the fast ripple k a sin{/Symbol f} cos({/Symbol w} t)"
alo = 1e308; ahi = -1e308
stats above u (alo = ($2 - pi/2 < alo ? $2 - pi/2 : alo), ahi = ($2 - pi/2 > ahi ? $2 - pi/2 : ahi), 0) nooutput
set ytics auto
if (ahi > alo) { eval "set ytics (".pitics(alo, ahi).")" }
set key top right
plot above u 1:($2 - pi/2) w l lw 1 lc rgb "#009e73" \
       t sprintf("a = 0.012 m = %.1f a_c", 0.012/a_c)

set title "Sweep over the amplitude, 30 s each: the slow oscillation about upright, or a fall (|{/Symbol f}| > ".sprintf("%.1f", fall)." rad)"
set xlabel "support amplitude a [m]"; set ylabel "slow angular frequency [rad/s]"
set ytics auto
set key bottom right
set xrange [0.005:0.02]
set yrange [-0.3:*]
set samples 500
set arrow 1 from a_c, graph 0 to a_c, graph 1 nohead dt 2 lw 1.5 lc rgb "#0072b2"
set label 1 sprintf("derived a_c = %.3g m", a_c) at a_c, graph 0.6 offset 1,0 \
    tc rgb "#0072b2"
plot slow(x) w l lw 1.5 lc rgb "#0072b2" \
       t "Kapitza: {/Symbol W}^2 = k g ((a/a_c)^2 - 1), k = 3/(2L)", \
     sweep u 1:($3 == 1 ? $4 : NaN) w p pt 7 ps 1.2 lc rgb "#009e73" \
       t "simulated: stays up (zero crossings of {/Symbol f})", \
     sweep u 1:($3 == 0 ? 0 : NaN) w p pt 5 ps 1.2 lc rgb "#e51e10" t "simulated: falls"
unset multiplot
