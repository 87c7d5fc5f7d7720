#!/usr/bin/env python3
"""The examples of issue 24 derived the way a SymPy user derives them, for
bench_derive's side-by-side table (bench/run_sympy.sh): base points as unit
weight vectors, along(P, Q, s) = P + (Q - P)*s, every meet of two lines by
sp.solve for the two line parameters, sp.cancel after every step (as
pointcalc reduces every definition), and the result printed with str() (what
`derive` prints: a user's whole job).  Usage: bench_whole.py NAME ... with
NAME desargues_arc, conic_five_points, double_contact, space_cubic or
interp:N; prints "NAME SECONDS" (the median of RUNS=3 runs, or one run for
interp with N >= 24: seconds to minutes)."""
import os
import statistics
import sys
import time

import sympy as sp


def base(i, n):
    return sp.Matrix([1 if j == i else 0 for j in range(n)])


def simp(v):
    return v.applyfunc(sp.cancel)


def along(p, q, s):
    return simp(p + (q - p) * s)


def meet(p, q, r, s):
    lam, mu = sp.symbols('lam mu')
    sol = sp.solve(list(p + (q - p) * lam - r - (s - r) * mu), [lam, mu],
                   dict=True)[0]
    return simp((p + (q - p) * lam).subs(sol))


def desargues_arc():
    t = sp.symbols('t')
    A, B, C, D = (base(i, 4) for i in range(4))
    P, Q, K = along(A, C, t), along(C, B, t), along(B, D, t)
    N, J = along(P, Q, t), along(Q, K, t)
    T, S = meet(P, Q, A, B), meet(Q, K, C, D)
    return meet(S, N, T, J)


def conic_five_points():
    u, pD, qD, pE, qE = sp.symbols('u pD qD pE qE')
    A, B, C = (base(i, 3) for i in range(3))
    D = simp((A - C) * pD + (B - C) * qD + C)
    E = simp((A - C) * pE + (B - C) * qE + C)
    S = meet(B, E, A, D)
    U = simp((A - C) * u + C)
    V = meet(S, U, C, B)
    return meet(U, E, V, D)


def conic_2_1_6(A, B, C, T, k):
    T1 = simp((A + B) / 2)
    K = along(C, T1, k)
    Pa, Pb = meet(A, K, C, T), meet(B, K, C, T)
    return meet(A, Pb, B, Pa)


def double_contact():
    v, kp, kq = sp.symbols('v kp kq')
    A, B, C = (base(i, 3) for i in range(3))
    T = along(A, B, v)
    P, Q = conic_2_1_6(A, B, C, T, kp), conic_2_1_6(A, B, C, T, kq)
    return along(P, Q, v)


def space_cubic():
    u, v, fP, fQ, n = sp.symbols('u v fP fQ n')
    A, B, C, D = (base(i, 4) for i in range(4))
    P = conic_2_1_6(A, B, C, along(A, B, u), fP)
    Q = conic_2_1_6(A, B, C, along(A, B, v), fQ)
    XP, XQ = meet(A, P, C, B), meet(A, Q, C, B)
    # X_Q = X_P on the line CB: the same ratio of the weights of B and C
    roots = sp.solve(sp.numer(sp.cancel(XQ[1] * XP[2] - XQ[2] * XP[1])), v)
    vs = [r for r in roots if sp.simplify(r - u) != 0][0]
    Q = simp(Q.subs(v, vs))
    N = along(A, D, n)
    return meet(D, P, N, Q)


def interpolation(n):
    u = sp.symbols('u')
    A = sp.symbols(f'A1:{n + 2}')
    M = sp.symbols(f'M1:{n + 2}')
    e = sum(A[i] * sp.binomial(n, i) * (1 - u)**(n - i) * u**i
            for i in range(n + 1))
    S = [sp.Eq(e.subs(u, sp.Rational(i, n)), M[i]) for i in range(n + 1)]
    R = sp.solve(S, A)
    return sp.collect(sp.expand(e.subs(R)), M)


def main():
    runs = int(os.environ.get('RUNS', '3'))
    for name in sys.argv[1:]:
        if name.startswith('interp:'):
            n = int(name.split(':')[1])
            job, k = (lambda n=n: interpolation(n)), (1 if n >= 24 else runs)
        else:
            job, k = globals()[name], runs
        ts = []
        for _ in range(k):
            t0 = time.perf_counter()
            str(job())
            ts.append(time.perf_counter() - t0)
        print(f"{name} {statistics.median(ts):.6f} {min(ts):.6f} "
              f"{max(ts):.6f}", flush=True)


if __name__ == '__main__':
    main()
