/*
 * knots.c - the knots of a composite curve and the smoothness at each
 * (knots.h; docs/composite.md, "Knots and smoothness").
 *
 * After the derivation, on a finished output: find the sign kernels its
 * weights use (also inside other kernels' arguments) whose argument
 * depends on the param, find their zeros exactly, then at each zero
 * compare the one-sided derivatives order by order.  Everything is exact:
 * a one-sided value is the weight with the vanishing sign kernels replaced
 * by +-1, differentiated by the chain rule
 * (kernel_derivative: a sign kernel's derivative is 0 off its zero) and
 * composed with t := t_k, where the other sign kernels take their exact
 * values.  Called by the printers (format_json.c, knots_print.c).
 */
#include "compiler/derive/knots.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"
#include "compiler/algebra/kernel.h"

/* the largest degree in t of an argument whose zeros are looked for by
 * factoring (FLINT's fmpz_poly_factor is fast far beyond this) */
enum { KNOTS_MAX_FACTOR_DEGREE = 200 };
/* a one-sided form with more terms (numerator and denominator) than this
 * is not differentiated further: eight derivatives of a large rational
 * function grow like its denominator's ninth power */
enum { KNOTS_MAX_TERMS = 4000 };

/* one zero of one sign kernel: sign(a) just right and left of it */
typedef struct Zero {
    slong var;   // the sign kernel's ring variable
    RatFun root; // where a vanishes
    int right, left;
} Zero;

/* what one analysis knows: the kernels the values use, the zeros found */
typedef struct Scan {
    const Derived *d;
    Kernels *K;
    const Ring *r;
    slong t;             // the param
    unsigned char *dep;  // per kernel: its argument depends on t
    unsigned char *used; // per kernel: the values use it (also nested)
    Zero *z;             // the zeros, nz of them
    slong nz, zalloc;
    slong *other; // the kernels whose zeros were not found, nother
    slong nother;
    slong nscan; // kernels used covers (those made before the scan)
} Scan;

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
static int uses(const Kernels *K, const unsigned char *dep,
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
static void fill_dep(const Kernels *K, unsigned char *dep, slong var)
{
    memset(dep, 0, (size_t)K->n + 1);
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        dep[i] = 0;
        if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
            continue;
        dep[i] =
            (unsigned char)(uses(K, dep, k->arg, var) ||
                            (k->fn == KF_ATAN2 && uses(K, dep, k->arg2, var)));
    }
}

/* used[i] = 1 for every kernel that one of xs[0..nx-1] uses, directly or
 * inside another used kernel's argument */
