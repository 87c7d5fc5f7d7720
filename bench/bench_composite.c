/*
 * bench_composite.c - a composite curve as one formula in |t - t_k| (issue
 * 19 item 6): emit-c's branch-free code against a hand-written branchy
 * piecewise loop, one thread, ns/sample over 10^6 samples.
 *
 *   square   examples/composite_square.pcs: the closed polyline O A B C O,
 *            knots t = 0 .. 4, in 2D.  Hand: an if/else chain over the
 *            sides (t <= 0, t < 1, ... : the side's two vertices mixed).
 *   spline   S(t) = 1/2 + t/5 + sum_k c_k |t - k|^3, ten knots k = 0 .. 9
 *            (a C^2 cubic spline), scalar.  Hand: a binary search over the
 *            knots and the interval's cubic in powers of t - t_j, its
 *            coefficients tabled once (what an engineer writes).
 *
 * Each at two orders of the samples: sorted (a sweep, as a plot or a
 * table: the hand loop's branches are predicted) and shuffled (the same
 * values in random order: they are not).  The generated code and the hand
 * loops are compiled at run time into one shared object per flag set
 * (`cc -O2` and `cc -O3 -march=native`), so each comparison is like for
 * like.  Rounds are interleaved with a rotating order; each contestant
 * reports its median and spread, and the goal (generated <= 1.2x the hand
 * loop) is judged per round (bench_util.h: met only when every round
 * agrees).  PC_BENCH_QUICK=1 runs 10^5 samples.  Times are CPU time of this
 * process.
 *
 * The single formula does O(knots) work per sample (a sign per knot, and
 * the pieces' weights prod (1 +- sign)/2), the hand loop O(1) after its
 * search; the numbers say what that costs (docs/codegen.md).
 */
#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <flint/flint.h>

#include "bench/bench_util.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/derive.h"

enum { NKNOTS = 10, FLAGSETS = 2 };
static const char *const flagsets[FLAGSETS] = {"-O2", "-O3 -march=native"};

/* the spline's coefficients: c_k = (-1)^k (k + 1)/7 */
static int coef_num(int k)
{
    return (k % 2 ? -1 : 1) * (k + 1);
}

/* the hand-written loops, compiled with the generated code */
static const char hand_src[] =
    "#include <stddef.h>\n"
    "void hand_square(size_t n, const double *t, const double *O,\n"
    "                 const double *A, const double *B, const double *C,\n"
    "                 double *out);\n"
    "void hand_square(size_t n, const double *t, const double *O,\n"
    "                 const double *A, const double *B, const double *C,\n"
    "                 double *out)\n"
    "{\n"
    "    for (size_t i = 0; i < n; i++) {\n"
    "        double s = t[i], u;\n"
    "        const double *P, *Q;\n"
    "        if (s <= 0) { P = Q = O; u = 0; }\n"
    "        else if (s < 1) { P = O; Q = A; u = s; }\n"
    "        else if (s < 2) { P = A; Q = B; u = s - 1; }\n"
    "        else if (s < 3) { P = B; Q = C; u = s - 2; }\n"
    "        else if (s < 4) { P = C; Q = O; u = s - 3; }\n"
    "        else { P = Q = O; u = 0; }\n"
    "        out[2 * i] = P[0] + (Q[0] - P[0]) * u;\n"
    "        out[2 * i + 1] = P[1] + (Q[1] - P[1]) * u;\n"
    "    }\n"
    "}\n"
    "void hand_spline(size_t n, const double *t, const double *knot,\n"
    "                 int m, const double (*c)[4], double *out);\n"
    "void hand_spline(size_t n, const double *t, const double *knot,\n"
    "                 int m, const double (*c)[4], double *out)\n"
    "{\n"
    "    for (size_t i = 0; i < n; i++) {\n"
    "        double s = t[i];\n"
    "        int lo = 0, hi = m; /* interval j: knot[j-1] <= s < knot[j] */\n"
    "        while (lo < hi) {\n"
    "            int mid = (lo + hi) / 2;\n"
    "            if (s < knot[mid]) hi = mid; else lo = mid + 1;\n"
    "        }\n"
    "        double x = s - knot[lo > 0 ? lo - 1 : 0];\n"
    "        const double *k = c[lo];\n"
    "        out[i] = ((k[3] * x + k[2]) * x + k[1]) * x + k[0];\n"
    "    }\n"
    "}\n";

typedef void (*square_fn)(size_t, const double *, const double *,
                          const double *, const double *, const double *, int,
                          double *);
typedef void (*hsquare_fn)(size_t, const double *, const double *,
                           const double *, const double *, const double *,
                           double *);
typedef void (*spline_fn)(size_t, const double *, int, double *);
typedef void (*hspline_fn)(size_t, const double *, const double *, int,
                           const double (*)[4], double *);

