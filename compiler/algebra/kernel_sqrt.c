/*
 * kernel_sqrt.c - square roots (kernel.h): of numbers, and of polynomials
 * with their squares pulled out, also squares modulo the relations.
 *
 * sqrt(8) = 2*sqrt(2) by the square-free part of a number; sqrt(x^2*y) =
 * |x|*sqrt(y) = x*sign(x)*sqrt(y), the sign decided where it can be
 * (kernel_sign.c, or a square modulo the relations below) and owed
 * otherwise.  So the relations stay a triangular set of irreducible
 * polynomials, and a reduced value is zero exactly when it is.
 * kernel_apply (kernel_fold.c) calls kernel_sqrt_poly for every sqrt of a
 * non-constant argument.
 */
#include "compiler/algebra/kernel_int.h"

#include <stdlib.h>

#include <flint/fmpz_factor.h>

#include "base/mem.h"

enum {
    FACTOR_BITS = 160, // integers under a sqrt factored up to this size
};

/* sqrt of a number q >= 0: s/d * prod sqrt(p) over the primes p of the
 * square-free part of num*den (beyond FACTOR_BITS: one kernel) */
int kernel_sqrt_num(Kernels *K, RatFun res, const fmpq_t q)
{
    const Ring *r = K->r;
    if (fmpq_is_zero(q)) {
        ratfun_zero(res, r);
        return 0;
    }
    fmpz_t m, s, f;
    fmpz_init(m);
    fmpz_init(s);
    fmpz_init(f);
    fmpz_mul(m, fmpq_numref(q), fmpq_denref(q));
    fmpz_one(s);
    fmpz_one(f);
    RatFun acc, t;
    ratfun_init(acc, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    int rc = 0;
    if (fmpz_bits(m) <= FACTOR_BITS) {
        fmpz_factor_t fac;
        fmpz_factor_init(fac);
        fmpz_factor(fac, m);
        for (slong i = 0; i < fac->num && rc == 0; i++) {
            ulong e = fac->exp[i];
            fmpz_t pw;
            fmpz_init(pw);
            fmpz_pow_ui(pw, fac->p + i, e / 2);
            fmpz_mul(s, s, pw);
            fmpz_clear(pw);
            if (e % 2) {
                fmpz_mpoly_set_fmpz(t->num, fac->p + i, r->ctx);
                fmpz_mpoly_one(t->den, r->ctx);
                rc = kernels_intern(K, t, KF_SQRT, t, NULL, 0);
                if (rc == 0)
                    ratfun_mul(acc, acc, t, r);
            }
        }
        fmpz_factor_clear(fac);
    } else {
        fmpz_t rem;
        fmpz_init(rem);
        fmpz_sqrtrem(s, rem, m);
        if (!fmpz_is_zero(rem)) {
            fmpz_one(s);
            fmpq_t mq;
            fmpq_init(mq);
            fmpq_set_fmpz_frac(mq, m, s);
            ratfun_set_fmpq(t, mq, r);
            fmpq_clear(mq);
            rc = kernels_intern(K, t, KF_SQRT, t, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
        }
        fmpz_clear(rem);
    }
    if (rc == 0) {
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_fmpz_frac(c, s, fmpq_denref(q));
        ratfun_set_fmpq(t, c, r);
        ratfun_mul(res, acc, t, r);
        fmpq_clear(c);
    }
    ratfun_clear(t, r);
    ratfun_clear(acc, r);
    fmpz_clear(f);
    fmpz_clear(s);
    fmpz_clear(m);
    return rc;
}

/* res *= P^e (e may be negative), P a polynomial */
static void mul_poly_pow(RatFun res, const fmpz_mpoly_t P, slong e,
                         const Ring *r)
{
    RatFun t;
    ratfun_init(t, r);
    fmpz_mpoly_set(t->num, P, r->ctx);
    fmpz_mpoly_one(t->den, r->ctx);
    ratfun_canonicalise(t, r);
    ratfun_pow_si(t, t, e, r);
    ratfun_mul(res, res, t, r);
    ratfun_clear(t, r);
}

/* ---- squares modulo the relations --------------------------------------- */

/* The normal form hides squares: (1 + cos(t))^2 is 2 + 2*cos(t) - sin(t)^2,
 * cos(t)^2 is 1 - sin(t)^2, (a + sqrt(a^2 - b^2)*cos(t))^2 has no square
 * factor as a polynomial.  A square f^2 modulo the relations is found by
 * denesting, one quadratic kernel v (v^2 = R) at a time, from the last:
 * P = A + B v is (g + h v)^2 = g^2 + h^2 R + 2 g h v exactly when
 *
 *   N = A^2 - B^2 R = (g^2 - h^2 R)^2          (the norm is a square m^2)
 *   g^2 = (A + m)/2,  h^2 R = (A - m)/2,  h = B/(2 g)   (for m or -m)
 *
 * where N, g^2 and h^2 R involve only the kernels before v: the same
 * question one level down.  Without any quadratic kernel, P must be a
 * square of the rational functions, or a square times one relation R
 * (1 - sin(t)^2 = cos(t)^2: f = h v).  Whatever is found is checked:
 * f^2 reduces to P exactly, so the search can only miss, never lie. */

enum {
    SQUARE_MAX_TERMS = 10000, // larger arguments are not searched
    SQUARE_MAX_CALLS = 64,    // searches (levels and signs) in one
};

/* f = sqrt(P) in Q(vars), the relations ignored: 1 when P is a square */
static int square_plain(RatFun f, const RatFun P, const Ring *r)
{
    if (ratfun_is_zero(P, r)) {
        ratfun_zero(f, r);
        return 1;
    }
    int ok = 0;
    fmpz_t cn, cd, s;
    fmpz_init(cn);
    fmpz_init(cd);
    fmpz_init(s);
    fmpz_mpoly_t pn, pd;
    fmpz_mpoly_init(pn, r->ctx);
    fmpz_mpoly_init(pd, r->ctx);
    /* P = (cn/cd) * pn/pd, pn and pd primitive with positive leading
     * coefficients: squares exactly when cn*cd is a square and pn, pd are */
    _fmpz_vec_content(cn, P->num->coeffs, P->num->length);
    _fmpz_vec_content(cd, P->den->coeffs, P->den->length);
    fmpz_mpoly_scalar_divexact_fmpz(pn, P->num, cn, r->ctx);
    fmpz_mpoly_scalar_divexact_fmpz(pd, P->den, cd, r->ctx);
    if (fmpz_sgn(pn->coeffs) < 0) {
        fmpz_mpoly_neg(pn, pn, r->ctx);
        fmpz_neg(cn, cn);
    }
    fmpz_mul(s, cn, cd);
    if (fmpz_sgn(s) > 0 && fmpz_is_square(s) &&
        fmpz_mpoly_sqrt(pn, pn, r->ctx) && fmpz_mpoly_sqrt(pd, pd, r->ctx)) {
        /* sqrt(cn/cd) = sqrt(cn*cd)/cd */
        fmpz_sqrt(s, s);
        fmpz_mpoly_scalar_mul_fmpz(f->num, pn, s, r->ctx);
        fmpz_mpoly_scalar_mul_fmpz(f->den, pd, cd, r->ctx);
        ratfun_canonicalise(f, r);
        ok = 1;
    }
    fmpz_mpoly_clear(pd, r->ctx);
    fmpz_mpoly_clear(pn, r->ctx);
    fmpz_clear(s);
    fmpz_clear(cd);
    fmpz_clear(cn);
    return ok;
}

/* the last kernel before top with a quadratic relation that x uses, or -1;
 * -2 when x uses one in a way the search does not handle (its square in
 * the numerator, or any power in the denominator) */
static slong last_quadratic(const Kernels *K, const RatFun x, slong top)
{
    const Ring *r = K->r;
    for (slong i = top - 1; i >= 0; i--) {
        const Kernel *k = &K->k[i];
        if (k->deg != 2 || !kernel_rf_has(x, k->var, r))
            continue;
        if (kernel_poly_has(x->den, k->var, r) ||
            fmpz_mpoly_degree_si(x->num, k->var, r->ctx) > 1)
            return -2;
        return i;
    }
    return -1;
}

/* x = the coefficient of var^e in num(P), over den(P) */
static void coeff_of(RatFun x, const RatFun P, slong var, ulong e,
                     const Ring *r)
{
    fmpz_mpoly_get_coeff_vars_ui(x->num, P->num, &var, &e, 1, r->ctx);
    fmpz_mpoly_set(x->den, P->den, r->ctx);
    ratfun_canonicalise(x, r);
}

static int square_search(Kernels *K, RatFun f, const RatFun P, slong top,
                         int *work);

/* 1 when f^2 reduces to P exactly (the check of every candidate) */
static int squares_to(Kernels *K, const RatFun f, const RatFun P)
{
    RatFun s;
    ratfun_init(s, K->r);
    ratfun_mul(s, f, f, K->r);
    int rc = kernel_reduce(K, s);
    if (rc == 0)
        rc = ratfun_equal(s, P, K->r);
    ratfun_clear(s, K->r);
    return rc;
}

/* one candidate of the denesting of P = A + B v (v kernel i, v^2 = R) for
 * the root m of the norm: g^2 = (A + m)/2, h = B/(2g); or, when that is
 * 0, g = 0 and h^2 = A/R.  1 (f = g + h v squares to P), 0, or an error */
static int denest_one(Kernels *K, RatFun f, const RatFun P, const RatFun A,
                      const RatFun B, const RatFun m, slong i, int *work)
{
    const Ring *r = K->r;
    const Kernel *k = &K->k[i];
    RatFun G, g, h;
    ratfun_init(G, r);
    ratfun_init(g, r);
    ratfun_init(h, r);
    ratfun_add(G, A, m, r);
    ratfun_set_si(h, 2, r);
    ratfun_div(G, G, h, r);
    int rc = kernel_reduce(K, G);
    if (rc == 0 && ratfun_is_zero(G, r)) {
        /* g = 0: P = h^2 R */
        rc = ratfun_div(G, A, k->rel, r) == 0 ? kernel_reduce(K, G) : 1;
        if (rc == 0)
            rc = square_search(K, h, G, i, work);
        if (rc == 1) {
            ratfun_gen(f, k->var, r);
            ratfun_mul(f, f, h, r);
        } else if (rc > 0) {
            rc = 0;
        }
    } else if (rc == 0) {
        rc = square_search(K, g, G, i, work);
        if (rc == 1) {
            ratfun_mul_si(h, g, 2, r);
            rc = ratfun_div(h, B, h, r) == 0 ? kernel_reduce(K, h) : 1;
            if (rc == 0) {
                ratfun_gen(f, k->var, r);
                ratfun_mul(f, f, h, r);
                ratfun_add(f, f, g, r);
                rc = kernel_reduce(K, f);
            }
            rc = rc == 0 ? 1 : rc > 0 ? 0 : rc;
        }
    }
    if (rc == 1)
        rc = squares_to(K, f, P);
    ratfun_clear(h, r);
    ratfun_clear(g, r);
    ratfun_clear(G, r);
    return rc;
}

/* P = A + B v with v kernel i: the norm's root m, then both signs of it */
static int square_denest(Kernels *K, RatFun f, const RatFun P, slong i,
                         int *work)
{
    const Ring *r = K->r;
    const Kernel *k = &K->k[i];
    RatFun A, B, N, m;
    ratfun_init(A, r);
    ratfun_init(B, r);
    ratfun_init(N, r);
    ratfun_init(m, r);
    coeff_of(A, P, k->var, 0, r);
    coeff_of(B, P, k->var, 1, r);
    /* N = A^2 - B^2 R, a square m^2 one level down */
    ratfun_mul(N, B, B, r);
    ratfun_mul(N, N, k->rel, r);
    ratfun_mul(m, A, A, r);
    ratfun_sub(N, m, N, r);
    int rc = kernel_reduce(K, N);
    if (rc == 0)
        rc = kernel_guard(K, N->num);
    if (rc == 0)
        rc = square_search(K, m, N, i, work);
    if (rc == 1) {
        rc = denest_one(K, f, P, A, B, m, i, work);
        if (rc == 0) {
            ratfun_neg(m, m, r);
            rc = denest_one(K, f, P, A, B, m, i, work);
        }
    }
    ratfun_clear(m, r);
    ratfun_clear(N, r);
    ratfun_clear(B, r);
    ratfun_clear(A, r);
    return rc;
}

/* P = h^2 R for the relation R of a quadratic kernel v before top
 * (f = h v): 1 - sin^2 = cos^2, x = sqrt(x)^2 inside a denesting
 * ((sqrt(x) - sqrt(y))^2 needs g^2 = x).  Tried where R divides P (a
 * number R: where P is a rational square once divided by it) */
static int square_by_relation(Kernels *K, RatFun f, const RatFun P, slong top,
                              int *work)
{
    const Ring *r = K->r;
    RatFun Q, h;
    ratfun_init(Q, r);
    ratfun_init(h, r);
    fmpz_mpoly_t t, u;
    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    int rc = 0;
    for (slong i = top - 1; i >= 0 && rc == 0; i--) {
        const Kernel *k = &K->k[i];
        if (k->deg != 2 || k->fn == KF_SIGN)
            continue;
        if (ratfun_is_constant(k->rel, r)) {
            /* sqrt(2): P/2 a rational square */
            if (ratfun_div(Q, P, k->rel, r) != 0 || !square_plain(h, Q, r))
                continue;
        } else {
            /* R divides P modulo the relations: P/R reduced has no new
             * denominator ((w c - q s)(1 + 2 s c) reduced is no multiple
             * of w c - q s as a polynomial) */
            if (ratfun_div(Q, P, k->rel, r) != 0)
                continue;
            rc = kernel_reduce(K, Q);
            if (rc != 0)
                break;
            fmpz_mpoly_mul(t, P->den, k->rel->den, r->ctx);
            if (!fmpz_mpoly_divides(u, t, Q->den, r->ctx))
                continue;
            rc = square_search(K, h, Q, top, work);
            if (rc != 1) {
                rc = rc < 0 ? rc : 0;
                continue;
            }
        }
        ratfun_gen(f, k->var, r);
        ratfun_mul(f, f, h, r);
        rc = kernel_reduce(K, f);
        if (rc == 0)
            rc = squares_to(K, f, P);
    }
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(t, r->ctx);
    ratfun_clear(h, r);
    ratfun_clear(Q, r);
    return rc;
}

/* f with f^2 = P modulo the relations of the kernels before top: 1 (found),
 * 0 (none found), or an error of the guard.  Without a quadratic kernel in
 * P: a square of the rational functions; with one: the denesting by the
 * last; then P = h^2 R for a relation R. */
static int square_search(Kernels *K, RatFun f, const RatFun P, slong top,
                         int *work)
{
    if (--*work < 0 || P->num->length + P->den->length > SQUARE_MAX_TERMS)
        return 0;
    int rc = kernel_guard(K, NULL);
    if (rc != 0)
        return rc;
    slong i = last_quadratic(K, P, top);
    if (i == -2)
        return 0;
    if (i == -1)
        rc = square_plain(f, P, K->r);
    else
        rc = square_denest(K, f, P, i, work);
    if (rc == 0)
        rc = square_by_relation(K, f, P, top, work);
    return rc;
}

/* 1 when f uses a root (sqrt, root) that x does not: f^2 = x holds only
 * where that root is real, which x does not promise (t = sqrt(t)^2, but
 * sqrt(t*u) is not sqrt(t)*sqrt(u)) */
static int adds_root(const Kernels *K, const RatFun f, const RatFun x)
{
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if ((k->fn == KF_SQRT || k->fn == KF_ROOT) &&
            kernel_rf_has(f, k->var, K->r) && !kernel_rf_has(x, k->var, K->r))
            return 1;
    }
    return 0;
}

/* 1 when the polynomial p is a square f^2 modulo the relations (f set),
 * 0, or an error of the guard */
static int poly_square(Kernels *K, RatFun f, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    if (fmpz_mpoly_is_fmpz(p, r->ctx))
        return 0;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    int work = SQUARE_MAX_CALLS;
    int rc = kernel_reduce(K, x);
    if (rc == 0)
        rc = square_search(K, f, x, K->n, &work);
    if (rc == 1 && adds_root(K, f, x))
        rc = 0;
    ratfun_clear(x, r);
    return rc;
}

/* 1 when x = w g^2 modulo the relations for a root w = sqrt(R) of x
 * (so x >= 0): x w / R is a square; 2 when x = -w g^2 (x <= 0).  |W (sqrt(u) -
 * sqrt(v))^2| = the same, though reduced the product has no factor W. */
static int root_times_square(Kernels *K, const RatFun x)
{
    enum { ROOTS_TRIED = 4 };
    const Ring *r = K->r;
    RatFun q, g;
    ratfun_init(q, r);
    ratfun_init(g, r);
    int rc = 0, tried = 0;
    for (slong i = K->n - 1; i >= 0 && rc == 0 && tried < ROOTS_TRIED; i--) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_SQRT || !kernel_rf_has(x, k->var, r))
            continue;
        tried++;
        ratfun_gen(q, k->var, r);
        ratfun_mul(q, q, x, r);
        if (ratfun_div(q, q, k->rel, r) != 0)
            continue;
        rc = kernel_reduce(K, q);
        for (int sg = 1; rc == 0 && sg >= -1; sg -= 2) {
            if (sg < 0)
                ratfun_neg(q, q, r);
            int work = SQUARE_MAX_CALLS;
            rc = square_search(K, g, q, K->n, &work);
            if (rc == 1 && adds_root(K, g, q))
                rc = 0;
            if (rc == 1 && sg < 0)
                rc = 2;
        }
    }
    ratfun_clear(g, r);
    ratfun_clear(q, r);
    return rc;
}

