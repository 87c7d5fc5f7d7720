/*
 * test_front.c - scanner, parser, sema and diagnostics: exact texts.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "base/arena.h"
#include "base/diag.h"
#include "compiler/derive.h"
#include "compiler/sema.h"
#include "driver/cli/budget.h"
#include "grammar/parse.h"
#include "libpointcalc.h"

/* parses text and returns the AST dump (or the diagnostics); caller frees */
static char *dump(const char *text, int *nerrors)
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
    if (d.nerrors == 0)
        ast_dump(mem, s);
    fclose(mem);
    *nerrors = d.nerrors;
    source_clear(&src);
    arena_reset(&a);
    return out;
}

/* derives text and returns stderr's would-be content */
static char *errors_of(const char *text)
{
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    Derived *d = derive_source("x.pcs", text, strlen(text), mem, NULL);
    fclose(mem);
    derived_free(d);
    return out;
}

static void test_parse_precedence_and_associativity(void **state)
{
    (void)state;
    int n;
    char *s = dump("M = -t^2*A + B/2 - C\nx = 2^3^2\n", &n);
    assert_int_equal(n, 0);
    assert_string_equal(s, "(def M (- (+ (* (neg (^ t 2)) A) (/ B 2)) C))\n"
                           "(def x (^ 2 (^ 3 2)))\n");
    free(s);
}

static void test_parse_statements(void **state)
{
    (void)state;
    int n;
    char *s = dump("# c\nscheme s1\npoint A, B # trailing\n"
                   "param t in [0, 1]\nconst k, pD\n\n"
                   "M = meet(line(A, B), plane(A, B, A))\noutput M",
                   &n);
    assert_int_equal(n, 0);
    assert_string_equal(s, "(scheme s1)\n(point A B)\n(param t (in 0 1))\n"
                           "(const k pD)\n"
                           "(def M (meet (line A B) (plane A B A)))\n"
                           "(output M)\n");
    free(s);
}

/* check, int, def and at are words, not keywords: the statement `WORD
 * EXPR [= EXPR] [at NAME = EXPR, ...]` tells them apart, so a point may
 * still be called check or at; `E at t = v` among arguments is subst */
static void test_parse_check_statements(void **state)
{
    (void)state;
    int n;
    char *s = dump("point check, at\nparam t\nint n = 2\n"
                   "def f(x, y) = x\ncheck = along(check, at, t)\n"
                   "check check = at at t = 1, n = 2\n"
                   "check tangent(check at t = 0, line(check, at))\n"
                   "check C2(f(at, t) at t = 1)\n",
                   &n);
    assert_int_equal(n, 0);
    assert_string_equal(s, "(point check at)\n(param t)\n(int n 2)\n"
                           "(function f x y x)\n"
                           "(def check (along check at t))\n"
                           "(check check (is at) (= t 1) (= n 2))\n"
                           "(check (tangent (subst check t 0) (line check "
                           "at)))\n"
                           "(check (C2 (subst (f at t) t 1)))\n");
    free(s);
}

static void test_diag_format_has_line_and_caret(void **state)
{
    (void)state;
    char *s = errors_of("point A, B\nparam t\nM = along(A, Q, t)\n");
    assert_string_equal(
        s, "x.pcs:3:14: error: undefined name 'Q'; expected a declared "
           "point, parameter, constant or an earlier definition\n"
           "M = along(A, Q, t)\n"
           "             ^\n");
    free(s);
}

static void test_diag_caret_spans_expression(void **state)
{
    (void)state;
    char *s = errors_of("point A, B\nparam t\nM = A*t + B\n");
    assert_string_equal(s, "x.pcs:3:5: error: weights of M sum to t+1, not "
                           "0 (a vector) or 1 (a point)\n"
                           "M = A*t + B\n"
                           "    ^~~~~~~\n");
    free(s);
}

static void test_diag_redefinition_has_note(void **state)
{
    (void)state;
    char *s = errors_of("point A, B\nparam A\nM = B\n");
    assert_string_equal(s, "x.pcs:2:7: error: redefinition of 'A'\n"
                           "param A\n"
                           "      ^\n"
                           "x.pcs:1:7: note: 'A' was first declared here as "
                           "a base point\n"
                           "point A, B\n"
                           "      ^\n");
    free(s);
}

static void test_syntax_errors_all_reported(void **state)
{
    (void)state;
    int n;
    char *s = dump("M = (\nN = )\nP = 1\n", &n);
    assert_int_equal(n, 2);
    assert_non_null(strstr(s, "x.pcs:1:6: error: syntax error, unexpected "
                              "end of line"));
    assert_non_null(strstr(s, "x.pcs:2:5: error: syntax error, unexpected "
                              "')'"));
    free(s);
}

