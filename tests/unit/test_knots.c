/*
 * test_knots.c - smoothness at the knots of composite curves
 * (compiler/derive/knots.c, docs/composite.md "Knots and smoothness").
 *
 * Expectations are worked out by hand from the formulas, never copied
 * from the tool: a term c(t)|t - k|^p (p odd) jumps by J(t) = 2 c(t) (t -
 * k)^p across k (right minus left), so the jump of derivative j is
 * J^(j)(k).  Cases:
 *   - the square of 2.2 ex. 1 (C^0): at vertex k the first derivative jumps
 *     by the difference of the adjacent side vectors, V_k - V_(k-1);
 *   - the C^1 triangle of 2.1 ex. 4 (the text's |.| formulas): the second
 *     derivative jumps by +-6 times a side;
 *   - the C^2 square of 2.1 ex. 5: the third derivative jumps by +-60;
 *   - a cubic spline in |t - k|^3: the third derivative jumps by 12 c
 *     (6 * 2 * c);
 *   - geometric orders: a corner (G^0), a curve that turns back (G^0), a
 *     change of speed along one tangent (G^1), a parabola reparametrised
 *     at a knot (G^2, only C^0);
 *   - zeros of non-linear arguments: |t^2 - 1| (two knots), |(t - 2)^3|, a
 *     const knot |t - a|, a pi/2 knot; sign(t^2 - 2) listed as not
 *     analysed; a derivative that is infinite (sqrt|t - 1|); an output in
 *     two params;
 *   - random sums of c_i(t)|t - k_i|^p_i against J^(j)(k_i) computed by
 *     fmpq_poly;
 *   - knots_one_sided; the JSON and --knots forms through the binary.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <flint/fmpq_poly.h>

#include "compiler/derive.h"
#include "compiler/derive/knots.h"
#include "compiler/print/knots_print.h"
#include "tests/unit/rand_algebra.h"

static Derived *derive_text(const char *text)
{
    DeriveOptions opt = {.max_seconds = 60};
    size_t elen = 0;
    char *ebuf = NULL;
    FILE *e = open_memstream(&ebuf, &elen);
    int nerr = 0;
    Derived *d = derive_source_ex("k.pcs", text, strlen(text), e, &nerr, &opt);
    fclose(e);
    if (!d)
        fail_msg("derive failed:\n%s\n%s", text, ebuf);
    free(ebuf);
    return d;
}

static slong output(const Derived *d, const char *name)
{
    slong o = derived_find_output(d, name);
    if (o < 0)
        fail_msg("no output %s", name);
    return o;
}

/* the knot at t = value (an expression of the scheme's names) */
static const Knot *knot_at(const Derived *d, const KnotList *L,
                           const char *value)
{
    RatFun v;
    ratfun_init(v, &d->ring);
    assert_int_equal(ratfun_set_str(v, value, &d->ring), 0);
    const Knot *k = NULL;
    for (slong i = 0; i < L->n && !k; i++)
        if (ratfun_equal(L->k[i].t, v, &d->ring))
            k = &L->k[i];
    ratfun_clear(v, &d->ring);
    if (!k)
        fail_msg("no knot at %s", value);
    return k;
}

/* the jump of knot k of output o is spec: "O=-6 X=6" (points absent from
 * it: 0), or "=6" for a scalar */
static void expect_jump(const Derived *d, slong o, const Knot *k,
                        const char *spec)
{
    const DerivedOutput *out = &d->outputs[o];
    assert_non_null(k->jump);
    RatFun want;
    ratfun_init(want, &d->ring);
    slong n = out->kind == KIND_SCALAR ? 1 : out->eq->len;
    assert_int_equal(k->njump, n);
    for (slong i = 0; i < n; i++) {
        const char *pt =
            out->kind == KIND_SCALAR ? "" : d->points[out->eq->terms[i].point];
        char key[64];
        snprintf(key, sizeof key, "%s=", pt);
        const char *at = NULL;
        for (const char *s = spec; (s = strstr(s, key)) != NULL; s++)
            if (s == spec || s[-1] == ' ') {
                at = s + strlen(key);
                break;
            }
        char val[64] = "0";
        if (at) {
            size_t len = strcspn(at, " ");
            snprintf(val, sizeof val, "%.*s", (int)len, at);
        }
        assert_int_equal(ratfun_set_str(want, val, &d->ring), 0);
        if (!ratfun_equal(want, k->jump + i, &d->ring)) {
            char *got = ratfun_get_str(k->jump + i, &d->ring);
            fail_msg("jump of %s at %s: %s, expected %s", pt,
                     ratfun_get_str(k->t, &d->ring), got, val);
        }
    }
    ratfun_clear(want, &d->ring);
}

