/*
 * test_book.c - golden tests of how derive prints (compiler/print/book_*.c):
 * every rule of book.h with its expected text written by hand from the
 * mathematics, not taken from the printer.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_poly_factor.h>

#include "base/budget.h"
#include "compiler/algebra/ring.h"
#include "compiler/print/book.h"
#include "compiler/print/format.h"
#include "compiler/print/latexbreak.h"
#include "libpointcalc.h"

/* derives src and prints it in style st with options; returns the text */
static char *printed_ex(const char *src, FormatStyle st, int width,
                        slong origin)
{
    Derived *d = derive_source("g.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (width > 0) {
        BookOptions o = {
            .latex = st == FMT_LATEX, .width = width, .origin = origin};
        for (slong i = 0; i < d->noutputs; i++) {
            char *s = book_output(d, &d->outputs[i], &o);
            fputs(s, f);
            free(s);
        }
    } else {
        format_derived(f, d, st, origin);
    }
    fclose(f);
    derived_free(d);
    return buf;
}

static void expect(const char *src, FormatStyle st, const char *want)
{
    char *got = printed_ex(src, st, 0, -1);
    assert_string_equal(got, want);
    free(got);
}

#define DESARGUES                                                              \
    "point A, B, C, D\nparam t in [0, 1]\n"                                    \
    "P = along(A, C, t)\nQ = along(C, B, t)\nK = along(B, D, t)\n"             \
    "N = along(P, Q, t)\nJ = along(Q, K, t)\n"                                 \
    "T = meet(line(P, Q), line(A, B))\nS = meet(line(Q, K), line(C, D))\n"     \
    "M = meet(line(S, N), line(T, J))\n"

/* the denominator 2t^2 - 2t + 1 is t^2 + (1 - t)^2 in the basis of t and
 * 1 - t: two terms for three; the weights factored; ascending order */
static void test_bernstein_denominator(void **state)
{
    (void)state;
    expect(DESARGUES "output M\n", FMT_TEXT,
           "M = (A*(1 - t)^3 + B*t^2*(1 - t) + C*t*(1 - t)^2 + D*t^3)"
           "/((1 - t)^2 + t^2)\n");
    expect(DESARGUES "output M\n", FMT_LATEX,
           "\\[ M = \\frac{A \\bar{t}^{3} + B t^{2} \\bar{t} + C t "
           "\\bar{t}^{2} + D t^{3}}{\\bar{t}^{2} + t^{2}} \\]\n");
    /* 1 - 3t + 3t^2 has three terms in either basis: expanded wins,
     * ascending */
    expect(DESARGUES "M_AD = subst(M, A, D)\noutput M_AD\n", FMT_TEXT,
           "M_AD = (B*t^2*(1 - t) + C*t*(1 - t)^2 + D*(1 - 3*t + 3*t^2))"
           "/((1 - t)^2 + t^2)\n");
}

/* the example: the canonical denominator's leading coefficient is
 * negative in FLINT's order (-2*w*u^2); printed, the denominator's first
 * term is positive and the numerator is not all minus */
static void test_sign_and_basis_of_the_conic(void **state)
{
    (void)state;
    static const char src[] = "point A, B, C\nparam u in [0, 1]\nconst w\n"
                              "R = (A*(1-u)^2 + 2*w*C*u*(1-u) + B*u^2)/"
                              "((1-u)^2 + 2*w*u*(1-u) + u^2)\n";
    expect(src, FMT_TEXT,
           "R = (A*(1 - u)^2 + B*u^2 + 2*w*C*u*(1 - u))"
           "/((1 - u)^2 + 2*w*u*(1 - u) + u^2)\n");
    expect(src, FMT_LATEX,
           "\\[ R = \\frac{A \\bar{u}^{2} + B u^{2} + 2 w C u \\bar{u}}"
           "{\\bar{u}^{2} + 2 w u \\bar{u} + u^{2}} \\]\n");
}

/* collected by the powers of a const, each coefficient factored: the
 * book's kq(1 - 2v)^2 + 2v(1 - v) for 4v^2kq - 2v^2 - 4vkq + 2v + kq, in
 * ascending powers of kq (the one ordering rule) */
static void test_collected_by_a_const(void **state)
{
    (void)state;
    expect("param v in [0, 1]\nconst kq\n"
           "s = 4*v^2*kq - 2*v^2 - 4*v*kq + 2*v + kq\n",
           FMT_TEXT, "s = 2*v*(1 - v) + kq*(1 - 2*v)^2\n");
    expect("param v in [0, 1]\nconst kq\n"
           "s = 4*v^2*kq - 2*v^2 - 4*v*kq + 2*v + kq\n",
           FMT_LATEX,
           "\\[ s = 2 v \\bar{v} + \\mathit{kq} \\left(1 - 2 "
           "v\\right)^{2} \\]\n");
}

/* factors: consts, then params (x before 1 - x), then sums by degree;
 * the same polynomial entered in any order prints the same */
static void test_factor_order(void **state)
{
    (void)state;
    expect("param t in [0, 1]\nconst a\ns = (1 + t^2)*(2 + t)*t*(1 - t)*a\n",
           FMT_TEXT, "s = a*t*(1 - t)*(2 + t)*(1 + t^2)\n");
    char *x =
        printed_ex("param t\ns = (3 + t)*(2 + t)*(t^2 + 5)\n", FMT_TEXT, 0, -1);
    char *y =
        printed_ex("param t\ns = (t^2 + 5)*(t + 2)*(t + 3)\n", FMT_TEXT, 0, -1);
    assert_string_equal(x, y);
    assert_true(strcmp(x, "s = (2 + t)*(3 + t)*(5 + t^2)\n") == 0 ||
                strcmp(x, "s = (3 + t)*(2 + t)*(5 + t^2)\n") == 0);
    free(x);
    free(y);
}

/* factors met before in a scheme are divided out first (book_factor.c,
 * factor_by_known): with them, a polynomial prints as it does alone
 * (FLINT's factoring of the whole), powers, signs and content included */
