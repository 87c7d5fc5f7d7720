/*
 * fit.c - the engine of `pointcalc fit` (fit.h, docs/fit.md): the
 * chapter-5 approximation with optimal nodes, on the exact curve and the
 * exact derivative pointcalc derives.
 *
 *   target text -> derive "param x / f = EXPR / fp = diff(f, x)" -> Plan
 *   N           -> derive the families interpolation scheme with n = N-1
 *               -> weights phi_k(t): exact coefficients, and a Plan
 *               -> phi_k(t_i) tabulated once at t_i = i/m
 *   starts      -> lsq_solve (runtime/lsq.c) on the log-gaps u -> best
 *
 * Residuals r_i = f(x(t_i)) - y(t_i) with x(t) = sum x_k phi_k(t) and
 * y(t) = sum f(x_k) phi_k(t); their Jacobian is exact:
 *   dr_i/dx_j = phi_j(t_i) (f'(x(t_i)) - f'(x_j)),
 * chained with dx/du of the log-gap map (fit.h).  Each evaluation is one
 * plan_eval of f (and of f') over the m + 1 samples and the N nodes.
 */
#include "driver/cli/fit.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "runtime/eval.h"

#define FIT_PI 3.14159265358979323846

/* the families scheme of docs/language.md (monograph 4.8) */
static const char curve_text[] =
    "scheme fit_curve\n"
    "int n = 5\n"
    "point M[1..n+1]\n"
    "param t in [0, 1]\n"
    "unknown C[2..n]\n"
    "X = bezier(t, M[1], C[2..n], M[n+1])\n"
    "solve subst(X, t, (i-1)/n) = M[i] for i in 2..n for C[2..n]\n"
    "output X\n";

/* the exact coefficients of each phi_k, weights of output `out` in ring
 * variable var: coef[k*n + j] = that of t^j.  -1 when a weight is not a
 * polynomial in that variable alone of degree < n. */
int fit_curve_coefficients(double *coef, const Derived *d, int out, slong var,
                           int n)
{
    const DerivedOutput *X = &d->outputs[out];
    const fmpz_mpoly_ctx_struct *ctx = d->ring.ctx;
    slong nv = ctx->minfo->nvars;
    ulong *ex = pc_xmalloc(sizeof *ex * (size_t)(nv ? nv : 1));
    int rc = 0;
    fmpz_t c, den;
    fmpq_t q;
    fmpz_init(c);
    fmpz_init(den);
    fmpq_init(q);
    memset(coef, 0, sizeof *coef * (size_t)n * (size_t)n);
    for (slong i = 0; i < X->eq->len && rc == 0; i++) {
        slong k = X->eq->terms[i].point;
        const RatFunStruct *w = &X->w[i];
        if (k < 0 || k >= n || !fmpz_mpoly_is_fmpz(w->den, ctx)) {
            rc = -1;
            break;
        }
        fmpz_mpoly_get_fmpz(den, w->den, ctx);
        for (slong e = 0; e < fmpz_mpoly_length(w->num, ctx); e++) {
            fmpz_mpoly_get_term_exp_ui(ex, w->num, e, ctx);
            ulong j = ex[var], other = 0;
            for (slong v = 0; v < nv; v++)
                other += v == var ? 0 : ex[v];
            if (j >= (ulong)n || other) {
                rc = -1;
                break;
            }
            fmpz_mpoly_get_term_coeff_fmpz(c, w->num, e, ctx);
            fmpq_set_fmpz_frac(q, c, den);
            coef[k * n + (slong)j] = fmpq_get_d(q);
        }
    }
    fmpq_clear(q);
    fmpz_clear(den);
    fmpz_clear(c);
    pc_free(ex);
    return rc;
}

/* phi[i*n + k] = phi_k(t_i), t_i = i/(ns - 1): output out of p evaluated
 * with base point M_k at the k-th unit vector of R^n, t its param `param`
 * of nparams (the others 0) */
