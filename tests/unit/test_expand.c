/*
 * test_expand.c - compiler/expand.c: the pass between the parser and sema
 * that unrolls int constants (`int n = 3`, overridden by -D), families
 * (`point M[1..n]` -> M_1 ... M_n), members and ranges among a call's
 * arguments, comprehensions inside `solve` and the name lists of `solve
 * ... for` and `output`.  The expanded AST is checked with ast_dump
 * against S-expressions written by hand; every error expand reports
 * (indices out of range, families and comprehensions too large, integers
 * too large, inexact divisions, redefinitions and member-name clashes) is
 * checked with its exact text, line, column and caret.  Also
 * expand_check_define (the command line's -D usage check) and the
 * defines option of derive_source_ex.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/arena.h"
#include "base/diag.h"
#include "compiler/derive.h"
#include "compiler/expand.h"
#include "grammar/ast.h"
#include "grammar/parse.h"

/* Parses text (which must parse), expands it with the defines and returns
 * the AST dump when expand reported no error, else the diagnostics;
 * *nerrors = the count expand returned (also checked against the Diag's).
 * The caller frees the text. */
static char *expand_with(const char *text, const char *const *defines,
                         int ndefines, char *used, int *nerrors)
{
    Arena a;
    Source src;
    Diag d;
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    arena_init(&a);
    source_init(&src, "x.pcs", text, strlen(text));
    diag_init(&d, &src, mem);
    Scheme *s = parse_scheme(&src, &a, &d);
    assert_int_equal(d.nerrors, 0);
    int n = expand_scheme(s, &a, &d, defines, ndefines, used);
    assert_int_equal(n, d.nerrors);
    if (n == 0)
        ast_dump(mem, s);
    fclose(mem);
    *nerrors = n;
    source_clear(&src);
    arena_reset(&a);
    return out;
}

static char *expand_text(const char *text, int *nerrors)
{
    char unused = 0;
    return expand_with(text, NULL, 0, &unused, nerrors);
}

/* asserts that text expands without error to want */
static void expands_to(const char *text, const char *want)
{
    int n;
    char *s = expand_text(text, &n);
    if (n != 0)
        fprintf(stderr, "unexpected diagnostics:\n%s", s);
    assert_int_equal(n, 0);
    assert_string_equal(s, want);
    free(s);
}

/* asserts that text gives nerrors errors, with exactly the diagnostics want */
static void fails_with(const char *text, int nerrors, const char *want)
{
    int n;
    char *s = expand_text(text, &n);
    assert_int_equal(n, nerrors);
    assert_string_equal(s, want);
    free(s);
}

/* ---- int constants ----------------------------------------------------- */

static void test_int_is_substituted(void **state)
{
    (void)state;
    /* the int statement itself is kept as written; every use becomes the
     * number */
    expands_to("int n = 3\npoint A, B\nparam t\nM = along(A, B, t/n)\n"
               "x = n*2 - n^2\n",
               "(int n 3)\n(point A B)\n(param t)\n"
               "(def M (along A B (/ t 3)))\n"
               "(def x (- (* 3 2) (^ 3 2)))\n");
}

static void test_int_expressions(void **state)
{
    (void)state;
    /* n = 5, m = 25/5 = 5: the family has five members */
    expands_to("int n = 2*3 - 1\nint m = n^2/5\npoint P[1..m]\n",
               "(int n (- (* 2 3) 1))\n(int m (/ (^ n 2) 5))\n"
               "(point P_1 P_2 P_3 P_4 P_5)\n");
    /* a negative int is written -|v| */
    expands_to("int n = 2 - 5\nx = n\n", "(int n (- 2 5))\n(def x (neg 3))\n");
    /* powers: (-1)^3 = -1, (-2)^3 = -8, 0^0 = 1, (-1)^4 = 1 */
    expands_to("int a = (-1)^3\nint b = (-2)^3\nint c = 0^0\nint d = (-1)^4\n"
               "x = a + b + c + d\n",
               "(int a (^ (neg 1) 3))\n(int b (^ (neg 2) 3))\n(int c (^ 0 0))\n"
               "(int d (^ (neg 1) 4))\n"
               "(def x (+ (+ (+ (neg 1) (neg 8)) 1) 1))\n");
    /* an exact division of negatives, and the largest int there is */
    expands_to("int n = -12/4\nint m = 1099511627775\nx = n + m\n",
               "(int n (/ (neg 12) 4))\n(int m 1099511627775)\n"
               "(def x (+ (neg 3) 1099511627775))\n");
    /* a param's range may use ints; open ends and a const's one-sided
     * bounds are dumped as written (ast_dump once crashed on `const k >
     * 0` and dropped `const k < 1`) */
    expands_to("int n = 2\nparam t in [0, n]\n",
               "(int n 2)\n(param t (in 0 2))\n");
    expands_to("int n = 2\nparam t in (0, n]\nconst e in [0, 1)\n",
               "(int n 2)\n(param t (in 0 2 lo-open))\n"
               "(const e (in 0 1 hi-open))\n");
    expands_to("int n = 2\nconst k > 0\nconst h < n\nconst a >= 1\n"
               "const b <= 1\n",
               "(int n 2)\n(const k (> 0))\n(const h (< 2))\n"
               "(const a (>= 1))\n(const b (<= 1))\n");
}

