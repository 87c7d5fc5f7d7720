/*
 * fit_plot.c - the picture of a fit (`pointcalc fit ... --plot FILE.svg`,
 * fit.h): the target f over [lo, hi] (grey), the fitted curve x(t), y(t)
 * for t in [0, 1] (blue) and its nodes (x_k, f(x_k)) (circles), like the
 * chapter's figures.
 *
 * The curve comes from its exact coefficients (x(t) = sum cx_j t^j) at
 * PLOT_T points when the weights are polynomials, else from the m + 1
 * samples the fit used.  f is drawn where it is defined and finite only.
 */
#include <math.h>
#include <stdlib.h>

#include "base/mem.h"
#include "driver/cli/fit.h"
#include "driver/cli/svgfig.h"
#include "runtime/plan.h"

enum { PLOT_F = 600, PLOT_T = 400 };

static const char fit_style[] =
    ".target { fill: none; stroke: #999; stroke-width: 3 }\n"
    ".curve { fill: none; stroke: #1f4e9c; stroke-width: 1.5 }\n"
    ".node { fill: white; stroke: #000; stroke-width: 1.2 }\n";

static double horner(const double *c, int n, double t)
{
    double v = 0;
    for (int j = n - 1; j >= 0; j--)
        v = v * t + c[j];
    return v;
}

/* the curve's points into px, py (PLOT_T + 1, or the m + 1 samples);
 * returns how many */
static size_t curve_points(const Fit *f, const FitResult *r, const double *y,
                           const double *cx, const double *cy, double *px,
                           double *py)
{
    if (f->coef) {
        for (int i = 0; i <= PLOT_T; i++) {
            double t = (double)i / PLOT_T;
            px[i] = horner(cx, f->n, t), py[i] = horner(cy, f->n, t);
        }
        return PLOT_T + 1;
    }
    for (size_t i = 0; i < f->ns; i++) {
        const double *ph = f->phi + i * (size_t)f->n;
        double sx = 0, sy = 0;
        for (int k = 0; k < f->n; k++)
            sx += r->nodes[k] * ph[k], sy += y[k] * ph[k];
        px[i] = sx, py[i] = sy;
    }
    return f->ns;
}

int fit_plot_svg(const char *path, const Fit *f, const FitResult *r,
                 const double *y, const double *cx, const double *cy, FILE *err)
{
    size_t nc = f->coef ? PLOT_T + 1 : f->ns;
    double *fx = pc_xmalloc(sizeof *fx * (4 * (size_t)PLOT_F + 2 * nc + 4));
    double *fv = fx + PLOT_F + 1, *px = fv + PLOT_F + 1, *py = px + nc;
    unsigned char *st = pc_xmalloc(PLOT_F + 1);
    for (int i = 0; i <= PLOT_F; i++)
        fx[i] = f->o.lo + (f->o.hi - f->o.lo) * i / PLOT_F;
    fit_target_at(f, 0, PLOT_F + 1, fx, fv, st);
    nc = curve_points(f, r, y, cx, cy, px, py);
    double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i <= PLOT_F; i++)
        if (st[i] == PLAN_STATUS_OK)
            svgfig_grow(b, fx[i], fv[i]);
    for (size_t i = 0; i < nc; i++)
        svgfig_grow(b, px[i], py[i]);
    double pad = 0.05 * fmax(b[2] - b[0], b[3] - b[1]);
    double box[4] = {b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad};
    SvgFig g;
    svgfig_begin(&g, box, fit_style);
    svgfig_line_begin(&g, "target");
    for (int i = 0; i <= PLOT_F; i++) {
        if (st[i] != PLAN_STATUS_OK) { // a gap: start a new line
            svgfig_line_end(&g);
            svgfig_line_begin(&g, "target");
            continue;
        }
        svgfig_line_to(&g, fx[i], fv[i]);
    }
    svgfig_line_end(&g);
    svgfig_line_begin(&g, "curve");
    for (size_t i = 0; i < nc; i++)
        svgfig_line_to(&g, px[i], py[i]);
    svgfig_line_end(&g);
    for (int k = 0; k < f->n; k++)
        svgfig_circle(&g, "node", r->nodes[k], y[k], 4);
    pc_free(fx);
    pc_free(st);
    return svgfig_end(&g, path, err);
}
