/*
 * test_pteq.c - point equations: every operation is checked point by point
 * against the same operation on the weights (RatFun), on seeded random
 * equations, including every aliasing pattern; plus the invariants (sorted,
 * no zero weight, canonical weights) after each step.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <stdlib.h>

#include <flint/flint.h>

#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"
#include "tests/unit/rand_algebra.h"

#define NPTS 6 /* base points 0..NPTS-1 in the random equations */

static int setup(void **state)
{
    return fixture_setup(state, 2);
}

/* pteq_weight(x, point): the reduced weight of point in x, or NULL when it
 * is absent (a rotating buffer of four, valid until the fourth next call);
 * the test's stand-in for a borrowed-weight accessor */
#define NWBUF 4
static RatFunStruct wbuf[NWBUF];
static int wbuf_next;
static const Ring *wbuf_ring;

static const RatFunStruct *weight_at(const PointEq x, slong point,
                                     const Ring *r)
{
    if (wbuf_ring == NULL) {
        wbuf_ring = r;
        for (int i = 0; i < NWBUF; i++)
            ratfun_init(wbuf + i, r);
    }
    if (!pteq_has_point(x, point))
        return NULL;
    RatFunStruct *w = wbuf + wbuf_next++ % NWBUF;
    pteq_get_weight(w, x, point, r);
    return w;
}
#define pteq_weight(x, point) weight_at(x, point, r)

static int teardown(void **state)
{
    if (wbuf_ring != NULL)
        for (int i = 0; i < NWBUF; i++)
            ratfun_clear(wbuf + i, wbuf_ring);
    wbuf_ring = NULL;
    return fixture_teardown(state);
}

static void parse(RatFun x, const char *s, const Ring *r)
{
    if (ratfun_set_str(x, s, r) != RATFUN_OK)
        fail_msg("cannot parse '%s'", s);
}

/* a random equation: each point present with probability 1/2 */
static void rand_pteq(PointEq x, flint_rand_t st, const Ring *r)
{
    RatFun w;
    ratfun_init(w, r);
    pteq_zero(x, r);
    for (slong p = 0; p < NPTS; p++) {
        if (n_randint(st, 2))
            continue;
        rand_ratfun_nz(w, st, r);
        pteq_set_weight(x, p, w, r);
    }
    ratfun_clear(w, r);
}

#define CHECK_CANON(x)                                                         \
    do {                                                                       \
        if (!pteq_is_canonical(x, r))                                          \
            fail_msg("point equation not canonical (line %d)", __LINE__);      \
    } while (0)

/* ---- structure -------------------------------------------------------- */

static void test_pteq_init_is_zero(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x;
    RatFun w;
    pteq_init(x, r);
    ratfun_init(w, r);
    assert_true(pteq_is_zero(x, r));
    assert_null(pteq_weight(x, 0));
    pteq_get_weight(w, x, 3, r);
    assert_true(ratfun_is_zero(w, r));
    pteq_weight_sum(w, x, r);
    assert_true(ratfun_is_zero(w, r));
    CHECK_CANON(x);
    ratfun_clear(w, r);
    pteq_clear(x, r);
}

static void test_pteq_set_point_weight_one(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x;
    RatFun w;
    pteq_init(x, r);
    ratfun_init(w, r);
    pteq_set_point(x, 4, r);
    assert_int_equal(x->len, 1);
    assert_true(ratfun_is_one(pteq_weight(x, 4), r));
    assert_null(pteq_weight(x, 3));
    pteq_weight_sum(w, x, r);
    assert_true(ratfun_is_one(w, r));
    CHECK_CANON(x);
    ratfun_clear(w, r);
    pteq_clear(x, r);
}

