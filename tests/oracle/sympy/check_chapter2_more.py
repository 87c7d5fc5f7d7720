#!/usr/bin/env python3
"""Checks the monograph's sections 2.4, 2.5, 2.7, 2.8 and the circle article
against an independent SymPy derivation.

Covered (source, section, equations):
  monograph 2.4.1  angular parametrization of the curve of one ratio  (2.123)-(2.128), final M
  monograph 2.4.2  radial parametrization of the curve of one ratio   (2.129)-(2.135)
  monograph 2.5    sinusoid whose axis is a circle                    (2.136)-(2.145)
  monograph 2.7    contour arcs in general form                        (2.160), M', w, (2.161)
  monograph 2.8    cycloid                                             P, (3.11), theta form, (3.12)
  article-circle-projective: circle through three points               (5), k, k1, x_O, y_O, R
  article-circle-projective: circle through two points and a tangent   K, R, (6), E, a1, (8), v, x(t), y(t)

Method (as tests/oracle/sympy/check_chapter2.py).  Where a metric is needed the base
points get coordinates (C at the origin, CA along x, B = a (cos g, sin g),
a = |CB|, b = |CA|, g = angle ACB); the current point is constructed in
coordinates from the geometry (ratio chains, law of sines/cosines, rotation,
rolling) and decomposed as M = (A - C) p + (B - C) q + C.  Affine
constructions (2.7) use the base points as unit weight vectors.  Printed and
derived forms are compared numerically at random parameter values to 30
digits, then the defining property is checked numerically (angle ACM = phi,
|CM| = rho, |CM| = |CT| for the sinusoid, rolling without slipping for the
cycloid, constant distance to the centre and tangency for the circles).

Prints one line per check: "OK ..." or "MISPRINT ..." (a misprint that was
expected, i.e. confirmed), REMARK lines are comments on the text.  Exits
non-zero if any check FAILs (a derived formula that does not satisfy its
defining property, a correction that does not equal the derivation, or a
printed formula whose verdict changed).  Used for the expectations of the
schemes curve_one_ratio_angular.pcs, curve_one_ratio_radial.pcs,
sinusoid_circle.pcs, contour_arc_general.pcs, cycloid.pcs,
circle_three_points*.pcs, circle_two_points_tangent*.pcs.
Runs in about 20-30 s.
"""
import random
import sys

import mpmath as mp
import sympy as sp

from verdicts import (R, compare, decompose, fix, misprint, misprints, failures,
                      ndist, npt, num, point_from, remark, report, rnd, same,
                      use_symbols, finish)

random.seed(20240612)

a, b, c, r_, rho1, m, n = sp.symbols('a b c r rho1 m n', positive=True)
gam = sp.symbols('gamma', positive=True)
phi, rho, t, theta, s_ = sp.symbols('phi rho t theta s', real=True)
SYM = {str(z): z for z in (a, b, c, r_, rho1, m, n, gam, phi, rho, t, theta, s_)}
use_symbols(SYM)



























def nangle(P, Q, Rr):
    """angle at Q (0..pi)."""
    u = (P[0] - Q[0], P[1] - Q[1]); v = (Rr[0] - Q[0], Rr[1] - Q[1])
    return mp.acos((u[0] * v[0] + u[1] * v[1]) / (mp.sqrt(u[0]**2 + u[1]**2) * mp.sqrt(v[0]**2 + v[1]**2)))


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def along(P, Q, s):
    return tuple(P[i] + (Q[i] - P[i]) * s for i in range(len(P)))


TOL = mp.mpf(10) ** -25
tb = 1 - t
# the simplex of 2.4 and 2.5: C = (0,0), A = (b,0), B = a (cos g, sin g)
Cg, Ag, Bg = (0, 0), (b, 0), (a * sp.cos(gam), a * sp.sin(gam))
TRI = [{a: R(4), b: R(3), gam: R(6, 5)}, {a: R(2), b: R(5), gam: R(2)}, {a: R(3), b: R(3), gam: R(7, 10)}]

# ============================================================================
print("== 2.4.1 angular parametrization of the curve of one ratio (2.123)-(2.128)")
P_ = along(Ag, Cg, t)                       # AP/AC = t
Q_ = along(Cg, Bg, t)                       # CQ/CB = t
M_par = along(P_, Q_, t)                    # PM/PQ = t
w_par = decompose(M_par, Cg, Ag, Bg)
fix_s = [dict(T, t=rnd(0, 1)) for T in TRI for _ in range(2)]
compare("2.1.3.1 curve of one ratio M = (A - C) tb^2 + (B - C) t^2 + C", [tb**2, t**2], w_par, fix_s)
K_ = point_from((tb**2, 0), Cg, Ag, Bg)     # K on CA, CKML a parallelogram with M
ok = all(abs(ndist(npt(K_, s), (0, 0)) - num(b * tb**2, s).real) < TOL and
         abs(ndist(npt(K_, s), npt(M_par, s)) - num(a * t**2, s).real) < TOL for s in fix_s)
report(ok, "(2.123) CK = b tb^2, KM = a t^2 (KM parallel to CB)")
# phi(t) = angle ACM from coordinates
phi_of_t = sp.atan2(M_par[1], M_par[0])
MC = sp.sqrt(M_par[0]**2 + M_par[1]**2)
s124 = [dict(s, phi=sp.N(phi_of_t.subs(s), 40)) for s in fix_s]
compare("(2.124) MC = a t^2 sin g/sin phi (law of sines in CKM)", [a * t**2 * sp.sin(gam) / sp.sin(phi)], [MC], s124)
compare("(2.125) MC = b tb^2 sin g/sin(g - phi) (law of sines in CML)",
        [b * tb**2 * sp.sin(gam) / sp.sin(gam - phi)], [MC], s124)
compare("(2.127) tb^2/t^2 = a sin(g - phi)/(b sin phi)", [a * sp.sin(gam - phi) / (b * sp.sin(phi))], [tb**2 / t**2], s124)
# (2.128): for a given phi, t is the root in [0, 1] of  M(t) x (cos phi, sin phi) = 0  (M on the ray at angle phi)
eq_t = sp.expand(M_par[1] * sp.cos(phi) - M_par[0] * sp.sin(phi))
t128 = sp.sqrt(b * sp.sin(phi)) / (sp.sqrt(a * sp.sin(gam - phi)) + sp.sqrt(b * sp.sin(phi)))
psamp = [dict(T, phi=rnd(0.01, float(T[gam]) - 0.01)) for T in TRI for _ in range(3)]
ok = True
for s in psamp:
    coeffs = sp.Poly(eq_t.subs(fix(s)), t).all_coeffs()
    roots = [z for z in mp.polyroots([mp.mpf(str(sp.N(cf, 40))) for cf in coeffs], extraprec=80)
             if abs(mp.im(z)) < TOL and -TOL <= mp.re(z) <= 1 + TOL]
    ok &= len(roots) == 1 and abs(roots[0] - num(t128, s).real) < TOL
report(ok, "(2.128) t = sqrt(b sin phi)/(sqrt(a sin(g - phi)) + sqrt(b sin phi)): the one root in [0, 1] of "
       "'M(t) on the ray at angle phi'", "agrees")
compare("(2.128) tb", [sp.sqrt(a * sp.sin(gam - phi)) / (sp.sqrt(a * sp.sin(gam - phi)) + sp.sqrt(b * sp.sin(phi)))],
        [1 - t128], psamp)
