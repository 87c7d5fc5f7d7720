#!/usr/bin/env python3
"""Checks the monograph's chapter 2.1 parametrizations of the ellipse,
hyperbola and circle against an independent SymPy derivation.

Covered (monograph section, equations):
  2.1.1.1  ellipse by the central angle            (2.6)-(2.11)
  2.1.1.1  ellipse with its axis at an angle θ      K, P, A^, Q (unnumbered)
  2.1.1.2  ellipse by the central radius           (2.12)-(2.15)
  2.1.1.3  ellipse by the angle at a focus          (2.16)-(2.18)
  2.1.1.4  ellipse by compression of a circle       (2.19)-(2.24), linear-parameter form
  2.1.1.5  ellipse by conjugate diameters, var. 1   (2.25)-(2.32)
  2.1.1.6  ellipse by conjugate diameters, var. 2   (2.33)-(2.41), final M
  2.1.2.1  hyperbola by the central angle           (2.44)-(2.49)
  2.1.2.2  hyperbola by the central radius          (2.50)-(2.53)
  2.1.2.3  hyperbola by the angle at a focus        (2.54)-(2.56)
  2.1.8.1  circle by the engineering discriminant   (2.107) with (2.97)
  2.1.8.2  circle by an angular parameter, var. 1   (2.108)-(2.116)
  2.1.8.3  circle by an angular parameter, var. 2   (2.117)-(2.118)

Method.  Where a metric is needed the base points get coordinates (C at the
origin, CA along x; for the ellipse/hyperbola CB along y with |CA| = a,
|CB| = b); the current point is constructed in coordinates from the geometry
(focal definition, polar form, line intersections, rotation) and then
decomposed as M = (A - C) p + (B - C) q + C.  Affine constructions
(conjugate diameters, the 2.1.6 conic) use the base points as unit weight
vectors of the simplex, exactly as the compiler does.  Printed and derived
weights are compared numerically at random parameter values to 30 digits
(trig/sqrt identities make symbolic zero tests slow and brittle); the
derived weights are printed in simplified form.  Then the defining property
is checked numerically: focal sum 2a (ellipse), |d1 - d2| = 2a (hyperbola),
constant distance to the centre (circle); for curves whose axes are not
given, the conic is fitted through sample points and its foci computed.

Prints one line per check: "OK ..." or "MISPRINT ..." (a misprint that was
expected, i.e. confirmed) and exits non-zero if any check FAILs, that is, if
a result differs from the verdicts recorded here (a derived formula that
does not satisfy its defining property, a stated correction that does not
equal the derivation, or a printed formula whose verdict changed).  Lines
starting with REMARK are comments on the text, not checks.  Used for the
expectations of the chapter 2.1 schemes (ellipse_*.pcs, hyperbola_*.pcs,
circle_*.pcs).  Runs in about 10 s.
"""
import random
import sys

import mpmath as mp
import sympy as sp

from verdicts import (R, compare, decompose, fix, misprint, misprints, failures,
                      ndist, npt, num, point_from, remark, report, rnd, same,
                      use_symbols, finish)

random.seed(20240611)

a, b, c, h, R_, lam = sp.symbols('a b c h R lambda', positive=True)
phi, rho, t, v, u, delta, gamma, beta, theta, m, n = sp.symbols(
    'phi rho t v u delta gamma beta theta m n', real=True)
x, y = sp.symbols('x y', real=True)
SYM = {str(z): z for z in (a, b, c, h, R_, lam, phi, rho, t, v, u, delta, gamma, beta, theta, m, n)}
use_symbols(SYM)









def D(base, **kw):
    return fix(dict(base, **kw))















dist = ndist




def fit_conic(pts):
    """Conic through >= 5 numeric points; returns (kind, centre, semi-axis a, foci)
    or for a circle (kind, centre, radius, None).  Checks all points lie on it."""
    rows = [[px * px, px * py, py * py, px, py, 1] for px, py in pts]
    U, S, Vt = mp.svd_r(mp.matrix(rows))        # null vector: last right singular vector
    co = [Vt[5, j] for j in range(6)]
    res = max(abs(sum(co[j] * r[j] for j in range(6))) for r in rows)
    assert res < mp.mpf(10) ** -25, f"points not on one conic (residual {res})"
    Aq, Bq, Cq, Dq, Eq, Fq = co
    Q = mp.matrix([[Aq, Bq / 2], [Bq / 2, Cq]])
    ctr = mp.lu_solve(Q, mp.matrix([-Dq / 2, -Eq / 2]))
    F0 = Fq + (Dq * ctr[0] + Eq * ctr[1]) / 2
    ev, V = mp.eigsy(Q)
    s = [-F0 / ev[i] for i in range(2)]            # squared semi-axes (signed)
    centre = (ctr[0], ctr[1])
    if s[0] > 0 and s[1] > 0:
        if abs(s[0] - s[1]) < mp.mpf(10) ** -25:
            return 'circle', centre, mp.sqrt(s[0]), None
        i = 0 if s[0] > s[1] else 1
        aa, cc = mp.sqrt(s[i]), mp.sqrt(s[i] - s[1 - i])
        kind = 'ellipse'
    else:
        i = 0 if s[0] > 0 else 1
        aa, cc = mp.sqrt(s[i]), mp.sqrt(s[i] - s[1 - i])
        kind = 'hyperbola'
    d = (V[0, i], V[1, i])
    foci = ((ctr[0] + cc * d[0], ctr[1] + cc * d[1]), (ctr[0] - cc * d[0], ctr[1] - cc * d[1]))
    return kind, centre, aa, foci


def prop_check(label, kind, pts, foci=None, a_val=None, centre=None, radius=None):
    """Defining property at numeric points."""
    tol = mp.mpf(10) ** -25
    if kind == 'ellipse':
        vals = [dist(P, foci[0]) + dist(P, foci[1]) for P in pts]
        ok = all(abs(s - 2 * a_val) < tol for s in vals)
        report(ok, label, f"|MF1| + |MF2| = {mp.nstr(vals[0], 12)}, 2a = {mp.nstr(2 * a_val, 12)}"
               f" at {len(pts)} points")
    elif kind == 'hyperbola':
        vals = [abs(dist(P, foci[0]) - dist(P, foci[1])) for P in pts]
        ok = all(abs(s - 2 * a_val) < tol for s in vals)
        report(ok, label, f"||MF1| - |MF2|| = {mp.nstr(vals[0], 12)}, 2a = {mp.nstr(2 * a_val, 12)}"
               f" at {len(pts)} points")
    else:
        vals = [dist(P, centre) for P in pts]
        ok = all(abs(s - radius) < tol for s in vals)
        report(ok, label, f"|MO| = {mp.nstr(vals[0], 12)} = r at {len(pts)} points")
    return ok


