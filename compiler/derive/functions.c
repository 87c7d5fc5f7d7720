/*
 * functions.c - the scalar functions applied: sqrt, sin, ..., abs, sign
 * and pi, each a kernel (kernel.h) or rewritten into kernels (tan =
 * sin/cos).
 *
 * Called by eval (expr.c) for an ND_CALL of a function builtin.
 */
#include "compiler/derive/derive_int.h"

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
