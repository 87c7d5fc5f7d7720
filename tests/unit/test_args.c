/*
 * test_args.c - the command line's option parsing, in-process:
 * driver/cli/budget.h's budget_parse_option (--max-seconds, --max-memory
 * with K, M, G, -v, -D n=3 and -Dn=3, and every bad value with its exact
 * message), driver/cli/args.h's args_parse (defaults, a command's own
 * options through the callback, unknown options, one FILE), the NameList
 * of --output and args_select_outputs, eval's EvalArgs (--at, --set,
 * --param, --output as typed) and eval_setup against the Plan of a small
 * scheme: the points' coordinates, consts, the grid of params and swept
 * consts (last varying fastest, swept consts slowest, docs/eval.md), and
 * every usage error with its exact text ("pointcalc: MESSAGE" then the
 * usage synopsis).
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

#include <flint/flint.h>

#include "codegen/lower.h"
#include "compiler/derive.h"
#include "driver/cli/args.h"
#include "driver/cli/budget.h"
#include "runtime/eval.h"

#define USAGE "usage: cmd FILE [options]\n"

/* a stream to capture err, and its text */
typedef struct Capture {
    FILE *f;
    char *text;
    size_t len;
} Capture;

static void cap_open(Capture *c)
{
    c->text = NULL;
    c->len = 0;
    c->f = open_memstream(&c->text, &c->len);
    assert_non_null(c->f);
}

/* closes the stream; the text stays until cap_free */
static const char *cap_close(Capture *c)
{
    fclose(c->f);
    c->f = NULL;
    return c->text;
}

static void cap_free(Capture *c)
{
    free(c->text);
    c->text = NULL;
}

/* ---- budget_parse_option ---------------------------------------------- */

/* budget_parse_option at argv[i] of argv {"cmd", a, b}: returns its result;
 * *msg receives what it wrote (free it) */
static int budget_opt(BudgetOptions *b, const char *a, const char *v,
                      char **msg)
{
    char *argv[4] = {(char *)"cmd", (char *)a, (char *)v, NULL};
    int argc = v ? 3 : 2;
    Capture c;
    cap_open(&c);
    int r = budget_parse_option(b, argc, argv, 1, c.f);
    cap_close(&c);
    *msg = c.text;
    return r;
}

static void test_budget_option_values(void **state)
{
    (void)state;
    BudgetOptions b;
    budget_options_default(&b);
    assert_true(b.max_seconds == 60);
    assert_true(b.max_memory == (size_t)2 << 30);
    assert_int_equal(b.verbose, 0);
    assert_int_equal(b.ndefines, 0);
    char *m;
    assert_int_equal(budget_opt(&b, "--max-seconds", "0.5", &m), 2);
    assert_true(b.max_seconds == 0.5);
    assert_string_equal(m, "");
    free(m);
    assert_int_equal(budget_opt(&b, "--max-seconds", "0", &m), 2);
    assert_true(b.max_seconds == 0);
    free(m);
    static const struct {
        const char *text;
        size_t bytes;
    } sizes[] = {
        {"0", 0},
        {"100", 100},
        {"1.5K", 1536},
        {"10k", 10240},
        {"3m", 3 << 20},
        {"64M", 64 << 20},
        {"2G", (size_t)2 << 30},
        {"0.5g", 1 << 29},
    };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        assert_int_equal(budget_opt(&b, "--max-memory", sizes[i].text, &m), 2);
        assert_true(b.max_memory == sizes[i].bytes);
        assert_string_equal(m, "");
        free(m);
    }
    assert_int_equal(budget_opt(&b, "-v", NULL, &m), 1);
    assert_int_equal(b.verbose, 1);
    free(m);
    b.verbose = 0;
    assert_int_equal(budget_opt(&b, "--verbose", "x.pcs", &m), 1);
    assert_int_equal(b.verbose, 1);
    free(m);
    /* -D n=3 takes two arguments, -Dn=3 one; the strings are argv's */
    char *argv[] = {(char *)"cmd", (char *)"-D", (char *)"n=3",
                    (char *)"-Dm=-4", NULL};
    Capture c;
    cap_open(&c);
    b.ndefines = 0;
    assert_int_equal(budget_parse_option(&b, 4, argv, 1, c.f), 2);
    assert_int_equal(budget_parse_option(&b, 4, argv, 3, c.f), 1);
    assert_string_equal(cap_close(&c), "");
    cap_free(&c);
    assert_int_equal(b.ndefines, 2);
    assert_ptr_equal(b.defines[0], argv[2]);
    assert_ptr_equal(b.defines[1], argv[3] + 2);
    assert_string_equal(b.defines[1], "m=-4");
    /* not a budget option: 0, nothing written */
    assert_int_equal(budget_opt(&b, "--at", "A=1", &m), 0);
    assert_string_equal(m, "");
    free(m);
    assert_int_equal(budget_opt(&b, "x.pcs", NULL, &m), 0);
    free(m);
}

