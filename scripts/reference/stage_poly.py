#!/usr/bin/env python3
"""Offline reference: the coefficients of `sincos_add_stage`
(src/lanes/dpend_pendulum_lane_math.inc) and their error bounds.

sin d = d + d^3 P(d^2) and cos d - 1 = d^2 Q(d^2) on |d| <= 1/16 (d_max): the
Taylor series of P and Q to z^3 (z = d^2), whose z^3 term is replaced by its best
quadratic on [0, Z] (Z = 1/256: Chebyshev economization, z^3 ~ 1.5 Z z^2 -
0.5625 Z^2 z + Z^3/32). Prints the coefficients rounded to double and the largest
errors on a grid of 2001 points, in 40-digit arithmetic (mpmath).

    python3 scripts/reference/stage_poly.py
"""
from mpmath import mp, mpf, sin, cos, fac

mp.dps = 40
Z = mpf(1) / 256


def economized(c0, c1, c2, c3):
    """c0 + c1 z + c2 z^2 + c3 z^3 with z^3 replaced by its best quadratic on [0, Z]."""
    return (c0 + c3 * Z**3 / 32, c1 - mpf("0.5625") * c3 * Z**2, c2 + mpf("1.5") * c3 * Z)


p = [float(x) for x in economized(-mpf(1) / 6, mpf(1) / 120, -mpf(1) / 5040, 1 / fac(9))]
q = [float(x) for x in economized(-mpf(1) / 2, mpf(1) / 24, -mpf(1) / 720, 1 / fac(8))]
for name, v in zip(["a3", "a5", "a7", "b2", "b4", "b6"], p + q):
    print(f"{name} = {v:.20e}_dp")
P = [mpf(x) for x in p]
Q = [mpf(x) for x in q]
err_s = err_c = mpf(0)
for k in range(2001):
    d = mpf(k) / 2000 / 16
    z = d * d
    s = d + d**3 * (P[0] + z * (P[1] + z * P[2]))
    c = z * (Q[0] + z * (Q[1] + z * Q[2]))
    err_s = max(err_s, abs(s - sin(d)))
    err_c = max(err_c, abs(c - (cos(d) - 1)))
print(f"max |error| on |d| <= 1/16: sin {float(err_s):.2e}, cos - 1 {float(err_c):.2e}")