static void test_last_line_without_newline(void **state)
{
    (void)state;
    int n;
    char *s = dump("point A\nM = A", &n);
    assert_int_equal(n, 0);
    assert_string_equal(s, "(point A)\n(def M A)\n");
    free(s);
}

static void test_scheme_name_defaults_to_file(void **state)
{
    (void)state;
    Derived *d =
        derive_source("dir/arc.v2.pcs", "point A\nM = A\n", 14, NULL, NULL);
    assert_non_null(d);
    assert_string_equal(d->scheme, "arc.v2");
    assert_int_equal(d->noutputs, 1);
    assert_string_equal(d->outputs[0].name, "M");
    derived_free(d);
}

static void test_decimals_are_exact(void **state)
{
    (void)state;
    const char *text = "point A, B\nM = along(A, B, 0.1 + 0.2 - 3e-1 + "
                       "1.5e1/150)\n";
    Derived *d = derive_source("x.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(d);
    /* 0.1 + 0.2 - 0.3 is exactly 0; 15/150 = 1/10 */
    RatFun w;
    ratfun_init(w, &d->ring);
    pteq_get_weight(w, d->outputs[0].eq, 1, &d->ring);
    RatFun want;
    ratfun_init(want, &d->ring);
    assert_int_equal(ratfun_set_str(want, "1/10", &d->ring), 0);
    assert_true(ratfun_equal(w, want, &d->ring));
    ratfun_clear(want, &d->ring);
    ratfun_clear(w, &d->ring);
    derived_free(d);
}

/* long operator chains and deep parentheses: a diagnostic, never a stack
 * overflow (every pass recurses over the tree) */
static void test_deep_expressions_are_refused(void **state)
{
    (void)state;
    enum { N = 20000 };
    char *text = malloc(4 * N + 64);
    strcpy(text, "param t\ns = t");
    size_t k = strlen(text);
    for (int i = 1; i < N; i++) {
        memcpy(text + k, "+t", 2);
        k += 2;
    }
    strcpy(text + k, "\n");
    char *e = errors_of(text);
    assert_non_null(strstr(e, "x.pcs:2:5: error: expression nested too deeply "
                              "(20000 levels; at most 2000): split it into "
                              "several definitions\n"));
    free(e);
    /* at the limit it derives: 1999 terms, depth 1999 */
    strcpy(text + 8 + 5 + 2 * 1998, "\n");
    e = errors_of(text);
    assert_string_equal(e, "");
    free(e);
    /* 20000 parentheses: the parser's own limit */
    k = 0;
    k += (size_t)sprintf(text, "param t\ns = ");
    for (int i = 0; i < N; i++)
        text[k++] = '(';
    text[k++] = 't';
    for (int i = 0; i < N; i++)
        text[k++] = ')';
    strcpy(text + k, "\n");
    e = errors_of(text);
    assert_non_null(strstr(e, "error: expression nested too deeply for the "
                              "parser (10000 levels of parentheses or "
                              "operators at most)"));
    free(e);
    free(text);
}

/* a NUL inside a line: reported, and the line printed whole (the NUL as a
 * space) so that the caret stands under it */
static void test_diag_nul_in_line(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nM = A\0 + B\n";
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    Derived *d = derive_source("x.pcs", text, sizeof text - 1, mem, NULL);
    fclose(mem);
    assert_null(d);
    assert_string_equal(out, "x.pcs:2:6: error: unexpected byte 0x00; "
                             "expected a name, a number, an operator or '#'\n"
                             "M = A\\x00 + B\n"
                             "     ^~~~\n");
    free(out);
}

/* the diagnostics of text as derive_source reports it */
static char *diagnose(const char *name, const char *text, size_t len)
{
    char *out = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&out, &n);
    Derived *d = derive_source(name, text, len, mem, NULL);
    fclose(mem);
    assert_null(d);
    return out;
}

/* control bytes and invalid UTF-8 never reach the terminal raw (a scheme
 * with ESC sequences used to retitle and clear the terminal when its error
 * was printed); columns and carets count characters, the escapes four
 * cells wide */
static char *file_diagnostic(const char *path);

