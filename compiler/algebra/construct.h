/*
 * construct.h - the constructions of point calculus on point equations.
 *
 * Each returns a status; derive.c turns a non-OK status into a diagnostic at
 * the construction's span.  All results are exact and reduced.
 */
#ifndef PC_CONSTRUCT_H
#define PC_CONSTRUCT_H

#include "compiler/algebra/linsolve.h"
#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"

typedef enum MeetStatus {
    MEET_OK,
    MEET_DEGENERATE_FIRST,  // the first flat's points are dependent
    MEET_DEGENERATE_SECOND, // the second flat's points are dependent
    MEET_PARALLEL,          // directions dependent, no common point
    MEET_COINCIDENT,        // directions dependent, a common line/point set
    MEET_SKEW,              // independent directions but not coplanar
    MEET_NO_POINT,          // a flat has no proper point (only vectors)
    MEET_TOO_BIG,           // an intermediate product could exceed 2^30
    MEET_FAILED,            // the normal form failed (nf->err)
                            // bits (128 MB; ratfun.h's size estimates)
} MeetStatus;

/* along(P, Q, s) = P + (Q - P)*s  (monograph 1.3: AP/AQ = s) */
void construct_along(PointEq res, const PointEq p, const PointEq q,
                     const RatFun s, const Ring *r);
/* divide(P, Q, k) = (P + k*Q)/(1 + k): simple ratio (P - T)/(T - Q) = k.
 * RATFUN_EDIVZERO when 1 + k is identically zero. */
int construct_divide(PointEq res, const PointEq p, const PointEq q,
                     const RatFun k, const Ring *r);
/* bezier(s, P0..Pn) = sum C(n,i) s^i (1-s)^(n-i) Pi */
void construct_bezier(PointEq res, const RatFun s, const PointEq *pts,
                      slong npts, const Ring *r);

/* The intersection of two flats given by points (weight sum 1) and improper
 * points (directions, weight sum 0): flat = its first proper point + the
 * span of the directions to the others.  Two lines: S-theorem; a line and a
 * plane: V-theorem (monograph 1.3.3-1.3.5), both as one exact linear system
 * over the base points, valid in a simplex of any dimension.  The system is
 * checked identically: lines that are not coplanar are MEET_SKEW. */
MeetStatus construct_meet(PointEq res, const PointEq *a, slong na,
                          const PointEq *b, slong nb, const Ring *r);
/* The same by the general path alone: Gaussian elimination over the
 * fraction field (linsolve), which also classifies every degenerate case.
 * construct_meet first tries the fraction-free form (signed maximal minors
 * of the homogeneous columns, one content reduction: construct.c) and
 * comes here when that cannot decide; the tests compare the two. */
MeetStatus construct_meet_general(PointEq res, const PointEq *a, slong na,
                                  const PointEq *b, slong nb, const Ring *r);
/* the general path with every entry in the normal form nf (the kernels'
 * identities, linsolve.h): for flats that are parallel, coincident or
 * degenerate only by sin^2 + cos^2 = 1 and the like, which the
 * fraction-free form, blind to the identities, solves with a denominator
 * that the normal form then finds identically zero.  The result is not
 * reduced. */
MeetStatus construct_meet_general_nf(PointEq res, const PointEq *a, slong na,
                                     const PointEq *b, slong nb, LinNormal *nf,
                                     const Ring *r);
/* For tests: the fraction-free form reduces a flat's points against each
 * other (column operations that eliminate a point they share) only where
 * the entries have at least n terms and a gcd holds most of them (default
 * 100, restored by n < 0); n = 0 reduces wherever a gcd is found, which
 * takes the tests' small flats down that path.  Results are the same
 * whatever n is.  construct_meet_stats: how many meets the fraction-free
 * form has solved so far (*fast) and how many columns it reduced
 * (*reduced).  Both are the calling thread's (_Thread_local). */
void construct_meet_set_reduce_min_terms(slong n);
void construct_meet_stats(slong *fast, slong *reduced);

/* For derive --steps: where the meet m of line(a[0], a[1]) and the flat
 * b[0..nb-1] lies on each flat.  params[0] = lambda with m = a0 + (a1 -
 * a0)*lambda, params[1..nb-1] = mu_j with m = b0 + sum (bj - b0)*mu_j
 * (a flat's origin is its first point; a direction argument d enters as
 * itself, not as d - origin).  params holds nb initialised entries.
 * 0, or -1 when m is not uniquely on both (degenerate flats). */
int construct_meet_params(RatFunStruct *params, const PointEq m,
                          const PointEq *a, const PointEq *b, slong nb,
                          const Ring *r);

/* The monograph's S-theorem (two lines) or V-theorem (a line and a plane)
 * form of the same meet, derive.h's DerivedStep: W = b[*w] written in the
 * simplex a0, a1, the other points of b, W = a0*coord[0] + a1*coord[1] +
 * sum_j V_j*coord[2 + j]; then lambda = coord[1]/det with det = coord[0]
 * + coord[1], which vanishes when the flats are parallel.  W is the last
 * point of b that lies outside the others' span with line a0 a1.  coord
 * holds nb + 1 initialised entries.  0, or -1 when no point of b works. */
int construct_meet_sv(RatFunStruct *coord, slong *w, RatFun det,
                      const PointEq *a, const PointEq *b, slong nb,
                      const Ring *r);

#endif
