/*
 * test_fit.c - `pointcalc fit` (driver/cli/fit.c, cmd_fit.c): the derived
 * curve's weights are the Lagrange basis, the residuals' exact Jacobian
 * agrees with central differences, and the chapter-5 results of the
 * monograph (docs/fit.md): Runge's function with 6 nodes at +-0.233198,
 * +-0.06054, MSE 2.84e-5, and the rows of table 5.1 and the examples of
 * 5.3 that reproduce (some only with m = 10 samples: docs/fit.md,
 * "Errata"); then the errors.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "base/mem.h"
#include "driver/cli/fit.h"

static const char runge[] = "1/(1 + 25*x^2)";

static Fit *new_fit(const char *target, double lo, double hi, int nodes,
                    int samples)
{
    FitOptions o = {
        .lo = lo, .hi = hi, .nodes = nodes, .samples = samples, .starts = 8};
    int rc;
    Fit *f = fit_new(target, &o, stderr, &rc);
    assert_non_null(f);
    assert_int_equal(rc, 0);
    return f;
}

/* phi_k(t_i) from the derived curve against the Lagrange basis on the
 * params j/(N-1); the exact coefficients against both */
static void test_fit_curve_is_lagrange_basis(void **state)
{
    (void)state;
    for (int n = 3; n <= 12; n++) {
        Fit *f = new_fit("x", -1, 1, n, 40);
        for (size_t i = 0; i < f->ns; i++) {
            double t = (double)i / (double)(f->ns - 1);
            for (int k = 0; k < n; k++) {
                double l = 1, p = 0, tj = 1, size = 0;
                for (int j = 0; j < n; j++)
                    if (j != k)
                        l *= (t - (double)j / (n - 1)) /
                             ((double)(k - j) / (n - 1));
                for (int j = 0; j < n; j++, tj *= t) {
                    p += f->coef[k * n + j] * tj;
                    size += fabs(f->coef[k * n + j]);
                }
                assert_true(fabs(f->phi[i * (size_t)n + k] - l) < 1e-13);
                /* the monomial form cancels: its rounding grows with the
                 * coefficients' size */
                assert_true(fabs(p - l) < 1e-15 * size + 1e-15);
            }
        }
        fit_free(f);
    }
}

/* the exact Jacobian (x and log-gap u) against central differences */
static void check_jacobian(const char *target, double lo, double hi, int n,
                           const double *x)
{
    Fit *f = new_fit(target, lo, hi, n, 100);
    int nu = f->nu;
    size_t ns = f->ns;
    double *r = pc_xmalloc(sizeof *r * ns),
           *J = pc_xmalloc(sizeof *J * ns * 64);
    double *rp = pc_xmalloc(sizeof *r * ns), *rm = pc_xmalloc(sizeof *r * ns);
    double xin[64], u[64], nodes[66];
    memcpy(xin, x, sizeof *x * (size_t)nu);
    for (int pass = 0; pass < 2; pass++) {
        double *v = pass == 0 ? xin : u;
        if (pass == 1) {
            nodes[0] = lo;
            memcpy(nodes + 1, x, sizeof *x * (size_t)nu);
            nodes[n - 1] = hi;
            fit_u_of_nodes(f, nodes, u);
            double back[66]; // and back: the log-gap map is one to one
            fit_nodes_of_u(f, u, back);
            for (int k = 0; k < n; k++)
                assert_true(fabs(back[k] - nodes[k]) < 1e-14 * (hi - lo));
        }
#define RES(w, out, jac)                                                       \
    (pass == 0 ? fit_residuals_x(f, w, out, jac)                               \
               : fit_residuals_u(f, w, out, jac))
        assert_int_equal(RES(v, r, J), 0);
        for (int j = 0; j < nu; j++) {
            double h = 1e-6 * (fabs(v[j]) > 1 ? fabs(v[j]) : 1), keep = v[j];
            v[j] = keep + h;
            assert_int_equal(RES(v, rp, NULL), 0);
            v[j] = keep - h;
            assert_int_equal(RES(v, rm, NULL), 0);
            v[j] = keep;
            double big = 0, err = 0;
            for (size_t i = 0; i < ns; i++) {
                double fd = (rp[i] - rm[i]) / (2 * h), ex = J[i * nu + j];
                big = fabs(ex) > big ? fabs(ex) : big;
                err = fabs(fd - ex) > err ? fabs(fd - ex) : err;
            }
            assert_true(big > 0);
            assert_true(err <= 1e-6 * big);
        }
#undef RES
    }
    free(r);
    free(J);
    free(rp);
    free(rm);
    fit_free(f);
}

