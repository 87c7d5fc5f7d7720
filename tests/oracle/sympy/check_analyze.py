#!/usr/bin/env python3
"""pointcalc analyze against SymPy: each book curve is written again from the
book's printed formula (or built again by its construction), and SymPy finds
what analyze reports, its own way:

  degree       max degree of the numerators over one reduced denominator
  order        the degree of the implicit equation (plane curves), or the
               degree over the index gcd_s,t(n_i(t) n_1(s) - n_1(t) n_i(s))
  poles        real roots of the denominator in the range (solveset)
  stop points  common real roots of the numerators of dM/dt
  inflections  plane curves: roots of the numerator of the cross product
               M' x M'' in coordinates A = (0, 0), B = (1, 0), C = (0, 1)
               (an affine frame; invariance makes it enough), stop points
               and poles left out
  smoothness   at each end: derivatives first..k parallel to the first
               non-zero one (sp.diff, then limits at the end)
  implicit     sp.resultant of x*n2 - y*n1, x*n3 - z*n1, factored, the
               spurious x^k left out; compared up to a constant factor
  passes       base points: where all other weights vanish

Every value of pointcalc's JSON is parsed with sympify and compared exactly
(isolated roots: within 1e-14).  With --at (check_metric): the curvature
at the ends, its largest value and the arc length, by mpmath at 30 digits,
within 1e-12.  PC_BIN names the binary (default
build/pointcalc).  Prints one line per curve and "analyze: N curves agree".
"""
import json
import os
import subprocess
import sys
import tempfile

import sympy as sp

PC = os.environ.get('PC_BIN', 'build/pointcalc')
t, s, x, y, z = sp.symbols('t s x y z')
tb = 1 - t


def along(p, q, r):
    return p + (q - p) * r


def contour(k, A, B, C):
    """monograph 3.6: the contour arc of smoothness order k, solved again"""
    P = sp.symbols(f'P1:{k+1}')
    Q = sp.symbols(f'Q1:{k+1}')
    eqs = [P[0] - along(A, P[1], t)]
    eqs += [P[i + 1] - along(P[i], P[i + 2], t) for i in range(k - 2)]
    eqs += [P[k - 1] - along(P[k - 2], C, t)]
    eqs += [Q[0] - along(C, Q[1], t)]
    eqs += [Q[i + 1] - along(Q[i], Q[i + 2], t) for i in range(k - 2)]
    eqs += [Q[k - 1] - along(Q[k - 2], B, t)]
    sol = sp.solve(eqs, list(P) + list(Q))
    return sp.expand(along(P[k - 1], Q[0], t).subs(sol))


def weights_of(expr, points):
    """the weights of a linear combination of point symbols"""
    e = sp.expand(expr)
    return [sp.factor(e.coeff(p)) for p in points]


def homogeneous(w):
    """numerators over the reduced common denominator"""
    den = sp.lcm([sp.fraction(sp.together(wi))[1] for wi in w])
    n = [sp.cancel(wi * den) for wi in w]
    g = sp.gcd_list(n + [den])
    return [sp.Poly(sp.cancel(ni / g), t) for ni in n], sp.Poly(sp.cancel(den / g), t)


def real_roots_in(p, lo, hi):
    if p.degree() < 1:
        return []
    rs = set(sp.real_roots(p))
    return sorted((r for r in rs if (lo is None or r >= lo) and (hi is None or r <= hi)),
                  key=lambda r: float(r))


def without(p, q):
    """p without the irreducible factors it shares with q"""
    p = sp.Poly(p, t)
    while True:
        g = sp.gcd(p, sp.Poly(q, t))
        if g.degree() < 1:
            return p
        p = sp.quo(p, g)


def common_roots(polys, lo, hi, excl=None):
    g = polys[0]
    for p in polys[1:]:
        g = sp.gcd(g, p)
    g = sp.Poly(g, t)
    return real_roots_in(without(g, excl) if excl is not None else g, lo, hi)


def index_of(n):
    """deg_t of gcd_i (n_i(t) n_0(s) - n_0(t) n_i(s))"""
    g = 0
    for ni in n[1:]:
        f = sp.expand(ni.as_expr() * n[0].as_expr().subs(t, s) -
                      n[0].as_expr() * ni.as_expr().subs(t, s))
        g = sp.gcd(g, f)
    return sp.Poly(g, t).degree()


