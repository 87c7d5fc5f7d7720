/*
 * test_meet.c - meet() two ways: construct_meet (the fraction-free form:
 * maximal minors of the homogeneous columns, unit columns eliminated, one
 * content reduction) against construct_meet_general (Gaussian elimination
 * over the fraction field, the original solver), on seeded random flats:
 * lines in a plane of three base points, in a plane spanned by random
 * points over five base points (rows beyond the minors are then checked),
 * a line and a plane in 3-space, skew lines, and the degenerate cases;
 * flats whose points are made from one random point X (along(X, Q, r)),
 * where the fast path reduces a flat's points against each other (with the
 * threshold of that reduction at 0 so that small flats take it too, and at
 * its default on a chain of meets in 3-space whose entries exceed it).
 * Both must agree on the status and, when they meet, on the canonical
 * point equation; every result is also checked to lie on both flats.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <stdlib.h>

#include <flint/flint.h>

#include "compiler/algebra/construct.h"
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

/* a random generator over lo..hi-1: a base point, a point or a direction */
static void rand_gen(PointEq x, flint_rand_t st, slong lo, slong hi,
                     int may_be_direction, const Ring *r)
{
    ulong kind = n_randint(st, may_be_direction ? 4 : 3);
    if (kind == 0)
        pteq_set_point(x, lo + (slong)n_randint(st, (ulong)(hi - lo)), r);
    else
        rand_comb(x, st, lo, hi, kind == 3 ? 0 : 1, r);
}

/* M lies on the flat spanned by g[0..n-1] (g[0] a point): M is g[0], or
 * the line through M and g[0] lies in the flat, which the general solver
 * reports as coincident */
static int on_flat(const PointEq m, const PointEq *g, slong n, const Ring *r)
{
    PointEq tmp, line[2];
    int ok = 1;
    if (pteq_equal(m, g[0], r))
        return 1;
    pteq_init(tmp, r);
    pteq_init(line[0], r);
    pteq_init(line[1], r);
    pteq_set(line[0], m, r);
    pteq_set(line[1], g[0], r);
    ok = construct_meet_general(tmp, (const PointEq *)line, 2, g, n, r) ==
         MEET_COINCIDENT;
    pteq_clear(line[1], r);
    pteq_clear(line[0], r);
    pteq_clear(tmp, r);
    return ok;
}

static int same(MeetStatus s1, const PointEq m1, MeetStatus s2,
                const PointEq m2, const Ring *r)
{
    return s1 == s2 && (s1 != MEET_OK || pteq_equal(m1, m2, r));
}

/* both paths on one configuration; returns the status */
static MeetStatus check_meet(const PointEq *a, slong na, const PointEq *b,
                             slong nb, const Ring *r, int line)
{
    PointEq m1, m2;
    pteq_init(m1, r);
    pteq_init(m2, r);
    MeetStatus s1 = construct_meet(m1, a, na, b, nb, r);
    MeetStatus s2 = construct_meet_general(m2, a, na, b, nb, r);
    if (!same(s1, m1, s2, m2, r))
        fail_msg("meet paths disagree (line %d): status %d vs %d", line,
                 (int)s1, (int)s2);
    if (s1 == MEET_OK) {
        RatFun sum;
        ratfun_init(sum, r);
        pteq_weight_sum(sum, m1, r);
        if (!pteq_is_canonical(m1, r) || !ratfun_is_one(sum, r))
            fail_msg("meet result not a canonical point (line %d)", line);
        if (!on_flat(m1, a, na, r) || !on_flat(m1, b, nb, r))
            fail_msg("meet result not on both flats (line %d)", line);
        ratfun_clear(sum, r);
    }
    pteq_clear(m2, r);
    pteq_clear(m1, r);
    return s1;
}

