/*
 * pteq.c - point equations: sparse maps from base points to weights.
 *
 * A PointEq is a short array of (point, weight) terms sorted by point index,
 * with no zero weight stored.  Schemes have a handful of base points, so a
 * sorted array with linear merging beats any hashing.
 *
 * Slot reuse: every entry terms[0..alloc) holds an INITIALISED RatFun, used
 * or not.  Removing a term rotates its RatFun past len instead of clearing
 * it, and inserting rotates a spare one in, so the polynomial buffers are
 * recycled and the hot operation acc = acc + y*s (along, divide, bezier,
 * meet) updates weights in place without allocating once acc has grown.
 * Terms are moved by swapping whole structs, which moves ownership and never
 * duplicates it.
 */
#include "compiler/pteq.h"

#include <stdint.h>

static void swap_terms(PtTerm *a, PtTerm *b)
{
    PtTerm t = *a;
    *a = *b;
    *b = t;
}

/* grow to at least len slots; new slots are initialised to 0 */
static void fit_length(PointEq x, slong len, const Ring *r)
{
    slong na;

    if (len <= x->alloc)
        return;
    na = FLINT_MAX(len, 2 * x->alloc);
    x->terms = flint_realloc(x->terms, (size_t)na * sizeof(PtTerm));
    for (slong i = x->alloc; i < na; i++) {
        x->terms[i].point = -1;
        ratfun_init(&x->terms[i].w, r);
    }
    x->alloc = na;
}

