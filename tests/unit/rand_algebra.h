/*
 * rand_algebra.h - seeded random values for the algebra property tests
 * (test_ratfun, test_pteq, test_linsolve).  Header-only, static: each test
 * binary is one translation unit.
 *
 * The seed is fixed so failures reproduce; PC_SEED=n in the environment
 * picks another stream for a wider sweep.  Values are kept small (few
 * terms, low degrees, small coefficients) so that gcds meet real common
 * factors often and the tests stay fast under valgrind.
 */
#ifndef PC_TEST_RAND_ALGEBRA_H
#define PC_TEST_RAND_ALGEBRA_H

#include <stdlib.h>

#include <flint/flint.h>
#include <flint/fmpq.h>
#include <flint/fmpz_mpoly.h>

#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"

static inline void rand_init(flint_rand_t st)
{
    const char *s = getenv("PC_SEED");
    flint_randinit(st);
    if (s != NULL)
        flint_randseed(st, (ulong)strtoul(s, NULL, 10) + 1, 12345);
}

/* The fixture of the algebra tests: a ring whose variables are the first
 * nvars of t, u, v, and the seeded random state.  Each test file defines
 * setup() as fixture_setup(state, nvars) and uses fixture_teardown. */
typedef struct Fixture {
    Ring r;
    flint_rand_t st;
} Fixture;

static inline int fixture_setup(void **state, slong nvars)
{
    static const char *const names[] = {"t", "u", "v"};
    Fixture *f = malloc(sizeof *f);
    ring_init(&f->r, nvars, names);
    rand_init(f->st);
    *state = f;
    return 0;
}

static inline int fixture_teardown(void **state)
{
    Fixture *f = *state;
    flint_randclear(f->st);
    ring_clear(&f->r);
    free(f);
    return 0;
}

/* number of iterations: fewer under valgrind (PC_VALGRIND set) */
static inline slong rand_iters(slong n)
{
    return getenv("PC_VALGRIND") != NULL ? (n + 4) / 5 : n;
}

/* a polynomial with up to maxlen terms, exponents < expb per variable */
static inline void rand_poly(fmpz_mpoly_t p, flint_rand_t st, slong maxlen,
                             ulong expb, const Ring *r)
{
    fmpz_mpoly_randtest_bound(p, st, 1 + (slong)n_randint(st, (ulong)maxlen),
                              1 + n_randint(st, 5), expb, r->ctx);
}

/* A canonical random rational function.  A quarter of them are
 * polynomials and a quarter have an integer denominator, so the fast paths
 * of add and mul are exercised as much as the general one; the rest share
 * a random factor between num and den before canonicalising, so the gcd
 * has something to cancel. */
static inline void rand_ratfun(RatFun x, flint_rand_t st, const Ring *r)
{
    fmpz_mpoly_t g;
    ulong kind = n_randint(st, 4);

    fmpz_mpoly_init(g, r->ctx);
    rand_poly(x->num, st, 4, 3, r);
    if (kind == 0) {
        fmpz_mpoly_one(x->den, r->ctx);
    } else if (kind == 1) {
        fmpz_mpoly_set_si(x->den, (slong)n_randint(st, 13) - 6, r->ctx);
    } else {
        rand_poly(x->den, st, 3, 3, r);
        if (kind == 3) {
            rand_poly(g, st, 2, 2, r);
            fmpz_mpoly_mul(x->num, x->num, g, r->ctx);
            fmpz_mpoly_mul(x->den, x->den, g, r->ctx);
        }
    }
    if (fmpz_mpoly_is_zero(x->den, r->ctx))
        fmpz_mpoly_set_si(x->den, -3, r->ctx);
    if (ratfun_canonicalise(x, r) != RATFUN_OK)
        abort(); /* den was made non-zero above */
    fmpz_mpoly_clear(g, r->ctx);
}

/* non-zero variant */
static inline void rand_ratfun_nz(RatFun x, flint_rand_t st, const Ring *r)
{
    do
        rand_ratfun(x, st, r);
    while (ratfun_is_zero(x, r));
}

/* a small rational number, num and den below 2^8 */
static inline void rand_fmpq(fmpq_t q, flint_rand_t st)
{
    fmpq_randtest(q, st, 8);
}

/* a random combination of the base points lo..hi-1 with weight sum `sum`
 * (1 a point, 0 a direction) */
static inline void rand_comb(PointEq x, flint_rand_t st, slong lo, slong hi,
                             int sum, const Ring *r)
{
    slong n = hi - lo;
    slong *pts = malloc(sizeof(slong) * (size_t)n);
    RatFunStruct *w = malloc(sizeof(RatFunStruct) * (size_t)n);
    RatFun acc;
    ratfun_init(acc, r);
    ratfun_set_si(acc, sum, r);
    for (slong i = 0; i < n; i++) {
        pts[i] = lo + i;
        ratfun_init(w + i, r);
        if (i + 1 < n) {
            if (n_randint(st, 3) == 0)
                ratfun_zero(w + i, r);
            else
                rand_ratfun(w + i, st, r);
            ratfun_sub(acc, acc, w + i, r);
        } else {
            ratfun_set(w + i, acc, r);
        }
    }
    pteq_set_weights(x, pts, w, n, r);
    for (slong i = 0; i < n; i++)
        ratfun_clear(w + i, r);
    free(w);
    free(pts);
    ratfun_clear(acc, r);
}

#endif