static void test_meet_lines_in_the_plane(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq a[2], b[2];
    slong ok = 0;
    for (int i = 0; i < 2; i++) {
        pteq_init(a[i], r);
        pteq_init(b[i], r);
    }
    for (slong it = 0; it < rand_iters(150); it++) {
        /* a point first in each line, then a point or a direction */
        rand_gen(a[0], f->st, 0, 3, 0, r);
        rand_gen(a[1], f->st, 0, 3, 1, r);
        rand_gen(b[0], f->st, 0, 3, 0, r);
        rand_gen(b[1], f->st, 0, 3, 1, r);
        ok += check_meet((const PointEq *)a, 2, (const PointEq *)b, 2, r,
                         __LINE__) == MEET_OK;
    }
    assert_true(ok > rand_iters(150) / 2); /* mostly proper meets */
    for (int i = 0; i < 2; i++) {
        pteq_clear(a[i], r);
        pteq_clear(b[i], r);
    }
}

/* lines in the plane of three random points over five base points: two of
 * the five rows are beyond the minors and must be checked */
static void test_meet_lines_in_a_spanned_plane(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq p[3], a[2], b[2], d;
    RatFun s;
    slong ok = 0;
    ratfun_init(s, r);
    pteq_init(d, r);
    for (int i = 0; i < 3; i++)
        pteq_init(p[i], r);
    for (int i = 0; i < 2; i++) {
        pteq_init(a[i], r);
        pteq_init(b[i], r);
    }
    for (slong it = 0; it < rand_iters(60); it++) {
        for (int i = 0; i < 3; i++)
            rand_comb(p[i], f->st, 0, 5, 1, r);
        PointEq *g[4] = {&a[0], &a[1], &b[0], &b[1]};
        for (int k = 0; k < 4; k++) {
            int i = (int)n_randint(f->st, 3), j = (i + 1) % 3;
            rand_ratfun(s, f->st, r);
            if (k % 2 == 1 && n_randint(f->st, 3) == 0) {
                pteq_sub(d, p[j], p[i], r); /* a direction of the plane */
                pteq_scalar_mul(*g[k], d, s, r);
                if (pteq_is_zero(*g[k], r))
                    pteq_set(*g[k], d, r);
            } else {
                construct_along(*g[k], p[i], p[j], s, r);
            }
        }
        ok += check_meet((const PointEq *)a, 2, (const PointEq *)b, 2, r,
                         __LINE__) == MEET_OK;
    }
    assert_true(ok > rand_iters(60) / 2);
    for (int i = 0; i < 2; i++) {
        pteq_clear(a[i], r);
        pteq_clear(b[i], r);
    }
    for (int i = 0; i < 3; i++)
        pteq_clear(p[i], r);
    pteq_clear(d, r);
    ratfun_clear(s, r);
}

static void test_meet_line_and_plane_in_space(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq a[2], b[3];
    slong ok = 0;
    for (int i = 0; i < 3; i++) {
        pteq_init(b[i], r);
        if (i < 2)
            pteq_init(a[i], r);
    }
    for (slong it = 0; it < rand_iters(80); it++) {
        rand_gen(a[0], f->st, 0, 4, 0, r);
        rand_gen(a[1], f->st, 0, 4, 1, r);
        rand_gen(b[0], f->st, 0, 4, 0, r);
        rand_gen(b[1], f->st, 0, 4, 1, r);
        rand_gen(b[2], f->st, 0, 4, 1, r);
        ok += check_meet((const PointEq *)a, 2, (const PointEq *)b, 3, r,
                         __LINE__) == MEET_OK;
    }
    assert_true(ok > rand_iters(80) / 2);
    for (int i = 0; i < 3; i++) {
        pteq_clear(b[i], r);
        if (i < 2)
            pteq_clear(a[i], r);
    }
}

/* skew lines in 3-space, the same point on both sides, coincident,
 * parallel and degenerate lines: the fraction-free form must hand every
 * one of them to the general path, which names it */
