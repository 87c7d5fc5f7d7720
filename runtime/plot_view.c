/*
 * plot_view.c - the projection of a plot (plot.h): points of dimension 1
 * on the x axis, 2 as they are, 3 and more orthographically by their first
 * three coordinates along a view (xy, xz, yz, iso, or azimuth,elevation in
 * degrees).  Used by the sampler (plot_sample.c) and the SVG writer.
 */
#include "runtime/plot_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/numfmt.h"

static void view_angles(PlotView *v, double az_deg, double el_deg)
{
    double az = az_deg * (PI / 180), el = el_deg * (PI / 180);
    v->u[0] = -sin(az);
    v->u[1] = cos(az);
    v->u[2] = 0;
    v->v[0] = -sin(el) * cos(az);
    v->v[1] = -sin(el) * sin(az);
    v->v[2] = cos(el);
}

static void view_axes(PlotView *v, int a, int b)
{
    memset(v, 0, sizeof *v);
    v->u[a] = 1;
    v->v[b] = 1;
}

void plot_view_default(PlotView *v, int dim)
{
    if (dim <= 2)
        view_axes(v, 0, 1);
    else
        view_angles(v, 45, asin(1 / sqrt(3)) * (180 / PI));
}

int plot_view_parse(PlotView *v, const char *text, char *msg, size_t len)
{
    if (strcmp(text, "xy") == 0)
        view_axes(v, 0, 1);
    else if (strcmp(text, "xz") == 0)
        view_axes(v, 0, 2);
    else if (strcmp(text, "yz") == 0)
        view_axes(v, 1, 2);
    else if (strcmp(text, "iso") == 0)
        plot_view_default(v, 3);
    else {
        char *end;
        double az = pc_strtod(text, &end), el = 0;
        int ok = end != text && *end == ',';
        if (ok) {
            const char *s = end + 1;
            el = pc_strtod(s, &end);
            ok = end != s && *end == '\0' && isfinite(az) && isfinite(el) &&
                 fabs(az) <= 360 && fabs(el) <= 90;
        }
        if (!ok) {
            pc_snprintf(msg, len,
                        "expected xy, xz, yz, iso or AZIMUTH,ELEVATION in "
                        "degrees (|azimuth| <= 360, |elevation| <= 90)");
            return -1;
        }
        view_angles(v, az, el);
    }
    return 0;
}

void plot_project(const PlotView *v, const double *P, int dim, double *x,
                  double *y)
{
    double sx = 0, sy = 0;
    for (int c = 0; c < dim && c < 3; c++) {
        sx += v->u[c] * P[c];
        sy += v->v[c] * P[c];
    }
    *x = sx;
    *y = sy;
}