def smoothness(w, e, deg):
    """first non-zero derivative at t = e and the last order up to which
    all are parallel to it (Taylor series: c_j = M^(j)(e)/j!)"""
    h = sp.Symbol('h')
    N = 2 * deg + 3
    ser = [sp.expand(sp.series(sp.cancel(c.subs(t, e + h)), h, 0, N).removeO())
           for c in w]
    ders = [[sp.factorial(j) * c.coeff(h, j) for c in ser] for j in range(1, N)]
    first = next(j for j, d in enumerate(ders, 1) if any(c != 0 for c in d))
    T = ders[first - 1]
    k = first
    for j in range(first + 1, len(ders) + 1):
        d = ders[j - 1]
        if all(d[a] * T[b] - d[b] * T[a] == 0
               for a in range(len(T)) for b in range(len(T))):
            k = j
        else:
            break
    return first, k, T


def implicit(n):
    R = sp.resultant(x * n[1].as_expr() - y * n[0].as_expr(),
                     x * n[2].as_expr() - z * n[0].as_expr(), t)
    facs = [f for f, _ in sp.factor_list(R)[1] if f.free_symbols != {x}]
    assert len(facs) == 1, facs
    return sp.expand(facs[0])


def same_up_to_constant(a, b):
    q = sp.cancel(a / b)
    return q.free_symbols == set()


def as_value(v):
    return sp.sympify(v) if isinstance(v, str) else v


def same_roots(got, want):
    if len(got) != len(want):
        return False
    for g, w in zip(got, want):
        if isinstance(g, str):
            if sp.simplify(sp.sympify(g) - w) != 0:
                return False
        elif abs(g - float(w)) > 1e-14 * max(1, abs(g)):
            return False
    return True


def analyze(path, name, defines=(), sets=()):
    cmd = [PC, 'analyze', path, '--format', 'json', '--output', name]
    for d in defines:
        cmd += ['-D', d]
    for v in sets:
        cmd += ['--set', v]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def check(label, path, name, expr, points, rng, defines=(), plane=None,
          smooth=None, defs=None, sets=()):
    """expr: the curve as a combination of the point symbols; rng: (lo, hi)
    or None; smooth: the book's smoothness order at both ends, if it states
    one; defs: {name: [poles]} the book states for the definitions"""
    j = analyze(path, name, defines, sets)
    o = j['outputs'][0]
    lo, hi = rng if rng else (None, None)
    w = weights_of(expr, points)
    n, den = homogeneous(w)
    deg = max(p.degree() for p in n + [den])
    idx = index_of(n)
    errs = []
    if o['degree'] != deg:
        errs.append(f"degree {o['degree']} != {deg}")
    if o['index'] != idx or o['order'] != deg // idx:
        errs.append(f"index/order {o['index']}/{o['order']} != {idx}/{deg // idx}")
    poles = real_roots_in(den, lo, hi)
    if not same_roots(o['poles'], poles):
        errs.append(f"poles {o['poles']} != {poles}")
    W = [ni.diff(t) * den - ni * den.diff(t) for ni in n]
    stops = common_roots(W, lo, hi, den)
    stop_poly = sp.Poly(W[0], t)
    for Wi in W[1:]:
        stop_poly = sp.gcd(stop_poly, Wi)
    if not same_roots(o['stop_points'], stops):
        errs.append(f"stop points {o['stop_points']} != {stops}")
    live = [i for i, p in enumerate(points) if w[i] != 0]
    if len(live) == 3 and plane is not False:
        a, b, c = (w[i] for i in live)  # frame: b -> (1, 0), c -> (0, 1)
        X, Y = b, c
        cross = sp.together(sp.diff(X, t) * sp.diff(Y, t, 2) -
                            sp.diff(Y, t) * sp.diff(X, t, 2))
        num = sp.Poly(sp.fraction(cross)[0], t)
        if stop_poly.degree() >= 1:
            num = without(num, stop_poly)
        infl = real_roots_in(without(num, den), lo, hi)
        if not same_roots(o['inflections'], infl):
            errs.append(f"inflections {o['inflections']} != {infl}")
        F = implicit([n[i] for i in live])
        names = [str(points[i]) for i in live]
        got = sp.sympify(o['implicit'], locals={k: sp.Symbol(k) for k in names})
        got = got.subs({sp.Symbol(names[0]): x, sp.Symbol(names[1]): y,
                        sp.Symbol(names[2]): z})
        if not same_up_to_constant(got, F):
            errs.append(f"implicit {o['implicit']} != {F}")
        if sp.Poly(F, x, y, z).total_degree() != o['order']:
            errs.append("order != degree of the implicit equation")
    want_pass = {}
    for i, p in enumerate(points):
        others = [n[k] for k in range(len(n)) if k != i and w[k] != 0]
        if w[i] != 0 and others:
            r = common_roots(others, lo, hi)
            if r:
                want_pass[str(p)] = r
    got_pass = {ps['point']: ps['t'] for ps in o['passes']}
    if set(got_pass) != set(want_pass) or any(
            not same_roots(got_pass[q], want_pass[q]) for q in want_pass):
        errs.append(f"passes {got_pass} != {want_pass}")
    ends = [lo, hi] if rng else []
    for e, je in zip(ends, o['ends']):
        first, k, T = smoothness(w, e, deg)
        Tj = [as_value(je['derivative'].get(str(p), '0')) for p in points]
        if je['derivative_order'] != first or any(
                sp.simplify(a - b) != 0 for a, b in zip(Tj, T)):
            errs.append(f"t = {e}: derivative {je['derivative']} != {T}")
        if je['smoothness'] != k:
            errs.append(f"t = {e}: smoothness {je['smoothness']} != {k}")
        if smooth is not None and k != smooth:
            errs.append(f"t = {e}: the book's smoothness {smooth}, found {k}")
    for dn, want in (defs or {}).items():
        got = next(d['poles'] for d in j['definitions'] if d['name'] == dn)
        if not same_roots(got, want):
            errs.append(f"definition {dn}: poles {got} != {want}")
    print(f"{label}: {'agrees' if not errs else 'DIFFERS: ' + '; '.join(errs)}")
    return not errs


