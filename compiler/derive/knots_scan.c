/*
 * knots_scan.c - the zeros of a composite curve's sign kernels and the
 * exact substitutions the knots need (knots.h, knots_int.h): which kernels
 * depend on the param, the zeros of their arguments (factoring over Q,
 * or the root of a linear argument), the value of a weight at a knot
 * through the kernels it uses only, and the one-sided forms of a knot,
 * with every sign kernel of t replaced by a number.  knots.c compares
 * their derivatives.
 */
#include "compiler/derive/knots_int.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"

/* ---- which kernels depend on what ------------------------------------- */

/* 1 when polynomial p has variable v */
static int has_var(const fmpz_mpoly_t p, slong v, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, v, r->ctx) > 0;
}

static int rf_has(const RatFunStruct *x, slong v, const Ring *r)
{
    return has_var(x->num, v, r) || has_var(x->den, v, r);
}

/* 1 when x depends on var directly or through a kernel (dep: per kernel,
 * its argument does) */
int knots_uses(const Kernels *K, const unsigned char *dep,
               const RatFunStruct *x, slong var)
{
    if (rf_has(x, var, K->r))
        return 1;
    for (slong i = 0; i < K->n; i++)
        if (dep[i] && rf_has(x, K->k[i].var, K->r))
            return 1;
    return 0;
}

/* dep[i] = 1 when kernel i's argument depends on var (arguments use only
 * the variables before the kernel, so one pass in order suffices) */
void knots_fill_dep(const Kernels *K, unsigned char *dep, slong var)
{
    memset(dep, 0, (size_t)K->n + 1);
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        dep[i] = 0;
        if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
            continue;
        dep[i] = (unsigned char)(knots_uses(K, dep, k->arg, var) ||
                                 (k->fn == KF_ATAN2 &&
                                  knots_uses(K, dep, k->arg2, var)));
    }
}

/* used[i] = 1 for every kernel that one of xs[0..nx-1] uses, directly or
 * inside another used kernel's argument */
void knots_fill_used(const Kernels *K, unsigned char *used,
                     const RatFunStruct *xs, slong nx)
{
    for (slong i = 0; i < K->n; i++) {
        used[i] = 0;
        for (slong j = 0; j < nx && !used[i]; j++)
            used[i] = (unsigned char)rf_has(xs + j, K->k[i].var, K->r);
    }
    for (slong i = K->n - 1; i >= 0; i--) {
        if (!used[i])
            continue;
        const Kernel *k = &K->k[i];
        for (slong j = 0; j < i; j++)
            if (rf_has(k->arg, K->k[j].var, K->r) ||
                (k->fn == KF_ATAN2 && rf_has(k->arg2, K->k[j].var, K->r)))
                used[j] = 1;
    }
}

/* ---- the zeros of one sign kernel --------------------------------------- */

static void add_zero(Scan *S, slong var, const RatFun root, int right, int left)
{
    if (S->nz == S->zalloc) {
        S->zalloc = S->zalloc ? 2 * S->zalloc : 8;
        S->z = pc_xrealloc(S->z, (size_t)S->zalloc * sizeof *S->z);
    }
    Zero *z = &S->z[S->nz++];
    z->var = var;
    ratfun_init(z->root, S->r);
    ratfun_set(z->root, root, S->r);
    z->right = right;
    z->left = left;
}

/* 1 when polynomial p uses no variable but t */
static int only_t(const fmpz_mpoly_t p, slong t, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    for (slong v = 0; v < nv; v++)
        if (v != t && has_var(p, v, r))
            return 0;
    return 1;
}

/* sign of the polynomial q (in t alone, as an fmpz_poly) at r */
static int poly_sign_at(const fmpz_poly_t q, const fmpq_t r)
{
    fmpq_t v;
    fmpq_init(v);
    fmpz_poly_evaluate_fmpq(v, q, r);
    int s = fmpq_sgn(v);
    fmpq_clear(v);
    return s;
}

/* The zeros of a = pn/pd, both polynomials in t alone: every rational root
 * r of either, a = (c*(t - r))^m * rest with rest(r) != 0, so just right
 * of r sign(a) = sign(c)^m sign(rest(r)), and just left (-1)^m times that.
 * Returns 0, or -1 when an irreducible factor of degree >= 2 has real
 * roots (irrational zeros: not analysed) or the degree is too high. */
