/*
 * natural_fit.c - fitting natural-parametrization segments (natural.h).
 *
 * G1, the linear law (Bertolazzi & Frego, "G1 fitting with clothoids",
 * 2015).  In the chord's frame (chord length r, direction phi) the angles
 * are p0 = th0 - phi and p1 = th1 - phi, reduced to (-pi, pi], and
 * d = p1 - p0.  With the scaled arc tau = s / L in [0, 1] the angle is
 *   psi(tau) = p0 + (d - A) tau + A tau^2,     A = k1 L^2 / 2,
 * which ends at p1 whatever A and L; the end point lies on the chord iff
 *   g(A) = int_0^1 sin psi = 0,
 * one equation in one unknown, with g'(A) = int_0^1 (tau^2 - tau) cos psi.
 * Then L = r / int_0^1 cos psi, k0 = (d - A) / L, k1 = 2 A / L^2.  Newton
 * from the initial guess guess_A() (a fit of the solution over the square
 * of angles, made by bench/bench_natural.c's --fit-guess) converges to the
 * root with int cos psi > 0 of the paper (the minimal winding).
 *
 * Quadratic and cubic laws (the article's G2, G3 joints).  The start
 * curvature kc (and for the cubic its derivative kd) are given; the top
 * coefficient follows from the end angle, the article's (14), (15) as
 * corrected (docs/errata.md, N1-N2):
 *   quadratic  a = 3 (D - b S^2/2 - c S) / S^3
 *   cubic      a = 4 (D - b S^3/3 - c S^2/2 - d S) / S^4
 * where D is the turning (the clothoid's, fixing the winding).  The
 * unknowns are u = (beta, S) with beta = b S^2 (quadratic) or b S^3 / 3
 * (cubic), which makes the phase linear in beta:
 *   quadratic  psi = (D - beta/2 - c S) tau^3 + beta/2 tau^2 + c S tau
 *   cubic      psi = (D - beta - c S^2/2 - d S) tau^4 + beta tau^3
 *                    + c S^2/2 tau^2 + d S tau
 * and the two residuals are the end point's offset, S int_0^1 e^{i psi}
 * minus the chord, with the exact Jacobian from the moments int tau^m
 * e^{i psi}.  Damped Newton (lsq_newton) by continuation: at lambda = 0
 * the start values are the clothoid's own (then the law's top coefficient
 * and, for the cubic, b vanish: the clothoid is an exact solution), and
 * lambda runs to 1 in steps that halve on a failure.
 */
#include "runtime/natural.h"

#include <math.h>
#include <string.h>

#include "runtime/lsq.h"

/* The initial guess of A from the reduced angles: A ~ (p0 + p1) times a
 * symmetric polynomial in x = p0/pi, y = p1/pi, fitted by least squares to
 * the solutions over a 41 x 41 grid of (-0.99 pi, 0.99 pi)^2 (bench_natural
 * --fit-guess prints the coefficients). */
static double guess_A(double p0, double p1)
{
    static const double cf[6] = {2.99732469107745,   0.787605180049466,
                                 -0.402819013099702, -0.543715083622581,
                                 0.20462859942196,   -0.0170087768353651};
    double x = p0 / NAT_PI, y = p1 / NAT_PI, xy = x * y, q = x * x + y * y;
    return (p0 + p1) *
           (cf[0] + xy * (cf[1] + xy * cf[2]) + q * (cf[3] + xy * cf[4]) +
            cf[5] * (x * x * x * x + y * y * y * y));
}

static void stats_clear(NatStats *st)
{
    st->iterations = st->integrals = 0;
    st->error = 0;
}

static void end_error(const NatSegment *g, double x1, double y1, NatStats *st)
{
    double x, y;
    nat_point(g, g->length, &x, &y);
    st->error = hypot(x - x1, y - y1);
}

/* a fitted segment is an answer only when its coefficients are numbers
 * and its end point is where it should be (within 1e-9 of the chord):
 * at scales beyond double precision (a chord of 1e-200: k1 ~ 1e400) the
 * coefficients overflow or vanish, which must fail, not print */
static int settled(const NatSegment *g, double r, const NatStats *st)
{
    for (int j = 0; j <= g->degree; j++)
        if (!isfinite(g->k[j]))
            return -1;
    return isfinite(g->length) && st->error <= 1e-9 * r ? 0 : -1;
}

