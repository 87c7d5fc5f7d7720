/*
 * polyfactor.h - cheap factoring and proofs of irreducibility (exact), for
 * the printer's factored forms: they let it skip FLINT's factoring, most of
 * the printing time, or run it in a smaller ring.
 *
 * Proofs answer 1 (proved) or 0 (no proof: the polynomial may still be
 * irreducible, or not), except polyfactor_quadratic_irreducible, which
 * answers both ways.
 */
#ifndef PC_POLYFACTOR_H
#define PC_POLYFACTOR_H

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_poly.h>

#include "compiler/algebra/ring.h"

/* ring_factor(f, p, r), done in a ring of only the variables p uses; f in
 * r's ring.  0 when ring_factor fails (f then unspecified). */
int polyfactor_compact(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                       const Ring *r);

/* p (of r) in one variable x, a product of distinct linear factors over
 * Q (times its integer content and a power of x): f as ring_factor would
 * make it, up to the order of the factors (the content with the sign of
 * p's leading term, x^k, the factors a*x - b, a > 0), found by p's roots
 * modulo a prime of 16 bits, each read as a fraction b/a, and proved by
 * their product.  Only where ring_factor factors fully
 * (ring_factor_affordable).  0: not so, or not found (f untouched). */
int polyfactor_split_linear(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                            const Ring *r);

/* q(1, ..., 1) == 0: necessary for x - 1 to divide q */
int polyfactor_vanishes_at_ones(const fmpz_mpoly_t q, const Ring *r);

/* u of degree 2 is irreducible over Q: its discriminant is not a square */
int polyfactor_quadratic_irreducible(const fmpz_poly_t u);

/* u (primitive, degree >= 1) proved irreducible over Q: irreducible modulo
 * a small prime not dividing its leading coefficient */
int polyfactor_irreducible_mod_small_prime(const fmpz_poly_t u);

/* p (of r, not linear) proved irreducible and primitive, by its content in
 * one variable and an irreducible univariate image, or by the degrees of
 * its images on lines modulo small primes */
int polyfactor_surely_irreducible(const fmpz_mpoly_t p, const Ring *r);

#endif
