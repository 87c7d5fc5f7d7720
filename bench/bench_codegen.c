/*
 * bench_codegen.c - the Desargues arc in 3D over 10^6 and 10^7 parameter
 * values, single thread, ns/point (median of several runs):
 *
 *   generated   emit-c's desargues_arc_M_batch, compiled at run time with
 *               `cc -std=c99 -O2 -shared -fPIC` and dlopen'ed
 *   runtime     plan_eval, the interpreter of the same Plan
 *   naive       the construction step by step in floating point: along x 5,
 *               meet x 3 (each a 2x2 solve of the normal equations)
 *   hand        hand-written loops of the closed formula: `simple` (the
 *               weights per sample, then the coordinates) and `careful`
 *               (each coordinate a cubic in t with coefficients combined
 *               from the points once, Horner, one division per sample:
 *               what an engineer writes for this one curve); the goals are
 *               measured against the faster of the two
 *   floor       writing the same output (3 doubles per point from t[i])
 *   lambdify    sympy.lambdify with and without cse (bench/lambdify.py,
 *               run with $PYTHON, default python3; skipped when it lacks
 *               sympy)
 *
 * Times are CPU time of this process (CLOCK_PROCESS_CPUTIME_ID, the bench
 * is single-threaded), less disturbed by other load than wall time.
 *
 * Goals (docs/codegen.md): generated <= 1.2x hand, <= 2x floor; runtime
 * <= 4x generated.  PC_BENCH_QUICK=1 runs 10^5 and 10^6 only.
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

#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/derive.h"
#include "runtime/eval.h"

typedef void (*batch_fn)(size_t, const double *, const double *, const double *,
                         const double *, const double *, int, double *);

static double A[3] = {0.0, 0.0, 0.0}, B[3] = {1.0, 0.2, -0.3},
              C[3] = {0.1, 1.0, 0.4}, D[3] = {-0.2, 0.3, 1.0};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---- the contestants ---------------------------------------------------- */

static void hand(size_t n, const double *t, double *out)
{
    for (size_t i = 0; i < n; i++) {
        double s = t[i], u = 1.0 - s;
        double inv = 1.0 / ((2.0 * s - 2.0) * s + 1.0);
        double s2 = s * s, u2 = u * u;
        double wa = u2 * u * inv, wb = s2 * u * inv, wc = s * u2 * inv,
               wd = s2 * s * inv;
        double *o = out + 3 * i;
        o[0] = wa * A[0] + wb * B[0] + wc * C[0] + wd * D[0];
        o[1] = wa * A[1] + wb * B[1] + wc * C[1] + wd * D[1];
        o[2] = wa * A[2] + wb * B[2] + wc * C[2] + wd * D[2];
    }
}

/* the careful hand-written loop: M_c(t) = (k3 t^3 + k2 t^2 + k1 t + k0) /
 * (2t^2 - 2t + 1) per coordinate c, with (1-t)^3 = 1 - 3t + 3t^2 - t^3,
 * t^2(1-t) = t^2 - t^3, t(1-t)^2 = t - 2t^2 + t^3 combined once */
static void hand_careful(size_t n, const double *restrict t,
                         double *restrict out)
{
    double k[3][4];
    for (int c = 0; c < 3; c++) {
        k[c][0] = A[c];
        k[c][1] = -3.0 * A[c] + C[c];
        k[c][2] = 3.0 * A[c] + B[c] - 2.0 * C[c];
        k[c][3] = -A[c] - B[c] + C[c] + D[c];
    }
    for (size_t i = 0; i < n; i++) {
        double s = t[i];
        double inv = 1.0 / ((2.0 * s - 2.0) * s + 1.0);
        double *o = out + 3 * i;
        o[0] = (((k[0][3] * s + k[0][2]) * s + k[0][1]) * s + k[0][0]) * inv;
        o[1] = (((k[1][3] * s + k[1][2]) * s + k[1][1]) * s + k[1][0]) * inv;
        o[2] = (((k[2][3] * s + k[2][2]) * s + k[2][1]) * s + k[2][0]) * inv;
    }
}

static void floor_loop(size_t n, const double *t, double *out)
{
    for (size_t i = 0; i < n; i++) {
        double *o = out + 3 * i;
        o[0] = t[i];
        o[1] = t[i];
        o[2] = t[i];
    }
}

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

/* ---- setup -------------------------------------------------------------- */

typedef struct Bench {
    const Plan *plan;
    batch_fn gen;
    const double *t;
    double *out;
    int m; // the output M
} Bench;

