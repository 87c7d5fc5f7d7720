/*
 * test_book_fast.c - the printer's shortcuts choose what the long way
 * chooses.  Its bounds on the form search
 * (compiler/print/book_forms.c, book_collect.c) never change what it
 * chooses: a collected form is given up once the leaves it has plus a
 * lower bound on those still to come (book_leaves_lower: 2 for a
 * coefficient that cannot be one product of vars and 1 - x's, the exact
 * count for one already chosen) exceed the best form's, and the tests
 * compare every print against the exhaustive search (BookOptions.
 * exhaustive: every collected form built whole) on random polynomials
 * made to have such coefficients, in text and LaTeX.
 *
 * Also the printer's cheapest proof of irreducibility, by images on lines
 * modulo small primes (compiler/algebra/polyfactor.c): it proves what no
 * single variable could, and never claims a product irreducible; and its
 * split of a polynomial in one variable into linear factors by its roots
 * modulo a prime, which gives FLINT's factors or nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/algebra/polyfactor.h"
#include "compiler/algebra/ring.h"
#include "compiler/print/book.h"
#include "libpointcalc.h"
#include "tests/unit/rand_algebra.h"

/* every output of src printed by book_output, the search exhaustive or
 * not (in style latex); malloc'd */
static char *printed(const Derived *d, int latex, int exhaustive)
{
    StrBuf b = {0};
    BookOptions o = {.latex = latex, .origin = -1, .exhaustive = exhaustive};
    o.memo = book_memo_new(); /* shared by the outputs, as format.c does */
    for (slong i = 0; i < d->noutputs; i++) {
        char *s = book_output(d, &d->outputs[i], &o);
        sb_puts(&b, s);
        pc_free(s);
    }
    book_memo_free(o.memo, d);
    return sb_take(&b);
}

static void put_int(StrBuf *b, int k)
{
    char x[16];
    snprintf(x, sizeof x, "%d", k);
    sb_puts(b, x);
}

/* one random product: a small integer times powers of t, u, a, b and of
 * 1 - t, 1 - a (one leaf each way it is written), now and then times a
 * sum of two terms (two leaves at least) */
static void rand_product(StrBuf *b, flint_rand_t st)
{
    static const char *const atom[] = {"t", "u",       "a",
                                       "b", "(1 - t)", "(1 - a)"};
    put_int(b, 1 + (int)n_randint(st, 4));
    for (int i = 0; i < 6; i++) {
        ulong e = n_randint(st, 4);
        if (e > 2)
            e = 0; /* half the atoms absent */
        if (e > 0) {
            sb_puts(b, "*");
            sb_puts(b, atom[i]);
            sb_puts(b, "^");
            put_int(b, (int)e);
        }
    }
    if (n_randint(st, 4) == 0) {
        sb_puts(b, "*(");
        put_int(b, 1 + (int)n_randint(st, 3));
        sb_puts(b, "*");
        sb_puts(b, atom[n_randint(st, 4)]);
        sb_puts(b, " + ");
        sb_puts(b, atom[n_randint(st, 6)]);
        sb_puts(b, ")");
    }
}

/* a random sum in powers of the const a whose coefficients are one
 * product each of t, u, 1 - t and 1 - u (one leaf, several terms): the
 * case the bound must count as one leaf */
static void rand_collected(StrBuf *b, flint_rand_t st)
{
    static const char *const atom[] = {"t", "u", "(1 - t)", "(1 - u)"};
    int n = 2 + (int)n_randint(st, 3);
    for (int k = 0; k < n; k++) {
        if (k > 0)
            sb_puts(b, n_randint(st, 3) == 0 ? " - " : " + ");
        put_int(b, 1 + (int)n_randint(st, 3));
        sb_puts(b, "*a^");
        put_int(b, k);
        for (int i = 0; i < 4; i++) {
            ulong e = n_randint(st, 3);
            if (e > 0) {
                sb_puts(b, "*");
                sb_puts(b, atom[i]);
                sb_puts(b, "^");
                put_int(b, (int)e);
            }
        }
    }
}

/* a random sum of 1 to 5 products, signs mixed, or (one time in three)
 * one collected in powers of a */