static void test_diag_escapes_and_utf8_columns(void **state)
{
    (void)state;
    static const char esc[] = "point A\nM = A + \x1b[2J\n";
    char *out = diagnose("e\x1b.pcs", esc, sizeof esc - 1);
    assert_string_equal(out, "e\\x1b.pcs:2:9: error: unexpected byte 0x1b; "
                             "expected a name, a number, an operator or '#'\n"
                             "M = A + \\x1b[2J\n"
                             "        ^~~~\n");
    free(out);
    /* two 2-byte letters (two cells), then an invalid byte (four); one
     * lexical error a line: the invalid byte after the letters is not
     * reported again (no cascade), the one on the next line is */
    static const char u8[] =
        "point A\nM = \xc3\xa9\xc3\xa9 + \xff\nN = A + \xff\n";
    out = diagnose("u.pcs", u8, sizeof u8 - 1);
    assert_string_equal(out,
                        "u.pcs:2:5: error: unexpected non-ASCII text; names "
                        "are ASCII letters, digits and '_'\n"
                        "M = \xc3\xa9\xc3\xa9 + \\xff\n"
                        "    ^~\n"
                        "u.pcs:3:9: error: unexpected non-ASCII text; names "
                        "are ASCII letters, digits and '_'\n"
                        "N = A + \\xff\n"
                        "        ^~~~\n");
    free(out);
    /* valid UTF-8 that drives a terminal or reorders text (issue 23 item
     * 9): the C1 controls U+009B (CSI) and U+009D (OSC), the bidi override
     * U+202E and isolate U+2066, in the file name and in the line, six
     * cells each; the caret after them lines up */
    static const char bidi[] = "point A\nM = \xc2\x9b\xe2\x80\xae + A\n"
                               "N = \xc2\x9d\xe2\x81\xa6\n";
    out = diagnose("b\xe2\x80\xae\xc2\x9b.pcs", bidi, sizeof bidi - 1);
    assert_string_equal(out,
                        "b\\u202e\\u009b.pcs:2:5: error: unexpected non-ASCII "
                        "text; names are ASCII letters, digits and '_'\n"
                        "M = \\u009b\\u202e + A\n"
                        "    ^~~~~~~~~~~~\n"
                        "b\\u202e\\u009b.pcs:3:5: error: unexpected non-ASCII "
                        "text; names are ASCII letters, digits and '_'\n"
                        "N = \\u009d\\u2066\n"
                        "    ^~~~~~~~~~~~\n");
    free(out);
    /* derive_file's own messages escape the name too */
    out = file_diagnostic("/nonexistent/\xc2\x9b\xe2\x80\xae.pcs");
    assert_string_equal(out, "/nonexistent/\\u009b\\u202e.pcs: error: cannot "
                             "open the file: No such file or directory\n");
    free(out);
}

/* derive_file's message for a file it refuses */
static char *file_diagnostic(const char *path)
{
    char *out = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&out, &n);
    int nerr = 0;
    Derived *d = derive_file(path, mem, &nerr);
    fclose(mem);
    assert_null(d);
    assert_int_equal(nerr, 1);
    return out;
}

/* input is bounded: an endless device, a directory, and a file one byte
 * over the limit are refused, in bounded time and memory */
static void test_input_limits(void **state)
{
    (void)state;
    char *out = file_diagnostic("/dev/zero");
    assert_string_equal(out, "/dev/zero: error: cannot read the file: it is "
                             "larger than 16 MiB, the limit of a scheme\n");
    free(out);
    out = file_diagnostic(".");
    assert_string_equal(out,
                        ".: error: cannot read the file: it is a directory\n");
    free(out);
    char path[] = "/tmp/pc_limitXXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    assert_non_null(f);
    assert_int_equal(fseek(f, (long)DERIVE_MAX_SOURCE, SEEK_SET), 0);
    fputc('\n', f); /* DERIVE_MAX_SOURCE + 1 bytes */
    fclose(f);
    out = file_diagnostic(path);
    assert_non_null(strstr(out, "larger than 16 MiB"));
    free(out);
    remove(path);
}

/* the time budget, checked between operations: a budget that has run out
 * before the first node is reported there, once, and nothing else is
 * derived */
static void test_time_budget_soft(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t\nM = along(A, B, t)\n"
                               "N = along(A, B, 1 - t)\n";
    char *out = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&out, &n);
    DeriveOptions opt = {.max_seconds = 1e-9};
    int nerr = 0;
    Derived *d =
        derive_source_ex("b.pcs", text, sizeof text - 1, mem, &nerr, &opt);
    fclose(mem);
    assert_null(d);
    assert_int_equal(nerr, 1);
    assert_string_equal(out, "b.pcs:3:5: error: the time budget of 1e-09 s "
                             "ran out while deriving this; raise it with "
                             "--max-seconds\n"
                             "M = along(A, B, t)\n"
                             "    ^~~~~~~~~~~~~~\n");
    free(out);
}

