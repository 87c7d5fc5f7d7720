/*
 * test_collapse.c - the collapsed kernel (emit-c --kernel collapsed,
 * codegen/collapse.h) against exact rational evaluation.
 *
 * Every scheme in examples/ and tests/schemes/, a few families at degree
 * 10 and 12 (interpolation_bezier -D n=10, 12; inline schemes of degree 12)
 * is emitted with the collapsed kernel, compiled (-std=c99 -pedantic
 * -Werror), and every collapsed output's _batch_checked and _batch are
 * compared, at 301 parameter values spread over the declared range (and
 * its ends), with the exact value of the reduced equation (FLINT fmpq), in
 * dims 2, 3 and 5, with points of comparable size (coordinates of
 * magnitude 1 to 2, either sign):
 *
 *   |got - exact| <= 1e-12 max(|exact|, sum_k |w_k P_k[c]|)   (the tests'
 *                                                              scale)
 *   |got - exact| <= bound * max_k |P_k[c]| * sum_k |w_k|      (the bound
 *                                                              itself)
 *
 * Values outside the range and NaN go to the weights code (compared at
 * 1e-12 too, NaN: status 3).  The fast path of full blocks against the
 * weights code: one flagged sample in a block, n not a multiple of 64,
 * non-finite points.  The bound must refuse the monomial basis for
 * the degree-12 Bernstein and Lagrange weights, and a perturbed
 * coefficient must be caught.
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

#include "codegen/collapse.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "tests/unit/emit_harness.h"

#define REL_TOL 1e-12
#define NS 301 // samples in the range: > 4 blocks of 64

typedef size_t (*batch_fn)(size_t n, const double *const *prm,
                           const double *cst, const double *const *pts, int dim,
                           double *out, unsigned char *status, int checked);

static int total_checks, total_collapsed;

/* the C (collapsed kernel), its header and a wrapper wb_O per output */
static void compile(Compiled *c, const Plan *p)
{
    char *src = NULL, *hdr = NULL, *wrap = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&src, &len);
    emit_c_kernel(m, p, "pcx", "test.pcs", EMIT_C_ALL);
    fclose(m);
    m = open_memstream(&hdr, &len);
    emit_c_header(m, p, "pcx", "test.pcs");
    fclose(m);
    m = open_memstream(&wrap, &len);
    fputs("#include <stddef.h>\n#include \"gen.h\"\n", m);
    for (int o = 0; o < p->noutputs; o++)
        harness_batch_wrapper(m, p, o);
    fclose(m);
    harness_compile(c, "collapse", src, hdr, wrap);
    free(src);
    free(hdr);
    free(wrap);
}

/* The largest error of output o over the samples, relative to the bound's
 * scale (max_k |P_k[c]| sum_k |w_k|); fails (strict) when a value misses
 * the tests' 1e-12 or the bound itself. */
