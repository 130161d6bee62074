# The look shared by the figure scripts (issue 25), loaded first by each of them as
#   load style_gp   (style_gp: this file, found beside the script from ARG0)
# Defines, all from numbers only (nothing here reads an argument):
#   fontspec(w)        "DejaVu Sans,S" with S proportional to the canvas width w [px]
#                      (10.5 pt at 1000 px, at least 7): text scales with the image
#   font_pt(w)         that size S in points
#   viridis            a string: `eval "set palette ".viridis` sets the perceptual
#                      palette of every map (viridis control points)
#   pitics(lo, hi)     a tic list in multiples of pi/2 (or of pi, 2 pi, ... when the
#                      range is wide) covering [lo, hi] [rad], for
#                      eval "set xtics (".pitics(lo, hi).")"
#   pistr(x)           x [rad] as text: a multiple of pi/4 as "−π/2", "3π/4", else %.4g
#   has(y), pos(y)     1 for a finite y (pos: finite and > 0), else 0; NaN otherwise
#   keyline(fig, title, n)  the line a figure's sidecar holds for one key entry:
#                      "FIG<TAB>TITLE<TAB>N" (N: points of that series with data);
#                      the scripts print it to KEYS (OUTDIR/keys.txt) for each key
#                      entry they draw, which test/test_figures.f90 reads
font_pt(w) = (10.5*w/1000.0 > 7 ? 10.5*w/1000.0 : 7)
fontspec(w) = sprintf("DejaVu Sans,%.3g", font_pt(w))
viridis = 'defined (0 "#440154", 1 "#482475", 2 "#414487", 3 "#355f8d", 4 "#2a788e", ' . \
          '5 "#21918c", 6 "#22a884", 7 "#44bf70", 8 "#7ad151", 9 "#bddf26", 10 "#fde725")'
# m half-turns of pi/2 as a label: 0, π/2, π, 3π/2, 2π, −π/2, ...
pi_sign(m) = (m < 0 ? "−" : "")
pi_half(m) = (m == 0 ? "0" : (m % 2 == 0 ? \
  pi_sign(m).(abs(m) == 2 ? "" : sprintf("%d", abs(m)/2))."π" : \
  pi_sign(m).(abs(m) == 1 ? "" : sprintf("%d", abs(m)))."π/2"))
# step (in units of pi/2) giving at most 9 tics over [lo, hi]
pi_step(lo, hi) = (hi - lo <= 8*pi/2 ? 1 : (hi - lo <= 16*pi/2 ? 2 : \
  (hi - lo <= 32*pi/2 ? 4 : (hi - lo <= 64*pi/2 ? 8 : 2*int(ceil((hi - lo)/(8*pi))) ))))
pi_list(m, mmax, st) = sprintf('"%s" %.17g', pi_half(m), m*pi/2) . \
  (m + st <= mmax ? ", " . pi_list(m + st, mmax, st) : "")
pi_first(lo, st) = st*int(ceil(lo/(st*pi/2) - 1e-9))
pitics(lo, hi) = pi_list(pi_first(lo, pi_step(lo, hi)), \
  int(floor(hi/(pi/2) + 1e-9)), pi_step(lo, hi))
pistr(x) = (abs(x/(pi/4) - floor(x/(pi/4) + 0.5)) < 1e-9 ? \
  (int(floor(x/(pi/4) + 0.5)) % 2 == 0 ? pi_half(int(floor(x/(pi/4) + 0.5))/2) : \
   pi_sign(x) . (abs(int(floor(x/(pi/4) + 0.5))) == 1 ? "" : \
   sprintf("%d", abs(int(floor(x/(pi/4) + 0.5))))) . "π/4") : sprintf("%.4g", x))
has(y) = (y == y && abs(y) < 1e308 ? 1 : 0)
pos(y) = (y == y && y > 0 && y < 1e308 ? y : NaN)
keyline(fig, title, n) = sprintf("%s\t%s\t%d", fig, title, n)
