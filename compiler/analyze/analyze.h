/*
 * analyze.h - what a derived curve is, found exactly (`pointcalc analyze`,
 * docs/analyze.md).
 *
 * A point or vector output that depends on one param t and nothing else
 * (no const, no function) is the curve t -> (n_1(t) A_1 + ... + n_k(t)
 * A_k) / d(t) with integer polynomials: its equation over one common
 * denominator (pteq.h).  Everything below is read from those polynomials,
 * with the base points generic (the simplex), so every finding is affinely
 * invariant:
 *
 *   degree       max deg n_i (the degree of the parametrization)
 *   index        how many times it traces the curve: deg_t of gcd over i
 *                of n_i(t) n_1(s) - n_1(t) n_i(s) in Q[s, t] (1: proper)
 *   order        degree / index: the order of the curve (its points on a
 *                generic hyperplane)
 *   dim          of the smallest flat holding it: the rank of the
 *                numerators' coefficient matrix, less one
 *   poles        the real roots of d in the range
 *   stop points  dM/dt = 0: common roots of n_i' d - n_i d'
 *   inflections  plane curves (dim 2): roots of det(N, N', N'') for three
 *                numerators N of independent rows, stop points and poles
 *                left out
 *   passages     the curve is at base point A_j where every other n_i is 0
 *   ends         the point at each end of the declared range (t -> oo
 *                without one), the first derivative that is not zero there,
 *                and how many more are parallel to it (the order of
 *                smoothness of monograph 3.6)
 *   implicit     plane curves over three base points: F(x, y, z) = 0 in
 *                the barycentric coordinates, Res_t(n_2 - y n_1, n_3 - z
 *                n_1) = c F(1, y, z)^index, homogenised
 *
 * The definitions of the scheme (derive's steps) get their poles too.
 */
#ifndef PC_ANALYZE_H
#define PC_ANALYZE_H

#include <stdio.h>

#include <flint/fmpq.h>

#include "compiler/analyze/roots.h"
#include "compiler/derive.h"

/* One end of the range. */
typedef struct AnEnd {
    char *t;         // "0", "1", "oo" (t -> +-oo: no declared range), owned
    int infinite;    // 1: the curve goes to infinity there (a pole)
    fmpq *point;     // npoints: the end point's weights; infinite: the
                     // direction it goes to infinity in (a vector)
    slong first;     // points: order of the first non-zero derivative there
                     // (1 regular; 0 not found or infinite)
    fmpq *tangent;   // npoints: that derivative (d/ds with s = 1/t at
                     // t -> oo), or NULL
    slong parallel;  // derivatives first..parallel are parallel to it; -1:
                     // every one (a straight line)
    slong vanishing; // derivatives 1..first-1 vanish: first - 1
    double *num;     // a curve found numerically (AnCurve.numeric): the
    double *num_tan; // end point's and first derivative's weights
                     // (npoints each; d->npoints), owned; point, tangent
                     // NULL
} AnEnd;

/* A base point the curve passes through, and where. */
typedef struct AnPass {
    slong point;
    AnRoots t;
} AnPass;

typedef struct AnCurve {
    const char *name; // borrowed from the Derived
    Kind kind;
    char *skip;    // owned: why it is not analysed, or NULL
    slong param;   // the param (ring variable) it depends on
    int bounded;   // 1: the param has a declared range [lo, hi]
    slong degree;  // of the parametrization
    slong index;   // points: times traced (1: proper)
    slong order;   // points: degree / index
    slong dim;     // points: 1 a straight line, 2 a plane curve, 3 ...
    AnRoots poles; // in the range
    AnRoots stops; // points: stop points in the range
    AnRoots infl;  // plane curves: inflections in the range
    int has_infl;  // 1: infl was computed (a plane curve)
    slong nends;   // 2 with a range, 1 (t -> oo) without
    AnEnd ends[2];
    slong npass; // points: the base points it passes through in the range
    AnPass *pass;
    char *implicit;        // plane curves over three base points: F, in the
                           // points' names as coordinates (text), or NULL
    char *implicit_j;      // the same in the JSON form (products with '*')
    char *implicit_tex;    // and in LaTeX
    char *implicit_xy;     // with exact plane coordinates of the three points
    char *implicit_xy_j;   // (AnSet.qpt, dim 2): G(x, y) = 0 in Cartesian
    char *implicit_xy_tex; // coordinates, text, JSON, LaTeX; else NULL
    /* with coordinates (AnSet.dim; metric.c), points on a bounded range
     * without poles: */
    int has_metric;        // 1: the values below were computed
    int metric_missing;    // 1: a point of the curve has no coordinates
    double kappa_end[2];   // the curvature at the ends (NAN: M' = 0 there)
    double kappa_ext[2];   // its largest [0] and smallest [1] value
    double kappa_ext_t[2]; // and where
    int has_kappa_ext[2];
    double length; // the arc length over the range
    /* a curve whose weights have functions (sin, sqrt, abs = x sign(x),
     * pi, dist ...): found numerically by analyze_numeric (driver/cli/
     * analyze_num.c: the runtime's Plan with exact derivatives), every
     * AnRoot a number */
    int numeric;           // 1: such a curve (degree, order, index unused)
    const char *nature;    // "piecewise", "algebraic" or "transcendental"
    char *functions;       // owned: the functions it has, "sin(t), pi"
    int num_done;          // 1: analyze_numeric filled what follows
    char *num_why;         // owned: why it could not be evaluated, or NULL
    double num_lo, num_hi; // the interval sampled
    double undefined[2];   // the first and last sample where a function is
                           // undefined (NAN: none)
} AnCurve;