static void fill_used(const Kernels *K, unsigned char *used,
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
static void scan_init(Scan *S, const Derived *d, const RatFunStruct *xs,
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
    fill_dep(S->K, S->dep, t);
    S->nscan = n;
    fill_used(S->K, S->used, xs, nx);
    for (slong i = 0; i < n; i++)
        if (S->used[i] && S->dep[i] && S->K->k[i].fn == KF_SIGN)
            scan_sign(S, i);
}

static void scan_clear(Scan *S)
{
    for (slong i = 0; i < S->nz; i++)
        ratfun_clear(S->z[i].root, S->r);
    free(S->z);
    free(S->other);
    free(S->used);
    free(S->dep);
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
    free(has);
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
    fill_used(K, used, x, 1);
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
        if (!used[i] || k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
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
        if (rc == 0)
            rc = kernel_reduce(K, a);
        if (rc == 0 && fn == KF_ATAN2)
            rc = kernel_reduce(K, b);
        if (rc != 0)
            break;
        /* (k may move from here on: kernel_apply can add kernels) */
        RatFunStruct *v = ratfun_vec_init(1, r);
        img[kv] = v;
        if (fn == KF_ROOT)
            rc = kernel_pow_q(K, v, a, 1, q);
        else
            rc = kernel_apply(K, v, fn, a, fn == KF_ATAN2 ? b : NULL);
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
    free(img);
    free(used);
    return rc;
}

/* res = x at t = t0 (subst_vars) */
static int eval_at(Scan *S, RatFun res, const RatFunStruct *x,
                   const RatFunStruct *t0)
{
    return subst_vars(S, res, x, 1, &S->t, t0);
}

/* The side forms of a knot t0: the sign kernels the values use that
 * depend on t, each replaced by a number or a value free of t - those
 * with a zero at t0 by their sign just right of it (side +1) or just left
 * (-1), the others by their exact value at t0, where they are locally
 * constant - then only t and the other functions of t are left.  Returns
 * 0, or -1 with why set (another sign kernel vanishes at t0, or a value
 * is not finite there). */
static int side_forms(Scan *S, const RatFunStruct *t0, const RatFunStruct *xs,
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
        if (j < S->nz) {
            ratfun_set_si(vr + nsub, S->z[j].right, r);
            ratfun_set_si(vl + nsub, S->z[j].left, r);
        } else if (eval_at(S, a, S->K->k[i].arg, t0) != 0) {
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
        }
    }
    ratfun_clear(a, r);
    ratfun_vec_clear(vl, S->nscan + 1, r);
    ratfun_vec_clear(vr, S->nscan + 1, r);
    free(vars);
    return rc;
}

/* The one-sided derivatives of xs[0..nx-1] at a knot, order by order:
 * cur holds the side's derivative of order have - 1 (the side's form
 * before the first), val[j] the values of order j at the knot. */
typedef struct Side {
    RatFunStruct *cur;  // nx
    RatFunStruct **val; // KNOTS_MAX_ORDER + 1 rows of nx, made on demand
    int have;           // orders 0..have-1 are in val
    int failed;         // an order could not be made: 1 not finite or exact, 2
                        // too large (KNOTS_MAX_TERMS)
} Side;

typedef struct Sides {
    Scan *S;
    const RatFunStruct *t0; // the knot
    slong nx;
    Side s[2]; // [0] right, [1] left
} Sides;

static int sides_init(Sides *Q, Scan *S, const RatFunStruct *xs, slong nx,
                      const RatFun t0, const char **why)
{
    memset(Q, 0, sizeof *Q);
    Q->S = S;
    Q->t0 = t0;
    Q->nx = nx;
    for (int k = 0; k < 2; k++) {
        Q->s[k].cur = ratfun_vec_init(nx, S->r);
        Q->s[k].val = pc_xcalloc(KNOTS_MAX_ORDER + 1, sizeof *Q->s[k].val);
    }
    return side_forms(S, t0, xs, nx, Q->s[0].cur, Q->s[1].cur, why);
}

static void sides_clear(Sides *Q)
{
    for (int k = 0; k < 2; k++) {
        ratfun_vec_clear(Q->s[k].cur, Q->nx, Q->S->r);
        for (int j = 0; j <= KNOTS_MAX_ORDER; j++)
            if (Q->s[k].val[j])
                ratfun_vec_clear(Q->s[k].val[j], Q->nx, Q->S->r);
        free(Q->s[k].val);
    }
}

/* the values of order j on side k (0 right, 1 left), or NULL when they
 * are not finite or exact */
static const RatFunStruct *side_value(Sides *Q, int k, int j)
{
    Side *s = &Q->s[k];
    Scan *S = Q->S;
    while (!s->failed && s->have <= j) {
        RatFunStruct *v = ratfun_vec_init(Q->nx, S->r);
        int rc = 0;
        for (slong i = 0; i < Q->nx && rc == 0; i++) {
            if (ratfun_length(s->cur + i, S->r) > KNOTS_MAX_TERMS) {
                rc = 2;
                break;
            }
            if (s->have > 0)
                rc = kernel_derivative(S->K, s->cur + i, s->cur + i, S->t);
            if (rc == 0)
                rc = eval_at(S, v + i, s->cur + i, Q->t0);
        }
        if (rc != 0) {
            ratfun_vec_clear(v, Q->nx, S->r);
            s->failed = rc == 2 ? 2 : 1;
            break;
        }
        s->val[s->have++] = v;
    }
    return s->have > j ? s->val[j] : NULL;
}

/* why side_value failed */
static const char *side_why(const Sides *Q)
{
    return Q->s[0].failed == 2 || Q->s[1].failed == 2
               ? "the one-sided derivatives grow too large to compare"
               : "a one-sided derivative is not finite or exact";
}

static int vec_is_zero(const RatFunStruct *v, slong n, const Ring *r)
{
    for (slong i = 0; i < n; i++)
        if (!ratfun_is_zero(v + i, r))
            return 0;
    return 1;
}

/* res = a - b, reduced; 0 or an error */
static int vec_sub(Kernels *K, RatFunStruct *res, const RatFunStruct *a,
                   const RatFunStruct *b, slong n)
{
    int rc = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        ratfun_sub(res + i, a + i, b + i, K->r);
        rc = kernel_reduce(K, res + i);
    }
    return rc;
}

