/*
 * ratfun.c - exact multivariate rational functions over Q.
 *
 * A RatFun is a pair of fmpz_mpoly kept canonical (coprime, lc(den) > 0,
 * zero = 0/1), following the design of FLINT 3's fmpz_mpoly_q, which the
 * installed FLINT 2.9 lacks.  Canonical form makes equality a comparison of
 * polynomials and keeps sizes down, but the gcd that maintains it is by far
 * the most expensive step, so every operation first looks for a reason to
 * skip it:
 *   - an operand with denominator 1, or an integer, needs at most an integer
 *     content gcd (cofactors() below);
 *   - a + b with equal denominators needs one gcd against that denominator;
 *     with a denominator 1 on either side, none at all;
 *   - a * b cancels crosswise, gcd(xn, yd) and gcd(yn, xd), which are gcds
 *     of smaller polynomials than gcd(xn*yn, xd*yd) and leave nothing to
 *     cancel afterwards (Knuth, TAOCP 4.5.1, for fractions).
 * Results are computed into fresh polynomials when an input aliases the
 * result, then swapped in; FLINT objects are never struct-copied.
 */
#define _DEFAULT_SOURCE // lgamma_r (lgamma writes the process-wide signgam)
#include "compiler/ratfun.h"

#include <stdlib.h>

#include "base/mem.h"

#include <flint/fmpz_poly.h>
#include <flint/fmpz_vec.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* lc > 0 in the ring's ordering: terms are stored leading term first */
static int lc_is_negative(const fmpz_mpoly_t p)
{
    return p->length > 0 && fmpz_sgn(p->coeffs + 0) < 0;
}

/* The one variable that a and b (non-constant) together use, or -1 when
 * they use several.  Schemes with one parameter make every gcd univariate,
 * and FLINT's dense fmpz_poly gcd is several times faster there than the
 * general fmpz_mpoly one (about 0.2 against 1 microsecond at degree 3). */
static slong common_var(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                        const Ring *r)
{
    slong da[8], db[8], v = -1;

    if (r->nvars <= 1)
        return 0;
    if (r->nvars > 8 || !fmpz_mpoly_degrees_fit_si(a, r->ctx) ||
        !fmpz_mpoly_degrees_fit_si(b, r->ctx))
        return -1;
    fmpz_mpoly_degrees_si(da, a, r->ctx);
    fmpz_mpoly_degrees_si(db, b, r->ctx);
    for (slong i = 0; i < r->nvars; i++) {
        if (da[i] <= 0 && db[i] <= 0)
            continue;
        if (v >= 0)
            return -1;
        v = i;
    }
    return v;
}


/* g = gcd of the integer contents of a and b (positive) */
static void contents_gcd(fmpz_t g, const fmpz_mpoly_t a, const fmpz_mpoly_t b)
{
    fmpz_t h;
    fmpz_init(h);
    _fmpz_vec_content(g, a->coeffs, a->length);
    _fmpz_vec_content(h, b->coeffs, b->length);
    fmpz_gcd(g, g, h);
    fmpz_clear(h);
}

/* Univariate cofactors through fmpz_poly: 1 if g != 1 (ta, tb, tg set),
 * 0 if g = 1, -1 if the conversion is not possible (use fmpz_mpoly). */
static int univar_cofactors(fmpz_mpoly_t ta, fmpz_mpoly_t tb, fmpz_mpoly_t tg,
                            const fmpz_mpoly_t a, const fmpz_mpoly_t b, slong v,
                            const Ring *r)
{
    int st = -1;
    fmpz_poly_t A, B, G, Q;

    fmpz_poly_init(A);
    fmpz_poly_init(B);
    fmpz_poly_init(G);
    fmpz_poly_init(Q);
    if (!fmpz_mpoly_get_fmpz_poly(A, a, v, r->ctx) ||
        !fmpz_mpoly_get_fmpz_poly(B, b, v, r->ctx))
        goto cleanup;
    fmpz_poly_gcd(G, A, B); /* lc(G) > 0 */
    if (fmpz_poly_is_one(G)) {
        st = 0;
        goto cleanup;
    }
    if (!fmpz_poly_divides(Q, A, G))
        goto cleanup;
    fmpz_mpoly_set_fmpz_poly(ta, Q, v, r->ctx);
    if (!fmpz_poly_divides(Q, B, G))
        goto cleanup;
    fmpz_mpoly_set_fmpz_poly(tb, Q, v, r->ctx);
    fmpz_mpoly_set_fmpz_poly(tg, G, v, r->ctx);
    st = 1;
cleanup:
    fmpz_poly_clear(Q);
    fmpz_poly_clear(G);
    fmpz_poly_clear(B);
    fmpz_poly_clear(A);
    return st;
}

/* Cofactors of a and b by g = gcd(a, b) (lc(g) > 0): on return *pa = a/g,
 * *pb = b/g and *pg = g, or *pg = NULL when g = 1.  When g = 1 the pointers
 * are the inputs themselves, which spares copies on the frequent coprime
 * path; otherwise they point at ta, tb, tg.  a and b are non-zero.  Units
 * and integers take an integer content gcd instead of a polynomial one,
 * univariate pairs a dense fmpz_poly gcd (univar_cofactors).  If
 * FLINT's gcd fails (exponent overflow, practically unreachable), g = 1 is
 * reported: the result stays correct, only not fully reduced. */
static void cofactors(const fmpz_mpoly_struct **pa,
                      const fmpz_mpoly_struct **pb,
                      const fmpz_mpoly_struct **pg, fmpz_mpoly_t ta,
                      fmpz_mpoly_t tb, fmpz_mpoly_t tg, const fmpz_mpoly_t a,
                      const fmpz_mpoly_t b, const Ring *r)
{
    *pa = a;
    *pb = b;
    *pg = NULL;
    if (fmpz_mpoly_is_one(a, r->ctx) || fmpz_mpoly_is_one(b, r->ctx))
        return;
    if (fmpz_mpoly_is_fmpz(a, r->ctx) || fmpz_mpoly_is_fmpz(b, r->ctx)) {
        fmpz_t g;
        fmpz_init(g);
        contents_gcd(g, a, b);
        if (!fmpz_is_one(g)) {
            fmpz_mpoly_scalar_divexact_fmpz(ta, a, g, r->ctx);
            fmpz_mpoly_scalar_divexact_fmpz(tb, b, g, r->ctx);
            fmpz_mpoly_set_fmpz(tg, g, r->ctx);
            *pa = ta;
            *pb = tb;
            *pg = tg;
        }
        fmpz_clear(g);
        return;
    }
    {
        slong v = common_var(a, b, r);
        int u = v >= 0 ? univar_cofactors(ta, tb, tg, a, b, v, r) : -1;
        if (u == 0)
            return;
        if (u == 1) {
            *pa = ta;
            *pb = tb;
            *pg = tg;
            return;
        }
    }
    if (!fmpz_mpoly_gcd_cofactors(tg, ta, tb, a, b, r->ctx))
        return;
    if (fmpz_mpoly_is_one(tg, r->ctx))
        return;
    *pa = ta;
    *pb = tb;
    *pg = tg;
}

