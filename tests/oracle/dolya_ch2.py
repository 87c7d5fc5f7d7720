#!/usr/bin/env python3
"""dolya_ch2.py - an independent SymPy derivation of every worked example of
chapter 2 of the composite-curve text (seeds/dolya-composite-curves.txt,
P. G. Dolya, "Параметрические уравнения составных кривых").

For each example the curve is built twice, the way the theorem says:
  * piecewise: the segments R_k(tau) re-parametrised to their knot intervals
    [t_{k-1}, t_k] (plus the constant ends or the rays outside [t0, tn]);
  * as one formula with Abs: Theorem 1 of 2.1 (formula (2), the ramp P),
    Theorem 2 (the C^1 / C^2 steps P_1^3, P_2^5), Theorem 3 (rays Q, Ql),
    formula (1) of 2.2, Theorem 1 of 2.3.1 ((5)-(6)), the Bezier formulas
    (9)-(11) of 2.3.3, the spline formula (2) of 2.3.4.
The one formula must equal the piecewise curve on every piece: symbolically
(every |t - c| replaced by +-(t - c) with the sign it has on the piece, then
the difference simplified to 0) and at rational sample points (exact values,
Abs evaluated by SymPy).  Then the text's printed formula is compared with
the derivation on every interval between its breakpoints (so two formulas
count as equal only if they agree for every real t), and one-sided
derivatives at the knots give the continuity order C^k that the text claims.

Prints one line per check (OK / MISPRINT / FAIL), then a table: example,
printed formula correct?, the correct formula.  Exits 1 on a FAIL (a
derivation that does not hold); a MISPRINT is an expected verdict, recorded
in docs/errata.md (entries D1-D9).

Then every example scheme examples/dolya_*.pcs is checked: its
`# expect-weight R.POINT:` lines must equal the weights derived here (the
same theorem constructions, with the base points as symbols), and
pointcalc's own `derive --format json` of R (build/pointcalc, or $PC_BIN)
must equal them on every interval between the knots; `pointcalc eval` of R
must agree with the exact values to 1e-12 at the knots, 1e-7 left and right
of them and at non-dyadic points (also with -D n=8, -D N=5).  With
`--expect NAME` it prints the expectation lines of examples/NAME.pcs from
this derivation instead.

Run from the repository root:  python3 tests/oracle/dolya_ch2.py
"""
import sys
from fractions import Fraction

import sympy as sp
from sympy import Abs, Rational as R, cos, sin, pi, oo, sqrt

t = sp.Symbol('t', real=True)
tau = sp.Symbol('tau', real=True)

FAIL = []
MISPRINTS = []
TABLE = []          # (example, printed ok?, correct formula)
NUMERIC = []        # identities decided by 50-digit coefficients (trig constants)


def line(verdict, label, msg=''):
    print(f"{verdict:8s} {label}{(': ' + msg) if msg else ''}")


def ok(cond, label, msg=''):
    line('OK' if cond else 'FAIL', label, msg)
    if not cond:
        FAIL.append(label)
    return cond


def misprint(label, msg):
    line('MISPRINT', label, msg)
    MISPRINTS.append(label)


# --- the step blocks of the text ------------------------------------------

def P(x, a, w):
    """(2.1.3): the ramp, 0 before a, linear on [a, a + w], 1 after."""
    return (w + Abs(x - a) - Abs(x - a - w)) / (2 * w)


def Q(x, a):
    """(9) of 2.1: the right ray max(x - a, 0)."""
    return (x - a + Abs(x - a)) / 2


def Ql(x, a):
    """(9) of 2.1: the left ray min(x - a, 0)."""
    return (x - a - Abs(x - a)) / 2


def P13(x, a, w):
    """(5) of 2.1: the C^1 step, as printed."""
    return (w**3 + (-2*x + 2*a + 3*w) * (x - a) * Abs(x - a)
            + (2*x - 2*a + w) * (x - a - w) * Abs(x - a - w)) / (2 * w**3)


def P25(x, a, w):
    """(6) of 2.1: the C^2 step, as printed."""
    return (w**5 + (6*x**2 - 3*x*(5*w + 4*a) + 10*w**2 + 15*w*a + 6*a**2) * Abs(x - a)**3
            - (6*x**2 + 3*x*(w - 4*a) + w**2 - 3*w*a + 6*a**2) * Abs(x - a - w)**3) / (2 * w**5)


# the steps on [a, a + w] as polynomials of s = (x - a)/w (the text's piecewise forms)
STEP = {
    'P': lambda s: s,
    'P13': lambda s: 3*s**2 - 2*s**3,
    'P25': lambda s: 10*s**3 - 15*s**4 + 6*s**5,
}
STEPFN = {'P': P, 'P13': P13, 'P25': P25}


# --- evaluating a formula with Abs on one piece ----------------------------

def on_piece(expr, lo, hi, at=None):
    """expr with every Abs(u) replaced by +-u, the sign u has on (lo, hi).
    at: substitutions for symbolic knots used only to decide the signs."""
    at = at or {}
    if lo == -oo:
        mid = hi - 1
    elif hi == oo:
        mid = lo + 1
    else:
        mid = (lo + hi) / 2

    def repl(e):
        u = e.args[0]
        val = u.subs(t, mid).subs(at)
        val = sp.nsimplify(val) if val.is_number else val
        if not val.is_number:
            raise ValueError(f'sign of {u} on ({lo}, {hi}) unknown')
        if val == 0:
            raise ValueError(f'{u} vanishes inside ({lo}, {hi})')
        # the root of a linear u must not lie inside the piece
        roots = sp.solve(u, t)
        for r in roots:
            rv = sp.nsimplify(r.subs(at)) if r.subs(at).is_number else None
            lov = lo if lo == -oo else sp.nsimplify(sp.sympify(lo).subs(at))
            hiv = hi if hi == oo else sp.nsimplify(sp.sympify(hi).subs(at))
            if rv is not None and rv.is_real and lov < rv < hiv:
                raise ValueError(f'{u} changes sign inside ({lo}, {hi})')
        return 1 if val > 0 else -1

    expr = expr.replace(lambda e: isinstance(e, Abs), lambda e: e.args[0] * repl(e))
    # sign(u), as pointcalc's JSON writes |u| inside functions: u*sign(u)
    return expr.replace(lambda e: isinstance(e, sp.sign), repl)


def zero(d):
    """d == 0 exactly (rational functions and trigonometric ones)."""
    d = sp.sympify(d)
    if d == 0:
        return True
    if sp.expand(d) == 0 or sp.cancel(sp.expand(d)) == 0:
        return True
    s = sp.simplify(d)
    if s == 0:
        return True
    s = sp.simplify(sp.expand_trig(sp.expand(d)))
    if s == 0:
        return True
    if sp.trigsimp(sp.expand(sp.expand_trig(d))) == 0:
        return True
    # trigonometric values of rational multiples of pi (the n-gon's vertices)
    # that simplify cannot cancel: every coefficient of the polynomial in the
    # free symbols must vanish to 50 digits (counted in NUMERIC)
    free = sorted(d.free_symbols, key=str)
    try:
        coeffs = sp.Poly(sp.expand(d), *free).coeffs() if free else [d]
    except sp.PolynomialError:
        return False
    if all(numeric_zero(c) for c in coeffs):
        NUMERIC.append(str(d)[:40])
        return True
    return False


def vec(x):
    return list(x) if isinstance(x, (list, tuple, sp.Matrix)) else [x]


def same_vec(a, b):
    return all(zero(p - q) for p, q in zip(vec(a), vec(b)))


def numeric_zero(d, digits=50):
    v = sp.N(d, digits)
    return abs(v) < sp.Float(10) ** (-(digits - 10))


def sample_points(lo, hi):
    if lo == -oo:
        return [hi - R(7, 3), hi - R(1, 5)]
    if hi == oo:
        return [lo + R(1, 7), lo + R(11, 4)]
    return [lo + (hi - lo) * r for r in (R(1, 7), R(1, 2), R(5, 6))]


def check_pieces(label, one, pieces, at=None, samples=True):
    """one: the one formula (list of coordinates); pieces: [(lo, hi, curve)].
    Symbolic check per piece, then exact rational samples (knots included)."""
    good = True
    for lo, hi, cur in pieces:
        on = [on_piece(c, lo, hi, at) for c in vec(one)]
        if not same_vec(on, cur):
            good = False
            ok(False, f'{label}: one formula = piece on ({lo}, {hi})',
               f'{[sp.simplify(a - b) for a, b in zip(on, vec(cur))]}')
        if samples and not at:
            pts = sample_points(lo, hi) + [x for x in (lo, hi) if x not in (-oo, oo)]
            for x in pts:
                for c, p in zip(vec(one), vec(cur)):
                    d = sp.sympify(c).subs(t, x) - sp.sympify(p).subs(t, x)
                    if not (zero(d) or numeric_zero(d)):
                        good = False
                        ok(False, f'{label}: sample t = {x}', str(d))
    ok(good, f'{label}: one formula = piecewise curve',
       f'{len(pieces)} pieces, symbolic{" and rational samples" if samples and not at else ""}')
    return good


def breakpoints(*exprs):
    pts = set()
    for e in exprs:
        for c in vec(e):
            for a in sp.sympify(c).atoms(Abs):
                for r in sp.solve(a.args[0], t):
                    pts.add(r)
    return sorted(pts, key=lambda z: float(z))


def equal_everywhere(a, b, at=None):
    """a == b for every real t: compared on every interval between the
    breakpoints of both (numeric breakpoints)."""
    bp = breakpoints(a, b)
    edges = [-oo] + bp + [oo]
    bad = []
    for lo, hi in zip(edges, edges[1:]):
        pa = [on_piece(c, lo, hi, at) for c in vec(a)]
        pb = [on_piece(c, lo, hi, at) for c in vec(b)]
        if not same_vec(pa, pb):
            bad.append((lo, hi))
    return bad


def equal_on(a, b, lo, hi):
    """a == b on [lo, hi] only (numeric lo, hi)."""
    bp = [x for x in breakpoints(a, b) if lo < x < hi]
    edges = [lo] + bp + [hi]
    bad = []
    for l, h in zip(edges, edges[1:]):
        if not same_vec([on_piece(c, l, h) for c in vec(a)], [on_piece(c, l, h) for c in vec(b)]):
            bad.append((l, h))
    return bad


def compare_printed(label, derived, printed, note_ok='', lo=None, hi=None):
    bad = equal_everywhere(derived, printed) if lo is None else equal_on(derived, printed, lo, hi)
    if not bad:
        line('OK', f'{label}: printed = derived', note_ok)
    return bad


def one_sided(expr, knot, side, order, left_piece, right_piece, at=None):
    """order-th derivative of expr at knot from the left (side=-1) or right (+1)."""
    lo, hi = (left_piece, knot) if side < 0 else (knot, right_piece)
    e = on_piece(expr, lo, hi, at)
    return sp.simplify(sp.diff(e, t, order).subs(t, knot))


def continuity(expr_vec, knot, lo, hi, maxorder=4):
    """(C^k order, jump of the first discontinuous derivative) at knot, from
    one-sided derivatives on (lo, knot) and (knot, hi)."""
    for q in range(0, maxorder + 1):
        jl = [one_sided(c, knot, -1, q, lo, hi) for c in vec(expr_vec)]
        jr = [one_sided(c, knot, +1, q, lo, hi) for c in vec(expr_vec)]
        jump = [sp.simplify(b - a) for a, b in zip(jl, jr)]
        if any(j != 0 for j in jump):
            return q - 1, q, jump, jr
    return maxorder, None, None, None


def pc(e):
    """a scalar in pointcalc syntax (abs, ^)."""
    s = str(e).replace('**', '^').replace('Abs(', 'abs(')
    return s


def abs_form(expr):
    """expr in the text's form: a polynomial plus sum c_k(t) |t - t_k|, a
    coefficient c (t - t_k)^2 written c |t - t_k|^3; pointcalc syntax."""
    e = sp.expand(expr)
    ab = sorted(e.atoms(Abs), key=lambda a: float(sp.solve(a.args[0], t)[0]))
    parts = sp.collect(e, ab, evaluate=False)
    out = []                             # (negative?, text without its sign)
    rest = parts.get(sp.S.One, 0)
    if rest != 0:
        out.append((False, pc(sp.factor(rest))))

    def term(coef, absu):
        if coef.is_number:
            neg = coef < 0
            m = abs(coef)
            return neg, absu if m == 1 else f'{pc(m)}*{absu}'
        neg = sp.factor(coef).could_extract_minus_sign()
        f = sp.factor(-coef if neg else coef)
        return neg, (f'({pc(f)})' if isinstance(f, sp.Add) else pc(f)) + f'*{absu}'

    for a in ab:
        c = sp.factor(parts.get(a, 0))
        if c == 0:
            continue
        u = a.args[0]
        q, r = sp.div(sp.expand(c), sp.expand(u**2), t)
        if r == 0 and not q.has(t):
            out.append(term(q, f'abs({pc(u)})^3'))
        else:
            out.append(term(c, f'abs({pc(u)})'))
    if not out:
        return '0'
    txt = ('-' if out[0][0] else '') + out[0][1]
    for neg, x in out[1:]:
        txt += (' - ' if neg else ' + ') + x
    return txt


