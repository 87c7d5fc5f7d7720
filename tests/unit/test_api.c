/*
 * test_api.c - the public C API, libpointcalc.h (docs/api.md): every
 * function it declares is called at least once and its result checked
 * against values written here by hand (names, counts, kinds, lines, the
 * weights' text, numbers from the constructions' definitions), the
 * documented sentinels of bad arguments (PC_NOKIND, -1, NULL, PC_EINVAL),
 * and the diagnostics' exact text.
 *
 * Every public function and the test that calls it:
 *
 *   pc_use_memory_budget   main (0: no budget; process-wide, so it is
 *                          called once, before any other pc_ call)
 *   pc_scheme_parse        test_api_names_and_counts, test_api_weight_str,
 *                          test_api_compile_and_eval, test_api_eval_statuses,
 *                          test_api_eval_einval, test_api_parse_errors,
 *                          test_api_compile_errors, test_api_emit_c,
 *                          test_api_options (without options),
 *                          thread_main (test_api_thread_cleanup)
 *   pc_scheme_load         test_api_load (examples/desargues_arc.pcs, a
 *                          missing file)
 *   pc_scheme_parse_opts   test_api_options, test_api_budget_after_derive,
 *                          test_api_budget_after_last_check
 *   pc_scheme_load_opts    test_api_options
 *   pc_scheme_free         every test that makes a scheme (and NULL)
 *   pc_scheme_name         test_api_names_and_counts, test_api_load
 *   pc_npoints             test_api_names_and_counts, test_api_load
 *   pc_point_name          test_api_names_and_counts, test_api_load
 *   pc_nparams             test_api_names_and_counts, test_api_load
 *   pc_param_name          test_api_names_and_counts, test_api_load
 *   pc_nconsts             test_api_names_and_counts, test_api_load
 *   pc_const_name          test_api_names_and_counts
 *   pc_noutputs            test_api_names_and_counts, test_api_load
 *   pc_output_name         test_api_names_and_counts, test_api_load
 *   pc_output_kind         test_api_names_and_counts, test_api_load
 *   pc_output_line         test_api_names_and_counts
 *   pc_find_output         test_api_names_and_counts, test_api_load
 *   pc_find_point          test_api_names_and_counts, test_api_load
 *   pc_weight_str          test_api_weight_str, test_api_load,
 *                          test_api_options, test_api_weight_str_budget
 *   pc_compile             test_api_compile_and_eval, test_api_eval_statuses,
 *                          test_api_eval_einval, test_api_compile_errors,
 *                          thread_main
 *   pc_plan_free           every test that compiles (and NULL)
 *   pc_plan_dump           test_api_compile_and_eval
 *   pc_eval                test_api_compile_and_eval, test_api_eval_statuses,
 *                          test_api_eval_einval, thread_main
 *   pc_emit_c              test_api_emit_c, test_api_compile_errors
 *   pc_thread_cleanup      thread_main (a thread other than the main one)
 *   pc_cleanup             teardown_group (once, at the end)
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/unit/slow_lower.h"
#include <time.h>
#include <unistd.h>

#include "libpointcalc.h"

static const char api_text[] = "scheme api\n"          // 1
                               "point A, B, C\n"       // 2
                               "param t\n"             // 3
                               "const k\n"             // 4
                               "M = along(A, B, t)\n"  // 5
                               "\n"                    // 6
                               "D = divide(A, C, k)\n" // 7
                               "V = C - B\n"           // 8
                               "s = t*k + 1\n"         // 9
                               "output M, D, V, s\n";  // 10

static pc_scheme *parse_ok(const char *name, const char *text)
{
    char *diag = (char *)"not touched";
    pc_scheme *s = pc_scheme_parse(name, text, strlen(text), &diag);
    if (!s)
        fail_msg("%s", diag);
    assert_null(diag); /* set to NULL on success */
    return s;
}

static pc_plan *compile_ok(const pc_scheme *s)
{
    char *diag = (char *)"not touched";
    pc_plan *p = pc_compile(s, &diag);
    assert_non_null(p);
    assert_null(diag);
    return p;
}

static void assert_close(double a, double b)
{
    if (!(fabs(a - b) <= 4 * DBL_EPSILON * fmax(1.0, fabs(b))))
        fail_msg("%.17g is not %.17g", a, b);
}