static void test_factors_shared(void **state)
{
    (void)state;
    static const char s1[] = "s1 = (2 + t)*(3 + t)*(5 + t^2)\n";
    static const char s2[] = "s2 = (3 + t)*(5 + t^2)*(7 + t + t^3)\n";
    static const char s3[] = "s3 = -4*(3 + t)^2*(2 - t)*(5 + t^2)*(1 + t^3)\n";
    char src[512], alone[512];
    snprintf(src, sizeof src, "param t\n%s%s%soutput s1, s2, s3\n", s1, s2, s3);
    char *all = printed_ex(src, FMT_TEXT, 0, -1);
    /* s2 with s1's factors divided out: the rest is irreducible */
    assert_non_null(strstr(all, "s2 = (3 + t)*(5 + t^2)*(7 + t + t^3)\n"));
    snprintf(alone, sizeof alone, "param t\n%s", s3);
    char *a3 = printed_ex(alone, FMT_TEXT, 0, -1);
    assert_non_null(strstr(all, a3));
    /* 1 + t^3 = (1 + t)(1 - t + t^2), found by FLINT after the known
     * factors are divided out */
    assert_non_null(strstr(a3, "(1 + t)"));
    assert_non_null(strstr(a3, "(1 - t + t^2)"));
    assert_non_null(strstr(a3, "(3 + t)^2"));
    free(a3);
    free(all);
}

/* JSON's factors in one total order (format.c, factor_before: terms,
 * degree, FLINT's order of polynomials), the same whether a weight's
 * factors were shared from the weights before it (book_factor) or found
 * alone; the values by hand: (t + 2)(t + 3)(t^2 + 5) expanded etc. */
static void test_json_factors_shared(void **state)
{
    (void)state;
    static const char src[] = "param t\n"
                              "s1 = (2 + t)*(3 + t)*(5 + t^2)\n"
                              "s2 = (3 + t)*(5 + t^2)*(7 + t + t^3)/(2 - t)\n"
                              "s3 = -4*(3 + t)^2*(2 - t)*(5 + t^2)*(1 + t^3)\n"
                              "s4 = (4*t - 3)*(4*t - 1)*(t - 1)*t\n"
                              "output s1, s2, s3, s4\n";
    char *js = printed_ex(src, FMT_JSON, 0, -1);
    /* t + 3 before t + 2: FLINT's order from the last (docs/language.md) */
    assert_non_null(strstr(js, "\"value\": \"(t+3)*(t+2)*(t^2+5)\""));
    assert_non_null(
        strstr(js, "\"value\": \"-(t+3)*(t^2+5)*(t^3+t+7)/(t-2)\""));
    assert_non_null(
        strstr(js, "\"value\": \"-4*(t+3)^2*(t+1)*(2-t)*(t^2+5)*(t^2-t+1)\""));
    /* 1 - 4t, 3 - 4t, 1 - t: FLINT's order of 4t - 1, 4t - 3, t - 1 from
     * the last, the order of sums in the text */
    assert_non_null(strstr(js, "\"value\": \"-t*(1-4*t)*(3-4*t)*(1-t)\""));
    /* each output alone prints the same */
    const char *one[] = {"s3 = -4*(3 + t)^2*(2 - t)*(5 + t^2)*(1 + t^3)\n"
                         "output s3\n",
                         "s2 = (3 + t)*(5 + t^2)*(7 + t + t^3)/(2 - t)\n"
                         "output s2\n"};
    for (int i = 0; i < 2; i++) {
        char alone[256];
        snprintf(alone, sizeof alone, "param t\n%s", one[i]);
        char *a = printed_ex(alone, FMT_JSON, 0, -1);
        const char *v = strstr(a, "\"value\": ");
        assert_non_null(v);
        char w[160];
        snprintf(w, sizeof w, "%.*s", (int)strcspn(v + 10, "}"), v + 10);
        assert_non_null(strstr(js, w));
        free(a);
    }
    free(js);
}

/* factors found without FLINT's factoring (book.c, factor_known: an
 * integer, a monomial, powers of 1 - x, one irreducible rest) print as
 * FLINT's would: the same rules as above */
static void test_factor_known(void **state)
{
    (void)state;
    expect("param t in [0, 1]\nconst a\n"
           "s = 6*t^2*a*(1 - t)^2*(1 - a)*(2 + t + a^2*t)\n",
           FMT_TEXT, "s = 6*a*(1 - a)*t^2*(1 - t)^2*(2 + t + a^2*t)\n");
    expect("param t in [0, 1]\nconst a\n"
           "s = 2*t*(1 - t)^3*(t^2 + a*t + 1)\n",
           FMT_TEXT, "s = 2*t*(1 - t)^3*(1 + a*t + t^2)\n");
    expect("param t in [0, 1]\nconst a\n"
           "s = -3*t*(t - 1)*(1 + a*t^2)\n",
           FMT_TEXT, "s = 3*t*(1 - t)*(1 + a*t^2)\n");
    /* irreducible (no shortcut can split it): expanded */
    expect("param t\nparam u\ns = t^2 + u^3 + 1\n", FMT_TEXT,
           "s = 1 + t^2 + u^3\n");
}

/* ---- the cheap proofs of irreducibility (book.c), against FLINT ------ */

/* a random integer in [-b, b] */
static slong rand_si(flint_rand_t st, slong b)
{
    return (slong)n_randint(st, (ulong)(2 * b + 1)) - b;
}

/* a random polynomial of degree d, coefficients in [-b, b], the leading one
 * nonzero */
static void rand_upoly(fmpz_poly_t u, flint_rand_t st, slong d, slong b)
{
    fmpz_poly_zero(u);
    for (slong k = 0; k < d; k++)
        fmpz_poly_set_coeff_si(u, k, rand_si(st, b));
    slong lc = 0;
    while (lc == 0)
        lc = rand_si(st, b);
    fmpz_poly_set_coeff_si(u, d, lc);
}

/* FLINT: u is irreducible over Q (its content aside) */
static int flint_upoly_irreducible(const fmpz_poly_t u)
{
    fmpz_poly_factor_t f;
    fmpz_poly_factor_init(f);
    fmpz_poly_factor(f, u);
    int irr = f->num == 1 && f->exp[0] == 1;
    fmpz_poly_factor_clear(f);
    return irr;
}

/* FLINT: p is irreducible (its integer content aside); with primitive,
 * and primitive (what surely_irreducible proves: p is its factorisation) */
static int flint_mpoly_irreducible_ex(const fmpz_mpoly_t p, const Ring *r,
                                      int primitive)
{
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    assert_true(fmpz_mpoly_factor(f, p, r->ctx));
    int irr = f->num == 1 && fmpz_is_one(f->exp + 0) &&
              (!primitive || fmpz_is_pm1(f->constant));
    fmpz_mpoly_factor_clear(f, r->ctx);
    return irr;
}

static int flint_mpoly_irreducible(const fmpz_mpoly_t p, const Ring *r)
{
    return flint_mpoly_irreducible_ex(p, r, 0);
}

/* surely_irreducible's claim: irreducible and primitive */
static int flint_mpoly_primitive_irreducible(const fmpz_mpoly_t p,
                                             const Ring *r)
{
    return flint_mpoly_irreducible_ex(p, r, 1);
}

