# Animated GIF of a `dpend simulate` file, the figure as the file describes it. Called
# by `dpend animate` as
#   gnuplot -c animate.gp PARAMS FRAMES TRAIL GIF TITLE LABEL1 LABEL2 PNGSTEM
# PARAMS  gnuplot assignments of numbers only, written by dpend: links, links2 (points
#         of the input's and the overlay's figure, 0 without an overlay), nforces,
#         spring, spring2 (1: the segments are springs, else rods), nframes, nrows,
#         per_frame, ntrail, delay [1/100 s], width, height [px], overlay, side (0/1:
#         the overlay in its own panel), reactions (0/1), lim [m], newtons_per_m
#         [N/m], fmax [N]; the arrays BOB, BOB2 (per link of each file: where its point
#         mass sits as a fraction of the link, -1: none, a rod); clock_unit (0: the
#         clock in s; 1, 2: in sqrt(l1/g), sqrt(l0/g) of clock_seconds s, then in s)
# FRAMES  one row per frame: t, the anchor xA yA, the points x1 y1 .. xP yP (the far
#         end of each link; the bob), the forces (x, y of each: for rods the force of
#         body i-1 on body i at joint i, acting at the start of segment i), then the
#         overlay's anchor and points
# TRAIL   the last point per_frame times per frame interval: t x y [x2 y2]
#         (frame i, from 0, is trail row i*per_frame; the trail is ntrail rows long)
# GIF     the animation to write; TITLE, LABEL1, LABEL2: text shown as it is (the
#         key names every link of each file: LABEL1 link 1, ...; side by side, the
#         panels' titles)
# PNGSTEM if not empty: also PNGSTEM-0001.png, PNGSTEM-0002.png, ...
# The arguments are data: never pasted into code (only PARAMS is loaded).
load ARG1
if (!exists("spring2")) { spring2 = 0 }
if (!exists("clock_unit")) { clock_unit = 0; clock_seconds = 1 }
# the clock: t in s, or in the natural unit first and then in s (--time-unit natural)
clock(t) = (clock_unit == 0 ? sprintf("t = %.2f s", t) : \
  sprintf("t = %.2f %s = %.2f s", t/clock_seconds, \
          (clock_unit == 1 ? "sqrt(l1/g)" : "sqrt(l0/g)"), t))
framefile = ARG2
trailfile = ARG3

# frame k (1-based): the anchor (AX, AY)[k]; point i (PX, PY)[(k-1)*links + i]; force
# i (FX, FY)[(k-1)*nf + i]; the overlay's anchor (AX2, AY2)[k] and points (PX2, PY2)
nl2 = (links2 > 0 ? links2 : 1)
nf = (nforces > 0 ? nforces : 1)
array T[nframes]; array AX[nframes]; array AY[nframes]; array AX2[nframes]
array AY2[nframes]
array PX[nframes*links]; array PY[nframes*links]; array FX[nframes*nf]
array FY[nframes*nf]; array PX2[nframes*nl2]; array PY2[nframes*nl2]
array TX[nrows]; array TY[nrows]; array TX2[nrows]; array TY2[nrows]
stats framefile using (r = int($0) + 1, T[r] = $1, AX[r] = $2, AY[r] = $3, 0) nooutput
do for [i = 1:links] {
  stats framefile using (r = int($0)*links + i, PX[r] = column(2 + 2*i), \
    PY[r] = column(3 + 2*i), 0) nooutput
}
do for [i = 1:nforces] {
  stats framefile using (r = int($0)*nf + i, FX[r] = column(2 + 2*links + 2*i), \
    FY[r] = column(3 + 2*links + 2*i), 0) nooutput
}
c2 = 4 + 2*links + 2*nforces        # column of the overlay's anchor x
if (overlay) {
  stats framefile using (r = int($0) + 1, AX2[r] = column(c2), AY2[r] = column(c2 + 1), \
    0) nooutput
  do for [i = 1:links2] {
    stats framefile using (r = int($0)*links2 + i, PX2[r] = column(c2 + 2*i), \
      PY2[r] = column(c2 + 1 + 2*i), 0) nooutput
  }
  stats trailfile using (r = int($0) + 1, TX[r] = $2, TY[r] = $3, TX2[r] = $4, \
    TY2[r] = $5, 0) nooutput
} else {
  stats trailfile using (r = int($0) + 1, TX[r] = $2, TY[r] = $3, 0) nooutput
}
# start (x, y) of segment i in frame k: the anchor or point i - 1
sx(k, i) = (i == 1 ? AX[k] : PX[(k - 1)*links + i - 1])
sy(k, i) = (i == 1 ? AY[k] : PY[(k - 1)*links + i - 1])
sx2(k, i) = (i == 1 ? AX2[k] : PX2[(k - 1)*links2 + i - 1])
sy2(k, i) = (i == 1 ? AY2[k] : PY2[(k - 1)*links2 + i - 1])
# a spring from (x0, y0) to (x1, y1): straight leads of 12 %, then ncoil zigzags of
# half-width coil_w; vertex v = 0 .. ncoil + 2 along it
ncoil = 12
coil_w = 0.035*lim
slen(x0, y0, x1, y1) = sqrt((x1 - x0)**2 + (y1 - y0)**2) + 1e-300
vfrac(v) = (v == 0 ? 0 : (v >= ncoil + 2 ? 1 : 0.12 + 0.76*(v - 0.5)/ncoil))
voff(v) = ((v == 0 || v >= ncoil + 1) ? 0 : (v % 2 ? 1 : -1)*coil_w)
vx(x0, y0, x1, y1, v) = x0 + vfrac(v)*(x1 - x0) - voff(v)*(y1 - y0)/slen(x0, y0, x1, y1)
vy(x0, y0, x1, y1, v) = y0 + vfrac(v)*(y1 - y0) + voff(v)*(x1 - x0)/slen(x0, y0, x1, y1)

