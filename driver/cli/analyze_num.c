/*
 * analyze_num.c - the curves `analyze` cannot read exactly: weights with
 * functions (sin, sqrt, abs = x sign(x), pi, dist; AnCurve.numeric),
 * found numerically on the runtime's Plan (codegen/lower.h), whose
 * forward mode gives the exact derivatives of the reduced equation
 * (plot_jet_terms), so every quantity below is the derived expression
 * evaluated in doubles, never a difference quotient.
 *
 * The base points are generic: the vertices of a simplex (point i the
 * unit vector e_i, unless --at gives every point coordinates, which dist
 * and coord then read), so the curve is its barycentric weights w(t) and
 * every finding is affinely invariant, as the exact analysis's.  Over the
 * declared range (without one: the knots of sign() and one unit beyond,
 * or [-10, 10]) the weights are sampled at
 * AN_SAMPLES uniform points and at the knots of sign() (plot_knots):
 *
 *   passes through A_j   minima of sum_{i != j} |w_i| that reach 0
 *   poles                minima of 1 / (1 + sum |w_i|) that reach 0 (or
 *                        where the Plan reports the pole)
 *   stop points          minima of sum |w_i'| that reach 0
 *   inflections          plane curves (the centred samples of rank 2):
 *                        sign changes of x'y'' - y'x'' in that plane
 *
 * A minimum is refined by golden section over its two sample intervals
 * to 1e-15 max(1, |t|) (the norms are V-shaped at a simple zero, so the
 * comparisons stay exact to the last bits), a sign change by bisection to
 * the same width; then a rational with a denominator up to 16 within
 * 1e-9 is taken instead when the function is no larger there (the knots
 * of the book's composite curves are integers).
 */
#include "driver/cli/cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "codegen/lower.h"
#include "compiler/algebra/kernel.h"
#include "compiler/analyze/analyze.h"
#include "runtime/plot.h"

enum { AN_SAMPLES = 2048, AN_GOLDEN_MAX = 200 };
#define AN_ZERO 1e-9 // a minimum this small (relative) is a zero
#define AN_PI 3.14159265358979323846

typedef struct Num {
    PlotEnv env;
    int o;               // the plan's output
    int n;               // its terms
    const int *pt;       // term -> base point
    double (*w)[3];      // the weights at the last jet (n rows)
    double *u[2];        // a plane curve: an orthonormal basis of its plane
                         // (n each), for NF_CROSS
    const PlotEnv *menv; // env when it has --at's coordinates of every
                         // point (the curvature, the arc length), or NULL
} Num;

/* what is minimised */
typedef enum NumFn { NF_PASS, NF_POLE, NF_STOP, NF_CROSS } NumFn;

/* x'y'' - y'x'' in the plane u of the jet in N->w */
static double cross(const Num *N)
{
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    for (int i = 0; i < N->n; i++) {
        x1 += N->u[0][i] * N->w[i][1];
        x2 += N->u[0][i] * N->w[i][2];
        y1 += N->u[1][i] * N->w[i][1];
        y2 += N->u[1][i] * N->w[i][2];
    }
    return x1 * y2 - y1 * x2;
}

/* the jet at t into N->w: the Plan's status (0 fine) */
static int jet(Num *N, double t)
{
    return plot_jet_terms(&N->env, N->o, t, N->w);
}

/* f at t (fn, and the term j left out for NF_PASS); NAN where a function
 * is undefined */
static double fval(Num *N, NumFn fn, int j, double t)
{
    int st = jet(N, t);
    if (st == PLAN_STATUS_DOMAIN)
        return NAN;
    if (st == PLAN_STATUS_POLE || st == PLAN_STATUS_OVERFLOW)
        return fn == NF_POLE ? 0.0 : NAN;
    /* else fine, or a derivative that is not finite (sqrt at 0) */
    if (fn == NF_CROSS)
        return cross(N);
    double s = 0;
    for (int i = 0; i < N->n; i++)
        if (fn == NF_STOP)
            s += fabs(N->w[i][1]);
        else if (fn == NF_POLE || i != j)
            s += fabs(N->w[i][0]);
    return fn == NF_POLE ? 1 / (1 + s) : s;
}