/* weights set in any order end up sorted; setting 0 removes the term */
static void test_pteq_set_weight_sorted_no_zeros(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    static const slong order[] = {5, 1, 9, 0, 3, 7};
    PointEq x;
    RatFun w;
    pteq_init(x, r);
    ratfun_init(w, r);
    for (size_t i = 0; i < 6; i++) {
        ratfun_set_si(w, (slong)order[i] + 1, r);
        pteq_set_weight(x, order[i], w, r);
        CHECK_CANON(x);
    }
    assert_int_equal(x->len, 6);
    for (slong i = 1; i < x->len; i++)
        assert_true(x->terms[i - 1].point < x->terms[i].point);
    ratfun_zero(w, r);
    pteq_set_weight(x, 3, w, r);
    pteq_set_weight(x, 4, w, r); /* absent and zero: no-op */
    CHECK_CANON(x);
    assert_int_equal(x->len, 5);
    assert_null(pteq_weight(x, 3));
    pteq_get_weight(w, x, 9, r);
    assert_true(fmpz_mpoly_equal_si(w->num, 10, r->ctx));
    /* the weight may come from x itself, even when x must grow */
    for (slong p = 10; p < 40; p++)
        pteq_set_weight(x, p, pteq_weight(x, 0), r);
    CHECK_CANON(x);
    assert_int_equal(x->len, 35);
    assert_true(ratfun_is_one(pteq_weight(x, 39), r));
    ratfun_clear(w, r);
    pteq_clear(x, r);
}

/* along(A, B, t) = A*(1 - t) + B*t is a point: weights sum to 1 */
static void test_pteq_weight_sum_along_is_one(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq a, b, d, m;
    RatFun t, s;
    pteq_init(a, r);
    pteq_init(b, r);
    pteq_init(d, r);
    pteq_init(m, r);
    ratfun_init(t, r);
    ratfun_init(s, r);
    pteq_set_point(a, 0, r);
    pteq_set_point(b, 1, r);
    parse(t, "t", r);
    pteq_sub(d, b, a, r);
    pteq_weight_sum(s, d, r);
    assert_true(ratfun_is_zero(s, r)); /* a vector */
    pteq_addmul(m, a, d, t, r);
    CHECK_CANON(m);
    pteq_weight_sum(s, m, r);
    assert_true(ratfun_is_one(s, r));
    parse(s, "1-t", r);
    assert_true(ratfun_equal(pteq_weight(m, 0), s, r));
    assert_true(ratfun_equal(pteq_weight(m, 1), t, r));
    /* at t = 1 the weight of A vanishes and must disappear */
    ratfun_one(t, r);
    pteq_addmul(m, a, d, t, r);
    CHECK_CANON(m);
    assert_true(pteq_equal(m, b, r));
    ratfun_clear(s, r);
    ratfun_clear(t, r);
    pteq_clear(m, r);
    pteq_clear(d, r);
    pteq_clear(b, r);
    pteq_clear(a, r);
}

/* equal denominators take a shortcut; the sum must still be reduced */
static void test_pteq_weight_sum_common_den_reduced(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    static const char *const W[3] = {"t/(t^2+u)", "u/(t^2+u)",
                                     "(t^2-t)/(t^2+u)"};
    PointEq x;
    RatFun w;
    pteq_init(x, r);
    ratfun_init(w, r);
    for (slong i = 0; i < 3; i++) {
        parse(w, W[i], r);
        pteq_set_weight(x, i, w, r);
    }
    pteq_weight_sum(w, x, r);
    assert_true(ratfun_is_one(w, r));
    parse(w, "-2*t/(t^2+u)", r); /* sum (u - t)/(t^2 + u) */
    pteq_set_weight(x, 2, w, r);
    pteq_weight_sum(w, x, r);
    assert_true(ratfun_is_canonical(w, r));
    parse(w, "(u-t)/(t^2+u)", r);
    {
        RatFun s;
        ratfun_init(s, r);
        pteq_weight_sum(s, x, r);
        assert_true(ratfun_equal(s, w, r));
        ratfun_clear(s, r);
    }
    /* 1/6 + (t+2)/6 - t/6 = 1/2: the shared integer den still reduces */
    pteq_zero(x, r);
    parse(w, "1/6", r);
    pteq_set_weight(x, 0, w, r);
    parse(w, "(t+2)/6", r);
    pteq_set_weight(x, 1, w, r);
    parse(w, "-t/6", r);
    pteq_set_weight(x, 2, w, r);
    pteq_weight_sum(w, x, r);
    assert_true(ratfun_is_canonical(w, r));
    {
        RatFun e;
        ratfun_init(e, r);
        parse(e, "1/2", r);
        assert_true(ratfun_equal(w, e, r));
        ratfun_clear(e, r);
    }
    ratfun_clear(w, r);
    pteq_clear(x, r);
}