static double O[2] = {0, 0}, A[2] = {1, 0}, B[2] = {1, 1}, C[2] = {0, 1};
static double knot[NKNOTS];
static double table[NKNOTS + 1][4]; // per interval: the cubic in t - t_j

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* the spline's cubic on interval j (knots 0..j-1 below t) in powers of
 * x = t - c, c = knot[j - 1] (knot[0] for j = 0) */
static void spline_table(void)
{
    for (int k = 0; k < NKNOTS; k++)
        knot[k] = k;
    for (int j = 0; j <= NKNOTS; j++) {
        double c = knot[j > 0 ? j - 1 : 0];
        double *q = table[j];
        q[0] = 0.5 + c / 5;
        q[1] = 0.2;
        q[2] = q[3] = 0;
        for (int k = 0; k < NKNOTS; k++) {
            /* s (x + d)^3, d = c - t_k, s = +1 above t_k */
            double s = (k < j ? 1.0 : -1.0) * coef_num(k) / 7.0;
            double d = c - knot[k];
            q[0] += s * d * d * d;
            q[1] += s * 3 * d * d;
            q[2] += s * 3 * d;
            q[3] += s;
        }
    }
}

static char *spline_text(void)
{
    static char text[2048];
    int n =
        snprintf(text, sizeof text, "scheme spline10\nparam t\nS = 1/2 + t/5");
    for (int k = 0; k < NKNOTS; k++)
        n += snprintf(text + n, sizeof text - (size_t)n,
                      " + (%d)*abs(t - %d)^3/7", coef_num(k), k);
    snprintf(text + n, sizeof text - (size_t)n, "\n");
    return text;
}

/* emit-c of the scheme (path, or text) into file */
static int emit(const char *path, const char *text, const char *file)
{
    Derived *d =
        path ? derive_file(path, stderr, NULL)
             : derive_source("spline10.pcs", text, strlen(text), stderr, NULL);
    if (!d)
        return -1;
    Plan *p = lower_derived(d, stderr);
    derived_free(d);
    if (!p)
        return -1;
    FILE *f = fopen(file, "w");
    if (!f) {
        plan_free(p);
        return -1;
    }
    emit_c_ex(f, p, NULL, path ? path : "spline10.pcs", EMIT_C_BATCH);
    fclose(f);
    plan_free(p);
    return 0;
}

static void *compile_set(const char *dir, int set)
{
    char cmd[900], so[200];
    snprintf(so, sizeof so, "%s/set%d.so", dir, set);
    snprintf(cmd, sizeof cmd,
             "cc -std=c99 -Wall -Wextra %s -fPIC -shared -o %s %s/square.c "
             "%s/spline.c %s/hand.c",
             flagsets[set], so, dir, dir, dir);
    if (system(cmd) != 0)
        return NULL;
    return dlopen(so, RTLD_NOW | RTLD_LOCAL);
}

typedef struct Set {
    square_fn gsq;
    hsquare_fn hsq;
    spline_fn gsp;
    hspline_fn hsp;
} Set;

enum { PER_SET = 4, NC = FLAGSETS * PER_SET };
static const char *const names[PER_SET] = {
    "square: generated", "square: hand if/else", "spline: generated",
    "spline: hand bsearch"};

static double run(const Set *s, int k, size_t n, const double *ts,
                  const double *tp, double *out)
{
    double t0 = now();
    switch (k) {
    case 0:
        s->gsq(n, ts, O, A, B, C, 2, out);
        break;
    case 1:
        s->hsq(n, ts, O, A, B, C, out);
        break;
    case 2:
        s->gsp(n, tp, 1, out);
        break;
    default:
        s->hsp(n, tp, knot, NKNOTS, (const double(*)[4])table, out);
        break;
    }
    return now() - t0;
}

/* the two loops agree (a check of the bench, not of pointcalc) */
static int agree(const Set *s, size_t n, const double *ts, const double *tp)
{
    double *a = malloc(sizeof *a * 2 * n), *b = malloc(sizeof *b * 2 * n);
    double e1 = 0, e2 = 0;
    s->gsq(n, ts, O, A, B, C, 2, a);
    s->hsq(n, ts, O, A, B, C, b);
    for (size_t i = 0; i < 2 * n; i++)
        e1 = fmax(e1, fabs(a[i] - b[i]));
    s->gsp(n, tp, 1, a);
    s->hsp(n, tp, knot, NKNOTS, (const double(*)[4])table, b);
    for (size_t i = 0; i < n; i++)
        e2 = fmax(e2, fabs(a[i] - b[i]) / fmax(1, fabs(b[i])));
    free(a);
    free(b);
    printf("  generated vs hand: square max |diff| %.2g, spline max rel "
           "diff %.2g\n",
           e1, e2);
    return e1 <= 1e-12 && e2 <= 1e-9;
}

