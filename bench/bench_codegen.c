/*
 * bench_codegen.c - evaluation speed of the Desargues arc M(t) in 3D, one
 * thread, ns/point, at 10^6 and 10^7 points.
 *
 * Contestants, each at both flag sets (`cc -O2` and `cc -O3
 * -march=native`: the generated code and bench/kernels.c are compiled at
 * run time into one shared object per flag set, so every comparison is
 * like for like):
 *
 *   generated      emit-c's desargues_arc_M_batch
 *   collapsed      the same with --kernel collapsed (codegen/collapse.h):
 *                  each coordinate a cubic in tau, one division
 *   hand, simple   the weights per sample, then the coordinates
 *   hand, careful  each coordinate a cubic, coefficients combined once,
 *                  Horner, one division: what an engineer writes
 *   store floor    3 doubles stored per point, nothing read
 *   stream floor   the same with non-temporal stores (SSE2)
 *   read + store   t read and stored three times (not a floor: it reads)
 *
 * and, compiled with the bench itself: runtime (plan_eval, the
 * interpreter of the same Plan) and the naive construction step by step.
 *
 * Every contestant runs once per round, the rounds interleaved with a
 * rotating order, so that a slow spell of the host spreads over all of
 * them instead of landing on one; each reports the median and the spread
 * (lowest and highest round).  A goal is judged on the ratio of two
 * contestants within each round (paired), and stated as met or not met
 * only when every round agrees; otherwise "undecided (spread)".
 *
 * Goals (issue 6): generated <= 1.0x the careful hand loop at each flag
 * set; runtime <= 4x generated; collapsed <= 1.3x the store floor at
 * each flag set (issue 6, item 3).  PC_BENCH_QUICK=1 runs 10^5 and 10^6.
 * Times are CPU time of this process (CLOCK_PROCESS_CPUTIME_ID).
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
#include "codegen/collapse.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/derive.h"
#include "runtime/eval.h"

typedef void (*batch_fn)(size_t, const double *, const double *, const double *,
                         const double *, const double *, int, double *);
typedef void (*kernel_fn)(size_t, const double *, const double *,
                          const double *, const double *, const double *,
                          double *);

static double A[3] = {0.0, 0.0, 0.0}, B[3] = {1.0, 0.2, -0.3},
              C[3] = {0.1, 1.0, 0.4}, D[3] = {-0.2, 0.3, 1.0};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the contestants ---------------------------------------------------- */

static void along(double *r, const double *p, const double *q, double s)
{
    for (int c = 0; c < 3; c++)
        r[c] = p[c] + (q[c] - p[c]) * s;
}

/* meet(line(p, q), line(r, s)) by the normal equations of
 * p + l (q - p) = r + m (s - r) */
static void meet(double *x, const double *p, const double *q, const double *r,
                 const double *s)
{
    double d1[3], d2[3], w[3];
    for (int c = 0; c < 3; c++) {
        d1[c] = q[c] - p[c];
        d2[c] = s[c] - r[c];
        w[c] = r[c] - p[c];
    }
    double a = 0, b = 0, e = 0, f = 0, g = 0;
    for (int c = 0; c < 3; c++) {
        a += d1[c] * d1[c];
        b += d1[c] * d2[c];
        e += d2[c] * d2[c];
        f += w[c] * d1[c];
        g += w[c] * d2[c];
    }
    /* [a -b; b -e] [l m]' = [f g]' */
    double det = -a * e + b * b;
    double l = (-f * e + b * g) / det;
    for (int c = 0; c < 3; c++)
        x[c] = p[c] + l * d1[c];
}

static void naive(size_t n, const double *t, double *out)
{
    for (size_t i = 0; i < n; i++) {
        double s = t[i], P[3], Q[3], K[3], N[3], J[3], T[3], S[3];
        along(P, A, C, s);
        along(Q, C, B, s);
        along(K, B, D, s);
        along(N, P, Q, s);
        along(J, Q, K, s);
        meet(T, P, Q, A, B);
        meet(S, Q, K, C, D);
        meet(out + 3 * i, S, N, T, J);
    }
}

/* ---- the contestants ---------------------------------------------------- */

