/*
 * bench_util.h - what every benchmark of bench/ shares: the clock and the
 * order of doubles for medians.  Header-only: each bench is one program.
 */
#ifndef PC_BENCH_UTIL_H
#define PC_BENCH_UTIL_H

#include <time.h>

/* wall-clock (monotonic) milliseconds */
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

#endif