static void test_int_too_large(void **state)
{
    (void)state;
    fails_with("int n = 2^40\n", 1,
               "x.pcs:1:9: error: integer too large: the integers of a scheme "
               "stay below 2^40 in magnitude\n"
               "int n = 2^40\n"
               "        ^~~~\n");
    /* 2^40 written out: 13 digits, out of range */
    fails_with("int n = 1099511627776\n", 1,
               "x.pcs:1:9: error: integer too large: the integers of a scheme "
               "stay below 2^40 in magnitude\n"
               "int n = 1099511627776\n"
               "        ^~~~~~~~~~~~~\n");
    /* 14 digits: refused by its length */
    fails_with("int n = 12345678901234\n", 1,
               "x.pcs:1:9: error: integer too large: the integers of a scheme "
               "stay below 2^40 in magnitude\n"
               "int n = 12345678901234\n"
               "        ^~~~~~~~~~~~~~\n");
    /* a product: blamed on the whole product */
    fails_with("int n = 2^20*2^20\n", 1,
               "x.pcs:1:9: error: integer too large: the integers of a scheme "
               "stay below 2^40 in magnitude\n"
               "int n = 2^20*2^20\n"
               "        ^~~~~~~~~\n");
    /* the negative bound too */
    fails_with("int n = -2^39 - 2^39\n", 1,
               "x.pcs:1:9: error: integer too large: the integers of a scheme "
               "stay below 2^40 in magnitude\n"
               "int n = -2^39 - 2^39\n"
               "        ^~~~~~~~~~~~\n");
}

static void test_int_errors(void **state)
{
    (void)state;
    fails_with("int n = 1.5\n", 1,
               "x.pcs:1:9: error: expected a whole number here, found '1.5'\n"
               "int n = 1.5\n"
               "        ^~~\n");
    fails_with("int n = 7/2\n", 1,
               "x.pcs:1:9: error: 7/2 is not a whole number; expected an "
               "exact division here\n"
               "int n = 7/2\n"
               "        ^~~\n");
    fails_with("int n = -7/2\n", 1,
               "x.pcs:1:9: error: -7/2 is not a whole number; expected an "
               "exact division here\n"
               "int n = -7/2\n"
               "        ^~~~\n");
    fails_with("int n = 1/0\n", 1,
               "x.pcs:1:11: error: division by zero\n"
               "int n = 1/0\n"
               "          ^\n");
    fails_with("int n = 2^-1\n", 1,
               "x.pcs:1:11: error: expected a non-negative exponent here, "
               "found -1\n"
               "int n = 2^-1\n"
               "          ^~\n");
    fails_with("int n = k + 1\n", 1,
               "x.pcs:1:9: error: 'k' is not an integer; expected whole "
               "numbers, 'int' constants and comprehension variables here\n"
               "int n = k + 1\n"
               "        ^\n");
    fails_with("int n = sin(1)\n", 1,
               "x.pcs:1:9: error: expected a whole number here (numbers, "
               "'int' constants, comprehension variables, + - * / ^)\n"
               "int n = sin(1)\n"
               "        ^~~~~~\n");
}

static void test_bad_int_reported_once(void **state)
{
    (void)state;
    /* m and the family use the bad n: not reported again */
    fails_with("int n = 1/0\nint m = n + 1\npoint M[1..m]\nx = n\n", 1,
               "x.pcs:1:11: error: division by zero\n"
               "int n = 1/0\n"
               "          ^\n");
}

static void test_int_redefinition(void **state)
{
    (void)state;
    fails_with("int n = 2\nint n = 3\n", 1,
               "x.pcs:2:5: error: redefinition of 'n'\n"
               "int n = 3\n"
               "    ^\n"
               "x.pcs:1:5: note: 'n' was first declared here\n"
               "int n = 2\n"
               "    ^\n");
    fails_with("int n = 2\npoint n\n", 1,
               "x.pcs:2:7: error: redefinition of 'n'\n"
               "point n\n"
               "      ^\n"
               "x.pcs:1:5: note: 'n' was first declared here\n"
               "int n = 2\n"
               "    ^\n");
    fails_with("int n = 2\nn = 3\n", 1,
               "x.pcs:2:1: error: redefinition of 'n'\n"
               "n = 3\n"
               "^\n"
               "x.pcs:1:5: note: 'n' was first declared here\n"
               "int n = 2\n"
               "    ^\n");
    /* an int after a plain name */
    fails_with("point A\nint A = 1\n", 1,
               "x.pcs:2:5: error: redefinition of 'A'\n"
               "int A = 1\n"
               "    ^\n"
               "x.pcs:1:7: note: 'A' was first declared here\n"
               "point A\n"
               "      ^\n");
}