int fit_curve_table(double *phi, const Plan *p, const double *consts, int out,
                    int param, int nparams, size_t ns, int n)
{
    double *t = pc_xcalloc(ns * 2, sizeof *t);
    double *unit = pc_xcalloc((size_t)n * (size_t)n, sizeof *unit);
    const double **pts = pc_xmalloc(sizeof *pts * (size_t)n);
    const double **params = pc_xmalloc(sizeof *params * (size_t)nparams);
    unsigned char *st = pc_xmalloc(ns);
    for (size_t i = 0; i < ns; i++)
        t[i] = (double)i / (double)(ns - 1);
    for (int k = 0; k < n; k++) {
        unit[k * n + k] = 1;
        pts[k] = unit + k * n;
    }
    for (int j = 0; j < nparams; j++)
        params[j] = j == param ? t : t + ns;
    size_t bad = plan_eval(p, out, ns, params, consts, pts, n, phi, st);
    pc_free(st);
    pc_free(params);
    pc_free(pts);
    pc_free(unit);
    pc_free(t);
    return bad ? -1 : 0;
}

int fit_lagrange_curve(int n, size_t ns, double **phi, double **coef, FILE *err)
{
    char def[32];
    const char *defs[1] = {def};
    pc_snprintf(def, sizeof def, "n=%d", n - 1);
    DeriveOptions opt = {
        .max_seconds = BUDGET_DEFAULT_SECONDS, .defines = defs, .ndefines = 1};
    Derived *d = derive_source_ex("<fit curve>", curve_text,
                                  sizeof curve_text - 1, err, NULL, &opt);
    Plan *p = d ? lower_derived(d, err) : NULL;
    int rc = p && d->noutputs == 1 && d->npoints == n ? 0 : -1;
    *phi = pc_xmalloc(sizeof **phi * ns * (size_t)n);
    *coef = pc_xmalloc(sizeof **coef * (size_t)n * (size_t)n);
    if (rc == 0)
        rc = fit_curve_coefficients(*coef, d, 0, 0, n);
    if (rc == 0)
        rc = fit_curve_table(*phi, p, NULL, 0, 0, 1, ns, n);
    if (rc != 0)
        fprintf(err,
                "pointcalc: fit: the derived curve through %d nodes is "
                "not an interpolation polynomial curve\n",
                n);
    plan_free(p);
    derived_free(d);
    return rc;
}

/* f and f' of the target, derived and lowered; the messages of a target
 * with an error name its text as "<target>" */
static Plan *derive_target(const char *expr, FILE *err)
{
    char *text = pc_xasprintf("param x\nf = %s\nfp = diff(f, x)\n"
                              "output f, fp\n",
                              expr);
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS};
    Derived *d =
        derive_source_ex("<target>", text, strlen(text), err, NULL, &opt);
    Plan *p = NULL;
    if (d && d->outputs[0].kind != KIND_SCALAR)
        fprintf(err,
                "pointcalc: fit: the target '%s' is a %s, not a scalar "
                "function of x\n",
                expr, d->outputs[0].kind == KIND_POINT ? "point" : "vector");
    else if (d)
        p = lower_derived(d, err);
    derived_free(d);
    pc_free(text);
    return p;
}

static const char *status_text(unsigned char st)
{
    switch (st) {
    case PLAN_STATUS_POLE:
        return "a denominator vanishes (a pole)";
    case PLAN_STATUS_DOMAIN:
        return "a function's argument is outside its domain (sqrt of a "
               "negative number, ln of one <= 0, asin or acos beyond [-1, 1])";
    default:
        return "its value is not finite in double precision";
    }
}

enum { CHECK_SAMPLES = 2001 };

void fit_target_at(const Fit *f, int o, size_t n, const double *x, double *v,
                   unsigned char *st)
{
    const FitTarget *t = &f->tg;
    if (t->spline) {
        fit_spline_eval(t->spline, o, n, x, v, st);
        return;
    }
    f->tpar[t->param] = x;
    if (f->prog[o ? 1 : 0])
        plan_prog_eval(f->prog[o ? 1 : 0], n, f->tpar, v, st);
    else
        plan_eval(t->plan, o ? t->fp_out : t->f_out, n, f->tpar, t->consts,
                  NULL, 0, v, st);
}

/* f on CHECK_SAMPLES points of [lo, hi], ends included: defined and
 * finite everywhere, else an error that says where */