/* Divides num and den by their gcd in place and fixes the sign of den.
 * den is non-zero. */
static void reduce(fmpz_mpoly_t num, fmpz_mpoly_t den, const Ring *r)
{
    const fmpz_mpoly_struct *pn, *pd, *pg;
    fmpz_mpoly_t tn, td, tg;

    if (fmpz_mpoly_is_zero(num, r->ctx)) {
        fmpz_mpoly_one(den, r->ctx);
        return;
    }
    fmpz_mpoly_init(tn, r->ctx);
    fmpz_mpoly_init(td, r->ctx);
    fmpz_mpoly_init(tg, r->ctx);
    cofactors(&pn, &pd, &pg, tn, td, tg, num, den, r);
    if (pg != NULL) {
        fmpz_mpoly_swap(num, tn, r->ctx);
        fmpz_mpoly_swap(den, td, r->ctx);
    }
    if (lc_is_negative(den)) {
        fmpz_mpoly_neg(num, num, r->ctx);
        fmpz_mpoly_neg(den, den, r->ctx);
    }
    fmpz_mpoly_clear(tg, r->ctx);
    fmpz_mpoly_clear(td, r->ctx);
    fmpz_mpoly_clear(tn, r->ctx);
}

int ratfun_poly_gcd(fmpz_mpoly_t g, const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                    const Ring *r)
{
    int ok = 1;

    if (fmpz_mpoly_is_zero(a, r->ctx) || fmpz_mpoly_equal(a, b, r->ctx)) {
        fmpz_mpoly_set(g, b, r->ctx);
    } else if (fmpz_mpoly_is_zero(b, r->ctx)) {
        fmpz_mpoly_set(g, a, r->ctx);
    } else if (fmpz_mpoly_is_fmpz(a, r->ctx) || fmpz_mpoly_is_fmpz(b, r->ctx)) {
        fmpz_t c;
        fmpz_init(c);
        contents_gcd(c, a, b);
        fmpz_mpoly_set_fmpz(g, c, r->ctx);
        fmpz_clear(c);
        return 1;
    } else {
        slong v = common_var(a, b, r);
        fmpz_poly_t A, B, G;
        int done = 0;
        if (v >= 0) {
            fmpz_poly_init(A);
            fmpz_poly_init(B);
            fmpz_poly_init(G);
            if (fmpz_mpoly_get_fmpz_poly(A, a, v, r->ctx) &&
                fmpz_mpoly_get_fmpz_poly(B, b, v, r->ctx)) {
                fmpz_poly_gcd(G, A, B);
                fmpz_mpoly_set_fmpz_poly(g, G, v, r->ctx);
                done = 1;
            }
            fmpz_poly_clear(G);
            fmpz_poly_clear(B);
            fmpz_poly_clear(A);
        }
        if (!done && !fmpz_mpoly_gcd(g, a, b, r->ctx)) {
            fmpz_mpoly_one(g, r->ctx);
            ok = 0;
        }
    }
    if (lc_is_negative(g))
        fmpz_mpoly_neg(g, g, r->ctx);
    return ok;
}

int ratfun_canonicalise(RatFun x, const Ring *r)
{
    if (fmpz_mpoly_is_zero(x->den, r->ctx))
        return RATFUN_EDIVZERO;
    reduce(x->num, x->den, r);
    return RATFUN_OK;
}

/* ---- basic management ------------------------------------------------- */

