/*
 * plot_sample.c - adaptive sampling of a plot's curves (plot.h).
 *
 * PLOT_INITIAL uniform samples, then breadth-first bisection of every
 * segment whose midpoint leaves the chord by more than the tolerance (half
 * a pixel of the figure) or turns by more than 10 degrees, to a bounded
 * depth and within a hard budget of samples per curve.  Poles are cut,
 * never joined: a pole between two samples shows as a denominator factor
 * changing sign (plot_jet.c gives the factors' values).  Positions come
 * from plan_eval (eval's very numbers), projected by plot_view.c; the SVG
 * writer (svg.c) draws the result.
 */
#include "runtime/plot_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "runtime/eval.h"

void plot_limits_default(PlotLimits *l)
{
    l->initial = PLOT_INITIAL;
    l->max_depth = PLOT_MAX_DEPTH;
    l->max_samples = PLOT_MAX_SAMPLES;
}

/* A batch evaluator of one output: positions through plan_eval (eval's very
 * numbers), the denominator factors through the forward-mode run. */
typedef struct Sampler {
    const PlotEnv *env;
    const PlotView *view;
    int o;
    unsigned char *live;
    double (*r)[3];
    double **pv; // per param: a column of n values
    double *pos;
    unsigned char *st;
    size_t cap;
} Sampler;

static void sampler_init(Sampler *S, const PlotEnv *env, const PlotView *view,
                         int o, PlotCurve *c)
{
    const Plan *p = env->plan;
    memset(S, 0, sizeof *S);
    S->env = env;
    S->view = view;
    S->o = o;
    S->live = pc_xmalloc((size_t)p->nins + 1);
    S->r = pc_xmalloc(sizeof *S->r * (size_t)(p->nins + 1));
    plan_live(p, o, S->live);
    S->pv = pc_xcalloc((size_t)p->nparams + 1, sizeof *S->pv);
    /* the factors whose sign change is a pole: live, varying POLE operands */
    if (!c->facreg) {
        c->facreg = pc_xmalloc(sizeof *c->facreg * (size_t)(p->nins + 1));
        c->nfac = 0;
        for (int i = 0; i < p->nins; i++)
            if (S->live[i] && p->ins[i].op == PLAN_POLE &&
                !p->ins[p->ins[i].a].uniform)
                c->facreg[c->nfac++] = p->ins[i].a;
    }
}

static void sampler_clear(Sampler *S)
{
    const Plan *p = S->env->plan;
    for (int i = 0; i < p->nparams; i++)
        pc_free(S->pv[i]);
    pc_free(S->pv);
    pc_free(S->live);
    pc_free(S->r);
    pc_free(S->pos);
    pc_free(S->st);
}

/* Evaluates n values ts into x, y, ok, fac (nfac per sample). */
static void sampler_run(Sampler *S, const PlotCurve *c, size_t n,
                        const double *ts, double *x, double *y,
                        unsigned char *ok, double *fac)
{
    const PlotEnv *env = S->env;
    const Plan *p = env->plan;
    int dim = env->dim;
    if (n == 0)
        return;
    if (n > S->cap) {
        for (int i = 0; i < p->nparams; i++)
            S->pv[i] = pc_xrealloc(S->pv[i], sizeof **S->pv * n);
        S->pos = pc_xrealloc(S->pos, sizeof *S->pos * n * (size_t)dim);
        S->st = pc_xrealloc(S->st, n);
        S->cap = n;
    }
    for (int i = 0; i < p->nparams; i++)
        for (size_t j = 0; j < n; j++)
            S->pv[i][j] = i == env->param ? ts[j] : env->params[i];
    plan_eval(p, S->o, n, (const double *const *)S->pv, env->consts,
              env->points, dim, S->pos, S->st);
    for (size_t j = 0; j < n; j++) {
        plot_project(S->view, S->pos + j * (size_t)dim, dim, &x[j], &y[j]);
        ok[j] = S->st[j] == 0 && isfinite(x[j]) && isfinite(y[j]);
        for (int c0 = 0; c0 < dim && ok[j]; c0++)
            ok[j] = isfinite(S->pos[j * (size_t)dim + (size_t)c0]);
        if (c->nfac) {
            plot_jet_run(env, S->live, ts[j], S->r);
            for (int k = 0; k < c->nfac; k++)
                fac[j * (size_t)c->nfac + (size_t)k] = S->r[c->facreg[k]][0];
        }
    }
}