# --- the joining theorems of 2.1 ------------------------------------------

def theorem1(segs, knots, step='P'):
    """(2) of 2.1 (step 'P'), (4) with alpha_k = P13 or P25 (Theorem 2).
    segs: [(R(tau) -> list, tau0, tau1)]."""
    f = STEPFN[step]
    R0 = segs[0][0](segs[0][1])
    out = list(R0)
    for k, (Rk, a, b) in enumerate(segs, start=1):
        al = f(t, knots[k - 1], knots[k] - knots[k - 1])
        new = Rk(a + (b - a) * al)
        old = Rk(a)
        out = [o + n - d for o, n, d in zip(out, new, old)]
    return out


def theorem1_pieces(segs, knots, step='P'):
    g = STEP[step]
    pcs = [(-oo, knots[0], segs[0][0](segs[0][1]))]
    for k, (Rk, a, b) in enumerate(segs, start=1):
        s = (t - knots[k - 1]) / (knots[k] - knots[k - 1])
        pcs.append((knots[k - 1], knots[k], Rk(a + (b - a) * g(s))))
    pcs.append((knots[-1], oo, segs[-1][0](segs[-1][2])))
    return pcs


def theorem3(R0, t01, segs, Rn1, tn10, knots):
    """(8) of 2.1: infinite end branches R0 (tau <= t01), Rn1 (tau >= tn10)."""
    out = list(R0(t01 + Ql(t, knots[0])))
    for k, (Rk, a, b) in enumerate(segs, start=1):
        new = Rk(a + (b - a) * P(t, knots[k - 1], knots[k] - knots[k - 1]))
        out = [o + n - d for o, n, d in zip(out, new, Rk(a))]
    out = [o + n - d for o, n, d in zip(out, Rn1(tn10 + Q(t, knots[-1])), Rn1(tn10))]
    return out


def theorem3_pieces(R0, t01, segs, Rn1, tn10, knots):
    pcs = [(-oo, knots[0], R0(t01 + t - knots[0]))]
    for k, (Rk, a, b) in enumerate(segs, start=1):
        pcs.append((knots[k - 1], knots[k], Rk(a + (b - a) * (t - knots[k - 1]) / (knots[k] - knots[k - 1]))))
    pcs.append((knots[-1], oo, Rn1(tn10 + t - knots[-1])))
    return pcs


# --- Theorem 1 of 2.3.1: piecewise-polynomial curves -----------------------

def pp_one_formula(polys, knots):
    """(5)-(6): polys = [(p_k(tau) -> list, tau0, tau1)], knots t_0..t_n.
    Returns the one formula and the re-parametrised pieces (4)."""
    n = len(polys)
    ptil = []
    for k, (pk, a, b) in enumerate(polys, start=1):
        ptil.append(pk(a + (b - a) * (t - knots[k - 1]) / (knots[k] - knots[k - 1])))
    dim = len(ptil[0])
    out = [(ptil[0][j] + ptil[-1][j]) / 2 for j in range(dim)]
    Pk = []
    for k in range(1, n):
        pk, a0, a1 = polys[k - 1]
        pn, b0, b1 = polys[k]
        h = max(sp.degree(sp.expand(c), tau) if sp.expand(c).has(tau) else 0
                for c in pk(tau) + pn(tau))
        coef = []
        for j in range(dim):
            s = 0
            for q in range(1, h + 1):
                dr = sp.diff(pn(tau)[j], tau, q).subs(tau, b0) * (b1 - b0)**q / (knots[k + 1] - knots[k])**q
                dl = sp.diff(pk(tau)[j], tau, q).subs(tau, a1) * (a1 - a0)**q / (knots[k] - knots[k - 1])**q
                s += (dr - dl) / sp.factorial(q) * (t - knots[k])**(q - 1)
            coef.append(sp.expand(s / 2))
        Pk.append(coef)
        out = [o + c * Abs(t - knots[k]) for o, c in zip(out, coef)]
    pieces = [(knots[k - 1], knots[k], ptil[k - 1]) for k in range(1, n + 1)]
    # outside [t0, tn] (5) continues the first and the last polynomial (Remark of 2.3.1)
    pieces = [(-oo, knots[0], ptil[0])] + pieces + [(knots[-1], oo, ptil[-1])]
    return out, pieces, Pk


def fmt(v):
    return '(' + ', '.join(abs_form(c) if sp.sympify(c).atoms(Abs) else pc(sp.factor(c)) for c in vec(v)) + ')'


# ===========================================================================
# 2.1  Composite curves (Theorems 1-3)
# ===========================================================================

def sec_2_1():
    # Example 1: the segment A0 A1
    x0, x1 = sp.symbols('x0 x1', real=True)
    segs = [(lambda s: [x0 + s * (x1 - x0)], 0, 1)]
    one = theorem1(segs, [0, 1])
    check_pieces('2.1 ex.1 segment', one, theorem1_pieces(segs, [0, 1]))
    printed = [x0 + (x1 - x0) * R(1, 2) * (1 + Abs(t) - Abs(t - 1))]
    bad = compare_printed('2.1 ex.1', one, printed)
    TABLE.append(('2.1 ex.1 segment A0A1', not bad, 'A0 + (A1 - A0)(1 + |t| - |t-1|)/2'))

    # Example 2: [0, 1] of the x axis and a quarter circle
    segs = [(lambda s: [s, 0], 0, 1), (lambda s: [cos(pi * s / 2), sin(pi * s / 2)], 0, 1)]
    one = theorem1(segs, [0, 1, 2])
    check_pieces('2.1 ex.2 segment + quarter circle', one, theorem1_pieces(segs, [0, 1, 2]))
    printed = [-1 + P(t, 0, 1) + cos(pi * P(t, 1, 1) / 2), sin(pi * P(t, 1, 1) / 2)]
    bad = compare_printed('2.1 ex.2', one, printed)
    ok(not bad, '2.1 ex.2 printed', str(bad))
    ends = [sp.simplify(c.subs(t, 0)) for c in one], [sp.simplify(c.subs(t, 2)) for c in one]
    line('NOTE', '2.1 ex.2', f'the text calls it "the closed curve", but it runs from {ends[0]} to {ends[1]} '
         '(the text itself says a moment later that it is a curve with ends)')
    TABLE.append(('2.1 ex.2 segment + quarter circle', not bad,
                  '(-1 + P(t,0,1) + cos(pi P(t,1,1)/2), sin(pi P(t,1,1)/2)); not closed (wording)'))

    # Example 3: two elliptic arcs
    a, b, c = sp.symbols('a b c', positive=True)
    segs = [(lambda s: [a * cos(s), b * sin(s)], 0, pi), (lambda s: [a * cos(s), c * sin(s)], pi, 2 * pi)]
    one = theorem1(segs, [0, 1, 2])
    check_pieces('2.1 ex.3 two elliptic arcs', one, theorem1_pieces(segs, [0, 1, 2]))
    printed = [a * (cos(pi * P(t, 0, 1)) - cos(pi * P(t, 1, 1)) + 1),
               b * sin(pi * P(t, 0, 1)) - c * sin(pi * P(t, 1, 1))]
    bad = compare_printed('2.1 ex.3', one, printed)
    ok(not bad, '2.1 ex.3 printed', str(bad))
    ok(same_vec([x.subs(t, 0) for x in one], [x.subs(t, 2) for x in one]), '2.1 ex.3 closed: R(0) = R(2)')
    TABLE.append(('2.1 ex.3 two elliptic arcs', not bad,
                  '(a(cos pi P(t,0,1) - cos pi P(t,1,1) + 1), b sin pi P(t,0,1) - c sin pi P(t,1,1))'))

    # Example 4 (first): the closed space curve of three quarter circles
    h = pi / 2
    segs = [(lambda s: [cos(s), sin(s), 0], 0, h), (lambda s: [0, cos(s), sin(s)], 0, h),
            (lambda s: [sin(s), 0, cos(s)], 0, h)]
    one = theorem1(segs, [0, 1, 2, 3])
    check_pieces('2.1 ex.4 space curve', one, theorem1_pieces(segs, [0, 1, 2, 3]))
    q = pi / 4
    printed = [cos(q * (1 + Abs(t) - Abs(t - 1))) + sin(q * (1 + Abs(t - 2) - Abs(t - 3))),
               -1 + sin(q * (1 + Abs(t) - Abs(t - 1))) + cos(q * (1 + Abs(t - 1) - Abs(t - 2))),
               -1 + sin(q * (1 + Abs(t - 1) - Abs(t - 2))) + cos(q * (1 + Abs(t - 2) - Abs(t - 3)))]
    bad = compare_printed('2.1 ex.4', one, printed)
    ok(not bad, '2.1 ex.4 printed', str(bad))
    TABLE.append(('2.1 ex.4 space curve (3 quarter circles)', not bad,
                  'as printed (cos(pi/4 (1+|t|-|t-1|)) means cos of the product)'))

    # Theorem 2: the steps (5) P_1^3 and (6) P_2^5 as printed
    aa, ww = sp.symbols('a w', real=True)
    at = {aa: R(1, 3), ww: R(5, 2)}
    for name, fn, m in (('P13 (5)', P13, 1), ('P25 (6)', P25, 2)):
        g = STEP[name[:3]]
        pcs = [(-oo, aa, [0]), (aa, aa + ww, [g((t - aa) / ww)]), (aa + ww, oo, [1])]
        check_pieces(f'2.1 Theorem 2 step {name}', [fn(t, aa, ww)], pcs, at=at)
        # C^m and not C^(m+1), at both knots (a = 0, w = 1 and a = -2, w = 3)
        for (a0, w0) in ((0, 1), (-2, 3)):
            e = fn(t, a0, w0)
            for kn in (a0, a0 + w0):
                cm, qq, jump, _ = continuity([e], kn, kn - 1, kn + 1)
                ok(cm == m, f'2.1 step {name} a={a0} w={w0} at t={kn}',
                   f'C^{cm}, jump of derivative {qq}: {jump}')
        TABLE.append((f'2.1 Theorem 2, {name}', True, f'C^{m} step, = piecewise form of the text'))
    # the text's piecewise form of P13: p(t) = -2/w^3 (t-a)^3 + 3/w^2 (t-a)^2
    ok(zero(-2 / ww**3 * (t - aa)**3 + 3 / ww**2 * (t - aa)**2 - STEP['P13']((t - aa) / ww)),
       '2.1 P13 piecewise form as printed')

    # Example 4 (after Theorem 2): the C^1 right triangle O(0,0) A(1,0) B(0,1)
    lin = lambda p0, p1: (lambda s: [p0[0] + (p1[0] - p0[0]) * s, p0[1] + (p1[1] - p0[1]) * s], 0, 1)
    O, A, B, C = (0, 0), (1, 0), (1, 1), (0, 1)
    tri = [lin(O, A), lin(A, (0, 1)), lin((0, 1), O)]
    one = theorem1(tri, [0, 1, 2, 3], 'P13')
    check_pieces('2.1 ex.4 C1 triangle', one, theorem1_pieces(tri, [0, 1, 2, 3], 'P13'))
    printed_steps = [
        R(1, 2) * (1 + (3 - 2 * t) * t * Abs(t) + (2 * t + 1) * (t - 1) * Abs(t - 1)),
        R(1, 2) * (1 + (-2 * t + 5) * (t - 1) * Abs(t - 1) + (2 * t - 1) * (t - 2) * Abs(t - 2)),
        R(1, 2) * (1 + (-2 * t + 7) * (t - 2) * Abs(t - 2) + (2 * t - 3) * (t - 3) * Abs(t - 3))]
    for i, ps in enumerate(printed_steps):
        ok(not equal_everywhere([P13(t, i, 1)], [ps]), f'2.1 ex.4 printed P13(t,{i},1)')
    printed = [R(1, 2) * ((-2 * t + 3) * t * Abs(t) + 4 * (t - 1)**2 * Abs(t - 1) - (2 * t - 1) * (t - 2) * Abs(t - 2)),
               R(1, 2) * ((-2 * t + 5) * (t - 1) * Abs(t - 1) + 4 * (t - 2)**2 * Abs(t - 2) - (2 * t - 3) * (t - 3) * Abs(t - 3))]
    bad = compare_printed('2.1 ex.4 C1 triangle', one, printed)
    ok(not bad, '2.1 ex.4 C1 triangle printed', str(bad))
    for kn in (0, 1, 2, 3):
        cm, qq, jump, _ = continuity(one, kn, kn - R(1, 2), kn + R(1, 2))
        ok(cm == 1, f'2.1 ex.4 C1 triangle at t={kn}', f'C^{cm}, jump of R^({qq}): {jump}')
        ok(all(zero(sp.diff(on_piece(c, kn, kn + R(1, 2)), t).subs(t, kn)) for c in one),
           f'2.1 ex.4 Theorem 2 (ii): R\'({kn}) = 0')
    TABLE.append(('2.1 ex.4 C^1 triangle (Theorem 2)', not bad,
                  'x = ((3-2t)t|t| + 4(t-1)^2|t-1| - (2t-1)(t-2)|t-2|)/2, y likewise; C^1, R\'=0 at knots'))

    # Example 5: the C^2 square O A B C
    sq = [lin(O, A), lin(A, B), lin(B, C), lin(C, O)]
    one = theorem1(sq, [0, 1, 2, 3, 4], 'P25')
    check_pieces('2.1 ex.5 C2 square', one, theorem1_pieces(sq, [0, 1, 2, 3, 4], 'P25'))
    ok(not equal_everywhere(one, [P25(t, 0, 1) - P25(t, 2, 1), P25(t, 1, 1) - P25(t, 3, 1)]),
       '2.1 ex.5 = (P25(t,0,1) - P25(t,2,1), P25(t,1,1) - P25(t,3,1)) as the text says')
    printed = [R(1, 2) * ((6 * t**2 - 15 * t + 10) * Abs(t)**3 - (6 * t**2 + 3 * t + 1) * Abs(t - 1)**3
                          - (6 * t**2 - 39 * t + 64) * Abs(t - 2)**3 + (6 * t**2 - 21 * t + 19) * Abs(t - 3)**3),
               R(1, 2) * ((6 * t**2 - 27 * t + 31) * Abs(t - 1)**3 - (6 * t**2 - 9 * t + 4) * Abs(t - 2)**3
                          - (6 * t**2 - 51 * t + 109) * Abs(t - 3)**3 + (6 * t**2 - 33 * t + 46) * Abs(t - 4)**3)]
    bad = compare_printed('2.1 ex.5 C2 square', one, printed)
    ok(not bad, '2.1 ex.5 C2 square printed', str(bad))
    for kn in range(5):
        cm, qq, jump, _ = continuity(one, kn, kn - R(1, 2), kn + R(1, 2))
        ok(cm == 2, f'2.1 ex.5 C2 square at t={kn}', f'C^{cm}, jump of R^({qq}): {jump}')
    TABLE.append(('2.1 ex.5 C^2 square (Theorem 2)', not bad, 'as printed; C^2, R\'=R\'\'=0 at knots'))

    # Theorem 3, example 4: the infinite curve with a sine wave
    R0 = lambda s: [s, pi * s]
    R1 = lambda s: [s, sin(pi * s)]
    R2 = lambda s: [s + 2, pi * s]
    one = theorem3(R0, 0, [(R1, 0, 2)], R2, 0, [0, 2])
    check_pieces('2.1 Th.3 ex.4 sine with rays', one, theorem3_pieces(R0, 0, [(R1, 0, 2)], R2, 0, [0, 2]))
    mid = [Ql(t, 0) + 2 * P(t, 0, 2) + Q(t, 2), pi * Ql(t, 0) + sin(2 * pi * P(t, 0, 2)) + pi * Q(t, 2)]
    ok(not equal_everywhere(one, mid), '2.1 Th.3 ex.4 printed intermediate form')
    printed = [t, pi * (t - 1) + pi / 2 * (Abs(t - 2) - Abs(t)) + sin(pi * (Abs(t - 2) - Abs(t)) / 2)]
    bad = compare_printed('2.1 Th.3 ex.4', one, printed)
    ok(not bad, '2.1 Th.3 ex.4 printed', str(bad))
    for kn in (0, 2):
        cm, qq, jump, _ = continuity(one, kn, kn - 1, kn + 1)
        line('NOTE', f'2.1 Th.3 ex.4 at t={kn}', f'C^{cm} (jump of R^({qq}): {jump}): the sine meets the rays C^2')
    TABLE.append(('2.1 Th.3 ex.4 sine wave with rays', not bad,
                  'x = t, y = pi(t-1) + pi(|t-2|-|t|)/2 + sin(pi(|t-2|-|t|)/2)'))

    # Theorem 3, example 5: parabola branches and a segment
    R0 = lambda s: [s, s**2 - 1]
    R1 = lambda s: [-2 - s, 0]
    R2 = lambda s: [s - 4, s**2 - 1]
    one = theorem3(R0, -1, [(R1, -1, 1)], R2, 1, [-1, 1])
    check_pieces('2.1 Th.3 ex.5 parabola branches', one, theorem3_pieces(R0, -1, [(R1, -1, 1)], R2, 1, [-1, 1]))
    mid = [-1 + Ql(t, -1) - 2 * P(t, -1, 2) + Q(t, 1), -2 * (Ql(t, -1) - Q(t, 1)) + Ql(t, -1)**2 + Q(t, 1)**2]
    ok(not equal_everywhere(one, mid), '2.1 Th.3 ex.5 printed intermediate form')
    printed = [-2 + t - Abs(t + 1) + Abs(t - 1),
               t**2 - 1 + R(1, 2) * (t + 1) * Abs(t - 1) + R(1, 2) * (1 - t) * Abs(t + 1)]
    bad = compare_printed('2.1 Th.3 ex.5', one, printed)
    ok(not bad, '2.1 Th.3 ex.5 printed', str(bad))
    TABLE.append(('2.1 Th.3 ex.5 parabola branches + segment', not bad,
                  'x = -2 + t - |t+1| + |t-1|, y = t^2 - 1 + (t+1)|t-1|/2 + (1-t)|t+1|/2'))