def check_metric(label, path, name, expr, coords, rng):
    """--at: the curvature at the ends (exact, then float), its largest and
    smallest value (mpmath: a dense grid, then findroot on kappa'), the arc
    length (mpmath.quad at 30 digits)"""
    import mpmath
    mpmath.mp.dps = 30
    cmd = [PC, 'analyze', path, '--format', 'json', '--output', name]
    for p, xy in coords.items():
        cmd += ['--at', f"{p}={','.join(str(v) for v in xy)}"]
    o = json.loads(subprocess.run(cmd, capture_output=True, text=True,
                                  check=True).stdout)['outputs'][0]
    e = sp.expand(expr)
    X = [sum(sp.together(e.coeff(sp.Symbol(p))) * xy[k]
             for p, xy in coords.items()) for k in range(len(next(iter(coords.values()))))]
    d1 = [sp.diff(x, t) for x in X]
    d2 = [sp.diff(x, t, 2) for x in X]
    sq = sum(a * a for a in d1)
    cross = sum((d1[a] * d2[b] - d1[b] * d2[a])**2
                for a in range(len(X)) for b in range(a + 1, len(X)))
    kappa = sp.sqrt(cross) / sq**sp.Rational(3, 2)
    errs = []
    lo, hi = rng
    for k, end in enumerate((lo, hi)):
        want = float(sp.simplify(kappa.subs(t, end)))
        if abs(o['curvature_ends'][k] - want) > 1e-12 * max(1, want):
            errs.append(f"curvature at {end}: {o['curvature_ends'][k]} != {want}")
    f = sp.lambdify(t, kappa, 'mpmath')
    grid = [lo + (hi - lo) * mpmath.mpf(i) / 4000 for i in range(4001)]
    vals = [f(g) for g in grid]
    imax = max(range(len(vals)), key=lambda i: vals[i])
    fd = sp.lambdify(t, sp.diff(sq**3 / cross, t), 'mpmath')  # kappa^-2
    tmax = grid[imax] if imax in (0, 4000) else mpmath.findroot(fd, grid[imax])
    if abs(o['curvature_max'] - float(f(tmax))) > 1e-12 * float(f(tmax)):
        errs.append(f"largest curvature {o['curvature_max']} != {f(tmax)}")
    speed = sp.lambdify(t, sp.sqrt(sq), 'mpmath')
    L = mpmath.quad(speed, [lo, hi])
    if abs(o['arc_length'] - float(L)) > 1e-12 * float(L):
        errs.append(f"arc length {o['arc_length']} != {L}")
    print(f"{label}: {'agrees' if not errs else 'DIFFERS: ' + '; '.join(errs)}")
    return not errs


