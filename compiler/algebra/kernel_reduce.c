/*
 * kernel_reduce.c - the normal form modulo the kernels' relations
 * (kernel.h: kernel_reduce, kernel_uses).
 *
 * Some kernels carry a relation v^q = rel (cos^2 = 1 - sin^2, sqrt(a)^2 =
 * a, sign^2 = 1).  A value is reduced from the last such kernel down:
 * every power v^k (k >= q) is rewritten by the relation, and a
 * denominator linear in a quadratic kernel is rationalised by its
 * conjugate.  Every operation of kernel_fold.c, kernel_sqrt.c and
 * kernel_calc.c ends here; derive.c reduces what it combines.
 */
#include "compiler/algebra/kernel_int.h"

#include <stdlib.h>

#include "base/mem.h"

/* ---- normal form -------------------------------------------------------- */

/* res = P with var^k (k >= q) rewritten by var^q = rel, as a RatFun */
static int reduce_poly(Kernels *K, RatFun res, const fmpz_mpoly_t P,
                       const Kernel *k)
{
    const Ring *r = K->r;
    slong d = fmpz_mpoly_degree_si(P, k->var, r->ctx);
    if (d < k->deg) {
        fmpz_mpoly_set(res->num, P, r->ctx);
        fmpz_mpoly_one(res->den, r->ctx);
        return 0;
    }
    if (ratfun_log2_bits_pow(k->rel, d / k->deg, r) > RATFUN_MAX_LOG2_BITS) {
        K->why = "expression too large for the functions' identities";
        return KERNEL_EBIG;
    }
    int rc = 0;
    RatFun acc, term, relp;
    fmpz_mpoly_t C;
    ratfun_init(acc, r);
    ratfun_init(term, r);
    ratfun_init(relp, r);
    fmpz_mpoly_init(C, r->ctx);
    slong var = k->var;
    for (slong j = 0; j <= d && rc == 0; j++) {
        ulong ju = (ulong)j;
        fmpz_mpoly_get_coeff_vars_ui(C, P, &var, &ju, 1, r->ctx);
        if (fmpz_mpoly_is_zero(C, r->ctx))
            continue;
        /* C * rel^(j / q) * var^(j % q) */
        fmpz_mpoly_gen(term->num, var, r->ctx);
        fmpz_mpoly_pow_ui(term->num, term->num, (ulong)(j % k->deg), r->ctx);
        fmpz_mpoly_mul(term->num, term->num, C, r->ctx);
        fmpz_mpoly_one(term->den, r->ctx);
        ratfun_canonicalise(term, r);
        if (j >= k->deg) {
            ratfun_pow_si(relp, k->rel, j / k->deg, r);
            if (ratfun_log2_bits_product(term, relp, r) >
                RATFUN_MAX_LOG2_BITS) {
                K->why = "expression too large for the functions' identities";
                rc = KERNEL_EBIG;
                break;
            }
            ratfun_mul(term, term, relp, r);
        }
        ratfun_add(acc, acc, term, r);
        rc = kernel_guard(K, acc->num);
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    fmpz_mpoly_clear(C, r->ctx);
    ratfun_clear(relp, r);
    ratfun_clear(term, r);
    ratfun_clear(acc, r);
    return rc;
}

int kernel_uses(const Kernels *K, const RatFun x, int any)
{
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++)
        if ((any || K->k[i].deg) && kernel_rf_has(x, K->k[i].var, K->r))
            return 1;
    return 0;
}

int kernel_uses_pteq(const Kernels *K, const PointEq x, int any)
{
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++) {
        if (!any && !K->k[i].deg)
            continue;
        if (kernel_poly_has(x->den, K->k[i].var, K->r))
            return 1;
        for (slong j = 0; j < x->len; j++)
            if (kernel_poly_has(x->terms[j].num, K->k[i].var, K->r))
                return 1;
    }
    return 0;
}