static double check_output(const Derived *d, const Plan *p, const Collapse *col,
                           const Compiled *c, int o, int strict)
{
    const CollapseOutput *co = &col->o[o];
    const DerivedOutput *dout = &d->outputs[derived_find_output(d, co->name)];
    int np = p->nparams, nv = (int)d->ring.nvars > 0 ? (int)d->ring.nvars : 1;
    int K = (int)dout->eq->len, pi = co->param;
    char name[32];
    snprintf(name, sizeof name, "wb_%d", o);
    batch_fn batch = (batch_fn)(uintptr_t)dlsym(c->so, name);
    assert_non_null(batch);
    /* the samples: the range's doubles, its ends, then outside it and NaN */
    enum { NOUT = 5 };
    int n = NS + NOUT;
    double **prm = calloc((size_t)np + 1, sizeof *prm);
    for (int i = 0; i < np; i++) {
        prm[i] = malloc(sizeof **prm * (size_t)n);
        for (int s = 0; s < n; s++)
            prm[i][s] = 0.5;
    }
    double lo = co->lo, hi = co->hi, w = hi - lo;
    for (int s = 0; s < NS; s++)
        prm[pi][s] = s == NS - 1 ? hi : lo + w * s / (NS - 1);
    const double outside[NOUT] = {lo - 0.25 * w - 0.5, hi + 0.5 * w + 0.25, NAN,
                                  lo - 1e-3 * w - 1e-3, hi + 2.0 * w + 1};
    for (int s = 0; s < NOUT; s++)
        prm[pi][NS + s] = outside[s];
    /* the outside samples in the middle of a block: the weights code gets
     * a whole block */
    for (int s = 0; s < NOUT; s++) {
        double t = prm[pi][NS + s];
        prm[pi][NS + s] = prm[pi][70 + 3 * s];
        prm[pi][70 + 3 * s] = t;
    }
    double cst[8] = {0.75, 0.625, 1.25, -0.5, 2.0, 0.375, 1.5, 3.0};
    fmpq *vals = _fmpq_vec_init(nv), *wk = _fmpq_vec_init(K);
    for (int i = 0; i < np; i++)
        fmpq_set_si(vals + i, 1, 2);
    for (int i = 0; i < p->nconsts && i < 8; i++)
        fmpq_set_double(vals + np + i, cst[i]);
    flint_rand_t rs;
    flint_randinit(rs);
    double worst = 0;
    static const int dims[] = {2, 3, 5};
    for (int di = 0; di < 3; di++) {
        int dim = dims[di];
        double **pts = calloc((size_t)p->npoints + 1, sizeof *pts);
        for (int k = 0; k < p->npoints; k++) {
            pts[k] = malloc(sizeof **pts * (size_t)dim);
            for (int cc = 0; cc < dim; cc++) { // 1 to 2, either sign
                double v = 1 + (double)n_randint(rs, 1025) / 1024;
                pts[k][cc] = n_randint(rs, 2) ? v : -v;
            }
        }
        double *got = malloc(sizeof *got * (size_t)(n * dim));
        unsigned char *st = malloc((size_t)n);
        for (int checked = 1; checked >= 0; checked--) {
            memset(st, 7, (size_t)n);
            size_t nb = batch((size_t)n, (const double *const *)prm, cst,
                              (const double *const *)pts, dim, got,
                              checked ? st : NULL, checked);
            for (int s = 0; s < n; s++) {
                double t = prm[pi][s];
                if (isnan(t)) { /* the weights code: status 3 */
                    if (checked)
                        assert_int_equal(st[s], 3);
                    for (int cc = 0; cc < dim; cc++)
                        assert_true(checked ? isnan(got[s * dim + cc]) : 1);
                    continue;
                }
                int in = t >= lo && t <= hi;
                fmpq_set_double(vals + pi, t);
                int pole = 0;
                double sumw = 0;
                for (int k = 0; k < K; k++) {
                    if (ratfun_evaluate_fmpq(wk + k, &dout->w[k], vals,
                                             &d->ring) == RATFUN_EPOLE)
                        pole = 1;
                    else
                        sumw += fabs(fmpq_get_d(wk + k));
                }
                /* a value outside a declared range the output rests
                 * on: status 4 (docs/language.md, "Declared ranges") */
                int out_of_range = outside_assumed(d, dout, vals);
                if (checked)
                    assert_int_equal(st[s], out_of_range ? 4 : pole ? 1 : 0);
                for (int cc = 0; cc < dim; cc++) {
                    double g = got[s * dim + cc];
                    if (out_of_range) {
                        assert_true(isnan(g));
                        continue;
                    }
                    if (pole) {
                        assert_false(in);
                        assert_true(isnan(g));
                        continue;
                    }
                    fmpq_t sum, x;
                    fmpq_init(sum);
                    fmpq_init(x);
                    double sc = 0, pmax = 0;
                    for (int k = 0; k < K; k++) {
                        double P = pts[dout->eq->terms[k].point][cc];
                        fmpq_set_double(x, P);
                        fmpq_mul(x, x, wk + k);
                        fmpq_add(sum, sum, x);
                        sc += fabs(fmpq_get_d(wk + k) * P);
                        pmax = fmax(pmax, fabs(P));
                    }
                    /* |got - exact|, exactly, rounded */
                    fmpq_set_double(x, g);
                    fmpq_sub(x, x, sum);
                    double err = fabs(fmpq_get_d(x));
                    double exact = fmpq_get_d(sum);
                    fmpq_clear(x);
                    fmpq_clear(sum);
                    double tol = REL_TOL * fmax(fabs(exact), sc);
                    total_checks++;
                    if (strict && !(err <= tol))
                        fail_msg("%s output %s t = %.17g dim %d coord %d: "
                                 "got %.17g, exact %.17g (error %g, tol %g)",
                                 p->name, co->name, t, dim, cc, g, exact, err,
                                 tol);
                    if (!in)
                        continue;
                    double rel = err / (pmax * sumw);
                    worst = fmax(worst, rel);
                    if (strict && !(rel <= co->bound))
                        fail_msg("%s output %s t = %.17g: error %g relative, "
                                 "above the bound %g",
                                 p->name, co->name, t, rel, co->bound);
                }
            }
            if (checked) {
                size_t expect = 0;
                for (int s = 0; s < n; s++)
                    expect += st[s] != 0;
                assert_int_equal(nb, expect);
            }
        }
        free(st);
        free(got);
        for (int k = 0; k < p->npoints; k++)
            free(pts[k]);
        free(pts);
    }
    flint_randclear(rs);
    _fmpq_vec_clear(vals, nv);
    _fmpq_vec_clear(wk, K);
    for (int i = 0; i < np; i++)
        free(prm[i]);
    free(prm);
    return worst;
}

