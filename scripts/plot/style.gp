# The look shared by the figure scripts, loaded first by each of them as
#   load style_gp   (style_gp: this file, found beside the script from ARG0)
# Defines, all from numbers only (nothing here reads an argument):
#   fontspec(w)        "DejaVu Sans,S" with S proportional to the canvas width w [px]
#                      (12 pt at 1000 px, at least 8): text scales with the image
#   font_pt(w)         that size S in points
#   viridis            a string: `eval "set palette ".viridis` sets the perceptual
#                      palette of every map (viridis control points)
#   pitics(lo, hi)     a tic list in multiples of pi/2^j or 2^j pi (3 to 6 intervals)
#                      covering [lo, hi] [rad] (hi > lo), for
#                      eval "set xtics (".pitics(lo, hi).")"
#   pistr(x)           x [rad] as text: a multiple of pi/4 as "−π/2", "3π/4", else %.4g
#   has(y), pos(y)     1 for a finite y (pos: finite and > 0), else 0; NaN otherwise
#   keyline(fig, title, n)  the line a figure's sidecar holds for one key entry:
#                      "FIG<TAB>TITLE<TAB>N" (N: points of that series with data);
#                      the scripts print it to KEYS (OUTDIR/keys.txt) for each key
#                      entry they draw, which test/test_figures.f90 reads
font_pt(w) = (12.0*w/1000.0 > 8 ? 12.0*w/1000.0 : 8)
fontspec(w) = sprintf("DejaVu Sans,%.3g", font_pt(w))
viridis = 'defined (0 "#440154", 1 "#482475", 2 "#414487", 3 "#355f8d", 4 "#2a788e", ' . \
          '5 "#21918c", 6 "#22a884", 7 "#44bf70", 8 "#7ad151", 9 "#bddf26", 10 "#fde725")'
# m*pi/d (d a power of 2) as a reduced label: 0, π/8, π/4, 3π/4, π, −3π/2, 2π, ...
pi_sign(m) = (m < 0 ? "−" : "")
pi_num(n) = (abs(n) == 1 ? "" : sprintf("%d", abs(n)))
pi_lab(m, d) = (m == 0 ? "0" : (m % 2 == 0 && d > 1 ? pi_lab(m/2, d/2) : \
  pi_sign(m).pi_num(m)."π".(d > 1 ? sprintf("/%d", d) : "")))
# the tic spacing pi*st/d (st, d powers of 2) giving 3 to 6 intervals over [lo, hi]
pi_units(lo, hi) = (hi - lo)/(pi/4)
pi_den(lo, hi) = (pi_units(lo, hi) >= 3 ? 4 : 4*2**int(ceil(log(3/pi_units(lo, hi))/log(2))))
pi_step(lo, hi) = (pi_units(lo, hi) <= 6 ? 1 : \
  2**int(ceil(log(pi_units(lo, hi)/6)/log(2) - 1e-9)))
pi_list(m, mmax, st, d) = sprintf('"%s" %.17g', pi_lab(m, d), m*pi/d) . \
  (m + st <= mmax ? ", " . pi_list(m + st, mmax, st, d) : "")
pi_first(lo, st, d) = st*int(ceil(lo/(st*pi/d) - 1e-9))
pitics(lo, hi) = pi_list(pi_first(lo, pi_step(lo, hi), pi_den(lo, hi)), \
  int(floor(hi/(pi/pi_den(lo, hi)) + 1e-9)), pi_step(lo, hi), pi_den(lo, hi))
pi_round(x) = int(floor(x/(pi/4) + 0.5))
pistr(x) = (abs(x/(pi/4) - pi_round(x)) < 1e-9 ? pi_lab(pi_round(x), 4) : sprintf("%.4g", x))
has(y) = (y == y && abs(y) < 1e308 ? 1 : 0)
pos(y) = (y == y && y > 0 && y < 1e308 ? y : NaN)
keyline(fig, title, n) = sprintf("%s\t%s\t%d", fig, title, n)