static void test_fit_jacobian_matches_differences(void **state)
{
    (void)state;
    const double runge6[] = {-0.41, -0.07, 0.1, 0.52};
    const double sines7[] = {-0.3, -0.11, 0.02, 0.2, 0.33};
    const double ellipse4[] = {-1.7, 2.0};
    const double exp5[] = {0.3, 0.9, 1.4};
    check_jacobian(runge, -1, 1, 6, runge6);
    check_jacobian("sin(x) + sin(10*x)", -0.5, 0.5, 7, sines7);
    check_jacobian("sqrt(9 - 9*x^2/16)", -4, 4, 4, ellipse4);
    check_jacobian("exp(x)*cos(3*x)", 0, 2, 5, exp5);
}

typedef struct Expect {
    const char *target;
    double lo, hi;
    int nodes, samples;
    double mse; // the book's MSE (relative tolerance tol)
    double tol;
    double node[4]; // the book's inner nodes (the right half), 6 digits
    int nnode;
} Expect;

static void check_fit(const Expect *e)
{
    Fit *f = new_fit(e->target, e->lo, e->hi, e->nodes, e->samples);
    FitResult r;
    assert_int_equal(fit_run(f, &r), 0);
    if (fabs(r.mse - e->mse) > e->tol * e->mse)
        fprintf(stderr, "%s on [%g, %g], %d nodes: MSE %.6g, expected %.6g\n",
                e->target, e->lo, e->hi, e->nodes, r.mse, e->mse);
    assert_true(fabs(r.mse - e->mse) <= e->tol * e->mse);
    for (int k = 0; k < e->nnode; k++) {
        /* the inner nodes right of the middle, from the highest down */
        double got = r.nodes[e->nodes - 2 - k], want = e->node[k];
        assert_true(fabs(got - want) <
                    1e-6 * (fabs(want) > 1 ? fabs(want) : 1));
        /* and symmetric: the left one */
        assert_true(fabs(r.nodes[1 + k] + want) <
                    1e-6 * (fabs(want) > 1 ? fabs(want) : 1));
    }
    fit_result_clear(&r);
    fit_free(f);
}

/* monograph 5.2: 6 nodes, m = 100: x = +-0.233198, +-0.06054, MSE
 * 0.0000284 (to 6 digits: 0.0605405; the MSE is 2.83922e-5) */
static void test_fit_runge_6_nodes(void **state)
{
    (void)state;
    Expect e = {runge, -1, 1, 6, 100, 2.84e-5, 0.002, {0.233198, 0.0605405}, 2};
    check_fit(&e);
}

/* table 5.1 where it reproduces (7, 8 nodes; 5 nodes with m = 10) and
 * 5.2's [-2.5, 2.5], 5.3's examples 1 (with m = 10) and 2 */
static void test_fit_chapter5_table_and_examples(void **state)
{
    (void)state;
    const Expect e[] = {
        {runge, -1, 1, 7, 100, 5.14e-7, 0.002, {0}, 0},
        {runge, -1, 1, 8, 100, 1.01e-8, 0.005, {0}, 0},
        {runge, -1, 1, 5, 10, 0.000963, 0.001, {0}, 0},
        {runge, -2.5, 2.5, 6, 100, 0.0005587, 0.001, {0}, 0},
        {runge, -2.5, 2.5, 7, 100, 0.00001936, 0.001, {0}, 0},
        {"sqrt(9 - 9*x^2/16)", -4, 4, 4, 10, 0.00014577, 0.001, {1.877016}, 1},
        {"sin(x) + sin(10*x)",
         -0.5,
         0.5,
         6,
         100,
         2.47e-6,
         0.002,
         {0.265069, 0.084952},
         2},
    };
    for (size_t i = 0; i < sizeof e / sizeof e[0]; i++)
        check_fit(&e[i]);
}

/* where the book's optimiser stopped early: ours is far better */
static void test_fit_beats_table_5_1(void **state)
{
    (void)state;
    const int nodes[] = {9, 10, 11};
    const double book[] = {8.15e-10, 2.67e-8, 4e-9};
    for (int i = 0; i < 3; i++) {
        Fit *f = new_fit(runge, -1, 1, nodes[i], 100);
        FitResult r;
        assert_int_equal(fit_run(f, &r), 0);
        assert_true(r.mse < book[i] / 5);
        fit_result_clear(&r);
        fit_free(f);
    }
}

/* runs pointcalc fit ARGS; returns its exit status, out and err text */
static int run_fit(char **out, char **err, int argc, const char **argv)
{
    size_t no, ne;
    FILE *o = pc_xopen_memstream(out, &no), *e = pc_xopen_memstream(err, &ne);
    int rc = cli_fit(argc, (char **)argv, o, e);
    pc_xclose_memstream(o);
    pc_xclose_memstream(e);
    return rc;
}

