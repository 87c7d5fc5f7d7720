/*
 * kernel_calc.c - calculus through the kernels (kernel.h): dependence,
 * the total derivative by the chain rule, and substitution of a variable
 * (also inside the kernels' arguments) and of coordinates.
 *
 * d/dvar of a value is its partial derivative plus, for every kernel whose
 * argument depends on var, the partial by the kernel times the kernel's
 * derivative (sin' = cos, sqrt(a)' = sqrt(a) a'/(2a) ...).  Substitution
 * builds the image of var and of every kernel over it (sin(t) -> sin(s))
 * and composes all at once.  derive.c's diff() and subst() land here.
 */
#include "compiler/algebra/kernel_int.h"

#include <stdlib.h>

#include "base/mem.h"
#include "base/stack.h"

/* ---- dependence, derivatives ------------------------------------------- */

static int kernel_depends(const Kernels *K, const RatFun x, slong var);

static int kernel_arg_depends(const Kernels *K, const Kernel *k, slong var)
{
    if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
        return 0;
    return kernel_depends(K, k->arg, var) ||
           (k->fn == KF_ATAN2 && kernel_depends(K, k->arg2, var));
}

/* 1 when x depends on variable var, directly or through a kernel */
static int kernel_depends(const Kernels *K, const RatFun x, slong var)
{
    if (kernel_rf_has(x, var, K ? K->r : NULL))
        return 1;
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++)
        if (kernel_rf_has(x, K->k[i].var, K->r) &&
            kernel_arg_depends(K, &K->k[i], var))
            return 1;
    return 0;
}

/* does kernel i measure base point `point`? */
static int kernel_measures(const Kernels *K, slong i, slong point)
{
    const Kernel *k = &K->k[i];
    if (k->fn == KF_DIST)
        return k->pa == point || k->pb == point;
    for (slong j = 0; j < i; j++)
        if ((kernel_rf_has(k->arg, K->k[j].var, K->r) ||
             kernel_rf_has(k->arg2, K->k[j].var, K->r)) &&
            kernel_measures(K, j, point))
            return 1;
    return 0;
}

int kernel_measures_point(const Kernels *K, const PointEq x, slong point)
{
    for (slong i = 0; K && i < K->n; i++) {
        int used = kernel_poly_has(x->den, K->k[i].var, K->r);
        for (slong j = 0; j < x->len && !used; j++)
            used = kernel_poly_has(x->terms[j].num, K->k[i].var, K->r);
        if (used && kernel_measures(K, i, point))
            return 1;
    }
    return 0;
}

