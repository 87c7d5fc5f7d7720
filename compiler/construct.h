/*
 * construct.h - the constructions of point calculus on point equations.
 *
 * Each returns a status; derive.c turns a non-OK status into a diagnostic at
 * the construction's span.  All results are exact and reduced.
 */
#ifndef PC_CONSTRUCT_H
#define PC_CONSTRUCT_H

#include "compiler/pteq.h"
#include "compiler/ratfun.h"

typedef enum MeetStatus {
    MEET_OK,
    MEET_DEGENERATE_FIRST,  // the first flat's points are dependent
    MEET_DEGENERATE_SECOND, // the second flat's points are dependent
    MEET_PARALLEL,          // directions dependent, no common point
    MEET_COINCIDENT,        // directions dependent, a common line/point set
    MEET_SKEW,              // independent directions but not coplanar
    MEET_NO_POINT,          // a flat has no proper point (only vectors)
    MEET_TOO_BIG,           // an intermediate product could exceed 2^30
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

#endif
