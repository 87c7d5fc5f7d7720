/*
 * kernel_fold.c - kernel_apply: f(x) as a kernel, after the rewrites and
 * exact values of each function family (kernel.h).
 *
 * Before a kernel is made its argument is looked at: a number folds where
 * the value is exact (sin(pi/6) = 1/2, asin(1) = pi/2, sqrt(8) =
 * 2*sqrt(2)); sin and cos shift by multiples of pi/2 and expand over a sum
 * with asin, acos or atan; odd and even functions see a canonical sign;
 * sin(asin(x)) = x and its kin; exp splits over a sum; ln(exp(x)) = x.
 * What is left is a kernel (kernel.c), reduced (kernel_reduce.c).  Also
 * x^(p/q) and abs().
 */
#include "compiler/algebra/kernel_int.h"

#include <stdlib.h>

enum {
    MAX_POWER = 1000, // exponents a kernel rewrite may make
};

/* sign of the leading coefficient of x's numerator (0 for zero) */
static int rf_lead_sign(const RatFun x, const Ring *r)
{
    if (fmpz_mpoly_is_zero(x->num, r->ctx))
        return 0;
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_get_term_coeff_fmpz(c, x->num, 0, r->ctx);
    int s = fmpz_sgn(c);
    fmpz_clear(c);
    return s;
}

/* x divided by the positive rational that makes its numerator and its
 * denominator primitive: sign(2t - 2) is sign(t - 1), sign((2t - 1)/2) is
 * sign(2t - 1), so that one knot has one sign kernel */
static void rf_make_primitive(RatFun x, const Ring *r)
{
    fmpz_t c;
    fmpz_init(c);
    _fmpz_vec_content(c, x->num->coeffs, x->num->length);
    if (!fmpz_is_zero(c) && !fmpz_is_one(c))
        fmpz_mpoly_scalar_divexact_fmpz(x->num, x->num, c, r->ctx);
    _fmpz_vec_content(c, x->den->coeffs, x->den->length);
    if (!fmpz_is_zero(c) && !fmpz_is_one(c))
        fmpz_mpoly_scalar_divexact_fmpz(x->den, x->den, c, r->ctx);
    fmpz_clear(c);
}

static int pi_times(Kernels *K, RatFun res, slong num, slong den)
{
    int rc = kernels_intern(K, res, KF_PI, NULL, NULL, 0);
    if (rc == 0) {
        RatFun c;
        ratfun_init(c, K->r);
        fmpq_t q;
        fmpq_init(q);
        fmpq_set_si(q, num, (ulong)den);
        ratfun_set_fmpq(c, q, K->r);
        ratfun_mul(res, res, c, K->r);
        fmpq_clear(q);
        ratfun_clear(c, K->r);
    }
    return rc;
}

/* x = c * pi with c rational?  (c returned) */
static int is_pi_multiple(const Kernels *K, const RatFun x, fmpq_t c)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(x->den, r->ctx) || x->num->length != 1 ||
        fmpz_mpoly_total_degree_si(x->num, r->ctx) != 1)
        return 0;
    slong pi = kernels_find(K, KF_PI, NULL, NULL, 0);
    if (pi < 0 || !kernel_poly_has(x->num, K->k[pi].var, r))
        return 0;
    fmpz_t a, b;
    fmpz_init(a);
    fmpz_init(b);
    fmpz_mpoly_get_term_coeff_fmpz(a, x->num, 0, r->ctx);
    fmpz_mpoly_get_fmpz(b, x->den, r->ctx);
    fmpq_set_fmpz_frac(c, a, b);
    fmpz_clear(a);
    fmpz_clear(b);
    return 1;
}

