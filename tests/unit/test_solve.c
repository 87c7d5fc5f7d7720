/*
 * test_solve.c - linear point systems (compiler/algebra/solve.c) and the family
 * schemes built on them.
 *
 *  - Random systems with a known answer: unknowns X_j, true values T_j
 *    (random points over the base points), equations
 *    sum_j U[e][j] * (X_j - T_j) = 0 with a random U.  solve_points must
 *    return exactly T, on the numeric path (U numbers) and on the
 *    fraction-free one (U rational functions, or U numbers times a common
 *    symbolic factor, which forces the general path on a numeric answer).
 *  - Singular and inconsistent systems: the status, the undetermined
 *    unknowns and the dependent equations.
 *  - The order-n interpolation scheme (monograph 4.8) for n = 1..12, 24 and
 *    48: the weights of its curve equal the Lagrange basis polynomials
 *    prod_{j != i} (t - t_j)/(t_i - t_j) built here by hand (a polynomial
 *    of degree n through n+1 nodes is unique), and each solved control
 *    point is a point.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "compiler/algebra/linsolve.h"
#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"
#include "compiler/algebra/solve.h"
#include "compiler/derive.h"
#include "tests/unit/rand_algebra.h"

static int setup(void **state)
{
    return fixture_setup(state, 2);
}

static int teardown(void **state)
{
    return fixture_teardown(state);
}

enum { NBASE = 5, UCOL = 10 }; /* base points 0..4, unknowns 10.. */

/* U[e][j] for a k x k system: numbers (kind 0), rational functions (1),
 * or numbers times the common factor (1 + t*u) (2) */
static void rand_matrix(RatFunStruct *U, slong k, int kind, flint_rand_t st,
                        const Ring *r)
{
    RatFun f;
    ratfun_init(f, r);
    ratfun_set_str(f, "1 + t*u", r);
    for (slong i = 0; i < k * k; i++) {
        if (kind == 1) {
            rand_ratfun(U + i, st, r);
        } else {
            fmpq_t q;
            fmpq_init(q);
            rand_fmpq(q, st);
            ratfun_set_fmpq(U + i, q, r);
            fmpq_clear(q);
            if (kind == 2)
                ratfun_mul(U + i, U + i, f, r);
        }
    }
    ratfun_clear(f, r);
}

/* eqs[e] = sum_j U[e][j] * (X_j - T_j) */
static void build_equations(PointEq *eqs, const RatFunStruct *U,
                            const PointEq *T, slong k, const Ring *r)
{
    PointEq d;
    pteq_init(d, r);
    for (slong e = 0; e < k; e++) {
        pteq_zero(eqs[e], r);
        for (slong j = 0; j < k; j++) {
            pteq_set_point(d, UCOL + j, r);
            pteq_sub(d, d, T[j], r);
            pteq_addmul(eqs[e], eqs[e], d, U + e * k + j, r);
        }
    }
    pteq_clear(d, r);
}

