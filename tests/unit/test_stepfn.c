/*
 * test_stepfn.c - the step blocks ramp, step, rayr, rayl (compiler/derive/
 * functions.c; docs/language.md "Step functions"), against expectations
 * made independently of their code:
 *
 *   - values: step(t, a, w, m) at exact points left of, on, inside and
 *     right of [a, a + w], for every m = 0 .. 10, against the regularized
 *     incomplete beta function I_s(m + 1, m + 1) = the integral of
 *     x^m (1 - x)^m from 0 to s over the same from 0 to 1, summed here
 *     term by term (the smoothstep is the C^m step whose derivative is a
 *     multiple of s^m (1 - s)^m); for w < 0 the step rises on [a + w, a];
 *   - the text's formulas (Dolya, 2.1 (3), (5), (6), (9)) typed in, with a
 *     symbolic start and width: the difference derives to 0;
 *   - smoothness, exactly: derivative j of step(t, a, w, m) is
 *     p0 + sum sign(x_k)*c_k with every c_k divisible by x_k (continuous)
 *     for j <= m, and for j = m + 1 the jump at t = a is
 *     p^(m+1)(0)/w^(m+1) = (2m + 1)!/m!/w^(m+1);
 *   - printing: the text's printed forms of P_1^3(t, 0, 1), P_1^3(t, 1, 1)
 *     (2.1 ex. 4), the square of 2.1 ex. 5 and of 2.2 ex. 1, Q(t, 3), as
 *     the text writes them (hand-typed, in the house order: ascending
 *     coefficients, |x| last in a product), text and LaTeX;
 *   - names: `step` and `ramp` stay free for points and definitions; the
 *     errors (zero width, the order m, arity, a point argument) located.
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

#include <flint/fmpq.h>

#include "compiler/algebra/kernel.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

static Derived *derive_ok(const char *src)
{
    Derived *d = derive_source("s.pcs", src, strlen(src), stderr, NULL);
    assert_non_null(d);
    return d;
}

/* the errors of src, as text */
static char *errors_of(const char *src)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    int n = 0;
    Derived *d = derive_source("s.pcs", src, strlen(src), f, &n);
    fclose(f);
    assert_null(d);
    assert_true(n > 0);
    return buf;
}

/* I_s(m + 1, m + 1) = sum_k C(m, k) (-1)^k s^(m+k+1)/(m+k+1), over the
 * same at s = 1 */
static void beta_step(fmpq_t res, const fmpq_t s, slong m)
{
    fmpq_t num, den, term, pw;
    fmpq_init(num);
    fmpq_init(den);
    fmpq_init(term);
    fmpq_init(pw);
    fmpz_t bin;
    fmpz_init(bin);
    for (slong k = 0; k <= m; k++) {
        fmpz_bin_uiui(bin, (ulong)m, (ulong)k);
        if (k & 1)
            fmpz_neg(bin, bin);
        fmpq_set_fmpz_frac(term, bin, (fmpz[]){m + k + 1}); /* small */
        fmpq_add(den, den, term);
        fmpq_pow_si(pw, s, m + k + 1);
        fmpq_mul(term, term, pw);
        fmpq_add(num, num, term);
    }
    fmpq_div(res, num, den);
    fmpz_clear(bin);
    fmpq_clear(pw);
    fmpq_clear(term);
    fmpq_clear(den);
    fmpq_clear(num);
}

/* step(t, a, w, m) at t = a + s*w for s in a list (s < 0 and s > 1 too),
 * w = 3/2 and w = -3/2, a = 5/7 */
