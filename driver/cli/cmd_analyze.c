/*
 * cmd_analyze.c - `pointcalc analyze FILE [--output NAME[,NAME...]]
 * [--format text|json]`: what each output curve is, found exactly from its
 * derived equation (compiler/analyze/analyze.h, docs/analyze.md): its
 * ends, degree and order, poles, stop points, inflections, the base points
 * it passes through, the implicit equation of a plane curve, and the
 * poles of every definition.
 */
#include "driver/cli/cli.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "compiler/analyze/analyze.h"
#include "driver/cli/args.h"

typedef struct AnalyzeArgs {
    int json;         // --format json
    NameList outputs; // --output
    const char *usage;
} AnalyzeArgs;

/* --format text|json, --output NAMES */
static int analyze_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    AnalyzeArgs *a = ctx;
    const char *v = args_value(argc, argv, i);
    if (!v)
        return 0;
    if (strcmp(argv[i], "--output") == 0) {
        if (args_names_add(&a->outputs, v) < 0) {
            args_usage_error(err, a->usage, "--output '%s': an empty name", v);
            return -1;
        }
        return 2;
    }
    if (strcmp(argv[i], "--format") != 0)
        return 0;
    if (strcmp(v, "text") == 0)
        a->json = 0;
    else if (strcmp(v, "json") == 0)
        a->json = 1;
    else {
        args_usage_error(err, a->usage,
                         "unknown format '%s'; expected text or json", v);
        return -1;
    }
    return 2;
}

/* --output's names as indices of d's outputs into sel; the count, or -1
 * after a usage error */
static int select_outputs(int *sel, const AnalyzeArgs *a, const Derived *d,
                          FILE *err)
{
    int n = 0;
    if (a->outputs.n == 0)
        for (slong o = 0; o < d->noutputs; o++)
            sel[n++] = (int)o;
    for (int i = 0; i < a->outputs.n; i++) {
        slong o = derived_find_output(d, a->outputs.v[i]);
        if (o < 0) {
            args_usage_error(err, a->usage,
                             "--output '%s' is not an output of the scheme",
                             a->outputs.v[i]);
            return -1;
        }
        for (int j = 0; j < n; j++)
            if (sel[j] == o) {
                args_usage_error(err, a->usage, "--output '%s' is given twice",
                                 a->outputs.v[i]);
                return -1;
            }
        sel[n++] = (int)o;
    }
    return n;
}

int cli_analyze(int argc, char **argv, FILE *out, FILE *err)
{
    AnalyzeArgs a = {0, {NULL, 0}, help_usage("analyze")};
    BudgetOptions bo;
    const char *file;
    int rc =
        args_parse(argc, argv, a.usage, &bo, &file, analyze_option, &a, err);
    if (rc) {
        args_names_clear(&a.outputs);
        return rc;
    }
    Derived *d = cli_derive_file_steps(file, &bo, 1, err, &rc);
    if (!d) {
        args_names_clear(&a.outputs);
        return rc;
    }
    int *sel =
        pc_xmalloc((size_t)(d->noutputs + a.outputs.n + 1) * sizeof *sel);
    int nsel = select_outputs(sel, &a, d, err);
    if (nsel < 0)
        rc = 2;
    else {
        /* made in memory and written in one piece, as derive's result */
        char *text = NULL;
        size_t len = 0;
        FILE *m = pc_xopen_memstream(&text, &len);
        Analysis *an = analyze_derived(d, sel, nsel);
        if (a.json)
            analyze_print_json(m, an);
        else
            analyze_print_text(m, an);
        analysis_free(an);
        pc_xclose_memstream(m);
        fwrite(text, 1, len, out);
        free(text);
    }
    free(sel);
    derived_free(d);
    args_names_clear(&a.outputs);
    return rc;
}
