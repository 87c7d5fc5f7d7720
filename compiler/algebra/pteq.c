/*
 * pteq.c - point equations over one common denominator.
 *
 * A PointEq is a short array of (point, numerator) terms sorted by point
 * index, with no zero numerator stored, over one denominator (pteq.h).
 * Schemes have a handful of base points, so a sorted array with linear
 * merging beats any hashing.
 *
 * Every entry terms[0..alloc) holds an INITIALISED numerator, used or not,
 * so buffers are recycled; terms are moved by swapping whole structs, which
 * moves ownership and never duplicates it.
 *
 * The cost model: an operation on two equations forms its result over the
 * lcm of their denominators with polynomial products only, then makes it
 * primitive with ONE content reduction (canonicalise: a running gcd of the
 * denominator with the numerators, shortest first, that stops as soon as it
 * reaches 1).  The per-weight representation it replaces needed one gcd per
 * weight and per addition.  Scalar multiples use the structure of the
 * operands instead (scalar_mul).  Reduced weights are formed only where a
 * caller asks for them (pteq_get_weight: printing, lowering, tests).
 */
#include "compiler/algebra/pteq.h"

#include <stdint.h>
#include <stdlib.h>

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
        fmpz_mpoly_init(x->terms[i].num, r->ctx);
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

static int lc_negative(const fmpz_mpoly_t p)
{
    return p->length > 0 && fmpz_sgn(p->coeffs + 0) < 0;
}

static void exact_div(fmpz_mpoly_t q, const fmpz_mpoly_t a,
                      const fmpz_mpoly_t b, const Ring *r)
{
    if (fmpz_mpoly_is_one(b, r->ctx)) {
        fmpz_mpoly_set(q, a, r->ctx);
    } else if (fmpz_mpoly_is_fmpz(b, r->ctx)) {
        fmpz_mpoly_scalar_divexact_fmpz(q, a, b->coeffs + 0, r->ctx);
    } else {
        int ok = fmpz_mpoly_divides(q, a, b, r->ctx);
        (void)ok;
        FLINT_ASSERT(ok);
    }
}

/* ---- management ------------------------------------------------------- */

void pteq_init(PointEq x, const Ring *r)
{
    x->terms = NULL;
    x->len = 0;
    x->alloc = 0;
    fmpz_mpoly_init(x->den, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
}

void pteq_clear(PointEq x, const Ring *r)
{
    for (slong i = 0; i < x->alloc; i++)
        fmpz_mpoly_clear(x->terms[i].num, r->ctx);
    flint_free(x->terms);
    fmpz_mpoly_clear(x->den, r->ctx);
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
        fmpz_mpoly_set(res->terms[i].num, x->terms[i].num, r->ctx);
    }
    res->len = x->len;
    fmpz_mpoly_set(res->den, x->den, r->ctx);
}

void pteq_zero(PointEq res, const Ring *r)
{
    res->len = 0;
    fmpz_mpoly_one(res->den, r->ctx);
}

void pteq_set_point(PointEq res, slong point, const Ring *r)
{
    fit_length(res, 1, r);
    res->terms[0].point = point;
    fmpz_mpoly_one(res->terms[0].num, r->ctx);
    res->len = 1;
    fmpz_mpoly_one(res->den, r->ctx);
}

fmpz_mpoly_struct *pteq_append(PointEq x, slong point, const Ring *r)
{
    fit_length(x, x->len + 1, r);
    x->terms[x->len].point = point;
    return x->terms[x->len++].num;
}

/* order of the terms by numerator length, shortest first (the cheapest
 * gcd partners of the denominator come first) */
static slong *by_length(const PointEq x)
{
    slong *o = flint_malloc((size_t)FLINT_MAX(x->len, 1) * sizeof(slong));
    for (slong i = 0; i < x->len; i++) {
        slong j = i;
        for (;
             j > 0 && x->terms[o[j - 1]].num->length > x->terms[i].num->length;
             j--)
            o[j] = o[j - 1];
        o[j] = i;
    }
    return o;
}

