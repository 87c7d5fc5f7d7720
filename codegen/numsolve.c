/*
 * numsolve.c - the numeric back end of a numeric solve (numsolve.h): the
 * compiler's exact residuals and Jacobian (the scalar outputs of a view
 * of the derivation) lowered to one Plan, evaluated one output at a time
 * at one sample by the interpreter (runtime/eval.h), and solved by
 * runtime/lsq.h: damped Newton for a square system, Levenberg-Marquardt
 * for more residuals than unknowns.
 */
#include "codegen/numsolve.h"

#include <math.h>
#include <string.h>

#include "base/mem.h"
#include "codegen/lower.h"
#include "runtime/eval.h"
#include "runtime/lsq.h"

struct NumEval {
    Plan *plan;
    int n, m, nin;
    const int *input;   // unknown j is input input[j]
    double *in;         // the nin inputs (0 but the unknowns')
    const double **pin; // pointers to them, as plan_eval takes params
};

NumEval *numsolve_prepare(const NumericSystem *s)
{
    Plan *p = lower_derived(s->view, NULL);
    if (!p)
        return NULL;
    NumEval *e = pc_xcalloc(1, sizeof *e);
    e->plan = p;
    e->n = s->n;
    e->m = s->m;
    e->nin = (int)s->view->nparams;
    e->input = s->input;
    e->in = pc_xcalloc((size_t)(e->nin ? e->nin : 1), sizeof(double));
    e->pin = pc_xmalloc(sizeof(double *) * (size_t)(e->nin ? e->nin : 1));
    for (int i = 0; i < e->nin; i++)
        e->pin[i] = e->in + i;
    return e;
}

void numsolve_free(NumEval *e)
{
    if (!e)
        return;
    plan_free(e->plan);
    pc_free(e->pin);
    pc_free(e->in);
    pc_free(e);
}

/* output o at the current inputs into *v; 0, or 1 where it has no value */
static int eval_one(NumEval *e, int o, double *v)
{
    unsigned char st = 0;
    plan_eval(e->plan, o, 1, e->pin, NULL, NULL, 0, v, &st);
    return st != 0 || !isfinite(*v);
}

int numsolve_eval(void *ctx, const double *u, double *r, double *J)
{
    NumEval *e = ctx;
    int bad = 0;
    for (int j = 0; j < e->n; j++)
        e->in[e->input[j]] = u[j];
    for (int i = 0; i < e->m; i++)
        bad |= eval_one(e, i, r + i);
    for (int k = 0; J && k < e->m * e->n; k++)
        bad |= eval_one(e, e->m + k, J + k);
    return bad;
}

/* Gaussian elimination with complete pivoting of A (m x n, m >= n,
 * destroyed): the rank (pivots above 1e-12 of the largest entry, times
 * the size); when it is n = m, b (m values) receives A^-1 b. */
static int gauss(double *A, int m, int n, double *b)
{
    int *col = pc_xmalloc(sizeof(int) * (size_t)n);
    double big = 0;
    for (int k = 0; k < m * n; k++)
        big = fmax(big, fabs(A[k]));
    double tol = big * 1e-12 * (m > n ? m : n);
    int rank = 0;
    for (int j = 0; j < n; j++)
        col[j] = j;
    for (int k = 0; k < n && k < m; k++, rank++) {
        int pi = k, pj = k;
        for (int i = k; i < m; i++)
            for (int j = k; j < n; j++)
                if (fabs(A[i * n + j]) > fabs(A[pi * n + pj]))
                    pi = i, pj = j;
        if (!(fabs(A[pi * n + pj]) > tol))
            break;
        for (int j = 0; j < n; j++) { /* rows k, pi */
            double t = A[k * n + j];
            A[k * n + j] = A[pi * n + j];
            A[pi * n + j] = t;
        }
        if (b) {
            double t = b[k];
            b[k] = b[pi];
            b[pi] = t;
        }
        for (int i = 0; i < m; i++) { /* columns k, pj */
            double t = A[i * n + k];
            A[i * n + k] = A[i * n + pj];
            A[i * n + pj] = t;
        }
        int c = col[k];
        col[k] = col[pj];
        col[pj] = c;
        for (int i = k + 1; i < m; i++) {
            double f = A[i * n + k] / A[k * n + k];
            for (int j = k; j < n; j++)
                A[i * n + j] -= f * A[k * n + j];
            if (b)
                b[i] -= f * b[k];
        }
    }
    if (b && rank == n && m == n) { /* back substitution, unpermuted */
        double *x = pc_xmalloc(sizeof(double) * (size_t)n);
        for (int k = n - 1; k >= 0; k--) {
            double s = b[k];
            for (int j = k + 1; j < n; j++)
                s -= A[k * n + j] * x[j];
            x[k] = s / A[k * n + k];
        }
        for (int k = 0; k < n; k++)
            b[col[k]] = x[k];
        pc_free(x);
    }
    pc_free(col);
    return rank;
}

/* the residual norms at s->u, and the Jacobian's rank there; for a
 * square system, whether the full Newton step from u is within 1e-9 of
 * |u| (a root), else 1 */
