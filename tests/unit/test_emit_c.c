/*
 * test_emit_c.c - differential tests of the two back ends (house style 26c).
 *
 * For every scheme in examples/ (and a few inline edge cases) the
 * reduced equations are lowered to a Plan, printed as C with a header, and
 * compiled with `cc -std=c99 -Wall -Wextra -Werror -O2` into a shared
 * object together with a small wrapper that calls the generated functions
 * with fixed-arity arguments.  At sample parameter values (dyadic, so exact
 * in binary) every output is then computed four ways and compared:
 *
 *   exact      ratfun_evaluate_fmpq of every weight, coordinates in Q
 *   NAME_M / NAME_M_checked            (generated, one sample)
 *   NAME_M_batch / NAME_M_batch_checked (generated, n samples, > 1 block)
 *   plan_eval                           (the runtime interpreter)
 *
 * in dimensions 1, 2, 3, 7 and npoints (with the unit points e_k, whose
 * coordinates are the weights themselves): |got - exact| <= 1e-12 times
 * max(|exact|, sum |w_i P_i|).  A sample where an exact weight has a pole
 * must come out NaN with status 1 everywhere.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <dirent.h>
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <flint/flint.h>
#include <flint/fmpq.h>

#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "codegen/numsolve.h"
#include "compiler/algebra/kernel.h"
#include "compiler/derive.h"
#include "runtime/eval.h"
#include "tests/unit/emit_harness.h"

#define REL_TOL 1e-12
#define NBATCH 300 // > 2 blocks of the generated code (64) and runtime (128)

typedef int (*one_fn)(const double *prm, const double *cst,
                      const double *const *pts, int dim, double *out,
                      int checked);
typedef size_t (*batch_fn)(size_t n, const double *const *prm,
                           const double *cst, const double *const *pts, int dim,
                           double *out, unsigned char *status, int checked);

/* dyadic sample values: exact as doubles */
static const double param_vals[] = {-0.75, 0.0, 0.25, 0.5, 0.8125, 1.0, 1.5};
static const double const_vals[] = {0.75, 0.625, 1.25, -0.5, 2.0, 0.375};
#define NPV (int)(sizeof param_vals / sizeof *param_vals)
#define NCV (int)(sizeof const_vals / sizeof *const_vals)

static int total_checks;

/* ---- compiling generated code ------------------------------------------ */

/* wrapper: w1_O and wb_O with fixed arity call the generated pcx_NAME_* */
static char *wrapper(const Plan *p)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    fputs("#include <stddef.h>\n#include \"gen.h\"\n", m);
    for (int o = 0; o < p->noutputs; o++) {
        const char *nm = p->outputs[o].name;
        fprintf(
            m,
            "int w1_%d(const double *prm, const double *cst, "
            "const double *const *pts, int dim, double *out, int checked);\n"
            "int w1_%d(const double *prm, const double *cst, "
            "const double *const *pts, int dim, double *out, int checked)\n"
            "{\n    (void)prm; (void)cst; (void)pts;\n"
            "    if (!checked) {\n        pcx_%s(",
            o, o, nm);
        for (int pass = 0; pass < 2; pass++) {
            for (int i = 0; i < p->nparams; i++)
                fprintf(m, "prm[%d], ", i);
            for (int i = 0; i < p->nconsts; i++)
                fprintf(m, "cst[%d], ", i);
            for (int i = 0; i < p->npoints; i++)
                fprintf(m, "pts[%d], ", i);
            fputs("dim, out);\n", m);
            if (pass == 0)
                fprintf(m,
                        "        return -1;\n    }\n    return pcx_%s_checked(",
                        nm);
        }
        fputs("}\n", m);
        harness_batch_wrapper(m, p, o);
    }
    fclose(m);
    return text;
}

static void compile_plan(Compiled *c, const Plan *p)
{
    char *src = harness_emit(p, 0, "test.pcs"),
         *hdr = harness_emit(p, 1, "test.pcs");
    char *wrap = wrapper(p);
    harness_compile(c, "emit", src, hdr, wrap);
    free(src);
    free(hdr);
    free(wrap);
}

/* ---- exact values ------------------------------------------------------- */

/* The values of the functions (kernels) at vals (the params and consts
 * set): each kernel's argument evaluated exactly, the function applied in
 * double (<math.h>, independent of the Plan), its value stored exactly in
 * vals.  Returns 4 when an argument is outside its function's domain, 1 at
 * a pole of an argument, else 0. */
static int rf_uses(const RatFunStruct *x, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(x->num, var, r->ctx) > 0 ||
           fmpz_mpoly_degree_si(x->den, var, r->ctx) > 0;
}

/* natx (y = 0) or naty of law k at u, independently of the runtime's
 * Gauss-Legendre panels: composite Simpson on 2^11 and 2^12 intervals,
 * extrapolated (Richardson: error O(h^6), below 1e-13 for the examples'
 * laws and ranges).  In double: long double's sinl, cosl made this test
 * ten times slower under valgrind, which emulates them. */
static double ref_natural(const fmpq *k, double u, int y)
{
    double c[4], res[2];
    for (int j = 0; j < 4; j++)
        c[j] = fmpq_get_d(k + j) / (j + 1);
    for (int pass = 0; pass < 2; pass++) {
        long n = 2048L << pass;
        double h = u / n, sum = 0;
        for (long i = 0; i <= n; i++) {
            double s = h * i;
            double ph = (((c[3] * s + c[2]) * s + c[1]) * s + c[0]) * s;
            double f = y ? sin(ph) : cos(ph);
            sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
        }
        res[pass] = sum * h / 3;
    }
    return res[1] + (res[1] - res[0]) / 15;
}