/* v.v' of what NF_PASS (v the weights but w_j) or NF_STOP (v = w')
 * takes the norm of: half the derivative of |v|^2, which changes sign at
 * a zero of v, simple or not; NAN where undefined */
static double vdv(Num *N, NumFn fn, int j, double t)
{
    if (jet(N, t) % 3) /* 3: a derivative is not finite */
        return NAN;
    double s = 0;
    int k = fn == NF_STOP;
    for (int i = 0; i < N->n; i++)
        if (fn == NF_STOP || i != j)
            s += N->w[i][k] * N->w[i][k + 1];
    return s;
}

static double width_at(double t)
{
    return 1e-15 * fmax(1.0, fabs(t));
}

/* the minimum of f in [a, b] by golden section; *fm its value */
static double golden(Num *N, NumFn fn, int j, double a, double b, double *fm)
{
    const double g = 0.6180339887498949;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = fval(N, fn, j, c), fd = fval(N, fn, j, d);
    for (int it = 0; it < AN_GOLDEN_MAX && b - a > width_at(a); it++) {
        if (!(fc > fd)) { /* NAN on the right: go left */
            b = d, d = c, fd = fc;
            c = b - g * (b - a);
            fc = fval(N, fn, j, c);
        } else {
            a = c, c = d, fc = fd;
            d = a + g * (b - a);
            fd = fval(N, fn, j, d);
        }
    }
    double t = fc <= fd ? c : d;
    *fm = fmin(fc, fd);
    for (int e = 0; e < 2; e++) { /* the bracket's ends themselves */
        double x = e ? b : a, fx = fval(N, fn, j, x);
        if (fx < *fm)
            t = x, *fm = fx;
    }
    return t;
}

/* sum sigma_i v_i' at t (v as vdv's, sigma the signs of v at the left
 * end): at a double zero of v, - before it and + after; NAN where
 * undefined */
static double sdv(Num *N, NumFn fn, int j, double t, const double *sigma)
{
    if (jet(N, t) % 3)
        return NAN;
    double s = 0;
    int k = fn == NF_STOP;
    for (int i = 0; i < N->n; i++)
        if (fn == NF_STOP || i != j)
            s += sigma[i] * N->w[i][k + 1];
    return s;
}

/* a double zero of v near t, where v rounds to 0 over a band: bisection
 * on sdv over [a, b]; t itself when that does not change sign there */
static double flat_zero(Num *N, NumFn fn, int j, double a, double b, double t)
{
    int k = fn == NF_STOP;
    if (jet(N, a) % 3)
        return t;
    double *sigma = pc_xmalloc((size_t)(N->n + 1) * sizeof *sigma);
    for (int i = 0; i < N->n; i++)
        sigma[i] = N->w[i][k] < 0 ? -1 : 1;
    double fa = sdv(N, fn, j, a, sigma), fb = sdv(N, fn, j, b, sigma);
    if (fa < 0 && fb > 0) {
        while (b - a > width_at(a)) {
            double m = a + (b - a) / 2, f = sdv(N, fn, j, m, sigma);
            if (m <= a || m >= b || isnan(f))
                break;
            if (f < 0)
                a = m;
            else
                b = m;
        }
        t = a + (b - a) / 2;
    }
    pc_free(sigma);
    return t;
}

/* the minimum of |v| in [a, b] by bisection on v.v' (vdv), when that
 * changes sign from - to + there; else golden section */
static double refine(Num *N, NumFn fn, int j, double a, double b, double *fm)
{
    double fa = fn == NF_POLE ? NAN : vdv(N, fn, j, a);
    double fb = fn == NF_POLE ? NAN : vdv(N, fn, j, b);
    if (!(fa < 0 && fb > 0))
        return golden(N, fn, j, a, b, fm);
    while (b - a > width_at(a)) {
        double m = a + (b - a) / 2, f = vdv(N, fn, j, m);
        if (m <= a || m >= b || isnan(f))
            break;
        if (f < 0)
            a = m;
        else
            b = m;
    }
    double t = a + (b - a) / 2;
    *fm = fval(N, fn, j, t);
    return t;
}

