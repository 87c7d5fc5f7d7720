/*
 * test_lsq.c - runtime/lsq.c: Levenberg-Marquardt on problems with a
 * known optimum (a line and an exponential through exact data, Rosenbrock
 * as least squares, a non-zero-residual fit whose normal equations are
 * solved by hand, seeded random linear problems against their normal
 * equations), damped Newton on known systems, and the stop reasons
 * (singular Jacobian, iteration limit, a start outside the domain).
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

#include "runtime/lsq.h"

/* data y_i = a + b t_i (+ noise_i) at t_i = i, i = 0..m-1 */
typedef struct Data {
    size_t m;
    double t[64], y[64];
} Data;

static int line_fn(void *ctx, const double *u, double *r, double *J)
{
    const Data *d = ctx;
    for (size_t i = 0; i < d->m; i++) {
        r[i] = u[0] + u[1] * d->t[i] - d->y[i];
        if (J) {
            J[2 * i] = 1;
            J[2 * i + 1] = d->t[i];
        }
    }
    return 0;
}

static void test_lsq_line_exact_data(void **state)
{
    (void)state;
    Data d = {.m = 10};
    for (size_t i = 0; i < d.m; i++) {
        d.t[i] = (double)i;
        d.y[i] = 2.5 - 0.75 * d.t[i];
    }
    double u[2] = {0, 0};
    LsqResult r;
    assert_int_equal(lsq_solve(u, 2, d.m, line_fn, &d, NULL, &r), 0);
    assert_true(r.converged);
    assert_true(fabs(u[0] - 2.5) < 1e-12);
    assert_true(fabs(u[1] + 0.75) < 1e-12);
    assert_true(r.cost < 1e-24);
}

/* y = a exp(b t) through exact data, from a poor start */
static int exp_fn(void *ctx, const double *u, double *r, double *J)
{
    const Data *d = ctx;
    for (size_t i = 0; i < d->m; i++) {
        double e = exp(u[1] * d->t[i]);
        r[i] = u[0] * e - d->y[i];
        if (J) {
            J[2 * i] = e;
            J[2 * i + 1] = u[0] * d->t[i] * e;
        }
    }
    return 0;
}

static void test_lsq_exponential_exact_data(void **state)
{
    (void)state;
    Data d = {.m = 20};
    for (size_t i = 0; i < d.m; i++) {
        d.t[i] = 0.1 * (double)i;
        d.y[i] = 3 * exp(-1.3 * d.t[i]);
    }
    double u[2] = {1, 0};
    LsqResult r;
    assert_int_equal(lsq_solve(u, 2, d.m, exp_fn, &d, NULL, &r), 0);
    assert_true(fabs(u[0] - 3) < 1e-10);
    assert_true(fabs(u[1] + 1.3) < 1e-10);
}

/* Rosenbrock: r = (10 (y - x^2), 1 - x), minimum 0 at (1, 1) */
static int rosen_fn(void *ctx, const double *u, double *r, double *J)
{
    (void)ctx;
    r[0] = 10 * (u[1] - u[0] * u[0]);
    r[1] = 1 - u[0];
    if (J) {
        J[0] = -20 * u[0];
        J[1] = 10;
        J[2] = -1;
        J[3] = 0;
    }
    return 0;
}

static void test_lsq_rosenbrock(void **state)
{
    (void)state;
    double starts[3][2] = {{-1.2, 1}, {-3, -4}, {2, 5}};
    for (int s = 0; s < 3; s++) {
        double u[2] = {starts[s][0], starts[s][1]};
        LsqResult r;
        assert_int_equal(lsq_solve(u, 2, 2, rosen_fn, NULL, NULL, &r), 0);
        assert_true(fabs(u[0] - 1) < 1e-10);
        assert_true(fabs(u[1] - 1) < 1e-10);
        assert_true(r.iterations < 100);
    }
}

/* Geodesic acceleration (LsqOptions.geodesic): Rosenbrock from three
 * starts reaches (1, 1), in no more steps than without it from the
 * classic start (-1.2, 1), whose path follows the curved valley; on a
 * linear problem (r_vv = 0) it changes nothing but rounding: the exact
 * line in as many steps. */
