/*
 * lsq.h - small dense nonlinear least squares and nonlinear systems, with
 * the Jacobian supplied by the caller (exact: pointcalc derives it).
 *
 *   lsq_solve    Levenberg-Marquardt: minimises 1/2 |r(u)|^2 over u in R^n
 *                (n <= LSQ_MAX_UNKNOWNS, m residuals, m <= LSQ_MAX_RESIDUALS)
 *   lsq_newton   damped Newton for a square system r(u) = 0 (m = n)
 *
 * Both call one callback for residuals and Jacobian; both stop for a
 * reason they report (LsqStop) and never allocate beyond O(m n) doubles
 * (through base/mem.h).  Deterministic: the same inputs give the same
 * iterates, bit for bit.  The numeric side only (no FLINT): runtime/.
 */
#ifndef PC_LSQ_H
#define PC_LSQ_H

#include <stddef.h>

enum {
    LSQ_MAX_UNKNOWNS = 64,
    LSQ_MAX_RESIDUALS = 100000,
};

/* r (m values) and, when J is not NULL, the Jacobian J (m*n, row-major:
 * J[i*n + j] = dr_i/du_j) at u.  Returns 0, or non-zero when r cannot be
 * evaluated at u (outside a domain): the solvers then treat u as a step
 * too far (LM: more damping; Newton: a shorter step). */
typedef int LsqFn(void *ctx, const double *u, double *r, double *J);

/* Called after every accepted step with the new u and its cost; a
 * non-zero return stops the solver (LSQ_STOP_CALLER): a multistart
 * abandons a start that has joined a basin it knows. */
typedef int LsqMonitor(void *ctx, const double *u, double cost);

typedef struct LsqOptions {
    int max_iter;        // iterations (Jacobian evaluations) at most
    double xtol;         // stop when |du| <= xtol * (xtol + |u|)
    double ftol;         // stop when an accepted step lowers the cost by less
                         // than ftol * cost, predicted and actual (LM)
    double gtol;         // stop when max_j |g_j| / (|J_j| |r|) <= gtol (LM: the
                         // cosine of residual and Jacobian columns); Newton:
                         // max |r_i| <= gtol
    double lambda0;      // initial damping, relative to diag(J^T J)
    int geodesic;        // 1: geodesic acceleration (LM; lsq.c), one
                         // residual evaluation more a trial step
    LsqMonitor *monitor; // or NULL
    void *monitor_ctx;
} LsqOptions;

/* why a solver stopped */
typedef enum LsqStop {
    LSQ_STOP_NONE = 0, // (not run)
    LSQ_STOP_GTOL,     // gradient (LM) or residual (Newton) small enough
    LSQ_STOP_XTOL,     // relative step small enough
    LSQ_STOP_FTOL,     // relative cost decrease small enough
    LSQ_STOP_ZERO,     // r = 0 exactly
    LSQ_STOP_MAXITER,  // max_iter reached (not converged)
    LSQ_STOP_STALL,    // no step lowers the cost any more (damping beyond
                       // 1e32, or Newton's step halved 60 times): not
                       // converged to the tolerances
    LSQ_STOP_EVAL,     // r cannot be evaluated at the start
    LSQ_STOP_SINGULAR, // Newton: the Jacobian is singular
    LSQ_STOP_CALLER,   // the monitor asked to stop
} LsqStop;

typedef struct LsqResult {
    LsqStop stop;
    double cost;     // 1/2 |r|^2 at the returned u
    double gnorm;    // max |J^T r| at the returned u (Newton: max |r|)
    int iterations;  // steps taken (Jacobian evaluations but one)
    int evaluations; // callback calls
    int converged;   // 1 for GTOL, XTOL, FTOL, ZERO
} LsqResult;

/* max_iter 200, xtol 1e-12, ftol 1e-15, gtol 1e-12, lambda0 1e-3, no
 * monitor */
void lsq_options_default(LsqOptions *o);

/* Levenberg-Marquardt with Marquardt's scaling: each step solves
 *   (J^T J + lambda D) du = -J^T r,   D = diag(J^T J) (its running max),
 * by Cholesky; lambda follows the gain ratio (Nielsen's update).  u (n
 * values) is the start and receives the best point found.  Returns 0 when
 * converged, 1 otherwise (res says why; NULL: not reported), -1 on bad
 * sizes. */
int lsq_solve(double *u, int n, size_t m, LsqFn *fn, void *ctx,
              const LsqOptions *o, LsqResult *res);

/* Damped Newton for n equations in n unknowns: du = -J^-1 r (LU with
 * partial pivoting), halved until |r|^2 decreases (Armijo, 1e-4); stops on
 * max |r_i| <= gtol or a relative step <= xtol.  Returns as lsq_solve. */
int lsq_newton(double *u, int n, LsqFn *fn, void *ctx, const LsqOptions *o,
               LsqResult *res);

/* "gradient small", "max iterations reached", ... */
const char *lsq_stop_text(LsqStop s);

#endif