/* used[i]: output o uses kernel i (directly or inside another's argument) */
static void kernels_used(const Derived *d, int o, unsigned char *used)
{
    const Kernels *K = d->kernels;
    const DerivedOutput *out = &d->outputs[o];
    for (slong i = K->n - 1; i >= 0; i--) {
        slong v = K->k[i].var;
        used[i] = 0;
        if (out->kind == KIND_SCALAR)
            used[i] = rf_uses(out->scalar, v, &d->ring);
        for (slong j = 0; out->kind != KIND_SCALAR && j < out->eq->len; j++)
            used[i] |= rf_uses(&out->w[j], v, &d->ring);
        for (slong j = i + 1; j < K->n && !used[i]; j++)
            used[i] = used[j] && (rf_uses(K->k[j].arg, v, &d->ring) ||
                                  rf_uses(K->k[j].arg2, v, &d->ring));
    }
}

static int kernel_values(const Derived *d, int o, fmpq *vals,
                         double *const *pts, int dim)
{
    const Kernels *K = d->kernels;
    int st = 0;
    if (!K)
        return 0;
    unsigned char *used = calloc((size_t)K->n + 1, 1);
    kernels_used(d, o, used);
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if (!used[i])
            continue;
        fmpq_t a, b;
        fmpq_init(a);
        fmpq_init(b);
        double v = 0, x = 0, y = 0;
        if (k->fn != KF_PI) {
            if (ratfun_evaluate_fmpq(a, k->arg, vals, &d->ring) ==
                    RATFUN_EPOLE ||
                (k->fn == KF_ATAN2 &&
                 ratfun_evaluate_fmpq(b, k->arg2, vals, &d->ring) ==
                     RATFUN_EPOLE))
                st = st ? st : 1;
            x = fmpq_get_d(a);
            y = fmpq_get_d(b);
        }
        switch (k->fn) {
        case KF_PI:
            v = 3.14159265358979323846;
            break;
        case KF_COORD:
            v = k->pb <= dim ? pts[k->pa][k->pb - 1] : NAN;
            break;
        case KF_DIST: {
            double s2 = 0;
            for (int c = 0; c < dim; c++)
                s2 += (pts[k->pa][c] - pts[k->pb][c]) *
                      (pts[k->pa][c] - pts[k->pb][c]);
            v = sqrt(s2);
            break;
        }
        case KF_SQRT:
            if (fmpq_sgn(a) < 0)
                st = 4;
            v = sqrt(fabs(x));
            break;
        case KF_ROOT: {
            slong vv;
            const Kernel *e = NULL;
            if (fmpz_mpoly_is_one(k->arg->den, d->ring.ctx) &&
                k->arg->num->length == 1)
                for (vv = 0; vv < K->n; vv++)
                    if (K->k[vv].fn == KF_EXP &&
                        fmpz_mpoly_degree_si(k->arg->num, K->k[vv].var,
                                             d->ring.ctx) == 1)
                        e = &K->k[vv];
            if (e) { /* exp(m)^(1/q) */
                fmpq_t m;
                fmpq_init(m);
                ratfun_evaluate_fmpq(m, e->arg, vals, &d->ring);
                v = exp(fmpq_get_d(m) / (double)k->q);
                fmpq_clear(m);
            } else {
                if (fmpq_sgn(a) < 0 && k->q % 2 == 0)
                    st = 4;
                v = (x < 0 ? -1 : 1) * pow(fabs(x), 1.0 / (double)k->q);
            }
            break;
        }
        case KF_SIN:
            v = sin(x);
            break;
        case KF_COS:
            v = cos(x);
            break;
        case KF_SINH:
            v = sinh(x);
            break;
        case KF_COSH:
            v = cosh(x);
            break;
        case KF_EXP:
            v = exp(x);
            break;
        case KF_LN:
            if (fmpq_sgn(a) <= 0)
                st = 4;
            v = fmpq_sgn(a) > 0 ? log(x) : 0;
            break;
        case KF_ASIN:
        case KF_ACOS:
            if (fabs(x) > 1)
                st = 4;
            v = fabs(x) > 1 ? 0 : k->fn == KF_ASIN ? asin(x) : acos(x);
            break;
        case KF_ATAN:
            v = atan(x);
            break;
        case KF_ATAN2:
            v = atan2(x, y);
            break;
        case KF_SIGN:
            v = (double)fmpq_sgn(a);
            break;
        case KF_NATX:
        case KF_NATY:
            v = ref_natural(kernels_law(K, k->q), x, k->fn == KF_NATY);
            break;
        default:
            break;
        }
        fmpq_set_double(vals + k->var, v);
        fmpq_clear(b);
        fmpq_clear(a);
    }
    free(used);
    return st;
}

/* exact weights of output o at vals (the kernels' values set in vals):
 * w[k] per plan slot k; returns 1 when some weight has a pole there */
static int exact_weights(const Derived *d, int o, const fmpq *vals, fmpq *w,
                         int nterms)
{
    const DerivedOutput *out = &d->outputs[o];
    int pole = 0;
    for (int k = 0; k < nterms; k++) {
        const RatFunStruct *x =
            out->kind == KIND_SCALAR ? out->scalar : &out->w[k];
        if (ratfun_evaluate_fmpq(w + k, x, vals, &d->ring) == RATFUN_EPOLE)
            pole = 1;
    }
    return pole;
}

/* the size of the terms of weight x at vals, |num|(|vals|)/|den(vals)|:
 * where the terms of a weight cancel (1 + cos(pi*u) at u = 1), double
 * evaluation is exact only to this scale, not to the tiny value itself */
static double term_scale(const RatFunStruct *x, const fmpq *vals, int nv,
                         const Ring *r)
{
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    fmpz_mpoly_set(a->num, x->num, r->ctx);
    for (slong i = 0; i < a->num->length; i++)
        fmpz_abs(a->num->coeffs + i, a->num->coeffs + i);
    fmpz_mpoly_set(b->num, x->den, r->ctx);
    fmpq *av = _fmpq_vec_init(nv);
    for (int i = 0; i < nv; i++)
        fmpq_abs(av + i, vals + i);
    fmpq_t n, d;
    fmpq_init(n);
    fmpq_init(d);
    double sc = 0;
    if (ratfun_evaluate_fmpq(n, a, av, r) == RATFUN_OK &&
        ratfun_evaluate_fmpq(d, b, vals, r) == RATFUN_OK && !fmpq_is_zero(d))
        sc = fabs(fmpq_get_d(n) / fmpq_get_d(d));
    fmpq_clear(n);
    fmpq_clear(d);
    _fmpq_vec_clear(av, nv);
    ratfun_clear(a, r);
    ratfun_clear(b, r);
    return sc;
}

