/*
 * plot.h - drawing a scheme as SVG: the curves of its point outputs over a
 * param range, its base points, the construction at one param value, tangent
 * vectors and a curvature comb.  Independent of the command line
 * (driver/cli/cmd_plot.c parses the options and calls plot_svg).
 *
 *   Plan + coordinates --plot_curve_sample--> samples (t, projected x, y)
 *                      --plot_svg-----------> one SVG document
 *
 * Sampling is adaptive: PLOT_INITIAL uniform samples, then breadth-first
 * bisection of every segment whose midpoint leaves the chord by more than
 * the tolerance (half a pixel of the figure) or turns by more than 10
 * degrees, to a bounded depth and within a hard budget of samples per
 * curve.  Poles are cut, never joined: the plan's pole checks are on the
 * irreducible factors of the denominators, whose real roots are simple, so
 * a pole between two samples shows as a factor changing sign; such a
 * segment is bisected to the depth limit and no line is drawn across it.
 * Samples where the evaluator reports a pole, an overflow, a domain error
 * or a non-finite coordinate are not drawn either (the boundary is located
 * by bisection), nor is a segment still failing the flatness test at the
 * depth limit with a chord of more than 2% of the figure (a jump:
 * atan2's branch cut, sign()).
 *
 * Derivatives (tangents, the comb) are exact: the Plan is differentiated in
 * forward mode (value, first and second derivative of every register with
 * respect to the swept param, the chain rule per opcode), i.e. the
 * derivative of the same reduced equation that eval computes, in floating
 * point.
 *
 * Projection: points of dimension 1 are drawn on the x axis, 2 as they
 * are, 3 and more orthographically by their first three coordinates along
 * a view (xy, xz, yz, iso, or azimuth,elevation in degrees).
 */
#ifndef PC_PLOT_H
#define PC_PLOT_H

#include <stddef.h>
#include <stdio.h>

#include "runtime/plan.h"

enum {
    PLOT_INITIAL = 64,            // uniform segments before refinement
    PLOT_MAX_DEPTH = 16,          // bisections of one initial segment
    PLOT_MAX_SAMPLES = 4000,      // default budget per curve
    PLOT_SAMPLES_LIMIT = 1000000, // the largest budget accepted
    PLOT_TOTAL_SAMPLES = 2000000, // all curves of a figure together
    PLOT_MAX_TEETH = 10000,       // comb teeth
    PLOT_MAX_TANGENTS = 1000,     // tangent param values
};

/* Where a plan is evaluated: every param but the swept one fixed. */
typedef struct PlotEnv {
    const Plan *plan;
    int param;                   // the swept param
    const double *params;        // a value per param (the swept one ignored)
    const double *consts;        // a value per const
    const double *const *points; // per base point: dim coordinates or NULL
    int dim;                     // >= 1
} PlotEnv;

/* Orthographic projection: screen x = u . P, screen y = v . P (first three
 * coordinates of P; fewer when dim < 3). */
typedef struct PlotView {
    double u[3], v[3];
} PlotView;

/* "xy", "xz", "yz", "iso" or "AZ,EL" (degrees: the camera's azimuth about
 * the z axis from the x axis, and elevation above the xy plane).  0 or -1
 * with a message in msg. */
int plot_view_parse(PlotView *v, const char *text, char *msg, size_t len);
/* xy for dim <= 2, iso for 3 and more */
void plot_view_default(PlotView *v, int dim);
void plot_project(const PlotView *v, const double *P, int dim, double *x,
                  double *y);

/* The position and first two derivatives of point output o at t (each dim
 * doubles; d1, d2 may be NULL).  Returns the PlanStatus of the sample as
 * plan_eval gives it, or 3 when a value is not finite. */
int plot_jet(const PlotEnv *env, int o, double t, double *pos, double *d1,
             double *d2);

/* The weight of every term k of output o (p->outputs[o].point[k]) at t,
 * with its first two derivatives: w[k][0..2] (nterms rows).  Returns the
 * status as plot_jet does. */
int plot_jet_terms(const PlotEnv *env, int o, double t, double (*w)[3]);

