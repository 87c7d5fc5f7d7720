/*
 * test_ratfun.c - exact rational functions: canonical form after every
 * operation, parsing and printing, error codes, and seeded random property
 * tests in the FLINT manner (identities that a wrong implementation breaks).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>
#include <flint/fmpq.h>

#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"
#include "tests/unit/rand_algebra.h"

/* the names of the fixture's ring, for rings of fewer variables */
static const char *const NAMES[] = {"t", "u", "v"};

static int setup(void **state)
{
    return fixture_setup(state, 3);
}

static int teardown(void **state)
{
    return fixture_teardown(state);
}

/* parses s into x, failing the test on any error */
static void parse(RatFun x, const char *s, const Ring *r)
{
    int rc = ratfun_set_str(x, s, r);
    if (rc != RATFUN_OK)
        fail_msg("cannot parse '%s': %d", s, rc);
    assert_true(ratfun_is_canonical(x, r));
}

/* x equals the text s */
static void assert_ratfun_str(const RatFun x, const char *s, const Ring *r)
{
    RatFun y;
    ratfun_init(y, r);
    parse(y, s, r);
    if (!ratfun_equal(x, y, r)) {
        char *g = ratfun_get_str(x, r);
        fail_msg("got %s, expected %s", g, s);
    }
    ratfun_clear(y, r);
}

/* printing x gives exactly s */
static void assert_get_str(const RatFun x, const char *s, const Ring *r)
{
    char *g = ratfun_get_str(x, r);
    assert_string_equal(g, s);
    flint_free(g);
}

/* ---- canonical form --------------------------------------------------- */

static void test_ratfun_init_is_canonical_zero(void **state)
{
    Fixture *f = *state;
    RatFun x;
    ratfun_init(x, &f->r);
    assert_true(ratfun_is_zero(x, &f->r));
    assert_true(ratfun_is_canonical(x, &f->r));
    assert_true(fmpz_mpoly_is_one(x->den, f->r.ctx));
    ratfun_clear(x, &f->r);
}

/* (t^2 - 1)/(2*t - 2) -> (t + 1)/2, content and polynomial factor cancel */
static void test_ratfun_canonicalise_gcd_reduction(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set_str_pretty(x->num, "t^2-1", (const char **)NAMES, r->ctx);
    fmpz_mpoly_set_str_pretty(x->den, "2*t-2", (const char **)NAMES, r->ctx);
    assert_false(ratfun_is_canonical(x, r));
    assert_int_equal(ratfun_canonicalise(x, r), RATFUN_OK);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "(t+1)/2", r);

    /* integer content only: 6*t*u/(4*v) -> 3*t*u/(2*v) */
    fmpz_mpoly_set_str_pretty(x->num, "6*t*u", (const char **)NAMES, r->ctx);
    fmpz_mpoly_set_str_pretty(x->den, "4*v", (const char **)NAMES, r->ctx);
    assert_false(ratfun_is_canonical(x, r));
    ratfun_canonicalise(x, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "3*t*u/(2*v)", r);
    ratfun_clear(x, r);
}

/* the denominator's leading coefficient is made positive */
static void test_ratfun_canonicalise_sign_normalised(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set_str_pretty(x->num, "t", (const char **)NAMES, r->ctx);
    fmpz_mpoly_set_str_pretty(x->den, "1-u^2", (const char **)NAMES, r->ctx);
    assert_false(ratfun_is_canonical(x, r));
    ratfun_canonicalise(x, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "-t/(u^2-1)", r);

    fmpz_mpoly_set_si(x->num, 4, r->ctx);
    fmpz_mpoly_set_si(x->den, -6, r->ctx);
    ratfun_canonicalise(x, r);
    assert_get_str(x, "-2/3", r);

    /* 0/(-5) is 0/1 */
    fmpz_mpoly_zero(x->num, r->ctx);
    fmpz_mpoly_set_si(x->den, -5, r->ctx);
    ratfun_canonicalise(x, r);
    assert_true(ratfun_is_zero(x, r));
    assert_true(ratfun_is_canonical(x, r));
    ratfun_clear(x, r);
}

static void test_ratfun_canonicalise_zero_den_rejected(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_gen(x->num, 0, r->ctx);
    fmpz_mpoly_zero(x->den, r->ctx);
    assert_int_equal(ratfun_canonicalise(x, r), RATFUN_EDIVZERO);
    assert_false(ratfun_is_canonical(x, r));
    ratfun_clear(x, r);
}

/* is_canonical must reject each kind of violation, or the other tests
 * would prove nothing */
