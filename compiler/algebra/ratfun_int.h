/*
 * ratfun_int.h - what the ratfun files share (private to ratfun*.c).
 *
 * ratfun.c        canonical form, management, predicates, arithmetic
 * ratfun_calc.c   derivatives, composition, evaluation
 * ratfun_parse.c  ratfun_set_str
 * ratfun_size.c   the size guards
 */
#ifndef PC_RATFUN_INT_H
#define PC_RATFUN_INT_H

#include "compiler/algebra/ratfun.h"

/* Divides num and den by their gcd in place and fixes the sign of den.
 * den is non-zero. */
void _ratfun_reduce(fmpz_mpoly_t num, fmpz_mpoly_t den, const Ring *r);

#endif