static void test_solve_random_systems(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    slong solved = 0, singular = 0;
    for (slong it = 0; it < rand_iters(150); it++) {
        slong k = 1 + (slong)n_randint(f->st, 4);
        int kind = (int)(it % 3);
        RatFunStruct U[16];
        PointEq T[4], X[4], eqs[4];
        slong cols[4];
        char und[4], dep[4];
        for (slong i = 0; i < k * k; i++)
            ratfun_init(U + i, r);
        for (slong j = 0; j < k; j++) {
            pteq_init(T[j], r);
            pteq_init(X[j], r);
            pteq_init(eqs[j], r);
            cols[j] = UCOL + j;
            rand_comb(T[j], f->st, 0, NBASE, 1, r);
        }
        rand_matrix(U, k, kind, f->st, r);
        build_equations(eqs, U, (const PointEq *)T, k, r);
        SolveStatus s =
            solve_points(X, (const PointEq *)eqs, k, cols, k, und, dep, r);
        /* U may be singular by chance (randtest draws 0 often): the rank
         * that linsolve finds for U decides what the status must be */
        RatFunStruct b[4], x[4];
        slong rank = 0;
        for (slong j = 0; j < k; j++) {
            ratfun_init(b + j, r);
            ratfun_init(x + j, r);
        }
        linsolve(x, &rank, U, b, k, k, r);
        for (slong j = 0; j < k; j++) {
            ratfun_clear(b + j, r);
            ratfun_clear(x + j, r);
        }
        assert_int_equal(s == SOLVE_OK, rank == k);
        if (s == SOLVE_OK) {
            solved++;
            for (slong j = 0; j < k; j++) {
                assert_true(pteq_is_canonical(X[j], r));
                assert_true(pteq_equal(X[j], T[j], r));
            }
        } else {
            singular++;
            assert_int_equal(s, SOLVE_SINGULAR);
        }
        for (slong j = 0; j < k; j++) {
            pteq_clear(eqs[j], r);
            pteq_clear(X[j], r);
            pteq_clear(T[j], r);
        }
        for (slong i = 0; i < k * k; i++)
            ratfun_clear(U + i, r);
    }
    assert_true(solved > singular);
}

/* X + Y = 2A, X - Y = B - C, 2X = 2A + B - C: the third equation is the
 * sum of the first two (singular as an exact system of 3 for 3 with a
 * free Z), or contradicts them when it says 2X = 2A + B - D */
static void test_solve_singular_and_inconsistent(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    const char *rhs3[2] = {"C", "D"};
    for (int c = 0; c < 2; c++) {
        PointEq eqs[3], X[3], p;
        slong cols[3] = {UCOL, UCOL + 1, UCOL + 2};
        char und[3], dep[3];
        RatFun two, one;
        ratfun_init(two, r);
        ratfun_init(one, r);
        ratfun_set_si(two, 2, r);
        ratfun_set_si(one, -1, r);
        pteq_init(p, r);
        for (int i = 0; i < 3; i++) {
            pteq_init(eqs[i], r);
            pteq_init(X[i], r);
        }
        /* e0 = X + Y - 2A */
        pteq_set_point(eqs[0], UCOL, r);
        pteq_set_point(p, UCOL + 1, r);
        pteq_add(eqs[0], eqs[0], p, r);
        pteq_set_point(p, 0, r);
        pteq_addmul(eqs[0], eqs[0], p, one, r);
        pteq_addmul(eqs[0], eqs[0], p, one, r);
        /* e1 = X - Y - B + C */
        pteq_set_point(eqs[1], UCOL, r);
        pteq_set_point(p, UCOL + 1, r);
        pteq_sub(eqs[1], eqs[1], p, r);
        pteq_set_point(p, 1, r);
        pteq_sub(eqs[1], eqs[1], p, r);
        pteq_set_point(p, 2, r);
        pteq_add(eqs[1], eqs[1], p, r);
        /* e2 = 2X - 2A - B + C (or + D): Z appears nowhere */
        pteq_set_point(p, UCOL, r);
        pteq_scalar_mul(eqs[2], p, two, r);
        pteq_set_point(p, 0, r);
        pteq_addmul(eqs[2], eqs[2], p, one, r);
        pteq_addmul(eqs[2], eqs[2], p, one, r);
        pteq_set_point(p, 1, r);
        pteq_sub(eqs[2], eqs[2], p, r);
        pteq_set_point(p, strcmp(rhs3[c], "C") == 0 ? 2 : 3, r);
        pteq_add(eqs[2], eqs[2], p, r);

        SolveStatus s =
            solve_points(X, (const PointEq *)eqs, 3, cols, 3, und, dep, r);
        if (c == 0) {
            assert_int_equal(s, SOLVE_SINGULAR);
            assert_int_equal(und[0] + und[1] + und[2], 1);
            assert_int_equal(und[2], 1); /* Z is in no equation */
            assert_int_equal(dep[0] + dep[1] + dep[2], 1);
        } else {
            assert_int_equal(s, SOLVE_INCONSISTENT);
            assert_int_equal(dep[0] + dep[1] + dep[2], 1);
        }
        /* and without Z, 3 equations for X, Y: over-determined but
         * consistent in case 0 */
        s = solve_points(X, (const PointEq *)eqs, 3, cols, 2, und, dep, r);
        assert_int_equal(s, c == 0 ? SOLVE_OK : SOLVE_INCONSISTENT);
        if (c == 0) {
            /* X = A + (B - C)/2 */
            RatFun w;
            ratfun_init(w, r);
            pteq_get_weight(w, X[0], 0, r);
            assert_true(ratfun_is_one(w, r));
            pteq_get_weight(w, X[0], 1, r);
            RatFun half;
            ratfun_init(half, r);
            ratfun_set_str(half, "1/2", r);
            assert_true(ratfun_equal(w, half, r));
            ratfun_clear(half, r);
            ratfun_clear(w, r);
        }
        for (int i = 0; i < 3; i++) {
            pteq_clear(X[i], r);
            pteq_clear(eqs[i], r);
        }
        pteq_clear(p, r);
        ratfun_clear(one, r);
        ratfun_clear(two, r);
    }
}