static void expect_knot(const Derived *d, slong o, const KnotList *L,
                        const char *at, int continuity, int geometric,
                        const char *jump)
{
    const Knot *k = knot_at(d, L, at);
    assert_true(k->analysed);
    assert_int_equal(k->continuity, continuity);
    assert_int_equal(k->geometric, geometric);
    assert_int_equal(k->jump_order, continuity + 1);
    expect_jump(d, o, k, jump);
}

/* The square of 2.2 ex. 1: R = O + sum V_k P(t, k, 1), P(t, a, 1) = (1 +
 * |t - a| - |t - a - 1|)/2, V_0..V_3 = A - O, B - A, C - B, O - C.  The
 * coefficient of |t - k| is (V_k - V_(k-1))/2, so R' jumps by V_k -
 * V_(k-1) (V_-1 = V_4 = 0); the other derivatives do not jump.  At 0 and 4
 * the curve stands still on one side: G^0. */
static void test_knots_square_c0(void **state)
{
    (void)state;
    Derived *d = derive_text(
        "point O, A, B, C\nparam t\n"
        "R = O + (A - O)*(1 + abs(t) - abs(t - 1))/2 + (B - A)*(1 + abs(t "
        "- 1) - abs(t - 2))/2 + (C - B)*(1 + abs(t - 2) - abs(t - 3))/2 + "
        "(O - C)*(1 + abs(t - 3) - abs(t - 4))/2\n");
    slong o = output(d, "R");
    KnotList L;
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 5);
    assert_int_equal(L.nskip, 0);
    expect_knot(d, o, &L, "0", 0, 0, "A=1 O=-1");
    expect_knot(d, o, &L, "1", 0, 0, "B=1 A=-2 O=1");
    expect_knot(d, o, &L, "2", 0, 0, "C=1 B=-2 A=1");
    expect_knot(d, o, &L, "3", 0, 0, "O=1 C=-2 B=1");
    expect_knot(d, o, &L, "4", 0, 0, "O=-1 C=1");
    /* knots come in increasing order */
    for (slong i = 0; i + 1 < L.n; i++)
        assert_true(L.k[i].approx < L.k[i + 1].approx);
    knots_clear(&L, d);
    derived_free(d);
}

/* The C^1 triangle of 2.1 ex. 4, the text's formulas: x(t) = ((-2t +
 * 3)t|t| + 4(t - 1)^2|t - 1| - (2t - 1)(t - 2)|t - 2|)/2, y(t) = ((-2t +
 * 5)(t - 1)|t - 1| + 4(t - 2)^2|t - 2| - (2t - 3)(t - 3)|t - 3|)/2, as
 * weights R = O + (X - O)x + (Y - O)y.  Jumps J(t) = 2c(t)(t - k)^p:
 *   t = 0: x: (3 - 2t)t^2 -> J'' = 6;              y: none
 *   t = 1: x: 4(t - 1)^3 -> J'' = 0;               y: (5 - 2t)(t - 1)^2 -> 6
 *   t = 2: x: -(2t - 1)(t - 2)^2 -> -6;           y: 4(t - 2)^3 -> 0
 *   t = 3: y: -(2t - 3)(t - 3)^2 -> -6
 * so C^1 everywhere (the claim of the text), and R'' jumps by 6(X - O),
 * 6(Y - O), -6(X - O), -6(Y - O).  Its vertices are corners: G^0. */