den = (sp.sqrt(a * sp.sin(gam - phi)) + sp.sqrt(b * sp.sin(phi)))**2
w_ang = [w.subs(t, t128) for w in w_par]
compare("2.4.1 final M = (A - C) a sin(g - phi)/D + (B - C) b sin phi/D + C, D = (sqrt(a sin(g-phi)) + sqrt(b sin phi))^2",
        [a * sp.sin(gam - phi) / den, b * sp.sin(phi) / den], w_ang, psamp)
ok = all(abs(nangle(npt(Ag, s), (0, 0), npt(point_from(w_ang, Cg, Ag, Bg), s)) - num(phi, s).real) < TOL for s in psamp)
report(ok, "2.4.1 final M: angle ACM = phi at 9 points (3 triangles)")
ok = all(abs(num(w_ang[0], dict(T, phi=0)) - 1) < TOL and abs(num(w_ang[1], dict(T, phi=T[gam])) - 1) < TOL for T in TRI)
report(ok, "2.4.1 final M: phi = 0 gives A, phi = g gives B (range 0 <= phi <= g)")

# ============================================================================
print("== 2.4.2 radial parametrization of the curve of one ratio (2.129)-(2.135)")
# (2.129): in triangle CKM (angle K = pi - g, angle C = phi, angle M = g - phi) the law of sines gives
# |KM| = |CK| sin phi/sin(g - phi); KM is parallel to CB, so M = K + (B - C) |KM|/a.
printed_129 = tuple(K_[i] - (Cg[i] - K_[i]) * sp.sin(phi) / sp.sin(gam - phi) for i in range(2))
correct_129 = tuple(K_[i] + (Bg[i] - Cg[i]) * b * tb**2 / a * sp.sin(phi) / sp.sin(gam - phi) for i in range(2))
s129 = s124
compare("(2.129) M from triangle CKM", list(decompose(printed_129, Cg, Ag, Bg)), list(w_par), s129, expect_ok=False,
        why="printed M = -(C - K) sin phi/sin(g - phi) + K puts M on the line CA (the ray C K); by the law of sines "
            "|KM| = |CK| sin phi/sin(g - phi), but KM is parallel to CB, not to CK: correct "
            "M = (B - C) |CK| sin phi/(a sin(g - phi)) + K = (B - C) b tb^2 sin phi/(a sin(g - phi)) + K",
        correct=list(decompose(correct_129, Cg, Ag, Bg)))
compare("(2.130) sin phi/sin(g - phi) = a t^2/(b tb^2) (from (2.127))", [a * t**2 / (b * t**2)],
        [sp.sin(phi) / sp.sin(gam - phi)], s129, expect_ok=False,
        why="printed 'a t^2/(b t^2)' (bar lost over the second t): the ratio is a t^2/(b tb^2) by (2.127)",
        correct=[a * t**2 / (b * tb**2)])
remark("(2.130) with the corrected (2.129): M = (B - C)(b tb^2/a)(a t^2/(b tb^2)) + K = (B - C) t^2 + K, i.e. "
       "the parabola again; (2.129)-(2.130) cannot give rho, the radius needs the law of cosines")
compare("(2.131) K = (A - C) tb^2 + C", list(decompose(K_, Cg, Ag, Bg)), [tb**2, 0], fix_s)
# (2.132) = printed (2.129) with (2.130) (bar restored) and (2.131): a point of the line CA
p132 = (a * t**2 + b * tb**2) / b
M132 = point_from((p132, 0), Cg, Ag, Bg)
compare("(2.132) follows from the printed (2.129)-(2.131)",
        [p132, 0], list(decompose(tuple(K_[i] - (Cg[i] - K_[i]) * a * t**2 / (b * tb**2) for i in range(2)), Cg, Ag, Bg)),
        fix_s)
ok = all(ndist(npt(M132, s), npt(M_par, s)) > 1e-3 for s in fix_s)
if ok:
    misprint("(2.132) M = (A - C)(a t^2 + b tb^2)/b + C",
             "a point of the line CA (no B term), not the point of the curve (consequence of the (2.129) error); "
             "the curve is M = (A - C) tb^2 + (B - C) t^2 + C")
else:
    report(False, "(2.132)", "verdict changed")
# (2.133): rho = |CM| -- law of cosines in CKM (angle at K is pi - g)
rho_true2 = a**2 * t**4 + b**2 * tb**4 + 2 * a * b * sp.cos(gam) * t**2 * tb**2
compare("|CM|^2 = a^2 t^4 + b^2 tb^4 + 2 a b cos g t^2 tb^2 (law of cosines)", [rho_true2], [MC**2], fix_s)
compare("(2.133) rho = |CM| = a t^2 + b tb^2", [a * t**2 + b * tb**2], [MC], fix_s, expect_ok=False,
        why="printed rho = a t^2 + b tb^2 = |KM| + |CK| (the broken line C K M), equal to |CM| only for g = 0; "
            "correct rho^2 = a^2 t^4 + b^2 tb^4 + 2ab cos(g) t^2 tb^2 (law of cosines in CKM), a quartic in t",
        correct=[sp.sqrt(rho_true2)])
report(sp.expand(rho_true2 - (a * t**2 + b * tb**2)**2 + 2 * a * b * t**2 * tb**2 * (1 - sp.cos(gam))) == 0,
       "|CM|^2 - (a t^2 + b tb^2)^2 = -2ab t^2 tb^2 (1 - cos g) (zero only for g = 0)")
quad = sp.expand((a + b) * t**2 - 2 * b * t + b - rho)
report(sp.expand(quad - (a * t**2 + b * tb**2 - rho)) == 0, "quadratic (a + b) t^2 - 2bt + b - rho = 0 follows from (2.133)")
t1 = (b - sp.sqrt(a * rho + b * rho - a * b)) / (a + b)
t2 = (b + sp.sqrt(a * rho + b * rho - a * b)) / (a + b)
report(all(sp.simplify(quad.subs(t, tt)) == 0 for tt in (t1, t2)), "t1, t2 are its roots; discriminant >= 0 <=> rho >= ab/(a+b)")
rsamp = [dict(T, rho=T[a] * T[b] / (T[a] + T[b]) + f * (min(T[a], T[b]) - T[a] * T[b] / (T[a] + T[b])))
         for T in TRI for f in (R(1, 5), R(3, 5))]
compare("(2.134) M1 = the curve at t1", [((a + sp.sqrt(a * rho + b * rho - a * b)) / (a + b))**2,
                                         ((b - sp.sqrt(a * rho + b * rho - a * b)) / (a + b))**2],
        [w.subs(t, t1) for w in w_par], rsamp)
compare("(2.135) M2 = the curve at t2", [((a - sp.sqrt(a * rho + b * rho - a * b)) / (a + b))**2,
                                         ((b + sp.sqrt(a * rho + b * rho - a * b)) / (a + b))**2],
        [w.subs(t, t2) for w in w_par], rsamp)
# ranges: t1 runs over [0, b/(a+b)] when rho goes from b down to ab/(a+b); t2 over [b/(a+b), 1] for rho up to a
ok = all(abs(num(t1, dict(T, rho=T[b]))) < TOL and abs(num(t2, dict(T, rho=T[a])) - 1) < TOL
         and abs(num(t1 - t2, dict(T, rho=T[a] * T[b] / (T[a] + T[b])))) < TOL for T in TRI)