static void bad_budget(const char *a, const char *v, const char *expect)
{
    BudgetOptions b;
    budget_options_default(&b);
    char *m;
    assert_int_equal(budget_opt(&b, a, v, &m), -1);
    assert_string_equal(m, expect);
    free(m);
    /* nothing was set */
    assert_true(b.max_seconds == 60);
    assert_true(b.max_memory == (size_t)2 << 30);
    assert_int_equal(b.ndefines, 0);
}

static void test_budget_option_errors(void **state)
{
    (void)state;
    bad_budget("--max-seconds", NULL,
               "pointcalc: --max-seconds needs a value\n");
    bad_budget("--max-memory", NULL, "pointcalc: --max-memory needs a value\n");
    bad_budget("--max-seconds", "abc",
               "pointcalc: --max-seconds 'abc': expected a number of seconds "
               "from 0 (no budget) up\n");
    bad_budget("--max-seconds", "-1",
               "pointcalc: --max-seconds '-1': expected a number of seconds "
               "from 0 (no budget) up\n");
    bad_budget("--max-seconds", "nan",
               "pointcalc: --max-seconds 'nan': expected a number of seconds "
               "from 0 (no budget) up\n");
    bad_budget("--max-seconds", "2e9",
               "pointcalc: --max-seconds '2e9': expected a number of seconds "
               "from 0 (no budget) up\n");
    bad_budget("--max-seconds", "5s",
               "pointcalc: --max-seconds '5s': expected a number of seconds, "
               "e.g. 60 or 0.5 (0: no budget)\n");
    bad_budget("--max-memory", "-1",
               "pointcalc: --max-memory '-1': expected a number of bytes from "
               "0 (no budget) up\n");
    bad_budget("--max-memory", "",
               "pointcalc: --max-memory '': expected a number of bytes from "
               "0 (no budget) up\n");
    bad_budget("--max-memory", "5T",
               "pointcalc: --max-memory '5T': expected a size in bytes, or "
               "with K, M or G (KiB, MiB, GiB), e.g. 2G (0: no budget)\n");
    bad_budget("--max-memory", "2GB",
               "pointcalc: --max-memory '2GB': expected a size in bytes, or "
               "with K, M or G (KiB, MiB, GiB), e.g. 2G (0: no budget)\n");
    /* 1e15 bytes is the most: 1e6 G is beyond */
    bad_budget("--max-memory", "1e6G",
               "pointcalc: --max-memory '1e6G': expected a size in bytes, or "
               "with K, M or G (KiB, MiB, GiB), e.g. 2G (0: no budget)\n");
    bad_budget("-D", NULL, "pointcalc: -D needs NAME=INTEGER\n");
    static const char *const bad_defines[] = {
        "3=4", "n", "n=", "n=x", "n=1.5", "=3", "n-1=2", "n=2000000000000",
    };
    for (size_t i = 0; i < sizeof bad_defines / sizeof bad_defines[0]; i++) {
        char expect[200];
        snprintf(expect, sizeof expect,
                 "pointcalc: -D '%s': expected NAME=INTEGER, e.g. -D n=24 (a "
                 "whole number below 2^40 in magnitude)\n",
                 bad_defines[i]);
        bad_budget("-D", bad_defines[i], expect);
        char joined[64];
        snprintf(joined, sizeof joined, "-D%s", bad_defines[i]);
        bad_budget(joined, NULL, expect);
    }
    /* 2^40 - 1 is allowed, and a sign */
    BudgetOptions b;
    budget_options_default(&b);
    char *m;
    assert_int_equal(budget_opt(&b, "-D", "n=1099511627775", &m), 2);
    free(m);
    assert_int_equal(budget_opt(&b, "-Dn_2=-7", NULL, &m), 1);
    free(m);
    assert_int_equal(b.ndefines, 2);
    /* at most BUDGET_MAX_DEFINES */
    budget_options_default(&b);
    char *argv[] = {(char *)"cmd", (char *)"-Dn=1", NULL};
    Capture c;
    cap_open(&c);
    for (int i = 0; i < BUDGET_MAX_DEFINES; i++)
        assert_int_equal(budget_parse_option(&b, 2, argv, 1, c.f), 1);
    assert_int_equal(budget_parse_option(&b, 2, argv, 1, c.f), -1);
    assert_string_equal(cap_close(&c), "pointcalc: more than 64 -D options\n");
    cap_free(&c);
    assert_int_equal(b.ndefines, BUDGET_MAX_DEFINES);
}