# ===========================================================================
# 2.2  Polylines
# ===========================================================================

def polyline_rays(pts, vl, vr, knots):
    """(1) of 2.2."""
    dim = len(pts[0])
    out = [pts[0][j] + vl[j] * Ql(t, knots[0]) + vr[j] * Q(t, knots[-1]) for j in range(dim)]
    for i in range(1, len(pts)):
        w = P(t, knots[i - 1], knots[i] - knots[i - 1])
        out = [o + (pts[i][j] - pts[i - 1][j]) * w for j, o in enumerate(out)]
    return out


def polyline_pieces(pts, vl, vr, knots):
    dim = len(pts[0])
    pcs = [(-oo, knots[0], [pts[0][j] + vl[j] * (t - knots[0]) for j in range(dim)])]
    for i in range(1, len(pts)):
        s = (t - knots[i - 1]) / (knots[i] - knots[i - 1])
        pcs.append((knots[i - 1], knots[i], [pts[i - 1][j] + (pts[i][j] - pts[i - 1][j]) * s for j in range(dim)]))
    pcs.append((knots[-1], oo, [pts[-1][j] + vr[j] * (t - knots[-1]) for j in range(dim)]))
    return pcs


def ngon_correct(n, Rr):
    """the closed polyline through r_i = R(cos 2 pi i/n, sin 2 pi i/n), t_i = i."""
    pts = [[Rr * cos(2 * pi * i / n), Rr * sin(2 * pi * i / n)] for i in range(n)] + [[Rr, 0]]
    return polyline_rays(pts, [0, 0], [0, 0], list(range(n + 1))), pts


def ngon_printed(n, Rr):
    s = sin(pi / n)
    x = Rr - 2 * Rr * s * sum(P(t, i, i + 1) * sin((2 * i + 1) * pi / n) for i in range(n + 1))
    y = 2 * Rr * s * sum(P(t, i, i + 1) * cos((2 * i + 1) * pi / n) for i in range(n + 1))
    return [x, y]


def ngon_fixed_ramps(n, Rr):
    """(2) with P(t, i, 1) and i = 0..n-1: the correction."""
    s = sin(pi / n)
    x = Rr - 2 * Rr * s * sum(P(t, i, 1) * sin((2 * i + 1) * pi / n) for i in range(n))
    y = 2 * Rr * s * sum(P(t, i, 1) * cos((2 * i + 1) * pi / n) for i in range(n))
    return [x, y]


def ngon_collected(n, Rr):
    """the same collected by |t - k| (derived below, checked for each n):
    x = R - R sin^2(pi/n)(|t| + |t-n|) - 2R sin^2(pi/n) sum_{k=1}^{n-1} cos(2 pi k/n)|t-k|
    y = R sin(pi/n) cos(pi/n)(|t| - |t-n|) - 2R sin^2(pi/n) sum_{k=1}^{n-1} sin(2 pi k/n)|t-k|"""
    s2 = sin(pi / n)**2
    x = Rr - Rr * s2 * (Abs(t) + Abs(t - n)) - 2 * Rr * s2 * sum(cos(2 * pi * k / n) * Abs(t - k) for k in range(1, n))
    y = Rr * sin(pi / n) * cos(pi / n) * (Abs(t) - Abs(t - n)) - 2 * Rr * s2 * sum(
        sin(2 * pi * k / n) * Abs(t - k) for k in range(1, n))
    return [x, y]