if ok:
    misprint("(2.134) range", "printed 'b <= rho <= ab/(a+b)' is an empty interval (ab/(a+b) < b); correct "
             "ab/(a+b) <= rho <= b (rho = b: t1 = 0, the point A; rho = ab/(a+b): t1 = t2 = b/(a+b)); "
             "(2.135)'s ab/(a+b) <= rho <= a agrees (rho = a: t2 = 1, the point B)")
else:
    report(False, "(2.134) range", "verdict changed")
# the printed M1/M2 are not at distance rho from C (except at the ends)
bad = []
for s in rsamp:
    Mn = npt(point_from([w.subs(t, t1) for w in w_par], Cg, Ag, Bg), s)
    bad.append((ndist(Mn, (0, 0)), num(rho, s).real))
if all(abs(d - r) > 1e-4 for d, r in bad):
    misprint("(2.134)-(2.135) as a radial parametrization",
             f"|CM1| != rho (e.g. a=4, b=3, g=6/5, rho={mp.nstr(bad[0][1], 6)}: |CM1| = {mp.nstr(bad[0][0], 8)}); "
             "rho in (2.134)-(2.135) is |CK| + |KM|, the printed M1, M2 are the curve reparametrized by that sum. "
             "Correct: M = (A - C) tb^2 + (B - C) t^2 + C with t in [0, 1] a root of "
             "a^2 t^4 + b^2 tb^4 + 2ab cos(g) t^2 tb^2 = rho^2 (no short closed form in general)")
else:
    report(False, "(2.134) |CM1|", "verdict changed")
# property of the corrected form: t from the quartic, |CM| = rho
ok = True
for s in rsamp:
    T = {k: v for k, v in s.items() if k != rho}
    tt = mp.findroot(lambda x: num(rho_true2 - rho**2, dict(s, t=x)).real, mp.mpf('0.05'))
    Mn = npt(point_from(w_par, Cg, Ag, Bg), dict(T, t=tt))
    ok &= abs(ndist(Mn, (0, 0)) - num(rho, s).real) < TOL
report(ok, "corrected radial form (t from the quartic): |CM| = rho at 6 points")
# the true minimum of |CM| (the split point of the two arcs) is not ab/(a+b)
Tn = TRI[0]
tmin = mp.findroot(lambda x: num(sp.diff(rho_true2, t), dict(Tn, t=x)).real, mp.mpf('0.5'))
rmin = mp.sqrt(num(rho_true2, dict(Tn, t=tmin)).real)
remark(f"2.4.2: the arcs split at the point nearest to C: for a=4, b=3, g=6/5 at t = {mp.nstr(tmin, 8)}, "
       f"rho_min = {mp.nstr(rmin, 8)} (the printed ab/(a+b) = {mp.nstr(mp.mpf(12) / 7, 8)} is the minimum of |CK| + |KM|)")
# closed form for a = b (symmetric parabola): t = 1/2 -+ sqrt(sigma)
ch, sh = sp.cos(gam / 2), sp.sin(gam / 2)
sig = (2 * sp.sqrt(rho**2 * ch**2 + a**2 * sh**2) - a * (1 + sh**2)) / (4 * a * ch**2)
ok = True
for T in TRI:
    for _ in range(2):
        rv = rnd(float(sp.N(T[a] * sp.cos(T[gam] / 2) / 2)), float(T[a]))
        s = dict(T, rho=rv)
        s[b] = T[a]
        for tt in (R(1, 2) - sp.sqrt(sig), R(1, 2) + sp.sqrt(sig)):
            ok &= abs(num(sp.sqrt(rho_true2.subs(t, tt)), s) - rv) < TOL
sig_cos = (2 * sp.sqrt(2 * (rho**2 * (1 + sp.cos(gam)) + a**2 * (1 - sp.cos(gam)))) - a * (3 - sp.cos(gam))) / \
    (4 * a * (1 + sp.cos(gam)))
ok &= same(sig, sig_cos, [dict(T, rho=rnd(1, 3)) for T in TRI])
report(ok, "a = b: t = 1/2 -+ sqrt(sigma), sigma = (2 sqrt(rho^2 cos^2(g/2) + a^2 sin^2(g/2)) - a(1 + sin^2(g/2)))"
       "/(4a cos^2(g/2)) gives |CM| = rho; rho in [a cos(g/2)/2, a]; sigma = (2 sqrt(2(rho^2 (1 + cos g) + "
       "a^2 (1 - cos g))) - a(3 - cos g))/(4a(1 + cos g)) (the scheme's form)")

# ============================================================================
print("== 2.5 sinusoid whose axis is a circle (2.136)-(2.145)")
# axis circle: centre C, radius b = |CA|; generating circle: centre A, radius rho1, P = the point of it on the
# ray CA beyond A.  Q = A rotated about C by phi (towards B); T = P rotated about A by theta; arc AQ = arc PT.
th = sp.symbols('th', real=True)
SYM['th'] = th
Tt = (b + rho1 * sp.cos(th), rho1 * sp.sin(th))          # P = (b + rho1, 0) rotated about A by th
th136 = sp.solve(sp.Eq(b * phi, rho1 * th), th)[0]
report(sp.simplify(th136 - b * phi / rho1) == 0, "(2.136) theta = b phi/rho1 (arc AQ = arc PT)", "agrees")
CT2 = sp.simplify(sp.expand(Tt[0]**2 + Tt[1]**2))
ssamp = [dict(T, rho1=rnd(0.2, 1.5), phi=rnd(0, 6.28)) for T in TRI for _ in range(2)]
compare("(2.137) CT^2 = b^2 + rho1^2 - 2 b rho1 cos(pi - theta) = b^2 + rho1^2 + 2 b rho1 cos(b phi/rho1)",
        [b**2 + rho1**2 - 2 * b * rho1 * sp.cos(sp.pi - b * phi / rho1), b**2 + rho1**2 + 2 * b * rho1 * sp.cos(b * phi / rho1)],
        [CT2.subs(th, th136)] * 2, ssamp)
Qs = (b * sp.cos(phi), b * sp.sin(phi))
compare("(2.138) Q = (A - C) sin(g - phi)/sin g + (B - C) b sin phi/(a sin g) + C",
        [sp.sin(gam - phi) / sp.sin(gam), b * sp.sin(phi) / (a * sp.sin(gam))], decompose(Qs, Cg, Ag, Bg), ssamp)
CTv = sp.sqrt(CT2.subs(th, th136))
M_sin = tuple(Qs[i] * CTv / b for i in range(2))                # M on ray CQ with |CM| = |CT|
w_sin = decompose(M_sin, Cg, Ag, Bg)
sq = sp.sqrt(b**2 + rho1**2 + 2 * b * rho1 * sp.cos(b * phi / rho1))
compare("(2.139)-(2.140) M", [sp.sin(gam - phi) * sq / (b * sp.sin(gam)), sp.sin(phi) * sq / (a * sp.sin(gam))], w_sin, ssamp)
sq_m = sp.sqrt(1 + m**2 + 2 * m * sp.cos(m * phi))
w_142 = [w.subs(rho1, b / m) for w in w_sin]
msamp = [dict(T, m=mm, phi=rnd(0, 6.28)) for T in TRI for mm in (3, 7)]
compare("(2.141)-(2.142) M with rho1 = b/m", [sp.sin(gam - phi) * sq_m / (m * sp.sin(gam)),
                                              b * sp.sin(phi) * sq_m / (a * m * sp.sin(gam))], w_142, msamp)
