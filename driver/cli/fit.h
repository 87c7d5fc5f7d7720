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
 *   fit_new_from  the same from a given target (a Plan's outputs or a
 *                CSV's spline, fit_data.c) and curve table: the scheme
 *                form `pointcalc fit FILE` (fit_scheme.c) and --data
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
#include "runtime/eval.h"
#include "runtime/lsq.h"

CliCommand cli_fit; // cmd_fit.c: pointcalc fit --target EXPR ...

/* its synopsis and help (help.c lists them) */
#define FIT_USAGE                                                              \
    "usage: pointcalc fit --target 'EXPR' --on LO,HI --nodes N [--samples "    \
    "M]\n"                                                                     \
    "       pointcalc fit --data FILE.csv [--on LO,HI] --nodes N [...]\n"      \
    "       pointcalc fit SCHEME.pcs [--data FILE.csv] [--samples M] [...]\n"  \
    "                     [--starts K] [--max-iter I] [--format text|json]\n"  \
    "                     [--plot FILE.svg]\n"
extern const char fit_help[];

typedef struct FitOptions {
    double lo, hi; // the interval (--on LO,HI)
    int nodes;     // N >= 3 (--nodes)
    int samples;   // m (--samples; default 100): t_i = i/m, i = 0..m
    int starts;    // seeded random starts after Chebyshev and uniform
    int max_iter;  // iterations a start at most (--max-iter; 0: 3000)
    int legacy;    // bench_fit's "before": the solver of stop 28 (plain
                   // Levenberg-Marquardt, plan_eval per call, the
                   // residuals computed again with the Jacobian, only the
                   // best start's basin joined)
    /* the scheme form only: --set NAME=VALUE for its consts, -D NAME=INT
     * for its ints (argv's strings) */
    const char *const *sets;
    int nsets;
    const char *const *defines;
    int ndefines;
} FitOptions;

/* a target given as data (fit_data.c): the natural cubic spline through
 * n points (x increasing); m its second derivatives at them */
typedef struct FitSpline {
    int n;
    double *x, *y, *m;
} FitSpline;

/* (fit_data.c) fit_target_data reads FILE.csv (x,y rows, an optional
 * header line, x increasing, at least 3 rows) into a spline */
void fit_spline_free(FitSpline *s);
/* s (o = 0) or s' (o = 1) at x[0..n-1] into v, st[i] = 0, or 3 where x[i]
 * lies outside the data; returns the count of those */
size_t fit_spline_eval(const FitSpline *s, int o, size_t n, const double *x,
                       double *v, unsigned char *st);

/* what f is: a Plan's outputs f_out (f) and fp_out (f') of its param
 * `param` (of nparams; the others 0), or a spline (plan NULL) */
typedef struct FitTarget {
    Plan *plan;
    double *consts; // the values of the plan's consts (owned), or NULL
    int f_out, fp_out, param, nparams;
    FitSpline *spline;
    const char *label; // for messages: the expression, "f", "FILE.csv"
} FitTarget;

typedef struct Fit {
    FitOptions o;
    int n;          // N nodes
    int nu;         // N - 2 unknowns
    size_t ns;      // m + 1 samples
    FitTarget tg;   // f and f' (owned)
    double *phi;    // ns * n: phi[i*n + k] = phi_k(t_i), from the derived
                    // curve's plan
    double *coef;   // n * n: coef[k*n + j] = the exact coefficient of t^j in
                    // phi_k (from the derived weights), or NULL: the
                    // weights are not polynomials
    int ends_exact; // phi_1 = 1 at t = 0 and phi_N = 1 at t = 1: x(0) and
                    // x(1) are set to LO and HI exactly
    const double **tpar; // scratch: the params of the target's plan
    PlanProg *prog[2];   // f and f' prepared (runtime/eval.h), or NULL
    double *tzero;       // ... the zeros of those that are not x
    /* scratch for the residuals */
    double *x, *xs, *fx, *fpx;
    unsigned char *st;
    double *jx;
    /* the residuals at the last nodes they were computed for: the
     * Jacobian is asked at the point just accepted, whose residuals the
     * solver has (the callback computes them again); f->fx is then not
     * computed */
    double *rlast, *xlast;
    int rvalid;
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
    int starts_merged;        // abandoned on two nodes merging (fit.c)
    int iterations_all;       // the solver's iterations over every start
    int evaluations_all;      // and its residual evaluations
    LsqResult lsq;            // the winning start's solver report
    double start_mse[2];      // MSE at the Chebyshev and uniform starts
    double cheb_lagrange_mse; // the baseline: Lagrange interpolation of f
                              // at N Chebyshev nodes, over x = lo .. hi in
                              // m uniform steps
} FitResult;

/* Derives and checks; NULL after reporting to err (*rc = 1: the target
 * has an error or is undefined on the interval; 2: bad options). */
Fit *fit_new(const char *target, const FitOptions *o, FILE *err, int *rc);
/* The same with the target t (taken over: freed with the fit, also on
 * failure) and the curve's table phi (ns * N, taken over), its
 * coefficients coef (N * N, taken over, or NULL) and ends_exact: what
 * the scheme form (fit_scheme.c) and --data give. */
Fit *fit_new_from(const FitOptions *o, FitTarget *t, double *phi, double *coef,
                  int ends_exact, FILE *err, int *rc);
/* o's values in range, else -1 after reporting */
int fit_check_options(const FitOptions *o, FILE *err);
/* --data: t's spline read from csv; o->lo, o->hi NaN take the data's ends */
int fit_target_data(FitTarget *t, const char *csv, FitOptions *o, FILE *err);
/* the interpolation curve through N nodes (the families scheme): its
 * table and coefficients for fit_new_from */
int fit_lagrange_curve(int n, size_t ns, double **phi, double **coef,
                       FILE *err);
/* the pieces of fit_lagrange_curve, for the scheme form: the exact
 * coefficients of output out's weights in ring variable var (-1: not
 * polynomials in it alone of degree < n), and its table */
int fit_curve_coefficients(double *coef, const Derived *d, int out, slong var,
                           int n);
int fit_curve_table(double *phi, const Plan *p, const double *consts, int out,
                    int param, int nparams, size_t ns, int n);
/* The scheme form (fit_scheme.c): `pointcalc fit FILE` derives the
 * scheme and, for each of its fit statements in order, builds the Fit
 * (samples, starts and max_iter of o unless the statement says; with
 * data, f is that CSV's spline) and calls report.  Returns 0, or the
 * first non-zero of report and the errors (1: in the scheme or its fit
 * statements, located; 2: usage). */
typedef struct FitInfo {
    const char *curve, *target; // the names of X and f (as written)
    const char *point_eq;       // when f->coef is NULL: X's point equation
} FitInfo;
typedef int (*FitReport)(void *ctx, Fit *f, const FitInfo *info);
int fit_scheme_run(const char *path, const char *data, const FitOptions *o,
                   FitReport report, void *ctx, FILE *err);
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
/* f (o = 0) or f' (o = 1) at x[0..n-1] into v, statuses (PlanStatus)
 * into st */
void fit_target_at(const Fit *f, int o, size_t n, const double *x, double *v,
                   unsigned char *st);

/* (fit_plot.c) the picture of a fit: f over [lo, hi], the curve x(t),
 * y(t) (from its exact coefficients when it has them, else at the m + 1
 * samples) and the nodes (x_k, y_k); 0, or 1 after a message on err */
int fit_plot_svg(const char *path, const Fit *f, const FitResult *r,
                 const double *y, const double *cx, const double *cy,
                 FILE *err);

/* the nodes (n values) of log-gaps u, and back */
void fit_nodes_of_u(const Fit *f, const double *u, double *x);
void fit_u_of_nodes(const Fit *f, const double *x, double *u);

#endif