/* p = u(x_v) in r */
static void upoly_in_var(fmpz_mpoly_t p, const fmpz_poly_t u, slong v,
                         const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    ulong e[4] = {0, 0, 0, 0};
    assert_true(nv <= 4);
    fmpz_mpoly_zero(p, r->ctx);
    for (slong k = 0; k <= fmpz_poly_degree(u); k++) {
        e[v] = (ulong)k;
        fmpz_mpoly_set_coeff_fmpz_ui(p, u->coeffs + k, e, r->ctx);
    }
}

static const char *const irr_names[] = {"x", "y", "z", "w"};

/* p on stderr (the failing case) */
static void put_mpoly(const char *what, const fmpz_mpoly_t p, const Ring *r)
{
    char *s = fmpz_mpoly_get_str_pretty(p, (const char **)irr_names, r->ctx);
    fprintf(stderr, "%s%s", what, s);
    flint_free(s);
}

/* (1) a polynomial in one variable, of degree 1..8: random (irreducible
 * most often), products of random factors, with repeated factors, times a
 * content; whenever irreducible_mod_small_prime, or surely_irreducible of
 * the same polynomial in one variable of a ring of 1..3, says
 * "irreducible", FLINT's factoring agrees */
static void test_irreducible_one_variable(void **state)
{
    (void)state;
    enum { N = 4000 };
    flint_rand_t st;
    flint_randinit(st);
    flint_randseed(st, 20261125, 284);
    Ring rings[3];
    for (int i = 0; i < 3; i++)
        ring_init(&rings[i], i + 1, irr_names);
    fmpz_poly_t u, f, g;
    fmpz_poly_init(u);
    fmpz_poly_init(f);
    fmpz_poly_init(g);
    long claims = 0, sure_claims = 0, reducible = 0, deg4 = 0;
    for (int i = 0; i < N; i++) {
        slong d = 1 + (slong)n_randint(st, 8);
        slong b = n_randint(st, 2) ? 9 : 40;
        switch (i % 4) {
        case 0: /* random */
            rand_upoly(u, st, d, b);
            break;
        case 1: /* a product of two or three random factors */
            rand_upoly(u, st, 1 + (slong)n_randint(st, 4), b);
            for (int k = 1 + (int)n_randint(st, 2); k > 0; k--) {
                slong df = 1 + (slong)n_randint(st, 3);
                if (fmpz_poly_degree(u) + df > 8)
                    break;
                rand_upoly(f, st, df, b);
                fmpz_poly_mul(u, u, f);
            }
            break;
        case 2: /* a repeated factor: f^k g */
        {
            slong df = 1 + (slong)n_randint(st, 3);
            slong k = 2 + (slong)n_randint(st, (ulong)(8 / df - 1));
            rand_upoly(f, st, df, 9);
            fmpz_poly_pow(u, f, (ulong)k);
            slong dg = (slong)n_randint(st, (ulong)(9 - df * k)); /* < 9 */
            if (dg > 0) {
                rand_upoly(g, st, dg, 9);
                fmpz_poly_mul(u, u, g);
            }
            break;
        }
        default: /* linear and quadratic factors whose leading coefficients
                  * are multiples of the small primes: images modulo those
                  * primes lose degree */
            fmpz_poly_one(u);
            while (fmpz_poly_degree(u) < d) {
                static const slong mult[] = {3, 5, 7, 9, 11, 13, 15, 21};
                slong df = 1 + (slong)n_randint(st, 2);
                rand_upoly(f, st, df, 9);
                fmpz_poly_set_coeff_si(f, df,
                                       mult[n_randint(st, 8)] *
                                           (n_randint(st, 2) ? 1 : -1));
                fmpz_poly_mul(u, u, f);
            }
            break;
        }
        if (n_randint(st, 4) == 0) /* a content */
            fmpz_poly_scalar_mul_si(u, u, 2 + (slong)n_randint(st, 12));
        if (fmpz_poly_degree(u) > 8 || fmpz_poly_degree(u) < 1)
            continue;
        int irr = flint_upoly_irreducible(u);
        reducible += !irr;
        if (book_test_irreducible_mod_small_prime(u)) {
            claims++;
            deg4 += fmpz_poly_degree(u) >= 4;
            if (!irr) {
                fprintf(stderr, "irreducible_mod_small_prime: ");
                fmpz_poly_fprint_pretty(stderr, u, "x");
                fprintf(stderr, "\n");
            }
            assert_true(irr);
        }
        /* the same polynomial in variable v of a ring of nv */
        const Ring *r = &rings[i % 3];
        slong v = (slong)n_randint(st, (ulong)(i % 3 + 1));
        fmpz_mpoly_t p;
        fmpz_mpoly_init(p, r->ctx);
        upoly_in_var(p, u, v, r);
        if (book_test_surely_irreducible(p, r)) {
            sure_claims++;
            if (!irr || !flint_mpoly_primitive_irreducible(p, r)) {
                fprintf(stderr, "surely_irreducible: ");
                put_mpoly("", p, r);
                fprintf(stderr, "\n");
            }
            assert_true(irr);
            assert_true(flint_mpoly_primitive_irreducible(p, r));
        }
        fmpz_mpoly_clear(p, r->ctx);
    }
    /* not vacuous: both answers, the proofs of degree 4 or more too */
    assert_true(reducible > N / 2);
    assert_true(claims > N / 10);
    assert_true(deg4 > N / 20);
    assert_true(sure_claims > N / 10);
    fmpz_poly_clear(g);
    fmpz_poly_clear(f);
    fmpz_poly_clear(u);
    for (int i = 0; i < 3; i++)
        ring_clear(&rings[i]);
    flint_randclear(st);
}

/* (2) quadratics: quadratic_irreducible is an answer both ways, FLINT's;
 * in one variable (random, and products of two linear factors, times a
 * content), in two as binary forms a x^2 + b x y + c y^2 (irreducible
 * exactly when a x^2 + b x + c is), and a(y) x^2 + b(y) x + c(y) through
 * surely_irreducible (whose images are quadratics) */