static double time_one(const Bench *b, int which, size_t n)
{
    const double *pts[4] = {A, B, C, D};
    const double *prm[1] = {b->t};
    double t0 = now();
    switch (which) {
    case 0:
        b->gen(n, b->t, A, B, C, D, 3, b->out);
        break;
    case 1:
        plan_eval(b->plan, b->m, n, prm, NULL, pts, 3, b->out, NULL);
        break;
    case 2:
        naive(n, b->t, b->out);
        break;
    case 3:
        hand(n, b->t, b->out);
        break;
    case 4:
        hand_careful(n, b->t, b->out);
        break;
    default:
        floor_loop(n, b->t, b->out);
    }
    return now() - t0;
}

static void *compile_generated(const Plan *p, char *dir, batch_fn *fn)
{
    char path[160], cmd[400];
    strcpy(dir, "/tmp/pc_bench_XXXXXX");
    if (!mkdtemp(dir))
        return NULL;
    snprintf(path, sizeof path, "%s/arc.c", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return NULL;
    emit_c(f, p, NULL, "examples/desargues_arc.pcs");
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "cc -std=c99 -Wall -Wextra -O2 -fPIC -shared -o %s/arc.so %s", dir,
             path);
    if (system(cmd) != 0)
        return NULL;
    snprintf(path, sizeof path, "%s/arc.so", dir);
    void *so = dlopen(path, RTLD_NOW);
    if (so)
        *fn = (batch_fn)(uintptr_t)dlsym(so, "desargues_arc_M_batch");
    return so;
}

static void cleanup_dir(const char *dir)
{
    char path[160];
    snprintf(path, sizeof path, "%s/arc.c", dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/arc.so", dir);
    unlink(path);
    rmdir(dir);
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
    static const char *const names[] = {
        "generated (emit-c batch)", "runtime (plan_eval)", "naive construction",
        "hand-written, simple", "hand-written, careful", "memory-write floor"};
    enum { NW = 6 };
    int quick = getenv("PC_BENCH_QUICK") != NULL;
    size_t sizes[2] = {quick ? 100000 : 1000000, quick ? 1000000 : 10000000};
    Derived *d = derive_file("examples/desargues_arc.pcs", stderr, NULL);
    if (!d)
        return 1;
    Plan *plan = lower_derived(d, stderr);
    derived_free(d);
    int m = plan ? plan_find_output(plan, "M") : -1;
    if (m < 0) {
        fputs("bench_codegen: no output M\n", stderr);
        return 1;
    }
    char dir[64];
    batch_fn gen = NULL;
    void *so = compile_generated(plan, dir, &gen);
    if (!so || !gen) {
        fputs("bench_codegen: cannot compile the generated code\n", stderr);
        return 1;
    }
    printf("bench_codegen: Desargues arc M(t) in 3D, single thread, "
           "ns/point (median)\n");
    for (int si = 0; si < 2; si++) {
        size_t n = sizes[si];
        int runs = n > 5000000 ? 5 : 9;
        double *t = malloc(sizeof *t * n), *out = malloc(sizeof *out * 3 * n);
        for (size_t i = 0; i < n; i++)
            t[i] = (double)i / (double)(n - 1);
        memset(out, 0, sizeof *out * 3 * n); // fault the pages in
        Bench b = {plan, gen, t, out, m};
        double med[NW];
        for (int w = 0; w < NW; w++) {
            double tm[9];
            time_one(&b, w, n); // warm up
            for (int r = 0; r < runs; r++)
                tm[r] = time_one(&b, w, n);
            qsort(tm, (size_t)runs, sizeof *tm, cmp_double);
            med[w] = tm[runs / 2] * 1e9 / (double)n;
        }
        printf("\nn = %zu\n", n);
        for (int w = 0; w < NW; w++)
            printf("  %-26s %8.3f ns/point  %6.2fx generated\n", names[w],
                   med[w], med[w] / med[0]);
        double hand_best = med[3] < med[4] ? med[3] : med[4];
        printf("  goals: generated/hand %.2f (<= 1.2), generated/floor %.2f "
               "(<= 2), runtime/generated %.2f (<= 4)\n",
               med[0] / hand_best, med[0] / med[5], med[1] / med[0]);
        fflush(stdout);
        lambdify(n);
        free(out);
        free(t);
    }
    dlclose(so);
    cleanup_dir(dir);
    plan_free(plan);
    flint_cleanup_master();
    return 0;
}
