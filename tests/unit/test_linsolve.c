/*
 * test_linsolve.c - Gaussian elimination over Q(t, u): random systems are
 * checked by substituting the answer back (A*x == b exactly), singular and
 * inconsistent systems by their result codes and ranks, and the shape meet()
 * produces - two unknowns, three rows, one of them redundant - by its known
 * solution.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <stdlib.h>

#include <flint/flint.h>

#include "compiler/algebra/linsolve.h"
#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"
#include "tests/unit/rand_algebra.h"

static int setup(void **state)
{
    return fixture_setup(state, 2);
}

static int teardown(void **state)
{
    return fixture_teardown(state);
}

static void parse(RatFun x, const char *s, const Ring *r)
{
    if (ratfun_set_str(x, s, r) != RATFUN_OK)
        fail_msg("cannot parse '%s'", s);
}

/* does a*x == b hold exactly (m x n system)? */
static int satisfies(const RatFunStruct *a, const RatFunStruct *x,
                     const RatFunStruct *b, slong m, slong n, const Ring *r)
{
    int ok = 1;
    RatFun s, t;
    ratfun_init(s, r);
    ratfun_init(t, r);
    for (slong i = 0; i < m && ok; i++) {
        ratfun_zero(s, r);
        for (slong j = 0; j < n; j++) {
            ratfun_mul(t, a + i * n + j, x + j, r);
            ratfun_add(s, s, t, r);
        }
        ok = ratfun_equal(s, b + i, r);
    }
    ratfun_clear(t, r);
    ratfun_clear(s, r);
    return ok;
}

/* a random n x n system with b = a*x0: a full-rank answer must be x0,
 * every answer must satisfy the system; a and b are left unmodified */
static void test_linsolve_random_square_exact(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    slong unique = 0, total = rand_iters(60);
    for (slong it = 0; it < total; it++) {
        slong n = 1 + (slong)n_randint(f->st, 4);
        RatFunStruct *a = ratfun_vec_init(n * n, r),
                     *a0 = ratfun_vec_init(n * n, r);
        RatFunStruct *b = ratfun_vec_init(n, r), *b0 = ratfun_vec_init(n, r);
        RatFunStruct *x0 = ratfun_vec_init(n, r), *x = ratfun_vec_init(n, r);
        RatFun t;
        slong rank = -1;
        ratfun_init(t, r);
        for (slong i = 0; i < n * n; i++) {
            rand_ratfun(a + i, f->st, r);
            ratfun_set(a0 + i, a + i, r);
        }
        for (slong j = 0; j < n; j++)
            rand_ratfun(x0 + j, f->st, r);
        for (slong i = 0; i < n; i++) {
            for (slong j = 0; j < n; j++) {
                ratfun_mul(t, a + i * n + j, x0 + j, r);
                ratfun_add(b + i, b + i, t, r);
            }
            ratfun_set(b0 + i, b + i, r);
        }
        LinSolveResult res = linsolve(x, &rank, a, b, n, n, r);
        assert_int_not_equal(res, LINSOLVE_INCONSISTENT);
        assert_true(rank >= 0 && rank <= n);
        assert_int_equal(res == LINSOLVE_UNIQUE, rank == n);
        for (slong j = 0; j < n; j++)
            assert_true(ratfun_is_canonical(x + j, r));
        assert_true(satisfies(a, x, b, n, n, r));
        if (res == LINSOLVE_UNIQUE) {
            unique++;
            for (slong j = 0; j < n; j++)
                assert_true(ratfun_equal(x + j, x0 + j, r));
        }
        for (slong i = 0; i < n * n; i++)
            assert_true(ratfun_equal(a + i, a0 + i, r));
        for (slong i = 0; i < n; i++)
            assert_true(ratfun_equal(b + i, b0 + i, r));
        ratfun_clear(t, r);
        ratfun_vec_clear(x, n, r);
        ratfun_vec_clear(x0, n, r);
        ratfun_vec_clear(b0, n, r);
        ratfun_vec_clear(b, n, r);
        ratfun_vec_clear(a0, n * n, r);
        ratfun_vec_clear(a, n * n, r);
    }
    /* random matrices are almost always regular */
    assert_true(unique >= total / 2);
}