int kernel_reduce(Kernels *K, RatFun x)
{
    if (!K || K->nrel == 0)
        return 0;
    const Ring *r = K->r;
    RatFun n, d, A, B;
    ratfun_init(n, r);
    ratfun_init(d, r);
    ratfun_init(A, r);
    ratfun_init(B, r);
    int rc = 0;
    for (slong i = K->n - 1; i >= 0 && rc == 0; i--) {
        const Kernel *k = &K->k[i];
        if (!k->deg || !kernel_rf_has(x, k->var, r))
            continue;
        rc = reduce_poly(K, n, x->num, k);
        if (rc == 0)
            rc = reduce_poly(K, d, x->den, k);
        if (rc != 0)
            break;
        if (ratfun_div(x, n, d, r) != 0) {
            rc = KERNEL_EZERO;
            break;
        }
        if (k->deg != 2 || !kernel_poly_has(x->den, k->var, r))
            continue;
        /* den = A + B v: multiply by A - B v; den becomes A^2 - B^2 rel */
        slong var = k->var;
        ulong e0 = 0, e1 = 1;
        fmpz_mpoly_get_coeff_vars_ui(A->num, x->den, &var, &e0, 1, r->ctx);
        fmpz_mpoly_one(A->den, r->ctx);
        fmpz_mpoly_get_coeff_vars_ui(B->num, x->den, &var, &e1, 1, r->ctx);
        fmpz_mpoly_one(B->den, r->ctx);
        ratfun_canonicalise(A, r);
        ratfun_canonicalise(B, r);
        RatFun conj, v;
        ratfun_init(conj, r);
        ratfun_init(v, r);
        ratfun_gen(v, var, r);
        ratfun_mul(conj, B, v, r);
        ratfun_sub(conj, A, conj, r);
        /* new numerator: num * conj (a polynomial), reduced */
        fmpz_mpoly_set(n->num, x->num, r->ctx);
        fmpz_mpoly_one(n->den, r->ctx);
        ratfun_canonicalise(n, r);
        ratfun_mul(n, n, conj, r);
        {
            RatFun red;
            ratfun_init(red, r);
            rc = reduce_poly(K, red, n->num, k);
            ratfun_swap(n, red, r);
            ratfun_clear(red, r);
        }
        /* new denominator: A^2 - B^2 rel */
        ratfun_mul(A, A, A, r);
        ratfun_mul(B, B, B, r);
        ratfun_mul(B, B, k->rel, r);
        ratfun_sub(d, A, B, r);
        ratfun_clear(v, r);
        ratfun_clear(conj, r);
        if (rc == 0 && ratfun_div(x, n, d, r) != 0)
            rc = KERNEL_EZERO;
        if (rc == 0)
            rc = kernel_guard(K, x->num);
    }
    ratfun_clear(B, r);
    ratfun_clear(A, r);
    ratfun_clear(d, r);
    ratfun_clear(n, r);
    if (rc == KERNEL_EZERO)
        K->why = "a denominator vanishes identically by the functions' "
                 "identities";
    return rc;
}

/* applies f to every weight of x and rebuilds x over one denominator */
int kernel_map_weights(Kernels *K, PointEq res, const PointEq x,
                       KernelWeightFn f, void *ctx)
{
    const Ring *r = K->r;
    slong n = x->len;
    RatFunStruct *w = ratfun_vec_init(n, r);
    slong *pts = pc_xmalloc(sizeof(slong) * (size_t)(n ? n : 1));
    pteq_get_weights(w, x, r);
    int rc = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        pts[i] = x->terms[i].point;
        rc = f(K, w + i, ctx);
    }
    if (rc == 0)
        pteq_set_weights(res, pts, w, n, r);
    pc_free(pts);
    ratfun_vec_clear(w, n, r);
    return rc;
}

static int reduce_one(Kernels *K, RatFun w, void *ctx)
{
    (void)ctx;
    return kernel_reduce(K, w);
}

int kernel_reduce_pteq(Kernels *K, PointEq x)
{
    if (!K || K->nrel == 0 || !kernel_uses_pteq(K, x, 0))
        return 0;
    return kernel_map_weights(K, x, x, reduce_one, NULL);
}
