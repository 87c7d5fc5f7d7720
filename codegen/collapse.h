/*
 * collapse.h - the collapsed evaluation kernel of emit-c (--kernel
 * collapsed, docs/codegen.md "The collapsed kernel").
 *
 * An output M(t) = sum_k n_k(t) P_k / d(t) whose numerators and
 * denominator are polynomials in ONE param t (no other param, const,
 * function or unknown), with a declared range t in [a, b] of rational
 * endpoints, is evaluated per coordinate as one polynomial:
 *
 *   tau   = (t - m) * 2^-e            m ~ (a + b)/2, |tau| <= 1 on [a, b]
 *   c_j   = sum_k a_jk P_k[c]          once per call (a_jk exact, rounded)
 *   M_c   = (sum_j c_j tau^j) / (sum_j b_j tau^j)     Horner, one division
 *
 * when a bound on its rounding error, computed at emit time over [a, b],
 * is at most COLLAPSE_TOL relative to max_k |P_k[c]| * sum_k |w_k(t)|:
 *
 *   kappa   >= max over [a, b] of sum_jk |a_jk| |tau|^j / sum_k |n_k(t)|
 *   kappa_d >= max over [a, b] of sum_j  |b_j|  |tau|^j / |d(t)|
 *   bound    = g_A kappa (1 + r)/(1 - r) (1 + u)^2 + r/(1 - r) + 3u,
 *              r = g_D kappa_d,  g_A = gamma(K + 3n + 1), g_D = gamma(3n + 1)
 *
 * (gamma(k) = k u / (1 - k u), u = 2^-53, n the degree, K the points).  The
 * kappas are upper bounds found on subintervals from exact values (FLINT
 * fmpq) and a mean-value lower bound of each |n_k|.  Samples outside [a, b]
 * (or NaN) are passed, a block of 64 at a time, to today's weights code,
 * which the file also holds (static).
 */
#ifndef PC_COLLAPSE_H
#define PC_COLLAPSE_H

#include <stdio.h>

#include "compiler/derive.h"
#include "runtime/plan.h"

/* the accepted bound (see above) */
#define COLLAPSE_TOL 1e-13
/* the largest degree collapsed */
enum { COLLAPSE_MAX_DEGREE = 64 };

/* The collapsed forms of p's outputs, p just lowered from d (the Collapse
 * is plain data, runtime/plan.h; lower_collapse attaches it to the Plan,
 * and plan_keep_outputs keeps it in step). */
Collapse *collapse_new(const Derived *d, const Plan *p);

/* The names the emitter uses (emit_c.c's, borrowed). */
typedef struct CollapseNames {
    const char *fn;       // NAME_M_batch_checked
    const char *fallback; // the static weights function for other samples
    int is_static;        // fn is static (not asked for)
    char *const *in;      // params then consts
    int nparams, nin;
    char *const *pt; // points
    int npt;
} CollapseNames;

/* Writes the collapsed NAME_M_batch_checked of output o (o->ok). */
void collapse_emit_batch(FILE *out, const CollapseOutput *o,
                         const CollapseNames *N, int line);
/* 1 when name is none of list[0..n-1] (the fallback's name is free) */
int collapse_name_free(const char *name, char *const *list, int n);
/* One comment line per output: its kernel, or why it keeps the weights. */
void collapse_banner(FILE *out, const Collapse *c);

#endif