/* index of the first term whose point is >= point (binary search) */
static slong find(const PointEq x, slong point)
{
    slong lo = 0, hi = x->len;

    while (lo < hi) {
        slong mid = lo + (hi - lo) / 2;
        if (x->terms[mid].point < point)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* opens slot k for point (a spare RatFun with an unspecified value is
 * rotated in; the caller sets it) and returns its weight */
static RatFunStruct *insert_at(PointEq x, slong k, slong point, const Ring *r)
{
    fit_length(x, x->len + 1, r);
    for (slong i = x->len; i > k; i--)
        swap_terms(x->terms + i, x->terms + i - 1);
    x->terms[k].point = point;
    x->len++;
    return &x->terms[k].w;
}

static void remove_at(PointEq x, slong k)
{
    for (slong i = k; i + 1 < x->len; i++)
        swap_terms(x->terms + i, x->terms + i + 1);
    x->len--;
}

/* drops zero weights, keeping the order */
static void compact(PointEq x, const Ring *r)
{
    slong j = 0;

    for (slong i = 0; i < x->len; i++) {
        if (ratfun_is_zero(&x->terms[i].w, r))
            continue;
        if (i != j)
            swap_terms(x->terms + i, x->terms + j);
        j++;
    }
    x->len = j;
}

/* Does w live inside x's term array?  Then growing or rotating x would
 * move it under the caller's feet, so callers copy it first. */
static int points_into(const PointEq x, const RatFunStruct *w)
{
    uintptr_t p = (uintptr_t)w, lo = (uintptr_t)x->terms;
    return x->terms != NULL && p >= lo &&
           p < lo + (uintptr_t)x->alloc * sizeof(PtTerm);
}

/* res += sign * y * s (s == NULL means 1); res and y distinct, s not inside
 * res.  One merge pass: the terms of both are sorted by point. */
static void accumulate(PointEq res, const PointEq y, const RatFunStruct *s,
                       int sign, const Ring *r)
{
    slong i = 0;
    RatFun t;

    ratfun_init(t, r);
    for (slong j = 0; j < y->len; j++) {
        slong pt = y->terms[j].point;
        const RatFunStruct *v = &y->terms[j].w;
        if (s != NULL) {
            ratfun_mul(t, v, s, r);
            v = t;
        }
        while (i < res->len && res->terms[i].point < pt)
            i++;
        if (i < res->len && res->terms[i].point == pt) {
            RatFunStruct *w = &res->terms[i].w;
            if (sign > 0)
                ratfun_add(w, w, v, r);
            else
                ratfun_sub(w, w, v, r);
            if (ratfun_is_zero(w, r))
                remove_at(res, i);
            else
                i++;
        } else {
            RatFunStruct *w = insert_at(res, i, pt, r);
            if (sign > 0)
                ratfun_set(w, v, r);
            else
                ratfun_neg(w, v, r);
            i++;
        }
    }
    ratfun_clear(t, r);
}

/* ---- management ------------------------------------------------------- */

void pteq_init(PointEq x, const Ring *r)
{
    (void)r;
    x->terms = NULL;
    x->len = 0;
    x->alloc = 0;
}

void pteq_clear(PointEq x, const Ring *r)
{
    for (slong i = 0; i < x->alloc; i++)
        ratfun_clear(&x->terms[i].w, r);
    flint_free(x->terms);
    x->terms = NULL;
    x->len = x->alloc = 0;
}

void pteq_swap(PointEq x, PointEq y, const Ring *r)
{
    PointEqStruct t = *x;
    (void)r;
    *x = *y;
    *y = t;
}

void pteq_set(PointEq res, const PointEq x, const Ring *r)
{
    if (res == x)
        return;
    fit_length(res, x->len, r);
    for (slong i = 0; i < x->len; i++) {
        res->terms[i].point = x->terms[i].point;
        ratfun_set(&res->terms[i].w, &x->terms[i].w, r);
    }
    res->len = x->len;
}

void pteq_zero(PointEq res, const Ring *r)
{
    (void)r;
    res->len = 0;
}

void pteq_set_point(PointEq res, slong point, const Ring *r)
{
    fit_length(res, 1, r);
    res->terms[0].point = point;
    ratfun_one(&res->terms[0].w, r);
    res->len = 1;
}

int pteq_is_canonical(const PointEq x, const Ring *r)
{
    for (slong i = 0; i < x->len; i++) {
        if (i > 0 && x->terms[i - 1].point >= x->terms[i].point)
            return 0;
        if (x->terms[i].point < 0 || ratfun_is_zero(&x->terms[i].w, r) ||
            !ratfun_is_canonical(&x->terms[i].w, r))
            return 0;
    }
    return x->len <= x->alloc;
}

/* ---- weights ---------------------------------------------------------- */

const RatFunStruct *pteq_weight(const PointEq x, slong point)
{
    slong k = find(x, point);
    if (k < x->len && x->terms[k].point == point)
        return &x->terms[k].w;
    return NULL;
}

void pteq_get_weight(RatFun res, const PointEq x, slong point, const Ring *r)
{
    const RatFunStruct *w = pteq_weight(x, point);
    if (w != NULL)
        ratfun_set(res, w, r);
    else
        ratfun_zero(res, r);
}

void pteq_set_weight(PointEq x, slong point, const RatFun w, const Ring *r)
{
    slong k;

    if (points_into(x, w)) {
        RatFun t;
        ratfun_init(t, r);
        ratfun_set(t, w, r);
        pteq_set_weight(x, point, t, r);
        ratfun_clear(t, r);
        return;
    }
    k = find(x, point);
    if (k < x->len && x->terms[k].point == point) {
        if (ratfun_is_zero(w, r))
            remove_at(x, k);
        else
            ratfun_set(&x->terms[k].w, w, r);
    } else if (!ratfun_is_zero(w, r)) {
        ratfun_set(insert_at(x, k, point, r), w, r);
    }
}

int pteq_is_zero(const PointEq x, const Ring *r)
{
    (void)r;
    return x->len == 0;
}

int pteq_equal(const PointEq x, const PointEq y, const Ring *r)
{
    if (x->len != y->len)
        return 0;
    for (slong i = 0; i < x->len; i++)
        if (x->terms[i].point != y->terms[i].point ||
            !ratfun_equal(&x->terms[i].w, &y->terms[i].w, r))
            return 0;
    return 1;
}

/* Derived equations usually share one denominator across all weights
 * (meet() divides by one determinant); then the numerators are summed and
 * a single gcd reduces the total, instead of one gcd per term. */
void pteq_weight_sum(RatFun res, const PointEq x, const Ring *r)
{
    int same_den = x->len > 1;
    RatFun acc;

    ratfun_init(acc, r);
    for (slong i = 1; i < x->len && same_den; i++)
        same_den =
            fmpz_mpoly_equal(x->terms[i].w.den, x->terms[0].w.den, r->ctx);
    if (same_den) {
        for (slong i = 0; i < x->len; i++)
            fmpz_mpoly_add(acc->num, acc->num, x->terms[i].w.num, r->ctx);
        fmpz_mpoly_set(acc->den, x->terms[0].w.den, r->ctx);
        ratfun_canonicalise(acc, r); /* den != 0 */
    } else {
        for (slong i = 0; i < x->len; i++)
            ratfun_add(acc, acc, &x->terms[i].w, r);
    }
    ratfun_swap(res, acc, r);
    ratfun_clear(acc, r);
}

/* ---- arithmetic ------------------------------------------------------- */

void pteq_neg(PointEq res, const PointEq x, const Ring *r)
{
    pteq_set(res, x, r);
    for (slong i = 0; i < res->len; i++)
        ratfun_neg(&res->terms[i].w, &res->terms[i].w, r);
}

void pteq_add(PointEq res, const PointEq x, const PointEq y, const Ring *r)
{
    if (x == y) {
        pteq_set(res, x, r);
        for (slong i = 0; i < res->len; i++)
            ratfun_mul_si(&res->terms[i].w, &res->terms[i].w, 2, r);
    } else if (res == y) {
        accumulate(res, x, NULL, 1, r); /* addition commutes */
    } else {
        pteq_set(res, x, r);
        accumulate(res, y, NULL, 1, r);
    }
}

void pteq_sub(PointEq res, const PointEq x, const PointEq y, const Ring *r)
{
    if (x == y) {
        pteq_zero(res, r);
    } else if (res == y) {
        accumulate(res, x, NULL, -1, r); /* y - x, then negate */
        pteq_neg(res, res, r);
    } else {
        pteq_set(res, x, r);
        accumulate(res, y, NULL, -1, r);
    }
}

void pteq_scalar_mul(PointEq res, const PointEq x, const RatFun s,
                     const Ring *r)
{
    RatFun t;

    if (ratfun_is_zero(s, r)) {
        pteq_zero(res, r);
        return;
    }
    if (ratfun_is_one(s, r)) {
        pteq_set(res, x, r);
        return;
    }
    /* s may be one of res's own weights: then keep a copy across the loop */
    ratfun_init(t, r);
    if (points_into(res, s)) {
        ratfun_set(t, s, r);
        s = t;
    }
    pteq_set(res, x, r);
    for (slong i = 0; i < res->len; i++)
        ratfun_mul(&res->terms[i].w, &res->terms[i].w, s, r);
    ratfun_clear(t, r);
}

int pteq_scalar_div(PointEq res, const PointEq x, const RatFun s, const Ring *r)
{
    RatFun t;

    if (ratfun_is_zero(s, r))
        return RATFUN_EDIVZERO;
    ratfun_init(t, r);
    ratfun_inv(t, s, r);
    pteq_scalar_mul(res, x, t, r);
    ratfun_clear(t, r);
    return RATFUN_OK;
}

void pteq_addmul(PointEq res, const PointEq x, const PointEq y, const RatFun s,
                 const Ring *r)
{
    RatFun t;
    PointEq tmp;

    if (ratfun_is_zero(s, r)) {
        pteq_set(res, x, r);
        return;
    }
    if (x == y) {
        /* x + x*s = x*(1 + s) */
        ratfun_init(t, r);
        ratfun_one(t, r);
        ratfun_add(t, t, s, r);
        pteq_scalar_mul(res, x, t, r);
        ratfun_clear(t, r);
        return;
    }
    ratfun_init(t, r);
    pteq_init(tmp, r);
    if (points_into(res, s)) {
        ratfun_set(t, s, r);
        s = t;
    }
    if (res == y) {
        pteq_set(tmp, x, r);
        accumulate(tmp, y, s, 1, r);
        pteq_swap(res, tmp, r);
    } else {
        pteq_set(res, x, r);
        accumulate(res, y, s, 1, r);
    }
    pteq_clear(tmp, r);
    ratfun_clear(t, r);
}

/* sum_{i != point} w_i X_i + w_point * p */
void pteq_subst_point(PointEq res, const PointEq x, slong point,
                      const PointEq p, const Ring *r)
{
    RatFun w;
    PointEq tmp;
    slong k;

    if (pteq_weight(x, point) == NULL) {
        pteq_set(res, x, r);
        return;
    }
    ratfun_init(w, r);
    pteq_init(tmp, r);
    pteq_get_weight(w, x, point, r);
    pteq_set(tmp, x, r);
    k = find(tmp, point);
    remove_at(tmp, k);
    accumulate(tmp, p, w, 1, r);
    pteq_swap(res, tmp, r);
    pteq_clear(tmp, r);
    ratfun_clear(w, r);
}

int pteq_compose_var(PointEq res, const PointEq x, slong var, const RatFun s,
                     const Ring *r)
{
    int st = RATFUN_OK;
    PointEq tmp;

    pteq_init(tmp, r);
    fit_length(tmp, x->len, r);
    for (slong i = 0; i < x->len; i++) {
        tmp->terms[i].point = x->terms[i].point;
        st = ratfun_compose_var(&tmp->terms[i].w, &x->terms[i].w, var, s, r);
        if (st != RATFUN_OK)
            goto cleanup;
    }
    tmp->len = x->len;
    compact(tmp, r); /* t - 1 at t := 1 vanishes */
    pteq_swap(res, tmp, r);
cleanup:
    pteq_clear(tmp, r);
    return st;
}

void pteq_derivative(PointEq res, const PointEq x, slong var, const Ring *r)
{
    pteq_derivative_n(res, x, var, 1, r);
}

void pteq_derivative_n(PointEq res, const PointEq x, slong var, ulong k,
                       const Ring *r)
{
    pteq_set(res, x, r);
    for (slong i = 0; i < res->len; i++)
        ratfun_derivative_n(&res->terms[i].w, &res->terms[i].w, var, k, r);
    compact(res, r);
}