/* res = d k / d var for kernel k whose argument depends on var */
static int kernel_dk(Kernels *K, RatFun res, const Kernel *k0, slong var)
{
    const Ring *r = K->r;
    /* K->k never moves (cap slots allocated at once), but the values are
     * copied: kernel_apply below adds kernels */
    KernelFn fn = k0->fn;
    slong kv = k0->var, q = k0->q;
    RatFun a, b, da, db, t, u;
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(da, r);
    ratfun_init(db, r);
    ratfun_init(t, r);
    ratfun_init(u, r);
    ratfun_set(a, k0->arg, r);
    ratfun_set(b, k0->arg2, r);
    int rc = kernel_derivative(K, da, a, var);
    if (rc == 0 && fn == KF_ATAN2)
        rc = kernel_derivative(K, db, b, var);
    if (rc != 0)
        goto done;
    ratfun_gen(t, kv, r); /* the kernel itself */
    switch (fn) {
    case KF_SIN:
    case KF_SINH:
        rc = kernel_apply(K, u, fn == KF_SIN ? KF_COS : KF_COSH, a, NULL);
        ratfun_mul(res, u, da, r);
        break;
    case KF_COS:
    case KF_COSH:
        rc = kernel_apply(K, u, fn == KF_COS ? KF_SIN : KF_SINH, a, NULL);
        if (fn == KF_COS)
            ratfun_neg(u, u, r);
        ratfun_mul(res, u, da, r);
        break;
    case KF_EXP:
        ratfun_mul(res, t, da, r);
        break;
    case KF_LN:
        ratfun_div(res, da, a, r);
        break;
    case KF_SQRT:
    case KF_ROOT: /* v' = v a' / (q a) */
        ratfun_mul(res, t, da, r);
        ratfun_div(res, res, a, r);
        ratfun_set_si(u, fn == KF_SQRT ? 2 : q, r);
        ratfun_div(res, res, u, r);
        break;
    case KF_ASIN:
    case KF_ACOS: /* +-a' / sqrt(1 - a^2) */
        ratfun_mul(u, a, a, r);
        ratfun_neg(u, u, r);
        ratfun_set_si(t, 1, r);
        ratfun_add(u, u, t, r);
        rc = kernel_apply(K, u, KF_SQRT, u, NULL);
        if (rc == 0 && ratfun_div(res, da, u, r) != 0)
            rc = KERNEL_EZERO;
        if (fn == KF_ACOS)
            ratfun_neg(res, res, r);
        break;
    case KF_ATAN: /* a' / (1 + a^2) */
        ratfun_mul(u, a, a, r);
        ratfun_set_si(t, 1, r);
        ratfun_add(u, u, t, r);
        ratfun_div(res, da, u, r);
        break;
    case KF_ATAN2: /* (x y' - y x') / (x^2 + y^2), y = a, x = b */
        ratfun_mul(t, b, da, r);
        ratfun_mul(u, a, db, r);
        ratfun_sub(t, t, u, r);
        ratfun_mul(u, a, a, r);
        ratfun_mul(da, b, b, r);
        ratfun_add(u, u, da, r);
        if (ratfun_div(res, t, u, r) != 0)
            rc = KERNEL_EZERO;
        break;
    case KF_NATX:
    case KF_NATY: /* cos(psi(a)) a', sin(psi(a)) a' */
        rc = kernel_natural_dk(K, res, fn, q, a, da);
        break;
    case KF_SIGN:
    case KF_PI:
    default:
        ratfun_zero(res, r);
        break;
    }
done:
    ratfun_clear(u, r);
    ratfun_clear(t, r);
    ratfun_clear(db, r);
    ratfun_clear(da, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

int kernel_derivative(Kernels *K, RatFun res, const RatFun x, slong var)
{
    const Ring *r = K->r;
    if (stack_low()) /* d sin(sin(...)) recurses through kernel_dk */
        return KERNEL_ESTACK;
    RatFun acc, part, dk;
    ratfun_init(acc, r);
    ratfun_init(part, r);
    ratfun_init(dk, r);
    ratfun_derivative(acc, x, var, r);
    int rc = 0;
    slong n = K->n; /* kernels made while deriving do not occur in x */
    for (slong i = 0; i < n && rc == 0; i++) {
        slong kv = K->k[i].var;
        if (!kernel_rf_has(x, kv, r) || !kernel_arg_depends(K, &K->k[i], var))
            continue;
        rc = kernel_dk(K, dk, &K->k[i], var);
        if (rc != 0)
            break;
        ratfun_derivative(part, x, kv, r);
        ratfun_mul(part, part, dk, r);
        ratfun_add(acc, acc, part, r);
    }
    if (rc == 0) {
        ratfun_swap(res, acc, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(dk, r);
    ratfun_clear(part, r);
    ratfun_clear(acc, r);
    return rc;
}

typedef struct DerivCtx {
    slong var;
} DerivCtx;

static int derive_one(Kernels *K, RatFun w, void *ctx)
{
    return kernel_derivative(K, w, w, ((DerivCtx *)ctx)->var);
}

int kernel_derivative_pteq(Kernels *K, PointEq res, const PointEq x, slong var)
{
    DerivCtx c = {var};
    return kernel_map_weights(K, res, x, derive_one, &c);
}

/* ---- substitution ------------------------------------------------------- */

/* res = P with the variables v where img[v] != NULL replaced by img[v],
 * simultaneously (over the product of the images' denominators) */
static int compose_poly(Kernels *K, RatFun res, const fmpz_mpoly_t P,
                        RatFunStruct *const *img)
{
    const Ring *r = K->r;
    int rc = 0;
    slong nv = r->ctx->minfo->nvars;
    slong *deg = flint_malloc(sizeof(slong) * (size_t)nv);
    ulong *e = flint_malloc(sizeof(ulong) * (size_t)nv);
    fmpz_mpoly_degrees_si(deg, P, r->ctx);
    fmpz_mpoly_t sum, term, pw, L;
    fmpz_mpoly_init(sum, r->ctx);
    fmpz_mpoly_init(term, r->ctx);
    fmpz_mpoly_init(pw, r->ctx);
    fmpz_mpoly_init(L, r->ctx);
    fmpz_mpoly_one(L, r->ctx);
    for (slong v = 0; v < nv; v++)
        if (img[v] && deg[v] > 0) {
            fmpz_mpoly_pow_ui(pw, img[v]->den, (ulong)deg[v], r->ctx);
            fmpz_mpoly_mul(L, L, pw, r->ctx);
        }
    fmpz_t c;
    fmpz_init(c);
    for (slong v = 0; v < nv && rc == 0; v++) /* the size of one term */
        if (img[v] && deg[v] > 0 &&
            (ratfun_log2_bits_pow(img[v], deg[v], r) > RATFUN_MAX_LOG2_BITS ||
             (double)deg[v] *
                     (double)(img[v]->num->length + img[v]->den->length) >
                 (double)KERNEL_MAX_WORK_TERMS)) {
            K->why = "expression too large for the functions' identities";
            rc = KERNEL_EBIG;
        }
    for (slong i = 0; i < P->length && rc == 0; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, P, i, r->ctx);
        fmpz_mpoly_get_term_exp_ui(e, P, i, r->ctx);
        fmpz_mpoly_set_fmpz(term, c, r->ctx);
        for (slong v = 0; v < nv; v++) {
            if (!img[v]) {
                if (e[v]) {
                    fmpz_mpoly_gen(pw, v, r->ctx);
                    fmpz_mpoly_pow_ui(pw, pw, e[v], r->ctx);
                    fmpz_mpoly_mul(term, term, pw, r->ctx);
                }
                continue;
            }
            if (deg[v] <= 0)
                continue;
            if (e[v]) {
                fmpz_mpoly_pow_ui(pw, img[v]->num, e[v], r->ctx);
                fmpz_mpoly_mul(term, term, pw, r->ctx);
            }
            if ((ulong)deg[v] > e[v]) {
                fmpz_mpoly_pow_ui(pw, img[v]->den, (ulong)deg[v] - e[v],
                                  r->ctx);
                fmpz_mpoly_mul(term, term, pw, r->ctx);
            }
        }
        fmpz_mpoly_add(sum, sum, term, r->ctx);
        rc = kernel_guard(K, sum);
        if (rc == 0)
            rc = kernel_guard(K, term);
    }
    fmpz_clear(c);
    if (rc == 0) {
        fmpz_mpoly_swap(res->num, sum, r->ctx);
        fmpz_mpoly_swap(res->den, L, r->ctx);
        ratfun_canonicalise(res, r);
    }
    fmpz_mpoly_clear(L, r->ctx);
    fmpz_mpoly_clear(pw, r->ctx);
    fmpz_mpoly_clear(term, r->ctx);
    fmpz_mpoly_clear(sum, r->ctx);
    flint_free(e);
    flint_free(deg);
    return rc;
}

static int compose_img(Kernels *K, RatFun res, const RatFun x,
                       RatFunStruct *const *img)
{
    const Ring *r = K->r;
    RatFun n, d;
    ratfun_init(n, r);
    ratfun_init(d, r);
    int rc = compose_poly(K, n, x->num, img);
    if (rc == 0)
        rc = compose_poly(K, d, x->den, img);
    if (rc == 0)
        rc = ratfun_div(res, n, d, r) == 0 ? 0 : RATFUN_EPOLE;
    ratfun_clear(d, r);
    ratfun_clear(n, r);
    return rc;
}

int kernel_remake(Kernels *K, RatFun res, KernelFn f, slong q, RatFun x,
                  RatFun y)
{
    int rc = kernel_reduce(K, x);
    if (rc == 0 && f == KF_ATAN2)
        rc = kernel_reduce(K, y);
    if (rc != 0)
        return rc;
    if (f == KF_ROOT)
        return kernel_pow_q(K, res, x, 1, q);
    if (f == KF_NATX || f == KF_NATY)
        return kernel_natural(K, res, f, kernels_law(K, q), x);
    return kernel_apply(K, res, f, x, f == KF_ATAN2 ? y : NULL);
}

/* the images of var := s and of every kernel depending on var; NULL
 * entries stay */
static int build_images(Kernels *K, RatFunStruct **img, slong var,
                        const RatFun s)
{
    const Ring *r = K->r;
    img[var] = ratfun_vec_init(1, r);
    ratfun_set(img[var], s, r);
    slong n = K->n;
    int rc = 0;
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < n && rc == 0; i++) {
        if (!kernel_arg_depends(K, &K->k[i], var))
            continue;
        KernelFn fn = K->k[i].fn;
        slong q = K->k[i].q, kv = K->k[i].var;
        rc = compose_img(K, a, K->k[i].arg, img);
        if (rc == 0 && fn == KF_ATAN2)
            rc = compose_img(K, b, K->k[i].arg2, img);
        if (rc != 0)
            break;
        RatFunStruct *v = ratfun_vec_init(1, r);
        rc = kernel_remake(K, v, fn, q, a, b);
        img[kv] = v;
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

static void free_images(RatFunStruct **img, slong nv, const Ring *r)
{
    for (slong v = 0; v < nv; v++)
        if (img[v])
            ratfun_vec_clear(img[v], 1, r);
    pc_free(img);
}

int kernel_compose(Kernels *K, RatFun res, const RatFun x, slong var,
                   const RatFun s)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int rc = build_images(K, img, var, s);
    if (rc == 0)
        rc = compose_img(K, res, x, img);
    if (rc == 0)
        rc = kernel_reduce(K, res);
    free_images(img, nv, r);
    return rc;
}

typedef struct ComposeCtx {
    RatFunStruct **img;
} ComposeCtx;

static int compose_one(Kernels *K, RatFun w, void *ctx)
{
    int rc = compose_img(K, w, w, ((ComposeCtx *)ctx)->img);
    return rc ? rc : kernel_reduce(K, w);
}

int kernel_compose_pteq(Kernels *K, PointEq res, const PointEq x, slong var,
                        const RatFun s)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int rc = build_images(K, img, var, s);
    ComposeCtx c = {img};
    if (rc == 0)
        rc = kernel_map_weights(K, res, x, compose_one, &c);
    free_images(img, nv, r);
    return rc;
}

/* the images of every coord(A_point, k) that x uses (x a RatFun, or a
 * PointEq when xp is not NULL): coord(P, k); and of every kernel whose
 * argument depends on one.  *any = 0 when x uses none. */
static int coord_images(Kernels *K, RatFunStruct **img, const RatFun x,
                        const PointEq xp, slong point, const PointEq P,
                        int *any)
{
    const Ring *r = K->r;
    slong n = K->n; /* the coordinates of P's points are made below */
    int rc = 0;
    *any = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_COORD || k->pa != point)
            continue;
        int used = 0;
        if (xp) {
            for (slong j = 0; j < xp->len && !used; j++) {
                RatFunStruct w;
                pteq_weight_view(&w, xp, j);
                used = kernel_depends(K, &w, k->var);
            }
        } else {
            used = kernel_depends(K, x, k->var);
        }
        if (!used)
            continue;
        for (slong j = 0; j < P->len && rc == 0; j++)
            if (P->terms[j].point >= K->npoints) {
                K->why = "coord() of an unknown point: this replacement "
                         "has an unsolved unknown point, and the expression "
                         "uses coordinates of the point it replaces; solve "
                         "it first";
                rc = KERNEL_EDOMAIN;
            }
        if (rc != 0)
            break;
        *any = 1;
        slong kv = k->var, kk = k->pb;
        img[kv] = ratfun_vec_init(1, r);
        rc = kernel_coord_pteq(K, img[kv], P, kk);
    }
    /* the kernels over them, in order (their arguments use earlier
     * variables only) */
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < n && rc == 0 && *any; i++) {
        const Kernel *k = &K->k[i];
        int dep = 0;
        if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
            continue;
        for (slong j = 0; j < i && !dep; j++)
            dep = img[K->k[j].var] && (kernel_rf_has(k->arg, K->k[j].var, r) ||
                                       kernel_rf_has(k->arg2, K->k[j].var, r));
        if (!dep)
            continue;
        KernelFn fn = k->fn;
        slong q = k->q, kv = k->var;
        rc = compose_img(K, a, k->arg, img);
        if (rc == 0 && fn == KF_ATAN2)
            rc = compose_img(K, b, k->arg2, img);
        if (rc != 0)
            break;
        RatFunStruct *v = ratfun_vec_init(1, r);
        img[kv] = v;
        rc = kernel_remake(K, v, fn, q, a, b);
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

int kernel_subst_coords(Kernels *K, RatFun res, const RatFun x, slong point,
                        const PointEq P)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int any;
    int rc = coord_images(K, img, x, NULL, point, P, &any);
    if (rc == 0 && any)
        rc = compose_img(K, res, x, img);
    else if (rc == 0)
        ratfun_set(res, x, r);
    if (rc == 0 && any)
        rc = kernel_reduce(K, res);
    free_images(img, nv, r);
    return rc;
}

int kernel_subst_coords_pteq(Kernels *K, PointEq res, const PointEq x,
                             slong point, const PointEq P)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int any;
    int rc = coord_images(K, img, NULL, x, point, P, &any);
    ComposeCtx c = {img};
    if (rc == 0 && any)
        rc = kernel_map_weights(K, res, x, compose_one, &c);
    else if (rc == 0)
        pteq_set(res, x, r);
    free_images(img, nv, r);
    return rc;
}