void pteq_canonicalise(PointEq x, const Ring *r)
{
    slong j = 0;
    fmpz_mpoly_t g;

    for (slong i = 0; i < x->len; i++) {
        if (fmpz_mpoly_is_zero(x->terms[i].num, r->ctx))
            continue;
        if (i != j)
            swap_terms(x->terms + i, x->terms + j);
        j++;
    }
    x->len = j;
    if (x->len == 0) {
        fmpz_mpoly_one(x->den, r->ctx);
        return;
    }
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_set(g, x->den, r->ctx);
    if (lc_negative(g))
        fmpz_mpoly_neg(g, g, r->ctx);
    if (!fmpz_mpoly_is_one(g, r->ctx)) {
        slong *o = by_length(x);
        for (slong k = 0; k < x->len && !fmpz_mpoly_is_one(g, r->ctx); k++)
            ratfun_poly_gcd(g, g, x->terms[o[k]].num, r);
        flint_free(o);
    }
    if (!fmpz_mpoly_is_one(g, r->ctx)) {
        for (slong i = 0; i < x->len; i++)
            exact_div(x->terms[i].num, x->terms[i].num, g, r);
        exact_div(x->den, x->den, g, r);
    }
    if (lc_negative(x->den)) {
        for (slong i = 0; i < x->len; i++)
            fmpz_mpoly_neg(x->terms[i].num, x->terms[i].num, r->ctx);
        fmpz_mpoly_neg(x->den, x->den, r->ctx);
    }
    fmpz_mpoly_clear(g, r->ctx);
}

int pteq_divide_known(PointEq x, const fmpz_mpoly_t f, const Ring *r)
{
    slong n = x->len, q;
    fmpz_mpoly_struct *quo;
    slong *o;
    if (fmpz_mpoly_is_fmpz(f, r->ctx) || n == 0)
        return 0;
    o = by_length(x);
    quo = flint_malloc((size_t)(n + 1) * sizeof(fmpz_mpoly_struct));
    for (q = 0; q <= n; q++) {
        const fmpz_mpoly_struct *a = q < n ? x->terms[o[q]].num : x->den;
        fmpz_mpoly_init(quo + q, r->ctx);
        if (!fmpz_mpoly_divides(quo + q, a, f, r->ctx))
            break;
    }
    int all = q > n;
    if (all) {
        for (slong i = 0; i < n; i++)
            fmpz_mpoly_swap(x->terms[o[i]].num, quo + i, r->ctx);
        fmpz_mpoly_swap(x->den, quo + n, r->ctx);
    }
    for (slong i = 0; i < (all ? n + 1 : q + 1); i++)
        fmpz_mpoly_clear(quo + i, r->ctx);
    flint_free(quo);
    flint_free(o);
    return all;
}