static int zeros_in_t(Scan *S, slong var, const fmpz_poly_t pn,
                      const fmpz_poly_t pd)
{
    if (fmpz_poly_degree(pn) > KNOTS_MAX_FACTOR_DEGREE ||
        fmpz_poly_degree(pd) > KNOTS_MAX_FACTOR_DEGREE)
        return -1;
    int rc = 0;
    fmpz_poly_factor_t f;
    fmpz_poly_t rest, pw;
    fmpq_t root;
    RatFun rt;
    fmpz_poly_factor_init(f);
    fmpz_poly_init(rest);
    fmpz_poly_init(pw);
    fmpq_init(root);
    ratfun_init(rt, S->r);
    for (int side = 0; side < 2 && rc == 0; side++) {
        const fmpz_poly_struct *p = side ? pd : pn, *o = side ? pn : pd;
        if (fmpz_poly_degree(p) < 1)
            continue;
        fmpz_poly_factor(f, p);
        for (slong i = 0; i < f->num && rc == 0; i++) {
            const fmpz_poly_struct *g = f->p + i;
            slong e = f->exp[i];
            if (fmpz_poly_degree(g) >= 2) {
                if (fmpz_poly_num_real_roots(g) > 0)
                    rc = -1;
                continue;
            }
            /* g = c1*t + c0: root -c0/c1 */
            fmpq_set_fmpz_frac(root, g->coeffs + 0, g->coeffs + 1);
            fmpq_neg(root, root);
            fmpz_poly_pow(pw, g, (ulong)e);
            fmpz_poly_div(rest, p, pw); /* exact: pw divides p */
            int s = poly_sign_at(rest, root) * poly_sign_at(o, root);
            if (e % 2 && fmpz_sgn(g->coeffs + 1) < 0)
                s = -s;
            ratfun_set_fmpq(rt, root, S->r);
            add_zero(S, var, rt, s, e % 2 ? -s : s);
        }
    }
    ratfun_clear(rt, S->r);
    fmpq_clear(root);
    fmpz_poly_clear(pw);
    fmpz_poly_clear(rest);
    fmpz_poly_factor_clear(f);
    return rc;
}

/* The zero of a = (alpha + beta*t)/delta with alpha, beta, delta free of
 * t (and of every kernel that depends on it, and of every other param):
 * -alpha/beta, where sign(a) goes from -sign(beta/delta) to sign(beta/
 * delta), when that sign is proved.  Returns 0 or -1 (not analysed). */
static int zero_linear(Scan *S, slong var, const RatFunStruct *a)
{
    const Ring *r = S->r;
    if (fmpz_mpoly_degree_si(a->num, S->t, r->ctx) != 1 ||
        has_var(a->den, S->t, r))
        return -1;
    for (slong v = 0; v < S->d->nparams; v++)
        if (v != S->t && (rf_has(a, v, r)))
            return -1;
    for (slong i = 0; i < S->K->n; i++)
        if (S->dep[i] && rf_has(a, S->K->k[i].var, r))
            return -1;
    int rc = -1;
    RatFun alpha, beta, den;
    ratfun_init(alpha, r);
    ratfun_init(beta, r);
    ratfun_init(den, r);
    ulong e0 = 0, e1 = 1;
    fmpz_mpoly_get_coeff_vars_ui(alpha->num, a->num, &S->t, &e0, 1, r->ctx);
    fmpz_mpoly_get_coeff_vars_ui(beta->num, a->num, &S->t, &e1, 1, r->ctx);
    fmpz_mpoly_one(alpha->den, r->ctx);
    fmpz_mpoly_one(beta->den, r->ctx);
    fmpz_mpoly_set(den->num, a->den, r->ctx);
    fmpz_mpoly_one(den->den, r->ctx);
    ratfun_canonicalise(alpha, r);
    ratfun_canonicalise(beta, r);
    ratfun_canonicalise(den, r);
    if (ratfun_div(den, beta, den, r) == 0) { /* den = beta/delta */
        int s = kernel_sign(S->K, den);
        if (s == 2 || s == -2) {
            ratfun_div(alpha, alpha, beta, r);
            ratfun_neg(alpha, alpha, r);
            add_zero(S, var, alpha, s > 0 ? 1 : -1, s > 0 ? -1 : 1);
            rc = 0;
        }
    }
    ratfun_clear(den, r);
    ratfun_clear(beta, r);
    ratfun_clear(alpha, r);
    return rc;
}