static const char FAMILY[] =
    "int n = 3\n"
    "point M[1..n+1]\n"
    "param t in [0, 1]\n"
    "unknown C[2..n]\n"
    "X = bezier(t, M[1], C[2..n], M[n+1])\n"
    "solve subst(X, t, (i-1)/n) = M[i] for i in 2..n for C[2..n]\n"
    "output X, C[2..n]\n";

/* the Lagrange basis polynomial of node i (0-based) of nodes k/n */
static void lagrange(RatFun res, slong i, slong n, const Ring *r)
{
    RatFun f;
    ratfun_init(f, r);
    ratfun_one(res, r);
    for (slong j = 0; j <= n; j++) {
        if (j == i)
            continue;
        char buf[96];
        /* (t - j/n) / (i/n - j/n) = (n t - j) / (i - j) */
        snprintf(buf, sizeof buf, "(%ld*t - %ld)/(%ld)", (long)n, (long)j,
                 (long)(i - j));
        assert_int_equal(ratfun_set_str(f, buf, r), 0);
        ratfun_mul(res, res, f, r);
    }
    ratfun_clear(f, r);
}

static void test_family_interpolation_is_lagrange(void **state)
{
    (void)state;
    const slong orders[] = {1, 2, 3, 4, 5, 6, 8, 12, 24, 48};
    for (size_t o = 0; o < sizeof orders / sizeof orders[0]; o++) {
        slong n = orders[o];
        char def[32];
        const char *defs[1] = {def};
        snprintf(def, sizeof def, "n=%ld", (long)n);
        DeriveOptions opt = {.max_seconds = 60, .defines = defs, .ndefines = 1};
        int nerr = 0;
        Derived *d = derive_source_ex("family.pcs", FAMILY, strlen(FAMILY),
                                      stderr, &nerr, &opt);
        assert_non_null(d);
        assert_int_equal(d->npoints, n + 1);
        assert_int_equal(d->noutputs, n); /* X and C_2..C_n */
        const DerivedOutput *x = &d->outputs[0];
        assert_int_equal(x->kind, KIND_POINT);
        assert_int_equal(x->eq->len, n + 1);
        RatFun l;
        ratfun_init(l, &d->ring);
        for (slong i = 0; i <= n; i++) {
            char name[32];
            snprintf(name, sizeof name, "M_%ld", (long)i + 1);
            assert_string_equal(d->points[i], name);
            lagrange(l, i, n, &d->ring);
            assert_int_equal(x->eq->terms[i].point, i);
            assert_true(ratfun_equal(x->w + i, l, &d->ring));
        }
        for (slong k = 1; k < d->noutputs; k++) {
            char name[32];
            snprintf(name, sizeof name, "C_%ld", (long)k + 1);
            assert_string_equal(d->outputs[k].name, name);
            assert_int_equal(d->outputs[k].kind, KIND_POINT);
        }
        ratfun_clear(l, &d->ring);
        derived_free(d);
    }
}