/* ---- -D defines -------------------------------------------------------- */

static const char *const bezier3 =
    "int n = 3\n"
    "point M[1..n+1]\n"
    "param t in [0, 1]\n"
    "unknown C[2..n]\n"
    "X = bezier(t, M[1], C[2..n], M[n+1])\n"
    "solve subst(X, t, (i-1)/n) = M[i] for i in 2..n for C[2..n]\n"
    "output X, C[2..n]\n";

static void test_family_scheme_of_the_docs(void **state)
{
    (void)state;
    expands_to(bezier3, "(int n 3)\n"
                        "(point M_1 M_2 M_3 M_4)\n"
                        "(param t (in 0 1))\n"
                        "(unknown C_2 C_3)\n"
                        "(def X (bezier t M_1 C_2 C_3 M_4))\n"
                        "(solve C_2 C_3"
                        " (= (subst X t (/ (- 2 1) 3)) M_2)"
                        " (= (subst X t (/ (- 3 1) 3)) M_3))\n"
                        "(output X C_2 C_3)\n");
}

static void test_defines_override(void **state)
{
    (void)state;
    const char *const defs[] = {"m=2", "n=4"};
    char used[2] = {1, 0};
    int n;
    char *s = expand_with(bezier3, defs, 2, used, &n);
    assert_int_equal(n, 0);
    /* m is declared by no int: not used; n is */
    assert_int_equal(used[0], 0);
    assert_int_equal(used[1], 1);
    assert_string_equal(s, "(int n 3)\n"
                           "(point M_1 M_2 M_3 M_4 M_5)\n"
                           "(param t (in 0 1))\n"
                           "(unknown C_2 C_3 C_4)\n"
                           "(def X (bezier t M_1 C_2 C_3 C_4 M_5))\n"
                           "(solve C_2 C_3 C_4"
                           " (= (subst X t (/ (- 2 1) 4)) M_2)"
                           " (= (subst X t (/ (- 3 1) 4)) M_3)"
                           " (= (subst X t (/ (- 4 1) 4)) M_4))\n"
                           "(output X C_2 C_3 C_4)\n");
    free(s);

    /* a malformed define overrides nothing */
    const char *const bad[] = {"n=x"};
    used[0] = 1;
    s = expand_with("int n = 3\nx = n\n", bad, 1, used, &n);
    assert_int_equal(n, 0);
    assert_int_equal(used[0], 0);
    assert_string_equal(s, "(int n 3)\n(def x 3)\n");
    free(s);

    /* a negative value, and a define that replaces an int with an error
     * (the error is still reported, the uses take the define's value) */
    const char *const neg[] = {"n=-2"};
    s = expand_with("int n = 3\nx = n\n", neg, 1, used, &n);
    assert_int_equal(n, 0);
    assert_int_equal(used[0], 1);
    assert_string_equal(s, "(int n 3)\n(def x (neg 2))\n");
    free(s);
    const char *const two[] = {"n=2"};
    s = expand_with("int n = 1/0\npoint M[1..n]\n", two, 1, used, &n);
    assert_int_equal(n, 1);
    assert_int_equal(used[0], 1);
    assert_string_equal(s, "x.pcs:1:11: error: division by zero\n"
                           "int n = 1/0\n"
                           "          ^\n");
    free(s);
}

static void test_check_define(void **state)
{
    (void)state;
    assert_int_equal(expand_check_define("n=3"), 0);
    assert_int_equal(expand_check_define("n=-3"), 0);
    assert_int_equal(expand_check_define("n=+3"), 0);
    assert_int_equal(expand_check_define("_a1=0"), 0);
    assert_int_equal(expand_check_define("n=1099511627775"), 0);
    assert_int_equal(expand_check_define("n=-1099511627775"), 0);
    assert_int_equal(expand_check_define("n=1099511627776"), -1);
    assert_int_equal(expand_check_define("n=-1099511627776"), -1);
    assert_int_equal(expand_check_define("n=12345678901234"), -1);
    assert_int_equal(expand_check_define("=3"), -1);
    assert_int_equal(expand_check_define("n"), -1);
    assert_int_equal(expand_check_define("n="), -1);
    assert_int_equal(expand_check_define("n=-"), -1);
    assert_int_equal(expand_check_define("n=3.5"), -1);
    assert_int_equal(expand_check_define("n=3 "), -1);
    assert_int_equal(expand_check_define("n=0x10"), -1);
    assert_int_equal(expand_check_define("1n=3"), -1);
    assert_int_equal(expand_check_define("n-x=3"), -1);
    assert_int_equal(expand_check_define("n x=3"), -1);
    /* a name of 127 characters is fine, 128 too long */
    char name[200];
    memset(name, 'a', 127);
    strcpy(name + 127, "=1");
    assert_int_equal(expand_check_define(name), 0);
    memset(name, 'a', 128);
    strcpy(name + 128, "=1");
    assert_int_equal(expand_check_define(name), -1);
}