/* a rational p/q (q <= 16) within 1e-9 of t where |f| is no larger */
static double snap(Num *N, NumFn fn, int j, double t, double ft)
{
    for (int q = 1; q <= 16; q++) {
        double r = nearbyint(t * q) / q;
        if (r == t)
            return t;
        if (fabs(r - t) <= 1e-9 * fmax(1.0, fabs(t)) &&
            fabs(fval(N, fn, j, r)) <= fabs(ft))
            return r;
    }
    return t;
}

/* appends t to r unless a root within 1e-9 is there */
static void add_root(AnRoots *r, double t)
{
    for (slong i = 0; i < r->n; i++)
        if (fabs(r->v[i].value - t) <= 1e-9 * fmax(1.0, fabs(t)))
            return;
    roots_push_value(r, t, 1);
}

/* where a run of zero samples really ends: from ts[i] towards ts[i + dir]
 * (when there is one), by bisection on f <= tol */
static double run_end(Num *N, NumFn fn, int j, double tol, const double *ts,
                      int ns, int i, int dir)
{
    if (i + dir < 0 || i + dir >= ns)
        return ts[i];
    double in = ts[i], out = ts[i + dir];
    for (int it = 0; it < 200 && fabs(out - in) > width_at(in); it++) {
        double m = in + (out - in) / 2;
        if (fval(N, fn, j, m) <= tol)
            in = m;
        else
            out = m;
    }
    for (int q = 1; q <= 16; q++) { /* a knot near: the book's integers */
        double r = nearbyint(in * q) / q;
        if (fabs(r - in) <= 1e-9 * fmax(1.0, fabs(in)))
            return r; /* the run's limit (f at a knot itself is the mean) */
    }
    return in;
}

/* the zeros of f: its local minima over the samples ts[0..ns-1] that
 * reach AN_ZERO of its largest value (1 for NF_POLE); a run of samples
 * that are all zeros is one interval (AN_RUN_START, AN_RUN_END) */
static void zeros(AnRoots *res, Num *N, NumFn fn, int j, const double *ts,
                  int ns)
{
    double *f = pc_xmalloc((size_t)ns * sizeof *f), big = 0;
    for (int i = 0; i < ns; i++) {
        f[i] = fval(N, fn, j, ts[i]);
        if (isfinite(f[i]))
            big = fmax(big, f[i]);
    }
    double tol = AN_ZERO * (fn == NF_POLE || big == 0 ? 1.0 : big);
    for (int i = 0; i < ns; i++) {
        if (f[i] <= tol && i + 1 < ns && f[i + 1] <= tol) {
            int k = i + 1;
            while (k + 1 < ns && f[k + 1] <= tol)
                k++;
            roots_push_value(res, run_end(N, fn, j, tol, ts, ns, i, -1) + 0.0,
                             AN_RUN_START);
            roots_push_value(res, run_end(N, fn, j, tol, ts, ns, k, 1) + 0.0,
                             AN_RUN_END);
            i = k;
            continue;
        }
        if (isnan(f[i]) || (i > 0 && f[i - 1] < f[i]) ||
            (i + 1 < ns && f[i + 1] < f[i]) || f[i] > 0.05 * big + tol)
            continue;
        double fm = f[i], a = ts[i > 0 ? i - 1 : i];
        double b = ts[i + 1 < ns ? i + 1 : i];
        double t = a < b ? refine(N, fn, j, a, b, &fm) : ts[i];
        if (fn != NF_POLE && a < b) { /* a double zero: on v' */
            t = flat_zero(N, fn, j, a, b, t);
            fm = fmin(fm, fval(N, fn, j, t));
        }
        if (fm <= tol)
            add_root(res, snap(N, fn, j, t, fm));
    }
    pc_free(f);
}

