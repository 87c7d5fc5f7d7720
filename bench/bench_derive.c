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
 *
 * Then derive alone and derive + text / LaTeX / JSON for the interpolation
 * curve at n = 4 ... 96 and the examples of issue 24 (goals: each <= 2x
 * derive alone; five-point conic + text <= 0.2 ms, n = 48 <= 75 ms);
 * PC_BENCH_NO_WHOLE=1 skips them.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

/* the scheme at path (at most 1 MiB), malloc'ed, or NULL */
static char *read_scheme(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = malloc(1 << 20);
    *len = buf ? fread(buf, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    return buf;
}

/* median ms of deriving text (with -D define, or none) and then, for
 * style >= 0, printing the result in that style (derive + print, what a
 * user waits for); the runs fill about budget_ms, at least 7 */

static double time_derive_print(const char *path, const char *text, size_t len,
                                const char *define, int style, double budget_ms,
                                FILE *sink)
{
    const char *defs[1] = {define};
    DeriveOptions opt = {
        .max_seconds = 600, .defines = defs, .ndefines = define ? 1 : 0};
    double t[2001];
    int runs = 0;
    double spent = 0;
    while (runs < 2001 && (runs < 7 || spent < budget_ms)) {
        double s = bench_now_ms();
        Derived *d = derive_source_ex(path, text, len, NULL, NULL, &opt);
        if (!d)
            return -1;
        if (style >= 0)
            format_derived(sink, d, (FormatStyle)style, -1);
        t[runs] = bench_now_ms() - s;
        spent += t[runs++];
        derived_free(d);
    }
    qsort(t, (size_t)runs, sizeof(double), bench_cmp_double);
    return t[runs / 2];
}

/* derive alone, + text, + LaTeX, + JSON (issue 24: each <= 2x derive
 * alone) for the interpolation curve at n = 4 ... 96 and the book's
 * examples named in issue 24, the styles interleaved run by run */
static void bench_whole(const char *dir, FILE *sink)
{
    static const char *const ex[] = {"desargues_arc", "conic_five_points",
                                     "double_contact", "space_cubic"};
    static const char *const ns[] = {"n=4",  "n=8",  "n=12",
                                     "n=24", "n=48", "n=96"};
    printf("\nderive + print (in-process medians, ms; ratio to derive "
           "alone)\n%-24s %10s %10s %6s %10s %6s %10s %6s\n",
           "scheme", "derive", "+text", "x", "+latex", "x", "+json", "x");
    for (int i = 0; i < 4 + 6; i++) {
        char path[1024], label[64];
        const char *def = i < 4 ? NULL : ns[i - 4];
        snprintf(path, sizeof path, "%s/%s.pcs", dir,
                 i < 4 ? ex[i] : "interpolation_bezier");
        snprintf(label, sizeof label, "%s%s%s", i < 4 ? ex[i] : "interp",
                 def ? " " : "", def ? def : "");
        size_t len;
        char *buf = read_scheme(path, &len);
        if (!buf)
            continue;
        double budget = i >= 8 ? 2000 : 300, m[4] = {0, 0, 0, 0};
        static const int styles[4] = {-1, FMT_TEXT, FMT_LATEX, FMT_JSON};
        for (int st = 0; st < 4; st++)
            m[st] = time_derive_print(path, buf, len, def, styles[st], budget,
                                      sink);
        printf("%-24s %10.4f %10.4f %6.2f %10.4f %6.2f %10.4f %6.2f\n", label,
               m[0], m[1], m[1] / m[0], m[2], m[2] / m[0], m[3], m[3] / m[0]);
        fflush(stdout);
        free(buf);
    }
}

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
        size_t len;
        char *buf = read_scheme(path, &len);
        if (!buf)
            continue;
        double t0 = bench_now_ms();
        /* (with the numeric back end: examples/numeric_kepler.pcs) */
        DeriveOptions nopt = {.max_seconds = 60, .numeric = numsolve_run};
        Derived *dv = derive_source_ex(path, buf, len, stderr, NULL, &nopt);
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
            dv = derive_source_ex(path, buf, len, NULL, NULL, &nopt);
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
    if (!getenv("PC_BENCH_NO_WHOLE"))
        bench_whole(dir, sink);
    fclose(sink);
    flint_cleanup_master();
    return bad;
}