/* the contour arcs of 3.6 for k = 2..5 against the printed M2..M5:
 * weights tb^(k+1)/den_k of A and t^(k+1)/den_k of B */
static void test_contour_arcs_match_the_book(void **state)
{
    (void)state;
    static const char *const den[] = {"1 - (1-t)*t", "1 - 2*(1-t)*t",
                                      "1 - 3*(1-t)*t + (1-t)^2*t^2",
                                      "1 - 4*(1-t)*t + 3*(1-t)^2*t^2"};
    for (int k = 2; k <= 5; k++) {
        char def[16], wa[128], wb[128];
        const char *defs[1] = {def};
        snprintf(def, sizeof def, "k=%d", k);
        snprintf(wa, sizeof wa, "(1-t)^%d/(%s)", k + 1, den[k - 2]);
        snprintf(wb, sizeof wb, "t^%d/(%s)", k + 1, den[k - 2]);
        DeriveOptions opt = {.max_seconds = 60, .defines = defs, .ndefines = 1};
        Derived *d =
            derive_file_ex("examples/contour_arcs.pcs", stderr, NULL, &opt);
        assert_non_null(d);
        const DerivedOutput *m = &d->outputs[0];
        assert_int_equal(m->eq->len, 3);
        RatFun e;
        ratfun_init(e, &d->ring);
        assert_int_equal(ratfun_set_str(e, wa, &d->ring), 0);
        assert_true(ratfun_equal(m->w + 0, e, &d->ring)); /* A */
        assert_int_equal(ratfun_set_str(e, wb, &d->ring), 0);
        assert_true(ratfun_equal(m->w + 1, e, &d->ring)); /* B */
        ratfun_clear(e, &d->ring);
        derived_free(d);
    }
}

/* a symbolic system that takes long stops at the library's own time
 * budget (no signal: derive_source_ex), located at the solve, and one
 * with too many unknowns is refused before any work */
static void test_solve_budgets(void **state)
{
    (void)state;
    static const char slow[] =
        "point A, B\nparam t\nunknown X[1..30]\n"
        "solve bezier(t + i, X[1..30]) = along(A, B, i) for i in 1..30 "
        "for X[1..30]\nM = X[1]\n";
    static const char big[] =
        "point A, B\nunknown X[1..2001]\n"
        "solve X[i] = along(A, B, 1/2) for i in 1..2001 for X[1..2001]\n"
        "M = X[1]\n";
    char *out = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&out, &n);
    DeriveOptions opt = {.max_seconds = 0.2};
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    Derived *d =
        derive_source_ex("slow.pcs", slow, sizeof slow - 1, mem, NULL, &opt);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double secs = (double)(t1.tv_sec - t0.tv_sec) +
                  1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    assert_null(d);
    opt.max_seconds = 60;
    d = derive_source_ex("big.pcs", big, sizeof big - 1, mem, NULL, &opt);
    assert_null(d);
    fclose(mem);
    /* at the solve (line 4), or at an expression of its equations when
     * the budget runs out before the elimination (valgrind) */
    assert_non_null(strstr(out, "slow.pcs:4:"));
    assert_non_null(strstr(out, ": error: the time budget of 0.2 s ran out "
                                "while deriving this"));
    assert_non_null(strstr(out, "big.pcs:3:1: error: system too large to "
                                "solve: 2001 unknowns (at most 2000)"));
    /* the budget is checked between rows: well within a second of it */
    assert_true(secs < 5.0);
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_solve_random_systems, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_solve_singular_and_inconsistent,
                                        setup, teardown),
        cmocka_unit_test(test_family_interpolation_is_lagrange),
        cmocka_unit_test(test_contour_arcs_match_the_book),
        cmocka_unit_test(test_solve_budgets),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