static int check_target(const Fit *f, FILE *err)
{
    size_t n = CHECK_SAMPLES;
    double *x = pc_xmalloc(sizeof *x * n), *v = pc_xmalloc(sizeof *v * n);
    unsigned char *st = pc_xmalloc(n);
    for (size_t i = 0; i < n; i++)
        x[i] = i + 1 == n ? f->o.hi
                          : f->o.lo + (f->o.hi - f->o.lo) * (double)i /
                                          (double)(n - 1);
    fit_target_at(f, 0, n, x, v, st);
    size_t first = n, last = 0, count = 0;
    for (size_t i = 0; i < n; i++) {
        if (st[i] == PLAN_STATUS_OK && isfinite(v[i]))
            continue;
        if (st[i] == PLAN_STATUS_OK)
            st[i] = 3;
        if (first == n)
            first = i;
        last = i;
        count++;
    }
    if (count)
        pc_fprintf(err,
                   "pointcalc: fit: the target '%s' is undefined at x = %.9g: "
                   "%s; %zu of %zu samples of [%.9g, %.9g] are, from x = "
                   "%.9g to x = %.9g\n",
                   f->tg.label, x[first],
                   f->tg.spline ? "outside the data" : status_text(st[first]),
                   count, n, f->o.lo, f->o.hi, x[first], x[last]);
    pc_free(st);
    pc_free(v);
    pc_free(x);
    return count ? -1 : 0;
}

int fit_check_options(const FitOptions *o, FILE *err)
{
    if (!(o->lo < o->hi) || !isfinite(o->lo) || !isfinite(o->hi)) {
        pc_fprintf(err,
                   "pointcalc: fit: --on LO,HI needs LO < HI, finite; "
                   "found %.17g,%.17g\n",
                   o->lo, o->hi);
        return -1;
    }
    if (o->nodes < 3 || o->nodes > LSQ_MAX_UNKNOWNS + 2) {
        fprintf(err,
                "pointcalc: fit: --nodes must be 3 .. %d (two end "
                "nodes and at least one free one); found %d\n",
                LSQ_MAX_UNKNOWNS + 2, o->nodes);
        return -1;
    }
    if (o->samples < o->nodes || o->samples >= LSQ_MAX_RESIDUALS) {
        fprintf(err,
                "pointcalc: fit: --samples must be %d .. %d (at least "
                "the number of nodes); found %d\n",
                o->nodes, LSQ_MAX_RESIDUALS - 1, o->samples);
        return -1;
    }
    if (o->max_iter < 0) {
        fprintf(err, "pointcalc: fit: --max-iter must be >= 1; found %d\n",
                o->max_iter);
        return -1;
    }
    if (o->starts < 0 || o->starts > 1000) {
        fprintf(err, "pointcalc: fit: --starts must be 0 .. 1000; found %d\n",
                o->starts);
        return -1;
    }
    return 0;
}

static void target_clear(FitTarget *t)
{
    plan_free(t->plan);
    fit_spline_free(t->spline);
    pc_free(t->consts);
    t->consts = NULL;
    t->plan = NULL;
    t->spline = NULL;
}

Fit *fit_new_from(const FitOptions *o, FitTarget *t, double *phi, double *coef,
                  int ends_exact, FILE *err, int *rc)
{
    *rc = 2;
    if (fit_check_options(o, err) != 0) {
        target_clear(t);
        pc_free(phi);
        pc_free(coef);
        return NULL;
    }
    *rc = 1;
    Fit *f = pc_xcalloc(1, sizeof *f);
    f->o = *o;
    f->n = o->nodes;
    f->nu = o->nodes - 2;
    f->ns = (size_t)o->samples + 1;
    f->tg = *t;
    f->phi = phi;
    f->coef = coef;
    f->ends_exact = ends_exact;
    size_t n = (size_t)f->n, ne = f->ns + n;
    size_t nz = ne > CHECK_SAMPLES ? ne : CHECK_SAMPLES;
    int np = t->plan ? t->nparams : 0;
    f->tpar = pc_xcalloc((size_t)(np ? np : 1), sizeof *f->tpar);
    f->tzero = pc_xcalloc(np > 1 ? nz : 1, sizeof *f->tzero);
    for (int j = 0; j < np; j++)
        f->tpar[j] = f->tzero;
    f->x = pc_xmalloc(sizeof *f->x * n);
    f->xs = pc_xmalloc(sizeof *f->xs * ne);
    f->fx = pc_xmalloc(sizeof *f->fx * ne);
    f->fpx = pc_xmalloc(sizeof *f->fpx * ne);
    f->st = pc_xmalloc(ne);
    f->jx = pc_xmalloc(sizeof *f->jx * f->ns * n);
    f->rlast = pc_xmalloc(sizeof *f->rlast * f->ns);
    f->xlast = pc_xmalloc(sizeof *f->xlast * n);
    if (t->plan && !o->legacy) {
        f->prog[0] = plan_prog_new(t->plan, t->f_out, t->consts, NULL, 0);
        f->prog[1] = plan_prog_new(t->plan, t->fp_out, t->consts, NULL, 0);
    }
    if (check_target(f, err) != 0) {
        fit_free(f);
        return NULL;
    }
    *rc = 0;
    return f;
}