def sec_2_2():
    # formula (1) in general: 3 segments, symbolic points, rays and knots
    X = sp.symbols('r0:4', real=True)
    vl, vr = sp.symbols('vl vr', real=True)
    T = sp.symbols('t0:4', real=True)
    at = {T[0]: 0, T[1]: R(1, 2), T[2]: 2, T[3]: 3}
    pts = [[x] for x in X]
    one = polyline_rays(pts, [vl], [vr], list(T))
    check_pieces('2.2 (1) polyline with end rays, symbolic', one, polyline_pieces(pts, [vl], [vr], list(T)), at=at)
    TABLE.append(('2.2 (1) polyline with rays', True,
                  'r0 + vl Ql(t,t0) + sum (r_i - r_{i-1}) P(t,t_{i-1},t_i - t_{i-1}) + vr Q(t,tn)'))

    # Example 1: the square
    sq = [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]
    one = polyline_rays(sq, [0, 0], [0, 0], [0, 1, 2, 3, 4])
    check_pieces('2.2 ex.1 square', one, polyline_pieces(sq, [0, 0], [0, 0], [0, 1, 2, 3, 4]))
    printed = [R(1, 2) * (Abs(t) - Abs(t - 1) - Abs(t - 2) + Abs(t - 3)),
               R(1, 2) * (Abs(t - 1) - Abs(t - 2) - Abs(t - 3) + Abs(t - 4))]
    bad = compare_printed('2.2 ex.1 square', one, printed)
    ok(not bad, '2.2 ex.1 square printed', str(bad))
    TABLE.append(('2.2 ex.1 square', not bad, '(|t|-|t-1|-|t-2|+|t-3|, |t-1|-|t-2|-|t-3|+|t-4|)/2'))

    # Example 1, second form: ray along OX into A(1,0), AB, BC, ray from C down OY
    pts = [[1, 0], [1, 1], [0, 1]]
    one = polyline_rays(pts, [1, 0], [0, -1], [1, 2, 3])
    check_pieces('2.2 ex.1 square with rays', one, polyline_pieces(pts, [1, 0], [0, -1], [1, 2, 3]))
    printed = [R(1, 2) * (t - Abs(t - 1) - Abs(t - 2) + Abs(t - 3)),
               R(1, 2) * (4 - t + Abs(t - 1) - Abs(t - 2) - Abs(t - 3))]
    bad = compare_printed('2.2 ex.1 square with rays', one, printed)
    ok(not bad, '2.2 ex.1 square with rays printed', str(bad))
    sqpc = polyline_pieces(sq, [0, 0], [0, 0], [0, 1, 2, 3, 4])[1:-1]
    ok(all(same_vec([on_piece(c, lo, hi) for c in one], cur) for lo, hi, cur in sqpc),
       '2.2 ex.1 the form with rays traces the square on [0, 4]')
    TABLE.append(('2.2 ex.1 square, rays form', not bad, '(t-|t-1|-|t-2|+|t-3|, 4-t+|t-1|-|t-2|-|t-3|)/2'))

    # Example 2: the parallelogram (0,0) (2,0) (3,1) (1,1); knots read off the printed formula
    par = [[0, 0], [2, 0], [3, 1], [1, 1], [0, 0]]
    kn = [0, 2, 3, 5, 6]
    one = polyline_rays(par, [0, 0], [0, 0], kn)
    check_pieces('2.2 ex.2 parallelogram', one, polyline_pieces(par, [0, 0], [0, 0], kn))
    pr1 = [3 * P(t, 0, 3) - 3 * P(t, 3, 3), P(t, 2, 1) - P(t, 5, 1)]
    pr2 = [R(1, 2) * (Abs(t) - 2 * Abs(t - 3) + Abs(t - 6)),
           R(1, 2) * (Abs(t - 2) - Abs(t - 3) - Abs(t - 5) + Abs(t - 6))]
    bad = compare_printed('2.2 ex.2 parallelogram (P form)', one, pr1) + \
        compare_printed('2.2 ex.2 parallelogram (|.| form)', one, pr2)
    ok(not bad, '2.2 ex.2 printed', str(bad))
    line('NOTE', '2.2 ex.2', 'the text does not say its knots; the printed formula has t = 0, 2, 3, 5, 6 '
         '(the vertices (0,0) (2,0) (3,1) (1,1) (0,0))')
    TABLE.append(('2.2 ex.2 parallelogram', not bad, 'as printed, knots t = 0,2,3,5,6 (not stated in the text)'))

    # Example 3: the regular n-gon, formula (2)
    Rr = sp.Symbol('R', positive=True)
    worst = None
    for n in range(3, 9):
        corr, pts = ngon_correct(n, Rr)
        check_pieces(f'2.2 ex.3 {n}-gon (1)', corr, polyline_pieces(pts, [0, 0], [0, 0], list(range(n + 1))),
                     samples=(n <= 4))
        # the edge vector printed before (2)
        for i in range(n):
            ev = [2 * Rr * sin(pi / n) * -sin((2 * i + 1) * pi / n), 2 * Rr * sin(pi / n) * cos((2 * i + 1) * pi / n)]
            if not same_vec(ev, [pts[i + 1][0] - pts[i][0], pts[i + 1][1] - pts[i][1]]):
                ok(False, f'2.2 ex.3 edge vector r_{i + 1} - r_{i}, n = {n}')
        ok(not equal_everywhere(corr, ngon_fixed_ramps(n, Rr)), f'2.2 ex.3 (2) with P(t,i,1), i<n equals (1), n = {n}')
        ok(not equal_everywhere(corr, ngon_collected(n, Rr)), f'2.2 ex.3 collected |t-k| form, n = {n}')
        pr = ngon_printed(n, Rr)
        bad = equal_on(corr, pr, 0, n)
        if bad:
            worst = worst or (n, bad)
            x = R(3, 2)
            misprint(f'2.2 ex.3 (2), n = {n}', f'differs from the polygon on {bad} of [0, {n}]; at t = 3/2 printed '
                     f'{[sp.nsimplify(sp.simplify(c.subs(t, x) / Rr)) for c in pr]} R, polygon '
                     f'{[sp.nsimplify(sp.simplify(c.subs(t, x) / Rr)) for c in corr]} R')
    hexa = [1 + R(1, 4) * (-Abs(t) - Abs(t - 1) + Abs(t - 2) + 2 * Abs(t - 3) + Abs(t - 4) - Abs(t - 5) - Abs(t - 6)),
            sqrt(3) / 4 * (Abs(t) - Abs(t - 1) - Abs(t - 2) + Abs(t - 4) + Abs(t - 5) - Abs(t - 6))]
    bad = compare_printed('2.2 ex.3 hexagon x6, y6', ngon_correct(6, 1)[0], hexa)
    ok(not bad, '2.2 ex.3 hexagon printed = the corrected (2) at n = 6, R = 1', str(bad))
    TABLE.append(('2.2 ex.3 n-gon formula (2)', False,
                  'sum_{i=0}^{n-1} P(t,i,1)...; collected: x = R - R s^2(|t|+|t-n|) - 2R s^2 sum_{k=1}^{n-1} '
                  'cos(2pi k/n)|t-k|, y = R s c(|t|-|t-n|) - 2R s^2 sum sin(2pi k/n)|t-k|, s,c = sin,cos(pi/n)'))
    TABLE.append(('2.2 ex.3 hexagon x6, y6', not bad, 'as printed'))


# ===========================================================================
# 2.3.1  Piecewise-polynomial curves
# ===========================================================================

def sec_2_3_1():
    # Example 1: segment [-1, 1] and the parabola 1 - x^2 over it
    p1 = lambda s: [-1 + s, 0 * s]
    p2 = lambda s: [1 - s, 2 * s - s**2]
    one, pcs, Pk = pp_one_formula([(p1, 0, 2), (p2, 0, 2)], [0, 2, 4])
    check_pieces('2.3.1 ex.1 segment + parabola', one, pcs)
    ok(same_vec(Pk[0], [-1, (4 - t) / 2]), '2.3.1 ex.1 P1(t) = (1/2)(-2, 4 - t) as printed', str(Pk[0]))
    # the printed middle line: 1/2((-1,2)-(1,0)) + 1/2((0,-2)-(0,0))(t-2)
    midline = [R(1, 2) * (-1 - 1) + R(1, 2) * 0 * (t - 2), R(1, 2) * (2 - 0) + R(1, 2) * (-2 - 0) * (t - 2)]
    if not same_vec(midline, Pk[0]):
        misprint('2.3.1 ex.1 P1, middle line', f'1/2(...) + 1/2((0,-2)-(0,0))(t-2) = {fmt(midline)}; '
                 f'the second term needs 1/2 * 1/2 (the 1/2! of (7)): {fmt(Pk[0])}')
    printed = [1 - Abs(t - 2), -t**2 / 2 + 3 * t - 4 + (4 - t) / 2 * Abs(t - 2)]
    bad = compare_printed('2.3.1 ex.1', one, printed)
    ok(not bad, '2.3.1 ex.1 printed', str(bad))
    TABLE.append(('2.3.1 ex.1 segment + parabola', not bad,
                  'x = 1 - |t-2|, y = -t^2/2 + 3t - 4 + (4-t)|t-2|/2 (middle line of P1 misprinted)'))

    # Example 2: parabola x^2, cubics 2 - x^3, 2 + x^3
    p1 = lambda s: [-1 + s, 1 - 2 * s + s**2]
    p2 = lambda s: [1 - s, 2 - (1 - s)**3]
    p3 = lambda s: [-s, 2 - s**3]
    one, pcs, Pk = pp_one_formula([(p1, 0, 2), (p2, 0, 1), (p3, 0, 1)], [0, 2, 3, 4])
    check_pieces('2.3.1 ex.2 parabola + two cubics', one, pcs)
    ok(same_vec(Pk[0], [-1, (t**2 - 8 * t + 13) / 2]), '2.3.1 ex.2 P1 as printed')
    ok(same_vec(Pk[1], [0, -(t - 3)**2]), '2.3.1 ex.2 P2 as printed')
    printed = [1 - Abs(t - 2),
               R(1, 2) * (30 - 29 * t + 10 * t**2 - t**3 + (t**2 - 8 * t + 13) * Abs(t - 2) - 2 * (t - 3)**2 * Abs(t - 3))]
    bad = compare_printed('2.3.1 ex.2', one, printed)
    ok(not bad, '2.3.1 ex.2 printed', str(bad))
    TABLE.append(('2.3.1 ex.2 parabola + two cubics', not bad, 'as printed'))

    # Example 3: formula (8), the polyline with end rays through p0, pn, general knots
    n = 4
    X = sp.symbols(f'r0:{n + 1}', real=True)
    T = sp.symbols(f't0:{n + 1}', real=True)
    at = {T[0]: -1, T[1]: 0, T[2]: R(1, 3), T[3]: 2, T[4]: 5}
    polys = [((lambda i: (lambda s: [X[i - 1] + (X[i] - X[i - 1]) * s]))(i), 0, 1) for i in range(1, n + 1)]
    one, pcs, Pk = pp_one_formula(polys, list(T))
    check_pieces('2.3.1 ex.3 (5)-(6) for a polyline', one, pcs, at=at)
    f8 = R(1, 2) * (X[0] + (X[1] - X[0]) / (T[1] - T[0]) * (t - T[0]) + X[n - 1]
                    + (X[n] - X[n - 1]) / (T[n] - T[n - 1]) * (t - T[n - 1])) + R(1, 2) * sum(
        ((X[i + 1] - X[i]) / (T[i + 1] - T[i]) - (X[i] - X[i - 1]) / (T[i] - T[i - 1])) * Abs(t - T[i])
        for i in range(1, n))
    ok(zero(f8 - one[0]), '2.3.1 ex.3 (8) as printed = (5)-(6)')
    # outside [t0, tn] (8) continues the end segments: rays in the directions r1 - r0, rn - r_{n-1}
    ray = polyline_pieces([[x] for x in X], [(X[1] - X[0]) / (T[1] - T[0])], [(X[n] - X[n - 1]) / (T[n] - T[n - 1])], list(T))
    check_pieces('2.3.1 ex.3 (8) = polyline (1) of 2.2 with the end rays along the end sides', [f8], ray, at=at)
    TABLE.append(('2.3.1 ex.3 polyline formula (8)', True, 'as printed'))

    # Theorem 1 (5)-(6) with general tau intervals (not Corollary 1): example 2 with stretched knots
    p1 = lambda s: [-1 + s, 1 - 2 * s + s**2]
    p2 = lambda s: [1 - s, 2 - (1 - s)**3]
    p3 = lambda s: [-s, 2 - s**3]
    one, pcs, _ = pp_one_formula([(p1, 0, 2), (p2, 0, 1), (p3, 0, 1)], [0, 1, R(5, 2), 4])
    check_pieces('2.3.1 (5)-(6) with t_i - t_{i-1} != tau^1 - tau^0', one, pcs)


# ===========================================================================
# 2.3.2  The composite cubic Hermite curve
# ===========================================================================

def hermite_piece(i, r0, r1, vl, vr):
    """p_i(t) on [i-1, i], as printed (it interpolates, checked below)."""
    return (r0 * (2 * t - 2 * i + 3) * (t - i)**2 + vl * (t - i + 1) * (t - i)**2
            + vr * (t - i) * (t - i + 1)**2 + r1 * (2 * i - 2 * t + 1) * (t - i + 1)**2)