/* the zeros of sign kernel i, or it joins the kernels not analysed */
static void scan_sign(Scan *S, slong i)
{
    const Ring *r = S->r;
    const Kernel *k = &S->K->k[i];
    int rc = -1;
    if (only_t(k->arg->num, S->t, r) && only_t(k->arg->den, S->t, r)) {
        fmpz_poly_t pn, pd;
        fmpz_poly_init(pn);
        fmpz_poly_init(pd);
        if (fmpz_mpoly_get_fmpz_poly(pn, k->arg->num, S->t, r->ctx) &&
            fmpz_mpoly_get_fmpz_poly(pd, k->arg->den, S->t, r->ctx))
            rc = zeros_in_t(S, k->var, pn, pd);
        fmpz_poly_clear(pd);
        fmpz_poly_clear(pn);
    } else {
        rc = zero_linear(S, k->var, k->arg);
    }
    if (rc != 0) {
        /* forget the zeros found before the failure */
        while (S->nz > 0 && S->z[S->nz - 1].var == k->var)
            ratfun_clear(S->z[--S->nz].root, r);
        S->other[S->nother++] = i;
    }
}

/* Scans xs[0..nx-1] for the sign kernels that depend on param t. */
void knots_scan_init(Scan *S, const Derived *d, const RatFunStruct *xs,
                     slong nx, slong t)
{
    memset(S, 0, sizeof *S);
    S->d = d;
    S->K = d->kernels;
    S->r = &d->ring;
    S->t = t;
    slong n = S->K->n;
    S->dep = pc_xcalloc((size_t)n + 1, 1);
    S->used = pc_xcalloc((size_t)n + 1, 1);
    S->other = pc_xcalloc((size_t)n + 1, sizeof *S->other);
    knots_fill_dep(S->K, S->dep, t);
    S->nscan = n;
    knots_fill_used(S->K, S->used, xs, nx);
    for (slong i = 0; i < n; i++)
        if (S->used[i] && S->dep[i] && S->K->k[i].fn == KF_SIGN)
            scan_sign(S, i);
}

void knots_scan_clear(Scan *S)
{
    for (slong i = 0; i < S->nz; i++)
        ratfun_clear(S->z[i].root, S->r);
    pc_free(S->z);
    pc_free(S->other);
    pc_free(S->used);
    pc_free(S->dep);
}

/* ---- one-sided values ---------------------------------------------------- */

/* res = p with every variable v where has[v] replaced by the integer
 * val[v], all in one pass over p's terms: into a dense polynomial in t
 * when no other variable is left (the common case: a composite curve's
 * weight with its signs replaced), else with one sort at the end */
static void eval_ints(fmpz_mpoly_t res, const fmpz_mpoly_t p,
                      const unsigned char *has, const fmpz *val, slong t,
                      const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    ulong *e = flint_malloc(sizeof(ulong) * (size_t)nv);
    slong *deg = flint_malloc(sizeof(slong) * (size_t)nv);
    fmpz_mpoly_degrees_si(deg, p, r->ctx);
    int dense = 1;
    for (slong v = 0; v < nv; v++)
        if (v != t && !has[v] && deg[v] > 0)
            dense = 0;
    fmpz_t c, pw;
    fmpz_init(c);
    fmpz_init(pw);
    fmpz_mpoly_t acc;
    fmpz_mpoly_init(acc, r->ctx);
    fmpz_poly_t dp;
    fmpz_poly_init(dp);
    for (slong i = 0; i < p->length; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, p, i, r->ctx);
        fmpz_mpoly_get_term_exp_ui(e, p, i, r->ctx);
        for (slong v = 0; v < nv && !fmpz_is_zero(c); v++)
            if (has[v] && e[v]) {
                fmpz_pow_ui(pw, val + v, e[v]);
                fmpz_mul(c, c, pw);
                e[v] = 0;
            }
        if (fmpz_is_zero(c))
            continue;
        if (dense) {
            fmpz_poly_get_coeff_fmpz(pw, dp, (slong)e[t]);
            fmpz_add(pw, pw, c);
            fmpz_poly_set_coeff_fmpz(dp, (slong)e[t], pw);
        } else
            fmpz_mpoly_push_term_fmpz_ui(acc, c, e, r->ctx);
    }
    if (dense) {
        fmpz_mpoly_set_fmpz_poly(acc, dp, t, r->ctx);
    } else {
        fmpz_mpoly_sort_terms(acc, r->ctx);
        fmpz_mpoly_combine_like_terms(acc, r->ctx);
    }
    fmpz_mpoly_swap(res, acc, r->ctx);
    fmpz_poly_clear(dp);
    fmpz_mpoly_clear(acc, r->ctx);
    fmpz_clear(pw);
    fmpz_clear(c);
    flint_free(deg);
    flint_free(e);
}