static void test_quadratic_irreducible(void **state)
{
    (void)state;
    enum { N = 3000 };
    flint_rand_t st;
    flint_randinit(st);
    flint_randseed(st, 20261125, 2);
    Ring r;
    ring_init(&r, 2, irr_names);
    fmpz_poly_t u, f, g;
    fmpz_poly_init(u);
    fmpz_poly_init(f);
    fmpz_poly_init(g);
    fmpz_mpoly_t p, a, b;
    fmpz_mpoly_init(p, r.ctx);
    fmpz_mpoly_init(a, r.ctx);
    fmpz_mpoly_init(b, r.ctx);
    long yes[2] = {0, 0}, no[2] = {0, 0}, sure_claims = 0;
    for (int i = 0; i < N; i++) {
        slong bd = n_randint(st, 2) ? 6 : 30;
        if (i % 2 == 0) {
            rand_upoly(u, st, 2, bd);
        } else {
            rand_upoly(f, st, 1, bd);
            rand_upoly(g, st, 1, bd);
            fmpz_poly_mul(u, f, g);
        }
        if (n_randint(st, 4) == 0)
            fmpz_poly_scalar_mul_si(u, u, 2 + (slong)n_randint(st, 8));
        /* one variable */
        int irr = flint_upoly_irreducible(u);
        assert_int_equal(book_test_quadratic_irreducible(u), irr);
        (irr ? yes : no)[0]++;
        /* two: the binary form u2 x^2 + u1 x y + u0 y^2 */
        fmpz_mpoly_zero(p, r.ctx);
        for (ulong k = 0; k <= 2; k++) {
            ulong e[2] = {k, 2 - k};
            fmpz_mpoly_set_coeff_fmpz_ui(p, u->coeffs + k, e, r.ctx);
        }
        irr = flint_mpoly_irreducible(p, &r);
        assert_int_equal(book_test_quadratic_irreducible(u), irr);
        (irr ? yes : no)[1]++;
        /* a(y) x^2 + b(y) x + c(y), or (a1 x + b1)(a2 x + b2), a, b in y */
        fmpz_mpoly_zero(p, r.ctx);
        if (i % 2 == 0) {
            for (ulong k = 0; k <= 2; k++)
                for (ulong j = 0; j <= 2; j++) {
                    ulong e[2] = {k, j};
                    if (n_randint(st, 2))
                        fmpz_mpoly_set_coeff_si_ui(p, rand_si(st, 6), e, r.ctx);
                }
        } else {
            fmpz_mpoly_one(p, r.ctx);
            for (int m = 0; m < 2; m++) {
                fmpz_mpoly_zero(a, r.ctx);
                for (ulong k = 0; k <= 1; k++)
                    for (ulong j = 0; j <= 2; j++) {
                        ulong e[2] = {k, j};
                        if (n_randint(st, 2))
                            fmpz_mpoly_set_coeff_si_ui(a, rand_si(st, 6), e,
                                                       r.ctx);
                    }
                fmpz_mpoly_mul(p, p, a, r.ctx);
            }
        }
        if (fmpz_mpoly_is_zero(p, r.ctx) ||
            fmpz_mpoly_degree_si(p, 0, r.ctx) != 2)
            continue;
        if (book_test_surely_irreducible(p, &r)) {
            sure_claims++;
            if (!flint_mpoly_primitive_irreducible(p, &r)) {
                fprintf(stderr, "surely_irreducible: ");
                put_mpoly("", p, &r);
                fprintf(stderr, "\n");
            }
            assert_true(flint_mpoly_primitive_irreducible(p, &r));
        }
    }
    for (int k = 0; k < 2; k++) {
        assert_true(yes[k] > N / 4);
        assert_true(no[k] > N / 4);
    }
    assert_true(sure_claims > N / 5);
    fmpz_mpoly_clear(b, r.ctx);
    fmpz_mpoly_clear(a, r.ctx);
    fmpz_mpoly_clear(p, r.ctx);
    fmpz_poly_clear(g);
    fmpz_poly_clear(f);
    fmpz_poly_clear(u);
    ring_clear(&r);
    flint_randclear(st);
}

/* a random polynomial of r, of 1..maxterms terms, exponents in [0, maxe],
 * coefficients in [-5, 5] */
static void rand_mpoly(fmpz_mpoly_t p, flint_rand_t st, slong maxterms,
                       ulong maxe, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    ulong e[4];
    fmpz_mpoly_zero(p, r->ctx);
    for (slong t = 1 + (slong)n_randint(st, (ulong)maxterms); t > 0; t--) {
        for (slong v = 0; v < nv; v++)
            e[v] = n_randint(st, maxe + 1);
        fmpz_mpoly_set_coeff_si_ui(p, rand_si(st, 5), e, r->ctx);
    }
}

/* (3) surely_irreducible never says "irreducible" of a product of two
 * non-constant polynomials of 2..4 variables (nor of a square), and when it
 * says so of a random polynomial, FLINT agrees */
static void test_surely_irreducible_products(void **state)
{
    (void)state;
    enum { N = 3000 };
    flint_rand_t st;
    flint_randinit(st);
    flint_randseed(st, 20261125, 3);
    Ring rings[3];
    for (int i = 0; i < 3; i++)
        ring_init(&rings[i], i + 2, irr_names);
    long products = 0, claims = 0;
    for (int i = 0; i < N; i++) {
        const Ring *r = &rings[i % 3];
        fmpz_mpoly_t p, f, g;
        fmpz_mpoly_init(p, r->ctx);
        fmpz_mpoly_init(f, r->ctx);
        fmpz_mpoly_init(g, r->ctx);
        ulong maxe = 1 + n_randint(st, 2);
        rand_mpoly(f, st, 5, maxe, r);
        if (i % 3 == 0) { /* one random polynomial */
            fmpz_mpoly_swap(p, f, r->ctx);
            if (fmpz_mpoly_total_degree_si(p, r->ctx) < 1)
                goto next;
            if (book_test_surely_irreducible(p, r)) {
                claims++;
                if (!flint_mpoly_primitive_irreducible(p, r)) {
                    fprintf(stderr, "surely_irreducible: ");
                    put_mpoly("", p, r);
                    fprintf(stderr, "\n");
                }
                assert_true(flint_mpoly_primitive_irreducible(p, r));
            }
            goto next;
        }
        if (i % 7 == 0)
            fmpz_mpoly_set(g, f, r->ctx); /* a square */
        else
            rand_mpoly(g, st, 5, maxe, r);
        if (fmpz_mpoly_total_degree_si(f, r->ctx) < 1 ||
            fmpz_mpoly_total_degree_si(g, r->ctx) < 1)
            goto next;
        fmpz_mpoly_mul(p, f, g, r->ctx);
        products++;
        assert_false(flint_mpoly_irreducible(p, r));
        if (book_test_surely_irreducible(p, r)) {
            fprintf(stderr, "surely_irreducible: (");
            put_mpoly("", f, r);
            fprintf(stderr, ")*(");
            put_mpoly("", g, r);
            fprintf(stderr, ")\n");
            fail();
        }
    next:
        fmpz_mpoly_clear(g, r->ctx);
        fmpz_mpoly_clear(f, r->ctx);
        fmpz_mpoly_clear(p, r->ctx);
    }
    assert_true(products > N / 2);
    assert_true(claims > N / 10);
    for (int i = 0; i < 3; i++)
        ring_clear(&rings[i]);
    flint_randclear(st);
}