def prop_fails(label, kind, pts, foci, a_val, why):
    """The printed (wrong) formula must violate the property: confirms a misprint."""
    if kind == 'ellipse':
        vals = [dist(P, foci[0]) + dist(P, foci[1]) for P in pts]
    else:
        vals = [abs(dist(P, foci[0]) - dist(P, foci[1])) for P in pts]
    bad = [s for s in vals if abs(s - 2 * a_val) > mp.mpf(10) ** -10]
    if bad:
        misprint(label, f"{why}: e.g. {'sum' if kind == 'ellipse' else '|difference|'} = "
                 f"{mp.nstr(bad[0], 12)} instead of 2a = {mp.nstr(2 * a_val, 12)}")
    else:
        report(False, label, "printed formula unexpectedly satisfies the property")


# numeric instances
AB_VALS = {a: R(5), b: R(3)}                      # ellipse a > b
HB_VALS = {a: R(3), b: R(2)}                      # hyperbola


def phis(lo, hi, k=5):
    return [rnd(lo, hi) for _ in range(k)]


# ----------------------------------------------------------------------------
print("== 2.1.1 ellipse: C = (0,0), A = (a,0), B = (0,b), foci F1,2 = C +- (A - C) e (2.5)")
Ce, Ae, Be = (0, 0), (a, 0), (0, b)
ce = sp.sqrt(a**2 - b**2)
F1e, F2e = (ce, 0), (-ce, 0)
ell_samples = [{a: R(5), b: R(3), phi: p} for p in phis(0, 6.28)] + \
              [{a: R(7, 2), b: R(1), phi: p} for p in phis(0, 6.28)]


def ell_points(weights, vals, params):
    return [npt(point_from(weights, Ce, Ae, Be), {**vals, **pp}) for pp in params]


def ell_foci(vals):
    return (npt(F1e, vals), npt(F2e, vals))


# --- 2.1.1.1 central angle: focal definition -> rho ----------------------------
print("-- 2.1.1.1 central angle (2.6)-(2.11)")
d1 = sp.symbols('d1', positive=True)
# cosine theorem in triangles F1CM, F2CM, M = C + rho (cos phi, sin phi)
e26 = sp.Eq(d1**2, ce**2 + rho**2 - 2 * ce * rho * sp.cos(phi))
e27 = sp.Eq((2 * a - d1)**2, ce**2 + rho**2 + 2 * ce * rho * sp.cos(phi))
d1_sol = sp.solve(sp.expand(e27.lhs - e27.rhs - (e26.lhs - e26.rhs)), d1)[0]
compare("(2.9) |F1M|", [(a**2 - ce * rho * sp.cos(phi)) / a], [d1_sol],
        [D(s, rho=R(4)) for s in ell_samples])
rho_sols = sp.solve(sp.Eq(d1_sol**2, e26.rhs), rho)
rho_e = [r for r in rho_sols if sp.N(r.subs({a: 5, b: 3, phi: 0.3})) > 0][0]
rho_e = sp.simplify(rho_e)
rho_210 = a * b / sp.sqrt(a**2 * sp.sin(phi)**2 + b**2 * sp.cos(phi)**2)
compare("(2.10) rho", [rho_210], [rho_e], ell_samples)
M_ca = (rho_e * sp.cos(phi), rho_e * sp.sin(phi))
w_ca = decompose(M_ca, Ce, Ae, Be)
den = sp.sqrt(a**2 * sp.sin(phi)**2 + b**2 * sp.cos(phi)**2)
compare("(2.11) M", [b * sp.cos(phi) / den, a * sp.sin(phi) / den], w_ca, ell_samples)
for vals in ({a: R(5), b: R(3)}, {a: R(7, 2), b: R(1)}):
    prop_check(f"(2.11) focal sum, a={vals[a]}, b={vals[b]}", 'ellipse',
               ell_points(w_ca, vals, [{phi: p} for p in phis(0, 6.28)]), ell_foci(vals), vals[a])

# --- 2.1.1.1 second problem: ellipse with its axis at angle theta to AB ------
print("-- 2.1.1.1 ellipse with its major axis CP at angle theta to AB (K, P, A^, Q)")
# triangle ABC, usual notation: a = |BC|, b = |CA|, c = |AB|, angles alpha, beta, gamma
gam = sp.symbols('gamma_', positive=True)
Ct, At, Bt = (0, 0), (b, 0), (a * sp.cos(gam), a * sp.sin(gam))
tri = {a: R(4), b: R(5), gam: R(11, 10)}      # a generic acute-ish triangle
ct_ = sp.sqrt(a**2 + b**2 - 2 * a * b * sp.cos(gam))
alpha_ = sp.acos((b**2 + ct_**2 - a**2) / (2 * b * ct_))
# K on AB with angle(CK, AB) = theta: K = A + (B - A) s, angle AKC = theta
s_ = sp.symbols('s_')
al_n = sp.N(alpha_.subs(tri), 40)
th_samples = [D(tri, theta=th) for th in [R(3, 2), R(2), R(17, 10)]]   # within (pi-alpha-gamma, pi-alpha)
Kt_num_ok = True
pK, qK, pP, qP, pQ, qQ = [], [], [], [], [], []
for smp in th_samples:
    A_ = npt(At, smp); B_ = npt(Bt, smp)
    th = mp.mpf(sp.N(smp[theta], 40))
    # solve for s: angle between K - C ... direction of ray KC vs KA: angle AKC = theta
    f = lambda ss: mp.acos(((A_[0] - (A_[0] + (B_[0] - A_[0]) * ss)) * (0 - (A_[0] + (B_[0] - A_[0]) * ss))
                            + (A_[1] - (A_[1] + (B_[1] - A_[1]) * ss)) * (0 - (A_[1] + (B_[1] - A_[1]) * ss)))
                           / (dist(A_, (A_[0] + (B_[0] - A_[0]) * ss, A_[1] + (B_[1] - A_[1]) * ss))
                              * dist((0, 0), (A_[0] + (B_[0] - A_[0]) * ss, A_[1] + (B_[1] - A_[1]) * ss)))) - th
    ss = mp.findroot(f, mp.mpf('0.5'))
    K_ = (A_[0] + (B_[0] - A_[0]) * ss, A_[1] + (B_[1] - A_[1]) * ss)
    # weights of K, P = C + m unit(CK), Q = C + n * (CK rotated by +90 deg towards B)
    def w_of(Pt):
        det = A_[0] * B_[1] - A_[1] * B_[0]
        return ((Pt[0] * B_[1] - Pt[1] * B_[0]) / det, (A_[0] * Pt[1] - A_[1] * Pt[0]) / det)
    mm, nn = mp.mpf(3), mp.mpf(2)
    uK = (K_[0] / dist(K_, (0, 0)), K_[1] / dist(K_, (0, 0)))
    P_ = (mm * uK[0], mm * uK[1])
    Q_ = (-nn * uK[1], nn * uK[0])
    for lst, val in zip((pK, qK, pP, qP, pQ, qQ), w_of(K_) + w_of(P_) + w_of(Q_)):
        lst.append(val)