static void test_values(void **state)
{
    (void)state;
    static const char *const ss[] = {"-1/5", "0",   "1/3", "2/7",
                                     "1/2",  "5/6", "1",   "8/7"};
    enum { NS = sizeof ss / sizeof *ss };
    for (int neg = 0; neg < 2; neg++)
        for (slong m = 0; m <= 10; m++) {
            char src[4096];
            int k = snprintf(src, sizeof src, "param t\n");
            for (int i = 0; i < NS; i++)
                k +=
                    snprintf(src + k, sizeof src - (size_t)k,
                             "v%d = step(5/7 + (%s)*(%s3/2), 5/7, %s3/2, "
                             "%ld)\n",
                             i, ss[i], neg ? "-" : "", neg ? "-" : "", (long)m);
            k += snprintf(src + k, sizeof src - (size_t)k, "output v0");
            for (int i = 1; i < NS; i++)
                k += snprintf(src + k, sizeof src - (size_t)k, ", v%d", i);
            snprintf(src + k, sizeof src - (size_t)k, "\n");
            Derived *d = derive_ok(src);
            assert_int_equal(d->noutputs, NS);
            fmpq_t s, want, got;
            fmpq_init(s);
            fmpq_init(want);
            fmpq_init(got);
            for (int i = 0; i < NS; i++) {
                assert_int_equal(fmpq_set_str(s, ss[i], 10), 0);
                if (fmpq_sgn(s) <= 0)
                    fmpq_zero(want);
                else if (fmpq_cmp_si(s, 1) >= 0)
                    fmpq_one(want);
                else
                    beta_step(want, s, m);
                /* w < 0: t = a + s*w lies in [a + w, a] read backwards,
                 * where the step is 1 - p(s); beyond a (s < 0) it is 1,
                 * before a + w (s > 1) 0 */
                if (neg) {
                    fmpq_neg(want, want);
                    fmpq_add_si(want, want, 1);
                }
                assert_true(
                    ratfun_get_fmpq(got, d->outputs[i].scalar, &d->ring));
                if (!fmpq_equal(got, want)) {
                    char *g = fmpq_get_str(NULL, 10, got);
                    char *w = fmpq_get_str(NULL, 10, want);
                    fprintf(stderr, "m=%ld s=%s w<0=%d: got %s, want %s\n",
                            (long)m, ss[i], neg, g, w);
                    flint_free(g);
                    flint_free(w);
                }
                assert_true(fmpq_equal(got, want));
            }
            fmpq_clear(got);
            fmpq_clear(want);
            fmpq_clear(s);
            derived_free(d);
        }
}

/* each difference with the text's formula is 0, for symbolic a and w */
static void test_text_formulas(void **state)
{
    (void)state;
    Derived *d = derive_ok(
        "param t\nconst a, w\n"
        /* (3) */
        "d0 = ramp(t, a, w) - (w + abs(t - a) - abs(t - a - w))/(2*w)\n"
        /* (5) */
        "d1 = step(t, a, w, 1) - (w^3 + (-2*t + 2*a + 3*w)*(t - a)*abs(t - "
        "a) + (2*t - 2*a + w)*(t - a - w)*abs(t - a - w))/(2*w^3)\n"
        /* (6) */
        "d2 = step(t, a, w, 2) - (w^5 + (6*t^2 - 3*t*(5*w + 4*a) + 10*w^2 + "
        "15*w*a + 6*a^2)*abs(t - a)^3 - (6*t^2 + 3*t*(w - 4*a) + w^2 - 3*w*a "
        "+ 6*a^2)*abs(t - a - w)^3)/(2*w^5)\n"
        /* (9) */
        "d3 = rayr(t, a) - (t - a + abs(t - a))/2\n"
        "d4 = rayl(t, a) - (t - a - abs(t - a))/2\n"
        /* m = 0 is the ramp; Q + Q_l = t - a */
        "d5 = step(t, a, w, 0) - ramp(t, a, w)\n"
        "d6 = rayr(t, a) + rayl(t, a) - (t - a)\n"
        "output d0, d1, d2, d3, d4, d5, d6\n");
    for (slong i = 0; i < d->noutputs; i++) {
        if (!ratfun_is_zero(d->outputs[i].scalar, &d->ring))
            fprintf(stderr, "%s is not 0\n", d->outputs[i].name);
        assert_true(ratfun_is_zero(d->outputs[i].scalar, &d->ring));
    }
    derived_free(d);
}

/* 1 when every sign kernel's coefficient in x's numerator is divisible by
 * the kernel's argument (x continuous); *jump = the jump at t = tk of the
 * kernel sign(t - tk) (2*c(tk)/den: sign goes from -1 to 1), if it has one */