static void curve_alloc(PlotCurve *c, size_t n)
{
    c->t = pc_xrealloc(c->t, sizeof *c->t * (n + 1));
    c->x = pc_xrealloc(c->x, sizeof *c->x * (n + 1));
    c->y = pc_xrealloc(c->y, sizeof *c->y * (n + 1));
    c->ok = pc_xrealloc(c->ok, n + 1);
    c->cut = pc_xrealloc(c->cut, n + 1);
    c->fac = pc_xrealloc(c->fac, sizeof *c->fac * (n * (size_t)c->nfac + 1));
}

/* ---- knots ---------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* the argument register a of a sign kernel at t (a jet run) */
static double arg_at(const PlotEnv *env, const unsigned char *live,
                     double (*r)[3], int a, double t, double *d1, double *d2)
{
    plot_jet_run(env, live, t, r);
    if (d1)
        *d1 = r[a][1];
    if (d2)
        *d2 = r[a][2];
    return r[a][0];
}

/* The zero of the linear argument a (value v0 at t = 0, slope s): -v0/s,
 * then the double nearest it whose value is nearest 0 (a Newton step and
 * the neighbours). */
static double knot_of(const PlotEnv *env, const unsigned char *live,
                      double (*r)[3], int a, double v0, double s)
{
    double k = -v0 / s;
    double v = arg_at(env, live, r, a, k, NULL, NULL);
    if (v != 0 && isfinite(v)) {
        double k2 = k - v / s, v2 = arg_at(env, live, r, a, k2, NULL, NULL);
        if (fabs(v2) < fabs(v)) {
            k = k2;
            v = v2;
        }
    }
    for (int side = 0; side < 2 && v != 0; side++) {
        double kk = nextafter(k, side ? INFINITY : -INFINITY);
        double vv = arg_at(env, live, r, a, kk, NULL, NULL);
        if (fabs(vv) < fabs(v)) {
            k = kk;
            v = vv;
        }
    }
    return k;
}

size_t plot_knots(const PlotEnv *env, int o, double lo, double hi,
                  double **knots)
{
    const Plan *p = env->plan;
    *knots = NULL;
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    plan_live(p, o, live);
    double(*r)[3] = pc_xmalloc(sizeof *r * (size_t)(p->nins + 1));
    size_t n = 0, cap = 0;
    double *k = NULL;
    for (int i = 0; i < p->nins; i++) {
        const PlanIns *x = &p->ins[i];
        if (!live[i] || x->op != PLAN_FN || (x->b & 255) != PLAN_FN_SIGN ||
            p->ins[x->a].uniform)
            continue;
        /* linear in the swept param: no second derivative at three
         * points, the same slope, and the values on its line */
        int a = x->a;
        double s0, s1, s2, c0, c1, c2;
        double v0 = arg_at(env, live, r, a, 0, &s0, &c0);
        double v1 = arg_at(env, live, r, a, 1, &s1, &c1);
        double m = mix(lo, hi, 0.5);
        double v2 = arg_at(env, live, r, a, m, &s2, &c2);
        if (!(isfinite(v0) && isfinite(v1) && isfinite(v2) && isfinite(s0)) ||
            c0 != 0 || c1 != 0 || c2 != 0 || s0 == 0 || s0 != s1 || s0 != s2 ||
            !(fabs(v1 - v0 - s0) <= 1e-9 * (fabs(v0) + fabs(v1) + fabs(s0))))
            continue;
        double t = knot_of(env, live, r, a, v0, s0);
        if (!(t >= lo && t <= hi))
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 16;
            k = pc_xrealloc(k, sizeof *k * cap);
        }
        k[n++] = t;
    }
    if (n > 1)
        qsort(k, n, sizeof *k, cmp_double);
    size_t u = 0;
    for (size_t i = 0; i < n; i++)
        if (u == 0 || k[i] != k[u - 1])
            k[u++] = k[i];
    pc_free(r);
    pc_free(live);
    if (u == 0) {
        pc_free(k);
        k = NULL;
    }
    *knots = k;
    return u;
}