static void test_ratfun_is_canonical_detects_violations(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set_si(x->num, 2, r->ctx);
    fmpz_mpoly_set_si(x->den, 4, r->ctx); /* content */
    assert_false(ratfun_is_canonical(x, r));
    fmpz_mpoly_set_si(x->num, 1, r->ctx);
    fmpz_mpoly_set_si(x->den, -3, r->ctx); /* sign */
    assert_false(ratfun_is_canonical(x, r));
    fmpz_mpoly_zero(x->num, r->ctx);
    fmpz_mpoly_set_si(x->den, 3, r->ctx); /* zero is 0/1 */
    assert_false(ratfun_is_canonical(x, r));
    fmpz_mpoly_set_si(x->den, 1, r->ctx);
    assert_true(ratfun_is_canonical(x, r));
    ratfun_clear(x, r);
}

/* ---- text ------------------------------------------------------------- */

static void test_ratfun_set_str_precedence(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);

    parse(x, "-t^2", r); /* -(t^2) */
    ratfun_gen(y, 0, r);
    ratfun_mul(y, y, y, r);
    ratfun_neg(y, y, r);
    assert_true(ratfun_equal(x, y, r));

    parse(x, "t/u*v", r); /* (t/u)*v */
    assert_get_str(x, "t*v/u", r);
    parse(x, "t^-2", r);
    assert_get_str(x, "1/t^2", r);
    parse(x, "t^(-2) - t^( +2 )", r);
    assert_ratfun_str(x, "(1 - t^4)/t^2", r);
    parse(x, "2^10", r);
    assert_get_str(x, "1024", r);
    parse(x, "--t", r);
    assert_get_str(x, "t", r);
    parse(x, "(t+1)^3/(t+1)", r);
    assert_get_str(x, "t^2+2*t+1", r);
    parse(x, "0^0", r);
    assert_true(ratfun_is_one(x, r));

    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* decimals are exact: 0.3 is 3/10, never a binary approximation */
static void test_ratfun_set_str_exact_decimals(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    fmpq_t q;
    ratfun_init(x, r);
    fmpq_init(q);

    parse(x, "0.3", r);
    assert_get_str(x, "3/10", r);
    parse(x, "0.1 + 0.2", r);
    assert_ratfun_str(x, "3/10", r);
    parse(x, ".5", r);
    assert_get_str(x, "1/2", r);
    parse(x, "1e-3", r);
    assert_get_str(x, "1/1000", r);
    parse(x, "2.5E+2", r);
    assert_get_str(x, "250", r);
    parse(x, "3.", r);
    assert_get_str(x, "3", r);
    parse(x, "0.125*t", r);
    assert_get_str(x, "t/8", r);
    parse(x, "123456789012345678901234567890.5", r);
    assert_true(ratfun_get_fmpq(q, x, r));
    assert_int_equal(fmpz_get_si(fmpq_denref(q)), 2);

    fmpq_clear(q);
    ratfun_clear(x, r);
}

/* each error has its code and leaves the result untouched */
static void test_ratfun_set_str_error_codes(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    static const struct {
        const char *text;
        int code;
    } cases[] = {
        {"", RATFUN_ESYNTAX},
        {"t+", RATFUN_ESYNTAX},
        {"(t", RATFUN_ESYNTAX},
        {"t)", RATFUN_ESYNTAX},
        {"2t", RATFUN_ESYNTAX},
        {"t^u", RATFUN_ESYNTAX},
        {"t^2^3", RATFUN_ESYNTAX},
        {"t^1.5", RATFUN_ESYNTAX},
        {"*t", RATFUN_ESYNTAX},
        {".", RATFUN_ESYNTAX},
        {"t $ u", RATFUN_ESYNTAX},
        {"w", RATFUN_ENAME},
        {"t + tt", RATFUN_ENAME},
        {"1/0", RATFUN_EDIVZERO},
        {"t/(u-u)", RATFUN_EDIVZERO},
        {"0^-1", RATFUN_EDIVZERO},
        {"(t-t)^(-2)", RATFUN_EDIVZERO},
        {"t^99999", RATFUN_EOVERFLOW},
        {"1e99999", RATFUN_EOVERFLOW},
    };
    RatFun x;
    ratfun_init(x, r);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        parse(x, "u/7", r);
        int rc = ratfun_set_str(x, cases[i].text, r);
        if (rc != cases[i].code)
            fail_msg("'%s': got %d, expected %d", cases[i].text, rc,
                     cases[i].code);
        assert_ratfun_str(x, "u/7", r); /* untouched */
    }
    ratfun_clear(x, r);
}