static int continuous(const Derived *d, const RatFun x, const fmpq_t tk,
                      fmpq_t jump)
{
    const Ring *r = &d->ring;
    const Kernels *K = d->kernels;
    int cont = 1;
    fmpq_zero(jump);
    fmpz_mpoly_t c, q;
    fmpz_mpoly_init(c, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    for (slong i = 0; K && i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_SIGN)
            continue;
        ulong one = 1;
        fmpz_mpoly_get_coeff_vars_ui(c, x->num, &k->var, &one, 1, r->ctx);
        if (fmpz_mpoly_is_zero(c, r->ctx) ||
            fmpz_mpoly_divides(q, c, k->arg->num, r->ctx))
            continue;
        cont = 0;
        /* the value of c at t = tk (c is a polynomial in t only here) */
        fmpq *vals = _fmpq_vec_init(r->nvars);
        fmpq_set(vals + 0, tk);
        RatFun cr, arg;
        ratfun_init(cr, r);
        ratfun_init(arg, r);
        fmpz_mpoly_set(arg->num, k->arg->num, r->ctx);
        fmpz_mpoly_set(arg->den, k->arg->den, r->ctx);
        fmpz_mpoly_set(cr->num, c, r->ctx);
        fmpz_mpoly_set(cr->den, x->den, r->ctx);
        ratfun_canonicalise(cr, r);
        fmpq_t at;
        fmpq_init(at);
        assert_int_equal(ratfun_evaluate_fmpq(at, arg, vals, r), 0);
        if (fmpq_is_zero(at)) { /* this kernel's knot is tk */
            assert_int_equal(ratfun_evaluate_fmpq(at, cr, vals, r), 0);
            fmpq_mul_si(jump, at, 2);
        }
        fmpq_clear(at);
        ratfun_clear(arg, r);
        ratfun_clear(cr, r);
        _fmpq_vec_clear(vals, r->nvars);
    }
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(c, r->ctx);
    return cont;
}

/* derivative j of step(t, 1, 2, m): continuous for j <= m; for j = m + 1
 * the jump at t = 1 is (2m + 1)!/m!/2^(m+1) */
static void test_smoothness(void **state)
{
    (void)state;
    for (slong m = 0; m <= 5; m++) {
        char src[1024];
        int k = snprintf(src, sizeof src, "param t\nf = step(t, 1, 2, %ld)\n",
                         (long)m);
        for (slong j = 0; j <= m + 1; j++)
            k += snprintf(src + k, sizeof src - (size_t)k,
                          "d%ld = diff(f, t, %ld)\n", (long)j, (long)j);
        k += snprintf(src + k, sizeof src - (size_t)k, "output d0");
        for (slong j = 1; j <= m + 1; j++)
            k += snprintf(src + k, sizeof src - (size_t)k, ", d%ld", (long)j);
        snprintf(src + k, sizeof src - (size_t)k, "\n");
        Derived *d = derive_ok(src);
        assert_int_equal(d->nparams, 1); /* t is ring variable 0 */
        fmpq_t tk, jump, want;
        fmpq_init(tk);
        fmpq_init(jump);
        fmpq_init(want);
        fmpq_set_si(tk, 1, 1);
        for (slong j = 0; j <= m + 1; j++) {
            int cont = continuous(d, d->outputs[j].scalar, tk, jump);
            assert_int_equal(cont, j <= m);
        }
        /* (2m + 1)!/m! / w^(m+1), w = 2 */
        fmpz_t f;
        fmpz_init(f);
        fmpz_fac_ui(f, (ulong)(2 * m + 1));
        fmpq_set_fmpz_frac(want, f, (fmpz[]){1});
        fmpz_fac_ui(f, (ulong)m);
        fmpz_mul_2exp(f, f, (ulong)(m + 1));
        fmpq_div_fmpz(want, want, f);
        fmpz_clear(f);
        continuous(d, d->outputs[m + 1].scalar, tk, jump);
        assert_true(fmpq_equal(jump, want));
        fmpq_clear(want);
        fmpq_clear(jump);
        fmpq_clear(tk);
        derived_free(d);
    }
}

static char *printed(const char *src, FormatStyle st)
{
    Derived *d = derive_ok(src);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    format_derived(f, d, st, -1);
    fclose(f);
    derived_free(d);
    return buf;
}

static void expect_printed(const char *src, FormatStyle st, const char *want)
{
    char *got = printed(src, st);
    assert_string_equal(got, want);
    free(got);
}