compare("(2.140) phi = 0: M = (A - C)(b + rho1)/b + C (the point P)", [(b + rho1) / b, 0],
        [sp.simplify(w_.subs(phi, 0)) for w_ in w_sin], ssamp)
# property: |CM| = |CT|, angle ACM = phi (mod 2 pi), offset |CM| - b within [-rho1, rho1], closed and m waves
ok = True
for s in ssamp:
    Mn = npt(point_from(w_sin, Cg, Ag, Bg), s)
    Tn = npt(Tt, dict(s, th=num(th136, s).real))
    ok &= abs(ndist(Mn, (0, 0)) - ndist(Tn, (0, 0))) < TOL
    ok &= abs(mp.atan2(Mn[1], Mn[0]) - mp.atan2(mp.sin(num(phi, s).real), mp.cos(num(phi, s).real))) < TOL
report(ok, "(2.140) |CM| = |CT| (T on the generating circle, arc PT = arc AQ) and M on the ray CQ, 6 points")
T0 = dict(TRI[0], m=5)
N = 400
offs = [ndist(npt(point_from(w_142, Cg, Ag, Bg), dict(T0, phi=2 * sp.pi * k / N)), (0, 0)) - 3 for k in range(N)]
maxima = sum(1 for k in range(N) if offs[k] > offs[k - 1] and offs[k] >= offs[(k + 1) % N])
closed = max(abs(x - y) for x, y in zip(npt(point_from(w_142, Cg, Ag, Bg), dict(T0, phi=0)),
                                         npt(point_from(w_142, Cg, Ag, Bg), dict(T0, phi=2 * sp.pi))))
report(maxima == 5 and closed < TOL and abs(max(offs) - mp.mpf(3) / 5) < 1e-3 and abs(min(offs) + mp.mpf(3) / 5) < 1e-3,
       "(2.142) m = 5: closed (M(0) = M(2pi)), 5 waves, offset |CM| - b in [-b/m, b/m]",
       f"max {mp.nstr(max(offs), 6)}, min {mp.nstr(min(offs), 6)}")
remark("2.5: the offset |CM| - b = sqrt(b^2 + rho1^2 + 2 b rho1 cos theta) - b is not rho1 cos theta (the classical "
       "sinusoid's projection); it is a sinusoid only to first order in rho1/b")
# (2.143)-(2.145)
rho2 = sp.symbols('rho2', positive=True)
N_def = [w * sp.sqrt(b**2 + rho2**2 + 2 * b * rho2 * sp.cos(b * phi / rho2)) / b for w in w_142]
sq_n = sp.sqrt(1 + n**2 + 2 * n * sp.cos(n * phi))
nsamp = [dict(T, m=mm, n=nn, phi=rnd(0, 6.28)) for T in TRI for mm, nn in ((3, 7), (5, 2))]
compare("(2.143)-(2.144) N = (M - C) sqrt(b^2 + rho2^2 + 2 b rho2 cos(b phi/rho2))/b + C with rho2 = b/n",
        [sp.sin(gam - phi) * sq_m * sq_n / (m * n * sp.sin(gam)), b * sp.sin(phi) * sq_m * sq_n / (a * m * n * sp.sin(gam))],
        [w.subs(rho2, b / n) for w in N_def], nsamp)
report(sp.simplify(m * (b / m) / n - b / n) == 0, "(2.143) rho2 = m rho1/n = b/n", "agrees")
prod2 = sq_m / m * sq_n / n
compare("(2.145) K_t for t = 2 generations equals (2.144)",
        [sp.sin(gam - phi) / sp.sin(gam) * prod2, b * sp.sin(phi) / (a * sp.sin(gam)) * prod2],
        [sp.sin(gam - phi) * sq_m * sq_n / (m * n * sp.sin(gam)), b * sp.sin(phi) * sq_m * sq_n / (a * m * n * sp.sin(gam))], nsamp)
remark("(2.144) the second generation scales CM by sqrt(b^2 + rho2^2 + 2 b rho2 cos(b phi/rho2))/b, i.e. the law of "
       "cosines with the AXIS radius b and the axis arc b phi, not with |CM| and the arc of the first-generation "
       "curve; a definition (a product of modulations), not the construction of 2.5 repeated literally")

# ============================================================================
print("== 2.7 contour arcs in general form (2.160)-(2.161); weights over (A1, A2, A3)")
u = sp.Function('u')(t)
v = sp.Function('v')(t)
w = sp.Function('w')(t)
E1, E2, E3 = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
B1 = E1 * (1 - u) + E3 * u
B2 = E3 * (1 - v) + E2 * v
Mg = B1 * (1 - w) + B2 * w
p160 = sp.Matrix([(u - 1) * w + 1 - u, v * w, (-u - v + 1) * w + u])
report(sp.simplify(Mg - p160) == sp.zeros(3, 1), "(2.160) M (B1, B2 eliminated)", "agrees")
ud, vd, wd = sp.diff(u, t), sp.diff(v, t), sp.diff(w, t)
pdot = sp.Matrix([ud * (w - 1) + wd * (u - 1), vd * w + v * wd, ud * (1 - w) - vd * w + wd * (1 - u - v)])
report(sp.simplify(sp.diff(Mg, t) - pdot) == sp.zeros(3, 1), "M' (derivative of (2.160))", "agrees")
report(sp.simplify(B2 - B1 - sp.Matrix([u - 1, v, 1 - u - v])) == sp.zeros(3, 1), "B2 - B1 = (u-1)A1 + vA2 + (1-u-v)A3", "agrees")
# tangency: M' parallel to B2 - B1 (both vectors: weight sums 0) <=> the 2x2 minor of their A1, A2 weights vanishes
minor = sp.expand(pdot[0] * (B2 - B1)[1] - pdot[1] * (B2 - B1)[0])
ws = sp.solve(minor, w)
report(len(ws) == 1 and sp.simplify(ws[0] - ud * v / (ud * v + vd * (1 - u))) == 0,
       "w = u'v/(u'v + v'(1 - u)) (w' cancels: the condition is linear in w)", "agrees")
