/*
 * emit_harness.h - what the tests of generated C share (test_emit_c.c,
 * test_collapse.c): writing the generated file, its header and a wrapper
 * into a temporary directory, compiling them with the contract's flags
 * (warnings are errors) into a shared object, loading it, and removing it
 * all again; the fixed-arity wrappers wb_O of the batch functions; the
 * exact value of a double; the generated text itself (harness_emit).
 * Include after <cmocka.h>, <flint/fmpq.h>, runtime/plan.h and
 * codegen/emit_c.h.
 */
#ifndef PC_TEST_EMIT_HARNESS_H
#define PC_TEST_EMIT_HARNESS_H

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct Compiled {
    char dir[64];
    void *so;
} Compiled;

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* the generated C of p (header: its header) for scheme file name file,
 * as emit-c writes it with --prefix pcx; the caller frees it */
static inline char *harness_emit(const Plan *p, int header, const char *file)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (header)
        emit_c_header(m, p, "pcx", file);
    else
        emit_c(m, p, "pcx", file);
    fclose(m);
    return text;
}

/* gen.c, gen.h and wrap.c in a new /tmp/pc_TAG_XXXXXX, compiled and
 * loaded into c; the wrapper includes the header, so prototypes and
 * definitions must agree */
static void harness_compile(Compiled *c, const char *tag, const char *src,
                            const char *hdr, const char *wrap)
{
    char path[128], cmd[512];
    snprintf(c->dir, sizeof c->dir, "/tmp/pc_%s_XXXXXX", tag);
    assert_non_null(mkdtemp(c->dir));
    snprintf(path, sizeof path, "%s/gen.c", c->dir);
    write_file(path, src);
    snprintf(path, sizeof path, "%s/gen.h", c->dir);
    write_file(path, hdr);
    snprintf(path, sizeof path, "%s/wrap.c", c->dir);
    write_file(path, wrap);
    snprintf(cmd, sizeof cmd,
             "cd %s && cc -std=c99 -Wall -Wextra -Werror -pedantic -O2 "
             "-fPIC -shared -o gen.so gen.c wrap.c -lm",
             c->dir);
    int rc = system(cmd);
    if (rc != 0)
        fprintf(stderr, "compile failed, sources kept in %s\n", c->dir);
    assert_int_equal(rc, 0);
    snprintf(path, sizeof path, "%s/gen.so", c->dir);
    c->so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    assert_non_null(c->so);
}

static void compiled_clear(Compiled *c)
{
    static const char *const files[] = {"gen.c", "gen.h", "wrap.c", "gen.so"};
    char path[128];
    dlclose(c->so);
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, "%s/%s", c->dir, files[i]);
        unlink(path);
    }
    rmdir(c->dir);
}

/* size_t wb_O(n, prm, cst, pts, dim, out, status, checked): output O's
 * pcx_NAME_batch (checked 0, returns (size_t)-1) or
 * pcx_NAME_batch_checked, with the params, consts and points as arrays */
static void harness_batch_wrapper(FILE *m, const Plan *p, int o)
{
    const char *nm = p->outputs[o].name;
    fprintf(m,
            "size_t wb_%d(size_t n, const double *const *prm, "
            "const double *cst, const double *const *pts, int dim, "
            "double *out, unsigned char *status, int checked);\n"
            "size_t wb_%d(size_t n, const double *const *prm, "
            "const double *cst, const double *const *pts, int dim, "
            "double *out, unsigned char *status, int checked)\n"
            "{\n    (void)prm; (void)cst; (void)pts;\n"
            "    if (!checked) {\n        pcx_%s_batch(n, ",
            o, o, nm);
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < p->nparams; i++)
            fprintf(m, "prm[%d], ", i);
        for (int i = 0; i < p->nconsts; i++)
            fprintf(m, "cst[%d], ", i);
        for (int i = 0; i < p->npoints; i++)
            fprintf(m, "pts[%d], ", i);
        fputs(pass == 0 ? "dim, out);\n" : "dim, out, status);\n", m);
        if (pass == 0)
            fprintf(m,
                    "        return (size_t)-1;\n    }\n"
                    "    return pcx_%s_batch_checked(n, ",
                    nm);
    }
    fputs("}\n", m);
}

/* exact value of a double as a rational (written here, independently of
 * the library's conversions that the tests check) */
static void fmpq_set_double(fmpq_t r, double v)
{
    int e;
    double m = frexp(v, &e); // v = m 2^e, m in [0.5, 1)
    fmpz_t num;
    fmpz_init(num);
    fmpz_set_d(num, ldexp(m, 53)); // exact: an integer below 2^53
    fmpq_set_fmpz_frac(r, num, (fmpz[]){1});
    if (e - 53 >= 0)
        fmpq_mul_2exp(r, r, (ulong)(e - 53));
    else
        fmpq_div_2exp(r, r, (ulong)(53 - e));
    fmpz_clear(num);
}

#ifdef PC_DERIVE_H
#include "compiler/algebra/kernel.h"

/* 4 when a param or const in vals lies outside a declared bound that
 * output o rests on (DerivedOutput.assumed: docs/language.md, "Declared
 * ranges"), compared exactly (a bound like 2*pi by its enclosure) */
static int outside_assumed(const Derived *d, const DerivedOutput *out,
                           const fmpq *vals)
{
    int st = 0;
    fmpq_t b, lo, hi;
    fmpq_init(b);
    fmpq_init(lo);
    fmpq_init(hi);
    for (slong v = 0; out->assumed && v < d->nparams + d->nconsts; v++)
        for (int upper = 0; upper < 2; upper++) {
            if (!(out->assumed[v] & (upper ? 2 : 1)))
                continue;
            int lo_open, hi_open;
            const RatFunStruct *e = d->bound + 2 * v + upper;
            if (ratfun_get_fmpq(b, e, &d->ring)) {
            } else if (kernel_bounds(d->kernels, e, lo, &lo_open, hi,
                                     &hi_open) == 3) { /* 2*pi */
                fmpq_add(b, lo, hi);
                fmpq_div_2exp(b, b, 1);
            } else { /* in terms of the consts: [b, a] */
                assert_int_equal(ratfun_evaluate_fmpq(b, e, vals, &d->ring), 0);
            }
            int c = fmpq_cmp(vals + v, b), f = d->bound_flags[v];
            int open =
                f & (upper ? DERIVED_BOUND_HI_OPEN : DERIVED_BOUND_LO_OPEN);
            if (upper ? (c > 0 || (open && c == 0))
                      : (c < 0 || (open && c == 0)))
                st = 4;
        }
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(b);
    return st;
}

#endif

#endif