/* Newton on g(A); returns 0 with *A the root, *X = int cos psi there */
static int solve_A(double p0, double p1, double *A, double *X, NatStats *st)
{
    double d = p1 - p0, a = guess_A(p0, p1);
    for (int it = 0; it < 50; it++) {
        double p[3] = {p0, d - a, a}, c[3], s[3];
        nat_moments(p, 2, 3, c, s);
        st->integrals++;
        double g = s[0], dg = c[2] - c[1];
        if (fabs(g) <= 1e-15 || (it > 0 && fabs(g) <= 4e-15 * (1 + fabs(a)))) {
            *A = a;
            *X = c[0];
            return c[0] > 0 ? 0 : -1;
        }
        if (dg == 0 || !isfinite(dg))
            return -1;
        double step = g / dg;
        a -= step;
        st->iterations++;
        if (fabs(step) <= 1e-15 * (1 + fabs(a))) {
            double q[3] = {p0, d - a, a};
            nat_moments(q, 2, 1, c, s);
            st->integrals++;
            *A = a;
            *X = c[0];
            return c[0] > 0 ? 0 : -1;
        }
    }
    return -1;
}

int nat_fit_g1(double x0, double y0, double th0, double x1, double y1,
               double th1, NatSegment *seg, NatStats *st)
{
    NatStats local;
    if (!st)
        st = &local;
    stats_clear(st);
    memset(seg, 0, sizeof *seg);
    seg->x0 = x0, seg->y0 = y0, seg->phi0 = th0, seg->degree = 1;
    double dx = x1 - x0, dy = y1 - y0, r = hypot(dx, dy);
    if (!(r > 0) || !isfinite(r) || !isfinite(th0) || !isfinite(th1))
        return -1;
    double phi = atan2(dy, dx);
    double p0 = nat_reduce_angle(th0 - phi), p1 = nat_reduce_angle(th1 - phi),
           A, X;
    if (solve_A(p0, p1, &A, &X, st) != 0)
        return -1;
    double L = r / X;
    seg->length = L;
    seg->k[0] = (p1 - p0 - A) / L;
    seg->k[1] = 2 * A / (L * L);
    end_error(seg, x1, y1, st);
    return settled(seg, r, st);
}

/* ---- quadratic and cubic laws ------------------------------------------- */

typedef struct LawCtx {
    NatLaw law;
    double th0, D; // start angle, turning
    double c, d;   // quadratic: c = k(0); cubic: c = k'(0), d = k(0)
    double ex, ey; // the end point relative to the start
    double smax;   // lengths beyond it are not tried (200 chords)
    NatStats *st;
} LawCtx;

/* psi's coefficients for u = (beta, S) */
static int law_phase(const LawCtx *L, double beta, double S, double *p)
{
    p[0] = L->th0;
    if (L->law == NAT_QUADRATIC) {
        p[1] = L->c * S;
        p[2] = beta / 2;
        p[3] = L->D - beta / 2 - L->c * S;
        return 3;
    }
    p[1] = L->d * S;
    p[2] = L->c * S * S / 2;
    p[3] = beta;
    p[4] = L->D - beta - L->c * S * S / 2 - L->d * S;
    return 4;
}

static int law_fn(void *ctx, const double *u, double *r, double *J)
{
    LawCtx *L = ctx;
    double beta = u[0], S = u[1], p[5], c[5], s[5];
    if (!(S > 0) || !(S < L->smax) || !isfinite(beta))
        return 1;
    int deg = law_phase(L, beta, S, p);
    double turn = 0;
    for (int j = 1; j <= deg; j++)
        turn += j * fabs(p[j]);
    if (!(turn < 2000)) // a bound of the turning: a spiral, not this curve
        return 1;
    nat_moments(p, deg, deg + 1, c, s);
    L->st->integrals++;
    r[0] = S * c[0] - L->ex;
    r[1] = S * s[0] - L->ey;
    if (!J)
        return 0;
    /* dz = i e^{i psi} dpsi: d(x, y) = S (-int sin * dpsi, int cos * dpsi) */
    double wb[5] = {0}, ws[5] = {0}; // dpsi/dbeta, dpsi/dS by powers of tau
    if (L->law == NAT_QUADRATIC) {
        wb[2] = 0.5, wb[3] = -0.5;
        ws[1] = L->c, ws[3] = -L->c;
    } else {
        wb[3] = 1, wb[4] = -1;
        ws[1] = L->d, ws[2] = L->c * S, ws[4] = -L->c * S - L->d;
    }
    double sb = 0, cb = 0, ss = 0, cs = 0;
    for (int m = 0; m <= deg; m++) {
        sb += wb[m] * s[m], cb += wb[m] * c[m];
        ss += ws[m] * s[m], cs += ws[m] * c[m];
    }
    J[0] = -S * sb;       // dx/dbeta
    J[1] = c[0] - S * ss; // dx/dS
    J[2] = S * cb;        // dy/dbeta
    J[3] = s[0] + S * cs; // dy/dS
    return 0;
}

