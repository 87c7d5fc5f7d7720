/*
 * lsq.c - Levenberg-Marquardt and damped Newton for small dense problems
 * (lsq.h).
 *
 * Levenberg-Marquardt, the classic form (Marquardt 1963 with Nielsen's
 * damping update, as in Madsen, Nielsen & Tingleff, "Methods for
 * non-linear least squares problems", 2004, algorithm 3.16):
 *
 *   A = J^T J, g = J^T r, D = running max of diag(A) (Marquardt scaling:
 *   the damping is invariant under a rescaling of the unknowns)
 *   solve (A + lambda D) h = -g   (Cholesky; not positive: more damping)
 *   rho = (F(u) - F(u + h)) / (L(0) - L(h)),  L(0) - L(h) = -h.g/2 + lambda
 *         h.D.h/2 ... computed as -(g.h) - h.A.h/2
 *   rho > 0: accept, lambda *= max(1/3, 1 - (2 rho - 1)^3), nu = 2
 *   else:    lambda *= nu, nu *= 2
 *
 * The unknowns are few (<= 64), so A is formed explicitly; the residuals
 * may be many (<= 1e5), so A and g cost O(m n^2) per Jacobian, which is
 * the whole cost for the problems at hand.  Everything is deterministic.
 */
#include "runtime/lsq.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

void lsq_options_default(LsqOptions *o)
{
    o->max_iter = 200;
    o->xtol = 1e-12;
    o->ftol = 1e-15;
    o->gtol = 1e-12;
    o->lambda0 = 1e-3;
    o->geodesic = 0;
    o->monitor = NULL;
    o->monitor_ctx = NULL;
}

const char *lsq_stop_text(LsqStop s)
{
    switch (s) {
    case LSQ_STOP_GTOL:
        return "the gradient vanishes (to gtol)";
    case LSQ_STOP_XTOL:
        return "the step is below xtol";
    case LSQ_STOP_FTOL:
        return "the cost decrease is below ftol";
    case LSQ_STOP_ZERO:
        return "the residuals are zero";
    case LSQ_STOP_MAXITER:
        return "the iteration limit was reached";
    case LSQ_STOP_STALL:
        return "no step lowers the cost any more";
    case LSQ_STOP_EVAL:
        return "the residuals cannot be evaluated at the start";
    case LSQ_STOP_SINGULAR:
        return "the Jacobian is singular";
    case LSQ_STOP_CALLER:
        return "stopped by the caller";
    default:
        return "not run";
    }
}

static double sumsq(const double *r, size_t m)
{
    double s = 0;
    for (size_t i = 0; i < m; i++)
        s += r[i] * r[i];
    return s;
}

static double norm2(const double *v, int n)
{
    double s = 0;
    for (int j = 0; j < n; j++)
        s += v[j] * v[j];
    return sqrt(s);
}

/* A = J^T J (n x n, full), g = J^T r */
static void normal_equations(double *A, double *g, const double *J,
                             const double *r, size_t m, int n)
{
    memset(A, 0, sizeof *A * (size_t)n * (size_t)n);
    memset(g, 0, sizeof *g * (size_t)n);
    for (size_t i = 0; i < m; i++) {
        const double *row = J + i * (size_t)n;
        for (int j = 0; j < n; j++) {
            double v = row[j];
            if (v == 0)
                continue;
            g[j] += v * r[i];
            double *Aj = A + (size_t)j * (size_t)n;
            for (int k = j; k < n; k++)
                Aj[k] += v * row[k];
        }
    }
    for (int j = 0; j < n; j++)
        for (int k = 0; k < j; k++)
            A[j * n + k] = A[k * n + j];
}

/* x = (L L^T)^-1 b, L lower triangular (n x n) */
static void cholesky_apply(double *x, const double *L, const double *b, int n)
{
    for (int j = 0; j < n; j++) {
        double s = b[j];
        for (int p = 0; p < j; p++)
            s -= L[j * n + p] * x[p];
        x[j] = s / L[j * n + j];
    }
    for (int j = n - 1; j >= 0; j--) {
        double s = x[j];
        for (int p = j + 1; p < n; p++)
            s -= L[p * n + j] * x[p];
        x[j] = s / L[j * n + j];
    }
}

