/*
 * kernel_int.h - what the kernel files share (private to kernel*.c).
 *
 * kernel.c       the table: slots, making and naming kernels, dist, coord
 * kernel_fold.c  kernel_apply: the rewrites and exact values of each
 *                function family, x^(p/q), abs
 * kernel_sqrt.c  square roots: numbers, squares modulo the relations,
 *                the signs a root owes
 * kernel_reduce.c the normal form modulo the relations
 * kernel_calc.c  dependence, derivatives, substitution
 * kernel_sign.c  signs and bounds by interval arithmetic
 */
#ifndef PC_KERNEL_INT_H
#define PC_KERNEL_INT_H

#include "compiler/algebra/kernel.h"

/* 0, or the reason to stop (KERNEL_EBIG, KERNEL_ETIME): asked by every
 * loop of the normal form and of substitution (kernel.c) */
int kernel_guard(Kernels *K, const fmpz_mpoly_struct *p);

/* 1 when p (x) uses variable var */
int kernel_poly_has(const fmpz_mpoly_t p, slong var, const Ring *r);
int kernel_rf_has(const RatFun x, slong var, const Ring *r);
/* 1 when x is exactly the variable *var */
int kernel_rf_is_var(const RatFun x, slong *var, const Ring *r);

/* the index of the kernel fn(a[, b]) (q: KF_ROOT's index, KF_DIST's
 * pair), or -1 */
slong kernels_find(const Kernels *K, KernelFn fn, const RatFun a,
                   const RatFun b, slong q);
/* res = the kernel variable of fn(a[, b]) (made if new) */
int kernels_intern(Kernels *K, RatFun res, KernelFn fn, const RatFun a,
                   const RatFun b, slong q);

/* res = sqrt(q) for a number q >= 0 (kernel_sqrt.c) */
int kernel_sqrt_num(Kernels *K, RatFun res, const fmpq_t q);
/* res = sqrt(x) for a non-constant x (kernel_sqrt.c) */
int kernel_sqrt_poly(Kernels *K, RatFun res, const RatFun x);

/* applies f to every weight of x and rebuilds x over one denominator
 * (kernel_reduce.c) */
typedef int (*KernelWeightFn)(Kernels *K, RatFun w, void *ctx);
int kernel_map_weights(Kernels *K, PointEq res, const PointEq x,
                       KernelWeightFn f, void *ctx);

/* k->name and k->latex of natx(a, law) / naty (kernel_natural.c); a, la:
 * the argument's text and LaTeX */
void kernel_natural_names(const Kernels *K, Kernel *k, const char *a,
                          const char *la);
/* res = d k / d var = cos(psi(a)) da (natx) or sin(psi(a)) da (naty) */
int kernel_natural_dk(Kernels *K, RatFun res, KernelFn fn, slong q,
                      const RatFun a, const RatFun da);

#endif