sub = lambda e, smp: mp.mpf(sp.N(e.subs(smp).subs({sp.Symbol('alpha'): al_n}), 40))
al = sp.Symbol('alpha')
printedK = [(sp.sin(theta) - b * sp.sin(al + theta)) / (ct_ * sp.sin(theta)), b * sp.sin(al + theta) / (ct_ * sp.sin(theta))]
correctK = [(ct_ * sp.sin(theta) - b * sp.sin(al + theta)) / (ct_ * sp.sin(theta)), b * sp.sin(al + theta) / (ct_ * sp.sin(theta))]
printedP = [m / sp.sin(al) * (sp.sin(theta) / b - sp.sin(al + theta) / ct_), m * sp.sin(al + theta) / (ct_ * sp.sin(al))]
# A^ printed: (C - A) cos(g+a+th)/sin g + (C - B) b cos(a+th)/(a sin g) + C ; Q = (A^ - C) n / b + C
printedAhat = [-sp.cos(gam + al + theta) / sp.sin(gam), -b * sp.cos(al + theta) / (a * sp.sin(gam))]
printedQ = [n * sp.cos(gam + al + theta) / (b * sp.sin(gam)), -n * sp.cos(al + theta) / (a * sp.sin(gam))]


def close_all(exprs, lists, extra):
    return all(abs(sub(e, {**smp, **extra}) - lst[i]) < mp.mpf(10) ** -25
               for e, lst in zip(exprs, lists) for i, smp in enumerate(th_samples))


if close_all(correctK, (pK, qK), {}) and not close_all(printedK, (pK, qK), {}):
    misprint("2.1.1.1 K (after transformation)",
             "printed A-weight (sin th - b sin(al+th))/(c sin th) is not dimensionless; "
             "correct (c sin th - b sin(al+th))/(c sin th) = 1 - b sin(al+th)/(c sin th), "
             "as in the line before it (lost factor c)")
else:
    report(False, "2.1.1.1 K", "verdict changed")
report(close_all(printedP, (pP, qP), {m: 3}), "2.1.1.1 P = (K - C) m/CK + C", "agrees (CK = b sin al/sin th)")
report(close_all(printedQ, (pQ, qQ), {n: 2}), "2.1.1.1 algorithm step 3, Q", "agrees (CQ = n, CQ perpendicular to CP)")
if not close_all([e * n / b for e in printedAhat], (pQ, qQ), {n: 2}):
    misprint("2.1.1.1 A^ (rotation of CA by omega)",
             "printed (C - A) cos(g+al+th)/sin g + (C - B) b cos(al+th)/(a sin g) + C; the first "
             "term must be (A - C) cos(g+al+th)/sin g: from the book's own S_CA^B/S_ABC = "
             "ab cos(g+al+th)/(ab sin g) = weight of (A - C); step 3 (Q) has the right sign")
else:
    report(False, "2.1.1.1 A^", "verdict changed")

# --- 2.1.1.2 central radius --------------------------------------------------
print("-- 2.1.1.2 central radius (2.12)-(2.15)")
xs = sp.symbols('x_s', positive=True)
x2 = sp.solve(sp.Eq(rho**2 * (a**2 * xs + b**2 * (1 - xs)), a**2 * b**2), xs)[0]   # xs = sin^2
rad_samples = [{a: R(5), b: R(3), rho: rnd(3, 5)} for _ in range(4)] + \
              [{a: R(7, 2), b: R(1), rho: rnd(1, 3.5)} for _ in range(4)]
compare("(2.13) sin^2 phi", [b**2 * (a**2 - rho**2) / (rho**2 * (a**2 - b**2))], [x2], rad_samples)
compare("(2.14) cos^2 phi", [a**2 * (rho**2 - b**2) / (rho**2 * (a**2 - b**2))], [1 - x2], rad_samples)
# independent: the point of the ellipse at distance rho from C in the first quadrant
X2 = sp.solve([x**2 / a**2 + y**2 / b**2 - 1, x**2 + y**2 - rho**2], [x, y], dict=True)
M_cr = [s for s in X2 if sp.N(s[x].subs(rad_samples[0])) > 0 and sp.N(s[y].subs(rad_samples[0])) > 0][0]
w_cr = decompose((M_cr[x], M_cr[y]), Ce, Ae, Be)
compare("(2.15) M", [sp.sqrt(rho**2 - b**2) / sp.sqrt(a**2 - b**2), sp.sqrt(a**2 - rho**2) / sp.sqrt(a**2 - b**2)],
        w_cr, rad_samples)
for vals, lo, hi in (({a: R(5), b: R(3)}, 3, 5), ({a: R(7, 2), b: R(1)}, 1, 3.5)):
    prop_check(f"(2.15) focal sum, a={vals[a]}, b={vals[b]}, rho in [b, a]", 'ellipse',
               ell_points(w_cr, vals, [{rho: rnd(lo, hi)} for _ in range(5)]), ell_foci(vals), vals[a])

# --- 2.1.1.3 angle at the focus F2 ------------------------------------------
print("-- 2.1.1.3 angle at the focus F2 (2.16)-(2.18); phi from the ray F2 A")
e_ = ce / a
p_ = b**2 / a
# independent: M = F2 + r (cos phi, sin phi) on the ellipse, r > 0
r_ = sp.symbols('r_', positive=True)
r_sol = [s for s in sp.solve((F2e[0] + r_ * sp.cos(phi))**2 / a**2 + (r_ * sp.sin(phi))**2 / b**2 - 1, r_)
         if all(sp.N(s.subs(smp)) > 0 for smp in ell_samples[:3])][0]
