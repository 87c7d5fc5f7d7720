/*
 * test_numsolve.c - the numeric solve (`solve ... for a, b near ...`,
 * compiler/derive/solve_num.c, codegen/numsolve.c): systems with a known
 * root (a circle and a line, a point of a parabola at a given distance
 * from the origin, Kepler's equation, a point equation), a least-squares
 * system with its normal equations solved by hand, the exact Jacobian
 * against central differences of the residuals at several points, the
 * values flowing into later definitions, and a derivation without a
 * numeric back end.
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

#include "codegen/numsolve.h"
#include "compiler/derive.h"

/* the scheme text derived with the numeric back end given (fn) */
static Derived *derive_with(const char *text, DeriveNumericFn *fn, FILE *err)
{
    DeriveOptions opt = {.max_seconds = 60, .numeric = fn};
    return derive_source_ex("n.pcs", text, strlen(text), err, NULL, &opt);
}

/* the value of scalar output `name` of d, a number */
static double scalar_of(const Derived *d, const char *name)
{
    slong o = derived_find_output(d, name);
    assert_true(o >= 0);
    assert_int_equal(d->outputs[o].kind, KIND_SCALAR);
    fmpq_t q;
    fmpq_init(q);
    assert_true(ratfun_get_fmpq(q, d->outputs[o].scalar, &d->ring));
    double v = fmpq_get_d(q);
    fmpq_clear(q);
    return v;
}

/* within 2 ulps of want (the decimal of the double found reads back to
 * it; the root's double may differ by rounding) */
static void assert_close(double got, double want, double rel)
{
    if (!(fabs(got - want) <= rel * fabs(want) + 1e-300)) {
        print_error("got %.17g, want %.17g\n", got, want);
        fail();
    }
}

/* x^2 + y^2 = 1 and y = 2x - 1/2: x = (2 + sqrt(19))/10 from (1, 1), the
 * other root (2 - sqrt(19))/10 from (-1, -1) */
static void test_numsolve_circle_line(void **state)
{
    (void)state;
    static const char text[] =
        "unknown scalar x, y, u, v\n"
        "solve x^2 + y^2 = 1, y = 2*x - 1/2 for x, y near x = 1, y = 1\n"
        "solve u^2 + v^2 = 1, v = 2*u - 1/2 for u, v near u = -1, v = -1\n"
        "output x, y, u, v\n";
    Derived *d = derive_with(text, numsolve_run, stderr);
    assert_non_null(d);
    double s = sqrt(19.0);
    assert_close(scalar_of(d, "x"), (2 + s) / 10, 3e-16);
    assert_close(scalar_of(d, "y"), (2 + s) / 5 - 0.5, 3e-16);
    assert_close(scalar_of(d, "u"), (2 - s) / 10, 3e-16);
    assert_close(scalar_of(d, "v"), (2 - s) / 5 - 0.5, 3e-16);
    derived_free(d);
}

/* the point (t, t^2) of the parabola at distance 2 from the origin:
 * t^2 + t^4 = 4, t^2 = (sqrt(17) - 1)/2 (through sqrt: the chain rule);
 * then a later definition uses t */
static void test_numsolve_parabola_distance(void **state)
{
    (void)state;
    static const char text[] =
        "unknown scalar t\n"
        "solve sqrt(t^2 + (t^2)^2) = 2 for t near t = 1\n"
        "h = t^2\n"
        "output t, h\n";
    Derived *d = derive_with(text, numsolve_run, stderr);
    assert_non_null(d);
    double t = sqrt((sqrt(17.0) - 1) / 2);
    assert_close(scalar_of(d, "t"), t, 3e-16);
    assert_close(scalar_of(d, "h"), t * t, 6e-16);
    derived_free(d);
}

/* Kepler's equation E - e sin E = M (e = 1/2, M = 1), against a
 * bisection written here */
static void test_numsolve_kepler(void **state)
{
    (void)state;
    static const char text[] = "unknown scalar E\n"
                               "solve E - sin(E)/2 = 1 for E near E = 1\n"
                               "output E\n";
    Derived *d = derive_with(text, numsolve_run, stderr);
    assert_non_null(d);
    double lo = 0, hi = 3;
    for (int i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        if (mid - 0.5 * sin(mid) - 1 < 0)
            lo = mid;
        else
            hi = mid;
    }
    assert_close(scalar_of(d, "E"), lo, 3e-16);
    derived_free(d);
}

/* a point equation: along(A, B, k) = divide(A, B, 2) holds one equation
 * per weight (the last follows): k = 2/3, and P uses it */
static void test_numsolve_point_equation(void **state)
{
    (void)state;
    static const char text[] =
        "point A, B\n"
        "unknown scalar k\n"
        "solve along(A, B, k) = divide(A, B, 2) for k near k = 0\n"
        "output k\n";
    Derived *d = derive_with(text, numsolve_run, stderr);
    assert_non_null(d);
    assert_close(scalar_of(d, "k"), 2.0 / 3, 2e-16);
    derived_free(d);
}

