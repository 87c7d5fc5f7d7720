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
#include "compiler/algebra/ratfun_int.h"

#include <stdlib.h>

#include "base/check.h"
#include "base/mem.h"

#include <flint/fmpz_poly.h>
#include <flint/fmpz_vec.h>
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
 * FLINT's gcd fails (exponent overflow, practically unreachable), the
 * program stops with an internal error: a value left unreduced would
 * break canonical form, and equality with it. */
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
        PC_UNREACHABLE("FLINT's gcd failed on a rational function's "
                       "numerator and denominator");
    if (fmpz_mpoly_is_one(tg, r->ctx))
        return;
    *pa = ta;
    *pb = tb;
    *pg = tg;
}

/* Divides num and den by their gcd in place and fixes the sign of den.
 * den is non-zero. */
void _ratfun_reduce(fmpz_mpoly_t num, fmpz_mpoly_t den, const Ring *r)
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
    _ratfun_reduce(x->num, x->den, r);
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
    RatFunStruct *v =
        pc_xmalloc(sizeof(RatFunStruct) * (size_t)FLINT_MAX(len, 1));
    for (slong i = 0; i < len; i++)
        ratfun_init(v + i, r);
    return v;
}

void ratfun_vec_clear(RatFunStruct *v, slong len, const Ring *r)
{
    for (slong i = 0; i < len; i++)
        ratfun_clear(v + i, r);
    pc_free(v);
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

/* ---- text ------------------------------------------------------------- */

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
