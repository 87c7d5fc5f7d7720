/*
 * ring.h - the polynomial ring of one compilation.
 *
 * A Ring is one FLINT fmpz_mpoly context whose variables are the scheme's
 * scalar symbols: every `param`, then every `const`, in declaration order
 * (later: transcendental and metric atoms get further variables).  All
 * RatFun and PointEq values of one compilation live in one Ring.
 *
 * Variable names are borrowed: they must outlive the Ring (arena strings).
 */
#ifndef PC_RING_H
#define PC_RING_H

#include <flint/fmpz_mpoly.h>
#include <flint/fmpz_mpoly_factor.h>

typedef struct Ring {
    fmpz_mpoly_ctx_t ctx; // FLINT context, ORD_DEGREVLEX
    slong nvars;          // number of named variables (may be 0)
    const char **names;   // owned array of borrowed strings, nvars entries
    const char **latex;   // NULL, or per variable its LaTeX (NULL entries:
                          // made from the name); owned array, borrowed
                          // strings (the kernels' names, kernel.h)
} Ring;

/* Initialise r with nvars variables called names[0..nvars-1].  nvars may be
 * 0 (a scheme without parameters); FLINT then still gets one unnamed,
 * never-used variable.  Copies the array, borrows the strings. */
void ring_init(Ring *r, slong nvars, const char *const *names);
void ring_clear(Ring *r);

/* Index of the variable called name, or -1. */
slong ring_var_index(const Ring *r, const char *name);

/* 1 when fmpz_mpoly_factor(p) is affordable: FLINT 2.9's factoring has no
 * time bound, and some short polynomials take minutes (1 - (t^60 +
 * u^60)(t^30 - u^17): 80 s; t^720 - 1: 27 s; a 600-variable linear form:
 * minutes).  Measured limits: at most 400 terms and 8 variables, degree at
 * most 200 in one variable, total degree at most 32 in several. */
int ring_factor_affordable(const fmpz_mpoly_t p, const Ring *r);

/* f = the factorisation of p into irreducibles where that is affordable,
 * else its square-free factorisation (gcd-based, fast: (4t - 3)^201 is
 * still found as a power of 4t - 3, which matters for accurate numerics
 * and pole checks), else nothing: returns 0 and callers treat p as one
 * factor.  f must be initialised. */
int ring_factor(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, const Ring *r);

/* f = the irreducible (full) or square-free factors of p, computed in a
 * context of only the variables p uses, then mapped back (FLINT's
 * factoring spends time on every variable of the context, used or not, and
 * a ring with functions has dozens of kernel slots); f initialised.  The
 * caller decides that it is affordable (ring_factor_affordable). */
int ring_factor_compact(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, int full,
                        const Ring *r);

#endif