/* sin(k*pi/12) for k in 0..23 where it is a simple surd: 1 and res set */
static int sin_pi12(Kernels *K, RatFun res, slong k)
{
    /* value for k in 0..6: 0, -, 1/2, sqrt2/2, sqrt3/2, -, 1 (-: not simple) */
    slong m = k % 12, sgn = k >= 12 ? -1 : 1;
    if (m > 6)
        m = 12 - m;
    fmpq_t q;
    fmpq_init(q);
    int ok = 1;
    switch (m) {
    case 0:
        ratfun_zero(res, K->r);
        break;
    case 2:
        fmpq_set_si(q, 1, 2);
        ratfun_set_fmpq(res, q, K->r);
        break;
    case 3:
    case 4:
        fmpq_set_si(q, m == 3 ? 2 : 3, 1);
        if (kernel_sqrt_num(K, res, q) != 0) {
            ok = -1;
            break;
        }
        fmpq_set_si(q, 1, 2);
        {
            RatFun h;
            ratfun_init(h, K->r);
            ratfun_set_fmpq(h, q, K->r);
            ratfun_mul(res, res, h, K->r);
            ratfun_clear(h, K->r);
        }
        break;
    case 6:
        ratfun_one(res, K->r);
        break;
    default:
        ok = 0;
    }
    fmpq_clear(q);
    if (ok == 1 && sgn < 0)
        ratfun_neg(res, res, K->r);
    return ok;
}

/* exp of x: a sum over a constant denominator splits into a product of
 * exp(monomial/q)^p; exp(k*ln(y)) = y^k */
