/*
 * lower.h - Derived (exact weights over FLINT) -> Plan (a numeric program).
 *
 * The only bridge between compiler/ (FLINT) and runtime/ (plain doubles).
 * For every output the weights w_i = n_i/d_i are lowered as
 *
 *   w_i = c_i * (product of n_i's factors) * (L / d_i) * inv,
 *   inv = 1/L,  L = lcm of the d_i,  pole checks on L's factors, and an
 *   overflow check on inv (0 where L is not finite),
 *
 * where every irreducible factor is written in Horner form (main variable:
 * a param, so coefficients in the consts are uniform and hoisted), powers
 * are shared multiplication chains, and the Plan builder hash-conses all of
 * it across weights and outputs (the common denominator and the factors
 * t, t - 1 of the Desargues arc are computed once).
 */
#ifndef PC_LOWER_H
#define PC_LOWER_H

#include <stdio.h>

#include <flint/fmpq.h>

#include "compiler/derive.h"
#include "runtime/plan.h"

/* Lowers every output of d.  Returns NULL, with an error in the contract's
 * format (FILE:LINE:COL at the output's definition) on err (NULL: none),
 * when an output cannot be evaluated in double precision: an unsolved
 * unknown scalar, a degree above 2^24, or a coefficient that no
 * double holds (beyond ~1.8e308, or non-zero below ~4.9e-324). */
Plan *lower_derived(const Derived *d, FILE *err);

/* The collapsed forms of p's outputs (emit-c --kernel collapsed,
 * codegen/collapse.h), p just lowered from d: computed exactly from d's
 * weights and attached to p (p->collapse, replacing any), so that the C
 * writer needs only the Plan.  Returns p->collapse. */
Collapse *lower_collapse(Plan *p, const Derived *d);

/* Why a coefficient cannot become a double. */
typedef enum LowerError {
    LOWER_OK,
    LOWER_OVERFLOW,  // beyond the largest double
    LOWER_UNDERFLOW, // non-zero, but it rounds to 0
} LowerError;

/* *res = q rounded to the nearest double, ties to even, subnormals
 * included (FLINT 2.9's fmpq_get_d truncates); LOWER_OK when the result is
 * finite and, for q != 0, non-zero. */
LowerError lower_q_to_double(double *res, const fmpq_t q);

#endif
