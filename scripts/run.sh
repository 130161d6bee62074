#!/usr/bin/env bash
# The main job: build in the release profile, run the showcase, write every .h5
# and figure under out/.  Usage: scripts/run.sh
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out/simulate
echo "== simulate: the chapter's numerical application (both links horizontal, at rest)"
scripts/dpend simulate --config data/simulate.nml --output out/simulate/simulate.h5 --force
scripts/plot_simulate.sh out/simulate/simulate.h5 out/simulate
echo "== study: energy conservation of every integrator (4-7 min on 2 cores)"
scripts/dpend study --output out/study/study.h5 --force
echo "== done: see out/"