/* more equations than unknowns, consistent by construction */
static void test_linsolve_overdetermined_consistent(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    slong inconsistent = 0, total = rand_iters(30);
    for (slong it = 0; it < total; it++) {
        slong n = 1 + (slong)n_randint(f->st, 3);
        slong m = n + 1 + (slong)n_randint(f->st, 2);
        RatFunStruct *a = ratfun_vec_init(m * n, r), *b = ratfun_vec_init(m, r);
        RatFunStruct *x0 = ratfun_vec_init(n, r), *x = ratfun_vec_init(n, r);
        RatFun t;
        slong rank;
        ratfun_init(t, r);
        for (slong i = 0; i < m * n; i++)
            rand_ratfun(a + i, f->st, r);
        for (slong j = 0; j < n; j++)
            rand_ratfun(x0 + j, f->st, r);
        for (slong i = 0; i < m; i++)
            for (slong j = 0; j < n; j++) {
                ratfun_mul(t, a + i * n + j, x0 + j, r);
                ratfun_add(b + i, b + i, t, r);
            }
        LinSolveResult res = linsolve(x, &rank, a, b, m, n, r);
        assert_int_not_equal(res, LINSOLVE_INCONSISTENT);
        assert_true(rank <= n);
        assert_true(satisfies(a, x, b, m, n, r));
        /* perturb one right-hand side: usually impossible now (not when
         * e_m lies in the column space, e.g. a = [0; u]); either way a
         * claimed solution must be one */
        ratfun_gen(t, 0, r);
        ratfun_add(b + m - 1, b + m - 1, t, r);
        res = linsolve(x, &rank, a, b, m, n, r);
        if (res == LINSOLVE_INCONSISTENT)
            inconsistent++;
        else
            assert_true(satisfies(a, x, b, m, n, r));
        ratfun_clear(t, r);
        ratfun_vec_clear(x, n, r);
        ratfun_vec_clear(x0, n, r);
        ratfun_vec_clear(b, m, r);
        ratfun_vec_clear(a, m * n, r);
    }
    assert_true(inconsistent >= total / 2);
}

/* row 2 = (t+1) * row 1: rank 1; consistent b gives a solution with the
 * free unknown at 0, inconsistent b leaves x untouched */
static void test_linsolve_singular_and_inconsistent(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFunStruct *a = ratfun_vec_init(4, r), *b = ratfun_vec_init(2, r),
                 *x = ratfun_vec_init(2, r);
    slong rank = -1;
    RatFun e;
    ratfun_init(e, r);
    parse(a + 0, "t", r);
    parse(a + 1, "u/(t-1)", r);
    parse(a + 2, "t*(t+1)", r);
    parse(a + 3, "u*(t+1)/(t-1)", r);
    parse(b + 0, "u", r);
    parse(b + 1, "u*(t+1)", r);
    assert_int_equal(linsolve(x, &rank, a, b, 2, 2, r),
                     LINSOLVE_UNDERDETERMINED);
    assert_int_equal(rank, 1);
    assert_true(satisfies(a, x, b, 2, 2, r));
    assert_true(ratfun_is_zero(x + 0, r) || ratfun_is_zero(x + 1, r));

    parse(x + 0, "17", r);
    parse(x + 1, "19", r);
    parse(b + 1, "u*(t+2)", r);
    assert_int_equal(linsolve(x, &rank, a, b, 2, 2, r), LINSOLVE_INCONSISTENT);
    assert_int_equal(rank, 1);
    parse(e, "17", r);
    assert_true(ratfun_equal(x + 0, e, r));
    parse(e, "19", r);
    assert_true(ratfun_equal(x + 1, e, r));

    /* the zero matrix: rank 0, consistent only with b = 0 */
    for (int i = 0; i < 4; i++)
        ratfun_zero(a + i, r);
    assert_int_equal(linsolve(x, &rank, a, b, 2, 2, r), LINSOLVE_INCONSISTENT);
    assert_int_equal(rank, 0);
    ratfun_zero(b + 0, r);
    ratfun_zero(b + 1, r);
    assert_int_equal(linsolve(x, NULL, a, b, 2, 2, r),
                     LINSOLVE_UNDERDETERMINED);
    assert_true(ratfun_is_zero(x + 0, r) && ratfun_is_zero(x + 1, r));
    ratfun_clear(e, r);
    ratfun_vec_clear(x, 2, r);
    ratfun_vec_clear(b, 2, r);
    ratfun_vec_clear(a, 4, r);
}