#define RUN(...)                                                               \
    run_fit(&out, &err,                                                        \
            (int)(sizeof(const char *[]){__VA_ARGS__} / sizeof(const char *)), \
            (const char *[]){__VA_ARGS__})

static void test_fit_cli_json_and_text(void **state)
{
    (void)state;
    char *out, *err;
    int rc = RUN("fit", "--target", runge, "--on", "-1,1", "--nodes", "6",
                 "--format", "json");
    assert_int_equal(rc, 0);
    assert_string_equal(err, "");
    assert_non_null(strstr(out, "\"nodes\": [-1, -0.2331983"));
    assert_non_null(strstr(out, "\"mse\": 2.839"));
    assert_non_null(strstr(out, "\"iterations\": "));
    assert_non_null(strstr(out, "\"start\": "));
    free(out);
    free(err);
    rc = RUN("fit", "--target", runge, "--on", "-1,1", "--nodes", "6");
    assert_int_equal(rc, 0);
    assert_non_null(strstr(out, "MSE: 2.83922e-05\n"));
    /* the book's x(t) = -1 + 22.886t^5 - 57.215t^4 + 57.076t^3 - 28.398t^2
     * + 7.652t */
    assert_non_null(strstr(out, "x(t) = 22.886"));
    assert_non_null(strstr(out, " - 57.215"));
    assert_non_null(strstr(out, " + 57.075"));
    assert_non_null(strstr(out, " - 28.398"));
    assert_non_null(strstr(out, " + 7.6517"));
    assert_non_null(strstr(out, "*t - 1\ny(t) = "));
    free(out);
    free(err);
}

/* the scheme form: examples/fit_runge6.pcs gives the --target form's
 * 6-node Runge fit to 6 digits */
static void test_fit_scheme_runge6(void **state)
{
    (void)state;
    char *out, *err;
    int rc = RUN("fit", "examples/fit_runge6.pcs");
    assert_int_equal(rc, 0);
    assert_string_equal(err, "");
    assert_non_null(strstr(out, "fit X to f\n"));
    assert_non_null(strstr(out, "nodes: -1, -0.233198"));
    assert_non_null(strstr(out, ", -0.06054045"));
    assert_non_null(strstr(out, ", 0.06054045"));
    assert_non_null(strstr(out, ", 0.233198"));
    assert_non_null(strstr(out, "MSE: 2.83922e-05\n"));
    assert_non_null(strstr(out, "x(t) = 22.886"));
    free(out);
    free(err);
}

/* a CSV of Runge's function at 201 points: its natural spline as the
 * target gives the function's nodes to 1e-4; the spline is exact on a
 * line and interpolates its rows */
static void test_fit_data_spline(void **state)
{
    (void)state;
    char path[] = "/tmp/pc_fit_runge_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("x,y\n", f);
    for (int i = 0; i <= 200; i++) {
        double x = -1 + 2.0 * i / 200;
        fprintf(f, "%.17g,%.17g\n", x, 1 / (1 + 25 * x * x));
    }
    fclose(f);
    FitOptions o = {
        .lo = NAN, .hi = NAN, .nodes = 6, .samples = 100, .starts = 8};
    FitTarget t;
    double *phi, *coef;
    int rc;
    assert_int_equal(fit_target_data(&t, path, &o, stderr), 0);
    assert_true(o.lo == -1 && o.hi == 1);
    assert_int_equal(fit_lagrange_curve(6, 101, &phi, &coef, stderr), 0);
    Fit *fd_fit = fit_new_from(&o, &t, phi, coef, 1, stderr, &rc);
    assert_non_null(fd_fit);
    FitResult r, rf;
    assert_int_equal(fit_run(fd_fit, &r), 0);
    Fit *ff = new_fit(runge, -1, 1, 6, 100);
    assert_int_equal(fit_run(ff, &rf), 0);
    for (int k = 0; k < 6; k++)
        assert_true(fabs(r.nodes[k] - rf.nodes[k]) < 1e-4);
    assert_true(fabs(r.mse - rf.mse) < 1e-3 * rf.mse);
    fit_result_clear(&r);
    fit_result_clear(&rf);
    fit_free(ff);
    fit_free(fd_fit);
    /* an interval beyond the data is an error */
    o.lo = -2;
    FILE *quiet = fopen("/dev/null", "w");
    assert_int_equal(fit_target_data(&t, path, &o, quiet), -1);
    fclose(quiet);
    remove(path);
    FitSpline line = {4, (double[]){0, 1, 3, 4}, (double[]){1, 3, 7, 9},
                      (double[]){0, 0, 0, 0}};
    double xs[3] = {0.5, 2, 4}, v[3];
    unsigned char st[3];
    assert_int_equal(fit_spline_eval(&line, 0, 3, xs, v, st), 0);
    assert_true(fabs(v[0] - 2) < 1e-15 && fabs(v[1] - 5) < 1e-15 &&
                fabs(v[2] - 9) < 1e-15);
    assert_int_equal(fit_spline_eval(&line, 1, 3, xs, v, st), 0);
    assert_true(fabs(v[0] - 2) < 1e-15 && fabs(v[2] - 2) < 1e-15);
    xs[0] = 4.5;
    assert_int_equal(fit_spline_eval(&line, 0, 1, xs, v, st), 1);
}