static int exp_split(Kernels *K, RatFun res, const RatFun x)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(x->den, r->ctx))
        return kernels_intern(K, res, KF_EXP, x, NULL, 0);
    fmpz_t d, c;
    fmpz_init(d);
    fmpz_init(c);
    fmpz_mpoly_get_fmpz(d, x->den, r->ctx);
    RatFun acc, t;
    ratfun_init(acc, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    fmpz_mpoly_t m;
    fmpz_mpoly_init(m, r->ctx);
    int rc = 0;
    for (slong i = 0; i < x->num->length && rc == 0; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, x->num, i, r->ctx);
        fmpz_mpoly_get_term_monomial(m, x->num, i, r->ctx);
        fmpq_t pq;
        fmpq_init(pq);
        fmpq_set_fmpz_frac(pq, c, d);
        if (!fmpz_fits_si(fmpq_numref(pq)) ||
            fmpz_bits(fmpq_numref(pq)) > 10 /* |p| >= 1024 */) {
            /* a huge multiple: keep it inside the exponential */
            fmpz_mpoly_scalar_mul_fmpz(t->num, m, fmpq_numref(pq), r->ctx);
            fmpz_mpoly_set_fmpz(t->den, fmpq_denref(pq), r->ctx);
            ratfun_canonicalise(t, r);
            rc = kernels_intern(K, t, KF_EXP, t, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
            fmpq_clear(pq);
            continue;
        }
        slong p = fmpz_get_si(fmpq_numref(pq));
        fmpz_mpoly_set(t->num, m, r->ctx);
        fmpz_mpoly_set_fmpz(t->den, fmpq_denref(pq), r->ctx);
        fmpq_clear(pq);
        ratfun_canonicalise(t, r);
        slong v;
        const Kernel *lk;
        if (kernel_rf_is_var(t, &v, r) && (lk = kernels_of_var(K, v)) &&
            lk->fn == KF_LN) {
            ratfun_set(t, lk->arg, r); /* exp(p*ln(y)) = y^p */
        } else {
            /* exp(m*p/q) = exp(m/q)^p, and exp(m/q) is the q-th root of
             * exp(m) (one kernel for every q: exp(t/2)^2 = exp(t)) */
            slong q = 1;
            if (!fmpz_mpoly_is_one(t->den, r->ctx)) {
                fmpz_t qq;
                fmpz_init(qq);
                fmpz_mpoly_get_fmpz(qq, t->den, r->ctx);
                q = fmpz_fits_si(qq) ? fmpz_get_si(qq) : 0;
                fmpz_clear(qq);
                fmpz_mpoly_one(t->den, r->ctx);
            }
            if (q <= 0 || q > MAX_POWER) {
                K->why = "exp() of a number with a denominator over 1000";
                rc = KERNEL_EBIG;
            } else {
                rc = kernels_intern(K, t, KF_EXP, t, NULL, 0);
                if (rc == 0 && q > 1)
                    rc = kernels_intern(K, t, KF_ROOT, t, NULL, q);
            }
        }
        if (rc == 0) {
            if (ratfun_pow_si(t, t, p, r) != 0) {
                K->why = "exp() of a logarithm of zero";
                rc = KERNEL_EDOMAIN;
            } else {
                ratfun_mul(acc, acc, t, r);
            }
        }
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    fmpz_mpoly_clear(m, r->ctx);
    ratfun_clear(t, r);
    ratfun_clear(acc, r);
    fmpz_clear(c);
    fmpz_clear(d);
    return rc;
}

/* the value of a function at a number, where it is exact: 1 (res set),
 * 0 (not exact: make a kernel), or an error */
static int fold_number(Kernels *K, RatFun res, KernelFn f, const fmpq_t q)
{
    const Ring *r = K->r;
    int zero = fmpq_is_zero(q), one = fmpq_is_one(q);
    fmpq_t h;
    fmpq_init(h);
    fmpq_set_si(h, 1, 2);
    int half = fmpq_equal(h, q);
    fmpq_clear(h);
    int cmp1 = fmpz_cmpabs(fmpq_numref(q), fmpq_denref(q)); /* |q| vs 1 */
    switch (f) {
    case KF_SQRT:
        if (fmpq_sgn(q) < 0) {
            K->why = "square root of a negative number";
            return KERNEL_EDOMAIN;
        }
        return kernel_sqrt_num(K, res, q) == 0 ? 1 : KERNEL_EFULL;
    case KF_SIN:
    case KF_SINH:
    case KF_ATAN:
    case KF_ASIN:
        if (f == KF_ASIN && cmp1 > 0) {
            K->why = "asin() of a number outside [-1, 1]";
            return KERNEL_EDOMAIN;
        }
        if (zero) {
            ratfun_zero(res, r);
            return 1;
        }
        if (f == KF_ASIN && (one || half))
            return pi_times(K, res, 1, one ? 2 : 6) == 0 ? 1 : KERNEL_EFULL;
        if (f == KF_ATAN && one)
            return pi_times(K, res, 1, 4) == 0 ? 1 : KERNEL_EFULL;
        return 0;
    case KF_COS:
    case KF_COSH:
    case KF_EXP:
        if (zero) {
            ratfun_one(res, r);
            return 1;
        }
        return 0;
    case KF_LN:
        if (fmpq_sgn(q) <= 0) {
            K->why = "logarithm of a number that is not positive";
            return KERNEL_EDOMAIN;
        }
        if (one) {
            ratfun_zero(res, r);
            return 1;
        }
        return 0;
    case KF_ACOS:
        if (cmp1 > 0) {
            K->why = "acos() of a number outside [-1, 1]";
            return KERNEL_EDOMAIN;
        }
        if (one) {
            ratfun_zero(res, r);
            return 1;
        }
        if (zero || half)
            return pi_times(K, res, 1, zero ? 2 : 3) == 0 ? 1 : KERNEL_EFULL;
        return 0;
    case KF_SIGN:
        ratfun_set_si(res, fmpq_sgn(q), r);
        return 1;
    default:
        return 0;
    }
}

static int is_odd(KernelFn f)
{
    return f == KF_SIN || f == KF_SINH || f == KF_ASIN || f == KF_ATAN ||
           f == KF_SIGN;
}

static int is_even(KernelFn f)
{
    return f == KF_COS || f == KF_COSH;
}

/* atan2(y, x): 0 on the positive x axis, undefined at the origin */
static int apply_atan2(Kernels *K, RatFun res, const RatFun a, const RatFun y)
{
    const Ring *r = K->r;
    int rc;
    fmpq_t qx;
    fmpq_init(qx);
    if (ratfun_is_zero(a, r) && ratfun_get_fmpq(qx, y, r) && fmpq_sgn(qx) > 0) {
        ratfun_zero(res, r);
        rc = 0;
    } else if (ratfun_is_zero(a, r) && ratfun_is_zero(y, r)) {
        K->why = "atan2(0, 0) is undefined";
        rc = KERNEL_EDOMAIN;
    } else {
        rc = kernels_intern(K, res, KF_ATAN2, a, y, 0);
    }
    fmpq_clear(qx);
    return rc;
}

/* f at a number where the value is exact (fold_number): 1 and *rc set
 * when decided, 0 when a kernel is to be made */
static int apply_number(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                        int *rc)
{
    fmpq_t q;
    fmpq_init(q);
    int decided = 0;
    if (ratfun_get_fmpq(q, a, K->r)) {
        int st = fold_number(K, res, f, q);
        if (st != 0) {
            *rc = st == 1 ? 0 : st;
            decided = 1;
        }
    }
    fmpq_clear(q);
    return decided;
}

/* sin, cos at multiples of pi/12 where the value is a simple surd: 1 and
 * *rc set when decided */
static int apply_trig_pi12(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                           int *rc)
{
    int decided = 0;
    fmpq_t c;
    fmpq_init(c);
    if (is_pi_multiple(K, a, c)) {
        fmpz_t k12;
        fmpz_init(k12);
        fmpz_mul_ui(k12, fmpq_numref(c), 12);
        if (fmpz_divisible(k12, fmpq_denref(c))) {
            fmpz_divexact(k12, k12, fmpq_denref(c));
            fmpz_fdiv_r(k12, k12, (fmpz[]){24});
            slong k = fmpz_get_si(k12);
            if (f == KF_COS)
                k = (k + 6) % 24;
            int ok = sin_pi12(K, res, k);
            if (ok != 0) {
                *rc = ok < 0 ? KERNEL_EFULL : 0;
                decided = 1;
            }
        }
        fmpz_clear(k12);
    }
    fmpq_clear(c);
    return decided;
}

/* sin, cos at any other rational multiple c*pi: reduced to c in
 * [0, 1/2] by the period and the symmetries (sin(7*pi/5) = -sin(2*pi/5),
 * cos(3*pi/5) = -cos(2*pi/5)), so that equal values are one kernel and
 * sums such as sin(pi/5) + sin(9*pi/5) cancel; 1 and *rc set when the
 * multiple was not already reduced */
static int apply_trig_reduce(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                             int *rc)
{
    const Ring *r = K->r;
    fmpq_t c, c2, h;
    fmpq_init(c);
    fmpq_init(c2);
    fmpq_init(h);
    int decided = 0, neg = 0;
    if (is_pi_multiple(K, a, c)) {
        fmpz_t q;
        fmpz_init(q);
        /* c2 = c mod 2, in [0, 2) */
        fmpz_mul_ui(q, fmpq_denref(c), 2);
        fmpz_fdiv_q(q, fmpq_numref(c), q);
        fmpq_set_fmpz_frac(c2, q, (fmpz[]){1});
        fmpq_mul_si(c2, c2, 2);
        fmpq_sub(c2, c, c2);
        fmpz_clear(q);
        fmpq_set_si(h, 1, 1);
        if (f == KF_SIN && fmpq_cmp(c2, h) >= 0) { /* sin(x + pi) = -sin x */
            fmpq_sub(c2, c2, h);
            neg = 1;
        } else if (f == KF_COS && fmpq_cmp(c2, h) > 0) { /* cos(2pi - x) */
            fmpq_set_si(h, 2, 1);
            fmpq_sub(c2, h, c2);
        }
        fmpq_set_si(h, 1, 2);
        if (fmpq_cmp(c2, h) > 0) { /* sin(pi - x) = sin x, cos = -cos x */
            fmpq_set_si(h, 1, 1);
            fmpq_sub(c2, h, c2);
            neg ^= f == KF_COS;
        }
        if (neg || !fmpq_equal(c, c2)) {
            RatFun b, cc;
            ratfun_init(b, r);
            ratfun_init(cc, r);
            ratfun_gen(b, K->k[kernels_find(K, KF_PI, NULL, NULL, 0)].var, r);
            ratfun_set_fmpq(cc, c2, r);
            ratfun_mul(b, b, cc, r);
            ratfun_clear(cc, r);
            *rc = kernel_apply(K, res, f, b, NULL);
            if (*rc == 0 && neg)
                ratfun_neg(res, res, r);
            ratfun_clear(b, r);
            decided = 1;
        }
    }
    fmpq_clear(h);
    fmpq_clear(c2);
    fmpq_clear(c);
    return decided;
}

/* c = the coefficient of the term pi alone in arg (over a number
 * denominator): arg = x + c*pi where x has no term pi alone, as in
 * pi*t + pi (c = 1); 0 when arg has no such term or a denominator that is
 * not a number */
static int pi_term_coeff(const Kernels *K, slong pi, const RatFun a, fmpq_t c)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(a->den, r->ctx))
        return 0;
    fmpz_mpoly_t m;
    fmpz_t b, num;
    fmpz_mpoly_init(m, r->ctx);
    fmpz_init(b);
    fmpz_init(num);
    fmpz_mpoly_gen(m, K->k[pi].var, r->ctx);
    fmpz_mpoly_get_coeff_fmpz_monomial(num, a->num, m, r->ctx);
    fmpz_mpoly_get_fmpz(b, a->den, r->ctx);
    int found = !fmpz_is_zero(num);
    if (found)
        fmpq_set_fmpz_frac(c, num, b);
    fmpz_clear(num);
    fmpz_clear(b);
    fmpz_mpoly_clear(m, r->ctx);
    return found;
}

