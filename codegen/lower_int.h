/*
 * lower_int.h - private to the lowering (lower.c, lower_kernel.c): how a
 * kernel of the exact algebra becomes Plan instructions.
 */
#ifndef PC_LOWER_INT_H
#define PC_LOWER_INT_H

#include "compiler/algebra/kernel.h"
#include "runtime/plan.h"

/* the PlanFn of a kernel (the same row of base/functions.def), with the
 * root's index q in the bits above 8; -1 for the kernels that are no FN
 * (pi, atan2, the metric atoms, natx and naty: lowered as their own ops) */
int lower_plan_fn(const Kernel *k);

/* natx or naty kernel k of argument register a: its NATX/NATY register;
 * the domain flag of a phase beyond reach (NaN: NAT_MAX_TURNING) is added
 * to *bad (-1: none yet) */
int lower_natural(Plan *p, const Kernels *K, const Kernel *k, int a, int *bad);

#endif