/* the samples: uniform over [lo, hi] and the knots, sorted */
static int samples(double **ts, Num *N, double lo, double hi)
{
    double *knots = NULL;
    size_t nk = plot_knots(&N->env, N->o, lo, hi, &knots);
    int ns = AN_SAMPLES + 1 + (int)nk;
    double *t = pc_xmalloc((size_t)ns * sizeof *t);
    for (int i = 0; i <= AN_SAMPLES; i++)
        t[i] = i == AN_SAMPLES ? hi : lo + (hi - lo) * i / AN_SAMPLES;
    for (size_t k = 0; k < nk; k++)
        t[AN_SAMPLES + 1 + k] = knots[k];
    pc_free(knots);
    for (int i = 1; i < ns; i++) /* insertion: the knots are few */
        for (int k = i; k > 0 && t[k - 1] > t[k]; k--) {
            double x = t[k];
            t[k] = t[k - 1];
            t[k - 1] = x;
        }
    int m = 0;
    for (int i = 0; i < ns; i++) /* without repeats */
        if (!m || t[i] != t[m - 1])
            t[m++] = t[i];
    *ts = t;
    return m;
}

/* ---- the plane of the curve ---------------------------------------------- */

/* the dimension of the flat of the samples' weights (0..3, 3 meaning 3
 * or more), from a Gram-Schmidt of the centred rows; the first two
 * directions into N->u */
static int flat_dim(Num *N, const double *ts, int ns)
{
    int n = N->n, dim = 0;
    double *row0 = pc_xcalloc((size_t)n + 1, sizeof *row0);
    double *v = pc_xmalloc((size_t)(n + 1) * sizeof *v);
    double *basis = pc_xcalloc(3 * (size_t)n + 1, sizeof *basis);
    double big = 0;
    int have0 = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < ns && dim < 3; i++) {
            if (jet(N, ts[i]))
                continue;
            if (!have0) {
                for (int k = 0; k < n; k++)
                    row0[k] = N->w[k][0];
                have0 = 1;
                continue;
            }
            double nv = 0;
            for (int k = 0; k < n; k++) {
                v[k] = N->w[k][0] - row0[k];
                nv += v[k] * v[k];
            }
            if (pass == 0) { /* the scale first */
                big = fmax(big, sqrt(nv));
                continue;
            }
            for (int b = 0; b < dim; b++) {
                double dot = 0;
                for (int k = 0; k < n; k++)
                    dot += v[k] * basis[b * n + k];
                for (int k = 0; k < n; k++)
                    v[k] -= dot * basis[b * n + k];
            }
            nv = 0;
            for (int k = 0; k < n; k++)
                nv += v[k] * v[k];
            if (sqrt(nv) <= 1e-7 * big)
                continue;
            for (int k = 0; k < n; k++)
                basis[dim * n + k] = v[k] / sqrt(nv);
            dim++;
        }
    for (int b = 0; b < 2; b++) {
        N->u[b] = pc_xcalloc((size_t)n + 1, sizeof *N->u[b]);
        if (b < dim)
            memcpy(N->u[b], basis + b * n, (size_t)n * sizeof *basis);
    }
    pc_free(basis);
    pc_free(v);
    pc_free(row0);
    return dim;
}

/* the sign changes of the cross product between samples, by bisection,
 * away from the stop points */
static void inflections(AnCurve *c, Num *N, const double *ts, int ns)
{
    double pt = NAN, pf = NAN;
    for (int i = 0; i < ns; i++) {
        double f = fval(N, NF_CROSS, 0, ts[i]);
        if (isnan(f) || f == 0) {
            if (isnan(f))
                pf = NAN;
            continue;
        }
        int pole = 0;
        for (slong k = 0; k < c->poles.n; k++)
            pole |= c->poles.v[k].value >= pt && c->poles.v[k].value <= ts[i];
        if (!isnan(pf) && (f > 0) != (pf > 0) && !pole) {
            double a = pt, b = ts[i], fa = pf;
            while (b - a > width_at(a)) {
                double m = a + (b - a) / 2, fm = fval(N, NF_CROSS, 0, m);
                if (m <= a || m >= b || isnan(fm))
                    break;
                if (fm == 0) {
                    a = b = m;
                    break;
                }
                if ((fm > 0) == (fa > 0))
                    a = m, fa = fm;
                else
                    b = m;
            }
            double t = a + (b - a) / 2;
            t = snap(N, NF_CROSS, 0, t, fval(N, NF_CROSS, 0, t));
            int stop = 0;
            for (slong k = 0; k < c->stops.n; k++)
                stop |= fabs(c->stops.v[k].value - t) <= 1e-9;
            if (!stop)
                add_root(&c->infl, t);
        }
        pt = ts[i], pf = f;
    }
    c->has_infl = 1;
}