compare("polar equation rho = |F2M| = p/(1 - e cos phi)", [p_ / (1 - e_ * sp.cos(phi))], [r_sol], ell_samples)
M_fa = (F2e[0] + r_sol * sp.cos(phi), r_sol * sp.sin(phi))
w_217 = decompose(M_fa, F2e, Ae, Be)                    # simplex A B F2
printed_216 = [a * sp.sin(sp.acos(e_) - phi) / ((1 - e_ * sp.cos(phi)) * (a * b + ce * b)),
               p_ * sp.sin(phi) / ((1 - e_ * sp.cos(phi)) * b)]
compare("(2.16) M in simplex A B F2", printed_216, w_217, ell_samples, expect_ok=False,
        why="printed (A - F2) weight a sin(arccos e - phi)/((1 - e cos phi)(ab + cb)) lacks the "
            "factor p = b^2/a (as printed it has the dimension 1/length; the (B - F2) weight has its p): "
            "correct p a sin(arccos e - phi)/((1 - e cos phi)(ab + cb)) = "
            "b(b cos phi - c sin phi)/(a(1 - e cos phi)(a + c)), which is (2.17)",
        correct=[p_ * a * sp.sin(sp.acos(e_) - phi) / ((1 - e_ * sp.cos(phi)) * (a * b + ce * b)), printed_216[1]])
printed_217 = [b * (b * sp.cos(phi) - ce * sp.sin(phi)) / (a * (1 - e_ * sp.cos(phi)) * (a + ce)),
               b * sp.sin(phi) / (a * (1 - e_ * sp.cos(phi)))]
compare("(2.17) M in simplex A B F2", printed_217, w_217, ell_samples)
w_218 = decompose(M_fa, Ce, Ae, Be)
printed_218 = [(a * sp.cos(phi) - ce) / (a - ce * sp.cos(phi)), b * sp.sin(phi) / (a - ce * sp.cos(phi))]
compare("(2.18) M in simplex A B C (F2 from (2.5))", printed_218, w_218, ell_samples)
# the substitution step itself: (2.17) with F2 = C - (A - C) e
p17, q17 = printed_217
sub_218 = [p17 * (1 + e_) + q17 * e_ - e_, q17]
compare("(2.17) + (2.5) -> (2.18)", printed_218, sub_218, ell_samples)
for vals in ({a: R(5), b: R(3)}, {a: R(7, 2), b: R(1)}):
    prop_check(f"(2.18) focal sum, a={vals[a]}, b={vals[b]}", 'ellipse',
               ell_points(w_218, vals, [{phi: p} for p in phis(0, 6.28)]), ell_foci(vals), vals[a])
vals = {a: R(5), b: R(3)}
prop_fails("(2.16) printed, focal sum", 'ellipse',
           [npt(point_from(printed_216, F2e, Ae, Be), D(vals, phi=p)) for p in phis(0.2, 3)],
           ell_foci(vals), vals[a], "the printed (2.16) is not on the ellipse")

# --- 2.1.1.4 compression of a circle ----------------------------------------
print("-- 2.1.1.4 compression of the circle of radius a towards CA (2.19)-(2.24)")
P_c = (a * sp.cos(phi), a * sp.sin(phi))                 # circle of radius a = |CA|
compare("(2.19) P", [sp.cos(phi), a / b * sp.sin(phi)], decompose(P_c, Ce, Ae, Be), ell_samples)
Q_c = (P_c[0], 0)                                         # foot of the perpendicular from P on CA
compare("(2.21) Q", [sp.cos(phi), 0], decompose(Q_c, Ce, Ae, Be), ell_samples)
kk = b / a                                                # (2.22) compression ratio QM/QP
M_c = tuple(Q_c[i] + (P_c[i] - Q_c[i]) * kk for i in range(2))
w_c = decompose(M_c, Ce, Ae, Be)
compare("(2.23)-(2.24) M", [sp.cos(phi), sp.sin(phi)], w_c, ell_samples)
# k = CN/CP: N = the point of the circle of radius b on ray CP; its projection has the height of M
Nn = (b * sp.cos(phi), b * sp.sin(phi))
report(sp.simplify(Nn[1] - M_c[1]) == 0, "(2.22) CN/CP = b/a: N (radius-b circle on ray CP) is level with M")
for vals in ({a: R(5), b: R(3)}, {a: R(7, 2), b: R(1)}):
    prop_check(f"(2.24) focal sum, a={vals[a]}, b={vals[b]}", 'ellipse',
               ell_points(w_c, vals, [{phi: p} for p in phis(0, 6.28)]), ell_foci(vals), vals[a])
# linear parameter: sin phi = t, phi in [-pi/2, pi/2]
w_lin = [sp.simplify(w.subs(phi, sp.asin(t))) for w in w_c]
lin_samples = [{a: R(5), b: R(3), t: rnd(-1, 1)} for _ in range(5)]
compare("linear-parameter form M = (A - C) sqrt(1 - t^2) + (B - C) t + C",
        [sp.sqrt(1 - t**2), t], w_lin, lin_samples)
report(all(w.subs(t, 0) == ww for w, ww in zip(w_lin, (1, 0))) and
       all(w.subs(t, 1) == ww for w, ww in zip(w_lin, (0, 1))),
       "linear form: t = 0 gives A, t = 1 gives B (arc AB); t in [-1, 1]: half on A's side of BC")

# --- 2.1.1.5 conjugate diameters, variant 1 (affine: unit weight vectors) ----
print("-- 2.1.1.5 conjugate diameters, variant 1 (2.25)-(2.32); weights over (A, B, C)")
EA, EB, EC = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])


def along(P, Q, s):
    return P + (Q - P) * s


def meet(P, Q, Rr, S):
    s1, s2 = sp.symbols('s1_ s2_')
    eqs = list(along(P, Q, s1) - along(Rr, S, s2))
    sol = sp.solve(eqs, [s1, s2], dict=True)[0]
    return sp.simplify(along(P, Q, s1).subs(sol))


def rel_C(Mv):
    """(weight of A - C, weight of B - C) when C is the origin: the A and B weights."""
    return [sp.factor(Mv[0]), sp.factor(Mv[1])]