static int check_point(NumEval *e, NumericSystem *s, int *near_root)
{
    int m = s->m, n = s->n;
    double *r = pc_xmalloc(sizeof(double) * (size_t)m);
    double *J = pc_xmalloc(sizeof(double) * (size_t)m * (size_t)n);
    int bad = numsolve_eval(e, s->u, r, J);
    double sum = 0, mx = 0, un = 0;
    for (int i = 0; i < m; i++) {
        sum += r[i] * r[i];
        mx = fmax(mx, fabs(r[i]));
    }
    for (int j = 0; j < n; j++)
        un = fmax(un, fabs(s->u[j]));
    s->max_resid = bad ? INFINITY : mx;
    s->rms_resid = bad ? INFINITY : sqrt(sum / m);
    s->rank = bad ? 0 : gauss(J, m, n, m == n ? r : NULL);
    *near_root = 1;
    if (!bad && m == n && s->rank == n)
        for (int j = 0; j < n; j++)
            if (!(fabs(r[j]) <= 1e-9 * (1 + un)))
                *near_root = 0;
    pc_free(J);
    pc_free(r);
    return bad;
}

static double sumsq(const double *r, int m)
{
    double s = 0;
    for (int i = 0; i < m; i++)
        s += r[i] * r[i];
    return s;
}

/* Gauss-Newton steps from s->u (the normal equations; for a square
 * system, Newton's steps),
 * while they do not raise the cost: Levenberg-Marquardt stops with its
 * damping still on, some digits short of the minimum */
static void polish(NumEval *e, NumericSystem *s)
{
    int m = s->m, n = s->n;
    double *r = pc_xmalloc(sizeof(double) * (size_t)m * (size_t)(n + 2));
    double *J = r + m, *rt = J + (size_t)m * (size_t)n;
    double *A = pc_xmalloc(sizeof(double) * (size_t)n * (size_t)(n + 2));
    double *g = A + n * n, *ut = g + n;
    for (int it = 0; it < 8 && numsolve_eval(e, s->u, r, J) == 0; it++) {
        for (int j = 0; j < n; j++) {
            g[j] = 0;
            for (int i = 0; i < m; i++)
                g[j] -= J[i * n + j] * r[i];
            for (int k = 0; k < n; k++) {
                double a = 0;
                for (int i = 0; i < m; i++)
                    a += J[i * n + j] * J[i * n + k];
                A[j * n + k] = a;
            }
        }
        if (gauss(A, n, n, g) < n)
            break;
        double step = 0, un = 0;
        for (int j = 0; j < n; j++) {
            ut[j] = s->u[j] + g[j];
            step = fmax(step, fabs(g[j]));
            un = fmax(un, fabs(s->u[j]));
        }
        /* kept unless the cost rises beyond its rounding (near the
         * minimum the cost cannot tell the last digits apart) */
        if (numsolve_eval(e, ut, rt, NULL) != 0 ||
            !(sumsq(rt, m) <= sumsq(r, m) * (1 + 1e-12)))
            break;
        memcpy(s->u, ut, sizeof(double) * (size_t)n);
        if (step <= 1e-15 * (1 + un))
            break;
    }
    pc_free(A);
    pc_free(r);
}

/* the status of a solver's stop at s->u */
static NumericStatus judge(NumEval *e, NumericSystem *s, const LsqResult *lr)
{
    int near_root;
    if (lr->stop == LSQ_STOP_EVAL)
        return NUMERIC_EVAL;
    if (check_point(e, s, &near_root))
        return NUMERIC_EVAL;
    if (s->rank < s->n)
        return NUMERIC_SINGULAR;
    if (lr->stop == LSQ_STOP_MAXITER)
        return NUMERIC_NOCONV;
    if (s->m == s->n) /* any stop but those: is u a root? */
        return near_root ? NUMERIC_OK : NUMERIC_NOCONV;
    return lr->converged ? NUMERIC_OK : NUMERIC_NOCONV;
}

int numsolve_run(NumericSystem *s)
{
    NumEval *e = numsolve_prepare(s);
    if (!e) {
        s->status = NUMERIC_NONUMBERS;
        return 1;
    }
    LsqOptions o;
    LsqResult lr = {0};
    lsq_options_default(&o);
    o.max_iter = s->max_iter > 0 ? s->max_iter : 200;
    if (s->m == s->n) {
        o.gtol = 0; /* a root: stop on the step, checked after */
        o.xtol = 1e-15;
        s->method = "damped Newton";
        lsq_newton(s->u, s->n, numsolve_eval, e, &o, &lr);
        if (lr.stop != LSQ_STOP_EVAL && lr.stop != LSQ_STOP_MAXITER)
            polish(e, s);
    } else {
        s->method = "Levenberg-Marquardt";
        lsq_solve(s->u, s->n, (size_t)s->m, numsolve_eval, e, &o, &lr);
        if (lr.converged)
            polish(e, s);
    }
    s->iterations = lr.iterations;
    s->status = judge(e, s, &lr);
    numsolve_free(e);
    return s->status != NUMERIC_OK;
}