/* a zero in the top-left corner needs a pivot elsewhere */
static void test_linsolve_pivot_off_diagonal(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFunStruct *a = ratfun_vec_init(4, r), *b = ratfun_vec_init(2, r),
                 *x = ratfun_vec_init(2, r);
    RatFun e;
    slong rank;
    ratfun_init(e, r);
    parse(a + 1, "t^2+u", r); /* a = [[0, t^2+u], [2, 1/t]] */
    parse(a + 2, "2", r);
    parse(a + 3, "1/t", r);
    parse(b + 0, "1", r);
    parse(b + 1, "0", r);
    assert_int_equal(linsolve(x, &rank, a, b, 2, 2, r), LINSOLVE_UNIQUE);
    assert_int_equal(rank, 2);
    parse(e, "-1/(2*t*(t^2+u))", r);
    assert_true(ratfun_equal(x + 0, e, r));
    parse(e, "1/(t^2+u)", r);
    assert_true(ratfun_equal(x + 1, e, r));
    ratfun_clear(e, r);
    ratfun_vec_clear(x, 2, r);
    ratfun_vec_clear(b, 2, r);
    ratfun_vec_clear(a, 4, r);
}

/* Line AB meets line CD, simplex P0 P1 P2:  A = P0, B = P1, C = P2,
 * D = (P0 + t*P1 + P2)/(2 + t).  Unknowns l, m in
 *   A + (B - A)*l = C + (D - C)*m   <=>   (B - A)*l + (C - D)*m = C - A,
 * one row per base point (the way meet() builds it); the rows sum to zero
 * (vectors), so one is redundant.  l = t/(1+t), m = (2+t)/(1+t). */
static void test_linsolve_line_intersection_redundant_row(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq A, B, C, D, c1, c2, rhs, M1, M2;
    RatFunStruct *a = ratfun_vec_init(6, r), *b = ratfun_vec_init(3, r),
                 *x = ratfun_vec_init(2, r);
    RatFun w, e;
    slong rank;
    pteq_init(A, r);
    pteq_init(B, r);
    pteq_init(C, r);
    pteq_init(D, r);
    pteq_init(c1, r);
    pteq_init(c2, r);
    pteq_init(rhs, r);
    pteq_init(M1, r);
    pteq_init(M2, r);
    ratfun_init(w, r);
    ratfun_init(e, r);
    pteq_set_point(A, 0, r);
    pteq_set_point(B, 1, r);
    pteq_set_point(C, 2, r);
    parse(w, "1/(2+t)", r);
    pteq_set_weight(D, 0, w, r);
    pteq_set_weight(D, 2, w, r);
    parse(w, "t/(2+t)", r);
    pteq_set_weight(D, 1, w, r);
    pteq_sub(c1, B, A, r);
    pteq_sub(c2, C, D, r);
    pteq_sub(rhs, C, A, r);
    for (slong i = 0; i < 3; i++) {
        pteq_get_weight(a + 2 * i + 0, c1, i, r);
        pteq_get_weight(a + 2 * i + 1, c2, i, r);
        pteq_get_weight(b + i, rhs, i, r);
    }
    assert_int_equal(linsolve(x, &rank, a, b, 3, 2, r), LINSOLVE_UNIQUE);
    assert_int_equal(rank, 2);
    parse(e, "t/(1+t)", r);
    assert_true(ratfun_equal(x + 0, e, r));
    parse(e, "(2+t)/(1+t)", r);
    assert_true(ratfun_equal(x + 1, e, r));
    /* both parametrisations give the same point, with weights summing to 1 */
    pteq_addmul(M1, A, c1, x + 0, r);
    pteq_sub(c2, D, C, r);
    pteq_addmul(M2, C, c2, x + 1, r);
    assert_true(pteq_equal(M1, M2, r));
    pteq_weight_sum(w, M1, r);
    assert_true(ratfun_is_one(w, r));
    ratfun_clear(e, r);
    ratfun_clear(w, r);
    pteq_clear(M2, r);
    pteq_clear(M1, r);
    pteq_clear(rhs, r);
    pteq_clear(c2, r);
    pteq_clear(c1, r);
    pteq_clear(D, r);
    pteq_clear(C, r);
    pteq_clear(B, r);
    pteq_clear(A, r);
    ratfun_vec_clear(x, 2, r);
    ratfun_vec_clear(b, 3, r);
    ratfun_vec_clear(a, 6, r);
}

