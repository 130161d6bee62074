#!/usr/bin/env bash
# Make data/robot_example.csv: a synthetic robot run of known parameters, as a
# 500 Hz encoder and the motors' torque readings would give it (docs/robot.md).
#
# The robot: two rods, m = 1, 0.7 kg, l = 0.8, 0.6 m, g = 9.8 m/s^2, viscous joint
# friction c = 0.02, 0.01 N m s, Coulomb friction c_f = 0.05, 0.03 N m smoothed at
# v_s = 0.5 rad/s; released from q = (-1.2, -1.0) rad at rest under the torques
#   tau1 = 0.8 sin(1.3 t) + 0.4 sin(3.7 t + 0.4),  tau2 = 0.3 sin(1.3 t + 1) - 0.25 sin(3.7 t + 0.2) + 0.05
# (a torque file sampled every 1 ms, linear between samples), dop853 at rtol 1e-12.
# Its angles are sampled at 500 Hz for 10 s and quantised to 2^18 counts per turn
# (an 18-bit encoder); the torques as a current sensor reads them: plus white noise
# of 0.01 N m (Park-Miller generator, seed 20261130, Box-Muller: the same on every awk).
#
# Usage: scripts/examples/robot_data.sh [DPEND] [OUT]
#   DPEND  the dpend binary (default: scripts/dpend, the release build)
#   OUT    the CSV to write (default: data/robot_example.csv)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dpend=${1:-"$root/scripts/dpend"}
out=${2:-"$root/data/robot_example.csv"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
awk 'BEGIN { print "t [s],tau1 [N m],tau2 [N m]";
             for (k = 0; k <= 10000; k++) { t = k/1000;
               printf "%.3f,%.17g,%.17g\n", t, 0.8*sin(1.3*t) + 0.4*sin(3.7*t + 0.4),
                      0.3*sin(1.3*t + 1) - 0.25*sin(3.7*t + 0.2) + 0.05 } }' > "$work/torques.csv"
"$dpend" simulate --m 1,0.7 --l 0.8,0.6 --damping 0.02,0.01 --coulomb 0.05,0.03 \
  --coulomb-speed 0.5 --torque-file "$work/torques.csv" --q1 -1.2 --q2 -1.0 \
  --method dop853 --rtol 1e-12 --atol 1e-14 --t-end 10 --output-dt 0.002 \
  --output "$work/run.h5" --quiet > /dev/null
"$dpend" export "$work/run.h5" --csv /trajectory/t /trajectory/q /trajectory/tau \
  > "$work/run.csv"
{
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}/# /; s/ *$//'
  echo '# Columns: t [s], q1, q2 [rad] from the horizontal x axis (quantised), tau1, tau2 [N m].'
  awk -F, 'function uniform() { x = (16807*x) % 2147483647; return x/2147483647 }
           function gauss(  u, v) { u = uniform(); v = uniform();
             return sqrt(-2*log(u))*cos(6.283185307179586*v) }
           BEGIN { x = 20261130; step = 6.283185307179586/262144 }
           NR == 1 { print "t [s],q1 [rad],q2 [rad],tau1 [N m],tau2 [N m]"; next }
           { q1 = step*int($2/step + ($2 >= 0 ? 0.5 : -0.5));
             q2 = step*int($3/step + ($3 >= 0 ? 0.5 : -0.5));
             printf "%.3f,%.12f,%.12f,%.6f,%.6f\n", $1, q1, q2, $4 + 0.01*gauss(),
                    $5 + 0.01*gauss() }' "$work/run.csv"
} > "$work/out.csv"
mv "$work/out.csv" "$out"
echo "robot_data: wrote $out ($(wc -l < "$out") lines)"