/* ---- args_parse -------------------------------------------------------- */

/* a command's own option: --pair X Y (three arguments), --fail (an error
 * it reports) */
typedef struct PairCtx {
    const char *x, *y;
    int calls;
} PairCtx;

static int pair_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    PairCtx *c = ctx;
    c->calls++;
    if (strcmp(argv[i], "--fail") == 0) {
        fputs("pointcalc: --fail failed\n", err);
        return -1;
    }
    if (strcmp(argv[i], "--pair") != 0 || i + 2 >= argc)
        return 0;
    c->x = argv[i + 1];
    c->y = argv[i + 2];
    return 3;
}

/* args_parse on the NULL-terminated argv; *msg = err's text (free it) */
static int parse(char **argv, BudgetOptions *b, const char **file,
                 ArgsOption *opt, void *ctx, char **msg)
{
    int argc = 0;
    while (argv[argc])
        argc++;
    Capture c;
    cap_open(&c);
    int rc = args_parse(argc, argv, USAGE, b, file, opt, ctx, c.f);
    cap_close(&c);
    *msg = c.text;
    return rc;
}

static void test_args_parse_options_and_file(void **state)
{
    (void)state;
    char *argv[] = {(char *)"derive",
                    (char *)"x.pcs",
                    (char *)"--max-seconds",
                    (char *)"5",
                    (char *)"--max-memory",
                    (char *)"64M",
                    (char *)"-v",
                    (char *)"-D",
                    (char *)"n=3",
                    (char *)"-Dm=4",
                    (char *)"--pair",
                    (char *)"a",
                    (char *)"b",
                    NULL};
    BudgetOptions b;
    memset(&b, 0x55, sizeof b); /* the defaults are set first */
    const char *file = NULL;
    PairCtx pc = {NULL, NULL, 0};
    char *m;
    assert_int_equal(parse(argv, &b, &file, pair_option, &pc, &m), 0);
    assert_string_equal(m, "");
    free(m);
    assert_ptr_equal(file, argv[1]);
    assert_true(b.max_seconds == 5);
    assert_true(b.max_memory == (size_t)64 << 20);
    assert_int_equal(b.verbose, 1);
    assert_int_equal(b.ndefines, 2);
    assert_string_equal(b.defines[0], "n=3");
    assert_string_equal(b.defines[1], "m=4");
    assert_ptr_equal(pc.x, argv[11]);
    assert_ptr_equal(pc.y, argv[12]);
    /* the callback sees only what the budget options leave: x.pcs and
     * --pair */
    assert_int_equal(pc.calls, 2);

    /* defaults; "-" is a FILE (standard input), not an option */
    char *argv2[] = {(char *)"eval", (char *)"-", NULL};
    memset(&b, 0x55, sizeof b);
    assert_int_equal(parse(argv2, &b, &file, NULL, NULL, &m), 0);
    free(m);
    assert_string_equal(file, "-");
    assert_true(b.max_seconds == 60);
    assert_true(b.max_memory == (size_t)2 << 30);
    assert_int_equal(b.verbose, 0);
    assert_int_equal(b.ndefines, 0);
}

static void parse_error(char **argv, ArgsOption *opt, const char *expect)
{
    BudgetOptions b;
    const char *file = NULL;
    PairCtx pc = {NULL, NULL, 0};
    char *m;
    assert_int_equal(parse(argv, &b, &file, opt, &pc, &m), 2);
    assert_string_equal(m, expect);
    free(m);
}

