/*
 * plot_int.h - private to the plot files (plot_view.c, plot_jet.c,
 * plot_sample.c, svg.c): what they share beside plot.h.
 */
#ifndef PC_PLOT_INT_H
#define PC_PLOT_INT_H

#include "runtime/plot.h"

#define PI 3.14159265358979323846

/* r[i][0..2]: value, d/dt, d2/dt2 of every live register at t
 * (plot_jet.c) */
void plot_jet_run(const PlotEnv *env, const unsigned char *live, double t,
                  double (*r)[3]);

/* lo + (hi - lo) s without overflow for any finite lo, hi */
static inline double mix(double lo, double hi, double s)
{
    return lo * (1 - s) + hi * s;
}

#endif