/* 1 when u = lambda*v for one lambda (v != 0), *lambda set; 0 when not */
static int proportional(Kernels *K, RatFun lambda, const RatFunStruct *u,
                        const RatFunStruct *v, slong n)
{
    const Ring *r = K->r;
    slong i0 = -1;
    for (slong i = 0; i < n && i0 < 0; i++)
        if (!ratfun_is_zero(v + i, r))
            i0 = i;
    if (i0 < 0 || ratfun_div(lambda, u + i0, v + i0, r) != 0 ||
        kernel_reduce(K, lambda) != 0)
        return 0;
    RatFun w;
    ratfun_init(w, r);
    int ok = 1;
    for (slong i = 0; i < n && ok; i++) {
        ratfun_mul(w, lambda, v + i, r);
        ratfun_sub(w, w, u + i, r);
        ok = kernel_reduce(K, w) == 0 && ratfun_is_zero(w, r);
    }
    ratfun_clear(w, r);
    return ok;
}

/* The geometric order at a continuous knot (knots.h): the oriented
 * tangents, then the curvature condition where the curve is regular. */
static void geometric_order(Knot *k, Sides *Q)
{
    Scan *S = Q->S;
    const Ring *r = S->r;
    slong nx = Q->nx;
    int first[2] = {0, 0};
    for (int s = 0; s < 2; s++)
        for (int j = 1; j <= KNOTS_MAX_ORDER && !first[s]; j++) {
            const RatFunStruct *v = side_value(Q, s, j);
            if (!v) {
                k->geometric = -2;
                k->gwhy = side_why(Q);
                return;
            }
            if (!vec_is_zero(v, nx, r))
                first[s] = j;
        }
    k->geometric = 0;
    if (!first[0] || !first[1]) {
        k->gwhy = "the curve stands still on one side: no tangent there";
        return;
    }
    int p = first[0], q = first[1];
    RatFunStruct *tin = ratfun_vec_init(nx, r);
    RatFun lambda, mu;
    ratfun_init(lambda, r);
    ratfun_init(mu, r);
    /* the curve arrives along (-1)^(q+1) L_q and leaves along R_p */
    const RatFunStruct *lq = side_value(Q, 1, q);
    for (slong i = 0; i < nx; i++)
        if (q % 2)
            ratfun_set(tin + i, lq + i, r);
        else
            ratfun_neg(tin + i, lq + i, r);
    if (proportional(S->K, lambda, side_value(Q, 0, p), tin, nx)) {
        int sg = kernel_sign(S->K, lambda);
        if (sg == 2) {
            k->geometric = 1;
        } else if (sg != -2) {
            k->geometric = -2;
            k->gwhy = "the tangents are parallel, but their orientation "
                      "could not be compared";
        } else
            k->gwhy = "the curve turns back: its tangents are opposite";
    }
    if (k->geometric == 1 && (p > 1 || q > 1))
        k->gwhy = "G^2 is tested only where the first derivatives do not "
                  "vanish";
    else if (k->geometric == 1) {
        /* R_2 - lambda^2 L_2 parallel to L_1 */
        const RatFunStruct *r2 = side_value(Q, 0, 2);
        const RatFunStruct *l2 = side_value(Q, 1, 2);
        const RatFunStruct *l1 = side_value(Q, 1, 1);
        int ok = r2 && l2;
        for (slong i = 0; i < nx && ok; i++) {
            ratfun_mul(mu, lambda, lambda, r);
            ratfun_mul(mu, mu, l2 + i, r);
            ratfun_sub(tin + i, r2 + i, mu, r);
            ok = kernel_reduce(S->K, tin + i) == 0;
        }
        if (ok &&
            (vec_is_zero(tin, nx, r) || proportional(S->K, mu, tin, l1, nx))) {
            k->geometric = k->continuity > 2 ? k->continuity : 2;
            k->g_more = k->c_more;
        } else if (!ok)
            k->gwhy = side_why(Q);
    }
    ratfun_clear(mu, r);
    ratfun_clear(lambda, r);
    ratfun_vec_clear(tin, nx, r);
}

