/*
 * kernel_natural.c - the natural-curve kernels natx(u, k) and naty(u, k)
 * (kernel.h, "Natural curves"): their laws, folding, names and derivative.
 *
 * A law is KERNEL_LAW_LEN exact coefficients k0 .. k3 of the curvature
 * k(s) = k0 + k1 s + k2 s^2 + k3 s^3.  Laws are interned in K->laws, so
 * that a kernel's q (the law's index) is equal exactly when the laws are:
 * kernels_find then compares natx kernels by (q, u) as it compares roots.
 */
#include "compiler/algebra/kernel_int.h"

#include <string.h>

#include "base/mem.h"
#include "compiler/algebra/poly_print.h"

const fmpq *kernels_law(const Kernels *K, slong q)
{
    return K->laws + q * KERNEL_LAW_LEN;
}

/* the index of law k, interned */
static slong law_index(Kernels *K, const fmpq *k)
{
    for (slong q = 0; q < K->nlaws; q++) {
        const fmpq *l = kernels_law(K, q);
        int same = 1;
        for (int j = 0; j < KERNEL_LAW_LEN && same; j++)
            same = fmpq_equal(l + j, k + j);
        if (same)
            return q;
    }
    K->laws = pc_xrealloc(K->laws, sizeof(fmpq) * (size_t)(K->nlaws + 1) *
                                       KERNEL_LAW_LEN);
    fmpq *l = K->laws + K->nlaws * KERNEL_LAW_LEN;
    for (int j = 0; j < KERNEL_LAW_LEN; j++) {
        fmpq_init(l + j);
        fmpq_set(l + j, k + j);
    }
    return K->nlaws++;
}

/* res = psi(u) = sum_j k_j u^(j+1)/(j+1), the tangent angle at u */
static void law_phase(const Kernels *K, RatFun res, slong q, const RatFun u)
{
    const Ring *r = K->r;
    const fmpq *k = kernels_law(K, q);
    RatFun p, c;
    ratfun_init(p, r);
    ratfun_init(c, r);
    ratfun_zero(res, r);
    ratfun_set(p, u, r);
    fmpq_t a;
    fmpz_t d;
    fmpq_init(a);
    fmpz_init(d);
    for (int j = 0; j < KERNEL_LAW_LEN; j++) {
        if (j > 0)
            ratfun_mul(p, p, u, r);
        if (fmpq_is_zero(k + j))
            continue;
        fmpz_set_si(d, j + 1);
        fmpq_div_fmpz(a, k + j, d);
        ratfun_set_fmpq(c, a, r);
        ratfun_mul(c, c, p, r);
        ratfun_add(res, res, c, r);
    }
    fmpz_clear(d);
    fmpq_clear(a);
    ratfun_clear(c, r);
    ratfun_clear(p, r);
}

/* a law of degree 0, the circle of curvature k0 (a line for k0 = 0):
 * natx = sin(k0 u)/k0, naty = (1 - cos(k0 u))/k0 */
static int fold_circle(Kernels *K, RatFun res, KernelFn f, const fmpq_t k0,
                       const RatFun u)
{
    const Ring *r = K->r;
    if (fmpq_is_zero(k0)) {
        if (f == KF_NATX)
            ratfun_set(res, u, r);
        else
            ratfun_zero(res, r);
        return 0;
    }
    RatFun a, c;
    ratfun_init(a, r);
    ratfun_init(c, r);
    ratfun_set_fmpq(c, k0, r);
    ratfun_mul(a, c, u, r);
    int rc = kernel_apply(K, res, f == KF_NATX ? KF_SIN : KF_COS, a, NULL);
    if (rc == 0) {
        if (f == KF_NATY) {
            ratfun_one(a, r);
            ratfun_sub(res, a, res, r);
        }
        ratfun_div(res, res, c, r); /* k0 != 0 */
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(c, r);
    ratfun_clear(a, r);
    return rc;
}

int kernel_natural(Kernels *K, RatFun res, KernelFn f, const fmpq *k,
                   const RatFun u)
{
    if (ratfun_is_zero(u, K->r)) {
        ratfun_zero(res, K->r);
        return 0;
    }
    int deg = 0;
    for (int j = 1; j < KERNEL_LAW_LEN; j++)
        if (!fmpq_is_zero(k + j))
            deg = j;
    if (deg == 0)
        return fold_circle(K, res, f, k, u);
    return kernels_intern(K, res, f, u, NULL, law_index(K, k));
}

int kernel_natural_dk(Kernels *K, RatFun res, KernelFn fn, slong q,
                      const RatFun a, const RatFun da)
{
    const Ring *r = K->r;
    RatFun p;
    ratfun_init(p, r);
    law_phase(K, p, q, a);
    int rc = kernel_apply(K, p, fn == KF_NATX ? KF_COS : KF_SIN, p, NULL);
    if (rc == 0) {
        ratfun_mul(res, p, da, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(p, r);
    return rc;
}

/* text + ", c" for every coefficient up to the law's last nonzero one (k0
 * always): the call as the language writes it */
static char *law_args(const Kernels *K, slong q, const char *a, FormatStyle st)
{
    const fmpq *k = kernels_law(K, q);
    int last = 0;
    for (int j = 1; j < KERNEL_LAW_LEN; j++)
        if (!fmpq_is_zero(k + j))
            last = j;
    char *s = pc_xstrdup(a);
    RatFun c;
    ratfun_init(c, K->r);
    for (int j = 0; j <= last; j++) {
        ratfun_set_fmpq(c, k + j, K->r);
        char *t = poly_print_ratfun(c, K->r, st);
        size_t n = strlen(s) + strlen(t) + 3;
        char *u = pc_xmalloc(n);
        snprintf(u, n, "%s, %s", s, t);
        pc_free(t);
        pc_free(s);
        s = u;
    }
    ratfun_clear(c, K->r);
    return s;
}

void kernel_natural_names(const Kernels *K, Kernel *k, const char *a,
                          const char *la)
{
    const char *fn = k->fn == KF_NATX ? "natx" : "naty";
    char *t = law_args(K, k->q, a, FMT_TEXT);
    size_t n = strlen(t) + 8;
    k->name = pc_xmalloc(n);
    snprintf(k->name, n, "%s(%s)", fn, t);
    pc_free(t);
    t = law_args(K, k->q, la, FMT_LATEX);
    n = strlen(t) + 40;
    k->latex = pc_xmalloc(n);
    snprintf(k->latex, n, "\\operatorname{%s}\\left(%s\\right)", fn, t);
    pc_free(t);
}
