/*
 * bench_interp.c - linear point systems against what users run today.
 *
 * The order-n interpolation curve (the monograph's Maple program, 4.8:
 * examples/interpolation_bezier.pcs with -D n=N) for n = 3 ... 48, and the
 * symbolic system of the 3.6 M5 contour arc (examples/contour_arcs.pcs, 10
 * unknown points with coefficients in t): pointcalc in-process (median of
 * repeated derivations, parse to reduced weights), then SymPy (the same
 * program as a SymPy user writes it, bench/sympy/bench_interpolation.py, one
 * run per order) and Maxima (linsolve, bench/maxima/bench_interpolation.mac,
 * the mean over at least 0.2 s of runs: its clock ticks in 10 ms) when they
 * are installed; "skipped" otherwise, "timeout" past 600 s.  PYTHON names the
 * interpreter (make bench finds one with sympy); PC_BENCH_PEERS=0 skips the
 * peers, PC_BENCH_MAX_N caps the peers' orders (default 48).
 *
 * Goals (issue 7): n = 12 in <= 5 ms, n = 48 in <= 0.5 s, >= 100x SymPy
 * from n = 6 on.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "compiler/derive.h"

static const int ORDERS[] = {3, 4, 6, 8, 12, 24, 48};
enum { NORD = sizeof ORDERS / sizeof ORDERS[0] };

/* median ms of deriving path with define (NULL: none); *spread gets the
 * interquartile range relative to the median */
static double time_derive(const char *path, const char *define, double *spread)
{
    size_t len;
    char *text = bench_read_scheme(path, &len);
    const char *defs[1] = {define};
    DeriveOptions opt = {
        .max_seconds = 600, .defines = defs, .ndefines = define ? 1 : 0};
    if (!text)
        return -1;
    double t0 = bench_now_ms();
    Derived *d = derive_source_ex(path, text, len, stderr, NULL, &opt);
    double first = bench_now_ms() - t0;
    if (!d) {
        free(text);
        return -1;
    }
    derived_free(d);
    int runs = (int)(500.0 / (first + 1e-3));
    runs = runs < 7 ? 7 : runs > 2001 ? 2001 : runs;
    double *t = malloc(sizeof(double) * (size_t)runs);
    for (int k = 0; k < runs; k++) {
        double s = bench_now_ms();
        d = derive_source_ex(path, text, len, NULL, NULL, &opt);
        t[k] = bench_now_ms() - s;
        derived_free(d);
    }
    qsort(t, (size_t)runs, sizeof(double), bench_cmp_double);
    double med = t[runs / 2];
    *spread = (t[(3 * runs) / 4] - t[runs / 4]) / med;
    free(t);
    free(text);
    return med;
}

/* runs cmd and stores "interp N SECONDS" / "contour5 SECONDS" /
 * "maxima N SECONDS" lines in ms[] (index by order), contour */
static void run_peer(const char *cmd, const char *tag, double *ms,
                     double *contour)
{
    FILE *p = popen(cmd, "r");
    char line[256];
    if (!p)
        return;
    while (fgets(line, sizeof line, p)) {
        char word[32];
        int n;
        double s;
        if (sscanf(line, "%31s %d %lf", word, &n, &s) == 3 &&
            strcmp(word, tag) == 0) {
            for (int i = 0; i < NORD; i++)
                if (ORDERS[i] == n)
                    ms[i] = 1e3 * s;
        } else if (sscanf(line, "%31s %lf", word, &s) == 2 &&
                   strcmp(word, "contour5") == 0) {
            *contour = 1e3 * s;
        }
    }
    pclose(p);
}

static void cell(double peer, double pc)
{
    if (peer < 0)
        printf(" %12s %9s", "skipped", "");
    else if (peer == 0)
        printf(" %12s %9s", "timeout", "");
    else
        printf(" %12.2f %8.0fx", peer, peer / pc);
}