static void test_knots_triangle_c1(void **state)
{
    (void)state;
    Derived *d = derive_text(
        "point O, X, Y\nparam t\n"
        "x = ((-2*t + 3)*t*abs(t) + 4*(t - 1)^2*abs(t - 1) - (2*t - 1)*(t - "
        "2)*abs(t - 2))/2\n"
        "y = ((-2*t + 5)*(t - 1)*abs(t - 1) + 4*(t - 2)^2*abs(t - 2) - (2*t "
        "- 3)*(t - 3)*abs(t - 3))/2\n"
        "R = O + (X - O)*x + (Y - O)*y\noutput R, x\n");
    slong o = output(d, "R");
    KnotList L;
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 4);
    expect_knot(d, o, &L, "0", 1, 0, "X=6 O=-6");
    expect_knot(d, o, &L, "1", 1, 0, "Y=6 O=-6");
    expect_knot(d, o, &L, "2", 1, 0, "X=-6 O=6");
    expect_knot(d, o, &L, "3", 1, 0, "Y=-6 O=6");
    knots_clear(&L, d);
    /* x alone is C^2 at t = 1: its jump there is of the third derivative,
     * J''' = 24 */
    o = output(d, "x");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 3);
    const Knot *k = knot_at(d, &L, "1");
    assert_int_equal(k->continuity, 2);
    expect_jump(d, o, k, "=24");
    knots_clear(&L, d);
    derived_free(d);
}

/* The C^2 square of 2.1 ex. 5: x(t) = ((6t^2 - 15t + 10)|t|^3 - (6t^2 +
 * 3t + 1)|t - 1|^3 - (6t^2 - 39t + 64)|t - 2|^3 + (6t^2 - 21t + 19)|t -
 * 3|^3)/2 and y(t) likewise at 1..4.  A term (q(t)/2)|t - k|^3 jumps by
 * q(t)(t - k)^3, whose third derivative at k is 6 q(k):
 *   x: q = 10, -10, -10, 10 at 0..3 -> 60, -60, -60, 60
 *   y: q = 10, -10, -10, 10 at 1..4 -> 60, -60, -60, 60
 * so C^2 (the claim of the text); the vertices are corners, G^0. */
static void test_knots_square_c2(void **state)
{
    (void)state;
    Derived *d = derive_text(
        "point O, X, Y\nparam t\n"
        "x = ((6*t^2 - 15*t + 10)*abs(t)^3 - (6*t^2 + 3*t + 1)*abs(t-1)^3 - "
        "(6*t^2 - 39*t + 64)*abs(t-2)^3 + (6*t^2 - 21*t + 19)*abs(t-3)^3)/2\n"
        "y = ((6*t^2 - 27*t + 31)*abs(t-1)^3 - (6*t^2 - 9*t + 4)*abs(t-2)^3 "
        "- (6*t^2 - 51*t + 109)*abs(t-3)^3 + (6*t^2 - 33*t + "
        "46)*abs(t-4)^3)/2\n"
        "R = O + (X - O)*x + (Y - O)*y\noutput R\n");
    slong o = output(d, "R");
    KnotList L;
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 5);
    expect_knot(d, o, &L, "0", 2, 0, "X=60 O=-60");
    expect_knot(d, o, &L, "1", 2, 0, "X=-60 Y=60");
    expect_knot(d, o, &L, "2", 2, 0, "X=-60 Y=-60 O=120");
    expect_knot(d, o, &L, "3", 2, 0, "X=60 Y=-60");
    expect_knot(d, o, &L, "4", 2, 0, "Y=60 O=-60");
    knots_clear(&L, d);
    derived_free(d);
}

/* A cubic spline in |t - k|^3: y = t^2/2 + 1/4 |t - 1|^3 - 2/5 |t - 2|^3
 * on the plane curve R = O + X t + Y y.  The third derivative jumps by
 * 12c: 3 at t = 1, -24/5 at t = 2; C^2.  R' = X + Y y' never vanishes, so
 * the regular C^2 curve is G^2. */