static void test_defines_option_of_derive(void **state)
{
    (void)state;
    const char *text = "int n = 2\npoint A, B\nM = along(A, B, 1/n)\n";
    const char *const defs[] = {"n=4", "m=3"};
    int bad = -1, nerrors = -1;
    DeriveOptions opt = {.defines = defs, .ndefines = 2, .bad_define = &bad};
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    Derived *d =
        derive_source_ex("x.pcs", text, strlen(text), mem, &nerrors, &opt);
    fclose(mem);
    assert_null(d);
    assert_int_equal(bad, 1);
    assert_int_equal(nerrors, 1);
    assert_string_equal(out, "pointcalc: -D m=3: x.pcs declares no 'int m'\n");
    free(out);

    /* the define used: no error */
    opt.ndefines = 1;
    out = NULL;
    mem = open_memstream(&out, &len);
    d = derive_source_ex("x.pcs", text, strlen(text), mem, &nerrors, &opt);
    fclose(mem);
    assert_non_null(d);
    assert_int_equal(bad, 0);
    assert_int_equal(nerrors, 0);
    assert_string_equal(out, "");
    free(out);
    derived_free(d);
}

/* ---- families ---------------------------------------------------------- */

static void test_families_members_and_ranges(void **state)
{
    (void)state;
    expands_to("point M[1..3]\nparam t\nX = bezier(t, M[1..3])\n"
               "Y = bezier(t, M[1], M[3..2], M[2..3])\nZ = M[1+1]\n",
               "(point M_1 M_2 M_3)\n(param t)\n"
               "(def X (bezier t M_1 M_2 M_3))\n"
               "(def Y (bezier t M_1 M_2 M_3))\n"
               "(def Z M_2)\n");
    /* an empty family declares none; indices may start at 0; plain names
     * and families mix in one list */
    expands_to("point E[2..1], N[0..1], A\n", "(point N_0 N_1 A)\n");
    /* names that are no member's name: a leading zero, out of the range */
    expands_to("point M_03, M_6, M_\npoint M[1..5]\n",
               "(point M_03 M_6 M_)\n(point M_1 M_2 M_3 M_4 M_5)\n");
    /* members inside arithmetic and nested calls */
    expands_to("int n = 2\npoint P[0..n]\nQ = (P[0] + P[n])/2 - "
               "along(P[1], P[n], 1/n)\n",
               "(int n 2)\n(point P_0 P_1 P_2)\n"
               "(def Q (- (/ (+ P_0 P_2) 2) (along P_1 P_2 (/ 1 2))))\n");
}

static void test_name_lists(void **state)
{
    (void)state;
    /* a family alone means all its members; members and ranges */
    expands_to("point A\nunknown C[1..3]\n"
               "solve C[1] = A, C[2] = A, C[3] = A for C\n"
               "output C[2], C[1..1], C, C[3..2]\n",
               "(point A)\n(unknown C_1 C_2 C_3)\n"
               "(solve C_1 C_2 C_3 (= C_1 A) (= C_2 A) (= C_3 A))\n"
               "(output C_2 C_1 C_1 C_2 C_3)\n");
}

static void test_comprehensions(void **state)
{
    (void)state;
    /* one equation per value; plain equations around it stay */
    expands_to("point A, B\nunknown C, D\n"
               "solve C = A, D = B*i for i in 1..2, D = A for C, D\n",
               "(point A B)\n(unknown C D)\n"
               "(solve C D (= C A) (= D (* B 1)) (= D (* B 2)) (= D A))\n");
    /* an empty range: no equation; a negative value of the variable */
    expands_to("point A\nunknown C\nsolve C = A for i in 3..2 for C\n",
               "(point A)\n(unknown C)\n(solve C)\n");
    expands_to("point A\nunknown C\nsolve C = A*i for i in -1..-1 for C\n",
               "(point A)\n(unknown C)\n(solve C (= C (* A (neg 1))))\n");
    /* the variable may be used again by a later comprehension */
    expands_to("point A\nunknown C\n"
               "solve C = A*i for i in 1..1, C = A*i for i in 2..2 for C\n",
               "(point A)\n(unknown C)\n"
               "(solve C (= C (* A 1)) (= C (* A 2)))\n");
}