/* sin, cos of x + c*pi with 2c an integer: +-sin(x), +-cos(x); 1 and *rc
 * set when decided.  c is d(arg)/d(pi) where that is a number, else the
 * coefficient of the term pi alone (sin(pi*t + pi) = -sin(pi*t)). */
static int apply_trig_shift(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                            int *rc)
{
    const Ring *r = K->r;
    slong pi = kernels_find(K, KF_PI, NULL, NULL, 0);
    RatFun c, xr;
    ratfun_init(c, r);
    ratfun_init(xr, r);
    fmpq_t cq;
    fmpq_init(cq);
    int done_shift = 0;
    if (pi >= 0 && kernel_rf_has(a, K->k[pi].var, r)) {
        /* c = d(arg)/d(pi): a number when arg = x + c*pi */
        ratfun_derivative(c, a, K->k[pi].var, r);
        fmpz_t k2;
        fmpz_init(k2);
        int have = ratfun_get_fmpq(cq, c, r);
        if (!have && pi_term_coeff(K, pi, a, cq)) {
            have = 1;
            ratfun_set_fmpq(c, cq, r);
        }
        if (have) {
            fmpz_mul_ui(k2, fmpq_numref(cq), 2);
            if (fmpz_divisible(k2, fmpq_denref(cq))) {
                fmpz_divexact(k2, k2, fmpq_denref(cq));
                fmpz_fdiv_r(k2, k2, (fmpz[]){4});
                slong k = fmpz_get_si(k2);
                /* the rest x = arg - c*pi */
                ratfun_gen(xr, K->k[pi].var, r);
                ratfun_mul(xr, xr, c, r);
                ratfun_sub(xr, a, xr, r);
                if (!ratfun_is_zero(xr, r)) {
                    /* sin(x + k pi/2) = sin, cos, -sin, -cos (k = 0..3);
                     * cos(x + k pi/2) = cos, -sin, -cos, sin */
                    int use_cos = (f == KF_SIN) == (k % 2 == 1);
                    int negr = f == KF_SIN ? k >= 2 : (k == 1 || k == 2);
                    *rc = kernel_apply(K, res, use_cos ? KF_COS : KF_SIN, xr,
                                       NULL);
                    if (*rc == 0 && negr)
                        ratfun_neg(res, res, r);
                    done_shift = 1;
                }
            }
        }
        fmpz_clear(k2);
    }
    fmpq_clear(cq);
    ratfun_clear(xr, r);
    ratfun_clear(c, r);
    return done_shift;
}