enum { FLAGSETS = 2, PER_SET = 7, NC = FLAGSETS * PER_SET + 2 };
static const char *const flagsets[FLAGSETS] = {"-O2", "-O3 -march=native"};
static const char *const set_names[PER_SET] = {
    "generated",    "hand, simple", "hand, careful", "store floor",
    "stream floor", "read + store", "collapsed"};
static const char *const kernel_syms[PER_SET] = {
    NULL,          "hand_simple",  "hand_careful",
    "floor_store", "floor_stream", "floor_read_store",
    NULL};

typedef struct Contestant {
    char name[64];
    batch_fn gen;   // the generated function, or
    kernel_fn kern; // a kernel, or
    int builtin;    // 1 runtime, 2 naive
} Contestant;

typedef struct Bench {
    const Plan *plan;
    const double *t;
    double *out;
    int m; // the output M
} Bench;

static double time_one(const Bench *b, const Contestant *c, size_t n)
{
    const double *pts[4] = {A, B, C, D};
    const double *prm[1] = {b->t};
    double t0 = now();
    if (c->gen)
        c->gen(n, b->t, A, B, C, D, 3, b->out);
    else if (c->kern)
        c->kern(n, b->t, A, B, C, D, b->out);
    else if (c->builtin == 1)
        plan_eval(b->plan, b->m, n, prm, NULL, pts, 3, b->out, NULL);
    else
        naive(n, b->t, b->out);
    return now() - t0;
}

/* generated code + bench/kernels.c at one flag set, as one shared object */
static void *compile_set(const char *dir, const char *cfile, const char *cfile2,
                         int set)
{
    char cmd[700], so[200];
    snprintf(so, sizeof so, "%s/set%d.so", dir, set);
    snprintf(cmd, sizeof cmd,
             "cc -std=c99 -Wall -Wextra %s -fPIC -shared -o %s %s %s "
             "bench/kernels.c",
             flagsets[set], so, cfile, cfile2);
    if (system(cmd) != 0)
        return NULL;
    return dlopen(so, RTLD_NOW | RTLD_LOCAL);
}

static void cleanup_dir(const char *dir)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "bench_codegen: could not remove %s\n", dir);
}

/* runs bench/lambdify.py; prints its lines; returns 0 when it ran */
static void lambdify(size_t n)
{
    char cmd[200];
    const char *py = getenv("PYTHON");
    if (!py || !*py)
        py = "python3";
    snprintf(cmd, sizeof cmd, "%s bench/lambdify.py %zu 2>/dev/null", py, n);
    FILE *p = popen(cmd, "r");
    char line[256];
    int any = 0;
    if (p) {
        while (fgets(line, sizeof line, p)) {
            fputs(line, stdout);
            any = 1;
        }
        pclose(p);
    }
    if (!any)
        printf("  %-26s skipped (python3 with sympy not available)\n",
               "sympy.lambdify");
}

