#!/usr/bin/env bash
# Special reliability test: every kind of simulate file draws and animates.
# Environment (set by the reliability runner): DPEND (the dpend binary), ROOT (the
# repository root), SCRATCH (an empty temporary directory, the cwd). Exit 0: pass,
# 77: skipped (printed note), other: fail. One line per check.
#
# Kinds: the double pendulum; the damped, the driven, the damped-and-driven two-link
# pendulum; 1, 3 and 5 links; the elastic pendulum. For each, `dpend animate` with
# --frames must write exactly the frames it announces (10: 1 s at 10 fps) and a GIF,
# and scripts/plot_simulate.sh every figure (balance.png too for a damped or driven
# run), each a PNG of real size. The figures have data: simulate.gp refuses to draw
# a figure whose columns hold fewer than two finite values (exit 1), so a figure that
# is written has data. The file's own description (draw_points, coordinates) is what
# both read: the test also checks that every file describes its figure.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
for tool in gnuplot h5dump; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "SKIP every_file_draws: $tool not installed"
    exit 77
  fi
done
cd "$SCRATCH" || exit 1
export DPEND DPEND_ROOT="$ROOT"
failures=0
pass() { printf 'ok   %s\n' "$1"; }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }

# kind NAME expected-points style args...: simulate, then draw and animate
kind() {
  local name=$1 points=$2 style=$3
  shift 3
  if ! "$DPEND" simulate --t-end 1.2 "$@" --output "$name.h5" > "$name.log" 2>&1; then
    fail "$name: simulate $* ($(tail -n 1 "$name.log"))"
    return
  fi
  local got
  got=$(h5dump -a /draw_style "$name.h5" 2>/dev/null | sed -n 's/^ *(0): *"\(.*\)"$/\1/p')
  if [[ $got == "$style" ]]; then pass "$name: draw_style $style"; else
    fail "$name: draw_style '$got', expected $style"
  fi
  # the animation: 1 s at 10 fps is 10 frames
  mkdir -p "frames_$name"
  if "$DPEND" animate "$name.h5" --output "$name.gif" --fps 10 --duration 1 --reactions \
    --frames "frames_$name" > "$name.alog" 2>&1; then
    local n
    n=$(find "frames_$name" -name 'frame_*.png' -size +2k | wc -l)
    if [[ $n -eq 10 && -s $name.gif ]] && grep -q ': 10 frames' "$name.alog"; then
      pass "$name: animate wrote 10 frames and the GIF"
    else
      fail "$name: animate wrote $n frames of real size ($(tail -n 1 "$name.alog"))"
    fi
  else
    fail "$name: animate ($(tail -n 1 "$name.alog"))"
  fi
  # the figures
  mkdir -p "fig_$name"
  if bash "$ROOT/scripts/plot_simulate.sh" "$name.h5" "fig_$name" > "$name.plog" 2>&1; then
    local f missing=""
    local figs=(angles angles_wrapped phase energy_error reactions tip_path)
    [[ $* == *--damping* || $* == *--support-amplitude* ]] && figs+=(balance)
    for f in "${figs[@]}"; do
      [[ -s fig_$name/$f.png && $(stat -c %s "fig_$name/$f.png") -gt 4000 ]] ||
        missing="$missing $f"
    done
    if [[ -z $missing ]]; then pass "$name: plot_simulate.sh drew ${#figs[@]} figures"; else
      fail "$name: figures missing or empty:$missing"
    fi
  else
    fail "$name: plot_simulate.sh ($(tail -n 1 "$name.plog"))"
  fi
  # the points the figure draws: one row per link (or the bob)
  local dims
  dims=$(h5dump -H -d /trajectory/rJ "$name.h5" 2>/dev/null || h5dump -H -d /trajectory/rC "$name.h5")
  if grep -q "( *[0-9]*, $points, 2 )" <<< "$dims"; then pass "$name: $points point(s) drawn"; else
    fail "$name: the figure's points are not ($points, 2) per sample"
  fi
}

kind double 2 rods
kind damped 2 rods --damping 0.1,0.05
kind driven 2 rods --support-amplitude 0,0.05 --support-frequency 30 --method dop853
kind damped_driven 2 rods --damping 0.1,0.05 --support-amplitude 0.05,0 \
  --support-frequency 20 --method gauss6
kind links1 1 rods --links 1 --q 0
kind links3 3 rods --links 3 --q 0,-0.5,-1
kind links5 5 rods --links 5 --q 0,0,0,0,0
kind elastic 1 spring --model elastic --m 1 --k 40 --l0 1 --g 9.8 --q 1.2,-1.0 --w 0,0

if ((failures > 0)); then
  echo "every_file_draws: $failures failure(s)"
  exit 1
fi
echo "every_file_draws: every kind of simulate file draws and animates"