static void test_api_names_and_counts(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("api.pcs", api_text);
    assert_string_equal(pc_scheme_name(s), "api");
    assert_int_equal(pc_npoints(s), 3);
    assert_string_equal(pc_point_name(s, 0), "A");
    assert_string_equal(pc_point_name(s, 1), "B");
    assert_string_equal(pc_point_name(s, 2), "C");
    assert_null(pc_point_name(s, 3));
    assert_null(pc_point_name(s, -1));
    assert_int_equal(pc_nparams(s), 1);
    assert_string_equal(pc_param_name(s, 0), "t");
    assert_null(pc_param_name(s, 1));
    assert_null(pc_param_name(s, -1));
    assert_int_equal(pc_nconsts(s), 1);
    assert_string_equal(pc_const_name(s, 0), "k");
    assert_null(pc_const_name(s, 1));
    assert_null(pc_const_name(s, -1));
    assert_int_equal(pc_noutputs(s), 4);
    static const char *const names[] = {"M", "D", "V", "s"};
    static const pc_kind kinds[] = {PC_POINT, PC_POINT, PC_VECTOR, PC_SCALAR};
    static const int lines[] = {5, 7, 8, 9};
    for (int o = 0; o < 4; o++) {
        assert_string_equal(pc_output_name(s, o), names[o]);
        assert_int_equal(pc_output_kind(s, o), kinds[o]);
        assert_int_equal(pc_output_line(s, o), lines[o]);
        assert_int_equal(pc_find_output(s, names[o]), o);
    }
    assert_null(pc_output_name(s, 4));
    assert_null(pc_output_name(s, -1));
    assert_int_equal(pc_output_kind(s, 4), PC_NOKIND);
    assert_int_equal(pc_output_kind(s, -1), PC_NOKIND);
    assert_int_equal(pc_output_line(s, 4), -1);
    assert_int_equal(pc_output_line(s, -1), -1);
    assert_int_equal(pc_find_output(s, "N"), -1);
    assert_int_equal(pc_find_output(s, "A"), -1); /* a point, no output */
    assert_int_equal(pc_find_point(s, "A"), 0);
    assert_int_equal(pc_find_point(s, "C"), 2);
    assert_int_equal(pc_find_point(s, "M"), -1); /* an output, no point */
    assert_int_equal(pc_find_point(s, "Z"), -1);
    pc_scheme_free(s);
    pc_scheme_free(NULL);

    /* without `scheme NAME`: the file's base name without its extension */
    s = parse_ok("dir/arc.pcs", "point A, B\nM = (A + B)/2\n");
    assert_string_equal(pc_scheme_name(s), "arc");
    assert_int_equal(pc_nparams(s), 0);
    assert_int_equal(pc_nconsts(s), 0);
    assert_int_equal(pc_noutputs(s), 1); /* the last definition */
    assert_string_equal(pc_output_name(s, 0), "M");
    assert_int_equal(pc_output_line(s, 0), 2);
    pc_scheme_free(s);
}

static void assert_weight(const pc_scheme *s, int o, int pt, const char *w)
{
    char *got = pc_weight_str(s, o, pt);
    assert_non_null(got);
    assert_string_equal(got, w);
    free(got);
}

static void test_api_weight_str(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("api.pcs", api_text);
    /* along(A, B, t) = A (1 - t) + B t */
    assert_weight(s, 0, 0, "-t+1");
    assert_weight(s, 0, 1, "t");
    assert_weight(s, 0, 2, "0"); /* C does not occur */
    /* divide(A, C, k) = (A + k C)/(1 + k) */
    assert_weight(s, 1, 0, "1/(k+1)");
    assert_weight(s, 1, 1, "0");
    assert_weight(s, 1, 2, "k/(k+1)");
    /* C - B */
    assert_weight(s, 2, 0, "0");
    assert_weight(s, 2, 1, "-1");
    assert_weight(s, 2, 2, "1");
    /* a scalar: point -1 */
    assert_weight(s, 3, -1, "t*k+1");
    /* bad indices: NULL */
    assert_null(pc_weight_str(s, 4, 0));
    assert_null(pc_weight_str(s, -1, 0));
    assert_null(pc_weight_str(s, 0, 3));
    assert_null(pc_weight_str(s, 0, -1)); /* -1 is for scalars only */
    assert_null(pc_weight_str(s, 3, 0));  /* a scalar has no point */
    pc_scheme_free(s);
}

/* the Desargues arc, from the repository's example (tests run from the
 * root); its weights as docs/api.md prints them */
