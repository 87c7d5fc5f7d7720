/*
 * bench_natural.c - curves in natural parametrization (issue 21,
 * docs/natural.md), in-process:
 *
 *   G1 fit   the clothoid between two points with tangent angles, on the
 *            issue's sweep (unit chord, angles uniform in (-0.95 pi,
 *            0.95 pi), a fixed seed): Newton (nat_fit_g1) and the
 *            article's Hooke-Jeeves (nat_fit_hj, to an end-point error of
 *            1e-12, at most 20000 integrals), the same quadrature, rounds
 *            interleaved; per fit: median [min..max] over the rounds, the
 *            success rate, iterations and integrals
 *   G2, G3   a segment of the quadratic/cubic law continuing a clothoid
 *   eval     a fitted clothoid at 10^6 points: the table (what emit-c's
 *            C does) and the quadrature
 *
 * Goals (issue 21): <= 10 us a G1 fit, >= 50x faster than Hooke-Jeeves
 * at equal accuracy, <= 100 ns a point.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench/bench_util.h"

#include "runtime/natural.h"
#include "runtime/plan.h"

enum { NFIT = 1000, NHJ = 200, ROUNDS = 7, NEVAL = 1000000 };

static uint64_t rng = 0x9e3779b97f4a7c15ULL;
static double rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static double cfg[NFIT][2];
static volatile double sink;

static double round_newton(int *fails, int *iters, double *err)
{
    double t0 = bench_now_ms();
    *fails = *iters = 0;
    *err = 0;
    for (int i = 0; i < NFIT; i++) {
        NatSegment g;
        NatStats st;
        if (nat_fit_g1(0, 0, cfg[i][0], 1, 0, cfg[i][1], &g, &st))
            ++*fails;
        *iters += st.iterations;
        *err = fmax(*err, st.error);
        sink += g.length;
    }
    return (bench_now_ms() - t0) * 1000 / NFIT; // us a fit
}

static double round_hj(int *fails, int *other, long *ints)
{
    double t0 = bench_now_ms();
    *fails = *other = 0;
    *ints = 0;
    for (int i = 0; i < NHJ; i++) {
        NatSegment h, g;
        NatStats st;
        if (nat_fit_hj(0, 0, cfg[i][0], 1, 0, cfg[i][1], 1e-12, 20000, &h, &st))
            ++*fails;
        *ints += st.integrals;
        nat_fit_g1(0, 0, cfg[i][0], 1, 0, cfg[i][1], &g, NULL);
        if (fabs(h.length - g.length) > 1e-6 * g.length)
            ++*other; // not the minimal-winding clothoid
        sink += h.length;
    }
    double tn = 0; // the Newton fits inside the loop, taken out again
    double t1 = bench_now_ms();
    for (int i = 0; i < NHJ; i++) {
        NatSegment g;
        nat_fit_g1(0, 0, cfg[i][0], 1, 0, cfg[i][1], &g, NULL);
        sink += g.length;
    }
    tn = bench_now_ms() - t1;
    return (t1 - t0 - tn) * 1000 / NHJ;
}

static void bench_g1(void)
{
    for (int i = 0; i < NFIT; i++) {
        cfg[i][0] = (2 * rnd() - 1) * 0.95 * NAT_PI;
        cfg[i][1] = (2 * rnd() - 1) * 0.95 * NAT_PI;
    }
    double tn[ROUNDS], th[ROUNDS], err = 0;
    int fn = 0, it = 0, fh = 0, other = 0;
    long ints = 0;
    for (int r = 0; r < ROUNDS; r++) {
        tn[r] = round_newton(&fn, &it, &err);
        th[r] = round_hj(&fh, &other, &ints);
    }
    double mn, ln, hn, mh, lh, hh;
    bench_stats(tn, ROUNDS, &mn, &ln, &hn);
    bench_stats(th, ROUNDS, &mh, &lh, &hh);
    printf("  G1 Newton:       %8.2f us a fit [%.2f..%.2f], %d/%d solved, "
           "%.2f steps a fit, end-point error <= %.2g\n",
           mn, ln, hn, NFIT - fn, NFIT, (double)it / NFIT, err);
    printf("  G1 Hooke-Jeeves: %8.2f us a fit [%.2f..%.2f], %d/%d to 1e-12, "
           "%.0f integrals a fit, %d not the minimal-winding clothoid\n",
           mh, lh, hh, NHJ - fh, NHJ, (double)ints / NHJ, other);
    printf("  %-40s %8.2f us goal <= 10 us: %s\n", "  median Newton fit", mn,
           hn <= 10  ? "met"
           : ln > 10 ? "not met"
                     : "undecided (spread)");
    printf("  %-40s %8.1fx goal >= 50x: %s\n", "  Hooke-Jeeves / Newton",
           mh / mn,
           lh / hn >= 50  ? "met"
           : hh / ln < 50 ? "not met"
                          : "undecided (spread)");
}

static void bench_laws(void)
{
    for (NatLaw l = NAT_QUADRATIC; l <= NAT_CUBIC; l++) {
        double t[ROUNDS];
        int fails = 0, iters = 0, n = 200;
        for (int r = 0; r < ROUNDS; r++) {
            fails = iters = 0;
            double t0 = bench_now_ms();
            for (int i = 0; i < n; i++) {
                NatSegment g, q;
                NatStats st;
                nat_fit_g1(0, 0, 0.6 * cfg[i][0], 1, 0, 0.6 * cfg[i][1], &g,
                           NULL);
                double k0 = g.k[0] + 0.5 * (cfg[i + n][0] / NAT_PI);
                double dk0 = g.k[1] + 0.5 * (cfg[i + n][1] / NAT_PI);
                fails += nat_fit_law(l, 0, 0, 0.6 * cfg[i][0], 1, 0,
                                     0.6 * cfg[i][1], k0, dk0, &q, &st) != 0;
                iters += st.iterations;
                sink += q.length;
            }
            t[r] = (bench_now_ms() - t0) * 1000 / n;
        }
        double m, lo, hi;
        bench_stats(t, ROUNDS, &m, &lo, &hi);
        printf("  %s segment:  %8.2f us a fit [%.2f..%.2f], %d/%d solved, "
               "%.1f Newton steps a fit (continuation included)\n",
               l == NAT_QUADRATIC ? "G2 quadratic" : "G3 cubic    ", m, lo, hi,
               n - fails, n, (double)iters / n);
    }
}

static void bench_eval(void)
{
    NatSegment g;
    nat_fit_g1(0, 0, 1.2, 1, 0, -0.7, &g, NULL);
    NatTable t;
    nat_table_build(&t, &g);
    double tt[ROUNDS], tq[ROUNDS];
    for (int r = 0; r < ROUNDS; r++) {
        double t0 = bench_now_ms(), x, y, acc = 0;
        for (int i = 0; i < NEVAL; i++) {
            nat_table_eval(&t, g.length * i / NEVAL, &x, &y);
            acc += x + y;
        }
        tt[r] = (bench_now_ms() - t0) * 1e6 / NEVAL;
        t0 = bench_now_ms();
        for (int i = 0; i < NEVAL / 100; i++) {
            nat_point(&g, g.length * i / (NEVAL / 100), &x, &y);
            acc += x + y;
        }
        tq[r] = (bench_now_ms() - t0) * 1e6 / (NEVAL / 100);
        sink += acc;
    }
    double m, lo, hi, mq, lq, hq;
    bench_stats(tt, ROUNDS, &m, &lo, &hi);
    bench_stats(tq, ROUNDS, &mq, &lq, &hq);
    printf("  eval, table:     %8.1f ns a point [%.1f..%.1f] (%d panels of "
           "%d coefficients); quadrature %.0f ns [%.0f..%.0f]\n",
           m, lo, hi, t.npanels, t.ncoef, mq, lq, hq);
    printf("  %-40s %8.1f ns goal <= 100 ns: %s\n", "  median table eval", m,
           hi <= 100  ? "met"
           : lo > 100 ? "not met"
                      : "undecided (spread)");
    nat_table_free(&t);
    /* the scheme language's natx and naty (plan.h NATX, NATY): a
     * quadrature each, per point */
    double tl[ROUNDS];
    for (int r = 0; r < ROUNDS; r++) {
        double t0 = bench_now_ms(), acc = 0;
        for (int i = 0; i < NEVAL / 100; i++) {
            double u = g.length * i / (NEVAL / 100);
            acc += plan_natural_eval(0, g.k, u) + plan_natural_eval(1, g.k, u);
        }
        tl[r] = (bench_now_ms() - t0) * 1e6 / (NEVAL / 100);
        sink += acc;
    }
    bench_stats(tl, ROUNDS, &m, &lo, &hi);
    printf("  eval, natx+naty: %8.1f ns a point [%.1f..%.1f] (a scheme's "
           "natural curve: two quadratures)\n",
           m, lo, hi);
}

int main(void)
{
    printf("bench_natural: natural-parametrization curves, in-process (%d "
           "rounds, interleaved)\n",
           ROUNDS);
    bench_g1();
    bench_laws();
    bench_eval();
    return sink == 42 ? 1 : 0;
}