static void test_pteq_equal_detects_differences(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, y;
    RatFun w;
    pteq_init(x, r);
    pteq_init(y, r);
    ratfun_init(w, r);
    pteq_set_point(x, 0, r);
    pteq_set_point(y, 1, r);
    assert_false(pteq_equal(x, y, r)); /* different point */
    pteq_set_point(y, 0, r);
    assert_true(pteq_equal(x, y, r));
    ratfun_set_si(w, 2, r);
    pteq_set_weight(y, 0, w, r);
    assert_false(pteq_equal(x, y, r)); /* different weight */
    pteq_set_weight(y, 0, pteq_weight(x, 0), r);
    pteq_set_weight(y, 2, w, r);
    assert_false(pteq_equal(x, y, r)); /* different length */
    ratfun_clear(w, r);
    pteq_clear(y, r);
    pteq_clear(x, r);
}

static void test_pteq_scalar_div_zero_code(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, y;
    RatFun z;
    pteq_init(x, r);
    pteq_init(y, r);
    ratfun_init(z, r);
    pteq_set_point(x, 2, r);
    pteq_set_point(y, 5, r);
    assert_int_equal(pteq_scalar_div(y, x, z, r), RATFUN_EDIVZERO);
    assert_non_null(pteq_weight(y, 5)); /* untouched */
    assert_int_equal(y->len, 1);
    ratfun_clear(z, r);
    pteq_clear(y, r);
    pteq_clear(x, r);
}

/* ---- random: operations against per-point weight operations ------------ */

enum { OP_ADD, OP_SUB, OP_ADDMUL, OP_SMUL, OP_SDIV, OP_NEG, NOPS };

