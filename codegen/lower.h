/*
 * lower.h - Derived (exact weights over FLINT) -> Plan (a numeric program).
 *
 * The only bridge between compiler/ (FLINT) and runtime/ (plain doubles).
 * For every output the weights w_i = n_i/d_i are lowered as
 *
 *   w_i = c_i * (product of n_i's factors) * (L / d_i) * inv,
 *   inv = 1/L,  L = lcm of the d_i,  pole check on L,
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

#include "compiler/derive.h"
#include "runtime/plan.h"

/* Lowers every output of d.  Returns NULL (with a message on err, which may
 * be NULL) when the equations use something the numeric back ends cannot
 * evaluate yet (symbolic atoms beyond params and consts). */
Plan *lower_derived(const Derived *d, FILE *err);

#endif