static void test_index_out_of_range(void **state)
{
    (void)state;
    fails_with("point M[1..4]\nY = M[5]\n", 1,
               "x.pcs:2:7: error: index 5 is out of range: M has the members "
               "M[1..4]\n"
               "Y = M[5]\n"
               "      ^\n");
    /* inside a comprehension the variable's value is named; stops at the
     * first bad value */
    fails_with("point M[1..4]\nunknown C\n"
               "solve C = M[i+2] for i in 2..4 for C\n",
               1,
               "x.pcs:3:13: error: index 5 (at i = 3) is out of range: M has "
               "the members M[1..4]\n"
               "solve C = M[i+2] for i in 2..4 for C\n"
               "            ^~~\n");
    fails_with("point M[2..1]\nY = M[1]\n", 1,
               "x.pcs:2:7: error: index 1 is out of range: the family M is "
               "empty\n"
               "Y = M[1]\n"
               "      ^\n");
    /* ranges among arguments: the end that is out */
    fails_with("point M[1..3]\nparam t\nY = bezier(t, M[0..2])\n", 1,
               "x.pcs:3:17: error: index 0 is out of range: M has the members "
               "M[1..3]\n"
               "Y = bezier(t, M[0..2])\n"
               "                ^\n");
    fails_with("point M[1..3]\nparam t\nY = bezier(t, M[2..4])\n", 1,
               "x.pcs:3:20: error: index 4 is out of range: M has the members "
               "M[1..3]\n"
               "Y = bezier(t, M[2..4])\n"
               "                   ^\n");
    /* and in name lists */
    fails_with("unknown C[2..3]\noutput C[1..3]\n", 1,
               "x.pcs:2:10: error: index 1 is out of range: C has the members "
               "C[2..3]\n"
               "output C[1..3]\n"
               "         ^\n");
    fails_with("unknown C[2..3]\noutput C[4]\n", 1,
               "x.pcs:2:10: error: index 4 is out of range: C has the members "
               "C[2..3]\n"
               "output C[4]\n"
               "         ^\n");
}

static void test_family_misuse(void **state)
{
    (void)state;
    fails_with("point M[1..2]\nY = M\n", 1,
               "x.pcs:2:5: error: 'M' is a family of points; expected a "
               "member M[i] or a range M[a..b] among a function's arguments\n"
               "Y = M\n"
               "    ^\n");
    fails_with("unknown C[1..2]\nY = C\n", 1,
               "x.pcs:2:5: error: 'C' is a family of unknowns; expected a "
               "member C[i] or a range C[a..b] among a function's arguments\n"
               "Y = C\n"
               "    ^\n");
    fails_with("point M[1..2]\nY = M[1..2]\n", 1,
               "x.pcs:2:5: error: a range M[a..b] stands for several points; "
               "expected it among the arguments of a function such as "
               "bezier()\n"
               "Y = M[1..2]\n"
               "    ^~~~~~~\n");
    fails_with("point A\nY = A[1]\n", 1,
               "x.pcs:2:5: error: 'A' is not a family; expected NAME[i] of a "
               "family declared as NAME[lo..hi]\n"
               "Y = A[1]\n"
               "    ^\n");
    fails_with("param t[1..2]\n", 1,
               "x.pcs:1:7: error: expected a plain name; families of "
               "parameters and constants are not supported\n"
               "param t[1..2]\n"
               "      ^~~~~~~\n");
    fails_with("point M[1]\n", 1,
               "x.pcs:1:7: error: expected a name or a family NAME[lo..hi] in "
               "a declaration\n"
               "point M[1]\n"
               "      ^~~~\n");
    fails_with("point M[-1..2]\n", 1,
               "x.pcs:1:9: error: a family's indices start at 0 or above, "
               "found -1\n"
               "point M[-1..2]\n"
               "        ^~\n");
}

static void test_member_name_clashes(void **state)
{
    (void)state;
    fails_with("point M[1..5]\npoint M_3\n", 1,
               "x.pcs:2:7: error: 'M_3' is the name of the family member "
               "M[3]; choose another name\n"
               "point M_3\n"
               "      ^~~\n"
               "x.pcs:1:7: note: the family M is declared here\n"
               "point M[1..5]\n"
               "      ^~~~~~~\n");
    fails_with("point M_3\nunknown M[1..5]\n", 1,
               "x.pcs:2:9: error: the family member M[3] would be named "
               "'M_3', which is declared already\n"
               "unknown M[1..5]\n"
               "        ^~~~~~~\n"
               "x.pcs:1:7: note: 'M_3' was declared here\n"
               "point M_3\n"
               "      ^~~\n");
    /* a definition named like a member */
    fails_with("point M[1..2]\nM_2 = M[1]\n", 1,
               "x.pcs:2:1: error: 'M_2' is the name of the family member "
               "M[2]; choose another name\n"
               "M_2 = M[1]\n"
               "^~~\n"
               "x.pcs:1:7: note: the family M is declared here\n"
               "point M[1..2]\n"
               "      ^~~~~~~\n");
    /* a definition named like a family */
    fails_with("point M[1..2]\nM = 1\n", 1,
               "x.pcs:2:1: error: redefinition of 'M'\n"
               "M = 1\n"
               "^\n"
               "x.pcs:1:7: note: 'M' was first declared here\n"
               "point M[1..2]\n"
               "      ^~~~~~~\n");
    /* a comprehension variable that would hide a point */
    fails_with("point A, i\nunknown C\nsolve C = A for i in 1..1 for C\n", 1,
               "x.pcs:3:17: error: redefinition of 'i'\n"
               "solve C = A for i in 1..1 for C\n"
               "                ^\n"
               "x.pcs:1:10: note: 'i' was first declared here\n"
               "point A, i\n"
               "         ^\n");
}

