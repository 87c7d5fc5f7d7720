#!/usr/bin/env python3
"""Checks the monograph's printed interpolation curves (4.10, 4.16, 4.17,
4.21, 4.24, 4.28, 4.35, 4.37) against an independent SymPy derivation.

The Bezier-based curves of order n through n+1 nodes at t = k/n are
polynomials of degree n through n+1 points, so each weight must be the
Lagrange basis polynomial of its node.  The printed forms are typed in
from the book as printed (tb = 1 - t; decimal commas as points).  Prints
one line per weight: "ok" or the difference.  Used for docs/errata.md and
the expectations of examples/interpolation_*.pcs.
"""
import sympy as sp

t = sp.symbols('t')
tb = 1 - t


def lagrange(n, i):
    return sp.prod([(t - sp.Rational(j, n)) / (sp.Rational(i, n) - sp.Rational(j, n))
                    for j in range(n + 1) if j != i])


def check(label, n, printed):
    for i, w in enumerate(printed):
        d = sp.expand(sp.nsimplify(w, rational=True) - lagrange(n, i))
        print(f"{label} M{i+1}: {'ok' if d == 0 else 'DIFFERS by ' + str(sp.factor(d))}")


R = sp.Rational
# (4.10)
check("(4.10)", 2, [tb * (1 - 2 * t), 4 * tb * t, t * (2 * t - 1)])
# (4.16)
check("(4.16)", 3, [tb**3 - R(5, 2) * tb**2 * t + tb * t**2,
                    9 * tb**2 * t - R(9, 2) * tb * t**2,
                    -R(9, 2) * tb**2 * t + 9 * tb * t**2,
                    tb**2 * t - R(5, 2) * tb * t**2 + t**3])
# (4.17): M = (M1 tb + M4 t)(2 - 9 tb t)/2 + 9 tb t (M2 (2 - 3t) + M3 (3t - 1))/2
check("(4.17)", 3, [tb * (2 - 9 * tb * t) / 2, 9 * tb * t * (2 - 3 * t) / 2,
                    9 * tb * t * (3 * t - 1) / 2, t * (2 - 9 * tb * t) / 2])
# (4.21)
check("(4.21)", 4, [tb**4 - R(13, 3) * tb**3 * t + R(13, 3) * tb**2 * t**2 - tb * t**3,
                    16 * tb**3 * t - R(64, 3) * tb**2 * t**2 + R(16, 3) * tb * t**3,
                    -12 * tb**3 * t + 40 * tb**2 * t**2 - 12 * tb * t**3,
                    R(16, 3) * tb**3 * t - R(64, 3) * tb**2 * t**2 + 16 * tb * t**3,
                    -tb**3 * t + R(13, 3) * tb**2 * t**2 - R(13, 3) * tb * t**3 + t**4])
# (4.24): Bernstein form with the printed control points
C = [[1, 0, 0, 0, 0, 0],
     [R(-77, 60), 5, -5, R(10, 3), R(-5, 4), R(1, 5)],
     [R(269, 240), R(-145, 24), R(295, 24), R(-115, 12), R(185, 48), R(-77, 120)],
     [R(-77, 120), R(185, 48), R(-115, 12), R(295, 24), R(-145, 24), R(269, 240)],
     [R(1, 5), R(-5, 4), R(10, 3), -5, 5, R(-77, 60)],
     [0, 0, 0, 0, 0, 1]]
check("(4.24)", 5, [sum(sp.binomial(5, k) * tb**(5 - k) * t**k * C[k][i] for k in range(6))
                    for i in range(6)])
# (4.28) as printed, with "tb tb^5" read as "tb t^5" and the last "tb^6" as
# "t^6" (otherwise the weights do not even sum to 1)
rows = [[1, -8.7, 22.7, -22.7, 8.7, -1, 0],
        [0, 36, -133.2, 151.2, -61.2, 7.2, 0],
        [0, -45, 301.5, -418.5, 184.5, -22.5, 0],
        [0, 40, -308, 600, -308, 40, 0],
        [0, -22.5, 184.5, -418.5, 301.5, -45, 0],
        [0, 7.2, -61.2, 151.2, -133.2, 36, 0],
        [0, -1, 8.7, -22.7, 22.7, -8.7, 1]]
check("(4.28)", 6, [sum(sp.nsimplify(c) * tb**(6 - k) * t**k for k, c in enumerate(row))
                    for row in rows])

# (4.35), (4.37): solve the systems here, with the points as symbols
M1, M2, M3, M4, B, C_, A, D = sp.symbols('M1 M2 M3 M4 B C A D')


def weights(expr, pts):
    expr = sp.together(expr)
    return [sp.factor(sp.diff(expr, p)) for p in pts]


des = (M1 * tb**3 + B * t**2 * tb + C_ * tb**2 * t + M4 * t**3) / (2 * t**2 - 2 * t + 1)
sol = sp.solve([des.subs(t, R(1, 3)) - M2, des.subs(t, R(2, 3)) - M3], [B, C_])
w = weights(des.subs(sol), [M1, M2, M3, M4])
den = 4 * t**2 - 4 * t + 2
printed = [(-9 * t**3 + 18 * t**2 - 11 * t + 2) / den, (15 * t**3 - 25 * t**2 + 10 * t) / den,
           (-15 * t**3 + 20 * t**2 - 5 * t) / den, (9 * t**3 - 9 * t**2 + 2 * t) / den]
for i in range(4):
    print(f"(4.35) M{i+1}: {'ok' if sp.simplify(w[i] - printed[i]) == 0 else 'DIFFERS'}"
          f"  {w[i]}")
print("(4.35) B =", sol[B], "  C =", sol[C_])

rat = (A * t**3 + B * t**2 + C_ * t + D) / (t**3 + t**2 + t + 1)
sol = sp.solve([rat.subs(t, R(k, 3)) - m for k, m in enumerate([M1, M2, M3, M4])], [A, B, C_, D])
w = weights(rat.subs(sol), [M1, M2, M3, M4])
den = 6 * t**3 + 6 * t**2 + 6 * t + 6
printed = [(-27 * t**3 + 54 * t**2 - 33 * t + 6) / den, (120 * t**3 - 200 * t**2 + 80 * t) / den,
           (-195 * t**3 + 260 * t**2 - 65 * t) / den, (108 * t**3 - 108 * t**2 + 24 * t) / den]
for i in range(4):
    print(f"(4.37) M{i+1}: {'ok' if sp.simplify(w[i] - printed[i]) == 0 else 'DIFFERS'}"
          f"  {w[i]}")
print("(4.37)", {k: v for k, v in sol.items()})
