/*
 * eval.h - the Plan interpreter: numeric values of a scheme's outputs
 * without a C compiler at run time.
 *
 * Samples are processed in blocks of PLAN_BLOCK: every instruction runs over
 * a whole block (a fixed-length loop the compiler vectorises), uniform
 * instructions (no param dependence) run once per call, and the weights are
 * then applied to the coordinates column by column.
 *
 * Pole convention (docs/codegen.md): a sample where a denominator of the
 * output's reduced equation evaluates to 0 (a pole) or to a non-finite
 * value (an overflow) gets NaN in every coordinate, status[i] = 1 or 2
 * (PlanStatus), and is counted in the return value.
 */
#ifndef PC_EVAL_H
#define PC_EVAL_H

#include <stddef.h>

#include "runtime/plan.h"

enum { PLAN_BLOCK = 128 }; // samples per block (a multiple of 8)

/* Evaluates output o of p at n samples.
 *   params[i]  the n values of param i (declaration order)
 *   consts[i]  the value of const i
 *   points[i]  dim coordinates of base point i; may be NULL for points the
 *              output does not use (plan_output_uses_point)
 *   out        n*dim doubles, row-major (n doubles for a scalar output)
 *   status     n PlanStatus codes (0 ok, 1 pole, 2 overflow) or NULL
 * Returns the number of pole and overflow samples. */
size_t plan_eval(const Plan *p, int o, size_t n, const double *const *params,
                 const double *consts, const double *const *points, int dim,
                 double *out, unsigned char *status);

/* A prepared evaluation of output o with the consts and points fixed:
 * what plan_eval does once per call (liveness, the uniform registers,
 * the register slots) done once, for a caller that evaluates one output
 * many times (fit, the numeric solve).  p, consts and points must stay
 * valid and unchanged while it is used. */
typedef struct PlanProg PlanProg;
PlanProg *plan_prog_new(const Plan *p, int o, const double *consts,
                        const double *const *points, int dim);
/* plan_eval of the prepared output at n samples */
size_t plan_prog_eval(const PlanProg *g, size_t n, const double *const *params,
                      double *out, unsigned char *status);
void plan_prog_free(PlanProg *g);

/* 1 if output o has a non-zero weight on base point `point`. */
int plan_output_uses_point(const Plan *p, int o, int point);

#endif