static void test_args_parse_errors(void **state)
{
    (void)state;
    char *unknown[] = {(char *)"derive", (char *)"x.pcs", (char *)"--bogus",
                       NULL};
    parse_error(unknown, pair_option,
                "pointcalc: unknown or incomplete option '--bogus'\n" USAGE);
    /* --pair without its two values is not taken: incomplete */
    char *incomplete[] = {(char *)"derive", (char *)"x.pcs", (char *)"--pair",
                          (char *)"a", NULL};
    parse_error(incomplete, pair_option,
                "pointcalc: unknown or incomplete option '--pair'\n" USAGE);
    char *two[] = {(char *)"eval", (char *)"x.pcs", (char *)"y.pcs", NULL};
    parse_error(two, NULL,
                "pointcalc: eval takes one FILE, found 'y.pcs'\n" USAGE);
    char *none[] = {(char *)"plot", (char *)"-v", NULL};
    parse_error(none, NULL, "pointcalc: plot needs a scheme FILE\n" USAGE);
    /* a budget error is reported by budget_parse_option alone (no usage) */
    char *badsec[] = {(char *)"derive", (char *)"x.pcs",
                      (char *)"--max-seconds", (char *)"x", NULL};
    parse_error(badsec, NULL,
                "pointcalc: --max-seconds 'x': expected a number of seconds "
                "from 0 (no budget) up\n");
    char *nosec[] = {(char *)"derive", (char *)"x.pcs", (char *)"--max-seconds",
                     NULL};
    parse_error(nosec, NULL, "pointcalc: --max-seconds needs a value\n");
    /* the command's own error: its message only */
    char *fail[] = {(char *)"derive", (char *)"--fail", (char *)"x.pcs", NULL};
    parse_error(fail, pair_option, "pointcalc: --fail failed\n");
}

static void test_args_usage_error_and_value(void **state)
{
    (void)state;
    Capture c;
    cap_open(&c);
    assert_int_equal(args_usage_error(c.f, USAGE, "%s has %d", "x", 3), 2);
    assert_string_equal(cap_close(&c), "pointcalc: x has 3\n" USAGE);
    cap_free(&c);
    char *argv[] = {(char *)"cmd", (char *)"--x", (char *)"v", NULL};
    assert_ptr_equal(args_value(3, argv, 1), argv[2]);
    assert_null(args_value(3, argv, 2));
    char buf[64];
    char *names[] = {(char *)"A", (char *)"B", (char *)"C"};
    assert_string_equal(args_name_list(names, 3, buf, sizeof buf), "A, B, C");
    assert_string_equal(args_name_list(names, 1, buf, sizeof buf), "A");
    assert_string_equal(args_name_list(names, 0, buf, sizeof buf), "none");
    /* truncated to the buffer */
    char small[5];
    char *long_names[] = {(char *)"Alpha", (char *)"Beta"};
    assert_string_equal(args_name_list(long_names, 2, small, sizeof small),
                        "Alph");
}

/* ---- NameList, --output ------------------------------------------------ */

static const char ev_text[] = "scheme ev\n"
                              "point A, B, C\n"
                              "param t, u\n"
                              "const k, h\n"
                              "M = along(A, B, t)\n"
                              "N = divide(A, C, k)\n"
                              "s = t*u\n"
                              "Z = B - B\n"
                              "x = coord(A, 3)\n"
                              "output M, N, s, Z, x\n";

static Plan *ev_plan(void)
{
    Derived *d =
        derive_source("ev.pcs", ev_text, strlen(ev_text), stderr, NULL);
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    derived_free(d);
    assert_non_null(p);
    assert_int_equal(p->noutputs, 5);
    return p;
}

static void test_args_names_and_select_outputs(void **state)
{
    (void)state;
    NameList l = {NULL, 0};
    assert_int_equal(args_names_add(&l, "s,M"), 0);
    assert_int_equal(args_names_add(&l, "Z"), 0);
    assert_int_equal(l.n, 3);
    assert_string_equal(l.v[0], "s");
    assert_string_equal(l.v[1], "M");
    assert_string_equal(l.v[2], "Z");
    Plan *p = ev_plan();
    int sel[5];
    Capture c;
    cap_open(&c);
    assert_int_equal(args_select_outputs(sel, &l, p, USAGE, c.f), 3);
    assert_int_equal(sel[0], 2);
    assert_int_equal(sel[1], 0);
    assert_int_equal(sel[2], 3);
    args_names_clear(&l);
    assert_null(l.v);
    assert_int_equal(l.n, 0);
    /* none: every output in order */
    assert_int_equal(args_select_outputs(sel, &l, p, USAGE, c.f), 5);
    for (int o = 0; o < 5; o++)
        assert_int_equal(sel[o], o);
    assert_string_equal(cap_close(&c), "");
    cap_free(&c);

    /* an unknown output, one given twice */
    assert_int_equal(args_names_add(&l, "M,Q"), 0);
    cap_open(&c);
    assert_int_equal(args_select_outputs(sel, &l, p, USAGE, c.f), -1);
    assert_string_equal(cap_close(&c),
                        "pointcalc: --output 'Q' is not an output of the "
                        "scheme (outputs: M, N, s, Z, x)\n" USAGE);
    cap_free(&c);
    args_names_clear(&l);
    assert_int_equal(args_names_add(&l, "N"), 0);
    assert_int_equal(args_names_add(&l, "x,N"), 0);
    cap_open(&c);
    assert_int_equal(args_select_outputs(sel, &l, p, USAGE, c.f), -1);
    assert_string_equal(cap_close(&c),
                        "pointcalc: --output 'N' is given twice\n" USAGE);
    cap_free(&c);
    args_names_clear(&l);

    /* empty names: -1 (what came before stays in the list) */
    assert_int_equal(args_names_add(&l, ""), -1);
    assert_int_equal(args_names_add(&l, ",M"), -1);
    assert_int_equal(args_names_add(&l, "M,"), -1);
    assert_int_equal(args_names_add(&l, "M,,N"), -1);
    args_names_clear(&l);
    plan_free(p);
}