/* deep nesting is refused, not a stack overflow */
static void test_ratfun_set_str_deep_nesting_refused(void **state)
{
    Fixture *f = *state;
    size_t n = 100000;
    char *s = malloc(2 * n + 2);
    RatFun x;
    memset(s, '(', n);
    s[n] = '1';
    memset(s + n + 1, ')', n);
    s[2 * n + 1] = '\0';
    ratfun_init(x, &f->r);
    assert_int_equal(ratfun_set_str(x, s, &f->r), RATFUN_ESYNTAX);
    memset(s, '-', n);
    s[n] = '1';
    s[n + 1] = '\0';
    assert_int_equal(ratfun_set_str(x, s, &f->r), RATFUN_ESYNTAX);
    ratfun_clear(x, &f->r);
    free(s);
}

/* parentheses only where needed, and the text reads back */
static void test_ratfun_get_str_format(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    static const struct {
        const char *in, *out;
    } cases[] = {
        {"0", "0"},
        {"-7", "-7"},
        {"t^3/(2*t^2-2*t+1)", "t^3/(2*t^2-2*t+1)"},
        {"(t+1)/u^2", "(t+1)/u^2"},
        {"t/(2*u)", "t/(2*u)"},
        {"-t/u", "-t/u"},
        {"-2*t/(u*v)", "-2*t/(u*v)"},
        {"1/(1-t)", "-1/(t-1)"},
        {"(1-t)/(-3)", "(t-1)/3"},
    };
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        parse(x, cases[i].in, r);
        char *s = ratfun_get_str(x, r);
        if (strcmp(s, cases[i].out) != 0)
            fail_msg("'%s' printed as '%s', expected '%s'", cases[i].in, s,
                     cases[i].out);
        parse(y, s, r);
        assert_true(ratfun_equal(x, y, r));
        flint_free(s);
    }
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

