/*
 * natural.h - plane curves in natural parametrization (the natural-
 * parametrization article, docs/natural.md): the curvature is a polynomial
 * in the arc length s,
 *
 *   k(s) = k0 + k1 s + k2 s^2 + k3 s^3          (the article's (4)-(6))
 *   phi(s) = phi0 + k0 s + k1 s^2/2 + ...        (2), (7)-(9): exact
 *   x(s) + i y(s) = x0 + i y0 + int_0^s exp(i phi(u)) du     (3)
 *
 * A segment is that curve on [0, length].  The integral is evaluated by
 * 16-point Gauss-Legendre panels, as many as the phase's variation needs
 * (at most NAT_PHASE_PER_PANEL radians of turning per panel), which gives
 * the point to about 1e-15 of the length; nat_table_build compiles a
 * segment into Chebyshev pieces (degree NAT_CHEB_DEGREE, checked by their
 * tails) for evaluation at many points (tens of ns a point).
 *
 * Fitting (natural_fit.c):
 *   nat_fit_g1      the G1 Hermite problem for the linear law (the
 *                   clothoid): one equation in one unknown (Bertolazzi &
 *                   Frego's reduction), Newton from a fitted initial guess;
 *                   the minimal-winding solution
 *   nat_fit_law     a quadratic or cubic law with the start curvature (and
 *                   its derivative) fixed - the article's G2 and G3 joints:
 *                   two equations (the end point) in two unknowns, damped
 *                   Newton (runtime/lsq.h) with the exact Jacobian, by
 *                   continuation from the clothoid
 *   nat_fit_hj      the article's own method for comparison: Hooke-Jeeves
 *                   on the end-point distance (16)
 *   nat_composite   a chain through points (angles given or by the chord
 *                   rule), each joint G1, G2 or G3
 *
 * The numeric side only (runtime/); no allocation but the table's and the
 * composite's (through base/mem.h).  Deterministic.
 */
#ifndef PC_NATURAL_H
#define PC_NATURAL_H

#include <stddef.h>

enum {
    NAT_MAX_DEGREE = 3, // curvature laws of degree <= 3
    NAT_GL_POINTS = 16, // Gauss-Legendre points per panel
    NAT_MAX_PANELS = 4096,
    NAT_CHEB_DEGREE = 20,      // Chebyshev pieces of the evaluation table
    NAT_MAX_POINTS = 10000,    // a composite through at most this many points
    NAT_MAX_HJ_POINTS = 100,   // the article's search: at most this many
    NAT_HJ_MAX_EVALS = 200000, // integrals a segment, to 1e-12 of the chord
};
#define NAT_PHASE_PER_PANEL 8.0
#define NAT_PI 3.14159265358979323846
/* the scales the command line and the library accept: |x|, |y| up to
 * NAT_MAX_COORD, consecutive points NAT_MIN_CHORD apart at least */
#define NAT_MAX_COORD 1e100
#define NAT_MIN_CHORD 1e-100

typedef enum NatLaw {
    NAT_LINEAR = 1,
    NAT_QUADRATIC = 2,
    NAT_CUBIC = 3,
} NatLaw;

typedef struct NatSegment {
    double x0, y0, phi0;          // start point, tangent angle (radians)
    double k[NAT_MAX_DEGREE + 1]; // k(s) = sum_j k[j] s^j
    int degree;                   // of k: 0 .. NAT_MAX_DEGREE
    double length;                // S >= 0
} NatSegment;

/* a to (-pi, pi] */
double nat_reduce_angle(double a);

/* the curvature, its derivative and the tangent angle at s (exact
 * polynomials, evaluated by Horner) */
double nat_kappa(const NatSegment *g, double s);
double nat_dkappa(const NatSegment *g, double s);
double nat_phi(const NatSegment *g, double s);

/* the point at s, by Gauss-Legendre panels */
void nat_point(const NatSegment *g, double s, double *x, double *y);

/* The natural-curve functions of the language (plan.h's NATX, NATY;
 * docs/language.md, "Natural curves"): x + i y = int_0^u exp(i psi(s)) ds
 * with psi(s) = k[0] s + k[1] s^2/2 + k[2] s^3/3 + k[3] s^4/4.  NaN (both)
 * when u or the law is not finite, or when the phase varies more than
 * NAT_MAX_PANELS panels resolve (NAT_MAX_TURNING radians). */
void nat_law_xy(const double *k, double u, double *x, double *y);
/* psi(u) and the curvature k(u) of that law */
double nat_law_phase(const double *k, double u);
double nat_law_kappa(const double *k, double u);
#define NAT_MAX_TURNING (NAT_PHASE_PER_PANEL * NAT_MAX_PANELS)

