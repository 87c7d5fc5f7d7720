/*
 * bench_fit.c - `pointcalc fit` in-process (issue 20, docs/fit.md): Runge's
 * function on [-1, 1] with 5 to 11 nodes, m = 100, the default starts
 * (Chebyshev, uniform, 8 seeded random ones).  For every node count the
 * solver of this tree ("now") and that of stop 28 ("before",
 * FitOptions.legacy: plain Levenberg-Marquardt, plan_eval per call, the
 * residuals computed again with every Jacobian, only the best basin
 * joined) run in interleaved rounds: the median and range of fit_run (the
 * optimisation: every start), the MSE, the solver's iterations over all
 * starts.  Then SciPy's least_squares on the same objective, Jacobian and
 * starts (bench/fit_scipy.py) where SciPy is installed ("skipped"
 * otherwise), and one table of the three side by side: the times, and
 * the MSE against SciPy's best, both evaluated by pointcalc's residuals
 * ("WORSE" beyond 1e-9 relative: at 11 nodes the rounding of the
 * residuals is some 1e-8 of the MSE).
 * PYTHON names the interpreter.
 *
 * Goals (issue 20): a 6-node fit in <= 5 ms and an 11-node one in <= 50 ms,
 * >= 10x SciPy.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "base/mem.h"
#include "driver/cli/fit.h"

enum { ROUNDS = 15, NMIN = 5, NMAX = 11 };

typedef struct Side {
    double med, lo, hi, mse;
    int iterations, ok;
} Side;

static Side side_now[NMAX + 1], side_before[NMAX + 1];
static double scipy_med[NMAX + 1], scipy_lo[NMAX + 1], scipy_hi[NMAX + 1];
static double scipy_mse[NMAX + 1];
static double scipy_ours[NMAX + 1]; /* SciPy's nodes in pointcalc's objective */

/* the MSE of the nodes x (nodes values) in pointcalc's own objective: the
 * two optima compared with one evaluation of the residuals (at 11 nodes
 * the MSE, 3e-15, is sum r_i^2 of r_i ~ 5e-8 whose rounding, ~1e-16, is
 * some 1e-8 of it: SciPy's numpy evaluation differs by that much) */
static double mse_in_ours(int nodes, const double *x)
{
    FitOptions o = {.lo = -1, .hi = 1, .nodes = nodes, .samples = 100};
    int rc;
    Fit *f = fit_new("1/(1 + 25*x^2)", &o, stderr, &rc);
    double *r = pc_xmalloc(sizeof *r * f->ns), s = 0;
    if (fit_residuals_x(f, x + 1, r, NULL) != 0)
        s = NAN;
    for (size_t i = 0; i < f->ns; i++)
        s += r[i] * r[i];
    s /= (double)f->ns;
    pc_free(r);
    fit_free(f);
    return s;
}

/* one round of fit f: its time, MSE and iterations into t[k], s */
static void round_of(Fit *f, double *t, Side *s)
{
    FitResult r;
    double t0 = bench_now_ms();
    s->ok &= fit_run(f, &r) == 0;
    *t = bench_now_ms() - t0;
    s->mse = r.mse;
    s->iterations = r.iterations_all;
    fit_result_clear(&r);
}

static void bench_nodes(int nodes)
{
    Fit *f[2];
    for (int v = 0; v < 2; v++) {
        FitOptions o = {.lo = -1,
                        .hi = 1,
                        .nodes = nodes,
                        .samples = 100,
                        .starts = 8,
                        .legacy = v};
        int rc;
        f[v] = fit_new("1/(1 + 25*x^2)", &o, stderr, &rc);
        if (!f[v]) {
            printf("  %2d nodes: fit_new failed\n", nodes);
            exit(1);
        }
    }
    double t[2][ROUNDS];
    Side *s[2] = {&side_now[nodes], &side_before[nodes]};
    s[0]->ok = s[1]->ok = 1;
    for (int k = 0; k < ROUNDS; k++) /* interleaved: now, before */
        for (int v = 0; v < 2; v++)
            round_of(f[v], &t[v][k], s[v]);
    for (int v = 0; v < 2; v++) {
        bench_stats(t[v], ROUNDS, &s[v]->med, &s[v]->lo, &s[v]->hi);
        fit_free(f[v]);
    }
    printf("  %2d nodes: now %8.3f ms [%.3f..%.3f], before %8.3f ms "
           "[%.3f..%.3f]; MSE %.6g / %.6g; iterations %d / %d%s\n",
           nodes, s[0]->med, s[0]->lo, s[0]->hi, s[1]->med, s[1]->lo, s[1]->hi,
           s[0]->mse, s[1]->mse, s[0]->iterations, s[1]->iterations,
           s[0]->ok && s[1]->ok ? "" : ", NOT CONVERGED");
    bench_verdict("    now / before, per round", t[0], t[1], ROUNDS, 1.0);
}