def main():
    A, B, C, D, K = sp.symbols('A B C D K')
    ok = True
    den = 2 * t**2 - 2 * t + 1
    # Desargues arc, monograph 3.7 (3.6); T and S have the pole t = 1/2
    M = (A * tb**3 + B * t**2 * tb + C * t * tb**2 + D * t**3) / den
    half = [sp.Rational(1, 2)]
    ok &= check('desargues M', 'examples/desargues_arc.pcs', 'M', M,
                [A, B, C, D], (0, 1), plane=False, smooth=1,
                defs={'T': half, 'S': half, 'R': half, 'M': []})
    ok &= check('desargues M_CB (C = B)', 'examples/desargues_arc.pcs',
                'M_CB', M.subs(C, B), [A, B, D], (0, 1))
    ok &= check('desargues M_AD (A = D)', 'examples/desargues_arc.pcs',
                'M_AD', M.subs(A, D), [B, C, D], (0, 1))
    # the contour arcs of smoothness order k (3.6), solved again
    for k in range(2, 6):
        ok &= check(f'contour arc k = {k}', 'examples/contour_arcs.pcs', 'M',
                    contour(k, A, B, C), [A, B, C], (0, 1),
                    defines=[f'k={k}'], smooth=k)
    # the redundant parametrizations (the conic traced twice)
    ok &= check('parabola through A, K, B (interpolation_conic)',
                'examples/interpolation_conic.pcs', 'M_parabola',
                (A - K) * tb * (1 - 2 * t) + (B - K) * t * (2 * t - 1) + K,
                [A, K, B], (0, 1))
    # the closed "cubic" arcs of 3.5 (scheme No. 1, table 3.2: kP = 0.8,
    # kQ = 0.5), the printed M1: of order 5, not 3
    kP, kQ = sp.Rational(4, 5), sp.Rational(1, 2)
    dP = kP * (1 - 2 * t)**2 + 2 * t * tb
    dQ = kQ * (1 - 2 * t)**2 + 2 * t * tb
    M1c = ((A - C) * (kP * t**2 * tb / dP + kQ * tb**2 * t / dQ) +
           (B - C) * (kP * tb**3 / dP + kQ * t**3 / dQ) + C)
    ok &= check('closed cubic No. 1, kP = 0.8, kQ = 0.5 (3.5)',
                'examples/closed_cubics.pcs', 'M1', M1c, [A, B, C], (0, 1),
                sets=['kP=0.8', 'kQ=0.5'])
    ok &= check_metric('desargues M --at (plane coordinates)',
                       'examples/desargues_arc.pcs', 'M', M,
                       {'A': (0, 0), 'B': (1, 0), 'C': (1, 1), 'D': (0, 1)},
                       (0, 1))
    ok &= check_metric('desargues M --at (space coordinates)',
                       'examples/desargues_arc.pcs', 'M', M,
                       {'A': (0, 0, 0), 'B': (1, 0, 0), 'C': (1, 1, 0),
                        'D': (0, 1, 1)}, (0, 1))
    M1, M2, M3, M4, M5, M6 = sp.symbols('M_1:7')
    nodes = [M1, M2, M3, M4, M5, M6]
    lag = sum(nodes[i] * sp.prod([(5 * t - j) / (i - j) for j in range(6) if j != i])
              for i in range(6))
    ok &= check('interpolation curve n = 5 (4.8)',
                'examples/interpolation_bezier.pcs', 'X', lag, nodes, (0, 1))
    # not from the book: poles, stop points and inflections at irrational
    # values (quadratic: sqrt forms; cubic: isolated)
    src = ('point A, B, C\nparam t in [-3, 3]\n'
           'Q = (A*(t^3 - t^2) + B*(1 - 3*t) + C*t^2)/(t^3 - 3*t + 1)\n'
           'R = (A*t^4 + B*(2 - 3*t^2) + C*(t - 1))/(t^4 - 3*t^2 + t + 1)\n'
           'output Q, R\n')
    with tempfile.NamedTemporaryFile('w', suffix='.pcs', delete=False) as f:
        f.write(src)
    try:
        ok &= check('poles at the roots of t^3 - 3t + 1', f.name, 'Q',
                    (A * (t**3 - t**2) + B * (1 - 3 * t) + C * t**2) /
                    (t**3 - 3 * t + 1), [A, B, C], (-3, 3))
        ok &= check('a quartic curve', f.name, 'R',
                    (A * t**4 + B * (2 - 3 * t**2) + C * (t - 1)) /
                    (t**4 - 3 * t**2 + t + 1), [A, B, C], (-3, 3))
    finally:
        os.unlink(f.name)
    print(f"analyze: {'all curves agree' if ok else 'some DIFFER'}")
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