P1 = along(EC, EB, t)                        # (2.26) CP/CB = t
N1 = EA + EB - EC                            # parallelogram CANB
Q1 = along(N1, EB, t)                        # NQ/NB = t
aff_samples = [{t: rnd(-2, 2)} for _ in range(5)]
compare("(2.27)-(2.28) Q", [1 - t, 1], [Q1[0], Q1[1]], aff_samples)
report(sp.simplify(Q1[2] - (t - 1)) == 0, "(2.28) Q: weight of C is t - 1", "agrees")
K1 = 2 * EC - EA
Mv = along(K1, P1, v)                        # (2.29)-(2.30) ray KP
compare("(2.30) ray KP", [v - 1, v * t], [Mv[0], Mv[1]], [D(s, v=rnd(0, 2)) for s in aff_samples])
det = sp.Matrix([list(EA), list(Q1), list(Mv)]).det()
compare("S-theorem determinant 2 - v - vt - vt(t - 1)", [2 - v - v * t - v * t * (t - 1)], [det],
        [D(s, v=rnd(0, 2)) for s in aff_samples])
vs = sp.solve(det, v)[0]
compare("(2.31) v", [2 / (1 + t**2)], [vs], aff_samples)
M1 = meet(K1, P1, Q1, EA)
w_cd1 = rel_C(M1)
compare("(2.32) M", [(1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)], w_cd1, aff_samples)
# property: a non-right angle at C; A - C, B - C conjugate semi-diameters
Cn, An, Bn = (R(1), R(1)), (R(6), R(2)), (R(3), R(4))
pts = [npt(point_from(w_cd1, Cn, An, Bn), {t: rnd(-3, 3)}) for _ in range(8)]
kind, ctr, aa, foci = fit_conic(pts)
report(kind == 'ellipse' and dist(ctr, Cn) < mp.mpf(10) ** -25, "(2.32) fitted conic",
       f"{kind} centred at C = {Cn}, semi-major axis {mp.nstr(aa, 12)}")
prop_check("(2.32) focal sum (C=(1,1), A=(6,2), B=(3,4), angle BCA not 90 deg)", 'ellipse',
           [npt(point_from(w_cd1, Cn, An, Bn), {t: rnd(-3, 3)}) for _ in range(5)], foci, aa)
# (A-C) cos + (B-C) sin with the same C, A, B has the same foci (conjugate semi-diameters)
pts_cs = [npt(point_from([sp.cos(phi), sp.sin(phi)], Cn, An, Bn), {phi: p}) for p in phis(0, 6.28)]
prop_check("(2.32) = (2.24) ellipse: its points have the same focal sum", 'ellipse', pts_cs, foci, aa)

# --- 2.1.1.6 conjugate diameters, variant 2 ----------------------------------
print("-- 2.1.1.6 conjugate diameters, variant 2 (2.33)-(2.41); weights over (A, B, K)")
EA, EB, EK = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
C2 = along(EK, EA, lam)                     # KC/KA = lambda
N2 = along(EK, EA, t)                       # (2.33)
L2 = EB + N2 - C2                           # parallelogram CNLB
compare("L = (A - K)(t - lambda) + B", [t - lam, 1], [L2[0], L2[1]], [{t: rnd(0, 1), lam: rnd(0, 1)} for _ in range(4)])
cd2_samples = [{t: rnd(0, 1), lam: rnd(0.05, 0.95), v: rnd(0, 2), u: rnd(0, 2)} for _ in range(5)]
Pv = along(N2, L2, v)
compare("(2.35) P", [t - lam * v, v], [Pv[0], Pv[1]], cd2_samples)
P2 = meet(N2, L2, EB, EA)
compare("(2.37) P = NL x BA", [(t - lam) / (1 - lam), (1 - t) / (1 - lam)], [P2[0], P2[1]], cd2_samples)
Q2 = meet(N2, L2, EK, EB)
compare("Q = NL x KB", [0, t / lam], [Q2[0], Q2[1]], cd2_samples)
Mu = along(EK, P2, u)
compare("(2.41) ray KP", [(t - lam) * u / (1 - lam), (1 - t) * u / (1 - lam)], [Mu[0], Mu[1]], cd2_samples)
u_sol = sp.solve(sp.Matrix([list(EA), list(Q2), list(Mu)]).det(), u)[0]
compare("u = t(1 - lambda)/(t^2 - 2 lambda t + lambda)", [t * (1 - lam) / (t**2 - 2 * lam * t + lam)], [u_sol], cd2_samples)
M2 = meet(EK, P2, Q2, EA)
w_cd2 = [sp.factor(M2[0]), sp.factor(M2[1])]
D2 = t**2 - 2 * lam * t + lam
compare("ellipse, variant 2, final M", [t * (t - lam) / D2, t * (1 - t) / D2], w_cd2, cd2_samples)
report(all(sp.simplify(w.subs(t, tv) - ww) == 0 for tv, wv in ((0, (0, 0)), (1, (1, 0)), (lam, (0, 1)))
           for w, ww in zip(w_cd2, wv)), "variant 2: t = 0 -> K, t = 1 -> A, t = lambda -> B")
tang0 = [sp.diff(w, t).subs(t, 0) for w in w_cd2]
tang1 = [sp.diff(w, t).subs(t, 1) for w in w_cd2]
# direction B - C = (A - K)(-lambda) + (B - K)
par = lambda tg: sp.simplify(tg[0] + lam * tg[1]) == 0
report(par(tang0) and par(tang1), "variant 2: tangents at K and A are parallel to BC (conjugate direction)")
Kn, An2, Bn2, lamv = (R(0), R(0)), (R(6), R(0)), (R(2), R(3)), R(3, 10)
pts = [npt(point_from(w_cd2, Kn, An2, Bn2), {t: rnd(-3, 3), lam: lamv}) for _ in range(8)]
kind, ctr, aa, foci = fit_conic(pts)
report(kind == 'ellipse' and dist(ctr, (3, 0)) < mp.mpf(10) ** -25, "variant 2 fitted conic",
       f"{kind}, centre the midpoint of KA, semi-major axis {mp.nstr(aa, 12)} (K=(0,0), A=(6,0), B=(2,3), lambda=3/10)")
prop_check("variant 2 focal sum", 'ellipse', pts[:5], foci, aa)

# ----------------------------------------------------------------------------
print("== 2.1.2 hyperbola: C = (0,0), A = (a,0), B = (0,b), F1 = C + (A - C) e, F2 = C - (A - C) e (2.43)")
ch = sp.sqrt(a**2 + b**2)
F1h, F2h = (ch, 0), (-ch, 0)
eh, ph = ch / a, b**2 / a
asb = sp.asin(b / ch)
hyp_samples = [{a: R(3), b: R(2), phi: rnd(-0.58, 0.58)} for _ in range(4)] + \
              [{a: R(1), b: R(3), phi: rnd(-1.2, 1.2)} for _ in range(4)]