static void test_size_bounds(void **state)
{
    (void)state;
    /* exactly EXPAND_MAX_MEMBERS: fine */
    int n;
    char *s = expand_text("point M[1..100000]\n", &n);
    assert_int_equal(n, 0);
    assert_true(strncmp(s, "(point M_1 M_2 M_3 ", 19) == 0);
    const char *end = " M_99999 M_100000)\n";
    assert_string_equal(s + strlen(s) - strlen(end), end);
    free(s);

    fails_with("point M[1..100001]\n", 1,
               "x.pcs:1:7: error: the scheme unrolls to more than 100000 "
               "family members and equations; expected smaller families or "
               "comprehensions\n"
               "point M[1..100001]\n"
               "      ^~~~~~~~~~~~\n");
    /* the members of all families count together; expand stops there
     * (the bad index M[0] after it is not reported) */
    fails_with("point M[1..60000]\nunknown C[1..40001]\nY = M[0]\n", 1,
               "x.pcs:2:9: error: the scheme unrolls to more than 100000 "
               "family members and equations; expected smaller families or "
               "comprehensions\n"
               "unknown C[1..40001]\n"
               "        ^~~~~~~~~~~\n");
    /* so do unrolled equations */
    fails_with("point A\nunknown C\nsolve C = A for i in 1..100001 for C\n", 1,
               "x.pcs:3:7: error: the scheme unrolls to more than 100000 "
               "family members and equations; expected smaller families or "
               "comprehensions\n"
               "solve C = A for i in 1..100001 for C\n"
               "      ^~~~~~~~~~~~~~~~~~~~~~~~\n");
    /* a family of 2^40 members is refused by the bound, not allocated */
    fails_with("point M[0..2^39]\n", 1,
               "x.pcs:1:7: error: the scheme unrolls to more than 100000 "
               "family members and equations; expected smaller families or "
               "comprehensions\n"
               "point M[0..2^39]\n"
               "      ^~~~~~~~~~\n");
}

/* ---- user functions, sum and prod, piecewise, join ---------------------- */

static void test_function_calls(void **state)
{
    (void)state;
    /* a call is a copy of the body with each parameter replaced by its
     * argument; the def itself is kept as written */
    expands_to(
        "point A, B\nparam t\ndef m(X, Y, s) = X + (Y - X)*s\n"
        "M = m(B, A, t/2)\n",
        "(point A B)\n(param t)\n(function m X Y s (+ X (* (- Y X) s)))\n"
        "(def M (+ B (* (- A B) (/ t 2))))\n");
    /* parameters named like points are the parameters: f(B, A) swaps them
     * (replaced once, not again inside the argument) */
    expands_to("point A, B\ndef f(A, B) = along(A, B, 1/3)\nM = f(B, A)\n",
               "(point A B)\n(function f A B (along A B (/ 1 3)))\n"
               "(def M (along B A (/ 1 3)))\n");
    /* a function calls an earlier one; the inner call sees only its own
     * parameters: g's t does not reach f's body */
    expands_to("point A, B\nparam t\ndef f(X) = along(X, B, t)\n"
               "def g(t) = f(A)*t\nM = g(1/2)\n",
               "(point A B)\n(param t)\n(function f X (along X B t))\n"
               "(function g t (* (f A) t))\n"
               "(def M (* (along A B t) (/ 1 2)))\n");
    /* an int argument used as an index, and ints in the body */
    expands_to("int n = 2\npoint M[0..n]\ndef v(k) = M[k + 1] - M[k]\n"
               "V = v(n - 1)\n",
               "(int n 2)\n(point M_0 M_1 M_2)\n"
               "(function v k (- (M (+ k 1)) (M k)))\n(def V (- M_2 M_1))\n");
}

static void test_sums_and_products(void **state)
{
    (void)state;
    /* a balanced tree of the terms (depth log n, not n) */
    expands_to("param t\nx = sum(t^i for i in 1..3)\n",
               "(param t)\n(def x (+ (^ t 1) (+ (^ t 2) (^ t 3))))\n");
    expands_to(
        "param t\nx = prod(t - i for i in 1..4)\n",
        "(param t)\n(def x (* (* (- t 1) (- t 2)) (* (- t 3) (- t 4))))\n");
    /* the empty sum is 0, the empty product 1 */
    expands_to("param t\nx = sum(t for i in 2..1) + prod(t for i in 1..0)\n",
               "(param t)\n(def x (+ 0 1))\n");
    /* over the members of a family, bounds from ints; nested, the inner
     * bound depending on the outer index */
    expands_to("int n = 2\npoint M[1..n]\nG = sum(M[i] for i in 1..n)/n\n",
               "(int n 2)\n(point M_1 M_2)\n(def G (/ (+ M_1 M_2) 2))\n");
    expands_to("x = sum(sum(j for j in 1..i) for i in 1..2)\n",
               "(def x (+ 1 (+ 1 2)))\n");
    /* in an int: the whole number; 1+2+3+4 = 10, 3! = 6 */
    expands_to("int n = sum(i for i in 1..4) + prod(i for i in 1..3)\nx = n\n",
               "(int n (+ (sum i (for i 1 4)) (prod i (for i 1 3))))\n"
               "(def x 16)\n");
}

