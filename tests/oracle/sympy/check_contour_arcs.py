#!/usr/bin/env python3
"""Contour arcs of smoothness order k = 2..5 (monograph 3.6): SymPy solves the
implicit point systems independently and compares M_k with the printed
formulas; then checks that the derivatives of order 1..k at t = 0 are
multiples of C - A (and at t = 1 of C - B), printing the multiples.

The scheme of order k (the book gives k = 2, fig. 3.9, and "generalises"):
A, P1, ..., Pk, C on one side and C, Q1, ..., Qk, B on the other, with
  AP1/AP2 = P1P2/P1P3 = ... = P(k-1)Pk/P(k-1)C = t,
  CQ1/CQ2 = Q1Q2/Q1Q3 = ... = Q(k-1)Qk/Q(k-1)B = t,
  M = Pk + (Q1 - Pk) t.
"""
import sympy as sp

t = sp.symbols('t')
tb = 1 - t
A, B, C = sp.symbols('A B C')


def along(p, q, s):
    return p + (q - p) * s


def contour(k):
    P = sp.symbols(f'P1:{k+1}')
    Q = sp.symbols(f'Q1:{k+1}')
    eqs = [P[0] - along(A, P[1], t)]
    eqs += [P[i + 1] - along(P[i], P[i + 2], t) for i in range(k - 2)]
    eqs += [P[k - 1] - along(P[k - 2], C, t)]
    eqs += [Q[0] - along(C, Q[1], t)]
    eqs += [Q[i + 1] - along(Q[i], Q[i + 2], t) for i in range(k - 2)]
    eqs += [Q[k - 1] - along(Q[k - 2], B, t)]
    sol = sp.solve(eqs, list(P) + list(Q))
    return sp.together(along(P[k - 1], Q[0], t).subs(sol))


printed = {
    2: 1 - tb * t,
    3: 1 - 2 * tb * t,
    4: 1 - 3 * tb * t + tb**2 * t**2,
    5: 1 - 4 * tb * t + 3 * tb**2 * t**2,
}
for k in range(2, 6):
    M = contour(k)
    den = printed[k]
    book = (A - C) * tb**(k + 1) / den + (B - C) * t**(k + 1) / den + C
    ok = sp.simplify(M - book) == 0
    print(f"M{k}: {'ok' if ok else 'DIFFERS'}; den = {sp.factor(den)}")
    for j in range(1, k + 1):
        d0 = sp.expand(sp.simplify(sp.diff(M, t, j).subs(t, 0)))
        d1 = sp.expand(sp.simplify(sp.diff(M, t, j).subs(t, 1)))
        c0 = d0.coeff(C)
        c1 = d1.coeff(C)
        ok0 = sp.expand(d0 - c0 * (C - A)) == 0
        ok1 = sp.expand(d1 - c1 * (C - B)) == 0
        print(f"  d^{j}M/dt^{j}: t=0: {c0}*(C - A) {'ok' if ok0 else 'NOT a multiple'};"
              f" t=1: {c1}*(C - B) {'ok' if ok1 else 'NOT a multiple'}")