/* SciPy's lines "  N nodes: scipy MED ms [LO..HI] (10 starts), MSE X,
 * nodes ..." read into scipy_*; 0 when it ran */
static int run_scipy(void)
{
    /* the first interpreter with SciPy: $PYTHON (make bench picks one with
     * SymPy, which may lack SciPy), python3, then the system's (Debian's
     * python3-scipy) */
    const char *cmd =
        "for p in \"$PYTHON\" python3 /usr/bin/python3; do "
        "if [ -n \"$p\" ] && \"$p\" -c 'import scipy, numpy' 2>/dev/null; "
        "then exec \"$p\" bench/fit_scipy.py -r 3 5 6 7 8 9 10 11; fi; "
        "done; echo '  skipped (no python3 with scipy)'";
    FILE *p = popen(cmd, "r");
    char line[1024];
    int got = 0;
    while (p && fgets(line, sizeof line, p)) {
        int n;
        double med, lo, hi, mse;
        fputs(line, stdout);
        if (sscanf(line,
                   " %d nodes: scipy %lf ms [%lf..%lf] (10 starts), "
                   "MSE %lf",
                   &n, &med, &lo, &hi, &mse) == 5 &&
            n >= NMIN && n <= NMAX) {
            scipy_med[n] = med;
            scipy_lo[n] = lo;
            scipy_hi[n] = hi;
            scipy_mse[n] = mse;
            const char *q = strstr(line, "nodes -");
            double x[NMAX + 1];
            int k = 0;
            for (q = q ? q + 6 : NULL; q && k < n; k++) {
                char *end;
                x[k] = strtod(q, &end);
                q = end;
            }
            scipy_ours[n] = k == n ? mse_in_ours(n, x) : NAN;
            got++;
        }
    }
    if (p)
        pclose(p);
    return got ? 0 : -1;
}

static void table(int have_scipy)
{
    printf("\nbench_fit: Runge on [-1, 1], m = 100, 10 starts; medians "
           "[min..max] in ms\n");
    printf("| nodes | now | before (stop 28) | SciPy | now/before | "
           "SciPy/now | MSE now | MSE SciPy (its own; in pointcalc's "
           "objective) | (now - SciPy)/SciPy, pointcalc's objective |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int n = NMIN; n <= NMAX; n++) {
        const Side *a = &side_now[n], *b = &side_before[n];
        printf("| %d | %.2f [%.2f..%.2f] | %.2f [%.2f..%.2f] | ", n, a->med,
               a->lo, a->hi, b->med, b->lo, b->hi);
        if (have_scipy && scipy_med[n] > 0)
            printf("%.0f [%.0f..%.0f] | %.2f | %.0fx | %.9g | %.9g; %.9g | "
                   "%+.1e%s |\n",
                   scipy_med[n], scipy_lo[n], scipy_hi[n], a->med / b->med,
                   scipy_med[n] / a->med, a->mse, scipy_mse[n], scipy_ours[n],
                   (a->mse - scipy_ours[n]) / scipy_ours[n],
                   a->mse <= scipy_ours[n] * (1 + 1e-9) ? "" : " WORSE");
        else
            printf("skipped | %.2f | - | %.6g | - | - |\n", a->med / b->med,
                   a->mse);
    }
    printf("goals: 6 nodes <= 5 ms: %s (median %.2f); 11 nodes <= 50 ms: %s "
           "(median %.2f)\n",
           side_now[6].hi <= 5  ? "met"
           : side_now[6].lo > 5 ? "not met"
                                : "undecided (spread)",
           side_now[6].med,
           side_now[11].hi <= 50  ? "met"
           : side_now[11].lo > 50 ? "not met"
                                  : "undecided (spread)",
           side_now[11].med);
}

int main(void)
{
    mem_use_for_gmp_flint();
    printf("bench_fit: pointcalc fit, Runge 1/(1 + 25x^2) on [-1, 1], m = "
           "100, in-process (%d interleaved rounds)\n",
           ROUNDS);
    for (int n = NMIN; n <= NMAX; n++)
        bench_nodes(n);
    flint_cleanup_master();
    printf("bench_fit: SciPy least_squares, same objective, Jacobian and "
           "starts (3 rounds):\n");
    fflush(stdout);
    table(run_scipy() == 0);
    return 0;
}