/* ---- eval's options ---------------------------------------------------- */

typedef struct EvalCtx {
    EvalArgs a;
} EvalCtx;

static int eval_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    return eval_args_option(&((EvalCtx *)ctx)->a, argc, argv, i, USAGE, err);
}

static void test_eval_args_option(void **state)
{
    (void)state;
    char *argv[] = {(char *)"eval",    (char *)"ev.pcs",    (char *)"--at",
                    (char *)"A=1,2",   (char *)"--set",     (char *)"k=0.5",
                    (char *)"--param", (char *)"t=0:1:5",   (char *)"--at",
                    (char *)"B=3,4",   (char *)"--output",  (char *)"M,N",
                    (char *)"--param", (char *)"u=0,0.5,1", NULL};
    EvalCtx c;
    eval_args_init(&c.a);
    BudgetOptions b;
    const char *file;
    char *m;
    assert_int_equal(parse(argv, &b, &file, eval_option, &c, &m), 0);
    assert_string_equal(m, "");
    free(m);
    assert_string_equal(file, "ev.pcs");
    assert_int_equal(c.a.nat, 2);
    assert_string_equal(c.a.at[0].name, "A");
    assert_ptr_equal(c.a.at[0].text, argv[3] + 2); /* borrowed */
    assert_string_equal(c.a.at[1].name, "B");
    assert_string_equal(c.a.at[1].text, "3,4");
    assert_int_equal(c.a.nset, 1);
    assert_string_equal(c.a.set[0].name, "k");
    assert_string_equal(c.a.set[0].text, "0.5");
    assert_int_equal(c.a.nparam, 2);
    assert_string_equal(c.a.param[0].name, "t");
    assert_string_equal(c.a.param[0].text, "0:1:5");
    assert_string_equal(c.a.param[1].name, "u");
    assert_string_equal(c.a.param[1].text, "0,0.5,1");
    assert_int_equal(c.a.outputs.n, 2);
    assert_string_equal(c.a.outputs.v[1], "N");
    eval_args_clear(&c.a);
    assert_int_equal(c.a.nat, 0);
    assert_null(c.a.at);

    /* what eval_args_option itself returns */
    Capture cap;
    cap_open(&cap);
    char *o1[] = {(char *)"eval", (char *)"--set", (char *)"h=", NULL};
    assert_int_equal(eval_args_option(&c.a, 3, o1, 1, USAGE, cap.f), 2);
    assert_string_equal(c.a.set[0].text, ""); /* checked later */
    assert_int_equal(eval_args_option(&c.a, 2, o1, 1, USAGE, cap.f), 0);
    char *o2[] = {(char *)"eval", (char *)"--foo", (char *)"a=1", NULL};
    assert_int_equal(eval_args_option(&c.a, 3, o2, 1, USAGE, cap.f), 0);
    assert_string_equal(cap_close(&cap), "");
    cap_free(&cap);
    eval_args_clear(&c.a);

    /* malformed NAME=VALUE, empty output names */
    static const struct {
        const char *opt, *val, *expect;
    } bad[] = {
        {"--at", "A", "pointcalc: --at expects NAME=VALUE, found 'A'\n" USAGE},
        {"--set", "=3",
         "pointcalc: --set expects NAME=VALUE, found '=3'\n" USAGE},
        {"--param", "t",
         "pointcalc: --param expects NAME=VALUE, found 't'\n" USAGE},
        {"--output", ",",
         "pointcalc: --output ',': expected output names separated by "
         "commas\n" USAGE},
        {"--output", "M,",
         "pointcalc: --output 'M,': expected output names separated by "
         "commas\n" USAGE},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char *av[] = {(char *)"eval", (char *)bad[i].opt, (char *)bad[i].val,
                      NULL};
        cap_open(&cap);
        assert_int_equal(eval_args_option(&c.a, 3, av, 1, USAGE, cap.f), -1);
        assert_string_equal(cap_close(&cap), bad[i].expect);
        cap_free(&cap);
        eval_args_clear(&c.a);
    }
    /* through args_parse: --at without a value is incomplete */
    char *inc[] = {(char *)"eval", (char *)"ev.pcs", (char *)"--at", NULL};
    assert_int_equal(parse(inc, &b, &file, eval_option, &c, &m), 2);
    assert_string_equal(
        m, "pointcalc: unknown or incomplete option '--at'\n" USAGE);
    free(m);
    eval_args_clear(&c.a);
}