static void test_meet_degenerate_cases(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq a[2], b[2], d;
    RatFun s;
    slong skew = 0;
    ratfun_init(s, r);
    pteq_init(d, r);
    for (int i = 0; i < 2; i++) {
        pteq_init(a[i], r);
        pteq_init(b[i], r);
    }
    for (slong it = 0; it < rand_iters(40); it++) {
        rand_comb(a[0], f->st, 0, 4, 1, r);
        rand_comb(a[1], f->st, 0, 4, 1, r);
        rand_comb(b[0], f->st, 0, 4, 1, r);
        rand_comb(b[1], f->st, 0, 4, 1, r);
        skew += check_meet((const PointEq *)a, 2, (const PointEq *)b, 2, r,
                           __LINE__) == MEET_SKEW;
        if (pteq_equal(a[0], a[1], r))
            continue; /* (rare) no line: the cases below need one */
        /* parallel: b = a shifted by a direction (coincident when the
         * direction happens to be the line's own) */
        rand_comb(d, f->st, 0, 4, 0, r);
        pteq_add(b[0], a[0], d, r);
        pteq_add(b[1], a[1], d, r);
        if (!pteq_is_zero(d, r)) {
            MeetStatus ms = check_meet((const PointEq *)a, 2,
                                       (const PointEq *)b, 2, r, __LINE__);
            assert_true(ms == MEET_PARALLEL || ms == MEET_COINCIDENT);
        }
        /* coincident: the same line through other points of it */
        rand_ratfun(s, f->st, r);
        construct_along(b[0], a[0], a[1], s, r);
        pteq_set(b[1], a[0], r);
        if (!pteq_equal(b[0], b[1], r))
            assert_int_equal(check_meet((const PointEq *)a, 2,
                                        (const PointEq *)b, 2, r, __LINE__),
                             MEET_COINCIDENT);
        /* degenerate: a line through one point twice */
        pteq_set(b[0], a[0], r);
        pteq_set(b[1], a[0], r);
        rand_comb(a[1], f->st, 0, 3, 1, r);
        check_meet((const PointEq *)a, 2, (const PointEq *)b, 2, r, __LINE__);
        /* one base point on both lines: meet(line(A, P), line(A, Q)) */
        pteq_set_point(a[0], 0, r);
        pteq_set_point(b[0], 0, r);
        rand_comb(a[1], f->st, 0, 3, 1, r);
        rand_comb(b[1], f->st, 0, 3, 1, r);
        check_meet((const PointEq *)a, 2, (const PointEq *)b, 2, r, __LINE__);
    }
    assert_true(skew > rand_iters(40) / 2);
    for (int i = 0; i < 2; i++) {
        pteq_clear(a[i], r);
        pteq_clear(b[i], r);
    }
    pteq_clear(d, r);
    ratfun_clear(s, r);
}

/* a generator made from X: along(X, Q, s) with Q a base point of lo..hi-1
 * or (a quarter of them) a random point; or (a sixth) a base point, or
 * when may_be_direction (a sixth) the direction (Q - X)*s */
static void rand_gen_from(PointEq g, const PointEq x, flint_rand_t st, slong lo,
                          slong hi, int may_be_direction, const Ring *r)
{
    PointEq q;
    RatFun s;
    pteq_init(q, r);
    ratfun_init(s, r);
    ulong kind = n_randint(st, 6);
    if (n_randint(st, 4) == 0)
        rand_comb(q, st, lo, hi, 1, r);
    else
        pteq_set_point(q, lo + (slong)n_randint(st, (ulong)(hi - lo)), r);
    rand_ratfun_nz(s, st, r);
    if (kind == 0) {
        pteq_set_point(g, lo + (slong)n_randint(st, (ulong)(hi - lo)), r);
    } else if (kind == 1 && may_be_direction) {
        pteq_sub(q, q, x, r);
        pteq_scalar_mul(g, q, s, r);
    } else {
        construct_along(g, x, q, s, r);
    }
    if (pteq_is_zero(g, r))
        pteq_set(g, x, r);
    ratfun_clear(s, r);
    pteq_clear(q, r);
}

/* line and plane in 3-space, two lines in the plane, with points made from
 * one X (the V-theorem chains of bench_chains): the reduction of a flat's
 * points against each other, at threshold 0.  In a third of the cases the
 * base points are not the simplex of the flats: X and the other points lie
 * in the span of random points p[] over five base points, and the rows
 * beyond the minors are checked. */