def sec_2_3_2():
    # Example 1: X(t), Y(t) of the five cases
    cases = {1: ((R(1, 2), R(1, 2)), (R(1, 2), -R(1, 2))), 2: ((1, 1), (1, -1)), 3: ((2, 2), (2, -2)),
             4: ((3, 3), (3, -3)), 5: ((4, 4), (4, -4))}
    curves = {}
    for c, (V0, V1) in cases.items():
        X = (t**2 - t) * ((V0[0] + V1[0]) * t - V0[0]) + 3 * t**2 - 2 * t**3
        Y = (t**2 - t) * ((V0[1] + V1[1]) * t - V0[1])
        ok(zero(X.subs(t, 0)) and zero(X.subs(t, 1) - 1) and zero(sp.diff(X, t).subs(t, 0) - V0[0])
           and zero(sp.diff(X, t).subs(t, 1) - V1[0]) and zero(Y.subs(t, 0)) and zero(Y.subs(t, 1))
           and zero(sp.diff(Y, t).subs(t, 0) - V0[1]) and zero(sp.diff(Y, t).subs(t, 1) - V1[1]),
           f'2.3.2 ex.1 case {c}: the cubic interpolates (0,0), (1,0) with V0, V1')
        curves[c] = [sp.expand(X), sp.expand(Y)]
    pr1 = [t, t - t**2]
    if not same_vec(curves[1], pr1):
        which = [c for c in curves if same_vec(curves[c], pr1)]
        misprint('2.3.2 ex.1 "case 1: x = t, y = t - t^2"',
                 f'case 1 (V0 = (1/2,1/2), V1 = (1/2,-1/2)) gives {fmt(curves[1])}; x = t, y = t - t^2 is case {which}')
    ok(same_vec(curves[4], [3 * t - 6 * t**2 + 4 * t**3, 3 * t - 3 * t**2]), '2.3.2 ex.1 case 4 as printed')
    TABLE.append(('2.3.2 ex.1 Hermite cubic, case 1', False,
                  'x = -t^3 + 3t^2/2 + t/2, y = (t - t^2)/2 (the printed x = t, y = t - t^2 is case 2)'))

    # the segment p_i and its derivatives as printed
    i = sp.Symbol('i', integer=True)
    r0, r1, vl, vr = sp.symbols('r_im1 r_i vl_i vr_i', real=True)
    p = hermite_piece(i, r0, r1, vl, vr)
    ok(zero(p.subs(t, i - 1) - r0) and zero(p.subs(t, i) - r1) and zero(sp.diff(p, t).subs(t, i - 1) - vl)
       and zero(sp.diff(p, t).subs(t, i) - vr), '2.3.2 p_i(t): ends r_{i-1}, r_i, tangents v_i^l, v_i^r')
    ok(zero(sp.diff(p, t, 2).subs(t, i - 1) - (-6 * r0 - 4 * vl - 2 * vr + 6 * r1)), "2.3.2 p_i''(i-1) as printed")
    ok(zero(sp.diff(p, t, 2).subs(t, i) - (6 * r0 + 2 * vl + 4 * vr - 6 * r1)), "2.3.2 p_i''(i) as printed")
    ok(zero(sp.diff(p, t, 3) - 6 * (2 * r0 + vl + vr - 2 * r1)), "2.3.2 p_i''' as printed")

    # the joint polynomial P_k, general and with v_{k+1}^l = v_k^r = v_k
    k = sp.Symbol('k', integer=True)
    rm, rk, rp = sp.symbols('r_km1 r_k r_kp1', real=True)
    vlk, vrk, vlp, vrp = sp.symbols('vl_k vr_k vl_kp1 vr_kp1', real=True)
    pk = hermite_piece(k, rm, rk, vlk, vrk)
    pn = hermite_piece(k + 1, rk, rp, vlp, vrp)
    d = [sp.expand(sp.diff(pn, t, q).subs(t, k) - sp.diff(pk, t, q).subs(t, k)) for q in (1, 2, 3)]
    ok(zero(d[0] - (vlp - vrk)), "2.3.2 p'_{k+1}(k) - p'_k(k) as printed")
    ok(zero(d[1] - (6 * rp - 4 * vlp - 2 * vrp - 2 * vlk - 4 * vrk - 6 * rm)), "2.3.2 p''_{k+1}(k) - p''_k(k) as printed")
    ok(zero(d[2] - 6 * (4 * rk - 2 * rp - 2 * rm + vlp + vrp - vlk - vrk)), "2.3.2 p'''_{k+1}(k) - p'''_k(k) as printed")
    Pk_general = sp.expand(R(1, 2) * (d[0] + d[1] / 2 * (t - k) + d[2] / 6 * (t - k)**2))
    vm, vk, vp = sp.symbols('v_km1 v_k v_kp1', real=True)
    same_v = {vlp: vk, vrk: vk, vlk: vm, vrp: vp}
    Pk = sp.expand(Pk_general.subs(same_v))
    printed = (t - k) * (3 * rp - 4 * vk - vp - vm - 3 * rm + 3 * (4 * rk - 2 * rp - 2 * rm + vp - vm) * (t - k))
    correct = (t - k) * (3 * rp - 4 * vk - vp - vm - 3 * rm + (4 * rk - 2 * rp - 2 * rm + vp - vm) * (t - k)) / 2
    ok(zero(Pk - correct), '2.3.2 P_k derived = (t-k)(3r_{k+1} - 4v_k - v_{k+1} - v_{k-1} - 3r_{k-1} '
       '+ (4r_k - 2r_{k+1} - 2r_{k-1} + v_{k+1} - v_{k-1})(t-k))/2')
    if not zero(Pk - printed):
        misprint('2.3.2 P_k', 'printed (t-k)(3r_{k+1} - ... + 3(4r_k - ...)(t-k)) lacks the factor 1/2 and has 3 '
                 'for 1 before the (t-k)^2 term: P_k = (1/2)(p\'\'_{k+1} - p\'\'_k)(t-k)/2 + (1/2)(p\'\'\'_{k+1} - '
                 'p\'\'\'_k)(t-k)^2/6, and 6/12 = 1/2, 6*... /12 = 1/2')

    # the whole curve, n = 3, generic data: one formula = the pieces
    n = 3
    rr = sp.symbols(f'r0:{n + 1}', real=True)
    vv = sp.symbols(f'v0:{n + 1}', real=True)
    pieces = [hermite_piece(j, rr[j - 1], rr[j], vv[j - 1], vv[j]) for j in range(1, n + 1)]
    Pt = (rr[0] * (2 * t + 1) * (t - 1)**2 + vv[0] * t * (t - 1)**2 + vv[1] * t**2 * (t - 1) + rr[1] * (3 - 2 * t) * t**2
          + rr[n - 1] * (2 * t - 2 * n + 3) * (t - n)**2 + vv[n - 1] * (t - n + 1) * (t - n)**2
          + vv[n] * (t - n) * (t - n + 1)**2 + rr[n] * (2 * n + 1 - 2 * t) * (t - n + 1)**2) / 2
    ok(zero(Pt - (pieces[0] + pieces[-1]) / 2), '2.3.2 P(t) = (p_1 + p_n)/2 with v_{n-1} for the printed v_{i-1}')
    one = Pt + sum(correct.subs({k: kk, rm: rr[kk - 1], rk: rr[kk], rp: rr[kk + 1], vm: vv[kk - 1], vk: vv[kk],
                                 vp: vv[kk + 1]}) * Abs(t - kk) for kk in range(1, n))
    pcs = [(-oo, 0, [pieces[0]])] + [(j - 1, j, [pieces[j - 1]]) for j in range(1, n + 1)] + [(n, oo, [pieces[-1]])]
    check_pieces('2.3.2 composite Hermite n = 3 with the corrected P_k', [one], pcs)
    one_pr = Pt + sum(printed.subs({k: kk, rm: rr[kk - 1], rk: rr[kk], rp: rr[kk + 1], vm: vv[kk - 1], vk: vv[kk],
                                    vp: vv[kk + 1]}) * Abs(t - kk) for kk in range(1, n))
    off = [j for j in range(n + 1) if not zero(one_pr.subs(t, j) - rr[j])]
    ok(bool(off), '2.3.2 with the printed P_k the one formula misses the nodes', f't = {off}')
    misprint('2.3.2 P(t)', 'the term v_{i-1}(t-n+1)(t-n)^2 should read v_{n-1}(t-n+1)(t-n)^2')
    for kk in (1, 2):
        cm, qq, jump, _ = continuity([one], kk, kk - R(1, 2), kk + R(1, 2))
        ok(cm == 1, f'2.3.2 Hermite composite at t = {kk}', f'C^{cm}, jump of p\'\' = {sp.factor(jump[0])}')
    TABLE.append(('2.3.2 composite Hermite P_k', False,
                  'P_k = (t-k)(3r_{k+1} - 4v_k - v_{k+1} - v_{k-1} - 3r_{k-1} + (4r_k - 2r_{k+1} - 2r_{k-1} + '
                  'v_{k+1} - v_{k-1})(t-k))/2'))
    TABLE.append(('2.3.2 composite Hermite P(t)', False, 'v_{n-1} for the printed v_{i-1}'))
    TABLE.append(('2.3.2 general P_k (v^l != v^r)', True,
                  '(v^l_{k+1} - v^r_k)/2 + (p\'\'_{k+1}-p\'\'_k)(t-k)/4 + (p\'\'\'_{k+1}-p\'\'\'_k)(t-k)^2/12, '
                  'differences as printed'))


# ===========================================================================
# 2.3.3  Composite Bezier curves
# ===========================================================================

def bern(N, i, s):
    return sp.binomial(N, i) * s**i * (1 - s)**(N - i)


def bezier_composite(polys):
    """(10) of 2.3.3 (with (9)): polys = [[r_0^k, ..., r_N^k]] (each r a list)."""
    n = len(polys)
    N = len(polys[0]) - 1
    dim = len(polys[0][0])
    out = [R(1, 2) * (sum(polys[0][i][j] * bern(N, i, t) for i in range(N + 1))
                      + sum(polys[-1][i][j] * bern(N, i, t + 1 - n) for i in range(N + 1))) for j in range(dim)]
    for k in range(1, n):
        for j in range(dim):
            Pk = R(1, 2) * sum(sp.binomial(N, q) * sum(sp.binomial(q, i) * ((-1)**(q - i) * polys[k][i][j]
                                                                               - (-1)**i * polys[k - 1][N - i][j])
                                                        for i in range(q + 1)) * (t - k)**(q - 1)
                               for q in range(1, N + 1))
            out[j] += Pk * Abs(t - k)
    return out


def bezier_pieces(polys):
    n = len(polys)
    N = len(polys[0]) - 1
    dim = len(polys[0][0])
    seg = [[sum(polys[k][i][j] * bern(N, i, t - k) for i in range(N + 1)) for j in range(dim)] for k in range(n)]
    return [(-oo, 0, seg[0])] + [(k, k + 1, seg[k]) for k in range(n)] + [(n, oo, seg[-1])]


def pt(*a):
    return [sp.nsimplify(x) for x in a]


