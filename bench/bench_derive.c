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
 * PC_BENCH_NO_WHOLE=1 skips them; PC_BENCH_WHOLE_ONLY=1 runs only them.
 */
#include <dirent.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

extern char **environ;

/* CPU milliseconds of this process (one thread: the bench's) */
static double cpu_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

/* CPU ms of one derivation of text (with -D define, or none) and then,
 * for style >= 0, printing the result in that style (derive + print, what
 * a user waits for); -1 on an error */
static double derive_print_once(const char *path, const char *text, size_t len,
                                const char *define, int style, FILE *sink)
{
    const char *defs[1] = {define};
    DeriveOptions opt = {
        .max_seconds = 600, .defines = defs, .ndefines = define ? 1 : 0};
    double s = cpu_now_ms();
    Derived *d = derive_source_ex(path, text, len, NULL, NULL, &opt);
    if (!d)
        return -1;
    if (style >= 0)
        format_derived(sink, d, (FormatStyle)style, -1);
    double t = cpu_now_ms() - s;
    derived_free(d);
    return t;
}

/* CPU ms (user + system) of the children waited for so far */
static double children_cpu_ms(void)
{
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1e3 +
           (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e3;
}

/* one whole `pc derive path [-D define]` process (text to /dev/null),
 * spawned and waited for: its CPU ms (user + system), *wall its wall ms;
 * -1 on a failure */
static double process_once(const char *pc, const char *path, const char *define,
                           double *wall)
{
    char *argv[6] = {(char *)pc, (char *)"derive", (char *)path, NULL, NULL,
                     NULL};
    if (define) {
        argv[3] = (char *)"-D";
        argv[4] = (char *)define;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    double t0 = bench_now_ms(), c0 = children_cpu_ms();
    int rc = posix_spawn(&pid, pc, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        return -1;
    int st;
    waitpid(pid, &st, 0);
    *wall = bench_now_ms() - t0;
    double cpu = children_cpu_ms() - c0;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0 ? cpu : -1;
}

enum { WHOLE_COLS = 6, WHOLE_MAX_RUNS = 401 };

/* the median of x[0..n) and the 10% and 90% points (sorts x) */
static void spread(double *x, int n, double *med, double *lo, double *hi)
{
    qsort(x, (size_t)n, sizeof(double), bench_cmp_double);
    *med = x[n / 2];
    *lo = x[n / 10];
    *hi = x[n - 1 - n / 10];
}

/* derive alone, + text, + LaTeX, + JSON (in-process) and the whole
 * `pointcalc derive` process (text; PC_BENCH_BIN, default build/pointcalc:
 * start, read, derive, print, exit), the in-process ones interleaved run
 * by run, then as many processes, for the
 * interpolation curve at n = 4 ... 96 and the book's examples named in
 * issue 24 (goals: each <= 2x derive alone; five-point conic + text <=
 * 0.2 ms; n = 48 <= 75 ms; the process at n = 12 <= 7 ms, n = 48 <= 0.1 s).
 * CPU time (the host is shared: wall time there measures the load),
 * medians, [10%..90%] for derive alone and the process. */
static void bench_whole(const char *dir, FILE *sink)
{
    static const char *const ex[] = {"desargues_arc", "conic_five_points",
                                     "double_contact", "space_cubic"};
    static const char *const ns[] = {"n=4",  "n=8",  "n=12",
                                     "n=24", "n=48", "n=96"};
    const char *pc =
        getenv("PC_BENCH_BIN") ? getenv("PC_BENCH_BIN") : "build/pointcalc";
    printf("\nderive + print and the whole process (CPU ms: medians, "
           "[10%%..90%%]; x: ratio to derive alone; process: %s derive, text,"
           " its CPU and its wall ms)\n"
           "%-20s %9s %-14s %9s %5s %9s %5s %9s %5s %9s %-14s %9s\n",
           pc, "scheme", "derive", "", "+text", "x", "+latex", "x", "+json",
           "x", "process", "", "wall");
    static double t[WHOLE_COLS][WHOLE_MAX_RUNS];
    for (int i = 0; i < 4 + 6; i++) {
        char path[1024], label[64];
        const char *def = i < 4 ? NULL : ns[i - 4];
        snprintf(path, sizeof path, "%s/%s.pcs", dir,
                 i < 4 ? ex[i] : "interpolation_bezier");
        snprintf(label, sizeof label, "%s%s%s", i < 4 ? ex[i] : "interp",
                 def ? " " : "", def ? def : "");
        size_t len;
        char *buf = bench_read_scheme(path, &len);
        if (!buf)
            continue;
        /* rounds of the four in-process columns, rotated, then as many
         * processes (a process between them would leave the caches cold);
         * about budget ms, 7 to 401 rounds */
        double budget = i >= 8 ? 4000 : 1500, spent = 0;
        static const int styles[4] = {-1, FMT_TEXT, FMT_LATEX, FMT_JSON};
        int runs = 0, bad = 0;
        while (!bad && runs < WHOLE_MAX_RUNS && (runs < 7 || spent < budget)) {
            for (int j = 0; j < 4; j++) {
                int c = (j + runs) % 4;
                double x =
                    derive_print_once(path, buf, len, def, styles[c], sink);
                bad |= x < 0;
                t[c][runs] = x;
                spent += x;
            }
            runs++;
        }
        for (int k = 0; k < runs && !bad; k++) {
            t[4][k] = process_once(pc, path, def, &t[5][k]);
            bad |= t[4][k] < 0;
        }
        free(buf);
        if (bad) {
            printf("%-20s failed (is %s built?)\n", label, pc);
            continue;
        }
        double m[WHOLE_COLS], lo[WHOLE_COLS], hi[WHOLE_COLS];
        for (int c = 0; c < WHOLE_COLS; c++)
            spread(t[c], runs, &m[c], &lo[c], &hi[c]);
        printf("%-20s %9.4f [%.3g..%.3g] %9.4f %5.2f %9.4f %5.2f %9.4f %5.2f"
               " %9.3f [%.3g..%.3g] %9.3f\n",
               label, m[0], lo[0], hi[0], m[1], m[1] / m[0], m[2], m[2] / m[0],
               m[3], m[3] / m[0], m[4], lo[4], hi[4], m[5]);
        fflush(stdout);
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
    int only = getenv("PC_BENCH_WHOLE_ONLY") != NULL;
    for (int i = 0; i < n && only; i++)
        free(names[i]);
    for (int i = 0; i < n && !only; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        size_t len;
        char *buf = bench_read_scheme(path, &len);
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