static void test_api_load(void **state)
{
    (void)state;
    char *diag = (char *)"not touched";
    pc_scheme *s = pc_scheme_load("examples/desargues_arc.pcs", &diag);
    assert_non_null(s);
    assert_null(diag);
    assert_string_equal(pc_scheme_name(s), "desargues_arc");
    assert_int_equal(pc_npoints(s), 4);
    assert_string_equal(pc_point_name(s, 3), "D");
    assert_int_equal(pc_nparams(s), 1);
    assert_string_equal(pc_param_name(s, 0), "t");
    assert_int_equal(pc_nconsts(s), 0);
    /* output M, M_CB, M_AD, dM, d2M */
    assert_int_equal(pc_noutputs(s), 5);
    assert_string_equal(pc_output_name(s, 0), "M");
    assert_string_equal(pc_output_name(s, 4), "d2M");
    assert_int_equal(pc_output_kind(s, 0), PC_POINT);
    assert_int_equal(pc_output_kind(s, 3), PC_VECTOR);
    assert_int_equal(pc_output_kind(s, 4), PC_VECTOR);
    int m = pc_find_output(s, "M");
    assert_int_equal(m, 0);
    assert_int_equal(pc_find_output(s, "dM"), 3);
    assert_int_equal(pc_find_output(s, "T"), -1); /* defined, not output */
    assert_weight(s, m, pc_find_point(s, "A"),
                  "(-t^3+3*t^2-3*t+1)/(2*t^2-2*t+1)");
    assert_weight(s, m, pc_find_point(s, "B"), "(-t^3+t^2)/(2*t^2-2*t+1)");
    assert_weight(s, m, pc_find_point(s, "C"), "(t^3-2*t^2+t)/(2*t^2-2*t+1)");
    assert_weight(s, m, pc_find_point(s, "D"), "t^3/(2*t^2-2*t+1)");
    pc_scheme_free(s);

    /* a missing file: NULL and one line that says why (the text of
     * tests/cli_test.sh; derive.h's comment says "cannot read the file"
     * for every unreadable file, but a missing one is "cannot open") */
    diag = NULL;
    assert_null(pc_scheme_load("/nonexistent-dir/x.pcs", &diag));
    assert_non_null(diag);
    assert_string_equal(diag, "/nonexistent-dir/x.pcs: error: cannot open "
                              "the file: No such file or directory\n");
    free(diag);
    /* diagnostics NULL: nothing handed back, still NULL */
    assert_null(pc_scheme_load("/nonexistent-dir/x.pcs", NULL));
}

static void test_api_parse_errors(void **state)
{
    (void)state;
    /* docs/language.md's example, text and caret */
    static const char bad[] = "param t\npoint A, B\nM = A*t + B\n";
    char *diag = NULL;
    assert_null(pc_scheme_parse("x.pcs", bad, strlen(bad), &diag));
    assert_non_null(diag);
    assert_string_equal(diag, "x.pcs:3:5: error: weights of M sum to t+1, "
                              "not 0 (a vector) or 1 (a point)\n"
                              "M = A*t + B\n"
                              "    ^~~~~~~\n");
    free(diag);
    assert_null(pc_scheme_parse("x.pcs", bad, strlen(bad), NULL));
    /* len counts: the text cut after line 2 is a valid scheme */
    static const char cut[] = "point A, B\nM = (A + B)/2\nZ = A*t\n";
    assert_null(pc_scheme_parse("x.pcs", cut, strlen(cut), NULL));
    pc_scheme *s = pc_scheme_parse("x.pcs", cut, 25, &diag);
    assert_non_null(s);
    assert_null(diag);
    assert_int_equal(pc_noutputs(s), 1);
    assert_string_equal(pc_output_name(s, 0), "M");
    pc_scheme_free(s);
}