static void test_piecewise_and_join(void **state)
{
    (void)state;
    /* (p1 + p2)/2 + (p2 - p1)/2 sign(t - t1) */
    expands_to("param t\nx = piecewise(t, 0, 1, t - 1)\n",
               "(param t)\n(def x (+ (/ (+ 0 (- t 1)) 2) "
               "(* (/ (- (- t 1) 0) 2) (sign (- t 1)))))\n");
    /* one segment between the knots 0 and 2: g(a) + (g(a + (b - a) P) -
     * g(a)) with the ramp P(t, 0, 2 - 0) */
    expands_to("param t\ndef g(u) = u^2\nx = join(t, 0, g[1..3], 2)\n",
               "(param t)\n(function g u (^ u 2))\n"
               "(def x (+ (^ 1 2) (- (^ (+ 1 (* (- 3 1) (ramp t 0 (- 2 0)))) "
               "2) (^ 1 2))))\n");
    /* Theorem 3's infinite branches: g0(b0 + rayl(t, t0)) and g(a +
     * rayr(t, tn)) - g(a); smoothjoin's step and its rays times (t0 -
     * t)^m, (t - tn)^m */
    expands_to("param t\ndef g(u) = u\n"
               "x = join(t, g[-inf..0], 1, g[0..inf])\n",
               "(param t)\n(function g u u)\n"
               "(def x (+ (+ 0 (rayl t 1)) (- (+ 0 (rayr t 1)) 0)))\n");
    expands_to("param t\ndef g(u) = u\n"
               "x = smoothjoin(2, t, g[-inf..0], 0, g[0..1], 1, g[1..inf])\n",
               "(param t)\n(function g u u)\n"
               "(def x (+ (+ 0 (* (^ (- 0 t) 2) (rayl t 0))) "
               "(+ (- (+ 0 (* (- 1 0) (step t 0 (- 1 0) 2))) 0) "
               "(- (+ 1 (* (^ (- t 1) 2) (rayr t 1))) 1))))\n");
}

static void test_function_errors(void **state)
{
    (void)state;
    fails_with("point A\ndef f(x) = x + Z\n", 1,
               "x.pcs:2:16: error: 'Z' is not a parameter of f() and is not "
               "declared before it; expected one of its parameters or an "
               "earlier name\n"
               "def f(x) = x + Z\n"
               "               ^\n");
    fails_with("def f(x) = f(x)\n", 1,
               "x.pcs:1:12: error: f() calls itself; a function cannot be "
               "recursive\n"
               "def f(x) = f(x)\n"
               "           ^\n");
    fails_with("def f(x, x) = x\n", 1,
               "x.pcs:1:10: error: the parameter 'x' of f() is repeated; "
               "expected distinct names\n"
               "def f(x, x) = x\n"
               "         ^\n");
    fails_with("def sin(x) = x\n", 1,
               "x.pcs:1:5: error: 'sin' is a built-in function; choose "
               "another name\n"
               "def sin(x) = x\n"
               "    ^~~\n");
    fails_with("def f(x) = x\ndef f(y) = y\n", 1,
               "x.pcs:2:5: error: redefinition of the function 'f'\n"
               "def f(y) = y\n"
               "    ^\n"
               "x.pcs:1:5: note: 'f' was first defined here\n"
               "def f(x) = x\n"
               "    ^\n");
    fails_with("def f(x) = g(x)\n", 1,
               "x.pcs:1:12: error: unknown function 'g'; a function may call "
               "the built-in functions and the functions defined before it\n"
               "def f(x) = g(x)\n"
               "           ^\n");
    /* arity at the call, with a note at the definition */
    fails_with("def f(x, y) = x\na = f(1)\n", 1,
               "x.pcs:2:5: error: f() takes 2 arguments, found 1\n"
               "a = f(1)\n"
               "    ^~~~\n"
               "x.pcs:1:5: note: f() is defined here\n"
               "def f(x, y) = x\n"
               "    ^\n");
    /* an index out of range inside an expansion: a note at the call */
    fails_with("point M[1..2]\ndef v(k) = M[k]\nV = v(3)\n", 1,
               "x.pcs:2:14: error: index 3 is out of range: M has the members "
               "M[1..2]\n"
               "def v(k) = M[k]\n"
               "             ^\n"
               "x.pcs:3:5: note: in the call of v() here\n"
               "V = v(3)\n"
               "    ^~~~\n");
}