int pteq_is_canonical(const PointEq x, const Ring *r)
{
    int ok = x->len <= x->alloc && !fmpz_mpoly_is_zero(x->den, r->ctx) &&
             !lc_negative(x->den);
    fmpz_mpoly_t g;

    for (slong i = 0; i < x->len && ok; i++) {
        if (i > 0 && x->terms[i - 1].point >= x->terms[i].point)
            ok = 0;
        if (x->terms[i].point < 0 ||
            fmpz_mpoly_is_zero(x->terms[i].num, r->ctx))
            ok = 0;
    }
    if (!ok)
        return 0;
    if (x->len == 0)
        return fmpz_mpoly_is_one(x->den, r->ctx);
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_set(g, x->den, r->ctx);
    for (slong i = 0; i < x->len; i++)
        if (!fmpz_mpoly_gcd(g, g, x->terms[i].num, r->ctx))
            ok = 0;
    ok = ok && fmpz_mpoly_is_one(g, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
    return ok;
}

/* ---- weights ---------------------------------------------------------- */

int pteq_has_point(const PointEq x, slong point)
{
    slong k = find(x, point);
    return k < x->len && x->terms[k].point == point;
}

void pteq_weight_view(RatFunStruct *v, const PointEq x, slong i)
{
    v->num[0] = x->terms[i].num[0];
    v->den[0] = x->den[0];
}

void pteq_get_weight(RatFun res, const PointEq x, slong point, const Ring *r)
{
    slong k = find(x, point);
    if (k < x->len && x->terms[k].point == point) {
        fmpz_mpoly_set(res->num, x->terms[k].num, r->ctx);
        fmpz_mpoly_set(res->den, x->den, r->ctx);
        ratfun_canonicalise(res, r); /* den != 0 */
    } else {
        ratfun_zero(res, r);
    }
}

void pteq_get_weights(RatFunStruct *w, const PointEq x, const Ring *r)
{
    for (slong i = 0; i < x->len; i++) {
        fmpz_mpoly_set(w[i].num, x->terms[i].num, r->ctx);
        fmpz_mpoly_set(w[i].den, x->den, r->ctx);
        ratfun_canonicalise(w + i, r);
    }
}

/* lcm of the weights' dens; each numerator is scaled by lcm/den.  The
 * result is primitive without a further gcd: a prime power of the lcm comes
 * whole from some den_i, and num_i is coprime to den_i. */
void pteq_set_weights(PointEq res, const slong *points, const RatFunStruct *w,
                      slong n, const Ring *r)
{
    PointEq acc;
    fmpz_mpoly_t g, q;
    slong *ord = flint_malloc((size_t)FLINT_MAX(n, 1) * sizeof(slong));
    slong m = 0;

    pteq_init(acc, r);
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    for (slong i = 0; i < n; i++) { /* non-zero weights, sorted by point */
        if (ratfun_is_zero(w + i, r))
            continue;
        slong j = m++;
        for (; j > 0 && points[ord[j - 1]] > points[i]; j--)
            ord[j] = ord[j - 1];
        ord[j] = i;
    }
    for (slong k = 0; k < m; k++) { /* acc->den = lcm */
        const fmpz_mpoly_struct *d = w[ord[k]].den;
        if (fmpz_mpoly_equal(acc->den, d, r->ctx) ||
            fmpz_mpoly_is_one(d, r->ctx))
            continue;
        ratfun_poly_gcd(g, acc->den, d, r);
        exact_div(q, d, g, r);
        fmpz_mpoly_mul(acc->den, acc->den, q, r->ctx);
    }
    for (slong k = 0; k < m; k++) {
        const RatFunStruct *wi = w + ord[k];
        fmpz_mpoly_struct *num = pteq_append(acc, points[ord[k]], r);
        exact_div(q, acc->den, wi->den, r);
        fmpz_mpoly_mul(num, wi->num, q, r->ctx);
    }
    pteq_swap(res, acc, r);
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
    pteq_clear(acc, r);
    flint_free(ord);
}

/* the reduced weights of x, with their points, for the per-weight paths */
static RatFunStruct *weights_of(slong **points, const PointEq x, const Ring *r)
{
    RatFunStruct *w =
        flint_malloc((size_t)FLINT_MAX(x->len + 1, 1) * sizeof(RatFunStruct));
    *points = flint_malloc((size_t)(x->len + 1) * sizeof(slong));
    for (slong i = 0; i <= x->len; i++)
        ratfun_init(w + i, r);
    pteq_get_weights(w, x, r);
    for (slong i = 0; i < x->len; i++)
        (*points)[i] = x->terms[i].point;
    return w;
}

static void weights_free(RatFunStruct *w, slong *points, slong n, const Ring *r)
{
    for (slong i = 0; i <= n; i++)
        ratfun_clear(w + i, r);
    flint_free(w);
    flint_free(points);
}

void pteq_set_weight(PointEq x, slong point, const RatFun w, const Ring *r)
{
    slong *pts, n0 = x->len, n = x->len, k = find(x, point);
    RatFunStruct *ws = weights_of(&pts, x, r);

    if (k < n && pts[k] == point) {
        ratfun_set(ws + k, w, r);
    } else {
        pts[n] = point;
        ratfun_set(ws + n, w, r);
        n++;
    }
    pteq_set_weights(x, pts, ws, n, r);
    weights_free(ws, pts, n0, r);
}

int pteq_is_zero(const PointEq x, const Ring *r)
{
    (void)r;
    return x->len == 0;
}

int pteq_equal(const PointEq x, const PointEq y, const Ring *r)
{
    if (x->len != y->len || !fmpz_mpoly_equal(x->den, y->den, r->ctx))
        return 0;
    for (slong i = 0; i < x->len; i++)
        if (x->terms[i].point != y->terms[i].point ||
            !fmpz_mpoly_equal(x->terms[i].num, y->terms[i].num, r->ctx))
            return 0;
    return 1;
}

/* one gcd at most: for a point the numerators sum to the den itself */
void pteq_weight_sum(RatFun res, const PointEq x, const Ring *r)
{
    RatFun acc;

    ratfun_init(acc, r);
    for (slong i = 0; i < x->len; i++)
        fmpz_mpoly_add(acc->num, acc->num, x->terms[i].num, r->ctx);
    if (fmpz_mpoly_equal(acc->num, x->den, r->ctx)) {
        ratfun_one(acc, r);
    } else if (!fmpz_mpoly_is_zero(acc->num, r->ctx)) {
        fmpz_mpoly_set(acc->den, x->den, r->ctx);
        ratfun_canonicalise(acc, r); /* den != 0 */
    }
    ratfun_swap(res, acc, r);
    ratfun_clear(acc, r);
}

/* ---- arithmetic ------------------------------------------------------- */

void pteq_neg(PointEq res, const PointEq x, const Ring *r)
{
    pteq_set(res, x, r);
    for (slong i = 0; i < res->len; i++)
        fmpz_mpoly_neg(res->terms[i].num, res->terms[i].num, r->ctx);
}

/* x*(a/b) with x primitive and a/b reduced: gcd(a*N, b*d) is
 * gcd(a, d)*gcd(b, N) (a prime of d divides no N_i entirely, and one of a
 * and b at most), so two gcds of the small scalar replace a reduction of
 * the whole equation. */
void pteq_scalar_mul(PointEq res, const PointEq x, const RatFun s,
                     const Ring *r)
{
    fmpz_mpoly_t a, b, g;

    if (ratfun_is_zero(s, r)) {
        pteq_zero(res, r);
        return;
    }
    if (ratfun_is_one(s, r)) {
        pteq_set(res, x, r);
        return;
    }
    fmpz_mpoly_init(a, r->ctx);
    fmpz_mpoly_init(b, r->ctx);
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_set(a, s->num, r->ctx); /* s may live inside res */
    fmpz_mpoly_set(b, s->den, r->ctx);
    pteq_set(res, x, r);
    if (res->len == 0)
        goto cleanup;
    /* a/g1 over d/g1 */
    ratfun_poly_gcd(g, a, res->den, r);
    if (!fmpz_mpoly_is_one(g, r->ctx)) {
        exact_div(a, a, g, r);
        exact_div(res->den, res->den, g, r);
    }
    /* b/g2 against the numerators' content */
    fmpz_mpoly_set(g, b, r->ctx);
    for (slong i = 0; i < res->len && !fmpz_mpoly_is_one(g, r->ctx); i++)
        ratfun_poly_gcd(g, g, res->terms[i].num, r);
    if (!fmpz_mpoly_is_one(g, r->ctx)) {
        exact_div(b, b, g, r);
        for (slong i = 0; i < res->len; i++)
            exact_div(res->terms[i].num, res->terms[i].num, g, r);
    }
    for (slong i = 0; i < res->len; i++)
        if (!fmpz_mpoly_is_one(a, r->ctx))
            fmpz_mpoly_mul(res->terms[i].num, res->terms[i].num, a, r->ctx);
    if (!fmpz_mpoly_is_one(b, r->ctx))
        fmpz_mpoly_mul(res->den, res->den, b, r->ctx);
    if (lc_negative(res->den)) {
        for (slong i = 0; i < res->len; i++)
            fmpz_mpoly_neg(res->terms[i].num, res->terms[i].num, r->ctx);
        fmpz_mpoly_neg(res->den, res->den, r->ctx);
    }
cleanup:
    fmpz_mpoly_clear(g, r->ctx);
    fmpz_mpoly_clear(b, r->ctx);
    fmpz_mpoly_clear(a, r->ctx);
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

/* ma = m * a (m == NULL: 1); products by 1 are copies */
static void mul_opt(fmpz_mpoly_t ma, const fmpz_mpoly_struct *m,
                    const fmpz_mpoly_t a, const Ring *r)
{
    if (m == NULL || fmpz_mpoly_is_one(m, r->ctx))
        fmpz_mpoly_set(ma, a, r->ctx);
    else if (fmpz_mpoly_is_one(a, r->ctx))
        fmpz_mpoly_set(ma, m, r->ctx);
    else
        fmpz_mpoly_mul(ma, m, a, r->ctx);
}

/*
 * res = x*(a/b) + y*(c/e).  Over F1 = b*dx and F2 = e*dy: the common
 * denominator is lcm(F1, F2) = F1*(F2/g), g = gcd(F1, F2); x's numerators
 * are multiplied by a*(F2/g), y's by c*(F1/g), and one content reduction
 * makes the sum primitive.  s == NULL or u == NULL stands for 1.
 */
static void lincomb(PointEq res, const PointEq x, const RatFunStruct *s,
                    const PointEq y, const RatFunStruct *u, const Ring *r)
{
    PointEq acc;
    fmpz_mpoly_t f1, f2, g, mx, my, t;
    const fmpz_mpoly_struct *px = NULL, *py = NULL;
    slong i = 0, j = 0;

    pteq_init(acc, r);
    fmpz_mpoly_init(f1, r->ctx);
    fmpz_mpoly_init(f2, r->ctx);
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_init(mx, r->ctx);
    fmpz_mpoly_init(my, r->ctx);
    fmpz_mpoly_init(t, r->ctx);
    mul_opt(f1, s ? s->den : NULL, x->den, r);
    mul_opt(f2, u ? u->den : NULL, y->den, r);
    if (fmpz_mpoly_equal(f1, f2, r->ctx)) {
        fmpz_mpoly_set(acc->den, f1, r->ctx);
        px = s ? s->num : NULL;
        py = u ? u->num : NULL;
    } else {
        ratfun_poly_gcd(g, f1, f2, r);
        exact_div(t, f2, g, r); /* F2/g */
        mul_opt(mx, s ? s->num : NULL, t, r);
        fmpz_mpoly_mul(acc->den, f1, t, r->ctx);
        exact_div(t, f1, g, r); /* F1/g */
        mul_opt(my, u ? u->num : NULL, t, r);
        px = mx;
        py = my;
    }
    while (i < x->len || j < y->len) {
        slong pi = i < x->len ? x->terms[i].point : WORD_MAX;
        slong pj = j < y->len ? y->terms[j].point : WORD_MAX;
        fmpz_mpoly_struct *num = pteq_append(acc, FLINT_MIN(pi, pj), r);
        if (pi <= pj)
            mul_opt(num, px, x->terms[i].num, r);
        else
            fmpz_mpoly_zero(num, r->ctx);
        if (pj <= pi) {
            mul_opt(t, py, y->terms[j].num, r);
            fmpz_mpoly_add(num, num, t, r->ctx);
        }
        i += pi <= pj;
        j += pj <= pi;
    }
    pteq_canonicalise(acc, r);
    pteq_swap(res, acc, r);
    fmpz_mpoly_clear(t, r->ctx);
    fmpz_mpoly_clear(my, r->ctx);
    fmpz_mpoly_clear(mx, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
    fmpz_mpoly_clear(f2, r->ctx);
    fmpz_mpoly_clear(f1, r->ctx);
    pteq_clear(acc, r);
}

void pteq_lincomb(PointEq res, const PointEq x, const RatFun s, const PointEq y,
                  const RatFun u, const Ring *r)
{
    lincomb(res, x, ratfun_is_one(s, r) ? NULL : s, y,
            ratfun_is_one(u, r) ? NULL : u, r);
}

void pteq_add(PointEq res, const PointEq x, const PointEq y, const Ring *r)
{
    lincomb(res, x, NULL, y, NULL, r);
}

void pteq_sub(PointEq res, const PointEq x, const PointEq y, const Ring *r)
{
    RatFun m;
    ratfun_init(m, r);
    ratfun_set_si(m, -1, r);
    lincomb(res, x, NULL, y, m, r);
    ratfun_clear(m, r);
}

void pteq_addmul(PointEq res, const PointEq x, const PointEq y, const RatFun s,
                 const Ring *r)
{
    if (ratfun_is_zero(s, r))
        pteq_set(res, x, r);
    else
        lincomb(res, x, NULL, y, ratfun_is_one(s, r) ? NULL : s, r);
}

/* sum_{i != point} w_i X_i + w_point * p */
void pteq_subst_point(PointEq res, const PointEq x, slong point,
                      const PointEq p, const Ring *r)
{
    pteq_subst_points(res, x, &point, (const PointEq *)p, 1, r);
}

void pteq_subst_points(PointEq res, const PointEq x, const slong *cols,
                       const PointEq *p, slong k, const Ring *r)
{
    slong maxp = -1, *which;
    fmpz_mpoly_struct *acc;
    fmpz_mpoly_t L, g, f, t;
    int any = 0;

    /* which[i]: the replacement of term i of x, or -1 */
    which = flint_malloc(sizeof(slong) * (size_t)FLINT_MAX(x->len, 1));
    fmpz_mpoly_init(L, r->ctx);
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_init(f, r->ctx);
    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_one(L, r->ctx);
    for (slong i = 0; i < x->len; i++) {
        which[i] = -1;
        for (slong j = 0; j < k; j++)
            if (cols[j] == x->terms[i].point)
                which[i] = j;
        maxp = FLINT_MAX(maxp, x->terms[i].point);
        if (which[i] < 0)
            continue;
        const PointEq *pj = p + which[i];
        any = 1;
        /* L = lcm(L, den of the replacement) */
        ratfun_poly_gcd(g, L, (*pj)->den, r);
        fmpz_mpoly_divides(t, (*pj)->den, g, r->ctx);
        fmpz_mpoly_mul(L, L, t, r->ctx);
        for (slong q = 0; q < (*pj)->len; q++)
            maxp = FLINT_MAX(maxp, (*pj)->terms[q].point);
    }
    if (!any) {
        pteq_set(res, x, r);
        goto done;
    }
    acc = flint_malloc(sizeof(fmpz_mpoly_struct) * (size_t)(maxp + 1));
    for (slong q = 0; q <= maxp; q++)
        fmpz_mpoly_init(acc + q, r->ctx);
    for (slong i = 0; i < x->len; i++) {
        if (which[i] < 0) {
            fmpz_mpoly_mul(t, x->terms[i].num, L, r->ctx);
            fmpz_mpoly_add(acc + x->terms[i].point, acc + x->terms[i].point, t,
                           r->ctx);
            continue;
        }
        const PointEq *pj = p + which[i];
        /* f = n_i * L / den_j: term i's share of every point of p[j] */
        fmpz_mpoly_divides(f, L, (*pj)->den, r->ctx);
        fmpz_mpoly_mul(f, f, x->terms[i].num, r->ctx);
        for (slong q = 0; q < (*pj)->len; q++) {
            fmpz_mpoly_mul(t, f, (*pj)->terms[q].num, r->ctx);
            fmpz_mpoly_add(acc + (*pj)->terms[q].point,
                           acc + (*pj)->terms[q].point, t, r->ctx);
        }
    }
    {
        PointEq out;
        pteq_init(out, r);
        fmpz_mpoly_mul(out->den, x->den, L, r->ctx);
        for (slong q = 0; q <= maxp; q++)
            if (!fmpz_mpoly_is_zero(acc + q, r->ctx))
                fmpz_mpoly_swap(pteq_append(out, q, r), acc + q, r->ctx);
        pteq_canonicalise(out, r);
        pteq_swap(res, out, r);
        pteq_clear(out, r);
    }
    for (slong q = 0; q <= maxp; q++)
        fmpz_mpoly_clear(acc + q, r->ctx);
    flint_free(acc);
done:
    fmpz_mpoly_clear(t, r->ctx);
    fmpz_mpoly_clear(f, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
    fmpz_mpoly_clear(L, r->ctx);
    flint_free(which);
}

/* On the one denominator: with s = a/b, every numerator and the den as
 * b^E * p(a/b), E the largest degree in var among them, then one content
 * reduction.  The den composed to zero is a pole: some weight's reduced
 * denominator (whose lcm the den is) vanishes identically. */
int pteq_compose_var(PointEq res, const PointEq x, slong var, const RatFun s,
                     const Ring *r)
{
    int st = RATFUN_OK, depends = 0;
    slong e = 0, d, *deg;
    PointEq acc;
    fmpz_mpoly_t pw;

    if (fmpz_mpoly_degrees_fit_si(x->den, r->ctx)) {
        depends = fmpz_mpoly_degree_si(x->den, var, r->ctx) > 0;
        for (slong i = 0; i < x->len && !depends; i++)
            depends = fmpz_mpoly_degree_si(x->terms[i].num, var, r->ctx) > 0;
    } else {
        depends = 1;
    }
    if (!depends) {
        pteq_set(res, x, r);
        return RATFUN_OK;
    }
    pteq_init(acc, r);
    fmpz_mpoly_init(pw, r->ctx);
    deg = flint_malloc((size_t)(x->len + 1) * sizeof(slong));
    for (slong i = 0; i <= x->len && st == RATFUN_OK; i++) {
        const fmpz_mpoly_struct *p = i < x->len ? x->terms[i].num : x->den;
        fmpz_mpoly_struct *out =
            i < x->len ? pteq_append(acc, x->terms[i].point, r) : acc->den;
        if (!ratfun_poly_compose_homog(out, deg + i, p, var, s->num, s->den, r))
            st = RATFUN_EOVERFLOW;
        else
            e = FLINT_MAX(e, deg[i]);
    }
    if (st == RATFUN_OK && fmpz_mpoly_is_zero(acc->den, r->ctx))
        st = RATFUN_EPOLE;
    for (slong i = 0; i <= x->len && st == RATFUN_OK; i++) {
        fmpz_mpoly_struct *out = i < x->len ? acc->terms[i].num : acc->den;
        d = e - deg[i];
        if (d == 0 || fmpz_mpoly_is_one(s->den, r->ctx))
            continue;
        if (!fmpz_mpoly_pow_ui(pw, s->den, (ulong)d, r->ctx)) {
            st = RATFUN_EOVERFLOW;
            break;
        }
        fmpz_mpoly_mul(out, out, pw, r->ctx);
    }
    if (st == RATFUN_OK) {
        pteq_canonicalise(acc, r); /* drops t - 1 at t := 1 */
        pteq_swap(res, acc, r);
    }
    flint_free(deg);
    fmpz_mpoly_clear(pw, r->ctx);
    pteq_clear(acc, r);
    return st;
}

void pteq_derivative(PointEq res, const PointEq x, slong var, const Ring *r)
{
    pteq_derivative_n(res, x, var, 1, r);
}

/* On the one denominator, as ratfun_derivative_n does for one weight:
 * (N_j / d^(j+1))' = (N_j' d - (j+1) N_j d') / d^(j+2) for every numerator
 * at once, then one content reduction (per weight it took a gcd to reduce
 * each weight, another after differentiating it, and an lcm to put the
 * weights back over one denominator). */
void pteq_derivative_n(PointEq res, const PointEq x, slong var, ulong k,
                       const Ring *r)
{
    PointEq acc;
    fmpz_mpoly_t dd, u, v;

    if (k == 0) {
        pteq_set(res, x, r);
        return;
    }
    pteq_init(acc, r);
    fmpz_mpoly_init(dd, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    fmpz_mpoly_init(v, r->ctx);
    pteq_set(acc, x, r);
    fmpz_mpoly_derivative(dd, x->den, var, r->ctx);
    for (ulong j = 0; j < k; j++)
        for (slong i = 0; i < acc->len; i++) {
            fmpz_mpoly_struct *N = acc->terms[i].num;
            fmpz_mpoly_derivative(u, N, var, r->ctx);
            if (fmpz_mpoly_is_zero(dd, r->ctx)) {
                fmpz_mpoly_swap(N, u, r->ctx); /* constant den: d stays */
                continue;
            }
            fmpz_mpoly_mul(u, u, x->den, r->ctx);
            fmpz_mpoly_mul(v, N, dd, r->ctx);
            fmpz_mpoly_scalar_mul_ui(v, v, j + 1, r->ctx);
            fmpz_mpoly_sub(N, u, v, r->ctx);
        }
    if (!fmpz_mpoly_is_zero(dd, r->ctx))
        fmpz_mpoly_pow_ui(acc->den, x->den, k + 1, r->ctx);
    pteq_canonicalise(acc, r); /* drops the weights that were constant */
    pteq_swap(res, acc, r);
    fmpz_mpoly_clear(v, r->ctx);
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(dd, r->ctx);
    pteq_clear(acc, r);
}