/* derives (a file, or text when not NULL; -D define), checks every
 * collapsed output; returns how many were collapsed */
static int check_scheme(const char *path, const char *text, const char *define)
{
    const char *defs[1] = {define};
    DeriveOptions opt = {.max_seconds = 60,
                         .defines = defs,
                         .ndefines = define ? 1 : 0,
                         .numeric = numsolve_run};
    Derived *d =
        text ? derive_source_ex(path, text, strlen(text), stderr, NULL, &opt)
             : derive_file_ex(path, stderr, NULL, &opt);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    Collapse *col = lower_collapse(p, d);
    assert_int_equal(col->n, p->noutputs);
    int any = 0;
    for (int o = 0; o < col->n; o++)
        any += col->o[o].ok;
    if (any) {
        Compiled c;
        compile(&c, p);
        for (int o = 0; o < col->n; o++) {
            if (!col->o[o].ok)
                continue;
            double worst = check_output(d, p, col, &c, o, 1);
            fprintf(stderr,
                    "collapse: %-34s %-10s deg %2d kappa %7.3g bound %8.3g "
                    "max error %8.3g\n",
                    path, col->o[o].name, col->o[o].deg, col->o[o].kappa,
                    col->o[o].bound, worst);
        }
        compiled_clear(&c);
    }
    total_collapsed += any;
    plan_free(p);
    derived_free(d);
    return any;
}

static void check_dir(const char *dir)
{
    DIR *dp = opendir(dir);
    assert_non_null(dp);
    struct dirent *e;
    while ((e = readdir(dp))) {
        size_t len = strlen(e->d_name);
        if (len <= 4 || strcmp(e->d_name + len - 4, ".pcs") != 0)
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        check_scheme(path, NULL, NULL);
    }
    closedir(dp);
}

/* ---- tests --------------------------------------------------------------- */

static void test_collapse_examples_match_exact(void **state)
{
    (void)state;
    total_collapsed = 0;
    check_dir("examples");
    check_dir("tests/schemes");
    assert_true(total_collapsed >= 15); // outputs that qualify
}

/* degree 12: a power (well conditioned: collapsed), a rational curve of
 * degree 12 with a denominator, a pole just outside the range; a range
 * of odd endpoints (the centre not a dyadic) and a wide one */
static const char high[] = "scheme high\n"
                           "point A, B, C\n"
                           "param t in [0, 1]\n"
                           "M = along(A, B, t^12)\n"
                           "R = along(along(A, B, t^12), C, t/(t^2 + 3))\n"
                           "output M, R\n";
/* the same power over another range: refused there (kappa >= 98) */
static const char odd[] = "scheme odd\n"
                          "point A, B, C\n"
                          "param t in [1/3, 7/5]\n"
                          "M = along(A, B, t^12)\n"
                          "Q = along(A, B, 1/(t - 2))\n"
                          "output M, Q\n";
static const char wide[] = "scheme wide\n"
                           "point A, B, C, D\n"
                           "param t in [-3, 1000]\n"
                           "P = along(A, C, t/1000)\n"
                           "Q = along(C, B, t/1000)\n"
                           "M = along(P, Q, t/(t + 500))\n"
                           "N = along(P, D, t/1000)\n"
                           "output M, N\n";
static const char bern12[] = "scheme bern12\n"
                             "point P[1..13]\n"
                             "param t in [0, 1]\n"
                             "X = bezier(t, P[1..13])\n";

static const CollapseOutput *find(const Collapse *col, const char *name)
{
    for (int o = 0; o < col->n; o++)
        if (strcmp(col->o[o].name, name) == 0)
            return &col->o[o];
    fail_msg("no output %s", name);
    return NULL;
}

