#!/usr/bin/env bash
# Make data/robot_example.csv: a synthetic robot run of known parameters, as a
# 500 Hz encoder and the motors' torque readings would give it (docs/robot.md).
#
# The robot: two rods, m = 1, 0.7 kg, l = 0.8, 0.6 m, g = 9.8 m/s^2, viscous joint
# friction c = 0.02, 0.01 N m s, Coulomb friction c_f = 0.05, 0.03 N m smoothed at
# v_s = 0.5 rad/s; released from q = (-1.2, -1.0) rad at rest under the torques
#   tau1 = 0.4 sin(1.3 t) + 0.2 sin(3.1 t + 0.4),  tau2 = 0.15 sin(2.2 t + 1) + 0.05
# (a torque file sampled every 1 ms, linear between samples), dop853 at rtol 1e-12.
# Its angles are sampled at 500 Hz for 6 s and quantised to 16384 counts per turn
# (a 4096-line quadrature encoder); the torques are the applied ones.
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
             for (k = 0; k <= 6000; k++) { t = k/1000;
               printf "%.3f,%.17g,%.17g\n", t, 0.4*sin(1.3*t) + 0.2*sin(3.1*t + 0.4),
                      0.15*sin(2.2*t + 1) + 0.05 } }' > "$work/torques.csv"
"$dpend" simulate --m 1,0.7 --l 0.8,0.6 --damping 0.02,0.01 --coulomb 0.05,0.03 \
  --coulomb-speed 0.5 --torque-file "$work/torques.csv" --q1 -1.2 --q2 -1.0 \
  --method dop853 --rtol 1e-12 --atol 1e-14 --t-end 6 --output-dt 0.002 \
  --output "$work/run.h5" --quiet > /dev/null
"$dpend" export "$work/run.h5" --csv /trajectory/t /trajectory/q /trajectory/tau \
  > "$work/run.csv"
{
  sed -n '2,12p' "$0" | sed 's/^# \{0,1\}/# /'
  echo '# Columns: t [s], q1, q2 [rad] from the horizontal x axis (quantised), tau1, tau2 [N m].'
  awk -F, 'NR == 1 { print "t [s],q1 [rad],q2 [rad],tau1 [N m],tau2 [N m]"; next }
           { step = 2*3.14159265358979323846/16384;
             q1 = step*int($2/step + ($2 >= 0 ? 0.5 : -0.5));
             q2 = step*int($3/step + ($3 >= 0 ? 0.5 : -0.5));
             printf "%.3f,%.10f,%.10f,%.9f,%.9f\n", $1, q1, q2, $4, $5 }' "$work/run.csv"
} > "$work/out.csv"
mv "$work/out.csv" "$out"
echo "robot_data: wrote $out ($(wc -l < "$out") lines)"
