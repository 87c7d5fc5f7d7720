/*
 * pteq.h - point equations over one common denominator.
 *
 *   M = (A1*n1 + A2*n2 + ... + An*nn) / d
 *
 * the form the monograph writes.  Base points are identified by their index
 * in the scheme's `point` declarations (0, 1, ...).  A PointEq keeps its
 * numerators sorted by point index, with no zero numerator stored, over ONE
 * shared denominator d.  It is CANONICAL on entry and exit of every public
 * function:
 *   - the numerators and d have no common factor (gcd(n1, ..., nn, d) = 1
 *     over Z, content included: the equation is primitive),
 *   - d has a positive leading coefficient (in the ring's ordering),
 *   - the empty equation (zero) has d = 1.
 * So equal equations have identical term lists and denominators.  The weight
 * of point Ai is ni/d; reduced on its own (pteq_get_weight) it may have a
 * smaller denominator.  The weight sum says what the value is: 1 a point (then
 * d = n1 + ... + nn), 0 a vector; any other sum is an intermediate
 * combination (e.g. A + B before dividing by 2).
 *
 * Why one denominator: every construction (along, divide, meet, subst) then
 * costs one content reduction of the whole equation instead of one gcd per
 * weight, and meet() is solved fraction-free (construct.c).
 *
 * Same conventions as ratfun.h: result first, ring last, aliasing allowed.
 */
#ifndef PC_PTEQ_H
#define PC_PTEQ_H

#include "compiler/algebra/ratfun.h"

typedef struct PtTerm {
    slong point;              // base point index
    fmpz_mpoly_struct num[1]; // its numerator over the common den, never 0
} PtTerm;

typedef struct PointEqStruct {
    PtTerm *terms; // owned, sorted by point, len used of alloc
    slong len;
    slong alloc;
    fmpz_mpoly_struct den[1]; // the common denominator, lc > 0
} PointEqStruct;
typedef PointEqStruct PointEq[1];

void pteq_init(PointEq x, const Ring *r); // x = 0 (empty)
void pteq_clear(PointEq x, const Ring *r);
void pteq_swap(PointEq x, PointEq y, const Ring *r);
void pteq_set(PointEq res, const PointEq x, const Ring *r);
void pteq_zero(PointEq res, const Ring *r);
/* res = the base point itself (weight 1) */
void pteq_set_point(PointEq res, slong point, const Ring *r);
/* checks the invariant (points strictly increasing and >= 0, numerators
 * non-zero, den with lc > 0, primitive); for asserts and tests */
int pteq_is_canonical(const PointEq x, const Ring *r);

/* 1 when point has a non-zero weight in x */
int pteq_has_point(const PointEq x, slong point);
/* res = the weight of point, reduced on its own (0 when absent) */
void pteq_get_weight(RatFun res, const PointEq x, slong point, const Ring *r);
/* w[i] = the reduced weight of x->terms[i].point, for i < x->len (w holds
 * x->len initialised RatFuns) */
void pteq_get_weights(RatFunStruct *w, const PointEq x, const Ring *r);
/* A read-only view of term i's weight as num/den, NOT reduced and sharing
 * x's memory: for size estimates only.  Valid while x is unchanged. */
void pteq_weight_view(RatFunStruct *v, const PointEq x, slong i);
/* sets the weight of point (removes the term when w is zero) */
void pteq_set_weight(PointEq x, slong point, const RatFun w, const Ring *r);
/* res = sum of points[i]*w[i] for i < n (points distinct, any order; zero
 * weights allowed): the equation over the lcm of the weights' dens */
void pteq_set_weights(PointEq res, const slong *points, const RatFunStruct *w,
                      slong n, const Ring *r);

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
/* res = x + y*s (the workhorse of along, divide, bezier) */
void pteq_addmul(PointEq res, const PointEq x, const PointEq y, const RatFun s,
                 const Ring *r);
/* res = x*s + y*u: one common denominator, one content reduction */
void pteq_lincomb(PointEq res, const PointEq x, const RatFun s, const PointEq y,
                  const RatFun u, const Ring *r);

/* Replace base point `point` by the combination p ("replacing the simplex",
 * monograph 4.1): x = sum w_i X_i  ->  sum_{i != point} w_i X_i + w_point*p */
void pteq_subst_point(PointEq res, const PointEq x, slong point,
                      const PointEq p, const Ring *r);
/* Replace the points cols[0..k-1] (distinct) by the combinations p[0..k-1]
 * simultaneously (a replacement that holds one of cols keeps it), over the
 * lcm of their denominators, with one content reduction: solve replaces
 * every unknown of a system in one pass; pteq_subst_point is k = 1. */
void pteq_subst_points(PointEq res, const PointEq x, const slong *cols,
                       const PointEq *p, slong k, const Ring *r);
/* every weight composed with var := s; RATFUN_EPOLE if a weight's
 * denominator vanishes identically (res untouched then) */
int pteq_compose_var(PointEq res, const PointEq x, slong var, const RatFun s,
                     const Ring *r);
/* weight-wise partial derivative */
void pteq_derivative(PointEq res, const PointEq x, slong var, const Ring *r);
/* the k-th derivative of every weight (ratfun_derivative_n) */
void pteq_derivative_n(PointEq res, const PointEq x, slong var, ulong k,
                       const Ring *r);

/* Makes x canonical from any numerators over any non-zero den (built
 * directly on the fields, e.g. by construct_meet): drops zero numerators,
 * removes the content gcd(n1, ..., nn, d), makes lc(d) > 0.  The terms
 * must already be sorted by point. */
void pteq_canonicalise(PointEq x, const Ring *r);
/* Divides every numerator and den of x by f when f divides them all (a
 * known factor of the content, before pteq_canonicalise, whose gcds then
 * need not find it); returns 1 then, 0 (x untouched) otherwise or when f
 * is a constant. */
int pteq_divide_known(PointEq x, const fmpz_mpoly_t f, const Ring *r);
/* Opens a term for point at the end of x (points must be appended in
 * increasing order) and returns its numerator to fill; for builders that
 * call pteq_canonicalise afterwards. */
fmpz_mpoly_struct *pteq_append(PointEq x, slong point, const Ring *r);

#endif