static void test_collapse_high_degree(void **state)
{
    (void)state;
    assert_int_equal(check_scheme("high.pcs", high, NULL), 2);
    assert_int_equal(check_scheme("odd.pcs", odd, NULL), 1);
    assert_int_equal(check_scheme("wide.pcs", wide, NULL), 2);
    Derived *d = derive_source("high.pcs", high, strlen(high), stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    Collapse *col = lower_collapse(p, d);
    assert_int_equal(find(col, "M")->deg, 12);
    assert_true(find(col, "R")->deg >= 12);
    assert_true(find(col, "M")->ok && find(col, "R")->ok);
    plan_free(p);
    derived_free(d);
    d = derive_source("odd.pcs", odd, strlen(odd), stderr, NULL);
    p = lower_derived(d, stderr);
    col = lower_collapse(p, d);
    assert_false(find(col, "M")->ok); // the same power: refused over this range
    assert_true(find(col, "Q")->ok);
    plan_free(p);
    derived_free(d);
}

/* the bound refuses the monomial basis where it must: Bernstein weights
 * of degree 12 (kappa = 2^12 at the ends), Lagrange-like weights of the
 * interpolating Bezier curves of degree 10 and 12, and a denominator with
 * a root in the range (kappa_d infinite); those keep the weights code */
static void test_collapse_bound_refuses(void **state)
{
    (void)state;
    static const struct {
        const char *path, *text, *define, *out;
    } cases[] = {
        {"bern12.pcs", bern12, NULL, "X"},
        {"examples/interpolation_bezier.pcs", NULL, "n=10", "X"},
        {"examples/interpolation_bezier.pcs", NULL, "n=12", "X"},
        {"pole.pcs",
         "scheme pole\npoint A, B\nparam t in [0, 3]\n"
         "Q = along(A, B, 1/(t - 2))\n",
         NULL, "Q"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const char *defs[1] = {cases[i].define};
        DeriveOptions opt = {.max_seconds = 60,
                             .defines = defs,
                             .ndefines = cases[i].define ? 1 : 0};
        Derived *d =
            cases[i].text
                ? derive_source_ex(cases[i].path, cases[i].text,
                                   strlen(cases[i].text), stderr, NULL, &opt)
                : derive_file_ex(cases[i].path, stderr, NULL, &opt);
        assert_non_null(d);
        Plan *p = lower_derived(d, stderr);
        Collapse *col = lower_collapse(p, d);
        const CollapseOutput *co = find(col, cases[i].out);
        fprintf(stderr, "collapse: %s %s: %s\n", cases[i].path,
                cases[i].define ? cases[i].define : "", co->why);
        assert_false(co->ok);
        assert_non_null(strstr(co->why, "refused"));
        /* the output is emitted with the weights code: still right */
        char *text = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&text, &len);
        emit_c_kernel(m, p, NULL, NULL, EMIT_C_ALL);
        fclose(m);
        assert_null(strstr(text, "collapsed kernel (emit-c"));
        free(text);
        plan_free(p);
        derived_free(d);
    }
}

/* the comparison can fail: one coefficient off by 1e-9 relative */
static void test_collapse_detects_a_broken_coefficient(void **state)
{
    (void)state;
    Derived *d = derive_file("examples/desargues_arc.pcs", stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    Collapse *col = lower_collapse(p, d);
    int o = plan_find_output(p, "M");
    assert_true(col->o[o].ok);
    Compiled c;
    compile(&c, p);
    double good = check_output(d, p, col, &c, o, 1);
    compiled_clear(&c);
    CollapseOutput *co = &col->o[o];
    co->a[2 * co->nterms + 1] *= 1 + 1e-9;
    compile(&c, p);
    double bad = check_output(d, p, col, &c, o, 0);
    compiled_clear(&c);
    fprintf(stderr, "collapse: desargues M max error %g, broken %g\n", good,
            bad);
    assert_true(good <= co->bound);
    assert_true(bad > 1e3 * co->bound);
    plan_free(p);
    derived_free(d);
}

typedef size_t (*arc_fn)(size_t n, const double *t, const double *A,
                         const double *B, const double *C, const double *D,
                         int dim, double *out, unsigned char *status);

/* The fast path of full blocks and the general code around it: the
 * Desargues arc's collapsed _batch_checked against the weights kernel's
 * (the same C without --kernel collapsed) on layouts that put one flagged
 * sample in an otherwise plain full block (out of range at a block's
 * first, middle and last sample, NaN, just outside either end), n a
 * multiple of 64 and not, the tail alone, non-finite points (every sample
 * status 3), in dims 2, 3 and 5, status NULL and not: the same statuses,
 * NaN at the same places, the values within 1e-12. */
static void test_collapse_fast_path_blocks(void **state)
{
    (void)state;
    Derived *d = derive_file("examples/desargues_arc.pcs", stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    Collapse *col = lower_collapse(p, d);
    const CollapseOutput *co = find(col, "M");
    assert_true(co->ok);
    char *src = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&src, &len);
    emit_c_ex(m, p, "pcd", "arc.pcs", EMIT_C_ALL);
    emit_c_kernel(m, p, "pcx", "arc.pcs", EMIT_C_ALL);
    fclose(m);
    Compiled c;
    char path[128], cmd[512];
    strcpy(c.dir, "/tmp/pc_collapse_XXXXXX");
    assert_non_null(mkdtemp(c.dir));
    snprintf(path, sizeof path, "%s/gen.c", c.dir);
    write_file(path, src);
    free(src);
    /* no header: the files compiled_clear removes must exist */
    snprintf(path, sizeof path, "%s/gen.h", c.dir);
    write_file(path, "\n");
    snprintf(path, sizeof path, "%s/wrap.c", c.dir);
    write_file(path, "\n");
    snprintf(cmd, sizeof cmd,
             "cd %s && cc -std=c99 -Wall -Wextra -Werror -pedantic -O2 "
             "-fPIC -shared -o gen.so gen.c -lm",
             c.dir);
    assert_int_equal(system(cmd), 0);
    snprintf(path, sizeof path, "%s/gen.so", c.dir);
    c.so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    assert_non_null(c.so);
    arc_fn ref = (arc_fn)(uintptr_t)dlsym(c.so, "pcd_M_batch_checked");
    arc_fn got = (arc_fn)(uintptr_t)dlsym(c.so, "pcx_M_batch_checked");
    assert_non_null(ref);
    assert_non_null(got);
    enum { NMAX = 4 * 64 + 9 };
    double lo = co->lo, hi = co->hi, w = hi - lo;
    const double flag_t[] = {lo - 0.5 * w, hi + 0.25 * w, NAN,
                             nextafter(lo, -INFINITY), nextafter(hi, INFINITY)};
    static const int where[] = {64 + 17, 128, 191, 192 + 63, 200};
    static const size_t ns[] = {NMAX, 256, 192, 64, 63, 1, 0};
    static const int dims[] = {2, 3, 5};
    double t[NMAX], P[4][5], *pts[4] = {P[0], P[1], P[2], P[3]};
    double a[NMAX * 5], b[NMAX * 5];
    unsigned char sa[NMAX], sb[NMAX];
    for (int k = 0; k < 4; k++)
        for (int cc = 0; cc < 5; cc++)
            P[k][cc] = (k + 1) * (cc % 2 ? -0.75 : 1.25) + 0.125 * cc;
    for (int layout = 0; layout < 7; layout++) {
        for (int s = 0; s < NMAX; s++)
            t[s] = lo + w * (s % 97) / 96;
        if (layout < 5) // one flagged sample
            t[where[layout]] = flag_t[layout];
        if (layout == 6) // every flagged sample at once
            for (int i = 0; i < 5; i++)
                t[where[i]] = flag_t[i];
        for (int bad = 0; bad < 2; bad++) {
            P[2][1] = bad ? INFINITY : 3 * -0.75 + 0.125;
            for (size_t ni = 0; ni < sizeof ns / sizeof *ns; ni++)
                for (int di = 0; di < 3; di++)
                    for (int checked = 1; checked >= 0; checked--) {
                        size_t n = ns[ni];
                        int dim = dims[di];
                        memset(sa, 7, sizeof sa);
                        memset(sb, 7, sizeof sb);
                        size_t ra = ref(n, t, pts[0], pts[1], pts[2], pts[3],
                                        dim, a, checked ? sa : NULL);
                        size_t rb = got(n, t, pts[0], pts[1], pts[2], pts[3],
                                        dim, b, checked ? sb : NULL);
                        if (!checked) {
                            assert_int_equal(sb[0], 7); // status untouched
                            if (bad) // no status: nothing to compare
                                continue;
                        }
                        assert_int_equal(ra, rb);
                        for (size_t s = 0; s < n; s++) {
                            if (checked)
                                assert_int_equal(sa[s], sb[s]);
                            int in = t[s] >= lo && t[s] <= hi;
                            for (int cc = 0; cc < dim; cc++) {
                                double x = a[s * (size_t)dim + (size_t)cc],
                                       y = b[s * (size_t)dim + (size_t)cc];
                                total_checks++;
                                if (isnan(x) || isnan(y)) {
                                    if (!(isnan(x) && isnan(y)))
                                        fail_msg("layout %d bad %d n %zu dim "
                                                 "%d checked %d sample %zu: "
                                                 "%.17g, weights %.17g",
                                                 layout, bad, n, dim, checked,
                                                 s, y, x);
                                    continue;
                                }
                                if (!in) /* the weights code itself */
                                    assert_true(x == y);
                                else if (!(fabs(x - y) <= 1e-12 * 8))
                                    fail_msg("layout %d n %zu dim %d sample "
                                             "%zu: %.17g, weights %.17g",
                                             layout, n, dim, s, y, x);
                            }
                        }
                    }
        }
    }
    compiled_clear(&c);
    plan_free(p);
    derived_free(d);
}

/* without a Collapse (and with one that collapses nothing) the C is
 * today's, byte for byte */
static void test_collapse_default_is_unchanged(void **state)
{
    (void)state;
    Derived *d = derive_file("examples/circle_three_points.pcs", stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    char *a = NULL, *b = NULL;
    size_t la = 0, lb = 0;
    FILE *m = open_memstream(&a, &la);
    emit_c_ex(m, p, NULL, "x.pcs", EMIT_C_ALL);
    fclose(m);
    m = open_memstream(&b, &lb);
    emit_c_kernel(m, p, NULL, "x.pcs", EMIT_C_ALL); /* p->collapse NULL */
    fclose(m);
    assert_string_equal(a, b);
    free(a);
    free(b);
    plan_free(p);
    derived_free(d);
}

static int teardown(void **state)
{
    (void)state;
    flint_cleanup_master();
    return 0;
}

/* the collapsed forms live in the Plan (lower_collapse) and follow its
 * outputs through plan_keep_outputs: reordered, dropped, each still its
 * own output's (name, degree, coefficients), so emit-c reads the Plan
 * alone */
static void test_collapse_follows_kept_outputs(void **state)
{
    (void)state;
    const char *text = "scheme keep\npoint A, B, C\nparam t in [0, 1]\n"
                       "M = along(A, B, t)\n"
                       "Q = along(along(A, B, t), along(B, C, t), t)\n"
                       "R = bezier(t, A, B, C, A)\noutput M, Q, R\n";
    Derived *d = derive_source("keep.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    assert_non_null(p);
    assert_null(p->collapse);
    Collapse *col = lower_collapse(p, d);
    assert_ptr_equal(col, p->collapse);
    assert_int_equal(col->n, 3);
    /* degrees 1, 2, 3 in t, all collapsed over [0, 1] */
    for (int o = 0; o < 3; o++) {
        assert_true(col->o[o].ok);
        assert_int_equal(col->o[o].deg, o + 1);
    }
    double r1 = col->o[2].a[col->o[2].nterms]; /* R's tau^1 coefficient */
    int sel[2] = {2, 0};                       /* R, then M; Q dropped */
    plan_keep_outputs(p, sel, 2);
    assert_ptr_equal(p->collapse, col);
    assert_int_equal(col->n, 2);
    assert_string_equal(col->o[0].name, "R");
    assert_string_equal(p->outputs[0].name, "R");
    assert_int_equal(col->o[0].deg, 3);
    assert_true(col->o[0].a[col->o[0].nterms] == r1);
    assert_string_equal(col->o[1].name, "M");
    assert_int_equal(col->o[1].deg, 1);
    plan_free(p); /* frees the collapsed forms too (valgrind checks) */
    derived_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_collapse_default_is_unchanged),
        cmocka_unit_test(test_collapse_follows_kept_outputs),
        cmocka_unit_test(test_collapse_bound_refuses),
        cmocka_unit_test(test_collapse_detects_a_broken_coefficient),
        cmocka_unit_test(test_collapse_high_degree),
        cmocka_unit_test(test_collapse_fast_path_blocks),
        cmocka_unit_test(test_collapse_examples_match_exact),
    };
    int rc = cmocka_run_group_tests(tests, NULL, teardown);
    fprintf(stderr, "test_collapse: %d value comparisons\n", total_checks);
    return rc;
}