wsol = ud * v / (ud * v + vd * (1 - u))
M161 = sp.simplify(Mg.subs(w, wsol))
Dd = ud * v + vd * (1 - u)
p161 = sp.Matrix([vd * (1 - u)**2 / Dd, ud * v**2 / Dd, (ud * v * (1 - v) + vd * u * (1 - u)) / Dd])
report(sp.simplify(M161 - p161) == sp.zeros(3, 1), "(2.161) M", "agrees")
report(sp.simplify((p161[0] + p161[1] + p161[2]) - 1) == 0, "(2.161) weights sum to 1 (compact form with A3 as origin)", "agrees")
M58 = sp.simplify(p161.subs({u: t, v: t}).doit())
report(sp.simplify(M58 - sp.Matrix([tb**2, t**2, 2 * t * tb])) == sp.zeros(3, 1), "(2.161) with u = v = t gives (2.58)", "agrees")
# numeric property: a concrete pair u, v, a 2D simplex; M' parallel to B2 - B1, ends A1, A2 with tangents A1A3, A3A2
A1n, A2n, A3n = (R(0), R(0)), (R(6), R(1)), (R(2), R(4))
for uf, vf, lab in (((sp.exp(t) - 1) / (sp.E - 1), t, "u = (e^t - 1)/(e - 1), v = t"), (t**2, sp.sin(sp.pi * t / 2), "u = t^2, v = sin(pi t/2)")):
    wt = (sp.diff(uf, t) * vf / (sp.diff(uf, t) * vf + sp.diff(vf, t) * (1 - uf)))
    B1n = tuple(A1n[i] * (1 - uf) + A3n[i] * uf for i in range(2))
    B2n = tuple(A3n[i] * (1 - vf) + A2n[i] * vf for i in range(2))
    Mn = tuple(B1n[i] * (1 - wt) + B2n[i] * wt for i in range(2))
    Md = tuple(sp.diff(Mn[i], t) for i in range(2))
    ok = all(abs(cross([num(Md[i], {t: tt}).real for i in range(2)],
                       [num(B2n[i] - B1n[i], {t: tt}).real for i in range(2)])) < TOL for tt in (R(1, 7), R(1, 2), R(4, 5)))
    e0 = [sp.limit(Mn[i], t, 0) for i in range(2)]
    e1 = [sp.limit(Mn[i], t, 1) for i in range(2)]
    ok &= all(sp.simplify(e0[i] - A1n[i]) == 0 and sp.simplify(e1[i] - A2n[i]) == 0 for i in range(2))
    report(ok, f"2.7 {lab}: M' parallel to B1B2 at t = 1/7, 1/2, 4/5; M(0) = A1, M(1) = A2")
    v0 = [sp.limit(Md[i], t, 0) for i in range(2)]
    v1 = [sp.limit(Md[i], t, 1) for i in range(2)]
    u0, vv1 = sp.diff(uf, t).subs(t, 0), sp.diff(vf, t).subs(t, 1)
    report(all(sp.simplify(v0[i] - 2 * u0 * (A3n[i] - A1n[i])) == 0 and
               sp.simplify(v1[i] - 2 * vv1 * (A2n[i] - A3n[i])) == 0 for i in range(2)),
           f"2.7 {lab}: M'(0) = 2u'(0)(A3 - A1) = {u0}*2(A3 - A1), M'(1) = 2v'(1)(A2 - A3) = {vv1}*2(A2 - A3)")
# the instance of contour_arc_general.pcs: u = t, v = t(1 + t)/2
ui, vi = t, t * (1 + t) / 2
wi = sp.diff(ui, t) * vi / (sp.diff(ui, t) * vi + sp.diff(vi, t) * (1 - ui))
Mi = sp.simplify(Mg.subs(w, wi).subs({u: ui, v: vi}).doit())
Mi_w = sp.Matrix([(1 + 2 * t) * tb**2 / (1 + 2 * t - t**2), t**2 * (1 + t)**2 / (2 * (1 + 2 * t - t**2)),
                  t * tb * (t**2 + 7 * t + 4) / (2 * (1 + 2 * t - t**2))])
report(sp.simplify(wi - t * (1 + t) / (1 + 2 * t - t**2)) == 0 and sp.simplify(Mi - Mi_w) == sp.zeros(3, 1) and
       sp.diff(Mi, t).subs(t, 0) == sp.Matrix([-2, 0, 2]) and sp.diff(Mi, t).subs(t, 1) == sp.Matrix([0, 3, -3]),
       "2.7 instance u = t, v = t(1 + t)/2 (scheme): w, M weights, M'(0) = 2(A3 - A1), M'(1) = 3(A2 - A3)")
remark("2.7: (2.161) needs v'(0) != 0 and u'(1) != 0 besides u(0) = v(0) = 0, u(1) = v(1) = 1 (otherwise the "
       "denominator u'v + v'(1 - u) vanishes at an end, e.g. u = v = t^2 gives 0/0 at t = 0), and the ends are "
       "regular points only if also u'(0) != 0 and v'(1) != 0 (M'(0) = 2u'(0)(A3 - A1), M'(1) = 2v'(1)(A2 - A3))")

# ============================================================================
print("== 2.8 cycloid: C = (0,0), B = (pi r, 0), A = (0, 2r) (|CB| = pi r, |CA| = 2r, angle ACB = 90 deg)")
Cc, Ac, Bc = (0, 0), (0, 2 * r_), (sp.pi * r_, 0)
# a circle of radius r rolls on the line CB towards C, its contact point starting at B (the cusp)
Oc = (sp.pi * r_ - r_ * phi, r_)
Mc = (Oc[0] + r_ * sp.sin(phi), Oc[1] - r_ * sp.cos(phi))     # rotated by phi counterclockwise from the bottom
Tc = (Oc[0], 0)
w_cyc = decompose(Mc, Cc, Ac, Bc)
csamp = [{r_: R(3, 2), phi: rnd(0, 3.14)} for _ in range(4)] + [{r_: R(1), phi: rnd(3.15, 6.28)} for _ in range(3)]
compare("2.8 centre O = (A - C)/2 + (B - C)(pi - phi)/pi + C, M - O = (A - C)(-cos phi/2) + (B - C) sin phi/pi",
        list(decompose(Oc, Cc, Ac, Bc)) + [w_cyc[0] - R(1, 2), w_cyc[1] - (sp.pi - phi) / sp.pi],
        [R(1, 2), (sp.pi - phi) / sp.pi, -sp.cos(phi) / 2, sp.sin(phi) / sp.pi], [{r_: 2, phi: rnd(0, 6)} for _ in range(3)])
compare("2.8 P = (A - C)(1 - cos phi)/2 + C: M's component along CA", [(1 - sp.cos(phi)) / 2], [w_cyc[0]], csamp)
compare("(3.11) M = P + Q - C = (A - C)(1 - cos phi)/2 + (B - C)(pi - phi + sin phi)/pi + C",
        [(1 - sp.cos(phi)) / 2, (sp.pi - phi + sp.sin(phi)) / sp.pi], w_cyc, csamp)
ok = True
for s in csamp:
    Mn, On, Tn = npt(Mc, s), npt(Oc, s), npt(Tc, s)
    Bn = npt(Bc, s)
    ok &= abs(ndist(Mn, On) - num(r_, s).real) < TOL                       # on the rolling circle
    ok &= abs(ndist(Tn, Bn) - num(r_ * phi, s).real) < TOL                # rolled distance = r phi
    arc = num(r_, s).real * nangle(Tn, On, Mn)                              # arc TM (angle TOM = phi mod 2pi)
    pv = num(phi, s).real
    ok &= abs(arc - num(r_, s).real * (pv if pv <= mp.pi else 2 * mp.pi - pv)) < TOL
    Md = [num(sp.diff(Mc[i], phi), s).real for i in range(2)]
    ok &= abs(Md[0] * (Mn[0] - Tn[0]) + Md[1] * (Mn[1] - Tn[1])) < TOL      # T is the instantaneous centre
report(ok, "(3.11) rolling without slipping: |OM| = r, |BT| = arc TM = r phi, M' perpendicular to TM (7 points)")
d0 = [sp.diff(w_, phi).subs(phi, 0) for w_ in w_cyc]
dpi = [sp.simplify(sp.diff(w_, phi).subs(phi, sp.pi)) for w_ in w_cyc]
d20 = [sp.diff(w_, phi, 2).subs(phi, 0) for w_ in w_cyc]
report(d0 == [0, 0] and d20 == [R(1, 2), 0] and dpi == [0, -2 / sp.pi],
       "(3.11) phi = 0: the cusp B, tangent along CA; phi = pi: the vertex A, tangent parallel to CB")
compare("2.8 theta form = (3.11) with phi = 2 theta", [(1 - sp.cos(2 * theta)) / 2, (sp.pi - 2 * theta + sp.sin(2 * theta)) / sp.pi],
        [w_.subs(phi, 2 * theta) for w_ in w_cyc], [{theta: rnd(0, 1.57)} for _ in range(4)])
