/*
 * knots_int.h - private to knots.c and knots_scan.c (knots.h): the scan
 * of one value's sign kernels and their zeros, and the substitutions
 * that make the one-sided forms at a knot.
 */
#ifndef PC_KNOTS_INT_H
#define PC_KNOTS_INT_H

#include "compiler/algebra/kernel.h"
#include "compiler/derive/knots.h"

/* the largest degree in t of an argument whose zeros are looked for by
 * factoring (FLINT's fmpz_poly_factor is fast far beyond this) */
enum { KNOTS_MAX_FACTOR_DEGREE = 200 };

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

/* 1 when x depends on var directly or through a kernel (dep: per kernel,
 * its argument does) */
int knots_uses(const Kernels *K, const unsigned char *dep,
               const RatFunStruct *x, slong var);
/* dep[i] = 1 when kernel i's argument depends on var (K->n + 1 entries) */
void knots_fill_dep(const Kernels *K, unsigned char *dep, slong var);
/* used[i] = 1 for every kernel one of xs[0..nx-1] uses, directly or inside
 * another used kernel's argument */
void knots_fill_used(const Kernels *K, unsigned char *used,
                     const RatFunStruct *xs, slong nx);

/* Scans xs[0..nx-1] for the sign kernels that depend on param t and finds
 * their zeros (S->z) or lists them as not analysed (S->other). */
void knots_scan_init(Scan *S, const Derived *d, const RatFunStruct *xs,
                     slong nx, slong t);
void knots_scan_clear(Scan *S);

/* res = x at t = t0, exactly (the kernels x uses that depend on t are
 * remade there); 0 or an error */
int knots_eval_at(Scan *S, RatFun res, const RatFunStruct *x,
                  const RatFunStruct *t0);

/* The one-sided forms right[i], left[i] of xs[i] at knot t0: every sign
 * kernel of t replaced by its value just right / left of t0 (constant
 * there).  0, or -1 with *why set. */
int knots_side_forms(Scan *S, const RatFunStruct *t0, const RatFunStruct *xs,
                     slong nx, RatFunStruct *right, RatFunStruct *left,
                     const char **why);

#endif