/* 1 when t is one of c's knots */
static int is_knot(const PlotCurve *c, double t)
{
    return c->nknots &&
           bsearch(&t, c->knots, c->nknots, sizeof t, cmp_double) != NULL;
}

void plot_curve_init(PlotCurve *c, const PlotEnv *env, int o, double lo,
                     double hi, const PlotView *view, const PlotLimits *lim)
{
    memset(c, 0, sizeof *c);
    c->output = o;
    Sampler S;
    sampler_init(&S, env, view, o, c);
    size_t n0 = (size_t)(lim->initial < 1 ? 1 : lim->initial);
    if (n0 + 1 > lim->max_samples && lim->max_samples >= 2)
        n0 = lim->max_samples - 1;
    size_t n = lo == hi ? 1 : n0 + 1;
    if (lo < hi)
        c->nknots = plot_knots(env, o, lo, hi, &c->knots);
    /* the knots within the budget, each a sample (merged in order) */
    size_t nk = c->nknots;
    if (n + nk > lim->max_samples)
        nk = lim->max_samples > n ? lim->max_samples - n : 0;
    curve_alloc(c, n + nk);
    size_t j = 0, q = 0;
    for (size_t i = 0; i < n; i++) {
        double t = i == 0       ? lo
                   : i == n - 1 ? hi
                                : mix(lo, hi, (double)i / (double)n0);
        for (; q < nk && c->knots[q] <= t; q++)
            if (c->knots[q] < t && (j == 0 || c->knots[q] > c->t[j - 1]))
                c->t[j++] = c->knots[q];
        c->t[j++] = t;
    }
    n = j;
    sampler_run(&S, c, n, c->t, c->x, c->y, c->ok, c->fac);
    memset(c->cut, 0, n);
    c->n = n;
    sampler_clear(&S);
}

void plot_curve_clear(PlotCurve *c)
{
    pc_free(c->t);
    pc_free(c->x);
    pc_free(c->y);
    pc_free(c->ok);
    pc_free(c->cut);
    pc_free(c->fac);
    pc_free(c->facreg);
    pc_free(c->knots);
    memset(c, 0, sizeof *c);
}

/* 1 when a denominator factor has opposite signs at samples i and j */
static int sign_change(const PlotCurve *c, size_t i, const double *fj)
{
    const double *fi = c->fac + i * (size_t)c->nfac;
    for (int k = 0; k < c->nfac; k++)
        if ((fi[k] < 0 && fj[k] > 0) || (fi[k] > 0 && fj[k] < 0))
            return 1;
    return 0;
}

/* distance of m from the segment ab */
static double seg_dist(double ax, double ay, double bx, double by, double mx,
                       double my)
{
    double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double s = l2 > 0 ? ((mx - ax) * dx + (my - ay) * dy) / l2 : 0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    return hypot(mx - ax - s * dx, my - ay - s * dy);
}

typedef struct Test {
    const double *box;
    double tol;
} Test;

/* 1 when segment (a, b) with midpoint m needs bisecting */
static int needs_split(const Test *T, int oka, int okm, int okb, double ax,
                       double ay, double mx, double my, double bx, double by,
                       int pole)
{
    if (!oka || !okm || !okb)
        return oka || okm || okb; // a boundary of the drawable part
    if (pole)
        return 1;
    const double *B = T->box;
    double w = B[2] - B[0], h = B[3] - B[1];
    double x0 = fmin(ax, fmin(bx, mx)), x1 = fmax(ax, fmax(bx, mx));
    double y0 = fmin(ay, fmin(by, my)), y1 = fmax(ay, fmax(by, my));
    if (x1 < B[0] - 0.05 * w || x0 > B[2] + 0.05 * w || y1 < B[1] - 0.05 * h ||
        y0 > B[3] + 0.05 * h)
        return 0; // wholly outside the figure
    if (seg_dist(ax, ay, bx, by, mx, my) > T->tol)
        return 1;
    double ux = mx - ax, uy = my - ay, vx = bx - mx, vy = by - my;
    double lu = hypot(ux, uy), lv = hypot(vx, vy);
    if (lu + lv > 4 * T->tol && lu > 0 && lv > 0 &&
        (ux * vx + uy * vy) < cos(10 * PI / 180) * lu * lv)
        return 1;
    return 0;
}

