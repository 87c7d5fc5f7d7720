#!/usr/bin/env python3
"""The "cubic arc in space" of monograph 2.6 (examples/space_cubic.pcs) is a
plane conic (docs/errata.md E26), found independently of pointcalc: in the
frame A = 0, B = e1, C = e2, D = e3 the two conics of (2.146), v of (2.148)
and N = A + n (D - A) of (2.156); M is the meet of the generators DP and NQ
(solved in coordinates, checked to lie on both).  For two sets of
(fP, fQ, n) the reduced coordinates of M have degree 2 in u (not 3), and
the chords from M(1/7) to M(2/7), M(3/7), M(4/7) span a plane (rank 2):
M is a conic.  Exits 1 otherwise.
"""
import sys

import sympy as sp

u, s, r = sp.symbols('u s r')
A = sp.Matrix([0, 0, 0])
B = sp.Matrix([1, 0, 0])
C = sp.Matrix([0, 1, 0])
D = sp.Matrix([0, 0, 1])


def conic(f, x):
    """(2.146): (A - C) f xb^2/d + (B - C) f x^2/d + C"""
    xb = 1 - x
    d = f * (1 - 2 * x)**2 + 2 * x * xb
    return (A - C) * f * xb**2 / d + (B - C) * f * x**2 / d + C


bad = 0
for fP, fQ, n in [(sp.Rational(1, 3), sp.Rational(1, 5), sp.Rational(1, 2)),
                  (sp.Rational(2, 7), sp.Rational(3, 4), sp.Rational(5, 3))]:
    P = conic(fP, u)
    v = fP * (1 - fQ) * u / (fP * (1 - fQ) * u + fQ * (1 - fP) * (1 - u))
    Q = conic(fQ, v)
    N = A + n * (D - A)
    eqs = list((D + s * (P - D)) - (N + r * (Q - N)))
    sol = sp.solve([eqs[0], eqs[2]], [s, r], dict=True)[0]
    M = (D + sol[s] * (P - D)).applyfunc(sp.cancel)
    if sp.simplify(M - (N + sol[r] * (Q - N))) != sp.zeros(3, 1):
        print('FAIL: DP and NQ do not meet', fP, fQ, n)
        bad = 1
        continue
    den = sp.lcm([sp.fraction(sp.together(c))[1] for c in M])
    num = [sp.cancel(c * den) for c in M]
    deg = max(sp.degree(sp.Poly(x, u)) for x in num + [den])
    pts = [M.subs(u, sp.Rational(k, 7)) for k in range(1, 5)]
    rank = sp.Matrix.hstack(*[p - pts[0] for p in pts[1:]]).rank()
    ok = deg == 2 and rank == 2
    print('%s fP=%s fQ=%s n=%s: degree %d in u, chords of rank %d' %
          ('ok' if ok else 'FAIL', fP, fQ, n, deg, rank))
    bad |= not ok
print('2.6: the arc is a plane conic, not a space cubic (E26)' if not bad
      else 'FAIL')
sys.exit(1 if bad else 0)