/* eval_setup of `eval ev.pcs ARGS...` (NULL-terminated) against the ev
 * Plan; *msg = err's text (free it) */
static int setup(const Plan *p, EvalSetup *s, const char *const *args,
                 char **msg)
{
    char *argv[40];
    int argc = 0;
    argv[argc++] = (char *)"eval";
    argv[argc++] = (char *)"ev.pcs";
    for (int i = 0; args[i]; i++)
        argv[argc++] = (char *)args[i];
    argv[argc] = NULL;
    EvalCtx c;
    eval_args_init(&c.a);
    BudgetOptions b;
    const char *file;
    char *m;
    int rc = parse(argv, &b, &file, eval_option, &c, &m);
    assert_int_equal(rc, 0);
    free(m);
    Capture cap;
    cap_open(&cap);
    rc = eval_setup(s, &c.a, p, USAGE, cap.f);
    *msg = (char *)cap_close(&cap);
    eval_args_clear(&c.a); /* the setup keeps nothing of it */
    return rc;
}

static void test_eval_setup_grid(void **state)
{
    (void)state;
    Plan *p = ev_plan();
    EvalSetup s;
    char *m;
    const char *const args[] = {"--output", "M,N,s",   "--at",    "A=0,0",
                                "--at",     "B=1,0",   "--at",    "C=0,1",
                                "--set",    "k=0.5",   "--param", "u=0,0.5,1",
                                "--param",  "t=0:1:5", NULL};
    assert_int_equal(setup(p, &s, args, &m), 0);
    assert_string_equal(m, "");
    free(m);
    assert_int_equal(s.nsel, 3);
    assert_int_equal(s.sel[0], 0);
    assert_int_equal(s.sel[1], 1);
    assert_int_equal(s.sel[2], 2);
    assert_int_equal(s.dim, 2);
    assert_int_equal(s.npoints, 3);
    assert_true(s.pt[1][0] == 1 && s.pt[1][1] == 0);
    assert_true(s.pt[2][0] == 0 && s.pt[2][1] == 1);
    assert_true(s.consts[0] == 0.5);
    assert_true(s.consts[1] == 0); /* h: not given, no output reads it */
    /* the axes in declaration order (t, then u), whatever the order given */
    assert_int_equal(s.naxes, 2);
    assert_int_equal(s.axes[0].param, 0);
    assert_int_equal(s.axes[0].cnst, -1);
    assert_int_equal(s.axes[1].param, 1);
    assert_true(s.rows == 15);
    /* the last param varies fastest: row 4 = t index 1, u index 1 */
    double params[2], consts[2] = {0.5, 0};
    eval_setup_row(&s, 4, params, consts);
    assert_true(params[0] == 0.25 && params[1] == 0.5);
    eval_setup_row(&s, 14, params, consts);
    assert_true(params[0] == 1 && params[1] == 1);
    eval_setup_row(&s, 0, params, consts);
    assert_true(params[0] == 0 && params[1] == 0);
    assert_true(eval_setup_run(&s, 4) == 11); /* nothing swept: to the end */
    /* row 7 (t = 0.5) through plan_eval: M = A/2 + B/2 = (0.5, 0) */
    eval_setup_row(&s, 7, params, consts);
    assert_true(params[0] == 0.5 && params[1] == 0.5);
    const double *pv[2] = {&params[0], &params[1]};
    double out[2];
    assert_int_equal(plan_eval(p, 0, 1, pv, s.consts,
                               (const double *const *)s.pt, s.dim, out, NULL),
                     0);
    assert_true(out[0] == 0.5 && out[1] == 0);
    eval_setup_clear(&s);
    assert_null(s.pt);
    assert_int_equal(s.naxes, 0);

    /* a swept const varies slowest, a const given once is no axis */
    const char *const swept[] = {
        "--output", "N",     "--at",  "A=0",   "--at", "C=1", "--param",
        "t=0,1",    "--set", "k=1,2", "--set", "h=3",  NULL};
    assert_int_equal(setup(p, &s, swept, &m), 0);
    free(m);
    assert_int_equal(s.dim, 1);
    assert_null(s.pt[1]); /* B: no selected output reads it */
    assert_int_equal(s.naxes, 2);
    assert_int_equal(s.axes[0].cnst, 0);
    assert_int_equal(s.axes[0].param, -1);
    assert_int_equal(s.axes[1].param, 0);
    assert_true(s.rows == 4);
    assert_true(s.consts[1] == 3);
    consts[0] = consts[1] = -1;
    eval_setup_row(&s, 2, params, consts);
    assert_true(consts[0] == 2 && params[0] == 0);
    assert_true(consts[1] == -1); /* not swept: left alone */
    eval_setup_row(&s, 1, params, consts);
    assert_true(consts[0] == 1 && params[0] == 1);
    assert_true(eval_setup_run(&s, 0) == 2);
    assert_true(eval_setup_run(&s, 1) == 1);
    assert_true(eval_setup_run(&s, 2) == 2);
    eval_setup_clear(&s);

    /* a range sweeps too: k = 0, 0.5, 1; no --param (N reads no param) */
    const char *const range[] = {"--output", "N",     "--at",    "A=0", "--at",
                                 "C=1",      "--set", "k=0:1:3", NULL};
    assert_int_equal(setup(p, &s, range, &m), 0);
    free(m);
    assert_true(s.rows == 3);
    eval_setup_row(&s, 1, params, consts);
    assert_true(consts[0] == 0.5);
    eval_setup_clear(&s);

    /* the zero vector with a dimension, and a coordinate the points have */
    const char *const zx[] = {"--output", "Z,x", "--at", "A=1,2,3", NULL};
    assert_int_equal(setup(p, &s, zx, &m), 0);
    free(m);
    assert_int_equal(s.dim, 3);
    assert_true(s.rows == 1); /* no axis: one row */
    eval_setup_clear(&s);
    plan_free(p);
}

