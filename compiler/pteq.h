/*
 * pteq.h - point equations: sparse maps from base points to weights.
 *
 *   M = A1*w1 + A2*w2 + ... + An*wn
 *
 * Base points are identified by their index in the scheme's `point`
 * declarations (0, 1, ...).  A PointEq keeps its terms sorted by point index
 * with no zero weight stored, so equal equations have identical term lists.
 * The weight sum says what the value is: 1 a point, 0 a vector; any other sum
 * is an intermediate combination (e.g. A + B before dividing by 2).
 *
 * Same conventions as ratfun.h: result first, ring last, aliasing allowed.
 */
#ifndef PC_PTEQ_H
#define PC_PTEQ_H

#include "compiler/ratfun.h"

typedef struct PtTerm {
    slong point;    // base point index
    RatFunStruct w; // its weight, never zero
} PtTerm;

typedef struct PointEqStruct {
    PtTerm *terms; // owned, sorted by point, len used of alloc
    slong len;
    slong alloc;
} PointEqStruct;
typedef PointEqStruct PointEq[1];

void pteq_init(PointEq x, const Ring *r); // x = 0 (empty)
void pteq_clear(PointEq x, const Ring *r);
void pteq_swap(PointEq x, PointEq y, const Ring *r);
void pteq_set(PointEq res, const PointEq x, const Ring *r);
void pteq_zero(PointEq res, const Ring *r);
/* res = the base point itself (weight 1) */
void pteq_set_point(PointEq res, slong point, const Ring *r);
/* checks the invariant (points strictly increasing and >= 0, weights
 * non-zero and canonical); for asserts and tests */
int pteq_is_canonical(const PointEq x, const Ring *r);

/* borrowed pointer to the weight of point, or NULL when it is zero */
const RatFunStruct *pteq_weight(const PointEq x, slong point);
/* res = weight of point (0 when absent) */
void pteq_get_weight(RatFun res, const PointEq x, slong point, const Ring *r);
/* sets the weight of point (removes the term when w is zero) */
void pteq_set_weight(PointEq x, slong point, const RatFun w, const Ring *r);

int pteq_is_zero(const PointEq x, const Ring *r);
int pteq_equal(const PointEq x, const PointEq y, const Ring *r);
/* res = sum of all weights */
void pteq_weight_sum(RatFun res, const PointEq x, const Ring *r);

void pteq_neg(PointEq res, const PointEq x, const Ring *r);
void pteq_add(PointEq res, const PointEq x, const PointEq y, const Ring *r);
void pteq_sub(PointEq res, const PointEq x, const PointEq y, const Ring *r);
void pteq_scalar_mul(PointEq res, const PointEq x, const RatFun s,
                     const Ring *r);
/* RATFUN_EDIVZERO when s is zero */
int pteq_scalar_div(PointEq res, const PointEq x, const RatFun s,
                    const Ring *r);
/* res = x + y*s (the workhorse of along, divide, meet) */
void pteq_addmul(PointEq res, const PointEq x, const PointEq y, const RatFun s,
                 const Ring *r);

/* Replace base point `point` by the combination p ("replacing the simplex",
 * monograph 4.1): x = sum w_i X_i  ->  sum_{i != point} w_i X_i + w_point*p */
void pteq_subst_point(PointEq res, const PointEq x, slong point,
                      const PointEq p, const Ring *r);
/* every weight composed with var := s; RATFUN_EPOLE if a weight's
 * denominator vanishes identically (res untouched then) */
int pteq_compose_var(PointEq res, const PointEq x, slong var, const RatFun s,
                     const Ring *r);
/* weight-wise partial derivative */
void pteq_derivative(PointEq res, const PointEq x, slong var, const Ring *r);
/* the k-th derivative of every weight (ratfun_derivative_n) */
void pteq_derivative_n(PointEq res, const PointEq x, slong var, ulong k,
                       const Ring *r);

#endif