def sec_2_3_3():
    # (9)-(10) in general: cubic n = 3 and quintic n = 2, symbolic control points (one coordinate)
    for N, n in ((3, 3), (5, 2), (2, 4)):
        syms = [[[sp.Symbol(f'r{i}_{k}', real=True)] for i in range(N + 1)] for k in range(1, n + 1)]
        for k in range(1, n):          # continuity r_N^k = r_0^{k+1}
            syms[k][0] = syms[k - 1][N]
        one = bezier_composite(syms)
        check_pieces(f'2.3.3 (10) N = {N}, n = {n} segments, symbolic', one, bezier_pieces(syms), samples=False)
    TABLE.append(('2.3.3 (9)-(10) composite Bezier, any N', True, 'as printed'))

    # the cubic expansions printed: 2P_k and the smooth-joint form
    r = {(i, s): sp.Symbol(f'r{i}_{s}', real=True) for i in range(4) for s in ('k', 'k1')}
    k = sp.Symbol('k')
    twoPk = 2 * R(1, 2) * sum(sp.binomial(3, q) * sum(sp.binomial(q, i) * ((-1)**(q - i) * r[i, 'k1'] - (-1)**i * r[3 - i, 'k'])
                                                      for i in range(q + 1)) * (t - k)**(q - 1) for q in (1, 2, 3))
    printed = (3 * ((r[1, 'k1'] - r[0, 'k1']) - (r[3, 'k'] - r[2, 'k']))
               + 3 * ((r[2, 'k1'] - 2 * r[1, 'k1'] + r[0, 'k1']) - (r[3, 'k'] - 2 * r[2, 'k'] + r[1, 'k'])) * (t - k)
               + ((r[3, 'k1'] - 3 * r[2, 'k1'] + 3 * r[1, 'k1'] - r[0, 'k1']) - (r[3, 'k'] - 3 * r[2, 'k'] + 3 * r[1, 'k'] - r[0, 'k'])) * (t - k)**2)
    ok(zero(twoPk - printed), '2.3.3 cubic 2P_k as printed')
    smooth = {r[0, 'k1']: r[3, 'k'], r[1, 'k1']: 2 * r[3, 'k'] - r[2, 'k']}
    printed_smooth = (3 * (r[2, 'k1'] - 2 * r[1, 'k1'] + 2 * r[2, 'k'] - r[1, 'k'])
                      + (r[3, 'k1'] - 3 * r[2, 'k1'] + 2 * r[1, 'k1'] + 2 * r[2, 'k'] - 3 * r[1, 'k'] + r[0, 'k']) * (t - k)) * (t - k)
    ok(zero(twoPk.subs(smooth) - printed_smooth.subs(smooth)), '2.3.3 cubic smooth-joint form as printed')

    # Example 1: the polyline (11)
    X = sp.symbols('r0:5', real=True)
    for n in (2, 3, 4):
        polys = [[[X[k]], [X[k + 1]]] for k in range(n)]
        f11 = R(1, 2) * ((1 - t) * X[0] + t * X[1] + (n - t) * X[n - 1] + (t + 1 - n) * X[n]) + R(1, 2) * sum(
            (X[kk + 1] - 2 * X[kk] + X[kk - 1]) * Abs(t - kk) for kk in range(1, n))
        ok(zero(f11 - bezier_composite(polys)[0]), f'2.3.3 (11) = (10) with N = 1, n = {n}')
    pts = [[1, 0], [2, 1], [1, 2], [0, 1]]
    n = 3
    f11 = [R(1, 2) * ((1 - t) * pts[0][j] + t * pts[1][j] + (n - t) * pts[2][j] + (t + 1 - n) * pts[3][j])
           + R(1, 2) * sum((pts[kk + 1][j] - 2 * pts[kk][j] + pts[kk - 1][j]) * Abs(t - kk) for kk in range(1, n))
           for j in range(2)]
    check_pieces('2.3.3 ex.1 polyline (1,0) (2,1) (1,2) (0,1)', f11,
                 bezier_pieces([[pts[k], pts[k + 1]] for k in range(n)]))
    printed = [t - 1 - Abs(t - 1) + Abs(t - 3), 2 - Abs(t - 2)]
    ok(not equal_on(f11, printed, 0, 3), '2.3.3 ex.1 printed = (11) on [0, 3]')
    bad = equal_everywhere(f11, printed)
    if bad:
        misprint('2.3.3 ex.1 polyline', f'(11) gives {fmt([sp.expand(c) for c in f11])}; the printed x = t - 1 - |t-1| + |t-3| '
                 f'agrees on [0, 3] only (differs on {bad}: for t > 3 it gives x = t - 3 instead of 3 - t, '
                 'the continuation of the last side); and the points are labelled r0, r1, r3, r4 for r0, r1, r2, r3')
    TABLE.append(('2.3.3 ex.1 polyline by (11)', False, 'p(t) = (2 - |t-1|, 2 - |t-2|); points r0..r3'))

    # the three closed cubic composites of example 1 (cubic, n = 4)
    middle = [[pt(1, 0), pt(1.5, 0), pt(2, 0.5), pt(2, 1)], [pt(2, 1), pt(2, 1.5), pt(1.5, 2), pt(1, 2)],
              [pt(1, 2), pt(0.5, 2), pt(0, 1.5), pt(0, 1)], [pt(0, 1), pt(0, 0.5), pt(0.5, 0), pt(1, 0)]]
    right = [[pt(1, 0), pt(1.25, 0), pt(2, 0.75), pt(2, 1)], [pt(2, 1), pt(2, 1.25), pt(1.25, 2), pt(1, 2)],
             [pt(1, 2), pt(0.75, 2), pt(0, 1.25), pt(0, 1)], [pt(0, 1), pt(0, 0.75), pt(0.75, 0), pt(1, 0)]]
    # left: the text lists 3 points per polygon; the fourth (the corner repeated) is reconstructed below
    left = [[pt(1, 0), pt(2, 0), pt(2, 0), pt(2, 1)], [pt(2, 1), pt(2, 2), pt(2, 2), pt(1, 2)],
            [pt(1, 2), pt(0, 2), pt(0, 2), pt(0, 1)], [pt(0, 1), pt(0, 0), pt(0, 0), pt(1, 0)]]
    pr_left = [t**3 - 6 * t**2 + 15 * t - 13 - (t - 1)**2 * Abs(t - 1) + 3 * (t - 2) * Abs(t - 2) + (t - 3)**2 * Abs(t - 3),
               6 * t**2 - 24 * t + 32 - 3 * (t - 1) * Abs(t - 1) - (t - 2)**2 * Abs(t - 2) + 3 * (t - 3) * Abs(t - 3)]
    pr_mid = [R(1, 2) * (-t**3 + 6 * t**2 - 21 * t + 28 + (t - 1)**2 * Abs(t - 1) - (t - 3)**2 * Abs(t - 3)),
              R(1, 2) * (-3 * t**2 + 12 * t - 8 + (t - 2)**2 * Abs(t - 2))]
    pr_right = [R(1, 4) * (-5 * t**3 + 30 * t**2 - 93 * t + 110 + 5 * (t - 1)**2 * Abs(t - 1) - 6 * (t - 2) * Abs(t - 2)
                           - 5 * (t - 3)**2 * Abs(t - 3)),
                R(1, 4) * (-21 * t**2 + 84 * t - 88 + 6 * (t - 1) * Abs(t - 1) + 5 * (t - 2)**2 * Abs(t - 2)
                           - 6 * (t - 3) * Abs(t - 3))]
    misprint('2.3.3 cubic composite, left curve: polygons', 'each polygon is printed with three points '
             '((1,0), (2,0), (2,1); (2,1), (2,2), (2,2); ...); the printed curve is the one whose polygons repeat '
             'the corner: (1,0) (2,0) (2,0) (2,1), (2,1) (2,2) (2,2) (1,2), (1,2) (0,2) (0,2) (0,1), '
             '(0,1) (0,0) (0,0) (1,0) (checked below; these are the only cubic Bezier control points of its pieces)')
    for name, polys, pr in (('left', left, pr_left), ('middle', middle, pr_mid), ('right', right, pr_right)):
        one = bezier_composite(polys)
        check_pieces(f'2.3.3 cubic composite, {name} curve', one, bezier_pieces(polys))
        bad = equal_on(one, pr, 0, 4)
        bad_all = equal_everywhere(one, pr)
        for kk in (1, 2, 3):
            cm, qq, jump, _ = continuity(one, kk, kk - R(1, 2), kk + R(1, 2))
            line('NOTE', f'2.3.3 cubic {name} at t = {kk}', f'C^{cm}, jump of p^({qq}) = {jump}')
        if not bad and not bad_all:
            line('OK', f'2.3.3 cubic composite, {name} curve: printed = derived for every t')
            TABLE.append((f'2.3.3 cubic composite, {name} curve', True,
                          'as printed' + ('; the printed polygons lack a point: (2,0),(2,0) etc. doubled' if name == 'left' else '')))
        else:
            # the control points the printed formula implies (its pieces are Bezier cubics)
            implied = []
            for kk in range(4):
                seg = [sp.expand(on_piece(c, kk, kk + 1)) for c in pr]
                s = sp.Symbol('s')
                cps = []
                for c in seg:
                    poly = sp.Poly(sp.expand(c.subs(t, s + kk)), s)
                    # power to Bernstein: b_i = sum_{j<=i} C(i,j)/C(3,j) a_j
                    a = [poly.coeff_monomial(s**j) for j in range(4)]
                    cps.append([sum(sp.binomial(i, j) / sp.binomial(3, j) * a[j] for j in range(i + 1)) for i in range(4)])
                implied.append([(cps[0][i], cps[1][i]) for i in range(4)])
            misprint(f'2.3.3 cubic composite, {name} curve',
                     f'printed formula differs from (10) on {bad or bad_all}; derived x = '
                     f'{abs_form(one[0])}, y = '
                     f'{abs_form(one[1])}; the printed one has '
                     f'the polygons {implied}')
            TABLE.append((f'2.3.3 cubic composite, {name} curve', False, f'{fmt([sp.expand(c) for c in one])}'))

    # Example 2: two quintic segments
    p1 = [pt(i / 5, 0) for i in range(6)]
    p2 = [pt(1, 0), pt(1.2, 0), pt(1.4, 1), pt(-0.4, 1), pt(-0.2, 0), pt(0, 0)]
    p2b = [pt(1, 0), pt(2, 0), pt(3, 2), pt(-2, 2), pt(-1, 0), pt(0, 0)]
    pr_a = [-6 * t**5 + 45 * t**4 - 130 * t**3 + 180 * t**2 - 119 * t + 31 - (t - 1)**2 * (6 * t**2 - 27 * t + 31) * Abs(t - 1),
            5 * t**4 - 30 * t**3 + 65 * t**2 - 60 * t + 20 + 5 * (t - 1) * (t - 2)**2 * Abs(t - 1)]
    pr_b = [-18 * t**5 + 135 * t**4 - 390 * t**3 + 540 * t**2 - 357 * t + 91
            - (18 * t**4 - 117 * t**3 + 273 * t**2 - 267 * t + 91) * Abs(t - 1),
            10 * t**4 - 60 * t**3 + 130 * t**2 - 120 * t + 40 + 10 * (t - 1) * (t - 2)**2 * Abs(t - 1)]
    for name, polys, pr in (('first', [p1, p2], pr_a), ('second', [p1, p2b], pr_b)):
        one = bezier_composite(polys)
        check_pieces(f'2.3.3 ex.2 quintic, {name} polygon', one, bezier_pieces(polys))
        bad = equal_everywhere(one, pr)
        cm, qq, jump, _ = continuity(one, 1, R(1, 2), R(3, 2))
        line('NOTE', f'2.3.3 ex.2 quintic, {name} polygon at t = 1', f'C^{cm}, jump of p^({qq}) = {jump}')
        if not bad:
            line('OK', f'2.3.3 ex.2 quintic, {name} polygon: printed = derived for every t')
        else:
            misprint(f'2.3.3 ex.2 quintic, {name} polygon', f'differs on {bad}; derived '
                     f'{fmt(one)}')
        TABLE.append((f'2.3.3 ex.2 quintic composite, {name} polygon', not bad,
                      'as printed' if not bad else fmt(one)))
    misprint('2.3.3 ex.2 labels', 'the second polygon of the modified curve is labelled {r_i^2}_{i=0}^3 for '
             '{r_i^2}_{i=0}^5 (six points), and "formula (**)" is (10)')


# ===========================================================================
# 2.3.4  Cubic splines
# ===========================================================================

def spline(ys, knots, kind, v0=None, vn=None):
    """the cubic spline through (knots[i], ys[i]) as one formula (1)/(2):
    P3(t) + sum c_i |t - t_i|^3, the coefficients solved exactly.
    kind: natural (S'' = 0 at the ends), clamped (S' = v0, vn), periodic."""
    n = len(knots) - 1
    A = sp.symbols('A0:4')
    c = sp.symbols(f'c1:{n}')
    S = sum(A[j] * t**j for j in range(4)) + sum(c[i - 1] * Abs(t - knots[i])**3 for i in range(1, n))
    eqs = [S.subs(t, knots[i]) - ys[i] for i in range(n + 1)]
    left = on_piece(S, knots[0] - 1, knots[1])
    right = on_piece(S, knots[n - 1], knots[n] + 1)
    d = lambda e, q, x: sp.diff(e, t, q).subs(t, x)
    if kind == 'natural':
        eqs += [d(left, 2, knots[0]), d(right, 2, knots[n])]
    elif kind == 'clamped':
        eqs += [d(left, 1, knots[0]) - v0, d(right, 1, knots[n]) - vn]
    elif kind == 'periodic':
        eqs += [d(left, 1, knots[0]) - d(right, 1, knots[n]), d(left, 2, knots[0]) - d(right, 2, knots[n])]
    sol = sp.solve(eqs, list(A) + list(c), dict=True)
    assert len(sol) == 1
    return sp.expand(S.subs(sol[0])), left.subs(sol[0]), right.subs(sol[0])


def spline_pieces_independent(ys, knots, kind, v0=None, vn=None):
    """the same spline built piece by piece: one cubic per interval, C^2 at the
    inner knots, the end conditions - solved as its own linear system."""
    n = len(knots) - 1
    co = [sp.symbols(f'a{i}_0:4') for i in range(n)]
    pcs = [sum(co[i][j] * (t - knots[i])**j for j in range(4)) for i in range(n)]
    eqs = []
    for i in range(n):
        eqs += [pcs[i].subs(t, knots[i]) - ys[i], pcs[i].subs(t, knots[i + 1]) - ys[i + 1]]
    for i in range(1, n):
        for q in (1, 2):
            eqs.append(sp.diff(pcs[i - 1], t, q).subs(t, knots[i]) - sp.diff(pcs[i], t, q).subs(t, knots[i]))
    d = lambda e, q, x: sp.diff(e, t, q).subs(t, x)
    if kind == 'natural':
        eqs += [d(pcs[0], 2, knots[0]), d(pcs[-1], 2, knots[n])]
    elif kind == 'clamped':
        eqs += [d(pcs[0], 1, knots[0]) - v0, d(pcs[-1], 1, knots[n]) - vn]
    else:
        eqs += [d(pcs[0], 1, knots[0]) - d(pcs[-1], 1, knots[n]), d(pcs[0], 2, knots[0]) - d(pcs[-1], 2, knots[n])]
    sol = sp.solve(eqs, [x for cc in co for x in cc], dict=True)
    assert len(sol) == 1
    return [sp.expand(p.subs(sol[0])) for p in pcs]


SPLINE_PTS = [(5, 0), (0, 5), (5, 10), (10, 5), (5, 0)]
SPLINES = {}