/* the plan's values: the base points A = (0, 0), B = (4, 2), C = (1, 3) */
static void test_api_compile_and_eval(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("api.pcs", api_text);
    pc_plan *p = compile_ok(s);
    pc_scheme_free(s); /* a plan outlives its scheme */

    char *dump = pc_plan_dump(p);
    assert_non_null(dump);
    assert_true(strncmp(dump, "plan api:", 9) == 0);
    assert_non_null(strstr(dump, "output M point line 5"));
    assert_non_null(strstr(dump, "output D point line 7"));
    assert_non_null(strstr(dump, "output V vector line 8"));
    assert_non_null(strstr(dump, "output s scalar line 9"));
    free(dump);

    const double A[2] = {0, 0}, B[2] = {4, 2}, C[2] = {1, 3};
    const double *points[3] = {A, B, C};
    const double t[3] = {0, 0.25, 1};
    const double *params[1] = {t};
    const double k[1] = {3};
    double out[6];
    unsigned char st[3] = {9, 9, 9};
    size_t npoles = 99;
    /* M = A (1 - t) + B t = (4t, 2t) */
    assert_int_equal(pc_eval(p, 0, 3, params, k, points, 2, out, st, &npoles),
                     PC_OK);
    assert_true(npoles == 0);
    assert_close(out[0], 0);
    assert_close(out[1], 0);
    assert_close(out[2], 1);
    assert_close(out[3], 0.5);
    assert_close(out[4], 4);
    assert_close(out[5], 2);
    assert_int_equal(st[0] | st[1] | st[2], 0);
    /* D = (A + 3 C)/4 = (0.75, 2.25), whatever t */
    assert_int_equal(pc_eval(p, 1, 3, params, k, points, 2, out, NULL, NULL),
                     PC_OK);
    for (int i = 0; i < 3; i++) {
        assert_close(out[2 * i], 0.75);
        assert_close(out[2 * i + 1], 2.25);
    }
    /* V = C - B = (-3, 1) */
    assert_int_equal(pc_eval(p, 2, 1, params, k, points, 2, out, NULL, NULL),
                     PC_OK);
    assert_true(out[0] == -3 && out[1] == 1);
    /* s = t k + 1 = 1, 1.75, 4: one number per sample, no points needed */
    double sv[3];
    assert_int_equal(pc_eval(p, 3, 3, params, k, NULL, 0, sv, NULL, &npoles),
                     PC_OK);
    assert_true(sv[0] == 1 && sv[1] == 1.75 && sv[2] == 4);
    assert_true(npoles == 0);
    /* dim 3: the same point in space; A (0, 0, 1), B (4, 2, 1) */
    const double A3[3] = {0, 0, 1}, B3[3] = {4, 2, 1};
    const double *points3[3] = {A3, B3, NULL}; /* C: M does not use it */
    double o3[9];
    assert_int_equal(pc_eval(p, 0, 3, params, k, points3, 3, o3, NULL, NULL),
                     PC_OK);
    assert_close(o3[3], 1);
    assert_close(o3[4], 0.5);
    assert_close(o3[5], 1);
    pc_plan_free(p);
    pc_plan_free(NULL);
}

/* statuses: 1 a pole, 2 an overflow of a denominator, 4 a domain or a
 * declared range the derivation used; NaN there, counted in npoles */
static void test_api_eval_statuses(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("st.pcs", "point A, B\nparam t\n"
                                      "P = divide(A, B, t^3)\n"
                                      "q = sqrt(t - 2)\noutput P, q\n");
    pc_plan *p = compile_ok(s);
    const double A[1] = {0}, B[1] = {1};
    const double *points[2] = {A, B};
    /* P = (A + t^3 B)/(1 + t^3): at t = 1, 1/2; t = -1 a pole; t = 1e110
     * overflows 1 + t^3 */
    const double t[4] = {1, -1, 1e110, 2};
    const double *params[1] = {t};
    double out[4];
    unsigned char st[4];
    size_t npoles = 0;
    assert_int_equal(
        pc_eval(p, 0, 4, params, NULL, points, 1, out, st, &npoles), PC_OK);
    assert_true(npoles == 2);
    assert_int_equal(st[0], 0);
    assert_close(out[0], 0.5);
    assert_int_equal(st[1], 1);
    assert_true(isnan(out[1]));
    assert_int_equal(st[2], 2);
    assert_true(isnan(out[2]));
    assert_int_equal(st[3], 0);
    assert_close(out[3], 8.0 / 9.0);
    /* sqrt(t - 2): t < 2 is outside its domain */
    const double tq[3] = {1, 2, 6};
    const double *pq[1] = {tq};
    assert_int_equal(pc_eval(p, 1, 3, pq, NULL, NULL, 0, out, st, &npoles),
                     PC_OK);
    assert_true(npoles == 1);
    assert_int_equal(st[0], 4);
    assert_true(isnan(out[0]));
    assert_true(out[1] == 0 && out[2] == 2);
    assert_int_equal(st[1] | st[2], 0);
    pc_plan_free(p);
    pc_scheme_free(s);
    /* abs(t) = t for t in [0, 1] rests on t >= 0 */
    s = parse_ok("r.pcs", "param t in [0, 1]\nr = abs(t)\n");
    p = compile_ok(s);
    const double tr[3] = {-0.5, 0.5, 1.5};
    const double *pr[1] = {tr};
    assert_int_equal(pc_eval(p, 0, 3, pr, NULL, NULL, 0, out, st, &npoles),
                     PC_OK);
    assert_true(npoles == 1);
    assert_int_equal(st[0], 4);
    assert_true(isnan(out[0]));
    assert_true(out[1] == 0.5 && out[2] == 1.5);
    pc_plan_free(p);
    pc_scheme_free(s);
}

