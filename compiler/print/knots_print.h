/*
 * knots_print.h - the knots of derive's outputs and the smoothness at each
 * (compiler/derive/knots.h), as text (derive --knots) and as the "knots"
 * array of derive --format json.
 *
 *   R at t = 1: C^1, G^0; jump of d2R/dt2: 6*B - 6*O
 */
#ifndef PC_KNOTS_PRINT_H
#define PC_KNOTS_PRINT_H

#include <stdio.h>

#include "compiler/derive.h"
#include "compiler/derive/knots.h"

/* derive --knots: one line per knot of every output (text) */
void knots_print(FILE *out, const Derived *d);

/* , "knots": [...] (and "knots_not_analysed", "knots_note") of output o
 * for derive --format json; nothing when it has no sign kernel of a
 * param */
void knots_json(FILE *out, const Derived *d, slong o);

#endif
