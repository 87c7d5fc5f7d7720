/*
 * api_example.c - pointcalc as a library (docs/api.md).
 *
 * Derives the Desargues arc from a string, prints its weights, compiles it
 * to a plan and evaluates the arc at five parameter values in 3D.
 *
 *   make && cc -std=c11 -I. -o api_example examples/api_example.c \
 *       build/libpointcalc.a -lflint -lgmp -lm && ./api_example
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "libpointcalc.h"

static const char scheme[] = "scheme desargues_arc\n"
                             "point A, B, C, D\n"
                             "param t in [0, 1]\n"
                             "P = along(A, C, t)\n"
                             "Q = along(C, B, t)\n"
                             "K = along(B, D, t)\n"
                             "N = along(P, Q, t)\n"
                             "J = along(Q, K, t)\n"
                             "T = meet(line(P, Q), line(A, B))\n"
                             "S = meet(line(Q, K), line(C, D))\n"
                             "M = meet(line(S, N), line(T, J))\n"
                             "output M\n";

int main(void)
{
    char *diag = NULL;
    pc_scheme *s = pc_scheme_parse("arc.pcs", scheme, strlen(scheme), &diag);
    if (!s) {
        fputs(diag, stderr); // FILE:LINE:COL: error: ... with a caret
        free(diag);
        return 1;
    }
    int m = pc_find_output(s, "M");
    for (int i = 0; i < pc_npoints(s); i++) {
        char *w = pc_weight_str(s, m, i);
        printf("weight of %s: %s\n", pc_point_name(s, i), w);
        free(w);
    }

    pc_plan *p = pc_compile(s, &diag);
    if (!p) { // an equation no double can hold, e.g. a coefficient 10^400
        fputs(diag, stderr);
        free(diag);
        return 1;
    }
    double t[5] = {0, 0.25, 0.5, 0.75, 1};
    double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0},
           D[3] = {0, 0, 1};
    const double *params[1] = {t};
    const double *points[4] = {A, B, C, D};
    double out[5 * 3];
    size_t npoles = 0;
    if (pc_eval(p, m, 5, params, NULL, points, 3, out, NULL, &npoles) != PC_OK)
        return 1;
    for (int i = 0; i < 5; i++)
        printf("M(%.2f) = (%g, %g, %g)\n", t[i], out[3 * i], out[3 * i + 1],
               out[3 * i + 2]);
    printf("poles: %zu\n", npoles);

    pc_plan_free(p);
    pc_scheme_free(s);
    pc_cleanup();
    return 0;
}