static void setup_error(const Plan *p, const char *const *args, const char *msg)
{
    EvalSetup s;
    char *m;
    int rc = setup(p, &s, args, &m);
    if (rc != 2)
        fail_msg("rc %d, not 2, where '%s' was expected (%s)", rc, msg, m);
    char expect[600];
    snprintf(expect, sizeof expect, "pointcalc: %s\n%s", msg, USAGE);
    assert_string_equal(m, expect);
    free(m);
    eval_setup_clear(&s);
}

#define ARGS(...)                                                              \
    (const char *const[])                                                      \
    {                                                                          \
        __VA_ARGS__, NULL                                                      \
    }
/* every point, with the 3 coordinates x = coord(A, 3) needs */
#define PTS3 "--at", "A=0,0,0", "--at", "B=1,0,0", "--at", "C=0,1,0"

static void test_eval_setup_errors(void **state)
{
    (void)state;
    Plan *p = ev_plan();
    /* outputs */
    setup_error(p, ARGS("--output", "Q"),
                "--output 'Q' is not an output of the scheme (outputs: M, N, "
                "s, Z, x)");
    /* points */
    setup_error(p, ARGS("--output", "M", "--at", "A=0,0", "--param", "t=0"),
                "missing --at B=x,y,...: output M depends on base point B");
    setup_error(p, ARGS("--at", "A=0,0", "--at", "B=1,0,0"),
                "--at B has 3 coordinates but the points before it have 2: "
                "every point must have the same dimension");
    setup_error(p, ARGS("--at", "Z=1"),
                "--at Z: 'Z' is not a base point of the scheme (points: A, B, "
                "C)");
    setup_error(p, ARGS("--at", "A=0", "--at", "A=1"), "--at A given twice");
    setup_error(p, ARGS("--at", "A=1,x"),
                "--at A=1,x: malformed coordinates; expected numbers "
                "separated by commas");
    setup_error(p, ARGS("--at", "A=1,,2"),
                "--at A=1,,2: malformed coordinates; expected numbers "
                "separated by commas");
    setup_error(p, ARGS("--at", "A=inf"),
                "--at A=inf: malformed coordinates; expected numbers "
                "separated by commas");
    setup_error(p, ARGS("--output", "Z"),
                "output Z is the zero vector (it depends on no base point): "
                "give at least one --at to set the dimension");
    setup_error(p, ARGS("--output", "x"),
                "missing --at A=x,y,...: output x depends on base point A");
    setup_error(p, ARGS("--output", "x", "--at", "A=1,2"),
                "output x reads coordinate 3 of base point A (coord(A, 3)), "
                "but the points have 2: give every --at point at least 3 "
                "coordinates");
    /* consts */
    setup_error(p, ARGS(PTS3, "--set", "t=1"),
                "--set t: 't' is a param; give it with --param t=SPEC");
    setup_error(p, ARGS(PTS3, "--set", "z=1"),
                "--set z: 'z' is not a const of the scheme (consts: k, h)");
    setup_error(p, ARGS(PTS3, "--set", "k=1", "--set", "k=2"),
                "--set k given twice");
    setup_error(p, ARGS(PTS3, "--set", "k=abc"),
                "--set k=abc: malformed number");
    setup_error(p, ARGS(PTS3, "--set", "k="), "--set k=: malformed number");
    setup_error(p, ARGS(PTS3, "--set", "k=1:2"),
                "--set k=1:2: malformed range '1:2': expected lo:hi:count");
    /* params */
    setup_error(p, ARGS(PTS3, "--set", "k=1", "--param", "k=1"),
                "--param k: 'k' is a const; give it with --set k=VALUE");
    setup_error(p, ARGS(PTS3, "--param", "z=1"),
                "--param z: 'z' is not a param of the scheme (params: t, u)");
    setup_error(p, ARGS(PTS3, "--param", "t=0", "--param", "t=1"),
                "--param t given twice");
    setup_error(p, ARGS(PTS3, "--param", "t=0:1:0"),
                "--param t=0:1:0: malformed range '0:1:0': count must be a "
                "positive integer");
    setup_error(p, ARGS(PTS3, "--param", "t=0:1:1"),
                "--param t=0:1:1: range '0:1:1' has count 1 but lo != hi: "
                "both ends are included, so count must be at least 2");
    setup_error(p, ARGS(PTS3, "--param", "t=1,,2"),
                "--param t=1,,2: malformed value list '1,,2': expected a "
                "number, a list 0,0.25,1 or lo:hi:count");
    setup_error(p, ARGS(PTS3, "--param", "t=a:1:3"),
                "--param t=a:1:3: malformed range 'a:1:3': lo and hi must be "
                "numbers");
    /* missing inputs: consts first; only what the selected outputs read */
    /* every selected output's inputs are required, not only the last
     * one's (used_inputs once asked plan_live, which clears its array,
     * once per output and so kept only the last; eval then computed with
     * k = 0, u = 0 and exited 0) */
    setup_error(p, ARGS(PTS3, "--param", "t=0"),
                "missing --set k=VALUE"); // all outputs: x is last
    setup_error(p, ARGS("--output", "N,M", PTS3, "--param", "t=0"),
                "missing --set k=VALUE"); // N is not last
    setup_error(p, ARGS("--output", "s,M", PTS3, "--param", "t=0"),
                "missing --param u=SPEC");
    setup_error(p, ARGS("--output", "M,N", PTS3, "--param", "t=0"),
                "missing --set k=VALUE");
    setup_error(p, ARGS("--output", "N", "--at", "A=0", "--at", "C=1"),
                "missing --set k=VALUE");
    setup_error(p, ARGS("--output", "M", "--at", "A=0", "--at", "B=1"),
                "missing --param t=SPEC");
    setup_error(p, ARGS("--output", "s", "--param", "t=0"),
                "missing --param u=SPEC");
    /* a grid beyond SIZE_MAX / 2 rows */
    setup_error(p,
                ARGS("--output", "s", "--param", "t=0:1:10000000000", "--param",
                     "u=0:1:10000000000"),
                "the grid of samples is too large");
    plan_free(p);
}

static int teardown_group(void **state)
{
    (void)state;
    flint_cleanup_master();
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_budget_option_values),
        cmocka_unit_test(test_budget_option_errors),
        cmocka_unit_test(test_args_parse_options_and_file),
        cmocka_unit_test(test_args_parse_errors),
        cmocka_unit_test(test_args_usage_error_and_value),
        cmocka_unit_test(test_args_names_and_select_outputs),
        cmocka_unit_test(test_eval_args_option),
        cmocka_unit_test(test_eval_setup_grid),
        cmocka_unit_test(test_eval_setup_errors),
    };
    return cmocka_run_group_tests(tests, NULL, teardown_group);
}