Fit *fit_new(const char *target, const FitOptions *o, FILE *err, int *rc)
{
    *rc = 2;
    if (fit_check_options(o, err) != 0)
        return NULL;
    *rc = 1;
    FitTarget t = {.nparams = 1, .fp_out = 1, .label = target};
    double *phi = NULL, *coef = NULL;
    t.plan = derive_target(target, err);
    if (!t.plan || fit_lagrange_curve(o->nodes, (size_t)o->samples + 1, &phi,
                                      &coef, err) != 0) {
        target_clear(&t);
        pc_free(phi);
        pc_free(coef);
        return NULL;
    }
    return fit_new_from(o, &t, phi, coef, 1, err, rc);
}

void fit_free(Fit *f)
{
    if (!f)
        return;
    plan_prog_free(f->prog[0]);
    plan_prog_free(f->prog[1]);
    target_clear(&f->tg);
    pc_free(f->rlast);
    pc_free(f->xlast);
    pc_free(f->tpar);
    pc_free(f->tzero);
    pc_free(f->phi);
    pc_free(f->coef);
    pc_free(f->x);
    pc_free(f->xs);
    pc_free(f->fx);
    pc_free(f->fpx);
    pc_free(f->st);
    pc_free(f->jx);
    pc_free(f);
}

/* f (output 0) or f' (output 1) at the ns + n points f->xs into v; -1
 * where one is undefined or not finite */
static int target_eval(Fit *f, int o, double *v)
{
    size_t ne = f->ns + (size_t)f->n;
    fit_target_at(f, o, ne, f->xs, v, f->st);
    for (size_t i = 0; i < ne; i++)
        if (f->st[i] != PLAN_STATUS_OK || !isfinite(v[i]))
            return -1;
    return 0;
}
int fit_residuals_x(Fit *f, const double *xin, double *r, double *J)
{
    int n = f->n, nu = f->nu;
    f->x[0] = f->o.lo;
    f->x[n - 1] = f->o.hi;
    memcpy(f->x + 1, xin, sizeof *xin * (size_t)nu);
    for (size_t i = 0; i < f->ns; i++) {
        const double *ph = f->phi + i * (size_t)n;
        double s = 0;
        for (int k = 0; k < n; k++)
            s += f->x[k] * ph[k];
        f->xs[i] = s;
    }
    /* the ends are exact: no rounding may take x(t) outside [lo, hi] */
    if (f->ends_exact) {
        f->xs[0] = f->o.lo;
        f->xs[f->ns - 1] = f->o.hi;
    }
    memcpy(f->xs + f->ns, f->x, sizeof *f->x * (size_t)n);
    /* (only with the Jacobian: a call for r alone leaves f->fx as its
     * callers read it, f at the samples and the nodes) */
    if (J && f->rvalid &&
        memcmp(f->xlast, f->x, sizeof *f->x * (size_t)n) == 0) {
        memcpy(r, f->rlast, sizeof *r * f->ns);
    } else {
        f->rvalid = 0;
        if (target_eval(f, 0, f->fx) != 0)
            return -1;
        const double *fk = f->fx + f->ns;
        for (size_t i = 0; i < f->ns; i++) {
            const double *ph = f->phi + i * (size_t)n;
            double y = 0;
            for (int k = 0; k < n; k++)
                y += fk[k] * ph[k];
            r[i] = f->fx[i] - y;
        }
        memcpy(f->rlast, r, sizeof *r * f->ns);
        memcpy(f->xlast, f->x, sizeof *f->x * (size_t)n);
        f->rvalid = !f->o.legacy;
    }
    if (!J)
        return 0;
    /* f' at the ends of the interval is never needed (phi_j(0) = phi_j(1)
     * = 0 for the inner nodes j, and only the inner nodes' f'(x_j) enter):
     * sqrt(1 - x^2) has none there */
    if (f->ends_exact) {
        f->xs[0] = f->xs[1];
        f->xs[f->ns - 1] = f->xs[f->ns - 2];
    }
    f->xs[f->ns] = f->xs[f->ns + 1];
    f->xs[f->ns + (size_t)n - 1] = f->xs[f->ns + (size_t)n - 2];
    if (target_eval(f, 1, f->fpx) != 0)
        return -1;
    const double *fpk = f->fpx + f->ns;
    for (size_t i = 0; i < f->ns; i++) {
        const double *ph = f->phi + i * (size_t)n;
        double *row = J + i * (size_t)nu;
        int end = f->ends_exact && (i == 0 || i + 1 == f->ns);
        for (int j = 1; j <= nu; j++)
            row[j - 1] = end ? 0 : ph[j] * (f->fpx[i] - fpk[j]);
    }
    return 0;
}