static void test_knots_spline_c2(void **state)
{
    (void)state;
    Derived *d = derive_text(
        "point O, X, Y\nparam t\n"
        "R = O + (X - O)*t + (Y - O)*(t^2/2 + abs(t - 1)^3/4 - 2*abs(t - "
        "2)^3/5)\n");
    slong o = output(d, "R");
    KnotList L;
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 2);
    expect_knot(d, o, &L, "1", 2, 2, "Y=3 O=-3");
    expect_knot(d, o, &L, "2", 2, 2, "Y=-24/5 O=24/5");
    knots_clear(&L, d);
    derived_free(d);
}

/* Geometric orders, by hand:
 *   corner:  R = O + X|t| + Y t: R' = X + Y right, -X + Y left: G^0
 *   turn:    R = O + X|t|: R' = X right, -X left: the curve comes back, G^0
 *   speed:   R = O + X(t + |t|/2) + Y t^2: R' = 3/2 X vs 1/2 X (lambda =
 *            3), R'' = 2Y both sides: 2Y - 9*2Y is not along X: G^1, C^0
 *   reparametrised parabola: u = t + |t|/2, R = O + X u + Y u^2 (u^2 =
 *            5/4 t^2 + t|t|): R' = 3/2 X, 1/2 X; R'' = 9/2 Y, 1/2 Y;
 *            9/2 Y - 9 * 1/2 Y = 0: G^2, C^0
 *   stop:    R = O + X t|t|: R' = 0 both sides, R'' = 2X right and -2X
 *            left: it arrives along -(-2X) and leaves along 2X: G^1, C^1
 *   jump:    R = O + X sign(t): not continuous, R jumps by 2(X - O)
 *   quintic: R = O + X t + Y|t|^5: C^4, the fifth derivative jumps by 2 *
 *            5! = 240; R' = X: regular, so G^4 as well
 *   smooth:  R = O + X t + Y|t|^11: no jump up to order 8 (the first is of
 *            order 11): "C^8 or more", and G^8 or more */