/* r = x exactly, for x a multiple of 2^-10 */
static void dyadic(fmpq_t r, double x)
{
    assert_true(x * 1024 == (double)(slong)(x * 1024));
    fmpq_set_si(r, (slong)(x * 1024), 1024);
}

static void check_close(double got, double exact, double scale,
                        const char *what, const char *scheme,
                        const char *output, int sample, int coord)
{
    double tol = REL_TOL * fmax(fabs(exact), scale);
    total_checks++;
    if (!(fabs(got - exact) <= tol)) {
        fprintf(stderr,
                "%s: %s output %s sample %d coord %d: got %.17g, exact "
                "%.17g (tol %g)\n",
                scheme, what, output, sample, coord, got, exact, tol);
        fail();
    }
}

/* Checks every output of d/p at the samples in every dimension. */
static void check_derived(const Derived *d, const Plan *p, const Compiled *c)
{
    int nv = d->ring.nvars > 0 ? (int)d->ring.nvars : 1;
    int np = p->nparams, nc = p->nconsts, npt = p->npoints;
    flint_rand_t rs;
    flint_randinit(rs);
    fmpq *vals = _fmpq_vec_init(nv);
    double *cst = calloc((size_t)nc + 1, sizeof *cst);
    for (int i = 0; i < nc; i++) {
        cst[i] = const_vals[i % NCV];
        dyadic(vals + np + i, cst[i]);
    }
    /* samples: param i of sample s is param_vals[(s + 2i) % NPV] */
    int nsamples = NPV;
    for (int o = 0; o < p->noutputs; o++) {
        const PlanOutput *po = &p->outputs[o];
        int scalar = po->kind == KIND_SCALAR;
        int nterms = po->nterms;
        char name[64];
        snprintf(name, sizeof name, "w1_%d", o);
        one_fn one = (one_fn)(uintptr_t)dlsym(c->so, name);
        snprintf(name, sizeof name, "wb_%d", o);
        batch_fn batch = (batch_fn)(uintptr_t)dlsym(c->so, name);
        assert_non_null(one);
        assert_non_null(batch);
        fmpq *w = _fmpq_vec_init(nterms ? nterms : 1);
        static const int dims_fixed[] = {1, 2, 3, 7};
        for (int di = 0; di < 5; di++) {
            int dim = di < 4 ? dims_fixed[di] : npt; // last: unit points
            /* coord(P, k): the dims with k coordinates, for scalars too
             * (dim < k: test_emit_c_coord_dim_too_small) */
            int need = plan_output_min_dim(p, o, NULL);
            if (dim < 1 || dim < need)
                continue;
            if (scalar && di > 0 && !need)
                break;
            /* points: dyadic coordinates in [-8, 8], or e_k */
            double **pts = calloc((size_t)npt + 1, sizeof *pts);
            for (int k = 0; k < npt; k++) {
                pts[k] = malloc(sizeof **pts * (size_t)dim);
                for (int cc = 0; cc < dim; cc++)
                    pts[k][cc] =
                        di < 4 ? (double)((slong)n_randint(rs, 257) - 128) / 16
                               : (double)(k == cc);
            }
            int ncol = scalar ? 1 : dim;
            double *exact = malloc(sizeof *exact * (size_t)(NBATCH * ncol));
            double *scale = malloc(sizeof *scale * (size_t)(NBATCH * ncol));
            int *pole = malloc(sizeof *pole * NBATCH);
            double **prm = calloc((size_t)np + 1, sizeof *prm);
            for (int i = 0; i < np; i++)
                prm[i] = malloc(sizeof **prm * NBATCH);
            /* the batch repeats the samples; exact values per sample */
            for (int s = 0; s < NBATCH; s++) {
                int s0 = s % nsamples;
                for (int i = 0; i < np; i++) {
                    prm[i][s] = param_vals[(s0 + 2 * i) % NPV];
                    dyadic(vals + i, prm[i][s]);
                }
                /* the expected status: 4 outside a domain, 1 a pole */
                int kst = kernel_values(d, o, vals, pts, dim);
                if (!kst)
                    kst = outside_assumed(d, &d->outputs[o], vals);
                pole[s] = exact_weights(d, o, vals, w, nterms);
                if (kst)
                    pole[s] = kst;
                for (int cc = 0; cc < ncol; cc++) {
                    fmpq_t sum, t;
                    fmpq_init(sum);
                    fmpq_init(t);
                    double sc = 0;
                    for (int k = 0; k < nterms && !pole[s]; k++) {
                        double coord = scalar ? 1.0 : pts[po->point[k]][cc];
                        dyadic(t, coord);
                        fmpq_mul(t, t, w + k);
                        fmpq_add(sum, sum, t);
                        const RatFunStruct *x = po->kind == KIND_SCALAR
                                                    ? d->outputs[o].scalar
                                                    : &d->outputs[o].w[k];
                        sc += term_scale(x, vals, nv, &d->ring) * fabs(coord);
                    }
                    exact[s * ncol + cc] = fmpq_get_d(sum);
                    scale[s * ncol + cc] = sc;
                    fmpq_clear(t);
                    fmpq_clear(sum);
                }
            }
            /* one sample at a time, both entry points */
            double *got = malloc(sizeof *got * (size_t)(NBATCH * ncol));
            unsigned char *st = malloc(NBATCH);
            for (int s = 0; s < nsamples; s++) {
                double row[16];
                double prow[8];
                for (int i = 0; i < np; i++)
                    prow[i] = prm[i][s];
                for (int checked = 0; checked < 2; checked++) {
                    int rc = one(prow, cst, (const double *const *)pts, dim,
                                 row, checked);
                    if (checked)
                        assert_int_equal(rc, pole[s]);
                    for (int cc = 0; cc < ncol; cc++) {
                        if (pole[s])
                            assert_true(isnan(row[cc]));
                        else
                            check_close(row[cc], exact[s * ncol + cc],
                                        scale[s * ncol + cc], "generated",
                                        p->name, po->name, s, cc);
                    }
                }
            }
            /* batches, generated and interpreted */
            for (int way = 0; way < 3; way++) {
                size_t nb;
                memset(st, 7, NBATCH);
                if (way < 2)
                    nb = batch(NBATCH, (const double *const *)prm, cst,
                               (const double *const *)pts, dim, got,
                               way ? st : NULL, way);
                else
                    nb =
                        plan_eval(p, o, NBATCH, (const double *const *)prm, cst,
                                  (const double *const *)pts, dim, got, st);
                size_t expect_nb = 0;
                for (int s = 0; s < NBATCH; s++)
                    expect_nb += pole[s] != 0;
                if (way > 0)
                    assert_int_equal(nb, expect_nb);
                for (int s = 0; s < NBATCH; s++) {
                    if (way > 0)
                        assert_int_equal(st[s], pole[s]);
                    for (int cc = 0; cc < ncol; cc++) {
                        double g = got[s * ncol + cc];
                        if (pole[s])
                            assert_true(isnan(g));
                        else
                            check_close(g, exact[s * ncol + cc],
                                        scale[s * ncol + cc],
                                        way < 2 ? "generated batch" : "runtime",
                                        p->name, po->name, s, cc);
                    }
                }
            }
            free(st);
            free(got);
            for (int i = 0; i < np; i++)
                free(prm[i]);
            free(prm);
            free(pole);
            free(scale);
            free(exact);
            for (int k = 0; k < npt; k++)
                free(pts[k]);
            free(pts);
        }
        _fmpq_vec_clear(w, nterms ? nterms : 1);
    }
    free(cst);
    _fmpq_vec_clear(vals, nv);
    flint_randclear(rs);
}