void ratfun_init(RatFun x, const Ring *r)
{
    fmpz_mpoly_init(x->num, r->ctx);
    fmpz_mpoly_init(x->den, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
}

void ratfun_clear(RatFun x, const Ring *r)
{
    fmpz_mpoly_clear(x->num, r->ctx);
    fmpz_mpoly_clear(x->den, r->ctx);
}

void ratfun_swap(RatFun x, RatFun y, const Ring *r)
{
    fmpz_mpoly_swap(x->num, y->num, r->ctx);
    fmpz_mpoly_swap(x->den, y->den, r->ctx);
}

void ratfun_set(RatFun res, const RatFun x, const Ring *r)
{
    if (res == x)
        return;
    fmpz_mpoly_set(res->num, x->num, r->ctx);
    fmpz_mpoly_set(res->den, x->den, r->ctx);
}

void ratfun_zero(RatFun res, const Ring *r)
{
    fmpz_mpoly_zero(res->num, r->ctx);
    fmpz_mpoly_one(res->den, r->ctx);
}

void ratfun_one(RatFun res, const Ring *r)
{
    fmpz_mpoly_one(res->num, r->ctx);
    fmpz_mpoly_one(res->den, r->ctx);
}

void ratfun_set_si(RatFun res, slong c, const Ring *r)
{
    fmpz_mpoly_set_si(res->num, c, r->ctx);
    fmpz_mpoly_one(res->den, r->ctx);
}

/* fmpq_t values are canonical by FLINT's convention: den > 0, coprime */
void ratfun_set_fmpq(RatFun res, const fmpq_t c, const Ring *r)
{
    fmpz_mpoly_set_fmpz(res->num, fmpq_numref(c), r->ctx);
    fmpz_mpoly_set_fmpz(res->den, fmpq_denref(c), r->ctx);
}

void ratfun_gen(RatFun res, slong var, const Ring *r)
{
    FLINT_ASSERT(var >= 0 && var < r->nvars);
    fmpz_mpoly_gen(res->num, var, r->ctx);
    fmpz_mpoly_one(res->den, r->ctx);
}

/* ---- predicates ------------------------------------------------------- */

int ratfun_is_zero(const RatFun x, const Ring *r)
{
    return fmpz_mpoly_is_zero(x->num, r->ctx);
}

int ratfun_is_one(const RatFun x, const Ring *r)
{
    return fmpz_mpoly_is_one(x->num, r->ctx) &&
           fmpz_mpoly_is_one(x->den, r->ctx);
}

int ratfun_is_constant(const RatFun x, const Ring *r)
{
    return fmpz_mpoly_is_fmpz(x->num, r->ctx) &&
           fmpz_mpoly_is_fmpz(x->den, r->ctx);
}

int ratfun_get_fmpq(fmpq_t c, const RatFun x, const Ring *r)
{
    fmpz_t n, d;

    if (!ratfun_is_constant(x, r))
        return 0;
    fmpz_init(n);
    fmpz_init(d);
    fmpz_mpoly_get_fmpz(n, x->num, r->ctx);
    fmpz_mpoly_get_fmpz(d, x->den, r->ctx);
    fmpq_set_fmpz_frac(c, n, d);
    fmpz_clear(d);
    fmpz_clear(n);
    return 1;
}

int ratfun_equal(const RatFun x, const RatFun y, const Ring *r)
{
    return fmpz_mpoly_equal(x->num, y->num, r->ctx) &&
           fmpz_mpoly_equal(x->den, y->den, r->ctx);
}

int ratfun_is_canonical(const RatFun x, const Ring *r)
{
    int ok = 0;
    fmpz_mpoly_t g;

    fmpz_mpoly_init(g, r->ctx);
    if (!fmpz_mpoly_is_canonical(x->num, r->ctx) ||
        !fmpz_mpoly_is_canonical(x->den, r->ctx))
        goto cleanup;
    if (fmpz_mpoly_is_zero(x->den, r->ctx) || lc_is_negative(x->den))
        goto cleanup;
    if (fmpz_mpoly_is_zero(x->num, r->ctx)) {
        ok = fmpz_mpoly_is_one(x->den, r->ctx);
        goto cleanup;
    }
    /* a failed gcd cannot vouch for the invariant */
    ok = fmpz_mpoly_gcd(g, x->num, x->den, r->ctx) &&
         fmpz_mpoly_is_one(g, r->ctx);
cleanup:
    fmpz_mpoly_clear(g, r->ctx);
    return ok;
}

RatFunStruct *ratfun_vec_init(slong len, const Ring *r)
{
    RatFunStruct *v = pc_xmalloc(sizeof(RatFunStruct) * (size_t)FLINT_MAX(len, 1));
    for (slong i = 0; i < len; i++)
        ratfun_init(v + i, r);
    return v;
}

void ratfun_vec_clear(RatFunStruct *v, slong len, const Ring *r)
{
    for (slong i = 0; i < len; i++)
        ratfun_clear(v + i, r);
    free(v);
}

int ratfun_depends_on(const RatFun x, slong var, const Ring *r)
{
    if (var < 0 || var >= r->nvars)
        return 0;
    return fmpz_mpoly_degree_si(x->num, var, r->ctx) > 0 ||
           fmpz_mpoly_degree_si(x->den, var, r->ctx) > 0;
}

slong ratfun_length(const RatFun x, const Ring *r)
{
    (void)r;
    return x->num->length + x->den->length;
}

/* ---- arithmetic ------------------------------------------------------- */

void ratfun_neg(RatFun res, const RatFun x, const Ring *r)
{
    fmpz_mpoly_neg(res->num, x->num, r->ctx);
    if (res != x)
        fmpz_mpoly_set(res->den, x->den, r->ctx);
}

/* num/den = xn/xd + sign*yn/yd for canonical, non-zero operands; num and den
 * must not alias the inputs.
 *   xd = yd:       (xn + yn)/xd, then one gcd against xd (none if xd = 1);
 *   xd = 1:        (xn*yd + yn)/yd is already coprime;
 *   g = gcd(xd, yd), a = xd/g, b = yd/g:
 *                  (xn*b + yn*a) / (a*b*g); a common factor of this num and
 *                  den can only divide g, so the final gcd is against g
 *                  (FLINT 3's fmpz_mpoly_q_add does the same). */
static void _ratfun_add(fmpz_mpoly_t num, fmpz_mpoly_t den,
                        const fmpz_mpoly_t xn, const fmpz_mpoly_t xd,
                        const fmpz_mpoly_t yn, const fmpz_mpoly_t yd, int sign,
                        const Ring *r)
{
    const fmpz_mpoly_struct *pa, *pb, *pg, *pn, *pt, *pu;
    fmpz_mpoly_t ta, tb, tg, t, tn, tt;

    fmpz_mpoly_init(ta, r->ctx);
    fmpz_mpoly_init(tb, r->ctx);
    fmpz_mpoly_init(tg, r->ctx);
    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_init(tn, r->ctx);
    fmpz_mpoly_init(tt, r->ctx);

    if (fmpz_mpoly_equal(xd, yd, r->ctx)) {
        if (sign > 0)
            fmpz_mpoly_add(num, xn, yn, r->ctx);
        else
            fmpz_mpoly_sub(num, xn, yn, r->ctx);
        if (fmpz_mpoly_is_zero(num, r->ctx)) {
            fmpz_mpoly_one(den, r->ctx);
            goto cleanup;
        }
        cofactors(&pn, &pt, &pg, tn, tt, tg, num, xd, r);
        if (pg != NULL) {
            fmpz_mpoly_swap(num, tn, r->ctx);
            fmpz_mpoly_swap(den, tt, r->ctx);
        } else {
            fmpz_mpoly_set(den, xd, r->ctx);
        }
        goto cleanup;
    }
    if (fmpz_mpoly_is_one(xd, r->ctx)) {
        fmpz_mpoly_mul(num, xn, yd, r->ctx);
        if (sign > 0)
            fmpz_mpoly_add(num, num, yn, r->ctx);
        else
            fmpz_mpoly_sub(num, num, yn, r->ctx);
        fmpz_mpoly_set(den, yd, r->ctx);
        goto cleanup;
    }
    if (fmpz_mpoly_is_one(yd, r->ctx)) {
        fmpz_mpoly_mul(num, yn, xd, r->ctx);
        if (sign > 0)
            fmpz_mpoly_add(num, xn, num, r->ctx);
        else
            fmpz_mpoly_sub(num, xn, num, r->ctx);
        fmpz_mpoly_set(den, xd, r->ctx);
        goto cleanup;
    }

    cofactors(&pa, &pb, &pg, ta, tb, tg, xd, yd, r);
    fmpz_mpoly_mul(num, xn, pb, r->ctx);
    fmpz_mpoly_mul(t, yn, pa, r->ctx);
    if (sign > 0)
        fmpz_mpoly_add(num, num, t, r->ctx);
    else
        fmpz_mpoly_sub(num, num, t, r->ctx);
    if (fmpz_mpoly_is_zero(num, r->ctx)) {
        fmpz_mpoly_one(den, r->ctx);
        goto cleanup;
    }
    if (pg == NULL) {
        /* coprime denominators: the sum is already reduced */
        fmpz_mpoly_mul(den, xd, yd, r->ctx);
        goto cleanup;
    }
    /* den = a*b*(g/h) and num/h with h = gcd(num, g) */
    cofactors(&pn, &pu, &pt, tn, tt, t, num, pg, r);
    if (pt != NULL)
        fmpz_mpoly_swap(num, tn, r->ctx);
    fmpz_mpoly_mul(den, pa, pb, r->ctx);
    fmpz_mpoly_mul(den, den, pu, r->ctx);

cleanup:
    /* every factor of den has lc > 0; this guards the invariant cheaply */
    if (lc_is_negative(den)) {
        fmpz_mpoly_neg(num, num, r->ctx);
        fmpz_mpoly_neg(den, den, r->ctx);
    }
    fmpz_mpoly_clear(tt, r->ctx);
    fmpz_mpoly_clear(tn, r->ctx);
    fmpz_mpoly_clear(t, r->ctx);
    fmpz_mpoly_clear(tg, r->ctx);
    fmpz_mpoly_clear(tb, r->ctx);
    fmpz_mpoly_clear(ta, r->ctx);
}

static void add_sub(RatFun res, const RatFun x, const RatFun y, int sign,
                    const Ring *r)
{
    if (ratfun_is_zero(y, r)) {
        ratfun_set(res, x, r);
        return;
    }
    if (ratfun_is_zero(x, r)) {
        if (sign > 0)
            ratfun_set(res, y, r);
        else
            ratfun_neg(res, y, r);
        return;
    }
    if (res != x && res != y) {
        _ratfun_add(res->num, res->den, x->num, x->den, y->num, y->den, sign,
                    r);
    } else {
        RatFun t;
        ratfun_init(t, r);
        _ratfun_add(t->num, t->den, x->num, x->den, y->num, y->den, sign, r);
        ratfun_swap(res, t, r);
        ratfun_clear(t, r);
    }
}

void ratfun_add(RatFun res, const RatFun x, const RatFun y, const Ring *r)
{
    add_sub(res, x, y, 1, r);
}

void ratfun_sub(RatFun res, const RatFun x, const RatFun y, const Ring *r)
{
    add_sub(res, x, y, -1, r);
}

/* num/den = (xn/xd)*(yn/yd), all non-zero, xd and yd with any sign,
 * xn/xd and yn/yd each reduced; num, den must not alias the inputs.
 * Crosswise cancellation: with g1 = gcd(xn, yd), g2 = gcd(yn, xd),
 *   (xn/g1)*(yn/g2) / ((xd/g2)*(yd/g1))
 * is reduced, so no gcd of the (bigger) products is needed.  The sign of
 * den is fixed by the caller. */
static void _ratfun_mul(fmpz_mpoly_t num, fmpz_mpoly_t den,
                        const fmpz_mpoly_t xn, const fmpz_mpoly_t xd,
                        const fmpz_mpoly_t yn, const fmpz_mpoly_t yd,
                        const Ring *r)
{
    const fmpz_mpoly_struct *p1, *p2, *p3, *p4, *pg;
    fmpz_mpoly_t t1, t2, t3, t4, tg;

    fmpz_mpoly_init(t1, r->ctx);
    fmpz_mpoly_init(t2, r->ctx);
    fmpz_mpoly_init(t3, r->ctx);
    fmpz_mpoly_init(t4, r->ctx);
    fmpz_mpoly_init(tg, r->ctx);
    cofactors(&p1, &p2, &pg, t1, t2, tg, xn, yd, r); /* xn/g1, yd/g1 */
    cofactors(&p3, &p4, &pg, t3, t4, tg, yn, xd, r); /* yn/g2, xd/g2 */
    fmpz_mpoly_mul(num, p1, p3, r->ctx);
    fmpz_mpoly_mul(den, p4, p2, r->ctx);
    fmpz_mpoly_clear(tg, r->ctx);
    fmpz_mpoly_clear(t4, r->ctx);
    fmpz_mpoly_clear(t3, r->ctx);
    fmpz_mpoly_clear(t2, r->ctx);
    fmpz_mpoly_clear(t1, r->ctx);
}

/* res = (xn/xd)*(yn/yd) with aliasing handled and sign fixed */
static void mul_parts(RatFun res, const fmpz_mpoly_t xn, const fmpz_mpoly_t xd,
                      const fmpz_mpoly_t yn, const fmpz_mpoly_t yd,
                      const Ring *r)
{
    RatFun t;

    ratfun_init(t, r);
    _ratfun_mul(t->num, t->den, xn, xd, yn, yd, r);
    if (lc_is_negative(t->den)) {
        fmpz_mpoly_neg(t->num, t->num, r->ctx);
        fmpz_mpoly_neg(t->den, t->den, r->ctx);
    }
    ratfun_swap(res, t, r);
    ratfun_clear(t, r);
}

void ratfun_mul(RatFun res, const RatFun x, const RatFun y, const Ring *r)
{
    if (ratfun_is_zero(x, r) || ratfun_is_zero(y, r)) {
        ratfun_zero(res, r);
        return;
    }
    /* polynomial times polynomial: nothing can cancel */
    if (fmpz_mpoly_is_one(x->den, r->ctx) &&
        fmpz_mpoly_is_one(y->den, r->ctx)) {
        fmpz_mpoly_mul(res->num, x->num, y->num, r->ctx);
        fmpz_mpoly_one(res->den, r->ctx);
        return;
    }
    mul_parts(res, x->num, x->den, y->num, y->den, r);
}

/* c/1 times n/d: only the integer content of d can cancel against c */
void ratfun_mul_si(RatFun res, const RatFun x, slong c, const Ring *r)
{
    fmpz_t g, cc;

    if (c == 0 || ratfun_is_zero(x, r)) {
        ratfun_zero(res, r);
        return;
    }
    fmpz_init(g);
    fmpz_init_set_si(cc, c);
    ratfun_set(res, x, r);
    _fmpz_vec_content(g, res->den->coeffs, res->den->length);
    fmpz_gcd(g, g, cc);
    if (!fmpz_is_one(g)) {
        fmpz_divexact(cc, cc, g);
        /* coefficient-wise: exponents do not change */
        _fmpz_vec_scalar_divexact_fmpz(res->den->coeffs, res->den->coeffs,
                                       res->den->length, g);
    }
    _fmpz_vec_scalar_mul_fmpz(res->num->coeffs, res->num->coeffs,
                              res->num->length, cc);
    fmpz_clear(cc);
    fmpz_clear(g);
}

int ratfun_inv(RatFun res, const RatFun x, const Ring *r)
{
    if (ratfun_is_zero(x, r))
        return RATFUN_EDIVZERO;
    ratfun_set(res, x, r);
    fmpz_mpoly_swap(res->num, res->den, r->ctx);
    if (lc_is_negative(res->den)) {
        fmpz_mpoly_neg(res->num, res->num, r->ctx);
        fmpz_mpoly_neg(res->den, res->den, r->ctx);
    }
    return RATFUN_OK;
}

/* x / y = (xn/xd) * (yd/yn) */
int ratfun_div(RatFun res, const RatFun x, const RatFun y, const Ring *r)
{
    if (ratfun_is_zero(y, r))
        return RATFUN_EDIVZERO;
    if (ratfun_is_zero(x, r)) {
        ratfun_zero(res, r);
        return RATFUN_OK;
    }
    mul_parts(res, x->num, x->den, y->den, y->num, r);
    return RATFUN_OK;
}

/* (n/d)^e = n^e/d^e stays coprime; e < 0 inverts first */
int ratfun_pow_si(RatFun res, const RatFun x, slong e, const Ring *r)
{
    int st = RATFUN_OK;
    ulong k;
    RatFun t;

    if (e == 0) {
        ratfun_one(res, r);
        return RATFUN_OK;
    }
    if (ratfun_is_zero(x, r)) {
        if (e < 0)
            return RATFUN_EDIVZERO;
        ratfun_zero(res, r);
        return RATFUN_OK;
    }
    if (e == 1) {
        ratfun_set(res, x, r);
        return RATFUN_OK;
    }
    k = e > 0 ? (ulong)e : (ulong)(-(e + 1)) + 1; /* |e| without overflow */
    ratfun_init(t, r);
    if (!fmpz_mpoly_pow_ui(t->num, x->num, k, r->ctx) ||
        !fmpz_mpoly_pow_ui(t->den, x->den, k, r->ctx)) {
        st = RATFUN_EOVERFLOW;
        goto cleanup;
    }
    if (e < 0)
        ratfun_inv(t, t, r); /* t is non-zero */
    ratfun_swap(res, t, r);
cleanup:
    ratfun_clear(t, r);
    return st;
}

/* ---- calculus and substitution ---------------------------------------- */

/* (n/d)' = (n'd - nd')/d^2, reduced; for an integer d just n'/d */
void ratfun_derivative(RatFun res, const RatFun x, slong var, const Ring *r)
{
    RatFun t;
    fmpz_mpoly_t u;

    if (!ratfun_depends_on(x, var, r)) {
        ratfun_zero(res, r);
        return;
    }
    ratfun_init(t, r);
    fmpz_mpoly_init(u, r->ctx);
    if (fmpz_mpoly_is_fmpz(x->den, r->ctx)) {
        fmpz_mpoly_derivative(t->num, x->num, var, r->ctx);
        fmpz_mpoly_set(t->den, x->den, r->ctx);
    } else {
        fmpz_mpoly_derivative(t->num, x->num, var, r->ctx);
        fmpz_mpoly_mul(t->num, t->num, x->den, r->ctx);
        fmpz_mpoly_derivative(u, x->den, var, r->ctx);
        fmpz_mpoly_mul(u, u, x->num, r->ctx);
        fmpz_mpoly_sub(t->num, t->num, u, r->ctx);
        fmpz_mpoly_mul(t->den, x->den, x->den, r->ctx);
    }
    reduce(t->num, t->den, r);
    ratfun_swap(res, t, r);
    fmpz_mpoly_clear(u, r->ctx);
    ratfun_clear(t, r);
}

/* The k-th derivative without a gcd per step: with x = n/d,
 *   (N_j / d^(j+1))' = (N_j' d - (j+1) N_j d') / d^(j+2),  N_0 = n,
 * so N_k / d^(k+1) is reduced once at the end.  (A gcd per step costs far
 * more: the 8th derivative of 1/(t^100 u^100 + t + u + 1) took 17 s.) */
void ratfun_derivative_n(RatFun res, const RatFun x, slong var, ulong k,
                         const Ring *r)
{
    if (k == 0) {
        ratfun_set(res, x, r);
        return;
    }
    if (k == 1 || !ratfun_depends_on(x, var, r) ||
        fmpz_mpoly_is_fmpz(x->den, r->ctx)) {
        ratfun_derivative(res, x, var, r);
        for (ulong j = 1; j < k && !ratfun_is_zero(res, r); j++)
            ratfun_derivative(res, res, var, r);
        return;
    }
    fmpz_mpoly_t N, dd, u, v;
    RatFun t;
    fmpz_mpoly_init(N, r->ctx);
    fmpz_mpoly_init(dd, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    fmpz_mpoly_init(v, r->ctx);
    ratfun_init(t, r);
    fmpz_mpoly_set(N, x->num, r->ctx);
    fmpz_mpoly_derivative(dd, x->den, var, r->ctx);
    for (ulong j = 0; j < k; j++) {
        fmpz_mpoly_derivative(u, N, var, r->ctx);
        fmpz_mpoly_mul(u, u, x->den, r->ctx);
        fmpz_mpoly_mul(v, N, dd, r->ctx);
        fmpz_mpoly_scalar_mul_ui(v, v, j + 1, r->ctx);
        fmpz_mpoly_sub(N, u, v, r->ctx);
    }
    fmpz_mpoly_swap(t->num, N, r->ctx);
    fmpz_mpoly_pow_ui(t->den, x->den, k + 1, r->ctx);
    reduce(t->num, t->den, r);
    ratfun_swap(res, t, r);
    ratfun_clear(t, r);
    fmpz_mpoly_clear(v, r->ctx);
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(dd, r->ctx);
    fmpz_mpoly_clear(N, r->ctx);
}

/* res = b^e0 * p(var := a/b), e0 = deg_var(p), *deg = e0.  Homogenised
 * Horner over the terms c_j*var^e_j of p (e_0 > e_1 > ...; the c_j are free
 * of var):
 *   acc_0 = c_0,  acc_j = acc_{j-1}*a^(e_{j-1}-e_j) + c_j*b^(e_0-e_j),
 *   res = acc_last * a^e_last.
 * Returns 0 if a power overflows FLINT's exponent range. */
/* ratfun_poly_compose_homog when p has no variable but var and a, b are
 * numbers (a node at a fixed parameter value: subst(X, t, 1/3)): homogeneous
 * Horner on integers, without the polynomial machinery */
static void compose_homog_numeric(fmpz_mpoly_t res, slong *deg,
                                  const fmpz_mpoly_t p, slong var,
                                  const fmpz_t a, const fmpz_t b,
                                  const Ring *r)
{
    fmpz_t acc, c, pw, bp;
    slong prev = 0;
    fmpz_init(acc);
    fmpz_init(c);
    fmpz_init(pw);
    fmpz_init(bp);
    fmpz_one(bp);
    /* the terms of a univariate polynomial come in descending degree */
    for (slong i = 0; i < p->length; i++) {
        slong e = (slong)fmpz_mpoly_get_term_var_exp_ui(p, i, var, r->ctx);
        fmpz_mpoly_get_term_coeff_fmpz(c, p, i, r->ctx);
        if (i == 0) {
            *deg = e;
            fmpz_set(acc, c);
        } else {
            fmpz_pow_ui(pw, a, (ulong)(prev - e));
            fmpz_mul(acc, acc, pw);
            fmpz_pow_ui(pw, b, (ulong)(prev - e));
            fmpz_mul(bp, bp, pw);
            fmpz_addmul(acc, c, bp);
        }
        prev = e;
    }
    fmpz_pow_ui(pw, a, (ulong)prev);
    fmpz_mul(acc, acc, pw);
    fmpz_mpoly_set_fmpz(res, acc, r->ctx);
    fmpz_clear(bp);
    fmpz_clear(pw);
    fmpz_clear(c);
    fmpz_clear(acc);
}

/* 1 when p's only variable (if any) is var */
static int only_var(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    slong *degs = flint_malloc(sizeof(slong) * (size_t)FLINT_MAX(nv, 1));
    int ok = fmpz_mpoly_degrees_fit_si(p, r->ctx);
    if (ok) {
        fmpz_mpoly_degrees_si(degs, p, r->ctx);
        for (slong v = 0; v < nv && ok; v++)
            ok = v == var || degs[v] <= 0;
    }
    flint_free(degs);
    return ok;
}

int ratfun_poly_compose_homog(fmpz_mpoly_t res, slong *deg, const fmpz_mpoly_t p,
                         slong var, const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                         const Ring *r)
{
    if (p->length > 0 && fmpz_mpoly_is_fmpz(a, r->ctx) &&
        fmpz_mpoly_is_fmpz(b, r->ctx) && only_var(p, var, r)) {
        fmpz_t fa, fb;
        fmpz_init(fa);
        fmpz_init(fb);
        fmpz_mpoly_get_fmpz(fa, a, r->ctx);
        fmpz_mpoly_get_fmpz(fb, b, r->ctx);
        compose_homog_numeric(res, deg, p, var, fa, fb, r);
        fmpz_clear(fb);
        fmpz_clear(fa);
        return 1;
    }
    int ok = 1;
    int b_one = fmpz_mpoly_is_one(b, r->ctx);
    fmpz_mpoly_univar_t U;
    fmpz_mpoly_t acc, pw, bp;

    fmpz_mpoly_univar_init(U, r->ctx);
    fmpz_mpoly_init(acc, r->ctx);
    fmpz_mpoly_init(pw, r->ctx);
    fmpz_mpoly_init(bp, r->ctx);
    *deg = 0;
    fmpz_mpoly_to_univar(U, p, var, r->ctx);
    if (U->length == 0)
        goto done;
    *deg = fmpz_get_si(U->exps + 0);
    fmpz_mpoly_set(acc, U->coeffs + 0, r->ctx);
    /* Horner in a; bp = b^(deg - e_j) is kept by multiplying by b^(e_(j-1)
     * - e_j), usually b itself, rather than raised anew at every term */
    fmpz_mpoly_one(bp, r->ctx);
    for (slong j = 1; j < U->length; j++) {
        ulong da =
            (ulong)(fmpz_get_si(U->exps + j - 1) - fmpz_get_si(U->exps + j));
        if (!fmpz_mpoly_pow_ui(pw, a, da, r->ctx)) {
            ok = 0;
            goto done;
        }
        fmpz_mpoly_mul(acc, acc, pw, r->ctx);
        if (b_one) {
            fmpz_mpoly_add(acc, acc, U->coeffs + j, r->ctx);
        } else {
            if (!fmpz_mpoly_pow_ui(pw, b, da, r->ctx)) {
                ok = 0;
                goto done;
            }
            fmpz_mpoly_mul(bp, bp, pw, r->ctx);
            fmpz_mpoly_mul(pw, bp, U->coeffs + j, r->ctx);
            fmpz_mpoly_add(acc, acc, pw, r->ctx);
        }
    }
    {
        ulong dl = (ulong)fmpz_get_si(U->exps + U->length - 1);
        if (!fmpz_mpoly_pow_ui(pw, a, dl, r->ctx)) {
            ok = 0;
            goto done;
        }
        fmpz_mpoly_mul(acc, acc, pw, r->ctx);
    }
done:
    if (ok)
        fmpz_mpoly_swap(res, acc, r->ctx);
    fmpz_mpoly_clear(bp, r->ctx);
    fmpz_mpoly_clear(pw, r->ctx);
    fmpz_mpoly_clear(acc, r->ctx);
    fmpz_mpoly_univar_clear(U, r->ctx);
    return ok;
}

/* With s = a/b:  n(a/b)/d(a/b) = (N/b^dn)/(D/b^dd) = N*b^(dd-dn)/D, where
 * N, D are the homogenised compositions; then one full gcd, since the
 * substitution can create common factors (t/(t-1) at t := 1/u ...). */
int ratfun_compose_var(RatFun res, const RatFun x, slong var, const RatFun s,
                       const Ring *r)
{
    int st = RATFUN_OK;
    slong dn, dd;
    RatFun t;
    fmpz_mpoly_t pw;

    if (!ratfun_depends_on(x, var, r)) {
        ratfun_set(res, x, r);
        return RATFUN_OK;
    }
    ratfun_init(t, r);
    fmpz_mpoly_init(pw, r->ctx);
    if (!ratfun_poly_compose_homog(t->num, &dn, x->num, var, s->num, s->den, r) ||
        !ratfun_poly_compose_homog(t->den, &dd, x->den, var, s->num, s->den, r)) {
        st = RATFUN_EOVERFLOW;
        goto cleanup;
    }
    if (fmpz_mpoly_is_zero(t->den, r->ctx)) {
        st = RATFUN_EPOLE;
        goto cleanup;
    }
    if (dd != dn && !fmpz_mpoly_is_one(s->den, r->ctx)) {
        if (!fmpz_mpoly_pow_ui(pw, s->den, (ulong)(dd > dn ? dd - dn : dn - dd),
                               r->ctx)) {
            st = RATFUN_EOVERFLOW;
            goto cleanup;
        }
        if (dd > dn)
            fmpz_mpoly_mul(t->num, t->num, pw, r->ctx);
        else
            fmpz_mpoly_mul(t->den, t->den, pw, r->ctx);
    }
    reduce(t->num, t->den, r);
    ratfun_swap(res, t, r);
cleanup:
    fmpz_mpoly_clear(pw, r->ctx);
    ratfun_clear(t, r);
    return st;
}

/* value of p at vals, term by term (exponents are small in practice) */
static void poly_evaluate_fmpq(fmpq_t res, const fmpz_mpoly_t p,
                               const fmpq *vals, const Ring *r)
{
    fmpq_t term, pw;

    fmpq_init(term);
    fmpq_init(pw);
    fmpq_zero(res);
    for (slong i = 0; i < p->length; i++) {
        fmpz_set(fmpq_numref(term), p->coeffs + i);
        fmpz_one(fmpq_denref(term));
        for (slong v = 0; v < r->nvars; v++) {
            slong e = fmpz_mpoly_get_term_var_exp_si(p, i, v, r->ctx);
            if (e == 0)
                continue;
            fmpq_pow_si(pw, vals + v, e);
            fmpq_mul(term, term, pw);
        }
        fmpq_add(res, res, term);
    }
    fmpq_clear(pw);
    fmpq_clear(term);
}

int ratfun_evaluate_fmpq(fmpq_t res, const RatFun x, const fmpq *vals,
                         const Ring *r)
{
    int st = RATFUN_OK;
    fmpq_t n, d;

    fmpq_init(n);
    fmpq_init(d);
    poly_evaluate_fmpq(d, x->den, vals, r);
    if (fmpq_is_zero(d)) {
        st = RATFUN_EPOLE;
        goto cleanup;
    }
    poly_evaluate_fmpq(n, x->num, vals, r);
    fmpq_div(res, n, d);
cleanup:
    fmpq_clear(d);
    fmpq_clear(n);
    return st;
}

/* ---- text ------------------------------------------------------------- */

/* Recursive descent over
 *   expr   = ['+'|'-'] term (('+'|'-') term)*     (sign handled in unary)
 *   term   = unary (('*'|'/') unary)*
 *   unary  = ('+'|'-') unary | power
 *   power  = atom ['^' expo]
 *   expo   = ['+'|'-'] INT | '(' ['+'|'-'] INT ')'
 *   atom   = NUMBER | NAME | '(' expr ')'
 * so -x^2 = -(x^2) and a/b*c = (a/b)*c, as in the language. */
typedef struct StrParser {
    const char *s; // cursor
    const Ring *r;
    int depth; // nesting of '(' and unary signs, bounded: no stack blow-up
} StrParser;

#define STR_MAX_DEPTH 1000

static int parse_expr(RatFun res, StrParser *p);

static void skip_blanks(StrParser *p)
{
    while (*p->s == ' ' || *p->s == '\t' || *p->s == '\n' || *p->s == '\r')
        p->s++;
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int is_name_char(char c, int first)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' ||
           (!first && is_digit(c));
}

/* [+-] digits, capped at RATFUN_STR_MAX_EXP */
static int parse_small_int(slong *e, StrParser *p)
{
    int neg = 0;
    slong v = 0;

    skip_blanks(p);
    if (*p->s == '+' || *p->s == '-') {
        neg = *p->s == '-';
        p->s++;
        skip_blanks(p);
    }
    if (!is_digit(*p->s))
        return RATFUN_ESYNTAX;
    while (is_digit(*p->s)) {
        v = 10 * v + (*p->s - '0');
        if (v > RATFUN_STR_MAX_EXP)
            return RATFUN_EOVERFLOW;
        p->s++;
    }
    *e = neg ? -v : v;
    return RATFUN_OK;
}

/* NUMBER = (digits ['.' digits*] | '.' digits) [('e'|'E') ['+'|'-'] digits],
 * read exactly: mantissa m with f fraction digits and exponent x gives
 * m * 10^(x - f). */
static int parse_number(RatFun res, StrParser *p)
{
    int st = RATFUN_OK;
    slong frac = 0, ex = 0;
    fmpz_t m, ten;
    fmpq_t q;

    fmpz_init(m);
    fmpz_init(ten);
    fmpq_init(q);
    if (!is_digit(*p->s) && !(*p->s == '.' && is_digit(p->s[1]))) {
        st = RATFUN_ESYNTAX;
        goto cleanup;
    }
    while (is_digit(*p->s)) {
        fmpz_mul_ui(m, m, 10);
        fmpz_add_ui(m, m, (ulong)(*p->s++ - '0'));
    }
    if (*p->s == '.') {
        p->s++;
        while (is_digit(*p->s)) {
            fmpz_mul_ui(m, m, 10);
            fmpz_add_ui(m, m, (ulong)(*p->s++ - '0'));
            frac++;
        }
    }
    if ((*p->s == 'e' || *p->s == 'E') &&
        (is_digit(p->s[1]) ||
         ((p->s[1] == '+' || p->s[1] == '-') && is_digit(p->s[2])))) {
        p->s++;
        st = parse_small_int(&ex, p);
        if (st != RATFUN_OK)
            goto cleanup;
    }
    /* |ex| <= RATFUN_STR_MAX_EXP + (digits in the text): no blow-up */
    ex -= frac;
    fmpz_set_ui(ten, 10);
    fmpz_pow_ui(ten, ten, (ulong)(ex >= 0 ? ex : -ex));
    if (ex >= 0) {
        fmpz_mul(fmpq_numref(q), m, ten);
        fmpz_one(fmpq_denref(q));
    } else {
        fmpq_set_fmpz_frac(q, m, ten);
    }
    ratfun_set_fmpq(res, q, p->r);
cleanup:
    fmpq_clear(q);
    fmpz_clear(ten);
    fmpz_clear(m);
    return st;
}

static int parse_atom(RatFun res, StrParser *p)
{
    int st;

    skip_blanks(p);
    if (*p->s == '(') {
        p->s++;
        if (++p->depth > STR_MAX_DEPTH)
            return RATFUN_ESYNTAX;
        st = parse_expr(res, p);
        p->depth--;
        if (st != RATFUN_OK)
            return st;
        skip_blanks(p);
        if (*p->s != ')')
            return RATFUN_ESYNTAX;
        p->s++;
        return RATFUN_OK;
    }
    if (is_name_char(*p->s, 1)) {
        const char *start = p->s;
        size_t len;
        while (is_name_char(*p->s, 0))
            p->s++;
        len = (size_t)(p->s - start);
        for (slong i = 0; i < p->r->nvars; i++) {
            if (strlen(p->r->names[i]) == len &&
                memcmp(p->r->names[i], start, len) == 0) {
                ratfun_gen(res, i, p->r);
                return RATFUN_OK;
            }
        }
        return RATFUN_ENAME;
    }
    return parse_number(res, p);
}

static int parse_power(RatFun res, StrParser *p)
{
    int st;
    slong e;

    st = parse_atom(res, p);
    if (st != RATFUN_OK)
        return st;
    skip_blanks(p);
    if (*p->s != '^')
        return RATFUN_OK;
    p->s++;
    skip_blanks(p);
    if (*p->s == '(') {
        p->s++;
        st = parse_small_int(&e, p);
        if (st != RATFUN_OK)
            return st;
        skip_blanks(p);
        if (*p->s != ')')
            return RATFUN_ESYNTAX;
        p->s++;
    } else {
        st = parse_small_int(&e, p);
        if (st != RATFUN_OK)
            return st;
    }
    return ratfun_pow_si(res, res, e, p->r);
}

static int parse_unary(RatFun res, StrParser *p)
{
    int st;

    skip_blanks(p);
    if (*p->s == '-' || *p->s == '+') {
        int neg = *p->s == '-';
        p->s++;
        if (++p->depth > STR_MAX_DEPTH)
            return RATFUN_ESYNTAX;
        st = parse_unary(res, p);
        p->depth--;
        if (st == RATFUN_OK && neg)
            ratfun_neg(res, res, p->r);
        return st;
    }
    return parse_power(res, p);
}

static int parse_term(RatFun res, StrParser *p)
{
    int st;
    RatFun rhs;

    ratfun_init(rhs, p->r);
    st = parse_unary(res, p);
    while (st == RATFUN_OK) {
        char op;
        skip_blanks(p);
        op = *p->s;
        if (op != '*' && op != '/')
            break;
        p->s++;
        st = parse_unary(rhs, p);
        if (st != RATFUN_OK)
            break;
        if (op == '*')
            ratfun_mul(res, res, rhs, p->r);
        else
            st = ratfun_div(res, res, rhs, p->r);
    }
    ratfun_clear(rhs, p->r);
    return st;
}

static int parse_expr(RatFun res, StrParser *p)
{
    int st;
    RatFun rhs;

    ratfun_init(rhs, p->r);
    st = parse_term(res, p);
    while (st == RATFUN_OK) {
        char op;
        skip_blanks(p);
        op = *p->s;
        if (op != '+' && op != '-')
            break;
        p->s++;
        st = parse_term(rhs, p);
        if (st != RATFUN_OK)
            break;
        if (op == '+')
            ratfun_add(res, res, rhs, p->r);
        else
            ratfun_sub(res, res, rhs, p->r);
    }
    ratfun_clear(rhs, p->r);
    return st;
}

int ratfun_set_str(RatFun res, const char *s, const Ring *r)
{
    int st;
    StrParser p = {s, r, 0};
    RatFun t;

    ratfun_init(t, r);
    st = parse_expr(t, &p);
    if (st == RATFUN_OK) {
        skip_blanks(&p);
        if (*p.s != '\0')
            st = RATFUN_ESYNTAX;
    }
    if (st == RATFUN_OK)
        ratfun_swap(res, t, r);
    ratfun_clear(t, r);
    return st;
}

/* A one-term numerator reads correctly before '/' ("-2*x/(..)" parses as
 * ((-2)*x)/(..)); a denominator needs parentheses unless it is an integer
 * or a single power ("x^2"): it is never negative, so '*', '+' and '-' are
 * exactly the signs of trouble. */
char *ratfun_get_str(const RatFun x, const Ring *r)
{
    char *ns, *ds, *out;
    int pn, pd;
    size_t len;

    ns = fmpz_mpoly_get_str_pretty(x->num, r->names, r->ctx);
    if (fmpz_mpoly_is_one(x->den, r->ctx))
        return ns;
    ds = fmpz_mpoly_get_str_pretty(x->den, r->names, r->ctx);
    pn = x->num->length > 1;
    pd = strpbrk(ds, "*+-") != NULL;
    len = strlen(ns) + strlen(ds) + 6;
    out = flint_malloc(len);
    snprintf(out, len, "%s%s%s/%s%s%s", pn ? "(" : "", ns, pn ? ")" : "",
             pd ? "(" : "", ds, pd ? ")" : "");
    flint_free(ds);
    flint_free(ns);
    return out;
}

/* ---- size guards --------------------------------------------------------- */

/* A polynomial's shape for the estimates: log2 of its length, its largest
 * coefficient's bits, its degree in every variable (degs: nvars slots). */
typedef struct Shape {
    double llen;  // log2(length); -1 for the zero polynomial
    double bits;  // largest coefficient, bits
    slong *degs;  // borrowed buffer
    int huge;     // degrees beyond a slong
} Shape;

static void shape_of(Shape *s, const fmpz_mpoly_t p, slong *degs,
                     const Ring *r)
{
    slong len = fmpz_mpoly_length(p, r->ctx);
    s->degs = degs;
    s->llen = len ? log2((double)len) : -1;
    s->bits = (double)FLINT_ABS(fmpz_mpoly_max_bits(p));
    s->huge = !fmpz_mpoly_degrees_fit_si(p, r->ctx);
    if (!s->huge)
        fmpz_mpoly_degrees_si(degs, p, r->ctx);
}

/* log2 of the bits of a*b at most */
static double prod_bits(const Shape *a, const Shape *b, slong nv)
{
    if (a->llen < 0 || b->llen < 0)
        return 0;
    if (a->huge || b->huge)
        return INFINITY;
    double lterms = 0;
    for (slong v = 0; v < nv; v++)
        lterms += log2((double)a->degs[v] + (double)b->degs[v] + 1);
    if (a->llen + b->llen < lterms)
        lterms = a->llen + b->llen;
    double shorter = a->llen < b->llen ? a->llen : b->llen;
    return lterms + log2(a->bits + b->bits + shorter + 1);
}

/* log2 of binomial(n, k) (lgamma_r: lgamma sets the process-wide signgam,
 * a data race between threads) */
static double log2_binomial(double n, double k)
{
    int sg;
    return (lgamma_r(n + 1, &sg) - lgamma_r(k + 1, &sg) -
            lgamma_r(n - k + 1, &sg)) /
           log(2.0);
}

/* log2 of the number of terms of a^e at most: the multinomial count
 * binomial(len + e - 1, e) (the monomials of degree e in len symbols) and
 * the box of the degrees, whichever is smaller */
static double pow_lterms(const Shape *a, double e, slong nv)
{
    double box = 0;
    for (slong v = 0; v < nv; v++)
        box += log2(e * (double)a->degs[v] + 1);
    double len = exp2(a->llen);
    double multi = log2_binomial(len + e - 1, e);
    return multi < box ? multi : box;
}

/* log2 of the bits of a^e at most (e >= 0) */
static double pow_bits(const Shape *a, double e, slong nv)
{
    if (a->llen < 0 || e == 0)
        return 0;
    if (a->huge)
        return INFINITY;
    return pow_lterms(a, e, nv) + log2(e * (a->bits + a->llen + 1) + 1);
}

static double max2(double a, double b)
{
    return a > b ? a : b;
}

/* the shapes of a RatFun's numerator and denominator (own degree buffer) */
typedef struct Shapes {
    Shape n, d;
    slong *degs; // owned, 2 * nvars
} Shapes;

static void shapes_init(Shapes *s, const RatFun x, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    s->degs = flint_malloc(2 * (size_t)nv * sizeof(slong));
    shape_of(&s->n, x->num, s->degs, r);
    shape_of(&s->d, x->den, s->degs + nv, r);
}

static void shapes_clear(Shapes *s)
{
    flint_free(s->degs);
}

double ratfun_poly_log2_bits_mul(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                                 const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    slong *degs = flint_malloc((size_t)(2 * nv) * sizeof(slong));
    Shape sa, sb;
    shape_of(&sa, a, degs, r);
    shape_of(&sb, b, degs + nv, r);
    double bits = prod_bits(&sa, &sb, nv);
    flint_free(degs);
    return bits;
}

double ratfun_log2_bits_product(const RatFun x, const RatFun y, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a, b;
    shapes_init(&a, x, r);
    shapes_init(&b, y, r);
    double m = max2(max2(prod_bits(&a.n, &b.n, nv), prod_bits(&a.d, &b.d, nv)),
                    max2(prod_bits(&a.n, &b.d, nv), prod_bits(&a.d, &b.n, nv)));
    shapes_clear(&b);
    shapes_clear(&a);
    return m;
}

double ratfun_log2_bits_pow(const RatFun x, slong e, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a;
    shapes_init(&a, x, r);
    double ae = fabs((double)e);
    double m = max2(pow_bits(&a.n, ae, nv), pow_bits(&a.d, ae, nv));
    shapes_clear(&a);
    return m;
}

double ratfun_log2_bits_compose(const RatFun x, slong var, const RatFun s,
                                const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a, b;
    shapes_init(&a, x, r);
    shapes_init(&b, s, r);
    double m = INFINITY;
    if (!a.n.huge && !a.d.huge && !b.n.huge && !b.d.huge) {
        /* every term of x times a power of s of degree <= e, over the
         * common denominator: terms <= len(x) * terms(s^e), coefficient
         * bits <= bits(x) + e (bits(s) + log2 len(s)) + log2 len(x) */
        double e = (double)(a.n.degs[var] > a.d.degs[var] ? a.n.degs[var]
                                                          : a.d.degs[var]);
        double lx = max2(max2(a.n.llen, a.d.llen), 0);
        double bx = max2(a.n.bits, a.d.bits);
        double ls =
            e > 0 ? max2(pow_lterms(&b.n, e, nv), pow_lterms(&b.d, e, nv)) : 0;
        double bs = e * (max2(b.n.bits, b.d.bits) + max2(b.n.llen, b.d.llen) + 1);
        m = lx + ls + log2(bx + bs + lx + 1);
    }
    shapes_clear(&b);
    shapes_clear(&a);
    return m;
}