static void test_knots_geometric(void **state)
{
    (void)state;
    Derived *d = derive_text("point O, X, Y\nparam t\n"
                             "corner = O + (X - O)*abs(t) + (Y - O)*t\n"
                             "turn = O + (X - O)*abs(t)\n"
                             "speed = O + (X - O)*(t + abs(t)/2) + (Y - "
                             "O)*t^2\n"
                             "u = t + abs(t)/2\n"
                             "para = O + (X - O)*u + (Y - O)*u^2\n"
                             "stop = O + (X - O)*t*abs(t)\n"
                             "jump = O + (X - O)*sign(t)\n"
                             "quintic = O + (X - O)*t + (Y - O)*abs(t)^5\n"
                             "smooth = O + (X - O)*t + (Y - O)*abs(t)^11\n"
                             "output corner, turn, speed, para, stop, jump, "
                             "quintic, smooth\n");
    static const struct {
        const char *name;
        int c, g;
        const char *jump;
    } cases[] = {
        {"corner", 0, 0, "X=2 O=-2"},      {"turn", 0, 0, "X=2 O=-2"},
        {"speed", 0, 1, "X=1 O=-1"},       {"para", 0, 2, "X=1 O=-1"},
        {"stop", 1, 1, "X=4 O=-4"},        {"jump", -1, -1, "X=2 O=-2"},
        {"quintic", 4, 4, "Y=240 O=-240"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        slong o = output(d, cases[i].name);
        KnotList L;
        knots_analyse(&L, d, o);
        assert_int_equal(L.n, 1);
        expect_knot(d, o, &L, "0", cases[i].c, cases[i].g, cases[i].jump);
        knots_clear(&L, d);
    }
    KnotList L;
    knots_analyse(&L, d, output(d, "smooth"));
    assert_int_equal(L.n, 1);
    assert_true(L.k[0].analysed && L.k[0].c_more && L.k[0].g_more);
    assert_int_equal(L.k[0].continuity, KNOTS_MAX_ORDER);
    assert_int_equal(L.k[0].geometric, KNOTS_MAX_ORDER);
    assert_int_equal(L.k[0].jump_order, -1);
    assert_null(L.k[0].jump);
    knots_clear(&L, d);
    derived_free(d);
}

/* Zeros of other arguments:
 *   |t^2 - 1|: knots -1, 1; the derivative jumps by 2|2t| = 4 at both
 *   |(t - 2)^3| = |t - 2|^3: C^2, the third derivative jumps by 12; as a
 *       curve on a line it stops at 2 and turns back: G^0
 *   |t - a| (const a): a knot at a, the derivative jumps by 2
 *   t|t - pi/2|: a knot at pi/2, the derivative jumps by 2 * pi/2 = pi
 *   |t^2 - 2|: irrational zeros, listed as not analysed
 *   sqrt(|t - 1|): continuous, its derivative is infinite there
 *   |t - u| in two params: a note, no knots
 *   t^2 + 1 under abs() has no real zero: no knot
 *   nested: sign(sign(t - 1) + 1/2) is 1 right of 1 and -1 left: a jump
 *   of 2; |t - |t - 2|| is 2 right of 2 and 2t - 2 left of it: C^0, the
 *   derivative jumps by 0 - 2, and the outer argument's zero (at 1) is
 *   listed as not analysed */
static void test_knots_arguments(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B\nconst a\nparam t, u\n"
                             "s1 = abs(t^2 - 1)\ns2 = abs((t - 2)^3)\n"
                             "s3 = abs(t - a)\ns4 = t*abs(t - pi/2)\n"
                             "s5 = abs(t^2 - 2)\ns6 = sqrt(abs(t - 1))\n"
                             "s7 = abs(t - u)\ns8 = abs(t^2 + 1)*abs(t)\n"
                             "s9 = sign(sign(t - 1) + 1/2)\n"
                             "s10 = abs(t - abs(t - 2))\n"
                             "output s1, s2, s3, s4, s5, s6, s7, s8, s9, "
                             "s10\n");
    KnotList L;
    slong o = output(d, "s1");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 2);
    expect_knot(d, o, &L, "-1", 0, 0, "=4");
    expect_knot(d, o, &L, "1", 0, 0, "=4");
    knots_clear(&L, d);

    o = output(d, "s2");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    expect_knot(d, o, &L, "2", 2, 0, "=12"); /* a minimum: turns back */
    knots_clear(&L, d);

    o = output(d, "s3");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    expect_knot(d, o, &L, "a", 0, 0, "=2");
    knots_clear(&L, d);

    o = output(d, "s4");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    assert_true(L.k[0].analysed);
    assert_int_equal(L.k[0].continuity, 0);
    assert_true(L.k[0].approx > 1.5707 && L.k[0].approx < 1.5709);
    /* the jump is pi: its square over pi^2 is 1 ... compare with 2*t0 */
    {
        RatFun two_t;
        ratfun_init(two_t, &d->ring);
        ratfun_mul_si(two_t, L.k[0].t, 2, &d->ring);
        assert_true(ratfun_equal(two_t, L.k[0].jump, &d->ring));
        ratfun_clear(two_t, &d->ring);
    }
    knots_clear(&L, d);

    o = output(d, "s5");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 0);
    assert_int_equal(L.nskip, 1);
    assert_string_equal(L.skip[0], "t^2 - 2");
    knots_clear(&L, d);

    o = output(d, "s6");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    assert_false(L.k[0].analysed);
    assert_int_equal(L.k[0].continuity, 0);
    assert_int_equal(L.k[0].jump_order, 1);
    assert_non_null(L.k[0].why);
    knots_clear(&L, d);

    o = output(d, "s7");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 0);
    assert_int_equal(L.param, -1);
    assert_non_null(L.note);
    knots_clear(&L, d);

    o = output(d, "s8");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    expect_knot(d, o, &L, "0", 0, 0, "=2");
    knots_clear(&L, d);

    o = output(d, "s9");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    expect_knot(d, o, &L, "1", -1, -1, "=2");
    assert_int_equal(L.nskip, 1);
    knots_clear(&L, d);

    o = output(d, "s10");
    knots_analyse(&L, d, o);
    assert_int_equal(L.n, 1);
    expect_knot(d, o, &L, "2", 0, 0, "=-2");
    assert_int_equal(L.nskip, 1);
    knots_clear(&L, d);
    derived_free(d);
}