def sec_2_3_4():
    knots = [0, 1, 2, 3, 4]
    xs = [p[0] for p in SPLINE_PTS]
    ys = [p[1] for p in SPLINE_PTS]
    printed = [-60 + R(105, 2) * t - 15 * t**2 + R(5, 2) * t**3 - R(5, 2) * Abs(t - 1)**3 + R(5, 2) * Abs(t - 3)**3,
               -20 + 30 * t - R(15, 2) * t**2 + R(5, 2) * Abs(t - 2)**3]
    verdict = {}
    for kind, ends in (('natural', (None, None)), ('clamped', ((1, 0), (1, 0))), ('periodic', (None, None))):
        one = []
        for j, vals in enumerate((xs, ys)):
            v0 = ends[0][j] if ends[0] else None
            vn = ends[1][j] if ends[1] else None
            S, left, right = spline(vals, knots, kind, v0, vn)
            pcs = spline_pieces_independent(vals, knots, kind, v0, vn)
            check_pieces(f'2.3.4 {kind} spline, {"xy"[j]}', [S],
                         [(knots[i], knots[i + 1], [pcs[i]]) for i in range(4)]
                         + [(-oo, 0, [pcs[0]]), (4, oo, [pcs[-1]])])
            # (2): c_i = (1/12)((M_{i+1} - M_i)/h - (M_i - M_{i-1})/h), M = S'' at the knots; P3 = (p1 + pn)/2
            M = [sp.diff(pcs[min(i, 3)], t, 2).subs(t, knots[i]) for i in range(5)]
            c2 = sum(R(1, 12) * ((M[i + 1] - M[i]) - (M[i] - M[i - 1])) * Abs(t - i)**3 for i in range(1, 4))
            ok(zero(S - (pcs[0] + pcs[-1]) / 2 - c2), f'2.3.4 (2) for the {kind} spline, {"xy"[j]}')
            for kk in (1, 2, 3):
                cm, qq, jump, _ = continuity([S], kk, kk - R(1, 2), kk + R(1, 2))
                ok(cm >= 2, f'2.3.4 {kind} spline {"xy"[j]} at t = {kk}', f'C^{cm}' + (f', jump of S^({qq}) = {jump[0]}' if qq else ''))
            one.append(S)
        SPLINES[kind] = one
        verdict[kind] = not equal_everywhere(one, printed)
        line('NOTE', f'2.3.4 {kind} spline', f'x = {abs_form(one[0])}, '
             f'y = {abs_form(one[1])}; printed formula is this one: {verdict[kind]}')
    ok(verdict['periodic'] and not verdict['clamped'] and not verdict['natural'],
       '2.3.4 the printed spline is the periodic one (not the clamped one with v0 = v4 = (1,0), not the natural one)')
    d0 = [sp.diff(on_piece(c, -1, 1), t).subs(t, 0) for c in printed]
    misprint('2.3.4 ex.1', f'the text announces end vectors v0 = v4 = (1, 0) (clamped) but prints the periodic '
             f'spline: its end tangents are R\'(0) = R\'(4) = {d0}, R\'\'(0) = R\'\'(4); the clamped spline is '
             f'x = {abs_form(SPLINES["clamped"][0])}, '
             f'y = {abs_form(SPLINES["clamped"][1])}')
    TABLE.append(('2.3.4 ex.1 spline (announced clamped, v=(1,0))', False,
                  f'clamped: {fmt(SPLINES["clamped"])}; the printed formula is the periodic spline'))
    TABLE.append(('2.3.4 ex.1 spline, read as periodic', True, 'as printed'))
    TABLE.append(('2.3.4 ex.1 spline, natural (for reference)', None, fmt(SPLINES['natural'])))


# ===========================================================================
# 2.5  Exercises
# ===========================================================================

def sec_2_5():
    lin = lambda p0, p1: (lambda s: [p0[0] + (p1[0] - p0[0]) * s, p0[1] + (p1[1] - p0[1]) * s], 0, 1)
    sq = [lin((0, 0), (1, 0)), lin((1, 0), (1, 1)), lin((1, 1), (0, 1)), lin((0, 1), (0, 0))]
    one = theorem1(sq, [0, 1, 2, 3, 4], 'P13')
    check_pieces('2.5 ex.1 C1 square', one, theorem1_pieces(sq, [0, 1, 2, 3, 4], 'P13'))
    printed = [R(1, 2) * ((-2 * t + 3) * t * Abs(t) + (2 * t + 1) * (t - 1) * Abs(t - 1) + (2 * t - 7) * (t - 2) * Abs(t - 2)
                          - (2 * t - 3) * (t - 3) * Abs(t - 3)),
               R(1, 2) * ((-2 * t + 5) * (t - 1) * Abs(t - 1) + (2 * t - 1) * (t - 2) * Abs(t - 2) + (2 * t - 9) * (t - 3) * Abs(t - 3)
                          - (2 * t - 5) * (t - 4) * Abs(t - 4))]
    bad = compare_printed('2.5 ex.1 C1 square', one, printed)
    ok(not bad, '2.5 ex.1 answer', str(bad))
    for kn in range(5):
        cm, qq, jump, _ = continuity(one, kn, kn - R(1, 2), kn + R(1, 2))
        ok(cm == 1, f'2.5 ex.1 C1 square at t={kn}', f'C^{cm}, jump of R^({qq}): {jump}')
    TABLE.append(('2.5 ex.1 C^1 square', not bad, 'as printed'))

    segs = [(lambda s: [cos(pi * s), sin(pi * s)], 0, 1), (lambda s: [-1 + 2 * s, 0], 0, 1)]
    one = theorem1(segs, [0, 1, 2])
    check_pieces('2.5 ex.2 half-disc boundary', one, theorem1_pieces(segs, [0, 1, 2]))
    printed = [cos(pi * P(t, 0, 1)) + 2 * P(t, 1, 1), sin(pi * P(t, 0, 1))]
    bad = compare_printed('2.5 ex.2 half-disc boundary', one, printed)
    ok(not bad, '2.5 ex.2 solution', str(bad))
    TABLE.append(('2.5 ex.2 half-disc boundary', not bad, 'as printed'))


def table():
    print()
    print('| example | printed correct? | the correct formula |')
    print('|---|---|---|')
    for ex, good, f in TABLE:
        g = 'yes' if good else ('-' if good is None else 'NO')
        print(f'| {ex} | {g} | {f} |')


# ===========================================================================
# The example schemes: their weights, derived here, against their
# expectation lines and against pointcalc's own result
# ===========================================================================

def frame(xy, names=('O', 'X', 'Y', 'Z')):
    """weights of the point with coordinates xy in the frame O, X, Y(, Z):
    O + x (X - O) + y (Y - O) (+ z (Z - O))."""
    w = {names[j + 1]: c for j, c in enumerate(xy)}
    w[names[0]] = 1 - sum(xy)
    return w


def weights_of(curve, syms):
    """weights of a combination of symbolic points (one coordinate each)."""
    e = sp.expand(curve)
    return {str(s): e.coeff(s) for s in syms if e.coeff(s) != 0}


def lin_sym(p0, p1):
    return (lambda s: [p0 + (p1 - p0) * s], 0, 1)


def example_weights():
    """scheme file -> {point: weight of R}, each from the construction of
    the theorem the example uses (independent of the scheme's own text)."""
    W = {}
    A0, A1 = sp.symbols('A0 A1', real=True)
    W['dolya_2_1_ex1'] = weights_of(theorem1([lin_sym(A0, A1)], [0, 1])[0], [A0, A1])
    W['dolya_2_1_ex2'] = frame(theorem1([(lambda s: [s, 0], 0, 1),
                                         (lambda s: [cos(pi * s / 2), sin(pi * s / 2)], 0, 1)], [0, 1, 2]))
    a, b, c = sp.symbols('a b c', positive=True)
    W['dolya_2_1_ex3'] = frame(theorem1([(lambda s: [a * cos(s), b * sin(s)], 0, pi),
                                         (lambda s: [a * cos(s), c * sin(s)], pi, 2 * pi)], [0, 1, 2]))
    h = pi / 2
    W['dolya_2_1_ex4'] = frame(theorem1([(lambda s: [cos(s), sin(s), 0], 0, h), (lambda s: [0, cos(s), sin(s)], 0, h),
                                         (lambda s: [sin(s), 0, cos(s)], 0, h)], [0, 1, 2, 3]))
    O, A, B, C = sp.symbols('O A B C', real=True)
    W['dolya_2_1_ex4_c1_triangle'] = weights_of(
        theorem1([lin_sym(O, A), lin_sym(A, B), lin_sym(B, O)], [0, 1, 2, 3], 'P13')[0], [O, A, B])
    sq = [lin_sym(O, A), lin_sym(A, B), lin_sym(B, C), lin_sym(C, O)]
    W['dolya_2_1_ex5_c2_square'] = weights_of(theorem1(sq, [0, 1, 2, 3, 4], 'P25')[0], [O, A, B, C])
    W['dolya_2_5_ex1'] = weights_of(theorem1(sq, [0, 1, 2, 3, 4], 'P13')[0], [O, A, B, C])
    W['dolya_2_5_ex2'] = frame(theorem1([(lambda s: [cos(pi * s), sin(pi * s)], 0, 1),
                                         (lambda s: [-1 + 2 * s, 0], 0, 1)], [0, 1, 2]))
    W['dolya_2_1_th3_ex4'] = frame(theorem3(lambda s: [s, pi * s], 0, [(lambda s: [s, sin(pi * s)], 0, 2)],
                                            lambda s: [s + 2, pi * s], 0, [0, 2]))
    W['dolya_2_1_th3_ex5'] = frame(theorem3(lambda s: [s, s**2 - 1], -1, [(lambda s: [-2 - s, 0], -1, 1)],
                                            lambda s: [s - 4, s**2 - 1], 1, [-1, 1]))
    W['dolya_2_2_polyline'] = weights_of(polyline_rays([[A], [B], [C]], [A - O], [O - C], [1, 2, 3])[0], [O, A, B, C])
    W['dolya_2_2_parallelogram'] = weights_of(
        polyline_rays([[O], [A], [B], [C], [O]], [0], [0], [0, 2, 3, 5, 6])[0], [O, A, B, C])
    W['dolya_2_2_ngon'] = frame(ngon_correct(6, sp.Symbol('r', positive=True))[0])
    W['dolya_2_3_1_ex1'] = frame(pp_one_formula([(lambda s: [-1 + s, 0 * s], 0, 2),
                                                 (lambda s: [1 - s, 2 * s - s**2], 0, 2)], [0, 2, 4])[0])
    W['dolya_2_3_1_ex2'] = frame(pp_one_formula([(lambda s: [-1 + s, 1 - 2 * s + s**2], 0, 2),
                                                 (lambda s: [1 - s, 2 - (1 - s)**3], 0, 1),
                                                 (lambda s: [-s, 2 - s**3], 0, 1)], [0, 2, 3, 4])[0])
    r = sp.symbols('r_0:4', real=True)
    W['dolya_2_3_1_polyline_knots'] = weights_of(pp_one_formula(
        [((lambda i: (lambda s: [r[i - 1] + (r[i] - r[i - 1]) * s]))(i), 0, 1) for i in (1, 2, 3)],
        [0, 1, 3, 6])[0][0], r)
    # Hermite, n = 3: theorem 1 of 2.3.1 applied to the Hermite pieces (not the text's P_k)
    T = sp.symbols('T_0:4', real=True)
    v = [T[k] - r[k] for k in range(4)]
    s_ = sp.Symbol('s_')
    herm = [((lambda j: (lambda u: [hermite_piece(j, r[j - 1], r[j], v[j - 1], v[j]).subs(t, u + j - 1)]))(j), 0, 1)
            for j in (1, 2, 3)]
    W['dolya_2_3_2_hermite'] = weights_of(pp_one_formula(herm, [0, 1, 2, 3])[0][0], list(r) + list(T))
    f = lambda *xy: [sp.nsimplify(z) for z in xy]
    W['dolya_2_3_3_bezier_cubic'] = frame(bezier_composite(
        [[f(1, 0), f(1.5, 0), f(2, 0.5), f(2, 1)], [f(2, 1), f(2, 1.5), f(1.5, 2), f(1, 2)],
         [f(1, 2), f(0.5, 2), f(0, 1.5), f(0, 1)], [f(0, 1), f(0, 0.5), f(0.5, 0), f(1, 0)]]))
    W['dolya_2_3_3_bezier_quintic'] = frame(bezier_composite(
        [[f(i / 5, 0) for i in range(6)], [f(1, 0), f(1.2, 0), f(1.4, 1), f(-0.4, 1), f(-0.2, 0), f(0, 0)]]))
    Bs = sp.symbols('B_0:7', real=True)
    W['dolya_2_3_3_bezier_composite'] = weights_of(bezier_composite([[[Bs[i]] for i in range(4)],
                                                                     [[Bs[i]] for i in range(3, 7)]])[0], Bs)
    W['dolya_2_3_3_bezier_polyline'] = frame(bezier_composite([[f(1, 0), f(2, 1)], [f(2, 1), f(1, 2)],
                                                               [f(1, 2), f(0, 1)]]))
    for kind in ('natural', 'clamped', 'periodic'):
        if kind not in SPLINES:
            sec_2_3_4()
        W[f'dolya_2_3_4_spline_{kind}'] = frame(SPLINES[kind])
    return W