# colours: one per link (link 1 navy, link 2 amber, ...) and the tip trail; the
# overlay's links in another set (red, slate, ...)
array rodc[6] = ["#1f3b73", "#d98e04", "#2a9d8f", "#6c3483", "#7f8c8d", "#c0392b"]
array rodc2[6] = ["#b03a2e", "#5d6d7e", "#e67e22", "#117864", "#a04000", "#2e4053"]
rc1(i) = rodc[(i - 1)%6 + 1]
rc2(i) = rodc2[(i - 1)%6 + 1]
rod = rc1(1); rod2 = rc2(1); pin = "#111111"
trail_rgb = 0x2e86de; trail2_rgb = 0xe67e22
react1 = "#1e8449"; react2 = "#8e44ad"
# reaction arrows at joints 1, 2, ... (two links: react1, react2)
array reactc[6] = ["#1e8449", "#8e44ad", "#d35400", "#2471a3", "#b7950b", "#c0392b"]
rc(i) = reactc[(i - 1)%6 + 1]
# older trail points lighter: mix with white by age in [0, 1]
mix(c, s, age) = int(((c >> s) & 255) + (255 - ((c >> s) & 255))*age**0.7)
fade(c, age) = (mix(c, 16, age) << 16) + (mix(c, 8, age) << 8) + mix(c, 0, age)
s = (height < width ? height : width)/640.0      # line widths follow the image size
s = (s < 0.5 ? 0.5 : s)
# text follows the image size too: 2.4 % of its smaller side (8.6 pt at 360 px, 15 pt
# at 640 px), at least 7
fpt = 0.024*(height < width ? height : width)
fpt = (fpt < 7 ? 7 : fpt)

unset key
set size ratio -1
set xrange [-lim:lim]; set yrange [-lim:lim]
set tics scale 0.5 nomirror textcolor rgb "#777777"
set border 3 lc rgb "#aaaaaa"
set grid lc rgb "#e4e4e4" lw 1
set xlabel "x [m]" textcolor rgb "#777777"; set ylabel "y [m]" textcolor rgb "#777777"
set title ARG5 noenhanced
if (overlay) {
  set key tmargin center horizontal noenhanced samplen 2 tc rgb "#333333"
}
if (reactions) { set bmargin 6 }
set style fill solid 1.0 noborder
r_pin = 0.025*lim

# pendulum w (1: the input, 2: the overlay): its segment starts, points, colours
nlw(w) = (w == 1 ? links : links2)
springw(w) = (w == 1 ? spring : spring2)
stx(w, k, i) = (w == 1 ? sx(k, i) : sx2(k, i))
sty(w, k, i) = (w == 1 ? sy(k, i) : sy2(k, i))
ptx(w, j) = (w == 1 ? PX[j] : PX2[j])
pty(w, j) = (w == 1 ? PY[j] : PY2[j])
ancx(w, k) = (w == 1 ? AX[k] : AX2[k])
ancy(w, k) = (w == 1 ? AY[k] : AY2[k])
rcw(w, i) = (w == 1 ? rc1(i) : rc2(i))
bobw(w, i) = (w == 1 ? BOB[i] : BOB2[i])
if (!exists("side")) { side = 0 }
if (side) { set key bmargin center horizontal noenhanced samplen 2 tc rgb "#333333" }