/* The moments of the phase psi(tau) = sum_j p[j] tau^j (deg <= 4, p[0]
 * included) over [0, 1]:
 *   c[m] = int_0^1 tau^m cos psi,  s[m] = int_0^1 tau^m sin psi,
 * m = 0 .. nm - 1 (nm <= 6).  Panels from the bound of |psi'|. */
void nat_moments(const double *p, int deg, int nm, double *c, double *s);

/* ---- the evaluation table ------------------------------------------------ */

typedef struct NatTable {
    NatSegment seg;
    int npanels;     // uniform panels of [0, length]
    double scale;    // npanels / length
    int ncoef;       // Chebyshev coefficients a panel (<= NAT_CHEB_DEGREE+1)
    double *cx, *cy; // npanels * ncoef coefficients, panel-major
} NatTable;

/* Compiles seg: panels are doubled until each piece's Chebyshev tail is
 * below 1e-15 of the segment's length (or NAT_MAX_PANELS).  Returns 0, -1
 * when the length is not finite or the table would not be accurate. */
int nat_table_build(NatTable *t, const NatSegment *seg);
void nat_table_free(NatTable *t);
/* the point at s (clamped to [0, length]) */
void nat_table_eval(const NatTable *t, double s, double *x, double *y);

/* ---- fitting ------------------------------------------------------------- */

typedef struct NatStats {
    int iterations; // Newton steps (or HJ pattern moves)
    int integrals;  // evaluations of the phase integrals
    double error;   // the end point's distance from the target afterwards
} NatStats;

/* The clothoid from (x0, y0) at angle th0 to (x1, y1) at angle th1: seg
 * gets k0 + k1 s and the length.  Returns 0, or -1 when the points
 * coincide or Newton does not converge (it does on every configuration
 * the tests sweep). */
int nat_fit_g1(double x0, double y0, double th0, double x1, double y1,
               double th1, NatSegment *seg, NatStats *st);

/* A segment of law `law` (NAT_QUADRATIC or NAT_CUBIC) from (x0, y0, th0)
 * to (x1, y1, th1) whose curvature at the start is kstart and, for the
 * cubic, whose curvature derivative there is dkstart: the top coefficient
 * from the end angle (the article's (14), (15) as corrected in
 * docs/errata.md), the next one and the length by Newton on the end
 * point.  The end angle's winding is the clothoid's.  Returns as
 * nat_fit_g1. */
int nat_fit_law(NatLaw law, double x0, double y0, double th0, double x1,
                double y1, double th1, double kstart, double dkstart,
                NatSegment *seg, NatStats *st);

/* The article's method: Hooke-Jeeves on (b, S) for the linear law with a
 * from (13), minimising the end-point distance (16) from b = 0, S = the
 * chord, until the pattern step is below tol (relative to the chord) or
 * max_evals integrals.  Returns 0 when the end point is within tol of the
 * target, 1 otherwise (seg holds the best found). */
int nat_fit_hj(double x0, double y0, double th0, double x1, double y1,
               double th1, double tol, int max_evals, NatSegment *seg,
               NatStats *st);

/* ---- composite curves ---------------------------------------------------- */

typedef struct NatPoint {
    double x, y, th;
    int has_th; // 0: the angle comes from the chord rule
} NatPoint;

typedef struct NatJoint {
    double dphi, dk, ddk; // the jumps of angle, curvature and its derivative
} NatJoint;

typedef struct NatCurve {
    int nseg;
    NatSegment *seg; // nseg segments
    NatJoint *joint; // nseg - 1 joints
    NatStats stats;  // summed over the segments (error: the largest)
} NatCurve;

/* The angles the chord rule gives where pts[i].has_th is 0: at an inner
 * point the direction from its previous to its next neighbour (the
 * article, after Catmull-Rom); at an end, the mirror of the next angle in
 * the end chord (exact on a circle); with two points, the chord. */
void nat_chord_angles(NatPoint *pts, int n);

/* How a composite is fitted: the law of the later segments; the first
 * segment's start curvature (and its derivative) when has_kstart; the
 * article's Hooke-Jeeves search instead of Newton (linear law only). */
typedef struct NatChain {
    NatLaw law;
    int has_kstart;
    double kstart, dkstart;
    int hooke_jeeves;
} NatChain;

/* The composite curve through n >= 2 points: the first segment is the
 * clothoid (or, with ch->has_kstart, the law's segment with that start
 * curvature and dkstart), every later one a segment of ch->law whose start
 * continues the previous end: G1 (linear), G2 (quadratic: the curvature),
 * G3 (cubic: also its derivative).  The angles are reduced to (-pi, pi]
 * (directions; the winding is the fit's).  Returns 0, or -1 with the
 * failing segment's index in *bad. */
int nat_composite(NatPoint *pts, int n, const NatChain *ch, NatCurve *c,
                  int *bad);
void nat_curve_free(NatCurve *c);

#endif