/* the text's printed forms, typed from the text (house order) */
static void test_printing(void **state)
{
    (void)state;
    /* 2.1 ex. 4: P_1^3(t, 0, 1) = 1/2 (1 + (3 - 2t)t|t| + (2t + 1)(t - 1)
     * |t - 1|) */
    expect_printed("param t\nv = step(t, 0, 1, 1)\n", FMT_TEXT,
                   "v = (1 + (3 - 2*t)*t*abs(t) + (1 + 2*t)*(t - 1)*abs(t - "
                   "1))/2\n");
    expect_printed(
        "param t\nv = step(t, 0, 1, 1)\n", FMT_LATEX,
        "\\[ v = \\frac{1 + \\left(3 - 2 t\\right) t \\left|t\\right| "
        "+ \\left(1 + 2 t\\right) \\left(t - 1\\right) \\left|t - "
        "1\\right|}{2} \\]\n");
    /* P_1^3(t, 1, 1) = 1/2 (1 + (-2t + 5)(t - 1)|t - 1| + (2t - 1)(t - 2)
     * |t - 2|) */
    expect_printed("param t\nv = step(t, 1, 1, 1)\n", FMT_TEXT,
                   "v = (1 + (5 - 2*t)*(t - 1)*abs(t - 1) + (2*t - 1)*(t - "
                   "2)*abs(t - 2))/2\n");
    /* 2.1 ex. 5: x(t) = 1/2 ((6t^2 - 15t + 10)|t|^3 - (6t^2 + 3t + 1)
     * |t - 1|^3 - (6t^2 - 39t + 64)|t - 2|^3 + (6t^2 - 21t + 19)|t - 3|^3) */
    expect_printed("param t\nx = step(t, 0, 1, 2) - step(t, 2, 1, 2)\n",
                   FMT_TEXT,
                   "x = ((10 - 15*t + 6*t^2)*abs(t)^3 - (1 + 3*t + "
                   "6*t^2)*abs(t - 1)^3 - (64 - 39*t + 6*t^2)*abs(t - 2)^3 + "
                   "(19 - 21*t + 6*t^2)*abs(t - 3)^3)/2\n");
    /* 2.3.4: the clamped spline's x(t) = (60t^3 - 360t^2 + 1039t -
     * 1083)/7 - 43/7 |t-1|^3 + 43/7 |t-3|^3 (docs/errata.md D9): a free
     * part that would start with a minus is written in descending powers,
     * not with its positive terms first (1039*t - 360*t^2 + 60*t^3 - ...) */
    expect_printed("param t\nx = (60*t^3 - 360*t^2 + 1039*t - 1083)/7 - "
                   "43*abs(t - 1)^3/7 + 43*abs(t - 3)^3/7\n",
                   FMT_TEXT,
                   "x = (60*t^3 - 360*t^2 + 1039*t - 1083 - 43*abs(t - 1)^3 + "
                   "43*abs(t - 3)^3)/7\n");
    /* a scalar keeps its free part first, as the text writes x(t) = -2 +
     * t - |t + 1| + |t - 1|; in a point's weight a negative free part goes
     * last rather than a minus in front of the whole (the square's O
     * weight on t in [0, 4]) */
    expect_printed("param t\nx = abs(t - 1) + abs(t - 3) - 2\n", FMT_TEXT,
                   "x = -2 + abs(t - 1) + abs(t - 3)\n");
    expect_printed("point O, A\nparam t\nR = O + (A - O)*(3 - abs(t - 1) - "
                   "abs(t - 3))\n",
                   FMT_TEXT,
                   "R = O*(abs(t - 1) + abs(t - 3) - 2) + A*(3 - abs(t - 1) "
                   "- abs(t - 3))\n");
    /* 2.2 ex. 1: x = P(t,0,1) - P(t,2,1) = 1/2 (|t| - |t-1| - |t-2| +
     * |t-3|) */
    expect_printed("param t\nx = ramp(t, 0, 1) - ramp(t, 2, 1)\n", FMT_TEXT,
                   "x = (abs(t) - abs(t - 1) - abs(t - 2) + abs(t - 3))/2\n");
    /* in the order of the knots even with a leading minus: -(P(t,0,1) -
     * P(t,2,1)) */
    expect_printed("param t\nx = ramp(t, 2, 1) - ramp(t, 0, 1)\n", FMT_TEXT,
                   "x = -(abs(t) - abs(t - 1) - abs(t - 2) + abs(t - 3))/2\n");
    /* 2.2 ex. 2: 1 + Q_l(t,1) - P(t,2,1) = 1/2 (t - |t-1| - |t-2| +
     * |t-3|), P(t,1,1) - Q(t,3) = 1/2 (4 - t + |t-1| - |t-2| - |t-3|) */
    expect_printed("param t\nx = 1 + rayl(t, 1) - ramp(t, 2, 1)\n"
                   "y = ramp(t, 1, 1) - rayr(t, 3)\noutput x, y\n",
                   FMT_TEXT,
                   "x = (t - abs(t - 1) - abs(t - 2) + abs(t - 3))/2\n"
                   "y = (4 - t + abs(t - 1) - abs(t - 2) - abs(t - 3))/2\n");
    /* Theorem 3, example 5 of 2.1: y = t^2 - 1 + (t + 1)|t - 1|/2 +
     * (1 - t)|t + 1|/2, the free part first with a positive lead */
    expect_printed("param t\ny = t^2 - 1 + (t + 1)*abs(t - 1)/2 + "
                   "(1 - t)*abs(t + 1)/2\n",
                   FMT_TEXT,
                   "y = (2*t^2 - 2 + (1 - t)*abs(t + 1) + (1 + t)*abs(t - "
                   "1))/2\n");
    /* (9): Q(t, 3) = 1/2 (t - 3 + |t - 3|), Q_l(t, 3) = 1/2 (t - 3 - |t -
     * 3|) */
    expect_printed("param t\nq = rayr(t, 3)\nql = rayl(t, 3)\noutput q, ql\n",
                   FMT_TEXT,
                   "q = (t - 3 + abs(t - 3))/2\nql = (t - 3 - abs(t - 3))/2\n");
    /* on a declared range that makes t >= 0, |t| is t (valid on the whole
     * range, sign(t) only multiplying t^2): (3 - 2t)t|t| = 3t^2 - 2t^3 */
    expect_printed("param t in [0, 4]\nv = step(t, 0, 1, 1)\n", FMT_TEXT,
                   "v = (1 + 3*t^2 - 2*t^3 + (1 + 2*t)*(t - 1)*abs(t - "
                   "1))/2\n");
    /* a knot that is not whole: |t - 1/2| = |2t - 1|/2, and ramp(t, 1/2,
     * 1/3) = 1/2 + (3/2)|t - 1/2| - (3/2)|t - 5/6| */
    expect_printed("param t\nx = abs(t - 1/2)\ny = ramp(t, 1/2, 1/3)\n"
                   "output x, y\n",
                   FMT_TEXT,
                   "x = abs(2*t - 1)/2\n"
                   "y = (2 + 3*abs(2*t - 1) - abs(6*t - 5))/4\n");
    expect_printed("param t\nx = abs(t - 1/2)\n", FMT_LATEX,
                   "\\[ x = \\frac{\\left|2 t - 1\\right|}{2} \\]\n");
    /* a printed result never has x*sign(x) */
    char *s = printed("param t\nv = diff(step(t, 0, 1, 3), t, 2)\n", FMT_TEXT);
    assert_null(strstr(s, "sign"));
    free(s);
}