/* the kernel asin(y), acos(y) or atan(y) whose variable v occurs in arg
 * (over the number denominator dd) as exactly +-dd*v, with the sign in
 * *sgn; -1 when none */
static slong trig_sum_term(const Kernels *K, const RatFun a, const fmpz_t dd,
                           slong *sgn)
{
    const Ring *r = K->r;
    slong iv = -1;
    fmpz_t cc;
    fmpz_init(cc);
    fmpz_mpoly_t cpoly;
    fmpz_mpoly_init(cpoly, r->ctx);
    for (slong i = 0; i < K->n && iv < 0; i++) {
        KernelFn g = K->k[i].fn;
        slong kv = K->k[i].var;
        ulong one = 1;
        if ((g != KF_ASIN && g != KF_ACOS && g != KF_ATAN) ||
            fmpz_mpoly_degree_si(a->num, kv, r->ctx) != 1)
            continue;
        /* the term must be exactly +-d*v: its coefficient a number */
        fmpz_mpoly_get_coeff_vars_ui(cpoly, a->num, &kv, &one, 1, r->ctx);
        if (!fmpz_mpoly_is_fmpz(cpoly, r->ctx))
            continue;
        fmpz_mpoly_get_fmpz(cc, cpoly, r->ctx);
        if (fmpz_cmpabs(cc, dd) == 0) {
            iv = i;
            *sgn = fmpz_sgn(cc);
        }
    }
    fmpz_mpoly_clear(cpoly, r->ctx);
    fmpz_clear(cc);
    return iv;
}

