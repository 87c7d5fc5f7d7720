/*
 * numsolve.h - the numeric back end of a numeric solve (`solve ... near`,
 * compiler/derive.h: NumericSystem): the residuals and the exact Jacobian
 * the compiler derived, lowered to one Plan (codegen/lower.h) and
 * evaluated by the runtime's interpreter, solved by runtime/lsq.h.
 *
 *   m = n   damped Newton (lsq_newton), from the start
 *   m > n   Levenberg-Marquardt (lsq_solve): least squares
 *
 * then checked where it stopped: the Jacobian's rank there (below n:
 * NUMERIC_SINGULAR) and, for Newton, the full Newton step from there
 * (more than 1e-9 (1 + |u|): NUMERIC_NOCONV), so a stop on a small step
 * is never taken for a root.
 */
#ifndef PC_NUMSOLVE_H
#define PC_NUMSOLVE_H

#include "compiler/derive.h"

/* DeriveNumericFn: solves s (compiler/derive.h); 0 when converged */
int numsolve_run(NumericSystem *s);

/* The residuals and Jacobian of s as a program, for the solver and for
 * tests (NULL when they cannot be evaluated in double precision). */
typedef struct NumEval NumEval;
NumEval *numsolve_prepare(const NumericSystem *s);
/* r (m values) and, when J is not NULL, J (m*n, row-major) at u; 0, or 1
 * when a residual cannot be evaluated there (a pole, a domain) */
int numsolve_eval(void *e, const double *u, double *r, double *J);
void numsolve_free(NumEval *e);

#endif