/* A definition (derive's steps) in one param, and its poles in range. */
typedef struct AnDef {
    const char *name; // borrowed
    int line;
    slong param;
    AnRoots poles;
} AnDef;

typedef struct Analysis {
    const Derived *d; // borrowed: must outlive the Analysis
    slong ncurves;
    AnCurve *curves;
    slong ndefs;
    AnDef *defs;
    fmpq *cvalue;          // d->nconsts: the value each const was analysed
                           // with (given, or the generic rule below)
    unsigned char *cgiven; // 1: from AnSet (--set); 0: the generic value
    unsigned char *cused;  // 1: an analysed output depends on it
    int late;              // 1: the thread's deadline passed (budget_late): the
    Span late_at;          // analysis stopped at this output or definition (its
                  // curve skipped, AN_LATE; the curves after it and the
                  // definitions not analysed)
} Analysis;

/* AnCurve.skip of a curve left at the deadline */
#define AN_LATE "the time budget ran out before it was analysed"

/* The value of const k that has none from --set: a generic one, chosen
 * so that nothing special happens there (docs/analyze.md, "Consts"):
 * (k + 11)/(k + 7), i.e. 11/7, 3/2, 13/9, 7/5, ... */
void analyze_generic_value(fmpq_t res, slong k);

/* Values of consts (analyze --set k=VALUE): for const k (0 ..
 * d->nconsts - 1), given[k] = 1 and value[k] its exact value, which every
 * value is analysed with; the others stay symbolic (given NULL: none).
 * And the coordinates of base points (--at), for the curvature and the
 * arc length. */
typedef struct AnSet {
    const unsigned char *given;
    const fmpq *value;
    int dim;                 // coordinates (analyze --at): 0 none, else
    const double *const *pt; // pt[i] the dim coordinates of base point i,
                             // or NULL (not given)
    const fmpq *const *qpt;  // the same exactly, as typed (NULL: none, or
                             // qpt[i] NULL): the Cartesian implicit equation
} AnSet;

/* Analyses the outputs sel[0..nsel-1] of d (indices into d->outputs; sel
 * NULL: every output), and the poles of d's steps when d has them
 * (DeriveOptions.keep_steps), with the consts that set gives (NULL: none)
 * replaced by their values.  Never fails: a curve it cannot analyse says
 * why (AnCurve.skip).  Past the thread's deadline (base/budget.h, set by
 * the caller) it stops at the next step (Analysis.late). */
Analysis *analyze_derived(const Derived *d, const int *sel, int nsel,
                          const AnSet *set);
/* The same under a time budget of max_seconds (0: none), counted from the
 * call (budget_deadline_set; the thread has no deadline after it): NULL
 * when it ran out, after "FILE:LINE:COL: error: the time budget of S s
 * ran out while analysing this; raise it with --max-seconds" at the
 * output (or definition) being analysed, written to err (NULL:
 * nowhere).  Steps are checked, not single FLINT calls: a resultant or a
 * factorisation that started before the deadline ends first. */
Analysis *analyze_derived_within(const Derived *d, const int *sel, int nsel,
                                 const AnSet *set, double max_seconds,
                                 FILE *err);
void analysis_free(Analysis *a);

/* the report: text for people, JSON for programs (docs/analyze.md) */
void analyze_print_text(FILE *out, const Analysis *a);
void analyze_print_json(FILE *out, const Analysis *a);
void analyze_print_latex(FILE *out, const Analysis *a);

/* ---- inside compiler/analyze/ ------------------------------------------ */

/* the curve as integer polynomials in its param: term i is base point
 * pt[i] with numerator n[i], over den */
typedef struct AnPolys {
    slong len;
    slong *pt;
    fmpz_poly_struct *n;
    fmpz_poly_struct den[1];
} AnPolys;

/* curve.c: the ends (ends.c) */
void analyze_ends(AnCurve *c, const AnPolys *p, const fmpq *lo, const fmpq *hi,
                  slong npoints);
void analyze_end_clear(AnEnd *e, slong npoints);
/* metric.c: curvature and arc length, with set's coordinates */
void analyze_metric(AnCurve *c, const AnPolys *p, const fmpq *lo,
                    const fmpq *hi, const AnSet *set);
/* implicit.c: c->implicit of the plane curve over three points, and with
 * set's exact plane coordinates of them, c->implicit_xy */
void analyze_implicit(AnCurve *c, const AnPolys *p, const Derived *d,
                      const AnSet *set);

#endif