def hyp_points(weights, vals, params):
    return [npt(point_from(weights, Ce, Ae, Be), {**vals, **pp}) for pp in params]


def hyp_foci(vals):
    return (npt(F1h, vals), npt(F2h, vals))


print("-- 2.1.2.1 central angle (2.44)-(2.49)")
e244 = sp.Eq(d1**2, ch**2 + rho**2 - 2 * ch * rho * sp.cos(phi))
e245 = sp.Eq((2 * a + d1)**2, ch**2 + rho**2 + 2 * ch * rho * sp.cos(phi))
d1h = sp.solve(sp.expand(e245.lhs - e245.rhs - (e244.lhs - e244.rhs)), d1)[0]
compare("(2.47) |F1M|", [(ch * rho * sp.cos(phi) - a**2) / a], [d1h], [D(s, rho=R(5)) for s in hyp_samples])
rho_h = [r for r in sp.solve(sp.Eq(d1h**2, e244.rhs), rho) if sp.N(r.subs({a: 3, b: 2, phi: 0.3})) > 0][0]
den_h = sp.sqrt(b**2 * sp.cos(phi)**2 - a**2 * sp.sin(phi)**2)
compare("(2.48) rho", [a * b / den_h], [rho_h], hyp_samples)
w_hca = decompose((rho_h * sp.cos(phi), rho_h * sp.sin(phi)), Ce, Ae, Be)
compare("(2.49) M", [b * sp.cos(phi) / den_h, a * sp.sin(phi) / den_h], w_hca, hyp_samples)
report(all(sp.N((b**2 * sp.cos(asb)**2 - a**2 * sp.sin(asb)**2).subs(vv)) < 1e-25 for vv in (HB_VALS, {a: 1, b: 3})),
       "(2.49) domain: the radicand vanishes at phi = arcsin(b/c)", "agrees")
for vals, lim in (({a: R(3), b: R(2)}, 0.58), ({a: R(1), b: R(3)}, 1.2)):
    prop_check(f"(2.49) |d1 - d2| = 2a, a={vals[a]}, b={vals[b]}", 'hyperbola',
               hyp_points(w_hca, vals, [{phi: rnd(-lim, lim)} for _ in range(3)] +
                          [{phi: sp.pi + rnd(-lim, lim)} for _ in range(2)]), hyp_foci(vals), vals[a])

print("-- 2.1.2.2 central radius (2.50)-(2.53)")
x2h = sp.solve(sp.Eq(rho**2 * (b**2 * (1 - xs) - a**2 * xs), a**2 * b**2), xs)[0]
hr_samples = [{a: R(3), b: R(2), rho: rnd(3, 9)} for _ in range(4)] + [{a: R(1), b: R(3), rho: rnd(1, 5)} for _ in range(4)]
compare("(2.51) sin^2 phi", [b**2 * (rho**2 - a**2) / (rho**2 * (a**2 + b**2))], [x2h], hr_samples)
compare("(2.52) cos^2 phi", [a**2 * (rho**2 + b**2) / (rho**2 * (a**2 + b**2))], [1 - x2h], hr_samples)
X2 = sp.solve([x**2 / a**2 - y**2 / b**2 - 1, x**2 + y**2 - rho**2], [x, y], dict=True)
M_hr = [s for s in X2 if sp.N(s[x].subs(hr_samples[0])) > 0 and sp.N(s[y].subs(hr_samples[0])) > 0][0]
w_hr = decompose((M_hr[x], M_hr[y]), Ce, Ae, Be)
compare("(2.53) M", [sp.sqrt(rho**2 + b**2) / ch, sp.sqrt(rho**2 - a**2) / ch], w_hr, hr_samples)
for vals, hi in (({a: R(3), b: R(2)}, 9), ({a: R(1), b: R(3)}, 5)):
    prop_check(f"(2.53) |d1 - d2| = 2a, a={vals[a]}, b={vals[b]}, rho in [a, oo)", 'hyperbola',
               hyp_points(w_hr, vals, [{rho: rnd(float(vals[a]), hi)} for _ in range(5)]), hyp_foci(vals), vals[a])
# the printed range rho in [b; a]
vals = {a: R(3), b: R(2), rho: R(5, 2)}
im = sp.N(w_hr[1].subs(vals))
if not im.is_real or abs(sp.im(im)) > 0:
    misprint("(2.53) range of rho",
             "printed 'rho in [b; a]' (copied from (2.15)); sqrt(rho^2 - a^2) is imaginary for rho < a "
             f"(a=3, b=2, rho=5/2: weight of B - C = {sp.N(im, 6)}); the first quarter is rho in [a, oo) "
             "(rho = a gives the vertex A)")
else:
    report(False, "(2.53) range", "verdict changed")

print("-- 2.1.2.3 angle at the focus F1 (2.54)-(2.56)")
# independent: M = F1 + r (cos phi, sin phi) on the hyperbola (phi from the ray C F1, away from C),
# r signed: solve the quadratic, pick the root r(pi) = c - a (vertex A)
r_s = sp.symbols('r_s')
roots = sp.solve((F1h[0] + r_s * sp.cos(phi))**2 / a**2 - (r_s * sp.sin(phi))**2 / b**2 - 1, r_s)
rpol = [r for r in roots if abs(sp.N((r - (ch - a)).subs({a: 3, b: 2, phi: sp.pi}))) < 1e-20][0]
hf_samples = [{a: R(3), b: R(2), phi: rnd(0.6, 5.6)} for _ in range(4)] + \
             [{a: R(1), b: R(3), phi: rnd(1.3, 5.0)} for _ in range(4)]
compare("polar equation rho = |F1M| = p/(1 - e cos phi), phi from ray C F1 (C -> A direction)",
        [ph / (1 - eh * sp.cos(phi))], [rpol], hf_samples)
M_hf = (F1h[0] + rpol * sp.cos(phi), rpol * sp.sin(phi))
w_255 = decompose(M_hf, F1h, Ae, Be)               # simplex A B F1
w_256 = decompose(M_hf, Ce, Ae, Be)
printed_254 = [sp.sqrt(b**2 + ch**2) * ph * sp.sin(sp.asin(b / sp.sqrt(b**2 + ch**2)) - phi) /
               ((1 - eh * sp.cos(phi)) * (ch * b - a * b)),
               sp.sqrt(b**2 + ch**2) * ph * sp.sin(phi) / ((1 - eh * sp.cos(phi)) * b * sp.sqrt(b**2 + ch**2))]