ok = all(abs(nangle(npt(Mc, s), npt(Tc, s), npt(Bc, s)) - num(phi / 2, s).real) < TOL for s in csamp[:4])
report(ok, "2.8 theta = phi/2 is the angle MTB between the chord TM and the line CB at the contact point T "
           "(tangent-chord angle; figure 2.34 missing), so 0 <= theta <= pi/2")
# concave arc: the circle rolls under the line through A parallel to CB, cusp at A
Oq = (r_ * (sp.pi - phi), r_)
Mq = (Oq[0] - r_ * sp.sin(sp.pi - phi), Oq[1] + r_ * sp.cos(sp.pi - phi))
Tq = (Oq[0], 2 * r_)
w_cc = decompose(Mq, Cc, Ac, Bc)
compare("(3.12) M = (A - C)(1 - cos phi)/2 + (B - C)(pi - phi - sin phi)/pi + C",
        [(1 - sp.cos(phi)) / 2, (sp.pi - phi - sp.sin(phi)) / sp.pi], w_cc, csamp)
ok = True
for s in csamp:
    Mn, On, Tn = npt(Mq, s), npt(Oq, s), npt(Tq, s)
    ok &= abs(ndist(Mn, On) - num(r_, s).real) < TOL
    ok &= abs(ndist(Tn, npt(Ac, s)) - num(r_ * (sp.pi - phi), s).real) < TOL * 10 or num(phi, s).real > mp.pi
    Md = [num(sp.diff(Mq[i], phi), s).real for i in range(2)]
    ok &= abs(Md[0] * (Mn[0] - Tn[0]) + Md[1] * (Mn[1] - Tn[1])) < TOL
report(ok, "(3.12) rolling under the line through A parallel to CB: |OM| = r, |AT| = r(pi - phi), M' perpendicular to TM")
d0 = [sp.simplify(sp.diff(w_, phi).subs(phi, 0)) for w_ in w_cc]
dpi = [sp.simplify(sp.diff(w_, phi).subs(phi, sp.pi)) for w_ in w_cc]
d2pi = [sp.simplify(sp.diff(w_, phi, 2).subs(phi, sp.pi)) for w_ in w_cc]
report(d0 == [0, -2 / sp.pi] and dpi == [0, 0] and d2pi == [-R(1, 2), 0],
       "(3.12) phi = 0: B with tangent along BC; phi = pi: the cusp A with tangent along AC (the text's "
       "'arc AB with tangents AC and BC, a cusp at A' describes (3.12), fig. 2.36)")
misprint("2.8 equation numbers", "the two equations of section 2.8 are numbered (3.11) and (3.12) (chapter 3's "
         "numbers); in chapter 2 they follow (2.161), i.e. (2.162) and (2.163)")
remark("2.8: the text between 'Эту' and 'P = (A - C)(1 - cos phi)/2 + C' (the definition of Q and figure 2.34) is "
       "missing from the extracted text; Q = (B - C)(pi - phi + sin phi)/pi + C follows from M = P + Q - C")

# ============================================================================
print("== article: circle through three points, eq. (5); a = |AC|^2, b = |BA|^2, c = |CB|^2")
TRIS = [((R(0), R(0)), (R(5), R(1)), (R(2), R(4))), ((R(-1), R(2)), (R(3), R(-2)), (R(7), R(3))),
        ((R(1), R(1)), (R(2), R(5)), (R(-3), R(2)))]
al, be, ga = sp.symbols('alpha_ beta_ gamma_')
for k, (An, Bn, Cn) in enumerate(TRIS):
    sq = lambda P, Q: (P[0] - Q[0])**2 + (P[1] - Q[1])**2
    av, bv, cv = sq(An, Cn), sq(Bn, An), sq(Cn, Bn)
    # independent: the conic through A, B, C with t = 0, 1, oo there is (al(1-t) : be t : ga t(t-1)) in
    # barycentrics; make it the circle through A, B, C
    X, Y = sp.symbols('X Y')
    circ = sp.Matrix([[X**2 + Y**2, X, Y, 1]] + [[P[0]**2 + P[1]**2, P[0], P[1], 1] for P in (An, Bn, Cn)]).det()
    wts = (1 - t, be * t, ga * t * (t - 1))
    Dn = sum(wts)
    Xt = sum(wts[i] * (An, Bn, Cn)[i][0] for i in range(3))
    Yt = sum(wts[i] * (An, Bn, Cn)[i][1] for i in range(3))
    numer = sp.Poly(sp.cancel(circ.subs({X: Xt / Dn, Y: Yt / Dn}) * Dn**2), t)
    sol = sp.solve(numer.coeffs(), [be, ga], dict=True)
    sol = [s for s in sol if s[be] != 0 and s[ga] != 0]
    printed = (cv, av, bv)            # (5): weights c(1-t), a t, b t(t-1)
    ok = len(sol) == 1 and sp.simplify(sol[0][be] - printed[1] / printed[0]) == 0 and \
        sp.simplify(sol[0][ga] - printed[2] / printed[0]) == 0
    report(ok, f"(5) triangle {k + 1}: the circle through A, B, C with t = 0, 1, oo is "
               "(A c(1-t) + B a t + C b t(t-1))/(b t^2 + (a-c-b) t + c)", "agrees")
a5, b5, c5 = sp.symbols('a5 b5 c5', positive=True)
xA, yA, xB, yB, xC, yC = sp.symbols('x_A y_A x_B y_B x_C y_C', real=True)
rA, rB, rC = sp.Matrix([xA, yA]), sp.Matrix([xB, yB]), sp.Matrix([xC, yC])
D5 = b5 * t**2 + (a5 - c5 - b5) * t + c5
r5 = (rC * b5 * t**2 + (a5 * rB - c5 * rA - b5 * rC) * t + c5 * rA) / D5
met = {a5: (xA - xC)**2 + (yA - yC)**2, b5: (xB - xA)**2 + (yB - yA)**2, c5: (xC - xB)**2 + (yC - yB)**2}
report(sp.simplify(sp.expand((a5 - c5 - b5)**2 - 4 * b5 * c5).subs(met) +
                   4 * ((xA - xB) * (yC - yB) - (yA - yB) * (xC - xB))**2) == 0,
       "(5) denominator: discriminant (a - b - c)^2 - 4bc = -4 (2 area ABC)^2 < 0, so D > 0 and t in [0, oo] is the arc A B C")
