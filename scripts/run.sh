#!/usr/bin/env bash
# The main job, a showcase of every driver in small versions: builds the release
# profile and writes every .h5 and figure under out/ (a few minutes on 2 cores).
#   scripts/run.sh
set -euo pipefail
cd "$(dirname "$0")/.."
d=scripts/dpend   # always quoted: "$d"
start=$SECONDS
step() { echo; echo "== $1"; }

step "simulate: the chapter's numerical application (both links horizontal, at rest)"
mkdir -p out/simulate
"$d" simulate --config data/simulate.nml --output out/simulate/simulate.h5 --force
scripts/plot_simulate.sh out/simulate/simulate.h5 out/simulate
"$d" animate out/simulate/simulate.h5 --output out/simulate/simulate.gif --force \
  --duration 6 --reactions   # the first 6 s at 25 fps: 150 frames

step "simulate: the triple pendulum (three links horizontal, at rest; --links 3)"
mkdir -p out/triple
"$d" simulate --links 3 --q 0,0,0 --t-end 20 --output out/triple/triple.h5 --force
scripts/plot_simulate.sh out/triple/triple.h5 out/triple
"$d" animate out/triple/triple.h5 --output out/triple/triple.gif --force \
  --duration 6 --reactions   # the first 6 s at 25 fps: 150 frames

step "study --quick: energy conservation of every integrator (the full study: dpend study)"
"$d" study --quick --output out/study/study.h5 --force > /dev/null
echo "summary: out/study/study.md; figures: out/study/*.png"

step "lyapunov: spectrum of the horizontal release (t = 300 s)"
mkdir -p out/chaos
"$d" lyapunov --t-end 300 --output out/chaos/lyapunov.h5 --force | tail -n 1
scripts/plot_chaos.sh out/chaos/lyapunov.h5 out/chaos

step "lyapunov: the six exponents of the triple pendulum released horizontally (t = 200 s)"
mkdir -p out/chaos/triple
"$d" lyapunov --links 3 --q 0,0,0 --t-end 200 --output out/chaos/lyapunov_triple.h5 --force \
  | tail -n 1
scripts/plot_chaos.sh out/chaos/lyapunov_triple.h5 out/chaos/triple

step "divergence: 20 pairs of trajectories 1e-9 apart"
"$d" divergence --output out/chaos/divergence.h5 --force | tail -n 1
scripts/plot_chaos.sh out/chaos/divergence.h5 out/chaos

step "poincare: sections at E = -15 J (regular) and E = 0 J (chaotic)"
"$d" poincare --energy -15 --ics 20 --points 300 --output out/chaos/poincare_low.h5 --force \
  | tail -n 1
scripts/plot_chaos.sh out/chaos/poincare_low.h5 out/chaos/poincare_low
"$d" poincare --energy 0 --ics 20 --points 300 --output out/chaos/poincare_release.h5 --force \
  | tail -n 1
scripts/plot_chaos.sh out/chaos/poincare_release.h5 out/chaos/poincare_release

step "sweep: the flip-time map, 256 x 256 (the classic map at a quarter resolution)"
mkdir -p out/sweep
"$d" sweep --config data/sweep_classic.nml --n 256 --output out/sweep/flip_map_256.h5 --force
scripts/plot_sweep.sh out/sweep/flip_map_256.h5 out/sweep

echo
echo "== done in $((SECONDS - start)) s: figures and files under out/"
find out -name '*.png' | sort