printed_255 = [b * (b * sp.cos(phi) - ch * sp.sin(phi)) / (a * (1 - eh * sp.cos(phi)) * (ch - a)),
               b * sp.sin(phi) / (a * (1 - eh * sp.cos(phi)))]
compare("(2.54) = (2.55) as printed", printed_254, printed_255, hf_samples)
compare("(2.55) M in simplex A B F1", printed_255, w_255, hf_samples, expect_ok=False,
        why="printed (A - F1) weight b(b cos phi - c sin phi)/(a(1 - e cos phi)(c - a)) (and (2.54)) "
            "is the point F1 + rho(-cos phi, sin phi): phi measured from the ray F1 A (towards C) "
            "while rho = p/(1 - e cos phi) belongs to phi measured from the ray C F1 (away from C); "
            "correct -b(b cos phi + c sin phi)/(a(1 - e cos phi)(c - a)); (B - F1) weight agrees. "
            "(Alternatively keep (2.54)-(2.55) and use rho = p/(1 + e cos phi); then (2.56) changes.)",
        correct=[-b * (b * sp.cos(phi) + ch * sp.sin(phi)) / (a * (1 - eh * sp.cos(phi)) * (ch - a)), printed_255[1]])
printed_256 = [(ch - a * sp.cos(phi)) / (a - ch * sp.cos(phi)), b * sp.sin(phi) / (a - ch * sp.cos(phi))]
compare("(2.56) M in simplex A B C (F1 from (2.43))", printed_256, w_256, hf_samples)
p55, q55 = printed_255
compare("(2.55) printed + (2.43) -> (2.56)", printed_256,
        [p55 * (1 - eh) - q55 * eh + eh, q55], hf_samples, expect_ok=False,
        why="substituting F1 = C + (A - C) e into the printed (2.55) does not give (2.56) "
            "(A - C weight (ca - (b^2 + c^2) cos phi)/(a(a - c cos phi))); the corrected (2.55) does")
wc55 = [-b * (b * sp.cos(phi) + ch * sp.sin(phi)) / (a * (1 - eh * sp.cos(phi)) * (ch - a)), q55]
compare("corrected (2.55) + (2.43) gives (2.56)", printed_256, [wc55[0] * (1 - eh) - wc55[1] * eh + eh, wc55[1]],
        hf_samples)
for vals, lo, hi in (({a: R(3), b: R(2)}, 0.6, 5.6), ({a: R(1), b: R(3)}, 1.3, 5.0)):
    prop_check(f"(2.56) |d1 - d2| = 2a, a={vals[a]}, b={vals[b]}", 'hyperbola',
               hyp_points(w_256, vals, [{phi: rnd(lo, hi)} for _ in range(5)]), hyp_foci(vals), vals[a])
vals = HB_VALS
prop_fails("(2.55) printed, |d1 - d2|", 'hyperbola',
           [npt(point_from(printed_255, F1h, Ae, Be), D(vals, phi=p)) for p in phis(0.7, 5.5)],
           hyp_foci(vals), vals[a], "the printed (2.55) is not on the hyperbola")
# the printed phi range [0, arcsin(b/c)) U (2 pi - arcsin(b/c), 2 pi]: rho < 0 and the left branch
lim = float(sp.N(asb.subs(vals)))
xs_ = [sp.N(point_from(printed_256, Ce, Ae, Be)[0].subs(D(vals, phi=p))) for p in (0, lim / 2, -lim / 2)]
rs_ = [sp.N((ph / (1 - eh * sp.cos(phi))).subs(D(vals, phi=p))) for p in (0, lim / 2)]
if all(xx < 0 for xx in xs_) and all(rr < 0 for rr in rs_):
    misprint("(2.54)-(2.56) range of phi",
             "printed phi in [0, arcsin(b/c)) U (2pi - arcsin(b/c), 2pi] for 'the right branch': there "
             f"1 - e cos phi < 0, rho = |F1M| < 0 and (2.56) gives the LEFT branch (phi = 0: M = 2C - A, "
             f"x = {sp.N(xs_[0], 6)}); the right branch is phi in (arcsin(b/c), 2pi - arcsin(b/c)), "
             "phi = pi giving the vertex A")
else:
    report(False, "(2.56) range", "verdict changed")

# ----------------------------------------------------------------------------
print("== 2.1.8 circle")
print("-- 2.1.8.1 engineering discriminant (2.107) with (2.97)")
# chord AB of length c on the x axis, O its midpoint, K the arc midpoint at height h
Ac, Bc, Kc = (-c / 2, 0), (c / 2, 0), (0, h)
r_c = sp.simplify((c**2 / 4 + h**2) / (2 * h))            # radius: (c/2)^2 + (r - h)^2 = r^2
O1 = (0, h - r_c)
# tangent at A is perpendicular to O1 A; it meets the axis x = 0 at C
yC = sp.symbols('yC')
yC_sol = sp.solve((0 - Ac[0]) * (Ac[0] - O1[0]) + (yC - Ac[1]) * (Ac[1] - O1[1]), yC)[0]
k_der = sp.simplify((yC_sol - h) / yC_sol)                # k = CK/CO (K = C + (O - C) k)
circ_samples = [{c: R(4), h: rnd(0.1, 1.9)} for _ in range(4)]
compare("(2.107) k = KC/OC", [R(1, 2) + 2 * h**2 / c**2], [k_der], circ_samples)
# (2.97) from the construction of 2.1.6 (unit weight vectors A, B, C)
EA, EB, EC = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
kq = sp.symbols('k')
T1 = (EA + EB) / 2
Kv = along(EC, T1, kq)
Tu = along(EA, EB, u)
Pq = meet(EA, Kv, EC, Tu)
Qq = meet(EB, Kv, EC, Tu)
Mq = meet(EA, Qq, EB, Pq)
den97 = kq * (1 - 2 * u)**2 + 2 * (1 - u) * u
compare("(2.97) M (re-derived for 2.1.8.1)", [kq * (1 - u)**2 / den97, kq * u**2 / den97],
        [sp.factor(Mq[0]), sp.factor(Mq[1])], [{u: rnd(0, 1), kq: rnd(0, 1)} for _ in range(4)])