# tangents at A (t = 0) and C (t = oo: s = 1/t -> 0)
dA = sp.simplify(sp.diff(r5, t).subs(t, 0) * c5)
r5s = sp.simplify(r5.subs(t, 1 / s_))
dC = sp.simplify(sp.diff(r5s, s_).subs(s_, 0) * b5)
sampA = [dict(zip((xA, yA, xB, yB, xC, yC), (P[0][0], P[0][1], P[1][0], P[1][1], P[2][0], P[2][1]))) for P in TRIS]
sampA = [dict(s, **{str(k_): v_.subs(s) for k_, v_ in met.items()}) for s in sampA]
SYM.update({'a5': a5, 'b5': b5, 'c5': c5})
kd = dA[1] / dA[0]
k_pr = (a5 * (yB - yA) + b5 * (yA - yC)) / (a5 * (xB - xA) + b5 * (xA - xC))
compare("tangent at A: k = (a y_BA + b y_AC)/(a x_BA + b x_AC)", [k_pr], [kd], sampA)
k1d = dC[1] / dC[0]
k1_pr = (a5 * (yC - yB) + b5 * (yA - yC)) / (a5 * (xC - xB) + b5 * (xA - xC))
k1_co = (a5 * (yC - yB) + c5 * (yA - yC)) / (a5 * (xC - xB) + c5 * (xA - xC))
compare("tangent at C: k1 = (a y_CB + b y_AC)/(a x_CB + b x_AC)", [k1_pr], [k1d], sampA, expect_ok=False,
        why="the derivative of (5) at t = oo is (a (r_B - r_C) + c (r_C - r_A))/b, so the second coefficient is c = "
            "|CB|^2, not b = |BA|^2 (the tangent at C is c (A - C) - a (B - C), the mirror of the one at A, "
            "a (B - A) - b (C - A), under A <-> C, b <-> c): correct k1 = (a y_CB + c y_AC)/(a x_CB + c x_AC)",
        correct=[k1_co])
# centre and radius (normals at A and C)
xO = (xC * kd - xA * k1d - (yA - yC) * kd * k1d) / (kd - k1d)
yO = ((xA - xC) + yA * kd - yC * k1d) / (kd - k1d)
Rp = sp.sqrt(kd**2 + 1) / (kd - k1d) * ((yA - yC) * k1d + (xA - xC))
ok = True
okp = True
for s in sampA:
    On = (num(xO, s).real, num(yO, s).real)
    Rn = abs(num(Rp, s).real)
    for tt in (0, R(1, 3), 1, R(5, 2), 40):
        Pn = (num(r5[0], dict(s, t=tt)).real, num(r5[1], dict(s, t=tt)).real)
        ok &= abs(ndist(Pn, On) - Rn) < TOL
    ok &= abs(ndist((num(xC, s).real, num(yC, s).real), On) - Rn) < TOL
    xOp = (xC * kd - xA * k1_pr - (yA - yC) * kd * k1_pr) / (kd - k1_pr)
    yOp = ((xA - xC) + yA * kd - yC * k1_pr) / (kd - k1_pr)
    okp &= abs(ndist((num(xOp, s).real, num(yOp, s).real), (num(xA, s).real, num(yA, s).real)) -
               ndist((num(xOp, s).real, num(yOp, s).real), (num(xC, s).real, num(yC, s).real))) < TOL
report(ok, "x_O, y_O, R (with the tangent slopes k, k1 of the curve): |OM| = |R| at t = 0, 1/3, 1, 5/2, 40 and at C",
       "agrees (R as printed is signed: take |R|)")
report(not okp, "with the printed k1 the formulas for x_O, y_O give a point with |OA| != |OC| (not the centre): "
       "the k1 misprint propagates to the centre and radius")
# barycentric form used by the schemes: M = (A c (1-t) + B a t + C b t (t-1))/D
report(sp.simplify(r5 - (rA * c5 * (1 - t) + rB * a5 * t + rC * b5 * t * (t - 1)) / D5) == sp.zeros(2, 1),
       "(5) in point form: M = A c(1-t)/D + B a t/D + C b t(t-1)/D, D = b t^2 + (a - c - b) t + c")
# the circumcentre in point form (for the schemes): weights c(a+b-c), a(b+c-a), b(c+a-b) over 2(ab+bc+ca)-a^2-b^2-c^2
Wc = (c5 * (a5 + b5 - c5), a5 * (b5 + c5 - a5), b5 * (c5 + a5 - b5))
Sc = sum(Wc)
Ov = (rA * Wc[0] + rB * Wc[1] + rC * Wc[2]) / Sc
ok = all(abs(ndist([num(Ov[i], s).real for i in range(2)], [num(rA[i], s).real for i in range(2)]) -
             ndist([num(Ov[i], s).real for i in range(2)], [num(rC[i], s).real for i in range(2)])) < TOL and
         abs(ndist([num(Ov[i], s).real for i in range(2)], [num(rA[i], s).real for i in range(2)]) -
             ndist([num(Ov[i], s).real for i in range(2)], [num(rB[i], s).real for i in range(2)])) < TOL for s in sampA)
report(ok, "circumcentre O = (A c(a+b-c) + B a(b+c-a) + C b(c+a-b))/(2(ab+bc+ca) - a^2 - b^2 - c^2) (article's a, b, c)")
ok = True
for s in sampA:
    On = [num(Ov[i], s).real for i in range(2)]
    An_, Cn_ = [num(rA[i], s).real for i in range(2)], [num(rC[i], s).real for i in range(2)]
    R2n = ndist(On, An_)**2
    ok &= abs(R2n - num(a5 * b5 * c5 / (2 * (a5 * b5 + b5 * c5 + c5 * a5) - a5**2 - b5**2 - c5**2), s).real) < TOL
    Bn_ = [num(rB[i], s).real for i in range(2)]
    tp = [num(a5, s).real * (Cn_[i] - Bn_[i]) + num(b5, s).real * (An_[i] - Cn_[i]) for i in range(2)]
    dotp = tp[0] * (Cn_[0] - On[0]) + tp[1] * (Cn_[1] - On[1])
    ok &= abs(dotp - num(a5 * (c5 - b5) / 2, s).real) < TOL
report(ok, "R^2 = abc/(2(ab+bc+ca) - a^2 - b^2 - c^2); the printed k1's direction a(C - B) + b(A - C) has "
       "dot with C - O = a(c - b)/2 (not tangent unless |CB| = |BA|)")
# |M - O|^2 for a vector with weights (x, y, z), sum 0: -(c y z + a z x + b x y)  (a' ^2 = c, b'^2 = a, c'^2 = b)
xx, yy, zz = sp.symbols('xx yy zz')
vec = rA * xx + rB * yy + rC * (-xx - yy)
report(sp.expand((vec.T * vec)[0] + (c5 * yy * (-xx - yy) + a5 * (-xx - yy) * xx + b5 * xx * yy)).subs(met).expand() == 0,
       "metric of the simplex: |x A + y B + z C|^2 = -(c y z + a z x + b x y) for x + y + z = 0")

# ============================================================================
print("== article: circle through two points A(-a, 0), C(a, 0) with the tangent AB, B(0, b)")
xs_, ys_ = sp.symbols('x y', real=True)
A2, B2p, C2 = (-a, 0), (0, b), (a, 0)
k_AB = (B2p[1] - A2[1]) / (B2p[0] - A2[0])
report(sp.simplify(k_AB - b / a) == 0, "line AB: y = (b/a) x + b", "agrees")
# centre: on the normal to AB at A and on the perpendicular bisector x = 0 of AC
yK = sp.solve(sp.Eq((0 - A2[0]) * (B2p[0] - A2[0]) + (ys_ - A2[1]) * (B2p[1] - A2[1]), 0), ys_)[0]
report(sp.simplify(yK + a**2 / b) == 0, "line AK: y = -(a/b) x - a^2/b, K = (0, -a^2/b)", "agrees")
Rk = sp.sqrt(a**2 + yK**2)
report(sp.simplify(Rk - a * sp.sqrt(a**2 + b**2) / b) == 0, "R = a sqrt(a^2 + b^2)/b", "agrees")
report(sp.expand(b**2 * (xs_**2 + (ys_ - yK)**2 - Rk**2) - (b**2 * xs_**2 + (b * ys_ + a**2)**2 - a**2 * (a**2 + b**2))) == 0,
       "(6) b^2 x^2 + (b y + a^2)^2 = a^2 (a^2 + b^2)", "agrees")
