/*
 * test_sign.c - the sign proofs of compiler/algebra/kernel_sign.c, by random
 * property tests against exact evaluation:
 *
 *   - random polynomials in three declared variables (random intervals:
 *     ends present or not, open or closed) and in sin/cos of the first:
 *     every sign kernel_sign_poly proves holds at random exact points of
 *     the box (ends included where closed), sin and cos taken at a random
 *     angle (their double values are exact rationals in [-1, 1]);
 *   - the ends it records as assumed are enough: the sign still holds at
 *     points beyond every end it did not record;
 *   - hand cases: strictness from open ends, t (1 - t) >= 0 on [0, 1] by
 *     its factors, sign(e^2 - 1) = -1 on (0, 1), nothing proved where the
 *     sign changes.
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

#include <flint/fmpq.h>

#include "compiler/algebra/kernel.h"

enum { NDECL = 3, NSAMPLES = 60, NPOLYS = 400 };

typedef struct Box {
    int has_lo[NDECL], has_hi[NDECL], lo_open[NDECL], hi_open[NDECL];
    slong lo[NDECL], hi[NDECL]; // integers / 4
} Box;

typedef struct World {
    Ring r;
    Kernels K;
    slong vsin, vcos; // the ring variables of sin(x0), cos(x0)
} World;

static void world_init(World *w)
{
    static const char *const names[] = {"x0", "x1", "x2", "k0", "k1",
                                        "k2", "k3", "k4", "k5", "k6"};
    ring_init(&w->r, 10, names);
    kernels_init(&w->K, &w->r, NDECL, 7);
    RatFun x, s;
    ratfun_init(x, &w->r);
    ratfun_init(s, &w->r);
    ratfun_gen(x, 0, &w->r);
    assert_int_equal(kernel_apply(&w->K, s, KF_SIN, x, NULL), 0);
    w->vsin = w->vcos = -1;
    for (slong i = 0; i < w->K.n; i++) {
        if (w->K.k[i].fn == KF_SIN)
            w->vsin = w->K.k[i].var;
        if (w->K.k[i].fn == KF_COS)
            w->vcos = w->K.k[i].var;
    }
    assert_true(w->vsin >= 0 && w->vcos >= 0);
    ratfun_clear(s, &w->r);
    ratfun_clear(x, &w->r);
}

static void world_clear(World *w)
{
    kernels_clear(&w->K);
    ring_clear(&w->r);
}

/* declares the box and forgets what was assumed */
static void set_box(World *w, const Box *b)
{
    for (int v = 0; v < NDECL; v++) {
        KRange *g = &w->K.range[v];
        g->has_lo = g->has_hi = 0;
        fmpq_t lo, hi;
        fmpq_init(lo);
        fmpq_init(hi);
        fmpq_set_si(lo, b->lo[v], 4);
        fmpq_set_si(hi, b->hi[v], 4);
        kernels_set_range(&w->K, v, b->has_lo[v] ? lo : NULL, b->lo_open[v],
                          b->has_hi[v] ? hi : NULL, b->hi_open[v]);
        fmpq_clear(hi);
        fmpq_clear(lo);
        w->K.used[v] = 0;
    }
}

static void random_box(Box *b, flint_rand_t rs)
{
    for (int v = 0; v < NDECL; v++) {
        b->has_lo[v] = n_randint(rs, 4) != 0;
        b->has_hi[v] = n_randint(rs, 3) == 0;
        b->lo[v] = (slong)n_randint(rs, 9) - 4;
        b->hi[v] = b->lo[v] + 1 + (slong)n_randint(rs, 8);
        b->lo_open[v] = (int)n_randint(rs, 2);
        b->hi_open[v] = (int)n_randint(rs, 2);
    }
}

/* a random polynomial in x0, x1, x2, sin(x0), cos(x0): a few terms with
 * small coefficients, mostly of one sign so that some signs are provable,
 * sometimes a product of two such (for the factor-by-factor proofs) */