/* res = sin or cos of arg = x + sgn*v, v kernel iv, by the addition
 * formulas */
static int trig_sum_expand(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                           slong iv, slong sgn)
{
    const Ring *r = K->r;
    int rc;
    RatFun xr, v, sx, cx, sv, cv;
    ratfun_init(xr, r);
    ratfun_init(v, r);
    ratfun_init(sx, r);
    ratfun_init(cx, r);
    ratfun_init(sv, r);
    ratfun_init(cv, r);
    /* x = arg - sgn*v */
    ratfun_gen(v, K->k[iv].var, r);
    if (sgn < 0)
        ratfun_neg(v, v, r);
    ratfun_sub(xr, a, v, r);
    ratfun_gen(v, K->k[iv].var, r);
    rc = kernel_apply(K, sx, KF_SIN, xr, NULL);
    if (rc == 0)
        rc = kernel_apply(K, cx, KF_COS, xr, NULL);
    if (rc == 0)
        rc = kernel_apply(K, sv, KF_SIN, v, NULL);
    if (rc == 0)
        rc = kernel_apply(K, cv, KF_COS, v, NULL);
    if (rc == 0) {
        if (sgn < 0)
            ratfun_neg(sv, sv, r);
        /* sin(x + w) = sin x cos w + cos x sin w;
         * cos(x + w) = cos x cos w - sin x sin w */
        if (f == KF_SIN) {
            ratfun_mul(sx, sx, cv, r);
            ratfun_mul(cx, cx, sv, r);
            ratfun_add(res, sx, cx, r);
        } else {
            ratfun_mul(cx, cx, cv, r);
            ratfun_mul(sx, sx, sv, r);
            ratfun_sub(res, cx, sx, r);
        }
    }
    ratfun_clear(cv, r);
    ratfun_clear(sv, r);
    ratfun_clear(cx, r);
    ratfun_clear(sx, r);
    ratfun_clear(v, r);
    ratfun_clear(xr, r);
    return rc;
}

/* sin, cos of x + asin(y), x + acos(y), x + atan(y) (also minus):
 * the addition formulas, so that angle() results combine
 * algebraically (cos(acos(y)) = y, sin(acos(y)) = sqrt(1 - y^2)); 1 and
 * *rc set when applied */
static int apply_trig_sum(Kernels *K, RatFun res, KernelFn f, const RatFun a,
                          int *rc)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(a->den, r->ctx))
        return 0;
    fmpz_t dd;
    fmpz_init(dd);
    fmpz_mpoly_get_fmpz(dd, a->den, r->ctx);
    slong sgn = 0;
    slong iv = trig_sum_term(K, a, dd, &sgn);
    fmpz_clear(dd);
    /* arg = +-v alone: the rules for sin(asin(y)) ... below apply */
    if (iv >= 0 && a->num->length == 1)
        iv = -1;
    if (iv < 0)
        return 0;
    *rc = trig_sum_expand(K, res, f, a, iv, sgn);
    return 1;
}

/* sin(asin(x)) = x, cos(acos(x)) = x, cos(asin(x)) = sin(acos(x)) =
 * sqrt(1 - x^2), sin(atan(x)) = x/sqrt(1 + x^2), cos(atan(x)) =
 * 1/sqrt(1 + x^2); in: the kernel that the argument is.  1 and *rc set
 * when applied */