static void test_lsq_geodesic(void **state)
{
    (void)state;
    double starts[3][2] = {{-1.2, 1}, {-3, -4}, {2, 5}};
    LsqOptions o;
    lsq_options_default(&o);
    o.geodesic = 1;
    int with = 0, without = 0;
    for (int s = 0; s < 3; s++) {
        double u[2] = {starts[s][0], starts[s][1]};
        LsqResult r;
        assert_int_equal(lsq_solve(u, 2, 2, rosen_fn, NULL, &o, &r), 0);
        assert_true(fabs(u[0] - 1) < 1e-10);
        assert_true(fabs(u[1] - 1) < 1e-10);
        if (s == 0) {
            double v[2] = {starts[0][0], starts[0][1]};
            LsqResult p;
            assert_int_equal(lsq_solve(v, 2, 2, rosen_fn, NULL, NULL, &p), 0);
            with = r.iterations;
            without = p.iterations;
        }
    }
    assert_true(with <= without);
    Data d = {.m = 10};
    for (size_t i = 0; i < d.m; i++) {
        d.t[i] = (double)i;
        d.y[i] = 2.5 - 0.75 * d.t[i];
    }
    double u[2] = {0, 0}, v[2] = {0, 0};
    LsqResult r, p;
    assert_int_equal(lsq_solve(u, 2, d.m, line_fn, &d, &o, &r), 0);
    assert_int_equal(lsq_solve(v, 2, d.m, line_fn, &d, NULL, &p), 0);
    assert_true(fabs(u[0] - 2.5) < 1e-12 && fabs(u[1] + 0.75) < 1e-12);
    assert_int_equal(r.iterations, p.iterations);
}

/* A non-zero residual optimum: the line through noisy data equals the
 * solution of the normal equations (computed here by Cramer's rule). */
static void test_lsq_line_noisy_matches_normal_equations(void **state)
{
    (void)state;
    Data d = {.m = 30};
    uint64_t s = 12345;
    double St = 0, Sy = 0, Stt = 0, Sty = 0;
    for (size_t i = 0; i < d.m; i++) {
        s = s * 6364136223846793005u + 1442695040888963407u;
        double noise = ((double)(s >> 11) * 0x1p-53 - 0.5) * 0.2;
        d.t[i] = (double)i / 7;
        d.y[i] = 1 + 2 * d.t[i] + noise;
        St += d.t[i];
        Sy += d.y[i];
        Stt += d.t[i] * d.t[i];
        Sty += d.t[i] * d.y[i];
    }
    double det = (double)d.m * Stt - St * St;
    double a = (Sy * Stt - St * Sty) / det,
           b = ((double)d.m * Sty - St * Sy) / det;
    double u[2] = {-5, 5};
    LsqResult r;
    assert_int_equal(lsq_solve(u, 2, d.m, line_fn, &d, NULL, &r), 0);
    assert_true(fabs(u[0] - a) < 1e-10);
    assert_true(fabs(u[1] - b) < 1e-10);
    assert_true(r.cost > 0);
}

/* seeded random overdetermined linear problems r = A u - b: LM's answer
 * has a zero gradient A^T (A u - b) (the optimality condition) */
typedef struct Lin {
    int m, n;
    double A[40 * 6], b[40];
} Lin;

static int lin_fn(void *ctx, const double *u, double *r, double *J)
{
    const Lin *l = ctx;
    for (int i = 0; i < l->m; i++) {
        double s = -l->b[i];
        for (int j = 0; j < l->n; j++)
            s += l->A[i * l->n + j] * u[j];
        r[i] = s;
    }
    if (J)
        memcpy(J, l->A, sizeof l->A[0] * (size_t)(l->m * l->n));
    return 0;
}

static void test_lsq_random_linear_gradient_vanishes(void **state)
{
    (void)state;
    uint64_t s = 99;
    for (int trial = 0; trial < 20; trial++) {
        Lin l = {.m = 10 + trial, .n = 1 + trial % 6};
        for (int k = 0; k < l.m * l.n + l.m; k++) {
            s = s * 6364136223846793005u + 1442695040888963407u;
            double v = (double)(s >> 11) * 0x1p-53 * 2 - 1;
            if (k < l.m * l.n)
                l.A[k] = v;
            else
                l.b[k - l.m * l.n] = v;
        }
        double u[6] = {0}, r[40];
        LsqResult res;
        assert_int_equal(lsq_solve(u, l.n, (size_t)l.m, lin_fn, &l, NULL, &res),
                         0);
        lin_fn(&l, u, r, NULL);
        for (int j = 0; j < l.n; j++) {
            double g = 0, col = 0;
            for (int i = 0; i < l.m; i++) {
                g += l.A[i * l.n + j] * r[i];
                col += fabs(l.A[i * l.n + j]);
            }
            assert_true(fabs(g) < 1e-9 * col);
        }
    }
}