PARSE = {'t': t, 'pi': pi, 'sin': sin, 'cos': cos, 'sqrt': sqrt, 'abs': Abs, 'Abs': Abs, 'sign': sp.sign,
         'a': sp.Symbol('a', positive=True), 'b': sp.Symbol('b', positive=True),
         'c': sp.Symbol('c', positive=True), 'r': sp.Symbol('r', positive=True)}


def parse(e):
    return sp.sympify(e.replace('^', '**'), locals=PARSE)


def check_examples(root):
    """every examples/dolya_*.pcs: its `# expect-weight R.POINT:` lines equal
    the derived weights for every t (and name every point with a nonzero
    weight); with PC_BIN (make oracle), pointcalc's derive --format json of R
    equals them too."""
    import glob
    import json
    import os
    import subprocess
    W = example_weights()
    pcbin = os.environ.get('PC_BIN') or os.path.join(root, 'build', 'pointcalc')
    files = sorted(glob.glob(os.path.join(root, 'examples', 'dolya_*.pcs')))
    seen = set()
    for path in files:
        name = os.path.basename(path)[:-4]
        seen.add(name)
        if name not in W:
            ok(False, f'{name}: no derivation in dolya_ch2.py')
            continue
        want = W[name]
        exp = {}
        for ln in open(path, encoding='utf-8'):
            if ln.startswith('# expect-weight R.'):
                key, val = ln[len('# expect-weight R.'):].split(':', 1)
                exp[key.strip()] = parse(val.strip())
        bad = [p for p in set(want) | set(exp)
               if equal_everywhere([want.get(p, sp.S.Zero)], [exp.get(p, sp.S.Zero)])]
        ok(not bad and set(exp) == {p for p, w in want.items() if w != 0},
           f'{name}: expect-weight lines = derivation', f'{len(exp)} weights' + (f'; differ: {bad}' if bad else ''))
        if os.access(pcbin, os.X_OK):
            out = subprocess.run([pcbin, 'derive', '--format', 'json', path], capture_output=True, text=True)
            if out.returncode != 0:
                ok(False, f'{name}: pointcalc derive', out.stderr.strip()[:200])
                continue
            js = json.loads(out.stdout)
            terms = next(o for o in js['outputs'] if o['name'] == 'R')['terms']
            got = {k: parse(v) for k, v in terms.items()}
            bad = [p for p in set(want) | set(got)
                   if equal_everywhere([want.get(p, sp.S.Zero)], [got.get(p, sp.S.Zero)])]
            ok(not bad, f'{name}: pointcalc derive = derivation', 'every weight on every interval'
               + (f'; differ: {bad}' if bad else ''))
    missing = sorted(set(W) - seen)
    ok(not missing, 'every derived example has its scheme', str(missing))


EVAL_T = ['-1.5', '-1', '-0.3', '0', '1e-7', '0.3333333333333333', '0.9999999', '1', '1.0000001', '1.7',
          '2', '2.0000001', '2.6666666666666665', '3', '3.0000001', '3.9999999', '4', '4.1', '5', '6', '6.5']
CONSTS = {'a': R(3, 2), 'b': 1, 'c': R(1, 2), 'r': 2}


def coords_for(points):
    """the frame O, X, Y(, Z) where a scheme has one; otherwise fixed
    rational coordinates in the plane."""
    if set(points) <= {'O', 'X', 'Y', 'Z'}:
        dim = 3 if 'Z' in points else 2
        unit = {'O': [0] * dim, 'X': [1, 0, 0][:dim], 'Y': [0, 1, 0][:dim], 'Z': [0, 0, 1]}
        return {p: unit[p] for p in points}
    out = {}
    for k, p in enumerate(sorted(points)):
        out[p] = [R((7 * k + 3) % 11, 3) - 1, R((5 * k + 2) % 13, 4) - 1]
    return out


def eval_check(root, W):
    """pointcalc eval (the runtime) of R against the exact values of the
    derived weights, at the knots, 1e-7 left and right of them and at
    non-dyadic points; the relative error must stay below 1e-12."""
    import csv
    import io
    import os
    import subprocess
    pcbin = os.environ.get('PC_BIN') or os.path.join(root, 'build', 'pointcalc')
    if not os.access(pcbin, os.X_OK):
        line('SKIP', 'eval checks', f'no {pcbin}')
        return
    runs = [(n, [], W[n]) for n in sorted(W)]
    Rr = sp.Symbol('r', positive=True)
    runs.append(('dolya_2_2_ngon', ['-D', 'n=8'], frame(ngon_correct(8, Rr)[0])))
    Bs = sp.symbols('B_0:11', real=True)
    runs.append(('dolya_2_3_3_bezier_composite', ['-D', 'N=5'], weights_of(
        bezier_composite([[[Bs[i]] for i in range(6)], [[Bs[i]] for i in range(5, 11)]])[0], Bs)))
    worst = 0
    for name, extra, w in runs:
        pts = coords_for([p for p, v in w.items() if v != 0])
        cmd = [pcbin, 'eval'] + extra + [os.path.join(root, 'examples', name + '.pcs')]
        for p, xy in pts.items():
            cmd += ['--at', f'{p}=' + ','.join(str(float(z)) for z in xy)]
        for k, v in CONSTS.items():
            if any(sp.Symbol(k, positive=True) in sp.sympify(x).free_symbols for x in w.values()):
                cmd += ['--set', f'{k}={float(v)}']
        cmd += ['--param', 't=' + ','.join(EVAL_T), '--output', 'R', '--format', 'csv']
        out = subprocess.run(cmd, capture_output=True, text=True)
        if out.returncode != 0:
            ok(False, f'{name} {" ".join(extra)}: pointcalc eval', out.stderr.strip()[:300])
            continue
        rows = list(csv.reader(io.StringIO(out.stdout)))[1:]
        err = 0
        subs = {sp.Symbol(k, positive=True): v for k, v in CONSTS.items()}
        for row, ts in zip(rows, EVAL_T):
            tv = sp.Rational(ts)
            dim = len(next(iter(pts.values())))
            for j in range(dim):
                exact = sum(sp.sympify(v).subs(subs).subs(t, tv) * pts[p][j] for p, v in w.items() if v != 0)
                ex = float(sp.N(exact, 30))
                err = max(err, abs(float(row[1 + j]) - ex) / max(1.0, abs(ex)))
        worst = max(worst, err)
        ok(err < 1e-12 and len(rows) == len(EVAL_T), f'{name} {" ".join(extra)}: pointcalc eval = exact',
           f'{len(rows)} values of t (knots, knots +- 1e-7, non-dyadic), max relative error {err:.1e}')
    line('NOTE', 'eval', f'largest relative error over all example schemes {worst:.1e}')


def emit_c_check(root, W):
    """the C that `pointcalc emit-c` writes for R, compiled (cc -std=c99
    -Wall -Wextra -Werror -O2) and run at the same values of t as eval_check,
    against the exact values: relative error below 1e-12."""
    import json
    import os
    import shutil
    import subprocess
    import tempfile
    pcbin = os.environ.get('PC_BIN') or os.path.join(root, 'build', 'pointcalc')
    cc = shutil.which(os.environ.get('CC', 'cc'))
    if not os.access(pcbin, os.X_OK) or not cc:
        line('SKIP', 'emit-c checks', 'no pointcalc or no C compiler')
        return
    Rr = sp.Symbol('r', positive=True)
    Bs = sp.symbols('B_0:11', real=True)
    runs = [(n, [], W[n]) for n in sorted(W)]
    runs.append(('dolya_2_2_ngon', ['-D', 'n=8'], frame(ngon_correct(8, Rr)[0])))
    runs.append(('dolya_2_3_3_bezier_composite', ['-D', 'N=5'], weights_of(
        bezier_composite([[[Bs[i]] for i in range(6)], [[Bs[i]] for i in range(5, 11)]])[0], Bs)))
    subs = {sp.Symbol(k, positive=True): v for k, v in CONSTS.items()}
    worst = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra, w in runs:
            src = os.path.join(root, 'examples', name + '.pcs')
            js = json.loads(subprocess.run([pcbin, 'derive', '--format', 'json'] + extra + [src],
                                           capture_output=True, text=True).stdout)
            pts = coords_for([p for p, v in w.items() if v != 0])
            dim = len(next(iter(pts.values())))
            cfile, hfile, exe = (os.path.join(tmp, name + x) for x in ('.c', '.h', ''))
            r = subprocess.run([pcbin, 'emit-c'] + extra + [src, '-o', cfile, '--header', hfile, '--output', 'R'],
                               capture_output=True, text=True)
            if r.returncode != 0:
                r = subprocess.run([pcbin, 'emit-c'] + extra + [src, '-o', cfile, '--header', hfile],
                                   capture_output=True, text=True)
            if r.returncode != 0:
                ok(False, f'{name}: emit-c', r.stderr.strip()[:200])
                continue
            args = ['ts[i]'] + [repr(float(CONSTS[k])) for k in js['consts']] + js['points']
            drv = [f'#include "{name}.h"', '#include <stdio.h>', 'int main(void)', '{']
            for p in js['points']:
                xy = pts.get(p, [0.0] * dim)
                drv.append(f'    static const double {p}[] = {{{", ".join(repr(float(z)) for z in xy)}}};')
            drv.append(f'    static const double ts[] = {{{", ".join(EVAL_T)}}};')
            drv.append(f'    double out[{dim}];')
            drv.append(f'    for (int i = 0; i < {len(EVAL_T)}; i++) {{')
            drv.append(f'        {js["scheme"]}_R({", ".join(args)}, {dim}, out);')
            drv.append('        printf("' + ' '.join(['%.17g'] * dim) + '\\n", ' + ', '.join(f'out[{j}]' for j in range(dim)) + ');')
            drv += ['    }', '    return 0;', '}']
            with open(os.path.join(tmp, 'main.c'), 'w') as fh:
                fh.write('\n'.join(drv) + '\n')
            r = subprocess.run([cc, '-std=c99', '-Wall', '-Wextra', '-Werror', '-O2', '-I', tmp, '-o', exe,
                                os.path.join(tmp, 'main.c'), cfile, '-lm'], capture_output=True, text=True)
            if r.returncode != 0:
                ok(False, f'{name} {" ".join(extra)}: the generated C compiles', r.stderr.strip()[:300])
                continue
            rows = subprocess.run([exe], capture_output=True, text=True).stdout.split('\n')
            err = 0
            for row, ts in zip(rows, EVAL_T):
                vals = [float(x) for x in row.split()]
                for j in range(dim):
                    exact = sum(sp.sympify(v).subs(subs).subs(t, sp.Rational(ts)) * pts[p][j]
                                for p, v in w.items() if v != 0)
                    ex = float(sp.N(exact, 30))
                    err = max(err, abs(vals[j] - ex) / max(1.0, abs(ex)))
            worst = max(worst, err)
            ok(err < 1e-12, f'{name} {" ".join(extra)}: generated C = exact',
               f'{len(EVAL_T)} values of t, max relative error {err:.1e}')
    line('NOTE', 'emit-c', f'largest relative error over all example schemes {worst:.1e}')


def print_expect(name):
    for p, w in sorted(example_weights()[name].items()):
        if w != 0:
            print(f'# expect-weight R.{p}: {abs_form(w) if sp.sympify(w).atoms(Abs) else pc(sp.factor(w))}')


def main():
    import os
    root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
    if len(sys.argv) == 3 and sys.argv[1] == '--expect':
        import contextlib
        import io
        with contextlib.redirect_stdout(io.StringIO()):
            sec_2_3_4()
        print_expect(sys.argv[2])
        return 0
    sec_2_1()
    sec_2_2()
    sec_2_3_1()
    sec_2_3_2()
    sec_2_3_3()
    sec_2_3_4()
    sec_2_5()
    check_examples(root)
    W = example_weights()
    eval_check(root, W)
    emit_c_check(root, W)
    table()
    print()
    if NUMERIC:
        print(f'{len(NUMERIC)} identities with trigonometric constants decided coefficient-wise to 50 digits')
    print(f'{len(MISPRINTS)} misprints (docs/errata.md D1-D9), {len(FAIL)} failures')
    return 1 if FAIL else 0


if __name__ == '__main__':
    sys.exit(main())