/* Solves M x = b for symmetric M (n x n) by Cholesky, into x; L is n*n
 * scratch.  Returns 0, or -1 when M is not positive definite. */
static int cholesky_solve(double *x, const double *M, const double *b,
                          double *L, int n)
{
    for (int j = 0; j < n; j++) {
        for (int k = 0; k <= j; k++) {
            double s = M[j * n + k];
            for (int p = 0; p < k; p++)
                s -= L[j * n + p] * L[k * n + p];
            if (k == j) {
                if (!(s > 0))
                    return -1;
                L[j * n + j] = sqrt(s);
            } else {
                L[j * n + k] = s / L[k * n + k];
            }
        }
    }
    cholesky_apply(x, L, b, n);
    return 0;
}

/* the scaled gradient: max_j |g_j| / (|J_j| |r|) (MINPACK's gnorm) */
static double cosine_gradient(const double *g, const double *A, double rnorm,
                              int n)
{
    double c = 0;
    for (int j = 0; j < n; j++) {
        double cj = A[j * n + j] > 0 && rnorm > 0
                        ? fabs(g[j]) / (sqrt(A[j * n + j]) * rnorm)
                        : 0;
        if (cj > c)
            c = cj;
    }
    return c;
}

static double max_abs(const double *v, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        if (fabs(v[i]) > s)
            s = fabs(v[i]);
    return s;
}

/* the solvers' scratch */
typedef struct Work {
    double *r, *rt, *J, *A, *Ad, *L, *g, *h, *ut, *D;
    double *rvv, *acc; // geodesic acceleration: r'' along h, and its step
} Work;

static void work_init(Work *w, size_t m, int n)
{
    size_t nn = (size_t)n * (size_t)n;
    w->r = pc_xmalloc(sizeof *w->r * m);
    w->rt = pc_xmalloc(sizeof *w->rt * m);
    w->J = pc_xmalloc(sizeof *w->J * m * (size_t)n);
    w->A = pc_xmalloc(sizeof *w->A * nn);
    w->Ad = pc_xmalloc(sizeof *w->Ad * nn);
    w->L = pc_xmalloc(sizeof *w->L * nn);
    w->g = pc_xmalloc(sizeof *w->g * (size_t)n);
    w->h = pc_xmalloc(sizeof *w->h * (size_t)n);
    w->ut = pc_xmalloc(sizeof *w->ut * (size_t)n);
    w->D = pc_xcalloc((size_t)n, sizeof *w->D);
    w->rvv = pc_xmalloc(sizeof *w->rvv * m);
    w->acc = pc_xmalloc(sizeof *w->acc * (size_t)n);
}

static void work_clear(Work *w)
{
    pc_free(w->r);
    pc_free(w->rt);
    pc_free(w->J);
    pc_free(w->A);
    pc_free(w->Ad);
    pc_free(w->L);
    pc_free(w->g);
    pc_free(w->h);
    pc_free(w->ut);
    pc_free(w->D);
    pc_free(w->rvv);
    pc_free(w->acc);
}

/* the LM state between iterations */
typedef struct LmState {
    double F;      // cost 1/2 |r|^2 at u
    double lambda; // damping
    double nu;     // growth of lambda after a rejected step
} LmState;

/* Geodesic acceleration (Transtrum & Sethna, "Improvements to the
 * Levenberg-Marquardt algorithm for nonlinear least-squares
 * minimization", 2012): the residuals' second directional derivative
 * along the step h, r_vv = 2/e ((r(u + e h) - r(u))/e - J h) with e =
 * 0.1, gives the second-order correction a = -(A + lambda D)^-1 J^T r_vv
 * (the factor L of the step's own system), and the trial point becomes
 * u + h + a/2 (in w->ut) when |a| <= 0.75 |h|: the step bends along a
 * curved valley instead of leaving it.  One residual evaluation more. */