static void test_sum_and_join_errors(void **state)
{
    (void)state;
    fails_with("param t\nx = foo(t for i in 1..2)\n", 1,
               "x.pcs:2:5: error: 'foo' takes no comprehension; expected "
               "sum(EXPR for i in a..b) or prod(EXPR for i in a..b)\n"
               "x = foo(t for i in 1..2)\n"
               "    ^~~\n");
    fails_with("param t\nx = sum(i for t in 1..2)\n", 1,
               "x.pcs:2:15: error: redefinition of 't'\n"
               "x = sum(i for t in 1..2)\n"
               "              ^\n"
               "x.pcs:1:7: note: 't' was first declared here\n"
               "param t\n"
               "      ^\n");
    fails_with("x = sum(sum(i for i in 1..2) for i in 1..2)\n", 1,
               "x.pcs:1:19: error: 'i' is already bound here; expected "
               "another name for the index\n"
               "x = sum(sum(i for i in 1..2) for i in 1..2)\n"
               "                  ^\n");
    fails_with("x = sum(1 for i in 1..t)\n", 1,
               "x.pcs:1:23: error: 't' is not an integer; expected whole "
               "numbers, 'int' constants and comprehension variables here\n"
               "x = sum(1 for i in 1..t)\n"
               "                      ^\n");
    fails_with("param t\nx = sum(t)\n", 1,
               "x.pcs:2:5: error: sum() takes one comprehension: sum(EXPR for "
               "i in a..b)\n"
               "x = sum(t)\n"
               "    ^~~~~~\n");
    fails_with("param t\nx = sum(t for i in 1..2^30)\n", 1,
               "x.pcs:2:5: error: the scheme unrolls to more than 4194304 "
               "expression nodes; expected smaller families or "
               "comprehensions\n"
               "x = sum(t for i in 1..2^30)\n"
               "    ^~~~~~~~~~~~~~~~~~~~~~~\n");
    fails_with("param t\nx = piecewise(t, 1, 2, 3, 1, 4)\n", 1,
               "x.pcs:2:27: error: the knots must increase: this one is 1, "
               "after 2\n"
               "x = piecewise(t, 1, 2, 3, 1, 4)\n"
               "                          ^\n");
    fails_with("param t\ndef g(u) = u\nx = join(t, 0, g[0..1], 0.5, "
               "g[1..2], 1/2)\n",
               1,
               "x.pcs:3:39: error: the knots must increase: this one is 1/2, "
               "after 1/2\n"
               "x = join(t, 0, g[0..1], 0.5, g[1..2], 1/2)\n"
               "                                      ^~~\n");
    fails_with("param t\ndef g(u) = u\nx = join(t, 0, g[0..1], g[1..2], 1)\n",
               1,
               "x.pcs:3:25: error: expected a knot here: join() takes knots "
               "and segments in turn, t0, g1[a..b], t1, ..., the first and "
               "the last segment may be infinite (g0[-inf..b], g[a..inf])\n"
               "x = join(t, 0, g[0..1], g[1..2], 1)\n"
               "                        ^~~~~~~\n");
    fails_with("param t\ndef g(u, v) = u\nx = join(t, 0, g[0..1], 1)\n", 1,
               "x.pcs:3:16: error: the segment function g() takes 2 "
               "parameters; expected a function of one parameter\n"
               "x = join(t, 0, g[0..1], 1)\n"
               "               ^\n"
               "x.pcs:2:5: note: g() is defined here\n"
               "def g(u, v) = u\n"
               "    ^\n");
    fails_with("param t\ndef g(u) = u\nx = join(t, 0, g[2..1/2], 1)\n", 1,
               "x.pcs:3:16: error: the segment g[2..1/2] is empty; expected "
               "an interval lo..hi with lo < hi (the segment is traced from "
               "lo to hi)\n"
               "x = join(t, 0, g[2..1/2], 1)\n"
               "               ^~~~~~~~~\n");
    fails_with("param t\ndef g(u) = u\nx = join(t, 0)\n", 1,
               "x.pcs:3:5: error: join() needs at least one segment between "
               "two knots, or two infinite branches at one knot\n"
               "x = join(t, 0)\n"
               "    ^~~~~~~~~~\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_int_is_substituted),
        cmocka_unit_test(test_int_expressions),
        cmocka_unit_test(test_int_too_large),
        cmocka_unit_test(test_int_errors),
        cmocka_unit_test(test_bad_int_reported_once),
        cmocka_unit_test(test_int_redefinition),
        cmocka_unit_test(test_family_scheme_of_the_docs),
        cmocka_unit_test(test_defines_override),
        cmocka_unit_test(test_check_define),
        cmocka_unit_test(test_defines_option_of_derive),
        cmocka_unit_test(test_families_members_and_ranges),
        cmocka_unit_test(test_name_lists),
        cmocka_unit_test(test_comprehensions),
        cmocka_unit_test(test_index_out_of_range),
        cmocka_unit_test(test_family_misuse),
        cmocka_unit_test(test_member_name_clashes),
        cmocka_unit_test(test_size_bounds),
        cmocka_unit_test(test_function_calls),
        cmocka_unit_test(test_sums_and_products),
        cmocka_unit_test(test_piecewise_and_join),
        cmocka_unit_test(test_function_errors),
        cmocka_unit_test(test_sum_and_join_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