/* the softmax of (0, u): s[0..n-2], and the partial sums S_k = sum_{l<k}
 * s_l into S[0..n-1] */
static void softmax(const Fit *f, const double *u, double *s, double *S)
{
    int g = f->n - 1;
    double mx = 0;
    for (int l = 1; l < g; l++)
        if (u[l - 1] > mx)
            mx = u[l - 1];
    double sum = 0;
    for (int l = 0; l < g; l++) {
        s[l] = exp((l ? u[l - 1] : 0) - mx);
        sum += s[l];
    }
    S[0] = 0;
    for (int l = 0; l < g; l++) {
        s[l] /= sum;
        S[l + 1] = S[l] + s[l];
    }
}

void fit_nodes_of_u(const Fit *f, const double *u, double *x)
{
    double s[LSQ_MAX_UNKNOWNS + 2], S[LSQ_MAX_UNKNOWNS + 3];
    double L = f->o.hi - f->o.lo;
    softmax(f, u, s, S);
    x[0] = f->o.lo;
    for (int k = 1; k < f->n - 1; k++)
        x[k] = f->o.lo + L * S[k];
    x[f->n - 1] = f->o.hi;
}

void fit_u_of_nodes(const Fit *f, const double *x, double *u)
{
    double g0 = x[1] - x[0];
    for (int l = 1; l < f->n - 1; l++)
        u[l - 1] = log((x[l + 1] - x[l]) / g0);
}

int fit_residuals_u(void *ctx, const double *u, double *r, double *J)
{
    Fit *f = ctx;
    int n = f->n, nu = f->nu;
    double s[LSQ_MAX_UNKNOWNS + 2], S[LSQ_MAX_UNKNOWNS + 3];
    double x[LSQ_MAX_UNKNOWNS + 2], L = f->o.hi - f->o.lo;
    softmax(f, u, s, S);
    fit_nodes_of_u(f, u, x);
    for (int k = 1; k < n - 1; k++) // strictly inside and in order
        if (!(x[k] > x[k - 1]) || !(x[k] < f->o.hi))
            return -1;
    if (fit_residuals_x(f, x + 1, r, J ? f->jx : NULL) != 0)
        return -1;
    if (!J)
        return 0;
    /* dx_k/du_j = L s_j ([j < k] - S_k), inner k and j = 1 .. n-2, so
     * row i of J = Jx dx/du is  L s_j (sum_{k > j} Jx_ik - sum_k Jx_ik S_k):
     * a suffix sum, O(nu) a row */
    for (size_t i = 0; i < f->ns; i++) {
        const double *jr = f->jx + i * (size_t)nu; // jr[k - 1]: inner k
        double *row = J + i * (size_t)nu;
        double w = 0, suffix = 0;
        for (int k = 1; k < n - 1; k++)
            w += jr[k - 1] * S[k];
        for (int j = n - 2; j >= 1; j--) {
            row[j - 1] = L * s[j] * (suffix - w);
            suffix += jr[j - 1];
        }
    }
    return 0;
}