a1 = a * (sp.sqrt(a**2 + b**2) - a)
yE = sp.simplify(yK + Rk)
report(sp.simplify(yE - a1 / b) == 0, "E = (0, a1/b), a1 = a(sqrt(a^2 + b^2) - a): the top of the circle", "agrees")
# (8): the conic r = (r_A + v r_B t + r_C t^2)/(1 + v t + t^2) through E at t = 1
vv = sp.symbols('v')
vsol = sp.solve(sp.Eq(vv * b / (2 + vv), yE), vv)[0]
# v from its definition in (8): E_AB = CE x AB, v = -(A - E_AB)/(B - E_AB) (x coordinates)
xEab = sp.solve(sp.Eq(yE * (1 - xs_ / a), b / a * (xs_ + a)), xs_)[0]
vdef = -(A2[0] - xEab) / (B2p[0] - xEab)
report(sp.simplify(vdef - vsol) == 0, "(8) v = -(r_A - r_E_AB)/(r_B - r_E_AB) (E_AB = CE x AB) puts E at t = 1")
absamp = [{a: R(2), b: R(3)}, {a: R(5), b: R(1, 2)}, {a: R(1), b: R(7)}]
compare("v = 2 a1/(b - a1)", [2 * a1 / (b - a1)], [vsol], absamp, expect_ok=False,
        why="printed v = 2a1/(b - a1) adds a length to an area (a1 = a(sqrt(a^2+b^2) - a) is a length^2, "
            "E = (0, a1/b)); from (8) v = 2 y_E/(b - y_E) with y_E = a1/b: correct v = 2 a1/(b^2 - a1) "
            "= 2a/sqrt(a^2 + b^2) = 2 cos(angle BAC) (printed and correct agree only for b = 1)",
        correct=[2 * a1 / (b**2 - a1)])
report(sp.simplify(2 * a1 / (b**2 - a1) - 2 * a / sp.sqrt(a**2 + b**2)) == 0, "2 a1/(b^2 - a1) = 2a/sqrt(a^2 + b^2)")
xt = a * (t**2 - 1) / (1 + vv * t + t**2)
yt = vv * b * t / (1 + vv * t + t**2)
report(sp.simplify(xt - (A2[0] + vv * B2p[0] * t + C2[0] * t**2) / (1 + vv * t + t**2)) == 0 and
       sp.simplify(yt - (A2[1] + vv * B2p[1] * t + C2[1] * t**2) / (1 + vv * t + t**2)) == 0,
       "x = a(t^2 - 1)/(1 + vt + t^2), y = vbt/(1 + vt + t^2) is (8) with (7)", "agrees")
for vname, vval, expect in (("correct v", 2 * a / sp.sqrt(a**2 + b**2), True), ("printed v", 2 * a1 / (b - a1), False)):
    ok = True
    for s in absamp:
        Kn = (mp.mpf(0), num(yK, s).real)
        dists = [ndist((num(xt.subs(vv, vval), dict(s, t=tt)).real, num(yt.subs(vv, vval), dict(s, t=tt)).real), Kn)
                 for tt in (R(1, 5), 1, R(3, 2), 9)]
        ok &= all(abs(d - num(Rk, s).real) < TOL for d in dists)
    if expect:
        report(ok, f"with the {vname}: |MK| = R at t = 1/5, 1, 3/2, 9 (3 cases)")
    elif ok:
        report(False, f"with the {vname}", "unexpectedly on the circle")
    else:
        misprint("article, two points + tangent: v", "with the printed v the curve is not the circle (|MK| != R), "
                 "except for b = 1")
# tangency at A and C
vc = 2 * a / sp.sqrt(a**2 + b**2)
dA2 = [sp.diff(e.subs(vv, vc), t).subs(t, 0) for e in (xt, yt)]
report(sp.simplify(cross(dA2, (B2p[0] - A2[0], B2p[1] - A2[1]))) == 0,
       "tangent at A (t = 0) is AB; by symmetry the tangent at C (t = oo) is CB", "agrees")
report(sp.simplify(cross([sp.diff(sp.cancel(e.subs(t, 1 / s_)), s_).subs(s_, 0).subs(vv, vc) for e in (xt, yt)],
                         (B2p[0] - C2[0], B2p[1] - C2[1]))) == 0, "tangent at C is CB (computed)")
report(sp.simplify(yK + a**2 / b) == 0 and sp.simplify(yE * b**2 / b - a1) == 0,
       "point forms of the scheme: K = Om + (B - Om)(-a^2/b^2), E = Om + (B - Om) a1/b^2 (Om the midpoint of AC)")
ok = True
for An_, Cn_, Dn_ in (((R(0), R(0)), (R(5), R(1)), (R(1), R(3))), ((R(2), R(-1)), (R(-3), R(2)), (R(4), R(4))),
                      ((R(0), R(0)), (R(4), R(0)), (R(-1), R(2)))):
    dAC2 = (Cn_[0] - An_[0])**2 + (Cn_[1] - An_[1])**2
    dotD = (Dn_[0] - An_[0]) * (Cn_[0] - An_[0]) + (Dn_[1] - An_[1]) * (Cn_[1] - An_[1])
    lam = dAC2 / (2 * dotD)
    Bp = tuple(An_[i] + (Dn_[i] - An_[i]) * lam for i in range(2))
    vg = 2 * dotD / (sp.sqrt(dAC2) * sp.sqrt((Dn_[0] - An_[0])**2 + (Dn_[1] - An_[1])**2))
    Mg2 = [(An_[i] + Bp[i] * vg * t + Cn_[i] * t**2) / (1 + vg * t + t**2) for i in range(2)]
    # independent centre: on the normal at A (perpendicular to AD) and equidistant from A and C
    kx, ky = sp.symbols('kx ky')
    ks = sp.solve([(kx - An_[0]) * (Dn_[0] - An_[0]) + (ky - An_[1]) * (Dn_[1] - An_[1]),
                   (kx - An_[0])**2 + (ky - An_[1])**2 - (kx - Cn_[0])**2 - (ky - Cn_[1])**2], [kx, ky], dict=True)[0]
    Kn = (mp.mpf(str(sp.N(ks[kx], 40))), mp.mpf(str(sp.N(ks[ky], 40))))
    Rn = ndist(Kn, [mp.mpf(x_) for x_ in An_])
    for tt in (R(1, 4), 1, 3, -R(1, 2)):
        ok &= abs(ndist([num(Mg2[i], {t: tt}).real for i in range(2)], Kn) - Rn) < TOL
    ok &= abs(ndist([mp.mpf(x_) for x_ in Bp], [mp.mpf(x_) for x_ in An_]) -
              ndist([mp.mpf(x_) for x_ in Bp], [mp.mpf(x_) for x_ in Cn_])) < TOL
report(ok, "general form: D on the tangent at A, B = A + (D - A)|AC|^2/(2 (D - A).(C - A)) (|BA| = |BC|), "
       "v = 2 cos(angle DAC): |KM| = R (3 configurations, one with angle DAC obtuse)")
remark("point form used by the schemes: M = (A + B v t + C t^2)/(1 + v t + t^2), v = 2 cos(angle BAC), "
       "valid whenever |BA| = |BC| (B the pole of AC); t in [0, oo] is the arc A E C")

# ----------------------------------------------------------------------------
finish()
