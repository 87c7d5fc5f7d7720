/*
 * analyze_num_metric.c - the curvature and arc length (analyze --at) of a
 * curve with functions (analyze_num.c), as compiler/analyze/metric.c gives
 * them for rational curves: on the Plan with the points' coordinates, M'
 * and M'' from its forward mode (plot_jet: the exact derivatives of the
 * reduced equation), the curvature |M' x M''| / |M'|^3 in any dimension
 * (the norm of the wedge product), at the ends from inside the range, its
 * largest and smallest value over the samples (the knots of sign() among
 * them) each refined by golden section to 1e-15, and the arc length by
 * adaptive Simpson on |M'| over each interval between samples (so no
 * corner of a composite curve lies inside one), pieces accepted at 1e-13
 * of the whole.  A pole in the range leaves it all out, as for rational
 * curves.
 */
#include "driver/cli/cli.h"

#include <math.h>

#include "base/mem.h"
#include "compiler/analyze/analyze.h"
#include "runtime/plot.h"

typedef struct Met {
    const PlotEnv *env;
    int o, dim;
    double *p, *v1, *v2; // dim each
} Met;

/* the curvature at t; NAN where M' = 0 or the Plan reports a problem */
static double kappa(Met *m, double t)
{
    if (plot_jet(m->env, m->o, t, m->p, m->v1, m->v2) % 3)
        return NAN;
    double a = 0, cross = 0;
    for (int c = 0; c < m->dim; c++) {
        a += m->v1[c] * m->v1[c];
        for (int e = c + 1; e < m->dim; e++) {
            double w = m->v1[c] * m->v2[e] - m->v1[e] * m->v2[c];
            cross += w * w;
        }
    }
    return a == 0 || !isfinite(a) ? NAN : sqrt(cross) / (a * sqrt(a));
}

/* |M'| at t (0 where undefined) */
static double speed(Met *m, double t)
{
    if (plot_jet(m->env, m->o, t, m->p, m->v1, NULL) % 3)
        return 0;
    double a = 0;
    for (int c = 0; c < m->dim; c++)
        a += m->v1[c] * m->v1[c];
    return isfinite(a) ? sqrt(a) : 0;
}

/* an extreme (sign 1 the largest, -1 the smallest) in [a, b] */
static double golden_kappa(Met *m, double a, double b, int sign, double *at)
{
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = sign * kappa(m, x1), f2 = sign * kappa(m, x2);
    for (int it = 0; it < 200 && b - a > 1e-15 * fmax(1.0, fabs(a)); it++) {
        if (f1 > f2 || isnan(f2)) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a);
            f1 = sign * kappa(m, x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a);
            f2 = sign * kappa(m, x2);
        }
    }
    *at = (a + b) / 2;
    return kappa(m, *at);
}

static void extremes(AnCurve *c, Met *m, const double *ts, int ns)
{
    double best[2] = {-1, INFINITY};
    int where[2] = {-1, -1};
    for (int k = 0; k < ns; k++) {
        double v = kappa(m, ts[k]);
        if (isnan(v))
            continue;
        if (v > best[0])
            best[0] = v, where[0] = k;
        if (v < best[1])
            best[1] = v, where[1] = k;
    }
    for (int e = 0; e < 2; e++) {
        if (where[e] < 0)
            continue;
        double a = ts[where[e] > 0 ? where[e] - 1 : 0];
        double b = ts[where[e] + 1 < ns ? where[e] + 1 : ns - 1];
        double at, v = golden_kappa(m, a, b, e ? -1 : 1, &at);
        if (isnan(v) || (e ? best[e] < v : best[e] > v))
            v = best[e], at = ts[where[e]];
        for (int k = 1; k >= 0; k--) { /* an extreme at an end: its value */
            double ke = c->kappa_end[k];
            if (!isnan(ke) && (e ? ke <= v : ke >= v))
                v = ke, at = k ? ts[ns - 1] : ts[0];
        }
        c->kappa_ext[e] = v;
        c->kappa_ext_t[e] = at;
        c->has_kappa_ext[e] = 1;
    }
}

static double simpson(Met *m, double tol, double a, double fa, double b,
                      double fb, double mid, double fm, double whole, int depth)
{
    double lm = (a + mid) / 2, rm = (mid + b) / 2;
    double flm = speed(m, lm), frm = speed(m, rm);
    double left = (mid - a) / 6 * (fa + 4 * flm + fm);
    double right = (b - mid) / 6 * (fm + 4 * frm + fb);
    double diff = left + right - whole;
    if (depth <= 0 || fabs(diff) <= 15 * tol * (b - a))
        return left + right + diff / 15;
    return simpson(m, tol, a, fa, mid, fm, lm, flm, left, depth - 1) +
           simpson(m, tol, mid, fm, b, fb, rm, frm, right, depth - 1);
}

static double arc_length(Met *m, const double *ts, int ns)
{
    double est = 0;
    for (int k = 0; k + 1 < ns; k++)
        est += speed(m, (ts[k] + ts[k + 1]) / 2) * (ts[k + 1] - ts[k]);
    double tol = 1e-13 * est / fmax(ts[ns - 1] - ts[0], 1e-300), total = 0;
    for (int k = 0; k + 1 < ns; k++) {
        /* inside the interval: a corner's mean derivative is no speed */
        double a = ts[k], b = ts[k + 1], mid = (a + b) / 2;
        double fa = speed(m, nextafter(a, b)), fb = speed(m, nextafter(b, a));
        double fm = speed(m, mid);
        total += simpson(m, tol, a, fa, b, fb, mid, fm,
                         (b - a) / 6 * (fa + 4 * fm + fb), 30);
    }
    return total;
}

void analyze_num_metric(AnCurve *c, const PlotEnv *env, int o, const double *ts,
                        int ns)
{
    if (c->poles.n || c->kind != KIND_POINT || ns < 2)
        return;
    Met m = {env, o, env->dim, NULL, NULL, NULL};
    m.p = pc_xmalloc((size_t)(3 * m.dim + 3) * sizeof *m.p);
    m.v1 = m.p + m.dim + 1;
    m.v2 = m.v1 + m.dim + 1;
    c->kappa_end[0] = kappa(&m, nextafter(ts[0], ts[1]));
    c->kappa_end[1] = kappa(&m, nextafter(ts[ns - 1], ts[ns - 2]));
    extremes(c, &m, ts, ns);
    c->length = arc_length(&m, ts, ns);
    c->has_metric = 1;
    pc_free(m.p);
}
