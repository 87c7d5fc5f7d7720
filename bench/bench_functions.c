/*
 * bench_functions.c - evaluation of transcendental schemes (issue 8, item 3):
 * the generated batch functions of two chapter-2 ellipses against careful
 * hand-written loops that call sin and cos once each per sample
 * (bench/kernels_functions.c), compiled into one shared object with the
 * same cc at -O2 and at -O3 -march=native, and the runtime (plan_eval):
 *
 *   ellipse by central angle (2.11)   examples/ellipse_central_angle.pcs
 *   ellipse by compression (2.24)     examples/ellipse_compression.pcs
 *
 * 3D, 10^6 points, one thread, phi over [0, 2 pi].  Contestants run once per
 * round, rounds interleaved with a rotating order; a goal (generated <= 1.2x
 * the hand loop) is judged on the per-round ratios: met or not met only
 * when every round agrees, else "undecided (spread)".
 */
#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench/bench_util.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/derive.h"
#include "runtime/eval.h"

enum { NSCHEMES = 2, FLAGSETS = 2, MAXROUNDS = 31 };

static const char *const flagsets[FLAGSETS] = {"-O2", "-O3 -march=native"};

typedef void (*angle_gen)(size_t, const double *, double, double,
                          const double *, const double *, const double *, int,
                          double *);
typedef void (*angle_hand)(size_t, const double *, double, double,
                           const double *, const double *, const double *,
                           double *);
typedef void (*comp_gen)(size_t, const double *, const double *, double, double,
                         const double *, const double *, const double *, int,
                         double *);
typedef void (*comp_hand)(size_t, const double *, const double *,
                          const double *, const double *, double *);

static const double A[3] = {3.0, 0.25, -1.0}, B[3] = {0.5, 2.0, 0.75},
                    C[3] = {0.125, -0.5, 0.25};
static const double ab[2] = {3.0, 2.0};

typedef struct Contestant {
    char name[64];
    int scheme; // 0 angle, 1 compression
    int kind;   // 0 generated, 1 hand, 2 runtime
    void *fn;
} Contestant;

typedef struct Data {
    const double *phi, *zero;
    double *out;
    Plan *plan[NSCHEMES];
    int m[NSCHEMES];
} Data;

static double time_one(const Data *d, const Contestant *c, size_t n)
{
    double t0 = bench_now_ms();
    if (c->kind == 2) {
        const double *pts[3] = {A, B, C};
        const double *prm[2] = {d->phi, d->zero};
        plan_eval(d->plan[c->scheme], d->m[c->scheme], n, prm, ab, pts, 3,
                  d->out, NULL);
    } else if (c->scheme == 0 && c->kind == 0) {
        ((angle_gen)(uintptr_t)c->fn)(n, d->phi, ab[0], ab[1], A, B, C, 3,
                                      d->out);
    } else if (c->scheme == 0) {
        ((angle_hand)(uintptr_t)c->fn)(n, d->phi, ab[0], ab[1], A, B, C,
                                       d->out);
    } else if (c->kind == 0) {
        ((comp_gen)(uintptr_t)c->fn)(n, d->phi, d->zero, ab[0], ab[1], A, B, C,
                                     3, d->out);
    } else {
        ((comp_hand)(uintptr_t)c->fn)(n, d->phi, A, B, C, d->out);
    }
    return bench_now_ms() - t0;
}

static Plan *plan_of(const char *path, int *m)
{
    Derived *d = derive_file(path, stderr, NULL);
    if (!d)
        return NULL;
    Plan *p = lower_derived(d, stderr);
    derived_free(d);
    *m = p ? plan_find_output(p, "M") : -1;
    return p;
}