static void random_poly(fmpz_mpoly_t p, const World *w, flint_rand_t rs)
{
    const fmpz_mpoly_ctx_struct *ctx = w->r.ctx;
    slong vars[5] = {0, 1, 2, w->vsin, w->vcos};
    fmpz_mpoly_t f, m;
    fmpz_mpoly_init(f, ctx);
    fmpz_mpoly_init(m, ctx);
    fmpz_mpoly_one(p, ctx);
    int nf = n_randint(rs, 3) == 0 ? 2 : 1;
    for (int k = 0; k < nf; k++) {
        fmpz_mpoly_zero(f, ctx);
        int nt = 1 + (int)n_randint(rs, 4), neg = n_randint(rs, 5) == 0;
        for (int i = 0; i < nt; i++) {
            fmpz_mpoly_set_si(m, 1 + (slong)n_randint(rs, 5), ctx);
            if (neg || n_randint(rs, 6) == 0)
                fmpz_mpoly_neg(m, m, ctx);
            for (int j = 0; j < 2; j++) {
                slong v = vars[n_randint(rs, 5)];
                fmpz_mpoly_t g;
                fmpz_mpoly_init(g, ctx);
                fmpz_mpoly_gen(g, v, ctx);
                fmpz_mpoly_pow_ui(g, g, n_randint(rs, 3), ctx);
                fmpz_mpoly_mul(m, m, g, ctx);
                fmpz_mpoly_clear(g, ctx);
            }
            fmpz_mpoly_add(f, f, m, ctx);
        }
        if (fmpz_mpoly_is_zero(f, ctx))
            fmpz_mpoly_one(f, ctx);
        fmpz_mpoly_mul(p, p, f, ctx);
    }
    fmpz_mpoly_clear(m, ctx);
    fmpz_mpoly_clear(f, ctx);
}

/* a random rational in the box's side of v (beyond: past every end
 * that is not in keep: 1 lower, 2 upper) */
static void random_in(fmpq_t x, const Box *b, int v, int keep, flint_rand_t rs)
{
    int has_lo = b->has_lo[v] && (keep & 1),
        has_hi = b->has_hi[v] && (keep & 2);
    slong lo = has_lo ? b->lo[v] * 64 : -2000,
          hi = has_hi ? b->hi[v] * 64 : 2000;
    if (has_lo && !has_hi)
        hi = lo + 2000;
    if (has_hi && !has_lo)
        lo = hi - 2000;
    /* ends themselves a fifth of the time where closed */
    slong n;
    ulong r = n_randint(rs, 10);
    if (r == 0 && has_lo && !b->lo_open[v])
        n = lo;
    else if (r == 1 && has_hi && !b->hi_open[v])
        n = hi;
    else
        n = lo + 1 + (slong)n_randint(rs, (ulong)(hi - lo - 1));
    fmpq_set_si(x, n, 256);
}

/* r = x exactly (a double is a dyadic rational) */
static void set_double(fmpq_t r, double x)
{
    int e;
    double m = frexp(x, &e); /* x = m 2^e, m in [1/2, 1) */
    fmpz_t n;
    fmpz_init(n);
    fmpz_set_d(n, ldexp(m, 53));
    fmpq_set_fmpz(r, n);
    if (e - 53 >= 0)
        fmpq_mul_2exp(r, r, (ulong)(e - 53));
    else
        fmpq_div_2exp(r, r, (ulong)(53 - e));
    fmpz_clear(n);
}

static int sign_holds(int s, const fmpq_t v)
{
    int g = fmpq_sgn(v);
    return s == 2 ? g > 0 : s == 1 ? g >= 0 : s == -1 ? g <= 0 : g < 0;
}

