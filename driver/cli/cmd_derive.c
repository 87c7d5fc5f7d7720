/*
 * cmd_derive.c - `pointcalc derive FILE [--format text|latex|json]
 * [--origin POINT] [--steps] [--knots]`: the exact equations of the outputs
 * (format.h), after every step of the derivation with --steps (steps.h),
 * followed by the smoothness at every knot with --knots (knots_print.h;
 * JSON always carries the knots).
 */
#include "driver/cli/cli.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "compiler/print/format.h"
#include "compiler/print/knots_print.h"
#include "compiler/print/steps.h"
#include "driver/cli/args.h"

typedef struct DeriveArgs {
    FormatStyle style;
    const char *origin; // a base point's name, or NULL
    int steps;          // --steps
    int knots;          // --knots
    int standalone;     // --standalone (LaTeX)
    int width;          // --width N (LaTeX), 0: the default
    const char *usage;
} DeriveArgs;

/* --format text|latex|json, --origin POINT, --steps, --knots */
static int derive_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    DeriveArgs *a = ctx;
    if (strcmp(argv[i], "--steps") == 0) {
        a->steps = 1;
        return 1;
    }
    if (strcmp(argv[i], "--knots") == 0) {
        a->knots = 1;
        return 1;
    }
    if (strcmp(argv[i], "--standalone") == 0) {
        a->standalone = 1;
        return 1;
    }
    const char *v = args_value(argc, argv, i);
    if (!v)
        return 0;
    if (strcmp(argv[i], "--width") == 0) {
        char *end;
        long w = strtol(v, &end, 10);
        if (end == v || *end || w < 20 || w > 10000) {
            args_usage_error(err, a->usage,
                             "--width '%s': expected a number of columns "
                             "from 20 to 10000",
                             v);
            return -1;
        }
        a->width = (int)w;
        return 2;
    }
    if (strcmp(argv[i], "--origin") == 0) {
        a->origin = v;
        return 2;
    }
    if (strcmp(argv[i], "--format") != 0)
        return 0;
    if (strcmp(v, "text") == 0)
        a->style = FMT_TEXT;
    else if (strcmp(v, "latex") == 0)
        a->style = FMT_LATEX;
    else if (strcmp(v, "json") == 0)
        a->style = FMT_JSON;
    else {
        args_usage_error(err, a->usage,
                         "unknown format '%s'; expected text, latex or json",
                         v);
        return -1;
    }
    return 2;
}

/* The result is made in memory and written in one piece: a budget that
 * runs out while printing (the handler exits 1, "ran out while printing
 * the result") leaves nothing on stdout, as docs/language.md promises for
 * every exit 1. */
static void print_result(const DeriveArgs *a, const Derived *d, slong origin,
                         FILE *out)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&text, &len);
    if (a->steps && a->style == FMT_JSON) /* the object with "steps" */
        steps_print(m, d, a->style, origin);
    else {
        if (a->standalone)
            format_latex_begin(m, d);
        if (a->steps) { /* the steps, a blank line, then the outputs */
            steps_print(m, d, a->style, origin);
            fputs("\n", m);
        }
        format_derived_width(m, d, a->style, origin, a->width);
        if (a->standalone)
            format_latex_end(m);
        if (a->knots && a->style == FMT_TEXT) { /* a blank line, the knots */
            fputs("\n", m);
            knots_print(m, d);
        }
    }
    pc_xclose_memstream(m);
    fwrite(text, 1, len, out);
    pc_free(text);
}

int cli_derive(int argc, char **argv, FILE *out, FILE *err)
{
    DeriveArgs a = {FMT_TEXT, NULL, 0, 0, 0, 0, help_usage("derive")};
    BudgetOptions bo;
    const char *file;
    int rc =
        args_parse(argc, argv, a.usage, &bo, &file, derive_option, &a, err);
    if (rc)
        return rc;
    if ((a.standalone || a.width) && a.style != FMT_LATEX)
        return args_usage_error(err, a.usage,
                                "%s is for LaTeX: expected --format latex",
                                a.standalone ? "--standalone" : "--width");
    if (a.knots && a.style == FMT_LATEX)
        return args_usage_error(err, a.usage,
                                "--knots prints text: use --format text, "
                                "or --format json (which always carries "
                                "the knots)");
    /* a failed check is an error of the scheme: exit 1 and nothing on
     * stdout, in every format (contract section 4) */
    Derived *d = cli_derive_file_steps(file, &bo, a.steps ? CLI_KEEP_STEPS : 0,
                                       err, &rc);
    if (!d)
        return rc;
    slong origin = a.origin ? derived_find_point(d, a.origin) : -1;
    if (a.origin && origin < 0)
        rc = args_usage_error(err, a.usage,
                              "--origin '%s' is not a base point of the "
                              "scheme",
                              a.origin);
    else
        print_result(&a, d, origin, out);
    budget_disarm(); /* printed within the budget of the derivation */
    derived_free(d);
    return rc;
}