/* want = x op y (s) computed point by point on the weights */
static void per_point(PointEq want, int op, const PointEq x, const PointEq y,
                      const RatFun s, const Ring *r)
{
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    pteq_zero(want, r);
    for (slong p = 0; p < NPTS; p++) {
        pteq_get_weight(a, x, p, r);
        pteq_get_weight(b, y, p, r);
        switch (op) {
        case OP_ADD:
            ratfun_add(a, a, b, r);
            break;
        case OP_SUB:
            ratfun_sub(a, a, b, r);
            break;
        case OP_ADDMUL:
            ratfun_mul(b, b, s, r);
            ratfun_add(a, a, b, r);
            break;
        case OP_SMUL:
            ratfun_mul(a, a, s, r);
            break;
        case OP_SDIV:
            ratfun_div(a, a, s, r);
            break;
        default:
            ratfun_neg(a, a, r);
            break;
        }
        pteq_set_weight(want, p, a, r);
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
}

static void apply(PointEq res, int op, const PointEq x, const PointEq y,
                  const RatFun s, const Ring *r)
{
    switch (op) {
    case OP_ADD:
        pteq_add(res, x, y, r);
        break;
    case OP_SUB:
        pteq_sub(res, x, y, r);
        break;
    case OP_ADDMUL:
        pteq_addmul(res, x, y, s, r);
        break;
    case OP_SMUL:
        pteq_scalar_mul(res, x, s, r);
        break;
    case OP_SDIV:
        assert_int_equal(pteq_scalar_div(res, x, s, r), RATFUN_OK);
        break;
    default:
        pteq_neg(res, x, r);
        break;
    }
}

/* each op, with res distinct, res == x, res == y, and x == y */
static void test_pteq_ops_match_per_point(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, y, want, got;
    RatFun s;
    pteq_init(x, r);
    pteq_init(y, r);
    pteq_init(want, r);
    pteq_init(got, r);
    ratfun_init(s, r);
    for (slong i = 0; i < rand_iters(150); i++) {
        rand_pteq(x, f->st, r);
        rand_pteq(y, f->st, r);
        /* s = 0 and s = 1 take shortcuts: include them */
        switch (n_randint(f->st, 6)) {
        case 0:
            ratfun_one(s, r);
            break;
        case 1:
            ratfun_set_si(s, -1, r);
            break;
        default:
            rand_ratfun_nz(s, f->st, r);
        }
        for (int op = 0; op < NOPS; op++) {
            per_point(want, op, x, y, s, r);
            apply(got, op, x, y, s, r); /* distinct */
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
            pteq_set(got, x, r); /* res == x */
            apply(got, op, got, y, s, r);
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
            pteq_set(got, y, r); /* res == y */
            apply(got, op, x, got, s, r);
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
            per_point(want, op, x, x, s, r); /* x == y, res == x */
            pteq_set(got, x, r);
            apply(got, op, got, got, s, r);
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
        }
        /* s equal to a weight of res itself: res = res + y*w(res) */
        if (x->len > 0) {
            RatFun w;
            ratfun_init(w, r);
            pteq_get_weight(w, x, x->terms[0].point, r);
            per_point(want, OP_ADDMUL, x, y, w, r);
            pteq_set(got, x, r);
            pteq_addmul(got, got, y, w, r);
            assert_true(pteq_equal(got, want, r));
            per_point(want, OP_SMUL, x, y, w, r);
            pteq_set(got, x, r);
            pteq_scalar_mul(got, got, w, r);
            assert_true(pteq_equal(got, want, r));
            ratfun_clear(w, r);
        }
    }
    ratfun_clear(s, r);
    pteq_clear(got, r);
    pteq_clear(want, r);
    pteq_clear(y, r);
    pteq_clear(x, r);
}

/* x - x == 0 and (x + y) - y == x; weight_sum is additive */
static void test_pteq_sub_add_inverse(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, y, z;
    RatFun a, b, c;
    pteq_init(x, r);
    pteq_init(y, r);
    pteq_init(z, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(c, r);
    for (slong i = 0; i < rand_iters(200); i++) {
        rand_pteq(x, f->st, r);
        rand_pteq(y, f->st, r);
        pteq_sub(z, x, x, r);
        assert_true(pteq_is_zero(z, r));
        pteq_add(z, x, y, r);
        pteq_weight_sum(a, z, r);
        pteq_weight_sum(b, x, r);
        pteq_weight_sum(c, y, r);
        ratfun_add(b, b, c, r);
        assert_true(ratfun_equal(a, b, r));
        pteq_sub(z, z, y, r);
        CHECK_CANON(z);
        assert_true(pteq_equal(z, x, r));
    }
    ratfun_clear(c, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    pteq_clear(z, r);
    pteq_clear(y, r);
    pteq_clear(x, r);
}

/* subst_point: res_j = x_j + x_point*p_j (j != point), res_point = x_point *
 * p_point; also with res == x and res == p */
static void test_pteq_subst_point_per_point(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, p, want, got;
    RatFun a, b, wp;
    pteq_init(x, r);
    pteq_init(p, r);
    pteq_init(want, r);
    pteq_init(got, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(wp, r);
    for (slong i = 0; i < rand_iters(200); i++) {
        slong pt = (slong)n_randint(f->st, NPTS);
        rand_pteq(x, f->st, r);
        rand_pteq(p, f->st, r);
        pteq_get_weight(wp, x, pt, r);
        pteq_zero(want, r);
        for (slong j = 0; j < NPTS; j++) {
            if (j == pt)
                ratfun_zero(a, r);
            else
                pteq_get_weight(a, x, j, r);
            pteq_get_weight(b, p, j, r);
            ratfun_mul(b, b, wp, r);
            ratfun_add(a, a, b, r);
            pteq_set_weight(want, j, a, r);
        }
        pteq_subst_point(got, x, pt, p, r);
        CHECK_CANON(got);
        assert_true(pteq_equal(got, want, r));
        pteq_set(got, x, r);
        pteq_subst_point(got, got, pt, p, r);
        assert_true(pteq_equal(got, want, r));
        pteq_set(got, p, r);
        pteq_subst_point(got, x, pt, got, r);
        assert_true(pteq_equal(got, want, r));
    }
    /* replacing the simplex: M = A*(1-t) + B*t with B := (A + C)/2 */
    {
        PointEq m;
        RatFun h;
        pteq_init(m, r);
        ratfun_init(h, r);
        pteq_zero(m, r);
        parse(a, "1-t", r);
        pteq_set_weight(m, 0, a, r);
        parse(a, "t", r);
        pteq_set_weight(m, 1, a, r);
        pteq_zero(p, r);
        parse(h, "1/2", r);
        pteq_set_weight(p, 0, h, r);
        pteq_set_weight(p, 2, h, r);
        pteq_subst_point(m, m, 1, p, r);
        CHECK_CANON(m);
        assert_int_equal(m->len, 2);
        parse(a, "1-t/2", r);
        assert_true(ratfun_equal(pteq_weight(m, 0), a, r));
        parse(a, "t/2", r);
        assert_true(ratfun_equal(pteq_weight(m, 2), a, r));
        ratfun_clear(h, r);
        pteq_clear(m, r);
    }
    ratfun_clear(wp, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    pteq_clear(got, r);
    pteq_clear(want, r);
    pteq_clear(p, r);
    pteq_clear(x, r);
}

/* compose_var and derivative weight by weight; vanishing weights go */
static void test_pteq_compose_derivative_per_point(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    PointEq x, want, got;
    RatFun a, s;
    pteq_init(x, r);
    pteq_init(want, r);
    pteq_init(got, r);
    ratfun_init(a, r);
    ratfun_init(s, r);
    for (slong i = 0; i < rand_iters(150); i++) {
        slong var = (slong)n_randint(f->st, 2);
        int pole = 0;
        rand_pteq(x, f->st, r);
        rand_ratfun(s, f->st, r);
        pteq_zero(want, r);
        for (slong j = 0; j < NPTS && !pole; j++) {
            pteq_get_weight(a, x, j, r);
            if (ratfun_compose_var(a, a, var, s, r) != RATFUN_OK)
                pole = 1;
            else
                pteq_set_weight(want, j, a, r);
        }
        pteq_set(got, x, r);
        if (pole) {
            assert_int_equal(pteq_compose_var(got, got, var, s, r),
                             RATFUN_EPOLE);
            assert_true(pteq_equal(got, x, r)); /* untouched */
        } else {
            assert_int_equal(pteq_compose_var(got, got, var, s, r), RATFUN_OK);
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
        }
        pteq_zero(want, r);
        for (slong j = 0; j < NPTS; j++) {
            pteq_get_weight(a, x, j, r);
            ratfun_derivative(a, a, var, r);
            pteq_set_weight(want, j, a, r);
        }
        pteq_derivative(got, x, var, r);
        CHECK_CANON(got);
        assert_true(pteq_equal(got, want, r));
        pteq_set(got, x, r);
        pteq_derivative(got, got, var, r);
        assert_true(pteq_equal(got, want, r));
        /* the k-th derivative at once (one reduction over d^(k+1)) is k
         * single steps */
        for (ulong k = 2; k <= 3; k++) {
            pteq_derivative(want, want, var, r);
            pteq_derivative_n(got, x, var, k, r);
            CHECK_CANON(got);
            assert_true(pteq_equal(got, want, r));
        }
        pteq_derivative_n(got, x, var, 0, r);
        assert_true(pteq_equal(got, x, r));
    }
    /* M = A*(1-t) + B*t at t := 1 is B alone; d/dt M = B - A, sum 0 */
    pteq_zero(x, r);
    parse(a, "1-t", r);
    pteq_set_weight(x, 0, a, r);
    parse(a, "t", r);
    pteq_set_weight(x, 1, a, r);
    ratfun_one(s, r);
    assert_int_equal(pteq_compose_var(got, x, 0, s, r), RATFUN_OK);
    CHECK_CANON(got);
    assert_int_equal(got->len, 1);
    assert_true(ratfun_is_one(pteq_weight(got, 1), r));
    pteq_derivative(got, x, 0, r);
    pteq_weight_sum(a, got, r);
    assert_true(ratfun_is_zero(a, r));
    pteq_derivative(got, got, 0, r); /* constants: everything vanishes */
    assert_true(pteq_is_zero(got, r));
    /* a pole: A/(t-1) at t := 1 */
    parse(a, "1/(t-1)", r);
    pteq_set_weight(x, 0, a, r);
    pteq_set(got, x, r);
    assert_int_equal(pteq_compose_var(got, x, 0, s, r), RATFUN_EPOLE);
    assert_true(pteq_equal(got, x, r));
    ratfun_clear(s, r);
    ratfun_clear(a, r);
    pteq_clear(got, r);
    pteq_clear(want, r);
    pteq_clear(x, r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pteq_init_is_zero),
        cmocka_unit_test(test_pteq_set_point_weight_one),
        cmocka_unit_test(test_pteq_set_weight_sorted_no_zeros),
        cmocka_unit_test(test_pteq_weight_sum_along_is_one),
        cmocka_unit_test(test_pteq_weight_sum_common_den_reduced),
        cmocka_unit_test(test_pteq_equal_detects_differences),
        cmocka_unit_test(test_pteq_scalar_div_zero_code),
        cmocka_unit_test(test_pteq_ops_match_per_point),
        cmocka_unit_test(test_pteq_sub_add_inverse),
        cmocka_unit_test(test_pteq_subst_point_per_point),
        cmocka_unit_test(test_pteq_compose_derivative_per_point),
    };
    int fails = cmocka_run_group_tests(tests, setup, teardown);
    flint_cleanup_master();
    return fails;
}
