/*
 * linsolve.h - linear systems over the field of rational functions.
 *
 * Solves  sum_j a[i*n + j] * x_j = b_i  (i < m, j < n)  exactly by Gaussian
 * elimination over Q(x1..xk), choosing at each step the structurally simplest
 * non-zero pivot (ratfun_length).  "Non-zero" means not identically zero: the
 * answer is the generic one, valid wherever the pivots do not vanish.
 *
 * Used by meet() (S-theorem: two unknowns; V-theorem: three) and later by
 * `solve` (unknown points, monograph ch. 4).
 */
#ifndef PC_LINSOLVE_H
#define PC_LINSOLVE_H

#include "compiler/algebra/ratfun.h"

typedef enum LinSolveResult {
    LINSOLVE_UNIQUE,          // rank == n and consistent: x holds the solution
    LINSOLVE_UNDERDETERMINED, // rank < n and consistent: x holds one solution
                              // (free unknowns set to 0)
    LINSOLVE_INCONSISTENT,    // no solution (x untouched)
    LINSOLVE_FAILED,          // the normal form failed (LinNormal.err; x
                              // untouched)
} LinSolveResult;

/* A normal form applied to every entry the elimination forms (the kernels'
 * identities, kernel_reduce): pivots, rank and consistency are then decided
 * on normal forms, in which a numerator is zero exactly when the value is.
 * reduce returns 0, or an error code that stops the elimination (kept in
 * err: LINSOLVE_FAILED). */
typedef struct LinNormal {
    int (*reduce)(void *ctx, RatFunStruct *x);
    void *ctx;
    int err;
} LinNormal;

/* x must have n initialised entries; a and b are not modified.  *rank (if
 * rank != NULL) receives the rank of the coefficient matrix a. */
LinSolveResult linsolve(RatFunStruct *x, slong *rank, const RatFunStruct *a,
                        const RatFunStruct *b, slong m, slong n, const Ring *r);
/* the same with every entry, those of a and b first, in the normal form
 * nf (NULL: none) */
LinSolveResult linsolve_nf(RatFunStruct *x, slong *rank, const RatFunStruct *a,
                           const RatFunStruct *b, slong m, slong n,
                           LinNormal *nf, const Ring *r);

/* The simplest non-zero pivot (fewest terms, ratfun_length) among rows
 * from..m-1 and the columns 0..n-1 not used: its row, and its column in
 * *col; -1 when every such entry is zero.  row[i] is row i's n entries. */
slong linsolve_pivot(RatFunStruct *const *row, slong from, slong m, slong n,
                     const char *used, slong *col, const Ring *r);

#endif