/* parallel lines: the same system shape without a solution */
static void test_linsolve_parallel_lines_inconsistent(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    /* A = P0, B = P1, C = P2, D = C + (B - A): (B-A)l + (C-D)m = C - A */
    RatFunStruct *a = ratfun_vec_init(6, r), *b = ratfun_vec_init(3, r),
                 *x = ratfun_vec_init(2, r);
    slong rank;
    static const char *const A[6] = {"-1", "1", "1", "-1", "0", "0"};
    static const char *const B[3] = {"-1", "0", "1"};
    for (int i = 0; i < 6; i++)
        parse(a + i, A[i], r);
    for (int i = 0; i < 3; i++)
        parse(b + i, B[i], r);
    assert_int_equal(linsolve(x, &rank, a, b, 3, 2, r), LINSOLVE_INCONSISTENT);
    assert_int_equal(rank, 1);
    ratfun_vec_clear(x, 2, r);
    ratfun_vec_clear(b, 3, r);
    ratfun_vec_clear(a, 6, r);
}

/* degenerate sizes: no equations, no unknowns */
static void test_linsolve_empty_sizes(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFunStruct *x = ratfun_vec_init(2, r), *b = ratfun_vec_init(1, r);
    slong rank = -1;
    parse(x + 0, "5", r);
    assert_int_equal(linsolve(x, &rank, NULL, NULL, 0, 2, r),
                     LINSOLVE_UNDERDETERMINED);
    assert_int_equal(rank, 0);
    assert_true(ratfun_is_zero(x + 0, r));
    assert_int_equal(linsolve(x, &rank, NULL, b, 1, 0, r), LINSOLVE_UNIQUE);
    parse(b + 0, "t", r);
    assert_int_equal(linsolve(x, &rank, NULL, b, 1, 0, r),
                     LINSOLVE_INCONSISTENT);
    ratfun_vec_clear(b, 1, r);
    ratfun_vec_clear(x, 2, r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linsolve_random_square_exact),
        cmocka_unit_test(test_linsolve_overdetermined_consistent),
        cmocka_unit_test(test_linsolve_singular_and_inconsistent),
        cmocka_unit_test(test_linsolve_pivot_off_diagonal),
        cmocka_unit_test(test_linsolve_line_intersection_redundant_row),
        cmocka_unit_test(test_linsolve_parallel_lines_inconsistent),
        cmocka_unit_test(test_linsolve_empty_sizes),
    };
    int fails = cmocka_run_group_tests(tests, setup, teardown);
    flint_cleanup_master();
    return fails;
}