static void geodesic(const double *u, int n, size_t m, LsqFn *fn, void *ctx,
                     Work *w, LsqResult *res)
{
    const double e = 0.1;
    for (int j = 0; j < n; j++)
        w->ut[j] = u[j] + e * w->h[j];
    res->evaluations++;
    if (fn(ctx, w->ut, w->rt, NULL) != 0) {
        for (int j = 0; j < n; j++)
            w->ut[j] = u[j] + w->h[j];
        return;
    }
    for (size_t i = 0; i < m; i++) {
        const double *row = w->J + i * (size_t)n;
        double jh = 0;
        for (int j = 0; j < n; j++)
            jh += row[j] * w->h[j];
        w->rvv[i] = 2 / e * ((w->rt[i] - w->r[i]) / e - jh);
    }
    for (int j = 0; j < n; j++) {
        double s = 0;
        for (size_t i = 0; i < m; i++)
            s -= w->J[i * (size_t)n + (size_t)j] * w->rvv[i];
        w->rt[j] = s; /* (scratch: -J^T r_vv) */
    }
    cholesky_apply(w->acc, w->L, w->rt, n);
    int keep = 2 * norm2(w->acc, n) <= 0.75 * norm2(w->h, n);
    for (int j = 0; j < n; j++)
        w->ut[j] = u[j] + w->h[j] + (keep ? 0.5 * w->acc[j] : 0);
}

/* one Levenberg-Marquardt iteration from u (r, J, A, g current): tries
 * steps until one is accepted (then u, r, F move) or the damping runs
 * away.  Returns LSQ_STOP_NONE to go on, or why to stop. */
static LsqStop lm_step(double *u, int n, size_t m, LsqFn *fn, void *ctx,
                       const LsqOptions *o, Work *w, LmState *s, LsqResult *res)
{
    for (;;) {
        memcpy(w->Ad, w->A, sizeof *w->A * (size_t)n * (size_t)n);
        for (int j = 0; j < n; j++) {
            w->Ad[j * n + j] += s->lambda * w->D[j];
            w->ut[j] = -w->g[j];
        }
        if (s->lambda > 1e32)
            return LSQ_STOP_STALL;
        if (cholesky_solve(w->h, w->Ad, w->ut, w->L, n) != 0) {
            s->lambda = s->lambda > 0 ? s->lambda * s->nu : 1e-12;
            s->nu *= 2;
            continue;
        }
        double hn = norm2(w->h, n), un = norm2(u, n);
        if (hn <= o->xtol * (o->xtol + un))
            return LSQ_STOP_XTOL;
        for (int j = 0; j < n; j++)
            w->ut[j] = u[j] + w->h[j];
        /* predicted decrease: -(g.h) - h.A.h/2 */
        double gh = 0, hAh = 0;
        for (int j = 0; j < n; j++) {
            gh += w->g[j] * w->h[j];
            double a = 0;
            for (int k = 0; k < n; k++)
                a += w->A[j * n + k] * w->h[k];
            hAh += w->h[j] * a;
        }
        double pred = -gh - 0.5 * hAh;
        if (o->geodesic)
            geodesic(u, n, m, fn, ctx, w, res);
        res->evaluations++;
        int bad = fn(ctx, w->ut, w->rt, NULL);
        double Ft = bad ? INFINITY : 0.5 * sumsq(w->rt, m);
        double rho = isfinite(Ft) && pred > 0 ? (s->F - Ft) / pred : -1;
        if (rho > 0) {
            double dF = s->F - Ft, F0 = s->F;
            memcpy(u, w->ut, sizeof *u * (size_t)n);
            memcpy(w->r, w->rt, sizeof *w->r * m);
            s->F = Ft;
            double c = 2 * rho - 1;
            double f = 1 - c * c * c;
            s->lambda *= f > 1.0 / 3 ? f : 1.0 / 3;
            s->nu = 2;
            if (Ft == 0)
                return LSQ_STOP_ZERO;
            if (dF <= o->ftol * F0 && pred <= o->ftol * F0)
                return LSQ_STOP_FTOL;
            if (o->monitor && o->monitor(o->monitor_ctx, u, Ft))
                return LSQ_STOP_CALLER;
            return LSQ_STOP_NONE;
        }
        if (!isfinite(Ft) && hn <= o->xtol * (o->xtol + un) * 1e3)
            return LSQ_STOP_STALL;
        s->lambda *= s->nu;
        s->nu *= 2;
    }
}