/* PC_EINVAL for every bad argument docs/api.md names; n = 0 is PC_OK */
static void test_api_eval_einval(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("api.pcs", api_text);
    pc_plan *p = compile_ok(s);
    const double A[2] = {0, 0}, B[2] = {4, 2}, C[2] = {1, 3};
    const double *points[3] = {A, B, C};
    const double *no_b[3] = {A, NULL, C};
    const double t[1] = {0.5};
    const double *params[1] = {t};
    const double *no_param[1] = {NULL};
    const double k[1] = {3};
    double out[2];
    size_t npoles = 99;
    assert_int_equal(pc_eval(p, -1, 1, params, k, points, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 4, 1, params, k, points, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, params, k, NULL, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, params, k, no_b, 2, out, NULL, NULL),
                     PC_EINVAL);
    /* C is not used by M: NULL is allowed there */
    const double *no_c[3] = {A, B, NULL};
    assert_int_equal(pc_eval(p, 0, 1, params, k, no_c, 2, out, NULL, NULL),
                     PC_OK);
    assert_int_equal(pc_eval(p, 0, 1, params, k, points, 0, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, NULL, k, points, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, no_param, k, points, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, params, NULL, points, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, params, k, points, 2, NULL, NULL, NULL),
                     PC_EINVAL);
    /* n = 0: nothing to do, whatever the other arguments */
    assert_int_equal(pc_eval(p, 0, 0, NULL, NULL, NULL, 0, NULL, NULL, &npoles),
                     PC_OK);
    assert_true(npoles == 0);
    assert_int_equal(pc_eval(p, 9, 0, NULL, NULL, NULL, 0, NULL, NULL, NULL),
                     PC_EINVAL); /* but the output must exist */
    pc_plan_free(p);
    pc_scheme_free(s);

    /* coord(A, 2) needs dim >= 2 */
    s = parse_ok("c.pcs", "point A\ny = coord(A, 2)\n");
    p = compile_ok(s);
    const double a2[2] = {5, 7};
    const double *pa[1] = {a2};
    assert_int_equal(pc_eval(p, 0, 1, NULL, NULL, pa, 1, out, NULL, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_eval(p, 0, 1, NULL, NULL, pa, 2, out, NULL, NULL),
                     PC_OK);
    assert_true(out[0] == 7);
    pc_plan_free(p);
    pc_scheme_free(s);
}

static void test_api_compile_errors(void **state)
{
    (void)state;
    static const char big[] = "param t\ns = 10^400*t\n";
    static const char expect[] =
        "x.pcs:2:1: error: s cannot be evaluated in double precision: scaled "
        "to integer coefficients, its equation has a coefficient of about "
        "10^400, beyond the largest double\n"
        "s = 10^400*t\n"
        "^\n";
    pc_scheme *s = parse_ok("x.pcs", big);
    char *diag = NULL;
    assert_null(pc_compile(s, &diag));
    assert_non_null(diag);
    assert_string_equal(diag, expect);
    free(diag);
    assert_null(pc_compile(s, NULL));
    /* emit-c refuses it the same way */
    diag = NULL;
    assert_null(pc_emit_c(s, NULL, &diag));
    assert_non_null(diag);
    assert_string_equal(diag, expect);
    free(diag);
    pc_scheme_free(s);
}

static void test_api_emit_c(void **state)
{
    (void)state;
    pc_scheme *s = parse_ok("api.pcs", api_text);
    char *diag = (char *)"not touched";
    char *c = pc_emit_c(s, NULL, &diag);
    assert_non_null(c);
    assert_null(diag);
    /* docs/codegen.md: NAME_M, NAME_M_batch and the _checked pair, for
     * every output; params, consts, points in declaration order */
    static const char *const fns[] = {
        "void api_M(double t, double k, const double *A,",
        "void api_M_batch(",
        "int api_M_checked(",
        "size_t api_M_batch_checked(",
        "void api_D(",
        "void api_V_batch(",
        "int api_s_checked(",
    };
    for (size_t i = 0; i < sizeof fns / sizeof fns[0]; i++)
        if (!strstr(c, fns[i]))
            fail_msg("no '%s' in the generated C", fns[i]);
    assert_non_null(strstr(c, "#include <math.h>"));
    free(c);
    /* a prefix */
    c = pc_emit_c(s, "geo", &diag);
    assert_non_null(c);
    assert_non_null(strstr(c, "void geo_M("));
    assert_null(strstr(c, "api_M"));
    free(c);
    /* a prefix that is no C identifier */
    diag = NULL;
    assert_null(pc_emit_c(s, "1x", &diag));
    assert_non_null(diag);
    assert_string_equal(
        diag, "pointcalc: prefix '1x' is not a usable C identifier\n");
    free(diag);
    pc_scheme_free(s);
    /* two outputs making the same C name: M's batch and M_batch */
    s = parse_ok("x.pcs", "point A, B\nparam t\nM = along(A, B, t)\n"
                          "M_batch = along(B, A, t)\noutput M, M_batch\n");
    diag = NULL;
    assert_null(pc_emit_c(s, NULL, &diag));
    assert_non_null(diag);
    assert_string_equal(diag, "x.pcs:4:1: error: emit-c would write the C "
                              "function x_M_batch for both M (line 3) and "
                              "M_batch; rename one of them\n"
                              "M_batch = along(B, A, t)\n"
                              "^~~~~~~\n");
    free(diag);
    /* a prefix removes the clash? no: geo_M_batch twice as well */
    assert_null(pc_emit_c(s, "geo", NULL));
    pc_scheme_free(s);
}

/* pc_options: -D's defines and the time budget */
static void test_api_options(void **state)
{
    (void)state;
    static const char fam[] = "int n = 2\npoint A, B\nparam t\n"
                              "M = along(A, B, t^n)\n";
    /* without options: n = 2 */
    pc_scheme *s = parse_ok("fam.pcs", fam);
    assert_weight(s, 0, 1, "t^2");
    pc_scheme_free(s);
    const char *defines[] = {"n=3"};
    pc_options opt = {.max_seconds = 0, .defines = defines, .ndefines = 1};
    char *diag = (char *)"not touched";
    s = pc_scheme_parse_opts("fam.pcs", fam, strlen(fam), &opt, &diag);
    assert_non_null(s);
    assert_null(diag);
    assert_weight(s, 0, 0, "-t^3+1");
    assert_weight(s, 0, 1, "t^3");
    pc_scheme_free(s);
    /* opt NULL: as pc_scheme_parse */
    s = pc_scheme_parse_opts("fam.pcs", fam, strlen(fam), NULL, NULL);
    assert_non_null(s);
    assert_weight(s, 0, 1, "t^2");
    pc_scheme_free(s);
    /* a define the scheme does not declare (docs/language.md's text) */
    const char *bad[] = {"m=3"};
    pc_options optb = {.max_seconds = 60, .defines = bad, .ndefines = 1};
    diag = NULL;
    assert_null(pc_scheme_parse_opts("x.pcs", fam, strlen(fam), &optb, &diag));
    assert_non_null(diag);
    assert_string_equal(diag, "pointcalc: -D m=3: x.pcs declares no 'int m'\n");
    free(diag);

    /* the same from a file */
    char dir[] = "/tmp/test_api_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[64];
    snprintf(path, sizeof path, "%s/fam.pcs", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(fam, f);
    fclose(f);
    const char *four[] = {"n=4"};
    pc_options opt4 = {.max_seconds = 0, .defines = four, .ndefines = 1};
    diag = (char *)"not touched";
    s = pc_scheme_load_opts(path, &opt4, &diag);
    assert_non_null(s);
    assert_null(diag);
    assert_string_equal(pc_scheme_name(s), "fam");
    assert_weight(s, 0, 1, "t^4");
    pc_scheme_free(s);
    diag = NULL;
    assert_null(pc_scheme_load_opts(path, &optb, &diag));
    char expect[160];
    snprintf(expect, sizeof expect,
             "pointcalc: -D m=3: %s declares no 'int m'\n", path);
    assert_string_equal(diag, expect);
    free(diag);
    unlink(path);
    rmdir(dir);
    diag = NULL;
    assert_null(pc_scheme_load_opts("/nonexistent-dir/y.pcs", &opt4, &diag));
    assert_string_equal(diag, "/nonexistent-dir/y.pcs: error: cannot open "
                              "the file: No such file or directory\n");
    free(diag);

    /* a time budget of 1 ns runs out at the first check: a located
     * error naming the budget */
    pc_options quick = {.max_seconds = 1e-9};
    diag = NULL;
    s = pc_scheme_load_opts("examples/desargues_arc.pcs", &quick, &diag);
    assert_null(s);
    assert_non_null(diag);
    assert_true(strncmp(diag, "examples/desargues_arc.pcs:", 27) == 0);
    assert_non_null(strstr(diag, ": error: the time budget of 1e-09 s ran "
                                 "out while deriving this"));
    free(diag);
}

/* a thread other than the main one uses the library, then releases its
 * FLINT caches */
static void *thread_main(void *arg)
{
    double *res = arg;
    static const char text[] = "point A, B\nparam t\nM = divide(A, B, t)\n";
    pc_scheme *s = pc_scheme_parse("th.pcs", text, strlen(text), NULL);
    pc_plan *p = s ? pc_compile(s, NULL) : NULL;
    if (p) {
        const double A[1] = {1}, B[1] = {5}, t[1] = {3};
        const double *points[2] = {A, B}, *params[1] = {t};
        /* (A + 3 B)/4 = 4 */
        if (pc_eval(p, 0, 1, params, NULL, points, 1, res, NULL, NULL) != PC_OK)
            *res = -1;
    }
    pc_plan_free(p);
    pc_scheme_free(s);
    pc_thread_cleanup();
    return NULL;
}

static void test_api_thread_cleanup(void **state)
{
    (void)state;
    double res = 0;
    pthread_t th;
    assert_int_equal(pthread_create(&th, NULL, thread_main, &res), 0);
    assert_int_equal(pthread_join(th, NULL), 0);
    assert_close(res, 4);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* pc_options.max_seconds bounds pc_compile and pc_emit_c too: with a
 * budget between the derivation's time and the lowering's (both measured
 * here first, so the test holds on a slow machine and under valgrind),
 * the scheme derives, and both calls stop with the located budget error,
 * well before lowering would have ended */
static void test_api_budget_after_derive(void **state)
{
    (void)state;
    char *text = slow_to_lower(), *diag = NULL;
    pc_options big = {.max_seconds = 600};
    double t0 = now_s();
    pc_scheme *s =
        pc_scheme_parse_opts("budget.pcs", text, strlen(text), &big, &diag);
    double t1 = now_s();
    assert_non_null(s);
    pc_plan *p = pc_compile(s, &diag);
    double t2 = now_s();
    assert_non_null(p);
    pc_plan_free(p);
    pc_scheme_free(s);
    double derive = t1 - t0, lower = t2 - t1;
    if (lower < 20 * derive)
        skip(); /* too close to tell apart on this machine */
    pc_options o = {.max_seconds = sqrt(derive * lower)};
    s = pc_scheme_parse_opts("budget.pcs", text, strlen(text), &o, &diag);
    if (!s)
        fail_msg("%s", diag);
    for (int emit = 0; emit < 2; emit++) {
        double t3 = now_s();
        char *c = emit ? pc_emit_c(s, NULL, &diag) : NULL;
        p = emit ? NULL : pc_compile(s, &diag);
        assert_true(now_s() - t3 < lower / 2);
        assert_null(c);
        assert_null(p);
        assert_non_null(diag);
        assert_true(strncmp(diag, "budget.pcs:", 11) == 0);
        assert_non_null(strstr(diag, ": error: the time budget of "));
        assert_non_null(strstr(diag, " s ran out while lowering this to "
                                     "numbers; raise it with --max-seconds\n"));
        free(diag);
    }
    pc_scheme_free(s);
    free(text);
}

/* the time budget inside meet(): a meet whose fraction-free products
 * each pass the size guard but add up to seconds (tests/fuzz/regressions/
 * timeout-meet-big-result.pcs: 6 s natively, 111 s under ASan with a
 * budget of 0.25 s) stops at the next product past the budget, at the
 * meet (the library has no timer: the meet's loops read the clock) */
static void test_api_budget_inside_meet(void **state)
{
    (void)state;
    const char *text = "point A, B, C\nparam t, u\nconst k, h\n"
                       "a = (t + u + k + h)^30\nb = (t / u + k - h)^40\n"
                       "M = meet(line(A, along(B, C, a)), "
                       "line(B, along(C, A, b)))\n";
    char *diag = NULL;
    pc_options o = {.max_seconds = 0.25};
    double t0 = now_s();
    pc_scheme *s =
        pc_scheme_parse_opts("meet.pcs", text, strlen(text), &o, &diag);
    double took = now_s() - t0;
    assert_null(s);
    assert_non_null(diag);
    const char *want = "meet.pcs:6:5: error: the time budget of 0.25 s ran "
                       "out while deriving this; raise it with --max-seconds\n";
    assert_true(strncmp(diag, want, strlen(want)) == 0);
    free(diag);
    if (!getenv("PC_VALGRIND")) /* one product under memcheck takes long */
        assert_true(took < 4);
}

/* a derivation that ends past its deadline fails even when it never read
 * the clock there: the clock is read at each node, but the power below is
 * one FLINT call after the last node.  Its time is measured first (the
 * faster of two runs); a budget of an eighth of it runs out inside that
 * call, and the scheme fails with the located time-budget message (it
 * came back whole before the derivation's last look at the clock) */
static void test_api_budget_after_last_check(void **state)
{
    (void)state;
    const char *text = "point A, B\nparam t, u\nconst k, h\n"
                       "M = along(A, B, (t + u + k + h + 1)^40)\n";
    char *diag = NULL;
    pc_options big = {.max_seconds = 600};
    double full = 1e9;
    for (int i = 0; i < 2; i++) {
        double t0 = now_s();
        pc_scheme *s =
            pc_scheme_parse_opts("pow.pcs", text, strlen(text), &big, &diag);
        full = fmin(full, now_s() - t0);
        assert_non_null(s);
        pc_scheme_free(s);
    }
    pc_options o = {.max_seconds = full / 8};
    pc_scheme *s =
        pc_scheme_parse_opts("pow.pcs", text, strlen(text), &o, &diag);
    assert_null(s);
    assert_non_null(diag);
    assert_true(strncmp(diag, "pow.pcs:4:", 10) == 0);
    assert_non_null(strstr(diag, ": error: the time budget of "));
    assert_non_null(strstr(diag, " s ran out while deriving this; raise it "
                                 "with --max-seconds\nM = along("));
    free(diag);
}

/* pc_weight_str under the scheme's budget, counted from the call: a weight
 * with four coefficients of a million digits (x = 10^(10^6): derived in
 * tens of milliseconds, written in about a second).  Both are timed
 * first (each the fastest of two runs); with a budget between them the
 * scheme derives, and the weight's text, which took longer than the
 * budget, is NULL (FLINT writes it in one call: the clock is read when it
 * ends) */
static void test_api_weight_str_budget(void **state)
{
    (void)state;
    if (getenv("PC_VALGRIND")) /* a second of GMP is minutes there */
        skip();
    const char *text = "point A, B\nparam t\nx = 1e1000^1000\n"
                       "M = along(A, B, x*(t + t^2 + t^3 + t^4))\n";
    char *diag = NULL;
    pc_options big = {.max_seconds = 600};
    double derive = 1e9, print = 1e9;
    for (int k = 0; k < 2; k++) {
        double t0 = now_s();
        pc_scheme *s =
            pc_scheme_parse_opts("w.pcs", text, strlen(text), &big, &diag);
        double t1 = now_s();
        assert_non_null(s);
        char *w = pc_weight_str(s, 0, 1);
        derive = fmin(derive, t1 - t0);
        print = fmin(print, now_s() - t1);
        assert_non_null(w); /* 10^(10^6)*t^4 + ... + 10^(10^6)*t */
        assert_int_equal(strlen(w), 4 * 1000001 + strlen("*t^4+*t^3+*t^2+*t"));
        assert_true(strncmp(w, "10000", 5) == 0);
        assert_string_equal(w + strlen(w) - 4, "00*t");
        free(w);
        pc_scheme_free(s);
    }
    if (print < 8 * derive)
        skip(); /* too close to tell apart on this machine */
    pc_options o = {.max_seconds = sqrt(derive * print)};
    pc_scheme *s = pc_scheme_parse_opts("w.pcs", text, strlen(text), &o, &diag);
    if (!s)
        fail_msg("%s", diag);
    assert_null(pc_weight_str(s, 0, 1));
    assert_null(pc_weight_str(s, 0, 0));
    pc_scheme_free(s);
}

static int teardown_group(void **state)
{
    (void)state;
    pc_cleanup();
    return 0;
}

int main(void)
{
    /* process-wide and first: the counted allocators, no budget */
    pc_use_memory_budget(0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_api_names_and_counts),
        cmocka_unit_test(test_api_weight_str),
        cmocka_unit_test(test_api_load),
        cmocka_unit_test(test_api_parse_errors),
        cmocka_unit_test(test_api_compile_and_eval),
        cmocka_unit_test(test_api_eval_statuses),
        cmocka_unit_test(test_api_eval_einval),
        cmocka_unit_test(test_api_compile_errors),
        cmocka_unit_test(test_api_emit_c),
        cmocka_unit_test(test_api_options),
        cmocka_unit_test(test_api_thread_cleanup),
        cmocka_unit_test(test_api_budget_after_derive),
        cmocka_unit_test(test_api_budget_inside_meet),
        cmocka_unit_test(test_api_budget_after_last_check),
        cmocka_unit_test(test_api_weight_str_budget),
    };
    return cmocka_run_group_tests(tests, NULL, teardown_group);
}
