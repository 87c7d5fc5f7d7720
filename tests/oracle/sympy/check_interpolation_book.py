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

# 4.9: the arc of order 5 through M1..M4 (u = 0, 1/3, 2/3, 1) that keeps the
# end tangents M1C2, M4C5 (C2, C5 given, C3, C4 unknown), and the cubic
# through M1, M2, M3 (u = 0, 1/2, 1) that keeps the tangent M1C2
u = sp.symbols('u')
ub = 1 - u
C2, C3, C4, C5 = sp.symbols('C2 C3 C4 C5')
bez5 = (M1 * ub**5 + 5 * C2 * ub**4 * u + 10 * C3 * ub**3 * u**2 + 10 * C4 * ub**2 * u**3
        + 5 * C5 * ub * u**4 + M4 * u**5)
sol = sp.solve([bez5.subs(u, R(1, 3)) - M2, bez5.subs(u, R(2, 3)) - M3], [C3, C4])
w = weights(bez5.subs(sol), [M1, M2, M3, M4, C2, C5])
printed = [ub**2 * (ub**3 - R(21, 4) * ub * u**2 + R(5, 2) * u**3),
           R(81, 4) * ub**2 * u**2 * (2 - 3 * u), R(81, 4) * ub**2 * u**2 * (3 * u - 1),
           u**2 * (R(5, 2) * ub**3 - R(21, 4) * ub**2 * u + u**3),
           5 * ub * u * (1 - R(9, 2) * ub * u) * ub, 5 * ub * u * (1 - R(9, 2) * ub * u) * u]
for i, nm in enumerate(['M1', 'M2', 'M3', 'M4', 'C2', 'C5']):
    print(f"4.9 order 5 {nm}: {'ok' if sp.simplify(w[i] - printed[i]) == 0 else 'DIFFERS'}  {w[i]}")
print("4.9 order 5: C3 =", sol[C3], "  C4 =", sol[C4])
bez3 = M1 * ub**3 + 3 * C2 * ub**2 * u + 3 * C3 * ub * u**2 + M3 * u**3
sol = sp.solve([bez3.subs(u, R(1, 2)) - M2], [C3])
w = weights(bez3.subs(sol), [M1, M2, M3, C2])
printed = [ub * (1 - 2 * u), 8 * u**2 * ub, u**2 * (2 * u - 1), 3 * ub * u * (1 - 2 * u)]
for i, nm in enumerate(['M1', 'M2', 'M3', 'C2']):
    print(f"4.9 order 3 {nm}: {'ok' if sp.simplify(w[i] - printed[i]) == 0 else 'DIFFERS'}  {w[i]}")
print("4.9 order 3: C3 =", sol[C3])

# 4.10, (4.34): the adaptive parabola through M2 at v = v0; the book takes
# v0 = (8.89 - 1.11)/(8.89 - 0.33) ~ 0.91 and prints rounded decimals
v, v0 = sp.symbols('v v0')
vb = 1 - v
par = M1 * vb**2 + 2 * C_ * vb * v + M3 * v**2
sol = sp.solve([par.subs(v, v0) - M2], [C_])
w = weights(par.subs(sol), [M1, M2, M3])
print("(4.34) general node v0:", w, " C =", sol[C_])
for val in [R(91, 100), (R(889, 100) - R(111, 100)) / (R(889, 100) - R(33, 100))]:
    print(f"(4.34) v0 = {val}: ", [sp.expand(x.subs(v0, val)) for x in w],
          " C =", sp.expand(sol[C_].subs(v0, val)))
print("(4.34) printed decimals at v0 = 0.91: 1/v0 =", sp.N(1 / R(91, 100), 6),
      " 1/(v0(1-v0)) =", sp.N(1 / (R(91, 100) * R(9, 100)), 6),
      " 1/(1-v0) =", sp.N(1 / R(9, 100), 6), " v0/(1-v0) =", sp.N(R(91, 9), 6))

# 4.1: C from the book's own relation C kb = K - K_C k, K_C = (A + B)/2
k, K = sp.symbols('k K')
Csol = sp.solve(sp.Eq(C_ * (1 - k), K - (A + B) / 2 * k), C_)[0]
printed = -A * k / (2 * (1 - k)) - B * k / (2 * (1 - k)) + K / k
print("4.1 C:", sp.factor(Csol), " printed K coefficient 1/k:",
      'ok' if sp.simplify(Csol - printed) == 0 else
      'DIFFERS (K coefficient is ' + str(sp.factor(sp.diff(Csol, K))) + ')')