int main(void)
{
    int quick = getenv("PC_BENCH_QUICK") != NULL;
    size_t sizes[2] = {quick ? 100000 : 1000000, quick ? 1000000 : 10000000};
    Derived *d = derive_file("examples/desargues_arc.pcs", stderr, NULL);
    if (!d)
        return 1;
    Plan *plan = lower_derived(d, stderr);
    Collapse *col = plan ? lower_collapse(plan, d) : NULL;
    derived_free(d);
    int m = plan ? plan_find_output(plan, "M") : -1;
    if (m < 0) {
        fputs("bench_codegen: no output M\n", stderr);
        return 1;
    }
    char dir[64], cfile[128];
    strcpy(dir, "/tmp/pc_bench_XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    snprintf(cfile, sizeof cfile, "%s/arc.c", dir);
    FILE *f = fopen(cfile, "w");
    if (!f)
        return 1;
    emit_c_ex(f, plan, NULL, "examples/desargues_arc.pcs", EMIT_C_BATCH);
    fclose(f);
    char cfile2[128];
    snprintf(cfile2, sizeof cfile2, "%s/arc_collapsed.c", dir);
    f = fopen(cfile2, "w");
    if (!f)
        return 1;
    emit_c_kernel(f, plan, "arcc", "examples/desargues_arc.pcs", EMIT_C_BATCH);
    fclose(f);
    if (!col->o[m].ok) {
        fprintf(stderr, "bench_codegen: M not collapsed: %s\n", col->o[m].why);
        return 1;
    }

    Contestant cs[NC];
    void *so[FLAGSETS];
    memset(cs, 0, sizeof cs);
    for (int set = 0; set < FLAGSETS; set++) {
        so[set] = compile_set(dir, cfile, cfile2, set);
        if (!so[set]) {
            fprintf(stderr, "bench_codegen: cannot compile at %s\n",
                    flagsets[set]);
            return 1;
        }
        for (int k = 0; k < PER_SET; k++) {
            Contestant *c = &cs[set * PER_SET + k];
            snprintf(c->name, sizeof c->name, "%s (%s)", set_names[k],
                     flagsets[set]);
            if (k == 0 || k == PER_SET - 1)
                c->gen = (batch_fn)(uintptr_t)dlsym(
                    so[set], k ? "arcc_M_batch" : "desargues_arc_M_batch");
            else
                c->kern = (kernel_fn)(uintptr_t)dlsym(so[set], kernel_syms[k]);
            if (!c->gen && !c->kern) {
                fprintf(stderr, "bench_codegen: %s missing\n", c->name);
                return 1;
            }
        }
    }
    strcpy(cs[NC - 2].name, "runtime (plan_eval)");
    cs[NC - 2].builtin = 1;
    strcpy(cs[NC - 1].name, "naive construction");
    cs[NC - 1].builtin = 2;

    printf("bench_codegen: Desargues arc M(t) in 3D, single thread, ns/point: "
           "median [lowest..highest round], rounds interleaved\n");
    for (int si = 0; si < 2; si++) {
        size_t n = sizes[si];
        int rounds = n > 5000000 ? 7 : 15;
        double *t = malloc(sizeof *t * n), *out = malloc(sizeof *out * 3 * n);
        double tm[NC][64];
        for (size_t i = 0; i < n; i++)
            t[i] = (double)i / (double)(n - 1);
        memset(out, 0, sizeof *out * 3 * n); // fault the pages in
        Bench b = {plan, t, out, m};
        for (int c = 0; c < NC; c++)
            time_one(&b, &cs[c], n); // warm up
        for (int k = 0; k < rounds; k++)
            for (int j = 0; j < NC; j++) {
                int c = (j + k) % NC; // rotating order
                tm[c][k] = time_one(&b, &cs[c], n) * 1e9 / (double)n;
            }
        printf("\nn = %zu (%d rounds)\n", n, rounds);
        for (int c = 0; c < NC; c++) {
            double med, lo, hi;
            bench_stats(tm[c], rounds, &med, &lo, &hi);
            printf("  %-36s %8.3f [%7.3f..%7.3f]\n", cs[c].name, med, lo, hi);
        }
        for (int set = 0; set < FLAGSETS; set++) {
            char what[96];
            const double *g = tm[set * PER_SET];
            snprintf(what, sizeof what, "generated / hand careful (%s)",
                     flagsets[set]);
            bench_verdict(what, g, tm[set * PER_SET + 2], rounds, 1.0);
            snprintf(what, sizeof what, "generated / store floor (%s)",
                     flagsets[set]);
            bench_verdict(what, g, tm[set * PER_SET + 3], rounds, 2.0);
            const double *cl = tm[set * PER_SET + PER_SET - 1];
            snprintf(what, sizeof what, "collapsed / store floor (%s)",
                     flagsets[set]);
            bench_verdict(what, cl, tm[set * PER_SET + 3], rounds, 1.3);
            snprintf(what, sizeof what, "collapsed / hand careful (%s)",
                     flagsets[set]);
            bench_verdict(what, cl, tm[set * PER_SET + 2], rounds, 1.0);
        }
        bench_verdict("runtime / generated (-O2)", tm[NC - 2], tm[0], rounds,
                      4.0);
        fflush(stdout);
        lambdify(n);
        free(out);
        free(t);
    }
    for (int set = 0; set < FLAGSETS; set++)
        dlclose(so[set]);
    cleanup_dir(dir);
    plan_free(plan);
    flint_cleanup_master();
    return 0;
}