int main(void)
{
    static const char *const files[NSCHEMES] = {
        "examples/ellipse_central_angle.pcs",
        "examples/ellipse_compression.pcs"};
    static const char *const gen_syms[NSCHEMES] = {
        "ellipse_central_angle_M_batch", "ellipse_compression_M_batch"};
    static const char *const hand_syms[NSCHEMES] = {"hand_ellipse_angle",
                                                    "hand_ellipse_compression"};
    static const char *const labels[NSCHEMES] = {"angle (2.11)",
                                                 "compression (2.24)"};
    Data d;
    char dir[64], cfile[128], cmd[700], so[FLAGSETS][160];
    strcpy(dir, "/tmp/pc_bench_fn_XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    snprintf(cfile, sizeof cfile, "%s/gen.c", dir);
    FILE *f = fopen(cfile, "w");
    if (!f)
        return 1;
    for (int s = 0; s < NSCHEMES; s++) {
        d.plan[s] = plan_of(files[s], &d.m[s]);
        if (!d.plan[s] || d.m[s] < 0)
            return 1;
        emit_c_ex(f, d.plan[s], NULL, files[s], EMIT_C_BATCH);
    }
    fclose(f);
    Contestant cs[NSCHEMES * (2 * FLAGSETS + 1)];
    int nc = 0;
    void *h[FLAGSETS];
    for (int set = 0; set < FLAGSETS; set++) {
        snprintf(so[set], sizeof so[set], "%s/set%d.so", dir, set);
        snprintf(cmd, sizeof cmd,
                 "cc -std=c99 -Wall -Wextra %s -fPIC -shared -o %s %s "
                 "bench/kernels_functions.c -lm",
                 flagsets[set], so[set], cfile);
        if (system(cmd) != 0 ||
            !(h[set] = dlopen(so[set], RTLD_NOW | RTLD_LOCAL))) {
            fprintf(stderr, "bench_functions: cannot compile at %s\n",
                    flagsets[set]);
            return 1;
        }
    }
    for (int s = 0; s < NSCHEMES; s++) {
        for (int set = 0; set < FLAGSETS; set++)
            for (int kind = 0; kind < 2; kind++) {
                Contestant *c = &cs[nc++];
                c->scheme = s;
                c->kind = kind;
                c->fn = dlsym(h[set], kind ? hand_syms[s] : gen_syms[s]);
                snprintf(c->name, sizeof c->name, "%s, %s (%s)", labels[s],
                         kind ? "hand" : "generated", flagsets[set]);
                if (!c->fn)
                    return 1;
            }
        Contestant *c = &cs[nc++];
        c->scheme = s;
        c->kind = 2;
        c->fn = NULL;
        snprintf(c->name, sizeof c->name, "%s, runtime (plan_eval)", labels[s]);
    }
    int quick = getenv("PC_BENCH_QUICK") != NULL;
    size_t n = quick ? 100000 : 1000000;
    int rounds = quick ? 7 : 15;
    double *phi = malloc(sizeof *phi * n), *zero = calloc(n, sizeof *zero);
    double *out = malloc(sizeof *out * 3 * n);
    for (size_t i = 0; i < n; i++)
        phi[i] = 6.283185307179586 * (double)i / (double)n;
    memset(out, 0, sizeof *out * 3 * n);
    d.phi = phi;
    d.zero = zero;
    d.out = out;
    double tm[NSCHEMES * (2 * FLAGSETS + 1)][MAXROUNDS];
    for (int c = 0; c < nc; c++)
        time_one(&d, &cs[c], n); // warm up
    for (int k = 0; k < rounds; k++)
        for (int j = 0; j < nc; j++) {
            int c = (j + k) % nc;
            tm[c][k] = time_one(&d, &cs[c], n) * 1e6 / (double)n;
        }
    printf("bench_functions: ellipses of chapter 2 in 3D, n = %zu, single "
           "thread, ns/point: median [lowest..highest round], %d rounds "
           "interleaved\n",
           n, rounds);
    for (int c = 0; c < nc; c++) {
        double med, lo, hi;
        bench_stats(tm[c], rounds, &med, &lo, &hi);
        printf("  %-46s %8.3f [%7.3f..%7.3f]\n", cs[c].name, med, lo, hi);
    }
    for (int s = 0; s < NSCHEMES; s++)
        for (int set = 0; set < FLAGSETS; set++) {
            int base = s * (2 * FLAGSETS + 1) + 2 * set;
            char what[96];
            snprintf(what, sizeof what, "%s generated / hand (%s)", labels[s],
                     flagsets[set]);
            bench_verdict(what, tm[base], tm[base + 1], rounds, 1.2);
        }
    free(out);
    free(zero);
    free(phi);
    for (int set = 0; set < FLAGSETS; set++)
        dlclose(h[set]);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "bench_functions: could not remove %s\n", dir);
    for (int s = 0; s < NSCHEMES; s++)
        plan_free(d.plan[s]);
    flint_cleanup_master();
    return 0;
}