/* continuity, jump and geometric order at knot k */
static void analyse_knot(Knot *k, Scan *S, const RatFunStruct *xs, slong nx)
{
    const Ring *r = S->r;
    k->continuity = -1;
    k->jump_order = -1;
    k->geometric = -1;
    Sides Q;
    if (sides_init(&Q, S, xs, nx, k->t, &k->why) != 0) {
        sides_clear(&Q);
        return;
    }
    RatFunStruct *jump = ratfun_vec_init(nx, r);
    int j;
    for (j = 0; j <= KNOTS_MAX_ORDER; j++) {
        const RatFunStruct *R = side_value(&Q, 0, j);
        const RatFunStruct *L = side_value(&Q, 1, j);
        if (!R || !L || vec_sub(S->K, jump, R, L, nx) != 0) {
            k->why = side_why(&Q);
            break;
        }
        if (!vec_is_zero(jump, nx, r))
            break;
    }
    if (j <= KNOTS_MAX_ORDER && k->why) { /* known up to order j - 1 */
        k->continuity = j - 1;
        k->jump_order = j;
        ratfun_vec_clear(jump, nx, r);
    } else {
        k->analysed = 1;
        if (j > KNOTS_MAX_ORDER) {
            k->continuity = KNOTS_MAX_ORDER;
            k->c_more = 1;
            ratfun_vec_clear(jump, nx, r);
        } else {
            k->continuity = j - 1;
            k->jump_order = j;
            k->jump = jump;
            k->njump = nx;
        }
        if (k->continuity >= 0)
            geometric_order(k, &Q);
    }
    sides_clear(&Q);
}

/* ---- the output's knots ------------------------------------------------- */

/* the weights of output o: its terms' (or its scalar value) */
static const RatFunStruct *output_values(const Derived *d, slong o, slong *n)
{
    const DerivedOutput *out = &d->outputs[o];
    if (out->kind == KIND_SCALAR) {
        *n = 1;
        return out->scalar;
    }
    *n = out->eq->len;
    return out->w;
}

int knots_present(const Derived *d, slong o)
{
    const Kernels *K = d->kernels;
    if (!K || o < 0 || o >= d->noutputs)
        return 0;
    slong nx;
    const RatFunStruct *xs = output_values(d, o, &nx);
    unsigned char *used = pc_xcalloc((size_t)K->n + 1, 1);
    unsigned char *dep = pc_xcalloc((size_t)K->n + 1, 1);
    fill_used(K, used, xs, nx);
    int any = 0;
    for (slong p = 0; p < d->nparams && !any; p++) {
        fill_dep(K, dep, p);
        for (slong i = 0; i < K->n && !any; i++)
            any = used[i] && dep[i] && K->k[i].fn == KF_SIGN;
    }
    free(dep);
    free(used);
    return any;
}

/* an approximate value of a knot free of params and consts, or NAN */
static double approx(const Kernels *K, const RatFun x)
{
    fmpq_t q, lo, hi;
    fmpq_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    double v = NAN;
    int lo_open, hi_open;
    if (ratfun_get_fmpq(q, x, K->r))
        v = fmpq_get_d(q);
    else if (kernel_bounds(K, x, lo, &lo_open, hi, &hi_open) == 3)
        v = (fmpq_get_d(lo) + fmpq_get_d(hi)) / 2;
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(q);
    return v;
}

/* 1 when knot x lies outside param t's declared range (numbers only) */
static int out_of_range(const Derived *d, slong t, const RatFun x)
{
    if (!d->has_range || !d->has_range[t])
        return 0;
    fmpq_t q, b;
    fmpq_init(q);
    fmpq_init(b);
    int out = 0;
    if (ratfun_get_fmpq(q, x, &d->ring)) {
        if (ratfun_get_fmpq(b, d->range + 2 * t, &d->ring) &&
            fmpq_cmp(q, b) < 0)
            out = 1;
        if (ratfun_get_fmpq(b, d->range + 2 * t + 1, &d->ring) &&
            fmpq_cmp(q, b) > 0)
            out = 1;
    }
    fmpq_clear(b);
    fmpq_clear(q);
    return out;
}