static int finish(LsqResult *out, LsqResult *res, LsqStop stop)
{
    res->stop = stop;
    res->converged = stop == LSQ_STOP_GTOL || stop == LSQ_STOP_XTOL ||
                     stop == LSQ_STOP_FTOL || stop == LSQ_STOP_ZERO;
    if (out)
        *out = *res;
    return res->converged ? 0 : 1;
}

int lsq_solve(double *u, int n, size_t m, LsqFn *fn, void *ctx,
              const LsqOptions *o, LsqResult *out)
{
    LsqOptions def;
    LsqResult res = {0};
    if (n < 1 || n > LSQ_MAX_UNKNOWNS || m < 1 || m > LSQ_MAX_RESIDUALS)
        return -1;
    if (!o) {
        lsq_options_default(&def);
        o = &def;
    }
    Work w;
    work_init(&w, m, n);
    LsqStop stop = LSQ_STOP_NONE;
    LmState s = {0, 0, 2};
    res.evaluations = 1;
    if (fn(ctx, u, w.r, w.J) != 0) {
        res.cost = INFINITY;
        stop = LSQ_STOP_EVAL;
    }
    s.F = 0.5 * sumsq(w.r, m);
    for (int it = 0; stop == LSQ_STOP_NONE; it++) {
        if (it > 0) {
            res.evaluations++;
            fn(ctx, u, w.r, w.J); /* evaluable: accepted before */
        }
        res.iterations = it;
        normal_equations(w.A, w.g, w.J, w.r, m, n);
        double amax = 0;
        for (int j = 0; j < n; j++) {
            double a = w.A[j * n + j];
            if (a > w.D[j])
                w.D[j] = a;
            if (a > amax)
                amax = a;
        }
        for (int j = 0; j < n; j++) // a column of zeros: keep D positive
            if (w.D[j] <= 0)
                w.D[j] = amax > 0 ? amax * 1e-16 : 1;
        if (it == 0)
            s.lambda = o->lambda0;
        res.gnorm = max_abs(w.g, (size_t)n);
        if (s.F == 0)
            stop = LSQ_STOP_ZERO;
        else if (cosine_gradient(w.g, w.A, sqrt(2 * s.F), n) <= o->gtol)
            stop = LSQ_STOP_GTOL;
        else if (it >= o->max_iter)
            stop = LSQ_STOP_MAXITER;
        else
            stop = lm_step(u, n, m, fn, ctx, o, &w, &s, &res);
    }
    if (stop != LSQ_STOP_EVAL)
        res.cost = s.F;
    work_clear(&w);
    return finish(out, &res, stop);
}

/* LU with partial pivoting of the n x n matrix A in place, solving
 * A x = b into b.  Returns -1 when A is singular (a zero pivot, or one
 * below 1e-300 relative to the largest entry). */