/* a deterministic generator for the random starts (splitmix64) */
static double unit_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

/* start s as log-gaps u: 0 Chebyshev-Lobatto nodes, 1 uniform, s >= 2
 * seeded random gaps (each a factor e^[-1.5, 1.5] of the first) */
static void start_point(const Fit *f, int s, double *u)
{
    double x[LSQ_MAX_UNKNOWNS + 2];
    int n = f->n;
    double mid = 0.5 * (f->o.lo + f->o.hi), half = 0.5 * (f->o.hi - f->o.lo);
    if (s >= 2) {
        uint64_t state = (uint64_t)s * 7919u;
        for (int j = 0; j < f->nu; j++)
            u[j] = 3 * unit_random(&state) - 1.5;
        return;
    }
    for (int k = 0; k < n; k++)
        x[k] = s == 0 ? mid - half * cos(FIT_PI * k / (n - 1))
                      : f->o.lo + 2 * half * k / (n - 1);
    fit_u_of_nodes(f, x, u);
}

static double mse_of(const Fit *f, const double *r, double *max_err,
                     double *max_t)
{
    double s = 0, mx = -1;
    for (size_t i = 0; i < f->ns; i++) {
        s += r[i] * r[i];
        if (fabs(r[i]) > mx) {
            mx = fabs(r[i]);
            if (max_t)
                *max_t = (double)i / (double)(f->ns - 1);
        }
    }
    if (max_err)
        *max_err = mx;
    return s / (double)f->ns;
}

/* the baseline of the chapter: Lagrange interpolation of f at N
 * Chebyshev nodes (of the first kind), its MSE at x = lo .. hi in m
 * uniform steps; NaN where f is not defined at the nodes */
static double cheb_lagrange_mse(Fit *f)
{
    int n = f->n;
    size_t ns = f->ns;
    double mid = 0.5 * (f->o.lo + f->o.hi), half = 0.5 * (f->o.hi - f->o.lo);
    for (size_t i = 0; i < ns; i++)
        f->xs[i] = i + 1 == ns
                       ? f->o.hi
                       : f->o.lo + 2 * half * (double)i / (double)(ns - 1);
    for (int k = 0; k < n; k++)
        f->xs[ns + k] = mid - half * cos(FIT_PI * (2 * k + 1) / (2.0 * n));
    if (target_eval(f, 0, f->fx) != 0)
        return NAN;
    double s = 0;
    for (size_t i = 0; i < ns; i++) {
        double p = 0, x = f->xs[i];
        for (int k = 0; k < n; k++) {
            double l = 1, xk = f->xs[ns + k];
            for (int j = 0; j < n; j++)
                if (j != k)
                    l *= (x - f->xs[ns + j]) / (xk - f->xs[ns + j]);
            p += f->fx[ns + k] * l;
        }
        s += (f->fx[i] - p) * (f->fx[i] - p);
    }
    return s / (double)ns;
}

static void start_name(char *buf, size_t cap, int s)
{
    if (s < 2)
        pc_snprintf(buf, cap, "%s", s == 0 ? "chebyshev" : "uniform");
    else
        pc_snprintf(buf, cap, "random %d", s - 1);
}

/* the multistart's monitor: a start whose nodes come within JOIN of
 * those of a start that converged before (the best one, or a local
 * minimum) has joined that basin and is abandoned (starts that reach one
 * minimum would only repeat its iterations; a joined minimum that is not
 * the best cannot become the best).  A start two of whose nodes come
 * within MERGE of each other is abandoned too (b->merged): it is running
 * to the boundary of the admissible nodes, where two coincide (a log-gap
 * to -infinity), a limit that is no fit with N distinct nodes and that
 * Levenberg-Marquardt approaches only linearly (hundreds of steps) */
#define FIT_JOIN 1e-3
#define FIT_MERGE 1e-8
#define FIT_BASINS 16
typedef struct Basin {
    Fit *f;
    int have;
    int merged; // the monitor stopped a start whose nodes were merging
    double best[FIT_BASINS][LSQ_MAX_UNKNOWNS + 2];
} Basin;

