/*
 * bench_fit.c - `pointcalc fit` in-process (issue 20, docs/fit.md): Runge's
 * function on [-1, 1] with 6 and 11 nodes, m = 100, the default starts
 * (Chebyshev, uniform, 8 seeded random ones).  Reported: the median and
 * range of fit_run over repeated rounds (the optimisation: every start's
 * Levenberg-Marquardt run), the one-time derivation of target and curve
 * (fit_new), the MSE and the iterations; then SciPy's least_squares on the
 * same objective, Jacobian and starts (bench/fit_scipy.py) where SciPy is
 * installed, "skipped" otherwise.  PYTHON names the interpreter.
 *
 * Goals (issue 20): a 6-node fit in <= 5 ms and an 11-node one in <= 50 ms.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "base/mem.h"
#include "driver/cli/fit.h"

enum { ROUNDS = 15 };

static void bench_one(int nodes, double goal_ms)
{
    FitOptions o = {
        .lo = -1, .hi = 1, .nodes = nodes, .samples = 100, .starts = 8};
    int rc;
    double t0 = bench_now_ms();
    Fit *f = fit_new("1/(1 + 25*x^2)", &o, stderr, &rc);
    double derive_ms = bench_now_ms() - t0;
    if (!f) {
        printf("  %2d nodes: fit_new failed\n", nodes);
        return;
    }
    double t[ROUNDS], med, lo, hi, mse = 0;
    int iterations = 0, ok = 1;
    for (int k = 0; k < ROUNDS; k++) {
        FitResult r;
        t0 = bench_now_ms();
        ok &= fit_run(f, &r) == 0;
        t[k] = bench_now_ms() - t0;
        mse = r.mse;
        iterations = r.lsq.iterations;
        fit_result_clear(&r);
    }
    bench_stats(t, ROUNDS, &med, &lo, &hi);
    printf("  %2d nodes: fit %8.3f ms [%.3f..%.3f] (10 starts), derivation "
           "%.1f ms, MSE %.6g, %d iterations (best start)%s\n",
           nodes, med, lo, hi, derive_ms, mse, iterations,
           ok ? "" : ", NOT CONVERGED");
    printf("  %-46s %8.3f ms goal <= %.0f ms: %s\n", "  median fit", med,
           goal_ms,
           hi <= goal_ms  ? "met"
           : lo > goal_ms ? "not met"
                          : "undecided (spread)");
    fit_free(f);
}

int main(void)
{
    mem_use_for_gmp_flint();
    printf("bench_fit: pointcalc fit, Runge 1/(1 + 25x^2) on [-1, 1], m = "
           "100, in-process (%d rounds)\n",
           ROUNDS);
    bench_one(6, 5);
    bench_one(11, 50);
    flint_cleanup_master();
    fflush(stdout);
    /* the first interpreter with SciPy: $PYTHON (make bench picks one with
     * SymPy, which may lack SciPy), python3, then the system's (Debian's
     * python3-scipy) */
    const char *cmd =
        "for p in \"$PYTHON\" python3 /usr/bin/python3; do "
        "if [ -n \"$p\" ] && \"$p\" -c 'import scipy, numpy' 2>/dev/null; "
        "then exec \"$p\" bench/fit_scipy.py 6 11; fi; done; "
        "echo '  skipped (no python3 with scipy)'";
    printf("bench_fit: SciPy least_squares, same objective, Jacobian and "
           "starts:\n");
    fflush(stdout);
    if (system(cmd) != 0)
        printf("  skipped (bench/fit_scipy.py failed)\n");
    return 0;
}