/* ---- the ends ------------------------------------------------------------ */

/* the end at t = x, the derivative from inside (in the direction dir) */
static void end_at(AnEnd *e, Num *N, double x, double dir, slong npoints)
{
    char buf[40];
    pc_snprintf(buf, sizeof buf, "%.15g", x);
    e->t = pc_xstrdup(buf);
    int finite = jet(N, x) % 3 == 0;
    for (int i = 0; i < N->n; i++)
        finite &= isfinite(N->w[i][0]);
    if (!finite) {
        e->infinite = 1; /* no finite point there */
        return;
    }
    e->num = pc_xcalloc((size_t)npoints + 1, sizeof *e->num);
    for (int i = 0; i < N->n; i++)
        e->num[N->pt[i]] += N->w[i][0] + 0.0;
    if (jet(N, nextafter(x, x + dir)))
        return; /* a derivative that is not finite: no tangent */
    double s1 = 0, s2 = 0;
    for (int i = 0; i < N->n; i++) {
        s1 += fabs(N->w[i][1]);
        s2 += fabs(N->w[i][2]);
    }
    if (!(s1 < 1e6))
        return; /* it goes to infinity there (sqrt at 0): no tangent */
    (void)s2;
    e->first = s1 > 1e-12 ? 1 : 2;
    e->num_tan = pc_xcalloc((size_t)npoints + 1, sizeof *e->num_tan);
    for (int i = 0; i < N->n; i++)
        e->num_tan[N->pt[i]] += N->w[i][e->first];
}

/* ---- one curve ----------------------------------------------------------- */

static void passes(AnCurve *c, Num *N, const double *ts, int ns)
{
    c->pass = pc_xcalloc((size_t)N->n + 1, sizeof *c->pass);
    for (int j = 0; j < N->n; j++) {
        AnPass *p = c->pass + c->npass;
        roots_init(&p->t);
        zeros(&p->t, N, NF_PASS, j, ts, ns);
        if (p->t.n) {
            p->point = N->pt[j];
            c->npass++;
        } else
            roots_clear(&p->t);
    }
}

/* where a function is undefined: the first and last such sample */
static void undefined(AnCurve *c, Num *N, const double *ts, int ns)
{
    c->undefined[0] = c->undefined[1] = NAN;
    for (int i = 0; i < ns; i++)
        if (jet(N, ts[i]) == PLAN_STATUS_DOMAIN) {
            if (isnan(c->undefined[0]))
                c->undefined[0] = ts[i];
            c->undefined[1] = ts[i];
        }
}

/* p at the values of its variables: pi for the kernel pi, nothing else
 * (a declared range's end such as 2*pi); NAN otherwise */
static double poly_value(const fmpz_mpoly_t p, const Derived *d)
{
    const fmpz_mpoly_ctx_struct *ctx = d->ring.ctx;
    slong nv = ctx->minfo->nvars;
    ulong *e = pc_xmalloc((size_t)(nv + 1) * sizeof *e);
    double v = 0;
    for (slong i = 0; i < fmpz_mpoly_length(p, ctx) && !isnan(v); i++) {
        fmpz_mpoly_get_term_exp_ui(e, p, i, ctx);
        double term = fmpz_get_d(p->coeffs + i);
        for (slong x = 0; x < nv && !isnan(v); x++) {
            const Kernel *k =
                e[x] && d->kernels ? kernels_of_var(d->kernels, x) : NULL;
            if (e[x] && (!k || k->fn != KF_PI))
                v = NAN;
            term *= pow(AN_PI, (double)e[x]);
        }
        v += term;
    }
    pc_free(e);
    return v;
}

/* the declared range's ends as numbers (2*pi too) into lo, hi */
static void range_values(double *lo, double *hi, const AnCurve *c,
                         const Derived *d)
{
    const RatFunStruct *r = d->range + 2 * c->param;
    for (int e = 0; e < 2; e++) {
        double v = poly_value(r[e].num, d) / poly_value(r[e].den, d);
        if (isfinite(v))
            *(e ? hi : lo) = v;
    }
}