Cc = (0, yC_sol)
ok = True
for hv in (R(1, 2), R(3, 2)):
    vals = {c: R(4), h: hv}
    wts = [Mq[0].subs(kq, k_der), Mq[1].subs(kq, k_der)]
    pts = [npt(point_from(wts, Cc, Ac, Bc), D(vals, u=uu)) for uu in (0, R(1, 2), rnd(0, 1), rnd(-3, 3), rnd(1, 4))]
    ok &= prop_check(f"(2.97) with k of (2.107): distance to O1, c=4, h={hv}", 'circle', pts,
                     centre=npt(O1, vals), radius=mp.mpf(sp.N(r_c.subs(vals), 40)))

print("-- 2.1.8.2 angular parameter, variant 1 (2.108)-(2.116); C = (0,0), A = (b,0), B = a(cos g, sin g)")
# independent: M = ray from C at angle phi to CA  x  ray from A with angle CAM = pi - phi - delta
Cg, Ag, Bg = (0, 0), (b, 0), (a * sp.cos(gamma), a * sp.sin(gamma))
s1, s2 = sp.symbols('s1 s2')
sol = sp.solve([s1 * sp.cos(phi) - (b + s2 * sp.cos(phi + delta)), s1 * sp.sin(phi) - s2 * sp.sin(phi + delta)],
               [s1, s2], dict=True)[0]
MCg = sp.simplify(sol[s1])
compare("(2.111) MC", [b * sp.sin(delta + phi) / sp.sin(delta)], [MCg],
        [{b: R(3), delta: R(1), phi: rnd(0, 2.1)} for _ in range(4)])
M115 = (MCg * sp.cos(phi), MCg * sp.sin(phi))
w115 = decompose(M115, Cg, Ag, Bg)
s8_samples = [{a: R(4), b: R(3), gamma: R(6, 5), delta: R(1), phi: rnd(0, 3.1)} for _ in range(4)] + \
             [{a: R(2), b: R(5), gamma: R(2), delta: R(5, 2), phi: rnd(0, 3.1)} for _ in range(4)]
printed_115 = [sp.sin(delta + phi) * sp.sin(gamma - phi) / (sp.sin(delta) * sp.sin(gamma)),
               b * sp.sin(delta + phi) * sp.sin(phi) / (a * sp.sin(delta) * sp.sin(gamma))]
compare("(2.114)-(2.115) M", printed_115, w115, s8_samples)
vals = {a: R(4), b: R(3), gamma: R(6, 5), delta: R(1)}
ctr = (sp.N(b / 2, 40).subs(vals), sp.N((b / 2 * sp.cot(delta)).subs(vals), 40))
prop_check("(2.115) phi in [0, pi]: distance to the centre (b/2, b cot(delta)/2)", 'circle',
           [npt(point_from(w115, Cg, Ag, Bg), D(vals, phi=p)) for p in phis(0, 3.14)],
           centre=(mp.mpf(ctr[0]), mp.mpf(ctr[1])), radius=mp.mpf(sp.N((b / (2 * sp.sin(delta))).subs(vals), 40)))


def angle_AMC(weights, vals, p):
    M_ = npt(point_from(weights, Cg, Ag, Bg), D(vals, phi=p))
    A_, C_ = npt(Ag, vals), (0, 0)
    u1 = (A_[0] - M_[0], A_[1] - M_[1]); u2 = (C_[0] - M_[0], C_[1] - M_[1])
    return mp.acos((u1[0] * u2[0] + u1[1] * u2[1]) / (mp.sqrt(u1[0]**2 + u1[1]**2) * mp.sqrt(u2[0]**2 + u2[1]**2)))


dl = mp.mpf(1)
up = [angle_AMC(w115, vals, p) for p in phis(0.05, float(mp.pi - dl) - 0.05, 3)]
down = [angle_AMC(w115, vals, p) for p in phis(float(mp.pi - dl) + 0.05, 3.1, 3)]
report(all(abs(x_ - dl) < 1e-25 for x_ in up), "(2.115) phi in (0, pi - delta): angle AMC = delta", "agrees")
if all(abs(x_ - (mp.pi - dl)) < 1e-25 for x_ in down):
    print("REMARK   (2.115) text: for phi in (pi - delta, pi) M runs over the arc of the SAME circle below CA, "
          "from which CA is seen under pi - delta, not delta (the mirror arc seeing CA under delta "
          "is not produced); the formula itself is right")
else:
    report(False, "(2.115) lower arc", "unexpected angle")
# (2.116): delta = beta; with b = a sin(beta)/sin(beta + gamma) (sine theorem) the circle is ABC's
w116 = [w.subs(delta, beta) for w in w115]
tri = {a: R(4), gamma: R(6, 5), beta: R(9, 10)}
tri[b] = sp.N((a * sp.sin(beta) / sp.sin(beta + gamma)).subs(tri), 40)
at = lambda p: [sp.N(w.subs(tri).subs(phi, p), 30) for w in w116]
report(all(abs(x_ - y_) < 1e-25 for x_, y_ in zip(at(0), (1, 0))), "(2.116) phi = 0 gives A", "agrees")
if all(abs(x_ - y_) < 1e-25 for x_, y_ in zip(at(tri[gamma]), (0, 1))) and \
        all(abs(x_) < 1e-25 for x_ in at(sp.pi - tri[beta])):
    misprint("(2.116) text", "'phi = pi - beta gives the end point B' is wrong: phi = pi - beta gives C "
             "(sin(beta + phi) = 0), B is reached at phi = gamma; phi in [0, pi - beta] is the arc A B C")
else:
    report(False, "(2.116) end point", "verdict changed")

print("-- 2.1.8.3 angular parameter, variant 2 (2.117)-(2.118)")
M118 = (R_ * sp.cos(phi), R_ * sp.sin(phi))
w118 = decompose(M118, Cg, Ag, Bg)
s9 = [D(s, R=R(7, 3)) for s in s8_samples]
compare("(2.117)-(2.118) M", [R_ * sp.sin(gamma - phi) / (b * sp.sin(gamma)), R_ * sp.sin(phi) / (a * sp.sin(gamma))],
        w118, s9)
vals = {a: R(4), b: R(3), gamma: R(6, 5), R_: R(7, 3)}
prop_check("(2.118) |CM| = R", 'circle', [npt(point_from(w118, Cg, Ag, Bg), D(vals, phi=p)) for p in phis(0, 6.28)],
           centre=(0, 0), radius=mp.mpf(7) / 3)

# ----------------------------------------------------------------------------
finish()