static int law_newton(LawCtx *L, double *u)
{
    LsqOptions o;
    LsqResult res;
    lsq_options_default(&o);
    o.max_iter = 40;
    o.gtol = 1e-14 * fmax(1, hypot(L->ex, L->ey));
    o.xtol = 1e-15;
    double w[2] = {u[0], u[1]};
    lsq_newton(w, 2, law_fn, L, &o, &res);
    L->st->iterations += res.iterations;
    /* converged, and to the end point (a relative step below xtol far
     * from it is a stall, not a solution) */
    double r[2];
    if (!res.converged || !(w[1] > 0) || law_fn(L, w, r, NULL) ||
        hypot(r[0], r[1]) > 1e-12 * fmax(1, hypot(L->ex, L->ey)))
        return -1;
    u[0] = w[0], u[1] = w[1];
    return 0;
}

/* the law's coefficients from u */
static void law_coef(const LawCtx *L, const double *u, NatSegment *seg)
{
    double beta = u[0], S = u[1];
    seg->length = S;
    seg->degree = L->law;
    if (L->law == NAT_QUADRATIC) {
        seg->k[0] = L->c;
        seg->k[1] = beta / (S * S);
        seg->k[2] = 3 * (L->D - beta / 2 - L->c * S) / (S * S * S);
    } else {
        seg->k[0] = L->d;
        seg->k[1] = L->c;
        seg->k[2] = 3 * beta / (S * S * S);
        seg->k[3] =
            4 * (L->D - beta - L->c * S * S / 2 - L->d * S) / (S * S * S * S);
    }
}

/* from the clothoid's (c0, d0), where u is a solution, to (c1, d1) in
 * steps that double after a success and halve after a failure */
static int continuation(LawCtx *L, double c0, double d0, double c1, double d1,
                        double *u)
{
    double lam = 0, dl = 1;
    while (lam < 1) {
        double next = fmin(1, lam + dl), v[2] = {u[0], u[1]};
        L->c = c0 + next * (c1 - c0);
        L->d = d0 + next * (d1 - d0);
        if (law_newton(L, v) == 0) {
            lam = next, u[0] = v[0], u[1] = v[1];
            dl *= 2;
        } else if ((dl /= 2) < 1.0 / 256)
            return -1;
    }
    return 0;
}

/* When the continuation meets a fold: Newton at the target values from a
 * grid of starts (lengths 1 to 4 clothoid lengths, beta of either sign up
 * to 10 times the turning's scale); the shortest solution wins. */
static int multistart(LawCtx *L, double c1, double d1, double S0, double *u)
{
    L->c = c1, L->d = d1;
    static const double sm[] = {1, 1.3, 1.7, 2.2, 3, 4};
    static const double bm[] = {0, 1, -1, 3, -3, 10, -10};
    double scale = 1 + fabs(L->D) + fabs(L->c) * S0 + fabs(L->d) * S0;
    double best = INFINITY;
    for (size_t i = 0; i < sizeof sm / sizeof sm[0]; i++)
        for (size_t j = 0; j < sizeof bm / sizeof bm[0]; j++) {
            double v[2] = {bm[j] * scale, sm[i] * S0};
            if (law_newton(L, v) == 0 && v[1] < best) {
                best = v[1];
                u[0] = v[0], u[1] = v[1];
            }
        }
    return isfinite(best) ? 0 : -1;
}

int nat_fit_law(NatLaw law, double x0, double y0, double th0, double x1,
                double y1, double th1, double kstart, double dkstart,
                NatSegment *seg, NatStats *st)
{
    NatStats local;
    if (!st)
        st = &local;
    NatSegment cl;
    if (law == NAT_LINEAR)
        return nat_fit_g1(x0, y0, th0, x1, y1, th1, seg, st);
    if (nat_fit_g1(x0, y0, th0, x1, y1, th1, &cl, st) != 0)
        return -1;
    LawCtx L = {.law = law, .th0 = th0, .ex = x1 - x0, .ey = y1 - y0, .st = st};
    L.smax = 200 * hypot(L.ex, L.ey);
    double S0 = cl.length;
    L.D = cl.k[0] * S0 + cl.k[1] * S0 * S0 / 2;
    /* lambda = 0: the clothoid, an exact solution */
    double c0 = law == NAT_QUADRATIC ? cl.k[0] : cl.k[1], d0 = cl.k[0];
    double c1 = law == NAT_QUADRATIC ? kstart : dkstart, d1 = kstart;
    double u[2] = {law == NAT_QUADRATIC ? cl.k[1] * S0 * S0 : 0, S0};
    if (continuation(&L, c0, d0, c1, d1, u) != 0 &&
        multistart(&L, c1, d1, S0, u) != 0)
        return -1;
    L.c = c1, L.d = d1;
    memset(seg, 0, sizeof *seg);
    seg->x0 = x0, seg->y0 = y0, seg->phi0 = th0;
    law_coef(&L, u, seg);
    end_error(seg, x1, y1, st);
    return settled(seg, hypot(L.ex, L.ey), st);
}