/* the segments pending bisection whose midpoints are sampled this
 * level: at most budget; a segment with no room, or no double in
 * between, is no longer pending */
static size_t count_pending(const PlotCurve *c, size_t n, unsigned char *pend,
                            size_t budget)
{
    size_t m = 0;
    for (size_t i = 0; i + 1 < n; i++)
        if (pend[i]) {
            double t = mix(c->t[i], c->t[i + 1], 0.5);
            if (m >= budget || !(t > c->t[i] && t < c->t[i + 1]) ||
                (c->t[i] > c->t[i + 1])) {
                pend[i] = 0; // no room, or no double in between
                continue;
            }
            m++;
        }
    return m;
}

/* The midpoints' samples (mt, mx, my, mok, mf: m of them) merged into c
 * after the segments pending; the flags of each segment (pending,
 * depth, unresolved) replaced by those of its halves. */
static void merge(PlotCurve *c, const Test *T, const PlotLimits *lim, size_t m,
                  const double *mt, const double *mx, const double *my,
                  const unsigned char *mok, const double *mf,
                  unsigned char **pendp, unsigned char **depthp,
                  unsigned char **unresp)
{
    int nf = c->nfac;
    size_t n = c->n;
    unsigned char *pend = *pendp, *depth = *depthp, *unres = *unresp;
    PlotCurve nc = *c;
    nc.t = nc.x = nc.y = nc.fac = NULL;
    nc.ok = nc.cut = NULL;
    curve_alloc(&nc, n + m);
    unsigned char *npend = pc_xcalloc(n + m, 1);
    unsigned char *ndepth = pc_xcalloc(n + m, 1);
    unsigned char *nunres = pc_xcalloc(n + m, 1);
    size_t j = 0, k = 0;
    for (size_t i = 0; i < n; i++) {
        nc.t[j] = c->t[i];
        nc.x[j] = c->x[i];
        nc.y[j] = c->y[i];
        nc.ok[j] = c->ok[i];
        memcpy(nc.fac + j * (size_t)nf, c->fac + i * (size_t)nf,
               sizeof *c->fac * (size_t)nf);
        ndepth[j] = depth[i];
        nunres[j] = unres[i];
        j++;
        if (i + 1 < n && pend[i]) {
            const double *fm = mf + k * (size_t)nf;
            nc.t[j] = mt[k];
            nc.x[j] = mx[k];
            nc.y[j] = my[k];
            nc.ok[j] = mok[k];
            memcpy(nc.fac + j * (size_t)nf, fm, sizeof *mf * (size_t)nf);
            int split =
                needs_split(T, c->ok[i], mok[k], c->ok[i + 1], c->x[i], c->y[i],
                            mx[k], my[k], c->x[i + 1], c->y[i + 1],
                            sign_change(c, i, c->fac + (i + 1) * (size_t)nf));
            int d = depth[i] + 1;
            ndepth[j - 1] = ndepth[j] = (unsigned char)d;
            if (split && d < lim->max_depth)
                npend[j - 1] = npend[j] = 1;
            else if (split)
                nunres[j - 1] = nunres[j] = 1;
            j++;
            k++;
        }
    }
    pc_free(c->t);
    pc_free(c->x);
    pc_free(c->y);
    pc_free(c->ok);
    pc_free(c->cut);
    pc_free(c->fac);
    c->t = nc.t;
    c->x = nc.x;
    c->y = nc.y;
    c->ok = nc.ok;
    c->cut = nc.cut;
    c->fac = nc.fac;
    pc_free(pend);
    pc_free(depth);
    pc_free(unres);
    *pendp = npend;
    *depthp = ndepth;
    *unresp = nunres;
    c->n = n + m;
}

/* cuts: a sample not drawable, a pole between, or a jump */
static void mark_cuts(PlotCurve *c, const double box[4],
                      const unsigned char *unres)
{
    int nf = c->nfac;
    size_t n = c->n;
    double diag = hypot(box[2] - box[0], box[3] - box[1]);
    c->cut[0] = 1;
    for (size_t i = 1; i < n; i++) {
        int cut = !c->ok[i - 1] || !c->ok[i] ||
                  sign_change(c, i - 1, c->fac + i * (size_t)nf);
        if (!cut && unres[i - 1] &&
            hypot(c->x[i] - c->x[i - 1], c->y[i] - c->y[i - 1]) > 0.02 * diag)
            cut = 1;
        c->cut[i] = (unsigned char)cut;
    }
}