typedef struct PlotLimits {
    int initial;        // uniform segments (>= 1)
    int max_depth;      // bisections per initial segment
    size_t max_samples; // hard budget per curve (>= initial + 1)
} PlotLimits;
void plot_limits_default(PlotLimits *l);

/* The samples of one curve, in increasing t. */
typedef struct PlotCurve {
    int output;
    size_t n;
    double *t, *x, *y;  // param value, projected position (eval's values)
    unsigned char *ok;  // 1: finite and no pole/domain status
    unsigned char *cut; // cut[i] = 1: no segment between sample i-1 and i
    double *fac;        // n * nfac values of the denominator factors
    int nfac;
    int *facreg;   // registers of the pole-checked factors
    double *knots; // the knots in the range (plot_knots), each a sample
    size_t nknots;
} PlotCurve;

/* The knots of point output o in [lo, hi]: the zeros of the arguments of
 * its sign kernels (abs(x) = x sign(x)) that are linear in the swept param,
 * each the double where the argument is nearest 0, sorted, without
 * repeats.  *knots receives them (malloc'ed, NULL when none: pc_free() it);
 * returns how many. */
size_t plot_knots(const PlotEnv *env, int o, double lo, double hi,
                  double **knots);

/* Samples output o (a point output) uniformly with lim->initial segments
 * over [lo, hi], and at its knots (plot_knots: a corner is drawn sharp,
 * never cut; refining keeps these samples). */
void plot_curve_init(PlotCurve *c, const PlotEnv *env, int o, double lo,
                     double hi, const PlotView *view, const PlotLimits *lim);
/* Refines against the figure's box (xmin, ymin, xmax, ymax: the tolerance
 * is diag/2000, and segments wholly outside it are not refined), then marks
 * the cuts and drops samples that lie on the chord of their neighbours. */
void plot_curve_refine(PlotCurve *c, const PlotEnv *env, const PlotView *view,
                       const double box[4], const PlotLimits *lim);
void plot_curve_clear(PlotCurve *c);
/* subpaths: maximal runs of drawable segments */
int plot_curve_subpaths(const PlotCurve *c);

/* A labelled point (base point, auxiliary point, or a curve's current
 * point) with its dim coordinates. */
typedef enum PlotMarkKind { PLOT_BASE, PLOT_AUX, PLOT_CURRENT } PlotMarkKind;
typedef struct PlotMark {
    const char *name; // NULL: drawn without a label
    const double *at; // dim coordinates (borrowed)
    PlotMarkKind kind;
    int curve; // PLOT_CURRENT: index into PlotSpec.curves
} PlotMark;

/* A construction line through up to 4 marks (indices into PlotSpec.marks):
 * drawn as the segment that spans them all. */
typedef struct PlotLine {
    int n;
    int m[4];
} PlotLine;

typedef struct PlotSpec {
    PlotEnv env;
    const int *curves; // point outputs drawn as curves
    int ncurves;
    double lo, hi; // the swept range
    PlotView view;
    PlotLimits lim;
    const PlotMark *marks;
    int nmarks;
    const PlotLine *lines;
    int nlines;
    const double *tangents; // param values of the tangent vectors
    int ntangents;
    double tangent_scale; // drawn vector = scale * dM/dt
    int comb;             // teeth of the curvature comb, 0: none
    double comb_scale;    // tooth = scale * curvature; 0: automatic
    int width, height;    // pixels; height 0: from the aspect
    const double *window; // xmin, ymin, xmax, ymax or NULL: fitted
    const char *title;
} PlotSpec;

typedef struct PlotStats {
    size_t samples;    // vertices of all curves (before clipping)
    int subpaths;      // of all curves
    double box[4];     // the window: xmin, ymin, xmax, ymax
    int digits;        // significant digits of the curves' coordinates
    int keep_curves;   // in: 1 to receive the curves' samples below
    PlotCurve *curves; // out (keep_curves): ncurves, free each with
                       // plot_curve_clear, then the array with pc_free()
} PlotStats;

void plot_spec_default(PlotSpec *s);

/* Writes the SVG document.  Returns 0, or -1 when out reports an error. */
int plot_svg(FILE *out, const PlotSpec *s, PlotStats *st);

#endif
