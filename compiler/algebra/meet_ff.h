/*
 * meet_ff.h - the fraction-free meet of two flats (meet_ff.c), private to
 * construct.c: construct_meet tries it first and falls back to the exact
 * general path.
 */
#ifndef PC_MEET_FF_H
#define PC_MEET_FF_H

#include "compiler/algebra/construct.h"

/* the most columns (defining points of both flats) the fast path and the
 * meet's parameters take */
#define MEET_MAX_COLS 5

/* The meet of the flats cols[0..na-1] and cols[na..k-1] over the sorted
 * base points rows[0..m-1] (their supports' union): 1 (res set), 0 when
 * the general path must decide (a degenerate or unusual case), -1 when an
 * intermediate product would be too large (MEET_TOO_BIG). */
int meet_fraction_free(PointEq res, const PointEq *cols, slong na, slong k,
                       const slong *rows, slong m, const Ring *r);

#endif