/* an all-minus numerator is written -(...); the denominator's first term
 * is positive */
static void test_minus_outside(void **state)
{
    (void)state;
    expect("param t\nparam u\ns = (t + u^2)/(-1 - t)\n", FMT_TEXT,
           "s = -(t + u^2)/(1 + t)\n");
    expect("param t\ns = -3*t/(2 - t^2)\n", FMT_TEXT, "s = -3*t/(2 - t^2)\n");
}

/* vectors: a factor common to every weight once in front, opposite
 * weights as one difference, the positive one first */
static void test_vector_differences(void **state)
{
    (void)state;
    expect("point A, C\nparam u\nV = 2*(C - A)*u\n", FMT_TEXT,
           "V = 2*u*(C - A)    (vector)\n");
    expect("point A, C\nV = -2*A + 2*C\n", FMT_TEXT,
           "V = 2*(C - A)    (vector)\n");
    expect("point A, B, C\nparam t\nV = A*(t^2 + t - 1) - B*t + C*(1 - t^2)"
           "\n",
           FMT_TEXT,
           /* no common factor; 1 - t^2 factored (as many terms); the
            * fewest minus signs: t + t^2 - 1, not -(1 - t - t^2) */
           "V = A*(t + t^2 - 1) - B*t + C*(1 - t)*(1 + t)    (vector)\n");
    expect("point A, C\nparam u\nV = 2*(C - A)*u\n", FMT_LATEX,
           "\\[ V = 2 u \\left(C - A\\right) \\]\n");
}

/* LaTeX names: one-letter stems subscripted, Greek, several letters as one
 * word, derivatives from diff as d/dt */
