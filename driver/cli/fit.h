/*
 * fit.h - `pointcalc fit`: approximation with optimal nodes (monograph
 * chapter 5, docs/fit.md), the engine behind it for tests and benches.
 *
 *   fit_new      derive the target f(x) and f'(x) (exact `diff`) and the
 *                order-(N-1) interpolation curve (the families scheme of
 *                docs/language.md, examples/interpolation_bezier.pcs),
 *                lower both to Plans, tabulate the curve's weights phi_k
 *                at the samples t_i = i/m, check f on [lo, hi]
 *   fit_run      Levenberg-Marquardt (runtime/lsq.h) from the Chebyshev,
 *                uniform and seeded random starts; the best one wins (a
 *                start whose nodes come within 1e-3 (hi - lo) of the best
 *                converged start's so far is abandoned: it has joined
 *                that basin)
 *   fit_free
 *
 * The unknowns are the inner nodes' abscissas x_1 .. x_{N-2}, through
 * log-gaps (fit_residuals_u): the N-1 gaps x_{k+1} - x_k are (hi - lo)
 * times the softmax of (0, u_1, .., u_{N-2}), so every u gives nodes in
 * order strictly inside (lo, hi), and no bound is ever active.
 */
#ifndef PC_FIT_H
#define PC_FIT_H

#include <stdio.h>

#include "driver/cli/cli.h"
#include "runtime/lsq.h"

CliCommand cli_fit; // cmd_fit.c: pointcalc fit --target EXPR ...

/* its synopsis and help (help.c lists them) */
#define FIT_USAGE                                                              \
    "usage: pointcalc fit --target 'EXPR' --on LO,HI --nodes N [--samples "    \
    "M]\n"                                                                     \
    "                     [--starts K] [--max-iter I] [--format text|json]\n"
extern const char fit_help[];

typedef struct FitOptions {
    double lo, hi; // the interval (--on LO,HI)
    int nodes;     // N >= 3 (--nodes)
    int samples;   // m (--samples; default 100): t_i = i/m, i = 0..m
    int starts;    // seeded random starts after Chebyshev and uniform
    int max_iter;  // iterations a start at most (--max-iter; 0: 3000)
} FitOptions;

typedef struct Fit {
    FitOptions o;
    int n;        // N nodes
    int nu;       // N - 2 unknowns
    size_t ns;    // m + 1 samples
    Plan *target; // outputs f and fp of param x
    double *phi;  // ns * n: phi[i*n + k] = phi_k(t_i), from the derived
                  // curve's plan
    double *coef; // n * n: coef[k*n + j] = the exact coefficient of t^j in
                  // phi_k (from the derived weights)
    /* scratch for the residuals */
    double *x, *xs, *fx, *fpx;
    unsigned char *st;
    double *jx;
} Fit;

/* the outcome of fit_run */
typedef struct FitResult {
    double *nodes;      // n abscissas, ends included, in order (owned)
    double mse;         // sum r_i^2 / (m + 1)
    double max_error;   // max |r_i|
    double max_error_t; // the t_i where it is reached
    char start[24];     // "chebyshev", "uniform", "random 3", ...
    int starts_run;
    int starts_joined;        // abandoned on joining the best start's basin
    LsqResult lsq;            // the winning start's solver report
    double start_mse[2];      // MSE at the Chebyshev and uniform starts
    double cheb_lagrange_mse; // the baseline: Lagrange interpolation of f
                              // at N Chebyshev nodes, over x = lo .. hi in
                              // m uniform steps
} FitResult;

/* Derives and checks; NULL after reporting to err (*rc = 1: the target
 * has an error or is undefined on the interval; 2: bad options). */
Fit *fit_new(const char *target, const FitOptions *o, FILE *err, int *rc);
void fit_free(Fit *f);

/* Runs the starts; returns 0 when the best start converged, 1 when not
 * (r holds what was reached).  fit_result_clear frees r's nodes. */
int fit_run(Fit *f, FitResult *r);
void fit_result_clear(FitResult *r);

/* The residuals r_i = f(x(t_i)) - y(t_i), i = 0..m, and their exact
 * Jacobian (ns * nu, row-major) with respect to the inner nodes x (nu
 * values), or (LsqFn) to the log-gaps u.  Return non-zero where f or f'
 * is undefined at a sample. */
int fit_residuals_x(Fit *f, const double *xin, double *r, double *J);
int fit_residuals_u(void *f, const double *u, double *r, double *J);
/* the nodes (n values) of log-gaps u, and back */
void fit_nodes_of_u(const Fit *f, const double *u, double *x);
void fit_u_of_nodes(const Fit *f, const double *x, double *u);

#endif
