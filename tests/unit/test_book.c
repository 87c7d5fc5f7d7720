/*
 * test_book.c - golden tests of how derive prints (compiler/book.c): every
 * rule of book.h with its expected text written by hand from the
 * mathematics, not taken from the printer.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "compiler/book.h"
#include "compiler/format.h"
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
        BookOptions o = {st == FMT_LATEX, width, origin, NULL};
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

#define DESARGUES                                                          \
    "point A, B, C, D\nparam t in [0, 1]\n"                                \
    "P = along(A, C, t)\nQ = along(C, B, t)\nK = along(B, D, t)\n"         \
    "N = along(P, Q, t)\nJ = along(Q, K, t)\n"                             \
    "T = meet(line(P, Q), line(A, B))\nS = meet(line(Q, K), line(C, D))\n" \
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
    static const char src[] =
        "point A, B, C\nparam u in [0, 1]\nconst w\n"
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
    char *x = printed_ex("param t\ns = (3 + t)*(2 + t)*(t^2 + 5)\n",
                         FMT_TEXT, 0, -1);
    char *y = printed_ex("param t\ns = (t^2 + 5)*(t + 2)*(t + 3)\n",
                         FMT_TEXT, 0, -1);
    assert_string_equal(x, y);
    assert_true(strcmp(x, "s = (2 + t)*(3 + t)*(5 + t^2)\n") == 0 ||
                strcmp(x, "s = (3 + t)*(2 + t)*(5 + t^2)\n") == 0);
    free(x);
    free(y);
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

/* an all-minus numerator is written -(...); the denominator's first term
 * is positive */
static void test_minus_outside(void **state)
{
    (void)state;
    expect("param t\nparam u\ns = (t + u^2)/(-1 - t)\n", FMT_TEXT,
           "s = -(t + u^2)/(1 + t)\n");
    expect("param t\ns = -3*t/(2 - t^2)\n", FMT_TEXT,
           "s = -3*t/(2 - t^2)\n");
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
           /* no common factor; 1 - t^2 factored (as many terms) */
           "V = -A*(1 - t - t^2) - B*t + C*(1 - t)*(1 + t)    (vector)\n");
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
    static const char src[] =
        "point A, B, C\nparam u in [0, 1]\nconst w\n"
        "R = (A*(1-u)^2 + 2*w*C*u*(1-u) + B*u^2)/"
        "((1-u)^2 + 2*w*u*(1-u) + u^2)\n";
    char *got = printed_ex(src, FMT_LATEX, 40, -1);
    assert_string_equal(
        got, "\\begin{multline*}\n"
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bernstein_denominator),
        cmocka_unit_test(test_sign_and_basis_of_the_conic),
        cmocka_unit_test(test_collected_by_a_const),
        cmocka_unit_test(test_factor_order),
        cmocka_unit_test(test_minus_outside),
        cmocka_unit_test(test_vector_differences),
        cmocka_unit_test(test_latex_names),
        cmocka_unit_test(test_factor_known),
        cmocka_unit_test(test_multline),
        cmocka_unit_test(test_origin),
        cmocka_unit_test(test_conic_of_2_1_6),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}