static int apply_of_inverse(Kernels *K, RatFun res, KernelFn f,
                            const Kernel *in, int *rc)
{
    const Ring *r = K->r;
    if ((f != KF_SIN && f != KF_COS) || !in ||
        (in->fn != KF_ASIN && in->fn != KF_ACOS && in->fn != KF_ATAN))
        return 0;
    RatFun yv, w;
    ratfun_init(yv, r);
    ratfun_init(w, r);
    ratfun_set(yv, in->arg, r);
    ratfun_mul(w, yv, yv, r);
    if (in->fn == KF_ATAN) {
        ratfun_set_si(res, 1, r);
        ratfun_add(w, res, w, r);
        *rc = kernel_apply(K, w, KF_SQRT, w, NULL);
        if (*rc == 0)
            ratfun_div(res, f == KF_SIN ? yv : res, w, r);
    } else if ((f == KF_SIN) == (in->fn == KF_ASIN)) {
        ratfun_set(res, yv, r);
        *rc = 0;
    } else {
        ratfun_set_si(res, 1, r);
        ratfun_sub(w, res, w, r);
        *rc = kernel_apply(K, res, KF_SQRT, w, NULL);
    }
    ratfun_clear(w, r);
    ratfun_clear(yv, r);
    return 1;
}

/* arguments that are provably outside the domain on the declared
 * signs and ranges: -t^2 - 1, or -t with t in [1, 2] */
static int apply_domain(Kernels *K, KernelFn f, const RatFun a)
{
    if (f != KF_SQRT && f != KF_LN)
        return 0;
    int sg = kernel_sign(K, a);
    if (sg == -2 || (f == KF_LN && sg < 0)) {
        K->why = f == KF_SQRT ? "square root of an expression that is negative "
                                "for every value of its params and consts (on "
                                "their declared ranges and signs)"
                              : "logarithm of an expression that is never "
                                "positive (on the declared ranges and signs)";
        return KERNEL_EDOMAIN;
    }
    return 0;
}

/* the sign taken out of the argument put back: sin(-a) = -sin(a),
 * acos(-y) = pi - acos(y) */
static int apply_sign_back(Kernels *K, RatFun res, KernelFn f, int neg, int rc)
{
    const Ring *r = K->r;
    if (rc == 0 && neg && is_odd(f))
        ratfun_neg(res, res, r);
    if (rc == 0 && neg && f == KF_ACOS) { /* acos(-y) = pi - acos(y) */
        RatFun p;
        ratfun_init(p, r);
        rc = kernels_intern(K, p, KF_PI, NULL, NULL, 0);
        if (rc == 0)
            ratfun_sub(res, p, res, r);
        ratfun_clear(p, r);
    }
    return rc;
}

/* f(a) once the number and the sin/cos rules did not decide it: the
 * canonical sign of odd and even functions, the known signs, the inverse
 * functions, the domain, sqrt, exp and ln; else a kernel.  a is changed */
static int apply_general(Kernels *K, RatFun res, KernelFn f, RatFun a)
{
    const Ring *r = K->r;
    int rc;
    /* odd and even functions see a canonical sign: sin(-a) = -sin(a) */
    int neg =
        rf_lead_sign(a, r) < 0 && (is_odd(f) || is_even(f) || f == KF_ACOS);
    if (neg)
        ratfun_neg(a, a, r);
    if (f == KF_SIGN) /* sign(c x) = sign(x) for c > 0 */
        rf_make_primitive(a, r);
    slong v;
    const Kernel *in = kernel_rf_is_var(a, &v, r) ? kernels_of_var(K, v) : NULL;
    if (f == KF_SIGN && abs(kernel_sign(K, a)) == 2) {
        ratfun_set_si(res, kernel_sign(K, a) > 0 ? 1 : -1, r);
        return apply_sign_back(K, res, f, neg, 0);
    }
    if (apply_of_inverse(K, res, f, in, &rc))
        return apply_sign_back(K, res, f, neg, rc);
    rc = apply_domain(K, f, a);
    if (rc != 0)
        return rc;
    switch (f) {
    case KF_SQRT:
        return kernel_sqrt_poly(K, res, a);
    case KF_EXP:
        return exp_split(K, res, a);
    case KF_LN:
        if (in && in->fn == KF_EXP) { /* ln(exp(y)) = y */
            ratfun_set(res, in->arg, r);
            return 0;
        }
        break;
    default:
        break;
    }
    rc = kernels_intern(K, res, f, a, NULL, 0);
    return apply_sign_back(K, res, f, neg, rc);
}