int main(void)
{
    double pc[NORD], spread[NORD], sy[NORD], mx[NORD], pcc, sc, sy_c = -1,
                                                                mx_c = -1;
    int maxn = getenv("PC_BENCH_MAX_N") ? atoi(getenv("PC_BENCH_MAX_N")) : 48;
    int peers = !getenv("PC_BENCH_PEERS") || atoi(getenv("PC_BENCH_PEERS"));
    const char *py = getenv("PYTHON");
    printf("interpolation (monograph 4.8): pointcalc median of in-process "
           "derivations [IQR/median]; SymPy one run each; Maxima the mean "
           "over >= 0.2 s of runs; ms\n");
    for (int i = 0; i < NORD; i++) {
        char def[16];
        snprintf(def, sizeof def, "n=%d", ORDERS[i]);
        pc[i] =
            time_derive("examples/interpolation_bezier.pcs", def, &spread[i]);
        sy[i] = mx[i] = -1;
    }
    pcc = time_derive("examples/contour_arcs.pcs", NULL, &sc);
    if (peers && py && *py) {
        char cmd[1024], list[256] = "";
        for (int i = 0; i < NORD; i++)
            if (ORDERS[i] <= maxn) {
                size_t l = strlen(list);
                snprintf(list + l, sizeof list - l, " %d", ORDERS[i]);
                sy[i] = 0; /* timeout unless a figure arrives */
            }
        snprintf(cmd, sizeof cmd,
                 "timeout 600 %s bench/sympy/bench_interpolation.py --contour"
                 "%s 2>/dev/null",
                 py, list);
        sy_c = 0;
        run_peer(cmd, "interp", sy, &sy_c);
    }
    if (peers && system("command -v maxima >/dev/null 2>&1") == 0) {
        char cmd[512];
        for (int i = 0; i < NORD; i++)
            if (ORDERS[i] <= maxn)
                mx[i] = 0;
        snprintf(cmd, sizeof cmd,
                 "timeout 600 maxima --very-quiet --batch-string='maxn: %d$ "
                 "batchload(\"bench/maxima/bench_interpolation.mac\")$' "
                 "2>/dev/null",
                 maxn);
        mx_c = 0;
        run_peer(cmd, "maxima", mx, &mx_c);
    }
    printf("%-10s %12s %8s %12s %9s %12s %9s\n", "case", "pointcalc", "spread",
           "sympy", "ratio", "maxima", "ratio");
    for (int i = 0; i < NORD; i++) {
        char name[32];
        snprintf(name, sizeof name, "n = %d", ORDERS[i]);
        printf("%-10s %12.4f %7.0f%%", name, pc[i], 100 * spread[i]);
        cell(sy[i], pc[i]);
        cell(mx[i], pc[i]);
        putchar('\n');
    }
    printf("%-10s %12.4f %7.0f%%", "3.6 M5", pcc, 100 * sc);
    cell(sy_c, pcc);
    cell(mx_c, pcc);
    putchar('\n');
    for (int i = 0; i < NORD; i++) {
        if (ORDERS[i] == 12)
            printf("goal n = 12 <= 5 ms: %.3f ms, %s\n", pc[i],
                   pc[i] <= 5 ? "met" : "not met");
        if (ORDERS[i] == 48)
            printf("goal n = 48 <= 500 ms: %.3f ms, %s\n", pc[i],
                   pc[i] <= 500 ? "met" : "not met");
    }
    double worst = -1;
    for (int i = 0; i < NORD; i++)
        if (ORDERS[i] >= 6 && sy[i] > 0 && (worst < 0 || sy[i] / pc[i] < worst))
            worst = sy[i] / pc[i];
    if (worst > 0)
        printf("goal >= 100x SymPy from n = 6 on: worst %.0fx, %s\n", worst,
               worst >= 100 ? "met" : "not met");
    flint_cleanup_master();
    return 0;
}