/* res = x with every variable v that has an image img[v] replaced by it:
 * the integer images (the signs +-1 and 0, integer knots) in one pass,
 * the others one after another (ratfun_compose_var); the images are free
 * of every replaced variable */
static int compose_images(Scan *S, RatFun res, const RatFunStruct *x,
                          RatFunStruct *const *img, slong nv)
{
    const Ring *r = S->r;
    int rc = 0, nint = 0;
    unsigned char *has = pc_xcalloc((size_t)nv + 1, 1);
    fmpz *val = _fmpz_vec_init(nv);
    fmpq_t q;
    fmpq_init(q);
    for (slong v = 0; v < nv; v++)
        if (img[v] && rf_has(x, v, r) && ratfun_get_fmpq(q, img[v], r) &&
            fmpz_is_one(fmpq_denref(q))) {
            has[v] = 1;
            fmpz_set(val + v, fmpq_numref(q));
            nint++;
        }
    ratfun_set(res, x, r);
    if (nint) {
        eval_ints(res->num, res->num, has, val, S->t, r);
        eval_ints(res->den, res->den, has, val, S->t, r);
        rc = ratfun_canonicalise(res, r) == 0 ? 0 : RATFUN_EPOLE;
    }
    for (slong v = 0; v < nv && rc == 0; v++)
        if (img[v] && !has[v] && rf_has(res, v, r))
            rc = ratfun_compose_var(res, res, v, img[v], r);
    fmpq_clear(q);
    _fmpz_vec_clear(val, nv);
    pc_free(has);
    return rc;
}

/* res = x with the variables vars[0..nsub-1] := vals[0..nsub-1] (free of
 * all of them and of every kernel that depends on one), exactly: they and
 * every kernel x uses whose argument depends on one of them are replaced
 * by their values.  kernel_compose would remake every kernel of the ring
 * that depends on a variable, and a value at a knot that holds a const
 * needs a new kernel for each of them (sign(t - a) at t = b is sign(b -
 * a)); only those x uses are remade here. */
static int subst_vars(Scan *S, RatFun res, const RatFunStruct *x, slong nsub,
                      const slong *vars, const RatFunStruct *vals)
{
    const Ring *r = S->r;
    Kernels *K = S->K;
    slong n = K->n, nv = r->ctx->minfo->nvars;
    unsigned char *used = pc_xcalloc((size_t)n + 1, 1);
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    knots_fill_used(K, used, x, 1);
    for (slong i = 0; i < nsub; i++) {
        img[vars[i]] = ratfun_vec_init(1, r);
        ratfun_set(img[vars[i]], vals + i, r);
    }
    int rc = 0;
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < n && rc == 0; i++) {
        const Kernel *k = &K->k[i];
        /* a kernel replaced itself (a sign by its value) is not remade */
        if (!used[i] || img[k->var] || k->fn == KF_PI || k->fn == KF_DIST ||
            k->fn == KF_COORD)
            continue;
        /* remade when its argument holds a replaced variable (a kernel
         * remade before it counts: it has an image) */
        int dep = 0;
        for (slong v = 0; v < nv && !dep; v++)
            dep = img[v] && (rf_has(k->arg, v, r) ||
                             (k->fn == KF_ATAN2 && rf_has(k->arg2, v, r)));
        if (!dep)
            continue;
        slong kv = k->var;
        KernelFn fn = k->fn;
        slong q = k->q;
        rc = compose_images(S, a, k->arg, img, nv);
        if (rc == 0 && fn == KF_ATAN2)
            rc = compose_images(S, b, k->arg2, img, nv);
        if (rc != 0)
            break;
        /* (k may move from here on: kernel_remake can add kernels) */
        RatFunStruct *v = ratfun_vec_init(1, r);
        img[kv] = v;
        rc = kernel_remake(K, v, fn, q, a, b);
    }
    if (rc == 0)
        rc = compose_images(S, res, x, img, nv);
    if (rc == 0)
        rc = kernel_reduce(K, res);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    for (slong v = 0; v < nv; v++)
        if (img[v])
            ratfun_vec_clear(img[v], 1, r);
    pc_free(img);
    pc_free(used);
    return rc;
}

/* res = x at t = t0 (subst_vars) */
int knots_eval_at(Scan *S, RatFun res, const RatFunStruct *x,
                  const RatFunStruct *t0)
{
    return subst_vars(S, res, x, 1, &S->t, t0);
}

/* 1 when sign kernel i's argument holds a function of t (sign(sign(t -
 * 1) + 1/2), abs(t - abs(t - 2))): it need not be constant near a knot of
 * the kernels inside it */