static void test_latex_names(void **state)
{
    (void)state;
    static const struct {
        const char *name, *latex;
    } cases[] = {
        {"A", "A"},
        {"A1", "A_{1}"},
        {"fP", "f_{P}"},
        {"pD", "p_{D}"},
        {"d2M", "d_{2M}"},
        {"kq", "\\mathit{kq}"},
        {"Mx", "\\mathit{Mx}"},
        {"alpha", "\\alpha"},
        {"alpha2", "\\alpha_{2}"},
        {"Omega", "\\Omega"},
        {"x_max", "x_{max}"},
        {"kp_1", "\\mathit{kp}_{1}"},
        {"M116_abc", "M_{116,abc}"}, /* no double subscript */
        {"alpha1_x", "\\alpha_{1,x}"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *s = book_latex_name(cases[i].name);
        assert_string_equal(s, cases[i].latex);
        free(s);
    }
    expect("point A, B\nparam t\nM = along(A, B, t^2)\ndM = diff(M, t)\n"
           "d2M = diff(M, t, 2)\noutput dM, d2M\n",
           FMT_LATEX,
           "\\[ \\frac{\\mathrm{d}M}{\\mathrm{d}t} = 2 t \\left(B - A\\right)"
           " \\]\n"
           "\\[ \\frac{\\mathrm{d}^{2}M}{\\mathrm{d}t^{2}} = 2 \\left(B - "
           "A\\right) \\]\n");
    /* the text form keeps the names */
    expect("point A, B\nparam t\nM = along(A, B, t^2)\ndM = diff(M, t)\n"
           "output dM\n",
           FMT_TEXT, "dM = 2*t*(B - A)    (vector)\n");
}

/* a LaTeX equation wider than the width is set in multline*, broken
 * between its terms */
static void test_multline(void **state)
{
    (void)state;
    static const char src[] = "point A, B, C\nparam u in [0, 1]\nconst w\n"
                              "R = (A*(1-u)^2 + 2*w*C*u*(1-u) + B*u^2)/"
                              "((1-u)^2 + 2*w*u*(1-u) + u^2)\n";
    char *got = printed_ex(src, FMT_LATEX, 40, -1);
    assert_string_equal(got,
                        "\\begin{multline*}\n"
                        "R = \\frac{1}{\\bar{u}^{2} + 2 w u \\bar{u} + u^{2}} "
                        "\\Bigl(A \\bar{u}^{2} \\\\\n"
                        "+ B u^{2} + 2 w C u \\bar{u}\\Bigr)\n"
                        "\\end{multline*}\n");
    free(got);
    /* at the default width (80) it fits: the fraction is as wide as its
     * numerator */
    got = printed_ex(src, FMT_LATEX, 80, -1);
    assert_non_null(strstr(got, "\\[ R = \\frac{"));
    free(got);
}

/* relative to an origin: M = (B - A)*t + A, the point first as in B*t */
static void test_origin(void **state)
{
    (void)state;
    char *got = printed_ex("point A, B\nparam t\nM = along(A, B, t)\n",
                           FMT_TEXT, 80, 0);
    assert_string_equal(got, "M = (B - A)*t + A\n");
    free(got);
    got = printed_ex("point A, B\nparam t\nM = along(A, B, t/(1 + t))\n",
                     FMT_TEXT, 80, 0);
    assert_string_equal(got, "M = (B - A)*t/(1 + t) + A\n");
    free(got);
}

/* the conic of the monograph's 2.1.6 (double_contact.pcs, 3.4): the book
 * prints P = (A - C) kp v̄²/D + (B - C) kp v²/D + C, D = kp(1 - 2v)² + 2vv̄;
 * over one denominator C's weight is 2(1 - kp)vv̄ (D minus the others), and
 * D is collected by kp (three terms, shorter than the Bernstein form) */
static void test_conic_of_2_1_6(void **state)
{
    (void)state;
    static const char src[] =
        "point A, B, C\nparam v in [0, 1]\nconst kp\n"
        "T1 = (A + B)/2\nT = along(A, B, v)\nK_P = along(C, T1, kp)\n"
        "P_a = meet(line(A, K_P), line(C, T))\n"
        "P_b = meet(line(B, K_P), line(C, T))\n"
        "P = meet(line(A, P_b), line(B, P_a))\n";
    expect(src, FMT_TEXT,
           "P = (kp*A*(1 - v)^2 + kp*B*v^2 + 2*(1 - kp)*C*v*(1 - v))"
           "/(2*v*(1 - v) + kp*(1 - 2*v)^2)\n");
    /* its numerator is 79 columns of LaTeX: at 100 one line, at the
     * default 80 broken after the first term */
    char *got = printed_ex(src, FMT_LATEX, 100, -1);
    assert_string_equal(
        got, "\\[ P = \\frac{\\mathit{kp} A \\bar{v}^{2} + \\mathit{kp} B "
             "v^{2} + 2 \\bar{\\mathit{kp}} C v \\bar{v}}{2 v \\bar{v} + "
             "\\mathit{kp} \\left(1 - 2 v\\right)^{2}} \\]\n");
    free(got);
    expect(src, FMT_LATEX,
           "\\begin{multline*}\n"
           "P = \\frac{1}{2 v \\bar{v} + \\mathit{kp} \\left(1 - 2 "
           "v\\right)^{2}} \\Bigl(\\mathit{kp} A \\bar{v}^{2} \\\\\n"
           "+ \\mathit{kp} B v^{2} + 2 \\bar{\\mathit{kp}} C v \\bar{v}"
           "\\Bigr)\n"
           "\\end{multline*}\n");
    got = printed_ex(src, FMT_TEXT, 80, 2);
    assert_string_equal(
        got, "P = (A - C)*kp*(1 - v)^2/(2*v*(1 - v) + kp*(1 - 2*v)^2) + "
             "(B - C)*kp*v^2/(2*v*(1 - v) + kp*(1 - 2*v)^2) + C\n");
    free(got);
}

/* abs(x) is x*sign(x) inside (kernel.h); every x*sign(x) prints as abs(x)
 * in text, LaTeX and JSON (absform.h): the square of the composite-curve
 * text, 2.2.2 ex. 1, its weights P(t,k-1,1) - P(t,k,1) by hand; x^3 sign(x)
 * is |x|^3; a sign(x) without the factor x stays sign(x) */
#define SQUARE                                                                 \
    "point O, A, B, C\nparam t\n"                                              \
    "R = O + (A - O)*(1 + abs(t) - abs(t - 1))/2"                              \
    " + (B - A)*(1 + abs(t - 1) - abs(t - 2))/2"                               \
    " + (C - B)*(1 + abs(t - 2) - abs(t - 3))/2"                               \
    " + (O - C)*(1 + abs(t - 3) - abs(t - 4))/2\n"

static void test_abs(void **state)
{
    (void)state;
    expect(SQUARE, FMT_TEXT,
           "R = (O*(2 - abs(t) + abs(t - 1) + abs(t - 3) - abs(t - 4))"
           " + A*(abs(t) - 2*abs(t - 1) + abs(t - 2))"
           " + B*(abs(t - 1) - 2*abs(t - 2) + abs(t - 3))"
           " + C*(abs(t - 2) - 2*abs(t - 3) + abs(t - 4)))/2\n");
    expect("param t\nr = t^2*abs(t)\nq = sign(t)\n"
           "w = (1 - t)*abs(t - 1)\noutput r, q, w\n",
           FMT_TEXT, "r = abs(t)^3\nq = sign(t)\nw = (1 - t)*abs(t - 1)\n");
    expect("param t\nr = t^2*abs(t)\nw = (1 - t)*abs(t - 1)\n"
           "output r, w\n",
           FMT_LATEX,
           "\\[ r = \\left|t\\right|^{3} \\]\n"
           "\\[ w = \\bar{t} \\left|t - 1\\right| \\]\n");
    char *js = printed_ex("point A, B\nparam t\n"
                          "M = A + (B - A)*(abs(t) - t^3*sign(t))\n"
                          "q = sign(t)\noutput M, q\n",
                          FMT_JSON, 0, -1);
    assert_non_null(strstr(js, "\"B\": \"abs(t)*(t+1)*(1-t)\""));
    assert_non_null(strstr(js, "\"value\": \"sign(t)\""));
    assert_null(strstr(js, "sign(t)*"));
    assert_null(strstr(js, "*sign("));
    free(js);
}

/* Roots stay where the user put them (book 2.1.1.1, (2.10), (2.11)): the
 * normal form keeps b*cos(phi)*sqrt(X)/X with X = b^2 - b^2*sin(phi)^2 +
 * a^2*sin(phi)^2; printed, the root goes back to the denominator and X is
 * written through cos^2 = 1 - sin^2 as b^2*cos(phi)^2 + a^2*sin(phi)^2.
 * By a focus (2.18): 1/(a - c*cos(phi)), c = sqrt(a^2 - b^2), which the
 * normal form rationalises to (a + c*cos(phi))/(b^2 + (a^2 - b^2)*sin^2),
 * is written back, its A weight (a*cos(phi) - c)/(a - c*cos(phi)). */
#define ELLIPSE                                                                \
    "point A, B, C\nconst a, b > 0\nparam phi\n"                               \
    "rho = a*b/sqrt(a^2*sin(phi)^2 + b^2*cos(phi)^2)\n"                        \
    "M = C + (A - C)*(rho*cos(phi)/a) + (B - C)*(rho*sin(phi)/b)\n"
#define FOCAL                                                                  \
    "point A, B, C\nconst a, b > 0\nparam phi\nc = sqrt(a^2 - b^2)\n"          \
    "rho = b^2/(a - c*cos(phi))\n"                                             \
    "M = C + (A - C)*(rho*cos(phi) - c)/a + (B - C)*rho*sin(phi)/b\n"

static void test_roots_where_written(void **state)
{
    (void)state;
    expect(ELLIPSE "output rho\n", FMT_TEXT,
           "rho = a*b/sqrt(b^2*cos(phi)^2 + a^2*sin(phi)^2)\n");
    char *o = printed_ex(ELLIPSE "output M\n", FMT_TEXT, 0, 2);
    assert_string_equal(o, "M = (A - C)*b*cos(phi)/sqrt(b^2*cos(phi)^2 + "
                           "a^2*sin(phi)^2) + (B - C)*a*sin(phi)/"
                           "sqrt(b^2*cos(phi)^2 + a^2*sin(phi)^2) + C\n");
    assert_true(strlen(o) - 1 <= 130); /* issue 18: the book's is 123 */
    free(o);
    /* over one denominator: weights b*cos(phi)/s, a*sin(phi)/s,
     * 1 - (b*cos(phi) + a*sin(phi))/s */
    expect(ELLIPSE "output M\n", FMT_TEXT,
           "M = (b*A*cos(phi) + a*B*sin(phi) + C*(sqrt(b^2*cos(phi)^2 + "
           "a^2*sin(phi)^2) - b*cos(phi) - a*sin(phi)))/"
           "sqrt(b^2*cos(phi)^2 + a^2*sin(phi)^2)\n");
    o = printed_ex(ELLIPSE "output M\n", FMT_LATEX, 0, 2);
    assert_string_equal(
        o, "\\[ M = \\left(A - C\\right) \\frac{b \\cos\\varphi}{\\sqrt{b^{2} "
           "\\cos^{2}\\varphi + a^{2} \\sin^{2}\\varphi}} + \\left(B - "
           "C\\right) \\frac{a \\sin\\varphi}{\\sqrt{b^{2} \\cos^{2}\\varphi "
           "+ a^{2} \\sin^{2}\\varphi}} + C \\]\n");
    free(o);
    /* (c = sqrt(a^2 - b^2) is named: results print through c) */
    expect(FOCAL "output rho\n", FMT_TEXT, "rho = b^2/(a - c*cos(phi))\n");
    o = printed_ex(FOCAL "output M\n", FMT_TEXT, 0, 2);
    assert_string_equal(o, "M = (A - C)*(a*cos(phi) - c)/(a - c*cos(phi))"
                           " + (B - C)*b*sin(phi)/(a - c*cos(phi)) + C\n");
    free(o);
    expect("const a, b > 0\nparam phi\n"
           "rho = b^2/(a - sqrt(a^2 - b^2)*cos(phi))\n",
           FMT_TEXT, "rho = b^2/(a - sqrt(a^2 - b^2)*cos(phi))\n");
    /* a scalar alone: its normal form (b^2*cos(phi) -
     * a*c*sin(phi)^2)/(b^2*cos(phi)^2 + a^2*sin(phi)^2) is (a*cos(phi) -
     * c)/(a - c*cos(phi)), the conjugate read off the denominator:
     * (a - c*cos)(a + c*cos) = a^2 - (a^2 - b^2)*cos^2 */
    expect("const a, b > 0\nparam phi\nc = sqrt(a^2 - b^2)\n"
           "x = (a*cos(phi) - c)/(a - c*cos(phi))\n",
           FMT_TEXT, "x = (a*cos(phi) - c)/(a - c*cos(phi))\n");
}

/* Results through the user's named scalars (the book's a, b, c): the circle
 * through three points (article, eq. (5)) with a = |AC|^2, b = |BA|^2,
 * c = |CB|^2; its denominator b*t^2 + (a - c - b)*t + c is (1 - t)*(c -
 * b*t) + a*t.  A name prints only in what is defined after it, and a
 * definition never prints as its own name; dist(A, C)^4 is a^2. */
static void test_named_scalars(void **state)
{
    (void)state;
    expect("point A, B, C\nparam t\n"
           "a = dist(A, C)^2\nb = dist(B, A)^2\nc = dist(C, B)^2\n"
           "M = (A*c*(1 - t) + B*a*t + C*b*t*(t - 1))/"
           "(b*t^2 + (a - c - b)*t + c)\n"
           "w = dist(A, C)^4 + t\nu = dist(A, C)^3\noutput a, M, w, u\n",
           FMT_TEXT,
           "a = dist(A, C)^2\n"
           "M = (c*A*(1 - t) + a*B*t - b*C*t*(1 - t))/"
           "((1 - t)*(c - b*t) + a*t)\n"
           "w = t + a^2\nu = dist(A, C)^3\n");
    expect("point A, B\nparam t\nM = A + (B - A)*t*dist(A, B)\n"
           "q = dist(A, B)\nN = A + (B - A)*t*dist(A, B)\noutput M, q, N\n",
           FMT_TEXT,
           "M = A*(1 - dist(A, B)*t) + dist(A, B)*B*t\n"
           "q = dist(A, B)\n"
           "N = A*(1 - q*t) + q*B*t\n");
}

/* LaTeX broken to the page (latexbreak.h): before the operators, a
 * fraction too wide as 1/den times its numerator in \Bigl( \Bigr) whose
 * terms part; every line balanced.  Widths by the rule: a letter 1, an
 * operator 2.2, a space 0.5, \frac{1}{y} 1.6, \Bigl( 0.8. */
static void expect_lines(const char *math, double width,
                         const char *const *want, size_t nwant)
{
    char **ls;
    size_t n = latex_break(&ls, math, width);
    assert_int_equal(n, nwant);
    for (size_t i = 0; i < n && i < nwant; i++)
        assert_string_equal(ls[i], want[i]);
    latex_lines_free(ls, n);
}

static void test_latex_break(void **state)
{
    (void)state;
    static const char *const sum[] = {"a + b", "+ c", "+ d"};
    expect_lines("a + b + c + d", 6, sum, 3);
    static const char *const frac[] = {"x = \\frac{1}{y} \\Bigl( a", "+ b + c",
                                       "+ d + e \\Bigr)"};
    expect_lines("x = \\frac{a + b + c + d + e}{y}", 12, frac, 3);
    static const char *const paren[] = {"2 \\Bigl( a + b", "+ c \\Bigr)^{2}"};
    expect_lines("2 \\left(a + b + c\\right)^{2}", 9, paren, 2);
    static const char *const fits[] = {"a + b"};
    expect_lines("a + b", 56, fits, 1);
    /* a named function's argument list parts after its name (natx with
     * a long law): the name stays with the first piece */
    static const char *const named[] = {
        "x = \\operatorname{natx}\\Bigl( aaaa, bbbb,", "cccc, dddd \\Bigr)"};
    expect_lines(
        "x = \\operatorname{natx}\\left(aaaa, bbbb, cccc, dddd\\right)", 20,
        named, 2);
    /* the hexagon of the composite-curve text set as a standalone
     * document: six lines, each within the page */
    char *o = printed_ex("point A0, A1, A2, A3, A4, A5\nparam t\n"
                         "R = A0 + (A1 - A0)*(1 + abs(t) - abs(t - 1))/2"
                         " + (A2 - A1)*(1 + abs(t - 1) - abs(t - 2))/2"
                         " + (A3 - A2)*(1 + abs(t - 2) - abs(t - 3))/2"
                         " + (A4 - A3)*(1 + abs(t - 3) - abs(t - 4))/2"
                         " + (A5 - A4)*(1 + abs(t - 4) - abs(t - 5))/2"
                         " + (A0 - A5)*(1 + abs(t - 5) - abs(t - 6))/2\n",
                         FMT_LATEX, 0, -1);
    size_t lines = 0;
    for (char *p = o; (p = strstr(p, "\\\\\n")); p++)
        lines++;
    assert_int_equal(lines, 5);
    for (char *p = o, *e; (e = strchr(p, '\n')); p = e + 1)
        assert_true(latex_width(p, (size_t)(e - p)) <= LATEX_LINE_UNITS);
    free(o);
}

/* no stray parentheses: 1 - t as a term of a sum is written bare (it was
 * ((1 - t) + k*t^2)); alone after a fraction bar it keeps them */
static void test_bar_in_sum(void **state)
{
    (void)state;
    expect("param t\nconst k\nx = 1/(1 - t + k*t^2)\ny = 1 - t + k*t^2\n"
           "z = (1 - t + k*t^2)^2\nw = t^2/(t - 1)\noutput x, y, z, w\n",
           FMT_TEXT,
           "x = 1/(1 - t + k*t^2)\ny = 1 - t + k*t^2\n"
           "z = (1 - t + k*t^2)^2\nw = -t^2/(1 - t)\n");
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* d printed in style st under a deadline of `deadline` s (0: none): the
 * text, its length in *len, the time in *took, and whether it was late */
static char *printed_within(const Derived *d, FormatStyle st, double deadline,
                            size_t *len, double *took, int *late)
{
    char *buf = NULL;
    FILE *f = open_memstream(&buf, len);
    budget_deadline_set(deadline);
    double t0 = now_s();
    format_derived(f, d, st, -1);
    *took = now_s() - t0;
    *late = budget_late();
    budget_deadline_set(0);
    fclose(f);
    return buf;
}

/* the whole text with no deadline, printed three times: its length and the
 * fastest of the three times (*full), the baseline a timed test compares
 * with on a loaded machine */
static char *printed_fastest(const Derived *d, FormatStyle st, size_t *len,
                             double *full)
{
    char *text = NULL;
    double took;
    int late;
    *full = 1e9;
    for (int k = 0; k < 3; k++) {
        free(text);
        text = printed_within(d, st, 0, len, &took, &late);
        *full = fmin(*full, took);
        assert_false(late);
    }
    return text;
}

/* The printer under the caller's deadline (budget.h).  The derivative of
 * a tower of 6 functions x_i = sin(x_(i-1)) + cos(i x_(i-1)) derives in
 * milliseconds and prints 110 KB of LaTeX; choosing each function's
 * argument rendered it twice per level (2^depth: 10 levels took a minute,
 * and went on past any deadline).  Timed first (the fastest of three):
 * past a deadline of an eighth of that time, the call returns well before
 * the whole would have, late, its text cut short ("+ \ldots"); past a deadline
 * that has already passed, a sum stops after its first term: a few dozen bytes.
 */
static void test_deadline(void **state)
{
    (void)state;
    char src[512], *p = src;
    p += sprintf(p, "point A, B\nparam t\nx0 = t\n");
    for (int i = 1; i <= 6; i++)
        p += sprintf(p, "x%d = sin(x%d) + cos(%d*x%d)\n", i, i - 1, i, i - 1);
    sprintf(p, "y = diff(x6, t)\nM = along(A, B, y)\n");
    Derived *d = derive_source("g.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    size_t len, full_len;
    double took, full;
    int late;
    char *text = printed_fastest(d, FMT_LATEX, &full_len, &full);
    assert_true(full_len > 100000);
    assert_null(strstr(text, "\\ldots"));
    free(text);
    text = printed_within(d, FMT_LATEX, full / 8, &len, &took, &late);
    assert_true(late);
    assert_true(took < 0.75 * full);
    assert_non_null(strstr(text, " + \\ldots"));
    free(text);
    text = printed_within(d, FMT_LATEX, 1e-9, &len, &took, &late);
    assert_true(late);
    assert_true(len < 200);
    assert_non_null(strstr(text, " + \\ldots"));
    free(text);
    derived_free(d);
}

/* JSON under the caller's deadline: its factors (shared between the
 * weights: book_factor) are looked for only before it.  60 products of
 * two polynomials, timed first (the fastest of three); past an eighth of
 * that time the rest is written expanded, and the call returns well
 * before the whole would have; past a deadline that has already passed, a
 * weight is its expanded product */
static void test_deadline_json(void **state)
{
    (void)state;
    char *src = malloc(16384), *p = src;
    p += sprintf(p, "param t, u\n");
    for (int i = 1; i <= 60; i++)
        p += sprintf(p,
                     "s%d = (t^9 + u^7 + t^2*u^3 + t*u + %d)*(t^7*u^4 + u^9 + "
                     "t^3*u + t + %d)\n",
                     i, i, 2 * i + 1);
    p += sprintf(p, "output s1");
    for (int i = 2; i <= 60; i++)
        p += sprintf(p, ", s%d", i);
    sprintf(p, "\n");
    Derived *d = derive_source("g.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    size_t len;
    double took, full;
    int late;
    char *text = printed_fastest(d, FMT_JSON, &len, &full);
    assert_non_null(strstr(
        text,
        "\"value\": \"(t^9+u^7+t^2*u^3+t*u+1)*(t^7*u^4+u^9+t^3*u+t+3)\""));
    free(text);
    text = printed_within(d, FMT_JSON, full / 8, &len, &took, &late);
    assert_true(late);
    assert_true(took < 0.75 * full);
    free(text);
    text = printed_within(d, FMT_JSON, 1e-9, &len, &took, &late);
    assert_true(late);
    assert_null(strstr(
        text,
        "\"value\": \"(t^9+u^7+t^2*u^3+t*u+1)*(t^7*u^4+u^9+t^3*u+t+3)\""));
    free(text);
    derived_free(d);
    free(src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bernstein_denominator),
        cmocka_unit_test(test_sign_and_basis_of_the_conic),
        cmocka_unit_test(test_collected_by_a_const),
        cmocka_unit_test(test_factor_order),
        cmocka_unit_test(test_factors_shared),
        cmocka_unit_test(test_json_factors_shared),
        cmocka_unit_test(test_minus_outside),
        cmocka_unit_test(test_vector_differences),
        cmocka_unit_test(test_latex_names),
        cmocka_unit_test(test_factor_known),
        cmocka_unit_test(test_irreducible_one_variable),
        cmocka_unit_test(test_quadratic_irreducible),
        cmocka_unit_test(test_surely_irreducible_products),
        cmocka_unit_test(test_multline),
        cmocka_unit_test(test_origin),
        cmocka_unit_test(test_conic_of_2_1_6),
        cmocka_unit_test(test_abs),
        cmocka_unit_test(test_roots_where_written),
        cmocka_unit_test(test_named_scalars),
        cmocka_unit_test(test_latex_break),
        cmocka_unit_test(test_bar_in_sum),
        cmocka_unit_test(test_deadline),
        cmocka_unit_test(test_deadline_json),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}