static void rand_sum(StrBuf *b, flint_rand_t st)
{
    if (n_randint(st, 3) == 0) {
        rand_collected(b, st);
        return;
    }
    int n = 1 + (int)n_randint(st, 5);
    for (int i = 0; i < n; i++) {
        if (i > 0)
            sb_puts(b, n_randint(st, 3) == 0 ? " - " : " + ");
        rand_product(b, st);
    }
}

/* a scalar and a point equation over a denominator, both random, printed
 * with and without the bounds: the same text */
static void test_bound_keeps_the_winner(void **state)
{
    (void)state;
    flint_rand_t st;
    rand_init(st);
    slong iters = rand_iters(150), differ = 0;
    for (slong k = 0; k < iters; k++) {
        StrBuf src = {0};
        sb_puts(&src, "point A, B\nparam t in [0, 1]\nparam u\nconst a, b\n"
                      "s = ");
        rand_sum(&src, st);
        sb_puts(&src, "\nM = (A*(");
        rand_sum(&src, st);
        sb_puts(&src, ") + B*(");
        rand_sum(&src, st);
        sb_puts(&src, "))/(");
        rand_sum(&src, st);
        sb_puts(&src, ")\noutput s\noutput M\n");
        Derived *d = derive_source("r.pcs", src.s, src.len, NULL, NULL);
        if (!d) { /* a zero denominator, say: another */
            pc_free(src.s);
            continue;
        }
        for (int latex = 0; latex < 2; latex++) {
            char *fast = printed(d, latex, 0);
            char *full = printed(d, latex, 1);
            if (strcmp(fast, full) != 0) {
                fprintf(stderr, "bounded search differs on\n%s\n%s\n%s\n",
                        src.s, fast, full);
                differ++;
            }
            pc_free(fast);
            pc_free(full);
        }
        derived_free(d);
        pc_free(src.s);
    }
    flint_randclear(st);
    assert_int_equal(differ, 0);
}

/* the bound itself, on random polynomials at every depth: never above
 * the leaves of the form chosen, and exact once that is remembered */
static void test_bound_below_the_leaves(void **state)
{
    (void)state;
    flint_rand_t st;
    rand_init(st);
    slong iters = rand_iters(300), checked = 0, twos = 0;
    for (slong k = 0; k < iters; k++) {
        StrBuf src = {0};
        sb_puts(&src, "param t in [0, 1]\nparam u\nconst a, b\ns = ");
        rand_sum(&src, st);
        sb_puts(&src, "\noutput s\n");
        Derived *d = derive_source("r.pcs", src.s, src.len, NULL, NULL);
        assert_non_null(d);
        for (int depth = 0; depth <= 2; depth++) {
            slong lower[2];
            slong n =
                book_test_leaves(d, d->outputs[0].scalar->num, depth, lower);
            if (lower[0] > n || lower[1] != n)
                fprintf(stderr, "%s: depth %d, %ld leaves, bound %ld, %ld\n",
                        src.s, depth, (long)n, (long)lower[0], (long)lower[1]);
            assert_true(lower[0] <= n);
            assert_int_equal(lower[1], n);
            checked++;
            twos += lower[0] == 2;
        }
        derived_free(d);
        pc_free(src.s);
    }
    flint_randclear(st);
    assert_true(checked > 0);
    assert_true(twos > 0); /* the bound is not only 1 */
}

/* the bound's cases by hand, where the one-leaf coefficients decide:
 * collected by u (a param, before the const a: the first of equal forms),
 * the coefficients are 1 + t^2 + a^2*t*(1 - t)^2 (three leaves, itself
 * collected by a, its terms joining the sum) and 2*a*(1 - t) (one leaf: the
 * bound may not count it as two); 4 leaves against the expanded form's 9
 * terms; the exhaustive search agrees */
static void test_one_leaf_coefficients(void **state)
{
    (void)state;
    static const char src[] = "param t in [0, 1]\nparam u\nconst a\n"
                              "s = a^2*t*(1 - t)^2 + 2*a*u*(1 - t) + 1 + t^2\n";
    Derived *d = derive_source("h.pcs", src, strlen(src), NULL, NULL);
    assert_non_null(d);
    char *fast = printed(d, 0, 0);
    char *full = printed(d, 0, 1);
    assert_string_equal(full, fast);
    assert_string_equal(fast, "s = 1 + t^2 + a^2*t*(1 - t)^2 + "
                              "2*a*(1 - t)*u\n");
    pc_free(fast);
    pc_free(full);
    derived_free(d);
}