/* Newton: x^2 + y^2 = 4, x y = 1 (a root near (1.93, 0.52)) */
static int circle_fn(void *ctx, const double *u, double *r, double *J)
{
    (void)ctx;
    r[0] = u[0] * u[0] + u[1] * u[1] - 4;
    r[1] = u[0] * u[1] - 1;
    if (J) {
        J[0] = 2 * u[0];
        J[1] = 2 * u[1];
        J[2] = u[1];
        J[3] = u[0];
    }
    return 0;
}

static void test_lsq_newton_known_system(void **state)
{
    (void)state;
    double u[2] = {2, 0.3};
    LsqResult r;
    assert_int_equal(lsq_newton(u, 2, circle_fn, NULL, NULL, &r), 0);
    /* x^2 = 2 + sqrt(3) */
    double x = sqrt(2 + sqrt(3));
    assert_true(fabs(u[0] - x) < 1e-12);
    assert_true(fabs(u[1] - 1 / x) < 1e-12);
    assert_true(r.iterations < 10);
}

/* Newton needs its damping: atan(x) = 0 from x = 3 (a full step
 * overshoots to -9.5, and then diverges) */
static int atan_fn(void *ctx, const double *u, double *r, double *J)
{
    (void)ctx;
    r[0] = atan(u[0]);
    if (J)
        J[0] = 1 / (1 + u[0] * u[0]);
    return 0;
}

static void test_lsq_newton_damped(void **state)
{
    (void)state;
    double u[1] = {3};
    LsqResult r;
    assert_int_equal(lsq_newton(u, 1, atan_fn, NULL, NULL, &r), 0);
    assert_true(fabs(u[0]) < 1e-12);
}

/* the stop reasons */
static int singular_fn(void *ctx, const double *u, double *r, double *J)
{
    (void)ctx;
    r[0] = u[0] + u[1] - 1;
    r[1] = 2 * (u[0] + u[1]) - 3; // inconsistent with r[0] = 0
    if (J) {
        J[0] = 1;
        J[1] = 1;
        J[2] = 2;
        J[3] = 2;
    }
    return 0;
}

static int domain_fn(void *ctx, const double *u, double *r, double *J)
{
    (void)ctx;
    if (u[0] < 0)
        return -1;
    r[0] = sqrt(u[0]) - 2;
    if (J)
        J[0] = 0.5 / sqrt(u[0]);
    return 0;
}

static void test_lsq_stop_reasons(void **state)
{
    (void)state;
    double u[2] = {0, 0};
    LsqResult r;
    assert_int_equal(lsq_newton(u, 2, singular_fn, NULL, NULL, &r), 1);
    assert_int_equal(r.stop, LSQ_STOP_SINGULAR);
    assert_false(r.converged);

    LsqOptions o;
    lsq_options_default(&o);
    o.max_iter = 3;
    double v[2] = {-1.2, 1};
    assert_int_equal(lsq_solve(v, 2, 2, rosen_fn, NULL, &o, &r), 1);
    assert_int_equal(r.stop, LSQ_STOP_MAXITER);
    assert_string_equal(lsq_stop_text(r.stop),
                        "the iteration limit was reached");

    double w[1] = {-1};
    assert_int_equal(lsq_solve(w, 1, 1, domain_fn, NULL, NULL, &r), 1);
    assert_int_equal(r.stop, LSQ_STOP_EVAL);
    /* a start inside the domain: steps beyond it are damped, not taken */
    w[0] = 0.01;
    assert_int_equal(lsq_solve(w, 1, 1, domain_fn, NULL, NULL, &r), 0);
    assert_true(fabs(w[0] - 4) < 1e-10);
    w[0] = 0.01;
    assert_int_equal(lsq_newton(w, 1, domain_fn, NULL, NULL, &r), 0);
    assert_true(fabs(w[0] - 4) < 1e-10);

    assert_int_equal(lsq_solve(w, 0, 1, domain_fn, NULL, NULL, &r), -1);
    assert_int_equal(
        lsq_solve(w, LSQ_MAX_UNKNOWNS + 1, 1, domain_fn, NULL, NULL, &r), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lsq_line_exact_data),
        cmocka_unit_test(test_lsq_exponential_exact_data),
        cmocka_unit_test(test_lsq_rosenbrock),
        cmocka_unit_test(test_lsq_geodesic),
        cmocka_unit_test(test_lsq_line_noisy_matches_normal_equations),
        cmocka_unit_test(test_lsq_random_linear_gradient_vanishes),
        cmocka_unit_test(test_lsq_newton_known_system),
        cmocka_unit_test(test_lsq_newton_damped),
        cmocka_unit_test(test_lsq_stop_reasons),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