/* the scheme form's errors: located at the fit statement */
static void test_fit_scheme_errors(void **state)
{
    (void)state;
    char path[] = "/tmp/pc_fit_scheme_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("point A, B, C\nparam t in [0, 1]\nX = bezier(t, A, B, C)\n"
          "param x\nf = sin(x)\nfit X to f on [0, 1]\n",
          f);
    fclose(f);
    char *out, *err;
    int rc = RUN("fit", path);
    assert_int_equal(rc, 1);
    assert_string_equal(out, "");
    assert_non_null(strstr(err, ":6:1: error: 'X' is not an interpolation "
                                "curve through its nodes: no t in [0, 1] "
                                "gives weight 1 to the base point B"));
    free(out);
    free(err);
    remove(path);
}

static void expect_error(int want_rc, const char *text, int argc,
                         const char **argv)
{
    char *out, *err;
    int rc = run_fit(&out, &err, argc, argv);
    if (rc != want_rc || !strstr(err, text))
        fprintf(stderr, "exit %d, err: %s", rc, err);
    assert_int_equal(rc, want_rc);
    assert_non_null(strstr(err, text));
    assert_string_equal(out, "");
    free(out);
    free(err);
}

#define ERR(rc, text, ...)                                                     \
    expect_error(                                                              \
        rc, text,                                                              \
        (int)(sizeof(const char *[]){__VA_ARGS__} / sizeof(const char *)),     \
        (const char *[]){__VA_ARGS__})

static void test_fit_errors(void **state)
{
    (void)state;
    ERR(1, "<target>:2:", "fit", "--target", "x + y", "--on", "0,1", "--nodes",
        "4");
    ERR(1, "'y'", "fit", "--target", "x + y", "--on", "0,1", "--nodes", "4");
    ERR(1,
        "the target 'sqrt(x)' is undefined at x = -1: a function's argument "
        "is outside its domain",
        "fit", "--target", "sqrt(x)", "--on", "-1,1", "--nodes", "4");
    ERR(1, "to x = -0.001", "fit", "--target", "sqrt(x)", "--on", "-1,1",
        "--nodes", "4");
    ERR(1, "undefined at x = 0: a denominator vanishes", "fit", "--target",
        "1/x", "--on", "-1,1", "--nodes", "4");
    ERR(2, "--nodes must be 3 ..", "fit", "--target", "x", "--on", "0,1",
        "--nodes", "2");
    ERR(2, "needs LO < HI", "fit", "--target", "x", "--on", "1,1", "--nodes",
        "4");
    ERR(2, "bad value '1;2' for --on", "fit", "--target", "x", "--on", "1;2",
        "--nodes", "4");
    ERR(2, "fit needs --nodes N", "fit", "--target", "x", "--on", "0,1");
    ERR(2, "unknown or incomplete option '--foo'", "fit", "--foo");
    ERR(2, "one expression in x", "fit", "--target", "x\noutput y", "--on",
        "0,1", "--nodes", "3");
    ERR(2, "bad value '0' for --max-iter", "fit", "--target", "x", "--on",
        "0,1", "--nodes", "3", "--max-iter", "0");
    ERR(2, "--samples must be 5 ..", "fit", "--target", "x", "--on", "0,1",
        "--nodes", "5", "--samples", "4");
    ERR(1,
        "pointcalc: fit: did not converge: the iteration limit was reached "
        "after 3 iterations (best start: ",
        "fit", "--target", runge, "--on", "-1,1", "--nodes", "11", "--max-iter",
        "3");
    ERR(2, "unknown format 'csv'", "fit", "--target", "x", "--on", "0,1",
        "--nodes", "3", "--format", "csv");
}

int main(void)
{
    mem_use_for_gmp_flint();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_curve_is_lagrange_basis),
        cmocka_unit_test(test_fit_jacobian_matches_differences),
        cmocka_unit_test(test_fit_runge_6_nodes),
        cmocka_unit_test(test_fit_chapter5_table_and_examples),
        cmocka_unit_test(test_fit_beats_table_5_1),
        cmocka_unit_test(test_fit_cli_json_and_text),
        cmocka_unit_test(test_fit_errors),
        cmocka_unit_test(test_fit_scheme_runge6),
        cmocka_unit_test(test_fit_data_spline),
        cmocka_unit_test(test_fit_scheme_errors),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