static int nested(const Scan *S, slong i)
{
    const Kernel *k = &S->K->k[i];
    for (slong j = 0; j < i; j++)
        if (S->dep[j] && rf_has(k->arg, S->K->k[j].var, S->r))
            return 1;
    return 0;
}

/* 1 when a side form x still holds a sign kernel of t whose argument
 * vanishes at t0 (a nested one, remade on the side: abs(t - abs(t - 2))
 * left of 2 is abs(2*t - 2), which vanishes at 1), or an argument that
 * is not finite there */
static int vanishes_at(Scan *S, const RatFunStruct *x, const RatFunStruct *t0)
{
    const Ring *r = S->r;
    Kernels *K = S->K;
    slong n = K->n;
    unsigned char *used = pc_xcalloc((size_t)n + 1, 1);
    unsigned char *dep = pc_xcalloc((size_t)n + 1, 1);
    knots_fill_used(K, used, x, 1);
    knots_fill_dep(K, dep, S->t);
    RatFun a;
    ratfun_init(a, r);
    int bad = 0;
    for (slong i = 0; i < n && !bad; i++)
        if (used[i] && dep[i] && K->k[i].fn == KF_SIGN)
            bad = knots_eval_at(S, a, K->k[i].arg, t0) != 0 ||
                  ratfun_is_zero(a, r);
    ratfun_clear(a, r);
    pc_free(dep);
    pc_free(used);
    return bad;
}

/* The side forms of a knot t0: the sign kernels the values use that
 * depend on t, each replaced by a number or a value free of t - those
 * with a zero at t0 by their sign just right of it (side +1) or just left
 * (-1), the others by their exact value at t0, where they are locally
 * constant - then only t and the other functions of t are left.  A sign
 * kernel whose argument holds a function of t is remade on each side
 * instead (its argument with the inner signs replaced).  Returns
 * 0, or -1 with why set (another sign kernel vanishes at t0, or a value
 * is not finite there). */
int knots_side_forms(Scan *S, const RatFunStruct *t0, const RatFunStruct *xs,
                     slong nx, RatFunStruct *right, RatFunStruct *left,
                     const char **why)
{
    const Ring *r = S->r;
    slong nsub = 0;
    slong *vars = pc_xcalloc((size_t)S->nscan + 1, sizeof *vars);
    RatFunStruct *vr = ratfun_vec_init(S->nscan + 1, r);
    RatFunStruct *vl = ratfun_vec_init(S->nscan + 1, r);
    RatFun a;
    ratfun_init(a, r);
    int rc = 0;
    for (slong i = 0; i < S->nscan && rc == 0; i++) {
        const Kernel *k = &S->K->k[i];
        if (!S->used[i] || !S->dep[i] || k->fn != KF_SIGN)
            continue;
        slong var = k->var, j;
        for (j = 0; j < S->nz; j++)
            if (S->z[j].var == var && ratfun_equal(S->z[j].root, t0, r))
                break;
        if (j == S->nz && nested(S, i))
            continue; /* remade on each side by subst_vars, checked below */
        if (j < S->nz) {
            ratfun_set_si(vr + nsub, S->z[j].right, r);
            ratfun_set_si(vl + nsub, S->z[j].left, r);
        } else if (knots_eval_at(S, a, S->K->k[i].arg, t0) != 0) {
            rc = -1;
            *why = "a sign kernel's argument is not finite there";
        } else if (ratfun_is_zero(a, r)) {
            rc = -1;
            *why = "another argument of abs() or sign() vanishes there, "
                   "whose zeros were not analysed";
        } else if (kernel_apply(S->K, vr + nsub, KF_SIGN, a, NULL) != 0) {
            rc = -1;
            *why = "a sign kernel's value there could not be made";
        } else
            ratfun_set(vl + nsub, vr + nsub, r);
        vars[nsub++] = var;
    }
    for (slong i = 0; i < nx && rc == 0; i++) {
        if (subst_vars(S, right + i, xs + i, nsub, vars, vr) != 0 ||
            subst_vars(S, left + i, xs + i, nsub, vars, vl) != 0) {
            rc = -1;
            *why = "the one-sided forms could not be made exactly";
        } else if (vanishes_at(S, right + i, t0) ||
                   vanishes_at(S, left + i, t0)) {
            rc = -1;
            *why = "an abs() or sign() whose argument holds another one "
                   "vanishes there";
        }
    }
    ratfun_clear(a, r);
    ratfun_vec_clear(vl, S->nscan + 1, r);
    ratfun_vec_clear(vr, S->nscan + 1, r);
    pc_free(vars);
    return rc;
}