/* --verbose: one line per definition with its size (the time varies) */
static void test_verbose_progress(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C\nparam t\nM = along(A, B, t)\n"
                               "k = t^2 + 3\n";
    char *out = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&out, &n);
    DeriveOptions opt = {.max_seconds = 0, .verbose = mem};
    Derived *d =
        derive_source_ex("v.pcs", text, sizeof text - 1, NULL, NULL, &opt);
    fclose(mem);
    assert_non_null(d);
    derived_free(d);
    /* M = (A*(1 - t) + B*t)/1: numerators 2 + 1 terms, den 1 term */
    char *l1 = strstr(out, "v.pcs:3: M: ");
    char *l2 = strstr(out, "v.pcs:4: k: ");
    assert_true(l1 == out && l2 != NULL);
    assert_non_null(strstr(l1, " ms, combination of points, 4 terms, degree "
                               "1, 1-bit coefficients\nv.pcs:4: k: "));
    assert_non_null(
        strstr(l2, " ms, scalar, 3 terms, degree 2, 2-bit coefficients\n"));
    free(out);
}

/* the C API's budget option */
static void test_api_time_budget(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t\nM = along(A, B, t)\n";
    char *diag = NULL;
    pc_options opt = {.max_seconds = 1e-9};
    pc_scheme *s =
        pc_scheme_parse_opts("a.pcs", text, sizeof text - 1, &opt, &diag);
    assert_null(s);
    assert_non_null(diag);
    assert_non_null(strstr(diag, "a.pcs:3:5: error: the time budget of 1e-09 "
                                 "s ran out while deriving this"));
    free(diag);
    opt.max_seconds = 0; /* none */
    s = pc_scheme_parse_opts("a.pcs", text, sizeof text - 1, &opt, &diag);
    assert_non_null(s);
    assert_null(diag);
    pc_scheme_free(s);
}

/* the C API's -D: an int of a family scheme, and a define not declared */
static void test_api_defines(void **state)
{
    (void)state;
    static const char text[] = "int n = 2\npoint M[1..n+1]\nparam t\n"
                               "X = bezier(t, M[1..n+1])\n";
    const char *defs[1] = {"n=4"};
    pc_options opt = {.max_seconds = 60, .defines = defs, .ndefines = 1};
    char *diag = NULL;
    pc_scheme *s =
        pc_scheme_parse_opts("f.pcs", text, sizeof text - 1, &opt, &diag);
    assert_non_null(s);
    assert_int_equal(pc_npoints(s), 5);
    assert_string_equal(pc_point_name(s, 4), "M_5");
    pc_scheme_free(s);
    defs[0] = "m=4";
    s = pc_scheme_parse_opts("f.pcs", text, sizeof text - 1, &opt, &diag);
    assert_null(s);
    assert_non_null(diag);
    assert_string_equal(diag, "pointcalc: -D m=4: f.pcs declares no 'int m'\n");
    free(diag);
}

static void test_budget_options(void **state)
{
    (void)state;
    BudgetOptions b;
    static const char *const ok_text[] = {
        "x",  "--max-seconds", "2.5", "--max-memory", "512M",
        "-v", "--max-memory",  "3G",  "--max-memory", "4096"};
    static const char *const bad_text[] = {
        "--max-seconds", "-1", "--max-memory", "2X",
        "--max-seconds", "1s", "--max-memory"};
    char *ok[10], *bad[7]; /* argv is char ** */
    for (int i = 0; i < 10; i++)
        ok[i] = (char *)ok_text[i];
    for (int i = 0; i < 7; i++)
        bad[i] = (char *)bad_text[i];
    budget_options_default(&b);
    assert_true(b.max_seconds == 60.0 && b.max_memory == (size_t)2 << 30);
    assert_int_equal(budget_parse_option(&b, 10, ok, 0, stderr), 0);
    assert_int_equal(budget_parse_option(&b, 10, ok, 1, stderr), 2);
    assert_true(b.max_seconds == 2.5);
    assert_int_equal(budget_parse_option(&b, 10, ok, 3, stderr), 2);
    assert_true(b.max_memory == (size_t)512 << 20);
    assert_int_equal(budget_parse_option(&b, 10, ok, 5, stderr), 1);
    assert_true(b.verbose);
    assert_int_equal(budget_parse_option(&b, 10, ok, 6, stderr), 2);
    assert_true(b.max_memory == (size_t)3 << 30);
    assert_int_equal(budget_parse_option(&b, 10, ok, 8, stderr), 2);
    assert_true(b.max_memory == 4096);
    /* plain bytes above 10^9 as well as 1G (issue 23 item 9) */
    char *big[] = {(char *)"--max-memory", (char *)"1073741824"};
    assert_int_equal(budget_parse_option(&b, 2, big, 0, stderr), 2);
    assert_true(b.max_memory == (size_t)1 << 30);
    char *msg = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&msg, &n);
    assert_int_equal(budget_parse_option(&b, 7, bad, 0, mem), -1);
    assert_int_equal(budget_parse_option(&b, 7, bad, 2, mem), -1);
    assert_int_equal(budget_parse_option(&b, 7, bad, 4, mem), -1);
    assert_int_equal(budget_parse_option(&b, 7, bad, 6, mem), -1);
    fclose(mem);
    assert_string_equal(
        msg, "pointcalc: --max-seconds '-1': expected a number of seconds "
             "from 0 (no budget) up\n"
             "pointcalc: --max-memory '2X': expected a size in bytes, or with "
             "K, M or G (KiB, MiB, GiB), e.g. 2G (0: no budget)\n"
             "pointcalc: --max-seconds '1s': expected a number of seconds, "
             "e.g. 60 or 0.5 (0: no budget)\n"
             "pointcalc: --max-memory needs a value\n");
    free(msg);
}

