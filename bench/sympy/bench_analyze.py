#!/usr/bin/env python3
"""What `pointcalc analyze` finds, done by SymPy the way a SymPy user would
(bench/bench_analyze.c runs it after its own timings): for each case
PC FILE|DEFINE|OUTPUT|LO|HI the curve's weights are read from `pointcalc
derive --format json` (not timed), then timed, median of ROUNDS runs:
the reduced common denominator, the poles (real_roots of the denominator
in [LO, HI]), the index (a gcd in s, t), the stop points (gcd of the
numerators of dM/dt, real_roots), the Taylor series at both ends to 2n + 3
terms (the order of smoothness), and for curves over three base points the
inflections (real_roots of det(N, N', N'')) and the implicit equation
(resultant, factor_list).  Prints "OUTPUT MS" per case (one run when it
takes over 2 s; "OUTPUT timeout" after TIMEOUT s).
"""
import json
import signal
import subprocess
import sys
import time

import sympy as sp

ROUNDS = 3
TIMEOUT = 120  # seconds per case: SymPy's order-12 series can take long


def analyze(w, t, lo, hi):
    s, h, x, y, z = sp.symbols('s h x y z')
    den = sp.lcm([sp.fraction(sp.together(wi))[1] for wi in w])
    n = [sp.Poly(sp.cancel(wi * den), t) for wi in w]
    den = sp.Poly(den, t)
    deg = max(p.degree() for p in n + [den])

    def in_range(p):
        if p.degree() < 1:
            return []
        return [r for r in sp.real_roots(p) if lo <= r <= hi]

    poles = in_range(den)
    g = 0
    for ni in n[1:]:
        g = sp.gcd(g, sp.expand(ni.as_expr() * n[0].as_expr().subs(t, s) -
                                n[0].as_expr() * ni.as_expr().subs(t, s)))
    index = sp.Poly(g, t).degree()
    W = [ni.diff(t) * den - ni * den.diff(t) for ni in n]
    gs = W[0]
    for Wi in W[1:]:
        gs = sp.gcd(gs, Wi)
    stops = in_range(sp.Poly(gs, t))
    for e in (lo, hi):
        [sp.series(sp.cancel(wi.subs(t, e + h)), h, 0, 2 * deg + 3) for wi in w]
    if len(n) == 3:
        m = sp.Matrix([[p.as_expr() for p in n],
                       [p.diff(t).as_expr() for p in n],
                       [p.diff(t).diff(t).as_expr() for p in n]])
        infl = in_range(sp.Poly(m.det(), t))
        R = sp.resultant(x * n[1].as_expr() - y * n[0].as_expr(),
                         x * n[2].as_expr() - z * n[0].as_expr(), t)
        F = sp.factor_list(R)
        return poles, index, stops, infl, F
    return poles, index, stops


def timeout(signum, frame):
    raise TimeoutError


def main():
    pc = sys.argv[1]
    for case in sys.argv[2:]:
        path, define, name, lo, hi = case.split('|')
        cmd = [pc, 'derive', path, '--format', 'json']
        if define:
            cmd += ['-D', define]
        j = json.loads(subprocess.run(cmd, capture_output=True, text=True,
                                      check=True).stdout)
        o = next(o for o in j['outputs'] if o['name'] == name)
        t = sp.Symbol(j['params'][0])
        loc = {p: sp.Symbol(p) for p in j['points'] + j['params']}
        w = [sp.sympify(v, locals=loc) for v in o['terms'].values()]
        label = f"{name}{'(' + define + ')' if define else ''}"
        times = []
        signal.signal(signal.SIGALRM, timeout)
        signal.alarm(TIMEOUT)
        try:
            for _ in range(ROUNDS):
                t0 = time.perf_counter()
                analyze(w, t, sp.Rational(lo), sp.Rational(hi))
                times.append((time.perf_counter() - t0) * 1e3)
                if times[0] > 2000:  # one run is enough to compare
                    break
        except TimeoutError:
            print(f"{label} timeout", flush=True)
            continue
        finally:
            signal.alarm(0)
        times.sort()
        print(f"{label} {times[len(times) // 2]:.1f}", flush=True)


if __name__ == '__main__':
    main()
