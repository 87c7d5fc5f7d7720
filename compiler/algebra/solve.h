/*
 * solve.h - linear systems of point equations (`solve`, monograph 3.6, ch. 4).
 *
 * An unknown point is a free column while it is unknown: every construction
 * treats it as one more generic base point, so every equation built from
 * constructions is LINEAR in the unknown points, with scalar coefficients
 * (rational functions of the params and consts).  An equation P = Q is the
 * combination E = P - Q = 0 (weights summing to 0); over one denominator
 * E = (sum n_c * X_c) / d, and since the base points are independent,
 * E = 0 says exactly that every numerator n_c of a known column vanishes once
 * the unknowns are replaced by their combinations.  With U the numerators of
 * the unknown columns and R those of the known ones:
 *
 *     U * X = -R * K        (X the unknown points, K the known columns)
 *
 * one scalar system with one right-hand side per known column, whose
 * solution puts every unknown over ONE denominator: a PointEq.
 *
 *   - U numeric (every entry a number: the interpolation schemes, nodes at
 *     fixed parameter values): FLINT's fmpz_mat_solve (fraction-free or
 *     multimodular, FLINT's choice) of U * Y = det * I, then X = -Y*R/det.
 *   - otherwise: fraction-free Gauss-Jordan (Bareiss) on [U | R] over
 *     Z[params, consts], choosing the shortest non-zero pivot among the
 *     remaining rows and unknowns; every division is exact, and at the end
 *     every pivot equals the same determinant, the common denominator.
 *
 * The answer is the generic one: valid wherever that determinant does not
 * vanish (the same convention as meet()).
 */
#ifndef PC_SOLVE_H
#define PC_SOLVE_H

#include "compiler/algebra/linsolve.h"
#include "compiler/algebra/pteq.h"

typedef enum SolveStatus {
    SOLVE_OK,           // x holds the unknowns
    SOLVE_SINGULAR,     // consistent, but some unknowns stay undetermined
    SOLVE_INCONSISTENT, // some equation contradicts the others
    SOLVE_TOO_BIG,      // an intermediate product would pass the size limit
    SOLVE_TIME,         // the deadline passed (solve_points_ex)
    SOLVE_FAILED,       // the normal form failed (solve_points_nf: nf->err)
} SolveStatus;

/* the most unknowns of one system (point unknowns, or scalar unknowns of
 * the mixed path in derive.c, which counts each point's weights) */
#define SOLVE_MAX_UNKNOWNS 2000

/* Solves eqs[e] = 0 (e < neq) for the unknown columns cols[0..nunk-1]
 * (distinct point indices).  On SOLVE_OK, x[j] (nunk initialised PointEqs)
 * is unknown cols[j] as a canonical combination of the other columns.
 * Otherwise x is untouched, and (when not NULL) undetermined[j] is set to 1
 * for each unknown the system leaves free, dependent[e] to 1 for each
 * equation that the others already imply (SOLVE_SINGULAR) or contradict
 * (SOLVE_INCONSISTENT); both arrays are cleared first. */
SolveStatus solve_points(PointEq *x, const PointEq *eqs, slong neq,
                         const slong *cols, slong nunk, char *undetermined,
                         char *dependent, const Ring *r);
/* the same with a deadline (CLOCK_MONOTONIC seconds; 0: none), checked at
 * every row of the elimination: SOLVE_TIME when it has passed */
SolveStatus solve_points_ex(PointEq *x, const PointEq *eqs, slong neq,
                            const slong *cols, slong nunk, char *undetermined,
                            char *dependent, double deadline, const Ring *r);
/* the same over the rational functions with every entry in the normal form
 * nf (the kernels' identities, kernel_reduce) when nf is not NULL: pivots,
 * rank and consistency decided modulo the identities (SOLVE_FAILED when the
 * normal form fails: nf->err).  The solutions are not reduced. */
SolveStatus solve_points_nf(PointEq *x, const PointEq *eqs, slong neq,
                            const slong *cols, slong nunk, char *undetermined,
                            char *dependent, double deadline, LinNormal *nf,
                            const Ring *r);

#endif
