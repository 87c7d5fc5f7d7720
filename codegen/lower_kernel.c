/*
 * lower_kernel.c - the Plan instructions of a kernel's function
 * (lower_int.h): the FN table of base/functions.def and the natural-curve
 * kernels with their law in the constant pool.
 */
#include "codegen/lower_int.h"

#include <flint/fmpq.h>

int lower_plan_fn(const Kernel *k)
{
    static const int fn_of[KF_COUNT] = {
#define PC_FUNCTION(ID, name, ar, lang, kern, p, c, latex, dom)                \
    PC_WHEN(kern)([KF_##ID] = PC_PICK(p)(PLAN_FN_##ID, -1), )
#include "base/functions.def"
#undef PC_FUNCTION
        [KF_DIST] = -1,
        [KF_COORD] = -1,
        [KF_NATX] = -1,
        [KF_NATY] = -1,
    };
    if (k->fn == KF_ROOT)
        return PLAN_FN_ROOT | (int)(k->q << 8);
    return fn_of[k->fn];
}

int lower_natural(Plan *p, const Kernels *K, const Kernel *k, int a, int *bad)
{
    const fmpq *law = kernels_law(K, k->q);
    double kd[KERNEL_LAW_LEN];
    for (int j = 0; j < KERNEL_LAW_LEN; j++)
        kd[j] = fmpq_get_d(law + j);
    int reg = plan_natural(p, k->fn == KF_NATY, a, kd);
    /* NaN beyond NAT_MAX_TURNING: a domain error, said as such */
    int dom = plan_mul(p, plan_isnan(p, reg), plan_const(p, PLAN_DOMAIN_FLAG));
    *bad = *bad < 0 ? dom : plan_add(p, *bad, dom);
    return reg;
}
