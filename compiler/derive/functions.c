/*
 * functions.c - the scalar functions applied: sqrt, sin, ..., abs, sign
 * and pi, each a kernel (kernel.h) or rewritten into kernels (tan =
 * sin/cos).
 *
 * Called by eval (expr.c) for an ND_CALL of a function builtin.
 *
 * The step blocks of the composite-curve text (Dolya, 2.1: (3), (5), (6),
 * (9); docs/language.md "Step functions") are rewritten here into sign
 * kernels times polynomials, which the printers read back as |t - a|:
 *   step(t, a, w, m) = 1/2 + p/2*sign(t - a) + (1 - p)/2*sign(t - a - w),
 * p = p(s), s = (t - a)/w, the smoothstep of degree 2m + 1
 *   p(s) = s^(m+1) * sum_{j=0..m} C(m + j, j) (1 - s)^j
 * (p(0) = 0, p(1) = 1, p^(i)(0) = p^(i)(1) = 0 for i = 1..m).  Left of
 * both knots the signs are -1, -1 (value 0), between them +1, -1 (p),
 * right of both +1, +1 (1); p has the factor (t - a)^(m+1) and 1 - p the
 * factor (t - a - w)^(m+1), so each sign kernel s = sign(x) comes with
 * x^(m+1): |x|^(m+1) or x*|x|^m, and the value of sign at 0 never
 * matters (which is why a declared range that proves x >= 0 may replace
 * sign(x) by 1, as abs() does).  ramp = step with m = 0 (the text's P,
 * (3)); rayr(t, a) = (x + |x|)/2 = max(x, 0) and rayl(t, a) = (x - |x|)/2 =
 * min(x, 0), x = t - a (the text's Q and Q_l, (9)).
 */
#include "compiler/derive/derive_int.h"

#include <flint/fmpz_vec.h>

/* the scalar functions are the builtins of base/functions.def (sema.h),
 * pi (a call of no arguments) the first */
int derive_is_function(int b)
{
    return b >= BI_FIRST_FUNCTION && b < BI_COUNT;
}

/* the kernel a function builtin makes directly (functions.def's kernel
 * column; tan, tanh and abs are rewritten, kernel.h), or -1 */
