/*
 * metric.c - what needs coordinates (analyze --at): the curvature at the
 * ends and its extremes over the range, and the arc length.
 *
 * The exact polynomials n_i, d and their first two derivatives are turned
 * into doubles once; at t, M' = (N' d - N d')/d^2 and M'' = ((N'' d - N
 * d'') d - 2 d' (N' d - N d'))/d^3 (N = sum n_i P_i in coordinates), and
 * the curvature in any dimension is |M' x M''| / |M'|^3 (the norm of
 * the wedge product: its 2x2 minors).  Its extremes: the largest and smallest
 * of 2048 samples, each refined by golden section.  The arc length: adaptive
 * Simpson on |M'|, each piece accepted when two levels agree to 1e-13 of the
 * whole.  A pole in the closed range leaves all of it out (the length is
 * infinite).
 */
#include "compiler/analyze/analyze.h"

#include <math.h>
#include <stdlib.h>

#include "base/budget.h"
#include "base/mem.h"

typedef struct Jet {
    slong len, dim;
    double **n[3]; // n[k][i]: coefficients of the k-th derivative of n_i
    slong *deg[3];
    double *d[3];
    slong ddeg[3];
    const double *const *pt; // per term, its point's coordinates
} Jet;

static double *poly_doubles(slong *deg, const fmpz_poly_t p)
{
    *deg = fmpz_poly_degree(p);
    double *c = pc_xmalloc((size_t)(*deg + 2) * sizeof *c);
    for (slong k = 0; k <= *deg; k++)
        c[k] = fmpz_get_d(p->coeffs + k);
    return c;
}

static double horner(const double *c, slong deg, double t)
{
    double v = 0;
    for (slong k = deg; k >= 0; k--)
        v = v * t + c[k];
    return v;
}

static void jet_init(Jet *j, const AnPolys *p, const AnSet *set)
{
    fmpz_poly_t q;
    fmpz_poly_init(q);
    j->len = p->len;
    j->dim = set->dim;
    for (int k = 0; k < 3; k++) {
        j->n[k] = pc_xmalloc((size_t)(p->len + 1) * sizeof *j->n[k]);
        j->deg[k] = pc_xmalloc((size_t)(p->len + 1) * sizeof *j->deg[k]);
        for (slong i = 0; i < p->len; i++) {
            fmpz_poly_set(q, p->n + i);
            for (int r = 0; r < k; r++)
                fmpz_poly_derivative(q, q);
            j->n[k][i] = poly_doubles(j->deg[k] + i, q);
        }
        fmpz_poly_set(q, p->den);
        for (int r = 0; r < k; r++)
            fmpz_poly_derivative(q, q);
        j->d[k] = poly_doubles(j->ddeg + k, q);
    }
    fmpz_poly_clear(q);
}

static void jet_clear(Jet *j)
{
    for (int k = 0; k < 3; k++) {
        for (slong i = 0; i < j->len; i++)
            pc_free(j->n[k][i]);
        pc_free(j->n[k]);
        pc_free(j->deg[k]);
        pc_free(j->d[k]);
    }
}

/* v1 = M'(t), v2 = M''(t) in coordinates (dim each) */
static void jet_eval(const Jet *j, double t, double *v1, double *v2)
{
    double d0 = horner(j->d[0], j->ddeg[0], t);
    double d1 = horner(j->d[1], j->ddeg[1], t);
    double d2 = horner(j->d[2], j->ddeg[2], t);
    for (slong c = 0; c < j->dim; c++)
        v1[c] = v2[c] = 0;
    for (slong i = 0; i < j->len; i++) {
        double n0 = horner(j->n[0][i], j->deg[0][i], t);
        double n1 = horner(j->n[1][i], j->deg[1][i], t);
        double n2 = horner(j->n[2][i], j->deg[2][i], t);
        double w1 = (n1 * d0 - n0 * d1) / (d0 * d0);
        double w2 = ((n2 * d0 - n0 * d2) * d0 - 2 * d1 * (n1 * d0 - n0 * d1)) /
                    (d0 * d0 * d0);
        for (slong c = 0; c < j->dim; c++) {
            v1[c] += w1 * j->pt[i][c];
            v2[c] += w2 * j->pt[i][c];
        }
    }
}

static double speed(const Jet *j, double t, double *v1, double *v2)
{
    jet_eval(j, t, v1, v2);
    double s = 0;
    for (slong c = 0; c < j->dim; c++)
        s += v1[c] * v1[c];
    return sqrt(s);
}

/* the curvature at t; NAN where M' = 0.  |M' x M''|^2 as the sum of the
 * squared 2x2 minors, which does not cancel where the curvature is small
 * (|M'|^2 |M''|^2 - (M'.M'')^2 would, to 1e-8) */
static double curvature(const Jet *j, double t, double *v1, double *v2)
{
    jet_eval(j, t, v1, v2);
    double a = 0, cross = 0;
    for (slong c = 0; c < j->dim; c++) {
        a += v1[c] * v1[c];
        for (slong e = c + 1; e < j->dim; e++) {
            double m = v1[c] * v2[e] - v1[e] * v2[c];
            cross += m * m;
        }
    }
    if (a == 0)
        return NAN;
    return sqrt(cross) / (a * sqrt(a));
}

/* golden-section refinement of an extreme of the curvature in [a, b]
 * (sign 1: a maximum, -1: a minimum); *at gets where */