static int lu_solve(double *A, double *b, int n)
{
    double big = 0;
    for (int k = 0; k < n * n; k++)
        if (fabs(A[k]) > big)
            big = fabs(A[k]);
    if (!(big > 0) || !isfinite(big))
        return -1;
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(A[i * n + k]) > fabs(A[p * n + k]))
                p = i;
        if (fabs(A[p * n + k]) <= big * 1e-300 * 1e16)
            return -1;
        if (p != k) {
            for (int j = 0; j < n; j++) {
                double t = A[k * n + j];
                A[k * n + j] = A[p * n + j];
                A[p * n + j] = t;
            }
            double t = b[k];
            b[k] = b[p];
            b[p] = t;
        }
        for (int i = k + 1; i < n; i++) {
            double f = A[i * n + k] / A[k * n + k];
            for (int j = k; j < n; j++)
                A[i * n + j] -= f * A[k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (int k = n - 1; k >= 0; k--) {
        double s = b[k];
        for (int j = k + 1; j < n; j++)
            s -= A[k * n + j] * b[j];
        b[k] = s / A[k * n + k];
    }
    return 0;
}

/* one damped Newton step from u (r, J current): the Newton direction,
 * halved until the Armijo condition holds; u and r move.  Returns
 * LSQ_STOP_NONE to go on, or why to stop. */
static LsqStop newton_step(double *u, int n, LsqFn *fn, void *ctx,
                           const LsqOptions *o, Work *w, LsqResult *res)
{
    size_t m = (size_t)n;
    double F = sumsq(w->r, m);
    memcpy(w->A, w->J, sizeof *w->A * m * m);
    for (int j = 0; j < n; j++)
        w->h[j] = -w->r[j];
    if (lu_solve(w->A, w->h, n) != 0)
        return LSQ_STOP_SINGULAR;
    double hn = norm2(w->h, n), un = norm2(u, n);
    for (double a = 1; a > 0x1p-60; a *= 0.5) {
        if (a * hn <= o->xtol * (o->xtol + un))
            return LSQ_STOP_XTOL;
        for (int j = 0; j < n; j++)
            w->ut[j] = u[j] + a * w->h[j];
        res->evaluations++;
        if (fn(ctx, w->ut, w->rt, NULL) != 0)
            continue;
        double Ft = sumsq(w->rt, m);
        /* the directional derivative of |r|^2 along h is -2F */
        if (isfinite(Ft) && Ft <= (1 - 2e-4 * a) * F) {
            memcpy(u, w->ut, sizeof *u * m);
            return LSQ_STOP_NONE;
        }
    }
    return LSQ_STOP_STALL;
}

int lsq_newton(double *u, int n, LsqFn *fn, void *ctx, const LsqOptions *o,
               LsqResult *out)
{
    LsqOptions def;
    LsqResult res = {0};
    if (n < 1 || n > LSQ_MAX_UNKNOWNS)
        return -1;
    if (!o) {
        lsq_options_default(&def);
        o = &def;
    }
    Work w;
    size_t m = (size_t)n;
    work_init(&w, m, n);
    LsqStop stop = LSQ_STOP_NONE;
    res.evaluations = 1;
    if (fn(ctx, u, w.r, w.J) != 0)
        stop = LSQ_STOP_EVAL;
    for (int it = 0; stop == LSQ_STOP_NONE; it++) {
        if (it > 0) {
            res.evaluations++;
            fn(ctx, u, w.r, w.J);
        }
        res.iterations = it;
        res.gnorm = max_abs(w.r, m);
        if (res.gnorm == 0)
            stop = LSQ_STOP_ZERO;
        else if (res.gnorm <= o->gtol)
            stop = LSQ_STOP_GTOL;
        else if (it >= o->max_iter)
            stop = LSQ_STOP_MAXITER;
        else
            stop = newton_step(u, n, fn, ctx, o, &w, &res);
    }
    /* the residuals at the returned u */
    if (stop != LSQ_STOP_EVAL && stop != LSQ_STOP_NONE)
        fn(ctx, u, w.r, NULL);
    res.cost = stop == LSQ_STOP_EVAL ? INFINITY : 0.5 * sumsq(w.r, m);
    res.gnorm = stop == LSQ_STOP_EVAL ? INFINITY : max_abs(w.r, m);
    work_clear(&w);
    return finish(out, &res, stop);
}