/* the sign of the polynomial p as far as it is decided: kernel_sign, or
 * a square modulo the relations (never negative), or minus one, or a root
 * times a square: *s = 1, -1 or 0 (unknown); 0 or an error */
static int poly_abs_sign(Kernels *K, int *s, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    RatFun x, g;
    ratfun_init(x, r);
    ratfun_init(g, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    int rc = 0;
    *s = kernel_sign(K, x);
    *s = *s > 0 ? 1 : *s < 0 ? -1 : 0;
    if (*s == 0 && !fmpz_mpoly_is_fmpz(p, r->ctx)) {
        rc = poly_square(K, g, x->num);
        if (rc == 1) {
            *s = 1;
        } else if (rc == 0) {
            fmpz_mpoly_t q;
            fmpz_mpoly_init(q, r->ctx);
            fmpz_mpoly_neg(q, x->num, r->ctx);
            rc = poly_square(K, g, q);
            *s = rc == 1 ? -1 : 0;
            fmpz_mpoly_clear(q, r->ctx);
        }
        if (rc == 0) {
            rc = root_times_square(K, x);
            if (rc > 0)
                *s = rc == 1 ? 1 : -1;
        }
        rc = rc < 0 ? rc : 0;
    }
    ratfun_clear(g, r);
    ratfun_clear(x, r);
    return rc;
}

/* The signs a square root still owes: sqrt(f^2 g) = |f| sqrt(g) =
 * f sgn(f) sqrt(g).  They are collected over the whole root and decided
 * at once, since a square may come out in pieces that are not squares
 * (sin(t) * (sin(t) (sqrt(x) - sqrt(y))^2 ...)), then one by one. */
typedef struct SignDebt {
    slong n, alloc;
    fmpz_mpoly_struct *p; // owned: the polynomials f
    unsigned char *split; // 1: decided by its factors when alone
} SignDebt;

static void debt_init(SignDebt *d)
{
    d->n = d->alloc = 0;
    d->p = NULL;
    d->split = NULL;
}

static void debt_clear(SignDebt *d, const Ring *r)
{
    for (slong i = 0; i < d->n; i++)
        fmpz_mpoly_clear(d->p + i, r->ctx);
    pc_free(d->p);
    pc_free(d->split);
    debt_init(d);
}

static void debt_push(SignDebt *d, const fmpz_mpoly_t p, int split,
                      const Ring *r)
{
    /* a positive number owes nothing; a negative one stays (-1) */
    if (fmpz_mpoly_is_fmpz(p, r->ctx) &&
        (fmpz_mpoly_is_zero(p, r->ctx) || fmpz_sgn(p->coeffs) > 0))
        return;
    if (d->n == d->alloc) {
        d->alloc = d->alloc ? 2 * d->alloc : 4;
        d->p = pc_xrealloc(d->p, sizeof *d->p * (size_t)d->alloc);
        d->split = pc_xrealloc(d->split, (size_t)d->alloc);
    }
    fmpz_mpoly_init(d->p + d->n, r->ctx);
    fmpz_mpoly_set(d->p + d->n, p, r->ctx);
    d->split[d->n++] = (unsigned char)split;
}

/* acc *= sgn(p) for one polynomial: +-1 where poly_abs_sign decides it,
 * else sign(p) */
static int mul_sign_whole(Kernels *K, RatFun acc, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    int s = 0, rc = poly_abs_sign(K, &s, p);
    if (rc != 0)
        return rc;
    if (s < 0)
        ratfun_neg(acc, acc, r);
    if (s != 0)
        return 0;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    rc = kernel_apply(K, x, KF_SIGN, x, NULL);
    if (rc == 0)
        ratfun_mul(acc, acc, x, r);
    ratfun_clear(x, r);
    return rc;
}

/* acc *= sgn(p), decided whole, else factor by factor (irreducible
 * factors where affordable, else the variables of the term content and
 * the rest): sgn((1 + sqrt(u))(a + cos(t))) = sign(a + cos(t)) */
static int mul_sign_split(Kernels *K, RatFun acc, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    int s = 0, rc = poly_abs_sign(K, &s, p);
    if (rc != 0 || s != 0) {
        if (s < 0)
            ratfun_neg(acc, acc, r);
        return rc;
    }
    fmpz_mpoly_factor_t fac;
    fmpz_mpoly_factor_init(fac, r->ctx);
    if (ring_factor_affordable(p, r) && ring_factor(fac, p, r)) {
        if (fmpz_sgn(fac->constant) < 0)
            ratfun_neg(acc, acc, r);
        for (slong i = 0; i < fac->num && rc == 0; i++)
            if (fmpz_get_si(fac->exp + i) % 2)
                rc = mul_sign_whole(K, acc, fac->poly + i);
    } else {
        /* p = M q, M the monomial content */
        fmpz_mpoly_t M, q, v;
        fmpz_mpoly_init(M, r->ctx);
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_init(v, r->ctx);
        fmpz_mpoly_term_content(M, p, r->ctx);
        if (!fmpz_mpoly_divides(q, p, M, r->ctx)) {
            fmpz_mpoly_one(M, r->ctx);
            fmpz_mpoly_set(q, p, r->ctx);
        }
        slong nv = r->ctx->minfo->nvars;
        for (slong i = 0; i < nv && rc == 0; i++) {
            if (fmpz_mpoly_degree_si(M, i, r->ctx) % 2 == 0)
                continue;
            fmpz_mpoly_gen(v, i, r->ctx);
            rc = mul_sign_whole(K, acc, v);
        }
        if (rc == 0)
            rc = mul_sign_whole(K, acc, q);
        fmpz_mpoly_clear(v, r->ctx);
        fmpz_mpoly_clear(q, r->ctx);
        fmpz_mpoly_clear(M, r->ctx);
    }
    fmpz_mpoly_factor_clear(fac, r->ctx);
    return rc;
}

/* acc *= the signs owed: +-1 when the product of the debts is decided
 * (a square, minus one, a root times one), else each on its own */
static int debt_settle(Kernels *K, RatFun acc, const SignDebt *d)
{
    const Ring *r = K->r;
    int rc = 0;
    if (d->n >= 2) {
        double len = 1;
        for (slong i = 0; i < d->n; i++)
            len *= (double)d->p[i].length;
        if (len <= SQUARE_MAX_TERMS) {
            fmpz_mpoly_t prod;
            fmpz_mpoly_init(prod, r->ctx);
            fmpz_mpoly_one(prod, r->ctx);
            for (slong i = 0; i < d->n; i++)
                fmpz_mpoly_mul(prod, prod, d->p + i, r->ctx);
            int s = 0;
            rc = poly_abs_sign(K, &s, prod);
            fmpz_mpoly_clear(prod, r->ctx);
            if (rc == 0 && s != 0) {
                if (s < 0)
                    ratfun_neg(acc, acc, r);
                return kernel_reduce(K, acc);
            }
        }
    }
    for (slong i = 0; i < d->n && rc == 0; i++)
        rc = d->split[i] ? mul_sign_split(K, acc, d->p + i)
                         : mul_sign_whole(K, acc, d->p + i);
    if (rc == 0)
        rc = kernel_reduce(K, acc);
    return rc;
}

/* acc *= |f|^e = f^e sgn(f)^e, the sign owed (e odd) */
static int mul_abs_pow(Kernels *K, RatFun acc, const RatFun f, slong e,
                       SignDebt *debt)
{
    RatFun x;
    ratfun_init(x, K->r);
    int rc = ratfun_pow_si(x, f, e, K->r) == 0 ? 0 : KERNEL_EZERO;
    if (rc == 0) {
        ratfun_mul(acc, acc, x, K->r);
        if (e % 2) {
            debt_push(debt, f->num, 1, K->r);
            debt_push(debt, f->den, 1, K->r);
        }
    }
    ratfun_clear(x, K->r);
    return rc;
}

/* the part p (numerator, e = 1, or denominator, e = -1) of the square-free
 * rest of a square root's argument: when p, or some of its irreducible
 * factors, is a square f^2 modulo the relations, acc *= |f|^e and the
 * square leaves p (rest = the product of what is left) */
static int squares_out_part(Kernels *K, RatFun acc, fmpz_mpoly_t p, slong e,
                            SignDebt *debt)
{
    const Ring *r = K->r;
    RatFun f;
    ratfun_init(f, r);
    int rc = poly_square(K, f, p);
    if (rc == 1) {
        rc = mul_abs_pow(K, acc, f, e, debt);
        fmpz_mpoly_one(p, r->ctx);
    } else if (rc == 0) {
        /* p = -f^2 (s^2 - 1 = -cos^2): the sign stays under the root */
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_neg(q, p, r->ctx);
        rc = poly_square(K, f, q);
        if (rc == 1) {
            rc = mul_abs_pow(K, acc, f, e, debt);
            fmpz_mpoly_set_si(p, -1, r->ctx);
        }
        fmpz_mpoly_clear(q, r->ctx);
    }
    fmpz_mpoly_factor_t fac;
    fmpz_mpoly_factor_init(fac, r->ctx);
    if (rc == 0 && ring_factor_affordable(p, r) && ring_factor(fac, p, r) &&
        fac->num > 1) {
        /* p = c * prod f_i^e_i: the factors that are squares leave */
        fmpz_mpoly_t left, pw;
        fmpz_mpoly_init(left, r->ctx);
        fmpz_mpoly_init(pw, r->ctx);
        fmpz_mpoly_set_fmpz(left, fac->constant, r->ctx);
        int any = 0;
        for (slong i = 0; i < fac->num && rc >= 0; i++) {
            slong ei = fmpz_get_si(fac->exp + i);
            rc = poly_square(K, f, fac->poly + i);
            if (rc == 0) {
                /* factors have a positive leading coefficient: -(2 + 2 cos
                 * - sin^2) is sin^2 - 2 cos - 2; its sign joins c */
                fmpz_mpoly_neg(pw, fac->poly + i, r->ctx);
                rc = poly_square(K, f, pw);
                if (rc == 1 && ei % 2)
                    fmpz_mpoly_neg(left, left, r->ctx);
            }
            if (rc == 1) {
                rc = mul_abs_pow(K, acc, f, e * ei, debt);
                any = 1;
                continue;
            }
            fmpz_mpoly_pow_ui(pw, fac->poly + i, (ulong)ei, r->ctx);
            fmpz_mpoly_mul(left, left, pw, r->ctx);
        }
        if (rc == 0 && any)
            fmpz_mpoly_swap(p, left, r->ctx);
        fmpz_mpoly_clear(pw, r->ctx);
        fmpz_mpoly_clear(left, r->ctx);
    }
    fmpz_mpoly_factor_clear(fac, r->ctx);
    ratfun_clear(f, r);
    return rc;
}

/* rest = the square-free part of a square root's argument (kernel_sqrt_poly):
 * the squares modulo the relations in its numerator and denominator leave
 * the root as |f| (acc *= |f|, or /= for the denominator) */
static int squares_out(Kernels *K, RatFun acc, RatFun rest, SignDebt *debt)
{
    if (K->nrel == 0)
        return 0;
    int rc = squares_out_part(K, acc, rest->num, 1, debt);
    if (rc == 0)
        rc = squares_out_part(K, acc, rest->den, -1, debt);
    if (rc == 0)
        ratfun_canonicalise(rest, K->r);
    return rc;
}

/* sqrt(x) for a non-constant x = n/d: squares pulled out as |f|^k =
 * f^k sign(f)^k, the positive numeric content as a surd */
int kernel_sqrt_poly(Kernels *K, RatFun res, const RatFun x)
{
    const Ring *r = K->r;
    RatFun acc, rest, t;
    ratfun_init(acc, r);
    ratfun_init(rest, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    ratfun_one(rest, r);
    fmpq_t content;
    fmpq_init(content);
    fmpq_one(content);
    SignDebt debt;
    debt_init(&debt);
    int rc = 0;
    for (int part = 0; part < 2 && rc == 0; part++) {
        const fmpz_mpoly_struct *P = part ? x->den : x->num;
        fmpz_mpoly_factor_t f;
        fmpz_mpoly_factor_init(f, r->ctx);
        if (!ring_factor_compact(f, P, 0, r)) {
            /* cannot split: keep the polynomial whole */
            fmpz_mpoly_factor_clear(f, r->ctx);
            mul_poly_pow(rest, P, part ? -1 : 1, r);
            continue;
        }
        fmpq_t k;
        fmpq_init(k);
        fmpq_set_fmpz_frac(k, f->constant, f->constant_den);
        if (part)
            fmpq_div(content, content, k);
        else
            fmpq_mul(content, content, k);
        fmpq_clear(k);
        for (slong i = 0; i < f->num && rc == 0; i++) {
            slong e = fmpz_get_si(f->exp + i), h = e / 2;
            if (e % 2)
                mul_poly_pow(rest, f->poly + i, part ? -1 : 1, r);
            if (h == 0)
                continue;
            /* |f|^h = f^h * sign(f)^h, sign(f) = +-1 where it is known */
            mul_poly_pow(acc, f->poly + i, part ? -h : h, r);
            int fs = kernel_sign_poly(K, f->poly + i);
            if (h % 2 && fs < 0)
                ratfun_neg(acc, acc, r);
            if (h % 2 && fs == 0)
                debt_push(&debt, f->poly + i, 0, r); /* owed: below */
        }
        fmpz_mpoly_factor_clear(f, r->ctx);
    }
    if (rc == 0) {
        /* the numeric content: sqrt(|c|), its sign stays under the root */
        if (fmpq_sgn(content) < 0) {
            fmpq_neg(content, content);
            ratfun_neg(rest, rest, r);
        }
        rc = kernel_sqrt_num(K, t, content);
        if (rc == 0)
            ratfun_mul(acc, acc, t, r);
    }
    if (rc == 0)
        rc = squares_out(K, acc, rest, &debt);
    if (rc == 0)
        rc = debt_settle(K, acc, &debt);
    if (rc == 0) {
        fmpq_t c;
        fmpq_init(c);
        if (ratfun_get_fmpq(c, rest, r)) {
            /* only -1 can remain: sqrt of a negative number */
            if (fmpq_sgn(c) < 0) {
                K->why = "square root of a negative number";
                rc = KERNEL_EDOMAIN;
            }
        } else {
            rc = kernels_intern(K, t, KF_SQRT, rest, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
        }
        fmpq_clear(c);
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    debt_clear(&debt, r);
    fmpq_clear(content);
    ratfun_clear(t, r);
    ratfun_clear(rest, r);
    ratfun_clear(acc, r);
    return rc;
}