/* step and ramp stay names of the scheme's own; errors located */
static void test_names_and_errors(void **state)
{
    (void)state;
    Derived *d = derive_ok("point step, ramp\nparam t\n"
                           "rayr = step + (ramp - step)*ramp(t, 0, 1)\n"
                           "M = rayr + (step - rayr)*step(t, 1, 1, 2)\n");
    derived_free(d);
    char *e = errors_of("param t\nv = step(t, 0, 2 - 2, 1)\n");
    assert_non_null(strstr(e, "s.pcs:2:16: error: the width of step() is "
                              "zero"));
    free(e);
    e = errors_of("param t\nv = ramp(t, 1, 0)\n");
    assert_non_null(strstr(e, "s.pcs:2:16: error: the width of ramp() is "
                              "zero"));
    free(e);
    e = errors_of("param t\nv = step(t, 0, 1, 11)\n");
    assert_non_null(strstr(e, "s.pcs:2:19: error: expected the smoothness "
                              "of step() as a whole number from 0 to 10"));
    free(e);
    e = errors_of("param t\nv = step(t, 0, 1, t)\n");
    assert_non_null(strstr(e, "s.pcs:2:19: error: expected the smoothness"));
    free(e);
    e = errors_of("param t\nv = ramp(t, 0)\n");
    assert_non_null(
        strstr(e, "s.pcs:2:5: error: ramp() takes 3 arguments, found 2"));
    free(e);
    e = errors_of("point A\nparam t\nv = rayr(A, 0)\n");
    assert_non_null(strstr(e, "s.pcs:3:10: error: expected a scalar"));
    free(e);
    /* int constants give m */
    d = derive_ok("int m = 2\nparam t\nv = step(t, 0, 1, m - 1) - "
                  "step(t, 0, 1, 1)\n");
    assert_true(ratfun_is_zero(d->outputs[0].scalar, &d->ring));
    derived_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values),
        cmocka_unit_test(test_text_formulas),
        cmocka_unit_test(test_smoothness),
        cmocka_unit_test(test_printing),
        cmocka_unit_test(test_names_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