static void test_random_signs_hold(void **state)
{
    (void)state;
    World w;
    world_init(&w);
    flint_rand_t rs;
    flint_randinit(rs);
    fmpz_mpoly_t p;
    fmpz_mpoly_init(p, w.r.ctx);
    fmpq *vals = _fmpq_vec_init(w.r.nvars);
    fmpq_t v;
    fmpq_init(v);
    RatFun pr;
    ratfun_init(pr, &w.r);
    int proved = 0, strict = 0, dropped = 0;
    for (int k = 0; k < NPOLYS; k++) {
        Box b;
        random_box(&b, rs);
        set_box(&w, &b);
        random_poly(p, &w, rs);
        fmpz_mpoly_set(pr->num, p, w.r.ctx);
        fmpz_mpoly_one(pr->den, w.r.ctx);
        int s = kernel_sign_poly(&w.K, p);
        if (!s)
            continue;
        proved++;
        strict += abs(s) == 2;
        /* in the box, and beyond the ends not assumed */
        for (int beyond = 0; beyond < 2; beyond++)
            for (int i = 0; i < NSAMPLES; i++) {
                for (int x = 0; x < NDECL; x++) {
                    int keep = beyond ? w.K.used[x] : 3;
                    dropped += beyond && i == 0 && keep != 3;
                    random_in(vals + x, &b, x, keep, rs);
                }
                double a = (double)n_randint(rs, 100000) / 7919.0;
                set_double(vals + w.vsin, sin(a));
                set_double(vals + w.vcos, cos(a));
                assert_int_equal(ratfun_evaluate_fmpq(v, pr, vals, &w.r), 0);
                if (!sign_holds(s, v)) {
                    char *t = fmpz_mpoly_get_str_pretty(p, NULL, w.r.ctx);
                    fail_msg("sign %d claimed for %s (%s), value %s", s, t,
                             beyond ? "beyond the unassumed ends" : "in box",
                             fmpq_get_str(NULL, 10, v));
                }
            }
    }
    /* the test exercises what it should */
    assert_true(proved > NPOLYS / 4);
    assert_true(strict > 10);
    assert_true(dropped > 10);
    ratfun_clear(pr, &w.r);
    fmpq_clear(v);
    _fmpq_vec_clear(vals, w.r.nvars);
    fmpz_mpoly_clear(p, w.r.ctx);
    flint_randclear(rs);
    world_clear(&w);
}

/* the sign of the polynomial written as text in x0, x1, x2 */
static int sign_of(World *w, const Box *b, const char *text)
{
    const char *names[] = {"x0", "x1", "x2", "k0", "k1",
                           "k2", "k3", "k4", "k5", "k6"};
    fmpz_mpoly_t p;
    fmpz_mpoly_init(p, w->r.ctx);
    assert_int_equal(fmpz_mpoly_set_str_pretty(p, text, names, w->r.ctx), 0);
    set_box(w, b);
    int s = kernel_sign_poly(&w->K, p);
    fmpz_mpoly_clear(p, w->r.ctx);
    return s;
}

static void test_sign_cases(void **state)
{
    (void)state;
    World w;
    world_init(&w);
    /* x0 in [0, 1] (lo, hi = 0, 4 quarters), x1 in (0, 1), x2 free */
    Box b = {{1, 1, 0}, {1, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 0}, {4, 4, 0}};
    assert_int_equal(sign_of(&w, &b, "x0"), 1);      /* >= 0 */
    assert_int_equal(w.K.used[0], 1);                /* lo only */
    assert_int_equal(sign_of(&w, &b, "x1"), 2);      /* > 0: open */
    assert_int_equal(sign_of(&w, &b, "x0 - 2"), -2); /* hi only */
    assert_int_equal(w.K.used[0], 2);
    assert_int_equal(sign_of(&w, &b, "x0 - x0^2"), 1); /* factors */
    assert_int_equal(sign_of(&w, &b, "x1^2 - 1"), -2); /* (0, 1) */
    assert_int_equal(w.K.used[1], 3);                  /* both ends */
    assert_int_equal(sign_of(&w, &b, "x2^2 + 1"), 2);  /* even power */
    assert_int_equal(sign_of(&w, &b, "x2^2"), 1);
    assert_int_equal(sign_of(&w, &b, "x2"), 0);       /* unknown */
    assert_int_equal(sign_of(&w, &b, "3*x0 - 1"), 0); /* changes */
    assert_int_equal(sign_of(&w, &b, "2*x0 - 1"), 0);
    assert_int_equal(sign_of(&w, &b, "x0*x2^2"), 1);
    assert_int_equal(sign_of(&w, &b, "-x1*x2^2 - x1"), -2);
    world_clear(&w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sign_cases),
        cmocka_unit_test(test_random_signs_hold),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