static int joined(void *ctx, const double *u, double cost)
{
    Basin *b = ctx;
    double x[LSQ_MAX_UNKNOWNS + 2];
    (void)cost;
    if (!b->have && b->f->o.legacy)
        return 0;
    fit_nodes_of_u(b->f, u, x);
    for (int k = 1; k < b->f->n && !b->f->o.legacy; k++)
        if (x[k] - x[k - 1] < FIT_MERGE * (b->f->o.hi - b->f->o.lo)) {
            b->merged = 1;
            return 1;
        }
    for (int m = 0; m < b->have; m++) {
        int k;
        for (k = 1; k < b->f->n - 1; k++)
            if (fabs(x[k] - b->best[m][k]) >
                FIT_JOIN * (b->f->o.hi - b->f->o.lo))
                break;
        if (k == b->f->n - 1)
            return 1;
    }
    return 0;
}

/* a converged start's minimum, for joined() */
static void basin_add(Basin *b, const double *u)
{
    if (b->have < FIT_BASINS)
        fit_nodes_of_u(b->f, u, b->best[b->have++]);
}

int fit_run(Fit *f, FitResult *res)
{
    int nu = f->nu, best = -1, best_merged = 0;
    double u[LSQ_MAX_UNKNOWNS], ubest[LSQ_MAX_UNKNOWNS];
    double *r = pc_xmalloc(sizeof *r * f->ns);
    Basin basin = {.f = f};
    LsqOptions o;
    lsq_options_default(&o);
    o.max_iter = f->o.max_iter > 0 ? f->o.max_iter : 3000;
    o.lambda0 = 1;
    o.geodesic = !f->o.legacy;
    o.monitor = joined;
    o.monitor_ctx = &basin;
    memset(res, 0, sizeof *res);
    res->nodes = pc_xmalloc(sizeof *res->nodes * (size_t)f->n);
    res->mse = INFINITY;
    for (int s = 0; s < f->o.starts + 2; s++) {
        LsqResult lr;
        start_point(f, s, u);
        if (s < 2)
            res->start_mse[s] = fit_residuals_u(f, u, r, NULL) == 0
                                    ? mse_of(f, r, NULL, NULL)
                                    : NAN;
        lsq_solve(u, nu, f->ns, fit_residuals_u, f, &o, &lr);
        res->starts_run++;
        res->iterations_all += lr.iterations;
        res->evaluations_all += lr.evaluations;
        int merged = basin.merged;
        basin.merged = 0;
        res->starts_merged += merged;
        if (lr.stop == LSQ_STOP_CALLER && !merged) {
            res->starts_joined++;
            continue;
        }
        double mse = 2 * lr.cost / (double)f->ns;
        /* the best: the lowest cost (ties: the earlier start); a start
         * stopped on merging nodes only when no other start has a value */
        if (isfinite(mse) && (best < 0 || (best_merged && !merged) ||
                              (best_merged == merged && mse < res->mse))) {
            best = s;
            best_merged = merged;
            res->mse = mse;
            res->lsq = lr;
            memcpy(ubest, u, sizeof *u * (size_t)nu);
        }
        if (lr.converged && f->o.legacy && best == s)
            basin.have = 0; /* (stop 28 kept the best one only) */
        if (lr.converged && (best == s || !f->o.legacy))
            basin_add(&basin, u);
    }
    if (best >= 0) {
        fit_nodes_of_u(f, ubest, res->nodes);
        fit_residuals_u(f, ubest, r, NULL);
        res->mse = mse_of(f, r, &res->max_error, &res->max_error_t);
        start_name(res->start, sizeof res->start, best);
    } else {
        pc_snprintf(res->start, sizeof res->start, "none");
        res->lsq.stop = LSQ_STOP_EVAL;
    }
    res->cheb_lagrange_mse = cheb_lagrange_mse(f);
    pc_free(r);
    return best >= 0 && res->lsq.converged ? 0 : 1;
}

void fit_result_clear(FitResult *r)
{
    pc_free(r->nodes);
    r->nodes = NULL;
}