static void test_meet_flats_through_one_point(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, a[2], b[3], p[4];
    RatFun s;
    slong ok = 0, fast0, red0, fast1, red1, spanned = 0, spanned_fast = 0;
    ratfun_init(s, r);
    pteq_init(x, r);
    for (int i = 0; i < 4; i++)
        pteq_init(p[i], r);
    for (int i = 0; i < 3; i++) {
        pteq_init(b[i], r);
        if (i < 2)
            pteq_init(a[i], r);
    }
    construct_meet_stats(&fast0, &red0);
    construct_meet_set_reduce_min_terms(0);
    for (slong it = 0; it < rand_iters(150); it++) {
        int plane = it % 3 != 0, span = it % 3 == 2 || it % 7 == 0;
        slong hi = plane ? 4 : 3;
        PointEq *g[5] = {&a[0], &a[1], &b[0], &b[1], &b[2]};
        rand_comb(x, f->st, 0, hi, 1, r);
        if (it % 2 == 0)
            rand_gen(a[0], f->st, 0, hi, 0, r); /* line(A, along(X, ...)) */
        else
            rand_gen_from(a[0], x, f->st, 0, hi, 0, r);
        rand_gen_from(a[1], x, f->st, 0, hi, 1, r);
        if (it % 5 == 0)
            rand_gen(b[0], f->st, 0, hi, 0, r);
        else
            rand_gen_from(b[0], x, f->st, 0, hi, 0, r);
        for (int i = 1; i < (plane ? 3 : 2); i++)
            rand_gen_from(b[i], x, f->st, 0, hi, 1, r);
        if (span) { /* base point q -> p[q]: the same figure, spanned */
            for (slong i = 0; i < hi; i++)
                rand_comb(p[i], f->st, 0, 5, 1, r);
            for (int q = 0; q < (plane ? 5 : 4); q++) {
                PointEq m;
                pteq_init(m, r);
                for (slong i = 0; i < (*g[q])->len; i++) {
                    fmpz_mpoly_set(s->num, (*g[q])->terms[i].num, r->ctx);
                    fmpz_mpoly_set(s->den, (*g[q])->den, r->ctx);
                    ratfun_canonicalise(s, r);
                    pteq_addmul(m, m, p[(*g[q])->terms[i].point], s, r);
                }
                pteq_swap(*g[q], m, r);
                pteq_clear(m, r);
            }
            construct_meet_stats(&fast1, &red1);
        }
        MeetStatus ms = check_meet((const PointEq *)a, 2, (const PointEq *)b,
                                   plane ? 3 : 2, r, __LINE__);
        ok += ms == MEET_OK;
        if (span && ms == MEET_OK) {
            slong fast2, red2;
            construct_meet_stats(&fast2, &red2);
            spanned++;
            spanned_fast += fast2 > fast1 && red2 > red1;
        }
    }
    construct_meet_set_reduce_min_terms(-1);
    construct_meet_stats(&fast1, &red1);
    assert_true(ok > rand_iters(150) / 2);
    /* the fast path solved most, reduced often, also with rows to check */
    assert_true(fast1 - fast0 > ok / 2);
    assert_true(red1 - red0 > rand_iters(150) / 4);
    assert_true(spanned > 0 && spanned_fast > spanned / 3);
    for (int i = 0; i < 3; i++) {
        pteq_clear(b[i], r);
        if (i < 2)
            pteq_clear(a[i], r);
    }
    for (int i = 0; i < 4; i++)
        pteq_clear(p[i], r);
    pteq_clear(x, r);
    ratfun_clear(s, r);
}

/* bench_chains' vplane chain over this ring's two variables: X_i =
 * meet(line(A, along(X, B, t)), plane(B, along(X, C, u), along(X, D, t)))
 * until the entries pass the default threshold of the reduction, each
 * meet checked against the general path */