static const char *const names[] = {"x", "y", "z"};

static void set_str(fmpz_mpoly_t p, const char *s, const Ring *r)
{
    assert_int_equal(
        fmpz_mpoly_set_str_pretty(p, s, (const char **)names, r->ctx), 0);
}

/* dense in each variable (every coefficient of every power has two terms
 * or more, no variable of degree 1): only the lines prove these
 * irreducible (irreducible by SymPy's factor_list) */
static void test_irreducible_on_lines(void **state)
{
    (void)state;
    Ring r;
    ring_init(&r, 3, names);
    fmpz_mpoly_t p;
    fmpz_mpoly_init(p, r.ctx);
    set_str(p, "x^2*y + x^2 + x*y^2 + x + y^2 + y + 1", &r);
    assert_true(book_test_surely_irreducible(p, &r));
    set_str(p, "x^2*y^2 + x^2*y + x^2 + x*y^2 + 2*x*y + x + y^2 + y + 3", &r);
    assert_true(book_test_surely_irreducible(p, &r));
    /* the product of the two (and a square) is no such thing */
    fmpz_mpoly_t f, g;
    fmpz_mpoly_init(f, r.ctx);
    fmpz_mpoly_init(g, r.ctx);
    set_str(f, "x^2*y + x^2 + x*y^2 + x + y^2 + y + 1", &r);
    fmpz_mpoly_mul(g, f, p, r.ctx);
    assert_false(book_test_surely_irreducible(g, &r));
    fmpz_mpoly_mul(g, f, f, r.ctx);
    assert_false(book_test_surely_irreducible(g, &r));
    fmpz_mpoly_clear(g, r.ctx);
    fmpz_mpoly_clear(f, r.ctx);
    fmpz_mpoly_clear(p, r.ctx);
    ring_clear(&r);
}

/* random products of two polynomials dense in x, y, z (each coefficient
 * of two terms or more, as above, of total degree 2 to 6): never proved
 * irreducible, by the lines or any other way */
static void test_lines_never_claim_a_product(void **state)
{
    (void)state;
    flint_rand_t st;
    rand_init(st);
    Ring r;
    ring_init(&r, 3, names);
    fmpz_mpoly_t f[2], p;
    fmpz_mpoly_init(f[0], r.ctx);
    fmpz_mpoly_init(f[1], r.ctx);
    fmpz_mpoly_init(p, r.ctx);
    slong iters = rand_iters(400);
    for (slong k = 0; k < iters; k++) {
        for (int j = 0; j < 2; j++) {
            fmpz_mpoly_zero(f[j], r.ctx);
            slong nv = 2 + (slong)n_randint(st, 2);
            for (int t = 0; t < 8; t++) {
                ulong e[3] = {n_randint(st, 3), n_randint(st, 3), 0};
                if (nv == 3)
                    e[2] = n_randint(st, 2);
                fmpz_mpoly_set_coeff_si_ui(f[j], 1 + (slong)n_randint(st, 4), e,
                                           r.ctx);
            }
            fmpz_mpoly_add_si(f[j], f[j], 1, r.ctx); /* no monomial factor */
        }
        fmpz_mpoly_mul(p, f[0], f[1], r.ctx);
        if (fmpz_mpoly_total_degree_si(f[0], r.ctx) < 1 ||
            fmpz_mpoly_total_degree_si(f[1], r.ctx) < 1)
            continue;
        assert_false(book_test_surely_irreducible(p, &r));
    }
    fmpz_mpoly_clear(p, r.ctx);
    fmpz_mpoly_clear(f[1], r.ctx);
    fmpz_mpoly_clear(f[0], r.ctx);
    ring_clear(&r);
    flint_randclear(st);
}

/* f and g hold the same factors with the same powers (in any order) and
 * the same constant */
static int same_factoring(const fmpz_mpoly_factor_t f,
                          const fmpz_mpoly_factor_t g, const Ring *r)
{
    if (f->num != g->num || !fmpz_equal(f->constant, g->constant))
        return 0;
    for (slong i = 0; i < f->num; i++) {
        int found = 0;
        for (slong j = 0; j < g->num && !found; j++)
            found = fmpz_mpoly_equal(f->poly + i, g->poly + j, r->ctx) &&
                    fmpz_equal(f->exp + i, g->exp + j);
        if (!found)
            return 0;
    }
    return 1;
}

