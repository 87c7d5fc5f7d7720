/*
 * functions.c - the scalar functions applied: sqrt, sin, ..., abs, sign
 * and pi, each a kernel (kernel.h) or rewritten into kernels (tan =
 * sin/cos).
 *
 * Called by eval (expr.c) for an ND_CALL of a function builtin.
 */
#include "compiler/derive/derive_int.h"

/* the scalar functions are the builtins BI_SQRT .. BI_SIGN (sema.h) */
int derive_is_function(int b)
{
    return b >= BI_SQRT && b <= BI_SIGN;
}

/* the kernel a function builtin makes directly (tan, tanh and abs are
 * rewritten, kernel.h), or -1 */
static int builtin_kernel(int b)
{
    switch ((Builtin)b) {
    case BI_SQRT:
        return KF_SQRT;
    case BI_SIN:
        return KF_SIN;
    case BI_COS:
        return KF_COS;
    case BI_ASIN:
        return KF_ASIN;
    case BI_ACOS:
        return KF_ACOS;
    case BI_ATAN:
        return KF_ATAN;
    case BI_ATAN2:
        return KF_ATAN2;
    case BI_SINH:
        return KF_SINH;
    case BI_COSH:
        return KF_COSH;
    case BI_EXP:
        return KF_EXP;
    case BI_LN:
        return KF_LN;
    case BI_SIGN:
        return KF_SIGN;
    default:
        return -1;
    }
}

/* a scalar function applied: sqrt(x), sin(x), ..., pi */
int derive_eval_function(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Kernels *K = D->K;
    res->is_point = 0;
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