/* "\r\n" and a lone "\r" end lines like "\n" (a CR-only file used to be
 * read as one line) */
static void test_line_ends_cr_crlf(void **state)
{
    (void)state;
    static const char *const texts[] = {
        "point A, B\rparam t\rM = along(A, B, t)\rN = along(A, B, s)\r",
        "point A, B\r\nparam t\r\nM = along(A, B, t) # c\r\n"
        "N = along(A, B, s)\r\n",
        "point A, B\nparam t\rM = along(A, B, t)\r\nN = along(A, B, s)",
    };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        char *out = diagnose("c.pcs", texts[i], strlen(texts[i]));
        assert_string_equal(out, "c.pcs:4:17: error: undefined name 's'; "
                                 "expected a declared point, parameter, "
                                 "constant or an earlier definition\n"
                                 "N = along(A, B, s)\n"
                                 "                ^\n");
        free(out);
    }
}

/* the size limits refuse what would be huge, not what is merely large:
 * these derive (each result is at most a few tens of KB) */
static void test_limits_allow_reasonable_results(void **state)
{
    (void)state;
    static const char *const ok[] = {
        /* a Bezier curve of order 20 with a substituted parameter */
        "point P0, P1, P2, P3, P4, P5, P6, P7, P8, P9, P10, P11, P12, P13, "
        "P14, P15, P16, P17, P18, P19, P20\nparam t, u\nconst k\n"
        "B = bezier(t, P0, P1, P2, P3, P4, P5, P6, P7, P8, P9, P10, P11, P12, "
        "P13, P14, P15, P16, P17, P18, P19, P20)\nM = subst(B, t, t*u + k)\n",
        /* a power of a sum in several variables */
        "point A, B\nparam t, u\nconst k\n"
        "M = along(A, B, (t^2 + u^2 + k^2)^50)\n",
        /* a high derivative of a sparse high-degree function */
        "param t, u\nS = diff(1/(t^100*u^100 + t + u + 1), t, 30)\n",
    };
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++) {
        char *e = errors_of(ok[i]);
        assert_string_equal(e, "");
        free(e);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_precedence_and_associativity),
        cmocka_unit_test(test_parse_statements),
        cmocka_unit_test(test_parse_check_statements),
        cmocka_unit_test(test_diag_format_has_line_and_caret),
        cmocka_unit_test(test_diag_caret_spans_expression),
        cmocka_unit_test(test_diag_redefinition_has_note),
        cmocka_unit_test(test_syntax_errors_all_reported),
        cmocka_unit_test(test_last_line_without_newline),
        cmocka_unit_test(test_scheme_name_defaults_to_file),
        cmocka_unit_test(test_decimals_are_exact),
        cmocka_unit_test(test_deep_expressions_are_refused),
        cmocka_unit_test(test_diag_nul_in_line),
        cmocka_unit_test(test_diag_escapes_and_utf8_columns),
        cmocka_unit_test(test_line_ends_cr_crlf),
        cmocka_unit_test(test_input_limits),
        cmocka_unit_test(test_time_budget_soft),
        cmocka_unit_test(test_verbose_progress),
        cmocka_unit_test(test_budget_options),
        cmocka_unit_test(test_api_time_budget),
        cmocka_unit_test(test_api_defines),
        cmocka_unit_test(test_limits_allow_reasonable_results),
    };
    int rc = cmocka_run_group_tests_name("front", tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