do for [pass = 1:(strlen(ARG8) > 0 ? 2 : 1)] {
  fsize = sprintf(",%.3g", fpt)
  if (pass == 1) {
    set terminal gif animate delay delay loop 0 size width,height font "DejaVuSans".fsize
    set output ARG4
  } else {
    set terminal png size width,height font "DejaVuSans".fsize
  }
  do for [i = 0:nframes - 1] {
    k = i + 1
    if (pass == 2) { set output sprintf("%s-%04d.png", ARG8, k) }
    if (side) {
      unset title
      set multiplot layout 1, 2 title ARG5 noenhanced
    }
    do for [panel = 1:(side ? 2 : 1)] {
      unset arrow; unset object; unset label
      set label 1 clock(T[k]) at graph 0.03, graph 0.95 left front
      if (side) { set title (panel == 1 ? ARG6 : ARG7) noenhanced }
      # the pendulums this panel draws: side, its own; overlay, the second below
      wfirst = (side ? panel : (overlay ? 2 : 1))
      wlast = (side ? panel : 1)
      do for [w = wfirst:wlast:(wfirst > wlast ? -1 : 1)] {
        # tags: rods w*40 - 40 + i, springs 1000*w + 40*i + v; pins: the anchor
        # 39*w - 38, points 40*w - 40 + i + 1; bobs 300 + 40*w + i; reactions 101..
        set object 39*w - 38 circle at ancx(w, k),ancy(w, k) size 1.3*r_pin fc rgb pin front
        do for [i = 1:nlw(w)] {
          j = (k - 1)*nlw(w) + i
          if (springw(w)) {
            do for [v = 0:ncoil + 1] {
              set arrow 1000*w + 40*i + v \
                from vx(stx(w, k, i), sty(w, k, i), ptx(w, j), pty(w, j), v), \
                vy(stx(w, k, i), sty(w, k, i), ptx(w, j), pty(w, j), v) to \
                vx(stx(w, k, i), sty(w, k, i), ptx(w, j), pty(w, j), v + 1), \
                vy(stx(w, k, i), sty(w, k, i), ptx(w, j), pty(w, j), v + 1) nohead \
                lw 2.5*s lc rgb rcw(w, i) front
            }
          } else {
            set arrow 40*w - 40 + i from stx(w, k, i),sty(w, k, i) to ptx(w, j),pty(w, j) \
              nohead lw 7*s lc rgb rcw(w, i) front
          }
          set object 40*w - 40 + i + 1 circle at ptx(w, j),pty(w, j) \
            size (springw(w) ? 2.5 : 1)*r_pin fc rgb (i < nlw(w) ? pin : rcw(w, i)) front
          # a point mass: a bob at its place on the link (com_i / l_i)
          if (bobw(w, i) >= 0) {
            set object 300 + 40*w + i circle \
              at stx(w, k, i) + bobw(w, i)*(ptx(w, j) - stx(w, k, i)), \
                 sty(w, k, i) + bobw(w, i)*(pty(w, j) - sty(w, k, i)) \
              size 2.4*r_pin fc rgb rcw(w, i) fs solid 1.0 border lc rgb pin front
          }
        }
      }
      if (reactions && (panel == 1)) {
        do for [i = 1:nforces] {
          j = (k - 1)*nf + i
          set arrow 100 + i from sx(k, i),sy(k, i) rto FX[j]/newtons_per_m,FY[j]/newtons_per_m \
            head filled size screen 0.018,20 lw 3*s lc rgb rc(i) front
        }
        fsmall = sprintf(",%.3g", (0.8*fpt > 7 ? 0.8*fpt : 7))
        if (spring) {
          set label 2 "F01: the ground on the spring, at A (the spring's pull on the bob)" \
            at screen 0.03, screen 0.065 left front font fsmall tc rgb react1
        } else {
          if (links == 2) {
            set label 2 "F01: ground on link 1, at A" at screen 0.03, screen 0.065 left front \
              font fsmall tc rgb react1
            set label 3 "F12 = -F21: link 1 on link 2, at B" at screen 0.03, screen 0.03 left \
              front font fsmall tc rgb react2
          } else {
            set label 2 "at joint i: the force of link i-1 on link i" at screen 0.03, \
              screen 0.065 left front font fsmall tc rgb "#333333"
            set label 3 "(link 0: the ground; joint 1: the pin A)" at screen 0.03, \
              screen 0.03 left front font fsmall tc rgb "#333333"
          }
        }
        set label 4 sprintf("arrows: 1 m = %g N\n(largest |F| shown %.3g N)", newtons_per_m, \
          fmax) at screen 0.97, screen 0.065 right front font fsmall tc rgb "#333333"
      }
      last = i*per_frame + 1
      first = (last - ntrail > 1 ? last - ntrail : 1)
      if (side) {
        # this panel's trail, its links named in the key
        if (panel == 1) {
          plot sample [j = first:last:1] '+' using (TX[j]):(TY[j]):\
                 (fade(trail_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
                 notitle, \
               for [m = 1:links] NaN with lines lw 7*s lc rgb rc1(m) title sprintf("link %d", m)
        } else {
          plot sample [j = first:last:1] '+' using (TX2[j]):(TY2[j]):\
                 (fade(trail2_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
                 notitle, \
               for [m = 1:links2] NaN with lines lw 7*s lc rgb rc2(m) title sprintf("link %d", m)
        }
      } else {
        if (overlay) {
          plot sample [j = first:last:1] '+' using (TX2[j]):(TY2[j]):\
                 (fade(trail2_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
                 notitle, \
               [j = first:last:1] '+' using (TX[j]):(TY[j]):\
                 (fade(trail_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
                 notitle, \
               for [m = 1:links] NaN with lines lw 7*s lc rgb rc1(m) \
                 title sprintf("%s: link %d", ARG6, m), \
               for [m = 1:links2] NaN with lines lw 7*s lc rgb rc2(m) \
                 title sprintf("%s: link %d", ARG7, m)
        } else {
          plot sample [j = first:last:1] '+' using (TX[j]):(TY[j]):\
                 (fade(trail_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable
        }
      }
    }
    if (side) { unset multiplot }
  }
  set output
}
