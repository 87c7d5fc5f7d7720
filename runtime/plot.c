/*
 * plot.c - adaptive sampling of a scheme's curves and the SVG writer
 * (plot.h says what is drawn and how).
 */
#include "runtime/plot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "runtime/eval.h"

#define PI 3.14159265358979323846

/* ---- projection ---------------------------------------------------------- */

static void view_angles(PlotView *v, double az_deg, double el_deg)
{
    double az = az_deg * (PI / 180), el = el_deg * (PI / 180);
    v->u[0] = -sin(az);
    v->u[1] = cos(az);
    v->u[2] = 0;
    v->v[0] = -sin(el) * cos(az);
    v->v[1] = -sin(el) * sin(az);
    v->v[2] = cos(el);
}

static void view_axes(PlotView *v, int a, int b)
{
    memset(v, 0, sizeof *v);
    v->u[a] = 1;
    v->v[b] = 1;
}

void plot_view_default(PlotView *v, int dim)
{
    if (dim <= 2)
        view_axes(v, 0, 1);
    else
        view_angles(v, 45, asin(1 / sqrt(3)) * (180 / PI));
}

int plot_view_parse(PlotView *v, const char *text, char *msg, size_t len)
{
    if (strcmp(text, "xy") == 0)
        view_axes(v, 0, 1);
    else if (strcmp(text, "xz") == 0)
        view_axes(v, 0, 2);
    else if (strcmp(text, "yz") == 0)
        view_axes(v, 1, 2);
    else if (strcmp(text, "iso") == 0)
        plot_view_default(v, 3);
    else {
        char *end;
        double az = pc_strtod(text, &end), el = 0;
        int ok = end != text && *end == ',';
        if (ok) {
            const char *s = end + 1;
            el = pc_strtod(s, &end);
            ok = end != s && *end == '\0' && isfinite(az) && isfinite(el) &&
                 fabs(az) <= 360 && fabs(el) <= 90;
        }
        if (!ok) {
            pc_snprintf(msg, len,
                        "expected xy, xz, yz, iso or AZIMUTH,ELEVATION in "
                        "degrees (|azimuth| <= 360, |elevation| <= 90)");
            return -1;
        }
        view_angles(v, az, el);
    }
    return 0;
}

void plot_project(const PlotView *v, const double *P, int dim, double *x,
                  double *y)
{
    double sx = 0, sy = 0;
    for (int c = 0; c < dim && c < 3; c++) {
        sx += v->u[c] * P[c];
        sy += v->v[c] * P[c];
    }
    *x = sx;
    *y = sy;
}

/* ---- derivatives: the plan in forward mode ------------------------------- */

/* f, f', f'' of PlanFn b at x */
static void fn_jet(int b, double x, double *f0, double *f1, double *f2)
{
    int q = b >> 8;
    double f = plan_fn_eval(b, x), d, dd;
    switch ((PlanFn)(b & 255)) {
    case PLAN_FN_SQRT:
        d = 0.5 / f;
        dd = -d / (2 * x);
        break;
    case PLAN_FN_ROOT:
        d = f / (q * x);
        dd = d * (1.0 / q - 1) / x;
        break;
    case PLAN_FN_SIN: d = cos(x); dd = -f; break;
    case PLAN_FN_COS: d = -sin(x); dd = -f; break;
    case PLAN_FN_SINH: d = cosh(x); dd = f; break;
    case PLAN_FN_COSH: d = sinh(x); dd = f; break;
    case PLAN_FN_EXP: d = f; dd = f; break;
    case PLAN_FN_LOG: d = 1 / x; dd = -1 / (x * x); break;
    case PLAN_FN_ASIN:
    case PLAN_FN_ACOS: {
        double s = 1 - x * x;
        d = 1 / sqrt(s);
        dd = x / (s * sqrt(s));
        if ((b & 255) == PLAN_FN_ACOS) {
            d = -d;
            dd = -dd;
        }
        break;
    }
    case PLAN_FN_ATAN: {
        double s = 1 + x * x;
        d = 1 / s;
        dd = -2 * x / (s * s);
        break;
    }
    default: d = 0; dd = 0; break;
    }
    *f0 = f;
    *f1 = d;
    *f2 = dd;
}

