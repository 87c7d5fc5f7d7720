/*
 * natural.h - `pointcalc natural`: curves in natural parametrization (the
 * natural-parametrization article, docs/natural.md), fitted through points
 * with tangent angles (runtime/natural.h does the numbers).
 *
 *   cmd_natural.c   the options, the fit, text and JSON
 *   natural_out.c   the samples table, the SVG picture and the C
 */
#ifndef PC_CLI_NATURAL_H
#define PC_CLI_NATURAL_H

#include <stdio.h>

#include "driver/cli/cli.h"
#include "runtime/natural.h"

CliCommand cli_natural;

#define NATURAL_USAGE                                                          \
    "usage: pointcalc natural --from X,Y,PHI [--through X,Y[,PHI]]... --to "   \
    "X,Y,PHI\n"                                                                \
    "                 [--law linear|quadratic|cubic] [--k0 K] [--dk0 D]\n"     \
    "                 [--method newton|hooke-jeeves] [--format text|json]\n"   \
    "                 [--samples N] [--plot FILE.svg [--comb]]\n"              \
    "                 [--emit-c FILE.c] [--scheme FILE.pcs] [--name F]\n"
extern const char natural_help[];

/* one curve of the command line: its points as typed, and what the fit
 * made of them */
typedef struct NatCli {
    NatPoint *pts;
    int npts;
    NatCurve curve;
} NatCli;

/* natural_out.c: N + 1 samples a segment (s, x, y, phi, k, k') as JSON
 * rows, the SVG picture, the C */
void natural_samples_json(FILE *out, const NatCurve *c, int n);
int natural_svg(const char *path, const NatCli *curves, int ncurves, int comb,
                FILE *err);
int natural_emit_c(const char *path, const NatCurve *c, const char *name,
                   FILE *err);
/* the curve as a scheme (natx, naty; docs/natural.md, "In the scheme
 * language"): segment i is Mi, the curve M their piecewise join in s */
int natural_scheme(const char *path, const NatCurve *c, const char *name,
                   FILE *err);

#endif
