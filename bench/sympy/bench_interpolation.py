#!/usr/bin/env python3
"""The monograph's Maple program (4.8) written the way a SymPy user writes
it: symbols for the points, the Bezier curve of order n, solve for the
control points, collect by the nodes.  Usage: bench_interpolation.py N ...
[--contour]; prints "interp N SECONDS" per N (one run each: the large
orders take seconds to minutes), and with --contour "contour5 SECONDS" for
the 3.6 M5 arc (10 unknown points, coefficients in t)."""
import sys
import time

import sympy as sp


def interpolation(n):
    u = sp.symbols('u')
    A = sp.symbols(f'A1:{n + 2}')
    M = sp.symbols(f'M1:{n + 2}')
    e = sum(A[i] * sp.binomial(n, i) * (1 - u)**(n - i) * u**i for i in range(n + 1))
    S = [sp.Eq(e.subs(u, sp.Rational(i, n)), M[i]) for i in range(n + 1)]
    R = sp.solve(S, A)
    return sp.collect(sp.expand(e.subs(R)), M)


def contour5():
    t = sp.symbols('t')
    A, B, C = sp.symbols('A B C')
    k = 5
    P = sp.symbols('P1:6')
    Q = sp.symbols('Q1:6')

    def along(p, q, s):
        return p + (q - p) * s
    eqs = [P[0] - along(A, P[1], t)] + [P[i + 1] - along(P[i], P[i + 2], t) for i in range(k - 2)]
    eqs += [P[k - 1] - along(P[k - 2], C, t)]
    eqs += [Q[0] - along(C, Q[1], t)] + [Q[i + 1] - along(Q[i], Q[i + 2], t) for i in range(k - 2)]
    eqs += [Q[k - 1] - along(Q[k - 2], B, t)]
    sol = sp.solve(eqs, list(P) + list(Q))
    return sp.collect(sp.together(along(P[k - 1], Q[0], t).subs(sol)), [A, B, C])


for a in sys.argv[1:]:
    t0 = time.perf_counter()
    if a == '--contour':
        contour5()
        print(f"contour5 {time.perf_counter() - t0:.6f}", flush=True)
    else:
        interpolation(int(a))
        print(f"interp {a} {time.perf_counter() - t0:.6f}", flush=True)
