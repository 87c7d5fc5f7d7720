/*
 * ratfun_calc.c - calculus and substitution on rational functions
 * (ratfun.h): derivatives, composition, evaluation at rational points.
 *
 * Each works on the numerator and denominator as polynomials and reduces
 * once at the end (_ratfun_reduce, ratfun.c), never per step: a gcd per
 * step costs far more than the products it saves.  The kernels' calculus
 * (kernel_calc.c) and derive.c's diff() and subst() stand on these.
 */
#include "compiler/algebra/ratfun_int.h"

#include <stdlib.h>

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
    _ratfun_reduce(t->num, t->den, r);
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
    _ratfun_reduce(t->num, t->den, r);
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
                                  const fmpz_t a, const fmpz_t b, const Ring *r)
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

int ratfun_poly_compose_homog(fmpz_mpoly_t res, slong *deg,
                              const fmpz_mpoly_t p, slong var,
                              const fmpz_mpoly_t a, const fmpz_mpoly_t b,
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
    if (!ratfun_poly_compose_homog(t->num, &dn, x->num, var, s->num, s->den,
                                   r) ||
        !ratfun_poly_compose_homog(t->den, &dd, x->den, var, s->num, s->den,
                                   r)) {
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
    _ratfun_reduce(t->num, t->den, r);
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