/* more equations than unknowns: least squares.  a = 1, b = 2, a + b = 4:
 * the normal equations [2 1; 1 2] (a, b) = (5, 6) give a = 4/3, b = 7/3 */
static void test_numsolve_least_squares(void **state)
{
    (void)state;
    static const char text[] =
        "unknown scalar a, b\n"
        "solve a = 1, b = 2, a + b = 4 for a, b near a = 0, b = 0\n"
        "output a, b\n";
    Derived *d = derive_with(text, numsolve_run, stderr);
    assert_non_null(d);
    assert_close(scalar_of(d, "a"), 4.0 / 3, 3e-16);
    assert_close(scalar_of(d, "b"), 7.0 / 3, 3e-16);
    derived_free(d);
}

/* A back end that checks the exact Jacobian against central differences
 * of the residuals at the start and at two points around it, then
 * solves. */
static int checks; /* Jacobian entries compared */

static int check_then_solve(NumericSystem *s)
{
    NumEval *e = numsolve_prepare(s);
    assert_non_null(e);
    int m = s->m, n = s->n;
    double *r = malloc(sizeof(double) * (size_t)m * 2);
    double *J = malloc(sizeof(double) * (size_t)(m * n));
    double u[8], up[8];
    assert_true(n <= 8);
    for (int p = 0; p < 3; p++) {
        for (int j = 0; j < n; j++)
            u[j] = s->u[j] + 0.1 * p * (j % 2 ? -1 : 1);
        assert_int_equal(numsolve_eval(e, u, r, J), 0);
        for (int j = 0; j < n; j++) {
            double h = 1e-6 * (1 + fabs(u[j]));
            memcpy(up, u, sizeof(double) * (size_t)n);
            up[j] = u[j] + h;
            assert_int_equal(numsolve_eval(e, up, r, NULL), 0);
            memcpy(r + m, r, sizeof(double) * (size_t)m);
            up[j] = u[j] - h;
            assert_int_equal(numsolve_eval(e, up, r, NULL), 0);
            for (int i = 0; i < m; i++) {
                double fd = (r[m + i] - r[i]) / (2 * h);
                double ex = J[i * n + j];
                if (!(fabs(fd - ex) <= 1e-6 * (1 + fabs(ex)))) {
                    print_error("dr%d/du%d: exact %.17g, differences %.17g\n",
                                i, j, ex, fd);
                    fail();
                }
                checks++;
            }
        }
    }
    free(J);
    free(r);
    numsolve_free(e);
    return numsolve_run(s);
}

static void test_numsolve_jacobian_differences(void **state)
{
    (void)state;
    static const char text[] =
        "point A, B, C\n"
        "unknown scalar a, b, c\n"
        "solve sin(a)*b + exp(a*b) + atan(b) = 2, "
        "along(A, B, c*a) + (C - A)*sqrt(1 + b^2)/3 = "
        "A + (B - A)/2 + (C - A)*c for a, b, c near a = 1.4, b = 0.2, "
        "c = 0.35\n"
        "output a, b, c\n";
    checks = 0;
    Derived *d = derive_with(text, check_then_solve, stderr);
    assert_non_null(d);
    /* 3 points, 3 unknowns, 3 rows: the scalar equation, and the weights
     * of A and B in the point equation (that of C follows) */
    assert_int_equal(checks, 3 * 3 * 3);
    /* the values solve the equations */
    double a = scalar_of(d, "a"), b = scalar_of(d, "b"), c = scalar_of(d, "c");
    assert_true(fabs(sin(a) * b + exp(a * b) + atan(b) - 2) < 1e-14);
    assert_true(fabs(c * a - 0.5) < 1e-14);
    assert_true(fabs(sqrt(1 + b * b) / 3 - c) < 1e-14);
    derived_free(d);
}

/* without a back end (derive_source) a numeric solve is an error */
static void test_numsolve_needs_back_end(void **state)
{
    (void)state;
    static const char text[] = "unknown scalar k\n"
                               "solve k^2 = 2 for k near k = 1\n"
                               "output k\n";
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    Derived *d = derive_source("n.pcs", text, strlen(text), mem, NULL);
    fclose(mem);
    assert_null(d);
    assert_non_null(strstr(out, "n.pcs:2:1: error: a numeric solve needs a "
                                "numeric back end, and this program gave "
                                "none (DeriveOptions.numeric)"));
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_numsolve_circle_line),
        cmocka_unit_test(test_numsolve_parabola_distance),
        cmocka_unit_test(test_numsolve_kepler),
        cmocka_unit_test(test_numsolve_point_equation),
        cmocka_unit_test(test_numsolve_least_squares),
        cmocka_unit_test(test_numsolve_jacobian_differences),
        cmocka_unit_test(test_numsolve_needs_back_end),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
