#!/usr/bin/env python3
"""The order of the closed curves of monograph 3.5 ("к3п", curves of the
3rd order), from the book's printed point equations of schemes No. 1 and
No. 2 (scheme 2's M as printed: docs/errata.md E5 finds it right), in the
frame C = (0, 0), A = (1, 0), B = (0, 1): the homogeneous coordinates are
reduced (their gcd divided out), the parametrisation's degree in u is read,
and the implicit equation is formed by the resultant in u; its degree is
the curve's order.  Table 3.2's (kP, kQ) = (0.8, 0.5) and (0.9, 0.6) give
order 5 for both schemes (docs/errata.md E25); kP = kQ gives scheme 2 a
cubic and folds scheme 1 onto a segment.  Exits 1 when a result differs
from what E25 records, or from pointcalc's `check order(...)` of
examples/closed_cubics.pcs.
"""
import subprocess
import sys
import os
import json

import sympy as sp

u, kP, kQ, x, y = sp.symbols('u kP kQ x y')
ub = 1 - u
dP = kP * (1 - 2 * u)**2 + 2 * u * ub
dQ = kQ * (1 - 2 * u)**2 + 2 * u * ub
printed = {
    1: (kP * u**2 * ub / dP + kQ * ub**2 * u / dQ,
        kP * ub**3 / dP + kQ * u**3 / dQ),
    2: (u + kP * u**2 * ub / dP - kQ * u * (ub**2 + u**2) / dQ,
        kP * ub**3 / dP + kQ * u**3 / dQ),
}


def orders(scheme, kp, kq):
    """(degree of the reduced parametrisation, degree of the implicit
    curve) of M = (A - C) a + (B - C) b + C"""
    a, b = [sp.cancel(w.subs({kP: kp, kQ: kq})) for w in printed[scheme]]
    na, da = sp.fraction(sp.together(a))
    nb, db = sp.fraction(sp.together(b))
    den = sp.lcm(da, db)
    X = sp.expand(na * sp.cancel(den / da))
    Y = sp.expand(nb * sp.cancel(den / db))
    W = sp.expand(den)
    g = sp.gcd(sp.gcd(X, Y), W)
    X, Y, W = [sp.cancel(p / g) for p in (X, Y, W)]
    pdeg = max(sp.degree(p, u) for p in (X, Y, W))
    res = sp.resultant(sp.expand(X - x * W), sp.expand(Y - y * W), u)
    deg = max(sp.Poly(f, x, y).total_degree()
              for f, m in sp.factor_list(sp.expand(res))[1])
    return pdeg, deg


R = sp.Rational
want = {  # (scheme, kP, kQ): (parametrisation degree, order)
    (1, R(4, 5), R(1, 2)): (5, 5),
    (1, R(9, 10), R(3, 5)): (5, 5),
    (1, R(4, 5), R(4, 5)): (2, 1),
    (2, R(4, 5), R(1, 2)): (5, 5),
    (2, R(9, 10), R(3, 5)): (5, 5),
    (2, R(4, 5), R(4, 5)): (3, 3),
}
bad = 0
for (s, kp, kq), w in want.items():
    got = orders(s, kp, kq)
    ok = got == w
    bad += not ok
    print(f"scheme {s}, kP = {kp}, kQ = {kq}: parametrisation of degree "
          f"{got[0]}, a curve of order {got[1]}: {'agrees' if ok else 'DIFFERS'}")
# pointcalc's own verdicts on the same claims (examples/closed_cubics.pcs)
pc = os.environ.get('PC_BIN', 'build/pointcalc')
if os.path.exists(pc):
    out = subprocess.run([pc, 'derive', 'examples/closed_cubics.pcs',
                          '--format', 'json'], capture_output=True, text=True)
    checks = [c for c in json.loads(out.stdout)['checks']
              if c['kind'] == 'order']
    ok = out.returncode == 0 and [c['found'] for c in checks] == [5, 5, 5, 3]
    bad += not ok
    print(f"pointcalc check order(...): {[c['found'] for c in checks]}: "
          f"{'agrees' if ok else 'DIFFERS'}")
print("closed curves of 3.5: order 5 for table 3.2, not 3 (E25)" if not bad
      else "FAILED")
sys.exit(1 if bad else 0)