static void num_curve(AnCurve *c, Num *N, const Derived *d)
{
    double lo = -10, hi = 10;
    if (c->bounded)
        range_values(&lo, &hi, c, d);
    double *knots = NULL;
    size_t nk = c->bounded ? 0 : plot_knots(&N->env, N->o, lo, hi, &knots);
    if (nk) { /* no range: the knots and one unit beyond */
        lo = knots[0] - 1;
        hi = knots[nk - 1] + 1;
    }
    pc_free(knots);
    c->num_lo = lo, c->num_hi = hi;
    double *ts;
    int ns = samples(&ts, N, lo, hi);
    undefined(c, N, ts, ns);
    zeros(&c->poles, N, NF_POLE, 0, ts, ns);
    if (c->kind == KIND_POINT) {
        zeros(&c->stops, N, NF_STOP, 0, ts, ns);
        passes(c, N, ts, ns);
        c->dim = flat_dim(N, ts, ns);
        if (c->dim == 2)
            inflections(c, N, ts, ns);
    }
    if (c->bounded) {
        c->nends = 2;
        end_at(c->ends + 0, N, lo, 1, d->npoints);
        end_at(c->ends + 1, N, hi, -1, d->npoints);
    }
    if (N->menv && c->bounded)
        analyze_num_metric(c, N->menv, N->o, ts, ns);
    pc_free(ts);
    c->num_done = 1;
}

/* the base points' coordinates: set's when it gives every point, else the
 * simplex (point i = e_i) */
static double **coordinates(int *dim, const Derived *d, const AnSet *set)
{
    int all = set && set->dim > 0;
    for (slong i = 0; all && i < d->npoints; i++)
        all = set->pt[i] != NULL;
    *dim = all ? set->dim : (int)FLINT_MAX(d->npoints, 1);
    double **pt = pc_xcalloc((size_t)d->npoints + 1, sizeof *pt);
    for (slong i = 0; i < d->npoints; i++) {
        pt[i] = pc_xcalloc((size_t)*dim, sizeof *pt[i]);
        if (all)
            memcpy(pt[i], set->pt[i], (size_t)*dim * sizeof *pt[i]);
        else
            pt[i][i] = 1;
    }
    return pt;
}

void analyze_numeric(Analysis *a, const AnSet *set)
{
    const Derived *d = a->d;
    int any = 0;
    for (slong i = 0; i < a->ncurves; i++)
        any |= a->curves[i].numeric;
    if (!any)
        return;
    Plan *p = lower_derived(d, NULL);
    int dim;
    double **pt = coordinates(&dim, d, set);
    double *params = pc_xcalloc((size_t)d->nparams + 1, sizeof *params);
    double *consts = pc_xcalloc((size_t)d->nconsts + 1, sizeof *consts);
    for (slong k = 0; k < d->nconsts; k++)
        lower_q_to_double(consts + k, a->cvalue + k);
    for (slong i = 0; i < a->ncurves; i++) {
        AnCurve *c = a->curves + i;
        if (!c->numeric)
            continue;
        int o = p ? plan_find_output(p, c->name) : -1;
        if (o < 0) {
            c->num_why = pc_xstrdup("it cannot be evaluated in double "
                                    "precision (emit-c says why)");
            continue;
        }
        Num N = {
            {p, (int)c->param, params, consts, (const double *const *)pt, dim},
            o,
            p->outputs[o].nterms,
            p->outputs[o].point,
            NULL,
            {0},
            NULL};
        if (dim == (set ? set->dim : 0)) /* coordinates() took --at's */
            N.menv = &N.env;
        else if (set && set->dim)
            c->metric_missing = 1;
        N.w = pc_xmalloc(sizeof *N.w * (size_t)(N.n + 1));
        num_curve(c, &N, d);
        pc_free(N.u[0]);
        pc_free(N.u[1]);
        pc_free(N.w);
    }
    for (slong k = 0; k < d->npoints; k++)
        pc_free(pt[k]);
    pc_free(pt);
    pc_free(params);
    pc_free(consts);
    plan_free(p);
}