/* the rules in the order they are tried: atan2; a number; sin and cos at
 * multiples of pi/12, shifted by multiples of pi/2, over a sum with an
 * inverse function; then apply_general.  The result is reduced. */
int kernel_apply(Kernels *K, RatFun res, KernelFn f, const RatFun x,
                 const RatFun y)
{
    const Ring *r = K->r;
    int rc = 0;
    if (f == KF_PI)
        return kernels_intern(K, res, KF_PI, NULL, NULL, 0);
    RatFun a;
    ratfun_init(a, r);
    ratfun_set(a, x, r);
    int trig = f == KF_SIN || f == KF_COS;
    if (f == KF_ATAN2)
        rc = apply_atan2(K, res, a, y);
    else if (!apply_number(K, res, f, a, &rc) &&
             !(trig && apply_trig_pi12(K, res, f, a, &rc)) &&
             !(trig && apply_trig_reduce(K, res, f, a, &rc)) &&
             !(trig && apply_trig_shift(K, res, f, a, &rc)) &&
             !(trig && apply_trig_sum(K, res, f, a, &rc)))
        rc = apply_general(K, res, f, a);
    ratfun_clear(a, r);
    if (rc == 0)
        rc = kernel_reduce(K, res);
    return rc;
}

int kernel_pow_q(Kernels *K, RatFun res, const RatFun x, slong p, slong q)
{
    const Ring *r = K->r;
    RatFun t;
    ratfun_init(t, r);
    int rc;
    if (q == 2) {
        rc = kernel_apply(K, t, KF_SQRT, x, NULL);
    } else {
        fmpq_t c;
        fmpq_init(c);
        rc = 0;
        if (ratfun_get_fmpq(c, x, r)) {
            /* an exact root of a number folds */
            fmpz_t a, b;
            fmpz_init(a);
            fmpz_init(b);
            if (fmpq_sgn(c) < 0 && q % 2 == 0) {
                K->why = "even root of a negative number";
                rc = KERNEL_EDOMAIN;
            } else if (fmpz_root(a, fmpq_numref(c), q) &&
                       fmpz_root(b, fmpq_denref(c), q)) {
                fmpq_t v;
                fmpq_init(v);
                fmpq_set_fmpz_frac(v, a, b);
                ratfun_set_fmpq(t, v, r);
                fmpq_clear(v);
                rc = 1;
            }
            fmpz_clear(a);
            fmpz_clear(b);
        }
        fmpq_clear(c);
        if (rc == 0)
            rc = kernels_intern(K, t, KF_ROOT, x, NULL, q);
        else if (rc == 1)
            rc = 0;
    }
    /* the root may be a polynomial (sqrt((t + 1)^1000) = (t + 1)^500):
     * its power has the size guard of every power (ratfun.h), before the
     * one FLINT call that could otherwise run for hours */
    if (rc == 0 && ratfun_log2_bits_pow(t, p, r) > RATFUN_MAX_LOG2_BITS)
        rc = KERNEL_EBIG;
    if (rc == 0 && ratfun_pow_si(t, t, p, r) != 0) {
        K->why = "negative power of zero";
        rc = KERNEL_EDOMAIN;
    }
    if (rc == 0) {
        ratfun_swap(res, t, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(t, r);
    return rc;
}

int kernel_abs(Kernels *K, RatFun res, const RatFun x)
{
    int known = kernel_sign(K, x);
    if (known) {
        if (known > 0)
            ratfun_set(res, x, K->r);
        else
            ratfun_neg(res, x, K->r);
        return 0;
    }
    RatFun s;
    ratfun_init(s, K->r);
    int rc = kernel_apply(K, s, KF_SIGN, x, NULL);
    if (rc == 0) {
        ratfun_mul(res, x, s, K->r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(s, K->r);
    return rc;
}
