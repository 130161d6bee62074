# Animated GIF of a `dpend simulate` file. Called by `dpend animate` as
#   gnuplot -c animate.gp PARAMS FRAMES TRAIL GIF TITLE LABEL1 LABEL2 PNGSTEM
# PARAMS  gnuplot assignments of numbers only, written by dpend: nframes, nrows,
#         per_frame, ntrail, delay [1/100 s], width, height [px], overlay, reactions
#         (0/1), lim [m], newtons_per_m [N/m], fmax [N]
# FRAMES  one row per frame: t xB yB xD yD F01x F01y F21x F21y [xB2 yB2 xD2 yD2]
# TRAIL   the tip per_frame times per frame interval: t xD yD [xD2 yD2]
#         (frame i, from 0, is trail row i*per_frame; the trail is ntrail rows long)
# GIF     the animation to write; TITLE, LABEL1, LABEL2: text shown as it is
# PNGSTEM if not empty: also PNGSTEM-0001.png, PNGSTEM-0002.png, ...
# The arguments are data: never pasted into code (only PARAMS is loaded).
load ARG1
framefile = ARG2
trailfile = ARG3

array T[nframes]; array BX[nframes]; array BY[nframes]; array DX[nframes]; array DY[nframes]
array F1X[nframes]; array F1Y[nframes]; array F2X[nframes]; array F2Y[nframes]
array BX2[nframes]; array BY2[nframes]; array DX2[nframes]; array DY2[nframes]
array TX[nrows]; array TY[nrows]; array TX2[nrows]; array TY2[nrows]
if (overlay) {
  stats framefile using (r = int($0) + 1, T[r] = $1, BX[r] = $2, BY[r] = $3, DX[r] = $4, \
    DY[r] = $5, F1X[r] = $6, F1Y[r] = $7, F2X[r] = $8, F2Y[r] = $9, BX2[r] = $10, \
    BY2[r] = $11, DX2[r] = $12, DY2[r] = $13, 0) nooutput
  stats trailfile using (r = int($0) + 1, TX[r] = $2, TY[r] = $3, TX2[r] = $4, \
    TY2[r] = $5, 0) nooutput
} else {
  stats framefile using (r = int($0) + 1, T[r] = $1, BX[r] = $2, BY[r] = $3, DX[r] = $4, \
    DY[r] = $5, F1X[r] = $6, F1Y[r] = $7, F2X[r] = $8, F2Y[r] = $9, 0) nooutput
  stats trailfile using (r = int($0) + 1, TX[r] = $2, TY[r] = $3, 0) nooutput
}

# colours: rods and their tip trail; the overlay in warm colours
rod = "#1f3b73"; rod2 = "#b03a2e"; pin = "#111111"
trail_rgb = 0x2e86de; trail2_rgb = 0xe67e22
react1 = "#1e8449"; react2 = "#8e44ad"
# older trail points lighter: mix with white by age in [0, 1]
mix(c, s, age) = int(((c >> s) & 255) + (255 - ((c >> s) & 255))*age**0.7)
fade(c, age) = (mix(c, 16, age) << 16) + (mix(c, 8, age) << 8) + mix(c, 0, age)
s = (height < width ? height : width)/640.0      # line widths follow the image size
s = (s < 0.5 ? 0.5 : s)

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

do for [pass = 1:(strlen(ARG8) > 0 ? 2 : 1)] {
  fsize = sprintf(",%d", int(11*s + 0.5))
  if (pass == 1) {
    set terminal gif animate delay delay loop 0 size width,height font "DejaVuSans".fsize
    set output ARG4
  } else {
    set terminal png size width,height font "DejaVuSans".fsize
  }
  do for [i = 0:nframes - 1] {
    k = i + 1
    if (pass == 2) { set output sprintf("%s-%04d.png", ARG8, k) }
    unset arrow; unset object; unset label
    set label 1 sprintf("t = %.2f s", T[k]) at graph 0.03, graph 0.95 left front
    if (overlay) {
      set arrow 5 from 0,0 to BX2[k],BY2[k] nohead lw 7*s lc rgb rod2 front
      set arrow 6 from BX2[k],BY2[k] to DX2[k],DY2[k] nohead lw 7*s lc rgb rod2 front
      set object 5 circle at BX2[k],BY2[k] size r_pin fc rgb pin front
      set object 6 circle at DX2[k],DY2[k] size r_pin fc rgb rod2 front
    }
    set arrow 1 from 0,0 to BX[k],BY[k] nohead lw 7*s lc rgb rod front
    set arrow 2 from BX[k],BY[k] to DX[k],DY[k] nohead lw 7*s lc rgb rod front
    set object 1 circle at 0,0 size 1.3*r_pin fc rgb pin front
    set object 2 circle at BX[k],BY[k] size r_pin fc rgb pin front
    set object 3 circle at DX[k],DY[k] size r_pin fc rgb rod front
    if (reactions) {
      set arrow 10 from 0,0 rto F1X[k]/newtons_per_m,F1Y[k]/newtons_per_m \
        head filled size screen 0.018,20 lw 3*s lc rgb react1 front
      set arrow 11 from BX[k],BY[k] rto F2X[k]/newtons_per_m,F2Y[k]/newtons_per_m \
        head filled size screen 0.018,20 lw 3*s lc rgb react2 front
      fsmall = sprintf(",%d", int(9*s + 0.5))
      set label 2 "F01: ground on link 1, at A" at screen 0.03, screen 0.065 left front \
        font fsmall tc rgb react1
      set label 3 "F21: link 2 on link 1, at B" at screen 0.03, screen 0.03 left front \
        font fsmall tc rgb react2
      set label 4 sprintf("arrows: 1 m = %g N\n(largest |F| shown %.3g N)", newtons_per_m, \
        fmax) at screen 0.97, screen 0.065 right front font fsmall tc rgb "#333333"
    }
    last = i*per_frame + 1
    first = (last - ntrail > 1 ? last - ntrail : 1)
    if (overlay) {
      plot sample [j = first:last:1] '+' using (TX2[j]):(TY2[j]):\
             (fade(trail2_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
             notitle, \
           [j = first:last:1] '+' using (TX[j]):(TY[j]):\
             (fade(trail_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable \
             notitle, \
           NaN with lines lw 7*s lc rgb rod title ARG6, \
           NaN with lines lw 7*s lc rgb rod2 title ARG7
    } else {
      plot sample [j = first:last:1] '+' using (TX[j]):(TY[j]):\
             (fade(trail_rgb, (last - j)/real(ntrail))) with lines lw 3*s lc rgb variable
    }
  }
  set output
}