/* random c * x^k * prod (a x - b): split by the roots as FLINT factors it;
 * with a repeated root, an irreducible quadratic factor or a root past
 * the prime's reach (b = 1000), not split (FLINT's factoring does it) */
static void test_split_linear(void **state)
{
    (void)state;
    flint_rand_t st;
    rand_init(st);
    Ring r;
    ring_init(&r, 3, names);
    fmpz_mpoly_t p, lin;
    fmpz_mpoly_init(p, r.ctx);
    fmpz_mpoly_init(lin, r.ctx);
    fmpz_mpoly_factor_t f, g;
    slong iters = rand_iters(200), split = 0;
    for (slong k = 0; k < iters; k++) {
        int kind = (int)n_randint(st, 5); /* 0, 1: linear; 2: repeated
                                           * root; 3: quadratic; 4: far */
        slong x = (slong)n_randint(st, 3);
        fmpz_mpoly_set_si(p, (slong)n_randint(st, 7) - 3, r.ctx);
        if (fmpz_mpoly_is_zero(p, r.ctx))
            fmpz_mpoly_one(p, r.ctx);
        fmpz_mpoly_gen(lin, x, r.ctx);
        fmpz_mpoly_pow_ui(lin, lin, n_randint(st, 3), r.ctx);
        fmpz_mpoly_mul(p, p, lin, r.ctx);
        slong n = 2 + (slong)n_randint(st, 8), ra[10], rb[10];
        for (slong i = 0; i < n; i++) { /* (a x - b), b != 0, b/a new */
            slong a, b;
            int again;
            do {
                a = 1 + (slong)n_randint(st, 12);
                b = (1 + (slong)n_randint(st, 60)) *
                    (n_randint(st, 2) ? 1 : -1);
                again = n_gcd((ulong)a, (ulong)labs(b)) != 1;
                for (slong j = 0; j < i && !again; j++)
                    again = ra[j] == a && rb[j] == b;
            } while (again);
            ra[i] = a;
            rb[i] = b;
            fmpz_mpoly_gen(lin, x, r.ctx);
            fmpz_mpoly_scalar_mul_si(lin, lin, a, r.ctx);
            fmpz_mpoly_sub_si(lin, lin, b, r.ctx);
            fmpz_mpoly_mul(p, p, lin, r.ctx);
        }
        if (kind >= 2) {
            fmpz_mpoly_gen(lin, x, r.ctx);
            if (kind == 2)
                fmpz_mpoly_sub_si(lin, lin, 1, r.ctx);
            if (kind == 3)
                fmpz_mpoly_mul(lin, lin, lin, r.ctx);
            fmpz_mpoly_add_si(lin, lin, kind == 4 ? 1000 : 3, r.ctx);
            if (kind == 2)
                fmpz_mpoly_mul(lin, lin, lin, r.ctx); /* (x + 2)^2 */
            fmpz_mpoly_mul(p, p, lin, r.ctx);
        }
        fmpz_mpoly_factor_init(f, r.ctx);
        fmpz_mpoly_factor_init(g, r.ctx);
        int ok = polyfactor_split_linear(f, p, &r);
        assert_true(ring_factor(g, p, &r));
        if (kind < 2) {
            assert_true(ok);
            split++;
        }
        if (kind >= 2)
            assert_false(ok);
        if (ok)
            assert_true(same_factoring(f, g, &r));
        fmpz_mpoly_factor_clear(g, r.ctx);
        fmpz_mpoly_factor_clear(f, r.ctx);
    }
    assert_true(split > 0);
    /* in two variables: not this way */
    set_str(p, "(x - 1)*(y - 2)", &r);
    fmpz_mpoly_factor_init(f, r.ctx);
    assert_false(polyfactor_split_linear(f, p, &r));
    fmpz_mpoly_factor_clear(f, r.ctx);
    fmpz_mpoly_clear(lin, r.ctx);
    fmpz_mpoly_clear(p, r.ctx);
    ring_clear(&r);
    flint_randclear(st);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bound_keeps_the_winner),
        cmocka_unit_test(test_bound_below_the_leaves),
        cmocka_unit_test(test_one_leaf_coefficients),
        cmocka_unit_test(test_irreducible_on_lines),
        cmocka_unit_test(test_lines_never_claim_a_product),
        cmocka_unit_test(test_split_linear),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}