/* r[i][0..2]: value, d/dt, d2/dt2 of every live register at t */
static void jet_run(const PlotEnv *env, const unsigned char *live, double t,
                    double (*r)[3])
{
    const Plan *p = env->plan;
    for (int i = 0; i < p->nins; i++) {
        if (!live[i])
            continue;
        const PlanIns *x = &p->ins[i];
        double *d = r[i];
        const double *a = NULL, *b = NULL;
        int nargs = plan_op_nargs((PlanOp)x->op);
        if (nargs >= 1)
            a = r[x->a];
        if (nargs >= 2)
            b = r[x->b];
        d[1] = d[2] = 0;
        switch ((PlanOp)x->op) {
        case PLAN_CONST: d[0] = p->k[x->a]; break;
        case PLAN_INPUT:
            if (x->a == env->param) {
                d[0] = t;
                d[1] = 1;
            } else if (x->a < p->nparams) {
                d[0] = env->params[x->a];
            } else {
                d[0] = env->consts[x->a - p->nparams];
            }
            break;
        case PLAN_DIST:
            d[0] = plan_dist_eval(env->points[x->a], env->points[x->b],
                                  env->dim);
            break;
        case PLAN_COORD:
            d[0] = plan_coord_eval(env->points[x->a], x->b, env->dim);
            break;
        case PLAN_NEG:
            for (int k = 0; k < 3; k++)
                d[k] = -a[k];
            break;
        case PLAN_ADD:
            for (int k = 0; k < 3; k++)
                d[k] = a[k] + b[k];
            break;
        case PLAN_SUB:
            for (int k = 0; k < 3; k++)
                d[k] = a[k] - b[k];
            break;
        case PLAN_MUL:
            d[0] = a[0] * b[0];
            d[1] = a[1] * b[0] + a[0] * b[1];
            d[2] = a[2] * b[0] + 2 * a[1] * b[1] + a[0] * b[2];
            break;
        case PLAN_DIV:
            d[0] = a[0] / b[0];
            d[1] = (a[1] - d[0] * b[1]) / b[0];
            d[2] = (a[2] - 2 * d[1] * b[1] - d[0] * b[2]) / b[0];
            break;
        case PLAN_POWI: {
            double e = x->b;
            d[0] = pow(a[0], e);
            double f1 = e * pow(a[0], e - 1), f2 = e * (e - 1) * pow(a[0], e - 2);
            d[1] = f1 * a[1];
            d[2] = f2 * a[1] * a[1] + f1 * a[2];
            break;
        }
        case PLAN_POLE: d[0] = a[0] == 0 ? 1.0 : 0.0; break;
        case PLAN_DOMAIN: d[0] = plan_domain_eval(x->b, a[0]); break;
        case PLAN_FN: {
            double f0, f1, f2;
            fn_jet(x->b, a[0], &f0, &f1, &f2);
            d[0] = f0;
            d[1] = f1 * a[1];
            d[2] = f2 * a[1] * a[1] + f1 * a[2];
            break;
        }
        case PLAN_ATAN2: { // atan2(y = a, x = b)
            double y0 = a[0], x0 = b[0];
            double D = x0 * x0 + y0 * y0, N = x0 * a[1] - y0 * b[1];
            double N1 = x0 * a[2] - y0 * b[2];
            double D1 = 2 * (x0 * b[1] + y0 * a[1]);
            d[0] = atan2(y0, x0);
            d[1] = N / D;
            d[2] = (N1 * D - N * D1) / (D * D);
            break;
        }
        default: d[0] = NAN; break;
        }
    }
}

int plot_jet(const PlotEnv *env, int o, double t, double *pos, double *d1,
             double *d2)
{
    const Plan *p = env->plan;
    const PlanOutput *po = &p->outputs[o];
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    double(*r)[3] = pc_xmalloc(sizeof *r * (size_t)(p->nins + 1));
    plan_live(p, o, live);
    jet_run(env, live, t, r);
    int dim = po->kind == PLAN_SCALAR ? 1 : env->dim;
    double *out[3] = {pos, d1, d2};
    int finite = 1;
    for (int k = 0; k < 3; k++) {
        if (!out[k])
            continue;
        for (int c = 0; c < dim; c++) {
            double s = 0;
            for (int j = 0; j < po->nterms; j++)
                s += r[po->reg[j]][k] *
                     (po->point[j] < 0 ? 1.0 : env->points[po->point[j]][c]);
            out[k][c] = s;
            finite &= isfinite(s);
        }
    }
    int st = po->bad >= 0 ? (int)plan_status(r[po->bad][0]) : 0;
    free(live);
    free(r);
    return st ? st : finite ? 0 : 3;
}

/* ---- sampling ------------------------------------------------------------ */

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
        free(S->pv[i]);
    free(S->pv);
    free(S->live);
    free(S->r);
    free(S->pos);
    free(S->st);
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
            jet_run(env, S->live, ts[j], S->r);
            for (int k = 0; k < c->nfac; k++)
                fac[j * (size_t)c->nfac + (size_t)k] = S->r[c->facreg[k]][0];
        }
    }
}

/* lo + (hi - lo) s without overflow for any finite lo, hi */
static double mix(double lo, double hi, double s)
{
    return lo * (1 - s) + hi * s;
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
    curve_alloc(c, n);
    for (size_t i = 0; i < n; i++)
        c->t[i] = i == 0       ? lo
                  : i == n - 1 ? hi
                               : mix(lo, hi, (double)i / (double)n0);
    sampler_run(&S, c, n, c->t, c->x, c->y, c->ok, c->fac);
    memset(c->cut, 0, n);
    c->n = n;
    sampler_clear(&S);
}