static int builtin_kernel(int b)
{
    static const int kernel_of[BI_COUNT] = {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(lang)([BI_##ID] = PC_PICK(k)(KF_##ID, -1), )
#include "base/functions.def"
#undef PC_FUNCTION
    };
    return derive_is_function(b) ? kernel_of[b] : -1;
}

/* s = sign(x) where the coefficient of s vanishes at x = 0: a declared
 * range that proves x >= 0 (x <= 0) gives 1 (-1), as abs() does.  Over a
 * number (t - 1/2 = (2t - 1)/2) and with an integer content (2t - 2) the
 * argument is taken primitive, sign(2t - 1), sign(t - 1): the kernels
 * keep sign(x/2) apart from sign(x), and the printers read |x| only of an
 * argument without a denominator (absform.h) */
static int step_sign(Kernels *K, RatFun s, const RatFun x)
{
    const Ring *r = K->r;
    int known = kernel_sign(K, x);
    if (known) {
        ratfun_set_si(s, known > 0 ? 1 : -1, r);
        return 0;
    }
    RatFun y;
    ratfun_init(y, r);
    ratfun_set(y, x, r);
    slong len = fmpz_mpoly_length(y->num, r->ctx);
    if (len > 0 && fmpz_mpoly_is_fmpz(y->den, r->ctx)) { /* den > 0 */
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, y->num->coeffs, len);
        fmpz_mpoly_scalar_divexact_fmpz(y->num, y->num, g, r->ctx);
        fmpz_mpoly_one(y->den, r->ctx);
        fmpz_clear(g);
    }
    int rc = kernel_apply(K, s, KF_SIGN, y, NULL);
    ratfun_clear(y, r);
    return rc;
}

/* res = the smoothstep p(s) of degree 2m + 1 (see the top of the file) */
static void smoothstep(RatFun res, const RatFun s, slong m, const Ring *r)
{
    RatFun one_s, pw, term;
    ratfun_init(one_s, r);
    ratfun_init(pw, r);
    ratfun_init(term, r);
    ratfun_one(one_s, r);
    ratfun_sub(one_s, one_s, s, r);
    ratfun_zero(res, r);
    ratfun_one(pw, r); /* (1 - s)^j */
    fmpz_t bin;
    fmpz_init(bin);
    for (slong j = 0; j <= m; j++) {
        fmpz_bin_uiui(bin, (ulong)(m + j), (ulong)j);
        ratfun_mul_si(term, pw, fmpz_get_si(bin), r);
        ratfun_add(res, res, term, r);
        ratfun_mul(pw, pw, one_s, r);
    }
    ratfun_pow_si(pw, s, m + 1, r);
    ratfun_mul(res, res, pw, r);
    fmpz_clear(bin);
    ratfun_clear(term, r);
    ratfun_clear(pw, r);
    ratfun_clear(one_s, r);
}

/* ramp(t, a, w), step(t, a, w, m), rayr(t, a), rayl(t, a) (see the top of
 * the file); the arguments are scalars (sema), m a literal 0 .. 10 */
static int eval_step(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Kernels *K = D->K;
    int b = n->builtin, st = 0, rc = 0;
    RatFun t, a, w, x, y, p, q, s1, s2;
    RatFun *all[] = {&t, &a, &w, &x, &y, &p, &q, &s1, &s2};
    for (size_t i = 0; i < sizeof all / sizeof *all; i++)
        ratfun_init(*all[i], r);
    int nin = b == BI_RAYR || b == BI_RAYL ? 2 : 3;
    RatFun *in[] = {&t, &a, &w};
    slong terms = 0;
    for (int i = 0; i < nin; i++) {
        if (derive_eval_scalar(D, *in[i], derive_nth(n, i)) < 0) {
            st = -1;
            goto done;
        }
        terms += (*in[i])->num->length + (*in[i])->den->length;
    }
    if (terms > KERNEL_MAX_TERMS) {
        st = derive_kernel_error(D, KERNEL_EBIG, n, NULL);
        goto done;
    }
    ratfun_sub(x, t, a, r); /* x = t - a */
    if (b == BI_RAYR || b == BI_RAYL) {
        rc = step_sign(K, s1, x); /* |x| = x*sign(x) */
        if (rc == 0) {
            ratfun_mul(y, x, s1, r);
            (b == BI_RAYR ? ratfun_add : ratfun_sub)(res->s, x, y, r);
            ratfun_set_si(y, 2, r);
            ratfun_div(res->s, res->s, y, r);
            rc = kernel_reduce(K, res->s);
        }
        goto done;
    }
    if (ratfun_is_zero(w, r)) {
        diag_error(D->diag, derive_nth(n, 2)->span,
                   "the width of %s() is zero: the step from 0 to 1 would be "
                   "a jump; expected a width w != 0 (the step rises on "
                   "[a, a + w])",
                   b == BI_RAMP ? "ramp" : "step");
        st = -1;
        goto done;
    }
    slong m = b == BI_RAMP ? 0 : atol(derive_nth(n, 3)->text);
    if (ratfun_div(y, x, w, r) != 0) { /* s = (t - a)/w */
        rc = KERNEL_EZERO;
        goto done;
    }
    smoothstep(p, y, m, r);
    ratfun_one(q, r);
    ratfun_sub(q, q, p, r); /* 1 - p */
    ratfun_sub(y, x, w, r); /* t - a - w */
    rc = step_sign(K, s1, x);
    if (rc == 0)
        rc = step_sign(K, s2, y);
    if (rc != 0)
        goto done;
    /* 1/2 + p/2*sign(x) + (1 - p)/2*sign(y) */
    ratfun_mul(p, p, s1, r);
    ratfun_mul(q, q, s2, r);
    ratfun_one(res->s, r);
    ratfun_add(res->s, res->s, p, r);
    ratfun_add(res->s, res->s, q, r);
    ratfun_set_si(y, 2, r);
    ratfun_div(res->s, res->s, y, r);
    rc = kernel_reduce(K, res->s);
done:
    if (rc != 0 && st == 0)
        st = derive_kernel_error(D, rc, n, derive_nth(n, 0));
    for (size_t i = 0; i < sizeof all / sizeof *all; i++)
        ratfun_clear(*all[i], r);
    return st;
}

/* a scalar function applied: sqrt(x), sin(x), ..., pi */
int derive_eval_function(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Kernels *K = D->K;
    res->is_point = 0;
    if (n->builtin == BI_RAMP || n->builtin == BI_STEP ||
        n->builtin == BI_RAYR || n->builtin == BI_RAYL)
        return eval_step(D, res, n);
    if (n->builtin == BI_PI) {
        int rc = kernel_apply(K, res->s, KF_PI, NULL, NULL);
        return rc ? derive_kernel_error(D, rc, n, NULL) : 0;
    }
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    int rc = 0, st = 0;
    if (derive_eval_scalar(D, x, derive_nth(n, 0)) < 0 ||
        (n->builtin == BI_ATAN2 &&
         derive_eval_scalar(D, y, derive_nth(n, 1)) < 0)) {
        st = -1;
        goto done;
    }
    if (x->num->length + x->den->length + y->num->length + y->den->length >
        KERNEL_MAX_TERMS) {
        st = derive_kernel_error(D, KERNEL_EBIG, n, NULL);
        goto done;
    }
    switch ((Builtin)n->builtin) {
    case BI_ABS:
        rc = kernel_abs(K, res->s, x);
        break;
    case BI_TAN:
    case BI_TANH: { /* sin/cos, sinh/cosh */
        int hyp = n->builtin == BI_TANH;
        rc = kernel_apply(K, y, hyp ? KF_SINH : KF_SIN, x, NULL);
        if (rc == 0)
            rc = kernel_apply(K, x, hyp ? KF_COSH : KF_COS, x, NULL);
        if (rc == 0 && ratfun_div(res->s, y, x, r) != 0) {
            diag_error(D->diag, derive_nth(n, 0)->span,
                       "tan() of this argument is infinite: its cosine is "
                       "identically zero");
            st = -1;
        }
        if (rc == 0 && st == 0)
            rc = kernel_reduce(K, res->s);
        break;
    }
    default:
        rc = kernel_apply(K, res->s, (KernelFn)builtin_kernel(n->builtin), x,
                          n->builtin == BI_ATAN2 ? y : NULL);
        break;
    }
    if (rc != 0)
        st = derive_kernel_error(D, rc, n, derive_nth(n, 0));
done:
    ratfun_clear(y, r);
    ratfun_clear(x, r);
    return st;
}

int derive_eval_natural(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    res->is_point = 0;
    RatFun u, c;
    ratfun_init(u, r);
    ratfun_init(c, r);
    fmpq k[KERNEL_LAW_LEN];
    for (int j = 0; j < KERNEL_LAW_LEN; j++)
        fmpq_init(k + j);
    int st = derive_eval_scalar(D, u, derive_nth(n, 0));
    for (int j = 0; st == 0 && j + 1 < n->nargs; j++) {
        const Node *a = derive_nth(n, j + 1);
        if (derive_eval_scalar(D, c, a) < 0)
            st = -1;
        else if (!ratfun_get_fmpq(k + j, c, r)) {
            diag_error(D->diag, a->span,
                       "expected a number: the coefficients of the curvature "
                       "law of %s() are numbers (k%d here depends on a "
                       "param, const or function)",
                       n->builtin == BI_NATX ? "natx" : "naty", j);
            st = -1;
        }
    }
    if (st == 0) {
        int rc = kernel_natural(
            D->K, res->s, n->builtin == BI_NATX ? KF_NATX : KF_NATY, k, u);
        if (rc != 0)
            st = derive_kernel_error(D, rc, n, derive_nth(n, 0));
    }
    for (int j = 0; j < KERNEL_LAW_LEN; j++)
        fmpq_clear(k + j);
    ratfun_clear(c, r);
    ratfun_clear(u, r);
    return st;
}
