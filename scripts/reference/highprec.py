#!/usr/bin/env python3
"""High-precision reference trajectories for dpend's tests (independent of the Fortran code).

Lagrange's equations of the compound double pendulum, written here from scratch
(angles from the horizontal x axis, counter-clockwise, y up):
    M11 = (m1/3 + m2) L1^2,  M12 = m2 L1 L2/2 cos(q1-q2),  M22 = m2 L2^2/3
    M qdd = -dV/dq - c,  c = k sin(q1-q2) (qd2^2, -qd1^2),  k = m2 L1 L2/2
    V = (m1/2 + m2) g L1 sin q1 + m2 g L2/2 sin q2
integrated with mpmath's Taylor-series ODE solver (mpmath.odefun) at 40 digits.
Not a dependency of dpend: run once to regenerate data/reference/*.txt.

usage: highprec.py q1 q2 w1 w2 t_end n_out out.txt
"""
import sys
import mpmath as mp

mp.mp.dps = 40


def main():
    q1, q2, w1, w2 = (mp.mpf(a) for a in sys.argv[1:5])
    t_end = mp.mpf(sys.argv[5])
    n_out = int(sys.argv[6])
    out = sys.argv[7]
    m1 = m2 = mp.mpf(1)
    l1 = l2 = mp.mpf(1)
    g = mp.mpf('9.8')
    k = m2 * l1 * l2 / 2

    def f(t, y):
        a, b, wa, wb = y
        d = a - b
        m11 = (m1 / 3 + m2) * l1**2
        m12 = k * mp.cos(d)
        m22 = m2 * l2**2 / 3
        r1 = -(m1 / 2 + m2) * g * l1 * mp.cos(a) - k * mp.sin(d) * wb**2
        r2 = -m2 * g * l2 / 2 * mp.cos(b) + k * mp.sin(d) * wa**2
        det = m11 * m22 - m12**2
        return [wa, wb, (m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det]

    sol = mp.odefun(f, 0, [q1, q2, w1, w2], tol=mp.mpf(10) ** (-32), degree=30)
    with open(out, 'w') as fh:
        fh.write('# high-precision reference (mpmath odefun, 40 digits, tol 1e-32)\n')
        fh.write(f'# m1=m2=1 kg, l1=l2=1 m, g=9.8 m/s^2; q(0)=({sys.argv[1]}, {sys.argv[2]}) rad,'
                 f' qdot(0)=({sys.argv[3]}, {sys.argv[4]}) rad/s\n')
        fh.write('# t [s]   q1 [rad]   q2 [rad]   qdot1 [rad/s]   qdot2 [rad/s]\n')
        for i in range(1, n_out + 1):
            t = t_end * i / n_out
            y = sol(t)
            fh.write(' '.join(mp.nstr(v, 25, min_fixed=-5, max_fixed=5) for v in [t] + list(y)) + '\n')
            print(t, flush=True)


if __name__ == '__main__':
    main()
