/*
 * bench_util.h - what every benchmark of bench/ shares: the clock and the
 * order of doubles for medians.  Header-only: each bench is one program.
 */
#ifndef PC_BENCH_UTIL_H
#define PC_BENCH_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* wall-clock (monotonic) milliseconds */
/* the scheme at path (at most 1 MiB), malloc'ed, or NULL */
static inline char *bench_read_scheme(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = malloc(1 << 20);
    *len = buf ? fread(buf, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    return buf;
}

static inline double bench_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

/* qsort order of doubles */
static inline int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* median and range of x[0..n) (a sorted copy) */
static inline void bench_stats(const double *x, int n, double *med, double *lo,
                               double *hi)
{
    double *s = (double *)malloc(sizeof *s * (size_t)n);
    memcpy(s, x, sizeof *s * (size_t)n);
    qsort(s, (size_t)n, sizeof *s, bench_cmp_double);
    *med = s[n / 2];
    *lo = s[0];
    *hi = s[n - 1];
    free(s);
}

/* A goal on the per-round ratio ta/tb of two contestants timed in the same
 * rounds: met when every round is within it, not met when none is, else
 * undecided (the spread of the host decides nothing). */
static inline void bench_verdict(const char *what, const double *ta,
                                 const double *tb, int rounds, double goal)
{
    double r[64], med, lo, hi;
    if (rounds > 64)
        rounds = 64;
    for (int k = 0; k < rounds; k++)
        r[k] = ta[k] / tb[k];
    bench_stats(r, rounds, &med, &lo, &hi);
    printf("  %-46s %5.2f [%4.2f..%4.2f] goal <= %.1f: %s\n", what, med, lo, hi,
           goal,
           hi <= goal  ? "met"
           : lo > goal ? "not met"
                       : "undecided (spread)");
}

#endif