static void test_ratfun_get_str_round_trip_random(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    for (slong i = 0; i < rand_iters(300); i++) {
        rand_ratfun(x, f->st, r);
        char *s = ratfun_get_str(x, r);
        assert_int_equal(ratfun_set_str(y, s, r), RATFUN_OK);
        if (!ratfun_equal(x, y, r))
            fail_msg("'%s' does not read back", s);
        flint_free(s);
    }
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* ---- fast paths with known answers ------------------------------------ */

static void test_ratfun_add_cancels_against_shared_factor(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    /* equal denominators: t/(t+1) + 1/(t+1) = 1 */
    parse(x, "t/(t+1)", r);
    parse(y, "1/(t+1)", r);
    ratfun_add(x, x, y, r);
    assert_true(ratfun_is_one(x, r));
    /* shared factor t of the dens also divides the new num */
    parse(x, "1/(t*(t+1))", r);
    parse(y, "2/(t*(t+2))", r);
    ratfun_sub(x, x, y, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_ratfun_str(x, "-1/((t+1)*(t+2))", r);
    /* integer denominators */
    parse(x, "t/6", r);
    parse(y, "t/10", r);
    ratfun_add(x, x, y, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "4*t/15", r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

static void test_ratfun_mul_cross_cancels(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    parse(x, "(t^2-1)/u", r);
    parse(y, "2*u^2/(3*t-3)", r);
    ratfun_mul(x, x, y, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "(2*t*u+2*u)/3", r);
    parse(y, "-3/u", r);
    assert_int_equal(ratfun_div(x, y, x, r), RATFUN_OK);
    assert_true(ratfun_is_canonical(x, r));
    assert_ratfun_str(x, "-9/(2*u^2*(t+1))", r);
    ratfun_mul_si(x, x, -6, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_ratfun_str(x, "27/(u^2*(t+1))", r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* ---- error codes ------------------------------------------------------ */

static void test_ratfun_div_by_zero_codes(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, z;
    ratfun_init(x, r);
    ratfun_init(z, r);
    parse(x, "t/u", r);
    assert_int_equal(ratfun_div(x, x, z, r), RATFUN_EDIVZERO);
    assert_ratfun_str(x, "t/u", r);
    assert_int_equal(ratfun_inv(x, z, r), RATFUN_EDIVZERO);
    assert_ratfun_str(x, "t/u", r);
    assert_int_equal(ratfun_pow_si(x, z, -3, r), RATFUN_EDIVZERO);
    assert_ratfun_str(x, "t/u", r);
    assert_int_equal(ratfun_pow_si(x, z, 0, r), RATFUN_OK);
    assert_true(ratfun_is_one(x, r));
    assert_int_equal(ratfun_pow_si(x, z, 5, r), RATFUN_OK);
    assert_true(ratfun_is_zero(x, r));
    /* 0/y is fine */
    parse(x, "t", r);
    assert_int_equal(ratfun_div(x, z, x, r), RATFUN_OK);
    assert_true(ratfun_is_zero(x, r));
    ratfun_clear(z, r);
    ratfun_clear(x, r);
}

/* x = 1/(t-1) at t := 1 has a pole: EPOLE, result untouched */
static void test_ratfun_compose_var_pole(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, s, res;
    ratfun_init(x, r);
    ratfun_init(s, r);
    ratfun_init(res, r);
    parse(x, "u/(t-1)", r);
    parse(s, "1", r);
    parse(res, "v", r);
    assert_int_equal(ratfun_compose_var(res, x, 0, s, r), RATFUN_EPOLE);
    assert_ratfun_str(res, "v", r);
    /* numerator may vanish: (t-1)/u at t := 1 is 0 */
    parse(x, "(t-1)/u", r);
    assert_int_equal(ratfun_compose_var(res, x, 0, s, r), RATFUN_OK);
    assert_true(ratfun_is_zero(res, r));
    /* substitution can create cancellation: t/(t-1) at t := 1/u */
    parse(x, "t/(t-1)", r);
    parse(s, "1/u", r);
    assert_int_equal(ratfun_compose_var(res, x, 0, s, r), RATFUN_OK);
    assert_true(ratfun_is_canonical(res, r));
    assert_ratfun_str(res, "-1/(u-1)", r);
    /* s depending on the variable itself: t := t^2/(t+1) */
    parse(x, "1/(t+2)", r);
    parse(s, "t^2/(t+1)", r);
    assert_int_equal(ratfun_compose_var(res, x, 0, s, r), RATFUN_OK);
    assert_ratfun_str(res, "(t+1)/(t^2+2*t+2)", r);
    ratfun_clear(res, r);
    ratfun_clear(s, r);
    ratfun_clear(x, r);
}

static void test_ratfun_evaluate_fmpq_pole(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    fmpq v[3];
    fmpq_t res;
    ratfun_init(x, r);
    fmpq_init(res);
    for (int i = 0; i < 3; i++)
        fmpq_init(v + i);
    parse(x, "(t^2+u)/(2*t-1)", r);
    fmpq_set_si(v + 0, 1, 2);
    fmpq_set_si(v + 1, 3, 1);
    fmpq_set_si(res, 7, 1);
    assert_int_equal(ratfun_evaluate_fmpq(res, x, v, r), RATFUN_EPOLE);
    assert_true(fmpq_equal_si(res, 7));
    fmpq_set_si(v + 0, 1, 3);
    assert_int_equal(ratfun_evaluate_fmpq(res, x, v, r), RATFUN_OK);
    /* (1/9 + 3)/(-1/3) = -28/3 */
    fmpq_set_si(v + 2, -28, 3);
    assert_true(fmpq_equal(res, v + 2));
    for (int i = 0; i < 3; i++)
        fmpq_clear(v + i);
    fmpq_clear(res);
    ratfun_clear(x, r);
}

/* ---- queries ---------------------------------------------------------- */

static void test_ratfun_queries_constant_depends_length(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x;
    fmpq_t q;
    ratfun_init(x, r);
    fmpq_init(q);
    parse(x, "-6/4", r);
    assert_true(ratfun_is_constant(x, r));
    assert_true(ratfun_get_fmpq(q, x, r));
    assert_true(fmpz_equal_si(fmpq_numref(q), -3));
    assert_true(fmpz_equal_si(fmpq_denref(q), 2));
    assert_int_equal(ratfun_length(x, r), 2);
    parse(x, "(t+u)/(t-1)", r);
    assert_false(ratfun_is_constant(x, r));
    assert_false(ratfun_get_fmpq(q, x, r));
    assert_true(ratfun_depends_on(x, 0, r));
    assert_true(ratfun_depends_on(x, 1, r));
    assert_false(ratfun_depends_on(x, 2, r));
    assert_false(ratfun_depends_on(x, 3, r));
    assert_int_equal(ratfun_length(x, r), 4);
    assert_false(ratfun_is_one(x, r));
    parse(x, "(t+1)/(1+t)", r);
    assert_true(ratfun_is_one(x, r));
    fmpq_set_si(q, -5, 7);
    ratfun_set_fmpq(x, q, r);
    assert_true(ratfun_is_canonical(x, r));
    assert_get_str(x, "-5/7", r);
    ratfun_set_si(x, -12, r);
    assert_get_str(x, "-12", r);
    assert_int_equal(ring_var_index(r, "u"), 1);
    assert_int_equal(ring_var_index(r, "w"), -1);
    fmpq_clear(q);
    ratfun_clear(x, r);
}

/* a ring without variables still does exact constants */
static void test_ratfun_no_variables_ring(void **state)
{
    (void)state;
    Ring r;
    RatFun x;
    fmpq_t q;
    ring_init(&r, 0, NULL);
    ratfun_init(x, &r);
    assert_int_equal(ratfun_set_str(x, "1/3 + 0.5", &r), RATFUN_OK);
    assert_get_str(x, "5/6", &r);
    assert_int_equal(ratfun_set_str(x, "t", &r), RATFUN_ENAME);
    /* no variables: vals may be NULL */
    fmpq_init(q);
    assert_int_equal(ratfun_evaluate_fmpq(q, x, NULL, &r), RATFUN_OK);
    assert_int_equal(fmpz_get_si(fmpq_numref(q)), 5);
    assert_int_equal(fmpz_get_si(fmpq_denref(q)), 6);
    fmpq_clear(q);
    ratfun_clear(x, &r);
    ring_clear(&r);
}

/* ---- random properties ------------------------------------------------ */

#define CHECK_CANON(x)                                                         \
    do {                                                                       \
        if (!ratfun_is_canonical(x, r)) {                                      \
            char *s_ = ratfun_get_str(x, r);                                   \
            fail_msg("not canonical: %s", s_);                                 \
        }                                                                      \
    } while (0)

/* (x + y) - y == x, and x - x == 0; canonical all along */
static void test_ratfun_add_sub_inverse(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, z;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(z, r);
    for (slong i = 0; i < rand_iters(500); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun(y, f->st, r);
        ratfun_add(z, x, y, r);
        CHECK_CANON(z);
        ratfun_sub(z, z, y, r);
        CHECK_CANON(z);
        assert_true(ratfun_equal(z, x, r));
        ratfun_sub(z, x, x, r);
        assert_true(ratfun_is_zero(z, r));
        CHECK_CANON(z);
    }
    ratfun_clear(z, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* x + y == y + x, (x + y) + z == x + (y + z) */
static void test_ratfun_add_commutative_associative(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, z, a, b;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(z, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < rand_iters(300); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun(y, f->st, r);
        rand_ratfun(z, f->st, r);
        ratfun_add(a, x, y, r);
        ratfun_add(b, y, x, r);
        assert_true(ratfun_equal(a, b, r));
        ratfun_add(a, a, z, r);
        ratfun_add(b, y, z, r);
        ratfun_add(b, x, b, r);
        CHECK_CANON(a);
        CHECK_CANON(b);
        assert_true(ratfun_equal(a, b, r));
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    ratfun_clear(z, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* (x*y)/y == x for y != 0 */
static void test_ratfun_mul_div_inverse(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, z;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(z, r);
    for (slong i = 0; i < rand_iters(500); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun_nz(y, f->st, r);
        ratfun_mul(z, x, y, r);
        CHECK_CANON(z);
        assert_int_equal(ratfun_div(z, z, y, r), RATFUN_OK);
        CHECK_CANON(z);
        assert_true(ratfun_equal(z, x, r));
    }
    ratfun_clear(z, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* (x/y)*(y/x) == 1 and x * inv(x) == 1 */
static void test_ratfun_mul_quotients_is_one(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, a, b;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < rand_iters(300); i++) {
        rand_ratfun_nz(x, f->st, r);
        rand_ratfun_nz(y, f->st, r);
        assert_int_equal(ratfun_div(a, x, y, r), RATFUN_OK);
        assert_int_equal(ratfun_div(b, y, x, r), RATFUN_OK);
        CHECK_CANON(a);
        CHECK_CANON(b);
        ratfun_mul(a, a, b, r);
        assert_true(ratfun_is_one(a, r));
        assert_int_equal(ratfun_inv(b, x, r), RATFUN_OK);
        CHECK_CANON(b);
        ratfun_mul(b, b, x, r);
        assert_true(ratfun_is_one(b, r));
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* x*(y + z) == x*y + x*z and x*(y - z) == x*y - x*z */
static void test_ratfun_mul_distributive(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, z, a, b, c;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(z, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(c, r);
    for (slong i = 0; i < rand_iters(300); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun(y, f->st, r);
        rand_ratfun(z, f->st, r);
        ratfun_add(a, y, z, r);
        ratfun_mul(a, x, a, r);
        ratfun_mul(b, x, y, r);
        ratfun_mul(c, x, z, r);
        ratfun_add(b, b, c, r);
        CHECK_CANON(a);
        CHECK_CANON(b);
        assert_true(ratfun_equal(a, b, r));
        ratfun_sub(a, y, z, r);
        ratfun_mul(a, a, x, r);
        ratfun_mul(b, y, x, r);
        ratfun_sub(b, b, c, r);
        assert_true(ratfun_equal(a, b, r));
    }
    ratfun_clear(c, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    ratfun_clear(z, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* every result may alias every input: compare with unaliased results */
static void test_ratfun_ops_alias_inputs(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, want, got;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(want, r);
    ratfun_init(got, r);
    for (slong i = 0; i < rand_iters(200); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun_nz(y, f->st, r);
        for (int op = 0; op < 4; op++) {
            /* want = x op y, then got = x; got = got op y and
             * got = y; got = x op got */
            for (int side = 0; side < 2; side++) {
                switch (op) {
                case 0:
                    ratfun_add(want, x, y, r);
                    break;
                case 1:
                    ratfun_sub(want, x, y, r);
                    break;
                case 2:
                    ratfun_mul(want, x, y, r);
                    break;
                default:
                    ratfun_div(want, x, y, r);
                    break;
                }
                ratfun_set(got, side == 0 ? x : y, r);
                const RatFunStruct *a = side == 0 ? got : x;
                const RatFunStruct *b = side == 0 ? y : got;
                switch (op) {
                case 0:
                    ratfun_add(got, a, b, r);
                    break;
                case 1:
                    ratfun_sub(got, a, b, r);
                    break;
                case 2:
                    ratfun_mul(got, a, b, r);
                    break;
                default:
                    ratfun_div(got, a, b, r);
                    break;
                }
                assert_true(ratfun_equal(got, want, r));
            }
        }
        /* x op x */
        ratfun_set(got, x, r);
        ratfun_add(got, got, got, r);
        ratfun_mul_si(want, x, 2, r);
        assert_true(ratfun_equal(got, want, r));
        ratfun_set(got, x, r);
        ratfun_mul(got, got, got, r);
        ratfun_pow_si(want, x, 2, r);
        assert_true(ratfun_equal(got, want, r));
        ratfun_set(got, y, r);
        ratfun_div(got, got, got, r);
        assert_true(ratfun_is_one(got, r));
    }
    ratfun_clear(got, r);
    ratfun_clear(want, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* x^e by repeated multiplication, for e in -3..3; mul_si == mul by c */
static void test_ratfun_pow_si_matches_mul(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, p, q, c;
    ratfun_init(x, r);
    ratfun_init(p, r);
    ratfun_init(q, r);
    ratfun_init(c, r);
    for (slong i = 0; i < rand_iters(100); i++) {
        rand_ratfun_nz(x, f->st, r);
        ratfun_one(q, r);
        for (slong e = 0; e <= 3; e++) {
            assert_int_equal(ratfun_pow_si(p, x, e, r), RATFUN_OK);
            CHECK_CANON(p);
            assert_true(ratfun_equal(p, q, r));
            assert_int_equal(ratfun_pow_si(p, x, -e, r), RATFUN_OK);
            CHECK_CANON(p);
            ratfun_mul(p, p, q, r);
            assert_true(ratfun_is_one(p, r));
            ratfun_mul(q, q, x, r);
        }
        slong k = (slong)n_randint(f->st, 41) - 20;
        ratfun_mul_si(p, x, k, r);
        CHECK_CANON(p);
        ratfun_set_si(c, k, r);
        ratfun_mul(q, x, c, r);
        assert_true(ratfun_equal(p, q, r));
    }
    ratfun_clear(c, r);
    ratfun_clear(q, r);
    ratfun_clear(p, r);
    ratfun_clear(x, r);
}

/* (x*y)' == x'*y + x*y' and (x/y)' == (x'*y - x*y')/y^2 */
/* the k-th derivative in one reduction equals k single steps, and the
 * denominators that are not square-free (x^2 (x+1)^3) cancel right */
static void test_ratfun_derivative_n_matches_steps(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, a, b;
    ratfun_init(x, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < rand_iters(150); i++) {
        slong var = (slong)n_randint(f->st, 3);
        ulong k = n_randint(f->st, 5);
        rand_ratfun(x, f->st, r);
        if (i % 3 == 0) { // a repeated factor in the denominator
            ratfun_mul(a, x, x, r);
            if (ratfun_inv(b, a, r) == 0)
                ratfun_swap(x, b, r);
        }
        ratfun_derivative_n(a, x, var, k, r);
        CHECK_CANON(a);
        ratfun_set(b, x, r);
        for (ulong j = 0; j < k; j++)
            ratfun_derivative(b, b, var, r);
        assert_true(ratfun_equal(a, b, r));
    }
    /* d^3/dt^3 1/(t^2 (t+1)^3) by hand: -(120 t^3 + 120 t^2 + 60 t + 12)...
     * checked against the steps instead of a printed form */
    parse(x, "1/(t^2*(t+1)^3)", r);
    ratfun_derivative_n(a, x, 0, 3, r);
    ratfun_derivative(b, x, 0, r);
    ratfun_derivative(b, b, 0, r);
    ratfun_derivative(b, b, 0, r);
    assert_true(ratfun_equal(a, b, r));
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    ratfun_clear(x, r);
}

static void test_ratfun_derivative_product_rule(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, a, b, c;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(c, r);
    for (slong i = 0; i < rand_iters(200); i++) {
        slong var = (slong)n_randint(f->st, 3);
        rand_ratfun(x, f->st, r);
        rand_ratfun_nz(y, f->st, r);
        ratfun_mul(a, x, y, r);
        ratfun_derivative(a, a, var, r);
        CHECK_CANON(a);
        ratfun_derivative(b, x, var, r);
        CHECK_CANON(b);
        ratfun_mul(b, b, y, r);
        ratfun_derivative(c, y, var, r);
        ratfun_mul(c, c, x, r);
        ratfun_add(b, b, c, r);
        assert_true(ratfun_equal(a, b, r));

        ratfun_div(a, x, y, r);
        ratfun_derivative(a, a, var, r);
        CHECK_CANON(a);
        ratfun_derivative(b, x, var, r);
        ratfun_mul(b, b, y, r);
        ratfun_derivative(c, y, var, r);
        ratfun_mul(c, c, x, r);
        ratfun_sub(b, b, c, r);
        ratfun_mul(c, y, y, r);
        ratfun_div(b, b, c, r);
        assert_true(ratfun_equal(a, b, r));
    }
    /* d/dt t^3/(t+1) = (2*t^3+3*t^2)/(t+1)^2 */
    parse(x, "t^3/(t+1)", r);
    ratfun_derivative(x, x, 0, r);
    assert_ratfun_str(x, "(2*t^3+3*t^2)/(t+1)^2", r);
    ratfun_derivative(x, x, 1, r);
    assert_true(ratfun_is_zero(x, r));
    ratfun_clear(c, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* evaluation is a ring homomorphism: eval(x op y) == eval(x) op eval(y)
 * wherever no denominator vanishes */
static void test_ratfun_evaluate_fmpq_homomorphism(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, y, z;
    fmpq v[3];
    fmpq_t ex, ey, ez, e;
    slong checked = 0;
    ratfun_init(x, r);
    ratfun_init(y, r);
    ratfun_init(z, r);
    fmpq_init(ex);
    fmpq_init(ey);
    fmpq_init(ez);
    fmpq_init(e);
    for (int i = 0; i < 3; i++)
        fmpq_init(v + i);
    for (slong i = 0; i < rand_iters(300); i++) {
        rand_ratfun(x, f->st, r);
        rand_ratfun(y, f->st, r);
        for (int k = 0; k < 3; k++)
            rand_fmpq(v + k, f->st);
        if (ratfun_evaluate_fmpq(ex, x, v, r) != RATFUN_OK ||
            ratfun_evaluate_fmpq(ey, y, v, r) != RATFUN_OK)
            continue;
        checked++;
        ratfun_add(z, x, y, r);
        assert_int_equal(ratfun_evaluate_fmpq(ez, z, v, r), RATFUN_OK);
        fmpq_add(e, ex, ey);
        assert_true(fmpq_equal(e, ez));
        ratfun_sub(z, x, y, r);
        assert_int_equal(ratfun_evaluate_fmpq(ez, z, v, r), RATFUN_OK);
        fmpq_sub(e, ex, ey);
        assert_true(fmpq_equal(e, ez));
        ratfun_mul(z, x, y, r);
        assert_int_equal(ratfun_evaluate_fmpq(ez, z, v, r), RATFUN_OK);
        fmpq_mul(e, ex, ey);
        assert_true(fmpq_equal(e, ez));
        if (!fmpq_is_zero(ey)) {
            ratfun_div(z, x, y, r);
            assert_int_equal(ratfun_evaluate_fmpq(ez, z, v, r), RATFUN_OK);
            fmpq_div(e, ex, ey);
            assert_true(fmpq_equal(e, ez));
        }
    }
    assert_true(checked > rand_iters(300) / 2);
    for (int i = 0; i < 3; i++)
        fmpq_clear(v + i);
    fmpq_clear(e);
    fmpq_clear(ez);
    fmpq_clear(ey);
    fmpq_clear(ex);
    ratfun_clear(z, r);
    ratfun_clear(y, r);
    ratfun_clear(x, r);
}

/* x(var := s) evaluated at v == x evaluated at v with v[var] := s(v) */
static void test_ratfun_compose_var_then_evaluate(void **state)
{
    Fixture *f = *state;
    const Ring *r = &f->r;
    RatFun x, s, z;
    fmpq v[3], w[3];
    fmpq_t a, b;
    slong checked = 0;
    ratfun_init(x, r);
    ratfun_init(s, r);
    ratfun_init(z, r);
    fmpq_init(a);
    fmpq_init(b);
    for (int i = 0; i < 3; i++) {
        fmpq_init(v + i);
        fmpq_init(w + i);
    }
    for (slong i = 0; i < rand_iters(300); i++) {
        slong var = (slong)n_randint(f->st, 3);
        rand_ratfun(x, f->st, r);
        rand_ratfun(s, f->st, r);
        for (int k = 0; k < 3; k++)
            rand_fmpq(v + k, f->st);
        int st = ratfun_compose_var(z, x, var, s, r);
        if (st == RATFUN_EPOLE)
            continue;
        assert_int_equal(st, RATFUN_OK);
        CHECK_CANON(z);
        if (ratfun_evaluate_fmpq(b, s, v, r) != RATFUN_OK)
            continue;
        for (int k = 0; k < 3; k++)
            fmpq_set(w + k, v + k);
        fmpq_set(w + var, b);
        if (ratfun_evaluate_fmpq(a, x, w, r) != RATFUN_OK ||
            ratfun_evaluate_fmpq(b, z, v, r) != RATFUN_OK)
            continue;
        checked++;
        assert_true(fmpq_equal(a, b));
    }
    assert_true(checked > rand_iters(300) / 3);
    for (int i = 0; i < 3; i++) {
        fmpq_clear(w + i);
        fmpq_clear(v + i);
    }
    fmpq_clear(b);
    fmpq_clear(a);
    ratfun_clear(z, r);
    ratfun_clear(s, r);
    ratfun_clear(x, r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ratfun_init_is_canonical_zero),
        cmocka_unit_test(test_ratfun_canonicalise_gcd_reduction),
        cmocka_unit_test(test_ratfun_canonicalise_sign_normalised),
        cmocka_unit_test(test_ratfun_canonicalise_zero_den_rejected),
        cmocka_unit_test(test_ratfun_is_canonical_detects_violations),
        cmocka_unit_test(test_ratfun_set_str_precedence),
        cmocka_unit_test(test_ratfun_set_str_exact_decimals),
        cmocka_unit_test(test_ratfun_set_str_error_codes),
        cmocka_unit_test(test_ratfun_set_str_deep_nesting_refused),
        cmocka_unit_test(test_ratfun_get_str_format),
        cmocka_unit_test(test_ratfun_get_str_round_trip_random),
        cmocka_unit_test(test_ratfun_add_cancels_against_shared_factor),
        cmocka_unit_test(test_ratfun_mul_cross_cancels),
        cmocka_unit_test(test_ratfun_div_by_zero_codes),
        cmocka_unit_test(test_ratfun_compose_var_pole),
        cmocka_unit_test(test_ratfun_evaluate_fmpq_pole),
        cmocka_unit_test(test_ratfun_queries_constant_depends_length),
        cmocka_unit_test(test_ratfun_no_variables_ring),
        cmocka_unit_test(test_ratfun_add_sub_inverse),
        cmocka_unit_test(test_ratfun_add_commutative_associative),
        cmocka_unit_test(test_ratfun_mul_div_inverse),
        cmocka_unit_test(test_ratfun_mul_quotients_is_one),
        cmocka_unit_test(test_ratfun_mul_distributive),
        cmocka_unit_test(test_ratfun_ops_alias_inputs),
        cmocka_unit_test(test_ratfun_pow_si_matches_mul),
        cmocka_unit_test(test_ratfun_derivative_n_matches_steps),
        cmocka_unit_test(test_ratfun_derivative_product_rule),
        cmocka_unit_test(test_ratfun_evaluate_fmpq_homomorphism),
        cmocka_unit_test(test_ratfun_compose_var_then_evaluate),
    };
    int fails = cmocka_run_group_tests(tests, setup, teardown);
    flint_cleanup_master();
    return fails;
}
