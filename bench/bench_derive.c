/*
 * bench_derive.c - derivation speed: every example derived many times
 * in-process (read once, then parse + sema + exact reduction each time);
 * prints the median and the first-call time in milliseconds per scheme,
 * and the median time to print the result as text and LaTeX (the book's
 * forms, book.c) and as JSON.
 *
 * Goals (issue #6): printing text no slower than deriving; Desargues arc
 * <= 0.15 ms, ellipse_axis_at_angle, conic_five_points, space_cubic
 * <= 1.5 ms (before: 0.27, 4.2, 4.7, 3.6 ms).
 *
 * Goals (issue #2): Desargues arc <= 0.3 ms, five-point conic <= 2 ms,
 * every example <= 5 ms.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "compiler/derive.h"
#include "compiler/print/format.h"

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "examples";
    int reps = argc > 2 ? atoi(argv[2]) : 0;
    DIR *d = opendir(dir);
    if (!d) {
        perror(dir);
        return 1;
    }
    char *names[512];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < 512) {
        size_t l = strlen(e->d_name);
        if (l > 4 && strcmp(e->d_name + l - 4, ".pcs") == 0)
            names[n++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof(char *), cmp_str);

    printf("derive: median over repeated in-process derivations\n");
    printf("%-34s %10s %10s %8s %10s %10s %10s\n", "scheme", "first ms",
           "median ms", "runs", "text ms", "latex ms", "json ms");
    FILE *sink = fopen("/dev/null", "w");
    int bad = 0;
    for (int i = 0; i < n; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        char *buf = malloc(1 << 20);
        size_t len = fread(buf, 1, (1 << 20) - 1, f);
        fclose(f);
        double t0 = bench_now_ms();
        Derived *dv = derive_source(path, buf, len, stderr, NULL);
        double first = bench_now_ms() - t0;
        if (!dv) {
            printf("%-34s %10s\n", names[i], "ERROR");
            bad = 1;
            free(buf);
            continue;
        }
        /* printing: the same Derived, many times */
        static const FormatStyle styles[3] = {FMT_TEXT, FMT_LATEX, FMT_JSON};
        double pr[3];
        for (int st = 0; st < 3; st++) {
            enum { PRINTS = 41 };
            double tp[PRINTS];
            for (int k = 0; k < PRINTS; k++) {
                double s = bench_now_ms();
                format_derived(sink, dv, styles[st], -1);
                tp[k] = bench_now_ms() - s;
            }
            qsort(tp, PRINTS, sizeof(double), bench_cmp_double);
            pr[st] = tp[PRINTS / 2];
        }
        derived_free(dv);
        /* enough runs for ~0.3 s per scheme, at least 20 */
        int runs = reps > 0 ? reps : (int)(300.0 / (first + 1e-3));
        if (runs < 20)
            runs = 20;
        if (runs > 5000)
            runs = 5000;
        double *t = malloc(sizeof(double) * (size_t)runs);
        for (int k = 0; k < runs; k++) {
            double s = bench_now_ms();
            dv = derive_source(path, buf, len, NULL, NULL);
            t[k] = bench_now_ms() - s;
            derived_free(dv);
        }
        qsort(t, (size_t)runs, sizeof(double), bench_cmp_double);
        printf("%-34s %10.4f %10.4f %8d %10.4f %10.4f %10.4f\n", names[i],
               first, t[runs / 2], runs, pr[0], pr[1], pr[2]);
        free(t);
        free(buf);
        free(names[i]);
    }
    fclose(sink);
    flint_cleanup_master();
    return bad;
}