static void test_meet_vplane_chain(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, a[2], b[3], y;
    RatFun s, v;
    slong fast0, red0, fast1, red1;
    construct_meet_stats(&fast0, &red0);
    ratfun_init(s, r);
    ratfun_init(v, r);
    pteq_init(x, r);
    pteq_init(y, r);
    for (int i = 0; i < 3; i++) {
        pteq_init(b[i], r);
        if (i < 2)
            pteq_init(a[i], r);
    }
    ratfun_gen(s, 0, r);
    ratfun_gen(v, 1, r);
    /* X0 = (A + 2B + 4C + 8D)/15 */
    pteq_set_point(x, 0, r);
    for (slong p = 1; p < 4; p++) {
        RatFun w;
        ratfun_init(w, r);
        ratfun_set_si(w, WORD(1) << p, r);
        pteq_set_point(y, p, r);
        pteq_addmul(x, x, y, w, r);
        ratfun_clear(w, r);
    }
    {
        RatFun w;
        ratfun_init(w, r);
        ratfun_set_si(w, 15, r);
        ratfun_inv(w, w, r);
        pteq_scalar_mul(x, x, w, r);
        ratfun_clear(w, r);
    }
    for (int i = 1; i <= 4; i++) {
        pteq_set_point(a[0], 0, r);
        pteq_set_point(y, 1, r);
        construct_along(a[1], x, y, s, r);
        pteq_set_point(b[0], 1, r);
        pteq_set_point(y, 2, r);
        construct_along(b[1], x, y, v, r);
        pteq_set_point(y, 3, r);
        construct_along(b[2], x, y, s, r);
        assert_int_equal(check_meet((const PointEq *)a, 2, (const PointEq *)b,
                                    3, r, __LINE__),
                         MEET_OK);
        construct_meet(x, (const PointEq *)a, 2, (const PointEq *)b, 3, r);
    }
    construct_meet_stats(&fast1, &red1);
    assert_int_equal(fast1 - fast0, 2 * 4); /* check_meet's and the chain's */
    assert_true(red1 > red0);
    for (int i = 0; i < 3; i++) {
        pteq_clear(b[i], r);
        if (i < 2)
            pteq_clear(a[i], r);
    }
    pteq_clear(y, r);
    pteq_clear(x, r);
    ratfun_clear(v, r);
    ratfun_clear(s, r);
}

/* pteq_divide_known, which meet uses for a multiplier it could not divide
 * out of z: x*f/f is x again; a factor that does not divide leaves x as
 * it was */
static void test_pteq_divide_known(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, y;
    fmpz_mpoly_t g;
    pteq_init(x, r);
    pteq_init(y, r);
    fmpz_mpoly_init(g, r->ctx);
    for (slong it = 0; it < rand_iters(100); it++) {
        rand_comb(x, f->st, 0, 4, (int)(it & 1), r);
        rand_poly(g, f->st, 4, 3, r);
        pteq_set(y, x, r);
        if (fmpz_mpoly_is_zero(g, r->ctx) || pteq_is_zero(x, r))
            continue;
        for (slong i = 0; i < y->len; i++)
            fmpz_mpoly_mul(y->terms[i].num, y->terms[i].num, g, r->ctx);
        fmpz_mpoly_mul(y->den, y->den, g, r->ctx);
        assert_int_equal(pteq_divide_known(y, g, r),
                         !fmpz_mpoly_is_fmpz(g, r->ctx));
        if (!fmpz_mpoly_is_fmpz(g, r->ctx))
            assert_true(pteq_equal(x, y, r));
        /* x is canonical: a non-constant factor cannot divide it all */
        if (!fmpz_mpoly_is_fmpz(g, r->ctx)) {
            assert_int_equal(pteq_divide_known(y, g, r), 0);
            assert_true(pteq_equal(x, y, r));
        }
    }
    fmpz_mpoly_clear(g, r->ctx);
    pteq_clear(y, r);
    pteq_clear(x, r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_meet_lines_in_the_plane),
        cmocka_unit_test(test_meet_lines_in_a_spanned_plane),
        cmocka_unit_test(test_meet_line_and_plane_in_space),
        cmocka_unit_test(test_meet_degenerate_cases),
        cmocka_unit_test(test_meet_flats_through_one_point),
        cmocka_unit_test(test_meet_vplane_chain),
        cmocka_unit_test(test_pteq_divide_known),
    };
    int fails = cmocka_run_group_tests(tests, setup, teardown);
    flint_cleanup_master();
    return fails;
}