void plot_curve_clear(PlotCurve *c)
{
    free(c->t);
    free(c->x);
    free(c->y);
    free(c->ok);
    free(c->cut);
    free(c->fac);
    free(c->facreg);
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
        /* merge */
        PlotCurve nc = *c;
        nc.t = nc.x = nc.y = nc.fac = NULL;
        nc.ok = nc.cut = NULL;
        curve_alloc(&nc, n + m);
        unsigned char *npend = pc_xcalloc(n + m, 1);
        unsigned char *ndepth = pc_xcalloc(n + m, 1);
        unsigned char *nunres = pc_xcalloc(n + m, 1);
        size_t j = 0;
        k = 0;
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
                int split = needs_split(
                    &T, c->ok[i], mok[k], c->ok[i + 1], c->x[i], c->y[i],
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
        free(c->t);
        free(c->x);
        free(c->y);
        free(c->ok);
        free(c->cut);
        free(c->fac);
        c->t = nc.t;
        c->x = nc.x;
        c->y = nc.y;
        c->ok = nc.ok;
        c->cut = nc.cut;
        c->fac = nc.fac;
        free(pend);
        free(depth);
        free(unres);
        pend = npend;
        depth = ndepth;
        unres = nunres;
        n += m;
        c->n = n;
    }
    /* cuts: a sample not drawable, a pole between, or a jump */
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
    /* drop samples that lie on the chord of their drawn neighbours (within
     * a quarter of the tolerance, checked against every sample dropped
     * since the last one kept) */
    unsigned char *keep = pc_xmalloc(n);
    memset(keep, 1, n);
    size_t last = 0;
    for (size_t i = 1; i + 1 < n; i++) {
        if (!c->ok[i] || c->cut[i] || c->cut[i + 1] || i - last > 64) {
            last = i;
            continue;
        }
        int fits = 1;
        for (size_t q = last + 1; q <= i && fits; q++)
            fits = seg_dist(c->x[last], c->y[last], c->x[i + 1], c->y[i + 1],
                            c->x[q], c->y[q]) <= T.tol / 4;
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
    free(keep);
    free(pend);
    free(depth);
    free(unres);
    free(mt);
    free(mx);
    free(my);
    free(mf);
    free(mok);
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

/* ---- the figure ---------------------------------------------------------- */

void plot_spec_default(PlotSpec *s)
{
    memset(s, 0, sizeof *s);
    plot_view_default(&s->view, 2);
    plot_limits_default(&s->lim);
    s->tangent_scale = 1;
    s->width = 720;
}

static const char *const palette[] = {"#d62728", "#1f77b4", "#2ca02c",
                                      "#9467bd", "#ff7f0e", "#8c564b"};
enum { NPALETTE = sizeof palette / sizeof palette[0] };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* xs[n] sorted in place; the q-quantile */
static double quantile(double *xs, size_t n, double q)
{
    qsort(xs, n, sizeof *xs, cmp_double);
    size_t k = (size_t)(q * (double)(n - 1) + 0.5);
    return xs[k < n ? k : n - 1];
}

static void box_add(double *B, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    B[0] = fmin(B[0], x);
    B[1] = fmin(B[1], y);
    B[2] = fmax(B[2], x);
    B[3] = fmax(B[3], y);
}

static int box_empty(const double *B) { return !(B[0] <= B[2] && B[1] <= B[3]); }

static double box_diag(const double *B) { return hypot(B[2] - B[0], B[3] - B[1]); }

/* The window: everything, unless the curves run far beyond the points and
 * the middle of the curves (poles, a long param range): then the core,
 * enlarged by a quarter each side.  Never degenerate; a 6% margin. */
static void fit_box(double *box, const PlotSpec *s, const PlotCurve *cv,
                    const double *mx, const double *my)
{
    double F[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    double C[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    size_t n = 0;
    for (int i = 0; i < s->nmarks; i++) {
        box_add(F, mx[i], my[i]);
        box_add(C, mx[i], my[i]);
    }
    for (int k = 0; k < s->ncurves; k++)
        for (size_t i = 0; i < cv[k].n; i++)
            if (cv[k].ok[i]) {
                box_add(F, cv[k].x[i], cv[k].y[i]);
                n++;
            }
    if (n > 0) {
        double *xs = pc_xmalloc(sizeof *xs * n), *ys = pc_xmalloc(sizeof *ys * n);
        size_t j = 0;
        for (int k = 0; k < s->ncurves; k++)
            for (size_t i = 0; i < cv[k].n; i++)
                if (cv[k].ok[i]) {
                    xs[j] = cv[k].x[i];
                    ys[j++] = cv[k].y[i];
                }
        box_add(C, quantile(xs, n, 0.05), quantile(ys, n, 0.05));
        box_add(C, quantile(xs, n, 0.95), quantile(ys, n, 0.95));
        free(xs);
        free(ys);
    }
    if (box_empty(F)) {
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    double dc = box_diag(C), df = box_diag(F);
    if (!isfinite(dc)) { // coordinates beyond half the double range
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    if (!(df <= 8 * dc) && dc > 0) {
        double w = C[2] - C[0], h = C[3] - C[1];
        memcpy(box, C, sizeof C);
        box[0] -= w / 4;
        box[2] += w / 4;
        box[1] -= h / 4;
        box[3] += h / 4;
    } else {
        memcpy(box, F, sizeof F);
    }
    double w = box[2] - box[0], h = box[3] - box[1];
    if (!(w > 0) && !(h > 0)) {
        double e = fmax(fabs(box[0]), fabs(box[1])) * 0.2;
        w = h = e > 0 && isfinite(e) ? e : 1;
        box[0] -= w / 2;
        box[2] += w / 2;
        box[1] -= h / 2;
        box[3] += h / 2;
    } else if (!(w > h * 1e-6)) {
        box[0] -= h / 2;
        box[2] += h / 2;
    } else if (!(h > w * 1e-6)) {
        box[1] -= w / 2;
        box[3] += w / 2;
    }
    w = box[2] - box[0];
    h = box[3] - box[1];
    if (!(isfinite(w) && isfinite(h) && w > 0 && h > 0)) {
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    box[0] -= 0.06 * w;
    box[2] += 0.06 * w;
    box[1] -= 0.06 * h;
    box[3] += 0.06 * h;
}

/* Liang-Barsky: clips (x0,y0)-(x1,y1) to B; 0 when nothing is left;
 * *c0, *c1 say whether an end moved */
static int clip(const double *B, double *x0, double *y0, double *x1,
                double *y1, int *c0, int *c1)
{
    double dx = *x1 - *x0, dy = *y1 - *y0, u0 = 0, u1 = 1;
    double pq[4][2] = {{-dx, *x0 - B[0]},
                       {dx, B[2] - *x0},
                       {-dy, *y0 - B[1]},
                       {dy, B[3] - *y0}};
    for (int k = 0; k < 4; k++) {
        double p = pq[k][0], q = pq[k][1];
        if (p == 0) {
            if (q < 0)
                return 0;
        } else {
            double r = q / p;
            if (p < 0 && r > u0)
                u0 = r;
            else if (p > 0 && r < u1)
                u1 = r;
        }
    }
    if (!(u0 <= u1))
        return 0;
    double ax = *x0, ay = *y0;
    *c0 = u0 > 0;
    *c1 = u1 < 1;
    if (*c1) {
        *x1 = ax + u1 * dx;
        *y1 = ay + u1 * dy;
    }
    if (*c0) {
        *x0 = ax + u0 * dx;
        *y0 = ay + u0 * dy;
    }
    return 1;
}

typedef struct Fig {
    FILE *out;
    double s, tx, ty; // pixel = (tx + s x, ty - s y)
    int W, H;
    double clipw[4];  // the canvas in world coordinates, a little larger
    double clipp[4];  // the canvas in pixels, a little larger
    int digits;       // significant digits of world coordinates
} Fig;

/* a number in the C locale, %.*g, no "-0" */
static void put_num(FILE *out, double v, int digits)
{
    char buf[64];
    if (v == 0)
        v = 0; // -0 -> 0
    pc_snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
    fputs(buf, out);
}

static void put_px(FILE *out, double v)
{
    char buf[64];
    pc_snprintf(buf, sizeof buf, "%.1f", v);
    size_t n = strlen(buf);
    if (n >= 2 && strcmp(buf + n - 2, ".0") == 0)
        buf[n - 2] = '\0';
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
    fputs(buf, out);
}

static void put_escaped(FILE *out, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        case '\'': fputs("&apos;", out); break;
        default:
            /* control characters are not allowed in XML 1.0 */
            if ((unsigned char)*s >= 0x20 || *s == '\t' || *s == '\n')
                fputc(*s, out);
            else
                fputc('?', out);
        }
    }
}

static void px_of(const Fig *g, double x, double y, double *px, double *py)
{
    *px = g->tx + g->s * x;
    *py = g->ty - g->s * y;
}

/* A pixel polyline: segments clipped to the canvas, joined where one
 * starts where the last one ended. */
typedef struct Pen {
    const Fig *g;
    int down;     // the pen rests at (x, y)
    double x, y;
} Pen;

static void pen_move_to(const Fig *g, double x, double y)
{
    fputs("M", g->out);
    put_px(g->out, x);
    fputc(' ', g->out);
    put_px(g->out, y);
}

static void pen_line(Pen *P, double x0, double y0, double x1, double y1)
{
    const Fig *g = P->g;
    int c0, c1;
    if (!clip(g->clipp, &x0, &y0, &x1, &y1, &c0, &c1)) {
        P->down = 0;
        return;
    }
    if (!P->down || x0 != P->x || y0 != P->y)
        pen_move_to(g, x0, y0);
    fputs("L", g->out);
    put_px(g->out, x1);
    fputc(' ', g->out);
    put_px(g->out, y1);
    P->down = !c1;
    P->x = x1;
    P->y = y1;
}

static void pen_lift(Pen *P) { P->down = 0; }

/* one separate pixel segment, clipped */
static void px_segment(const Fig *g, double x0, double y0, double x1,
                       double y1)
{
    Pen P = {g, 0, 0, 0};
    pen_line(&P, x0, y0, x1, y1);
}

static void write_curve(const Fig *g, const PlotCurve *c, const char *name,
                        const char *colour)
{
    FILE *out = g->out;
    fputs("<path class=\"curve\" id=\"curve-", out);
    put_escaped(out, name);
    fprintf(out, "\" stroke=\"%s\" stroke-width=\"", colour);
    put_num(out, 2 / g->s, 3);
    fputs("\" d=\"", out);
    long pen = -1; // sample the pen rests on, unclipped
    int cont = 0;  // the last command was L (more pairs continue it)
    for (size_t i = 1; i < c->n; i++) {
        if (c->cut[i])
            continue;
        double x0 = c->x[i - 1], y0 = c->y[i - 1], x1 = c->x[i], y1 = c->y[i];
        int c0, c1;
        if (!clip(g->clipw, &x0, &y0, &x1, &y1, &c0, &c1)) {
            pen = -1;
            continue;
        }
        if (c0 || pen != (long)i - 1) {
            fputs("M", out);
            put_num(out, x0, g->digits);
            fputc(' ', out);
            put_num(out, y0, g->digits);
            cont = 0;
        }
        fputs(cont ? " " : "L", out);
        put_num(out, x1, g->digits);
        fputc(' ', out);
        put_num(out, y1, g->digits);
        cont = 1;
        pen = c1 ? -1 : (long)i;
    }
    fputs("\"/>\n", out);
}

/* the forward-mode jet of output o at t, projected: position, r', r'' */
typedef struct Jet {
    const PlotEnv *env;
    const PlotView *view;
    unsigned char *live;
    double (*r)[3];
    double *buf; // 3 * dim
} Jet;

static void jet_init(Jet *J, const PlotEnv *env, const PlotView *view)
{
    J->env = env;
    J->view = view;
    J->live = pc_xmalloc((size_t)env->plan->nins + 1);
    J->r = pc_xmalloc(sizeof *J->r * (size_t)(env->plan->nins + 1));
    J->buf = pc_xmalloc(sizeof *J->buf * 3 * (size_t)env->dim);
}

static void jet_clear(Jet *J)
{
    free(J->live);
    free(J->r);
    free(J->buf);
}

/* p[k] = (x, y) of the k-th derivative; 1 when all finite and no status */
static int jet_at(Jet *J, int o, double t, double p[3][2])
{
    const PlotEnv *env = J->env;
    const PlanOutput *po = &env->plan->outputs[o];
    int dim = env->dim;
    plan_live(env->plan, o, J->live);
    jet_run(env, J->live, t, J->r);
    if (po->bad >= 0 && J->r[po->bad][0] != 0)
        return 0;
    int ok = 1;
    for (int k = 0; k < 3; k++) {
        double *P = J->buf + (size_t)k * (size_t)dim;
        for (int c = 0; c < dim; c++) {
            double v = 0;
            for (int j = 0; j < po->nterms; j++)
                v += J->r[po->reg[j]][k] * env->points[po->point[j]][c];
            P[c] = v;
        }
        plot_project(J->view, P, dim, &p[k][0], &p[k][1]);
        ok &= isfinite(p[k][0]) && isfinite(p[k][1]);
    }
    return ok;
}

static void write_tangents(const Fig *g, const PlotSpec *s, Jet *J)
{
    FILE *out = g->out;
    fputs("<g class=\"tangents\" stroke-width=\"1.5\">\n", out);
    for (int k = 0; k < s->ncurves; k++) {
        for (int i = 0; i < s->ntangents; i++) {
            double p[3][2];
            if (!jet_at(J, s->curves[k], s->tangents[i], p))
                continue;
            double x0, y0, x1, y1;
            px_of(g, p[0][0], p[0][1], &x0, &y0);
            px_of(g, p[0][0] + s->tangent_scale * p[1][0],
                  p[0][1] + s->tangent_scale * p[1][1], &x1, &y1);
            double dx = x1 - x0, dy = y1 - y0, l = hypot(dx, dy);
            if (!isfinite(l))
                continue;
            fprintf(out, "<path stroke=\"%s\" d=\"", palette[k % NPALETTE]);
            px_segment(g, x0, y0, x1, y1);
            /* the arrowhead, when the tip is on the canvas */
            if (l > 1 && x1 >= 0 && x1 <= g->W && y1 >= 0 && y1 <= g->H) {
                double ux = dx / l, uy = dy / l, a = l < 20 ? l / 2 : 10;
                px_segment(g, x1, y1, x1 - a * ux + 0.4 * a * uy,
                           y1 - a * uy - 0.4 * a * ux);
                px_segment(g, x1, y1, x1 - a * ux - 0.4 * a * uy,
                           y1 - a * uy + 0.4 * a * ux);
            }
            fputs("\"/>\n", out);
        }
    }
    fputs("</g>\n", out);
}

/* the curvature comb of the drawn (projected) curve: teeth along the
 * normal, away from the centre of curvature, length scale * curvature */
static void write_comb(const Fig *g, const PlotSpec *s, Jet *J,
                       const PlotCurve *cv)
{
    FILE *out = g->out;
    int n = s->comb;
    double *px = pc_xmalloc(sizeof *px * (size_t)(n + 1) * 4);
    double *kap = pc_xmalloc(sizeof *kap * (size_t)(n + 1));
    unsigned char *ok = pc_xmalloc((size_t)n + 1);
    double *fac = NULL;
    fputs("<g class=\"comb\" stroke-width=\"0.75\">\n", out);
    for (int k = 0; k < s->ncurves; k++) {
        const PlotCurve *c = &cv[k];
        int nf = c->nfac;
        fac = pc_xrealloc(fac, sizeof *fac * ((size_t)(n + 1) * (size_t)nf + 1));
        double kmax[2] = {0, 0};
        size_t nk = 0;
        for (int i = 0; i <= n; i++) {
            double t = n == 0 ? s->lo : mix(s->lo, s->hi, (double)i / n);
            double p[3][2];
            ok[i] = (unsigned char)jet_at(J, s->curves[k], t, p);
            for (int f = 0; f < nf; f++)
                fac[(size_t)i * (size_t)nf + (size_t)f] = J->r[c->facreg[f]][0];
            if (!ok[i]) /* p is not filled in */
                continue;
            double sp = hypot(p[1][0], p[1][1]);
            double kp = (p[1][0] * p[2][1] - p[1][1] * p[2][0]) / (sp * sp * sp);
            if (!(sp > 0) || !isfinite(kp))
                ok[i] = 0;
            if (!ok[i])
                continue;
            kap[i] = kp;
            px[4 * i] = p[0][0];
            px[4 * i + 1] = p[0][1];
            px[4 * i + 2] = -p[1][1] / sp; // left normal
            px[4 * i + 3] = p[1][0] / sp;
            nk++;
        }
        /* automatic scale: the 90% quantile of |curvature| makes a tooth
         * a tenth of the figure */
        double scale = s->comb_scale;
        if (!(scale > 0) && nk > 0) {
            double *a = pc_xmalloc(sizeof *a * nk);
            size_t j = 0;
            for (int i = 0; i <= n; i++)
                if (ok[i])
                    a[j++] = fabs(kap[i]);
            kmax[0] = quantile(a, nk, 0.9);
            free(a);
            scale = kmax[0] > 0 ? 0.1 * (g->W + g->H) / 2 / g->s / kmax[0] : 0;
        }
        const char *col = palette[k % NPALETTE];
        fprintf(out, "<path stroke=\"%s\" stroke-opacity=\"0.5\" d=\"", col);
        for (int i = 0; i <= n; i++) {
            if (!ok[i])
                continue;
            double ax, ay, bx, by;
            px_of(g, px[4 * i], px[4 * i + 1], &ax, &ay);
            px_of(g, px[4 * i] - scale * kap[i] * px[4 * i + 2],
                  px[4 * i + 1] - scale * kap[i] * px[4 * i + 3], &bx, &by);
            px_segment(g, ax, ay, bx, by);
        }
        fputs("\"/>\n", out);
        /* the envelope through the teeth's ends, cut where the curve is */
        fprintf(out, "<path stroke=\"%s\" d=\"", col);
        Pen pen = {g, 0, 0, 0};
        for (int i = 1; i <= n; i++) {
            if (!ok[i] || !ok[i - 1]) {
                pen_lift(&pen);
                continue;
            }
            int pole = 0;
            for (int f = 0; f < nf && !pole; f++) {
                double u = fac[(size_t)(i - 1) * (size_t)nf + (size_t)f];
                double v = fac[(size_t)i * (size_t)nf + (size_t)f];
                pole = (u < 0 && v > 0) || (u > 0 && v < 0);
            }
            if (pole) {
                pen_lift(&pen);
                continue;
            }
            double ax, ay, bx, by;
            px_of(g, px[4 * (i - 1)] - scale * kap[i - 1] * px[4 * (i - 1) + 2],
                  px[4 * (i - 1) + 1] - scale * kap[i - 1] * px[4 * (i - 1) + 3],
                  &ax, &ay);
            px_of(g, px[4 * i] - scale * kap[i] * px[4 * i + 2],
                  px[4 * i + 1] - scale * kap[i] * px[4 * i + 3], &bx, &by);
            pen_line(&pen, ax, ay, bx, by);
        }
        fputs("\"/>\n", out);
    }
    fputs("</g>\n", out);
    free(px);
    free(kap);
    free(ok);
    free(fac);
}

static void write_lines(const Fig *g, const PlotSpec *s, const double *mx,
                        const double *my)
{
    FILE *out = g->out;
    fputs("<path class=\"lines\" stroke=\"#888\" stroke-width=\"1\" d=\"", out);
    for (int i = 0; i < s->nlines; i++) {
        const PlotLine *L = &s->lines[i];
        double px[4], py[4];
        int n = 0;
        for (int k = 0; k < L->n && k < 4; k++) {
            int m = L->m[k];
            if (m < 0 || m >= s->nmarks || !isfinite(mx[m]) || !isfinite(my[m]))
                continue;
            px_of(g, mx[m], my[m], &px[n], &py[n]);
            n++;
        }
        /* the direction: the two points furthest apart */
        double best = 0;
        int a = 0, b = 0;
        for (int p = 0; p < n; p++)
            for (int q = p + 1; q < n; q++) {
                double d = hypot(px[q] - px[p], py[q] - py[p]);
                if (d > best) {
                    best = d;
                    a = p;
                    b = q;
                }
            }
        if (!(best > 0.5) || !isfinite(best))
            continue;
        double ux = (px[b] - px[a]) / best, uy = (py[b] - py[a]) / best;
        /* a little beyond both ends */
        px_segment(g, px[a] - 8 * ux, py[a] - 8 * uy, px[b] + 8 * ux,
                   py[b] + 8 * uy);
    }
    fputs("\"/>\n", out);
}

static void write_marks(const Fig *g, const PlotSpec *s, const double *mx,
                        const double *my)
{
    FILE *out = g->out;
    fputs("<g class=\"points\">\n", out);
    for (int i = 0; i < s->nmarks; i++) {
        const PlotMark *m = &s->marks[i];
        double x, y;
        px_of(g, mx[i], my[i], &x, &y);
        if (!(x >= 0 && x <= g->W && y >= 0 && y <= g->H))
            continue;
        const char *fill = m->kind == PLOT_BASE ? "#000"
                           : m->kind == PLOT_AUX
                               ? "#fff"
                               : palette[(m->curve < 0 ? 0 : m->curve) % NPALETTE];
        fputs("<circle cx=\"", out);
        put_px(out, x);
        fputs("\" cy=\"", out);
        put_px(out, y);
        fprintf(out, "\" r=\"%s\" fill=\"%s\" stroke=\"#000\"/>",
                m->kind == PLOT_BASE ? "3" : "2.5", fill);
        if (!m->name) { // a point of the construction without a name
            fputc('\n', out);
            continue;
        }
        fputs("<text x=\"", out);
        put_px(out, x + 5);
        fputs("\" y=\"", out);
        put_px(out, y - 5);
        fprintf(out, "\"%s>", m->kind == PLOT_AUX ? " fill=\"#555\"" : "");
        put_escaped(out, m->name);
        fputs("</text>\n", out);
    }
    fputs("</g>\n", out);
}

int plot_svg(FILE *out, const PlotSpec *s, PlotStats *st)
{
    const PlotEnv *env = &s->env;
    const Plan *p = env->plan;
    int nc = s->ncurves;
    PlotCurve *cv = pc_xcalloc((size_t)nc + 1, sizeof *cv);
    double *mx = pc_xmalloc(sizeof *mx * (size_t)(s->nmarks + 1));
    double *my = pc_xmalloc(sizeof *my * (size_t)(s->nmarks + 1));
    PlotStats local;
    if (!st) {
        memset(&local, 0, sizeof local);
        st = &local;
    }
    for (int i = 0; i < s->nmarks; i++)
        plot_project(&s->view, s->marks[i].at, env->dim, &mx[i], &my[i]);
    /* the budget: per curve, and PLOT_TOTAL_SAMPLES for all of them */
    PlotLimits lim = s->lim;
    if (nc > 0 && lim.max_samples > PLOT_TOTAL_SAMPLES / (size_t)nc)
        lim.max_samples = PLOT_TOTAL_SAMPLES / (size_t)nc;
    if (lim.max_samples < 2)
        lim.max_samples = 2;
    if (lim.initial < 1)
        lim.initial = 1;
    if ((size_t)lim.initial + 1 > lim.max_samples)
        lim.initial = (int)(lim.max_samples - 1);
    if (lim.max_depth > 60)
        lim.max_depth = 60;
    for (int k = 0; k < nc; k++)
        plot_curve_init(&cv[k], env, s->curves[k], s->lo, s->hi, &s->view,
                        &lim);
    double box[4];
    const double *W = s->window;
    if (W && W[0] < W[2] && W[1] < W[3] && isfinite(W[2] - W[0]) &&
        isfinite(W[3] - W[1]))
        memcpy(box, W, sizeof box);
    else
        fit_box(box, s, cv, mx, my);
    for (int k = 0; k < nc; k++)
        plot_curve_refine(&cv[k], env, &s->view, box, &lim);
    /* the canvas */
    Fig g;
    g.out = out;
    double w = box[2] - box[0], h = box[3] - box[1];
    g.W = s->width > 0 ? s->width : 720;
    if (s->height > 0) {
        g.H = s->height;
    } else {
        double hh = g.W * h / w;
        g.H = !(hh >= g.W / 3.0) ? (g.W + 2) / 3 : hh > 1.5 * g.W ? g.W * 3 / 2 : (int)(hh + 0.5);
    }
    g.s = fmin(g.W / w, g.H / h);
    double cx = (box[0] + box[2]) / 2, cy = (box[1] + box[3]) / 2;
    g.tx = g.W / 2.0 - g.s * cx;
    g.ty = g.H / 2.0 + g.s * cy;
    double ex = 4 / g.s; // 4 px beyond the canvas
    g.clipw[0] = (0 - g.tx) / g.s - ex;
    g.clipw[2] = (g.W - g.tx) / g.s + ex;
    g.clipw[1] = (g.ty - g.H) / g.s - ex;
    g.clipw[3] = g.ty / g.s + ex;
    g.clipp[0] = g.clipp[1] = -4;
    g.clipp[2] = g.W + 4;
    g.clipp[3] = g.H + 4;
    double maxabs = fmax(fmax(fabs(g.clipw[0]), fabs(g.clipw[2])),
                         fmax(fabs(g.clipw[1]), fabs(g.clipw[3])));
    double res = 0.02 / g.s; // a fiftieth of a pixel
    double lg = ceil(log10(maxabs / res));
    g.digits = !(lg >= 4) ? 4 : !(lg <= 17) ? 17 : (int)lg;
    memcpy(st->box, box, sizeof box);
    st->digits = g.digits;

    fprintf(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" "
            "width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
            "font-family=\"sans-serif\" font-size=\"14\">\n",
            g.W, g.H, g.W, g.H);
    fputs("<title>", out);
    put_escaped(out, s->title ? s->title : p->name);
    fputs("</title>\n", out);
    fprintf(out, "<rect width=\"%d\" height=\"%d\" fill=\"#fff\"/>\n", g.W, g.H);
    fputs("<g fill=\"none\" stroke-linecap=\"round\" "
          "stroke-linejoin=\"round\">\n",
          out);
    if (s->nlines)
        write_lines(&g, s, mx, my);
    Jet J;
    jet_init(&J, env, &s->view);
    if (s->comb > 0)
        write_comb(&g, s, &J, cv);
    /* the curves in world coordinates (eval's numbers, projected) */
    fputs("<g transform=\"matrix(", out);
    put_num(out, g.s, 10);
    fputs(" 0 0 ", out);
    put_num(out, -g.s, 10);
    fputc(' ', out);
    put_num(out, g.tx, 10);
    fputc(' ', out);
    put_num(out, g.ty, 10);
    fputs(")\">\n", out);
    st->samples = 0;
    st->subpaths = 0;
    for (int k = 0; k < nc; k++) {
        write_curve(&g, &cv[k], p->outputs[s->curves[k]].name,
                    palette[k % NPALETTE]);
        st->samples += cv[k].n;
        st->subpaths += plot_curve_subpaths(&cv[k]);
    }
    fputs("</g>\n", out);
    if (s->ntangents > 0)
        write_tangents(&g, s, &J);
    jet_clear(&J);
    fputs("</g>\n", out);
    write_marks(&g, s, mx, my);
    /* the legend */
    if (nc > 0) {
        fputs("<g class=\"legend\">\n", out);
        for (int k = 0; k < nc; k++) {
            fprintf(out,
                    "<path d=\"M10 %dh20\" stroke=\"%s\" stroke-width=\"2\"/>"
                    "<text x=\"36\" y=\"%d\">",
                    18 + 18 * k, palette[k % NPALETTE], 23 + 18 * k);
            put_escaped(out, p->outputs[s->curves[k]].name);
            fputs("</text>\n", out);
        }
        fputs("</g>\n", out);
    }
    fputs("</svg>\n", out);
    if (st->keep_curves) {
        st->curves = cv;
    } else {
        for (int k = 0; k < nc; k++)
            plot_curve_clear(&cv[k]);
        free(cv);
        st->curves = NULL;
    }
    free(mx);
    free(my);
    return ferror(out) ? -1 : 0;
}