static double refine_extreme(const Jet *j, double a, double b, int sign,
                             double *at, double *v1, double *v2)
{
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = sign * curvature(j, x1, v1, v2);
    double f2 = sign * curvature(j, x2, v1, v2);
    for (int it = 0; it < 80 && b - a > 1e-15 * (1 + fabs(a)); it++) {
        if (f1 > f2 || isnan(f2)) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a);
            f1 = sign * curvature(j, x1, v1, v2);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a);
            f2 = sign * curvature(j, x2, v1, v2);
        }
    }
    *at = (a + b) / 2;
    return curvature(j, *at, v1, v2);
}

enum { SAMPLES = 2048 };

static void extremes(AnCurve *c, const Jet *j, double lo, double hi, double *v1,
                     double *v2)
{
    double h = (hi - lo) / SAMPLES, best[2] = {-1, INFINITY};
    slong where[2] = {-1, -1};
    for (slong k = 0; k <= SAMPLES; k++) {
        double kap = curvature(j, lo + k * h, v1, v2);
        if (isnan(kap))
            continue;
        if (kap > best[0])
            best[0] = kap, where[0] = k;
        if (kap < best[1])
            best[1] = kap, where[1] = k;
    }
    for (int e = 0; e < 2; e++) {
        if (where[e] < 0)
            continue;
        double a = fmax(lo, lo + (where[e] - 1) * h);
        double b = fmin(hi, lo + (where[e] + 1) * h);
        c->kappa_ext[e] =
            refine_extreme(j, a, b, e ? -1 : 1, c->kappa_ext_t + e, v1, v2);
        for (int k = 1; k >= 0; k--) { /* an extreme at an end: its value */
            double ke = c->kappa_end[k];
            if (!isnan(ke) &&
                (isnan(c->kappa_ext[e]) ||
                 (e ? ke <= c->kappa_ext[e] : ke >= c->kappa_ext[e]))) {
                c->kappa_ext[e] = ke;
                c->kappa_ext_t[e] = k ? hi : lo;
            }
        }
        c->has_kappa_ext[e] = !isnan(c->kappa_ext[e]);
    }
}

/* the most evaluations of |M'| an arc length may take: past it the
 * pieces are accepted as they are and the length is not reported (a range
 * like [0, 1e31] would otherwise refine to the depth limit everywhere) */
enum { ARC_MAX_EVALS = 1 << 20 };

typedef struct Simpson {
    const Jet *j;
    double *v1, *v2, tol;
    long evals; // left
} Simpson;

static double simpson(Simpson *s, double a, double fa, double b, double fb,
                      double m, double fm, double whole, int depth)
{
    double lm = (a + m) / 2, rm = (m + b) / 2;
    double flm = speed(s->j, lm, s->v1, s->v2);
    double frm = speed(s->j, rm, s->v1, s->v2);
    double left = (m - a) / 6 * (fa + 4 * flm + fm);
    double right = (b - m) / 6 * (fm + 4 * frm + fb);
    double diff = left + right - whole;
    s->evals -= 2;
    if (s->evals % 4096 == 0 && budget_late()) /* past the deadline: no */
        s->evals = 0;                          /* length (curve.c) */
    if (depth <= 0 || s->evals <= 0 || fabs(diff) <= 15 * s->tol * (b - a))
        return left + right + diff / 15;
    return simpson(s, a, fa, m, fm, lm, flm, left, depth - 1) +
           simpson(s, m, fm, b, fb, rm, frm, right, depth - 1);
}

static double arc_length(const Jet *j, double lo, double hi, double *v1,
                         double *v2)
{
    Simpson s = {j, v1, v2, 0, ARC_MAX_EVALS};
    /* a first estimate sets the tolerance relative to the length */
    double est = 0;
    for (int k = 0; k < 64; k++)
        est += speed(j, lo + (k + 0.5) * (hi - lo) / 64, v1, v2);
    s.tol = 1e-13 * est / 64;
    double total = 0, h = (hi - lo) / 16;
    for (int k = 0; k < 16; k++) {
        double a = lo + k * h, b = k == 15 ? hi : a + h, m = (a + b) / 2;
        double fa = speed(j, a, v1, v2), fb = speed(j, b, v1, v2);
        double fm = speed(j, m, v1, v2);
        total += simpson(&s, a, fa, b, fb, m, fm,
                         (b - a) / 6 * (fa + 4 * fm + fb), 40);
    }
    return s.evals > 0 ? total : NAN;
}

void analyze_metric(AnCurve *c, const AnPolys *p, const fmpq *lo,
                    const fmpq *hi, const AnSet *set)
{
    if (!set || !set->dim || !lo || c->poles.n || c->kind != KIND_POINT)
        return;
    const double **pt = pc_xmalloc((size_t)(p->len + 1) * sizeof *pt);
    for (slong i = 0; i < p->len; i++)
        if (!(pt[i] = set->pt[p->pt[i]])) {
            pc_free(pt);
            c->metric_missing = 1;
            return;
        }
    Jet j;
    j.pt = pt;
    jet_init(&j, p, set);
    double *v1 = pc_xmalloc((size_t)(2 * set->dim + 2) * sizeof *v1);
    double *v2 = v1 + set->dim + 1;
    double a = fmpq_get_d(lo), b = fmpq_get_d(hi);
    c->kappa_end[0] = curvature(&j, a, v1, v2);
    c->kappa_end[1] = curvature(&j, b, v1, v2);
    extremes(c, &j, a, b, v1, v2);
    c->length = arc_length(&j, a, b, v1, v2);
    c->has_metric = 1;
    pc_free(v1);
    jet_clear(&j);
    pc_free(pt);
}