/* A declared range leaves out the knots beyond it (and abs(t) on [0, 3]
 * is t already) */
static void test_knots_range(void **state)
{
    (void)state;
    Derived *d = derive_text("param t in [0, 3]\n"
                             "s = abs(t) + abs(t - 1) + abs(t - 5)*abs(t + "
                             "1)*abs(t - 2)\n");
    KnotList L;
    knots_analyse(&L, d, 0);
    assert_int_equal(L.n, 2);
    assert_true(L.k[0].approx == 1 && L.k[1].approx == 2);
    knots_clear(&L, d);
    derived_free(d);
}

/* knots_one_sided: x = |t - 1|^3 + t: right of 1 it is (t - 1)^3 + t,
 * left -(t - 1)^3 + t; order 1: 1 and 1, order 3: 6 and -6, order 0: 1 */
static void test_knots_one_sided(void **state)
{
    (void)state;
    Derived *d = derive_text("param t\nx = abs(t - 1)^3 + t\n");
    RatFun one, v;
    ratfun_init(one, &d->ring);
    ratfun_init(v, &d->ring);
    ratfun_one(one, &d->ring);
    static const struct {
        int side;
        ulong j;
        slong want;
    } cases[] = {{1, 0, 1}, {-1, 0, 1},  {1, 1, 1}, {-1, 1, 1},
                 {1, 3, 6}, {-1, 3, -6}, {1, 4, 0}, {-1, 2, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        assert_int_equal(knots_one_sided(v, d, d->outputs[0].scalar, 0, one,
                                         cases[i].side, cases[i].j),
                         0);
        fmpq_t q;
        fmpq_init(q);
        assert_true(ratfun_get_fmpq(q, v, &d->ring));
        assert_true(fmpq_equal_si(q, cases[i].want));
        fmpq_clear(q);
    }
    ratfun_clear(v, &d->ring);
    ratfun_clear(one, &d->ring);
    derived_free(d);
}

/* Random scalar curves x = p0(t) + sum_i c_i(t)|t - k_i|^p_i (distinct
 * knots k_i = n_i/2, p_i odd, c_i of degree <= 2): at k_i only term i
 * jumps, by J_i(t) = 2 c_i(t)(t - k_i)^p_i; its first non-zero derivative
 * at k_i (fmpq_poly, independent of the tool) is the jump, its order minus
 * one the continuity. */
static void test_knots_random_sums(void **state)
{
    (void)state;
    flint_rand_t st;
    rand_init(st);
    for (int iter = 0; iter < 25; iter++) {
        enum { NK = 3 };
        slong kn[NK], p[NK], c[NK][3];
        char text[2048];
        int len = snprintf(text, sizeof text, "param t\nx = 1 + 2*t - t^3");
        for (int i = 0; i < NK; i++) {
            int dup;
            do {
                kn[i] = (slong)n_randint(st, 13) - 6;
                dup = 0;
                for (int j = 0; j < i; j++)
                    dup |= kn[j] == kn[i];
            } while (dup);
            p[i] = 2 * (slong)n_randint(st, 3) + 1;
            do {
                for (int j = 0; j < 3; j++)
                    c[i][j] = (slong)n_randint(st, 7) - 3;
            } while (!c[i][0] && !c[i][1] && !c[i][2]);
            len += snprintf(text + len, sizeof text - (size_t)len,
                            " + (%ld + %ld*t + %ld*t^2)*abs(t - %ld/2)^%ld",
                            (long)c[i][0], (long)c[i][1], (long)c[i][2],
                            (long)kn[i], (long)p[i]);
        }
        snprintf(text + len, sizeof text - (size_t)len, "\n");
        Derived *d = derive_text(text);
        KnotList L;
        knots_analyse(&L, d, 0);
        for (int i = 0; i < NK; i++) {
            /* J = 2 c(t) (t - k)^p */
            fmpq_poly_t J, lin, cp;
            fmpq_t k, v;
            fmpq_poly_init(J);
            fmpq_poly_init(lin);
            fmpq_poly_init(cp);
            fmpq_init(k);
            fmpq_init(v);
            fmpq_set_si(k, kn[i], 2);
            for (int j = 0; j < 3; j++)
                fmpq_poly_set_coeff_si(cp, j, 2 * c[i][j]);
            fmpq_poly_set_coeff_si(lin, 1, 1);
            fmpq_neg(v, k);
            fmpq_poly_set_coeff_fmpq(lin, 0, v);
            fmpq_poly_pow(J, lin, (ulong)p[i]);
            fmpq_poly_mul(J, J, cp);
            int order = 0;
            for (;; order++) {
                fmpq_poly_evaluate_fmpq(v, J, k);
                if (!fmpq_is_zero(v))
                    break;
                fmpq_poly_derivative(J, J);
            }
            char at[32], want[128];
            snprintf(at, sizeof at, "%ld/2", (long)kn[i]);
            char *vs = fmpq_get_str(NULL, 10, v);
            snprintf(want, sizeof want, "=%s", vs);
            flint_free(vs);
            if (order > KNOTS_MAX_ORDER) {
                const Knot *kk = knot_at(d, &L, at);
                assert_true(kk->c_more);
            } else {
                const Knot *kk = knot_at(d, &L, at);
                assert_true(kk->analysed);
                assert_int_equal(kk->continuity, order - 1);
                expect_jump(d, 0, kk, want);
            }
            fmpq_clear(v);
            fmpq_clear(k);
            fmpq_poly_clear(cp);
            fmpq_poly_clear(lin);
            fmpq_poly_clear(J);
        }
        assert_int_equal(L.n, NK);
        knots_clear(&L, d);
        derived_free(d);
    }
    flint_randclear(st);
}

/* derive --knots and --format json through the binary ($PC_BIN): the
 * triangle's knots with their orders, and the JSON's jumps read back */
static void test_knots_cli(void **state)
{
    (void)state;
    const char *bin = getenv("PC_BIN");
    if (!bin)
        bin = "build/pointcalc";
    char path[] = "/tmp/pc_knotsXXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("point O, X, Y\nparam t\n"
          "R = O + (X - O)*abs(t) + (Y - O)*t\n",
          f);
    fclose(f);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%s derive %s --knots", bin, path);
    FILE *p = popen(cmd, "r");
    char *buf = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&buf, &n);
    int ch;
    while ((ch = fgetc(p)) != EOF)
        fputc(ch, m);
    fclose(m);
    assert_int_equal(pclose(p), 0);
    /* d|t|/dt jumps by 2 at 0: the jump of R' is 2 (X - O); the tangents
     * Y - X (left) and Y + X - 2 O (right) are not parallel: G^0 */
    assert_non_null(
        strstr(buf, "\nR at t = 0: C^0, G^0; jump of dR/dt: -2*O + 2*X\n"));
    free(buf);
    snprintf(cmd, sizeof cmd, "%s derive %s --format json", bin, path);
    p = popen(cmd, "r");
    buf = NULL;
    m = open_memstream(&buf, &n);
    while ((ch = fgetc(p)) != EOF)
        fputc(ch, m);
    fclose(m);
    assert_int_equal(pclose(p), 0);
    assert_non_null(strstr(buf, "\"knots\": [{\"t\": \"0\", \"continuity\": "
                                "0, \"geometric\": 0, \"jump_order\": 1"));
    assert_non_null(strstr(buf, "\"jump\": {\"O\": \"-2\", \"X\": \"2\"}"));
    free(buf);
    snprintf(cmd, sizeof cmd, "%s derive %s --knots --format latex 2>/dev/null",
             bin, path);
    assert_int_equal(WEXITSTATUS(system(cmd)), 2);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_knots_square_c0),
        cmocka_unit_test(test_knots_triangle_c1),
        cmocka_unit_test(test_knots_square_c2),
        cmocka_unit_test(test_knots_spline_c2),
        cmocka_unit_test(test_knots_geometric),
        cmocka_unit_test(test_knots_arguments),
        cmocka_unit_test(test_knots_range),
        cmocka_unit_test(test_knots_one_sided),
        cmocka_unit_test(test_knots_random_sums),
        cmocka_unit_test(test_knots_cli),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