/* the samples that lie on the chord of their neighbours, dropped */
static void drop_flat(PlotCurve *c, double tol)
{
    int nf = c->nfac;
    size_t n = c->n;
    /* drop samples that lie on the chord of their drawn neighbours (within
     * a quarter of the tolerance, checked against every sample dropped
     * since the last one kept) */
    unsigned char *keep = pc_xmalloc(n);
    memset(keep, 1, n);
    size_t last = 0;
    for (size_t i = 1; i + 1 < n; i++) {
        if (!c->ok[i] || c->cut[i] || c->cut[i + 1] || i - last > 64 ||
            is_knot(c, c->t[i])) {
            last = i;
            continue;
        }
        int fits = 1;
        for (size_t q = last + 1; q <= i && fits; q++)
            fits = seg_dist(c->x[last], c->y[last], c->x[i + 1], c->y[i + 1],
                            c->x[q], c->y[q]) <= tol / 4;
        if (fits)
            keep[i] = 0;
        else
            last = i;
    }
    size_t j = 0;
    for (size_t i = 0; i < n; i++) {
        if (!keep[i])
            continue;
        c->t[j] = c->t[i];
        c->x[j] = c->x[i];
        c->y[j] = c->y[i];
        c->ok[j] = c->ok[i];
        c->cut[j] = c->cut[i];
        memmove(c->fac + j * (size_t)nf, c->fac + i * (size_t)nf,
                sizeof *c->fac * (size_t)nf);
        j++;
    }
    c->n = j;
    pc_free(keep);
}

void plot_curve_refine(PlotCurve *c, const PlotEnv *env, const PlotView *view,
                       const double box[4], const PlotLimits *lim)
{
    if (c->n < 2) {
        if (c->n == 1)
            c->cut[0] = 1;
        return;
    }
    Test T;
    T.box = box;
    T.tol = hypot(box[2] - box[0], box[3] - box[1]) / 2000;
    Sampler S;
    sampler_init(&S, env, view, c->output, c);
    int nf = c->nfac;
    size_t n = c->n;
    /* per segment i (samples i, i+1): pending bisection, depth, and
     * "unresolved" (still failing the test at the depth limit) */
    unsigned char *pend = pc_xmalloc(n), *depth = pc_xcalloc(n, 1);
    unsigned char *unres = pc_xcalloc(n, 1);
    memset(pend, 1, n);
    pend[n - 1] = 0;
    size_t budget = lim->max_samples > n ? lim->max_samples - n : 0;
    double *mt = NULL, *mx = NULL, *my = NULL, *mf = NULL;
    unsigned char *mok = NULL;
    for (int level = 0; level < lim->max_depth && budget > 0; level++) {
        size_t m = count_pending(c, n, pend, budget);
        if (m == 0)
            break;
        mt = pc_xrealloc(mt, sizeof *mt * m);
        mx = pc_xrealloc(mx, sizeof *mx * m);
        my = pc_xrealloc(my, sizeof *my * m);
        mok = pc_xrealloc(mok, m);
        mf = pc_xrealloc(mf, sizeof *mf * (m * (size_t)nf + 1));
        size_t k = 0;
        for (size_t i = 0; i + 1 < n; i++)
            if (pend[i])
                mt[k++] = mix(c->t[i], c->t[i + 1], 0.5);
        sampler_run(&S, c, m, mt, mx, my, mok, mf);
        budget -= m;
        merge(c, &T, lim, m, mt, mx, my, mok, mf, &pend, &depth, &unres);
        n += m;
    }
    mark_cuts(c, box, unres);
    drop_flat(c, T.tol);
    pc_free(pend);
    pc_free(depth);
    pc_free(unres);
    pc_free(mt);
    pc_free(mx);
    pc_free(my);
    pc_free(mf);
    pc_free(mok);
    sampler_clear(&S);
}

int plot_curve_subpaths(const PlotCurve *c)
{
    int k = 0;
    for (size_t i = 1; i < c->n; i++)
        if (!c->cut[i] && (i == 1 || c->cut[i - 1]))
            k++;
    return k;
}
