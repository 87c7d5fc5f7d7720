/*
 * knots.h - smoothness of a composite curve at its knots, exact (issue 19
 * item 5; docs/composite.md, "Knots and smoothness").
 *
 * A derived composite curve is a rational function of its param t and of
 * sign kernels sign(a(t)) (abs(x) is x*sign(x) inside the algebra,
 * kernel.h).  Its knots are the real zeros of those arguments; off them
 * every sign kernel is locally constant.  At a knot t_k:
 *
 *   right side: every sign(a) with a(t_k) = 0 -> its sign just right of t_k
 *               (sign(t - t_k) -> +1), left side -> its sign just left of
 *               t_k (sign(t - t_k) -> -1); every other sign kernel keeps
 *               its exact value at t_k;
 *   then differentiate j times in t and put t = t_k:  R_j and L_j;
 *   the jump of order j is R_j - L_j (per base point weight).
 *
 * The continuity order is the largest k with jumps of orders 0..k all zero
 * (searched up to KNOTS_MAX_ORDER: "C^8 or more"; -1: the curve jumps).
 * The geometric order: G^0 continuous; G^1 when the oriented tangents
 * agree: the first non-zero derivative on each side, R_p and L_q (p, q >=
 * 1), with R_p = lambda*(-1)^(q+1)*L_q, lambda > 0 (the curve arrives
 * along (-1)^(q+1)*L_q and leaves along R_p: one that stops and turns back
 * is not G^1); G^2 where the first derivatives do not vanish, when also
 * R_2 - lambda^2*L_2 is parallel to L_1 (a C^2 reparametrisation exists).
 * A regular curve (R_1, L_1 != 0) that is C^k is G^k as well.
 *
 * Zeros are found for arguments whose numerator and denominator are
 * polynomials in t alone (their rational zeros, with multiplicity: a
 * factor (t - r)^m changes the sign when m is odd) and for arguments
 * linear in t with coefficients free of t (sign(t - a) with `const a`,
 * sign(t - pi/2)), whose zero is -alpha/beta.  Other arguments (sign(t^2 -
 * 2), sign(sin(t))) are listed as not analysed, never guessed.
 */
#ifndef PC_KNOTS_H
#define PC_KNOTS_H

#include "compiler/derive.h"

/* the highest order of derivative compared at a knot */
enum { KNOTS_MAX_ORDER = 8 };

typedef struct Knot {
    RatFun t;           // the knot: a number or an expression free of params
    double approx;      // its value (NAN when it depends on a const)
    int analysed;       // 1: the fields below hold; 0: why says what stopped it
    const char *why;    // static text, or NULL
    int continuity;     // C^continuity: -1 (a jump of the point itself) ..
                        // KNOTS_MAX_ORDER
    int c_more;         // 1: no jump up to KNOTS_MAX_ORDER: "C^8 or more"
    int jump_order;     // continuity + 1, or -1 (c_more, or not analysed)
    RatFunStruct *jump; // njump exact jumps of derivative jump_order: one
    slong njump;        // per term of the output's equation (its weights'
                        // order, DerivedOutput.w), one for a scalar; NULL
                        // when there is none
    int geometric;      // G^geometric: -1 (not continuous) .. ; -2: the
                        // continuity is known but the tangents could not be
                        // compared (gwhy says why)
    int g_more;         // 1: "or more" (a regular curve that is C^8 or
                        // more)
    const char *gwhy;   // static text: why G stops where it does, or NULL
} Knot;

typedef struct KnotList {
    slong param;      // the ring variable t, or -1: none (no knots) or several
                      // params (note says so)
    slong n;          // knots, increasing (those that depend on a const last)
    Knot *k;          // owned
    slong nskip;      // sign kernels whose zeros were not analysed: their text
    char **skip;      // ("sign(t^2 - 2)"), owned
    const char *note; // static text about the whole output, or NULL
} KnotList;

/* 1 when output o of d uses a sign kernel that depends on a param: it
 * may have knots (cheap: no derivative is taken) */
int knots_present(const Derived *d, slong o);

/* The knots of output o of d and the smoothness at each.  d's kernels
 * may gain kernels (the exact values of other sign kernels at a knot that
 * depends on a const); the outputs are not changed.  Knots outside a
 * param's declared range are left out.  res is initialised here; free it
 * with knots_clear. */
void knots_analyse(KnotList *res, const Derived *d, slong o);
void knots_clear(KnotList *res, const Derived *d);

/* The one-sided derivative of order j of weight x at knot t0 of param
 * var: side +1 the right, -1 the left.  Every sign kernel that vanishes at
 * t0 (found as knots_analyse finds them) takes its one-sided value.
 * Returns 0, or -1 when the derivative is not finite or exact there, or
 * a sign kernel vanishing at t0 was not analysed. */
int knots_one_sided(RatFun res, const Derived *d, const RatFun x, slong var,
                    const RatFun t0, int side, ulong j);

#endif