int main(void)
{
    int quick = getenv("PC_BENCH_QUICK") != NULL;
    size_t n = quick ? 100000 : 1000000;
    int rounds = quick ? 9 : 15;
    spline_table();
    char dir[64], path[128];
    strcpy(dir, "/tmp/pc_bench_comp_XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    snprintf(path, sizeof path, "%s/square.c", dir);
    if (emit("examples/composite_square.pcs", NULL, path) != 0)
        return 1;
    snprintf(path, sizeof path, "%s/spline.c", dir);
    if (emit(NULL, spline_text(), path) != 0)
        return 1;
    snprintf(path, sizeof path, "%s/hand.c", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return 1;
    fputs(hand_src, f);
    fclose(f);
    Set sets[FLAGSETS];
    void *so[FLAGSETS];
    for (int set = 0; set < FLAGSETS; set++) {
        so[set] = compile_set(dir, set);
        if (!so[set]) {
            fprintf(stderr, "bench_composite: cannot compile at %s\n",
                    flagsets[set]);
            return 1;
        }
        Set *s = &sets[set];
        s->gsq =
            (square_fn)(uintptr_t)dlsym(so[set], "composite_square_R_batch");
        s->hsq = (hsquare_fn)(uintptr_t)dlsym(so[set], "hand_square");
        s->gsp = (spline_fn)(uintptr_t)dlsym(so[set], "spline10_S_batch");
        s->hsp = (hspline_fn)(uintptr_t)dlsym(so[set], "hand_spline");
        if (!s->gsq || !s->hsq || !s->gsp || !s->hsp) {
            fputs("bench_composite: a function is missing\n", stderr);
            return 1;
        }
    }
    /* samples: the square's [-0.5, 4.5] and the spline's [-0.5, 9.5],
     * sorted, then the same values shuffled */
    double *ts = malloc(sizeof *ts * n), *tp = malloc(sizeof *tp * n);
    double *out = malloc(sizeof *out * 2 * n);
    memset(out, 0, sizeof *out * 2 * n);
    printf("bench_composite: one formula in |t - t_k| (emit-c) vs a branchy "
           "hand loop, %zu samples, ns/sample: median [lowest..highest "
           "round], rounds interleaved\n",
           n);
    for (int order = 0; order < 2; order++) {
        for (size_t i = 0; i < n; i++) {
            double u = (double)i / (double)(n - 1);
            ts[i] = -0.5 + 5 * u;
            tp[i] = -0.5 + 10 * u;
        }
        if (order) {
            srand(19);
            for (size_t i = n - 1; i > 0; i--) {
                size_t j = (size_t)rand() % (i + 1);
                double x = ts[i];
                ts[i] = ts[j];
                ts[j] = x;
                x = tp[i];
                tp[i] = tp[j];
                tp[j] = x;
            }
        }
        if (!agree(&sets[0], n, ts, tp)) {
            fputs("bench_composite: the loops disagree\n", stderr);
            return 1;
        }
        double tm[NC][64];
        for (int c = 0; c < NC; c++)
            run(&sets[c / PER_SET], c % PER_SET, n, ts, tp, out); // warm up
        for (int k = 0; k < rounds; k++)
            for (int j = 0; j < NC; j++) {
                int c = (j + k) % NC;
                tm[c][k] =
                    run(&sets[c / PER_SET], c % PER_SET, n, ts, tp, out) * 1e9 /
                    (double)n;
            }
        printf("\n%s samples (%d rounds)\n", order ? "shuffled" : "sorted",
               rounds);
        for (int c = 0; c < NC; c++) {
            double med, lo, hi;
            bench_stats(tm[c], rounds, &med, &lo, &hi);
            printf("  %-22s (%-17s) %8.3f [%7.3f..%7.3f]\n", names[c % PER_SET],
                   flagsets[c / PER_SET], med, lo, hi);
        }
        for (int set = 0; set < FLAGSETS; set++) {
            char what[96];
            snprintf(what, sizeof what, "square generated / hand (%s)",
                     flagsets[set]);
            bench_verdict(what, tm[set * PER_SET], tm[set * PER_SET + 1],
                          rounds, 1.2);
            snprintf(what, sizeof what, "spline generated / hand (%s)",
                     flagsets[set]);
            bench_verdict(what, tm[set * PER_SET + 2], tm[set * PER_SET + 3],
                          rounds, 1.2);
        }
        fflush(stdout);
    }
    free(out);
    free(tp);
    free(ts);
    for (int set = 0; set < FLAGSETS; set++)
        dlclose(so[set]);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "bench_composite: could not remove %s\n", dir);
    flint_cleanup_master();
    return 0;
}