static void check_scheme_text(const char *name, const char *text)
{
    int nerr = 0;
    DeriveOptions opt = {.max_seconds = 60, .numeric = numsolve_run};
    Derived *d =
        text ? derive_source_ex(name, text, strlen(text), stderr, &nerr, &opt)
             : derive_file_ex(name, stderr, &nerr, &opt);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    Compiled c;
    compile_plan(&c, p);
    check_derived(d, p, &c);
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

/* ---- tests --------------------------------------------------------------- */

static void test_emit_c_examples_match_exact_and_runtime(void **state)
{
    (void)state;
    DIR *dir = opendir("examples");
    assert_non_null(dir);
    struct dirent *e;
    char *names[256];
    int n = 0;
    while ((e = readdir(dir)) && n < 256) {
        size_t len = strlen(e->d_name);
        if (len > 4 && strcmp(e->d_name + len - 4, ".pcs") == 0) {
            names[n] = malloc(len + 10);
            snprintf(names[n], len + 10, "examples/%s", e->d_name);
            n++;
        }
    }
    closedir(dir);
    assert_true(n >= 1);
    for (int i = 0; i < n; i++) {
        check_scheme_text(names[i], NULL);
        free(names[i]);
    }
}

/* Functions at the edges of their domains, in generated C against exact
 * values and statuses: odd roots of negative numbers keep their sign
 * (t^(1/5), t^(3/7) at t = -0.75), ln at 0 and below is status 4 like
 * sqrt of a negative number, an even root of a negative number too. */
static void test_emit_c_function_edges(void **state)
{
    (void)state;
    check_scheme_text("edges.pcs", "point A, B\nparam t\n"
                                   "M = along(A, B, t^(1/5))\n"
                                   "R = along(A, B, t^(3/7) + t^(1/9))\n"
                                   "L = ln(t)\n"
                                   "Q = along(A, B, t^(1/4))\n"
                                   "output M, R, L, Q\n");
}

/* An interpolation scheme passes through its nodes (issue: evaluation at
 * the nodes): output o at the node parameters is the node points, in the
 * generated C (one point and batch) and in the runtime (what `eval` runs),
 * to 1e-12 relative to the largest coordinate, in dims 2, 3 and 7, with
 * random (non-dyadic) points. */
static void check_nodes_ex(const char *path, const char *define, int o, int nn,
                           const double *tnode, const int *node_pt,
                           const double *cst)
{
    const char *defs[1] = {define};
    DeriveOptions opt = {.max_seconds = 60,
                         .defines = defs,
                         .ndefines = define ? 1 : 0,
                         .numeric = numsolve_run};
    Derived *d = derive_file_ex(path, stderr, NULL, &opt);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    assert_int_equal(p->nparams, 1);
    Compiled c;
    compile_plan(&c, p);
    char name[32];
    snprintf(name, sizeof name, "w1_%d", o);
    one_fn one = (one_fn)(uintptr_t)dlsym(c.so, name);
    snprintf(name, sizeof name, "wb_%d", o);
    batch_fn batch = (batch_fn)(uintptr_t)dlsym(c.so, name);
    assert_non_null(one);
    assert_non_null(batch);
    static const int dims[] = {2, 3, 7};
    const double *prm[1] = {tnode};
    int npt = p->npoints;
    srand(12345);
    for (int di = 0; di < 3; di++) {
        int dim = dims[di];
        double **pts = malloc(sizeof *pts * (size_t)npt), big = 0;
        double *out = malloc(sizeof *out * (size_t)(dim * nn));
        unsigned char st[64];
        for (int k = 0; k < npt; k++) {
            pts[k] = malloc(sizeof **pts * (size_t)dim);
            for (int cc = 0; cc < dim; cc++) {
                pts[k][cc] = 10.0 * rand() / RAND_MAX - 5.0;
                big = fmax(big, fabs(pts[k][cc]));
            }
        }
        for (int way = 0; way < 3; way++) {
            if (way == 0)
                for (int k = 0; k < nn; k++)
                    assert_int_equal(one(tnode + k, cst,
                                         (const double *const *)pts, dim,
                                         out + k * dim, 1),
                                     0);
            else if (way == 1)
                assert_int_equal(batch((size_t)nn, prm, cst,
                                       (const double *const *)pts, dim, out, st,
                                       1),
                                 0);
            else
                assert_int_equal(plan_eval(p, o, (size_t)nn, prm, cst,
                                           (const double *const *)pts, dim, out,
                                           st),
                                 0);
            for (int k = 0; k < nn; k++)
                for (int cc = 0; cc < dim; cc++) {
                    double err =
                        fabs(out[k * dim + cc] - pts[node_pt[k]][cc]) / big;
                    total_checks++;
                    if (!(err <= REL_TOL))
                        fail_msg("%s (%s) output %d dim %d, %s: node %d "
                                 "coordinate %d off by %g relative",
                                 path, define ? define : "-", o, dim,
                                 way == 0   ? "generated"
                                 : way == 1 ? "generated batch"
                                            : "runtime",
                                 k, cc, err);
                }
        }
        for (int k = 0; k < npt; k++)
            free(pts[k]);
        free(pts);
        free(out);
    }
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

/* nodes at t = k/n, k = 0..n, the points in node order, output 0 */
static void check_nodes(const char *path, const char *define, int n)
{
    double ts[64];
    int pt[64];
    for (int k = 0; k <= n; k++) {
        ts[k] = (double)k / n;
        pt[k] = k;
    }
    check_nodes_ex(path, define, 0, n + 1, ts, pt, NULL);
}

static void test_emit_c_interpolation_passes_through_nodes(void **state)
{
    (void)state;
    check_nodes("examples/interpolation_bezier_order2.pcs", NULL, 2);
    check_nodes("examples/interpolation_desargues.pcs", NULL, 3);
    check_nodes("examples/interpolation_rational_cubic.pcs", NULL, 3);
    static const char *const orders[] = {"n=1", "n=2", "n=3", "n=4",
                                         "n=5", "n=6", "n=8", "n=12"};
    for (size_t i = 0; i < sizeof orders / sizeof *orders; i++)
        check_nodes("examples/interpolation_bezier.pcs", orders[i],
                    atoi(orders[i] + 2));
    /* 4.1: A, K, B at u = 0, 1/2, 1, for a const k */
    const double t3[3] = {0, 0.5, 1}, kc[1] = {0.3};
    const int p3[3] = {0, 1, 2};
    check_nodes_ex("examples/interpolation_conic.pcs", NULL, 0, 3, t3, p3, kc);
    /* 4.9: M through M1..M4 at 0, 1/3, 2/3, 1; N through M1..M3 at 0,
     * 1/2, 1 (outputs M, C3, C4, N, D3) */
    const double t4[4] = {0, 1.0 / 3, 2.0 / 3, 1};
    const int p4[4] = {0, 1, 2, 3};
    check_nodes_ex("examples/interpolation_tangents.pcs", NULL, 0, 4, t4, p4,
                   NULL);
    check_nodes_ex("examples/interpolation_tangents.pcs", NULL, 3, 3, t3, p3,
                   NULL);
    /* 4.10: M through M2 at 389/428, M91 at 0.91 (outputs M, C, M91, C91) */
    const double ta[3] = {0, 389.0 / 428, 1}, tb[3] = {0, 0.91, 1};
    check_nodes_ex("examples/interpolation_adaptive.pcs", NULL, 0, 3, ta, p3,
                   NULL);
    check_nodes_ex("examples/interpolation_adaptive.pcs", NULL, 2, 3, tb, p3,
                   NULL);
}

/* the contract's Desargues scheme, inline: at t = 1/2 the centroid */
static const char desargues[] = "scheme desargues_arc\n"
                                "point A, B, C, D\n"
                                "param t in [0, 1]\n"
                                "P = along(A, C, t)\n"
                                "Q = along(C, B, t)\n"
                                "K = along(B, D, t)\n"
                                "N = along(P, Q, t)\n"
                                "J = along(Q, K, t)\n"
                                "T = meet(line(P, Q), line(A, B))\n"
                                "S = meet(line(Q, K), line(C, D))\n"
                                "M = meet(line(S, N), line(T, J))\n"
                                "output M\n";

static void test_emit_c_desargues_centroid_at_half(void **state)
{
    (void)state;
    Derived *d =
        derive_source("d.pcs", desargues, strlen(desargues), stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    Compiled c;
    compile_plan(&c, p);
    one_fn one = (one_fn)(uintptr_t)dlsym(c.so, "w1_0");
    batch_fn batch = (batch_fn)(uintptr_t)dlsym(c.so, "wb_0");
    double A[3] = {1, 2, 3}, B[3] = {-4, 5, 0.5}, C[3] = {7, -1, 2},
           D[3] = {0, 0, 8};
    const double *pts[4] = {A, B, C, D};
    double half = 0.5, out[3], bout[3 * 5];
    assert_int_equal(one(&half, NULL, pts, 3, out, 1), 0);
    for (int k = 0; k < 3; k++)
        assert_true(fabs(out[k] - (A[k] + B[k] + C[k] + D[k]) / 4) < 1e-15);
    /* the whole arc: no pole anywhere (2t^2 - 2t + 1 >= 1/2) */
    double ts[5] = {0, 0.25, 0.5, 0.75, 1};
    const double *prm[1] = {ts};
    unsigned char st[5];
    assert_int_equal(batch(5, prm, NULL, pts, 3, bout, st, 1), 0);
    for (int k = 0; k < 3; k++) {
        assert_true(bout[k] == A[k]);       // t = 0: A
        assert_true(bout[12 + k] == D[k]);  // t = 1: D
        assert_true(bout[6 + k] == out[k]); // t = 1/2 as above
    }
    /* the plan shares one denominator and one division; two checks: the
     * pole of the denominator's one factor, the overflow (1/L == 0) */
    int ndiv = 0, npole = 0, inv = -1;
    for (int i = 0; i < p->nins; i++) {
        ndiv += p->ins[i].op == PLAN_DIV;
        npole += p->ins[i].op == PLAN_POLE;
        if (p->ins[i].op == PLAN_DIV)
            inv = i;
    }
    assert_int_equal(ndiv, 1);
    assert_int_equal(npole, 2);
    int on_inv = 0;
    for (int i = 0; i < p->nins; i++)
        on_inv += p->ins[i].op == PLAN_POLE && p->ins[i].a == inv;
    assert_int_equal(on_inv, 1);
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

/* names that clash with C, <math.h> macros, the generated code's locals
 * and its function names; a scalar output; consts; a power above the
 * multiplication chains (POWI, i.e. pow()); a pole */
static const char clashes[] = "scheme clash\n"
                              "point n, out, int, r1, FP_NAN, clash_V_batch\n"
                              "point unix, q0, s1, M_PI, new, EDOM, FLT_MAX\n"
                              "param dim, j\n"
                              "const w0, nb\n"
                              "k = 1/(dim - w0)\n"
                              "M = along(n, out, dim^40/(1 + dim^2))\n"
                              "V = int - r1\n"
                              "Z = divide(n, int, j*w0*nb)\n"
                              "Y = along(FP_NAN, clash_V_batch, nb*dim)\n"
                              "X = (unix + q0 + s1 + M_PI + new + EDOM + "
                              "FLT_MAX)/7\n"
                              "output k, M, V, Z, Y, X\n";

static void test_emit_c_edge_cases_match(void **state)
{
    (void)state;
    check_scheme_text("clash.pcs", clashes);
}

/* dim = w0 = 0.75 is never a sample of dim; j*w0 = -1 happens at
 * j = -4/3 - not dyadic either; so poles are tested here */
static const char poles[] = "scheme poles\n"
                            "point A, B\n"
                            "param t\n"
                            "M = A + (B - A)/t\n"
                            "h = 1/(t^2 - t)\n"
                            "output M, h\n";

static void test_emit_c_poles_are_nan_and_reported(void **state)
{
    (void)state;
    check_scheme_text("poles.pcs", poles);
}

static void test_emit_c_is_deterministic(void **state)
{
    (void)state;
    Derived *d =
        derive_source("d.pcs", desargues, strlen(desargues), stderr, NULL);
    Plan *p1 = lower_derived(d, stderr), *p2 = lower_derived(d, stderr);
    char *a = harness_emit(p1, 0, "test.pcs"),
         *b = harness_emit(p2, 0, "test.pcs");
    assert_string_equal(a, b);
    /* every temporary names its scheme line */
    assert_non_null(strstr(a, "/* line 11"));
    free(a);
    free(b);
    plan_free(p1);
    plan_free(p2);
    derived_free(d);
}

/* two outputs whose C function names coincide, and a name C reserves */
static void test_emit_c_clash_detects_function_names(void **state)
{
    (void)state;
    static const char src[] = "scheme f\npoint A, B\nparam t\n"
                              "M = along(A, B, t)\nM_batch = along(B, A, t)\n"
                              "output M, M_batch\n";
    Derived *d = derive_source("f.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    int o1 = -1, o2 = -1;
    char *name = NULL;
    assert_int_equal(emit_c_clash(p, NULL, &o1, &o2, &name), 1);
    assert_int_equal(o1, 0);
    assert_int_equal(o2, 1);
    assert_string_equal(name, "f_M_batch");
    free(name);
    /* a prefix changes the names, not the clash */
    assert_int_equal(emit_c_clash(p, "g", &o1, &o2, &name), 1);
    assert_string_equal(name, "g_M_batch");
    free(name);
    plan_free(p);
    derived_free(d);
    /* the Desargues arc has none */
    d = derive_source("d.pcs", desargues, strlen(desargues), stderr, NULL);
    p = lower_derived(d, stderr);
    assert_int_equal(emit_c_clash(p, NULL, &o1, &o2, &name), 0);
    plan_free(p);
    derived_free(d);
}

/* lower_q_to_double is the nearest double, ties to even: |q - d| is at
 * most the distance to either neighbour, and on a tie d's last bit is 0 */
static void test_lower_q_to_double_rounds_to_nearest(void **state)
{
    (void)state;
    flint_rand_t rs;
    flint_randinit(rs);
    fmpq_t q, x, dist, other;
    fmpq_init(q);
    fmpq_init(x);
    fmpq_init(dist);
    fmpq_init(other);
    int wrong_if_truncated = 0;
    for (int i = 0; i < 3000; i++) {
        fmpq_randtest_not_zero(q, rs, 120 + (flint_bitcnt_t)(i % 7) * 40);
        double d;
        assert_int_equal(lower_q_to_double(&d, q), LOWER_OK);
        fmpq_set_double(x, d);
        fmpq_sub(dist, q, x);
        fmpq_abs(dist, dist);
        for (int s = -1; s <= 1; s += 2) {
            double nb = nextafter(d, s * INFINITY);
            fmpq_set_double(x, nb);
            fmpq_sub(other, q, x);
            fmpq_abs(other, other);
            int c = fmpq_cmp(dist, other);
            assert_true(c <= 0);
            if (c == 0) { // a tie: d even
                int e;
                double m = frexp(d, &e);
                assert_true(fmod(ldexp(m, 53), 2.0) == 0.0);
            }
        }
        wrong_if_truncated += fmpq_get_d(q) != d;
    }
    /* the case FLINT 2.9's fmpq_get_d gets wrong: 2^54 + 3 */
    fmpq_set_si(q, 18014398509481987, 1);
    double d;
    assert_int_equal(lower_q_to_double(&d, q), LOWER_OK);
    assert_true(d == 18014398509481988.0);
    assert_true(wrong_if_truncated > 0); // the test can tell the two apart
    /* subnormals, the edges, zero */
    fmpq_set_si(q, 1, 1);
    fmpq_div_2exp(q, q, 1074);
    assert_int_equal(lower_q_to_double(&d, q), LOWER_OK);
    assert_true(d == 0x1p-1074);
    fmpq_div_2exp(q, q, 2); // 2^-1076 rounds to 0
    assert_int_equal(lower_q_to_double(&d, q), LOWER_UNDERFLOW);
    fmpq_set_si(q, 3, 1);
    fmpq_mul_2exp(q, q, 1023); // 1.5 * 2^1024
    assert_int_equal(lower_q_to_double(&d, q), LOWER_OVERFLOW);
    fmpq_set_si(q, -7, 3);
    assert_int_equal(lower_q_to_double(&d, q), LOWER_OK);
    assert_true(d == -7.0 / 3.0);
    fmpq_zero(q);
    assert_int_equal(lower_q_to_double(&d, q), LOWER_OK);
    assert_true(d == 0);
    fmpq_clear(other);
    fmpq_clear(dist);
    fmpq_clear(x);
    fmpq_clear(q);
    flint_randclear(rs);
}

/* the first line of what lower_derived reports for scheme src */
static char *lower_error(const char *src)
{
    Derived *d = derive_source("x.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    Plan *p = lower_derived(d, m);
    fclose(m);
    assert_null(p);
    derived_free(d);
    char *nl = strchr(text, '\n');
    if (nl)
        *nl = '\0';
    return text;
}

static void test_lower_reports_unrepresentable_equations(void **state)
{
    (void)state;
    /* weights that no double holds, whatever their scaling */
    char *e = lower_error("point A, B\nparam t\nM = A + (B - A)*10^400*t\n");
    assert_string_equal(e, "x.pcs:3:1: error: M cannot be evaluated in double "
                           "precision: scaled to integer coefficients, its "
                           "equation has a coefficient of about 10^400, "
                           "beyond the largest double");
    free(e);
    /* a tiny ratio as written: the message says why 10^400 appears */
    e = lower_error("point A, B\nparam t\nM = along(A, B, 10^-400*t)\n");
    assert_string_equal(e, "x.pcs:3:1: error: M cannot be evaluated in double "
                           "precision: scaled to integer coefficients, its "
                           "equation has a coefficient of about 10^400, "
                           "beyond the largest double");
    free(e);
    e = lower_error("point A, B\nparam t\nV = (B - A)*t/10^400\n");
    assert_string_equal(e, "x.pcs:3:1: error: V cannot be evaluated in double "
                           "precision: a coefficient of its equation (about "
                           "10^-400) is below the smallest double and would "
                           "be 0");
    free(e);
    /* no rescaling: a coefficient beyond the double range is an error even
     * where the value would be fine for some t (10^400 t + 1 at t = 0) */
    e = lower_error("point A, B\nparam t\nN = divide(A, B, 10^400*t)\n");
    assert_string_equal(e, "x.pcs:3:1: error: N cannot be evaluated in double "
                           "precision: scaled to integer coefficients, its "
                           "equation has a coefficient of about 10^400, "
                           "beyond the largest double");
    free(e);
    e = lower_error("param t\nb = (((t^1000)^1000)^1000)^3\n");
    assert_string_equal(e, "x.pcs:2:1: error: b cannot be evaluated "
                           "numerically: its equation has degree 3000000000, "
                           "beyond the limit of 16777216");
    free(e);
}

/* high powers of one factor stay powers (square-free factorisation where
 * full factoring is too costly): 1/(4t - 3)^201 expanded would lose every
 * digit near t = 3/4, and its pole would be checked on the product */
static void test_lower_keeps_powers_of_factors(void **state)
{
    (void)state;
    check_scheme_text("powers.pcs", "scheme powers\nparam t, u\n"
                                    "s = 1/(t - 3/4)^201\n"
                                    "v = 1/((t - 3/4)^17*(u + 5/8)^17)\n"
                                    "output s, v\n");
    static const char src[] = "param t\ns = 1/(t - 3/4)^201\n";
    Derived *d = derive_source("p.pcs", src, strlen(src), stderr, NULL);
    Plan *p = lower_derived(d, stderr);
    double t = 0.75, out;
    const double *prm[1] = {&t};
    unsigned char st;
    assert_int_equal(plan_eval(p, 0, 1, prm, NULL, NULL, 1, &out, &st), 1);
    assert_int_equal(st, PLAN_STATUS_POLE);
    assert_true(isnan(out));
    plan_free(p);
    derived_free(d);
}

/* a denominator that overflows (k t = 1e310) would make 1/L = 0 and the
 * point silently A; it is NaN with status 2 in all four generated
 * functions and in the runtime, a pole stays status 1 */
static void test_emit_c_denominator_overflow_is_reported(void **state)
{
    (void)state;
    static const char src[] = "scheme ov\npoint A, B\nparam t\nconst k\n"
                              "M = divide(A, B, k*t)\n";
    Derived *d = derive_source("ov.pcs", src, strlen(src), stderr, NULL);
    Plan *p = lower_derived(d, stderr);
    Compiled c;
    compile_plan(&c, p);
    one_fn one = (one_fn)(uintptr_t)dlsym(c.so, "w1_0");
    batch_fn batch = (batch_fn)(uintptr_t)dlsym(c.so, "wb_0");
    double A[2] = {0, 1}, B[2] = {1e10, 2};
    const double *pts[2] = {A, B};
    double k = 1e300, ts[3] = {1e10, 1, -1e-300}, out[2], bout[6], rout[6];
    const double *prm[1] = {ts};
    unsigned char st[3], rst[3];
    static const int want[3] = {2, 0, 1};
    for (int i = 0; i < 3; i++) {
        assert_int_equal(one(&ts[i], &k, pts, 2, out, 1), want[i]);
        assert_true(want[i] ? isnan(out[0]) && isnan(out[1])
                            : fabs(out[0] - 1e10) <= 1e-5);
    }
    assert_int_equal(batch(3, prm, &k, pts, 2, bout, st, 1), 2);
    assert_int_equal(plan_eval(p, 0, 3, prm, &k, pts, 2, rout, rst), 2);
    for (int i = 0; i < 3; i++) {
        assert_int_equal(st[i], want[i]);
        assert_int_equal(rst[i], want[i]);
        assert_true(want[i] ? isnan(bout[2 * i]) && isnan(rout[2 * i])
                            : bout[2 * i] == rout[2 * i]);
    }
    /* the unchecked batch (its own code for dim 2 and 3: 1/L made NaN
     * where L * (1/L) is not about 1) writes NaN rows at the pole and the
     * overflow too, and the value elsewhere; dim 3 and dim 4 (the general
     * code) as well */
    double A3[4] = {0, 1, 5, 6}, B3[4] = {1e10, 2, 5, 7}, bout3[12];
    const double *pts3[2] = {A3, B3};
    for (int dim = 2; dim <= 4; dim++) {
        for (int i = 0; i < 3 * dim; i++)
            bout3[i] = 0.0;
        batch(3, prm, &k, dim == 2 ? pts : pts3, dim, bout3, NULL, 0);
        for (int i = 0; i < 3; i++)
            for (int cc = 0; cc < dim; cc++)
                assert_true(want[i] ? isnan(bout3[dim * i + cc])
                                    : fabs(bout3[dim * i + cc] -
                                           (cc == 0   ? 1e10
                                            : cc == 1 ? 2.0
                                            : cc == 2 ? 5.0
                                                      : 7.0)) <= 1e-5);
    }
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

/* coord(P, k): a point whose weights read a coordinate, scalars of
 * coordinates (under a function too), compared exactly in every dim that
 * has k coordinates; with fewer, the generated functions read no memory
 * beyond the point: NaN, status 3 (not finite), and the runtime NaN */
static void test_emit_c_coord_matches_exact(void **state)
{
    (void)state;
    static const char text[] = "scheme cc\n"
                               "point A, B, C\n"
                               "param t\n"
                               "M = along(A, B, coord(C, 1)*t)\n"
                               "x = coord(M, 2)\n"
                               "r = sqrt(coord(A, 1)^2 + coord(A, 2)^2 + 1)\n"
                               "v = coord(B - A, 3)*t\n"
                               "output M, x, r, v\n";
    check_scheme_text("coord.pcs", text);
    /* an unknown scalar and kernels in one ring (lower.c's uses_atoms
     * wrote past its array: tests/fuzz/regressions/) */
    check_scheme_text("us.pcs", "point A, B\nunknown scalar k\nparam t\n"
                                "solve A*k + B*(1-k) = along(A, B, 1/2) for k\n"
                                "M = along(A, B, sin(t)*k + coord(B, 1))\n");

    int nerr = 0;
    Derived *d = derive_source("coord.pcs", text, strlen(text), stderr, &nerr);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    assert_int_equal(plan_output_min_dim(p, 0, NULL), 1);
    assert_int_equal(plan_output_min_dim(p, 1, NULL), 2);
    int pt = -2;
    assert_int_equal(plan_output_min_dim(p, 3, &pt), 3);
    assert_true(pt == 0 || pt == 1);
    Compiled c;
    compile_plan(&c, p);
    double a[3] = {1, 2, 3}, b[3] = {4, 6, 8}, cc[3] = {0.5, 0, 0};
    const double *pts[3] = {a, b, cc};
    double prm[1] = {0.5}, row[3];
    /* dim 3: x = coord(M, 2) = 2 + (6 - 2)*0.5*0.5 = 3, v = 5*0.5 */
    one_fn x = (one_fn)(uintptr_t)dlsym(c.so, "w1_1");
    one_fn v = (one_fn)(uintptr_t)dlsym(c.so, "w1_3");
    assert_non_null(x);
    assert_non_null(v);
    assert_int_equal(x(prm, NULL, pts, 3, row, 1), 0);
    assert_true(row[0] == 3.0);
    assert_int_equal(v(prm, NULL, pts, 3, row, 1), 0);
    assert_true(row[0] == 2.5);
    /* too few coordinates: NaN, status 3 */
    assert_int_equal(x(prm, NULL, pts, 1, row, 1), 3);
    assert_true(isnan(row[0]));
    x(prm, NULL, pts, 1, row, 0);
    assert_true(isnan(row[0]));
    assert_int_equal(v(prm, NULL, pts, 2, row, 1), 3);
    assert_true(isnan(row[0]));
    batch_fn vb = (batch_fn)(uintptr_t)dlsym(c.so, "wb_3");
    assert_non_null(vb);
    const double *prms[1] = {prm};
    unsigned char st[1] = {0};
    assert_int_equal(vb(1, prms, NULL, pts, 2, row, st, 1), 1);
    assert_int_equal(st[0], 3);
    assert_true(isnan(row[0]));
    /* the runtime: NaN, never a read beyond the point */
    plan_eval(p, 3, 1, prms, NULL, pts, 2, row, st);
    assert_true(isnan(row[0]));
    plan_eval(p, 3, 1, prms, NULL, pts, 3, row, st);
    assert_true(row[0] == 2.5);
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

static int teardown(void **state)
{
    (void)state;
    flint_cleanup_master();
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_emit_c_desargues_centroid_at_half),
        cmocka_unit_test(test_emit_c_is_deterministic),
        cmocka_unit_test(test_emit_c_edge_cases_match),
        cmocka_unit_test(test_emit_c_poles_are_nan_and_reported),
        cmocka_unit_test(test_emit_c_clash_detects_function_names),
        cmocka_unit_test(test_lower_q_to_double_rounds_to_nearest),
        cmocka_unit_test(test_lower_reports_unrepresentable_equations),
        cmocka_unit_test(test_lower_keeps_powers_of_factors),
        cmocka_unit_test(test_emit_c_denominator_overflow_is_reported),
        cmocka_unit_test(test_emit_c_coord_matches_exact),
        cmocka_unit_test(test_emit_c_examples_match_exact_and_runtime),
        cmocka_unit_test(test_emit_c_function_edges),
        cmocka_unit_test(test_emit_c_interpolation_passes_through_nodes),
    };
    int rc = cmocka_run_group_tests(tests, NULL, teardown);
    fprintf(stderr, "test_emit_c: %d value comparisons\n", total_checks);
    return rc;
}