static int knot_cmp(const void *a, const void *b)
{
    const Knot *x = a, *y = b;
    if (isnan(x->approx) || isnan(y->approx))
        return isnan(x->approx) - isnan(y->approx);
    return (x->approx > y->approx) - (x->approx < y->approx);
}

/* the argument of a sign kernel, as text: "t^2 - 2" of "sign(t^2 - 2)" */
static char *sign_arg_text(const Kernel *k)
{
    const char *s = k->name;
    size_t n = strlen(s);
    if (n > 6 && strncmp(s, "sign(", 5) == 0 && s[n - 1] == ')')
        return pc_xstrndup(s + 5, n - 6);
    return pc_xstrdup(s);
}

void knots_analyse(KnotList *res, const Derived *d, slong o)
{
    memset(res, 0, sizeof *res);
    res->param = -1;
    if (!knots_present(d, o))
        return;
    const Kernels *K = d->kernels;
    const Ring *r = &d->ring;
    slong nx;
    const RatFunStruct *xs = output_values(d, o, &nx);
    /* the one param the output depends on */
    unsigned char *dep = pc_xcalloc((size_t)K->n + 1, 1);
    slong t = -1, nused = 0;
    for (slong p = 0; p < d->nparams; p++) {
        fill_dep(K, dep, p);
        int u = 0;
        for (slong i = 0; i < nx && !u; i++)
            u = uses(K, dep, xs + i, p);
        if (u) {
            t = p;
            nused++;
        }
    }
    free(dep);
    if (nused != 1) {
        res->note = "the output depends on several params: its knots are "
                    "not analysed";
        return;
    }
    res->param = t;
    Scan S;
    scan_init(&S, d, xs, nx, t);
    /* the distinct zeros, in the declared range */
    res->k = pc_xcalloc((size_t)S.nz + 1, sizeof *res->k);
    for (slong j = 0; j < S.nz; j++) {
        int seen = 0;
        for (slong i = 0; i < res->n && !seen; i++)
            seen = ratfun_equal(res->k[i].t, S.z[j].root, r);
        if (seen || out_of_range(d, t, S.z[j].root))
            continue;
        Knot *k = &res->k[res->n++];
        ratfun_init(k->t, r);
        ratfun_set(k->t, S.z[j].root, r);
        k->approx = approx(K, k->t);
    }
    qsort(res->k, (size_t)res->n, sizeof *res->k, knot_cmp);
    for (slong i = 0; i < res->n; i++)
        analyse_knot(&res->k[i], &S, xs, nx);
    res->nskip = S.nother;
    res->skip = pc_xcalloc((size_t)S.nother + 1, sizeof *res->skip);
    for (slong i = 0; i < S.nother; i++)
        res->skip[i] = sign_arg_text(&K->k[S.other[i]]);
    scan_clear(&S);
}

void knots_clear(KnotList *res, const Derived *d)
{
    for (slong i = 0; i < res->n; i++) {
        ratfun_clear(res->k[i].t, &d->ring);
        if (res->k[i].jump)
            ratfun_vec_clear(res->k[i].jump, res->k[i].njump, &d->ring);
    }
    free(res->k);
    for (slong i = 0; i < res->nskip; i++)
        free(res->skip[i]);
    free(res->skip);
    memset(res, 0, sizeof *res);
}

int knots_one_sided(RatFun res, const Derived *d, const RatFun x, slong var,
                    const RatFun t0, int side, ulong j)
{
    if (!d->kernels)
        return -1;
    Scan S;
    scan_init(&S, d, x, 1, var);
    const char *why = NULL;
    RatFun v, w;
    ratfun_init(v, &d->ring);
    ratfun_init(w, &d->ring);
    int rc = side > 0 ? side_forms(&S, t0, x, 1, v, w, &why)
                      : side_forms(&S, t0, x, 1, w, v, &why);
    for (ulong i = 0; i < j && rc == 0; i++)
        rc = kernel_derivative(S.K, v, v, var);
    if (rc == 0)
        rc = eval_at(&S, res, v, t0);
    ratfun_clear(w, &d->ring);
    ratfun_clear(v, &d->ring);
    scan_clear(&S);
    return rc == 0 ? 0 : -1;
}
